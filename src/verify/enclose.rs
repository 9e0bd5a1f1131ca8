//! Rigorous eigenvalue enclosures of the NURDS face block over a box of
//! edge ratios (math doc section 15).
//!
//! **The matrix family.** The face block is `A(r) = (I + R(r) + 1 c^T)/4`
//! (math doc section 4) with `R` affine in `r`. `R 1 = 2 * 1` for every `r`,
//! so in the basis `T = [1, e_1, .., e_{n-1}]` the block is upper block
//! triangular and `spec(A) = {1} U spec(C(r))` with the `(n-1) x (n-1)` matrix
//!
//! ```text
//! C(r)_{ab} = ( delta_ab + R_{a+1, b+1} - R_{0, b+1} ) / 4      (a, b = 0 .. n-2)
//! ```
//!
//! **\[derived\]** (`T^{-1} y = (y_0, y_1 - y_0, ..)`, `T^{-1} 1 = e_0`, so the
//! rank-one term `1 c^T` only touches row 0). `C` is affine in `r`:
//! `C(r) = C_0 + sum_k r_k C_k` with entries that are multiples of `1/4`
//! (exact in `f64`).
//!
//! **Even `n` \[derived\].** The alternating vector `y = (1, -1, 1, ..)` is a
//! left null vector of `R` (column `j` of `R` holds `r_j`, `1 - r_{j-1} + r_j`,
//! `1 - r_{j-1}`), and `y^T 1 = 0`, so `y^T A = y^T / 4`: every even-sided
//! face block has the eigenvalue `1/4` for all ratios. It is removed exactly
//! as well: with `w = (y_1, .., y_{n-1})`, `w^T C = w^T / 4`, and with `S` the
//! identity whose row 0 is `w^T`, row 0 of `S C S^{-1}` is `e_0^T / 4`; the
//! remaining `(n-2)`-square block `C'_{ij} = C_{ij} - C_{i0} w_j / w_0`
//! (`i, j >= 1`) is again affine in `r`. Then `spec(A) = {1, 1/4} U spec(C')`.
//! Both reductions are tested against the eigenvalues of the assembled face
//! block.
//!
//! **The enclosure.** At the cell centre `r0` (a float) take a numerical
//! eigen-decomposition `C(r0) ~ V D V^{-1}` and a numerical inverse `X` of
//! `V`. In interval arithmetic: `E = I - X V`; if `beta = ||E||_inf < 1/2`,
//! `V` is invertible and `||V^{-1} - X||_inf <= beta ||X||_inf / (1 - beta)`
//! (Neumann series), so an interval matrix `Y` contains `V^{-1}`. For every
//! `r` in the cell,
//!
//! ```text
//! V^{-1} C(r) V  in  M0 + [-G, G],   M0 = Y C(r0) V,   G = sum_k h_k |Y C_k V|
//! ```
//!
//! with `h_k` the half-widths. Gershgorin's theorem on this interval matrix
//! (rows, and separately columns) gives discs that contain every eigenvalue
//! of every `C(r)` in the cell, and a union of `k` discs disjoint from the
//! others contains exactly `k` of them (continuity: shrinking the
//! off-diagonal part keeps each disc of the actual matrix inside ours).

use super::interval::{Ci, Disc, Iv};
use crate::spectral::eigen::{Eigen, EigenOptions};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Largest accepted `||I - X V||_inf` for the verified inverse: below `1/2`
/// the Neumann bound at most doubles `||X||` times `beta`; a larger residual
/// means an ill-conditioned eigenvector basis (near a defective pair), where
/// the discs would be useless anyway.
pub const MAX_INVERSE_RESIDUAL: f64 = 0.5;

/// How the enclosure may be weakened on purpose, to show that the soundness
/// tests catch an unsound enclosure. Never used outside tests.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Tamper {
    /// The sound enclosure.
    #[default]
    None,
    /// Omit the variation over the cell (`G = 0`): the discs only hold at
    /// the centre.
    DropVariation,
}

/// An affine matrix family `C(x) = C_0 + sum_k x_k C_k` of size `m`.
#[derive(Clone, Debug)]
pub struct AffineFamily {
    m: usize,
    c0: Vec<f64>,
    terms: Vec<Vec<(usize, usize, f64)>>,
}

impl AffineFamily {
    /// The deflated NURDS face-block family `C(r)` of valence `n >= 3`
    /// (module docs).
    ///
    /// ```
    /// use subdiv_lab::verify::enclose::AffineFamily;
    /// let f = AffineFamily::nurds(3);
    /// assert_eq!(f.dim(), 2);
    /// // uniform ratios: C = diag-free 2x2 with eigenvalues 3/8, 3/8
    /// let c = f.at(&[0.5; 3]);
    /// let (t, d) = (c[0] + c[3], c[0] * c[3] - c[1] * c[2]);
    /// assert!((t - 0.75).abs() < 1e-15 && (d - 0.140625).abs() < 1e-15);
    /// ```
    pub fn nurds(n: usize) -> Self {
        let m = n - 1;
        // R as affine entries: (row, col) -> (const, [(k, coef)])
        let mut rc = vec![0.0; n * n];
        let mut rt: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n * n];
        for i in 0..n {
            let im1 = (i + n - 1) % n;
            let ip1 = (i + 1) % n;
            rt[i * n + im1].push((im1, 1.0));
            rc[i * n + i] += 1.0;
            rt[i * n + i].push((im1, -1.0));
            rt[i * n + i].push((i, 1.0));
            rc[i * n + ip1] += 1.0;
            rt[i * n + ip1].push((i, -1.0));
        }
        // dense affine pieces: index 0 = constant, 1 + k = coefficient of r_k
        let mut dense = vec![vec![0.0; m * m]; n + 1];
        for a in 0..m {
            for b in 0..m {
                let (i, j) = (a + 1, b + 1);
                let delta = if a == b { 1.0 } else { 0.0 };
                dense[0][a * m + b] = (delta + rc[i * n + j] - rc[j]) / 4.0;
                for &(k, v) in &rt[i * n + j] {
                    dense[1 + k][a * m + b] += v / 4.0;
                }
                for &(k, v) in &rt[j] {
                    dense[1 + k][a * m + b] -= v / 4.0;
                }
            }
        }
        let (m, dense) = if n % 2 == 0 {
            // even n: w = ((-1)^(j+1))_j is a left eigenvector of C for 1/4
            // (the alternating vector is a left null vector of R); remove it
            // exactly: rows/columns 1.. of S C S^{-1}, S = I with row 0 := w
            let m2 = m - 1;
            let red: Vec<Vec<f64>> = dense
                .iter()
                .map(|d| {
                    let mut o = vec![0.0; m2 * m2];
                    for i in 1..m {
                        for j in 1..m {
                            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                            o[(i - 1) * m2 + (j - 1)] = d[i * m + j] - d[i * m] * sign;
                        }
                    }
                    o
                })
                .collect();
            (m2, red)
        } else {
            (m, dense)
        };
        let c0 = dense[0].clone();
        let terms = dense[1..]
            .iter()
            .map(|d| {
                let mut t = Vec::new();
                for a in 0..m {
                    for b in 0..m {
                        if d[a * m + b] != 0.0 {
                            t.push((a, b, d[a * m + b]));
                        }
                    }
                }
                t
            })
            .collect();
        AffineFamily { m, c0, terms }
    }

    /// Matrix size.
    pub fn dim(&self) -> usize {
        self.m
    }

    /// Number of parameters.
    pub fn params(&self) -> usize {
        self.terms.len()
    }

    /// `C(x)` in floating point, row-major.
    pub fn at(&self, x: &[f64]) -> Vec<f64> {
        let mut c = self.c0.clone();
        for (k, t) in self.terms.iter().enumerate() {
            for &(a, b, v) in t {
                c[a * self.m + b] += v * x[k];
            }
        }
        c
    }

    /// `C(x)` enclosed in interval arithmetic (each entry contains the exact value).
    fn at_interval(&self, x: &[f64]) -> Vec<Iv> {
        let mut c: Vec<Iv> = self.c0.iter().map(|&v| Iv::point(v)).collect();
        for (k, t) in self.terms.iter().enumerate() {
            for &(a, b, v) in t {
                let e = &mut c[a * self.m + b];
                *e = e.add(Iv::point(v).mul(Iv::point(x[k])));
            }
        }
        c
    }
}

/// Row- and column-Gershgorin discs enclosing the eigenvalues of `C(x)` for
/// every `x` in the box `[lo, hi]`; `None` when the centre decomposition or
/// the verified inverse fails (the cell is then undecided).
#[derive(Clone, Debug)]
pub struct Enclosure {
    /// Discs from the rows of the transformed interval matrix.
    pub rows: Vec<Disc>,
    /// Discs from its columns.
    pub cols: Vec<Disc>,
}

/// Encloses the spectrum of the family over the box (module docs).
pub fn enclose(family: &AffineFamily, lo: &[f64], hi: &[f64], tamper: Tamper) -> Option<Enclosure> {
    let m = family.m;
    let k = family.params();
    if lo.len() != k || hi.len() != k {
        return None;
    }
    let mut r0 = vec![0.0; k];
    let mut h = vec![0.0; k];
    for i in 0..k {
        let mid = 0.5 * lo[i] + 0.5 * hi[i];
        r0[i] = mid;
        // exact half-width bound: the larger distance to an end, rounded up
        h[i] = Iv::point(hi[i])
            .sub(Iv::point(mid))
            .hi
            .max(Iv::point(mid).sub(Iv::point(lo[i])).hi);
    }
    let cf = family.at(&r0);
    let dm = DMatrix::from_row_slice(m, m, &cf);
    let eig = Eigen::new(
        &dm,
        EigenOptions {
            right: true,
            left: false,
        },
    )
    .ok()?;
    let v = eig.right()?.clone();
    let x = v.clone().try_inverse()?;
    let vi = |a: usize, b: usize| -> Ci {
        let z: Complex64 = v[(a, b)];
        Ci::point(z.re, z.im)
    };
    let xi = |a: usize, b: usize| -> Ci {
        let z: Complex64 = x[(a, b)];
        Ci::point(z.re, z.im)
    };
    // E = I - X V, beta = ||E||_inf
    let mut beta = 0.0f64;
    let mut xnorm = 0.0f64;
    for a in 0..m {
        let mut row = 0.0;
        let mut xrow = 0.0;
        for b in 0..m {
            let mut s = if a == b {
                Ci::point(1.0, 0.0)
            } else {
                Ci::ZERO
            };
            for j in 0..m {
                s = s.sub(xi(a, j).mul(vi(j, b)));
            }
            row = super::interval::up(row + s.mag());
            xrow = super::interval::up(xrow + xi(a, b).mag());
        }
        beta = beta.max(row);
        xnorm = xnorm.max(xrow);
    }
    if !(beta < MAX_INVERSE_RESIDUAL) || !xnorm.is_finite() {
        return None;
    }
    let one_minus = Iv::point(1.0).sub(Iv::point(beta)).lo;
    let delta = Iv::point(beta).mul(Iv::point(xnorm)).hi;
    let delta = super::interval::up(delta / one_minus);
    let y: Vec<Ci> = (0..m * m).map(|t| xi(t / m, t % m).widen(delta)).collect();
    // M0 = Y (C(r0) V)
    let c0 = family.at_interval(&r0);
    let mut cv = vec![Ci::ZERO; m * m];
    for a in 0..m {
        for b in 0..m {
            let mut s = Ci::ZERO;
            for j in 0..m {
                s = s.add(vi(j, b).scale(c0[a * m + j]));
            }
            cv[a * m + b] = s;
        }
    }
    let mut m0 = vec![Ci::ZERO; m * m];
    for a in 0..m {
        for b in 0..m {
            let mut s = Ci::ZERO;
            for j in 0..m {
                s = s.add(y[a * m + j].mul(cv[j * m + b]));
            }
            m0[a * m + b] = s;
        }
    }
    // G = sum_k h_k |Y C_k V|
    let mut g = vec![0.0f64; m * m];
    if tamper != Tamper::DropVariation {
        for (kk, t) in family.terms.iter().enumerate() {
            if t.is_empty() {
                continue;
            }
            let mut p = vec![Ci::ZERO; m * m];
            for &(i, j, val) in t {
                for a in 0..m {
                    let yv = y[a * m + i].scale(Iv::point(val));
                    for b in 0..m {
                        p[a * m + b] = p[a * m + b].add(yv.mul(vi(j, b)));
                    }
                }
            }
            for (gi, pi) in g.iter_mut().zip(&p) {
                *gi = super::interval::up(*gi + Iv::point(h[kk]).mul(Iv::point(pi.mag())).hi);
            }
        }
    }
    let disc = |a: usize, off: f64| -> Disc {
        let mut d = Disc::around(m0[a * m + a]);
        d.radius = super::interval::up(super::interval::up(d.radius + g[a * m + a]) + off);
        d
    };
    let mut rows = Vec::with_capacity(m);
    let mut cols = Vec::with_capacity(m);
    for a in 0..m {
        let mut off_r = 0.0;
        let mut off_c = 0.0;
        for b in 0..m {
            if b != a {
                off_r = super::interval::up(
                    off_r + super::interval::up(m0[a * m + b].mag() + g[a * m + b]),
                );
                off_c = super::interval::up(
                    off_c + super::interval::up(m0[b * m + a].mag() + g[b * m + a]),
                );
            }
        }
        rows.push(disc(a, off_r));
        cols.push(disc(a, off_c));
    }
    let finite = rows
        .iter()
        .chain(&cols)
        .all(|d| d.re.is_finite() && d.im.is_finite() && d.radius.is_finite());
    finite.then_some(Enclosure { rows, cols })
}

/// `[lo, hi]^2` (exact range of the square, rounded outward).
fn sqr(x: Iv) -> Iv {
    if x.lo >= 0.0 {
        x.mul(x)
    } else if x.hi <= 0.0 {
        x.neg().mul(x.neg())
    } else {
        let m = x.mag();
        Iv::new(0.0, Iv::point(m).mul(Iv::point(m)).hi)
    }
}

impl AffineFamily {
    /// The range of the affine combination `sum_t w_t C_t(x)_{entry_t}`
    /// over the box, rounded outward (each parameter enters once, so the
    /// interval evaluation is the exact range up to rounding).
    fn affine_range(&self, entries: &[(usize, f64)], lo: &[f64], hi: &[f64]) -> Iv {
        let mut acc = Iv::point(0.0);
        for &(e, w) in entries {
            acc = acc.add(Iv::point(self.c0[e]).mul(Iv::point(w)));
        }
        for (k, t) in self.terms.iter().enumerate() {
            let mut coef = Iv::point(0.0);
            for &(a, b, v) in t {
                for &(e, w) in entries {
                    if e == a * self.m + b {
                        coef = coef.add(Iv::point(v).mul(Iv::point(w)));
                    }
                }
            }
            acc = acc.add(coef.mul(Iv::new(lo[k], hi[k])));
        }
        acc
    }
}

/// The exact 2 x 2 route (`n = 3`, and `n = 4` after the removal of `1/4`):
/// eigenvalues `t/2 +- sqrt(disc)` with `t = C00 + C11` and
/// `disc = ((C00 - C11)/2)^2 + C01 C10`, both ranges over the cell in
/// interval arithmetic (`t` and `C00 - C11` affine: exact ranges; the
/// product `C01 C10` overestimates only to second order in the width).
/// `None` unless the family is 2 x 2. Verdicts as [`super::decide::decide`].
pub fn decide_2x2(
    family: &AffineFamily,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Option<super::decide::SpectralVerdict> {
    use super::decide::{SpectralVerdict, Status, FIXED_MODULUS};
    use crate::spectral::ClassName;
    if family.m != 2 || lo.len() != family.params() || hi.len() != family.params() {
        return None;
    }
    let centre: Vec<f64> = lo.iter().zip(hi).map(|(a, b)| 0.5 * a + 0.5 * b).collect();
    let (lo, hi) = match tamper {
        Tamper::DropVariation => (centre.as_slice(), centre.as_slice()),
        Tamper::None => (lo, hi),
    };
    let half_t = family
        .affine_range(&[(0, 1.0), (3, 1.0)], lo, hi)
        .mul(Iv::point(0.5));
    let half_diff = family
        .affine_range(&[(0, 1.0), (3, -1.0)], lo, hi)
        .mul(Iv::point(0.5));
    let c01 = family.affine_range(&[(1, 1.0)], lo, hi);
    let c10 = family.affine_range(&[(2, 1.0)], lo, hi);
    let disc = sqr(half_diff).add(c01.mul(c10));
    let undecided = SpectralVerdict {
        separation: Status::Undecided,
        class: None,
    };
    let not_separated = SpectralVerdict {
        separation: Status::Refuted,
        class: Some(ClassName::NotSeparated),
    };
    if disc.lo > 0.0 {
        // real, distinct: lambda_- < lambda_+
        let root = Iv::new(
            super::interval::down(disc.lo.sqrt()),
            super::interval::up(disc.hi.sqrt()),
        );
        let plus = half_t.add(root);
        let minus = half_t.sub(root);
        if !(plus.hi < 1.0) {
            return Some(undecided);
        }
        if minus.lo > FIXED_MODULUS {
            return Some(SpectralVerdict {
                separation: Status::Certified,
                class: Some(ClassName::RealDistinct),
            });
        }
        if minus.lo > -FIXED_MODULUS && minus.hi < FIXED_MODULUS {
            return Some(not_separated);
        }
        Some(undecided)
    } else if disc.hi < 0.0 {
        // complex pair, |lambda|^2 = (t/2)^2 - disc
        let mod2 = sqr(half_t).sub(disc);
        let q = FIXED_MODULUS * FIXED_MODULUS;
        if !(mod2.hi < 1.0) {
            return Some(undecided);
        }
        if mod2.lo > q {
            return Some(SpectralVerdict {
                separation: Status::Certified,
                class: Some(ClassName::ComplexPair),
            });
        }
        if mod2.hi < q {
            return Some(not_separated);
        }
        Some(undecided)
    } else {
        Some(undecided)
    }
}
