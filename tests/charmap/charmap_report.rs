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
fn convergence_figure_rejects_catmull_clark_configs_at_parse_time() {
    // A convergence figure with a Catmull-Clark configuration is refused at
    // parse time, not a panic inside the contraction measurement (no face
    // weights).
    let text = "name = \"x\"\n[[figure]]\nkind = \"convergence\"\nconfigs = [{ scheme = \"doo-sabin\", valence = 4 }, { scheme = \"catmull-clark\", valence = 5 }]\n";
    let e = ReportSpec::parse(text).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("line 4") && e.contains("configs[1].scheme") && e.contains("Doo-Sabin family"),
        "{e}"
    );
    let cc = subdiv_lab::schemes::LocalScheme::<f64>::adjustable_cc(5, 0.3).unwrap();
    let e = subdiv_lab::contraction::measure(&cc, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("Doo-Sabin-family"), "{e}");
    // the shape parameter is validated where it is written
    for (bad, want) in [
        (
            "{ scheme = \"adjustable-cc\", valence = 5 }",
            "configs[0].c",
        ),
        (
            "{ scheme = \"adjustable-cc\", valence = 5, c = 1.5 }",
            "configs[0].c",
        ),
        (
            "{ scheme = \"catmull-clark\", valence = 5, c = 0.5 }",
            "configs[0].c",
        ),
    ] {
        let text = format!("name = \"x\"\n[[figure]]\nkind = \"charmap\"\nconfigs = [{bad}]\n");
        let e = ReportSpec::parse(&text)
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "{bad}: {e}");
    }
}

#[test]
fn catmull_clark_family_rings_are_plotted_with_their_verdicts() {
    use subdiv_lab::charmap::catmull_clark::check;
    let text = "name = \"x\"\n[[figure]]\nkind = \"charmap\"\nid = \"cc\"\nwidth = 600\nheight = 400\nlevels = 2\nsamples = 4\nconfigs = [{ scheme = \"catmull-clark\", valence = 5 }, { scheme = \"adjustable-cc\", valence = 6, c = 0.25 }, { scheme = \"adjustable-cc\", valence = 4, c = 0.0 }]\n";
    let spec = ReportSpec::parse(text).unwrap();
    let r = generate(&spec, &RunInfo::default(), &NoProgress).unwrap();
    let verdicts = csv(&r, "cc-verdict.csv");
    assert_eq!(verdicts.len(), 3);
    assert_eq!(verdicts[0][6], check(5, 0.5).unwrap().verdict.to_string());
    assert_eq!(verdicts[1][6], check(6, 0.25).unwrap().verdict.to_string());
    assert!(
        verdicts[2][6].starts_with("no characteristic map"),
        "{:?}",
        verdicts[2]
    );
    // every sampled Jacobian of the two C1 rings has the ring's orientation
    let signs = csv(&r, "cc-jacobian.csv");
    assert!(signs.len() > 100);
    assert!(signs.iter().all(|row| row[5] == "1"), "a wrong-sign sample");
    // outlines: 3n cells per level, labelled Omega_m
    let outline = csv(&r, "cc.csv");
    let cells: std::collections::BTreeSet<(String, String, String)> = outline
        .iter()
        .filter(|row| row[0] == "0")
        .map(|row| (row[2].clone(), row[3].clone(), row[4].clone()))
        .collect();
    assert_eq!(cells.len(), 2 * 15);
    assert!(cells.iter().all(|c| c.2.starts_with("Omega")));
}
