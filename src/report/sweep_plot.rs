//! Plots of sweep results (`subdiv-lab plot` and the report figure kind
//! `sweep`): a [`Table`] of named columns in, a figure out, in the reports'
//! fonts, colours and print-safe markers (`super::plot`).
//!
//! Kinds ([`PlotKind`]):
//!
//! * `fractions`: for each value of `x` (default `valence`), the fraction of
//!   rows in each category of `color` (default `class`): `count / rows at x`;
//! * `histogram`: counts of `x` in equal bins (the square-root rule, between
//!   [`MIN_BINS`] and [`MAX_BINS`] bins), stacked by the categories of `color`
//!   if given;
//! * `scatter`: `y` against `x`, coloured by `color` (categories: colour and
//!   marker per category; numbers: viridis with a colour bar);
//! * `map`: a 2-D slice, one cell per row centred at `(x, y)` with the grid
//!   spacing of the data, coloured by `color` (default `class`); a category
//!   with fewer than 2% of the cells (a measure-zero set such as the
//!   `standard` or `not_separated` lines and points) also gets an enlarged
//!   marker with a white halo on each of its cells, drawn on top, and the
//!   marker in its legend box, as the knot map of the reports does.
//!
//! With no kind the data decides ([`choose`]): class fractions against the
//! valence for a multi-valence sweep with a `class` column; a class map when
//! exactly two parameter columns vary (a 2-D slice); a scatter of
//! `contraction_rate` when one varies; else a histogram. Parameter columns
//! are those between `valence` and `class` in a sweep CSV (all numeric
//! columns but `id` and `valence` otherwise).
//!
//! ```
//! use subdiv_lab::report::table::Table;
//! use subdiv_lab::report::sweep_plot::{PlotKind, PlotRequest, SweepPlot};
//! let t = Table::from_csv(b"id,valence,class\n0,3,standard\n1,3,defective\n2,4,standard\n").unwrap();
//! let p = SweepPlot::build(&t, &PlotRequest::default()).unwrap();
//! assert_eq!(p.kind(), PlotKind::Fractions);
//! let csv = p.data().to_csv().unwrap();
//! assert!(String::from_utf8(csv).unwrap().contains("3,defective,1,0.5"));
//! ```

use super::backend::Area;
use super::error::ReportError;
use super::figures::{num, DataTable};
use super::plot::{
    class_color, colorbar, draw_err, series_color, side_legend, titled, viridis, LegendGlyph,
    Marker, Theme,
};
use super::table::{Table, TableError};
use crate::budget::Estimate;
use plotters::prelude::*;

/// Fewest histogram bins.
pub const MIN_BINS: usize = 10;
/// Most histogram bins.
pub const MAX_BINS: usize = 60;
/// Most distinct `x` values of a `fractions` plot (one point per value).
pub const MAX_GROUPS: usize = 500;
/// Most categories of a colour column (beyond this a legend is unreadable).
pub const MAX_CATEGORIES: usize = 24;
/// Points above which `scatter` and `map` draw small dots instead of
/// markers (so dense plots stay readable and the SVG small).
pub const DENSE_POINTS: usize = 5000;
/// Wall time per plotted point (rendered into SVG and PNG), seconds: measured
/// about 2e-6 s for 280 000 scatter points on the reference machine; doubled.
pub const SECONDS_PER_POINT: f64 = 4e-6;
/// Memory per table cell while reading (the text, the parsed value and the
/// vectors around it), bytes.
pub const BYTES_PER_CELL: f64 = 64.0;

/// The kinds of sweep plot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlotKind {
    /// Category fractions against a discrete column.
    Fractions,
    /// Histogram of one column.
    Histogram,
    /// One column against another.
    Scatter,
    /// A 2-D slice coloured by a column.
    Map,
}

impl PlotKind {
    /// All kinds.
    pub const ALL: [PlotKind; 4] = [
        PlotKind::Fractions,
        PlotKind::Histogram,
        PlotKind::Scatter,
        PlotKind::Map,
    ];

    /// The name used on the command line and in specs.
    pub fn name(self) -> &'static str {
        match self {
            PlotKind::Fractions => "fractions",
            PlotKind::Histogram => "histogram",
            PlotKind::Scatter => "scatter",
            PlotKind::Map => "map",
        }
    }

    /// The kind called `name`.
    pub fn from_name(name: &str) -> Option<PlotKind> {
        PlotKind::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// Checks the options of a sweep plot before any reading: the kind's name,
/// if given, and the width and height (between
/// [`MIN_PIXELS`](super::MIN_PIXELS) and [`MAX_PIXELS`](super::MAX_PIXELS)
/// pixels); returns the kind. The message names the argument as `spelling`
/// spells it.
///
/// ```
/// use subdiv_lab::budget::Spelling;
/// use subdiv_lab::report::sweep_plot::{check_options, PlotKind};
/// assert_eq!(check_options(Some("map"), 1600, 1000, Spelling::Cli), Ok(Some(PlotKind::Map)));
/// assert_eq!(
///     check_options(None, 10, 1000, Spelling::Python).unwrap_err(),
///     "width must be between 400 and 8000 pixels, got 10"
/// );
/// ```
pub fn check_options(
    kind: Option<&str>,
    width: u32,
    height: u32,
    spelling: crate::budget::Spelling,
) -> Result<Option<PlotKind>, String> {
    use super::{MAX_PIXELS, MIN_PIXELS};
    let kind = match kind {
        None => None,
        Some(k) => Some(PlotKind::from_name(k).ok_or_else(|| {
            let known: Vec<&str> = PlotKind::ALL.iter().map(|k| k.name()).collect();
            format!(
                "{} {k:?} is not a plot kind (known: {})",
                spelling.arg("kind"),
                known.join(", ")
            )
        })?),
    };
    for (name, v) in [("width", width), ("height", height)] {
        if !(MIN_PIXELS..=MAX_PIXELS).contains(&v) {
            return Err(format!(
                "{} must be between {MIN_PIXELS} and {MAX_PIXELS} pixels, got {v}",
                spelling.arg(name)
            ));
        }
    }
    Ok(kind)
}

/// What to plot: every field may be left to the data ([`choose`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlotRequest {
    /// Plot kind.
    pub kind: Option<PlotKind>,
    /// Column on the horizontal axis.
    pub x: Option<String>,
    /// Column on the vertical axis (scatter and map).
    pub y: Option<String>,
    /// Column giving colours or categories.
    pub color: Option<String>,
}

/// The parameter columns of a sweep table: numeric columns between `valence`
/// and `class` if both exist, else every numeric column except `id` and
/// `valence`. In a corner-interval sweep (columns `p0` and `q0`) the edge
/// ratios `r_i` are derived from the intervals, not parameters, and are left
/// out.
pub fn parameter_columns(t: &Table) -> Vec<String> {
    let names = t.names();
    let range = match (t.index("valence"), t.index("class")) {
        (Some(v), Some(c)) if v < c => v + 1..c,
        _ => 0..names.len(),
    };
    let corner = t.has("p0") && t.has("q0");
    let derived = |n: &str| {
        corner
            && n.strip_prefix('r')
                .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
    };
    names[range]
        .iter()
        .filter(|n| *n != "id" && *n != "valence" && !derived(n) && t.is_numeric(n))
        .cloned()
        .collect()
}

/// The first numeric column that is not a parameter, `id` or `valence`
/// (`contraction_rate` if present).
fn default_value_column(t: &Table, params: &[String]) -> Option<String> {
    if t.is_numeric("contraction_rate") {
        return Some("contraction_rate".to_owned());
    }
    t.names()
        .iter()
        .find(|n| *n != "id" && *n != "valence" && !params.contains(n) && t.is_numeric(n))
        .cloned()
}

/// Fills the unspecified parts of `req` from the data (see the module docs).
pub fn choose(t: &Table, req: &PlotRequest) -> Result<(PlotKind, PlotRequest), TableError> {
    let params: Vec<String> = parameter_columns(t)
        .into_iter()
        .filter(|p| t.distinct_numbers(p) > 1)
        .collect();
    let class = t.has("class").then(|| "class".to_owned());
    let multi_valence = t.has("valence") && t.distinct_numbers("valence") > 1;
    let kind = match req.kind {
        Some(k) => k,
        None if req.y.is_some() => PlotKind::Scatter,
        None if multi_valence && class.is_some() && req.x.is_none() => PlotKind::Fractions,
        None if params.len() == 2 => PlotKind::Map,
        None if params.len() == 1 => PlotKind::Scatter,
        None if req.x.is_some() => PlotKind::Histogram,
        None => PlotKind::Histogram,
    };
    let value = default_value_column(t, &params);
    let mut out = req.clone();
    out.kind = Some(kind);
    match kind {
        PlotKind::Fractions => {
            if out.x.is_none() {
                out.x = if t.has("valence") {
                    Some("valence".to_owned())
                } else {
                    params.first().cloned()
                };
            }
            if out.color.is_none() {
                out.color = class;
            }
            if out.color.is_none() {
                return Err(TableError::NoDefault(
                    "a fractions plot needs a category column (--color; the table has no `class`)"
                        .to_owned(),
                ));
            }
        }
        PlotKind::Histogram => {
            if out.x.is_none() {
                // A result column, else any numeric column.
                out.x = value.or_else(|| parameter_columns(t).into_iter().next());
            }
        }
        PlotKind::Scatter => {
            if out.x.is_none() {
                out.x = params
                    .first()
                    .cloned()
                    .or_else(|| t.has("valence").then(|| "valence".to_owned()));
            }
            if out.y.is_none() {
                out.y = value.filter(|v| Some(v) != out.x.as_ref());
            }
            if out.color.is_none() {
                out.color = class;
            }
        }
        PlotKind::Map => {
            let (gx, gy) = (out.x.clone(), out.y.clone());
            let mut free = params
                .iter()
                .filter(|p| Some(*p) != gx.as_ref() && Some(*p) != gy.as_ref());
            if out.x.is_none() {
                out.x = free.next().cloned();
            }
            if out.y.is_none() {
                out.y = free.next().cloned();
            }
            if out.color.is_none() {
                out.color = class.or(value);
            }
        }
    }
    if out.x.is_none() {
        return Err(TableError::NoDefault(format!(
            "no numeric column for the x axis of a {} plot",
            kind.name()
        )));
    }
    if matches!(kind, PlotKind::Scatter | PlotKind::Map) && out.y.is_none() {
        return Err(TableError::NoDefault(format!(
            "no second numeric column for the y axis of a {} plot",
            kind.name()
        )));
    }
    Ok((kind, out))
}

/// Colours of the plotted rows.
#[derive(Clone, Debug)]
enum Colors {
    /// One colour.
    None,
    /// Category index per row, and the categories.
    Categories(Vec<usize>, Vec<String>),
    /// A value per row (NaN: missing), and the finite range.
    Values(Vec<f64>, (f64, f64)),
}

#[derive(Clone, Debug)]
enum Data {
    Fractions {
        xs: Vec<f64>,
        cats: Vec<String>,
        /// counts[cat][x]
        counts: Vec<Vec<usize>>,
        totals: Vec<usize>,
    },
    Histogram {
        edges: Vec<f64>,
        cats: Vec<String>,
        /// counts[cat][bin]
        counts: Vec<Vec<usize>>,
    },
    Points {
        xs: Vec<f64>,
        ys: Vec<f64>,
        colors: Colors,
        /// Cell size (dx, dy) of a map on a grid.
        cell: Option<(f64, f64)>,
    },
}

/// A sweep plot, built from a table and ready to draw.
#[derive(Clone, Debug)]
pub struct SweepPlot {
    kind: PlotKind,
    x: String,
    y: Option<String>,
    color: Option<String>,
    data: Data,
}

/// Finite `(x, y)` values of two numeric columns and the row indices kept.
fn finite_pairs(xs: &[Option<f64>], ys: &[Option<f64>]) -> Vec<usize> {
    (0..xs.len())
        .filter(|&i| matches!((xs[i], ys[i]), (Some(a), Some(b)) if a.is_finite() && b.is_finite()))
        .collect()
}

/// Categories of `labels` in order of first appearance; `None` if there are
/// more than [`MAX_CATEGORIES`].
fn categories(labels: &[String]) -> Vec<String> {
    let mut cats: Vec<String> = Vec::new();
    for l in labels {
        if !cats.contains(l) {
            cats.push(l.clone());
            if cats.len() > MAX_CATEGORIES {
                break;
            }
        }
    }
    cats
}

fn too_many(
    name: &str,
    count: usize,
    max: usize,
    kind: PlotKind,
    hint: &'static str,
) -> TableError {
    TableError::TooManyValues {
        name: name.to_owned(),
        count,
        max,
        kind: kind.name(),
        hint,
    }
}

/// Smallest positive gap between sorted distinct values (`None` if one value).
fn grid_step(v: &[f64]) -> Option<f64> {
    let mut s: Vec<f64> = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.dedup();
    s.windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .min_by(f64::total_cmp)
}

/// Largest magnitude of a value on a plot axis or colour scale: the axis
/// range is padded by a few percent and divided into ticks, so the span and
/// the padded ends must stay finite (values of `+-1e308` made the tick
/// search loop for ever). `1e300` leaves a wide margin below `f64::MAX`.
pub const MAX_PLOT_MAGNITUDE: f64 = 1e300;

/// Refuses a column with a finite value beyond [`MAX_PLOT_MAGNITUDE`].
fn check_magnitude(name: &str, values: &[Option<f64>]) -> Result<(), TableError> {
    match values
        .iter()
        .flatten()
        .find(|v| v.is_finite() && v.abs() > MAX_PLOT_MAGNITUDE)
    {
        Some(&value) => Err(TableError::TooLargeToPlot {
            name: name.to_owned(),
            value,
            max: MAX_PLOT_MAGNITUDE,
        }),
        None => Ok(()),
    }
}

impl SweepPlot {
    /// Builds the plot: chooses what `req` leaves open ([`choose`]) and
    /// extracts the data; errors name the offending column.
    pub fn build(t: &Table, req: &PlotRequest) -> Result<SweepPlot, TableError> {
        let (kind, req) = choose(t, req)?;
        let x = req.x.clone().unwrap_or_default();
        let xs = t.numeric(&x)?;
        if !xs.iter().flatten().any(|v| v.is_finite()) {
            return Err(TableError::NoFiniteValues(x));
        }
        check_magnitude(&x, &xs)?;
        let color_labels = match &req.color {
            Some(c) => Some(t.labels(c)?),
            None => None,
        };
        let data = match kind {
            PlotKind::Fractions => {
                let color = req.color.clone().unwrap_or_default();
                let labels = color_labels.unwrap_or_default();
                let cats = categories(&labels);
                if cats.len() > MAX_CATEGORIES {
                    return Err(too_many(
                        &color,
                        cats.len(),
                        MAX_CATEGORIES,
                        kind,
                        "choose a column of categories, such as class",
                    ));
                }
                let mut gx: Vec<f64> = xs
                    .iter()
                    .flatten()
                    .copied()
                    .filter(|v| v.is_finite())
                    .collect();
                gx.sort_by(f64::total_cmp);
                gx.dedup();
                if gx.len() > MAX_GROUPS {
                    return Err(too_many(
                        &x,
                        gx.len(),
                        MAX_GROUPS,
                        kind,
                        "use --kind histogram with --color for a continuous column",
                    ));
                }
                let mut counts = vec![vec![0usize; gx.len()]; cats.len()];
                let mut totals = vec![0usize; gx.len()];
                for (i, v) in xs.iter().enumerate() {
                    let Some(v) = v.filter(|v| v.is_finite()) else {
                        continue;
                    };
                    let Ok(k) = gx.binary_search_by(|g| g.total_cmp(&v)) else {
                        continue;
                    };
                    let Some(c) = cats.iter().position(|c| *c == labels[i]) else {
                        continue;
                    };
                    counts[c][k] += 1;
                    totals[k] += 1;
                }
                Data::Fractions {
                    xs: gx,
                    cats,
                    counts,
                    totals,
                }
            }
            PlotKind::Histogram => {
                let labels = color_labels.unwrap_or_else(|| vec![String::new(); xs.len()]);
                let cats = categories(&labels);
                if cats.len() > MAX_CATEGORIES {
                    let c = req.color.clone().unwrap_or_default();
                    return Err(too_many(
                        &c,
                        cats.len(),
                        MAX_CATEGORIES,
                        kind,
                        "choose a column of categories, such as class",
                    ));
                }
                let vals: Vec<(f64, usize)> = xs
                    .iter()
                    .enumerate()
                    .filter_map(|(i, v)| v.filter(|v| v.is_finite()).map(|v| (v, i)))
                    .collect();
                let lo = vals.iter().map(|v| v.0).fold(f64::INFINITY, f64::min);
                let hi = vals.iter().map(|v| v.0).fold(f64::NEG_INFINITY, f64::max);
                let bins = ((vals.len() as f64).sqrt().round() as usize).clamp(MIN_BINS, MAX_BINS);
                let (lo, hi) = if hi > lo {
                    (lo, hi)
                } else {
                    (lo - 0.5, lo + 0.5)
                };
                let w = (hi - lo) / bins as f64;
                let edges: Vec<f64> = (0..=bins).map(|k| lo + w * k as f64).collect();
                let mut counts = vec![vec![0usize; bins]; cats.len()];
                for (v, i) in vals {
                    let b = (((v - lo) / w) as usize).min(bins - 1);
                    if let Some(c) = cats.iter().position(|c| *c == labels[i]) {
                        counts[c][b] += 1;
                    }
                }
                Data::Histogram {
                    edges,
                    cats,
                    counts,
                }
            }
            PlotKind::Scatter | PlotKind::Map => {
                let y = req.y.clone().unwrap_or_default();
                let ys = t.numeric(&y)?;
                check_magnitude(&y, &ys)?;
                let keep = finite_pairs(&xs, &ys);
                if keep.is_empty() {
                    return Err(TableError::NoFiniteValues(format!("{x}\" and \"{y}")));
                }
                let colors = match (&req.color, color_labels) {
                    (Some(c), Some(labels)) => {
                        // Numbers are categories only if they are few whole
                        // numbers (a valence); else a continuous colour scale.
                        let whole = t
                            .numeric(c)
                            .is_ok_and(|v| v.iter().flatten().all(|x| x.fract() == 0.0));
                        if t.is_numeric(c) && (!whole || t.distinct_numbers(c) > MAX_CATEGORIES) {
                            let v = t.numeric(c)?;
                            check_magnitude(c, &v)?;
                            let vals: Vec<f64> =
                                keep.iter().map(|&i| v[i].unwrap_or(f64::NAN)).collect();
                            let fin = vals.iter().copied().filter(|v| v.is_finite());
                            let lo = fin.clone().fold(f64::INFINITY, f64::min);
                            let hi = fin.fold(f64::NEG_INFINITY, f64::max);
                            if !lo.is_finite() {
                                return Err(TableError::NoFiniteValues(c.clone()));
                            }
                            Colors::Values(vals, (lo, hi))
                        } else {
                            let kept: Vec<String> =
                                keep.iter().map(|&i| labels[i].clone()).collect();
                            let cats = categories(&kept);
                            if cats.len() > MAX_CATEGORIES {
                                return Err(too_many(
                                    c,
                                    cats.len(),
                                    MAX_CATEGORIES,
                                    kind,
                                    "colour by a numeric column or by categories such as class",
                                ));
                            }
                            let idx = kept
                                .iter()
                                .map(|l| cats.iter().position(|c| c == l).unwrap_or(0))
                                .collect();
                            Colors::Categories(idx, cats)
                        }
                    }
                    _ => Colors::None,
                };
                let px: Vec<f64> = keep.iter().map(|&i| xs[i].unwrap_or(f64::NAN)).collect();
                let py: Vec<f64> = keep.iter().map(|&i| ys[i].unwrap_or(f64::NAN)).collect();
                let cell = if kind == PlotKind::Map && px.len() <= 1_000_000 {
                    match (grid_step(&px), grid_step(&py)) {
                        (Some(dx), Some(dy)) => Some((dx, dy)),
                        _ => None,
                    }
                } else {
                    None
                };
                Data::Points {
                    xs: px,
                    ys: py,
                    colors,
                    cell,
                }
            }
        };
        Ok(SweepPlot {
            kind,
            x,
            y: req.y.clone(),
            color: req.color.clone(),
            data,
        })
    }

    /// The plot kind.
    pub fn kind(&self) -> PlotKind {
        self.kind
    }

    /// Number of drawn items (points, bars or line vertices).
    pub fn items(&self) -> usize {
        match &self.data {
            Data::Fractions { xs, cats, .. } => xs.len() * cats.len(),
            Data::Histogram { counts, .. } => counts.iter().map(Vec::len).sum(),
            Data::Points { xs, .. } => xs.len(),
        }
    }

    /// A title naming the columns.
    pub fn default_title(&self) -> String {
        let c = self.color.as_deref().unwrap_or("");
        match self.kind {
            PlotKind::Fractions => format!("Fraction of configurations by {c} against {}", self.x),
            PlotKind::Histogram if c.is_empty() => format!("Histogram of {}", self.x),
            PlotKind::Histogram => format!("Histogram of {} by {c}", self.x),
            PlotKind::Scatter | PlotKind::Map => {
                let y = self.y.as_deref().unwrap_or("");
                if c.is_empty() {
                    format!("{y} against {}", self.x)
                } else {
                    format!("{y} against {}, coloured by {c}", self.x)
                }
            }
        }
    }

    /// The data plotted, as a table (what a report writes as CSV).
    pub fn data(&self) -> DataTable {
        match &self.data {
            Data::Fractions {
                xs,
                cats,
                counts,
                totals,
            } => {
                let c = self.color.as_deref().unwrap_or("category");
                let mut t = DataTable::new(None, &[&self.x, c, "count", "fraction"]);
                for (k, x) in xs.iter().enumerate() {
                    for (ci, cat) in cats.iter().enumerate() {
                        let n = counts[ci][k];
                        t.push(vec![
                            num(*x),
                            cat.clone(),
                            n.to_string(),
                            num(n as f64 / totals[k].max(1) as f64),
                        ]);
                    }
                }
                t
            }
            Data::Histogram {
                edges,
                cats,
                counts,
            } => {
                let c = self.color.as_deref().unwrap_or("category");
                let mut t = DataTable::new(None, &["bin_lo", "bin_hi", c, "count"]);
                for b in 0..edges.len() - 1 {
                    for (ci, cat) in cats.iter().enumerate() {
                        t.push(vec![
                            num(edges[b]),
                            num(edges[b + 1]),
                            cat.clone(),
                            counts[ci][b].to_string(),
                        ]);
                    }
                }
                t
            }
            Data::Points { xs, ys, colors, .. } => {
                let y = self.y.as_deref().unwrap_or("y");
                let mut head = vec![self.x.as_str(), y];
                if let Some(c) = &self.color {
                    head.push(c);
                }
                let mut t = DataTable::new(None, &head);
                for i in 0..xs.len() {
                    let mut row = vec![num(xs[i]), num(ys[i])];
                    match colors {
                        Colors::None => {}
                        Colors::Categories(idx, cats) => row.push(cats[idx[i]].clone()),
                        Colors::Values(v, _) => row.push(num(v[i])),
                    }
                    if row.len() == head.len() {
                        t.push(row);
                    }
                }
                t
            }
        }
    }

    /// Draws the plot with `title` on `area` of `size` pixels.
    pub fn draw(&self, area: &Area<'_>, title: &str, size: (u32, u32)) -> Result<(), ReportError> {
        let th = Theme::for_size(size);
        let body = titled(area, title, &th)?;
        let (w, _) = body.dim_in_pixel();
        let side_w = (w as f64 * 0.24) as u32;
        let (main, side) = body.split_horizontally(w - side_w);
        let cat_color = |cats: &[String], i: usize| -> RGBColor {
            if cats
                .iter()
                .all(|c| super::figures::knot_map::CLASSES.contains(&c.as_str()))
            {
                class_color(&cats[i])
            } else {
                series_color(i, cats.len())
            }
        };
        // The enlarged marker of a rare category of a map (drawn on top).
        let rare_marker = |cats: &[String], i: usize| -> Marker {
            if cats
                .iter()
                .all(|c| super::figures::knot_map::CLASSES.contains(&c.as_str()))
            {
                super::figures::knot_map::rare_marker(&cats[i])
            } else {
                Marker::nth(i)
            }
        };
        let legend = |cats: &[String], marker: bool, rare: &[bool]| -> Result<(), ReportError> {
            let entries: Vec<(LegendGlyph, Vec<String>)> = cats
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let col = cat_color(cats, i);
                    let g = if marker {
                        LegendGlyph::line((0, 0), &th, col, th.line)
                            .marker(Marker::nth(i), th.marker)
                    } else if rare.get(i) == Some(&true) {
                        LegendGlyph::line((0, 0), &th, col, 0)
                            .boxed()
                            .marker(rare_marker(cats, i), th.marker)
                    } else {
                        LegendGlyph::line((0, 0), &th, col, 0).boxed()
                    };
                    let name = if c.is_empty() {
                        "(missing)".to_owned()
                    } else {
                        c.replace('_', " ")
                    };
                    (g, vec![name])
                })
                .collect();
            side_legend(&side, &entries, &th)
        };
        let pad = |lo: f64, hi: f64| -> (f64, f64) {
            if hi > lo {
                let m = (hi - lo) * 0.04;
                (lo - m, hi + m)
            } else {
                (lo - 0.5, hi + 0.5)
            }
        };
        let mut builder = ChartBuilder::on(&main);
        builder
            .margin(th.tick as i32)
            .x_label_area_size(th.label * 3)
            .y_label_area_size(th.label * 4);
        match &self.data {
            Data::Fractions {
                xs,
                cats,
                counts,
                totals,
            } => {
                let (x0, x1) = pad(xs[0], xs[xs.len() - 1]);
                let mut chart = builder
                    .build_cartesian_2d(x0..x1, -0.02f64..1.02f64)
                    .map_err(draw_err)?;
                // One tick per discrete value, up to 10.
                mesh(
                    &mut chart,
                    &self.x,
                    "fraction of configurations",
                    xs.len().clamp(2, 10),
                    &th,
                )?;
                for (ci, _) in cats.iter().enumerate() {
                    let col = cat_color(cats, ci);
                    let pts: Vec<(f64, f64)> = xs
                        .iter()
                        .enumerate()
                        .filter(|(k, _)| totals[*k] > 0)
                        .map(|(k, x)| (*x, counts[ci][k] as f64 / totals[k] as f64))
                        .collect();
                    chart
                        .draw_series(LineSeries::new(pts.clone(), col.stroke_width(th.line)))
                        .map_err(draw_err)?;
                    let ms = if pts.len() > 80 {
                        th.marker / 2
                    } else {
                        th.marker
                    };
                    chart
                        .draw_series(pts.iter().map(|p| Marker::nth(ci).at(*p, ms.max(2), col)))
                        .map_err(draw_err)?;
                }
                legend(cats, true, &[])
            }
            Data::Histogram {
                edges,
                cats,
                counts,
            } => {
                let bins = edges.len() - 1;
                let top = (0..bins)
                    .map(|b| counts.iter().map(|c| c[b]).sum::<usize>())
                    .max()
                    .unwrap_or(1)
                    .max(1) as f64;
                let mut chart = builder
                    .build_cartesian_2d(edges[0]..edges[bins], 0f64..top * 1.05)
                    .map_err(draw_err)?;
                mesh(&mut chart, &self.x, "count", 6, &th)?;
                let mut base = vec![0usize; bins];
                for (ci, c) in counts.iter().enumerate() {
                    let col = if cats.len() == 1 {
                        viridis(0.3)
                    } else {
                        cat_color(cats, ci)
                    };
                    chart
                        .draw_series((0..bins).filter(|b| c[*b] > 0).map(|b| {
                            Rectangle::new(
                                [
                                    (edges[b], base[b] as f64),
                                    (edges[b + 1], (base[b] + c[b]) as f64),
                                ],
                                col.filled(),
                            )
                        }))
                        .map_err(draw_err)?;
                    for b in 0..bins {
                        base[b] += c[b];
                    }
                }
                if cats.len() > 1 || self.color.is_some() {
                    legend(cats, false, &[])?;
                }
                Ok(())
            }
            Data::Points {
                xs,
                ys,
                colors,
                cell,
            } => {
                let fx = |v: &[f64]| {
                    (
                        v.iter().copied().fold(f64::INFINITY, f64::min),
                        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                    )
                };
                let ((mut x0, mut x1), (mut y0, mut y1)) = (fx(xs), fx(ys));
                if let Some((dx, dy)) = cell {
                    (x0, x1, y0, y1) = (x0 - dx / 2.0, x1 + dx / 2.0, y0 - dy / 2.0, y1 + dy / 2.0);
                } else {
                    (x0, x1) = pad(x0, x1);
                    (y0, y1) = pad(y0, y1);
                }
                let mut chart = builder
                    .build_cartesian_2d(x0..x1, y0..y1)
                    .map_err(draw_err)?;
                mesh(&mut chart, &self.x, self.y.as_deref().unwrap_or(""), 8, &th)?;
                let color_of = |i: usize| -> RGBColor {
                    match colors {
                        Colors::None => viridis(0.1),
                        Colors::Categories(idx, cats) => cat_color(cats, idx[i]),
                        Colors::Values(v, (lo, hi)) => {
                            if v[i].is_finite() {
                                viridis(if hi > lo {
                                    (v[i] - lo) / (hi - lo)
                                } else {
                                    0.5
                                })
                            } else {
                                RGBColor(215, 215, 215)
                            }
                        }
                    }
                };
                let dense = xs.len() > DENSE_POINTS;
                let rare = match (colors, cell) {
                    (Colors::Categories(idx, cats), Some(_)) => rare_categories(idx, cats.len()),
                    _ => Vec::new(),
                };
                match cell {
                    Some((dx, dy)) => {
                        chart
                            .draw_series((0..xs.len()).map(|i| {
                                Rectangle::new(
                                    [
                                        (xs[i] - dx / 2.0, ys[i] - dy / 2.0),
                                        (xs[i] + dx / 2.0, ys[i] + dy / 2.0),
                                    ],
                                    color_of(i).filled(),
                                )
                            }))
                            .map_err(draw_err)?;
                        if let Colors::Categories(idx, cats) = colors {
                            // Measure-zero sets on top, as on the knot map:
                            // enlarged markers (a cell wide, at least a
                            // marker) with a white halo.
                            let (ax, _) = chart.backend_coord(&(x0, y0));
                            let (bx, _) = chart.backend_coord(&(x0 + dx, y0));
                            let ms = (((bx - ax).abs() as f64) * 0.9).max(th.marker as f64) as i32;
                            for (c, _) in cats.iter().enumerate().filter(|(c, _)| rare[*c]) {
                                let m = rare_marker(cats, c);
                                let at: Vec<(f64, f64)> = (0..xs.len())
                                    .filter(|&i| idx[i] == c)
                                    .map(|i| (xs[i], ys[i]))
                                    .collect();
                                chart
                                    .draw_series(at.iter().map(|p| m.at(*p, ms + 2, WHITE)))
                                    .map_err(draw_err)?;
                                chart
                                    .draw_series(
                                        at.iter().map(|p| m.at(*p, ms, cat_color(cats, c))),
                                    )
                                    .map_err(draw_err)?;
                            }
                        }
                    }
                    None => {
                        let marker = |i: usize| match colors {
                            Colors::Categories(idx, _) if !dense => Marker::nth(idx[i]),
                            _ => Marker::Circle,
                        };
                        let ms = if dense {
                            (th.marker / 3).max(1)
                        } else {
                            th.marker
                        };
                        chart
                            .draw_series(
                                (0..xs.len())
                                    .map(|i| marker(i).at((xs[i], ys[i]), ms, color_of(i))),
                            )
                            .map_err(draw_err)?;
                    }
                }
                match colors {
                    Colors::None => Ok(()),
                    Colors::Categories(_, cats) => legend(cats, cell.is_none() && !dense, &rare),
                    Colors::Values(_, (lo, hi)) => colorbar(
                        &side,
                        *lo,
                        if hi > lo { *hi } else { lo + 1.0 },
                        self.color.as_deref().unwrap_or(""),
                        &th,
                        &viridis,
                    ),
                }
            }
        }
    }
}

/// Which of `count` categories (the category of each cell in `idx`) a map
/// draws as measure-zero sets: those with fewer than
/// [`RARE_SHARE`](super::figures::knot_map::RARE_SHARE) of the cells, as on
/// the knot map (special classes such as `standard` or `not_separated` are
/// points and curves of the parameter space, too thin to see as fill).
fn rare_categories(idx: &[usize], count: usize) -> Vec<bool> {
    let mut n = vec![0usize; count];
    for &i in idx {
        if let Some(c) = n.get_mut(i) {
            *c += 1;
        }
    }
    let total = idx.len() as f64;
    n.iter()
        .map(|&k| k > 0 && (k as f64) < super::figures::knot_map::RARE_SHARE * total)
        .collect()
}

/// Axes, tick labels (no negative zero) and axis descriptions.
fn mesh<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    x: &str,
    y: &str,
    x_labels: usize,
    th: &Theme,
) -> Result<(), ReportError> {
    chart
        .configure_mesh()
        .x_labels(x_labels)
        .x_desc(x)
        .y_desc(y)
        .label_style(th.font(th.tick))
        .axis_desc_style(th.font(th.label))
        .light_line_style(WHITE)
        .bold_line_style(BLACK.mix(0.08))
        .x_label_formatter(&|v| super::plot::tick(*v))
        .y_label_formatter(&|v| super::plot::tick(*v))
        .draw()
        .map_err(draw_err)
}

/// The estimated cost of plotting `rows` rows of `columns` columns (reading
/// and drawing every row into SVG and PNG), for the CLI's work limits.
pub fn estimate(rows: usize, columns: usize) -> Estimate {
    Estimate {
        bytes: rows as f64 * columns.max(1) as f64 * BYTES_PER_CELL,
        seconds: rows as f64 * SECONDS_PER_POINT,
        what: format!("plotting {rows} rows"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(s: &str) -> Table {
        Table::from_csv(s.as_bytes()).unwrap()
    }

    #[test]
    fn defaults_follow_the_data() {
        let multi = t("id,valence,r0,class,x\n0,3,0.1,standard,1\n1,4,0.1,defective,2\n");
        assert_eq!(
            choose(&multi, &PlotRequest::default()).unwrap().0,
            PlotKind::Fractions
        );
        let slice = t("id,valence,r0,r1,r2,class,contraction_rate\n0,3,0.1,0.1,0.5,a,1\n1,3,0.2,0.1,0.5,b,2\n2,3,0.1,0.2,0.5,a,3\n");
        let (k, r) = choose(&slice, &PlotRequest::default()).unwrap();
        assert_eq!(k, PlotKind::Map);
        assert_eq!(
            (r.x.as_deref(), r.y.as_deref(), r.color.as_deref()),
            (Some("r0"), Some("r1"), Some("class"))
        );
        let line = t("id,valence,c,class,contraction_rate\n0,3,0.1,a,1\n1,3,0.2,b,2\n");
        let (k, r) = choose(&line, &PlotRequest::default()).unwrap();
        assert_eq!(
            (k, r.y.as_deref()),
            (PlotKind::Scatter, Some("contraction_rate"))
        );
    }

    #[test]
    fn fractions_sum_to_one_per_valence() {
        let tab = t("valence,class\n3,a\n3,b\n3,b\n5,a\n");
        let p = SweepPlot::build(&tab, &PlotRequest::default()).unwrap();
        let d = p.data();
        for v in ["3", "5"] {
            let s: f64 = d
                .rows
                .iter()
                .filter(|r| r[0] == v)
                .map(|r| r[3].parse::<f64>().unwrap())
                .sum();
            assert!((s - 1.0).abs() < 1e-12, "{v}: {s}");
        }
        assert!(d
            .rows
            .contains(&vec!["3".into(), "b".into(), "2".into(), num(2.0 / 3.0)]));
    }

    #[test]
    fn histogram_counts_every_finite_row() {
        let mut s = String::from("x\n");
        for i in 0..200 {
            s.push_str(&format!("{}\n", (i as f64 * 0.37).sin()));
        }
        s.push_str("NaN\n\n");
        let p = SweepPlot::build(
            &t(&s),
            &PlotRequest {
                kind: Some(PlotKind::Histogram),
                ..Default::default()
            },
        )
        .unwrap();
        let total: usize = p
            .data()
            .rows
            .iter()
            .map(|r| r[3].parse::<usize>().unwrap())
            .sum();
        assert_eq!(total, 200);
    }

    #[test]
    fn bad_columns_are_named() {
        let tab = t("valence,class,v\n3,a,x\n4,b,1\n");
        let req = |x: &str| PlotRequest {
            kind: Some(PlotKind::Histogram),
            x: Some(x.into()),
            ..Default::default()
        };
        let e = SweepPlot::build(&tab, &req("nope"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("\"nope\""), "{e}");
        let e = SweepPlot::build(&tab, &req("v")).unwrap_err().to_string();
        assert!(e.contains("\"v\"") && e.contains("not numeric"), "{e}");
    }

    /// A corner-interval table: its `r_i` are derived, not parameters, so a
    /// slice of two intervals is still a class map.
    #[test]
    fn derived_ratios_are_not_parameters() {
        let tab = t("id,valence,p0,p1,p2,q0,q1,q2,r0,r1,r2,class\n0,3,1,1,1,1,1,1,0.5,0.5,0.5,a\n1,3,2,1,1,1,1,1,0.3,0.5,0.5,b\n2,3,1,1,1,1,2,1,0.6,0.5,0.5,a\n");
        assert_eq!(
            parameter_columns(&tab),
            ["p0", "p1", "p2", "q0", "q1", "q2"]
        );
        let (k, r) = choose(&tab, &PlotRequest::default()).unwrap();
        assert_eq!(
            (k, r.x.as_deref(), r.y.as_deref()),
            (PlotKind::Map, Some("p0"), Some("q1"))
        );
        // Without intervals, r columns are the parameters.
        let ratios = t("id,valence,r0,r1,class\n0,3,0.1,0.1,a\n1,3,0.2,0.1,b\n");
        assert_eq!(parameter_columns(&ratios), ["r0", "r1"]);
    }

    /// A map draws a class below 2% of its cells (a measure-zero set) as
    /// enlarged markers on top, one per cell, and marks its legend box; a
    /// common class gets none (issue 21).
    #[test]
    fn map_marks_rare_classes() {
        assert_eq!(rare_categories(&[0, 0, 1, 0], 3), [false, false, false]);
        let mut idx = vec![0usize; 99];
        idx.push(1);
        assert_eq!(rare_categories(&idx, 3), [false, true, false]);
        // A 10 x 10 grid: one `standard` cell, three `not_separated` cells
        // (3%: common enough to be seen as fill), the rest real_distinct.
        let mut s = String::from("r0,r1,class\n");
        for i in 0..10 {
            for j in 0..10 {
                let class = match (i, j) {
                    (4, 5) => "standard",
                    (_, 0) if i < 3 => "not_separated",
                    _ => "real_distinct",
                };
                s.push_str(&format!(
                    "{},{},{class}\n",
                    i as f64 / 10.0,
                    j as f64 / 10.0
                ));
            }
        }
        let tab = t(&s);
        let p = SweepPlot::build(&tab, &PlotRequest::default()).unwrap();
        assert_eq!(p.kind(), PlotKind::Map);
        let svg = |p: &SweepPlot| {
            crate::report::render_svg((800, 500), &|a: &Area<'_>| p.draw(a, "t", (800, 500)))
                .unwrap()
        };
        // The standard point's marker (a diamond: a 4-point polygon) in its
        // colour, over a white halo, on the map and in the legend.
        let std_color = {
            let c = class_color("standard");
            format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
        };
        let with = svg(&p);
        let polygons_in = |svg: &str, color: &str| {
            svg.lines()
                .filter(|l| l.contains("<polygon") && l.contains(color))
                .count()
        };
        assert_eq!(polygons_in(&with, &std_color), 2, "map and legend");
        // The same table without the rare cell: no marker of that colour.
        let common = t(&s.replace("standard", "real_distinct"));
        let without = svg(&SweepPlot::build(&common, &PlotRequest::default()).unwrap());
        assert_eq!(polygons_in(&without, &std_color), 0);
        assert!(with.len() > without.len());
    }
}
