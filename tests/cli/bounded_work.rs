//! Bounded work. Every spec shipped in `analysis/` runs (at its full size, or
//! with the `--limit` documented here and in the README), and the structured
//! path classifies the 7 x 7 matrix on which faer's SVD does not converge. Refusals of heavy work are rows of `tests/cli/hostile_inputs.rs`
//! (section bounded-work).

use crate::common;

use common::run;
use std::path::{Path, PathBuf};

fn analysis() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("analysis")
}

/// The test-time `--limit` of each shipped sweep spec (`None`: full size).
/// Full sizes (2-core reference machine, idle): n3-grid 0.2 s,
/// vertex-ep-sobol 0.1 s, boundary-k 0.02 s, random 1.9 s, cc-shape 3.3 s, n3-slice 2.8 s,
/// uniform-valences 4.2 s (the exact certificate up to n = 64); n3-slice is
/// limited here only to keep the suite cheap. The benchmark-sized sweep
/// (5 000 000 rows, 267 s on 2 threads) lives in `benches/specs/`, not in
/// `analysis/`; [`benchmark_sweep_spec_runs_with_a_limit`] covers it.
const SWEEP_LIMITS: &[(&str, Option<u64>)] = &[
    ("sweep-cc-shape.toml", Some(600)),
    ("sweep-n3-grid.toml", None),
    ("sweep-n3-slice.toml", Some(200)),
    ("sweep-boundary-k.toml", None),
    ("sweep-random.toml", Some(20_000)),
    ("sweep-uniform-valences.toml", None),
    ("sweep-vertex-ep-sobol.toml", None),
];

/// Report specs shipped in `analysis/`, run at full size by the default
/// suite (idle reference machine: default 3.5 s, charmap 0.1 s).
const REPORTS: &[&str] = &["default.toml", "charmap.toml"];

/// Report specs shipped in `analysis/` whose full-size run is heavy (idle
/// reference machine: ccss-bound 13 s, cc-study 24 s): run by
/// [`shipped_heavy_report_specs_run`], which is ignored by the default suite
/// and run by `.ci/run` with `--ignored`.
const HEAVY_REPORTS: &[&str] = &["ccss-bound.toml", "cc-study.toml"];

/// Shipped specs not run here, with the reason (none today).
const NOT_RUN: &[&str] = &[];

#[test]
fn every_shipped_spec_is_listed() {
    for entry in std::fs::read_dir(analysis()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if !name.ends_with(".toml") {
            continue;
        }
        let known = SWEEP_LIMITS.iter().any(|(s, _)| *s == name)
            || REPORTS.contains(&name.as_str())
            || HEAVY_REPORTS.contains(&name.as_str())
            || NOT_RUN.contains(&name.as_str());
        assert!(known, "{name} is shipped but not run by this test");
    }
}

#[test]
fn shipped_sweep_specs_run() {
    let dir = tempfile::tempdir().unwrap();
    for (spec, limit) in SWEEP_LIMITS {
        let path = analysis().join(spec);
        let out = dir.path().join(format!("{spec}.csv"));
        let mut args = vec![
            "sweep".to_owned(),
            path.to_string_lossy().into_owned(),
            "--out".to_owned(),
            out.to_string_lossy().into_owned(),
        ];
        if let Some(k) = limit {
            args.push("--limit".to_owned());
            args.push(k.to_string());
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, _, err) = run(&args);
        assert_eq!(code, 0, "{spec}: {err}");
        let text = std::fs::read_to_string(&out).unwrap();
        // Data rows: every line but the header.
        let rows = text.lines().count() - 1;
        assert!(rows > 0, "{spec}: no rows");
        if let Some(k) = limit {
            assert_eq!(rows as u64, *k, "{spec}");
        }
    }
}

/// `benches/specs/sweep-bench-large.toml` parses and runs (its first 20 000
/// rows); the full size is a benchmark, sharded (README).
#[test]
fn benchmark_sweep_spec_runs_with_a_limit() {
    let dir = tempfile::tempdir().unwrap();
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/specs/sweep-bench-large.toml");
    let out = dir.path().join("big.csv");
    let (code, _, err) = run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--limit",
        "20000",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        text.lines().filter(|l| !l.starts_with('#')).count() - 1,
        20_000
    );
}

/// Runs each report spec of `specs` (names in `analysis/`) at full size and
/// asserts exit 0.
fn run_report_specs(specs: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    for spec in specs {
        let out = dir.path().join(spec);
        let path = analysis().join(spec);
        let (code, _, err) = run(&[
            "report",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        assert_eq!(code, 0, "{spec}: {err}");
    }
}

#[test]
fn shipped_report_specs_run() {
    run_report_specs(REPORTS);
}

#[test]
#[ignore = "heavy full-size run (about 40 s); .ci/run runs it with --ignored"]
fn shipped_heavy_report_specs_run() {
    run_report_specs(HEAVY_REPORTS);
}

/// faer's SVD does not converge on the 7 x 7 matrix of the rank test; the
/// Jacobi fallback gives the same verdict as the full path.
#[test]
fn structured_path_survives_the_svd_failure() {
    let base = [
        "analyze",
        "--scheme",
        "adjustable-cc",
        "--valence",
        "3",
        "--c",
        "0.22986",
    ];
    let mut structured = base.to_vec();
    structured.extend(["--path", "structured"]);
    let (code, out, err) = run(&structured);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("subdominant class: standard"), "{out}");
    let (code, full, err) = run(&base);
    assert_eq!(code, 0, "{err}");
    let verdict = |s: &str| {
        s.lines()
            .find(|l| l.starts_with("characteristic map:"))
            .map(str::to_owned)
    };
    assert_eq!(verdict(&out), verdict(&full));
    assert!(verdict(&out).is_some());
}

/// cc-study curves over a grid containing the point above finish and write
/// one row per point (a failing point would be an `error` row, not the end).
#[test]
fn cc_study_curves_write_every_row() {
    let (code, out, err) = run(&[
        "cc-study",
        "--n-min",
        "3",
        "--n-max",
        "3",
        "--samples",
        "200",
        "--curves",
    ]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].ends_with(",charmap,error"));
    assert_eq!(lines.len(), 1 + 201);
    assert!(lines[1..].iter().all(|l| l.ends_with(',')), "an error row");
}
