//! Loop subdivision in sweep and report specs (`--scheme loop` wherever it
//! makes sense): a valence sweep's rows equal the per-scheme
//! analysis and Loop's closed form (math doc section 11), and report specs
//! draw Loop configurations and refine triangle meshes with Loop's rules.

use crate::common;

use subdiv_lab::charmap;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{self, AnalyzeOptions};
use subdiv_lab::sweep::output::{self, split_csv_line};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

const SPEC: &str = r#"
name = "loop-valences"
scheme = "loop"
valences = { from = 3, to = 12 }
[space]
kind = "uniform"
[sampler]
kind = "grid"
points_per_axis = 1
[columns]
eigenvalues = 4
charmap = true
"#;

/// Two backward-stable eigenvalue computations (the sweep's and `analyze`'s)
/// of a (3n+1)-matrix with entries in [0, 1] and a semisimple double
/// subdominant eigenvalue: they agree to a few hundred ulps.
const PATH_AGREEMENT: f64 = 1e-12;

pub(crate) fn rows(spec: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let plan = Plan::new(SweepSpec::from_toml(spec).unwrap());
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
    let mut out = Vec::new();
    layout.write_header(&mut out).unwrap();
    output::run(
        &plan,
        &layout,
        &eval,
        0..plan.total(),
        &mut out,
        &mut summary,
        &mut |_| {},
    )
    .unwrap();
    let text = String::from_utf8(out).unwrap();
    let mut lines = text.lines();
    let header = split_csv_line(lines.next().unwrap()).unwrap();
    (header, lines.map(|l| split_csv_line(l).unwrap()).collect())
}

#[test]
fn loop_valence_sweep_equals_analyze_and_the_closed_form() {
    let (header, rows) = rows(SPEC);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(rows.len(), 10);
    for (row, n) in rows.iter().zip(3usize..) {
        assert_eq!(row[col("valence")], n.to_string());
        assert_eq!(row[col("error")], "", "n = {n}");
        let s = LocalScheme::loop_subdivision(n).unwrap();
        let a = spectral::analyze(&s, &AnalyzeOptions::default()).unwrap();
        assert_eq!(row[col("class")], a.subdominant.class.name(), "n = {n}");
        let lambda: f64 = row[col("lambda1_re")].parse().unwrap();
        let closed = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
        assert!(
            (lambda - closed).abs() < PATH_AGREEMENT,
            "n = {n}: {lambda} vs {closed}"
        );
        assert!((lambda - a.subdominant.lambda1.re).abs() < PATH_AGREEMENT);
        let ev1: f64 = row[col("ev1_re")].parse().unwrap();
        assert!((ev1 - closed).abs() < PATH_AGREEMENT, "n = {n}: ev1 {ev1}");
        let report = charmap::check(&s).unwrap();
        assert_eq!(
            row[col("charmap_verdict")],
            report.verdict.code(),
            "n = {n}"
        );
        assert_eq!(row[col("charmap_winding")], "1.0", "n = {n}");
    }
}

#[test]
fn loop_is_refused_in_knot_spaces_and_for_the_exact_certificate() {
    let e = SweepSpec::from_toml(&SPEC.replace(
        "kind = \"uniform\"",
        "kind = \"ratios\"\nratio_range = [0.1, 0.9]",
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("space.kind: scheme loop takes no knot intervals"),
        "{e}"
    );
    let e = SweepSpec::from_toml(&format!("{SPEC}exact_certificate = true\n"))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("columns.exact_certificate"), "{e}");
}

#[test]
fn report_draws_loop_configurations_and_refines_with_loop() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let spec = dir.join("s.toml");
    std::fs::write(
        &spec,
        r#"name = "loop"
[[figure]]
kind = "spectrum"
configs = [{ scheme = "loop", valence = 5 }, { scheme = "loop", valence = 7 }]
[[figure]]
kind = "table"
configs = [{ scheme = "loop", valence = 6 }]
[[figure]]
kind = "mesh-picture"
mesh = "icosahedron"
scheme = "loop"
levels = 2
"#,
    )
    .unwrap();
    let out = dir.join("r");
    let (code, _, err) = common::run(&[
        "report",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let read = |f: &str| std::fs::read_to_string(out.join(f)).unwrap();
    let spectrum = read("spectrum-1.svg");
    assert!(
        spectrum.contains("Loop n=5") && spectrum.contains("Loop n=7"),
        "legend labels"
    );
    assert!(read("table-2.csv").contains("Loop n=6"));
    assert!(
        read("mesh-picture-3.svg").contains("loop x2: 320 faces"),
        "the mesh picture refines 20 -> 320 triangles"
    );
}
