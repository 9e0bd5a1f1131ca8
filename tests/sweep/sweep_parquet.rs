//! End-to-end tests of `sweep --format parquet` (math doc section 16.2):
//! values equal to the CSV's, typed columns, byte identity for any thread
//! count, resume after `kill -9` and after a torn trailing row group, resume
//! verifies the committed rows.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use subdiv_lab::sweep::output::parquet::{journal_bytes, read_table, Column, ROW_GROUP_ROWS};

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

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The summary without its throughput (which depends on the run).
fn summary(p: &Path) -> serde_json::Value {
    let name = p.file_name().unwrap().to_str().unwrap();
    let stem = name
        .strip_suffix(".csv")
        .or_else(|| name.strip_suffix(".parquet"))
        .unwrap();
    let text = fs::read_to_string(p.with_file_name(format!("{stem}.summary.json"))).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut().unwrap().remove("throughput");
    v
}

/// The CSV's data lines (after the fingerprint and header lines).
fn csv_data(p: &Path) -> String {
    let text = fs::read_to_string(p).unwrap();
    text.splitn(3, '\n').nth(2).unwrap().to_owned()
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

/// More than two row groups of n = 3 (fast).
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
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--quiet",
    ]);
    let t = read_table(fs::read(&pq).unwrap()).unwrap();
    // The same lines, byte for byte (numbers in shortest round-trip form).
    assert_eq!(t.csv_lines(0, t.rows()), csv_data(&csv));
    assert_eq!(t.rows(), 80);
    // Typed columns, and the numbers bit for bit those of the CSV text.
    let header: Vec<String> = fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    assert_eq!(t.names, header);
    assert!(matches!(t.column("id"), Some(Column::U64(_))));
    assert!(matches!(t.column("valence"), Some(Column::U32(_))));
    assert!(matches!(t.column("class"), Some(Column::Str(_))));
    assert!(matches!(t.column("exact_agrees"), Some(Column::Bool(_))));
    let text = csv_data(&csv);
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let mut numbers = 0;
    let mut booleans = 0;
    for (k, name) in header.iter().enumerate() {
        match t.column(name).unwrap() {
            Column::F64(v) => {
                for (r, x) in v.iter().enumerate() {
                    let cell = rows[r][k];
                    match x {
                        Some(x) => {
                            assert_eq!(cell.parse::<f64>().unwrap().to_bits(), x.to_bits());
                            numbers += 1;
                        }
                        None => assert_eq!(cell, ""),
                    }
                }
            }
            Column::Bool(v) => {
                for (r, b) in v.iter().enumerate() {
                    let want = match rows[r][k] {
                        "true" => Some(true),
                        "false" => Some(false),
                        "" => None,
                        other => panic!("boolean cell {other:?}"),
                    };
                    assert_eq!(*b, want);
                    booleans += usize::from(b.is_some());
                }
            }
            _ => {}
        }
    }
    assert!(numbers > 80 * 10, "{numbers}");
    assert!(booleans > 40, "{booleans}");
    // The fingerprint ties the file to the spec, as the CSV's first line does.
    let first = fs::read_to_string(&csv).unwrap();
    assert_eq!(t.fingerprint().unwrap(), first.lines().next().unwrap());
    // The summary is the CSV run's (the same rows).
    assert_eq!(summary(&pq), summary(&csv));
    let schema = summary(&csv)["schema"].as_array().unwrap().clone();
    assert_eq!(schema.len(), header.len());
    assert_eq!(schema[0]["name"], "id");
    assert!(schema
        .iter()
        .any(|c| c["name"] == "exact_agrees" && c["type"] == "bool"));
}

#[test]
fn parquet_is_byte_identical_for_any_thread_count_and_groups_are_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", BIG);
    let one = dir.path().join("one.parquet");
    let two = dir.path().join("two.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&one),
        "--format",
        "parquet",
        "--threads",
        "1",
        "--quiet",
    ]);
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&two),
        "--format",
        "parquet",
        "--threads",
        "2",
        "--quiet",
    ]);
    let a = fs::read(&one).unwrap();
    assert_eq!(a, fs::read(&two).unwrap());
    let t = read_table(a).unwrap();
    let g = ROW_GROUP_ROWS as u64;
    assert_eq!(t.group_rows(), vec![g, g, 150_000 - 2 * g]);
    // No journal is left after a finished run.
    assert!(!dir.path().join(".one.parquet.commit").exists());
}

#[test]
fn parquet_resume_drops_a_torn_trailing_group() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", BIG);
    let full = dir.path().join("full.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&full),
        "--format",
        "parquet",
        "--quiet",
    ]);
    let want = fs::read(&full).unwrap();
    let table = read_table(want.clone()).unwrap();
    // The state of a run killed while writing group 2: group 1 committed (its
    // footer in the journal: the file of a run limited to one group), then
    // part of group 2, and no footer.
    let one = dir.path().join("one.parquet");
    let limit = ROW_GROUP_ROWS.to_string();
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&one),
        "--format",
        "parquet",
        "--limit",
        &limit,
        "--quiet",
    ]);
    let one_bytes = fs::read(&one).unwrap();
    let end = table.end_of_groups(1) as usize;
    assert_eq!(one_bytes[..end], want[..end]);
    let footer = &one_bytes[end..];
    let killed = dir.path().join("killed.parquet");
    fs::write(&killed, &want[..end + 5000]).unwrap();
    fs::write(
        dir.path().join(".killed.parquet.commit"),
        journal_bytes(end as u64, footer),
    )
    .unwrap();
    let o = ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&killed),
        "--format",
        "parquet",
        "--resume",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("at row {ROW_GROUP_ROWS}")), "{err}");
    assert_eq!(fs::read(&killed).unwrap(), want);
    assert_eq!(summary(&killed), summary(&full));
    assert!(!dir.path().join(".killed.parquet.commit").exists());
    // A finished file resumes to itself; a shorter last group (a finished
    // --limit run) is evaluated again, so extending it gives the full file.
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&killed),
        "--format",
        "parquet",
        "--resume",
        "--quiet",
    ]);
    assert_eq!(fs::read(&killed).unwrap(), want);
    let short = dir.path().join("short.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&short),
        "--format",
        "parquet",
        "--limit",
        "70000",
        "--quiet",
    ]);
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&short),
        "--format",
        "parquet",
        "--resume",
        "--quiet",
    ]);
    assert_eq!(fs::read(&short).unwrap(), want);
    // Torn without its journal: refused, the file left as it was.
    let torn = dir.path().join("torn.parquet");
    fs::write(&torn, &want[..end + 5000]).unwrap();
    let o = run(&[
        "sweep",
        s(&spec),
        "--out",
        s(&torn),
        "--format",
        "parquet",
        "--resume",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("torn"));
    assert_eq!(fs::read(&torn).unwrap(), &want[..end + 5000]);
}

#[test]
fn parquet_resume_after_sigkill_is_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "k.toml",
        r#"
scheme = "nurds"
valences = [6, 9]
[space]
kind = "face-ep"
interval_range = [0.1, 10.0]
[sampler]
kind = "sobol"
count = 100000
"#,
    );
    let full = dir.path().join("full.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&full),
        "--format",
        "parquet",
        "--quiet",
    ]);
    let want = fs::read(&full).unwrap();
    for round in 0..2 {
        let p = dir.path().join(format!("killed{round}.parquet"));
        let mut child = Command::new(BIN)
            .args([
                "sweep",
                s(&spec),
                "--out",
                s(&p),
                "--format",
                "parquet",
                "--threads",
                "2",
            ])
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // Kill (SIGKILL) after the first commit (round 0) or a little later.
        let target = (want.len() / 8 * (1 + 2 * round)) as u64;
        let start = std::time::Instant::now();
        while fs::metadata(&p).map(|m| m.len()).unwrap_or(0) < target
            && start.elapsed() < std::time::Duration::from_secs(120)
        {
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        child.kill().unwrap();
        child.wait().unwrap();
        ok(&[
            "sweep",
            s(&spec),
            "--out",
            s(&p),
            "--format",
            "parquet",
            "--resume",
            "--quiet",
        ]);
        assert_eq!(fs::read(&p).unwrap(), want, "round {round}");
        assert_eq!(summary(&p), summary(&full));
    }
}

#[test]
fn parquet_resume_verifies_the_committed_rows() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s.toml", SMALL);
    let pq = dir.path().join("s.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--quiet",
    ]);
    let bytes = fs::read(&pq).unwrap();
    let t = read_table(bytes.clone()).unwrap();
    // Change the bytes of one coordinate (PLAIN-encoded doubles): the
    // parameters re-derived from the id no longer match.
    let Some(Column::F64(r1)) = t.column("r1") else {
        panic!("r1")
    };
    let x = r1[17].unwrap();
    let needle = x.to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w == needle)
        .expect("the value's bytes");
    let mut edited = bytes.clone();
    edited[at..at + 8].copy_from_slice(&(x * 0.5).to_le_bytes());
    fs::write(&pq, &edited).unwrap();
    let o = run(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--resume",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("r1"), "{err}");
    assert_eq!(fs::read(&pq).unwrap(), edited);
    // Another spec's file is refused by its fingerprint.
    fs::write(&pq, &bytes).unwrap();
    let other = write_spec(dir.path(), "o.toml", &SMALL.replace("seed = 5", "seed = 6"));
    let o = run(&[
        "sweep",
        s(&other),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--resume",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("another spec"));
    assert_eq!(fs::read(&pq).unwrap(), bytes);
}

#[test]
fn parquet_shards_merge_to_the_unsharded_file() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "b.toml", &BIG.replace("150000", "70000"));
    let full = dir.path().join("full.parquet");
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&full),
        "--format",
        "parquet",
        "--quiet",
    ]);
    let mut shards = Vec::new();
    for i in 0..3 {
        let p = dir.path().join(format!("shard-{i}.parquet"));
        let shard = format!("{i}/3");
        ok(&[
            "sweep",
            s(&spec),
            "--out",
            s(&p),
            "--format",
            "parquet",
            "--shard",
            &shard,
            "--quiet",
        ]);
        shards.push(p);
    }
    let merged = dir.path().join("merged.parquet");
    let mut args = vec!["merge", "--spec", s(&spec), "--out", s(&merged)];
    args.extend(shards.iter().map(|p| s(p)));
    ok(&args);
    assert_eq!(fs::read(&merged).unwrap(), fs::read(&full).unwrap());
    assert_eq!(summary(&merged), summary(&full));
    // A shard of another spec is refused by its fingerprint.
    let other = write_spec(dir.path(), "o.toml", &BIG.replace("150000", "70001"));
    let foreign = dir.path().join("foreign.parquet");
    ok(&[
        "sweep",
        s(&other),
        "--out",
        s(&foreign),
        "--format",
        "parquet",
        "--shard",
        "2/3",
        "--quiet",
    ]);
    fs::copy(
        dir.path().join("foreign.summary.json"),
        dir.path().join("shard-2.summary.json"),
    )
    .unwrap();
    fs::copy(&foreign, &shards[2]).unwrap();
    let out2 = dir.path().join("merged2.parquet");
    let mut args = vec!["merge", "--spec", s(&spec), "--out", s(&out2)];
    args.extend(shards.iter().map(|p| s(p)));
    let o = run(&args);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("another spec"));
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
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--quiet",
    ]);
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
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--quiet",
    ]);
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
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&pq),
        "--format",
        "parquet",
        "--quiet",
    ]);
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
