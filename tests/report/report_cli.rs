//! End-to-end tests of `subdiv-lab report`: files written, PNGs decode with the
//! stated size, SVGs parse, index.html links resolve, bad specs fail with the
//! line and key and leave no output directory.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

const SMALL_SPEC: &str = r#"
name = "small"
title = "Small test report"
seed = 7

[[figure]]
kind = "spectrum"
id = "spec"
width = 900
height = 600
configs = [
  { scheme = "cc-variant", valence = 5 },
  { scheme = "nurds", ratios = [0.3, 0.6, 0.5] },
]

[[figure]]
kind = "subdominant-vs-valence"
id = "valence"
width = 800
height = 500
valence = [3, 9]
samples = 3

[[figure]]
kind = "convergence"
id = "conv"
width = 820
height = 520
steps = 12
configs = [{ scheme = "nurds", valence = 4, random_knots = 3.0 }]

[[figure]]
kind = "knot-map"
id = "map"
width = 1000
height = 450
slices = [[0.3], [0.7]]
grid = 9
color_by = "modulus-ratio"

[[figure]]
kind = "table"
id = "tab"
configs = [{ scheme = "doo-sabin", valence = 3 }]
"#;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
}

fn write_spec(dir: &Path, text: &str) -> PathBuf {
    let p = dir.join("spec.toml");
    std::fs::write(&p, text).unwrap();
    p
}

fn run_report(spec: &Path, out: &Path) -> std::process::Output {
    bin()
        .args([
            "report",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap()
}

/// Local files referenced by href/src attributes in index.html.
fn referenced(html: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for attr in ["href=\"", "src=\""] {
        let mut rest = html;
        while let Some(i) = rest.find(attr) {
            rest = &rest[i + attr.len()..];
            let end = rest.find('"').unwrap();
            let target = &rest[..end];
            if !target.starts_with('#') {
                out.insert(target.to_owned());
            }
            rest = &rest[end..];
        }
    }
    out
}

#[test]
fn small_spec_writes_complete_report() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = write_spec(tmp.path(), SMALL_SPEC);
    let out = tmp.path().join("out");
    let o = run_report(&spec, &out);
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        o.stdout.is_empty() && o.stderr.is_empty(),
        "--quiet prints nothing"
    );

    let files: BTreeSet<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let expected: BTreeSet<String> = [
        "index.html",
        "manifest.json",
        "spec.svg",
        "spec.png",
        "spec.csv",
        "valence.svg",
        "valence.png",
        "valence.csv",
        "valence-samples.csv",
        "conv.svg",
        "conv.png",
        "conv.csv",
        "map.svg",
        "map.png",
        "map.csv",
        "tab.csv",
        "tab-eigenvalues.csv",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    assert_eq!(files, expected);
    // No temporary directories left next to the output.
    let siblings: Vec<String> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(siblings.len(), 2, "{siblings:?}");

    // Every PNG decodes with the size the manifest states.
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["name"], "small");
    assert_eq!(manifest["seed"], 7);
    assert_eq!(manifest["spec"], SMALL_SPEC);
    let figs = manifest["figures"].as_array().unwrap();
    assert_eq!(figs.len(), 5);
    let mut pngs = 0;
    for f in figs {
        assert!(f["seed"].is_u64());
        assert!(f["compute_seconds"].as_f64().unwrap() >= 0.0);
        let Some(png) = f["png"].as_str() else {
            assert_eq!(f["kind"], "table");
            continue;
        };
        let (w, h) = (
            f["size"][0].as_u64().unwrap(),
            f["size"][1].as_u64().unwrap(),
        );
        let decoder = png::Decoder::new(std::fs::File::open(out.join(png)).unwrap());
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width as u64, info.height as u64), (w, h), "{png}");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        // Not blank: some dark pixels (text, axes) and mostly white background.
        let px = &buf[..info.buffer_size()];
        let dark = px.chunks(3).filter(|c| c.iter().all(|&v| v < 80)).count();
        assert!(dark > 500, "{png}: only {dark} dark pixels");
        pngs += 1;

        // The SVG parses as XML and has the stated size.
        let svg_name = f["svg"].as_str().unwrap();
        let svg = std::fs::read_to_string(out.join(svg_name)).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{svg_name}: {e}"));
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        assert_eq!(root.attribute("width").unwrap(), w.to_string());
        assert_eq!(root.attribute("height").unwrap(), h.to_string());
        assert!(
            doc.descendants().any(|n| n.tag_name().name() == "text"),
            "{svg_name} has no text"
        );
    }
    assert_eq!(pngs, 4);

    // index.html references every figure and CSV, and nothing that is missing.
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let refs = referenced(&html);
    for f in &files {
        if f != "index.html" {
            assert!(refs.contains(f), "index.html does not reference {f}");
        }
    }
    for r in &refs {
        assert!(files.contains(r), "index.html references missing {r}");
    }
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "no network references"
    );
    assert!(
        html.contains("<table>"),
        "the table figure adds an HTML table"
    );
}

const TINY_SPEC: &str = "name = \"t\"\n[[figure]]\nkind = \"table\"\nid = \"a\"\nconfigs = [{ scheme = \"cc-variant\", valence = 4 }]\n";

/// Every file under `dir` (relative path -> contents).
fn tree(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut out = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.insert(
                    p.strip_prefix(dir).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    out
}

fn run_in(cwd: &Path, args: &[&str]) -> std::process::Output {
    bin().args(args).current_dir(cwd).output().unwrap()
}

fn stderr_line(o: &std::process::Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(err.trim().lines().count(), 1, "one stderr line: {err:?}");
    err
}

/// `--out` naming a directory with the user's files (the
/// spec among them) is refused with exit 2 and nothing is touched.
#[test]
fn out_dir_with_foreign_files_is_refused_and_untouched() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("d");
    std::fs::create_dir(&d).unwrap();
    std::fs::write(d.join("keep.txt"), "x\n").unwrap();
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/default.toml"),
        d.join("s.toml"),
    )
    .unwrap();
    let before = tree(tmp.path());
    let o = run_in(tmp.path(), &["report", "d/s.toml", "--out", "d", "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr_line(&o);
    assert!(
        err.contains("--out d") && err.contains("not empty"),
        "{err}"
    );
    assert_eq!(tree(tmp.path()), before, "files touched");
}

/// `--out` naming an existing regular file is exit 2, the file untouched.
#[test]
fn out_naming_a_file_is_refused_and_untouched() {
    let tmp = tempfile::tempdir().unwrap();
    write_spec(tmp.path(), TINY_SPEC);
    std::fs::write(tmp.path().join("f"), "user data\n").unwrap();
    let before = tree(tmp.path());
    let o = run_in(
        tmp.path(),
        &["report", "spec.toml", "--out", "f", "--quiet"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr_line(&o).contains("not a directory"));
    assert_eq!(tree(tmp.path()), before, "files touched");
}

/// A previous report is replaced by default (so the main job can be
/// run again), touching only the files its manifest lists: the user's files
/// in the directory survive, stale outputs of the old report are removed, no
/// temporaries remain.
#[test]
fn rerun_replaces_only_the_previous_reports_files() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = write_spec(tmp.path(), TINY_SPEC);
    let out = tmp.path().join("out");
    // An existing empty directory is filled.
    std::fs::create_dir(&out).unwrap();
    let o = run_report(&spec, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("a.csv").exists());
    std::fs::write(out.join("notes.txt"), "mine").unwrap();

    // The same spec again: the report is rewritten, notes.txt stays.
    let o = run_report(&spec, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );

    // A spec whose figure has another id: a.csv (listed by the old manifest)
    // goes, b.csv comes, notes.txt stays.
    let spec2 = tmp.path().join("spec2.toml");
    std::fs::write(&spec2, TINY_SPEC.replace("id = \"a\"", "id = \"b\"")).unwrap();
    let o = bin()
        .args([
            "report",
            spec2.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let names: BTreeSet<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let expected: BTreeSet<String> = [
        "b.csv",
        "b-eigenvalues.csv",
        "index.html",
        "manifest.json",
        "notes.txt",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    assert_eq!(names, expected);
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("manifest.json")).unwrap()).unwrap();
    let listed: BTreeSet<&str> = manifest["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(
        listed,
        ["b.csv", "b-eigenvalues.csv", "index.html", "manifest.json"]
            .into_iter()
            .collect()
    );
    // No temporaries beside or inside the output.
    let siblings = std::fs::read_dir(tmp.path()).unwrap().count();
    assert_eq!(siblings, 3, "spec.toml, spec2.toml, out");

    // A user's file with the name of a new output is never overwritten:
    // exit 2, nothing touched.
    std::fs::write(out.join("a.csv"), "user's a.csv").unwrap();
    let before = tree(tmp.path());
    let o = bin()
        .args([
            "report",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr_line(&o).contains("a.csv"));
    assert_eq!(tree(tmp.path()), before);
}

/// The manifest is not trusted blindly. A user file added
/// to an edited manifest's list is never removed, a report file the user
/// edited is never overwritten (exit 2, naming it, nothing touched), and a
/// manifest without digests (an older version, or edited) owns no file.
#[test]
fn rerun_never_touches_files_the_manifest_does_not_vouch_for() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = write_spec(tmp.path(), TINY_SPEC);
    let out = tmp.path().join("out");
    let o = run_report(&spec, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let manifest_path = out.join("manifest.json");
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut m: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&manifest_path).unwrap()).unwrap();
        f(&mut m);
        std::fs::write(&manifest_path, serde_json::to_vec(&m).unwrap()).unwrap();
    };
    // 1. A user file added to the list (with or without a made-up digest):
    //    the rerun succeeds and the file stays.
    std::fs::write(out.join("precious.txt"), "mine").unwrap();
    edit(&|m| {
        m["files"]
            .as_array_mut()
            .unwrap()
            .push("precious.txt".into());
        m["digests"]["precious.txt"] = "0000000000000000".into();
    });
    let o = run_report(&spec, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(out.join("precious.txt")).unwrap(),
        "mine"
    );
    // 2. A report file the user edited: refused by name, nothing touched.
    std::fs::write(out.join("a.csv"), "my annotated copy").unwrap();
    let before = tree(tmp.path());
    let o = run_report(&spec, &out);
    assert_eq!(o.status.code(), Some(2));
    let line = stderr_line(&o);
    assert!(line.contains("a.csv") && line.contains("changed"), "{line}");
    assert_eq!(tree(tmp.path()), before);
    // 3. A manifest without digests owns nothing: index.html is refused.
    std::fs::remove_file(out.join("a.csv")).unwrap();
    edit(&|m| {
        m.as_object_mut().unwrap().remove("digests");
    });
    let before = tree(tmp.path());
    let o = run_report(&spec, &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr_line(&o).contains("index.html"));
    assert_eq!(tree(tmp.path()), before);
}

/// A report whose closing line cannot be written (stdout
/// is /dev/full) exits 1 and installs nothing: no new directory, and an
/// existing report is left as it was.
#[test]
fn report_with_a_failing_stdout_installs_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = write_spec(tmp.path(), TINY_SPEC);
    let out = tmp.path().join("out");
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let before = tree(tmp.path());
    let o = bin()
        .args([
            "report",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .stdout(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr_line(&o).contains("stdout"));
    assert_eq!(tree(tmp.path()), before, "a new report was installed");
    // Into a previous report: it stays as it was.
    let o = run_report(&spec, &out);
    assert!(o.status.success());
    let before = tree(tmp.path());
    let o = bin()
        .args([
            "report",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .stdout(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(tree(tmp.path()), before, "the previous report was replaced");
}

/// The default report works from any directory (the spec is built
/// into the binary; its meshes are generated in code) and records the
/// version and the build-time git revision.
#[test]
fn default_report_runs_from_another_directory() {
    let tmp = tempfile::tempdir().unwrap();
    let o = run_in(tmp.path(), &["report", "--out", "r", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(tmp.path().join("r/manifest.json")).unwrap())
            .unwrap();
    assert_eq!(manifest["name"], "default");
    assert_eq!(manifest["spec_builtin"], true);
    assert_eq!(manifest["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(
        manifest["spec"].as_str().unwrap(),
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/analysis/default.toml"
        ))
        .unwrap()
    );
    // Built from a git checkout (as the tests are), the revision is known.
    let head = Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned());
    if let Some(head) = head {
        let rev = manifest["git_revision"].as_str().unwrap_or("null");
        assert!(
            rev.starts_with(&head),
            "manifest revision {rev}, HEAD {head}"
        );
    }
    let html = std::fs::read_to_string(tmp.path().join("r/index.html")).unwrap();
    assert!(
        html.contains("built in"),
        "index.html names the built-in spec"
    );
    let files = manifest["files"].as_array().unwrap();
    assert_eq!(
        files.len(),
        std::fs::read_dir(tmp.path().join("r")).unwrap().count()
    );
    // The default report is at most 8 MB, and no data file is
    // written twice (the three knot maps of one grid share one CSV, named by
    // each figure's record).
    let mut total = 0u64;
    let mut csvs: Vec<Vec<u8>> = Vec::new();
    for f in files {
        let name = f.as_str().unwrap();
        let bytes = std::fs::read(tmp.path().join("r").join(name)).unwrap();
        total += bytes.len() as u64;
        if name.ends_with(".csv") {
            assert!(!csvs.contains(&bytes), "{name} repeats another CSV");
            csvs.push(bytes);
        }
    }
    assert!(total <= 8 << 20, "the default report has {total} bytes");
    for fig in manifest["figures"].as_array().unwrap() {
        for c in fig["csv"].as_array().unwrap() {
            assert!(
                files.contains(c),
                "{} names {c}, not a report file",
                fig["id"]
            );
        }
    }
    let angle = manifest["figures"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "knot-map-angle")
        .unwrap();
    assert_eq!(angle["csv"], serde_json::json!(["knot-map-class.csv"]));
}

/// (spec text, substrings the error must contain).
fn bad_specs() -> Vec<(&'static str, String, Vec<&'static str>)> {
    let head = "name = \"bad\"\n[[figure]]\n";
    vec![
        (
            "unknown scheme",
            format!("{head}kind = \"spectrum\"\nconfigs = [\n  {{ scheme = \"midedge\", valence = 5 }},\n]\n"),
            vec!["line 5", "configs[0].scheme", "unknown scheme \"midedge\""],
        ),
        (
            "bad knots",
            format!("{head}kind = \"convergence\"\nconfigs = [{{ scheme = \"nurds\", knots = [[1, 2], [0, 1], [1, 1]] }}]\n"),
            vec!["line 4", "configs[0].knots", "p_1", "> 0"],
        ),
        (
            "bad ratios",
            format!("{head}kind = \"table\"\n\nconfigs = [{{ scheme = \"nurds\", ratios = [0.3, 1.5, 0.5] }}]\n"),
            vec!["line 5", "configs[0].ratios", "r_1", "1.5"],
        ),
        (
            "unknown figure kind",
            format!("{head}id = \"x\"\nkind = \"histogram\"\n"),
            vec!["line 4", "figure[0].kind", "unknown figure kind \"histogram\"", "spectrum"],
        ),
        (
            "unknown key in a figure",
            format!("{head}kind = \"knot-map\"\nslices = [[0.5]]\ncolour_by = \"class\"\n"),
            vec!["line 5", "figure[0]", "colour_by"],
        ),
        (
            "unknown key in a configuration",
            format!("{head}kind = \"spectrum\"\nconfigs = [{{ scheme = \"nurds\", valence = 3, ratio = [0.5] }}]\n"),
            vec!["line 4", "ratio"],
        ),
        (
            "unknown top-level key",
            "name = \"bad\"\ntitel = \"typo\"\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"nurds\", valence = 3 }]\n".to_owned(),
            vec!["line 2", "titel"],
        ),
        (
            "TOML syntax error",
            format!("{head}kind = \"table\"\nconfigs = [{{ scheme = \"nurds\" valence = 3 }}]\n"),
            vec!["line 4"],
        ),
    ]
}

#[test]
fn bad_specs_fail_with_line_and_key_and_leave_no_output() {
    for (what, text, needles) in bad_specs() {
        let tmp = tempfile::tempdir().unwrap();
        let spec = write_spec(tmp.path(), &text);
        let out = tmp.path().join("out");
        let o = run_report(&spec, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{what}: exit code, stderr {err}");
        for n in &needles {
            assert!(err.contains(n), "{what}: {n:?} missing from {err:?}");
        }
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{what}: one-line message: {err:?}"
        );
        assert!(!out.exists(), "{what}: output directory was created");
        let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().collect();
        assert_eq!(left.len(), 1, "{what}: only the spec remains");
    }
}

#[test]
fn missing_spec_file_is_a_usage_error() {
    let tmp = tempfile::tempdir().unwrap();
    let o = run_report(&tmp.path().join("nope.toml"), &tmp.path().join("out"));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nope.toml"));
    assert!(!tmp.path().join("out").exists());
}

#[test]
fn default_spec_parses() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/analysis/default.toml"
    ))
    .unwrap();
    let spec = subdiv_lab::report::ReportSpec::parse(&text).unwrap();
    assert_eq!(spec.name, "default");
    let kinds: BTreeSet<&str> = spec.figures.iter().map(|f| f.common.kind).collect();
    // `sweep` draws a user's sweep CSV (a file path): the default report is
    // embedded in the binary and runs from any directory, so it cannot carry
    // one; tests/report/figure_layout.rs renders that kind from its own sample.
    const DRAWS_A_USER_FILE: &[&str] = &["sweep"];
    for k in subdiv_lab::report::figures::REGISTRY {
        if DRAWS_A_USER_FILE.contains(&k.name) {
            assert!(
                !kinds.contains(k.name),
                "the default report must not read user files"
            );
            continue;
        }
        assert!(kinds.contains(k.name), "default report lacks {}", k.name);
    }
}
