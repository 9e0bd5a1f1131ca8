//! Analyze throughput (configurations per second, one thread).
//!
//! `cargo bench --bench analyze`
//!
//! * `structured`: [`classify_scheme`] (face block, allocation-free kernel,
//!   condition numbers of lambda_1..3, classification) from random edge ratios;
//! * `structured_batches`: the same through [`classify_schemes_batch`],
//!   [`BATCH`] configurations per call (the sweep driver's path; items =
//!   configurations);
//! * `kernel_single` / `kernel_batch`: the eigenvalues of deflated face blocks
//!   (dimension `n - 1`) by [`KernelWorkspace::eigenvalues`] one at a time and
//!   by [`KernelWorkspace::eigenvalues_batch`] in lock step (items =
//!   matrices);
//! * `full_values`: assemble `S_n` (4n x 4n) and all its eigenvalues with faer;
//! * `full_analyze`: the complete [`analyze`] (vectors, residuals, condition
//!   numbers, Theorem 1 certificate and 60-level measurement), small `n` only.

use divan::counter::ItemsCount;
use divan::Bencher;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::eigen::{Eigen, EigenOptions};
use subdiv_lab::spectral::{
    analyze, classify_scheme, classify_schemes_batch, AnalyzeOptions, StructuredWorkspace,
};
use subdiv_lab::spectral::{KernelWorkspace, BATCH};

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
fn structured_batches(bencher: Bencher, n: usize) {
    let ratios = pool(n);
    let mut ws: [StructuredWorkspace; BATCH] = Default::default();
    let mut k = 0;
    bencher.counter(ItemsCount::new(BATCH)).bench_local(|| {
        k = (k + BATCH) % POOL;
        let schemes: [LocalScheme<f64>; BATCH] = std::array::from_fn(|i| {
            LocalScheme::nurds(EdgeRatios::new(ratios[k + i].clone()).unwrap())
        });
        divan::black_box(classify_schemes_batch(ws.each_mut(), schemes.each_ref()))
    });
}

/// Deflated face blocks (column major, dimension `n - 1`) of random NURDS configurations.
fn face_blocks(n: usize) -> Vec<Vec<f64>> {
    let mut ws = StructuredWorkspace::new();
    pool(n)
        .into_iter()
        .map(|r| {
            ws.face_nonunit(&LocalScheme::nurds(EdgeRatios::new(r).unwrap()))
                .unwrap();
            ws.deflated_matrix().to_vec()
        })
        .collect()
}

const KERNEL_SIZES: &[usize] = &[5, 8, 12, 16, 20, 24, 26, 28, 32];

#[divan::bench(args = KERNEL_SIZES, threads = 1)]
fn kernel_single(bencher: Bencher, n: usize) {
    let blocks = face_blocks(n);
    let mut ws = KernelWorkspace::new();
    let mut k = 0;
    bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
        k = (k + 1) % POOL;
        ws.input(n - 1).copy_from_slice(&blocks[k]);
        divan::black_box(ws.eigenvalues().unwrap().0[0])
    });
}

#[divan::bench(args = KERNEL_SIZES, threads = 1)]
fn kernel_batch(bencher: Bencher, n: usize) {
    let blocks = face_blocks(n);
    let mut ws: [KernelWorkspace; BATCH] = Default::default();
    let mut k = 0;
    bencher.counter(ItemsCount::new(BATCH)).bench_local(|| {
        k = (k + BATCH) % POOL;
        for (i, w) in ws.iter_mut().enumerate() {
            w.input(n - 1).copy_from_slice(&blocks[k + i]);
        }
        divan::black_box(KernelWorkspace::eigenvalues_batch(ws.each_mut()))
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
