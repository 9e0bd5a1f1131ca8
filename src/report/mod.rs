//! Plotted reports: a TOML spec in, a directory of figures out.
//!
//! A report spec (format in `spec`) lists figures by kind; [`generate`]
//! computes every figure, renders it to SVG and PNG, writes the data behind it
//! as CSV, and assembles a self-contained `index.html` and a `manifest.json`
//! (tool version, git revision, the spec text, seeds and timings). Everything
//! is produced **in memory** as a list of [`OutputFile`]s: the library does no
//! file-system I/O, the CLI (`subdiv-lab report`) writes the files atomically.
//!
//! * `spec`: the spec format and parser (errors name line and key);
//! * `config`: scheme configurations as written in specs;
//! * [`figures`]: the figure registry and the figure kinds — **to add a figure
//!   kind, read the module docs of [`figures`]**: one new module plus one line
//!   in [`figures::REGISTRY`];
//! * `plot`: plotting helpers (bundled font, sizes, colours, markers);
//! * `backend`: one drawing backend for SVG and PNG, in-memory rendering;
//! * `html`: the `index.html` page;
//! * [`crate::rng`]: the deterministic random generator behind random knots.
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
pub(crate) mod config;
pub(crate) mod error;
pub(crate) mod figure_spec;
pub mod figures;
pub(crate) mod font;
pub(crate) mod html;
mod inputs;
mod manifest;
pub(crate) mod markup;
pub(crate) mod plot;
pub(crate) mod spec;
pub mod sweep_plot;

pub use backend::{render_png, render_svg, Area};
pub use error::{Location, ReportError};
pub use figure_spec::{MAX_PIXELS, MIN_PIXELS};
pub use inputs::Inputs;
pub use manifest::{FigureRecord, Manifest};
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

/// The digest of a report file recorded in [`Manifest::digests`]: FNV-1a 64
/// of its bytes (the crate's one FNV-1a) as 16 lower-case hex digits (a
/// guard against accidents, not against an adversary).
///
/// ```
/// assert_eq!(subdiv_lab::report::file_digest(b""), "cbf29ce484222325");
/// ```
pub fn file_digest(bytes: &[u8]) -> String {
    format!("{:016x}", crate::hash::fnv1a64(bytes))
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

/// Which picture formats a report writes for each figure (CSV data, index.html
/// and manifest.json are always written).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formats {
    /// Write `<id>.svg`.
    pub svg: bool,
    /// Write `<id>.png`.
    pub png: bool,
}

impl Default for Formats {
    fn default() -> Self {
        Formats::ALL
    }
}

/// An unknown or empty `--formats` list.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("formats {0:?}: give a comma-separated list of svg and png (e.g. svg,png)")]
pub struct FormatsError(pub String);

impl Formats {
    /// Both SVG and PNG (the default).
    pub const ALL: Formats = Formats {
        svg: true,
        png: true,
    };
}

impl std::str::FromStr for Formats {
    type Err = FormatsError;

    /// Parses a comma-separated list of `svg` and `png`.
    ///
    /// ```
    /// use subdiv_lab::report::Formats;
    /// assert_eq!("png".parse::<Formats>().unwrap(), Formats { svg: false, png: true });
    /// assert_eq!("svg, png".parse::<Formats>().unwrap(), Formats::ALL);
    /// assert!("pdf".parse::<Formats>().is_err() && "".parse::<Formats>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let mut f = Formats {
            svg: false,
            png: false,
        };
        for part in s.split(',').map(str::trim) {
            match part {
                "svg" => f.svg = true,
                "png" => f.png = true,
                _ => return Err(FormatsError(s.to_owned())),
            }
        }
        Ok(f)
    }
}

/// How a report is generated beyond its spec.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Picture formats.
    pub formats: Formats,
    /// Input files of the figures.
    pub inputs: Inputs,
}

/// Computes and renders every figure of `spec` (SVG and PNG; a spec that
/// reads input files needs [`generate_with`]).
pub fn generate(
    spec: &ReportSpec,
    run: &RunInfo,
    progress: &dyn Progress,
) -> Result<RenderedReport, ReportError> {
    generate_with(spec, run, progress, &Options::default())
}

/// One figure's part of the report.
struct Part {
    record: FigureRecord,
    files: Vec<OutputFile>,
    fragment: Option<String>,
}

/// Computes and renders one figure.
fn figure_part(
    entry: &spec::FigureEntry,
    progress: &dyn Progress,
    options: &Options,
) -> Result<Part, ReportError> {
    let common = &entry.common;
    let t0 = Instant::now();
    let ctx = Context {
        common,
        progress,
        inputs: &options.inputs,
    };
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
    let mut files = Vec::new();
    for table in out.tables() {
        let name = table.file_name(&common.id);
        let bytes = table.to_csv().map_err(|e| e.in_figure(&common.id))?;
        record.csv.push(name.clone());
        files.push(OutputFile { path: name, bytes });
    }
    if out.has_plot() {
        let draw = |area: &backend::Area<'_>| out.draw(area, common);
        let f = options.formats;
        let (svg, png) = rayon::join(
            || f.svg.then(|| backend::render_svg(common.size, &draw)),
            || f.png.then(|| backend::render_png(common.size, &draw)),
        );
        if let Some(svg) = svg {
            let svg = svg.map_err(|e| e.in_figure(&common.id))?;
            let name = format!("{}.svg", common.id);
            files.push(OutputFile {
                path: name.clone(),
                bytes: svg.into_bytes(),
            });
            record.svg = Some(name);
        }
        if let Some(png) = png {
            let png = png.map_err(|e| e.in_figure(&common.id))?;
            let name = format!("{}.png", common.id);
            files.push(OutputFile {
                path: name.clone(),
                bytes: png,
            });
            record.png = Some(name);
        }
    }
    progress.inc(RENDER_WORK);
    record.render_seconds = t1.elapsed().as_secs_f64();
    Ok(Part {
        record,
        files,
        fragment: out.html(),
    })
}

/// Computes and renders every figure of `spec` in the given formats, with the
/// given input files. Every figure's inputs are checked first (so a bad input
/// fails before any long computation); the figures are then computed and
/// rendered in parallel (their results do not depend on the order), and the
/// files are listed in spec order.
pub fn generate_with(
    spec: &ReportSpec,
    run: &RunInfo,
    progress: &dyn Progress,
    options: &Options,
) -> Result<RenderedReport, ReportError> {
    use rayon::prelude::*;
    let start = Instant::now();
    for entry in &spec.figures {
        entry
            .figure
            .check_inputs(&options.inputs)
            .map_err(|e| e.in_figure(&entry.common.id))?;
    }
    let parts = spec
        .figures
        .par_iter()
        .map(|entry| figure_part(entry, progress, options))
        .collect::<Vec<_>>();
    let mut files: Vec<OutputFile> = Vec::new();
    let mut records = Vec::new();
    let mut fragments = Vec::new();
    // A CSV with the same bytes as an earlier figure's (figures that show
    // other columns of one computation, such as the knot maps coloured by
    // class, modulus ratio and angle) is written once: the later figure's
    // record names the earlier file.
    let mut csv_names: std::collections::HashMap<Vec<u8>, String> = Default::default();
    for part in parts {
        let mut part = part?;
        for f in part.files {
            if !f.path.ends_with(".csv") {
                files.push(f);
                continue;
            }
            match csv_names.get(&f.bytes) {
                Some(first) => {
                    for name in &mut part.record.csv {
                        if *name == f.path {
                            name.clone_from(first);
                        }
                    }
                }
                None => {
                    csv_names.insert(f.bytes.clone(), f.path.clone());
                    files.push(f);
                }
            }
        }
        records.push(part.record);
        fragments.push(part.fragment);
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
        digests: std::collections::BTreeMap::new(),
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
    let mut manifest = manifest;
    manifest.digests = files
        .iter()
        .map(|f| (f.path.clone(), file_digest(&f.bytes)))
        .collect();
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
