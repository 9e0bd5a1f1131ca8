//! The `charmap` property of `subdiv-lab verify` over cells (math doc
//! section 15, "The characteristic map over a cell"): at random points
//! of the cells certified for `charmap` the pointwise certificate of math
//! doc section 7 finds the map regular and injective, and the pointwise ring
//! (in the cell's own normalisation) lies in the cell's enclosure; a run with
//! the subspace variation dropped is caught by the same check; the certified
//! intervals of `c` agree with `cc-study`.

use crate::common;

use proptest::prelude::*;
use std::fs;
use subdiv_lab::charmap::{self, Verdict};
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::verify::charmap::ratios::ratio_ring;
use subdiv_lab::verify::charmap::shape::{pointwise_windows, shape_ring};
use subdiv_lab::verify::charmap::CellTamper;
use subdiv_lab::verify::decide::Status;
use subdiv_lab::verify::spec::{Property, Region, VerifySpec};
use subdiv_lab::verify::{run, Cell, Limits, Outcome, Tamper};

/// Slack for the floating-point error of the pointwise ring.
const POINT_TOL: f64 = 1e-10;

fn spec(region: Region, min_width: f64) -> VerifySpec {
    VerifySpec {
        name: "c".into(),
        region,
        properties: vec![Property::Class, Property::Separation, Property::Charmap],
        min_width,
        time_budget: None,
        symmetry: Default::default(),
    }
}

fn charmap_certified(c: &Cell) -> bool {
    c.status
        .iter()
        .any(|(p, s)| *p == Property::Charmap && *s == Status::Certified)
}

/// At `samples` random points of the charmap-certified cells: the number of
/// points where the pointwise certificate does not find a regular and
/// injective map (`Indeterminate` counts too), the number of enclosure misses
/// of the pointwise ring (recomputed with `tamper`, the enclosure the run
/// used), and the number of points checked.
fn check(
    spec: &VerifySpec,
    out: &Outcome,
    tamper: CellTamper,
    samples: usize,
    seed: u64,
) -> (usize, usize, usize) {
    let cells: Vec<&Cell> = out.cells.iter().filter(|c| charmap_certified(c)).collect();
    if cells.is_empty() {
        return (0, 0, 0);
    }
    let mut rng = SplitMix64::new(seed);
    let (mut wrong, mut misses) = (0, 0);
    for s in 0..samples {
        let cell = cells[(s * 7919 + seed as usize) % cells.len()];
        let x: Vec<f64> = cell
            .lo
            .iter()
            .zip(&cell.hi)
            .map(|(a, b)| rng.uniform(*a, *b).clamp(*a, *b))
            .collect();
        match &spec.region {
            Region::Shape { valence, .. } => {
                let v = charmap::catmull_clark::check(*valence, x[0])
                    .unwrap()
                    .verdict;
                if v != Verdict::C1Standard {
                    wrong += 1;
                }
                let ring = shape_ring(*valence, cell.lo[0], cell.hi[0], tamper).unwrap();
                misses += ring.misses(&pointwise_windows(*valence, x[0]).unwrap(), POINT_TOL);
            }
            Region::Ratios { .. } | Region::Corners { .. } => {
                let scheme = LocalScheme::nurds(EdgeRatios::new(x.clone()).unwrap());
                let v = charmap::check(&scheme).unwrap().verdict;
                if !matches!(
                    v,
                    Verdict::C1Standard | Verdict::TangentPlaneContinuous { .. }
                ) {
                    wrong += 1;
                }
                let ring = ratio_ring(&cell.lo, &cell.hi, tamper).unwrap();
                let (pf, pts) = ring.pointwise(&x).unwrap();
                misses += ring.misses(pf, &pts, POINT_TOL);
            }
        }
    }
    (wrong, misses, samples)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    /// Random NURDS boxes (n = 3, 4): every sampled point of a cell certified
    /// for charmap is regular and injective pointwise, and its ring lies in
    /// the cell's enclosure.
    #[test]
    fn certified_charmap_cells_agree_with_the_pointwise_certificate(
        n in 3usize..=4,
        corner in prop::collection::vec(0.02f64..0.85, 4),
        width in prop::collection::vec(0.03f64..0.12, 4),
        seed in 0u64..1000,
    ) {
        let lo: Vec<f64> = corner[..n].to_vec();
        let hi: Vec<f64> = lo.iter().zip(&width).map(|(a, w)| (a + w).min(0.98)).collect();
        let s = spec(Region::Ratios { lo, hi }, if n == 3 { 1.0 / 128.0 } else { 1.0 / 64.0 });
        let out = run(&s, &Limits::default());
        let (wrong, misses, checked) = check(&s, &out, CellTamper::None, 12, seed);
        prop_assume!(checked > 0);
        prop_assert_eq!(wrong, 0, "{} of {} points not regular and injective", wrong, checked);
        prop_assert_eq!(misses, 0, "{} enclosure misses at {} points", misses, checked);
    }
}

#[test]
fn cc_family_cells_agree_with_the_pointwise_certificate_and_cc_study() {
    for n in [3usize, 6, 11] {
        let s = spec(
            Region::Shape {
                valence: n,
                lo: 0.001,
                hi: 1.0,
            },
            1e-5,
        );
        let out = run(&s, &Limits::default());
        let (wrong, misses, checked) = check(&s, &out, CellTamper::None, 40, n as u64);
        assert!(checked > 0, "n={n}: nothing certified");
        assert_eq!((wrong, misses), (0, 0), "n={n}: {checked} points");
        // the certified cells lie in cc-study's C1 intervals and cover them
        let iv = subdiv_lab::cc_study::c1_intervals(n, 200, 1e-9).unwrap();
        let mut certified = 0.0;
        for c in out.cells.iter().filter(|c| charmap_certified(c)) {
            assert!(
                iv.iter()
                    .any(|i| i.lo <= c.lo[0] + 1e-6 && c.hi[0] <= i.hi + 1e-6),
                "n={n}: [{}, {}] outside {iv:?}",
                c.lo[0],
                c.hi[0]
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
fn a_tampered_charmap_enclosure_is_caught() {
    // the same checks on runs whose enclosure ignores the subspace variation
    // over the cell: the pointwise rings leave the enclosures
    let s = spec(
        Region::Ratios {
            lo: vec![0.3, 0.35, 0.4],
            hi: vec![0.36, 0.41, 0.46],
        },
        1.0 / 64.0,
    );
    let limits = Limits {
        tamper: Tamper::DropSubspaceVariation,
        ..Limits::default()
    };
    let out = run(&s, &limits);
    let (_, misses, checked) = check(&s, &out, CellTamper::DropSubspaceVariation, 12, 3);
    assert!(
        checked > 0 && misses > 0,
        "{misses} misses at {checked} points"
    );
    // and the sound run on the same box passes
    let out = run(&s, &Limits::default());
    let (wrong, misses, checked) = check(&s, &out, CellTamper::None, 12, 3);
    assert!(checked > 0 && wrong == 0 && misses == 0);
    let c = spec(
        Region::Shape {
            valence: 5,
            lo: 0.2,
            hi: 0.4,
        },
        1e-3,
    );
    let out = run(&c, &limits);
    let (_, misses, checked) = check(&c, &out, CellTamper::DropSubspaceVariation, 12, 4);
    assert!(
        checked > 0 && misses > 0,
        "{misses} misses at {checked} points"
    );
}

#[test]
fn cli_writes_the_charmap_column() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("v.toml");
    fs::write(
        &spec,
        "scheme = \"nurds\"\nvalence = 3\nbox = [[0.3, 0.36], [0.3, 0.36], [0.3, 0.36]]\nproperties = [\"class\", \"charmap\"]\nmin_width = 0.01\n",
    )
    .unwrap();
    let out = dir.path().join("o");
    let (code, _, stderr) = common::run(&[
        "verify",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let text = fs::read_to_string(out.join("cells.csv")).unwrap();
    assert!(text.starts_with("lo0,lo1,lo2,hi0,hi1,hi2,verdict,class,charmap\n"));
    assert!(
        text.lines().skip(1).all(|l| l.ends_with(",certified")),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let f = summary["property_volume_fraction"]["charmap"]["certified"]
        .as_f64()
        .unwrap();
    assert!((f - 1.0).abs() < 1e-12, "{f}");
}
