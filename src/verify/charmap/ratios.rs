//! The characteristic map of NURDS over a box of edge ratios (math doc
//! sections 4, 7 and 15 **\[derived\]**).
//!
//! **The invariant subspace without the face weights.** The face block is
//! `A = (I + R)/4 + 1 c^T / 4` with the face weights `c` (rational in `r`).
//! `W = (I + R)/4` is affine in `r` with entries that are multiples of `1/4`,
//! `W 1 = (3/4) 1` and `c^T W = (3/4) c^T`, so `c^perp` is `W`-invariant and
//! `A = W` on it: `spec(W) = {3/4} U (spec(A) \ {1})`, and the invariant
//! subspace of the subdominant pair is the same for `A` and `W`.
//!
//! **Subspace over the cell (Stewart's argument).** At the centre `r0` the
//! numerical eigenvectors of `W(r0)` give a real basis
//! `Q = [q_1 q_2 | 1 | rest]` (the pair, the exact eigenvector `1` of `3/4`,
//! the others; complex pairs as real and imaginary parts) and an interval
//! `Y` containing `Q^{-1}` ([`super::ivla::verified_inverse`]). For every `r`
//! in the cell `T(r) = Q^{-1} W(r) Q` lies in `Y W(r0) Q + sum_k [-h_k, h_k]
//! |Y W_k Q|`. Split `T` after the first two indices into
//! `T11, T12, T21, T22` and let `L_r(P) = P T11 - T22 P`, `L_0` at the
//! interval midpoints (its Kronecker matrix `K_0` has a verified inverse;
//! all 2-norms are bounded by [`super::ivla::norm2_op_upper`]). With
//! `a >= sup ||L_0^{-1} T21||_F`, `b >= ||L_0^{-1} (L_r - L_0)||` (the
//! preconditioned variation, entrywise through `K_0^{-1} K(Y W_k Q)`) and
//! `c >= ||L_0^{-1}|| ||T12||_2`, the map
//! `P -> L_0^{-1}(T21 - (L_r - L_0)(P) - P T12 P)` sends the ball
//! `||P||_F <= rho` into itself and contracts it when `a + b rho + c rho^2
//! <= rho` and `b + 2 c rho < 1` ([`contraction_radius`]; Stewart's
//! `4 gamma eta < delta^2` is the case `a = gamma / sigma_0`,
//! `b = (||rad T11|| + ||rad T22||) / sigma_0`); its fixed point
//! `P(r)` makes `range(Q [I; P])` invariant with restriction
//! `N = T11 + T12 P`, and it depends continuously on `r`.
//!
//! **It is the subdominant pair.** `T` is similar to
//! `[[N, T12], [0, T22 - P T12]]`. The column of `T` belonging to `1` is
//! exactly `(3/4) e` (so that column of `T12` is zero), hence
//! `spec(T22 - P T12) = {3/4} U spec(K')` with `K'` the rest. When every
//! eigenvalue of `N` is larger in modulus than a bound of the spectral radius
//! of `K'` (block norms in the basis of the numerical eigenvectors), the
//! eigenvalues of `N` are the two largest of `spec(A) \ {1}`: the subdominant
//! pair (the cell's class, certified separately, says which kind).
//!
//! **The ring.** `B = Q [I; P]` (entries within `rho ||Q_{a, rest}||_2` of
//! `Q`'s first two columns) is lifted to `S_n` by the block equations of
//! [`crate::charmap::basis`] (a 4 x 4 Sylvester system per edge and a 2 x 2
//! system per corner, solved as interval systems); the first `4n` ring points
//! are `w_k N` (`S_n w = w N`), the other `5n` the rows of the E- and V-face
//! blocks (the E-face weights `(r/2, s/2, s/2, r/2)`, `s = 1 - r`, make them
//! affine in `r`). The `3n` biquadratic Bezier nets use the spans' exact
//! conversion weights (`1/2`, `r`, `s`); the Jacobian's Bezier coefficients
//! (bidegree (3, 3), scaled by the binomial denominators) must have one sign
//! for every parameter, else they are split by de Casteljau; the outer
//! boundary's winding number must be 1 after orientation
//! ([`super::winding`]). Regularity and injectivity do not depend on the
//! basis of the plane, so `B` serves for every eigenstructure.
//!
//! **Named remainders.** The remainder of every form of `N`, of the lifted
//! basis and of the ring points becomes a fresh symbol
//! ([`Af::name_remainder`], [`named_remainders`] of them), so that the
//! Bezier differences and the Jacobian coefficients cancel it instead of
//! adding it (math doc section 15, "Named remainders").

use super::af::{self, det, Af};
use super::ivla::{mid, norm2_op_upper, norm2_upper, sqr, verified_inverse, P2};
use super::winding::{winding_number, BoxCurve};
use super::CellTamper;
use crate::schemes::doo_sabin::ring::{patch_grid, PatchKind, RingPatchId};
use crate::schemes::doo_sabin::Layout;
use crate::spectral::eigen::{Eigen, EigenOptions};
use crate::verify::interval::{down, up, Iv};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Rounds of the a-posteriori bound of the subspace correction: Stewart's
/// radius `rho` of the ball of `P` is replaced by `p_hat + ||D||_F` while that
/// is smaller (each round is a valid bound; three reach the fixed point to
/// a few per cent).
pub const RHO_ITERATIONS: usize = 3;

/// Most de Casteljau levels of the Jacobian per patch.
pub const JACOBIAN_DEPTH: u32 = 5;

/// Most Jacobian pieces examined per cell.
pub const JACOBIAN_PIECES: usize = 4_000;

/// Relative size below which an eigenvalue's imaginary part counts as zero
/// when the numerical basis `Q` is built (any choice gives a valid basis:
/// the verified inverse and the bounds make the result rigorous; a bad
/// choice only makes the cell undecided).
pub const REAL_TOL: f64 = 1e-9;

/// The enclosure of the characteristic ring over a box of ratios.
#[derive(Clone, Debug)]
pub struct RatioRing {
    /// The centre basis `Q = [q_1 q_2 | 1 | rest]` (`n x n`).
    pub q: DMatrix<f64>,
    /// `||P||_F <= rho` for the exact basis `Q [I; P(r)]`.
    pub rho: f64,
    /// The restriction `N = T11 + T12 P` (row-major 2 x 2).
    pub restriction: [Iv; 4],
    /// The eigenvalue moduli of `N` over the cell ([`pair_moduli`]).
    pub pair: PairModuli,
    /// An upper bound of the spectral radius of the rest `K'` of the face
    /// block over the cell (`0` for `n = 3`, where `K'` is empty).
    pub rest_radius: f64,
    /// The first-order part `P^ = L_0^{-1}(T21(r))` of `P` as affine forms
    /// (entry `(k, j)` at `k + (n - 2) j`).
    pub correction: Vec<Af>,
    /// `||P - P^||_F <= correction_radius` for every ratio vector of the cell.
    pub correction_radius: f64,
    /// The lifted basis (`4n` rows in the order of `S_n`, two columns).
    pub basis: Vec<P2>,
    /// The `9n` ring points in the order of the extended matrix (ranges).
    pub points: Vec<P2>,
    /// The same as affine forms (symbols: the ratios, then the entries of `P`).
    pub forms: Vec<[Af; 2]>,
    /// Per ratio: its share of the subspace variation (for the split rule).
    pub scores: Vec<f64>,
    /// The cell's centre `r0` (the ratio `k` is `r0_k + h_k eps_k`).
    pub centre: Vec<f64>,
    /// The half-widths `h` (rounded up).
    pub half_width: Vec<f64>,
}

/// How many remainders of a ring over a cell of valence `n` are named
/// (math doc section 15, "Named remainders"): the 4 entries of `N`, the
/// `4n` edge and `2n` corner coordinates of the lifted basis, the `18n`
/// coordinates of the ring points.
pub const fn named_remainders(n: usize) -> usize {
    4 + 6 * n + RING_POINT_NAMES * n
}

/// Named remainders of the ring points per unit of valence: two
/// coordinates of each of the `9n` points.
const RING_POINT_NAMES: usize = 18;

/// The next free symbol for a named remainder.
struct Named {
    next: usize,
}

impl Named {
    fn new(first: usize) -> Named {
        Named { next: first }
    }

    /// `f` with its remainder turned into the next fresh symbol
    /// ([`Af::name_remainder`]).
    fn name(&mut self, f: Af) -> Af {
        let out = f.name_remainder(self.next);
        self.next += 1;
        out
    }
}

/// Sparse matrix entries `(row, col, value)`.
type Sparse = Vec<(usize, usize, f64)>;

/// `W(r) = W_0 + sum_k r_k W_k` as sparse terms: `(W_0, [W_k])`.
fn w_terms(n: usize) -> (Sparse, Vec<Sparse>) {
    let mut c0 = Vec::new();
    let mut terms = vec![Vec::new(); n];
    for i in 0..n {
        let ip = (i + 1) % n;
        c0.push((i, i, 0.5));
        c0.push((i, ip, 0.25));
        // W[i][i] += r_i/4, W[ip][ip] -= r_i/4, W[ip][i] += r_i/4, W[i][ip] -= r_i/4
        terms[i].push((i, i, 0.25));
        terms[i].push((ip, ip, -0.25));
        terms[i].push((ip, i, 0.25));
        terms[i].push((i, ip, -0.25));
    }
    (c0, terms)
}

/// How the first two columns of the centre basis `Q` span the pair's
/// invariant subspace of `W(r0)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairBasis {
    /// The pair's eigenvectors (two real ones, or the real and imaginary
    /// parts of a complex one): needs the class, degenerates near the class
    /// boundary.
    Eigenvectors,
    /// An orthonormal basis of the pair's real invariant subspace (the first
    /// two Schur vectors of an ordered real Schur form): the null space of
    /// `(W - mu_1)(W - mu_2) = W^2 - t W + d I`, `t = mu_1 + mu_2`,
    /// `d = mu_1 mu_2` (real for a real or a conjugate pair), from an SVD.
    /// Well conditioned on both sides of the class boundary and on the
    /// defective lines (math doc section 15, "G1 over a cell").
    Schur,
}

/// An orthonormal basis (two columns) of the null space of
/// `W^2 - t W + d I`: the right singular vectors of its two smallest
/// singular values (any result is only a guess; the enclosure is rigorous).
fn pair_subspace(w: &DMatrix<f64>, t: f64, d: f64) -> Option<[Vec<f64>; 2]> {
    let n = w.nrows();
    let w2 = w * w;
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        w2[(i, j)] - t * w[(i, j)] + if i == j { d } else { 0.0 }
    });
    let svd = m.svd().ok()?;
    let v = svd.V();
    let s = svd.S().column_vector();
    // faer orders the singular values decreasingly; find the two smallest anyway
    let mut idx: Vec<usize> = (0..n).collect();
    idx.sort_by(|&a, &b| s[a].total_cmp(&s[b]));
    let (a, b) = (*idx.first()?, *idx.get(1)?);
    let col = |k: usize| -> Vec<f64> { (0..n).map(|i| v[(i, k)]).collect() };
    let out = [col(a), col(b)];
    out.iter()
        .all(|c| c.iter().all(|x| x.is_finite()))
        .then_some(out)
}

/// A real basis of `W(r0)` from its numerical eigen-decomposition: the pair
/// (as `pair` says), `1`, the rest's eigenvectors, and the sizes of the
/// rest's blocks (1 real, 2 complex pair).
fn centre_basis(w: &DMatrix<f64>, pair: PairBasis) -> Option<(DMatrix<f64>, Vec<usize>)> {
    let n = w.nrows();
    let eig = Eigen::new(
        w,
        EigenOptions {
            right: true,
            left: false,
        },
    )
    .ok()?;
    let vals = eig.values();
    let vecs = eig.right()?;
    // the eigenvalue 3/4 (eigenvector 1) is the one nearest 3/4
    let k34 =
        (0..n).min_by(|&a, &b| (vals[a] - 0.75).norm().total_cmp(&(vals[b] - 0.75).norm()))?;
    let order: Vec<usize> = (0..n).filter(|&k| k != k34).collect();
    let is_real = |z: Complex64| z.im.abs() <= REAL_TOL * z.norm().max(1.0);
    let col = |k: usize| -> Vec<Complex64> { (0..n).map(|i| vecs[(i, k)]).collect() };
    // a real eigenvector: remove the phase of the largest entry
    let real_vec = |k: usize| -> Vec<f64> {
        let v = col(k);
        let big = v
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or(Complex64::new(1.0, 0.0));
        let ph = if big.norm() > 0.0 {
            big.conj() / big.norm()
        } else {
            Complex64::new(1.0, 0.0)
        };
        v.iter().map(|z| (z * ph).re).collect()
    };
    let mut cols: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut blocks = Vec::new();
    let mut used = vec![false; n];
    // the pair: the first two of `order` (largest moduli after 3/4)
    let (a, b) = (*order.first()?, *order.get(1)?);
    if pair == PairBasis::Schur {
        let [u, v] = pair_subspace(w, (vals[a] + vals[b]).re, (vals[a] * vals[b]).re)?;
        cols.push(u);
        cols.push(v);
    } else if is_real(vals[a]) && is_real(vals[b]) {
        cols.push(real_vec(a));
        cols.push(real_vec(b));
    } else if !is_real(vals[a]) && (vals[a] - vals[b].conj()).norm() <= 1e-6 * vals[a].norm() {
        let v = col(a);
        cols.push(v.iter().map(|z| z.re).collect());
        cols.push(v.iter().map(|z| z.im).collect());
    } else {
        return None;
    }
    used[a] = true;
    used[b] = true;
    used[k34] = true;
    cols.push(vec![1.0; n]);
    for &k in &order {
        if used[k] {
            continue;
        }
        used[k] = true;
        if is_real(vals[k]) {
            cols.push(real_vec(k));
            blocks.push(1);
        } else {
            // its conjugate partner
            let partner = order
                .iter()
                .copied()
                .filter(|&j| !used[j])
                .min_by(|&x, &y| {
                    (vals[x] - vals[k].conj())
                        .norm()
                        .total_cmp(&(vals[y] - vals[k].conj()).norm())
                })?;
            used[partner] = true;
            let v = col(k);
            cols.push(v.iter().map(|z| z.re).collect());
            cols.push(v.iter().map(|z| z.im).collect());
            blocks.push(2);
        }
    }
    // unit columns (except the exact 1)
    let mut q = DMatrix::zeros(n, n);
    for (j, c) in cols.iter().enumerate() {
        let s = if j == 2 {
            1.0
        } else {
            let nrm = c.iter().map(|x| x * x).sum::<f64>().sqrt();
            if !(nrm > 0.0) {
                return None;
            }
            nrm
        };
        for i in 0..n {
            q[(i, j)] = if j == 2 { c[i] } else { c[i] / s };
        }
    }
    Some((q, blocks))
}

/// Upper bound of the spectral radius of every matrix in the interval
/// matrix `k` (`m x m`, row-major), block diagonal up to the off-block part
/// with the given block sizes: `max_b ||K_bb||_2 + ||off-block part||_F`.
fn spectral_radius_upper(k: &[Iv], m: usize, blocks: &[usize]) -> f64 {
    let mut start = Vec::with_capacity(blocks.len());
    let mut s = 0;
    for &b in blocks {
        start.push(s);
        s += b;
    }
    if s != m {
        return f64::INFINITY;
    }
    let block_of = |i: usize| start.iter().rposition(|&b0| b0 <= i).unwrap_or(0);
    let mut worst = 0.0f64;
    for (bi, &b) in blocks.iter().enumerate() {
        let o = start[bi];
        let e = |i: usize, j: usize| k[(o + i) * m + o + j];
        let nb = if b == 1 {
            e(0, 0).mag()
        } else {
            // ||B||_2^2 = (f + sqrt(f^2 - 4 det^2)) / 2, f = ||B||_F^2:
            // increasing in f, decreasing in |det|
            let f = norm2_upper([e(0, 0).mag(), e(0, 1).mag(), e(1, 0).mag(), e(1, 1).mag()]);
            let f2 = up(f * f);
            let det = e(0, 0).mul(e(1, 1)).sub(e(0, 1).mul(e(1, 0)));
            let dl = det.mig();
            let inner = up(f2 * f2 - down(4.0 * down(dl * dl))).max(0.0);
            up(up(up(f2 + up(inner.sqrt())) * 0.5).sqrt())
        };
        worst = worst.max(nb);
    }
    let mut off = Vec::new();
    for i in 0..m {
        for j in 0..m {
            if block_of(i) != block_of(j) {
                off.push(k[i * m + j].mag());
            }
        }
    }
    up(worst + norm2_upper(off))
}

/// Bounds of the eigenvalue moduli of every matrix of a 2 x 2 family
/// (math doc section 15, "G1 over a cell").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairModuli {
    /// An enclosure of the determinant.
    pub det: Iv,
    /// A lower bound of the smallest eigenvalue modulus.
    pub min: f64,
    /// An upper bound of the largest eigenvalue modulus.
    pub max: f64,
}

/// `[lo, hi]` of two enclosures of one quantity intersected (a `NaN`
/// interval when they are disjoint, which fails every later test).
fn meet(a: Iv, b: Iv) -> Iv {
    let (lo, hi) = (a.lo.max(b.lo), a.hi.min(b.hi));
    if lo <= hi {
        Iv::new(lo, hi)
    } else {
        Iv::new(f64::NAN, f64::NAN)
    }
}

/// The eigenvalue moduli of every matrix of the interval 2 x 2 matrix `a`
/// (row-major), optionally also enclosed by the affine forms `forms` of
/// the same entries. With `h = t/2` (`t` the trace), `det` and the
/// discriminant written as
///
/// ```text
/// disc = h^2 - det = ((a_00 - a_11)/2)^2 + a_01 a_10
/// ```
///
/// (the second form has no first-order cancellation: at a double
/// eigenvalue both sides are second order in the entries' variation, while
/// `h^2` and `det` each vary to first order), each enclosed by both forms
/// and by the affine forms when given, and intersected:
///
/// * real roots (`disc >= 0`): `h +- sqrt(disc)`, modulus at most
///   `|h| + sqrt(disc)` and at least `max(|det| / (|h| + sqrt(disc)),
///   min|h| - sqrt(disc))`;
/// * a complex pair (`disc < 0`): modulus `sqrt(det)`, and `det = h^2 - disc
///   > h^2`.
///
/// Every bound is rounded against the claim.
///
/// ```
/// use subdiv_lab::verify::charmap::ratios::pair_moduli;
/// use subdiv_lab::verify::interval::Iv;
/// // 0.6 I + [-0.01, 0.01] in every entry: eigenvalues within 0.03 of 0.6
/// let a = [Iv::new(0.59, 0.61), Iv::new(-0.01, 0.01), Iv::new(-0.01, 0.01), Iv::new(0.59, 0.61)];
/// let p = pair_moduli(&a, None);
/// assert!(p.min > 0.56 && p.max < 0.64);
/// ```
pub fn pair_moduli(a: &[Iv; 4], forms: Option<&[Af]>) -> PairModuli {
    pair_moduli_with(a, forms, false)
}

/// [`pair_moduli`], with `drop_cross` the cross term `a_01 a_10` of the
/// discriminant left out ([`CellTamper::DropPairCrossTerm`], unsound).
fn pair_moduli_with(a: &[Iv; 4], forms: Option<&[Af]>, drop_cross: bool) -> PairModuli {
    let half = Iv::point(0.5);
    let cross = |x: Iv| if drop_cross { Iv::point(0.0) } else { x };
    let mut h = a[0].add(a[3]).mul(half);
    let mut det = a[0].mul(a[3]).sub(a[1].mul(a[2]));
    let hd = a[0].sub(a[3]).mul(half);
    let mut disc = sqr(hd).add(cross(a[1].mul(a[2])));
    if !drop_cross {
        disc = meet(disc, sqr(h).sub(det));
    }
    if let Some([f0, f1, f2, f3]) = forms {
        h = meet(h, f0.add(f3).scale(0.5).range());
        det = meet(
            det,
            af::det(&[f0.clone(), f1.clone()], &[f2.clone(), f3.clone()]).range(),
        );
        let hd = f0.sub(f3).scale(0.5).range();
        disc = meet(disc, sqr(hd).add(cross(f1.mul(f2).range())));
    }
    let h_mag = h.mag();
    let h_mig = h.mig();
    let det_mig = det.mig();
    let (mut min, mut max) = (f64::INFINITY, 0.0f64);
    if !(disc.lo <= disc.hi && h.lo <= h.hi && det.lo <= det.hi) {
        return PairModuli {
            det,
            min: 0.0,
            max: f64::INFINITY,
        };
    }
    if disc.hi >= 0.0 {
        let s = up(disc.hi.sqrt());
        let big = up(h_mag + s);
        max = max.max(big);
        min = min.min(down(det_mig / big).max(down(h_mig - s)));
    }
    if disc.lo < 0.0 {
        max = max.max(up(det.hi.max(0.0).sqrt()));
        min = min.min(down(det.lo.max(down(h_mig * h_mig)).max(0.0).sqrt()));
    }
    PairModuli {
        det,
        min: min.max(0.0),
        max,
    }
}

/// The Kronecker matrix (`2m x 2m`, row-major, row `i + m j` for `P_ij`)
/// of `P -> P X11 - X22 P` for the `n x n` interval matrix `x` split after
/// its first two indices (`m = n - 2`).
fn kron_op(m: usize, x: impl Fn(usize, usize) -> Iv) -> Vec<Iv> {
    let k = 2 * m;
    let mut out = vec![Iv::point(0.0); k * k];
    for row in 0..k {
        let (i, j) = (row % m, row / m);
        for col in 0..k {
            let (i2, j2) = (col % m, col / m);
            let mut v = Iv::point(0.0);
            if i == i2 {
                v = v.add(x(j2, j));
            }
            if j == j2 {
                v = v.sub(x(2 + i, 2 + i2));
            }
            out[row * k + col] = v;
        }
    }
    out
}

/// `acc += w |a b|` entrywise (rounded up) for `k x k` interval matrices
/// `a`, `b` (row-major) and a float `w >= 0`.
fn add_product_mag(acc: &mut [f64], a: &[Iv], b: &[Iv], k: usize, w: f64) {
    debug_assert!(acc.len() == k * k && a.len() == k * k && b.len() == k * k);
    for i in 0..k {
        for j in 0..k {
            let mut s = Iv::point(0.0);
            for l in 0..k {
                s = s.add(a[i * k + l].mul(b[l * k + j]));
            }
            acc[i * k + j] = up(acc[i * k + j] + up(w * s.mag()));
        }
    }
}

/// Relative margin of the contraction radius above the computed root, so
/// that its verification with upward rounding (relative errors of a few
/// `2^-52`) passes unless the root is nearly double (then the cell is
/// left undecided, never certified by a guess).
pub const ROOT_MARGIN: f64 = 1.0 / (1u64 << 30) as f64;

/// A radius `rho` with `a + b rho + c rho^2 <= rho` and `b + 2 c rho < 1`,
/// both verified with upward rounding, or `None` (math doc section 15, "G1
/// over a cell"): for `a >= sup ||L0^{-1} T21||_F`, `b >= ||L0^{-1} dL_r||`
/// and `c >= ||L0^{-1}|| ||T12||_2` the map `P -> L0^{-1}(T21 - dL_r(P) -
/// P T12 P)` sends the ball `||P||_F <= rho` into itself and contracts it.
/// The smallest root of `c rho^2 - (1 - b) rho + a` is `2a / ((1 - b) +
/// sqrt((1 - b)^2 - 4 a c))`, widened by [`ROOT_MARGIN`].
///
/// ```
/// use subdiv_lab::verify::charmap::ratios::contraction_radius;
/// let rho = contraction_radius(0.1, 0.2, 0.5).unwrap();
/// assert!(0.1 + 0.2 * rho + 0.5 * rho * rho <= rho && rho < 0.14);
/// assert!(contraction_radius(0.5, 0.2, 0.5).is_none());
/// ```
pub fn contraction_radius(a: f64, b: f64, c: f64) -> Option<f64> {
    let one_b = down(1.0 - b);
    let q = down(down(one_b * one_b) - up(4.0 * up(a * c)));
    if !(one_b > 0.0 && q > 0.0 && a >= 0.0 && c >= 0.0) {
        return None;
    }
    let root = up(up(2.0 * a) / down(one_b + down(q.sqrt())));
    let rho = up(root * up(1.0 + ROOT_MARGIN));
    let image = up(up(a + up(b * rho)) + up(c * up(rho * rho)));
    let lipschitz = up(b + up(2.0 * up(c * rho)));
    (image <= rho && lipschitz < 1.0).then_some(rho)
}

/// The enclosure of the ring over the ratio box `[lo, hi]` (module docs),
/// or `None` when a step fails. With
/// [`CellTamper::DropSubspaceVariation`] the basis is taken as `Q`'s first
/// two columns for the whole cell (`rho = 0`, deliberately unsound).
pub fn ratio_ring(lo: &[f64], hi: &[f64], tamper: CellTamper) -> Option<RatioRing> {
    ratio_ring_with(lo, hi, tamper, PairBasis::Eigenvectors)
}

/// [`ratio_ring`] with the pair's columns of `Q` chosen by `pair`. With
/// [`CellTamper::ShrinkStewartRadius`] the radius `rho` of the ball of `P`
/// is divided by 64 and the bound of its second-order part dropped
/// (deliberately unsound).
pub fn ratio_ring_with(
    lo: &[f64],
    hi: &[f64],
    tamper: CellTamper,
    pair: PairBasis,
) -> Option<RatioRing> {
    let n = lo.len();
    if n < 3 || hi.len() != n {
        return None;
    }
    let mut r0 = vec![0.0; n];
    let mut h = vec![0.0; n];
    for i in 0..n {
        let m = 0.5 * lo[i] + 0.5 * hi[i];
        r0[i] = m;
        h[i] = Iv::point(hi[i])
            .sub(Iv::point(m))
            .hi
            .max(Iv::point(m).sub(Iv::point(lo[i])).hi);
    }
    let (c0, terms) = w_terms(n);
    let mut wc = vec![Iv::point(0.0); n * n];
    for &(i, j, v) in &c0 {
        wc[i * n + j] = wc[i * n + j].add(Iv::point(v));
    }
    for (k, t) in terms.iter().enumerate() {
        for &(i, j, v) in t {
            wc[i * n + j] = wc[i * n + j].add(Iv::point(v).mul(Iv::point(r0[k])));
        }
    }
    let wf = DMatrix::from_fn(n, n, |i, j| mid(wc[i * n + j]));
    let (q, blocks) = centre_basis(&wf, pair)?;
    let y = verified_inverse(&q)?;
    let qi = |i: usize, j: usize| Iv::point(q[(i, j)]);
    // M0 = Y (W(r0) Q)
    let mut wq = vec![Iv::point(0.0); n * n];
    for i in 0..n {
        for j in 0..n {
            let mut s = Iv::point(0.0);
            for l in 0..n {
                s = s.add(wc[i * n + l].mul(qi(l, j)));
            }
            wq[i * n + j] = s;
        }
    }
    let ymul = |x: &[Iv]| -> Vec<Iv> {
        let mut out = vec![Iv::point(0.0); n * n];
        for i in 0..n {
            for j in 0..n {
                let mut s = Iv::point(0.0);
                for l in 0..n {
                    s = s.add(y[i * n + l].mul(x[l * n + j]));
                }
                out[i * n + j] = s;
            }
        }
        out
    };
    let mut t = ymul(&wq);
    let mut yterms: Vec<Vec<Iv>> = Vec::with_capacity(n);
    let mut g = vec![0.0f64; n * n];
    let mut scores = vec![0.0f64; n];
    for (k, tk) in terms.iter().enumerate() {
        let mut wkq = vec![Iv::point(0.0); n * n];
        for &(i, l, v) in tk {
            for j in 0..n {
                wkq[i * n + j] = wkq[i * n + j].add(Iv::point(v).mul(qi(l, j)));
            }
        }
        let p = ymul(&wkq);
        for (gi, pi) in g.iter_mut().zip(&p) {
            let v = up(h[k] * pi.mag());
            *gi = up(*gi + v);
            scores[k] += v;
        }
        yterms.push(p);
    }
    let m0 = t.clone();
    for (ti, gi) in t.iter_mut().zip(&g) {
        *ti = ti.widen(*gi);
    }
    let m = n - 2;
    let tb = |i: usize, j: usize| t[i * n + j];
    // sep(T11, T22) over the cell
    let tm = |i: usize, j: usize| mid(tb(i, j));
    let tr = |i: usize, j: usize| tb(i, j).mid_rad().1;
    let kk = DMatrix::from_fn(2 * m, 2 * m, |row, colm| {
        let (i, j) = (row % m, row / m);
        let (i2, j2) = (colm % m, colm / m);
        let mut v = 0.0;
        if i == i2 {
            v += tm(j2, j);
        }
        if j == j2 {
            v -= tm(2 + i, 2 + i2);
        }
        v
    });
    let kinv = verified_inverse(&kk)?;
    // ||K^{-1}||_2 (the operator norm of L0^{-1} on the Frobenius norm)
    // and the spectral norms of the variations of T11 and T22
    let kinv_mag: Vec<f64> = kinv.iter().map(|x| x.mag()).collect();
    let kinv_f = norm2_op_upper(&kinv_mag, 2 * m, 2 * m);
    let r11 = norm2_op_upper(&(0..4).map(|t| tr(t / 2, t % 2)).collect::<Vec<_>>(), 2, 2);
    let r22 = norm2_op_upper(
        &(0..m * m)
            .map(|t| tr(2 + t / m, 2 + t % m))
            .collect::<Vec<_>>(),
        m,
        m,
    );
    // b >= ||L0^{-1} dL_r|| over the cell (math doc section 15, "G1 over a
    // cell"): dL_r has the Kronecker matrix K(T(r) - mid T) with
    // T(r) - mid T in (M0 - mid T) + sum_k d_k Y W_k Q, so
    // |K0^{-1} dK| <= |kinv K(M0 - mid T)| + sum_k h_k |kinv K(Y W_k Q)|
    // entrywise; the plain bound (||rad T11||_2 + ||rad T22||_2) ||K0^{-1}||_2
    // is kept when smaller
    let mut pre = vec![0.0f64; 4 * m * m];
    let centre_dev = kron_op(m, |i, j| m0[i * n + j].sub(Iv::point(tm(i, j))));
    add_product_mag(&mut pre, &kinv, &centre_dev, 2 * m, 1.0);
    for (k, yk) in yterms.iter().enumerate() {
        add_product_mag(
            &mut pre,
            &kinv,
            &kron_op(m, |i, j| yk[i * n + j]),
            2 * m,
            h[k],
        );
    }
    let mut b = norm2_op_upper(&pre, 2 * m, 2 * m).min(up(up(r11 + r22) * kinv_f));
    if tamper == CellTamper::ShrinkSubspaceVariation {
        b /= 8.0;
    }
    let gamma = norm2_upper((0..2 * m).map(|t| tb(2 + t / 2, t % 2).mag()));
    // eta >= ||T12||_2 suffices: ||P T12 P||_F <= ||P||_F^2 ||T12||_2
    let eta = norm2_op_upper(
        &(0..2 * m)
            .map(|t| tb(t / m, 2 + t % m).mag())
            .collect::<Vec<_>>(),
        2,
        m,
    );
    // affine forms: symbols 0..n the ratios, n + 2k + j the entries P_kj,
    // then one named remainder per form of N, of the lifted basis and of
    // the ring (math doc section 15, "Named remainders")
    let mut named = Named::new(n + 2 * m);
    // the forms are computed over the symbols that exist before the ring
    // points are named (`ns`, the ratios, `D`, `N` and the lifted basis);
    // the `18n` symbols of the ring points are appended when they are
    // named, the only place they occur
    let full = n + 2 * m + named_remainders(n);
    let ns = full - RING_POINT_NAMES * n;
    let t_af = |a: usize, b: usize| -> Af {
        let (c, r) = m0[a * n + b].mid_rad();
        let mut f = Af::constant(c, ns);
        let mut e = r;
        for (k, p) in yterms.iter().enumerate() {
            let (pm, pr) = p[a * n + b].mid_rad();
            let v = h[k] * pm;
            f.l[k] = v;
            e = up(up(e + up(h[k] * pr)) + up(up(v.abs() * f64::EPSILON) + f64::MIN_POSITIVE));
        }
        f.widen(e)
    };
    let t21: Vec<Af> = (0..2 * m).map(|v| t_af(2 + v % m, v / m)).collect();
    // P^ = L0^{-1}(T21(r)): first order in the ratios, with
    // L0(P) = P mid(T11) - mid(T22) P (kinv encloses the inverse of its
    // Kronecker matrix), and p_hat >= sup ||P^||_F over the cell
    let phat: Vec<Af> = (0..2 * m)
        .map(|v| {
            let mut acc = Af::constant(0.0, ns);
            for (u, tu) in t21.iter().enumerate() {
                acc.add_scaled(1.0, &tu.mul_iv(kinv[v * 2 * m + u]));
            }
            acc
        })
        .collect();
    let p_hat = norm2_upper(phat.iter().map(|f| f.range().mag())).min(up(gamma * kinv_f));
    // the fixed point of Phi(P) = L0^{-1}(T21 - dL_r(P) - P T12 P) in the
    // ball ||P||_F <= rho (math doc section 15, "G1 over a cell")
    let c = up(eta * kinv_f);
    let mut rho = contraction_radius(p_hat, b, c)?;
    // D = P - P^ = -L0^{-1}(dL_r(P) + P T12 P), so
    // ||D||_F <= b (p_hat + ||D||_F) + c rho^2, i.e.
    // ||D||_F <= (b p_hat + c rho^2) / (1 - b) for every bound rho >= ||P||_F;
    // then ||P||_F <= p_hat + ||D||_F is a new bound, and the two are iterated
    let one_minus_b = down(1.0 - b);
    let d_bound = |rho: f64| up(up(up(b * p_hat) + up(c * up(rho * rho))) / one_minus_b);
    let stewart = rho;
    let mut eps2 = d_bound(rho);
    for _ in 0..RHO_ITERATIONS {
        let next = up(p_hat + eps2);
        if !(next < rho) {
            break;
        }
        rho = next;
        eps2 = d_bound(rho);
    }
    match tamper {
        CellTamper::DropSubspaceVariation => rho = 0.0,
        CellTamper::ShrinkStewartRadius => {
            rho = stewart / 64.0;
            eps2 = 0.0;
        }
        CellTamper::None | CellTamper::DropPairCrossTerm | CellTamper::ShrinkSubspaceVariation => {}
    }
    // N = T11 + T12 P
    let t12_row = |a: usize| norm2_upper((0..m).map(|k| tb(a, 2 + k).mag()));
    let nb: [Iv; 4] = std::array::from_fn(|ab| {
        let (a, b) = (ab / 2, ab % 2);
        tb(a, b).widen(up(rho * t12_row(a)))
    });
    let pmat: Vec<Af> = (0..2 * m)
        .map(|v| {
            let (k, j) = (v % m, v / m);
            if tamper == CellTamper::DropSubspaceVariation {
                return Af::constant(0.0, ns);
            }
            phat[v].add(&Af::symbol(0.0, eps2, n + 2 * k + j, ns))
        })
        .collect();
    let pk = |k: usize, j: usize| &pmat[k + m * j];
    let nf: Vec<Af> = (0..4)
        .map(|ab| {
            let (a, b) = (ab / 2, ab % 2);
            let mut acc = t_af(a, b);
            for k in 0..m {
                acc.add_scaled(1.0, &t_af(a, 2 + k).mul(pk(k, b)));
            }
            named.name(acc)
        })
        .collect();
    // N lies in both enclosures (the interval one and the affine forms'
    // range), so in their intersection
    let mut restriction = [Iv::point(0.0); 4];
    for k in 0..4 {
        let f = nf[k].range();
        let (a, b) = (f.lo.max(nb[k].lo), f.hi.min(nb[k].hi));
        if !(a <= b) {
            return None;
        }
        restriction[k] = Iv::new(a, b);
    }
    let drop_cross = tamper == CellTamper::DropPairCrossTerm;
    let pair = pair_moduli_with(&restriction, Some(&nf), drop_cross);
    let mut rest_radius = 0.0;
    // the pair is the subdominant one: min |spec N| > spectral radius of K'
    if m > 1 {
        let mk = m - 1;
        let t12_col = |j: usize| norm2_upper((0..2).map(|a| tb(a, 2 + j).mag()));
        let widen = |j: usize| up(rho * t12_col(j));
        let kp: Vec<Iv> = (0..mk * mk)
            .map(|ij| {
                let (i, j) = (1 + ij / mk, 1 + ij % mk);
                tb(2 + i, 2 + j).widen(widen(j))
            })
            .collect();
        let mut rad = spectral_radius_upper(&kp, mk, &blocks);
        if mk == 2 {
            // a 2 x 2 K': the root bound of its characteristic polynomial
            let kf: Vec<Af> = (0..4)
                .map(|ij| {
                    let (i, j) = (1 + ij / 2, 1 + ij % 2);
                    t_af(2 + i, 2 + j).widen(widen(j))
                })
                .collect();
            rad =
                rad.min(pair_moduli_with(&[kp[0], kp[1], kp[2], kp[3]], Some(&kf), drop_cross).max);
        }
        rest_radius = rad;
        if !(pair.min > rad) {
            return None;
        }
    }
    let lay = Layout::new(n);
    let zero = Af::constant(0.0, ns);
    let mut w: Vec<[Af; 2]> = vec![[zero.clone(), zero.clone()]; 4 * n];
    for a in 0..n {
        w[lay.p(a)] = std::array::from_fn(|b| {
            let mut acc = Af::constant(q[(a, b)], ns);
            for k in 0..m {
                acc.add_scaled(q[(a, 2 + k)], pk(k, b));
            }
            acc
        });
    }
    let ratio = |i: usize| Af::symbol(r0[i], h[i], i, ns);
    let one = Af::constant(1.0, ns);
    // E parts: B_i X - X N = -G_i [w_{P_i}; w_{P_{i+1}}]
    for i in 0..n {
        let r = ratio(i);
        let bm = [
            one.add(&r).scale(0.125),
            one.sub(&r).scale(0.125),
            r.scale(0.125),
            Af::constant(2.0, ns).sub(&r).scale(0.125),
        ];
        let wp = [w[lay.p(i)].clone(), w[lay.p(i + 1)].clone()];
        let mut rhs = vec![zero.clone(); 4];
        for a in 0..2 {
            for k in 0..2 {
                let g = bm[2 * a].mul(&wp[0][k]).add(&bm[2 * a + 1].mul(&wp[1][k]));
                rhs[a + 2 * k] = g.scale(-3.0);
            }
        }
        let mut sys = vec![zero.clone(); 16];
        for a in 0..2 {
            for k in 0..2 {
                let eq = a + 2 * k;
                for c in 0..2 {
                    sys[eq * 4 + c + 2 * k] = sys[eq * 4 + c + 2 * k].add(&bm[2 * a + c]);
                }
                for l in 0..2 {
                    sys[eq * 4 + a + 2 * l] = sys[eq * 4 + a + 2 * l].sub(&nf[2 * l + k]);
                }
            }
        }
        let x: Vec<Af> = af::solve(&sys, &[rhs], 4)?
            .pop()?
            .into_iter()
            .map(|f| named.name(f))
            .collect();
        w[lay.e1(i)] = [x[0].clone(), x[2].clone()];
        w[lay.e2(i)] = [x[1].clone(), x[3].clone()];
    }
    // C parts: X_c (N - I/16) = (9 w_{P_i} + 3 w_{E_i1} + 3 w_{E_{i-1,2}}) / 16
    let ntm = [
        nf[0].sub(&Af::constant(0.0625, ns)),
        nf[2].clone(),
        nf[1].clone(),
        nf[3].sub(&Af::constant(0.0625, ns)),
    ];
    let rhs_c: Vec<Vec<Af>> = (0..n)
        .map(|i| {
            (0..2)
                .map(|k| {
                    w[lay.p(i)][k]
                        .scale(9.0)
                        .add(&w[lay.e1(i)][k].scale(3.0))
                        .add(&w[lay.e2(i + n - 1)][k].scale(3.0))
                        .scale(0.0625)
                })
                .collect()
        })
        .collect();
    let xc = af::solve(&ntm, &rhs_c, 2)?;
    for (i, x) in xc.into_iter().enumerate() {
        w[lay.c(i)] = [named.name(x[0].clone()), named.name(x[1].clone())];
    }
    // the 9n ring points
    let mut pts: Vec<[Af; 2]> = Vec::with_capacity(9 * n);
    for wk in &w {
        pts.push([
            wk[0].mul(&nf[0]).add(&wk[1].mul(&nf[2])),
            wk[0].mul(&nf[1]).add(&wk[1].mul(&nf[3])),
        ]);
    }
    let comb = |terms: &[(Af, &[Af; 2])]| -> [Af; 2] {
        std::array::from_fn(|k| {
            let mut acc = zero.clone();
            for (c, v) in terms {
                acc.add_scaled(1.0, &c.mul(&v[k]));
            }
            acc
        })
    };
    for i in 0..n {
        let r = ratio(i);
        let s = one.sub(&r);
        let (pi, pn, e1, e2) = (&w[lay.p(i)], &w[lay.p(i + 1)], &w[lay.e1(i)], &w[lay.e2(i)]);
        // (E_i, E_i1)
        pts.push(comb(&[
            (one.add(&r).scale(0.125), pi),
            (s.scale(0.125), pn),
            (s.scale(0.375), e2),
            (one.add(&r).scale(0.375), e1),
        ]));
        // (E_i, E_i2)
        pts.push(comb(&[
            (r.scale(0.125), pi),
            (one.add(&s).scale(0.125), pn),
            (one.add(&s).scale(0.375), e2),
            (r.scale(0.375), e1),
        ]));
    }
    let c9 = Af::constant(0.5625, ns);
    let c3 = Af::constant(0.1875, ns);
    let c1 = Af::constant(0.0625, ns);
    for i in 0..n {
        let (pi, e1, ci, e2p) = (
            &w[lay.p(i)],
            &w[lay.e1(i)],
            &w[lay.c(i)],
            &w[lay.e2(i + n - 1)],
        );
        pts.push(comb(&[
            (c9.clone(), e1),
            (c3.clone(), pi),
            (c3.clone(), ci),
            (c1.clone(), e2p),
        ]));
        pts.push(comb(&[
            (c9.clone(), ci),
            (c3.clone(), e1),
            (c3.clone(), e2p),
            (c1.clone(), pi),
        ]));
        pts.push(comb(&[
            (c9.clone(), e2p),
            (c3.clone(), ci),
            (c3.clone(), pi),
            (c1.clone(), e1),
        ]));
    }
    let pts: Vec<[Af; 2]> = pts
        .into_iter()
        .map(|[a, b]| [named.name(a.extended(full)), named.name(b.extended(full))])
        .collect();
    debug_assert_eq!(named.next, full);
    let boxes =
        |v: &[[Af; 2]]| -> Vec<P2> { v.iter().map(|p| [p[0].range(), p[1].range()]).collect() };
    Some(RatioRing {
        q,
        rho,
        restriction,
        pair,
        rest_radius,
        correction: phat,
        correction_radius: eps2,
        basis: boxes(&w),
        points: boxes(&pts),
        forms: pts,
        scores,
        centre: r0,
        half_width: h,
    })
}

/// The symbols with a non-zero coefficient in some form of `forms`, and
/// `always`, in increasing order.
fn used_symbols<'a>(forms: impl Iterator<Item = &'a Af>, always: usize) -> Vec<usize> {
    let mut mask: Vec<bool> = Vec::new();
    for f in forms {
        if mask.len() < f.l.len() {
            mask.resize(f.l.len(), false);
        }
        for (m, x) in mask.iter_mut().zip(&f.l) {
            *m |= *x != 0.0;
        }
    }
    if always < mask.len() {
        mask[always] = true;
    }
    (0..mask.len()).filter(|&k| mask[k]).collect()
}

/// The form `f` over the symbols `used` only (renumbered `0..used.len()`):
/// exact when `f`'s other coefficients are zero.
fn compact(f: &Af, used: &[usize]) -> Af {
    Af {
        c: f.c,
        l: used.iter().map(|&k| f.l[k]).collect(),
        e: f.e,
    }
}

/// The Bezier net (3 x 3, `b[a][c]`, `a` along `s`) of ring patch `id` as
/// affine forms over the patch's own symbols: the ratio of its span and
/// every symbol with a non-zero coefficient in one of its nine ring
/// points, renumbered in order ([`compact`]); the others are zero in every
/// form of the patch, its Jacobian included.
fn bezier_net(ring: &RatioRing, n: usize, id: RingPatchId) -> Option<[[[Af; 2]; 3]; 3]> {
    let g = patch_grid(n, id);
    let i = id.index % n;
    let ids: Vec<usize> = g.iter().flatten().copied().collect();
    let used = used_symbols(ids.iter().flat_map(|&k| &ring.forms[k]), i);
    let ns = used.len();
    let local =
        |k: usize| -> [Af; 2] { std::array::from_fn(|c| compact(&ring.forms[k][c], &used)) };
    let ri = used.binary_search(&i).ok()?;
    let r = Af::symbol(ring.centre[i], ring.half_width[i], ri, ns);
    let half = |a: &[Af; 2], b: &[Af; 2]| -> [Af; 2] {
        std::array::from_fn(|k| a[k].add(&b[k]).scale(0.5))
    };
    // b + r (a - b)
    let lerp = |b: &[Af; 2], a: &[Af; 2]| -> [Af; 2] {
        std::array::from_fn(|k| b[k].add(&r.mul(&a[k].sub(&b[k]))))
    };
    // conversion along s: A (s, s, r): [1/2 1/2 0; 0 1 0; 0 r s];
    // B (s, r, r): [r s 0; 0 1 0; 0 1/2 1/2]; C uniform
    let conv_s = |p: &[[Af; 2]; 3]| -> [[Af; 2]; 3] {
        match id.kind {
            PatchKind::A => [half(&p[0], &p[1]), p[1].clone(), lerp(&p[2], &p[1])],
            PatchKind::B => [lerp(&p[1], &p[0]), p[1].clone(), half(&p[1], &p[2])],
            PatchKind::C => [half(&p[0], &p[1]), p[1].clone(), half(&p[1], &p[2])],
        }
    };
    let conv_t = |p: &[[Af; 2]; 3]| -> [[Af; 2]; 3] {
        [half(&p[0], &p[1]), p[1].clone(), half(&p[1], &p[2])]
    };
    let cols: Vec<[[Af; 2]; 3]> = (0..3)
        .map(|c| conv_s(&std::array::from_fn(|a| local(g[a][c]))))
        .collect();
    Some(std::array::from_fn(|a| {
        conv_t(&std::array::from_fn(|c| cols[c][a].clone()))
    }))
}

/// The Jacobian's Bezier coefficients (bidegree (3, 3)) of a biquadratic
/// net, each multiplied by the positive factor `C(3, k) C(3, l) / 4`:
/// `sum C(1,i) C(2,i') C(2,j) C(1,j') det(b_{i+1,j} - b_{ij}, b_{i',j'+1} - b_{i'j'})`.
fn jacobian_scaled(b: &[[[Af; 2]; 3]; 3]) -> Vec<Vec<Af>> {
    let d = |p: &[Af; 2], q: &[Af; 2]| -> [Af; 2] { std::array::from_fn(|k| p[k].sub(&q[k])) };
    let ds: Vec<Vec<[Af; 2]>> = (0..2)
        .map(|i| (0..3).map(|j| d(&b[i + 1][j], &b[i][j])).collect())
        .collect();
    let dt: Vec<Vec<[Af; 2]>> = (0..3)
        .map(|i| (0..2).map(|j| d(&b[i][j + 1], &b[i][j])).collect())
        .collect();
    let ns = b[0][0][0].symbols();
    let c1 = [1.0, 1.0];
    let c2 = [1.0, 2.0, 1.0];
    let mut out = vec![vec![Af::constant(0.0, ns); 4]; 4];
    for i in 0..2 {
        for j in 0..3 {
            for i2 in 0..3 {
                for j2 in 0..2 {
                    let wgt = c1[i] * c2[i2] * c2[j] * c1[j2];
                    out[i + i2][j + j2].add_scaled(wgt, &det(&ds[i][j], &dt[i2][j2]));
                }
            }
        }
    }
    out
}

/// de Casteljau halves of a 4 x 4 Bernstein coefficient grid (`c[k][l]`)
/// at the parameter `1/2` of the index `axis` (0: `k`, 1: `l`): per line
/// the seven points `p_0, p_01, p_012, p_0123, p_123, p_23, p_3`, of which
/// the first four are the left half's and the last four the right half's.
fn split_half(c: &[Vec<Af>], axis: usize) -> (Vec<Vec<Af>>, Vec<Vec<Af>>) {
    let at = |line: usize, k: usize| if axis == 0 { &c[k][line] } else { &c[line][k] };
    let lines: Vec<[Af; 7]> = (0..4)
        .map(|line| {
            let mid = |a: &Af, b: &Af| a.add(b).scale(0.5);
            let (p0, p1, p2, p3) = (at(line, 0), at(line, 1), at(line, 2), at(line, 3));
            let (a, b, d) = (mid(p0, p1), mid(p1, p2), mid(p2, p3));
            let (ab, bd) = (mid(&a, &b), mid(&b, &d));
            let centre = mid(&ab, &bd);
            [p0.clone(), a, ab, centre, bd, d, p3.clone()]
        })
        .collect();
    let half = |offset: usize| -> Vec<Vec<Af>> {
        (0..4)
            .map(|k| {
                (0..4)
                    .map(|l| {
                        let (line, t) = if axis == 0 { (l, k) } else { (k, l) };
                        lines[line][offset + t].clone()
                    })
                    .collect()
            })
            .collect()
    };
    (half(0), half(3))
}

/// The sign `sigma` of the Jacobian that the first patch's first
/// coefficient gives (`None` when that coefficient's centre is zero).
fn jacobian_orientation(c: &[Vec<Af>]) -> Option<f64> {
    let c0 = c.first()?.first()?.c;
    if c0 > 0.0 {
        Some(1.0)
    } else if c0 < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// `sigma J > 0` on one patch for every parameter, from its Jacobian
/// coefficients `c` ([`jacobian_scaled`]): checked as they are, then split
/// by de Casteljau (unscaled) up to [`JACOBIAN_DEPTH`] levels, counting the
/// pieces of the cell in `pieces` (at most [`JACOBIAN_PIECES`]). A corner
/// coefficient is the Jacobian's value at a corner of its piece, and de
/// Casteljau passes it unchanged to the sub-piece at that corner: a piece
/// with a corner coefficient not of the sign `sigma` can never be
/// certified, so the test stops there.
fn jacobian_signed(c: Vec<Vec<Af>>, sigma: f64, pieces: &mut usize) -> bool {
    let signed = |v: &Af| {
        let r = v.range();
        if sigma > 0.0 {
            r.lo > 0.0
        } else {
            r.hi < 0.0
        }
    };
    let positive = |c: &[Vec<Af>]| c.iter().flatten().all(signed);
    let corners_signed = |c: &[Vec<Af>]| {
        [(0, 0), (0, 3), (3, 0), (3, 3)]
            .iter()
            .all(|&(k, l)| signed(&c[k][l]))
    };
    if positive(&c) {
        return true;
    }
    if !corners_signed(&c) {
        return false;
    }
    let binom = [1.0, 3.0, 3.0, 1.0];
    // unscale: divide by C(3,k) C(3,l) in {1, 3, 9} (rounding into the remainder)
    let u: Vec<Vec<Af>> = (0..4)
        .map(|k| {
            (0..4)
                .map(|l| {
                    let d = binom[k] * binom[l];
                    let v = c[k][l].scale(1.0 / d);
                    // 1/d is rounded: |x/d - x fl(1/d)| <= |x| u / d
                    v.widen(up(c[k][l].range().mag() * f64::EPSILON))
                })
                .collect()
        })
        .collect();
    let mut work = vec![(u, 0u32)];
    while let Some((c, depth)) = work.pop() {
        *pieces += 1;
        if positive(&c) {
            continue;
        }
        if !corners_signed(&c)
            || depth >= JACOBIAN_DEPTH
            || *pieces + work.len() + 4 > JACOBIAN_PIECES
        {
            return false;
        }
        let (l, r) = split_half(&c, 0);
        for half in [l, r] {
            let (a, b) = split_half(&half, 1);
            work.push((a, depth + 1));
            work.push((b, depth + 1));
        }
    }
    true
}

/// A quadratic Bezier curve with box control points.
#[derive(Clone, Debug)]
struct BezBox(Vec<P2>);

impl BoxCurve for BezBox {
    fn hull(&self) -> Vec<P2> {
        self.0.clone()
    }
    fn halves(&self) -> (Self, Self) {
        let mut pts = self.0.clone();
        let d = pts.len();
        let mut left = vec![pts[0]];
        let mut right = vec![pts[d - 1]];
        for level in 1..d {
            for k in 0..d - level {
                pts[k] = [
                    pts[k][0].add(pts[k + 1][0]).mul(Iv::point(0.5)),
                    pts[k][1].add(pts[k + 1][1]).mul(Iv::point(0.5)),
                ];
            }
            left.push(pts[0]);
            right.push(pts[d - 1 - level]);
        }
        right.reverse();
        (BezBox(left), BezBox(right))
    }
}

/// Whether the characteristic map is certified regular and injective for
/// every ratio vector of the box (given that the cell's class is certified
/// `complex_pair`, `real_distinct` or `standard`), with the split scores.
pub fn certified(lo: &[f64], hi: &[f64], tamper: CellTamper) -> (bool, Option<Vec<f64>>) {
    let Some(ring) = ratio_ring(lo, hi, tamper) else {
        return (false, None);
    };
    let scores = Some(ring.scores.clone());
    (map_certified(&ring), scores)
}

/// The spectral part of the `g1` property from the restriction `N` of the
/// pair's invariant subspace (math doc section 15, "G1 over a cell"): for
/// every matrix of the enclosure of `N` ([`RatioRing::pair`], from the
/// interval matrix and the affine forms, [`pair_moduli`]),
///
/// * `det N > 0`: the next ring is the image of this one under the
///   orientation-preserving linear map `x -> x N`;
/// * every eigenvalue modulus `< 1`: `1` stays the simple dominant
///   eigenvalue;
/// * every eigenvalue modulus `> 1/4`: the pair lies above the fixed
///   eigenvalues `1/4, 1/8, 1/16` of the `E` and `V` blocks (section 4).
///
/// Separation from the rest of the face block's spectrum is part of the
/// enclosure itself ([`ratio_ring_with`]).
pub fn g1_spectrum(pair: &PairModuli) -> bool {
    pair.det.lo > 0.0 && pair.max < 1.0 && pair.min > G1_FIXED_MODULUS
}

/// The largest modulus of the fixed eigenvalues of `S_n` outside the face
/// block (`1/4` of the `E` blocks, math doc section 4): the pair must lie
/// strictly above it.
pub const G1_FIXED_MODULUS: f64 = 0.25;

/// The `g1` property over the ratio box (math doc section 15, "G1 over a
/// cell"): for every ratio vector of the box the two largest eigenvalues of
/// `spec(A) \ {1}`, as a set, are separated from the rest of the spectrum of
/// `S_n`, `det N > 0`, and the characteristic map built from the basis
/// `Q [I; P(r)]` of their real invariant subspace ([`PairBasis::Schur`]) is
/// regular and injective. No class is needed. Returns the verdict and the
/// split scores.
pub fn g1_certified(lo: &[f64], hi: &[f64], tamper: CellTamper) -> (bool, Option<Vec<f64>>) {
    let Some(ring) = ratio_ring_with(lo, hi, tamper, PairBasis::Schur) else {
        return (false, None);
    };
    let scores = Some(ring.scores.clone());
    if !g1_spectrum(&ring.pair) {
        return (false, scores);
    }
    (map_certified(&ring), scores)
}

/// Whether the enclosed ring is regular (one Jacobian sign on every patch
/// for every parameter) and its outer boundary winds once after orientation.
/// The patches' nets are built one at a time and dropped after their
/// Jacobian test (only their boundary curves are kept, as boxes), so a
/// patch that fails stops the test before the later nets are built.
fn map_certified(ring: &RatioRing) -> bool {
    let n = ring.centre.len();
    let bx = |p: &[Af; 2]| -> P2 { [p[0].range(), p[1].range()] };
    let top = |b: &[[[Af; 2]; 3]; 3]| BezBox((0..3).map(|a| bx(&b[a][2])).collect());
    let left = |b: &[[[Af; 2]; 3]; 3]| BezBox((0..3).map(|c| bx(&b[0][c])).collect());
    let mut sigma = None;
    let mut pieces = 0usize;
    // per patch 3 i + k (kinds A, B, C): the top and left boundary curves
    let mut edges: Vec<(BezBox, BezBox)> = Vec::with_capacity(3 * n);
    for i in 0..n {
        for kind in [PatchKind::A, PatchKind::B, PatchKind::C] {
            let Some(net) = bezier_net(ring, n, RingPatchId { kind, index: i }) else {
                return false;
            };
            let c = jacobian_scaled(&net);
            let s = match sigma {
                Some(s) => s,
                None => match jacobian_orientation(&c) {
                    Some(s) => *sigma.insert(s),
                    None => return false,
                },
            };
            if !jacobian_signed(c, s, &mut pieces) {
                return false;
            }
            edges.push((top(&net), left(&net)));
        }
    }
    let Some(sigma) = sigma else {
        return false;
    };
    let mut fwd = Vec::with_capacity(4 * n);
    for i in 0..n {
        fwd.push(edges[3 * i].0.clone());
        fwd.push(edges[3 * i + 1].0.clone());
        let c = &edges[3 * ((i + 1) % n) + 2];
        fwd.push(c.1.clone());
        fwd.push(c.0.clone());
    }
    let curves: Vec<BezBox> = fwd
        .into_iter()
        .rev()
        .map(|mut b| {
            b.0.reverse();
            b
        })
        .collect();
    match winding_number(&curves) {
        Some(wn) => (sigma * wn as f64) == 1.0,
        None => false,
    }
}

impl RatioRing {
    /// The ring at one ratio vector `r` of the cell, in floating point, in
    /// the normalisation `Q [I; P(r)]` of this enclosure (for the soundness
    /// tests): `(||P(r)||_F, the 9n ring points)`. The pair's eigenvectors of
    /// `W(r)` (the two largest moduli other than `3/4`) give `P` by
    /// `[Z_1; Z_2] = Q^{-1} B`, `P = Z_2 Z_1^{-1}`; the restriction is
    /// `N = T11 + T12 P` of `Q^{-1} W(r) Q`; the lift is
    /// [`crate::charmap::basis::lift_subspace`] and the ring
    /// [`crate::schemes::doo_sabin::ring::ring_points`].
    pub fn pointwise(&self, r: &[f64]) -> crate::error::Result<(f64, Vec<[f64; 2]>)> {
        use crate::knots::EdgeRatios;
        use crate::schemes::doo_sabin::extended::ExtendedMatrix;
        use crate::schemes::LocalScheme;
        let n = r.len();
        let (w, p, qinv) = self.pointwise_graph(r)?;
        let mut ip = DMatrix::zeros(n, 2);
        ip[(0, 0)] = 1.0;
        ip[(1, 1)] = 1.0;
        ip.rows_mut(2, n - 2).copy_from(&p);
        let basis = &self.q * ip;
        let t = &qinv * &w * &self.q;
        let nmat = t.view((0, 0), (2, 2)).into_owned() + t.view((0, 2), (2, n - 2)) * &p;
        let scheme = LocalScheme::nurds(EdgeRatios::new(r.to_vec())?);
        let sn = scheme.matrix()?.into_matrix();
        let wa: Vec<[f64; 2]> = (0..n).map(|i| [basis[(i, 0)], basis[(i, 1)]]).collect();
        let m = [[nmat[(0, 0)], nmat[(0, 1)]], [nmat[(1, 0)], nmat[(1, 1)]]];
        let full = crate::charmap::basis::lift_subspace(&sn, &wa, m)?;
        let w1: Vec<f64> = full.iter().map(|x| x[0]).collect();
        let w2: Vec<f64> = full.iter().map(|x| x[1]).collect();
        let ext = ExtendedMatrix::new(&scheme)?;
        Ok((
            p.norm(),
            crate::schemes::doo_sabin::ring::ring_points(&ext, &w1, &w2)?,
        ))
    }

    /// The eigenvalue moduli of `W(r)` at one ratio vector `r` of the cell,
    /// in floating point, for the soundness tests: the pair (the two
    /// largest other than the eigenvalue nearest `3/4`, largest first) and
    /// the largest of the rest (`0` when there is none).
    pub fn pointwise_moduli(&self, r: &[f64]) -> crate::error::Result<([f64; 2], f64)> {
        let (w, _, _) = self.pointwise_graph(r)?;
        let vals = Eigen::new(
            &w,
            EigenOptions {
                right: false,
                left: false,
            },
        )
        .map_err(|e| crate::error::Error::Numerical {
            routine: "pointwise spectrum in the cell",
            reason: e.to_string(),
        })?
        .values()
        .to_vec();
        let k34 = (0..vals.len())
            .min_by(|&a, &b| (vals[a] - 0.75).norm().total_cmp(&(vals[b] - 0.75).norm()))
            .unwrap_or(0);
        let mut mods: Vec<f64> = (0..vals.len())
            .filter(|&k| k != k34)
            .map(|k| vals[k].norm())
            .collect();
        mods.sort_by(|a, b| b.total_cmp(a));
        let rest = mods.get(2).copied().unwrap_or(0.0);
        match mods[..] {
            [a, b, ..] => Ok(([a, b], rest)),
            _ => Err(crate::error::Error::Numerical {
                routine: "pointwise spectrum in the cell",
                reason: "fewer than two eigenvalues besides 3/4".to_owned(),
            }),
        }
    }

    /// How many entries of the pointwise `P(r)` (in this enclosure's
    /// normalisation, as in [`RatioRing::pointwise`]) lie farther from the
    /// first-order part `P^(r)` than the bound of `D = P - P^` allows (plus
    /// the forms' rounding remainder and `tol`), for the soundness tests.
    pub fn correction_misses(&self, r: &[f64], tol: f64) -> crate::error::Result<usize> {
        let n = r.len();
        let m = n - 2;
        let (_, p, _) = self.pointwise_graph(r)?;
        let mut bad = 0;
        for (v, f) in self.correction.iter().enumerate() {
            let (k, j) = (v % m, v / m);
            let mut at = f.c;
            for i in 0..n {
                if self.half_width[i] > 0.0 {
                    at += f.l[i] * (r[i] - self.centre[i]) / self.half_width[i];
                }
            }
            let slack = f.l[n..].iter().fold(f.e, |a, x| a + x.abs());
            if (p[(k, j)] - at).abs() > self.correction_radius + slack + tol {
                bad += 1;
            }
        }
        Ok(bad)
    }

    /// `(W(r), P(r), Q^{-1})` in floating point: `P = Z_2 Z_1^{-1}` for the
    /// pair's eigenvectors `[Z_1; Z_2] = Q^{-1} B` of `W(r)`.
    fn pointwise_graph(
        &self,
        r: &[f64],
    ) -> crate::error::Result<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>)> {
        use crate::error::Error;
        let n = r.len();
        let bad = |reason: &str| Error::Numerical {
            routine: "pointwise ring in the cell normalisation",
            reason: reason.to_owned(),
        };
        if n != self.q.nrows() {
            return Err(bad("valence differs from the enclosure's"));
        }
        let (c0, terms) = w_terms(n);
        let mut w = DMatrix::zeros(n, n);
        for &(i, j, v) in &c0 {
            w[(i, j)] += v;
        }
        for (k, t) in terms.iter().enumerate() {
            for &(i, j, v) in t {
                w[(i, j)] += v * r[k];
            }
        }
        let eig = Eigen::new(
            &w,
            EigenOptions {
                right: true,
                left: false,
            },
        )
        .map_err(|e| bad(&e.to_string()))?;
        let vals = eig.values();
        let vecs = eig.right().ok_or_else(|| bad("no eigenvectors"))?;
        let k34 = (0..n)
            .min_by(|&a, &b| (vals[a] - 0.75).norm().total_cmp(&(vals[b] - 0.75).norm()))
            .ok_or_else(|| bad("empty spectrum"))?;
        let order: Vec<usize> = (0..n).filter(|&k| k != k34).collect();
        let (a, b) = (order[0], order[1]);
        let real = |k: usize| -> Vec<f64> {
            let big = (0..n)
                .map(|i| vecs[(i, k)])
                .max_by(|x, y| x.norm().total_cmp(&y.norm()))
                .unwrap_or(Complex64::new(1.0, 0.0));
            let ph = big.conj() / big.norm();
            (0..n).map(|i| (vecs[(i, k)] * ph).re).collect()
        };
        let bmat = if vals[a].im.abs() > REAL_TOL * vals[a].norm().max(1.0) {
            DMatrix::from_fn(n, 2, |i, j| {
                if j == 0 {
                    vecs[(i, a)].re
                } else {
                    vecs[(i, a)].im
                }
            })
        } else {
            let (va, vb) = (real(a), real(b));
            DMatrix::from_fn(n, 2, |i, j| if j == 0 { va[i] } else { vb[i] })
        };
        let qinv = self
            .q
            .clone()
            .try_inverse()
            .ok_or_else(|| bad("Q is singular"))?;
        let z = &qinv * &bmat;
        let z1 = z
            .rows(0, 2)
            .into_owned()
            .try_inverse()
            .ok_or_else(|| bad("the pair is not a graph over Q's first two columns"))?;
        let p = z.rows(2, n - 2).into_owned() * z1;
        Ok((w, p, qinv))
    }

    /// How many coordinates of the pointwise ring `pts` lie outside the
    /// enclosure by more than `tol (1 + |x|)`, plus one if `p_norm` exceeds
    /// `rho` by more than the same tolerance.
    pub fn misses(&self, p_norm: f64, pts: &[[f64; 2]], tol: f64) -> usize {
        let mut bad = usize::from(p_norm > self.rho + tol * (1.0 + self.rho));
        for (p, e) in pts.iter().zip(&self.points) {
            for k in 0..2 {
                let t = tol * (1.0 + p[k].abs());
                if !(e[k].lo - t <= p[k] && p[k] <= e[k].hi + t) {
                    bad += 1;
                }
            }
        }
        bad + self.points.len().abs_diff(pts.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The value at `(s, t)` of the bicubic Bernstein polynomial whose
    /// coefficients are the centres of `c` (`c[k][l]`, `k` along `s`).
    fn bernstein(c: &[Vec<Af>], s: f64, t: f64) -> f64 {
        let b = |i: usize, x: f64| {
            [1.0, 3.0, 3.0, 1.0][i] * x.powi(i as i32) * (1.0 - x).powi(3 - i as i32)
        };
        let mut v = 0.0;
        for (k, row) in c.iter().enumerate() {
            for (l, x) in row.iter().enumerate() {
                v += x.c * b(k, s) * b(l, t);
            }
        }
        v
    }

    #[test]
    fn de_casteljau_halves_are_the_polynomial_on_each_half() {
        let mut rng = SplitMix64::new(3);
        let c: Vec<Vec<Af>> = (0..4)
            .map(|_| {
                (0..4)
                    .map(|_| Af::constant(rng.uniform(-1.0, 1.0), 1))
                    .collect()
            })
            .collect();
        for axis in 0..2 {
            let (lo, hi) = split_half(&c, axis);
            for i in 0..=4 {
                for j in 0..=4 {
                    let (s, t) = (0.25 * i as f64, 0.25 * j as f64);
                    let (a, b) = if axis == 0 {
                        ((0.5 * s, t), (0.5 + 0.5 * s, t))
                    } else {
                        ((s, 0.5 * t), (s, 0.5 + 0.5 * t))
                    };
                    assert!((bernstein(&lo, s, t) - bernstein(&c, a.0, a.1)).abs() < 1e-12);
                    assert!((bernstein(&hi, s, t) - bernstein(&c, b.0, b.1)).abs() < 1e-12);
                }
            }
        }
    }

    /// `f(s) = m - s + s^2` (minimum `m - 1/4` at `s = 1/2`), constant in
    /// `t`, as the scaled coefficients of [`jacobian_scaled`]: its cubic
    /// Bernstein coefficients `m - i/3 + C(i, 2)/3` times `C(3, k) C(3, l)`.
    fn parabola(m: f64) -> Vec<Vec<Af>> {
        let binom = [1.0, 3.0, 3.0, 1.0];
        let b = [m, m - 1.0 / 3.0, m - 1.0 / 3.0, m];
        (0..4)
            .map(|k| {
                (0..4)
                    .map(|l| Af::constant(b[k] * binom[k] * binom[l], 1))
                    .collect()
            })
            .collect()
    }

    /// Positive with negative coefficients: certified after splitting;
    /// negative inside with positive corners: refused.
    #[test]
    fn jacobian_pieces_decide_the_sign_inside_the_patch() {
        let mut pieces = 0;
        assert!(jacobian_signed(parabola(0.26), 1.0, &mut pieces));
        assert!(pieces > 1, "the coefficients alone are not all positive");
        let mut pieces = 0;
        assert!(!jacobian_signed(parabola(0.24), 1.0, &mut pieces));
        let mut pieces = 0;
        assert!(jacobian_signed(parabola(0.5), 1.0, &mut pieces) && pieces == 0);
    }
}
