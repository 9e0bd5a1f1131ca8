//! The targets of `verify` (math doc section 15), printed as numbers
//! (not a divan micro-benchmark: one run of each target takes seconds to
//! minutes). Run: `cargo bench --bench verify [-- NAME..]` with NAME among
//! `n3`, `n4`, `n5`, `n6`, `n7`, `n8`, `cc` (default: `n3 cc`). Threads: the
//! rayon default (set `RAYON_NUM_THREADS=2` for the reference runs).

use subdiv_lab::verify::spec::{Region, VerifySpec};
use subdiv_lab::verify::{run, summary, Limits};

fn spec_text(name: &str) -> Option<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/specs");
    match name {
        "n3" => std::fs::read_to_string(format!("{dir}/verify-n3.toml")).ok(),
        "n4" | "n5" | "n6" | "n7" | "n8" => {
            let n: usize = name[1..].parse().ok()?;
            let text = std::fs::read_to_string(format!("{dir}/verify-{name}.toml")).ok()?;
            debug_assert!(text.contains(&format!("valence = {n}")));
            Some(text)
        }
        _ => None,
    }
}

fn report(spec: &VerifySpec, limits: &Limits) {
    let out = run(spec, limits);
    let s = summary(spec, &out);
    println!(
        "{:>10} n={:<2} cells {:>8} evaluated {:>8} undecided {:>7.3}% certified-class {:>7.3}% separation {:>7.3}% depth {:>2} {:>7.1} s{}",
        spec.name,
        spec.valence(),
        s.cells,
        s.evaluated,
        100.0 * s.undecided_fraction,
        100.0 * (1.0 - s.undecided_fraction),
        100.0 * s.property_volume_fraction.get("separation").and_then(|m| m.get("certified")).copied().unwrap_or(0.0),
        s.deepest_level,
        s.seconds,
        match s.stopped {
            Some(stop) => format!(" (stopped: {stop:?})"),
            None => String::new(),
        }
    );
}

fn main() {
    let mut names: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    if names.is_empty() {
        names = vec!["n3".into(), "cc".into()];
    }
    let limits = Limits::default();
    for name in &names {
        if name == "cc" {
            let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/specs");
            let text = std::fs::read_to_string(format!("{dir}/verify-cc.toml")).expect("spec");
            let base = VerifySpec::parse(&text).expect("valid spec");
            for n in 3..=16 {
                let mut spec = base.clone();
                if let Region::Shape { valence, .. } = &mut spec.region {
                    *valence = n;
                }
                let out = run(&spec, &limits);
                let c_lo = out
                    .cells
                    .iter()
                    .filter(|c| c.class.is_some())
                    .map(|c| c.lo[0])
                    .fold(f64::INFINITY, f64::min);
                let s = summary(&spec, &out);
                println!(
                    "{:>10} n={n:<2} standard certified on {:.4}% of [0.001, 1] (lowest certified c {c_lo:.5}), {} cells, {:.3} s",
                    spec.name,
                    100.0 * (1.0 - s.undecided_fraction),
                    s.cells,
                    s.seconds
                );
            }
            continue;
        }
        match spec_text(name) {
            Some(text) => report(&VerifySpec::parse(&text).expect("valid spec"), &limits),
            None => eprintln!("unknown target {name}"),
        }
    }
}
