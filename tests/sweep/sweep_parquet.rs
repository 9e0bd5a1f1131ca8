//! End-to-end tests of `sweep --out NAME.parquet` (math doc section 16.2):
//! a dataset directory of part files whose values equal the CSV's, typed
//! columns and metadata, byte identity for any thread count, resume after
//! `kill -9` (complete parts kept, every row verified), shards written into
//! one directory and merged (checked and compacted into one file).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use subdiv_lab::sweep::output::parquet::{
    csv_lines, read_table, FINGERPRINT_KEY, FORMAT, FORMAT_KEY, NULLS_KEY, PART_ROWS, SCHEMA_KEY,
};
use subdiv_lab::table::{Column, Table};

const BIN: &str = env!("CARGO_BIN_EXE_subdiv-lab");

fn write_spec(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    fs::write(&p, text).unwrap();
    p
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn ok(args: &[&str]) -> Output {
    let o = run(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn refused(args: &[&str], needle: &str) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A JSON file without its throughput (which depends on the run).
fn json(p: &Path) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_str(&fs::read_to_string(p).unwrap()).unwrap();
    v.as_object_mut().unwrap().remove("throughput");
    v
}

/// The summary beside a CSV or compacted file.
fn summary(p: &Path) -> serde_json::Value {
    let name = p.file_name().unwrap().to_str().unwrap();
    let stem = name
        .strip_suffix(".csv")
        .or_else(|| name.strip_suffix(".parquet"))
        .unwrap();
    json(&p.with_file_name(format!("{stem}.summary.json")))
}

/// The CSV's data lines (after the header line).
fn csv_data(p: &Path) -> String {
    let text = fs::read_to_string(p).unwrap();
    text.split_once('\n').unwrap().1.to_owned()
}

/// The part files of a dataset directory, sorted by name, with their bytes.
fn parts(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_name().to_str().unwrap().ends_with(".parquet"))
        .map(|e| {
            (
                e.file_name().to_str().unwrap().to_owned(),
                fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

/// The rows of a dataset as CSV lines, part after part.
fn dataset_lines(dir: &Path) -> String {
    parts(dir)
        .into_iter()
        .map(|(_, b)| {
            let t = read_table(b).unwrap();
            csv_lines(&t, 0, t.len())
        })
        .collect()
}

fn sweep_pq(spec: &Path, out: &Path, extra: &[&str]) {
    let mut args = vec!["sweep", s(spec), "--out", s(out), "--quiet"];
    args.extend_from_slice(extra);
    ok(&args);
}

/// A single compacted Parquet file `out` of `spec`'s rows (a dataset merged).
fn single_file(spec: &Path, out: &Path) {
    let d = out.with_extension("d.parquet");
    sweep_pq(spec, &d, &[]);
    ok(&["merge", "--spec", s(spec), "--out", s(out), s(&d)]);
}

/// 3 and 4 with the exact certificate (labels, booleans, empty cells) and
/// eigenvalue columns.
const SMALL: &str = r#"
name = "pq-small"
scheme = "nurds"
valences = [3, 4]
[space]
kind = "ratios"
ratio_range = [0.05, 0.95]
[sampler]
kind = "random"
count = 40
seed = 5
[columns]
eigenvalues = 3
exact_certificate = true
"#;

/// More than two parts of n = 3 (fast).
const BIG: &str = r#"
name = "pq-big"
scheme = "nurds"
valences = [3]
[space]
kind = "ratios"
ratio_range = [0.01, 0.99]
[sampler]
kind = "halton"
count = 150000
"#;

#[test]
fn parquet_values_equal_the_csv() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s.toml", SMALL);
    let csv = dir.path().join("s.csv");
    let pq = dir.path().join("s.parquet");
    ok(&["sweep", s(&spec), "--out", s(&csv), "--quiet"]);
    sweep_pq(&spec, &pq, &[]);
    assert!(pq.is_dir());
    let p = parts(&pq);
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].0, "part-000000.parquet");
    let t: Table = read_table(p[0].1.clone()).unwrap();
    // The same lines, byte for byte (numbers in shortest round-trip form).
    assert_eq!(csv_lines(&t, 0, t.len()), csv_data(&csv));
    assert_eq!(t.len(), 80);
    // Typed columns, and the numbers bit for bit those of the CSV text.
    let header: Vec<String> = fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    assert_eq!(t.names(), header);
    assert!(matches!(t.column("id"), Some(Column::U64(_))));
    assert!(matches!(t.column("valence"), Some(Column::U32(_))));
    assert!(matches!(t.column("class"), Some(Column::Str(_))));
    assert!(matches!(t.column("exact_agrees"), Some(Column::Bool(_))));
    assert!(matches!(t.column("lambda1_re"), Some(Column::F64(_))));
    // r3 is null on the rows of valence 3 (an empty CSV cell).
    let Some(Column::F64(r3)) = t.column("r3") else {
        panic!("r3")
    };
    assert!(r3.iter().any(Option::is_none) && r3.iter().any(Option::is_some));
    // The metadata: the fingerprint (spec digest and shard), the format, the
    // column documentation and the null rules.
    let digest = summary(&pq)["spec_digest"].as_str().unwrap().to_owned();
    let fp = t.metadata(FINGERPRINT_KEY).unwrap();
    assert!(
        fp.starts_with(&format!("# subdiv-lab sweep: digest {digest}, shard 0/1")),
        "{fp}"
    );
    assert_eq!(t.metadata(FORMAT_KEY), Some(FORMAT));
    assert!(t
        .metadata(NULLS_KEY)
        .unwrap()
        .contains("beyond the row's valence"));
    let docs: serde_json::Value = serde_json::from_str(t.metadata(SCHEMA_KEY).unwrap()).unwrap();
    assert_eq!(docs.as_array().unwrap().len(), header.len());
    // The summary (beside the directory) is the CSV run's (the same rows).
    assert_eq!(summary(&pq), summary(&csv));
}

#[test]
fn parquet_is_byte_identical_for_any_thread_count_and_parts_are_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", BIG);
    let one = dir.path().join("one.parquet");
    let two = dir.path().join("two.parquet");
    sweep_pq(&spec, &one, &["--threads", "1"]);
    sweep_pq(&spec, &two, &["--threads", "2"]);
    let a = parts(&one);
    assert!(a == parts(&two), "the parts differ between thread counts");
    let names: Vec<&str> = a.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "part-000000.parquet",
            "part-000001.parquet",
            "part-000002.parquet"
        ]
    );
    let rows: Vec<usize> = a
        .iter()
        .map(|(_, b)| read_table(b.clone()).unwrap().len())
        .collect();
    assert_eq!(rows, [PART_ROWS, PART_ROWS, 150_000 - 2 * PART_ROWS]);
    // Only the parts are in the directory, and no temporary file is left.
    assert_eq!(fs::read_dir(&one).unwrap().count(), 3);
    let hidden = fs::read_dir(dir.path())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_str()
                .unwrap()
                .starts_with('.')
        })
        .count();
    assert_eq!(hidden, 0);
}

/// Kills (SIGKILL) a Parquet sweep of `spec` into `out` once `parts`
/// part files exist (or after `at_least` when given), leaving what it wrote.
fn kill_after(spec: &Path, out: &Path, parts_done: usize, threads: &str) {
    let mut child = Command::new(BIN)
        .args(["sweep", s(spec), "--out", s(out), "--threads", threads])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while fs::read_dir(out).map_or(0, |d| {
        d.filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.file_name().to_str().unwrap().starts_with("part-"))
        })
        .count()
    }) < parts_done
        && start.elapsed() < std::time::Duration::from_secs(120)
    {
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
    child.kill().unwrap();
    child.wait().unwrap();
}

#[test]
fn parquet_resume_after_sigkill_is_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", BIG);
    let full = dir.path().join("full.parquet");
    sweep_pq(&spec, &full, &[]);
    let want = parts(&full);
    for (round, k) in [(0, 0), (1, 1), (2, 2)] {
        let p = dir.path().join(format!("killed{round}.parquet"));
        kill_after(&spec, &p, k, "2");
        // Without --resume the existing parts are refused.
        if k > 0 {
            refused(&["sweep", s(&spec), "--out", s(&p)], "pass --resume");
        }
        sweep_pq(&spec, &p, &["--resume"]);
        assert!(parts(&p) == want, "round {round}");
        assert_eq!(summary(&p), summary(&full));
    }
    // A run limited to a short last part, continued: that part is written again.
    let p = dir.path().join("steps.parquet");
    sweep_pq(&spec, &p, &["--limit", "70000"]);
    assert_eq!(parts(&p).len(), 2);
    sweep_pq(&spec, &p, &["--resume"]);
    assert!(parts(&p) == want);
}

#[test]
fn parquet_resume_verifies_the_parts() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", BIG);
    let pq = dir.path().join("b.parquet");
    sweep_pq(&spec, &pq, &["--limit", "140000"]);
    let part1 = pq.join("part-000001.parquet");
    let bytes = fs::read(&part1).unwrap();
    let t = read_table(bytes.clone()).unwrap();
    // Change the bytes of one coordinate (PLAIN-encoded doubles): the
    // parameters re-derived from the id no longer match.
    let Some(Column::F64(r1)) = t.column("r1") else {
        panic!("r1")
    };
    let x = r1[17].unwrap();
    let at = bytes
        .windows(8)
        .position(|w| w == x.to_le_bytes())
        .expect("the value's bytes");
    let mut edited = bytes.clone();
    edited[at..at + 8].copy_from_slice(&(x * 0.5).to_le_bytes());
    fs::write(&part1, &edited).unwrap();
    let resume = ["sweep", s(&spec), "--out", s(&pq), "--resume"];
    refused(&resume, "r1");
    assert_eq!(fs::read(&part1).unwrap(), edited);
    // A part of another spec is refused by its fingerprint.
    let other = write_spec(dir.path(), "o.toml", &BIG.replace("150000", "150001"));
    let foreign = dir.path().join("o.parquet");
    sweep_pq(&other, &foreign, &["--limit", "70000"]);
    fs::copy(foreign.join("part-000001.parquet"), &part1).unwrap();
    refused(&resume, "another spec");
    // A torn part (not written by this tool: parts are renamed into place).
    fs::write(&part1, &bytes[..bytes.len() / 2]).unwrap();
    refused(&resume, "part-000001.parquet: line 1: read failed");
    // A part renamed to another index.
    fs::copy(pq.join("part-000000.parquet"), &part1).unwrap();
    refused(&resume, "holds part 0 where part 1 was expected");
    // A missing part before an existing one.
    fs::write(&part1, &bytes).unwrap();
    fs::remove_file(pq.join("part-000000.parquet")).unwrap();
    refused(&resume, "part-000000.parquet is missing");
    // An output of the older single-file format is refused by name.
    let old = dir.path().join("old.parquet");
    fs::copy(foreign.join("part-000000.parquet"), &old).unwrap();
    refused(
        &["sweep", s(&spec), "--out", s(&old), "--resume"],
        "written by an older subdiv-lab",
    );
}

/// A dataset of part format 1 ([`FORMAT`]: `tests/data/sweep-part-format-1`,
/// the 80 rows of [`SMALL`] with their summary, stored as written) is
/// accepted by `--resume` (its fingerprint is this spec's; every row is
/// verified, nothing evaluated), and its rows read back equal to those a
/// sweep of the spec writes; a spec of another seed refuses it.
#[test]
fn a_dataset_of_part_format_1_resumes_and_reads_back_equal() {
    let dir = tempfile::tempdir().unwrap();
    let stored = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sweep-part-format-1");
    let spec = write_spec(dir.path(), "s.toml", SMALL);
    let pq = dir.path().join("s.parquet");
    fs::create_dir(&pq).unwrap();
    let part = "part-000000.parquet";
    fs::copy(stored.join("s.parquet").join(part), pq.join(part)).unwrap();
    fs::copy(
        stored.join("s.summary.json"),
        dir.path().join("s.summary.json"),
    )
    .unwrap();
    let t = read_table(fs::read(pq.join(part)).unwrap()).unwrap();
    assert_eq!(t.metadata(FORMAT_KEY), Some(FORMAT));
    let o = ok(&["sweep", s(&spec), "--out", s(&pq), "--resume"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("already complete: 80 rows verified"), "{err}");
    let fresh = dir.path().join("f.parquet");
    sweep_pq(&spec, &fresh, &[]);
    assert_eq!(dataset_lines(&pq), dataset_lines(&fresh));
    assert_eq!(summary(&pq)["classes"], summary(&fresh)["classes"]);
    let other = write_spec(dir.path(), "o.toml", &SMALL.replace("seed = 5", "seed = 6"));
    refused(
        &["sweep", s(&other), "--out", s(&pq), "--resume"],
        "another spec",
    );
}

#[test]
fn parquet_shards_in_one_directory_merge_to_the_unsharded_rows() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", &BIG.replace("150000", "70000"));
    let full = dir.path().join("full.parquet");
    sweep_pq(&spec, &full, &[]);
    // Three shards into one directory (as the Slurm recipe runs them).
    let shared = dir.path().join("shared.parquet");
    for i in 0..3 {
        sweep_pq(&spec, &shared, &["--shard", &format!("{i}/3"), "--resume"]);
    }
    let names: Vec<String> = parts(&shared).into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        names,
        [
            "part-0-of-3-000000.parquet",
            "part-1-of-3-000000.parquet",
            "part-2-of-3-000000.parquet"
        ]
    );
    assert!(dir.path().join("shared.shard-2-of-3.summary.json").exists());
    // Compacted into one file: the rows of the unsharded run, in id order.
    let merged = dir.path().join("merged.parquet");
    ok(&["merge", "--spec", s(&spec), "--out", s(&merged), s(&shared)]);
    let t = read_table(fs::read(&merged).unwrap()).unwrap();
    assert_eq!(csv_lines(&t, 0, t.len()), dataset_lines(&full));
    assert_eq!(summary(&merged), summary(&full));
    // A missing shard: the error names the first missing id, and no output appears.
    let out2 = dir.path().join("merged2.parquet");
    fs::rename(
        shared.join("part-1-of-3-000000.parquet"),
        dir.path().join("away.parquet"),
    )
    .unwrap();
    refused(
        &["merge", "--spec", s(&spec), "--out", s(&out2), s(&shared)],
        "configuration id 1 is missing",
    );
    assert!(!out2.exists());
    // The same shard twice (a second directory holding a copy).
    fs::rename(
        dir.path().join("away.parquet"),
        shared.join("part-1-of-3-000000.parquet"),
    )
    .unwrap();
    let copy = dir.path().join("copy.parquet");
    fs::create_dir(&copy).unwrap();
    let f = "part-1-of-3-000000.parquet";
    fs::copy(shared.join(f), copy.join(f)).unwrap();
    let f = "shard-1-of-3.summary.json";
    fs::copy(
        dir.path().join(format!("shared.{f}")),
        dir.path().join(format!("copy.{f}")),
    )
    .unwrap();
    refused(
        &[
            "merge",
            "--spec",
            s(&spec),
            "--out",
            s(&out2),
            s(&shared),
            s(&copy),
        ],
        "configuration id 1 appears twice",
    );
    assert!(!out2.exists());
}

/// A 2-D slice of n = 4 with the special classes (the `standard` point and
/// lines of `not_separated`), and the exact certificate (booleans).
const SLICE: &str = r#"
name = "pq-slice"
scheme = "nurds"
valences = [4]
[space]
kind = "ratios"
ratio_range = [0.1, 0.9]
fixed = { r2 = 0.5, r3 = 0.5 }
[sampler]
kind = "grid"
points_per_axis = 9
[columns]
exact_certificate = true
"#;

/// `plot` draws the same figure from a sweep's Parquet file as from its CSV,
/// for the default (a class map of the slice) and every kind.
#[test]
fn plot_from_parquet_equals_plot_from_csv() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s.toml", SLICE);
    let csv = dir.path().join("s.csv");
    let pq = dir.path().join("s.parquet");
    ok(&["sweep", s(&spec), "--out", s(&csv), "--quiet"]);
    single_file(&spec, &pq);
    let cases: &[&[&str]] = &[
        &[],
        &["--kind", "fractions", "--x", "r0"],
        &[
            "--kind",
            "histogram",
            "--x",
            "lambda1_re",
            "--color",
            "class",
        ],
        &[
            "--kind",
            "scatter",
            "--x",
            "r0",
            "--y",
            "contraction_rate",
            "--color",
            "exact_agrees",
        ],
        &["--kind", "map", "--x", "r0", "--y", "r1", "--color", "gap"],
    ];
    for (k, extra) in cases.iter().enumerate() {
        let a = dir.path().join(format!("a{k}.svg"));
        let b = dir.path().join(format!("b{k}.svg"));
        let mut args = vec!["plot", s(&csv), "-o", s(&a)];
        args.extend_from_slice(extra);
        ok(&args);
        let mut args = vec!["plot", s(&pq), "-o", s(&b)];
        args.extend_from_slice(extra);
        ok(&args);
        let (a, b) = (fs::read(&a).unwrap(), fs::read(&b).unwrap());
        assert!(a.len() > 1000, "{extra:?}");
        assert!(a == b, "{extra:?}: the SVGs differ");
    }
    // PNG too.
    let a = dir.path().join("a.png");
    let b = dir.path().join("b.png");
    ok(&["plot", s(&csv), "-o", s(&a)]);
    ok(&["plot", s(&pq), "-o", s(&b)]);
    assert!(fs::read(&a).unwrap() == fs::read(&b).unwrap());
}

/// A Parquet file under another name (renamed `x.csv`; `sweep` itself
/// refuses `--format parquet --out x.csv`) is recognised by its magic bytes:
/// `plot` draws the same figure as from the `.parquet` file (read as CSV it
/// would fail with "line 1: not valid UTF-8").
#[test]
fn plot_recognises_parquet_under_a_csv_name() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s.toml", SLICE);
    let pq = dir.path().join("s.parquet");
    let disguised = dir.path().join("d.csv");
    single_file(&spec, &pq);
    fs::copy(&pq, &disguised).unwrap();
    let a = dir.path().join("a.svg");
    let b = dir.path().join("b.svg");
    ok(&["plot", s(&pq), "-o", s(&a)]);
    ok(&["plot", s(&disguised), "-o", s(&b)]);
    assert!(fs::read(&a).unwrap() == fs::read(&b).unwrap());
}

/// Bad Parquet input to `plot` exits 2 with one line naming the problem and
/// writes nothing: a missing column, a text column for an axis, a truncated
/// file (cut inside a row group, so no footer at its end).
#[test]
fn plot_refuses_bad_parquet_input() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s.toml", SLICE);
    let pq = dir.path().join("s.parquet");
    single_file(&spec, &pq);
    let bytes = fs::read(&pq).unwrap();
    let cut = dir.path().join("cut.parquet");
    fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let out = dir.path().join("f.svg");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["plot", s(&pq), "-o", s(&out), "--x", "nope"],
            "no column \"nope\"",
        ),
        (
            vec![
                "plot",
                s(&pq),
                "-o",
                s(&out),
                "--kind",
                "scatter",
                "--x",
                "r0",
                "--y",
                "class",
            ],
            "column \"class\" is not numeric",
        ),
        (
            vec![
                "plot",
                s(&pq),
                "-o",
                s(&out),
                "--kind",
                "histogram",
                "--x",
                "exact_agrees",
            ],
            "column \"exact_agrees\" is not numeric",
        ),
        (
            vec!["plot", s(&cut), "-o", s(&out)],
            "cut.parquet: not a Parquet file, or torn",
        ),
    ];
    for (args, needle) in cases {
        let o = run(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists());
    }
}
