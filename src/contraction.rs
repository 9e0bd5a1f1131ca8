//! Theorem 1: the 3/4 contraction of the central face (math doc section 5, seed 000).
//!
//! One step moves the corners of the extraordinary face as
//!
//! ```text
//! P'_i - F = 1/4 [ (1 + r_i + 1 - r_{i-1}) (P_i - F) + r_{i-1} (P_{i-1} - F) + (1 - r_i) (P_{i+1} - F) ]
//! ```
//!
//! with non-negative weights summing to exactly 3/4, and `F` invariant
//! (`c^T A = c^T`). Hence `max_i |P^{k+1}_i - F| <= 3/4 max_j |P^k_j - F|`.
//!
//! Three independent pieces of evidence are produced here:
//!
//! 1. [`certificate`]: the weight matrix `W = A - 1 c^T / 4` read off the
//!    *assembled* face block (`P'_i = (P_i + E_{i-1} + E_i + F)/4`, so removing
//!    the `F/4` term leaves the weights of the differences `P_j - F`); checks
//!    `W >= 0`, every row sum `= 3/4` and `c^T A = c^T`, exactly for rational
//!    input. For NURDS `W = (I + R)/4` (the formula above); for original
//!    Doo-Sabin `W_ij = (2 + 2 cos(2 pi (i-j)/n)) / (4n)`, `W_ii = (n+4)/(4n)`
//!    **\[derived\]**, so the theorem holds for the whole family.
//! 2. [`measure`]: iterate `S_n` on random control points (deterministic
//!    [`SplitMix64`]) and record `m_k = max_i |P^k_i - F|` for `k = 0..levels`,
//!    the per-step ratios `m_{k+1} / m_k` and the fitted asymptotic rate.
//! 3. The spectral bound: every non-unit eigenvalue has modulus `<= 3/4`
//!    (reported by [`crate::spectral::analyze`]).
//!
//! The bound 3/4 is attained by the row sums, but the asymptotic rate is
//! `|lambda_1|` of `A`, `< 3/4` and tending to 3/4 as `n` grows.

use crate::error::Result;
use crate::scalar::Scalar;
use crate::schemes::LocalScheme;
use nalgebra::DMatrix;
use serde::Serialize;

/// Tolerance on `|row sum - 3/4|` and on negative weights for `f64` input: the
/// weights are sums of at most three terms of size `<= 1`, each rounded, so
/// their error is below `8 eps`; `1e-13` leaves room for the `c_j` (accurate to
/// `O(n eps)`, `n <= 256`). Rational input is checked exactly.
pub const CERTIFICATE_TOL: f64 = 1e-13;

/// Theorem 1 certificate for one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Certificate<T> {
    /// `W = A - 1 c^T / 4`: row `i` holds the weights of `P_j - F` in `P'_i - F`.
    pub weights: DMatrix<T>,
    /// Row sums of `W` (exactly 3/4).
    pub row_sums: Vec<T>,
    /// Smallest weight.
    pub min_weight: T,
    /// `max_j |(c^T A - c^T)_j|` (zero: `F` is invariant).
    pub invariance_defect: T,
    /// All weights `>= 0` (exactly for rationals, `>= -CERTIFICATE_TOL` for `f64`).
    pub nonnegative: bool,
    /// Every row sum equals 3/4 (exactly for rationals, to `CERTIFICATE_TOL` for `f64`).
    pub sums_three_quarters: bool,
    /// `c^T A = c^T` (exactly for rationals, to `CERTIFICATE_TOL` for `f64`).
    pub face_point_invariant: bool,
}

impl<T: Scalar> Certificate<T> {
    /// Whether the certificate proves the 3/4 contraction.
    pub fn holds(&self) -> bool {
        self.nonnegative && self.sums_three_quarters && self.face_point_invariant
    }
    /// The largest `|row sum - 3/4|` as `f64`.
    pub fn max_sum_defect(&self) -> f64 {
        let q = T::frac(3, 4);
        self.row_sums
            .iter()
            .map(|s| (s.clone() - q.clone()).to_f64().abs())
            .fold(0.0, f64::max)
    }
}

/// Builds and checks the Theorem 1 certificate (exact for `T = Rational`).
///
/// ```
/// use subdiv_lab::contraction::certificate;
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::scalar::{parse_exact, Rational};
/// use subdiv_lab::schemes::LocalScheme;
/// let r: Vec<Rational> = ["1/3", "0.9", "1/2", "0.05"].iter().map(|t| parse_exact(t).unwrap()).collect();
/// let cert = certificate(&LocalScheme::nurds(EdgeRatios::new(r).unwrap())).unwrap();
/// assert!(cert.holds());
/// assert_eq!(cert.row_sums[0], Rational::new(3.into(), 4.into()));
/// ```
pub fn certificate<T: Scalar>(scheme: &LocalScheme<T>) -> Result<Certificate<T>> {
    let a = scheme.face_block()?;
    let c = scheme.face_weights();
    let n = a.nrows();
    let quarter = T::frac(1, 4);
    let w = DMatrix::from_fn(n, n, |i, j| {
        a[(i, j)].clone() - quarter.clone() * c[j].clone()
    });
    let row_sums: Vec<T> = w
        .row_iter()
        .map(|row| row.iter().cloned().fold(T::zero(), |s, x| s + x))
        .collect();
    let min_weight = w
        .iter()
        .cloned()
        .fold(None::<T>, |m, x| match m {
            Some(m) if m <= x => Some(m),
            _ => Some(x),
        })
        .unwrap_or_else(T::zero);
    let mut invariance_defect = T::zero();
    for j in 0..n {
        let mut s = T::zero() - c[j].clone();
        for i in 0..n {
            s = s + c[i].clone() * a[(i, j)].clone();
        }
        let s = s.abs();
        if s > invariance_defect {
            invariance_defect = s;
        }
    }
    let q = T::frac(3, 4);
    let (tol_neg, tol) = if T::EXACT {
        (T::zero(), T::zero())
    } else {
        (
            T::from_f64_lossless(-CERTIFICATE_TOL),
            T::from_f64_lossless(CERTIFICATE_TOL),
        )
    };
    let nonnegative = min_weight >= tol_neg;
    let sums_three_quarters = row_sums
        .iter()
        .all(|s| (s.clone() - q.clone()).abs() <= tol);
    let face_point_invariant = invariance_defect <= tol;
    Ok(Certificate {
        weights: w,
        row_sums,
        min_weight,
        invariance_defect,
        nonnegative,
        sums_three_quarters,
        face_point_invariant,
    })
}

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny, deterministic, seedable
/// generator, good enough for random test geometry (not for cryptography).
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)` (53 random bits).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// Options of the measured contraction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MeasureOptions {
    /// Number of subdivision levels (default 60).
    pub levels: usize,
    /// Seed of the random control points.
    pub seed: u64,
    /// Dimension of the control points (default 3).
    pub dim: usize,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        Self {
            levels: 60,
            seed: 0x5EED,
            dim: 3,
        }
    }
}

/// The measured contraction of the central face.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measured {
    /// `m_k = max_i |P^k_i - F|`, `k = 0..=levels`.
    pub distances: Vec<f64>,
    /// `m_{k+1} / m_k` (NaN-free: levels where `m_k = 0` stop the sequence).
    pub ratios: Vec<f64>,
    /// Largest per-step ratio (Theorem 1: `<= 3/4`).
    pub max_ratio: f64,
    /// Geometric-mean rate over the second half of the levels,
    /// `(m_K / m_{K/2})^(1 / (K - K/2))`, which tends to `|lambda_1|`.
    pub fitted_rate: f64,
}

/// Iterates `S_n` on random control points (entries uniform in `[-1, 1)`).
///
/// All `4n` points are iterated with the full matrix; `F = c^T P` is the face
/// point. Rounding adds to the iterates a component along the invariant
/// direction `1` (eigenvalue 1) of size `eps`, which would put a floor of
/// `1e-16` under `m_k`; it is removed after every step by re-centring on the
/// current face point `c^T P^k` (zero in exact arithmetic, since `F` is
/// invariant), so the rates are measured over all 60 levels.
pub fn measure(scheme: &LocalScheme<f64>, options: &MeasureOptions) -> Result<Measured> {
    if !scheme.kind().is_doo_sabin_family() {
        return Err(crate::error::Error::NotApplicable {
            scheme: scheme.kind().name(),
            operation: "the face contraction of Theorem 1 (a Doo-Sabin-family notion)",
        });
    }
    let s = scheme.matrix()?.into_matrix();
    let c = scheme.face_weights();
    let n = scheme.valence();
    let dim = options.dim.max(1);
    let mut rng = SplitMix64::new(options.seed);
    let mut x = DMatrix::from_fn(s.nrows(), dim, |_, _| rng.uniform(-1.0, 1.0));
    let recentre = |x: &mut DMatrix<f64>| {
        for d in 0..dim {
            let f: f64 = (0..n).map(|i| c[i] * x[(i, d)]).sum();
            for i in 0..x.nrows() {
                x[(i, d)] -= f;
            }
        }
    };
    recentre(&mut x);
    let dist = |x: &DMatrix<f64>| -> f64 { (0..n).map(|i| x.row(i).norm()).fold(0.0, f64::max) };
    let mut distances = vec![dist(&x)];
    for _ in 0..options.levels {
        x = &s * &x;
        recentre(&mut x);
        distances.push(dist(&x));
    }
    let mut ratios = Vec::with_capacity(options.levels);
    for k in 0..options.levels {
        if distances[k] > 0.0 && distances[k + 1].is_finite() {
            ratios.push(distances[k + 1] / distances[k]);
        } else {
            break;
        }
    }
    let max_ratio = ratios.iter().copied().fold(0.0, f64::max);
    let kk = options.levels;
    let half = kk / 2;
    let fitted_rate = if kk > half && distances[half] > 0.0 && distances[kk] > 0.0 {
        (distances[kk] / distances[half]).powf(1.0 / (kk - half) as f64)
    } else {
        0.0
    };
    Ok(Measured {
        distances,
        ratios,
        max_ratio,
        fitted_rate,
    })
}
