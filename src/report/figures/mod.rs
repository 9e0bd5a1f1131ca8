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
//!    draws it on an [`Area`](crate::report::Area) (the same code renders SVG and PNG; use the
//!    helpers of `super::plot` for fonts, colours, markers and colour bars,
//!    and draw only what `tables` contains, so the CSV is exactly the data
//!    plotted), and optionally `html` adds an HTML fragment to index.html (e.g.
//!    a table). A kind without a picture returns `false` from `has_plot`.
//!
//! Nothing else changes: the spec parser, index.html, manifest and CLI pick
//! the new kind up from [`REGISTRY`]. Add a spec using it to a test in
//! `tests/report*.rs`.

pub mod cc_c1_interval;
pub mod cc_eigenvalues;
pub mod ccss_bound;
pub mod certified_map;
pub mod charmap_ring;
pub mod config_table;
pub mod convergence;
pub mod crease_picture;
pub mod curvature;
pub mod curvature_tuning;
pub mod g2_cap_curvature;
pub mod g2_cap_rays;
pub mod knot_map;
pub mod mesh_convergence;
pub mod mesh_picture;
pub mod sector_spectra;
pub mod spectrum;
pub mod sweep;
pub mod valence;

mod common;
mod panels;

pub(crate) use common::{bounded, valence_range};
pub use common::{
    eigenvalues, num, Context, DataTable, Figure, FigureKind, FigureOutput, NoProgress, Progress,
};

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
    sector_spectra::KIND,
    crease_picture::KIND,
];

/// The kind named `name`.
pub fn find_kind(name: &str) -> Option<&'static FigureKind> {
    REGISTRY.iter().find(|k| k.name == name)
}
