//! The boundary figure kinds of the report: `sector-spectra` (the leading
//! eigenvalues at boundary vertices against K, both rule sets) and
//! `crease-picture` (a tagged open mesh and its refinement).

use subdiv_lab::report::figures::NoProgress;
use subdiv_lab::report::{generate, ReportSpec, RunInfo};

fn csv_of(spec: &str, name: &str) -> String {
    let spec = ReportSpec::parse(spec).unwrap();
    let report = generate(&spec, &RunInfo::default(), &NoProgress).unwrap();
    assert!(report.files.iter().any(|f| f.path.ends_with(".png")));
    assert!(report.files.iter().any(|f| f.path.ends_with(".svg")));
    let f = report.files.iter().find(|f| f.path == name).unwrap();
    String::from_utf8(f.bytes.clone()).unwrap()
}

/// Where the standard rules lose the double subdominant 1/2 and BLZ keep
/// it: Catmull-Clark's regular boundary is K = 2, Loop's K = 3.
#[test]
fn sector_spectra_show_where_standard_rules_lose_one_half() {
    for (scheme, regular) in [("catmull-clark", 2usize), ("loop", 3)] {
        let text = csv_of(
            &format!("name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nid = \"s\"\nwidth = 800\nheight = 500\nscheme = \"{scheme}\"\nmax_faces = 6\n"),
            "s.csv",
        );
        let mut rows = 0;
        for line in text.lines().skip(1) {
            rows += 1;
            let c: Vec<&str> = line.split(',').collect();
            let k: usize = c[1].parse().unwrap();
            let (l1, l2): (f64, f64) = (c[2].parse().unwrap(), c[3].parse().unwrap());
            let half = (l1 - 0.5).abs() < 1e-9 && (l2 - 0.5).abs() < 1e-9;
            match c[0] {
                "blz" if k >= 2 => {
                    assert!(
                        half && c[5] == "standard" && c[6] == "c1",
                        "{scheme}: {line}"
                    )
                }
                "standard" if k == regular => {
                    assert!(
                        half && c[5] == "standard" && c[6] == "c1",
                        "{scheme}: {line}"
                    )
                }
                "standard" if k > regular => assert!(l1 > 0.5 + 1e-3, "{scheme}: {line}"),
                "standard" | "blz" => {}
                other => panic!("rules {other}"),
            }
        }
        assert_eq!(rows, 12);
    }
}

/// The refined panel has 4^L times the corners as faces (Catmull-Clark:
/// one quad per parent corner, then 4 per quad), and every infinitely sharp
/// edge of the cage is split into 2^L infinitely sharp edges; the
/// semi-sharp ones are down by L.
#[test]
fn crease_picture_refines_the_tagged_mesh() {
    let levels = 3;
    let spec = format!("name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nid = \"p\"\nwidth = 800\nheight = 500\nlevels = {levels}\n");
    let faces = csv_of(&spec, "p.csv");
    let edges = csv_of(&spec, "p-edges.csv");
    let count_faces = |panel: &str| {
        faces
            .lines()
            .skip(1)
            .filter(|l| l.starts_with(&format!("{panel},")) && l.split(',').nth(2) == Some("0"))
            .count()
    };
    // grid_quads: 19 quads and 2 triangles
    assert_eq!(count_faces("0"), 21);
    assert_eq!(count_faces("1"), (19 * 4 + 2 * 3) * 4usize.pow(levels - 1));
    let sharp = |panel: &str| -> Vec<f64> {
        edges
            .lines()
            .skip(1)
            .filter(|l| l.starts_with(&format!("{panel},")))
            .map(|l| l.split(',').nth(5).unwrap().parse().unwrap())
            .collect()
    };
    let (cage, fine) = (sharp("0"), sharp("1"));
    let infinite = |v: &[f64]| v.iter().filter(|&&s| s >= 10.0).count();
    assert!(infinite(&cage) > 0);
    assert_eq!(infinite(&fine), infinite(&cage) << levels);
    let semi_max = cage
        .iter()
        .copied()
        .filter(|&s| s < 10.0)
        .fold(0.0, f64::max);
    for s in fine.iter().filter(|&&s| s < 10.0) {
        assert!(*s <= semi_max - f64::from(levels) + 1e-6, "{s}");
    }
}
