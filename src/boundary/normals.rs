//! Limit normals at the vertices of a [`SharpMesh`] (math doc section 18.6).
//!
//! ```text
//! smooth, dart:          n = t_1 x t_2, the limit tangent masks of the ring
//!                        Loop:  t_1 = sum cos(2 pi i/n) e_i,  t_2 = the same with sin
//!                        Catmull-Clark: the tangent stencils of
//!                        schemes::catmull_clark::limit::tangent_stencils (c = 1/2)
//! sector between two sharp edges (a boundary, an interior crease, three
//! or more sharp edges):
//!                        n = t_1 x t_2 with t_k the left eigenvectors of the
//!                        subdominant eigenvalues of the sector's local matrix
//!                        (SectorConfig, standard rules: a boundary sector of K
//!                        faces under the crease rule, a corner sector under
//!                        the corner rule), applied to the sector's points
//!                        v, e_0..e_K, f_0..f_(K-1) (boundary::analysis::limit_frame)
//! ```
//!
//! Under the standard rules a sector's points refine from the sector's
//! points alone: the vertex follows its sharp edges, the sharp edges'
//! points their ends, and every other new point of the sector lies in
//! faces of the sector. So each sector of a crease or corner evolves as a
//! boundary or corner sector with the same number of faces, and its
//! tangent plane is that configuration's. The ring `e_i` (and `f_i` for
//! Catmull-Clark) runs in the order of the faces (face `i` is `v, e_i, f_i,
//! e_(i+1)`), from sharp edge to sharp edge. A left eigenvector's sign is
//! arbitrary, so a sector normal is turned to the side of the sector's
//! control fan `sum_i (e_i - v) x (e_(i+1) - v)` (the faces' orientation);
//! the smooth masks' `t_1 x t_2` has that orientation by construction. The
//! standard rules do not depend on a corner's angle, so a corner's
//! configuration is built with [`CORNER_ANGLE_DEGREES`]. The vertex rule is
//! the one of the level evaluated, as for the limit positions (math doc
//! section 17): at semi-sharp features and darts the normal is OpenSubdiv's
//! approximation.

use super::analysis::{analyze_sector, cross, limit_frame, SectorAnalysis, PARALLEL_TANGENTS};
use super::{RuleSet, SectorConfig, VertexKind};
use crate::mesh::sharp::rules::{is_sharp, vertex_rule, Rule, SdcScheme};
use crate::mesh::sharp::SharpMesh;
use crate::schemes::catmull_clark::limit::tangent_stencils;
use std::collections::HashMap;
use std::f64::consts::PI;

/// The corner angle (degrees) of the configuration built for a corner
/// vertex: the standard rules' matrix does not depend on it (only BLZ's
/// `gamma` does, math doc section 18.2).
pub const CORNER_ANGLE_DEGREES: f64 = 90.0;

/// A vertex without a limit normal: its index and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("vertex {vertex}: {reason}")]
pub struct NormalError {
    /// The vertex (0-based).
    pub vertex: usize,
    /// Why it has no normal.
    pub reason: String,
}

/// The limit normals of a mesh's vertices, with one normal per sector at
/// the vertices whose sharp edges cut the surface into sectors (an
/// interior crease, three or more sharp edges, a crease that meets the
/// boundary).
///
/// `normals[v]` is vertex `v`'s normal (at a vertex with sectors: its first
/// sector's); the normals of the further sectors follow the vertices'.
/// [`corner`](Self::corner) gives the normal of a face's corner, so a face
/// takes the normal of its own sector.
#[derive(Clone, Debug, PartialEq)]
pub struct LimitNormals {
    /// Unit normals: one per vertex, then the further sectors' normals.
    pub normals: Vec<[f64; 3]>,
    /// `(face, vertex) -> index into normals` for the corners whose normal
    /// is not `normals[vertex]`.
    pub sector_corners: HashMap<(usize, usize), usize>,
}

impl LimitNormals {
    /// The index into [`normals`](Self::normals) of the normal at the
    /// corner of `face` at `vertex`.
    pub fn corner(&self, face: usize, vertex: usize) -> usize {
        self.sector_corners
            .get(&(face, vertex))
            .copied()
            .unwrap_or(vertex)
    }
}

/// The unit limit normals of `mesh` under `scheme` (module docs; math doc
/// section 18.6). The mesh is all quads (Catmull-Clark) or all triangles
/// (Loop), open or closed. A smooth or dart vertex gets the tangent masks'
/// normal; a vertex whose sharp edges bound sectors gets one normal per
/// sector, from the sector's own configuration (a boundary sector under the
/// crease rule, a corner sector under the corner rule). Fails, naming the
/// vertex, where there is no tangent plane: an interior vertex with the
/// corner rule and fewer than two sharp edges (a cone point), an open fan
/// without sharp boundary edges (`--boundary none`), a configuration whose
/// honest class gives no pair of tangent eigenvectors (for example
/// Catmull-Clark's boundary sector with one face: `--boundary
/// edge-and-corner` makes a boundary vertex with one face a corner, which
/// has one), or parallel tangents.
pub fn limit_normals(mesh: &SharpMesh, scheme: SdcScheme) -> Result<LimitNormals, NormalError> {
    let mut cache: HashMap<(VertexKind, Vec<usize>), SectorAnalysis> = HashMap::new();
    let count = mesh.vertex_count();
    let mut normals = Vec::with_capacity(count);
    let mut further = Vec::new();
    let mut sector_corners = HashMap::new();
    for v in 0..count {
        match vertex_normal(mesh, scheme, v, &mut cache)? {
            VertexNormals::One(n) => normals.push(n),
            VertexNormals::Sectors(sectors) => {
                normals.push(sectors[0].1);
                for (faces, n) in sectors.into_iter().skip(1) {
                    let index = count + further.len();
                    further.push(n);
                    for f in faces {
                        sector_corners.insert((f, v), index);
                    }
                }
            }
        }
    }
    normals.extend(further);
    Ok(LimitNormals {
        normals,
        sector_corners,
    })
}

/// The ordered neighbourhood of `v`: the ring `e_i`, the far corners `f_i`
/// (Catmull-Clark) and whether the fan is open.
struct Fan {
    faces: Vec<usize>,
    e: Vec<usize>,
    f: Vec<usize>,
    open: bool,
}

fn fan(mesh: &SharpMesh, scheme: SdcScheme, v: usize) -> Result<Fan, String> {
    let size = match scheme {
        SdcScheme::CatmullClark => 4,
        SdcScheme::Loop => 3,
    };
    // (next, opposite, previous) around every face at v
    let mut corners = Vec::new();
    let mut ids = Vec::new();
    for &f in mesh.vertex_faces(v) {
        ids.push(f as usize);
        let verts = mesh.face_vertices(f as usize);
        if verts.len() != size {
            return Err(format!("face {f} has {} corners", verts.len()));
        }
        let i = verts
            .iter()
            .position(|&x| x as usize == v)
            .ok_or_else(|| format!("face {f} does not contain the vertex"))?;
        corners.push((
            verts[(i + 1) % size] as usize,
            verts[(i + 2) % size] as usize,
            verts[(i + size - 1) % size] as usize,
        ));
    }
    if corners.is_empty() {
        return Err("no face".to_owned());
    }
    let sharp = |a: usize| {
        mesh.find_edge(v, a)
            .is_some_and(|e| is_sharp(mesh.edge_sharpness()[e]))
    };
    // an open fan starts at the face whose first edge no face ends with;
    // a closed one at a sharp edge if there is one
    let start = corners
        .iter()
        .position(|c| !corners.iter().any(|d| d.2 == c.0))
        .or_else(|| corners.iter().position(|c| sharp(c.0)))
        .unwrap_or(0);
    let open = !corners.iter().any(|d| d.2 == corners[start].0);
    let mut order = vec![start];
    while order.len() < corners.len() {
        let prev = corners[*order.last().unwrap_or(&start)].2;
        match corners.iter().position(|c| c.0 == prev) {
            Some(j) if !order.contains(&j) => order.push(j),
            Some(_) if !open => break,
            _ => return Err("its faces do not form one fan".to_owned()),
        }
    }
    if order.len() != corners.len() {
        return Err("its faces do not form one fan".to_owned());
    }
    let mut e: Vec<usize> = order.iter().map(|&j| corners[j].0).collect();
    if open {
        e.push(corners[*order.last().unwrap_or(&start)].2);
    }
    let f = if scheme == SdcScheme::CatmullClark {
        order.iter().map(|&j| corners[j].1).collect()
    } else {
        Vec::new()
    };
    let faces = order.iter().map(|&j| ids[j]).collect();
    Ok(Fan { faces, e, f, open })
}

/// One vertex's normals: one, or one per sector with the sector's faces.
enum VertexNormals {
    One([f64; 3]),
    Sectors(Vec<(Vec<usize>, [f64; 3])>),
}

fn vertex_normal(
    mesh: &SharpMesh,
    scheme: SdcScheme,
    v: usize,
    cache: &mut HashMap<(VertexKind, Vec<usize>), SectorAnalysis>,
) -> Result<VertexNormals, NormalError> {
    let err = |reason: String| NormalError { vertex: v, reason };
    let fan = fan(mesh, scheme, v).map_err(err)?;
    let p = mesh.positions();
    let sharp: Vec<usize> = (0..fan.e.len())
        .filter(|&i| {
            mesh.find_edge(v, fan.e[i])
                .is_some_and(|e| is_sharp(mesh.edge_sharpness()[e]))
        })
        .collect();
    let rule = vertex_rule(mesh.vertex_sharpness()[v], sharp.len());
    let faces = fan.faces.len();
    // The sectors: the faces between consecutive sharp edges (math doc
    // section 18.6). An open fan starts and ends at a boundary edge, which
    // is sharp; a closed fan needs two sharp edges to have sectors.
    let kind = match rule {
        Rule::Smooth | Rule::Dart if !fan.open => {
            return smooth_normal(p, scheme, v, &fan)
                .map(VertexNormals::One)
                .map_err(err);
        }
        Rule::Crease => VertexKind::Boundary,
        Rule::Corner if fan.open || sharp.len() >= 2 => VertexKind::Corner,
        _ => {
            let place = if fan.open {
                "a boundary"
            } else {
                "an interior"
            };
            return Err(err(format!(
                "{place} vertex with the {rule:?} rule and {} sharp edges has no limit tangent plane (no sector between two sharp edges)",
                sharp.len()
            )));
        }
    };
    if fan.open && (sharp.first() != Some(&0) || sharp.last() != Some(&faces)) {
        return Err(err(
            "an open fan whose boundary edges are not sharp (--boundary none) has no limit tangent plane"
                .to_owned(),
        ));
    }
    let n = fan.e.len();
    let bounds: Vec<(usize, usize)> = if fan.open {
        sharp.windows(2).map(|w| (w[0], w[1])).collect()
    } else {
        (0..sharp.len())
            .map(|j| (sharp[j], sharp[(j + 1) % sharp.len()]))
            .collect()
    };
    let mut out = Vec::with_capacity(bounds.len());
    for (a, b) in bounds {
        // the sector's faces a, a+1, .., b-1 (cyclically for a closed fan)
        let k = if b > a { b - a } else { b + faces - a };
        let sector: Vec<usize> = (0..k).map(|i| (a + i) % faces).collect();
        let angle = (kind == VertexKind::Corner).then_some(CORNER_ANGLE_DEGREES);
        let key = (kind, vec![k]);
        if !cache.contains_key(&key) {
            let c = SectorConfig::new(scheme, kind, &[k], angle, RuleSet::Standard)
                .map_err(|e| err(e.to_string()))?;
            let s = analyze_sector(&c).map_err(|e| err(e.to_string()))?;
            cache.insert(key.clone(), s);
        }
        let s = &cache[&key];
        let mut points = vec![p[v]];
        points.extend((0..=k).map(|i| p[fan.e[(a + i) % n]]));
        if !fan.f.is_empty() {
            points.extend(sector.iter().map(|&i| p[fan.f[i]]));
        }
        let (_, normal) = limit_frame(s, &points).ok_or_else(|| {
            err(format!(
                "the {} has no pair of tangent eigenvectors (subdominant class {}) or its limit tangents are parallel",
                s.configuration,
                s.subdominant.class.name()
            ))
        })?;
        let c = control_fan(p, v, &fan, &sector);
        let sign = if dot(normal, c) < 0.0 { -1.0 } else { 1.0 };
        let faces_of_sector = sector.iter().map(|&i| fan.faces[i]).collect();
        out.push((faces_of_sector, normal.map(|x| sign * x)));
    }
    Ok(match out.len() {
        1 => VertexNormals::One(out[0].1),
        _ => VertexNormals::Sectors(out),
    })
}

/// `sum_i (e_i - v) x (e_(i+1) - v)` over the faces `i` of a sector of the fan.
fn control_fan(p: &[[f64; 3]], v: usize, fan: &Fan, sector: &[usize]) -> [f64; 3] {
    let n = fan.e.len();
    let d = |a: usize| sub(p[a], p[v]);
    let mut s = [0.0; 3];
    for &i in sector {
        let c = cross(d(fan.e[i]), d(fan.e[(i + 1) % n]));
        for k in 0..3 {
            s[k] += c[k];
        }
    }
    s
}

/// The smooth tangent masks (module docs) at an interior vertex.
fn smooth_normal(
    p: &[[f64; 3]],
    scheme: SdcScheme,
    v: usize,
    fan: &Fan,
) -> Result<[f64; 3], String> {
    let n = fan.e.len();
    let (t1, t2) = match scheme {
        SdcScheme::Loop => {
            let mut t = [[0.0; 3]; 2];
            for (i, &e) in fan.e.iter().enumerate() {
                let a = 2.0 * PI * i as f64 / n as f64;
                for k in 0..3 {
                    t[0][k] += a.cos() * p[e][k];
                    t[1][k] += a.sin() * p[e][k];
                }
            }
            (t[0], t[1])
        }
        SdcScheme::CatmullClark => {
            let (_, [s1, s2]) = tangent_stencils(n, 0.5).map_err(|e| e.to_string())?;
            let pts: Vec<usize> = std::iter::once(v)
                .chain(fan.e.iter().copied())
                .chain(fan.f.iter().copied())
                .collect();
            let apply = |w: &[f64]| {
                let mut q = [0.0; 3];
                for (x, &i) in w.iter().zip(&pts) {
                    for k in 0..3 {
                        q[k] += x * p[i][k];
                    }
                }
                q
            };
            (apply(&s1), apply(&s2))
        }
    };
    let c = cross(t1, t2);
    let len = dot(c, c).sqrt();
    if len.is_nan() || len <= PARALLEL_TANGENTS * dot(t1, t1).sqrt() * dot(t2, t2).sqrt() {
        return Err("the limit tangents are parallel".to_owned());
    }
    Ok(c.map(|x| x / len))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
