//! The `generic_charmap` column group of a sweep: each row carries what the
//! generic certificate (math doc section 20) says about that configuration,
//! and where both certificates decide, the ring certificate agrees.

use crate::loop_specs::rows;
use subdiv_lab::charmap::{self, generic};
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral;

fn spec(scheme: &str, valences: &str) -> String {
    format!(
        r#"
name = "generic-{scheme}"
scheme = "{scheme}"
valences = {valences}
[space]
kind = "uniform"
[sampler]
kind = "grid"
points_per_axis = 1
[columns]
classification = false
gap = false
contraction = false
charmap = true
generic_charmap = true
"#
    )
}

/// The printed form of an optional integer column.
fn cell(x: Option<i64>) -> String {
    x.map_or(String::new(), |v| format!("{:?}", v as f64))
}

/// The rows of a valence sweep `3..=8` of `scheme_name` equal the generic
/// certificate computed directly; with `all_c1`, every row is certified by
/// both certificates.
fn check(scheme_name: &str, all_c1: bool, build: impl Fn(usize) -> LocalScheme<f64>) {
    let (header, rows) = rows(&spec(scheme_name, "{ from = 3, to = 8 }"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(rows.len(), 6);
    for row in &rows {
        let n: usize = row[col("valence")].parse().unwrap();
        assert_eq!(row[col("error")], "", "{scheme_name} n = {n}");
        let s = build(n);
        let sub = spectral::classify_local(&s).unwrap();
        let g = generic::check(&s, &sub).unwrap();
        let at = format!("{scheme_name} n = {n}");
        assert_eq!(
            row[col("generic_charmap_verdict")],
            g.verdict.code(),
            "{at}"
        );
        assert_eq!(
            row[col("generic_charmap_orientation")],
            cell(g.orientation.map(i64::from)),
            "{at}"
        );
        assert_eq!(
            row[col("generic_charmap_winding")],
            cell(g.winding_number),
            "{at}"
        );
        assert_eq!(
            row[col("generic_charmap_level")],
            cell(g.level.map(i64::from)),
            "{at}"
        );
        let direct = charmap::certify(charmap::Method::Generic, &s, &sub);
        assert_eq!(direct.verdict_code(), g.verdict.code(), "{at}");
        if !all_c1 {
            continue;
        }
        assert_eq!(row[col("generic_charmap_verdict")], "c1", "{at}");
        assert_eq!(row[col("charmap_verdict")], "c1", "{at}");
        assert_eq!(
            row[col("generic_charmap_winding")],
            row[col("generic_charmap_orientation")],
            "{at}: a certified c1 map winds once, in its orientation"
        );
    }
}

#[test]
fn loop_rows_carry_the_generic_certificate() {
    check("loop", true, |n| LocalScheme::loop_subdivision(n).unwrap());
}

#[test]
fn catmull_clark_rows_carry_the_generic_certificate() {
    check("catmull-clark", true, |n| {
        LocalScheme::catmull_clark(n).unwrap()
    });
}

/// Butterfly's rows carry whatever the certificate decides, and at valence 3
/// never `c1`: the butterfly scheme is not C1 there (Zorin 2000).
#[test]
fn butterfly_rows_carry_the_generic_certificate() {
    check("butterfly", false, |n| LocalScheme::Butterfly {
        valence: n,
    });
    let (header, rows) = rows(&spec("butterfly", "[3]"));
    let verdict = header
        .iter()
        .position(|h| h == "generic_charmap_verdict")
        .unwrap();
    assert_ne!(rows[0][verdict], "c1");
}

#[test]
fn the_generic_columns_are_absent_unless_asked_for() {
    let plain = spec("loop", "[3]").replace("generic_charmap = true\n", "");
    let (header, _) = rows(&plain);
    assert!(header.iter().all(|h| !h.starts_with("generic_charmap")));
    assert!(header.iter().any(|h| h == "charmap_verdict"));
}
