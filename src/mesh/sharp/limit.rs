//! Limit positions of the vertices of a [`SharpMesh`] (math doc section 17):
//! OpenSubdiv's limit masks, chosen by the vertex's rule at that level.
//!
//! ```text
//! smooth, Catmull-Clark:  (n^2 v + 4 sum e_i + sum d_j) / (n (n + 5))
//!                         (d_j: the corner of face j opposite v; all quads)
//! smooth, Loop:           (1 - n x) v + x sum e_i,  x = 1 / (n + 3 / (8 w)),
//!                         w = (5/8 - beta^2)/n   (x = 1/12 at n = 6)
//! crease (both schemes):  2/3 v + 1/6 (e_a + e_b)
//! corner:                 v
//! ```
//!
//! The crease and corner masks are exact for infinitely sharp features (the
//! crease curve is the cubic B-spline of its vertices); for semi-sharp
//! features they are OpenSubdiv's approximation (the mask of the rule at the
//! level evaluated, not of the decayed rules below it), and so is the smooth
//! mask at a dart (a vertex with one sharp edge).

use super::rules::{is_sharp, vertex_rule, Rule, SdcScheme};
use super::SharpMesh;
use crate::mesh::MeshError;

impl SharpMesh {
    /// The limit position of every vertex (module docs), indexed like the
    /// vertices. Catmull-Clark needs an all-quad mesh
    /// ([`MeshError::NotAllQuads`]: refine once first); Loop an all-triangle
    /// one ([`MeshError::NotAllTriangles`]).
    pub fn limit_positions(&self, scheme: SdcScheme) -> Result<Vec<[f64; 3]>, MeshError> {
        let size = match scheme {
            SdcScheme::CatmullClark => 4,
            SdcScheme::Loop => 3,
        };
        if let Some(f) = (0..self.face_count()).find(|&f| self.face_vertices(f).len() != size) {
            let corners = self.face_vertices(f).len();
            return Err(match scheme {
                SdcScheme::CatmullClark => MeshError::NotAllQuads {
                    face: f,
                    corners,
                    operation: "the Catmull-Clark limit masks",
                },
                SdcScheme::Loop => MeshError::NotAllTriangles {
                    face: f,
                    corners,
                    operation: "the Loop limit masks",
                },
            });
        }
        let p = &self.positions;
        let mut out = Vec::with_capacity(self.vertex_count());
        for v in 0..self.vertex_count() {
            let edges = self.vertex_edges(v);
            let far = |e: u32| -> usize {
                let [a, b] = self.edge_verts[e as usize];
                if a as usize == v {
                    b as usize
                } else {
                    a as usize
                }
            };
            let sharp = edges
                .iter()
                .filter(|&&e| is_sharp(self.edge_sharpness[e as usize]))
                .count();
            let n = edges.len();
            let mut q = [0.0; 3];
            let mut add = |x: &[f64; 3], w: f64| {
                for k in 0..3 {
                    q[k] += w * x[k];
                }
            };
            match vertex_rule(self.vertex_sharpness[v], sharp) {
                Rule::Corner => add(&p[v], 1.0),
                Rule::Crease => {
                    add(&p[v], 2.0 / 3.0);
                    for &e in edges {
                        if is_sharp(self.edge_sharpness[e as usize]) {
                            add(&p[far(e)], 1.0 / 6.0);
                        }
                    }
                }
                Rule::Smooth | Rule::Dart => match scheme {
                    SdcScheme::CatmullClark if n == 2 => add(&p[v], 1.0),
                    SdcScheme::CatmullClark => {
                        let nf = n as f64;
                        let wf = 1.0 / (nf * (nf + 5.0));
                        let we = 4.0 * wf;
                        add(&p[v], 1.0 - nf * (we + wf));
                        for &e in edges {
                            add(&p[far(e)], we);
                        }
                        for &f in self.vertex_faces(v) {
                            let verts = self.face_vertices(f as usize);
                            let i = verts.iter().position(|&x| x as usize == v).unwrap_or(0);
                            add(&p[verts[(i + 2) % 4] as usize], wf);
                        }
                    }
                    SdcScheme::Loop => {
                        let nf = n as f64;
                        let we = if n == 6 {
                            1.0 / 12.0
                        } else {
                            let beta = 0.25 * (2.0 * std::f64::consts::PI / nf).cos() + 0.375;
                            let w = (0.625 - beta * beta) / nf;
                            1.0 / (nf + 3.0 / (8.0 * w))
                        };
                        add(&p[v], 1.0 - nf * we);
                        for &e in edges {
                            add(&p[far(e)], we);
                        }
                    }
                },
            }
            out.push(q);
        }
        Ok(out)
    }
}

impl SharpMesh {
    /// Replaces the vertex positions (same count, all finite).
    pub fn set_positions(&mut self, positions: Vec<[f64; 3]>) -> Result<(), MeshError> {
        if positions.len() != self.positions.len() {
            return Err(MeshError::CountMismatch {
                what: "vertex positions",
                expected: self.positions.len(),
                got: positions.len(),
            });
        }
        if let Some((v, x)) = positions
            .iter()
            .enumerate()
            .find_map(|(v, p)| p.iter().find(|x| !x.is_finite()).map(|x| (v, *x)))
        {
            return Err(MeshError::NonFiniteCoordinate {
                vertex: v,
                value: format!("{x:?}"),
            });
        }
        self.positions = positions;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::rules::{Boundary, Creasing};
    use super::*;

    /// The limit positions of a level are where the vertex points of later
    /// levels go: on an open quad grid with an infinitely sharp crease across
    /// it and a corner on the crease, the distance shrinks by about 4 per
    /// level. (Darts are left out: their smooth limit mask is OpenSubdiv's
    /// approximation, not the limit.)
    #[test]
    fn limit_positions_are_where_refinement_converges() {
        let p: Vec<[f64; 3]> = (0..12)
            .map(|i| {
                let (x, y) = ((i % 4) as f64, (i / 4) as f64);
                [x, y, (x * 1.3 + y * y * 0.7).sin()]
            })
            .collect();
        let faces: Vec<Vec<usize>> = (0..2)
            .flat_map(|j| {
                (0..3).map(move |i| vec![4 * j + i, 4 * j + i + 1, 4 * j + i + 5, 4 * j + i + 4])
            })
            .collect();
        // an infinitely sharp crease across the middle row, pinned by a corner
        let edge = |a, b, line| super::super::tags::Tag {
            line,
            target: super::super::tags::TagTarget::Edge(a, b),
            sharpness: 10.0,
        };
        let tags = [
            edge(4, 5, 1),
            edge(5, 6, 2),
            edge(6, 7, 3),
            super::super::tags::Tag {
                line: 4,
                target: super::super::tags::TagTarget::Vertex(5),
                sharpness: 10.0,
            },
        ];
        let m = SharpMesh::new(p, &faces, &tags, Boundary::EdgeOnly).unwrap();
        let m1 = m
            .refine(SdcScheme::CatmullClark, Creasing::Uniform)
            .unwrap();
        let limit = m1.limit_positions(SdcScheme::CatmullClark).unwrap();
        let mut errors = Vec::new();
        let mut finer = m1.clone();
        for _ in 0..5 {
            finer = finer
                .refine(SdcScheme::CatmullClark, Creasing::Uniform)
                .unwrap();
            let e = limit
                .iter()
                .zip(finer.positions())
                .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
                .fold(0.0f64, f64::max);
            errors.push(e);
        }
        for w in errors.windows(2) {
            assert!(w[1] < 0.3 * w[0], "{errors:?}");
        }
        assert!(errors[4] < 1e-3, "{errors:?}");
    }
}
