//! The inputs of a shard merge: shard files (CSV or Parquet, as `sweep
//! --shard I/N` writes them) with the summaries written beside them, checked
//! against the spec and against each other ([`prepare`]), then merged and
//! compared with their summaries ([`PreparedMerge::run`]). Of the file side
//! only the summary of a shard is read here ([`ShardFile::read`]); opening
//! the shards, the output's temporary file and its renaming are the
//! caller's: this module takes the shards' readers or bytes, and writes the
//! merged rows to any [`Write`].

use super::merge::{merge, MergeSource};
#[cfg(feature = "parquet")]
use super::parquet::{csv_lines, read_table, FINGERPRINT_KEY, FORMAT, FORMAT_KEY, PART_KEY};
#[cfg(feature = "parquet")]
use super::verify::{check_fingerprint, fingerprint_shard};
use super::verify::{is_old_csv_fingerprint, OLD_CSV};
use super::Layout;
use crate::sweep::eval::Evaluate;
use crate::sweep::plan::{Plan, Shard};
use crate::sweep::summary::Summary;
use crate::sweep::SweepError;
#[cfg(feature = "parquet")]
use crate::table::Table;
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};

/// Where `sweep --out NAME.csv` (or `NAME.parquet`) writes its summary:
/// `NAME.summary.json` beside it (any other name gets `.summary.json`
/// appended). A path computation only.
///
/// ```
/// use std::path::Path;
/// use subdiv_lab::sweep::output::shards::summary_path;
/// assert_eq!(summary_path(Path::new("out/a.parquet")), Path::new("out/a.summary.json"));
/// assert_eq!(summary_path(Path::new("a.txt")), Path::new("a.txt.summary.json"));
/// ```
pub fn summary_path(rows: &Path) -> PathBuf {
    let name = rows
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name
        .strip_suffix(".csv")
        .or_else(|| name.strip_suffix(".parquet"))
        .unwrap_or(&name);
    rows.with_file_name(format!("{stem}.summary.json"))
}

/// The summary of `shard` of the dataset directory `dir`, beside it:
/// `NAME.summary.json`, or `NAME.shard-I-of-N.summary.json` for a shard.
///
/// ```
/// use std::path::Path;
/// use subdiv_lab::sweep::output::shards::summary_in;
/// let d = Path::new("out/d.parquet");
/// assert_eq!(summary_in(d, "0/1".parse().unwrap()), Path::new("out/d.summary.json"));
/// assert_eq!(summary_in(d, "1/4".parse().unwrap()), Path::new("out/d.shard-1-of-4.summary.json"));
/// ```
pub fn summary_in(dir: &Path, shard: Shard) -> PathBuf {
    let all = summary_path(dir);
    if shard == Shard::ALL {
        return all;
    }
    let name = all
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name.strip_suffix(".summary.json").unwrap_or(&name);
    dir.with_file_name(format!(
        "{stem}.shard-{}-of-{}.summary.json",
        shard.index, shard.count
    ))
}

/// A salt for the re-evaluated sample of a resume or merge ([`Verifier`](super::Verifier),
/// [`merge`]): which lines are re-evaluated must not be predictable, so it
/// mixes the clock and the process id.
pub fn fresh_salt() -> u64 {
    let t = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    t ^ (u64::from(std::process::id()) << 32)
}

/// The data of one shard file.
pub enum ShardData<R> {
    /// A CSV (header, data lines), read line by line.
    Csv(R),
    /// The part files of one shard of a Parquet dataset, in part order:
    /// (file name, bytes).
    #[cfg(feature = "parquet")]
    Parquet(Vec<(String, Vec<u8>)>),
}

/// One shard of a merge.
pub struct ShardFile<R> {
    /// The shard's file name (for messages).
    pub name: String,
    /// The file name of its summary (for messages).
    pub summary_name: String,
    /// The summary's JSON text.
    pub summary: String,
    /// The rows.
    pub data: ShardData<R>,
}

impl<R> ShardFile<R> {
    /// The shard `name`: the summary at `spath` (read first; `relation`:
    /// where a sweep writes it, `beside` or `with` the shard), then `data`.
    pub fn read(
        name: String,
        spath: &Path,
        relation: &str,
        data: impl FnOnce() -> Result<ShardData<R>, SweepError>,
    ) -> Result<Self, SweepError> {
        let summary = std::fs::read_to_string(spath).map_err(|e| {
            input(format!(
                "reading {} (the summary a sweep writes {relation} {name}; merge needs it): {e}",
                spath.display()
            ))
        })?;
        Ok(ShardFile {
            name,
            summary_name: spath.display().to_string(),
            summary,
            data: data()?,
        })
    }
}

/// Data lines of one shard (CSV lines without `\n`; a Parquet shard's rows
/// as the CSV lines the sweep writes for them).
type Lines<'a> = Box<dyn Iterator<Item = Result<String, SweepError>> + 'a>;

/// Shards checked against the spec and each other, ready to merge.
pub struct PreparedMerge<'a> {
    sources: Vec<MergeSource<Lines<'a>>>,
    /// `(shard name, summary name)` per shard.
    names: Vec<(String, String)>,
    summaries: Vec<Summary>,
    /// The shards' summaries merged (for the throughput).
    merged: Summary,
    parquet: bool,
}

/// An input error of the merge (the message names the file).
fn input(message: String) -> SweepError {
    SweepError::MergeInput(message)
}

/// Checks the shards before any row is merged: each summary parses and is
/// of this spec (`spec_name` names it in messages), each shard's fingerprint
/// is of this spec and names the shard its summary names, its columns are
/// the spec's, all shards are of one shard count and one format.
pub fn prepare<'a, R: BufRead + 'a>(
    plan: &Plan,
    layout: &Layout,
    spec_name: &str,
    shards: Vec<ShardFile<R>>,
) -> Result<PreparedMerge<'a>, SweepError> {
    if shards.is_empty() {
        return Err(input("no shards to merge".into()));
    }
    let digest = plan.digest();
    let mut summaries = Vec::with_capacity(shards.len());
    for s in &shards {
        let summary: Summary = serde_json::from_str(&s.summary)
            .map_err(|e| input(format!("parsing {}: {e}", s.summary_name)))?;
        if summary.spec_digest != digest {
            return Err(input(format!(
                "{}: the summary of another spec (digest {}; {spec_name} has digest {digest})",
                s.summary_name, summary.spec_digest
            )));
        }
        summaries.push(summary);
    }
    let mut merged = summaries[0].clone();
    for s in &summaries[1..] {
        merged.merge(s)?;
    }
    let mut sources: Vec<MergeSource<Lines<'a>>> = Vec::with_capacity(shards.len());
    let mut names = Vec::with_capacity(shards.len());
    let mut formats = Vec::with_capacity(shards.len());
    for (file, summary) in shards.into_iter().zip(&summaries) {
        let (src, parquet) = match file.data {
            ShardData::Csv(r) => (csv_source(&file.name, r, summary.shard, layout)?, false),
            #[cfg(feature = "parquet")]
            ShardData::Parquet(b) => (parquet_source(&file.name, b, plan, layout)?, true),
        };
        formats.push(parquet);
        if src.shard != summary.shard {
            return Err(input(format!(
                "{}: holds shard {} but its summary {} says shard {}",
                file.name, src.shard, file.summary_name, summary.shard
            )));
        }
        if let Some(first) = sources.first() {
            if src.shard.count != first.shard.count {
                return Err(input(format!(
                    "{}: shard {} of {} shards, but {} is shard {} of {}: shards of one run have the same count",
                    file.name, src.shard, src.shard.count, first.name, first.shard, first.shard.count
                )));
            }
        }
        sources.push(src);
        names.push((file.name, file.summary_name));
    }
    if formats.iter().any(|&q| q != formats[0]) {
        return Err(input(
            "the shards mix CSV and Parquet files; merge shards of one format".into(),
        ));
    }
    Ok(PreparedMerge {
        sources,
        names,
        summaries,
        merged,
        parquet: formats[0],
    })
}

impl PreparedMerge<'_> {
    /// Whether the shards are Parquet files (else CSV).
    pub fn is_parquet(&self) -> bool {
        self.parquet
    }

    /// Merges the rows into `out` ([`merge`]: every row verified, every id
    /// `0..total` once; `out` gets the data lines only, the front end writes
    /// the fingerprint and the header of its format), then checks each
    /// shard's summary against its rows. Returns the merged summary, rebuilt
    /// from the verified rows (only the throughput comes from the shards'
    /// summaries). `salt` chooses the re-evaluated sample.
    pub fn run<W: Write, E: Evaluate + ?Sized>(
        self,
        plan: &Plan,
        layout: &Layout,
        eval: &E,
        out: &mut W,
        salt: u64,
    ) -> Result<Summary, SweepError> {
        let PreparedMerge {
            sources,
            names,
            summaries,
            merged: shard_summaries,
            ..
        } = self;
        let parts = merge(plan, layout, eval, sources, out, salt)?;
        for (((name, summary_name), s), part) in names.iter().zip(&summaries).zip(&parts) {
            if s.rows != part.rows {
                return Err(input(format!(
                    "{name}: the summary counts {} rows but the CSV has {}; resume that shard's sweep to finish it",
                    s.rows, part.rows
                )));
            }
            if s.errors != part.errors || s.classes != part.classes || s.columns != part.columns {
                return Err(input(format!(
                    "{summary_name}: the summary does not match the rows of {name} (was one of them edited?)"
                )));
            }
        }
        let mut merged = parts
            .first()
            .cloned()
            .ok_or_else(|| input("no shards to merge".into()))?;
        for p in &parts[1..] {
            merged.merge(p)?;
        }
        merged.throughput = shard_summaries.throughput;
        Ok(merged)
    }
}

/// The data lines of one shard CSV (of `shard`, the shard its summary
/// names), after its header (checked against `layout`).
fn csv_source<'a, R: BufRead + 'a>(
    name: &str,
    mut reader: R,
    shard: Shard,
    layout: &Layout,
) -> Result<MergeSource<Lines<'a>>, SweepError> {
    let mut header = String::new();
    reader
        .read_line(&mut header)
        .map_err(|e| input(format!("reading {name}: {e}")))?;
    if is_old_csv_fingerprint(header.as_bytes()) {
        return Err(SweepError::mismatch(name, 1, OLD_CSV));
    }
    if header != layout.header() {
        let m = "the header does not match the spec's columns";
        return Err(SweepError::mismatch(name, 1, m));
    }
    let n2 = name.to_owned();
    let mut lineno = 1u64;
    let mut buf = Vec::new();
    let iter = std::iter::from_fn(move || {
        buf.clear();
        match reader.read_until(b'\n', &mut buf) {
            Ok(0) => None,
            Ok(_) => {
                lineno += 1;
                if buf.last() != Some(&b'\n') {
                    return Some(Err(SweepError::mismatch(
                        &n2,
                        lineno,
                        "torn last line; resume this shard's sweep to finish it first",
                    )));
                }
                buf.pop();
                Some(
                    String::from_utf8(std::mem::take(&mut buf))
                        .map_err(|_| SweepError::mismatch(&n2, lineno, "not UTF-8")),
                )
            }
            Err(e) => Some(Err(SweepError::Io(format!("{n2}: {e}")))),
        }
    });
    Ok(MergeSource {
        name: name.to_owned(),
        shard,
        lines: Box::new(iter),
    })
}

#[cfg(feature = "parquet")]
/// A Parquet shard (its part files, in part order) as a merge source: each
/// part's format, fingerprint (which gives the shard) and index checked
/// against `plan`, its columns against `layout`, its rows as the CSV lines
/// the sweep writes for them (verified by the merge like a CSV's).
fn parquet_source<'a>(
    name: &str,
    parts: Vec<(String, Vec<u8>)>,
    plan: &Plan,
    layout: &Layout,
) -> Result<MergeSource<Lines<'a>>, SweepError> {
    let mut shard = None;
    let mut lines: Vec<String> = Vec::new();
    for (k, (part, bytes)) in parts.into_iter().enumerate() {
        let (table, s) = check_part(&part, bytes, plan, layout, None, k as u64)?;
        shard.get_or_insert(s);
        let text = csv_lines(&table, 0, table.len());
        lines.extend(text.lines().map(str::to_owned));
    }
    let iter = lines.into_iter().map(Ok);
    Ok(MergeSource {
        name: name.to_owned(),
        shard: shard.unwrap_or(Shard::ALL),
        lines: Box::new(iter),
    })
}

#[cfg(feature = "parquet")]
/// Reads part `k` of a shard of a sweep's Parquet dataset and checks its
/// format, its columns (against `layout`), its index and its fingerprint
/// against `plan` and `shard` (this run's, for resume; `None`: the shard the
/// fingerprint names, for the merge). Returns the rows and the shard. A file
/// of the older single-file format is refused by name.
pub fn check_part(
    name: &str,
    bytes: Vec<u8>,
    plan: &Plan,
    layout: &Layout,
    shard: Option<Shard>,
    k: u64,
) -> Result<(Table, Shard), SweepError> {
    let fault = |m: String| SweepError::mismatch(name, 1, m);
    let table = read_table(bytes).map_err(|e| fault(e.to_string()))?;
    match table.metadata(FORMAT_KEY) {
        Some(f) if f == FORMAT => {}
        Some(f) => {
            return Err(fault(format!(
                "a part of format {f:?}, not {FORMAT:?}: written by another version of subdiv-lab"
            )));
        }
        None => return Err(fault(OLD_PARQUET.into())),
    }
    if table.names() != layout.column_names() {
        return Err(fault("the columns do not match the spec's".into()));
    }
    let part = table.metadata(PART_KEY);
    if part != Some(k.to_string().as_str()) {
        let found = part.unwrap_or("?");
        return Err(fault(format!(
            "holds part {found} where part {k} was expected (renamed?)"
        )));
    }
    let fp = table.metadata(FINGERPRINT_KEY).unwrap_or_default();
    let shard = shard.unwrap_or_else(|| fingerprint_shard(fp).unwrap_or(Shard::ALL));
    check_fingerprint(plan, shard, fp).map_err(fault)?;
    Ok((table, shard))
}

#[cfg(feature = "parquet")]
/// The refusal of a Parquet file written by an older version.
pub const OLD_PARQUET: &str = "written by an older subdiv-lab (a single Parquet file with a commit journal; sweeps now write a dataset directory NAME.parquet/part-*.parquet): run the sweep into a new directory";
