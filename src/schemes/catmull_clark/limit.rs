//! Limit-point stencils of the Catmull-Clark family.
//!
//! The limit position of the extraordinary vertex is `l^T M` over the one-ring
//! `M = [v, e_0..e_{n-1}, f_0..f_{n-1}]`, where `l` is the left eigenvector of
//! the one-ring matrix for the eigenvalue 1, normalised to sum 1.
//!
//! * Catmull-Clark (`c = 1/2`): `(n^2 v + 4 sum e_i + sum f_i) / (n (n + 5))`
//!   (Halstead, Kass and DeRose, "Efficient, fair interpolation using
//!   Catmull-Clark surfaces", SIGGRAPH 1993, appendix).
//! * Shape-adjustable scheme **\[derived\]** (from the rules of math doc
//!   section 8; the Fourier `l = 0` block gives three scalar equations):
//!   `(n^2 v + 8c sum e_i + 4c^2 sum f_i) / (n (n + 8c + 4c^2))`. At `n = 4`
//!   this is the tensor square of the univariate limit mask
//!   `(c/2, 1, c/2) / (1 + c)`.
//!
//! Both are checked against [`left_fixed_vector`], a linear solve on the
//! assembled matrix (exact for rationals), in the tests.

use crate::error::Result;
use crate::scalar::Scalar;
use nalgebra::{DMatrix, DVector};

/// Closed-form limit-point stencil over the one-ring (length `2n + 1`).
///
/// ```
/// use subdiv_lab::scalar::{Rational, Scalar};
/// use subdiv_lab::schemes::catmull_clark::limit::limit_stencil;
/// let l = limit_stencil::<Rational>(3, &Rational::frac(1, 2)).unwrap();
/// assert_eq!(l[0], Rational::frac(9, 24));   // n^2 / (n (n + 5))
/// assert_eq!(l[1], Rational::frac(4, 24));
/// assert_eq!(l[4], Rational::frac(1, 24));
/// ```
pub fn limit_stencil<T: Scalar>(n: usize, c: &T) -> Result<Vec<T>> {
    super::validate(n, c)?;
    let nn = T::frac(n as i64, 1);
    let we = T::frac(8, 1) * c.clone();
    let wf = T::frac(4, 1) * c.clone() * c.clone();
    let den = nn.clone() * (nn.clone() + we.clone() + wf.clone());
    let mut l = Vec::with_capacity(2 * n + 1);
    l.push(nn.clone() * nn / den.clone());
    l.extend((0..n).map(|_| we.clone() / den.clone()));
    l.extend((0..n).map(|_| wf.clone() / den.clone()));
    Ok(l)
}

pub use super::linear::{solve_linear, SINGULAR_PIVOT_TOL};

/// The left eigenvector `l` of a square matrix `s` for the eigenvalue 1,
/// normalised to `sum l = 1`, by one linear solve (`(s^T - I) l = 0` with the
/// last equation replaced by `sum l = 1`). Fails if 1 is not a simple
/// eigenvalue with a left eigenvector of non-zero sum.
pub fn left_fixed_vector<T: Scalar>(s: &DMatrix<T>) -> Result<Vec<T>> {
    let n = s.nrows();
    let mut a = s.transpose();
    for i in 0..n {
        a[(i, i)] = a[(i, i)].clone() - T::one();
    }
    for j in 0..n {
        a[(n - 1, j)] = T::one();
    }
    let mut b = DVector::from_element(n, T::zero());
    b[n - 1] = T::one();
    Ok(solve_linear(a, b)?.iter().cloned().collect())
}

/// Tangent stencils **\[derived\]**: the two real left eigenvectors of the
/// one-ring matrix for the `+` root `lambda` of Fourier block `l = 1` (the
/// subdominant eigenvalue for Catmull-Clark; for the adjustable scheme compare
/// with [`super::fourier::subdominant`]). With `theta = 2 pi / n`:
///
/// ```text
/// t_1: v -> 0,  e_i -> cos(i theta),  f_i -> c (cos(i theta) + cos((i+1) theta)) / (8 lambda - 2)
/// t_2: the same with sin
/// ```
///
/// At `c = 1/2` this is, up to the factor `A_n = 16 lambda - 4 =
/// 1 + cos(2 pi/n) + cos(pi/n) sqrt(2 (9 + cos(2 pi/n)))`, the classical
/// Catmull-Clark tangent mask `e_i: A_n cos(2 pi i/n)`,
/// `f_i: cos(2 pi i/n) + cos(2 pi (i+1)/n)` (Halstead, Kass and DeRose 1993).
/// Returns `(lambda, [t_1, t_2])`, each over `[v, e_0.., f_0..]`.
pub fn tangent_stencils(n: usize, c: f64) -> Result<(f64, [Vec<f64>; 2])> {
    let ev = super::fourier::block_eigenvalues(n, 1, c)?;
    let lambda = ev[0].re.max(ev[1].re);
    let theta = 2.0 * std::f64::consts::PI / n as f64;
    let scale = c / (8.0 * lambda - 2.0);
    let mk = |f: fn(f64) -> f64| {
        let mut t = vec![0.0; 2 * n + 1];
        for i in 0..n {
            let (a, b) = (f(i as f64 * theta), f((i + 1) as f64 * theta));
            t[1 + i] = a;
            t[1 + n + i] = scale * (a + b);
        }
        t
    };
    Ok((lambda, [mk(f64::cos), mk(f64::sin)]))
}
