//! Property tests of mesh refinement (proptest, modest case counts).

use proptest::prelude::*;
use subdiv_lab::mesh::limit::face_limit_points;
use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};
use subdiv_lab::mesh::refine::{refine, refine_levels};
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::schemes::SchemeKind;

fn base(i: usize) -> Mesh {
    generators::shipped()[i].1.clone()
}

fn scheme(i: usize) -> SchemeKind {
    [
        SchemeKind::Nurds,
        SchemeKind::DooSabin,
        SchemeKind::CcVariant,
    ][i]
}

/// A shipped mesh with random log-uniform knots in [1e-2, 1e2].
fn knotted() -> impl Strategy<Value = Mesh> {
    (0usize..5).prop_flat_map(|i| {
        let m = base(i);
        let h = m.half_edge_count();
        proptest::collection::vec(-2.0f64..2.0, h).prop_map(move |e| {
            let mut m = m.clone();
            m.set_knots(e.iter().map(|x| 10f64.powf(*x)).collect())
                .unwrap();
            m
        })
    })
}

fn chi(m: &Mesh) -> i64 {
    m.vertex_count() as i64 - m.edge_count() as i64 + m.face_count() as i64
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn refinement_keeps_a_valid_closed_manifold(m in knotted(), s in 0usize..3, levels in 1usize..3) {
        let r = refine_levels(&m, scheme(s), levels).unwrap();
        prop_assert!(r.check_invariants().is_ok());
        prop_assert_eq!(chi(&r), chi(&m));
        prop_assert_eq!(r.half_edge_count(), m.half_edge_count() * 4usize.pow(levels as u32));
        // and it is valid when rebuilt from scratch through the OBJ reader
        let (back, _) = parse_obj(&write_obj_string(&r)).unwrap();
        prop_assert_eq!(back.positions(), r.positions());
    }

    /// Affine invariance: refining a moved mesh = moving the refined mesh.
    #[test]
    fn refinement_is_affine_invariant(m in knotted(), s in 0usize..3,
                                      shift in proptest::array::uniform3(-5.0f64..5.0),
                                      scale in 0.1f64..10.0) {
        let mv = |p: &[f64; 3]| [scale * p[0] + shift[0], scale * p[1] - shift[1] * 0.5 + shift[2], scale * p[2] + shift[2]];
        let mut moved = m.clone();
        moved.set_positions(m.positions().iter().map(mv).collect()).unwrap();
        let a = refine(&moved, scheme(s)).unwrap();
        let b = refine(&m, scheme(s)).unwrap();
        for (p, q) in a.positions().iter().zip(b.positions()) {
            let q = mv(q);
            for k in 0..3 {
                prop_assert!((p[k] - q[k]).abs() < 1e-12 * (1.0 + scale * 4.0 + 10.0));
            }
        }
    }

    /// Only ratios matter: scaling every interval leaves the geometry unchanged
    /// (math doc section 2), and the face limit points are invariant.
    #[test]
    fn knot_scaling_and_limit_invariance(m in knotted(), factor in 0.01f64..100.0) {
        let mut scaled = m.clone();
        scaled.set_knots(m.knots().iter().map(|d| d * factor).collect()).unwrap();
        let a = refine(&m, SchemeKind::Nurds).unwrap();
        let b = refine(&scaled, SchemeKind::Nurds).unwrap();
        for (p, q) in a.positions().iter().zip(b.positions()) {
            for k in 0..3 {
                prop_assert!((p[k] - q[k]).abs() < 1e-13);
            }
        }
        let f0 = face_limit_points(&m, SchemeKind::Nurds);
        let f1 = face_limit_points(&a, SchemeKind::Nurds);
        for (p, q) in f0.iter().zip(&f1) {
            for k in 0..3 {
                prop_assert!((p[k] - q[k]).abs() < 1e-13);
            }
        }
    }
}
