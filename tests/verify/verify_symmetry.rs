//! `verify` with the symmetry of the ratio box (math doc section 15,
//! "Symmetry of the ratio box"): every ratio vector of the box has a group
//! image in the fundamental domain and in an evaluated cell; the cells
//! still tile the box exactly; the summary's fractions are the bounds
//! through the group; the spec refuses boxes the group does not preserve.

use crate::verify_g1::assert_exact_tiling;
use num_traits::{One, Zero};
use proptest::prelude::*;
use subdiv_lab::scalar::{f64_to_rational, Rational};
use subdiv_lab::verify::decide::Status;
use subdiv_lab::verify::spec::{Property, Region, Symmetry, VerifySpec};
use subdiv_lab::verify::symmetry::symmetric_enclosure;
use subdiv_lab::verify::{run, summary, Cell, Limits, Outcome};

fn spec(n: usize, lo: f64, hi: f64, properties: Vec<Property>, min_width: f64) -> VerifySpec {
    VerifySpec {
        name: "s".into(),
        region: Region::Ratios {
            lo: vec![lo; n],
            hi: vec![hi; n],
        },
        properties,
        min_width,
        time_budget: None,
        symmetry: Symmetry::None,
    }
}

/// A small run of valence 4 over `[0.05, 0.95]^4` (widened to be exactly
/// reflection-invariant) whose class boundary forces refinement.
fn small_run(symmetry: Symmetry) -> (VerifySpec, Outcome) {
    let (lo, hi) = symmetric_enclosure(0.05, 0.95);
    let s = VerifySpec {
        symmetry,
        ..spec(4, lo, hi, vec![Property::Class], 0.12)
    };
    let out = run(&s, &Limits::default());
    (s, out)
}

fn q(x: f64) -> Rational {
    f64_to_rational(x).unwrap()
}

/// Whether the rational point `r` lies in the fundamental domain, exactly.
fn in_domain(symmetry: Symmetry, r: &[Rational]) -> bool {
    let half = Rational::new(1.into(), 2.into());
    match symmetry {
        Symmetry::None => true,
        Symmetry::Rotations => r.iter().all(|x| *x <= r[0]),
        Symmetry::Dihedral => {
            let u0 = &r[0] - &half;
            r.iter().all(|x| {
                let u = x - &half;
                let a = if u < Rational::zero() { -u } else { u };
                a <= u0
            })
        }
    }
}

/// The group images of `r` (rotations, and with the reflection
/// `r_i -> 1 - r_{n-1-i}` their mirrors), exactly.
fn images(symmetry: Symmetry, r: &[Rational]) -> Vec<Vec<Rational>> {
    let n = r.len();
    let mut out = Vec::new();
    let mut bases = vec![r.to_vec()];
    if symmetry == Symmetry::Dihedral {
        bases.push(
            (0..n)
                .map(|i| Rational::one() - r[n - 1 - i].clone())
                .collect(),
        );
    }
    for b in bases {
        for k in 0..n {
            out.push((0..n).map(|i| b[(i + k) % n].clone()).collect());
        }
    }
    out
}

/// Ratio vectors of the box whose every group image in the fundamental
/// domain lies in no evaluated cell (lies only in `by_symmetry` cells, or in
/// none): must be none.
fn uncovered(symmetry: Symmetry, out: &Outcome, points: &[Vec<f64>]) -> usize {
    let evaluated: Vec<(Vec<Rational>, Vec<Rational>)> = out
        .cells
        .iter()
        .filter(|c| !c.by_symmetry())
        .map(|c| {
            (
                c.lo.iter().map(|&x| q(x)).collect(),
                c.hi.iter().map(|&x| q(x)).collect(),
            )
        })
        .collect();
    let mut bad = 0;
    for p in points {
        let r: Vec<Rational> = p.iter().map(|&x| q(x)).collect();
        let ok = images(symmetry, &r).iter().any(|g| {
            in_domain(symmetry, g)
                && evaluated
                    .iter()
                    .any(|(a, b)| g.iter().enumerate().all(|(k, x)| a[k] <= *x && *x <= b[k]))
        });
        if !ok {
            bad += 1;
        }
    }
    bad
}

/// `vol(C cap D)` for the cell `C = [a, b]`, exactly: the integral over
/// `s = r_0` of `prod_{j >= 1} len([a_j, b_j] cap [1 - s, s])` (dihedral) or
/// `len([a_j, b_j] cap (-inf, s])` (rotations), cut at every break point,
/// where the integrand is a polynomial of degree `n - 1 <= 5`, which Boole's
/// rule integrates exactly.
fn clipped_exact(symmetry: Symmetry, a: &[Rational], b: &[Rational]) -> Rational {
    let half = Rational::new(1.into(), 2.into());
    let one = Rational::one();
    let n = a.len();
    assert!(n <= 6);
    let dihedral = symmetry == Symmetry::Dihedral;
    let s0 = if dihedral && a[0] < half {
        half.clone()
    } else {
        a[0].clone()
    };
    let s1 = b[0].clone();
    if s1 <= s0 {
        return Rational::zero();
    }
    let f = |s: &Rational| -> Rational {
        (1..n)
            .map(|j| {
                let top = if b[j] < *s { b[j].clone() } else { s.clone() };
                let mut bottom = a[j].clone();
                if dihedral && &one - s > bottom {
                    bottom = &one - s;
                }
                if top > bottom {
                    top - bottom
                } else {
                    Rational::zero()
                }
            })
            .product()
    };
    let mut cuts = vec![s0.clone(), s1.clone(), half.clone()];
    for j in 1..n {
        for x in [&a[j], &b[j]] {
            cuts.push(x.clone());
            cuts.push(&one - x);
        }
    }
    cuts.retain(|x| s0 <= *x && *x <= s1);
    cuts.sort();
    cuts.dedup();
    let w = [7, 32, 12, 32, 7];
    let mut total = Rational::zero();
    for p in cuts.windows(2) {
        let h = (&p[1] - &p[0]) / Rational::from_integer(4.into());
        let mut sum = Rational::zero();
        for (i, wi) in w.iter().enumerate() {
            let s = &p[0] + &h * Rational::from_integer((i as i64).into());
            sum += f(&s) * Rational::from_integer((*wi).into());
        }
        total += sum * &h * Rational::new(2.into(), 45.into());
    }
    total
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Every orbit meets the evaluated cells: random points of the box, and
    /// points on the walls of the fundamental domain (ties `r_j = r_0`,
    /// `r_j = 1 - r_0`, `r_0 = 1/2`), have a group image in the domain that
    /// lies in a cell that was evaluated.
    #[test]
    fn every_orbit_meets_an_evaluated_cell(seed in any::<u64>()) {
        for symmetry in [Symmetry::Rotations, Symmetry::Dihedral] {
            let (s, out) = small_run(symmetry);
            let (lo, hi) = s.bounds();
            let mut rng = subdiv_lab::rng::SplitMix64::new(seed);
            let mut points = Vec::new();
            for _ in 0..40 {
                let mut p: Vec<f64> = (0..4).map(|k| rng.uniform(lo[k], hi[k])).collect();
                points.push(p.clone());
                // walls: r_j = r_0 and r_j = 1 - r_0 (exact for r_0 >= 1/2)
                let j = 1 + (rng.next_f64() * 3.0) as usize % 3;
                p[j] = p[0];
                points.push(p.clone());
                if p[0] >= 0.5 {
                    p[j] = 1.0 - p[0];
                    points.push(p.clone());
                }
                p[0] = 0.5;
                points.push(p);
            }
            prop_assert_eq!(uncovered(symmetry, &out, &points), 0, "{:?}", symmetry);
        }
    }
}

#[test]
fn the_run_leaves_cells_to_the_symmetry_and_still_tiles_the_box() {
    for symmetry in [Symmetry::Rotations, Symmetry::Dihedral] {
        let (s, out) = small_run(symmetry);
        let skipped = out.cells.iter().filter(|c| c.by_symmetry()).count();
        assert!(
            skipped > 10 && out.cells.len() > skipped + 10,
            "{symmetry:?}"
        );
        assert_eq!(out.by_symmetry, skipped as u64);
        for c in &out.cells {
            if c.by_symmetry() {
                assert_eq!(c.verdict(), "by_symmetry");
                assert!(c.class.is_none());
                assert!(c.status.iter().all(|(_, st)| *st == Status::BySymmetry));
                assert!(!symmetry.meets_domain(&c.lo, &c.hi));
            } else {
                assert!(symmetry.meets_domain(&c.lo, &c.hi));
            }
        }
        // an exact tiling, in rationals
        let (lo, hi) = s.bounds();
        assert_exact_tiling(&lo, &hi, &out.cells);
        let total: Rational = lo.iter().zip(&hi).map(|(a, b)| q(*b) - q(*a)).product();
        // the summary counts the undecided cells only among the evaluated
        let sm = summary(&s, &out);
        assert_eq!(sm.counts.get("by_symmetry").copied(), Some(skipped));
        assert!(!sm.volume_fraction.contains_key("by_symmetry"));
        assert_eq!(sm.group_order, symmetry.order(4));
        // the same bound recomputed from the cells, in rationals, with the
        // exact volume of each open cell's part in the fundamental domain;
        // the parts of all the cells add up to vol(D cap B) = vol(B) / |G|
        let k = Rational::from_integer(symmetry.order(4).into());
        let part = |c: &Cell| {
            let a: Vec<Rational> = c.lo.iter().map(|&x| q(x)).collect();
            let b: Vec<Rational> = c.hi.iter().map(|&x| q(x)).collect();
            clipped_exact(symmetry, &a, &b)
        };
        let all: Rational = out.cells.iter().map(part).sum();
        assert_eq!(&all * &k, total, "{symmetry:?}");
        let open: Rational = out
            .cells
            .iter()
            .filter(|c| !c.by_symmetry() && c.class.is_none())
            .map(part)
            .sum();
        let bound = Rational::one() - k * open / &total;
        let cert = sm.property_volume_fraction["class"]["certified"];
        let want = if bound < Rational::zero() {
            0.0
        } else {
            num_traits::ToPrimitive::to_f64(&bound).unwrap()
        };
        assert!((cert - want).abs() <= 1e-12, "{cert} vs {want}");
    }
}

/// The bounds of the summary on a hand-made outcome over `[1/4, 3/4]^3`
/// (volume `1/8`) with the dihedral group (order 6): a `g1` cell of volume
/// `1/64`, an undecided cell `[1/2, 5/8]^3` of volume `1/512`, of which the
/// fundamental domain `u_0 >= |u_1|, |u_2|` holds a third, a cell left to the
/// symmetry of volume `1/16`. Certified at least
/// `1 - 6 (1/1536) / (1/8) = 31/32`, undecided at most `6 (1/1536) / (1/8) =
/// 1/32` (the bounds of the clipped volume are rounded outward: within
/// `1e-14`, on the safe side); without the symmetry the plain shares `1/8`
/// and `1/64`.
#[test]
fn the_summary_bounds_on_a_hand_made_outcome() {
    let cell = |lo: [f64; 3], hi: [f64; 3], st: Status| Cell {
        lo: lo.to_vec(),
        hi: hi.to_vec(),
        level: 3,
        class: None,
        status: vec![(Property::G1, st)],
    };
    let out = Outcome {
        cells: vec![
            cell([0.5, 0.25, 0.25], [0.75, 0.5, 0.5], Status::Certified),
            cell([0.5, 0.5, 0.5], [0.625, 0.625, 0.625], Status::Undecided),
            cell([0.25, 0.25, 0.25], [0.5, 0.5, 0.75], Status::BySymmetry),
        ],
        evaluated: 7,
        unevaluated: 0,
        by_symmetry: 1,
        stopped: None,
        seconds: 0.0,
    };
    let s = VerifySpec {
        symmetry: Symmetry::Dihedral,
        ..spec(3, 0.25, 0.75, vec![Property::G1], 0.1)
    };
    let sm = summary(&s, &out);
    assert_eq!(sm.group_order, 6);
    let below = |x: f64, want: f64| x <= want && x >= want - 1e-14;
    let above = |x: f64, want: f64| x >= want && x <= want + 1e-14;
    assert!(below(sm.volume_fraction["g1"], 31.0 / 32.0));
    assert!(above(sm.volume_fraction["undecided"], 1.0 / 32.0));
    assert!(above(sm.undecided_fraction, 1.0 / 32.0));
    assert!(below(
        sm.property_volume_fraction["g1"]["certified"],
        31.0 / 32.0
    ));
    assert!(above(
        sm.property_volume_fraction["g1"]["undecided"],
        1.0 / 32.0
    ));
    assert_eq!(sm.property_volume_fraction["g1"]["refuted"], 0.0);
    assert_eq!(sm.counts["by_symmetry"], 1);
    assert!(!sm.volume_fraction.contains_key("by_symmetry"));
    let json = serde_json::to_value(&sm).unwrap();
    assert_eq!(json["symmetry"], "dihedral");
    let plain = VerifySpec {
        symmetry: Symmetry::None,
        ..s
    };
    let sm = summary(&plain, &out);
    assert_eq!(sm.group_order, 1);
    assert_eq!(sm.volume_fraction["g1"], 1.0 / 8.0);
    assert_eq!(sm.undecided_fraction, 1.0 / 64.0);
}

#[test]
fn the_spec_refuses_boxes_the_group_does_not_preserve() {
    let text = |b: &str, sy: &str| {
        format!("scheme = \"nurds\"\nvalence = 3\nbox = {b}\nproperties = [\"g1\"]\nsymmetry = \"{sy}\"\n")
    };
    let ok = VerifySpec::parse(&text(
        "[[0.25, 0.75], [0.25, 0.75], [0.25, 0.75]]",
        "dihedral",
    ))
    .unwrap();
    assert_eq!(ok.symmetry, Symmetry::Dihedral);
    let ok = VerifySpec::parse(&text(
        "[[0.05, 0.95], [0.05, 0.95], [0.05, 0.95]]",
        "rotations",
    ))
    .unwrap();
    assert_eq!(ok.symmetry, Symmetry::Rotations);
    let ok = VerifySpec::parse(&text("[[0.05, 0.95], [0.1, 0.95], [0.05, 0.95]]", "none")).unwrap();
    assert_eq!(ok.symmetry, Symmetry::None);
    for (b, sy, needle) in [
        (
            "[[0.05, 0.95], [0.05, 0.95], [0.05, 0.95]]",
            "dihedral",
            "0.9500000000000001",
        ),
        (
            "[[0.05, 0.95], [0.1, 0.95], [0.05, 0.95]]",
            "rotations",
            "equal sides",
        ),
        (
            "[[0.25, 0.75], [0.25, 0.75], [0.25, 0.7]]",
            "dihedral",
            "equal sides",
        ),
        (
            "[[0.25, 0.75], [0.25, 0.75], [0.25, 0.75]]",
            "reflection",
            "unknown symmetry",
        ),
    ] {
        let e = VerifySpec::parse(&text(b, sy)).unwrap_err().to_string();
        assert!(e.contains(needle) && e.contains("line 5"), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }
}
