//! Speed of the Loop-subdivision local analysis: the two-ring matrix, the
//! closed-form spectrum from the Fourier blocks, and the certified
//! characteristic map (math doc section 11).
//!
//! Run: `cargo bench --bench loop_subdivision`.

use subdiv_lab::charmap::loop_subdivision as charmap;
use subdiv_lab::schemes::loop_subdivision::{fourier, matrix};

fn main() {
    divan::main();
}

#[divan::bench(args = [3, 8, 32])]
fn two_ring_matrix(n: usize) -> f64 {
    let m = matrix::two_ring_matrix(divan::black_box(n)).expect("valence");
    m.matrix()[(0, 0)]
}

#[divan::bench(args = [3, 8, 32])]
fn spectrum(n: usize) -> usize {
    fourier::spectrum(divan::black_box(n))
        .expect("valence")
        .len()
}

#[divan::bench(args = [3, 8, 32], sample_count = 20)]
fn certify(n: usize) -> Option<i64> {
    charmap::check(divan::black_box(n))
        .expect("check")
        .winding_number
}
