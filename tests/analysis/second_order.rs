//! The second-order neighbourhood (math doc section 13.5): for every
//! built-in scheme, the spectrum that decides the curvature verdict is the
//! same on the scheme's second-order matrix (the `k`-ring:
//! `Scheme::second_order_matrix`) and on the next larger closed neighbourhood
//! (the `(k+1)`-ring), and the verdict's `mu / lambda^2` is what refining a
//! net measures.
//!
//! The `(k+1)`-ring matrices come from the extended matrices, whose rows are
//! the next level's `(k+1)`-ring points (Catmull-Clark family: the `2n + 17`
//! points of the patch's 5 x 5 grid; Loop: the three-ring, `6n + 1`; the
//! Doo-Sabin family: the `9n` corners of the faces around the face) and whose
//! columns are only the `k`-ring points: the builders take their stencils
//! from the rules and refuse a stencil outside the `k`-ring, so the square
//! `(k+1)`-ring matrix has zero columns at the other old points.

use nalgebra::DMatrix;
use num_complex::Complex64;
use subdiv_lab::curvature::measured::measure;
use subdiv_lab::curvature::{curvature, CurvatureSummary, CurvatureVerdict};
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::schemes::catmull_clark;
use subdiv_lab::schemes::doo_sabin::extended::ExtendedMatrix;
use subdiv_lab::schemes::loop_subdivision::matrix as loop_matrix;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::eigen::{spectral_order, Eigen, EigenOptions};
use subdiv_lab::Scheme;

/// Which eigenvalues are compared: every one of modulus at least this
/// fraction of `min(mu, lambda^2)`. They decide `mu` with a margin, and they
/// hold the next modulus `nu` that sets the measured rates' convergence
/// (math doc section 13.2); below it lie only faster-decaying terms (and
/// the `(k+1)`-ring's zeros). `0.3` keeps the cut off the built-in schemes'
/// dyadic eigenvalues (`1/16` at `min = 1/4`).
const RELEVANT_FRACTION: f64 = 0.3;

/// Largest distance of two eigenvalues matched between the two spectra, and
/// of the two values of `mu`. The matrices share their non-zero spectrum
/// exactly; the computed values differ by rounding, which a defective
/// eigenvalue amplifies to `eps^(1/j)` for a Jordan block of size `j`
/// (original Doo-Sabin's `1/4` at `n >= 5`: `j = 2`, `1e-8`); `1e-5` allows
/// `j = 3` as well and is still far below the differences this test is
/// about (the one-ring's `mu` is below the patch's by `6e-2` at `n = 3`,
/// `c = 0.75`, and multiplicities are counted).
const MATCH_TOL: f64 = 1e-5;

/// Eigenvalues of a square matrix, sorted by [`spectral_order`].
fn eigenvalues(m: &DMatrix<f64>) -> Vec<Complex64> {
    let e = Eigen::new(m, EigenOptions::VALUES).unwrap();
    let mut v = e.values().to_vec();
    v.sort_by(spectral_order);
    v
}

/// The square `(k+1)`-ring matrix from an extended matrix (rows: the next
/// level's `(k+1)`-ring; columns: the `k`-ring): zero columns at the old
/// points outside the `k`-ring (module docs).
fn square_up(ext: &DMatrix<f64>) -> DMatrix<f64> {
    let (r, c) = ext.shape();
    assert!(r > c, "the (k+1)-ring is larger");
    let mut m = DMatrix::zeros(r, r);
    m.view_mut((0, 0), (r, c)).copy_from(ext);
    m
}

/// Compares the verdict-relevant spectrum of `scheme`'s second-order matrix
/// with that of the `(k+1)`-ring matrix `larger`, and the verdict's `mu`
/// with the `(k+1)`-ring's. Panics with `what` on a difference.
fn compare(scheme: &dyn Scheme, larger: &DMatrix<f64>, what: &str) -> CurvatureSummary {
    let k = scheme.second_order_matrix().unwrap();
    let k = k.matrix();
    // The (k+1)-ring's leading rows are the k-ring's next level.
    let d = k.nrows();
    let lead = larger.view((0, 0), (d, d));
    assert!(
        (lead - k).abs().max() < 1e-15,
        "{what}: the (k+1)-ring does not start with the k-ring"
    );
    let a = eigenvalues(k);
    let b = eigenvalues(larger);
    let v = curvature(scheme).unwrap();
    let mu_b = b[3].norm();
    assert!(
        (v.mu - mu_b).abs() <= MATCH_TOL,
        "{what}: the verdict's mu = {} but the (k+1)-ring's mu = {mu_b}",
        v.mu
    );
    let lambda = b[1].norm();
    let cut = RELEVANT_FRACTION * mu_b.min(lambda * lambda);
    let mut used = vec![false; b.len()];
    for z in a.iter().filter(|z| z.norm() >= cut) {
        let best = b
            .iter()
            .enumerate()
            .filter(|(j, w)| !used[*j] && (*w - z).norm() <= MATCH_TOL)
            .min_by(|x, y| (x.1 - z).norm().total_cmp(&(y.1 - z).norm()));
        match best {
            Some((j, _)) => used[j] = true,
            None => panic!("{what}: {z} of the k-ring is not in the (k+1)-ring"),
        }
    }
    for (j, w) in b.iter().enumerate() {
        assert!(
            used[j] || w.norm() < cut + MATCH_TOL,
            "{what}: {w} of the (k+1)-ring (|w| >= {cut:.4}) is not in the k-ring"
        );
    }
    v
}

#[test]
fn catmull_clark_patch_is_closed() {
    for n in 3..=16 {
        let s = LocalScheme::<f64>::catmull_clark(n).unwrap();
        let ext = catmull_clark::extended_matrix::<f64>(n, &0.5).unwrap();
        compare(
            &s,
            &square_up(ext.matrix()),
            &format!("catmull-clark n={n}"),
        );
    }
}

/// 200 values of `c` in `[0, 1]` at `n = 3..8`: the step `1/199` sees the
/// `n = 3` crossing `c/4 = lambda(c)^2` at `c = 0.6312` (the verdict turns
/// from `zero` to `unbounded` between `c = 126/199` and `127/199`).
#[test]
fn adjustable_patch_is_closed_on_a_fine_c_grid() {
    let mut crossing = None;
    for n in 3..=8 {
        let mut last = None;
        for j in 0..200 {
            let c = j as f64 / 199.0;
            let s = LocalScheme::adjustable_cc(n, c).unwrap();
            let ext = catmull_clark::extended_matrix::<f64>(n, &c).unwrap();
            let v = compare(
                &s,
                &square_up(ext.matrix()),
                &format!("adjustable n={n} c={c}"),
            );
            if n == 3 {
                if last == Some(CurvatureVerdict::Zero) && v.verdict == CurvatureVerdict::Unbounded
                {
                    crossing = Some(c);
                }
                last = Some(v.verdict);
            }
        }
    }
    let c = crossing.expect("zero turns into unbounded at n = 3");
    assert!((0.6312..0.6362).contains(&c), "crossing at {c}");
}

#[test]
fn loop_two_ring_is_closed() {
    for n in 3..=12 {
        let s = LocalScheme::loop_subdivision(n).unwrap();
        let ext = loop_matrix::extended_matrix(n).unwrap();
        compare(&s, &square_up(ext.matrix()), &format!("loop n={n}"));
    }
}

fn doo_sabin_family(s: &LocalScheme<f64>, what: &str) {
    let ext = ExtendedMatrix::new(s).unwrap();
    compare(s, &square_up(ext.matrix().matrix()), what);
}

#[test]
fn doo_sabin_and_cc_variant_configurations_are_closed() {
    for n in 3..=10 {
        doo_sabin_family(
            &LocalScheme::<f64>::doo_sabin(n).unwrap(),
            &format!("doo-sabin n={n}"),
        );
        doo_sabin_family(
            &LocalScheme::<f64>::cc_variant(n).unwrap(),
            &format!("cc-variant n={n}"),
        );
    }
}

#[test]
fn nurds_configurations_are_closed() {
    let mut rng = SplitMix64::new(34);
    for n in 3..=8 {
        for _ in 0..12 {
            let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
            let s = LocalScheme::nurds(EdgeRatios::new(r.clone()).unwrap());
            // Only the standard class has a curvature rate; the others are
            // compared all the same (the verdict's mu is defined for them).
            doo_sabin_family(&s, &format!("nurds {r:?}"));
        }
    }
}

/// Levels of the measured cross-check: the figure's largest
/// (`report::figures::curvature::MAX_LEVELS`); the stated errors there are
/// at most `4e-2` for the configurations below (`n = 3`, `c = 0.6`: the
/// next modulus `1/8` below `mu = c/4 = 0.15`, `rho = 0.83`), and
/// the rounding term `eps (lambda / mu)^24` stays below `1e-6`.
const LEVELS: usize = 24;

/// The verdict's `mu / lambda^2` (from `analyze`'s curvature) against the
/// rate measured by refining the patch nets of all `n` sectors and fitting
/// the limit surface (`curvature::measured`, its dominant Fourier part):
/// they must agree within the measurement's stated error, and that error
/// must be smaller than the distance to 1, so that the measurement alone
/// decides between `zero` and `unbounded` (and below `1e-3` where the
/// verdict is `bounded`). On the one-ring alone `n = 3`, `c = 0.75` would
/// give the verdict `zero` with `mu / lambda^2 = 0.829` against a measured
/// `1.2438`.
#[test]
fn measured_rates_agree_with_the_verdict() {
    for (n, c, verdict) in [
        (3, 0.75, CurvatureVerdict::Unbounded), // mu = c/4 (regular part): 1.2438
        (3, 0.5, CurvatureVerdict::Zero),       // Catmull-Clark: mu = 1/6 (block 0)
        (3, 0.6, CurvatureVerdict::Zero),       // mu = c/4 = 0.15, still below lambda^2
        (3, 0.9, CurvatureVerdict::Unbounded),
        (4, 0.5, CurvatureVerdict::Bounded),
        (5, 0.5, CurvatureVerdict::Unbounded),
        (8, 0.3, CurvatureVerdict::Unbounded),
    ] {
        let s = LocalScheme::adjustable_cc(n, c).unwrap();
        let v = curvature(&s).unwrap();
        assert_eq!(v.verdict, verdict, "n={n} c={c}: {}", v.reason);
        let m = measure(n, c, LEVELS, 17).unwrap();
        let ratio = v.mu_over_lambda_squared;
        let what = format!(
            "n={n} c={c}: measured {} +- {:.1e}, the verdict's mu/lambda^2 = {ratio}",
            m.dominant_rate, m.rate_error
        );
        let decisive = if verdict == CurvatureVerdict::Bounded {
            1e-3
        } else {
            (ratio - 1.0).abs()
        };
        assert!(
            m.rate_error < decisive,
            "{what}: the stated error cannot decide"
        );
        assert!(
            (m.dominant_rate - ratio).abs() <= m.rate_error,
            "{what}: they disagree"
        );
    }
}
