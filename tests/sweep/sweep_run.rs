//! The library's sweep run into files (`subdiv_lab::sweep::run`): the same
//! bytes for any thread count and after a resumed torn write, an existing
//! output refused without `resume`, progress reported, shards of one
//! Parquet dataset merged.

use std::fs;
use std::path::Path;
use subdiv_lab::sweep::output::files::{self, Opened, Progress, RunOptions, Sink};
use subdiv_lab::sweep::{Plan, Shard, SweepError, SweepSpec};

const SPEC: &str = "name = \"run\"\nscheme = \"nurds\"\nvalences = [3, 5]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"random\"\ncount = 700\nseed = 3\n";

fn spec() -> SweepSpec {
    SweepSpec::from_toml(SPEC).unwrap()
}

fn options(threads: usize, resume: bool) -> RunOptions<'static> {
    RunOptions {
        threads,
        resume,
        ..RunOptions::default()
    }
}

/// Records what a run reports.
#[derive(Default)]
struct Recorder {
    opened: Option<(bool, u64, u64, Option<&'static str>)>,
    written: Vec<u64>,
}

impl Progress for Recorder {
    fn opened(&mut self, o: &Opened) {
        self.opened = Some((o.existed, o.done, o.expected, o.repaired));
    }
    fn written(&mut self, rows: u64) {
        self.written.push(rows);
    }
}

fn run_csv(path: &Path, threads: usize) -> Vec<u8> {
    let report = subdiv_lab::sweep::run(
        spec(),
        None,
        Sink::Csv(path.into()),
        options(threads, false),
    )
    .unwrap();
    assert_eq!(report.summary.rows, 1400);
    fs::read(path).unwrap()
}

#[test]
fn a_run_resumed_after_a_torn_write_equals_the_uninterrupted_run() {
    let dir = tempfile::tempdir().unwrap();
    let one = run_csv(&dir.path().join("one.csv"), 1);
    let two = run_csv(&dir.path().join("two.csv"), 2);
    assert!(one == two, "the same bytes for any thread count");
    let mut stream = Vec::new();
    subdiv_lab::sweep::run(spec(), None, Sink::Stream(&mut stream), options(2, false)).unwrap();
    assert!(stream == one, "a stream gets the file's bytes");

    // Killed mid-line: the torn line is dropped and the run continues.
    let path = dir.path().join("two.csv");
    let cut = one.len() / 2 + 5;
    assert_ne!(one[cut - 1], b'\n');
    fs::write(&path, &one[..cut]).unwrap();
    let err = subdiv_lab::sweep::run(spec(), None, Sink::Csv(path.clone()), options(2, false))
        .unwrap_err();
    assert!(matches!(&err, SweepError::Exists(p) if *p == path), "{err}");
    assert!(
        fs::read(&path).unwrap() == one[..cut],
        "a refused run changes nothing"
    );
    let mut rec = Recorder::default();
    let opts = RunOptions {
        progress: Some(&mut rec),
        ..options(2, true)
    };
    let report = subdiv_lab::sweep::run(spec(), None, Sink::Csv(path.clone()), opts).unwrap();
    assert!(
        fs::read(&path).unwrap() == one,
        "the resumed file equals the uninterrupted one"
    );
    let rows_before = one[..cut].iter().filter(|&&b| b == b'\n').count() as u64 - 1;
    assert_eq!(
        rec.opened,
        Some((true, rows_before, 1400, Some("dropped a torn last line")))
    );
    assert_eq!(rec.written.last(), Some(&1400));
    assert_eq!(report.summary.throughput.evaluated, 1400 - rows_before);
    assert!(!report.complete);
    // Complete: nothing evaluated (the throughput is the last run's).
    let last = report.summary.throughput;
    let report =
        subdiv_lab::sweep::run(spec(), None, Sink::Csv(path.clone()), options(1, true)).unwrap();
    assert!(report.complete);
    assert_eq!(report.summary.throughput, last);
    assert!(
        fs::read(&path).unwrap() == one,
        "the resumed file equals the uninterrupted one"
    );
}

#[test]
fn shards_of_one_dataset_merge_into_the_full_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("d.parquet");
    for i in 0..3 {
        let opts = RunOptions {
            shard: Shard::new(i, 3).unwrap(),
            ..options(2, true)
        };
        let r = subdiv_lab::sweep::run(spec(), None, Sink::for_path(&data), opts).unwrap();
        assert_eq!(r.summary.rows, Shard::new(i, 3).unwrap().len(1400));
    }
    let plan = Plan::new(spec());
    let shards = files::merge_inputs(std::slice::from_ref(&data)).unwrap();
    assert_eq!(shards.len(), 3);
    let out = dir.path().join("m.parquet");
    let merged = files::merge_files(&plan, shards, "the spec", &out).unwrap();
    assert_eq!(merged.summary.rows, 1400);
    assert!(out.is_file() && dir.path().join("m.summary.json").is_file());
}
