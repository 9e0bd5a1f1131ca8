//! Subdominant eigenvectors of `S_n` from eigenvectors of the face block.
//!
//! Math doc section 4: `S_n` is block lower-triangular, P block `A` (the face
//! block), E block = `n` decoupled 2x2 blocks `B_i`, C block `= I/16`:
//!
//! ```text
//! S_n = [ A   0   0  ]        v = [ a ]       A a = lambda a
//!       [ G   B   0  ]            [ e ]       (lambda I - B_i) e_i = (G a)_i
//!       [ H   K  I/16]            [ c ]       (lambda - 1/16) c_i = (H a + K e)_i
//! ```
//!
//! so an invariant subspace of `A` whose eigenvalues avoid
//! `spec(B) U {1/16} = {1/4, 1/8, 1/16}` lifts to one of `S_n`. A subdominant
//! pair of a `standard`, `real_distinct` or `complex_pair` configuration has
//! `|lambda| > |lambda_3| >= 1/4`, so the lift always applies.
//! The block structure is verified on the given matrix (a perturbed matrix
//! without it is rejected).
//!
//! [`subdominant_basis`] works with the whole 2-D real invariant subspace at
//! once, which is well conditioned even when `lambda_1` and `lambda_2` nearly
//! coincide (the individual eigenvectors are not): the subspace of the face
//! block is the null space of the real matrix
//!
//! ```text
//! Q = (A - lambda_1 I)(A - lambda_2 I) = A^2 - (lambda_1 + lambda_2) A + lambda_1 lambda_2 I
//! ```
//!
//! (real for all three eigenstructures), computed as the right singular
//! vectors of its two smallest singular values (faer SVD). With `W_a` that
//! orthonormal basis and `M = W_a^T A W_a`, the E and C parts of `S_n`'s
//! invariant subspace `S W = W M` follow from the block equations
//!
//! ```text
//! B_i X_i - X_i M = -G_i W_a                  (a 4x4 linear system per edge)
//! X_c,i (M - S_cc I) = H_i W_a + K_i W_e       (a 2x2 system per corner).
//! ```

use super::{Eigenstructure, PlanarBasis};
use crate::error::{Error, Result};
use crate::schemes::doo_sabin::Layout;
use crate::schemes::LocalScheme;
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Smallest accepted pivot (relative to the largest entry) in the small solves
/// of the lift; a pair that close to `1/4, 1/8, 1/16` is not subdominant for
/// any classified configuration.
pub const LIFT_PIVOT_MIN: f64 = 1e-10;

/// Verifies the block lower-triangular structure of math doc section 4.
fn check_structure(s: &DMatrix<f64>, n: usize) -> Result<()> {
    let lay = Layout::new(n);
    let not_block = |row: usize, col: usize| {
        Error::Numerical {
        routine: "eigenvector lift",
        reason: format!(
            "S_n is not block lower-triangular as in math doc section 4 (entry ({row}, {col}) = {})",
            s[(row, col)]
        ),
    }
    };
    // Structure check: P rows only P columns; E rows of edge i only P and their own E columns;
    // C rows only P, E and their own C column.
    for i in 0..n {
        for col in n..4 * n {
            if s[(lay.p(i), col)] != 0.0 {
                return Err(not_block(lay.p(i), col));
            }
        }
        for row in [lay.e1(i), lay.e2(i)] {
            for col in n..4 * n {
                if col != lay.e1(i) && col != lay.e2(i) && s[(row, col)] != 0.0 {
                    return Err(not_block(row, col));
                }
            }
        }
        for col in 3 * n..4 * n {
            if col != lay.c(i) && s[(lay.c(i), col)] != 0.0 {
                return Err(not_block(lay.c(i), col));
            }
        }
    }
    Ok(())
}

/// Solves the small dense system `m x = b` (Gaussian elimination with partial pivoting).
fn solve_small<const K: usize>(mut m: [[f64; K]; K], mut b: [f64; K]) -> Option<[f64; K]> {
    let scale = m.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    for col in 0..K {
        let piv = (col..K).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        let p = m[piv][col].abs();
        if p.is_nan() || p <= LIFT_PIVOT_MIN * scale {
            return None;
        }
        m.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..K {
            let f = m[r][col] / m[col][col];
            let pivot_row = m[col];
            for (x, y) in m[r][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * y;
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; K];
    for r in (0..K).rev() {
        let mut acc = b[r];
        for c in r + 1..K {
            acc -= m[r][c] * x[c];
        }
        x[r] = acc / m[r][r];
    }
    Some(x)
}

/// Lifts an invariant subspace `A W_a = W_a M` of the face block (`W_a`: `n x 2`,
/// column-major pairs) to the invariant subspace `S W = W M` of `S_n` (`4n x 2`).
pub fn lift_subspace(s: &DMatrix<f64>, wa: &[[f64; 2]], m: [[f64; 2]; 2]) -> Result<Vec<[f64; 2]>> {
    let n = wa.len();
    if s.nrows() != 4 * n || s.ncols() != 4 * n {
        return Err(Error::CountMismatch {
            what: "rows of S_n (4n for a face-block basis with n rows)",
            expected: 4 * n,
            got: s.nrows(),
        });
    }
    check_structure(s, n)?;
    let lay = Layout::new(n);
    let singular = |what: String| Error::Numerical {
        routine: "invariant subspace lift",
        reason: what,
    };
    let mut w = vec![[0.0; 2]; 4 * n];
    w[..n].copy_from_slice(wa);
    let gw = |row: usize, k: usize| -> f64 { (0..n).map(|j| s[(row, lay.p(j))] * wa[j][k]).sum() };
    for i in 0..n {
        let rows = [lay.e1(i), lay.e2(i)];
        let b = [
            [s[(rows[0], rows[0])], s[(rows[0], rows[1])]],
            [s[(rows[1], rows[0])], s[(rows[1], rows[1])]],
        ];
        // unknowns x = vec(X) column-major: [X00, X10, X01, X11]; equation (a, k):
        // sum_c B[a][c] X[c][k] - sum_l X[a][l] M[l][k] = -(G W_a)[a][k]
        let mut sys = [[0.0; 4]; 4];
        let mut rhs = [0.0; 4];
        for k in 0..2 {
            for a in 0..2 {
                let eq = 2 * k + a;
                for c in 0..2 {
                    sys[eq][2 * k + c] += b[a][c];
                }
                for l in 0..2 {
                    sys[eq][2 * l + a] -= m[l][k];
                }
                rhs[eq] = -gw(rows[a], k);
            }
        }
        let x = solve_small(sys, rhs)
            .ok_or_else(|| singular(format!("the pair shares an eigenvalue with E block {i}")))?;
        w[rows[0]] = [x[0], x[2]];
        w[rows[1]] = [x[1], x[3]];
    }
    for i in 0..n {
        let row = lay.c(i);
        let scc = s[(row, row)];
        let mut r = [gw(row, 0), gw(row, 1)];
        for col in n..3 * n {
            let v = s[(row, col)];
            if v != 0.0 {
                r[0] += v * w[col][0];
                r[1] += v * w[col][1];
            }
        }
        // X (M - scc I) = r  <=>  (M - scc I)^T X^T = r^T
        let mt = [[m[0][0] - scc, m[1][0]], [m[0][1], m[1][1] - scc]];
        let x = solve_small(mt, r)
            .ok_or_else(|| singular("the pair shares an eigenvalue with the C block".to_owned()))?;
        w[row] = x;
    }
    Ok(w)
}

/// An orthonormal basis of the subdominant real invariant subspace of a
/// Doo-Sabin-family configuration, for the eigenvalues `lambda` (from the
/// classification) and the gap `|lambda_2| - |lambda_3|` (capped by
/// `1 - |lambda_1|`).
pub fn subdominant_basis(
    scheme: &LocalScheme<f64>,
    sn: &DMatrix<f64>,
    structure: Eigenstructure,
    lambda: [Complex64; 2],
    gap: f64,
) -> Result<PlanarBasis> {
    let a = scheme.face_block()?;
    let n = a.nrows();
    let tr = (lambda[0] + lambda[1]).re;
    let det = (lambda[0] * lambda[1]).re;
    let q = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        let mut v = 0.0;
        for k in 0..n {
            v += a[(i, k)] * a[(k, j)];
        }
        v - tr * a[(i, j)] + if i == j { det } else { 0.0 }
    });
    let wa: Vec<[f64; 2]> = match q.svd() {
        Ok(svd) => {
            let v = svd.V();
            (0..n).map(|i| [v[(i, n - 2)], v[(i, n - 1)]]).collect()
        }
        // fallback route: the one-sided Jacobi SVD with vectors
        Err(_) => {
            let qd = DMatrix::from_fn(n, n, |i, j| q[(i, j)]);
            let v = crate::spectral::svd::jacobi_svd(&qd, true)
                .ok()
                .and_then(|(_, v)| v)
                .ok_or_else(|| Error::Numerical {
                    routine: "subdominant subspace (SVD)",
                    reason: format!("no convergence for n = {n}"),
                })?;
            (0..n).map(|i| [v[(i, n - 2)], v[(i, n - 1)]]).collect()
        }
    };
    let mut m = [[0.0; 2]; 2];
    for (r, mr) in m.iter_mut().enumerate() {
        for (c, mrc) in mr.iter_mut().enumerate() {
            let mut acc = 0.0;
            for i in 0..n {
                let mut aw = 0.0;
                for j in 0..n {
                    aw += a[(i, j)] * wa[j][c];
                }
                acc += wa[i][r] * aw;
            }
            *mrc = acc;
        }
    }
    let w = lift_subspace(sn, &wa, m)?;
    let w1: Vec<f64> = w.iter().map(|p| p[0]).collect();
    let w2: Vec<f64> = w.iter().map(|p| p[1]).collect();
    PlanarBasis::new(sn, structure, lambda, &w1, &w2, gap)
}
