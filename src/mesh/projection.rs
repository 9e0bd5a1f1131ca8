//! Orthographic projection of a mesh for pictures: shaded, depth-sorted
//! polygons (painter's algorithm), in 2-D screen coordinates. Pure data;
//! drawing is left to the caller (the report's mesh picture figure).
//!
//! The viewer looks from direction `v = (cos e cos a, cos e sin a, sin e)`
//! (azimuth `a`, elevation `e`) towards the origin; screen axes are
//! `right = (-sin a, cos a, 0)` and `up = v x right`. Faces whose normal
//! (Newell's method) points away from the viewer are culled (the mesh is
//! closed and outward oriented); the rest are sorted back to front and shaded
//! `0.25 + 0.75 max(0, n . v)` (a head light).

use super::Mesh;

/// Viewing direction in degrees.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct View {
    /// Azimuth about the z axis, degrees.
    pub azimuth_deg: f64,
    /// Elevation above the xy plane, degrees.
    pub elevation_deg: f64,
}

impl Default for View {
    fn default() -> Self {
        View {
            azimuth_deg: 30.0,
            elevation_deg: 25.0,
        }
    }
}

impl View {
    /// `(right, up, towards_viewer)` unit vectors.
    pub fn axes(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        let v = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        let right = [-a.sin(), a.cos(), 0.0];
        let up = [
            v[1] * right[2] - v[2] * right[1],
            v[2] * right[0] - v[0] * right[2],
            v[0] * right[1] - v[1] * right[0],
        ];
        (right, up, v)
    }
}

/// One visible face on screen.
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectedFace {
    /// Face index in the mesh.
    pub face: usize,
    /// Corner positions on screen.
    pub points: Vec<[f64; 2]>,
    /// Mean depth towards the viewer (larger is closer).
    pub depth: f64,
    /// Brightness in `[0.25, 1]`.
    pub shade: f64,
}

/// A projected mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Projected {
    /// Visible faces, back to front.
    pub faces: Vec<ProjectedFace>,
    /// Screen bounding box of the whole mesh `[xmin, xmax, ymin, ymax]`.
    pub bounds: [f64; 4],
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Projects `mesh` orthographically (see the module docs).
pub fn project(mesh: &Mesh, view: &View) -> Projected {
    project_faces(
        mesh.positions(),
        mesh.face_count(),
        |f| mesh.face_vertices(f).collect(),
        view,
        false,
    )
}

/// Projects an open (or closed) mesh with sharp edges: as [`project`], but
/// two-sided, since the back of an open surface can face the viewer: no
/// face is culled and the shading is `0.25 + 0.75 |n . v|`.
pub fn project_sharp(mesh: &super::sharp::SharpMesh, view: &View) -> Projected {
    project_faces(
        mesh.positions(),
        mesh.face_count(),
        |f| mesh.face_vertices(f).iter().map(|&v| v as usize).collect(),
        view,
        true,
    )
}

/// The projection of the faces `0..face_count` (`face(f)` the vertices of
/// face `f`) over `positions`; `two_sided`: keep the faces turned away from
/// the viewer and shade them by `|n . v|`.
fn project_faces(
    positions: &[[f64; 3]],
    face_count: usize,
    face: impl Fn(usize) -> Vec<usize>,
    view: &View,
    two_sided: bool,
) -> Projected {
    let (right, up, v) = view.axes();
    let screen: Vec<[f64; 2]> = positions
        .iter()
        .map(|p| [dot(p, &right), dot(p, &up)])
        .collect();
    let mut bounds = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for s in &screen {
        bounds[0] = bounds[0].min(s[0]);
        bounds[1] = bounds[1].max(s[0]);
        bounds[2] = bounds[2].min(s[1]);
        bounds[3] = bounds[3].max(s[1]);
    }
    let mut faces = Vec::new();
    for f in 0..face_count {
        let verts: Vec<usize> = face(f);
        // Newell normal
        let mut n = [0.0; 3];
        for (k, &a) in verts.iter().enumerate() {
            let p = positions[a];
            let q = positions[verts[(k + 1) % verts.len()]];
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        let len = dot(&n, &n).sqrt();
        if len == 0.0 {
            continue;
        }
        let mut facing = dot(&n, &v) / len;
        if two_sided {
            facing = facing.abs();
        }
        if facing <= 0.0 && !two_sided {
            continue;
        }
        let depth = verts.iter().map(|&a| dot(&positions[a], &v)).sum::<f64>() / verts.len() as f64;
        faces.push(ProjectedFace {
            face: f,
            points: verts.iter().map(|&a| screen[a]).collect(),
            depth,
            shade: 0.25 + 0.75 * facing,
        });
    }
    faces.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    Projected { faces, bounds }
}

#[cfg(test)]
mod doc_examples {
    //! The example of this private module (not a doctest: the module is not
    //! public).
    use super::*;
    use crate::mesh::generators;

    #[test]
    fn three_faces_of_a_cube_are_visible_back_to_front() {
        let p = project(&generators::cube(), &View::default());
        assert!(p.faces.len() == 3);
        assert!(p.faces.windows(2).all(|w| w[0].depth <= w[1].depth));
    }
}
