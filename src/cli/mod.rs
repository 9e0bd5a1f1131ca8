//! Command-line front end. Each subcommand lives in its own module: it parses,
//! validates through [`scheme_args`] (shared scheme/knot flags), calls the
//! library, and formats the result. No numerics here.

mod analyze;
mod budget;
mod cc_study;
mod ccss_bound;
mod error;
mod g2_cap;
mod matrix;
mod outfiles;
mod plot;
mod report;
mod scheme_args;
mod sector;
mod sector_args;
mod spectrum_text;
mod subdivide;
mod sweep;
mod verify;

use clap::{Parser, Subcommand};
pub(crate) use error::{write_stderr, write_stdout, CliError, CliResult};
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
    /// Refine a polygon mesh (OBJ, closed or open): NURDS, Doo-Sabin, the Catmull-Clark variant, Catmull-Clark, adjustable-cc or Loop (triangles).
    Subdivide(subdivide::SubdivideArgs),
    /// Run a report spec (default analysis/default.toml) and write reports/<name>/.
    Report(report::ReportArgs),
    /// Spectrum, subdominant classification and Theorem 1 for one configuration.
    Analyze(analyze::AnalyzeArgs),
    /// Run a parameter sweep from a TOML spec into a CSV or Parquet file (+ summary JSON).
    Sweep(sweep::SweepArgs),
    /// G2 cap of bidegree (7, 7) around an extraordinary vertex (seed 003): JSON, OBJ.
    G2Cap(g2_cap::G2CapArgs),
    /// Merge shard files (CSV or Parquet) of one sweep, checking no configuration is missing or duplicated.
    Merge(sweep::MergeArgs),
    /// Plot a sweep's results (class fractions, histogram, scatter or 2-D class map) or verify's cells.
    Plot(plot::PlotArgs),
    /// Prove class/separation verdicts over a box of ratios or an interval of c (cells.csv + summary.json).
    Verify(verify::VerifyArgs),
}

/// One line from clap's error text: the message and its details (e.g. the
/// missing arguments, a tip) without the usage block and the "For more
/// information" line, whitespace collapsed, followed by "(see --help)".
fn one_line_clap_error(e: &clap::Error) -> String {
    use clap::error::ErrorKind;
    if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        let names: Vec<String> = <Cli as clap::CommandFactory>::command()
            .get_subcommands()
            .filter(|c| !c.is_hide_set())
            .map(|c| c.get_name().to_owned())
            .collect();
        return format!(
            "error: no command given; one of: {} (see --help)",
            names.join(", ")
        );
    }
    let text = e.render().to_string();
    let mut parts: Vec<String> = Vec::new();
    let mut in_usage = false;
    for line in text.lines() {
        let t = line.trim();
        if t.is_empty() {
            in_usage = false;
            continue;
        }
        if t.starts_with("Usage:") {
            in_usage = true;
            continue;
        }
        if in_usage || t.starts_with("For more information") {
            continue;
        }
        parts.push(t.split_whitespace().collect::<Vec<_>>().join(" "));
    }
    if parts.is_empty() {
        parts.push("error: invalid arguments".to_owned());
    }
    format!("{} (see --help)", parts.join(" "))
}

/// Parses the command line, runs the command, maps errors to exit codes.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                // Help and version go to stdout, exit 0 (1 if stdout fails).
                return match write_stdout(e.render().to_string().as_bytes()) {
                    Ok(()) => ExitCode::SUCCESS,
                    Err(err) => report_error(&err),
                };
            }
            write_stderr(&one_line_clap_error(&e));
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
        Command::Plot(args) => plot::run(args),
        Command::Verify(args) => verify::run(args),
        Command::G2Cap(args) => g2_cap::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => report_error(&e),
    }
}

/// Prints the one-line message of `e` and returns its exit code.
fn report_error(e: &CliError) -> ExitCode {
    let (err, code) = match e {
        CliError::Usage(e) => (e, EXIT_USAGE),
        CliError::Failure(e) => (e, EXIT_FAILURE),
    };
    // `{:#}` joins the context chain with ": "; a message with line breaks
    // (e.g. from a dependency) is folded onto one line.
    let text = format!("{err:#}");
    let line: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    write_stderr(&format!("error: {}", line.join(" ")));
    ExitCode::from(code)
}
