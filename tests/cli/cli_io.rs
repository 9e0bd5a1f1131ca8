//! Standard-output behaviour of the binary: a reader that closes the pipe
//! early (`subdiv-lab ... | head`) ends the run quietly (the default SIGPIPE
//! action, no message, no panic). Write errors (`/dev/full`) are rows of the
//! hostile-input table.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

#[cfg(unix)]
#[test]
fn closed_pipe_ends_quietly() {
    use std::os::unix::process::ExitStatusExt as _;
    // About 0.5 MB of CSV: more than a pipe buffer, so the writer is still
    // writing when the reader goes away.
    let mut child = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args([
            "cc-study",
            "--curves",
            "--n-min",
            "3",
            "--n-max",
            "40",
            "--samples",
            "100",
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("n,c,"), "{first:?}");
    // The reader (and the pipe) are dropped here.
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.is_empty(), "quiet: {stderr:?}");
    assert!(
        out.status.signal() == Some(libc_sigpipe()) || out.status.success(),
        "ended by SIGPIPE (or finished): {:?}",
        out.status
    );
}

/// SIGPIPE's number on the Unix systems we run on.
#[cfg(unix)]
fn libc_sigpipe() -> i32 {
    13
}

/// An output path that is a special file (a device such as `/dev/null`,
/// here a FIFO in a scratch directory, so that a failure cannot harm the
/// machine) is written in place, never replaced by a rename (which would
/// replace the device node with a regular file when run as root). `sweep --out` and `merge --out` refuse
/// it (their CSV is resumable and has a summary beside it).
#[cfg(target_os = "linux")]
#[test]
fn special_output_files_are_written_in_place_never_replaced() {
    use std::io::Read as _;
    use std::os::unix::fs::{FileTypeExt as _, OpenOptionsExt as _};
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("out.obj");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    // A non-blocking reader, so that the writer's open succeeds at once and
    // (the output being far below a pipe buffer) its writes do not block.
    let mut reader = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(&fifo)
        .unwrap();
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/meshes/cube.obj");
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
        .args(["subdivide", cube, "--scheme", "nurds", "-o"])
        .arg(&fifo)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "the FIFO was replaced by {kind:?}");
    let mut text = String::new();
    reader.read_to_string(&mut text).unwrap();
    assert!(text.contains("\nf "), "the mesh went through the FIFO");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 1, "no temporary left beside it");
    // sweep and merge refuse it, naming it, and leave it alone.
    let spec = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/sweep-n3-grid.toml");
    for args in [
        vec!["sweep", spec, "--limit", "3", "--out"],
        vec!["merge", "--spec", spec, "x.csv", "--out"],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_subdiv-lab"))
            .args(&args)
            .arg(&fifo)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("is not a regular file"), "{args:?}: {err}");
        assert!(std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo());
    }
}
