//! `kind = "curvature"`: measured curvature of the limit surface on the ring
//! of level `k` around an extraordinary point, against `k`, next to the
//! predicted rate `(mu / lambda^2)^k` (math doc sections 13.2 and 13.4).
//!
//! The Catmull-Clark family (no `scheme`, or `scheme = "catmull-clark"` /
//! `"adjustable-cc"`) is drawn from [`crate::curvature::measured::measure`]
//! (limit points of the refined patch nets, then a fitted quadric); every
//! other built-in scheme (`nurds` with optional `ratios` or `knots`,
//! `doo-sabin`, `cc-variant`, `loop`) from
//! [`crate::curvature::measured_scheme::measure_scheme`] (the level-`k`
//! control points of the second-order net, a quadric with a constant term; the
//! rate there is `mu / lambda_2^2`, which is `mu / lambda^2` except for a
//! split subdominant pair). The scheme choice goes through the shared
//! validator [`crate::schemes::choice`]. Per valence, the largest
//! principal curvature (solid, markers) and the prediction
//! `kappa_K (mu / lambda^2)^(k - K)` anchored at the last level `K` (dashed).
//! The CSV has every level's Gaussian curvature `K`, mean curvature `H`, the
//! half difference of the principal curvatures, the largest one and the
//! prediction (for schemes other than the Catmull-Clark family the column
//! `c` is replaced by `scheme`, the configuration's label, and
//! `ring_radius` is the radius of the level-`k` net).
//!
//! ```toml
//! [[figure]]
//! kind = "curvature"
//! valences = [3, 4, 5, 8]   # default; each in 3..=16
//! c = 0.5                   # shape parameter in [0, 1] (default 1/2: Catmull-Clark)
//! levels = 16               # 1..=24 (default 16)
//!
//! [[figure]]
//! kind = "curvature"
//! scheme = "loop"           # any built-in scheme (default: the Catmull-Clark family)
//! valences = [3, 5, 7]
//!
//! [[figure]]
//! kind = "curvature"
//! scheme_file = "my-cc.toml"  # or a scheme file (read beside the spec); no knots or c
//! valences = [3, 5]
//!
//! [[figure]]
//! kind = "curvature"
//! scheme = "nurds"
//! ratios = [0.3, 0.6, 0.5]  # or knots = [[p, q], ..]; fixes the valence
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::curvature::measured::{measure, MeasuredLevel};
use crate::curvature::measured_scheme::measure_scheme;
use crate::knots::{CornerIntervals, EdgeRatios};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, series_color, titled, LegendGlyph, Marker, Theme,
};
use crate::schemes::choice::{validate, Choice, ChoiceError};
use crate::schemes::SchemeKind;
use crate::schemes::{LocalScheme, Scheme};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted.
pub const MAX_VALENCE: usize = 16;
/// Largest number of levels accepted: the heights (of order `mu^k`) carry
/// the rounding of coordinates of order `lambda^k`, a relative
/// `eps (lambda / mu)^k` ([`crate::curvature::measured`]: `5e-7` at `k = 24`,
/// `n = 3`, `c = 1/2`), which stays far below the plotted changes; beyond
/// about 30 levels it reaches them there.
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
    scheme: Option<Spanned<String>>,
    scheme_file: Option<Spanned<String>>,
    valences: Option<Spanned<Vec<usize>>>,
    ratios: Option<Spanned<Vec<f64>>>,
    knots: Option<Spanned<Vec<[f64; 2]>>>,
    c: Option<Spanned<f64>>,
    levels: Option<Spanned<usize>>,
}

/// A configuration with its legend label.
type Labelled = (Box<dyn Scheme>, String);

/// What is measured.
enum Measured {
    /// The Catmull-Clark family at shape parameter `c`, per valence.
    CcFamily { valences: Vec<usize>, c: f64 },
    /// Any other built-in scheme, or a scheme file's: one configuration per
    /// valence, with its legend label.
    Scheme(Vec<Labelled>),
}

struct CurvatureFigure {
    what: Measured,
    levels: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let valences = match &p.valences {
        None => None,
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
            Some(list.clone())
        }
    };
    let c = match &p.c {
        None => None,
        Some(c) if (0.0..=1.0).contains(c.get_ref()) => Some(*c.get_ref()),
        Some(c) => {
            return Err(fs.error_at(
                c,
                "c",
                format!("c must be between 0 and 1, got {}", c.get_ref()),
            ))
        }
    };
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 16)?;
    if let Some(f) = &p.scheme_file {
        let what = Measured::Scheme(file_configurations(fs, f, &p, valences)?);
        return Ok(Box::new(CurvatureFigure { what, levels }));
    }
    let kind = match &p.scheme {
        None => None,
        Some(s) => Some((s, scheme_kind(fs, s, &p)?)),
    };
    let what = match kind {
        // No scheme: the Catmull-Clark family at c (default 1/2), as before
        // the key existed.
        None | Some((_, SchemeKind::CatmullClark | SchemeKind::AdjustableCc)) => {
            Measured::CcFamily {
                valences: valences.unwrap_or_else(|| vec![3, 4, 5, 8]),
                c: c.unwrap_or(0.5),
            }
        }
        Some((at, kind)) => Measured::Scheme(configurations(fs, at, kind, &p, valences)?),
    };
    Ok(Box::new(CurvatureFigure { what, levels }))
}

/// The scheme through the shared rules ([`crate::schemes::choice`]); the
/// error names the key of the wrong part.
fn scheme_kind(
    fs: &FigureSpec<'_>,
    s: &Spanned<String>,
    p: &Params,
) -> Result<SchemeKind, ReportError> {
    let choice = Choice {
        name: s.get_ref(),
        knots: p.ratios.is_some() || p.knots.is_some(),
        c: p.c.is_some(),
    };
    validate(&choice).map_err(|e| match (&e, &p.c, &p.ratios, &p.knots) {
        (ChoiceError::TakesNoC(_), Some(c), _, _) => fs.error_at(c, "c", e.to_string()),
        (ChoiceError::TakesNoKnots(_), _, Some(r), _) => fs.error_at(r, "ratios", e.to_string()),
        (ChoiceError::TakesNoKnots(_), _, _, Some(k)) => fs.error_at(k, "knots", e.to_string()),
        (ChoiceError::NeedsC(_), _, _, _) => fs.error_at(s, "c", e.to_string()),
        _ => fs.error_at(s, "scheme", e.to_string()),
    })
}

/// A scheme file's configurations, one per valence (default 3, 4, 5, 8):
/// without `scheme`, knot data or `c`.
fn file_configurations(
    fs: &FigureSpec<'_>,
    path: &Spanned<String>,
    p: &Params,
    valences: Option<Vec<usize>>,
) -> Result<Vec<Labelled>, ReportError> {
    let refused = [
        ("scheme", p.scheme.as_ref().map(|s| s.span())),
        ("ratios", p.ratios.as_ref().map(|s| s.span())),
        ("knots", p.knots.as_ref().map(|s| s.span())),
        ("c", p.c.as_ref().map(|s| s.span())),
    ];
    if let Some((name, Some(span))) = refused.iter().find(|(_, s)| s.is_some()) {
        return Err(fs.error_at(
            &Spanned::new(span.clone(), ()),
            name,
            format!("{name} is not taken with scheme_file"),
        ));
    }
    let file = fs.scheme_file(path, "scheme_file")?;
    valences
        .unwrap_or_else(|| vec![3, 4, 5, 8])
        .into_iter()
        .map(|n| {
            let s = file
                .at(n)
                .map_err(|e| fs.error_at(path, "scheme_file", e.to_string()))?;
            let label = s.label();
            Ok((Box::new(s) as Box<dyn Scheme>, label))
        })
        .collect()
}

/// One configuration per valence; `ratios` or `knots` (NURDS) fix the
/// valence, and `valences`, if given, must be that one.
fn configurations(
    fs: &FigureSpec<'_>,
    at: &Spanned<String>,
    kind: SchemeKind,
    p: &Params,
    valences: Option<Vec<usize>>,
) -> Result<Vec<Labelled>, ReportError> {
    let ratios = match (&p.ratios, &p.knots) {
        (Some(_), Some(k)) => {
            return Err(fs.error_at(k, "knots", "give at most one of ratios and knots"))
        }
        (Some(r), None) => Some(
            EdgeRatios::new(r.get_ref().clone())
                .map_err(|e| fs.error_at(r, "ratios", e.to_string()))?,
        ),
        (None, Some(k)) => {
            let pp: Vec<f64> = k.get_ref().iter().map(|x| x[0]).collect();
            let qq: Vec<f64> = k.get_ref().iter().map(|x| x[1]).collect();
            let ci =
                CornerIntervals::new(pp, qq).map_err(|e| fs.error_at(k, "knots", e.to_string()))?;
            Some(
                ci.ratios()
                    .map_err(|e| fs.error_at(k, "knots", e.to_string()))?,
            )
        }
        (None, None) => None,
    };
    // An error about the knot data, at whichever key gave it.
    let at_knots = |msg: String| match (&p.ratios, &p.knots) {
        (Some(r), _) => fs.error_at(r, "ratios", msg),
        (_, Some(k)) => fs.error_at(k, "knots", msg),
        _ => fs.error_at(at, "scheme", msg),
    };
    let valences = match &ratios {
        Some(r) => {
            let n = r.valence();
            if !(3..=MAX_VALENCE).contains(&n) {
                return Err(at_knots(format!(
                    "the curvature figure takes valences 3..={MAX_VALENCE}, got {n} knot values"
                )));
            }
            if let (Some(v), Some(key)) = (&valences, &p.valences) {
                if v[..] != [n] {
                    return Err(fs.error_at(
                        key,
                        "valences",
                        format!("valences {v:?} do not match the {n} knot values given"),
                    ));
                }
            }
            vec![n]
        }
        None => valences.unwrap_or_else(|| vec![3, 4, 5, 8]),
    };
    valences
        .iter()
        .map(|&n| {
            let s = LocalScheme::from_kind_with_c(kind, n, ratios.clone(), None)
                .map_err(|e| fs.error_at(at, "scheme", e.to_string()))?;
            let label = s.legend_label("");
            Ok((Box::new(s) as Box<dyn Scheme>, label))
        })
        .collect()
}

impl Figure for CurvatureFigure {
    fn work(&self) -> u64 {
        match &self.what {
            Measured::CcFamily { valences, .. } => valences.len() as u64,
            Measured::Scheme(s) => s.len() as u64,
        }
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let seed = ctx.common.seed;
        let runs = match &self.what {
            Measured::CcFamily { valences, c } => valences
                .par_iter()
                .map(|&n| {
                    let m = measure(n, *c, self.levels, seed).map_err(|e| ctx.err(e))?;
                    ctx.tick(1);
                    Ok(Run {
                        n: m.n,
                        column: num(m.c),
                        legend: format!("n = {}", m.n),
                        predicted_rate: m.predicted_rate,
                        levels: m.levels,
                    })
                })
                .collect::<Result<Vec<_>, ReportError>>()?,
            Measured::Scheme(schemes) => schemes
                .par_iter()
                .map(|(s, label)| {
                    let m = measure_scheme(&**s, self.levels, seed).map_err(|e| ctx.err(e))?;
                    ctx.tick(1);
                    let label = label.clone();
                    Ok(Run {
                        n: m.n,
                        column: label.clone(),
                        legend: label,
                        predicted_rate: m.predicted_rate,
                        levels: m.levels,
                    })
                })
                .collect::<Result<Vec<_>, ReportError>>()?,
        };
        let column = match self.what {
            Measured::CcFamily { .. } => "c",
            Measured::Scheme(_) => "scheme",
        };
        Ok(Box::new(Output { runs, column }))
    }
}

/// One measured configuration.
struct Run {
    n: usize,
    /// The value of the second CSV column (`c` or the scheme's label).
    column: String,
    /// The legend's text before the rate.
    legend: String,
    predicted_rate: f64,
    levels: Vec<MeasuredLevel>,
}

struct Output {
    runs: Vec<Run>,
    /// The second CSV column's name.
    column: &'static str,
}

impl Output {
    /// The prediction anchored at the last level.
    fn predicted(m: &Run, k: usize) -> f64 {
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
                self.column,
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
                    m.column.clone(),
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
                    "{} (mu/lambda^2 = {:.4})",
                    m.legend, m.predicted_rate
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
