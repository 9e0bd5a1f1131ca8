//! `kind = "subdominant-vs-valence"`: |lambda_1| against the valence n.
//!
//! Drawn: the uniform closed form 1/2 + cos(2 pi/n)/4 (math doc section 6),
//! the computed |lambda_1| of uniform NURDS (markers, must sit on the curve),
//! and the min/max envelope of |lambda_1| over `samples` random non-uniform
//! knot configurations per n (corner intervals log-uniform in
//! [1, `random_knots`], drawn from the figure's seed), with the bound 3/4.
//!
//! ```toml
//! [[figure]]
//! kind = "subdominant-vs-valence"
//! valence = [3, 64]           # inclusive range (default [3, 64])
//! samples = 24                # random configurations per valence (default 24)
//! random_knots = 4.0          # largest interval ratio (default 4)
//! ```

use super::{num, valence_range, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::knots::{CornerIntervals, EdgeRatios};
use crate::report::backend::Area;
use crate::report::config::MAX_VALENCE;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, mix_white, titled, viridis, LegendGlyph, Marker, Theme,
};
use crate::rng::{derive_seed, log_uniform, SplitMix64};
use crate::schemes::LocalScheme;
use crate::spectral::classify_scheme;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Most random samples per valence.
pub const MAX_SAMPLES: usize = 10_000;

/// CPU seconds per classification of the `n x n` face block, per `n^3`
/// (measured 1.3e-9 at n = 64..256 on the 2-core reference machine under
/// load, rounded up), plus a fixed cost per classification.
pub const SECONDS_PER_N3: f64 = 3e-9;
/// Fixed CPU seconds per classification (knot drawing, small matrices).
pub const SECONDS_PER_SAMPLE: f64 = 2e-5;

/// Estimated CPU seconds of the figure: `samples + 1` classifications per
/// valence in `lo..=hi`.
pub fn estimate_seconds(lo: usize, hi: usize, samples: usize) -> f64 {
    (lo..=hi)
        .map(|n| {
            (samples as f64 + 1.0) * (SECONDS_PER_SAMPLE + SECONDS_PER_N3 * (n as f64).powi(3))
        })
        .sum()
}

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "subdominant-vs-valence",
    default_title: "Subdominant modulus |λ₁| against valence n",
    summary:
        "uniform closed form vs computed |lambda_1|, with the min/max envelope over random knots",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    valence: Option<Spanned<[usize; 2]>>,
    samples: Option<Spanned<usize>>,
    random_knots: Option<Spanned<f64>>,
}

struct Valence {
    lo: usize,
    hi: usize,
    samples: usize,
    max_ratio: f64,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (lo, hi) = valence_range(fs, &p.valence, (3, 64), MAX_VALENCE)?;
    let samples = match &p.samples {
        None => 24,
        Some(s) if *s.get_ref() <= MAX_SAMPLES => *s.get_ref(),
        Some(s) => {
            return Err(fs.error_at(
                s,
                "samples",
                format!("samples must be at most {MAX_SAMPLES}, got {}", s.get_ref()),
            ))
        }
    };
    // Heavy work is refused with its estimate: valences up to 256 with
    // thousands of samples would run for hours without a word.
    let seconds = estimate_seconds(lo, hi, samples);
    if seconds > crate::budget::TIME_LIMIT_SECONDS {
        let what = format!(
            "{} classifications of up to {hi} x {hi} face blocks take ~{} (limit {} s); lower samples or the valence range",
            (samples + 1) * (hi - lo + 1),
            crate::budget::format_seconds(seconds),
            crate::budget::TIME_LIMIT_SECONDS
        );
        return Err(match (&p.samples, &p.valence) {
            (Some(s), _) => fs.error_at(s, "samples", what),
            (None, Some(v)) => fs.error_at(v, "valence", what),
            (None, None) => fs.error(what),
        });
    }
    let max_ratio = match &p.random_knots {
        None => 4.0,
        Some(m) if m.get_ref().is_finite() && *m.get_ref() > 1.0 && *m.get_ref() <= 1e6 => {
            *m.get_ref()
        }
        Some(m) => {
            return Err(fs.error_at(
                m,
                "random_knots",
                format!(
                    "random_knots is the largest interval ratio, in (1, 1e6]; got {}",
                    m.get_ref()
                ),
            ))
        }
    };
    Ok(Box::new(Valence {
        lo,
        hi,
        samples,
        max_ratio,
    }))
}

/// The uniform closed form |lambda_1| = 1/2 + cos(2 pi/n)/4 (math doc section 6).
pub fn uniform_subdominant(n: usize) -> f64 {
    0.5 + (std::f64::consts::TAU / n as f64).cos() / 4.0
}

#[derive(Clone, Debug)]
struct Row {
    n: usize,
    closed: f64,
    computed: f64,
    min: f64,
    max: f64,
    samples: Vec<(f64, String)>,
}

impl Figure for Valence {
    fn work(&self) -> u64 {
        (self.hi - self.lo + 1) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let rows = (self.lo..=self.hi)
            .into_par_iter()
            .map(|n| {
                let uni = LocalScheme::nurds(EdgeRatios::uniform(n).map_err(|e| ctx.err(e))?);
                let computed = classify_scheme(&uni)
                    .map_err(|e| ctx.err(e))?
                    .lambda1
                    .norm();
                let mut rng = SplitMix64::new(derive_seed(ctx.common.seed, &n.to_string()));
                let mut samples = Vec::with_capacity(self.samples);
                for _ in 0..self.samples {
                    let p: Vec<f64> = (0..n)
                        .map(|_| log_uniform(&mut rng, self.max_ratio))
                        .collect();
                    let q: Vec<f64> = (0..n)
                        .map(|_| log_uniform(&mut rng, self.max_ratio))
                        .collect();
                    let r = CornerIntervals::new(p, q)
                        .and_then(|k| k.ratios())
                        .map_err(|e| ctx.err(e))?;
                    let sub = classify_scheme(&LocalScheme::nurds(r)).map_err(|e| ctx.err(e))?;
                    samples.push((sub.lambda1.norm(), sub.class.name().to_owned()));
                }
                let min = samples.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
                let max = samples
                    .iter()
                    .map(|s| s.0)
                    .fold(f64::NEG_INFINITY, f64::max);
                ctx.tick(1);
                Ok(Row {
                    n,
                    closed: uniform_subdominant(n),
                    computed,
                    min,
                    max,
                    samples,
                })
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output {
            rows,
            max_ratio: self.max_ratio,
            samples: self.samples,
        }))
    }
}

struct Output {
    rows: Vec<Row>,
    max_ratio: f64,
    samples: usize,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "n",
                "closed_form",
                "computed_uniform",
                "abs_difference",
                "random_min",
                "random_max",
                "samples",
                "complex_pair_fraction",
            ],
        );
        let mut s = DataTable::new(Some("samples"), &["n", "sample", "abs_lambda1", "class"]);
        for r in &self.rows {
            let complex = r.samples.iter().filter(|s| s.1 == "complex_pair").count();
            t.push(vec![
                r.n.to_string(),
                num(r.closed),
                num(r.computed),
                num((r.closed - r.computed).abs()),
                if r.samples.is_empty() {
                    "NaN".into()
                } else {
                    num(r.min)
                },
                if r.samples.is_empty() {
                    "NaN".into()
                } else {
                    num(r.max)
                },
                r.samples.len().to_string(),
                if r.samples.is_empty() {
                    "NaN".into()
                } else {
                    num(complex as f64 / r.samples.len() as f64)
                },
            ]);
            for (i, (m, c)) in r.samples.iter().enumerate() {
                s.push(vec![r.n.to_string(), i.to_string(), num(*m), c.clone()]);
            }
        }
        vec![t, s]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let lo = self.rows.first().map_or(3, |r| r.n) as f64;
        let hi = self.rows.last().map_or(64, |r| r.n) as f64;
        let ymin = self
            .rows
            .iter()
            .flat_map(|r| {
                [
                    r.closed,
                    r.computed,
                    if r.samples.is_empty() { 1.0 } else { r.min },
                ]
            })
            .fold(0.75f64, f64::min);
        let ymin = (ymin * 20.0).floor() / 20.0 - 0.02;
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .build_cartesian_2d((lo - 1.0)..(hi + 1.0), ymin..0.8)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("valence n")
            .y_desc("|λ₁|  (subdominant eigenvalue modulus)")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.1))
            .y_label_formatter(&|y| format!("{y:.2}"))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        let band = viridis(0.6);
        let band_light = mix_white(band, 0.35);
        let with_samples: Vec<&Row> = self.rows.iter().filter(|r| !r.samples.is_empty()).collect();
        if !with_samples.is_empty() {
            let mut poly: Vec<(f64, f64)> =
                with_samples.iter().map(|r| (r.n as f64, r.max)).collect();
            poly.extend(with_samples.iter().rev().map(|r| (r.n as f64, r.min)));
            chart
                .draw_series(std::iter::once(Polygon::new(poly, band_light.filled())))
                .map_err(draw_err)?
                .label(format!(
                    "min–max over {} random knot sets per n (intervals in [1, {}])",
                    self.samples, self.max_ratio
                ))
                .legend(move |p| LegendGlyph::line(p, &th, band_light, 0).boxed());
            for sel in [0usize, 1] {
                let pts: Vec<(f64, f64)> = with_samples
                    .iter()
                    .map(|r| (r.n as f64, if sel == 0 { r.min } else { r.max }))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, viridis(0.35).stroke_width(lw)))
                    .map_err(draw_err)?;
            }
        }
        let (d, g) = dash(0, &th);
        chart
            .draw_series(DashedLineSeries::new(
                vec![(lo - 1.0, 0.75), (hi + 1.0, 0.75)],
                d,
                g,
                BLACK.stroke_width(lw),
            ))
            .map_err(draw_err)?
            .label("3/4 (Theorem 1 bound)")
            .legend(move |p| LegendGlyph::line(p, &th, BLACK, lw).dashed((d, g)));
        let fine: Vec<(f64, f64)> = (0..=400)
            .map(|k| {
                let x = lo + (hi - lo) * k as f64 / 400.0;
                (x, 0.5 + (std::f64::consts::TAU / x).cos() / 4.0)
            })
            .collect();
        chart
            .draw_series(LineSeries::new(fine, BLACK.stroke_width(lw)))
            .map_err(draw_err)?
            .label("uniform closed form 1/2 + cos(2π/n)/4")
            .legend(move |p| LegendGlyph::line(p, &th, BLACK, lw));
        let ms = th.marker;
        let dark = viridis(0.0);
        chart
            .draw_series(
                self.rows
                    .iter()
                    .map(|r| Marker::Ring.at((r.n as f64, r.computed), ms, dark)),
            )
            .map_err(draw_err)?
            .label("computed |λ₁|, uniform NURDS")
            .legend(move |p| LegendGlyph::line(p, &th, dark, 0).marker(Marker::Ring, ms));
        inner_legend(&mut chart, SeriesLabelPosition::LowerRight, &th)?;
        Ok(())
    }
}
