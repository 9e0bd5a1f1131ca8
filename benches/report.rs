//! Speed of the report generator (the target: the default report finishes in
//! under 2 minutes on a 2-core machine in release mode).
//!
//! Run: `cargo bench --bench report`. Measures the whole in-memory generation
//! of `analysis/default.toml` (all analyses, SVG + PNG rendering, CSV, HTML,
//! manifest; no file writing) and its most expensive figure kinds separately.

use subdiv_lab::report::figures::NoProgress;
use subdiv_lab::report::{generate, ReportSpec, RunInfo};

fn main() {
    divan::main();
}

fn default_spec() -> ReportSpec {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/analysis/default.toml"
    ))
    .expect("analysis/default.toml");
    ReportSpec::parse(&text).expect("default spec parses")
}

/// The whole default report, in memory.
#[divan::bench(sample_count = 5)]
fn default_report(bencher: divan::Bencher) {
    let spec = default_spec();
    bencher.bench(|| generate(&spec, &RunInfo::default(), &NoProgress).expect("report"));
}

/// One knot map (3 slices of 81 x 81 n = 3 classifications) with rendering.
#[divan::bench(sample_count = 10)]
fn knot_map_81(bencher: divan::Bencher) {
    let spec = ReportSpec::parse(
        "name = \"b\"\n[[figure]]\nkind = \"knot-map\"\nslices = [[0.2], [0.5], [0.8]]\ngrid = 81\n",
    )
    .expect("spec");
    bencher.bench(|| generate(&spec, &RunInfo::default(), &NoProgress).expect("report"));
}

/// The valence sweep n = 3..64 with 24 random knot sets per n.
#[divan::bench(sample_count = 5)]
fn valence_3_to_64(bencher: divan::Bencher) {
    let spec = ReportSpec::parse(
        "name = \"b\"\n[[figure]]\nkind = \"subdominant-vs-valence\"\nvalence = [3, 64]\nsamples = 24\n",
    )
    .expect("spec");
    bencher.bench(|| generate(&spec, &RunInfo::default(), &NoProgress).expect("report"));
}
