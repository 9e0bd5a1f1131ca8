//! `subdiv-lab report [SPEC.toml] [--out DIR] [--quiet]`: run a
//! report spec and write the report directory.
//!
//! The library renders everything in memory; this module reads the spec (or
//! takes the default spec built into the binary), shows progress, and writes
//! the files. The tool never deletes or renames anything it did not create:
//!
//! * `--out` naming a file, or a non-empty directory that holds no previous
//!   report (recognised by its `manifest.json`), is refused (exit 2) before
//!   any work, and nothing is touched;
//! * a new directory is written as a temporary sibling and renamed into place
//!   (it appears complete or not at all); an existing empty directory is
//!   filled;
//! * a previous report (recognised by its manifest) is replaced, which is the
//!   documented default so that the main job can simply be run again: only
//!   the files its manifest lists **with their bytes unchanged** (the
//!   manifest's FNV-1a digests) are overwritten or removed; every other file
//!   in the directory is kept (a file the user edited, added, or listed by
//!   editing the manifest), and a new file that would overwrite one of them
//!   is refused (exit 2);
//! * nothing is installed until the summary line is on standard output, so a
//!   failed write there (exit 1) leaves no new report.

use super::outfiles::{create_temp_dir, parent_dir, Staged};
use super::{write_stdout, CliError, CliResult};
use anyhow::{anyhow, Context as _};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::collections::BTreeSet;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv_lab::report::figures::{NoProgress, Progress};
use subdiv_lab::report::{
    generate_with, total_work, Formats, Inputs, Options, OutputFile, ReportSpec, RunInfo,
};

/// Where the built-in default spec comes from (shown in the manifest).
const DEFAULT_SPEC_PATH: &str = "analysis/default.toml";
/// The default spec, built into the binary so `subdiv-lab report` works from
/// any directory (its meshes are generated in code, nothing else is read).
const DEFAULT_SPEC_TEXT: &str = include_str!("../../analysis/default.toml");
/// Directory under which `reports/<name>/` is written by default.
const DEFAULT_ROOT: &str = "reports";
/// The git revision of the source the binary was built from (see build.rs).
const GIT_REVISION: &str = env!("SUBDIV_LAB_GIT_REVISION");

#[derive(Args, Debug)]
pub(crate) struct ReportArgs {
    /// Report spec (TOML). Default: the spec built into the binary
    /// (analysis/default.toml of this version), usable from any directory.
    spec: Option<PathBuf>,
    /// Output directory (default: reports/<name>/ with the spec's name). A new
    /// or empty directory is written; a previous report (recognised by its
    /// manifest.json) is replaced, touching only the files its manifest lists
    /// whose bytes are unchanged (other files in the directory are kept); a
    /// file or any other non-empty directory is refused (exit 2).
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress bar and no summary line.
    #[arg(long)]
    quiet: bool,
    /// Picture formats of the figures: a comma-separated list of svg and png
    /// (CSV data, index.html and manifest.json are always written).
    #[arg(long, default_value = "svg,png")]
    formats: Formats,
}

struct Bar(ProgressBar);

impl Progress for Bar {
    fn inc(&self, n: u64) {
        self.0.inc(n);
    }
}

/// What `--out` is now.
enum Target {
    /// Does not exist: written as a temporary sibling, renamed into place.
    New,
    /// An existing directory: empty, or a previous report;
    /// `previous` are the files its manifest lists that exist with the bytes
    /// it recorded, `changed` those listed that no longer have them (kept).
    Existing {
        previous: BTreeSet<String>,
        changed: BTreeSet<String>,
    },
}

/// A plain file name inside the report directory (no separators, not `.`/`..`).
fn plain_name(s: &str) -> bool {
    !s.is_empty() && s != "." && s != ".." && !s.contains(['/', '\\']) && !s.contains('\0')
}

/// The files of a previous report in `dir`, if it holds a `manifest.json`
/// written by this tool (`"tool": "subdiv-lab"`): `(previous, changed)`,
/// the listed plain file names whose current bytes match the manifest's
/// digest, and those listed whose bytes do not (or that have no digest: a
/// manifest of an older version, or an edited one). Only `previous` and
/// `manifest.json` itself are the tool's to replace.
fn previous_report_files(dir: &Path) -> Option<(BTreeSet<String>, BTreeSet<String>)> {
    let bytes = std::fs::read(dir.join("manifest.json")).ok()?;
    let m: serde_json::Value = serde_json::from_slice(&bytes).ok()?;
    if m.get("tool")?.as_str()? != "subdiv-lab" {
        return None;
    }
    let listed: BTreeSet<String> = m
        .get("files")
        .and_then(|f| f.as_array())
        .map(|list| {
            list.iter()
                .filter_map(|v| v.as_str())
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default();
    let digests = m.get("digests").and_then(|d| d.as_object());
    let mut previous = BTreeSet::new();
    let mut changed = BTreeSet::new();
    for name in listed {
        if !plain_name(&name) || name == "manifest.json" {
            continue;
        }
        let path = dir.join(&name);
        if !std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_file()) {
            continue;
        }
        let recorded = digests.and_then(|d| d.get(&name)).and_then(|v| v.as_str());
        let unchanged = recorded.is_some_and(|want| {
            std::fs::read(&path).is_ok_and(|b| subdiv_lab::report::file_digest(&b) == want)
        });
        if unchanged {
            previous.insert(name);
        } else {
            changed.insert(name);
        }
    }
    previous.insert("manifest.json".to_owned());
    Some((previous, changed))
}

/// Checks `--out` before any work: exit 2 for a file or a non-empty
/// directory that holds no previous report of this tool.
fn check_target(out: &Path) -> CliResult<Target> {
    let meta = match std::fs::metadata(out) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if std::fs::symlink_metadata(out).is_ok() {
                return Err(CliError::usage(anyhow!(
                    "--out {} is a dangling symbolic link; remove it or choose another directory",
                    out.display()
                )));
            }
            return Ok(Target::New);
        }
        Err(e) => {
            return Err(CliError::usage(anyhow!(
                "--out {}: cannot inspect it: {e}",
                out.display()
            )))
        }
    };
    if !meta.is_dir() {
        return Err(CliError::usage(anyhow!(
            "--out {} exists and is not a directory; give a new or empty directory",
            out.display()
        )));
    }
    let mut entries = std::fs::read_dir(out)
        .with_context(|| format!("--out {}: cannot list it", out.display()))
        .map_err(CliError::usage)?;
    if entries.next().is_none() {
        return Ok(Target::Existing {
            previous: BTreeSet::new(),
            changed: BTreeSet::new(),
        });
    }
    let Some((previous, changed)) = previous_report_files(out) else {
        return Err(CliError::usage(anyhow!(
            "--out {} is not empty and holds no previous subdiv-lab report (no manifest.json of this tool); give a new or empty directory",
            out.display()
        )));
    };
    Ok(Target::Existing { previous, changed })
}

pub(crate) fn run(args: ReportArgs) -> CliResult {
    let start = Instant::now();
    let (text, spec_name) = match &args.spec {
        Some(path) => (
            std::fs::read_to_string(path).map_err(|e| {
                CliError::usage(anyhow!("cannot read spec {}: {e}", path.display()))
            })?,
            path.display().to_string(),
        ),
        None => (DEFAULT_SPEC_TEXT.to_owned(), DEFAULT_SPEC_PATH.to_owned()),
    };
    // The files a spec names (scheme files while it is parsed, the figures'
    // sweep tables below): relative paths are read from the spec's directory.
    let base = args
        .spec
        .as_deref()
        .map(super::outfiles::parent_dir)
        .unwrap_or_else(|| PathBuf::from("."));
    let read = |p: &str| std::fs::read_to_string(base.join(p)).map_err(|e| e.to_string());
    let spec = ReportSpec::parse_with(&text, &read)
        .map_err(|e| CliError::usage(anyhow!("{spec_name}: {e}")))?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new(DEFAULT_ROOT).join(&spec.name));
    // Refuse a bad --out before the (long) generation: its kind, and the
    // files every report writes (the figures' names are checked again when
    // the report is installed).
    let target = check_target(&out)?;
    if let Target::Existing { previous, changed } = &target {
        refuse_foreign(&out, ALWAYS_WRITTEN, previous, changed)?;
    }
    // Input files of the figures (sweep CSVs), beside the spec like its scheme
    // files. The library checks their columns before any figure is computed.
    let mut inputs = Inputs::default();
    for p in spec.input_paths() {
        let path = base.join(&p);
        let bytes = std::fs::read(&path).map_err(|e| {
            CliError::usage(anyhow!(
                "{spec_name}: figure input {p} ({}): {e}",
                path.display()
            ))
        })?;
        inputs.insert(p, bytes);
    }
    let options = Options {
        formats: args.formats,
        inputs,
    };
    let run = RunInfo {
        version: Some(env!("CARGO_PKG_VERSION").to_owned()),
        git_revision: (GIT_REVISION != "unknown").then(|| GIT_REVISION.to_owned()),
        spec_path: Some(spec_name.clone()),
        spec_builtin: args.spec.is_none(),
    };
    let show = !args.quiet && std::io::stderr().is_terminal();
    let report = if show {
        let bar = ProgressBar::new(total_work(&spec));
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} report {msg} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}",
            )
            .map_err(|e| CliError::failure(anyhow!("progress bar: {e}")))?,
        );
        bar.set_message(spec.name.clone());
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let r = generate_with(&spec, &run, &Bar(bar.clone()), &options);
        bar.finish_and_clear();
        r
    } else {
        generate_with(&spec, &run, &NoProgress, &options)
    }
    .map_err(|e| CliError::report(e).context(spec_name.clone()))?;
    // The summary line goes out before the report is installed: if standard
    // output fails (exit 1), no new report is left behind.
    let announce = || -> CliResult {
        if args.quiet {
            return Ok(());
        }
        let line = format!(
            "wrote {} files to {} in {:.1} s; open {}\n",
            report.files.len(),
            out.display(),
            start.elapsed().as_secs_f64(),
            out.join("index.html").display()
        );
        write_stdout(line.as_bytes())
    };
    match target {
        Target::New => write_new_dir(&out, &report.files, announce),
        Target::Existing { previous, changed } => {
            write_into_dir(&out, &report.files, &previous, &changed, announce)
        }
    }
}

/// The files every report writes.
const ALWAYS_WRITTEN: &[&str] = &["index.html", "manifest.json"];

/// Refuses (exit 2) if one of `names` exists in `out` and is not an
/// unchanged file of the previous report: the tool never overwrites what it
/// did not create.
fn refuse_foreign(
    out: &Path,
    names: &[&str],
    previous: &BTreeSet<String>,
    changed: &BTreeSet<String>,
) -> CliResult {
    for name in names {
        let p = out.join(name);
        let taken = std::fs::symlink_metadata(&p).is_ok();
        if taken && !previous.contains(*name) {
            let why = if changed.contains(*name) {
                "has changed since the previous report wrote it (or manifest.json records no digest of it)"
            } else {
                "is not part of the previous report"
            };
            return Err(CliError::usage(anyhow!(
                "{} exists and {why}; move it away or choose another --out",
                p.display()
            )));
        }
    }
    Ok(())
}

/// Writes `files` into a new temporary sibling of `out` (created by this
/// run), calls `announce` (the summary line), then renames it to `out`; on
/// failure the temporary is removed.
fn write_new_dir(
    out: &Path,
    files: &[OutputFile],
    announce: impl FnOnce() -> CliResult,
) -> CliResult {
    let name = out
        .file_name()
        .ok_or_else(|| CliError::usage(anyhow!("--out {} has no directory name", out.display())))?
        .to_string_lossy()
        .into_owned();
    let parent = parent_dir(out);
    std::fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create {}", parent.display()))
        .map_err(CliError::failure)?;
    let tmp = create_temp_dir(&parent, &name)
        .with_context(|| format!("cannot create a directory in {}", parent.display()))
        .map_err(CliError::failure)?;
    let result = (|| -> CliResult {
        for f in files {
            let p = tmp.join(&f.path);
            std::fs::write(&p, &f.bytes)
                .with_context(|| format!("cannot write {}", p.display()))
                .map_err(CliError::failure)?;
        }
        announce()?;
        // rename(2) onto an existing non-empty directory fails, so a directory
        // that appeared meanwhile is never replaced.
        std::fs::rename(&tmp, out)
            .with_context(|| format!("cannot create {}", out.display()))
            .map_err(CliError::failure)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}

/// Writes `files` into the existing directory `out`: each to a temporary file
/// of this run; after `announce` (the summary line) they are renamed into
/// place (manifest.json last); then removes the files of the `previous`
/// report that the new one no longer has. A new file whose name is taken by a
/// file not in `previous` is refused (exit 2).
fn write_into_dir(
    out: &Path,
    files: &[OutputFile],
    previous: &BTreeSet<String>,
    changed: &BTreeSet<String>,
    announce: impl FnOnce() -> CliResult,
) -> CliResult {
    let names: Vec<&str> = files.iter().map(|f| f.path.as_str()).collect();
    refuse_foreign(out, &names, previous, changed)?;
    let mut ordered: Vec<(PathBuf, Vec<u8>)> = files
        .iter()
        .filter(|f| f.path != "manifest.json")
        .map(|f| (out.join(&f.path), f.bytes.clone()))
        .collect();
    ordered.extend(
        files
            .iter()
            .filter(|f| f.path == "manifest.json")
            .map(|f| (out.join(&f.path), f.bytes.clone())),
    );
    let staged = Staged::write(&ordered)?;
    announce()?;
    staged.commit()?;
    let new: BTreeSet<&str> = files.iter().map(|f| f.path.as_str()).collect();
    for old in previous {
        if !new.contains(old.as_str()) {
            let p = out.join(old);
            std::fs::remove_file(&p)
                .with_context(|| format!("cannot remove the old report file {}", p.display()))
                .map_err(CliError::failure)?;
        }
    }
    Ok(())
}
