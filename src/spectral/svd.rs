//! Singular value decompositions with a fallback route.
//!
//! The first route is faer's bidiagonalisation SVD (fast, LAPACK-style). Its
//! implicit QR iteration has an iteration bound and can report "no
//! convergence" on perfectly ordinary matrices (seen on a 7 x 7 one-ring
//! matrix of the adjustable Catmull-Clark scheme). The fallback is
//! the one-sided Jacobi SVD of Hestenes (Golub and Van Loan, *Matrix
//! Computations*, 4th ed., section 8.6.3; Demmel and Veselic, SIAM J. Matrix
//! Anal. Appl. 13, 1992): plane rotations `[c s; -s c]` applied to column
//! pairs `(p, q)` of `A` (accumulated in `V`) until every pair is orthogonal
//! to working precision,
//!
//! ```text
//! |a_p . a_q| <= JACOBI_TOLERANCE * ||a_p|| ||a_q||   for all p < q,
//! ```
//!
//! (a column of norm below `eps ||A||_F` is left alone: it is rounding
//! noise), after which `A V = U Sigma` with `sigma_j = ||a_j||`. Each rotation is
//! backward stable, so the singular values are computed to the same
//! `c m eps ||A||` absolute accuracy as the first route (the error model the
//! callers use, e.g. [`crate::charmap::SVD_ERROR_FACTOR`]). It converges
//! quadratically in practice; [`JACOBI_MAX_SWEEPS`] bounds it, and only a
//! failure of both routes is an error.

use super::SpectralError;
use nalgebra::DMatrix;

/// Relative orthogonality threshold of the one-sided Jacobi SVD: a column
/// pair is rotated while `|a_p . a_q| > JACOBI_TOLERANCE ||a_p|| ||a_q||`.
/// `n eps`-level (with `n` up to a few thousand) would be the textbook
/// choice; `4 eps` is reached in one or two extra sweeps and makes the
/// computed columns orthogonal to working precision.
pub const JACOBI_TOLERANCE: f64 = 4.0 * f64::EPSILON;

/// Bound on the Jacobi sweeps (each sweep visits every column pair once).
/// Convergence is quadratic once the off-diagonal part is small; 10-20
/// sweeps are typical even for badly scaled matrices, so 100 leaves room.
pub const JACOBI_MAX_SWEEPS: usize = 100;

/// The singular values of `a` (any shape), sorted non-increasing: faer's SVD,
/// and the one-sided Jacobi SVD ([`jacobi_svd`]) when that does not converge.
pub fn singular_values(a: &DMatrix<f64>) -> Result<Vec<f64>, SpectralError> {
    let (r, c) = a.shape();
    let m = faer::Mat::<f64>::from_fn(r, c, |i, j| a[(i, j)]);
    match m.singular_values() {
        Ok(s) => Ok(s),
        Err(_) => jacobi_svd(a, false).map(|(s, _)| s),
    }
}

/// Singular values (non-increasing) and, if `want_v`, the right singular
/// vectors (column `j` of `V` belongs to `sigma_j`) of `a` by the one-sided
/// Jacobi method (see the module documentation). Needs `rows >= cols` for the
/// vectors (a wide matrix is handled through its transpose when no vectors are
/// asked for). Errors: a non-finite entry, or no convergence within
/// [`JACOBI_MAX_SWEEPS`] sweeps.
pub fn jacobi_svd(
    a: &DMatrix<f64>,
    want_v: bool,
) -> Result<(Vec<f64>, Option<DMatrix<f64>>), SpectralError> {
    let (rows, cols) = a.shape();
    if let Some(k) = a.iter().position(|x| !x.is_finite()) {
        return Err(SpectralError::NonFinite {
            row: k % rows.max(1),
            col: k / rows.max(1),
        });
    }
    if rows < cols {
        if want_v {
            return Err(SpectralError::NotSquare { rows, cols });
        }
        return jacobi_svd(&a.transpose(), false);
    }
    let mut w = a.clone();
    // Columns of norm below eps ||A||_F are at the rounding level of A (their
    // singular values are within the error model already) and are not rotated:
    // noise against noise would never meet the relative test.
    let negligible = (f64::EPSILON * a.norm()).powi(2);
    let mut v = want_v.then(|| DMatrix::<f64>::identity(cols, cols));
    let mut converged = cols < 2;
    for _ in 0..JACOBI_MAX_SWEEPS {
        if converged {
            break;
        }
        let mut rotated = false;
        for p in 0..cols {
            for q in p + 1..cols {
                let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
                for i in 0..rows {
                    let (x, y) = (w[(i, p)], w[(i, q)]);
                    alpha += x * x;
                    beta += y * y;
                    gamma += x * y;
                }
                if gamma == 0.0
                    || alpha <= negligible
                    || beta <= negligible
                    || gamma.abs() <= JACOBI_TOLERANCE * (alpha * beta).sqrt()
                {
                    continue;
                }
                rotated = true;
                // tan of the rotation angle that zeroes gamma (the smaller root)
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                for i in 0..rows {
                    let (x, y) = (w[(i, p)], w[(i, q)]);
                    w[(i, p)] = c * x - s * y;
                    w[(i, q)] = s * x + c * y;
                }
                if let Some(v) = v.as_mut() {
                    for i in 0..cols {
                        let (x, y) = (v[(i, p)], v[(i, q)]);
                        v[(i, p)] = c * x - s * y;
                        v[(i, q)] = s * x + c * y;
                    }
                }
            }
        }
        converged = !rotated;
    }
    if !converged {
        return Err(SpectralError::SvdNoConvergence { size: cols });
    }
    let norms: Vec<f64> = (0..cols).map(|j| w.column(j).norm()).collect();
    let mut order: Vec<usize> = (0..cols).collect();
    order.sort_by(|&i, &j| norms[j].total_cmp(&norms[i]));
    let sigma = order.iter().map(|&j| norms[j]).collect();
    let v = v.map(|v| DMatrix::from_fn(cols, cols, |i, k| v[(i, order[k])]));
    Ok((sigma, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn faer_sigma(a: &DMatrix<f64>) -> Vec<f64> {
        faer::Mat::<f64>::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
            .singular_values()
            .unwrap()
    }

    /// Jacobi agrees with faer to a few ulps of ||A|| on assorted matrices,
    /// and A V has orthogonal columns of norms sigma.
    #[test]
    fn jacobi_matches_faer_and_v_is_orthogonal() {
        for (n, seed) in [(1usize, 1u64), (2, 2), (5, 3), (7, 4), (20, 5), (33, 6)] {
            let mut x = crate::rng::Lcg64::new(seed);
            let a = DMatrix::from_fn(n, n, |_, _| x.next_f64() - 0.5);
            let (s, v) = jacobi_svd(&a, true).unwrap();
            let f = faer_sigma(&a);
            let scale = s[0].max(1e-300);
            for (x, y) in s.iter().zip(&f) {
                assert!(
                    (x - y).abs() <= 64.0 * n as f64 * f64::EPSILON * scale,
                    "{x} vs {y}"
                );
            }
            let v = v.unwrap();
            let vtv = v.transpose() * &v;
            assert!((vtv - DMatrix::identity(n, n)).amax() < 1e-13);
            let av = &a * &v;
            for (j, sj) in s.iter().enumerate() {
                assert!((av.column(j).norm() - sj).abs() <= 1e-13 * scale);
            }
        }
    }

    /// Rank-deficient and non-finite inputs.
    #[test]
    fn jacobi_rank_deficient_and_nan() {
        let a = DMatrix::from_row_slice(3, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 1.0, 0.0, 1.0]);
        let (s, _) = jacobi_svd(&a, false).unwrap();
        assert!(s[2] < 1e-15 * s[0] && s[1] > 0.1);
        let mut b = a.clone();
        b[(1, 2)] = f64::NAN;
        assert!(matches!(
            jacobi_svd(&b, false),
            Err(SpectralError::NonFinite { row: 1, col: 2 })
        ));
        assert_eq!(
            singular_values(&DMatrix::<f64>::zeros(2, 4)).unwrap().len(),
            2
        );
    }
}

#[cfg(test)]
mod doc_examples {
    //! The examples of this private module's items (not doctests: the module is
    //! not public).
    use super::*;

    #[test]
    fn svd_of_a_diagonal_matrix() {
        use nalgebra::DMatrix;
        let a = DMatrix::from_row_slice(3, 3, &[2.0, 0.0, 0.0, 0.0, -3.0, 0.0, 0.0, 0.0, 1.0]);
        assert_eq!(singular_values(&a).unwrap(), vec![3.0, 2.0, 1.0]);
        let (s, _v) = jacobi_svd(&a, false).unwrap();
        assert_eq!(s, vec![3.0, 2.0, 1.0]);
    }
}
