//! CLI tests for the Catmull-Clark family (`matrix --scheme catmull-clark|adjustable-cc`)
//! and `ccss-bound`.

use crate::common;
use common::run;

#[test]
fn adjustable_matrix_exact_json() {
    let (code, out, err) = run(&[
        "matrix",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "3",
        "--c",
        "1/3",
        "--exact",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["scheme"], "adjustable-cc");
    // v' weight on v: (n + c^2 - 4c)/n = (3 + 1/9 - 4/3)/3 = 16/27.
    assert_eq!(v["matrix"][0][0], "16/27");
    assert_eq!(v["rows"][4], "f0");
}

#[test]
fn catmull_clark_matrix_and_errors() {
    let (code, out, _) = run(&[
        "matrix",
        "--scheme",
        "catmull-clark",
        "--valence",
        "4",
        "--exact",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("9x9"));
    let (code, _, err) = run(&[
        "matrix",
        "--scheme",
        "catmull-clark",
        "--valence",
        "4",
        "--block",
        "face",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("face block"), "{err}");
    let (code, _, err) = run(&[
        "matrix",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "4",
        "--c",
        "1.5",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("c = 1.5"), "{err}");
    let (code, _, err) = run(&[
        "matrix",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "4",
        "--c",
        "abc",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--c"), "{err}");
    let (code, _, _) = run(&["matrix", "--scheme", "adjustable-cc", "--valence", "4"]);
    assert_eq!(code, 2);
}

#[test]
fn ccss_bound_cli() {
    let (code, out, err) = run(&["ccss-bound", "--valence", "4", "--json", "--levels", "2"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((v["beta"].as_f64().unwrap() - 0.25).abs() < 1e-12);
    assert_eq!(v["lp_status"], "optimal");
    assert_eq!(v["family_size"], 18);
    let (code, out, _) = run(&["ccss-bound", "--table-to", "5", "--levels", "2"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 4);
    let (code, _, err) = run(&["ccss-bound", "--valence", "2"]);
    assert_eq!(code, 2);
    assert!(err.contains("valence"), "{err}");
}

#[test]
fn ccss_bound_steps_for_a_net() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("net.txt");
    let n = 5;
    let text: String = (0..2 * n + 8)
        .map(|k| {
            let k = k as f64;
            format!("{} {}, {}\n", (0.7 * k).sin(), (1.3 * k).cos(), 0.1 * k)
        })
        .collect();
    std::fs::write(&path, format!("# a net\n{text}")).unwrap();
    let p = path.to_str().unwrap();
    let (code, out, err) = run(&[
        "ccss-bound",
        "--valence",
        "5",
        "--levels",
        "2",
        "--json",
        "--net",
        p,
        "--epsilon",
        "1e-4",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let steps = v["steps"]["steps"].as_u64().unwrap();
    assert!(steps > 0 && v["steps"]["bound"].as_f64().unwrap() <= 1e-4);
    let (code, _, err) = run(&[
        "ccss-bound",
        "--valence",
        "5",
        "--net",
        p,
        "--epsilon",
        "-1",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("epsilon"), "{err}");
    let (code, _, err) = run(&[
        "ccss-bound",
        "--valence",
        "6",
        "--net",
        p,
        "--epsilon",
        "1e-3",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("expected 20"), "{err}");
}
