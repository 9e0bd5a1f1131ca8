//! A table of named, typed columns: the one table type of the crate.
//!
//! A sweep's rows ([`crate::sweep::output::Layout::table`]), a sweep's
//! Parquet file read back ([`crate::sweep::output::parquet::read_table`]),
//! a sweep's CSV read back ([`Table::from_csv`]), the input of the sweep
//! plots (`report::sweep_plot`, feature `report`) and the columns the
//! Python package hands to numpy and pyarrow are all a [`Table`]. The
//! module does no I/O: readers take bytes.
//!
//! Cells are typed by column ([`Column`]): `id` and `valence` are unsigned
//! integers, floats and strings may be null (an empty CSV cell), booleans
//! too. A CSV column whose every non-empty cell reads as a number is read as
//! `F64`, any other as `Str`.
//!
//! ```
//! use subdiv_lab::table::{Column, Table};
//! let t = Table::from_csv(b"# comment\nvalence,class\n3,standard\n4,\n").unwrap();
//! assert_eq!(t.len(), 2);
//! assert_eq!(t.numeric("valence").unwrap(), vec![Some(3.0), Some(4.0)]);
//! assert_eq!(t.column("class"), Some(&Column::Str(vec![Some("standard".into()), None])));
//! assert!(t.numeric("class").unwrap_err().to_string().contains("\"class\""));
//! ```

use thiserror::Error as ThisError;

/// One column's values.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// `u64` values, never null (`id`).
    U64(Vec<u64>),
    /// `u32` values, never null (`valence`).
    U32(Vec<u32>),
    /// `f64` values (`None`: null, an empty CSV cell).
    F64(Vec<Option<f64>>),
    /// Strings (`None`: null).
    Str(Vec<Option<String>>),
    /// Booleans (`None`: null).
    Bool(Vec<Option<bool>>),
}

impl Column {
    /// Number of values.
    pub fn len(&self) -> usize {
        match self {
            Column::U64(v) => v.len(),
            Column::U32(v) => v.len(),
            Column::F64(v) => v.len(),
            Column::Str(v) => v.len(),
            Column::Bool(v) => v.len(),
        }
    }

    /// Whether the column has no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Value `row` as a number: integers and floats as they are, a string
    /// (trimmed) if it reads as an `f64` (`Err` with the text if it does
    /// not), a boolean is `Err` with its text; nulls and empty strings are
    /// `Ok(None)`.
    fn number(&self, row: usize) -> Result<Option<f64>, String> {
        match self {
            Column::U64(v) => Ok(Some(v[row] as f64)),
            Column::U32(v) => Ok(Some(f64::from(v[row]))),
            Column::F64(v) => Ok(v[row]),
            Column::Str(v) => match v[row].as_deref().map(str::trim) {
                None | Some("") => Ok(None),
                Some(t) => t.parse::<f64>().map(Some).map_err(|_| t.to_owned()),
            },
            Column::Bool(v) => match v[row] {
                None => Ok(None),
                Some(b) => Err(b.to_string()),
            },
        }
    }

    /// Value `row` as a category label: numbers in shortest round-trip form
    /// (a string that reads as a number too), text as it is, null as `""`.
    fn label(&self, row: usize) -> String {
        match self.number(row) {
            Ok(Some(x)) => format!("{x}"),
            Ok(None) => String::new(),
            Err(text) => text,
        }
    }
}

/// Errors of building or reading a table, or of choosing columns from it;
/// every message names the offending column, row or line.
#[derive(Clone, Debug, PartialEq, ThisError)]
#[non_exhaustive]
pub enum TableError {
    /// No header line (no columns).
    #[error("the file is empty (no header line)")]
    Empty,
    /// A header but no data rows.
    #[error("no data rows under the header")]
    NoRows,
    /// The CSV text is malformed.
    #[error("line {line}: {message}")]
    Csv {
        /// Line in the file (1-based; 0 if unknown).
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// Two columns share a name.
    #[error("column {0:?} appears twice in the header")]
    DuplicateColumn(String),
    /// Columns of different lengths, or not one column per name.
    #[error("column {name:?} has {len} values, expected {expected}")]
    Ragged {
        /// Column name.
        name: String,
        /// Its length.
        len: usize,
        /// The first column's length.
        expected: usize,
    },
    /// A requested column does not exist.
    #[error("no column {name:?} (columns: {available})")]
    MissingColumn {
        /// The requested name.
        name: String,
        /// The names that exist, comma-separated.
        available: String,
    },
    /// A column used as a numeric axis holds text.
    #[error("column {name:?} is not numeric: row {row} has {value:?}")]
    NotNumeric {
        /// Column name.
        name: String,
        /// Data row (1-based, after the header).
        row: usize,
        /// The offending cell.
        value: String,
    },
    /// A numeric column has no finite value to plot.
    #[error("column {0:?} has no finite values")]
    NoFiniteValues(String),
    /// A numeric column with a value too large to plot (the axis arithmetic
    /// would overflow f64).
    #[error("column {name:?} has the value {value:e}, beyond the {max:e} a plot axis can span (its range and ticks would overflow f64); rescale the column")]
    TooLargeToPlot {
        /// Column name.
        name: String,
        /// The offending value.
        value: f64,
        /// The largest accepted magnitude.
        max: f64,
    },
    /// A column has too many distinct values for the plot kind.
    #[error("column {name:?} has {count} distinct values, more than the {max} a {kind} plot accepts; {hint}")]
    TooManyValues {
        /// Column name.
        name: String,
        /// Distinct values.
        count: usize,
        /// The limit.
        max: usize,
        /// Plot kind.
        kind: &'static str,
        /// What to do instead.
        hint: &'static str,
    },
    /// No plot kind fits the columns and none was asked for.
    #[error("cannot choose a plot: {0}; give --kind and the columns (--x, --y, --color)")]
    NoDefault(String),
    /// A Parquet file that cannot be read as a sweep's (not Parquet, torn,
    /// or a column of a type a sweep does not write).
    #[error("{0}")]
    Parquet(String),
    /// The input format is not supported.
    #[error("{0}")]
    Unsupported(String),
}

/// A table of named columns of equal length, with key-value metadata (a
/// Parquet file's).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    names: Vec<String>,
    columns: Vec<Column>,
    metadata: Vec<(String, String)>,
}

impl Table {
    /// A table from named columns: at least one, names unique, one column
    /// per name, all of the same length (zero rows is a table).
    pub fn new(names: Vec<String>, columns: Vec<Column>) -> Result<Self, TableError> {
        if names.is_empty() {
            return Err(TableError::Empty);
        }
        for (i, n) in names.iter().enumerate() {
            if names[..i].contains(n) {
                return Err(TableError::DuplicateColumn(n.clone()));
            }
        }
        let expected = columns.first().map_or(0, Column::len);
        for (n, c) in names.iter().zip(&columns) {
            if c.len() != expected {
                return Err(TableError::Ragged {
                    name: n.clone(),
                    len: c.len(),
                    expected,
                });
            }
        }
        if columns.len() != names.len() {
            return Err(TableError::Ragged {
                name: names[columns.len().min(names.len() - 1)].clone(),
                len: 0,
                expected,
            });
        }
        Ok(Table {
            names,
            columns,
            metadata: Vec::new(),
        })
    }

    /// The table with this key-value metadata.
    pub fn with_metadata(mut self, metadata: Vec<(String, String)>) -> Self {
        self.metadata = metadata;
        self
    }

    /// Reads CSV text with a header line; lines starting with `#` are
    /// skipped, fields are trimmed, an empty field is null. A column whose
    /// every non-empty field reads as an `f64` (`NaN` and `inf` included)
    /// is `F64`, any other `Str`. At least one data row.
    pub fn from_csv(bytes: &[u8]) -> Result<Self, TableError> {
        let mut r = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .has_headers(true)
            .flexible(false)
            .from_reader(bytes);
        let csv_err = |e: csv::Error| TableError::Csv {
            line: e.position().map_or(0, |p| p.line()),
            message: match e.kind() {
                csv::ErrorKind::UnequalLengths {
                    expected_len, len, ..
                } => format!("{len} fields, but the header has {expected_len}"),
                csv::ErrorKind::Utf8 { .. } => "not valid UTF-8".to_owned(),
                _ => e.to_string(),
            },
        };
        let header = r.headers().map_err(csv_err)?.clone();
        if header.is_empty() || (header.len() == 1 && header[0].trim().is_empty()) {
            return Err(TableError::Empty);
        }
        let names: Vec<String> = header.iter().map(|h| h.trim().to_owned()).collect();
        let mut text: Vec<Vec<Option<String>>> = vec![Vec::new(); names.len()];
        for rec in r.records() {
            let rec = rec.map_err(csv_err)?;
            for (col, field) in text.iter_mut().zip(rec.iter()) {
                let f = field.trim();
                col.push((!f.is_empty()).then(|| f.to_owned()));
            }
        }
        if text.first().is_none_or(Vec::is_empty) {
            return Err(TableError::NoRows);
        }
        let columns = text
            .into_iter()
            .map(|col| {
                let numbers: Option<Vec<Option<f64>>> = col
                    .iter()
                    .map(|c| match c {
                        None => Some(None),
                        Some(t) => t.parse::<f64>().ok().map(Some),
                    })
                    .collect();
                match numbers {
                    Some(v) => Column::F64(v),
                    None => Column::Str(col),
                }
            })
            .collect();
        Table::new(names, columns)
    }

    /// Column names in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The columns, in the order of the names.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// The names and columns, taken apart.
    pub fn into_columns(self) -> impl Iterator<Item = (String, Column)> {
        self.names.into_iter().zip(self.columns)
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.columns.first().map_or(0, Column::len)
    }

    /// Whether the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether a column exists.
    pub fn has(&self, name: &str) -> bool {
        self.names.iter().any(|n| n == name)
    }

    /// Position of a column.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The column named `name`.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.index(name).map(|i| &self.columns[i])
    }

    /// The value of key-value metadata `key`.
    pub fn metadata(&self, key: &str) -> Option<&str> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The column named `name`, or an error listing the names that exist.
    fn get(&self, name: &str) -> Result<&Column, TableError> {
        self.column(name).ok_or_else(|| TableError::MissingColumn {
            name: name.to_owned(),
            available: self.names.join(", "),
        })
    }

    /// Column `name` as numbers (`None` for nulls); a cell that is not a
    /// number (text that does not read as one, a boolean) is an error
    /// naming the column and the first such row.
    pub fn numeric(&self, name: &str) -> Result<Vec<Option<f64>>, TableError> {
        let c = self.get(name)?;
        (0..c.len())
            .map(|row| {
                c.number(row).map_err(|value| TableError::NotNumeric {
                    name: name.to_owned(),
                    row: row + 1,
                    value,
                })
            })
            .collect()
    }

    /// Whether every non-null cell of column `name` is a number (and one is
    /// finite).
    pub fn is_numeric(&self, name: &str) -> bool {
        self.numeric(name)
            .is_ok_and(|v| v.iter().any(|x| x.is_some_and(f64::is_finite)))
    }

    /// Number of distinct finite values of a numeric column (0 if not
    /// numeric).
    pub fn distinct_numbers(&self, name: &str) -> usize {
        let Ok(c) = self.numeric(name) else {
            return 0;
        };
        let mut v: Vec<f64> = c.into_iter().flatten().filter(|x| x.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.len()
    }

    /// Column `name` as category labels: numbers in shortest round-trip
    /// form (text that reads as a number too), other text as it is, null as
    /// `""`.
    pub fn labels(&self, name: &str) -> Result<Vec<String>, TableError> {
        let c = self.get(name)?;
        Ok((0..c.len()).map(|row| c.label(row)).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_errors_name_the_problem() {
        assert_eq!(Table::from_csv(b""), Err(TableError::Empty));
        assert_eq!(Table::from_csv(b"# only\n"), Err(TableError::Empty));
        assert_eq!(Table::from_csv(b"a,b\n"), Err(TableError::NoRows));
        let e = Table::from_csv(b"a,b\n1,2\n3\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("1 fields"), "{e}");
        let e = Table::from_csv(b"a,a\n1,2\n").unwrap_err().to_string();
        assert!(e.contains("\"a\" appears twice"), "{e}");
        let t = Table::from_csv(b"a,b\n1,x\n2,3\n").unwrap();
        let e = t.numeric("b").unwrap_err().to_string();
        assert!(
            e.contains("\"b\"") && e.contains("row 1") && e.contains("\"x\""),
            "{e}"
        );
        let e = t.labels("zz").unwrap_err().to_string();
        assert!(e.contains("\"zz\"") && e.contains("a, b"), "{e}");
    }

    /// A CSV column is `F64` when every non-empty field is a number; in a
    /// mixed column the numbers still read as numbers and label in
    /// shortest form.
    #[test]
    fn csv_columns_are_typed() {
        let t = Table::from_csv(b"x,c,m\n1.50,a,2.0\n,b,z\nNaN,,\n").unwrap();
        assert!(matches!(t.column("x"),
            Some(Column::F64(v)) if v[0] == Some(1.5) && v[1].is_none() && v[2].unwrap().is_nan()));
        assert!(matches!(t.column("c"), Some(Column::Str(_))));
        assert_eq!(t.labels("m").unwrap(), vec!["2", "z", ""]);
        assert_eq!(t.labels("x").unwrap(), vec!["1.5", "", "NaN"]);
        assert!(t.is_numeric("x") && !t.is_numeric("m"));
        assert_eq!(t.distinct_numbers("x"), 1);
    }

    #[test]
    fn new_checks_shape() {
        let n = |s: &[&str]| s.iter().map(|x| (*x).to_owned()).collect::<Vec<_>>();
        let e = Table::new(
            n(&["a", "b"]),
            vec![Column::F64(vec![None]), Column::U64(vec![])],
        )
        .unwrap_err();
        assert!(matches!(e, TableError::Ragged { .. }), "{e}");
        let e = Table::new(n(&["a", "b"]), vec![Column::U32(vec![1])]).unwrap_err();
        assert!(matches!(e, TableError::Ragged { .. }), "{e}");
        let t = Table::new(n(&["a"]), vec![Column::U32(vec![7])]).unwrap();
        assert_eq!(t.len(), 1);
        assert_eq!(t.labels("a").unwrap(), vec!["7"]);
        let b = Table::new(n(&["b"]), vec![Column::Bool(vec![Some(true), None])]).unwrap();
        assert_eq!(b.labels("b").unwrap(), vec!["true", ""]);
        assert!(b.numeric("b").is_err());
    }
}
