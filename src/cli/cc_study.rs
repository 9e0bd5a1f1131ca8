//! `subdiv-lab cc-study`: the shape-adjustable Catmull-Clark parameter study
//! (subdominant eigenvalues, `|lambda_3|`, class and characteristic-map
//! verdict against `c`; certified C1 or certified-standard intervals of `c`
//! per valence by bisection). CSV on standard output.

use super::{CliError, CliResult};
use clap::Args;
use std::io::Write as _;
use subdiv_lab::cc_study::{csv_cell, intervals, study_curve_rows, Criterion};

#[derive(Args, Debug)]
pub(crate) struct CcStudyArgs {
    /// Smallest valence (3 <= --n-min <= --n-max).
    #[arg(long, default_value_t = 3)]
    n_min: usize,
    /// Largest valence (at most 256).
    #[arg(long, default_value_t = 32)]
    n_max: usize,
    /// Grid cells in c (samples + 1 values in [0, 1]); 1 to 100000.
    #[arg(long, default_value_t = 100)]
    samples: usize,
    /// Bisection width for the interval ends: at least 2^-52 (2.2e-16, what
    /// f64 resolves in [0, 1]) and below 1.
    #[arg(long, default_value_t = 1e-6)]
    tol: f64,
    /// Print the curves (one row per (n, c)) instead of the intervals.
    #[arg(long)]
    curves: bool,
    /// What the intervals certify: `c1` (standard, characteristic map regular
    /// and injective) or `standard` (the spectral part only).
    #[arg(long, value_enum, default_value_t = CriterionArg::C1)]
    criterion: CriterionArg,
    /// Run even when the estimated time or memory exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum CriterionArg {
    C1,
    Standard,
}

pub(crate) fn run(args: CcStudyArgs) -> CliResult {
    subdiv_lab::cc_study::check_study(
        args.n_min,
        args.n_max,
        args.samples,
        args.tol,
        subdiv_lab::budget::Spelling::Cli,
    )
    .map_err(super::budget::usage)?;
    super::budget::check(
        "cc-study",
        &format!("valences {}..{}", args.n_min, args.n_max),
        &subdiv_lab::budget::cc_study(args.n_min, args.n_max, args.samples, args.curves),
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )?;
    // Rows are written as they are computed (the intervals take a while per
    // valence); a write error on stdout is a failure (exit 1), not a panic.
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    if args.curves {
        // A point whose computation fails becomes a row with class and
        // charmap "error" and the message in the last column; the run goes on.
        writeln!(
            out,
            "n,c,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,class,fourier_subdominant,charmap,error"
        )
        .map_err(CliError::stdout)?;
        for n in args.n_min..=args.n_max {
            for (c, row) in study_curve_rows(n, args.samples) {
                match row {
                    Ok(p) => writeln!(
                        out,
                        "{},{},{:e},{:e},{:e},{:e},{:e},{},{:e},{},",
                        n,
                        p.c,
                        p.lambda1[0],
                        p.lambda1[1],
                        p.lambda2[0],
                        p.lambda2[1],
                        p.abs_lambda3,
                        p.class,
                        p.fourier_subdominant,
                        p.charmap
                    ),
                    Err(e) => writeln!(
                        out,
                        "{n},{c},,,,,,error,,error,{}",
                        csv_cell(&e.to_string())
                    ),
                }
                .map_err(CliError::stdout)?;
            }
        }
    } else {
        let criterion = match args.criterion {
            CriterionArg::C1 => Criterion::C1,
            CriterionArg::Standard => Criterion::Standard,
        };
        writeln!(
            out,
            "n,interval,c_lo,c_hi,c_lo_outside,c_hi_outside,below,above"
        )
        .map_err(CliError::stdout)?;
        for n in args.n_min..=args.n_max {
            let iv = intervals(n, args.samples, args.tol, criterion).map_err(CliError::lib)?;
            for (k, i) in iv.iter().enumerate() {
                writeln!(
                    out,
                    "{n},{k},{:.9e},{:.9e},{:.9e},{:.9e},{},{}",
                    i.lo, i.hi, i.lo_outside, i.hi_outside, i.below, i.above
                )
                .map_err(CliError::stdout)?;
            }
            // One valence at a time reaches the reader (a long study shows progress).
            out.flush().map_err(CliError::stdout)?;
        }
    }
    out.flush().map_err(CliError::stdout)?;
    Ok(())
}
