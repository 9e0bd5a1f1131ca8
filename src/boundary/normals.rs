//! Limit normals at the vertices of a [`SharpMesh`] (math doc section 18.6).
//!
//! ```text
//! smooth, dart:          n = t_1 x t_2, the limit tangent masks of the ring
//!                        Loop:  t_1 = sum cos(2 pi i/n) e_i,  t_2 = the same with sin
//!                        Catmull-Clark: the tangent stencils of
//!                        schemes::catmull_clark::limit::tangent_stencils (c = 1/2)
//! boundary, corner:      n = t_1 x t_2 with t_k the left eigenvectors of the
//!                        subdominant eigenvalues of the vertex's local matrix
//!                        (SectorConfig, standard rules), applied to the
//!                        neighbourhood v, e_0.., f_0.. (boundary::analysis::limit_frame)
//! ```
//!
//! The ring `e_i` (and `f_i` for Catmull-Clark) runs in the order of the
//! faces (face `i` is `v, e_i, f_i, e_(i+1)`), from boundary edge to
//! boundary edge at boundary and corner vertices. An interior crease vertex
//! has one tangent plane per sector and no vertex normal. A left eigenvector's sign is
//! arbitrary, so a sector normal is turned to the side of the control fan
//! `sum_i (e_i - v) x (e_(i+1) - v)` (the faces' orientation); the smooth
//! masks' `t_1 x t_2` has that orientation by construction. The standard
//! rules do not depend on a corner's angle, so a corner's configuration is
//! built with [`CORNER_ANGLE_DEGREES`]. The vertex rule is the one of the
//! level evaluated, as for the limit positions (math doc section 17): at
//! semi-sharp features and darts the normal is OpenSubdiv's approximation.

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

/// The unit limit normal of every vertex of `mesh` under `scheme` (module
/// docs), indexed like the vertices. The mesh is all quads (Catmull-Clark)
/// or all triangles (Loop). Fails, naming the vertex, at a vertex with more
/// than two sharp edges, an interior crease or an interior corner (no
/// single tangent plane), at
/// an open fan without sharp boundary edges (`--boundary none`), when the
/// honest class of the configuration's subdominant eigenvalues gives no
/// pair of tangent eigenvectors (for example Catmull-Clark's boundary
/// vertex with one face: `--boundary edge-and-corner` makes it a corner,
/// which has one), or when the
/// tangents are parallel.
pub fn limit_normals(mesh: &SharpMesh, scheme: SdcScheme) -> Result<Vec<[f64; 3]>, NormalError> {
    let mut cache: HashMap<(VertexKind, Vec<usize>), SectorAnalysis> = HashMap::new();
    (0..mesh.vertex_count())
        .map(|v| vertex_normal(mesh, scheme, v, &mut cache))
        .collect()
}

/// The ordered neighbourhood of `v`: the ring `e_i`, the far corners `f_i`
/// (Catmull-Clark) and whether the fan is open.
struct Fan {
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
    for &f in mesh.vertex_faces(v) {
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
    Ok(Fan { e, f, open })
}

fn vertex_normal(
    mesh: &SharpMesh,
    scheme: SdcScheme,
    v: usize,
    cache: &mut HashMap<(VertexKind, Vec<usize>), SectorAnalysis>,
) -> Result<[f64; 3], NormalError> {
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
    let k = fan.e.len() - usize::from(fan.open);
    let (kind, faces) = match (fan.open, rule) {
        (false, Rule::Smooth | Rule::Dart) => {
            return smooth_normal(p, scheme, v, &fan).map_err(err);
        }
        (true, Rule::Crease) if sharp == [0, k] => (VertexKind::Boundary, vec![k]),
        (true, Rule::Corner) if sharp == [0, k] => (VertexKind::Corner, vec![k]),
        (false, Rule::Crease) => {
            return Err(err(
                "an interior crease vertex has one limit tangent plane per sector (the surface has a kink there): no single vertex normal"
                    .to_owned(),
            ));
        }
        (open, rule) => {
            let place = if open { "a boundary" } else { "an interior" };
            return Err(err(format!(
                "{place} vertex with the {rule:?} rule and {} sharp edges has no single limit tangent plane",
                sharp.len()
            )));
        }
    };
    let angle = (kind == VertexKind::Corner).then_some(CORNER_ANGLE_DEGREES);
    let key = (kind, faces.clone());
    if !cache.contains_key(&key) {
        let c = SectorConfig::new(scheme, kind, &faces, angle, RuleSet::Standard)
            .map_err(|e| err(e.to_string()))?;
        let a = analyze_sector(&c).map_err(|e| err(e.to_string()))?;
        cache.insert(key.clone(), a);
    }
    let a = &cache[&key];
    let mut points = vec![p[v]];
    points.extend(fan.e.iter().map(|&i| p[i]));
    points.extend(fan.f.iter().map(|&i| p[i]));
    let (_, n) = limit_frame(a, &points).ok_or_else(|| {
        err(format!(
            "the {} has no pair of tangent eigenvectors (subdominant class {}) or its limit tangents are parallel",
            a.configuration,
            a.subdominant.class.name()
        ))
    })?;
    let c = control_fan(p, v, &fan);
    let s = if dot(n, c) < 0.0 { -1.0 } else { 1.0 };
    Ok(n.map(|x| s * x))
}

/// `sum_i (e_i - v) x (e_(i+1) - v)` over the faces of the fan.
fn control_fan(p: &[[f64; 3]], v: usize, fan: &Fan) -> [f64; 3] {
    let n = fan.e.len();
    let faces = if fan.open { n - 1 } else { n };
    let d = |a: usize| sub(p[a], p[v]);
    let mut s = [0.0; 3];
    for i in 0..faces {
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
