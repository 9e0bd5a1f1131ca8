//! Mesh-level refinement for the Catmull-Clark family: Catmull-Clark and the
//! shape-adjustable scheme with parameter `c` (math doc sections 6 and 8; the
//! rules and their **\[reconstructed\]** status are documented in
//! [`crate::schemes::catmull_clark`]).
//!
//! One step on a closed polygon mesh (quads and n-gons in, all quads out):
//!
//! ```text
//! f' = centroid of the face
//! e' = (1 - c)(v + e)/2 + c (f'_1 + f'_2)/2
//! v' = ( 4 c^2 Q + 8 c (1 - c) R + (n - 4 c (2 - c)) v ) / n
//! ```
//!
//! with `Q` the mean of the new face points around `v` and `R` the mean of the
//! edge midpoints `(v + e_i)/2`; at `c = 1/2` these are Catmull-Clark's
//! `e' = (v + e + f'_1 + f'_2)/4`, `v' = (Q + 2R + (n - 3)v)/n`.
//!
//! Index layout of the result: vertices `[old vertices (V), edge points (E, in
//! order of first half-edge), face points (F)]`; one quad
//! `[v', e'(h), f', e'(prev h)]` per old corner `h`, in corner order (so the
//! orientation is kept). Knot intervals of the result are all 1 (the family
//! has none).
//!
//! ```
//! use subdiv_lab::mesh::{catmull_clark::refine_cc, generators};
//! let cube = generators::cube();
//! let once = refine_cc(&cube, 0.5).unwrap();
//! assert_eq!((once.face_count(), once.vertex_count()), (24, 26));
//! ```

use super::rules::{ValenceCache, VertexRule};
use super::{Mesh, MeshError};
use std::sync::Arc;

fn check_c(c: f64) -> Result<(), MeshError> {
    if (0.0..=1.0).contains(&c) {
        Ok(())
    } else {
        Err(MeshError::InvalidShapeParameter(c))
    }
}

fn add(a: &mut [f64; 3], b: &[f64; 3], w: f64) {
    for k in 0..3 {
        a[k] += w * b[k];
    }
}

/// Edge index of every half-edge (`0..E`, in order of the first half-edge of
/// each edge).
fn edge_ids(mesh: &Mesh) -> (Vec<u32>, usize) {
    let hc = mesh.half_edge_count();
    let mut id = vec![u32::MAX; hc];
    let mut next = 0u32;
    for h in 0..hc {
        if id[h] == u32::MAX {
            id[h] = next;
            id[mesh.twin(h)] = next;
            next += 1;
        }
    }
    (id, next as usize)
}

/// One step of the shape-adjustable Catmull-Clark scheme with parameter `c`
/// in `[0, 1]` (`c = 1/2` is Catmull-Clark).
pub fn refine_cc(mesh: &Mesh, c: f64) -> Result<Mesh, MeshError> {
    check_c(c)?;
    refine_quads(mesh, c, &ShapeRule(c))
}

/// The vertex rule of the shape-adjustable scheme at `c` (module docs):
/// `w_v = (n - 4 c (2 - c)) / n`, `w_R = 8 c (1 - c) / n`, `w_Q = 4 c^2 / n`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ShapeRule(f64);

impl VertexRule for ShapeRule {
    fn refine_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let (c, n) = (self.0, n as f64);
        let (wq, wr) = (4.0 * c * c / n, 8.0 * c * (1.0 - c) / n);
        let wv = (n - 4.0 * c * (2.0 - c)) / n;
        Ok([wv, wr, wq])
    }

    fn limit_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let (c, n) = (self.0, n as f64);
        let den = n * (n + 8.0 * c + 4.0 * c * c);
        Ok([n * n / den, 8.0 * c / den, 4.0 * c * c / den])
    }
}

/// One step of a Catmull-Clark-type scheme: the shape-adjustable edge rule
/// at `c` and face centroids (module docs), and the vertex point
/// `v' = w_v v + w_R R + w_Q Q` with the weights `vertex` gives at each
/// valence ([`VertexRule::refine_weights`]). [`refine_cc`] is this with the
/// shape-adjustable vertex rule; a scheme file's rule enters here too
/// ([`crate::mesh::user`]).
pub fn refine_quads(mesh: &Mesh, c: f64, vertex: &dyn VertexRule) -> Result<Mesh, MeshError> {
    check_c(c)?;
    let hc = mesh.half_edge_count();
    crate::mesh::quadrupled_half_edges(mesh)?;
    let (nv, nf) = (mesh.vertex_count(), mesh.face_count());
    let (eid, ne) = edge_ids(mesh);
    let p = mesh.positions();
    // Face points.
    let mut fp = vec![[0.0f64; 3]; nf];
    for (f, out) in fp.iter_mut().enumerate() {
        let n = mesh.face_size(f) as f64;
        for v in mesh.face_vertices(f) {
            add(out, &p[v], 1.0 / n);
        }
    }
    // Edge points.
    let mut ep = vec![[0.0f64; 3]; ne];
    let mut done = vec![false; ne];
    for h in 0..hc {
        let e = eid[h] as usize;
        if done[e] {
            continue;
        }
        done[e] = true;
        let (a, b) = (mesh.origin(h), mesh.target(h));
        let (f1, f2) = (mesh.face_of(h), mesh.face_of(mesh.twin(h)));
        let out = &mut ep[e];
        add(out, &p[a], 0.5 * (1.0 - c));
        add(out, &p[b], 0.5 * (1.0 - c));
        add(out, &fp[f1], 0.5 * c);
        add(out, &fp[f2], 0.5 * c);
    }
    // Vertex points.
    let mut weights = ValenceCache::new(vertex, false);
    let mut vp = vec![[0.0f64; 3]; nv];
    for (v, out) in vp.iter_mut().enumerate() {
        let ring = mesh.vertex_ring(v);
        let [wv, wr, wq] = weights.get(ring.len())?;
        let n = ring.len() as f64;
        add(out, &p[v], wv);
        for &h in &ring {
            add(out, &fp[mesh.face_of(h)], wq / n);
            // R: mean of (v + e_i)/2.
            add(out, &p[v], 0.5 * wr / n);
            add(out, &p[mesh.target(h)], 0.5 * wr / n);
        }
    }
    let mut positions = vp;
    positions.extend(ep);
    positions.extend(fp);
    let mut faces: Vec<[usize; 4]> = Vec::with_capacity(hc);
    for h in 0..hc {
        faces.push([
            mesh.origin(h),
            nv + eid[h] as usize,
            nv + ne + mesh.face_of(h),
            nv + eid[mesh.prev(h)] as usize,
        ]);
    }
    Mesh::from_polygons(positions, &faces)
}

/// `levels` steps of [`refine_cc`].
pub fn refine_cc_levels(mesh: &Mesh, c: f64, levels: usize) -> Result<Mesh, MeshError> {
    let mut m = mesh.clone();
    for _ in 0..levels {
        m = refine_cc(&m, c)?;
    }
    Ok(m)
}

/// Limit positions of the vertices of an all-quad mesh:
/// `(n^2 v + 8c sum e_i + 4c^2 sum f_i) / (n (n + 8c + 4c^2))` over the
/// vertex's one-ring (the left eigenvector for 1 of the one-ring matrix;
/// [`crate::schemes::catmull_clark::limit::limit_stencil`]; at `c = 1/2`
/// Halstead, Kass and DeRose's `(n^2 v + 4 sum e + sum f)/(n (n + 5))`).
/// Refine once first for meshes with other faces.
pub fn limit_positions(mesh: &Mesh, c: f64) -> Result<Vec<[f64; 3]>, MeshError> {
    check_c(c)?;
    limit_positions_with(mesh, &ShapeRule(c))
}

/// Limit positions of the vertices of an all-quad mesh by the stencil
/// `l_v v + l_e sum e_i + l_f sum f_i` that `vertex` gives at each valence
/// ([`VertexRule::limit_weights`]; [`limit_positions`] for the
/// shape-adjustable rule).
pub fn limit_positions_with(
    mesh: &Mesh,
    vertex: &dyn VertexRule,
) -> Result<Vec<[f64; 3]>, MeshError> {
    if let Some(f) = (0..mesh.face_count()).find(|&f| mesh.face_size(f) != 4) {
        return Err(MeshError::NotAllQuads {
            face: f,
            corners: mesh.face_size(f),
            operation: "the Catmull-Clark limit stencil",
        });
    }
    let p = mesh.positions();
    let mut weights = ValenceCache::new(vertex, true);
    (0..mesh.vertex_count())
        .map(|v| {
            let ring = mesh.vertex_ring(v);
            let [lv, le, lf] = weights.get(ring.len())?;
            let mut out = [0.0; 3];
            add(&mut out, &p[v], lv);
            for &h in &ring {
                add(&mut out, &p[mesh.target(h)], le);
                // Far corner of the quad of h: two steps along the face.
                let far = mesh.target(mesh.next(h));
                add(&mut out, &p[far], lf);
            }
            Ok(out)
        })
        .collect()
}

/// The mesh with every vertex moved to its limit position ([`limit_positions`]).
pub fn limit_mesh_cc(mesh: &Mesh, c: f64) -> Result<Mesh, MeshError> {
    let mut m = mesh.clone();
    m.set_positions(limit_positions(mesh, c)?)?;
    Ok(m)
}

/// The Catmull-Clark family's mesh rules ([`refine_cc`], [`limit_mesh_cc`])
/// at shape parameter `c` (`1/2`: Catmull-Clark), or Catmull-Clark's edge and
/// face rules with another vertex rule ([`refine_quads`],
/// [`limit_positions_with`]; a scheme file's, [`crate::mesh::user`]).
#[derive(Clone, Debug)]
pub struct CatmullClarkRules {
    name: String,
    c: f64,
    vertex: Option<Arc<dyn VertexRule>>,
}

impl CatmullClarkRules {
    /// The rules at `c` in `[0, 1]` (named `name` in messages).
    pub fn new(name: &str, c: f64) -> Result<Self, MeshError> {
        check_c(c)?;
        Ok(CatmullClarkRules {
            name: name.to_owned(),
            c,
            vertex: None,
        })
    }

    /// Catmull-Clark's edge and face rules (`c = 1/2`) with the vertex rule
    /// `vertex` (named `name` in messages).
    pub fn with_vertex_rule(name: &str, vertex: Arc<dyn VertexRule>) -> Self {
        CatmullClarkRules {
            name: name.to_owned(),
            c: 0.5,
            vertex: Some(vertex),
        }
    }
}

impl super::rules::MeshRules for CatmullClarkRules {
    fn name(&self) -> &str {
        &self.name
    }

    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        match &self.vertex {
            None => refine_cc(mesh, self.c),
            Some(rule) => refine_quads(mesh, self.c, rule.as_ref()),
        }
    }

    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        let positions = match &self.vertex {
            None => limit_positions(mesh, self.c)?,
            Some(rule) => limit_positions_with(mesh, rule.as_ref())?,
        };
        let mut m = mesh.clone();
        m.set_positions(positions)?;
        Ok(m)
    }

    /// Catmull-Clark (`c = 1/2` with its own vertex rule) only: the
    /// sharp-feature masks are Catmull-Clark's.
    fn sharp_scheme(&self) -> Option<super::sharp::rules::SdcScheme> {
        (self.c == 0.5 && self.vertex.is_none())
            .then_some(super::sharp::rules::SdcScheme::CatmullClark)
    }
}
