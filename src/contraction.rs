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
//! 1. [`certificate`]: the weight matrix `W` derived from the knots by the
//!    theorem's own formula ([`theorem_weights`]: for NURDS `W = (I + R)/4`,
//!    the formula above; for original Doo-Sabin
//!    `W_ij = (2 + 2 cos(2 pi (i-j)/n)) / (4n)`, `W_ii = (n+4)/(4n)`
//!    **\[derived\]**, so the theorem holds for the whole family), compared
//!    with the *assembled* face block (`A = W + 1 c^T / 4`, since
//!    `P'_i = (P_i + E_{i-1} + E_i + F)/4`); checks `W >= 0`, every row sum
//!    `= 3/4` and `c^T A = c^T`, exactly for rational input.
//!    [`certify_face_block`] runs the same checks on any block.
//! 2. [`measure`]: iterate `S_n` on random control points (deterministic
//!    [`SplitMix64`]) and record `m_k = max_i |P^k_i - F|` for `k = 0..levels`,
//!    the per-step ratios `m_{k+1} / m_k` and the fitted asymptotic rate.
//! 3. The spectral bound: every non-unit eigenvalue has modulus `<= 3/4`
//!    (reported by [`crate::spectral::analyze`]).
//!
//! The bound 3/4 is attained by the row sums, but the asymptotic rate is
//! `|lambda_1|` of `A`, `< 3/4` and tending to 3/4 as `n` grows.
//!
//! Theorem 1 is a statement about the Doo-Sabin family (a central face whose
//! corners contract towards its face point), so this module is part of that
//! family's analysis: [`face_contraction`] reaches it for any [`Scheme`]
//! through the scheme's ring of patches
//! ([`RingPatches::Biquadratic`]: the face-centred family), and its
//! functions take a [`LocalScheme`] and refuse the other families with
//! [`Error::NotApplicable`](crate::Error::NotApplicable).

use crate::error::Result;
use crate::scalar::Scalar;
use crate::schemes::{LocalScheme, RingPatches, Scheme};
use nalgebra::DMatrix;
use serde::Serialize;

/// The generator of the random control points (moved to [`crate::rng`];
/// re-exported here so that existing paths keep working).
pub use crate::rng::SplitMix64;

/// Tolerance on `|row sum - 3/4|` and on negative weights for `f64` input: the
/// weights are sums of at most three terms of size `<= 1`, each rounded, so
/// their error is below `8 eps`; `1e-13` leaves room for the `c_j` (accurate to
/// `O(n eps)`, `n <= 256`). Rational input is checked exactly.
pub const CERTIFICATE_TOL: f64 = 1e-13;

/// Theorem 1 evidence of a face-centred scheme (math doc section 5): the
/// certificate, the measured contraction and the face block whose spectrum
/// bounds the rate ([`face_contraction`]).
#[derive(Clone, Debug, PartialEq)]
pub struct FaceContraction {
    /// The certificate (weights from the scheme's parameters, checked against the assembly).
    pub certificate: Certificate<f64>,
    /// The measured contraction of random control points.
    pub measured: Measured,
    /// The `n x n` central face block `A`.
    pub face_block: DMatrix<f64>,
}

/// Theorem 1 evidence of any [`Scheme`]: [`certificate`], [`measure`] and the
/// face block when the scheme is face-centred (its ring of patches is
/// [`RingPatches::Biquadratic`]: the Doo-Sabin family, whose face contracts by
/// 3/4); `None` for the others (no Theorem 1 section).
pub fn face_contraction<S: Scheme + ?Sized>(
    scheme: &S,
    options: &MeasureOptions,
) -> Option<Result<FaceContraction>> {
    let Some(RingPatches::Biquadratic(s)) = scheme.ring_patches() else {
        return None;
    };
    Some((|| {
        Ok(FaceContraction {
            certificate: certificate(s)?,
            measured: measure(s, options)?,
            face_block: s.face_block()?,
        })
    })())
}

/// Theorem 1 certificate for one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Certificate<T> {
    /// The weights `W`: row `i` holds the weights of `P_j - F` in `P'_i - F`,
    /// derived from the knots by the theorem's formula ([`theorem_weights`]),
    /// not read back from the assembled block.
    pub weights: DMatrix<T>,
    /// Row sums of `W` (exactly 3/4).
    pub row_sums: Vec<T>,
    /// Smallest weight (structural zeros included: 0 for every `n >= 4`).
    pub min_weight: T,
    /// Smallest *positive* weight (0 if there is none): how far the
    /// non-zero weights are from losing their sign.
    pub min_positive_weight: T,
    /// `max_j |(c^T A - c^T)_j|` (zero: `F` is invariant).
    pub invariance_defect: T,
    /// `max_ij |A_ij - (W_ij + c_j / 4)|`: the assembled face block `A` is the
    /// theorem's `W + 1 c^T / 4` (zero).
    pub assembly_defect: T,
    /// All weights `>= 0` (exactly for rationals, `>= -CERTIFICATE_TOL` for `f64`).
    pub nonnegative: bool,
    /// Every row sum equals 3/4 (exactly for rationals, to `CERTIFICATE_TOL` for `f64`).
    pub sums_three_quarters: bool,
    /// `c^T A = c^T` (exactly for rationals, to `CERTIFICATE_TOL` for `f64`).
    pub face_point_invariant: bool,
    /// `A = W + 1 c^T / 4` (exactly for rationals, to `CERTIFICATE_TOL` for `f64`).
    pub matches_assembly: bool,
}

impl<T: Scalar> Certificate<T> {
    /// Whether the certificate proves the 3/4 contraction: non-negative
    /// weights summing to 3/4 per row, `F` invariant, and the assembled face
    /// block equal to the one the weights describe.
    pub fn holds(&self) -> bool {
        self.nonnegative
            && self.sums_three_quarters
            && self.face_point_invariant
            && self.matches_assembly
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

/// The weights `W` of Theorem 1 from the scheme's parameters (math doc
/// section 5), independent of the matrix assembly:
///
/// * NURDS (and the Catmull-Clark variant, `r_i = 1/2`):
///   `W_ii = (2 + r_i - r_{i-1}) / 4`, `W_{i,i-1} = r_{i-1} / 4`,
///   `W_{i,i+1} = (1 - r_i) / 4`, 0 elsewhere;
/// * original Doo-Sabin **\[derived\]**: `W_ii = (n + 4) / (4n)`,
///   `W_ij = (2 + 2 cos(2 pi (i - j) / n)) / (4n)`.
///
/// Errors for the Catmull-Clark family (no face block) and for an exact
/// Doo-Sabin valence with an irrational cosine.
pub fn theorem_weights<T: Scalar>(scheme: &LocalScheme<T>) -> Result<DMatrix<T>> {
    let n = scheme.valence();
    match scheme {
        LocalScheme::DooSabin { .. } => {
            let den = T::frac(4 * n as i64, 1);
            let mut w = DMatrix::from_element(n, n, T::zero());
            for i in 0..n {
                for j in 0..n {
                    let k = (i + n - j) % n;
                    w[(i, j)] = if k == 0 {
                        T::frac(n as i64 + 4, 1) / den.clone()
                    } else {
                        let cos = crate::schemes::doo_sabin::cos_2pi::<T>(k, n).ok_or(
                            crate::error::Error::InvalidParameter {
                                name: "valence",
                                value: n.to_string(),
                                reason: "original Doo-Sabin weights are irrational for this valence; use f64",
                            },
                        )?;
                        (T::frac(2, 1) + T::frac(2, 1) * cos) / den.clone()
                    };
                }
            }
            Ok(w)
        }
        LocalScheme::Nurds(_) | LocalScheme::CcVariant { .. } => {
            let ratios = scheme.ratios();
            let r = ratios.as_slice();
            let s = ratios.complement();
            let q = T::frac(1, 4);
            let mut w = DMatrix::from_element(n, n, T::zero());
            for i in 0..n {
                let prev = (i + n - 1) % n;
                let next = (i + 1) % n;
                w[(i, i)] = q.clone() * (T::one() + s[prev].clone() + r[i].clone());
                w[(i, prev)] = w[(i, prev)].clone() + q.clone() * r[prev].clone();
                w[(i, next)] = w[(i, next)].clone() + q.clone() * s[i].clone();
            }
            Ok(w)
        }
        _ => Err(crate::error::Error::NotApplicable {
            scheme: scheme.kind().name().to_owned(),
            operation: "the face contraction of Theorem 1 (a Doo-Sabin-family notion)",
        }),
    }
}

/// Builds and checks the Theorem 1 certificate (exact for `T = Rational`):
/// the weights from the knots by the theorem's formula ([`theorem_weights`]),
/// the assembled face block and the face weights `c`, checked by
/// [`certify_face_block`].
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
/// // smallest positive weight: r_3 / 4 = 1/80 (the zeros of a quad are structural)
/// assert_eq!(cert.min_positive_weight, Rational::new(1.into(), 80.into()));
/// ```
pub fn certificate<T: Scalar>(scheme: &LocalScheme<T>) -> Result<Certificate<T>> {
    let w = theorem_weights(scheme)?;
    let a = scheme.face_block()?;
    let c = scheme.face_weights();
    certify_face_block(&a, &c, w)
}

/// Checks the Theorem 1 certificate for an arbitrary face block `a` (the
/// assembled `P'_i = sum_j a_ij P_j`), face-point weights `c` and claimed
/// weights `w` (math doc section 5):
///
/// * `w >= 0`, every row of `w` sums to 3/4;
/// * `a = w + 1 c^T / 4`, i.e. `P'_i - F = sum_j w_ij (P_j - F)` with `F = c^T P`;
/// * `c^T a = c^T` (`F` is invariant).
///
/// Exact for rationals; to [`CERTIFICATE_TOL`] for `f64`. Errors if the
/// dimensions disagree.
///
/// ```
/// use nalgebra::DMatrix;
/// use subdiv_lab::contraction::certify_face_block;
/// // n = 3, uniform knots: w = (I + R)/4 has 1/2 on the diagonal, 1/8 elsewhere
/// let w = DMatrix::from_fn(3, 3, |i, j| if i == j { 0.5 } else { 0.125 });
/// let a = w.map(|x| x + 1.0 / 12.0);
/// let c = vec![1.0 / 3.0; 3];
/// assert!(certify_face_block(&a, &c, w.clone()).unwrap().holds());
/// // a negative weight (rows still sum to 3/4) is rejected
/// let mut bad = w.clone();
/// bad[(0, 1)] = -0.125;
/// bad[(0, 0)] = 0.75;
/// assert!(!certify_face_block(&(bad.map(|x| x + 1.0 / 12.0)), &c, bad).unwrap().nonnegative);
/// ```
pub fn certify_face_block<T: Scalar>(
    a: &DMatrix<T>,
    c: &[T],
    w: DMatrix<T>,
) -> Result<Certificate<T>> {
    let n = a.nrows();
    // The first count that disagrees with the face block's `n` rows.
    let wrong = [a.ncols(), w.nrows(), w.ncols(), c.len()]
        .into_iter()
        .find(|&k| k != n);
    if let Some(got) = wrong {
        return Err(crate::error::Error::CountMismatch {
            what: "Theorem 1 certificate: face block, weights and face-point weights must be n x n, n x n and n",
            expected: n,
            got,
        });
    }
    let quarter = T::frac(1, 4);
    let row_sums: Vec<T> = w
        .row_iter()
        .map(|row| row.iter().cloned().fold(T::zero(), |s, x| s + x))
        .collect();
    let mut min_weight: Option<T> = None;
    let mut min_positive: Option<T> = None;
    for x in w.iter() {
        if min_weight.as_ref().is_none_or(|m| x < m) {
            min_weight = Some(x.clone());
        }
        if *x > T::zero() && min_positive.as_ref().is_none_or(|m| x < m) {
            min_positive = Some(x.clone());
        }
    }
    let c4: Vec<T> = c.iter().map(|x| quarter.clone() * x.clone()).collect();
    let mut assembly_defect = T::zero();
    for i in 0..n {
        for j in 0..n {
            let d = (a[(i, j)].clone() - w[(i, j)].clone() - c4[j].clone()).abs();
            if d > assembly_defect {
                assembly_defect = d;
            }
        }
    }
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
    let min_weight = min_weight.unwrap_or_else(T::zero);
    let nonnegative = min_weight >= tol_neg;
    let sums_three_quarters = row_sums
        .iter()
        .all(|s| (s.clone() - q.clone()).abs() <= tol);
    let face_point_invariant = invariance_defect <= tol;
    let matches_assembly = assembly_defect <= tol;
    Ok(Certificate {
        weights: w,
        row_sums,
        min_weight,
        min_positive_weight: min_positive.unwrap_or_else(T::zero),
        invariance_defect,
        assembly_defect,
        nonnegative,
        sums_three_quarters,
        face_point_invariant,
        matches_assembly,
    })
}

/// Most subdivision levels of the measured contraction (`analyze`'s
/// `levels`): far beyond what the rate needs (the distances reach the
/// underflow of `f64` long before), and a bound on the work.
pub const MAX_LEVELS: usize = 10_000;

/// Checks the level count of the measured contraction: 1 to [`MAX_LEVELS`]
/// (the message names the argument as `spelling` spells it).
///
/// ```
/// use subdiv_lab::budget::Spelling;
/// use subdiv_lab::contraction::check_levels;
/// assert!(check_levels(60, Spelling::Cli).is_ok());
/// assert_eq!(check_levels(0, Spelling::Cli).unwrap_err(), "--levels must be between 1 and 10000, got 0");
/// ```
pub fn check_levels(levels: usize, spelling: crate::budget::Spelling) -> Result<(), String> {
    if levels == 0 || levels > MAX_LEVELS {
        return Err(format!(
            "{} must be between 1 and {MAX_LEVELS}, got {levels}",
            spelling.arg("levels")
        ));
    }
    Ok(())
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
            scheme: scheme.kind().name().to_owned(),
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
