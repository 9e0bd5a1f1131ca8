//! `subdiv-lab sweep` and `subdiv-lab merge`: the file side of parameter sweeps
//! (the enumeration, evaluation, CSV layout and summaries live in
//! `subdiv_lab::sweep`).
//!
//! Files: `--out NAME.csv` gets the rows, `NAME.summary.json` the summary (written
//! when the run starts and again when it ends). `--resume` re-reads `NAME.csv`,
//! drops a torn last line, verifies every row against the spec, and continues.

use super::{CliError, CliResult};
use anyhow::{anyhow, Context};
use clap::Args;
use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, IsTerminal, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv_lab::sweep::output::{self, MergeSource};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepError, SweepSpec};

#[derive(Args, Debug)]
pub(crate) struct SweepArgs {
    /// The sweep spec (TOML; see analysis/sweep-*.toml).
    spec: PathBuf,
    /// Output CSV (default: standard output, without a summary file). The summary
    /// JSON goes beside it: NAME.csv -> NAME.summary.json.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Run shard I of N: the configurations with id % N == I.
    #[arg(long, value_parser = parse_shard)]
    shard: Option<Shard>,
    /// Continue an interrupted run of the same command (needs --out; starts afresh
    /// if the file does not exist).
    #[arg(long)]
    resume: bool,
    /// Stop after the first K configurations of the shard (a prefix of the full run).
    #[arg(long)]
    limit: Option<u64>,
    /// Run even when the estimated time or memory exceeds the limits (see README).
    #[arg(long)]
    force: bool,
}

#[derive(Args, Debug)]
pub(crate) struct MergeArgs {
    /// Shard CSVs written by `sweep --shard I/N --out ...` (each with its
    /// .summary.json beside it).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Merged CSV (its summary goes beside it).
    #[arg(long)]
    out: PathBuf,
}

fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse::<Shard>().map_err(|e| e.to_string())
}

/// `NAME.csv` -> `NAME.summary.json` (any other name gets `.summary.json` appended).
fn summary_path(csv: &Path) -> PathBuf {
    let name = csv
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name.strip_suffix(".csv").unwrap_or(&name);
    csv.with_file_name(format!("{stem}.summary.json"))
}

/// Writes `bytes` to `path` atomically (temporary file + rename).
fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let tmp = path.with_file_name(format!(
        ".{}.tmp",
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    ));
    fs::write(&tmp, bytes).with_context(|| format!("writing {}", tmp.display()))?;
    fs::rename(&tmp, path)
        .with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))?;
    Ok(())
}

fn write_summary(path: &Path, summary: &Summary) -> CliResult {
    let json = serde_json::to_string_pretty(summary).map_err(CliError::failure)? + "\n";
    write_atomic(path, json.as_bytes()).map_err(CliError::failure)
}

/// Reads an existing CSV for `--resume`: checks the header, verifies every
/// complete line against the spec (adding it to `summary`), and returns the number
/// of rows and the byte length of the good prefix (a torn last line excluded).
fn scan_existing(
    path: &Path,
    plan: &Plan,
    layout: &Layout,
    shard: Shard,
    summary: &mut Summary,
) -> CliResult<(u64, u64, bool)> {
    let file = File::open(path)
        .with_context(|| format!("opening {}", path.display()))
        .map_err(CliError::failure)?;
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let name = path.display().to_string();
    let mut line = Vec::new();
    let mut good: u64 = 0;
    let mut rows: u64 = 0;
    let mut lineno: u64 = 0;
    let mut torn = false;
    let header = layout.header();
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .with_context(|| format!("reading {name}"))
            .map_err(CliError::failure)?;
        if n == 0 {
            break;
        }
        if line.last() != Some(&b'\n') {
            // Killed mid-write: the last line is incomplete. Drop it.
            torn = true;
            break;
        }
        lineno += 1;
        let text = std::str::from_utf8(&line).map_err(|_| {
            CliError::usage(anyhow!(
                "{name}: line {lineno} is not UTF-8; not a sweep CSV"
            ))
        })?;
        if lineno == 1 {
            if text != header {
                return Err(CliError::usage(anyhow!(
                    "{name}: the header does not match this spec's columns; cannot resume (expected {:?})",
                    header.trim_end()
                )));
            }
        } else {
            if rows >= summary.expected_rows {
                return Err(CliError::usage(anyhow!(
                    "{name}: has more rows than this run expects ({}); was it written with another --shard or --limit?",
                    summary.expected_rows
                )));
            }
            let row = layout
                .verify(plan, shard.id(rows), text.trim_end_matches('\n'))
                .map_err(|message| {
                    CliError::usage(SweepError::Mismatch {
                        source_name: name.clone(),
                        line: lineno,
                        message,
                    })
                })?;
            summary.add(layout, &row);
            rows += 1;
        }
        good += n as u64;
    }
    Ok((rows, good, torn || lineno == 0))
}

pub(crate) fn run_sweep(args: SweepArgs) -> CliResult {
    let text = fs::read_to_string(&args.spec)
        .with_context(|| format!("reading spec {}", args.spec.display()))
        .map_err(CliError::usage)?;
    let spec = SweepSpec::from_toml(&text)
        .map_err(|e| CliError::usage(anyhow!("{}: {e}", args.spec.display())))?;
    if let Some(t) = args.threads {
        super::budget::check_threads(t)?;
    }
    if args.resume && args.out.is_none() {
        return Err(CliError::usage(anyhow!("--resume needs --out FILE.csv")));
    }
    let shard = args.shard.unwrap_or(Shard::ALL);
    let plan = Plan::new(spec);
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(&plan, &layout, shard, args.limit);
    let expected = summary.expected_rows;
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    // Work estimate of this shard's rows (before --resume skips any: a
    // conservative bound), checked before any file is opened.
    let estimate = subdiv_lab::budget::sweep_rows(&plan, expected, shard.count, threads);
    super::budget::check(
        "sweep",
        &format!("{}", args.spec.display()),
        &estimate,
        subdiv_lab::budget::SWEEP_TIME_LIMIT_SECONDS,
        args.force,
    )?;
    if estimate.seconds > subdiv_lab::budget::TIME_LIMIT_SECONDS {
        eprintln!(
            "sweep: {} estimated at ~{}",
            estimate.what,
            subdiv_lab::budget::format_seconds(estimate.seconds)
        );
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(CliError::failure)?;

    // Open the output (only now: a bad spec or flag creates no file).
    let (mut sink, done, summary_file): (Box<dyn Write + Send>, u64, Option<PathBuf>) =
        match &args.out {
            None => {
                let mut w = BufWriter::with_capacity(1 << 20, std::io::stdout());
                layout.write_header(&mut w).map_err(CliError::failure)?;
                (Box::new(w), 0, None)
            }
            Some(path) => {
                let spath = summary_path(path);
                let exists = path.exists();
                if exists && !args.resume {
                    return Err(CliError::usage(anyhow!(
                        "{} exists; pass --resume to continue it, or remove it",
                        path.display()
                    )));
                }
                let (done, good, rewrite) = if exists {
                    scan_existing(path, &plan, &layout, shard, &mut summary)?
                } else {
                    (0, 0, true)
                };
                let mut file = OpenOptions::new()
                    .create(true)
                    .truncate(false)
                    .write(true)
                    .open(path)
                    .with_context(|| format!("opening {}", path.display()))
                    .map_err(CliError::failure)?;
                if exists {
                    file.set_len(good)
                        .and_then(|_| file.seek(SeekFrom::End(0)).map(|_| ()))
                        .with_context(|| format!("truncating {}", path.display()))
                        .map_err(CliError::failure)?;
                    if rewrite && good == 0 {
                        // Empty or torn inside the header.
                        layout.write_header(&mut file).map_err(CliError::failure)?;
                    }
                    if done > 0 || good > 0 {
                        eprintln!(
                            "sweep: resuming {} at row {done} of {expected}{}",
                            path.display(),
                            if rewrite && good > 0 {
                                " (dropped a torn last line)"
                            } else {
                                ""
                            }
                        );
                    }
                } else {
                    layout.write_header(&mut file).map_err(CliError::failure)?;
                }
                write_summary(&spath, &summary)?;
                (
                    Box::new(BufWriter::with_capacity(1 << 20, file)),
                    done,
                    Some(spath),
                )
            }
        };

    // Progress bar on a terminal only.
    let bar = if std::io::stderr().is_terminal() && expected > done {
        let pb = indicatif::ProgressBar::new(expected);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} {rate} ETA {eta}",
        ) {
            pb.set_style(style.with_key(
                "rate",
                |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{:.0} configurations/s", state.per_sec());
                },
            ));
        }
        pb.set_position(done);
        pb.reset_eta();
        Some(pb)
    } else {
        None
    };
    let start = Instant::now();
    let ids = (done..expected).map(|j| shard.id(j));
    let result = pool.install(|| {
        output::run(
            &plan,
            &layout,
            &eval,
            ids,
            &mut sink,
            &mut summary,
            &mut |k| {
                if let Some(pb) = &bar {
                    pb.set_position(done + k);
                }
            },
        )
    });
    if let Some(pb) = &bar {
        pb.finish_and_clear();
    }
    let evaluated = result.map_err(CliError::failure)?;
    sink.flush().map_err(CliError::failure)?;
    drop(sink);
    let seconds = start.elapsed().as_secs_f64();
    summary.set_throughput(evaluated, seconds, threads);
    if let Some(spath) = &summary_file {
        write_summary(spath, &summary)?;
    }
    let rate = if seconds > 0.0 {
        evaluated as f64 / seconds
    } else {
        0.0
    };
    eprintln!(
        "sweep: {} rows ({evaluated} evaluated in {seconds:.2} s, {rate:.0} configurations/s, {threads} threads){}{}",
        summary.rows,
        if summary.errors > 0 {
            format!(", {} failed (see the error column)", summary.errors)
        } else {
            String::new()
        },
        match &summary_file {
            Some(p) => format!("; summary {}", p.display()),
            None => String::new(),
        }
    );
    Ok(())
}

/// Data lines of one shard CSV.
type LineIter = Box<dyn Iterator<Item = Result<String, SweepError>>>;

/// Lines of a data file after its header, as a [`MergeSource`].
fn data_lines(
    path: &Path,
    header: &mut Option<String>,
    rows: std::rc::Rc<std::cell::Cell<u64>>,
) -> CliResult<MergeSource<LineIter>> {
    let name = path.display().to_string();
    let file = File::open(path)
        .with_context(|| format!("opening {name}"))
        .map_err(CliError::usage)?;
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let mut first = String::new();
    reader
        .read_line(&mut first)
        .with_context(|| format!("reading {name}"))
        .map_err(CliError::failure)?;
    match header {
        None => *header = Some(first),
        Some(h) if *h == first => {}
        Some(_) => {
            return Err(CliError::usage(anyhow!(
                "{name}: header differs from the first input's; not shards of one sweep"
            )))
        }
    }
    let n2 = name.clone();
    let mut lineno = 1u64;
    let mut buf = Vec::new();
    let iter = std::iter::from_fn(move || {
        buf.clear();
        match reader.read_until(b'\n', &mut buf) {
            Ok(0) => None,
            Ok(_) => {
                lineno += 1;
                if buf.last() != Some(&b'\n') {
                    return Some(Err(SweepError::Mismatch {
                        source_name: n2.clone(),
                        line: lineno,
                        message: "torn last line; finish this shard with `sweep --resume` first"
                            .into(),
                    }));
                }
                buf.pop();
                rows.set(rows.get() + 1);
                Some(String::from_utf8(std::mem::take(&mut buf)).map_err(|_| {
                    SweepError::Mismatch {
                        source_name: n2.clone(),
                        line: lineno,
                        message: "not UTF-8".into(),
                    }
                }))
            }
            Err(e) => Some(Err(SweepError::Io(format!("{n2}: {e}")))),
        }
    });
    Ok(MergeSource {
        name,
        lines: Box::new(iter),
    })
}

pub(crate) fn run_merge(args: MergeArgs) -> CliResult {
    // Summaries first: they name the sweep (digest, total).
    let mut summaries = Vec::new();
    for p in &args.inputs {
        let sp = summary_path(p);
        let mut text = String::new();
        File::open(&sp)
            .and_then(|mut f| f.read_to_string(&mut text))
            .with_context(|| {
                format!(
                    "reading {} (the summary `sweep` writes beside {})",
                    sp.display(),
                    p.display()
                )
            })
            .map_err(CliError::usage)?;
        let s: Summary = serde_json::from_str(&text)
            .with_context(|| format!("parsing {}", sp.display()))
            .map_err(CliError::usage)?;
        summaries.push(s);
    }
    let mut merged = summaries[0].clone();
    for s in &summaries[1..] {
        merged.merge(s).map_err(CliError::usage)?;
    }
    let total = summaries[0].total_configurations;
    let mut header = None;
    let mut sources = Vec::new();
    let mut counters = Vec::new();
    for p in &args.inputs {
        let c = std::rc::Rc::new(std::cell::Cell::new(0u64));
        sources.push(data_lines(p, &mut header, c.clone())?);
        counters.push(c);
    }
    let header = header.unwrap_or_default();
    if args
        .inputs
        .iter()
        .any(|p| fs::canonicalize(p).ok() == fs::canonicalize(&args.out).ok())
    {
        return Err(CliError::usage(anyhow!(
            "--out {} is one of the inputs",
            args.out.display()
        )));
    }
    // Write to a temporary file; rename only when every check passed.
    let tmp = args.out.with_file_name(format!(
        ".{}.partial",
        args.out
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    ));
    let result = (|| -> CliResult<u64> {
        let file = File::create(&tmp)
            .with_context(|| format!("creating {}", tmp.display()))
            .map_err(CliError::failure)?;
        let mut w = BufWriter::with_capacity(1 << 20, file);
        w.write_all(header.as_bytes()).map_err(CliError::failure)?;
        let n = output::merge(total, sources, &mut w).map_err(|e| match e {
            SweepError::Io(_) => CliError::failure(e),
            other => CliError::usage(other),
        })?;
        w.flush().map_err(CliError::failure)?;
        Ok(n)
    })();
    let n = match result {
        Ok(n) => n,
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            return Err(e);
        }
    };
    for ((p, s), c) in args.inputs.iter().zip(&summaries).zip(&counters) {
        if s.rows != c.get() {
            let _ = fs::remove_file(&tmp);
            return Err(CliError::usage(anyhow!(
                "{}: the summary counts {} rows but the CSV has {}; finish that shard with `sweep --resume`",
                p.display(),
                s.rows,
                c.get()
            )));
        }
    }
    fs::rename(&tmp, &args.out)
        .with_context(|| format!("renaming {} to {}", tmp.display(), args.out.display()))
        .map_err(CliError::failure)?;
    write_summary(&summary_path(&args.out), &merged)?;
    eprintln!(
        "merge: {n} rows from {} shards into {}; every configuration 0..{total} present once",
        args.inputs.len(),
        args.out.display()
    );
    Ok(())
}
