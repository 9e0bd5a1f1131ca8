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
use super::panels::{draw_panels, faces_table, FaceStyle};
use super::{bounded, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::mesh::projection::{project, Projected, View};
use crate::mesh::rules::MeshRules;
use crate::mesh::Mesh;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::Theme;
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
        vec![faces_table(self.panels.iter().map(|(_, p)| p))]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let panels: Vec<(&str, &Projected)> =
            self.panels.iter().map(|(l, p)| (l.as_str(), p)).collect();
        let style = FaceStyle {
            wireframe: self.wireframe,
            edge_alpha: if self.wireframe { 0.8 } else { 0.55 },
        };
        draw_panels(area, &common.title, &th, &panels, style, |_, _| Ok(()))
    }
}
