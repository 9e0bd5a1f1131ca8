//! Catmull-Clark-family mesh refinement: the textbook cube
//! step, agreement with the one-ring matrix of the scheme module for random c,
//! limit positions (invariance under refinement and deep refinement), OBJ
//! round trip through the `subdivide` CLI.

use proptest::prelude::*;
use std::process::Command;
use subdiv_lab::mesh::catmull_clark::{limit_positions, refine_cc, refine_cc_levels};
use subdiv_lab::mesh::{generators, obj, Mesh};
use subdiv_lab::schemes::catmull_clark::{fourier, one_ring_matrix};

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Textbook Catmull-Clark (Catmull and Clark 1978), written independently of
/// the library from the polygon list: face points at centroids, edge points
/// `(v + e + f1 + f2)/4`, vertex points `(Q + 2R + (n - 3)v)/n`. Returns the
/// multiset of new positions.
fn textbook(p: &[[f64; 3]], faces: &[Vec<usize>]) -> Vec<[f64; 3]> {
    let mean = |pts: &[[f64; 3]]| {
        let mut m = [0.0; 3];
        for q in pts {
            for k in 0..3 {
                m[k] += q[k] / pts.len() as f64;
            }
        }
        m
    };
    let fp: Vec<[f64; 3]> = faces
        .iter()
        .map(|f| mean(&f.iter().map(|&v| p[v]).collect::<Vec<_>>()))
        .collect();
    let mut edges: std::collections::BTreeMap<(usize, usize), Vec<usize>> = Default::default();
    for (fi, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            edges.entry((a.min(b), a.max(b))).or_default().push(fi);
        }
    }
    let mut out = Vec::new();
    for (&(a, b), fs) in &edges {
        out.push(mean(&[p[a], p[b], fp[fs[0]], fp[fs[1]]]));
    }
    for v in 0..p.len() {
        let q: Vec<[f64; 3]> = faces
            .iter()
            .enumerate()
            .filter(|(_, f)| f.contains(&v))
            .map(|(i, _)| fp[i])
            .collect();
        let r: Vec<[f64; 3]> = edges
            .keys()
            .filter(|&&(a, b)| a == v || b == v)
            .map(|&(a, b)| mean(&[p[a], p[b]]))
            .collect();
        let n = r.len() as f64;
        let (qm, rm) = (mean(&q), mean(&r));
        let mut x = [0.0; 3];
        for k in 0..3 {
            x[k] = (qm[k] + 2.0 * rm[k] + (n - 3.0) * p[v][k]) / n;
        }
        out.push(x);
    }
    out.extend(fp);
    out
}

fn same_multiset(a: &[[f64; 3]], b: &[[f64; 3]], tol: f64) {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    for x in a {
        let j = (0..b.len())
            .filter(|&j| !used[j])
            .min_by(|&i, &j| dist(x, &b[i]).total_cmp(&dist(x, &b[j])))
            .unwrap();
        assert!(dist(x, &b[j]) < tol, "{x:?} has no partner");
        used[j] = true;
    }
}

fn polygons(m: &Mesh) -> Vec<Vec<usize>> {
    (0..m.face_count())
        .map(|f| m.face_vertices(f).collect())
        .collect()
}

#[test]
fn one_step_on_the_cube_is_the_textbook_mesh() {
    let cube = generators::cube();
    let once = refine_cc(&cube, 0.5).unwrap();
    assert_eq!(once.face_count(), 24);
    assert_eq!(once.vertex_count(), 26);
    assert_eq!(once.edge_count(), 48);
    assert!((0..24).all(|f| once.face_size(f) == 4));
    // Known values on [-1, 1]^3: corners +-5/9, edge points (+-3/4, +-3/4, 0),
    // face points at the face centres.
    for v in 0..8 {
        for k in 0..3 {
            assert!((once.positions()[v][k].abs() - 5.0 / 9.0).abs() < 1e-15);
        }
    }
    let expected = textbook(cube.positions(), &polygons(&cube));
    same_multiset(once.positions(), &expected, 1e-15);
    let face_centres = expected[8 + 12..].to_vec();
    for f in &face_centres {
        assert!((f.iter().map(|x| x.abs()).sum::<f64>() - 1.0).abs() < 1e-15);
    }
}

#[test]
fn n_gon_meshes_become_all_quads_and_match_the_textbook_rules() {
    for (name, m) in generators::shipped() {
        let once = refine_cc(&m, 0.5).unwrap();
        assert_eq!(once.face_count(), m.half_edge_count(), "{name}");
        assert!(
            (0..once.face_count()).all(|f| once.face_size(f) == 4),
            "{name}"
        );
        once.check_invariants().unwrap();
        let expected = textbook(m.positions(), &polygons(&m));
        same_multiset(once.positions(), &expected, 1e-12);
    }
}

/// Gathers the one-ring `[v, e_0.., f_0..]` of vertex `v` of an all-quad mesh
/// (counter-clockwise, as in the scheme module's `PatchLayout`).
fn one_ring(m: &Mesh, v: usize) -> Vec<usize> {
    let ring = m.vertex_ring(v);
    let mut out = vec![v];
    out.extend(ring.iter().map(|&h| m.target(h)));
    out.extend(ring.iter().map(|&h| m.target(m.next(h))));
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    /// Mesh refinement = the one-ring matrix of `schemes::catmull_clark`
    /// (assembled independently) for random c, at vertices of valence 3, 4, 5.
    #[test]
    fn mesh_step_equals_the_one_ring_matrix(c in 0.0f64..=1.0) {
        let ico = refine_cc(&generators::icosahedron(), 0.5).unwrap();
        let next = refine_cc(&ico, c).unwrap();
        let p = ico.positions();
        for v in [0usize, 15, ico.vertex_count() - 1] {
            let idx = one_ring(&ico, v);
            let n = ico.valence(v);
            let s = one_ring_matrix::<f64>(n, &c).unwrap().into_matrix();
            let idx_new = one_ring(&next, v);
            for (row, &target) in idx_new.iter().enumerate() {
                let mut x = [0.0; 3];
                for (col, &src) in idx.iter().enumerate() {
                    for k in 0..3 {
                        x[k] += s[(row, col)] * p[src][k];
                    }
                }
                prop_assert!(dist(&x, &next.positions()[target]) < 1e-13, "v {}, row {}", v, row);
            }
        }
    }

    /// The limit stencil is a left eigenvector for 1: limit positions do not
    /// move under refinement (up to rounding).
    #[test]
    fn limit_positions_are_invariant_under_refinement(c in 0.0f64..=1.0) {
        let m = refine_cc(&generators::tetrahedron(), c).unwrap();
        let l0 = limit_positions(&m, c).unwrap();
        let m2 = refine_cc_levels(&m, c, 2).unwrap();
        let l2 = limit_positions(&m2, c).unwrap();
        for v in 0..m.vertex_count() {
            prop_assert!(dist(&l0[v], &l2[v]) < 1e-13);
        }
    }
}

#[test]
fn limit_positions_agree_with_deep_refinement() {
    // Old vertices keep their index, so vertex v of level k is the image of
    // vertex v. The distance to the limit decays like lambda_1^k (lambda_1 the
    // subdominant eigenvalue at that vertex): check the decay and the size.
    for c in [0.5, 0.3, 0.8] {
        let m = refine_cc(&generators::icosahedron(), c).unwrap();
        let limit = limit_positions(&m, c).unwrap();
        let lam = (3..=5)
            .map(|n| fourier::subdominant(n, c).unwrap())
            .fold(0.0, f64::max);
        let mut prev: Option<f64> = None;
        let mut cur = m.clone();
        for k in 1..=6 {
            cur = refine_cc(&cur, c).unwrap();
            let e = (0..m.vertex_count())
                .map(|v| dist(&cur.positions()[v], &limit[v]))
                .fold(0.0, f64::max);
            if let Some(p) = prev {
                assert!(e <= (lam + 0.02) * p, "c = {c}, level {k}: {e} vs {p}");
            }
            prev = Some(e);
        }
        assert!(
            prev.unwrap() < 2.0 * lam.powi(6),
            "c = {c}: {}",
            prev.unwrap()
        );
    }
}

#[test]
fn limit_positions_need_quads() {
    assert!(limit_positions(&generators::cube(), 0.5).is_ok());
    assert!(limit_positions(&generators::icosahedron(), 0.5).is_err());
    assert!(refine_cc(&generators::cube(), 1.5).is_err());
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).expect("utf8"),
        String::from_utf8(out.stderr).expect("utf8"),
    )
}

#[test]
fn subdivide_cli_for_the_catmull_clark_family() {
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/meshes/cube.obj");
    let (code, out, err) = run(&[
        "subdivide",
        cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "-o",
        "-",
    ]);
    assert_eq!(code, 0, "{err}");
    let (m, _) = obj::parse_obj(&out).unwrap();
    let lib = refine_cc_levels(&generators::cube(), 0.5, 2).unwrap();
    assert_eq!(m.face_count(), 96);
    for (a, b) in m.positions().iter().zip(lib.positions()) {
        assert!(dist(a, b) < 1e-12);
    }
    let (code, out, err) = run(&[
        "subdivide",
        cube,
        "--scheme",
        "adjustable-cc",
        "--c",
        "1/3",
        "--limit",
        "-o",
        "-",
    ]);
    assert_eq!(code, 0, "{err}");
    let (m, _) = obj::parse_obj(&out).unwrap();
    let lib = limit_positions(
        &refine_cc(&generators::cube(), 1.0 / 3.0).unwrap(),
        1.0 / 3.0,
    )
    .unwrap();
    for (a, b) in m.positions().iter().zip(&lib) {
        assert!(dist(a, b) < 1e-12);
    }
    let (code, _, _) = run(&["subdivide", cube, "--scheme", "adjustable-cc", "-o", "-"]);
    assert_eq!(code, 2);
    let (code, _, _) = run(&[
        "subdivide",
        cube,
        "--scheme",
        "catmull-clark",
        "--c",
        "0.3",
        "-o",
        "-",
    ]);
    assert_eq!(code, 2);
}
