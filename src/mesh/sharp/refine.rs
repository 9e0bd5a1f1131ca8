//! One level of Catmull-Clark or Loop refinement of a [`SharpMesh`] with the
//! masks of [`super::rules`] (math doc section 17), and the sharpness of the
//! child edges and vertices. Closed meshes without tags refine to the same
//! points as the closed refiners ([`crate::mesh::catmull_clark`],
//! [`crate::mesh::loop_subdivision`]) up to rounding, with the same
//! index layout.

use super::rules::{self, decrement, edge_weights, is_sharp, Creasing, SdcScheme, VertexMask};
use super::{SharpMesh, NONE};
use crate::mesh::{MeshError, MAX_HALF_EDGES};

fn add(a: &mut [f64; 3], b: &[f64; 3], w: f64) {
    a[0] += w * b[0];
    a[1] += w * b[1];
    a[2] += w * b[2];
}

/// The normal index of a face's corner: `(face, vertex) -> index`.
type CornerNormal<'a> = &'a dyn Fn(usize, usize) -> usize;

impl SharpMesh {
    /// One refinement step with `scheme`'s masks and `creasing`'s
    /// sharpness decay.
    ///
    /// Errors: [`MeshError::NotAllTriangles`] for Loop on a face that is
    /// not a triangle; [`MeshError::TooLarge`] if the result would exceed
    /// the 32-bit index range.
    pub fn refine(&self, scheme: SdcScheme, creasing: Creasing) -> Result<SharpMesh, MeshError> {
        if scheme == SdcScheme::Loop {
            if let Some(f) = self.first_non_triangle() {
                return Err(MeshError::NotAllTriangles {
                    face: f,
                    corners: self.face_vertices(f).len(),
                    operation: "Loop refinement",
                });
            }
        }
        let nc = self.corner_count() as u64;
        if 4 * nc > MAX_HALF_EDGES {
            return Err(MeshError::TooLarge {
                half_edges: 4 * nc,
                max: MAX_HALF_EDGES,
            });
        }
        let (nv, ne, nf) = (self.vertex_count(), self.edge_count(), self.face_count());
        let p = &self.positions;

        // Child sharpness of every edge at each of its ends.
        let mut edge_child = vec![[0.0f32; 2]; ne];
        let mut parent_buf: Vec<f32> = Vec::new();
        let mut child_buf: Vec<f32> = Vec::new();
        let mut vertex_sharp_edges = vec![false; nv];
        for v in 0..nv {
            let edges = self.vertex_edges(v);
            if !edges
                .iter()
                .any(|&e| is_sharp(self.edge_sharpness[e as usize]))
            {
                continue;
            }
            vertex_sharp_edges[v] = true;
            parent_buf.clear();
            parent_buf.extend(edges.iter().map(|&e| self.edge_sharpness[e as usize]));
            child_buf.clear();
            child_buf.resize(edges.len(), 0.0);
            rules::child_edge_sharpness(creasing, &parent_buf, &mut child_buf);
            for (&e, &c) in edges.iter().zip(&child_buf) {
                let end = usize::from(self.edge_verts[e as usize][0] as usize != v);
                edge_child[e as usize][end] = c;
            }
        }

        let face_points = scheme == SdcScheme::CatmullClark;
        let total = nv + ne + if face_points { nf } else { 0 };
        let mut positions = vec![[0.0f64; 3]; total];
        if face_points {
            for f in 0..nf {
                let verts = self.face_vertices(f);
                let w = 1.0 / verts.len() as f64;
                let out = &mut positions[nv + ne + f];
                for &v in verts {
                    add(out, &p[v as usize], w);
                }
            }
        }
        // Edge points.
        for e in 0..ne {
            let [a, b] = self.edge_verts[e];
            let (wv, wf) = edge_weights(scheme, self.edge_sharpness[e], edge_child[e]);
            let mut out = [0.0; 3];
            add(&mut out, &p[a as usize], wv);
            add(&mut out, &p[b as usize], wv);
            if wf != 0.0 {
                for &f in &self.edge_faces[e] {
                    if f == NONE {
                        continue;
                    }
                    let point = if face_points {
                        positions[nv + ne + f as usize]
                    } else {
                        let opposite = self
                            .face_vertices(f as usize)
                            .iter()
                            .copied()
                            .find(|&x| x != a && x != b)
                            .unwrap_or(a);
                        p[opposite as usize]
                    };
                    add(&mut out, &point, wf);
                }
            }
            positions[nv + e] = out;
        }
        // Vertex points.
        let mut mask = VertexMask::default();
        for v in 0..nv {
            let edges = self.vertex_edges(v);
            let faces = self.vertex_faces(v);
            let mut out = [0.0; 3];
            let far = |e: u32| -> usize {
                let [a, b] = self.edge_verts[e as usize];
                if a as usize == v {
                    b as usize
                } else {
                    a as usize
                }
            };
            if !vertex_sharp_edges[v] && !is_sharp(self.vertex_sharpness[v]) {
                let (wv, we, wf) = rules::smooth_vertex_weights(scheme, edges.len());
                add(&mut out, &p[v], wv);
                for &e in edges {
                    add(&mut out, &p[far(e)], we);
                }
                if face_points {
                    for &f in faces {
                        let fp = positions[nv + ne + f as usize];
                        add(&mut out, &fp, wf);
                    }
                }
            } else {
                parent_buf.clear();
                parent_buf.extend(edges.iter().map(|&e| self.edge_sharpness[e as usize]));
                mask.compute(
                    scheme,
                    creasing,
                    self.vertex_sharpness[v],
                    &parent_buf,
                    faces.len(),
                );
                add(&mut out, &p[v], mask.v);
                for (&e, &w) in edges.iter().zip(&mask.edges) {
                    if w != 0.0 {
                        add(&mut out, &p[far(e)], w);
                    }
                }
                if face_points {
                    for (&f, &w) in faces.iter().zip(&mask.faces) {
                        if w != 0.0 {
                            let fp = positions[nv + ne + f as usize];
                            add(&mut out, &fp, w);
                        }
                    }
                }
            }
            positions[v] = out;
        }

        // Child faces, and the key of the edge leaving each child corner:
        // `2 e + end` for the half of parent edge `e` at its end `end`
        // (0: `edge_verts[e][0]`), `2 ne + c` for the edge inside the parent
        // face at parent corner `c` (Catmull-Clark: from the edge point of
        // `c`'s edge to the face point; Loop: between the edge points of
        // `c`'s edge and of the corner before it).
        let half = |e: u32, v: u32| 2 * e + u32::from(self.edge_verts[e as usize][0] != v);
        let inner = |c: usize| (2 * ne + c) as u32;
        let mut face_verts = Vec::with_capacity(4 * nc as usize);
        let mut corner_key = Vec::with_capacity(4 * nc as usize);
        let hole = if face_points {
            let mut hole = Vec::with_capacity(nc as usize);
            for f in 0..nf {
                let (s, t) = (self.face_start[f] as usize, self.face_start[f + 1] as usize);
                for c in s..t {
                    let prev = if c == s { t - 1 } else { c - 1 };
                    let (v, e, ep) = (
                        self.face_verts[c],
                        self.face_edges[c],
                        self.face_edges[prev],
                    );
                    face_verts.extend_from_slice(&[
                        v,
                        (nv + e as usize) as u32,
                        (nv + ne + f) as u32,
                        (nv + ep as usize) as u32,
                    ]);
                    corner_key.extend_from_slice(&[half(e, v), inner(c), inner(prev), half(ep, v)]);
                    hole.push(self.hole[f]);
                }
            }
            hole
        } else {
            let mut hole = Vec::with_capacity(4 * nf);
            for f in 0..nf {
                let s = self.face_start[f] as usize;
                let e = |k: usize| self.face_edges[s + k % 3];
                let ep = |k: usize| (nv + e(k) as usize) as u32;
                for k in 0..3 {
                    let v = self.face_verts[s + k];
                    face_verts.extend_from_slice(&[v, ep(k), ep(k + 2)]);
                    corner_key.extend_from_slice(&[half(e(k), v), inner(s + k), half(e(k + 2), v)]);
                }
                face_verts.extend_from_slice(&[ep(0), ep(1), ep(2)]);
                corner_key.extend_from_slice(&[inner(s + 1), inner(s + 2), inner(s)]);
                hole.extend_from_slice(&[self.hole[f]; 4]);
            }
            hole
        };
        let keys = 2 * ne + nc as usize;
        let (mut child, edge_of) = if face_points {
            SharpMesh::assemble_keyed::<4>(positions, face_verts, &corner_key, keys, hole)
        } else {
            SharpMesh::assemble_keyed::<3>(positions, face_verts, &corner_key, keys, hole)
        };
        // Vertex points keep their parent's rotational edge order.
        for v in 0..nv {
            let start = child.vert_edge_start[v] as usize;
            for (i, &e) in self.vertex_edges(v).iter().enumerate() {
                child.vert_edges[start + i] = edge_of[half(e, v as u32) as usize];
            }
        }
        for e in 0..ne {
            if is_sharp(self.edge_sharpness[e]) {
                for end in 0..2 {
                    child.edge_sharpness[edge_of[2 * e + end] as usize] = edge_child[e][end];
                }
            }
        }
        for v in 0..nv {
            child.vertex_sharpness[v] = decrement(self.vertex_sharpness[v]);
        }
        Ok(child)
    }

    /// `levels` steps of [`refine`](Self::refine); the size of the result
    /// is checked before the first step.
    pub fn refine_levels(
        &self,
        scheme: SdcScheme,
        creasing: Creasing,
        levels: usize,
    ) -> Result<SharpMesh, MeshError> {
        let needed =
            (self.corner_count() as u64).saturating_mul(4u64.saturating_pow(levels as u32));
        if needed > MAX_HALF_EDGES {
            return Err(MeshError::TooLarge {
                half_edges: needed,
                max: MAX_HALF_EDGES,
            });
        }
        let mut m = self.clone();
        for _ in 0..levels {
            m = m.refine(scheme, creasing)?;
        }
        Ok(m)
    }

    /// Writes the mesh as OBJ (`v` lines with round-trip precision, then
    /// the `f` lines of the faces that are not holes, 1-based).
    pub fn write_obj<W: std::io::Write>(&self, out: &mut W) -> std::io::Result<()> {
        self.write_obj_inner(out, None)
    }

    /// The OBJ text with the `vn` lines of `normals` after the `v` lines,
    /// and faces `f v//n` with `n = corner(face, v)` (0-based; written
    /// 1-based). With one normal per vertex, `corner` returns `v`: `f v//v`.
    /// Fewer normals than vertices, or a corner index beyond `normals`, is
    /// an [`std::io::ErrorKind::InvalidInput`] error.
    pub fn write_obj_with_normals<W: std::io::Write>(
        &self,
        out: &mut W,
        normals: &[[f64; 3]],
        corner: impl Fn(usize, usize) -> usize,
    ) -> std::io::Result<()> {
        let invalid = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, m);
        if normals.len() < self.vertex_count() {
            return Err(invalid(format!(
                "{} normals for {} vertices",
                normals.len(),
                self.vertex_count()
            )));
        }
        if let Some((f, v)) = (0..self.face_count())
            .flat_map(|f| self.face_vertices(f).iter().map(move |&v| (f, v as usize)))
            .find(|&(f, v)| corner(f, v) >= normals.len())
        {
            return Err(invalid(format!(
                "the corner of face {f} at vertex {v} names normal {} of {}",
                corner(f, v),
                normals.len()
            )));
        }
        self.write_obj_inner(out, Some((normals, &corner)))
    }

    fn write_obj_inner<W: std::io::Write>(
        &self,
        out: &mut W,
        normals: Option<(&[[f64; 3]], CornerNormal<'_>)>,
    ) -> std::io::Result<()> {
        let kept = (0..self.face_count()).filter(|&f| !self.hole[f]).count();
        writeln!(
            out,
            "# subdiv-lab: {} vertices, {} faces",
            self.vertex_count(),
            kept
        )?;
        for p in &self.positions {
            writeln!(out, "v {:?} {:?} {:?}", p[0], p[1], p[2])?;
        }
        for n in normals.map_or(&[][..], |(n, _)| n) {
            writeln!(out, "vn {:?} {:?} {:?}", n[0], n[1], n[2])?;
        }
        let mut line = String::new();
        for f in 0..self.face_count() {
            if self.hole[f] {
                continue;
            }
            line.clear();
            line.push('f');
            for &v in self.face_vertices(f) {
                use std::fmt::Write as _;
                let _ = if let Some((_, corner)) = normals {
                    write!(line, " {}//{}", v + 1, corner(f, v as usize) + 1)
                } else {
                    write!(line, " {}", v + 1)
                };
            }
            line.push('\n');
            out.write_all(line.as_bytes())?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::rules::Boundary;
    use super::super::tags::{Tag, TagTarget};
    use super::*;
    use crate::mesh::generators;

    fn sharp_from(mesh: &crate::mesh::Mesh) -> SharpMesh {
        let faces: Vec<Vec<usize>> = (0..mesh.face_count())
            .map(|f| mesh.face_vertices(f).collect())
            .collect();
        SharpMesh::new(mesh.positions().to_vec(), &faces, &[], Boundary::EdgeOnly).unwrap()
    }

    fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
        assert_eq!(a.len(), b.len());
        a.iter()
            .zip(b)
            .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).abs()))
            .fold(0.0, f64::max)
    }

    #[test]
    fn closed_untagged_meshes_agree_with_the_closed_refiners() {
        let cube = generators::cube();
        let ours = sharp_from(&cube)
            .refine_levels(SdcScheme::CatmullClark, Creasing::Uniform, 2)
            .unwrap();
        let theirs = crate::mesh::catmull_clark::refine_cc_levels(&cube, 0.5, 2).unwrap();
        assert!(max_diff(ours.positions(), theirs.positions()) < 1e-14);
        for f in 0..theirs.face_count() {
            let v: Vec<u32> = theirs.face_vertices(f).map(|v| v as u32).collect();
            assert_eq!(ours.face_vertices(f), &v[..]);
        }
        let ico = generators::icosahedron();
        let ours = sharp_from(&ico)
            .refine_levels(SdcScheme::Loop, Creasing::Chaikin, 2)
            .unwrap();
        let theirs = crate::mesh::loop_subdivision::refine_levels(&ico, 2).unwrap();
        assert!(max_diff(ours.positions(), theirs.positions()) < 1e-14);
    }

    /// The child's topology, built from its parts by construction, equals
    /// the one the general corner pairing finds from its faces alone (the
    /// edges around a parent vertex are in the parent's rotational order
    /// instead of edge order, so those are compared as sets).
    fn assert_topology_matches_pairing(parent: &SharpMesh, child: &SharpMesh) {
        let paired = SharpMesh::assemble(
            child.positions.clone(),
            child.face_start.clone(),
            child.face_verts.clone(),
            child.hole.clone(),
        )
        .unwrap();
        assert_eq!(child.face_edges, paired.face_edges);
        assert_eq!(child.edge_verts, paired.edge_verts);
        assert_eq!(child.edge_faces, paired.edge_faces);
        assert_eq!(child.vert_edge_start, paired.vert_edge_start);
        assert_eq!(child.vert_face_start, paired.vert_face_start);
        assert_eq!(child.vert_faces, paired.vert_faces);
        for v in 0..child.vertex_count() {
            let (mut a, mut b) = (
                child.vertex_edges(v).to_vec(),
                paired.vertex_edges(v).to_vec(),
            );
            if v >= parent.vertex_count() {
                assert_eq!(a, b, "edges of child vertex {v}");
            }
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "edges of vertex {v}");
        }
    }

    #[test]
    fn child_topology_equals_the_general_pairing() {
        // an open strip of quads, a semi-sharp crease and a corner, and the
        // same strip cut into triangles; boundary `none` leaves holes
        let p: Vec<[f64; 3]> = (0..12)
            .map(|i| [(i % 4) as f64, (i / 4) as f64, ((i % 4) * (i / 4)) as f64])
            .collect();
        let quads = vec![
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![4, 5, 9, 8],
            vec![5, 6, 10, 9],
            vec![6, 7, 11, 10],
        ];
        let tris: Vec<Vec<usize>> = quads
            .iter()
            .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
            .collect();
        let tag = |target, sharpness| Tag {
            line: 1,
            target,
            sharpness,
        };
        let tags = [
            tag(TagTarget::Edge(5, 6), 1.5),
            tag(TagTarget::Edge(1, 5), 10.0),
            tag(TagTarget::Vertex(6), 2.0),
        ];
        for (faces, scheme) in [(&quads, SdcScheme::CatmullClark), (&tris, SdcScheme::Loop)] {
            for boundary in [Boundary::EdgeOnly, Boundary::None] {
                let mut m = SharpMesh::new(p.clone(), faces, &tags, boundary).unwrap();
                for _ in 0..3 {
                    let r = m.refine(scheme, Creasing::Chaikin).unwrap();
                    assert_topology_matches_pairing(&m, &r);
                    m = r;
                }
            }
        }
    }

    #[test]
    fn infinitely_sharp_boundary_is_a_cubic_b_spline() {
        // a 3x1 strip of quads: the bottom boundary row refines by the
        // cubic B-spline curve rules (1/8, 3/4, 1/8) and (1/2, 1/2)
        let p: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i % 4) as f64, (i / 4) as f64, ((i % 4) * (i % 4)) as f64])
            .collect();
        let faces = vec![vec![0, 1, 5, 4], vec![1, 2, 6, 5], vec![2, 3, 7, 6]];
        let m = SharpMesh::new(p.clone(), &faces, &[], Boundary::EdgeOnly).unwrap();
        let r = m
            .refine(SdcScheme::CatmullClark, Creasing::Uniform)
            .unwrap();
        let z1 = r.positions()[1][2];
        assert!((z1 - (0.125 * 0.0 + 0.75 * 1.0 + 0.125 * 4.0)).abs() < 1e-15);
        let e = m.find_edge(1, 2).unwrap();
        let mid = r.positions()[8 + e];
        assert!((mid[2] - 2.5).abs() < 1e-15);
    }
}
