//! The Jacobian's sign over the annulus and the winding number, from the
//! refined net with convex-hull enclosures (math doc section 20.5).

use super::layout::{Lattice, LatticePoint};
use super::mask::{NormBound, NormBounds, RegularRules};
use super::net::{Ball, Net};
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

/// The annulus cells of sector `s` at `level` (the sector's part of the
/// one-ring region minus its half-size copy, in level units `L = 2^level`).
pub fn annulus(lattice: Lattice, s: usize, level: u32) -> Vec<Cell> {
    let l = 1i64 << level;
    let h = l / 2;
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

/// The cells of the next level inside `c`.
pub fn children(lattice: Lattice, c: &Cell) -> Vec<Cell> {
    let mk = |kind, i, j| Cell {
        level: c.level + 1,
        sector: c.sector,
        kind,
        i,
        j,
    };
    let (i, j) = (2 * c.i, 2 * c.j);
    match (lattice, c.kind) {
        (Lattice::Quad, _) => vec![
            mk(0, i, j),
            mk(0, i + 1, j),
            mk(0, i, j + 1),
            mk(0, i + 1, j + 1),
        ],
        (Lattice::Triangle, 0) => vec![mk(0, i, j), mk(0, i + 1, j), mk(0, i, j + 1), mk(1, i, j)],
        (Lattice::Triangle, _) => vec![
            mk(1, i + 1, j),
            mk(1, i, j + 1),
            mk(1, i + 1, j + 1),
            mk(0, i + 1, j + 1),
        ],
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
fn differences(net: &Net, rules: &RegularRules, c: &Cell, k: usize) -> Option<Vec<Ball>> {
    let b = rules.derivative_box[k];
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let mut out = Vec::new();
    for ax in c.i - b[1]..=c.i + 1 - b[0] {
        for ay in c.j - b[3]..=c.j + 1 - b[2] {
            let p = net.at(c.sector, [ax, ay])?;
            let q = net.at(c.sector, [ax - e[0], ay - e[1]])?;
            let mid = [p.mid[0] - q.mid[0], p.mid[1] - q.mid[1]];
            let size = mid[0].abs().max(mid[1].abs());
            out.push(Ball {
                mid,
                rad: (p.rad + q.rad + gamma(1) * size) * (1.0 + gamma(3)),
            });
        }
    }
    Some(out)
}

/// `p_x - p_{x - e}` as a ball.
fn difference(net: &Net, s: usize, x: LatticePoint, e: LatticePoint) -> Option<Ball> {
    let p = net.at(s, x)?;
    let q = net.at(s, [x[0] - e[0], x[1] - e[1]])?;
    let mid = [p.mid[0] - q.mid[0], p.mid[1] - q.mid[1]];
    let size = mid[0].abs().max(mid[1].abs());
    Some(Ball {
        mid,
        rad: (p.rad + q.rad + gamma(1) * size) * (1.0 + gamma(3)),
    })
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

/// The balls of radius `rad + factor * M` around `value` at the corners of
/// the box `bx` (the cell's bounding box), `M` the largest difference over
/// the box's window: the limit over the cell lies in their union (math doc
/// section 20.3, [`NormBound`]: `|g(x) - q_{floor(x)}| <= K T M`).
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
    let m = largest_difference(window, nb.directions, &value)?;
    let mut out = Vec::with_capacity(4);
    for x in [bx[0], bx[1]] {
        for y in [bx[2], bx[3]] {
            let q = value([x, y])?;
            out.push(Ball {
                mid: q.mid,
                rad: (q.rad + nb.factor * m) * (1.0 + gamma(2)),
            });
        }
    }
    Some(out)
}

/// The norm-based enclosure of the derivative `d_{e_k} f` over a cell
/// **\[derived\]**: [`norm_balls`] of the differences
/// `q_y = p_y - p_{y - e_k}`.
fn derivative_balls(net: &Net, nb: &NormBounds, c: &Cell, k: usize) -> Option<Vec<Ball>> {
    let e: LatticePoint = if k == 0 { [1, 0] } else { [0, 1] };
    let bx = [c.i, c.i + 1, c.j, c.j + 1];
    norm_balls(&nb.derivative[k], bx, |y| difference(net, c.sector, y, e))
}

/// The Jacobian's sign on a cell **\[derived\]**: `d_1 f` and `d_2 f` lie in
/// the convex hulls of the two windows of differences (non-negative
/// refinable functions with partition of unity), and `det(a, b)` is bilinear,
/// so its extremes over the product of hulls are at pairs of window points;
/// each pair's determinant is enclosed in midpoint-radius arithmetic
/// (`|det(a, b) - det(a~, b~)| <= r_a (|b~_x| + |b~_y|) + r_b (|a~_x| + |a~_y|) + 2 r_a r_b`
/// plus `gamma_3 (|a~_x b~_y| + |a~_y b~_x|)` of rounding).
pub fn cell_sign(net: &Net, rules: &RegularRules, c: &Cell) -> CellSign {
    let undecided = CellSign {
        sign: 0,
        bounds: [f64::NAN; 2],
    };
    let windows = match rules.norm {
        None => (differences(net, rules, c, 0), differences(net, rules, c, 1)),
        Some(nb) => (
            derivative_balls(net, &nb, c, 0),
            derivative_balls(net, &nb, c, 1),
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

/// The closed path at ring index `3 L / 4` through all sectors (lattice
/// points of each sector's chart, sector by sector counter-clockwise; the
/// last point of a sector is the first of the next).
fn ring_path(lattice: Lattice, level: u32) -> Vec<LatticePoint> {
    let r = 3i64 << level >> 2;
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
/// (non-negative refinable function of the mask); with `p_x` and `p_y` that
/// set lies in an open half-plane through the origin (checked with the
/// direction `u = p_x + p_y`, every ball at positive distance), so the angle
/// swept from `f(x)` to `f(y)` equals the principal angle, and summing the
/// principal angles of the control polygon telescopes to the same total.
pub fn winding(net: &Net, rules: &RegularRules, level: u32) -> Option<i64> {
    let path = ring_path(rules.lattice, level);
    let b = rules.mask_box;
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
