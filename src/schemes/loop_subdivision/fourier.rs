//! Discrete-Fourier block diagonalisation of the Loop two-ring matrix (math
//! doc section 11) **\[derived\]**.
//!
//! The two-ring matrix `S` ([`super::matrix::two_ring_matrix`]) commutes with
//! the rotation `e_i -> e_{i+1}, g_i -> g_{i+1}, f_i -> f_{i+1}`. In the
//! unitary basis
//!
//! ```text
//! [v, ê_0, ĝ_0, f̂_0, ê_1, ĝ_1, f̂_1, .., ê_{n-1}, ĝ_{n-1}, f̂_{n-1}],
//! ê_l = (1/sqrt n) sum_i w^{il} e_i,   w = exp(2 pi i / n)   (likewise ĝ_l, f̂_l)
//! ```
//!
//! it is block diagonal. With `theta = 2 pi l / n`, the rules of
//! [`super::matrix`] give, for `l = 1..n-1` (order `ê_l, ĝ_l, f̂_l`),
//!
//! ```text
//! B_l = [[ 3/8 + cos(theta)/4,   0,      0                 ],
//!        [ 5/8 + cos(theta)/8,   1/16,   (1 + conj w^l)/16 ],
//!        [ 3 (1 + w^l)/8,        0,      1/8               ]]
//! ```
//!
//! and for `l = 0` (order `v, ê_0, ĝ_0, f̂_0`)
//!
//! ```text
//! B_0 = [[ 1 - n beta_n,   sqrt(n) beta_n,   0,      0    ],
//!        [ 3 sqrt(n)/8,    5/8,              0,      0    ],
//!        [ sqrt(n)/16,     3/4,              1/16,   1/8  ],
//!        [ sqrt(n)/8,      3/4,              0,      1/8  ]].
//! ```
//!
//! The one-ring part is the 1 x 1 block `3/8 + cos(theta)/4` (`l >= 1`) and
//! the 2 x 2 block on `(v, ê_0)` (`l = 0`, eigenvalues `1` and
//! `5/8 - n beta_n`); the two-ring adds the triangular `(ĝ_l, f̂_l)` part with
//! eigenvalues `1/16` and `1/8`. So the spectrum of `S` is
//!
//! ```text
//! 1,   5/8 - n beta_n = lambda^2,   3/8 + cos(2 pi l/n)/4 (l = 1..n-1),   1/16 (n times),   1/8 (n times)
//! ```
//!
//! with `lambda = 3/8 + cos(2 pi/n)/4` the subdominant eigenvalue (double:
//! `l = 1` and `l = n - 1`). Loop's `beta_n` is exactly the choice that makes
//! the `l = 0` eigenvalue `lambda^2` (`n beta_n = 5/8 - lambda^2`).
//!
//! ```
//! use subdiv_lab::schemes::loop_subdivision::fourier::{spectrum, subdominant};
//! let s = spectrum(6).unwrap();
//! assert_eq!(s.len(), 19);
//! assert!((s[0].re - 1.0).abs() < 1e-15 && (s[1].re - 0.5).abs() < 1e-15);
//! assert!((subdominant(3).unwrap() - 0.25).abs() < 1e-15);
//! ```

use super::{beta, check_size, subdominant_eigenvalue, TwoRing};
use crate::error::{Error, Result};
use crate::schemes::spectral_order;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Agreement required between the closed-form blocks and the blocks of
/// `Q^H S Q` computed from the assembled matrix, per `n^2`: the entries are
/// `O(1)` and each transformed entry sums at most `9 n^2` products with
/// unit-modulus factors `1/n`, so rounding stays below about `9 n^2 eps`
/// relative to `O(1)`; `4e-15 n^2` leaves a factor 2 (`1.6e-12` at `n = 20`).
pub const BLOCK_MATCH_TOL_PER_N2: f64 = 4e-15;

/// One Fourier block.
#[derive(Clone, Debug, PartialEq)]
pub struct FourierBlock {
    /// Frequency `l` (`0..n`).
    pub frequency: usize,
    /// 4 x 4 on `(v, ê_0, ĝ_0, f̂_0)` for `l = 0`, 3 x 3 on `(ê_l, ĝ_l, f̂_l)` otherwise.
    pub matrix: DMatrix<Complex64>,
}

fn r(x: f64) -> Complex64 {
    Complex64::new(x, 0.0)
}

/// `theta = 2 pi l / n` with `l` reduced mod `n` first (exact phases for large `n`).
fn angle(n: usize, l: usize) -> f64 {
    2.0 * PI * (l % n) as f64 / n as f64
}

fn check(n: usize) -> Result<()> {
    check_size(n, 16 * n as u128, "Fourier blocks")
}

/// The closed-form blocks of valence `n >= 3` (see the module docs).
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::fourier::fourier_blocks;
/// let b = fourier_blocks(4).unwrap();
/// assert_eq!(b.len(), 4);
/// assert_eq!(b[0].matrix.shape(), (4, 4));
/// assert!((b[1].matrix[(0, 0)].re - 0.375).abs() < 1e-15); // 3/8 + cos(pi/2)/4
/// ```
pub fn fourier_blocks(n: usize) -> Result<Vec<FourierBlock>> {
    check(n)?;
    let nf = n as f64;
    let sn = nf.sqrt();
    let b = beta(n);
    let mut out = Vec::with_capacity(n);
    out.push(FourierBlock {
        frequency: 0,
        matrix: DMatrix::from_row_slice(
            4,
            4,
            &[
                r(1.0 - nf * b),
                r(sn * b),
                r(0.0),
                r(0.0),
                r(3.0 * sn / 8.0),
                r(0.625),
                r(0.0),
                r(0.0),
                r(sn / 16.0),
                r(0.75),
                r(0.0625),
                r(0.125),
                r(sn / 8.0),
                r(0.75),
                r(0.0),
                r(0.125),
            ],
        ),
    });
    for l in 1..n {
        let theta = angle(n, l);
        let w = Complex64::from_polar(1.0, theta);
        let one = r(1.0);
        out.push(FourierBlock {
            frequency: l,
            matrix: DMatrix::from_row_slice(
                3,
                3,
                &[
                    r(0.375 + 0.25 * theta.cos()),
                    r(0.0),
                    r(0.0),
                    r(0.625 + 0.125 * theta.cos()),
                    r(0.0625),
                    (one + w.conj()) / 16.0,
                    (one + w) * 0.375,
                    r(0.0),
                    r(0.125),
                ],
            ),
        });
    }
    Ok(out)
}

/// The unitary change of basis `Q`, columns
/// `[v, ê_0, ĝ_0, f̂_0, ê_1, ĝ_1, f̂_1, ..]` over the two-ring layout.
pub fn fourier_basis(n: usize) -> Result<DMatrix<Complex64>> {
    let d = 3 * n as u128 + 1;
    check_size(n, 2 * d * d, "Fourier basis")?;
    let lay = TwoRing::new(n)?;
    let m = lay.len();
    let mut q = DMatrix::from_element(m, m, r(0.0));
    q[(0, 0)] = r(1.0);
    let s = 1.0 / (n as f64).sqrt();
    for l in 0..n {
        for i in 0..n {
            let z = Complex64::from_polar(s, angle(n, i * l));
            q[(lay.e(i), 1 + 3 * l)] = z;
            q[(lay.g(i), 2 + 3 * l)] = z;
            q[(lay.f(i), 3 + 3 * l)] = z;
        }
    }
    Ok(q)
}

/// `Q^H S Q` of an assembled two-ring matrix `s` (valence `(dim - 1)/3`), cut
/// into blocks, and the largest modulus of an entry outside the blocks (zero
/// up to rounding iff `s` is rotationally symmetric).
pub fn transform(s: &DMatrix<f64>) -> Result<(Vec<FourierBlock>, f64)> {
    let dim = s.nrows();
    if s.ncols() != dim || dim < 10 || (dim - 1) % 3 != 0 {
        return Err(Error::CountMismatch {
            what: "two-ring matrix (square, 3n + 1 rows, n >= 3)",
            expected: 3 * ((dim.max(10) - 1) / 3) + 1,
            got: dim,
        });
    }
    let n = (dim - 1) / 3;
    let q = fourier_basis(n)?;
    let sc = s.map(r);
    let t = q.adjoint() * sc * &q;
    let block_of = |k: usize| if k == 0 { 0 } else { (k - 1) / 3 };
    let mut off = 0.0f64;
    for i in 0..dim {
        for j in 0..dim {
            if block_of(i) != block_of(j) {
                off = off.max(t[(i, j)].norm());
            }
        }
    }
    let mut blocks = Vec::with_capacity(n);
    blocks.push(FourierBlock {
        frequency: 0,
        matrix: t.view((0, 0), (4, 4)).into_owned(),
    });
    for l in 1..n {
        blocks.push(FourierBlock {
            frequency: l,
            matrix: t.view((1 + 3 * l, 1 + 3 * l), (3, 3)).into_owned(),
        });
    }
    Ok((blocks, off))
}

/// Eigenvalues of block `l` in closed form: `[1, 5/8 - n beta_n, 1/16, 1/8]`
/// for `l = 0`, `[3/8 + cos(2 pi l/n)/4, 1/16, 1/8]` otherwise.
pub fn block_eigenvalues(n: usize, l: usize) -> Result<Vec<Complex64>> {
    check(n)?;
    if l >= n {
        return Err(Error::InvalidParameter {
            name: "frequency",
            value: l.to_string(),
            reason: "the frequency must be in 0..n",
        });
    }
    if l == 0 {
        return Ok(vec![
            r(1.0),
            r(0.625 - n as f64 * beta(n)),
            r(0.0625),
            r(0.125),
        ]);
    }
    Ok(vec![
        r(0.375 + 0.25 * angle(n, l).cos()),
        r(0.0625),
        r(0.125),
    ])
}

/// All `3n + 1` eigenvalues of the two-ring matrix from the closed-form
/// blocks, in the crate's order ([`spectral_order`]: non-increasing modulus,
/// then larger real part).
pub fn spectrum(n: usize) -> Result<Vec<Complex64>> {
    check(n)?;
    let mut all = Vec::with_capacity(3 * n + 1);
    for l in 0..n {
        all.extend(block_eigenvalues(n, l)?);
    }
    all.sort_by(spectral_order);
    Ok(all)
}

/// The largest modulus among the eigenvalues other than the (simple, `l = 0`)
/// eigenvalue 1, from the blocks; equals `3/8 + cos(2 pi/n)/4`
/// ([`subdominant_eigenvalue`]) for every `n >= 3` (tested).
pub fn subdominant(n: usize) -> Result<f64> {
    let mut best = 0.0f64;
    for l in 0..n {
        let ev = block_eigenvalues(n, l)?;
        let skip = usize::from(l == 0);
        for z in &ev[skip..] {
            best = best.max(z.norm());
        }
    }
    Ok(best)
}

/// The real right eigenvectors of the two-ring matrix for the subdominant
/// eigenvalue `lambda = 3/8 + cos(theta)/4`, `theta = 2 pi / n` **\[derived\]**
/// (from block `B_1`: solve its rows for `ĝ_1`, `f̂_1` with `ê_1 = 1`):
///
/// ```text
/// v -> 0,   e_i -> cos(i theta),   g_i -> (13 + 2 cos theta) / (5 + 4 cos theta) cos(i theta),
/// f_i -> 3 (cos(i theta) + cos((i+1) theta)) / (2 (1 + cos theta))
/// ```
///
/// and the same with `sin`. At `n = 6` these are the lattice coordinates of
/// the regular two-ring (`g_i = 2 e_i`, `f_i = e_i + e_{i+1}`). Returns
/// `(lambda, [x_cos, x_sin])` in the layout of [`TwoRing`].
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::fourier::subdominant_eigenvectors;
/// use subdiv_lab::schemes::loop_subdivision::TwoRing;
/// let (lambda, [xc, _]) = subdominant_eigenvectors(6).unwrap();
/// let r = TwoRing::new(6).unwrap();
/// assert!((lambda - 0.5).abs() < 1e-15);
/// assert!((xc[r.g(0)] - 2.0).abs() < 1e-14 && (xc[r.f(0)] - 1.5).abs() < 1e-14);
/// ```
pub fn subdominant_eigenvectors(n: usize) -> Result<(f64, [Vec<f64>; 2])> {
    check(n)?;
    let lay = TwoRing::new(n)?;
    let theta = angle(n, 1);
    let c = theta.cos();
    let gw = (13.0 + 2.0 * c) / (5.0 + 4.0 * c);
    let fw = 3.0 / (2.0 * (1.0 + c));
    let make = |f: fn(f64) -> f64| {
        let mut x = vec![0.0; lay.len()];
        for i in 0..n {
            let (p, q) = (f(angle(n, i)), f(angle(n, i + 1)));
            x[lay.e(i)] = p;
            x[lay.g(i)] = gw * p;
            x[lay.f(i)] = fw * (p + q);
        }
        x
    };
    Ok((subdominant_eigenvalue(n), [make(f64::cos), make(f64::sin)]))
}

/// Tangent stencils over the one-ring `[v, e_0..e_{n-1}]`: the two real left
/// eigenvectors of the one-ring matrix for the subdominant eigenvalue
/// `lambda` (math doc section 11):
///
/// ```text
/// t_1: v -> 0, e_i -> cos(2 pi i / n);     t_2: v -> 0, e_i -> sin(2 pi i / n)
/// ```
///
/// (`sum_i cos(2 pi i/n) = 0` kills the `v` column; the `e` columns give
/// `cos(i theta) (3/8 + cos(theta)/4)`). On the two-ring they are padded with
/// zeros on `g_i`, `f_i` (block lower-triangular matrix). Returns
/// `(lambda, [t_1, t_2])`.
pub fn tangent_stencils(n: usize) -> Result<(f64, [Vec<f64>; 2])> {
    check(n)?;
    let make = |f: fn(f64) -> f64| {
        let mut t = vec![0.0; n + 1];
        for (i, x) in t.iter_mut().skip(1).enumerate() {
            *x = f(angle(n, i));
        }
        t
    };
    Ok((subdominant_eigenvalue(n), [make(f64::cos), make(f64::sin)]))
}

#[cfg(test)]
mod tests {
    use super::super::matrix::two_ring_matrix;
    use super::*;

    #[test]
    fn closed_form_blocks_match_the_assembled_matrix() {
        for n in 3..=20 {
            let s = two_ring_matrix(n).unwrap();
            let (blocks, off) = transform(s.matrix()).unwrap();
            let tol = BLOCK_MATCH_TOL_PER_N2 * (n * n) as f64;
            assert!(off < tol, "n = {n}: off-block {off:e}");
            for (b, c) in blocks.iter().zip(fourier_blocks(n).unwrap()) {
                assert_eq!(b.frequency, c.frequency);
                let d = (&b.matrix - &c.matrix)
                    .iter()
                    .map(|z| z.norm())
                    .fold(0.0, f64::max);
                assert!(d < tol, "n = {n}, l = {}: {d:e}", b.frequency);
            }
        }
    }

    #[test]
    fn block_eigenvalues_are_the_eigenvalues_of_the_blocks() {
        for n in 3..=12 {
            for b in fourier_blocks(n).unwrap() {
                let re = b.matrix.map(|z| z.re);
                let im = b.matrix.map(|z| z.im);
                // the blocks are complex: compare characteristic polynomials at the claimed roots
                for mu in block_eigenvalues(n, b.frequency).unwrap() {
                    let k = re.nrows();
                    let m = DMatrix::from_fn(k, k, |i, j| {
                        Complex64::new(re[(i, j)], im[(i, j)]) - if i == j { mu } else { r(0.0) }
                    });
                    assert!(
                        m.determinant().norm() < 1e-14,
                        "n = {n}, l = {}",
                        b.frequency
                    );
                }
            }
        }
    }

    #[test]
    fn subdominant_is_the_closed_form_and_l0_is_its_square() {
        for n in 3..=64 {
            let want = 0.375 + 0.25 * (2.0 * PI / n as f64).cos();
            assert!((subdominant(n).unwrap() - want).abs() < 1e-15, "n = {n}");
            let l0 = block_eigenvalues(n, 0).unwrap()[1].re;
            assert!((l0 - want * want).abs() < 1e-15, "n = {n}");
            let s = spectrum(n).unwrap();
            assert_eq!(s.len(), 3 * n + 1);
            assert_eq!(s[0], r(1.0));
            assert!((s[1].re - want).abs() < 1e-15 && (s[2].re - want).abs() < 1e-15);
            assert!(s[3].re < want - 1e-6, "n = {n}: subdominant not separated");
        }
    }

    #[test]
    fn valence_three_has_a_jordan_block_at_one_sixteenth() {
        // rank of S - I/16 on the l = 0 block is 3 (geometric multiplicity 1,
        // algebraic 2): the reason for the wider tolerance of the dense comparison
        // (`crate::spectral` closed-form tests)
        let b = &fourier_blocks(3).unwrap()[0].matrix;
        let m = b.map(|z| z.re) - DMatrix::identity(4, 4) * 0.0625;
        let sv = m.singular_values();
        assert!(sv[2] > 1e-2, "{sv}");
        assert!(sv[3] < 1e-14, "{sv}");
        let m2 = &m * &m;
        let sv2 = m2.singular_values();
        assert!(sv2[2] < 1e-14, "(S - I/16)^2 has rank 2: {sv2}");
    }

    #[test]
    fn subdominant_right_eigenvectors_have_small_residuals() {
        for n in 3..=20 {
            let s = two_ring_matrix(n).unwrap();
            let (lam, xs) = subdominant_eigenvectors(n).unwrap();
            for x in xs {
                let xv = nalgebra::DVector::from_vec(x);
                let res = (s.matrix() * &xv - &xv * lam).norm() / xv.norm();
                assert!(res < 1e-14, "n = {n}: {res:e}");
            }
        }
    }

    #[test]
    fn invalid_input() {
        assert!(spectrum(2).is_err());
        assert!(block_eigenvalues(5, 5).is_err());
        assert!(transform(&DMatrix::zeros(11, 11)).is_err());
        assert!(spectrum(1_000_000_000).is_err());
    }
}
