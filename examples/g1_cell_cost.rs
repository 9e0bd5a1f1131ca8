//! CPU per cell of the `g1` certificate (math doc section 15, "G1 over a
//! cell"): runs [`g1_certified`] on one thread over a fixed, seeded set of
//! cubes of side `SIDE` inside `[0.05, 0.95]^N` and prints how many were
//! certified, how many got no enclosure of the ring (Stewart's conditions
//! or the separation from the rest of the spectrum failed) and the wall
//! time per cell. The same arguments give the same cells, so two builds can be
//! compared side by side; quote the CPU time (`/usr/bin/time`) on a shared
//! machine.
//!
//! ```text
//! cargo run --release --example g1_cell_cost -- N SIDE COUNT [SEED]
//! ```

use std::time::Instant;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::verify::charmap::ratios::g1_certified;
use subdiv_lab::verify::charmap::CellTamper;

/// The box the cells are drawn from (that of the `n >= 4` targets).
const BOX: [f64; 2] = [0.05, 0.95];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: g1_cell_cost N SIDE COUNT [SEED]";
    let arg = |k: usize| -> &str { args.get(k).unwrap_or_else(|| panic!("{usage}")) };
    let n: usize = arg(0).parse().expect(usage);
    let side: f64 = arg(1).parse().expect(usage);
    let count: usize = arg(2).parse().expect(usage);
    let seed: u64 = args.get(3).map_or(1, |s| s.parse().expect(usage));
    assert!(side > 0.0 && side < BOX[1] - BOX[0], "{usage}");
    let mut rng = SplitMix64::new(seed);
    let cells: Vec<Vec<f64>> = (0..count)
        .map(|_| (0..n).map(|_| rng.uniform(BOX[0], BOX[1] - side)).collect())
        .collect();
    let start = Instant::now();
    let (mut certified, mut early) = (0, 0);
    for lo in &cells {
        let hi: Vec<f64> = lo.iter().map(|x| x + side).collect();
        let (ok, scores) = g1_certified(lo, &hi, CellTamper::None);
        certified += usize::from(ok);
        early += usize::from(scores.is_none());
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "n={n} side={side} cells={count} seed={seed}: certified {certified}, no ring enclosure {early}, {:.3} ms/cell wall",
        1e3 * secs / count as f64
    );
}
