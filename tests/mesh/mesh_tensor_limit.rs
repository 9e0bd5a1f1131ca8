//! Tensor-product grids (math doc section 2) and limit points (math doc section 5).

// Grid loops mirror the (i, j) subscripts of the formulas.
#![allow(clippy::needless_range_loop)]

use subdiv_lab::bspline::refine_grid;
use subdiv_lab::mesh::limit::{face_limit_points, limit_mesh, regular_patch, regular_vertex_limit};
use subdiv_lab::mesh::refine::{face_point, refine, refine_levels};
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::schemes::SchemeKind;

const M: usize = 7;
const K: usize = 5;

fn tensor_knots() -> (Vec<f64>, Vec<f64>) {
    let d = vec![1.0, 2.5, 0.4, 1.7, 0.9, 3.1, 0.6];
    let e = vec![0.3, 1.1, 2.0, 0.5, 1.4];
    (d, e)
}

/// A torus grid with tensor-product knots: vertex (i, j) carries d_i along u and e_j along v.
fn tensor_torus() -> (Mesh, Vec<f64>, Vec<f64>) {
    let mut m = generators::torus(M, K, 3.0, 1.0);
    let (d, e) = tensor_knots();
    let id = |i: usize, j: usize| (i % M) * K + (j % K);
    for i in 0..M {
        for j in 0..K {
            for (a, val) in [
                (id(i + 1, j), d[i]),
                (id(i + M - 1, j), d[i]),
                (id(i, j + 1), e[j]),
                (id(i, j + K - 1), e[j]),
            ] {
                let h = m.find_half_edge(id(i, j), a).unwrap();
                m.set_knot(h, val).unwrap();
            }
        }
    }
    (m, d, e)
}

fn grid_of(m: &Mesh) -> Vec<Vec<[f64; 3]>> {
    (0..M)
        .map(|i| (0..K).map(|j| m.positions()[i * K + j]).collect())
        .collect()
}

/// New vertex of corner c of face (i, j) and its refined grid position.
fn corner_grid_pos(i: usize, j: usize, c: usize) -> (usize, usize) {
    match c {
        0 => (2 * i, 2 * j),
        1 => (2 * i + 1, 2 * j),
        2 => (2 * i + 1, 2 * j + 1),
        _ => (2 * i, 2 * j + 1),
    }
}

#[test]
fn tensor_grid_step_is_biquadratic_refinement() {
    let (m, d, e) = tensor_torus();
    let r = refine(&m, SchemeKind::Nurds).unwrap();
    let (g, d2, e2) = refine_grid(&grid_of(&m), &d, &e, true, true).unwrap();
    let mut where_ = vec![(0, 0); r.vertex_count()];
    for i in 0..M {
        for j in 0..K {
            let f = i * K + j;
            for (c, h) in m.face_corners(f).enumerate() {
                let (a, b) = corner_grid_pos(i, j, c);
                where_[h] = (a, b);
                let p = r.positions()[h];
                for k in 0..3 {
                    assert!(
                        (p[k] - g[a][b][k]).abs() < 1e-14,
                        "face ({i},{j}) corner {c}"
                    );
                }
            }
        }
    }
    // the refined intervals are tensor-product again: d(X -> u-neighbour) = d'_a, etc.
    for h in 0..r.half_edge_count() {
        let (a, b) = where_[r.origin(h)];
        let (a2, b2) = where_[r.target(h)];
        let expected = if b == b2 { d2[a] } else { e2[b] };
        assert!(a == a2 || b == b2);
        assert_eq!(r.knot(h), expected, "half-edge {h}");
    }
}

/// Tensor knots on a region only: faces none of whose edges were perturbed
/// still follow biquadratic refinement; the perturbed ones do not.
#[test]
fn tensor_region_of_a_perturbed_mesh() {
    let (mut m, d, e) = tensor_torus();
    let centre = 3 * K + 2;
    for h in m.vertex_ring(centre) {
        let v = m.knot(h) * 1.9;
        m.set_knot(h, v).unwrap();
    }
    let r = refine(&m, SchemeKind::Nurds).unwrap();
    let (g, _, _) = refine_grid(&grid_of(&m), &d, &e, true, true).unwrap();
    let (mut same, mut differ) = (0, 0);
    for i in 0..M {
        for j in 0..K {
            let f = i * K + j;
            let touches = m.face_vertices(f).any(|v| v == centre);
            let worst = m
                .face_corners(f)
                .enumerate()
                .map(|(c, h)| {
                    let (a, b) = corner_grid_pos(i, j, c);
                    (0..3)
                        .map(|k| (r.positions()[h][k] - g[a][b][k]).abs())
                        .fold(0.0, f64::max)
                })
                .fold(0.0, f64::max);
            if touches {
                assert!(worst > 1e-3, "perturbed face ({i},{j}) unchanged");
                differ += 1;
            } else {
                assert!(worst < 1e-14, "face ({i},{j}): {worst:e}");
                same += 1;
            }
        }
    }
    assert_eq!((same, differ), (M * K - 4, 4));
}

/// The face point is invariant: the F-face child has the same limit point.
#[test]
fn face_limit_points_are_invariant() {
    for scheme in [
        SchemeKind::Nurds,
        SchemeKind::DooSabin,
        SchemeKind::CcVariant,
    ] {
        let (m, _, _) = tensor_torus();
        let mut m2 = generators::truncated_icosahedron();
        let k: Vec<f64> = (0..m2.half_edge_count())
            .map(|h| 0.2 + (h * 37 % 11) as f64 * 0.3)
            .collect();
        m2.set_knots(k).unwrap();
        for mesh in [m, m2] {
            let f0 = face_limit_points(&mesh, scheme);
            let r = refine_levels(&mesh, scheme, 3).unwrap();
            let f3 = face_limit_points(&r, scheme);
            for (f, p) in f0.iter().enumerate() {
                for k in 0..3 {
                    assert!((p[k] - f3[f][k]).abs() < 1e-13, "{scheme} face {f}");
                }
            }
        }
    }
}

/// At a regular vertex the biquadratic evaluation at the span midpoint equals
/// the limit point of the vertex's V-face (an independent route), and further
/// refinement converges to it.
#[test]
fn regular_vertex_limit_is_the_v_face_limit() {
    let mut cases: Vec<(SchemeKind, Mesh)> = Vec::new();
    cases.push((SchemeKind::Nurds, tensor_torus().0));
    for scheme in [
        SchemeKind::Nurds,
        SchemeKind::DooSabin,
        SchemeKind::CcVariant,
    ] {
        // refined twice: most vertices are regular (uniform knots are tensor)
        cases.push((
            scheme,
            refine_levels(&generators::truncated_icosahedron(), scheme, 2).unwrap(),
        ));
        cases.push((
            scheme,
            refine_levels(&generators::cube(), scheme, 2).unwrap(),
        ));
    }
    let mut regular = 0;
    for (scheme, mesh) in cases {
        let r1 = refine(&mesh, scheme).unwrap();
        let base = mesh.face_count() + mesh.edge_count();
        let deep = refine_levels(&r1, scheme, 4).unwrap();
        for v in 0..mesh.vertex_count() {
            let Some(p) = regular_vertex_limit(&mesh, v, scheme) else {
                continue;
            };
            regular += 1;
            let vf = base + v;
            let q = face_point(&r1, vf, scheme);
            for k in 0..3 {
                assert!(
                    (p[k] - q[k]).abs() < 1e-13,
                    "{scheme} vertex {v}: {p:?} vs {q:?}"
                );
            }
            // after 4 more steps the V-face corners are within (3/4)^4 of the initial spread
            let d0 = r1
                .face_vertices(vf)
                .map(|w| dist(&r1.positions()[w], &p))
                .fold(0.0, f64::max);
            let d6 = deep
                .face_vertices(vf)
                .map(|w| dist(&deep.positions()[w], &p))
                .fold(0.0, f64::max);
            assert!(d6 <= 0.75f64.powi(4) * d0 + 1e-13, "{d6} vs {d0}");
        }
    }
    assert!(regular > 500, "{regular}");
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[test]
fn regularity_needs_tensor_knots_and_quads() {
    let (mut m, _, _) = tensor_torus();
    assert!(regular_patch(&m, 0, false).is_some());
    // break the tensor structure near vertex 0
    let h = m.find_half_edge(0, 1).unwrap();
    m.set_knot(h, 42.0).unwrap();
    assert!(regular_patch(&m, 0, false).is_none());
    assert!(regular_patch(&m, 0, true).is_some()); // uniform schemes ignore knots
                                                   // valence 3 vertices of the cube are never regular
    let cube = generators::cube();
    assert!((0..8).all(|v| regular_patch(&cube, v, true).is_none()));
}

#[test]
fn limit_mesh_is_a_closed_manifold_on_the_limit_surface() {
    for scheme in [SchemeKind::Nurds, SchemeKind::CcVariant] {
        let m = refine_levels(&generators::truncated_icosahedron(), scheme, 2).unwrap();
        let lm = limit_mesh(&m, scheme).unwrap();
        lm.check_invariants().unwrap();
        let regular = (0..m.vertex_count())
            .filter(|&v| regular_vertex_limit(&m, v, scheme).is_some())
            .count();
        assert_eq!(lm.vertex_count(), m.face_count() + regular);
        // Euler characteristic of the sphere is preserved
        let chi = lm.vertex_count() as i64 - lm.edge_count() as i64 + lm.face_count() as i64;
        assert_eq!(chi, 2);
        // first F vertices are the face limit points
        let fl = face_limit_points(&m, scheme);
        assert_eq!(&lm.positions()[..m.face_count()], &fl[..]);
    }
}
