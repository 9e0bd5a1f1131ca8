//! CSV layout, row formatting and parsing, the streaming sweep driver and the
//! shard merge.
//!
//! The CSV has a header and one line per configuration:
//!
//! ```text
//! id,valence,<coordinates>,<results>,error
//! ```
//!
//! Coordinates are named for the largest valence of the sweep (`r0..r{N-1}`,
//! `p0..p{N-1},q0..q{N-1}`, ...); a row of a smaller valence leaves the extra
//! cells empty. Numbers are written in the shortest round-trip form, Ryu's format (reading a
//! cell back gives the same `f64` bit for bit), so a summary rebuilt from the CSV
//! equals the one accumulated while writing. Text cells never contain line
//! breaks, so every line is one row; a line without its final `\n` is a torn
//! write.
//!
//! By concern (files of this directory):
//!
//! * `layout.rs`: the columns of a sweep ([`Layout`]) and one [`Row`]; a leaf
//!   (the summary builds on it, it knows no summary);
//! * `csv.rs`: number and text cells, line splitting (no sweep types);
//! * `run.rs`: the streaming driver ([`run()`]);
//! * `merge.rs`: the shard merge ([`merge()`]);
//! * `shards.rs`: the shard files of a merge and their summaries, checked
//!   before and after it ([`shards::prepare`]);
//! * `parquet.rs`: the Parquet form of the rows (typed columns, a dataset of
//!   part files written by the `parquet` crate, reading back:
//!   [`parquet::read_table`]);
//! * `files.rs`: a run into files and the merge of shard files
//!   ([`files::run_plan`], [`files::merge_files`]);
//! * `dataset.rs`: the Parquet dataset directory on disk (part files
//!   committed by rename, resume, the shards of a merge:
//!   [`dataset::open`], [`dataset::dataset_shards`]);
//! * `verify.rs`: the verification of existing files (resume and merge,
//!   [`Verifier`]);
//! * here: a sweep's output read back as a [`Table`] ([`read_output`]).

pub(crate) mod csv;
#[cfg(feature = "parquet")]
pub mod dataset;
mod detect;
pub mod files;
pub(crate) mod layout;
mod merge;
#[cfg(feature = "parquet")]
pub mod parquet;
mod run;
pub mod shards;
mod verify;

pub use csv::{format_number, split_csv_line};
pub use detect::{MAGIC, NO_PARQUET};
pub use layout::{ColumnDoc, Layout, Row};
pub use merge::{merge, MergeSource};
#[cfg(feature = "parquet")]
pub use parquet::run_parquet;
pub use run::{run, run_discard, CHUNK, SUB_CHUNK};
pub use shards::fresh_salt;
pub use verify::{
    check_fingerprint, check_summary, fingerprint_line, fingerprint_shard, is_old_csv_fingerprint,
    LineFault, Verifier, OLD_CSV, PIECE_BYTES, RECHECK_SAMPLE,
};

use crate::table::{Table, TableError};

/// Reads a sweep's output from its bytes (the library does no I/O) as a
/// [`Table`]: as Parquet ([`parquet::read_table`]) when `name` ends in
/// `.parquet` or the bytes begin and end with the Parquet magic `PAR1` (a
/// Parquet file under another name), as CSV ([`Table::from_csv`])
/// otherwise. At least one row. The cells read from a Parquet file are
/// those read from the CSV of the same rows (a figure drawn from one equals
/// the one drawn from the other).
///
/// ```
/// use subdiv_lab::sweep::output::read_output;
/// let e = read_output("x.parquet", b"PAR1").unwrap_err().to_string();
/// assert!(e.contains("not a Parquet file, or torn"), "{e}");
/// assert_eq!(read_output("x.csv", b"id,class\n0,a\n").unwrap().len(), 1);
/// ```
pub fn read_output(name: &str, bytes: &[u8]) -> Result<Table, TableError> {
    if !is_parquet(name, bytes) {
        return Table::from_csv(bytes);
    }
    #[cfg(feature = "parquet")]
    {
        let t = parquet::read_table(bytes.to_vec()).map_err(table_error)?;
        if t.is_empty() {
            return Err(TableError::NoRows);
        }
        Ok(t)
    }
    #[cfg(not(feature = "parquet"))]
    Err(TableError::Unsupported(NO_PARQUET.into()))
}

/// An upper bound of the rows and the number of columns of the table
/// [`read_output`] would read from `bytes`, without reading it (a work
/// estimate): for CSV the line count and the fields of the first line that
/// is not a `#` comment; for Parquet the footer's counts.
pub fn output_shape(name: &str, bytes: &[u8]) -> Result<(usize, usize), TableError> {
    if is_parquet(name, bytes) {
        #[cfg(feature = "parquet")]
        {
            let (rows, columns) = parquet::shape(bytes).map_err(table_error)?;
            return Ok((usize::try_from(rows).unwrap_or(usize::MAX), columns));
        }
        #[cfg(not(feature = "parquet"))]
        return Err(TableError::Unsupported(NO_PARQUET.into()));
    }
    let lines = memchr::memchr_iter(b'\n', bytes).count() + 1;
    let header = bytes
        .split(|&b| b == b'\n')
        .find(|l| !l.starts_with(b"#"))
        .unwrap_or_default();
    let columns = memchr::memchr_iter(b',', header).count() + 1;
    Ok((lines, columns))
}

/// A reader error of [`parquet`] as a [`TableError::Parquet`].
#[cfg(feature = "parquet")]
fn table_error(e: crate::sweep::SweepError) -> TableError {
    match e {
        crate::sweep::SweepError::Io(m) | crate::sweep::SweepError::Read(m) => {
            TableError::Parquet(m)
        }
        other => TableError::Parquet(other.to_string()),
    }
}

/// Whether [`read_output`] reads `bytes` as Parquet.
fn is_parquet(name: &str, bytes: &[u8]) -> bool {
    let magic = MAGIC;
    let parquet_bytes =
        bytes.len() >= 2 * magic.len() && bytes.starts_with(magic) && bytes.ends_with(magic);
    name.ends_with(".parquet") || parquet_bytes
}
