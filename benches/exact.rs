//! The exact certificates of `analyze --exact` ([`exact_verdict`]): wall time
//! per configuration at n = 8, 16, 32, 64.
//!
//! `cargo bench --bench exact`
//!
//! * `uniform`: uniform knot intervals (all ratios 1/2; double eigenvalues,
//!   the standard class with the exact rank of the double root);
//! * `random_rational`: the knot intervals of `benches/exact_knots.sh N`
//!   (every `p_i`, `q_i` = a/b, a and b in 1..12, from the same 32-bit LCG
//!   with seed 1), so the CLI timings of the README use the same inputs.

use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::scalar::Rational;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::exact::exact_verdict;

fn main() {
    divan::main();
}

const SIZES: &[usize] = &[8, 16, 32, 64];

/// The knot intervals of `benches/exact_knots.sh n 1` (LCG with the
/// Numerical Recipes constants; four draws per corner).
fn lcg_knots(n: usize) -> (Vec<Rational>, Vec<Rational>) {
    let mut x: u64 = 1;
    let mut draw = || {
        x = (1664525 * x + 1013904223) % (1 << 32);
        1 + ((x * 12) >> 32) as i64
    };
    let (mut p, mut q) = (Vec::new(), Vec::new());
    for _ in 0..n {
        let v: Vec<i64> = (0..4).map(|_| draw()).collect();
        p.push(Rational::new(v[0].into(), v[1].into()));
        q.push(Rational::new(v[2].into(), v[3].into()));
    }
    (p, q)
}

#[divan::bench(args = SIZES, sample_count = 3, sample_size = 1)]
fn uniform(n: usize) {
    let s = LocalScheme::nurds(EdgeRatios::<Rational>::uniform(n).unwrap());
    divan::black_box(exact_verdict(&s, None).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 3, sample_size = 1)]
fn random_rational(n: usize) {
    let (p, q) = lcg_knots(n);
    let r = CornerIntervals::new(p, q).unwrap().ratios().unwrap();
    let s = LocalScheme::nurds(r);
    divan::black_box(exact_verdict(&s, None).unwrap());
}
