//! The shipped meshes (`analysis/meshes/*.obj`) and whole-mesh facts on them:
//! uniform NURDS equals the Catmull-Clark variant; every extraordinary face
//! contracts to its limit point by at least 3/4 per level (Theorem 1).

use std::path::PathBuf;
use subdiv_lab::mesh::limit::{refine_with_stats, LevelStats};
use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};
use subdiv_lab::mesh::refine::{refine, refine_levels};
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::rng::Lcg64;
use subdiv_lab::schemes::SchemeKind;

fn mesh_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("analysis/meshes")
}

/// The files are the generators' output. Set `SUBDIV_LAB_WRITE_MESHES=1` to
/// (re)write them; otherwise they are compared byte for byte.
#[test]
fn shipped_meshes_are_the_generated_ones() {
    let write = std::env::var_os("SUBDIV_LAB_WRITE_MESHES").is_some();
    for (name, mesh) in generators::shipped() {
        let path = mesh_dir().join(format!("{name}.obj"));
        let text = write_obj_string(&mesh);
        if write {
            std::fs::create_dir_all(mesh_dir()).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        let on_disk = std::fs::read_to_string(&path).unwrap();
        let (parsed, _) = parse_obj(&on_disk).unwrap();
        // same topology; positions equal up to the last-bit differences a
        // platform's sin/cos/sqrt may produce
        assert_eq!(parsed.face_count(), mesh.face_count(), "{name}");
        for f in 0..mesh.face_count() {
            assert!(
                parsed.face_vertices(f).eq(mesh.face_vertices(f)),
                "{name} face {f}"
            );
        }
        assert!(max_diff(&parsed, &mesh) < 1e-14, "{name}");
        mesh.check_invariants().unwrap();
        // closed surfaces: Euler characteristic 2 (spheres) or 0 (torus)
        let chi = mesh.vertex_count() as i64 - mesh.edge_count() as i64 + mesh.face_count() as i64;
        assert_eq!(chi, if name == "torus" { 0 } else { 2 }, "{name}");
    }
    let soccer = generators::truncated_icosahedron();
    let sizes: Vec<usize> = (0..soccer.face_count())
        .map(|f| soccer.face_size(f))
        .collect();
    assert_eq!(sizes.iter().filter(|&&n| n == 5).count(), 12);
    assert_eq!(sizes.iter().filter(|&&n| n == 6).count(), 20);
}

fn max_diff(a: &Mesh, b: &Mesh) -> f64 {
    a.positions()
        .iter()
        .zip(b.positions())
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, f64::max)
}

/// Uniform knots: NURDS = Catmull-Clark variant to rounding (coordinates are O(1)).
#[test]
fn uniform_nurds_equals_cc_variant_on_every_shipped_mesh() {
    for (name, mesh) in generators::shipped() {
        for default in [1.0, 0.37] {
            let mut m = mesh.clone();
            m.set_knots(vec![default; m.half_edge_count()]).unwrap();
            let a = refine_levels(&m, SchemeKind::Nurds, 3).unwrap();
            let b = refine_levels(&m, SchemeKind::CcVariant, 3).unwrap();
            assert_eq!(a.face_count(), b.face_count());
            let d = max_diff(&a, &b);
            assert!(d < 1e-14, "{name}: {d:e}");
            a.check_invariants().unwrap();
        }
        // and it differs from original Doo-Sabin wherever a face is not a quad
        let ds = refine(&mesh, SchemeKind::DooSabin).unwrap();
        let cc = refine(&mesh, SchemeKind::CcVariant).unwrap();
        let has_ep = (0..mesh.face_count()).any(|f| mesh.face_size(f) != 4);
        assert_eq!(max_diff(&ds, &cc) > 1e-3, has_ep, "{name}");
    }
}

fn check_contraction(name: &str, stats: &[LevelStats]) -> usize {
    let mut checked = 0;
    for s in stats {
        for e in &s.extraordinary {
            if let Some(r) = e.ratio {
                // Theorem 1: r <= 3/4 exactly; 1e-12 absorbs rounding of distances ~1e-3..1.
                assert!(
                    r <= 0.75 + 1e-12,
                    "{name} level {} face {}: ratio {r}",
                    s.level,
                    e.face
                );
                checked += 1;
            }
        }
    }
    checked
}

#[test]
fn extraordinary_faces_contract_by_three_quarters() {
    let mut state = Lcg64::new(12345u64);
    let mut rnd = move || state.next_f64();
    let mut total = 0;
    for (name, mesh) in generators::shipped() {
        for scheme in [
            SchemeKind::Nurds,
            SchemeKind::DooSabin,
            SchemeKind::CcVariant,
        ] {
            let mut m = mesh.clone();
            if scheme == SchemeKind::Nurds {
                let k = (0..m.half_edge_count())
                    .map(|_| 100f64.powf(2.0 * rnd() - 1.0))
                    .collect();
                m.set_knots(k).unwrap();
            }
            let (_, stats) = refine_with_stats(&m, scheme, 4).unwrap();
            total += check_contraction(name, &stats);
            // the distance really shrinks (a test that could not fail would be useless)
            for s in &stats[1..] {
                for e in &s.extraordinary {
                    assert!(e.distance > 0.0);
                }
            }
        }
    }
    assert!(total > 500, "{total}");
}
