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
