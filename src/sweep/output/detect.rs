//! How a Parquet output is recognised without the `parquet` feature's
//! reader: its magic bytes, the check of a file's first bytes, and the one
//! line that refuses Parquet in a build without the feature.

use std::fs::{self, File};
use std::io::Read;
use std::path::Path;

/// The four bytes that start (and end) every Parquet file.
pub const MAGIC: &[u8; 4] = b"PAR1";

/// The refusal of a Parquet output or input in a build without the
/// `parquet` feature.
pub const NO_PARQUET: &str = "this subdiv-lab is built without Parquet (the cargo feature `parquet`): write NAME.csv, or rebuild with `--features parquet`";

/// Whether `path` is a regular file that starts as a Parquet file does (a
/// sweep output of the older single-file format, or a compacted dataset).
pub fn is_parquet_file(path: &Path) -> bool {
    let mut head = [0u8; 4];
    fs::metadata(path).is_ok_and(|m| m.is_file())
        && File::open(path)
            .and_then(|mut f| f.read_exact(&mut head))
            .is_ok()
        && &head == MAGIC
}
