//! Theorem 1 (math doc section 5): certificate (exact and f64), measured
//! contraction, spectral bound.

use nalgebra::DMatrix;
use proptest::prelude::*;
use subdiv_lab::contraction::{
    certificate, certify_face_block, measure, theorem_weights, MeasureOptions, SplitMix64,
};
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

/// A genuine face block of valence 5 (exact), its face weights and the
/// theorem's weights.
fn genuine_block() -> (DMatrix<Rational>, Vec<Rational>, DMatrix<Rational>) {
    let mut rng = SplitMix64::new(1);
    let s = LocalScheme::nurds(rational_ratios(&mut rng, 5, 10));
    let w = theorem_weights(&s).unwrap();
    (s.face_block().unwrap(), s.face_weights(), w)
}

/// `A = W + 1 c^T / 4`: the block a set of weights describes.
fn block_of(w: &DMatrix<Rational>, c: &[Rational]) -> DMatrix<Rational> {
    DMatrix::from_fn(w.nrows(), w.ncols(), |i, j| {
        w[(i, j)].clone() + Rational::frac(1, 4) * c[j].clone()
    })
}

/// Broken blocks are passed to the certificate itself, one
/// defect at a time (each other check still passes, so `holds()` must look
/// at the broken one).
#[test]
fn certificate_detects_a_broken_face_block() {
    let (a, c, w) = genuine_block();
    let ok = certify_face_block(&a, &c, w.clone()).unwrap();
    assert!(ok.holds() && ok.matches_assembly && ok.nonnegative);
    let eps = Rational::frac(1, 1000);
    let ratio = c[0].clone() / c[1].clone();

    // A negative weight: rows still sum to 3/4, c^T W unchanged (F invariant).
    let mut neg = w.clone();
    neg[(0, 0)] = neg[(0, 0)].clone() + eps.clone();
    neg[(0, 2)] = neg[(0, 2)].clone() - eps.clone(); // a structural zero for n = 5
    neg[(1, 0)] = neg[(1, 0)].clone() - eps.clone() * ratio.clone();
    neg[(1, 2)] = neg[(1, 2)].clone() + eps.clone() * ratio.clone();
    let cert = certify_face_block(&block_of(&neg, &c), &c, neg).unwrap();
    assert!(!cert.nonnegative, "{:?}", cert.min_weight);
    assert!(cert.sums_three_quarters && cert.face_point_invariant && cert.matches_assembly);
    assert!(!cert.holds());

    // A wrong row sum: W_00 grows, compensated in row 1 so c^T W is unchanged.
    let mut sum = w.clone();
    sum[(0, 0)] = sum[(0, 0)].clone() + eps.clone();
    sum[(1, 0)] = sum[(1, 0)].clone() - eps.clone() * ratio;
    let cert = certify_face_block(&block_of(&sum, &c), &c, sum).unwrap();
    assert!(!cert.sums_three_quarters);
    // Row 0 is off by exactly eps (row 1 by eps * c_0 / c_1, checked below).
    let row1 = (eps.clone() * c[0].clone() / c[1].clone()).to_f64();
    assert_eq!(cert.max_sum_defect(), eps.to_f64().max(row1));
    assert_eq!(ok.max_sum_defect(), 0.0);
    assert!(cert.nonnegative && cert.face_point_invariant && cert.matches_assembly);
    assert!(!cert.holds());

    // A face point that is not invariant: uniform c' instead of c (the block
    // is W + 1 c'^T / 4, consistent with the weights, but c'^T A != c'^T).
    let uniform = vec![Rational::frac(1, 5); 5];
    let cert = certify_face_block(&block_of(&w, &uniform), &uniform, w.clone()).unwrap();
    assert!(!cert.face_point_invariant, "{:?}", cert.invariance_defect);
    assert!(cert.nonnegative && cert.sums_three_quarters && cert.matches_assembly);
    assert!(!cert.holds());

    // An assembled block that is not the one the weights describe.
    let mut off = a.clone();
    off[(2, 3)] = off[(2, 3)].clone() + eps.clone();
    off[(2, 2)] = off[(2, 2)].clone() - eps;
    let cert = certify_face_block(&off, &c, w).unwrap();
    assert!(!cert.matches_assembly);
    assert!(!cert.holds());

    // Dimension mismatch is an error, not a panic.
    assert!(certify_face_block(&a, &c[..4], DMatrix::zeros(5, 5)).is_err());
}

/// The weights come from the knots by the theorem's formula, equal the
/// assembled rows, and the reported minimum is the smallest positive weight
/// (structural zeros excluded, so it is not 0 for n >= 4).
#[test]
fn certificate_weights_come_from_the_formula() {
    let mut rng = SplitMix64::new(9);
    for n in 3..=9 {
        let s = LocalScheme::nurds(rational_ratios(&mut rng, n, 97));
        let cert = certificate(&s).unwrap();
        assert!(cert.holds() && cert.matches_assembly, "n = {n}");
        assert_eq!(cert.assembly_defect, Rational::frac(0, 1));
        let r = s.ratios();
        let smallest = (0..n)
            .flat_map(|i| {
                let prev = (i + n - 1) % n;
                let (ri, rp) = (r.as_slice()[i].clone(), r.as_slice()[prev].clone());
                [
                    Rational::frac(1, 4) * (Rational::frac(2, 1) + ri.clone() - rp.clone()),
                    Rational::frac(1, 4) * rp,
                    Rational::frac(1, 4) * (Rational::frac(1, 1) - ri),
                ]
            })
            .min()
            .unwrap();
        assert_eq!(cert.min_positive_weight, smallest, "n = {n}");
        assert!(cert.min_positive_weight > Rational::frac(0, 1));
        if n >= 4 {
            assert_eq!(cert.min_weight, Rational::frac(0, 1), "structural zeros");
        }
    }
    // f64: the analysis reports the smallest positive weight.
    let s = LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.5, 0.3]).unwrap());
    let c = analyze(&s, &AnalyzeOptions::default())
        .unwrap()
        .contraction
        .unwrap();
    assert!(
        (c.certificate_min_weight - 0.1 / 4.0).abs() < 1e-15,
        "{c:?}"
    );
    // Original Doo-Sabin: the derived weights (n + 4)/(4n), (2 + 2 cos)/(4n).
    let w = theorem_weights(&LocalScheme::<Rational>::doo_sabin(4).unwrap()).unwrap();
    assert_eq!(w[(0, 0)], Rational::frac(8, 16));
    assert_eq!(w[(0, 1)], Rational::frac(2, 16));
    assert_eq!(w[(0, 2)], Rational::frac(0, 1));
    // The Catmull-Clark family has no face block.
    assert!(theorem_weights(&LocalScheme::<f64>::catmull_clark(5).unwrap()).is_err());
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

/// Every dimension of the
/// certificate's input is checked on its own, and the error reports the
/// count that disagrees with the face block's `n` rows.
#[test]
fn certify_face_block_checks_every_dimension() {
    use subdiv_lab::Error;
    let (a, c, w) = genuine_block();
    let bad = |r: subdiv_lab::Result<_>| match r {
        Err(Error::CountMismatch { expected, got, .. }) => (expected, got),
        other => panic!("expected a count mismatch, got {other:?}"),
    };
    let cols = |m: &DMatrix<Rational>, k: usize| m.columns(0, k).into_owned();
    let rows = |m: &DMatrix<Rational>, k: usize| m.rows(0, k).into_owned();
    // the face block not square
    assert_eq!(bad(certify_face_block(&cols(&a, 4), &c, w.clone())), (5, 4));
    // the weights with a row or a column too few
    assert_eq!(bad(certify_face_block(&a, &c, rows(&w, 4))), (5, 4));
    assert_eq!(bad(certify_face_block(&a, &c, cols(&w, 4))), (5, 4));
    // the face-point weights too short or too long
    assert_eq!(bad(certify_face_block(&a, &c[..4], w.clone())), (5, 4));
    let mut long = c.clone();
    long.push(Rational::frac(0, 1));
    assert_eq!(bad(certify_face_block(&a, &long, w.clone())), (5, 6));
    assert!(certify_face_block(&a, &c, w).unwrap().holds());
}

/// The measured rate with no
/// level (nothing to fit: rate 0, no ratio) and with one level (the ratio is
/// `m_1 / m_0`, and the fitted rate over the one level is that ratio).
#[test]
fn measured_rate_with_zero_and_one_level() {
    let s = LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.5]).unwrap());
    let opts = |levels| MeasureOptions {
        levels,
        ..MeasureOptions::default()
    };
    let m = measure(&s, &opts(0)).unwrap();
    assert_eq!(m.distances.len(), 1);
    assert!(m.distances[0] > 0.0);
    assert!(m.ratios.is_empty());
    assert_eq!((m.max_ratio, m.fitted_rate), (0.0, 0.0));
    let m = measure(&s, &opts(1)).unwrap();
    assert_eq!(m.distances.len(), 2);
    assert_eq!(m.ratios, vec![m.distances[1] / m.distances[0]]);
    assert_eq!(m.max_ratio, m.ratios[0]);
    assert_eq!(m.fitted_rate, m.ratios[0]);
    assert!(m.max_ratio > 0.0 && m.max_ratio <= 0.75);
}

/// `Measured::ratios` is
/// NaN-free; it stops at the first level where `m_k = 0`. Enough levels
/// drive the distances below the smallest subnormal (`|lambda_1| = 3/8` for
/// the valence-3 Catmull-Clark variant: `(3/8)^k < 2^-1074` from `k = 760`);
/// from there on they are exactly 0 (the face corners move only among
/// themselves, towards the invariant face point), and the fitted rate of a
/// window that ends at 0 is 0.
#[test]
fn measured_ratios_stop_where_the_distance_underflows_to_zero() {
    let s = LocalScheme::<f64>::cc_variant(3).unwrap();
    let m = measure(
        &s,
        &MeasureOptions {
            levels: 1000,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    assert_eq!(m.distances.len(), 1001);
    let first_zero = m
        .distances
        .iter()
        .position(|&d| d == 0.0)
        .expect("the distances underflow to 0");
    assert!(first_zero > 100, "{first_zero}");
    assert!(m.distances[first_zero..].iter().all(|&d| d == 0.0));
    assert_eq!(m.ratios.len(), first_zero);
    assert!(m.ratios.iter().all(|r| r.is_finite() && *r >= 0.0));
    assert_eq!(m.fitted_rate, 0.0);
}
