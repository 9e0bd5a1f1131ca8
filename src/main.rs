//! The `subdiv-lab` command-line tool: a thin layer over the `subdiv_lab` library.
//!
//! Arguments are parsed (clap), validated into library types, and handed to the
//! library; errors become a one-line message on stderr and a non-zero exit code.

mod cli;

fn main() -> std::process::ExitCode {
    // Rust ignores SIGPIPE, so writing to a closed pipe (`subdiv-lab ... | head`)
    // would make `print!` panic; restore the default action, under which the
    // process ends quietly as Unix tools do.
    #[cfg(unix)]
    // SAFETY: called once at start-up before any thread exists; it only
    // changes the disposition of SIGPIPE back to the system default.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    cli::main()
}
