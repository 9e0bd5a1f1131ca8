//! Scheme files (`--scheme-file`): the shipped restatements of Catmull-Clark
//! and Loop give the built-ins' verdicts, matrices and sweep rows.

mod common;
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
