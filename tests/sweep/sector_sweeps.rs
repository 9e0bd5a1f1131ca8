//! Sweeps of boundary, crease and corner sectors (`[sector]` specs): every
//! row is the sector analysis of its configuration, rebuilt here from the
//! row's `valence` (the face count K) and `angle` (degrees).

use subdiv_lab::boundary::analysis::analyze_sector;
use subdiv_lab::boundary::{RuleSet, SectorConfig, VertexKind};
use subdiv_lab::mesh::sharp::rules::SdcScheme;
use subdiv_lab::sweep::{run_csv, Plan, SweepSpec};

fn spec(scheme: &str, vertex: &str, rules: &str, faces: &str, space: &str, points: u64) -> String {
    format!(
        "scheme = \"{scheme}\"\n[sector]\nvertex = \"{vertex}\"\nrules = \"{rules}\"\nfaces = {faces}\n[space]\n{space}\n[sampler]\nkind = \"grid\"\npoints_per_axis = {points}\n[columns]\neigenvalues = 3\ncharmap = true\ncurvature = true\n"
    )
}

/// The rows of a sector sweep equal the sector analysis of the
/// configuration named by the row, column by column.
#[test]
fn rows_are_the_sector_analysis_of_their_configuration() {
    let cases = [
        (
            SdcScheme::CatmullClark,
            "catmull-clark",
            VertexKind::Boundary,
            RuleSet::Standard,
            "[1, 3, 5]",
            "kind = \"uniform\"",
            1,
        ),
        (
            SdcScheme::Loop,
            "loop",
            VertexKind::Crease,
            RuleSet::Blz,
            "{ from = 2, to = 4 }",
            "kind = \"uniform\"",
            1,
        ),
        (
            SdcScheme::Loop,
            "loop",
            VertexKind::Corner,
            RuleSet::Standard,
            "[2, 3]",
            "kind = \"corner-angle\"\nangle_range = [60.0, 300.0]",
            3,
        ),
        (
            SdcScheme::CatmullClark,
            "catmull-clark",
            VertexKind::Corner,
            RuleSet::Blz,
            "[3]",
            "kind = \"corner-angle\"\nangle_range = [45.0, 135.0]",
            2,
        ),
    ];
    for (sdc, scheme, kind, rules, faces, space, points) in cases {
        let text = spec(scheme, kind.name(), rules.name(), faces, space, points);
        let plan = Plan::new(SweepSpec::from_toml(&text).unwrap());
        let csv = run_csv(&plan).unwrap();
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| *h == name)
                .unwrap_or_else(|| panic!("{name} in {header:?}"))
        };
        let corner = kind == VertexKind::Corner;
        assert_eq!(header.contains(&"angle"), corner, "{header:?}");
        assert!(header.contains(&"charmap_swept_degrees"), "{header:?}");
        let mut rows = 0;
        for line in lines {
            rows += 1;
            let f: Vec<&str> = line.split(',').collect();
            let num = |name: &str| f[col(name)].parse::<f64>().unwrap();
            let k: usize = f[1].parse().unwrap();
            let counts = if kind == VertexKind::Crease {
                vec![k, k]
            } else {
                vec![k]
            };
            let angle = corner.then(|| num("angle"));
            let c = SectorConfig::new(sdc, kind, &counts, angle, rules).unwrap();
            let a = analyze_sector(&c).unwrap();
            let what = format!("{} (row {line})", c.describe());
            assert_eq!(f[col("error")], "", "{what}");
            let class = match &a.subdominant.class {
                subdiv_lab::spectral::SubdominantClass::Indeterminate { between, .. } => {
                    format!(
                        "indeterminate:{}/{}",
                        between.0.as_str(),
                        between.1.as_str()
                    )
                }
                other => other.name().to_owned(),
            };
            assert_eq!(f[col("class")], class, "{what}");
            assert_eq!(num("lambda1_re"), a.subdominant.lambda1.re, "{what}");
            assert_eq!(num("lambda2_re"), a.subdominant.lambda2.re, "{what}");
            assert_eq!(num("ev1_re"), a.eigenvalues[1][0], "{what}");
            assert_eq!(
                f[col("charmap_verdict")],
                a.charmap.verdict.as_str(),
                "{what}"
            );
            assert_eq!(
                f[col("curvature_verdict")],
                a.curvature.verdict.as_str(),
                "{what}"
            );
            assert_eq!(
                num("curvature_ratio").to_bits(),
                a.curvature.mu_over_lambda_squared.to_bits(),
                "{what}"
            );
        }
        let per_k = if corner { points as usize } else { 1 };
        assert_eq!(rows as u64, plan.total(), "{text}");
        assert_eq!(rows % per_k, 0);
    }
}

/// The figure the sweep is for: on a Catmull-Clark boundary the standard
/// rules keep the subdominant 1/2 only up to K = 2 and lose the
/// characteristic map's boundary beyond K = 3 (lambda1 > 1/2 from K = 3,
/// the map collapsing from K = 5), while BLZ keeps lambda1 = lambda2 = 1/2
/// (class standard, certified C1 map) for every K >= 2.
#[test]
fn standard_rules_lose_one_half_where_blz_keeps_it() {
    let run = |rules: &str| {
        let text = spec(
            "catmull-clark",
            "boundary",
            rules,
            "{ from = 2, to = 8 }",
            "kind = \"uniform\"",
            1,
        );
        run_csv(&Plan::new(SweepSpec::from_toml(&text).unwrap())).unwrap()
    };
    for (k, line) in (2..).zip(run("blz").lines().skip(1)) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[2], "standard", "K = {k}: {line}");
        assert!(
            (f[3].parse::<f64>().unwrap() - 0.5).abs() < 1e-12,
            "K = {k}: {line}"
        );
        assert!(line.contains(",c1,"), "K = {k}: {line}");
    }
    for (k, line) in (2..).zip(run("standard").lines().skip(1)) {
        let l1: f64 = line.split(',').nth(3).unwrap().parse().unwrap();
        if k == 2 {
            assert!((l1 - 0.5).abs() < 1e-12, "{line}");
        } else {
            assert!(l1 > 0.5 + 1e-3, "K = {k}: {line}");
        }
        if k >= 5 {
            assert!(line.contains(",boundary_collapses,"), "K = {k}: {line}");
        }
    }
}
