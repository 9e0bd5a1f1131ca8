//! The figure registry: every figure kind a spec can name.
//!
//! # Adding a figure kind
//!
//! A figure kind is **one new module** in this directory plus **one line** in
//! [`REGISTRY`]. The module defines:
//!
//! 1. a parameter struct with `#[derive(Deserialize)]` and
//!    `#[serde(deny_unknown_fields)]` for the kind's own keys (the shared keys
//!    `kind`, `id`, `title`, `caption`, `width`, `height`, `seed` are handled by
//!    the spec parser and never reach it);
//! 2. a `pub(crate) const KIND: FigureKind` naming the kind, its default title,
//!    a one-line summary and its `parse` function. `parse` receives a
//!    `FigureSpec`: call `FigureSpec::parse` to deserialize the keys (errors
//!    then carry line and key), validate every value there (use
//!    `FigureSpec::error_at` with a `toml::Spanned` field so the message names
//!    the line; configurations go through `super::config::ConfigSpec`), and
//!    return a boxed [`Figure`]. A spec that parses must not fail later on bad
//!    input;
//! 3. the [`Figure`] impl: `compute` does the numerics (through the library's
//!    analysis modules, never its own copy of them; use rayon for independent
//!    items and report progress through [`Context::tick`]) and returns a boxed
//!    [`FigureOutput`];
//! 4. the [`FigureOutput`] impl: `tables` returns the data behind the figure
//!    (written as `<id>.csv`, or `<id>-<name>.csv` for named tables), `draw`
//!    draws it on an [`Area`] (the same code renders SVG and PNG; use the
//!    helpers of `super::plot` for fonts, colours, markers and colour bars,
//!    and draw only what `tables` contains, so the CSV is exactly the data
//!    plotted), and optionally `html` adds an HTML fragment to index.html (e.g.
//!    a table). A kind without a picture returns `false` from `has_plot`.
//!
//! Nothing else changes: the spec parser, index.html, manifest and CLI pick
//! the new kind up from [`REGISTRY`]. Add a spec using it to a test in
//! `tests/report*.rs`.

use super::backend::Area;
use super::error::ReportError;
use super::figure_spec::{Common, FigureSpec};

pub mod cc_c1_interval;
pub mod cc_eigenvalues;
pub mod ccss_bound;
pub mod certified_map;
pub mod charmap_ring;
pub mod config_table;
pub mod convergence;
pub mod curvature;
pub mod curvature_tuning;
pub mod g2_cap_curvature;
pub mod g2_cap_rays;
pub mod knot_map;
pub mod mesh_convergence;
pub mod mesh_picture;
pub mod spectrum;
pub mod sweep;
pub mod valence;

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

/// Every figure kind, in documentation order. Add new kinds here.
pub const REGISTRY: &[FigureKind] = &[
    spectrum::KIND,
    valence::KIND,
    convergence::KIND,
    knot_map::KIND,
    config_table::KIND,
    charmap_ring::KIND,
    mesh_convergence::KIND,
    mesh_picture::KIND,
    ccss_bound::KIND,
    cc_eigenvalues::KIND,
    cc_c1_interval::KIND,
    curvature::KIND,
    curvature_tuning::KIND,
    g2_cap_curvature::KIND,
    g2_cap_rays::KIND,
    sweep::KIND,
    certified_map::KIND,
];

/// The kind named `name`.
pub fn find_kind(name: &str) -> Option<&'static FigureKind> {
    REGISTRY.iter().find(|k| k.name == name)
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
    /// Input files of the spec's figures (see [`crate::report::Inputs`]).
    pub inputs: &'a crate::report::Inputs,
}

impl Context<'_> {
    /// Reports `n` finished work units (of the figure's [`Figure::work`]).
    pub fn tick(&self, n: u64) {
        self.progress.inc(n);
    }

    /// Wraps a library error with the figure id.
    pub fn err(&self, e: crate::Error) -> ReportError {
        ReportError::Analysis {
            figure: self.common.id.clone(),
            source: e,
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
    fn check_inputs(&self, _inputs: &crate::report::Inputs) -> Result<(), ReportError> {
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
