//! The butterfly scheme (`schemes::butterfly`, math doc section 21): the
//! three-ring is the smallest ring closed under one step that holds the
//! characteristic map's support, its matrix nests exactly in the four-ring's,
//! the regular valence has the spectrum of a scheme that reproduces cubics,
//! the weights are rational at every valence, and `analyze` reports
//! `no_charmap`.

use nalgebra::DMatrix;
use num_complex::Complex64;
use subdiv_lab::scalar::Rational;
use subdiv_lab::schemes::butterfly::{local_matrix, local_matrix_on, regular_edge_mask};
use subdiv_lab::schemes::{LocalScheme, Scheme, SchemeKind};
use subdiv_lab::spectral::{analyze, AnalyzeOptions, Eigen, EigenOptions};

/// Eigenvalues of simple (or semisimple) eigenvalues of these small dyadic
/// matrices come out within a few hundred `eps` of the truth (condition
/// numbers below 100); `1e-10` is far above that and far below the gaps of
/// the facts tested (`>= 1/8`).
const EIG_TOL: f64 = 1e-10;

/// Eigenvalues sorted by non-increasing modulus (then real part).
pub(crate) fn eigenvalues(m: &DMatrix<f64>) -> Vec<Complex64> {
    let mut v = Eigen::new(m, EigenOptions::VALUES)
        .unwrap()
        .values()
        .to_vec();
    v.sort_by(subdiv_lab::schemes::spectral_order);
    v
}

/// `big` = `[[small, 0], [*, *]]` exactly: the rows of the small ring's new
/// points use only its old points, so the small ring's spectrum is part of
/// the big ring's.
pub(crate) fn nests(small: &DMatrix<Rational>, big: &DMatrix<Rational>) -> bool {
    let d = small.nrows();
    (0..d).all(|i| {
        (0..big.ncols()).all(|j| {
            let want = if j < d {
                small[(i, j)].clone()
            } else {
                Rational::from_integer(0.into())
            };
            big[(i, j)] == want
        })
    })
}

/// Every eigenvalue of `small` is one of `big` (within [`EIG_TOL`], for the
/// simple eigenvalues above `floor` in modulus).
pub(crate) fn shared_eigenvalues_agree(small: &[Complex64], big: &[Complex64], floor: f64) {
    for z in small.iter().filter(|z| z.norm() > floor) {
        let d = big
            .iter()
            .map(|w| (w - z).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(d < EIG_TOL, "{z} missing from the larger ring ({d:e})");
    }
}

#[test]
fn the_one_ring_is_not_closed_and_the_three_ring_nests_in_the_four_ring() {
    for n in [3, 4, 5, 7, 9] {
        let err = local_matrix_on::<f64>(n, 1).unwrap_err().to_string();
        assert!(err.contains("outside the 1-ring"), "{err}");
        let s2 = local_matrix_on::<Rational>(n, 2).unwrap();
        let s3 = local_matrix_on::<Rational>(n, 3).unwrap();
        let s4 = local_matrix_on::<Rational>(n, 4).unwrap();
        assert_eq!(s3.matrix().nrows(), 6 * n + 1);
        assert!(nests(s2.matrix(), s3.matrix()), "n={n}");
        assert!(nests(s3.matrix(), s4.matrix()), "n={n}");
        // the spectra agree on the shared eigenvalues (above the defective
        // cluster at 1/4, whose computed values spread by eps^(1/3))
        let e3 = eigenvalues(&s3.to_f64().into_matrix());
        let e4 = eigenvalues(&s4.to_f64().into_matrix());
        shared_eigenvalues_agree(&e3, &e4, 0.3);
    }
}

/// At the regular valence the butterfly scheme reproduces cubic
/// polynomials (Dyn, Gregory, Levin 1990), so its local matrix has the
/// eigenvalues 1, 1/2 (twice), 1/4 (three times) and 1/8 (four times) of the
/// polynomials of degree 0..3. Planted: the wings of the edge's second end
/// read one neighbour off (`tq +- 1` for `tq +- 2`) make this fail.
#[test]
fn the_regular_valence_has_the_spectrum_of_cubic_precision() {
    let s = local_matrix(6).unwrap();
    let e = eigenvalues(s.matrix());
    assert!((e[0] - 1.0).norm() < EIG_TOL);
    for z in &e[1..3] {
        assert!((z - 0.5).norm() < EIG_TOL, "{z}");
    }
    // 1/4 is a defective cluster (its computed values spread by about
    // eps^(1/3)); count within 1e-4. The three ring's 1/4 holds the three
    // quadratics and four more of the regular part (seven in all).
    let count = |x: f64| e.iter().filter(|z| (*z - x).norm() < 1e-4).count();
    assert!(count(0.25) >= 3, "{e:?}");
    assert!(count(0.125) >= 4, "{e:?}");
    // nothing else reaches 1/4 in modulus
    assert!(e[3..]
        .iter()
        .all(|z| z.norm() < 0.25 - 1e-3 || (z - 0.25).norm() < 1e-4));
}

#[test]
fn the_mask_is_rational_at_every_valence_and_its_data_sums_to_one() {
    let m = regular_edge_mask();
    assert!((m.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-15);
    for n in [5, 7, 11] {
        let s = LocalScheme::from_kind(SchemeKind::Butterfly, n, None).unwrap();
        let q = s.exact_local_matrix().unwrap().unwrap();
        assert_eq!(q.to_f64().matrix(), s.local_matrix().unwrap().matrix());
    }
}

#[test]
fn analyze_reports_the_three_ring_and_no_characteristic_map() {
    let s = LocalScheme::from_kind(SchemeKind::Butterfly, 5, None).unwrap();
    let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
    assert_eq!(a.eigenvalues.len(), 31);
    assert!(a.steps.is_none());
    // the limit point of an interpolatory scheme is the vertex itself
    assert!(a.limit_weights_error.unwrap() < 1e-12);
    let c = subdiv_lab::charmap::check_classified(&s, &a.charmap_subdominant()).unwrap();
    assert_eq!(c.verdict.code(), "no_charmap");
}

/// The third ring is needed: three steps take a point of the third ring
/// (off the rays) to non-zero new points of the seven-ring, all of which lie
/// inside the old one-ring (distance `<= 7 / 8`), so the two-ring alone would
/// miss part of the characteristic map's support (math doc section 21).
#[test]
fn a_third_ring_point_reaches_the_one_ring_in_three_steps() {
    use subdiv_lab::schemes::tri_rings::ring_len;
    for n in [3, 5, 6, 8] {
        let s = local_matrix_on::<f64>(n, 8).unwrap().into_matrix();
        let inside = ring_len(n, 7);
        let reaches = (ring_len(n, 2)..ring_len(n, 3)).any(|h| {
            let mut x = nalgebra::DVector::zeros(s.ncols());
            x[h] = 1.0;
            let y = &s * (&s * (&s * x));
            y.rows(0, inside).iter().any(|v| v.abs() > 1e-6)
        });
        assert!(reaches, "n={n}");
    }
}
