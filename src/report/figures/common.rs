//! What every figure kind shares: the [`Figure`] and [`FigureOutput`]
//! traits, the [`FigureKind`] entry of the registry, the computing
//! [`Context`] and the [`DataTable`] behind a figure's CSV.

use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};

/// A registered figure kind.
pub struct FigureKind {
    /// Name used as `kind = "..."` in specs.
    pub name: &'static str,
    /// Title used when the spec gives none.
    pub default_title: &'static str,
    /// One-line description.
    pub summary: &'static str,
    /// Parses and validates the kind's keys.
    pub parse: fn(&FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError>,
}

/// Progress sink: the report generator counts work units through it.
pub trait Progress: Sync {
    /// Adds `n` finished work units.
    fn inc(&self, n: u64);
}

/// A progress sink that ignores everything.
pub struct NoProgress;

impl Progress for NoProgress {
    fn inc(&self, _n: u64) {}
}

/// What `compute` gets: the figure's shared keys and a progress sink.
pub struct Context<'a> {
    /// Shared keys (id, title, size, seed).
    pub common: &'a Common,
    /// Progress sink.
    pub progress: &'a dyn Progress,
    /// Input files of the spec's figures (see [`crate::report::inputs::Inputs`]).
    pub inputs: &'a crate::report::inputs::Inputs,
}

impl Context<'_> {
    /// Reports `n` finished work units (of the figure's [`Figure::work`]).
    pub fn tick(&self, n: u64) {
        self.progress.inc(n);
    }

    /// Wraps a library error with the figure id.
    pub fn err(&self, e: impl Into<crate::any_error::AnyError>) -> ReportError {
        ReportError::Analysis {
            figure: self.common.id.clone(),
            source: e.into(),
        }
    }
}

/// A parsed figure, ready to compute.
pub trait Figure: Send + Sync {
    /// Number of progress units `compute` reports (for the progress bar's ETA).
    fn work(&self) -> u64;
    /// Input files the figure reads, as written in the spec (default: none).
    fn inputs(&self) -> Vec<String> {
        Vec::new()
    }
    /// Checks the input files before any figure is computed (default: nothing to check).
    fn check_inputs(&self, _inputs: &crate::report::inputs::Inputs) -> Result<(), ReportError> {
        Ok(())
    }
    /// Runs the analyses behind the figure.
    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError>;
}

/// A computed figure: its data and how to draw it.
pub trait FigureOutput: Send + Sync {
    /// The data behind the figure, one CSV file per table.
    fn tables(&self) -> Vec<DataTable>;
    /// Whether the figure has a picture (SVG + PNG).
    fn has_plot(&self) -> bool {
        true
    }
    /// Draws the figure (title included) on `area`.
    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError>;
    /// An optional HTML fragment for index.html (already escaped).
    fn html(&self) -> Option<String> {
        None
    }
}

/// A table of data behind a figure, written as CSV.
#[derive(Clone, Debug, PartialEq)]
pub struct DataTable {
    /// Name suffix (`None`: the figure's main table `<id>.csv`).
    pub name: Option<String>,
    /// Column names.
    pub header: Vec<String>,
    /// Rows of cells (already formatted; numbers use Rust's shortest round-trip form).
    pub rows: Vec<Vec<String>>,
}

impl DataTable {
    /// An empty table with these columns.
    pub fn new(name: Option<&str>, header: &[&str]) -> Self {
        DataTable {
            name: name.map(str::to_owned),
            header: header.iter().map(|s| (*s).to_owned()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row (must have one cell per column).
    pub fn push(&mut self, row: Vec<String>) {
        debug_assert_eq!(row.len(), self.header.len());
        self.rows.push(row);
    }

    /// The file name of this table for figure `id`.
    pub fn file_name(&self, id: &str) -> String {
        match &self.name {
            None => format!("{id}.csv"),
            Some(n) => format!("{id}-{n}.csv"),
        }
    }

    /// The CSV text.
    pub fn to_csv(&self) -> Result<Vec<u8>, ReportError> {
        let err = |e: csv::Error| ReportError::Render {
            figure: String::new(),
            message: format!("CSV: {e}"),
        };
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&self.header).map_err(err)?;
        for r in &self.rows {
            w.write_record(r).map_err(err)?;
        }
        w.into_inner().map_err(|e| ReportError::Render {
            figure: String::new(),
            message: format!("CSV: {e}"),
        })
    }
}

/// The eigenvalues of an analysis as complex numbers (in the analysis' order:
/// decreasing modulus, dominant first).
pub fn eigenvalues(a: &crate::spectral::LocalAnalysis) -> Vec<num_complex::Complex64> {
    a.eigenvalues
        .iter()
        .map(|z| num_complex::Complex64::new(z[0], z[1]))
        .collect()
}

/// Formats a number for CSV: shortest round-trip form (`NaN` for missing values).
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// Validates an inclusive valence range key (`valence = [lo, hi]`):
/// `3 <= lo <= hi <= max`; `None` gives `default`.
pub(crate) fn valence_range(
    fs: &FigureSpec<'_>,
    value: &Option<toml::Spanned<[usize; 2]>>,
    default: (usize, usize),
    max: usize,
) -> Result<(usize, usize), ReportError> {
    match value {
        None => Ok(default),
        Some(v) => {
            let [a, b] = *v.get_ref();
            if 3 <= a && a <= b && b <= max {
                Ok((a, b))
            } else {
                Err(fs.error_at(
                    v,
                    "valence",
                    format!("valence range must satisfy 3 <= lo <= hi <= {max}, got [{a}, {b}]"),
                ))
            }
        }
    }
}

/// Validates an optional bounded integer key: `lo <= value <= hi`; `None`
/// gives `default`. The error names the key and its line.
pub(crate) fn bounded<T>(
    fs: &FigureSpec<'_>,
    value: &Option<toml::Spanned<T>>,
    key: &str,
    lo: T,
    hi: T,
    default: T,
) -> Result<T, ReportError>
where
    T: Copy + PartialOrd + std::fmt::Display,
{
    match value {
        None => Ok(default),
        Some(x) if lo <= *x.get_ref() && *x.get_ref() <= hi => Ok(*x.get_ref()),
        Some(x) => Err(fs.error_at(
            x,
            key,
            format!("{key} must be between {lo} and {hi}, got {}", x.get_ref()),
        )),
    }
}
