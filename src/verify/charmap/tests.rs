//! Unit tests of the cell characteristic-map certificate: the enclosures
//! contain the pointwise rings (in the same normalisation) at random
//! parameters of the cell, and a deliberately weakened enclosure (the
//! subspace variation dropped) is caught by the same check.

use super::ratios::{ratio_ring, RatioRing};
use super::shape::shape_ring;
use super::*;
use crate::charmap::extended::ExtendedMatrix;
use crate::charmap::ring::ring_points;
use crate::knots::EdgeRatios;
use crate::rng::SplitMix64;
use crate::schemes::catmull_clark::{self, fourier, PatchLayout, SubPatch};
use crate::schemes::LocalScheme;
use crate::spectral::eigen::{Eigen, EigenOptions};
use crate::verify::interval::Iv;
use nalgebra::DMatrix;

/// Slack for the floating-point error of the pointwise computation.
const POINT_TOL: f64 = 1e-10;

fn inside(x: f64, iv: Iv) -> bool {
    iv.lo - POINT_TOL * (1.0 + x.abs()) <= x && x <= iv.hi + POINT_TOL * (1.0 + x.abs())
}

/// The sector-0 windows of the adjustable scheme at `c`, pointwise, in the
/// `(x_cos, x_sin)` normalisation of the cell enclosure.
fn shape_windows_at(n: usize, c: f64) -> [[[[f64; 2]; 4]; 4]; 3] {
    let (_, [xc, xs]) = fourier::mode_patch_eigenvectors(n, c, 1).unwrap();
    let ext = catmull_clark::extended_matrix::<f64>(n, &c)
        .unwrap()
        .into_matrix();
    let lay = PatchLayout::new(n).unwrap();
    let pt = |i: usize| -> [f64; 2] {
        let row = ext.row(i);
        [
            row.iter().zip(xc.iter()).map(|(a, b)| a * b).sum(),
            row.iter().zip(xs.iter()).map(|(a, b)| a * b).sum(),
        ]
    };
    std::array::from_fn(|m| {
        let idx = lay.sub_patch(SubPatch::ALL[m]);
        std::array::from_fn(|a| std::array::from_fn(|b| pt(idx[a][b])))
    })
}

/// Number of window coordinates outside the enclosure at `samples` random
/// `c` of the cell, and the number checked.
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
    let (mut bad, mut checks) = (0, 0);
    for _ in 0..samples {
        let c = rng.uniform(lo, hi);
        let w = shape_windows_at(n, c);
        for m in 0..3 {
            for a in 0..4 {
                for b in 0..4 {
                    for k in 0..2 {
                        checks += 1;
                        if !inside(w[m][a][b][k], ring.windows[m][a][b][k]) {
                            bad += 1;
                        }
                    }
                }
            }
        }
    }
    (bad, checks)
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

/// `W(r) = (I + R(r))/4` in floats.
fn w_at(r: &[f64]) -> DMatrix<f64> {
    let n = r.len();
    let mut w = DMatrix::zeros(n, n);
    for i in 0..n {
        let im = (i + n - 1) % n;
        let ip = (i + 1) % n;
        w[(i, i)] += (2.0 - r[im] + r[i]) / 4.0;
        w[(i, im)] += r[im] / 4.0;
        w[(i, ip)] += (1.0 - r[i]) / 4.0;
    }
    w
}

/// The pointwise ring at `r` in the normalisation `Q [I; P]` of the cell's
/// enclosure: `(||P||_F, 9n ring points, the basis of S_n)`.
fn ratio_ring_at(ring: &RatioRing, r: &[f64]) -> (f64, Vec<[f64; 2]>) {
    let n = r.len();
    let w = w_at(r);
    let eig = Eigen::new(
        &w,
        EigenOptions {
            right: true,
            left: false,
        },
    )
    .unwrap();
    // the pair: the two largest moduli other than 3/4
    let vals = eig.values();
    let vecs = eig.right().unwrap();
    let k34 = (0..n)
        .min_by(|&a, &b| (vals[a] - 0.75).norm().total_cmp(&(vals[b] - 0.75).norm()))
        .unwrap();
    let order: Vec<usize> = (0..n).filter(|&k| k != k34).collect();
    let (a, b) = (order[0], order[1]);
    let bmat = if vals[a].im.abs() > 1e-12 {
        DMatrix::from_fn(n, 2, |i, j| {
            if j == 0 {
                vecs[(i, a)].re
            } else {
                vecs[(i, a)].im
            }
        })
    } else {
        let real = |k: usize| {
            let big = (0..n)
                .map(|i| vecs[(i, k)])
                .max_by(|x, y| x.norm().total_cmp(&y.norm()))
                .unwrap();
            let ph = big.conj() / big.norm();
            (0..n).map(|i| (vecs[(i, k)] * ph).re).collect::<Vec<f64>>()
        };
        let (va, vb) = (real(a), real(b));
        DMatrix::from_fn(n, 2, |i, j| if j == 0 { va[i] } else { vb[i] })
    };
    let qinv = ring.q.clone().try_inverse().unwrap();
    let z = &qinv * &bmat;
    let z1 = z.rows(0, 2).into_owned().try_inverse().unwrap();
    let p = z.rows(2, n - 2).into_owned() * z1;
    let pf = p.norm();
    let mut ip = DMatrix::zeros(n, 2);
    ip[(0, 0)] = 1.0;
    ip[(1, 1)] = 1.0;
    ip.rows_mut(2, n - 2).copy_from(&p);
    let basis = &ring.q * ip;
    let t = &qinv * &w * &ring.q;
    let nmat = t.view((0, 0), (2, 2)).into_owned() + t.view((0, 2), (2, n - 2)) * &p;
    let scheme = LocalScheme::nurds(EdgeRatios::new(r.to_vec()).unwrap());
    let sn = scheme.matrix().unwrap().into_matrix();
    let wa: Vec<[f64; 2]> = (0..n).map(|i| [basis[(i, 0)], basis[(i, 1)]]).collect();
    let m = [[nmat[(0, 0)], nmat[(0, 1)]], [nmat[(1, 0)], nmat[(1, 1)]]];
    let full = crate::charmap::basis::lift_subspace(&sn, &wa, m).unwrap();
    let w1: Vec<f64> = full.iter().map(|x| x[0]).collect();
    let w2: Vec<f64> = full.iter().map(|x| x[1]).collect();
    let ext = ExtendedMatrix::new(&scheme).unwrap();
    (pf, ring_points(&ext, &w1, &w2).unwrap())
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
    let (mut bad, mut checks) = (0, 0);
    for _ in 0..samples {
        let r: Vec<f64> = lo
            .iter()
            .zip(hi)
            .map(|(a, b)| rng.uniform(*a, *b))
            .collect();
        let (pf, pts) = ratio_ring_at(&ring, &r);
        checks += 1;
        if pf > ring.rho * (1.0 + 1e-9) + 1e-14 {
            bad += 1;
        }
        for (p, e) in pts.iter().zip(&ring.points) {
            for k in 0..2 {
                checks += 1;
                if !inside(p[k], e[k]) {
                    bad += 1;
                }
            }
        }
    }
    (bad, checks)
}

#[test]
fn ratio_enclosure_contains_the_pointwise_ring() {
    let cases: [(Vec<f64>, Vec<f64>); 4] = [
        (vec![0.3, 0.4, 0.5], vec![0.31, 0.41, 0.51]),
        (vec![0.1, 0.8, 0.3], vec![0.105, 0.81, 0.305]),
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
    assert!(bad > 0, "{bad} of {checks}");
}

#[test]
fn small_cells_are_certified() {
    // the adjustable scheme and NURDS n = 3, 4 on small cells of typical parameters
    for (n, lo, hi) in [(3, 0.5, 0.501), (5, 0.1, 0.101), (16, 0.9, 0.901)] {
        assert!(
            shape::certified(n, lo, hi, CellTamper::None),
            "n={n} [{lo}, {hi}]"
        );
    }
    for (lo, hi) in [
        (vec![0.3, 0.4, 0.5], vec![0.301, 0.401, 0.501]),
        (vec![0.1, 0.8, 0.3], vec![0.101, 0.801, 0.301]),
        (vec![0.4, 0.45, 0.5, 0.55], vec![0.401, 0.451, 0.501, 0.551]),
    ] {
        assert!(ratios::certified(&lo, &hi, CellTamper::None).0, "{lo:?}");
    }
}
