//! The work limits of the command-line tool: a heavy step's estimate
//! ([`subdiv_lab::budget`]) against the documented limits, before any of the
//! work starts. Above a limit the command is refused (exit 2, one line with
//! the estimate) unless `--force`; above the machine's physical memory it is
//! refused even with `--force`, since the allocation would abort the process.
//! The checks and their messages are the library's
//! ([`subdiv_lab::budget::check`], [`subdiv_lab::budget::check_threads`]),
//! shared with the Python binding.

use super::{CliError, CliResult};
use anyhow::anyhow;
use subdiv_lab::budget::{Estimate, Spelling};

/// A message of a shared validator as a usage error (exit 2).
pub(crate) fn usage(message: String) -> CliError {
    CliError::usage(anyhow!(message))
}

/// Checks `--threads`: between 1 and [`subdiv_lab::budget::max_threads`].
pub(crate) fn check_threads(threads: usize) -> CliResult {
    subdiv_lab::budget::check_threads(threads, Spelling::Cli).map_err(usage)
}

/// Refuses `estimate` of `command` on `subject` (e.g. "valence 100000") when
/// it exceeds [`subdiv_lab::budget::MEMORY_LIMIT_BYTES`] or `time_limit`
/// seconds, unless `force`; refuses it always when it exceeds the physical
/// memory.
pub(crate) fn check(
    command: &str,
    subject: &str,
    estimate: &Estimate,
    time_limit: f64,
    force: bool,
) -> CliResult {
    subdiv_lab::budget::check(command, subject, estimate, time_limit, force, Spelling::Cli)
        .map_err(usage)
}
