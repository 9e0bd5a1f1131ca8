//! `subdiv-lab report [SPEC.toml] [--out DIR] [--quiet]`: run a report spec
//! and write the report directory atomically.
//!
//! The library renders everything in memory; this module reads the spec,
//! shows progress, and writes the files into a temporary sibling directory
//! that is renamed into place at the end, so the output directory appears
//! complete or not at all (and an old report of the same name is replaced
//! only once the new one is complete).

use super::{CliError, CliResult};
use anyhow::{anyhow, Context as _};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv_lab::report::figures::{NoProgress, Progress};
use subdiv_lab::report::{generate, total_work, ReportSpec, RunInfo};

/// Default spec path.
const DEFAULT_SPEC: &str = "analysis/default.toml";
/// Directory under which `reports/<name>/` is written by default.
const DEFAULT_ROOT: &str = "reports";

#[derive(Args, Debug)]
pub(crate) struct ReportArgs {
    /// Report spec (TOML).
    #[arg(default_value = DEFAULT_SPEC)]
    spec: PathBuf,
    /// Output directory (default: reports/<name>/ with the spec's name).
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress bar and no summary line.
    #[arg(long)]
    quiet: bool,
}

struct Bar(ProgressBar);

impl Progress for Bar {
    fn inc(&self, n: u64) {
        self.0.inc(n);
    }
}

/// The git revision of the working directory, with `-dirty` for uncommitted changes.
fn git_revision() -> Option<String> {
    let out = std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .stderr(std::process::Stdio::null())
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    let mut rev = String::from_utf8(out.stdout).ok()?.trim().to_owned();
    if rev.is_empty() {
        return None;
    }
    let dirty = std::process::Command::new("git")
        .args(["status", "--porcelain", "--untracked-files=no"])
        .stderr(std::process::Stdio::null())
        .output()
        .ok()
        .is_some_and(|o| o.status.success() && !o.stdout.is_empty());
    if dirty {
        rev.push_str("-dirty");
    }
    Some(rev)
}

pub(crate) fn run(args: ReportArgs) -> CliResult {
    let start = Instant::now();
    let text = std::fs::read_to_string(&args.spec)
        .map_err(|e| CliError::usage(anyhow!("cannot read spec {}: {e}", args.spec.display())))?;
    let spec = ReportSpec::parse(&text)
        .map_err(|e| CliError::usage(anyhow!("{}: {e}", args.spec.display())))?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new(DEFAULT_ROOT).join(&spec.name));
    let run = RunInfo {
        version: Some(env!("CARGO_PKG_VERSION").to_owned()),
        git_revision: git_revision(),
        spec_path: Some(args.spec.display().to_string()),
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
        let r = generate(&spec, &run, &Bar(bar.clone()));
        bar.finish_and_clear();
        r
    } else {
        generate(&spec, &run, &NoProgress)
    }
    .map_err(|e| CliError::failure(anyhow!("{}: {e}", args.spec.display())))?;
    write_atomically(&out, &report.files).map_err(CliError::failure)?;
    if !args.quiet {
        println!(
            "wrote {} files to {} in {:.1} s; open {}",
            report.files.len(),
            out.display(),
            start.elapsed().as_secs_f64(),
            out.join("index.html").display()
        );
    }
    Ok(())
}

/// Writes `files` into a temporary sibling of `out`, then renames it into place.
fn write_atomically(out: &Path, files: &[subdiv_lab::report::OutputFile]) -> anyhow::Result<()> {
    let name = out
        .file_name()
        .ok_or_else(|| anyhow!("output path {} has no directory name", out.display()))?
        .to_string_lossy()
        .into_owned();
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create {}", parent.display()))?;
    let pid = std::process::id();
    let tmp = parent.join(format!(".{name}.tmp-{pid}"));
    let old = parent.join(format!(".{name}.old-{pid}"));
    let result = (|| -> anyhow::Result<()> {
        std::fs::create_dir(&tmp).with_context(|| format!("cannot create {}", tmp.display()))?;
        for f in files {
            let p = tmp.join(&f.path);
            std::fs::write(&p, &f.bytes)
                .with_context(|| format!("cannot write {}", p.display()))?;
        }
        let replaced = out.exists();
        if replaced {
            std::fs::rename(out, &old)
                .with_context(|| format!("cannot move the old {} aside", out.display()))?;
        }
        if let Err(e) = std::fs::rename(&tmp, out) {
            if replaced {
                // Put the old report back; the new one stays in tmp until cleanup below.
                let _ = std::fs::rename(&old, out);
            }
            return Err(anyhow!(e).context(format!("cannot rename into {}", out.display())));
        }
        if replaced {
            std::fs::remove_dir_all(&old)
                .with_context(|| format!("cannot remove the old report {}", old.display()))?;
        }
        Ok(())
    })();
    if result.is_err() && tmp.exists() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}
