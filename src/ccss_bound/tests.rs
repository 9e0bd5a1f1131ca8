use super::bound::bound;
use super::differences::{default_family, Difference, DifferenceFamily};
use super::lp::{dual_objective, l1_representation, residual};
use super::patch::{bspline_basis, ExtraordinaryPatch, SubDomain};
use super::steps::{contraction, steps_a_priori, steps_needed};
use crate::schemes::catmull_clark::SubPatch;
use proptest::prelude::*;

/// LP duality gap accepted between microlp's primal and dual optima (both
/// solved to microlp's 1e-9 feasibility tolerance on O(1) data).
const DUALITY_TOL: f64 = 1e-7;

#[test]
fn default_family_is_valid_and_sized() {
    for n in 3..=12 {
        let f = default_family(n).unwrap();
        assert_eq!(f.len(), 2 * n + 10);
        f.validate().unwrap();
    }
}

#[test]
fn validator_rejects_bad_differences() {
    let n = 5;
    let good = default_family(n).unwrap();
    let mut ds = good.differences().to_vec();
    // Not summing to zero.
    ds[0].terms[0].1 = 2;
    assert!(DifferenceFamily::new(n, ds).is_err());
    // e_0 - 2v + e_3 is not straight through v at n = 6 (three edges apart on both sides).
    let lay6 = crate::schemes::catmull_clark::PatchLayout::new(6).unwrap();
    let bent = Difference {
        name: "bent".into(),
        terms: vec![
            (lay6.e(0), 1, (-1, 0)),
            (lay6.v(), -2, (0, 0)),
            (lay6.e(3), 1, (1, 0)),
        ],
    };
    assert!(DifferenceFamily::new(6, vec![bent.clone()]).is_err());
    // ... but e_0 - 2v + e_2 is (one edge, v-e_1, between them).
    let mut straight = bent;
    straight.terms[2].0 = lay6.e(2);
    assert!(DifferenceFamily::new(6, vec![straight]).is_ok());
    let lay = crate::schemes::catmull_clark::PatchLayout::new(n).unwrap();
    // Chart neighbours that are not mesh edges.
    let far = Difference {
        name: "far".into(),
        terms: vec![
            (lay.f(3), 1, (-1, 0)),
            (lay.v(), -2, (0, 0)),
            (lay.e(1), 1, (1, 0)),
        ],
    };
    assert!(DifferenceFamily::new(n, vec![far]).is_err());
    // A mixed difference on a quad is fine.
    let mixed = Difference {
        name: "mixed".into(),
        terms: vec![
            (lay.v(), 1, (0, 0)),
            (lay.e(0), -1, (1, 0)),
            (lay.f(0), 1, (1, 1)),
            (lay.e(1), -1, (0, 1)),
        ],
    };
    assert!(DifferenceFamily::new(n, vec![mixed]).is_ok());
}

/// n = 4 contains both grid lines through the extraordinary vertex.
#[test]
fn n4_family_contains_the_lines_through_v() {
    let f = default_family(4).unwrap();
    let lay = crate::schemes::catmull_clark::PatchLayout::new(4).unwrap();
    let has = |a: usize, b: usize| {
        f.differences().iter().any(|d| {
            let v = d.to_vector(16);
            v[lay.v()] == -2.0 && v[a] == 1.0 && v[b] == 1.0
        })
    };
    assert!(has(lay.e(0), lay.e(2)) && has(lay.e(1), lay.e(3)));
}

#[test]
fn n4_reproduces_d_equals_one_minus_t_squared_over_four() {
    let r = bound(4, 2).unwrap();
    let b12 = r.omega_1_2().unwrap();
    for k in 0..=100 {
        let t = k as f64 / 100.0;
        let d = b12.eval(t, t);
        assert!((d - (1.0 - t * t) / 4.0).abs() < 1e-12, "t = {t}: {d}");
    }
    assert!((r.beta - 0.25).abs() < 1e-12);
    assert!((r.full_max - 0.25).abs() < 1e-12);
}

#[test]
fn lp_residual_and_duality() {
    // n = 8: the family has a 3-dimensional extra left kernel (n divisible by 4).
    for n in [3usize, 5, 8] {
        let patch = ExtraordinaryPatch::new(n).unwrap();
        let family = default_family(n).unwrap();
        let alphas = family.matrix();
        for d in [
            SubDomain {
                level: 1,
                part: SubPatch::Two,
            },
            SubDomain {
                level: 2,
                part: SubPatch::One,
            },
        ] {
            let diff = patch.bezier_net(d) - patch.limit_face_bezier(d).unwrap();
            for row in 0..16 {
                let target: Vec<f64> = diff.row(row).iter().copied().collect();
                let sol = l1_representation(&alphas, &target, "test").unwrap();
                assert!(sol.residual < 1e-12, "n = {n}: residual {:e}", sol.residual);
                assert_eq!(sol.residual, residual(&alphas, &target, &sol.x));
                let dual = dual_objective(&alphas, &target, "test dual").unwrap();
                assert!(
                    (dual - sol.objective).abs() < DUALITY_TOL,
                    "n = {n}, {d:?}, row {row}: primal {} dual {dual}",
                    sol.objective
                );
            }
        }
    }
}

/// beta(n) strictly decreasing on 3..=10 (the full 3..=48 check takes ~25 s:
/// `subdiv-lab ccss-bound --table-to 50`, see the report).
#[test]
fn beta_decreasing_small_valences() {
    let rows = super::bound::beta_table(3..=10, 2).unwrap();
    for w in rows.windows(2) {
        assert!(
            w[1].beta < w[0].beta,
            "beta({}) = {} >= beta({}) = {}",
            w[1].n,
            w[1].beta,
            w[0].n,
            w[0].beta
        );
    }
    let mut csv = Vec::new();
    super::bound::write_beta_csv(&rows, &mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    assert!(text.starts_with("n,beta,t_max,level,full_max\n3,0.258"));
    assert_eq!(text.lines().count(), 9);
}

#[test]
fn published_facts_small_valences() {
    let b3 = bound(3, 3).unwrap();
    let b4 = bound(4, 3).unwrap();
    let b5 = bound(5, 3).unwrap();
    let b6 = bound(6, 3).unwrap();
    assert!(b3.beta > 0.25, "beta(3) = {}", b3.beta);
    // n = 3: maximum in [1/4, 1/2]; n >= 4: in [1/2, 1].
    assert!((0.25..=0.5).contains(&b3.t_max));
    assert!(b5.t_max >= 0.5 && b6.t_max >= 0.5);
    assert!(b5.beta < b4.beta && b6.beta < b5.beta && b4.beta < b3.beta);
    for r in [&b3, &b4, &b5, &b6] {
        assert!(r.max_asymmetry < 1e-12 && r.mirror_defect < 1e-12);
        // The maximum of B lies on the diagonal (the paper's symmetry claim).
        assert!((r.full_max - r.beta).abs() < 1e-9, "n = {}", r.valence);
    }
}

/// Exact evaluation of the patch by subdivision: `(u, v)` in `Omega^k_m`.
fn evaluate(patch: &ExtraordinaryPatch, net: &[Vec<f64>], u: f64, v: f64) -> Vec<f64> {
    let d = SubDomain::containing(u, v).unwrap();
    let forms = patch.bspline_net(d);
    let ((u0, u1), (v0, v1)) = d.bounds();
    let (bu, bv) = (
        bspline_basis((u - u0) / (u1 - u0)),
        bspline_basis((v - v0) / (v1 - v0)),
    );
    let dim = net[0].len();
    let mut out = vec![0.0; dim];
    for i in 0..4 {
        for j in 0..4 {
            let w = bu[i] * bv[j];
            for (p, x) in net.iter().enumerate() {
                let f = w * forms[(4 * i + j, p)];
                for k in 0..dim {
                    out[k] += f * x[k];
                }
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Random control nets: the true distance |S - F| (dense sampling, exact
    /// evaluation via subdivision) never exceeds B(u, v) M, hence beta M.
    #[test]
    fn random_nets_respect_the_bound(n in prop::sample::select(vec![3usize, 5, 6]), seed in 0u64..1000) {
        let patch = ExtraordinaryPatch::new(n).unwrap();
        let family = default_family(n).unwrap();
        let report = bound(n, 3).unwrap();
        // The first state is one LCG step from the seed.
        let mut lcg = crate::rng::Lcg64::new(seed);
        lcg.next_u64();
        let mut rnd = || lcg.next_f64() * 2.0 - 1.0;
        let net: Vec<Vec<f64>> = (0..patch.len()).map(|_| vec![rnd(), rnd(), rnd()]).collect();
        let m = family.max_norm(&net).unwrap();
        let corners = patch.corner_limits().unwrap();
        let samples = 40;
        for a in 0..=samples {
            for b in 0..=samples {
                let (u, v) = (a as f64 / samples as f64, b as f64 / samples as f64);
                if u.max(v) < 0.125 { continue; } // levels 1..3 examined
                let s = evaluate(&patch, &net, u, v);
                let fform = patch.limit_face_at(&corners, u, v);
                let dist: f64 = (0..3).map(|k| {
                    let f: f64 = fform.iter().zip(&net).map(|(w, p)| w * p[k]).sum();
                    (s[k] - f).powi(2)
                }).sum::<f64>().sqrt();
                let d = SubDomain::containing(u, v).unwrap();
                let sb = report.sub_patches.iter().find(|x| x.domain == d).unwrap();
                let ((u0, u1), (v0, v1)) = d.bounds();
                let bound_here = sb.eval((u - u0) / (u1 - u0), (v - v0) / (v1 - v0)) * m;
                prop_assert!(dist <= bound_here + 1e-12, "n = {}, ({}, {}): {} > {}", n, u, v, dist, bound_here);
                prop_assert!(dist <= report.full_max * m + 1e-12);
            }
        }
    }
}

#[test]
fn contraction_at_the_extraordinary_vertex() {
    // n = 4: the regular factor 1/4.
    let c4 = contraction(4, 2).unwrap();
    assert!((c4.r_ev - 0.25).abs() < 1e-9, "r_ev(4) = {}", c4.r_ev);
    for n in [3usize, 5, 6] {
        let c = contraction(n, 2).unwrap();
        let lambda = crate::schemes::catmull_clark::fourier::subdominant(n, 0.5).unwrap();
        // Derived: the spoke differences see the subdominant eigenvectors, so r_ev >= lambda_1 > 1/4.
        assert!(
            c.r_ev >= lambda - 1e-9,
            "n = {n}: r_ev {} < lambda {lambda}",
            c.r_ev
        );
        assert!(c.rho < 1.0);
    }
}

#[test]
fn steps_needed_bounds_the_refined_distance() {
    let n = 5;
    let c = contraction(n, 3).unwrap();
    let patch = ExtraordinaryPatch::new(n).unwrap();
    let family = default_family(n).unwrap();
    let net: Vec<Vec<f64>> = (0..patch.len())
        .map(|k| {
            vec![
                (k as f64 * 0.37).sin(),
                (k as f64 * 0.11).cos(),
                (k * k % 7) as f64 / 7.0,
            ]
        })
        .collect();
    let eps = 1e-3;
    let (k, m0) = steps_a_priori(&c, &net, eps).unwrap();
    assert!(k > 0 && m0 > 0.0);
    // M_k of the level-k extraordinary patch obeys M_k <= r_ev^k M_0.
    let mut cur = net.clone();
    for level in 1..=k {
        let a = patch.patch_matrix();
        cur = (0..patch.len())
            .map(|i| {
                (0..3)
                    .map(|d| (0..patch.len()).map(|j| a[(i, j)] * cur[j][d]).sum())
                    .collect()
            })
            .collect();
        let mk = family.max_norm(&cur).unwrap();
        assert!(mk <= c.r_ev.powi(level as i32) * m0 * (1.0 + 1e-12) + 1e-15);
    }
    // One step fewer is not enough according to the bound.
    assert!(c.constant * c.rho.powi(k as i32 - 1) * m0 > eps);
    assert!(c.constant * c.rho.powi(k as i32) * m0 <= eps);
    assert!(steps_a_priori(&c, &net, 0.0).is_err());
    assert!(steps_a_priori(&c, &net[1..], 1e-3).is_err());
    // The data-driven count never exceeds the a-priori one and meets epsilon.
    let data = steps_needed(&patch, &family, c.beta, &net, eps).unwrap();
    assert!(data.steps <= k && data.bound <= eps);
    assert_eq!(data.m_ev.len(), data.steps as usize + 1);
    assert!(steps_needed(&patch, &family, c.beta, &net, f64::NAN).is_err());
}

/// The step counts are homogeneous in the net, so a net scaled by 2^k (here
/// up to coordinates near 1e300, whose squared differences overflow) gives
/// the same steps and bounds scaled by 2^k; a tolerance below the f64
/// resolution of the net is refused by name (instead of running MAX_STEPS
/// steps into a failing LP); `steps_a_priori` terminates on an infinite M_0.
#[test]
fn step_counts_are_scale_invariant_and_refuse_unresolvable_tolerances() {
    let n = 5;
    let c = contraction(n, 3).unwrap();
    let patch = ExtraordinaryPatch::new(n).unwrap();
    let family = default_family(n).unwrap();
    let net: Vec<Vec<f64>> = (0..patch.len())
        .map(|k| vec![(k as f64).cos(), (k as f64).sin(), 0.1 * k as f64])
        .collect();
    let eps = 1e-3;
    let base = steps_needed(&patch, &family, c.beta, &net, eps).unwrap();
    let (k0, m0) = steps_a_priori(&c, &net, eps).unwrap();
    for k in [-1000, -300, 300, 996] {
        let f = 2f64.powi(k / 2) * 2f64.powi(k - k / 2);
        let big: Vec<Vec<f64>> = net
            .iter()
            .map(|p| p.iter().map(|x| x * f).collect())
            .collect();
        let r = steps_needed(&patch, &family, c.beta, &big, eps * f).unwrap();
        assert_eq!(r.steps, base.steps, "2^{k}");
        assert_eq!(r.bound, base.bound * f, "2^{k}");
        let (ka, ma) = steps_a_priori(&c, &big, eps * f).unwrap();
        assert_eq!(ka, k0, "2^{k}");
        assert_eq!(ma, m0 * f, "2^{k}");
    }
    let e = steps_needed(&patch, &family, c.beta, &net, 1e-300).unwrap_err();
    assert!(e.to_string().contains("below what f64 resolves"), "{e}");
    assert!(
        matches!(e, super::CcssBoundError::ToleranceBelowResolution { .. }),
        "{e}"
    );
}

/// Derived: at the extraordinary vertex M shrinks by lambda_1 per step on
/// subdominant eigenvector data (not by 4); at n = 4 by exactly 4 on generic data.
#[test]
fn m_at_the_extraordinary_vertex_decays_like_lambda() {
    use nalgebra::{DMatrix, DVector};
    for n in [3usize, 5, 7] {
        let patch = ExtraordinaryPatch::new(n).unwrap();
        let family = default_family(n).unwrap();
        let lam = crate::schemes::catmull_clark::fourier::subdominant(n, 0.5).unwrap();
        // Eigenvector of A for lambda_1 (real cosine mode of Fourier block l = 1):
        // v = 0, e_i = cos(i theta), f_i = (cos(i theta) + cos((i+1) theta)) / (4 lambda - 1);
        // the 7 outer entries solve (A_oo - lambda I) x_o = -A_or x_r.
        let lay = patch.layout();
        let len = patch.len();
        let theta = 2.0 * std::f64::consts::PI / n as f64;
        let mut x = DVector::zeros(len);
        for i in 0..n {
            let ci = (i as f64 * theta).cos();
            x[lay.e(i)] = ci;
            x[lay.f(i)] = (ci + ((i + 1) as f64 * theta).cos()) / (4.0 * lam - 1.0);
        }
        let a = patch.patch_matrix();
        let r = 2 * n + 1;
        let a_oo = a.view((r, r), (7, 7)).into_owned() - DMatrix::identity(7, 7) * lam;
        let rhs = -(a.view((r, 0), (7, r)) * x.rows(0, r));
        let xo = crate::schemes::catmull_clark::limit::solve_linear(a_oo, rhs).unwrap();
        x.rows_mut(r, 7).copy_from(&xo);
        let ax = patch.patch_matrix() * &x;
        let defect = (&ax - &x * lam).amax();
        assert!(defect < 1e-10, "n = {n}: not an eigenvector ({defect:e})");
        let net0: Vec<Vec<f64>> = x.iter().map(|v| vec![*v]).collect();
        let net1: Vec<Vec<f64>> = ax.iter().map(|v| vec![*v]).collect();
        let (m0, m1) = (
            family.max_norm(&net0).unwrap(),
            family.max_norm(&net1).unwrap(),
        );
        assert!(m0 > 1e-3);
        assert!(
            (m1 / m0 - lam).abs() < 1e-10,
            "n = {n}: ratio {} vs lambda {lam}",
            m1 / m0
        );
        assert!(m1 / m0 > 0.25 + 0.1);
    }
}

/// The sub-patch nets fit together (continuity across sub-patch and level
/// boundaries) and converge to the limit point at the extraordinary corner:
/// an independent check of the level structure `Pick_m A-bar A^{k-1}` for n != 4.
#[test]
fn sub_patches_join_continuously_and_converge_to_the_limit_point() {
    for n in [3usize, 5, 7] {
        let patch = ExtraordinaryPatch::new(n).unwrap();
        let net: Vec<Vec<f64>> = (0..patch.len())
            .map(|k| vec![((k * 37) % 11) as f64 / 11.0 - 0.5])
            .collect();
        let at = |d: SubDomain, s: f64, t: f64| -> f64 {
            let forms = patch.bspline_net(d);
            let (bu, bv) = (bspline_basis(s), bspline_basis(t));
            let mut acc = 0.0;
            for i in 0..4 {
                for j in 0..4 {
                    for (p, x) in net.iter().enumerate() {
                        acc += bu[i] * bv[j] * forms[(4 * i + j, p)] * x[0];
                    }
                }
            }
            acc
        };
        let sd = |level, part| SubDomain { level, part };
        for k in 1..=3 {
            for s in [0.0, 0.3, 0.7, 1.0] {
                let a = at(sd(k, SubPatch::One), s, 1.0);
                let b = at(sd(k, SubPatch::Two), s, 0.0);
                assert!((a - b).abs() < 1e-13, "n = {n}, k = {k}: 1|2 {a} vs {b}");
                let a = at(sd(k, SubPatch::Three), 1.0, s);
                let b = at(sd(k, SubPatch::Two), 0.0, s);
                assert!((a - b).abs() < 1e-13, "n = {n}, k = {k}: 3|2 {a} vs {b}");
                // Level k+1's Omega_2 top edge lies on level k's Omega_3 bottom edge.
                let a = at(sd(k + 1, SubPatch::Two), s, 1.0);
                let b = at(sd(k, SubPatch::Three), 0.5 + 0.5 * s, 0.0);
                assert!((a - b).abs() < 1e-13, "n = {n}, k = {k}: levels {a} vs {b}");
            }
        }
        let limit: f64 = patch.corner_limits().unwrap()[0]
            .iter()
            .zip(&net)
            .map(|(w, p)| w * p[0])
            .sum();
        let near = at(sd(30, SubPatch::Two), 0.0, 0.0);
        assert!(
            (near - limit).abs() < 1e-6,
            "n = {n}: {near} vs limit {limit}"
        );
    }
}

/// The published "strictly decreasing for 3 <= n <= 48" ends exactly where our
/// family's sequence first rises: beta(49) > beta(48). (For n >= 5 the maximum
/// lies on Omega^1_2, so one level suffices here; the full table with 4 levels
/// is in the report.)
#[test]
fn beta_stops_decreasing_after_48() {
    let rows = super::bound::beta_table([46usize, 47, 48, 49], 1).unwrap();
    let b: Vec<f64> = rows.iter().map(|r| r.beta).collect();
    assert!(b[0] > b[1] && b[1] > b[2], "{b:?}");
    assert!(b[3] > b[2], "{b:?}");
    assert!(rows.iter().all(|r| r.t_max > 0.5 && r.level == 1));
}

#[test]
fn diagonal_csv_for_figures() {
    let r = bound(4, 2).unwrap();
    let mut out = Vec::new();
    super::bound::write_diagonal_csv(std::slice::from_ref(&r), 8, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "n,t,d");
    // t = 0 (D = 0), then t = 2/8.. 8/8 (t = 1/8 lies below the two examined levels).
    assert_eq!(lines.len(), 1 + 1 + 7);
    // n = 4: D(3/4) on Omega^1_2 is (1 - (1/2)^2)/4 = 3/16 at local t = 1/2.
    let row: Vec<&str> = lines
        .iter()
        .find(|l| l.starts_with("4,0.75,"))
        .unwrap()
        .split(',')
        .collect();
    assert!((row[2].parse::<f64>().unwrap() - 0.1875).abs() < 1e-12);
    assert!(lines[1].ends_with(",0"));
}
