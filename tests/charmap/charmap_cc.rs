//! Characteristic maps of the Catmull-Clark family (math doc sections 7 and
//! 8).

use proptest::prelude::*;
use subdiv_lab::cc_study::{c1_intervals, study_point};
use subdiv_lab::charmap::catmull_clark::{
    check, check_bicubic, check_ring, prepare_ring, CcRing, Certificate,
};
use subdiv_lab::charmap::regularity::RegularityVerdict;
use subdiv_lab::charmap::winding::winding_number;
use subdiv_lab::charmap::Verdict;
use subdiv_lab::schemes::catmull_clark::ring::{UnivariateRule, Window};
use subdiv_lab::schemes::catmull_clark::{fourier, patch_matrix};

use crate::common;

#[test]
fn catmull_clark_charmap_is_regular_and_injective_for_n_3_to_32_by_both_certificates() {
    // A long-known result (Peters and Reif 1998): a failure here is a bug.
    for n in 3..=32 {
        let bez = check_bicubic(n).unwrap();
        assert_eq!(
            bez.verdict,
            Verdict::C1Standard,
            "bicubic, n = {n}: {bez:?}"
        );
        assert_eq!(
            (bez.winding_number, bez.inner_winding_number),
            (Some(1), Some(1))
        );
        let cone = check(n, 0.5).unwrap();
        assert_eq!(cone.verdict, Verdict::C1Standard, "cone, n = {n}: {cone:?}");
        assert_eq!(cone.inner_winding_number, Some(1));
        // same orientation from both certificates
        assert_eq!(
            bez.regularity.unwrap().orientation,
            cone.regularity.unwrap().orientation
        );
    }
}

#[test]
fn the_bezier_jacobian_of_the_bicubic_ring_has_bidegree_5() {
    let prep = prepare_ring(5, 0.5, 1, 0.1).unwrap();
    let patches = prep.ring.bicubic_patches().unwrap();
    assert_eq!(patches.len(), 15);
    for (_, p) in &patches {
        assert_eq!(p.jacobian().degree(), (5, 5));
    }
    // only Catmull-Clark proper has polynomial cells
    let other = prepare_ring(5, 0.3, 1, 0.1).unwrap();
    assert!(other.ring.bicubic_patches().is_none());
}

#[test]
fn fourier_mode_vectors_are_eigenvectors_of_the_patch_matrix() {
    for n in [3, 4, 5, 7, 12, 24] {
        for c in [0.1, 0.5, 1.0] {
            let a = patch_matrix::<f64>(n, &c).unwrap().into_matrix();
            for l in (1..n).filter(|l| 2 * l != n).take(3) {
                let (lambda, xs) = fourier::mode_patch_eigenvectors(n, c, l).unwrap();
                for x in &xs {
                    let r = (&a * x - x * lambda).amax();
                    assert!(r < 1e-13 * x.amax(), "n = {n}, c = {c}, l = {l}: {r:e}");
                }
            }
        }
    }
}

/// Limit points of a window's 4 x 4 vertices after `levels` refinements of
/// the rule, computed here independently of the library (tensor refinement
/// plus the limit stencil), and the finite-difference Jacobians at every
/// interior vertex.
fn sampled_jacobians(c: f64, w: &Window, levels: usize) -> Vec<f64> {
    let n0 = 4;
    let mut grid: Vec<Vec<[f64; 2]>> = (0..n0).map(|a| w[a].to_vec()).collect();
    let refine = |pts: &[[f64; 2]]| -> Vec<[f64; 2]> {
        // all edge points, and the vertex points of interior vertices
        let m = pts.len();
        let mut out = Vec::new();
        for i in 0..m - 1 {
            out.push([
                0.5 * (pts[i][0] + pts[i + 1][0]),
                0.5 * (pts[i][1] + pts[i + 1][1]),
            ]);
            if i + 2 < m {
                let (a, b, d) = (pts[i], pts[i + 1], pts[i + 2]);
                out.push([
                    c / 4.0 * a[0] + (1.0 - c / 2.0) * b[0] + c / 4.0 * d[0],
                    c / 4.0 * a[1] + (1.0 - c / 2.0) * b[1] + c / 4.0 * d[1],
                ]);
            }
        }
        out
    };
    for _ in 0..levels {
        let rows: Vec<Vec<[f64; 2]>> = grid.iter().map(|r| refine(r)).collect();
        let m = rows[0].len();
        let cols: Vec<Vec<[f64; 2]>> = (0..m)
            .map(|b| refine(&rows.iter().map(|r| r[b]).collect::<Vec<_>>()))
            .collect();
        grid = (0..cols[0].len())
            .map(|a| cols.iter().map(|col| col[a]).collect())
            .collect();
    }
    let (al, be) = (c / (2.0 * (1.0 + c)), 1.0 / (1.0 + c));
    let m = grid.len();
    let lim = |a: usize, b: usize| {
        let mut p = [0.0; 2];
        for (da, wa) in [(0, al), (1, be), (2, al)] {
            for (db, wb) in [(0, al), (1, be), (2, al)] {
                for k in 0..2 {
                    p[k] += wa * wb * grid[a + da - 1][b + db - 1][k];
                }
            }
        }
        p
    };
    let mut out = Vec::new();
    for a in 2..m - 2 {
        for b in 2..m - 2 {
            let (e, wv, n, s) = (lim(a + 1, b), lim(a - 1, b), lim(a, b + 1), lim(a, b - 1));
            let du = [e[0] - wv[0], e[1] - wv[1]];
            let dv = [n[0] - s[0], n[1] - s[1]];
            out.push(du[0] * dv[1] - du[1] * dv[0]);
        }
    }
    out
}

#[test]
fn adjustable_scheme_rings_are_certified_and_sampling_agrees() {
    for n in [3, 5, 6, 9, 16] {
        for c in [0.05, 0.3, 0.7, 1.0] {
            let rep = check(n, c).unwrap();
            assert_eq!(
                rep.verdict,
                Verdict::C1Standard,
                "n = {n}, c = {c}: {rep:?}"
            );
            let sigma = rep.regularity.as_ref().unwrap().orientation as f64;
            let prep = prepare_ring(n, c, 1, 0.1).unwrap();
            for (id, w) in prep.ring.cells().iter().take(3) {
                let js = sampled_jacobians(c, w, 3);
                assert!(js.len() >= 9);
                for j in js {
                    assert!(sigma * j > 0.0, "n = {n}, c = {c}, {id}: sampled J = {j:e}");
                }
            }
        }
    }
}

#[test]
fn a_ring_with_one_mirrored_sector_is_not_regular() {
    let prep = prepare_ring(6, 0.3, 1, 0.1).unwrap();
    let mut cells = prep.ring.cells().to_vec();
    for (id, w) in cells.iter_mut() {
        if id.sector == 2 {
            for row in w.iter_mut() {
                for p in row.iter_mut() {
                    p[1] = -p[1];
                }
            }
        }
    }
    let rule = *prep.ring.rule();
    let bad = CcRing::from_cells(rule, cells).unwrap();
    let rep = check_ring(&bad, prep.point_error, Certificate::Cone);
    assert_eq!(rep.verdict, Verdict::NotRegular, "{rep:?}");
    let reg = rep.regularity.unwrap();
    assert_eq!(reg.verdict, RegularityVerdict::NotRegular);
    let (at, v) = reg.witness.unwrap();
    assert!(v < 0.0);
    // the witness lies in the flipped sector or on its boundary
    assert!(
        at.patch.sector == 2 || at.patch.sector == 1 || at.patch.sector == 3,
        "{at:?}"
    );
    // and a wrongly ordered cell list is rejected
    let mut cells = prep.ring.cells().to_vec();
    cells.swap(0, 1);
    assert!(CcRing::from_cells(rule, cells).is_err());
}

#[test]
fn the_mode_two_ring_is_not_injective() {
    for n in [5, 7, 11] {
        let prep = prepare_ring(n, 0.5, 2, 0.05).unwrap();
        let rep = check_ring(&prep.ring, prep.point_error, Certificate::Cone);
        // regular (the mode-2 map is a local diffeomorphism) but it winds twice
        assert_eq!(rep.regular(), Some(true), "n = {n}: {rep:?}");
        assert!(
            matches!(rep.verdict, Verdict::NotInjective { winding } if winding.abs() == 2),
            "n = {n}: {:?}",
            rep.verdict
        );
    }
}

#[test]
fn an_error_bound_beyond_the_data_makes_the_verdict_indeterminate() {
    let prep = prepare_ring(5, 0.3, 1, 0.1).unwrap();
    let rep = check_ring(&prep.ring, 1.0, Certificate::Cone);
    assert!(
        matches!(rep.verdict, Verdict::Indeterminate { .. }),
        "{rep:?}"
    );
    assert!(prep.point_error < 1e-9, "{}", prep.point_error);
}

#[test]
fn rule_validation() {
    assert!(UnivariateRule::new(0.0).is_err());
    assert!(UnivariateRule::new(1.5).is_err());
    assert!(UnivariateRule::new(f64::NAN).is_err());
    assert!(check_bicubic(2).is_err());
    assert!(subdiv_lab::charmap::catmull_clark::check_with(5, 0.3, Certificate::Bicubic).is_err());
    // c = 0 is not separated: no characteristic map, never C1
    let r = check(5, 0.0).unwrap();
    assert!(
        matches!(r.verdict, Verdict::NoCharacteristicMap { .. }),
        "{r:?}"
    );
}

#[test]
fn c1_intervals_are_bracketed_and_certified() {
    for n in [3, 8, 32] {
        let iv = c1_intervals(n, 16, 1e-6).unwrap();
        assert_eq!(iv.len(), 1, "n = {n}: {iv:?}");
        let i = &iv[0];
        assert_eq!(i.hi, 1.0);
        assert!(i.lo > 0.0 && i.lo - i.lo_outside <= 1e-6, "{i:?}");
        let p = study_point(n, i.lo).unwrap();
        assert_eq!((p.class, p.charmap), ("standard", "c1"));
        let q = study_point(n, i.lo_outside).unwrap();
        assert!(q.class != "standard" || q.charmap != "c1");
        if q.class == "standard" {
            assert_eq!(i.below, format!("charmap:{}", q.charmap));
        } else {
            assert_eq!(i.below, q.class);
        }
        for c in [0.1, 0.5, 0.9, 1.0] {
            assert_eq!(study_point(n, c).unwrap().charmap, "c1", "n = {n}, c = {c}");
        }
    }
}

#[test]
fn cli_analyze_and_cc_study_report_the_characteristic_map() {
    let (code, out, err) = common::run(&[
        "analyze",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "6",
        "--c",
        "0.25",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["charmap"]["verdict_code"], "c1");
    assert_eq!(v["charmap"]["winding_number"], 1);
    assert!(v["charmap"]["min_jacobian_location"]["patch"]
        .as_str()
        .unwrap()
        .starts_with("Omega"));
    let (code, out, err) =
        common::run(&["cc-study", "--n-min", "3", "--n-max", "4", "--samples", "4"]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "n,interval,c_lo,c_hi,c_lo_outside,c_hi_outside,below,above"
    );
    assert_eq!(lines.len(), 3);
    assert!(lines[1].starts_with("3,0,"), "{}", lines[1]);
    assert!(
        lines[1].ends_with(",not_separated,") || lines[1].ends_with(",charmap:indeterminate,"),
        "{}",
        lines[1]
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Regularity and injectivity do not depend on the planar basis: any
    /// invertible linear map of the ring keeps the verdict and multiplies the
    /// orientation by the sign of its determinant.
    #[test]
    fn verdict_is_invariant_under_linear_maps(
        n in 3usize..12,
        c in 0.1f64..1.0,
        m in prop::array::uniform4(-2.0f64..2.0),
    ) {
        let d = m[0] * m[3] - m[1] * m[2];
        prop_assume!(d.abs() > 0.2);
        let prep = prepare_ring(n, c, 1, 0.1).unwrap();
        let base = check_ring(&prep.ring, prep.point_error, Certificate::Cone);
        prop_assert_eq!(&base.verdict, &Verdict::C1Standard);
        let cells = prep.ring.cells().iter().map(|(id, w)| {
            let mut w2 = *w;
            for row in w2.iter_mut() {
                for p in row.iter_mut() {
                    *p = [m[0] * p[0] + m[1] * p[1], m[2] * p[0] + m[3] * p[1]];
                }
            }
            (*id, w2)
        }).collect();
        let mapped = CcRing::from_cells(*prep.ring.rule(), cells).unwrap();
        let norm = m.iter().fold(0.0f64, |a, x| a.max(x.abs())) * 2.0;
        let rep = check_ring(&mapped, prep.point_error * norm * 2.0, Certificate::Cone);
        prop_assert_eq!(&rep.verdict, &Verdict::C1Standard);
        let o0 = base.regularity.unwrap().orientation;
        let o1 = rep.regularity.unwrap().orientation;
        prop_assert_eq!(o1, o0 * if d > 0.0 { 1 } else { -1 });
    }
}

/// Largest coordinate magnitude of a ring's window points.
fn window_max_abs(ring: &CcRing) -> f64 {
    ring.cells()
        .iter()
        .flat_map(|(_, w)| w.iter().flatten().flatten())
        .fold(0.0f64, |a, x| a.max(x.abs()))
}

#[test]
fn an_error_bound_beyond_the_data_leaves_the_bicubic_jacobian_sign_indeterminate() {
    // The bicubic Bezier certificate (Catmull-Clark, c = 1/2) accepts a piece
    // only when its smallest Jacobian coefficient exceeds the error bound; with
    // a bound far above every window coordinate nothing is certified, whatever
    // the signs of the computed coefficients. The regularity verdict itself
    // (not only the report, whose winding number also fails) is `indeterminate`.
    for n in [3, 5, 8] {
        let prep = prepare_ring(n, 0.5, 1, 0.05).unwrap();
        let honest = check_ring(&prep.ring, prep.point_error, Certificate::Bicubic);
        assert_eq!(honest.verdict, Verdict::C1Standard, "n = {n}: {honest:?}");
        let scale = window_max_abs(&prep.ring);
        for big in [10.0 * scale, 1e3 * scale] {
            let rep = check_ring(&prep.ring, big, Certificate::Bicubic);
            assert!(
                matches!(rep.verdict, Verdict::Indeterminate { .. }),
                "n = {n}: {rep:?}"
            );
            let reg = rep.regularity.unwrap();
            assert_eq!(
                reg.verdict,
                RegularityVerdict::Indeterminate,
                "n = {n}, delta {big}: {reg:?}"
            );
            assert!(reg.witness.is_none() && reg.undecided.is_some(), "{reg:?}");
            // every computed coefficient is positive: only the bound stops it
            assert!(
                reg.min_coeff > 0.0 && reg.relative_error_bound > 1.0,
                "{reg:?}"
            );
            // the cone certificate agrees (its own regularity verdict, too)
            let cone = check_ring(&prep.ring, big, Certificate::Cone);
            assert_eq!(
                cone.regularity.unwrap().verdict,
                RegularityVerdict::Indeterminate,
                "cone, n = {n}"
            );
        }
    }
}

#[test]
fn a_mirrored_catmull_clark_ring_winds_negatively_and_the_report_turns_it_back() {
    for (n, c) in [(3, 0.5), (5, 0.5), (6, 0.3), (9, 0.7)] {
        let prep = prepare_ring(n, c, 1, 0.05).unwrap();
        let delta = prep.point_error;
        let cert = Certificate::for_c(c);
        let orientation = check_ring(&prep.ring, delta, cert)
            .regularity
            .unwrap()
            .orientation;
        let ring = if orientation < 0 {
            prep.ring.mirrored()
        } else {
            prep.ring.clone()
        };
        let mirror = ring.mirrored();
        // positively oriented ring: both boundaries wind once counter-clockwise
        assert_eq!(
            winding_number(&ring.outer_boundary(), delta),
            Some(1),
            "n = {n}, c = {c}"
        );
        assert_eq!(
            winding_number(&ring.inner_boundary(), delta),
            Some(1),
            "n = {n}, c = {c}"
        );
        // the mirror image winds clockwise
        assert_eq!(
            winding_number(&mirror.outer_boundary(), delta),
            Some(-1),
            "n = {n}, c = {c}"
        );
        assert_eq!(
            winding_number(&mirror.inner_boundary(), delta),
            Some(-1),
            "n = {n}, c = {c}"
        );
        for certificate in [Certificate::Cone, cert] {
            let (r, m) = (
                check_ring(&ring, delta, certificate),
                check_ring(&mirror, delta, certificate),
            );
            let (rr, mr) = (
                r.regularity.as_ref().unwrap(),
                m.regularity.as_ref().unwrap(),
            );
            assert_eq!(
                (rr.orientation, mr.orientation),
                (1, -1),
                "n = {n}, c = {c}"
            );
            // the report orients the ring before counting: both give +1
            for rep in [&r, &m] {
                assert_eq!(
                    rep.verdict,
                    Verdict::C1Standard,
                    "n = {n}, c = {c}: {rep:?}"
                );
                assert_eq!(
                    (rep.winding_number, rep.inner_winding_number),
                    (Some(1), Some(1))
                );
            }
        }
    }
}
