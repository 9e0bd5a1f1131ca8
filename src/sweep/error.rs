//! The errors of sweep specs, enumeration, resume and merge.

use thiserror::Error as ThisError;

/// Errors of sweep specs, enumeration, resume and merge.
#[derive(Debug, Clone, PartialEq, ThisError)]
#[non_exhaustive]
pub enum SweepError {
    /// An invalid spec; `message` starts with the TOML key path.
    #[error("{message}{}", line.map(|l| format!(" (line {l})")).unwrap_or_default())]
    Spec {
        /// The TOML key path (`sampler.points_per_axis`, `space.fixed.r3`, ...).
        key: String,
        /// 1-based line in the spec, where known.
        line: Option<usize>,
        /// The full message.
        message: String,
    },
    /// A shard that is not `I/N` with `0 <= I < N`.
    #[error("shard must be I/N with 0 <= I < N, got {0:?}")]
    BadShard(String),
    /// A configuration id beyond the sweep.
    #[error("configuration id {id} is out of range (the sweep has {total} configurations)")]
    IdOutOfRange {
        /// The id.
        id: u64,
        /// Number of configurations.
        total: u64,
    },
    /// An existing CSV (resume or merge) does not match the spec.
    #[error("{source_name}: line {line}: {message}")]
    Mismatch {
        /// File or stream name.
        source_name: String,
        /// 1-based line.
        line: u64,
        /// What does not match.
        message: String,
    },
    /// Shards do not combine to the full sweep.
    #[error("merge: {0}")]
    Merge(String),
    /// A shard or its summary is not what the merge needs (the message
    /// names the file).
    #[error("{0}")]
    MergeInput(String),
    /// An existing output, or an input, is refused (not this tool's, of an
    /// older format, of another spec or shard; the message names the file).
    #[error("{0}")]
    Refused(String),
    /// The output exists and the run does not resume it: an output is never
    /// replaced (the front ends name their way to resume).
    #[error("{} exists; resume the run to continue it, or remove it", .0.display())]
    Exists(std::path::PathBuf),
    /// The output path is a special file (a device, a FIFO): a sweep
    /// writes a file and its summary beside it (the command is named).
    #[error("{} is not a regular file: {command} writes a CSV (or Parquet) file and a summary beside it", .path.display())]
    NotRegular {
        /// `sweep` or `merge`.
        command: &'static str,
        /// The output path.
        path: std::path::PathBuf,
    },
    /// A file could not be created, read or put in place (the message names
    /// the file and the step).
    #[error("{0}")]
    File(String),
    /// Writing output failed.
    #[error("write failed: {0}")]
    Io(String),
    /// An existing file (a Parquet file to resume, merge or plot) could not
    /// be read as a sweep writes it: not Parquet, torn, or of other types.
    #[error("read failed: {0}")]
    Read(String),
}

impl SweepError {
    /// A [`SweepError::Mismatch`] of line `line` of `source_name`.
    pub(crate) fn mismatch(source_name: &str, line: u64, message: impl Into<String>) -> Self {
        SweepError::Mismatch {
            source_name: source_name.to_owned(),
            line,
            message: message.into(),
        }
    }
}

impl From<std::io::Error> for SweepError {
    fn from(e: std::io::Error) -> Self {
        SweepError::Io(e.to_string())
    }
}
