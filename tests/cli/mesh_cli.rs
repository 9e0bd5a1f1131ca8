//! The `subdivide` subcommand end to end.

use crate::common;
use common::run;
use std::path::{Path, PathBuf};
fn mesh(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("analysis/meshes")
        .join(format!("{name}.obj"))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn subdivide_writes_mesh_knots_and_stats() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let kout = dir.path().join("out.knots");
    let kin = dir.path().join("in.knots");
    std::fs::write(&kin, "1 2 3.0\n2 1 0.5\n").unwrap();
    let input = mesh("tetrahedron");
    let (code, stdout, stderr) = run(&[
        "subdivide",
        s(&input),
        "--scheme",
        "nurds",
        "--knots",
        s(&kin),
        "--levels",
        "2",
        "-o",
        s(&out),
        "--knots-out",
        s(&kout),
        "--stats",
    ]);
    assert_eq!(code, 0, "{stderr}");
    // tetrahedron: 4 faces -> 4+6+4 = 14 -> 14 + 24 + 12 = 50 faces
    assert!(
        stdout.contains("level 0: faces 4, vertices 4, extraordinary faces 4"),
        "{stdout}"
    );
    assert!(
        stdout.contains("level 1: faces 14, vertices 12, extraordinary faces 8"),
        "{stdout}"
    );
    assert!(
        stdout.contains("level 2: faces 50, vertices 48, extraordinary faces 8"),
        "{stdout}"
    );
    // every ratio printed at level 2 is <= 3/4
    let ratios: Vec<f64> = stdout
        .lines()
        .filter_map(|l| l.split("ratio ").nth(1))
        .filter(|r| *r != "-")
        .map(|r| r.trim().parse().unwrap())
        .collect();
    assert_eq!(ratios.len(), 4 + 8);
    assert!(
        ratios.iter().all(|&r| r <= 0.75 + 1e-6 && r > 0.0),
        "{ratios:?}"
    );
    let (m, _) = subdiv_lab::mesh::obj::parse_obj(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(m.face_count(), 50);
    let ktext = std::fs::read_to_string(&kout).unwrap();
    assert_eq!(
        ktext.lines().filter(|l| !l.starts_with('#')).count(),
        m.half_edge_count()
    );
    // no temporary files left behind
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");
}

#[test]
fn limit_output_and_stdout() {
    let (code, stdout, stderr) = run(&[
        "subdivide",
        s(&mesh("cube")),
        "--scheme",
        "cc-variant",
        "--levels",
        "2",
        "--limit",
        "-o",
        "-",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let (m, _) = subdiv_lab::mesh::obj::parse_obj(&stdout).unwrap();
    m.check_invariants().unwrap();
    // 2 levels of the cube: 98 faces become 98 limit points, plus one per regular vertex
    assert!(m.vertex_count() > 98);
}

#[test]
fn errors_leave_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let bad_knots = dir.path().join("bad.knots");
    std::fs::write(&bad_knots, "1 2 1.0\n1 2 2.0\n").unwrap();
    let cube = mesh("cube");
    let (code, _, stderr) = run(&[
        "subdivide",
        s(&cube),
        "--scheme",
        "nurds",
        "--knots",
        s(&bad_knots),
        "-o",
        s(&out),
    ]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("line 2") && stderr.contains("already given on line 1"),
        "{stderr}"
    );
    assert!(!out.exists());

    let open = dir.path().join("open.obj");
    std::fs::write(&open, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    // (the Doo-Sabin family, Catmull-Clark and Loop refine open meshes; adjustable-cc does not)
    let (code, _, stderr) = run(&[
        "subdivide",
        s(&open),
        "--scheme",
        "adjustable-cc",
        "--c",
        "0.3",
        "-o",
        s(&out),
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("boundary not supported"), "{stderr}");
    assert!(!out.exists());

    // an unwritable target: a directory that does not exist
    let nowhere = dir.path().join("missing/dir/out.obj");
    let kout = dir.path().join("k.knots");
    let (code, _, stderr) = run(&[
        "subdivide",
        s(&cube),
        "--scheme",
        "nurds",
        "-o",
        s(&nowhere),
        "--knots-out",
        s(&kout),
    ]);
    // Refused before anything is written (exit 2, the directory named).
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("does not exist"), "{stderr}");
    assert!(
        !kout.exists(),
        "no partial output when one of two writes fails"
    );

    for (args, needle) in [
        (vec!["--scheme", "midedge"], "unknown scheme"),
        (
            vec!["--scheme", "doo-sabin", "--knots", s(&bad_knots), "--stats"],
            "takes no knot intervals",
        ),
        (
            vec!["--scheme", "nurds", "--default-interval", "-1", "--stats"],
            "--default-interval",
        ),
        (vec!["--scheme", "nurds"], "nothing to do"),
        (
            vec!["--scheme", "nurds", "--levels", "40", "--stats"],
            "half-edges",
        ),
    ] {
        let mut full = vec!["subdivide", s(&cube)];
        full.extend(args);
        let (code, _, stderr) = run(&full);
        assert_eq!(code, 2, "{full:?}: {stderr}");
        assert!(stderr.contains(needle), "{full:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "one-line error: {stderr}");
    }
}
