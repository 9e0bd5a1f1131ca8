//! Theorem 1 (math doc section 5): certificate (exact and f64), measured
//! contraction, spectral bound.

use proptest::prelude::*;
use subdiv_lab::contraction::{certificate, measure, MeasureOptions, SplitMix64};
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::scalar::{Rational, Scalar};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{analyze, classify_scheme, AnalyzeOptions, SubdominantClass};

fn rational_ratios(rng: &mut SplitMix64, n: usize, den: i64) -> EdgeRatios<Rational> {
    EdgeRatios::new(
        (0..n)
            .map(|_| Rational::frac(1 + (rng.next_u64() % (den as u64 - 1)) as i64, den))
            .collect(),
    )
    .unwrap()
}

#[test]
fn exact_certificate_for_random_rational_knots() {
    let mut rng = SplitMix64::new(5);
    let three_quarters = Rational::frac(3, 4);
    for trial in 0..60 {
        let n = 3 + trial % 8;
        let s = LocalScheme::nurds(rational_ratios(&mut rng, n, 997));
        let c = certificate(&s).unwrap();
        assert!(c.holds(), "n = {n}");
        assert!(c.row_sums.iter().all(|x| *x == three_quarters));
        assert!(c.min_weight >= Rational::frac(0, 1));
        assert_eq!(c.invariance_defect, Rational::frac(0, 1));
        // The weights are exactly (I + R)/4 (math doc section 5).
        let r = s.ratios();
        for i in 0..n {
            let prev = (i + n - 1) % n;
            let next = (i + 1) % n;
            let ri = r.as_slice()[i].clone();
            let rp = r.as_slice()[prev].clone();
            let q = Rational::frac(1, 4);
            assert_eq!(
                c.weights[(i, i)],
                q.clone() * (Rational::frac(2, 1) + ri.clone() - rp.clone())
            );
            assert_eq!(c.weights[(i, prev)], q.clone() * rp);
            assert_eq!(c.weights[(i, next)], q * (Rational::frac(1, 1) - ri));
        }
    }
}

#[test]
fn exact_certificate_for_original_doo_sabin_and_cc_variant() {
    for n in [3, 4, 6] {
        let c = certificate(&LocalScheme::<Rational>::doo_sabin(n).unwrap()).unwrap();
        assert!(c.holds(), "doo-sabin n = {n}");
    }
    for n in 3..=12 {
        let c = certificate(&LocalScheme::<Rational>::cc_variant(n).unwrap()).unwrap();
        assert!(c.holds(), "cc-variant n = {n}");
    }
    // f64 for the irrational Doo-Sabin valences.
    for n in 3..=40 {
        let c = certificate(&LocalScheme::<f64>::doo_sabin(n).unwrap()).unwrap();
        assert!(c.holds(), "doo-sabin f64 n = {n}: {}", c.max_sum_defect());
    }
}

#[test]
fn certificate_detects_a_broken_face_block() {
    // A face block whose rows still sum to 1 but with a negative weight fails.
    let mut rng = SplitMix64::new(1);
    let s = LocalScheme::nurds(rational_ratios(&mut rng, 5, 10));
    let c = certificate(&s).unwrap();
    assert!(c.holds());
    let mut w = c.weights.clone();
    w[(0, 2)] = w[(0, 2)].clone() - Rational::frac(1, 100);
    w[(0, 0)] = w[(0, 0)].clone() + Rational::frac(1, 100);
    assert!(w.iter().any(|x| *x < Rational::frac(0, 1)));
}

#[test]
fn measured_rate_matches_lambda1_and_stays_below_three_quarters() {
    let mut rng = SplitMix64::new(17);
    let mut checked = 0;
    for trial in 0..80 {
        let n = 3 + trial % 10;
        let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
        let s = LocalScheme::nurds(EdgeRatios::new(r).unwrap());
        let m = measure(&s, &MeasureOptions::default()).unwrap();
        assert_eq!(m.distances.len(), 61);
        assert!(m.max_ratio <= 0.75 + 1e-12, "n = {n}: {}", m.max_ratio);
        let sub = classify_scheme(&s).unwrap();
        let l1 = sub.lambda1.norm();
        // For a real dominant lambda_1 well separated from |lambda_2| the rate
        // converges like (|lambda_2| / |lambda_1|)^30.
        if sub.class == SubdominantClass::RealDistinct && sub.lambda2.norm() / l1 < 0.9 {
            assert!(
                (m.fitted_rate - l1).abs() < 2e-3,
                "n = {n}: rate {} vs |lambda1| {l1}",
                m.fitted_rate
            );
            checked += 1;
        }
        // Complex pair / double: the rate still tends to |lambda_1| (oscillating ratios).
        if sub.class == SubdominantClass::ComplexPair {
            assert!(
                (m.fitted_rate - l1).abs() < 0.05,
                "n = {n}: rate {} vs |lambda1| {l1}",
                m.fitted_rate
            );
        }
        assert!(m.fitted_rate < 0.75);
    }
    assert!(checked > 10, "{checked}");
}

#[test]
fn uniform_rate_is_the_closed_form() {
    for n in [3, 5, 8, 12] {
        let s = LocalScheme::<f64>::cc_variant(n).unwrap();
        let m = measure(&s, &MeasureOptions::default()).unwrap();
        let l1 = 0.5 + (2.0 * std::f64::consts::PI / n as f64).cos() / 4.0;
        // The next eigenvalue: 1/2 + cos(4 pi / n)/4 or the 1/4 of the E blocks.
        let l3 = (0.5 + (4.0 * std::f64::consts::PI / n as f64).cos() / 4.0)
            .abs()
            .max(0.25);
        // The fit window starts at level 30: the subleading term is (l3/l1)^30.
        let tol = 2.0 * (l3 / l1).powi(30);
        assert!(
            (m.fitted_rate - l1).abs() < tol,
            "n = {n}: {} vs {l1} (tol {tol:e})",
            m.fitted_rate
        );
    }
}

#[test]
fn measurement_is_deterministic_and_seeded() {
    let s = LocalScheme::<f64>::cc_variant(5).unwrap();
    let a = measure(&s, &MeasureOptions::default()).unwrap();
    let b = measure(&s, &MeasureOptions::default()).unwrap();
    assert_eq!(a, b);
    let c = measure(
        &s,
        &MeasureOptions {
            seed: 42,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    assert_ne!(a.distances, c.distances);
}

#[test]
fn splitmix64_reference_values() {
    // Reference outputs of SplitMix64 with seed 1234567 (Vigna's splitmix64.c).
    let mut g = SplitMix64::new(1234567);
    assert_eq!(g.next_u64(), 6457827717110365317);
    assert_eq!(g.next_u64(), 3203168211198807973);
    let x = SplitMix64::new(0).next_f64();
    assert!((0.0..1.0).contains(&x));
}

#[test]
fn analyze_reports_the_three_pieces() {
    let s = LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.5, 0.3]).unwrap());
    let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
    let c = a.contraction.as_ref().unwrap();
    assert!(c.certificate_holds && c.certificate_nonnegative);
    assert!((c.certificate_sum - 0.75).abs() < 1e-15);
    assert!(c.certificate_sum_defect < 1e-15);
    assert!(c.spectral_bound_ok && c.spectral_bound < 0.75);
    assert!((c.spectral_bound - a.subdominant.lambda1.norm()).abs() < 1e-12);
    assert!(c.measured_max_ratio <= 0.75 + 1e-12);
    assert_eq!(c.measured_ratios.len(), 60);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn per_step_contraction_at_most_three_quarters(n in 3usize..24, seed in any::<u64>(), extreme in any::<bool>()) {
        let mut rng = SplitMix64::new(seed);
        let (lo, hi) = if extreme { (1e-6, 1.0 - 1e-6) } else { (0.01, 0.99) };
        let r: Vec<f64> = (0..n).map(|_| rng.uniform(lo, hi)).collect();
        let s = LocalScheme::nurds(EdgeRatios::new(r).unwrap());
        let m = measure(&s, &MeasureOptions { levels: 30, seed, dim: 3 }).unwrap();
        for (k, ratio) in m.ratios.iter().enumerate() {
            prop_assert!(*ratio <= 0.75 + 1e-9, "level {}: ratio {}", k, ratio);
        }
        let c = certificate(&s).unwrap();
        prop_assert!(c.holds(), "sum defect {}, min weight {}", c.max_sum_defect(), c.min_weight);
        let sub = classify_scheme(&s).unwrap();
        prop_assert!(sub.lambda1.norm() <= 0.75 + 1e-12);
    }
}
