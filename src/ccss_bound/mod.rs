//! Distance between an extraordinary Catmull-Clark patch and its limit face:
//! the bound `beta(n)` by linear programming (math doc section 9, seed 002).
//!
//! * `patch`: the patch with its `2n + 8` control points as symbols; the
//!   sub-patches `Omega^k_m` as bicubic B-spline and Bezier nets of linear
//!   forms; the limit face `F` in Bezier form on the same sub-domains;
//! * `differences`: families of second-order differences, their validator,
//!   and the documented default family of `2n + 10`;
//! * `lp`: `min sum |x_l|` s.t. `sum x_l alpha_l = b_ij - bbar_ij` (good_lp +
//!   microlp) and its dual;
//! * [`bound`]: `c_ij`, `B(u, v)`, `D(t)`, `beta(n)`, the `beta(n)` table as CSV;
//! * `steps`: how many subdivision steps bring the limit mesh within `epsilon`.
//!
//! The bound: for `(u, v)` in `Omega^k_m`, `|S(u, v) - F(u, v)| <= B^k_m M`,
//! `M = max_l |alpha_l|`, `B^k_m = sum c_ij B^3_i B^3_j`.
//!
//! # The published facts, with the default family (tests and `ccss-bound --table-to 50`)
//!
//! * `beta(4) = 1/4` with `D(t) = (1 - t^2)/4` on `Omega^1_2` (local `t`), exactly;
//! * `beta(3) = 0.258146 > 1/4`, attained at `t = 0.4937` in `[1/4, 1/2]` (on `Omega^2_2`);
//! * `beta(n) < 1/4` for `n > 4`, attained in `[1/2, 1]` (on `Omega^1_2`),
//!   e.g. `beta(5) = 0.243129`, `beta(8) = 0.228848`, `beta(50) = 0.197303`;
//! * `beta(n)` strictly decreasing for `3 <= n <= 48`, and `beta(49) > beta(48)`:
//!   the sequence first rises exactly after the published range. Valences
//!   divisible by 4 sit slightly below the trend for large `n` (the spoke
//!   differences then have a 3-dimensional extra linear dependency).
//!
//! Which sub-patches matter (checked, not assumed): over levels `k = 1..4`
//! and all three parts, the sampled maximum of `B(u, v)` equals the diagonal
//! maximum for every `n = 3..50`; the per-level diagonal maxima decrease
//! after level 2, `c_ij = c_ji` on `Omega^k_2` to `1e-15`, and
//! `Omega^k_1`, `Omega^k_3` mirror each other to `1e-15`.

pub mod bound;
pub(crate) mod differences;
pub(crate) mod lp;
pub(crate) mod patch;
pub(crate) mod steps;
pub mod summary;

mod error;

pub use differences::{default_family, Difference, DifferenceFamily};
pub use error::{CcssBoundError, Result};
pub use patch::ExtraordinaryPatch;
pub use steps::{
    contraction, contraction_with, steps_a_priori, steps_needed, Contraction, StepsReport,
    MAX_STEPS,
};

#[cfg(test)]
mod tests;
