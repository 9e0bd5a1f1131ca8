//! Refinement of closed triangle meshes by the butterfly scheme, the
//! modified butterfly scheme and Kobbelt's sqrt(3) scheme (math doc section
//! 20), with the stencils of [`crate::schemes::butterfly`],
//! [`crate::schemes::modified_butterfly`] and [`crate::schemes::sqrt3`]
//! applied through the same neighbourhood trait as their local matrices
//! ([`TriNeighbourhood`]).
//!
//! * **butterfly, modified butterfly**: every old vertex keeps its position
//!   and index, every edge gets one new point, every triangle is cut into
//!   four: the index layout of Loop's step
//!   ([`crate::mesh::loop_subdivision`]). The limit position of a vertex is
//!   the vertex itself (interpolatory schemes).
//! * **sqrt3**: vertex `v < V` is the moved old vertex
//!   `(1 - alpha_n) v + alpha_n / n sum e_i`, vertex `V + f` the centroid of
//!   old face `f`; old half-edge `h` (from `a`, in face `f`, its twin in face
//!   `g`) becomes face `h`, the triangle `(a, V + g, V + f)` (the flipped
//!   edge), so `F' = 3F`. The limit position of a vertex is `(1 - beta) v + beta / n
//!   sum e_i` with `beta = 3 alpha_n / (1 + 3 alpha_n)` (math doc section 21).
//!
//! ```
//! use subdiv_lab::mesh::{generators, rules::MeshRules};
//! use subdiv_lab::mesh::tri_schemes::TriRules;
//! use subdiv_lab::schemes::SchemeKind;
//! let ico = generators::icosahedron();
//! let mb = TriRules::new(SchemeKind::ModifiedButterfly).unwrap();
//! let once = mb.refine(&ico).unwrap();
//! assert_eq!(once.face_count(), 80);
//! assert_eq!(once.positions()[3], ico.positions()[3]); // interpolatory
//! let s3 = TriRules::new(SchemeKind::Sqrt3).unwrap();
//! assert_eq!(s3.refine(&ico).unwrap().face_count(), 60);
//! ```

use super::loop_subdivision::{check_triangles, split_with};
use super::rules::MeshRules;
use super::{Mesh, MeshError, MAX_HALF_EDGES};
use crate::schemes::tri_rings::{butterfly_edge, TriNeighbourhood};
use crate::schemes::{modified_butterfly, sqrt3, SchemeKind};

/// The counter-clockwise neighbours of every vertex of a closed triangle
/// mesh (compressed rows), and the position of every half-edge's target
/// among its origin's neighbours.
struct Neighbours {
    start: Vec<usize>,
    list: Vec<u32>,
    /// `position[h]`: index of `target(h)` among the neighbours of `origin(h)`.
    position: Vec<u32>,
}

impl Neighbours {
    fn of(mesh: &Mesh) -> Neighbours {
        let nv = mesh.vertex_count();
        let mut start = Vec::with_capacity(nv + 1);
        let mut list = Vec::with_capacity(mesh.half_edge_count());
        let mut position = vec![0u32; mesh.half_edge_count()];
        for v in 0..nv {
            start.push(list.len());
            let first = mesh.vertex_half_edge(v);
            let mut h = first;
            let mut k = 0u32;
            loop {
                list.push(mesh.corner_vertex[mesh.next(h)]);
                position[h] = k;
                k += 1;
                h = mesh.rotate(h);
                if h == first {
                    break;
                }
            }
        }
        start.push(list.len());
        Neighbours {
            start,
            list,
            position,
        }
    }
}

impl TriNeighbourhood for Neighbours {
    fn valence(&self, p: usize) -> usize {
        self.start[p + 1] - self.start[p]
    }

    fn neighbour(&self, p: usize, k: usize) -> usize {
        self.list[self.start[p] + k % self.valence(p)] as usize
    }
}

/// `sum w_i p_i` over a stencil.
fn combine(positions: &[[f64; 3]], stencil: &[(usize, f64)]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for &(q, w) in stencil {
        let p = positions[q];
        for k in 0..3 {
            out[k] += w * p[k];
        }
    }
    out
}

/// The weights of the modified butterfly by valence, each computed once.
struct WeightCache(Vec<Option<Vec<f64>>>);

impl WeightCache {
    fn get(&mut self, k: usize) -> crate::Result<Vec<f64>> {
        if self.0.len() <= k {
            self.0.resize(k + 1, None);
        }
        if let Some(w) = &self.0[k] {
            return Ok(w.clone());
        }
        let w = modified_butterfly::extraordinary_weights::<f64>(k)?;
        self.0[k] = Some(w.clone());
        Ok(w)
    }
}

/// One step of the butterfly (`modified = false`) or modified butterfly
/// scheme on a closed triangle mesh (module docs).
fn refine_butterfly(mesh: &Mesh, modified: bool, what: &'static str) -> Result<Mesh, MeshError> {
    check_triangles(mesh, what)?;
    super::quadrupled_half_edges(mesh)?;
    let nb = Neighbours::of(mesh);
    let p = &mesh.positions;
    let mut vertex_points = Vec::with_capacity(mesh.vertex_count() + mesh.half_edge_count() / 2);
    vertex_points.extend_from_slice(p);
    let mut cache = WeightCache(Vec::new());
    let mut failure: Option<crate::Error> = None;
    let out = split_with(mesh, vertex_points, |h, t| {
        let (a, b) = (mesh.origin(h), mesh.origin(t));
        let (ta, tb) = (nb.position[h] as usize, nb.position[t] as usize);
        let stencil = if modified {
            match modified_butterfly::edge(&nb, (a, ta), (b, tb), &mut |k| cache.get(k)) {
                Ok(s) => s,
                Err(e) => {
                    failure.get_or_insert(e);
                    return [0.0; 3];
                }
            }
        } else {
            butterfly_edge(&nb, a, ta, b, tb)
        };
        combine(p, &stencil)
    });
    match failure {
        Some(e) => Err(MeshError::from(e)),
        None => Ok(out),
    }
}

/// One sqrt(3) step on a closed triangle mesh (module docs).
fn refine_sqrt3(mesh: &Mesh) -> Result<Mesh, MeshError> {
    check_triangles(mesh, "sqrt3 refinement")?;
    let h = mesh.half_edge_count();
    if 3 * h as u64 > MAX_HALF_EDGES {
        return Err(MeshError::TooLarge {
            half_edges: 3 * h as u64,
            max: MAX_HALF_EDGES,
        });
    }
    let nb = Neighbours::of(mesh);
    let p = &mesh.positions;
    let nv = mesh.vertex_count();
    let nf = mesh.face_count();
    let mut positions = Vec::with_capacity(nv + nf);
    let mut alphas: Vec<Option<f64>> = Vec::new();
    for v in 0..nv {
        let n = nb.valence(v);
        if alphas.len() <= n {
            alphas.resize(n + 1, None);
        }
        let a = match alphas[n] {
            Some(a) => a,
            None => {
                let a = sqrt3::alpha::<f64>(n).map_err(MeshError::from)?;
                alphas[n] = Some(a);
                a
            }
        };
        positions.push(combine(p, &sqrt3::vertex_stencil(&nb, v, a)));
    }
    for f in 0..nf {
        let third = 1.0 / 3.0;
        let st: Vec<(usize, f64)> = mesh.face_vertices(f).map(|v| (v, third)).collect();
        positions.push(combine(p, &st));
    }
    // Triangle `e` (corners 3e..3e+3) of old half-edge `e` (from `a`, in face
    // `f`, its twin in face `g`): `a -> V+g -> V+f`. Its twins: `a -> V+g`
    // against corner 2 of `next(twin(e))` (also from `a`, in `g`); `V+g ->
    // V+f` against corner 1 of `twin(e)`; `V+f -> a` against corner 0 of
    // `twin(prev(e))`.
    let hn = 3 * h;
    let mut corner_vertex = vec![0u32; hn];
    let mut twin = vec![0u32; hn];
    for e in 0..h {
        let t = mesh.twin(e);
        corner_vertex[3 * e] = mesh.corner_vertex[e];
        corner_vertex[3 * e + 1] = (nv + mesh.face_of(t)) as u32;
        corner_vertex[3 * e + 2] = (nv + mesh.face_of(e)) as u32;
        twin[3 * e] = (3 * mesh.next(t) + 2) as u32;
        twin[3 * e + 1] = (3 * t + 1) as u32;
        twin[3 * e + 2] = (3 * mesh.twin(mesh.prev(e))) as u32;
    }
    let mut vertex_out: Vec<u32> = mesh.vertex_out.iter().map(|&e| 3 * e).collect();
    vertex_out.extend((0..nf).map(|f| (3 * mesh.twin(mesh.face_start[f] as usize) + 1) as u32));
    Ok(Mesh {
        positions,
        face_start: (0..=h).map(|e| (3 * e) as u32).collect(),
        corner_vertex,
        corner_face: (0..hn).map(|c| (c / 3) as u32).collect(),
        twin,
        vertex_out,
        knots: vec![1.0; hn],
    })
}

/// The sqrt(3) limit position of every vertex: `(1 - beta) v + beta / n sum
/// e_i` (module docs).
fn sqrt3_limit_positions(mesh: &Mesh) -> Result<Vec<[f64; 3]>, MeshError> {
    check_triangles(mesh, "the sqrt3 limit stencil")?;
    let nb = Neighbours::of(mesh);
    (0..mesh.vertex_count())
        .map(|v| {
            let n = nb.valence(v);
            let (wv, we) = sqrt3::limit_vertex_weights(n).map_err(MeshError::from)?;
            let mut st = vec![(v, wv)];
            st.extend((0..n).map(|k| (nb.neighbour(v, k), we)));
            Ok(combine(&mesh.positions, &st))
        })
        .collect()
}

/// The mesh rules of sqrt3, butterfly or modified butterfly (closed triangle
/// meshes without tags).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriRules(SchemeKind);

impl TriRules {
    /// The rules of `kind`, one of the three schemes
    /// ([`MeshError::UnsupportedScheme`] otherwise).
    pub fn new(kind: SchemeKind) -> Result<TriRules, MeshError> {
        if kind.is_triangle_lattice_scheme() {
            Ok(TriRules(kind))
        } else {
            Err(MeshError::UnsupportedScheme(kind.name().to_owned()))
        }
    }
}

impl MeshRules for TriRules {
    fn name(&self) -> &str {
        self.0.name()
    }

    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        match self.0 {
            SchemeKind::Butterfly => refine_butterfly(mesh, false, "butterfly refinement"),
            SchemeKind::ModifiedButterfly => {
                refine_butterfly(mesh, true, "modified butterfly refinement")
            }
            _ => refine_sqrt3(mesh),
        }
    }

    /// Interpolatory schemes: the mesh itself (every vertex is its own limit
    /// point). sqrt3: its limit stencil.
    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        let mut m = mesh.clone();
        match self.0 {
            SchemeKind::Sqrt3 => m.set_positions(sqrt3_limit_positions(mesh)?)?,
            _ => check_triangles(mesh, "the limit of an interpolatory scheme")?,
        }
        Ok(m)
    }

    /// sqrt3 triples the half-edges per step, the butterfly schemes
    /// quadruple them.
    fn half_edges_after(&self, mesh: &Mesh, levels: usize) -> u64 {
        let factor = if self.0 == SchemeKind::Sqrt3 { 3 } else { 4 };
        let mut h = mesh.half_edge_count() as u64;
        for _ in 0..levels.min(64) {
            h = h.saturating_mul(factor);
        }
        h
    }
}
