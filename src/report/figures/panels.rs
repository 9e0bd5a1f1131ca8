//! Side-by-side panels of projected meshes, shared by `mesh-picture` and
//! `crease-picture`: the faces' data table, one square frame for all panels
//! (the union of their bounds, so both panels share one scale), and the
//! shaded or wireframe faces drawn in painter's order
//! ([`crate::mesh::projection`] sorts and shades them).

use super::{num, DataTable};
use crate::mesh::projection::Projected;
use crate::report::backend::{AnyBackend, Area};
use crate::report::error::ReportError;
use crate::report::plot::{draw_err, titled, Theme};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// The chart of one panel: screen coordinates of the projection.
pub(super) type PanelChart<'a, 'b> =
    ChartContext<'a, AnyBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// How the faces are drawn.
#[derive(Clone, Copy)]
pub(super) struct FaceStyle {
    /// White faces (a wireframe) instead of head-light shading.
    pub wireframe: bool,
    /// Opacity of the black face outlines.
    pub edge_alpha: f64,
}

/// The faces' table: one row per face corner, `panel, face, corner, x, y, shade`.
pub(super) fn faces_table<'p>(panels: impl IntoIterator<Item = &'p Projected>) -> DataTable {
    let mut t = DataTable::new(None, &["panel", "face", "corner", "x", "y", "shade"]);
    for (i, p) in panels.into_iter().enumerate() {
        for f in &p.faces {
            for (k, q) in f.points.iter().enumerate() {
                t.push(vec![
                    i.to_string(),
                    f.face.to_string(),
                    k.to_string(),
                    num(q[0]),
                    num(q[1]),
                    num(f.shade),
                ]);
            }
        }
    }
    t
}

/// Draws the titled figure: one panel per `(caption, projection)`, left to
/// right, in one frame, faces in `style`; `overlay(i, chart)` then draws on
/// panel `i` (sharp edges, for example).
pub(super) fn draw_panels(
    area: &Area<'_>,
    title: &str,
    th: &Theme,
    panels: &[(&str, &Projected)],
    style: FaceStyle,
    mut overlay: impl FnMut(usize, &mut PanelChart<'_, '_>) -> Result<(), ReportError>,
) -> Result<(), ReportError> {
    let body = titled(area, title, th)?;
    // one scale for all panels: the union of the bounds, squared up
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for (_, p) in panels {
        b[0] = b[0].min(p.bounds[0]);
        b[1] = b[1].max(p.bounds[1]);
        b[2] = b[2].min(p.bounds[2]);
        b[3] = b[3].max(p.bounds[3]);
    }
    let half = 0.55 * (b[1] - b[0]).max(b[3] - b[2]).max(1e-12);
    let (cx, cy) = ((b[0] + b[1]) / 2.0, (b[2] + b[3]) / 2.0);
    let areas = body.split_evenly((1, panels.len()));
    let edge = BLACK.mix(style.edge_alpha);
    for (i, ((label, p), a)) in panels.iter().zip(areas.iter()).enumerate() {
        let (w, h) = a.dim_in_pixel();
        let aspect = w as f64 / h.max(1) as f64;
        let (hx, hy) = if aspect >= 1.0 {
            (half * aspect, half)
        } else {
            (half, half / aspect)
        };
        let mut chart = ChartBuilder::on(a)
            .margin(th.tick as i32)
            .caption(label, th.font(th.label))
            .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)
            .map_err(draw_err)?;
        for f in &p.faces {
            let pts: Vec<(f64, f64)> = f.points.iter().map(|q| (q[0], q[1])).collect();
            let fill = if style.wireframe {
                WHITE
            } else {
                let g = |base: f64| (base * f.shade).round().clamp(0.0, 255.0) as u8;
                RGBColor(g(150.0), g(185.0), g(235.0))
            };
            chart
                .draw_series(std::iter::once(Polygon::new(pts.clone(), fill.filled())))
                .map_err(draw_err)?;
            let mut closed = pts;
            closed.push(closed[0]);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    closed,
                    edge.stroke_width(1),
                )))
                .map_err(draw_err)?;
        }
        overlay(i, &mut chart)?;
    }
    Ok(())
}
