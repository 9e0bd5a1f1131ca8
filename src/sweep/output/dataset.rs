//! A sweep's Parquet dataset on disk (math doc section 16.2): the directory
//! `NAME.parquet` holds only part files, `part-000017.parquet` (shard I/N:
//! `part-I-of-N-000017.parquet`), each a complete Parquet file of
//! [`PART_ROWS`] rows (the last part of a shard shorter), so every reader
//! opens the directory as one dataset (pyarrow, pandas, polars, DuckDB's
//! `NAME.parquet/*.parquet`, Spark). Each shard's summary is beside the
//! directory: `NAME.summary.json` (shard I/N: `NAME.shard-I-of-N.summary.json`).
//!
//! A part is written to a hidden temporary file beside the directory
//! (`.NAME.parquet.part-000017.parquet.tmp`, on the same file system) and
//! renamed into the directory, so a part file exists whole or not at all: a
//! run killed anywhere leaves complete parts. [`open`] checks the parts a
//! shard already has, from part 0 on, and continues after the last one. The
//! shards of one run write into one directory; [`dataset_shards`] reads them
//! back for the merge.

use super::detect::is_parquet_file;
use super::parquet::{csv_lines, parse_part_name, part_name, ParquetRows, PartFn, PART_ROWS};
use super::shards::{check_part, summary_in, ShardData, ShardFile, OLD_PARQUET};
use super::{fingerprint_line, Layout, LineFault, Verifier};
use crate::sweep::eval::Evaluate;
use crate::sweep::plan::{Plan, Shard};
use crate::sweep::summary::Summary;
use crate::sweep::SweepError;
use std::fs::{self, File};
use std::io::BufReader;
use std::path::{Path, PathBuf};

fn refused(m: String) -> SweepError {
    SweepError::Refused(m)
}

fn io(what: &str, path: &Path, e: std::io::Error) -> SweepError {
    SweepError::Io(format!("{what} {}: {e}", path.display()))
}

/// The part files of a dataset directory: `(shard, index, path)` sorted by
/// shard and index. Other files are ignored.
pub fn list_parts(dir: &Path) -> Result<Vec<(Shard, u64, PathBuf)>, SweepError> {
    let mut parts = Vec::new();
    for e in fs::read_dir(dir).map_err(|e| io("reading the directory", dir, e))? {
        let e = e.map_err(|e| io("reading the directory", dir, e))?;
        if let Some((s, k)) = e.file_name().to_str().and_then(parse_part_name) {
            parts.push((s, k, e.path()));
        }
    }
    parts.sort_by_key(|(s, k, _)| (s.count, s.index, *k));
    Ok(parts)
}

/// Refuses a dataset path that is not a directory: a file of the older
/// single-file format (by name), or any other file. A missing path is fine.
pub fn check_dataset_path(path: &Path) -> Result<(), SweepError> {
    let Ok(meta) = fs::symlink_metadata(path) else {
        return Ok(());
    };
    if meta.is_dir() {
        return Ok(());
    }
    if is_parquet_file(path) {
        return Err(refused(format!("{}: {OLD_PARQUET}", path.display())));
    }
    Err(refused(format!(
        "{} exists and is not a dataset directory (sweep writes NAME.parquet/part-*.parquet); remove it or choose another output",
        path.display()
    )))
}

/// Whether the dataset `dir` holds a part of `shard`.
pub fn has_shard(dir: &Path, shard: Shard) -> bool {
    list_parts(dir).is_ok_and(|p| p.iter().any(|(s, _, _)| *s == shard))
}

/// The commit of a part: written to a hidden temporary file beside `dir`,
/// then renamed into it (atomic: the part exists whole or not at all).
fn commit_fn(dir: PathBuf, shard: Shard) -> PartFn {
    let dir_name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Box::new(move |k, _rows, bytes| {
        let name = part_name(shard, k);
        let tmp = dir.with_file_name(format!(".{dir_name}.{name}.tmp"));
        fs::write(&tmp, &bytes)?;
        fs::rename(&tmp, dir.join(&name))
    })
}

/// Opens the dataset `dir` for `shard` of `plan`: creates the directory if
/// needed; with parts of the shard already there (a resumed run), checks
/// each from part 0 on (a complete Parquet file of this format, fingerprint
/// and index, full but the last, every row verified as a CSV's, a sample
/// re-evaluated with `eval`) and adds their rows to `summary`. Returns the
/// rows sink, the rows already present and whether a short last part (of a
/// shorter `--limit`) will be written again.
pub fn open<E: Evaluate + ?Sized>(
    dir: &Path,
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    shard: Shard,
    summary: &mut Summary,
    salt: u64,
) -> Result<(ParquetRows, u64, bool), SweepError> {
    check_dataset_path(dir)?;
    match fs::create_dir(dir) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && dir.is_dir() => {}
        Err(e) => return Err(io("creating the directory", dir, e)),
    }
    let parts: Vec<(u64, PathBuf)> = list_parts(dir)?
        .into_iter()
        .filter(|(s, _, _)| *s == shard)
        .map(|(_, k, p)| (k, p))
        .collect();
    let expected = summary.expected_rows;
    let mut verifier = Verifier::new(plan, layout, salt);
    let (mut done, mut kept, mut redo) = (0u64, 0u64, false);
    for (i, (k, path)) in parts.iter().enumerate() {
        let name = path.display().to_string();
        if *k != i as u64 {
            return Err(refused(format!(
                "{}: {} is missing but {name} exists; cannot resume",
                dir.display(),
                part_name(shard, i as u64)
            )));
        }
        let bytes = fs::read(path).map_err(|e| io("reading", path, e))?;
        let (table, _) = check_part(&name, bytes, plan, layout, Some(shard), *k)
            .map_err(|e| refused(format!("{e}; cannot resume")))?;
        let mismatch = |line, message: String| SweepError::mismatch(&name, line, message);
        let rows = table.len() as u64;
        let want = (expected - done.min(expected)).min(PART_ROWS as u64);
        if rows > want || (rows < want && i + 1 < parts.len()) {
            return Err(mismatch(
                1,
                format!("has {rows} rows where this run expects {want} (was it written with another limit?); cannot resume"),
            ));
        }
        if rows < want {
            // A short last part of a shorter --limit: written again.
            redo = true;
            break;
        }
        let lines = csv_lines(&table, 0, rows as usize);
        verifier
            .check_block(1, lines.as_bytes(), shard, expected)
            .map_err(|(l, fault)| match fault {
                LineFault::Mismatch(m) => mismatch(l, format!("row {l}: {m}")),
                LineFault::NotUtf8 => mismatch(l, "not UTF-8".into()),
                LineFault::TooManyRows => mismatch(l, "more rows than expected".into()),
            })?;
        done += rows;
        kept += 1;
    }
    verifier
        .recheck(eval)
        .map_err(|(l, m)| refused(format!("{}: row {l}: {m}", dir.display())))?;
    verifier.add_to(summary);
    let rows = ParquetRows::parts(
        layout,
        &fingerprint_line(plan, shard),
        kept,
        commit_fn(dir.to_path_buf(), shard),
    )?;
    Ok((rows, done, redo))
}

/// The shards of dataset `dir` for the merge, in shard order: each shard's
/// summary (read) and its part files (read, in part order). A directory
/// without a part is refused.
pub fn dataset_shards(dir: &Path) -> Result<Vec<ShardFile<BufReader<File>>>, SweepError> {
    let parts = list_parts(dir)?;
    if parts.is_empty() {
        return Err(refused(format!(
            "{}: no part files (part-*.parquet): not a sweep dataset",
            dir.display()
        )));
    }
    let mut shards = Vec::new();
    for group in parts.chunk_by(|a, b| a.0 == b.0) {
        let s = group[0].0;
        let name = if s == Shard::ALL {
            dir.display().to_string()
        } else {
            format!("{} (shard {s})", dir.display())
        };
        let data = || {
            let mut data = Vec::with_capacity(group.len());
            for (_, _, p) in group {
                let bytes = fs::read(p).map_err(|e| io("reading", p, e))?;
                data.push((p.display().to_string(), bytes));
            }
            Ok(ShardData::Parquet(data))
        };
        shards.push(ShardFile::read(name, &summary_in(dir, s), "with", data)?);
    }
    Ok(shards)
}
