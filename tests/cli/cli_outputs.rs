//! The one rule for outputs (README, "Files"), the positive side; the
//! refusals are rows of the hostile-input table.
//!
//! * A single-file output (`-o FILE`, `merge --out FILE`) replaces a regular
//!   file atomically: a new file is renamed over it, so another hard link to
//!   the old file keeps the old bytes, and no temporary is left beside it.
//! * Directories and resumable outputs are touched only when the tool wrote
//!   them: a previous `verify` output keeps the user's other files; a
//!   finished sweep resumed is left as it was (its summary keeps the
//!   throughput of the run that wrote the rows).
//!
//! Also: `plot` counts the rows it leaves out, draws `verify`'s cells as the
//! certified map, and refuses only SVGs (not PNGs) of many points; the
//! `--help` texts state the accepted ranges and the output rule.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

/// A one-valence NURDS sweep of 8 configurations.
const SPEC: &str = "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n";

/// A small verify spec (n = 3, class and separation, wide cells).
const VERIFY: &str = "name = \"v\"\nscheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\", \"separation\"]\nmin_width = 0.1\n";

fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("binary runs")
}

fn ok_in(dir: &Path, args: &[&str]) -> Output {
    let o = run_in(dir, args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// `-o` of plot, g2-cap and subdivide and `merge --out` replace a user's
/// regular file by a rename: the file at the path is new, a hard link to the
/// old one still holds the user's bytes, nothing else is left behind.
#[test]
fn single_file_outputs_replace_a_regular_file_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("h.toml"), SPEC).unwrap();
    ok_in(d, &["sweep", "h.toml", "--out", "a.csv", "--quiet"]);
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/meshes/cube.obj");
    let runs: [(&str, Vec<&str>, &str); 4] = [
        ("f.svg", vec!["plot", "a.csv", "-o", "f.svg"], "<svg"),
        (
            "cap.obj",
            vec![
                "g2-cap",
                "--valence",
                "3",
                "--random-net",
                "1",
                "--c",
                "0.5",
                "-o",
                "cap.obj",
            ],
            "# subdiv-lab g2-cap",
        ),
        (
            "sub.obj",
            vec!["subdivide", cube, "--scheme", "nurds", "-o", "sub.obj"],
            "\nf ",
        ),
        (
            "m.csv",
            vec!["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            "id,valence,",
        ),
    ];
    for (target, args, marker) in runs {
        fs::write(d.join(target), "mine\n").unwrap();
        fs::hard_link(d.join(target), d.join("link")).unwrap();
        let before = names(d);
        ok_in(d, &args);
        let new = fs::read_to_string(d.join(target)).unwrap();
        assert!(new.contains(marker), "{args:?}: {new:.80}");
        assert_eq!(
            fs::read_to_string(d.join("link")).unwrap(),
            "mine\n",
            "{args:?} wrote into the user's file instead of replacing it"
        );
        let mut after = names(d);
        after.retain(|n| n != "m.summary.json");
        assert_eq!(after, before, "{args:?}: a temporary was left");
        fs::remove_file(d.join("link")).unwrap();
    }
}

/// A previous `verify` output is re-run in place: its two files are
/// replaced, a file the user put beside them is not touched.
#[test]
fn output_directories_are_touched_only_when_the_tool_wrote_them() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("v.toml"), VERIFY).unwrap();
    fs::create_dir(d.join("empty")).unwrap();
    ok_in(d, &["verify", "v.toml", "--out", "empty", "--quiet"]);
    assert_eq!(names(&d.join("empty")), ["cells.csv", "summary.json"]);
    fs::write(d.join("empty/notes.txt"), "mine").unwrap();
    fs::write(d.join("empty/cells.csv"), "stale").unwrap();
    ok_in(d, &["verify", "v.toml", "--out", "empty", "--quiet"]);
    assert_eq!(
        fs::read_to_string(d.join("empty/notes.txt")).unwrap(),
        "mine"
    );
    assert!(fs::read_to_string(d.join("empty/cells.csv"))
        .unwrap()
        .starts_with("lo0,lo1,lo2,hi0,hi1,hi2,verdict,class,separation\n"));
}

/// `sweep --out NAME.parquet` without `--format` writes Parquet and says so;
/// resuming a finished sweep (CSV or Parquet) evaluates nothing, says it is
/// complete, and leaves the file and its summary (with the throughput of
/// the run that wrote the rows) byte for byte as they were.
#[test]
fn resuming_a_finished_sweep_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("h.toml"), SPEC).unwrap();
    let o = ok_in(d, &["sweep", "h.toml", "--out", "p.parquet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("writing Parquet (from the extension of --out p.parquet)"),
        "{err}"
    );
    let part = "p.parquet/part-000000.parquet";
    assert!(fs::read(d.join(part)).unwrap().starts_with(b"PAR1"));
    ok_in(d, &["sweep", "h.toml", "--out", "c.csv", "--quiet"]);
    for (name, file) in [("c.csv", "c.csv"), ("p.parquet", part)] {
        let stem = name.split('.').next().unwrap();
        let summary = d.join(format!("{stem}.summary.json"));
        let (rows, json) = (fs::read(d.join(file)).unwrap(), fs::read(&summary).unwrap());
        let o = ok_in(d, &["sweep", "h.toml", "--out", name, "--resume"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(&format!("{name} is already complete: 8 rows verified")),
            "{err}"
        );
        assert_eq!(fs::read(d.join(file)).unwrap(), rows, "{name}");
        assert_eq!(
            fs::read(&summary).unwrap(),
            json,
            "{name}: summary rewritten"
        );
    }
}

/// `plot` says how many rows it left out (missing, NaN, infinite); draws
/// `verify`'s cells.csv as the certified map; writes a PNG of more points
/// than an SVG may hold.
#[test]
fn plot_counts_dropped_rows_and_draws_verify_cells() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("s.csv"), "a,b\n1,2\n2,NaN\n3,inf\n4,\n5,6\n6,7\n").unwrap();
    let o = ok_in(
        d,
        &[
            "plot", "s.csv", "-o", "s.svg", "--kind", "scatter", "--x", "a", "--y", "b",
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("left out 3 of 6 rows without a finite a or b (missing, NaN or infinite)"),
        "{err}"
    );
    let o = ok_in(
        d,
        &[
            "plot",
            "s.csv",
            "-o",
            "h.svg",
            "--kind",
            "histogram",
            "--x",
            "a",
        ],
    );
    assert!(o.stderr.is_empty(), "nothing left out: {:?}", o.stderr);

    fs::write(d.join("v.toml"), VERIFY).unwrap();
    ok_in(d, &["verify", "v.toml", "--out", "v", "--quiet"]);
    ok_in(d, &["plot", "v/cells.csv", "-o", "map.svg"]);
    let svg = fs::read_to_string(d.join("map.svg")).unwrap();
    assert!(
        svg.contains("Certified map: verdict over r0 and r1, at r2 = 0.5"),
        "title"
    );
    assert!(svg.contains("complex pair") && svg.contains("real distinct"));
    assert!(!svg.contains("Histogram"));

    let mut many = String::from("a,b\n");
    for i in 0..100_001 {
        many.push_str(&format!("{},{}\n", i % 1000, i / 1000));
    }
    fs::write(d.join("many.csv"), many).unwrap();
    ok_in(
        d,
        &[
            "plot", "many.csv", "-o", "many.png", "--kind", "scatter", "--x", "a", "--y", "b",
        ],
    );
    assert!(fs::read(d.join("many.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
}

/// The `--help` texts state the accepted ranges and the output rule.
#[test]
fn help_states_ranges_and_the_output_rule() {
    let dir = tempfile::tempdir().unwrap();
    let help = |args: &[&str]| String::from_utf8(ok_in(dir.path(), args).stdout).unwrap();
    let top = help(&["--help"]);
    for cmd in ["sweep", "merge"] {
        let line = top
            .lines()
            .find(|l| l.trim_start().starts_with(cmd))
            .unwrap();
        assert!(line.contains("Parquet"), "{line}");
    }
    let checks: [(&[&str], &[&str]); 6] = [
        (&["merge", "--help"], &["Parquet", "replaced atomically"]),
        (
            &["sweep", "--help"],
            &["NAME.parquet", "never replaced", "summary is of this spec"],
        ),
        (
            &["verify", "--help"],
            &[
                "p_box",
                "q_box",
                "nurds 3 to 16",
                "2^-40",
                "any other directory",
            ],
        ),
        (
            &["g2-cap", "--help"],
            &["3 to 16", "1 to 256", "replaced atomically"],
        ),
        (
            &["cc-study", "--help"],
            &["at most 256", "1 to 100000", "2^-52"],
        ),
        (
            &["plot", "--help"],
            &["400 to 8000", "replaced atomically", "100000 points"],
        ),
    ];
    for (args, needles) in checks {
        let text = help(args).split_whitespace().collect::<Vec<_>>().join(" ");
        for n in needles {
            assert!(text.contains(n), "{args:?} lacks {n:?}");
        }
    }
    let sub = help(&["subdivide", "--help"]);
    assert!(sub
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .contains("replaced atomically"));
}
