//! `subdiv-lab ccss-bound`: the distance bound beta(n) between an
//! extraordinary Catmull-Clark patch and its limit face.

use super::{write_stdout, CliError, CliResult};
use anyhow::anyhow;
use clap::Args;
use std::fmt::Write as _;
use subdiv_lab::budget::Spelling;
use subdiv_lab::ccss_bound::bound::{beta_table, write_beta_csv, DEFAULT_LEVELS};
use subdiv_lab::ccss_bound::summary::{check_levels, check_table_to, BoundSummary};

#[derive(Args, Debug)]
pub(crate) struct CcssBoundArgs {
    /// Valence n >= 3 of the extraordinary vertex.
    #[arg(long, required_unless_present = "table_to")]
    valence: Option<usize>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Number of levels k = 1..K of sub-patches Omega^k_m examined.
    #[arg(long, default_value_t = DEFAULT_LEVELS)]
    levels: u32,
    /// Print the CSV table of beta(n) for n = 3..N instead (N >= 3).
    #[arg(long, value_name = "N", conflicts_with = "valence")]
    table_to: Option<usize>,
    /// A control net (2n+8 points, one per line, coordinates separated by
    /// spaces or commas, '#' comments; numbering as in the docs of
    /// `schemes::catmull_clark::PatchLayout`): also print the number of
    /// subdivision steps needed for --epsilon.
    #[arg(long, value_name = "PATH", requires = "epsilon")]
    net: Option<std::path::PathBuf>,
    /// Tolerance for --net.
    #[arg(long, requires = "net", allow_hyphen_values = true)]
    epsilon: Option<f64>,
    /// Run even when the estimated memory or time exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
}

/// Reads a control net: one point per line.
fn read_net(path: &std::path::Path) -> CliResult<Vec<Vec<f64>>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::usage(anyhow!("cannot read {}: {e}", path.display())))?;
    let mut net = Vec::new();
    for (lineno, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let point = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .map(|s| {
                s.parse::<f64>().map_err(|_| {
                    CliError::usage(anyhow!(
                        "{}:{}: {s:?} is not a number",
                        path.display(),
                        lineno + 1
                    ))
                })
            })
            .collect::<CliResult<Vec<f64>>>()?;
        if let Some(first) = net.first() {
            let first: &Vec<f64> = first;
            if first.len() != point.len() {
                return Err(CliError::usage(anyhow!(
                    "{}:{}: {} coordinates, expected {}",
                    path.display(),
                    lineno + 1,
                    point.len(),
                    first.len()
                )));
            }
        }
        net.push(point);
    }
    Ok(net)
}

pub(crate) fn run(args: CcssBoundArgs) -> CliResult {
    check_levels(args.levels, Spelling::Cli).map_err(super::budget::usage)?;
    if let Some(max) = args.table_to {
        check_table_to(max, Spelling::Cli).map_err(super::budget::usage)?;
        super::budget::check(
            "ccss-bound",
            &format!("--table-to {max}"),
            &subdiv_lab::budget::ccss_table(max, args.levels),
            subdiv_lab::budget::TIME_LIMIT_SECONDS,
            args.force,
        )?;
        let rows = beta_table(3..=max, args.levels).map_err(CliError::lib)?;
        let mut out = Vec::new();
        write_beta_csv(&rows, &mut out).map_err(CliError::failure)?;
        return write_stdout(&out);
    }
    let n = args
        .valence
        .ok_or_else(|| CliError::usage(anyhow!("--valence is required")))?;
    if n < 3 {
        return Err(CliError::usage(anyhow!(
            "valence must be at least 3, got {n}"
        )));
    }
    super::budget::check(
        "ccss-bound",
        &format!("valence {n}"),
        &subdiv_lab::budget::ccss_bound(n, args.levels),
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )?;
    let net = match (&args.net, args.epsilon) {
        (Some(path), Some(eps)) => Some((read_net(path)?, eps)),
        _ => None,
    };
    let summary = BoundSummary::compute(
        n,
        args.levels,
        net.as_ref().map(|(points, eps)| (points.as_slice(), *eps)),
    )
    .map_err(CliError::lib)?;
    let (r, c12, rate, steps) = (
        &summary.report,
        summary.c_omega_1_2,
        &summary.contraction,
        &summary.steps,
    );
    if args.json {
        let doc = summary.to_json();
        let text = serde_json::to_string_pretty(&doc).map_err(CliError::failure)? + "\n";
        write_stdout(text.as_bytes())
    } else {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "valence n = {n}: {} second-order differences",
            r.family_size
        );
        let _ = writeln!(
            s,
            "beta(n) = {:.9}  at t = {:.6} (sub-patch Omega^{}_2)",
            r.beta, r.t_max, r.level_of_max
        );
        let _ = writeln!(
            s,
            "max of B over all sub-patches (sampled) = {:.9} on Omega^{}_{}",
            r.full_max,
            r.full_max_domain.level,
            r.full_max_domain.part.index()
        );
        let _ = writeln!(s, "c_ij on Omega^1_2 (i along u):");
        for row in c12 {
            let _ = writeln!(
                s,
                "  {}",
                row.iter()
                    .map(|x| format!("{x:.9}"))
                    .collect::<Vec<_>>()
                    .join("  ")
            );
        }
        let _ = writeln!(
            s,
            "per-level max D on Omega^k_2: {}",
            r.level_maxima
                .iter()
                .map(|x| format!("{x:.6}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let _ = writeln!(
            s,
            "LP status: optimal (all {} LPs); max equality residual {:.1e}; max |c_ij - c_ji| {:.1e}; Omega_1/Omega_3 mirror defect {:.1e}",
            16 * r.sub_patches.len(),
            r.max_residual,
            r.max_asymmetry,
            r.mirror_defect
        );
        let _ = writeln!(
            s,
            "per-step factor of M: extraordinary family r_ev = {:.6}, new regular nets r_sub = {:.6}, rho = {:.6}; distance after k steps <= {:.6} rho^k M_0",
            rate.r_ev, rate.r_sub, rate.rho, rate.constant
        );
        if let Some(st) = &steps {
            let _ = writeln!(
            s,
                "control net: M_0 = {:.6e}; {} subdivision step(s) bring the limit mesh within {:.3e} (bound {:.6e})",
                st.m_ev[0],
                st.steps,
                args.epsilon.unwrap_or(f64::NAN),
                st.bound
            );
        }
        write_stdout(s.as_bytes())
    }
}
