//! The columns of a sweep's CSV ([`Layout`]) and one row ([`Row`]): header,
//! formatting and parsing of a whole row, the evaluation of one configuration
//! into a row. A leaf of the sweep modules' graph: the summary builds on it.

use super::csv::split_csv_line;
use crate::sweep::eval::{result_columns, Cell, ColumnType};
use crate::sweep::plan::Plan;
use crate::sweep::SweepError;
use crate::table::{Column, Table, TableError};
use std::io::Write;

/// One CSV row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Configuration id.
    pub id: u64,
    /// Valence.
    pub valence: usize,
    /// Coordinate cells then result cells, in column order.
    pub cells: Vec<Cell>,
    /// The evaluation error, if the configuration failed.
    pub error: Option<String>,
}

/// The columns of a sweep's CSV.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    pub(super) names: Vec<String>,
    pub(super) coordinates: usize,
    /// Derived cells among the coordinate cells (the last ones).
    pub(super) derived: usize,
    pub(super) class: Option<usize>,
    pub(super) numeric: Vec<(usize, String)>,
    /// The type of each cell's column (coordinates: `Float`). A cell is
    /// numeric exactly when its column is [`ColumnType::Float`] (the sweep
    /// driver relies on it: [`RowBlock::float`](super::run::RowBlock::float)).
    pub(super) types: Vec<ColumnType>,
    /// The schema documentation of every column, `id` to `error`.
    pub(super) docs: Vec<ColumnDoc>,
}

/// The documentation of one column of a sweep's output (CSV and Parquet):
/// written into the summary JSON and listed in the README.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct ColumnDoc {
    /// Column name.
    pub name: String,
    /// Type: `u64`, `u32`, `f64`, `string`, `bool`.
    #[serde(rename = "type")]
    pub ty: String,
    /// What the value is.
    pub meaning: String,
    /// Unit (`1`: a pure number; `-`: not a quantity).
    pub unit: String,
}

impl Layout {
    /// The layout of `plan`'s CSV.
    pub fn new(plan: &Plan) -> Layout {
        let mut names = Vec::new();
        let mut types = Vec::new();
        let doc = |name: &str, ty: &str, meaning: &str, unit: &str| ColumnDoc {
            name: name.to_owned(),
            ty: ty.to_owned(),
            meaning: meaning.to_owned(),
            unit: unit.to_owned(),
        };
        let mut docs = vec![
            doc("id", "u64", "configuration id: its position in the enumeration of the spec (the parameters are re-derived from it)", "-"),
            match plan.spec().sector {
                Some(_) => doc("valence", "u32", "face count K of the sector (a [sector] sweep; a crease has two sectors of K faces)", "-"),
                None => doc("valence", "u32", "valence n of the extraordinary face or vertex", "-"),
            },
        ];
        let kind = plan.spec().space.kind;
        for c in plan.coordinate_columns() {
            let fam = c.trim_end_matches(|ch: char| ch.is_ascii_digit());
            let meaning = match fam {
                "r" => "edge ratio r_i of the knot intervals around the extraordinary face (math doc section 2); empty beyond the row's valence",
                "p" | "q" => "corner knot interval p_i / q_i (log-uniform); empty beyond the row's valence",
                "forward" | "backward" => "directed edge knot interval around the face (log-uniform); empty beyond the row's valence",
                "a" => "knot interval a_k around the extraordinary vertex (log-uniform); empty beyond the row's valence",
                "c" => "shape parameter c of the adjustable Catmull-Clark scheme",
                "angle" => "angle of the corner sector in degrees",
                _ => "coordinate of the parameter space",
            };
            let unit = if kind.is_log() {
                "knot interval"
            } else if kind == crate::sweep::SpaceKind::CornerAngle {
                "deg"
            } else {
                "1"
            };
            docs.push(doc(&c, "f64", meaning, unit));
            names.push(c);
            types.push(ColumnType::Float);
        }
        let derived = plan.derived_columns().len();
        for c in plan.derived_columns() {
            docs.push(doc(
                &c,
                "f64",
                "edge ratio r_i = q_(i+1) / (p_i + q_(i+1)) derived from the corner intervals, the r_i of the scheme's matrix (math doc section 2); empty beyond the row's valence",
                "1",
            ));
            names.push(c);
            types.push(ColumnType::Float);
        }
        let coordinates = names.len();
        for c in result_columns(&plan.spec().columns) {
            docs.push(doc(&c.name, c.ty.name(), &c.meaning, c.unit));
            names.push(c.name.to_owned());
            types.push(c.ty);
        }
        docs.push(doc(
            "error",
            "string",
            "why the configuration could not be evaluated (empty on success; a failed row has every result cell empty)",
            "-",
        ));
        let class = names.iter().position(|n| n == "class");
        let numeric = names
            .iter()
            .zip(&types)
            .enumerate()
            .filter(|(_, (_, t))| **t == ColumnType::Float)
            .map(|(i, (n, _))| (i, n.clone()))
            .collect();
        Layout {
            names,
            coordinates,
            derived,
            class,
            numeric,
            types,
            docs,
        }
    }

    /// The schema documentation of every column, `id` to `error` (name, type,
    /// meaning, unit).
    pub fn column_docs(&self) -> &[ColumnDoc] {
        &self.docs
    }

    /// The column names, `id` to `error`.
    pub fn column_names(&self) -> Vec<String> {
        self.docs.iter().map(|d| d.name.clone()).collect()
    }

    /// Number of cells (coordinates + results) of a row.
    pub fn cells(&self) -> usize {
        self.names.len()
    }

    /// Number of coordinate cells.
    pub fn coordinate_cells(&self) -> usize {
        self.coordinates
    }

    /// The header line (with `\n`).
    pub fn header(&self) -> String {
        let mut s = String::from("id,valence");
        for n in &self.names {
            s.push(',');
            s.push_str(n);
        }
        s.push_str(",error\n");
        s
    }

    /// Writes the header.
    pub fn write_header<W: Write>(&self, out: &mut W) -> Result<(), SweepError> {
        out.write_all(self.header().as_bytes())?;
        Ok(())
    }

    /// The rows as a [`Table`] with the CSV's columns, `id` (`U64`) and
    /// `valence` (`U32`), then a `F64` column per numeric cell and a `Str`
    /// column per text cell (an empty cell is null), then `error` (`Str`,
    /// null when the row succeeded): the table [`Table::from_csv`] reads
    /// from the CSV of the same rows, up to the empty columns it cannot
    /// type.
    pub fn table(&self, rows: Vec<Row>) -> Result<Table, TableError> {
        let n = rows.len();
        let mut ids = Vec::with_capacity(n);
        let mut valences = Vec::with_capacity(n);
        let mut errors = Vec::with_capacity(n);
        let mut cells: Vec<Column> = self
            .types
            .iter()
            .map(|&t| match t {
                ColumnType::Float => Column::F64(Vec::with_capacity(n)),
                _ => Column::Str(Vec::with_capacity(n)),
            })
            .collect();
        for r in rows {
            ids.push(r.id);
            valences.push(u32::try_from(r.valence).unwrap_or(u32::MAX));
            for (j, col) in cells.iter_mut().enumerate() {
                let cell = r.cells.get(j).unwrap_or(&Cell::Empty);
                match (col, cell) {
                    (Column::F64(v), Cell::Num(x)) => v.push(Some(*x)),
                    (Column::F64(v), _) => v.push(None),
                    (Column::Str(v), Cell::Text(t)) => v.push(Some(t.clone())),
                    (Column::Str(v), Cell::Num(x)) => v.push(Some(x.to_string())),
                    (Column::Str(v), Cell::Empty) => v.push(None),
                    _ => {}
                }
            }
            errors.push(r.error);
        }
        let mut columns = vec![Column::U64(ids), Column::U32(valences)];
        columns.extend(cells);
        columns.push(Column::Str(errors));
        Table::new(self.column_names(), columns)
    }

    /// Numeric cells: (cell index, column name).
    pub fn numeric_columns(&self) -> &[(usize, String)] {
        &self.numeric
    }

    /// The number in cell `pos` of `row`, if any.
    pub fn number_at(&self, row: &Row, pos: usize) -> Option<f64> {
        match row.cells.get(pos) {
            Some(Cell::Num(x)) => Some(*x),
            _ => None,
        }
    }

    /// The `class` cell of `row`, if the sweep computes it and the row has one.
    pub fn class_of<'a>(&self, row: &'a Row) -> Option<&'a str> {
        match row.cells.get(self.class?) {
            Some(Cell::Text(t)) => Some(t),
            _ => None,
        }
    }

    /// Parses one line (without `\n`) back into a row.
    pub fn parse(&self, line: &str) -> Result<Row, String> {
        let fields = split_csv_line(line)?;
        if fields.len() != self.names.len() + 3 {
            return Err(format!(
                "expected {} fields, found {}",
                self.names.len() + 3,
                fields.len()
            ));
        }
        let id: u64 = fields[0]
            .parse()
            .map_err(|_| format!("id {:?} is not an integer", fields[0]))?;
        let valence: usize = fields[1]
            .parse()
            .map_err(|_| format!("valence {:?} is not an integer", fields[1]))?;
        let mut cells = Vec::with_capacity(self.names.len());
        for ((f, k), name) in fields[2..2 + self.names.len()]
            .iter()
            .zip(&self.types)
            .zip(&self.names)
        {
            cells.push(if f.is_empty() {
                Cell::Empty
            } else {
                match k {
                    ColumnType::Float => Cell::Num(
                        f.parse()
                            .map_err(|_| format!("{name} = {f:?} is not a number"))?,
                    ),
                    _ => Cell::Text(f.clone()),
                }
            });
        }
        let e = &fields[fields.len() - 1];
        Ok(Row {
            id,
            valence,
            cells,
            error: (!e.is_empty()).then(|| e.clone()),
        })
    }

    /// The coordinate cells of configuration `c` (by column, `None`: empty)
    /// into `out`: the coordinates of the space, then the derived columns
    /// ([`Plan::derived_columns`]). The one placement of coordinates, for the
    /// driver and the verifier.
    pub(super) fn coordinates_into(
        &self,
        plan: &Plan,
        c: &crate::sweep::Configuration,
        out: &mut Vec<Option<f64>>,
    ) {
        out.clear();
        out.resize(self.coordinates, None);
        for (k, x) in c.coordinates.iter().enumerate() {
            out[plan.coordinate_column(c.valence, k)] = Some(*x);
        }
        let sampled = self.coordinates - self.derived;
        plan.derived_into(c, &mut out[sampled..]);
    }
}
