//! The characteristic map of the shape-adjustable Catmull-Clark scheme over
//! an interval of `c` (math doc sections 8 and 15 **\[derived\]**).
//!
//! For a cell `[c_lo, c_hi]` on which the class `standard` is certified
//! ([`crate::verify::cc`]: the subdominant pair comes from Fourier mode
//! `l = 1`), the planar control net `(x_cos, x_sin)` of the characteristic
//! map is enclosed for every `c` in the cell, with the normalisation of
//! [`crate::schemes::catmull_clark::fourier::mode_patch_eigenvectors`]
//! (`theta = 2 pi / n`):
//!
//! * `lambda = t/2 + sqrt(t^2/4 - d)`, `t = 3/4 - (c/4)(1 - cos theta)`,
//!   `d = (1 - c)/8` (the larger root of Fourier block 1);
//! * one-ring: `v -> 0`, `e_i -> cos(i theta)`,
//!   `f_i -> (cos(i theta) + cos((i + 1) theta)) / (4 lambda - 1)` (and `sin`);
//! * the 7 outer entries solve `(lambda I - A_oo) x_o = A_or x_r`, whose rows
//!   are the tensor-product rule (weights `c/4, 1 - c/2, c/4` and `1/2, 1/2`),
//!   by the verified interval solve of [`super::ivla::solve`];
//! * the windows of the three regular cells of sector 0: a point of the next
//!   level's patch is `lambda x` (the patch rows of the extended matrix are
//!   the patch matrix, and `A x = lambda x`); the 9 extra points are the
//!   tensor-product rule applied to `x`.
//!
//! Every quantity is an interval over the cell (`c` enters as the interval
//! `[c_lo, c_hi]`; `cos` and `sin` with [`crate::verify::cc::COS_SLACK`]).
//!
//! **Regularity.** The cone test of [`crate::charmap::catmull_clark`] holds
//! for each `c` separately (the derived rule's mask
//! `(c/2, 1 - c/2, 1 - c/2, c/2)` is non-negative): if every pair
//! determinant `det(a, b)` of a `u`-difference `a` and a `v`-difference `b`
//! of the window is positive for *every* `c` and every admissible window,
//! the Jacobian is positive on the cell of the ring for every `c`. The
//! differences are refined directly: the scaled differences of a refined
//! window are the derived rule applied to the parent's differences along
//! their own direction and the rule itself across, both convex combinations,
//! so in midpoint-radius form ([`super::ivla::Mr`]) their radius does not grow
//! with the depth. Sector `j` is sector 0 rotated by `j theta` in the
//! `(x_cos, x_sin)` plane, so its Jacobian has the same sign: the three cells
//! of sector 0 decide the whole ring.
//!
//! **Injectivity.** The outer boundary (per sector the same four limit curves
//! as the pointwise check, rotated) has winding number 1 for every `c`
//! ([`super::winding`]), once the plane is oriented so that the Jacobian is
//! positive.

use super::ivla::{div, solve, sqrt, Mr, P2};
use super::winding::{winding_number, BoxCurve};
use super::CellTamper;
use crate::schemes::catmull_clark::{PatchLayout, SubPatch};
use crate::verify::cc::COS_SLACK;
use crate::verify::interval::{down, up, Iv};

/// Most refinement levels of the cone test per ring cell.
pub const CONE_DEPTH: u32 = 10;

/// Most pieces examined by the cone test per `c` cell.
pub const CONE_PIECES: usize = 20_000;

/// The enclosure of the characteristic ring over a cell of `c`.
#[derive(Clone, Debug)]
pub struct ShapeRing {
    /// The subdominant eigenvalue.
    pub lambda: Iv,
    /// The patch eigenvector (`2n + 8` entries) for the `cos` and `sin` nets.
    pub x: [Vec<Iv>; 2],
    /// The windows of sector 0 (`Omega_1, Omega_2, Omega_3`), `w[a][b]` as in
    /// [`crate::schemes::catmull_clark::ring::Window`], as boxes in `(x_cos, x_sin)`.
    pub windows: [[[P2; 4]; 4]; 3],
}

/// `cos` and `sin` of `2 pi k / n` as intervals (the platform values widened
/// by [`COS_SLACK`], clipped to `[-1, 1]`).
pub fn cos_sin(k: usize, n: usize) -> (Iv, Iv) {
    let phase = 2.0 * std::f64::consts::PI * (k % n) as f64 / n as f64;
    let (s, c) = phase.sin_cos();
    let w = |x: f64| Iv::new(down(x - COS_SLACK).max(-1.0), up(x + COS_SLACK).min(1.0));
    (w(c), w(s))
}

/// The univariate rule at half-grid coordinate `h` with the interval `c`:
/// `(old coordinate, weight)` (vertex mask for even `h`, midpoint for odd).
fn rule(h: usize, c: Iv) -> Vec<(usize, Iv)> {
    if h % 2 == 0 {
        let k = h / 2;
        let q = c.mul(Iv::point(0.25));
        vec![
            (k - 1, q),
            (k, Iv::point(1.0).sub(c.mul(Iv::point(0.5)))),
            (k + 1, q),
        ]
    } else {
        let k = (h - 1) / 2;
        vec![(k, Iv::point(0.5)), (k + 1, Iv::point(0.5))]
    }
}

/// The tensor-product row of the new point at new-grid position `(a, b)`:
/// `(column in the patch layout, weight)`; `None` if it reached the
/// extraordinary corner (never for the outer and extra points).
fn regular_row(lay: &PatchLayout, (a, b): (usize, usize), c: Iv) -> Option<Vec<(usize, Iv)>> {
    let mut out = Vec::with_capacity(9);
    for (i, wi) in rule(a + 1, c) {
        for (j, wj) in rule(b + 1, c) {
            out.push((lay.grid(i, j)?, wi.mul(wj)));
        }
    }
    Some(out)
}

/// Encloses the ring of valence `n` over `c` in `[lo, hi]` (module docs);
/// `None` when an enclosure fails (e.g. the outer system is not proven
/// non-singular). With `tamper` = [`CellTamper::DropSubspaceVariation`] the
/// eigenvector is evaluated at the cell's midpoint only (a deliberately
/// unsound enclosure for the soundness tests).
pub fn shape_ring(n: usize, lo: f64, hi: f64, tamper: CellTamper) -> Option<ShapeRing> {
    if n < 3 || !(0.0 < lo && lo <= hi && hi <= 1.0) {
        return None;
    }
    let lay = PatchLayout::new(n).ok()?;
    let c = if tamper == CellTamper::DropSubspaceVariation {
        Iv::point(0.5 * lo + 0.5 * hi)
    } else {
        Iv::new(lo, hi)
    };
    let (cos1, _) = cos_sin(1, n);
    let t = Iv::point(0.75).sub(c.mul(Iv::point(0.25)).mul(Iv::point(1.0).sub(cos1)));
    let d = Iv::point(1.0).sub(c).mul(Iv::point(0.125));
    let h = t.mul(Iv::point(0.5));
    let lambda = h.add(sqrt(h.mul(h).sub(d))?);
    let den = Iv::point(4.0).mul(lambda).sub(Iv::point(1.0));
    let ring_len = lay.one_ring_len();
    let mut x: [Vec<Iv>; 2] = [
        vec![Iv::point(0.0); lay.patch_len()],
        vec![Iv::point(0.0); lay.patch_len()],
    ];
    for i in 0..n {
        let (c0, s0) = cos_sin(i, n);
        let (c1, s1) = cos_sin(i + 1, n);
        x[0][lay.e(i)] = c0;
        x[1][lay.e(i)] = s0;
        x[0][lay.f(i)] = div(c0.add(c1), den)?;
        x[1][lay.f(i)] = div(s0.add(s1), den)?;
    }
    // outer entries: (lambda I - A_oo) x_o = A_or x_r
    let mut m = vec![Iv::point(0.0); 49];
    let mut rhs = [vec![Iv::point(0.0); 7], vec![Iv::point(0.0); 7]];
    for k in 0..7 {
        m[k * 7 + k] = lambda;
        for (col, w) in regular_row(&lay, PatchLayout::outer_position(k), c)? {
            if col >= ring_len {
                let j = col - ring_len;
                m[k * 7 + j] = m[k * 7 + j].sub(w);
            } else {
                for (q, r) in rhs.iter_mut().enumerate() {
                    r[k] = r[k].add(w.mul(x[q][col]));
                }
            }
        }
    }
    let sol = solve(&m, &rhs, 7)?;
    for q in 0..2 {
        for j in 0..7 {
            x[q][ring_len + j] = sol[q][j];
        }
    }
    // ring values of the extended configuration
    let patch_len = lay.patch_len();
    let value = |idx: usize| -> Option<P2> {
        if idx < patch_len {
            return Some([lambda.mul(x[0][idx]), lambda.mul(x[1][idx])]);
        }
        let k = idx - patch_len;
        if k >= 9 {
            return None;
        }
        let mut p = [Iv::point(0.0); 2];
        for (col, w) in regular_row(&lay, PatchLayout::extra_position(k), c)? {
            for (q, pq) in p.iter_mut().enumerate() {
                *pq = pq.add(w.mul(x[q][col]));
            }
        }
        Some(p)
    };
    let mut windows = [[[[Iv::point(0.0); 2]; 4]; 4]; 3];
    for (mi, sub) in SubPatch::ALL.iter().enumerate() {
        let idx = lay.sub_patch(*sub);
        for a in 0..4 {
            for b in 0..4 {
                windows[mi][a][b] = value(idx[a][b])?;
            }
        }
    }
    Some(ShapeRing { lambda, x, windows })
}

/// Interval weights of the rule over the cell: `c/4` (vertex side weight),
/// `c/2` (derived rule) and the limit-stencil weight `alpha = c / (2 (1 + c))`.
#[derive(Clone, Copy, Debug)]
struct Weights {
    quarter: Iv,
    half: Iv,
    alpha: Iv,
}

impl Weights {
    fn new(lo: f64, hi: f64) -> Self {
        let c = Iv::new(lo, hi);
        // alpha(c) = c / (2 + 2c) is increasing in c
        let a_lo = down(lo / up(2.0 + 2.0 * lo));
        let a_hi = up(hi / down(2.0 + 2.0 * hi));
        Weights {
            quarter: c.mul(Iv::point(0.25)),
            half: c.mul(Iv::point(0.5)),
            alpha: Iv::new(a_lo.max(0.0), a_hi.min(0.25)),
        }
    }

    /// One refinement of 4 points: the 5 points at `-1/2, 0, 1/2, 1, 3/2`.
    fn refine4(&self, q: [Mr; 4]) -> [Mr; 5] {
        [
            Mr::mid2(q[0], q[1]),
            Mr::stencil3(q[0], q[1], q[2], self.quarter),
            Mr::mid2(q[1], q[2]),
            Mr::stencil3(q[1], q[2], q[3], self.quarter),
            Mr::mid2(q[2], q[3]),
        ]
    }

    /// The derived rule on 3 scaled differences: the 4 refined ones.
    fn refine_diff3(&self, q: [Mr; 3]) -> [Mr; 4] {
        [
            Mr::lerp(q[0], q[1], self.half),
            Mr::lerp(q[1], q[0], self.half),
            Mr::lerp(q[1], q[2], self.half),
            Mr::lerp(q[2], q[1], self.half),
        ]
    }

    /// Limit point of the middle of three points.
    fn limit3(&self, a: Mr, b: Mr, d: Mr) -> Mr {
        Mr::stencil3(a, b, d, self.alpha)
    }
}

/// The scaled differences of one piece of a ring cell: `du[i][j]`
/// (`i` along `s`, 3 x 4) and `dv[i][j]` (`j` along `t`, 4 x 3).
#[derive(Clone, Copy, Debug)]
struct Diffs {
    du: [[Mr; 4]; 3],
    dv: [[Mr; 3]; 4],
}

impl Diffs {
    fn of(w: &[[Mr; 4]; 4]) -> Self {
        let du = std::array::from_fn(|i| std::array::from_fn(|j| Mr::diff(w[i + 1][j], w[i][j])));
        let dv = std::array::from_fn(|i| std::array::from_fn(|j| Mr::diff(w[i][j + 1], w[i][j])));
        Diffs { du, dv }
    }

    /// The differences of sub-cell `(su, sv)` (0 or 1 per direction).
    fn child(&self, wt: &Weights, su: usize, sv: usize) -> Self {
        // du: derived rule along s, the rule along t
        let mut t1 = [[self.du[0][0]; 4]; 3];
        for j in 0..4 {
            let r = wt.refine_diff3([self.du[0][j], self.du[1][j], self.du[2][j]]);
            for i in 0..3 {
                t1[i][j] = r[i + su];
            }
        }
        let mut du = t1;
        for (d, t) in du.iter_mut().zip(&t1) {
            d.copy_from_slice(&wt.refine4(*t)[sv..sv + 4]);
        }
        // dv: derived rule along t, the rule along s
        let mut t2 = [[self.dv[0][0]; 3]; 4];
        for (t, d) in t2.iter_mut().zip(&self.dv) {
            t.copy_from_slice(&wt.refine_diff3(*d)[sv..sv + 3]);
        }
        let mut dv = t2;
        for j in 0..3 {
            let r = wt.refine4([t2[0][j], t2[1][j], t2[2][j], t2[3][j]]);
            for i in 0..4 {
                dv[i][j] = r[i + su];
            }
        }
        Diffs { du, dv }
    }

    /// `min sigma det(a, b)` over the 144 pairs, a lower bound.
    fn cone_lower(&self, sigma: f64) -> f64 {
        let a: Vec<P2> = self.du.iter().flatten().map(|m| m.to_box()).collect();
        let b: Vec<P2> = self.dv.iter().flatten().map(|m| m.to_box()).collect();
        let mut lo = f64::INFINITY;
        for p in &a {
            for q in &b {
                let d = super::ivla::p2_det(*p, *q);
                let v = if sigma > 0.0 { d.lo } else { -d.hi };
                if !(v < lo) {
                    continue;
                }
                lo = v;
            }
        }
        if lo.is_nan() {
            f64::NEG_INFINITY
        } else {
            lo
        }
    }
}

fn mr_window(w: &[[P2; 4]; 4]) -> [[Mr; 4]; 4] {
    std::array::from_fn(|a| std::array::from_fn(|b| Mr::from_box(w[a][b])))
}

/// Cone-test regularity of the three sector-0 cells for every `c` in the
/// cell: `Some(sigma)` (the sign of the Jacobian) when certified.
fn regular(ring: &ShapeRing, wt: &Weights) -> Option<f64> {
    let cells: Vec<Diffs> = ring
        .windows
        .iter()
        .map(|w| Diffs::of(&mr_window(w)))
        .collect();
    // orientation: the central pair of Omega_2's midpoints
    let c = &cells[1];
    let s = c.du[1][1].m[0] * c.dv[1][1].m[1] - c.du[1][1].m[1] * c.dv[1][1].m[0];
    let sigma = if s > 0.0 {
        1.0
    } else if s < 0.0 {
        -1.0
    } else {
        return None;
    };
    let mut work: Vec<(Diffs, u32)> = cells.into_iter().map(|d| (d, 0)).collect();
    let mut pieces = 0usize;
    while let Some((d, depth)) = work.pop() {
        pieces += 1;
        if d.cone_lower(sigma) > 0.0 {
            continue;
        }
        if depth >= CONE_DEPTH || pieces + work.len() + 4 > CONE_PIECES {
            return None;
        }
        for (su, sv) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            work.push((d.child(wt, su, sv), depth + 1));
        }
    }
    Some(sigma)
}

/// A boundary curve of a ring cell in midpoint-radius form: the limit curve
/// of the rule on the 4-point polygon `q` (middle span).
#[derive(Clone, Copy, Debug)]
struct ShapeCurve {
    wt: Weights,
    q: [Mr; 4],
}

impl BoxCurve for ShapeCurve {
    fn hull(&self) -> Vec<P2> {
        let s = self.wt.limit3(self.q[0], self.q[1], self.q[2]);
        let e = self.wt.limit3(self.q[1], self.q[2], self.q[3]);
        vec![
            s.to_box(),
            self.q[0].to_box(),
            self.q[1].to_box(),
            self.q[2].to_box(),
            self.q[3].to_box(),
            e.to_box(),
        ]
    }
    fn halves(&self) -> (Self, Self) {
        let r = self.wt.refine4(self.q);
        (
            ShapeCurve {
                wt: self.wt,
                q: [r[0], r[1], r[2], r[3]],
            },
            ShapeCurve {
                wt: self.wt,
                q: [r[1], r[2], r[3], r[4]],
            },
        )
    }
}

/// The winding number of the outer boundary for every `c` in the cell
/// (sector 0's four curves as in the pointwise check, rotated by `j theta`
/// for sector `j`; mirrored when `sigma < 0`).
fn outer_winding(ring: &ShapeRing, wt: &Weights, n: usize, sigma: f64) -> Option<i64> {
    let w: Vec<[[Mr; 4]; 4]> = ring.windows.iter().map(mr_window).collect();
    let column = |w: &[[Mr; 4]; 4], a: usize| -> [Mr; 4] {
        std::array::from_fn(|b| wt.limit3(w[a - 1][b], w[a][b], w[a + 1][b]))
    };
    let row = |w: &[[Mr; 4]; 4], b: usize| -> [Mr; 4] {
        std::array::from_fn(|a| wt.limit3(w[a][b - 1], w[a][b], w[a][b + 1]))
    };
    let rev = |q: [Mr; 4]| [q[3], q[2], q[1], q[0]];
    let sector0 = [
        column(&w[0], 2),
        column(&w[1], 2),
        rev(row(&w[1], 2)),
        rev(row(&w[2], 2)),
    ];
    let mut curves = Vec::with_capacity(4 * n);
    for j in 0..n {
        let (cj, sj) = cos_sin(j, n);
        for q in &sector0 {
            let mut q = q.map(|p| if j == 0 { p } else { p.rotate(cj, sj) });
            if sigma < 0.0 {
                for p in q.iter_mut() {
                    p.m[1] = -p.m[1];
                }
            }
            curves.push(ShapeCurve { wt: *wt, q });
        }
    }
    winding_number(&curves)
}

/// Whether the characteristic map of valence `n` is certified regular and
/// injective for every `c` in `[lo, hi]`, given that `standard` is certified
/// there (module docs).
pub fn certified(n: usize, lo: f64, hi: f64, tamper: CellTamper) -> bool {
    let Some(ring) = shape_ring(n, lo, hi, tamper) else {
        return false;
    };
    let wt = Weights::new(lo, hi);
    let Some(sigma) = regular(&ring, &wt) else {
        return false;
    };
    outer_winding(&ring, &wt, n, sigma) == Some(1)
}

/// The sector-0 windows at one `c`, in floating point, in the normalisation
/// of [`shape_ring`] (for the soundness tests: they must lie in the
/// enclosure of every cell containing `c`): the patch eigenvector of
/// [`crate::schemes::catmull_clark::fourier::mode_patch_eigenvectors`]
/// (mode 1) under the extended matrix.
pub fn pointwise_windows(n: usize, c: f64) -> crate::error::Result<[[[[f64; 2]; 4]; 4]; 3]> {
    use crate::schemes::catmull_clark::{extended_matrix, fourier};
    let (_, [xc, xs]) = fourier::mode_patch_eigenvectors(n, c, 1)?;
    let ext = extended_matrix::<f64>(n, &c)?.into_matrix();
    let lay = PatchLayout::new(n)?;
    let pt = |i: usize| -> [f64; 2] {
        let row = ext.row(i);
        [
            row.iter().zip(xc.iter()).map(|(a, b)| a * b).sum(),
            row.iter().zip(xs.iter()).map(|(a, b)| a * b).sum(),
        ]
    };
    Ok(std::array::from_fn(|m| {
        let idx = lay.sub_patch(SubPatch::ALL[m]);
        std::array::from_fn(|a| std::array::from_fn(|b| pt(idx[a][b])))
    }))
}

impl ShapeRing {
    /// How many window coordinates of `w` lie outside the enclosure by more
    /// than `tol (1 + |x|)` (the pointwise computation's own rounding).
    pub fn misses(&self, w: &[[[[f64; 2]; 4]; 4]; 3], tol: f64) -> usize {
        let mut bad = 0;
        for m in 0..3 {
            for a in 0..4 {
                for b in 0..4 {
                    for k in 0..2 {
                        let (x, iv) = (w[m][a][b][k], self.windows[m][a][b][k]);
                        let t = tol * (1.0 + x.abs());
                        if !(iv.lo - t <= x && x <= iv.hi + t) {
                            bad += 1;
                        }
                    }
                }
            }
        }
        bad
    }
}
