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
use crate::report::config::{check_analysis_budget, resolve_all, ConfigSpec, Configuration};
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    circle_points, clip_polyline, dash, draw_err, equal_aspect, legend_rows, legend_rows_height,
    mix_white, tick, titled, viridis, LegendGlyph, Marker, Theme,
};
use crate::schemes::Scheme;
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
    check_analysis_budget(fs, &p.configs, &configs)?;
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
        .collect::<Result<Vec<_>, crate::spectral::SpectralError>>()
        .map_err(|source| ReportError::Analysis {
            figure: title.to_owned(),
            source: source.into(),
        })?;
    let cols = panels.len().min(3);
    crate::report::backend::render_svg(size, &|area| {
        let refs: Vec<(&str, &(LocalAnalysis, Vec<Complex64>))> =
            panels.iter().map(|(l, a)| (l.as_str(), a)).collect();
        draw_spectra(area, title, size, cols, &refs)
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
        let refs: Vec<(&str, &(LocalAnalysis, Vec<Complex64>))> = self
            .panels
            .iter()
            .map(|(c, a)| (c.label.as_str(), a))
            .collect();
        draw_spectra(area, &common.title, common.size, self.columns, &refs)
    }
}

/// The part of the complex plane every panel shows (before the equal-aspect
/// widening): the circle |z| = 3/4 that holds every non-unit eigenvalue
/// (Theorem 1) and the dominant eigenvalue 1, with room for their markers.
pub const PANEL_BOX: ((f64, f64), (f64, f64)) = ((-0.82, 1.1), (-0.82, 0.82));

/// Draws the title, one panel per analysis and one legend shared by all
/// panels (below them).
fn draw_spectra(
    area: &Area<'_>,
    title: &str,
    size: (u32, u32),
    columns: usize,
    panels: &[(&str, &(LocalAnalysis, Vec<Complex64>))],
) -> Result<(), ReportError> {
    let th = Theme::for_size(size);
    let body = titled(area, title, &th)?;
    let cols = columns.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(cols).max(1);
    // Panel text scales with the panel, but never below 70% of the figure's
    // text size (paper readability wins over panel density).
    let (pw, ph) = (size.0 / cols as u32, size.1 / rows as u32);
    let side = pw.min(ph).max(size.0.min(size.1) * 70 / 100);
    let pt = Theme::for_size((side, side));
    let (bw, bh) = body.dim_in_pixel();
    let entries = legend_entries(&th);
    let legend_h = legend_rows_height(&body, bw, &entries, &th) + th.legend;
    let (panels_area, legend_area) = body.split_vertically(bh.saturating_sub(legend_h));
    for ((label, a), pa) in panels
        .iter()
        .zip(panels_area.split_evenly((rows, cols)).iter())
    {
        draw_panel(pa, label, a, &pt)?;
    }
    legend_rows(&legend_area.margin(th.legend / 2, 0, 0, 0), &entries, &th)?;
    Ok(())
}

/// The shared legend: circles and marker kinds (the same in every panel).
fn legend_entries(th: &Theme) -> Vec<(LegendGlyph, String)> {
    let lw = th.line;
    let grey = RGBColor(120, 120, 120);
    let ms = th.marker;
    vec![
        (
            LegendGlyph::line((0, 0), th, BLACK, lw).dashed(dash(0, th)),
            "|z| = 3/4 (Theorem 1 bound)".to_owned(),
        ),
        (
            LegendGlyph::line((0, 0), th, grey, lw).dashed(dash(1, th)),
            "|z| = 1/4".to_owned(),
        ),
        (
            LegendGlyph::line((0, 0), th, mix_white(grey, 0.5), 1),
            "|z| = 1".to_owned(),
        ),
        (
            LegendGlyph::line((0, 0), th, BLACK, 0).marker(Marker::Square, ms + 2),
            "λ₀ = 1".to_owned(),
        ),
        (
            LegendGlyph::line((0, 0), th, viridis(0.0), 0).marker(Marker::Diamond, ms * 2),
            "λ₁, λ₂ (subdominant)".to_owned(),
        ),
        (
            LegendGlyph::line((0, 0), th, viridis(0.45), 0).marker(Marker::Ring, ms),
            "other eigenvalues".to_owned(),
        ),
    ]
}

fn draw_panel(
    area: &Area<'_>,
    label: &str,
    (a, eig): &(LocalAnalysis, Vec<Complex64>),
    th: &Theme,
) -> Result<(), ReportError> {
    // Two caption lines: the configuration, then its class and |λ₁|.
    let area = area.margin(th.tick / 2, 0, 0, 0);
    let area = area.titled(label, th.font(th.label)).map_err(draw_err)?;
    let info = format!(
        "{}, |λ₁| = {}",
        a.subdominant.class.name().replace('_', " "),
        tick((a.subdominant.lambda1.norm() * 1e4).round() / 1e4)
    );
    let area = area.titled(&info, th.font(th.legend)).map_err(draw_err)?;
    let (w, h) = area.dim_in_pixel();
    let xl = th.label * 2 + th.tick;
    let yl = th.label * 2 + th.tick * 3;
    let m = th.tick / 2;
    let plot = (
        w.saturating_sub(yl + 2 * m).max(10),
        h.saturating_sub(xl + 2 * m).max(10),
    );
    // Equal aspect: circles must look round.
    // The box holds every eigenvalue (with room for its marker), so none
    // is clipped even for schemes outside Theorem 1.
    let pad = 0.08;
    let ((mut x0, mut x1), (mut y0, mut y1)) = PANEL_BOX;
    for z in eig.iter().filter(|z| z.re.is_finite() && z.im.is_finite()) {
        x0 = x0.min(z.re - pad);
        x1 = x1.max(z.re + pad);
        y0 = y0.min(z.im - pad);
        y1 = y1.max(z.im + pad);
    }
    let (xr, yr) = equal_aspect(plot, (x0, x1), (y0, y1));
    let mut chart = ChartBuilder::on(&area)
        .margin(m as i32)
        .x_label_area_size(xl)
        .y_label_area_size(yl)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .x_desc("Re λ")
        .y_desc("Im λ")
        .x_labels(5)
        .y_labels(5)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(th.font(th.tick))
        .axis_desc_style(th.font(th.label))
        .light_line_style(WHITE)
        .bold_line_style(BLACK.mix(0.08))
        .draw()
        .map_err(draw_err)?;
    let lw = th.line;
    let grey = RGBColor(120, 120, 120);
    // Circles clipped to the plot area (never drawn along its frame).
    let circle = |r: f64, n: usize| clip_polyline(&circle_points(r, n), xr, yr);
    for piece in circle(1.0, 240) {
        chart
            .draw_series(LineSeries::new(piece, mix_white(grey, 0.5).stroke_width(1)))
            .map_err(draw_err)?;
    }
    let (d1, g1) = dash(0, th);
    for piece in circle(0.75, 240) {
        chart
            .draw_series(DashedLineSeries::new(piece, d1, g1, BLACK.stroke_width(lw)))
            .map_err(draw_err)?;
    }
    let (d2, g2) = dash(1, th);
    for piece in circle(0.25, 160) {
        chart
            .draw_series(DashedLineSeries::new(piece, d2, g2, grey.stroke_width(lw)))
            .map_err(draw_err)?;
    }
    let ms = th.marker;
    let other = viridis(0.45);
    let others: Vec<(f64, f64)> = eig.iter().skip(3).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(others.iter().map(|&p| Marker::Ring.at(p, ms, other)))
        .map_err(draw_err)?;
    let sub_col = viridis(0.0);
    let sub: Vec<(f64, f64)> = eig.iter().skip(1).take(2).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(sub.iter().map(|&p| Marker::Diamond.at(p, ms * 2, sub_col)))
        .map_err(draw_err)?;
    let dom: Vec<(f64, f64)> = eig.iter().take(1).map(|z| (z.re, z.im)).collect();
    chart
        .draw_series(dom.iter().map(|&p| Marker::Square.at(p, ms + 2, BLACK)))
        .map_err(draw_err)?;
    Ok(())
}
