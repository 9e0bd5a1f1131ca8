//! The modified butterfly scheme (`schemes::modified_butterfly`, math doc
//! section 21): the weights of Zorin, Schroder and Sweldens, the
//! three-ring's nesting in the four-ring, the subdominant eigenvalue 1/2 at
//! every valence, exact matrices where the weights are rational.

use super::butterfly::{eigenvalues, nests, shared_eigenvalues_agree};
use subdiv_lab::scalar::Rational;
use subdiv_lab::schemes::modified_butterfly::{
    extraordinary_weights, local_matrix, local_matrix_on,
};
use subdiv_lab::schemes::{LocalScheme, Scheme, SchemeKind};
use subdiv_lab::spectral::{analyze, AnalyzeOptions, SubdominantClass};

/// See `butterfly::EIG_TOL`: simple eigenvalues of these small matrices to a
/// few hundred eps, the gaps tested are at least 1/4.
const EIG_TOL: f64 = 1e-10;

/// The stencil's Fourier coefficients are 1/4 (mode 0), 1/2 (modes 1 and
/// K - 1) and 1/4 (modes 2 and K - 2): the weights sum to 1/4 and are
/// symmetric, at K = 3, 4 and for K >= 5.
#[test]
fn the_weights_have_the_designed_fourier_coefficients() {
    for k in 3..=16 {
        let s = extraordinary_weights::<f64>(k).unwrap();
        assert_eq!(s.len(), k);
        let mode = |l: usize| -> f64 {
            s.iter()
                .enumerate()
                .map(|(j, w)| w * (2.0 * std::f64::consts::PI * (j * l) as f64 / k as f64).cos())
                .sum()
        };
        assert!((mode(0) - 0.25).abs() < 1e-14, "K={k}");
        assert!((mode(1) - 0.5).abs() < 1e-14, "K={k}");
        for j in 1..k {
            assert_eq!(s[j], s[k - j], "K={k} j={j}");
        }
    }
    let q = extraordinary_weights::<Rational>(3).unwrap();
    assert_eq!(q[0], Rational::new(5.into(), 12.into()));
    assert!(extraordinary_weights::<Rational>(5).is_err());
}

/// On the one-ring (closed under the extraordinary stencil) the matrix is
/// `[[1, 0], [3/4, circulant(s)]]`, whose eigenvalues are 1 and the Fourier
/// coefficients of `s`: 1/4 (mode 0), 1/2 (modes 1, K - 1), 1/4 (modes 2,
/// K - 2), 0 elsewhere: the spectrum Zorin, Schroder and Sweldens (1996)
/// designed. Planted: the K >= 5 formula with `cos(4 pi j / K)` weighted 1/4
/// instead of 1/2 makes this fail (its modes 2 become 1/8).
#[test]
fn the_one_ring_has_the_designed_spectrum() {
    // (at n = 6 every edge takes the regular butterfly stencil, which
    // reaches beyond the one-ring)
    for n in (3..=16).filter(|&n| n != 6) {
        let e = eigenvalues(local_matrix_on::<f64>(n, 1).unwrap().matrix());
        let mut want = vec![1.0, 0.5, 0.5, 0.25];
        want.extend(std::iter::repeat_n(0.25, 2.min(n - 3)));
        want.resize(n + 1, 0.0);
        for (z, w) in e.iter().zip(&want) {
            assert!((z - w).norm() < EIG_TOL, "n={n}: {e:?}");
        }
    }
}

/// Zorin, Schroder and Sweldens (1996) chose the stencil so that the
/// subdominant eigenvalue is 1/2 (double) at every valence, with 1/4 next,
/// also on the three-ring (the regular part adds nothing above 1/4).
/// Planted: a wing of the regular butterfly stencil read one neighbour off
/// makes this fail.
#[test]
fn the_subdominant_eigenvalue_is_one_half_at_every_valence() {
    for n in 3..=16 {
        let e = eigenvalues(local_matrix(n).unwrap().matrix());
        assert!((e[0] - 1.0).norm() < EIG_TOL, "n={n}");
        assert!(
            (e[1] - 0.5).norm() < EIG_TOL && (e[2] - 0.5).norm() < EIG_TOL,
            "n={n}: {e:?}"
        );
        assert!(e[3].norm() < 0.25 + 1e-4, "n={n}: {}", e[3]);
    }
}

#[test]
fn the_three_ring_nests_in_the_four_ring() {
    for n in [3, 4] {
        let s1 = local_matrix_on::<Rational>(n, 1).unwrap();
        let s3 = local_matrix_on::<Rational>(n, 3).unwrap();
        let s4 = local_matrix_on::<Rational>(n, 4).unwrap();
        // the one-ring is closed too (the extraordinary stencil), but the
        // three-ring holds the regular part's reach (math doc section 21)
        assert!(nests(s1.matrix(), s3.matrix()), "n={n}");
        assert!(nests(s3.matrix(), s4.matrix()), "n={n}");
    }
    for n in [5, 7] {
        let e3 = eigenvalues(local_matrix_on::<f64>(n, 3).unwrap().matrix());
        let e4 = eigenvalues(local_matrix_on::<f64>(n, 4).unwrap().matrix());
        shared_eigenvalues_agree(&e3, &e4, 0.3);
    }
}

#[test]
fn exact_where_rational_and_refused_elsewhere() {
    for n in [3, 4, 6] {
        let s = LocalScheme::from_kind(SchemeKind::ModifiedButterfly, n, None).unwrap();
        let q = s.exact_local_matrix().unwrap().unwrap().to_f64();
        let f = s.local_matrix().unwrap();
        let d = (q.matrix() - f.matrix()).abs().max();
        assert!(d < 1e-15, "n={n}: {d}");
    }
    let s = LocalScheme::from_kind(SchemeKind::ModifiedButterfly, 5, None).unwrap();
    assert!(s.exact_local_matrix().is_none());
    assert!(local_matrix_on::<Rational>(5, 3).is_err());
}

#[test]
fn analyze_classifies_the_pair_and_gives_no_characteristic_map() {
    let s = LocalScheme::from_kind(SchemeKind::ModifiedButterfly, 5, None).unwrap();
    let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
    assert_eq!(a.subdominant.class, SubdominantClass::Standard);
    let c = subdiv_lab::charmap::check_classified(&s, &a.charmap_subdominant()).unwrap();
    assert_eq!(c.verdict.code(), "no_charmap");
}
