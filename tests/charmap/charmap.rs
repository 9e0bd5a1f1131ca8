//! Characteristic maps of the Doo-Sabin family (math doc section 7).

use faer::diag::Diag;
use faer::linalg::evd::{evd_real, evd_scratch, ComputeEigenvectors};
use faer::{Mat, Par};
use num_complex::Complex64;
use proptest::prelude::*;
use subdiv_lab::bezier::BezierCurve;
use subdiv_lab::bezier::{PlanarPatch, TensorBezier};
use subdiv_lab::charmap::regularity::{
    check_bezier_patches, check_regularity, gamma, Coefficients, ErrorModel, RegularityVerdict,
    MAX_DEPTH, MAX_PIECES,
};
use subdiv_lab::charmap::winding::{winding_number, HullCurve, ANGLE_MARGIN, MAX_SPLIT_DEPTH};
use subdiv_lab::charmap::{
    check, check_basis, CharmapReport, Eigenstructure, PlanarBasis, Verdict,
};
use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::rng::Lcg64;
use subdiv_lab::scalar::{f64_to_rational, Rational, Scalar};
use subdiv_lab::schemes::doo_sabin::extended::{ExtLayout, ExtendedMatrix};
use subdiv_lab::schemes::doo_sabin::ring::{PatchKind, Ring, RingPatchId};
use subdiv_lab::schemes::LocalScheme;

/// Independent eigen-decomposition (faer directly) of S_n: the subdominant pair's
/// planar basis, classified crudely (tests only).
fn basis_of(scheme: &LocalScheme<f64>) -> PlanarBasis {
    basis_at(scheme, 1)
}

/// The planar basis of the eigenvalue pair at sorted positions `k, k + 1`.
fn basis_at(scheme: &LocalScheme<f64>, k: usize) -> PlanarBasis {
    let s = scheme.matrix().unwrap().into_matrix();
    let n = s.nrows();
    let a = Mat::<f64>::from_fn(n, n, |i, j| s[(i, j)]);
    let mut re = Diag::<f64>::zeros(n);
    let mut im = Diag::<f64>::zeros(n);
    let mut u = Mat::<f64>::zeros(n, n);
    let scratch = evd_scratch::<f64>(
        n,
        ComputeEigenvectors::No,
        ComputeEigenvectors::Yes,
        Par::Seq,
        Default::default(),
    );
    let mut mem = faer::dyn_stack::MemBuffer::new(scratch);
    let stack = faer::dyn_stack::MemStack::new(&mut mem);
    evd_real(
        a.as_ref(),
        re.as_mut(),
        im.as_mut(),
        None,
        Some(u.as_mut()),
        Par::Seq,
        stack,
        Default::default(),
    )
    .unwrap();
    let mut order: Vec<usize> = (0..n).collect();
    let modulus = |k: usize| re[k].hypot(im[k]);
    order.sort_by(|&x, &y| modulus(y).total_cmp(&modulus(x)));
    let (k1, k2, k3) = (order[k], order[k + 1], order[k + 2]);
    let l1 = Complex64::new(re[k1], im[k1]);
    let l2 = Complex64::new(re[k2], im[k2]);
    let gap = (modulus(k2) - modulus(k3)).min(modulus(order[k - 1]) - modulus(k1));
    let col = |k: usize| (0..n).map(|i| u[(i, k)]).collect::<Vec<f64>>();
    let (structure, a, b) = if im[k1] != 0.0 {
        // columns j (Re) and j+1 (Im) for the member with positive imaginary part
        let j = if im[k1] > 0.0 { k1 } else { k2 };
        let j = j.min(if im[j] > 0.0 { j } else { j - 1 });
        let st = if im[k1].abs() < 1e-9 {
            Eigenstructure::Standard
        } else {
            Eigenstructure::ComplexPair
        };
        (st, col(j), col(j + 1))
    } else if (re[k1] - re[k2]).abs() < 1e-9 {
        (Eigenstructure::Standard, col(k1), col(k2))
    } else {
        (Eigenstructure::RealDistinct, col(k1), col(k2))
    };
    PlanarBasis::new(&s, structure, [l1, l2], &a, &b, gap).unwrap()
}

/// The library entry point (spectral classification + structured subspace).
fn report(scheme: &LocalScheme<f64>) -> CharmapReport<subdiv_lab::charmap::AnyPatchId> {
    check(scheme).unwrap()
}

/// Independent route: eigenvectors of the full 4n x 4n matrix (faer directly).
fn report_full(scheme: &LocalScheme<f64>) -> CharmapReport {
    let ext = ExtendedMatrix::new(scheme).unwrap();
    check_basis(&ext, &scheme.ratios(), &basis_of(scheme)).unwrap()
}

fn ring_of(scheme: &LocalScheme<f64>, basis: &PlanarBasis) -> Ring {
    let ext = ExtendedMatrix::new(scheme).unwrap();
    Ring::from_basis(&ext, &scheme.ratios(), &basis.w1, &basis.w2).unwrap()
}

fn rat(a: i64, b: i64) -> Rational {
    Rational::frac(a, b)
}

fn assert_c1(scheme: &LocalScheme<f64>) {
    let r = report(scheme);
    let g = r.regularity.as_ref().unwrap();
    let why = match g.witness {
        Some((p, v)) => format!(
            "wrong-sign Jacobian {v:e} at {} ({}, {})",
            p.patch, p.s, p.t
        ),
        None => format!(
            "min coefficient {:e} at {}",
            g.min_coeff, g.min_location.patch
        ),
    };
    assert_eq!(
        r.verdict,
        Verdict::C1Standard,
        "{} n={}: {} ({why}); winding {:?}",
        scheme.kind(),
        scheme.valence(),
        r.verdict,
        r.winding_number
    );
    assert_eq!(g.verdict, RegularityVerdict::Regular);
    assert!(g.min_coeff > g.relative_error_bound);
    assert_eq!(r.winding_number, Some(1));
    assert_eq!(r.inner_winding_number, Some(1));
    let f = report_full(scheme);
    assert_eq!(f.verdict, r.verdict);
    assert!((f.min_jacobian_coeff().unwrap() - g.min_coeff).abs() < 1e-8);
}

// ---------------------------------------------------------------- extended matrix

#[test]
fn extended_rows_for_configuration_points_equal_s_n_exactly() {
    let cases: Vec<LocalScheme<Rational>> = vec![
        LocalScheme::nurds(
            EdgeRatios::new(vec![
                rat(1, 3),
                rat(5, 7),
                rat(1, 2),
                rat(9, 10),
                rat(2, 11),
            ])
            .unwrap(),
        ),
        LocalScheme::nurds(EdgeRatios::new(vec![rat(1, 100), rat(99, 100), rat(3, 4)]).unwrap()),
        LocalScheme::nurds(
            CornerIntervals::new(
                vec![rat(13, 10), rat(22, 10), rat(4, 10), rat(7, 10)],
                vec![rat(22, 10), rat(13, 10), rat(7, 10), rat(4, 10)],
            )
            .unwrap()
            .ratios()
            .unwrap(),
        ),
        LocalScheme::doo_sabin(3).unwrap(),
        LocalScheme::doo_sabin(6).unwrap(),
        LocalScheme::cc_variant(7).unwrap(),
    ];
    for s in cases {
        let n = s.valence();
        let sn = s.matrix().unwrap();
        let ext = ExtendedMatrix::new(&s).unwrap();
        let m = ext.matrix();
        assert_eq!(m.matrix().shape(), (9 * n, 4 * n));
        assert_eq!(&m.rows()[..4 * n], sn.rows());
        assert_eq!(m.cols(), sn.cols());
        for i in 0..4 * n {
            for j in 0..4 * n {
                assert_eq!(
                    m.matrix()[(i, j)],
                    sn.matrix()[(i, j)],
                    "{} row {i} col {j}",
                    s.kind()
                );
            }
        }
        // every row sums to exactly 1, all weights non-negative
        assert!(m
            .row_sum_defects()
            .iter()
            .all(|d| *d == Rational::frac(0, 1)));
        assert!(m.matrix().iter().all(|x| *x >= Rational::frac(0, 1)));
        // labels: (F,P_i), (E_i,P_i), (E_i,P_{i+1}), (V_i,P_i), then the rest
        let l = ext.labels();
        let x = ExtLayout::new(n);
        assert_eq!(l[x.f_p(1)].to_string(), "(F,P1)");
        assert_eq!(
            l[x.e_pnext(n - 1)].to_string(),
            "(E".to_string() + &(n - 1).to_string() + ",P0)"
        );
        assert_eq!(l[x.v_eprev2(0)].to_string(), format!("(V0,E{},2)", n - 1));
        assert_eq!(l[x.v_c(2)].to_string(), "(V2,C2)");
        // the f64 build agrees with the exact one
        let sf = match &s {
            LocalScheme::Nurds(r) => LocalScheme::nurds(r.to_f64()),
            LocalScheme::DooSabin { valence } => LocalScheme::doo_sabin(*valence).unwrap(),
            _ => LocalScheme::cc_variant(n).unwrap(),
        };
        let ef = ExtendedMatrix::new(&sf).unwrap();
        let exact = m.to_f64();
        for (a, b) in ef.matrix().matrix().iter().zip(exact.matrix().iter()) {
            assert!((a - b).abs() < 1e-15);
        }
    }
}

#[test]
fn extended_rows_of_new_points_follow_the_face_rules() {
    // (E_i, E_i1) = 1/4 (E_i1 + midpoint(E_i1, P_i) + edge point of E_i1 E_i2 + face point), tensor face point.
    let r = [0.3, 0.8, 0.55];
    let s = LocalScheme::nurds(EdgeRatios::new(r.to_vec()).unwrap());
    let ext = ExtendedMatrix::new(&s).unwrap();
    let lay = subdiv_lab::schemes::doo_sabin::Layout::new(3);
    let x = ExtLayout::new(3);
    for i in 0..3 {
        let (ri, si) = (r[i], 1.0 - r[i]);
        let row = ext.matrix().matrix().row(x.e_e1(i));
        let want = [
            (lay.e1(i), (1.0 + 0.5 + ri + ri / 2.0) / 4.0),
            (lay.p(i), (0.5 + ri / 2.0) / 4.0),
            (lay.e2(i), (si + si / 2.0) / 4.0),
            (lay.p(i + 1), (si / 2.0) / 4.0),
        ];
        for (col, w) in want {
            assert!(
                (row[col] - w).abs() < 1e-15,
                "row (E{i},E{i}1) col {col}: {} vs {w}",
                row[col]
            );
        }
        // V-face: (V_i, C_i) = 9/16 C_i + 3/16 (E_i1 + E_{i-1,2}) + 1/16 P_i
        let row = ext.matrix().matrix().row(x.v_c(i));
        assert_eq!(row[lay.c(i)], 9.0 / 16.0);
        assert_eq!(row[lay.e1(i)], 3.0 / 16.0);
        assert_eq!(row[lay.e2(i + 2)], 3.0 / 16.0);
        assert_eq!(row[lay.p(i)], 1.0 / 16.0);
    }
}

// ---------------------------------------------------------------- ring geometry

fn same_curve(a: &BezierCurve, b: &BezierCurve, tol: f64) -> bool {
    a.points.len() == b.points.len()
        && a.points
            .iter()
            .zip(&b.points)
            .all(|(p, q)| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol)
}

#[test]
fn neighbouring_ring_patches_share_boundaries_and_bezier_matches_bspline() {
    // Arbitrary planar data: the join property holds for any control points.
    let r = vec![0.15, 0.7, 0.42, 0.93, 0.5];
    let s = LocalScheme::nurds(EdgeRatios::new(r).unwrap());
    let ext = ExtendedMatrix::new(&s).unwrap();
    let w1: Vec<f64> = (0..20).map(|k| ((k * 7 % 11) as f64).sin()).collect();
    let w2: Vec<f64> = (0..20).map(|k| ((k * 5 % 13) as f64).cos()).collect();
    let ring = Ring::from_basis(&ext, &s.ratios(), &w1, &w2).unwrap();
    let id = |kind, index| RingPatchId { kind, index };
    for i in 0..5 {
        let a = &ring.patch(id(PatchKind::A, i)).bezier;
        let b = &ring.patch(id(PatchKind::B, i)).bezier;
        let c = &ring.patch(id(PatchKind::C, i)).bezier;
        let bprev = &ring.patch(id(PatchKind::B, i + 4)).bezier;
        assert!(
            same_curve(&a.boundary_s(true), &b.boundary_s(false), 1e-14),
            "A{i}|B{i}"
        );
        assert!(
            same_curve(&c.boundary_s(true), &a.boundary_s(false), 1e-14),
            "C{i}|A{i}"
        );
        assert!(
            same_curve(
                &bprev.boundary_s(true),
                &c.boundary_t(false).reversed(),
                1e-14
            ),
            "B{}|C{i}",
            i + 4
        );
        for p in ring.patches() {
            for (u, v) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5)] {
                let (e, f) = (p.bezier.eval(u, v), p.spline.eval(u, v));
                assert!((e[0] - f[0]).abs() < 1e-14 && (e[1] - f[1]).abs() < 1e-14);
            }
        }
    }
    // The boundary chains close up.
    for chain in [ring.outer_boundary(), ring.inner_boundary()] {
        for k in 0..chain.len() {
            let (a, b) = (
                chain[k].points.last().unwrap(),
                chain[(k + 1) % chain.len()].points[0],
            );
            assert!((a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14);
        }
    }
}

/// Distance from `p` to the polyline sampled from `curves` (dense).
fn dist_to_chain(p: [f64; 2], pts: &[[f64; 2]]) -> f64 {
    pts.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = if l2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            ((p[0] - a[0] - t * d[0]).powi(2) + (p[1] - a[1] - t * d[1]).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn consecutive_rings_nest_inner_boundary_is_the_next_outer_boundary() {
    // Ring k+1 = M^T ring k (M = W^T S W): its outer boundary must be ring k's
    // inner boundary. This checks the extended matrix, the patch layout and the
    // knot spans together, for standard, real_distinct and complex_pair bases.
    let schemes = vec![
        LocalScheme::<f64>::cc_variant(5).unwrap(),
        LocalScheme::<f64>::doo_sabin(3).unwrap(),
        LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.85, 0.4, 0.6, 0.1, 0.7]).unwrap()),
        LocalScheme::nurds(EdgeRatios::new(vec![0.9, 0.1, 0.9, 0.1, 0.5]).unwrap()),
        LocalScheme::nurds(EdgeRatios::new(vec![0.05, 0.3, 0.95]).unwrap()),
        LocalScheme::nurds(EdgeRatios::new(vec![0.05, 0.9, 0.3, 0.6, 0.95, 0.2]).unwrap()),
    ];
    let mut seen = std::collections::HashSet::new();
    for s in schemes {
        let basis = basis_of(&s);
        seen.insert(basis.structure);
        let ring = ring_of(&s, &basis);
        let m = basis.restriction;
        let next = |p: [f64; 2]| {
            [
                m[0][0] * p[0] + m[1][0] * p[1],
                m[0][1] * p[0] + m[1][1] * p[1],
            ]
        };
        let mut outer_next = Vec::new();
        for c in ring.outer_boundary() {
            for k in 0..=400 {
                outer_next.push(next(c.eval(k as f64 / 400.0)));
            }
        }
        let scale = ring.max_abs();
        for c in ring.inner_boundary() {
            for k in 0..=10 {
                let p = c.eval(k as f64 / 10.0);
                let d = dist_to_chain(p, &outer_next);
                assert!(
                    d < 1e-4 * scale,
                    "{} n={}: inner point {p:?} is {d:e} from the next ring",
                    s.kind(),
                    s.valence()
                );
            }
        }
        // and the eigen-relation really holds (residual tiny)
        assert!(basis.residual < 1e-12, "residual {}", basis.residual);
    }
    assert!(
        seen.len() >= 2,
        "cases should cover several eigenstructures: {seen:?}"
    );
}

// ---------------------------------------------------------------- n = 4

#[test]
fn n4_uniform_and_tensor_rings_are_affine_images_of_a_rectangular_annulus() {
    let tensor = |d0: f64, d1: f64, e0: f64, e1: f64| {
        // fact 2 of math doc section 3: P0: p=d0,q=e0; P1: p=e0,q=d1; P2: p=d1,q=e1; P3: p=e1,q=d0
        CornerIntervals::new(vec![d0, e0, d1, e1], vec![e0, d1, e1, d0])
            .unwrap()
            .ratios()
            .unwrap()
    };
    let schemes = vec![
        LocalScheme::<f64>::cc_variant(4).unwrap(),
        LocalScheme::<f64>::doo_sabin(4).unwrap(),
        LocalScheme::nurds(tensor(1.3, 0.4, 2.2, 0.7)),
        LocalScheme::nurds(tensor(0.05, 3.0, 1.0, 0.2)),
    ];
    for s in schemes {
        let basis = basis_of(&s);
        assert_eq!(
            basis.structure,
            Eigenstructure::Standard,
            "{:?}",
            basis.lambda
        );
        assert!((basis.lambda[0].re - 0.5).abs() < 1e-12);
        let ring = ring_of(&s, &basis);
        let scale = ring.max_abs();
        for p in ring.patches() {
            // every net is affine in (i, j): b_ij = b_00 + i a + j b
            let b = |i, j| p.bezier.control(i, j);
            for i in 0..3 {
                for j in 0..3 {
                    for k in 0..2 {
                        let aff = b(0, 0)[k]
                            + i as f64 / 2.0 * (b(2, 0)[k] - b(0, 0)[k])
                            + j as f64 / 2.0 * (b(0, 2)[k] - b(0, 0)[k]);
                        assert!(
                            (b(i, j)[k] - aff).abs() < 1e-12 * scale,
                            "{} {}: not affine",
                            s.kind(),
                            p.id
                        );
                    }
                }
            }
            // constant Jacobian on each patch
            let j = p.bezier.jacobian();
            let (lo, hi) = (j.min_coeff().0, j.max_coeff().0);
            assert!(
                (hi - lo).abs() < 1e-10 * hi.abs().max(lo.abs()),
                "{}: J in [{lo}, {hi}]",
                p.id
            );
        }
        // the image is the region between two parallelograms: the ring's outer
        // boundary consists of straight segments with 4 corners; simplest check:
        // all 12 patches are pieces of ONE affine map of the knot plane, i.e. the
        // A/B/C nets' edge vectors along x and y are parallel to two fixed directions.
        // The tensor configurations' double 1/2 has no structural
        // certificate in floating point (math doc section 10): the checked
        // verdict is given for the uniform ones; for the tensor ones the
        // planar basis above is taken as given.
        let r = if s.kind() == subdiv_lab::schemes::SchemeKind::Nurds {
            assert!(
                matches!(report(&s).verdict, Verdict::NoCharacteristicMap { .. }),
                "uncertified double: no definite verdict"
            );
            let r = check_basis(&ExtendedMatrix::new(&s).unwrap(), &s.ratios(), &basis).unwrap();
            let g = r.regularity.as_ref().map(|g| (g.min_coeff, g.pieces));
            (r.verdict, r.winding_number, g)
        } else {
            let r = report(&s);
            let g = r.regularity.as_ref().map(|g| (g.min_coeff, g.pieces));
            (r.verdict, r.winding_number, g)
        };
        assert_eq!(r.0, Verdict::C1Standard);
        assert_eq!(r.1, Some(1));
        let (min_coeff, pieces) = r.2.unwrap();
        assert!(
            min_coeff > 0.0 && pieces == 12,
            "no subdivision needed: {}",
            pieces
        );
        if s.kind() != subdiv_lab::schemes::SchemeKind::Nurds {
            assert!(
                (min_coeff - 1.0).abs() < 1e-9,
                "uniform: all coefficients equal"
            );
        }
    }
}

// ---------------------------------------------------------------- uniform surveys

#[test]
fn cc_variant_is_c1_for_n_3_to_32() {
    for n in 3..=32 {
        assert_c1(&LocalScheme::<f64>::cc_variant(n).unwrap());
    }
}

#[test]
fn original_doo_sabin_is_c1_for_n_3_to_32() {
    for n in 3..=32 {
        assert_c1(&LocalScheme::<f64>::doo_sabin(n).unwrap());
    }
}

// ---------------------------------------------------------------- counterexamples

#[test]
fn a_folding_perturbation_is_not_regular_with_an_evaluated_witness() {
    // Reflect the outer points (E_i, E_i2) through (E_i, P_{i+1}): new row =
    // 2 row(E_i,P_{i+1}) - row(E_i,E_i2) (rows still sum to 1). The patches
    // B_i then fold back over themselves.
    let s = LocalScheme::<f64>::cc_variant(5).unwrap();
    let ext = ExtendedMatrix::new(&s).unwrap();
    let x = ExtLayout::new(5);
    let m = ext.matrix().matrix().clone();
    let folded = ext
        .map_entries(|i, j, v| {
            if (0..5).any(|k| x.e_e2(k) == i) {
                let k = (i - x.e_e2(0)) / 2;
                2.0 * m[(x.e_pnext(k), j)] - v
            } else {
                *v
            }
        })
        .unwrap();
    let basis = basis_of(&s);
    let r = check_basis(&folded, &s.ratios(), &basis).unwrap();
    assert_eq!(r.verdict, Verdict::NotRegular, "{}", r.verdict);
    let g = r.regularity.as_ref().unwrap();
    let (p, v) = g.witness.expect("a witness point");
    assert!(v < 0.0);
    // Evaluate the Jacobian at the witness independently: central differences of
    // the B-spline patch (not the Bezier form).
    let ring = Ring::from_basis(&folded, &s.ratios(), &basis.w1, &basis.w2).unwrap();
    let patch = &ring.patch(p.patch).spline;
    let h = 1e-6;
    let (s0, t0) = (p.s.clamp(h, 1.0 - h), p.t.clamp(h, 1.0 - h));
    let (a, b) = (patch.eval(s0 + h, t0), patch.eval(s0 - h, t0));
    let (c, d) = (patch.eval(s0, t0 + h), patch.eval(s0, t0 - h));
    let xs = [(a[0] - b[0]) / (2.0 * h), (a[1] - b[1]) / (2.0 * h)];
    let xt = [(c[0] - d[0]) / (2.0 * h), (c[1] - d[1]) / (2.0 * h)];
    let jac = xs[0] * xt[1] - xs[1] * xt[0];
    assert!(
        f64::from(g.orientation) * jac < 0.0,
        "witness {p:?}: J = {jac}, orientation {}",
        g.orientation
    );
    // the unperturbed matrix is fine
    assert_eq!(
        check_basis(&ext, &s.ratios(), &basis).unwrap().verdict,
        Verdict::C1Standard
    );
}

#[test]
fn the_second_fourier_mode_is_not_injective() {
    // Using the eigenvectors of the k = 2 Fourier mode (lambda = 1/2 + cos(4 pi/n)/4)
    // as a "characteristic map" gives a ring that winds twice (z -> z^2-like).
    for n in [5usize, 7, 9] {
        let s = LocalScheme::<f64>::cc_variant(n).unwrap();
        let basis = basis_at(&s, 3);
        let want = 0.5 + (4.0 * std::f64::consts::PI / n as f64).cos() / 4.0;
        assert!(
            (basis.lambda[0].re - want).abs() < 1e-12,
            "{:?} vs {want}",
            basis.lambda
        );
        let ext = ExtendedMatrix::new(&s).unwrap();
        let r = check_basis(&ext, &s.ratios(), &basis).unwrap();
        assert_ne!(r.verdict, Verdict::C1Standard);
        match r.verdict {
            Verdict::NotInjective { winding } => assert_eq!(winding, 2, "n={n}"),
            Verdict::NotRegular => {}
            ref v => panic!("n={n}: unexpected {v}"),
        }
    }
}

// ---------------------------------------------------------------- invariances

fn summary(r: &CharmapReport<subdiv_lab::charmap::AnyPatchId>) -> (String, i64, f64) {
    (
        r.verdict.code().to_owned(),
        r.winding_number.unwrap_or(i64::MIN),
        r.min_jacobian_coeff().unwrap_or(f64::NAN),
    )
}

#[test]
fn rotating_face_labels_and_scaling_knots_change_nothing() {
    let p = vec![1.0, 0.3, 2.5, 0.8, 1.7, 0.45];
    let q = vec![0.6, 1.9, 0.2, 1.1, 0.9, 2.2];
    let knots = CornerIntervals::new(p, q).unwrap();
    let base = report(&LocalScheme::nurds(knots.ratios().unwrap()));
    let (code, w, min) = summary(&base);
    for k in 1..6 {
        let rot = report(&LocalScheme::nurds(knots.rotated(k).ratios().unwrap()));
        let (c2, w2, m2) = summary(&rot);
        assert_eq!((c2.as_str(), w2), (code.as_str(), w), "rotation by {k}");
        assert!(
            (m2 - min).abs() < 1e-8,
            "rotation by {k}: min coeff {m2} vs {min}"
        );
    }
    for f in [1e-3, 7.3, 1e4] {
        let sc = report(&LocalScheme::nurds(
            knots.scaled(&f).unwrap().ratios().unwrap(),
        ));
        let (c2, w2, m2) = summary(&sc);
        assert_eq!((c2.as_str(), w2), (code.as_str(), w), "scale {f}");
        assert!((m2 - min).abs() < 1e-10, "scale {f}: {m2} vs {min}");
        assert_eq!(sc.structure, base.structure);
    }
}

// ---------------------------------------------------------------- random knots

const VERDICT_CODES: &[&str] = &[
    "c1",
    "tpc_real_distinct",
    "tpc_complex_pair",
    "not_regular",
    "not_injective",
    "indeterminate",
    "no_charmap",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(120))]
    #[test]
    fn random_nurds_verdicts_are_defined(r in (3usize..=8).prop_flat_map(|n| proptest::collection::vec(0.01f64..0.99, n))) {
        let ratios = EdgeRatios::new(r).unwrap();
        let s = LocalScheme::nurds(ratios.clone());
        let rep = report(&s);
        prop_assert!(VERDICT_CODES.contains(&rep.verdict.code()));
        if rep.structure != Some(Eigenstructure::Standard) {
            prop_assert_ne!(rep.verdict.code(), "c1");
        }
        // relabelling the corners (i -> i + 1) changes nothing
        let rot = report(&LocalScheme::nurds(ratios.rotated(1)));
        prop_assert_eq!(rot.verdict.code(), rep.verdict.code());
        prop_assert_eq!(rot.winding_number, rep.winding_number);
        if let (Some(a), Some(b)) = (rot.min_jacobian_coeff(), rep.min_jacobian_coeff()) {
            prop_assert!((a - b).abs() < 1e-7, "min coeff {} vs {}", a, b);
        }
        prop_assert!(rep.point_error.is_nan() || rep.point_error < 1e-6, "point error {}", rep.point_error);
    }
}

#[test]
fn indeterminate_is_rare_for_random_nurds_knots() {
    // Deterministic LCG sampler, 200 configurations per n = 3..8.
    let mut state = Lcg64::new(0x2545_f491_4f6c_dd1du64);
    let mut next = || 0.01 + 0.98 * state.next_f64();
    let mut total = 0;
    let mut indeterminate = 0;
    for n in 3..=8 {
        for _ in 0..200 {
            let r: Vec<f64> = (0..n).map(|_| next()).collect();
            let rep = report(&LocalScheme::nurds(EdgeRatios::new(r).unwrap()));
            total += 1;
            if rep.verdict.code() == "indeterminate" {
                indeterminate += 1;
            }
        }
    }
    println!("indeterminate: {indeterminate} of {total}");
    assert!(
        indeterminate * 100 <= total,
        "indeterminate {indeterminate} of {total}"
    );
}

// ---------------------------------------------------------------- structured basis

#[test]
fn structured_subspace_equals_the_full_eigenvector_subspace() {
    // Face-block null space of (A - l1)(A - l2) lifted by the block equations
    // vs. eigenvectors of the full 4n x 4n matrix (faer): same plane, and the
    // same verdict and min coefficient.
    use subdiv_lab::charmap::basis::subdominant_basis;
    let mut state = Lcg64::new(7u64);
    let mut next = || 0.01 + 0.98 * state.next_f64();
    let mut schemes = vec![
        LocalScheme::<f64>::cc_variant(7).unwrap(),
        LocalScheme::<f64>::doo_sabin(5).unwrap(),
    ];
    for n in 3..=8 {
        for _ in 0..4 {
            schemes.push(LocalScheme::nurds(
                EdgeRatios::new((0..n).map(|_| next()).collect()).unwrap(),
            ));
        }
    }
    for s in schemes {
        let full = basis_of(&s);
        let sn = s.matrix().unwrap().into_matrix();
        let st = subdominant_basis(&s, &sn, full.structure, full.lambda, 0.01).unwrap();
        // principal angles: W_full^T W_st has singular values 1 <=> |det| = 1 for orthonormal 2-frames
        let d = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        let g = [
            [d(&full.w1, &st.w1), d(&full.w1, &st.w2)],
            [d(&full.w2, &st.w1), d(&full.w2, &st.w2)],
        ];
        let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
        assert!(
            (det.abs() - 1.0).abs() < 1e-9,
            "{} {:?}: |det| = {}",
            s.kind(),
            s.ratios().as_slice(),
            det.abs()
        );
        assert!(st.residual < 1e-12);
        let ext = ExtendedMatrix::new(&s).unwrap();
        let (a, b) = (
            check_basis(&ext, &s.ratios(), &full).unwrap(),
            check_basis(&ext, &s.ratios(), &st).unwrap(),
        );
        assert_eq!(a.verdict, b.verdict);
        assert!((a.min_jacobian_coeff().unwrap() - b.min_jacobian_coeff().unwrap()).abs() < 1e-8);
    }
}

#[test]
fn n4_uniform_ring_is_exactly_the_square_annulus_up_to_a_linear_map() {
    // Exact subdominant eigenvectors of the regular 4x4 grid: the Greville
    // coordinates (linear precision). The ring is then the square annulus
    // 1/2 <= max(|x|, |y|) <= 1 itself, and the ring of the computed basis is a
    // linear image of it.
    let s = LocalScheme::<f64>::cc_variant(4).unwrap();
    let xy: [(f64, f64); 16] = [
        (-0.5, -0.5),
        (0.5, -0.5),
        (0.5, 0.5),
        (-0.5, 0.5),
        (-0.5, -1.5),
        (0.5, -1.5),
        (1.5, -0.5),
        (1.5, 0.5),
        (0.5, 1.5),
        (-0.5, 1.5),
        (-1.5, 0.5),
        (-1.5, -0.5),
        (-1.5, -1.5),
        (1.5, -1.5),
        (1.5, 1.5),
        (-1.5, 1.5),
    ];
    let gx: Vec<f64> = xy.iter().map(|p| p.0).collect();
    let gy: Vec<f64> = xy.iter().map(|p| p.1).collect();
    let sn = s.matrix().unwrap().into_matrix();
    for (w, name) in [(&gx, "x"), (&gy, "y")] {
        let sw = &sn * nalgebra::DVector::from_column_slice(w);
        for i in 0..16 {
            assert!(
                (sw[i] - 0.5 * w[i]).abs() < 1e-15,
                "{name} is an eigenvector for 1/2"
            );
        }
    }
    let ext = ExtendedMatrix::new(&s).unwrap();
    let exact = Ring::from_basis(&ext, &s.ratios(), &gx, &gy).unwrap();
    let linf = |p: [f64; 2]| p[0].abs().max(p[1].abs());
    for (chain, want) in [(exact.outer_boundary(), 1.0), (exact.inner_boundary(), 0.5)] {
        for c in &chain {
            for k in 0..=8 {
                let p = c.eval(k as f64 / 8.0);
                assert!(
                    (linf(p) - want).abs() < 1e-14,
                    "{p:?} not on the square max(|x|, |y|) = {want}"
                );
            }
        }
    }
    for p in exact.patches() {
        // each patch is an axis-parallel square of side 1/2
        let (a, b) = (p.bezier.eval(0.0, 0.0), p.bezier.eval(1.0, 1.0));
        assert!(
            ((a[0] - b[0]).abs() - 0.5).abs() < 1e-14 && ((a[1] - b[1]).abs() - 0.5).abs() < 1e-14
        );
        // |J| = (1/2)^2 everywhere; the charts are oriented clockwise with respect
        // to the counter-clockwise face, so J = -1/4 in these coordinates
        assert!(
            (p.bezier.jacobian_at(0.3, 0.6) + 0.25).abs() < 1e-14,
            "{}: J = {}",
            p.id,
            p.bezier.jacobian_at(0.3, 0.6)
        );
    }
    // computed basis: a linear image
    let basis = basis_of(&s);
    let ring = ring_of(&s, &basis);
    let (p0, q0) = (
        exact.patches()[0].bezier.eval(0.0, 0.0),
        ring.patches()[0].bezier.eval(0.0, 0.0),
    );
    let (p1, q1) = (
        exact.patches()[1].bezier.eval(1.0, 0.0),
        ring.patches()[1].bezier.eval(1.0, 0.0),
    );
    // solve L [p0 p1] = [q0 q1]
    let det = p0[0] * p1[1] - p1[0] * p0[1];
    let inv = [[p1[1] / det, -p1[0] / det], [-p0[1] / det, p0[0] / det]];
    let l = |k: usize| {
        [
            q0[k] * inv[0][0] + q1[k] * inv[1][0],
            q0[k] * inv[0][1] + q1[k] * inv[1][1],
        ]
    };
    let (lx, ly) = (l(0), l(1));
    for (pe, pr) in exact.patches().iter().zip(ring.patches()) {
        for (u, v) in [(0.0, 1.0), (0.5, 0.5), (1.0, 0.25)] {
            let (e, r) = (pe.bezier.eval(u, v), pr.bezier.eval(u, v));
            let img = [lx[0] * e[0] + lx[1] * e[1], ly[0] * e[0] + ly[1] * e[1]];
            assert!(
                (img[0] - r[0]).abs() < 1e-12 && (img[1] - r[1]).abs() < 1e-12,
                "{}: {img:?} vs {r:?}",
                pe.id
            );
        }
    }
}

#[test]
fn eigenstructures_without_a_planar_map_are_reported_with_a_reason() {
    use subdiv_lab::charmap::check_classified;
    use subdiv_lab::spectral::classify::ClassName;
    use subdiv_lab::spectral::{classify_scheme, SubdominantClass};
    let s = LocalScheme::<f64>::cc_variant(5).unwrap();
    let base = classify_scheme(&s).unwrap();
    for (class, code, needle) in [
        (
            SubdominantClass::Defective,
            "defective",
            "1-dimensional eigenspace",
        ),
        (
            SubdominantClass::NotSeparated,
            "not_separated",
            "|lambda_2| = |lambda_3|",
        ),
        (
            SubdominantClass::Indeterminate {
                between: (ClassName::Standard, ClassName::ComplexPair),
                reason: "test".into(),
            },
            "indeterminate",
            "undecided between standard and complex_pair",
        ),
    ] {
        let mut sub = base.clone();
        sub.class = class;
        let r = check_classified(&s, &sub).unwrap();
        assert_eq!(r.verdict.code(), "no_charmap");
        let text = r.verdict.to_string();
        assert!(text.contains(code) && text.contains(needle), "{text}");
        assert!(r.regularity.is_none() && r.winding_number.is_none());
        assert_eq!(r.to_json()["regular"], serde_json::Value::Null);
    }
}

// ---------------------------------------------------------------- certificate error bound and orientation

/// A regular ring of the Doo-Sabin family, its control-point error bound, and
/// the ring turned so that its Jacobian is positive.
fn oriented_ring(scheme: &LocalScheme<f64>) -> (Ring, f64) {
    let basis = basis_of(scheme);
    let ext = ExtendedMatrix::new(scheme).unwrap();
    let ring = ring_of(scheme, &basis);
    let delta = subdiv_lab::charmap::point_error(&ext, &basis);
    let reg = check_regularity(&ring, delta);
    assert_eq!(reg.verdict, RegularityVerdict::Regular, "{reg:?}");
    if reg.orientation < 0 {
        (ring.mirrored(), delta)
    } else {
        (ring, delta)
    }
}

#[test]
fn an_error_bound_beyond_the_data_leaves_the_bezier_jacobian_sign_indeterminate() {
    // The Bezier certificate accepts a piece only when its smallest coefficient
    // exceeds the error bound. With a bound far above every coordinate (and so
    // every Jacobian coefficient) nothing can be certified, whatever the signs
    // of the computed coefficients: the verdict must be `indeterminate`, never
    // `regular`.
    for scheme in [
        LocalScheme::<f64>::doo_sabin(5).unwrap(),
        LocalScheme::<f64>::cc_variant(7).unwrap(),
    ] {
        let (ring, delta) = oriented_ring(&scheme);
        // the same ring with its honest bound is certified (so the data are fine)
        let honest = check_regularity(&ring, delta);
        assert_eq!(honest.verdict, RegularityVerdict::Regular);
        assert!(honest.min_coeff > honest.relative_error_bound);
        for big in [10.0 * ring.max_abs(), 1e3 * ring.max_abs()] {
            let reg = check_regularity(&ring, big);
            assert_eq!(
                reg.verdict,
                RegularityVerdict::Indeterminate,
                "{} n={}, delta {big}: {reg:?}",
                scheme.kind(),
                scheme.valence()
            );
            assert!(reg.witness.is_none(), "no witness from noise: {reg:?}");
            assert!(reg.undecided.is_some());
            // hopeless at once: no piece is split (the bound exceeds every coefficient)
            assert_eq!(reg.max_depth, 0, "{reg:?}");
            assert_eq!(reg.pieces, ring.patches().len(), "{reg:?}");
            // every computed coefficient is positive: only the bound stops the certificate
            assert!(
                reg.min_coeff > 0.0 && reg.relative_error_bound > 1.0,
                "{reg:?}"
            );
            // and the whole report says so
            let rep = subdiv_lab::charmap::check_ring(&ring, big, Eigenstructure::Standard);
            assert!(
                matches!(rep.verdict, Verdict::Indeterminate { .. }),
                "{rep:?}"
            );
            assert_eq!(
                rep.regularity.unwrap().verdict,
                RegularityVerdict::Indeterminate
            );
        }
    }
}

#[test]
fn a_mirrored_doo_sabin_ring_winds_negatively_and_the_report_turns_it_back() {
    for scheme in [
        LocalScheme::<f64>::doo_sabin(3).unwrap(),
        LocalScheme::<f64>::doo_sabin(6).unwrap(),
        LocalScheme::<f64>::cc_variant(5).unwrap(),
    ] {
        let what = format!("{} n={}", scheme.kind(), scheme.valence());
        let (ring, delta) = oriented_ring(&scheme);
        let mirror = ring.mirrored();
        // positively oriented ring: both boundaries wind once counter-clockwise
        assert_eq!(
            winding_number(&ring.outer_boundary(), delta),
            Some(1),
            "{what}"
        );
        assert_eq!(
            winding_number(&ring.inner_boundary(), delta),
            Some(1),
            "{what}"
        );
        // its mirror image: clockwise, winding number -1
        assert_eq!(
            winding_number(&mirror.outer_boundary(), delta),
            Some(-1),
            "{what}"
        );
        assert_eq!(
            winding_number(&mirror.inner_boundary(), delta),
            Some(-1),
            "{what}"
        );
        // the regularity check sees the reversed orientation and still certifies
        let (r, m) = (
            check_regularity(&ring, delta),
            check_regularity(&mirror, delta),
        );
        assert_eq!((r.orientation, m.orientation), (1, -1), "{what}");
        assert_eq!(m.verdict, RegularityVerdict::Regular, "{what}");
        assert!((r.min_coeff - m.min_coeff).abs() < 1e-12, "{what}");
        // the report orients the ring before counting: both give winding +1
        for g in [&ring, &mirror] {
            let rep = subdiv_lab::charmap::check_ring(g, delta, Eigenstructure::Standard);
            assert_eq!(rep.verdict, Verdict::C1Standard, "{what}: {rep:?}");
            assert_eq!(
                (rep.winding_number, rep.inner_winding_number),
                (Some(1), Some(1)),
                "{what}"
            );
        }
    }
}

#[test]
fn a_jacobian_that_touches_zero_is_indeterminate_not_a_false_witness() {
    // x = s, y = (t - 1/2)^3: J = x_s y_t - x_t y_s = 3 (t - 1/2)^2 >= 0, zero
    // on the line t = 1/2 (the centre of the patch). No piece along that line
    // can be certified and no point has J < 0: the verdict is `indeterminate`
    // (a zero within rounding is neither a proof of regularity nor a witness).
    let x = TensorBezier::from_fn(3, 3, |a, _| a as f64 / 3.0);
    let yc = [-0.125, 0.125, -0.125, 0.125];
    let y = TensorBezier::from_fn(3, 3, |_, b| yc[b]);
    let patch = PlanarPatch { x, y };
    assert_eq!(patch.jacobian_at(0.5, 0.5), 0.0);
    assert!((patch.jacobian_at(0.3, 0.0) - 0.75).abs() < 1e-15);
    let reg = check_bezier_patches(&[(0usize, &patch)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Indeterminate, "{reg:?}");
    assert_eq!(reg.orientation, 1);
    assert!(reg.witness.is_none(), "{reg:?}");
    // the undecided piece lies on the line t = 1/2 (as its lower or upper edge)
    let at = reg.undecided.unwrap();
    assert!((at.t - 0.5).abs() <= 1.0 / 1024.0 + 1e-15, "{at:?}");
    // the search went down to the depth limit along the line
    assert_eq!(reg.max_depth, MAX_DEPTH);
    // mirrored (y -> -y): the same verdict with orientation -1
    let flipped = PlanarPatch {
        x: patch.x.clone(),
        y: TensorBezier::from_fn(3, 3, |_, b| -yc[b]),
    };
    let reg = check_bezier_patches(&[(0usize, &flipped)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Indeterminate, "{reg:?}");
    assert_eq!(reg.orientation, -1);
    assert!(reg.witness.is_none(), "{reg:?}");
    // y = (t - 1/2)^3 - (t - 1/2)/8 bends back: J < 0 near t = 1/2, a witness exists
    let bent = PlanarPatch {
        x: patch.x.clone(),
        y: TensorBezier::from_fn(3, 3, |_, b| yc[b] - (b as f64 / 3.0 - 0.5) / 8.0),
    };
    let reg = check_bezier_patches(&[(0usize, &bent)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
    let (p, v) = reg.witness.unwrap();
    assert!(v < 0.0 && bent.jacobian_at(p.s, p.t) * f64::from(reg.orientation) < 0.0);
}

#[test]
fn a_negative_jacobian_at_a_corner_is_reported_at_that_corner() {
    // x = s, y = t^2 - t/4: J = y_t = 2t - 1/4, negative for t < 1/8 and
    // positive at the centre. The corner coefficient (0, 0) is the exact value
    // J(0, 0) = -1/4: the first piece yields the witness at that corner, before
    // any subdivision (a centre found after splitting would have t > 0).
    let x = TensorBezier::from_fn(3, 3, |a, _| a as f64 / 3.0);
    let yc = [0.0, -1.0 / 12.0, 1.0 / 6.0, 0.75];
    let y = TensorBezier::from_fn(3, 3, |_, b| yc[b]);
    let patch = PlanarPatch { x, y };
    assert!((patch.jacobian_at(0.0, 0.0) + 0.25).abs() < 1e-15);
    assert!(patch.jacobian_at(0.5, 0.5) > 0.0);
    let reg = check_bezier_patches(&[(7usize, &patch)], 1e-15).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
    assert_eq!(reg.orientation, 1);
    let (p, v) = reg.witness.unwrap();
    assert_eq!((p.patch, p.s, p.t), (7, 0.0, 0.0), "{reg:?}");
    assert_eq!((reg.pieces, reg.max_depth), (1, 0), "{reg:?}");
    // relative to the largest Jacobian coefficient (7/4 at t = 1)
    assert!((v + 0.25 / 1.75).abs() < 1e-12, "{v}");
}

// ---------------------------------------------------------------------------
// The winding certificate on hand-made chains: they reach the error
// allowances and branches of `src/charmap/winding.rs` that no ring test
// reaches (docs/testing.md has the mutation score).

/// The quadrant chain: four quadratic Bezier arcs through `(1, 0)`, `(0, 1)`,
/// `(-1, 0)`, `(0, -1)` with control points `(+-1, +-1)`, scaled by `s`
/// (exact points, exact joins: no bridge).
fn quadrant_polygons(s: f64) -> Vec<Vec<[f64; 2]>> {
    let q = [
        [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        [[0.0, 1.0], [-1.0, 1.0], [-1.0, 0.0]],
        [[-1.0, 0.0], [-1.0, -1.0], [0.0, -1.0]],
        [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]],
    ];
    q.iter()
        .map(|c| c.iter().map(|p| [s * p[0], s * p[1]]).collect())
        .collect()
}

/// A curve for the winding certificate whose error allowances are declared
/// numbers, relative to the chain's magnitude (`split_error = split * scale`,
/// `hull_error = hull * scale`): large and exact, so that the certificate's
/// error accounting decides the outcome. The hull is a Bezier control polygon.
#[derive(Clone, Debug)]
struct Declared {
    curve: BezierCurve,
    split: f64,
    hull: f64,
}

impl Declared {
    fn chain(polygons: &[Vec<[f64; 2]>], split: f64, hull: &[f64]) -> Vec<Declared> {
        polygons
            .iter()
            .zip(hull)
            .map(|(p, &hull)| Declared {
                curve: BezierCurve::new(p.clone()),
                split,
                hull,
            })
            .collect()
    }
}

impl HullCurve for Declared {
    fn hull(&self) -> Vec<[f64; 2]> {
        self.curve.points.clone()
    }
    fn halves(&self) -> (Self, Self) {
        let (l, r) = self.curve.split(0.5);
        let half = |curve| Declared {
            curve,
            split: self.split,
            hull: self.hull,
        };
        (half(l), half(r))
    }
    fn split_error(&self, scale: f64) -> f64 {
        self.split * scale
    }
    fn hull_error(&self, scale: f64) -> f64 {
        self.hull * scale
    }
}

/// `BezierCurve::split_error`, the certificate's allowance for one midpoint
/// split, bounds the rounding of `halves()` against the exact de Casteljau
/// split of the same control points (every `f64` is a dyadic rational), at
/// degrees 1 to 5 and magnitudes `1e-3` to `1e3`; and the splits do round, so
/// that a zero or negative allowance, or one not proportional to the
/// magnitude, is wrong.
#[test]
fn bezier_split_error_bounds_the_rounding_of_a_midpoint_split() {
    use num_traits::Signed;
    let to_q = |x: f64| f64_to_rational(x).expect("finite");
    let half = rat(1, 2);
    let mut rng = Lcg64::new(22);
    let mut rounded = 0;
    for degree in 1..=5usize {
        for scale in [1e-3, 1.0, 1e3] {
            for _ in 0..10 {
                let pts: Vec<[f64; 2]> = (0..=degree)
                    .map(|_| {
                        [
                            scale * (2.0 * rng.next_f64() - 1.0),
                            scale * (2.0 * rng.next_f64() - 1.0),
                        ]
                    })
                    .collect();
                let m = pts
                    .iter()
                    .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
                let c = BezierCurve::new(pts.clone());
                let bound = to_q(c.split_error(m));
                let (l, r) = c.halves();
                for d in 0..2 {
                    // exact de Casteljau at 1/2
                    let mut t: Vec<Rational> = pts.iter().map(|p| to_q(p[d])).collect();
                    let k = t.len();
                    let mut lo = Vec::with_capacity(k);
                    let mut hi = vec![Rational::from_integer(0.into()); k];
                    for level in 0..k {
                        lo.push(t[0].clone());
                        hi[k - 1 - level] = t[k - 1 - level].clone();
                        for i in 0..k - 1 - level {
                            t[i] = (&t[i] + &t[i + 1]) * &half;
                        }
                    }
                    for (computed, exact) in
                        l.points.iter().zip(&lo).chain(r.points.iter().zip(&hi))
                    {
                        let err = (to_q(computed[d]) - exact).abs();
                        assert!(
                            err <= bound,
                            "degree {degree}, scale {scale}: rounding {err} above the allowance"
                        );
                        if err > Rational::from_integer(0.into()) {
                            rounded += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(
        rounded > 0,
        "no split rounded: the test would not see a zero allowance"
    );
}

/// The data error of Bezier hull points is the caller's `eps` alone (their
/// control points are the data): the quadrant chain, whose end points lie at
/// distance 1 from the origin, is certified with `eps = 0.99` (after splits)
/// and undecided with `eps = 1`.
#[test]
fn a_bezier_chain_within_its_data_error_of_the_origin_is_undecided() {
    let chain: Vec<BezierCurve> = quadrant_polygons(1.0)
        .into_iter()
        .map(BezierCurve::new)
        .collect();
    assert_eq!(winding_number(&chain, 0.0), Some(1));
    assert_eq!(winding_number(&chain, 0.99), Some(1));
    assert_eq!(winding_number(&chain, 1.0), None);
}

/// The allowance of a piece at split depth `k` is `eps + hull_error + k *
/// split_error`, and a point's direction is widened by `asin(e / r)`. On the
/// quadrant chain (end points at distance 1, each arc a right angle) every
/// piece at depth 0, 1, 2 is certified iff the allowance is below about
/// 0.7071, 0.9487, 0.9899, and none at 1 or more. Hull error 0.75 and split
/// error 0.1 certify at depth 1 (0.75, then 0.85); hull error 0.75 and split
/// error 0.25 never do (0.75, 1.0, 1.25, ...); hull error 0.5 plus `eps = 0.2`
/// certifies at depth 0, plus `eps = 0.5` never. The same chain scaled by 2
/// with hull error 1 (relative 0.5) is certified: the widening at its end
/// points is `asin(1/2)`, not `asin(1)`.
#[test]
fn the_winding_allowance_grows_with_the_split_depth_and_is_relative_to_the_distance() {
    let unit = quadrant_polygons(1.0);
    assert_eq!(
        winding_number(&Declared::chain(&unit, 0.1, &[0.75; 4]), 0.0),
        Some(1)
    );
    assert_eq!(
        winding_number(&Declared::chain(&unit, 0.25, &[0.75; 4]), 0.0),
        None
    );
    assert_eq!(
        winding_number(&Declared::chain(&unit, 0.0, &[0.5; 4]), 0.2),
        Some(1)
    );
    assert_eq!(
        winding_number(&Declared::chain(&unit, 0.0, &[0.5; 4]), 0.5),
        None
    );
    let double = quadrant_polygons(2.0);
    assert_eq!(
        winding_number(&Declared::chain(&double, 0.0, &[0.5; 4]), 0.0),
        Some(1)
    );
}

/// Curves that do not join are bridged by the principal angle between the end
/// of one and the start of the next, both points uncertain by `eps`, the
/// larger hull error of the two curves, and the splits' rounding (`40` times
/// the largest split error). Three segments `(1,0)-(0,1)`, `(-1,0)-(0,-1)`,
/// `(0,-1)-(1,0)` leave one gap, a right angle from `(0,1)` to `(-1,0)`, next
/// to the curve with the larger hull error (0.2): with `eps = 0.1` the bridge's
/// allowance is `0.3 + 40 split`, certified (winding 1) for split `0.005` (0.5)
/// and not for `0.0125` (0.8; a right angle at distance 1 needs less than about 0.707).
#[test]
fn gaps_between_curves_are_bridged_with_the_larger_allowance_of_their_curves() {
    let segments = vec![
        vec![[1.0, 0.0], [0.0, 1.0]],
        vec![[-1.0, 0.0], [0.0, -1.0]],
        vec![[0.0, -1.0], [1.0, 0.0]],
    ];
    let hull = [0.0, 0.2, 0.0];
    assert_eq!(
        winding_number(&Declared::chain(&segments, 0.005, &hull), 0.1),
        Some(1)
    );
    assert_eq!(
        winding_number(&Declared::chain(&segments, 0.0125, &hull), 0.1),
        None
    );
}

/// A point that is not a number never certifies: the quadrant chain with one
/// NaN control point is undecided (its other hull points alone lie in a cone).
#[test]
fn a_nan_control_point_leaves_the_winding_number_undecided() {
    let mut polygons = quadrant_polygons(1.0);
    polygons[1][1] = [f64::NAN, 1.0];
    let chain: Vec<BezierCurve> = polygons.into_iter().map(BezierCurve::new).collect();
    assert_eq!(winding_number(&chain, 0.0), None);
}

/// A bridge (two points, never split) is certified only if its opening,
/// widened by the points' uncertainty, stays below `pi - ANGLE_MARGIN`. The
/// chain `(1,0)-(0,1)`, gap to `b = (-t, -1)` (just past `-pi/2`), `b-(1,0)`:
/// the gap turns by `pi - t` counter-clockwise (across the negative x-axis),
/// so that the total is one turn. Certified for `t = 2^-29` (about
/// `1.9 ANGLE_MARGIN`), undecided for `t = 2^-31` (about `0.47 ANGLE_MARGIN`);
/// the same for the mirror image (`y -> -y`), which turns clockwise: winding -1.
#[test]
fn a_gap_of_almost_half_a_turn_is_bridged_only_outside_the_angle_margin() {
    let chain = |t: f64, y: f64| {
        vec![
            BezierCurve::new(vec![[1.0, 0.0], [0.0, y]]),
            BezierCurve::new(vec![[-t, -y], [1.0, 0.0]]),
        ]
    };
    let wide = 2f64.powi(-29);
    let narrow = 2f64.powi(-31);
    assert!(wide > 1.5 * ANGLE_MARGIN && narrow < 0.5 * ANGLE_MARGIN);
    assert_eq!(winding_number(&chain(wide, 1.0), 0.0), Some(1));
    assert_eq!(winding_number(&chain(narrow, 1.0), 0.0), None);
    assert_eq!(winding_number(&chain(wide, -1.0), 0.0), Some(-1));
    assert_eq!(winding_number(&chain(narrow, -1.0), 0.0), None);
}

/// Every point's direction is widened by `asin(e / r)` plus `4 EPSILON` (the
/// rounding of `atan2` and of the difference of two angles), also where `e`
/// is only rounding. In the chain of the previous test (segments: no data or
/// hull error) the bridge's allowance is the splits' rounding alone, `e = 40
/// split_error`, so the gap is refused iff `t <= ANGLE_MARGIN + 2 (asin(e) +
/// 4 EPSILON)`; without the `4 EPSILON` the bound would be `8 EPSILON` (4 ulps
/// of the angle) lower. `t` halfway between the two is refused, `t` 3 ulps of
/// the angle above the bound is bridged.
#[test]
fn the_angle_rounding_allowance_widens_every_point() {
    let segment = BezierCurve::new(vec![[1.0, 0.0], [0.0, 1.0]]);
    let chain = |t: f64| {
        vec![
            segment.clone(),
            BezierCurve::new(vec![[-t, -1.0], [1.0, 0.0]]),
        ]
    };
    // the chain's magnitude is 1; every curve is of degree 1
    let e = MAX_SPLIT_DEPTH as f64 * segment.split_error(1.0);
    let bound = ANGLE_MARGIN + 2.0 * (e.asin() + 4.0 * f64::EPSILON);
    assert_eq!(
        winding_number(&chain(bound - 4.0 * f64::EPSILON), 0.0),
        None
    );
    assert_eq!(
        winding_number(&chain(bound + 6.0 * f64::EPSILON), 0.0),
        Some(1)
    );
}

/// Both halves of a split piece carry the allowance of their own depth. On
/// quarter arcs with control point `(1, 1/2)` (rotated by right angles) the
/// right half is the harder one: a whole arc is certified below an allowance
/// of 0.707, its left half below 0.894, its right half below 0.832 and the
/// right half's halves below 0.859 and 0.868. Hull error 0.75 with split
/// error 0.05 certifies both halves at depth 1 (0.80); with split error 0.12
/// the left half is certified at depth 1 (0.87) but the right half is not,
/// nor its halves at depth 2 (0.99): undecided.
#[test]
fn the_right_half_of_a_split_carries_the_allowance_of_its_depth() {
    let arc = [[1.0, 0.0], [1.0, 0.5], [0.0, 1.0]];
    let quarter_turns: Vec<Vec<[f64; 2]>> = (0..4)
        .map(|k| {
            arc.iter()
                .map(|&p| (0..k).fold(p, |[x, y], _| [-y, x]))
                .collect()
        })
        .collect();
    assert_eq!(
        winding_number(&Declared::chain(&quarter_turns, 0.05, &[0.75; 4]), 0.0),
        Some(1)
    );
    assert_eq!(
        winding_number(&Declared::chain(&quarter_turns, 0.12, &[0.75; 4]), 0.0),
        None
    );
}

// ---------------------------------------------------------------------------
// The Bezier Jacobian certificate on hand-made patches: they reach the bounds,
// boundaries and bookkeeping of `src/charmap/regularity.rs` that no ring test
// reaches (every ring is certified or refuted on its first pieces, far from
// the bounds; docs/testing.md has the mutation score).

/// A bicubic patch `x = 3 s` (control points `x_ij = i`), `y` with
/// `y_{i,j+1} - y_ij = d(i, j)`: `x_s = 3`, `x_t = 0`, `y_t` has the Bernstein
/// coefficients `3 d(i, j)` (bidegree (3, 2)), so the Jacobian is
/// `J(s, t) = 9 sum_ij B^3_i(s) B^2_j(t) d(i, j)` (integer data: exact corners).
fn patch_with_y_steps(d: impl Fn(usize, usize) -> f64) -> PlanarPatch {
    let mut y = [[0.0; 4]; 4];
    for (i, row) in y.iter_mut().enumerate() {
        for j in 0..3 {
            row[j + 1] = row[j] + d(i, j);
        }
    }
    PlanarPatch {
        x: TensorBezier::from_fn(3, 3, |i, _| i as f64),
        y: TensorBezier::from_fn(3, 3, |i, j| y[i][j]),
    }
}

/// The bilinear patch `x = a s`, `y = b t`: every Jacobian coefficient is `a b`.
fn bilinear(a: f64, b: f64) -> PlanarPatch {
    PlanarPatch {
        x: TensorBezier::from_fn(1, 1, |i, _| a * i as f64),
        y: TensorBezier::from_fn(1, 1, |_, j| b * j as f64),
    }
}

#[test]
fn gamma_is_highams_bound_for_k_roundings() {
    // gamma_k = k u / (1 - k u), u = 2^-53 the unit roundoff of f64 (math doc
    // section 7): strictly above k u, and exactly the formula's value.
    let u = 2f64.powi(-53);
    for k in 1..=64usize {
        let ku = k as f64 * u;
        assert_eq!(gamma(k), ku / (1.0 - ku), "k = {k}");
        assert!(gamma(k) > ku, "k = {k}");
    }
}

#[test]
fn the_coefficient_error_bound_is_the_documented_sum_of_data_and_rounding_terms() {
    // `ErrorModel`: 8 p delta md + 8 p^2 delta^2 + gamma_{8 + 2 p^2} 2 md^2 for a
    // coefficient, plus 2 d gamma_{2p - 1} cmax after d subdivision levels; a
    // directly evaluated value has the coefficient bound. Each term is isolated
    // once (delta = 0, md = 0) so that none hides behind a larger one.
    let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs();
    for p in [1usize, 2, 3] {
        let pf = p as f64;
        for (delta, md) in [(0.0, 3.0), (0.25, 0.0), (0.25, 3.0), (2f64.powi(-20), 5.0)] {
            let m = ErrorModel {
                delta,
                md,
                degree: p,
            };
            let want = 8.0 * pf * delta * md
                + 8.0 * pf * pf * delta * delta
                + gamma(8 + 2 * p * p) * 2.0 * md * md;
            assert!(close(m.coefficient_bound(), want), "{m:?}");
            assert!(close(m.evaluation_bound(), want), "{m:?}");
            for depth in [0u32, 1, 7] {
                for cmax in [1.0, 6.0] {
                    let sub = want + 2.0 * f64::from(depth) * gamma(2 * p - 1) * cmax;
                    assert!(close(m.subdivided_bound(depth, cmax), sub), "{m:?} {depth}");
                }
            }
        }
    }
}

#[test]
fn the_certificate_reports_its_minimum_relative_to_the_largest_coefficient() {
    // x = 2s (biquadratic), y_t = 1 except its corner coefficient (2, 1) = 1/2:
    // J = 2 y_t elevated to bidegree (3, 3), coefficients in [1, 2], the
    // smallest (1, exact: a corner) only at (s, t) = (1, 1), the largest 2.
    let x = TensorBezier::from_fn(2, 2, |i, _| i as f64);
    let y = TensorBezier::from_fn(2, 2, |i, j| {
        if (i, j) == (2, 2) {
            0.75
        } else {
            j as f64 / 2.0
        }
    });
    let patch = PlanarPatch { x, y };
    let jac = patch.jacobian();
    assert_eq!(jac.degree(), (3, 3));
    assert_eq!(jac.min_coeff(), (1.0, 3, 3));
    let cmax = jac.max_abs();
    assert!((cmax - 2.0).abs() < 1e-15, "{cmax}");
    let reg = check_bezier_patches(&[(4usize, &patch)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Regular, "{reg:?}");
    assert_eq!(reg.min_coeff, 1.0 / cmax, "{reg:?}");
    let loc = reg.min_location;
    assert_eq!((loc.patch, loc.s, loc.t), (4, 1.0, 1.0), "{reg:?}");
    // the error bound relative to the same scale: md = 2 (x_s), degree 2
    let model = ErrorModel {
        delta: 0.0,
        md: 2.0,
        degree: 2,
    };
    assert_eq!(reg.relative_error_bound, model.coefficient_bound() / cmax);
}

#[test]
fn ties_for_the_smallest_coefficient_report_the_first_in_patch_order() {
    // Two patches with the same constant Jacobian 6: every coefficient ties.
    // The reported location is the first (patch order, then s, then t), so
    // that the same input always gives the same report.
    let p = bilinear(2.0, 3.0);
    let reg = check_bezier_patches(&[(5usize, &p), (9usize, &p)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Regular);
    let loc = reg.min_location;
    assert_eq!((loc.patch, loc.s, loc.t), (5, 0.0, 0.0), "{reg:?}");
    assert_eq!(reg.min_coeff, 1.0);
}

#[test]
fn a_coefficient_equal_to_its_error_bound_certifies_nothing() {
    // x = s, y = beta t: every Jacobian coefficient is exactly beta, and with
    // exact data (delta = 0, md = 1, degree 1) the coefficient bound is
    // 2 gamma_10. At beta = that bound the true Jacobian may be 0: the piece is
    // not certified (and, the bound reaching every coefficient, not split);
    // at twice the bound it is.
    let bound = ErrorModel {
        delta: 0.0,
        md: 1.0,
        degree: 1,
    }
    .coefficient_bound();
    for (beta, verdict) in [
        (bound, RegularityVerdict::Indeterminate),
        (2.0 * bound, RegularityVerdict::Regular),
    ] {
        let patch = bilinear(1.0, beta);
        assert_eq!(patch.jacobian().coeffs(), &[beta; 4]);
        let reg = check_bezier_patches(&[(0usize, &patch)], 0.0).unwrap();
        assert_eq!(reg.verdict, verdict, "beta {beta:e}: {reg:?}");
        assert_eq!((reg.pieces, reg.max_depth), (1, 0), "{reg:?}");
        assert!(reg.witness.is_none());
    }
}

#[test]
fn a_value_equal_to_minus_the_evaluation_bound_is_not_a_witness() {
    // Patch 0 (J = 1) fixes the orientation and md = 1; patch 1 has the
    // constant Jacobian -beta. At beta = the evaluation bound its values may be
    // 0: no witness, indeterminate; at twice the bound, not regular, with the
    // witness at the first corner of patch 1 (its corner coefficients are now
    // below minus the bound).
    let bound = ErrorModel {
        delta: 0.0,
        md: 1.0,
        degree: 1,
    }
    .evaluation_bound();
    let one = bilinear(1.0, 1.0);
    for (beta, verdict) in [
        (bound, RegularityVerdict::Indeterminate),
        (2.0 * bound, RegularityVerdict::NotRegular),
    ] {
        let neg = bilinear(1.0, -beta);
        let reg = check_bezier_patches(&[(0usize, &one), (1usize, &neg)], 0.0).unwrap();
        assert_eq!(reg.verdict, verdict, "beta {beta:e}: {reg:?}");
        assert_eq!(reg.orientation, 1);
        if let Some((p, v)) = reg.witness {
            assert_eq!((p.patch, p.s, p.t), (1, 0.0, 0.0), "{reg:?}");
            assert_eq!(v, -beta);
        } else {
            assert_eq!(reg.undecided.map(|u| u.patch), Some(1), "{reg:?}");
        }
    }
}

#[test]
fn a_negative_jacobian_at_any_corner_is_reported_at_that_corner() {
    // y_t negative only at one corner coefficient of its (3, 2) net: J = -9 at
    // that corner of the domain (the corner coefficient is the exact value),
    // +9 at the other three, positive at the centre: the witness is that
    // corner, on the first piece, relative to max |c_ij|. The same with the
    // coordinates scaled by 2^20 (J by 2^40, exactly): a clearly negative
    // corner is evaluated whatever the magnitude of its coefficient.
    for (ci, cj, s, t) in [(3, 0, 1.0, 0.0), (0, 2, 0.0, 1.0), (3, 2, 1.0, 1.0)] {
        let unit = patch_with_y_steps(|i, j| if (i, j) == (ci, cj) { -1.0 } else { 1.0 });
        for scale in [1.0, 2f64.powi(20)] {
            let patch = PlanarPatch {
                x: TensorBezier::from_fn(3, 3, |i, j| scale * unit.x.coeff(i, j)),
                y: TensorBezier::from_fn(3, 3, |i, j| scale * unit.y.coeff(i, j)),
            };
            let corner = -9.0 * scale * scale;
            assert_eq!(patch.jacobian_at(s, t), corner);
            assert!(patch.jacobian_at(0.5, 0.5) > 0.0);
            let reg = check_bezier_patches(&[(3usize, &patch)], 0.0).unwrap();
            assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
            let (p, v) = reg.witness.unwrap();
            assert_eq!((p.patch, p.s, p.t), (3, s, t), "{reg:?}");
            assert_eq!(v, corner / patch.jacobian().max_abs(), "{reg:?}");
            assert_eq!((reg.pieces, reg.max_depth), (1, 0), "{reg:?}");
        }
    }
}

#[test]
fn a_jacobian_negative_only_inside_is_witnessed_at_the_centre_of_its_piece() {
    // d(1, 1) = d(2, 1) = -3, else 1: J = 9 at the four corners (so no corner
    // is a witness) and J(1/2, 1/2) = 9 (1 - 4 * 3/8) = -4.5 at the centre of
    // the patch: the witness of the first piece.
    let patch = patch_with_y_steps(|i, j| {
        if j == 1 && (i == 1 || i == 2) {
            -3.0
        } else {
            1.0
        }
    });
    for (s, t) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        assert_eq!(patch.jacobian_at(s, t), 9.0);
    }
    assert_eq!(patch.jacobian_at(0.5, 0.5), -4.5);
    let reg = check_bezier_patches(&[(2usize, &patch)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
    let (p, v) = reg.witness.unwrap();
    assert_eq!((p.patch, p.s, p.t), (2, 0.5, 0.5), "{reg:?}");
    assert_eq!((reg.pieces, reg.max_depth), (1, 0), "{reg:?}");
    assert_eq!(v, -4.5 / patch.jacobian().max_abs());
    // after one split: u = (1, 5, -3, 1) in s, constant in t. U(s) = sum
    // B^3_i(s) u_i is 1 at s = 0, 1/2, 1 and -1/8 at s = 3/4: J = 9 U > 0 at
    // every corner of the patch and of the quarter [1/2, 1]^2, and at the
    // patch centre; the quarter (the first piece examined after the split) has
    // its centre (3/4, 3/4) as the witness.
    let u = [1.0, 5.0, -3.0, 1.0];
    let patch = patch_with_y_steps(|i, _| u[i]);
    assert_eq!(patch.jacobian_at(0.75, 0.75), -1.125);
    let reg = check_bezier_patches(&[(0usize, &patch)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
    let (p, _) = reg.witness.unwrap();
    assert_eq!((p.s, p.t), (0.75, 0.75), "{reg:?}");
    assert_eq!((reg.pieces, reg.max_depth), (2, 1), "{reg:?}");
    // a witness in the second piece examined after the split: d(i, 0) = 12 u_i,
    // d(i, 1) = d(i, 2) = 1, so J = 9 (12 U(s) (1 - t)^2 + 1 - (1 - t)^2).
    // J > 2.5 on the quarter [1/2, 1]^2 (examined first: no witness there,
    // certified after splitting), J > 0 at every corner of the quarter
    // [1/2, 1] x [0, 1/2] (examined next) and J(3/4, 1/4) = -3.65625 at its centre.
    let patch = patch_with_y_steps(|i, j| if j == 0 { 12.0 * u[i] } else { 1.0 });
    assert_eq!(patch.jacobian_at(0.75, 0.25), -3.65625);
    for (s, t) in [(0.5, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 0.5)] {
        assert!(patch.jacobian_at(s, t) > 30.0, "({s}, {t})");
    }
    let reg = check_bezier_patches(&[(0usize, &patch)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
    let (p, _) = reg.witness.unwrap();
    assert_eq!((p.s, p.t), (0.75, 0.25), "{reg:?}");
}

#[test]
fn all_zero_or_infinite_coefficients_are_indeterminate_at_once() {
    // A constant x gives J = 0 everywhere; coordinates of 1e300 overflow J to
    // infinity. Nothing can be certified: indeterminate before any piece is
    // examined, the undecided point the minimum's location, finite relative
    // numbers for the zero Jacobian (the scale 0 is replaced by 1).
    let flat = PlanarPatch {
        x: TensorBezier::from_fn(1, 1, |_, _| 1.0),
        y: TensorBezier::from_fn(1, 1, |_, j| j as f64),
    };
    let reg = check_bezier_patches(&[(6usize, &flat)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Indeterminate, "{reg:?}");
    assert_eq!(reg.pieces, 0, "{reg:?}");
    assert_eq!(reg.undecided, Some(reg.min_location));
    assert_eq!(reg.min_coeff, 0.0);
    assert!(reg.relative_error_bound.is_finite() && reg.relative_error_bound > 0.0);
    let huge = bilinear(1e300, 1e300);
    assert_eq!(huge.jacobian().max_abs(), f64::INFINITY);
    let reg = check_bezier_patches(&[(6usize, &huge)], 0.0).unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::Indeterminate, "{reg:?}");
    assert_eq!(reg.pieces, 0, "{reg:?}");
    assert!(reg.undecided.is_some() && reg.witness.is_none());
}

#[test]
fn the_orientation_is_the_sign_of_the_signed_area() {
    // The signed area is the sum of the patches' coefficient means. A single
    // mirrored patch (J = -4 everywhere, coefficient sum -16, a multiple of
    // the coefficient count) is regular with orientation -1; two patches of
    // opposite Jacobians (area exactly 0) take orientation +1 and refute it on
    // the negative patch.
    let reg = check_bezier_patches(&[(0usize, &bilinear(2.0, -2.0))], 0.0).unwrap();
    assert_eq!(
        (reg.verdict, reg.orientation),
        (RegularityVerdict::Regular, -1),
        "{reg:?}"
    );
    let (pos, neg) = (bilinear(1.0, 1.0), bilinear(1.0, -1.0));
    for (a, b) in [(0usize, 1usize), (1, 0)] {
        let patches = [
            (a, if a == 0 { &pos } else { &neg }),
            (b, if b == 0 { &pos } else { &neg }),
        ];
        let reg = check_bezier_patches(&patches, 0.0).unwrap();
        assert_eq!(reg.orientation, 1, "{reg:?}");
        assert_eq!(reg.verdict, RegularityVerdict::NotRegular, "{reg:?}");
        assert_eq!(reg.witness.unwrap().0.patch, 1, "{reg:?}");
    }
}

#[test]
fn the_piece_limit_is_exact_and_the_search_splits_only_along_the_zero_line() {
    // J = 3 (t - 1/2)^2 (as in the touching test): only the pieces that meet
    // the line t = 1/2 are undecided and split, 2^(d+1) of them at depth
    // d >= 1 (one at depth 0), down to MAX_DEPTH. Examined: 1 + 4 +
    // sum_{d=2}^{10} 4 * 2^d = 8181 pieces for one patch, and the undecided
    // piece is one of the depth-limit pieces on the line, inside the domain.
    let x = TensorBezier::from_fn(3, 3, |a, _| a as f64 / 3.0);
    let yc = [-0.125, 0.125, -0.125, 0.125];
    let patch = PlanarPatch {
        x,
        y: TensorBezier::from_fn(3, 3, |_, b| yc[b]),
    };
    let reg = check_bezier_patches(&[(0usize, &patch)], 0.0).unwrap();
    let want: usize = 5 + (2..=MAX_DEPTH).map(|d| 4usize << d).sum::<usize>();
    assert_eq!(want, 8181);
    assert_eq!(reg.pieces, want, "{reg:?}");
    assert_eq!(reg.max_depth, MAX_DEPTH);
    let at = reg.undecided.unwrap();
    let side = 2f64.powi(-(MAX_DEPTH as i32));
    assert!(
        (0.0..1.0).contains(&at.s) && (at.s / side).fract() == 0.0,
        "{at:?}"
    );
    assert!(at.t == 0.5 || at.t == 0.5 - side, "{at:?}");
    // four such patches would need 4 * 8181 pieces: the search stops at
    // exactly MAX_PIECES (4 + 4k pieces, the largest such count within the
    // limit), still indeterminate and without a witness
    let four: Vec<(usize, &PlanarPatch)> = (0..4).map(|k| (k, &patch)).collect();
    let reg = check_bezier_patches(&four, 0.0).unwrap();
    assert_eq!(MAX_PIECES % 4, 0);
    assert_eq!(reg.pieces, MAX_PIECES, "{:?}", (reg.verdict, reg.max_depth));
    assert_eq!(reg.verdict, RegularityVerdict::Indeterminate);
    assert!(reg.witness.is_none());
}

#[test]
fn verdict_and_coefficient_names_are_the_documented_words() {
    // The text and CSV outputs spell a verdict with `as_str`, the JSON output
    // with serde: both must give the same word. `describe` names what a
    // certificate's `min_coeff` is in the text output.
    for (v, word) in [
        (RegularityVerdict::Regular, "regular"),
        (RegularityVerdict::NotRegular, "not_regular"),
        (RegularityVerdict::Indeterminate, "indeterminate"),
    ] {
        assert_eq!(v.as_str(), word);
        assert_eq!(serde_json::to_string(&v).unwrap(), format!("\"{word}\""));
    }
    assert_eq!(
        Coefficients::BezierJacobian.describe(),
        "Bezier coefficient"
    );
    assert_eq!(
        Coefficients::DerivativeCones.describe(),
        "derivative-cone determinant"
    );
    let reg = check_bezier_patches(&[(0usize, &bilinear(1.0, 1.0))], 0.0).unwrap();
    assert_eq!(reg.coefficients, Coefficients::BezierJacobian);
}
