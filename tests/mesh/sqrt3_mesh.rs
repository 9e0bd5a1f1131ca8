//! sqrt(3) refinement of closed triangle meshes (`mesh::tri_schemes`, math
//! doc section 21) against a reference step on the triangle list: moved old
//! vertices, face centroids, the flipped triangles; the limit stencil is
//! invariant under refinement.

use super::butterfly_mesh::{meshes, Tris, ROUTE_RTOL};
use std::collections::HashSet;
use std::f64::consts::PI;
use subdiv_lab::mesh::builtin::mesh_rules;
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::schemes::SchemeKind;

fn close(a: [f64; 3], b: [f64; 3], scale: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= ROUTE_RTOL * scale)
}

fn scale(m: &Mesh) -> f64 {
    m.positions()
        .iter()
        .flatten()
        .fold(0.0f64, |s, x| s.max(x.abs()))
}

/// Planted: the flipped triangle written `(a, V + f, V + g)` (reversed) or
/// `alpha_n = (4 - cos(2 pi / n)) / 9` fails here.
#[test]
fn one_step_matches_the_reference_on_every_shipped_triangle_mesh() {
    let rules = mesh_rules(SchemeKind::Sqrt3, None).unwrap();
    for (name, mesh) in meshes() {
        let t = Tris::of(&mesh);
        let p = mesh.positions();
        let nv = mesh.vertex_count();
        let s = scale(&mesh);
        let r = rules.refine(&mesh).unwrap();
        r.check_invariants().unwrap();
        rules.refine(&r).unwrap().check_invariants().unwrap();
        assert_eq!(r.face_count(), 3 * mesh.face_count(), "{name}");
        assert_eq!(r.vertex_count(), nv + mesh.face_count(), "{name}");
        for v in 0..nv {
            let nb = t.ring(v, t.opp.keys().find(|(a, _)| *a == v).unwrap().1);
            let n = nb.len() as f64;
            let a = (4.0 - 2.0 * (2.0 * PI / n).cos()) / 9.0;
            let mut want = [0.0; 3];
            for k in 0..3 {
                want[k] = (1.0 - a) * p[v][k] + a / n * nb.iter().map(|&q| p[q][k]).sum::<f64>();
            }
            assert!(close(want, r.positions()[v], s), "{name}: vertex {v}");
        }
        // every face point is a centroid; the triangles are (a, face across, face)
        let mut face_of_point = Vec::new();
        for (f, tri) in t.tris.iter().enumerate() {
            let mut c = [0.0; 3];
            for k in 0..3 {
                c[k] = tri.iter().map(|&q| p[q][k]).sum::<f64>() / 3.0;
            }
            assert!(close(c, r.positions()[nv + f], s), "{name}: face {f}");
            face_of_point.push(*tri);
        }
        let key = |tri: [usize; 3]| -> ([usize; 3], [usize; 3], usize) {
            let mut a = face_of_point[tri[0]];
            let mut b = face_of_point[tri[1]];
            a.sort();
            b.sort();
            (a, b, tri[2])
        };
        let mut want = HashSet::new();
        for tri in &t.tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let other = [b, a, t.opp[&(b, a)]];
                // (a, centroid across, centroid of tri), keyed from the face points
                want.insert(key([pos(&t, &other), pos(&t, tri), a]));
            }
        }
        let mut got = HashSet::new();
        for f in 0..r.face_count() {
            let v: Vec<usize> = r.face_vertices(f).collect();
            let i = v.iter().position(|&x| x < nv).unwrap();
            let (a, g, h) = (v[i], v[(i + 1) % 3] - nv, v[(i + 2) % 3] - nv);
            got.insert(key([g, h, a]));
        }
        assert_eq!(got, want, "{name}");
    }
}

/// Index of a triangle (given by any rotation of its corners) in the list.
fn pos(t: &Tris, tri: &[usize; 3]) -> usize {
    let mut s = *tri;
    s.sort();
    t.tris
        .iter()
        .position(|x| {
            let mut y = *x;
            y.sort();
            y == s
        })
        .unwrap()
}

/// The limit stencil `(1 - beta) v + beta / n sum e_i`,
/// `beta = 3 alpha_n / (1 + 3 alpha_n)`, gives the same point before and
/// after a step (it is the left eigenvector of the step). Planted:
/// `beta = 3 alpha_n / (1 + 2 alpha_n)` fails here.
#[test]
fn the_limit_of_a_vertex_does_not_move_under_refinement() {
    let rules = mesh_rules(SchemeKind::Sqrt3, None).unwrap();
    for (name, mesh) in meshes() {
        let once = rules.refine(&mesh).unwrap();
        let a = rules.limit_mesh(&mesh).unwrap();
        let b = rules.limit_mesh(&once).unwrap();
        let s = scale(&mesh);
        for v in 0..mesh.vertex_count() {
            assert!(
                close(a.positions()[v], b.positions()[v], s),
                "{name}: vertex {v}"
            );
        }
    }
    assert!(rules.refine(&generators::cube()).is_err());
}
