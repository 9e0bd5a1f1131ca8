//! The Jacobian's sign over the annulus and the winding number, from the
//! refined net with convex-hull enclosures (math doc section 20.5).

use super::layout::{Lattice, LatticePoint};
use super::mask::{NormBound, NormBounds, RegularRules};
use super::matrix_mask::MatrixBound;
use super::net::{regular_value, Ball, Net};
use crate::charmap::regularity::gamma;
use std::f64::consts::PI;

/// Largest accepted distance (in turns) of the accumulated angle of the
/// control polygon from an integer (the sum of principal angles is an exact
/// multiple of `2 pi` in exact arithmetic; the rounding of a few thousand
/// `atan2` is below `1e-12` turns).
pub const INTEGRALITY_TOL: f64 = 1e-6;

/// A cell of the annulus: sector `s`, lattice cell `(i, j)` of the level
/// (`kind` 0: the square `[i, i+1] x [j, j+1]`, or the triangle
/// `(i, j), (i+1, j), (i, j+1)`; 1: the triangle `(i+1, j), (i, j+1), (i+1, j+1)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Cell {
    /// Subdivision level.
    pub level: u32,
    /// Sector.
    pub sector: usize,
    /// Cell kind (0 or 1; quads only 0).
    pub kind: u8,
    /// Lattice coordinates of the cell's lower corner.
    pub i: i64,
    /// See `i`.
    pub j: i64,
}

impl std::fmt::Display for Cell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "level {} sector {} cell {}({}, {})",
            self.level,
            self.sector,
            ["a", "b"][self.kind as usize],
            self.i,
            self.j
        )
    }
}

/// `d^level`, the number of lattice steps of a level-0 edge at `level`.
pub fn steps(dilation: i64, level: u32) -> i64 {
    dilation.pow(level)
}

/// The annulus cells of sector `s` at `level` for rules of dilation `d`
/// (the sector's part of the one-ring region minus its `1/d`-size copy, in
/// level units `L = d^level`).
pub fn annulus(lattice: Lattice, dilation: i64, s: usize, level: u32) -> Vec<Cell> {
    let l = steps(dilation, level);
    let h = l / dilation;
    let mut out = Vec::new();
    for i in 0..l {
        for j in 0..l {
            let cell = |kind| Cell {
                level,
                sector: s,
                kind,
                i,
                j,
            };
            match lattice {
                Lattice::Quad => {
                    if i.max(j) >= h {
                        out.push(cell(0));
                    }
                }
                Lattice::Triangle => {
                    if i + j < l && i + j >= h {
                        out.push(cell(0));
                    }
                    if i + j + 2 <= l && i + j + 1 >= h {
                        out.push(cell(1));
                    }
                }
            }
        }
    }
    out
}

/// The `d^2` cells of the next level inside `c` (rules of dilation `d`).
/// A square splits into the squares at offsets `(a, b) in {0..d-1}^2`; the
/// triangle of kind 0, `(i, j) + T`, `T` the unit triangle, into the
/// triangles of kind 0 at offsets `a + b <= d - 1` and of kind 1 at
/// `a + b <= d - 2`; the triangle of kind 1, `(i + 1, j + 1) - T`, into
/// their reflections through the centre of `d c`'s square (kind 0 at offset
/// `(a, b)` becomes kind 1 at `(d - 1 - a, d - 1 - b)` and vice versa).
pub fn children(lattice: Lattice, dilation: i64, c: &Cell) -> Vec<Cell> {
    let d = dilation;
    let mk = |kind, a: i64, b: i64| Cell {
        level: c.level + 1,
        sector: c.sector,
        kind,
        i: d * c.i + a,
        j: d * c.j + b,
    };
    // offsets (a, b) with a + b <= top, b outer, a inner
    let under = |top: i64| -> Vec<(i64, i64)> {
        (0..d)
            .flat_map(|b| (0..d).map(move |a| (a, b)))
            .filter(|(a, b)| a + b <= top)
            .collect()
    };
    match (lattice, c.kind) {
        (Lattice::Quad, _) => under(2 * d).into_iter().map(|(a, b)| mk(0, a, b)).collect(),
        (Lattice::Triangle, 0) => under(d - 1)
            .into_iter()
            .map(|(a, b)| mk(0, a, b))
            .chain(under(d - 2).into_iter().map(|(a, b)| mk(1, a, b)))
            .collect(),
        (Lattice::Triangle, _) => under(d - 1)
            .into_iter()
            .rev()
            .map(|(a, b)| mk(1, d - 1 - a, d - 1 - b))
            .chain(
                under(d - 2)
                    .into_iter()
                    .rev()
                    .map(|(a, b)| mk(0, d - 1 - a, d - 1 - b)),
            )
            .collect(),
    }
}

/// The certified sign of the Jacobian on a cell, or `None`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellSign {
    /// `1`, `-1` or `0` (undecided, or a stencil point missing).
    pub sign: i8,
    /// Lower and upper bounds of the Jacobian over the cell (scaled by the
    /// largest difference squared; `NaN` when not evaluated).
    pub bounds: [f64; 2],
}

/// The divided differences `p_alpha - p_{alpha - e_k}` over the window of
/// `alpha` whose refinable function `psi_k` can be non-zero on the cell
/// (the cell's bounding box minus the derivative scheme's support box).
fn differences(values: &Values, rules: &RegularRules, c: &Cell, k: usize) -> Option<Vec<Ball>> {
    let b = rules.derivative_box[k];
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let mut out = Vec::new();
    for ax in c.i - b[1]..=c.i + 1 - b[0] {
        for ay in c.j - b[3]..=c.j + 1 - b[2] {
            out.push(difference(values, [ax, ay], e)?);
        }
    }
    Some(out)
}

/// `p_x - p_{x - e}` as a ball.
fn difference(values: &Values, x: LatticePoint, e: LatticePoint) -> Option<Ball> {
    Some(ball_difference(
        values(x)?,
        values([x[0] - e[0], x[1] - e[1]])?,
    ))
}

/// `p - q` as a ball (one rounding per coordinate).
fn ball_difference(p: Ball, q: Ball) -> Ball {
    let mid = [p.mid[0] - q.mid[0], p.mid[1] - q.mid[1]];
    let size = mid[0].abs().max(mid[1].abs());
    Ball {
        mid,
        rad: (p.rad + q.rad + gamma(1) * size) * (1.0 + gamma(3)),
    }
}

/// The largest `|v_y - v_{y - w}|` (coordinate-wise, radii included,
/// rounded up) over `y` in the box `[x0, x1] x [y0, y1]` and both directions
/// `w`, where `v_y` is `value(y)`; `None` when a value is missing.
fn largest_difference<F>(bx: [i64; 4], dirs: [LatticePoint; 2], value: F) -> Option<f64>
where
    F: Fn(LatticePoint) -> Option<Ball>,
{
    let mut m = 0.0f64;
    for x in bx[0]..=bx[1] {
        for y in bx[2]..=bx[3] {
            let v = value([x, y])?;
            for e in dirs {
                let w = value([x - e[0], y - e[1]])?;
                for k in 0..2 {
                    let d = (v.mid[k] - w.mid[k]).abs();
                    m = m.max((d + v.rad + w.rad) * (1.0 + gamma(2)));
                }
            }
        }
    }
    Some(m)
}

/// The norm-based enclosure of the limit `g` over the box `bx` (a cell's
/// bounding box; the corners are lattice points) from the values `value`
/// of the scheme of `nb`: four balls whose convex hull contains `g` over the
/// box. Both enclosures of math doc section 20.3 are formed (the
/// first-order one only when the scheme reproduces affine data) and the one
/// with the smaller largest radius is returned; each is sound on its own.
fn norm_balls<F>(nb: &NormBound, bx: [i64; 4], value: F) -> Option<Vec<Ball>>
where
    F: Fn(LatticePoint) -> Option<Ball>,
{
    let w = nb.window;
    let window = [
        bx[0] + w[0][0],
        bx[1] + w[0][1],
        bx[2] + w[1][0],
        bx[3] + w[1][1],
    ];
    let zero = zero_order_balls(nb, bx, window, &value)?;
    let Some(sigma) = nb.shift else {
        return Some(zero);
    };
    let first = first_order_balls(nb, bx, window, sigma, &value)?;
    let widest = |b: &[Ball]| b.iter().fold(0.0f64, |a, x| a.max(x.rad));
    Some(if widest(&first) < widest(&zero) {
        first
    } else {
        zero
    })
}

/// The four corners of the lattice box `bx = [x0, x1, y0, y1]`, in the
/// order `(x0, y0), (x0, y1), (x1, y0), (x1, y1)` every enclosure lists its
/// balls in.
fn corners(bx: [i64; 4]) -> [LatticePoint; 4] {
    [
        [bx[0], bx[2]],
        [bx[0], bx[3]],
        [bx[1], bx[2]],
        [bx[1], bx[3]],
    ]
}

/// The zero-order enclosure: the balls of radius `rad + factor * M` around
/// the values at the corners of `bx`, `M` the largest difference over the
/// window (`|g(x) - q_{floor(x)}| <= K T M`, [`NormBound`]).
fn zero_order_balls<F>(
    nb: &NormBound,
    bx: [i64; 4],
    window: [i64; 4],
    value: &F,
) -> Option<Vec<Ball>>
where
    F: Fn(LatticePoint) -> Option<Ball>,
{
    let m = largest_difference(window, nb.directions, value)?;
    let mut out = Vec::with_capacity(4);
    for p in corners(bx) {
        let q = value(p)?;
        out.push(Ball {
            mid: q.mid,
            rad: (q.rad + nb.factor * m) * (1.0 + gamma(2)),
        });
    }
    Some(out)
}

/// `(a, b)` with `d = a u + b v` for the lattice directions `dirs`
/// (`det(u, v) = +-1`; exact for dyadic `d`).
fn in_directions(d: [f64; 2], dirs: [LatticePoint; 2]) -> [f64; 2] {
    let [u, v] = dirs.map(|x| x.map(|c| c as f64));
    let det = u[0] * v[1] - u[1] * v[0];
    [
        (d[0] * v[1] - d[1] * v[0]) * det,
        (u[0] * d[1] - u[1] * d[0]) * det,
    ]
}

/// The first-order enclosure **\[derived\]** (math doc section 20.3). With
/// `alpha` the lower corner of `bx`, `G_w` the midrange of the differences
/// `D_w q_y` over the window (per coordinate) and the affine
/// `l(alpha + a u + b v) = q_alpha + a G_u + b G_v`, the data `r = q - l`
/// has the limit `g(x) - l(x - sigma)` (the scheme reproduces affine data
/// with shift `sigma`), its differences are `D_w q_y - G_w`, so
///
/// ```text
/// |g(x) - l(x - sigma)| <= |r_{floor(x)}| + K T max_{y, w} |D_w q_y - G_w|,
/// ```
///
/// and `l(x - sigma)` over the box lies in the hull of `l(c - sigma)` over
/// its corners `c`: the balls around those four points with that radius
/// (plus the rounding of `l`) enclose `g` over the box.
fn first_order_balls<F>(
    nb: &NormBound,
    bx: [i64; 4],
    window: [i64; 4],
    sigma: [f64; 2],
    value: &F,
) -> Option<Vec<Ball>>
where
    F: Fn(LatticePoint) -> Option<Ball>,
{
    let alpha = [bx[0], bx[2]];
    let q0 = value(alpha)?;
    // the differences over the window, per direction
    let mut diffs: [Vec<Ball>; 2] = Default::default();
    let mut grad = [[0.0f64; 2]; 2];
    for (k, e) in nb.directions.iter().enumerate() {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for x in window[0]..=window[1] {
            for y in window[2]..=window[3] {
                let d = ball_difference(value([x, y])?, value([x - e[0], y - e[1]])?);
                for c in 0..2 {
                    lo[c] = lo[c].min(d.mid[c]);
                    hi[c] = hi[c].max(d.mid[c]);
                }
                diffs[k].push(d);
            }
        }
        // any values serve as G_w; the midrange makes the deviations small
        grad[k] = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    }
    // M(r): the largest |D_w q_y - G_w|, radii included, rounded up
    let mut m = 0.0f64;
    for (d, g) in diffs.iter().zip(&grad) {
        for b in d {
            for (x, gx) in b.mid.iter().zip(g) {
                m = m.max(((x - gx).abs() + b.rad) * (1.0 + gamma(2)));
            }
        }
    }
    // l at a point alpha + a u + b v, with the rounding bound of its computation
    let affine = |ab: [f64; 2]| -> ([f64; 2], f64) {
        let mut mid = [0.0f64; 2];
        let mut err = 0.0f64;
        for c in 0..2 {
            let (x, y) = (ab[0] * grad[0][c], ab[1] * grad[1][c]);
            mid[c] = q0.mid[c] + x + y;
            err = err.max(gamma(3) * (q0.mid[c].abs() + x.abs() + y.abs()));
        }
        (mid, err)
    };
    // rho: the largest |r_c| over the corners (r_alpha is within q0's radius)
    let mut rho = 0.0f64;
    for [x, y] in corners(bx) {
        let q = value([x, y])?;
        let ab = in_directions(
            [(x - alpha[0]) as f64, (y - alpha[1]) as f64],
            nb.directions,
        );
        let (l, err) = affine(ab);
        for (x, lx) in q.mid.iter().zip(&l) {
            rho = rho.max(((x - lx).abs() + q.rad + err) * (1.0 + gamma(2)));
        }
    }
    let reach = (rho + nb.factor * m) * (1.0 + gamma(2));
    let mut out = Vec::with_capacity(4);
    for [x, y] in corners(bx) {
        let d = [
            x as f64 - sigma[0] - alpha[0] as f64,
            y as f64 - sigma[1] - alpha[1] as f64,
        ];
        let (mid, err) = affine(in_directions(d, nb.directions));
        out.push(Ball {
            mid,
            rad: (reach + err) * (1.0 + gamma(2)),
        });
    }
    Some(out)
}

/// The norm-based enclosure of the derivative `d_{e_k} f` over a cell
/// **\[derived\]**: [`norm_balls`] of the differences
/// `q_y = p_y - p_{y - e_k}`.
fn derivative_balls(values: &Values, nb: &NormBounds, c: &Cell, k: usize) -> Option<Vec<Ball>> {
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let bx = [c.i, c.i + 1, c.j, c.j + 1];
    norm_balls(&nb.derivative[k], bx, |y| difference(values, y, e))
}

/// The Jacobian's sign on a cell **\[derived\]**: `d_1 f` and `d_2 f` lie in
/// the convex hulls of the two windows of differences (non-negative
/// refinable functions with partition of unity), and `det(a, b)` is bilinear,
/// so its extremes over the product of hulls are at pairs of window points;
/// each pair's determinant is enclosed in midpoint-radius arithmetic
/// (`|det(a, b) - det(a~, b~)| <= r_a (|b~_x| + |b~_y|) + r_b (|a~_x| + |a~_y|) + 2 r_a r_b`
/// plus `gamma_3 (|a~_x b~_y| + |a~_y b~_x|)` of rounding).
pub fn cell_sign(net: &Net, rules: &RegularRules, c: &Cell) -> CellSign {
    cell_sign_of(&|p| net.at(c.sector, p), rules, c)
}

/// Balls whose convex hull contains the derivative `d_{e_k} f` (in the
/// level's units) over the cell: the window of differences (non-negative
/// masks) or the norm-based enclosure (math doc section 20.3); `None` when a
/// value is missing.
pub fn derivative_enclosure(
    values: &Values,
    rules: &RegularRules,
    c: &Cell,
    k: usize,
) -> Option<Vec<Ball>> {
    if let Some(mb) = &rules.matrix {
        return matrix_balls(values, mb, c, k);
    }
    match rules.norm {
        None => differences(values, rules, c, k),
        Some(nb) => derivative_balls(values, &nb, c, k),
    }
}

/// The second difference `v_s` at `y` (`s = 0, 1, 2`: `(1 - z_1)^2`,
/// `(1 - z_1)(1 - z_2)`, `(1 - z_2)^2` applied to the values) as a rounded
/// combination of balls ([`super::net::combine`]).
pub fn second_difference(values: &Values, y: LatticePoint, s: usize) -> Option<Ball> {
    let at = |dx: i64, dy: i64| values([y[0] - dx, y[1] - dy]);
    let terms = match s {
        0 => vec![(1.0, at(0, 0)?), (-2.0, at(1, 0)?), (1.0, at(2, 0)?)],
        1 => vec![
            (1.0, at(0, 0)?),
            (-1.0, at(1, 0)?),
            (-1.0, at(0, 1)?),
            (1.0, at(1, 1)?),
        ],
        _ => vec![(1.0, at(0, 0)?), (-2.0, at(0, 1)?), (1.0, at(0, 2)?)],
    };
    Some(super::net::combine(&terms))
}

/// The enclosure of the derivative `d_{e_k} f` over a cell through the
/// matrix difference schemes **\[derived\]** (math doc section 20.9,
/// [`MatrixBound`]). Zero order: the balls of radius `rad + K_k T M_2` around
/// the first differences `p_c - p_{c - e_k}` at the four corners `c` of the
/// cell's bounding square (`floor(x)` is one of them), `M_2` the largest
/// second difference over the window. Second order, when the mask
/// reproduces quadratics ([`MatrixBound::quadratic`]): the same bound for
/// the residual `p - Q` of a quadratic `Q` whose second differences are the
/// midranges `G` of the window's (`quadratic_balls`). The narrower of the
/// two is returned; each is sound on its own.
pub fn matrix_balls(values: &Values, mb: &MatrixBound, c: &Cell, k: usize) -> Option<Vec<Ball>> {
    let stats = second_differences(values, mb, c)?;
    matrix_balls_with(values, mb, c, k, &stats)
}

/// The second differences over a cell's window: `M_2 = max |v|` and, per
/// component and coordinate, the midrange `G` and `max |v - G|` (radii
/// included, rounded up).
struct WindowStats {
    m2: f64,
    mid: [[f64; 2]; 3],
    spread: f64,
}

/// [`WindowStats`] of the cell's window; `None` when a value is missing.
fn second_differences(values: &Values, mb: &MatrixBound, c: &Cell) -> Option<WindowStats> {
    let bx = [c.i, c.i + 1, c.j, c.j + 1];
    let w = mb.window;
    let mut all = Vec::new();
    let (mut lo, mut hi) = ([[f64::INFINITY; 2]; 3], [[f64::NEG_INFINITY; 2]; 3]);
    let mut m2 = 0.0f64;
    for x in bx[0] + w[0][0]..=bx[1] + w[0][1] {
        for y in bx[2] + w[1][0]..=bx[3] + w[1][1] {
            for s in 0..3 {
                let v = second_difference(values, [x, y], s)?;
                for (z, (l, h)) in v.mid.iter().zip(lo[s].iter_mut().zip(hi[s].iter_mut())) {
                    m2 = m2.max((z.abs() + v.rad) * (1.0 + gamma(2)));
                    *l = l.min(*z);
                    *h = h.max(*z);
                }
                all.push((s, v));
            }
        }
    }
    // any values serve as G; the midrange makes the deviations small
    let mut mid = [[0.0f64; 2]; 3];
    for s in 0..3 {
        for k in 0..2 {
            mid[s][k] = 0.5 * (lo[s][k] + hi[s][k]);
        }
    }
    let mut spread = 0.0f64;
    for (s, v) in all {
        for (z, g) in v.mid.iter().zip(&mid[s]) {
            spread = spread.max(((z - g).abs() + v.rad) * (1.0 + gamma(2)));
        }
    }
    Some(WindowStats { m2, mid, spread })
}

/// [`matrix_balls`] with the window's statistics given.
fn matrix_balls_with(
    values: &Values,
    mb: &MatrixBound,
    c: &Cell,
    k: usize,
    stats: &WindowStats,
) -> Option<Vec<Ball>> {
    let bx = [c.i, c.i + 1, c.j, c.j + 1];
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let mut zero = Vec::with_capacity(4);
    for p in corners(bx) {
        let q = difference(values, p, e)?;
        zero.push(Ball {
            mid: q.mid,
            rad: (q.rad + mb.factor[k] * stats.m2) * (1.0 + gamma(2)),
        });
    }
    if !mb.quadratic {
        return Some(zero);
    }
    let second = quadratic_balls(values, mb, c, k, stats)?;
    let widest = |b: &[Ball]| b.iter().fold(0.0f64, |a, x| a.max(x.rad));
    Some(if widest(&second) < widest(&zero) {
        second
    } else {
        zero
    })
}

/// The second-order enclosure **\[derived\]** (math doc section 20.9). With
/// `alpha` the lower corner of the cell, `G` the midranges of the second
/// differences over the window and the quadratic `Q` with Hessian
/// `[[G_11, G_12], [G_12, G_22]]` and `d_k Q(alpha - e_k / 2) = q_{alpha, k}`
/// (`d_k Q` is affine), the data `r = p - Q` has second differences `v - G`
/// and, the mask reproducing quadratics up to a constant, the limit
/// derivative `g - grad Q`; the bound of [`MatrixBound`] for `r` gives
///
/// ```text
/// |g_k(x) - d_k Q(x)| <= |q_{floor(x), k} - d_k Q(floor(x) - e_k / 2)| + K_k T max |v - G|
/// ```
///
/// (`Q(y) - Q(y - e_k) = d_k Q(y - e_k / 2)` exactly for a quadratic), and
/// `d_k Q` over the cell lies in the hull of its values at the four corners:
/// the balls of that radius (plus the rounding of `d_k Q`) around them
/// enclose `g_k` over the cell.
fn quadratic_balls(
    values: &Values,
    mb: &MatrixBound,
    c: &Cell,
    k: usize,
    stats: &WindowStats,
) -> Option<Vec<Ball>> {
    let bx = [c.i, c.i + 1, c.j, c.j + 1];
    let alpha = [c.i, c.j];
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let g = &stats.mid;
    // the gradient of d_k Q per coordinate: (G_{k1}, G_{k2})
    let slope = if k == 0 { [g[0], g[1]] } else { [g[1], g[2]] };
    let q0 = difference(values, alpha, e)?;
    let diag = g[2 * k];
    let base = [q0.mid[0] + 0.5 * diag[0], q0.mid[1] + 0.5 * diag[1]];
    // d_k Q at alpha + (dx, dy), with the rounding bound of its computation
    let dq = |dx: f64, dy: f64| -> ([f64; 2], f64) {
        let mut mid = [0.0f64; 2];
        let mut err = 0.0f64;
        for z in 0..2 {
            let (a, b) = (slope[0][z] * dx, slope[1][z] * dy);
            mid[z] = base[z] + a + b;
            err = err.max(gamma(3) * (base[z].abs() + a.abs() + b.abs()));
        }
        (mid, err)
    };
    // rho: the largest |q_c - d_k Q(c - e_k / 2)| over the corners
    let mut rho = 0.0f64;
    for p in corners(bx) {
        let q = difference(values, p, e)?;
        let (dx, dy) = ((p[0] - alpha[0]) as f64, (p[1] - alpha[1]) as f64);
        let (m, err) = dq(dx - 0.5 * e[0] as f64, dy - 0.5 * e[1] as f64);
        for (x, y) in q.mid.iter().zip(&m) {
            rho = rho.max(((x - y).abs() + q.rad + err) * (1.0 + gamma(2)));
        }
    }
    let reach = (rho + mb.factor[k] * stats.spread) * (1.0 + gamma(2));
    let mut out = Vec::with_capacity(4);
    for p in corners(bx) {
        let (mid, err) = dq((p[0] - alpha[0]) as f64, (p[1] - alpha[1]) as f64);
        out.push(Ball {
            mid,
            rad: (reach + err) * (1.0 + gamma(2)),
        });
    }
    Some(out)
}

/// The values of one level in a sector's chart (`None` where not held).
pub type Values<'a> = dyn Fn(LatticePoint) -> Option<Ball> + 'a;

/// [`cell_sign`] with the level's values in the cell's sector chart given
/// by `values` (a net, or a [`Patch`]).
pub fn cell_sign_of(values: &Values, rules: &RegularRules, c: &Cell) -> CellSign {
    let undecided = CellSign {
        sign: 0,
        bounds: [f64::NAN; 2],
    };
    let windows = match &rules.matrix {
        // one M_2 serves both derivatives
        Some(mb) => match second_differences(values, mb, c) {
            Some(stats) => (
                matrix_balls_with(values, mb, c, 0, &stats),
                matrix_balls_with(values, mb, c, 1, &stats),
            ),
            None => (None, None),
        },
        None => (
            derivative_enclosure(values, rules, c, 0),
            derivative_enclosure(values, rules, c, 1),
        ),
    };
    let (Some(da), Some(db)) = windows else {
        return undecided;
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut scale = 0.0f64;
    for a in &da {
        for b in &db {
            let det = a.mid[0] * b.mid[1] - a.mid[1] * b.mid[0];
            let prod = (a.mid[0] * b.mid[1]).abs() + (a.mid[1] * b.mid[0]).abs();
            let err = (a.rad * (b.mid[0].abs() + b.mid[1].abs())
                + b.rad * (a.mid[0].abs() + a.mid[1].abs())
                + 2.0 * a.rad * b.rad
                + gamma(3) * prod)
                * (1.0 + gamma(6));
            lo = lo.min(det - err);
            hi = hi.max(det + err);
            scale = scale.max(prod);
        }
    }
    let sign = if lo > 0.0 {
        1
    } else if hi < 0.0 {
        -1
    } else {
        0
    };
    let s = if scale > 0.0 { scale } else { 1.0 };
    CellSign {
        sign,
        bounds: [lo / s, hi / s],
    }
}

/// The closed path at ring index `floor(3 L / 4)` (`L = d^level`) through
/// all sectors (lattice points of each sector's chart, sector by sector
/// counter-clockwise; the last point of a sector is the first of the next).
fn ring_path(lattice: Lattice, dilation: i64, level: u32) -> Vec<LatticePoint> {
    let r = 3 * steps(dilation, level) / 4;
    match lattice {
        Lattice::Triangle => (0..r).map(|t| [r - t, t]).collect(),
        Lattice::Quad => (0..r)
            .map(|t| [r, t])
            .chain((0..r).map(|t| [r - t, r]))
            .collect(),
    }
}

/// The winding number of the characteristic map's image of the ring path
/// around the origin, or `None` when a piece's enclosure is not certified
/// to avoid the origin **\[derived\]**: the limit curve over the lattice edge
/// from `x` to `y` lies in the convex hull of the mask-window's control points
/// (non-negative refinable function of the mask, supported in
/// `hull(supp a) / (d - 1)` for dilation `d`); with `p_x` and `p_y` that
/// set lies in an open half-plane through the origin (checked with the
/// direction `u = p_x + p_y`, every ball at positive distance), so the angle
/// swept from `f(x)` to `f(y)` equals the principal angle, and summing the
/// principal angles of the control polygon telescopes to the same total.
pub fn winding(net: &Net, rules: &RegularRules, level: u32) -> Option<i64> {
    let path = ring_path(rules.lattice, rules.dilation, level);
    // supp phi lies in hull(supp a) / (d - 1) (phi = sum_g a_g phi(d . - g)),
    // rounded outwards to lattice points
    let d1 = rules.dilation - 1;
    let mb = rules.mask_box;
    let b = [
        mb[0].div_euclid(d1),
        mb[1].div_euclid(d1) + i64::from(mb[1].rem_euclid(d1) != 0),
        mb[2].div_euclid(d1),
        mb[3].div_euclid(d1) + i64::from(mb[3].rem_euclid(d1) != 0),
    ];
    let mut total = 0.0f64;
    for s in 0..net.n {
        for (k, x) in path.iter().enumerate() {
            let y = match path.get(k + 1) {
                Some(y) => *y,
                None => {
                    // the first point of the next sector, in this sector's chart
                    let next = path[0];
                    let d1 = rules.lattice.direction(1);
                    let d2 = rules.lattice.direction(2);
                    [
                        next[0] * d1[0] + next[1] * d2[0],
                        next[0] * d1[1] + next[1] * d2[1],
                    ]
                }
            };
            let px = net.at(s, *x)?;
            let py = net.at(s, y)?;
            let u = [px.mid[0] + py.mid[0], px.mid[1] + py.mid[1]];
            let (xl, xh) = (x[0].min(y[0]), x[0].max(y[0]));
            let (yl, yh) = (x[1].min(y[1]), x[1].max(y[1]));
            let mut window = vec![px, py];
            match rules.norm {
                None => {
                    for ax in xl - b[1]..=xh - b[0] {
                        for ay in yl - b[3]..=yh - b[2] {
                            window.push(net.at(s, [ax, ay])?);
                        }
                    }
                }
                Some(nb) => {
                    // the limit over the edge lies within (2 + K_a T_a) M of p_x
                    // (the edge's bounding square is the cell of the bound)
                    let bx = [xl, xh, yl, yh];
                    window.extend(norm_balls(&nb.mask, bx, |z| net.at(s, z))?);
                }
            }
            for q in &window {
                let dot = u[0] * q.mid[0] + u[1] * q.mid[1];
                let slack = q.rad * (u[0].abs() + u[1].abs())
                    + gamma(3) * (u[0] * q.mid[0]).abs().max((u[1] * q.mid[1]).abs()) * 2.0;
                if dot - slack * (1.0 + gamma(4)) <= 0.0 {
                    return None;
                }
            }
            let cross = px.mid[0] * py.mid[1] - px.mid[1] * py.mid[0];
            let dot = px.mid[0] * py.mid[0] + px.mid[1] * py.mid[1];
            total += cross.atan2(dot);
        }
    }
    let turns = total / (2.0 * PI);
    let w = turns.round();
    ((turns - w).abs() <= INTEGRALITY_TOL).then_some(w as i64)
}

/// The values of one level on a box of a sector's chart, refined locally
/// from the previous level by the regular mask **\[derived\]**: away from
/// the centre every point of the net follows the regular rule in any chart
/// that holds its stencil, so a patch holds the net's values (as balls
/// enclosing the exact ones) without refining the whole net. Points whose
/// ring index is at most `min_ring`, or whose stencil is not held, are left
/// out (cells that need them stay undecided).
#[derive(Clone, Debug)]
pub struct Patch {
    /// Lower corner of the box.
    lo: LatticePoint,
    /// Extent of the box along both axes.
    size: [usize; 2],
    values: Vec<Option<Ball>>,
}

impl Patch {
    /// The value at a lattice point of the chart.
    pub fn at(&self, p: LatticePoint) -> Option<Ball> {
        let (x, y) = (p[0] - self.lo[0], p[1] - self.lo[1]);
        if x < 0 || y < 0 || x >= self.size[0] as i64 || y >= self.size[1] as i64 {
            return None;
        }
        self.values[x as usize * self.size[1] + y as usize]
    }

    /// The next level's values on the box `[x0, x1] x [y0, y1]` from this
    /// level's `values`: `p'_beta = sum_gamma a_gamma p_{(beta - gamma) / 2}`
    /// (math doc section 20.4), only at ring index above `min_ring`.
    pub fn refine(values: &Values, rules: &RegularRules, bx: [i64; 4], min_ring: i64) -> Patch {
        let size = [(bx[1] - bx[0] + 1) as usize, (bx[3] - bx[2] + 1) as usize];
        let mut out = Vec::with_capacity(size[0] * size[1]);
        for x in bx[0]..=bx[1] {
            for y in bx[2]..=bx[3] {
                let beta = [x, y];
                out.push(if rules.lattice.ring(beta) <= min_ring {
                    None
                } else {
                    regular_value(rules, beta, values)
                });
            }
        }
        Patch {
            lo: [bx[0], bx[2]],
            size,
            values: out,
        }
    }
}
