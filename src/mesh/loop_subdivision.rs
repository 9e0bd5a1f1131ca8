//! Loop subdivision of closed triangle meshes: one refinement step, several
//! levels, limit positions, and the work estimate (math doc, Loop section).
//!
//! One step on a closed, oriented triangle mesh with `V` vertices, `E` edges
//! and `F` faces:
//!
//! ```text
//! vertex point  v' = (1 - n beta_n) v + beta_n sum_{i<n} e_i,
//!               beta_n = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n   (beta_6 = 1/16)
//! edge point    E(a, b) = 3/8 (a + b) + 1/8 (c + d)
//! ```
//!
//! with `e_i` the `n` neighbours of `v` and `c, d` the vertices opposite the
//! edge `(a, b)` in its two triangles; every triangle is cut into four. The
//! result has `V' = V + E`, `E' = 2E + 3F`, `F' = 4F` (so `H' = 4H`
//! half-edges, and `V - E + F` is unchanged).
//!
//! Both rules are convex combinations (`0 < n beta_n <= 7/16` for `n >= 3`), so
//! every refined and every limit point lies in the convex hull of the control
//! points.
//!
//! **Limit positions.** The one-ring of `v` is mapped onto the one-ring of
//! `v'`; the left eigenvector for the eigenvalue 1 of that `(n+1) x (n+1)`
//! one-ring matrix gives the closed-form limit stencil
//!
//! ```text
//! v_inf = (1 - n chi_n) v + chi_n sum e_i,   chi_n = 1 / (3 / (8 beta_n) + n)
//! ```
//!
//! (`chi_6 = 1/12`, vertex weight `1/2`). Under refinement the vertex itself
//! approaches `v_inf` with the ratio `5/8 - n beta_n` per level (the second
//! eigenvalue of the rotation-invariant block, which equals `lambda_n^2` for
//! Loop's `beta_n`, `lambda_n = 3/8 + cos(2 pi / n) / 4` the subdominant
//! eigenvalue); its neighbours approach it with the ratio `lambda_n`.
//!
//! **Index layout of the result** (produced directly, no hashing; `O(H)` time,
//! each array allocated once at its final size):
//!
//! * vertices `0..V` are the vertex points of the old vertices (same index);
//!   vertex `V + e` is the edge point of edge `e`, the edges numbered by their
//!   representative half-edges `h < twin(h)` in increasing order (as in
//!   [`crate::mesh::refine`] and [`crate::mesh::catmull_clark`]);
//! * old face `f` with corners `h_k = 3f + k` (`k = 0, 1, 2`) becomes faces
//!   `4f + k`, the corner triangle `[origin(h_k), E(h_k), E(h_{k-1})]`, and
//!   `4f + 3`, the middle triangle `[E(h_0), E(h_1), E(h_2)]`, all keeping the
//!   orientation of `f`;
//! * knot intervals of the result are all 1 (Loop has none).
//!
//! ```
//! use subdiv_lab::mesh::generators;
//! use subdiv_lab::mesh::loop_subdivision::{limit_positions, refine_levels};
//! let ico = generators::icosahedron();
//! let twice = refine_levels(&ico, 2).unwrap();
//! assert_eq!((twice.vertex_count(), twice.face_count()), (162, 320));
//! // the refined mesh has the same limit surface: vertex 0 keeps its index
//! let (a, b) = (limit_positions(&ico).unwrap()[0], limit_positions(&twice).unwrap()[0]);
//! assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-14));
//! ```

use crate::mesh::rules::{ValenceCache, VertexRule};
use crate::mesh::{Mesh, MeshError, MAX_HALF_EDGES};
use crate::schemes::loop_subdivision::beta;
use std::sync::Arc;

/// The next corner of the same triangle (faces are `3f..3f+3`).
#[inline]
fn next3(h: usize) -> usize {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}

/// The previous corner of the same triangle.
#[inline]
fn prev3(h: usize) -> usize {
    if h % 3 == 0 {
        h + 2
    } else {
        h - 1
    }
}

/// First corner of the corner triangle of old corner `h` in the refined mesh:
/// face `4 (h / 3) + h % 3`, whose corners are `3` times that.
#[inline]
fn tri(h: usize) -> usize {
    12 * (h / 3) + 3 * (h % 3)
}

/// Checks that every face of `mesh` is a triangle; the error names the first
/// face that is not, and `operation`.
pub fn check_triangles(mesh: &Mesh, operation: &'static str) -> Result<(), MeshError> {
    for f in 0..mesh.face_count() {
        let corners = mesh.face_size(f);
        if corners != 3 {
            return Err(MeshError::NotAllTriangles {
                face: f,
                corners,
                operation,
            });
        }
    }
    Ok(())
}

/// Loop's vertex rule: `(1 - n beta_n, beta_n)`.
fn vertex_weights(n: usize) -> (f64, f64) {
    let b = beta(n);
    (1.0 - n as f64 * b, b)
}

/// The closed-form limit stencil `(1 - n chi_n, chi_n)` with
/// `chi_n = 1 / (3 / (8 beta_n) + n)` (module docs; `n = 6`: `(1/2, 1/12)`).
fn limit_weights(n: usize) -> (f64, f64) {
    let chi = 1.0 / (3.0 / (8.0 * beta(n)) + n as f64);
    (1.0 - n as f64 * chi, chi)
}

/// Loop's vertex rule and limit stencil ([`vertex_weights`],
/// [`limit_weights`]) as a [`VertexRule`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct LoopVertexRule;

impl VertexRule for LoopVertexRule {
    fn refine_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let (wv, we) = vertex_weights(n);
        Ok([wv, we, 0.0])
    }

    fn limit_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let (wv, we) = limit_weights(n);
        Ok([wv, we, 0.0])
    }
}

/// Applies the one-ring stencil of `rule` (its refinement weights, or with
/// `limit` its limit stencil) to every vertex of a closed triangle mesh:
/// `w_v(n) v + w_e(n) sum e_i`. The neighbour sums are accumulated over the
/// half-edges (each directed edge `u -> v` adds `v` to `u`), `O(H)`, into the
/// returned vector itself.
fn one_ring_stencil(
    mesh: &Mesh,
    rule: &dyn VertexRule,
    limit: bool,
    capacity: usize,
) -> Result<Vec<[f64; 3]>, MeshError> {
    let nv = mesh.vertex_count();
    let p = &mesh.positions;
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(capacity.max(nv));
    out.resize(nv, [0.0; 3]);
    let mut valence = vec![0u32; nv];
    for h in 0..mesh.half_edge_count() {
        let u = mesh.corner_vertex[h] as usize;
        let v = p[mesh.corner_vertex[next3(h)] as usize];
        let s = &mut out[u];
        s[0] += v[0];
        s[1] += v[1];
        s[2] += v[2];
        valence[u] += 1;
    }
    let mut table = ValenceCache::new(rule, limit);
    for (v, s) in out.iter_mut().enumerate() {
        let [wv, we, _] = table.get(valence[v] as usize)?;
        let c = p[v];
        *s = [
            wv * c[0] + we * s[0],
            wv * c[1] + we * s[1],
            wv * c[2] + we * s[2],
        ];
    }
    Ok(out)
}

/// One Loop step on a closed triangle mesh (see the module docs for the
/// rules and the index layout of the result).
///
/// Errors: [`MeshError::NotAllTriangles`] naming the first face that is not a
/// triangle; [`MeshError::TooLarge`] if the result would exceed the 32-bit
/// index range. (A mesh with boundary cannot be a [`Mesh`]:
/// [`Mesh::from_polygons`] refuses it with [`MeshError::BoundaryEdge`],
/// naming the face.)
///
/// ```
/// use subdiv_lab::mesh::{generators, MeshError};
/// use subdiv_lab::mesh::loop_subdivision::refine;
/// let tet = generators::tetrahedron();
/// let once = refine(&tet).unwrap();
/// assert_eq!((once.vertex_count(), once.edge_count(), once.face_count()), (10, 24, 16));
/// let err = refine(&generators::cube()).unwrap_err();
/// assert!(matches!(err, MeshError::NotAllTriangles { face: 0, corners: 4, .. }));
/// ```
pub fn refine(mesh: &Mesh) -> Result<Mesh, MeshError> {
    refine_with(mesh, &LoopVertexRule)
}

/// One step of a Loop-type scheme: Loop's edge rule and split (module docs)
/// with the vertex rule `vertex` (its [`VertexRule::refine_weights`]
/// `[w_v, w_e, 0]`); [`refine`] is this with Loop's own rule, and a scheme
/// file's rule enters here too ([`crate::mesh::user`]).
pub fn refine_with(mesh: &Mesh, vertex: &dyn VertexRule) -> Result<Mesh, MeshError> {
    check_triangles(mesh, "Loop refinement")?;
    crate::mesh::quadrupled_half_edges(mesh)?;
    let ne = mesh.half_edge_count() / 2;
    let p = &mesh.positions;
    let cv = &mesh.corner_vertex;
    let vertex_points = one_ring_stencil(mesh, vertex, false, mesh.vertex_count() + ne)?;
    Ok(split_with(mesh, vertex_points, |h, t| {
        let (a, b) = (p[cv[h] as usize], p[cv[t] as usize]);
        let (c, d) = (p[cv[prev3(h)] as usize], p[cv[prev3(t)] as usize]);
        let mut e = [0.0; 3];
        for k in 0..3 {
            e[k] = 0.375 * (a[k] + b[k]) + 0.125 * (c[k] + d[k]);
        }
        e
    }))
}

/// The one-to-four split of a closed triangle mesh (module docs: the index
/// layout of the result) with the given vertex points (indices `0..V`,
/// capacity for `V + E`) and the new point `edge_point(h, twin(h))` of the
/// edge of every half-edge `h < twin(h)`: Loop's step and the butterfly
/// schemes' ([`crate::mesh::tri_schemes`]). The caller has checked that the
/// mesh is all triangles and that the result fits the index range.
pub(crate) fn split_with(
    mesh: &Mesh,
    vertex_points: Vec<[f64; 3]>,
    mut edge_point: impl FnMut(usize, usize) -> [f64; 3],
) -> Mesh {
    let h_count = mesh.half_edge_count();
    let nv = mesh.vertex_count();
    let nf = mesh.face_count();
    let ne = h_count / 2;
    let cv = &mesh.corner_vertex;
    let mut positions = vertex_points;
    let mut vertex_out: Vec<u32> = Vec::with_capacity(nv + ne);
    vertex_out.extend(mesh.vertex_out.iter().map(|&h| tri(h as usize) as u32));
    // edge_vertex[h] = the new vertex of the edge of h (both half-edges).
    let mut edge_vertex = vec![0u32; h_count];
    for h in 0..h_count {
        let t = mesh.twin[h] as usize;
        if h < t {
            let id = positions.len() as u32;
            edge_vertex[h] = id;
            edge_vertex[t] = id;
            positions.push(edge_point(h, t));
            // E(h) -> E(prev h) is the second corner of h's corner triangle.
            vertex_out.push((tri(h) + 1) as u32);
        }
    }
    debug_assert_eq!(positions.len(), nv + ne);

    let hn = 4 * h_count;
    let mut corner_vertex = vec![0u32; hn];
    let mut twin = vec![0u32; hn];
    for f in 0..nf {
        let middle = 3 * (4 * f + 3);
        for k in 0..3 {
            let h = 3 * f + k;
            let t = tri(h);
            let pk = (k + 2) % 3;
            // corner triangle [origin(h), E(h), E(prev h)]
            corner_vertex[t] = cv[h];
            corner_vertex[t + 1] = edge_vertex[h];
            corner_vertex[t + 2] = edge_vertex[3 * f + pk];
            // middle triangle: corner k is E(h_k), its half-edge E(h_k) -> E(h_{k+1})
            corner_vertex[middle + k] = edge_vertex[h];
            // E(h) -> E(prev h) against the middle's E(h_{k-1}) -> E(h_k)
            twin[t + 1] = (middle + pk) as u32;
            twin[middle + pk] = (t + 1) as u32;
            // origin(h) -> E(h): the first half of h; its twin E(h) -> origin(h)
            // is the last corner of the corner triangle of next(twin(h)).
            let th = mesh.twin[h] as usize;
            twin[t] = (tri(next3(th)) + 2) as u32;
            // E(prev h) -> origin(h): its twin is the first corner of the
            // corner triangle of twin(prev h).
            let tp = mesh.twin[prev3(h)] as usize;
            twin[t + 2] = tri(tp) as u32;
        }
    }
    let corner_face: Vec<u32> = (0..hn).map(|c| (c / 3) as u32).collect();
    let face_start: Vec<u32> = (0..=4 * nf).map(|f| (3 * f) as u32).collect();
    Mesh {
        positions,
        face_start,
        corner_vertex,
        corner_face,
        twin,
        vertex_out,
        knots: vec![1.0; hn],
    }
}

/// `levels` steps of [`refine`]. The size of the final mesh is checked
/// before the first level is refined.
pub fn refine_levels(mesh: &Mesh, levels: usize) -> Result<Mesh, MeshError> {
    check_triangles(mesh, "Loop refinement")?;
    let needed = half_edges_after(mesh, levels);
    if needed > MAX_HALF_EDGES {
        return Err(MeshError::TooLarge {
            half_edges: needed,
            max: MAX_HALF_EDGES,
        });
    }
    let mut m = mesh.clone();
    for _ in 0..levels {
        m = refine(&m)?;
    }
    Ok(m)
}

/// Limit positions of every vertex of a closed triangle mesh by the
/// closed-form stencil `(1 - n chi_n) v + chi_n sum e_i`,
/// `chi_n = 1 / (3 / (8 beta_n) + n)` (module docs), indexed like the
/// vertices.
///
/// ```
/// use subdiv_lab::mesh::generators;
/// use subdiv_lab::mesh::loop_subdivision::limit_positions;
/// // a regular tetrahedron: every limit point lies on the way to the centre
/// let lim = limit_positions(&generators::tetrahedron()).unwrap();
/// assert_eq!(lim.len(), 4);
/// ```
pub fn limit_positions(mesh: &Mesh) -> Result<Vec<[f64; 3]>, MeshError> {
    limit_positions_with(mesh, &LoopVertexRule)
}

/// Limit positions of every vertex of a closed triangle mesh by the limit
/// stencil `l_v v + l_e sum e_i` of `vertex` ([`VertexRule::limit_weights`];
/// [`limit_positions`] for Loop's own).
pub fn limit_positions_with(
    mesh: &Mesh,
    vertex: &dyn VertexRule,
) -> Result<Vec<[f64; 3]>, MeshError> {
    check_triangles(mesh, "the Loop limit stencil")?;
    one_ring_stencil(mesh, vertex, true, 0)
}

/// The mesh with every vertex moved to its limit position ([`limit_positions`]).
pub fn limit_mesh(mesh: &Mesh) -> Result<Mesh, MeshError> {
    let mut m = mesh.clone();
    m.set_positions(limit_positions(mesh)?)?;
    Ok(m)
}

/// Vertex, edge and face counts after `levels` Loop steps of a triangle mesh
/// with the given counts: `V' = V + E`, `E' = 2E + 3F`, `F' = 4F`
/// (saturating).
pub fn counts_after(vertices: u64, edges: u64, faces: u64, levels: usize) -> (u64, u64, u64) {
    let (mut v, mut e, mut f) = (vertices, edges, faces);
    for _ in 0..levels {
        (v, e, f) = (
            v.saturating_add(e),
            e.saturating_mul(2).saturating_add(f.saturating_mul(3)),
            f.saturating_mul(4),
        );
    }
    (v, e, f)
}

/// Number of half-edges after `levels` Loop steps: `4^levels H`, saturating
/// (the same growth as the other schemes' steps,
/// [`crate::mesh::refine::half_edges_after`]); lets callers refuse a request
/// before allocating.
pub fn half_edges_after(mesh: &Mesh, levels: usize) -> u64 {
    crate::mesh::refine::half_edges_after(mesh, levels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generators;

    #[test]
    fn closed_form_limit_weights_at_valence_6_are_half_and_twelfth() {
        let (wv, we) = limit_weights(6);
        assert!((wv - 0.5).abs() < 1e-15 && (we - 1.0 / 12.0).abs() < 1e-16);
        let (wv, we) = vertex_weights(6);
        assert!((wv - 0.625).abs() < 1e-15 && (we - 0.0625).abs() < 1e-16);
        // valence 3: beta = 3/16
        let (wv, we) = vertex_weights(3);
        assert!((wv - 7.0 / 16.0).abs() < 1e-15 && (we - 3.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn corner_triangle_index() {
        for h in 0..30 {
            assert_eq!(tri(h) / 3, 4 * (h / 3) + h % 3);
            assert_eq!(next3(prev3(h)), h);
        }
    }

    #[test]
    fn counts_after_saturate() {
        assert_eq!(counts_after(12, 30, 20, 1), (42, 120, 80));
        let (v, e, f) = counts_after(12, 30, 20, 200);
        assert_eq!((v, e, f), (u64::MAX, u64::MAX, u64::MAX));
        let ico = generators::icosahedron();
        assert_eq!(half_edges_after(&ico, 2), 60 * 16);
    }
}

/// Loop's mesh rules ([`refine`], [`limit_mesh`]) behind
/// [`MeshRules`](crate::mesh::rules::MeshRules), or Loop's edge rule with
/// another vertex rule ([`refine_with`], [`limit_positions_with`]; a scheme
/// file's, [`crate::mesh::user`]).
#[derive(Clone, Debug, Default)]
pub struct LoopRules {
    vertex: Option<(String, Arc<dyn VertexRule>)>,
}

impl LoopRules {
    /// Loop's edge rule with the vertex rule `vertex` (named `name` in
    /// messages).
    pub fn with_vertex_rule(name: &str, vertex: Arc<dyn VertexRule>) -> Self {
        LoopRules {
            vertex: Some((name.to_owned(), vertex)),
        }
    }
}

impl crate::mesh::rules::MeshRules for LoopRules {
    fn name(&self) -> &str {
        match &self.vertex {
            None => "loop",
            Some((name, _)) => name,
        }
    }

    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        match &self.vertex {
            None => refine(mesh),
            Some((_, rule)) => refine_with(mesh, rule.as_ref()),
        }
    }

    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        let positions = match &self.vertex {
            None => limit_positions(mesh)?,
            Some((_, rule)) => limit_positions_with(mesh, rule.as_ref())?,
        };
        let mut m = mesh.clone();
        m.set_positions(positions)?;
        Ok(m)
    }

    /// Loop with its own vertex rule only: the sharp-feature masks are Loop's.
    fn sharp_scheme(&self) -> Option<crate::mesh::sharp::rules::SdcScheme> {
        self.vertex
            .is_none()
            .then_some(crate::mesh::sharp::rules::SdcScheme::Loop)
    }
}
