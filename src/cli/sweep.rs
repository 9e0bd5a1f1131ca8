//! `subdiv-lab sweep` and `subdiv-lab merge`: flags, the work estimate and
//! progress on stderr. The files (rows, summaries, resume, merge) are the
//! library's (`subdiv_lab::sweep::output::files`). `sweep --out` is a
//! resumable output, `merge --out` a single-file output replaced atomically
//! (the rules of `super::outfiles`); the extension `.csv` or `.parquet` of an
//! output must match its format.

use super::{CliError, CliResult};
use anyhow::{anyhow, Context};
use clap::Args;
use std::fs;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv_lab::sweep::output::files::{self, Opened, Progress, RunOptions, Sink};
use subdiv_lab::sweep::output::shards::summary_path;
use subdiv_lab::sweep::{Plan, Shard, SweepError, SweepSpec};

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
    #[arg(long)]
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

/// Progress lines for batch jobs (stderr not a terminal, e.g. a Slurm log): a
/// thread that prints `sweep: K/N rows (P%), R configurations/s, elapsed E,
/// ETA T` when the run starts, then every [`PROGRESS_EVERY`] during the first
/// minute and every [`PROGRESS_EVERY_LATER`] after it (a long job's log stays
/// short).
struct Reporter {
    /// Dropped to stop the thread.
    stop: std::sync::mpsc::Sender<()>,
    handle: std::thread::JoinHandle<()>,
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
        let (stop, stopped) = std::sync::mpsc::channel::<()>();
        let handle = std::thread::spawn(move || {
            let start = Instant::now();
            let mut deadline = start;
            // A timeout is the next line; a message or the sender dropped, the end.
            while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
                stopped.recv_timeout(deadline.saturating_duration_since(Instant::now()))
            {
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
        Reporter { stop, handle }
    }

    fn finish(self) {
        drop(self.stop);
        let _ = self.handle.join();
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

/// The progress of a run on stderr: a bar on a terminal, progress lines
/// every few seconds otherwise (batch jobs: the Slurm log shows the run is
/// alive and how far it got), and what a resumed run found.
struct Printer {
    quiet: bool,
    /// The path of --out, and whether Parquet was inferred from its extension.
    out: Option<(PathBuf, bool)>,
    every: std::time::Duration,
    bar: Option<indicatif::ProgressBar>,
    reporter: Option<Reporter>,
}

impl Progress for Printer {
    fn opened(&mut self, o: &Opened) {
        if self.quiet {
            return;
        }
        if let Some((path, inferred)) = &self.out {
            if *inferred && !o.existed {
                eprintln!(
                    "sweep: writing Parquet (from the extension of --out {})",
                    path.display()
                );
            }
            if o.existed && (o.done > 0 || o.repaired.is_some() || path.is_file()) {
                eprintln!(
                    "sweep: resuming {} at row {} of {}{}",
                    path.display(),
                    o.done,
                    o.expected,
                    o.repaired.map(|r| format!(" ({r})")).unwrap_or_default()
                );
            }
        }
        if o.expected <= o.done {
            return;
        }
        if !std::io::stderr().is_terminal() {
            self.reporter = Some(Reporter::start(
                o.evaluated.clone(),
                o.done,
                o.expected,
                self.every,
            ));
            return;
        }
        let pb = indicatif::ProgressBar::new(o.expected);
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
        pb.set_position(o.done);
        pb.reset_eta();
        self.bar = Some(pb);
    }

    fn written(&mut self, rows: u64) {
        if let Some(pb) = &self.bar {
            pb.set_position(rows);
        }
    }
}

impl Printer {
    fn finish(&mut self) {
        if let Some(r) = self.reporter.take() {
            r.finish();
        }
        if let Some(pb) = self.bar.take() {
            pb.finish_and_clear();
        }
    }
}

/// A library error of `sweep` or `merge` in the command line's words: an
/// existing output names `--resume`, a special file `--out`.
fn sweep_err(e: SweepError) -> CliError {
    match e {
        SweepError::Exists(p) => CliError::usage(anyhow!(
            "{} exists; pass --resume to continue it, or remove it",
            p.display()
        )),
        SweepError::NotRegular { command, path } => CliError::usage(anyhow!(
            "--out {} is not a regular file: {command} writes a CSV (or Parquet) file and a summary beside it; to discard the rows, leave out --out and redirect standard output",
            path.display()
        )),
        e => CliError::lib(e),
    }
}

/// The spec of `path`, read and parsed (errors name the file).
fn read_spec(path: &Path) -> CliResult<SweepSpec> {
    let text = fs::read_to_string(path)
        .with_context(|| format!("reading spec {}", path.display()))
        .map_err(CliError::usage)?;
    SweepSpec::from_toml(&text).map_err(|e| CliError::usage(anyhow!("{}: {e}", path.display())))
}

pub(crate) fn run_sweep(args: SweepArgs) -> CliResult {
    let spec = read_spec(&args.spec)?;
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
    let mut stdout = std::io::stdout();
    let sink = match (&args.out, format) {
        (Some(p), Format::Parquet) => Sink::Parquet(p.clone()),
        (Some(p), Format::Csv) => Sink::Csv(p.clone()),
        (None, _) => Sink::Stream(&mut stdout),
    };
    // The output checked before any work (a bad spec or flag creates no
    // file): its kind, its paths distinct from the spec, an existing output
    // only with --resume.
    sink.check_kind().map_err(sweep_err)?;
    if let (Some(out), Some(spath)) = (sink.path(), sink.summary_path(shard)) {
        let mut outputs = vec![("--out", out), ("its summary", spath.as_path())];
        if format == Format::Parquet {
            outputs.remove(0);
        }
        super::outfiles::check_distinct(&outputs, &[("the spec", &args.spec)])?;
    }
    sink.check_existing(shard, args.resume).map_err(sweep_err)?;
    let plan = plan_of(spec, &args.spec, args.scheme_file.as_deref())?;
    let threads = args.threads.unwrap_or(RunOptions::default().threads);
    // Work estimate of this shard's rows (before --resume skips any: a
    // conservative bound), checked before any file is opened.
    let expected = shard.len(plan.total()).min(args.limit.unwrap_or(u64::MAX));
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
    let mut printer = Printer {
        quiet: args.quiet,
        out: args.out.clone().map(|p| (p, inferred)),
        every: std::time::Duration::try_from_secs_f64(args.progress_every)
            .unwrap_or(PROGRESS_EVERY)
            .max(std::time::Duration::from_millis(1)),
        bar: None,
        reporter: None,
    };
    let options = RunOptions {
        shard,
        limit: args.limit,
        resume: args.resume,
        threads,
        progress: Some(&mut printer),
    };
    let result = files::run_plan(&plan, sink, options);
    printer.finish();
    let report = result.map_err(sweep_err)?;
    if args.quiet {
        return Ok(());
    }
    let summary_file = report
        .summary_path
        .as_deref()
        .map(|p| p.display().to_string());
    if report.complete {
        eprintln!(
            "sweep: {} is already complete: {} rows verified, nothing evaluated; summary {}",
            args.out.as_deref().unwrap_or(Path::new("-")).display(),
            report.summary.rows,
            summary_file.as_deref().unwrap_or("-")
        );
        return Ok(());
    }
    let t = &report.summary.throughput;
    let (evaluated, seconds, rate) = (t.evaluated, t.seconds, t.configurations_per_second);
    eprintln!(
        "sweep: {} rows ({evaluated} evaluated in {seconds:.2} s, {rate:.0} configurations/s, {threads} threads){}{}",
        report.summary.rows,
        if report.summary.errors > 0 {
            format!(", {} failed (see the error column)", report.summary.errors)
        } else {
            String::new()
        },
        summary_file
            .map(|p| format!("; summary {p}"))
            .unwrap_or_default()
    );
    Ok(())
}

pub(crate) fn run_merge(args: MergeArgs) -> CliResult {
    let spec = read_spec(&args.spec)?;
    let plan = plan_of(spec, &args.spec, args.scheme_file.as_deref())?;
    // The inputs: CSV shard files (each with its summary beside it) or
    // Parquet dataset directories (the parts and summaries of their shards).
    let parquet = files::merge_format(&args.inputs).map_err(sweep_err)?;
    // A dataset's shards are listed (and read) first, for their summaries'
    // names; CSV shards are read after the output checks, so that a refused
    // output is named before a missing input.
    let mut shards = Vec::new();
    let summaries: Vec<PathBuf> = if parquet {
        shards = files::merge_inputs(&args.inputs).map_err(sweep_err)?;
        shards.iter().map(|s| (&s.summary_name).into()).collect()
    } else {
        args.inputs.iter().map(|p| summary_path(p)).collect()
    };
    let format = if parquet {
        Format::Parquet
    } else {
        Format::Csv
    };
    // The output and its summary are distinct from the spec, every shard and
    // every shard's summary; an existing output file is replaced atomically,
    // an existing summary only if it is a sweep summary.
    let mut inputs: Vec<(&str, &Path)> = vec![("the spec", args.spec.as_path())];
    for p in &args.inputs {
        inputs.push(("the input", p.as_path()));
    }
    for s in &summaries {
        inputs.push(("the summary of an input", s.as_path()));
    }
    let spath = summary_path(&args.out);
    files::check_not_special("merge", &args.out).map_err(sweep_err)?;
    super::outfiles::check_distinct(&[("--out", &args.out), ("its summary", &spath)], &inputs)?;
    files::check_summary_path(&args.out, &spath).map_err(sweep_err)?;
    if let Some(named) = Format::of_name(&args.out).filter(|&n| n != format) {
        return Err(CliError::usage(anyhow!(
            "the shards are {} files but --out {} names a {} file; name it NAME.{} (merge writes the shards' format)",
            format.name(),
            args.out.display(),
            named.name(),
            format.extension()
        )));
    }
    if !parquet {
        shards = files::merge_inputs(&args.inputs).map_err(sweep_err)?;
    }
    let merged = files::merge_files(&plan, shards, &args.spec.display().to_string(), &args.out)
        .map_err(sweep_err)?;
    eprintln!(
        "merge: {} rows from {} shards into {}; every configuration 0..{} present once and verified",
        merged.summary.rows,
        merged.shards,
        args.out.display(),
        plan.total()
    );
    Ok(())
}
