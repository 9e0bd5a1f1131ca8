//! Catmull-Clark family: matrix assembly, Fourier fast path vs dense
//! eigenvalues, and one LP bound. Run: `cargo bench --bench ccfamily`.

use subdiv_lab::ccss_bound::bound::bound;
use subdiv_lab::schemes::catmull_clark::{fourier, one_ring_matrix};

fn main() {
    divan::main();
}

#[divan::bench(args = [8, 64, 256])]
fn one_ring_assembly(n: usize) {
    divan::black_box(one_ring_matrix::<f64>(divan::black_box(n), &0.5).unwrap());
}

#[divan::bench(args = [8, 64, 256])]
fn spectrum_fourier_closed_form(n: usize) {
    divan::black_box(fourier::spectrum(divan::black_box(n), 0.5).unwrap());
}

#[divan::bench(args = [8, 64, 256])]
fn spectrum_dense_faer(bencher: divan::Bencher, n: usize) {
    let s = one_ring_matrix::<f64>(n, &0.5).unwrap();
    let m = faer::Mat::<f64>::from_fn(2 * n + 1, 2 * n + 1, |i, j| s.matrix()[(i, j)]);
    bencher.bench(|| divan::black_box(m.eigenvalues().unwrap()));
}

#[divan::bench(args = [8, 64])]
fn fourier_transform_of_assembled(bencher: divan::Bencher, n: usize) {
    let s = one_ring_matrix::<f64>(n, &0.5).unwrap();
    bencher.bench(|| divan::black_box(fourier::transform(s.matrix()).unwrap()));
}

#[divan::bench(args = [5, 20], sample_count = 5)]
fn ccss_bound_one_level(n: usize) {
    divan::black_box(bound(divan::black_box(n), 1).unwrap());
}
