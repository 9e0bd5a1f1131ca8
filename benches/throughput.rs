//! Side-by-side throughput counterpart of the numpy reference of
//! `benches/compare_numpy.sh` (a script outside the repository; see there).
//!
//! `cargo bench --bench throughput -- --valence 8 --count 20000 [--seed 1] [--path structured|full]`
//!
//! Same work as the numpy script: random ratios uniform in `[0.01, 0.99)`,
//! the spectrum of the local matrix and the subdominant classification, one
//! thread (the structured path classifies configurations in batches with
//! [`classify_schemes_batch`], as the sweep driver does). Prints one line in the numpy script's format so that
//! `benches/compare_numpy.sh` can tabulate both.

use std::time::Instant;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::eigen::{Eigen, EigenOptions};
use subdiv_lab::spectral::BATCH;
use subdiv_lab::spectral::{
    classify_scheme_with, classify_schemes_batch, StructuredWorkspace, SubdominantClass,
};

fn arg(args: &[String], name: &str, default: &str) -> String {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
        .unwrap_or_else(|| default.to_owned())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = arg(&args, "--valence", "8").parse().expect("--valence");
    let count: usize = arg(&args, "--count", "20000").parse().expect("--count");
    let seed: u64 = arg(&args, "--seed", "1").parse().expect("--seed");
    let path = arg(&args, "--path", "structured");
    let mut rng = SplitMix64::new(seed);
    let mut counts = [0usize; 4]; // complex, double, real_distinct, other
    let mut tally = |class: &SubdominantClass| match class {
        SubdominantClass::ComplexPair => counts[0] += 1,
        SubdominantClass::Standard | SubdominantClass::Defective => counts[1] += 1,
        SubdominantClass::RealDistinct => counts[2] += 1,
        _ => counts[3] += 1,
    };
    let mut next = || {
        let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.01, 0.99)).collect();
        LocalScheme::nurds(EdgeRatios::new(r).expect("ratios in (0, 1)"))
    };
    let mut ws: [StructuredWorkspace; BATCH] = Default::default();
    let t0 = Instant::now();
    if path == "full" {
        for _ in 0..count {
            let m = next().matrix().expect("assembly").into_matrix();
            let e = Eigen::new(&m, EigenOptions::VALUES).expect("eigenvalues");
            let v = e.values();
            // numpy's classification: complex if |Im l1| > 1e-9, double if |l1 - l2| <= 1e-9.
            tally(&if v[1].im.abs() > 1e-9 {
                SubdominantClass::ComplexPair
            } else if (v[1] - v[2]).norm() <= 1e-9 {
                SubdominantClass::Standard
            } else {
                SubdominantClass::RealDistinct
            });
        }
    } else {
        // The structured path classifies configurations in batches (the QR
        // iterations in lock step), as the sweep driver does.
        for _ in 0..count / BATCH {
            let schemes: [LocalScheme<f64>; BATCH] = std::array::from_fn(|_| next());
            for s in classify_schemes_batch(ws.each_mut(), schemes.each_ref()) {
                tally(&s.expect("classification").class);
            }
        }
        for _ in 0..count % BATCH {
            tally(
                &classify_scheme_with(&mut ws[0], &next())
                    .expect("classification")
                    .class,
            );
        }
    }
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "valence={n} configs={count} seconds={dt:.3} configs_per_s={:.0} complex={} double={} real_distinct={} other={} path={path}",
        count as f64 / dt,
        counts[0],
        counts[1],
        counts[2],
        counts[3]
    );
}
