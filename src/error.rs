//! Typed errors of the library core.
//!
//! Every error names the offending value (and its index where there is one),
//! so the binary can print a one-line message without extra context. The core
//! never panics on user input: invalid input is one of these variants.
//!
//! The modules above the core (spectral analysis, meshes, sweeps, the G2 cap,
//! the CCSS bound, reports) define their own error enums, which wrap [`Error`]
//! where their work calls into the core; [`Error`] wraps none of them.
//! Whether an error is about the caller's input is decided by the front ends
//! (`AnyError::is_input_error` in `any_error`).

use thiserror::Error as ThisError;

/// Errors of the library core.
#[derive(Debug, Clone, PartialEq, ThisError)]
#[non_exhaustive]
pub enum Error {
    /// A face or vertex valence below 3.
    #[error("valence must be at least 3, got {valence}")]
    ValenceTooSmall {
        /// The rejected valence.
        valence: usize,
    },
    /// A knot interval that is not finite and strictly positive.
    #[error("knot interval {name}_{index} must be finite and > 0, got {value}")]
    InvalidInterval {
        /// Which interval family (`p`, `q`, `a`, `forward`, `backward`).
        name: &'static str,
        /// Corner or edge index.
        index: usize,
        /// The rejected value, as text.
        value: String,
    },
    /// An edge ratio outside the open interval (0, 1).
    #[error("edge ratio r_{index} must lie strictly between 0 and 1, got {value}")]
    InvalidRatio {
        /// Edge index.
        index: usize,
        /// The rejected value, as text.
        value: String,
    },
    /// An edge ratio that lies strictly inside (0, 1) but rounds to 0 or 1 in
    /// `f64` (an interval quotient beyond the `f64` range, or a ratio closer
    /// to 0 or 1 than `f64` resolves).
    #[error("edge ratio r_{index} = {value} is not representable in f64: it rounds to {rounded}")]
    RatioNotRepresentable {
        /// Edge index.
        index: usize,
        /// The exact value or the expression it comes from, as text.
        value: String,
        /// What `f64` makes of it (`0` or `1`).
        rounded: &'static str,
    },
    /// Two lists that must have the same length (or a given length) do not.
    #[error("{what}: expected {expected} values, got {got}")]
    CountMismatch {
        /// What was counted.
        what: &'static str,
        /// Expected count.
        expected: usize,
        /// Actual count.
        got: usize,
    },
    /// A scheme parameter that is out of range or not representable.
    #[error("invalid parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The rejected value, as text.
        value: String,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// An operation that the scheme does not have (e.g. the face block of a
    /// vertex-centred scheme).
    #[error("{operation} is not defined for scheme {scheme}")]
    NotApplicable {
        /// The scheme's name.
        scheme: String,
        /// The operation asked for.
        operation: &'static str,
    },
    /// A refused scheme file (the key and the valence it names).
    #[error(transparent)]
    SchemeFile(#[from] SchemeFileError),
    /// A numerical routine that did not converge or met a singular system.
    #[error("numerical failure in {routine}: {reason}")]
    Numerical {
        /// Which routine failed.
        routine: &'static str,
        /// What went wrong.
        reason: String,
    },
}

/// A refused scheme file (`schemes::user`): the key, the valence where it
/// depends on one, and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct SchemeFileError {
    /// The dotted key (`vertex.self`, `topology`, `vertex` for the sum).
    pub key: String,
    /// The valence the problem shows at, if it depends on one.
    pub valence: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl std::fmt::Display for SchemeFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.valence {
            Some(n) => write!(f, "{} at valence {n}: {}", self.key, self.reason),
            None => write!(f, "{}: {}", self.key, self.reason),
        }
    }
}

/// Shorthand for results of the library core.
pub type Result<T, E = Error> = std::result::Result<T, E>;
