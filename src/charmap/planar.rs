//! The planar invariant subspace of the subdominant pair: an orthonormal basis,
//! its restriction and the error bound every characteristic-map verdict rests
//! on (math doc section 7).

use super::regularity::gamma;
use super::Eigenstructure;
use crate::error::{Error, Result};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Safety factor on the first-order estimate `||S W - W M||_F / gap` of the
/// error of the computed invariant subspace, reported as
/// [`PlanarBasis::estimated_error`] next to the rigorous bound (for
/// comparison: exact for normal matrices; for non-normal ones the true
/// separation can be smaller than the eigenvalue gap, hence the factor).
pub const SUBSPACE_ERROR_SAFETY: f64 = 100.0;

/// Backward-error factor `c` of the SVD that computes the separation: the
/// computed smallest singular value of the `2m x 2m` Kronecker matrix `K` is
/// taken to be within `c (2m) eps ||K||_F` of the exact one (LAPACK's bound
/// has `c` of order 1; we allow 8).
pub const SVD_ERROR_FACTOR: f64 = 8.0;

/// Smallest accepted `sin` of the angle between the two computed basis vectors;
/// below it the vectors do not determine a plane (numerically parallel).
pub const MIN_BASIS_SINE: f64 = 1e-8;

/// An orthonormal basis `W = [w1 w2]` of the subdominant real invariant subspace
/// of `S_n`, with `M = W^T S W` (so that `S W ~ W M`) and an error estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarBasis {
    /// The eigenstructure the subspace belongs to.
    pub structure: Eigenstructure,
    /// The subdominant eigenvalues `lambda_1, lambda_2`.
    pub lambda: [Complex64; 2],
    /// First basis vector (`4n` entries, unit 2-norm).
    pub w1: Vec<f64>,
    /// Second basis vector (orthogonal to `w1`, unit 2-norm).
    pub w2: Vec<f64>,
    /// The restriction `M` (row-major 2x2): next ring = `M` applied to this ring.
    pub restriction: [[f64; 2]; 2],
    /// `||S W - W M||_F`.
    pub residual: f64,
    /// Bound on the error of every entry of `w1`, `w2` (there is an exact
    /// invariant subspace with a basis within this distance, entry-wise):
    /// Stewart's bound ([`subspace_bound`]), `+inf` when its hypothesis
    /// fails (the subspace is then not certified and every verdict built on
    /// it is `indeterminate`).
    pub vector_error: f64,
    /// The first-order estimate [`SUBSPACE_ERROR_SAFETY`] `* residual / gap`
    /// (for comparison with the bound; not used by the checks).
    pub estimated_error: f64,
    /// Lower bound on `sep(M, L_22)` (0 if none could be certified).
    pub separation: f64,
}

impl PlanarBasis {
    /// Orthonormalises two real vectors spanning the subspace (`(v1, v2)` or
    /// `(Re v, Im v)`), computes `M = W^T S W`, the residual and the error
    /// estimate. `gap` is a lower bound on the distance of `lambda_{1,2}` from
    /// the rest of the spectrum (e.g. `min(|lambda_2| - |lambda_3|, 1 - |lambda_1|)`).
    pub fn new(
        s: &DMatrix<f64>,
        structure: Eigenstructure,
        lambda: [Complex64; 2],
        a: &[f64],
        b: &[f64],
        gap: f64,
    ) -> Result<Self> {
        let dim = s.nrows();
        for v in [a, b] {
            if v.len() != dim {
                return Err(Error::CountMismatch {
                    what: "planar basis vector (4n entries)",
                    expected: dim,
                    got: v.len(),
                });
            }
        }
        let bad = |reason: String| Error::Numerical {
            routine: "characteristic map basis",
            reason,
        };
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let na = norm(a);
        if !(na > 0.0 && na.is_finite()) {
            return Err(bad(format!("first basis vector has norm {na}")));
        }
        let w1: Vec<f64> = a.iter().map(|x| x / na).collect();
        let nb = norm(b);
        if !(nb > 0.0 && nb.is_finite()) {
            return Err(bad(format!("second basis vector has norm {nb}")));
        }
        let proj: f64 = w1.iter().zip(b).map(|(x, y)| x * y).sum();
        let mut w2: Vec<f64> = b.iter().zip(&w1).map(|(y, x)| y - proj * x).collect();
        // re-orthogonalise once (classical Gram-Schmidt twice is enough)
        let proj2: f64 = w1.iter().zip(&w2).map(|(x, y)| x * y).sum();
        for (y, x) in w2.iter_mut().zip(&w1) {
            *y -= proj2 * x;
        }
        let n2 = norm(&w2);
        if n2.is_nan() || n2 <= MIN_BASIS_SINE * nb {
            return Err(bad(format!(
                "the two subdominant vectors are numerically parallel (sin angle = {:e})",
                n2 / nb
            )));
        }
        for y in w2.iter_mut() {
            *y /= n2;
        }
        let sw1: Vec<f64> = (0..dim)
            .map(|i| (0..dim).map(|j| s[(i, j)] * w1[j]).sum())
            .collect();
        let sw2: Vec<f64> = (0..dim)
            .map(|i| (0..dim).map(|j| s[(i, j)] * w2[j]).sum())
            .collect();
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
        let m = [
            [dot(&w1, &sw1), dot(&w1, &sw2)],
            [dot(&w2, &sw1), dot(&w2, &sw2)],
        ];
        let mut res2 = 0.0;
        for i in 0..dim {
            let r1 = sw1[i] - (w1[i] * m[0][0] + w2[i] * m[1][0]);
            let r2 = sw2[i] - (w1[i] * m[0][1] + w2[i] * m[1][1]);
            res2 += r1 * r1 + r2 * r2;
        }
        let residual = res2.sqrt();
        if gap.is_nan() || gap <= 0.0 {
            return Err(bad(format!(
                "no spectral gap around the subdominant pair (gap = {gap})"
            )));
        }
        // the residual is itself computed in floating point: add its rounding floor
        let floor = gamma(2 * dim) * frob(s);
        let estimated_error = SUBSPACE_ERROR_SAFETY * (residual + floor) / gap;
        let (vector_error, separation) = subspace_bound(s, &w1, &w2)?;
        Ok(Self {
            structure,
            lambda,
            w1,
            w2,
            restriction: m,
            residual,
            vector_error,
            estimated_error,
            separation,
        })
    }
}

/// Rigorous (up to [`SVD_ERROR_FACTOR`]) entry-wise error bound of an
/// orthonormal basis `W = [w1 w2]` of an approximate invariant subspace of
/// `S`, and the certified separation **\[derived\]** from Stewart's theorem
/// (G. W. Stewart, SIAM Review 15, 1973; Golub and Van Loan, *Matrix
/// Computations*, 3rd ed., Theorem 7.2.4):
///
/// With `Q = [W W_perp]` orthogonal (QR of `W`), `Q^T S Q = T + E` where
/// `T = [[M, T_12], [0, L_22]]` has the exactly invariant subspace
/// `span(e_1, e_2)` and `E = [[0, 0], [E_21, 0]]`. If
/// `sep = sep(M, L_22) = sigma_min(I ⊗ M - L_22^T ⊗ I) > 0` and
/// `||E||_2 (1 + 5 ||T_12||_2 / sep) <= sep / 5`, then `S` has an invariant
/// subspace spanned by `W + W_perp P` with `||P||_2 <= 4 ||E_21||_2 / sep`;
/// every entry of `W_perp P e_j` is at most `||P||_2`. We use Frobenius norms
/// (upper bounds of the 2-norms), add the rounding of `Q^T S Q`
/// (`gamma_{4 dim} ||S||_F`) to `||E_21||` and `||T_12||`, and subtract the
/// SVD's error from `sigma_min`. Returns `(bound, sep_lower)`; the bound is
/// `+inf` when the hypothesis fails.
///
/// Cost: one `dim x dim` QR and product, and the singular values of a
/// `2 (dim - 2)` square matrix.
pub fn subspace_bound(s: &DMatrix<f64>, w1: &[f64], w2: &[f64]) -> Result<(f64, f64)> {
    let dim = s.nrows();
    if dim < 3 {
        return Ok((0.0, f64::INFINITY));
    }
    let wmat = faer::Mat::<f64>::from_fn(dim, 2, |i, j| if j == 0 { w1[i] } else { w2[i] });
    let q = wmat.qr().compute_Q();
    let sm = faer::Mat::<f64>::from_fn(dim, dim, |i, j| s[(i, j)]);
    let t = q.transpose() * &sm * &q;
    let m = dim - 2;
    let fro = |rows: std::ops::Range<usize>, cols: std::ops::Range<usize>| {
        let mut acc = 0.0;
        for i in rows {
            for j in cols.clone() {
                acc += t[(i, j)] * t[(i, j)];
            }
        }
        acc.sqrt()
    };
    let round = gamma(4 * dim) * frob(s);
    let e21 = fro(2..dim, 0..2) + round;
    let t12 = fro(0..2, 2..dim) + round;
    // K = I_m ⊗ M - L22^T ⊗ I_2 on vec(X), X 2 x m (column-major: X[a][i] at a + 2 i)
    let k = faer::Mat::<f64>::from_fn(2 * m, 2 * m, |r, c| {
        let (a, i) = (r % 2, r / 2);
        let (b, j) = (c % 2, c / 2);
        let mut v = 0.0;
        if i == j {
            v += t[(a, b)];
        }
        if a == b {
            v -= t[(2 + j, 2 + i)];
        }
        v
    });
    let mut kf = 0.0;
    for c in 0..2 * m {
        for r in 0..2 * m {
            kf += k[(r, c)] * k[(r, c)];
        }
    }
    let kf = kf.sqrt();
    let sv = match k.singular_values() {
        Ok(sv) => sv,
        // fallback route: the one-sided Jacobi SVD (same error model)
        Err(_) => {
            let kd = DMatrix::from_fn(2 * m, 2 * m, |r, c| k[(r, c)]);
            crate::spectral::svd::jacobi_svd(&kd, false)
                .map_err(|_| Error::Numerical {
                    routine: "subspace separation (SVD)",
                    reason: format!("no convergence for a {0} x {0} Kronecker matrix", 2 * m),
                })?
                .0
        }
    };
    let smin = sv.last().copied().unwrap_or(0.0);
    // sep of the exact T: the computed K is off by the rounding of Q^T S Q too
    let sep = smin - SVD_ERROR_FACTOR * (2 * m) as f64 * f64::EPSILON * kf - 2.0 * round;
    if sep.is_nan() || sep <= 0.0 || !sep.is_finite() {
        return Ok((f64::INFINITY, 0.0));
    }
    if e21 * (1.0 + 5.0 * t12 / sep) > sep / 5.0 {
        return Ok((f64::INFINITY, sep));
    }
    Ok((4.0 * e21 / sep, sep))
}

fn frob(s: &DMatrix<f64>) -> f64 {
    s.iter().map(|x| x * x).sum::<f64>().sqrt()
}
