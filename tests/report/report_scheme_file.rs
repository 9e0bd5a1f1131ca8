//! Report specs with `scheme_file`: a scheme file that restates a built-in
//! scheme gives the built-in's numbers in every figure that takes one
//! (configuration tables, spectra, mesh pictures, curvature), read beside the
//! spec.

use std::path::Path;
use std::process::Command;

const CC_FILE: &str = include_str!("../../analysis/schemes/catmull-clark.toml");
const LOOP_FILE: &str = include_str!("../../analysis/schemes/loop.toml");

/// Two configurations per pair: the scheme file, then the built-in it restates.
const SPEC: &str = r#"
name = "files"

[[figure]]
kind = "table"
id = "tab"
configs = [
  { scheme_file = "schemes/cc.toml", valence = 5 },
  { scheme = "catmull-clark", valence = 5 },
  { scheme_file = "schemes/loop.toml", valence = 7 },
  { scheme = "loop", valence = 7 },
]

[[figure]]
kind = "spectrum"
id = "spec"
configs = [
  { scheme_file = "schemes/cc.toml", valence = 3 },
  { scheme = "catmull-clark", valence = 3 },
]

[[figure]]
kind = "mesh-picture"
id = "file-mesh"
mesh = "cube"
scheme_file = "schemes/cc.toml"
levels = 2

[[figure]]
kind = "mesh-picture"
id = "builtin-mesh"
mesh = "cube"
scheme = "catmull-clark"
levels = 2

[[figure]]
kind = "curvature"
id = "file-curv"
seed = 7
scheme_file = "schemes/loop.toml"
valences = [5]
levels = 6

[[figure]]
kind = "curvature"
id = "builtin-curv"
seed = 7
scheme = "loop"
valences = [5]
levels = 6
"#;

fn csv(dir: &Path, name: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join(name)).unwrap();
    text.lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// Every numeric cell of `a` equals `b`'s to `tol` (relative to 1), every
/// other cell is equal, except the columns `skip`.
fn same_rows(a: &[String], b: &[String], header: &[String], skip: &[&str], tol: f64) {
    assert_eq!(a.len(), b.len());
    for ((x, y), h) in a.iter().zip(b).zip(header) {
        if skip.contains(&h.as_str()) {
            continue;
        }
        match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(p), Ok(q)) if p.is_nan() || q.is_nan() => assert_eq!(x, y, "{h}"),
            (Ok(p), Ok(q)) => assert!((p - q).abs() <= tol, "{h}: {p} vs {q}"),
            _ => assert_eq!(x, y, "{h}"),
        }
    }
}

#[test]
fn scheme_files_in_a_report_give_the_builtins_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("spec-dir");
    std::fs::create_dir_all(d.join("schemes")).unwrap();
    std::fs::write(d.join("schemes/cc.toml"), CC_FILE).unwrap();
    std::fs::write(d.join("schemes/loop.toml"), LOOP_FILE).unwrap();
    std::fs::write(d.join("s.toml"), SPEC).unwrap();
    let out = tmp.path().join("out");
    // Run from another directory: the scheme files are found beside the spec.
    let o = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .current_dir(tmp.path())
        .args(["report", "spec-dir/s.toml", "--out", "out", "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    // Configuration table: file row i, built-in row i + 1. The file's weights
    // are evaluated exactly and rounded once, the built-in's in f64: the
    // numbers agree to a few rounding errors. A built-in without knot
    // intervals shows its uniform edge ratios, a file none.
    let tab = csv(&out, "tab.csv");
    let header = tab[0].clone();
    let scheme = header.iter().position(|h| h == "scheme").unwrap();
    assert_eq!(tab[1][scheme], "catmull-clark-file");
    assert_eq!(tab[2][scheme], "catmull-clark");
    for (f, b) in [(1, 2), (3, 4)] {
        same_rows(
            &tab[f],
            &tab[b],
            &header,
            &["config", "label", "scheme", "ratios"],
            1e-12,
        );
    }
    let eig = csv(&out, "tab-eigenvalues.csv");
    let rows = |config: &str| -> Vec<Vec<String>> {
        eig[1..]
            .iter()
            .filter(|r| r[0] == config)
            .cloned()
            .collect()
    };
    for (f, b) in [("0", "1"), ("2", "3")] {
        let (rf, rb) = (rows(f), rows(b));
        assert!(!rf.is_empty());
        assert_eq!(rf.len(), rb.len());
        for (x, y) in rf.iter().zip(&rb) {
            same_rows(x, y, &eig[0], &["config"], 1e-12);
        }
    }
    // The spectrum figure's data: the same eigenvalues for both panels.
    let spec = csv(&out, "spec.csv");
    let panel =
        |p: &str| -> Vec<Vec<String>> { spec[1..].iter().filter(|r| r[0] == p).cloned().collect() };
    let (p0, p1) = (panel("0"), panel("1"));
    assert!(!p0.is_empty() && p0.len() == p1.len());
    for (x, y) in p0.iter().zip(&p1) {
        same_rows(x, y, &spec[0], &["config", "label"], 1e-12);
    }
    // Mesh refinement with the file's rules is the built-in's, bit for bit:
    // the report writes a CSV with the bytes of an earlier figure's once, and
    // the built-in's figure names the file's.
    assert!(csv(&out, "file-mesh.csv").len() > 100);
    assert!(!out.join("builtin-mesh.csv").exists());
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("manifest.json")).unwrap()).unwrap();
    let figure = |id: &str| -> serde_json::Value {
        manifest["figures"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == id)
            .unwrap()["csv"]
            .clone()
    };
    assert_eq!(figure("builtin-mesh"), serde_json::json!(["file-mesh.csv"]));
    // Curvature measured with the file's Loop from the same random net (one
    // seed): the built-in's to rounding.
    let (fc, bc) = (csv(&out, "file-curv.csv"), csv(&out, "builtin-curv.csv"));
    assert_eq!(fc.len(), bc.len());
    for (x, y) in fc[1..].iter().zip(&bc[1..]) {
        same_rows(x, y, &fc[0], &["scheme"], 1e-9);
    }
}
