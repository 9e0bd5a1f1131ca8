//! `kind = "cc-eigenvalues"`: the shape-adjustable Catmull-Clark scheme's
//! subdominant eigenvalue `lambda_1 = lambda_2` and `|lambda_3|` against the
//! shape parameter `c`, one colour per valence (math doc sections 6 and 8).
//!
//! Drawn from [`crate::cc_study::study_curve`] (common spectral engine on the
//! one-ring matrix, cross-checked against the closed-form Fourier blocks):
//! solid lines `lambda_1`, dashed lines `|lambda_3|`; points whose class is not
//! certified `standard` or whose characteristic map is not certified C1 are
//! ringed. The CSV has one row per `(n, c)` with both eigenvalues, the Fourier
//! value, the class and the characteristic-map verdict code.
//!
//! ```toml
//! [[figure]]
//! kind = "cc-eigenvalues"
//! valences = [3, 5, 8, 16]   # 1 to 8 valences in 3..=64 (default [3, 4, 5, 8, 16])
//! samples = 100              # grid cells in c (samples + 1 values in [0, 1]; default 100)
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::cc_study::{study_curve, StudyPoint};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, series_color, tick, titled, LegendGlyph, Marker, Theme,
};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted.
pub const MAX_VALENCE: usize = 64;
/// Most valences in one figure (colours stay distinguishable).
pub const MAX_SERIES: usize = 8;
/// Most grid cells in `c`.
pub const MAX_SAMPLES: usize = 2000;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "cc-eigenvalues",
    default_title: "Shape-adjustable Catmull-Clark: subdominant eigenvalues against c",
    summary: "lambda_1 = lambda_2 and |lambda_3| against c in [0, 1], one line per valence",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valences: Option<Spanned<Vec<usize>>>,
    samples: Option<Spanned<usize>>,
}

struct CcEigenvalues {
    valences: Vec<usize>,
    samples: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let valences = match &p.valences {
        None => vec![3, 4, 5, 8, 16],
        Some(v) => {
            let list = v.get_ref();
            if list.is_empty() || list.len() > MAX_SERIES {
                return Err(fs.error_at(
                    v,
                    "valences",
                    format!(
                        "valences must list 1 to {MAX_SERIES} valences, got {}",
                        list.len()
                    ),
                ));
            }
            if let Some(bad) = list.iter().find(|&&n| !(3..=MAX_VALENCE).contains(&n)) {
                return Err(fs.error_at(
                    v,
                    "valences",
                    format!("every valence must be in 3..={MAX_VALENCE}, got {bad}"),
                ));
            }
            list.clone()
        }
    };
    let samples = bounded(fs, &p.samples, "samples", 1, MAX_SAMPLES, 100)?;
    Ok(Box::new(CcEigenvalues { valences, samples }))
}

impl Figure for CcEigenvalues {
    fn work(&self) -> u64 {
        self.valences.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let curves = self
            .valences
            .par_iter()
            .map(|&n| {
                let c = study_curve(n, self.samples).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok((n, c))
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output { curves }))
    }
}

struct Output {
    curves: Vec<(usize, Vec<StudyPoint>)>,
}

fn flagged(p: &StudyPoint) -> bool {
    p.class != "standard" || p.charmap != "c1"
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "n",
                "c",
                "lambda1",
                "lambda2",
                "abs_lambda3",
                "fourier_subdominant",
                "class",
                "charmap",
            ],
        );
        for (n, curve) in &self.curves {
            for p in curve {
                t.push(vec![
                    n.to_string(),
                    num(p.c),
                    num(p.lambda1[0].hypot(p.lambda1[1])),
                    num(p.lambda2[0].hypot(p.lambda2[1])),
                    num(p.abs_lambda3),
                    num(p.fourier_subdominant),
                    p.class.to_owned(),
                    p.charmap.to_owned(),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let values = self.curves.iter().flat_map(|(_, c)| {
            c.iter()
                .flat_map(|p| [p.lambda1[0].hypot(p.lambda1[1]), p.abs_lambda3])
        });
        let ymin = values.clone().fold(f64::INFINITY, f64::min).min(0.5);
        let ymax = values.fold(0.0f64, f64::max).max(0.5);
        let pad = (ymax - ymin).max(1e-3) * 0.06;
        let count = self.curves.len();
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            // headroom above the curves for the legend (one row per valence + 1)
            .build_cartesian_2d(
                -0.02f64..1.02f64,
                (ymin - pad)..(ymax + pad + (ymax - ymin).max(1e-3) * 0.08 * (count + 1) as f64),
            )
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("shape parameter c  (c = 1/2: Catmull-Clark)")
            .y_desc("eigenvalue")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.1))
            .y_label_formatter(&|y| format!("{y:.2}"))
            .x_label_formatter(&|x| tick(*x))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        // Dashes (not dots): the legend and the caption say "dashed".
        let (d, g) = dash(0, &th);
        for (k, (n, curve)) in self.curves.iter().enumerate() {
            let col = series_color(k, count);
            let l1: Vec<(f64, f64)> = curve
                .iter()
                .map(|p| (p.c, p.lambda1[0].hypot(p.lambda1[1])))
                .collect();
            let l3: Vec<(f64, f64)> = curve.iter().map(|p| (p.c, p.abs_lambda3)).collect();
            chart
                .draw_series(LineSeries::new(l1, col.stroke_width(lw)))
                .map_err(draw_err)?
                .label(format!("n = {n}: λ₁ = λ₂"))
                .legend(move |p| LegendGlyph::line(p, &th, col, lw));
            chart
                .draw_series(DashedLineSeries::new(l3, d, g, col.stroke_width(lw)))
                .map_err(draw_err)?;
            let ms = th.marker * 2;
            chart
                .draw_series(
                    curve
                        .iter()
                        .filter(|p| flagged(p))
                        .map(|p| Marker::Ring.at((p.c, p.lambda1[0].hypot(p.lambda1[1])), ms, col)),
                )
                .map_err(draw_err)?;
        }
        // legend entries for the line styles
        let grey = RGBColor(90, 90, 90);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(draw_err)?
            .label("dashed: |λ₃|; ring: not certified C1")
            .legend(move |p| LegendGlyph::line(p, &th, grey, lw).dashed((d, g)));
        inner_legend(&mut chart, SeriesLabelPosition::UpperLeft, &th)?;
        Ok(())
    }
}
