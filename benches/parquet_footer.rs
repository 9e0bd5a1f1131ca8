//! The cost of a Parquet commit's footer as a sweep grows (math doc section
//! 16.2, "Cost of a footer per commit").
//!
//! Every commit writes the footer of the whole file so far, which lists every
//! row group. For `G` = 16, 153, 1,526 and 15,259 groups of 65,536 rows (1M,
//! 10M, 100M and 1,000M rows of nurds at n = 3, default columns) this prints
//! the footer's bytes, the time to form one (best of `RUNS` batches, default
//! 5) and the total over a run that commits `G` groups (each commit's footer
//! lists the groups so far, so the run forms about `G^2 / 2` group entries),
//! and the same for the CLI's commit journal of that footer (its checksum and
//! copy, `journal_bytes`).
//! A real group's metadata (from a sweep written into memory) stands for
//! every group.
//!
//!     cargo bench --bench parquet_footer

use subdiv_lab::sweep::output::parquet::{
    journal_bytes, read_table, Commit, ParquetRows, ROW_GROUP_ROWS,
};
use subdiv_lab::sweep::{output, Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

fn main() {
    let runs: usize = std::env::var("RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5);
    let count = ROW_GROUP_ROWS as u64 + 1000;
    let spec = SweepSpec::from_toml(&format!(
        "name = \"footer\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = {count}\n"
    ))
    .expect("bench spec is valid");
    let plan = Plan::new(spec);
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let fp = output::fingerprint_line(&plan, Shard::ALL);
    // The sweep into memory: PAR1, the groups, the last footer.
    let mut file = output::parquet::MAGIC.to_vec();
    {
        let commit = |c: Commit<'_>| {
            file.truncate(c.offset as usize);
            for p in c.group {
                file.extend_from_slice(p);
            }
            file.extend_from_slice(c.footer);
            Ok(())
        };
        let mut pq = ParquetRows::new(&layout, &fp, Vec::new(), 4, commit).expect("writer");
        let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
        output::run_parquet(
            &plan,
            &layout,
            &eval,
            0..count,
            &mut pq,
            &mut summary,
            &mut |_| {},
            &std::sync::atomic::AtomicU64::new(0),
        )
        .expect("sweep runs");
        pq.finish().expect("last group");
    }
    let table = read_table(file).expect("reads back");
    let group = table.row_groups()[0].clone();
    println!("| groups G | rows | footer | one footer | its journal | footers and journals of a run of G commits |");
    println!("|---|---|---|---|---|---|");
    for g in [16usize, 153, 1526, 15_259] {
        let pq = ParquetRows::new(&layout, &fp, vec![group.clone(); g], 4, |_: Commit<'_>| {
            Ok(())
        })
        .expect("writer");
        let reps = (20_000 / g).max(3);
        let mut best = f64::INFINITY;
        let mut best_journal = f64::INFINITY;
        let mut len = 0;
        for _ in 0..runs {
            let t0 = std::time::Instant::now();
            for _ in 0..reps {
                len = pq.current_footer().expect("footer").len();
            }
            best = best.min(t0.elapsed().as_secs_f64() / reps as f64);
            let footer = pq.current_footer().expect("footer");
            let t0 = std::time::Instant::now();
            let mut journal = 0;
            for _ in 0..reps {
                journal += journal_bytes(1, &footer).len();
            }
            assert!(journal > reps * len);
            best_journal = best_journal.min(t0.elapsed().as_secs_f64() / reps as f64);
        }
        println!(
            "| {g} | {}M | {:.0} kB | {:.1} µs | {:.1} µs | {:.2} s |",
            g * ROW_GROUP_ROWS / 1_000_000,
            len as f64 / 1e3,
            best * 1e6,
            best_journal * 1e6,
            (best + best_journal) * g as f64 / 2.0
        );
    }
}
