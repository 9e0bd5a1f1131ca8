//! Winding number of a closed chain of curves given by boxes, valid for every
//! curve the boxes admit (math doc section 15, "The characteristic map over
//! a cell" **\[derived\]**). No angle is computed; only signs of bilinear
//! forms, in interval arithmetic.
//!
//! 1. Each curve is split (its own subdivision rule, [`BoxCurve::halves`])
//!    until all the boxes of a piece's hull lie in one open half-plane
//!    `H = {p : u . p > 0}` (a float direction `u`, checked in interval
//!    arithmetic). The piece's curve lies in the convex hull of its hull
//!    points, hence in `H`, for every curve in the boxes; so it avoids the
//!    origin. The first and last hull points are the piece's end points.
//! 2. A ray `D = {t d : t > 0}` (from a fixed list of float directions) is
//!    chosen such that, for every piece, either `u . d <= 0` (then `D` misses
//!    `H` and the piece does not meet `D`), or `u . d > 0` and both end boxes
//!    lie strictly on one side of the line `R d` (the sign of `d x p` is
//!    certain). `H` minus `D` has two components, `d x p > 0` and `< 0`, so
//!    the piece crosses `D` counter-clockwise `(s_end - s_start) / 2` times
//!    net, with `s = sign(d x p)`.
//! 3. The winding number about the origin is the net number of
//!    counter-clockwise crossings of any ray from the origin by the closed
//!    chain (the argument measured from `-d` jumps by `-2 pi` exactly at
//!    each such crossing, and telescopes to 0 along the chain), so it is the
//!    sum over the pieces. Consecutive curves must share their end points for
//!    every admissible curve (true for the rings: each joint is one point of
//!    the characteristic map, enclosed by both boxes).

use super::ivla::{mid, P2};
use crate::verify::interval::Iv;

/// Most halvings of one curve before the winding number is given up.
pub const WINDING_MAX_DEPTH: u32 = 24;

/// Candidate ray directions (floats; the first that decides every piece is used).
const DIRECTIONS: [[f64; 2]; 12] = [
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
    [0.0, -1.0],
    [1.0, 0.375],
    [-0.375, 1.0],
    [-1.0, -0.375],
    [0.375, -1.0],
    [1.0, -0.625],
    [0.625, 1.0],
    [-1.0, 0.625],
    [-0.625, -1.0],
];

/// A planar curve known through boxes: the convex hull of any choice of
/// points in the hull boxes contains the curve.
pub trait BoxCurve: Sized {
    /// The hull boxes; the first encloses the start point, the last the end point.
    fn hull(&self) -> Vec<P2>;
    /// The two halves (parametric midpoint).
    fn halves(&self) -> (Self, Self);
}

struct Piece {
    start: P2,
    end: P2,
    u: [f64; 2],
}

fn dot(u: [f64; 2], p: P2) -> Iv {
    Iv::point(u[0]).mul(p[0]).add(Iv::point(u[1]).mul(p[1]))
}

fn split_into<C: BoxCurve>(c: &C, depth: u32, out: &mut Vec<Piece>) -> bool {
    let h = c.hull();
    let (Some(first), Some(last)) = (h.first(), h.last()) else {
        return false;
    };
    let mut u = [0.0f64; 2];
    for p in &h {
        u[0] += mid(p[0]);
        u[1] += mid(p[1]);
    }
    if h.iter().all(|p| dot(u, *p).lo > 0.0) {
        out.push(Piece {
            start: *first,
            end: *last,
            u,
        });
        return true;
    }
    if depth >= WINDING_MAX_DEPTH {
        return false;
    }
    let (a, b) = c.halves();
    split_into(&a, depth + 1, out) && split_into(&b, depth + 1, out)
}

/// `sign(d x p)` when certain.
fn side(d: [f64; 2], p: P2) -> Option<i64> {
    let x = Iv::point(d[0]).mul(p[1]).sub(Iv::point(d[1]).mul(p[0]));
    if x.lo > 0.0 {
        Some(1)
    } else if x.hi < 0.0 {
        Some(-1)
    } else {
        None
    }
}

/// The winding number about the origin of the closed chain `curves`, valid
/// for every chain the boxes admit, or `None` when it cannot be decided (a
/// piece comes within its boxes of the origin at [`WINDING_MAX_DEPTH`], or
/// no ray decides).
pub fn winding_number<C: BoxCurve>(curves: &[C]) -> Option<i64> {
    let mut pieces = Vec::new();
    for c in curves {
        if !split_into(c, 0, &mut pieces) {
            return None;
        }
    }
    'dirs: for d in DIRECTIONS {
        let mut total = 0i64;
        for p in &pieces {
            let ud = dot(p.u, [Iv::point(d[0]), Iv::point(d[1])]);
            if ud.hi <= 0.0 {
                continue;
            }
            if !(ud.lo > 0.0) {
                continue 'dirs;
            }
            match (side(d, p.start), side(d, p.end)) {
                (Some(a), Some(b)) => total += (b - a) / 2,
                _ => continue 'dirs,
            }
        }
        return Some(total);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::charmap::ivla::p2;

    /// A polygon edge as a curve (its hull is its two end points).
    #[derive(Clone)]
    struct Seg(P2, P2);

    impl BoxCurve for Seg {
        fn hull(&self) -> Vec<P2> {
            vec![self.0, self.1]
        }
        fn halves(&self) -> (Self, Self) {
            let m = [
                self.0[0].add(self.1[0]).mul(Iv::point(0.5)),
                self.0[1].add(self.1[1]).mul(Iv::point(0.5)),
            ];
            (Seg(self.0, m), Seg(m, self.1))
        }
    }

    fn polygon(pts: &[[f64; 2]], turns: usize, r: f64) -> Vec<Seg> {
        let m = pts.len();
        (0..m * turns)
            .map(|k| {
                let (a, b) = (pts[k % m], pts[(k + 1) % m]);
                let w = |p: [f64; 2]| {
                    let q = p2(p);
                    [q[0].widen(r), q[1].widen(r)]
                };
                Seg(w(a), w(b))
            })
            .collect()
    }

    #[test]
    fn polygons_wind_as_expected() {
        let sq = [[1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0]];
        assert_eq!(winding_number(&polygon(&sq, 1, 0.0)), Some(1));
        assert_eq!(winding_number(&polygon(&sq, 2, 0.01)), Some(2));
        let rev: Vec<[f64; 2]> = sq.iter().rev().copied().collect();
        assert_eq!(winding_number(&polygon(&rev, 1, 0.01)), Some(-1));
        // shifted away from the origin
        let sh: Vec<[f64; 2]> = sq.iter().map(|p| [p[0] + 3.0, p[1]]).collect();
        assert_eq!(winding_number(&polygon(&sh, 1, 0.01)), Some(0));
        // boxes that reach the origin: undecided
        assert_eq!(winding_number(&polygon(&sq, 1, 1.5)), None);
        // a triangle whose vertices lie on the candidate rays
        let tri = [[1.0, 0.0], [-0.5, 1.0], [-0.5, -1.0]];
        assert_eq!(winding_number(&polygon(&tri, 1, 1e-9)), Some(1));
    }
}
