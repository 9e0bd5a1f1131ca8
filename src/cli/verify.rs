//! `subdiv-lab verify SPEC.toml --out DIR [--threads N] [--max-cells K]`:
//! certified verdicts over a box of edge ratios or an interval of `c`
//! (library: [`subdiv_lab::verify`]; math doc section 15).
//!
//! Parse, validate, estimate (refused above the limits unless `--force`),
//! run, write `DIR/cells.csv` and `DIR/summary.json`. The tool never deletes
//! or renames anything it did not create: `--out` must be new (written as a
//! temporary sibling and renamed into place), empty, or hold a previous
//! `verify` output (recognised by its `summary.json`), of which only
//! `cells.csv` and `summary.json` are replaced; anything else is refused
//! (exit 2) before any work.

use super::outfiles::{create_temp_dir, parent_dir, Staged};
use super::{write_stdout, CliError, CliResult};
use anyhow::{anyhow, Context as _};
use clap::Args;
use std::path::{Path, PathBuf};
use subdiv_lab::verify::{self, spec::VerifySpec, Limits};

/// The files a run writes.
const FILES: [&str; 2] = ["cells.csv", "summary.json"];

#[derive(Args, Debug)]
pub(crate) struct VerifyArgs {
    /// Verify spec (TOML): name, scheme ("nurds" or "adjustable-cc"),
    /// valence (nurds 3 to 16, adjustable-cc 3 to 1024), the region (nurds:
    /// box = one [lo, hi] per edge ratio, or p_box and q_box = one [lo, hi]
    /// per corner knot interval; adjustable-cc: c_range), properties (class,
    /// separation, theorem1, charmap, g1), min_width (at least 2^-40),
    /// time_budget (seconds), symmetry ("none", "rotations" or "dihedral";
    /// a nurds box of equal sides, dihedral with lo + hi = 1 exactly).
    spec: PathBuf,
    /// Output directory: new, empty, or a previous verify output (only its
    /// cells.csv and summary.json are replaced); any other directory or a
    /// file is refused. Nothing is installed unless the run, including the
    /// summary line on stdout, succeeds.
    #[arg(long)]
    out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Most cells evaluated (default 4000000); refinement stops before a
    /// level that would exceed it and the open cells stay undecided.
    #[arg(long)]
    max_cells: Option<u64>,
    /// Run even when the work estimate exceeds the limits.
    #[arg(long)]
    force: bool,
    /// No summary line on stdout.
    #[arg(long)]
    quiet: bool,
}

/// Whether `dir` holds a previous `verify` output of this tool.
fn previous_output(dir: &Path) -> bool {
    let Ok(bytes) = std::fs::read(dir.join("summary.json")) else {
        return false;
    };
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(&bytes) else {
        return false;
    };
    v.get("tool").and_then(|t| t.as_str()) == Some("subdiv-lab")
        && v.get("command").and_then(|t| t.as_str()) == Some("verify")
}

/// `true`: `out` does not exist (new directory); `false`: existing usable directory.
fn check_out(out: &Path) -> CliResult<bool> {
    match std::fs::symlink_metadata(out) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let parent = parent_dir(out);
            if !parent.is_dir() {
                return Err(CliError::usage(anyhow!(
                    "--out {}: directory {} does not exist",
                    out.display(),
                    parent.display()
                )));
            }
            if out.file_name().is_none() {
                return Err(CliError::usage(anyhow!(
                    "--out {} has no directory name",
                    out.display()
                )));
            }
            Ok(true)
        }
        Err(e) => Err(CliError::usage(anyhow!(
            "--out {}: cannot inspect it: {e}",
            out.display()
        ))),
        Ok(m) => {
            if !std::fs::metadata(out).is_ok_and(|m| m.is_dir())
                || m.file_type().is_symlink() && !out.is_dir()
            {
                return Err(CliError::usage(anyhow!(
                    "--out {} exists and is not a directory; give a new or empty directory",
                    out.display()
                )));
            }
            let mut entries = std::fs::read_dir(out)
                .with_context(|| format!("--out {}: cannot list it", out.display()))
                .map_err(CliError::usage)?;
            if entries.next().is_none() {
                return Ok(false);
            }
            if !previous_output(out) {
                return Err(CliError::usage(anyhow!(
                    "--out {} is not empty and holds no previous verify output (no summary.json of this tool); give a new or empty directory",
                    out.display()
                )));
            }
            for f in FILES {
                let p = out.join(f);
                if let Ok(m) = std::fs::symlink_metadata(&p) {
                    if !m.file_type().is_file() {
                        return Err(CliError::usage(anyhow!(
                            "{} is not a regular file; move it away or choose another --out",
                            p.display()
                        )));
                    }
                }
            }
            Ok(false)
        }
    }
}

pub(crate) fn run(args: VerifyArgs) -> CliResult {
    let text = std::fs::read_to_string(&args.spec)
        .map_err(|e| CliError::usage(anyhow!("cannot read spec {}: {e}", args.spec.display())))?;
    let spec = VerifySpec::parse(&text)
        .map_err(|e| CliError::usage(anyhow!("{}: {e}", args.spec.display())))?;
    if let Some(t) = args.threads {
        super::budget::check_threads(t)?;
    }
    let max_cells = args.max_cells.unwrap_or(verify::DEFAULT_MAX_CELLS);
    verify::check_max_cells(max_cells, subdiv_lab::budget::Spelling::Cli)
        .map_err(super::budget::usage)?;
    let new_dir = check_out(&args.out)?;
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let estimate = verify::estimate(&spec, max_cells, threads);
    super::budget::check(
        "verify",
        &format!("{} (--max-cells {max_cells})", args.spec.display()),
        &estimate,
        subdiv_lab::budget::SWEEP_TIME_LIMIT_SECONDS,
        args.force,
    )?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(CliError::failure)?;
    let limits = Limits {
        max_cells,
        ..Limits::default()
    };
    let outcome = pool.install(|| verify::run(&spec, &limits));
    let summary = verify::summary(&spec, &outcome);
    let mut json = serde_json::to_vec_pretty(&summary).map_err(CliError::failure)?;
    json.push(b'\n');
    let files: Vec<(&str, Vec<u8>)> = vec![
        ("cells.csv", verify::cells_csv(&spec, &outcome).into_bytes()),
        ("summary.json", json),
    ];
    // The summary line goes out before the files are installed: if standard
    // output fails (exit 1), no new output is left behind.
    let announce = || -> CliResult {
        if args.quiet {
            return Ok(());
        }
        let line = format!(
            "verify {}: {} cells, {}{:.2}% of the volume undecided{}, deepest level {}, {:.1} s{}; wrote {}\n",
            spec.name,
            summary.cells,
            if summary.group_order > 1 { "at most " } else { "" },
            100.0 * summary.undecided_fraction,
            if summary.group_order > 1 {
                format!(
                    " (by {} symmetry, group of order {}; {} cells left to it)",
                    summary.symmetry.as_str(),
                    summary.group_order,
                    outcome.by_symmetry
                )
            } else {
                String::new()
            },
            summary.deepest_level,
            summary.seconds,
            match summary.stopped {
                Some(verify::Stop::TimeBudget) => " (stopped: time budget)",
                Some(verify::Stop::MaxCells) => " (stopped: --max-cells)",
                None => "",
            },
            args.out.display()
        );
        write_stdout(line.as_bytes())
    };
    if new_dir {
        write_new_dir(&args.out, &files, announce)
    } else {
        // summary.json last: a half-written run is not taken for a complete one
        let staged: Vec<(PathBuf, Vec<u8>)> = files
            .iter()
            .map(|(n, b)| (args.out.join(n), b.clone()))
            .collect();
        let staged = Staged::write(&staged)?;
        announce()?;
        staged.commit()
    }
}

/// Writes `files` into a new temporary sibling of `out` (created by this
/// run), calls `announce` (the summary line), then renames it to `out`; on
/// failure the temporary is removed.
fn write_new_dir(
    out: &Path,
    files: &[(&str, Vec<u8>)],
    announce: impl FnOnce() -> CliResult,
) -> CliResult {
    let name = out
        .file_name()
        .ok_or_else(|| CliError::usage(anyhow!("--out {} has no directory name", out.display())))?
        .to_string_lossy()
        .into_owned();
    let parent = parent_dir(out);
    let tmp = create_temp_dir(&parent, &name)
        .with_context(|| format!("cannot create a directory in {}", parent.display()))
        .map_err(CliError::failure)?;
    let result = (|| -> CliResult {
        for (f, bytes) in files {
            let p = tmp.join(f);
            std::fs::write(&p, bytes)
                .with_context(|| format!("cannot write {}", p.display()))
                .map_err(CliError::failure)?;
        }
        announce()?;
        // rename(2) onto an existing non-empty directory fails: a directory
        // that appeared meanwhile is never replaced
        std::fs::rename(&tmp, out)
            .with_context(|| format!("cannot create {}", out.display()))
            .map_err(CliError::failure)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}
