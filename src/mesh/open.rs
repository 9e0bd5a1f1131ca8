//! Open manifold meshes (one or more boundary loops) refined by the
//! Doo-Sabin family: NURDS, original Doo-Sabin and the Catmull-Clark
//! variant (math doc section 19).
//!
//! An [`OpenMesh`] is a [`Mesh`] whose boundary edges have a *ghost*
//! half-edge: the direction `v -> u` of a boundary edge `u -> v`, which lies
//! in no face but carries the knot interval `d(v -> u)`. Ghosts are numbered
//! after the corners: `twin(h) = H + g` for the boundary corner `h` of ghost
//! `g` (`H` corners), and `knots[H + g] = d(v -> u)`; so every formula of
//! math doc sections 2-3 reads its intervals exactly as on a closed mesh.
//! A boundary vertex starts its fan ([`Mesh::vertex_half_edge`]) at its
//! outgoing boundary corner.
//!
//! One step ([`OpenMesh::refine`], the boundary rule of section 19): every
//! corner gets its new point by the member's face rule, unchanged; every
//! boundary edge `u -> v` gets the two points of the curve rule,
//! `B(g, u) = (u + E) / 2` and `B(g, v) = (E + v) / 2` with the edge point
//! `E` of its face. Faces: the F-faces, an E-face per edge (a boundary
//! edge's is `[X(f, v), X(f, u), B(g, u), B(g, v)]`) and a V-face per vertex
//! (a boundary vertex with `k` faces gets the `(k + 2)`-gon
//! `[X(h_0) .. X(h_{k-1}), B(g_in, u), B(g_out, u)]`). The new boundary is
//! `.. B(g_in, u), B(g_out, u), B(g_out, v) ..`: the curve rule applied to
//! the old boundary polygon.
//!
//! Index layout of the result: vertices `0..H` are the corners' new points,
//! `H + 2g`, `H + 2g + 1` the two curve points of ghost `g`; faces are the
//! F-faces (old face order), the E-faces (edges by representative corner
//! `h < twin(h)`, increasing), the V-faces (vertex order); ghost `2g` of
//! the result is the reverse of the E-face side `B(g, u) -> B(g, v)`, ghost
//! `2g + 1` the reverse of the V-face side at the origin of ghost `g`'s
//! corner. On a mesh without boundary this is [`super::refine::refine`]'s
//! layout and result.
//!
//! ```
//! use subdiv_lab::mesh::open::OpenMesh;
//! use subdiv_lab::schemes::SchemeKind;
//! // one quad: a boundary loop of four edges
//! let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let m = OpenMesh::from_polygons(p, &[vec![0, 1, 2, 3]]).unwrap();
//! let r = m.refine(SchemeKind::DooSabin).unwrap();
//! // 4 corner points + 2 curve points per boundary edge; F + 4 E + 4 V faces
//! assert_eq!((r.vertex_count(), r.face_count()), (12, 9));
//! // the boundary is Chaikin's polygon of the square: 8 points
//! assert_eq!(r.boundary_loops()[0].len(), 8);
//! ```

use super::refine::{first_not_halvable, new_points};
use super::sharp::rules::Boundary;
use super::sharp::SharpMesh;
use super::{Mesh, MeshError, MAX_HALF_EDGES};
use crate::schemes::SchemeKind;

/// An open (or closed) oriented manifold polygon mesh with one knot interval
/// per directed edge, boundary directions included (module docs). Built
/// only by validation ([`OpenMesh::from_polygons`]) or by refinement.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenMesh {
    /// The faces; `twin` and `knots` hold `H + G` entries (ghosts after the corners).
    mesh: Mesh,
}

impl OpenMesh {
    /// Builds and validates a mesh from positions and faces (0-based vertex
    /// indices, counter-clockwise), every knot interval 1. The polygon
    /// validator and the open-mesh topology are the ones of
    /// [`SharpMesh::builder`]: errors name non-finite coordinates, dangling
    /// indices, degenerate faces, non-manifold edges and vertices,
    /// inconsistent orientation and isolated vertices. An interior vertex of
    /// valence below 3 is refused as on closed meshes (its V-face would be
    /// degenerate); a boundary vertex with `k >= 1` faces gets a
    /// `(k + 2)`-gon.
    pub fn from_polygons<F: AsRef<[usize]>>(
        positions: Vec<[f64; 3]>,
        faces: &[F],
    ) -> Result<OpenMesh, MeshError> {
        let s = SharpMesh::builder(positions, faces)?.build(Boundary::EdgeOnly);
        let h_count = s.face_verts.len();
        let nf = s.face_start.len() - 1;
        let mut corner_face = vec![0u32; h_count];
        for f in 0..nf {
            corner_face[s.face_start[f] as usize..s.face_start[f + 1] as usize].fill(f as u32);
        }
        // Pair the corners of every edge; an edge with one corner gets a ghost.
        const UNSET: u32 = u32::MAX;
        let mut first = vec![UNSET; s.edge_verts.len()];
        let mut twin = vec![UNSET; h_count];
        for c in 0..h_count {
            let e = s.face_edges[c] as usize;
            match first[e] {
                UNSET => first[e] = c as u32,
                d => {
                    twin[c] = d;
                    twin[d as usize] = c as u32;
                }
            }
        }
        let mut ghosts = 0u32;
        for t in twin.iter_mut() {
            if *t == UNSET {
                *t = h_count as u32 + ghosts;
                ghosts += 1;
            }
        }
        let g_count = ghosts as usize;
        if (h_count + g_count) as u64 > MAX_HALF_EDGES {
            return Err(MeshError::TooLarge {
                half_edges: (h_count + g_count) as u64,
                max: MAX_HALF_EDGES,
            });
        }
        let mut ghost_twin = vec![0u32; g_count];
        for (c, &t) in twin.iter().enumerate() {
            if t as usize >= h_count {
                ghost_twin[t as usize - h_count] = c as u32;
            }
        }
        twin.extend_from_slice(&ghost_twin);
        // One outgoing corner per vertex; a boundary vertex's boundary corner.
        let nv = s.positions.len();
        let mut vertex_out = vec![UNSET; nv];
        for c in 0..h_count {
            let v = s.face_verts[c] as usize;
            // the last corner (as on closed meshes) unless a boundary corner came first
            let cur = vertex_out[v];
            if cur == UNSET || (twin[cur as usize] as usize) < h_count {
                vertex_out[v] = c as u32;
            }
        }
        let mesh = Mesh {
            positions: s.positions,
            face_start: s.face_start,
            corner_vertex: s.face_verts,
            corner_face,
            twin,
            vertex_out,
            knots: vec![1.0; h_count + g_count],
        };
        let open = OpenMesh { mesh };
        for v in 0..nv {
            if !open.is_boundary_vertex(v) {
                let valence = open.fan(v).len();
                if valence < 3 {
                    return Err(MeshError::LowValence { vertex: v, valence });
                }
            }
        }
        Ok(open)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.mesh.face_count()
    }

    /// Number of corners (half-edges in faces).
    pub fn corner_count(&self) -> usize {
        self.mesh.half_edge_count()
    }

    /// Number of boundary edges (= ghost half-edges).
    pub fn boundary_edge_count(&self) -> usize {
        self.mesh.twin.len() - self.corner_count()
    }

    /// Number of directed edges: corners and ghosts (the entries of [`Self::knots`]).
    pub fn directed_edge_count(&self) -> usize {
        self.mesh.twin.len()
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        self.mesh.positions()
    }

    /// The vertices of face `f`, counter-clockwise.
    pub fn face_vertices(&self, f: usize) -> impl Iterator<Item = usize> + '_ {
        self.mesh.face_vertices(f)
    }

    /// The faces as a [`Mesh`] view for writing (positions and faces only;
    /// its `twin` and `knots` include the ghosts).
    pub(crate) fn faces(&self) -> &Mesh {
        &self.mesh
    }

    /// Start and end vertex of directed edge `h` (a corner or a ghost).
    pub fn directed_edge(&self, h: usize) -> (usize, usize) {
        let hc = self.corner_count();
        if h < hc {
            (self.mesh.origin(h), self.mesh.target(h))
        } else {
            let c = self.mesh.twin[h] as usize;
            (self.mesh.target(c), self.mesh.origin(c))
        }
    }

    /// Whether directed edge `h` (a corner or a ghost) lies on the boundary.
    pub fn is_boundary_edge(&self, h: usize) -> bool {
        h >= self.corner_count() || self.mesh.twin[h] as usize >= self.corner_count()
    }

    /// Whether vertex `v` lies on a boundary loop.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.mesh.twin[self.mesh.vertex_out[v] as usize] as usize >= self.corner_count()
    }

    /// The outgoing corners of `v` counter-clockwise (`rotate`), from its
    /// outgoing boundary corner on a boundary vertex.
    fn fan(&self, v: usize) -> Vec<usize> {
        let hc = self.corner_count();
        let start = self.mesh.vertex_out[v] as usize;
        let mut out = vec![start];
        let mut h = start;
        loop {
            let t = self.mesh.twin[self.mesh.prev(h)] as usize;
            if t >= hc || t == start {
                return out;
            }
            out.push(t);
            h = t;
        }
    }

    /// The directed edge `u -> v` (a corner or a ghost), if the mesh has it.
    pub fn find_directed_edge(&self, u: usize, v: usize) -> Option<usize> {
        if u >= self.vertex_count() || v >= self.vertex_count() {
            return None;
        }
        let fan = self.fan(u);
        if let Some(&h) = fan.iter().find(|&&h| self.mesh.target(h) == v) {
            return Some(h);
        }
        // the ghost leaving a boundary vertex: reverse of its incoming boundary corner
        let last = *fan.last()?;
        let g = self.mesh.twin[self.mesh.prev(last)] as usize;
        (g >= self.corner_count() && self.directed_edge(g) == (u, v)).then_some(g)
    }

    /// All knot intervals, indexed by directed edge (corners, then ghosts).
    pub fn knots(&self) -> &[f64] {
        &self.mesh.knots
    }

    /// Replaces every knot interval (one per directed edge, all finite and > 0).
    pub fn set_knots(&mut self, knots: Vec<f64>) -> Result<(), MeshError> {
        if knots.len() != self.directed_edge_count() {
            return Err(MeshError::CountMismatch {
                what: "knot intervals (one per directed edge)",
                expected: self.directed_edge_count(),
                got: knots.len(),
            });
        }
        if let Some(h) = knots.iter().position(|d| !(d.is_finite() && *d > 0.0)) {
            let (u, v) = self.directed_edge(h);
            return Err(MeshError::InvalidInterval {
                u,
                v,
                value: format!("{:?}", knots[h]),
            });
        }
        self.mesh.knots = knots;
        Ok(())
    }

    /// The boundary loops, each as its boundary corners in order along the
    /// faces' direction (corner `h` runs from its vertex to the next loop
    /// entry's); loops start at their lowest-numbered ghost.
    pub fn boundary_corner_loops(&self) -> Vec<Vec<usize>> {
        let hc = self.corner_count();
        let mut seen = vec![false; self.boundary_edge_count()];
        let mut loops = Vec::new();
        for g in 0..seen.len() {
            if seen[g] {
                continue;
            }
            let mut lp = Vec::new();
            let mut h = self.mesh.twin[hc + g] as usize;
            loop {
                let t = self.mesh.twin[h] as usize - hc;
                if seen[t] {
                    break;
                }
                seen[t] = true;
                lp.push(h);
                h = self.mesh.vertex_out[self.mesh.target(h)] as usize;
            }
            loops.push(lp);
        }
        loops
    }

    /// The boundary loops as vertex indices (see [`Self::boundary_corner_loops`]).
    pub fn boundary_loops(&self) -> Vec<Vec<usize>> {
        self.boundary_corner_loops()
            .into_iter()
            .map(|lp| lp.into_iter().map(|h| self.mesh.origin(h)).collect())
            .collect()
    }

    /// The twin of directed edge `h` (a corner's twin may be a ghost, a ghost's is its corner).
    pub fn twin(&self, h: usize) -> usize {
        self.mesh.twin[h] as usize
    }

    /// The number of directed edges after `levels` steps, saturating (each
    /// step takes `H` corners and `G` ghosts to `4H + 4G` and `2G`): lets
    /// callers refuse a request before allocating.
    pub fn directed_edges_after(&self, levels: usize) -> u64 {
        let (mut h, mut g) = (
            self.corner_count() as u64,
            self.boundary_edge_count() as u64,
        );
        for _ in 0..levels.min(32) {
            h = h.saturating_add(g).saturating_mul(4);
            g = g.saturating_mul(2);
        }
        h.saturating_add(g)
    }

    /// One step of `scheme` (a member of the Doo-Sabin family) with the
    /// boundary rule of math doc section 19 and knot propagation (module
    /// docs). Errors: a scheme outside the family, an interval refinement
    /// cannot halve, a result beyond the 32-bit index range.
    pub fn refine(&self, scheme: SchemeKind) -> Result<OpenMesh, MeshError> {
        if !scheme.is_doo_sabin_family() {
            return Err(MeshError::UnsupportedScheme(scheme.name().to_owned()));
        }
        let m = &self.mesh;
        if let Some(h) = first_not_halvable(&m.knots) {
            let (u, v) = self.directed_edge(h);
            return Err(MeshError::KnotNotHalvable {
                u,
                v,
                value: format!("{:?}", m.knots[h]),
            });
        }
        let hc = self.corner_count();
        let gc = self.boundary_edge_count();
        let new_total = self.directed_edges_after(1);
        if new_total > MAX_HALF_EDGES {
            return Err(MeshError::TooLarge {
                half_edges: new_total,
                max: MAX_HALF_EDGES,
            });
        }
        let (nf, nv) = (self.face_count(), self.vertex_count());
        let knot = |h: usize| 0.5 * m.knots[h];

        // --- new points: corners by the face rule, two curve points per boundary edge ---
        let mut positions = vec![[0.0f64; 3]; hc + 2 * gc];
        let (corners, boundary) = positions.split_at_mut(hc);
        new_points::<true>(m, scheme, corners, boundary);

        // --- edges: representative corners h < twin(h) (every boundary corner) ---
        let mut edge_of = vec![0u32; hc];
        let mut reps: Vec<u32> = Vec::with_capacity((hc + gc) / 2);
        for h in 0..hc {
            let t = m.twin[h] as usize;
            if h < t {
                edge_of[h] = reps.len() as u32;
                if t < hc {
                    edge_of[t] = reps.len() as u32;
                }
                reps.push(h as u32);
            }
        }
        let ne = reps.len();
        let new_hc = 4 * hc + 4 * gc;
        let ghost0 = new_hc;
        let mut corner_vertex = vec![0u32; new_hc];
        let mut corner_face = vec![0u32; new_hc];
        let mut twin = vec![0u32; new_hc + 2 * gc];
        let mut knots = vec![0f64; new_hc + 2 * gc];
        let mut vertex_out: Vec<u32> = (0..(hc + 2 * gc) as u32).collect();
        let mut face_start = Vec::with_capacity(nf + ne + nv + 1);

        // F-faces: the old faces' corners.
        face_start.extend_from_slice(&m.face_start[..nf]);
        for c in 0..hc {
            corner_vertex[c] = c as u32;
            corner_face[c] = m.corner_face[c];
            knots[c] = knot(c);
            let e = edge_of[c] as usize;
            let base = hc + 4 * e;
            twin[c] = if reps[e] as usize == c {
                base
            } else {
                base + 2
            } as u32;
        }
        // E-faces.
        for (e, &h) in reps.iter().enumerate() {
            let h = h as usize;
            let t = m.twin[h] as usize;
            let base = hc + 4 * e;
            face_start.push(base as u32);
            corner_face[base..base + 4].fill((nf + e) as u32);
            corner_vertex[base] = m.next(h) as u32;
            corner_vertex[base + 1] = h as u32;
            knots[base] = knot(t);
            knots[base + 1] = knot(m.rotate(h));
            knots[base + 2] = knot(h);
            twin[base] = h as u32;
            if t < hc {
                corner_vertex[base + 2] = m.next(t) as u32;
                corner_vertex[base + 3] = t as u32;
                knots[base + 3] = knot(m.rotate(t));
                twin[base + 2] = t as u32;
            } else {
                // boundary edge u -> v: [X(f, v), X(f, u), B(g, u), B(g, v)]
                let g = t - hc;
                corner_vertex[base + 2] = (hc + 2 * g) as u32;
                corner_vertex[base + 3] = (hc + 2 * g + 1) as u32;
                // the spoke B(g, v) -> X(f, v) carries X(f, v)'s interval across the edge
                knots[base + 3] = knot(m.next(h));
                twin[base + 2] = (ghost0 + 2 * g) as u32;
                twin[ghost0 + 2 * g] = (base + 2) as u32;
                knots[ghost0 + 2 * g] = knot(t);
                vertex_out[hc + 2 * g] = (base + 2) as u32;
            }
        }
        // V-faces.
        let mut next_corner = hc + 4 * ne;
        for v in 0..nv {
            face_start.push(next_corner as u32);
            let fv = (nf + ne + v) as u32;
            let start = m.vertex_out[v] as usize;
            let mut h = start;
            loop {
                let c = next_corner;
                next_corner += 1;
                corner_vertex[c] = h as u32;
                corner_face[c] = fv;
                knots[c] = knot(h);
                // The V-face edge X(h_k) -> X(h_{k+1}) crosses g = prev(h_k).
                let g = m.prev(h);
                let e = edge_of[g] as usize;
                let base = hc + 4 * e;
                let partner = if reps[e] as usize == g {
                    base + 3
                } else {
                    base + 1
                };
                twin[c] = partner as u32;
                twin[partner] = c as u32;
                let t = m.twin[g] as usize;
                if t >= hc {
                    // g is the incoming boundary corner: close with B(g_in, v), B(g_out, v).
                    let (g_in, g_out) = (t - hc, m.twin[start] as usize - hc);
                    let c1 = next_corner;
                    let c2 = next_corner + 1;
                    next_corner += 2;
                    corner_vertex[c1] = (hc + 2 * g_in + 1) as u32;
                    corner_vertex[c2] = (hc + 2 * g_out) as u32;
                    corner_face[c1] = fv;
                    corner_face[c2] = fv;
                    // boundary side B(g_in, v) -> B(g_out, v): v's interval along g_in's edge
                    knots[c1] = knot(t);
                    twin[c1] = (ghost0 + 2 * g_out + 1) as u32;
                    twin[ghost0 + 2 * g_out + 1] = c1 as u32;
                    knots[ghost0 + 2 * g_out + 1] = knot(start);
                    vertex_out[hc + 2 * g_in + 1] = c1 as u32;
                    // spoke B(g_out, v) -> X(start), twin of the E-face's X(f, v) -> B(g, v)
                    knots[c2] = knot(m.rotate(start));
                    let base_out = hc + 4 * edge_of[start] as usize;
                    twin[c2] = (base_out + 1) as u32;
                    twin[base_out + 1] = c2 as u32;
                    break;
                }
                h = t;
                if h == start {
                    break;
                }
            }
        }
        face_start.push(next_corner as u32);
        debug_assert_eq!(next_corner, new_hc);
        Ok(OpenMesh {
            mesh: Mesh {
                positions,
                face_start,
                corner_vertex,
                corner_face,
                twin,
                vertex_out,
                knots,
            },
        })
    }

    /// `levels` steps of [`Self::refine`].
    pub fn refine_levels(&self, scheme: SchemeKind, levels: usize) -> Result<OpenMesh, MeshError> {
        let mut m = self.clone();
        for _ in 0..levels {
            m = m.refine(scheme)?;
        }
        Ok(m)
    }

    /// Re-checks the structural invariants (used by tests on refined
    /// meshes): twins are an involution that reverses every directed edge,
    /// ghosts pair with corners, intervals are positive, every vertex's fan
    /// holds all its outgoing corners. Returns the first violation.
    pub fn check_invariants(&self) -> Result<(), String> {
        let n = self.directed_edge_count();
        if self.mesh.knots.len() != n {
            return Err("knots and twins disagree in length".into());
        }
        let hc = self.corner_count();
        for h in 0..n {
            let t = self.twin(h);
            if t >= n || self.twin(t) != h {
                return Err(format!("twin of {h} is not an involution"));
            }
            if h >= hc && t >= hc {
                return Err(format!("ghost {h} is paired with a ghost"));
            }
            let ((a, b), (c, d)) = (self.directed_edge(h), self.directed_edge(t));
            if (a, b) != (d, c) {
                return Err(format!("twin of {h} does not reverse it"));
            }
            if !(self.mesh.knots[h].is_finite() && self.mesh.knots[h] > 0.0) {
                return Err(format!("knot of {h} is {}", self.mesh.knots[h]));
            }
        }
        let mut count = vec![0usize; self.vertex_count()];
        for h in 0..hc {
            count[self.mesh.origin(h)] += 1;
        }
        for (v, &c) in count.iter().enumerate() {
            if self.mesh.origin(self.mesh.vertex_out[v] as usize) != v {
                return Err(format!("vertex_out of {v} does not start at it"));
            }
            if self.fan(v).len() != c {
                return Err(format!("vertex {v}'s corners are not a single fan"));
            }
        }
        Ok(())
    }
}
