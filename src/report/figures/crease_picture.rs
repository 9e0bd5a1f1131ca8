//! `kind = "crease-picture"`: a shipped open mesh with crease and corner
//! tags (OpenSubdiv's `t crease` / `t corner` lines, math doc section 17)
//! before and after refinement, side by side, shaded from both sides (an
//! open surface shows its back), with the sharp edges drawn over it: red the
//! infinitely sharp ones (the boundary among them), orange the semi-sharp
//! ones, whose sharpness decays by one per level (uniform creasing), so
//! that after `L` levels only the creases sharper than `L` are still drawn.
//!
//! Catmull-Clark refines `grid_quads`, Loop `grid_tris`, both with
//! OpenSubdiv's `edge-and-corner` boundary interpolation
//! ([`crate::mesh::sharp`]). The tables are the projected faces (as
//! `mesh-picture`'s) and `<id>-edges.csv`, the projected sharp edges with
//! their sharpness.
//!
//! ```toml
//! [[figure]]
//! kind = "crease-picture"
//! mesh = "grid_quads"   # grid_quads (Catmull-Clark) or grid_tris (Loop); default grid_quads
//! levels = 3            # 1..=4: the right panel (default 3)
//! ```

use super::panels::{draw_panels, faces_table, FaceStyle};
use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::mesh::obj::parse_obj_data;
use crate::mesh::projection::{project_sharp, Projected, View};
use crate::mesh::sharp::rules::{is_infinite, Boundary, Creasing, SdcScheme};
use crate::mesh::sharp::SharpMesh;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{draw_err, Theme};
use plotters::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest accepted number of levels (the right panel stays below 25k faces).
pub const MAX_LEVELS: usize = 4;

/// The shipped tagged meshes: name, OBJ text (with its `t` lines), scheme.
const MESHES: [(&str, &str, SdcScheme); 2] = [
    (
        "grid_quads",
        include_str!("../../../analysis/meshes/sharp/grid_quads.obj"),
        SdcScheme::CatmullClark,
    ),
    (
        "grid_tris",
        include_str!("../../../analysis/meshes/sharp/grid_tris.obj"),
        SdcScheme::Loop,
    ),
];

/// The view: from the front left, above the grid.
const VIEW: View = View {
    azimuth_deg: -60.0,
    elevation_deg: 35.0,
};

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "crease-picture",
    default_title: "An open mesh with creases and corners before and after refinement",
    summary: "shaded picture of a shipped tagged open mesh and its refinement, sharp edges drawn",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    mesh: Option<Spanned<String>>,
    levels: Option<Spanned<usize>>,
}

struct CreasePicture {
    name: &'static str,
    obj: &'static str,
    scheme: SdcScheme,
    levels: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (name, text, scheme) = match &p.mesh {
        None => MESHES[0],
        Some(m) => MESHES
            .into_iter()
            .find(|(n, _, _)| *n == m.get_ref().as_str())
            .ok_or_else(|| {
                fs.error_at(
                    m,
                    "mesh",
                    format!(
                        "unknown tagged mesh {:?} (shipped: grid_quads, grid_tris)",
                        m.get_ref()
                    ),
                )
            })?,
    };
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 3)?;
    Ok(Box::new(CreasePicture {
        name,
        obj: text,
        scheme,
        levels,
    }))
}

/// A projected mesh and its projected sharp edges (`[x0, y0, x1, y1]`, sharpness).
struct Panel {
    label: String,
    faces: Projected,
    sharp: Vec<([f64; 4], f32)>,
}

fn panel(label: String, mesh: &SharpMesh) -> Panel {
    let faces = project_sharp(mesh, &VIEW);
    let (right, up, _) = VIEW.axes();
    let screen = |p: [f64; 3]| {
        (
            p[0] * right[0] + p[1] * right[1] + p[2] * right[2],
            p[0] * up[0] + p[1] * up[1] + p[2] * up[2],
        )
    };
    let sharp = mesh
        .edge_sharpness()
        .iter()
        .enumerate()
        .filter(|(_, s)| **s > 0.0)
        .map(|(e, &s)| {
            let [a, b] = mesh.edge_vertices(e);
            let (p, q) = (screen(mesh.positions()[a]), screen(mesh.positions()[b]));
            ([p.0, p.1, q.0, q.1], s)
        })
        .collect();
    Panel {
        label,
        faces,
        sharp,
    }
}

impl Figure for CreasePicture {
    fn work(&self) -> u64 {
        2
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        // the shipped meshes are valid (the figure's test draws both); an
        // error here is reported, never a panic
        let data = parse_obj_data(self.obj).map_err(|e| ctx.err(e))?;
        let mesh = SharpMesh::new(
            data.positions,
            &data.faces,
            &data.tags,
            Boundary::EdgeAndCorner,
        )
        .map_err(|e| ctx.err(e))?;
        let before = panel(format!("{}: {} faces", self.name, mesh.face_count()), &mesh);
        ctx.tick(1);
        let refined = mesh
            .refine_levels(self.scheme, Creasing::Uniform, self.levels)
            .map_err(|e| ctx.err(e))?;
        let after = panel(
            format!(
                "{} x{}: {} faces",
                crate::boundary::scheme_name(self.scheme),
                self.levels,
                refined.face_count()
            ),
            &refined,
        );
        ctx.tick(1);
        Ok(Box::new(Output {
            panels: vec![before, after],
        }))
    }
}

struct Output {
    panels: Vec<Panel>,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut e = DataTable::new(
            Some("edges"),
            &["panel", "x0", "y0", "x1", "y1", "sharpness"],
        );
        for (i, p) in self.panels.iter().enumerate() {
            for (s, sharpness) in &p.sharp {
                e.push(vec![
                    i.to_string(),
                    num(s[0]),
                    num(s[1]),
                    num(s[2]),
                    num(s[3]),
                    num(f64::from(*sharpness)),
                ]);
            }
        }
        vec![faces_table(self.panels.iter().map(|p| &p.faces)), e]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let panels: Vec<(&str, &Projected)> = self
            .panels
            .iter()
            .map(|p| (p.label.as_str(), &p.faces))
            .collect();
        let style = FaceStyle {
            wireframe: false,
            edge_alpha: 0.35,
        };
        let infinite = RGBColor(200, 30, 30);
        let semi = RGBColor(240, 140, 20);
        // sharp edges on top (an orthographic picture of a gently curved
        // grid: drawing them last keeps every crease visible)
        draw_panels(area, &common.title, &th, &panels, style, |i, chart| {
            for (s, sharpness) in &self.panels[i].sharp {
                let col = if is_infinite(*sharpness) {
                    infinite
                } else {
                    semi
                };
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(s[0], s[1]), (s[2], s[3])],
                        col.stroke_width(th.line + 1),
                    )))
                    .map_err(draw_err)?;
            }
            Ok(())
        })
    }
}
