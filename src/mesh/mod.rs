//! Closed, oriented polygon meshes with directed-edge knot intervals, and
//! mesh-level subdivision (NURDS, original Doo-Sabin, the Catmull-Clark variant).
//!
//! Math doc sections 1-4. The mesh is index based: every face is a cycle of
//! *corners*; corner `h` of face `f` is also the half-edge from its vertex to
//! the vertex of the next corner of `f`. Each half-edge stores its twin (the
//! opposite half-edge in the neighbouring face) and one knot interval
//!
//! ```text
//! knot(h) = d(u -> v)  for the half-edge h = (u -> v),
//! ```
//!
//! "the knot interval of vertex `u` along edge `uv`" (math doc section 2,
//! **\[derived\]** for meshes of arbitrary topology). On a closed oriented
//! manifold every directed edge `u -> v` is exactly one half-edge, so the
//! intervals are one positive number per directed edge. On a face with corners
//! `P_0..P_{n-1}` the corner intervals are `p_i = knot(h_i)` and
//! `q_i = knot(twin(h_{i-1}))`.
//!
//! Submodules: [`obj`] (OBJ text in and out), [`knot_file`] (the knot-interval
//! sidecar), [`rules`] (a scheme's mesh rules behind one trait, the way the
//! library refines: [`crate::mesh::builtin::mesh_rules`]), [`refine`] and
//! [`limit`] (the Doo-Sabin family's rules: one step, limit points, limit
//! meshes, per-level convergence statistics), [`catmull_clark`] (the
//! Catmull-Clark family's rules), [`generators`] (the small closed meshes
//! shipped under `analysis/meshes/`), [`neighbourhood`] (the `4n` points of
//! `S_n` around a face), `projection` (orthographic pictures).
//!
//! ```
//! use subdiv_lab::mesh::{generators, refine::refine};
//! use subdiv_lab::schemes::SchemeKind;
//! let cube = generators::cube();
//! assert_eq!((cube.face_count(), cube.vertex_count()), (6, 8));
//! let once = refine(&cube, SchemeKind::Nurds).unwrap();
//! // Doo-Sabin topology: F + E + V faces, one new vertex per corner
//! assert_eq!((once.face_count(), once.vertex_count()), (6 + 12 + 8, 24));
//! ```

// Index loops mirror the subscripts of the formulas in the math doc.
#![allow(clippy::needless_range_loop)]

pub mod builtin;
pub mod catmull_clark;
pub mod generators;
pub mod knot_file;
pub mod limit;
pub mod loop_subdivision;
pub mod neighbourhood;
pub mod obj;
pub mod open;
#[cfg(feature = "report")]
pub(crate) mod projection;
pub mod refine;
pub mod rules;
pub mod sharp;
pub mod tri_schemes;
pub mod user;

use std::fmt;

/// Errors of mesh construction, validation, I/O parsing and refinement.
///
/// Vertex and face indices are 0-based; messages also print the 1-based OBJ
/// index of vertices.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// An error of the core (a scheme parameter the mesh rules refuse).
    #[error(transparent)]
    Core(#[from] crate::error::Error),
    /// A mesh without faces.
    #[error("the mesh has no faces")]
    Empty,
    /// A vertex coordinate that is NaN or infinite.
    #[error("vertex {vertex} (OBJ {}) has a non-finite coordinate {value}", vertex + 1)]
    NonFiniteCoordinate {
        /// The vertex.
        vertex: usize,
        /// The coordinate, as text.
        value: String,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index} (OBJ {}), but the mesh has {vertex_count} vertices", index + 1)]
    DanglingIndex {
        /// The face.
        face: usize,
        /// The missing vertex index.
        index: usize,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A face with fewer than 3 corners.
    #[error("face {face} is degenerate: it has {corners} corners (at least 3 needed)")]
    TooFewCorners {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A face that visits the same vertex twice.
    #[error("face {face} is degenerate: vertex {vertex} (OBJ {}) occurs twice", vertex + 1)]
    RepeatedVertex {
        /// The face.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// An edge shared by more than two faces.
    #[error("non-manifold edge {u}-{v} (OBJ {}-{}): it lies in {faces} faces", u + 1, v + 1)]
    NonManifoldEdge {
        /// One end.
        u: usize,
        /// The other end.
        v: usize,
        /// Number of faces containing it.
        faces: usize,
    },
    /// Two faces traverse their common edge in the same direction.
    #[error("inconsistent orientation: faces {face_a} and {face_b} both traverse edge {u}->{v} (OBJ {}->{})", u + 1, v + 1)]
    InconsistentOrientation {
        /// Start of the doubly used directed edge.
        u: usize,
        /// Its end.
        v: usize,
        /// First face.
        face_a: usize,
        /// Second face.
        face_b: usize,
    },
    /// An edge with only one face: meshes with boundary are not supported.
    #[error("boundary not supported: edge {u}->{v} (OBJ {}->{}) of face {face} has no opposite face", u + 1, v + 1)]
    BoundaryEdge {
        /// Start of the boundary half-edge.
        u: usize,
        /// Its end.
        v: usize,
        /// The only face containing it.
        face: usize,
    },
    /// The faces around a vertex form more than one fan.
    #[error("non-manifold vertex {vertex} (OBJ {}): its faces form {fans} separate fans", vertex + 1)]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
        /// Number of fans (at least 2).
        fans: usize,
    },
    /// A vertex with fewer than 3 edges: its V-face would have fewer than 3 sides.
    #[error("vertex {vertex} (OBJ {}) has valence {valence}; subdivision needs at least 3 (its V-face would be degenerate)", vertex + 1)]
    LowValence {
        /// The vertex.
        vertex: usize,
        /// Its valence.
        valence: usize,
    },
    /// A vertex used by no face.
    #[error("vertex {vertex} (OBJ {}) is not used by any face", vertex + 1)]
    IsolatedVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A knot interval that is not finite and positive.
    #[error("knot interval d({u}->{v}) (OBJ {}->{}) must be finite and > 0, got {value}", u + 1, v + 1)]
    InvalidInterval {
        /// Start vertex.
        u: usize,
        /// End vertex.
        v: usize,
        /// The value, as text.
        value: String,
    },
    /// A default knot interval that is not finite and positive.
    #[error("default knot interval must be finite and > 0, got {value}")]
    InvalidDefaultInterval {
        /// The value, as text.
        value: String,
    },
    /// A list of per-half-edge values of the wrong length.
    #[error("{what}: expected {expected} values, got {got}")]
    CountMismatch {
        /// What was counted.
        what: &'static str,
        /// Expected count.
        expected: usize,
        /// Actual count.
        got: usize,
    },
    /// A malformed line of an OBJ file.
    #[error("OBJ line {line}: {message}")]
    ObjSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A malformed line of a knot-interval file.
    #[error("knot file line {line}: {message}")]
    KnotSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A knot-file line naming a directed edge the mesh does not have.
    #[error("knot file line {line}: the mesh has no directed edge {u}->{v} (OBJ indices)")]
    UnknownEdge {
        /// 1-based line number.
        line: usize,
        /// Start vertex (OBJ, 1-based).
        u: usize,
        /// End vertex (OBJ, 1-based).
        v: usize,
    },
    /// A directed edge listed twice in a knot file.
    #[error("knot file line {line}: directed edge {u}->{v} (OBJ indices) was already given on line {first_line}")]
    DuplicateEdge {
        /// 1-based line number of the repetition.
        line: usize,
        /// Start vertex (OBJ, 1-based).
        u: usize,
        /// End vertex (OBJ, 1-based).
        v: usize,
        /// Line of the first occurrence.
        first_line: usize,
    },
    /// A knot-file interval that is not finite and positive.
    #[error("knot file line {line}: interval of {u}->{v} (OBJ indices) must be finite and > 0, got {value}")]
    KnotValue {
        /// 1-based line number.
        line: usize,
        /// Start vertex (OBJ, 1-based).
        u: usize,
        /// End vertex (OBJ, 1-based).
        v: usize,
        /// The value, as text.
        value: String,
    },
    /// A knot-file interval that is a positive finite number but rounds to 0
    /// or infinity in `f64` (`1e-400`, `1e400`).
    #[error("knot file line {line}: interval of {u}->{v} (OBJ indices) = {value} is not representable in f64: it rounds to {rounded}")]
    KnotNotRepresentable {
        /// 1-based line number.
        line: usize,
        /// Start vertex (OBJ, 1-based).
        u: usize,
        /// End vertex (OBJ, 1-based).
        v: usize,
        /// The value, as text.
        value: String,
        /// What `f64` makes of it.
        rounded: f64,
    },
    /// A knot interval that refinement cannot halve exactly in `f64` (a
    /// subnormal interval with an odd last bit, or the smallest subnormal):
    /// halving it would change the edge ratios or give 0.
    #[error("knot interval d({u}->{v}) (OBJ {}->{}) = {value} cannot be halved exactly in f64 (refinement halves every interval); scale all intervals up", u + 1, v + 1)]
    KnotNotHalvable {
        /// Start vertex.
        u: usize,
        /// End vertex.
        v: usize,
        /// The value, as text.
        value: String,
    },
    /// The refined mesh would exceed the 32-bit index range.
    #[error("the refined mesh would have {half_edges} half-edges, more than the supported {max}")]
    TooLarge {
        /// Half-edges the result would need.
        half_edges: u64,
        /// The limit.
        max: u64,
    },
    /// A scheme this module does not refine.
    #[error("mesh refinement does not support scheme {0}")]
    UnsupportedScheme(String),
    /// A Catmull-Clark-family operation that needs quads met another face.
    #[error(
        "face {face} has {corners} corners; {operation} needs an all-quad mesh (refine once first)"
    )]
    NotAllQuads {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
        /// What needed quads.
        operation: &'static str,
    },
    /// A Loop operation (triangle meshes only) met a face that is not a triangle.
    #[error("face {face} has {corners} corners; {operation} needs an all-triangle mesh")]
    NotAllTriangles {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
        /// What needed triangles.
        operation: &'static str,
    },
    /// A malformed crease or corner tag line (OBJ or tag file).
    #[error("tag line {line}: {message}")]
    TagSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A tag sharpness that is negative, NaN or infinite.
    #[error("tag line {line}: sharpness {value} must be a finite number >= 0")]
    TagSharpness {
        /// 1-based line number.
        line: usize,
        /// The value, as text.
        value: String,
    },
    /// A crease tag naming two vertices that share no edge.
    #[error("tag line {line}: the mesh has no edge {u}-{v} (0-based vertex indices)")]
    TagUnknownEdge {
        /// 1-based line number.
        line: usize,
        /// One end (0-based).
        u: usize,
        /// The other end (0-based).
        v: usize,
    },
    /// A corner tag naming a vertex the mesh does not have.
    #[error("tag line {line}: the mesh has no vertex {vertex} (0-based; it has {vertex_count})")]
    TagUnknownVertex {
        /// 1-based line number.
        line: usize,
        /// The vertex (0-based).
        vertex: usize,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// An edge or vertex tagged twice.
    #[error("tag line {line}: {what} was already tagged on line {first_line}")]
    TagDuplicate {
        /// 1-based line number of the repetition.
        line: usize,
        /// The edge or vertex (0-based indices).
        what: String,
        /// Line of the first tag.
        first_line: usize,
    },
    /// Crease or corner tags given to a scheme or mesh that cannot carry them.
    #[error("tag line {line}: crease and corner tags need --scheme catmull-clark or loop")]
    TagsUnsupported {
        /// 1-based line number of the first tag.
        line: usize,
    },
    /// A knot file that gives one direction of a boundary edge but not the
    /// other (the direction outside the faces, or the one inside).
    #[error("knot file line {line}: boundary edge {u}->{v} (OBJ indices) is given, its direction {v}->{u} is not; a boundary edge needs both (the boundary curve's rule uses both)")]
    BoundaryKnotMissing {
        /// 1-based line number of the direction that is given.
        line: usize,
        /// Start vertex of the given direction (OBJ, 1-based).
        u: usize,
        /// Its end (OBJ, 1-based).
        v: usize,
    },
    /// The shape parameter `c` of the Catmull-Clark family is outside `[0, 1]`.
    #[error("shape parameter c = {0} is not in [0, 1]")]
    InvalidShapeParameter(f64),
}

/// Largest number of half-edges a mesh may have (indices are `u32`).
pub const MAX_HALF_EDGES: u64 = u32::MAX as u64;

/// The one validator of a polygon mesh's input, shared by the closed and the
/// open (tagged) mesh builders: finite coordinates, at least one face, at most
/// [`MAX_HALF_EDGES`] corners and vertices, and faces of at least 3 distinct
/// existing vertices. Returns the faces flattened: `face_start` (one offset a
/// face, then the total) and the corners' vertices. Errors name the element.
pub(crate) fn polygon_soup<F: AsRef<[usize]>>(
    positions: &[[f64; 3]],
    faces: &[F],
) -> Result<(Vec<u32>, Vec<u32>), MeshError> {
    for (v, p) in positions.iter().enumerate() {
        if let Some(x) = p.iter().find(|x| !x.is_finite()) {
            return Err(MeshError::NonFiniteCoordinate {
                vertex: v,
                value: format!("{x:?}"),
            });
        }
    }
    if faces.is_empty() {
        return Err(MeshError::Empty);
    }
    let nv = positions.len();
    let total: u64 = faces.iter().map(|f| f.as_ref().len() as u64).sum();
    if total > MAX_HALF_EDGES || nv as u64 > MAX_HALF_EDGES {
        return Err(MeshError::TooLarge {
            half_edges: total,
            max: MAX_HALF_EDGES,
        });
    }
    let mut face_start = Vec::with_capacity(faces.len() + 1);
    let mut corners = Vec::with_capacity(total as usize);
    face_start.push(0u32);
    let mut seen = vec![u32::MAX; nv];
    for (f, face) in faces.iter().enumerate() {
        let face = face.as_ref();
        if let Some(&v) = face.iter().find(|&&v| v >= nv) {
            return Err(MeshError::DanglingIndex {
                face: f,
                index: v,
                vertex_count: nv,
            });
        }
        if face.len() < 3 {
            return Err(MeshError::TooFewCorners {
                face: f,
                corners: face.len(),
            });
        }
        for &v in face {
            if seen[v] == f as u32 {
                return Err(MeshError::RepeatedVertex { face: f, vertex: v });
            }
            seen[v] = f as u32;
            corners.push(v as u32);
        }
        face_start.push(corners.len() as u32);
    }
    Ok((face_start, corners))
}

/// The half-edge count after one step that splits every face into as many
/// faces as it has corners (every scheme here: `4H`), refused with
/// [`MeshError::TooLarge`] above [`MAX_HALF_EDGES`] before anything is
/// allocated.
pub(crate) fn quadrupled_half_edges(mesh: &Mesh) -> Result<u64, MeshError> {
    let new_h = 4 * mesh.half_edge_count() as u64;
    if new_h > MAX_HALF_EDGES {
        return Err(MeshError::TooLarge {
            half_edges: new_h,
            max: MAX_HALF_EDGES,
        });
    }
    Ok(new_h)
}

/// A closed, oriented 2-manifold polygon mesh with one knot interval per
/// directed edge. Constructed only through validation ([`Mesh::from_polygons`])
/// or by refinement, so every instance satisfies the invariants.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    pub(crate) positions: Vec<[f64; 3]>,
    /// `face_start[f]..face_start[f + 1]` are the corners of face `f`.
    pub(crate) face_start: Vec<u32>,
    /// Vertex of each corner (= start vertex of the half-edge).
    pub(crate) corner_vertex: Vec<u32>,
    /// Face of each corner.
    pub(crate) corner_face: Vec<u32>,
    /// Opposite half-edge.
    pub(crate) twin: Vec<u32>,
    /// One outgoing half-edge per vertex.
    pub(crate) vertex_out: Vec<u32>,
    /// `d(u -> v)` for each half-edge `u -> v`.
    pub(crate) knots: Vec<f64>,
}

impl Mesh {
    /// Builds and validates a mesh from positions and faces (vertex indices,
    /// 0-based, counter-clockwise seen from outside). Every knot interval is 1.
    ///
    /// Errors name the offending element: non-finite coordinates, dangling
    /// indices, degenerate faces, non-manifold edges and vertices, inconsistent
    /// orientation, boundary edges, isolated vertices, vertices of valence
    /// below 3 (whose V-faces would be degenerate).
    ///
    /// ```
    /// use subdiv_lab::mesh::{Mesh, MeshError};
    /// let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tet = Mesh::from_polygons(p.clone(), &[vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]]).unwrap();
    /// assert_eq!(tet.half_edge_count(), 12);
    /// let open = Mesh::from_polygons(p, &[vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3]]);
    /// assert!(matches!(open, Err(MeshError::BoundaryEdge { .. })));
    /// ```
    pub fn from_polygons<F: AsRef<[usize]>>(
        positions: Vec<[f64; 3]>,
        faces: &[F],
    ) -> Result<Mesh, MeshError> {
        let (face_start, corner_vertex) = polygon_soup(&positions, faces)?;
        let nv = positions.len();
        let mut corner_face = Vec::with_capacity(corner_vertex.len());
        for (f, w) in face_start.windows(2).enumerate() {
            corner_face.extend(std::iter::repeat_n(f as u32, (w[1] - w[0]) as usize));
        }
        let h_count = corner_vertex.len();
        let next = |h: usize| -> usize {
            let f = corner_face[h] as usize;
            if h + 1 == face_start[f + 1] as usize {
                face_start[f] as usize
            } else {
                h + 1
            }
        };
        // Pair half-edges by their undirected edge.
        let mut keyed: Vec<(u32, u32, u32)> = (0..h_count)
            .map(|h| {
                let (a, b) = (corner_vertex[h], corner_vertex[next(h)]);
                (a.min(b), a.max(b), h as u32)
            })
            .collect();
        keyed.sort_unstable();
        let mut twin = vec![u32::MAX; h_count];
        let mut i = 0;
        while i < keyed.len() {
            let mut j = i + 1;
            while j < keyed.len() && keyed[j].0 == keyed[i].0 && keyed[j].1 == keyed[i].1 {
                j += 1;
            }
            let group = &keyed[i..j];
            let h0 = group[0].2 as usize;
            let (u0, v0) = (corner_vertex[h0] as usize, corner_vertex[next(h0)] as usize);
            match group.len() {
                1 => {
                    return Err(MeshError::BoundaryEdge {
                        u: u0,
                        v: v0,
                        face: corner_face[h0] as usize,
                    })
                }
                2 => {
                    let h1 = group[1].2 as usize;
                    if corner_vertex[h1] as usize == u0 {
                        let (fa, fb) = (corner_face[h0] as usize, corner_face[h1] as usize);
                        return Err(MeshError::InconsistentOrientation {
                            u: u0,
                            v: v0,
                            face_a: fa.min(fb),
                            face_b: fa.max(fb),
                        });
                    }
                    twin[h0] = h1 as u32;
                    twin[h1] = h0 as u32;
                }
                k => {
                    return Err(MeshError::NonManifoldEdge {
                        u: u0.min(v0),
                        v: u0.max(v0),
                        faces: k,
                    })
                }
            }
            i = j;
        }
        // Vertex stars: every outgoing half-edge must lie on one fan.
        let mut outgoing = vec![0u32; nv];
        let mut vertex_out = vec![u32::MAX; nv];
        for h in 0..h_count {
            let v = corner_vertex[h] as usize;
            outgoing[v] += 1;
            vertex_out[v] = h as u32;
        }
        if let Some(v) = vertex_out.iter().position(|&h| h == u32::MAX) {
            return Err(MeshError::IsolatedVertex { vertex: v });
        }
        let mesh = Mesh {
            positions,
            face_start,
            corner_vertex,
            corner_face,
            twin,
            vertex_out,
            knots: vec![1.0; h_count],
        };
        let mut visited = vec![false; h_count];
        for v in 0..nv {
            let start = mesh.vertex_out[v] as usize;
            let mut h = start;
            let mut ring = 0u32;
            loop {
                visited[h] = true;
                ring += 1;
                h = mesh.rotate(h);
                if h == start {
                    break;
                }
            }
            if ring != outgoing[v] {
                // count the fans for the message
                let mut fans = 1;
                for h0 in 0..h_count {
                    if mesh.corner_vertex[h0] as usize == v && !visited[h0] {
                        fans += 1;
                        let mut h = h0;
                        loop {
                            visited[h] = true;
                            h = mesh.rotate(h);
                            if h == h0 {
                                break;
                            }
                        }
                    }
                }
                return Err(MeshError::NonManifoldVertex { vertex: v, fans });
            }
            if ring < 3 {
                return Err(MeshError::LowValence {
                    vertex: v,
                    valence: ring as usize,
                });
            }
        }
        Ok(mesh)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_start.len() - 1
    }

    /// Number of half-edges (= corners = directed edges).
    pub fn half_edge_count(&self) -> usize {
        self.corner_vertex.len()
    }

    /// Number of (undirected) edges.
    pub fn edge_count(&self) -> usize {
        self.half_edge_count() / 2
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// Replaces the vertex positions (same count, all finite).
    pub fn set_positions(&mut self, positions: Vec<[f64; 3]>) -> Result<(), MeshError> {
        if positions.len() != self.positions.len() {
            return Err(MeshError::CountMismatch {
                what: "vertex positions",
                expected: self.positions.len(),
                got: positions.len(),
            });
        }
        for (v, p) in positions.iter().enumerate() {
            if let Some(x) = p.iter().find(|x| !x.is_finite()) {
                return Err(MeshError::NonFiniteCoordinate {
                    vertex: v,
                    value: format!("{x:?}"),
                });
            }
        }
        self.positions = positions;
        Ok(())
    }

    /// The corners (half-edges) of face `f`: `start..end`.
    pub fn face_corners(&self, f: usize) -> std::ops::Range<usize> {
        self.face_start[f] as usize..self.face_start[f + 1] as usize
    }

    /// Number of corners of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        (self.face_start[f + 1] - self.face_start[f]) as usize
    }

    /// The vertices of face `f`, counter-clockwise.
    pub fn face_vertices(&self, f: usize) -> impl Iterator<Item = usize> + '_ {
        self.face_corners(f)
            .map(move |h| self.corner_vertex[h] as usize)
    }

    /// Start vertex of half-edge `h`.
    pub fn origin(&self, h: usize) -> usize {
        self.corner_vertex[h] as usize
    }

    /// End vertex of half-edge `h`.
    pub fn target(&self, h: usize) -> usize {
        self.corner_vertex[self.next(h)] as usize
    }

    /// Face of half-edge `h`.
    pub fn face_of(&self, h: usize) -> usize {
        self.corner_face[h] as usize
    }

    /// The opposite half-edge.
    pub fn twin(&self, h: usize) -> usize {
        self.twin[h] as usize
    }

    /// The next half-edge of the same face.
    #[inline]
    pub fn next(&self, h: usize) -> usize {
        let f = self.corner_face[h] as usize;
        if h + 1 == self.face_start[f + 1] as usize {
            self.face_start[f] as usize
        } else {
            h + 1
        }
    }

    /// The previous half-edge of the same face.
    #[inline]
    pub fn prev(&self, h: usize) -> usize {
        let f = self.corner_face[h] as usize;
        if h == self.face_start[f] as usize {
            self.face_start[f + 1] as usize - 1
        } else {
            h - 1
        }
    }

    /// The next outgoing half-edge counter-clockwise around `origin(h)`:
    /// `twin(prev(h))` (math doc section 3: face `f_{k+1}` lies across the edge
    /// `(v, prev_{f_k}(v))`).
    #[inline]
    pub fn rotate(&self, h: usize) -> usize {
        self.twin[self.prev(h)] as usize
    }

    /// One outgoing half-edge of vertex `v`.
    pub fn vertex_half_edge(&self, v: usize) -> usize {
        self.vertex_out[v] as usize
    }

    /// The outgoing half-edges of `v`, counter-clockwise (`h_{k+1} = rotate(h_k)`).
    pub fn vertex_ring(&self, v: usize) -> Vec<usize> {
        let start = self.vertex_out[v] as usize;
        let mut out = vec![start];
        let mut h = self.rotate(start);
        while h != start {
            out.push(h);
            h = self.rotate(h);
        }
        out
    }

    /// Number of edges at vertex `v`.
    pub fn valence(&self, v: usize) -> usize {
        self.vertex_ring(v).len()
    }

    /// The half-edge `u -> v`, if the mesh has it.
    pub fn find_half_edge(&self, u: usize, v: usize) -> Option<usize> {
        if u >= self.vertex_count() || v >= self.vertex_count() {
            return None;
        }
        let start = self.vertex_out[u] as usize;
        let mut h = start;
        loop {
            if self.target(h) == v {
                return Some(h);
            }
            h = self.rotate(h);
            if h == start {
                return None;
            }
        }
    }

    /// All knot intervals, indexed by half-edge: `knots()[h] = d(origin(h) -> target(h))`.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// `d(origin(h) -> target(h))`.
    pub fn knot(&self, h: usize) -> f64 {
        self.knots[h]
    }

    /// Corner intervals of corner `h` in its face: `(p, q)` with
    /// `p = d(P_i -> P_{i+1}) = knot(h)` and `q = d(P_i -> P_{i-1}) = knot(twin(prev(h)))`.
    #[inline]
    pub fn corner_intervals(&self, h: usize) -> (f64, f64) {
        (self.knots[h], self.knots[self.rotate(h)])
    }

    /// Sets `d(origin(h) -> target(h))`.
    pub fn set_knot(&mut self, h: usize, value: f64) -> Result<(), MeshError> {
        if !(value.is_finite() && value > 0.0) {
            return Err(MeshError::InvalidInterval {
                u: self.origin(h),
                v: self.target(h),
                value: format!("{value:?}"),
            });
        }
        self.knots[h] = value;
        Ok(())
    }

    /// Replaces every knot interval (indexed by half-edge; all finite and > 0).
    pub fn set_knots(&mut self, knots: Vec<f64>) -> Result<(), MeshError> {
        if knots.len() != self.half_edge_count() {
            return Err(MeshError::CountMismatch {
                what: "knot intervals (one per half-edge)",
                expected: self.half_edge_count(),
                got: knots.len(),
            });
        }
        if let Some(h) = knots.iter().position(|d| !(d.is_finite() && *d > 0.0)) {
            return Err(MeshError::InvalidInterval {
                u: self.origin(h),
                v: self.target(h),
                value: format!("{:?}", knots[h]),
            });
        }
        self.knots = knots;
        Ok(())
    }

    /// Whether every knot interval has the same value.
    pub fn has_uniform_knots(&self) -> bool {
        self.knots.iter().all(|&d| d == self.knots[0])
    }

    /// Whether face `f` is extraordinary (not a quad).
    pub fn is_extraordinary_face(&self, f: usize) -> bool {
        self.face_size(f) != 4
    }

    /// Re-checks the structural invariants (used by tests on refined meshes):
    /// twins are an involution between opposite half-edges of different faces,
    /// vertex rings close, knots positive. Returns a description of the first violation.
    pub fn check_invariants(&self) -> Result<(), String> {
        let h = self.half_edge_count();
        if self.twin.len() != h || self.knots.len() != h || self.corner_face.len() != h {
            return Err("array lengths disagree".into());
        }
        for e in 0..h {
            let t = self.twin(e);
            if t >= h || self.twin(t) != e {
                return Err(format!("twin of {e} is not an involution"));
            }
            if self.origin(t) != self.target(e) || self.target(t) != self.origin(e) {
                return Err(format!("twin of {e} does not reverse it"));
            }
            if !(self.knots[e].is_finite() && self.knots[e] > 0.0) {
                return Err(format!("knot of {e} is {}", self.knots[e]));
            }
        }
        let mut count = vec![0usize; self.vertex_count()];
        for e in 0..h {
            count[self.origin(e)] += 1;
        }
        for (v, &c) in count.iter().enumerate() {
            if self.origin(self.vertex_half_edge(v)) != v {
                return Err(format!("vertex_out of {v} does not start at it"));
            }
            if self.vertex_ring(v).len() != c {
                return Err(format!("vertex {v} ring is not a single fan"));
            }
        }
        Ok(())
    }
}

impl fmt::Display for Mesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} vertices, {} faces, {} edges",
            self.vertex_count(),
            self.face_count(),
            self.edge_count()
        )
    }
}

/// `a + t (b - a)` style helpers on 3-vectors.
pub(crate) mod vec3 {
    /// `|a - b|`.
    pub fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }
}
