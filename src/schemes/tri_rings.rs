//! The `k`-ring of a vertex of valence `n` in a triangle mesh whose other
//! vertices are regular, as a lattice with one extraordinary point, and the
//! one assembly of a local matrix on it for the triangle schemes without a
//! ring of polynomial patches: [`super::butterfly`],
//! [`super::modified_butterfly`] and [`super::sqrt3`] (math doc section 21).
//!
//! ## Layout
//!
//! The `n` sectors around the centre `v` are copies of one sixth of the
//! regular triangle lattice: sector `s` is spanned by `u_s` and `u_{s+1}`, the
//! directions of the neighbours `e_s` and `e_{s+1}`. A point of sector `s` has
//! lattice coordinates `(a, b)` (`a >= 1`, `b >= 0`): it sits at
//! `a u_s + b u_{s+1}`, on ring `r = a + b` (its graph distance from `v`).
//! Ring `r >= 1` holds `r n` points, `r` per sector (`b = 0..r`; the point
//! `b = r` is the point `b = 0` of the next sector), indexed
//!
//! ```text
//! index(s, a, b) = 1 + n r (r - 1) / 2 + s r + b,     r = a + b;     index(v) = 0,
//! ```
//!
//! so the `k`-ring has `1 + n k (k + 1) / 2` points: `n + 1` (one-ring),
//! `3n + 1` (two-ring, the order and labels of Loop's
//! [`TwoRing`](super::loop_subdivision::TwoRing): `v, e_i, g_i, f_i`),
//! `6n + 1` (three-ring; its third ring is labelled `h0..`).
//!
//! The neighbours of a lattice point, counter-clockwise, are the points at
//! `+u, +w, w - u, -u, -w, u - w` (`u = u_s`, `w = u_{s+1}`); the centre's
//! are `e_0 .. e_{n-1}`. A point whose coordinates leave its sector is read in
//! the neighbouring sector: `(0, b)` of sector `s` is `(b, 0)` of sector
//! `s + 1`, and `(a, b)` with `b < 0` is `(-b, a + b)` of sector `s - 1`
//! (near the seam the lattice is regular, where `u_{s+1} = u_s - u_{s-1}`).

use super::assembly::{Assembler, LocalMatrix, PointLabel, Role};
use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// A stencil: `(point, weight)` pairs.
pub type Stencil<T> = Vec<(usize, T)>;

/// A regular-part mask as plain data: `(lattice offset (a, b) = a u + b w,
/// weight)` pairs, `u` and `w` two lattice directions 60 degrees apart.
pub type Mask = Vec<([i64; 2], f64)>;

/// Counter-clockwise neighbour lists of a closed triangle mesh or of the
/// lattice around an extraordinary vertex: the one thing the edge stencils
/// of the butterfly schemes read, so the local matrices and the mesh
/// refinement ([`crate::mesh::tri_schemes`]) apply the same code.
pub trait TriNeighbourhood {
    /// Number of neighbours of point `p`.
    fn valence(&self, p: usize) -> usize;
    /// The `k`-th neighbour of `p` counter-clockwise (`k` mod the valence).
    fn neighbour(&self, p: usize, k: usize) -> usize;
}

/// The lattice around a vertex of valence `n` (module docs); every index is
/// a point, the `k`-ring is the first [`ring_len`] of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice {
    n: usize,
}

/// Number of points of the `k`-ring at valence `n`: `1 + n k (k + 1) / 2`.
pub fn ring_len(n: usize, k: usize) -> usize {
    1 + n * k * (k + 1) / 2
}

impl Lattice {
    /// The lattice of valence `n` (`n >= 3` is the caller's business).
    pub fn new(n: usize) -> Self {
        Lattice { n }
    }

    /// The valence of the centre.
    pub fn centre_valence(&self) -> usize {
        self.n
    }

    /// `(ring, sector, a, b)` of a point (`(0, 0, 0, 0)` for the centre).
    pub fn coords(&self, p: usize) -> (usize, usize, i64, i64) {
        if p == 0 {
            return (0, 0, 0, 0);
        }
        let n = self.n;
        let mut r = 1;
        while ring_len(n, r) <= p {
            r += 1;
        }
        let off = p - ring_len(n, r - 1);
        let (s, b) = (off / r, off % r);
        (r, s, (r - b) as i64, b as i64)
    }

    /// The index of the point `(a, b)` of sector `s` (any integer sector,
    /// taken mod `n`), read in the neighbouring sector where it leaves `s`.
    pub fn index(&self, s: i64, a: i64, b: i64) -> usize {
        let n = self.n as i64;
        let (mut s, mut a, mut b) = (s, a, b);
        loop {
            if a == 0 && b == 0 {
                return 0;
            }
            if b < 0 {
                (s, a, b) = (s - 1, -b, a + b);
            } else if a <= 0 {
                // a u_s + b u_{s+1} = (a + b) u_{s+1} - a u_{s+2}
                (s, a, b) = (s + 1, a + b, -a);
            } else {
                break;
            }
        }
        let r = (a + b) as usize;
        let s = s.rem_euclid(n) as usize;
        ring_len(self.n, r - 1) + s * r + b as usize
    }

    /// The position of `q` among the neighbours of `p` (`None`: not adjacent).
    pub fn position(&self, p: usize, q: usize) -> Option<usize> {
        (0..self.valence(p)).find(|&k| self.neighbour(p, k) == q)
    }

    /// The label of a point: `v`, `e_s`, then `g_s` / `f_s` on the second
    /// ring (as Loop's two-ring), `h_i` beyond (`i` counted from the first
    /// point of the third ring).
    pub fn label(&self, p: usize) -> PointLabel {
        let (r, s, _, b) = self.coords(p);
        match (r, b) {
            (0, _) => PointLabel::new(Role::Vertex, 0),
            (1, _) => PointLabel::new(Role::EdgeNeighbour, s),
            (2, 0) => PointLabel::new(Role::SecondRing, s),
            (2, _) => PointLabel::new(Role::FaceNeighbour, s),
            _ => PointLabel::new(Role::OuterRing, p - ring_len(self.n, 2)),
        }
    }
}

impl TriNeighbourhood for Lattice {
    fn valence(&self, p: usize) -> usize {
        if p == 0 {
            self.n
        } else {
            6
        }
    }

    fn neighbour(&self, p: usize, k: usize) -> usize {
        if p == 0 {
            return 1 + k % self.n;
        }
        let (_, s, a, b) = self.coords(p);
        const DIRS: [(i64, i64); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];
        let (da, db) = DIRS[k % 6];
        self.index(s as i64, a + da, b + db)
    }
}

/// Assembles the square local matrix of scheme `name` on the `k`-ring of
/// valence `n`: `row(p)` is the stencil of the new point `p` (in the same
/// layout, at the next level) over old lattice points. Refuses a stencil
/// that reaches outside the `k`-ring ([`Error::Numerical`] naming the
/// point): the ring is then not closed under one step.
pub fn assemble<T: Scalar>(
    name: &str,
    n: usize,
    k: usize,
    mut row: impl FnMut(usize) -> Result<Stencil<T>>,
) -> Result<LocalMatrix<T>> {
    let lat = Lattice::new(n);
    let d = ring_len(n, k);
    let labels: Vec<PointLabel> = (0..d).map(|p| lat.label(p)).collect();
    let mut asm = Assembler::square(name, n, labels);
    for p in 0..d {
        let st = row(p)?;
        if let Some((q, _)) = st.iter().find(|(q, _)| *q >= d) {
            return Err(Error::Numerical {
                routine: "local matrix assembly",
                reason: format!(
                    "the new point {} needs the old point {} outside the {k}-ring",
                    lat.label(p),
                    lat.label(*q)
                ),
            });
        }
        asm.stencil(p, sorted_sums(st));
    }
    asm.finish()
}

/// The stencil with one entry per point, each the sum of that point's
/// weights taken in increasing order: rows that are rotations or mirror
/// images of each other get bit-identical entries whatever order their
/// terms came in (the symmetry certificate of
/// [`crate::spectral::pairing::symmetric_pair`] compares them bit for bit).
fn sorted_sums<T: Scalar>(st: Stencil<T>) -> Stencil<T> {
    let mut by_point: std::collections::BTreeMap<usize, Vec<T>> = Default::default();
    for (q, w) in st {
        by_point.entry(q).or_default().push(w);
    }
    by_point
        .into_iter()
        .map(|(q, mut ws)| {
            ws.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
            let sum = ws.into_iter().fold(T::zero(), |acc, w| acc + w);
            (q, sum)
        })
        .collect()
}

/// Where the rotation of the sectors by one (or the mirror through sector
/// 0, `u_j -> u_{-j}`) takes the outer-ring point `h_i` (`i` counted from the
/// first point of the third ring; label [`Role::OuterRing`]) at valence `n`.
pub fn moved_outer(i: usize, n: usize, mirror: bool) -> usize {
    let lat = Lattice::new(n);
    let base = ring_len(n, 2);
    let (_, s, a, b) = lat.coords(i + base);
    let s = s as i64;
    let p = if mirror {
        lat.index(-s - 1, b, a)
    } else {
        lat.index(s + 1, a, b)
    };
    p - base
}

/// What a point of the refined lattice is, for the schemes that split every
/// triangle into four (the butterfly schemes): an old vertex (its index) or
/// the new point of the edge `(p, q)` with `q` the `t`-th neighbour of `p`
/// and `p` the `tq`-th neighbour of `q`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split4Point {
    /// The old vertex.
    Vertex(usize),
    /// The edge `(p, t, q, tq)`.
    Edge(usize, usize, usize, usize),
}

/// The old element under the new point `p` of a one-to-four split: new
/// `(A, B)` of sector `s` sits at `(A/2, B/2)` of the old lattice (same
/// sector), a vertex when both are even, else the midpoint of a lattice edge.
pub fn split4_parent(lat: &Lattice, p: usize) -> Split4Point {
    let (_, s, a, b) = lat.coords(p);
    let s = s as i64;
    if a % 2 == 0 && b % 2 == 0 {
        return Split4Point::Vertex(lat.index(s, a / 2, b / 2));
    }
    let (x, y) = match (a % 2, b % 2) {
        (1, 0) => ((a - 1, b), (a + 1, b)),
        (0, _) => ((a, b - 1), (a, b + 1)),
        _ => ((a + 1, b - 1), (a - 1, b + 1)),
    };
    let p0 = lat.index(s, x.0 / 2, x.1 / 2);
    let q0 = lat.index(s, y.0 / 2, y.1 / 2);
    let t = lat.position(p0, q0).expect("midpoint of a lattice edge");
    let tq = lat.position(q0, p0).expect("midpoint of a lattice edge");
    Split4Point::Edge(p0, t, q0, tq)
}

/// The regular butterfly edge stencil (Dyn, Gregory, Levin 1990; tension
/// `w = 1/16`) of the edge `(p, q)`, `q` the `t`-th neighbour of `p`, `p` the
/// `tq`-th neighbour of `q` (math doc section 21):
///
/// ```text
/// 1/2 (p + q) + 1/8 (c + d) - 1/16 (w1 + w2 + w3 + w4)
/// ```
///
/// with `c, d` the neighbours `t + 1`, `t - 1` of `p` (the far corners of
/// the edge's triangles) and the wings `t + 2`, `t - 2` of `p` and of `q`
/// (`tq + 2`, `tq - 2`), the far corners of the triangles across the other
/// edges. At valence 3 and 4 two of these points coincide and their weights
/// add up (the regular stencil "at every valence").
pub fn butterfly_edge<T: Scalar>(
    g: &impl TriNeighbourhood,
    p: usize,
    t: usize,
    q: usize,
    tq: usize,
) -> Stencil<T> {
    let np = g.valence(p);
    let nq = g.valence(q);
    let w = T::frac(-1, 16);
    vec![
        (p, T::frac(1, 2)),
        (q, T::frac(1, 2)),
        (g.neighbour(p, t + 1), T::frac(1, 8)),
        (g.neighbour(p, t + np - 1), T::frac(1, 8)),
        (g.neighbour(p, t + 2), w.clone()),
        (g.neighbour(p, t + 2 * np - 2), w.clone()),
        (g.neighbour(q, tq + 2), w.clone()),
        (g.neighbour(q, tq + 2 * nq - 2), w),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_round_trip_and_neighbours_are_symmetric() {
        for n in [3, 4, 5, 6, 9] {
            let lat = Lattice::new(n);
            for p in 1..ring_len(n, 4) {
                let (r, s, a, b) = lat.coords(p);
                assert_eq!(a + b, r as i64);
                assert_eq!(lat.index(s as i64, a, b), p);
                for k in 0..6 {
                    let q = lat.neighbour(p, k);
                    assert!(lat.position(q, p).is_some(), "n={n} p={p} q={q}");
                    // consecutive neighbours are adjacent (triangles)
                    let q2 = lat.neighbour(p, k + 1);
                    assert!(lat.position(q, q2).is_some(), "n={n} p={p}");
                }
            }
            // the labels of the two-ring are Loop's
            let loop_labels = crate::schemes::loop_subdivision::TwoRing::new(n)
                .unwrap()
                .labels();
            let ours: Vec<PointLabel> = (0..3 * n + 1).map(|p| lat.label(p)).collect();
            assert_eq!(ours, loop_labels);
        }
    }
}
