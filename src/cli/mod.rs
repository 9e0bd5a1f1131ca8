//! Command-line front end. Each subcommand lives in its own module: it parses,
//! validates through [`scheme_args`] (shared scheme/knot flags), calls the
//! library, and formats the result. No numerics here.

mod analyze;
mod budget;
mod cc_study;
mod ccss_bound;
mod matrix;
mod report;
mod scheme_args;
mod subdivide;
mod sweep;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Exit code for invalid input (bad flags, bad values, bad files).
const EXIT_USAGE: u8 = 2;
/// Exit code for failures while running valid input (numerical failure, I/O).
const EXIT_FAILURE: u8 = 1;

#[derive(Parser, Debug)]
#[command(
    name = "subdiv-lab",
    version,
    about = "Numerical analysis and verification of subdivision surfaces"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print a local subdivision matrix (S_n or its face block).
    Matrix(matrix::MatrixArgs),
    /// Distance bound beta(n) between a Catmull-Clark patch and its limit face (LP).
    CcssBound(ccss_bound::CcssBoundArgs),
    /// Adjustable Catmull-Clark parameter study: eigenvalues and class against c (CSV).
    CcStudy(cc_study::CcStudyArgs),
    /// Refine a closed polygon mesh (OBJ) with NURDS, Doo-Sabin or the Catmull-Clark variant.
    Subdivide(subdivide::SubdivideArgs),
    /// Run a report spec (default analysis/default.toml) and write reports/<name>/.
    Report(report::ReportArgs),
    /// Spectrum, subdominant classification and Theorem 1 for one configuration.
    Analyze(analyze::AnalyzeArgs),
    /// Run a parameter sweep from a TOML spec into a CSV (+ summary JSON).
    Sweep(sweep::SweepArgs),
    /// Merge shard CSVs of one sweep, checking no configuration is missing or duplicated.
    Merge(sweep::MergeArgs),
}

/// An error with the exit code it maps to.
#[derive(Debug)]
pub(crate) enum CliError {
    /// The input is invalid: exit code 2.
    Usage(anyhow::Error),
    /// Valid input, failure while running: exit code 1.
    Failure(anyhow::Error),
}

impl CliError {
    pub(crate) fn usage(e: impl Into<anyhow::Error>) -> Self {
        CliError::Usage(e.into())
    }
    pub(crate) fn failure(e: impl Into<anyhow::Error>) -> Self {
        CliError::Failure(e.into())
    }
}

pub(crate) type CliResult<T = ()> = Result<T, CliError>;

/// Parses the command line, runs the command, maps errors to exit codes.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                print!("{e}");
                return ExitCode::SUCCESS;
            }
            // One line: clap's first line names the problem.
            let text = e.render().to_string();
            let first = text
                .lines()
                .find(|l| !l.trim().is_empty())
                .unwrap_or("invalid arguments");
            eprintln!("{} (see --help)", first.trim_end());
            return ExitCode::from(EXIT_USAGE);
        }
    };
    let result = match cli.command {
        Command::Matrix(args) => matrix::run(args),
        Command::CcssBound(args) => ccss_bound::run(args),
        Command::CcStudy(args) => cc_study::run(args),
        Command::Subdivide(args) => subdivide::run(args),
        Command::Report(args) => report::run(args),
        Command::Analyze(args) => analyze::run(args),
        Command::Sweep(args) => sweep::run_sweep(args),
        Command::Merge(args) => sweep::run_merge(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Usage(e)) => {
            eprintln!("error: {e:#}");
            ExitCode::from(EXIT_USAGE)
        }
        Err(CliError::Failure(e)) => {
            eprintln!("error: {e:#}");
            ExitCode::from(EXIT_FAILURE)
        }
    }
}
