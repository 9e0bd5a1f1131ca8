//! The public testing kit used exactly as a user would (feature `testing`).
#![cfg(feature = "testing")]

use nalgebra::DMatrix;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestError, TestRunner};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::testing::assertions::{
    check_affine_invariance, check_face_contraction, ROW_SUM_TOL,
};
use subdiv_lab::testing::strategies::{
    edge_ratios, nurds_with_points, vertex_ep_ratios, IntervalBox,
};

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

    #[test]
    fn vertex_ep_configurations_are_affine(r in vertex_ep_ratios(3..=12, IntervalBox::new(0.1, 10.0).unwrap())) {
        let s = LocalScheme::nurds(r.clone()).matrix()?;
        check_affine_invariance(s.matrix(), &r, ROW_SUM_TOL)?;
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
    let mut runner = TestRunner::new(Config {
        cases: 64,
        failure_persistence: None,
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
                r.as_slice().iter().all(|&x| x == 0.5),
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
    let mut runner = TestRunner::new(Config {
        cases: 32,
        failure_persistence: None,
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
            assert!(r.as_slice().iter().all(|&x| x == 0.5), "{r:?}");
            let msg = reason.to_string();
            assert!(
                msg.contains("affine invariance failed") && msg.contains("row 4 sums to"),
                "{msg}"
            );
        }
        other => panic!("the broken scheme was not caught: {other:?}"),
    }
}
