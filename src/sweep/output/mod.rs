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
//! * `run.rs`: the streaming driver ([`run()`], [`run_counting`]);
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
//!   [`Verifier`]).

pub(crate) mod csv;
pub mod dataset;
pub mod files;
pub(crate) mod layout;
mod merge;
pub mod parquet;
#[cfg(test)]
mod parquet_tests;
mod run;
pub mod shards;
mod verify;

pub use csv::{format_number, split_csv_line};
pub use layout::{ColumnDoc, Layout, Row};
pub use merge::{merge, MergeSource};
pub use parquet::run_parquet;
pub use run::{run, run_counting, run_discard, CHUNK, SUB_CHUNK};
pub use shards::fresh_salt;
pub use verify::{
    check_fingerprint, check_summary, fingerprint_digest, fingerprint_line, fingerprint_shard,
    is_old_csv_fingerprint, LineFault, Verifier, OLD_CSV, PIECE_BYTES, RECHECK_SAMPLE,
};
