use super::*;
use crate::schemes::LocalScheme;

const CC: &str = include_str!("../../../analysis/schemes/catmull-clark.toml");
const LOOP: &str = include_str!("../../../analysis/schemes/loop.toml");

fn shared(text: &str) -> Arc<SchemeFile> {
    SchemeFile::parse_shared(text).unwrap()
}

/// The shipped Catmull-Clark file gives the built-in's matrices: exactly
/// equal in rationals (one-ring and patch), and in `f64` within a few
/// rounding errors (the built-in sums its vertex row from the rules' `Q` and
/// `R` terms, the file evaluates each weight once).
#[test]
fn catmull_clark_file_is_the_builtin() {
    let file = shared(CC);
    assert_eq!(file.topology(), Topology::Quad);
    for n in 3..=12 {
        let s = file.at(n).unwrap();
        let b = LocalScheme::<f64>::catmull_clark(n).unwrap();
        let (xs, xb) = (
            s.exact_local_matrix().unwrap().unwrap(),
            b.exact_local_matrix().unwrap().unwrap(),
        );
        assert_eq!(xs.matrix(), xb.matrix(), "n = {n}");
        assert_eq!(xs.rows(), xb.rows());
        let (ps, pb) = (
            s.exact_second_order_matrix().unwrap().unwrap(),
            b.exact_second_order_matrix().unwrap().unwrap(),
        );
        assert_eq!(ps.matrix(), pb.matrix(), "patch, n = {n}");
        let (fs, fb) = (s.local_matrix().unwrap(), b.local_matrix().unwrap());
        let d = (fs.matrix() - fb.matrix()).abs().max();
        assert!(d <= 4.0 * f64::EPSILON, "n = {n}: {d}");
        assert_eq!(s.regular_part_spectrum(), b.regular_part_spectrum());
        assert_eq!(s.cost_model(), b.cost_model());
    }
}

/// The shipped Loop file gives the built-in's two-ring matrix bit for bit
/// (its formula is the built-in's `beta_n`, evaluated in the same order).
#[test]
fn loop_file_is_the_builtin_bit_for_bit() {
    let file = shared(LOOP);
    for n in 3..=12 {
        let s = file.at(n).unwrap();
        let b = crate::schemes::LocalScheme::loop_subdivision(n).unwrap();
        let (ms, mb) = (s.local_matrix().unwrap(), b.local_matrix().unwrap());
        assert_eq!(ms.rows(), mb.rows());
        let same = ms
            .matrix()
            .iter()
            .zip(mb.matrix().iter())
            .all(|(x, y)| x.to_bits() == y.to_bits());
        assert!(same, "n = {n}");
        assert!(s.exact_local_matrix().is_none());
        assert_eq!(s.cost_model(), b.cost_model());
    }
}

fn quad(own: &str, edge: &str, face: &str) -> String {
    format!("name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"{own}\"\nedge = \"{edge}\"\nface = \"{face}\"\n")
}

#[test]
fn every_refusal_names_the_key_and_the_valence() {
    let cases: Vec<(String, &str)> = vec![
        (quad("1", "1/n", "0"), "vertex at valence 3: the weights self + n*edge + n*face sum to 2, not 1"),
        (quad("1 - 1/(n-5)", "1/(n*(n-5))", "0"), "vertex.self at valence 5: division by zero"),
        (quad("1 - m", "0", "0"), "vertex.self: unknown variable m"),
        (quad("1 + 0*sqrt(4-n)", "0", "0"), "vertex.self at valence 5: the weight is NaN"),
        (
            quad("cos(0) + 1e-9", "0", "0"),
            "vertex at valence 3: the weights self + n*edge + n*face sum to 1.000000001 in f64, not 1 within 1e-12",
        ),
        ("topology = \"quad\"\n[vertex]\n".into(), "name: missing key"),
        ("name = \"t\"\n[vertex]\n".into(), "topology: missing key"),
        ("name = \"t\"\ntopology = \"quad\"\n".into(), "vertex: missing key"),
        ("name = \"t\"\ntopology = \"hex\"\n[vertex]\n".into(), "topology: \"hex\" is not a topology"),
        ("name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1\"\nedge = \"0\"\n".into(), "vertex.face: missing key"),
        ("colour = \"red\"\n".to_owned() + &quad("1", "0", "0"), "colour: unknown key"),
        (quad("1", "0", "0") + "colour = \"red\"\n", "vertex.colour: unknown key (known: self, edge, face)"),
        (
            "name = \"t\"\ntopology = \"triangle\"\n[vertex]\nself = \"1\"\nedge = \"0\"\nface = \"0\"\n".into(),
            "vertex.face: a triangle scheme has no face-diagonal neighbours",
        ),
        ("name = \"loop\"\ntopology = \"triangle\"\n".into(), "name: \"loop\" is a built-in scheme's name"),
        ("name = 3\n".into(), "name: must be a string, got a integer"),
        ("name = \"t\n".into(), "scheme file: not valid TOML (line 1"),
        (quad("1", "0", "0").replace("edge = \"0\"", "edge = 0"), "vertex.edge: must be a string"),
    ];
    for (text, want) in cases {
        let e = SchemeFile::parse(&text).unwrap_err().to_string();
        assert!(e.starts_with(want), "{text:?}\n got: {e}\nwant: {want}");
        assert!(!e.contains('\n'), "{e}");
    }
    // A rule that breaks only above the load-time check is refused when the
    // configuration is made, naming the valence.
    let late = shared(&quad("1 - 1/(n-40)", "1/(n*(n-40))", "0"));
    assert_eq!(
        late.at(40).unwrap_err().to_string(),
        "vertex.self at valence 40: division by zero"
    );
    assert!(late.at(41).is_ok());
    assert_eq!(
        late.at(2).unwrap_err().to_string(),
        "valence: must be at least 3, got 2"
    );
}
