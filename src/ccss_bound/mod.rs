//! Distance between an extraordinary Catmull-Clark patch and its limit face:
//! the bound `beta(n)` by linear programming (math doc section 9, seed 002).
//!
//! * [`patch`]: the patch with its `2n + 8` control points as symbols; the
//!   sub-patches `Omega^k_m` as bicubic B-spline and Bezier nets of linear
//!   forms; the limit face `F` in Bezier form on the same sub-domains;
//! * [`differences`]: families of second-order differences, their validator,
//!   and the documented default family of `2n + 10`;
//! * [`lp`]: `min sum |x_l|` s.t. `sum x_l alpha_l = b_ij - bbar_ij` (good_lp +
//!   microlp) and its dual;
//! * [`bound`]: `c_ij`, `B(u, v)`, `D(t)`, `beta(n)`, the `beta(n)` table as CSV;
//! * [`steps`]: how many subdivision steps bring the limit mesh within `epsilon`.
//!
//! The bound: for `(u, v)` in `Omega^k_m`, `|S(u, v) - F(u, v)| <= B^k_m M`,
//! `M = max_l |alpha_l|`, `B^k_m = sum c_ij B^3_i B^3_j`.

pub mod bound;
pub mod differences;
pub mod lp;
pub mod patch;
pub mod steps;

/// Failures specific to the bound computation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CcssBoundError {
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
    /// A control net coordinate that is not finite.
    #[error("control point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// The point's index.
        index: usize,
    },
    /// Writing output failed.
    #[error("writing output failed: {0}")]
    Output(String),
}

#[cfg(test)]
mod tests;
