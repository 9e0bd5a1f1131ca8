//! Knot intervals, edge ratios and face weights (math doc sections 2-3).

use proptest::prelude::*;
use subdiv_lab::knots::{face_weights, stationary_distribution, CornerIntervals, EdgeRatios};
use subdiv_lab::scalar::{Rational, Scalar};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::Error;

/// Corner intervals log-uniform in [1e-3, 1e3].
fn corner_intervals(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = CornerIntervals> {
    n.prop_flat_map(|n| {
        (
            prop::collection::vec(-3.0f64..3.0, n),
            prop::collection::vec(-3.0f64..3.0, n),
        )
            .prop_map(|(p, q)| {
                CornerIntervals::new(
                    p.into_iter().map(|x| 10f64.powf(x)).collect(),
                    q.into_iter().map(|x| 10f64.powf(x)).collect(),
                )
                .unwrap()
            })
    })
}

/// Tolerance for closed form vs GTH: both are O(n eps) accurate componentwise
/// relative to the weights; for n <= 64 that is below 64 * 1.1e-16 * (a small
/// constant), so 1e-12 absolute (weights are <= 1) has a wide margin.
const WEIGHTS_AGREE: f64 = 1e-12;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Math doc fact 3: the closed form equals the stationary distribution of R/2.
    #[test]
    fn closed_form_equals_stationary_distribution(k in corner_intervals(3..=64)) {
        let r = k.ratios().unwrap();
        let c = face_weights(&r);
        let g = stationary_distribution(&r);
        let sum: f64 = c.iter().sum();
        prop_assert!((sum - 1.0).abs() < WEIGHTS_AGREE);
        for (j, (a, b)) in c.iter().zip(&g).enumerate() {
            prop_assert!((a - b).abs() < WEIGHTS_AGREE, "c_{j}: closed form {a} vs GTH {b}");
        }
    }

    /// c^T A = c^T for the face block (c is the left eigenvector for 1).
    #[test]
    fn face_weights_are_left_fixed_point(k in corner_intervals(3..=64)) {
        let s = LocalScheme::nurds(k.ratios().unwrap());
        let a = s.face_block().unwrap();
        let c = nalgebra::DVector::from_vec(s.face_weights());
        let ca = a.transpose() * &c;
        prop_assert!((ca - c).amax() < WEIGHTS_AGREE);
    }

    /// Only ratios matter: scaling every interval leaves ratios and weights unchanged.
    #[test]
    fn scale_invariance(k in corner_intervals(3..=16), e in -6.0f64..6.0) {
        let scale = 10f64.powf(e);
        let r1 = k.ratios().unwrap();
        let r2 = k.scaled(&scale).unwrap().ratios().unwrap();
        for (a, b) in r1.as_slice().iter().zip(r2.as_slice()) {
            prop_assert!((a - b).abs() <= 4.0 * f64::EPSILON * a.abs());
        }
        let m1 = LocalScheme::nurds(r1).matrix().unwrap();
        let m2 = LocalScheme::nurds(r2).matrix().unwrap();
        prop_assert!((m1.matrix() - m2.matrix()).amax() < 1e-14);
    }

    /// Exact scale invariance for rational knots.
    #[test]
    fn exact_scale_invariance(p in prop::collection::vec(1i64..50, 3..8), s in 1i64..1000) {
        let n = p.len();
        let q: Vec<i64> = p.iter().rev().map(|x| x % 7 + 1).collect();
        let k = CornerIntervals::<Rational>::new(
            p.iter().map(|&x| Rational::frac(x, 3)).collect(),
            q.iter().map(|&x| Rational::frac(x, 5)).collect(),
        ).unwrap();
        let scaled = k.scaled(&Rational::frac(s, 7)).unwrap();
        prop_assert_eq!(k.ratios().unwrap(), scaled.ratios().unwrap());
        prop_assert_eq!(face_weights(&k.ratios().unwrap()).len(), n);
    }
}

#[test]
fn exact_closed_form_equals_exact_gth() {
    for n in 3..=12 {
        let r: Vec<Rational> = (0..n)
            .map(|i| Rational::frac((7 * i as i64 + 3) % 11 + 1, 13))
            .collect();
        let r = EdgeRatios::new(r).unwrap();
        assert_eq!(face_weights(&r), stationary_distribution(&r), "n = {n}");
    }
}

/// Math doc fact 2 with the printed weights.
#[test]
fn tensor_quad_gives_printed_weights() {
    let (d, e) = ([1.3, 0.4], [2.2, 0.7]);
    let k =
        CornerIntervals::new(vec![d[0], e[0], d[1], e[1]], vec![e[0], d[1], e[1], d[0]]).unwrap();
    let c = face_weights(&k.ratios().unwrap());
    for (a, b) in c.iter().zip([0.056795, 0.184584, 0.580122, 0.178499]) {
        assert!((a - b).abs() < 5e-7, "{c:?}");
    }
}

/// Math doc fact 4: n up to 256 and interval ratios up to 1e6 stay accurate.
/// Reference: the exact rational closed form on the same f64 inputs.
#[test]
fn extreme_intervals_against_exact_rationals() {
    for &(n, seed) in &[(40usize, 1u64), (64, 7)] {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let p: Vec<f64> = (0..n).map(|_| 10f64.powf(6.0 * next() - 3.0)).collect();
        let q: Vec<f64> = (0..n).map(|_| 10f64.powf(6.0 * next() - 3.0)).collect();
        let c = face_weights(
            &CornerIntervals::new(p.clone(), q.clone())
                .unwrap()
                .ratios()
                .unwrap(),
        );
        let exact = face_weights(
            &CornerIntervals::<Rational>::new(
                p.iter().map(|&x| Rational::from_f64_lossless(x)).collect(),
                q.iter().map(|&x| Rational::from_f64_lossless(x)).collect(),
            )
            .unwrap()
            .ratios()
            .unwrap(),
        );
        for (j, (a, b)) in c.iter().zip(&exact).enumerate() {
            let b = b.to_f64();
            // O(n eps) relative error: products of n factors each with one rounding.
            assert!(
                ((a - b) / b).abs() < 1e-12,
                "n = {n}, c_{j}: {a} vs exact {b}"
            );
        }
    }
    // n = 256 with ratio 1e6 between neighbours: the naive product underflows
    // (1e-6^128 < f64::MIN_POSITIVE); the result must stay finite and agree with GTH.
    let n = 256;
    let p: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1e6 } else { 1.0 }).collect();
    let q: Vec<f64> = (0..n).map(|i| if i % 3 == 0 { 1.0 } else { 1e6 }).collect();
    let r = CornerIntervals::new(p, q).unwrap().ratios().unwrap();
    let (c, g) = (face_weights(&r), stationary_distribution(&r));
    assert!(c.iter().all(|x| x.is_finite() && *x > 0.0));
    for (a, b) in c.iter().zip(&g) {
        assert!(((a - b) / b).abs() < 1e-10, "{a} vs {b}");
    }
}

#[test]
fn bad_inputs_are_typed_errors_naming_the_value() {
    assert_eq!(
        CornerIntervals::new(vec![1.0; 2], vec![1.0; 2]).unwrap_err(),
        Error::ValenceTooSmall { valence: 2 }
    );
    let e = CornerIntervals::new(vec![1.0, 0.0, 1.0], vec![1.0; 3]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "knot interval p_1 must be finite and > 0, got 0.0"
    );
    let e = CornerIntervals::new(vec![1.0; 3], vec![1.0, 1.0, f64::INFINITY]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "knot interval q_2 must be finite and > 0, got inf"
    );
    let e = CornerIntervals::new(vec![1.0; 3], vec![1.0; 4]).unwrap_err();
    assert!(matches!(
        e,
        Error::CountMismatch {
            expected: 3,
            got: 4,
            ..
        }
    ));
    for bad in [0.0, 1.0, -0.5, 1.5, f64::NAN] {
        let e = EdgeRatios::new(vec![0.5, bad, 0.5]).unwrap_err();
        assert!(
            matches!(e, Error::InvalidRatio { index: 1, .. }),
            "{bad}: {e}"
        );
    }
    let e = EdgeRatios::<Rational>::new(vec![
        Rational::frac(1, 2),
        Rational::frac(1, 2),
        Rational::frac(3, 2),
    ])
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "edge ratio r_2 must lie strictly between 0 and 1, got 3/2"
    );
    assert!(EdgeRatios::vertex_ep(&[1.0, 1.0, -1.0, 1.0])
        .unwrap_err()
        .to_string()
        .contains("a_2"));
    assert!(EdgeRatios::face_ep(&[1.0, 1.0, 1.0], &[1.0, 0.0, 1.0])
        .unwrap_err()
        .to_string()
        .contains("backward_1"));
}

#[test]
fn rotation_rotates_weights() {
    let k =
        CornerIntervals::new(vec![1.0, 2.0, 0.5, 3.0, 1.5], vec![0.7, 1.1, 2.0, 0.3, 1.0]).unwrap();
    let c = face_weights(&k.ratios().unwrap());
    let c2 = face_weights(&k.rotated(2).ratios().unwrap());
    for i in 0..5 {
        assert!((c2[i] - c[(i + 2) % 5]).abs() < 1e-15);
    }
}

/// Runs the release binary in a fresh scratch directory.
fn run_bin(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("subdiv-knots-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn cube() -> String {
    format!("{}/analysis/meshes/cube.obj", env!("CARGO_MANIFEST_DIR"))
}

/// `subdivide --knots k.knots --default-interval 1e300` with `1 3 1e-300`
/// (a ratio of about 1e-600) and `--default-interval 9e307` (sums overflow)
/// run without a stack overflow in `frexp(0.0)`. Any finite positive
/// intervals are accepted; the output only depends on ratios, so uniform
/// 9e307 gives exactly the output of uniform 1.
#[test]
fn subdivide_takes_extreme_intervals() {
    let d = scratch("subdivide");
    std::fs::write(d.join("k.knots"), "1 3 1e-300\n").unwrap();
    let cube = cube();
    let out = run_bin(
        &d,
        &[
            "subdivide",
            &cube,
            "--scheme",
            "nurds",
            "--knots",
            "k.knots",
            "--default-interval",
            "1e300",
            "-o",
            "x.obj",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(d.join("x.obj")).unwrap();
    assert!(!text.contains("NaN") && !text.contains("inf"));
    for (big, name) in [
        ("9e307", "big.obj"),
        ("1", "one.obj"),
        ("1.7976931348623157e308", "max.obj"),
    ] {
        let out = run_bin(
            &d,
            &[
                "subdivide",
                &cube,
                "--scheme",
                "nurds",
                "--default-interval",
                big,
                "--levels",
                "2",
                "-o",
                name,
            ],
        );
        assert!(
            out.status.success(),
            "{big}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let one = std::fs::read(d.join("one.obj")).unwrap();
    assert_eq!(std::fs::read(d.join("big.obj")).unwrap(), one);
    assert_eq!(std::fs::read(d.join("max.obj")).unwrap(), one);
    let _ = std::fs::remove_dir_all(&d);
}

/// Extreme intervals through the library: interval sums that
/// overflow give the exact ratios; a ratio below the f64 range names the edge.
#[test]
fn ratios_of_extreme_intervals() {
    let k = CornerIntervals::new(vec![9e307; 4], vec![9e307; 4]).unwrap();
    assert!(k.ratios().unwrap().is_uniform());
    let k = CornerIntervals::new(vec![f64::MAX, 1.0, 1.0], vec![1.0, f64::MAX, 1.0]).unwrap();
    let r = k.ratios().unwrap();
    // r_0 = q_1 / (p_0 + q_1) = 1/2 exactly with p_0 = q_1 = MAX
    assert_eq!(r.as_slice()[0], 0.5);
    let k = CornerIntervals::new(vec![1e300; 3], vec![1.0, 1e-300, 1.0]).unwrap();
    match k.ratios() {
        Err(Error::RatioNotRepresentable {
            index: 0,
            rounded: "0",
            value,
        }) => {
            assert!(
                value.contains("1e-300") && value.contains("1e300"),
                "{value}"
            )
        }
        other => panic!("{other:?}"),
    }
    // The exact path: any size, ratios exact, rounded once to f64.
    let big = subdiv_lab::scalar::parse_exact("1e400/3").unwrap();
    let kq = CornerIntervals::new(vec![big.clone(); 3], vec![big; 3]).unwrap();
    let rf = kq.ratios().unwrap().to_f64_checked().unwrap();
    assert!(rf.is_uniform());
}

/// Extreme knots through the CLI: numbers are read exactly. Uniform 9e307
/// knots (whose sums overflow f64; also with --exact) and, with --exact,
/// knots of 1e400/3 (beyond the f64 range) are the uniform configuration.
#[test]
fn analyze_reads_extreme_knots() {
    let d = scratch("analyze");
    for args in [
        &[
            "analyze",
            "--knots",
            "9e307:9e307,9e307:9e307,9e307:9e307,9e307:9e307,9e307:9e307",
        ][..],
        &[
            "analyze",
            "--exact",
            "--knots",
            "9e307:9e307,9e307:9e307,9e307:9e307,9e307:9e307,9e307:9e307",
        ][..],
        &[
            "analyze",
            "--exact",
            "--knots",
            "1e400/3:1e400/3,1e400/3:1e400/3,1e400/3:1e400/3,1e400/3:1e400/3,1e400/3:1e400/3",
        ][..],
    ] {
        let out = run_bin(&d, args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            text.contains("subdominant class: standard"),
            "{args:?}: {text}"
        );
        assert!(
            text.contains("0.5772542486"),
            "{args:?}: lambda_1 of uniform n = 5: {text}"
        );
        if args.contains(&"--exact") {
            assert!(text.contains("exact: class standard"), "{text}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
