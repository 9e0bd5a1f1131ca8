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
mod local;
pub mod pairing;
pub(crate) mod poly;
pub mod structured;
pub(crate) mod svd;

#[cfg(test)]
mod closed_form_tests;

mod error;
pub use error::{Result, SpectralError};

pub use classify::{ClassName, Subdominant, SubdominantClass};
pub use eigen::{Eigen, EigenOptions};
pub use kernel::{
    KernelWorkspace, BATCH, EXCEPTIONAL_SHIFT_PERIOD, LOCKSTEP_MAX_DIM, LOCKSTEP_MIN_DIM,
    MAX_SWEEPS_PER_DIMENSION, MAX_SWEEPS_PER_EIGENVALUE,
};
pub(crate) use local::classify_schemes_batch_into;
use local::{c64, double_test, modulus_radius, radius};
pub use local::{
    classify_local, classify_matrix, classify_matrix_with, classify_scheme, classify_scheme_with,
    classify_schemes_batch,
};
pub use structured::{structured_spectrum, StructuredWorkspace};

use crate::contraction::FaceContraction;
use crate::contraction::MeasureOptions;
use crate::error::Error;
use crate::scalar::Rational;
use crate::schemes::LocalScheme;
use crate::schemes::{Scheme, SpectralStructure};
use classify::{classify, Evidence, BACKWARD_ERROR_FACTOR};
use num_complex::Complex64;
use serde::Serialize;

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

/// The one-step spectrum of a scheme whose local matrix covers several steps
/// ([`LocalAnalysis::steps`]).
#[derive(Clone, Debug, Serialize)]
pub struct StepsSummary {
    /// Subdivision steps the local matrix (and every verdict) covers.
    pub matrix_steps: usize,
    /// The one-step matrix's spectrum `[re, im]`, sorted by non-increasing
    /// modulus (complex subdominant pair where one step turns the ring).
    pub one_step_eigenvalues: Vec<[f64; 2]>,
}

/// The [`StepsSummary`] of `scheme`, if its local matrix covers several steps.
fn steps_summary<S: Scheme + ?Sized>(scheme: &S) -> Result<Option<StepsSummary>> {
    let Some((steps, m)) = scheme.one_step_matrix() else {
        return Ok(None);
    };
    let e = Eigen::new(m?.matrix(), EigenOptions::VALUES)?;
    let mut values = e.values().to_vec();
    values.sort_by(crate::schemes::spectral_order);
    Ok(Some(StepsSummary {
        matrix_steps: steps,
        one_step_eigenvalues: values.iter().map(|&z| c64(z)).collect(),
    }))
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
    /// Present only for a scheme whose local matrix covers several steps
    /// ([`Scheme::one_step_matrix`]: sqrt(3)): how many, and the one-step
    /// matrix's spectrum. Every other field, and every verdict, refers to
    /// the local (multi-step) matrix.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<StepsSummary>,
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
            subdominant = if scheme.spectral_structure() == SpectralStructure::FaceBlock {
                classify_scheme(scheme)?
            } else {
                full.clone()
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
            let all = structured::spectrum_of(scheme).ok_or_else(|| Error::NotApplicable {
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
    let contraction =
        if let Some(fc) = crate::contraction::face_contraction(scheme, &options.measure) {
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
        steps: steps_summary(scheme)?,
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
