//! A table of named columns: the input of sweep plots ([`super::sweep_plot`]).
//!
//! The plots only see this type, never a file format: [`Table::from_csv`]
//! reads the CSV that `subdiv-lab sweep` writes (`#` comment lines, such as
//! the fingerprint line older versions wrote first, are skipped), and any other reader (e.g. Parquet) plugs in by building a
//! [`Table`] with [`Table::new`] from its columns. Cells are numbers, text or
//! missing (an empty CSV field).
//!
//! ```
//! use subdiv_lab::report::table::{Table, Value};
//! let t = Table::from_csv(b"# comment\nvalence,class\n3,standard\n4,\n").unwrap();
//! assert_eq!(t.len(), 2);
//! assert_eq!(t.numeric("valence").unwrap(), vec![Some(3.0), Some(4.0)]);
//! assert_eq!(t.column("class").unwrap()[1], Value::Missing);
//! assert!(t.numeric("class").unwrap_err().to_string().contains("\"class\""));
//! ```

use thiserror::Error as ThisError;

/// One cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// An empty field.
    Missing,
    /// A number (any text that parses as `f64`, including `NaN` and `inf`).
    Number(f64),
    /// Anything else.
    Text(String),
}

impl Value {
    /// The cell as a category label: text as is, numbers in shortest
    /// round-trip form, missing as `""`.
    pub fn label(&self) -> String {
        match self {
            Value::Missing => String::new(),
            Value::Number(x) => format!("{x}"),
            Value::Text(s) => s.clone(),
        }
    }
}

/// Errors of reading a table or choosing columns from it; every message
/// names the offending column, row or line.
#[derive(Clone, Debug, PartialEq, ThisError)]
#[non_exhaustive]
pub enum TableError {
    /// No header line.
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
    /// Columns of different lengths were given to [`Table::new`].
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
    /// The input format is not supported (yet).
    #[error("{0}")]
    Unsupported(String),
}

/// A table of named columns of equal length.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    names: Vec<String>,
    columns: Vec<Vec<Value>>,
}

impl Table {
    /// A table from named columns (all of the same length, names unique, at
    /// least one row).
    pub fn new(names: Vec<String>, columns: Vec<Vec<Value>>) -> Result<Self, TableError> {
        if names.is_empty() {
            return Err(TableError::Empty);
        }
        for (i, n) in names.iter().enumerate() {
            if names[..i].contains(n) {
                return Err(TableError::DuplicateColumn(n.clone()));
            }
        }
        let expected = columns.first().map_or(0, Vec::len);
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
        if expected == 0 {
            return Err(TableError::NoRows);
        }
        Ok(Table { names, columns })
    }

    /// Reads CSV text with a header line; lines starting with `#` are skipped.
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
        let mut columns: Vec<Vec<Value>> = vec![Vec::new(); names.len()];
        for rec in r.records() {
            let rec = rec.map_err(csv_err)?;
            for (col, field) in columns.iter_mut().zip(rec.iter()) {
                let f = field.trim();
                col.push(if f.is_empty() {
                    Value::Missing
                } else if let Ok(x) = f.parse::<f64>() {
                    Value::Number(x)
                } else {
                    Value::Text(f.to_owned())
                });
            }
        }
        Table::new(names, columns)
    }

    /// Reads a sweep's Parquet file from its bytes (the library does no I/O:
    /// the caller reads the file) with
    /// [`read_table`](crate::sweep::output::parquet::read_table). The cells are
    /// those [`from_csv`](Self::from_csv) reads from the CSV of the same rows:
    /// `id`, `valence` and floats are numbers (a null is missing), booleans are
    /// the text `true` / `false`, and a string is read as a CSV field is (a
    /// number if it parses as one, missing if empty), so a figure drawn from
    /// the Parquet file equals the one drawn from the CSV.
    ///
    /// ```
    /// use subdiv_lab::report::table::Table;
    /// let e = Table::from_parquet(b"PAR1".to_vec()).unwrap_err().to_string();
    /// assert!(e.contains("not a Parquet file, or torn"), "{e}");
    /// ```
    pub fn from_parquet(bytes: Vec<u8>) -> Result<Self, TableError> {
        use crate::sweep::output::parquet::{read_table, Column};
        // The reader's problems are reported as they are (not as a write).
        let t = read_table(bytes).map_err(|e| match e {
            crate::sweep::SweepError::Io(m) | crate::sweep::SweepError::Read(m) => {
                TableError::Parquet(m)
            }
            other => TableError::Parquet(other.to_string()),
        })?;
        if t.names.is_empty() {
            return Err(TableError::Empty);
        }
        let text = |s: &Option<String>| match s.as_deref().map(str::trim) {
            None | Some("") => Value::Missing,
            Some(f) => match f.parse::<f64>() {
                Ok(x) => Value::Number(x),
                Err(_) => Value::Text(f.to_owned()),
            },
        };
        let columns = t
            .columns
            .iter()
            .map(|c| match c {
                Column::U64(v) => v.iter().map(|&x| Value::Number(x as f64)).collect(),
                Column::U32(v) => v.iter().map(|&x| Value::Number(f64::from(x))).collect(),
                Column::F64(v) => v
                    .iter()
                    .map(|x| x.map_or(Value::Missing, Value::Number))
                    .collect(),
                Column::Str(v) => v.iter().map(text).collect(),
                Column::Bool(v) => v
                    .iter()
                    .map(|b| match b {
                        None => Value::Missing,
                        Some(b) => Value::Text(b.to_string()),
                    })
                    .collect(),
            })
            .collect();
        Table::new(t.names.clone(), columns)
    }

    /// Reads `bytes` as Parquet when `name` ends in `.parquet` or the bytes
    /// begin and end with the Parquet magic `PAR1` (a Parquet file under
    /// another name, e.g. a `.parquet` file renamed `x.csv`), as CSV
    /// otherwise ([`from_parquet`](Self::from_parquet),
    /// [`from_csv`](Self::from_csv)).
    pub fn from_named_bytes(name: &str, bytes: &[u8]) -> Result<Self, TableError> {
        if Self::is_parquet(name, bytes) {
            Table::from_parquet(bytes.to_vec())
        } else {
            Table::from_csv(bytes)
        }
    }

    /// An upper bound of the rows and the number of columns of the table
    /// [`from_named_bytes`](Self::from_named_bytes) would read from `bytes`,
    /// without reading it (a work estimate): for CSV the line count and the
    /// fields of the first line that is not a `#` comment; for Parquet the
    /// footer's counts.
    pub fn shape(name: &str, bytes: &[u8]) -> Result<(usize, usize), TableError> {
        if Self::is_parquet(name, bytes) {
            let (rows, columns) =
                crate::sweep::output::parquet::shape(bytes).map_err(|e| match e {
                    crate::sweep::SweepError::Read(m) => TableError::Parquet(m),
                    other => TableError::Parquet(other.to_string()),
                })?;
            return Ok((usize::try_from(rows).unwrap_or(usize::MAX), columns));
        }
        let lines = memchr::memchr_iter(b'\n', bytes).count() + 1;
        let header = bytes
            .split(|&b| b == b'\n')
            .find(|l| !l.starts_with(b"#"))
            .unwrap_or_default();
        let columns = memchr::memchr_iter(b',', header).count() + 1;
        Ok((lines, columns))
    }

    /// Whether [`from_named_bytes`](Self::from_named_bytes) reads `bytes` as
    /// Parquet.
    fn is_parquet(name: &str, bytes: &[u8]) -> bool {
        let magic = b"PAR1";
        let parquet_bytes =
            bytes.len() >= 2 * magic.len() && bytes.starts_with(magic) && bytes.ends_with(magic);
        name.ends_with(".parquet") || parquet_bytes
    }

    /// Column names in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.columns.first().map_or(0, Vec::len)
    }

    /// Whether the table has no rows (never true for a constructed table).
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

    /// The cells of column `name`.
    pub fn column(&self, name: &str) -> Result<&[Value], TableError> {
        self.index(name)
            .map(|i| self.columns[i].as_slice())
            .ok_or_else(|| TableError::MissingColumn {
                name: name.to_owned(),
                available: self.names.join(", "),
            })
    }

    /// Column `name` as numbers (`None` for missing cells); text is an error
    /// naming the column and the first such row.
    pub fn numeric(&self, name: &str) -> Result<Vec<Option<f64>>, TableError> {
        self.column(name)?
            .iter()
            .enumerate()
            .map(|(row, v)| match v {
                Value::Missing => Ok(None),
                Value::Number(x) => Ok(Some(*x)),
                Value::Text(t) => Err(TableError::NotNumeric {
                    name: name.to_owned(),
                    row: row + 1,
                    value: t.clone(),
                }),
            })
            .collect()
    }

    /// Whether every non-missing cell of column `name` is a number (and one is finite).
    pub fn is_numeric(&self, name: &str) -> bool {
        self.column(name).is_ok_and(|c| {
            c.iter()
                .all(|v| matches!(v, Value::Missing | Value::Number(_)))
                && c.iter()
                    .any(|v| matches!(v, Value::Number(x) if x.is_finite()))
        })
    }

    /// Number of distinct finite values of a numeric column (0 if not numeric).
    pub fn distinct_numbers(&self, name: &str) -> usize {
        let Ok(c) = self.numeric(name) else {
            return 0;
        };
        let mut v: Vec<f64> = c.into_iter().flatten().filter(|x| x.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.len()
    }

    /// Column `name` as category labels (see [`Value::label`]).
    pub fn labels(&self, name: &str) -> Result<Vec<String>, TableError> {
        Ok(self.column(name)?.iter().map(Value::label).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shape is read without parsing: a bound of the rows (the lines)
    /// and the header's fields; a Parquet file's from its footer.
    #[test]
    fn shape_bounds_rows_before_parsing() {
        let csv = b"# fingerprint\nid,valence,class\n0,3,a\n1,3,b\n";
        let (rows, cols) = Table::shape("s.csv", csv).unwrap();
        assert_eq!(cols, 3);
        assert!(rows >= Table::from_csv(csv).unwrap().len());
        assert!(Table::shape("s.parquet", b"PAR1").is_err());
    }

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
        let e = t.column("zz").unwrap_err().to_string();
        assert!(e.contains("\"zz\"") && e.contains("a, b"), "{e}");
    }

    #[test]
    fn new_checks_shape() {
        let n = |s: &[&str]| s.iter().map(|x| (*x).to_owned()).collect::<Vec<_>>();
        let e = Table::new(n(&["a", "b"]), vec![vec![Value::Missing], vec![]]).unwrap_err();
        assert!(matches!(e, TableError::Ragged { .. }), "{e}");
        let t = Table::new(n(&["a"]), vec![vec![Value::Number(1.0)]]).unwrap();
        assert_eq!(t.len(), 1);
        assert_eq!(t.distinct_numbers("a"), 1);
    }
}
