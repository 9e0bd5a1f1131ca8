//! Dense linear solves of the Catmull-Clark family's closed forms (limit
//! stencils, eigenvectors): a leaf module shared by [`super::limit`] and
//! [`super::fourier`].

use crate::error::{Error, Result};
use crate::scalar::Scalar;
use nalgebra::{DMatrix, DVector};

/// Relative pivot threshold of [`solve_linear`] in `f64`: a pivot smaller
/// than this times the largest entry of the matrix is treated as singular.
/// The systems solved here (one-ring and patch matrices minus the identity,
/// one row replaced by ones) have entries in `[-1, 1]` and condition numbers
/// below `1e4` for `n <= 256`, so genuine pivots are many orders larger.
pub const SINGULAR_PIVOT_TOL: f64 = 1e-13;

/// Solves `a x = b` by Gaussian elimination with partial pivoting, over any
/// [`Scalar`] (exact for rationals).
pub fn solve_linear<T: Scalar>(mut a: DMatrix<T>, mut b: DVector<T>) -> Result<DVector<T>> {
    let n = a.nrows();
    if a.ncols() != n || b.len() != n {
        return Err(Error::CountMismatch {
            what: "linear system (square matrix, matching right-hand side)",
            expected: n,
            got: a.ncols().min(b.len()),
        });
    }
    let scale = a.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| {
                a[(i, k)]
                    .abs()
                    .partial_cmp(&a[(j, k)].abs())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(k);
        let piv = a[(p, k)].clone();
        let singular = if T::EXACT {
            piv.is_zero()
        } else {
            piv.to_f64().abs().is_nan() || piv.to_f64().abs() <= SINGULAR_PIVOT_TOL * scale
        };
        if singular {
            return Err(Error::Numerical {
                routine: "linear solve",
                reason: format!("singular system (pivot {} in column {k})", piv.to_text()),
            });
        }
        a.swap_rows(k, p);
        b.swap_rows(k, p);
        for i in k + 1..n {
            let f = a[(i, k)].clone() / a[(k, k)].clone();
            if f.is_zero() {
                continue;
            }
            for j in k..n {
                let t = f.clone() * a[(k, j)].clone();
                a[(i, j)] = a[(i, j)].clone() - t;
            }
            let t = f * b[k].clone();
            b[i] = b[i].clone() - t;
        }
    }
    let mut x = DVector::from_element(n, T::zero());
    for k in (0..n).rev() {
        let mut s = b[k].clone();
        for j in k + 1..n {
            s = s - a[(k, j)].clone() * x[j].clone();
        }
        x[k] = s / a[(k, k)].clone();
    }
    Ok(x)
}
