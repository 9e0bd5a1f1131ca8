//! `kind = "ccss-bound"`: the Catmull-Clark patch to limit-face distance
//! bound beta(n) against the valence (math doc section 9; seed 002).
//!
//! Drawn: beta(n) from [`crate::ccss_bound::bound`] (one LP per Bezier
//! coefficient, default family of 2n+10 second differences), the sampled
//! maximum of B(u, v) over all examined sub-patches (it must coincide), and
//! the published reference value 1/4 = beta(4). The CSV has one row per
//! valence with beta, the diagonal parameter t of the maximum, the sub-patch
//! level attaining it, the sampled whole-patch maximum, and the LP equality
//! residual.
//!
//! ```toml
//! [[figure]]
//! kind = "ccss-bound"
//! valence = [3, 50]     # inclusive range (default [3, 20]); about 0.5 s per valence
//! levels = 4            # sub-patch levels k = 1..levels examined (default 4)
//! ```

use super::{bounded, num, valence_range, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::ccss_bound::bound::bound;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, titled, viridis, LegendGlyph, Marker, Theme,
};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted (the LPs grow like n^2).
pub const MAX_VALENCE: usize = 64;
/// Most sub-patch levels examined.
pub const MAX_LEVELS: u32 = 8;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "ccss-bound",
    default_title: "Distance bound β(n) between a Catmull-Clark patch and its limit face",
    summary:
        "beta(n) by linear programming against the valence, with the sampled whole-patch maximum",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valence: Option<Spanned<[usize; 2]>>,
    levels: Option<Spanned<u32>>,
}

struct CcssBound {
    lo: usize,
    hi: usize,
    levels: u32,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (lo, hi) = valence_range(fs, &p.valence, (3, 20), MAX_VALENCE)?;
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 4)?;
    Ok(Box::new(CcssBound { lo, hi, levels }))
}

struct Row {
    n: usize,
    beta: f64,
    t_max: f64,
    level: u32,
    full_max: f64,
    residual: f64,
}

impl Figure for CcssBound {
    fn work(&self) -> u64 {
        (self.hi - self.lo + 1) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let rows = (self.lo..=self.hi)
            .into_par_iter()
            .map(|n| {
                let r = bound(n, self.levels).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok(Row {
                    n,
                    beta: r.beta,
                    t_max: r.t_max,
                    level: r.level_of_max,
                    full_max: r.full_max,
                    residual: r.max_residual,
                })
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
                "beta",
                "t_max",
                "level",
                "sampled_full_max",
                "lp_residual",
            ],
        );
        for r in &self.rows {
            t.push(vec![
                r.n.to_string(),
                num(r.beta),
                num(r.t_max),
                r.level.to_string(),
                num(r.full_max),
                num(r.residual),
            ]);
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let lo = self.rows.first().map_or(3, |r| r.n) as f64;
        let hi = self.rows.last().map_or(20, |r| r.n) as f64;
        let values = self.rows.iter().flat_map(|r| [r.beta, r.full_max]);
        let ymin = values.clone().fold(0.25f64, f64::min);
        let ymax = values.fold(0.25f64, f64::max);
        let pad = (ymax - ymin).max(1e-3) * 0.08;
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d((lo - 1.0)..(hi + 1.0), (ymin - pad)..(ymax + pad))
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("valence n")
            .y_desc("β(n)  (|S − F| ≤ β(n) M)")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.1))
            .y_label_formatter(&|y| format!("{y:.3}"))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        let (d, g) = dash(0, &th);
        chart
            .draw_series(DashedLineSeries::new(
                vec![(lo - 1.0, 0.25), (hi + 1.0, 0.25)],
                d,
                g,
                BLACK.stroke_width(lw),
            ))
            .map_err(draw_err)?
            .label("1/4 = β(4) (regular case, published)")
            .legend(move |p| LegendGlyph::line(p, &th, BLACK, lw).dashed((d, g)));
        let dark = viridis(0.0);
        let pts: Vec<(f64, f64)> = self.rows.iter().map(|r| (r.n as f64, r.beta)).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), dark.stroke_width(lw)))
            .map_err(draw_err)?
            .label("β(n): max of D(t) = B(t, t) by LP")
            .legend(move |p| LegendGlyph::line(p, &th, dark, lw));
        let ms = th.marker;
        chart
            .draw_series(pts.iter().map(|&p| Marker::Circle.at(p, ms, dark)))
            .map_err(draw_err)?;
        let light = viridis(0.6);
        chart
            .draw_series(
                self.rows
                    .iter()
                    .map(|r| Marker::Ring.at((r.n as f64, r.full_max), ms * 2, light)),
            )
            .map_err(draw_err)?
            .label("sampled max of B(u, v) over all sub-patches")
            .legend(move |p| LegendGlyph::line(p, &th, light, 0).marker(Marker::Ring, ms * 2));
        inner_legend(&mut chart, SeriesLabelPosition::UpperRight, &th)?;
        Ok(())
    }
}
