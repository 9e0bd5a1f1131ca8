//! The contents of a report's `manifest.json`.

use serde::Serialize;

/// Per-figure manifest entry.
#[derive(Clone, Debug, Serialize)]
pub struct FigureRecord {
    /// Figure id.
    pub id: String,
    /// Figure kind.
    pub kind: &'static str,
    /// Title.
    pub title: String,
    /// Caption.
    pub caption: Option<String>,
    /// Seed of the figure's random draws.
    pub seed: u64,
    /// Pixel size.
    pub size: (u32, u32),
    /// SVG file, if the figure has a picture.
    pub svg: Option<String>,
    /// PNG file, if the figure has a picture.
    pub png: Option<String>,
    /// CSV files. A table whose bytes equal an earlier figure's CSV is not
    /// written again: its entry names the earlier file.
    pub csv: Vec<String>,
    /// Wall-clock seconds of the analyses.
    pub compute_seconds: f64,
    /// Wall-clock seconds of SVG + PNG rendering.
    pub render_seconds: f64,
}

/// The contents of `manifest.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Manifest {
    /// Tool name.
    pub tool: &'static str,
    /// Tool version.
    pub version: String,
    /// Git revision, if known.
    pub git_revision: Option<String>,
    /// Spec path as given.
    pub spec_path: Option<String>,
    /// The spec is the one built into the binary (see [`RunInfo::spec_builtin`](crate::report::RunInfo::spec_builtin)).
    pub spec_builtin: bool,
    /// Every file of the report (plain names, `index.html` and
    /// `manifest.json` included): what a later run replacing this report
    /// may remove, and nothing else.
    pub files: Vec<String>,
    /// The FNV-1a 64 digest ([`file_digest`](crate::report::file_digest), 16 hex digits) of
    /// every file but `manifest.json`: a later run replaces or removes a
    /// listed file only if it still has these bytes, so a file the user
    /// edited, or put under a listed name, or added to an edited list, is
    /// never lost.
    pub digests: std::collections::BTreeMap<String, String>,
    /// Report name.
    pub name: String,
    /// Base seed.
    pub seed: u64,
    /// The spec text.
    pub spec: String,
    /// Figures in order.
    pub figures: Vec<FigureRecord>,
    /// Wall-clock seconds of the whole generation.
    pub total_seconds: f64,
}
