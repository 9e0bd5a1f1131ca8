//! `kind = "curvature-tuning"`: the shape-adjustable Catmull-Clark scheme,
//! `mu / lambda^2` against the shape parameter `c` for a range of valences,
//! with the certified values of `c` where `mu = lambda^2` (bounded
//! curvature; math doc section 13.3).
//!
//! Drawn from [`crate::curvature::tuning::tune`]: one curve per valence, the
//! level 1 (bounded curvature) as a horizontal line, certified roots as
//! markers. The main CSV has every sample with `lambda`, `mu`, the ratio, the
//! certified sign of `mu - lambda^2` (interval arithmetic) and whether
//! `mu = lambda^2` was certified exactly there; the `roots` CSV has each
//! certified bracket `[c_lo, c_hi]` with the signs at its ends.
//!
//! ```toml
//! [[figure]]
//! kind = "curvature-tuning"
//! valence = [3, 16]   # inclusive range (default [3, 16]; at most 64)
//! grid = 128          # cells in c over [0, 1] (default 128; a power of two keeps c dyadic)
//! ```

use super::{bounded, num, valence_range, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::curvature::tuning::{tune, Tuning, MAX_VALENCE};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    draw_err, series_color, side_legend, titled, LegendGlyph, Marker, Theme,
};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Most grid cells accepted.
pub const MAX_GRID: usize = 4096;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "curvature-tuning",
    default_title: "Shape-adjustable Catmull-Clark: μ/λ² against c",
    summary: "mu/lambda^2 of the adjustable scheme against c per valence, with the certified c where mu = lambda^2",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valence: Option<Spanned<[usize; 2]>>,
    grid: Option<Spanned<usize>>,
}

struct TuningFigure {
    lo: usize,
    hi: usize,
    grid: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (lo, hi) = valence_range(fs, &p.valence, (3, 16), MAX_VALENCE)?;
    let grid = bounded(fs, &p.grid, "grid", 1, MAX_GRID, 128)?;
    Ok(Box::new(TuningFigure { lo, hi, grid }))
}

impl Figure for TuningFigure {
    fn work(&self) -> u64 {
        (self.hi - self.lo + 1) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let rows = (self.lo..=self.hi)
            .into_par_iter()
            .map(|n| {
                let t = tune(n, self.grid).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok(t)
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output { rows }))
    }
}

struct Output {
    rows: Vec<Tuning>,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "n",
                "c",
                "lambda",
                "mu",
                "mu_over_lambda_squared",
                "sign",
                "exact_bounded",
            ],
        );
        let mut r = DataTable::new(Some("roots"), &["n", "c_lo", "c_hi", "below", "above"]);
        for row in &self.rows {
            for p in &row.curve {
                t.push(vec![
                    row.n.to_string(),
                    num(p.c),
                    num(p.lambda),
                    num(p.mu),
                    num(p.ratio),
                    p.sign.as_str().to_owned(),
                    u8::from(p.exact_bounded).to_string(),
                ]);
            }
            for x in &row.roots {
                r.push(vec![
                    row.n.to_string(),
                    num(x.c_lo),
                    num(x.c_hi),
                    x.below.as_str().to_owned(),
                    x.above.as_str().to_owned(),
                ]);
            }
        }
        vec![t, r]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let ratios = || {
            self.rows
                .iter()
                .flat_map(|r| r.curve.iter().map(|p| p.ratio))
        };
        let ymin = ratios().fold(1.0f64, f64::min).max(0.0) - 0.05;
        let ymax = ratios().fold(1.0f64, f64::max).min(4.0) + 0.05;
        let (w, _) = body.dim_in_pixel();
        let (plot_area, legend_area) = body.split_horizontally(w * 72 / 100);
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d(0.0f64..1.0f64, ymin..ymax)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("shape parameter c")
            .y_desc("μ / λ²")
            .x_label_formatter(&|x| format!("{x:.1}"))
            .y_label_formatter(&|y| format!("{y:.2}"))
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        chart
            .draw_series(LineSeries::new(
                vec![(0.0, 1.0), (1.0, 1.0)],
                BLACK.stroke_width(1),
            ))
            .map_err(draw_err)?;
        let mut legend = Vec::new();
        let count = self.rows.len();
        for (i, row) in self.rows.iter().enumerate() {
            let col = series_color(i, count);
            let pts: Vec<(f64, f64)> = row
                .curve
                .iter()
                .map(|p| (p.c, p.ratio))
                .filter(|p| p.1 >= ymin && p.1 <= ymax)
                .collect();
            chart
                .draw_series(LineSeries::new(pts, col.stroke_width(lw)))
                .map_err(draw_err)?;
            let size = th.marker;
            chart
                .draw_series(
                    row.roots
                        .iter()
                        .map(|r| Marker::nth(0).at((0.5 * (r.c_lo + r.c_hi), 1.0), size, col)),
                )
                .map_err(draw_err)?;
            let label = if row.roots.is_empty() {
                format!("n = {}", row.n)
            } else {
                let cs: Vec<String> = row.roots.iter().map(|r| format!("{:.4}", r.c_lo)).collect();
                format!("n = {}: c = {}", row.n, cs.join(", "))
            };
            legend.push((label, col));
        }
        let entries: Vec<(LegendGlyph, Vec<String>)> = legend
            .into_iter()
            .map(|(l, c)| (LegendGlyph::line((0, 0), &th, c, lw), vec![l]))
            .collect();
        side_legend(&legend_area, &entries, &th)?;
        Ok(())
    }
}
