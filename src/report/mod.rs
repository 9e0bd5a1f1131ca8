//! Plotted reports: a TOML spec in, a directory of figures out.
//!
//! A report spec (format in [`spec`]) lists figures by kind; [`generate`]
//! computes every figure, renders it to SVG and PNG, writes the data behind it
//! as CSV, and assembles a self-contained `index.html` and a `manifest.json`
//! (tool version, git revision, the spec text, seeds and timings). Everything
//! is produced **in memory** as a list of [`OutputFile`]s: the library does no
//! file-system I/O, the CLI (`subdiv-lab report`) writes the files atomically.
//!
//! * [`spec`]: the spec format and parser (errors name line and key);
//! * [`config`]: scheme configurations as written in specs;
//! * [`figures`]: the figure registry and the figure kinds — **to add a figure
//!   kind, read the module docs of [`figures`]**: one new module plus one line
//!   in [`figures::REGISTRY`];
//! * [`plot`]: plotting helpers (bundled font, sizes, colours, markers);
//! * [`backend`]: one drawing backend for SVG and PNG, in-memory rendering;
//! * [`html`]: the `index.html` page;
//! * [`rng`]: the deterministic random generator behind random knots.
//!
//! ```
//! use subdiv_lab::report::{generate, ReportSpec, RunInfo, figures::NoProgress};
//! let spec = ReportSpec::parse(r#"
//! name = "demo"
//! [[figure]]
//! kind = "convergence"
//! id = "conv"
//! width = 800
//! height = 500
//! steps = 10
//! configs = [{ scheme = "nurds", ratios = [0.3, 0.6, 0.5] }]
//! "#).unwrap();
//! let report = generate(&spec, &RunInfo::default(), &NoProgress).unwrap();
//! let names: Vec<&str> = report.files.iter().map(|f| f.path.as_str()).collect();
//! assert!(names.contains(&"conv.png") && names.contains(&"conv.svg") && names.contains(&"conv.csv"));
//! assert!(names.contains(&"index.html") && names.contains(&"manifest.json"));
//! ```

pub(crate) mod backend;
pub mod config;
pub mod error;
pub mod figure_spec;
pub mod figures;
pub(crate) mod font;
pub(crate) mod html;
pub(crate) mod plot;
pub mod spec;

pub use error::{Location, ReportError};
pub use spec::{Common, ReportSpec};

use figures::{Context, Progress};
use serde::Serialize;
use std::time::Instant;

/// Facts about the run that the library cannot know (passed in by the CLI).
#[derive(Clone, Debug, Default, Serialize)]
pub struct RunInfo {
    /// Tool version (default: this crate's version).
    pub version: Option<String>,
    /// Git revision of the source tree, if known.
    pub git_revision: Option<String>,
    /// Path of the spec file as given.
    pub spec_path: Option<String>,
    /// The spec is the one built into the binary (`analysis/default.toml` at
    /// build time), not a file read at run time.
    pub spec_builtin: bool,
}

/// One generated file: path relative to the report directory, and contents.
#[derive(Clone, Debug)]
pub struct OutputFile {
    /// Relative path (a plain file name).
    pub path: String,
    /// Contents.
    pub bytes: Vec<u8>,
}

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
    /// CSV files.
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
    /// The spec is the one built into the binary (see [`RunInfo::spec_builtin`]).
    pub spec_builtin: bool,
    /// Every file of the report (plain names, `index.html` and
    /// `manifest.json` included): what a later run replacing this report
    /// may remove, and nothing else.
    pub files: Vec<String>,
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

/// A generated report, in memory.
#[derive(Clone, Debug)]
pub struct RenderedReport {
    /// All files, `index.html` and `manifest.json` included.
    pub files: Vec<OutputFile>,
    /// The manifest (also in `files` as JSON).
    pub manifest: Manifest,
}

/// Progress units charged for rendering one figure (SVG + PNG).
pub const RENDER_WORK: u64 = 20;

/// Total progress units of a spec (for a progress bar's length).
pub fn total_work(spec: &ReportSpec) -> u64 {
    spec.figures
        .iter()
        .map(|f| f.figure.work() + RENDER_WORK)
        .sum()
}

/// Computes and renders every figure of `spec`.
pub fn generate(
    spec: &ReportSpec,
    run: &RunInfo,
    progress: &dyn Progress,
) -> Result<RenderedReport, ReportError> {
    let start = Instant::now();
    let mut files = Vec::new();
    let mut records = Vec::new();
    let mut fragments = Vec::new();
    for entry in &spec.figures {
        let common = &entry.common;
        let t0 = Instant::now();
        let ctx = Context { common, progress };
        let out = entry.figure.compute(&ctx)?;
        let compute_seconds = t0.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let mut record = FigureRecord {
            id: common.id.clone(),
            kind: common.kind,
            title: common.title.clone(),
            caption: common.caption.clone(),
            seed: common.seed,
            size: common.size,
            svg: None,
            png: None,
            csv: Vec::new(),
            compute_seconds,
            render_seconds: 0.0,
        };
        for table in out.tables() {
            let name = table.file_name(&common.id);
            let bytes = table.to_csv().map_err(|e| e.in_figure(&common.id))?;
            record.csv.push(name.clone());
            files.push(OutputFile { path: name, bytes });
        }
        if out.has_plot() {
            let draw = |area: &backend::Area<'_>| out.draw(area, common);
            let (svg, png) = rayon::join(
                || backend::render_svg(common.size, &draw),
                || backend::render_png(common.size, &draw),
            );
            let svg = svg.map_err(|e| e.in_figure(&common.id))?;
            let png = png.map_err(|e| e.in_figure(&common.id))?;
            let svg_name = format!("{}.svg", common.id);
            let png_name = format!("{}.png", common.id);
            files.push(OutputFile {
                path: svg_name.clone(),
                bytes: svg.into_bytes(),
            });
            files.push(OutputFile {
                path: png_name.clone(),
                bytes: png,
            });
            record.svg = Some(svg_name);
            record.png = Some(png_name);
        }
        progress.inc(RENDER_WORK);
        record.render_seconds = t1.elapsed().as_secs_f64();
        fragments.push(out.html());
        records.push(record);
    }
    let manifest = Manifest {
        tool: "subdiv-lab",
        version: run
            .version
            .clone()
            .unwrap_or_else(|| env!("CARGO_PKG_VERSION").to_owned()),
        git_revision: run.git_revision.clone(),
        spec_path: run.spec_path.clone(),
        spec_builtin: run.spec_builtin,
        files: files
            .iter()
            .map(|f| f.path.clone())
            .chain(["index.html".to_owned(), "manifest.json".to_owned()])
            .collect(),
        name: spec.name.clone(),
        seed: spec.seed,
        spec: spec.source.clone(),
        figures: records,
        total_seconds: start.elapsed().as_secs_f64(),
    };
    files.push(OutputFile {
        path: "index.html".into(),
        bytes: html::index(spec, &manifest, &fragments).into_bytes(),
    });
    let json = serde_json::to_vec_pretty(&manifest).map_err(|e| ReportError::Render {
        figure: String::new(),
        message: format!("manifest: {e}"),
    })?;
    files.push(OutputFile {
        path: "manifest.json".into(),
        bytes: json,
    });
    Ok(RenderedReport { files, manifest })
}
