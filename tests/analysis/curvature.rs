//! Second order at extraordinary points (math doc section 13): the curvature
//! verdict against eigenvalues computed here independently, the exact
//! certificate, the measured curvature rates, and the certified tuning of
//! the shape-adjustable scheme.

use crate::example_scheme as own_scheme;

use own_scheme::VertexWeightCc;
use proptest::prelude::*;
use std::f64::consts::PI;
use subdiv_lab::curvature::measured::measure;
use subdiv_lab::curvature::tuning::{cos_enclosures, enclosure, tune, Sign};
use subdiv_lab::curvature::{certify_rational, curvature, CurvatureEvidence, CurvatureVerdict};
use subdiv_lab::schemes::catmull_clark::fourier;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{analyze, AnalyzeOptions, SpectrumPath};
use subdiv_lab::Scheme;

/// Catmull-Clark's eigenvalue moduli from Stam's closed forms (Stam 1998,
/// appendix; written out here, not taken from the crate): Fourier block
/// `l >= 1` gives `(5 + cos t +- cos(t/2) sqrt(2 (9 + cos t))) / 16`,
/// `t = 2 pi l / n`; block 0 gives 1 and `(3n - 7 +- sqrt(5n^2 - 30n + 49)) / (8n)`.
/// Returns `(lambda, mu)`: the largest non-unit modulus and the one after the pair.
fn stam_lambda_mu(n: usize) -> (f64, f64) {
    let nf = n as f64;
    let mut m = Vec::new();
    let s0 = (5.0 * nf * nf - 30.0 * nf + 49.0).sqrt();
    m.push(((3.0 * nf - 7.0 + s0) / (8.0 * nf)).abs());
    m.push(((3.0 * nf - 7.0 - s0) / (8.0 * nf)).abs());
    for l in 1..n {
        let t = 2.0 * PI * l as f64 / nf;
        let r = (t / 2.0).cos() * (2.0 * (9.0 + t.cos())).sqrt();
        m.push(((5.0 + t.cos() + r) / 16.0).abs());
        m.push(((5.0 + t.cos() - r) / 16.0).abs());
    }
    m.sort_by(|a, b| b.total_cmp(a));
    assert!((m[0] - m[1]).abs() < 1e-15, "the pair l = 1, n - 1");
    (m[0], m[2])
}

#[test]
fn catmull_clark_zero_at_3_bounded_at_4_unbounded_from_5() {
    for n in 3..=16 {
        let (lambda, mu) = stam_lambda_mu(n);
        let expected = match n {
            3 => CurvatureVerdict::Zero,
            4 => CurvatureVerdict::Bounded,
            _ => CurvatureVerdict::Unbounded,
        };
        // The independent eigenvalues say the same (away from n = 4 by a margin).
        let margin = mu - lambda * lambda;
        match n {
            3 => assert!(margin < -1e-3, "n=3: {margin}"),
            4 => assert!(margin.abs() < 1e-15),
            _ => assert!(margin > 1e-2, "n={n}: {margin}"),
        }
        let s = LocalScheme::<f64>::catmull_clark(n).unwrap();
        let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
        let c = &a.curvature;
        assert_eq!(c.verdict, expected, "n={n}: {}", c.reason);
        assert!((c.lambda - lambda).abs() < 1e-12, "n={n}");
        assert!((c.mu - mu).abs() < 1e-12, "n={n}");
        assert!((c.mu_over_lambda_squared - mu / (lambda * lambda)).abs() < 1e-11);
        let evidence = if n == 4 {
            CurvatureEvidence::Exact
        } else {
            CurvatureEvidence::Float
        };
        assert_eq!(c.evidence, evidence, "n={n}");
        // The structured path agrees (it adds the dense decomposition).
        let st = analyze(
            &s,
            &AnalyzeOptions {
                path: SpectrumPath::Structured,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(st.curvature.verdict, expected, "n={n} structured");
    }
}

#[test]
fn mu_multiplicity_and_modes_of_catmull_clark() {
    // n = 4: mu = 1/4 from block 0 and the double root of block 2 (theta = pi).
    let c4 = curvature(&LocalScheme::<f64>::catmull_clark(4).unwrap()).unwrap();
    assert_eq!(c4.mu_multiplicity, 3);
    assert_eq!(c4.mu_mode.as_deref(), Some(&[0, 2][..]));
    assert!(c4.reason.contains("lambda = 1/2") && c4.reason.contains("mu = 1/4"));
    // n = 3: mu = 1/6 from block 0 ((3n - 7 + sqrt(5n^2 - 30n + 49)) / (8n) = 4/24).
    let c3 = curvature(&LocalScheme::<f64>::catmull_clark(3).unwrap()).unwrap();
    assert!((c3.mu - 1.0 / 6.0).abs() < 1e-14);
    assert_eq!(c3.mu_mode.as_deref(), Some(&[0][..]));
    assert_eq!(c3.mu_multiplicity, 1);
    // n >= 5: the pair of block 2 (l = 2 and n - 2).
    for n in 5..=10 {
        let c = curvature(&LocalScheme::<f64>::catmull_clark(n).unwrap()).unwrap();
        assert_eq!(c.mu_mode.as_deref(), Some(&[2][..]), "n={n}");
        assert_eq!(c.mu_multiplicity, 2, "n={n}");
    }
}

#[test]
fn loop_verdicts_from_its_closed_form_spectrum() {
    // Loop: lambda = 3/8 + cos(2 pi/n)/4 (double), block 0 has lambda^2 exactly,
    // block 2 has 3/8 + cos(4 pi/n)/4, and 1/8 is an eigenvalue (n times).
    for n in 3..=12 {
        let nf = n as f64;
        let lambda = 0.375 + 0.25 * (2.0 * PI / nf).cos();
        // (for n = 3 block 2 is block 1's conjugate: the pair itself)
        let block2 = if n > 3 {
            0.375 + 0.25 * (4.0 * PI / nf).cos()
        } else {
            0.0
        };
        let mu = (lambda * lambda).max(block2.abs()).max(0.125);
        let c = curvature(&LocalScheme::loop_subdivision(n).unwrap()).unwrap();
        assert!((c.mu - mu).abs() < 1e-12, "n={n}");
        let rational = matches!(n, 3 | 4 | 6);
        let expected = if mu - lambda * lambda > 1e-6 {
            CurvatureVerdict::Unbounded
        } else if rational {
            // mu = lambda^2 in closed form, and the two-ring matrix is
            // rational (cos(2 pi/n) in {-1/2, 0, 1/2}): certified exactly.
            CurvatureVerdict::Bounded
        } else {
            // mu = lambda^2 in closed form; the weights are irrational, so
            // there is no exact matrix and the float verdict must not guess.
            CurvatureVerdict::Indeterminate
        };
        assert_eq!(c.verdict, expected, "n={n}: {}", c.reason);
        if expected == CurvatureVerdict::Bounded {
            assert_eq!(c.evidence, CurvatureEvidence::Exact, "n={n}");
        }
        assert!(c.mu_mode.is_some());
    }
}

#[test]
fn uniform_doo_sabin_family_is_certified_where_rational() {
    // cc-variant = uniform NURDS: at n = 4 (tensor product) lambda = 1/2, mu = 1/4.
    for s in [
        LocalScheme::<f64>::cc_variant(4).unwrap(),
        LocalScheme::nurds(subdiv_lab::knots::EdgeRatios::uniform(4).unwrap()),
    ] {
        let c = curvature(&s).unwrap();
        assert_eq!(c.verdict, CurvatureVerdict::Bounded, "{}", c.reason);
        assert_eq!(c.evidence, CurvatureEvidence::Exact);
        assert!(c.mu_mode.is_none());
    }
    // Original Doo-Sabin at n = 5 has irrational weights: no exact matrix, and
    // its mu = lambda^2 = 1/4 stays indeterminate.
    let ds = curvature(&LocalScheme::<f64>::doo_sabin(5).unwrap()).unwrap();
    assert_eq!(ds.verdict, CurvatureVerdict::Indeterminate, "{}", ds.reason);
    // At n = 3, 4, 6 its weights are rational (cos(2 pi/n) in {-1/2, 0, 1/2}):
    // lambda = 1/2 and mu = 1/4 = lambda^2 are certified. At n = 3, 4 the
    // eigenvalue 1/4 is non-defective: bounded. At n = 6 it has a Jordan
    // block (the curvature grows like the level k): unbounded, certified.
    for n in [3, 4, 6] {
        let ds = curvature(&LocalScheme::<f64>::doo_sabin(n).unwrap()).unwrap();
        let expected = if n == 6 {
            CurvatureVerdict::Unbounded
        } else {
            CurvatureVerdict::Bounded
        };
        assert_eq!(ds.verdict, expected, "n={n}: {}", ds.reason);
        assert_eq!(ds.evidence, CurvatureEvidence::Exact, "n={n}");
        assert_eq!(
            ds.reason.contains("defective"),
            n == 6,
            "n={n}: {}",
            ds.reason
        );
    }
}

/// Geometric multiplicity of `mu` from an SVD of `S - mu I` in floating
/// point, independent of the exact rank used by the certificate: the number
/// of singular values below `1e-9` (the others are of order 1e-2 or more for
/// these small rational matrices).
fn float_eigenvectors(s: &nalgebra::DMatrix<f64>, mu: f64) -> usize {
    let n = s.nrows();
    let a = s - nalgebra::DMatrix::<f64>::identity(n, n) * mu;
    a.svd(false, false)
        .singular_values
        .iter()
        .filter(|&&x| x < 1e-9)
        .count()
}

#[test]
fn the_exact_certificate_counts_eigenvectors_of_mu() {
    // Original Doo-Sabin, mu = 1/4: the certificate's eigenvector count is
    // the float SVD's null-space dimension, and below the multiplicity
    // (a Jordan block) exactly at n = 6.
    for n in [3, 4, 6] {
        let s = LocalScheme::<f64>::doo_sabin(n).unwrap();
        let m = s.exact_local_matrix().unwrap().unwrap();
        let x = certify_rational(m.matrix(), 0.5, 0.25, 1e-12, 1e-12).unwrap();
        let f = s.local_matrix().unwrap();
        assert_eq!(
            x.mu_eigenvectors,
            float_eigenvectors(f.matrix(), 0.25),
            "n={n}"
        );
        assert_eq!(
            x.mu_eigenvectors < x.mu_multiplicity,
            n == 6,
            "n={n}: {x:?}"
        );
    }
    // Catmull-Clark at n = 4 (the regular case): bounded, non-defective.
    let s = LocalScheme::<f64>::catmull_clark(4).unwrap();
    let m = s.exact_local_matrix().unwrap().unwrap();
    let x = certify_rational(m.matrix(), 0.5, 0.25, 1e-12, 1e-12).unwrap();
    assert_eq!(x.mu_eigenvectors, x.mu_multiplicity);
}

#[test]
fn a_scheme_from_outside_the_crate_gets_the_dense_default() {
    for n in [3, 5, 6] {
        let own = curvature(&VertexWeightCc::catmull_clark(n)).unwrap();
        let builtin = curvature(&LocalScheme::<f64>::catmull_clark(n).unwrap()).unwrap();
        assert_eq!(own.verdict, builtin.verdict, "n={n}");
        assert!((own.mu - builtin.mu).abs() < 1e-12);
        assert!(own.mu_mode.is_none(), "no Fourier capability");
    }
    // n = 4 without an exact matrix: mu = lambda^2 cannot be certified.
    let own4 = curvature(&VertexWeightCc::catmull_clark(4)).unwrap();
    assert_eq!(own4.verdict, CurvatureVerdict::Indeterminate);
}

#[test]
fn the_exact_certificate_rejects_wrong_candidates() {
    let s = LocalScheme::<f64>::catmull_clark(4).unwrap();
    let m = s.exact_local_matrix().unwrap().unwrap();
    assert!(certify_rational(m.matrix(), 0.5, 0.25, 1e-12, 1e-12).is_ok());
    // mu = 1/8 is a root, but 1/4 lies above it.
    // (1/4 and 1/16 are symmetric about |z| = 1/8: the Schur-Cohn count is
    // singular, which is also a refusal)
    let e = certify_rational(m.matrix(), 0.5, 0.125, 1e-12, 1e-12).unwrap_err();
    assert!(e.contains("mu = 1/8"), "{e}");
    // lambda = 1/4 has multiplicity 3, not 2.
    let e = certify_rational(m.matrix(), 0.25, 0.125, 1e-12, 1e-12).unwrap_err();
    assert!(e.contains("multiplicity"), "{e}");
    // n = 5: lambda is irrational.
    let s5 = LocalScheme::<f64>::catmull_clark(5).unwrap();
    let m5 = s5.exact_local_matrix().unwrap().unwrap();
    let c5 = curvature(&s5).unwrap();
    assert!(certify_rational(m5.matrix(), c5.lambda, c5.mu, 1e-12, 1e-12).is_err());
}

/// Relative tolerance of the measured rates at level 16. The fitted
/// quadric's per-level ratios converge to the predicted rates with
/// corrections of relative order `(nu/mu)^k` (the next eigenvalue of the same
/// Fourier block) and `(mu/lambda)^k` (the tangential parametrisation); at
/// `k = 16` these leave deviations of at most 6e-4 for the valences tested
/// (n = 3: 5e-4 from the slow block-0 convergence); 2e-3 allows three times
/// that and is still 40 times smaller than the smallest gap between the
/// predicted rate and 1 away from n = 4 (n = 3: 9e-3).
const RATE_TOL: f64 = 2e-3;

#[test]
fn measured_curvature_follows_mu_over_lambda_squared() {
    let k = 16;
    // n = 3: mu is in block 0, the mean curvature carries it.
    let m = measure(3, 0.5, k, 7).unwrap();
    let l = &m.levels;
    let rate = l[k].mean / l[k - 1].mean;
    assert!(
        (rate - m.predicted_rate).abs() < RATE_TOL * m.predicted_rate,
        "n=3: {rate} vs {}",
        m.predicted_rate
    );
    assert!(rate < 1.0, "n=3: the curvature decreases");
    // n = 4: bounded; both parts keep their size.
    let m = measure(4, 0.5, k, 7).unwrap();
    for (a, b) in [
        (m.levels[k].mean, m.levels[k - 1].mean),
        (m.levels[k].twist, m.levels[k - 1].twist),
    ] {
        assert!((a / b - 1.0).abs() < RATE_TOL, "n=4: {}", a / b);
    }
    // n >= 5: mu is the pair of block 2, carried by the twist (the half
    // difference of the principal curvatures). (The mean curvature follows
    // block 0's slower rate, but with the larger correction (mu/lambda)^k
    // from the twist leaking through the parametrisation: not tested.)
    for n in 5..=8 {
        let m = measure(n, 0.5, k, 11).unwrap();
        let l = &m.levels;
        let twist = l[k].twist / l[k - 1].twist;
        let pred = m.twist_rate.unwrap();
        assert!(
            (pred - m.predicted_rate).abs() < 1e-12,
            "n={n}: mu is in block 2"
        );
        assert!(
            (twist - pred).abs() < RATE_TOL * pred,
            "n={n}: {twist} vs {pred}"
        );
    }
}

#[test]
fn tuning_roots_are_certified_and_where_the_floats_change_sign() {
    let f = |n: usize, c: f64| {
        let s = fourier::patch_spectrum(n, c).unwrap();
        s[3].norm() - s[1].norm().powi(2)
    };
    let expected_roots = [(3, 2), (4, 0), (5, 1), (6, 1)];
    for (n, count) in expected_roots {
        let t = tune(n, 64).unwrap();
        assert_eq!(t.roots.len(), count, "n={n}: {:?}", t.roots);
        for r in &t.roots {
            assert!(r.c_hi - r.c_lo <= 1e-12);
            // Independent f64 evaluation just outside the bracket agrees.
            let (a, b) = (f(n, r.c_lo - 1e-9), f(n, r.c_hi + 1e-9));
            assert!(a * b < 0.0, "n={n}: {a} {b}");
            assert_eq!(r.below == Sign::Negative, a < 0.0);
        }
    }
    // n = 4: mu = lambda^2 on [1/2, 1] (certified exactly on the 1/32 grid),
    // mu > lambda^2 below 1/2.
    let t = tune(4, 64).unwrap();
    for p in &t.curve {
        if p.c >= 0.5 {
            assert_eq!(p.sign, Sign::Undecided, "c={}", p.c);
            assert_eq!(p.exact_bounded, (p.c * 32.0).fract() == 0.0, "c={}", p.c);
        } else {
            assert_eq!(p.sign, Sign::Positive, "c={}", p.c);
        }
    }
    // n >= 7: unbounded for every c in [0, 1], certified at every sample.
    for n in 7..=16 {
        let t = tune(n, 64).unwrap();
        assert!(t.roots.is_empty());
        assert!(t.curve.iter().all(|p| p.sign == Sign::Positive), "n={n}");
    }
}

/// The second `n = 3` tuning root is where the regular part's `c/4` (an
/// eigenvalue of the patch matrix, not of the one-ring) meets `lambda^2`:
/// `lambda(c)` from block 1's closed form (trace `3/4 - 3c/8` at
/// `cos(2 pi/3) = -1/2`, determinant `(1 - c)/8`), the crossing by bisection
/// here. (The one-ring alone puts the root at `0.79686`.)
#[test]
fn the_second_n3_tuning_root_is_the_regular_part_crossing() {
    let lambda = |c: f64| {
        let t = 0.75 - 0.375 * c;
        0.5 * (t + (t * t - 0.5 * (1.0 - c)).sqrt())
    };
    let g = |c: f64| c / 4.0 - lambda(c).powi(2);
    let (mut lo, mut hi) = (0.6, 0.7);
    assert!(g(lo) < 0.0 && g(hi) > 0.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = tune(3, 64).unwrap();
    assert_eq!(t.roots.len(), 2);
    let r = &t.roots[1];
    assert!(
        r.c_lo <= hi + 1e-12 && lo - 1e-12 <= r.c_hi,
        "{r:?} vs {lo}"
    );
    assert_eq!((r.below, r.above), (Sign::Negative, Sign::Positive));
    assert!((lo - 0.631231).abs() < 1e-6, "{lo}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The interval enclosures contain the closed-form f64 values computed
    /// by a different route (complex quadratic roots, sorted spectrum).
    #[test]
    fn enclosures_contain_the_float_values(n in 3usize..=16, c in 0.0f64..=1.0) {
        let cos = cos_enclosures(n).unwrap();
        let [lambda, mu, _] = enclosure(n, c, &cos);
        let s = fourier::patch_spectrum(n, c).unwrap();
        let slack = 1e-14;
        prop_assert!(lambda.lo - slack <= s[1].norm() && s[1].norm() <= lambda.hi + slack);
        // lambda >= 3/8 > 1/4 >= c/4: the regular part never reaches the pair.
        prop_assert!(lambda.lo >= 0.375 - slack && lambda.lo > c / 4.0);
        prop_assert!(mu.lo - slack <= s[3].norm() && s[3].norm() <= mu.hi + slack);
        // near a double root of a block the sqrt of the rounded discriminant
        // widens the enclosure to about sqrt(eps)
        prop_assert!(lambda.hi - lambda.lo < 1e-6 && mu.hi - mu.lo < 1e-6);
    }
}
