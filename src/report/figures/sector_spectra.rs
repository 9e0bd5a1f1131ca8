//! `kind = "sector-spectra"`: the leading eigenvalues of the local matrix at
//! a boundary vertex against the number of faces `K` of its sector, for the
//! standard rules and for Biermann-Levin-Zorin's (math doc section 18).
//!
//! Drawn from [`crate::boundary::analysis::analyze_sector`] (the honest
//! class and the sector characteristic-map certificate): `lambda_1` solid,
//! `lambda_2` dashed, `|lambda_3|` dotted, one colour per rule set, and the
//! line `1/2`, the eigenvalue of the boundary curve. Points where the class
//! is not `standard` or the characteristic map is not certified C1 are
//! ringed: the standard rules keep `lambda_1 = lambda_2 = 1/2` only on the
//! regular sector and lose it (`lambda_1 > 1/2`, the map collapsing the
//! boundary) as `K` grows, BLZ keep it for every `K >= 2`. The CSV has one
//! row per `(rules, K)`.
//!
//! ```toml
//! [[figure]]
//! kind = "sector-spectra"
//! scheme = "catmull-clark"   # catmull-clark | loop
//! max_faces = 12             # K = 1..=max_faces, in 2..=32 (default 12)
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::boundary::analysis::analyze_sector;
use crate::boundary::charmap::MAX_CHARMAP_FACES;
use crate::boundary::{RuleSet, SectorConfig, VertexKind};
use crate::mesh::sharp::rules::SdcScheme;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, series_color, titled, LegendGlyph, Marker, Theme,
};
use crate::sweep::eval::class_text;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "sector-spectra",
    default_title: "Boundary vertices: leading eigenvalues against the faces K of the sector",
    summary: "lambda_1, lambda_2, |lambda_3| of the boundary local matrix against K, standard and BLZ rules",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    scheme: Spanned<String>,
    max_faces: Option<Spanned<usize>>,
}

struct SectorSpectra {
    scheme: SdcScheme,
    max_faces: usize,
}

const RULES: [RuleSet; 2] = [RuleSet::Standard, RuleSet::Blz];

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let scheme = match p.scheme.get_ref().as_str() {
        "catmull-clark" => SdcScheme::CatmullClark,
        "loop" => SdcScheme::Loop,
        other => {
            return Err(fs.error_at(
                &p.scheme,
                "scheme",
                format!("scheme must be \"catmull-clark\" or \"loop\", got {other:?}"),
            ))
        }
    };
    let max_faces = bounded(fs, &p.max_faces, "max_faces", 2, MAX_CHARMAP_FACES, 12)?;
    Ok(Box::new(SectorSpectra { scheme, max_faces }))
}

/// One `(rules, K)` point.
struct Point {
    rules: RuleSet,
    k: usize,
    lambda1: f64,
    lambda2: f64,
    abs_lambda3: f64,
    class: String,
    charmap: &'static str,
}

impl Point {
    fn flagged(&self) -> bool {
        self.class != "standard" || self.charmap != "c1"
    }
}

impl Figure for SectorSpectra {
    fn work(&self) -> u64 {
        (RULES.len() * self.max_faces) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let items: Vec<(RuleSet, usize)> = RULES
            .iter()
            .flat_map(|&r| (1..=self.max_faces).map(move |k| (r, k)))
            .collect();
        let points = items
            .par_iter()
            .map(|&(rules, k)| {
                let c = SectorConfig::new(self.scheme, VertexKind::Boundary, &[k], None, rules)
                    .map_err(|e| ctx.err(e))?;
                let a = analyze_sector(&c).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                let s = &a.subdominant;
                Ok(Point {
                    rules,
                    k,
                    lambda1: s.lambda1.norm(),
                    lambda2: s.lambda2.norm(),
                    abs_lambda3: s.abs_lambda3,
                    class: class_text(&s.class),
                    charmap: a.charmap.verdict.as_str(),
                })
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output { points }))
    }
}

struct Output {
    points: Vec<Point>,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "rules",
                "faces",
                "lambda1",
                "lambda2",
                "abs_lambda3",
                "class",
                "charmap",
            ],
        );
        for p in &self.points {
            t.push(vec![
                p.rules.name().to_owned(),
                p.k.to_string(),
                num(p.lambda1),
                num(p.lambda2),
                num(p.abs_lambda3),
                p.class.clone(),
                p.charmap.to_owned(),
            ]);
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let kmax = self.points.iter().map(|p| p.k).max().unwrap_or(2) as f64;
        let ymax = self.points.iter().map(|p| p.lambda1).fold(0.5f64, f64::max);
        let ymin = self
            .points
            .iter()
            .map(|p| p.abs_lambda3)
            .fold(0.5f64, f64::min);
        let span = (ymax - ymin).max(0.05);
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            // headroom for the legend (three rows)
            .build_cartesian_2d(
                0.5f64..kmax + 0.5,
                (ymin - 0.06 * span)..(ymax + 0.45 * span),
            )
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("faces K of the boundary sector")
            .y_desc("eigenvalue modulus")
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.1))
            .x_labels(kmax as usize)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.2}"))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        let grey = RGBColor(90, 90, 90);
        chart
            .draw_series(LineSeries::new(
                [(0.5, 0.5), (kmax + 0.5, 0.5)],
                grey.mix(0.6).stroke_width(1),
            ))
            .map_err(draw_err)?;
        let (d, g) = dash(0, &th);
        let (dd, dg) = (lw.max(1) * 2, lw.max(1) * 3);
        for (i, rules) in RULES.iter().enumerate() {
            let col = series_color(i, RULES.len());
            let pts: Vec<&Point> = self.points.iter().filter(|p| p.rules == *rules).collect();
            let line = |f: fn(&Point) -> f64| -> Vec<(f64, f64)> {
                pts.iter().map(|p| (p.k as f64, f(p))).collect()
            };
            let name = match rules {
                RuleSet::Standard => "standard rules",
                RuleSet::Blz => "BLZ rules",
            };
            chart
                .draw_series(LineSeries::new(line(|p| p.lambda1), col.stroke_width(lw)))
                .map_err(draw_err)?
                .label(format!("{name}: λ₁ (solid), λ₂ (dashed), |λ₃| (dotted)"))
                .legend(move |p| LegendGlyph::line(p, &th, col, lw));
            chart
                .draw_series(DashedLineSeries::new(
                    line(|p| p.lambda2),
                    d,
                    g,
                    col.stroke_width(lw),
                ))
                .map_err(draw_err)?;
            chart
                .draw_series(DashedLineSeries::new(
                    line(|p| p.abs_lambda3),
                    dd,
                    dg,
                    col.mix(0.7).stroke_width(lw.max(2) - 1),
                ))
                .map_err(draw_err)?;
            chart
                .draw_series(
                    pts.iter()
                        .map(|p| Marker::nth(i).at((p.k as f64, p.lambda1), th.marker, col)),
                )
                .map_err(draw_err)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.flagged())
                        .map(|p| Marker::Ring.at((p.k as f64, p.lambda1), th.marker * 2, col)),
                )
                .map_err(draw_err)?;
        }
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(draw_err)?
            .label("ring: class not standard or map not certified C1; grey: 1/2")
            .legend(move |p| LegendGlyph::line(p, &th, grey, lw).marker(Marker::Ring, th.marker));
        inner_legend(&mut chart, SeriesLabelPosition::UpperLeft, &th)?;
        Ok(())
    }
}
