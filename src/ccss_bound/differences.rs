//! Families of second-order differences of the patch's control points.
//!
//! A [`Difference`] is a small integer stencil over the `2n + 8` points,
//! together with the *chart* it lives in: integer grid coordinates for each
//! of its points in a regular planar unfolding of quads of the patch's
//! control mesh. [`DifferenceFamily::validate`] checks that every difference
//! annihilates constants and linear functions of its chart coordinates, that
//! chart neighbours are mesh edges, and that three collinear chart points
//! `y, x, z` are "straight" in the mesh (on at least one side, `y` and `z` are
//! separated by exactly one edge `(x, w)` in the cyclic order around `x`, so
//! the two quads at that edge unfold to a chart in which `y, x, z` lie on a
//! line; at a valence-3 vertex this holds for every pair).
//!
//! # The default family ([`default_family`], `2n + 10` differences)
//!
//! The paper's own list (its eq. (1)) is not recoverable from the source
//! (math doc section 9). We use every second difference `y - 2x + z` along a
//! straight line of the control mesh that stays inside the patch:
//!
//! * at each regular vertex `x` of the patch mesh, one per grid line through
//!   `x` whose both neighbours are patch points: `n + 10` differences
//!   (`f_{i-1} - 2 e_i + f_i` for every `i`; `v - 2 e_0 + o_1`,
//!   `v - 2 e_1 + o_5`; two through `f_0`; one each through `f_1`, `f_{n-1}`;
//!   one each through `o_1, o_2, o_4, o_5`);
//! * at the extraordinary vertex, which has no global grid lines, one per
//!   spoke `v e_i`: `e_{i-1} - 2 v + e_{i+1}`, the straight line through `v`
//!   in the chart that unfolds the two quads adjacent to the spoke: `n`
//!   differences.
//!
//! Total `2n + 10`, the paper's count. At `n = 4` the spoke differences are
//! the two grid lines through the extraordinary vertex, each twice (so the
//! family contains them, as math doc section 9 requires), and the family is
//! the 16 row and column second differences of the 4 x 4 net (plus the two
//! repeats), which reproduce `D(t) = (1 - t^2)/4`. The family is invariant
//! under the patch's diagonal reflection and, around `v`, under rotation.

use super::CcssBoundError;
use super::Result;
use crate::error::Error;
use crate::schemes::catmull_clark::PatchLayout;
use std::collections::HashSet;

/// One second-order difference: `sum_k coeff_k P_{point_k}`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Difference {
    /// Human-readable name, e.g. `"f3-2e4+f4"`.
    pub name: String,
    /// `(point index, integer coefficient, chart coordinates)`.
    pub terms: Vec<(usize, i64, (i64, i64))>,
}

impl Difference {
    /// The difference as a dense coefficient vector over `len` points.
    pub fn to_vector(&self, len: usize) -> Vec<f64> {
        let mut v = vec![0.0; len];
        for &(p, a, _) in &self.terms {
            v[p] += a as f64;
        }
        v
    }
    /// Applies the difference to a control net (one point per row): `sum a_k P_k`.
    pub fn apply(&self, net: &[Vec<f64>]) -> Vec<f64> {
        let dim = net.first().map_or(0, Vec::len);
        let mut out = vec![0.0; dim];
        for &(p, a, _) in &self.terms {
            for (o, x) in out.iter_mut().zip(&net[p]) {
                *o += a as f64 * x;
            }
        }
        out
    }
}

/// A family of second-order differences for the patch of valence `n`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct DifferenceFamily {
    valence: usize,
    differences: Vec<Difference>,
}

/// The control mesh of the patch: its quads (each a cyclic 4-tuple of point indices).
pub fn patch_quads(lay: &PatchLayout) -> Vec<[usize; 4]> {
    let n = lay.valence();
    let mut quads: Vec<[usize; 4]> = (0..n)
        .map(|i| [lay.v(), lay.e(i), lay.f(i), lay.e(i + 1)])
        .collect();
    // The 5 grid cells not touching v: (i, j) lower-left corner.
    for (i, j) in [(2, 0), (2, 1), (2, 2), (1, 2), (0, 2)] {
        let g = |a, b| lay.grid(a, b);
        if let (Some(a), Some(b), Some(c), Some(d)) =
            (g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1))
        {
            quads.push([a, b, c, d]);
        }
    }
    quads
}

impl DifferenceFamily {
    /// A family from explicit differences; validated.
    pub fn new(valence: usize, differences: Vec<Difference>) -> Result<Self> {
        let f = Self {
            valence,
            differences,
        };
        f.validate()?;
        Ok(f)
    }
    /// The valence.
    pub fn valence(&self) -> usize {
        self.valence
    }
    /// The differences.
    pub fn differences(&self) -> &[Difference] {
        &self.differences
    }
    /// Number of differences.
    pub fn len(&self) -> usize {
        self.differences.len()
    }
    /// Whether the family is empty.
    pub fn is_empty(&self) -> bool {
        self.differences.is_empty()
    }
    /// The differences as columns of a `(2n+8) x L` matrix.
    pub fn matrix(&self) -> nalgebra::DMatrix<f64> {
        let len = 2 * self.valence + 8;
        let cols: Vec<_> = self
            .differences
            .iter()
            .map(|d| nalgebra::DVector::from_vec(d.to_vector(len)))
            .collect();
        nalgebra::DMatrix::from_columns(&cols)
    }
    /// `M = max_l |alpha_l|` (Euclidean norm) for a control net (`2n + 8` rows).
    pub fn max_norm(&self, net: &[Vec<f64>]) -> Result<f64> {
        let len = 2 * self.valence + 8;
        if net.len() != len {
            return Err(Error::CountMismatch {
                what: "control net points (2n+8)",
                expected: len,
                got: net.len(),
            }
            .into());
        }
        Ok(self
            .differences
            .iter()
            .map(|d| d.apply(net).iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0, f64::max))
    }

    /// Checks every difference: integer coefficients summing to 0, annihilating
    /// linear functions of its chart coordinates, distinct chart positions,
    /// chart neighbours joined by mesh edges, collinear chart triples straight
    /// in the mesh.
    pub fn validate(&self) -> Result<()> {
        let lay = PatchLayout::new(self.valence)?;
        let quads = patch_quads(&lay);
        let edges: HashSet<(usize, usize)> = quads
            .iter()
            .flat_map(|q| (0..4).map(move |k| (q[k], q[(k + 1) % 4])))
            .flat_map(|(a, b)| [(a, b), (b, a)])
            .collect();
        // y and z straight through x: some w with quads (.., y, x, w, ..) and (.., w, x, z, ..)
        // i.e. {y, w} and {w, z} are the two x-neighbours of two different quads.
        let nbrs_in_quad = |q: &[usize; 4], x: usize| -> Option<(usize, usize)> {
            let k = q.iter().position(|&p| p == x)?;
            Some((q[(k + 3) % 4], q[(k + 1) % 4]))
        };
        let straight = |y: usize, x: usize, z: usize| {
            let pairs: Vec<(usize, usize)> =
                quads.iter().filter_map(|q| nbrs_in_quad(q, x)).collect();
            let has = |a: usize, b: usize| {
                pairs
                    .iter()
                    .any(|&(p, q)| (p == a && q == b) || (p == b && q == a))
            };
            pairs.iter().any(|&(p, q)| {
                let w = if p == y {
                    q
                } else if q == y {
                    p
                } else {
                    return false;
                };
                has(w, z)
            })
        };
        let len = lay.patch_len();
        for (index, d) in self.differences.iter().enumerate() {
            let bad = |reason: String| {
                Err(CcssBoundError::InvalidDifference {
                    index,
                    name: d.name.clone(),
                    reason,
                })
            };
            if d.terms.iter().all(|t| t.1 == 0) {
                return bad("all coefficients are zero".into());
            }
            if let Some(t) = d.terms.iter().find(|t| t.0 >= len) {
                return bad(format!("point index {} is not a patch point", t.0));
            }
            let s: i64 = d.terms.iter().map(|t| t.1).sum();
            let sx: i64 = d.terms.iter().map(|t| t.1 * t.2 .0).sum();
            let sy: i64 = d.terms.iter().map(|t| t.1 * t.2 .1).sum();
            if s != 0 {
                return bad(format!("coefficients sum to {s}, not 0 (constants)"));
            }
            if sx != 0 || sy != 0 {
                return bad(format!(
                    "does not annihilate linear functions of its chart ({sx}, {sy})"
                ));
            }
            for (a, ta) in d.terms.iter().enumerate() {
                for tb in &d.terms[a + 1..] {
                    if ta.2 == tb.2 || ta.0 == tb.0 {
                        return bad("two terms share a point or a chart position".into());
                    }
                    let dist = (ta.2 .0 - tb.2 .0).abs() + (ta.2 .1 - tb.2 .1).abs();
                    if dist == 1 && !edges.contains(&(ta.0, tb.0)) {
                        return bad(format!(
                            "chart neighbours {} and {} are not joined by a mesh edge",
                            ta.0, tb.0
                        ));
                    }
                }
            }
            for x in &d.terms {
                for y in &d.terms {
                    for z in &d.terms {
                        let dy = (y.2 .0 - x.2 .0, y.2 .1 - x.2 .1);
                        let dz = (z.2 .0 - x.2 .0, z.2 .1 - x.2 .1);
                        let unit = dy.0.abs() + dy.1.abs() == 1;
                        if unit && dz == (-dy.0, -dy.1) && y.0 < z.0 && !straight(y.0, x.0, z.0) {
                            return bad(format!(
                                "points {}, {}, {} are collinear in the chart but not straight in the mesh",
                                y.0, x.0, z.0
                            ));
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// `y - 2x + z` along a straight line, chart `y = (-1, 0), x = (0, 0), z = (1, 0)`.
fn line(name: String, y: usize, x: usize, z: usize) -> Difference {
    Difference {
        name,
        terms: vec![(y, 1, (-1, 0)), (x, -2, (0, 0)), (z, 1, (1, 0))],
    }
}

/// The documented default family of `2n + 10` differences (module docs).
///
/// ```
/// use subdiv_lab::ccss_bound::default_family;
/// for n in 3..10 {
///     assert_eq!(default_family(n).unwrap().len(), 2 * n + 10);
/// }
/// ```
pub fn default_family(n: usize) -> Result<DifferenceFamily> {
    let lay = PatchLayout::new(n)?;
    let labels = lay.labels();
    let nm = |p: usize| labels[p].to_string();
    let mut ds = Vec::with_capacity(2 * n + 10);
    let mut add = |y: usize, x: usize, z: usize| {
        ds.push(line(format!("{}-2{}+{}", nm(y), nm(x), nm(z)), y, x, z));
    };
    // Extraordinary vertex: one per spoke.
    for i in 0..n {
        add(lay.e(i + n - 1), lay.v(), lay.e(i + 1));
    }
    // Transverse lines at the edge neighbours.
    for i in 0..n {
        add(lay.f(i + n - 1), lay.e(i), lay.f(i));
    }
    // Remaining grid lines of the 4 x 4 picture with a regular centre.
    let g = |i: usize, j: usize| lay.grid(i, j);
    let grid_lines = [
        // (y, x, z) as grid positions
        ((1, 1), (2, 1), (3, 1)), // v - 2e0 + o1
        ((1, 1), (1, 2), (1, 3)), // v - 2e1 + o5
        ((1, 2), (2, 2), (3, 2)), // through f0 along u
        ((2, 1), (2, 2), (2, 3)), // through f0 along v
        ((0, 1), (0, 2), (0, 3)), // through f1
        ((1, 0), (2, 0), (3, 0)), // through f_{n-1}
        ((3, 0), (3, 1), (3, 2)), // through o1
        ((3, 1), (3, 2), (3, 3)), // through o2
        ((1, 3), (2, 3), (3, 3)), // through o4
        ((0, 3), (1, 3), (2, 3)), // through o5
    ];
    for (y, x, z) in grid_lines {
        match (g(y.0, y.1), g(x.0, x.1), g(z.0, z.1)) {
            (Some(a), Some(b), Some(c)) => add(a, b, c),
            _ => {
                return Err(Error::Numerical {
                    routine: "default difference family",
                    reason: format!("grid line {y:?}-{x:?}-{z:?} leaves the patch"),
                }
                .into())
            }
        }
    }
    DifferenceFamily::new(n, ds)
}
