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
//! valence for a multi-valence sweep with a `class` column; for one valence, a
//! class map when exactly two parameter columns vary (a 2-D slice), a scatter
//! of `contraction_rate` when one varies, and otherwise the class fractions
//! too; a histogram for a table without a `class` column. Parameter columns
//! are those between `valence` and `class` in a sweep CSV (all numeric
//! columns but `id` and `valence` otherwise).
//!
//! The `cells.csv` of `subdiv-lab verify` (columns `lo0..`, `hi0..` or
//! `c_lo, c_hi`, and `verdict`; [`cell_coordinates`]) is drawn as the
//! certified map: every cell as its rectangle over two coordinates (default
//! `r0`, `r1`; `c` alone for an interval of `c`), coloured by `verdict` (or
//! `--color` naming a property column), the other coordinates held at the
//! middle of the box (the cells containing that point tile the slice).
//!
//! Rows without a finite value on a plotted axis (missing, NaN or infinite)
//! are left out and counted ([`SweepPlot::dropped`]).
//!
//! ```
//! use subdiv_lab::table::Table;
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
use crate::budget::Estimate;
use crate::table::{Table, TableError};
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
/// Most points or cells drawn into an SVG without `--force`: each is an SVG
/// element of about [`SVG_BYTES_PER_ITEM`] bytes, so the file stays below
/// about 8 MB (3 million scatter points made a 240 MB SVG). A PNG has a
/// fixed size whatever the number of points.
pub const MAX_SVG_ITEMS: usize = 100_000;
/// Bytes of SVG per drawn point or cell: measured 80 (a 3-million-point
/// scatter, 240 MB).
pub const SVG_BYTES_PER_ITEM: f64 = 80.0;

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
    let slice = params.len() == 1 || params.len() == 2;
    let kind = match req.kind {
        Some(k) => k,
        None if req.y.is_some() => PlotKind::Scatter,
        None if class.is_some() && req.x.is_none() && (multi_valence || !slice) => {
            PlotKind::Fractions
        }
        None if params.len() == 2 => PlotKind::Map,
        None if params.len() == 1 => PlotKind::Scatter,
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
    /// The cells of a `verify` run: `[x_lo, x_hi, y_lo, y_hi]` per cell (`y`
    /// from 0 to 1 for one coordinate), the category of each, the
    /// categories, the box, and the coordinates held fixed.
    Cells {
        rects: Vec<[f64; 4]>,
        idx: Vec<usize>,
        cats: Vec<String>,
        bounds: [f64; 4],
        fixed: Vec<(String, f64)>,
    },
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
    /// Rows left out for a missing, NaN or infinite value on a plotted axis.
    dropped: usize,
}

/// The coordinates of a `verify` cells table (`cells.csv`, see
/// [`crate::verify::csv_header`]): per coordinate, its name and its lower and
/// upper columns: `r{i}` from `lo{i}`, `hi{i}` (edge ratios), or `c` from
/// `c_lo`, `c_hi`. `None` for a table without a `verdict` column or without
/// such pairs.
pub fn cell_coordinates(t: &Table) -> Option<Vec<(String, String, String)>> {
    if !t.has("verdict") {
        return None;
    }
    if t.has("c_lo") && t.has("c_hi") {
        return Some(vec![("c".into(), "c_lo".into(), "c_hi".into())]);
    }
    let v: Vec<(String, String, String)> = (0..)
        .map(|i| (format!("r{i}"), format!("lo{i}"), format!("hi{i}")))
        .take_while(|(_, lo, hi)| t.has(lo) && t.has(hi))
        .collect();
    (!v.is_empty()).then_some(v)
}

/// Whether `req` asks for the certified map of a cells table with
/// coordinates `coords` (no kind or `map`, axes among the coordinates).
fn wants_cells(req: &PlotRequest, coords: &[(String, String, String)]) -> bool {
    let coordinate = |a: &Option<String>| {
        a.as_ref()
            .is_none_or(|a| coords.iter().any(|(name, _, _)| name == a))
    };
    matches!(req.kind, None | Some(PlotKind::Map)) && coordinate(&req.x) && coordinate(&req.y)
}

/// The certified map of a `verify` cells table (module docs).
fn build_cells(
    t: &Table,
    req: &PlotRequest,
    coords: &[(String, String, String)],
) -> Result<SweepPlot, TableError> {
    let pos = |name: &str| coords.iter().position(|(n, _, _)| n == name);
    let xi = req.x.as_deref().and_then(pos).unwrap_or(0);
    let yi = match req.y.as_deref() {
        Some(y) => pos(y),
        None => (0..coords.len()).find(|&k| k != xi),
    };
    if yi == Some(xi) {
        return Err(TableError::NoDefault(format!(
            "--x and --y both name the coordinate {}",
            coords[xi].0
        )));
    }
    let color = req.color.clone().unwrap_or_else(|| "verdict".to_owned());
    let labels = t.labels(&color)?;
    let lo: Vec<Vec<Option<f64>>> = coords
        .iter()
        .map(|(_, l, _)| t.numeric(l))
        .collect::<Result<_, _>>()?;
    let hi: Vec<Vec<Option<f64>>> = coords
        .iter()
        .map(|(_, _, h)| t.numeric(h))
        .collect::<Result<_, _>>()?;
    for (k, (_, l, h)) in coords.iter().enumerate() {
        check_magnitude(l, &lo[k])?;
        check_magnitude(h, &hi[k])?;
    }
    let finite = |i: usize| {
        (0..coords.len()).all(|k| {
            matches!((lo[k][i], hi[k][i]), (Some(a), Some(b)) if a.is_finite() && b.is_finite())
        })
    };
    let rows: Vec<usize> = (0..t.len()).filter(|&i| finite(i)).collect();
    let dropped = t.len() - rows.len();
    if rows.is_empty() {
        return Err(TableError::NoFiniteValues(coords[xi].1.clone()));
    }
    let range = |k: usize| {
        let a = rows
            .iter()
            .map(|&i| lo[k][i].unwrap_or(0.0))
            .fold(f64::INFINITY, f64::min);
        let b = rows
            .iter()
            .map(|&i| hi[k][i].unwrap_or(0.0))
            .fold(f64::NEG_INFINITY, f64::max);
        (a, b)
    };
    // The other coordinates at the middle of the box; a cell is in the slice
    // when the point lies in its half-open side [lo, hi) (or at the top end).
    let fixed: Vec<(usize, f64, f64)> = (0..coords.len())
        .filter(|&k| k != xi && Some(k) != yi)
        .map(|k| {
            let (a, b) = range(k);
            (k, 0.5 * a + 0.5 * b, b)
        })
        .collect();
    let in_slice = |i: usize| {
        fixed.iter().all(|&(k, v, top)| {
            let (a, b) = (lo[k][i].unwrap_or(0.0), hi[k][i].unwrap_or(0.0));
            (a <= v && v < b) || (v == top && b == top && a <= v)
        })
    };
    let kept: Vec<usize> = rows.iter().copied().filter(|&i| in_slice(i)).collect();
    let kept_labels: Vec<String> = kept.iter().map(|&i| labels[i].clone()).collect();
    let cats = categories(&kept_labels);
    if cats.len() > MAX_CATEGORIES {
        return Err(too_many(
            &color,
            cats.len(),
            MAX_CATEGORIES,
            PlotKind::Map,
            "colour by verdict or by a property column",
        ));
    }
    let idx: Vec<usize> = kept_labels
        .iter()
        .map(|l| cats.iter().position(|c| c == l).unwrap_or(0))
        .collect();
    let rects: Vec<[f64; 4]> = kept
        .iter()
        .map(|&i| {
            let (y0, y1) = match yi {
                Some(k) => (lo[k][i].unwrap_or(0.0), hi[k][i].unwrap_or(0.0)),
                None => (0.0, 1.0),
            };
            [lo[xi][i].unwrap_or(0.0), hi[xi][i].unwrap_or(0.0), y0, y1]
        })
        .collect();
    let (x0, x1) = range(xi);
    let (y0, y1) = yi.map_or((0.0, 1.0), range);
    Ok(SweepPlot {
        kind: PlotKind::Map,
        x: coords[xi].0.clone(),
        y: yi.map(|k| coords[k].0.clone()),
        color: Some(color),
        data: Data::Cells {
            rects,
            idx,
            cats,
            bounds: [x0, x1, y0, y1],
            fixed: fixed
                .iter()
                .map(|&(k, v, _)| (coords[k].0.clone(), v))
                .collect(),
        },
        dropped,
    })
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
        if let Some(coords) = cell_coordinates(t).filter(|c| wants_cells(req, c)) {
            return build_cells(t, req, &coords);
        }
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
        let finite_x = xs.iter().flatten().filter(|v| v.is_finite()).count();
        let mut dropped = t.len() - finite_x;
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
                dropped = t.len() - keep.len();
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
            dropped,
        })
    }

    /// Rows left out because a plotted coordinate (`x`, or `x` or `y`) is
    /// missing, NaN or infinite.
    pub fn dropped(&self) -> usize {
        self.dropped
    }

    /// The plotted axes, `x` or `x` and `y` (for messages).
    pub fn axes(&self) -> String {
        match &self.y {
            Some(y) if !matches!(self.kind, PlotKind::Fractions | PlotKind::Histogram) => {
                format!("{} or {y}", self.x)
            }
            _ => self.x.clone(),
        }
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
            Data::Cells { rects, .. } => rects.len(),
        }
    }

    /// A title naming the columns.
    pub fn default_title(&self) -> String {
        let c = self.color.as_deref().unwrap_or("");
        if let Data::Cells { fixed, .. } = &self.data {
            let over = match &self.y {
                Some(y) => format!("Certified map: {c} over {} and {y}", self.x),
                None => format!("Certified map: {c} over {}", self.x),
            };
            if fixed.is_empty() {
                return over;
            }
            let at: Vec<String> = fixed
                .iter()
                .map(|(n, v)| format!("{n} = {}", super::plot::tick(*v)))
                .collect();
            return format!("{over}, at {}", at.join(", "));
        }
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
            Data::Cells {
                rects, idx, cats, ..
            } => {
                let c = self.color.as_deref().unwrap_or("verdict");
                let (xl, xh) = (format!("{}_lo", self.x), format!("{}_hi", self.x));
                let mut head = vec![xl.as_str(), xh.as_str()];
                let (yl, yh);
                if let Some(y) = &self.y {
                    (yl, yh) = (format!("{y}_lo"), format!("{y}_hi"));
                    head.extend([yl.as_str(), yh.as_str()]);
                }
                head.push(c);
                let mut t = DataTable::new(None, &head);
                for (r, &k) in rects.iter().zip(idx) {
                    let mut row = vec![format!("{:?}", r[0]), format!("{:?}", r[1])];
                    if self.y.is_some() {
                        row.extend([format!("{:?}", r[2]), format!("{:?}", r[3])]);
                    }
                    row.push(cats[k].clone());
                    t.push(row);
                }
                t
            }
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
            // class names (with `undecided`, the verify cells' open verdict)
            if cats.iter().all(|c| {
                super::figures::knot_map::CLASSES.contains(&c.as_str()) || c == "undecided"
            }) {
                class_color(&cats[i])
            } else if cats.iter().all(|c| VERDICTS.contains(&c.as_str())) {
                verdict_color(&cats[i])
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
            Data::Cells {
                rects,
                idx,
                cats,
                bounds,
                ..
            } => {
                let [x0, x1, y0, y1] = *bounds;
                let (x0, x1) = if x1 > x0 { (x0, x1) } else { pad(x0, x1) };
                let (y0, y1) = if y1 > y0 { (y0, y1) } else { pad(y0, y1) };
                let mut chart = builder
                    .build_cartesian_2d(x0..x1, y0..y1)
                    .map_err(draw_err)?;
                match &self.y {
                    Some(y) => mesh(&mut chart, &self.x, y, 8, &th)?,
                    None => chart
                        .configure_mesh()
                        .x_labels(8)
                        .y_labels(0)
                        .x_desc(self.x.as_str())
                        .label_style(th.font(th.tick))
                        .axis_desc_style(th.font(th.label))
                        .light_line_style(WHITE)
                        .bold_line_style(BLACK.mix(0.08))
                        .x_label_formatter(&|v| super::plot::tick(*v))
                        .draw()
                        .map_err(draw_err)?,
                }
                chart
                    .draw_series(rects.iter().zip(idx).map(|(r, &k)| {
                        Rectangle::new([(r[0], r[2]), (r[1], r[3])], cat_color(cats, k).filled())
                    }))
                    .map_err(draw_err)?;
                legend(cats, false, &[])
            }
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

/// The verdicts of a `verify` property column (and of `verdict` without the
/// class property).
const VERDICTS: &[&str] = &["certified", "refuted", "undecided"];

/// The colour of a verdict: certified green-blue, refuted dark, undecided
/// light grey (as on the certified map).
fn verdict_color(v: &str) -> RGBColor {
    match v {
        "certified" => viridis(0.6),
        "refuted" => RGBColor(60, 60, 60),
        _ => RGBColor(215, 215, 215),
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

/// The estimated cost of plotting `rows` rows of `columns` columns read from
/// a file of `file_bytes` bytes (holding the file, reading the table and
/// drawing every row into SVG or PNG), for the CLI's work limits.
pub fn estimate(rows: usize, columns: usize, file_bytes: u64) -> Estimate {
    Estimate {
        bytes: file_bytes as f64 + rows as f64 * columns.max(1) as f64 * BYTES_PER_CELL,
        seconds: rows as f64 * SECONDS_PER_POINT,
        what: format!("plotting {rows} rows"),
    }
}

/// The size of an SVG of `items` drawn points or cells, bytes (about
/// [`SVG_BYTES_PER_ITEM`] each).
pub fn svg_bytes(items: usize) -> f64 {
    items as f64 * SVG_BYTES_PER_ITEM
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

    /// One valence: the class fractions, unless one or two parameters vary
    /// (then the scatter or the class map of the slice); without a class
    /// column, a histogram.
    #[test]
    fn one_valence_defaults_to_the_class_fractions() {
        let cube = t("id,valence,r0,r1,r2,class,contraction_rate\n0,3,0.1,0.1,0.1,a,1\n1,3,0.2,0.2,0.2,b,2\n2,3,0.1,0.2,0.3,a,3\n");
        let (k, r) = choose(&cube, &PlotRequest::default()).unwrap();
        assert_eq!(
            (k, r.x.as_deref(), r.color.as_deref()),
            (PlotKind::Fractions, Some("valence"), Some("class"))
        );
        let fixed = t("id,valence,r0,class,contraction_rate\n0,3,0.1,a,1\n1,3,0.1,b,2\n");
        assert_eq!(
            choose(&fixed, &PlotRequest::default()).unwrap().0,
            PlotKind::Fractions
        );
        let no_class = t("id,valence,r0,r1,r2,x\n0,3,0.1,0.1,0.1,1\n1,3,0.2,0.2,0.2,2\n");
        assert_eq!(
            choose(&no_class, &PlotRequest::default()).unwrap().0,
            PlotKind::Histogram
        );
    }

    /// A verify cells table is the certified map: one rectangle per cell in
    /// the slice through the middle of the box, coloured by verdict; rows
    /// with a non-finite end are counted as dropped.
    #[test]
    fn verify_cells_are_drawn_as_the_certified_map() {
        let cells = t("lo0,lo1,lo2,hi0,hi1,hi2,verdict,class\n\
            0.1,0.1,0.1,0.5,0.5,0.5,complex_pair,certified\n\
            0.1,0.1,0.5,0.5,0.5,0.9,real_distinct,certified\n\
            0.5,0.1,0.1,0.9,0.9,0.9,undecided,undecided\n\
            0.1,0.5,0.1,0.5,0.9,0.9,NaN,undecided\n\
            0.1,0.5,NaN,0.5,0.9,0.9,undecided,undecided\n");
        let p = SweepPlot::build(&cells, &PlotRequest::default()).unwrap();
        assert_eq!(p.kind(), PlotKind::Map);
        assert_eq!(p.dropped(), 1);
        // r2 = 0.5 lies in [0.5, 0.9) of the second cell, not in the first's [0.1, 0.5).
        let d = p.data();
        assert_eq!(d.rows.len(), 3, "{:?}", d.rows);
        assert!(d.rows.iter().all(|r| r[4] != "complex_pair"));
        assert!(p
            .default_title()
            .starts_with("Certified map: verdict over r0 and r1, at r2 = 0.5"));
        let by_c = t("c_lo,c_hi,verdict\n0.0,0.5,standard\n0.5,1.0,undecided\n");
        let p = SweepPlot::build(&by_c, &PlotRequest::default()).unwrap();
        assert_eq!(
            (p.items(), p.default_title().as_str()),
            (2, "Certified map: verdict over c")
        );
        // Another kind asked for: the table's columns as they are.
        let h = SweepPlot::build(
            &cells,
            &PlotRequest {
                kind: Some(PlotKind::Histogram),
                x: Some("lo0".into()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(h.kind(), PlotKind::Histogram);
    }

    /// Rows without a finite value on an axis are counted.
    #[test]
    fn dropped_rows_are_counted() {
        let tab = t("a,b\n1,2\n2,NaN\n3,inf\n4,\n5,6\n");
        let req = |kind, y: Option<&str>| PlotRequest {
            kind: Some(kind),
            x: Some("a".into()),
            y: y.map(Into::into),
            ..Default::default()
        };
        let p = SweepPlot::build(&tab, &req(PlotKind::Scatter, Some("b"))).unwrap();
        assert_eq!((p.dropped(), p.axes().as_str()), (3, "a or b"));
        let p = SweepPlot::build(&tab, &req(PlotKind::Histogram, None)).unwrap();
        assert_eq!((p.dropped(), p.axes().as_str()), (0, "a"));
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
    /// common class gets none.
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
