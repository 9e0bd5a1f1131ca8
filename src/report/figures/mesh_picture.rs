//! `kind = "mesh-picture"`: a built-in closed mesh before and after
//! refinement, side by side, as an orthographic shaded (or wireframe) picture.
//!
//! Projection, back-face culling, painter's-order sorting and head-light
//! shading come from `crate::mesh::projection`; both panels share one scale.
//!
//! ```toml
//! [[figure]]
//! kind = "mesh-picture"
//! mesh = "truncated_icosahedron"   # cube, tetrahedron, icosahedron, truncated_icosahedron, torus
//! scheme = "nurds"                 # nurds, doo-sabin, cc-variant
//! levels = 2                       # 1..=4: the right panel
//! random_knots = 4.0               # NURDS only (default: uniform)
//! azimuth = 30.0                   # degrees (default 30)
//! elevation = 25.0                 # degrees (default 25)
//! style = "shaded"                 # shaded (default) or wireframe
//! ```

use super::mesh_convergence::{built_in_mesh, mesh_scheme};
use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::mesh::projection::{project, Projected, View};
use crate::mesh::rules::MeshRules;
use crate::mesh::Mesh;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{draw_err, titled, Theme};
use plotters::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest accepted number of levels for a picture (faces stay below ~50k).
pub const MAX_LEVELS: usize = 4;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "mesh-picture",
    default_title: "A mesh before and after refinement",
    summary: "orthographic shaded or wireframe picture of a built-in mesh and its refinement",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    mesh: Spanned<String>,
    scheme: Option<Spanned<String>>,
    scheme_file: Option<Spanned<String>>,
    levels: Option<Spanned<usize>>,
    random_knots: Option<Spanned<f64>>,
    azimuth: Option<Spanned<f64>>,
    elevation: Option<Spanned<f64>>,
    style: Option<Spanned<String>>,
}

struct MeshPicture {
    mesh: Mesh,
    rules: Box<dyn MeshRules>,
    levels: usize,
    view: View,
    wireframe: bool,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (rules, _, _) = mesh_scheme(
        fs,
        p.scheme.as_ref(),
        p.scheme_file.as_ref(),
        p.random_knots.as_ref(),
    )?;
    let mesh = built_in_mesh(fs, &p.mesh, p.random_knots.as_ref())?;
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 2)?;
    let angle = |a: &Option<Spanned<f64>>, key: &str, default: f64, lim: f64| match a {
        None => Ok(default),
        Some(v) if v.get_ref().is_finite() && v.get_ref().abs() <= lim => Ok(*v.get_ref()),
        Some(v) => Err(fs.error_at(
            v,
            key,
            format!(
                "{key} must lie in [-{lim}, {lim}] degrees, got {}",
                v.get_ref()
            ),
        )),
    };
    let view = View {
        azimuth_deg: angle(&p.azimuth, "azimuth", 30.0, 360.0)?,
        elevation_deg: angle(&p.elevation, "elevation", 25.0, 90.0)?,
    };
    let wireframe = match &p.style {
        None => false,
        Some(s) if s.get_ref() == "shaded" => false,
        Some(s) if s.get_ref() == "wireframe" => true,
        Some(s) => {
            return Err(fs.error_at(
                s,
                "style",
                format!(
                    "style must be \"shaded\" or \"wireframe\", got {:?}",
                    s.get_ref()
                ),
            ))
        }
    };
    Ok(Box::new(MeshPicture {
        mesh,
        rules,
        levels,
        view,
        wireframe,
    }))
}

impl Figure for MeshPicture {
    fn work(&self) -> u64 {
        2
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let before = project(&self.mesh, &self.view);
        ctx.tick(1);
        let refined = self
            .rules
            .refine_levels(&self.mesh, self.levels)
            .map_err(|e| ctx.err(e))?;
        let after = project(&refined, &self.view);
        ctx.tick(1);
        Ok(Box::new(Output {
            panels: vec![
                (format!("input: {} faces", self.mesh.face_count()), before),
                (
                    format!(
                        "{} x{}: {} faces",
                        self.rules.name(),
                        self.levels,
                        refined.face_count()
                    ),
                    after,
                ),
            ],
            wireframe: self.wireframe,
        }))
    }
}

struct Output {
    panels: Vec<(String, Projected)>,
    wireframe: bool,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(None, &["panel", "face", "corner", "x", "y", "shade"]);
        for (i, (_, p)) in self.panels.iter().enumerate() {
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
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        // one scale for both panels: the union of the bounds, squared up
        let mut b = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for (_, p) in &self.panels {
            b[0] = b[0].min(p.bounds[0]);
            b[1] = b[1].max(p.bounds[1]);
            b[2] = b[2].min(p.bounds[2]);
            b[3] = b[3].max(p.bounds[3]);
        }
        let half = 0.55 * (b[1] - b[0]).max(b[3] - b[2]).max(1e-12);
        let (cx, cy) = ((b[0] + b[1]) / 2.0, (b[2] + b[3]) / 2.0);
        let panels = body.split_evenly((1, self.panels.len()));
        for ((label, p), panel) in self.panels.iter().zip(panels.iter()) {
            let (w, h) = panel.dim_in_pixel();
            let aspect = w as f64 / h.max(1) as f64;
            let (hx, hy) = if aspect >= 1.0 {
                (half * aspect, half)
            } else {
                (half, half / aspect)
            };
            let mut chart = ChartBuilder::on(panel)
                .margin(th.tick as i32)
                .caption(label, th.font(th.label))
                .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)
                .map_err(draw_err)?;
            let edge = BLACK.mix(if self.wireframe { 0.8 } else { 0.55 });
            for f in &p.faces {
                let pts: Vec<(f64, f64)> = f.points.iter().map(|q| (q[0], q[1])).collect();
                let fill = if self.wireframe {
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
        }
        Ok(())
    }
}
