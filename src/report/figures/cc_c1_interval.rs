//! `kind = "cc-c1-interval"`: the interval(s) of the shape parameter `c` on
//! which the shape-adjustable Catmull-Clark scheme is certified C1, against
//! the valence (math doc sections 7 and 8).
//!
//! Drawn from [`crate::cc_study::c1_intervals`] (class certified `standard`
//! and characteristic map certified regular and injective; ends located by
//! bisection to `tol`) on a log axis of `c`: the lower end `c_min(n)` of each
//! C1 interval and of each certified-`standard` interval
//! ([`crate::cc_study::standard_intervals`]) against `n`, each with its
//! bisection bracket `[outside, end]` as an error bar (a bracket reaching
//! `c = 0` runs to the axis); upper ends are drawn only where they are below 1. The CSV has one row per interval and
//! criterion with both ends, the bracketing points just outside, and the
//! verdict there.
//!
//! ```toml
//! [[figure]]
//! kind = "cc-c1-interval"
//! valence = [3, 32]     # inclusive range (default [3, 32])
//! samples = 20          # grid cells in c bracketing the ends (default 20)
//! tol = 1e-6            # bisection width (default 1e-6)
//! ```

use super::{bounded, num, valence_range, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::cc_study::{intervals, CInterval, Criterion};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    draw_err, legend_rows, legend_rows_height, log_tick, titled, viridis, LegendGlyph, Marker,
    Theme,
};
use plotters::coord::combinators::IntoLogRange;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted.
pub const MAX_VALENCE: usize = 64;
/// Most grid cells in `c`.
pub const MAX_SAMPLES: usize = 1000;

/// CPU seconds per evaluated point (classification and cone certificate of
/// the `(2n + 1)`-square one-ring) per `d^3`, `d = 2n + 1`: measured 2.4e-9
/// (n = 60..64 and n = 3..32, 2-core reference machine under load), doubled.
pub const SECONDS_PER_POINT_D3: f64 = 5e-9;
/// Fixed CPU seconds per evaluated point.
pub const SECONDS_PER_POINT: f64 = 1e-4;

/// Estimated CPU seconds of the figure: two studies (C1 and standard), each
/// evaluating `samples + 1` grid points and, at each of about 4 interval
/// ends, `log2(1 / (samples tol))` bisection points, per valence.
pub fn estimate_seconds(lo: usize, hi: usize, samples: usize, tol: f64) -> f64 {
    let steps = (1.0 / (samples as f64 * tol)).log2().max(1.0);
    let points = samples as f64 + 1.0 + 4.0 * steps;
    (lo..=hi)
        .map(|n| {
            let d = 2.0 * n as f64 + 1.0;
            2.0 * points * (SECONDS_PER_POINT + SECONDS_PER_POINT_D3 * d * d * d)
        })
        .sum()
}

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "cc-c1-interval",
    default_title: "Shape-adjustable Catmull-Clark: certified C1 interval of c against the valence",
    summary: "intervals of c certified C1 (standard, regular, injective) per valence, by bisection",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valence: Option<Spanned<[usize; 2]>>,
    samples: Option<Spanned<usize>>,
    tol: Option<Spanned<f64>>,
}

struct CcC1Interval {
    lo: usize,
    hi: usize,
    samples: usize,
    tol: f64,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (lo, hi) = valence_range(fs, &p.valence, (3, 32), MAX_VALENCE)?;
    let samples = bounded(fs, &p.samples, "samples", 1, MAX_SAMPLES, 20)?;
    let tol = match &p.tol {
        None => 1e-6,
        Some(t) if *t.get_ref() >= 1e-12 && *t.get_ref() <= 0.1 => *t.get_ref(),
        Some(t) => {
            return Err(fs.error_at(
                t,
                "tol",
                format!("tol must be between 1e-12 and 0.1, got {}", t.get_ref()),
            ))
        }
    };
    // Heavy work is refused with its estimate: the largest settings would
    // run for hours without a word.
    let seconds = estimate_seconds(lo, hi, samples, tol);
    if seconds > crate::budget::TIME_LIMIT_SECONDS {
        let what = format!(
            "the C1 and standard intervals of {} valences up to {hi} with {samples} samples and tol {tol:e} take ~{} (limit {} s); lower samples, the valence range or raise tol",
            hi - lo + 1,
            crate::budget::format_seconds(seconds),
            crate::budget::TIME_LIMIT_SECONDS
        );
        return Err(match (&p.samples, &p.valence, &p.tol) {
            (Some(s), _, _) => fs.error_at(s, "samples", what),
            (None, Some(v), _) => fs.error_at(v, "valence", what),
            (None, None, Some(t)) => fs.error_at(t, "tol", what),
            (None, None, None) => fs.error(what),
        });
    }
    Ok(Box::new(CcC1Interval {
        lo,
        hi,
        samples,
        tol,
    }))
}

struct Row {
    n: usize,
    c1: Vec<CInterval>,
    standard: Vec<CInterval>,
}

impl Figure for CcC1Interval {
    fn work(&self) -> u64 {
        (self.hi - self.lo + 1) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let rows = (self.lo..=self.hi)
            .into_par_iter()
            .map(|n| {
                let c1 =
                    intervals(n, self.samples, self.tol, Criterion::C1).map_err(|e| ctx.err(e))?;
                let standard = intervals(n, self.samples, self.tol, Criterion::Standard)
                    .map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok(Row { n, c1, standard })
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output { rows }))
    }
}

struct Output {
    rows: Vec<Row>,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "n",
                "criterion",
                "interval",
                "c_lo",
                "c_hi",
                "c_lo_outside",
                "c_hi_outside",
                "below",
                "above",
            ],
        );
        for r in &self.rows {
            for (name, list) in [("c1", &r.c1), ("standard", &r.standard)] {
                for (k, i) in list.iter().enumerate() {
                    t.push(vec![
                        r.n.to_string(),
                        name.to_owned(),
                        k.to_string(),
                        num(i.lo),
                        num(i.hi),
                        num(i.lo_outside),
                        num(i.hi_outside),
                        i.below.clone(),
                        i.above.clone(),
                    ]);
                }
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let lo = self.rows.first().map_or(3, |r| r.n) as f64;
        let hi = self.rows.last().map_or(32, |r| r.n) as f64;
        let dark = viridis(0.1);
        let mid = viridis(0.55);
        let red = RGBColor(200, 40, 40);
        let lw = th.line;
        let ms = th.marker;
        // Lower ends (c_min of the C1 intervals, the start of the standard
        // intervals) and upper ends below 1, each with its bisection bracket.
        let ends = |pick: &dyn Fn(&Row) -> &Vec<CInterval>, upper: bool| -> Vec<(f64, f64, f64)> {
            self.rows
                .iter()
                .flat_map(|r| {
                    pick(r).iter().filter_map(move |i| {
                        let (v, out) = if upper {
                            (i.hi, i.hi_outside)
                        } else {
                            (i.lo, i.lo_outside)
                        };
                        (v > 0.0 && (!upper || v < 1.0)).then_some((r.n as f64, v, out))
                    })
                })
                .collect()
        };
        let c1_lo = ends(&|r| &r.c1, false);
        let st_lo = ends(&|r| &r.standard, false);
        let c1_hi = ends(&|r| &r.c1, true);
        let positive = c1_lo
            .iter()
            .chain(&st_lo)
            .chain(&c1_hi)
            .flat_map(|e| [e.1, e.2])
            .filter(|v| *v > 0.0);
        let ymin = positive.fold(0.5f64, f64::min) / 4.0;
        let ymax = 2.0;
        let mut entries = vec![
            (
                LegendGlyph::line((0, 0), &th, dark, lw).marker(Marker::Circle, ms),
                "C1 interval: lower end c_min(n) (bar: bisection bracket)".to_owned(),
            ),
            (
                LegendGlyph::line((0, 0), &th, mid, lw).marker(Marker::Diamond, ms),
                "standard-eigenstructure interval: lower end (bracket down to c = 0)".to_owned(),
            ),
        ];
        if !c1_hi.is_empty() {
            entries.push((
                LegendGlyph::line((0, 0), &th, dark, lw).marker(Marker::Triangle, ms),
                "C1 interval: upper end below 1".to_owned(),
            ));
        }
        entries.push((
            LegendGlyph::line((0, 0), &th, red, lw),
            "c = 1/2: Catmull-Clark".to_owned(),
        ));
        let (bw, bh) = body.dim_in_pixel();
        let legend_h = legend_rows_height(&body, bw, &entries, &th) + th.legend;
        let (plot_area, legend_area) = body.split_vertically(bh.saturating_sub(legend_h));
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d((lo - 1.0)..(hi + 1.0), (ymin..ymax).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("valence n")
            .y_desc("shape parameter c (log scale)")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE)
            .bold_line_style(BLACK.mix(0.1))
            .y_label_formatter(&|y| log_tick(*y))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(draw_err)?;
        chart
            .draw_series(LineSeries::new(
                vec![(lo - 1.0, 0.5), (hi + 1.0, 0.5)],
                red.stroke_width(lw),
            ))
            .map_err(draw_err)?;
        let cap = 0.25;
        for (points, col, marker) in [
            (&st_lo, mid, Marker::Diamond),
            (&c1_lo, dark, Marker::Circle),
            (&c1_hi, dark, Marker::Triangle),
        ] {
            for &(n, v, out) in points.iter() {
                // The bracket [outside, end]; an outside end at 0 runs to the axis.
                let o = out.max(ymin);
                let style = col.stroke_width(lw);
                chart
                    .draw_series(LineSeries::new(vec![(n, o), (n, v)], style))
                    .map_err(draw_err)?;
                if out > ymin {
                    chart
                        .draw_series(LineSeries::new(vec![(n - cap, o), (n + cap, o)], style))
                        .map_err(draw_err)?;
                }
                chart
                    .draw_series(std::iter::once(marker.at((n, v), ms, col)))
                    .map_err(draw_err)?;
            }
        }
        legend_rows(&legend_area.margin(th.legend / 2, 0, 0, 0), &entries, &th)?;
        Ok(())
    }
}
