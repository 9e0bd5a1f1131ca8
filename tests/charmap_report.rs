//! The `charmap` report figure: files, data consistent with `charmap::check`,
//! and bad specs rejected with the key named.

use subdiv_lab::charmap::check;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::report::figures::NoProgress;
use subdiv_lab::report::{generate, ReportSpec, RunInfo};
use subdiv_lab::schemes::LocalScheme;

const SPEC: &str = r#"
name = "rings"
seed = 3

[[figure]]
kind = "charmap"
id = "ring"
width = 900
height = 450
levels = 3
samples = 4
configs = [
  { scheme = "doo-sabin", valence = 5 },
  { scheme = "nurds", ratios = [0.2, 0.7, 0.4] },
]
"#;

fn csv(report: &subdiv_lab::report::RenderedReport, name: &str) -> Vec<Vec<String>> {
    let f = report
        .files
        .iter()
        .find(|f| f.path == name)
        .unwrap_or_else(|| panic!("{name} missing"));
    let mut r = csv::Reader::from_reader(f.bytes.as_slice());
    r.records()
        .map(|x| x.unwrap().iter().map(str::to_owned).collect())
        .collect()
}

#[test]
fn charmap_figure_files_and_data() {
    let spec = ReportSpec::parse(SPEC).unwrap();
    let report = generate(&spec, &RunInfo::default(), &NoProgress).unwrap();
    let names: Vec<&str> = report.files.iter().map(|f| f.path.as_str()).collect();
    for want in [
        "ring.svg",
        "ring.png",
        "ring.csv",
        "ring-jacobian.csv",
        "ring-verdict.csv",
    ] {
        assert!(names.contains(&want), "{want} missing: {names:?}");
    }
    let verdicts = csv(&report, "ring-verdict.csv");
    let schemes = [
        LocalScheme::<f64>::doo_sabin(5).unwrap(),
        LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4]).unwrap()),
    ];
    for (row, s) in verdicts.iter().zip(&schemes) {
        let r = check(s).unwrap();
        assert_eq!(row[6], r.verdict.to_string());
        assert_eq!(row[5], r.winding_number.unwrap().to_string());
    }
    // outlines: 3 levels x 3n patches per configuration; all Jacobian samples positive
    let outline = csv(&report, "ring.csv");
    let patches = |cfg: &str| {
        let mut set = std::collections::HashSet::new();
        for r in outline.iter().filter(|r| r[0] == cfg) {
            set.insert((r[2].clone(), r[3].clone()));
        }
        set.len()
    };
    assert_eq!(patches("0"), 3 * 15);
    assert_eq!(patches("1"), 3 * 9);
    let signs = csv(&report, "ring-jacobian.csv");
    assert!(!signs.is_empty());
    assert!(
        signs.iter().all(|r| r[5] == "1"),
        "regular rings have positive samples"
    );
    // deeper levels are smaller (contraction by the subdominant eigenvalues)
    let radius = |cfg: &str, level: &str| {
        outline
            .iter()
            .filter(|r| r[0] == cfg && r[2] == level)
            .map(|r| {
                r[7].parse::<f64>()
                    .unwrap()
                    .hypot(r[8].parse::<f64>().unwrap())
            })
            .fold(0.0, f64::max)
    };
    assert!(radius("0", "1") < 0.6 * radius("0", "0"));
}

#[test]
fn bad_charmap_specs_name_the_key() {
    for (bad, key) in [
        ("levels = 0", "levels"),
        ("samples = 100", "samples"),
        ("columns = 9", "columns"),
    ] {
        let text = format!(
            "name = \"x\"\n[[figure]]\nkind = \"charmap\"\n{bad}\nconfigs = [{{ scheme = \"doo-sabin\", valence = 4 }}]\n"
        );
        let e = ReportSpec::parse(&text)
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(e.contains(key), "{bad}: {e}");
    }
    let e = ReportSpec::parse("name = \"x\"\n[[figure]]\nkind = \"charmap\"\nconfigs = []\n")
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(e.contains("configs"), "{e}");
}

#[test]
fn doo_sabin_only_figures_reject_catmull_clark_configs_at_parse_time() {
    // Regression: a convergence figure with a Catmull-Clark configuration used
    // to panic inside the contraction measurement (no face weights).
    for kind in ["charmap", "convergence"] {
        let text = format!(
            "name = \"x\"\n[[figure]]\nkind = \"{kind}\"\nconfigs = [{{ scheme = \"doo-sabin\", valence = 4 }}, {{ scheme = \"catmull-clark\", valence = 5 }}]\n"
        );
        let e = ReportSpec::parse(&text)
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line 4")
                && e.contains("configs[1].scheme")
                && e.contains("Doo-Sabin family"),
            "{kind}: {e}"
        );
    }
    let cc = subdiv_lab::schemes::LocalScheme::<f64>::adjustable_cc(5, 0.3).unwrap();
    let e = subdiv_lab::contraction::measure(&cc, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("Doo-Sabin-family"), "{e}");
}
