//! Catmull-Clark family through the common spectral engine:
//! classification, Fourier fast path vs full path, limit and tangent stencils
//! from left eigenvectors vs the closed forms of `catmull_clark::limit`, the
//! patch matrix's extra eigenvalues, and the `analyze` CLI.

use nalgebra::DMatrix;
use proptest::prelude::*;
use std::process::Command;
use subdiv_lab::schemes::catmull_clark::{fourier, limit, patch_matrix};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{
    analyze, classify_scheme, AnalyzeOptions, Eigen, EigenOptions, SpectrumPath, SubdominantClass,
};

/// Agreement between the dense eigen-solver and the closed-form Fourier
/// eigenvalues: both are backward stable on matrices with entries in [0, 1]
/// and well-conditioned (the one-ring matrix is unitarily similar to the
/// blocks), so `64 (2n+1) eps` covers the rounding for n <= 64.
fn engine_tol(n: usize) -> f64 {
    64.0 * (2 * n + 1) as f64 * f64::EPSILON
}

fn full() -> AnalyzeOptions {
    AnalyzeOptions::default()
}

fn fourier_path() -> AnalyzeOptions {
    AnalyzeOptions {
        path: SpectrumPath::Structured,
        ..AnalyzeOptions::default()
    }
}

#[test]
fn catmull_clark_is_standard_for_n_3_to_16_on_every_path() {
    for n in 3..=16 {
        let s = LocalScheme::<f64>::catmull_clark(n).unwrap();
        let sweep = classify_scheme(&s).unwrap();
        assert_eq!(sweep.class, SubdominantClass::Standard, "n = {n} (sweep)");
        for opts in [full(), fourier_path()] {
            let a = analyze(&s, &opts).unwrap();
            assert_eq!(a.subdominant.class, SubdominantClass::Standard, "n = {n}");
            let stam = fourier::stam_subdominant(n);
            assert!(
                (a.subdominant.lambda1.re - stam).abs() < engine_tol(n),
                "n = {n}"
            );
            assert!(
                (a.subdominant.lambda2.re - stam).abs() < engine_tol(n),
                "n = {n}"
            );
            assert!(a.contraction.is_none());
        }
    }
}

#[test]
fn full_path_equals_fourier_blocks_for_n_3_to_64() {
    for n in 3..=64 {
        for c in [0.0, 0.25, 0.5, 0.8, 1.0] {
            let s = LocalScheme::<f64>::adjustable_cc(n, c).unwrap();
            let a = analyze(&s, &full()).unwrap();
            assert_eq!(a.eigenvalues.len(), 2 * n + 1);
            let d = a.fourier_deviation.unwrap();
            assert!(d < engine_tol(n), "n = {n}, c = {c}: deviation {d:e}");
        }
    }
}

#[test]
fn fourier_deviation_detects_a_wrong_spectrum() {
    // The cross-check is not vacuous: the Fourier spectrum of another c differs.
    let s = LocalScheme::<f64>::adjustable_cc(5, 0.3).unwrap();
    let a = analyze(&s, &full()).unwrap();
    let other = fourier::spectrum(5, 0.31).unwrap();
    let mine = fourier::spectrum(5, 0.3).unwrap();
    let far = other
        .iter()
        .zip(&mine)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max);
    assert!(far > 1e-4);
    assert!(a.fourier_deviation.unwrap() < 1e-12);
}

/// Coefficients of `t` in the basis `(b1, b2)` by least squares, and the residual.
fn span_residual(t: &[f64], b: &[Vec<f64>; 2]) -> f64 {
    let m = DMatrix::from_fn(t.len(), 2, |i, j| b[j][i]);
    let rhs = nalgebra::DVector::from_column_slice(t);
    let x = (m.transpose() * &m)
        .lu()
        .solve(&(m.transpose() * &rhs))
        .unwrap();
    (m * x - rhs).amax()
}

#[test]
fn limit_and_tangent_stencils_from_the_engine_match_the_closed_forms() {
    for n in 3..=24 {
        for c in [0.2, 0.5, 0.7] {
            let s = LocalScheme::<f64>::adjustable_cc(n, c).unwrap();
            let a = analyze(&s, &full()).unwrap();
            let w = a.limit_weights.as_ref().unwrap();
            let closed = limit::limit_stencil(n, &c).unwrap();
            for (x, y) in w.iter().zip(&closed) {
                assert!((x - y).abs() < 1e-13, "n = {n}, c = {c}");
            }
            assert!(a.limit_weights_error.unwrap() < 1e-13);
            // Tangent stencils span the same left eigenspace as the closed form
            // whenever lambda_1 = lambda_2 comes from the l = 1 block.
            let (lam, t) = limit::tangent_stencils(n, c).unwrap();
            if (a.subdominant.lambda1.re - lam).abs() < 1e-12
                && a.subdominant.class == SubdominantClass::Standard
            {
                let eng = a.tangent_stencils.as_ref().unwrap();
                for v in eng {
                    assert!(span_residual(v, &t) < 1e-10, "n = {n}, c = {c}");
                }
                for v in &t {
                    let m = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                    let v: Vec<f64> = v.iter().map(|x| x / m).collect();
                    assert!(span_residual(&v, eng) < 1e-10, "n = {n}, c = {c}");
                }
            }
        }
    }
}

#[test]
fn the_patch_matrix_adds_only_small_powers_of_two() {
    // Stam: the (2n+8) patch matrix has the one-ring spectrum plus eigenvalues
    // 1/8, 1/16, 1/32, 1/64, all below the subdominant eigenvalue, so the
    // one-ring matrix is the right one for the eigen-analysis.
    for n in [3, 4, 5, 8] {
        let p = patch_matrix::<f64>(n, &0.5).unwrap().into_matrix();
        let e = Eigen::new(&p, EigenOptions::default()).unwrap();
        let mut rest: Vec<_> = e.values().to_vec();
        for z in fourier::spectrum(n, 0.5).unwrap() {
            let k = rest
                .iter()
                .enumerate()
                .min_by(|a, b| (a.1 - z).norm().total_cmp(&(b.1 - z).norm()))
                .unwrap()
                .0;
            assert!((rest[k] - z).norm() < 1e-9, "n = {n}: {z} missing");
            rest.remove(k);
        }
        assert_eq!(rest.len(), 7);
        for z in &rest {
            let ok = [0.125, 0.0625, 0.03125, 0.015625, 0.0]
                .iter()
                .any(|&q| (z - q).norm() < 1e-6);
            assert!(ok, "n = {n}: unexpected extra eigenvalue {z}");
            assert!(z.norm() < fourier::stam_subdominant(n));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn sweep_and_full_and_fourier_classifications_agree(n in 3usize..33, c in 0.0f64..=1.0) {
        let s = LocalScheme::<f64>::adjustable_cc(n, c).unwrap();
        let f = analyze(&s, &full()).unwrap();
        let q = analyze(&s, &fourier_path()).unwrap();
        let k = classify_scheme(&s).unwrap();
        prop_assert_eq!(f.subdominant.class.name(), k.class.name());
        prop_assert_eq!(q.subdominant.class.name(), k.class.name());
        prop_assert!((f.subdominant.abs_lambda3 - k.abs_lambda3).abs() < 1e-10);
        prop_assert!((fourier::subdominant(n, c).unwrap() - f.subdominant.lambda1.norm()).abs() < 1e-10);
    }
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).expect("utf8"),
        String::from_utf8(out.stderr).expect("utf8"),
    )
}

#[test]
fn cli_analyze_json_for_the_catmull_clark_family() {
    for (args, c) in [
        (
            vec![
                "analyze",
                "--scheme",
                "catmull-clark",
                "--valence",
                "6",
                "--json",
            ],
            0.5,
        ),
        (
            vec![
                "analyze",
                "--scheme",
                "adjustable-cc",
                "--valence",
                "6",
                "--c",
                "1/3",
                "--json",
            ],
            1.0 / 3.0,
        ),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["eigenvalues"].as_array().unwrap().len(), 13);
        assert_eq!(v["subdominant"]["class"], "standard");
        assert!(v["contraction"].is_null());
        assert!(v["fourier_deviation"].as_f64().unwrap() < 1e-13);
        let w: Vec<f64> = v["limit_weights"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let closed = limit::limit_stencil(6, &c).unwrap();
        for (x, y) in w.iter().zip(&closed) {
            assert!((x - y).abs() < 1e-13);
        }
    }
    let (code, out, _) = run(&[
        "analyze",
        "--scheme",
        "catmull-clark",
        "--valence",
        "4",
        "--path",
        "structured",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("Fourier blocks"));
    assert!(out.contains("standard"));
    // Exact verdicts are a Doo-Sabin-family feature: refused as an input
    // combination (exit 2), not a panic.
    let (code, _, err) = run(&[
        "analyze",
        "--scheme",
        "catmull-clark",
        "--valence",
        "4",
        "--exact",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("face block"), "{err}");
}

mod study {
    use subdiv_lab::cc_study::{standard_intervals, study_curve, study_point};

    #[test]
    fn curves_agree_with_the_fourier_blocks() {
        for n in [3, 4, 7, 16, 32] {
            for p in study_curve(n, 20).unwrap() {
                let m = p.lambda1[0].hypot(p.lambda1[1]);
                assert!(
                    (m - p.fourier_subdominant).abs() < 1e-10,
                    "n = {n}, c = {}",
                    p.c
                );
            }
        }
    }

    #[test]
    fn c_zero_is_not_separated_and_catmull_clark_is_standard() {
        // c = 0: spectrum 1, 1/2 (n-fold), 1/4 (n-fold) -> |lambda_2| = |lambda_3|.
        for n in 3..=32 {
            assert_eq!(
                study_point(n, 0.0).unwrap().class,
                "not_separated",
                "n = {n}"
            );
            assert_eq!(study_point(n, 0.5).unwrap().class, "standard", "n = {n}");
        }
    }

    #[test]
    fn standard_intervals_are_bracketed_to_the_tolerance() {
        for n in [3, 5, 8, 32] {
            let iv = standard_intervals(n, 16, 1e-6).unwrap();
            assert!(!iv.is_empty());
            for i in &iv {
                assert!(i.lo <= i.hi);
                if i.lo > 0.0 {
                    assert!((i.lo - i.lo_outside).abs() <= 1e-6);
                    assert_eq!(study_point(n, i.lo).unwrap().class, "standard");
                    assert_ne!(study_point(n, i.lo_outside).unwrap().class, "standard");
                }
                if i.hi < 1.0 {
                    assert!((i.hi_outside - i.hi).abs() <= 1e-6);
                    assert_ne!(study_point(n, i.hi_outside).unwrap().class, "standard");
                }
            }
            // Catmull-Clark (c = 1/2) lies in one of them.
            assert!(iv.iter().any(|i| i.lo <= 0.5 && 0.5 <= i.hi), "n = {n}");
        }
    }
}

/// A case found by the proptest above: faer returns zero eigenvector columns
/// at the exactly double subdominant eigenvalue of the adjustable scheme
/// (n = 9, c = 0.10944...). Zero columns have residual 0; taken as
/// eigenvectors they would give infinite condition numbers and a wrong
/// `not_separated`. They are refined, and double eigenvalues get the
/// condition number of their spectral projector.
#[test]
fn double_eigenvalue_vectors_are_unit_and_well_conditioned() {
    use subdiv_lab::spectral::eigen::{Eigen, EigenOptions};
    for (n, c) in [(9, 0.1094457555588049), (7, 0.3), (12, 0.9)] {
        let s = LocalScheme::<f64>::adjustable_cc(n, c).unwrap();
        let m = s.matrix().unwrap().into_matrix();
        let e = Eigen::new(&m, EigenOptions::BOTH).unwrap();
        for vecs in [e.right().unwrap(), e.left().unwrap()] {
            for k in 0..vecs.ncols() {
                assert!(
                    (vecs.column(k).norm() - 1.0).abs() < 1e-12,
                    "n = {n}, column {k}"
                );
            }
        }
        let kappa = e.condition_numbers().unwrap();
        assert!(
            kappa[1] < 10.0 && kappa[2] < 10.0,
            "n = {n}: {:?}",
            &kappa[..3]
        );
        let full = analyze(&s, &full()).unwrap();
        assert_eq!(
            full.subdominant.class.name(),
            "standard",
            "n = {n}, c = {c}"
        );
    }
}
