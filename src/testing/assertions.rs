//! Checks that return a [`Violation`] diagnostic instead of panicking.
//!
//! Each check names the configuration it was given and the offending row,
//! eigenvalue or level, so a shrunk proptest failure reads as a counterexample.
//! [`Violation`] implements `std::error::Error`, so inside `proptest!` bodies
//! the checks compose with `?`.

use crate::scalar::Scalar;
use nalgebra::{DMatrix, DVector, Point3};
use std::fmt;

/// A failed check: which check, on what, and the evidence.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{check} failed for {configuration}: {detail}")]
pub struct Violation {
    /// The check that failed (e.g. `"affine invariance"`).
    pub check: &'static str,
    /// The configuration, as the caller described it.
    pub configuration: String,
    /// The evidence: offending row, eigenvalue, level and values.
    pub detail: String,
}

impl Violation {
    fn new(check: &'static str, configuration: &dyn fmt::Debug, detail: String) -> Self {
        Self {
            check,
            configuration: format!("{configuration:?}"),
            detail,
        }
    }
}

/// Default tolerance on `|row sum - 1|` for `f64` matrices: see
/// [`crate::schemes::ROW_SUM_TOL`].
pub const ROW_SUM_TOL: f64 = crate::schemes::assembly::ROW_SUM_TOL;

/// Every row of `matrix` sums to 1 (affine invariance): exactly for rationals,
/// within `tol` for `f64`.
///
/// ```
/// use nalgebra::DMatrix;
/// use subdiv_lab::testing::assertions::check_affine_invariance;
/// let good = DMatrix::from_row_slice(2, 2, &[0.75, 0.25, 0.5, 0.5]);
/// assert!(check_affine_invariance(&good, &"good", 1e-12).is_ok());
/// let bad = DMatrix::from_row_slice(2, 2, &[0.75, 0.25, 0.5, 0.6]);
/// let v = check_affine_invariance(&bad, &"bad", 1e-12).unwrap_err();
/// assert!(v.detail.contains("row 1"));
/// ```
pub fn check_affine_invariance<T: Scalar>(
    matrix: &DMatrix<T>,
    configuration: &dyn fmt::Debug,
    tol: f64,
) -> Result<(), Violation> {
    for (i, row) in matrix.row_iter().enumerate() {
        let sum = row.iter().cloned().fold(T::zero(), |a, b| a + b);
        let defect = sum.clone() - T::one();
        let bad = if T::EXACT {
            !defect.is_zero()
        } else {
            {
                let d = defect.to_f64().abs();
                d.is_nan() || d > tol
            }
        };
        if bad {
            return Err(Violation::new(
                "affine invariance",
                configuration,
                format!(
                    "row {i} sums to {} (defect {})",
                    sum.to_text(),
                    defect.to_text()
                ),
            ));
        }
    }
    Ok(())
}

/// Per-level record of an iterated contraction check.
#[derive(Clone, Debug, PartialEq)]
pub struct ContractionTrace {
    /// `max_i |P^k_i - F|` for `k = 0..=levels`.
    pub distances: Vec<f64>,
    /// `distances[k+1] / distances[k]`.
    pub ratios: Vec<f64>,
}

/// Relative slack for per-level contraction checks: the distances are computed
/// from `f64` matrix-vector products with `O(4n)` terms of magnitude `<= 1`,
/// so each ratio carries a relative error of a few hundred ulps at most;
/// `1e-10` is far above that and far below any real violation.
pub const CONTRACTION_SLACK: f64 = 1e-10;

/// Distances below this are at the level of rounding of the coordinates
/// (`|P| <= 1e3` times `eps`): the check stops there rather than divide noise.
pub const DISTANCE_FLOOR: f64 = 1e-12;

/// Iterates `matrix` on `points` for `levels` levels and checks that the first
/// `face_size` points (the face `P_0..P_{n-1}`, Doo-Sabin ordering) shrink
/// towards the face's limit point `F = c^T P` by at least `factor` per level:
/// `max_i |P^{k+1}_i - F| <= factor * max_i |P^k_i - F|` (Theorem 1, math doc section 5).
///
/// `c` is the left fixed vector of the `face_size x face_size` face block,
/// computed by a linear solve; a face block without a unique fixed vector
/// is itself reported as a violation.
///
/// ```
/// use nalgebra::Point3;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::testing::assertions::check_face_contraction;
/// let s = LocalScheme::<f64>::cc_variant(5).unwrap();
/// let m = s.matrix().unwrap();
/// let pts: Vec<_> = (0..20).map(|i| Point3::new((i as f64).sin(), (i as f64).cos(), 0.1 * i as f64)).collect();
/// let trace = check_face_contraction(m.matrix(), 5, &pts, 0.75, 30, &s).unwrap();
/// assert!(trace.ratios.iter().all(|&r| r <= 0.75 + 1e-10));
/// ```
pub fn check_face_contraction(
    matrix: &DMatrix<f64>,
    face_size: usize,
    points: &[Point3<f64>],
    factor: f64,
    levels: usize,
    configuration: &dyn fmt::Debug,
) -> Result<ContractionTrace, Violation> {
    let check = "face contraction";
    let size = matrix.nrows();
    if matrix.ncols() != size || points.len() != size || face_size == 0 || face_size > size {
        return Err(Violation::new(
            check,
            configuration,
            format!(
                "shape mismatch: matrix {}x{}, {} points, face size {face_size}",
                size,
                matrix.ncols(),
                points.len()
            ),
        ));
    }
    let c = left_fixed_vector(&matrix.view((0, 0), (face_size, face_size)).into_owned())
        .ok_or_else(|| {
            Violation::new(
                check,
                configuration,
                "the face block has no unique left fixed vector".into(),
            )
        })?;
    let mut coords = DMatrix::from_fn(size, 3, |i, j| points[i][j]);
    let mut distances = Vec::with_capacity(levels + 1);
    let mut ratios = Vec::with_capacity(levels);
    for k in 0..=levels {
        let face = coords.rows(0, face_size);
        let f = face.transpose() * &c;
        let d = (0..face_size)
            .map(|i| (face.row(i).transpose() - &f).norm())
            .fold(0.0, f64::max);
        if let Some(&prev) = distances.last() {
            if prev > DISTANCE_FLOOR {
                let ratio: f64 = d / prev;
                ratios.push(ratio);
                if ratio.is_nan() || ratio > factor * (1.0 + CONTRACTION_SLACK) {
                    return Err(Violation::new(
                        check,
                        configuration,
                        format!("level {} -> {k}: distance {prev:.6e} -> {d:.6e}, ratio {ratio:.9} > factor {factor}", k - 1),
                    ));
                }
            }
        }
        distances.push(d);
        if k < levels {
            coords = matrix * coords;
        }
    }
    Ok(ContractionTrace { distances, ratios })
}

/// The left fixed vector `c^T A = c^T`, `sum c = 1`, by an LU solve; `None` if singular.
fn left_fixed_vector(a: &DMatrix<f64>) -> Option<DVector<f64>> {
    let n = a.nrows();
    let mut m = a.transpose() - DMatrix::identity(n, n);
    for j in 0..n {
        m[(n - 1, j)] = 1.0;
    }
    let mut rhs = DVector::zeros(n);
    rhs[n - 1] = 1.0;
    let c = m.lu().solve(&rhs)?;
    c.iter().all(|x| x.is_finite()).then_some(c)
}

fn subdominant_of(
    matrix: &DMatrix<f64>,
    check: &'static str,
    configuration: &dyn fmt::Debug,
) -> Result<crate::spectral::Subdominant, Violation> {
    crate::spectral::classify_matrix(matrix)
        .map_err(|e| Violation::new(check, configuration, format!("eigen-analysis failed: {e}")))
}

/// The dominant eigenvalue is 1 and simple: `|lambda_0 - 1|` is within its
/// error radius and `|lambda_1 - 1|` is certainly non-zero (beyond
/// [`crate::spectral::classify::SEPARATION_FACTOR`] times its radius; the
/// radii are the spectral engine's condition-scaled error radii). A verdict in
/// the grey zone is a violation: the property could not be certified.
///
/// ```
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::testing::assertions::check_dominant_simple;
/// let s = LocalScheme::<f64>::cc_variant(5).unwrap();
/// assert!(check_dominant_simple(s.matrix().unwrap().matrix(), &s).is_ok());
/// let identity = nalgebra::DMatrix::<f64>::identity(4, 4);
/// assert!(check_dominant_simple(&identity, &"identity").is_err());
/// ```
pub fn check_dominant_simple(
    matrix: &DMatrix<f64>,
    configuration: &dyn fmt::Debug,
) -> Result<(), Violation> {
    use crate::spectral::classify::{decide, Decision};
    let check = "dominant eigenvalue 1 simple";
    let sub = subdominant_of(matrix, check, configuration)?;
    if decide((sub.lambda0 - 1.0).norm(), sub.radii[0]) != Decision::Zero {
        return Err(Violation::new(
            check,
            configuration,
            format!(
                "lambda_0 = {} is not 1 (error radius {:.3e})",
                sub.lambda0, sub.radii[0]
            ),
        ));
    }
    if decide((sub.lambda1 - 1.0).norm(), sub.radii[1]) != Decision::NonZero {
        return Err(Violation::new(
            check,
            configuration,
            format!(
                "lambda_1 = {} cannot be separated from 1 (error radius {:.3e})",
                sub.lambda1, sub.radii[1]
            ),
        ));
    }
    Ok(())
}

/// The largest non-unit eigenvalue modulus `|lambda_1|` is at most `bound`
/// (within the engine's error radius of `lambda_1`, so that an exact equality
/// such as `|lambda_1| = 1/2` for `bound = 1/2` is not failed by rounding).
///
/// ```
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::testing::assertions::check_spectral_radius;
/// let s = LocalScheme::<f64>::cc_variant(4).unwrap(); // |lambda_1| = 1/2
/// let m = s.matrix().unwrap();
/// assert!(check_spectral_radius(m.matrix(), 0.5, &s).is_ok());
/// let v = check_spectral_radius(m.matrix(), 0.45, &s).unwrap_err();
/// assert!(v.detail.contains("|lambda_1| = 0.5"));
/// ```
pub fn check_spectral_radius(
    matrix: &DMatrix<f64>,
    bound: f64,
    configuration: &dyn fmt::Debug,
) -> Result<(), Violation> {
    let check = "non-unit spectral radius";
    let sub = subdominant_of(matrix, check, configuration)?;
    let modulus = sub.lambda1.norm();
    if modulus.is_nan() || modulus > bound + sub.radii[1] {
        return Err(Violation::new(
            check,
            configuration,
            format!(
                "|lambda_1| = {modulus} (lambda_1 = {}, error radius {:.3e}) exceeds the bound {bound}",
                sub.lambda1, sub.radii[1]
            ),
        ));
    }
    Ok(())
}

/// The subdominant class (math doc section 7) is one of `allowed`; an
/// indeterminate classification is a violation that names both candidates.
///
/// ```
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::ClassName;
/// use subdiv_lab::testing::assertions::check_subdominant_class;
/// let s = LocalScheme::<f64>::doo_sabin(7).unwrap();
/// assert!(check_subdominant_class(&s, &[ClassName::Standard]).is_ok());
/// ```
pub fn check_subdominant_class(
    scheme: &crate::schemes::LocalScheme<f64>,
    allowed: &[crate::spectral::ClassName],
) -> Result<(), Violation> {
    let check = "subdominant class";
    let sub = crate::spectral::classify_scheme(scheme)
        .map_err(|e| Violation::new(check, scheme, format!("eigen-analysis failed: {e}")))?;
    match sub.class.class_name() {
        Some(c) if allowed.contains(&c) => Ok(()),
        _ => Err(Violation::new(
            check,
            scheme,
            format!(
                "class {:?} (lambda_1 = {}, lambda_2 = {}, |lambda_3| = {}) is not one of {:?}",
                sub.class, sub.lambda1, sub.lambda2, sub.abs_lambda3, allowed
            ),
        )),
    }
}

/// The characteristic map (math doc section 7) is regular and injective: the
/// verdict is `C1 (standard; Reif)` or, for a non-standard eigenstructure,
/// tangent-plane continuous. Anything else (not regular, not injective,
/// indeterminate, no characteristic map) is a violation with the verdict text.
///
/// ```
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::testing::assertions::check_charmap_regular_injective;
/// let s = LocalScheme::<f64>::cc_variant(6).unwrap();
/// assert!(check_charmap_regular_injective(&s).is_ok());
/// ```
pub fn check_charmap_regular_injective(
    scheme: &crate::schemes::LocalScheme<f64>,
) -> Result<(), Violation> {
    use crate::charmap::Verdict;
    let check = "characteristic map regular and injective";
    let report = crate::charmap::check(scheme).map_err(|e| {
        Violation::new(
            check,
            scheme,
            format!("characteristic-map check failed: {e}"),
        )
    })?;
    match &report.verdict {
        Verdict::C1Standard | Verdict::TangentPlaneContinuous { .. } => Ok(()),
        other => Err(Violation::new(
            check,
            scheme,
            format!(
                "verdict: {other}; min Jacobian coefficient {:?}, winding number {:?}",
                report.min_jacobian_coeff(),
                report.winding_number
            ),
        )),
    }
}

/// Mesh-level Theorem 1: refining `mesh` `levels` times with `scheme`, every
/// extraordinary face's distance `max_i |P_i - F|` shrinks by at least `factor`
/// per level (up to [`CONTRACTION_SLACK`]; distances below [`DISTANCE_FLOOR`]
/// are not compared).
///
/// ```
/// use subdiv_lab::mesh::generators;
/// use subdiv_lab::schemes::SchemeKind;
/// use subdiv_lab::testing::assertions::check_mesh_contraction;
/// let cube = generators::cube();
/// assert!(check_mesh_contraction(&cube, SchemeKind::Nurds, 3, 0.75).is_ok());
/// ```
pub fn check_mesh_contraction(
    mesh: &crate::mesh::Mesh,
    scheme: crate::schemes::SchemeKind,
    levels: usize,
    factor: f64,
) -> Result<(), Violation> {
    let check = "mesh face contraction";
    let describe = format!(
        "{} mesh with {} faces, {} vertices",
        scheme.name(),
        mesh.face_count(),
        mesh.vertex_count()
    );
    // the scheme's mesh rules, through the one dispatch
    let rules = crate::mesh::builtin::mesh_rules(scheme, None)
        .map_err(|e| Violation::new(check, &describe, format!("no mesh rules: {e}")))?;
    let (_, stats) = rules
        .refine_with_stats(mesh, levels)
        .ok_or_else(|| {
            Violation::new(
                check,
                &describe,
                "the scheme has no per-level statistics of extraordinary faces".to_owned(),
            )
        })?
        .map_err(|e| Violation::new(check, &describe, format!("refinement failed: {e}")))?;
    for level in &stats {
        for face in &level.extraordinary {
            if let Some(ratio) = face.ratio {
                let previous = face.distance / ratio;
                if previous > DISTANCE_FLOOR
                    && (ratio.is_nan() || ratio > factor * (1.0 + CONTRACTION_SLACK))
                {
                    return Err(Violation::new(
                        check,
                        &describe,
                        format!(
                            "level {}: extraordinary face {} (n = {}) shrank by {ratio:.9} > factor {factor}",
                            level.level, face.face, face.valence
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}
