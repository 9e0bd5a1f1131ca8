//! Unit tests of the region verifier: the deflated family against the face
//! block, soundness against the exact pointwise classifier, a deliberately
//! weakened enclosure caught by the same check, exact tiling.

use super::enclose::{enclose, AffineFamily};
use super::*;
use crate::knots::EdgeRatios;
use crate::rng::SplitMix64;
use crate::scalar::{f64_to_rational, Rational};
use crate::schemes::LocalScheme;
use crate::spectral::eigen::{Eigen, EigenOptions};
use crate::spectral::exact::exact_verdict;
use nalgebra::DMatrix;
use num_traits::Zero;

fn spec3(lo: [f64; 3], hi: [f64; 3], min_width: f64) -> VerifySpec {
    VerifySpec {
        name: "t".into(),
        region: Region::Ratios {
            lo: lo.to_vec(),
            hi: hi.to_vec(),
        },
        properties: vec![Property::Class, Property::Separation],
        min_width,
        time_budget: None,
        symmetry: Default::default(),
    }
}

#[test]
fn deflated_family_has_the_face_block_spectrum() {
    let mut rng = SplitMix64::new(7);
    for n in 3..=8 {
        let f = AffineFamily::nurds(n);
        for _ in 0..5 {
            let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
            let a = LocalScheme::nurds(EdgeRatios::new(r.clone()).unwrap())
                .face_block()
                .unwrap();
            let ea = Eigen::new(&a, EigenOptions::VALUES).unwrap();
            let m = f.dim();
            let c = DMatrix::from_row_slice(m, m, &f.at(&r));
            let ec = Eigen::new(&c, EigenOptions::VALUES).unwrap();
            // face block: 1 first, then the spectrum of C
            assert!((ea.values()[0].re - 1.0).abs() < 1e-12);
            let mut rest: Vec<_> = ea.values()[1..].to_vec();
            for z in ec.values() {
                let (k, d) = rest
                    .iter()
                    .enumerate()
                    .map(|(k, w)| (k, (w - z).norm()))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                assert!(d < 1e-7, "n={n} r={r:?}: {z} missing (nearest {d})");
                rest.remove(k);
            }
            // even n: the exactly removed eigenvalue 1/4 is what is left
            if n % 2 == 0 {
                assert!(
                    rest.len() == 1 && (rest[0].re - 0.25).abs() < 1e-7 && rest[0].im.abs() < 1e-7,
                    "n={n}: {rest:?}"
                );
            } else {
                assert!(rest.is_empty());
            }
        }
    }
}

#[test]
fn discs_contain_the_spectrum_at_sampled_points() {
    let mut rng = SplitMix64::new(11);
    for n in 3..=6 {
        let f = AffineFamily::nurds(n);
        for _ in 0..20 {
            let lo: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.9)).collect();
            let hi: Vec<f64> = lo.iter().map(|x| x + 0.01).collect();
            let Some(e) = enclose(&f, &lo, &hi, Tamper::None) else {
                continue;
            };
            for _ in 0..5 {
                let r: Vec<f64> = lo
                    .iter()
                    .zip(&hi)
                    .map(|(a, b)| rng.uniform(*a, *b))
                    .collect();
                let m = f.dim();
                let c = DMatrix::from_row_slice(m, m, &f.at(&r));
                for z in Eigen::new(&c, EigenOptions::VALUES).unwrap().values() {
                    for discs in [&e.rows, &e.cols] {
                        assert!(discs
                            .iter()
                            .any(|d| ((z.re - d.re).powi(2) + (z.im - d.im).powi(2)).sqrt()
                                <= d.radius + 1e-12));
                    }
                }
            }
        }
    }
}

/// Random rational points inside the decided cells, each compared with the
/// exact classifier; returns the number of disagreements and of checks.
pub(super) fn disagreements(
    spec: &VerifySpec,
    out: &Outcome,
    samples: usize,
    seed: u64,
) -> (usize, usize) {
    let mut rng = SplitMix64::new(seed);
    let decided: Vec<&Cell> = out.cells.iter().filter(|c| c.class.is_some()).collect();
    let mut bad = 0;
    let mut checks = 0;
    if decided.is_empty() {
        return (0, 0);
    }
    let _ = spec;
    for s in 0..samples {
        let cell = decided[s % decided.len()];
        let r: Vec<Rational> = cell
            .lo
            .iter()
            .zip(&cell.hi)
            .map(|(a, b)| f64_to_rational(rng.uniform(*a, *b).clamp(*a, *b)).unwrap())
            .collect();
        assert!(r.iter().all(|x| !x.is_zero()));
        let v = exact_verdict(&LocalScheme::nurds(EdgeRatios::new(r).unwrap()), None).unwrap();
        checks += 1;
        if let Some(k) = v.class {
            if Some(k) != cell.class {
                bad += 1;
            }
        }
        for (p, st) in &cell.status {
            if *p == Property::Separation {
                let want = match st {
                    Status::Certified => Some(true),
                    Status::Refuted => Some(false),
                    Status::Undecided | Status::BySymmetry => None,
                };
                if want.is_some() && v.separated.is_some() && want != v.separated {
                    bad += 1;
                }
            }
        }
    }
    (bad, checks)
}

#[test]
fn certified_cells_agree_with_the_exact_classifier() {
    // a box across the class boundary and the separation boundary
    let spec = spec3([0.05, 0.05, 0.05], [0.95, 0.95, 0.95], 1.0 / 32.0);
    let out = run(&spec, &Limits::default());
    let classes: std::collections::HashSet<_> = out.cells.iter().filter_map(|c| c.class).collect();
    assert!(
        classes.len() >= 2,
        "expected several classes, got {classes:?}"
    );
    let (bad, checks) = disagreements(&spec, &out, 300, 1);
    assert!(checks == 300 && bad == 0, "{bad} disagreements in {checks}");
}

#[test]
fn a_weakened_enclosure_is_caught() {
    let spec = spec3([0.05, 0.05, 0.05], [0.95, 0.95, 0.95], 1.0 / 32.0);
    let limits = Limits {
        tamper: Tamper::DropVariation,
        ..Limits::default()
    };
    let out = run(&spec, &limits);
    let (bad, checks) = disagreements(&spec, &out, 300, 1);
    assert!(
        bad > 0,
        "the weakened enclosure went unnoticed in {checks} checks"
    );
}

fn spec5(min_width: f64) -> VerifySpec {
    VerifySpec {
        name: "t5".into(),
        region: Region::Ratios {
            lo: vec![0.05; 5],
            hi: vec![0.95; 5],
        },
        properties: vec![Property::Class, Property::Separation],
        min_width,
        time_budget: None,
        symmetry: Default::default(),
    }
}

#[test]
fn gershgorin_path_agrees_with_the_exact_classifier_and_its_weakening_is_caught() {
    // n = 5: the 4 x 4 block, discs in the eigenvector basis; small random boxes
    let mut rng = SplitMix64::new(5);
    let mut certified = 0;
    for _ in 0..8 {
        let lo: Vec<f64> = (0..5).map(|_| rng.uniform(0.05, 0.85)).collect();
        let hi: Vec<f64> = lo.iter().map(|x| x + 0.06).collect();
        let spec = VerifySpec {
            region: Region::Ratios { lo, hi },
            ..spec5(0.01)
        };
        let out = run(&spec, &Limits::default());
        certified += out.cells.iter().filter(|c| c.class.is_some()).count();
        let (bad, checks) = disagreements(&spec, &out, 20, 3);
        assert!(bad == 0, "{bad} disagreements in {checks}");
    }
    assert!(certified > 0, "no n = 5 cell was certified");
    // coarse cells certified from their centre alone are caught
    let spec = spec5(0.25);
    let weak = run(
        &spec,
        &Limits {
            tamper: Tamper::DropVariation,
            ..Limits::default()
        },
    );
    let (bad, checks) = disagreements(&spec, &weak, 150, 3);
    assert!(
        bad > 0,
        "the weakened enclosure went unnoticed in {checks} checks"
    );
}

fn spec_n(n: usize, lo: Vec<f64>, hi: Vec<f64>, min_width: f64) -> VerifySpec {
    assert_eq!(lo.len(), n);
    VerifySpec {
        name: format!("t{n}"),
        region: Region::Ratios { lo, hi },
        properties: vec![Property::Class, Property::Separation],
        min_width,
        time_budget: None,
        symmetry: Default::default(),
    }
}

/// Three random boxes of side 0.04 at each valence of `valences`, through the
/// factor route: no certified cell disagrees with the exact classifier, and
/// some cell is certified.
fn factor_route_agrees_with_the_exact_classifier(valences: std::ops::RangeInclusive<usize>) {
    let mut rng = SplitMix64::new(15);
    let mut certified = 0;
    for n in valences {
        for _ in 0..3 {
            let lo: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.9)).collect();
            let hi: Vec<f64> = lo.iter().map(|x| x + 0.04).collect();
            let spec = spec_n(n, lo, hi, 0.02);
            let out = run(&spec, &Limits::default());
            certified += out.cells.iter().filter(|c| c.class.is_some()).count();
            let (bad, checks) = disagreements(&spec, &out, 8, 5);
            assert!(bad == 0, "n = {n}: {bad} disagreements in {checks}");
        }
    }
    assert!(certified > 0, "no cell was certified");
}

#[test]
fn factor_route_agrees_with_the_exact_classifier_for_n_6() {
    factor_route_agrees_with_the_exact_classifier(6..=6);
}

#[test]
#[ignore = "heavy full-size run (about 12 s); .ci/run runs it with --ignored"]
fn factor_route_agrees_with_the_exact_classifier_for_n_7_and_8() {
    factor_route_agrees_with_the_exact_classifier(7..=8);
}

/// Exact tiling of the box by the cells, in rationals: every cell inside
/// the box, interiors pairwise disjoint, volumes summing to the box's.
fn assert_tiles(spec: &VerifySpec, out: &Outcome) {
    let q = |x: f64| f64_to_rational(x).unwrap();
    let (lo, hi) = spec.bounds();
    let k = lo.len();
    let total: Rational = lo.iter().zip(&hi).map(|(a, b)| q(*b) - q(*a)).product();
    let mut sum = Rational::zero();
    for (i, c) in out.cells.iter().enumerate() {
        for d in 0..k {
            assert!(lo[d] <= c.lo[d] && c.lo[d] < c.hi[d] && c.hi[d] <= hi[d]);
        }
        sum +=
            c.lo.iter()
                .zip(&c.hi)
                .map(|(a, b)| q(*b) - q(*a))
                .product::<Rational>();
        for e in &out.cells[..i] {
            assert!((0..k).any(|d| c.hi[d] <= e.lo[d] || e.hi[d] <= c.lo[d]));
        }
    }
    assert_eq!(sum, total);
}

#[test]
fn invariant_tree_route_at_n5_agrees_with_the_exact_classifier_and_tiles() {
    // n = 5 goes through the invariant tree (math doc section 15): a box
    // across the complex / real boundary
    let f = AffineFamily::nurds(5);
    let p = &factor::CharPoly::new(&f).unwrap();
    let inv = &invariants::Invariants::new(p).expect("n = 5 has invariants");
    let spec = spec_n(5, vec![0.4; 5], vec![0.6; 5], 0.05);
    let (lo, hi) = spec.bounds();
    assert!(invariants::Tree::new(inv, &lo, &hi).is_some());
    let out = run(&spec, &Limits::default());
    // the box crosses the complex / real boundary (a_shrunk_invariant_enclosure_at_n5_is_caught)
    assert!(
        out.cells.iter().any(|c| c.class.is_some()),
        "nothing certified"
    );
    let (bad, checks) = disagreements(&spec, &out, 300, 21);
    assert!(checks == 300 && bad == 0, "{bad} disagreements in {checks}");
    assert_tiles(&spec, &out);
}

#[test]
fn a_shrunk_invariant_enclosure_at_n5_is_caught() {
    // the invariants enclosed at the centre of each cell only (G = 0)
    let spec = spec_n(5, vec![0.4; 5], vec![0.6; 5], 0.05);
    let weak = run(
        &spec,
        &Limits {
            tamper: Tamper::DropVariation,
            ..Limits::default()
        },
    );
    let (bad, checks) = disagreements(&spec, &weak, 300, 21);
    assert!(
        bad > 0,
        "the shrunk invariant enclosure went unnoticed in {checks} checks"
    );
}

#[test]
fn cells_tile_the_box_exactly() {
    let spec = spec3([0.05, 0.2, 0.3], [0.95, 0.7, 0.9], 1.0 / 16.0);
    let out = run(&spec, &Limits::default());
    assert!(out.cells.len() > 10);
    let q = |x: f64| f64_to_rational(x).unwrap();
    let (lo, hi) = spec.bounds();
    let total: Rational = lo.iter().zip(&hi).map(|(a, b)| q(*b) - q(*a)).product();
    let mut sum = Rational::zero();
    for (i, c) in out.cells.iter().enumerate() {
        for k in 0..3 {
            assert!(lo[k] <= c.lo[k] && c.lo[k] < c.hi[k] && c.hi[k] <= hi[k]);
        }
        sum +=
            c.lo.iter()
                .zip(&c.hi)
                .map(|(a, b)| q(*b) - q(*a))
                .product::<Rational>();
        for d in &out.cells[..i] {
            // interiors disjoint: separated along some axis (float comparisons are exact)
            assert!((0..3).any(|k| c.hi[k] <= d.lo[k] || d.hi[k] <= c.lo[k]));
        }
    }
    assert_eq!(sum, total);
}

#[test]
fn cc_path_agrees_with_cc_study() {
    for n in [3usize, 5, 8] {
        let spec = VerifySpec {
            name: "cc".into(),
            region: Region::Shape {
                valence: n,
                lo: 0.001,
                hi: 1.0,
            },
            properties: vec![Property::Class, Property::Separation],
            min_width: 1e-4,
            time_budget: None,
            symmetry: Default::default(),
        };
        let out = run(&spec, &Limits::default());
        let iv = crate::cc_study::standard_intervals(n, 200, 1e-9).unwrap();
        let mut certified = 0.0;
        for c in out.cells.iter().filter(|c| c.class.is_some()) {
            assert!(
                iv.iter()
                    .any(|i| i.lo <= c.lo[0] + 1e-6 && c.hi[0] <= i.hi + 1e-6),
                "n={n}: {:?} outside {iv:?}",
                c.lo
            );
            let mid = 0.5 * (c.lo[0] + c.hi[0]);
            assert_eq!(
                crate::cc_study::study_point(n, mid).unwrap().class,
                "standard"
            );
            certified += c.hi[0] - c.lo[0];
        }
        let study: f64 = iv.iter().map(|i| i.hi - i.lo.max(0.001)).sum();
        assert!(
            certified > study - 0.01,
            "n={n}: certified {certified} of {study}"
        );
    }
}

#[test]
fn taylor_products_contain_sampled_values() {
    use super::interval::Iv;
    use super::taylor::Taylor;
    let mut rng = SplitMix64::new(21);
    for _ in 0..200 {
        let k = 3;
        let h: Vec<f64> = (0..k).map(|_| rng.uniform(0.0, 0.5)).collect();
        let mut forms = Vec::new();
        let mut coefs = Vec::new();
        for _ in 0..3 {
            let c = rng.uniform(-2.0, 2.0);
            let g: Vec<f64> = (0..k).map(|_| rng.uniform(-2.0, 2.0)).collect();
            forms.push(Taylor::affine(Iv::point(c), &g));
            coefs.push((c, g));
        }
        // q = f0 f1 - f2 f2 / 2 + f0
        let q = forms[0]
            .mul(&forms[1], &h)
            .sub(&forms[2].mul(&forms[2], &h).scale(0.5))
            .add(&forms[0]);
        let r = q.range(&h);
        let eval = |i: usize, d: &[f64]| {
            coefs[i].0 + coefs[i].1.iter().zip(d).map(|(g, x)| g * x).sum::<f64>()
        };
        let mut seen = (f64::INFINITY, f64::NEG_INFINITY);
        for _ in 0..50 {
            // corners and interior points
            let d: Vec<f64> = h
                .iter()
                .map(|&hk| {
                    let t = rng.uniform(-1.0, 1.0);
                    hk * if t.abs() > 0.7 { t.signum() } else { t }
                })
                .collect();
            let v = eval(0, &d) * eval(1, &d) - eval(2, &d) * eval(2, &d) / 2.0 + eval(0, &d);
            assert!(r.lo - 1e-12 <= v && v <= r.hi + 1e-12, "{v} outside {r:?}");
            seen = (seen.0.min(v), seen.1.max(v));
        }
        // and the enclosure is not vacuous: at most the sampled range plus
        // the second-order remainder and a first-order slack
        let lin = q.linear_bound(&h);
        assert!(r.hi - r.lo <= 2.0 * (lin + q.rem) + 1e-9);
        let _ = seen;
    }
}

#[test]
fn scaled_discs_are_sound_and_tighter_than_plain_gershgorin() {
    let mut rng = SplitMix64::new(13);
    let (mut tight, mut plain, mut cases) = (0.0, 0.0, 0);
    for n in 5..=8 {
        let f = AffineFamily::nurds(n);
        for _ in 0..20 {
            let lo: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.9)).collect();
            let hi: Vec<f64> = lo.iter().map(|x| x + 0.004).collect();
            let (Some(e), Some(p)) = (
                enclose(&f, &lo, &hi, Tamper::None),
                enclose(&f, &lo, &hi, Tamper::PlainGershgorin),
            ) else {
                continue;
            };
            for _ in 0..5 {
                let r: Vec<f64> = lo
                    .iter()
                    .zip(&hi)
                    .map(|(a, b)| rng.uniform(*a, *b))
                    .collect();
                let m = f.dim();
                let c = DMatrix::from_row_slice(m, m, &f.at(&r));
                let values = Eigen::new(&c, EigenOptions::VALUES).unwrap();
                // every tight row disc holds exactly one eigenvalue
                for d in &e.rows {
                    let inside = values
                        .values()
                        .iter()
                        .filter(|z| {
                            ((z.re - d.re).powi(2) + (z.im - d.im).powi(2)).sqrt()
                                <= d.radius + 1e-12
                        })
                        .count();
                    assert!(inside >= 1, "n={n}: an empty disc {d:?}");
                }
            }
            cases += 1;
            tight += e.rows.iter().map(|d| d.radius).sum::<f64>();
            plain += p.rows.iter().map(|d| d.radius).sum::<f64>();
        }
    }
    assert!(cases > 20, "{cases}");
    assert!(tight < 0.8 * plain, "scaled {tight} vs plain {plain}");
}

#[test]
fn corner_box_encloses_its_ratios_and_its_cells_agree_with_the_exact_classifier() {
    use crate::knots::CornerIntervals;
    let text = "scheme = \"nurds\"\nvalence = 3\np_box = [[0.5, 2.0], [1.0, 4.0], [0.25, 1.0]]\nq_box = [[1.0, 2.0], [0.5, 1.0], [2.0, 8.0]]\nproperties = [\"class\", \"separation\"]\nmin_width = 0.03\n";
    let spec = VerifySpec::parse(text).unwrap();
    let Region::Corners { p, q, lo, hi } = &spec.region else {
        panic!("not a corner box: {:?}", spec.region)
    };
    // every corner-interval vector of the box has its ratios inside the ratio box
    let mut rng = SplitMix64::new(17);
    for _ in 0..200 {
        let pv: Vec<f64> = p.iter().map(|[a, b]| rng.uniform(*a, *b)).collect();
        let qv: Vec<f64> = q.iter().map(|[a, b]| rng.uniform(*a, *b)).collect();
        let r = CornerIntervals::new(pv, qv).unwrap().ratios().unwrap();
        for (i, x) in r.as_slice().iter().enumerate() {
            assert!(
                lo[i] <= *x && *x <= hi[i],
                "r_{i} = {x} outside [{}, {}]",
                lo[i],
                hi[i]
            );
        }
    }
    // the extreme corners reach the ends (up to the outward rounding)
    assert!((lo[0] - 0.5 / 2.5).abs() < 1e-15 && (hi[0] - 1.0 / 1.5).abs() < 1e-15);
    let out = run(&spec, &Limits::default());
    assert!(out.cells.iter().any(|c| c.class.is_some()));
    // log-scaled bisection: a split point is not the arithmetic midpoint
    assert!(out
        .cells
        .iter()
        .any(|c| (0..3).any(|k| c.lo[k] != lo[k] && c.lo[k] != 0.5 * lo[k] + 0.5 * hi[k])));
    let (bad, checks) = disagreements(&spec, &out, 200, 9);
    assert!(checks == 200 && bad == 0, "{bad} disagreements in {checks}");
}

/// Budget of [`a_time_budget_stops_within_a_level`], seconds: a few
/// hundred `n = 7` cells per thread fit in it.
const SHORT_BUDGET: f64 = 1.0;

/// The wall-time bound of [`a_time_budget_stops_within_a_level`] as a
/// multiple of the budget. The run checks the clock before every cell, so it
/// returns within one cell's evaluation (about 0.5 ms at `n = 7`) plus the
/// collection of the remaining cells of the level after the deadline; the
/// factor 3 leaves room for a loaded 2-core machine (the clock is wall time,
/// so load delays the return only by the post-processing).
const BUDGET_OVERRUN_FACTOR: f64 = 3.0;

#[test]
fn a_time_budget_stops_within_a_level() {
    // n = 7 over [0.05, 0.95]^7 runs for many minutes (math doc section 15);
    // with a short budget it stops inside a level: the cells of that level
    // not yet evaluated stay whole and undecided, and the box stays tiled.
    // The deadline can fall on the very end of a level (then no cell is left
    // unevaluated and the between-levels check stops the run); a slightly
    // longer budget moves it into the next level.
    for attempt in 0..3 {
        let budget = SHORT_BUDGET * (1.0 + 0.3 * f64::from(attempt));
        let spec = VerifySpec {
            time_budget: Some(budget),
            symmetry: Default::default(),
            ..spec_n(7, vec![0.05; 7], vec![0.95; 7], 0.02)
        };
        let t0 = Instant::now();
        let out = run(&spec, &Limits::default());
        let wall = t0.elapsed().as_secs_f64();
        assert!(
            wall < BUDGET_OVERRUN_FACTOR * budget,
            "budget {budget} s, returned after {wall} s"
        );
        assert_eq!(out.stopped, Some(Stop::TimeBudget));
        let s = summary(&spec, &out);
        let json = serde_json::to_value(&s).unwrap();
        assert_eq!(json["stopped"], "time_budget");
        assert_eq!(json["unevaluated"], out.unevaluated);
        assert_tiles(&spec, &out);
        let open = out.cells.iter().filter(|c| c.verdict() == "undecided");
        assert!(open.count() as u64 >= out.unevaluated);
        if out.unevaluated > 0 {
            return;
        }
    }
    panic!("three budgets ran out exactly at the end of a level");
}

/// With a symmetry, a cut that leaves one half outside the fundamental
/// domain goes before the enclosure's preferred side: in `[1/2, 3/4] x
/// [1/2, 1]` cutting `r_1` at `3/4` leaves `r_1 >= 3/4 >= r_0`, outside
/// `u_0 >= |u_1|` (dihedral) and `r_0 >= r_1` (rotations) but for a face,
/// while both halves of the cut of `r_0` meet the domain. Without a symmetry
/// the scores decide.
#[test]
fn a_cut_that_leaves_a_half_to_the_symmetry_goes_first() {
    let (a, b) = ([0.5, 0.5], [0.75, 1.0]);
    let scores = [1.0, 0.0];
    for group in [symmetry::Symmetry::Dihedral, symmetry::Symmetry::Rotations] {
        assert_eq!(
            split_coordinate(&a, &b, Some(&scores), 0.01, false, group),
            Some((1, 0.75)),
            "{group:?}"
        );
    }
    assert_eq!(
        split_coordinate(&a, &b, Some(&scores), 0.01, false, symmetry::Symmetry::None),
        Some((0, 0.625))
    );
    // no free cut: the scores decide
    let (a, b) = ([0.5, 0.25], [0.75, 0.75]);
    assert_eq!(
        split_coordinate(
            &a,
            &b,
            Some(&scores),
            0.01,
            false,
            symmetry::Symmetry::Dihedral
        ),
        Some((0, 0.625))
    );
}
