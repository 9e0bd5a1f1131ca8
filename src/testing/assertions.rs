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
/// [`crate::schemes::assembly::ROW_SUM_TOL`].
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
