//! The `charmap` property over a cell: the characteristic map is regular and
//! injective for *every* parameter of the cell (math doc section 15, "The characteristic map over a cell").
//!
//! The pointwise certificates of math doc section 7 ([`crate::charmap`]) are
//! carried over to a cell by enclosing the planar control net of the
//! characteristic ring for all parameters at once and running the same
//! geometric tests on boxes:
//!
//! * the adjustable Catmull-Clark scheme over an interval of `c`
//!   ([`shape`]): the Fourier-mode eigenvector in closed form and one 7 x 7
//!   interval solve, the cone test on the rule's differences, refined with
//!   the interval rule;
//! * NURDS over a box of ratios ([`ratios`]): the subdominant invariant
//!   subspace of the affine matrix `W(r) = (I + R(r))/4` by Stewart's
//!   contraction argument around the centre (a ball `||P||_F <= rho` that
//!   holds for every `r`), the lift to `S_n` by interval solves, the Bezier
//!   Jacobian coefficients as intervals.
//!
//! Injectivity: the winding number of the outer boundary, decided for every
//! admissible curve by ray crossings with certain signs ([`winding`]).
//!
//! The property is only attempted when the cell's class is certified with
//! a characteristic map (`standard`, `real_distinct` or `complex_pair`); it
//! is `refuted` when the class is certified `not_separated` (no map exists
//! anywhere in the cell), and otherwise `undecided` when a test fails: the
//! cell is then split like any open cell.

// Index loops over small fixed-size matrices read more clearly than iterator chains here.
#![allow(clippy::needless_range_loop)]

pub mod af;
pub mod ivla;
pub mod ratios;
pub mod shape;
mod tamper;
pub mod winding;

#[cfg(test)]
mod tests;

use super::decide::Status;
use super::spec::Region;
use crate::spectral::ClassName;
pub use tamper::CellTamper;

/// The status of the `charmap` property on the cell `[lo, hi]` of `region`
/// whose certified class is `class` (`None`: not certified), and, for
/// NURDS, each ratio's share of the enclosure's uncertainty (for the split
/// rule only).
///
/// ```
/// use subdiv_lab::spectral::ClassName;
/// use subdiv_lab::verify::charmap::{cell_status, CellTamper};
/// use subdiv_lab::verify::decide::Status;
/// use subdiv_lab::verify::spec::Region;
/// let region = Region::Shape { valence: 5, lo: 0.4, hi: 0.6 };
/// let (s, _) = cell_status(&region, Some(ClassName::Standard), &[0.45], &[0.46], CellTamper::None);
/// assert_eq!(s, Status::Certified);
/// ```
pub fn cell_status(
    region: &Region,
    class: Option<ClassName>,
    lo: &[f64],
    hi: &[f64],
    tamper: CellTamper,
) -> (Status, Option<Vec<f64>>) {
    match class {
        Some(ClassName::NotSeparated) => return (Status::Refuted, None),
        Some(ClassName::Standard | ClassName::RealDistinct | ClassName::ComplexPair) => {}
        _ => return (Status::Undecided, None),
    }
    let ok = |b: bool| {
        if b {
            Status::Certified
        } else {
            Status::Undecided
        }
    };
    match region {
        Region::Shape { valence, .. } => {
            if class != Some(ClassName::Standard) || lo.len() != 1 || hi.len() != 1 {
                return (Status::Undecided, None);
            }
            (ok(shape::certified(*valence, lo[0], hi[0], tamper)), None)
        }
        Region::Ratios { .. } | Region::Corners { .. } => {
            let (b, scores) = ratios::certified(lo, hi, tamper);
            (ok(b), scores)
        }
    }
}

/// The status of the `g1` property on the cell `[lo, hi]` of `region`
/// (math doc section 15, "G1 over a cell"): `certified` when
/// [`ratios::g1_certified`] proves it for every ratio vector of the cell,
/// else `undecided` (never `refuted`: a failed test proves nothing), and the
/// split scores. The `c` path has no `g1` property (the spec refuses it).
///
/// ```
/// use subdiv_lab::verify::charmap::{g1_status, CellTamper};
/// use subdiv_lab::verify::decide::Status;
/// use subdiv_lab::verify::spec::Region;
/// let region = Region::Ratios { lo: vec![0.3; 3], hi: vec![0.36; 3] };
/// let (s, _) = g1_status(&region, &[0.3; 3], &[0.31; 3], CellTamper::None);
/// assert_eq!(s, Status::Certified);
/// ```
pub fn g1_status(
    region: &Region,
    lo: &[f64],
    hi: &[f64],
    tamper: CellTamper,
) -> (Status, Option<Vec<f64>>) {
    match region {
        Region::Ratios { .. } | Region::Corners { .. } => {
            let (b, scores) = ratios::g1_certified(lo, hi, tamper);
            let s = if b {
                Status::Certified
            } else {
                Status::Undecided
            };
            (s, scores)
        }
        Region::Shape { .. } => (Status::Undecided, None),
    }
}
