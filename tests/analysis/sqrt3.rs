//! Kobbelt's sqrt(3) scheme (`schemes::sqrt3`, math doc section 21): one
//! step turns the ring (complex subdominant pair), the two-step matrix read
//! in the old layout is real with Kobbelt's eigenvalues, both rings nest,
//! the limit stencil, exactness at n = 3, 4, 6, and what `analyze` reports.

use super::butterfly::{eigenvalues, nests, shared_eigenvalues_agree};
use std::f64::consts::PI;
use subdiv_lab::scalar::Rational;
use subdiv_lab::schemes::sqrt3::{
    alpha, limit_weights, local_matrix, local_matrix_on, one_step_matrix, one_step_matrix_on,
};
use subdiv_lab::schemes::{LocalScheme, Scheme, SchemeKind};
use subdiv_lab::spectral::{analyze, AnalyzeOptions, SubdominantClass};

/// See `butterfly::EIG_TOL`.
const EIG_TOL: f64 = 1e-10;

/// One step maps the neighbour `e_i` direction onto the face point between
/// `e_i` and `e_{i+1}`: the Fourier mode `l = 1` of the one-ring has the
/// eigenvalue `(1 + exp(2 pi i / n)) / 3`, modulus `2 cos(pi / n) / 3`,
/// argument `pi / n` (Kobbelt 2000, section 4). Planted: face points with
/// the weights (1/2, 1/4, 1/4) instead of 1/3 each make this fail.
#[test]
fn one_step_has_the_turned_complex_pair() {
    for n in 3..=12 {
        let e = eigenvalues(one_step_matrix(n).unwrap().matrix());
        let want = (num_complex::Complex64::new(1.0, 0.0)
            + num_complex::Complex64::from_polar(1.0, 2.0 * PI / n as f64))
            / 3.0;
        assert!((e[0] - 1.0).norm() < EIG_TOL);
        let hit = |w: num_complex::Complex64| e.iter().any(|z| (z - w).norm() < EIG_TOL);
        assert!(hit(want) && hit(want.conj()), "n={n}: {e:?}");
        assert!(
            (e[1].norm() - 2.0 * (PI / n as f64).cos() / 3.0).abs() < EIG_TOL,
            "n={n}"
        );
        assert!(e[1].im.abs() > 0.1, "n={n}: the one-step pair is complex");
    }
}

/// Kobbelt's `alpha_n` makes the two-step matrix's subdominant eigenvalue
/// `lambda = (2 + 2 cos(2 pi / n)) / 9` (double, real) and its mode-0
/// eigenvalue `(2/3 - alpha_n)^2 = lambda^2` (Kobbelt 2000, section 4: the
/// choice of `alpha_n`). Planted: `alpha_n = (4 - cos(2 pi / n)) / 9` makes
/// this fail.
#[test]
fn two_steps_have_kobbelts_real_eigenvalues() {
    for n in 3..=12 {
        let e = eigenvalues(local_matrix(n).unwrap().matrix());
        let lambda = (2.0 + 2.0 * (2.0 * PI / n as f64).cos()) / 9.0;
        assert!((e[0] - 1.0).norm() < EIG_TOL, "n={n}");
        assert!(
            (e[1] - lambda).norm() < EIG_TOL && (e[2] - lambda).norm() < EIG_TOL,
            "n={n}: {e:?}"
        );
        assert!(
            e.iter().any(|z| (z - lambda * lambda).norm() < EIG_TOL),
            "n={n}"
        );
        let a: f64 = alpha(n).unwrap();
        assert!(((2.0 / 3.0 - a) - lambda).abs() < 1e-15);
    }
}

/// The one-ring is closed under one step, the two-ring nests exactly in the
/// three-ring (one step and two), and the spectra agree on the shared
/// eigenvalues.
#[test]
fn the_two_ring_nests_in_the_three_ring_and_the_one_ring_is_closed() {
    for n in [3, 4, 6] {
        let s1 = local_matrix_on::<Rational>(n, 1).unwrap();
        let s2 = local_matrix_on::<Rational>(n, 2).unwrap();
        let s3 = local_matrix_on::<Rational>(n, 3).unwrap();
        assert!(nests(s1.matrix(), s2.matrix()), "n={n}");
        assert!(nests(s2.matrix(), s3.matrix()), "n={n}");
        let o2 = one_step_matrix_on::<Rational>(n, 2).unwrap();
        let o3 = one_step_matrix_on::<Rational>(n, 3).unwrap();
        assert!(nests(o2.matrix(), o3.matrix()), "n={n}");
    }
    for n in [5, 7] {
        let e2 = eigenvalues(local_matrix_on::<f64>(n, 2).unwrap().matrix());
        let e3 = eigenvalues(local_matrix_on::<f64>(n, 3).unwrap().matrix());
        shared_eigenvalues_agree(&e2, &e3, 0.0);
    }
}

#[test]
fn the_limit_stencil_is_the_left_eigenvector_and_exactness_follows_alpha() {
    for n in [3, 5, 6, 9] {
        let l = limit_weights(n).unwrap();
        for m in [one_step_matrix(n).unwrap(), local_matrix(n).unwrap()] {
            let s = m.matrix();
            for j in 0..s.ncols() {
                let x: f64 = (0..s.nrows()).map(|i| l[i] * s[(i, j)]).sum();
                assert!((x - l[j]).abs() < 1e-14, "n={n} column {j}");
            }
        }
    }
    // regular valence: beta = 1/2
    assert!((limit_weights(6).unwrap()[0] - 0.5).abs() < 1e-15);
    for n in [3, 4, 6] {
        let s = LocalScheme::from_kind(SchemeKind::Sqrt3, n, None).unwrap();
        let q = s.exact_local_matrix().unwrap().unwrap().to_f64();
        let d = (q.matrix() - s.local_matrix().unwrap().matrix())
            .abs()
            .max();
        assert!(d < 1e-15, "n={n}: {d}");
    }
    let s5 = LocalScheme::from_kind(SchemeKind::Sqrt3, 5, None).unwrap();
    assert!(s5.exact_local_matrix().is_none());
    assert!(alpha::<Rational>(5).is_err());
}

/// `analyze` works on the two-step matrix and says so, with the one-step
/// spectrum beside it; the characteristic map is `no_charmap`.
#[test]
fn analyze_uses_the_two_step_matrix_and_reports_the_one_step_spectrum() {
    let s = LocalScheme::from_kind(SchemeKind::Sqrt3, 5, None).unwrap();
    let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
    let st = a.steps.as_ref().unwrap();
    assert_eq!(st.matrix_steps, 2);
    assert!(st.one_step_eigenvalues[1][1].abs() > 0.1);
    assert_eq!(a.subdominant.class, SubdominantClass::Standard);
    assert!(a.subdominant.lambda1.im == 0.0);
    let c = subdiv_lab::charmap::check_classified(&s, &a.charmap_subdominant()).unwrap();
    assert_eq!(c.verdict.code(), "no_charmap");
}

/// The second ring is needed: two steps take `g_0` to non-zero new points of
/// the two-ring, which lie within distance `2/3` of `v` (two steps scale by
/// 1/3), inside the old one-ring (math doc section 21).
#[test]
fn a_second_ring_point_reaches_the_one_ring_in_two_steps() {
    for n in [3, 5, 6, 8] {
        let s = local_matrix_on::<f64>(n, 2).unwrap().into_matrix();
        let mut x = nalgebra::DVector::zeros(s.ncols());
        x[n + 1] = 1.0; // g_0
        let y = &s * x;
        assert!(y.iter().any(|v| v.abs() > 1e-3), "n={n}");
    }
}
