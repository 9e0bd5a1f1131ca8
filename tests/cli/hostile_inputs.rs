//! The hostile-input table: every command and every spec key has rows here.
//!
//! Each row runs the release binary in a fresh scratch directory (after
//! writing the row's set-up files into it) and checks:
//!
//! * the exit code (2 for bad input, 1 for a failure while running);
//! * stderr is exactly one line and contains the row's `needle`, which names
//!   the problem (the offending value, key or path);
//! * nothing panicked (no "panicked" in stderr, no exit 101 or signal);
//! * no file in the scratch directory was created, changed or removed
//!   (unless the row says `changes_allowed`);
//! * the run ended within [`TIME_LIMIT`] (refusing heavy work must be fast).
//!
//! Paths in the arguments: `{M}` is the shipped `analysis/meshes` directory,
//! `{A}` the shipped `analysis` directory; relative paths resolve inside the
//! scratch directory, which is the working directory of the run.
//!
//! Rows are grouped in sections by area; add rows to the section they belong
//! to (one section per area keeps parallel edits apart).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A run that takes longer than this fails the row: refusals must be quick.
const TIME_LIMIT: Duration = Duration::from_secs(20);

/// Where stdout goes.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Stdout {
    /// Captured (the normal case).
    Pipe,
    /// `/dev/full`: every write fails with ENOSPC.
    Full,
}

/// One row of the table.
struct Case {
    /// A short unique name, printed when the row fails.
    name: &'static str,
    /// Arguments after the binary name (with `{M}`, `{A}` substituted).
    args: &'static [&'static str],
    /// Files written into the scratch directory before the run: (relative path, contents).
    files: &'static [(&'static str, &'static str)],
    /// Expected exit code.
    code: i32,
    /// A substring the single stderr line must contain (case-sensitive).
    needle: &'static str,
    /// Where stdout goes.
    stdout: Stdout,
}

/// A row with the usual defaults: exit 2, no set-up files, stdout captured.
const fn bad(name: &'static str, args: &'static [&'static str], needle: &'static str) -> Case {
    Case {
        name,
        args,
        files: &[],
        code: 2,
        needle,
        stdout: Stdout::Pipe,
    }
}

/// A row with set-up files.
const fn bad_with(
    name: &'static str,
    args: &'static [&'static str],
    files: &'static [(&'static str, &'static str)],
    needle: &'static str,
) -> Case {
    Case {
        name,
        args,
        files,
        code: 2,
        needle,
        stdout: Stdout::Pipe,
    }
}

/// A row whose stdout is `/dev/full`: exit 1, a message naming the write error.
const fn full(name: &'static str, args: &'static [&'static str]) -> Case {
    Case {
        name,
        args,
        files: &[],
        code: 1,
        needle: "stdout",
        stdout: Stdout::Full,
    }
}

/// A valid one-shard sweep of the spec [`MERGE_SPEC`] (rows, and the summary
/// beside them), for merge rows whose refusal must come before a merge that
/// would otherwise succeed.
const MERGE_SPEC: &str = "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n";
/// The rows of [`MERGE_SPEC`]'s single shard.
const MERGE_A_CSV: &str = "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n";
/// The summary of [`MERGE_A_CSV`].
const MERGE_A_SUMMARY: &str = "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe5\",\"total_configurations\":8,\"shard\":{\"index\":0,\"count\":1},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}";
/// A summary of [`MERGE_SPEC`]'s shard 1/2 (the fingerprint of a shard CSV).
const MERGE_SHARD12_SUMMARY: &str = "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe5\",\"total_configurations\":8,\"shard\":{\"index\":1,\"count\":2},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}";
/// A summary of another spec (digest ...e6) for [`MERGE_SPEC`]'s rows.
const FOREIGN_SUMMARY: &str = "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe6\",\"total_configurations\":8,\"shard\":{\"index\":0,\"count\":1},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}";

/// A small verify spec (n = 3, class only, wide cells: a fraction of a second).
const VERIFY_SMALL: &str = "name = \"v\"\nscheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\nmin_width = 0.2\n";
/// A verify `cells.csv` (two coordinates' worth of an n = 3 box).
const VERIFY_CELLS: &str = "lo0,lo1,lo2,hi0,hi1,hi2,verdict,class\n0.1,0.1,0.1,0.5,0.5,0.9,complex_pair,certified\n0.5,0.1,0.1,0.9,0.5,0.9,real_distinct,certified\n0.1,0.5,0.1,0.9,0.9,0.9,undecided,undecided\n";

/// A CSV of `rows` scatter points (columns `a`, `b`), built once.
fn many_points(rows: usize) -> &'static str {
    let mut s = String::from("a,b\n");
    for i in 0..rows {
        s.push_str(&format!("{},{}\n", i % 1000, i / 1000));
    }
    Box::leak(s.into_boxed_str())
}

/// An open strip of two quads (8 lines: tag lines added after it are line 9 on).
macro_rules! sharp_strip {
    () => {
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n"
    };
}

fn cases() -> Vec<Case> {
    let mut v = Vec::new();

    // ===================================================================
    // SECTION knots-and-numerics: knot files, ratios, intervals, --exact,
    // overflow and underflow of derived quantities, verdicts.
    // ===================================================================
    v.extend([bad(
        "ratios-out-of-range",
        &["analyze", "--ratios", "0.5,1.5,0.5"],
        "1.5",
    )]);
    // A mesh interval refinement that cannot halve exactly
    // (5e-324 / 2 rounds to 0) names the edge instead of recursing in frexp.
    v.extend([
        bad(
            "subdivide-interval-not-halvable",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "--default-interval",
                "5e-324",
                "-o",
                "x.obj",
            ],
            "cannot be halved exactly",
        ),
        bad_with(
            "subdivide-knot-file-interval-not-halvable",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "--knots",
                "k.knots",
                "-o",
                "x.obj",
            ],
            &[("k.knots", "1 2 1.5e-323\n")],
            "d(0->1) (OBJ 1->2) = 1.5e-323",
        ),
        bad_with(
            "subdivide-knot-file-interval-below-f64",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "--knots",
                "k.knots",
                "-o",
                "x.obj",
            ],
            &[("k.knots", "1 2 1e-400\n")],
            "1->2 (OBJ indices) = 1e-400 is not representable in f64: it rounds to 0",
        ),
        bad_with(
            "subdivide-knot-file-interval-above-f64",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "--knots",
                "k.knots",
                "-o",
                "x.obj",
            ],
            &[("k.knots", "1 2 1e400\n")],
            "= 1e400 is not representable in f64: it rounds to inf",
        ),
    ]);
    // A ratio below the f64 range names the edge ratio.
    v.extend([bad(
        "analyze-knots-ratio-below-f64",
        &["analyze", "--knots", "1e300:1e300,1e300:1e-300,1e300:1e300"],
        "r_0 = 1e-300 / (1e300 + 1e-300) is not representable in f64",
    )]);
    // Values that do not fit in f64 are named as such on
    // the float path (not "got inf", "got 1.0", or silently 0).
    v.extend([
        bad(
            "analyze-knot-overflows-f64",
            &["analyze", "--knots", "1e400/3:1,1:1,1:1"],
            "knot interval p_0 = 1e400/3 is not representable in f64: it overflows",
        ),
        bad(
            "analyze-knot-underflows-f64",
            &["analyze", "--knots", "1:1,1:1e-400,1:1"],
            "knot interval q_1 = 1e-400 is not representable in f64: it rounds to 0",
        ),
        bad(
            "analyze-ratio-rounds-to-one",
            &["analyze", "--ratios", "0.9999999999999999999999,0.5,0.5"],
            "edge ratio r_0 = 0.9999999999999999999999 is not representable in f64: it rounds to 1",
        ),
        bad(
            "analyze-ratio-rounds-to-one-exact",
            &[
                "analyze",
                "--exact",
                "--ratios",
                "0.5,0.9999999999999999999999,0.5",
            ],
            "edge ratio r_1 = 0.9999999999999999999999 is not representable in f64",
        ),
        bad(
            "analyze-ratio-rounds-to-zero",
            &["analyze", "--ratios", "0.5,0.5,1e-400"],
            "edge ratio r_2 = 1e-400 is not representable in f64: it rounds to 0",
        ),
        bad(
            "analyze-c-rounds-to-zero",
            &[
                "analyze",
                "--scheme",
                "adjustable-cc",
                "--valence",
                "5",
                "--c",
                "1e-400",
            ],
            "--c = 1e-400 is not representable in f64: it rounds to 0",
        ),
        bad(
            "subdivide-c-rounds-to-zero",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "adjustable-cc",
                "--c",
                "1e-400",
                "-o",
                "x.obj",
            ],
            "--c = 1e-400 is not representable in f64: it rounds to 0",
        ),
        // --exact: the ratios are exact, but one below the f64 range is named
        bad(
            "analyze-exact-ratio-below-f64",
            &["analyze", "--exact", "--knots", "1e400/3:1,1:1,1:1"],
            "edge ratio r_0 = ~3.000000e-400 is not representable in f64: it rounds to 0",
        ),
    ]);
    // (end of section knots-and-numerics)
    //
    //
    //

    // ===================================================================
    // SECTION cli-io: report output directories, stdout write errors,
    // conflicting outputs, exit codes, messages.
    // ===================================================================
    v.extend([bad(
        "unknown-scheme",
        &["analyze", "--scheme", "bogus", "--valence", "4"],
        "bogus",
    )]);
    // A write error on stdout (/dev/full) is exit 1 with one line naming
    // stdout, never a panic.
    v.extend([
        full("full-analyze", &["analyze", "--uniform", "--valence", "3"]),
        full(
            "full-analyze-json",
            &["analyze", "--uniform", "--valence", "3", "--json"],
        ),
        full("full-matrix", &["matrix", "--uniform", "--valence", "3"]),
        full(
            "full-matrix-exact-csv",
            &[
                "matrix",
                "--uniform",
                "--valence",
                "4",
                "--exact",
                "--format",
                "csv",
            ],
        ),
        full(
            "full-cc-study-intervals",
            &["cc-study", "--n-min", "3", "--n-max", "3", "--samples", "2"],
        ),
        full(
            "full-cc-study-curves",
            &[
                "cc-study",
                "--n-min",
                "3",
                "--n-max",
                "3",
                "--samples",
                "2",
                "--curves",
            ],
        ),
        full(
            "full-ccss-bound",
            &["ccss-bound", "--valence", "3", "--levels", "1"],
        ),
        full(
            "full-ccss-bound-json",
            &["ccss-bound", "--valence", "3", "--levels", "1", "--json"],
        ),
        full("full-help", &["--help"]),
        full(
            "full-subdivide-stdout",
            &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "-o", "-"],
        ),
        // Stats to a full stdout with -o: exit 1 and no x.obj left behind
        // (outputs are staged and renamed only after stdout succeeded).
        full(
            "full-subdivide-stats-with-output-file",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "--stats",
                "-o",
                "x.obj",
            ],
        ),
        full(
            "full-subdivide-cc-stdout",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "catmull-clark",
                "-o",
                "-",
            ],
        ),
    ]);
    // Input errors are exit 2 everywhere.
    v.extend([
        bad(
            "exact-doo-sabin-irrational-valence",
            &[
                "analyze",
                "--exact",
                "--scheme",
                "doo-sabin",
                "--valence",
                "5",
            ],
            "valence = 5",
        ),
        bad(
            "exact-matrix-doo-sabin-irrational-valence",
            &[
                "matrix",
                "--exact",
                "--scheme",
                "doo-sabin",
                "--valence",
                "5",
            ],
            "valence = 5",
        ),
        bad(
            "exact-catmull-clark",
            &[
                "analyze",
                "--exact",
                "--scheme",
                "catmull-clark",
                "--valence",
                "5",
            ],
            "--exact is not available for --scheme catmull-clark",
        ),
        bad(
            "exact-loop",
            &["analyze", "--exact", "--scheme", "loop", "--valence", "5"],
            "--exact is not available for --scheme loop",
        ),
        bad(
            "loop-valence-2",
            &["analyze", "--scheme", "loop", "--valence", "2"],
            "valence must be at least 3",
        ),
        bad(
            "loop-with-c",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--c",
                "0.3",
            ],
            "c",
        ),
        bad(
            "loop-with-ratios",
            &["analyze", "--scheme", "loop", "--ratios", "0.3,0.5,0.5"],
            "takes no knot intervals",
        ),
        bad(
            "face-block-loop",
            &[
                "matrix",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--block",
                "face",
            ],
            "loop",
        ),
        bad(
            "loop-absurd-valence",
            &["analyze", "--scheme", "loop", "--valence", "100000"],
            "300001 x 300001",
        ),
        bad(
            "loop-of-quad-mesh",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "loop",
                "--levels",
                "1",
                "-o",
                "out.obj",
            ],
            "triangle",
        ),
        bad(
            "loop-with-knots-out",
            &[
                "subdivide",
                "{M}/icosahedron.obj",
                "--scheme",
                "loop",
                "--levels",
                "1",
                "--knots-out",
                "k.knots",
            ],
            "--knots/--knots-out: scheme loop takes no knot intervals",
        ),
        bad(
            "loop-with-stats",
            &[
                "subdivide",
                "{M}/icosahedron.obj",
                "--scheme",
                "loop",
                "--stats",
            ],
            "--stats: scheme loop has no per-level statistics",
        ),
        bad(
            "subdivide-catmull-clark-with-c",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "catmull-clark",
                "--c",
                "0.3",
                "-o",
                "out.obj",
            ],
            "--c: scheme catmull-clark takes no shape parameter c",
        ),
        bad(
            "subdivide-adjustable-cc-without-c",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "adjustable-cc",
                "-o",
                "out.obj",
            ],
            "--c: scheme adjustable-cc needs the shape parameter c",
        ),
        bad_with(
            "report-mesh-picture-loop-random-knots",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"mesh-picture\"\nmesh = \"icosahedron\"\nscheme = \"loop\"\nrandom_knots = 2.0\n",
            )],
            "figure[0].random_knots: scheme loop takes no knot intervals",
        ),
        bad(
            "face-block-catmull-clark",
            &[
                "matrix",
                "--scheme",
                "catmull-clark",
                "--valence",
                "5",
                "--block",
                "face",
            ],
            "catmull-clark",
        ),
        bad(
            "cc-limit-of-non-quad-mesh",
            &[
                "subdivide",
                "{M}/tetrahedron.obj",
                "--scheme",
                "catmull-clark",
                "--levels",
                "0",
                "--limit",
                "-o",
                "out.obj",
            ],
            "all-quad",
        ),
    ]);
    // Messages name the problem on one line; clap's errors too.
    v.extend([
        bad(
            "ccss-bound-epsilon-without-net",
            &["ccss-bound", "--valence", "5", "--epsilon", "0.01"],
            "--net",
        ),
        bad("no-command", &[], "no command given"),
        bad("unknown-flag", &["analyze", "--bogus-flag"], "--bogus-flag"),
        bad(
            "valence-not-a-number",
            &["analyze", "--uniform", "--valence", "three"],
            "three",
        ),
        bad(
            "unknown-command",
            &["analyse", "--uniform", "--valence", "3"],
            "analyse",
        ),
        bad_with(
            "sweep-count-not-an-integer",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 5.5\nseed = 1\n",
            )],
            "sampler.count: invalid type: floating point `5.5`, expected i64 (line 9)",
        ),
        bad_with(
            "sweep-sobol-dimension-beyond-the-joe-kuo-table",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"nurds\"\nvalences = [3, 600]\n[space]\nkind = \"corner-intervals\"\ninterval_range = [0.5, 2.0]\n[sampler]\nkind = \"sobol\"\ncount = 4\n",
            )],
            "sampler.kind: the Sobol sampler supports at most 1024 free coordinates (Joe-Kuo direction numbers shipped), valence 600 has 1200",
        ),
        bad_with(
            "sweep-sobol-scramble-not-a-bool",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"sobol\"\ncount = 4\nscramble = \"owen\"\n",
            )],
            "sampler.scramble",
        ),
        bad_with(
            "sweep-missing-sampler",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n",
            )],
            "sampler: missing [sampler] table",
        ),
        bad_with(
            "sweep-missing-key-in-table",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 5\n",
            )],
            "space.kind: missing (required key) (line 4)",
        ),
        bad_with(
            "report-spec-float-valence",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"nurds\", valence = 4.5 }]\n",
            )],
            "line 4, column 42: figure[0].configs[0].valence",
        ),
        bad_with(
            "report-spec-loop",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"spectrum\"\nconfigs = [{ scheme = \"loop\", ratios = [0.3, 0.5, 0.5] }]\n",
            )],
            "figure[0].configs[0].scheme: scheme loop takes no knot intervals",
        ),
        // sqrt3, butterfly and modified butterfly
        bad(
            "sqrt3-of-quad-mesh",
            &["subdivide", "{M}/cube.obj", "--scheme", "sqrt3", "--levels", "1", "-o", "out.obj"],
            "face 0 has 4 corners; sqrt3 refinement needs an all-triangle mesh",
        ),
        bad(
            "butterfly-of-quad-mesh",
            &["subdivide", "{M}/cube.obj", "--scheme", "butterfly", "-o", "out.obj"],
            "butterfly refinement needs an all-triangle mesh",
        ),
        bad(
            "modified-butterfly-of-open-mesh",
            &[
                "subdivide",
                "{M}/sharp/grid_quads_untagged.obj",
                "--scheme",
                "modified-butterfly",
                "-o",
                "out.obj",
            ],
            "boundary",
        ),
        bad(
            "butterfly-of-tagged-mesh",
            &["subdivide", "{M}/sharp/grid_tris.obj", "--scheme", "butterfly", "-o", "out.obj"],
            "tag line",
        ),
        bad(
            "sqrt3-with-tag-file",
            &[
                "subdivide",
                "{M}/icosahedron.obj",
                "--scheme",
                "sqrt3",
                "--tags",
                "t.tags",
                "-o",
                "out.obj",
            ],
            "--tags: scheme sqrt3 refines closed meshes without tags only",
        ),
        bad(
            "modified-butterfly-with-stats",
            &["subdivide", "{M}/icosahedron.obj", "--scheme", "modified-butterfly", "--stats"],
            "--stats: scheme modified-butterfly has no per-level statistics",
        ),
        bad(
            "sqrt3-with-knots-out",
            &["subdivide", "{M}/icosahedron.obj", "--scheme", "sqrt3", "--knots-out", "k.knots"],
            "scheme sqrt3 takes no knot intervals",
        ),
        bad(
            "sqrt3-levels-too-many",
            &["subdivide", "{M}/icosahedron.obj", "--scheme", "sqrt3", "--levels", "40", "-o", "out.obj"],
            "half-edges",
        ),
        bad(
            "butterfly-valence-2",
            &["analyze", "--scheme", "butterfly", "--valence", "2"],
            "valence must be at least 3",
        ),
        bad(
            "modified-butterfly-with-c",
            &["analyze", "--scheme", "modified-butterfly", "--valence", "5", "--c", "0.3"],
            "c",
        ),
        bad(
            "sqrt3-with-ratios",
            &["matrix", "--scheme", "sqrt3", "--ratios", "0.3,0.5,0.5"],
            "takes no knot intervals",
        ),
        bad(
            "butterfly-absurd-valence",
            &["analyze", "--scheme", "butterfly", "--valence", "100000"],
            "600001 x 600001",
        ),
        bad(
            "sqrt3-absurd-valence-matrix",
            &["matrix", "--scheme", "sqrt3", "--valence", "100000"],
            "300001 x 300001",
        ),
        bad(
            "face-block-butterfly",
            &["matrix", "--scheme", "butterfly", "--valence", "5", "--block", "face"],
            "butterfly",
        ),
        bad(
            "exact-sqrt3",
            &["analyze", "--exact", "--scheme", "sqrt3", "--valence", "6"],
            "--exact is not available for --scheme sqrt3",
        ),
        bad(
            "matrix-exact-modified-butterfly-irrational",
            &["matrix", "--exact", "--scheme", "modified-butterfly", "--valence", "5"],
            "modified butterfly weights are irrational for this valence",
        ),
        bad_with(
            "sweep-spec-sqrt3-knots",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"sqrt3\"\nvalences = [5]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n",
            )],
            "space.kind: scheme sqrt3 takes no knot intervals",
        ),
        bad_with(
            "sweep-spec-loop",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"loop\"\nvalences = [5]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n",
            )],
            "space.kind: scheme loop takes no knot intervals",
        ),
        bad_with(
            "report-spec-missing-kind",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nid = \"a\"\n")],
            "figure[0].kind: missing",
        ),
    ]);
    // `report --out`: never delete or rename a file the tool did not create.
    // Refusals come before any work and touch nothing.
    v.extend([
        bad_with(
            "report-out-foreign-nonempty-dir",
            &["report", "d/s.toml", "--out", "d"],
            &[
                ("d/keep.txt", "x\n"),
                (
                    "d/s.toml",
                    "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"cc-variant\", valence = 4 }]\n",
                ),
            ],
            "--out d is not empty",
        ),
        bad_with(
            "report-out-foreign-dir",
            &["report", "--out", "d"],
            &[("d/keep.txt", "x\n")],
            "holds no previous subdiv-lab report",
        ),
        bad_with(
            "report-out-is-a-file",
            &["report", "--out", "f"],
            &[("f", "user data\n")],
            "--out f exists and is not a directory",
        ),
        bad_with(
            "report-previous-report-new-output-over-a-user-file",
            &["report", "--out", "r"],
            &[
                (
                    "r/manifest.json",
                    "{\"tool\": \"subdiv-lab\", \"files\": [\"manifest.json\"]}",
                ),
                ("r/index.html", "<html>the user's page</html>\n"),
            ],
            "index.html",
        ),
        bad(
            "report-force-is-not-a-report-option",
            &["report", "--force"],
            "--force",
        ),
        bad_with(
            "report-out-foreign-manifest",
            &["report", "--out", "r"],
            &[("r/manifest.json", "{\"tool\": \"other\"}")],
            "holds no previous subdiv-lab report",
        ),
    ]);
    // Conflicting outputs are refused before anything is written.
    v.extend([
        bad(
            "subdivide-same-output-twice",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "-o",
                "x",
                "--knots-out",
                "x",
            ],
            "name the same file",
        ),
        bad_with(
            "subdivide-same-output-twice-spelled-differently",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "-o",
                "x",
                "--knots-out",
                "./sub/../x",
            ],
            &[("sub/keep.txt", "x\n")],
            "name the same file",
        ),
        bad_with(
            "subdivide-output-is-input",
            &["subdivide", "m.obj", "--scheme", "nurds", "-o", "./m.obj"],
            &[(
                "m.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
            )],
            "is also the input",
        ),
        bad_with(
            "subdivide-knots-out-is-knots-input",
            &[
                "subdivide",
                "{M}/tetrahedron.obj",
                "--scheme",
                "nurds",
                "--knots",
                "k.txt",
                "--knots-out",
                "k.txt",
            ],
            &[("k.txt", "1 2 1.5\n")],
            "is also --knots",
        ),
        bad_with(
            "subdivide-output-is-a-directory",
            &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "-o", "d"],
            &[("d/keep.txt", "x\n")],
            "is a directory",
        ),
        bad(
            "subdivide-output-dir-missing",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme",
                "nurds",
                "-o",
                "nodir/x.obj",
            ],
            "nodir",
        ),
    ]);
    // One rule for outputs: a failed run (stdout full) leaves no new output,
    // and an output directory is never replaced by a file.
    v.extend([
        Case {
            name: "verify-stdout-full-new-dir",
            args: &["verify", "v.toml", "--out", "o"],
            files: &[("v.toml", VERIFY_SMALL)],
            code: 1,
            needle: "stdout",
            stdout: Stdout::Full,
        },
        Case {
            name: "verify-stdout-full-previous-output",
            args: &["verify", "v.toml", "--out", "o"],
            files: &[
                ("v.toml", VERIFY_SMALL),
                (
                    "o/summary.json",
                    "{\"tool\": \"subdiv-lab\", \"command\": \"verify\"}\n",
                ),
                ("o/cells.csv", "old cells\n"),
            ],
            code: 1,
            needle: "stdout",
            stdout: Stdout::Full,
        },
        bad_with(
            "plot-out-is-a-directory",
            &["plot", "s.csv", "-o", "d.svg"],
            &[("s.csv", "a,b\n1,2\n3,4\n"), ("d.svg/keep.txt", "mine")],
            "-o d.svg is a directory",
        ),
        bad_with(
            "g2-cap-out-is-a-directory",
            &[
                "g2-cap",
                "--valence",
                "3",
                "--random-net",
                "1",
                "--c",
                "0.5",
                "-o",
                "d.obj",
            ],
            &[("d.obj/keep.txt", "mine")],
            "-o d.obj is a directory",
        ),
        bad_with(
            "merge-out-is-a-directory",
            &["merge", "--spec", "h.toml", "--out", "d", "a.csv"],
            &[
                ("h.toml", MERGE_SPEC),
                ("a.csv", MERGE_A_CSV),
                ("a.summary.json", MERGE_A_SUMMARY),
                ("d/keep.txt", "mine"),
            ],
            "--out d is a directory",
        ),
    ]);
    // (end of section cli-io)
    //
    //
    //

    // ===================================================================
    // SECTION bounded-work: estimates and refusals of heavy work, --threads.
    // ===================================================================
    v.extend([bad(
        "valence-zero",
        &["analyze", "--uniform", "--valence", "0"],
        "0",
    )]);
    // Sizes whose matrices do not fit in memory are refused from the
    // estimate, before any allocation (which would abort the process).
    v.extend([
        bad(
            "analyze-cc-valence-100000",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--valence",
                "100000",
            ],
            "valence 100000 needs ~",
        ),
        bad(
            "analyze-nurds-valence-100000",
            &["analyze", "--uniform", "--valence", "100000"],
            "400000 x 400000",
        ),
        bad(
            "analyze-doo-sabin-valence-100000",
            &["analyze", "--scheme", "doo-sabin", "--valence", "100000"],
            "valence 100000 needs ~",
        ),
        bad(
            "analyze-cc-variant-valence-100000",
            &["analyze", "--scheme", "cc-variant", "--valence", "100000"],
            "valence 100000 needs ~",
        ),
        bad(
            "analyze-adjustable-valence-100000",
            &[
                "analyze",
                "--scheme",
                "adjustable-cc",
                "--c",
                "0.3",
                "--valence",
                "100000",
            ],
            "200001 x 200001",
        ),
        bad(
            "analyze-structured-nurds-20000",
            &[
                "analyze",
                "--uniform",
                "--valence",
                "20000",
                "--path",
                "structured",
            ],
            "valence 20000 needs ~",
        ),
        bad(
            "analyze-structured-cc-20000",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--valence",
                "20000",
                "--path",
                "structured",
            ],
            "valence 20000 needs ~",
        ),
        bad(
            "analyze-charmap-unknown-method",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--charmap",
                "bogus",
            ],
            "bogus",
        ),
        bad(
            "analyze-charmap-generic-at-a-sector-vertex",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--charmap",
                "generic",
            ],
            "--charmap generic is not available with --vertex",
        ),
        bad(
            "analyze-charmap-generic-above-the-time-limit",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "300",
                "--charmap",
                "generic",
            ],
            "analyze --charmap generic: valence 300 takes ~",
        ),
        bad(
            "analyze-force-still-refuses-beyond-memory",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--valence",
                "100000",
                "--force",
            ],
            "refused even with --force",
        ),
        bad(
            "matrix-cc-valence-100000",
            &["matrix", "--scheme", "catmull-clark", "--valence", "100000"],
            "matrix: valence 100000 needs ~",
        ),
        bad(
            "matrix-nurds-valence-100000-csv",
            &[
                "matrix",
                "--uniform",
                "--valence",
                "100000",
                "--format",
                "csv",
            ],
            "matrix: valence 100000 needs ~",
        ),
        bad(
            "matrix-nurds-valence-2000",
            &[
                "matrix",
                "--uniform",
                "--valence",
                "2000",
                "--format",
                "csv",
            ],
            "use --force to run anyway",
        ),
        bad(
            "ccss-bound-valence-100000",
            &["ccss-bound", "--valence", "100000"],
            "ccss-bound: valence 100000 needs ~",
        ),
    ]);
    // Runs of minutes are refused with their estimate.
    v.extend([
        bad(
            "analyze-valence-1000-uniform",
            &["analyze", "--valence", "1000", "--uniform"],
            "analyze: valence 1000 takes ~",
        ),
        bad(
            "analyze-valence-1000-structured",
            &["analyze", "--valence", "1000", "--uniform", "--path", "structured"],
            "use --force to run anyway",
        ),
        bad(
            "analyze-exact-valence-300-structured",
            &[
                "analyze",
                "--valence",
                "300",
                "--uniform",
                "--path",
                "structured",
                "--exact",
            ],
            "analyze --exact: valence 300 takes ~",
        ),
        bad(
            "ccss-bound-valence-1000",
            &["ccss-bound", "--valence", "1000"],
            "use --force to run anyway",
        ),
        bad(
            "ccss-bound-table-to-1000",
            &["ccss-bound", "--table-to", "1000"],
            "--table-to 1000",
        ),
        bad(
            "cc-study-huge",
            &["cc-study", "--n-max", "256", "--samples", "100000", "--curves"],
            "cc-study: valences 3..256",
        ),
        bad(
            "subdivide-levels-beyond-memory",
            &["subdivide", "{M}/cube.obj", "--scheme", "catmull-clark", "--levels", "13", "-o", "x.obj"],
            "subdivide: --levels 13 needs ~",
        ),
        bad(
            "subdivide-levels-over-limit",
            &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "--levels", "11", "-o", "x.obj"],
            "subdivide: --levels 11 needs ~",
        ),
        bad(
            "subdivide-cc-levels-over-limit",
            &["subdivide", "{M}/cube.obj", "--scheme", "catmull-clark", "--levels", "11", "--timing"],
            "subdivide: --levels 11 needs ~",
        ),
        bad_with(
            "sweep-10-to-the-12",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"huge\"\nscheme = \"nurds\"\nvalences = [12]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 10\n",
            )],
            "1000000000000 configurations",
        ),
        bad(
            "sweep-threads-10000",
            &["sweep", "{A}/sweep-n3-slice.toml", "--threads", "10000"],
            "--threads must be between 1 and",
        ),
        bad(
            "sweep-threads-zero",
            &["sweep", "{A}/sweep-n3-slice.toml", "--threads", "0"],
            "got 0",
        ),
    ]);
    // cc-study: a bisection width below what f64 resolves in [0, 1] never
    // ended; it is refused (and every bisection is bounded by a step count).
    v.extend([
        bad(
            "cc-study-tol-below-f64",
            &["cc-study", "--n-min", "5", "--n-max", "5", "--tol", "1e-21"],
            "--tol: invalid parameter tol = 1e-21",
        ),
        bad(
            "cc-study-tol-zero",
            &["cc-study", "--n-min", "5", "--n-max", "5", "--tol", "0"],
            "tol = 0.0",
        ),
        bad(
            "cc-study-tol-one",
            &["cc-study", "--n-min", "5", "--n-max", "5", "--tol", "1"],
            "tol = 1.0",
        ),
        bad(
            "cc-study-samples-zero",
            &["cc-study", "--samples", "0"],
            "--samples must be in 1..=100000, got 0",
        ),
        bad(
            "cc-study-n-max-above-range",
            &["cc-study", "--n-max", "257"],
            "--n-max <= 256, got 3..257",
        ),
    ]);
    // (end of section bounded-work)
    //
    //
    //

    // ===================================================================
    // SECTION sweep-resume-merge: sweep specs, resume, merge, shards.
    // ===================================================================
    v.extend([bad_with(
        "sweep-spec-not-toml",
        &["sweep", "s.toml", "--out", "o.csv"],
        &[("s.toml", "this is = = not toml\n")],
        "s.toml",
    )]);
    // `--format`: the value named, Parquet only to a file, and a resumed
    // Parquet file that is not one (or torn without its journal) refused.
    v.extend([
        Case {
            name: "sweep-format-unknown",
            args: &["sweep", "h.toml", "--out", "o.csv", "--format", "xml"],
            files: &[("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n")],
            code: 2,
            needle: "xml",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-format-parquet-stdout",
            args: &["sweep", "h.toml", "--format", "parquet"],
            files: &[("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n")],
            code: 2,
            needle: "--format parquet needs --out",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-format-parquet-resume-csv",
            args: &["sweep", "h.toml", "--out", "o.dat", "--resume", "--format", "parquet"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.dat", "id,valence\n"),
            ],
            code: 2,
            needle: "o.dat exists and is not a dataset directory",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-format-parquet-resume-torn-part",
            args: &["sweep", "h.toml", "--out", "o.parquet", "--resume", "--format", "parquet"],
            files: &[("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"), ("o.parquet/part-000000.parquet", "PAR1 torn row group")],
            code: 2,
            needle: "o.parquet/part-000000.parquet: line 1: read failed: not a Parquet file, or torn",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-parquet-old-single-file-with-journal",
            args: &["sweep", "h.toml", "--out", "o.parquet", "--resume", "--format", "parquet"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.parquet", "PAR1 torn row group"),
                (".o.parquet.commit", "subdiv-lab parquet commit v1\n4\n0000000000000000 3\nxyz"),
            ],
            code: 2,
            needle: "o.parquet: written by an older subdiv-lab (a single Parquet file with a commit journal",
            stdout: Stdout::Pipe,
        },
    ]);

    // Resume and merge trust nothing: every row verified, files tied to their
    // spec and shard by the summary beside them (the set-up files are left as they were).
    v.extend([
        Case {
            name: "sweep-resume-edited-class",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,0.123456789,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("o.summary.json", MERGE_A_SUMMARY),
            ],
            code: 2,
            needle: "class = \"0.123456789\"",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-edited-lambda",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.46,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("o.summary.json", MERGE_A_SUMMARY),
            ],
            code: 2,
            needle: "lambda1_re is \"0.46\" in the file",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-shard-count-mismatch",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume", "--shard", "1/4"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n"),
                ("o.summary.json", MERGE_SHARD12_SUMMARY),
            ],
            code: 2,
            needle: "the shard count must be the same",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-foreign-spec",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("o.summary.json", FOREIGN_SUMMARY),
            ],
            code: 2,
            needle: "written by another spec",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-no-summary",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
            ],
            code: 2,
            needle: "its summary o.summary.json is missing or not a sweep summary",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-old-format",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            files: &[
                ("h.toml", MERGE_SPEC),
                ("o.csv", "# subdiv-lab sweep: digest 0d1298a9b5daefe5, shard 0/1, 8 configurations, spec \"h\"\nid,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n"),
                ("o.summary.json", MERGE_A_SUMMARY),
            ],
            code: 2,
            needle: "o.csv: line 1: written by an older subdiv-lab",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "sweep-resume-limit-too-small",
            args: &["sweep", "h.toml", "--out", "o.csv", "--resume", "--limit", "7"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("o.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("o.summary.json", MERGE_A_SUMMARY),
            ],
            code: 2,
            needle: "more rows than this run expects (7)",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "merge-bogus-class",
            args: &["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("a.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,bogus,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("a.summary.json", "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe5\",\"total_configurations\":8,\"shard\":{\"index\":0,\"count\":1},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}"),
            ],
            code: 2,
            needle: "class = \"bogus\"",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "merge-old-format-shard",
            args: &["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("a.csv", "# subdiv-lab sweep: digest 0d1298a9b5daefe5, shard 0/1, 8 configurations, spec \"h\"\nid,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("a.summary.json", "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe5\",\"total_configurations\":8,\"shard\":{\"index\":0,\"count\":1},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}"),
            ],
            code: 2,
            needle: "a.csv: line 1: written by an older subdiv-lab",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "merge-missing-summary",
            args: &["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("a.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
            ],
            code: 2,
            needle: "a.summary.json",
            stdout: Stdout::Pipe,
        },
        Case {
            name: "merge-summary-of-another-spec",
            args: &["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            files: &[
                ("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n"),
                ("a.csv", "id,valence,r0,r1,r2,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,ratio,rho,theta,contraction_rate,error\n0,3,0.2,0.2,0.2,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n1,3,0.2,0.2,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n2,3,0.2,0.8,0.2,real_distinct,0.44999999999999996,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666669,,,0.44999999999999996,\n3,3,0.2,0.8,0.8,real_distinct,0.45,0.0,0.29999999999999993,0.0,0.25,0.04999999999999993,0.6666666666666665,,,0.45,\n4,3,0.8,0.2,0.2,real_distinct,0.45,0.0,0.3,0.0,0.25,0.04999999999999999,0.6666666666666666,,,0.45,\n5,3,0.8,0.2,0.8,real_distinct,0.45,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.6666666666666667,,,0.45,\n6,3,0.8,0.8,0.2,real_distinct,0.4499999999999999,0.0,0.30000000000000004,0.0,0.25,0.050000000000000044,0.666666666666667,,,0.4499999999999999,\n7,3,0.8,0.8,0.8,complex_pair,0.375,0.12990381056766587,0.375,-0.12990381056766587,0.25,0.1468626966596886,,0.3968626966596886,0.33347317225183226,0.3968626966596886,\n"),
                ("a.summary.json", "{\"spec_name\":\"h\",\"spec_digest\":\"0d1298a9b5daefe6\",\"total_configurations\":8,\"shard\":{\"index\":0,\"count\":1},\"limit\":null,\"expected_rows\":8,\"rows\":8,\"complete\":true,\"errors\":0,\"classes\":{\"3\":{\"complex_pair\":2,\"real_distinct\":6}},\"columns\":[{\"name\":\"r0\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":4},{\"name\":\"r1\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":2},{\"name\":\"r2\",\"count\":8,\"non_finite\":0,\"min\":0.2,\"min_id\":0,\"max\":0.8,\"max_id\":1},{\"name\":\"lambda1_re\",\"count\":8,\"non_finite\":0,\"min\":0.375,\"min_id\":0,\"max\":0.45,\"max_id\":1},{\"name\":\"lambda1_im\",\"count\":8,\"non_finite\":0,\"min\":0.0,\"min_id\":1,\"max\":0.12990381056766587,\"max_id\":0},{\"name\":\"lambda2_re\",\"count\":8,\"non_finite\":0,\"min\":0.29999999999999993,\"min_id\":1,\"max\":0.375,\"max_id\":0},{\"name\":\"lambda2_im\",\"count\":8,\"non_finite\":0,\"min\":-0.12990381056766587,\"min_id\":0,\"max\":0.0,\"max_id\":1},{\"name\":\"abs_lambda3\",\"count\":8,\"non_finite\":0,\"min\":0.25,\"min_id\":0,\"max\":0.25,\"max_id\":0},{\"name\":\"gap\",\"count\":8,\"non_finite\":0,\"min\":0.04999999999999993,\"min_id\":1,\"max\":0.1468626966596886,\"max_id\":0},{\"name\":\"ratio\",\"count\":6,\"non_finite\":0,\"min\":0.6666666666666665,\"min_id\":1,\"max\":0.666666666666667,\"max_id\":6},{\"name\":\"rho\",\"count\":2,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.3968626966596886,\"max_id\":0},{\"name\":\"theta\",\"count\":2,\"non_finite\":0,\"min\":0.33347317225183226,\"min_id\":0,\"max\":0.33347317225183226,\"max_id\":0},{\"name\":\"contraction_rate\",\"count\":8,\"non_finite\":0,\"min\":0.3968626966596886,\"min_id\":0,\"max\":0.45,\"max_id\":1}],\"throughput\":{\"evaluated\":8,\"seconds\":0.000160557,\"configurations_per_second\":49826.54135291516,\"threads\":2}}"),
            ],
            code: 2,
            needle: "summary of another spec",
            stdout: Stdout::Pipe,
        },
    ]);
    // Sweep and merge never overwrite a file
    // they did not write (the summary beside --out, the spec, an input
    // shard's summary, an existing sweep --out), and a missing --out
    // directory is bad input (exit 2), not a failure while running.
    v.extend([
        bad_with(
            "sweep-exact-certificate-doo-sabin-irrational-valence",
            &["sweep", "d.toml", "--limit", "2"],
            &[("d.toml", "name = \"d\"\nscheme = \"doo-sabin\"\nvalences = [3, 5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\nexact_certificate = true\n")],
            "irrational at valence 5",
        ),
        bad_with(
            "sweep-summary-path-holds-a-user-file",
            &["sweep", "{A}/sweep-n3-grid.toml", "--out", "u.csv", "--limit", "3"],
            &[("u.summary.json", "mine")],
            "u.summary.json exists",
        ),
        bad_with(
            "sweep-summary-path-is-the-spec",
            &["sweep", "s.summary.json", "--out", "s.csv", "--limit", "3"],
            &[("s.summary.json", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n")],
            "is also the spec s.summary.json",
        ),
        bad(
            "sweep-out-directory-missing",
            &["sweep", "{A}/sweep-n3-grid.toml", "--out", "nodir/x.csv"],
            "directory nodir does not exist",
        ),
        bad_with(
            "sweep-out-is-a-directory",
            &["sweep", "{A}/sweep-n3-grid.toml", "--out", "d"],
            &[("d/keep.txt", "mine")],
            "--out d is a directory",
        ),
        bad_with(
            "merge-out-is-an-input-summary",
            &["merge", "--spec", "h.toml", "--out", "a.summary.json", "a.csv"],
            &[("h.toml", MERGE_SPEC), ("a.csv", MERGE_A_CSV), ("a.summary.json", MERGE_A_SUMMARY)],
            "--out a.summary.json is also the summary of an input",
        ),
        bad_with(
            "merge-summary-of-out-exists",
            &["merge", "--spec", "h.toml", "--out", "m.csv", "a.csv"],
            &[("h.toml", MERGE_SPEC), ("a.csv", MERGE_A_CSV), ("a.summary.json", MERGE_A_SUMMARY), ("m.summary.json", "mine")],
            "m.summary.json exists",
        ),
        bad_with(
            "merge-summary-of-out-is-the-spec",
            &["merge", "--spec", "h.summary.json", "--out", "h.csv", "a.csv"],
            &[("h.summary.json", MERGE_SPEC), ("a.csv", MERGE_A_CSV), ("a.summary.json", MERGE_A_SUMMARY)],
            "is also the spec h.summary.json",
        ),
        bad_with(
            "merge-missing-input-is-named",
            &["merge", "--spec", "h.toml", "--out", "m3.csv", "m.csv"],
            &[("h.toml", MERGE_SPEC)],
            "m.summary.json",
        ),
    ]);
    // Resumable outputs are continued only when they are the tool's (a file
    // of this tool is created whole with its header); the extension of
    // an output must match its format; reading a file is called reading.
    v.extend([
        bad_with(
            "sweep-resume-empty-parquet",
            &["sweep", "h.toml", "--out", "zero.parquet", "--resume"],
            &[("h.toml", MERGE_SPEC), ("zero.parquet", "")],
            "zero.parquet exists and is not a dataset directory",
        ),
        bad_with(
            "sweep-resume-empty-csv",
            &["sweep", "h.toml", "--out", "zero.csv", "--resume"],
            &[("h.toml", MERGE_SPEC), ("zero.csv", "")],
            "zero.csv exists but is empty: not a sweep file of this tool",
        ),
        bad_with(
            "sweep-resume-foreign-torn-first-line",
            &["sweep", "h.toml", "--out", "f.csv", "--resume"],
            &[("h.toml", MERGE_SPEC), ("f.csv", "my notes, no newline"), ("f.summary.json", MERGE_A_SUMMARY)],
            "f.csv: line 1: an incomplete first line that is not this spec's header",
        ),
        bad_with(
            "sweep-resume-summary-is-a-user-file",
            &["sweep", "h.toml", "--out", "o.csv", "--resume"],
            &[("h.toml", MERGE_SPEC), ("o.csv", MERGE_A_CSV), ("o.summary.json", "mine")],
            "o.summary.json exists and is not a sweep summary",
        ),
        bad_with(
            "sweep-format-parquet-out-csv",
            &["sweep", "h.toml", "--format", "parquet", "--out", "x.csv"],
            &[("h.toml", MERGE_SPEC)],
            "--format parquet but --out x.csv names a CSV file",
        ),
        bad_with(
            "sweep-format-csv-out-parquet",
            &["sweep", "h.toml", "--format", "csv", "--out", "x.parquet"],
            &[("h.toml", MERGE_SPEC)],
            "--format csv but --out x.parquet names a Parquet file",
        ),
        bad_with(
            "merge-parquet-shards-out-csv",
            &["merge", "--spec", "h.toml", "--out", "m.csv", "a.parquet"],
            &[("h.toml", MERGE_SPEC), ("a.parquet/part-000000.parquet", "PAR1 a shard"), ("a.summary.json", MERGE_A_SUMMARY)],
            "the shards are Parquet files but --out m.csv names a CSV file",
        ),
        bad_with(
            "merge-csv-shards-out-parquet",
            &["merge", "--spec", "h.toml", "--out", "m.parquet", "a.csv"],
            &[("h.toml", MERGE_SPEC), ("a.csv", MERGE_A_CSV), ("a.summary.json", MERGE_A_SUMMARY)],
            "the shards are CSV files but --out m.parquet names a Parquet file",
        ),
        bad_with(
            "merge-torn-parquet-shard",
            &["merge", "--spec", "h.toml", "--out", "m.parquet", "a.parquet"],
            &[("h.toml", MERGE_SPEC), ("a.parquet/part-000000.parquet", "PAR1 torn row group"), ("a.summary.json", MERGE_A_SUMMARY)],
            "a.parquet/part-000000.parquet: line 1: read failed: not a Parquet file, or torn",
        ),
        bad_with(
            "merge-single-parquet-file",
            &["merge", "--spec", "h.toml", "--out", "m.parquet", "a.parquet"],
            &[("h.toml", MERGE_SPEC), ("a.parquet", "PAR1 a file"), ("a.summary.json", MERGE_A_SUMMARY)],
            "a.parquet: a single Parquet file: merge takes the dataset directories",
        ),
        bad_with(
            "merge-dataset-without-parts",
            &["merge", "--spec", "h.toml", "--out", "m.parquet", "a.parquet"],
            &[("h.toml", MERGE_SPEC), ("a.parquet/notes.txt", "mine")],
            "a.parquet: no part files (part-*.parquet): not a sweep dataset",
        ),
        bad_with(
            "sweep-resume-parquet-part-missing",
            &["sweep", "h.toml", "--out", "o.parquet", "--resume"],
            &[("h.toml", MERGE_SPEC), ("o.parquet/part-000001.parquet", "PAR1 x")],
            "o.parquet: part-000000.parquet is missing but o.parquet/part-000001.parquet exists",
        ),
        bad_with(
            "sweep-resume-old-single-parquet-file",
            &["sweep", "h.toml", "--out", "o.parquet", "--resume"],
            &[("h.toml", MERGE_SPEC), ("o.parquet", "PAR1 torn row group")],
            "o.parquet: written by an older subdiv-lab",
        ),
        bad_with(
            "sweep-ratio-range-huge-bound",
            &["sweep", "h.toml", "--out", "o.csv"],
            &[("h.toml", "name = \"h\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [-1e300, 0.5]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n")],
            "bound -1e300 is outside the open interval (0, 1)",
        ),
    ]);
    // (end of section sweep-resume-merge)
    //
    //
    //

    // ===================================================================
    // SECTION figures: `plot` (sweep CSV -> figure), `report --formats`,
    // the keys of the report figure kind `sweep`.
    // ===================================================================
    v.extend([
        bad_with(
            "plot-missing-column",
            &["plot", "s.csv", "-o", "f.svg", "--x", "nope"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "no column \"nope\"",
        ),
        bad_with(
            "plot-non-numeric-axis",
            &["plot", "s.csv", "-o", "f.svg", "--kind", "scatter", "--x", "r0", "--y", "class"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "column \"class\" is not numeric",
        ),
        bad_with(
            "plot-non-numeric-histogram",
            &["plot", "s.csv", "-o", "f.png", "--kind", "histogram", "--x", "class"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "column \"class\" is not numeric",
        ),
        bad_with(
            "plot-missing-color-column",
            &["plot", "s.csv", "-o", "f.svg", "--color", "colour"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "no column \"colour\"",
        ),
        // Values near the f64 limit: the axis range would overflow and the
        // tick search loop for ever, so they are refused naming the column.
        bad_with(
            "plot-x-beyond-plot-range",
            &["plot", "h.csv", "-o", "f.svg", "--kind", "histogram", "--x", "a"],
            &[("h.csv", "a,b\n1e308,2\n-1e308,4\n")],
            "column \"a\" has the value 1e308, beyond",
        ),
        bad_with(
            "plot-y-beyond-plot-range",
            &["plot", "h.csv", "-o", "f.svg", "--kind", "scatter", "--x", "b", "--y", "a"],
            &[("h.csv", "a,b\n1e308,2\n-1e308,4\n")],
            "column \"a\" has the value 1e308, beyond",
        ),
        bad_with(
            "plot-color-beyond-plot-range",
            &["plot", "h.csv", "-o", "f.svg", "--kind", "scatter", "--x", "b", "--y", "b", "--color", "a"],
            &[("h.csv", "a,b\n1.5e308,2\n-1e308,4\n2.5,3\n")],
            "column \"a\" has the value 1.5e308, beyond",
        ),
        bad_with(
            "plot-empty-file",
            &["plot", "e.csv", "-o", "f.svg"],
            &[("e.csv", "")],
            "e.csv: the file is empty",
        ),
        bad_with(
            "plot-comment-only-file",
            &["plot", "e.csv", "-o", "f.svg"],
            &[("e.csv", "# subdiv-lab sweep: nothing\n")],
            "the file is empty",
        ),
        bad_with(
            "plot-header-only",
            &["plot", "h.csv", "-o", "f.svg"],
            &[("h.csv", "id,valence,class\n")],
            "no data rows",
        ),
        bad_with(
            "plot-ragged-row",
            &["plot", "r.csv", "-o", "f.svg"],
            &[("r.csv", "valence,class\n3,standard\n4\n")],
            "line 3",
        ),
        bad_with(
            "plot-no-numeric-column",
            &["plot", "t.csv", "-o", "f.svg"],
            &[("t.csv", "name\nx\ny\n")],
            "no numeric column",
        ),
        bad_with(
            "plot-unknown-kind",
            &["plot", "s.csv", "-o", "f.svg", "--kind", "pie"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "\"pie\"",
        ),
        bad_with(
            "plot-bad-output-extension",
            &["plot", "s.csv", "-o", "f.pdf"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "f.pdf",
        ),
        bad_with(
            "plot-output-directory-missing",
            &["plot", "s.csv", "-o", "nodir/f.svg"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "nodir",
        ),
        bad_with(
            "plot-output-is-the-input",
            &["plot", "s.svg", "-o", "s.svg"],
            &[("s.svg", "valence,class\n3,standard\n")],
            "s.svg",
        ),
        bad_with(
            "plot-width-too-small",
            &["plot", "s.csv", "-o", "f.svg", "--width", "10"],
            &[("s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "--width",
        ),
        bad_with(
            "plot-parquet-truncated",
            &["plot", "s.parquet", "-o", "f.svg"],
            &[("s.parquet", "PAR1")],
            "s.parquet: not a Parquet file, or torn",
        ),
        bad_with(
            "plot-parquet-cut-before-footer",
            &["plot", "s.parquet", "-o", "f.svg"],
            &[("s.parquet", "PAR1\u{15}\u{4}\u{15}\u{80}\u{2}\u{15}\u{80}\u{2}L\u{15}")],
            "s.parquet: not a Parquet file, or torn",
        ),
        bad_with(
            "plot-parquet-damaged-footer",
            &["plot", "s.parquet", "-o", "f.svg"],
            &[("s.parquet", "PAR1 some bytes, not a footer \u{8}\u{0}\u{0}\u{0}PAR1")],
            "s.parquet: parquet:",
        ),
        bad_with(
            "plot-parquet-not-parquet",
            &["plot", "s.parquet", "-o", "f.svg"],
            &[("s.parquet", "id,valence\n0,3\n")],
            "s.parquet: not a Parquet file",
        ),
        bad_with(
            "report-sweep-missing-file",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"nope.csv\"\n")],
            "nope.csv",
        ),
        bad_with(
            "report-sweep-missing-column",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\nx = \"nope\"\n"), ("d/s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "no column \"nope\"",
        ),
        bad_with(
            "report-sweep-non-numeric-axis",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\nplot = \"scatter\"\nx = \"r0\"\ny = \"class\"\n"), ("d/s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "column \"class\" is not numeric",
        ),
        bad_with(
            "report-sweep-empty-csv",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\n"), ("d/s.csv", "")],
            "the file is empty",
        ),
        bad_with(
            "report-sweep-unknown-plot",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\nplot = \"pie\"\n"), ("d/s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "unknown plot \"pie\"",
        ),
        bad_with(
            "report-sweep-parquet-truncated",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.parquet\"\n"), ("d/s.parquet", "PAR1")],
            "not a Parquet file, or torn",
        ),
        bad_with(
            "report-sweep-empty-path",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"\"\n")],
            "path is empty",
        ),
        bad_with(
            "report-sweep-missing-path",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\n")],
            "figure[0].path",
        ),
        bad_with(
            "report-sweep-unknown-key",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\ncolour = \"class\"\n"), ("d/s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "colour",
        ),
        bad_with(
            "report-sweep-x-not-a-string",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"h\"\n[[figure]]\nkind = \"sweep\"\npath = \"s.csv\"\nx = 3\n"), ("d/s.csv", "# subdiv-lab sweep: test\nid,valence,r0,r1,class,contraction_rate\n0,3,0.2,0.2,complex_pair,0.4\n1,4,0.2,0.8,real_distinct,0.45\n2,3,0.8,0.2,real_distinct,0.45\n")],
            "figure[0].x",
        ),
        bad("plot-missing-input", &["plot", "none.csv", "-o", "f.svg"], "none.csv"),
        bad("report-formats-unknown", &["report", "--formats", "svg,pdf", "--out", "r"], "svg,pdf"),
        bad("report-formats-empty", &["report", "--formats", "", "--out", "r"], "formats"),
    ]);
    // plot: an SVG of more points than MAX_SVG_ITEMS is refused (a PNG is
    // not); verify's cells are drawn over two distinct coordinates.
    v.extend([
        bad_with(
            "plot-svg-too-many-points",
            &[
                "plot", "p.csv", "-o", "f.svg", "--kind", "scatter", "--x", "a", "--y", "b",
            ],
            Box::leak(Box::new([("p.csv", many_points(100_001))])),
            "draws 100001 points or cells, an SVG of ~8.0 MB (limit 100000); write a PNG",
        ),
        bad_with(
            "plot-cells-same-axis-twice",
            &["plot", "cells.csv", "-o", "f.svg", "--x", "r1", "--y", "r1"],
            &[("cells.csv", VERIFY_CELLS)],
            "--x and --y both name the coordinate r1",
        ),
        bad_with(
            "plot-cells-unknown-colour",
            &["plot", "cells.csv", "-o", "f.svg", "--color", "charmap"],
            &[("cells.csv", VERIFY_CELLS)],
            "no column \"charmap\"",
        ),
    ]);
    // (end of section figures)

    // ===================================================================
    // SECTION mesh: subdivide, OBJ input, knot files.
    // ===================================================================
    v.extend([bad_with(
        "mesh-empty-obj",
        &["subdivide", "e.obj", "--scheme", "nurds", "-o", "x.obj"],
        &[("e.obj", "")],
        "e.obj",
    )]);
    // (end of section mesh)

    // ===================================================================
    // SECTION verify: verify specs (every key), --out, --threads, --max-cells.
    // ===================================================================
    v.extend([
        bad_with(
            "verify-missing-spec",
            &["verify", "nope.toml", "--out", "o"],
            &[],
            "nope.toml",
        ),
        bad_with(
            "verify-not-toml",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = ")],
            "v.toml",
        ),
        bad_with(
            "verify-unknown-key",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\nbogus = 1\n")],
            "bogus",
        ),
        bad_with(
            "verify-missing-properties",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\n")],
            "properties",
        ),
        bad_with(
            "verify-unknown-scheme",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"butterfly\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "butterfly",
        ),
        bad_with(
            "verify-valence-2",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 2\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "valence",
        ),
        bad_with(
            "verify-valence-huge",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 100000\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "valence",
        ),
        bad_with(
            "verify-box-count",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "box",
        ),
        bad_with(
            "verify-box-ratio-1",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 1.0], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "box[1]",
        ),
        bad_with(
            "verify-box-reversed",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.9, 0.1]]\nproperties = [\"class\"]\n")],
            "box[2]",
        ),
        bad_with(
            "verify-box-nan",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, nan], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "box[0]",
        ),
        bad_with(
            "verify-box-three-numbers",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.5, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "box[0]",
        ),
        bad_with(
            "verify-box-missing",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\n")],
            "box",
        ),
        bad_with(
            "verify-c-range-for-nurds",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nc_range = [0.1, 0.5]\nproperties = [\"class\"]\n")],
            "c_range",
        ),
        bad_with(
            "verify-box-for-cc",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nbox = [[0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "box",
        ),
        bad_with(
            "verify-c-range-outside",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nc_range = [0.1, 1.5]\nproperties = [\"class\"]\n")],
            "c_range",
        ),
        bad_with(
            "verify-c-range-missing",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nproperties = [\"class\"]\n")],
            "c_range",
        ),
        bad_with(
            "verify-theorem1-for-cc",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nc_range = [0.1, 0.5]\nproperties = [\"theorem1\"]\n")],
            "properties[0]",
        ),
        bad_with(
            "verify-g1-for-cc",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nc_range = [0.1, 0.5]\nproperties = [\"g1\"]\n")],
            "g1",
        ),
        bad_with(
            "verify-g1-twice",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"g1\", \"g1\"]\n")],
            "properties[1]",
        ),
        bad_with(
            "verify-g1-misspelt",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"G1\"]\n")],
            "properties[0]",
        ),
        bad_with(
            "verify-unknown-property",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\", \"smooth\"]\n")],
            "properties[1]",
        ),
        bad_with(
            "verify-property-twice",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\", \"class\"]\n")],
            "properties[1]",
        ),
        bad_with(
            "verify-properties-empty",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = []\n")],
            "properties",
        ),
        bad_with(
            "verify-min-width-zero",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\nmin_width = 0.0\n")],
            "min_width",
        ),
        bad_with(
            "verify-min-width-string",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\nmin_width = \"small\"\n")],
            "min_width",
        ),
        bad_with(
            "verify-time-budget-negative",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\ntime_budget = -1.0\n")],
            "time_budget",
        ),
        bad_with(
            "verify-symmetry-unknown",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.25, 0.75], [0.25, 0.75], [0.25, 0.75]]\nproperties = [\"g1\"]\nsymmetry = \"mirror\"\n")],
            "symmetry",
        ),
        bad_with(
            "verify-symmetry-unequal-sides",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.25, 0.75], [0.25, 0.75], [0.2, 0.75]]\nproperties = [\"g1\"]\nsymmetry = \"rotations\"\n")],
            "equal sides",
        ),
        bad_with(
            "verify-symmetry-dihedral-not-exact",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.05, 0.95], [0.05, 0.95], [0.05, 0.95]]\nproperties = [\"g1\"]\nsymmetry = \"dihedral\"\n")],
            "lo + hi = 1 exactly",
        ),
        bad_with(
            "verify-symmetry-corner-box",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\np_box = [[1, 2], [1, 2], [1, 2]]\nq_box = [[1, 2], [1, 2], [1, 2]]\nproperties = [\"g1\"]\nsymmetry = \"rotations\"\n")],
            "corner-interval",
        ),
        bad_with(
            "verify-symmetry-c-interval",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 3\nc_range = [0.1, 0.9]\nproperties = [\"charmap\"]\nsymmetry = \"dihedral\"\n")],
            "c interval",
        ),
        bad_with(
            "verify-threads-zero",
            &["verify", "v.toml", "--out", "o", "--threads", "0"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "--threads",
        ),
        bad_with(
            "verify-max-cells-zero",
            &["verify", "v.toml", "--out", "o", "--max-cells", "0"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "--max-cells",
        ),
        bad_with(
            "verify-max-cells-huge",
            &["verify", "v.toml", "--out", "o", "--max-cells", "100000000000"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "--force",
        ),
        bad_with(
            // the charmap property's own cost estimate (budget::verify_charmap):
            // the same spec without charmap is within the limits
            "verify-charmap-over-budget",
            &["verify", "v.toml", "--out", "o", "--threads", "1"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 5\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\", \"charmap\"]\n")],
            "--force",
        ),
        bad_with(
            // g1 has the charmap property's cost estimate
            "verify-g1-over-budget",
            &["verify", "v.toml", "--out", "o", "--threads", "1"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 5\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"g1\"]\n")],
            "--force",
        ),
        bad_with(
            "verify-out-is-file",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n"), ("o", "x")],
            "not a directory",
        ),
        bad_with(
            "verify-out-foreign-dir",
            &["verify", "v.toml", "--out", "d"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n"), ("d/keep.txt", "x")],
            "not empty",
        ),
        bad_with(
            "verify-out-parent-missing",
            &["verify", "v.toml", "--out", "no/such/o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "does not exist",
        ),
        bad_with(
            "verify-missing-out",
            &["verify", "v.toml"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\n")],
            "--out",
        ),
        bad_with(
            "report-certified-map-no-slices",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = []\n",
            )],
            "figure[0].slices: give 1 to 3 values of r_2",
        ),
        bad_with(
            "report-certified-map-slice-outside",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5, 1.0]\n",
            )],
            "figure[0].slices[1]: edge ratio r_2 must lie strictly between 0 and 1",
        ),
        bad_with(
            "report-certified-map-too-many-slices",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.2, 0.4, 0.6, 0.8]\n",
            )],
            "give 1 to 3 values of r_2, got 4",
        ),
        bad_with(
            "report-certified-map-range-reversed",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\nrange = [0.9, 0.1]\n",
            )],
            "figure[0].range: range must satisfy 0 < lo < hi < 1",
        ),
        bad_with(
            "report-certified-map-min-width-tiny",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\nmin_width = 1e-9\n",
            )],
            "figure[0].min_width: min_width must lie in",
        ),
        bad_with(
            "report-certified-map-grid-huge",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\ngrid = 100000\n",
            )],
            "figure[0].grid: grid must be between 4 and 200",
        ),
        bad_with(
            "report-certified-map-unknown-key",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\nbogus = 1\n",
            )],
            "bogus",
        ),
        bad_with(
            "report-certified-map-unknown-property",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\nproperty = \"charmap\"\n",
            )],
            "figure[0].property: property must be \"class\" or \"g1\", got \"charmap\"",
        ),
        bad_with(
            "report-certified-map-property-not-a-string",
            &["report", "s.toml", "--out", "r"],
            &[(
                "s.toml",
                "name = \"t\"\n[[figure]]\nkind = \"certified-map\"\nslices = [0.5]\nproperty = 1\n",
            )],
            "property",
        ),
        bad_with(
            "verify-p-box-without-q-box",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "q_box: missing",
        ),
        bad_with(
            "verify-q-box-without-p-box",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\nq_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "p_box: missing",
        ),
        bad_with(
            "verify-box-and-p-box",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\np_box = [[1, 2], [1, 2], [1, 2]]\nq_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "not both",
        ),
        bad_with(
            "verify-p-box-count",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2]]\nq_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "p_box must have one [lo, hi] per corner",
        ),
        bad_with(
            "verify-q-box-zero",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2], [1, 2]]\nq_box = [[1, 2], [0, 2], [1, 2]]\n")],
            "q_box[1]: knot intervals must be positive",
        ),
        bad_with(
            "verify-p-box-reversed",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2], [3, 2]]\nq_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "p_box[2]: lower bound 3 must be below",
        ),
        bad_with(
            "verify-p-box-nan",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, nan], [1, 2]]\nq_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "p_box[1]: knot intervals must be positive and finite",
        ),
        bad_with(
            "verify-q-box-three-numbers",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2], [1, 2]]\nq_box = [[1, 2, 3], [1, 2], [1, 2]]\n")],
            "q_box[0] must be [lower, upper]",
        ),
        bad_with(
            "verify-corner-ratio-rounds-to-one",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nproperties = [\"class\"]\np_box = [[1e-300, 2e-300], [1, 2], [1, 2]]\nq_box = [[1, 2], [1e300, 1.1e300], [1, 2]]\n")],
            "must lie strictly inside (0, 1)",
        ),
        bad_with(
            "verify-p-box-for-cc",
            &["verify", "v.toml", "--out", "o"],
            &[("v.toml", "scheme = \"adjustable-cc\"\nvalence = 5\nc_range = [0.1, 0.9]\nproperties = [\"class\"]\np_box = [[1, 2], [1, 2], [1, 2]]\n")],
            "p_box is for scheme",
        ),
    ]);
    v.extend([bad_with(
        "verify-min-width-tiny",
        &["verify", "v.toml", "--out", "o"],
        &[("v.toml", "scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"class\"]\nmin_width = 1e-300\n")],
        "at least 2^-40 (9.094947017729282e-13), got 1e-300 (line 5)",
    )]);
    // (end of section verify)

    // ===================================================================
    // SECTION g2-cap: the G2 cap command.
    // ===================================================================
    const RING5: &str = "v 0.0000 0.0000 0.0000\nv 1.0000 0.0000 0.1000\nv 2.0000 0.0000 0.4000\nv 0.3090 0.9511 -0.0809\nv 0.6180 1.9021 -0.3236\nv -0.8090 0.5878 0.0309\nv -1.6180 1.1756 0.1236\nv -0.8090 -0.5878 0.0309\nv -1.6180 -1.1756 0.1236\nv 0.3090 -0.9511 -0.0809\nv 0.6180 -1.9021 -0.3236\nv 1.3090 0.9511 0.0809\nv 1.6180 1.9021 -0.1000\nv 2.3090 0.9511 0.4427\nv 2.6180 1.9021 0.3236\nv -0.5000 1.5388 -0.2118\nv -1.3090 2.1266 -0.2809\nv -0.1910 2.4899 -0.6163\nv -1.0000 3.0777 -0.8472\nv -1.6180 0.0000 0.2618\nv -2.4271 -0.5878 0.5545\nv -2.4271 0.5878 0.5545\nv -3.2361 0.0000 1.0472\nv -0.5000 -1.5388 -0.2118\nv -0.1910 -2.4899 -0.6163\nv -1.3090 -2.1266 -0.2809\nv -1.0000 -3.0777 -0.8472\nv 1.3090 -0.9511 0.0809\nv 2.3090 -0.9511 0.4427\nv 1.6180 -1.9021 -0.1000\nv 2.6180 -1.9021 0.3236\nf 1 2 12 4\nf 2 3 14 12\nf 4 12 13 5\nf 12 14 15 13\nf 1 4 16 6\nf 4 5 18 16\nf 6 16 17 7\nf 16 18 19 17\nf 1 6 20 8\nf 6 7 22 20\nf 8 20 21 9\nf 20 22 23 21\nf 1 8 24 10\nf 8 9 26 24\nf 10 24 25 11\nf 24 26 27 25\nf 1 10 28 2\nf 10 11 30 28\nf 2 28 29 3\nf 28 30 31 29\n";
    const TRI5: &str = "v 0.0000 0.0000 0.0000\nv 1.0000 0.0000 0.1000\nv 2.0000 0.0000 0.4000\nv 0.3090 0.9511 -0.0809\nv 0.6180 1.9021 -0.3236\nv -0.8090 0.5878 0.0309\nv -1.6180 1.1756 0.1236\nv -0.8090 -0.5878 0.0309\nv -1.6180 -1.1756 0.1236\nv 0.3090 -0.9511 -0.0809\nv 0.6180 -1.9021 -0.3236\nv 1.3090 0.9511 0.0809\nv 1.6180 1.9021 -0.1000\nv 2.3090 0.9511 0.4427\nv 2.6180 1.9021 0.3236\nv -0.5000 1.5388 -0.2118\nv -1.3090 2.1266 -0.2809\nv -0.1910 2.4899 -0.6163\nv -1.0000 3.0777 -0.8472\nv -1.6180 0.0000 0.2618\nv -2.4271 -0.5878 0.5545\nv -2.4271 0.5878 0.5545\nv -3.2361 0.0000 1.0472\nv -0.5000 -1.5388 -0.2118\nv -0.1910 -2.4899 -0.6163\nv -1.3090 -2.1266 -0.2809\nv -1.0000 -3.0777 -0.8472\nv 1.3090 -0.9511 0.0809\nv 2.3090 -0.9511 0.4427\nv 1.6180 -1.9021 -0.1000\nv 2.6180 -1.9021 0.3236\nf 1 2 12\nf 2 3 14 12\nf 4 12 13 5\nf 12 14 15 13\nf 1 4 16 6\nf 4 5 18 16\nf 6 16 17 7\nf 16 18 19 17\nf 1 6 20 8\nf 6 7 22 20\nf 8 20 21 9\nf 20 22 23 21\nf 1 8 24 10\nf 8 9 26 24\nf 10 24 25 11\nf 24 26 27 25\nf 1 10 28 2\nf 10 11 30 28\nf 2 28 29 3\nf 28 30 31 29\n";
    const OPEN5: &str = "v 0.0000 0.0000 0.0000\nv 1.0000 0.0000 0.1000\nv 2.0000 0.0000 0.4000\nv 0.3090 0.9511 -0.0809\nv 0.6180 1.9021 -0.3236\nv -0.8090 0.5878 0.0309\nv -1.6180 1.1756 0.1236\nv -0.8090 -0.5878 0.0309\nv -1.6180 -1.1756 0.1236\nv 0.3090 -0.9511 -0.0809\nv 0.6180 -1.9021 -0.3236\nv 1.3090 0.9511 0.0809\nv 1.6180 1.9021 -0.1000\nv 2.3090 0.9511 0.4427\nv 2.6180 1.9021 0.3236\nv -0.5000 1.5388 -0.2118\nv -1.3090 2.1266 -0.2809\nv -0.1910 2.4899 -0.6163\nv -1.0000 3.0777 -0.8472\nv -1.6180 0.0000 0.2618\nv -2.4271 -0.5878 0.5545\nv -2.4271 0.5878 0.5545\nv -3.2361 0.0000 1.0472\nv -0.5000 -1.5388 -0.2118\nv -0.1910 -2.4899 -0.6163\nv -1.3090 -2.1266 -0.2809\nv -1.0000 -3.0777 -0.8472\nv 1.3090 -0.9511 0.0809\nv 2.3090 -0.9511 0.4427\nv 1.6180 -1.9021 -0.1000\nv 2.6180 -1.9021 0.3236\nf 2 3 14 12\nf 4 12 13 5\nf 12 14 15 13\nf 1 4 16 6\nf 4 5 18 16\nf 6 16 17 7\nf 16 18 19 17\nf 1 6 20 8\nf 6 7 22 20\nf 8 20 21 9\nf 20 22 23 21\nf 1 8 24 10\nf 8 9 26 24\nf 10 24 25 11\nf 24 26 27 25\nf 1 10 28 2\nf 10 11 30 28\nf 2 28 29 3\nf 28 30 31 29\n";
    const PENTA5: &str = "v 0.0000 0.0000 0.0000\nv 1.0000 0.0000 0.1000\nv 2.0000 0.0000 0.4000\nv 0.3090 0.9511 -0.0809\nv 0.6180 1.9021 -0.3236\nv -0.8090 0.5878 0.0309\nv -1.6180 1.1756 0.1236\nv -0.8090 -0.5878 0.0309\nv -1.6180 -1.1756 0.1236\nv 0.3090 -0.9511 -0.0809\nv 0.6180 -1.9021 -0.3236\nv 1.3090 0.9511 0.0809\nv 1.6180 1.9021 -0.1000\nv 2.3090 0.9511 0.4427\nv 2.6180 1.9021 0.3236\nv -0.5000 1.5388 -0.2118\nv -1.3090 2.1266 -0.2809\nv -0.1910 2.4899 -0.6163\nv -1.0000 3.0777 -0.8472\nv -1.6180 0.0000 0.2618\nv -2.4271 -0.5878 0.5545\nv -2.4271 0.5878 0.5545\nv -3.2361 0.0000 1.0472\nv -0.5000 -1.5388 -0.2118\nv -0.1910 -2.4899 -0.6163\nv -1.3090 -2.1266 -0.2809\nv -1.0000 -3.0777 -0.8472\nv 1.3090 -0.9511 0.0809\nv 2.3090 -0.9511 0.4427\nv 1.6180 -1.9021 -0.1000\nv 2.6180 -1.9021 0.3236\nv 9.0 9.0 9.0\nf 1 2 12 4\nf 2 3 32 14 12\nf 4 12 13 5\nf 12 14 15 13\nf 1 4 16 6\nf 4 5 18 16\nf 6 16 17 7\nf 16 18 19 17\nf 1 6 20 8\nf 6 7 22 20\nf 8 20 21 9\nf 20 22 23 21\nf 1 8 24 10\nf 8 9 26 24\nf 10 24 25 11\nf 24 26 27 25\nf 1 10 28 2\nf 10 11 30 28\nf 2 28 29 3\nf 28 30 31 29\n";
    const G2: &[(&str, &str)] = &[
        ("ring5.obj", RING5),
        ("tri5.obj", TRI5),
        ("open5.obj", OPEN5),
        ("penta5.obj", PENTA5),
    ];
    v.extend([
        bad_with(
            "g2cap-not-extraordinary",
            &[
                "g2-cap",
                "ring5.obj",
                "--vertex",
                "1",
                "--c",
                "0.5",
                "-o",
                "cap.obj",
            ],
            G2,
            "vertex 1 (OBJ 2) is not extraordinary",
        ),
        bad_with(
            "g2cap-boundary-vertex",
            &[
                "g2-cap",
                "ring5.obj",
                "--vertex",
                "2",
                "--c",
                "0.5",
                "-o",
                "cap.obj",
            ],
            G2,
            "vertex 2 (OBJ 3) is a boundary vertex",
        ),
        bad_with(
            "g2cap-not-quads-around-vertex",
            &[
                "g2-cap", "tri5.obj", "--vertex", "0", "--c", "0.5", "-o", "cap.obj",
            ],
            G2,
            "vertex 0 (OBJ 1) is not all quads",
        ),
        bad_with(
            "g2cap-centre-on-the-boundary",
            &[
                "g2-cap",
                "open5.obj",
                "--vertex",
                "0",
                "--c",
                "0.5",
                "-o",
                "cap.obj",
            ],
            G2,
            "vertex 0 (OBJ 1) is a boundary vertex",
        ),
        bad_with(
            "g2cap-pentagon-in-the-2-ring",
            &[
                "g2-cap",
                "penta5.obj",
                "--vertex",
                "0",
                "--c",
                "0.5",
                "-o",
                "cap.obj",
            ],
            G2,
            "the 2-ring of vertex 0 (OBJ 1) is not all quads",
        ),
        bad_with(
            "g2cap-vertex-out-of-range",
            &["g2-cap", "ring5.obj", "--vertex", "99", "--c", "0.5"],
            G2,
            "vertex 99 (OBJ 100) does not exist",
        ),
        bad_with(
            "g2cap-missing-mesh",
            &["g2-cap", "nothere.obj", "--vertex", "0", "--c", "0.5"],
            G2,
            "nothere.obj",
        ),
        bad_with(
            "g2cap-c-out-of-range",
            &["g2-cap", "ring5.obj", "--vertex", "0", "--c", "1.5"],
            G2,
            "--c",
        ),
        bad_with(
            "g2cap-output-is-input",
            &[
                "g2-cap",
                "ring5.obj",
                "--vertex",
                "0",
                "--c",
                "0.5",
                "-o",
                "ring5.obj",
            ],
            G2,
            "ring5.obj",
        ),
        bad_with(
            "g2cap-mesh-without-vertex",
            &["g2-cap", "ring5.obj", "--c", "0.5"],
            G2,
            "--vertex",
        ),
        bad(
            "g2cap-both-sources",
            &[
                "g2-cap",
                "--vertex",
                "0",
                "--valence",
                "5",
                "--random-net",
                "1",
                "--c",
                "0.5",
            ],
            "not both",
        ),
        bad(
            "g2cap-valence-without-seed",
            &["g2-cap", "--valence", "5", "--c", "0.5"],
            "--random-net",
        ),
        bad("g2cap-nothing", &["g2-cap", "--c", "0.5"], "nothing to cap"),
        bad(
            "g2cap-valence-too-large",
            &[
                "g2-cap",
                "--valence",
                "40",
                "--random-net",
                "1",
                "--c",
                "0.5",
            ],
            "valence 40",
        ),
        bad(
            "g2cap-valence-two",
            &[
                "g2-cap",
                "--valence",
                "2",
                "--random-net",
                "1",
                "--c",
                "0.5",
            ],
            "valence 2",
        ),
        bad(
            "g2cap-samples-zero",
            &[
                "g2-cap",
                "--valence",
                "5",
                "--random-net",
                "1",
                "--c",
                "0.5",
                "--samples",
                "0",
            ],
            "--samples",
        ),
        full(
            "g2cap-stdout-full",
            &[
                "g2-cap",
                "--valence",
                "5",
                "--random-net",
                "1",
                "--c",
                "0.5",
            ],
        ),
            // Degenerate 2-rings (all points on one point, or on one line) are
        // bad input naming the vertex (not a NaN residual and exit 1).
        bad_with(
            "g2cap-ring-on-one-point",
            &["g2-cap", "pt.obj", "--vertex", "0", "--c", "0.5"],
            &[("pt.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 9 21 12\nf 3 10 21 9\nf 4 11 21 10\nf 2 12 21 11\nf 5 13 22 16\nf 6 14 22 13\nf 8 15 22 14\nf 7 16 22 15\nf 1 12 23 18\nf 2 17 23 12\nf 6 13 23 17\nf 5 18 23 13\nf 3 19 24 10\nf 7 15 24 19\nf 8 20 24 15\nf 4 10 24 20\nf 1 18 25 9\nf 5 16 25 18\nf 7 19 25 16\nf 3 9 25 19\nf 2 11 26 17\nf 4 20 26 11\nf 8 14 26 20\nf 6 17 26 14\n")],
            "the 2-ring of vertex 0 (OBJ 1) is degenerate",
        ),
        bad_with(
            "g2cap-ring-on-one-line",
            &["g2-cap", "line.obj", "--vertex", "0", "--c", "0.5"],
            &[("line.obj", "v -0.5555555555555556 0 0\nv 0.5555555555555556 0 0\nv -0.5555555555555556 0 0\nv 0.5555555555555556 0 0\nv -0.5555555555555556 0 0\nv 0.5555555555555556 0 0\nv -0.5555555555555556 0 0\nv 0.5555555555555556 0 0\nv -0.75 0 0\nv 0.0 0 0\nv 0.75 0 0\nv 0.0 0 0\nv 0.0 0 0\nv 0.75 0 0\nv 0.0 0 0\nv -0.75 0 0\nv 0.75 0 0\nv -0.75 0 0\nv -0.75 0 0\nv 0.75 0 0\nv 0.0 0 0\nv 0.0 0 0\nv 0.0 0 0\nv 0.0 0 0\nv -1.0 0 0\nv 1.0 0 0\nf 1 9 21 12\nf 3 10 21 9\nf 4 11 21 10\nf 2 12 21 11\nf 5 13 22 16\nf 6 14 22 13\nf 8 15 22 14\nf 7 16 22 15\nf 1 12 23 18\nf 2 17 23 12\nf 6 13 23 17\nf 5 18 23 13\nf 3 19 24 10\nf 7 15 24 19\nf 8 20 24 15\nf 4 10 24 20\nf 1 18 25 9\nf 5 16 25 18\nf 7 19 25 16\nf 3 9 25 19\nf 2 11 26 17\nf 4 20 26 11\nf 8 14 26 20\nf 6 17 26 14\n")],
            "the 2-ring of vertex 0 (OBJ 1) is degenerate",
        ),
        // ccss-bound: a tolerance below what f64 resolves for the net is bad
        // input naming it (not 200 steps and a failing LP, exit 1).
        bad_with(
            "ccss-bound-epsilon-below-resolution",
            &["ccss-bound", "--valence", "5", "--net", "net.txt", "--epsilon", "1e-300"],
            &[("net.txt", "0 0 0\n1 2 1\n2 4 0\n0 1 1\n1 3 0\n2 0 1\n0 2 0\n1 4 1\n2 1 0\n0 3 1\n1 0 0\n2 2 1\n0 4 0\n1 1 1\n2 3 0\n0 0 1\n1 2 0\n2 4 1\n")],
            "epsilon = 1e-300 is below what f64 resolves",
        ),
]);
    // (end of section g2-cap)

    let _ = full; // used by the cli-io section
                  // ===================================================================
                  // SECTION curvature: the `curvature` and
                  // `curvature-tuning` figure keys and the sweep column switch.
                  // ===================================================================
    v.extend([
        bad_with(
            "report-curvature-valence-too-small",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nvalences = [2, 5]\n")],
            "valences must list 1 to 8 valences in 3..=16, got [2, 5]",
        ),
        bad_with(
            "report-curvature-c-out-of-range",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nc = 1.5\n")],
            "c must be between 0 and 1, got 1.5",
        ),
        bad_with(
            "report-curvature-levels-zero",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nlevels = 0\n")],
            "levels must be between 1 and 24, got 0",
        ),
        bad_with(
            "report-curvature-unknown-key",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nvalence = [3, 5]\n")],
            "valence",
        ),
        bad_with(
            "report-curvature-unknown-scheme",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"butterfly\"\n")],
            "butterfly",
        ),
        bad_with(
            "report-curvature-ratios-for-loop",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"loop\"\nratios = [0.3, 0.6, 0.5]\n")],
            "scheme loop takes no knot intervals",
        ),
        bad_with(
            "report-curvature-c-for-doo-sabin",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"doo-sabin\"\nc = 0.5\n")],
            "scheme doo-sabin takes no shape parameter c",
        ),
        bad_with(
            "report-curvature-adjustable-without-c",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"adjustable-cc\"\n")],
            "needs the shape parameter c",
        ),
        bad_with(
            "report-curvature-ratio-out-of-range",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"nurds\"\nratios = [0.3, 1.6, 0.5]\n")],
            "figure[0].ratios: edge ratio r_1 must lie strictly between 0 and 1",
        ),
        bad_with(
            "report-curvature-ratios-and-knots",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"nurds\"\nratios = [0.3, 0.6, 0.5]\nknots = [[1, 2], [2, 1], [1, 1]]\n")],
            "give at most one of ratios and knots",
        ),
        bad_with(
            "report-curvature-knots-not-positive",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"nurds\"\nknots = [[1, 2], [0, 1], [1, 1]]\n")],
            "figure[0].knots: knot interval p_1 must be finite and > 0",
        ),
        bad_with(
            "report-curvature-valences-do-not-match-ratios",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"nurds\"\nratios = [0.3, 0.6, 0.5]\nvalences = [4]\n")],
            "valences [4] do not match the 3 knot values given",
        ),
        bad_with(
            "report-curvature-too-many-ratios",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme = \"nurds\"\nratios = [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5]\n")],
            "the curvature figure takes valences 3..=16, got 17 knot values",
        ),
        bad_with(
            "report-curvature-tuning-grid-zero",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature-tuning\"\ngrid = 0\n")],
            "grid must be between 1 and 4096, got 0",
        ),
        bad_with(
            "report-curvature-tuning-valence-range",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature-tuning\"\nvalence = [2, 5]\n")],
            "valence range must satisfy 3 <= lo <= hi <= 64, got [2, 5]",
        ),
        // Report figures whose largest settings would run for hours without
        // a word: refused at parse time with the estimate.
        bad_with(
            "report-cc-c1-interval-heavy",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"cc-c1-interval\"\nvalence = [3, 64]\nsamples = 1000\ntol = 1e-12\n")],
            "figure[0].samples: the C1 and standard intervals of 62 valences up to 64 with 1000 samples",
        ),
        bad_with(
            "report-subdominant-vs-valence-heavy",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"subdominant-vs-valence\"\nvalence = [3, 256]\nsamples = 1000\n")],
            "figure[0].samples: 254254 classifications of up to 256 x 256 face blocks take",
        ),
        bad_with(
            "report-table-charmap-unknown-method",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\ncharmap = \"rings\"\nconfigs = [{ scheme = \"loop\", valence = 5 }]\n")],
            "figure[0].charmap: charmap must be one of ring, generic, got \"rings\"",
        ),
        bad_with(
            "report-table-charmap-generic-heavy",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\ncharmap = \"generic\"\nconfigs = [{ scheme = \"loop\", valence = 200 }]\n")],
            "figure[0].configs: the generic certificate of 1 configuration takes ~",
        ),
        bad_with(
            "report-table-heavy-configurations",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"nurds\", valence = 256, random_knots = 4.0 }, { scheme = \"nurds\", valence = 256, random_knots = 4.0 }]\n")],
            "figure[0].configs: analysing these 2 configurations (valences up to 256) takes",
        ),
        bad_with(
            "sweep-columns-curvature-not-bool",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"catmull-clark\"\nvalences = [5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\ncurvature = \"yes\"\n",
            )],
            "columns.curvature",
        ),
        bad_with(
            "sweep-columns-generic-charmap-in-a-sector-sweep",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"loop\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\ngeneric_charmap = true\n",
            )],
            "columns.generic_charmap: the generic certificate analyses interior configurations",
        ),
        bad_with(
            "sweep-columns-generic-charmap-not-bool",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[(
                "s.toml",
                "name = \"x\"\nscheme = \"loop\"\nvalences = [5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\ngeneric_charmap = \"yes\"\n",
            )],
            "columns.generic_charmap: invalid type: string \"yes\", expected a boolean",
        ),
    ]);

    // ===================================================================
    // SECTION sharp-meshes: open meshes, crease and corner tags (OBJ `t`
    // lines and --tags), --boundary, --creasing.
    // ===================================================================
    v.extend([
        bad_with("sharp-tag-bad-counts", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1 0 1 2\n"))], "tag line 9: tag crease: counts \"2/1\""),
        bad_with("sharp-tag-unsupported-name", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t hole 1/0/0 0\n"))], "tag line 9: unsupported tag \"hole\""),
        bad_with("sharp-tag-negative-sharpness", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 1 -1\n"))], "tag line 9: sharpness -1 must be a finite number >= 0"),
        bad_with("sharp-tag-nan-sharpness", &["subdivide", "m.obj", "--scheme", "loop", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt corner 1/1/0 0 nan\n")], "tag line 5: sharpness nan"),
        bad_with("sharp-tag-infinite-sharpness", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t corner 1/1/0 0 inf\n"))], "tag line 9: sharpness inf"),
        bad_with("sharp-tag-names-no-edge", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 4 1\n"))], "tag line 9: the mesh has no edge 0-4"),
        bad_with("sharp-tag-names-no-vertex", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t corner 1/1/0 6 1\n"))], "tag line 9: the mesh has no vertex 6"),
        bad_with("sharp-tag-duplicate", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 1 1\nt crease 2/1/0 1 0 2\n"))], "tag line 10: edge 1-0 was already tagged on line 9"),
        bad_with("sharp-tag-bad-index", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 x 1\n"))], "tag line 9: tag crease: vertex index \"x\""),
        bad_with("sharp-tag-missing-argument", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 1\n"))], "tag line 9: tag crease 2/1/0: expected 3 arguments, got 2"),
        bad_with("sharp-tag-odd-crease-indices", &["subdivide", "m.obj", "--scheme", "catmull-clark", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 3/1/0 0 1 2 1\n"))], "tag line 9: tag crease: 3 vertex indices"),
        bad_with("sharp-tags-file-missing", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--tags", "nope.tags", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "nope.tags"),
        bad_with("sharp-tags-file-non-tag-line", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--tags", "t.tags", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("t.tags", "# tags\nv 0 0 0\n")], "t.tags: tag line 2: \"v\": a tag file holds only t lines"),
        bad_with("sharp-tags-file-names-no-edge", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--tags", "t.tags", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("t.tags", "t crease 2/1/0 0 5 1\n")], "t.tags: tag line 1: the mesh has no edge 0-5"),
        bad_with("sharp-tags-file-is-output", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--tags", "t.tags", "-o", "t.tags"],
            &[("m.obj", sharp_strip!()), ("t.tags", "t crease 2/1/0 0 1 1\n")], "t.tags"),
        bad_with("sharp-open-non-manifold-edge", &["subdivide", "m.obj", "--scheme", "loop", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")], "non-manifold edge 0-1 (OBJ 1-2): it lies in 3 faces"),
        bad_with("sharp-open-non-manifold-vertex", &["subdivide", "m.obj", "--scheme", "loop", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n")], "non-manifold vertex 0 (OBJ 1): its faces form 2 separate fans"),
        bad_with("sharp-boundary-bad-value", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--boundary", "sideways", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "sideways"),
        bad_with("sharp-creasing-bad-value", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--creasing", "linear", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "linear"),
        bad("sharp-boundary-with-closed-only-scheme", &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "--boundary", "edge-only", "-o", "o.obj"],
            "--boundary: scheme nurds takes no crease or corner tags and has one boundary rule"),
        bad("sharp-creasing-with-closed-only-scheme", &["subdivide", "{M}/cube.obj", "--scheme", "adjustable-cc", "--c", "0.3", "--creasing", "chaikin", "-o", "o.obj"],
            "--creasing: scheme adjustable-cc refines closed meshes without tags only"),
        bad_with("sharp-tags-with-closed-only-scheme", &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "--tags", "t.tags", "-o", "o.obj"],
            &[("t.tags", "t crease 2/1/0 0 1 1\n")], "--tags: scheme nurds takes no crease or corner tags and has one boundary rule"),
        bad_with("sharp-obj-tags-with-closed-only-scheme", &["subdivide", "m.obj", "--scheme", "doo-sabin", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nt crease 2/1/0 0 1 1\n")], "tag line 9: crease and corner tags need --scheme catmull-clark or loop"),
        bad_with("sharp-limit-needs-quads", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--levels", "0", "--limit", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")], "--limit: face 0 has 3 corners; the Catmull-Clark limit masks needs an all-quad mesh"),
        bad_with("sharp-loop-on-open-quads", &["subdivide", "m.obj", "--scheme", "loop", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "face 0 has 4 corners; --scheme loop needs an all-triangle mesh"),
        bad_with("sharp-levels-too-many", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--levels", "40", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--levels 40: the result would have"),
        bad_with("sharp-levels-over-budget", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--levels", "13", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--levels 13"),
        bad_with("sharp-normals-without-limit", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--normals", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--normals needs --limit"),
        bad_with("sharp-normals-without-output", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--limit", "--normals", "--timing"],
            &[("m.obj", sharp_strip!())], "--normals needs -o OUT.obj"),
        bad("sharp-normals-closed-only-scheme", &["subdivide", "{M}/cube.obj", "--scheme", "nurds", "--limit", "--normals", "-o", "o.obj"],
            "--normals: scheme nurds: limit normals are written under catmull-clark or loop only"),
        bad("sharp-normals-scheme-file", &["subdivide", "{M}/cube.obj", "--scheme-file", "{A}/schemes/catmull-clark.toml", "--limit", "--normals", "-o", "o.obj"],
            "limit normals are written under catmull-clark or loop only"),
        bad("sharp-normals-closed-non-quads-level-0", &["subdivide", "{M}/tetrahedron.obj", "--scheme", "catmull-clark", "--levels", "0", "--limit", "--normals", "-o", "o.obj"],
            "--normals: vertex 0: face 0 has 3 corners"),
        bad_with("sharp-normals-interior-corner", &["subdivide", "m.obj", "--scheme", "catmull-clark", "--levels", "1", "--boundary", "edge-and-corner", "--limit", "--normals", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\nf 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\nt corner 1/1/0 4 10\n")],
            "--normals: vertex 4: an interior vertex with the Corner rule"),
    ]);
    // (end of section sharp-meshes)
    // ===================================================================
    // SECTION open-doo-sabin: open meshes under NURDS, Doo-Sabin and the
    // CC variant (boundary rule of math doc section 19).
    // ===================================================================
    v.extend([
        bad_with("open-ds-non-manifold-edge", &["subdivide", "m.obj", "--scheme", "nurds", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")], "non-manifold edge 0-1 (OBJ 1-2): it lies in 3 faces"),
        bad_with("open-ds-non-manifold-vertex", &["subdivide", "m.obj", "--scheme", "doo-sabin", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n")], "non-manifold vertex 0 (OBJ 1): its faces form 2 separate fans"),
        bad_with("open-ds-inconsistent-orientation", &["subdivide", "m.obj", "--scheme", "cc-variant", "-o", "o.obj"],
            &[("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n")], "inconsistent orientation"),
        bad_with("open-ds-knots-boundary-direction-missing", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "1 2 0.5\n")], "k.txt: knot file line 1: boundary edge 1->2 (OBJ indices) is given, its direction 2->1 is not"),
        bad_with("open-ds-knots-outer-direction-only", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "# outer side\n2 1 0.5\n")], "knot file line 2: boundary edge 2->1 (OBJ indices) is given, its direction 1->2 is not"),
        bad_with("open-ds-knots-boundary-negative", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "1 2 0.5\n2 1 -1\n")], "knot file line 2: interval of 2->1 (OBJ indices) must be finite and > 0, got -1"),
        bad_with("open-ds-knots-boundary-zero", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "2 1 0\n1 2 1\n")], "knot file line 1: interval of 2->1 (OBJ indices) must be finite and > 0, got 0"),
        bad_with("open-ds-knots-no-such-edge", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "1 3 1\n")], "knot file line 1: the mesh has no directed edge 1->3"),
        bad_with("open-ds-knots-duplicate-boundary-direction", &["subdivide", "m.obj", "--scheme", "nurds", "--knots", "k.txt", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("k.txt", "2 1 1\n1 2 1\n2 1 3\n")], "knot file line 3: directed edge 2->1 (OBJ indices) was already given on line 1"),
        bad_with("open-ds-default-interval-negative", &["subdivide", "m.obj", "--scheme", "cc-variant", "--default-interval", "-1", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--default-interval must be finite and > 0"),
        bad_with("open-ds-obj-crease-tag", &["subdivide", "m.obj", "--scheme", "nurds", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t crease 2/1/0 0 1 1\n"))], "tag line 9: crease and corner tags need --scheme catmull-clark or loop"),
        bad_with("open-ds-obj-corner-tag", &["subdivide", "m.obj", "--scheme", "doo-sabin", "-o", "o.obj"],
            &[("m.obj", concat!(sharp_strip!(), "t corner 1/1/0 0 10\n"))], "tag line 9: crease and corner tags need --scheme catmull-clark or loop"),
        bad_with("open-ds-tags-file", &["subdivide", "m.obj", "--scheme", "cc-variant", "--tags", "t.tags", "-o", "o.obj"],
            &[("m.obj", sharp_strip!()), ("t.tags", "t corner 1/1/0 0 1\n")], "--tags: scheme cc-variant takes no crease or corner tags"),
        bad_with("open-ds-boundary-flag", &["subdivide", "m.obj", "--scheme", "doo-sabin", "--boundary", "edge-and-corner", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--boundary: scheme doo-sabin takes no crease or corner tags and has one boundary rule"),
        bad_with("open-ds-limit", &["subdivide", "m.obj", "--scheme", "nurds", "--limit", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--limit: m.obj has a boundary; --scheme nurds gives --limit for closed meshes only"),
        bad_with("open-ds-stats", &["subdivide", "m.obj", "--scheme", "doo-sabin", "--stats"],
            &[("m.obj", sharp_strip!())], "--stats: m.obj has a boundary"),
        bad_with("open-ds-levels-too-many", &["subdivide", "m.obj", "--scheme", "nurds", "--levels", "40", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--levels 40: the result would have"),
        bad_with("open-ds-levels-over-budget", &["subdivide", "m.obj", "--scheme", "doo-sabin", "--levels", "13", "-o", "o.obj"],
            &[("m.obj", sharp_strip!())], "--levels 13"),
    ]);
    // (end of section open-doo-sabin)
    // ===================================================================
    // SECTION scheme-files: --scheme-file of analyze, matrix, sweep and
    // merge; every refusal of the scheme-file validator.
    // ===================================================================
    const SF_SUM: &str =
        "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1\"\nedge = \"1/n\"\nface = \"0\"\n";
    const SF_DIV0: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - 1/(n-5)\"\nedge = \"1/(n*(n-5))\"\nface = \"0\"\n";
    const SF_LATE: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - 1/(n-40)\"\nedge = \"1/(n*(n-40))\"\nface = \"0\"\n";
    const SF_VAR: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - m\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_NOFACE: &str =
        "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1\"\nedge = \"0\"\n";
    const SF_UNKNOWN: &str = "name = \"t\"\ntopology = \"quad\"\ncolour = \"red\"\n[vertex]\nself = \"1\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_TOPO: &str =
        "name = \"t\"\ntopology = \"hex\"\n[vertex]\nself = \"1\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_TRIFACE: &str = "name = \"t\"\ntopology = \"triangle\"\n[vertex]\nself = \"1\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_NAME: &str =
        "name = \"loop\"\ntopology = \"triangle\"\n[vertex]\nself = \"1\"\nedge = \"0\"\n";
    const SF_FLOAT: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"cos(0) + 1e-9\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_NAN: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1 + 0*sqrt(4-n)\"\nedge = \"0\"\nface = \"0\"\n";
    const SF_OK: &str = "name = \"t\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - 7/(4*n)\"\nedge = \"3/(2*n^2)\"\nface = \"1/(4*n^2)\"\n";
    const SF_SPEC_RATIOS: &str = "name = \"x\"\nscheme = \"nurds\"\nvalences = [5]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n";
    const SF_SPEC_EXACT: &str = "name = \"x\"\nscheme = \"nurds\"\nvalences = [5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\nexact_certificate = true\n";
    const SF_SPEC: &str = "name = \"x\"\nscheme = \"catmull-clark\"\nvalences = [5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n";
    const A5: &[&str] = &["analyze", "--scheme-file", "f.toml", "--valence", "5"];
    v.extend([
        bad(
            "scheme-file-missing",
            &["analyze", "--scheme-file", "nope.toml", "--valence", "5"],
            "--scheme-file nope.toml: cannot read",
        ),
        bad_with(
            "scheme-file-with-scheme",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--scheme-file",
                "f.toml",
                "--valence",
                "5",
            ],
            &[("f.toml", SF_OK)],
            "cannot be used with",
        ),
        bad_with(
            "scheme-file-with-c",
            &[
                "matrix",
                "--scheme-file",
                "f.toml",
                "--c",
                "0.3",
                "--valence",
                "5",
            ],
            &[("f.toml", SF_OK)],
            "cannot be used with",
        ),
        bad_with(
            "scheme-file-no-valence",
            &["analyze", "--scheme-file", "f.toml"],
            &[("f.toml", SF_OK)],
            "--valence is required with --scheme-file",
        ),
        bad_with(
            "scheme-file-valence-2",
            &["matrix", "--scheme-file", "f.toml", "--valence", "2"],
            &[("f.toml", SF_OK)],
            "valence: must be at least 3, got 2",
        ),
        bad_with(
            "scheme-file-sum",
            A5,
            &[("f.toml", SF_SUM)],
            "vertex at valence 3: the weights self + n*edge + n*face sum to 2, not 1",
        ),
        bad_with(
            "scheme-file-division-by-zero",
            A5,
            &[("f.toml", SF_DIV0)],
            "vertex.self at valence 5: division by zero",
        ),
        bad_with(
            "scheme-file-unknown-variable",
            A5,
            &[("f.toml", SF_VAR)],
            "vertex.self: unknown variable m",
        ),
        bad_with(
            "scheme-file-missing-key",
            A5,
            &[("f.toml", SF_NOFACE)],
            "vertex.face: missing key",
        ),
        bad_with(
            "scheme-file-unknown-key",
            A5,
            &[("f.toml", SF_UNKNOWN)],
            "colour: unknown key",
        ),
        bad_with(
            "scheme-file-bad-topology",
            A5,
            &[("f.toml", SF_TOPO)],
            "topology: \"hex\" is not a topology",
        ),
        bad_with(
            "scheme-file-triangle-face",
            A5,
            &[("f.toml", SF_TRIFACE)],
            "vertex.face: a triangle scheme has no face-diagonal neighbours",
        ),
        bad_with(
            "scheme-file-builtin-name",
            A5,
            &[("f.toml", SF_NAME)],
            "name: \"loop\" is a built-in scheme's name",
        ),
        bad_with(
            "scheme-file-float-sum",
            A5,
            &[("f.toml", SF_FLOAT)],
            "in f64, not 1 within 1e-12",
        ),
        bad_with(
            "scheme-file-nan-weight",
            A5,
            &[("f.toml", SF_NAN)],
            "vertex.self at valence 5: the weight is NaN",
        ),
        bad_with(
            "scheme-file-not-toml",
            A5,
            &[("f.toml", "name = \"t\n")],
            "not valid TOML (line 1",
        ),
        bad_with(
            "scheme-file-late-division-by-zero",
            &["analyze", "--scheme-file", "f.toml", "--valence", "40"],
            &[("f.toml", SF_LATE)],
            "vertex.self at valence 40: division by zero",
        ),
        bad_with(
            "scheme-file-analyze-exact",
            &[
                "analyze",
                "--scheme-file",
                "f.toml",
                "--valence",
                "5",
                "--exact",
            ],
            &[("f.toml", SF_OK)],
            "--exact is not available with --scheme-file",
        ),
        bad(
            "scheme-file-matrix-exact-irrational",
            &[
                "matrix",
                "--scheme-file",
                "{A}/schemes/loop.toml",
                "--valence",
                "5",
                "--exact",
            ],
            "has no exact matrix",
        ),
        bad_with(
            "scheme-file-sweep-missing",
            &[
                "sweep",
                "s.toml",
                "--scheme-file",
                "nope.toml",
                "--out",
                "o.csv",
            ],
            &[("s.toml", SF_SPEC)],
            "--scheme-file nope.toml: cannot read",
        ),
        bad_with(
            "scheme-file-sweep-invalid-file",
            &[
                "sweep",
                "s.toml",
                "--scheme-file",
                "f.toml",
                "--out",
                "o.csv",
            ],
            &[("s.toml", SF_SPEC), ("f.toml", SF_SUM)],
            "vertex at valence 3",
        ),
        bad_with(
            "scheme-file-sweep-space-not-uniform",
            &[
                "sweep",
                "s.toml",
                "--scheme-file",
                "f.toml",
                "--out",
                "o.csv",
            ],
            &[("s.toml", SF_SPEC_RATIOS), ("f.toml", SF_OK)],
            "space.kind: scheme t sweeps valences only",
        ),
        bad_with(
            "scheme-file-sweep-exact-certificate",
            &[
                "sweep",
                "s.toml",
                "--scheme-file",
                "f.toml",
                "--out",
                "o.csv",
            ],
            &[("s.toml", SF_SPEC_EXACT), ("f.toml", SF_OK)],
            "columns.exact_certificate: scheme t has no exact face-block certificate",
        ),
        bad_with(
            "scheme-file-merge-invalid-file",
            &[
                "merge",
                "a.csv",
                "--spec",
                "s.toml",
                "--scheme-file",
                "f.toml",
                "--out",
                "m.csv",
            ],
            &[("s.toml", SF_SPEC), ("f.toml", SF_DIV0)],
            "vertex.self at valence 5: division by zero",
        ),
        // subdivide --scheme-file: closed meshes without tags only.
        bad(
            "subdivide-scheme-file-missing",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "nope.toml",
                "-o",
                "o.obj",
            ],
            "--scheme-file nope.toml: cannot read",
        ),
        bad_with(
            "subdivide-scheme-file-invalid",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "f.toml",
                "-o",
                "o.obj",
            ],
            &[("f.toml", SF_SUM)],
            "vertex at valence 3",
        ),
        bad(
            "subdivide-scheme-file-with-scheme",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--scheme",
                "catmull-clark",
                "-o",
                "o.obj",
            ],
            "cannot be used with",
        ),
        bad(
            "subdivide-scheme-file-with-c",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--c",
                "0.3",
                "-o",
                "o.obj",
            ],
            "cannot be used with",
        ),
        bad(
            "subdivide-scheme-file-with-boundary",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--boundary",
                "none",
                "-o",
                "o.obj",
            ],
            "cannot be used with",
        ),
        bad(
            "subdivide-scheme-file-with-knots-out",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--knots-out",
                "k.txt",
                "-o",
                "o.obj",
            ],
            "cannot be used with",
        ),
        // Report specs: `scheme_file` in configurations, mesh figures and
        // the curvature figure (read beside the spec).
        bad_with(
            "report-scheme-file-missing",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"nope.toml\", valence = 5 }]\n")],
            "figure[0].configs[0].scheme_file: nope.toml:",
        ),
        bad_with(
            "report-scheme-file-invalid",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\", valence = 5 }]\n"),
                ("d/f.toml", SF_SUM),
            ],
            "figure[0].configs[0].scheme_file: f.toml:",
        ),
        bad_with(
            "report-scheme-file-and-scheme",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"loop\", scheme_file = \"f.toml\", valence = 5 }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "give either scheme or scheme_file, not both",
        ),
        bad_with(
            "report-config-without-scheme",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ valence = 5 }]\n")],
            "configs[0]: give scheme (a built-in name) or scheme_file",
        ),
        bad_with(
            "report-scheme-file-with-ratios",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\", ratios = [0.5, 0.5, 0.5] }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "configs[0].ratios: ratios is not taken with scheme_file",
        ),
        bad_with(
            "report-scheme-file-with-c",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\", valence = 5, c = 0.3 }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "configs[0].c: c is not taken with scheme_file",
        ),
        bad_with(
            "report-scheme-file-without-valence",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\" }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "scheme_file needs a valence",
        ),
        bad_with(
            "report-scheme-file-valence-2",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\", valence = 2 }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "configs[0].valence: valence must be between 3 and",
        ),
        bad_with(
            "report-scheme-file-late-division-by-zero",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme_file = \"f.toml\", valence = 40 }]\n"),
                ("d/f.toml", SF_LATE),
            ],
            "configs[0].valence:",
        ),
        bad_with(
            "report-scheme-file-convergence-not-doo-sabin",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"convergence\"\nconfigs = [{ scheme_file = \"f.toml\", valence = 5 }]\n"),
                ("d/f.toml", SF_OK),
            ],
            "configs[0].scheme_file: scheme t is not in the Doo-Sabin family",
        ),
        bad_with(
            "report-mesh-picture-scheme-file-random-knots",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"mesh-picture\"\nmesh = \"cube\"\nscheme_file = \"f.toml\"\nrandom_knots = 2.0\n"),
                ("d/f.toml", SF_OK),
            ],
            "figure[0].random_knots: random_knots is not taken with scheme_file",
        ),
        bad_with(
            "report-mesh-picture-scheme-and-scheme-file",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"mesh-picture\"\nmesh = \"cube\"\nscheme = \"catmull-clark\"\nscheme_file = \"f.toml\"\n"),
                ("d/f.toml", SF_OK),
            ],
            "figure[0].scheme_file: give either scheme or scheme_file, not both",
        ),
        bad_with(
            "report-mesh-picture-without-scheme",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"mesh-picture\"\nmesh = \"cube\"\n")],
            "give scheme (a built-in name) or scheme_file",
        ),
        bad_with(
            "report-mesh-convergence-scheme-file",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"mesh-convergence\"\nmesh = \"cube\"\nscheme_file = \"f.toml\"\n"),
                ("d/f.toml", SF_OK),
            ],
            "figure[0].scheme_file: scheme t has no per-level statistics",
        ),
        bad_with(
            "report-curvature-scheme-file-with-c",
            &["report", "d/s.toml", "--out", "r"],
            &[
                ("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme_file = \"f.toml\"\nc = 0.5\n"),
                ("d/f.toml", SF_OK),
            ],
            "figure[0].c: c is not taken with scheme_file",
        ),
        bad_with(
            "report-curvature-scheme-file-missing",
            &["report", "d/s.toml", "--out", "r"],
            &[("d/s.toml", "name = \"t\"\n[[figure]]\nkind = \"curvature\"\nscheme_file = \"nope.toml\"\n")],
            "figure[0].scheme_file: nope.toml:",
        ),
        bad(
            "subdivide-scheme-file-open-mesh",
            &[
                "subdivide",
                "{M}/sharp/grid_quads_untagged.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "-o",
                "o.obj",
            ],
            "gives no boundary rules (scheme files refine closed meshes)",
        ),
        bad(
            "subdivide-scheme-file-tagged-mesh",
            &[
                "subdivide",
                "{M}/sharp/grid_quads.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "-o",
                "o.obj",
            ],
            "gives no crease or corner rules",
        ),
        bad(
            "subdivide-scheme-file-stats",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--stats",
            ],
            "--stats: scheme catmull-clark-file has no per-level statistics",
        ),
        bad(
            "subdivide-scheme-file-triangle-on-quads",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/loop.toml",
                "-o",
                "o.obj",
            ],
            "Loop refinement needs an all-triangle mesh",
        ),
        bad(
            "subdivide-scheme-file-limit-non-quads",
            &[
                "subdivide",
                "{M}/truncated_icosahedron.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--levels",
                "0",
                "--limit",
                "-o",
                "o.obj",
            ],
            "the Catmull-Clark limit stencil",
        ),
        bad(
            "subdivide-scheme-file-over-budget",
            &[
                "subdivide",
                "{M}/cube.obj",
                "--scheme-file",
                "{A}/schemes/catmull-clark.toml",
                "--levels",
                "13",
                "-o",
                "o.obj",
            ],
            "--levels 13",
        ),
    ]);

    // ===================================================================
    // SECTION boundary-analysis: `analyze` and `matrix` at boundary,
    // crease and corner vertices (--vertex, --faces, --angle, --rules).
    // ===================================================================
    v.extend([
        bad(
            "sector-no-faces",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--rules", "blz",
            ],
            "--vertex boundary needs --faces",
        ),
        bad(
            "sector-no-rules",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "3",
            ],
            "needs --rules standard or blz",
        ),
        bad(
            "sector-bad-rules",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "3", "--rules",
                "zorin",
            ],
            "invalid value 'zorin' for '--rules",
        ),
        bad(
            "sector-bad-vertex",
            &[
                "analyze", "--scheme", "loop", "--vertex", "edge", "--faces", "3", "--rules", "blz",
            ],
            "invalid value 'edge' for '--vertex",
        ),
        bad(
            "sector-faces-zero",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "0", "--rules",
                "blz",
            ],
            "faces = 0: a sector has at least 1 face",
        ),
        bad(
            "sector-faces-negative",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "-2", "--rules",
                "blz",
            ],
            "--faces: \"-2\" is not a face count",
        ),
        bad(
            "sector-faces-text",
            &[
                "matrix", "--scheme", "loop", "--vertex", "boundary", "--faces", "three",
                "--rules", "blz",
            ],
            "--faces: \"three\" is not a face count",
        ),
        bad(
            "sector-faces-empty-entry",
            &[
                "analyze", "--scheme", "loop", "--vertex", "crease", "--faces", "2,", "--rules",
                "blz",
            ],
            "--faces: \"\" is not a face count",
        ),
        bad(
            "sector-faces-overflow",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--vertex",
                "boundary",
                "--faces",
                "99999999999999999999999",
                "--rules",
                "blz",
            ],
            "is not a face count",
        ),
        bad(
            "sector-faces-above-limit",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "2000000",
                "--rules", "blz",
            ],
            "a sector has at most 2^20 faces",
        ),
        bad(
            "sector-boundary-two-counts",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "2,3", "--rules",
                "blz",
            ],
            "a boundary or corner vertex takes one face count K",
        ),
        bad(
            "sector-crease-one-count",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--vertex",
                "crease",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "a crease takes two face counts K1,K2",
        ),
        bad(
            "sector-crease-zero-count",
            &[
                "matrix",
                "--scheme",
                "catmull-clark",
                "--vertex",
                "crease",
                "--faces",
                "3,0",
                "--rules",
                "standard",
            ],
            "faces = 0",
        ),
        bad(
            "sector-angle-on-boundary",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "3", "--angle",
                "90", "--rules", "blz",
            ],
            "only a corner takes an angle",
        ),
        bad(
            "sector-corner-no-angle",
            &[
                "analyze", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--rules",
                "blz",
            ],
            "a corner needs its angle",
        ),
        bad(
            "sector-angle-zero",
            &[
                "analyze", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--angle",
                "0", "--rules", "blz",
            ],
            "angle = 0: the corner angle must be finite and strictly between 0 and 360",
        ),
        bad(
            "sector-angle-360",
            &[
                "matrix", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--angle",
                "360", "--rules", "blz",
            ],
            "angle = 360",
        ),
        bad(
            "sector-angle-negative",
            &[
                "analyze", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--angle",
                "-90", "--rules", "blz",
            ],
            "angle = -90",
        ),
        bad(
            "sector-angle-nan",
            &[
                "analyze", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--angle",
                "nan", "--rules", "blz",
            ],
            "angle = NaN",
        ),
        bad(
            "sector-angle-inf",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--vertex",
                "corner",
                "--faces",
                "3",
                "--angle",
                "inf",
                "--rules",
                "blz",
            ],
            "angle = inf",
        ),
        bad(
            "sector-angle-text",
            &[
                "analyze", "--scheme", "loop", "--vertex", "corner", "--faces", "3", "--angle",
                "right", "--rules", "blz",
            ],
            "--angle: \"right\" is not a number of degrees",
        ),
        bad(
            "sector-scheme-nurds",
            &[
                "analyze", "--vertex", "boundary", "--faces", "3", "--rules", "blz",
            ],
            "--vertex needs --scheme catmull-clark or loop, got \"nurds\"",
        ),
        bad(
            "sector-with-valence",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--valence is not available with --vertex",
        ),
        bad(
            "sector-with-knots",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--knots",
                "1:1,1:1,1:1",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--knots is not available with --vertex",
        ),
        bad(
            "sector-with-ratios",
            &[
                "matrix",
                "--scheme",
                "loop",
                "--ratios",
                "0.5,0.5,0.5",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--ratios is not available with --vertex",
        ),
        bad(
            "sector-with-uniform",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--uniform",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--uniform is not available with --vertex",
        ),
        bad(
            "sector-with-c",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--c",
                "0.5",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--c is not available with --vertex",
        ),
        bad(
            "sector-with-exact",
            &[
                "analyze", "--scheme", "loop", "--exact", "--vertex", "boundary", "--faces", "3",
                "--rules", "standard",
            ],
            "--exact is not available with --vertex",
        ),
        bad(
            "sector-matrix-with-exact",
            &[
                "matrix", "--scheme", "loop", "--exact", "--vertex", "boundary", "--faces", "3",
                "--rules", "standard",
            ],
            "--exact is not available with --vertex",
        ),
        bad(
            "sector-with-structured-path",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--path",
                "structured",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            "--path structured is not available with --vertex",
        ),
        bad(
            "sector-matrix-face-block",
            &[
                "matrix", "--scheme", "loop", "--block", "face", "--vertex", "boundary", "--faces",
                "3", "--rules", "blz",
            ],
            "--block face is not available with --vertex",
        ),
        bad_with(
            "sector-with-scheme-file",
            &[
                "analyze",
                "--scheme-file",
                "f.toml",
                "--vertex",
                "boundary",
                "--faces",
                "3",
                "--rules",
                "blz",
            ],
            &[("f.toml", "name = \"x\"\n")],
            "--scheme-file is not available with --vertex",
        ),
        bad(
            "sector-faces-without-vertex",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--faces",
                "3",
            ],
            "--faces needs --vertex",
        ),
        bad(
            "sector-angle-without-vertex",
            &[
                "matrix",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--angle",
                "90",
            ],
            "--angle needs --vertex",
        ),
        bad(
            "sector-rules-without-vertex",
            &[
                "analyze",
                "--scheme",
                "loop",
                "--valence",
                "5",
                "--rules",
                "blz",
            ],
            "--rules needs --vertex",
        ),
        bad(
            "sector-analyze-work-limit",
            &[
                "analyze",
                "--scheme",
                "catmull-clark",
                "--vertex",
                "boundary",
                "--faces",
                "1000",
                "--rules",
                "blz",
            ],
            "catmull-clark boundary K=1000 (blz) takes",
        ),
        bad(
            "sector-matrix-physical-memory",
            &[
                "matrix",
                "--scheme",
                "loop",
                "--vertex",
                "crease",
                "--faces",
                "100000,100000",
                "--rules",
                "blz",
                "--force",
            ],
            "refused even with --force",
        ),
        full(
            "full-sector-analyze",
            &[
                "analyze", "--scheme", "loop", "--vertex", "boundary", "--faces", "4", "--rules",
                "blz",
            ],
        ),
        full(
            "full-sector-matrix-json",
            &[
                "matrix",
                "--scheme",
                "catmull-clark",
                "--vertex",
                "corner",
                "--faces",
                "2",
                "--angle",
                "90",
                "--rules",
                "blz",
                "--format",
                "json",
            ],
        ),
    ]);

    // ===================================================================
    // SECTION sector-sweeps: sweep specs with a [sector] table (boundary,
    // crease and corner configurations over K and the corner angle).
    // ===================================================================
    v.extend([
        bad_with(
            "sector-sweep-scheme-nurds",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"nurds\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "scheme: a [sector] sweep takes scheme catmull-clark or loop, got \"nurds\"",
        ),
        bad_with(
            "sector-sweep-unknown-scheme",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"midedge\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "scheme: a [sector] sweep takes scheme catmull-clark or loop, got \"midedge\"",
        ),
        bad_with(
            "sector-sweep-with-valences",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\nvalences = [3]\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "valences is not used by a [sector] sweep",
        ),
        bad_with(
            "sector-sweep-unknown-vertex",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"edge\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.vertex: unknown vertex kind \"edge\"",
        ),
        bad_with(
            "sector-sweep-unknown-rules",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"zorin\"\nfaces = [2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.rules: unknown rule set \"zorin\"",
        ),
        bad_with(
            "sector-sweep-missing-faces",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\n\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces: missing (required key)",
        ),
        bad_with(
            "sector-sweep-missing-vertex",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.vertex: missing (required key)",
        ),
        bad_with(
            "sector-sweep-missing-rules",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nfaces = [2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.rules: missing (required key)",
        ),
        bad_with(
            "sector-sweep-unknown-key",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = [2]\nangle = 90.0\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.angle: unknown field",
        ),
        bad_with(
            "sector-sweep-not-a-table",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\nsector = \"boundary\"\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector: invalid type",
        ),
        bad_with(
            "sector-sweep-faces-zero",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = [0, 2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces[0] must be a face count in 1..=4096, got 0",
        ),
        bad_with(
            "sector-sweep-faces-negative",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = { from = -2, to = 3 }\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces.from must be a face count in 1..=4096, got -2",
        ),
        bad_with(
            "sector-sweep-faces-huge",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = [5000]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces[0] must be a face count in 1..=4096, got 5000",
        ),
        bad_with(
            "sector-sweep-faces-float",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = [2.5]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces[0] must be an integer, got 2.5",
        ),
        bad_with(
            "sector-sweep-faces-empty",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = []\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces: empty list",
        ),
        bad_with(
            "sector-sweep-faces-twice",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = [2, 2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces: face count 2 is listed twice",
        ),
        bad_with(
            "sector-sweep-faces-empty-range",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = { from = 5, to = 2 }\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces: empty range, from = 5 > to = 2",
        ),
        bad_with(
            "sector-sweep-faces-range-unknown-key",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = { from = 1, upto = 2 }\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces.upto: unknown key (a face count range has `from` and `to`)",
        ),
        bad_with(
            "sector-sweep-faces-range-no-to",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = { from = 1 }\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces.to is missing",
        ),
        bad_with(
            "sector-sweep-faces-string",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"blz\"\nfaces = \"1..4\"\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector.faces must be a list [1, 2, 5] or a range { from = 1, to = 8 }, got \"1..4\"",
        ),
        bad_with(
            "sector-sweep-corner-uniform",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.kind: kind \"uniform\" with sector.vertex = \"corner\"",
        ),
        bad_with(
            "sector-sweep-boundary-corner-angle",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.kind: kind \"corner-angle\" with sector.vertex = \"boundary\"",
        ),
        bad_with(
            "sector-sweep-boundary-ratios",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.kind: kind \"ratios\" with sector.vertex = \"boundary\"",
        ),
        bad_with(
            "sector-sweep-unknown-space",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"angles\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.kind: unknown space \"angles\"",
        ),
        bad_with(
            "sector-sweep-angle-range-missing",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range is required by space kind \"corner-angle\"",
        ),
        bad_with(
            "sector-sweep-angle-zero",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [0.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range: bound 0.0 is outside the open interval (0, 360)",
        ),
        bad_with(
            "sector-sweep-angle-360",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 360.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range: bound 360.0 is outside the open interval (0, 360)",
        ),
        bad_with(
            "sector-sweep-angle-nan",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, nan]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range: bounds must be finite",
        ),
        bad_with(
            "sector-sweep-angle-reversed",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [90.0, 30.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range: lower bound 90.0 > upper bound 30.0",
        ),
        bad_with(
            "sector-sweep-angle-empty",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [90.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range: empty range",
        ),
        bad_with(
            "sector-sweep-angle-three-values",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 60.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range must be [lower, upper], got 3 values",
        ),
        bad_with(
            "sector-sweep-angle-not-numbers",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [\"a\", \"b\"]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range[0]: invalid type",
        ),
        bad_with(
            "sector-sweep-angle-with-ratio-range",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 90.0]\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.ratio_range is not used by space kind \"corner-angle\"",
        ),
        bad_with(
            "sector-sweep-boundary-angle-range",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\nangle_range = [30.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range is not used except by space kind \"corner-angle\"",
        ),
        bad_with(
            "sector-sweep-boundary-fixed",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\nfixed = { angle = 90.0 }\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.fixed is not used by space kind \"uniform\"",
        ),
        bad_with(
            "sector-sweep-fixed-angle-out-of-range",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 90.0]\nfixed = { angle = 400.0 }\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.fixed.angle must be a corner angle in degrees strictly between 0 and 360, got 400.0",
        ),
        bad_with(
            "sector-sweep-fixed-unknown-coordinate",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"corner\"\nrules = \"blz\"\nfaces = [2]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 90.0]\nfixed = { theta = 90.0 }\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.fixed.theta: unknown coordinate \"theta\" (coordinates of valence 2: angle)",
        ),
        bad_with(
            "sector-sweep-exact-certificate",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\nexact_certificate = true\n")],
            "columns.exact_certificate",
        ),
        bad_with(
            "sector-sweep-heavy",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"crease\"\nrules = \"blz\"\nfaces = [4096]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "for 1 configurations",
        ),
        bad_with(
            "sweep-corner-angle-without-sector",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\nvalences = [3]\n[space]\nkind = \"corner-angle\"\nangle_range = [30.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.kind: kind \"corner-angle\" sweeps corners: it needs a [sector] table",
        ),
        bad_with(
            "sweep-angle-range-without-sector",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\nvalences = [3]\n[space]\nkind = \"uniform\"\nangle_range = [30.0, 90.0]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "space.angle_range is not used except by space kind \"corner-angle\"",
        ),
        bad_with(
            "sweep-no-valences-no-sector",
            &["sweep", "s.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "valences: missing (required key)",
        ),
        bad_with(
            "sector-sweep-with-scheme-file",
            &["sweep", "s.toml", "--scheme-file", "{A}/schemes/catmull-clark.toml", "--out", "o.csv"],
            &[("s.toml", "name = \"s\"\nscheme = \"catmull-clark\"\n[sector]\nvertex = \"boundary\"\nrules = \"standard\"\nfaces = [1, 2, 3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n")],
            "sector: a [sector] sweep runs the boundary rules",
        ),
        bad_with(
            "report-sector-spectra-unknown-scheme",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nscheme = \"nurds\"\n")],
            "scheme must be \"catmull-clark\" or \"loop\", got \"nurds\"",
        ),
        bad_with(
            "report-sector-spectra-missing-scheme",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\n")],
            "figure[0].scheme: missing",
        ),
        bad_with(
            "report-sector-spectra-max-faces-1",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nscheme = \"loop\"\nmax_faces = 1\n")],
            "figure[0].max_faces: max_faces must be between 2 and 32, got 1",
        ),
        bad_with(
            "report-sector-spectra-max-faces-33",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nscheme = \"loop\"\nmax_faces = 33\n")],
            "figure[0].max_faces: max_faces must be between 2 and 32, got 33",
        ),
        bad_with(
            "report-sector-spectra-max-faces-negative",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nscheme = \"loop\"\nmax_faces = -3\n")],
            "figure[0].max_faces: invalid value: integer `-3`",
        ),
        bad_with(
            "report-sector-spectra-unknown-key",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"sector-spectra\"\nscheme = \"loop\"\nrules = \"blz\"\n")],
            "unknown field `rules`",
        ),
        bad_with(
            "report-crease-picture-unknown-mesh",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nmesh = \"cube\"\n")],
            "unknown tagged mesh \"cube\" (shipped: grid_quads, grid_tris)",
        ),
        bad_with(
            "report-crease-picture-levels-0",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nlevels = 0\n")],
            "figure[0].levels: levels must be between 1 and 4, got 0",
        ),
        bad_with(
            "report-crease-picture-levels-5",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nlevels = 5\n")],
            "figure[0].levels: levels must be between 1 and 4, got 5",
        ),
        bad_with(
            "report-crease-picture-levels-float",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nlevels = 2.5\n")],
            "figure[0].levels: invalid type: floating point `2.5`",
        ),
        bad_with(
            "report-crease-picture-mesh-not-a-string",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nmesh = 3\n")],
            "figure[0].mesh: invalid type: integer `3`",
        ),
        bad_with(
            "report-crease-picture-unknown-key",
            &["report", "s.toml", "--out", "r"],
            &[("s.toml", "name = \"t\"\n[[figure]]\nkind = \"crease-picture\"\nscheme = \"loop\"\n")],
            "unknown field `scheme`",
        ),
    ]);
    // (end of section sector-sweeps)

    v
}

/// Every regular file under `dir` with its contents.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("scratch dir readable") {
            let entry = entry.expect("dir entry");
            let p = entry.path();
            let ft = entry.file_type().expect("file type");
            if ft.is_dir() {
                out.insert(p.strip_prefix(dir).unwrap().join(""), Vec::new());
                stack.push(p);
            } else {
                out.insert(
                    p.strip_prefix(dir).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap_or_default(),
                );
            }
        }
    }
    out
}

fn substitute(arg: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    arg.replace("{M}", root.join("analysis/meshes").to_str().unwrap())
        .replace("{A}", root.join("analysis").to_str().unwrap())
}

/// Runs one row; returns a description of what went wrong, if anything.
fn check(case: &Case) -> Option<String> {
    let scratch = tempfile::tempdir().expect("tempdir");
    for (rel, contents) in case.files {
        let p = scratch.path().join(rel);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::fs::write(&p, contents).unwrap();
    }
    let before = snapshot(scratch.path());
    let args: Vec<String> = case.args.iter().map(|a| substitute(a)).collect();
    let stdout = match case.stdout {
        Stdout::Pipe => Stdio::piped(),
        Stdout::Full => Stdio::from(
            std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .expect("/dev/full"),
        ),
    };
    let mut child = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(&args)
        .current_dir(scratch.path())
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary starts");
    let start = Instant::now();
    // Read stderr on a thread so a chatty child cannot block on a full pipe.
    let mut err_pipe = child.stderr.take().unwrap();
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut err_pipe, &mut s).ok();
        s
    });
    let mut out_pipe = child.stdout.take();
    let out_reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        if let Some(p) = out_pipe.as_mut() {
            std::io::Read::read_to_end(p, &mut s).ok();
        }
        s
    });
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > TIME_LIMIT {
            child.kill().ok();
            child.wait().ok();
            return Some(format!("did not finish within {TIME_LIMIT:?}"));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let stderr = err_reader.join().unwrap();
    let _stdout = out_reader.join().unwrap();
    let mut problems = Vec::new();
    match status.code() {
        Some(c) if c == case.code => {}
        Some(c) => problems.push(format!("exit {c}, expected {}", case.code)),
        None => problems.push("killed by a signal".to_string()),
    }
    if stderr.contains("panicked") {
        problems.push("panicked".to_string());
    }
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    if lines.len() != 1 {
        problems.push(format!("{} stderr lines, expected 1", lines.len()));
    }
    if !stderr.contains(case.needle) {
        problems.push(format!("stderr does not name {:?}", case.needle));
    }
    let after = snapshot(scratch.path());
    if before != after {
        let added: Vec<_> = after.keys().filter(|k| !before.contains_key(*k)).collect();
        let removed: Vec<_> = before.keys().filter(|k| !after.contains_key(*k)).collect();
        let changed: Vec<_> = before
            .iter()
            .filter(|(k, v)| after.get(*k).is_some_and(|w| w != *v))
            .map(|(k, _)| k)
            .collect();
        problems.push(format!(
            "files touched: added {added:?}, removed {removed:?}, changed {changed:?}"
        ));
    }
    if problems.is_empty() {
        None
    } else {
        Some(format!(
            "{} | stderr: {}",
            problems.join("; "),
            stderr.trim()
        ))
    }
}

#[test]
fn hostile_input_table() {
    let cases = cases();
    let mut names = std::collections::HashSet::new();
    for c in &cases {
        assert!(names.insert(c.name), "duplicate row name {}", c.name);
    }
    // Rows are independent; run them on a few threads.
    let failures: Vec<String> = std::thread::scope(|s| {
        let chunks: Vec<&[Case]> = cases.chunks(cases.len().div_ceil(4).max(1)).collect();
        let handles: Vec<_> = chunks
            .into_iter()
            .map(|chunk| {
                s.spawn(move || {
                    chunk
                        .iter()
                        .filter_map(|c| check(c).map(|p| format!("{} ({:?}): {p}", c.name, c.args)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert!(
        failures.is_empty(),
        "{} of {} hostile-input rows failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// A build without the cargo feature `parquet` refuses every Parquet output
/// and input with one line naming the path and the feature (exit 2, nothing
/// created or changed). `.ci/run` runs it in that build:
/// `cargo test --release --no-default-features --features cli --test cli without_parquet`.
#[cfg(not(feature = "parquet"))]
#[test]
fn without_parquet_feature() {
    const SPEC: &[(&str, &str)] = &[("h.toml", MERGE_SPEC)];
    let cases = [
        bad_with(
            "sweep-parquet-without-feature",
            &["sweep", "h.toml", "--out", "o.parquet"],
            SPEC,
            "o.parquet: this subdiv-lab is built without Parquet (the cargo feature `parquet`)",
        ),
        bad_with(
            "sweep-format-parquet-resume-without-feature",
            &[
                "sweep",
                "h.toml",
                "--format",
                "parquet",
                "--out",
                "o.parquet",
                "--resume",
            ],
            &[
                ("h.toml", MERGE_SPEC),
                ("o.parquet/part-000000.parquet", "PAR1 a part"),
            ],
            "o.parquet: this subdiv-lab is built without Parquet",
        ),
        bad_with(
            "merge-parquet-without-feature",
            &[
                "merge",
                "--spec",
                "h.toml",
                "--out",
                "m.parquet",
                "a.parquet",
            ],
            &[
                ("h.toml", MERGE_SPEC),
                ("a.parquet/part-000000.parquet", "PAR1 a part"),
                ("a.summary.json", MERGE_A_SUMMARY),
            ],
            "a.parquet: this subdiv-lab is built without Parquet",
        ),
        bad_with(
            "plot-parquet-without-feature",
            &["plot", "s.parquet", "-o", "f.svg"],
            &[("s.parquet", "PAR1 rows PAR1")],
            "this subdiv-lab is built without Parquet",
        ),
    ];
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|c| check(c).map(|p| format!("{}: {p}", c.name)))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
