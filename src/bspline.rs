//! Non-uniform quadratic B-splines with knot intervals: univariate basis and
//! refinement, tensor-product biquadratic patches, and their Bezier form.
//!
//! Math doc section 2. A control point `P_i` carries the knot interval `d_i`:
//! in knot-vector terms `d_i = t_{i+2} - t_{i+1}` is the middle span of the
//! support of its basis function `N_i`. The span "of" `P_1` (knot interval
//! `d_1`) is controlled by `P_0, P_1, P_2` and runs from the edge point
//!
//! ```text
//! E_0 = (d_1 P_0 + d_0 P_1) / (d_0 + d_1)    to    E_1 = (d_2 P_1 + d_1 P_2) / (d_1 + d_2).
//! ```
//!
//! On that span, with local parameter `t in [0, 1]` (`u = t d_1`):
//!
//! ```text
//! N_0(t) = (1 - t)^2 d_1 / (d_0 + d_1),   N_2(t) = t^2 d_1 / (d_1 + d_2),   N_1 = 1 - N_0 - N_2,
//! ```
//!
//! and its quadratic Bezier points are `[E_0, P_1, E_1]` (the blossom values
//! `f(t_2,t_2), f(t_2,t_3), f(t_3,t_3)`).
//!
//! One refinement step of a curve (math doc section 2):
//!
//! ```text
//! E_i      = (d_{i+1} P_i + d_i P_{i+1}) / (d_i + d_{i+1})
//! Q_{2i}   = (P_i + E_i) / 2,   Q_{2i+1} = (P_{i+1} + E_i) / 2,
//! ```
//!
//! where `Q_{2i-1}` and `Q_{2i}` inherit the interval `d_i / 2`.
//!
//! This module is shared by the mesh code ([`crate::mesh`]) and the
//! characteristic-map analysis; points are `[f64; D]` for any dimension `D`.
//!
//! ```
//! use subdiv_lab::bspline::{BiquadraticPatch, QuadraticSpan};
//! let u = QuadraticSpan::new(1.0, 2.0, 0.5).unwrap();
//! let b = u.basis(0.3);
//! assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
//! // a patch whose control net is an affine grid reproduces the affine map
//! let v = QuadraticSpan::uniform();
//! let mut net = [[[0.0; 2]; 3]; 3];
//! for a in 0..3 {
//!     for c in 0..3 {
//!         net[a][c] = [a as f64, c as f64];
//!     }
//! }
//! let patch = BiquadraticPatch::new(u, v, net);
//! let p = patch.eval(0.0, 0.5);
//! assert!((p[1] - 1.0).abs() < 1e-15);
//! ```

// Index loops mirror the subscripts of the formulas in the math doc.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};

fn check_interval(name: &'static str, index: usize, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidInterval {
            name,
            index,
            value: format!("{v:?}"),
        })
    }
}

/// The three knot intervals that define one quadratic span: `prev` (`d_0`),
/// `mid` (`d_1`, the span itself) and `next` (`d_2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadraticSpan {
    /// `d_0`: the interval of the first control point.
    pub prev: f64,
    /// `d_1`: the interval of the middle control point (the span's length).
    pub mid: f64,
    /// `d_2`: the interval of the last control point.
    pub next: f64,
}

impl QuadraticSpan {
    /// Validates three finite, positive intervals.
    pub fn new(prev: f64, mid: f64, next: f64) -> Result<Self> {
        check_interval("d", 0, prev)?;
        check_interval("d", 1, mid)?;
        check_interval("d", 2, next)?;
        Ok(Self { prev, mid, next })
    }

    /// All three intervals equal (the uniform quadratic B-spline).
    pub fn uniform() -> Self {
        Self {
            prev: 1.0,
            mid: 1.0,
            next: 1.0,
        }
    }

    /// Basis values `[N_0, N_1, N_2]` at local parameter `t in [0, 1]`.
    pub fn basis(&self, t: f64) -> [f64; 3] {
        let n0 = (1.0 - t) * (1.0 - t) * self.mid / (self.prev + self.mid);
        let n2 = t * t * self.mid / (self.mid + self.next);
        [n0, 1.0 - n0 - n2, n2]
    }

    /// Derivatives `d N_k / d t` (with respect to the local parameter `t`).
    pub fn basis_derivative(&self, t: f64) -> [f64; 3] {
        let d0 = -2.0 * (1.0 - t) * self.mid / (self.prev + self.mid);
        let d2 = 2.0 * t * self.mid / (self.mid + self.next);
        [d0, -d0 - d2, d2]
    }

    /// The 3x3 matrix `B` with `bezier = B * control`: row `k` gives Bezier
    /// point `b_k` as a combination of the control points `P_0, P_1, P_2`.
    pub fn bezier_matrix(&self) -> [[f64; 3]; 3] {
        let a = self.prev + self.mid;
        let b = self.mid + self.next;
        [
            [self.mid / a, self.prev / a, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, self.next / b, self.mid / b],
        ]
    }

    /// Evaluates the span's curve at `t`.
    pub fn eval<const D: usize>(&self, control: &[[f64; D]; 3], t: f64) -> [f64; D] {
        combine(&self.basis(t), control)
    }
}

/// `sum_k w_k P_k`.
fn combine<const D: usize>(w: &[f64; 3], p: &[[f64; D]; 3]) -> [f64; D] {
    let mut out = [0.0; D];
    for (wk, pk) in w.iter().zip(p) {
        for (o, x) in out.iter_mut().zip(pk) {
            *o += wk * x;
        }
    }
    out
}

/// Quadratic Bezier evaluation by de Casteljau (an independent route used to
/// check [`QuadraticSpan::bezier_matrix`]).
pub fn eval_bezier<const D: usize>(b: &[[f64; D]; 3], t: f64) -> [f64; D] {
    let lerp = |x: &[f64; D], y: &[f64; D]| {
        let mut o = [0.0; D];
        for k in 0..D {
            o[k] = (1.0 - t) * x[k] + t * y[k];
        }
        o
    };
    lerp(&lerp(&b[0], &b[1]), &lerp(&b[1], &b[2]))
}

/// One refinement step of a quadratic B-spline control polygon with knot
/// intervals (math doc section 2).
///
/// `closed`: the polygon is periodic (`m` edges, `2m` new points); otherwise
/// it has `m - 1` edges and `2(m - 1)` new points. Returns the new points and
/// their intervals (`Q_{2i}` carries `d_i / 2`, `Q_{2i+1}` carries `d_{i+1} / 2`).
///
/// ```
/// use subdiv_lab::bspline::refine_curve;
/// let (q, d) = refine_curve(&[[0.0], [1.0], [3.0]], &[1.0, 1.0, 2.0], false).unwrap();
/// // edge 0: E_0 = 1/2, Q_0 = 1/4, Q_1 = 3/4
/// assert_eq!(q[0], [0.25]);
/// assert_eq!(q[1], [0.75]);
/// assert_eq!(d, vec![0.5, 0.5, 0.5, 1.0]);
/// ```
pub fn refine_curve<const D: usize>(
    points: &[[f64; D]],
    intervals: &[f64],
    closed: bool,
) -> Result<(Vec<[f64; D]>, Vec<f64>)> {
    let m = points.len();
    if intervals.len() != m {
        return Err(Error::CountMismatch {
            what: "knot intervals (one per control point)",
            expected: m,
            got: intervals.len(),
        });
    }
    for (i, &d) in intervals.iter().enumerate() {
        check_interval("d", i, d)?;
    }
    let edges = if closed { m } else { m.saturating_sub(1) };
    let mut q = Vec::with_capacity(2 * edges);
    let mut dq = Vec::with_capacity(2 * edges);
    for i in 0..edges {
        let j = (i + 1) % m;
        let (di, dj) = (intervals[i], intervals[j]);
        let mut e = [0.0; D];
        for k in 0..D {
            e[k] = (dj * points[i][k] + di * points[j][k]) / (di + dj);
        }
        let mut a = [0.0; D];
        let mut b = [0.0; D];
        for k in 0..D {
            a[k] = 0.5 * (points[i][k] + e[k]);
            b[k] = 0.5 * (points[j][k] + e[k]);
        }
        q.push(a);
        q.push(b);
        dq.push(0.5 * di);
        dq.push(0.5 * dj);
    }
    Ok((q, dq))
}

/// A refined grid with its intervals along `u` and `v`.
pub type RefinedGrid<const D: usize> = (Vec<Vec<[f64; D]>>, Vec<f64>, Vec<f64>);

/// One refinement step of a tensor-product grid of biquadratic control points
/// `grid[i][j]` (`i` along `u` with intervals `d`, `j` along `v` with
/// intervals `e`): [`refine_curve`] applied to every row, then every column.
///
/// Returns the refined grid and its intervals `(d', e')`.
pub fn refine_grid<const D: usize>(
    grid: &[Vec<[f64; D]>],
    d: &[f64],
    e: &[f64],
    closed_u: bool,
    closed_v: bool,
) -> Result<RefinedGrid<D>> {
    if grid.len() != d.len() {
        return Err(Error::CountMismatch {
            what: "u intervals (one per grid row)",
            expected: grid.len(),
            got: d.len(),
        });
    }
    // refine along v inside each row i
    let mut rows = Vec::with_capacity(grid.len());
    let mut e_new = Vec::new();
    for row in grid {
        let (r, en) = refine_curve(row, e, closed_v)?;
        rows.push(r);
        e_new = en;
    }
    // refine along u in each column
    let cols = rows.first().map_or(0, Vec::len);
    let mut d_new = Vec::new();
    let mut out: Vec<Vec<[f64; D]>> = Vec::new();
    for j in 0..cols {
        let column: Vec<[f64; D]> = rows.iter().map(|r| r[j]).collect();
        let (c, dn) = refine_curve(&column, d, closed_u)?;
        if out.is_empty() {
            out = vec![Vec::with_capacity(cols); c.len()];
        }
        for (i, p) in c.into_iter().enumerate() {
            out[i].push(p);
        }
        d_new = dn;
    }
    Ok((out, d_new, e_new))
}

/// A non-uniform biquadratic tensor-product patch: control net
/// `control[a][b] = P_ab` (`a` along `u`, `b` along `v`) with knot spans `u`
/// and `v`. Parameters `(s, t)` range over `[0, 1]^2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BiquadraticPatch<const D: usize> {
    /// Knot intervals along `u`.
    pub u: QuadraticSpan,
    /// Knot intervals along `v`.
    pub v: QuadraticSpan,
    /// The 3x3 control net.
    pub control: [[[f64; D]; 3]; 3],
}

impl<const D: usize> BiquadraticPatch<D> {
    /// A patch.
    pub fn new(u: QuadraticSpan, v: QuadraticSpan, control: [[[f64; D]; 3]; 3]) -> Self {
        Self { u, v, control }
    }

    fn tensor(&self, bu: [f64; 3], bv: [f64; 3]) -> [f64; D] {
        let mut out = [0.0; D];
        for a in 0..3 {
            for b in 0..3 {
                let w = bu[a] * bv[b];
                for k in 0..D {
                    out[k] += w * self.control[a][b][k];
                }
            }
        }
        out
    }

    /// The point at `(s, t)`.
    pub fn eval(&self, s: f64, t: f64) -> [f64; D] {
        self.tensor(self.u.basis(s), self.v.basis(t))
    }

    /// Partial derivative with respect to `s` (local parameter, not knot units).
    pub fn deriv_s(&self, s: f64, t: f64) -> [f64; D] {
        self.tensor(self.u.basis_derivative(s), self.v.basis(t))
    }

    /// Partial derivative with respect to `t`.
    pub fn deriv_t(&self, s: f64, t: f64) -> [f64; D] {
        self.tensor(self.u.basis(s), self.v.basis_derivative(t))
    }

    /// The 3x3 Bezier net `b[a][b]` of the patch (bidegree (2, 2)):
    /// `Bu * control * Bv^T` with the spans' [`QuadraticSpan::bezier_matrix`].
    pub fn to_bezier(&self) -> [[[f64; D]; 3]; 3] {
        let bu = self.u.bezier_matrix();
        let bv = self.v.bezier_matrix();
        let mut out = [[[0.0; D]; 3]; 3];
        for (i, out_i) in out.iter_mut().enumerate() {
            for (j, out_ij) in out_i.iter_mut().enumerate() {
                for a in 0..3 {
                    for b in 0..3 {
                        let w = bu[i][a] * bv[j][b];
                        if w != 0.0 {
                            for k in 0..D {
                                out_ij[k] += w * self.control[a][b][k];
                            }
                        }
                    }
                }
            }
        }
        out
    }
}

/// Evaluates a biquadratic Bezier net at `(s, t)` by de Casteljau.
pub fn eval_bezier_patch<const D: usize>(b: &[[[f64; D]; 3]; 3], s: f64, t: f64) -> [f64; D] {
    let rows: [[f64; D]; 3] = [
        eval_bezier(&b[0], t),
        eval_bezier(&b[1], t),
        eval_bezier(&b[2], t),
    ];
    eval_bezier(&rows, s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close<const D: usize>(a: [f64; D], b: [f64; D], tol: f64) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn basis_matches_knot_vector_cox_de_boor() {
        // Independent route: Cox-de Boor recursion on the explicit knot vector.
        let (d0, d1, d2) = (0.7, 1.9, 0.4);
        let span = QuadraticSpan::new(d0, d1, d2).unwrap();
        let t = [-(d0 + 1.3), -d0, 0.0, d1, d1 + d2, d1 + d2 + 0.8];
        fn n(i: usize, p: usize, knots: &[f64], u: f64) -> f64 {
            if p == 0 {
                return if knots[i] <= u && u < knots[i + 1] {
                    1.0
                } else {
                    0.0
                };
            }
            let mut v = 0.0;
            let a = knots[i + p] - knots[i];
            if a > 0.0 {
                v += (u - knots[i]) / a * n(i, p - 1, knots, u);
            }
            let b = knots[i + p + 1] - knots[i + 1];
            if b > 0.0 {
                v += (knots[i + p + 1] - u) / b * n(i + 1, p - 1, knots, u);
            }
            v
        }
        for k in 0..10 {
            let s = k as f64 / 10.0;
            let b = span.basis(s);
            for (i, bi) in b.iter().enumerate() {
                let r = n(i, 2, &t, s * d1);
                assert!((bi - r).abs() < 1e-14, "{i} {s}: {bi} vs {r}");
            }
        }
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let span = QuadraticSpan::new(2.0, 0.3, 1.1).unwrap();
        let h = 1e-6;
        for s in [0.1, 0.5, 0.8] {
            let d = span.basis_derivative(s);
            let (a, b) = (span.basis(s + h), span.basis(s - h));
            for k in 0..3 {
                assert!((d[k] - (a[k] - b[k]) / (2.0 * h)).abs() < 1e-8);
            }
        }
    }

    #[test]
    fn bezier_form_agrees_with_basis() {
        let u = QuadraticSpan::new(0.3, 1.7, 2.9).unwrap();
        let v = QuadraticSpan::new(1.2, 0.5, 0.8).unwrap();
        let mut net = [[[0.0; 3]; 3]; 3];
        for (a, row) in net.iter_mut().enumerate() {
            for (b, p) in row.iter_mut().enumerate() {
                *p = [
                    (a * a) as f64 + 0.3 * b as f64,
                    (b as f64).sin() + a as f64,
                    (a * b) as f64,
                ];
            }
        }
        let patch = BiquadraticPatch::new(u, v, net);
        let bez = patch.to_bezier();
        for i in 0..=4 {
            for j in 0..=4 {
                let (s, t) = (i as f64 / 4.0, j as f64 / 4.0);
                assert!(close(
                    patch.eval(s, t),
                    eval_bezier_patch(&bez, s, t),
                    1e-14
                ));
            }
        }
        // corners of the Bezier net are the edge points of the edge points
        assert!(close(bez[1][1], net[1][1], 0.0));
    }

    #[test]
    fn refinement_preserves_the_curve() {
        // Refining must not change the curve: evaluate the span of P_2 before and
        // the two spans of Q_3, Q_4 (children of span 2) after.
        let p = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.0], [6.0, 1.0]];
        let d = [0.5, 1.5, 2.0, 0.25, 1.0];
        let (q, dq) = refine_curve(&p, &d, false).unwrap();
        let before = QuadraticSpan::new(d[1], d[2], d[3]).unwrap();
        // spans after: Q_2 (d_1/2)? children of span 2 are centered at Q_3 and Q_4.
        let left = QuadraticSpan::new(dq[2], dq[3], dq[4]).unwrap();
        let right = QuadraticSpan::new(dq[3], dq[4], dq[5]).unwrap();
        for k in 0..=8 {
            let t = k as f64 / 8.0;
            let x = before.eval(&[p[1], p[2], p[3]], t);
            let y = if t <= 0.5 {
                left.eval(&[q[2], q[3], q[4]], 2.0 * t)
            } else {
                right.eval(&[q[3], q[4], q[5]], 2.0 * t - 1.0)
            };
            assert!(close(x, y, 1e-14), "{t}: {x:?} vs {y:?}");
        }
        assert!(refine_curve(&p, &d[..4], false).is_err());
        assert!(refine_curve(&p, &[1.0, 1.0, 0.0, 1.0, 1.0], true).is_err());
    }

    #[test]
    fn grid_refinement_is_tensor_product() {
        let grid: Vec<Vec<[f64; 1]>> = (0..4)
            .map(|i| (0..5).map(|j| [(i * 7 + j * j) as f64]).collect())
            .collect();
        let d = [1.0, 2.0, 0.5, 1.5];
        let e = [0.3, 0.3, 1.0, 2.0, 0.7];
        let (g, dn, en) = refine_grid(&grid, &d, &e, true, false).unwrap();
        assert_eq!(g.len(), 8);
        assert_eq!(g[0].len(), 8);
        assert_eq!(dn.len(), 8);
        assert_eq!(en.len(), 8);
        // columns first then rows gives the same result
        let gt: Vec<Vec<[f64; 1]>> = (0..5)
            .map(|j| (0..4).map(|i| grid[i][j]).collect())
            .collect();
        let (h, _, _) = refine_grid(&gt, &e, &d, false, true).unwrap();
        for i in 0..8 {
            for j in 0..8 {
                assert!((g[i][j][0] - h[j][i][0]).abs() < 1e-13);
            }
        }
    }
}
