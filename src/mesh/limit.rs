//! Limit points, the limit mesh, and per-level convergence statistics of the
//! Doo-Sabin family (NURDS, original Doo-Sabin, the Catmull-Clark variant).
//!
//! With [`super::refine`] this is that family's implementation of the mesh
//! rules: the library reaches it only through
//! [`FaceSplit`](super::rules::FaceSplit) (and so through
//! [`crate::mesh::builtin::mesh_rules`]); the [`SchemeKind`] the functions
//! take selects the member of the family (NURDS uses the knot intervals, the
//! others are uniform). [`convergence_series`] and the statistics types are
//! scheme-independent.
//!
//! * **Face limit point** (math doc section 5): the face point
//!   `F = sum_j c_j P_j` is invariant under refinement (`c^T A = c^T`, and the
//!   F-face child keeps the parent's edge ratios) and every corner converges
//!   to it, so `F` is the limit of the face's centre.
//! * **Vertex limit point** at a *regular* vertex: valence 4, four quads, and
//!   tensor-product knots on the 3x3 control net (math doc section 2). There
//!   the surface is a non-uniform biquadratic patch
//!   ([`crate::bspline::BiquadraticPatch`]) whose corners are the four face
//!   limit points; the vertex's V-face shrinks to the patch's parameter
//!   midpoint, which is the vertex's limit position **\[derived\]** (the
//!   V-face's children carry the halved intervals of the centre span; checked
//!   in `tests/mesh/mesh_tensor_limit.rs` against the face limit point of the V-face
//!   after one mesh step, an independent route).
//! * **Limit mesh**: the dual of the mesh, its vertices the face limit points;
//!   each dual face of a regular vertex is split into a fan of triangles around
//!   that vertex's limit point. Every vertex of the result lies on the limit
//!   surface.
//! * **Convergence statistics**: for every extraordinary face (`n != 4`),
//!   `max_i |P_i - F|`; Theorem 1 (math doc section 5) bounds its decrease per
//!   level by the factor 3/4.

// Index loops mirror the subscripts of the formulas in the math doc.
#![allow(clippy::needless_range_loop)]

use super::refine::{face_point, refine};
use super::vec3::dist;
use super::{Mesh, MeshError};
use crate::bspline::{BiquadraticPatch, QuadraticSpan};
use crate::schemes::SchemeKind;

/// Relative tolerance under which two knot intervals count as equal when
/// deciding whether a 3x3 neighbourhood has tensor-product knots.
///
/// Knots enter the biquadratic evaluation only through ratios, so using the
/// mean of intervals that agree to a relative `1e-12` moves the evaluated point
/// by at most about `1e-12` times the size of the net: far below any
/// geometric significance and above the rounding of intervals written and read
/// back as decimal text (which round-trips exactly) or halved (exact).
pub const TENSOR_KNOT_RTOL: f64 = 1e-12;

/// The limit point of every face (indexed by face).
pub fn face_limit_points(mesh: &Mesh, scheme: SchemeKind) -> Vec<[f64; 3]> {
    (0..mesh.face_count())
        .map(|f| face_point(mesh, f, scheme))
        .collect()
}

/// `max_i |P_i - F|` over the corners of face `f`, with `F` its limit point.
pub fn face_distance(mesh: &Mesh, f: usize, scheme: SchemeKind) -> f64 {
    let fp = face_point(mesh, f, scheme);
    mesh.face_vertices(f)
        .map(|v| dist(&mesh.positions[v], &fp))
        .fold(0.0, f64::max)
}

fn agree(values: &[f64]) -> Option<f64> {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(0.0, f64::max);
    if hi - lo <= TENSOR_KNOT_RTOL * hi {
        Some(values.iter().sum::<f64>() / values.len() as f64)
    } else {
        None
    }
}

/// The regular 3x3 neighbourhood of vertex `v` as a biquadratic patch, or
/// `None` if `v` is not regular (valence 4, four quads, 9 distinct vertices,
/// tensor-product knots).
///
/// The net is `P_ab` (`a` along `u`, `b` along `v`, `P_11 = v`) with the
/// faces around `v` counter-clockwise: `f_0 = (P_11, P_21, P_22, P_12)`,
/// `f_1 = (P_11, P_12, P_02, P_01)`, `f_2 = (P_11, P_01, P_00, P_10)`,
/// `f_3 = (P_11, P_10, P_20, P_21)`. Tensor-product knots mean
/// `d(P_ab -> P_{a+-1,b}) = d_a` for every `b` and `d(P_ab -> P_{a,b+-1}) = e_b`
/// for every `a`. `uniform` ignores the mesh's knots (original Doo-Sabin and
/// the Catmull-Clark variant).
pub fn regular_patch(mesh: &Mesh, v: usize, uniform: bool) -> Option<BiquadraticPatch<3>> {
    let ring = mesh.vertex_ring(v);
    if ring.len() != 4 {
        return None;
    }
    if ring.iter().any(|&h| mesh.face_size(mesh.face_of(h)) != 4) {
        return None;
    }
    // grid[a][b] = vertex index
    let w = |k: usize| mesh.target(ring[k]);
    let diag = |k: usize| mesh.target(mesh.next(ring[k]));
    let grid = [
        [diag(2), w(2), diag(1)],
        [w(3), v, w(1)],
        [diag(3), w(0), diag(0)],
    ];
    let mut all: Vec<usize> = grid.iter().flatten().copied().collect();
    all.sort_unstable();
    all.dedup();
    if all.len() != 9 {
        return None;
    }
    let (u_span, v_span) = if uniform {
        (QuadraticSpan::uniform(), QuadraticSpan::uniform())
    } else {
        let mut d = [0.0; 3];
        let mut e = [0.0; 3];
        for a in 0..3usize {
            let mut vals = Vec::new();
            for b in 0..3 {
                for a2 in [a.wrapping_sub(1), a + 1] {
                    if a2 < 3 {
                        vals.push(mesh.knot(mesh.find_half_edge(grid[a][b], grid[a2][b])?));
                    }
                }
            }
            d[a] = agree(&vals)?;
        }
        for b in 0..3usize {
            let mut vals = Vec::new();
            for a in 0..3 {
                for b2 in [b.wrapping_sub(1), b + 1] {
                    if b2 < 3 {
                        vals.push(mesh.knot(mesh.find_half_edge(grid[a][b], grid[a][b2])?));
                    }
                }
            }
            e[b] = agree(&vals)?;
        }
        (
            QuadraticSpan::new(d[0], d[1], d[2]).ok()?,
            QuadraticSpan::new(e[0], e[1], e[2]).ok()?,
        )
    };
    let mut control = [[[0.0; 3]; 3]; 3];
    for a in 0..3 {
        for b in 0..3 {
            control[a][b] = mesh.positions[grid[a][b]];
        }
    }
    Some(BiquadraticPatch::new(u_span, v_span, control))
}

/// The limit position of vertex `v` if its neighbourhood is regular
/// ([`regular_patch`]): the patch at its parameter midpoint `(1/2, 1/2)`.
pub fn regular_vertex_limit(mesh: &Mesh, v: usize, scheme: SchemeKind) -> Option<[f64; 3]> {
    let uniform = !matches!(scheme, SchemeKind::Nurds);
    regular_patch(mesh, v, uniform).map(|p| p.eval(0.5, 0.5))
}

/// The limit mesh of `mesh` under `scheme` (see the module docs): dual
/// vertices at the face limit points, a fan around the limit point of every
/// regular vertex. Vertex `f` of the result is the limit point of face `f`.
pub fn limit_mesh(mesh: &Mesh, scheme: SchemeKind) -> Result<Mesh, MeshError> {
    let mut positions = face_limit_points(mesh, scheme);
    let mut faces: Vec<Vec<usize>> = Vec::with_capacity(mesh.vertex_count());
    for v in 0..mesh.vertex_count() {
        let ring: Vec<usize> = mesh
            .vertex_ring(v)
            .iter()
            .map(|&h| mesh.face_of(h))
            .collect();
        match regular_vertex_limit(mesh, v, scheme) {
            Some(p) => {
                let centre = positions.len();
                positions.push(p);
                for k in 0..ring.len() {
                    faces.push(vec![ring[k], ring[(k + 1) % ring.len()], centre]);
                }
            }
            None => faces.push(ring),
        }
    }
    Mesh::from_polygons(positions, &faces)
}

/// One extraordinary face at one level.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ExtraordinaryFaceStat {
    /// Face index at this level (an extraordinary face keeps its index under refinement).
    pub face: usize,
    /// Number of sides.
    pub valence: usize,
    /// `max_i |P_i - F|`.
    pub distance: f64,
    /// `distance / distance at the previous level`, when the face existed there.
    pub ratio: Option<f64>,
}

/// Counts and extraordinary-face distances at one level.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct LevelStats {
    /// Refinement level (0 = input).
    pub level: usize,
    /// Number of faces.
    pub faces: usize,
    /// Number of vertices.
    pub vertices: usize,
    /// Every extraordinary face, by index.
    pub extraordinary: Vec<ExtraordinaryFaceStat>,
}

/// Statistics of `mesh` at `level`; `previous` (the statistics of the parent
/// level) supplies the ratios.
pub fn level_stats(
    mesh: &Mesh,
    scheme: SchemeKind,
    level: usize,
    previous: Option<&LevelStats>,
) -> LevelStats {
    let prev_faces = previous.map_or(0, |p| p.faces);
    let extraordinary = (0..mesh.face_count())
        .filter(|&f| mesh.is_extraordinary_face(f))
        .map(|f| {
            let distance = face_distance(mesh, f, scheme);
            // F-face children keep their index, and come first in the new mesh.
            let ratio = previous.filter(|_| f < prev_faces).and_then(|p| {
                p.extraordinary
                    .binary_search_by_key(&f, |s| s.face)
                    .ok()
                    .map(|i| distance / p.extraordinary[i].distance)
            });
            ExtraordinaryFaceStat {
                face: f,
                valence: mesh.face_size(f),
                distance,
                ratio,
            }
        })
        .collect();
    LevelStats {
        level,
        faces: mesh.face_count(),
        vertices: mesh.vertex_count(),
        extraordinary,
    }
}

/// Refines `levels` times and returns the final mesh with the statistics of
/// every level `0..=levels`.
pub fn refine_with_stats(
    mesh: &Mesh,
    scheme: SchemeKind,
    levels: usize,
) -> Result<(Mesh, Vec<LevelStats>), MeshError> {
    let mut stats = vec![level_stats(mesh, scheme, 0, None)];
    let mut m = mesh.clone();
    for level in 1..=levels {
        m = refine(&m, scheme)?;
        let s = level_stats(&m, scheme, level, stats.last());
        stats.push(s);
    }
    Ok((m, stats))
}

/// One extraordinary face followed across levels: the data of a convergence
/// plot (distance to `F` against level).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ConvergenceSeries {
    /// Face index (stable across levels).
    pub face: usize,
    /// Number of sides.
    pub valence: usize,
    /// The level at which the face first appears.
    pub first_level: usize,
    /// `max_i |P_i - F|` at levels `first_level, first_level + 1, ...`.
    pub distances: Vec<f64>,
}

/// Regroups per-level statistics into one series per extraordinary face.
pub fn convergence_series(stats: &[LevelStats]) -> Vec<ConvergenceSeries> {
    let mut out: Vec<ConvergenceSeries> = Vec::new();
    let mut open: std::collections::BTreeMap<usize, usize> = Default::default();
    for level in stats {
        for s in &level.extraordinary {
            match (s.ratio, open.get(&s.face)) {
                (Some(_), Some(&i)) => out[i].distances.push(s.distance),
                _ => {
                    open.insert(s.face, out.len());
                    out.push(ConvergenceSeries {
                        face: s.face,
                        valence: s.valence,
                        first_level: level.level,
                        distances: vec![s.distance],
                    });
                }
            }
        }
    }
    out
}

/// The edge ratios of face `f` from the mesh's directed-edge intervals
/// (`p_i = knot(h_i)`, `q_i = knot(twin(h_{i-1}))`, math doc section 2).
pub fn face_edge_ratios(mesh: &Mesh, f: usize) -> crate::Result<crate::knots::EdgeRatios<f64>> {
    let (p, q): (Vec<f64>, Vec<f64>) = mesh
        .face_corners(f)
        .map(|h| mesh.corner_intervals(h))
        .unzip();
    crate::knots::CornerIntervals::new(p, q)?.ratios()
}

/// The local scheme that governs face `f` under `scheme` (NURDS: the face's
/// own edge ratios, which refinement preserves; the uniform schemes: the valence).
pub fn face_local_scheme(
    mesh: &Mesh,
    f: usize,
    scheme: SchemeKind,
) -> crate::Result<crate::schemes::LocalScheme<f64>> {
    let n = mesh.face_size(f);
    match scheme {
        SchemeKind::Nurds => Ok(crate::schemes::LocalScheme::nurds(face_edge_ratios(
            mesh, f,
        )?)),
        other => crate::schemes::LocalScheme::from_kind(other, n, None),
    }
}
