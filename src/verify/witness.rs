//! Witnesses against `g1` on a cell (math doc section 15, "G1 over a
//! cell"): a ratio vector of the cell at which the exact pointwise
//! classifier (section 10) proves the subdominant pair not separated, or
//! the pointwise characteristic-map certificate (section 7) proves the map
//! not regular or not injective. One such point refutes "for every
//! parameter of the cell"; a cell left `undecided` without a witness is
//! open either way.

use crate::charmap::{self, Verdict};
use crate::knots::EdgeRatios;
use crate::rng::SplitMix64;
use crate::scalar::f64_to_rational;
use crate::schemes::LocalScheme;
use crate::spectral::exact::exact_verdict;

/// What fails at a witness.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Failure {
    /// `|lambda_2| = |lambda_3|` (or `lambda_0 = 1` not simple), proven by
    /// the exact classifier in rational arithmetic.
    NotSeparated,
    /// The characteristic map has a Jacobian of both signs (the pointwise
    /// certificate).
    NotRegular,
    /// The map is regular but its boundary winds `winding` times.
    NotInjective {
        /// The certified winding number.
        winding: i64,
    },
}

impl Failure {
    /// A short name for reports.
    pub fn as_str(&self) -> &'static str {
        match self {
            Failure::NotSeparated => "not_separated",
            Failure::NotRegular => "not_regular",
            Failure::NotInjective { .. } => "not_injective",
        }
    }
}

/// A ratio vector (floats, taken as exact rationals) and what fails there.
#[derive(Clone, Debug, PartialEq)]
pub struct Witness {
    /// The ratios.
    pub ratios: Vec<f64>,
    /// The failure.
    pub failure: Failure,
}

/// The failure at one ratio vector `r`, if the pointwise tools prove one
/// (`None`: `g1` holds there or the tools do not decide).
pub fn failure_at(r: &[f64]) -> Option<Failure> {
    let q: Option<Vec<_>> = r.iter().map(|&x| f64_to_rational(x)).collect();
    let exact = LocalScheme::nurds(EdgeRatios::new(q?).ok()?);
    if exact_verdict(&exact, None).ok()?.separated == Some(false) {
        return Some(Failure::NotSeparated);
    }
    let float = LocalScheme::nurds(EdgeRatios::new(r.to_vec()).ok()?);
    match charmap::check(&float).ok()?.verdict {
        Verdict::NotRegular => Some(Failure::NotRegular),
        Verdict::NotInjective { winding } => Some(Failure::NotInjective { winding }),
        _ => None,
    }
}

/// Looks for a witness in the cell `[lo, hi]`: its centre, then `samples`
/// pseudo-random points (seeded by `seed`).
///
/// ```
/// use subdiv_lab::verify::witness::g1_witness;
/// // the uniform configuration is G1: no witness
/// assert!(g1_witness(&[0.49; 3], &[0.51; 3], 2, 1).is_none());
/// ```
pub fn g1_witness(lo: &[f64], hi: &[f64], samples: usize, seed: u64) -> Option<Witness> {
    let centre: Vec<f64> = lo.iter().zip(hi).map(|(a, b)| 0.5 * a + 0.5 * b).collect();
    let mut rng = SplitMix64::new(seed);
    std::iter::once(centre)
        .chain((0..samples).map(|_| {
            lo.iter()
                .zip(hi)
                .map(|(a, b)| rng.uniform(*a, *b).clamp(*a, *b))
                .collect()
        }))
        .find_map(|r: Vec<f64>| failure_at(&r).map(|failure| Witness { ratios: r, failure }))
}
