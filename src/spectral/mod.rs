//! Eigen-analysis of local subdivision matrices (math doc sections 4-7).
//!
//! One concept per module:
//!
//! * [`eigen`]: general eigen-decomposition of any square matrix (faer), with
//!   left/right vectors, residuals and condition numbers;
//! * `kernel` (private; [`KernelWorkspace`] and [`BATCH`] are re-exported): an allocation-free small dense eigenvalue kernel (Hessenberg +
//!   Francis double-shift QR, bounded iterations) for sweeps;
//! * [`structured`]: the Doo-Sabin family fast path (face block + the known
//!   1/4, 1/8, 1/16);
//! * [`classify`](mod@classify): the subdominant classes of section 7 with condition-scaled
//!   tolerances;
//! * [`exact`]: exact certificates over the rationals (characteristic
//!   polynomial, Sturm sequences, Schur-Cohn counts).
//!
//! Entry points: [`analyze`] (everything `subdiv-lab analyze --json` prints),
//! [`classify_scheme`] (classification only, structured, allocation-free
//! after warm-up: the sweep path for the Doo-Sabin family) and
//! [`classify_matrix`] (classification only, for any square matrix, by the
//! same kernel: the sweep path for schemes outside the family).
//!
//! ```
//! use subdiv_lab::knots::EdgeRatios;
//! use subdiv_lab::schemes::LocalScheme;
//! use subdiv_lab::spectral::{analyze, AnalyzeOptions, SubdominantClass};
//! let s = LocalScheme::nurds(EdgeRatios::new(vec![0.3, 0.6, 0.5, 0.2, 0.7]).unwrap());
//! let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
//! assert_eq!(a.eigenvalues.len(), 20);
//! let c = a.contraction.as_ref().unwrap(); // Doo-Sabin family only
//! assert!(c.certificate_nonnegative);
//! assert!(c.spectral_bound <= 0.75);
//! assert!(!matches!(a.subdominant.class, SubdominantClass::Standard));
//! ```

pub(crate) mod certify;
pub mod classify;
pub(crate) mod curvature;
pub mod eigen;
pub mod exact;
pub mod json;
pub(crate) mod kernel;
pub mod pairing;
pub(crate) mod poly;
pub mod structured;
pub(crate) mod svd;

mod error;
pub use error::SpectralError;

pub use classify::{ClassName, Subdominant, SubdominantClass};
pub use eigen::{Eigen, EigenOptions};
pub use kernel::{
    KernelWorkspace, BATCH, EXCEPTIONAL_SHIFT_PERIOD, LOCKSTEP_MAX_DIM, LOCKSTEP_MIN_DIM,
    MAX_SWEEPS_PER_DIMENSION, MAX_SWEEPS_PER_EIGENVALUE,
};
pub use structured::{structured_spectrum, StructuredWorkspace};

use crate::contraction::MeasureOptions;
use crate::error::Error;
use crate::error::Result;
use crate::scalar::Rational;
use crate::scheme::{FaceContraction, Scheme, SpectralStructure};
use crate::schemes::LocalScheme;
use classify::{classify, classify_into, DoubleTest, Evidence, BACKWARD_ERROR_FACTOR};
use eigen::spectral_order;
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;
use std::cell::RefCell;

/// Which spectrum computation [`analyze`] uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpectrumPath {
    /// Full `4n x 4n` decomposition with vectors (always available).
    #[default]
    Full,
    /// Structured (face block + known eigenvalues); Doo-Sabin family only.
    Structured,
}

/// Options of [`analyze`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyzeOptions {
    /// Spectrum path for the reported eigenvalues and classification.
    pub path: SpectrumPath,
    /// Measured-contraction options (levels, seed).
    pub measure: MeasureOptions,
}

impl Default for AnalyzeOptions {
    fn default() -> Self {
        Self {
            path: SpectrumPath::Full,
            measure: MeasureOptions::default(),
        }
    }
}

/// Contraction summary (math doc section 5).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContractionSummary {
    /// Largest row sum of the certificate weights `W` (3/4; see [`crate::contraction::certificate`]).
    pub certificate_sum: f64,
    /// Largest `|row sum of W - 3/4|` (0 up to rounding; exactly 0 for rationals).
    pub certificate_sum_defect: f64,
    /// All certificate weights are non-negative.
    pub certificate_nonnegative: bool,
    /// Smallest *positive* certificate weight (the weights derived from the
    /// knots by Theorem 1's formula; structural zeros excluded).
    pub certificate_min_weight: f64,
    /// The certificate holds (non-negative, sums 3/4, `F` invariant).
    pub certificate_holds: bool,
    /// Largest non-unit eigenvalue modulus (`|lambda_1|`).
    pub spectral_bound: f64,
    /// Error radius of `spectral_bound`: the classification's radius of
    /// `lambda_1` (see [`classify`](mod@classify): `max(kappa, 1) eta`), capped
    /// by the perturbation bound of a defective double eigenvalue
    /// (`sqrt((||A||_F + 1) eta)` for the face block `A`), plus the distance
    /// between the reported `|lambda_1|` and the classified one (they come
    /// from different paths on the full path).
    pub spectral_bound_radius: f64,
    /// [`BoundCheck`] of `|lambda_1| <= 3/4` at that radius.
    pub spectral_bound_check: BoundCheck,
    /// No certain violation of `|lambda_1| <= 3/4`: `spectral_bound_check`
    /// is `holds` or `indeterminate` (a value within its error radius of 3/4
    /// is not a violation; only `violated` makes this false).
    pub spectral_bound_ok: bool,
    /// Fitted asymptotic rate of `max_i |P^k_i - F|`.
    pub measured_rate: f64,
    /// Largest per-step ratio.
    pub measured_max_ratio: f64,
    /// `max_i |P^k_i - F|` per level.
    pub measured_distances: Vec<f64>,
    /// Per-step ratios.
    pub measured_ratios: Vec<f64>,
}

/// A floating-point check of `|lambda_1| <= 3/4` (Theorem 1's spectral side).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BoundCheck {
    /// `|lambda_1| < 3/4` certainly: `3/4 - |lambda_1| > SEPARATION_FACTOR * radius`.
    Holds,
    /// `|lambda_1|` is within `SEPARATION_FACTOR` error radii of 3/4 (or the
    /// radius is not finite): the computation cannot say on which side it lies.
    Indeterminate,
    /// `|lambda_1| > 3/4` certainly: `|lambda_1| - 3/4 > SEPARATION_FACTOR * radius`.
    Violated,
}

impl BoundCheck {
    /// Decides `value <= bound` for a value with error radius `radius`, by
    /// [`classify::decide`] on `|value - bound|` (the same grey zone as the
    /// classification).
    ///
    /// ```
    /// use subdiv_lab::spectral::BoundCheck;
    /// assert_eq!(BoundCheck::of(0.7, 1e-15, 0.75), BoundCheck::Holds);
    /// assert_eq!(BoundCheck::of(0.7500000000000018, 1e-14, 0.75), BoundCheck::Indeterminate);
    /// assert_eq!(BoundCheck::of(0.76, 1e-14, 0.75), BoundCheck::Violated);
    /// assert_eq!(BoundCheck::of(0.7, f64::INFINITY, 0.75), BoundCheck::Indeterminate);
    /// ```
    pub fn of(value: f64, radius: f64, bound: f64) -> Self {
        if value.is_nan() {
            return BoundCheck::Indeterminate;
        }
        match classify::decide((value - bound).abs(), radius) {
            classify::Decision::NonZero if value < bound => BoundCheck::Holds,
            classify::Decision::NonZero => BoundCheck::Violated,
            _ => BoundCheck::Indeterminate,
        }
    }

    /// `"holds"`, `"indeterminate"` or `"violated"`.
    pub fn as_str(self) -> &'static str {
        match self {
            BoundCheck::Holds => "holds",
            BoundCheck::Indeterminate => "indeterminate",
            BoundCheck::Violated => "violated",
        }
    }
}

/// Everything `subdiv-lab analyze --json` prints.
#[derive(Clone, Debug, Serialize)]
pub struct LocalAnalysis {
    /// Scheme name ([`Scheme::name`]).
    pub scheme: String,
    /// Valence.
    pub valence: usize,
    /// Which path computed the spectrum.
    pub path: SpectrumPath,
    /// Full spectrum `[re, im]`, sorted by non-increasing modulus.
    pub eigenvalues: Vec<[f64; 2]>,
    /// Residuals `||S v - lambda v||` (full path only).
    pub residuals: Option<Vec<f64>>,
    /// Eigenvalue condition numbers (full path: all; structured: `None`).
    pub condition_numbers: Option<Vec<f64>>,
    /// Face weights `c` (empty for the Catmull-Clark family).
    pub face_weights: Vec<f64>,
    /// Left eigenvector for 1 normalised to sum 1 (full path): `c` on the P
    /// points and 0 elsewhere for the Doo-Sabin family; the limit stencil of
    /// [`crate::schemes::catmull_clark::limit::limit_stencil`] for the
    /// Catmull-Clark family.
    pub limit_weights: Option<Vec<f64>>,
    /// `max |limit_weights - expected|` with the closed-form stencil above.
    pub limit_weights_error: Option<f64>,
    /// Catmull-Clark family only: largest distance between the reported
    /// spectrum and the closed-form Fourier-block eigenvalues
    /// ([`crate::schemes::catmull_clark::fourier::spectrum`]), after sorting
    /// both; an accuracy cross-check of the full path (0 on the structured
    /// path, which reports the Fourier eigenvalues themselves).
    pub fourier_deviation: Option<f64>,
    /// Tangent stencils: left eigenvectors of `lambda_1`, `lambda_2` (real) or
    /// real and imaginary part of the left eigenvector of a complex pair
    /// (full path), scaled to unit max-norm.
    pub tangent_stencils: Option<[Vec<f64>; 2]>,
    /// Subdominant classification. For the Doo-Sabin family it is made from
    /// the structured evidence ([`classify_scheme`]: the E/C eigenvalues are
    /// known exactly, condition numbers come from the face block), because in
    /// the full `S_n` the E-block eigenvalue 1/4 collides with face
    /// eigenvalues and is generally defective there (see [`eigen`]), which
    /// makes first-order error radii of the full matrix meaningless near 1/4.
    pub subdominant: Subdominant,
    /// The classification from the full `4n x 4n` decomposition alone (full
    /// path only); an independent cross-check of `subdominant`.
    pub subdominant_full: Option<Subdominant>,
    /// Theorem 1 (Doo-Sabin family only: the face-block contraction of
    /// math doc section 5; `None` for other schemes).
    pub contraction: Option<ContractionSummary>,
    /// Exact verdicts (`--exact`).
    pub exact: Option<exact::ExactVerdict>,
    /// The floating-point class when an exact class overrode it
    /// ([`add_exact`](Self::add_exact)); `None` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub float_class: Option<&'static str>,
    /// Second order at the extraordinary point: `mu` against `lambda^2`
    /// ([`crate::curvature`], math doc section 13), on the second-order
    /// matrix ([`Scheme::second_order_matrix`]; the reported spectrum is the
    /// local matrix's).
    pub curvature: curvature::CurvatureSummary,
}

impl LocalAnalysis {
    /// Adds the exact verdicts for the exact version of the same
    /// configuration, and makes every verdict that depends on the class
    /// follow the exact class (math doc section 10, "Exact verdicts
    /// override"):
    ///
    /// * when the exact class is decided and differs from the float class
    ///   (an indeterminate float verdict included), `subdominant.class`
    ///   becomes the exact class and `subdominant.note` says so;
    /// * the curvature verdict is `not_applicable` when the exact class is
    ///   not standard, and `indeterminate` when it is standard but the float
    ///   evidence did not show it (the rate is not derived from exact data);
    /// * the characteristic map is built only where the float eigenvectors
    ///   carry the exact class ([`charmap_subdominant`](Self::charmap_subdominant));
    /// * the 3/4 spectral-bound check takes the exact answer when there is one.
    ///
    /// ```
    /// use subdiv_lab::knots::EdgeRatios;
    /// use subdiv_lab::scalar::{Rational, Scalar};
    /// use subdiv_lab::schemes::LocalScheme;
    /// use subdiv_lab::spectral::{analyze, AnalyzeOptions, SubdominantClass};
    /// // On the exactly defective line r0 = r1 = 1/2 of valence 3.
    /// let r = [0.5, 0.5, 0.5000000001];
    /// let f = LocalScheme::nurds(EdgeRatios::new(r.to_vec()).unwrap());
    /// let x = LocalScheme::nurds(EdgeRatios::new(r.iter().map(|&v| Rational::from_f64_lossless(v)).collect()).unwrap());
    /// let mut a = analyze(&f, &AnalyzeOptions::default()).unwrap();
    /// assert!(a.subdominant.class.is_indeterminate());
    /// a.add_exact(&x).unwrap();
    /// assert_eq!(a.subdominant.class, SubdominantClass::Defective);
    /// assert_eq!(a.curvature.verdict.as_str(), "not_applicable");
    /// ```
    pub fn add_exact(&mut self, scheme: &LocalScheme<Rational>) -> Result<()> {
        let x = exact::exact_verdict(scheme, Some(&self.subdominant))?;
        if let Some(bound) = x.spectral_bound_below_three_quarters {
            if let Some(c) = self.contraction.as_mut() {
                c.spectral_bound_check = if bound {
                    BoundCheck::Holds
                } else {
                    BoundCheck::Violated
                };
                c.spectral_bound_ok = bound;
            }
        }
        if let Some(class) = x.class {
            let float = self.subdominant.class.clone();
            if float.class_name() != Some(class) {
                self.float_class = Some(float.name());
                self.subdominant.class = SubdominantClass::from_name(class);
                self.subdominant.note = Some(
                    "the class is the exact one (--exact); the floating-point evidence did not show it",
                );
                let c = &mut self.curvature;
                c.evidence = curvature::CurvatureEvidence::None;
                if class == ClassName::Standard {
                    c.verdict = curvature::CurvatureVerdict::Indeterminate;
                    c.reason = format!(
                        "the exact class is standard but the floating-point evidence was {}, so mu and lambda are not certified from the exact data",
                        float.name()
                    );
                } else {
                    c.verdict = curvature::CurvatureVerdict::NotApplicable;
                    c.reason = format!(
                        "the exact class is {}: the curvature criterion needs the standard structure",
                        class.as_str()
                    );
                }
            }
        }
        self.exact = Some(x);
        Ok(())
    }

    /// The classification the characteristic map is built from: the
    /// subdominant classification, except where an exact class overrode a
    /// float class that does not carry it (module docs of
    /// [`add_exact`](Self::add_exact)): a standard, real-distinct or complex
    /// exact class that the float eigenvectors did not show gives an
    /// indeterminate map; defective and not-separated classes have no map
    /// whatever the vectors.
    pub fn charmap_subdominant(&self) -> Subdominant {
        let mut sub = self.subdominant.clone();
        if let (Some(float), Some(exact)) = (self.float_class, sub.class.class_name()) {
            if !matches!(exact, ClassName::Defective | ClassName::NotSeparated) {
                sub.class = SubdominantClass::Indeterminate {
                    between: (exact, ClassName::Defective),
                    reason: format!(
                        "the exact class is {} but the floating-point evidence was {float}, so the float eigenvectors the map is built from do not carry the exact structure",
                        exact.as_str()
                    ),
                };
            }
        }
        sub
    }
}

/// Error radius of `|lambda_1|` for the spectral-bound check of a
/// Doo-Sabin-family scheme: the first-order radius `e` of the classification,
/// capped by the perturbation bound of a defective double eigenvalue (a
/// Jordan block of size 2, where first-order radii blow up: see
/// [`classify::equality_limit`]): a backward error `eta` moves its
/// eigenvalues by about `sqrt(||N|| eta)` with the nilpotent part
/// `||N|| <= ||A - lambda I|| <= ||A||_F + 1`, so the cap is
/// `sqrt((||A||_F + 1) eta)` with `eta = BACKWARD_ERROR_FACTOR n eps ||A||_F`
/// for the face block `A`. (The classification meets no larger Jordan
/// blocks; a block of size `k` would move by `eta^(1/k)`.)
fn modulus_radius(a: &DMatrix<f64>, e: f64) -> f64 {
    let norm = a.norm();
    let eta = BACKWARD_ERROR_FACTOR * a.nrows() as f64 * f64::EPSILON * norm;
    let cap = ((norm + 1.0) * eta).sqrt();
    if e.is_nan() {
        cap
    } else {
        e.min(cap)
    }
}

/// Error radius `max(kappa, 1) * eta` (0 when `eta = 0`, i.e. the zero matrix,
/// even if `kappa` is infinite).
fn radius(kappa: f64, eta: f64) -> f64 {
    if eta == 0.0 {
        0.0
    } else if kappa.is_nan() {
        f64::INFINITY
    } else {
        kappa.max(1.0) * eta
    }
}

fn c64(z: Complex64) -> [f64; 2] {
    [z.re, z.im]
}

/// The double-eigenvalue evidence ([`DoubleTest`]): the rank test of
/// [`second_smallest_sigma`] and the structural certificate `semisimple`.
fn double_test(
    x: &DMatrix<f64>,
    lambda: f64,
    semisimple: Option<&'static str>,
) -> Result<DoubleTest, SpectralError> {
    Ok(DoubleTest {
        sigma: second_smallest_sigma(x, lambda)?,
        semisimple,
    })
}

/// Second smallest singular value of `x - lambda I` ([`svd::singular_values`]:
/// faer's SVD, the one-sided Jacobi SVD when that does not converge).
fn second_smallest_sigma(x: &DMatrix<f64>, lambda: f64) -> Result<f64, SpectralError> {
    let n = x.nrows();
    if n < 2 {
        return Ok(f64::INFINITY);
    }
    let m = DMatrix::from_fn(n, n, |i, j| x[(i, j)] - if i == j { lambda } else { 0.0 });
    // faer's SVD, with the one-sided Jacobi SVD as the fallback route
    let s = svd::singular_values(&m)?;
    // Sorted non-increasing.
    Ok(s[n - 2])
}

/// Full analysis of one configuration of any [`Scheme`] (math doc sections
/// 4-7 and 12): the spectrum (dense, or the scheme's structured path), the
/// subdominant classification (the scheme's fast path when it has one), the
/// limit and tangent stencils, Theorem 1 when the scheme provides it, and
/// the deviation from the Fourier-block spectrum for rotationally symmetric
/// schemes.
///
/// ```
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::{analyze, AnalyzeOptions, SpectrumPath};
/// let s = LocalScheme::<f64>::catmull_clark(5).unwrap();
/// let opts = AnalyzeOptions { path: SpectrumPath::Structured, ..Default::default() };
/// let a = analyze(&s, &opts).unwrap();
/// assert_eq!(a.eigenvalues.len(), 11);
/// ```
pub fn analyze<S: Scheme + ?Sized>(scheme: &S, options: &AnalyzeOptions) -> Result<LocalAnalysis> {
    let n = scheme.valence();
    let lm = scheme.local_matrix()?;
    let s = lm.matrix();
    let face_weights = scheme.face_weights();
    let expected_limit = scheme.limit_stencil().transpose()?;
    let (eigenvalues, residuals, conditions, limit, tangents, subdominant, subdominant_full);
    let curvature;
    match options.path {
        SpectrumPath::Full => {
            let e = Eigen::new(s, EigenOptions::BOTH)?;
            let dim = e.dim();
            let eta = BACKWARD_ERROR_FACTOR * dim as f64 * f64::EPSILON * e.frobenius_norm();
            let kappa = e.condition_numbers().unwrap_or(&[]).to_vec();
            let radii: Vec<f64> = kappa.iter().map(|&k| radius(k, eta)).collect();
            let full = classify(
                &Evidence {
                    values: e.values(),
                    radii: &radii,
                    eta,
                },
                &mut |lam| double_test(s, lam, pairing::scheme_pair_certificate(scheme, lam)),
            )?;
            subdominant = match scheme.fast_classification() {
                Some(fast) => fast?,
                None => full.clone(),
            };
            subdominant_full = Some(full);
            curvature = curvature::with_classification(
                scheme,
                &subdominant,
                Some((s, e.values(), &radii)),
            )?;
            eigenvalues = e.values().iter().map(|&z| c64(z)).collect::<Vec<_>>();
            residuals = e.residuals().map(<[f64]>::to_vec);
            conditions = Some(kappa);
            let left = e.left();
            limit = left.map(|u| {
                let col = u.column(0);
                let sum: Complex64 = col.iter().sum();
                let w: Vec<f64> = col.iter().map(|z| (z / sum).re).collect();
                let err = w
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| {
                        let e = expected_limit
                            .as_ref()
                            .map(|l| l.get(i).copied().unwrap_or(0.0));
                        e.map_or(0.0, |e| (x - e).abs())
                    })
                    .fold(0.0, f64::max);
                (w, expected_limit.as_ref().map(|_| err))
            });
            tangents = left.filter(|_| dim >= 3).map(|u| {
                let scale = |v: Vec<f64>| {
                    let m = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                    if m > 0.0 {
                        v.iter().map(|x| x / m).collect()
                    } else {
                        v
                    }
                };
                if e.values()[1].im.abs() > 0.0 {
                    let col = u.column(1);
                    [
                        scale(col.iter().map(|z| z.re).collect()),
                        scale(col.iter().map(|z| z.im).collect()),
                    ]
                } else {
                    [
                        scale(u.column(1).iter().map(|z| z.re).collect()),
                        scale(u.column(2).iter().map(|z| z.re).collect()),
                    ]
                }
            });
        }
        SpectrumPath::Structured => {
            let all = scheme
                .structured_spectrum()
                .ok_or_else(|| Error::NotApplicable {
                    scheme: scheme.name().to_owned(),
                    operation: "the structured spectral path (use the full path)",
                })??;
            subdominant = classify_local(scheme)?;
            subdominant_full = None;
            curvature = curvature::structured(scheme, &subdominant, &all)?;
            eigenvalues = all.iter().map(|&z| c64(z)).collect();
            residuals = None;
            conditions = None;
            limit = None;
            tangents = None;
        }
    }
    let spectral_bound = eigenvalues
        .iter()
        .skip(1)
        .map(|z| z[0].hypot(z[1]))
        .fold(0.0, f64::max);
    let contraction = if let Some(fc) = scheme.face_contraction(&options.measure) {
        let FaceContraction {
            certificate: cert,
            measured,
            face_block,
        } = fc?;
        let bound_radius = modulus_radius(&face_block, subdominant.radii[1])
            + (spectral_bound - subdominant.lambda1.norm()).abs();
        let bound_check = BoundCheck::of(spectral_bound, bound_radius, 0.75);
        Some(ContractionSummary {
            certificate_sum: cert.row_sums.iter().copied().fold(0.0, f64::max),
            certificate_sum_defect: cert.max_sum_defect(),
            certificate_nonnegative: cert.nonnegative,
            certificate_min_weight: cert.min_positive_weight,
            certificate_holds: cert.holds(),
            spectral_bound,
            spectral_bound_radius: bound_radius,
            spectral_bound_check: bound_check,
            spectral_bound_ok: bound_check != BoundCheck::Violated,
            measured_rate: measured.fitted_rate,
            measured_max_ratio: measured.max_ratio,
            measured_distances: measured.distances,
            measured_ratios: measured.ratios,
        })
    } else {
        None
    };
    let fourier_deviation = match scheme.spectral_structure() {
        SpectralStructure::Fourier => match scheme.structured_spectrum() {
            Some(blocks) => Some(fourier_deviation(&eigenvalues, &blocks?)),
            None => None,
        },
        _ => None,
    };
    let (limit_weights, limit_weights_error) = match limit {
        Some((w, e)) => (Some(w), e),
        None => (None, None),
    };
    Ok(LocalAnalysis {
        scheme: scheme.name().to_owned(),
        valence: n,
        path: options.path,
        eigenvalues,
        residuals,
        condition_numbers: conditions,
        face_weights,
        limit_weights,
        limit_weights_error,
        tangent_stencils: tangents,
        subdominant,
        subdominant_full,
        contraction,
        exact: None,
        float_class: None,
        fourier_deviation,
        curvature,
    })
}

/// Largest distance between two spectra after sorting both by
/// [`spectral_order`] (`INFINITY` if the lengths differ). Within a cluster of
/// (nearly) equal modulus the order may differ, so each value is matched to the
/// nearest unused value of the other list.
fn fourier_deviation(a: &[[f64; 2]], b: &[Complex64]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    let mut used = vec![false; b.len()];
    let mut worst = 0.0f64;
    for z in a {
        let z = Complex64::new(z[0], z[1]);
        let mut best = (f64::INFINITY, usize::MAX);
        for (j, w) in b.iter().enumerate() {
            let d = (z - w).norm();
            if !used[j] && d < best.0 {
                best = (d, j);
            }
        }
        if best.1 != usize::MAX {
            used[best.1] = true;
        }
        worst = worst.max(best.0);
    }
    worst
}

/// Condition numbers of the `wanted` entries of `values` (the others are
/// left 0) by one call of `compute` (the kernel's interleaved inverse
/// iterations). A wanted value that is the conjugate of the wanted value
/// before it shares that value's number: for a real matrix the computation
/// for `conj(z)` is the conjugate of the one for `z`, bit for bit.
fn condition_numbers_of(
    values: &[Complex64; 4],
    wanted: [bool; 4],
    compute: impl FnOnce(&[Complex64], &mut [f64]),
) -> [f64; 4] {
    let mut shifts = [Complex64::new(0.0, 0.0); 4];
    let mut slot = [usize::MAX; 4];
    let mut count = 0;
    let mut last: Option<usize> = None;
    for k in 0..4 {
        if !wanted[k] {
            continue;
        }
        match last {
            Some(p) if values[p] == values[k].conj() => slot[k] = slot[p],
            _ => {
                shifts[count] = values[k];
                slot[k] = count;
                count += 1;
            }
        }
        last = Some(k);
    }
    let mut kappa = [0.0f64; 4];
    compute(&shifts[..count], &mut kappa[..count]);
    std::array::from_fn(|k| if wanted[k] { kappa[slot[k]] } else { 0.0 })
}

/// The subdominant classification of any scheme: its own
/// [`fast_classification`](Scheme::fast_classification) when it has one,
/// else [`classify_scheme`] (the face-block kernel, or the local matrix with
/// the scheme's structural certificate, [`pairing::scheme_pair_certificate`]).
pub fn classify_local<S: Scheme + ?Sized>(scheme: &S) -> Result<Subdominant> {
    match scheme.fast_classification() {
        Some(fast) => fast,
        None => classify_scheme(scheme),
    }
}

thread_local! {
    static WORKSPACE: RefCell<StructuredWorkspace> = RefCell::new(StructuredWorkspace::new());
}

/// Classification only, by the structured path (the sweep fast path).
///
/// Doo-Sabin family only; uses a thread-local [`StructuredWorkspace`], so it
/// allocates nothing after the first call per thread and valence (except in
/// the rare near-double case, which runs a singular value decomposition).
/// Condition numbers of the face eigenvalues in positions 1-3 come from
/// inverse iteration on the Hessenberg form (`O(n^2)` each).
///
/// Schemes without a face block (the Catmull-Clark family, Loop): the local
/// matrix is classified by [`classify_matrix`] (the allocation-free kernel;
/// the matrix itself is assembled per call).
pub fn classify_scheme<S: Scheme + ?Sized>(scheme: &S) -> Result<Subdominant> {
    WORKSPACE.with(|ws| classify_scheme_with(&mut ws.borrow_mut(), scheme))
}

/// [`classify_scheme`] with an explicit workspace (unused for schemes
/// without a face block: those are classified by [`classify_matrix`] on
/// their local matrix).
pub fn classify_scheme_with<S: Scheme + ?Sized>(
    ws: &mut StructuredWorkspace,
    scheme: &S,
) -> Result<Subdominant> {
    if scheme.spectral_structure() != SpectralStructure::FaceBlock {
        return classify_matrix_with(scheme.local_matrix()?.matrix(), &mut |lam| {
            pairing::scheme_pair_certificate(scheme, lam)
        });
    }
    ws.face_nonunit(scheme)?;
    classify_face(ws, scheme.valence())
}

/// [`classify_scheme_with`] for [`BATCH`] schemes in as many
/// workspaces at once: the face spectra come from
/// [`StructuredWorkspace::face_nonunit_batch`] (the QR iterations in lock
/// step, one per SIMD lane), so the results equal, bit for bit, those of
/// `classify_scheme_with` calls, at a higher throughput (the sweep driver and
/// `benches/throughput.rs` classify configurations in batches).
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::BATCH;
/// use subdiv_lab::spectral::{classify_scheme, classify_schemes_batch, StructuredWorkspace};
/// let schemes: Vec<LocalScheme<f64>> = (0..BATCH)
///     .map(|i| LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.5, 0.05 + 0.05 * i as f64]).unwrap()))
///     .collect();
/// let mut ws: [StructuredWorkspace; BATCH] = Default::default();
/// let res = classify_schemes_batch(ws.each_mut(), std::array::from_fn(|i| &schemes[i]));
/// for (r, s) in res.into_iter().zip(&schemes) {
///     assert_eq!(r.unwrap(), classify_scheme(s).unwrap());
/// }
/// ```
pub fn classify_schemes_batch<S: Scheme + ?Sized>(
    ws: [&mut StructuredWorkspace; kernel::BATCH],
    schemes: [&S; kernel::BATCH],
) -> [Result<Subdominant>; kernel::BATCH] {
    let mut subs: [Subdominant; kernel::BATCH] = std::array::from_fn(|_| Subdominant::unset());
    let res = classify_schemes_batch_into(ws, schemes, subs.each_mut());
    let mut subs = subs.into_iter();
    res.map(|r| {
        let s = subs.next().expect("one result per lane");
        r.map(|()| s)
    })
}

/// [`classify_schemes_batch`] into `out` (lane `l`'s classification into
/// `out[l]`, overwritten whole when its result is `Ok`).
pub(crate) fn classify_schemes_batch_into<S: Scheme + ?Sized>(
    ws: [&mut StructuredWorkspace; kernel::BATCH],
    schemes: [&S; kernel::BATCH],
    out: [&mut Subdominant; kernel::BATCH],
) -> [Result<()>; kernel::BATCH] {
    let mut ws = ws;
    let mut out = out;
    if !schemes
        .iter()
        .all(|s| s.spectral_structure() == SpectralStructure::FaceBlock)
    {
        return std::array::from_fn(|l| {
            classify_scheme_with(ws[l], schemes[l]).map(|s| *out[l] = s)
        });
    }
    let faces = StructuredWorkspace::face_nonunit_batch(ws.each_mut().map(|w| &mut **w), schemes);
    let mut faces = faces.into_iter();
    std::array::from_fn(|l| {
        let f = faces.next().expect("one result per lane");
        f.map_err(Into::into)
            .and_then(|()| classify_face_into(ws[l], schemes[l].valence(), out[l]))
    })
}

/// The classification of a valence-`n` Doo-Sabin-family scheme whose face
/// spectrum `ws` holds.
fn classify_face(ws: &mut StructuredWorkspace, n: usize) -> Result<Subdominant> {
    let mut out = Subdominant::unset();
    classify_face_into(ws, n, &mut out)?;
    Ok(out)
}

/// [`classify_face`] into `out` (overwritten whole when `Ok`).
fn classify_face_into(ws: &mut StructuredWorkspace, n: usize, out: &mut Subdominant) -> Result<()> {
    let face_len = ws.face_nonunit_cached().len();
    let m = ws.deflated_dim();
    let eta = BACKWARD_ERROR_FACTOR * m.max(1) as f64 * f64::EPSILON * ws.frobenius_norm();
    // Merge the top of the face spectrum with the known 1/4 (n copies).
    let mut top = [(Complex64::new(1.0, 0.0), 0.0f64, usize::MAX); 4];
    let mut face_top = [Complex64::new(0.0, 0.0); 3];
    let k = face_len.min(3);
    {
        let face = ws.face_nonunit_cached();
        face_top[..k].copy_from_slice(&face[..k]);
    }
    let quarter = Complex64::new(structured::KNOWN_EIGENVALUES[0], 0.0);
    let (mut fi, mut qi) = (0usize, 0usize);
    for slot in top.iter_mut().skip(1) {
        let take_face = fi < k && (qi >= n || spectral_order(&face_top[fi], &quarter).is_le());
        if take_face {
            *slot = (face_top[fi], 0.0, fi);
            fi += 1;
        } else {
            *slot = (quarter, 0.0, usize::MAX);
            qi += 1;
        }
    }
    // Condition numbers for face eigenvalues among lambda_1..lambda_3.
    let wanted = [
        false,
        top[1].2 != usize::MAX,
        top[2].2 != usize::MAX,
        top[3].2 != usize::MAX,
    ];
    let values4 = [top[0].0, top[1].0, top[2].0, top[3].0];
    let kappa = condition_numbers_of(&values4, wanted, |z, k| ws.condition_numbers(z, k));
    for (k, slot) in top.iter_mut().enumerate() {
        if wanted[k] {
            slot.1 = radius(kappa[k], eta);
        }
    }
    let values = [top[0].0, top[1].0, top[2].0, top[3].0];
    let radii = [top[0].1, top[1].1, top[2].1, top[3].1];
    let bm = ws.deflated_matrix();
    // A double made of two face eigenvalues (not the known 1/4) is certified
    // by a circulant, mirror-symmetric face block ([`pairing`]).
    let both_face = top[1].2 != usize::MAX && top[2].2 != usize::MAX;
    let face = ws.face_block();
    classify_into(
        &Evidence {
            values: &values,
            radii: &radii,
            eta,
        },
        &mut |lam| {
            let b = DMatrix::from_column_slice(m, m, bm);
            let cert = if both_face {
                pairing::circulant_pair(face, n, lam)
            } else {
                None
            };
            double_test(&b, lam, cert)
        },
        out,
    )?;
    Ok(())
}

thread_local! {
    static MATRIX_WORKSPACE: RefCell<(kernel::KernelWorkspace, Vec<Complex64>)> =
        RefCell::new((kernel::KernelWorkspace::new(), Vec::new()));
}

/// Classification only for any square matrix (e.g. schemes outside the
/// Doo-Sabin family), by the allocation-free eigenvalue kernel ([`KernelWorkspace`]): all eigenvalues,
/// condition numbers of `lambda_1..lambda_3` by inverse iteration, and the
/// rank test (faer SVD) only for a double-eigenvalue candidate.
///
/// ```
/// use nalgebra::DMatrix;
/// use subdiv_lab::spectral::{classify_matrix, SubdominantClass};
/// // Eigenvalues 1, 1/2, 1/4, 1/4: |lambda_2| = |lambda_3|.
/// let s = DMatrix::from_row_slice(4, 4, &[
///     1.0, 0.0, 0.0, 0.0,
///     0.5, 0.5, 0.0, 0.0,
///     0.75, 0.0, 0.25, 0.0,
///     0.75, 0.0, 0.0, 0.25,
/// ]);
/// assert_eq!(classify_matrix(&s).unwrap().class, SubdominantClass::NotSeparated);
/// ```
pub fn classify_matrix(s: &DMatrix<f64>) -> Result<Subdominant> {
    classify_matrix_with(s, &mut |_| None)
}

/// [`classify_matrix`] with a structural certificate for a double candidate
/// `lambda` ([`DoubleTest::semisimple`], e.g.
/// [`pairing::scheme_pair_certificate`]); without one a double eigenvalue is
/// `indeterminate` ([`classify`](mod@classify) module docs).
pub fn classify_matrix_with(
    s: &DMatrix<f64>,
    certificate: &mut dyn FnMut(f64) -> Option<&'static str>,
) -> Result<Subdominant> {
    let (n, m) = s.shape();
    if n != m {
        return Err(SpectralError::NotSquare { rows: n, cols: m }.into());
    }
    MATRIX_WORKSPACE.with(|cell| {
        let mut guard = cell.borrow_mut();
        let (ws, values) = &mut *guard;
        ws.input(n).copy_from_slice(s.as_slice());
        let (re, im) = match ws.eigenvalues() {
            Ok(v) => v,
            // fallback route: the general eigen-decomposition (faer), as on
            // the full path of `analyze`
            Err(SpectralError::NoConvergence { .. }) => return classify_general(s, certificate),
            Err(e) => return Err(e.into()),
        };
        values.clear();
        values.extend(re.iter().zip(im).map(|(&a, &b)| Complex64::new(a, b)));
        values.sort_by(spectral_order);
        let eta = BACKWARD_ERROR_FACTOR * n.max(1) as f64 * f64::EPSILON * s.norm();
        let top: Vec<Complex64> = values.iter().take(4).copied().collect();
        let mut values4 = [Complex64::new(0.0, 0.0); 4];
        values4[..top.len()].copy_from_slice(&top);
        let wanted: [bool; 4] = std::array::from_fn(|k| k < top.len());
        let kappa = condition_numbers_of(&values4, wanted, |z, k| ws.condition_numbers(z, k));
        let mut radii = [0.0f64; 4];
        for k in 0..top.len() {
            radii[k] = radius(kappa[k], eta);
        }
        Ok(classify(
            &Evidence {
                values: &top,
                radii: &radii[..top.len()],
                eta,
            },
            &mut |lam| double_test(s, lam, certificate(lam)),
        )?)
    })
}

/// Classification of any square matrix from its general eigen-decomposition
/// with condition numbers ([`Eigen`], the full path of [`analyze`]): the
/// fallback of [`classify_matrix`] when the small-matrix kernel's QR
/// iteration does not converge within its bound.
fn classify_general(
    s: &DMatrix<f64>,
    certificate: &mut dyn FnMut(f64) -> Option<&'static str>,
) -> Result<Subdominant> {
    let e = Eigen::new(s, EigenOptions::BOTH)?;
    let eta = BACKWARD_ERROR_FACTOR * e.dim() as f64 * f64::EPSILON * e.frobenius_norm();
    let radii: Vec<f64> = e
        .condition_numbers()
        .unwrap_or(&[])
        .iter()
        .map(|&k| radius(k, eta))
        .collect();
    Ok(classify(
        &Evidence {
            values: e.values(),
            radii: &radii,
            eta,
        },
        &mut |lam| double_test(s, lam, certificate(lam)),
    )?)
}
