//! The errors of the spectral engine (re-exported as
//! [`crate::spectral::SpectralError`]): its own failures, and the core's
//! errors of the schemes and routines it calls.

/// Results of the spectral engine.
pub type Result<T, E = SpectralError> = std::result::Result<T, E>;

/// Errors of the spectral engine.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpectralError {
    /// The matrix is not square.
    #[error("eigen-analysis needs a square matrix, got {rows} x {cols}")]
    NotSquare {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// A NaN or infinite entry.
    #[error("matrix entry ({row}, {col}) is not finite")]
    NonFinite {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// The QR iteration did not converge within its bound.
    #[error("{routine} did not converge for a {size} x {size} matrix ({sweeps} sweeps)")]
    NoConvergence {
        /// Which routine.
        routine: &'static str,
        /// Matrix dimension.
        size: usize,
        /// Sweeps used (0 if unknown).
        sweeps: usize,
    },
    /// An eigenpair failed the independent residual check.
    #[error("eigenpair {index} has residual {residual:e} above the bound {bound:e}")]
    ResidualTooLarge {
        /// Index in the sorted spectrum.
        index: usize,
        /// `||S v - lambda v||`.
        residual: f64,
        /// The bound it exceeds.
        bound: f64,
    },
    /// The structured path was asked for a scheme outside the Doo-Sabin family.
    #[error("the structured path needs a Doo-Sabin-family scheme, got {scheme}")]
    NotDooSabinFamily {
        /// Scheme name.
        scheme: String,
    },
    /// A scheme's face block could not be written.
    #[error("the face block of scheme {scheme}: {reason}")]
    FaceBlock {
        /// Scheme name.
        scheme: String,
        /// The scheme's error.
        reason: String,
    },
    /// A singular value decomposition failed to converge.
    #[error("singular value decomposition did not converge ({size} x {size})")]
    SvdNoConvergence {
        /// Matrix dimension.
        size: usize,
    },
    /// An error of the scheme or of the core routines the analysis calls
    /// (the scheme's local matrix at an invalid valence, for instance).
    #[error(transparent)]
    Core(#[from] crate::error::Error),
    /// An exact computation could not be carried out.
    #[error("exact analysis: {0}")]
    Exact(String),
}
