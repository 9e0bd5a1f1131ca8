//! The mesh figure kinds of the report: specs, data and bad input.

use subdiv_lab::report::figures::NoProgress;
use subdiv_lab::report::{generate, ReportSpec, RunInfo};

fn csv_of(spec: &str, name: &str) -> String {
    let spec = ReportSpec::parse(spec).unwrap();
    let report = generate(&spec, &RunInfo::default(), &NoProgress).unwrap();
    let f = report.files.iter().find(|f| f.path == name).unwrap();
    assert!(report.files.iter().any(|f| f.path.ends_with(".png")));
    assert!(report.files.iter().any(|f| f.path.ends_with(".svg")));
    String::from_utf8(f.bytes.clone()).unwrap()
}

#[test]
fn mesh_convergence_figure_stays_below_three_quarters() {
    let text = csv_of(
        r#"
name = "t"
[[figure]]
kind = "mesh-convergence"
id = "mc"
width = 800
height = 500
mesh = "truncated_icosahedron"
scheme = "nurds"
levels = 4
random_knots = 4.0
max_faces = 4
"#,
        "mc.csv",
    );
    let mut rows = 0;
    let mut valences = std::collections::BTreeSet::new();
    for line in text.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let rel: f64 = c[6].parse().unwrap();
        let bound: f64 = c[7].parse().unwrap();
        let lambda1: f64 = c[8].parse().unwrap();
        assert!(rel <= bound * (1.0 + 1e-12), "{line}");
        assert!(lambda1 > 0.0 && lambda1 < 0.75, "{line}");
        valences.insert((c[1].to_owned(), c[2].to_owned()));
        rows += 1;
    }
    // pentagon and hexagon face EPs and valence-3 vertex EPs are all represented
    assert!(valences.contains(&("5".into(), "0".into())), "{valences:?}");
    assert!(valences.contains(&("6".into(), "0".into())), "{valences:?}");
    assert!(valences.contains(&("3".into(), "1".into())), "{valences:?}");
    assert!(rows >= 4 * 4);
}

#[test]
fn mesh_picture_figure_has_both_panels() {
    let text = csv_of(
        r#"
name = "t"
[[figure]]
kind = "mesh-picture"
id = "mp"
width = 900
height = 450
mesh = "cube"
scheme = "cc-variant"
levels = 1
style = "wireframe"
"#,
        "mp.csv",
    );
    let panels: std::collections::BTreeSet<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(panels.len(), 2);
    // the cube from the default view shows 3 faces
    let faces0: std::collections::BTreeSet<&str> = text
        .lines()
        .skip(1)
        .filter(|l| l.starts_with("0,"))
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(faces0.len(), 3);
}

#[test]
fn bad_mesh_figure_specs_name_the_key() {
    for (body, needle) in [
        ("mesh = \"teapot\"\nscheme = \"nurds\"", "unknown mesh"),
        ("mesh = \"cube\"\nscheme = \"midedge\"", "unknown scheme"),
        (
            "mesh = \"cube\"\nscheme = \"loop\"",
            "no per-level statistics",
        ),
        (
            "mesh = \"cube\"\nscheme = \"doo-sabin\"\nrandom_knots = 2.0",
            "takes no knot intervals",
        ),
        (
            "mesh = \"cube\"\nscheme = \"nurds\"\nrandom_knots = 0.5",
            ">= 1",
        ),
        ("mesh = \"cube\"\nscheme = \"nurds\"\nlevels = 40", "levels"),
        ("mesh = \"torus\"\nscheme = \"nurds\"", "no extraordinary"),
    ] {
        let spec = format!("name = \"t\"\n[[figure]]\nkind = \"mesh-convergence\"\n{body}\n");
        let Err(e) = ReportSpec::parse(&spec) else {
            panic!("{body}: accepted");
        };
        let e = e.to_string();
        assert!(e.contains(needle) && e.contains("line"), "{body}: {e}");
    }
    let spec = "name = \"t\"\n[[figure]]\nkind = \"mesh-picture\"\nmesh = \"cube\"\nscheme = \"nurds\"\nstyle = \"oil\"\n";
    let Err(e) = ReportSpec::parse(spec) else {
        panic!("bad style accepted");
    };
    let e = e.to_string();
    assert!(e.contains("style"), "{e}");
}
