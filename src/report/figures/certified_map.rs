//! `kind = "certified-map"`: certified cells of the NURDS ratio space beside
//! the sampled knot map (math doc section 15).
//!
//! For `n = 3` and each fixed `r_2` of `slices`, the branch and bound of
//! [`crate::verify`] runs over the square `(r_0, r_1)` in `[lo, hi]^2` with
//! `r_2` held at the slice's float. With `property = "class"` (the default:
//! class + separation) every coloured cell on the left is *proven* to have
//! that subdominant class for every `(r_0, r_1)` in it; grey cells are
//! `undecided` at `min_width` (the class boundaries). With
//! `property = "g1"` the left panels show the cells proven `g1` (math doc
//! section 15, "G1 over a cell": the pair after `1` separated and its
//! characteristic map regular and injective, whatever the class), which
//! cross the class boundaries of the right panels. On the right, the same
//! square is sampled at `grid x grid` cell centres with the pointwise
//! classifier, as in `knot-map`.
//!
//! Tables: `<id>-cells.csv` (`slice, r2, r0_lo, r0_hi, r1_lo, r1_hi,
//! verdict`, end points in shortest round-trip form) and `<id>-samples.csv`
//! (`slice, r2, r0, r1, class`).
//!
//! ```toml
//! [[figure]]
//! kind = "certified-map"
//! slices = [0.3, 0.7]       # r_2 per row of panels (1 to 3 values)
//! range = [0.01, 0.99]      # the square [lo, hi]^2 of (r_0, r_1) (default)
//! min_width = 0.015625      # cells this narrow are not split (default 1/64)
//! grid = 41                 # sampled cells per axis (default 41)
//! property = "class"        # or "g1" (default "class")
//! ```

use super::{num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::knots::EdgeRatios;
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::plot::{
    class_color, class_swatch, draw_err, row_runs, square_ratio_panel, subscript, tick, titled,
    Theme,
};
use crate::schemes::LocalScheme;
use crate::spectral::classify_scheme;
use crate::verify::spec::{Property, Region, VerifySpec};
use crate::verify::{run, Limits};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Deserialize;
use toml::Spanned;

/// Most slices (rows of panel pairs).
pub const MAX_SLICES: usize = 3;
/// Sampled grid resolution bounds (cells per axis).
pub const GRID_RANGE: (usize, usize) = (4, 200);
/// Smallest accepted `min_width`: `2^-10` (about 10^4 cells per slice at
/// most along the class boundaries, well under a second).
pub const MIN_WIDTH_FLOOR: f64 = 1.0 / 1024.0;
/// Cap on the cells evaluated per slice (refinement stops before a level
/// that would exceed it; the open cells stay undecided).
pub const MAX_CELLS_PER_SLICE: u64 = 200_000;
/// The same cap for `property = "g1"`: a `g1` cell costs about 0.5 ms CPU
/// at `n = 3` against microseconds for the class, so 20 000 cells (about
/// 10 s CPU per slice) keep a figure within a report's time.
pub const MAX_G1_CELLS_PER_SLICE: u64 = 20_000;

/// What the left panels certify.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Proven {
    /// The subdominant class and its separation.
    Class,
    /// The class-free `g1` property.
    G1,
}

impl Proven {
    fn parse(s: &str) -> Option<Proven> {
        match s {
            "class" => Some(Proven::Class),
            "g1" => Some(Proven::G1),
            _ => None,
        }
    }

    /// The `verify` properties and the cell cap per slice.
    fn properties(self) -> (Vec<Property>, u64) {
        match self {
            Proven::Class => (
                vec![Property::Class, Property::Separation],
                MAX_CELLS_PER_SLICE,
            ),
            Proven::G1 => (vec![Property::G1], MAX_G1_CELLS_PER_SLICE),
        }
    }

    /// The caption word of the left panels.
    fn caption(self) -> &'static str {
        match self {
            Proven::Class => "certified",
            Proven::G1 => "g1 certified",
        }
    }
}

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "certified-map",
    default_title: "Certified classes over the ratio space (n = 3)",
    summary: "certified (r_0, r_1) cells at fixed r_2 beside the sampled knot map",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    slices: Spanned<Vec<f64>>,
    range: Option<Spanned<[f64; 2]>>,
    min_width: Option<Spanned<f64>>,
    grid: Option<Spanned<usize>>,
    property: Option<Spanned<String>>,
}

struct CertifiedMap {
    slices: Vec<f64>,
    range: [f64; 2],
    min_width: f64,
    grid: usize,
    proven: Proven,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let slices = p.slices.get_ref().clone();
    if slices.is_empty() || slices.len() > MAX_SLICES {
        return Err(fs.error_at(
            &p.slices,
            "slices",
            format!("give 1 to {MAX_SLICES} values of r_2, got {}", slices.len()),
        ));
    }
    if let Some((i, x)) = slices
        .iter()
        .enumerate()
        .find(|(_, x)| !(**x > 0.0 && **x < 1.0))
    {
        return Err(fs.error_at(
            &p.slices,
            &format!("slices[{i}]"),
            format!("edge ratio r_2 must lie strictly between 0 and 1, got {x}"),
        ));
    }
    let range = match &p.range {
        None => [0.01, 0.99],
        Some(r) => {
            let [a, b] = *r.get_ref();
            if !(a > 0.0 && a < b && b < 1.0) {
                return Err(fs.error_at(
                    r,
                    "range",
                    format!("range must satisfy 0 < lo < hi < 1, got [{a}, {b}]"),
                ));
            }
            [a, b]
        }
    };
    let min_width = match &p.min_width {
        None => 1.0 / 64.0,
        Some(w) => {
            let v = *w.get_ref();
            if !(MIN_WIDTH_FLOOR..=1.0).contains(&v) {
                return Err(fs.error_at(
                    w,
                    "min_width",
                    format!("min_width must lie in [{MIN_WIDTH_FLOOR}, 1], got {v}"),
                ));
            }
            v
        }
    };
    let grid = match &p.grid {
        None => 41,
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
    let proven = match &p.property {
        None => Proven::Class,
        Some(v) => Proven::parse(v.get_ref()).ok_or_else(|| {
            fs.error_at(
                v,
                "property",
                format!(
                    "property must be \"class\" or \"g1\", got {:?}",
                    v.get_ref()
                ),
            )
        })?,
    };
    Ok(Box::new(CertifiedMap {
        slices,
        range,
        min_width,
        grid,
        proven,
    }))
}

/// One slice: the certified cells `(lo, hi, verdict)` in `(r_0, r_1)` and
/// the sampled classes (row-major, `r_1` outer).
struct Slice {
    r2: f64,
    cells: Vec<([f64; 2], [f64; 2], &'static str)>,
    samples: Vec<String>,
}

impl Figure for CertifiedMap {
    fn work(&self) -> u64 {
        (self.slices.len() * (self.grid + 1)) as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let [a, b] = self.range;
        let g = self.grid;
        let mut out = Vec::new();
        for &r2 in &self.slices {
            // r_2 is held at the float r2 (a zero-width side is never split)
            let (properties, max_cells) = self.proven.properties();
            let spec = VerifySpec {
                name: "certified-map".into(),
                region: Region::Ratios {
                    lo: vec![a, a, r2],
                    hi: vec![b, b, r2],
                },
                properties,
                min_width: self.min_width,
                time_budget: None,
                symmetry: Default::default(),
            };
            let limits = Limits {
                max_cells,
                ..Limits::default()
            };
            let outcome = run(&spec, &limits);
            ctx.tick(1);
            let cells = outcome
                .cells
                .iter()
                .map(|c| ([c.lo[0], c.lo[1]], [c.hi[0], c.hi[1]], c.verdict()))
                .collect();
            let rows = (0..g)
                .into_par_iter()
                .map(|j| {
                    let r1 = a + (b - a) * (j as f64 + 0.5) / g as f64;
                    let mut row = Vec::with_capacity(g);
                    for i in 0..g {
                        let r0 = a + (b - a) * (i as f64 + 0.5) / g as f64;
                        let ratios = EdgeRatios::new(vec![r0, r1, r2]).map_err(|e| ctx.err(e))?;
                        let sub =
                            classify_scheme(&LocalScheme::nurds(ratios)).map_err(|e| ctx.err(e))?;
                        row.push(sub.class.name().to_owned());
                    }
                    ctx.tick(1);
                    Ok(row)
                })
                .collect::<Result<Vec<_>, ReportError>>()?;
            out.push(Slice {
                r2,
                cells,
                samples: rows.into_iter().flatten().collect(),
            });
        }
        Ok(Box::new(Output {
            slices: out,
            range: self.range,
            grid: g,
            proven: self.proven,
        }))
    }
}

struct Output {
    slices: Vec<Slice>,
    range: [f64; 2],
    grid: usize,
    proven: Proven,
}

/// Legend order (the verdicts a NURDS cell can be certified with, then
/// undecided).
const LEGEND: &[&str] = &[
    "g1",
    "real_distinct",
    "complex_pair",
    "not_separated",
    "undecided",
];

impl Output {
    /// Area share per verdict over all slices (verdicts with no area left out).
    fn shares(&self) -> Vec<(&'static str, f64)> {
        let [a, b] = self.range;
        let total = (b - a) * (b - a) * self.slices.len() as f64;
        LEGEND
            .iter()
            .map(|&v| {
                let area: f64 = self
                    .slices
                    .iter()
                    .flat_map(|s| s.cells.iter())
                    .filter(|c| c.2 == v)
                    .map(|(lo, hi, _)| (hi[0] - lo[0]) * (hi[1] - lo[1]))
                    .sum();
                // 0.0 + : an empty float sum is -0.0
                (v, 0.0 + area / total)
            })
            .filter(|(_, f)| *f > 0.0)
            .collect()
    }

    /// Share of the sampled points per class: the classes of [`LEGEND`] in
    /// its order, then any other class by name.
    fn sample_shares(&self) -> Vec<(String, f64)> {
        let mut counts: std::collections::BTreeMap<&str, usize> = Default::default();
        for c in self.slices.iter().flat_map(|s| s.samples.iter()) {
            *counts.entry(c.as_str()).or_default() += 1;
        }
        let total = counts.values().sum::<usize>().max(1) as f64;
        let mut names: Vec<&str> = LEGEND
            .iter()
            .copied()
            .filter(|v| counts.contains_key(v))
            .collect();
        names.extend(counts.keys().copied().filter(|k| !LEGEND.contains(k)));
        names
            .into_iter()
            .map(|v| (v.to_owned(), counts[v] as f64 / total))
            .collect()
    }
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut cells = DataTable::new(
            Some("cells"),
            &["slice", "r2", "r0_lo", "r0_hi", "r1_lo", "r1_hi", "verdict"],
        );
        let mut samples = DataTable::new(Some("samples"), &["slice", "r2", "r0", "r1", "class"]);
        let [a, b] = self.range;
        let g = self.grid as f64;
        for (s, sl) in self.slices.iter().enumerate() {
            for (lo, hi, v) in &sl.cells {
                cells.push(vec![
                    s.to_string(),
                    format!("{:?}", sl.r2),
                    format!("{:?}", lo[0]),
                    format!("{:?}", hi[0]),
                    format!("{:?}", lo[1]),
                    format!("{:?}", hi[1]),
                    (*v).to_owned(),
                ]);
            }
            for (k, class) in sl.samples.iter().enumerate() {
                let (i, j) = (k % self.grid, k / self.grid);
                samples.push(vec![
                    s.to_string(),
                    num(sl.r2),
                    num(a + (b - a) * (i as f64 + 0.5) / g),
                    num(a + (b - a) * (j as f64 + 0.5) / g),
                    class.clone(),
                ]);
            }
        }
        vec![cells, samples]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let th = Theme::for_size(common.size);
        let body = titled(area, &common.title, &th)?;
        let (w, _) = body.dim_in_pixel();
        let entry = |v: &str, f: f64| {
            (
                format!("{} ({:.1}%)", v.replace('_', " "), 100.0 * f),
                v.to_owned(),
            )
        };
        let mut groups: Vec<(&str, Vec<(String, String)>)> = vec![(
            "certified area",
            self.shares()
                .into_iter()
                .map(|(v, f)| entry(v, f))
                .collect(),
        )];
        // the g1 cells' colour is not a class: the sampled classes get their own key
        if self.proven == Proven::G1 {
            groups.push((
                "sampled class",
                self.sample_shares()
                    .into_iter()
                    .map(|(v, f)| entry(&v, f))
                    .collect(),
            ));
        }
        let text_w = |t: &str, size: u32| {
            body.estimate_text_size(t, &th.font(size))
                .map_or(0, |s| s.0)
        };
        let widest = groups
            .iter()
            .flat_map(|(head, items)| {
                std::iter::once(text_w(head, th.label))
                    .chain(items.iter().map(|(t, _)| text_w(t, th.legend)))
            })
            .max()
            .unwrap_or(0);
        let side_w = (widest + th.legend * 4 + th.tick * 2).clamp(w / 8, w / 3);
        let (maps, side) = body.split_horizontally(w - side_w);
        let rows = maps.split_evenly((self.slices.len(), 2));
        let [a, b] = self.range;
        let g = self.grid as f64;
        for (s, sl) in self.slices.iter().enumerate() {
            for half in 0..2 {
                let pa = &rows[2 * s + half];
                let caption = format!(
                    "{}: {} = {}",
                    if half == 0 {
                        self.proven.caption()
                    } else {
                        "sampled"
                    },
                    subscript("r", 2),
                    sl.r2
                );
                let (mut chart, _) = square_ratio_panel(pa, &caption, &th, [a, b], &|y| tick(*y))?;
                if half == 0 {
                    chart
                        .draw_series(sl.cells.iter().map(|(lo, hi, v)| {
                            Rectangle::new(
                                [(lo[0], lo[1]), (hi[0], hi[1])],
                                class_color(v).filled(),
                            )
                        }))
                        .map_err(draw_err)?;
                } else {
                    let gi = self.grid;
                    let step = (b - a) / g;
                    let rects = row_runs(
                        gi,
                        |k| a + k as f64 * step,
                        |i, j| class_color(&sl.samples[j * gi + i]),
                    );
                    chart.draw_series(rects).map_err(draw_err)?;
                }
            }
        }
        let x = th.tick as i32;
        let sz = th.legend as i32;
        let mut y = th.label as i32 * 3;
        for (head, items) in groups {
            side.draw(&Text::new(
                head,
                (x, y - th.label as i32 * 2),
                th.font(th.label),
            ))
            .map_err(draw_err)?;
            for (text, name) in items {
                class_swatch(&side, (x, y), sz, &name)?;
                side.draw(&Text::new(
                    text,
                    (x + sz * 3, y + sz / 3),
                    th.font(th.legend),
                ))
                .map_err(draw_err)?;
                y += sz * 3;
            }
            y += th.label as i32 * 3;
        }
        Ok(())
    }
}
