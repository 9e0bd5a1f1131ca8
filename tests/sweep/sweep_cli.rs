//! End-to-end tests of `subdiv-lab sweep` and `subdiv-lab merge`: sharding,
//! resume after a torn write, thread-count independence, bad specs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_subdiv-lab");

/// n = 3 and 4 on a grid: 9^3 + 9^4 = 7290 configurations (two CSV chunks and more).
const SPEC: &str = r#"
name = "test-grid"
scheme = "nurds"
valences = [3, 4]

[space]
kind = "ratios"
ratio_range = [0.05, 0.95]

[sampler]
kind = "grid"
points_per_axis = 9

[columns]
eigenvalues = 3
"#;

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
        "{args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The summary file beside a sweep CSV.
fn summary_of(p: &Path) -> std::path::PathBuf {
    p.with_file_name(
        p.file_name()
            .unwrap()
            .to_str()
            .unwrap()
            .replace(".csv", ".summary.json"),
    )
}

fn summary(p: &Path) -> serde_json::Value {
    let sp = summary_of(p);
    let mut v: serde_json::Value = serde_json::from_str(&fs::read_to_string(sp).unwrap()).unwrap();
    v.as_object_mut().unwrap().remove("throughput");
    v
}

/// Cuts the file in the middle of data row `row` (0-based; after the header
/// line), as a kill mid-write would.
fn truncate_mid_line(path: &Path, row: usize) {
    let bytes = fs::read(path).unwrap();
    let starts: Vec<usize> = std::iter::once(0)
        .chain(
            bytes
                .iter()
                .enumerate()
                .filter(|(_, b)| **b == b'\n')
                .map(|(i, _)| i + 1),
        )
        .collect();
    let (a, b) = (starts[row + 1], starts[row + 2]);
    let cut = a + (b - a) / 2;
    assert!(cut > a && cut < b - 1);
    fs::write(path, &bytes[..cut]).unwrap();
}

#[test]
fn full_run_shape_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let out = dir.path().join("g.csv");
    ok(&["sweep", s(&spec), "--out", s(&out)]);
    let text = fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 1 + 729 + 6561);
    assert!(lines[0].starts_with("id,valence,r0,r1,r2,r3,class,"));
    for (j, l) in lines[1..].iter().enumerate() {
        assert!(l.starts_with(&format!("{j},")), "{l}");
        assert!(l.ends_with(','), "row {j} has an error: {l}");
    }
    let sm = summary(&out);
    // The fingerprint: spec, digest and shard in the summary.
    assert_eq!(sm["spec_name"], "test-grid");
    assert_eq!(sm["spec_digest"].as_str().unwrap().len(), 16);
    assert_eq!(sm["shard"]["count"], 1);
    assert_eq!(sm["total_configurations"], 7290);
    assert_eq!(sm["rows"], 7290);
    assert_eq!(sm["complete"], true);
    assert_eq!(sm["errors"], 0);
    let per_valence: u64 = sm["classes"]["3"]
        .as_object()
        .unwrap()
        .values()
        .map(|v| v.as_u64().unwrap())
        .sum();
    assert_eq!(per_valence, 729);
    // Extremes of the coordinate columns are the grid ends.
    let cols = sm["columns"].as_array().unwrap();
    let r0 = cols.iter().find(|c| c["name"] == "r0").unwrap();
    assert_eq!(r0["min"], 0.05);
    assert_eq!(r0["min_id"], 0);
    assert_eq!(r0["max"], 0.95);
    let rate = cols
        .iter()
        .find(|c| c["name"] == "contraction_rate")
        .unwrap();
    assert!(rate["max"].as_f64().unwrap() < 0.75);
}

#[test]
fn thread_count_does_not_change_output() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let a = dir.path().join("a.csv");
    let b = dir.path().join("b.csv");
    ok(&["sweep", s(&spec), "--out", s(&a), "--threads", "1"]);
    ok(&["sweep", s(&spec), "--out", s(&b), "--threads", "2"]);
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
    assert_eq!(summary(&a), summary(&b));
    // Standard output carries the same CSV.
    let o = ok(&["sweep", s(&spec), "--threads", "2"]);
    assert_eq!(o.stdout, fs::read(&a).unwrap());
}

#[test]
fn shards_partition_the_sweep_and_merge_back() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let full = dir.path().join("full.csv");
    ok(&["sweep", s(&spec), "--out", s(&full)]);
    let n = 3;
    let mut shards = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for i in 0..n {
        let p = dir.path().join(format!("shard-{i}.csv"));
        ok(&[
            "sweep",
            s(&spec),
            "--out",
            s(&p),
            "--shard",
            &format!("{i}/{n}"),
        ]);
        for l in fs::read_to_string(&p).unwrap().lines().skip(1) {
            let id: u64 = l.split(',').next().unwrap().parse().unwrap();
            assert_eq!(id % n, i);
            assert!(seen.insert(id), "id {id} in two shards");
        }
        shards.push(p);
    }
    assert_eq!(seen.len(), 7290);
    assert_eq!(*seen.iter().next_back().unwrap(), 7289);
    let merged = dir.path().join("merged.csv");
    let mut args = vec!["merge", "--spec", s(&spec)];
    args.extend(shards.iter().map(|p| s(p)));
    args.extend(["--out", s(&merged)]);
    ok(&args);
    assert_eq!(fs::read(&merged).unwrap(), fs::read(&full).unwrap());
    assert_eq!(summary(&merged), summary(&full));

    // A missing shard: the error names the first missing id, and no output appears.
    let bad = dir.path().join("bad.csv");
    let o = run(&[
        "merge",
        "--spec",
        s(&spec),
        s(&shards[0]),
        s(&shards[2]),
        "--out",
        s(&bad),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("configuration id 1 is missing"), "{err}");
    assert!(!bad.exists());
    // A duplicated shard.
    let o = run(&[
        "merge",
        "--spec",
        s(&spec),
        s(&shards[0]),
        s(&shards[1]),
        s(&shards[2]),
        s(&shards[1]),
        "--out",
        s(&bad),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("configuration id 1 appears twice"), "{err}");
    assert!(!bad.exists());
}

#[test]
fn resume_after_torn_write_is_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let full = dir.path().join("full.csv");
    ok(&["sweep", s(&spec), "--out", s(&full)]);
    let expected = fs::read(&full).unwrap();
    for (shard, rows) in [(None, 7290usize), (Some("1/2"), 3645)] {
        let mut reference = full.clone();
        if let Some(sh) = shard {
            reference = dir.path().join("ref-shard.csv");
            let _ = fs::remove_file(&reference);
            ok(&["sweep", s(&spec), "--out", s(&reference), "--shard", sh]);
        }
        let want = fs::read(&reference).unwrap();
        for cut_row in [0usize, 1, rows / 2, 4095, 4096, rows - 1]
            .into_iter()
            .filter(|r| *r < rows)
        {
            let p = dir.path().join(format!("cut-{cut_row}.csv"));
            let _ = fs::remove_file(&p);
            fs::copy(&reference, &p).unwrap();
            fs::copy(summary_of(&reference), summary_of(&p)).unwrap();
            truncate_mid_line(&p, cut_row);
            // Without --resume the existing file is refused.
            let o = run(&["sweep", s(&spec), "--out", s(&p)]);
            assert_eq!(o.status.code(), Some(2));
            let mut args = vec!["sweep", s(&spec), "--out", s(&p), "--resume"];
            if let Some(sh) = shard {
                args.extend(["--shard", sh]);
            }
            ok(&args);
            assert_eq!(
                fs::read(&p).unwrap(),
                want,
                "cut in row {cut_row}, shard {shard:?}"
            );
            assert_eq!(summary(&p), summary(&reference));
        }
    }
    // Torn inside the header (beside the summary written before it), and an
    // interrupted --limit run continued in steps.
    let p = dir.path().join("steps.csv");
    fs::copy(summary_of(&full), summary_of(&p)).unwrap();
    fs::write(&p, "id,vale").unwrap();
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&p),
        "--resume",
        "--limit",
        "10",
    ]);
    let ten = fs::read_to_string(&p).unwrap();
    assert_eq!(ten.lines().count(), 11);
    assert!(String::from_utf8_lossy(&expected).starts_with(&ten));
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&p),
        "--resume",
        "--limit",
        "5000",
    ]);
    ok(&["sweep", s(&spec), "--out", s(&p), "--resume"]);
    assert_eq!(fs::read(&p).unwrap(), expected);
    assert_eq!(summary(&p), summary(&full));
}

#[test]
fn resume_refuses_a_changed_spec() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let p = dir.path().join("g.csv");
    ok(&["sweep", s(&spec), "--out", s(&p), "--limit", "100"]);
    let other = write_spec(dir.path(), "h.toml", &SPEC.replace("0.95", "0.9"));
    let o = run(&["sweep", s(&other), "--out", s(&p), "--resume"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("g.csv: written by another spec (digest "),
        "{err}"
    );
    // And a row with a wrong id is named with its line.
    let text = fs::read_to_string(&p).unwrap().replacen("\n5,", "\n6,", 1);
    fs::write(&p, text).unwrap();
    let o = run(&["sweep", s(&spec), "--out", s(&p), "--resume"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("line 7: configuration id 6 where 5 was expected"),
        "{err}"
    );
}

#[test]
fn bad_specs_name_the_key_and_create_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(String, &str)> = vec![
        (
            SPEC.replace("points_per_axis = 9", "points_per_axis = 0"),
            "sampler.points_per_axis must be >= 1, got 0",
        ),
        (
            SPEC.replace("[0.05, 0.95]", "[0.7, 0.2]"),
            "space.ratio_range: lower bound 0.7 > upper bound 0.2",
        ),
        (
            SPEC.replace("[0.05, 0.95]", "[0.0, 0.5]"),
            "space.ratio_range: bound 0.0 is outside the open interval (0, 1)",
        ),
        (
            SPEC.replace("[0.05, 0.95]", "[0.5, 1.5]"),
            "space.ratio_range: bound 1.5 is outside",
        ),
        (
            SPEC.replace("[0.05, 0.95]", "[0.3, 0.3]"),
            "space.ratio_range: empty range",
        ),
        (
            SPEC.replace("valences = [3, 4]", "valences = []"),
            "valences: empty list",
        ),
        (
            SPEC.replace("valences = [3, 4]", "valences = { from = 6, to = 4 }"),
            "valences: empty range",
        ),
        (
            SPEC.replace("valences = [3, 4]", "valences = [2, 4]"),
            "valences[0] must be a valence",
        ),
        (
            SPEC.replace("eigenvalues = 3", "eigenvalues = 3\nspeed = 1"),
            "columns.speed: unknown field",
        ),
        (
            SPEC.replace("kind = \"grid\"", "kind = \"grid\"\nsed = 1"),
            "sampler.sed: unknown field",
        ),
        (
            SPEC.replace("name = \"test-grid\"", "nme = \"x\""),
            "nme: unknown field",
        ),
        (
            SPEC.replace("kind = \"grid\"", "kind = \"latin\""),
            "sampler.kind: unknown sampler",
        ),
        (
            SPEC.replace("kind = \"ratios\"", "kind = \"corner-intervals\""),
            "space.ratio_range is not used",
        ),
        (
            SPEC.replace(
                "ratio_range = [0.05, 0.95]",
                "ratio_range = [0.05, 0.95]\nfixed = { r9 = 0.5 }",
            ),
            "space.fixed.r9: unknown coordinate",
        ),
        (
            SPEC.replace(
                "kind = \"grid\"\npoints_per_axis = 9",
                "kind = \"random\"\ncount = 10",
            ),
            "sampler.seed is required",
        ),
    ];
    for (k, (text, want)) in cases.iter().enumerate() {
        let spec = write_spec(dir.path(), &format!("bad{k}.toml"), text);
        let out = dir.path().join(format!("bad{k}.csv"));
        let o = run(&["sweep", s(&spec), "--out", s(&out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "case {k}: {err}");
        assert!(err.contains(want), "case {k}: {err:?} lacks {want:?}");
        assert!(err.contains("(line "), "case {k}: no line in {err:?}");
        assert_eq!(err.trim_end().lines().count(), 1, "case {k}: {err:?}");
        assert!(!out.exists(), "case {k} created {}", out.display());
        assert!(!dir.path().join(format!("bad{k}.summary.json")).exists());
        assert!(o.stdout.is_empty());
    }
    // Bad flags: also no file.
    let spec = write_spec(dir.path(), "good.toml", SPEC);
    let out = dir.path().join("flags.csv");
    for flags in [
        vec!["--shard", "3/3"],
        vec!["--threads", "0"],
        vec!["--shard", "x"],
    ] {
        let mut args = vec!["sweep", s(&spec), "--out", s(&out)];
        args.extend(flags.iter().copied());
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{flags:?}");
        assert!(!out.exists());
    }
}

#[test]
fn resume_after_sigkill_is_byte_identical() {
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
count = 60000
"#,
    );
    let full = dir.path().join("full.csv");
    ok(&["sweep", s(&spec), "--out", s(&full)]);
    let want = fs::read(&full).unwrap();
    let p = dir.path().join("killed.csv");
    let mut child = Command::new(BIN)
        .args(["sweep", s(&spec), "--out", s(&p), "--threads", "2"])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Kill (SIGKILL) once some rows are on disk but before the end.
    let start = std::time::Instant::now();
    while fs::metadata(&p).map(|m| m.len()).unwrap_or(0) < (want.len() / 4) as u64
        && start.elapsed() < std::time::Duration::from_secs(60)
    {
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let partial = fs::read(&p).unwrap();
    assert!(want.starts_with(&partial[..partial.iter().rposition(|b| *b == b'\n').unwrap()]));
    ok(&["sweep", s(&spec), "--out", s(&p), "--resume"]);
    assert_eq!(fs::read(&p).unwrap(), want);
    assert_eq!(summary(&p), summary(&full));
}

/// Replaces column `col` of data row `row` (0-based) of the CSV at `p`.
fn edit_field(p: &Path, row: usize, col: &str, value: &str) {
    let text = fs::read_to_string(p).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let k = lines[0].split(',').position(|c| c == col).unwrap();
    let mut f: Vec<&str> = lines[row + 1].split(',').collect();
    assert_ne!(f[k], value);
    f[k] = value;
    lines[row + 1] = f.join(",");
    fs::write(p, lines.join("\n") + "\n").unwrap();
}

fn refused(args: &[&str], needle: &str) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(needle), "{args:?}: wanted {needle:?} in {err}");
}

#[test]
fn resume_verifies_every_row_in_full() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let good = dir.path().join("good.csv");
    ok(&["sweep", s(&spec), "--out", s(&good), "--limit", "20"]);
    let p = dir.path().join("g.csv");
    // The summary written with the file (its fingerprint).
    fs::copy(summary_of(&good), summary_of(&p)).unwrap();
    let resume = [
        "sweep",
        s(&spec),
        "--out",
        s(&p),
        "--resume",
        "--limit",
        "30",
    ];
    let cases: [(&str, &str, &str); 7] = [
        (
            "class",
            "0.123456789",
            "line 12: class = \"0.123456789\" is not a value",
        ),
        ("class", "bogus", "class = \"bogus\" is not a value"),
        (
            "lambda1_re",
            "0.5",
            "line 12: configuration 10 differs from a fresh evaluation: lambda1_re",
        ),
        ("lambda1_im", "x", "lambda1_im = \"x\" is not a number"),
        (
            "abs_lambda3",
            "-0.25",
            "abs_lambda3 = -0.25 is out of range",
        ),
        (
            "r0",
            "0.5",
            "configuration 10 has r0 = \"0.5\" where the spec gives",
        ),
        (
            "error",
            "boom",
            "configuration 10 has an error and a result",
        ),
    ];
    for (k, value, needle) in cases {
        fs::copy(&good, &p).unwrap();
        edit_field(&p, 10, k, value);
        let before = fs::read(&p).unwrap();
        refused(&resume, needle);
        assert_eq!(
            fs::read(&p).unwrap(),
            before,
            "a refused resume leaves the file"
        );
    }
    // A field too many, and a valid but different class.
    fs::copy(&good, &p).unwrap();
    let text = fs::read_to_string(&p)
        .unwrap()
        .replacen("\n10,", "\n10,3,", 1);
    fs::write(&p, text).unwrap();
    refused(&resume, "line 12: expected 24 fields, found 25");
    fs::copy(&good, &p).unwrap();
    let row10: Vec<String> = fs::read_to_string(&p)
        .unwrap()
        .lines()
        .nth(11)
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let other = if row10[6] == "complex_pair" {
        "real_distinct"
    } else {
        "complex_pair"
    };
    edit_field(&p, 10, "class", other);
    refused(
        &resume,
        "line 12: configuration 10 differs from a fresh evaluation: class",
    );
    // The untouched file resumes.
    fs::copy(&good, &p).unwrap();
    ok(&resume);
}

#[test]
fn foreign_files_and_shard_counts_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "r.toml", "name = \"r\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"corner-intervals\"\ninterval_range = [0.1, 10.0]\n[sampler]\nkind = \"random\"\ncount = 40\nseed = 1\n");
    let other = write_spec(
        dir.path(),
        "o.toml",
        &fs::read_to_string(&spec)
            .unwrap()
            .replace("seed = 1", "seed = 2"),
    );
    let d = dir.path();
    for i in 0..2 {
        let sh = format!("{i}/2");
        ok(&[
            "sweep",
            s(&spec),
            "--out",
            s(&d.join(format!("a-{i}.csv"))),
            "--shard",
            &sh,
        ]);
        ok(&[
            "sweep",
            s(&other),
            "--out",
            s(&d.join(format!("b-{i}.csv"))),
            "--shard",
            &sh,
        ]);
    }
    let out = d.join("m.csv");
    ok(&[
        "merge",
        "--spec",
        s(&spec),
        s(&d.join("a-0.csv")),
        s(&d.join("a-1.csv")),
        "--out",
        s(&out),
    ]);
    // A shard of the other seed beside this spec's summary.
    fs::copy(d.join("b-1.csv"), d.join("x-1.csv")).unwrap();
    fs::copy(d.join("a-1.summary.json"), d.join("x-1.summary.json")).unwrap();
    let bad = d.join("bad.csv");
    refused(
        &[
            "merge",
            "--spec",
            s(&spec),
            s(&d.join("a-0.csv")),
            s(&d.join("x-1.csv")),
            "--out",
            s(&bad),
        ],
        "x-1.csv: line 2: configuration 1 has p0 = ",
    );
    // Its own summary with it: the summary is refused first.
    refused(
        &[
            "merge",
            "--spec",
            s(&spec),
            s(&d.join("a-0.csv")),
            s(&d.join("b-1.csv")),
            "--out",
            s(&bad),
        ],
        "b-1.summary.json: the summary of another spec",
    );
    // A bogus class in a shard.
    fs::copy(d.join("a-1.csv"), d.join("y-1.csv")).unwrap();
    fs::copy(d.join("a-1.summary.json"), d.join("y-1.summary.json")).unwrap();
    edit_field(&d.join("y-1.csv"), 3, "class", "bogus");
    refused(
        &[
            "merge",
            "--spec",
            s(&spec),
            s(&d.join("a-0.csv")),
            s(&d.join("y-1.csv")),
            "--out",
            s(&bad),
        ],
        "y-1.csv: line 5: class = \"bogus\"",
    );
    // An edited summary.
    fs::copy(d.join("a-1.csv"), d.join("z-1.csv")).unwrap();
    let sm = fs::read_to_string(d.join("a-1.summary.json")).unwrap();
    let edited = sm.replacen("\"errors\": 0", "\"errors\": 1", 1);
    assert_ne!(edited, sm);
    fs::write(d.join("z-1.summary.json"), edited).unwrap();
    refused(
        &[
            "merge",
            "--spec",
            s(&spec),
            s(&d.join("a-0.csv")),
            s(&d.join("z-1.csv")),
            "--out",
            s(&bad),
        ],
        "z-1.summary.json: the summary does not match the rows",
    );
    assert!(!bad.exists());
    // Resuming shard 1 of 2 as shard 1 of 3.
    refused(
        &["sweep", s(&spec), "--out", s(&d.join("a-1.csv")), "--resume", "--shard", "1/3"],
        "written as shard 1/2 of 2 shards, but this run is shard 1/3 of 3: the shard count must be the same",
    );
    refused(
        &[
            "sweep",
            s(&spec),
            "--out",
            s(&d.join("a-1.csv")),
            "--resume",
            "--shard",
            "0/2",
        ],
        "written as shard 1/2, but this run is shard 0/2",
    );
}

#[test]
fn resume_limit_boundaries() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let eleven = dir.path().join("eleven.csv");
    ok(&["sweep", s(&spec), "--out", s(&eleven), "--limit", "11"]);
    let ten = dir.path().join("ten.csv");
    ok(&["sweep", s(&spec), "--out", s(&ten), "--limit", "10"]);
    // 11 rows resumed with --limit 10: refused, file untouched.
    let before = fs::read(&eleven).unwrap();
    refused(
        &[
            "sweep",
            s(&spec),
            "--out",
            s(&eleven),
            "--resume",
            "--limit",
            "10",
        ],
        "has more rows than this run expects (10)",
    );
    assert_eq!(fs::read(&eleven).unwrap(), before);
    // 10 then 10: nothing to do, file unchanged.
    let ten_bytes = fs::read(&ten).unwrap();
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&ten),
        "--resume",
        "--limit",
        "10",
    ]);
    assert_eq!(fs::read(&ten).unwrap(), ten_bytes);
    assert_eq!(summary(&ten)["rows"], 10);
    // 10 then 11: continues to the 11-row file.
    ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&ten),
        "--resume",
        "--limit",
        "11",
    ]);
    assert_eq!(fs::read(&ten).unwrap(), before);
    assert_eq!(summary(&ten), summary(&eleven));
}

#[test]
fn progress_lines_without_a_terminal_and_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "g.toml", SPEC);
    let p = dir.path().join("g.csv");
    // stderr is a pipe here (not a terminal): progress lines, then the closing line.
    let o = ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&p),
        "--progress-every",
        "0.01",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.lines()
            .any(|l| l.starts_with("sweep: ") && l.contains("/7290 rows (") && l.contains("ETA")),
        "{err}"
    );
    assert!(
        err.lines().last().unwrap().starts_with("sweep: 7290 rows"),
        "{err}"
    );
    let q = dir.path().join("q.csv");
    let o = ok(&[
        "sweep",
        s(&spec),
        "--out",
        s(&q),
        "--progress-every",
        "0.01",
        "--quiet",
    ]);
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
    assert_eq!(fs::read(&q).unwrap(), fs::read(&p).unwrap());
}

/// A row whose float class is indeterminate has an empty `exact_agrees`
/// (the two classes cannot be compared): resume and merge accept it.
#[test]
fn resume_and_merge_accept_an_empty_exact_agrees() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "x.toml",
        "name = \"x\"\nscheme = \"nurds\"\nvalences = [4]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\nfixed = { r2 = 0.5, r3 = 0.5 }\n[sampler]\nkind = \"grid\"\npoints_per_axis = 3\n[columns]\nexact_certificate = true\n",
    );
    let p = dir.path().join("x.csv");
    ok(&["sweep", s(&spec), "--out", s(&p), "--limit", "5"]);
    let text = fs::read_to_string(&p).unwrap();
    assert!(
        text.contains(",indeterminate:") && text.contains(",,\n"),
        "{text}"
    );
    ok(&["sweep", s(&spec), "--out", s(&p), "--resume"]);
    let m = dir.path().join("m.csv");
    ok(&["merge", "--spec", s(&spec), s(&p), "--out", s(&m)]);
    assert_eq!(fs::read(&m).unwrap(), fs::read(&p).unwrap());
}
