//! Certified verdicts over regions (math doc section 15): soundness against the exact
//! pointwise classifier (proptest), exact tiling of the written cells,
//! thread-count independence, the `--out` rules and the Catmull-Clark path
//! against `cc-study`.

use crate::common;

use num_traits::Zero;
use proptest::prelude::*;
use std::fs;
use std::path::Path;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::scalar::{f64_to_rational, Rational};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::exact::exact_verdict;
use subdiv_lab::verify::decide::Status;
use subdiv_lab::verify::spec::{Property, Region, VerifySpec};
use subdiv_lab::verify::{run, Limits};

fn nurds_spec(lo: Vec<f64>, hi: Vec<f64>, min_width: f64) -> VerifySpec {
    VerifySpec {
        name: "p".into(),
        region: Region::Ratios { lo, hi },
        properties: vec![Property::Class, Property::Separation],
        min_width,
        time_budget: None,
        symmetry: Default::default(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// A random point inside a random certified cell of a random box never
    /// disagrees with the exact classifier (class and separation).
    #[test]
    fn certified_cells_never_disagree_with_exact(
        n in 3usize..=5,
        corner in prop::collection::vec(0.02f64..0.7, 5),
        width in prop::collection::vec(0.05f64..0.28, 5),
        picks in prop::collection::vec((any::<prop::sample::Index>(), prop::collection::vec(0.0f64..=1.0, 5)), 6),
    ) {
        let lo: Vec<f64> = corner[..n].to_vec();
        let hi: Vec<f64> = lo.iter().zip(&width).map(|(a, w)| a + w).collect();
        let spec = nurds_spec(lo, hi, match n { 3 => 1.0 / 64.0, 4 => 1.0 / 16.0, _ => 1.0 / 8.0 });
        let out = run(&spec, &Limits::default());
        let decided: Vec<_> = out.cells.iter().filter(|c| c.status.iter().any(|(_, s)| *s != Status::Undecided)).collect();
        prop_assume!(!decided.is_empty());
        for (ix, t) in &picks {
            let cell = decided[ix.index(decided.len())];
            let r: Vec<Rational> = (0..n)
                .map(|k| {
                    let x = cell.lo[k] + t[k] * (cell.hi[k] - cell.lo[k]);
                    f64_to_rational(x.clamp(cell.lo[k], cell.hi[k])).unwrap()
                })
                .collect();
            let v = exact_verdict(&LocalScheme::nurds(EdgeRatios::new(r.clone()).unwrap()), None).unwrap();
            if let (Some(c), Some(e)) = (cell.class, v.class) {
                prop_assert_eq!(c, e, "cell {:?}..{:?} at {:?}", cell.lo, cell.hi, r);
            }
            for (p, s) in &cell.status {
                if *p == Property::Separation && *s != Status::Undecided {
                    if let Some(sep) = v.separated {
                        prop_assert_eq!(sep, *s == Status::Certified, "separation at {:?}", r);
                    }
                }
            }
        }
    }
}

fn write_spec(dir: &Path, text: &str) -> String {
    let p = dir.join("v.toml");
    fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

const SPEC3: &str = "name = \"t3\"\nscheme = \"nurds\"\nvalence = 3\nbox = [[0.05, 0.95], [0.2, 0.6], [0.1, 0.9]]\nproperties = [\"class\", \"separation\", \"theorem1\"]\nmin_width = 0.03\n";

/// One row of cells.csv: lower corner, upper corner, verdict.
type Row = (Vec<f64>, Vec<f64>, String);

/// Reads cells.csv: the header and the rows.
fn read_cells(path: &Path) -> (Vec<String>, Vec<Row>) {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let n = header.iter().filter(|h| h.starts_with("lo")).count();
    let rows = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let lo = f[..n].iter().map(|x| x.parse().unwrap()).collect();
            let hi = f[n..2 * n].iter().map(|x| x.parse().unwrap()).collect();
            (lo, hi, f[2 * n].to_owned())
        })
        .collect();
    (header, rows)
}

#[test]
fn cli_cells_tile_the_box_exactly_in_rationals() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), SPEC3);
    let out = dir.path().join("o");
    let (code, stdout, stderr) = common::run(&[
        "verify",
        &spec,
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "2",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("cells"), "{stdout}");
    let (header, rows) = read_cells(&out.join("cells.csv"));
    assert_eq!(
        header,
        [
            "lo0",
            "lo1",
            "lo2",
            "hi0",
            "hi1",
            "hi2",
            "verdict",
            "class",
            "separation",
            "theorem1"
        ]
    );
    let lo = [0.05, 0.2, 0.1];
    let hi = [0.95, 0.6, 0.9];
    let q = |x: f64| f64_to_rational(x).unwrap();
    let total: Rational = (0..3).map(|k| q(hi[k]) - q(lo[k])).product();
    let mut sum = Rational::zero();
    for (i, (a, b, _)) in rows.iter().enumerate() {
        for k in 0..3 {
            assert!(lo[k] <= a[k] && a[k] < b[k] && b[k] <= hi[k]);
        }
        sum += (0..3).map(|k| q(b[k]) - q(a[k])).product::<Rational>();
        for (c, d, _) in &rows[..i] {
            assert!(
                (0..3).any(|k| b[k] <= c[k] || d[k] <= a[k]),
                "cells {i} overlap"
            );
        }
    }
    assert_eq!(sum, total, "the cells' volumes do not add up to the box");
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["cells"].as_u64().unwrap() as usize, rows.len());
    let fractions: f64 = summary["volume_fraction"]
        .as_object()
        .unwrap()
        .values()
        .map(|v| v.as_f64().unwrap())
        .sum();
    assert!((fractions - 1.0).abs() < 1e-9);
    assert_eq!(
        summary["property_volume_fraction"]["theorem1"]["certified"].as_f64(),
        Some(1.0)
    );

    // one thread gives the same cells; a previous output is replaced in place
    let (code, _, stderr) = common::run(&[
        "verify",
        &spec,
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "1",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let (_, rows1) = read_cells(&out.join("cells.csv"));
    assert_eq!(rows, rows1);
}

#[test]
fn cli_refuses_a_foreign_directory_and_leaves_it_alone() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), SPEC3);
    let out = dir.path().join("d");
    fs::create_dir(&out).unwrap();
    fs::write(out.join("cells.csv"), "mine").unwrap();
    let (code, _, stderr) = common::run(&["verify", &spec, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(stderr.contains("not empty"), "{stderr}");
    assert_eq!(fs::read_to_string(out.join("cells.csv")).unwrap(), "mine");
    assert_eq!(fs::read_dir(&out).unwrap().count(), 1);
}

#[test]
fn cli_max_cells_stops_refinement_with_undecided_cells() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), SPEC3);
    let out = dir.path().join("o");
    let (code, stdout, stderr) = common::run(&[
        "verify",
        &spec,
        "--out",
        out.to_str().unwrap(),
        "--max-cells",
        "40",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("--max-cells"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["stopped"], "max_cells");
    assert!(summary["evaluated"].as_u64().unwrap() <= 40);
    assert!(summary["undecided_fraction"].as_f64().unwrap() > 0.0);
}

#[test]
fn cli_cc_family_agrees_with_cc_study() {
    let dir = tempfile::tempdir().unwrap();
    for n in [3usize, 4, 7] {
        let spec = write_spec(
            dir.path(),
            &format!("scheme = \"adjustable-cc\"\nvalence = {n}\nc_range = [0.001, 1.0]\nproperties = [\"class\", \"separation\"]\nmin_width = 1e-4\n"),
        );
        let out = dir.path().join(format!("cc{n}"));
        let (code, _, stderr) =
            common::run(&["verify", &spec, "--out", out.to_str().unwrap(), "--quiet"]);
        assert_eq!(code, 0, "{stderr}");
        let text = fs::read_to_string(out.join("cells.csv")).unwrap();
        assert!(text.starts_with("c_lo,c_hi,verdict,class,separation\n"));
        let iv = subdiv_lab::cc_study::standard_intervals(n, 200, 1e-9).unwrap();
        let mut certified = 0.0;
        for l in text.lines().skip(1) {
            let f: Vec<&str> = l.split(',').collect();
            let (a, b): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
            if f[2] == "standard" {
                assert!(
                    iv.iter().any(|i| i.lo <= a + 1e-6 && b <= i.hi + 1e-6),
                    "n={n}: [{a}, {b}] outside {iv:?}"
                );
                certified += b - a;
            } else {
                assert_eq!(f[2], "undecided");
            }
        }
        let study: f64 = iv.iter().map(|i| i.hi - i.lo.max(0.001)).sum();
        assert!(
            certified > study - 0.01,
            "n={n}: certified {certified} of {study}"
        );
    }
}
