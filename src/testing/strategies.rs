//! proptest strategies for local configurations.
//!
//! Every strategy shrinks towards the simplest configuration in its box:
//! valences towards the lower bound, knot intervals towards all-equal
//! (uniform) intervals, ratios towards 1/2 when 1/2 lies in the box (else all
//! equal to the bound nearest 1/2), control points towards the origin. A failing
//! property therefore shrinks to a small valence with (nearly) uniform knots.
//!
//! Valence and per-corner values are drawn independently (values for the
//! largest valence, truncated to the drawn one), so shrinking the valence keeps
//! the other values and a failure usually survives it: counterexamples shrink to
//! the smallest valence that still fails, not just to simpler knots.

use crate::knots::{CornerIntervals, EdgeRatios};
use crate::schemes::LocalScheme;
use nalgebra::Point3;
use proptest::prelude::*;
use std::ops::RangeInclusive;

/// Valences in `range` (clamped below at 3); shrinks towards the lower bound.
pub fn valences(range: RangeInclusive<usize>) -> impl Strategy<Value = usize> + Clone {
    let lo = (*range.start()).max(3);
    let hi = (*range.end()).max(lo);
    lo..=hi
}

/// Options for [`corner_intervals`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntervalBox {
    min: f64,
    max: f64,
    extreme_probability: f64,
}

impl IntervalBox {
    /// Log-uniform intervals in `[min, max]` with no extra weight on the extremes.
    ///
    /// ```
    /// use subdiv_lab::testing::strategies::IntervalBox;
    /// assert!(IntervalBox::new(0.1, 10.0).is_ok());
    /// assert!(IntervalBox::new(0.0, 10.0).is_err());
    /// ```
    pub fn new(min: f64, max: f64) -> Result<Self, crate::Error> {
        if !(min.is_finite() && min > 0.0) {
            return Err(crate::Error::InvalidParameter {
                name: "min",
                value: min.to_string(),
                reason: "must be finite and > 0",
            });
        }
        if !(max.is_finite() && max >= min) {
            return Err(crate::Error::InvalidParameter {
                name: "max",
                value: max.to_string(),
                reason: "must be finite and >= min",
            });
        }
        Ok(Self {
            min,
            max,
            extreme_probability: 0.0,
        })
    }

    /// Smallest interval.
    pub fn min(&self) -> f64 {
        self.min
    }

    /// Largest interval.
    pub fn max(&self) -> f64 {
        self.max
    }

    /// The same box where each interval is drawn at an extreme (`min` or `max`)
    /// with the given probability (clamped to [0, 1]) instead of log-uniformly:
    /// extreme ratios are what break naive formulas.
    pub fn with_extremes(mut self, probability: f64) -> Self {
        self.extreme_probability = if probability.is_nan() {
            0.0
        } else {
            probability.clamp(0.0, 1.0)
        };
        self
    }
}

/// One interval: log-uniform in the box, stored as an exponent offset from the
/// bound nearest 1 so that shrinking drives every interval to the same value.
/// Grid resolution of the drawn values: log-intervals and ratio offsets are
/// multiples of `GRID_RESOLUTION = 2^-24`, far finer than any property depends
/// on. Shrinking drives each value to the anchor (uniform knots, ratio 1/2);
/// proptest's shrinker can stop one grid step short of it, so a shrunk
/// counterexample is uniform to within a few multiples of this resolution.
pub const GRID_RESOLUTION: f64 = 1.0 / 16_777_216.0;

const OFFSET_STEPS_PER_UNIT: f64 = 1.0 / GRID_RESOLUTION;

/// A value in `[lo, hi]` (`lo <= 0 <= hi`) on a fine grid, uniformly
/// distributed, that shrinks to exactly 0: an unsigned index `k` is mapped
/// bijectively onto the grid steps `-a..=b` by alternating around 0
/// (0, +1, -1, +2, -2, ...) and then continuing on the longer side. proptest
/// shrinks an unsigned index to exactly 0 in a few dozen steps, whereas a
/// float (or signed) binary search stops short of 0.
fn offset(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    let a = (-lo * OFFSET_STEPS_PER_UNIT).floor().max(0.0) as u64; // steps below 0
    let b = (hi * OFFSET_STEPS_PER_UNIT).floor().max(0.0) as u64; // steps above 0
    (0..=a + b).prop_map(move |k| {
        let m = a.min(b);
        let step: i64 = if k <= 2 * m {
            if k % 2 == 0 {
                (k / 2) as i64
            } else {
                -(k.div_ceil(2) as i64)
            }
        } else if b > a {
            (k - m) as i64
        } else {
            -((k - m) as i64)
        };
        (step as f64 / OFFSET_STEPS_PER_UNIT).clamp(lo, hi)
    })
}

fn interval(b: IntervalBox) -> impl Strategy<Value = f64> + Clone {
    let (lo, hi) = (b.min.ln(), b.max.ln());
    // anchor: the point of [lo, hi] nearest ln 1 = 0; offsets shrink towards 0.
    let anchor = 0f64.clamp(lo, hi);
    let normal = offset(lo - anchor, hi - anchor).prop_map(move |t| (anchor + t).exp());
    let p_ext = b.extreme_probability;
    let weight_ext = (p_ext * 1000.0).round() as u32;
    let weight_norm = 1000 - weight_ext;
    prop_oneof![
        weight_norm.max(1) => normal,
        weight_ext => prop::bool::ANY.prop_map(move |hi_side| if hi_side { b.max } else { b.min }),
    ]
}

/// Corner intervals `(p_i, q_i)` of an n-gon with `n` drawn from `valence`.
///
/// ```
/// use proptest::strategy::{Strategy, ValueTree};
/// use proptest::test_runner::TestRunner;
/// use subdiv_lab::testing::strategies::{corner_intervals, IntervalBox};
/// let s = corner_intervals(3..=6, IntervalBox::new(0.5, 2.0).unwrap());
/// let k = s.new_tree(&mut TestRunner::deterministic()).unwrap().current();
/// assert!((3..=6).contains(&k.valence()));
/// assert!(k.p().iter().all(|&x| (0.5..=2.0).contains(&x)));
/// ```
pub fn corner_intervals(
    valence: RangeInclusive<usize>,
    b: IntervalBox,
) -> impl Strategy<Value = CornerIntervals> {
    let hi = max_valence(&valence);
    (
        valences(valence),
        prop::collection::vec(interval(b), hi),
        prop::collection::vec(interval(b), hi),
    )
        .prop_map(|(n, p, q)| {
            CornerIntervals::new(p[..n].to_vec(), q[..n].to_vec())
                .expect("strategy draws valid intervals")
        })
}

fn max_valence(range: &RangeInclusive<usize>) -> usize {
    (*range.end()).max(*range.start()).max(3)
}

/// Edge ratios in `[min, max]^n` (`0 < min <= max < 1`); shrinks towards 1/2
/// (or the bound nearest 1/2).
pub fn edge_ratios(
    valence: RangeInclusive<usize>,
    min: f64,
    max: f64,
) -> impl Strategy<Value = EdgeRatios> {
    let lo = min.clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON);
    let hi = max.clamp(lo, 1.0 - f64::EPSILON);
    let anchor = 0.5f64.clamp(lo, hi);
    let top = max_valence(&valence);
    (
        valences(valence),
        prop::collection::vec(offset(lo - anchor, hi - anchor), top),
    )
        .prop_map(move |(n, t)| {
            EdgeRatios::new(t[..n].iter().map(|x| (anchor + x).clamp(lo, hi)).collect())
                .expect("strategy draws ratios inside (0, 1)")
        })
}

/// Face-EP preset ratios: an initial n-gon with directed-edge intervals in the box.
pub fn face_ep_ratios(
    valence: RangeInclusive<usize>,
    b: IntervalBox,
) -> impl Strategy<Value = EdgeRatios> {
    let hi = max_valence(&valence);
    (
        valences(valence),
        prop::collection::vec(interval(b), hi),
        prop::collection::vec(interval(b), hi),
    )
        .prop_map(|(n, f, bw)| EdgeRatios::face_ep(&f[..n], &bw[..n]).expect("valid intervals"))
}

/// Vertex-EP preset ratios: a valence-n vertex with intervals `a_k` in the box.
pub fn vertex_ep_ratios(
    valence: RangeInclusive<usize>,
    b: IntervalBox,
) -> impl Strategy<Value = EdgeRatios> {
    let hi = max_valence(&valence);
    (valences(valence), prop::collection::vec(interval(b), hi))
        .prop_map(|(n, a)| EdgeRatios::vertex_ep(&a[..n]).expect("valid intervals"))
}

/// NURDS configurations from [`corner_intervals`].
pub fn nurds_schemes(
    valence: RangeInclusive<usize>,
    b: IntervalBox,
) -> impl Strategy<Value = LocalScheme> {
    corner_intervals(valence, b)
        .prop_map(|k| LocalScheme::nurds(k.ratios().expect("finite ratios")))
}

/// `count` control points with coordinates in `[-extent, extent]`; shrinks towards the origin.
pub fn control_points(count: usize, extent: f64) -> impl Strategy<Value = Vec<Point3<f64>>> {
    let e = if extent.is_finite() && extent > 0.0 {
        extent
    } else {
        1.0
    };
    prop::collection::vec(
        (-e..=e, -e..=e, -e..=e).prop_map(|(x, y, z)| Point3::new(x, y, z)),
        count,
    )
}

/// A local configuration together with random positions for its `4n` points.
///
/// Points are ordered as the matrix columns: `P_0..P_{n-1}`, `E_01, E_02, ..`, `C_0..C_{n-1}`.
pub fn nurds_with_points(
    valence: RangeInclusive<usize>,
    b: IntervalBox,
) -> impl Strategy<Value = (LocalScheme, Vec<Point3<f64>>)> {
    let hi = max_valence(&valence);
    (nurds_schemes(valence, b), control_points(4 * hi, 1.0)).prop_map(move |(s, pts)| {
        let n = s.valence();
        // blocks of the largest configuration: P [0, hi), E [hi, 3 hi), C [3 hi, 4 hi)
        let mut v = Vec::with_capacity(4 * n);
        v.extend_from_slice(&pts[..n]);
        v.extend_from_slice(&pts[hi..hi + 2 * n]);
        v.extend_from_slice(&pts[3 * hi..3 * hi + n]);
        (s, v)
    })
}

/// Small closed polygon meshes from [`crate::mesh::generators`] (tetrahedron,
/// cube, icosahedron, a 4 x 3 torus, truncated icosahedron: triangles, quads,
/// pentagons and hexagons; valences 3 to 6) with one random knot interval per
/// directed edge drawn from the box. Shrinks towards the tetrahedron and
/// uniform intervals.
///
/// ```
/// use proptest::strategy::{Strategy, ValueTree};
/// use proptest::test_runner::TestRunner;
/// use subdiv_lab::testing::strategies::{meshes_with_knots, IntervalBox};
/// let s = meshes_with_knots(IntervalBox::new(0.5, 2.0).unwrap());
/// let mesh = s.new_tree(&mut TestRunner::deterministic()).unwrap().current();
/// assert!(mesh.knots().iter().all(|&d| (0.5..=2.0).contains(&d)));
/// ```
pub fn meshes_with_knots(b: IntervalBox) -> impl Strategy<Value = crate::mesh::Mesh> {
    use crate::mesh::generators;
    let build = |k: usize| match k {
        0 => generators::tetrahedron(),
        1 => generators::cube(),
        2 => generators::icosahedron(),
        3 => generators::torus(4, 3, 2.0, 0.7),
        _ => generators::truncated_icosahedron(),
    };
    let most = (0..5)
        .map(|k| build(k).half_edge_count())
        .max()
        .unwrap_or(0);
    // The mesh index shrinks towards 0 (the tetrahedron); one interval per
    // half-edge of the largest mesh, truncated to the drawn mesh.
    (0usize..5, prop::collection::vec(interval(b), most)).prop_map(move |(k, knots)| {
        let mut mesh = build(k);
        let h = mesh.half_edge_count();
        mesh.set_knots(knots[..h].to_vec())
            .expect("strategy draws positive finite intervals, one per half-edge");
        mesh
    })
}
