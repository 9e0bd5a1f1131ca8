//! A scheme defined outside the crate (examples/own_scheme.rs, public API
//! only) gets the toolkit: its analysis agrees with the built-in
//! Catmull-Clark at Catmull-Clark's weights, sweeps record rows and errors,
//! and the spectrum figure renders.

use crate::example_scheme as own_scheme;

use own_scheme::VertexWeightCc;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::{analyze, AnalyzeOptions};
use subdiv_lab::sweep::{run_csv, Plan, SchemeFactory, SweepSpec};
use subdiv_lab::Scheme;

#[test]
fn analysis_matches_the_builtin_catmull_clark_at_its_weights() {
    for n in 3..=9 {
        let own = analyze(
            &VertexWeightCc::catmull_clark(n),
            &AnalyzeOptions::default(),
        )
        .unwrap();
        let builtin = analyze(
            &LocalScheme::<f64>::catmull_clark(n).unwrap(),
            &AnalyzeOptions::default(),
        )
        .unwrap();
        assert_eq!(own.scheme, "vertex-weight-cc");
        assert_eq!(own.eigenvalues.len(), builtin.eigenvalues.len());
        for (a, b) in own.eigenvalues.iter().zip(&builtin.eigenvalues) {
            assert!(
                (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12,
                "n={n}: {a:?} vs {b:?}"
            );
        }
        assert_eq!(own.subdominant.class, builtin.subdominant.class, "n={n}");
        // no closed-form stencil, no Theorem 1, no Fourier cross-check: reported as absent
        assert!(own.limit_weights_error.is_none());
        assert!(own.contraction.is_none() && own.fourier_deviation.is_none());
    }
}

/// The non-unit eigenvalues of the k = 0 Fourier block on `(v, mean e, mean f)`:
/// the 3 x 3 block `[[1 - b - g, b, g], [3/8, 1/2, 1/8], [1/4, 1/2, 1/4]]` has
/// eigenvalue 1 and the roots of `x^2 - (3/4 - b - g) x + (1 - 2b)/16`
/// (trace minus 1, determinant), worked out by hand.
fn k0_roots(b: f64, g: f64) -> [f64; 2] {
    let (sum, prod) = (0.75 - b - g, (1.0 - 2.0 * b) / 16.0);
    let d = (sum * sum - 4.0 * prod).sqrt();
    [(sum + d) / 2.0, (sum - d) / 2.0]
}

#[test]
fn the_vertex_rule_moves_only_the_k0_block() {
    let cc = analyze(
        &VertexWeightCc::catmull_clark(5),
        &AnalyzeOptions::default(),
    )
    .unwrap();
    for (b, g) in [(0.1, 0.05), (0.2, 0.05), (0.3, 0.05), (0.25, 0.0)] {
        let a = analyze(
            &VertexWeightCc::new(5, b, g).unwrap(),
            &AnalyzeOptions::default(),
        )
        .unwrap();
        // closed form vs dense: both k = 0 roots are in the spectrum
        for r in k0_roots(b, g) {
            let near = a
                .eigenvalues
                .iter()
                .map(|z| (z[0] - r).hypot(z[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(near < 1e-12, "b={b} g={g}: root {r} missing ({near})");
        }
        // the k = 1 pair (lambda_1 = lambda_2) does not move
        assert!((a.subdominant.lambda1.re - cc.subdominant.lambda1.re).abs() < 1e-12);
        assert_eq!(a.subdominant.class, cc.subdominant.class, "b={b} g={g}");
    }
    // b = g = 0: the larger k = 0 root (0.6545...) exceeds the k = 1 pair
    // (0.5500...), so the eigenstructure is no longer standard
    let top = k0_roots(0.0, 0.0)[0];
    let a = analyze(
        &VertexWeightCc::new(5, 0.0, 0.0).unwrap(),
        &AnalyzeOptions::default(),
    )
    .unwrap();
    assert!((a.subdominant.lambda1.re - top).abs() < 1e-12);
    assert_ne!(a.subdominant.class, cc.subdominant.class);
}

#[test]
fn the_spec_sweep_runs_the_scheme_and_records_errors_in_their_rows() {
    // The tutorial's plan: one row per valence, no characteristic ring (the
    // verdict says so instead of guessing).
    let csv = run_csv(&own_scheme::valence_sweep(0.3, 0.05).unwrap()).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 7);
    assert!(lines[0].starts_with("id,valence,class,"));
    assert!(lines[1].starts_with("0,3,"));
    assert!(lines[6].starts_with("5,8,"));
    assert!(
        lines[1..].iter().all(|l| l.contains(",no_charmap,")),
        "{csv}"
    );
    // A configuration the factory refuses is a row with its error.
    let spec = SweepSpec::from_toml(
        "scheme = \"catmull-clark\"\nvalences = [4, 5, 6]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n",
    )
    .unwrap();
    let cost = VertexWeightCc::catmull_clark(5).cost_model();
    let factory = SchemeFactory::new("vertex-weight-cc", cost, |n| {
        let beta = if n == 5 { 1.5 } else { 0.3 };
        Ok(Box::new(VertexWeightCc::new(n, beta, 0.05)?) as Box<dyn Scheme>)
    });
    let csv = run_csv(&Plan::with_scheme(spec, factory).unwrap()).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4);
    assert!(
        lines[2].starts_with("1,5,") && lines[2].contains("beta"),
        "{csv}"
    );
    assert!(
        !lines[1].contains("beta") && !lines[3].contains("beta"),
        "{csv}"
    );
}

#[test]
fn spectrum_figure_renders() {
    let s = VertexWeightCc::catmull_clark(4);
    let svg =
        subdiv_lab::report::figures::spectrum::spectrum_svg(&[&s as &dyn Scheme], (600, 400), "t")
            .unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("n=4"));
}

#[test]
fn the_default_cost_model_fits_the_matrix_and_sizes_the_estimates() {
    // (2n + 1) x (2n + 1) at n = 7, measured from the scheme's own matrix
    let model = VertexWeightCc::catmull_clark(7).cost_model();
    assert_eq!(model.dimension(7), 15.0);
    let e = subdiv_lab::budget::analyze(&model, 7, false);
    assert!(e.what.contains("15 x 15"), "{}", e.what);
    assert!(e.within_limits(
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        subdiv_lab::budget::MEMORY_LIMIT_BYTES
    ));
    // a valence a front end must refuse before building anything
    let big = subdiv_lab::budget::analyze(&model, 100_000, false);
    assert!(big.bytes > subdiv_lab::budget::MEMORY_LIMIT_BYTES);
}
