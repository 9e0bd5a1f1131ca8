//! `subdiv-lab matrix`: output round trips and bad-input handling.

use crate::common;
use common::run;
use subdiv_lab::knots::CornerIntervals;
use subdiv_lab::scalar::{parse_exact, Rational, Scalar};
use subdiv_lab::schemes::LocalScheme;

fn parse_csv_f64(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .map(|l| {
            l.split(',')
                .map(|x| x.parse::<f64>().expect("number"))
                .collect()
        })
        .collect()
}

const KNOTS5: &str = "1:2,2.5:1,0.3:1,1:4,2:0.5";

fn knots5() -> CornerIntervals {
    CornerIntervals::new(vec![1.0, 2.5, 0.3, 1.0, 2.0], vec![2.0, 1.0, 1.0, 4.0, 0.5]).unwrap()
}

#[test]
fn csv_round_trip_equals_library_matrix() {
    let (code, out, err) = run(&[
        "matrix",
        "--scheme",
        "nurds",
        "--valence",
        "5",
        "--knots",
        KNOTS5,
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows = parse_csv_f64(&out);
    let lib = LocalScheme::nurds(knots5().ratios().unwrap())
        .matrix()
        .unwrap();
    assert_eq!(rows.len(), 20);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), 20);
        for (j, x) in row.iter().enumerate() {
            // shortest round-trip printing: bit-identical
            assert_eq!(*x, lib.matrix()[(i, j)], "({i}, {j})");
        }
    }
}

#[test]
fn face_block_csv_and_ratios_input() {
    let (code, out, _) = run(&[
        "matrix",
        "--ratios",
        "0.2,0.7,0.5",
        "--block",
        "face",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let rows = parse_csv_f64(&out);
    let lib = LocalScheme::nurds(subdiv_lab::knots::EdgeRatios::new(vec![0.2, 0.7, 0.5]).unwrap())
        .face_block()
        .unwrap();
    assert_eq!(rows.len(), 3);
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(rows[i][j], lib[(i, j)]);
        }
    }
}

#[test]
fn json_round_trip() {
    for scheme in ["nurds", "cc-variant", "doo-sabin"] {
        let mut args = vec![
            "matrix",
            "--scheme",
            scheme,
            "--valence",
            "5",
            "--format",
            "json",
        ];
        if scheme == "nurds" {
            args.extend(["--knots", KNOTS5]);
        }
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{scheme}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["scheme"], scheme);
        assert_eq!(v["valence"], 5);
        let lib = match scheme {
            "nurds" => LocalScheme::nurds(knots5().ratios().unwrap()),
            "cc-variant" => LocalScheme::cc_variant(5).unwrap(),
            _ => LocalScheme::doo_sabin(5).unwrap(),
        };
        let m = lib.matrix().unwrap();
        let rows: Vec<String> = m.rows().iter().map(ToString::to_string).collect();
        assert_eq!(v["rows"], serde_json::json!(rows));
        let mat = v["matrix"].as_array().unwrap();
        for (i, row) in mat.iter().enumerate() {
            for (j, x) in row.as_array().unwrap().iter().enumerate() {
                assert_eq!(x.as_f64().unwrap(), m.matrix()[(i, j)]);
            }
        }
        let c: Vec<f64> = v["face_weights"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(c, lib.face_weights());
    }
}

#[test]
fn exact_output_is_the_exact_matrix() {
    let (code, out, _) = run(&["matrix", "--knots", KNOTS5, "--format", "csv", "--exact"]);
    assert_eq!(code, 0);
    let exact = CornerIntervals::<Rational>::new(
        ["1", "2.5", "0.3", "1", "2"]
            .iter()
            .map(|s| parse_exact(s).unwrap())
            .collect(),
        ["2", "1", "1", "4", "0.5"]
            .iter()
            .map(|s| parse_exact(s).unwrap())
            .collect(),
    )
    .unwrap();
    let lib = LocalScheme::nurds(exact.ratios().unwrap())
        .matrix()
        .unwrap();
    for (i, line) in out.lines().enumerate() {
        let mut sum = Rational::frac(0, 1);
        for (j, cell) in line.split(',').enumerate() {
            let q = parse_exact(cell).unwrap();
            assert_eq!(q, lib.matrix()[(i, j)]);
            sum += q;
        }
        assert_eq!(sum, Rational::frac(1, 1), "row {i}");
    }
    let (code, out, _) = run(&["matrix", "--knots", KNOTS5, "--format", "json", "--exact"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["exact"], true);
    assert_eq!(
        v["matrix"][0][0].as_str().unwrap(),
        lib.matrix()[(0, 0)].to_text()
    );
}

#[test]
fn text_output_names_rows() {
    let (code, out, _) = run(&["matrix", "--scheme", "cc-variant", "--valence", "3"]);
    assert_eq!(code, 0);
    assert!(out.contains("cc-variant S_3"));
    assert!(out.lines().any(|l| l.trim_start().starts_with("E2,2 ")));
}

/// Every bad input exits non-zero with one line naming the problem and no matrix.
#[test]
fn bad_inputs() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["matrix", "--valence", "5", "--knots", "1:1,1:1,1:1,1:1"],
            "--valence is 5",
        ),
        (&["matrix", "--knots", "1:1,1:-2,1:1"], "q_1"),
        (&["matrix", "--knots", "1:1,0:2,1:1"], "p_1"),
        (&["matrix", "--knots", "1:1,1:nan,1:1"], "q_1"),
        (&["matrix", "--knots", "1:1,inf:1,1:1"], "p_1"),
        (&["matrix", "--knots", "1:1,1,1:1"], "entry 1"),
        (&["matrix", "--knots", "1:1,x:1,1:1"], "\"x\""),
        (&["matrix", "--ratios", "0.5,1.0,0.5"], "r_1"),
        (&["matrix", "--ratios", "0.5,0.5"], "at least 3"),
        (&["matrix", "--valence", "2", "--uniform"], "at least 3"),
        (
            &[
                "matrix",
                "--scheme",
                "midedge",
                "--valence",
                "4",
                "--uniform",
            ],
            "\"midedge\"",
        ),
        (
            &["matrix", "--uniform", "--ratios", "0.5,0.5,0.5"],
            "mutually exclusive",
        ),
        (
            &[
                "matrix",
                "--knots",
                "1:1,1:1,1:1",
                "--ratios",
                "0.5,0.5,0.5",
            ],
            "mutually exclusive",
        ),
        (
            &["matrix", "--scheme", "doo-sabin", "--knots", "1:1,1:1,1:1"],
            "no knot intervals",
        ),
        (
            &["matrix", "--scheme", "nurds", "--valence", "4"],
            "needs one of",
        ),
        (
            &["matrix", "--scheme", "doo-sabin"],
            "--valence is required",
        ),
        (
            &["matrix", "--uniform", "--valence", "4", "--format", "xml"],
            "xml",
        ),
        (
            &["matrix", "--uniform", "--valence", "4", "--bogus"],
            "--bogus",
        ),
        (
            &[
                "matrix",
                "--scheme",
                "doo-sabin",
                "--valence",
                "5",
                "--exact",
            ],
            "valence = 5",
        ),
    ];
    for (args, needle) in cases {
        let (code, out, err) = run(args);
        assert_ne!(code, 0, "{args:?} should fail");
        assert!(out.is_empty(), "{args:?} printed a matrix: {out}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(
            err.contains(needle),
            "{args:?}: {err:?} does not mention {needle:?}"
        );
    }
}
