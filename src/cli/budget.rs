//! The work limits of the command-line tool: a heavy step's estimate
//! ([`subdiv_lab::budget`]) against the documented limits, before any of the
//! work starts. Above a limit the command is refused (exit 2, one line with
//! the estimate) unless `--force`; above the machine's physical memory it is
//! refused even with `--force`, since the allocation would abort the process.

use super::{CliError, CliResult};
use anyhow::anyhow;
use subdiv_lab::budget::{format_bytes, format_seconds, Estimate, MEMORY_LIMIT_BYTES};

/// Most worker threads per available core accepted by `--threads` (more
/// only add scheduling and per-thread scratch memory).
pub(crate) const MAX_THREADS_PER_CORE: usize = 4;

/// Absolute cap on `--threads`, whatever the core count.
pub(crate) const MAX_THREADS: usize = 1024;

/// The largest `--threads` accepted on this machine:
/// `min(MAX_THREADS, MAX_THREADS_PER_CORE x available cores)`.
pub(crate) fn max_threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (MAX_THREADS_PER_CORE * cores).min(MAX_THREADS)
}

/// Checks `--threads`: between 1 and [`max_threads`].
pub(crate) fn check_threads(threads: usize) -> CliResult {
    let max = max_threads();
    if threads == 0 || threads > max {
        return Err(CliError::usage(anyhow!(
            "--threads must be between 1 and {max} ({MAX_THREADS_PER_CORE} per available core, at most {MAX_THREADS}), got {threads}"
        )));
    }
    Ok(())
}

/// Total physical memory (`MemTotal` of `/proc/meminfo`), if known.
fn physical_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses `estimate` of `command` on `subject` (e.g. "valence 100000") when
/// it exceeds [`MEMORY_LIMIT_BYTES`] or `time_limit` seconds, unless `force`;
/// refuses it always when it exceeds the physical memory.
pub(crate) fn check(
    command: &str,
    subject: &str,
    estimate: &Estimate,
    time_limit: f64,
    force: bool,
) -> CliResult {
    let bytes = format_bytes(estimate.bytes);
    let what = &estimate.what;
    if let Some(total) = physical_memory() {
        if estimate.bytes > total {
            return Err(CliError::usage(anyhow!(
                "{command}: {subject} needs ~{bytes} for {what}, more than this machine's {} of memory (refused even with --force)",
                format_bytes(total)
            )));
        }
    }
    if force {
        return Ok(());
    }
    let over_memory = estimate.bytes > MEMORY_LIMIT_BYTES;
    let over_time = estimate.seconds > time_limit;
    let time = format_seconds(estimate.seconds);
    let (mem_limit, time_limit) = (format_bytes(MEMORY_LIMIT_BYTES), format_seconds(time_limit));
    let text = match (over_memory, over_time) {
        (false, false) => return Ok(()),
        (true, false) => format!("needs ~{bytes} for {what} (limit {mem_limit})"),
        (false, true) => format!("takes ~{time} for {what} (limit {time_limit})"),
        (true, true) => {
            format!("needs ~{bytes} and ~{time} for {what} (limits {mem_limit}, {time_limit})")
        }
    };
    Err(CliError::usage(anyhow!(
        "{command}: {subject} {text}; use --force to run anyway"
    )))
}
