//! Speed of the characteristic-map check (the sweep entry point `charmap::check`).
//!
//! Run: `cargo bench --bench charmap`.

use subdiv_lab::charmap::check;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::schemes::LocalScheme;

fn main() {
    divan::main();
}

fn nurds(n: usize) -> LocalScheme<f64> {
    let r: Vec<f64> = (0..n)
        .map(|k| 0.1 + 0.8 * ((k * 7 + 3) % 11) as f64 / 10.0)
        .collect();
    LocalScheme::nurds(EdgeRatios::new(r).expect("ratios in (0, 1)"))
}

#[divan::bench(args = [3, 5, 8, 16, 32])]
fn check_nurds(bencher: divan::Bencher, n: usize) {
    let s = nurds(n);
    bencher.bench(|| check(divan::black_box(&s)).expect("check"));
}

#[divan::bench(args = [3, 8, 32])]
fn check_doo_sabin(bencher: divan::Bencher, n: usize) {
    let s = LocalScheme::<f64>::doo_sabin(n).expect("valence");
    bencher.bench(|| check(divan::black_box(&s)).expect("check"));
}
