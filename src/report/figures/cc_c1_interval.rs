//! `kind = "cc-c1-interval"`: the interval(s) of the shape parameter `c` on
//! which the shape-adjustable Catmull-Clark scheme is certified C1, against
//! the valence (issue 8 item 3; math doc sections 7 and 8).
//!
//! Drawn from [`crate::cc_study::c1_intervals`] (class certified `standard`
//! and characteristic map certified regular and injective; ends located by
//! bisection to `tol`): one vertical bar per interval and valence, with the
//! certified-`standard` intervals ([`crate::cc_study::standard_intervals`])
//! as wider light bars behind them. The CSV has one row per interval and
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
use crate::report::plot::{draw_err, inner_legend, mix_white, titled, viridis, LegendGlyph, Theme};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted.
pub const MAX_VALENCE: usize = 64;
/// Most grid cells in `c`.
pub const MAX_SAMPLES: usize = 1000;

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
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d((lo - 1.0)..(hi + 1.0), -0.05f64..1.25f64)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("valence n")
            .y_desc("shape parameter c")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.1))
            .y_label_formatter(&|y| format!("{y:.1}"))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(draw_err)?;
        let dark = viridis(0.1);
        let light = mix_white(viridis(0.6), 0.45);
        let (wide, narrow) = (0.36, 0.16);
        let bar = |n: usize, i: &CInterval, w: f64, col: RGBColor| {
            Rectangle::new([(n as f64 - w, i.lo), (n as f64 + w, i.hi)], col.filled())
        };
        chart
            .draw_series(
                self.rows
                    .iter()
                    .flat_map(|r| r.standard.iter().map(move |i| bar(r.n, i, wide, light))),
            )
            .map_err(draw_err)?
            .label("certified standard eigenstructure")
            .legend(move |p| LegendGlyph::line(p, &th, light, 0).boxed());
        chart
            .draw_series(
                self.rows
                    .iter()
                    .flat_map(|r| r.c1.iter().map(move |i| bar(r.n, i, narrow, dark))),
            )
            .map_err(draw_err)?
            .label("certified C1 (standard, regular, injective)")
            .legend(move |p| LegendGlyph::line(p, &th, dark, 0).boxed());
        let lw = th.line;
        let red = RGBColor(200, 40, 40);
        chart
            .draw_series(LineSeries::new(
                vec![(lo - 1.0, 0.5), (hi + 1.0, 0.5)],
                red.stroke_width(lw),
            ))
            .map_err(draw_err)?
            .label("c = 1/2: Catmull-Clark")
            .legend(move |p| LegendGlyph::line(p, &th, red, lw));
        inner_legend(&mut chart, SeriesLabelPosition::UpperRight, &th)?;
        Ok(())
    }
}
