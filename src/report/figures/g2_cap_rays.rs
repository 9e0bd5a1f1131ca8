//! `kind = "g2-cap-rays"`: Gaussian and mean curvature along two rays
//! towards the extraordinary vertex, on the G2 cap of seed 003 (solid) and on
//! the plain subdivision surface (dashed) of the same net (math doc section
//! 14.7).
//!
//! The rays lie in patch 0: the diagonal `u = v = t` and the spoke `u = t,
//! v = 0` (the internal edge shared with patch `n - 1`), `t` from `2^-levels`
//! to 1 on a logarithmic axis (the subdivision surface's rings are the
//! intervals `[2^-m, 2^-(m-1)]`). Net, cap and surface as in
//! `g2-cap-curvature` (same keys; `grid` is the number of samples per ray
//! divided by 4). The CSV has every sample drawn.
//!
//! ```toml
//! [[figure]]
//! kind = "g2-cap-rays"
//! valence = 5      # 3..=16 (default 5)
//! c = 0.5          # shape parameter in [0, 1] (default 1/2)
//! levels = 8       # 1..=16 (default 8): the rays start at 2^-levels
//! grid = 16        # 2..=48 (default 16): 4 grid samples per ray
//! ```

use super::g2_cap_curvature::{cap_err, setup, surfaces, CapSetup, Params};
use super::{num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, legend_rows, legend_rows_height, series_color, titled, LegendGlyph, Theme,
};
use plotters::coord::combinators::IntoLogRange;
use plotters::prelude::*;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "g2-cap-rays",
    default_title: "Curvature along rays towards the vertex: G2 cap and subdivision surface",
    summary: "Gaussian and mean curvature of the seed-003 G2 cap and of the subdivision surface along the diagonal and a spoke towards the vertex",
    parse,
};

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    Ok(Box::new(RaysFigure {
        setup: setup(fs, &p)?,
    }))
}

struct RaysFigure {
    setup: CapSetup,
}

/// A ray: `(u, v)` at parameter `t`.
type Ray = fn(f64) -> (f64, f64);

/// The two rays: name and `(u, v)` at parameter `t`.
const RAYS: [(&str, Ray); 2] = [("diagonal", |t| (t, t)), ("spoke", |t| (t, 0.0))];

/// One sample: ray, surface (0 cap, 1 subdivision), t, K, H.
struct Sample {
    ray: usize,
    surface: usize,
    t: f64,
    k: f64,
    h: f64,
}

impl Figure for RaysFigure {
    fn work(&self) -> u64 {
        1
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let s = self.setup;
        let (cap, plain) = surfaces(&s, ctx.common.seed).map_err(|e| cap_err(ctx, e))?;
        let count = 4 * s.grid;
        let lo = 0.5f64.powi(s.levels as i32);
        let mut samples = Vec::new();
        for (r, (_, at)) in RAYS.iter().enumerate() {
            for q in 0..=count {
                // Log-spaced from 2^-levels to 1.
                let t = lo.powf(1.0 - q as f64 / count as f64);
                let (u, v) = at(t);
                for (surface, kh) in [
                    (0, cap.curvature_at(0, u, v)),
                    (1, plain.curvature_at(0, u, v)),
                ] {
                    if let Some((k, h)) = kh {
                        samples.push(Sample {
                            ray: r,
                            surface,
                            t,
                            k,
                            h,
                        });
                    }
                }
            }
        }
        ctx.tick(1);
        Ok(Box::new(Output { setup: s, samples }))
    }
}

struct Output {
    setup: CapSetup,
    samples: Vec<Sample>,
}

const SURFACES: [&str; 2] = ["cap", "subdivision"];

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(None, &["n", "c", "ray", "surface", "t", "gaussian", "mean"]);
        for s in &self.samples {
            t.push(vec![
                self.setup.valence.to_string(),
                num(self.setup.c),
                RAYS[s.ray].0.to_owned(),
                SURFACES[s.surface].to_owned(),
                num(s.t),
                num(s.k),
                num(s.h),
            ]);
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let lw = th.line;
        let colors = [series_color(0, 2), series_color(1, 2)];
        // Pattern 0 is the dashed one (pattern 1 reads as dotted), as the
        // module docs and the default caption say.
        let d = dash(0, &th);
        let mut entries = Vec::new();
        for (r, (name, _)) in RAYS.iter().enumerate() {
            entries.push((
                LegendGlyph::line((0, 0), &th, colors[r], lw),
                format!("G2 cap, {name}"),
            ));
            entries.push((
                LegendGlyph::line((0, 0), &th, colors[r], lw).dashed(d),
                format!("subdivision surface, {name}"),
            ));
        }
        let (bw, bh) = body.dim_in_pixel();
        let legend_h = legend_rows_height(&body, bw, &entries, &th) + th.legend;
        let (plots, legend_area) = body.split_vertically(bh.saturating_sub(legend_h));
        let panels = plots.split_evenly((1, 2));
        let lo = 0.5f64.powi(self.setup.levels as i32);
        for (q, pa) in panels.iter().enumerate() {
            let val = |s: &Sample| if q == 0 { s.k } else { s.h };
            let (mut y0, mut y1) = (0.0f64, 0.0f64);
            for s in &self.samples {
                if val(s).is_finite() {
                    (y0, y1) = (y0.min(val(s)), y1.max(val(s)));
                }
            }
            let pad = 0.08 * (y1 - y0).max(1e-12);
            let (y0, y1) = (y0 - pad, y1 + pad);
            let mut chart = ChartBuilder::on(pa)
                .margin(th.tick as i32)
                .x_label_area_size(th.label * 3)
                .y_label_area_size(th.label * 4)
                .build_cartesian_2d((lo..1.0).log_scale(), y0..y1)
                .map_err(draw_err)?;
            chart
                .configure_mesh()
                .x_desc("t along the ray (log scale)")
                .y_desc(if q == 0 {
                    "Gaussian curvature K"
                } else {
                    "mean curvature H"
                })
                .x_labels(5)
                .y_labels(6)
                .x_label_formatter(&|x| crate::report::plot::log_tick(*x))
                .y_label_formatter(&|y| crate::report::plot::tick(*y))
                .label_style(th.font(th.tick))
                .axis_desc_style(th.font(th.label))
                .light_line_style(WHITE.mix(0.0))
                .bold_line_style(BLACK.mix(0.12))
                .draw()
                .map_err(draw_err)?;
            for (r, col) in colors.iter().enumerate() {
                for surface in 0..2 {
                    let pts: Vec<(f64, f64)> = self
                        .samples
                        .iter()
                        .filter(|s| s.ray == r && s.surface == surface)
                        .map(|s| (s.t, val(s)))
                        .collect();
                    if surface == 0 {
                        chart
                            .draw_series(LineSeries::new(pts, col.stroke_width(lw)))
                            .map_err(draw_err)?;
                    } else {
                        chart
                            .draw_series(DashedLineSeries::new(pts, d.0, d.1, col.stroke_width(lw)))
                            .map_err(draw_err)?;
                    }
                }
            }
        }
        legend_rows(&legend_area.margin(th.legend / 2, 0, 0, 0), &entries, &th)?;
        Ok(())
    }
}
