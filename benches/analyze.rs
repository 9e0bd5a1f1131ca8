//! Analyze throughput (configurations per second, one thread).
//!
//! `cargo bench --bench analyze`
//!
//! * `structured`: [`classify_scheme`] (face block, allocation-free kernel,
//!   condition numbers of lambda_1..3, classification) from random edge ratios;
//! * `full_values`: assemble `S_n` (4n x 4n) and all its eigenvalues with faer;
//! * `full_analyze`: the complete [`analyze`] (vectors, residuals, condition
//!   numbers, Theorem 1 certificate and 60-level measurement), small `n` only.

use divan::counter::ItemsCount;
use divan::Bencher;
use subdiv_lab::contraction::SplitMix64;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::eigen::{Eigen, EigenOptions};
use subdiv_lab::spectral::{analyze, classify_scheme, AnalyzeOptions};

fn main() {
    divan::main();
}

const SIZES: &[usize] = &[3, 5, 8, 16, 32, 64];
const POOL: usize = 64;

fn pool(n: usize) -> Vec<Vec<f64>> {
    let mut rng = SplitMix64::new(n as u64);
    (0..POOL)
        .map(|_| (0..n).map(|_| rng.uniform(0.01, 0.99)).collect())
        .collect()
}

#[divan::bench(args = SIZES, threads = 1)]
fn structured(bencher: Bencher, n: usize) {
    let ratios = pool(n);
    let mut k = 0;
    bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
        k = (k + 1) % POOL;
        let s = LocalScheme::nurds(EdgeRatios::new(ratios[k].clone()).unwrap());
        divan::black_box(classify_scheme(&s).unwrap())
    });
}

#[divan::bench(args = SIZES, threads = 1)]
fn full_values(bencher: Bencher, n: usize) {
    let ratios = pool(n);
    let mut k = 0;
    bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
        k = (k + 1) % POOL;
        let s = LocalScheme::nurds(EdgeRatios::new(ratios[k].clone()).unwrap());
        let m = s.matrix().unwrap().into_matrix();
        divan::black_box(Eigen::new(&m, EigenOptions::VALUES).unwrap())
    });
}

#[divan::bench(args = [3, 5, 8, 16], threads = 1, sample_count = 20)]
fn full_analyze(bencher: Bencher, n: usize) {
    let ratios = pool(n);
    let mut k = 0;
    bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
        k = (k + 1) % POOL;
        let s = LocalScheme::nurds(EdgeRatios::new(ratios[k].clone()).unwrap());
        divan::black_box(analyze(&s, &AnalyzeOptions::default()).unwrap())
    });
}
