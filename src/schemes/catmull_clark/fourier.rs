//! Discrete-Fourier block diagonalisation of the Catmull-Clark family's
//! one-ring matrix (math doc section 6; Stam 1998, section 4 and appendix).
//!
//! The one-ring matrix `S` (order `[v, e_0..e_{n-1}, f_0..f_{n-1}]`) commutes
//! with the rotation `e_i -> e_{i+1}, f_i -> f_{i+1}`. In the unitary basis
//!
//! ```text
//! [v, ê_0, f̂_0, ê_1, f̂_1, .., ê_{n-1}, f̂_{n-1}],   ê_l = (1/sqrt n) sum_i w^{il} e_i,  w = exp(2 pi i / n)
//! ```
//!
//! (and the same for `f̂_l`) it is block diagonal: one 3 x 3 block for `l = 0`
//! (on `v, ê_0, f̂_0`) and one 2 x 2 block per frequency `l = 1..n-1`. With
//! `theta = 2 pi l / n`, the blocks **\[derived\]** from the rules of math doc
//! section 8 are
//!
//! ```text
//! l >= 1:  [[ 1/2 - c/4 + (c/4) cos theta,  (c/8)(1 + conj w^l) ],
//!           [ (1 + w^l)/4,                   1/4                 ]]
//!          trace 3/4 - c/4 + (c/4) cos theta, determinant (1 - c)/8
//! l = 0:   [[ 1 - c(4 - c)/n,       2c(2 - c)/n^1.5,    c^2/n^1.5  ],
//!           [ sqrt n (1/2 - c/4),   1/2,                c/4        ],
//!           [ sqrt n / 4,           1/2,                1/4        ]]
//!          eigenvalues 1 and the roots of
//!          lambda^2 - (3n - 16c + 4c^2)/(4n) lambda + (n(1 - c) - 8c + 12c^2 - 4c^3)/(8n)
//! ```
//!
//! At `c = 1/2` the `l >= 1` eigenvalues are Stam's
//! `[5 + cos theta +- cos(theta/2) sqrt(2 (9 + cos theta))] / 16` and the `l = 0`
//! ones `1, (3n - 7 +- sqrt(5n^2 - 30n + 49)) / (8n)`. The `l >= 1`
//! discriminant equals `(c - 1/2)^2/4` at its minimum (`theta = pi`), so those
//! eigenvalues are always real.
//!
//! ```
//! use subdiv_lab::schemes::catmull_clark::fourier::{stam_subdominant, subdominant};
//! assert!((subdominant(5, 0.5).unwrap() - stam_subdominant(5)).abs() < 1e-15);
//! assert!((stam_subdominant(3) - 0.410097).abs() < 1e-6);
//! ```

use crate::error::{Error, Result};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Agreement required between the closed-form blocks and the blocks of
/// `Q^H S Q` computed from the assembled matrix: the entries are `O(1)` and
/// each transformed entry is a sum of at most `4n^2` products with unit-modulus
/// factors, so rounding stays below `8 n^2 eps`, i.e. `1.2e-10` at `n = 256`
/// and below `1e-12` for `n <= 24`; we scale the tolerance with `n^2`.
pub const BLOCK_MATCH_TOL_PER_N2: f64 = 2e-15;

/// One Fourier block.
#[derive(Clone, Debug, PartialEq)]
pub struct FourierBlock {
    /// Frequency `l` (`0..n`).
    pub frequency: usize,
    /// The block: 3 x 3 on `(v, ê_0, f̂_0)` for `l = 0`, 2 x 2 on `(ê_l, f̂_l)` otherwise.
    pub matrix: DMatrix<Complex64>,
}

fn check(n: usize, c: f64) -> Result<()> {
    super::validate(n, &c)
}

/// The closed-form blocks for valence `n` and parameter `c`.
pub fn fourier_blocks(n: usize, c: f64) -> Result<Vec<FourierBlock>> {
    check(n, c)?;
    let nf = n as f64;
    let sn = nf.sqrt();
    let r = |x: f64| Complex64::new(x, 0.0);
    let mut out = Vec::with_capacity(n);
    out.push(FourierBlock {
        frequency: 0,
        matrix: DMatrix::from_row_slice(
            3,
            3,
            &[
                r(1.0 - c * (4.0 - c) / nf),
                r(2.0 * c * (2.0 - c) / (nf * sn)),
                r(c * c / (nf * sn)),
                r(sn * (0.5 - c / 4.0)),
                r(0.5),
                r(c / 4.0),
                r(sn / 4.0),
                r(0.5),
                r(0.25),
            ],
        ),
    });
    for l in 1..n {
        let theta = 2.0 * PI * l as f64 / nf;
        let w = Complex64::from_polar(1.0, theta);
        out.push(FourierBlock {
            frequency: l,
            matrix: DMatrix::from_row_slice(
                2,
                2,
                &[
                    r(0.5 - c / 4.0 + c / 4.0 * theta.cos()),
                    (Complex64::new(1.0, 0.0) + w.conj()) * (c / 8.0),
                    (Complex64::new(1.0, 0.0) + w) * 0.25,
                    r(0.25),
                ],
            ),
        });
    }
    Ok(out)
}

/// The unitary change of basis `Q` (columns `[v, ê_0, f̂_0, ê_1, f̂_1, ..]`).
pub fn fourier_basis(n: usize) -> DMatrix<Complex64> {
    let m = 2 * n + 1;
    let mut q = DMatrix::from_element(m, m, Complex64::new(0.0, 0.0));
    q[(0, 0)] = Complex64::new(1.0, 0.0);
    let s = 1.0 / (n as f64).sqrt();
    for l in 0..n {
        for i in 0..n {
            // Reduce i*l mod n before forming the angle: exact phases for large n.
            let phase = 2.0 * PI * ((i * l) % n) as f64 / n as f64;
            let z = Complex64::from_polar(s, phase);
            q[(1 + i, 1 + 2 * l)] = z;
            q[(1 + n + i, 2 + 2 * l)] = z;
        }
    }
    q
}

/// `Q^H S Q` of an assembled one-ring matrix `s`, cut into blocks, and the
/// largest modulus of an entry outside the blocks (zero up to rounding iff `s`
/// is rotationally symmetric).
pub fn transform(s: &DMatrix<f64>) -> Result<(Vec<FourierBlock>, f64)> {
    let m = s.nrows();
    if m < 7 || m % 2 == 0 || s.ncols() != m {
        return Err(Error::CountMismatch {
            what: "one-ring matrix size 2n+1 (n >= 3)",
            expected: 7.max(m | 1),
            got: m,
        });
    }
    let n = (m - 1) / 2;
    let q = fourier_basis(n);
    let sc = s.map(|x| Complex64::new(x, 0.0));
    let t = q.adjoint() * sc * &q;
    let block_of = |k: usize| if k < 3 { 0 } else { (k - 1) / 2 };
    let mut off = 0.0f64;
    for i in 0..m {
        for j in 0..m {
            if block_of(i) != block_of(j) {
                off = off.max(t[(i, j)].norm());
            }
        }
    }
    let mut blocks = vec![FourierBlock {
        frequency: 0,
        matrix: t.view((0, 0), (3, 3)).into_owned(),
    }];
    for l in 1..n {
        blocks.push(FourierBlock {
            frequency: l,
            matrix: t.view((1 + 2 * l, 1 + 2 * l), (2, 2)).into_owned(),
        });
    }
    Ok((blocks, off))
}

/// Roots of `x^2 - t x + d` (stable form; complex pair when the discriminant is negative).
fn quadratic_roots(t: f64, d: f64) -> [Complex64; 2] {
    let disc = t * t - 4.0 * d;
    if disc >= 0.0 {
        let q = 0.5 * (t + t.signum() * disc.sqrt());
        if q == 0.0 {
            return [Complex64::new(0.0, 0.0); 2];
        }
        [Complex64::new(q, 0.0), Complex64::new(d / q, 0.0)]
    } else {
        let im = 0.5 * (-disc).sqrt();
        [Complex64::new(0.5 * t, im), Complex64::new(0.5 * t, -im)]
    }
}

/// Closed-form eigenvalues of block `l` (3 for `l = 0`, the first being 1; 2 otherwise).
pub fn block_eigenvalues(n: usize, l: usize, c: f64) -> Result<Vec<Complex64>> {
    check(n, c)?;
    if l >= n {
        return Err(Error::InvalidParameter {
            name: "frequency",
            value: l.to_string(),
            reason: "the Fourier frequency must be in 0..n",
        });
    }
    let nf = n as f64;
    if l == 0 {
        let t0 = (3.0 * nf - 16.0 * c + 4.0 * c * c) / (4.0 * nf);
        let d0 = (nf * (1.0 - c) - 8.0 * c + 12.0 * c * c - 4.0 * c * c * c) / (8.0 * nf);
        let [a, b] = quadratic_roots(t0, d0);
        return Ok(vec![Complex64::new(1.0, 0.0), a, b]);
    }
    let cos = (2.0 * PI * l as f64 / nf).cos();
    let t = 0.75 - c / 4.0 + c / 4.0 * cos;
    let d = (1.0 - c) / 8.0;
    Ok(quadratic_roots(t, d).to_vec())
}

/// All `2n + 1` eigenvalues from the closed-form blocks, sorted by decreasing
/// modulus (ties by decreasing real part).
pub fn spectrum(n: usize, c: f64) -> Result<Vec<Complex64>> {
    let mut all = Vec::with_capacity(2 * n + 1);
    for l in 0..n {
        all.extend(block_eigenvalues(n, l, c)?);
    }
    all.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.re.total_cmp(&a.re)));
    Ok(all)
}

/// All `2n + 8` eigenvalues of the [`patch_matrix`](super::patch_matrix),
/// the family's second-order matrix (math doc section 13.5): [`spectrum`]
/// together with [`regular_part_eigenvalues`](super::regular_part_eigenvalues),
/// sorted as [`spectrum`].
///
/// ```
/// use subdiv_lab::schemes::catmull_clark::fourier::patch_spectrum;
/// let s = patch_spectrum(3, 0.75).unwrap();
/// assert_eq!(s.len(), 14);
/// // mu: the regular part's c/4, above the one-ring's 1/8
/// assert_eq!(s[3].re, 0.1875);
/// assert!((s[3].norm() / s[1].norm().powi(2) - 1.2438).abs() < 1e-4);
/// ```
pub fn patch_spectrum(n: usize, c: f64) -> Result<Vec<Complex64>> {
    let mut all = spectrum(n, c)?;
    all.extend(
        super::regular_part_eigenvalues(&c)
            .into_iter()
            .map(|x| Complex64::new(x, 0.0)),
    );
    all.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.re.total_cmp(&a.re)));
    Ok(all)
}

/// The largest modulus among the eigenvalues other than the (simple, `l = 0`) eigenvalue 1.
pub fn subdominant(n: usize, c: f64) -> Result<f64> {
    let mut best = 0.0f64;
    for l in 0..n {
        let ev = block_eigenvalues(n, l, c)?;
        let skip = if l == 0 { 1 } else { 0 };
        for z in &ev[skip..] {
            best = best.max(z.norm());
        }
    }
    Ok(best)
}

/// Stam's closed form of the Catmull-Clark subdominant eigenvalue (math doc
/// section 6): `[5 + cos(2 pi/n) + cos(pi/n) sqrt(2 (9 + cos(2 pi/n)))] / 16`.
pub fn stam_subdominant(n: usize) -> f64 {
    let nf = n as f64;
    let c2 = (2.0 * PI / nf).cos();
    (5.0 + c2 + (PI / nf).cos() * (2.0 * (9.0 + c2)).sqrt()) / 16.0
}

/// The real right eigenvectors of the `(2n+8)` patch matrix for the `+` root
/// `lambda` of Fourier block `l = 1` (the subdominant pair for
/// Catmull-Clark): the characteristic map's control net is `(x_1, x_2)`, and
/// the extended matrix maps it to the control nets of the first ring's three
/// regular sub-patches of sector 0 (sector `j` is the same net rotated by
/// `2 pi j / n`). See [`mode_patch_eigenvectors`] (`l = 1`).
/// Returns `(lambda, [x_cos, x_sin])`.
pub fn subdominant_patch_eigenvectors(
    n: usize,
    c: f64,
) -> Result<(f64, [nalgebra::DVector<f64>; 2])> {
    mode_patch_eigenvectors(n, c, 1)
}

/// The real right eigenvectors of the `(2n+8)` patch matrix for the larger
/// root `lambda` of Fourier block `l` (`1 <= l < n`). **\[derived\]**: with
/// `theta = 2 pi l / n`, on the one-ring `v -> 0`, `e_i -> cos(i theta)`,
/// `f_i -> (cos(i theta) + cos((i+1) theta)) / (4 lambda - 1)` (and the same
/// with sin), from the second row of the block (the face rule does not depend
/// on `c`); the 7 outer entries solve `(A_oo - lambda I) x_o = -A_or x_r`.
/// Sector `j`'s net is sector 0's rotated by `j theta` in the plane
/// `(x_cos, x_sin)`. Returns `(lambda, [x_cos, x_sin])`.
pub fn mode_patch_eigenvectors(
    n: usize,
    c: f64,
    l: usize,
) -> Result<(f64, [nalgebra::DVector<f64>; 2])> {
    if l == 0 || 2 * l == n {
        return Err(Error::InvalidParameter {
            name: "frequency",
            value: l.to_string(),
            reason: "modes 0 and n/2 have no rotating eigenvector pair; use l in 1..n with 2l != n",
        });
    }
    let ev = block_eigenvalues(n, l, c)?;
    let lambda = ev[0].re.max(ev[1].re);
    if (4.0 * lambda - 1.0).abs() <= 4.0 * f64::EPSILON {
        return Err(Error::Numerical {
            routine: "Fourier mode eigenvectors",
            reason: format!(
                "mode {l} at n = {n}, c = {c} has lambda = 1/4 (face entries undefined)"
            ),
        });
    }
    let a = super::patch_matrix::<f64>(n, &c)?.into_matrix();
    let lay = super::PatchLayout::new(n)?;
    let r = lay.one_ring_len();
    let theta = 2.0 * PI * l as f64 / n as f64;
    let make = |f: fn(f64) -> f64| -> Result<nalgebra::DVector<f64>> {
        let mut x = nalgebra::DVector::zeros(lay.patch_len());
        for i in 0..n {
            let (p, q) = (f(i as f64 * theta), f((i + 1) as f64 * theta));
            x[lay.e(i)] = p;
            x[lay.f(i)] = (p + q) / (4.0 * lambda - 1.0);
        }
        let a_oo = a.view((r, r), (7, 7)).into_owned() - DMatrix::identity(7, 7) * lambda;
        let rhs = -(a.view((r, 0), (7, r)) * x.rows(0, r));
        let xo = super::linear::solve_linear(a_oo, rhs)?;
        x.rows_mut(r, 7).copy_from(&xo);
        Ok(x)
    };
    Ok((lambda, [make(f64::cos)?, make(f64::sin)?]))
}
