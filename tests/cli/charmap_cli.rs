//! `subdiv-lab analyze`: the characteristic-map part (human and `--json`).

use crate::common;
use common::run;

fn charmap_json(args: &[&str]) -> serde_json::Value {
    let mut a = vec!["analyze", "--json"];
    a.extend_from_slice(args);
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    v["charmap"].clone()
}

#[test]
fn json_has_the_charmap_object() {
    let c = charmap_json(&["--scheme", "doo-sabin", "--valence", "5"]);
    assert_eq!(c["regular"], serde_json::Value::Bool(true));
    assert_eq!(c["winding_number"], 1);
    assert_eq!(c["verdict"], "C1 (standard; Reif)");
    assert!(c["min_jacobian_coeff"].as_f64().unwrap() > 0.0);

    let c = charmap_json(&["--scheme", "nurds", "--ratios", "0.2,0.7,0.4,0.9,0.3"]);
    let verdict = c["verdict"].as_str().unwrap();
    assert!(
        verdict.starts_with("tangent-plane continuous (non-standard: "),
        "{verdict}"
    );
    assert_eq!(
        c["structure"],
        c["verdict_code"]
            .as_str()
            .unwrap()
            .trim_start_matches("tpc_")
    );
}

#[test]
fn human_output_names_the_verdict_and_the_winding_number() {
    let (code, out, err) = run(&["analyze", "--scheme", "cc-variant", "--valence", "7"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("characteristic map: C1 (standard; Reif)"),
        "{out}"
    );
    assert!(
        out.contains("winding number of the boundary around the origin: outer 1, inner 1"),
        "{out}"
    );
}
