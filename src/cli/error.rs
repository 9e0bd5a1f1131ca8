//! The command-line tool's errors with the exit code each maps to, and the
//! writes to the standard streams that report into them.

use subdiv_lab::AnyError;

/// An error with the exit code it maps to.
#[derive(Debug)]
pub(crate) enum CliError {
    /// The input is invalid: exit code 2.
    Usage(anyhow::Error),
    /// Valid input, failure while running: exit code 1.
    Failure(anyhow::Error),
}

impl CliError {
    pub(crate) fn usage(e: impl Into<anyhow::Error>) -> Self {
        CliError::Usage(e.into())
    }
    pub(crate) fn failure(e: impl Into<anyhow::Error>) -> Self {
        CliError::Failure(e.into())
    }
    /// A library error, mapped by its kind: invalid input (exit 2) or a
    /// failure while running (exit 1); see [`is_input_error`].
    pub(crate) fn lib(e: impl Into<AnyError>) -> Self {
        let e = e.into();
        if is_input_error(&e) {
            CliError::Usage(e.into())
        } else {
            CliError::Failure(e.into())
        }
    }
    /// A report error: an input error when the spec is invalid or the
    /// analysis behind a figure failed on its input (as [`CliError::lib`]).
    pub(crate) fn report(e: subdiv_lab::report::ReportError) -> Self {
        use subdiv_lab::report::ReportError as R;
        let input = match &e {
            R::Spec { .. } | R::Input { .. } => true,
            R::Analysis { source, .. } => is_input_error(source),
            _ => false,
        };
        if input {
            CliError::Usage(e.into())
        } else {
            CliError::Failure(e.into())
        }
    }
    /// The same error (same exit code) with `context` in front of its message.
    pub(crate) fn context(self, context: impl std::fmt::Display + Send + Sync + 'static) -> Self {
        match self {
            CliError::Usage(e) => CliError::Usage(e.context(context)),
            CliError::Failure(e) => CliError::Failure(e.context(context)),
        }
    }
    /// A failed write to standard output (exit 1).
    pub(crate) fn stdout(e: std::io::Error) -> Self {
        CliError::Failure(anyhow::anyhow!("cannot write to stdout: {e}"))
    }
}

/// Whether a library error is about the user's input (exit 2) rather than a
/// failure while running valid input (exit 1).
///
/// Input: invalid values (valence, knots, ratios, parameters, counts), an
/// operation the chosen scheme does not have (`NotApplicable`, e.g. exact
/// arithmetic or the face block where they are not defined), every mesh error
/// (the OBJ file, the knot file, a mesh the operation does not accept, a
/// result too large), spec errors of reports and sweeps. Failure: numerical
/// non-convergence, residual checks, LP failures, I/O while writing
/// ([`AnyError::is_input_error`], shared with the Python package).
pub(crate) fn is_input_error(e: &AnyError) -> bool {
    e.is_input_error()
}

pub(crate) type CliResult<T = ()> = Result<T, CliError>;

/// Writes `text` to standard output (locked, flushed); a write error (a full
/// disk, `/dev/full`, a closed descriptor) is a one-line failure, never a
/// panic. A closed pipe (`| head`) ends the process quietly through the
/// default SIGPIPE action restored in `main`.
pub(crate) fn write_stdout(text: &[u8]) -> CliResult {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text)
        .and_then(|()| out.flush())
        .map_err(CliError::stdout)
}

/// Writes one line to standard error, ignoring a failure (there is nowhere
/// left to report it; `eprintln!` would panic).
pub(crate) fn write_stderr(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}
