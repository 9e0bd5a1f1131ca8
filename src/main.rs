//! The `subdiv-lab` command-line tool: a thin layer over the `subdiv_lab` library.
//!
//! Arguments are parsed (clap), validated into library types, and handed to the
//! library; errors become a one-line message on stderr and a non-zero exit code.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
