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

use super::{Mesh, MeshError};

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
    let mut vp = vec![[0.0f64; 3]; nv];
    for (v, out) in vp.iter_mut().enumerate() {
        let ring = mesh.vertex_ring(v);
        let n = ring.len() as f64;
        let (wq, wr) = (4.0 * c * c / n, 8.0 * c * (1.0 - c) / n);
        let wv = (n - 4.0 * c * (2.0 - c)) / n;
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
    if let Some(f) = (0..mesh.face_count()).find(|&f| mesh.face_size(f) != 4) {
        return Err(MeshError::NotAllQuads {
            face: f,
            corners: mesh.face_size(f),
            operation: "the Catmull-Clark limit stencil",
        });
    }
    let p = mesh.positions();
    Ok((0..mesh.vertex_count())
        .map(|v| {
            let ring = mesh.vertex_ring(v);
            let n = ring.len() as f64;
            let den = n * (n + 8.0 * c + 4.0 * c * c);
            let mut out = [0.0; 3];
            add(&mut out, &p[v], n * n / den);
            for &h in &ring {
                add(&mut out, &p[mesh.target(h)], 8.0 * c / den);
                // Far corner of the quad of h: two steps along the face.
                let far = mesh.target(mesh.next(h));
                add(&mut out, &p[far], 4.0 * c * c / den);
            }
            out
        })
        .collect())
}

/// The mesh with every vertex moved to its limit position ([`limit_positions`]).
pub fn limit_mesh_cc(mesh: &Mesh, c: f64) -> Result<Mesh, MeshError> {
    let mut m = mesh.clone();
    m.set_positions(limit_positions(mesh, c)?)?;
    Ok(m)
}

/// The Catmull-Clark family's mesh rules ([`refine_cc`], [`limit_mesh_cc`])
/// at shape parameter `c` (`1/2`: Catmull-Clark).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CatmullClarkRules {
    name: &'static str,
    c: f64,
}

impl CatmullClarkRules {
    /// The rules at `c` in `[0, 1]` (named `name` in messages).
    pub fn new(name: &'static str, c: f64) -> Result<Self, MeshError> {
        check_c(c)?;
        Ok(CatmullClarkRules { name, c })
    }
}

impl super::rules::MeshRules for CatmullClarkRules {
    fn name(&self) -> &str {
        self.name
    }

    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        refine_cc(mesh, self.c)
    }

    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        limit_mesh_cc(mesh, self.c)
    }

    /// Catmull-Clark (`c = 1/2`) only.
    fn sharp_scheme(&self) -> Option<super::sharp::rules::SdcScheme> {
        (self.c == 0.5).then_some(super::sharp::rules::SdcScheme::CatmullClark)
    }
}
