//! The errors of the bound computation.

/// Results of the bound computation.
pub type Result<T, E = CcssBoundError> = std::result::Result<T, E>;

/// Failures of the bound computation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CcssBoundError {
    /// An error of the core (a valence or a numerical routine it calls).
    #[error(transparent)]
    Core(#[from] crate::error::Error),
    /// A difference of a family fails validation.
    #[error("second-order difference #{index} ({name}) is invalid: {reason}")]
    InvalidDifference {
        /// Position in the family.
        index: usize,
        /// Its name.
        name: String,
        /// Why.
        reason: String,
    },
    /// A linear program failed (infeasible, unbounded, solver error, residual).
    #[error("linear program for {what} failed: {status}")]
    Lp {
        /// Which LP.
        what: String,
        /// Solver status.
        status: String,
    },
    /// A tolerance that is not finite and positive.
    #[error("tolerance epsilon must be finite and > 0, got {0}")]
    InvalidTolerance(f64),
    /// A tolerance below what `f64` resolves for the net's coordinates.
    #[error("tolerance epsilon = {epsilon:e} is below what f64 resolves for this control net (coordinates up to {magnitude:e}: distances below {floor:e} are rounding noise); choose epsilon >= {floor:e}")]
    ToleranceBelowResolution {
        /// The tolerance.
        epsilon: f64,
        /// The largest coordinate magnitude of the net.
        magnitude: f64,
        /// The smallest accepted tolerance.
        floor: f64,
    },
    /// A control net coordinate that is not finite.
    #[error("control point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// The point's index.
        index: usize,
    },
    /// A control point whose dimension differs from the first point's (or
    /// a net of points without coordinates).
    #[error("control point {index} has {got} coordinates, expected {expected} (as point 0)")]
    RaggedNet {
        /// The point's index.
        index: usize,
        /// Its number of coordinates.
        got: usize,
        /// The first point's (at least 1).
        expected: usize,
    },
    /// Writing output failed.
    #[error("writing output failed: {0}")]
    Output(String),
}
