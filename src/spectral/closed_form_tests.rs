//! Cross-checks of the schemes' closed forms (Fourier spectra, limit and
//! tangent stencils, regular parts) against this module's dense and exact
//! machinery. They live with the analysis because the rules layer
//! ([`crate::schemes`]) imports no analysis.

use crate::scalar::{Rational, Scalar};
use crate::schemes::catmull_clark::{patch_matrix, regular_part_eigenvalues};
use crate::schemes::loop_subdivision::fourier::{spectrum, tangent_stencils};
use crate::schemes::loop_subdivision::matrix::{one_ring_matrix, two_ring_matrix};
use crate::schemes::loop_subdivision::{limit_weights, subdominant_eigenvalue};
use crate::spectral::eigen::{Eigen, EigenOptions};
use crate::spectral::exact::charpoly;
use crate::spectral::poly::Poly;
use nalgebra::DMatrix;
use num_complex::Complex64;
use proptest::prelude::*;

fn r(x: f64) -> Complex64 {
    Complex64::new(x, 0.0)
}

fn q(a: i64, b: i64) -> Rational {
    Rational::frac(a, b)
}

fn rational_c() -> impl Strategy<Value = Rational> {
    (1i64..=64).prop_flat_map(|den| (0..=den).prop_map(move |num| q(num, den)))
}

// Loop (math doc section 11).

/// Distance allowed between a closed-form eigenvalue and the dense one
/// (faer) for simple and semisimple eigenvalues: backward error
/// `~ dim eps ||S||_F` (`||S||_F < 3` here) times the condition number
/// (`<= 10` for these nearly normal blocks): `1e-12` is ample for `n <= 20`.
const DENSE_TOL: f64 = 1e-12;

/// The same for the eigenvalues inside a Jordan block: at `n = 3` the
/// `l = 0` eigenvalue `lambda^2 = 1/16` meets the `1/16` of `ĝ_0` and
/// forms a 2 x 2 Jordan block (tested below), which a perturbation
/// `eta ~ 1e-15` splits by `O(sqrt(eta)) ~ 3e-8`.
const DEFECTIVE_TOL: f64 = 1e-6;

/// Pairs every closed-form eigenvalue with a distinct dense one (greedy,
/// nearest first) and returns the largest distance, excluding `skip`
/// values near which the dense ones may split.
fn max_mismatch(closed: &[Complex64], dense: &[Complex64], loose: &[f64]) -> (f64, f64) {
    let mut used = vec![false; dense.len()];
    let (mut tight, mut wide) = (0.0f64, 0.0f64);
    for z in closed {
        let (k, d) = dense
            .iter()
            .enumerate()
            .filter(|(k, _)| !used[*k])
            .map(|(k, w)| (k, (w - z).norm()))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        used[k] = true;
        if loose.iter().any(|x| (x - z.re).abs() < 1e-12) {
            wide = wide.max(d);
        } else {
            tight = tight.max(d);
        }
    }
    (tight, wide)
}

#[test]
fn block_spectrum_equals_dense_spectrum() {
    for n in 3..=20 {
        let s = two_ring_matrix(n).unwrap();
        let e = Eigen::new(s.matrix(), EigenOptions::VALUES).unwrap();
        let closed = spectrum(n).unwrap();
        assert_eq!(e.values().len(), closed.len());
        let loose: &[f64] = if n == 3 { &[0.0625] } else { &[] };
        let (tight, wide) = max_mismatch(&closed, e.values(), loose);
        assert!(tight < DENSE_TOL, "n = {n}: {tight:e}");
        assert!(wide < DEFECTIVE_TOL, "n = {n}: {wide:e}");
        // the subdominant pair itself is the dense pair at positions 1, 2
        let lam = subdominant_eigenvalue(n);
        for z in &e.values()[1..3] {
            assert!((z - r(lam)).norm() < DENSE_TOL, "n = {n}: {z}");
        }
    }
}

#[test]
fn limit_stencil_is_the_dense_left_fixed_vector() {
    for n in 3..=20 {
        for s in [one_ring_matrix(n).unwrap(), two_ring_matrix(n).unwrap()] {
            let e = Eigen::new(s.matrix(), EigenOptions::BOTH).unwrap();
            let k = e
                .values()
                .iter()
                .position(|z| (z - r(1.0)).norm() < DENSE_TOL)
                .unwrap();
            let u = e.left().unwrap().column(k).into_owned();
            let u = (&u / u.sum()).map(|z| z.re);
            let l = limit_weights(n).unwrap();
            for j in 0..u.len() {
                let want = l.get(j).copied().unwrap_or(0.0);
                assert!(
                    (u[j] - want).abs() < 1e-12,
                    "n = {n}, j = {j}: {} vs {want}",
                    u[j]
                );
            }
        }
    }
}

/// Distance of the real vector `t` from the span of the columns `cols` of `u`.
fn distance_from_span(u: &DMatrix<Complex64>, cols: &[usize], t: &[f64]) -> f64 {
    let mut basis: Vec<nalgebra::DVector<Complex64>> = Vec::new();
    for &c in cols {
        let mut v = u.column(c).into_owned();
        for b in &basis {
            let p = b.dotc(&v);
            v -= b * p;
        }
        let nv = v.norm();
        basis.push(v / r(nv));
    }
    let mut x = nalgebra::DVector::from_iterator(t.len(), t.iter().map(|&a| r(a)));
    let nt = x.norm();
    for b in &basis {
        let p = b.dotc(&x);
        x -= b * p;
    }
    x.norm() / nt
}

#[test]
fn tangent_stencils_are_dense_left_eigenvectors() {
    for n in 3..=20 {
        let s = one_ring_matrix(n).unwrap();
        let (lam, ts) = tangent_stencils(n).unwrap();
        let e = Eigen::new(s.matrix(), EigenOptions::BOTH).unwrap();
        let cols: Vec<usize> = (0..n + 1)
            .filter(|&k| (e.values()[k] - r(lam)).norm() < 1e-9)
            .collect();
        assert_eq!(cols.len(), 2, "n = {n}: {:?}", e.values());
        for t in &ts {
            // exact left eigenvector of the assembled matrix ...
            let tv = nalgebra::DVector::from_vec(t.clone());
            let res = (s.matrix().transpose() * &tv - &tv * lam).norm();
            assert!(res < 1e-14, "n = {n}: residual {res:e}");
            // ... and in the span of the dense solver's pair
            let d = distance_from_span(e.left().unwrap(), &cols, t);
            assert!(d < 1e-10, "n = {n}: distance {d:e}");
        }
    }
}

// The Catmull-Clark family (math doc section 8).

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The patch matrix's outer 7 x 7 block has exactly the characteristic
    /// polynomial `prod (x - r)` over [`regular_part_eigenvalues`] (exact
    /// rationals), so the patch spectrum is the one-ring's and these.
    /// (Planted: `c/16` in place of `c^2/16` fails at once.)
    #[test]
    fn regular_part_is_the_outer_block_spectrum(n in 3usize..9, c in rational_c()) {
        let p = patch_matrix::<Rational>(n, &c).unwrap();
        let m = 2 * n + 1;
        let outer = p.matrix().view((m, m), (7, 7)).into_owned();
        let mut expected = Poly::new(vec![q(1, 1)]);
        for r in regular_part_eigenvalues(&c) {
            expected = expected.mul(&Poly::new(vec![-r, q(1, 1)]));
        }
        prop_assert_eq!(charpoly(&outer), expected);
        // c/4 is the largest of them on [0, 1].
        let ev = regular_part_eigenvalues(&c);
        prop_assert!(ev.iter().all(|x| num_traits::Signed::abs(x) <= ev[0]));
    }
}
