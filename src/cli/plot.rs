//! `subdiv-lab plot SWEEP.csv|SWEEP.parquet|cells.csv -o FIG.svg|FIG.png [--x COL]
//! [--y COL] [--color COL] [--kind fractions|histogram|scatter|map]`: a figure
//! of a sweep's results or of `verify`'s cells (parse -> validate -> library
//! call; the plot kinds and defaults are documented in
//! `subdiv_lab::report::sweep_plot`).
//!
//! Bad input (an unreadable or empty file, a missing column, a text column
//! for an axis, an unknown kind, a bad output name) exits 2 with one line
//! naming the problem, before anything is written. The work is estimated
//! before the table is read (rows and columns from the file,
//! [`output_shape`]) and an SVG of more than
//! [`sweep_plot::MAX_SVG_ITEMS`] points or cells is refused (a PNG has a
//! fixed size) unless `--force`. Rows left out for a missing, NaN or
//! infinite coordinate are counted on stderr. The figure replaces `-o`
//! atomically (temporary file, then rename).

use super::outfiles::{check_distinct, Staged};
use super::{write_stderr, CliError, CliResult};
use anyhow::anyhow;
use clap::Args;
use std::path::PathBuf;
use subdiv_lab::budget::format_bytes;
use subdiv_lab::report::sweep_plot::{self, PlotRequest, SweepPlot, MAX_SVG_ITEMS};
use subdiv_lab::report::{render_png, render_svg, Area};
use subdiv_lab::sweep::output::{output_shape, read_output};

#[derive(Args, Debug)]
pub(crate) struct PlotArgs {
    /// Sweep results: a CSV written by `subdiv-lab sweep` (or any CSV with a
    /// header line), its Parquet file (NAME.parquet), or the cells.csv of
    /// `subdiv-lab verify` (drawn as the certified map).
    input: PathBuf,
    /// Output figure: FIG.svg or FIG.png. An existing regular file is
    /// replaced atomically. An SVG of more than 100000 points or cells is
    /// refused unless --force (write a PNG instead).
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
    /// Plot kind: fractions, histogram, scatter or map (default: chosen from the data).
    #[arg(long)]
    kind: Option<String>,
    /// Column on the horizontal axis (for verify cells: a coordinate, r0.. or c).
    #[arg(long)]
    x: Option<String>,
    /// Column on the vertical axis (scatter, map).
    #[arg(long)]
    y: Option<String>,
    /// Column for colours or categories (default: class, or verdict for verify cells).
    #[arg(long)]
    color: Option<String>,
    /// Figure title (default: names the columns).
    #[arg(long)]
    title: Option<String>,
    /// Width in pixels (400 to 8000).
    #[arg(long, default_value_t = 1600)]
    width: u32,
    /// Height in pixels (400 to 8000).
    #[arg(long, default_value_t = 1000)]
    height: u32,
    /// Plot even when the estimated time or memory, or the SVG size, exceeds the limits.
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
    let limit = subdiv_lab::budget::TIME_LIMIT_SECONDS;
    // Holding the file: checked before it is read.
    let file_bytes = std::fs::metadata(&args.input)
        .map_err(|e| CliError::usage(anyhow!("cannot read {in_name}: {e}")))?
        .len();
    let holding = sweep_plot::estimate(0, 0, file_bytes);
    super::budget::check("plot", &in_name, &holding, limit, args.force)?;
    let bytes = std::fs::read(&args.input)
        .map_err(|e| CliError::usage(anyhow!("cannot read {in_name}: {e}")))?;
    // Reading and drawing the table: checked before it is parsed.
    let (rows, columns) =
        output_shape(&in_name, &bytes).map_err(|e| CliError::usage(anyhow!("{in_name}: {e}")))?;
    let estimate = sweep_plot::estimate(rows, columns, file_bytes);
    super::budget::check("plot", &in_name, &estimate, limit, args.force)?;
    let table =
        read_output(&in_name, &bytes).map_err(|e| CliError::usage(anyhow!("{in_name}: {e}")))?;
    drop(bytes);
    let request = PlotRequest {
        kind,
        x: args.x.clone(),
        y: args.y.clone(),
        color: args.color.clone(),
    };
    let plot = SweepPlot::build(&table, &request)
        .map_err(|e| CliError::usage(anyhow!("{in_name}: {e}")))?;
    let items = plot.items();
    if svg && items > MAX_SVG_ITEMS && !args.force {
        return Err(CliError::usage(anyhow!(
            "plot: {in_name} draws {items} points or cells, an SVG of ~{} (limit {MAX_SVG_ITEMS}); write a PNG (-o NAME.png), whose size does not grow with the points, or use --force",
            format_bytes(sweep_plot::svg_bytes(items))
        )));
    }
    let title = args.title.clone().unwrap_or_else(|| plot.default_title());
    let size = (args.width, args.height);
    let draw = |area: &Area<'_>| plot.draw(area, &title, size);
    let bytes = if svg {
        render_svg(size, &draw).map(String::into_bytes)
    } else {
        render_png(size, &draw)
    }
    .map_err(CliError::failure)?;
    Staged::write(&[(args.out.clone(), bytes)])?.commit()?;
    if plot.dropped() > 0 {
        write_stderr(&format!(
            "plot: left out {} of {} rows without a finite {} (missing, NaN or infinite)",
            plot.dropped(),
            table.len(),
            plot.axes()
        ));
    }
    Ok(())
}
