//! `kind = "g2-cap-curvature"`: Gaussian and mean curvature of the G2 cap
//! of seed 003 and of the plain subdivision surface around the same vertex,
//! side by side, as colour on the parameter domain (math doc section 14.7).
//!
//! The net is the random test 2-ring of [`crate::g2cap::ring::TwoRing::random`]
//! (valence `valence`, the figure's `seed`). The cap is built and checked
//! ([`crate::g2cap::G2Cap::check`]; a refused cap is an error, never drawn);
//! the subdivision surface is [`crate::g2cap::plain::PlainSurface`] with
//! `levels` levels. Both are sampled at the centres of a `grid x grid` grid
//! of cells on every patch's `[0, 1]^2`.
//!
//! **Domain.** Sector `i`'s `(u, v)` is drawn at `u e_i + v e_(i+1)`, `e_k`
//! the unit vector at angle `2 pi k / n`: the `n` cells form a star around the
//! vertex, drawn at equal scale in `x` and `y`; thin lines mark the patch
//! edges.
//!
//! **Colour scale.** One colour bar per quantity, shared by the two panels
//! of its row: a diverging scale, blue (negative) through white (zero) to red
//! (positive), linear on `[-s, s]` with `s` the largest magnitude over the
//! samples of both surfaces (so both panels use every colour they need, and
//! zero is white). Cells with no value (a singular parametrisation) are
//! grey. The CSV has every cell centre drawn.
//!
//! ```toml
//! [[figure]]
//! kind = "g2-cap-curvature"
//! valence = 5      # 3..=16 (default 5)
//! c = 0.5          # shape parameter in [0, 1] (default 1/2: Catmull-Clark)
//! levels = 8       # subdivision levels of the plain surface, 1..=16 (default 8)
//! grid = 16        # cells per patch side, 2..=48 (default 16)
//! ```

use super::{bounded, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::g2cap::plain::PlainSurface;
use crate::g2cap::ring::TwoRing;
use crate::g2cap::{G2Cap, G2CapError};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{colorbar, draw_err, equal_aspect, titled, Theme};
use plotters::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Largest valence accepted (that of the cap).
pub const MAX_VALENCE: usize = crate::g2cap::ring::MAX_VALENCE;
/// Largest number of subdivision levels: the drawn cells reach `2^-16` of
/// the cap's cell at most, far below a pixel.
pub const MAX_LEVELS: usize = 16;
/// Largest grid: `48^2 n` cells per panel keep the SVG below a few MB.
pub const MAX_GRID: usize = 48;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "g2-cap-curvature",
    default_title: "Curvature of the G2 cap and of the subdivision surface",
    summary: "Gaussian and mean curvature maps of the seed-003 G2 cap and of the plain subdivision surface around the same vertex",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Params {
    valence: Option<Spanned<usize>>,
    c: Option<Spanned<f64>>,
    levels: Option<Spanned<usize>>,
    grid: Option<Spanned<usize>>,
}

/// The validated keys shared by the two cap figure kinds.
#[derive(Clone, Copy, Debug)]
pub(super) struct CapSetup {
    pub valence: usize,
    pub c: f64,
    pub levels: usize,
    pub grid: usize,
}

/// Validates the shared keys (each error names its key and line).
pub(super) fn setup(fs: &FigureSpec<'_>, p: &Params) -> Result<CapSetup, ReportError> {
    let valence = bounded(fs, &p.valence, "valence", 3, MAX_VALENCE, 5)?;
    let c = match &p.c {
        None => 0.5,
        Some(c) if (0.0..=1.0).contains(c.get_ref()) => *c.get_ref(),
        Some(c) => {
            return Err(fs.error_at(
                c,
                "c",
                format!("c must be between 0 and 1, got {}", c.get_ref()),
            ))
        }
    };
    let levels = bounded(fs, &p.levels, "levels", 1, MAX_LEVELS, 8)?;
    let grid = bounded(fs, &p.grid, "grid", 2, MAX_GRID, 16)?;
    Ok(CapSetup {
        valence,
        c,
        levels,
        grid,
    })
}

/// The checked cap and the plain surface of the setup's net.
pub(super) fn surfaces(s: &CapSetup, seed: u64) -> Result<(G2Cap, PlainSurface), G2CapError> {
    let ring = TwoRing::random(s.valence, seed)?;
    let cap = G2Cap::build(&ring, s.c)?;
    cap.check()?;
    let plain = PlainSurface::new(&ring, s.c, s.levels)?;
    Ok((cap, plain))
}

/// A figure error from the cap construction.
pub(super) fn cap_err(ctx: &Context<'_>, e: G2CapError) -> ReportError {
    ctx.err(e)
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    Ok(Box::new(MapsFigure {
        setup: setup(fs, &p)?,
    }))
}

struct MapsFigure {
    setup: CapSetup,
}

/// One sampled cell.
struct Cell {
    patch: usize,
    u: f64,
    v: f64,
    /// `(K, H)`, `None` where singular.
    kh: Option<(f64, f64)>,
}

impl Figure for MapsFigure {
    fn work(&self) -> u64 {
        2
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let s = self.setup;
        let (cap, plain) = surfaces(&s, ctx.common.seed).map_err(|e| cap_err(ctx, e))?;
        ctx.tick(1);
        let g = s.grid;
        let mut cap_cells = Vec::with_capacity(s.valence * g * g);
        let mut plain_cells = Vec::with_capacity(s.valence * g * g);
        for i in 0..s.valence {
            for a in 0..g {
                for b in 0..g {
                    let (u, v) = ((a as f64 + 0.5) / g as f64, (b as f64 + 0.5) / g as f64);
                    cap_cells.push(Cell {
                        patch: i,
                        u,
                        v,
                        kh: cap.curvature_at(i, u, v),
                    });
                    plain_cells.push(Cell {
                        patch: i,
                        u,
                        v,
                        kh: plain.curvature_at(i, u, v),
                    });
                }
            }
        }
        ctx.tick(1);
        Ok(Box::new(Output {
            setup: s,
            surfaces: [cap_cells, plain_cells],
        }))
    }
}

struct Output {
    setup: CapSetup,
    /// Cap, then plain surface.
    surfaces: [Vec<Cell>; 2],
}

const SURFACE_NAMES: [&str; 2] = ["cap", "subdivision"];

/// The point `u e_i + v e_(i+1)` of the parameter-domain drawing.
pub(super) fn domain_point(n: usize, i: usize, u: f64, v: f64) -> (f64, f64) {
    let e = |k: usize| {
        let t = 2.0 * std::f64::consts::PI * (k % n) as f64 / n as f64;
        (t.cos(), t.sin())
    };
    let (a, b) = (e(i), e(i + 1));
    (u * a.0 + v * b.0, u * a.1 + v * b.1)
}

/// Blue - white - red at `t` in `[0, 1]` (white at 1/2).
pub fn diverging(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let blue = (33.0, 102.0, 172.0);
    let red = (178.0, 24.0, 43.0);
    let (end, w) = if t < 0.5 {
        (blue, 1.0 - 2.0 * t)
    } else {
        (red, 2.0 * t - 1.0)
    };
    let m = |x: f64| (255.0 + (x - 255.0) * w).round() as u8;
    RGBColor(m(end.0), m(end.1), m(end.2))
}

impl Output {
    /// The symmetric half range of quantity `q` (0: K, 1: H) over both surfaces.
    fn scale(&self, q: usize) -> f64 {
        let s = self
            .surfaces
            .iter()
            .flatten()
            .filter_map(|c| c.kh.map(|kh| if q == 0 { kh.0 } else { kh.1 }))
            .filter(|x| x.is_finite())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        if s > 0.0 {
            s
        } else {
            1.0
        }
    }
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let n = self.setup.valence;
        let mut t = DataTable::new(
            None,
            &[
                "surface", "n", "c", "patch", "u", "v", "x", "y", "gaussian", "mean",
            ],
        );
        for (name, cells) in SURFACE_NAMES.iter().zip(&self.surfaces) {
            for c in cells {
                let (x, y) = domain_point(n, c.patch, c.u, c.v);
                let (k, h) = c.kh.unwrap_or((f64::NAN, f64::NAN));
                t.push(vec![
                    (*name).to_owned(),
                    n.to_string(),
                    num(self.setup.c),
                    c.patch.to_string(),
                    num(c.u),
                    num(c.v),
                    num(x),
                    num(y),
                    num(k),
                    num(h),
                ]);
            }
        }
        vec![t]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let (w, _) = body.dim_in_pixel();
        let side_w = (w as f64 * 0.16) as u32;
        let (maps, side) = body.split_horizontally(w - side_w);
        let rows = maps.split_evenly((2, 2));
        let bars = side.split_evenly((2, 1));
        let n = self.setup.valence;
        let g = self.setup.grid as f64;
        let quantities = ["Gaussian curvature K", "mean curvature H"];
        let panel_names = ["G2 cap", "subdivision surface"];
        // The bounding box of the star.
        let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            for (u, v) in [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                let (x, y) = domain_point(n, i, u, v);
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
        for q in 0..2 {
            let s = self.scale(q);
            for (col, cells) in self.surfaces.iter().enumerate() {
                let pa = &rows[2 * q + col];
                let pa = pa
                    .margin(th.tick / 2, th.tick / 2, th.tick / 2, th.tick / 2)
                    .titled(
                        &format!("{}: {}", panel_names[col], ["K", "H"][q]),
                        th.font(th.label),
                    )
                    .map_err(draw_err)?;
                let (xr, yr) = equal_aspect(pa.dim_in_pixel(), (x0, x1), (y0, y1));
                let mut chart = ChartBuilder::on(&pa)
                    .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
                    .map_err(draw_err)?;
                let half = 0.5 / g;
                chart
                    .draw_series(cells.iter().map(|c| {
                        let color = match c.kh {
                            Some((k, h)) => {
                                let x = if q == 0 { k } else { h };
                                diverging(0.5 + 0.5 * x / s)
                            }
                            None => RGBColor(160, 160, 160),
                        };
                        let corners = [
                            (c.u - half, c.v - half),
                            (c.u + half, c.v - half),
                            (c.u + half, c.v + half),
                            (c.u - half, c.v + half),
                        ]
                        .map(|(u, v)| domain_point(n, c.patch, u, v));
                        Polygon::new(corners.to_vec(), color.filled())
                    }))
                    .map_err(draw_err)?;
                // Patch edges.
                for i in 0..n {
                    let outline = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)]
                        .map(|(u, v)| domain_point(n, i, u, v));
                    chart
                        .draw_series(LineSeries::new(
                            outline.to_vec(),
                            BLACK.mix(0.6).stroke_width(th.line.max(2) / 2),
                        ))
                        .map_err(draw_err)?;
                }
            }
            colorbar(&bars[q], -s, s, quantities[q], &th, &diverging)?;
        }
        Ok(())
    }
}
