//! Mesh validation errors, OBJ reading and writing, the knot-interval sidecar.

use subdiv_lab::mesh::knot_file::{apply_knot_text, write_knots_string};
use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};
use subdiv_lab::mesh::refine::refine_levels;
use subdiv_lab::mesh::{generators, Mesh, MeshError};
use subdiv_lab::schemes::SchemeKind;

const TET_V: &str = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\n";

fn err(text: &str) -> MeshError {
    parse_obj(text).unwrap_err()
}

#[test]
fn bad_meshes_name_the_element() {
    // boundary: a tetrahedron with one face missing
    let e = err(&format!("{TET_V}f 1 2 3\nf 1 4 2\nf 1 3 4\n"));
    assert!(matches!(e, MeshError::BoundaryEdge { .. }), "{e}");
    assert!(e.to_string().contains("boundary not supported"));
    // inconsistent orientation: one face flipped
    let e = err(&format!("{TET_V}f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 3 4\n"));
    assert!(
        matches!(e, MeshError::InconsistentOrientation { .. }),
        "{e}"
    );
    // non-manifold edge: three triangles on edge 1-2 (plus closing faces)
    let e = err("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
    assert_eq!(
        e,
        MeshError::NonManifoldEdge {
            u: 0,
            v: 1,
            faces: 3
        }
    );
    assert!(e.to_string().contains("OBJ 1-2"));
    // non-manifold vertex: two tetrahedra sharing one vertex
    let two = format!(
        "{TET_V}v 3 3 3\nv 3 1 1\nv 1 3 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\nf 1 5 6\nf 1 6 7\nf 1 7 5\nf 5 7 6\n"
    );
    let e = err(&two);
    assert_eq!(e, MeshError::NonManifoldVertex { vertex: 0, fans: 2 });
    // degenerate faces
    let e = err(&format!("{TET_V}f 1 2\n"));
    assert_eq!(
        e,
        MeshError::TooFewCorners {
            face: 0,
            corners: 2
        }
    );
    let e = err(&format!("{TET_V}f 1 2 2 3\n"));
    assert_eq!(e, MeshError::RepeatedVertex { face: 0, vertex: 1 });
    // dangling index
    let e = err(&format!("{TET_V}f 1 2 9\n"));
    assert_eq!(
        e,
        MeshError::DanglingIndex {
            face: 0,
            index: 8,
            vertex_count: 4
        }
    );
    // non-finite coordinates
    let e = err("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n");
    assert!(
        matches!(e, MeshError::NonFiniteCoordinate { vertex: 0, .. }),
        "{e}"
    );
    let e = err("v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n");
    assert!(
        matches!(e, MeshError::NonFiniteCoordinate { vertex: 1, .. }),
        "{e}"
    );
    // a pillow (two quads glued along all edges) is closed but has valence-2 vertices
    let e = err("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 4 3 2 1\n");
    assert_eq!(
        e,
        MeshError::LowValence {
            vertex: 0,
            valence: 2
        }
    );
    // isolated vertex, empty mesh
    let e = err(&format!(
        "{TET_V}v 5 5 5\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n"
    ));
    assert_eq!(e, MeshError::IsolatedVertex { vertex: 4 });
    assert_eq!(err(TET_V), MeshError::Empty);
    // syntax
    assert!(matches!(
        err("v 1 2\n"),
        MeshError::ObjSyntax { line: 1, .. }
    ));
    assert!(matches!(
        err("v 1 2 x\n"),
        MeshError::ObjSyntax { line: 1, .. }
    ));
    assert!(matches!(
        err(&format!("{TET_V}f 1 0 2\n")),
        MeshError::ObjSyntax { line: 5, .. }
    ));
    assert!(matches!(
        err(&format!("{TET_V}f -5 1 2\n")),
        MeshError::ObjSyntax { line: 5, .. }
    ));
    assert!(matches!(
        err(&format!("{TET_V}f a 1 2\n")),
        MeshError::ObjSyntax { line: 5, .. }
    ));
    // the same tetrahedron, correct, parses
    parse_obj(&format!("{TET_V}f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n")).unwrap();
}

#[test]
fn obj_forms_and_ignored_statements() {
    let text = "# comment\nmtllib x.mtl\no tet\nv 1 1 1\nv 1 -1 -1 1.0\nv -1 1 -1\nv -1 -1 1\n\
                vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl m\n\
                f 1/1 2/1 3/1\nf 1//1 4//1 2//1\nf -4/1/1 -2/1/1 -1/1/1 # trailing comment\nf 2 4 3\n";
    let (m, info) = parse_obj(text).unwrap();
    assert_eq!(m.face_count(), 4);
    assert_eq!(info.ignored_statements, 7);
    assert_eq!(
        info.ignored_keywords,
        ["mtllib", "o", "vt", "vn", "g", "s", "usemtl"]
    );
    assert_eq!(m.face_vertices(2).collect::<Vec<_>>(), vec![0, 2, 3]);
}

#[test]
fn obj_round_trip_is_exact() {
    for (name, mesh) in generators::shipped() {
        let refined = refine_levels(&mesh, SchemeKind::Nurds, 2).unwrap();
        for m in [mesh, refined] {
            let text = write_obj_string(&m);
            let (back, info) = parse_obj(&text).unwrap();
            assert_eq!(info.ignored_statements, 0);
            assert_eq!(back.positions(), m.positions(), "{name}");
            assert_eq!(back.face_count(), m.face_count());
            for f in 0..m.face_count() {
                assert!(back.face_vertices(f).eq(m.face_vertices(f)));
            }
            assert_eq!(write_obj_string(&back), text);
        }
    }
}

fn cube() -> Mesh {
    generators::cube()
}

#[test]
fn knot_file_errors_name_the_line() {
    let mut m = cube();
    let before = m.clone();
    // cube edge 1->2 exists (face 1 2 6 5 has 1->2); 1->8 does not
    let e = apply_knot_text(&mut m, "1 2 2.0\n\n1 8 1.0\n", 1.0).unwrap_err();
    assert_eq!(
        e,
        MeshError::UnknownEdge {
            line: 3,
            u: 1,
            v: 8
        }
    );
    let e = apply_knot_text(&mut m, "1 2 2.0\n# c\n1 2 3.0\n", 1.0).unwrap_err();
    assert_eq!(
        e,
        MeshError::DuplicateEdge {
            line: 3,
            u: 1,
            v: 2,
            first_line: 1
        }
    );
    for bad in ["0", "-1.5", "nan", "inf"] {
        let e = apply_knot_text(&mut m, &format!("2 1 1\n1 2 {bad}\n"), 1.0).unwrap_err();
        assert!(
            matches!(
                e,
                MeshError::KnotValue {
                    line: 2,
                    u: 1,
                    v: 2,
                    ..
                }
            ),
            "{bad}: {e}"
        );
    }
    for bad in ["1 2", "1 2 3 4", "0 2 1", "x 2 1", "1 2 one"] {
        let e = apply_knot_text(&mut m, &format!("{bad}\n"), 1.0).unwrap_err();
        assert!(
            matches!(e, MeshError::KnotSyntax { line: 1, .. }),
            "{bad}: {e}"
        );
    }
    let e = apply_knot_text(&mut m, "", 0.0).unwrap_err();
    assert!(matches!(e, MeshError::InvalidDefaultInterval { .. }));
    assert_eq!(m, before, "a failed knot file leaves the mesh unchanged");
}

#[test]
fn knot_file_defaults_and_round_trip() {
    let mut m = cube();
    apply_knot_text(&mut m, "1 2 2.5\n2 1 0.125\n", 0.75).unwrap();
    let h = m.find_half_edge(0, 1).unwrap();
    assert_eq!(m.knot(h), 2.5);
    assert_eq!(m.knot(m.twin(h)), 0.125);
    assert_eq!(m.knots().iter().filter(|&&d| d == 0.75).count(), 22);
    // refined knots written out and read back onto the refined mesh are identical
    let r = refine_levels(&m, SchemeKind::Nurds, 2).unwrap();
    let text = write_knots_string(&r);
    let mut r2 = r.clone();
    apply_knot_text(&mut r2, &text, 99.0).unwrap();
    assert_eq!(r2.knots(), r.knots());
    // ... and with the mesh written and re-read as OBJ too
    let (mut r3, _) = parse_obj(&write_obj_string(&r)).unwrap();
    apply_knot_text(&mut r3, &text, 99.0).unwrap();
    assert_eq!(r3.knots(), r.knots());
}

#[test]
fn programmatic_knots_are_validated() {
    let mut m = cube();
    assert!(matches!(
        m.set_knot(0, -1.0),
        Err(MeshError::InvalidInterval { .. })
    ));
    assert!(matches!(
        m.set_knots(vec![1.0; 3]),
        Err(MeshError::CountMismatch { .. })
    ));
    let mut k = vec![1.0; m.half_edge_count()];
    k[5] = f64::NAN;
    assert!(matches!(
        m.set_knots(k),
        Err(MeshError::InvalidInterval { .. })
    ));
    let p = vec![[0.0; 3]; 8];
    let mut p2 = p.clone();
    p2[3][1] = f64::INFINITY;
    assert!(m.set_positions(p).is_ok());
    assert!(matches!(
        m.set_positions(p2),
        Err(MeshError::NonFiniteCoordinate { vertex: 3, .. })
    ));
}
