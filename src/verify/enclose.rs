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
use super::taylor::Taylor;
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
    /// The sound enclosure without the second-order scaled discs (plain
    /// Gershgorin discs; for comparisons).
    PlainGershgorin,
    /// The sound spectral enclosure, but the `charmap` certificate drops the
    /// variation of the invariant subspace over the cell
    /// ([`super::charmap::CellTamper::DropSubspaceVariation`]).
    DropSubspaceVariation,
    /// The sound spectral enclosure, but the `g1` certificate shrinks
    /// Stewart's radius ([`super::charmap::CellTamper::ShrinkStewartRadius`]).
    ShrinkStewartRadius,
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

    /// Entry `(a, b)` of `C_0`.
    pub fn constant(&self, a: usize, b: usize) -> f64 {
        self.c0[a * self.m + b]
    }

    /// Per parameter `k`, the nonzero entries `(a, b, value)` of `C_k`.
    pub fn terms(&self) -> &[Vec<(usize, usize, f64)>] {
        &self.terms
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
    /// Per parameter `k`: `h_k sum_ab |Y C_k V|_ab`, its share of the
    /// radii, used to choose the split coordinate (never for a verdict).
    pub scores: Vec<f64>,
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
    let mut scores = vec![0.0f64; k];
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
                let v = Iv::point(h[kk]).mul(Iv::point(pi.mag())).hi;
                *gi = super::interval::up(*gi + v);
                scores[kk] += v;
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
    // diagonal discs (centre and own radius) and off-diagonal bounds F
    let mut diag = Vec::with_capacity(m);
    let mut f = vec![0.0f64; m * m];
    for a in 0..m {
        diag.push(disc(a, 0.0));
        for b in 0..m {
            if b != a {
                f[a * m + b] = super::interval::up(m0[a * m + b].mag() + g[a * m + b]);
            }
        }
    }
    for a in 0..m {
        let mut off_r = 0.0;
        let mut off_c = 0.0;
        for b in 0..m {
            if b != a {
                off_r = super::interval::up(off_r + f[a * m + b]);
                off_c = super::interval::up(off_c + f[b * m + a]);
            }
        }
        rows.push(disc(a, off_r));
        cols.push(disc(a, off_c));
    }
    if tamper != Tamper::PlainGershgorin {
        if let Some(t) = scaled_discs(&diag, &f, m, false) {
            rows = t;
        }
        if let Some(t) = scaled_discs(&diag, &f, m, true) {
            cols = t;
        }
    }
    let finite = rows
        .iter()
        .chain(&cols)
        .all(|d| d.re.is_finite() && d.im.is_finite() && d.radius.is_finite());
    finite.then_some(Enclosure { rows, cols, scores })
}

/// Second-order isolation discs by diagonal scaling (math doc section 15).
///
/// `diag[a]` is the disc of the diagonal entry `a` (centre `z_a`, radius
/// `rho_a`), `f[a m + b]` bounds the off-diagonal entry `(a, b)`
/// (`transpose`: use columns). For each `a`, the similarity
/// `D^{-1} M D` with `D = diag(s, .., 1 (at a), .., s)`, `0 < s <= 1`, has
/// the Gershgorin discs
///
/// ```text
/// row a:  |z - z_a| <= rho_a + s sum_{b != a} F_ab
/// row b:  |z - z_b| <= rho_b + F_ba / s + sum_{j != a, b} F_bj
/// ```
///
/// If the disc of row `a` is disjoint from those of all rows `b`, it holds
/// exactly one eigenvalue of every matrix of the interval family
/// (Gershgorin's count). `s = max_b 2 F_ba / gap_b` (capped at 1), `gap_b`
/// the room left between the two discs at `s = 1` without the `F_ab, F_ba`
/// terms, makes the disc of row `a` shrink to `rho_a + O(|F|^2 / gap)`
/// (`sqrt(s)` and `1` are tried next). The
/// result is returned only when every row is isolated: then the discs are
/// pairwise disjoint (each lies inside its unscaled disc, which the scaled
/// discs of the other rows contain), each holds exactly one eigenvalue, and
/// together all `m`. Otherwise `None` (the unscaled discs are used).
fn scaled_discs(diag: &[Disc], f: &[f64], m: usize, transpose: bool) -> Option<Vec<Disc>> {
    use super::interval::{down, up};
    let fa = |a: usize, b: usize| {
        if transpose {
            f[b * m + a]
        } else {
            f[a * m + b]
        }
    };
    let mut out = Vec::with_capacity(m);
    for a in 0..m {
        let r_a = (0..m)
            .filter(|&b| b != a)
            .fold(0.0, |s, b| up(s + fa(a, b)));
        // rest_b = sum_{j != a, b} F_bj
        let rest = |b: usize| {
            (0..m)
                .filter(|&j| j != a && j != b)
                .fold(0.0, |s, j| up(s + fa(b, j)))
        };
        let mut s = 0.0f64;
        for b in (0..m).filter(|&b| b != a) {
            let fb = fa(b, a);
            if fb == 0.0 {
                continue;
            }
            // lower bound of the distance between the centres
            let probe = Disc {
                re: diag[b].re,
                im: diag[b].im,
                radius: 0.0,
            };
            let centre_a = Disc {
                radius: 0.0,
                ..diag[a]
            };
            let dist = lower_distance(&centre_a, &probe);
            let gap = down(down(down(dist - diag[a].radius) - diag[b].radius) - rest(b));
            if !(gap > 0.0) {
                return None;
            }
            s = s.max(up(up(2.0 * fb) / gap));
        }
        let s = s.clamp(f64::MIN_POSITIVE, 1.0);
        // the first scaling (s, then sqrt(s), then 1: the unscaled disc)
        // whose disc of row a misses every other row's disc
        let isolated = |s: f64| -> Option<Disc> {
            let tight = Disc {
                radius: up(diag[a].radius + up(s * r_a)),
                ..diag[a]
            };
            for b in (0..m).filter(|&b| b != a) {
                let fb = fa(b, a);
                let grown = if fb == 0.0 { 0.0 } else { up(fb / s) };
                let other = Disc {
                    radius: up(up(diag[b].radius + grown) + rest(b)),
                    ..diag[b]
                };
                if !tight.disjoint(&other) {
                    return None;
                }
            }
            Some(tight)
        };
        let tight = isolated(s)
            .or_else(|| isolated(s.sqrt().clamp(s, 1.0)))
            .or_else(|| isolated(1.0))?;
        out.push(tight);
    }
    Some(out)
}

/// A lower bound of the distance between the centres of two discs.
fn lower_distance(a: &Disc, b: &Disc) -> f64 {
    // disjoint() with zero radii compares the distance against up(0) > 0;
    // compute the bound directly with the same rounding
    use super::interval::down;
    let dx = Iv::point(a.re).sub(Iv::point(b.re));
    let dy = Iv::point(a.im).sub(Iv::point(b.im));
    let (x, y) = (dx.mig(), dy.mig());
    down(down(down(x * x) + down(y * y)).max(0.0).sqrt())
}

impl AffineFamily {
    /// Entry `e` (row-major) of `C(x0 + d)` as an affine Taylor form around
    /// the centre `x0` (the constant in interval arithmetic, the gradient the
    /// family's exact coefficients).
    fn entry_taylor(&self, e: usize, x0: &[f64]) -> Taylor {
        let mut c = Iv::point(self.c0[e]);
        let mut g = vec![0.0; self.params()];
        for (k, t) in self.terms.iter().enumerate() {
            for &(a, b, v) in t {
                if a * self.m + b == e {
                    c = c.add(Iv::point(v).mul(Iv::point(x0[k])));
                    g[k] += v;
                }
            }
        }
        Taylor::affine(c, &g)
    }
}

/// The closed 2 x 2 route (`n = 3`, and `n = 4` after the removal of
/// `1/4`): with `t = C00 + C11` and `det = C00 C11 - C01 C10`, the
/// eigenvalues are the roots of `p(z) = z^2 - t z + det`. Every verdict is a
/// sign condition on a quadratic polynomial in the parameters, enclosed by a
/// first-order Taylor form with a rigorous remainder over the cell
/// ([`Taylor`]):
///
/// * `disc = t^2/4 - det > 0`: real and distinct. Both roots `< 1` iff
///   `p(1) > 0` and `t/2 < 1`; both `> 1/4` iff `p(1/4) > 0` and `t/2 > 1/4`
///   (`real_distinct`, separation certified); the smaller root in
///   `(-1/4, 1/4)` iff `p(1/4) < 0 < p(-1/4)`, or `p(+-1/4) > 0` and
///   `|t/2| < 1/4` (`not_separated`: the pair would include the fixed `1/4`).
/// * `disc < 0`: a complex pair of modulus `sqrt(det)`: `det < 1` needed;
///   `det > 1/16`: `complex_pair`; `det < 1/16`: `not_separated`.
///
/// Otherwise the cell is undecided, and the second value gives, per
/// parameter, the share of the undecided quantity's uncertainty
/// ([`Taylor::scores`]) to choose the split coordinate. `None` unless the
/// family is 2 x 2.
pub fn decide_2x2(
    family: &AffineFamily,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Option<(super::decide::SpectralVerdict, Option<Vec<f64>>)> {
    use super::decide::{SpectralVerdict, Status, FIXED_MODULUS};
    use crate::spectral::ClassName;
    let k = family.params();
    if family.m != 2 || lo.len() != k || hi.len() != k {
        return None;
    }
    let (x0, mut h) = centre_and_half_widths(lo, hi);
    if tamper == Tamper::DropVariation {
        h = vec![0.0; k];
    }
    let c00 = family.entry_taylor(0, &x0);
    let c01 = family.entry_taylor(1, &x0);
    let c10 = family.entry_taylor(2, &x0);
    let c11 = family.entry_taylor(3, &x0);
    let t = c00.add(&c11);
    let det = c00.mul(&c11, &h).sub(&c01.mul(&c10, &h));
    // disc = (t/2)^2 - det; t/2 is exact scaling by a power of two
    let half_t = t.scale(0.5);
    let disc = half_t.mul(&half_t, &h).sub(&det);
    let q = FIXED_MODULUS;
    // p(z) = z^2 - t z + det at z = 1, 1/4, -1/4
    let p_at = |z: f64| {
        // z in {1, 1/4, -1/4}: z^2 is exact
        Taylor::constant(z * z, k).sub(&t.scale(z)).add(&det)
    };
    let undecided = |why: &Taylor| {
        Some((
            SpectralVerdict {
                separation: Status::Undecided,
                class: None,
            },
            Some(why.scores(&h)),
        ))
    };
    let not_separated = Some((
        SpectralVerdict {
            separation: Status::Refuted,
            class: Some(ClassName::NotSeparated),
        },
        None,
    ));
    let dr = disc.range(&h);
    if dr.lo > 0.0 {
        let p1 = p_at(1.0);
        let ht = half_t.range(&h);
        if !(p1.range(&h).lo > 0.0 && ht.hi < 1.0) {
            return undecided(&p1);
        }
        let pq = p_at(q);
        let pmq = p_at(-q);
        let (pqr, pmqr) = (pq.range(&h), pmq.range(&h));
        if pqr.lo > 0.0 && ht.lo > q {
            return Some((
                SpectralVerdict {
                    separation: Status::Certified,
                    class: Some(ClassName::RealDistinct),
                },
                None,
            ));
        }
        if pqr.hi < 0.0 && pmqr.lo > 0.0 {
            return not_separated;
        }
        if pqr.lo > 0.0 && pmqr.lo > 0.0 && ht.lo > -q && ht.hi < q {
            return not_separated;
        }
        if !(pqr.lo > 0.0 || pqr.hi < 0.0) {
            undecided(&pq)
        } else if !(pmqr.lo > 0.0 || pmqr.hi < 0.0) {
            undecided(&pmq)
        } else {
            undecided(&half_t)
        }
    } else if dr.hi < 0.0 {
        let d = det.range(&h);
        if !(d.hi < 1.0) {
            return undecided(&det);
        }
        let q2 = q * q; // 1/16, exact
        if d.lo > q2 {
            return Some((
                SpectralVerdict {
                    separation: Status::Certified,
                    class: Some(ClassName::ComplexPair),
                },
                None,
            ));
        }
        if d.hi < q2 {
            return not_separated;
        }
        undecided(&det)
    } else {
        undecided(&disc)
    }
}

/// The float centre of a cell and half-widths `h` with
/// `[lo, hi] ⊂ [x0 - h, x0 + h]` (each the larger distance to an end,
/// rounded up).
pub fn centre_and_half_widths(lo: &[f64], hi: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let x0: Vec<f64> = lo.iter().zip(hi).map(|(a, b)| 0.5 * a + 0.5 * b).collect();
    let h = lo
        .iter()
        .zip(hi)
        .zip(&x0)
        .map(|((a, b), m)| {
            Iv::point(*b)
                .sub(Iv::point(*m))
                .hi
                .max(Iv::point(*m).sub(Iv::point(*a)).hi)
        })
        .collect();
    (x0, h)
}
