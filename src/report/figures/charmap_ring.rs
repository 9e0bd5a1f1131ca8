//! `kind = "charmap"`: the characteristic ring of each configuration (math doc
//! section 7) drawn in the plane, with the next levels (scaled / rotated
//! copies), patches coloured, and a Jacobian-sign overlay.
//!
//! The data come from [`crate::charmap::plot_data`]: the `3n` biquadratic ring
//! patches `A_i`, `B_i`, `C_i` on the (orthonormalised) subdominant planar
//! basis, oriented so that the Jacobian is positive; level `k` is the ring
//! mapped `k` times by the restriction `M` of `S_n` to the planar subspace.
//! Each patch outline is filled (colour by patch kind: `A`, `B`, `C`, or
//! `Omega1..3` in the Catmull-Clark family, lighter for deeper levels); the
//! overlay marks sample points of the ring (level 0) where `sigma J > 0`
//! (small grey dots) and `sigma J <= 0` (large red crosses, a fold). One
//! legend below the panels explains the colours and marks. The verdict is written under each panel (short form:
//! "TPC" = tangent-plane continuous, non-standard eigenstructure). The CSV
//! tables hold exactly the plotted data (outlines, signed samples of all
//! levels, verdicts).
//!
//! ```toml
//! [[figure]]
//! kind = "charmap"
//! levels = 3                  # ring + 2 further levels (1..=6, default 3)
//! samples = 6                 # Jacobian samples per patch side (2..=20, default 6)
//! columns = 2                 # panels per row (default: up to 3)
//! configs = [ { scheme = "doo-sabin", valence = 5 }, ... ]   # 1 to 6 panels
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::charmap::figure::RingPlot;
use crate::charmap::AnyPatchId;
use crate::charmap::{plot_data, CharmapReport};
use crate::report::backend::Area;
use crate::report::config::{check_analysis_budget, resolve_all, ConfigSpec, Configuration};
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    draw_err, equal_aspect, legend_rows, legend_rows_height, mix_white, titled, viridis,
    LegendGlyph, Marker, Theme,
};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Most panels in one figure.
pub const MAX_PANELS: usize = 6;
/// Most levels drawn.
pub const MAX_LEVELS: usize = 6;
/// Most Jacobian samples per patch side.
pub const MAX_SAMPLES: usize = 20;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "charmap",
    default_title: "Characteristic rings and their Jacobian sign",
    summary: "characteristic ring (3n biquadratic patches) and further levels in the plane, Jacobian-sign overlay, verdict",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    configs: Spanned<Vec<ConfigSpec>>,
    levels: Option<Spanned<usize>>,
    samples: Option<Spanned<usize>>,
    columns: Option<Spanned<usize>>,
}

struct Charmap {
    configs: Vec<Configuration>,
    levels: usize,
    samples: usize,
    columns: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let configs = resolve_all(fs, &p.configs, Some(MAX_PANELS))?;
    check_analysis_budget(fs, &p.configs, &configs)?;
    let count = configs.len();
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 3)?;
    let samples = bounded(fs, &p.samples, "samples", 2, MAX_SAMPLES, 6)?;
    let columns = bounded(fs, &p.columns, "columns", 1, MAX_PANELS, count.min(3))?.min(count);
    Ok(Box::new(Charmap {
        configs,
        levels,
        samples,
        columns,
    }))
}

impl Figure for Charmap {
    fn work(&self) -> u64 {
        self.configs.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let panels = self
            .configs
            .par_iter()
            .map(|c| {
                let (report, plot) =
                    plot_data(&*c.scheme, self.levels, self.samples).map_err(|e| ctx.err(e))?;
                ctx.tick(1);
                Ok(Panel {
                    config: c.clone(),
                    report,
                    plot,
                })
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output {
            panels,
            columns: self.columns,
        }))
    }
}

struct Panel {
    config: Configuration,
    report: CharmapReport<AnyPatchId>,
    plot: Option<RingPlot>,
}

struct Output {
    panels: Vec<Panel>,
    columns: usize,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut outline = DataTable::new(
            None,
            &[
                "config", "label", "level", "patch", "kind", "sector", "point", "x", "y",
            ],
        );
        let mut signs = DataTable::new(
            Some("jacobian"),
            &["config", "level", "patch", "x", "y", "sign"],
        );
        let mut verdicts = DataTable::new(
            Some("verdict"),
            &[
                "config",
                "label",
                "structure",
                "regular",
                "min_jacobian_coeff",
                "winding_number",
                "verdict",
            ],
        );
        for (i, p) in self.panels.iter().enumerate() {
            let r = &p.report;
            verdicts.push(vec![
                i.to_string(),
                p.config.label.clone(),
                r.structure.map_or("none", |s| s.as_str()).to_owned(),
                r.regular()
                    .map_or("undecided".to_owned(), |b| b.to_string()),
                r.min_jacobian_coeff().map_or("NaN".to_owned(), num),
                r.winding_number
                    .map_or("undecided".to_owned(), |w| w.to_string()),
                r.verdict.to_string(),
            ]);
            let Some(plot) = &p.plot else { continue };
            for pp in &plot.patches {
                for (k, q) in pp.outline.iter().enumerate() {
                    outline.push(vec![
                        i.to_string(),
                        p.config.label.clone(),
                        pp.level.to_string(),
                        pp.patch.to_string(),
                        pp.patch.kind_name(),
                        pp.patch.sector().to_string(),
                        k.to_string(),
                        num(q[0]),
                        num(q[1]),
                    ]);
                }
                for (q, s) in &pp.samples {
                    signs.push(vec![
                        i.to_string(),
                        pp.level.to_string(),
                        pp.patch.to_string(),
                        num(q[0]),
                        num(q[1]),
                        s.to_string(),
                    ]);
                }
            }
        }
        vec![outline, signs, verdicts]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols);
        let (pw, ph) = (common.size.0 / cols as u32, common.size.1 / rows as u32);
        let side = pw.min(ph).max(common.size.0.min(common.size.1) * 70 / 100);
        let panel_theme = Theme::for_size((side, side));
        // One legend for all panels, below them: patch kinds and sample signs.
        let entries = self.legend_entries(&th);
        let (bw, bh) = body.dim_in_pixel();
        let legend_h = legend_rows_height(&body, bw, &entries, &th) + th.legend;
        let (panels_area, legend_area) = body.split_vertically(bh.saturating_sub(legend_h));
        let areas = panels_area.split_evenly((rows, cols));
        for (p, pa) in self.panels.iter().zip(areas.iter()) {
            draw_panel(pa, p, &panel_theme)?;
        }
        legend_rows(&legend_area.margin(th.legend / 2, 0, 0, 0), &entries, &th)?;
        Ok(())
    }
}

/// Fill colour of a patch: by its kind (slot within the sector), lighter on
/// finer levels. Three viridis samples far apart in lightness, so the kinds
/// stay apart in greyscale.
fn patch_color(slot: usize, level: usize) -> RGBColor {
    let base = viridis([0.12, 0.5, 0.85][slot % 3]);
    mix_white(base, 0.75 - 0.35 * (level as f64 / 4.0).min(1.0))
}

/// The level whose colour the legend boxes show (the ring itself).
const LEGEND_LEVEL: usize = 0;

impl Output {
    /// Legend: one box per patch kind (names from the panels' patches, e.g.
    /// `A` or `Omega1`), the sample dots and crosses, the centre.
    fn legend_entries(&self, th: &Theme) -> Vec<(LegendGlyph, String)> {
        let mut names: [Vec<String>; 3] = Default::default();
        for p in &self.panels {
            if let Some(plot) = &p.plot {
                for pp in &plot.patches {
                    let s = pp.patch.slot() % 3;
                    let name = pp.patch.kind_name();
                    if !names[s].contains(&name) {
                        names[s].push(name);
                    }
                }
            }
        }
        let place = ["at (E_i, P_i)", "at (E_i, P_i+1)", "at (V_i, P_i)"];
        let mut out: Vec<(LegendGlyph, String)> = names
            .iter()
            .enumerate()
            .filter(|(_, n)| !n.is_empty())
            .map(|(s, n)| {
                let ds = n.iter().any(|x| ["A", "B", "C"].contains(&x.as_str()));
                let text = if ds {
                    format!("{} patches {}", n.join(" / "), place[s])
                } else {
                    format!("{} patches", n.join(" / "))
                };
                (
                    LegendGlyph::line((0, 0), th, patch_color(s, LEGEND_LEVEL), 0).boxed(),
                    text,
                )
            })
            .collect();
        let dot = (th.marker / 2).max(2);
        out.push((
            LegendGlyph::line((0, 0), th, RGBColor(115, 115, 115), 0).marker(Marker::Circle, dot),
            "Jacobian > 0 at a sample".to_owned(),
        ));
        out.push((
            LegendGlyph::line((0, 0), th, RGBColor(220, 30, 30), 0)
                .marker(Marker::Cross, th.marker),
            "Jacobian ≤ 0 at a sample".to_owned(),
        ));
        out.push((
            LegendGlyph::line((0, 0), th, BLACK, 0).marker(Marker::Plus, th.marker),
            "centre; finer levels lighter".to_owned(),
        ));
        out
    }
}

fn draw_panel(area: &Area<'_>, p: &Panel, th: &Theme) -> Result<(), ReportError> {
    let (_, h) = area.dim_in_pixel();
    // verdict line at the bottom of the panel, label as the caption
    let verdict = short_verdict(&p.report);
    area.draw_text(
        &verdict,
        &th.font(th.tick),
        (th.tick as i32, h as i32 - 2 * th.tick as i32),
    )
    .map_err(draw_err)?;
    let Some(plot) = &p.plot else {
        area.titled(&p.config.label, th.font(th.label))
            .map_err(draw_err)?;
        return Ok(());
    };
    let area = area.margin(0, 2 * th.tick, 0, 0);
    let area = area
        .titled(&p.config.label, th.font(th.tick))
        .map_err(draw_err)?;
    let mut r = 0.0f64;
    for pp in plot.patches.iter().filter(|q| q.level == 0) {
        for q in &pp.outline {
            r = r.max(q[0].abs()).max(q[1].abs());
        }
    }
    let r = if r > 0.0 { r * 1.05 } else { 1.0 };
    let m = th.tick / 2;
    let (w, h) = area.dim_in_pixel();
    // Equal aspect from the exact plot-area size (no axes: only the margin).
    let (xr, yr) = equal_aspect(
        (
            w.saturating_sub(2 * m).max(1),
            h.saturating_sub(2 * m).max(1),
        ),
        (-r, r),
        (-r, r),
    );
    let mut chart = ChartBuilder::on(&area)
        .margin(m as i32)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(draw_err)?;
    for pp in plot.patches.iter().rev() {
        let fill = patch_color(pp.patch.slot(), pp.level);
        let pts: Vec<(f64, f64)> = pp.outline.iter().map(|q| (q[0], q[1])).collect();
        chart
            .draw_series(std::iter::once(Polygon::new(pts.clone(), fill.filled())))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                pts,
                BLACK.mix(0.6).stroke_width(1),
            )))
            .map_err(draw_err)?;
    }
    let dot = (th.marker / 3).max(1);
    for pp in plot.patches.iter().filter(|q| q.level == 0) {
        for (q, s) in &pp.samples {
            if *s > 0 {
                chart
                    .draw_series(std::iter::once(Circle::new(
                        (q[0], q[1]),
                        dot,
                        RGBColor(115, 115, 115).filled(),
                    )))
                    .map_err(draw_err)?;
            } else {
                chart
                    .draw_series(std::iter::once(Marker::Cross.at(
                        (q[0], q[1]),
                        th.marker,
                        RGBColor(220, 30, 30),
                    )))
                    .map_err(draw_err)?;
            }
        }
    }
    chart
        .draw_series(std::iter::once(Marker::Plus.at(
            (0.0, 0.0),
            th.marker,
            BLACK,
        )))
        .map_err(draw_err)?;
    Ok(())
}

/// The verdict, shortened to fit under a panel (the CSV has the full text).
fn short_verdict(r: &CharmapReport<AnyPatchId>) -> String {
    use crate::charmap::Verdict;
    let w = r
        .winding_number
        .map_or(String::new(), |w| format!(", winding {w}"));
    match &r.verdict {
        Verdict::C1Standard => format!("C1 (standard; Reif){w}"),
        Verdict::TangentPlaneContinuous { structure } => {
            format!("TPC ({}){w}", structure.as_str())
        }
        Verdict::NotRegular => "NOT regular".to_owned(),
        Verdict::NotInjective { winding } => format!("NOT injective (winding {winding})"),
        Verdict::Indeterminate { .. } => "indeterminate".to_owned(),
        Verdict::NoCharacteristicMap { class, .. } => format!("no map ({class})"),
    }
}
