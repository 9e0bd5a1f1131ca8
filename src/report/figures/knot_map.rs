//! `kind = "knot-map"`: a map of the ratio space of NURDS.
//!
//! The edge ratios r_0, r_1 run over a `grid` x `grid` lattice of cell centres
//! in (0, 1); the remaining ratios r_2..r_{n-1} are fixed per panel (one panel
//! per entry of `slices`, so n = 2 + the slice length; n = 3 for one value).
//! Each cell is coloured by the subdominant class (math doc section 7), by
//! |lambda_2|/|lambda_1|, or by the angle theta = |arg lambda_1| (nonzero
//! exactly for complex pairs and negative real lambda_1). In the class map,
//! classes covering less than [`RARE_SHARE`] of the cells (points and curves
//! of the ratio space) are also drawn as enlarged markers on top.
//!
//! The CSV has one row per cell: `slice, r0, r1, fixed, class, lambda1_re,
//! lambda1_im, lambda2_re, lambda2_im, modulus_ratio, angle_degrees`; the
//! plotted column is `class`, `modulus_ratio` or `angle_degrees` by `color_by`.
//!
//! ```toml
//! [[figure]]
//! kind = "knot-map"
//! slices = [[0.2], [0.5], [0.8]]   # r_2 per panel (n = 3)
//! grid = 81                        # cells per axis (default 81)
//! color_by = "class"               # "class", "modulus-ratio" or "angle"
//! ```

use super::{num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::knots::EdgeRatios;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    class_color, class_swatch, colorbar, draw_err, row_runs, square_ratio_panel, subscript, tick,
    titled, viridis, Marker, Theme,
};
use crate::schemes::LocalScheme;
use crate::spectral::classify_scheme;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Grid resolution bounds (cells per axis).
pub const GRID_RANGE: (usize, usize) = (4, 400);
/// Most panels (slices).
pub const MAX_SLICES: usize = 6;
/// Colour levels of the continuous maps (cells of equal level are merged
/// into one rectangle, which keeps the SVG small).
pub const COLOR_LEVELS: f64 = 256.0;

/// Class names in legend order (math doc section 7).
pub const CLASSES: &[&str] = &[
    "standard",
    "real_distinct",
    "complex_pair",
    "defective",
    "not_separated",
    "indeterminate",
];

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "knot-map",
    default_title: "Subdominant eigenstructure over the ratio space",
    summary: "map of (r_0, r_1) at fixed r_2.. coloured by class, |lambda_2|/|lambda_1| or theta",
    parse,
};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum ColorBy {
    Class,
    ModulusRatio,
    Angle,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    slices: Spanned<Vec<Vec<f64>>>,
    grid: Option<Spanned<usize>>,
    color_by: Option<ColorBy>,
}

struct KnotMap {
    slices: Vec<Vec<f64>>,
    grid: usize,
    color_by: ColorBy,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let slices = p.slices.get_ref().clone();
    if slices.is_empty() || slices.len() > MAX_SLICES {
        return Err(fs.error_at(
            &p.slices,
            "slices",
            format!("give 1 to {MAX_SLICES} slices, got {}", slices.len()),
        ));
    }
    let m = slices[0].len();
    for (i, s) in slices.iter().enumerate() {
        if s.is_empty() || s.len() != m {
            return Err(fs.error_at(
                &p.slices,
                &format!("slices[{i}]"),
                "every slice lists the same number (>= 1) of fixed ratios r_2..r_{n-1}",
            ));
        }
        if let Some((j, x)) = s
            .iter()
            .enumerate()
            .find(|(_, x)| !(**x > 0.0 && **x < 1.0))
        {
            return Err(fs.error_at(
                &p.slices,
                &format!("slices[{i}][{j}]"),
                format!(
                    "edge ratio r_{} must lie strictly between 0 and 1, got {x}",
                    j + 2
                ),
            ));
        }
    }
    let grid = match &p.grid {
        None => 81,
        Some(g) if (GRID_RANGE.0..=GRID_RANGE.1).contains(g.get_ref()) => *g.get_ref(),
        Some(g) => {
            return Err(fs.error_at(
                g,
                "grid",
                format!(
                    "grid must be between {} and {}, got {}",
                    GRID_RANGE.0,
                    GRID_RANGE.1,
                    g.get_ref()
                ),
            ))
        }
    };
    Ok(Box::new(KnotMap {
        slices,
        grid,
        color_by: p.color_by.unwrap_or(ColorBy::Class),
    }))
}

/// One cell of the map.
#[derive(Clone, Debug)]
struct Cell {
    i: usize,
    j: usize,
    class: String,
    l1: num_complex::Complex64,
    l2: num_complex::Complex64,
}

impl Cell {
    fn modulus_ratio(&self) -> f64 {
        self.l2.norm() / self.l1.norm()
    }
    fn angle(&self) -> f64 {
        self.l1.arg().abs()
    }
}

impl Figure for KnotMap {
    fn work(&self) -> u64 {
        (self.slices.len() * self.grid) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let g = self.grid;
        let mut panels = Vec::new();
        for fixed in &self.slices {
            let rows = (0..g)
                .into_par_iter()
                .map(|j| {
                    let r1 = (j as f64 + 0.5) / g as f64;
                    let mut row = Vec::with_capacity(g);
                    for i in 0..g {
                        let r0 = (i as f64 + 0.5) / g as f64;
                        let mut r = vec![r0, r1];
                        r.extend_from_slice(fixed);
                        let ratios = EdgeRatios::new(r).map_err(|e| ctx.err(e))?;
                        let sub =
                            classify_scheme(&LocalScheme::nurds(ratios)).map_err(|e| ctx.err(e))?;
                        row.push(Cell {
                            i,
                            j,
                            class: sub.class.name().to_owned(),
                            l1: sub.lambda1,
                            l2: sub.lambda2,
                        });
                    }
                    ctx.tick(1);
                    Ok(row)
                })
                .collect::<Result<Vec<_>, ReportError>>()?;
            panels.push((
                fixed.clone(),
                rows.into_iter().flatten().collect::<Vec<_>>(),
            ));
        }
        let range = match self.color_by {
            ColorBy::Class | ColorBy::ModulusRatio => (0.0, 1.0),
            ColorBy::Angle => {
                let max = panels
                    .iter()
                    .flat_map(|p| p.1.iter())
                    .map(|c| c.angle().to_degrees())
                    .fold(0.0f64, f64::max);
                (0.0, ((max / 5.0).ceil() * 5.0).clamp(5.0, 180.0))
            }
        };
        Ok(Box::new(Output {
            panels,
            grid: g,
            color_by: self.color_by,
            range,
        }))
    }
}

struct Output {
    panels: Vec<(Vec<f64>, Vec<Cell>)>,
    grid: usize,
    color_by: ColorBy,
    /// Value range of the continuous colour maps: [0, 1] for the modulus
    /// ratio, [0, max rounded up to 5 degrees] for the angle.
    range: (f64, f64),
}

/// A class covering less than this share of a class map's cells is drawn as
/// a measure-zero set: every cell of it also gets an enlarged marker on top
/// (single cells are points of the ratio space, chains of cells are curves;
/// at 2% a class is below one row of an 81 x 81 grid per panel, too thin to
/// see as fill alone).
pub const RARE_SHARE: f64 = 0.02;

/// The marker of a rare class in the class map (and its legend; the sweep
/// plot's `map` uses the same).
pub(crate) fn rare_marker(class: &str) -> Marker {
    match class {
        "standard" => Marker::Diamond,
        "defective" => Marker::Square,
        "not_separated" => Marker::Triangle,
        "indeterminate" => Marker::TriangleDown,
        _ => Marker::Circle,
    }
}

impl Output {
    fn value(&self, c: &Cell) -> f64 {
        match self.color_by {
            ColorBy::Class => CLASSES
                .iter()
                .position(|k| *k == c.class)
                .unwrap_or(CLASSES.len()) as f64,
            ColorBy::ModulusRatio => c.modulus_ratio(),
            ColorBy::Angle => c.angle().to_degrees(),
        }
    }

    fn color(&self, c: &Cell) -> RGBColor {
        let (lo, hi) = self.range;
        match self.color_by {
            ColorBy::Class => class_color(&c.class),
            ColorBy::ModulusRatio | ColorBy::Angle => {
                let t = ((self.value(c) - lo) / (hi - lo)).clamp(0.0, 1.0);
                viridis((t * COLOR_LEVELS).floor() / COLOR_LEVELS)
            }
        }
    }

    /// The classes drawn as measure-zero sets (share below [`RARE_SHARE`]).
    fn rare_classes(&self) -> Vec<String> {
        let total: usize = self.panels.iter().map(|p| p.1.len()).sum();
        let mut names: Vec<String> = Vec::new();
        for c in self.panels.iter().flat_map(|p| p.1.iter()) {
            if !names.contains(&c.class) {
                names.push(c.class.clone());
            }
        }
        names
            .into_iter()
            .filter(|n| {
                let count = self
                    .panels
                    .iter()
                    .flat_map(|p| p.1.iter())
                    .filter(|c| &c.class == n)
                    .count();
                (count as f64) < RARE_SHARE * total as f64
            })
            .collect()
    }

    /// Legend lines of the class map: ("real distinct (58.2%)", class name),
    /// for the classes that occur.
    fn class_legend(&self) -> Vec<(String, String)> {
        let total: usize = self.panels.iter().map(|p| p.1.len()).sum();
        let mut names: Vec<String> = CLASSES.iter().map(|s| (*s).to_owned()).collect();
        for c in self.panels.iter().flat_map(|p| p.1.iter()) {
            if !names.contains(&c.class) {
                names.push(c.class.clone());
            }
        }
        names
            .into_iter()
            .filter_map(|name| {
                let count = self
                    .panels
                    .iter()
                    .flat_map(|p| p.1.iter())
                    .filter(|c| c.class == name)
                    .count();
                if count == 0 {
                    return None;
                }
                let pct = 100.0 * count as f64 / total as f64;
                let share = if pct < 0.1 {
                    format!("{count} cell{}", if count == 1 { "" } else { "s" })
                } else {
                    format!("{pct:.1}%")
                };
                Some((format!("{} ({share})", name.replace('_', " ")), name))
            })
            .collect()
    }
}

fn fixed_text(fixed: &[f64]) -> String {
    fixed
        .iter()
        .enumerate()
        .map(|(k, x)| format!("{} = {x}", subscript("r", k + 2)))
        .collect::<Vec<_>>()
        .join(", ")
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "slice",
                "r0",
                "r1",
                "fixed",
                "class",
                "lambda1_re",
                "lambda1_im",
                "lambda2_re",
                "lambda2_im",
                "modulus_ratio",
                "angle_degrees",
            ],
        );
        let g = self.grid as f64;
        for (s, (fixed, cells)) in self.panels.iter().enumerate() {
            let ftxt = fixed.iter().map(|x| num(*x)).collect::<Vec<_>>().join(";");
            for c in cells {
                t.push(vec![
                    s.to_string(),
                    num((c.i as f64 + 0.5) / g),
                    num((c.j as f64 + 0.5) / g),
                    ftxt.clone(),
                    c.class.clone(),
                    num(c.l1.re),
                    num(c.l1.im),
                    num(c.l2.re),
                    num(c.l2.im),
                    num(c.modulus_ratio()),
                    num(c.angle().to_degrees()),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let (w, _) = body.dim_in_pixel();
        let legend = self.class_legend();
        let rare = if self.color_by == ColorBy::Class {
            self.rare_classes()
        } else {
            Vec::new()
        };
        let side_w = match self.color_by {
            ColorBy::Class => {
                let widest = legend
                    .iter()
                    .map(|(text, _)| {
                        body.estimate_text_size(text, &th.font(th.legend))
                            .map_or(0, |s| s.0)
                    })
                    .max()
                    .unwrap_or(0);
                (widest + th.legend * 4 + th.tick * 2).clamp(w / 8, w / 3)
            }
            _ => (w as f64 * 0.18) as u32,
        };
        let (maps, side) = body.split_horizontally(w - side_w);
        let k = self.panels.len();
        let areas = maps.split_evenly((1, k));
        let g = self.grid as f64;
        for ((fixed, cells), pa) in self.panels.iter().zip(areas.iter()) {
            // The corner's 0 is written once, on the r₀ axis (two zeros there
            // would collide).
            let y_tick = |y: &f64| if *y == 0.0 { String::new() } else { tick(*y) };
            let (mut chart, plot_w) =
                square_ratio_panel(pa, &fixed_text(fixed), &th, [0.0, 1.0], &y_tick)?;
            let gi = self.grid;
            let rects = row_runs(gi, |k| k as f64 / g, |i, j| self.color(&cells[j * gi + i]));
            chart.draw_series(rects).map_err(draw_err)?;
            if self.color_by == ColorBy::Class {
                // Measure-zero sets on top: enlarged markers with a white halo.
                let ms = ((plot_w as f64 / g) * 0.9).max(th.marker as f64) as i32;
                for name in &rare {
                    let m = rare_marker(name);
                    let at: Vec<(f64, f64)> = cells
                        .iter()
                        .filter(|c| &c.class == name)
                        .map(|c| ((c.i as f64 + 0.5) / g, (c.j as f64 + 0.5) / g))
                        .collect();
                    chart
                        .draw_series(at.iter().map(|p| m.at(*p, ms + 2, WHITE)))
                        .map_err(draw_err)?;
                    chart
                        .draw_series(at.iter().map(|p| m.at(*p, ms, class_color(name))))
                        .map_err(draw_err)?;
                }
            }
        }
        match self.color_by {
            ColorBy::Class => {
                let x = th.tick as i32;
                let s = th.legend as i32;
                let mut y = th.label as i32 * 3;
                side.draw(&Text::new(
                    "class",
                    (x, y - th.label as i32 * 2),
                    th.font(th.label),
                ))
                .map_err(draw_err)?;
                for (text, name) in legend {
                    class_swatch(&side, (x, y), s, &name)?;
                    if rare.contains(&name) {
                        side.draw(&rare_marker(&name).at((x + s, y + s), s * 2 / 3 + 2, WHITE))
                            .map_err(draw_err)?;
                        side.draw(&rare_marker(&name).at(
                            (x + s, y + s),
                            s * 2 / 3,
                            class_color(&name),
                        ))
                        .map_err(draw_err)?;
                    }
                    side.draw(&Text::new(text, (x + s * 3, y + s / 3), th.font(th.legend)))
                        .map_err(draw_err)?;
                    y += s * 3;
                }
            }
            ColorBy::ModulusRatio => {
                let (lo, hi) = self.range;
                colorbar(&side, lo, hi, "|λ₂| / |λ₁|", &th, &viridis)?;
            }
            ColorBy::Angle => {
                let (lo, hi) = self.range;
                colorbar(&side, lo, hi, "θ = |arg λ₁|  (degrees)", &th, &viridis)?;
            }
        }
        Ok(())
    }
}
