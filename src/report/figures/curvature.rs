//! `kind = "curvature"`: measured curvature of the limit surface on the ring
//! of level `k` around an extraordinary vertex of the Catmull-Clark family,
//! against `k`, next to the predicted rate `(mu / lambda^2)^k` (math doc
//! section 13.2).
//!
//! Drawn from [`crate::curvature::measured::measure`] (limit points of the
//! refined net, then a fitted quadric; see there): per valence, the largest
//! principal curvature (solid, markers) and the prediction
//! `kappa_K (mu / lambda^2)^(k - K)` anchored at the last level `K` (dashed).
//! The CSV has every level's Gaussian curvature `K`, mean curvature `H`, the
//! half difference of the principal curvatures, the largest one and the
//! prediction.
//!
//! ```toml
//! [[figure]]
//! kind = "curvature"
//! valences = [3, 4, 5, 8]   # default; each in 3..=16
//! c = 0.5                   # shape parameter in [0, 1] (default 1/2: Catmull-Clark)
//! levels = 16               # 1..=24 (default 16)
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::curvature::measured::{measure, MeasuredCurvature};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, series_color, titled, LegendGlyph, Marker, Theme,
};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted.
pub const MAX_VALENCE: usize = 16;
/// Largest number of levels accepted: the measurement loses its heights to
/// rounding beyond about 19 levels at `n = 3` (heights `mu^k` against
/// coordinates `lambda^k`: [`crate::curvature::measured`]); 24 leaves room
/// for the larger valences, whose heights shrink more slowly.
pub const MAX_LEVELS: usize = 24;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "curvature",
    default_title: "Measured curvature on the rings around the extraordinary vertex",
    summary: "largest principal curvature of the fitted limit quadric on ring k against k, with (mu/lambda^2)^k",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valences: Option<Spanned<Vec<usize>>>,
    c: Option<Spanned<f64>>,
    levels: Option<Spanned<usize>>,
}

struct CurvatureFigure {
    valences: Vec<usize>,
    c: f64,
    levels: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let valences = match &p.valences {
        None => vec![3, 4, 5, 8],
        Some(v) => {
            let list = v.get_ref();
            if list.is_empty()
                || list.len() > 8
                || list.iter().any(|&n| !(3..=MAX_VALENCE).contains(&n))
            {
                return Err(fs.error_at(
                    v,
                    "valences",
                    format!(
                        "valences must list 1 to 8 valences in 3..={MAX_VALENCE}, got {list:?}"
                    ),
                ));
            }
            list.clone()
        }
    };
    let c = match &p.c {
        None => 0.5,
        Some(c) if (0.0..=1.0).contains(c.get_ref()) => *c.get_ref(),
        Some(c) => {
            return Err(fs.error_at(
                c,
                "c",
                format!("c must be between 0 and 1, got {}", c.get_ref()),
            ))
        }
    };
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 16)?;
    Ok(Box::new(CurvatureFigure {
        valences,
        c,
        levels,
    }))
}

impl Figure for CurvatureFigure {
    fn work(&self) -> u64 {
        self.valences.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let runs = self
            .valences
            .par_iter()
            .map(|&n| {
                let m = measure(n, self.c, self.levels, ctx.common.seed).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok(m)
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output { runs }))
    }
}

struct Output {
    runs: Vec<MeasuredCurvature>,
}

impl Output {
    /// The prediction anchored at the last level.
    fn predicted(m: &MeasuredCurvature, k: usize) -> f64 {
        let last = m.levels.last().map_or(f64::NAN, |l| l.max_principal);
        let kk = m.levels.len() as i32 - 1;
        last * m.predicted_rate.powi(k as i32 - kk)
    }
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "n",
                "c",
                "level",
                "ring_radius",
                "gaussian",
                "mean",
                "twist",
                "max_principal",
                "fit_residual",
                "mu_over_lambda_squared",
                "predicted",
            ],
        );
        for m in &self.runs {
            for l in &m.levels {
                t.push(vec![
                    m.n.to_string(),
                    num(m.c),
                    l.level.to_string(),
                    num(l.ring_radius),
                    num(l.gaussian),
                    num(l.mean),
                    num(l.twist),
                    num(l.max_principal),
                    num(l.fit_residual),
                    num(m.predicted_rate),
                    num(Self::predicted(m, l.level)),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let vals = || {
            self.runs.iter().flat_map(|m| {
                m.levels
                    .iter()
                    .flat_map(move |l| [l.max_principal, Self::predicted(m, l.level)])
            })
        };
        let ymin = vals().filter(|y| *y > 0.0).fold(f64::INFINITY, f64::min) / 2.0;
        let ymax = vals().fold(0.0f64, f64::max) * 2.0;
        let (ymin, ymax) = if ymin.is_finite() && ymax > ymin {
            (ymin, ymax)
        } else {
            (1e-3, 1e3)
        };
        let kmax = self.runs.first().map_or(1, |m| m.levels.len() - 1) as f64;
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d(0.0..kmax, (ymin..ymax).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("level k")
            .y_desc("largest principal curvature on ring k")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| crate::report::plot::log_tick(*y))
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        let count = self.runs.len();
        for (i, m) in self.runs.iter().enumerate() {
            let col = series_color(i, count);
            let pts: Vec<(f64, f64)> = m
                .levels
                .iter()
                .map(|l| (l.level as f64, l.max_principal))
                .filter(|p| p.1 > 0.0)
                .collect();
            let marker = Marker::nth(i);
            let size = th.marker;
            chart
                .draw_series(LineSeries::new(pts.clone(), col.stroke_width(lw)))
                .map_err(draw_err)?
                .label(format!(
                    "n = {} (mu/lambda^2 = {:.4})",
                    m.n, m.predicted_rate
                ))
                .legend(move |p| LegendGlyph::line(p, &th, col, lw).marker(marker, size));
            chart
                .draw_series(pts.iter().map(|&p| marker.at(p, size, col)))
                .map_err(draw_err)?;
            let pred: Vec<(f64, f64)> = m
                .levels
                .iter()
                .map(|l| (l.level as f64, Self::predicted(m, l.level)))
                .collect();
            // Pattern 0 is the dashed one (pattern 1 reads as dotted), as
            // the module docs and the default caption say.
            let (d, g) = dash(0, &th);
            chart
                .draw_series(DashedLineSeries::new(
                    pred,
                    d,
                    g,
                    col.stroke_width(lw.max(2) / 2),
                ))
                .map_err(draw_err)?;
        }
        inner_legend(&mut chart, SeriesLabelPosition::UpperLeft, &th)?;
        Ok(())
    }
}
