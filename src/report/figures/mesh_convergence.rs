//! `kind = "mesh-convergence"`: every extraordinary face of a refined mesh
//! shrinking to its limit point, on a log scale.
//!
//! A built-in closed mesh ([`crate::mesh::generators`]) is refined `levels`
//! times with the mesh-level scheme ([`crate::mesh::refine`]); for each
//! extraordinary face the distance `max_i |P_i - F|` to its limit point `F`
//! is recorded at every level ([`crate::mesh::limit::refine_with_stats`]) and
//! plotted relative to its first value against the number of steps `j` since
//! the face appeared (face EPs at level 0, vertex EPs at level 1). Drawn with
//! the Theorem 1 bound `(3/4)^j` (math doc section 5) and, per face, the
//! asymptotic rate `C |lambda_1|^j` of its local matrix (fitted at the last
//! level).
//!
//! ```toml
//! [[figure]]
//! kind = "mesh-convergence"
//! mesh = "truncated_icosahedron"   # cube, tetrahedron, icosahedron, truncated_icosahedron, torus
//! scheme = "nurds"                 # nurds, doo-sabin, cc-variant
//! levels = 6                       # 1..=7
//! random_knots = 4.0               # NURDS only: intervals log-uniform in [1, s] (default: uniform)
//! max_faces = 6                    # faces plotted (default 6), chosen to cover distinct valences
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::mesh::builtin::mesh_rules;
use crate::mesh::generators;
use crate::mesh::limit::convergence_series;
use crate::mesh::rules::MeshRules;
use crate::mesh::Mesh;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    dash, draw_err, inner_legend, series_color, titled, LegendGlyph, Marker, Theme,
};
use crate::rng::{log_uniform, SplitMix64};
use crate::schemes::choice::{validate, Choice, ChoiceError};
use crate::spectral::classify_scheme;
use plotters::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest accepted number of levels (the truncated icosahedron at 7 levels has 2.9M faces).
pub const MAX_LEVELS: usize = 7;
/// Relative distances below this are not plotted: rounding of coordinates of
/// size ~1 dominates them.
pub const RELATIVE_FLOOR: f64 = 1e-13;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "mesh-convergence",
    default_title: "Extraordinary faces of a refined mesh converging to their limit points",
    summary: "max_i |P_i - F| of every extraordinary face of a refined mesh against the step, with (3/4)^j and |lambda_1|^j",
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
    max_faces: Option<Spanned<usize>>,
}

/// A built-in mesh by name, with optional random knots; shared with `mesh-picture`.
pub(crate) fn built_in_mesh(
    fs: &FigureSpec<'_>,
    name: &Spanned<String>,
    random_knots: Option<&Spanned<f64>>,
) -> Result<Mesh, ReportError> {
    let mut mesh = generators::shipped()
        .into_iter()
        .find(|(n, _)| *n == name.get_ref().as_str())
        .map(|(_, m)| m)
        .ok_or_else(|| {
            let names: Vec<&str> = generators::shipped().iter().map(|(n, _)| *n).collect();
            fs.error_at(
                name,
                "mesh",
                format!(
                    "unknown mesh {:?} (built-in: {})",
                    name.get_ref(),
                    names.join(", ")
                ),
            )
        })?;
    if let Some(s) = random_knots {
        let v = *s.get_ref();
        if !(v.is_finite() && v >= 1.0) {
            return Err(fs.error_at(
                s,
                "random_knots",
                format!("random_knots must be >= 1, got {v}"),
            ));
        }
        let mut rng = SplitMix64::new(fs.seed());
        let k = (0..mesh.half_edge_count())
            .map(|_| log_uniform(&mut rng, v))
            .collect();
        mesh.set_knots(k)
            .map_err(|e| fs.error_at(s, "random_knots", e.to_string()))?;
    }
    Ok(mesh)
}

/// A mesh figure's rules, with the value and key that name its scheme.
pub(crate) type MeshScheme<'s> = (Box<dyn MeshRules>, &'s Spanned<String>, &'static str);

/// The scheme of a mesh figure and its mesh rules, with the value and key
/// later errors about the scheme name: exactly one of `scheme` (a built-in,
/// through the shared rules, [`crate::schemes::choice`]: `random_knots` is
/// knot data, and the one dispatch, [`crate::mesh::builtin::mesh_rules`];
/// mesh figures have no shape parameter) and `scheme_file` (a scheme file's
/// rules, [`crate::mesh::user::file_rules`]; no knots).
pub(crate) fn mesh_scheme<'s>(
    fs: &FigureSpec<'_>,
    scheme: Option<&'s Spanned<String>>,
    scheme_file: Option<&'s Spanned<String>>,
    random_knots: Option<&Spanned<f64>>,
) -> Result<MeshScheme<'s>, ReportError> {
    let s = match (scheme, scheme_file) {
        (Some(s), None) => s,
        (None, Some(f)) => {
            if let Some(r) = random_knots {
                return Err(fs.error_at(
                    r,
                    "random_knots",
                    "random_knots is not taken with scheme_file (a scheme file's rules use no knot intervals)",
                ));
            }
            let file = fs.scheme_file(f, "scheme_file")?;
            return Ok((crate::mesh::user::file_rules(file), f, "scheme_file"));
        }
        (Some(_), Some(f)) => {
            return Err(fs.error_at(
                f,
                "scheme_file",
                "give either scheme or scheme_file, not both",
            ))
        }
        (None, None) => return Err(fs.error("give scheme (a built-in name) or scheme_file")),
    };
    let choice = Choice {
        name: s.get_ref(),
        knots: random_knots.is_some(),
        c: false,
    };
    let kind = validate(&choice).map_err(|e| match (&e, random_knots) {
        (ChoiceError::TakesNoKnots(_), Some(r)) => fs.error_at(r, "random_knots", e.to_string()),
        (ChoiceError::NeedsC(_), _) => fs.error_at(
            s,
            "scheme",
            format!("{e}, which mesh figures do not take (use `subdiv-lab subdivide --c`)"),
        ),
        _ => fs.error_at(s, "scheme", e.to_string()),
    })?;
    let rules = mesh_rules(kind, None).map_err(|e| fs.error_at(s, "scheme", e.to_string()))?;
    Ok((rules, s, "scheme"))
}

struct MeshConvergence {
    mesh: Mesh,
    mesh_name: String,
    rules: Box<dyn MeshRules>,
    levels: usize,
    max_faces: usize,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let (rules, at, key) = mesh_scheme(
        fs,
        p.scheme.as_ref(),
        p.scheme_file.as_ref(),
        p.random_knots.as_ref(),
    )?;
    if !rules.has_level_stats() {
        return Err(fs.error_at(
            at,
            key,
            format!("scheme {} has no per-level statistics of extraordinary faces, which mesh-convergence plots (use mesh-picture)", rules.name()),
        ));
    }
    let mesh = built_in_mesh(fs, &p.mesh, p.random_knots.as_ref())?;
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 6)?;
    let max_faces = bounded(fs, &p.max_faces, "max_faces", 1, 32, 6)?;
    if !(0..mesh.face_count()).any(|f| mesh.is_extraordinary_face(f))
        && !(0..mesh.vertex_count()).any(|v| mesh.valence(v) != 4)
    {
        return Err(fs.error_at(
            &p.mesh,
            "mesh",
            "this mesh has no extraordinary faces or vertices",
        ));
    }
    Ok(Box::new(MeshConvergence {
        mesh,
        mesh_name: p.mesh.get_ref().clone(),
        rules,
        levels,
        max_faces,
    }))
}

/// One face's curve.
#[derive(Clone, Debug)]
struct Curve {
    face: usize,
    valence: usize,
    first_level: usize,
    distances: Vec<f64>,
    lambda1: f64,
    fit: f64,
}

impl Curve {
    fn label(&self) -> String {
        let origin = if self.first_level == 0 {
            "face"
        } else {
            "vertex"
        };
        format!("{origin} EP {} (n = {})", self.face, self.valence)
    }
    fn relative(&self) -> Vec<(usize, f64)> {
        let d0 = self.distances[0];
        self.distances
            .iter()
            .enumerate()
            .map(|(j, d)| (j, d / d0))
            .filter(|p| p.1 >= RELATIVE_FLOOR)
            .collect()
    }
}

impl MeshConvergence {
    /// The error of rules without per-face statistics or configurations
    /// (refused when the spec is parsed, so not reached).
    fn no_faces(&self) -> crate::Error {
        crate::Error::NotApplicable {
            scheme: self.rules.name().to_owned(),
            operation: "the statistics and local configurations of extraordinary faces",
        }
    }
}

impl Figure for MeshConvergence {
    fn work(&self) -> u64 {
        self.levels as u64 + 1
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let (last, stats) = self
            .rules
            .refine_with_stats(&self.mesh, self.levels)
            .ok_or_else(|| ctx.err(self.no_faces()))?
            .map_err(|e| ctx.err(e))?;
        ctx.tick(self.levels as u64);
        let mut series = convergence_series(&stats);
        series.retain(|s| s.distances.len() >= 2);
        // choose faces: one per (origin, valence) first, then fill in order
        let mut chosen: Vec<usize> = Vec::new();
        let mut seen = std::collections::BTreeSet::new();
        for (i, s) in series.iter().enumerate() {
            if seen.insert((s.first_level, s.valence)) && chosen.len() < self.max_faces {
                chosen.push(i);
            }
        }
        for i in 0..series.len() {
            if chosen.len() >= self.max_faces {
                break;
            }
            if !chosen.contains(&i) {
                chosen.push(i);
            }
        }
        chosen.sort_unstable();
        let mut curves = Vec::new();
        for i in chosen {
            let s = &series[i];
            let local = self
                .rules
                .face_scheme(&last, s.face)
                .ok_or_else(|| ctx.err(self.no_faces()))?
                .map_err(|e| ctx.err(e))?;
            let lambda1 = classify_scheme(&*local)
                .map_err(|e| ctx.err(e))?
                .lambda1
                .norm();
            let mut c = Curve {
                face: s.face,
                valence: s.valence,
                first_level: s.first_level,
                distances: s.distances.clone(),
                lambda1,
                fit: 1.0,
            };
            let rel = c.relative();
            let (j, d) = *rel.last().unwrap_or(&(0, 1.0));
            c.fit = if lambda1 > 0.0 {
                d / lambda1.powi(j as i32)
            } else {
                1.0
            };
            curves.push(c);
        }
        ctx.tick(1);
        Ok(Box::new(Output {
            curves,
            levels: self.levels,
            title_note: format!(
                "{}, {}, {} levels",
                self.mesh_name,
                self.rules.name(),
                self.levels
            ),
        }))
    }
}

struct Output {
    curves: Vec<Curve>,
    levels: usize,
    title_note: String,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "face",
                "valence",
                "first_level",
                "level",
                "j",
                "distance",
                "relative_distance",
                "bound_3_4_pow_j",
                "abs_lambda1",
                "rate_line",
            ],
        );
        for c in &self.curves {
            for (j, rel) in c.relative() {
                t.push(vec![
                    c.face.to_string(),
                    c.valence.to_string(),
                    c.first_level.to_string(),
                    (c.first_level + j).to_string(),
                    j.to_string(),
                    num(c.distances[j]),
                    num(rel),
                    num(0.75f64.powi(j as i32)),
                    num(c.lambda1),
                    num(c.fit * c.lambda1.powi(j as i32)),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let ymin = self
            .curves
            .iter()
            .flat_map(|c| c.relative().into_iter().map(|p| p.1))
            .fold(1.0f64, f64::min)
            .max(RELATIVE_FLOOR)
            / 2.0;
        let jmax = self.levels as f64;
        let mut chart = ChartBuilder::on(&body)
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4)
            .caption(&self.title_note, th.font(th.label))
            .build_cartesian_2d(0.0..jmax, (ymin..1.5f64).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("steps j since the face appeared")
            .y_desc("max_i |P_i − F| relative to j = 0")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .label_style(th.font(th.tick))
            .axis_desc_style(th.font(th.label))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_err)?;
        let lw = th.line;
        let bound: Vec<(f64, f64)> = (0..=self.levels)
            .map(|j| (j as f64, 0.75f64.powi(j as i32)))
            .filter(|p| p.1 >= ymin)
            .collect();
        let (dl, gap) = dash(2, &th);
        chart
            .draw_series(DashedLineSeries::new(
                bound,
                dl,
                gap,
                BLACK.stroke_width(lw + 1),
            ))
            .map_err(draw_err)?
            .label("(3/4)^j  (Theorem 1 bound)")
            .legend(move |p| LegendGlyph::line(p, &th, BLACK, lw + 1).dashed((dl, gap)));
        let n = self.curves.len();
        for (i, c) in self.curves.iter().enumerate() {
            let col = series_color(i, n);
            let marker = Marker::nth(i);
            let ms = th.marker;
            let pts: Vec<(f64, f64)> = c
                .relative()
                .into_iter()
                .map(|(j, d)| (j as f64, d))
                .collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), col.stroke_width(lw)))
                .map_err(draw_err)?
                .label(format!("{}  (|λ₁| = {:.4})", c.label(), c.lambda1))
                .legend(move |p| LegendGlyph::line(p, &th, col, lw).marker(marker, ms));
            chart
                .draw_series(pts.iter().map(|&p| marker.at(p, ms, col)))
                .map_err(draw_err)?;
            let (dl, gap) = dash(1, &th);
            let rate: Vec<(f64, f64)> = (0..=self.levels)
                .map(|j| (j as f64, c.fit * c.lambda1.powi(j as i32)))
                .filter(|p| p.1 >= ymin && p.1 <= 1.5)
                .collect();
            chart
                .draw_series(DashedLineSeries::new(rate, dl, gap, col.stroke_width(lw)))
                .map_err(draw_err)?;
        }
        let dl2 = dash(1, &th);
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
            .map_err(draw_err)?
            .label("C |λ₁|^j  (dotted, fitted at the last level)")
            .legend(move |p| LegendGlyph::line(p, &th, BLACK, lw).dashed(dl2));
        inner_legend(&mut chart, SeriesLabelPosition::LowerLeft, &th)?;
        Ok(())
    }
}
