//! A sweep run into files, and the merge of shard files: the one driver
//! behind `subdiv-lab sweep`/`merge` and the Python `sweep(..., out=...)`
//! and `merge` ([`run`], [`merge_files`]).
//!
//! * `Sink::Csv(NAME.csv)`: the rows, the header first; the summary
//!   `NAME.summary.json` beside it is written when the run starts (before
//!   the CSV, so a sweep CSV never exists without the fingerprint that ties
//!   it to its spec and shard) and again when it ends. A new file appears
//!   whole with its header; an existing one is never replaced, and a resumed
//!   run re-reads it, drops a torn last line, verifies every row against the
//!   spec ([`Verifier`]) and continues.
//! * `Sink::Parquet(NAME.parquet)`: the dataset directory of part files
//!   ([`super::dataset`]).
//! * `Sink::Stream(w)`: CSV text to any writer, without a summary file.
//!
//! The front ends parse their flags, check the work estimate and print;
//! progress comes back through [`Progress`].

use super::run::CsvBlock;
use super::shards::{self, summary_path, ShardData, ShardFile};
use super::{check_summary, is_old_csv_fingerprint, LineFault, Verifier, OLD_CSV};
#[cfg(feature = "parquet")]
use super::{dataset, parquet::ParquetRows};
use crate::outfiles::{create_temp_beside, install_new, is_special, write_atomic};
use crate::sweep::eval::SpectralEvaluator;
use crate::sweep::plan::{Plan, SchemeFactory, Shard};
use crate::sweep::spec::SweepSpec;
use crate::sweep::summary::Summary;
use crate::sweep::{Layout, SweepError};
use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicU64;
use std::sync::Arc;
use std::time::Instant;

/// Where the rows of a run go.
pub enum Sink<'a> {
    /// CSV text (the header first) to a writer; no summary file, no resume.
    Stream(&'a mut (dyn Write + Send)),
    /// The CSV file at this path, its summary beside it.
    Csv(PathBuf),
    /// The Parquet dataset directory at this path, its summary beside it.
    Parquet(PathBuf),
}

impl std::fmt::Debug for Sink<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Sink::Stream(_) => f.write_str("Stream"),
            Sink::Csv(p) => f.debug_tuple("Csv").field(p).finish(),
            Sink::Parquet(p) => f.debug_tuple("Parquet").field(p).finish(),
        }
    }
}

impl Sink<'_> {
    /// The file sink of `path` by its extension: `NAME.parquet` (any case) a
    /// Parquet dataset, any other name a CSV file.
    pub fn for_path(path: &Path) -> Sink<'static> {
        let parquet = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("parquet"));
        if parquet {
            Sink::Parquet(path.to_path_buf())
        } else {
            Sink::Csv(path.to_path_buf())
        }
    }

    /// The output path (none for a stream).
    pub fn path(&self) -> Option<&Path> {
        match self {
            Sink::Stream(_) => None,
            Sink::Csv(p) | Sink::Parquet(p) => Some(p),
        }
    }

    /// Where the summary of `shard` goes (none for a stream).
    pub fn summary_path(&self, shard: Shard) -> Option<PathBuf> {
        match self {
            Sink::Stream(_) => None,
            Sink::Csv(p) => Some(summary_path(p)),
            Sink::Parquet(p) => Some(shards::summary_in(p, shard)),
        }
    }

    /// The first check of an output path, before anything is read: a CSV
    /// must not be a special file (a device, a FIFO: it is resumable and
    /// its summary goes beside it), a dataset must be a directory or absent
    /// (and is refused in a build without the `parquet` feature).
    pub fn check_kind(&self) -> Result<(), SweepError> {
        match self {
            Sink::Stream(_) => Ok(()),
            Sink::Csv(p) => check_not_special("sweep", p),
            #[cfg(feature = "parquet")]
            Sink::Parquet(p) => dataset::check_dataset_path(p),
            #[cfg(not(feature = "parquet"))]
            Sink::Parquet(p) => Err(no_parquet(p)),
        }
    }

    /// Whether the output of `shard` exists (a CSV file; a dataset directory
    /// holding a part of the shard), after refusing a file at the summary
    /// path that is not a sweep summary, and an existing output when not
    /// `resume` (an output is never replaced).
    pub fn check_existing(&self, shard: Shard, resume: bool) -> Result<bool, SweepError> {
        let (Some(path), Some(spath)) = (self.path(), self.summary_path(shard)) else {
            return Ok(false);
        };
        check_summary_path(path, &spath)?;
        let exists = match self {
            #[cfg(feature = "parquet")]
            Sink::Parquet(p) => p.is_dir() && dataset::has_shard(p, shard),
            _ => fs::symlink_metadata(path).is_ok(),
        };
        if exists && !resume {
            return Err(SweepError::Exists(path.to_path_buf()));
        }
        Ok(exists)
    }
}

/// How a run goes: which rows, whether an existing output is continued, the
/// thread count and who hears of its progress.
pub struct RunOptions<'a> {
    /// The shard of the run (default: all configurations).
    pub shard: Shard,
    /// Only the first `limit` configurations of the shard.
    pub limit: Option<u64>,
    /// Continue an existing output (else an existing output is refused).
    pub resume: bool,
    /// Worker threads (default: all cores).
    pub threads: usize,
    /// Progress reports.
    pub progress: Option<&'a mut (dyn Progress + Send)>,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions {
            shard: Shard::ALL,
            limit: None,
            resume: false,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            progress: None,
        }
    }
}

/// The output of a run as it was opened.
#[derive(Debug, Clone)]
pub struct Opened {
    /// The output existed (a resumed run).
    pub existed: bool,
    /// Rows already there (verified).
    pub done: u64,
    /// Rows of the whole run.
    pub expected: u64,
    /// What a resumed run repaired: a torn last line dropped, a short last
    /// part to be written again.
    pub repaired: Option<&'static str>,
    /// Configurations evaluated so far in this run, counted as the workers
    /// finish them (before they are written): a progress report that moves
    /// even while a slow chunk is evaluated can read it from another thread.
    pub evaluated: Arc<AtomicU64>,
}

/// Hears of a run's progress (the front end prints it).
pub trait Progress {
    /// The output is open and verified; evaluation starts.
    fn opened(&mut self, _opened: &Opened) {}
    /// `rows` rows of the output are written (those already there included).
    fn written(&mut self, _rows: u64) {}
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunReport {
    /// The summary of every row of the output (also in its summary file);
    /// its throughput is this run's (configurations evaluated, seconds of
    /// evaluation and writing, threads) unless the output was complete.
    pub summary: Summary,
    /// The summary file (none for a stream).
    pub summary_path: Option<PathBuf>,
    /// The output was already complete: nothing evaluated (the summary
    /// keeps the throughput of the run that wrote the rows).
    pub complete: bool,
}

/// Runs the sweep of `spec` (with `scheme` in place of the spec's scheme
/// when given, [`Plan::with_scheme`]) into `sink`: [`run_plan`] of its plan.
pub fn run(
    spec: SweepSpec,
    scheme: Option<SchemeFactory>,
    sink: Sink<'_>,
    options: RunOptions<'_>,
) -> Result<RunReport, SweepError> {
    let plan = match scheme {
        Some(f) => Plan::with_scheme(spec, f)?,
        None => Plan::new(spec),
    };
    run_plan(&plan, sink, options)
}

/// Runs the configurations of `options.shard` (its first `options.limit`)
/// of `plan` into `sink`, on a pool of `options.threads`: opens the output
/// (creating it, or with `options.resume` verifying what is there and
/// continuing after it), writes the summary at the start and at the end,
/// and evaluates the rows in id order (the same bytes for any thread
/// count). A run that fails leaves the rows written so far, which a resumed
/// run continues.
pub fn run_plan(
    plan: &Plan,
    sink: Sink<'_>,
    options: RunOptions<'_>,
) -> Result<RunReport, SweepError> {
    let RunOptions {
        shard,
        limit,
        resume,
        threads,
        mut progress,
    } = options;
    sink.check_kind()?;
    let existed = sink.check_existing(shard, resume)?;
    let layout = Layout::new(plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(plan, &layout, shard, limit);
    let expected = summary.expected_rows;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| SweepError::File(e.to_string()))?;
    let spath = sink.summary_path(shard);
    let salt = shards::fresh_salt();
    let (mut out, done, repaired) = match sink {
        Sink::Stream(w) => {
            let mut w = BufWriter::with_capacity(1 << 20, w);
            layout.write_header(&mut w)?;
            (Rows::Csv(Box::new(w)), 0, None)
        }
        #[cfg(not(feature = "parquet"))]
        Sink::Parquet(path) => return Err(no_parquet(&path)),
        #[cfg(feature = "parquet")]
        Sink::Parquet(path) => {
            let (rows, done, redo) = pool.install(|| {
                dataset::open(&path, plan, &layout, &eval, shard, &mut summary, salt)
            })?;
            let repaired = redo.then_some("its short last part is written again");
            (Rows::Parquet(Box::new(rows)), done, repaired)
        }
        Sink::Csv(path) if !existed => {
            write_summary(&summary_path(&path), &summary)?;
            (Rows::Csv(Box::new(create_csv(&path, &layout)?)), 0, None)
        }
        Sink::Csv(path) => {
            let scan =
                pool.install(|| scan_csv(&path, plan, &layout, &eval, shard, &mut summary, salt))?;
            let file = (|| {
                let mut file = OpenOptions::new().write(true).open(&path)?;
                file.set_len(scan.good)?;
                file.seek(SeekFrom::End(0))?;
                Ok(file)
            })()
            .map_err(|e: std::io::Error| {
                SweepError::File(format!("truncating {}: {e}", path.display()))
            })?;
            let mut w = BufWriter::with_capacity(1 << 20, file);
            if scan.good == 0 {
                layout.write_header(&mut w)?;
            }
            let repaired = scan.torn.then_some("dropped a torn last line");
            (Rows::Csv(Box::new(w)), scan.rows, repaired)
        }
    };
    // A resumed output that is already complete: nothing is evaluated, and
    // the summary keeps the throughput of the run that wrote the rows.
    let complete = existed && done == expected;
    if let Some(spath) = &spath {
        if complete {
            if let Some(old) = read_summary(spath) {
                summary.throughput = old.throughput;
            }
        }
        write_summary(spath, &summary)?;
    }
    let evaluated_counter = Arc::new(AtomicU64::new(0));
    if let Some(p) = progress.as_deref_mut() {
        p.opened(&Opened {
            existed,
            done,
            expected,
            repaired,
            evaluated: evaluated_counter.clone(),
        });
    }
    let start = Instant::now();
    let ids = (done..expected).map(|j| shard.id(j));
    let mut moved = |k| {
        if let Some(p) = progress.as_deref_mut() {
            p.written(done + k);
        }
    };
    let evaluated = pool.install(|| match &mut out {
        #[cfg(feature = "parquet")]
        Rows::Parquet(p) => super::run_parquet(
            plan,
            &layout,
            &eval,
            ids,
            p,
            &mut summary,
            &mut moved,
            &evaluated_counter,
        ),
        Rows::Csv(w) => super::run::drive::<_, CsvBlock, _, _>(
            plan,
            &layout,
            &eval,
            ids,
            w,
            &mut summary,
            &mut moved,
            &evaluated_counter,
        ),
    })?;
    match out {
        Rows::Csv(mut w) => w.flush().map_err(|e| SweepError::File(e.to_string()))?,
        #[cfg(feature = "parquet")]
        Rows::Parquet(p) => {
            p.finish()?;
        }
    }
    if !complete {
        summary.set_throughput(evaluated, start.elapsed().as_secs_f64(), threads);
        if let Some(spath) = &spath {
            write_summary(spath, &summary)?;
        }
    }
    Ok(RunReport {
        summary,
        summary_path: spath,
        complete,
    })
}

/// Where a run writes its rows.
enum Rows<'a> {
    Csv(Box<dyn Write + Send + 'a>),
    #[cfg(feature = "parquet")]
    Parquet(Box<ParquetRows>),
}

/// The refusal of the Parquet output or input `path` in a build without
/// the `parquet` feature.
#[cfg(not(feature = "parquet"))]
fn no_parquet(path: &Path) -> SweepError {
    SweepError::Refused(format!("{}: {}", path.display(), super::detect::NO_PARQUET))
}

pub use super::detect::is_parquet_file;

/// Refuses a special file (a device such as `/dev/null`, a FIFO) as the
/// output of `command` (`sweep`, `merge`).
pub fn check_not_special(command: &'static str, out: &Path) -> Result<(), SweepError> {
    if is_special(out) {
        return Err(SweepError::NotRegular {
            command,
            path: out.to_path_buf(),
        });
    }
    Ok(())
}

/// Refuses an existing file at `spath`, the summary of the output `out`,
/// unless it is a sweep summary (this output's, or an earlier run's, e.g.
/// of `NAME.csv` beside `NAME.parquet`): the tool never overwrites a file
/// it did not write.
pub fn check_summary_path(out: &Path, spath: &Path) -> Result<(), SweepError> {
    if fs::symlink_metadata(spath).is_ok() && read_summary(spath).is_none() {
        return Err(SweepError::Refused(format!(
            "{} exists and is not a sweep summary (the summary of {}); remove it or choose another output",
            spath.display(),
            out.display()
        )));
    }
    Ok(())
}

/// The sweep summary at `path`, if it is one.
pub fn read_summary(path: &Path) -> Option<Summary> {
    let text = fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

/// The summary's JSON text as its file holds it.
fn summary_json(summary: &Summary) -> Result<String, SweepError> {
    serde_json::to_string_pretty(summary)
        .map(|j| j + "\n")
        .map_err(|e| SweepError::File(e.to_string()))
}

fn write_summary(path: &Path, summary: &Summary) -> Result<(), SweepError> {
    write_atomic(path, summary_json(summary)?.as_bytes()).map_err(SweepError::File)
}

/// A new CSV file at `path` with its header: written to a temporary file of
/// this run, then put in place only if nothing is there.
fn create_csv(path: &Path, layout: &Layout) -> Result<BufWriter<File>, SweepError> {
    let failed =
        |e: &dyn std::fmt::Display| SweepError::File(format!("creating {}: {e}", path.display()));
    let (mut file, tmp) = create_temp_beside(path).map_err(|e| failed(&e))?;
    let installed = layout
        .write_header(&mut file)
        .and_then(|()| install_new(&tmp, path).map_err(SweepError::from));
    if let Err(e) = installed {
        let _ = fs::remove_file(&tmp);
        return Err(failed(&e));
    }
    Ok(BufWriter::with_capacity(1 << 20, file))
}

/// An existing CSV as a resumed run finds it.
struct Scanned {
    /// Verified rows.
    rows: u64,
    /// Byte length of the good prefix (a torn last line excluded; 0 when
    /// the header line is torn: it is written again).
    good: u64,
    /// A torn last line was found.
    torn: bool,
}

/// Reads an existing CSV for a resumed run: checks its fingerprint (the
/// summary JSON beside it: same spec, same shard) and the header, verifies
/// every complete line in full against the spec ([`Verifier`]: ids,
/// parameters re-derived from the id, results well formed, a random sample
/// re-evaluated) and adds the rows to `summary`.
fn scan_csv(
    path: &Path,
    plan: &Plan,
    layout: &Layout,
    eval: &SpectralEvaluator,
    shard: Shard,
    summary: &mut Summary,
    salt: u64,
) -> Result<Scanned, SweepError> {
    let name = path.display().to_string();
    let file = File::open(path).map_err(|e| SweepError::File(format!("opening {name}: {e}")))?;
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let mut line = Vec::new();
    let header = layout.header();
    let mut verifier = Verifier::new(plan, layout, salt);
    let mismatch = |line, message: String| SweepError::mismatch(&name, line, message);
    let refused = |m: String| SweepError::Refused(format!("{name}: {m}"));
    let read_error = |e: std::io::Error| SweepError::File(format!("reading {name}: {e}"));
    let n = reader.read_until(b'\n', &mut line).map_err(read_error)?;
    if n == 0 {
        // A file of this tool appears whole with its header: an empty one is
        // someone else's.
        return Err(SweepError::Refused(format!(
            "{name} exists but is empty: not a sweep file of this tool (one is created whole, with its header); remove it or choose another output"
        )));
    }
    if is_old_csv_fingerprint(&line) {
        return Err(mismatch(1, format!("{OLD_CSV}; cannot resume")));
    }
    // The fingerprint: the summary JSON beside the file.
    let spath = summary_path(path);
    let Some(old) = read_summary(&spath) else {
        return Err(refused(format!(
            "its summary {} is missing or not a sweep summary; the summary ties a sweep CSV to its spec and shard; cannot resume",
            spath.display()
        )));
    };
    check_summary(plan, shard, &old).map_err(|m| {
        refused(format!(
            "{m} (by its summary {}); cannot resume",
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
        return Ok(Scanned {
            rows: 0,
            good: 0,
            torn: true,
        });
    }
    if line != header.as_bytes() {
        return Err(refused(format!(
            "the header does not match this spec's columns; cannot resume (expected {:?})",
            header.trim_end()
        )));
    }
    let mut lineno: u64 = 1;
    let mut good = n as u64;
    // The data lines, by blocks of about BLOCK_BYTES: each block's complete
    // lines are verified in parallel on the current pool while the next block
    // is read; the bytes after the last line end go to the next block, and at
    // the end of the file they are a torn last line (killed mid-write: dropped).
    const BLOCK_BYTES: u64 = 8 << 20;
    let fill = |reader: &mut BufReader<File>, buf: &mut Vec<u8>| {
        reader
            .by_ref()
            .take(BLOCK_BYTES)
            .read_to_end(buf)
            .map_err(read_error)
    };
    let mut block = Vec::with_capacity(BLOCK_BYTES as usize + (1 << 16));
    let mut next = Vec::with_capacity(BLOCK_BYTES as usize + (1 << 16));
    let mut at_end = fill(&mut reader, &mut block)? == 0;
    let max_rows = summary.expected_rows;
    let torn = loop {
        let complete = memchr::memrchr(b'\n', &block).map_or(0, |p| p + 1);
        next.clear();
        next.extend_from_slice(&block[complete..]);
        let (checked, read) = rayon::join(
            || verifier.check_block(lineno + 1, &block[..complete], shard, max_rows),
            || {
                if at_end {
                    Ok(0)
                } else {
                    fill(&mut reader, &mut next)
                }
            },
        );
        let lines = checked.map_err(|(l, fault)| match fault {
            LineFault::NotUtf8 => refused(format!("line {l} is not UTF-8; not a sweep CSV")),
            LineFault::TooManyRows => refused(format!(
                "has more rows than this run expects ({max_rows}); was it written with another limit?"
            )),
            LineFault::Mismatch(m) => mismatch(l, m),
        })?;
        lineno += lines;
        good += complete as u64;
        if at_end {
            break !next.is_empty();
        }
        at_end = read? == 0;
        std::mem::swap(&mut block, &mut next);
    };
    verifier.recheck(eval).map_err(|(l, m)| mismatch(l, m))?;
    verifier.add_to(summary);
    Ok(Scanned {
        rows: verifier.rows(),
        good,
        torn,
    })
}

/// What a merge did.
#[derive(Debug, Clone)]
pub struct MergeReport {
    /// The merged summary (also in the summary file beside the output).
    pub summary: Summary,
    /// Number of shards merged.
    pub shards: usize,
}

/// The format of the merge inputs: whether they are Parquet dataset
/// directories (else CSV shard files), refusing a single Parquet file and a
/// mix of formats.
pub fn merge_format(inputs: &[PathBuf]) -> Result<bool, SweepError> {
    let Some(first) = inputs.first() else {
        return Err(SweepError::MergeInput(
            "give at least one shard file".into(),
        ));
    };
    for p in inputs {
        #[cfg(not(feature = "parquet"))]
        if p.is_dir() || is_parquet_file(p) {
            return Err(no_parquet(p));
        }
        if !p.is_dir() && is_parquet_file(p) {
            return Err(SweepError::MergeInput(format!(
                "{}: a single Parquet file: merge takes the dataset directories NAME.parquet that sweep writes (a file of an older subdiv-lab, or a compacted dataset, is not one)",
                p.display()
            )));
        }
    }
    let parquet = first.is_dir();
    if inputs.iter().any(|p| p.is_dir() != parquet) {
        return Err(SweepError::MergeInput(
            "the shards mix CSV files and Parquet datasets; merge shards of one format".into(),
        ));
    }
    Ok(parquet)
}

/// The shards of the merge inputs ([`merge_format`]): every shard of each
/// Parquet dataset directory (its summary and parts read), or each CSV shard
/// file with the summary beside it (read) and the file opened.
pub fn merge_inputs(inputs: &[PathBuf]) -> Result<Vec<ShardFile<BufReader<File>>>, SweepError> {
    let parquet = merge_format(inputs)?;
    let mut shards = Vec::new();
    for p in inputs {
        if parquet {
            #[cfg(feature = "parquet")]
            shards.extend(dataset::dataset_shards(p)?);
            continue;
        }
        let name = p.display().to_string();
        let data = || {
            let file = File::open(p)
                .map_err(|e| SweepError::MergeInput(format!("opening {}: {e}", p.display())))?;
            Ok(ShardData::Csv(BufReader::with_capacity(1 << 20, file)))
        };
        shards.push(ShardFile::read(name, &summary_path(p), "beside", data)?);
    }
    Ok(shards)
}

/// Merges `shards` ([`merge_inputs`]) of `plan` into the single file `out`
/// (the shards' format: a CSV, or one compacted Parquet file) and its
/// summary beside it, every row verified against the spec (named
/// `spec_name` in messages). The merged file is written to a temporary file
/// and put in place with its summary only when every check passed; an
/// existing file at `out` is replaced.
pub fn merge_files(
    plan: &Plan,
    shards: Vec<ShardFile<BufReader<File>>>,
    spec_name: &str,
    out: &Path,
) -> Result<MergeReport, SweepError> {
    let layout = Layout::new(plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let n_shards = shards.len();
    let prepared = shards::prepare(plan, &layout, spec_name, shards)?;
    let salt = shards::fresh_salt();
    let (file, tmp) = create_temp_beside(out).map_err(|e| {
        SweepError::File(format!(
            "creating a temporary file for {}: {e}",
            out.display()
        ))
    })?;
    let cleanup = |e: SweepError| {
        let _ = fs::remove_file(&tmp);
        e
    };
    let w = BufWriter::with_capacity(1 << 20, file);
    let merged = (|| {
        #[cfg(feature = "parquet")]
        if prepared.is_parquet() {
            let fingerprint = super::fingerprint_line(plan, Shard::ALL);
            let mut w = ParquetRows::file(&layout, &fingerprint, Box::new(w))?;
            let merged = prepared.run(plan, &layout, &eval, &mut w, salt)?;
            w.finish()?;
            return Ok(merged);
        }
        let mut w = w;
        layout.write_header(&mut w)?;
        let merged = prepared.run(plan, &layout, &eval, &mut w, salt)?;
        w.flush().map_err(|e| SweepError::File(e.to_string()))?;
        Ok(merged)
    })()
    .map_err(cleanup)?;
    // The merged file, then its summary; a failure leaves neither new.
    let spath = summary_path(out);
    let json = summary_json(&merged).map_err(cleanup)?;
    let out_existed = fs::symlink_metadata(out).is_ok();
    fs::rename(&tmp, out).map_err(|e| {
        cleanup(SweepError::File(format!(
            "cannot write {}: {e}",
            out.display()
        )))
    })?;
    if let Err(e) = write_atomic(&spath, json.as_bytes()) {
        let also = if out_existed {
            format!(" (already replaced: {})", out.display())
        } else {
            let _ = fs::remove_file(out);
            String::new()
        };
        return Err(SweepError::File(format!("{e}{also}")));
    }
    Ok(MergeReport {
        summary: merged,
        shards: n_shards,
    })
}
