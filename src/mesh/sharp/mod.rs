//! Open manifold polygon meshes with sharp and semi-sharp edges and
//! vertices, refined by Catmull-Clark or Loop with OpenSubdiv's Sdc
//! semantics (math doc section 17).
//!
//! [`SharpMesh`] holds the topology (faces, edges, their faces, the edges
//! and faces around every vertex), the per-edge and per-vertex sharpness
//! (`f32`, OpenSubdiv's precision) and the hole flag of every face.
//! Boundaries are allowed; non-manifold edges and vertices are not.
//! Submodules: [`rules`] (vertex rules, sharpness decay, masks), [`tags`]
//! (OpenSubdiv's `t crease` / `t corner` lines), [`refine`] (one level),
//! [`limit`] (limit positions).
//!
//! Index layout of a refined mesh (as the closed refiners):
//! Catmull-Clark `[vertex points, edge points, face points]` with one quad
//! `[v, e(out), f, e(in)]` per parent corner; Loop `[vertex points, edge
//! points]` with the three corner triangles and then the middle triangle of
//! every parent triangle. Edges are numbered in order of their first corner.
//!
//! ```
//! use subdiv_lab::mesh::sharp::{rules::{Boundary, Creasing, SdcScheme}, SharpMesh};
//! // two quads side by side: an open strip with a boundary all around
//! let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0],
//!              [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [2.0, 1.0, 0.0]];
//! let m = SharpMesh::new(p, &[vec![0, 1, 4, 3], vec![1, 2, 5, 4]], &[], Boundary::EdgeAndCorner).unwrap();
//! assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (6, 7, 2));
//! let r = m.refine(SdcScheme::CatmullClark, Creasing::Uniform).unwrap();
//! assert_eq!((r.vertex_count(), r.face_count()), (6 + 7 + 2, 8));
//! // an infinitely sharp corner does not move
//! assert_eq!(r.positions()[0], [0.0, 0.0, 0.0]);
//! ```

pub mod limit;
pub mod refine;
pub mod rules;
pub mod tags;

use super::MeshError;
use rules::{is_infinite, Boundary, SHARPNESS_INFINITE};
use tags::{Tag, TagTarget};

/// "No face" in [`SharpMesh`]'s edge-face table.
const NONE: u32 = u32::MAX;

/// An open or closed manifold polygon mesh with edge and vertex sharpness.
/// Built only by validation ([`SharpMesh::new`]) or by refinement.
#[derive(Clone, Debug, PartialEq)]
pub struct SharpMesh {
    pub(crate) positions: Vec<[f64; 3]>,
    /// `face_start[f]..face_start[f + 1]` are the corners of face `f`.
    pub(crate) face_start: Vec<u32>,
    /// Vertex of each corner.
    pub(crate) face_verts: Vec<u32>,
    /// Edge from each corner's vertex to the next corner's.
    pub(crate) face_edges: Vec<u32>,
    /// End vertices of each edge (the first corner's direction).
    pub(crate) edge_verts: Vec<[u32; 2]>,
    /// The faces of each edge (second [`NONE`] on a boundary).
    pub(crate) edge_faces: Vec<[u32; 2]>,
    /// `vert_edge_start[v]..vert_edge_start[v + 1]` index `vert_edges`.
    pub(crate) vert_edge_start: Vec<u32>,
    /// Edges around each vertex.
    pub(crate) vert_edges: Vec<u32>,
    /// `vert_face_start[v]..vert_face_start[v + 1]` index `vert_faces`.
    pub(crate) vert_face_start: Vec<u32>,
    /// Faces around each vertex.
    pub(crate) vert_faces: Vec<u32>,
    /// Sharpness of each edge (boundary edges: infinite).
    pub(crate) edge_sharpness: Vec<f32>,
    /// Sharpness of each vertex.
    pub(crate) vertex_sharpness: Vec<f32>,
    /// Faces left out of the output (`--boundary none`).
    pub(crate) hole: Vec<bool>,
}

/// A validated mesh waiting for its tags ([`SharpMeshBuilder::tags`]) and
/// boundary interpolation ([`SharpMeshBuilder::build`]).
#[derive(Clone, Debug)]
pub struct SharpMeshBuilder {
    mesh: SharpMesh,
}

impl SharpMeshBuilder {
    /// Sets the sharpness of the tagged edges and vertices. Errors: a tag
    /// naming no edge ([`MeshError::TagUnknownEdge`]) or vertex
    /// ([`MeshError::TagUnknownVertex`]), an edge or vertex tagged twice in
    /// `tags` ([`MeshError::TagDuplicate`]). A later call overrides the
    /// values of an earlier one.
    pub fn tags(&mut self, tags: &[Tag]) -> Result<(), MeshError> {
        self.mesh.apply_tags(tags)
    }

    /// Whether the mesh has a boundary edge.
    pub fn has_boundary(&self) -> bool {
        self.mesh.has_boundary()
    }

    /// The mesh with boundary interpolation `boundary`: boundary edges get
    /// infinite sharpness; with [`Boundary::EdgeAndCorner`] a boundary
    /// vertex with one face is an infinitely sharp corner; with
    /// [`Boundary::None`] every face at a boundary vertex with a boundary
    /// edge that was not tagged infinitely sharp is a hole.
    pub fn build(mut self, boundary: Boundary) -> SharpMesh {
        self.mesh.apply_boundary(boundary);
        self.mesh
    }
}

/// Topology of a face list: corner edges, edge ends and faces, vertex
/// incidence. Assumes indices already checked.
struct Topology {
    face_edges: Vec<u32>,
    edge_verts: Vec<[u32; 2]>,
    edge_faces: Vec<[u32; 2]>,
    inc: Incidence,
}

/// Pairs the corners of `faces` into edges (bucketed by the smaller end
/// vertex), checking manifold edges and consistent orientation.
fn topology(nv: usize, face_start: &[u32], face_verts: &[u32]) -> Result<Topology, MeshError> {
    let nc = face_verts.len();
    let nf = face_start.len() - 1;
    let mut corner_face = vec![0u32; nc];
    for f in 0..nf {
        for c in face_start[f]..face_start[f + 1] {
            corner_face[c as usize] = f as u32;
        }
    }
    let next = |c: usize| -> usize {
        let f = corner_face[c] as usize;
        if c + 1 == face_start[f + 1] as usize {
            face_start[f] as usize
        } else {
            c + 1
        }
    };
    // Bucket corners by the smaller end vertex of their edge.
    let mut bstart = vec![0u32; nv + 1];
    for c in 0..nc {
        let (a, b) = (face_verts[c], face_verts[next(c)]);
        bstart[a.min(b) as usize + 1] += 1;
    }
    for v in 0..nv {
        bstart[v + 1] += bstart[v];
    }
    let mut fill = bstart.clone();
    let mut bucket = vec![0u32; nc];
    for c in 0..nc {
        let (a, b) = (face_verts[c], face_verts[next(c)]);
        let k = a.min(b) as usize;
        bucket[fill[k] as usize] = c as u32;
        fill[k] += 1;
    }
    // Edges in order of their first corner.
    let mut face_edges = vec![NONE; nc];
    let mut edge_verts: Vec<[u32; 2]> = Vec::with_capacity(nc / 2 + 1);
    let mut edge_faces: Vec<[u32; 2]> = Vec::with_capacity(nc / 2 + 1);
    for c in 0..nc {
        if face_edges[c] != NONE {
            continue;
        }
        let (a, b) = (face_verts[c], face_verts[next(c)]);
        let k = a.min(b) as usize;
        let e = edge_verts.len() as u32;
        face_edges[c] = e;
        let mut faces = [corner_face[c], NONE];
        let mut count = 1;
        for &d in &bucket[bstart[k] as usize..bstart[k + 1] as usize] {
            let d = d as usize;
            if d == c {
                continue;
            }
            let (x, y) = (face_verts[d], face_verts[next(d)]);
            if x.max(y) != a.max(b) {
                continue;
            }
            count += 1;
            if count > 2 {
                // count every face on the edge for the message
                let total = bucket[bstart[k] as usize..bstart[k + 1] as usize]
                    .iter()
                    .filter(|&&d| {
                        let d = d as usize;
                        face_verts[d].max(face_verts[next(d)]) == a.max(b)
                    })
                    .count();
                return Err(MeshError::NonManifoldEdge {
                    u: a.min(b) as usize,
                    v: a.max(b) as usize,
                    faces: total,
                });
            }
            if x == a {
                let (fa, fb) = (corner_face[c] as usize, corner_face[d] as usize);
                return Err(MeshError::InconsistentOrientation {
                    u: a as usize,
                    v: b as usize,
                    face_a: fa.min(fb),
                    face_b: fa.max(fb),
                });
            }
            face_edges[d] = e;
            faces[1] = corner_face[d];
        }
        edge_verts.push([a, b]);
        edge_faces.push(faces);
    }
    let inc = incidence(nv, &edge_verts, face_verts, |c| corner_face[c]);
    Ok(Topology {
        face_edges,
        edge_verts,
        edge_faces,
        inc,
    })
}

/// Vertex incidence: the edges and faces around every vertex.
struct Incidence {
    vert_edge_start: Vec<u32>,
    vert_edges: Vec<u32>,
    vert_face_start: Vec<u32>,
    vert_faces: Vec<u32>,
}

/// The edges around each vertex in edge order and the faces around each
/// vertex in corner order (counting sorts over the edge ends and corners).
fn incidence(
    nv: usize,
    edge_verts: &[[u32; 2]],
    face_verts: &[u32],
    corner_face: impl Fn(usize) -> u32,
) -> Incidence {
    let nc = face_verts.len();
    let ne = edge_verts.len();
    let mut vert_edge_start = vec![0u32; nv + 1];
    for ev in edge_verts {
        vert_edge_start[ev[0] as usize + 1] += 1;
        vert_edge_start[ev[1] as usize + 1] += 1;
    }
    for v in 0..nv {
        vert_edge_start[v + 1] += vert_edge_start[v];
    }
    let mut fill = vert_edge_start.clone();
    let mut vert_edges = vec![0u32; 2 * ne];
    for (e, ev) in edge_verts.iter().enumerate() {
        for &v in ev {
            vert_edges[fill[v as usize] as usize] = e as u32;
            fill[v as usize] += 1;
        }
    }
    let mut vert_face_start = vec![0u32; nv + 1];
    for &v in face_verts {
        vert_face_start[v as usize + 1] += 1;
    }
    for v in 0..nv {
        vert_face_start[v + 1] += vert_face_start[v];
    }
    let mut fill = vert_face_start.clone();
    let mut vert_faces = vec![0u32; nc];
    for c in 0..nc {
        let v = face_verts[c] as usize;
        vert_faces[fill[v] as usize] = corner_face(c);
        fill[v] += 1;
    }
    Incidence {
        vert_edge_start,
        vert_edges,
        vert_face_start,
        vert_faces,
    }
}

impl SharpMesh {
    /// Builds and validates a mesh from positions, faces (0-based vertex
    /// indices, counter-clockwise) and tags, with boundary interpolation
    /// `boundary`: [`SharpMesh::builder`], [`SharpMeshBuilder::tags`],
    /// [`SharpMeshBuilder::build`] in one call.
    pub fn new<F: AsRef<[usize]>>(
        positions: Vec<[f64; 3]>,
        faces: &[F],
        tags: &[Tag],
        boundary: Boundary,
    ) -> Result<SharpMesh, MeshError> {
        let mut b = SharpMesh::builder(positions, faces)?;
        b.tags(tags)?;
        Ok(b.build(boundary))
    }

    /// Validates the topology of a mesh from positions and faces (0-based
    /// vertex indices, counter-clockwise); tags and the boundary
    /// interpolation are added by the returned builder.
    ///
    /// Errors name the offending element: non-finite coordinates, dangling
    /// indices, degenerate faces, non-manifold edges and vertices,
    /// inconsistent orientation, isolated vertices.
    pub fn builder<F: AsRef<[usize]>>(
        positions: Vec<[f64; 3]>,
        faces: &[F],
    ) -> Result<SharpMeshBuilder, MeshError> {
        let (face_start, face_verts) = super::polygon_soup(&positions, faces)?;
        let hole = vec![false; face_start.len() - 1];
        let mut mesh = SharpMesh::assemble(positions, face_start, face_verts, hole)?;
        mesh.check_vertices()?;
        mesh.order_vertex_edges();
        Ok(SharpMeshBuilder { mesh })
    }

    /// The mesh of `positions` and the flattened faces (`face_start`,
    /// `face_verts`, as [`super::polygon_soup`] gives them) with its edge and
    /// vertex topology, `hole` per face, and no sharpness yet.
    fn assemble(
        positions: Vec<[f64; 3]>,
        face_start: Vec<u32>,
        face_verts: Vec<u32>,
        hole: Vec<bool>,
    ) -> Result<SharpMesh, MeshError> {
        let nv = positions.len();
        let t = topology(nv, &face_start, &face_verts)?;
        Ok(SharpMesh::from_parts(
            positions, face_start, face_verts, hole, t,
        ))
    }

    /// The child mesh of a refinement step whose edges are known by
    /// construction: `corner_key[c]` names the edge leaving child corner `c`
    /// among `keys` edge keys (halves of parent edges and edges inside
    /// parent faces, [`refine`]). Edges are numbered in order of their first
    /// corner and the second corner of a key gives the edge's second face,
    /// exactly as [`topology`] numbers them after pairing the corners by
    /// their end vertices, so the mesh equals [`SharpMesh::assemble`]'s
    /// without the search. Every child face has `PER_FACE` corners. Returns
    /// the mesh and the edge of every key.
    pub(super) fn assemble_keyed<const PER_FACE: usize>(
        positions: Vec<[f64; 3]>,
        face_verts: Vec<u32>,
        corner_key: &[u32],
        keys: usize,
        hole: Vec<bool>,
    ) -> (SharpMesh, Vec<u32>) {
        let nc = face_verts.len();
        let nf = nc / PER_FACE;
        let face_start: Vec<u32> = (0..=nf).map(|f| (PER_FACE * f) as u32).collect();
        let corner_face = |c: usize| (c / PER_FACE) as u32;
        let mut edge_of = vec![NONE; keys];
        let mut face_edges = vec![NONE; nc];
        let mut edge_verts: Vec<[u32; 2]> = Vec::with_capacity(nc / 2 + 1);
        let mut edge_faces: Vec<[u32; 2]> = Vec::with_capacity(nc / 2 + 1);
        for c in 0..nc {
            let k = corner_key[c] as usize;
            let f = corner_face(c);
            if edge_of[k] == NONE {
                let next = if (c + 1) % PER_FACE == 0 {
                    c + 1 - PER_FACE
                } else {
                    c + 1
                };
                edge_of[k] = edge_verts.len() as u32;
                edge_verts.push([face_verts[c], face_verts[next]]);
                edge_faces.push([f, NONE]);
            } else {
                edge_faces[edge_of[k] as usize][1] = f;
            }
            face_edges[c] = edge_of[k];
        }
        let inc = incidence(positions.len(), &edge_verts, &face_verts, corner_face);
        let t = Topology {
            face_edges,
            edge_verts,
            edge_faces,
            inc,
        };
        (
            SharpMesh::from_parts(positions, face_start, face_verts, hole, t),
            edge_of,
        )
    }

    /// A mesh from its faces and their topology, without sharpness.
    fn from_parts(
        positions: Vec<[f64; 3]>,
        face_start: Vec<u32>,
        face_verts: Vec<u32>,
        hole: Vec<bool>,
        t: Topology,
    ) -> SharpMesh {
        let (nv, ne) = (positions.len(), t.edge_verts.len());
        SharpMesh {
            positions,
            face_start,
            face_verts,
            face_edges: t.face_edges,
            edge_verts: t.edge_verts,
            edge_faces: t.edge_faces,
            vert_edge_start: t.inc.vert_edge_start,
            vert_edges: t.inc.vert_edges,
            vert_face_start: t.inc.vert_face_start,
            vert_faces: t.inc.vert_faces,
            edge_sharpness: vec![0.0; ne],
            vertex_sharpness: vec![0.0; nv],
            hole,
        }
    }

    /// Refuses isolated vertices and vertices whose faces form more than
    /// one fan (walking around the vertex across its two-face edges).
    fn check_vertices(&self) -> Result<(), MeshError> {
        for v in 0..self.vertex_count() {
            let faces = self.vertex_faces(v);
            if faces.is_empty() {
                return Err(MeshError::IsolatedVertex { vertex: v });
            }
            let edges = self.vertex_edges(v);
            let boundary = edges
                .iter()
                .filter(|&&e| self.edge_faces[e as usize][1] == NONE)
                .count();
            // A single fan: a closed cycle (faces = edges, no boundary) or a
            // path between two boundary edges (faces = edges - 1).
            let manifold_counts = (boundary == 0 && faces.len() == edges.len())
                || (boundary == 2 && faces.len() + 1 == edges.len());
            if !manifold_counts || self.fans(v) != 1 {
                return Err(MeshError::NonManifoldVertex {
                    vertex: v,
                    fans: self.fans(v).max(2),
                });
            }
        }
        Ok(())
    }

    /// Puts the edges around every vertex in rotational order, as
    /// OpenSubdiv does: an interior vertex starts with the edge leaving it
    /// in its first face, a boundary vertex with its boundary edge that
    /// leaves it; each next edge is the one entering the vertex in the face
    /// of the previous one. (Chaikin's average sums sharpness values in this
    /// order, and `f32` sums depend on it.)
    fn order_vertex_edges(&mut self) {
        let mut order: Vec<u32> = Vec::new();
        for v in 0..self.vertex_count() {
            let edges = self.vertex_edges(v);
            let boundary_start = edges.iter().copied().find(|&e| {
                let [a, _] = self.edge_verts[e as usize];
                self.edge_faces[e as usize][1] == NONE && a as usize == v
            });
            let (mut f, mut e) = match boundary_start {
                Some(e) => (self.edge_faces[e as usize][0] as usize, e),
                None => {
                    let f = self.vertex_faces(v)[0] as usize;
                    (f, self.face_edges[self.corner_of(f, v)])
                }
            };
            order.clear();
            order.push(e);
            while order.len() < edges.len() {
                let c = self.corner_of(f, v);
                let (s, t) = (self.face_start[f] as usize, self.face_start[f + 1] as usize);
                let prev = if c == s { t - 1 } else { c - 1 };
                e = self.face_edges[prev];
                order.push(e);
                let [f0, f1] = self.edge_faces[e as usize];
                if f1 == NONE {
                    break;
                }
                f = if f0 as usize == f { f1 } else { f0 } as usize;
            }
            let start = self.vert_edge_start[v] as usize;
            self.vert_edges[start..start + order.len()].copy_from_slice(&order);
        }
    }

    /// The corner of vertex `v` in face `f` (which contains it).
    fn corner_of(&self, f: usize, v: usize) -> usize {
        let s = self.face_start[f] as usize;
        s + self
            .face_vertices(f)
            .iter()
            .position(|&x| x as usize == v)
            .unwrap_or(0)
    }

    /// The number of fans of faces around `v` (faces linked across the
    /// two-face edges at `v`).
    fn fans(&self, v: usize) -> usize {
        let faces = self.vertex_faces(v);
        let edges = self.vertex_edges(v);
        let mut comp: Vec<usize> = (0..faces.len()).collect();
        fn root(c: &mut [usize], mut i: usize) -> usize {
            while c[i] != i {
                c[i] = c[c[i]];
                i = c[i];
            }
            i
        }
        for &e in edges {
            let [f0, f1] = self.edge_faces[e as usize];
            if f1 == NONE {
                continue;
            }
            let (Some(a), Some(b)) = (
                faces.iter().position(|&f| f == f0),
                faces.iter().position(|&f| f == f1),
            ) else {
                continue;
            };
            let (ra, rb) = (root(&mut comp, a), root(&mut comp, b));
            comp[ra] = rb;
        }
        (0..faces.len())
            .filter(|&i| root(&mut comp, i) == i)
            .count()
    }

    fn apply_tags(&mut self, tags: &[Tag]) -> Result<(), MeshError> {
        let mut edge_line = vec![0usize; self.edge_count()];
        let mut vertex_line = vec![0usize; self.vertex_count()];
        for t in tags {
            match t.target {
                TagTarget::Edge(a, b) => {
                    let e = self.find_edge(a, b).ok_or(MeshError::TagUnknownEdge {
                        line: t.line,
                        u: a,
                        v: b,
                    })?;
                    if edge_line[e] != 0 {
                        return Err(MeshError::TagDuplicate {
                            line: t.line,
                            what: format!("edge {a}-{b}"),
                            first_line: edge_line[e],
                        });
                    }
                    edge_line[e] = t.line;
                    self.edge_sharpness[e] = t.sharpness;
                }
                TagTarget::Vertex(v) => {
                    if v >= self.vertex_count() {
                        return Err(MeshError::TagUnknownVertex {
                            line: t.line,
                            vertex: v,
                            vertex_count: self.vertex_count(),
                        });
                    }
                    if vertex_line[v] != 0 {
                        return Err(MeshError::TagDuplicate {
                            line: t.line,
                            what: format!("vertex {v}"),
                            first_line: vertex_line[v],
                        });
                    }
                    vertex_line[v] = t.line;
                    self.vertex_sharpness[v] = t.sharpness;
                }
            }
        }
        Ok(())
    }

    fn apply_boundary(&mut self, boundary: Boundary) {
        if boundary == Boundary::None {
            for v in 0..self.vertex_count() {
                let open = self.vertex_edges(v).iter().any(|&e| {
                    self.edge_faces[e as usize][1] == NONE
                        && !is_infinite(self.edge_sharpness[e as usize])
                });
                if open {
                    let (a, b) = (
                        self.vert_face_start[v] as usize,
                        self.vert_face_start[v + 1] as usize,
                    );
                    for i in a..b {
                        self.hole[self.vert_faces[i] as usize] = true;
                    }
                }
            }
        }
        for e in 0..self.edge_count() {
            if self.edge_faces[e][1] == NONE {
                self.edge_sharpness[e] = SHARPNESS_INFINITE;
            }
        }
        if boundary == Boundary::EdgeAndCorner {
            for v in 0..self.vertex_count() {
                if self.vertex_faces(v).len() == 1 && self.vertex_edges(v).len() == 2 {
                    self.vertex_sharpness[v] = SHARPNESS_INFINITE;
                }
            }
        }
    }

    /// The edge between `a` and `b`, if any.
    pub fn find_edge(&self, a: usize, b: usize) -> Option<usize> {
        if a >= self.vertex_count() || b >= self.vertex_count() {
            return None;
        }
        self.vertex_edges(a).iter().map(|&e| e as usize).find(|&e| {
            let [x, y] = self.edge_verts[e];
            (x as usize == a && y as usize == b) || (x as usize == b && y as usize == a)
        })
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_start.len() - 1
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edge_verts.len()
    }

    /// Number of corners (face-vertex incidences).
    pub fn corner_count(&self) -> usize {
        self.face_verts.len()
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// The vertices of face `f`, counter-clockwise.
    pub fn face_vertices(&self, f: usize) -> &[u32] {
        &self.face_verts[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// The edges around vertex `v`.
    pub fn vertex_edges(&self, v: usize) -> &[u32] {
        &self.vert_edges[self.vert_edge_start[v] as usize..self.vert_edge_start[v + 1] as usize]
    }

    /// The faces around vertex `v`.
    pub fn vertex_faces(&self, v: usize) -> &[u32] {
        &self.vert_faces[self.vert_face_start[v] as usize..self.vert_face_start[v + 1] as usize]
    }

    /// Sharpness of every edge (boundary edges are infinitely sharp).
    pub fn edge_sharpness(&self) -> &[f32] {
        &self.edge_sharpness
    }

    /// End vertices of edge `e`.
    pub fn edge_vertices(&self, e: usize) -> [usize; 2] {
        let [a, b] = self.edge_verts[e];
        [a as usize, b as usize]
    }

    /// Sharpness of every vertex.
    pub fn vertex_sharpness(&self) -> &[f32] {
        &self.vertex_sharpness
    }

    /// Whether face `f` is a hole (left out of the output).
    pub fn is_hole(&self, f: usize) -> bool {
        self.hole[f]
    }

    /// Whether the mesh has a boundary edge.
    pub fn has_boundary(&self) -> bool {
        self.edge_faces.iter().any(|f| f[1] == NONE)
    }

    /// Whether face `f` is not a triangle (for Loop).
    pub(crate) fn first_non_triangle(&self) -> Option<usize> {
        (0..self.face_count()).find(|&f| self.face_start[f + 1] - self.face_start[f] != 3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strip() -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
        ];
        (p, vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]])
    }

    #[test]
    fn boundary_modes_tag_corners_and_holes() {
        let (p, f) = strip();
        let m = SharpMesh::new(p.clone(), &f, &[], Boundary::EdgeOnly).unwrap();
        assert!(m.vertex_sharpness().iter().all(|&s| s == 0.0));
        assert_eq!(m.edge_sharpness().iter().filter(|&&s| s == 10.0).count(), 6);
        let m = SharpMesh::new(p.clone(), &f, &[], Boundary::EdgeAndCorner).unwrap();
        assert_eq!(
            m.vertex_sharpness().iter().filter(|&&s| s == 10.0).count(),
            4
        );
        let m = SharpMesh::new(p, &f, &[], Boundary::None).unwrap();
        assert!(m.is_hole(0) && m.is_hole(1));
    }

    #[test]
    fn bowtie_vertex_is_refused() {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        let e = SharpMesh::new(p, &[vec![0, 1, 2], vec![0, 3, 4]], &[], Boundary::EdgeOnly);
        assert!(matches!(
            e,
            Err(MeshError::NonManifoldVertex { vertex: 0, fans: 2 })
        ));
    }

    #[test]
    fn tags_name_edges_and_vertices() {
        let (p, f) = strip();
        let tag = |target, line| Tag {
            line,
            target,
            sharpness: 2.0,
        };
        let m = SharpMesh::new(
            p.clone(),
            &f,
            &[tag(TagTarget::Edge(4, 1), 3)],
            Boundary::EdgeOnly,
        )
        .unwrap();
        assert_eq!(m.edge_sharpness()[m.find_edge(1, 4).unwrap()], 2.0);
        let e = SharpMesh::new(
            p.clone(),
            &f,
            &[tag(TagTarget::Edge(0, 4), 7)],
            Boundary::EdgeOnly,
        );
        assert!(matches!(e, Err(MeshError::TagUnknownEdge { line: 7, .. })));
        let e = SharpMesh::new(p, &f, &[tag(TagTarget::Vertex(6), 2)], Boundary::EdgeOnly);
        assert!(matches!(
            e,
            Err(MeshError::TagUnknownVertex { line: 2, .. })
        ));
    }
}
