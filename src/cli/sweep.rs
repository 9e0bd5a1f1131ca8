//! `subdiv-lab sweep` and `subdiv-lab merge`: the file side of parameter sweeps
//! (the enumeration, evaluation, CSV layout and summaries live in
//! `subdiv_lab::sweep`).
//!
//! Files: `--out NAME.csv` gets the rows (the header first), `NAME.summary.json`
//! the summary (written when the run starts, before the CSV, and again when it
//! ends); the summary's spec digest and shard are the CSV's fingerprint.
//! `--resume` re-reads `NAME.csv`, drops a torn last line, verifies every row
//! against the spec, and continues.
//!
//! `sweep --out` is a resumable output (the rule of `super::outfiles`): a new
//! file appears whole with its header; an existing one is never replaced, and
//! `--resume` continues it only if its summary is of this spec and shard (an
//! empty or foreign file is refused). `merge --out` is a
//! single-file output: an existing regular file is replaced atomically. The
//! extension `.csv` or `.parquet` of an output must match its format.

use super::outfiles::{write_atomic, Staged};
use super::{CliError, CliResult};
use anyhow::{anyhow, Context};
use clap::Args;
use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, IsTerminal, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv_lab::sweep::output::parquet::ParquetRows;
use subdiv_lab::sweep::output::shards::{self, summary_path, ShardData, ShardFile};
use subdiv_lab::sweep::output::{self, dataset, LineFault, Verifier};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepError, SweepSpec};

#[derive(Args, Debug)]
pub(crate) struct SweepArgs {
    /// The sweep spec (TOML; see analysis/sweep-*.toml).
    spec: PathBuf,
    /// Output file, NAME.csv or NAME.parquet (default: CSV on standard output,
    /// without a summary file). The summary JSON goes beside it: NAME.csv ->
    /// NAME.summary.json. A resumable output: an existing file is never
    /// replaced; --resume continues it if its summary is of this spec and shard.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Run shard I of N: the configurations with id % N == I.
    #[arg(long, value_parser = parse_shard)]
    shard: Option<Shard>,
    /// Continue an interrupted run of the same command (needs --out; starts afresh
    /// if the file does not exist; an existing file's summary must be of this
    /// spec and shard: an empty or foreign file is refused).
    #[arg(long)]
    resume: bool,
    /// Stop after the first K configurations of the shard (a prefix of the full run).
    #[arg(long)]
    limit: Option<u64>,
    /// Run even when the estimated time or memory exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
    /// No progress output (neither the bar on a terminal nor the periodic
    /// progress lines otherwise) and no closing line; errors are still reported.
    #[arg(long)]
    quiet: bool,
    /// Output format of the rows: `csv` or `parquet` (typed columns, row
    /// groups of 65536 rows as commit units; needs --out). Default: parquet
    /// when --out ends in .parquet, else csv; a --format that contradicts a
    /// .csv or .parquet --out is refused.
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Seconds between progress lines when stderr is not a terminal (testing).
    #[arg(long, hide = true, default_value_t = PROGRESS_EVERY.as_secs_f64())]
    progress_every: f64,
    /// Sweep the spec's valences with a scheme file (TOML; docs/scheme-files.md)
    /// in place of the spec's scheme (the spec's space must be "uniform").
    #[arg(long, value_name = "FILE.toml")]
    scheme_file: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub(crate) struct MergeArgs {
    /// Shards written by `sweep --shard I/N --out ...`: CSV files (each with
    /// its .summary.json beside it), or Parquet dataset directories
    /// NAME.parquet (every shard's parts and summary in them).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Merged file, in the shards' format (NAME.csv, or for datasets one
    /// compacted Parquet file NAME.parquet; its summary goes beside it). An
    /// existing regular file is replaced atomically.
    #[arg(long)]
    out: PathBuf,
    /// The sweep spec the shards were run with: every row is verified against it.
    #[arg(long)]
    spec: PathBuf,
    /// The scheme file the shards were run with (`sweep --scheme-file`).
    #[arg(long, value_name = "FILE.toml")]
    scheme_file: Option<PathBuf>,
}

/// The plan of `spec`, with the scheme file of `--scheme-file` when given
/// (errors name the spec or the file).
fn plan_of(spec: SweepSpec, spec_path: &Path, scheme_file: Option<&Path>) -> CliResult<Plan> {
    match scheme_file {
        None => Ok(Plan::new(spec)),
        Some(path) => {
            let file = super::scheme_args::read_scheme_file("--scheme-file", path)?;
            Plan::with_scheme(spec, subdiv_lab::sweep::SchemeFactory::from_file(file)).map_err(
                |e| {
                    CliError::usage(anyhow!(
                        "{}: {e} (with --scheme-file {})",
                        spec_path.display(),
                        path.display()
                    ))
                },
            )
        }
    }
}

/// Output format of `sweep`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Format {
    /// One CSV line per configuration.
    Csv,
    /// Apache Parquet, typed columns.
    Parquet,
}

impl Format {
    fn name(self) -> &'static str {
        match self {
            Format::Csv => "CSV",
            Format::Parquet => "Parquet",
        }
    }

    fn extension(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Parquet => "parquet",
        }
    }

    /// The format an output name's extension (`.csv`, `.parquet`, any case)
    /// stands for; `None` for any other name.
    fn of_name(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?;
        [Format::Csv, Format::Parquet]
            .into_iter()
            .find(|f| ext.eq_ignore_ascii_case(f.extension()))
    }
}

/// The format of `sweep`'s rows: `--format` if given (refused when `--out`
/// ends in the other format's extension), else the extension's (`.parquet`:
/// Parquet), else CSV. The flag says whether it was inferred as Parquet from
/// the extension (then the run says so on stderr).
fn sweep_format(flag: Option<Format>, out: Option<&Path>) -> CliResult<(Format, bool)> {
    let named = out.and_then(Format::of_name);
    match (flag, named, out) {
        (Some(f), Some(n), Some(out)) if f != n => Err(CliError::usage(anyhow!(
            "--format {} but --out {} names a {} file; name it NAME.{} or leave out --format",
            f.extension(),
            out.display(),
            n.name(),
            f.extension()
        ))),
        (Some(f), _, _) => Ok((f, false)),
        (None, Some(n), _) => Ok((n, n == Format::Parquet)),
        (None, None, _) => Ok((Format::Csv, false)),
    }
}

fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse::<Shard>().map_err(|e| e.to_string())
}

/// Checks the output paths of `sweep --out` and `merge --out` before any work
/// (exit 2): the output must not be a special file (a device such as
/// `/dev/null`, a FIFO: the CSV is resumable and its summary goes beside it),
/// the output and its summary must differ from every input (the spec, the
/// shards and their summaries), and an existing file at the summary path is
/// refused unless it is itself a sweep summary (this output's, or an earlier
/// run's, e.g. of `NAME.csv` beside `NAME.parquet`): the tool never
/// overwrites a file it did not write. `spath` is the output's summary.
fn check_out_paths(command: &str, out: &Path, spath: &Path, inputs: &[(&str, &Path)]) -> CliResult {
    if super::outfiles::is_special(out) {
        return Err(CliError::usage(anyhow!(
            "--out {} is not a regular file: {command} writes a CSV (or Parquet) file and a summary beside it; to discard the rows, leave out --out and redirect standard output",
            out.display()
        )));
    }
    super::outfiles::check_distinct(&[("--out", out), ("its summary", spath)], inputs)?;
    check_summary_path(out, spath)
}

/// Refuses an existing file at `spath`, the summary of `--out out`, unless
/// it is a sweep summary.
fn check_summary_path(out: &Path, spath: &Path) -> CliResult {
    let a_summary =
        || fs::read_to_string(spath).is_ok_and(|t| serde_json::from_str::<Summary>(&t).is_ok());
    if fs::symlink_metadata(spath).is_ok() && !a_summary() {
        return Err(CliError::usage(anyhow!(
            "{} exists and is not a sweep summary (the summary --out {} would write); remove it or choose another --out",
            spath.display(),
            out.display()
        )));
    }
    Ok(())
}

/// The sweep summary at `path`, if it is one.
fn read_summary(path: &Path) -> Option<Summary> {
    let text = fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

fn write_summary(path: &Path, summary: &Summary) -> CliResult {
    let json = serde_json::to_string_pretty(summary).map_err(CliError::failure)? + "\n";
    write_atomic(path, json.as_bytes()).map_err(CliError::failure)
}

/// A salt for the verifier's re-evaluated sample (the library's).
use subdiv_lab::sweep::output::fresh_salt as salt;

/// Reads an existing CSV for `--resume`: checks its fingerprint (the summary
/// JSON beside it: same spec, same shard) and the header, verifies every
/// complete line in full against the spec ([`Verifier`]: ids, parameters
/// re-derived from the id, results well formed, a random sample
/// re-evaluated), adds the rows to `summary`, and returns the number of rows,
/// the byte length of the good prefix (a torn last line excluded; 0 when the
/// header line is torn) and whether the header must be (re)written.
fn scan_existing(
    path: &Path,
    plan: &Plan,
    layout: &Layout,
    eval: &SpectralEvaluator,
    shard: Shard,
    summary: &mut Summary,
) -> CliResult<(u64, u64, bool, bool)> {
    let file = File::open(path)
        .with_context(|| format!("opening {}", path.display()))
        .map_err(CliError::failure)?;
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let name = path.display().to_string();
    let mut line = Vec::new();
    let mut good: u64 = 0;
    let mut lineno: u64 = 0;
    let torn;
    let header = layout.header();
    let mut verifier = Verifier::new(plan, layout, salt());
    let mismatch = |line: u64, message: String| {
        CliError::usage(SweepError::Mismatch {
            source_name: name.clone(),
            line,
            message,
        })
    };
    let read_error = |e: std::io::Error| {
        CliError::failure(anyhow::Error::new(e).context(format!("reading {name}")))
    };
    // The header line.
    let n = reader.read_until(b'\n', &mut line).map_err(read_error)?;
    if n == 0 {
        // A file of this tool appears whole with its header: an empty one is
        // someone else's.
        return Err(CliError::usage(anyhow!(
            "{name} exists but is empty: not a sweep file of this tool (one is created whole, with its header); remove it or choose another --out"
        )));
    }
    if output::is_old_csv_fingerprint(&line) {
        return Err(mismatch(1, format!("{}; cannot resume", output::OLD_CSV)));
    }
    // The fingerprint: the summary JSON beside the file.
    let spath = summary_path(path);
    let Some(old) = read_summary(&spath) else {
        return Err(CliError::usage(anyhow!(
            "{name}: its summary {} is missing or not a sweep summary; the summary ties a sweep CSV to its spec and shard; cannot resume",
            spath.display()
        )));
    };
    output::check_summary(plan, shard, &old).map_err(|m| {
        CliError::usage(anyhow!(
            "{name}: {m} (by its summary {}); cannot resume",
            spath.display()
        ))
    })?;
    if line.last() != Some(&b'\n') {
        // Killed while the header was written (a file not created whole by
        // the temporary-file-and-link step): start afresh if it is the start
        // of this spec's header.
        if !header.as_bytes().starts_with(&line) {
            return Err(mismatch(
                1,
                "an incomplete first line that is not this spec's header: not a sweep CSV of this spec; cannot resume".into(),
            ));
        }
        return Ok((0, 0, true, true));
    }
    if line != header.as_bytes() {
        return Err(CliError::usage(anyhow!(
            "{name}: the header does not match this spec's columns; cannot resume (expected {:?})",
            header.trim_end()
        )));
    }
    lineno += 1;
    good += n as u64;
    // The data lines, by blocks of about BLOCK_BYTES: each block's complete
    // lines are verified in parallel on the current pool while the next block
    // is read; the bytes after the last line end go to the next block, and at
    // the end of the file they are a torn last line (killed mid-write: dropped).
    const BLOCK_BYTES: u64 = 8 << 20;
    let fill = |reader: &mut BufReader<File>, buf: &mut Vec<u8>| -> CliResult<usize> {
        let n = reader
            .by_ref()
            .take(BLOCK_BYTES)
            .read_to_end(buf)
            .map_err(read_error)?;
        Ok(n)
    };
    let mut block = Vec::with_capacity(BLOCK_BYTES as usize + (1 << 16));
    let mut next = Vec::with_capacity(BLOCK_BYTES as usize + (1 << 16));
    let mut at_end = fill(&mut reader, &mut block)? == 0;
    let expected_id = |j: u64| shard.id(j);
    let max_rows = summary.expected_rows;
    loop {
        let complete = memchr::memrchr(b'\n', &block).map_or(0, |p| p + 1);
        next.clear();
        next.extend_from_slice(&block[complete..]);
        let (checked, read) = rayon::join(
            || verifier.check_block(lineno + 1, &block[..complete], &expected_id, max_rows),
            || {
                if at_end {
                    Ok(0)
                } else {
                    fill(&mut reader, &mut next)
                }
            },
        );
        let lines = checked.map_err(|(l, fault)| match fault {
            LineFault::NotUtf8 => CliError::usage(anyhow!(
                "{name}: line {l} is not UTF-8; not a sweep CSV"
            )),
            LineFault::TooManyRows => CliError::usage(anyhow!(
                "{name}: has more rows than this run expects ({max_rows}); was it written with another --limit?"
            )),
            LineFault::Mismatch(m) => mismatch(l, m),
        })?;
        lineno += lines;
        good += complete as u64;
        if at_end {
            torn = !next.is_empty();
            break;
        }
        at_end = read? == 0;
        std::mem::swap(&mut block, &mut next);
    }
    verifier.recheck(eval).map_err(|(l, m)| mismatch(l, m))?;
    verifier.add_to(summary);
    Ok((verifier.rows(), good, false, torn))
}

/// Where the rows go: CSV text, or Parquet row groups.
enum Sink {
    Csv(Box<dyn Write + Send>),
    Parquet(Box<ParquetRows>),
}

/// Progress lines for batch jobs (stderr not a terminal, e.g. a Slurm log): a
/// thread that prints `sweep: K/N rows (P%), R configurations/s, elapsed E,
/// ETA T` when the run starts, then every [`PROGRESS_EVERY`] during the first
/// minute and every [`PROGRESS_EVERY_LATER`] after it (a long job's log stays
/// short).
struct Reporter {
    stop: std::sync::Arc<(std::sync::Mutex<bool>, std::sync::Condvar)>,
    handle: Option<std::thread::JoinHandle<()>>,
}

/// Interval of the progress lines during the first minute.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(5);
/// Shortest elapsed time over which a progress line states a rate.
const RATE_MIN_SECONDS: f64 = 0.5;
/// Interval of the progress lines after the first minute.
const PROGRESS_EVERY_LATER: std::time::Duration = std::time::Duration::from_secs(30);

impl Reporter {
    fn start(
        counter: std::sync::Arc<std::sync::atomic::AtomicU64>,
        done: u64,
        expected: u64,
        first: std::time::Duration,
    ) -> Reporter {
        let stop = std::sync::Arc::new((std::sync::Mutex::new(false), std::sync::Condvar::new()));
        let stop2 = stop.clone();
        let handle = std::thread::spawn(move || {
            let start = Instant::now();
            let (lock, cv) = &*stop2;
            let Ok(mut stopped) = lock.lock() else { return };
            let mut deadline = Instant::now();
            loop {
                while !*stopped {
                    let left = deadline.saturating_duration_since(Instant::now());
                    if left.is_zero() {
                        break;
                    }
                    match cv.wait_timeout(stopped, left) {
                        Ok((g, _)) => stopped = g,
                        Err(_) => return,
                    }
                }
                if *stopped {
                    return;
                }
                deadline += if start.elapsed() < std::time::Duration::from_secs(60) {
                    first
                } else {
                    PROGRESS_EVERY_LATER.max(first)
                };
                let k = counter.load(std::sync::atomic::Ordering::Relaxed);
                let secs = start.elapsed().as_secs_f64();
                let pos = (done + k).min(expected);
                // A rate over less than RATE_MIN_SECONDS (the opening line)
                // would be noise: billions of configurations per second.
                let (rate, eta) = if secs >= RATE_MIN_SECONDS && k > 0 {
                    let r = k as f64 / secs;
                    (
                        format!("{r:.1} configurations/s"),
                        format_duration((expected - pos) as f64 / r),
                    )
                } else {
                    ("rate not yet measured".to_owned(), "unknown".to_owned())
                };
                eprintln!(
                    "sweep: {pos}/{expected} rows ({:.1}%), {rate}, elapsed {}, ETA {eta}",
                    100.0 * pos as f64 / expected.max(1) as f64,
                    format_duration(secs)
                );
            }
        });
        Reporter {
            stop,
            handle: Some(handle),
        }
    }

    fn finish(mut self) {
        if let Ok(mut g) = self.stop.0.lock() {
            *g = true;
            self.stop.1.notify_all();
        }
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

/// `1h02m03s`, `4m05s`, `6s`.
fn format_duration(secs: f64) -> String {
    let s = secs.max(0.0).round() as u64;
    let (h, m, s) = (s / 3600, (s / 60) % 60, s % 60);
    if h > 0 {
        format!("{h}h{m:02}m{s:02}s")
    } else if m > 0 {
        format!("{m}m{s:02}s")
    } else {
        format!("{s}s")
    }
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
    let (format, inferred) = sweep_format(args.format, args.out.as_deref())?;
    if format == Format::Parquet && args.out.is_none() {
        return Err(CliError::usage(anyhow!(
            "--format parquet needs --out FILE.parquet (Parquet is not written to standard output)"
        )));
    }
    let shard = args.shard.unwrap_or(Shard::ALL);
    // Whether --out exists (then it is continued, never replaced); for a
    // Parquet dataset, whether it holds a part of this shard (the shards of
    // one run write into one directory).
    let exists = match (&args.out, format) {
        (Some(p), Format::Parquet) => {
            dataset::check_dataset_path(p).map_err(CliError::usage)?;
            let spath = dataset::summary_in(p, shard);
            super::outfiles::check_distinct(
                &[("its summary", &spath)],
                &[("the spec", &args.spec)],
            )?;
            check_summary_path(p, &spath)?;
            p.is_dir() && dataset::has_shard(p, shard)
        }
        (Some(p), Format::Csv) => {
            check_out_paths("sweep", p, &summary_path(p), &[("the spec", &args.spec)])?;
            fs::symlink_metadata(p).is_ok()
        }
        (None, _) => false,
    };
    if let Some(out) = &args.out {
        if exists && !args.resume {
            return Err(CliError::usage(anyhow!(
                "{} exists; pass --resume to continue it, or remove it",
                out.display()
            )));
        }
    }
    let plan = plan_of(spec, &args.spec, args.scheme_file.as_deref())?;
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(&plan, &layout, shard, args.limit);
    let expected = summary.expected_rows;
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    // Work estimate of this shard's rows (before --resume skips any: a
    // conservative bound), checked before any file is opened.
    let estimate = subdiv_lab::sweep::sweep_rows(&plan, expected, shard.count, threads);
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
    let (mut sink, done, summary_file): (Sink, u64, Option<PathBuf>) = match &args.out {
        None => {
            let mut w = BufWriter::with_capacity(1 << 20, std::io::stdout());
            layout.write_header(&mut w).map_err(CliError::failure)?;
            (Sink::Csv(Box::new(w)), 0, None)
        }
        Some(path) if format == Format::Parquet => {
            let spath = dataset::summary_in(path, shard);
            let (sink, done, recovered) = pool
                .install(|| dataset::open(path, &plan, &layout, &eval, shard, &mut summary, salt()))
                .map_err(CliError::lib)?;
            if inferred && !exists && !args.quiet {
                eprintln!(
                    "sweep: writing Parquet (from the extension of --out {})",
                    path.display()
                );
            }
            if exists && (done > 0 || recovered) && !args.quiet {
                eprintln!(
                    "sweep: resuming {} at row {done} of {expected}{}",
                    path.display(),
                    if recovered {
                        " (its short last part is written again)"
                    } else {
                        ""
                    }
                );
            }
            (Sink::Parquet(Box::new(sink)), done, Some(spath))
        }
        Some(path) if !exists => {
            // Its fingerprint first: the summary beside it (so a CSV of this
            // tool never exists without one). A new file appears whole with
            // its header (written to a temporary file of this run, then put
            // in place).
            write_summary(&summary_path(path), &summary)?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let (mut file, tmp) =
                super::outfiles::create_temp_file(&super::outfiles::parent_dir(path), &name)
                    .with_context(|| format!("creating {}", path.display()))
                    .map_err(CliError::failure)?;
            let preamble = layout
                .write_header(&mut file)
                .map_err(anyhow::Error::from)
                .and_then(|()| {
                    super::outfiles::install_new(&tmp, path).map_err(anyhow::Error::from)
                })
                .with_context(|| format!("creating {}", path.display()));
            if let Err(e) = preamble {
                let _ = fs::remove_file(&tmp);
                return Err(CliError::failure(e));
            }
            (
                Sink::Csv(Box::new(BufWriter::with_capacity(1 << 20, file))),
                0,
                Some(summary_path(path)),
            )
        }
        Some(path) => {
            let spath = summary_path(path);
            let (done, good, preamble, torn) =
                pool.install(|| scan_existing(path, &plan, &layout, &eval, shard, &mut summary))?;
            let mut file = OpenOptions::new()
                .write(true)
                .open(path)
                .with_context(|| format!("opening {}", path.display()))
                .map_err(CliError::failure)?;
            {
                file.set_len(good)
                    .and_then(|_| file.seek(SeekFrom::End(0)).map(|_| ()))
                    .with_context(|| format!("truncating {}", path.display()))
                    .map_err(CliError::failure)?;
                if (done > 0 || good > 0 || torn) && !args.quiet {
                    eprintln!(
                        "sweep: resuming {} at row {done} of {expected}{}",
                        path.display(),
                        if torn {
                            " (dropped a torn last line)"
                        } else {
                            ""
                        }
                    );
                }
            }
            if preamble {
                layout.write_header(&mut file).map_err(CliError::failure)?;
            }
            (
                Sink::Csv(Box::new(BufWriter::with_capacity(1 << 20, file))),
                done,
                Some(spath),
            )
        }
    };

    // A resumed file that is already complete: nothing is evaluated, and the
    // summary keeps the throughput of the run that wrote the rows.
    let complete = exists && done == expected;
    if let Some(spath) = &summary_file {
        if complete {
            if let Some(old) = read_summary(spath) {
                summary.throughput = old.throughput;
            }
        }
        // The summary at the start (and, for a complete file, the only one).
        write_summary(spath, &summary)?;
    }

    // A progress bar on a terminal; progress lines every few seconds otherwise
    // (batch jobs: the Slurm log shows the run is alive and how far it got).
    let terminal = std::io::stderr().is_terminal();
    let counter = std::sync::Arc::new(std::sync::atomic::AtomicU64::new(0));
    let reporter = (!terminal && !args.quiet && expected > done).then(|| {
        let every = std::time::Duration::try_from_secs_f64(args.progress_every)
            .unwrap_or(PROGRESS_EVERY)
            .max(std::time::Duration::from_millis(1));
        Reporter::start(counter.clone(), done, expected, every)
    });
    let bar = if terminal && !args.quiet && expected > done {
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
    let mut moved = |k| {
        if let Some(pb) = &bar {
            pb.set_position(done + k);
        }
    };
    let result = pool.install(|| match &mut sink {
        // Parquet: the typed path (cells straight into column buffers).
        Sink::Parquet(p) => output::run_parquet(
            &plan,
            &layout,
            &eval,
            ids,
            p,
            &mut summary,
            &mut moved,
            &counter,
        ),
        Sink::Csv(w) => output::run_counting(
            &plan,
            &layout,
            &eval,
            ids,
            w,
            &mut summary,
            &mut moved,
            &counter,
        ),
    });
    if let Some(r) = reporter {
        r.finish();
    }
    if let Some(pb) = &bar {
        pb.finish_and_clear();
    }
    let evaluated = result.map_err(CliError::failure)?;
    match sink {
        Sink::Csv(mut w) => w.flush().map_err(CliError::failure)?,
        Sink::Parquet(p) => {
            p.finish().map_err(CliError::failure)?;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    if complete {
        if !args.quiet {
            eprintln!(
                "sweep: {} is already complete: {} rows verified, nothing evaluated; summary {}",
                args.out.as_deref().unwrap_or(Path::new("-")).display(),
                summary.rows,
                summary_file.as_deref().unwrap_or(Path::new("-")).display()
            );
        }
        return Ok(());
    }
    summary.set_throughput(evaluated, seconds, threads);
    if let Some(spath) = &summary_file {
        write_summary(spath, &summary)?;
    }
    let rate = if seconds > 0.0 {
        evaluated as f64 / seconds
    } else {
        0.0
    };
    if args.quiet {
        return Ok(());
    }
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

pub(crate) fn run_merge(args: MergeArgs) -> CliResult {
    let text = fs::read_to_string(&args.spec)
        .with_context(|| format!("reading spec {}", args.spec.display()))
        .map_err(CliError::usage)?;
    let spec = SweepSpec::from_toml(&text)
        .map_err(|e| CliError::usage(anyhow!("{}: {e}", args.spec.display())))?;
    let plan = plan_of(spec, &args.spec, args.scheme_file.as_deref())?;
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    // The inputs: CSV shard files (each with its summary beside it) or
    // Parquet dataset directories (the parts and summaries of their shards).
    // The output and its summary are distinct from the spec, every shard and
    // every shard's summary; an existing output file is replaced atomically,
    // an existing summary only if it is a sweep summary.
    let datasets: Vec<bool> = args.inputs.iter().map(|p| p.is_dir()).collect();
    for p in &args.inputs {
        if !p.is_dir() && dataset::is_parquet_file(p) {
            return Err(CliError::usage(anyhow!(
                "{}: a single Parquet file: {}",
                p.display(),
                "merge takes the dataset directories NAME.parquet that sweep writes (a file of an older subdiv-lab, or a compacted dataset, is not one)"
            )));
        }
    }
    if datasets.iter().any(|&q| q != datasets[0]) {
        return Err(CliError::usage(anyhow!(
            "the shards mix CSV files and Parquet datasets; merge shards of one format"
        )));
    }
    let format = if datasets[0] {
        Format::Parquet
    } else {
        Format::Csv
    };
    // The shards: per CSV file, or every shard of each dataset (summaries
    // and parts read).
    let mut shards = Vec::new();
    let mut csv: Vec<(PathBuf, PathBuf)> = Vec::new();
    let mut summaries: Vec<PathBuf> = Vec::new();
    for p in &args.inputs {
        if format == Format::Parquet {
            for f in dataset::dataset_shards(p).map_err(CliError::lib)? {
                summaries.push(PathBuf::from(&f.summary_name));
                shards.push(f);
            }
            continue;
        }
        let sp = summary_path(p);
        summaries.push(sp.clone());
        csv.push((p.clone(), sp));
    }
    let mut inputs: Vec<(&str, &Path)> = vec![("the spec", args.spec.as_path())];
    for p in &args.inputs {
        inputs.push(("the input", p.as_path()));
    }
    for sp in &summaries {
        inputs.push(("the summary of an input", sp.as_path()));
    }
    check_out_paths("merge", &args.out, &summary_path(&args.out), &inputs)?;
    if let Some(named) = Format::of_name(&args.out).filter(|&n| n != format) {
        return Err(CliError::usage(anyhow!(
            "the shards are {} files but --out {} names a {} file; name it NAME.{} (merge writes the shards' format)",
            format.name(),
            args.out.display(),
            named.name(),
            format.extension()
        )));
    }
    // A CSV shard's summary first: it must be of this spec (it gives the
    // throughput, and is compared with the rows).
    for (p, sp) in csv {
        let name = p.display().to_string();
        let summary = fs::read_to_string(&sp)
            .with_context(|| {
                format!(
                    "reading {} (the summary `sweep` writes beside {name}; merge needs it)",
                    sp.display()
                )
            })
            .map_err(CliError::usage)?;
        let file = File::open(&p)
            .with_context(|| format!("opening {name}"))
            .map_err(CliError::usage)?;
        shards.push(ShardFile {
            name,
            summary_name: sp.display().to_string(),
            summary,
            data: ShardData::Csv(BufReader::with_capacity(1 << 20, file)),
        });
    }
    let n_shards = shards.len();
    let prepared = shards::prepare(&plan, &layout, &args.spec.display().to_string(), shards)
        .map_err(CliError::usage)?;
    // Write to a new temporary file of this run; rename only when every
    // check passed.
    let out_name = args
        .out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let (file, tmp) =
        super::outfiles::create_temp_file(&super::outfiles::parent_dir(&args.out), &out_name)
            .with_context(|| format!("creating a temporary file for {}", args.out.display()))
            .map_err(CliError::failure)?;
    let result = (|| -> CliResult<Summary> {
        if prepared.is_parquet() {
            let mut w = ParquetRows::file(
                &layout,
                &output::fingerprint_line(&plan, Shard::ALL),
                Box::new(BufWriter::with_capacity(1 << 20, file)),
            )
            .map_err(CliError::failure)?;
            let merged = prepared
                .run(&plan, &layout, &eval, &mut w, salt())
                .map_err(CliError::lib)?;
            w.finish().map_err(CliError::failure)?;
            return Ok(merged);
        }
        let mut w = BufWriter::with_capacity(1 << 20, file);
        layout.write_header(&mut w).map_err(CliError::failure)?;
        let merged = prepared
            .run(&plan, &layout, &eval, &mut w, salt())
            .map_err(CliError::lib)?;
        w.flush().map_err(CliError::failure)?;
        Ok(merged)
    })();
    let merged = match result {
        Ok(m) => m,
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            return Err(e);
        }
    };
    let n = merged.rows;
    // The merged file and its summary are put in place together (the file
    // first); a failure leaves neither new.
    let staged = serde_json::to_string_pretty(&merged)
        .map_err(CliError::failure)
        .and_then(|j| Staged::write(&[(summary_path(&args.out), (j + "\n").into_bytes())]));
    let mut staged = match staged {
        Ok(st) => st,
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            return Err(e);
        }
    };
    staged.adopt_first(tmp, args.out.clone());
    staged.commit()?;
    let total = plan.total();
    eprintln!(
        "merge: {n} rows from {} shards into {}; every configuration 0..{total} present once and verified",
        n_shards,
        args.out.display()
    );
    Ok(())
}
