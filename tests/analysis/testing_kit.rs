//! The public testing kit used exactly as a user would (feature `testing`).
#![cfg(feature = "testing")]

use nalgebra::DMatrix;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestError, TestRunner};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::schemes::SchemeKind;
use subdiv_lab::spectral::ClassName;
use subdiv_lab::testing::assertions::{
    check_affine_invariance, check_charmap_regular_injective, check_dominant_simple,
    check_face_contraction, check_mesh_contraction, check_spectral_radius, check_subdominant_class,
    ROW_SUM_TOL,
};
use subdiv_lab::testing::strategies::{
    edge_ratios, face_ep_ratios, meshes_with_knots, nurds_schemes, nurds_with_points,
    vertex_ep_ratios, IntervalBox, GRID_RESOLUTION,
};

/// Uniform knots to within the strategy grid: a log-interval one grid step
/// off moves a ratio by GRID_RESOLUTION / 4; two intervals per ratio.
fn near_uniform(r: &[f64]) -> bool {
    r.iter().all(|&x| (x - 0.5).abs() <= GRID_RESOLUTION / 2.0)
}

/// A runner with a fixed seed: the shrunk counterexample is reproducible.
fn deterministic_runner(config: Config) -> TestRunner {
    let rng = proptest::test_runner::TestRng::deterministic_rng(config.rng_algorithm);
    TestRunner::new_with_rng(config, rng)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Theorem 1 for NURDS in a knot box with extreme draws.
    #[test]
    fn nurds_keeps_the_three_quarter_bound(
        (scheme, points) in nurds_with_points(3..=9, IntervalBox::new(1e-2, 1e2).unwrap().with_extremes(0.2))
    ) {
        let s = scheme.matrix()?;
        check_affine_invariance(s.matrix(), &scheme, ROW_SUM_TOL)?;
        check_face_contraction(s.matrix(), scheme.valence(), &points, 0.75, 40, &scheme)?;
    }

    /// The spectral facts of math doc sections 4-7 for random knots.
    #[test]
    fn nurds_spectral_facts(scheme in nurds_schemes(3..=8, IntervalBox::new(0.05, 20.0).unwrap())) {
        let s = scheme.matrix()?;
        check_dominant_simple(s.matrix(), &scheme)?;
        check_spectral_radius(s.matrix(), 0.75, &scheme)?;
        // Generic non-uniform knots break the double subdominant eigenvalue.
        check_subdominant_class(&scheme, &[ClassName::Standard, ClassName::RealDistinct, ClassName::ComplexPair, ClassName::Defective])?;
        check_charmap_regular_injective(&scheme)?;
    }

    #[test]
    fn face_ep_spectral_radius(r in face_ep_ratios(3..=10, IntervalBox::new(0.1, 10.0).unwrap().with_extremes(0.1))) {
        let scheme = LocalScheme::nurds(r);
        check_spectral_radius(scheme.matrix()?.matrix(), 0.75, &scheme)?;
    }

    #[test]
    fn vertex_ep_configurations_are_affine(r in vertex_ep_ratios(3..=12, IntervalBox::new(0.1, 10.0).unwrap())) {
        let s = LocalScheme::nurds(r.clone()).matrix()?;
        check_affine_invariance(s.matrix(), &r, ROW_SUM_TOL)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Mesh-level Theorem 1 on small closed meshes with random directed-edge knots.
    #[test]
    fn meshes_contract(mesh in meshes_with_knots(IntervalBox::new(0.2, 5.0).unwrap())) {
        check_mesh_contraction(&mesh, SchemeKind::Nurds, 3, 0.75)?;
    }
}

#[test]
fn broken_spectral_radius_is_reported_with_a_shrunk_counterexample() {
    let mut runner = deterministic_runner(Config {
        cases: 32,
        failure_persistence: None,
        // proptest stops shrinking after 128 steps by default; a fully shrunk
        // counterexample needs a few dozen steps per coordinate.
        max_shrink_iters: 1_000_000,
        ..Config::default()
    });
    let strategy = nurds_schemes(3..=10, IntervalBox::new(0.1, 10.0).unwrap());
    let result = runner.run(&strategy, |scheme| {
        check_spectral_radius(&under_relaxed(&scheme), 0.75, &scheme)?;
        Ok(())
    });
    match result {
        Err(TestError::Fail(reason, scheme)) => {
            assert_eq!(scheme.valence(), 3, "not shrunk: {scheme:?}");
            assert!(near_uniform(scheme.ratios().as_slice()), "{scheme:?}");
            let msg = reason.to_string();
            // uniform n = 3: lambda_1 = 3/8, under-relaxed: 3/4 + 3/32 = 0.84375
            assert!(
                msg.contains("non-unit spectral radius failed")
                    && msg.contains("|lambda_1| = 0.84375"),
                "{msg}"
            );
            assert!(msg.contains("exceeds the bound 0.75"), "{msg}");
        }
        other => panic!("the broken scheme was not caught: {other:?}"),
    }
}

/// A test-local "broken" variant: the face block under-relaxed,
/// `A' = (3 I + A) / 4`. Row sums stay 1, but the per-step contraction bound
/// becomes 15/16 and the asymptotic rate `3/4 + |lambda_1| / 4 > 3/4` for every n.
fn under_relaxed(scheme: &LocalScheme) -> DMatrix<f64> {
    let n = scheme.valence();
    let mut m = scheme.matrix().expect("valid scheme").into_matrix();
    let block = m.view((0, 0), (n, n)).into_owned();
    let relaxed = (DMatrix::identity(n, n) * 3.0 + block) * 0.25;
    m.view_mut((0, 0), (n, n)).copy_from(&relaxed);
    m
}

#[test]
fn broken_contraction_is_reported_with_a_shrunk_counterexample() {
    let mut runner = deterministic_runner(Config {
        cases: 64,
        failure_persistence: None,
        // proptest stops shrinking after 128 steps by default; a fully shrunk
        // counterexample needs a few dozen steps per coordinate.
        max_shrink_iters: 1_000_000,
        ..Config::default()
    });
    let strategy = nurds_with_points(3..=10, IntervalBox::new(0.1, 10.0).unwrap());
    let result = runner.run(&strategy, |(scheme, points)| {
        check_face_contraction(
            &under_relaxed(&scheme),
            scheme.valence(),
            &points,
            0.75,
            20,
            &scheme,
        )?;
        Ok(())
    });
    match result {
        Err(TestError::Fail(reason, (scheme, _points))) => {
            // Shrinking reaches the smallest valence and uniform knots.
            assert_eq!(scheme.valence(), 3, "not shrunk: {scheme:?}");
            let r = scheme.ratios();
            assert!(
                near_uniform(r.as_slice()),
                "knots not shrunk to uniform: {r:?}"
            );
            let msg = reason.to_string();
            assert!(msg.contains("face contraction failed for Nurds"), "{msg}");
            assert!(msg.contains("> factor 0.75"), "{msg}");
            assert!(msg.contains("level"), "{msg}");
        }
        other => panic!("the broken scheme was not caught: {other:?}"),
    }
}

#[test]
fn broken_affine_invariance_names_the_row() {
    let mut runner = deterministic_runner(Config {
        cases: 32,
        failure_persistence: None,
        // proptest stops shrinking after 128 steps by default; a fully shrunk
        // counterexample needs a few dozen steps per coordinate.
        max_shrink_iters: 1_000_000,
        ..Config::default()
    });
    let strategy = edge_ratios(3..=12, 0.05, 0.95);
    let result = runner.run(&strategy, |r| {
        let scheme = LocalScheme::nurds(r);
        let n = scheme.valence();
        let mut m = scheme.matrix()?.into_matrix();
        m[(n + 1, 0)] += 1e-6; // perturb one weight of E_0,2
        check_affine_invariance(&m, &scheme, ROW_SUM_TOL)?;
        Ok(())
    });
    match result {
        Err(TestError::Fail(reason, r)) => {
            assert_eq!(r.valence(), 3);
            // ratios shrink towards 1/2
            assert!(near_uniform(r.as_slice()), "{r:?}");
            let msg = reason.to_string();
            assert!(
                msg.contains("affine invariance failed") && msg.contains("row 4 sums to"),
                "{msg}"
            );
        }
        other => panic!("the broken scheme was not caught: {other:?}"),
    }
}
