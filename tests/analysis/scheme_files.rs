//! Scheme files (`--scheme-file`): the shipped restatements of Catmull-Clark
//! and Loop give the built-ins' verdicts, matrices and sweep rows.

use crate::common;
use common::run;

const CC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/analysis/schemes/catmull-clark.toml"
);
const LOOP: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/schemes/loop.toml");

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .flat_map(|z| z.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect()
}

/// `analyze --json`: the same class, curvature verdict and spectrum (to
/// 1e-12: the file's one-ring differs from the built-in's by rounding).
#[test]
fn analyze_gives_the_builtin_verdicts() {
    for (file, builtin) in [(CC, "catmull-clark"), (LOOP, "loop")] {
        for n in ["3", "5", "8"] {
            let a = json(&["analyze", "--scheme-file", file, "--valence", n, "--json"]);
            let b = json(&["analyze", "--scheme", builtin, "--valence", n, "--json"]);
            assert_eq!(
                a["subdominant"]["class"], b["subdominant"]["class"],
                "{builtin} {n}"
            );
            assert_eq!(
                a["curvature"]["verdict"], b["curvature"]["verdict"],
                "{builtin} {n}"
            );
            let (ea, eb) = (numbers(&a["eigenvalues"]), numbers(&b["eigenvalues"]));
            assert_eq!(ea.len(), eb.len());
            for (x, y) in ea.iter().zip(&eb) {
                assert!((x - y).abs() < 1e-12, "{builtin} {n}: {x} vs {y}");
            }
            assert_eq!(
                a["input"]["scheme"],
                if builtin == "loop" {
                    "loop-file"
                } else {
                    "catmull-clark-file"
                }
            );
        }
    }
}

/// `matrix --exact`: the Catmull-Clark file's rational matrix is the built-in's.
#[test]
fn exact_matrix_is_the_builtins() {
    for n in ["3", "4", "7"] {
        let a = json(&[
            "matrix",
            "--scheme-file",
            CC,
            "--valence",
            n,
            "--exact",
            "--format",
            "json",
        ]);
        let b = json(&[
            "matrix",
            "--scheme",
            "catmull-clark",
            "--valence",
            n,
            "--exact",
            "--format",
            "json",
        ]);
        assert_eq!(a["matrix"], b["matrix"], "n = {n}");
        assert_eq!(a["rows"], b["rows"]);
        assert_eq!(a["scheme"], "catmull-clark-file");
    }
}

/// `sweep --scheme-file`: the built-in's columns and classes, numbers to
/// 1e-12; the file enters the fingerprint, so resuming the built-in's output
/// with the file is refused.
#[test]
fn sweep_runs_the_file_through_the_spec_engine() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("s.toml");
    std::fs::write(
        &spec,
        "name = \"u\"\nscheme = \"catmull-clark\"\nvalences = [3, 4, 5, 6, 9]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\ncurvature = true\neigenvalues = 4\n",
    )
    .unwrap();
    let spec = spec.to_str().unwrap();
    let (c1, a, e1) = run(&["sweep", spec, "--quiet", "--scheme-file", CC]);
    let (c2, b, e2) = run(&["sweep", spec, "--quiet"]);
    assert_eq!((c1, c2), (0, 0), "{e1} {e2}");
    let rows = |t: &str| -> Vec<Vec<String>> {
        t.lines()
            .map(|l| l.split(',').map(str::to_owned).collect())
            .collect()
    };
    let (ra, rb) = (rows(&a), rows(&b));
    assert_eq!(ra[0], rb[0], "the same header");
    assert_eq!(ra.len(), 6);
    for (x, y) in ra[1..].iter().zip(&rb[1..]) {
        assert_eq!(x.len(), y.len());
        for (p, q) in x.iter().zip(y) {
            match (p.parse::<f64>(), q.parse::<f64>()) {
                (Ok(p), Ok(q)) => assert!((p - q).abs() < 1e-12, "{x:?} vs {y:?}"),
                _ => assert_eq!(p, q),
            }
        }
    }
    let out = dir.path().join("o.csv");
    let out = out.to_str().unwrap();
    assert_eq!(run(&["sweep", spec, "--quiet", "--out", out]).0, 0);
    let (code, _, err) = run(&[
        "sweep",
        spec,
        "--quiet",
        "--out",
        out,
        "--resume",
        "--scheme-file",
        CC,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("another spec"), "{err}");
}

fn mesh(name: &str) -> String {
    format!("{}/analysis/meshes/{name}.obj", env!("CARGO_MANIFEST_DIR"))
}

/// `subdivide --scheme-file`: the shipped files refine (and give limit
/// meshes) byte for byte like the built-ins, on quads, on a mesh with
/// pentagons and hexagons, and on triangles.
#[test]
fn subdivide_with_the_shipped_files_is_the_builtins_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.obj"), dir.path().join("b.obj"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let cases = [
        ("cube", CC, "catmull-clark", "2"),
        ("truncated_icosahedron", CC, "catmull-clark", "2"),
        ("torus", CC, "catmull-clark", "1"),
        ("icosahedron", LOOP, "loop", "3"),
        ("triangles/bipyramid_3_12", LOOP, "loop", "2"),
    ];
    let mut differ = Vec::new();
    for (m, file, builtin, levels) in cases {
        for limit in [false, true] {
            let mut x = vec!["subdivide", &mesh(m), "--levels", levels, "-o"]
                .into_iter()
                .map(str::to_owned)
                .collect::<Vec<_>>();
            if limit {
                x.push("--limit".to_owned());
            }
            let args = |out: &str, scheme: &[&str]| -> Vec<String> {
                let mut v = x.clone();
                v.insert(5, out.to_owned());
                v.extend(scheme.iter().map(|s| s.to_string()));
                v
            };
            for (out, scheme) in [(a, ["--scheme", builtin]), (b, ["--scheme-file", file])] {
                let v = args(out, &scheme);
                let v: Vec<&str> = v.iter().map(String::as_str).collect();
                let (code, _, err) = run(&v);
                assert_eq!(code, 0, "{v:?}: {err}");
            }
            let (ta, tb) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
            if ta != tb {
                differ.push(format!("{m} {builtin} limit={limit}"));
            }
        }
    }
    assert!(differ.is_empty(), "outputs differ: {differ:?}");
}

/// A modified file refines as its rule says: every edge and face point is
/// the built-in's bit for bit, and the vertex point of an extraordinary
/// vertex is `s v + e sum e_i (+ f sum f_i)` with the file's weights.
#[test]
fn a_modified_file_moves_the_extraordinary_vertex_as_its_rule_predicts() {
    use subdiv_lab::mesh::builtin::mesh_rules;
    use subdiv_lab::mesh::generators;
    use subdiv_lab::mesh::user::file_rules;
    use subdiv_lab::schemes::{user::SchemeFile, SchemeKind};
    let quad = "name = \"q\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - 2/n\"\nedge = \"1/n^2\"\nface = \"1/n^2\"\n";
    let tri =
        "name = \"t\"\ntopology = \"triangle\"\n[vertex]\nself = \"5/8\"\nedge = \"3/(8*n)\"\n";
    let cases = [
        (
            quad,
            SchemeKind::CatmullClark,
            generators::cube(),
            [1.0 - 2.0 / 3.0, 1.0 / 9.0, 1.0 / 9.0],
        ),
        (
            tri,
            SchemeKind::Loop,
            generators::icosahedron(),
            [5.0 / 8.0, 3.0 / 40.0, 0.0],
        ),
    ];
    for (text, kind, m, [s, e, f]) in cases {
        let mine = file_rules(SchemeFile::parse_shared(text).unwrap())
            .refine(&m)
            .unwrap();
        let theirs = mesh_rules(kind, None).unwrap().refine(&m).unwrap();
        let nv = m.vertex_count();
        assert_eq!(mine.positions()[nv..], theirs.positions()[nv..], "{kind}");
        let p = m.positions();
        for v in 0..nv {
            let ring = m.vertex_ring(v);
            let mut want = p[v].map(|x| s * x);
            for &h in &ring {
                let (en, fd) = (p[m.target(h)], p[m.target(m.next(h))]);
                for k in 0..3 {
                    want[k] += e * en[k];
                    if f != 0.0 {
                        want[k] += f * fd[k];
                    }
                }
            }
            let got = mine.positions()[v];
            let other = theirs.positions()[v];
            for k in 0..3 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-14,
                    "{kind} vertex {v}: {got:?} vs {want:?}"
                );
            }
            assert!(
                (0..3).any(|k| (got[k] - other[k]).abs() > 1e-3),
                "{kind} vertex {v} did not move"
            );
        }
    }
}

/// `subdivide --limit` with a modified file moves every vertex of the cube
/// (valence 3) to `l_v v + l_e sum e_i + l_f sum f_i`, the left eigenvector
/// for 1 that `analyze` computes from the file's one-ring matrix.
#[test]
fn the_limit_stencil_of_a_file_is_the_left_eigenvector_analyze_finds() {
    use subdiv_lab::mesh::{generators, obj};
    let flat = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/flat-cc.toml");
    let a = json(&["analyze", "--scheme-file", flat, "--valence", "3", "--json"]);
    let l: Vec<f64> = a["limit_weights"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(l.len(), 7);
    let (code, out, err) = run(&[
        "subdivide",
        &mesh("cube"),
        "--scheme-file",
        flat,
        "--levels",
        "0",
        "--limit",
        "-o",
        "-",
    ]);
    assert_eq!(code, 0, "{err}");
    let got = obj::parse_obj_data(&out).unwrap().positions;
    let m = generators::cube();
    let p = m.positions();
    for (v, g) in got.iter().enumerate() {
        let mut want = p[v].map(|x| l[0] * x);
        for &h in &m.vertex_ring(v) {
            let (e, f) = (p[m.target(h)], p[m.target(m.next(h))]);
            for k in 0..3 {
                want[k] += l[1] * e[k] + l[4] * f[k];
            }
        }
        for k in 0..3 {
            assert!(
                (g[k] - want[k]).abs() < 1e-9,
                "vertex {v}: {g:?} vs {want:?}"
            );
        }
    }
}
