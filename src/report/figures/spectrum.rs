//! `kind = "spectrum"`: eigenvalues of S_n in the complex plane, one panel per
//! configuration, with the circles |z| = 3/4 (Theorem 1: every non-unit
//! eigenvalue lies inside, math doc section 4) and |z| = 1/4, and the
//! subdominant pair lambda_1, lambda_2 highlighted.
//!
//! ```toml
//! [[figure]]
//! kind = "spectrum"
//! columns = 3                 # panels per row (default: up to 3)
//! configs = [ { scheme = "cc-variant", valence = 5 }, ... ]   # 1 to 12 panels
//! ```

use super::{eigenvalues, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::report::backend::Area;
use crate::report::config::{resolve_all, ConfigSpec, Configuration};
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    circle_points, dash, draw_err, titled, viridis, LegendGlyph, Marker, Theme,
};
use crate::scheme::Scheme;
use crate::spectral::{analyze, AnalyzeOptions, LocalAnalysis};
use num_complex::Complex64;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Most panels in one spectrum figure (beyond this they are unreadable).
pub const MAX_PANELS: usize = 12;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "spectrum",
    default_title: "Spectra of the local subdivision matrix S_n",
    summary:
        "eigenvalues of S_n in the complex plane with |z| = 3/4, |z| = 1/4 and the subdominant pair",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    configs: Spanned<Vec<ConfigSpec>>,
    columns: Option<Spanned<usize>>,
}

struct Spectrum {
    configs: Vec<Configuration>,
    columns: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let configs = resolve_all(fs, &p.configs, Some(MAX_PANELS))?;
    let count = configs.len();
    let columns = match &p.columns {
        None => count.min(3),
        Some(c) if (1..=MAX_PANELS).contains(c.get_ref()) => (*c.get_ref()).min(count),
        Some(c) => {
            return Err(fs.error_at(
                c,
                "columns",
                format!(
                    "columns must be between 1 and {MAX_PANELS}, got {}",
                    c.get_ref()
                ),
            ))
        }
    };
    Ok(Box::new(Spectrum { configs, columns }))
}

impl Figure for Spectrum {
    fn work(&self) -> u64 {
        self.configs.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let analyses = self
            .configs
            .par_iter()
            .map(|c| {
                let a = analyze(&*c.scheme, &AnalyzeOptions::default())
                    .map(|a| {
                        let e = eigenvalues(&a);
                        (a, e)
                    })
                    .map_err(|e| ctx.err(e));
                ctx.tick(1);
                a
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Box::new(Output {
            panels: self.configs.iter().cloned().zip(analyses).collect(),
            columns: self.columns,
        }))
    }
}

struct Output {
    panels: Vec<(Configuration, (LocalAnalysis, Vec<Complex64>))>,
    columns: usize,
}

/// The spectrum figure of any [`Scheme`]s, as an SVG document: one panel per
/// scheme (at most [`MAX_PANELS`]) labelled by [`Scheme::label`], the same
/// drawing as `kind = "spectrum"` in a report spec (math doc section 12: the
/// figure a scheme defined outside the crate gets).
///
/// ```
/// use subdiv_lab::report::figures::spectrum::spectrum_svg;
/// use subdiv_lab::schemes::LocalScheme;
/// let s = LocalScheme::<f64>::catmull_clark(5).unwrap();
/// let svg = spectrum_svg(&[&s], (640, 480), "Catmull-Clark").unwrap();
/// assert!(svg.starts_with("<svg"));
/// ```
pub fn spectrum_svg(
    schemes: &[&dyn Scheme],
    size: (u32, u32),
    title: &str,
) -> Result<String, ReportError> {
    if schemes.is_empty() || schemes.len() > MAX_PANELS {
        return Err(ReportError::Spec {
            at: None,
            key: None,
            message: format!("give 1 to {MAX_PANELS} schemes, got {}", schemes.len()),
        });
    }
    let panels = schemes
        .iter()
        .map(|s| {
            let a = analyze(*s, &AnalyzeOptions::default())?;
            let e = eigenvalues(&a);
            Ok((s.label(), (a, e)))
        })
        .collect::<crate::Result<Vec<_>>>()
        .map_err(|source| ReportError::Analysis {
            figure: title.to_owned(),
            source,
        })?;
    let cols = panels.len().min(3);
    let rows = panels.len().div_ceil(cols);
    crate::report::backend::render_svg(size, &|area| {
        let th = Theme::for_size(size);
        let body = titled(area, title, &th)?;
        let (pw, ph) = (size.0 / cols as u32, size.1 / rows as u32);
        let side = pw.min(ph).max(size.0.min(size.1) * 70 / 100);
        let panel_theme = Theme::for_size((side, side));
        for ((label, a), pa) in panels.iter().zip(body.split_evenly((rows, cols)).iter()) {
            draw_panel(pa, label, a, &panel_theme)?;
        }
        Ok(())
    })
}

/// Role of eigenvalue `index` (in the analysis' sorted order).
fn role(index: usize) -> &'static str {
    match index {
        0 => "dominant",
        1 | 2 => "subdominant",
        _ => "other",
    }
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "config", "label", "class", "index", "re", "im", "modulus", "role",
            ],
        );
        for (i, (c, a)) in self.panels.iter().enumerate() {
            for (k, z) in a.1.iter().enumerate() {
                t.push(vec![
                    i.to_string(),
                    c.label.clone(),
                    a.0.subdominant.class.name().to_owned(),
                    k.to_string(),
                    num(z.re),
                    num(z.im),
                    num(z.norm()),
                    role(k).into(),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols);
        // Panel text scales with the panel, but never below 70% of the figure's
        // text size (paper readability wins over panel density).
        let (pw, ph) = (common.size.0 / cols as u32, common.size.1 / rows as u32);
        let side = pw.min(ph).max(common.size.0.min(common.size.1) * 70 / 100);
        let panel_theme = Theme::for_size((side, side));
        let areas = body.split_evenly((rows, cols));
        for ((c, a), pa) in self.panels.iter().zip(areas.iter()) {
            draw_panel(pa, &c.label, a, &panel_theme)?;
        }
        Ok(())
    }
}

fn draw_panel(
    area: &Area<'_>,
    label: &str,
    (a, eig): &(LocalAnalysis, Vec<Complex64>),
    th: &Theme,
) -> Result<(), ReportError> {
    let (w, h) = area.dim_in_pixel();
    let xl = th.label * 2 + th.tick;
    let yl = th.label * 2 + th.tick * 3;
    let cap = th.label * 3;
    let pw = (w.saturating_sub(yl + th.tick * 2)).max(10) as f64;
    let ph = (h.saturating_sub(xl + cap + th.tick)).max(10) as f64;
    // Equal aspect: circles must look round.
    let (x0, x1) = (-0.85, 1.12);
    let half_y = (x1 - x0) * ph / pw / 2.0;
    let mut chart = ChartBuilder::on(area)
        .caption(label, th.font(th.label))
        .margin(th.tick as i32 / 2)
        .x_label_area_size(xl)
        .y_label_area_size(yl)
        .build_cartesian_2d(x0..x1, -half_y..half_y)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .x_desc("Re λ")
        .y_desc("Im λ")
        .x_labels(5)
        .y_labels(5)
        .label_style(th.font(th.tick))
        .axis_desc_style(th.font(th.label))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw()
        .map_err(draw_err)?;
    let lw = th.line;
    let th2 = *th;
    let grey = RGBColor(120, 120, 120);
    chart
        .draw_series(LineSeries::new(
            circle_points(1.0, 240),
            grey.mix(0.5).stroke_width(1),
        ))
        .map_err(draw_err)?;
    let (d1, g1) = dash(0, th);
    chart
        .draw_series(DashedLineSeries::new(
            circle_points(0.75, 240),
            d1,
            g1,
            BLACK.stroke_width(lw),
        ))
        .map_err(draw_err)?
        .label("|z| = 3/4")
        .legend(move |p| LegendGlyph::line(p, &th2, BLACK, lw).dashed((d1, g1)));
    let (d2, g2) = dash(1, th);
    chart
        .draw_series(DashedLineSeries::new(
            circle_points(0.25, 160),
            d2,
            g2,
            grey.stroke_width(lw),
        ))
        .map_err(draw_err)?
        .label("|z| = 1/4")
        .legend(move |p| LegendGlyph::line(p, &th2, grey, lw).dashed((d2, g2)));
    let ms = th.marker;
    let other = viridis(0.45);
    let others: Vec<(f64, f64)> = eig.iter().skip(3).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(others.iter().map(|&p| Marker::Ring.at(p, ms, other)))
        .map_err(draw_err)?
        .label("other eigenvalues")
        .legend(move |p| LegendGlyph::line(p, &th2, other, 0).marker(Marker::Ring, ms));
    let sub_col = viridis(0.0);
    let sub: Vec<(f64, f64)> = eig.iter().skip(1).take(2).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(sub.iter().map(|&p| Marker::Diamond.at(p, ms * 2, sub_col)))
        .map_err(draw_err)?
        .label(format!(
            "λ₁, λ₂ ({}): |λ₁| = {:.4}",
            a.subdominant.class.name().replace('_', " "),
            a.subdominant.lambda1.norm()
        ))
        .legend(move |p| LegendGlyph::line(p, &th2, sub_col, 0).marker(Marker::Diamond, ms * 2));
    let dom: Vec<(f64, f64)> = eig.iter().take(1).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(dom.iter().map(|&p| Marker::Square.at(p, ms + 2, BLACK)))
        .map_err(draw_err)?
        .label("λ₀ = 1")
        .legend(move |p| LegendGlyph::line(p, &th2, BLACK, 0).marker(Marker::Square, ms + 2));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(th.font(th.legend))
        .legend_area_size(th.legend_area())
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .margin(th.legend as i32 / 3)
        .draw()
        .map_err(draw_err)?;
    Ok(())
}
