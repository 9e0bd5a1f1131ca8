//! Sweep throughput: configurations per second for n = 3, 5, 8, 16, 64 with
//! classification (the default columns: class, subdominant pair, gap,
//! contraction rate), random edge ratios uniform in [0.01, 0.99] as in the
//! numpy reference of `benches/compare_sweep_numpy.sh`.
//!
//! * `classify_only`: enumerate + assemble + spectral classification (the
//!   evaluator), no output, one thread;
//! * `evaluate_one_thread`: the public per-row API (`Layout::row` building a
//!   `Row`, then `Layout::format`), one thread; it allocates per row, unlike the
//!   driver;
//! * `sweep_1_thread` / `sweep_2_threads`: the whole streaming driver
//!   (`sweep::output::run` into `io::sink`: reused per-task buffers, staged
//!   cells, partial summaries, chunk writes overlapped with evaluation) on a
//!   rayon pool of 1 or 2 threads, for the thread-scaling figure. The
//!   difference `sweep_1_thread` - `classify_only` is the sweep's own overhead
//!   (enumeration, CSV text, summary).
//!
//! Run: `cargo bench --bench sweep`. Side by side with numpy:
//! `benches/compare_sweep_numpy.sh`.

use std::hint::black_box;
use subdiv_lab::sweep::{
    output, Evaluate, Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec,
};

fn main() {
    divan::main();
}

/// Configurations per benchmark iteration.
fn batch(n: usize) -> u64 {
    match n {
        0..=8 => 4096,
        9..=16 => 1024,
        _ => 64,
    }
}

fn plan(n: usize) -> Plan {
    let spec = SweepSpec::from_toml(&format!(
        "name = \"bench\"\nscheme = \"nurds\"\nvalences = [{n}]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"random\"\ncount = {}\nseed = 1\n",
        batch(n)
    ))
    .expect("bench spec is valid");
    Plan::new(spec)
}

#[divan::bench(args = [3, 5, 8, 16, 64])]
fn classify_only(bencher: divan::Bencher, n: usize) {
    let plan = plan(n);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    bencher
        .counter(divan::counter::ItemsCount::new(plan.total()))
        .bench(|| {
            let mut cells = 0usize;
            for id in 0..plan.total() {
                let c = plan.configuration(id).expect("id in range");
                let s = plan.scheme(&c).expect("valid configuration");
                cells += eval.evaluate(&plan, &c, &*s).expect("evaluates").len();
            }
            black_box(cells)
        });
}

#[divan::bench(args = [3, 5, 8, 16, 64])]
fn evaluate_one_thread(bencher: divan::Bencher, n: usize) {
    let plan = plan(n);
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    bencher
        .counter(divan::counter::ItemsCount::new(plan.total()))
        .bench(|| {
            let mut bytes = 0usize;
            for id in 0..plan.total() {
                let row = layout.row(&plan, &eval, id);
                bytes += layout.format(&row).len();
            }
            black_box(bytes)
        });
}

fn run_on(threads: usize, bencher: divan::Bencher, n: usize) {
    let plan = plan(n);
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    // Enough configurations that both threads stay busy for several chunks.
    let total = plan.total();
    bencher
        .counter(divan::counter::ItemsCount::new(total))
        .bench(|| {
            let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
            pool.install(|| {
                output::run(
                    &plan,
                    &layout,
                    &eval,
                    0..total,
                    &mut std::io::sink(),
                    &mut summary,
                    &mut |_| {},
                )
            })
            .expect("sweep runs")
        });
}

#[divan::bench(args = [3, 5, 8, 16, 64])]
fn sweep_1_thread(bencher: divan::Bencher, n: usize) {
    run_on(1, bencher, n);
}

#[divan::bench(args = [3, 5, 8, 16, 64])]
fn sweep_2_threads(bencher: divan::Bencher, n: usize) {
    run_on(2, bencher, n);
}
