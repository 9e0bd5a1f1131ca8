//! `subdiv-lab analyze`: JSON keys, agreement with the library, exact verdicts, bad input.

use crate::common;
use common::run;

#[test]
fn json_has_the_documented_keys() {
    let (code, out, err) = run(&["analyze", "--knots", "1:2,2.5:1,0.3:1,1:4,2:0.5", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let ev = v["eigenvalues"].as_array().unwrap();
    assert_eq!(ev.len(), 20);
    let modulus = |z: &serde_json::Value| {
        let a = z.as_array().unwrap();
        a[0].as_f64().unwrap().hypot(a[1].as_f64().unwrap())
    };
    for w in ev.windows(2) {
        assert!(modulus(&w[0]) >= modulus(&w[1]));
    }
    assert_eq!(v["face_weights"].as_array().unwrap().len(), 5);
    let sub = &v["subdominant"];
    for key in ["class", "lambda1", "lambda2", "abs_lambda3", "gap"] {
        assert!(!sub[key].is_null(), "missing subdominant.{key}");
    }
    assert_eq!(sub["lambda1"].as_array().unwrap().len(), 2);
    let c = &v["contraction"];
    for key in [
        "certificate_sum",
        "certificate_nonnegative",
        "spectral_bound",
        "measured_rate",
    ] {
        assert!(!c[key].is_null(), "missing contraction.{key}");
    }
    assert_eq!(c["certificate_nonnegative"], serde_json::Value::Bool(true));
    assert!((c["certificate_sum"].as_f64().unwrap() - 0.75).abs() < 1e-15);
    assert!(v["exact"].is_null());
    // The input and the tool version are echoed.
    let input = &v["input"];
    assert_eq!(input["scheme"], "nurds");
    assert_eq!(input["valence"], 5);
    assert_eq!(input["knots"][1], serde_json::json!([2.5, 1.0]));
    assert_eq!(input["knots"].as_array().unwrap().len(), 5);
    assert!(input["ratios"].is_null() && input["c"].is_null());
    assert_eq!(input["uniform"], false);
    assert_eq!(v["tool_version"], env!("CARGO_PKG_VERSION"));
    let (code, out, err) = run(&[
        "analyze",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "4",
        "--c",
        "1/4",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["input"]["scheme"], "adjustable-cc");
    assert_eq!(v["input"]["c"], 0.25);
    assert!(v["input"]["knots"].is_null());
}

#[test]
fn exact_flag_adds_verdicts_that_agree() {
    let (code, out, err) = run(&[
        "analyze",
        "--ratios",
        "1/3,0.9,1/2,0.05,0.6",
        "--json",
        "--exact",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let x = &v["exact"];
    assert_eq!(x["one_is_simple"], serde_json::Value::Bool(true));
    assert_eq!(x["theorem1_certificate"], serde_json::Value::Bool(true));
    assert_eq!(x["class"], v["subdominant"]["class"]);
    assert_eq!(x["agrees_with_float"], serde_json::Value::Bool(true));
    assert_eq!(x["reduced_charpoly"].as_array().unwrap().len(), 5);
}

#[test]
fn uniform_summary_is_standard() {
    let (code, out, err) = run(&["analyze", "--scheme", "cc-variant", "--valence", "5"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("subdominant class: standard"), "{out}");
    assert!(out.contains("0.5772542486"), "{out}");
    let (code, out, _) = run(&[
        "analyze",
        "--scheme",
        "doo-sabin",
        "--valence",
        "7",
        "--path",
        "structured",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("standard"));
}

#[test]
fn bad_input_is_a_usage_error() {
    for args in [
        vec!["analyze", "--ratios", "0.5,1.5,0.5"],
        vec!["analyze", "--knots", "1:0,1:1,1:1"],
        vec!["analyze", "--uniform"],
        vec!["analyze", "--uniform", "--valence", "2"],
        vec!["analyze", "--uniform", "--valence", "4", "--levels", "0"],
    ] {
        let (code, _, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    // Input that the exact mode cannot represent (irrational weights): an
    // input error (exit 2) with a one-line message.
    let (code, _, err) = run(&[
        "analyze",
        "--scheme",
        "doo-sabin",
        "--valence",
        "5",
        "--exact",
    ]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("irrational"), "{err}");
}

/// `analyze --vertex ... --json`: the `curvature` object has the interior
/// document's keys, and the verdict is the library's (Loop BLZ boundary of 8
/// triangles: `mu = 0.4458 > lambda^2`, unbounded; the regular Catmull-Clark
/// boundary: bounded, certified exactly).
#[test]
fn sector_json_curvature_has_the_interior_keys() {
    let keys = |v: &serde_json::Value| {
        let mut k: Vec<String> = v["curvature"]
            .as_object()
            .unwrap()
            .keys()
            .cloned()
            .collect();
        k.sort();
        k
    };
    let (code, out, err) = run(&["analyze", "--scheme", "loop", "--valence", "5", "--json"]);
    assert_eq!(code, 0, "{err}");
    let interior: serde_json::Value = serde_json::from_str(&out).unwrap();
    for (args, verdict) in [
        (
            ["--scheme", "loop", "--faces", "8", "--rules", "blz"],
            "unbounded",
        ),
        (
            [
                "--scheme",
                "catmull-clark",
                "--faces",
                "2",
                "--rules",
                "standard",
            ],
            "bounded",
        ),
    ] {
        let mut cmd = vec!["analyze", "--vertex", "boundary", "--json"];
        cmd.extend(args);
        let (code, out, err) = run(&cmd);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(keys(&v), keys(&interior));
        assert_eq!(v["curvature"]["verdict"], verdict, "{args:?}");
    }
}
