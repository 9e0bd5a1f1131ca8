//! The cost of the sweep's output formats over evaluation alone (the target:
//! a Parquet overhead of at most 15% over evaluation alone at n = 3..16),
//! measured in one process, in CPU time (user + sys, all threads).
//!
//! For n = 3, 5, 8, 16 (nurds, edge ratios in [0.01, 0.99], Halton points,
//! the default columns), on a rayon pool of one thread, the same
//! configurations go through the sweep driver:
//!
//! * `evaluation alone`: [`output::run_discard`] (enumeration, evaluation,
//!   summary; the cells are dropped, no row is formed);
//! * `csv`: [`output::run`] into `io::sink` (the CSV text);
//! * `parquet`: [`output::run_parquet`] into part files of a dataset, each
//!   written by the `parquet` crate's column writers and copied into one
//!   buffer, kept from run to run (the typed column buffers, the encoding,
//!   and the copy a write makes).
//!
//! No file is written (the CLI's I/O is in `benches/parquet_rate.sh`). Each
//! cell is the best of `RUNS` runs (environment, default 5), the runs of the
//! three modes interleaved so that they see the same load.
//!
//!     cargo bench --bench sweep_formats            # RUNS=5 SCALE=1
//!
//! `SCALE` (environment, default 1) scales the configuration counts;
//! `VALENCES` (environment, e.g. `"3 5"`) picks some of the valences;
//! `MODES` (environment, e.g. `"discard parquet"`) some of the modes (for a
//! profile of one mode; skipped cells print as `-`).

use std::sync::{Arc, Mutex};
use subdiv_lab::sweep::output::parquet::ParquetRows;
use subdiv_lab::sweep::{output, Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

/// CPU time (user + sys) of this process so far, in seconds.
fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes the struct it is given; a zeroed rusage is a
    // valid value of the type.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

fn plan(n: usize, count: u64) -> Plan {
    let spec = SweepSpec::from_toml(&format!(
        "name = \"rate\"\nscheme = \"nurds\"\nvalences = [{n}]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = {count}\n"
    ))
    .expect("bench spec is valid");
    Plan::new(spec)
}

#[derive(Clone, Copy)]
enum Mode {
    Discard,
    Csv,
    Parquet,
}

impl Mode {
    /// The name `MODES` selects it by.
    fn name(self) -> &'static str {
        match self {
            Mode::Discard => "discard",
            Mode::Csv => "csv",
            Mode::Parquet => "parquet",
        }
    }
}

/// One sweep of `plan` in `mode`; returns the CPU seconds it took. `file`
/// stands for the files: each part is copied there, as a write copies it
/// into the page cache. It is kept from run to run, so
/// that the first touch of its pages (the kernel zeroing fresh memory, which
/// a write into the page cache does not do) is not counted in every run.
fn one(
    plan: &Plan,
    layout: &Layout,
    eval: &SpectralEvaluator,
    mode: Mode,
    file: &Arc<Mutex<Vec<u8>>>,
) -> f64 {
    let total = plan.total();
    let mut summary = Summary::new(plan, layout, Shard::ALL, None);
    let c0 = cpu_seconds();
    let rows = match mode {
        Mode::Discard => output::run_discard(plan, layout, eval, 0..total, &mut summary),
        Mode::Csv => output::run(
            plan,
            layout,
            eval,
            0..total,
            &mut std::io::sink(),
            &mut summary,
            &mut |_| {},
        ),
        Mode::Parquet => {
            let file = file.clone();
            let commit = Box::new(move |_k: u64, _rows: u64, bytes: Vec<u8>| {
                let mut f = file.lock().map_err(|_| std::io::Error::other("poisoned"))?;
                f.clear();
                f.extend_from_slice(&bytes);
                Ok(())
            });
            let fp = output::fingerprint_line(plan, Shard::ALL);
            let mut pq = ParquetRows::parts(layout, &fp, 0, commit).expect("writer");
            let r = output::run_parquet(
                plan,
                layout,
                eval,
                0..total,
                &mut pq,
                &mut summary,
                &mut |_| {},
                &std::sync::atomic::AtomicU64::new(0),
            );
            pq.finish().expect("last group");
            r
        }
    }
    .expect("sweep runs");
    let dt = cpu_seconds() - c0;
    assert_eq!(rows, total);
    dt
}

fn main() {
    // `cargo bench` passes `--bench`; nothing to parse.
    let runs: usize = std::env::var("RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5);
    let scale: f64 = std::env::var("SCALE")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(1.0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average before: {}", load.trim());
    println!();
    println!("| n | configurations | evaluation alone | csv (text, no I/O) | parquet (no I/O) | csv / evaluation | parquet / evaluation |");
    println!("|---|---|---|---|---|---|---|");
    let only: Option<Vec<usize>> = std::env::var("VALENCES").ok().map(|v| {
        v.split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect()
    });
    let modes: Option<Vec<String>> = std::env::var("MODES")
        .ok()
        .map(|v| v.split_whitespace().map(str::to_owned).collect());
    let modes: Option<Vec<&str>> = modes
        .as_ref()
        .map(|m| m.iter().map(String::as_str).collect());
    for (n, count) in [(3, 400_000u64), (5, 200_000), (8, 100_000), (16, 40_000)] {
        if only.as_ref().is_some_and(|o| !o.contains(&n)) {
            continue;
        }
        let count = ((count as f64 * scale) as u64).max(1);
        let plan = plan(n, count);
        let layout = Layout::new(&plan);
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let mut best = [f64::INFINITY; 3];
        let file = Arc::new(Mutex::new(Vec::new()));
        for _ in 0..runs {
            for (k, mode) in [Mode::Discard, Mode::Csv, Mode::Parquet]
                .into_iter()
                .enumerate()
            {
                if modes.as_ref().is_some_and(|m| !m.contains(&mode.name())) {
                    continue;
                }
                let dt = pool.install(|| one(&plan, &layout, &eval, mode, &file));
                best[k] = best[k].min(dt);
            }
        }
        let rate = |t: f64| {
            if t.is_finite() {
                format!("{:.0}k/s", count as f64 / t / 1e3)
            } else {
                "-".to_owned()
            }
        };
        let over = |t: f64| {
            if t.is_finite() && best[0].is_finite() {
                format!("{:.2}", t / best[0])
            } else {
                "-".to_owned()
            }
        };
        println!(
            "| {n} | {count} | {} | {} | {} | {} | {} |",
            rate(best[0]),
            rate(best[1]),
            rate(best[2]),
            over(best[1]),
            over(best[2])
        );
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!();
    println!("load average after: {}", load.trim());
}
