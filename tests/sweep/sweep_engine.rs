//! A sweep's rows equal per-configuration `spectral::analyze` results.

use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{self, AnalyzeOptions, SpectrumPath};
use subdiv_lab::sweep::output::{self, split_csv_line};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

fn sweep_csv(spec: &str) -> (Vec<String>, Vec<Vec<String>>, Summary) {
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
    let rows = lines.map(|l| split_csv_line(l).unwrap()).collect();
    (header, rows, summary)
}

fn get<'a>(header: &[String], row: &'a [String], name: &str) -> &'a str {
    &row[header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"))]
}

fn num(header: &[String], row: &[String], name: &str) -> f64 {
    get(header, row, name).parse().unwrap()
}

/// Agreement of the structured fast path (sweep) and the full 4n x 4n path:
/// eigenvalues of modulus <= 1 of matrices with entries in [0, 1] and norm ~1,
/// computed by two backward-stable methods; well-separated eigenvalues agree to
/// a few hundred ulps times their condition number, which stays below ~1e3 on
/// this grid (ratios in [0.05, 0.95]).
const PATH_AGREEMENT: f64 = 1e-9;

#[test]
fn n3_grid_equals_per_configuration_analyze() {
    let spec = r#"
scheme = "nurds"
valences = [3]
[space]
kind = "ratios"
ratio_range = [0.05, 0.95]
[sampler]
kind = "grid"
points_per_axis = 7
[columns]
eigenvalues = 12
"#;
    let (h, rows, summary) = sweep_csv(spec);
    assert_eq!(rows.len(), 343);
    let structured = AnalyzeOptions {
        path: SpectrumPath::Structured,
        ..AnalyzeOptions::default()
    };
    let full = AnalyzeOptions::default();
    let mut compared_full = 0;
    for row in &rows {
        assert_eq!(get(&h, row, "error"), "");
        let r: Vec<f64> = ["r0", "r1", "r2"].iter().map(|c| num(&h, row, c)).collect();
        let scheme = LocalScheme::nurds(EdgeRatios::new(r).unwrap());
        // The structured analysis: the same numbers, bit for bit.
        let a = spectral::analyze(&scheme, &structured).unwrap();
        let class = get(&h, row, "class");
        assert!(class.starts_with(a.subdominant.class.name()), "{class}");
        assert_eq!(num(&h, row, "lambda1_re"), a.subdominant.lambda1.re);
        assert_eq!(num(&h, row, "lambda1_im"), a.subdominant.lambda1.im);
        assert_eq!(num(&h, row, "lambda2_re"), a.subdominant.lambda2.re);
        assert_eq!(num(&h, row, "lambda2_im"), a.subdominant.lambda2.im);
        assert_eq!(num(&h, row, "abs_lambda3"), a.subdominant.abs_lambda3);
        assert_eq!(num(&h, row, "gap"), a.subdominant.gap);
        assert_eq!(
            num(&h, row, "contraction_rate"),
            a.contraction.as_ref().unwrap().spectral_bound
        );
        for (k, z) in a.eigenvalues.iter().enumerate() {
            assert_eq!(num(&h, row, &format!("ev{k}_re")), z[0]);
            assert_eq!(num(&h, row, &format!("ev{k}_im")), z[1]);
        }
        // The full 4n x 4n analysis: an independent computation.
        let b = spectral::analyze(&scheme, &full).unwrap();
        if !b.subdominant.class.is_indeterminate() && !class.starts_with("indeterminate") {
            assert_eq!(
                class,
                b.subdominant.class.name(),
                "r = {:?}",
                scheme.ratios()
            );
            compared_full += 1;
        }
        // Near a double eigenvalue the two paths may differ by the engine's own
        // error radii (O(sqrt(eps)) at a defective one): use them where larger.
        let radius = |k: usize| {
            PATH_AGREEMENT.max(a.subdominant.radii[k.min(3)] + b.subdominant.radii[k.min(3)])
        };
        let close_k = |x: f64, y: f64, k: usize| (x - y).abs() <= radius(k);
        let close = |x: f64, y: f64| close_k(x, y, 1);
        // Conjugate pairs may come in either order: compare moduli and |im|.
        assert!(close(num(&h, row, "lambda1_re"), b.subdominant.lambda1.re));
        assert!(
            close(
                num(&h, row, "lambda1_im").abs(),
                b.subdominant.lambda1.im.abs()
            ),
            "{row:?} vs {:?}",
            b.subdominant
        );
        assert!(close_k(
            num(&h, row, "abs_lambda3"),
            b.subdominant.abs_lambda3,
            3
        ));
        assert!(close(
            num(&h, row, "contraction_rate"),
            b.contraction.as_ref().unwrap().spectral_bound
        ));
        for (k, z) in b.eigenvalues.iter().enumerate() {
            let kk = if k < 4 { k } else { 4 };
            let tol = |x: f64, y: f64| {
                if kk < 4 {
                    close_k(x, y, kk)
                } else {
                    (x - y).abs() <= PATH_AGREEMENT
                }
            };
            assert!(tol(num(&h, row, &format!("ev{k}_re")), z[0]), "ev{k}");
            assert!(
                tol(num(&h, row, &format!("ev{k}_im")).abs(), z[1].abs()),
                "ev{k}"
            );
        }
    }
    assert!(compared_full > 300, "{compared_full}");
    // The summary counts every row once and brackets every column.
    let counted: u64 = summary.classes["3"].values().sum();
    assert_eq!(counted, 343);
    let rate = summary
        .columns
        .iter()
        .find(|c| c.name == "contraction_rate")
        .unwrap();
    assert!(rate.max.unwrap() < 0.75);
    let id = rate.max_id.unwrap() as usize;
    assert_eq!(num(&h, &rows[id], "contraction_rate"), rate.max.unwrap());
}

#[test]
fn uniform_valences_match_the_closed_form_and_exact_certificate() {
    let spec = r#"
scheme = "cc-variant"
valences = { from = 3, to = 12 }
[space]
kind = "uniform"
[sampler]
kind = "grid"
points_per_axis = 1
[columns]
exact_certificate = true
"#;
    let (h, rows, summary) = sweep_csv(spec);
    assert_eq!(rows.len(), 10);
    for row in &rows {
        let n: f64 = get(&h, row, "valence").parse().unwrap();
        let want = 0.5 + (2.0 * std::f64::consts::PI / n).cos() / 4.0;
        assert!((num(&h, row, "lambda1_re") - want).abs() < 1e-13);
        assert_eq!(get(&h, row, "class"), "standard");
        assert_eq!(get(&h, row, "exact_class"), "standard");
        assert_eq!(get(&h, row, "exact_agrees"), "true");
    }
    assert_eq!(summary.errors, 0);
}

#[test]
fn exact_certificate_agrees_on_a_random_slice() {
    let spec = r#"
scheme = "nurds"
valences = [3, 5]
[space]
kind = "corner-intervals"
interval_range = [0.1, 10.0]
[sampler]
kind = "random"
count = 8
seed = 3
[columns]
exact_certificate = true
"#;
    let (h, rows, _) = sweep_csv(spec);
    let mut decided = 0;
    for row in &rows {
        assert_eq!(get(&h, row, "error"), "");
        let agrees = get(&h, row, "exact_agrees");
        assert_ne!(agrees, "false", "exact and float disagree: {row:?}");
        if agrees == "true" {
            decided += 1;
        }
    }
    assert!(decided >= 12, "{decided}");
}

/// The `charmap` column equals a direct `charmap::check` of each configuration,
/// and the uniform valences are C1.
#[test]
fn charmap_column_equals_direct_check() {
    let spec = r#"
scheme = "nurds"
valences = [3, 4, 6]
[space]
kind = "ratios"
ratio_range = [0.05, 0.95]
[sampler]
kind = "random"
count = 6
seed = 11
[columns]
charmap = true
"#;
    let (h, rows, _) = sweep_csv(spec);
    assert_eq!(rows.len(), 18);
    for row in &rows {
        assert_eq!(get(&h, row, "error"), "");
        let n: usize = get(&h, row, "valence").parse().unwrap();
        let r: Vec<f64> = (0..n).map(|i| num(&h, row, &format!("r{i}"))).collect();
        let direct =
            subdiv_lab::charmap::check(&LocalScheme::nurds(EdgeRatios::new(r).unwrap())).unwrap();
        assert_eq!(get(&h, row, "charmap_verdict"), direct.verdict.code());
        assert_eq!(
            num(&h, row, "charmap_winding"),
            direct.winding_number.unwrap() as f64
        );
        assert_eq!(
            num(&h, row, "charmap_min_jacobian"),
            direct.min_jacobian_coeff().unwrap()
        );
    }
    let uniform = r#"
scheme = "nurds"
valences = { from = 3, to = 8 }
[space]
kind = "uniform"
[sampler]
kind = "grid"
points_per_axis = 1
[columns]
charmap = true
"#;
    let (h, rows, _) = sweep_csv(uniform);
    assert_eq!(rows.len(), 6);
    for row in &rows {
        assert_eq!(get(&h, row, "charmap_verdict"), "c1", "{row:?}");
        assert_eq!(num(&h, row, "charmap_winding"), 1.0);
    }
}

#[test]
fn adjustable_cc_shape_sweep_equals_the_parameter_study() {
    use subdiv_lab::cc_study::study_point;
    use subdiv_lab::schemes::catmull_clark::fourier;
    let spec = r#"
scheme = "adjustable-cc"
valences = [3, 5, 8]
[space]
kind = "shape"
c_range = [0.0, 1.0]
[sampler]
kind = "grid"
points_per_axis = 5
[columns]
eigenvalues = 3
charmap = true
"#;
    let (h, rows, summary) = sweep_csv(spec);
    assert_eq!(rows.len(), 15);
    assert_eq!(summary.errors, 0);
    for row in &rows {
        let n: usize = get(&h, row, "valence").parse().unwrap();
        let c = num(&h, row, "c");
        let p = study_point(n, c).unwrap();
        assert_eq!(get(&h, row, "class"), p.class, "n = {n}, c = {c}");
        assert_eq!(num(&h, row, "lambda1_re"), p.lambda1[0]);
        assert_eq!(num(&h, row, "abs_lambda3"), p.abs_lambda3);
        assert_eq!(get(&h, row, "charmap_verdict"), p.charmap);
        let ev = fourier::spectrum(n, c).unwrap();
        for (k, z) in ev.iter().take(3).enumerate() {
            assert_eq!(num(&h, row, &format!("ev{k}_re")), z.re);
        }
        // c = 0 is not separated; every other grid value is certified C1
        let want = if c == 0.0 { "no_charmap" } else { "c1" };
        assert_eq!(p.charmap, want, "n = {n}, c = {c}");
    }
    let counted: u64 = summary.classes["5"].values().sum();
    assert_eq!(counted, 5);
}

#[test]
fn catmull_clark_family_spec_errors_name_the_key() {
    let base = r#"
scheme = "adjustable-cc"
valences = [3]
[space]
kind = "shape"
c_range = [0.0, 1.0]
[sampler]
kind = "grid"
points_per_axis = 3
"#;
    let err = |t: &str| SweepSpec::from_toml(t).unwrap_err().to_string();
    assert!(SweepSpec::from_toml(base).is_ok());
    let e = err(&base.replace("[0.0, 1.0]", "[0.5, 1.2]"));
    assert!(
        e.starts_with("space.c_range: bound 1.2 is outside [0, 1]"),
        "{e}"
    );
    let e = err(&base.replace("[0.0, 1.0]", "[0.6, 0.2]"));
    assert!(
        e.starts_with("space.c_range: lower bound 0.6 > upper bound 0.2"),
        "{e}"
    );
    let e = err(&base.replace("c_range = [0.0, 1.0]", ""));
    assert!(e.starts_with("space.c_range is required"), "{e}");
    let e = err(&base.replace("kind = \"shape\"", "kind = \"ratios\""));
    assert!(e.starts_with("space.kind: scheme adjustable-cc"), "{e}");
    let e = err(&base.replace("adjustable-cc", "nurds"));
    assert!(e.starts_with("space.kind: kind \"shape\""), "{e}");
    let e = err(&format!("{base}[columns]\nexact_certificate = true\n"));
    assert!(e.starts_with("columns.exact_certificate"), "{e}");
    // Catmull-Clark proper: uniform space only
    let cc = base
        .replace("adjustable-cc", "catmull-clark")
        .replace(
            "kind = \"shape\"\nc_range = [0.0, 1.0]",
            "kind = \"uniform\"",
        )
        .replace("points_per_axis = 3", "points_per_axis = 1");
    let (h, rows, _) = sweep_csv(&cc);
    assert_eq!(rows.len(), 1);
    assert_eq!(get(&h, &rows[0], "class"), "standard");
    let stam = subdiv_lab::schemes::catmull_clark::fourier::stam_subdominant(3);
    assert!((num(&h, &rows[0], "lambda1_re") - stam).abs() < 1e-14);
}

/// Corner-interval sweeps write the edge ratios `r_i` the scheme is built
/// from, after the intervals: `r_i = q_(i+1) / (p_i + q_(i+1))`,
/// empty beyond the row's valence; and a ratios-space evaluation of those
/// `r_i` gives the row's spectrum (an independent route to the same matrix).
#[test]
fn corner_interval_sweeps_write_the_edge_ratios() {
    let spec = r#"
scheme = "nurds"
valences = [3, 5]
[space]
kind = "corner-intervals"
interval_range = [0.05, 20.0]
[sampler]
kind = "random"
count = 25
seed = 11
"#;
    let (h, rows, summary) = sweep_csv(spec);
    let names: Vec<&str> = h.iter().map(String::as_str).collect();
    assert_eq!(
        &names[..17],
        &[
            "id", "valence", "p0", "p1", "p2", "p3", "p4", "q0", "q1", "q2", "q3", "q4", "r0",
            "r1", "r2", "r3", "r4"
        ]
    );
    assert_eq!(names[17], "class");
    // The r_i enter the summary's extremes like the other numeric columns.
    let json = serde_json::to_value(&summary).unwrap();
    assert!(json["columns"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["name"] == "r4" && c["count"] == 25));
    // Relative error of the r_i against the formula evaluated here: the two
    // evaluations may round differently (a division and an addition, each
    // within half an ulp), so 4 ulps of 2^-52.
    const REL_TOL: f64 = 4.0 * f64::EPSILON;
    let mut checked = 0;
    for row in &rows {
        let n: usize = get(&h, row, "valence").parse().unwrap();
        let f = |name: String| get(&h, row, &name).parse::<f64>().unwrap();
        let mut r = Vec::new();
        for i in 0..5 {
            let cell = get(&h, row, &format!("r{i}"));
            if i >= n {
                assert_eq!(cell, "", "r{i} beyond valence {n}");
                continue;
            }
            let (p, q) = (f(format!("p{i}")), f(format!("q{}", (i + 1) % n)));
            let want = q / (p + q);
            let got: f64 = cell.parse().unwrap();
            assert!(
                (got - want).abs() <= REL_TOL * want,
                "r{i}: {got} vs {want}"
            );
            r.push(got);
            checked += 1;
        }
        // The same matrix through the ratios: the same subdominant spectrum.
        let s = LocalScheme::nurds(EdgeRatios::new(r).unwrap());
        let structured = AnalyzeOptions {
            path: SpectrumPath::Structured,
            ..AnalyzeOptions::default()
        };
        let a = spectral::analyze(&s, &structured).unwrap();
        let l1 = num(&h, row, "lambda1_re");
        // Ratios rebuilt from their rounded values (s_i = 1 - r_i recomputed):
        // the matrix differs by rounding, a simple eigenvalue by a few 1e-16;
        // 1e-12 leaves a wide margin, and the engine's error radius covers a
        // near-double one.
        const EIG_TOL: f64 = 1e-12;
        let tol = EIG_TOL.max(2.0 * a.subdominant.radii[0]);
        let got = a.subdominant.lambda1.re;
        assert!((got - l1).abs() <= tol, "{got} vs {l1}");
    }
    assert_eq!(checked, 25 * 3 + 25 * 5);
}

/// The `curvature` columns are the curvature verdict of `analyze` (on the
/// second-order matrix, math doc section 13.5), whether the row's
/// classification is made for other columns (and reused) or not: the
/// adjustable scheme at `n = 3` across the crossing `c = 0.63123`, where the
/// one-ring alone says `zero`.
#[test]
fn curvature_columns_equal_the_verdict_with_and_without_classification() {
    for classification in [true, false] {
        let spec = format!(
            "scheme = \"adjustable-cc\"\nvalences = [3, 5]\n[space]\nkind = \"shape\"\nc_range = [0.5, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 9\n[columns]\nclassification = {classification}\ngap = false\ncontraction = false\ncurvature = true\n"
        );
        let (header, rows, _) = sweep_csv(&spec);
        assert_eq!(rows.len(), 18);
        let mut unbounded_at_3 = 0;
        for row in &rows {
            let n: usize = get(&header, row, "valence").parse().unwrap();
            let c = num(&header, row, "c");
            let s = LocalScheme::adjustable_cc(n, c).unwrap();
            let a = spectral::analyze(&s, &AnalyzeOptions::default()).unwrap();
            let k = &a.curvature;
            assert_eq!(get(&header, row, "curvature_verdict"), k.verdict.as_str());
            assert!((num(&header, row, "curvature_mu") - k.mu).abs() < 1e-14);
            let ratio = num(&header, row, "curvature_ratio");
            assert!((ratio - k.mu_over_lambda_squared).abs() < 1e-13);
            if n == 3 && k.verdict.as_str() == "unbounded" {
                assert!(c > 0.6312, "c = {c}");
                unbounded_at_3 += 1;
            }
        }
        // c = 0.65, 0.7, .., 0.9
        assert_eq!(unbounded_at_3, 6, "classification = {classification}");
    }
}
