//! Unit tests of the cell characteristic-map certificate: the enclosures
//! contain the pointwise rings (in the same normalisation) at random
//! parameters of the cell, and a deliberately weakened enclosure (the
//! subspace variation dropped) is caught by the same check.

use super::ratios::ratio_ring;
use super::shape::{pointwise_windows, shape_ring};
use super::*;
use crate::knots::EdgeRatios;
use crate::rng::SplitMix64;
use crate::schemes::doo_sabin::extended::ExtendedMatrix;
use crate::schemes::LocalScheme;

/// Slack for the floating-point error of the pointwise computation.
const POINT_TOL: f64 = 1e-10;

/// Window coordinates outside the enclosure at `samples` random `c` of the
/// cell, and the number checked.
fn shape_misses(
    n: usize,
    lo: f64,
    hi: f64,
    tamper: CellTamper,
    samples: usize,
    seed: u64,
) -> (usize, usize) {
    let ring = shape_ring(n, lo, hi, tamper).expect("enclosure");
    let mut rng = SplitMix64::new(seed);
    let mut bad = 0;
    for _ in 0..samples {
        let c = rng.uniform(lo, hi);
        bad += ring.misses(&pointwise_windows(n, c).unwrap(), POINT_TOL);
    }
    (bad, samples * 96)
}

#[test]
fn shape_enclosure_contains_the_pointwise_windows() {
    for (n, lo, hi) in [
        (3, 0.3, 0.31),
        (5, 0.01, 0.0125),
        (8, 0.9, 0.95),
        (16, 0.5, 0.502),
    ] {
        let (bad, checks) = shape_misses(n, lo, hi, CellTamper::None, 8, 3 + n as u64);
        assert_eq!(bad, 0, "n={n} [{lo}, {hi}]: {bad} of {checks}");
    }
}

#[test]
fn shape_enclosure_without_the_variation_is_caught() {
    let (bad, checks) = shape_misses(5, 0.2, 0.3, CellTamper::DropSubspaceVariation, 8, 9);
    assert!(bad > checks / 10, "{bad} of {checks}");
}

fn ratio_misses(
    lo: &[f64],
    hi: &[f64],
    tamper: CellTamper,
    samples: usize,
    seed: u64,
) -> (usize, usize) {
    let ring = ratio_ring(lo, hi, tamper).expect("enclosure");
    let mut rng = SplitMix64::new(seed);
    let mut bad = 0;
    for _ in 0..samples {
        let r: Vec<f64> = lo
            .iter()
            .zip(hi)
            .map(|(a, b)| rng.uniform(*a, *b))
            .collect();
        let (pf, pts) = ring.pointwise(&r).unwrap();
        bad += ring.misses(pf, &pts, POINT_TOL);
    }
    (bad, samples * (1 + 2 * ring.points.len()))
}

#[test]
fn ratio_enclosure_contains_the_pointwise_ring() {
    let cases: [(Vec<f64>, Vec<f64>); 5] = [
        (vec![0.3, 0.4, 0.5], vec![0.31, 0.41, 0.51]),
        (vec![0.1, 0.8, 0.3], vec![0.105, 0.81, 0.305]),
        (vec![0.02, 0.97, 0.5], vec![0.022, 0.972, 0.502]),
        (vec![0.4, 0.45, 0.5, 0.55], vec![0.41, 0.46, 0.51, 0.56]),
        (
            vec![0.3, 0.5, 0.6, 0.4, 0.5],
            vec![0.305, 0.505, 0.605, 0.405, 0.505],
        ),
    ];
    for (k, (lo, hi)) in cases.iter().enumerate() {
        let (bad, checks) = ratio_misses(lo, hi, CellTamper::None, 6, 20 + k as u64);
        assert_eq!(bad, 0, "{lo:?}..{hi:?}: {bad} of {checks}");
    }
}

#[test]
fn ratio_enclosure_without_the_subspace_term_is_caught() {
    let (bad, checks) = ratio_misses(
        &[0.3, 0.4, 0.5],
        &[0.32, 0.42, 0.52],
        CellTamper::DropSubspaceVariation,
        6,
        5,
    );
    // more than the 6 violated bounds ||P(r)|| <= rho = 0: ring points leave too
    assert!(bad > 6, "{bad} of {checks}");
}

#[test]
fn ring_rows_match_the_extended_matrix() {
    // the E- and V-face rows written out in `ratios` against the assembled
    // extended matrix: at the centre of a tiny cell the enclosure of the
    // ring points contains the extended matrix applied to the lifted basis
    for lo in [vec![0.2, 0.7, 0.45], vec![0.6, 0.3, 0.5, 0.35]] {
        let hi: Vec<f64> = lo.iter().map(|x| x + 1e-9).collect();
        let ring = ratio_ring(&lo, &hi, CellTamper::None).unwrap();
        let r: Vec<f64> = lo.iter().map(|x| x + 5e-10).collect();
        let (pf, pts) = ring.pointwise(&r).unwrap();
        assert_eq!(ring.misses(pf, &pts, POINT_TOL), 0);
        let ext = ExtendedMatrix::new(&LocalScheme::nurds(EdgeRatios::new(r).unwrap())).unwrap();
        assert_eq!(ext.matrix().matrix().nrows(), ring.points.len());
        // the boxes are tight: width below 1e-6 for a cell of width 1e-9
        for p in &ring.points {
            assert!(
                p[0].hi - p[0].lo < 1e-6 && p[1].hi - p[1].lo < 1e-6,
                "{p:?}"
            );
        }
    }
}

#[test]
fn small_cells_are_certified() {
    // the adjustable scheme and NURDS n = 3, 4, 5 on small cells of typical parameters
    for (n, lo, hi) in [(3, 0.5, 0.501), (5, 0.1, 0.101), (16, 0.9, 0.901)] {
        assert!(
            shape::certified(n, lo, hi, CellTamper::None),
            "n={n} [{lo}, {hi}]"
        );
    }
    for (lo, w) in [
        (vec![0.3, 0.4, 0.5], 0.02),
        (vec![0.1, 0.8, 0.3], 0.01),
        (vec![0.4, 0.45, 0.5, 0.55], 0.01),
        (vec![0.3, 0.5, 0.6, 0.4, 0.5], 0.004),
    ] {
        let hi: Vec<f64> = lo.iter().map(|x| x + w).collect();
        assert!(
            ratios::certified(&lo, &hi, CellTamper::None).0,
            "{lo:?} + {w}"
        );
    }
}

#[test]
fn small_c_cells_agree_with_the_floating_cone_test_on_the_same_windows() {
    // Near c = 0 the pointwise check of `charmap::catmull_clark` is
    // indeterminate (its subspace bound grows like 1/gap and the gap is O(c));
    // the cell certificate does not need the gap (closed-form eigenvector).
    // Cross-check: the floating-point cone test and winding number of that
    // module, run on the pointwise windows in the cell's normalisation with a
    // small error bound, certify the same maps.
    use crate::charmap::catmull_clark::{check_ring, CcRing, Certificate};
    use crate::charmap::Verdict;
    use crate::schemes::catmull_clark::ring::UnivariateRule;
    for (n, lo, hi) in [(3, 1e-6, 2e-6), (5, 3e-5, 3.1e-5), (16, 2e-4, 2.2e-4)] {
        assert!(shape::certified(n, lo, hi, CellTamper::None), "n={n}");
        let c = 0.5 * lo + 0.5 * hi;
        let w = pointwise_windows(n, c).unwrap();
        let maps: Vec<[[f64; 2]; 2]> = (0..n)
            .map(|j| {
                let (s, co) = (2.0 * std::f64::consts::PI * j as f64 / n as f64).sin_cos();
                [[co, -s], [s, co]]
            })
            .collect();
        let ring = CcRing::from_sector(UnivariateRule::new(c).unwrap(), w, &maps);
        let rep = check_ring(&ring, 1e-13, Certificate::Cone);
        assert_eq!(rep.verdict, Verdict::C1Standard, "n={n} c={c}: {rep:?}");
    }
}
