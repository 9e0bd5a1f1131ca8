//! `subdiv-lab plot SWEEP.csv|SWEEP.parquet -o FIG.svg|FIG.png [--x COL] [--y COL]
//! [--color COL] [--kind fractions|histogram|scatter|map]`: a figure of a
//! sweep's results (parse -> validate -> library call; the plot kinds and
//! defaults are documented in `subdiv_lab::report::sweep_plot`).
//!
//! Bad input (an unreadable or empty file, a missing column, a text column
//! for an axis, an unknown kind, a bad output name) exits 2 with one line
//! naming the problem, before anything is written; the figure is written
//! atomically (temporary file, then rename).

use super::outfiles::{check_distinct, Staged};
use super::{CliError, CliResult};
use anyhow::anyhow;
use clap::Args;
use std::path::PathBuf;
use subdiv_lab::report::sweep_plot::{self, PlotRequest, SweepPlot};
use subdiv_lab::report::table::Table;
use subdiv_lab::report::{render_png, render_svg, Area};

#[derive(Args, Debug)]
pub(crate) struct PlotArgs {
    /// Sweep results: a CSV written by `subdiv-lab sweep` (or any CSV with a header line), or its Parquet file (NAME.parquet).
    input: PathBuf,
    /// Output figure: FIG.svg or FIG.png.
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
    /// Plot kind: fractions, histogram, scatter or map (default: chosen from the data).
    #[arg(long)]
    kind: Option<String>,
    /// Column on the horizontal axis.
    #[arg(long)]
    x: Option<String>,
    /// Column on the vertical axis (scatter, map).
    #[arg(long)]
    y: Option<String>,
    /// Column for colours or categories (default: class, where it exists).
    #[arg(long)]
    color: Option<String>,
    /// Figure title (default: names the columns).
    #[arg(long)]
    title: Option<String>,
    /// Width in pixels.
    #[arg(long, default_value_t = 1600)]
    width: u32,
    /// Height in pixels.
    #[arg(long, default_value_t = 1000)]
    height: u32,
    /// Plot even when the estimated time or memory exceeds the limits.
    #[arg(long)]
    force: bool,
}

pub(crate) fn run(args: PlotArgs) -> CliResult {
    let out_name = args.out.display().to_string();
    let svg = match args.out.extension().and_then(|e| e.to_str()) {
        Some("svg") => true,
        Some("png") => false,
        _ => {
            return Err(CliError::usage(anyhow!(
                "-o {out_name}: give a file name ending in .svg or .png"
            )))
        }
    };
    let kind = sweep_plot::check_options(
        args.kind.as_deref(),
        args.width,
        args.height,
        subdiv_lab::budget::Spelling::Cli,
    )
    .map_err(super::budget::usage)?;
    let in_name = args.input.display().to_string();
    check_distinct(&[("-o", &args.out)], &[("input", &args.input)])?;
    let bytes = std::fs::read(&args.input)
        .map_err(|e| CliError::usage(anyhow!("cannot read {in_name}: {e}")))?;
    let table = Table::from_named_bytes(&in_name, &bytes)
        .map_err(|e| CliError::usage(anyhow!("{in_name}: {e}")))?;
    super::budget::check(
        "plot",
        &in_name,
        &sweep_plot::estimate(table.len(), table.names().len()),
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )?;
    let request = PlotRequest {
        kind,
        x: args.x.clone(),
        y: args.y.clone(),
        color: args.color.clone(),
    };
    let plot = SweepPlot::build(&table, &request)
        .map_err(|e| CliError::usage(anyhow!("{in_name}: {e}")))?;
    let title = args.title.clone().unwrap_or_else(|| plot.default_title());
    let size = (args.width, args.height);
    let draw = |area: &Area<'_>| plot.draw(area, &title, size);
    let bytes = if svg {
        render_svg(size, &draw).map(String::into_bytes)
    } else {
        render_png(size, &draw)
    }
    .map_err(CliError::failure)?;
    Staged::write(&[(args.out.clone(), bytes)])?.commit()
}
