//! `--scheme loop` through the command-line tool: analysis (closed-form
//! subdominant eigenvalue, Fourier-block cross-check, certified
//! characteristic map), the matrix, and mesh refinement equal to the
//! library's (math doc section 11).

use crate::common;
use common::run;
use std::f64::consts::PI;
use subdiv_lab::mesh::loop_subdivision::{limit_mesh, refine_levels};
use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn analyze_loop_matches_the_closed_form_and_certifies_c1() {
    for n in 3..=8 {
        let v = n.to_string();
        let a = json(&["analyze", "--scheme", "loop", "--valence", &v, "--json"]);
        let lambda = 0.375 + 0.25 * (2.0 * PI / n as f64).cos();
        let l1 = a["subdominant"]["lambda1"][0].as_f64().unwrap();
        assert!((l1 - lambda).abs() < 1e-12, "n={n}: {l1} vs {lambda}");
        assert_eq!(a["subdominant"]["class"], "standard", "n={n}");
        // Every dense eigenvalue lies within its first-order error radius
        // max(kappa, 1) eta (eta = 10 d eps ||S||_F, math doc section 10) of
        // the closed-form Fourier spectrum. At n = 3 the eigenvalue 1/16 is
        // defective (kappa ~ 8e7) and the dense values split by ~sqrt(eps):
        // the radius covers that; elsewhere everything agrees to 1e-12.
        let m = subdiv_lab::schemes::loop_subdivision::matrix::two_ring_matrix(n).unwrap();
        let eta = 10.0 * (3 * n + 1) as f64 * f64::EPSILON * m.matrix().norm();
        let kappa: Vec<f64> = a["condition_numbers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|k| k.as_f64().unwrap())
            .collect();
        let fourier = subdiv_lab::schemes::loop_subdivision::fourier::spectrum(n).unwrap();
        for (z, k) in a["eigenvalues"].as_array().unwrap().iter().zip(&kappa) {
            let (re, im) = (z[0].as_f64().unwrap(), z[1].as_f64().unwrap());
            let d = fourier
                .iter()
                .map(|w| (w.re - re).hypot(w.im - im))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d <= k.max(1.0) * eta,
                "n={n}: {z} is {d} from the Fourier spectrum (kappa {k})"
            );
        }
        let dev = a["fourier_deviation"].as_f64().unwrap();
        if kappa.iter().all(|&k| k < 1e3) {
            assert!(dev < 1e-12, "n={n}: {dev}");
        }
        assert!(a["limit_weights_error"].as_f64().unwrap() < 1e-12);
        assert_eq!(a["eigenvalues"].as_array().unwrap().len(), 3 * n + 1);
        assert_eq!(a["charmap"]["verdict_code"], "c1", "n={n}");
        assert_eq!(a["charmap"]["winding_number"], 1);
        assert!(a["contraction"].is_null());
        // the structured (Fourier) path gives the same spectrum
        let s = json(&[
            "analyze",
            "--scheme",
            "loop",
            "--valence",
            &v,
            "--json",
            "--path",
            "structured",
        ]);
        for (x, y) in a["eigenvalues"]
            .as_array()
            .unwrap()
            .iter()
            .zip(s["eigenvalues"].as_array().unwrap())
        {
            let d = (x[0].as_f64().unwrap() - y[0].as_f64().unwrap())
                .hypot(x[1].as_f64().unwrap() - y[1].as_f64().unwrap());
            // (n = 3: the defective 1/16 splits differently; covered by the radius check above)
            assert!(d < 1e-12 || n == 3, "n={n}: {x} vs {y}");
        }
    }
}

#[test]
fn analyze_loop_text_names_the_two_ring() {
    let (code, out, err) = run(&["analyze", "--scheme", "loop", "--valence", "7"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with("loop around an n = 7 vertex (full (3n+1) two-ring path, 22 eigenvalues)"),
        "{out}"
    );
    assert!(
        out.contains("limit stencil (v, e_0.., g_0.., f_0..)"),
        "{out}"
    );
    assert!(out.contains("characteristic map: C1"), "{out}");
}

#[test]
fn matrix_loop_rows_are_affine() {
    let (code, out, err) = run(&[
        "matrix",
        "--scheme",
        "loop",
        "--valence",
        "4",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<Vec<f64>> = out
        .lines()
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 13);
    for r in &rows {
        assert_eq!(r.len(), 13);
        assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn subdivide_loop_equals_the_library() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = tempfile::tempdir().unwrap();
    for mesh in ["icosahedron.obj", "tetrahedron.obj"] {
        let input = format!("{root}/analysis/meshes/{mesh}");
        let (m, _) = parse_obj(&std::fs::read_to_string(&input).unwrap()).unwrap();
        let refined = refine_levels(&m, 2).unwrap();
        for (limit, expect) in [
            (false, refined.clone()),
            (true, limit_mesh(&refined).unwrap()),
        ] {
            let out = dir.path().join(format!("{mesh}-{limit}.obj"));
            let mut args = vec![
                "subdivide",
                &input,
                "--scheme",
                "loop",
                "--levels",
                "2",
                "-o",
                out.to_str().unwrap(),
            ];
            if limit {
                args.push("--limit");
            }
            let (code, _, err) = run(&args);
            assert_eq!(code, 0, "{err}");
            assert_eq!(
                std::fs::read_to_string(&out).unwrap(),
                write_obj_string(&expect)
            );
        }
    }
}
