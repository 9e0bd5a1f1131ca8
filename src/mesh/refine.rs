//! One refinement step of the Doo-Sabin family on a whole mesh (math doc section 3).
//!
//! This is that family's implementation of the mesh rules (with
//! [`super::limit`]), reached in the library only through
//! [`FaceSplit`](super::rules::FaceSplit); [`refine`] refuses any scheme
//! outside the family ([`MeshError::UnsupportedScheme`]), and the
//! [`SchemeKind`] selects the member (weights below).
//!
//! For every face `f` with corners `P_0..P_{n-1}` a new vertex per corner:
//!
//! * **NURDS**: edge points `E_i = r_i P_i + (1 - r_i) P_{i+1}` with
//!   `r_i = q_{i+1} / (p_i + q_{i+1})`, face point `F = sum_j c_j P_j` with the
//!   face weights of [`crate::knots::face_weights()`], and
//!   `P'_i = (P_i + E_{i-1} + E_i + F) / 4`;
//! * **Catmull-Clark variant**: the same with `r_i = 1/2`, `c_j = 1/n`
//!   (`P'_i = 1/2 P_i + 1/8 (P_{i-1} + P_{i+1}) + F/4`);
//! * **original Doo-Sabin** (seed 004): `P'_i = sum_j w_ij P_j`,
//!   `w_ii = (n+5)/(4n)`, `w_ij = (3 + 2 cos(2 pi (i-j)/n)) / (4n)`.
//!
//! New faces: an F-face per old face, an E-face per edge, a V-face per vertex.
//! Index layout of the result (old mesh with `F` faces, `E` edges, `V`
//! vertices, `H = 2E` half-edges):
//!
//! * new vertex `c` is the new point of old corner `c` (`H` vertices);
//! * faces `0..F` are the F-faces, F-face `f` has the corners of old face `f`
//!   in the same order (new corner `c` = new vertex `c`); so an extraordinary
//!   face keeps its index and its corner labelling under refinement;
//! * faces `F..F+E` are the E-faces, numbered by the edges' representative
//!   half-edges `h < twin(h)` in increasing order; the E-face of `h = (u->v)`
//!   in face `f` with twin in face `g` is `[X(f,v), X(f,u), X(g,u), X(g,v)]`;
//! * faces `F+E..F+E+V` are the V-faces in vertex order; V-face `v` has corner
//!   `k` in face `f_k`, the faces around `v` counter-clockwise starting at
//!   [`Mesh::vertex_half_edge`] (the order of the vertex-EP preset).
//!
//! New knot intervals **\[derived\]** (math doc section 3): for the new vertex
//! `X = (f, P_i)` with corner intervals `p, q`: `d(X -> (f,P_{i+1})) = p/2`,
//! `d(X -> (f,P_{i-1})) = q/2`, spoke across the old edge `(P_i, P_{i+1})`:
//! `q/2`, spoke across `(P_{i-1}, P_i)`: `p/2`. In the layout above every
//! new half-edge of an F- or V-face carries `p/2` of its start corner and
//! every half-edge of an E-face carries `q/2` of its start corner.
//!
//! Twins and knots are produced directly from this layout (no hashing), in
//! `O(H)` time and memory.

// Index loops mirror the subscripts of the formulas in the math doc.
#![allow(clippy::needless_range_loop)]

use super::{Mesh, MeshError};
use crate::knots::face_weights::interval_kernel;
use crate::schemes::SchemeKind;

/// Per-valence weight tables for original Doo-Sabin, built on demand.
#[derive(Default)]
struct DooSabinTables {
    by_n: Vec<Option<Vec<f64>>>,
}

impl DooSabinTables {
    /// `w(k) = (3 + 2 cos(2 pi k / n)) / (4n)` for `k != 0`, `w(0) = (n+5)/(4n)`.
    fn get(&mut self, n: usize) -> &[f64] {
        if self.by_n.len() <= n {
            self.by_n.resize(n + 1, None);
        }
        self.by_n[n].get_or_insert_with(|| {
            let den = 4.0 * n as f64;
            (0..n)
                .map(|k| {
                    if k == 0 {
                        (n as f64 + 5.0) / den
                    } else {
                        let c = (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos();
                        (3.0 + 2.0 * c) / den
                    }
                })
                .collect()
        })
    }
}

/// Scratch buffers reused across faces.
#[derive(Default)]
struct Scratch {
    p: Vec<[f64; 3]>,
    e: Vec<[f64; 3]>,
    r: Vec<f64>,
    s: Vec<f64>,
}

/// The face point `F = sum_j c_j P_j` of face `f` under `scheme`: the limit point
/// of the face's centre (math doc section 5: `F` is invariant, `c^T A = c^T`).
///
/// NURDS uses the face weights of the face's edge ratios; the Catmull-Clark
/// variant and original Doo-Sabin (whose face block is a symmetric circulant)
/// use the centroid.
pub fn face_point(mesh: &Mesh, f: usize, scheme: SchemeKind) -> [f64; 3] {
    let corners = mesh.face_corners(f);
    let n = corners.len();
    let mut out = [0.0; 3];
    if matches!(scheme, SchemeKind::Nurds) {
        let c = nurds_face_weights(mesh, corners.start, n);
        for (j, h) in corners.enumerate() {
            let p = mesh.positions[mesh.corner_vertex[h] as usize];
            for k in 0..3 {
                out[k] += c[j] * p[k];
            }
        }
    } else {
        for h in corners {
            let p = mesh.positions[mesh.corner_vertex[h] as usize];
            for k in 0..3 {
                out[k] += p[k];
            }
        }
        for o in &mut out {
            *o /= n as f64;
        }
    }
    out
}

/// Face weights and edge ratios `(r_i, s_i = 1 - r_i)` of the face starting at
/// corner `start`, from the intervals `p_i` and `q_{i+1}` of each edge with
/// unbounded exponents ([`interval_kernel`]): any finite positive intervals
/// are accepted (`p_i + q_{i+1}` may overflow `f64`, `r_i` may lie below it;
/// such an `r_i` rounds to 0 in the edge point, an error below `1e-308` of
/// the edge length).
fn face_ratios(
    mesh: &Mesh,
    start: usize,
    n: usize,
    r: &mut Vec<f64>,
    s: &mut Vec<f64>,
) -> Vec<f64> {
    let a: Vec<f64> = (0..n).map(|i| mesh.knots[start + i]).collect();
    let b: Vec<f64> = (0..n)
        .map(|i| mesh.knots[mesh.rotate(start + (i + 1) % n)])
        .collect();
    let (c, rs) = interval_kernel(&a, &b);
    r.clear();
    s.clear();
    for (ri, si) in rs {
        r.push(ri);
        s.push(si);
    }
    c
}

/// NURDS face weights of the face starting at corner `start`.
pub(crate) fn nurds_face_weights(mesh: &Mesh, start: usize, n: usize) -> Vec<f64> {
    let (mut r, mut s) = (Vec::with_capacity(n), Vec::with_capacity(n));
    face_ratios(mesh, start, n, &mut r, &mut s)
}

/// Checks that every knot interval halves exactly (the refined mesh carries
/// `d / 2`): true for every normal `f64`, and for a subnormal one with an even
/// last bit. An inexact half would silently change the edge ratios (or give
/// 0); [`MeshError::KnotNotHalvable`] names the edge instead.
fn check_halvable(mesh: &Mesh) -> Result<(), MeshError> {
    match first_not_halvable(&mesh.knots) {
        Some(h) => Err(MeshError::KnotNotHalvable {
            u: mesh.origin(h),
            v: mesh.target(h),
            value: format!("{:?}", mesh.knots[h]),
        }),
        None => Ok(()),
    }
}

/// The new points of one step of `scheme`: `corners[c]` is the new vertex of
/// old corner `c` (the member's face rule, module docs), for every face.
///
/// With `OPEN` (meshes with a boundary, [`super::open`], math doc section 19)
/// `mesh.twin` and `mesh.knots` run on past the corners into the ghost
/// half-edges: a corner `h` whose twin is the ghost `H + g` lies on a
/// boundary edge `P_i -> P_{i+1}`, and `boundary[2g]`, `boundary[2g + 1]`
/// get the two points of the curve rule on that edge (math doc section 2):
/// `(P_i + E_i) / 2` and `(E_i + P_{i+1}) / 2`, with the edge point `E_i` of
/// the face rule (NURDS: the ratio of the edge's two intervals; the uniform
/// members: the midpoint). Without `OPEN` nothing else is computed.
pub(crate) fn new_points<const OPEN: bool>(
    mesh: &Mesh,
    scheme: SchemeKind,
    corners: &mut [[f64; 3]],
    boundary: &mut [[f64; 3]],
) {
    let h_count = mesh.half_edge_count();
    let mut ds = DooSabinTables::default();
    let mut sc = Scratch::default();
    for f in 0..mesh.face_count() {
        let start = mesh.face_start[f] as usize;
        let n = mesh.face_start[f + 1] as usize - start;
        sc.p.clear();
        sc.p.extend((start..start + n).map(|h| mesh.positions[mesh.corner_vertex[h] as usize]));
        let out = &mut corners[start..start + n];
        match scheme {
            SchemeKind::DooSabin => {
                let w = ds.get(n);
                for (i, o) in out.iter_mut().enumerate() {
                    let mut acc = [0.0; 3];
                    for (j, p) in sc.p.iter().enumerate() {
                        let wij = w[(i + n - j) % n];
                        for k in 0..3 {
                            acc[k] += wij * p[k];
                        }
                    }
                    *o = acc;
                }
                if OPEN {
                    sc.e.clear();
                    for i in 0..n {
                        let (a, b) = (sc.p[i], sc.p[(i + 1) % n]);
                        sc.e.push([
                            0.5 * a[0] + 0.5 * b[0],
                            0.5 * a[1] + 0.5 * b[1],
                            0.5 * a[2] + 0.5 * b[2],
                        ]);
                    }
                }
            }
            _ => {
                let nurds = matches!(scheme, SchemeKind::Nurds);
                let mut fp = [0.0; 3];
                if nurds {
                    let c = face_ratios(mesh, start, n, &mut sc.r, &mut sc.s);
                    for (cj, p) in c.iter().zip(&sc.p) {
                        for k in 0..3 {
                            fp[k] += cj * p[k];
                        }
                    }
                } else {
                    for p in &sc.p {
                        for k in 0..3 {
                            fp[k] += p[k];
                        }
                    }
                    let inv = 1.0 / n as f64;
                    for x in &mut fp {
                        *x *= inv;
                    }
                }
                sc.e.clear();
                for i in 0..n {
                    let (a, b) = (sc.p[i], sc.p[(i + 1) % n]);
                    let (ri, si) = if nurds {
                        (sc.r[i], sc.s[i])
                    } else {
                        (0.5, 0.5)
                    };
                    sc.e.push([
                        ri * a[0] + si * b[0],
                        ri * a[1] + si * b[1],
                        ri * a[2] + si * b[2],
                    ]);
                }
                for (i, o) in out.iter_mut().enumerate() {
                    let (p, e0, e1) = (sc.p[i], sc.e[(i + n - 1) % n], sc.e[i]);
                    for k in 0..3 {
                        o[k] = 0.25 * (p[k] + e0[k] + e1[k] + fp[k]);
                    }
                }
            }
        }
        if OPEN {
            for i in 0..n {
                let t = mesh.twin[start + i] as usize;
                if t < h_count {
                    continue;
                }
                let g = t - h_count;
                let (a, e, b) = (sc.p[i], sc.e[i], sc.p[(i + 1) % n]);
                for k in 0..3 {
                    boundary[2 * g][k] = 0.5 * (a[k] + e[k]);
                    boundary[2 * g + 1][k] = 0.5 * (e[k] + b[k]);
                }
            }
        }
    }
}

/// The first knot interval of `knots` that refinement cannot halve exactly
/// (the refined mesh carries `d / 2`): none for a normal `f64`, and none for
/// a subnormal one with an even last bit. An inexact half would silently
/// change the edge ratios (or give 0).
pub(crate) fn first_not_halvable(knots: &[f64]) -> Option<usize> {
    knots.iter().position(|&d| {
        let half = 0.5 * d;
        !(half > 0.0 && half * 2.0 == d)
    })
}

/// One subdivision step of `scheme` (NURDS, original Doo-Sabin or the
/// Catmull-Clark variant) with knot propagation; see the module docs for the
/// index layout of the result.
///
/// The knot intervals of the input are used by NURDS only; the result always
/// carries the propagated (halved) intervals.
pub fn refine(mesh: &Mesh, scheme: SchemeKind) -> Result<Mesh, MeshError> {
    if !scheme.is_doo_sabin_family() {
        return Err(MeshError::UnsupportedScheme(scheme.name().to_owned()));
    }
    check_halvable(mesh)?;
    let h_count = mesh.half_edge_count();
    crate::mesh::quadrupled_half_edges(mesh)?;
    let nf = mesh.face_count();
    let nv = mesh.vertex_count();
    let ne = h_count / 2;

    // --- new positions: one per old corner ---
    let mut positions = vec![[0.0f64; 3]; h_count];
    new_points::<false>(mesh, scheme, &mut positions, &mut []);

    // --- edges: representative half-edges h < twin(h) ---
    // edge_of[h] = index of the edge of h, for both half-edges.
    let mut edge_of = vec![0u32; h_count];
    let mut reps: Vec<u32> = Vec::with_capacity(ne);
    for h in 0..h_count {
        let t = mesh.twin[h] as usize;
        if h < t {
            edge_of[h] = reps.len() as u32;
            edge_of[t] = reps.len() as u32;
            reps.push(h as u32);
        }
    }

    let hn = h_count * 4;
    let mut corner_vertex = vec![0u32; hn];
    let mut corner_face = vec![0u32; hn];
    let mut twin = vec![0u32; hn];
    let mut knots = vec![0f64; hn];
    let mut face_start = Vec::with_capacity(nf + ne + nv + 1);

    // F-faces: same corners as the old faces.
    face_start.extend_from_slice(&mesh.face_start[..nf]);
    for c in 0..h_count {
        corner_vertex[c] = c as u32;
        corner_face[c] = mesh.corner_face[c];
        knots[c] = 0.5 * mesh.knots[c];
        // twin: in the E-face of c's edge
        let e = edge_of[c] as usize;
        let base = h_count + 4 * e;
        twin[c] = if reps[e] as usize == c {
            base
        } else {
            base + 2
        } as u32;
    }
    // E-faces.
    for (e, &h) in reps.iter().enumerate() {
        let h = h as usize;
        let t = mesh.twin[h] as usize;
        let base = h_count + 4 * e;
        face_start.push(base as u32);
        let nh = mesh.next(h);
        let nt = mesh.next(t);
        corner_vertex[base] = nh as u32;
        corner_vertex[base + 1] = h as u32;
        corner_vertex[base + 2] = nt as u32;
        corner_vertex[base + 3] = t as u32;
        let fe = (nf + e) as u32;
        corner_face[base..base + 4].fill(fe);
        // E-face half-edges carry q/2 of their start corner.
        knots[base] = 0.5 * mesh.knots[t];
        knots[base + 1] = 0.5 * mesh.knots[mesh.rotate(h)];
        knots[base + 2] = 0.5 * mesh.knots[h];
        knots[base + 3] = 0.5 * mesh.knots[mesh.rotate(t)];
        twin[base] = h as u32;
        twin[base + 2] = t as u32;
        // base+1 and base+3 are twinned from the V-faces below.
    }
    // V-faces.
    let mut next_corner = 3 * h_count;
    for v in 0..nv {
        face_start.push(next_corner as u32);
        let fv = (nf + ne + v) as u32;
        let start = mesh.vertex_out[v] as usize;
        let mut h = start;
        loop {
            let c = next_corner;
            next_corner += 1;
            corner_vertex[c] = h as u32;
            corner_face[c] = fv;
            knots[c] = 0.5 * mesh.knots[h];
            // The V-face edge X(h_k) -> X(h_{k+1}) crosses g = prev(h_k).
            let g = mesh.prev(h);
            let e = edge_of[g] as usize;
            let base = h_count + 4 * e;
            let partner = if reps[e] as usize == g {
                base + 3
            } else {
                base + 1
            };
            twin[c] = partner as u32;
            twin[partner] = c as u32;
            h = mesh.twin[g] as usize;
            if h == start {
                break;
            }
        }
    }
    face_start.push(next_corner as u32);
    debug_assert_eq!(next_corner, hn);
    // One outgoing half-edge per new vertex: its F-face corner.
    let vertex_out: Vec<u32> = (0..h_count as u32).collect();
    Ok(Mesh {
        positions,
        face_start,
        corner_vertex,
        corner_face,
        twin,
        vertex_out,
        knots,
    })
}

/// `levels` steps of [`refine`].
pub fn refine_levels(mesh: &Mesh, scheme: SchemeKind, levels: usize) -> Result<Mesh, MeshError> {
    let mut m = mesh.clone();
    for _ in 0..levels {
        m = refine(&m, scheme)?;
    }
    Ok(m)
}

/// Number of half-edges after `levels` steps (each step multiplies it by 4),
/// saturating; lets callers refuse a request before allocating. Any count
/// has saturated after 32 steps, so a huge `levels` costs no more than that.
pub fn half_edges_after(mesh: &Mesh, levels: usize) -> u64 {
    let mut h = mesh.half_edge_count() as u64;
    for _ in 0..levels.min(32) {
        h = h.saturating_mul(4);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generators;

    /// The knot rules of math doc section 3, checked by looking the four
    /// directed edges of every new vertex up by their end points (independent
    /// of the index layout used to produce them).
    #[test]
    fn propagated_knots_follow_the_rules() {
        let mut m = generators::truncated_icosahedron();
        let k: Vec<f64> = (0..m.half_edge_count())
            .map(|h| 0.1 + ((h * 7919) % 97) as f64 / 10.0)
            .collect();
        m.set_knots(k).unwrap();
        let r = refine(&m, SchemeKind::Nurds).unwrap();
        r.check_invariants().unwrap();
        for c in 0..m.half_edge_count() {
            let (p, q) = m.corner_intervals(c);
            let x = c; // new vertex of corner c
            let d = |to: usize| r.knot(r.find_half_edge(x, to).expect("edge exists"));
            assert_eq!(d(m.next(c)), p / 2.0, "F-face edge to P_i+1");
            assert_eq!(d(m.prev(c)), q / 2.0, "F-face edge to P_i-1");
            assert_eq!(d(m.next(m.twin(c))), q / 2.0, "spoke across (P_i, P_i+1)");
            assert_eq!(d(m.twin(m.prev(c))), p / 2.0, "spoke across (P_i-1, P_i)");
            assert_eq!(r.valence(x), 4);
        }
        // face counts: F + E + V, sizes preserved for F-faces, V-faces have the valence
        assert_eq!(
            r.face_count(),
            m.face_count() + m.edge_count() + m.vertex_count()
        );
        for f in 0..m.face_count() {
            assert_eq!(r.face_size(f), m.face_size(f));
        }
        for v in 0..m.vertex_count() {
            assert_eq!(
                r.face_size(m.face_count() + m.edge_count() + v),
                m.valence(v)
            );
        }
    }

    #[test]
    fn tensor_quad_face_point_is_fact_2() {
        // A single quad of the cube with tensor knots: F from the mesh equals
        // the tensor face point of math doc section 2.
        let mut m = generators::cube();
        let (d0, d1, e0, e1) = (1.3, 0.4, 2.2, 0.7);
        let f = 0;
        let c: Vec<usize> = m.face_corners(f).collect();
        // P0: p0 = d0, q0 = e0; P1: p1 = e0, q1 = d1; P2: p2 = d1, q2 = e1; P3: p3 = e1, q3 = d0
        let p = [d0, e0, d1, e1];
        let q = [e0, d1, e1, d0];
        for i in 0..4 {
            m.set_knot(c[i], p[i]).unwrap();
            let h = m.rotate(c[i]);
            m.set_knot(h, q[i]).unwrap();
        }
        let w = nurds_face_weights(&m, c[0], 4);
        let den = (d0 + d1) * (e0 + e1);
        let expected = [e1 * d1 / den, e1 * d0 / den, e0 * d0 / den, e0 * d1 / den];
        for (a, b) in w.iter().zip(expected) {
            assert!((a - b).abs() < 1e-15);
        }
    }

    #[test]
    fn refusing_oversized_results() {
        let m = generators::cube();
        assert_eq!(half_edges_after(&m, 2), 24 * 16);
        assert_eq!(half_edges_after(&m, 100), u64::MAX);
    }
}
