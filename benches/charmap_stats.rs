//! Research statistics: eigenstructure classes and characteristic-map verdicts
//! of NURDS faces with random knots (math doc sections 6, 7).
//!
//! Run: `cargo bench --bench charmap_stats` (optionally `-- SAMPLES SEED LO`;
//! defaults 4000 per valence, seed 20261121, LO = 0.01: ratios in [LO, 1 - LO]).
//!
//! Sampler: for each valence n = 3..8 and sample k, the edge ratios
//! r_0..r_{n-1} are drawn independently and uniformly from [LO, 1 - LO]
//! (SplitMix64 seeded with `seed ^ (n << 32) ^ k`, 53-bit mantissa). Each
//! configuration is classified by `spectral::classify_scheme` (structured
//! path, its own documented tolerances) and checked by `charmap::check`
//! (regularity certified from Bezier coefficients of the Jacobian with the
//! derived error bound, adaptive de Casteljau subdivision up to depth
//! `charmap::regularity::MAX_DEPTH`; winding number certified by cone tests).
//! Output: one markdown table row per valence with counts.

use rayon::prelude::*;
use std::collections::BTreeMap;
use subdiv_lab::charmap::check;
use subdiv_lab::knots::EdgeRatios;
use subdiv_lab::rng::SplitMix64;
use subdiv_lab::schemes::LocalScheme;
use subdiv_lab::spectral::classify_scheme;

#[derive(Default)]
struct Row {
    classes: BTreeMap<String, usize>,
    verdicts: BTreeMap<String, usize>,
    errors: usize,
    min_coeff: f64,
    regular: usize,
    injective: usize,
}

/// Verdict code, regular, winding number, minimum relative Jacobian coefficient.
type Outcome = (String, Option<bool>, Option<i64>, Option<f64>);

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let samples: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(4000);
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20261121);
    let lo: f64 = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .filter(|x: &f64| *x > 0.0 && *x < 0.5)
        .unwrap_or(0.01);
    let hi = 1.0 - lo;
    println!("samples per valence: {samples}, seed: {seed}, ratios uniform in [{lo}, {hi}]^n\n");
    println!("| n | standard | real_distinct | complex_pair | defective | not_separated | class indeterminate | regular | regular+winding 1 | C1 | tpc real_distinct | tpc complex_pair | not_regular | not_injective | charmap indeterminate | errors | min rel. Jacobian coeff |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for n in 3..=8usize {
        let t0 = std::time::Instant::now();
        let results: Vec<(String, Option<Outcome>)> = (0..samples)
            .into_par_iter()
            .map(|k| {
                let mut rng = SplitMix64::new(seed ^ ((n as u64) << 32) ^ k as u64);
                let r: Vec<f64> = (0..n).map(|_| rng.uniform(lo, hi)).collect();
                let s = LocalScheme::nurds(EdgeRatios::new(r).expect("ratios in (0, 1)"));
                let class = match classify_scheme(&s) {
                    Ok(sub) => sub.class.name().to_owned(),
                    Err(_) => "error".to_owned(),
                };
                let rep = check(&s).ok().map(|r| {
                    (
                        r.verdict.code().to_owned(),
                        r.regular(),
                        r.winding_number,
                        r.min_jacobian_coeff(),
                    )
                });
                (class, rep)
            })
            .collect();
        let mut row = Row {
            min_coeff: f64::INFINITY,
            ..Row::default()
        };
        for (class, rep) in results {
            *row.classes.entry(class).or_default() += 1;
            match rep {
                None => row.errors += 1,
                Some((code, regular, winding, min)) => {
                    *row.verdicts.entry(code).or_default() += 1;
                    if regular == Some(true) {
                        row.regular += 1;
                        if winding == Some(1) {
                            row.injective += 1;
                        }
                    }
                    if let Some(m) = min {
                        row.min_coeff = row.min_coeff.min(m);
                    }
                }
            }
        }
        let c = |k: &str| row.classes.get(k).copied().unwrap_or(0);
        let v = |k: &str| row.verdicts.get(k).copied().unwrap_or(0);
        println!(
            "| {n} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.4e} |",
            c("standard"),
            c("real_distinct"),
            c("complex_pair"),
            c("defective"),
            c("not_separated"),
            c("indeterminate"),
            row.regular,
            row.injective,
            v("c1"),
            v("tpc_real_distinct"),
            v("tpc_complex_pair"),
            v("not_regular"),
            v("not_injective"),
            v("indeterminate"),
            row.errors,
            row.min_coeff
        );
        eprintln!("n = {n}: {:.2} s", t0.elapsed().as_secs_f64());
    }
}
