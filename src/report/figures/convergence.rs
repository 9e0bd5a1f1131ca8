//! `kind = "convergence"`: max_i |P^k_i - F| against the step k on a log scale.
//!
//! The distances come from the Theorem 1 analysis
//! ([`crate::contraction::face_contraction`], for the Doo-Sabin family
//! [`crate::contraction::measure`]): the 4n points of
//! the local neighbourhood (random in [-1, 1)^3, seed derived from the
//! figure's seed and the configuration index) are refined with S_n, and
//! max_i |P^k_i - F| over the face points is recorded relative to k = 0. Drawn with the
//! Theorem 1 bound (3/4)^k (math doc section 5; rigorous: every curve must
//! stay below it) and, per configuration, the asymptotic rate |lambda_1|^k of
//! the subdominant eigenvalue, fitted through the last recorded step.
//!
//! ```toml
//! [[figure]]
//! kind = "convergence"
//! steps = 40                  # k = 0..steps (default 40)
//! configs = [ { scheme = "nurds", valence = 5, random_knots = 4.0 }, ... ]
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::contraction::MeasureOptions;
use crate::report::backend::Area;
use crate::report::config::{require_doo_sabin_family, resolve_all, ConfigSpec, Configuration};
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, series_color, side_legend, titled, LegendGlyph, Marker, Theme,
};
use crate::rng::derive_seed;
use crate::spectral::classify_scheme;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest accepted number of steps.
pub const MAX_STEPS: usize = 500;
/// Default number of steps.
pub const DEFAULT_STEPS: usize = 40;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "convergence",
    default_title: "Convergence of the face to its limit point",
    summary: "max_i |P^k_i - F| / max_i |P^0_i - F| against k, with (3/4)^k and |lambda_1|^k",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    configs: Spanned<Vec<ConfigSpec>>,
    steps: Option<Spanned<usize>>,
}

struct Convergence {
    configs: Vec<Configuration>,
    steps: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let configs = resolve_all(fs, &p.configs, None)?;
    require_doo_sabin_family(fs, &p.configs, &configs, "the face contraction (Theorem 1)")?;
    let steps = bounded(fs, &p.steps, "steps", 1, MAX_STEPS, DEFAULT_STEPS)?;
    Ok(Box::new(Convergence { configs, steps }))
}

/// One configuration's curve.
#[derive(Clone, Debug)]
struct Curve {
    label: String,
    lambda1: f64,
    /// (k, max_i |P^k_i - F| / max_i |P^0_i - F|).
    points: Vec<(usize, f64)>,
    /// The constant C of the fitted line C |lambda_1|^k.
    fit: f64,
}

impl Figure for Convergence {
    fn work(&self) -> u64 {
        self.configs.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let curves = self
            .configs
            .par_iter()
            .enumerate()
            .map(|(i, c)| {
                let sub = classify_scheme(&*c.scheme).map_err(|e| ctx.err(e))?;
                let lambda1 = sub.lambda1.norm();
                let options = MeasureOptions {
                    levels: self.steps,
                    seed: derive_seed(ctx.common.seed, &i.to_string()),
                    dim: 3,
                };
                // the scheme's Theorem 1 capability (the figure's configurations
                // were checked to have a face block when the spec was parsed)
                let m = crate::contraction::face_contraction(&*c.scheme, &options)
                    .ok_or_else(|| {
                        ctx.err(crate::Error::NotApplicable {
                            scheme: c.scheme.name().to_owned(),
                            operation:
                                "the face contraction of Theorem 1 (a Doo-Sabin-family notion)",
                        })
                    })?
                    .map_err(|e| ctx.err(e))?
                    .measured;
                let d0 = m.distances.first().copied().unwrap_or(0.0);
                let points: Vec<(usize, f64)> = m
                    .distances
                    .iter()
                    .enumerate()
                    .map(|(k, d)| (k, d / d0))
                    .take_while(|(_, r)| r.is_finite() && *r > 0.0)
                    .collect();
                let (k_last, d_last) = *points.last().unwrap_or(&(0, 1.0));
                let fit = if lambda1 > 0.0 {
                    d_last / lambda1.powi(k_last as i32)
                } else {
                    1.0
                };
                ctx.tick(1);
                Ok(Curve {
                    label: c.label.clone(),
                    lambda1,
                    points,
                    fit,
                })
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output {
            curves,
            steps: self.steps,
        }))
    }
}

struct Output {
    curves: Vec<Curve>,
    steps: usize,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "config",
                "label",
                "k",
                "relative_distance",
                "bound_3_4_pow_k",
                "abs_lambda1",
                "rate_line",
            ],
        );
        for (i, c) in self.curves.iter().enumerate() {
            for &(k, d) in &c.points {
                t.push(vec![
                    i.to_string(),
                    c.label.clone(),
                    k.to_string(),
                    num(d),
                    num(0.75f64.powi(k as i32)),
                    num(c.lambda1),
                    num(c.fit * c.lambda1.powi(k as i32)),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let ymin = self
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.1))
            .fold(1.0f64, f64::min)
            / 2.0;
        let kmax = self.steps as f64;
        let (w, _) = body.dim_in_pixel();
        let (plot_area, legend_area) = body.split_horizontally(w * 66 / 100);
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d(0.0..kmax, (ymin..1.5f64).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("subdivision step k")
            .y_desc("max_i |P^k_i − F| / max_i |P^0_i − F|")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_err)?;
        let n = self.curves.len();
        let lw = th.line;
        let origin = (0, 0);
        let mut legend = Vec::new();
        // Theorem 1 bound.
        let bound: Vec<(f64, f64)> = (0..=self.steps)
            .map(|k| (k as f64, 0.75f64.powi(k as i32)))
            .filter(|p| p.1 >= ymin)
            .collect();
        let (dl, gap) = dash(2, &th);
        chart
            .draw_series(DashedLineSeries::new(
                bound,
                dl,
                gap,
                BLACK.stroke_width(lw + 1),
            ))
            .map_err(draw_err)?;
        legend.push((
            LegendGlyph::line(origin, &th, BLACK, lw + 1).dashed((dl, gap)),
            vec!["(3/4)^k: Theorem 1 bound".to_owned()],
        ));
        let rate_dash = dash(1, &th);
        for (i, c) in self.curves.iter().enumerate() {
            let col = series_color(i, n);
            let marker = Marker::nth(i);
            let ms = th.marker;
            let pts: Vec<(f64, f64)> = c.points.iter().map(|&(k, d)| (k as f64, d)).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), col.stroke_width(lw)))
                .map_err(draw_err)?;
            let every = (pts.len() / 12).max(1);
            chart
                .draw_series(pts.iter().step_by(every).map(|&p| marker.at(p, ms, col)))
                .map_err(draw_err)?;
            let rate: Vec<(f64, f64)> = (0..=self.steps)
                .map(|k| (k as f64, c.fit * c.lambda1.powi(k as i32)))
                .filter(|p| p.1 >= ymin && p.1 <= 1.5)
                .collect();
            chart
                .draw_series(DashedLineSeries::new(
                    rate,
                    rate_dash.0,
                    rate_dash.1,
                    col.stroke_width(lw),
                ))
                .map_err(draw_err)?;
            legend.push((
                LegendGlyph::line(origin, &th, col, lw).marker(marker, ms),
                vec![c.label.clone(), format!("|λ₁| = {:.4}", c.lambda1)],
            ));
        }
        legend.push((
            LegendGlyph::line(origin, &th, BLACK, lw).dashed(rate_dash),
            vec![
                "C |λ₁|^k, dotted, in the".to_owned(),
                "curve's colour (C fitted".to_owned(),
                "at the last step)".to_owned(),
            ],
        ));
        side_legend(&legend_area, &legend, &th)?;
        Ok(())
    }
}
