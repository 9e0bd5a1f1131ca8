//! Triangular Bernstein-Bezier polynomials, and the regular Loop patch (the
//! quartic three-direction box spline) in that form (math doc section 11).
//!
//! A [`TriBezier`] of degree `d` over the triangle with corners `p0, p1, p2`
//! is
//!
//! ```text
//! f = sum_{i+j+k=d} b_ijk B^d_ijk(u, v, w),   B^d_ijk = d!/(i! j! k!) u^i v^j w^k,
//! ```
//!
//! with barycentric coordinates `(u, v, w) = (1 - s - t, s, t)` for the
//! point `p0 + s (p1 - p0) + t (p2 - p0)`. Facts used (standard; Farin,
//! *Curves and Surfaces for CAGD*, ch. 17, and *Triangular Bernstein-Bezier
//! patches*, CAGD 3, 1986):
//!
//! * convex hull: `min b <= f <= max b` on the triangle; `b_d00, b_0d0, b_00d`
//!   are the values at the corners;
//! * de Casteljau: `b^{r+1}_ijk = u b^r_{i+1,j,k} + v b^r_{i,j+1,k} + w b^r_{i,j,k+1}`;
//!   with a different point at every level it computes the blossom, and the
//!   coefficients over a sub-triangle `(q0, q1, q2)` are the blossom values
//!   `b'_ijk = f[q0^i, q1^j, q2^k]`;
//! * derivatives: `d/ds` has degree `d - 1` and coefficients
//!   `d (b_{i,j+1,k} - b_{i+1,j,k})`, `d/dt` likewise with `b_{i,j,k+1}`;
//! * product: `(f g)_gamma = sum_{alpha+beta=gamma} M(alpha) M(beta) / M(gamma) f_alpha g_beta`
//!   with the multinomials `M(alpha) = d!/(i! j! k!)`; for fixed `gamma` the
//!   weights are non-negative and sum to 1 (Vandermonde);
//! * degree elevation: `b'_ijk = (i b_{i-1,j,k} + j b_{i,j-1,k} + k b_{i,j,k-1}) / (d + 1)`.
//!
//! So the Jacobian determinant of a planar quartic map is a degree-6
//! polynomial with 28 coefficients ([`PlanarTri::jacobian`]).
//!
//! ```
//! use subdiv_lab::schemes::loop_subdivision::tri_bezier::TriBezier;
//! // f = s (barycentric v) as a linear polynomial, squared: s^2
//! let f = TriBezier::new(1, vec![0.0, 1.0, 0.0]).unwrap();
//! let g = f.mul(&f);
//! assert_eq!(g.degree(), 2);
//! assert!((g.eval(0.5, 0.25) - 0.25).abs() < 1e-15);
//! assert!((g.deriv_s().eval(0.5, 0.25) - 1.0).abs() < 1e-15);
//! ```

use crate::bezier::{binomial, BezierCurve};
use crate::error::{Error, Result};

/// Number of coefficients of degree `d`: `(d + 1)(d + 2) / 2`.
pub const fn coefficient_count(d: usize) -> usize {
    (d + 1) * (d + 2) / 2
}

/// Storage index of `b_ijk` (`i = d - j - k`): `k` outer, `j` inner.
fn idx(d: usize, j: usize, k: usize) -> usize {
    k * (d + 1) - k * k.saturating_sub(1) / 2 + j
}

/// The multi-indices `(i, j, k)` of degree `d` in storage order.
pub fn multi_indices(d: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=d).flat_map(move |k| (0..=d - k).map(move |j| (d - j - k, j, k)))
}

/// The multinomial `d! / (i! j! k!)` as `f64` (exact for `d <= 60`).
fn multinomial(i: usize, j: usize, k: usize) -> f64 {
    binomial(i + j + k, i) * binomial(j + k, j)
}

/// A scalar triangular Bernstein polynomial (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TriBezier {
    d: usize,
    c: Vec<f64>,
}

impl TriBezier {
    /// A polynomial of degree `d` from its coefficients in storage order
    /// ([`multi_indices`]); `(d + 1)(d + 2)/2` of them.
    pub fn new(d: usize, coeffs: Vec<f64>) -> Result<Self> {
        if coeffs.len() != coefficient_count(d) {
            return Err(Error::CountMismatch {
                what: "triangular Bezier coefficients ((d + 1)(d + 2)/2)",
                expected: coefficient_count(d),
                got: coeffs.len(),
            });
        }
        Ok(Self { d, c: coeffs })
    }

    /// A polynomial from `f(i, j, k)`.
    pub fn from_fn(d: usize, mut f: impl FnMut(usize, usize, usize) -> f64) -> Self {
        Self {
            d,
            c: multi_indices(d).map(|(i, j, k)| f(i, j, k)).collect(),
        }
    }

    /// The degree `d`.
    pub fn degree(&self) -> usize {
        self.d
    }

    /// Coefficient `b_ijk` (`i + j + k` must equal the degree).
    pub fn coeff(&self, i: usize, j: usize, k: usize) -> f64 {
        debug_assert_eq!(i + j + k, self.d);
        self.c[idx(self.d, j, k)]
    }

    /// All coefficients in storage order.
    pub fn coeffs(&self) -> &[f64] {
        &self.c
    }

    /// Largest coefficient magnitude.
    pub fn max_abs(&self) -> f64 {
        self.c.iter().fold(0.0f64, |a, x| a.max(x.abs()))
    }

    /// Smallest coefficient and its multi-index.
    pub fn min_coeff(&self) -> (f64, (usize, usize, usize)) {
        let mut best = (f64::INFINITY, (self.d, 0, 0));
        for (x, ijk) in self.c.iter().zip(multi_indices(self.d)) {
            if *x < best.0 {
                best = (*x, ijk);
            }
        }
        best
    }

    /// The polynomial times `a`.
    pub fn scale(&self, a: f64) -> Self {
        Self {
            d: self.d,
            c: self.c.iter().map(|x| a * x).collect(),
        }
    }

    /// `self - other` (equal degrees; the lower degree is elevated first).
    pub fn sub(&self, other: &Self) -> Self {
        let (a, b) = Self::common(self, other);
        Self {
            d: a.d,
            c: a.c.iter().zip(&b.c).map(|(x, y)| x - y).collect(),
        }
    }

    /// `self + other` (the lower degree is elevated first).
    pub fn add(&self, other: &Self) -> Self {
        let (a, b) = Self::common(self, other);
        Self {
            d: a.d,
            c: a.c.iter().zip(&b.c).map(|(x, y)| x + y).collect(),
        }
    }

    fn common(a: &Self, b: &Self) -> (Self, Self) {
        let d = a.d.max(b.d);
        (a.elevate_to(d), b.elevate_to(d))
    }

    /// One de Casteljau level at barycentric `(u, v, w)`: degree `d - 1`.
    fn step(d: usize, c: &[f64], (u, v, w): (f64, f64, f64)) -> Vec<f64> {
        multi_indices(d - 1)
            .map(|(_, j, k)| {
                u * c[idx(d, j, k)] + v * c[idx(d, j + 1, k)] + w * c[idx(d, j, k + 1)]
            })
            .collect()
    }

    /// The blossom `f[x_1, .., x_d]` at `d` barycentric points.
    pub fn blossom(&self, args: &[(f64, f64, f64)]) -> Result<f64> {
        if args.len() != self.d {
            return Err(Error::CountMismatch {
                what: "blossom arguments (one per degree)",
                expected: self.d,
                got: args.len(),
            });
        }
        let mut c = self.c.clone();
        for (r, a) in args.iter().enumerate() {
            c = Self::step(self.d - r, &c, *a);
        }
        Ok(c[0])
    }

    /// The value at barycentric `(u, v, w)` (de Casteljau).
    pub fn eval_bary(&self, b: (f64, f64, f64)) -> f64 {
        let mut c = self.c.clone();
        for r in 0..self.d {
            c = Self::step(self.d - r, &c, b);
        }
        c[0]
    }

    /// The value at `(s, t)`, i.e. barycentric `(1 - s - t, s, t)`.
    pub fn eval(&self, s: f64, t: f64) -> f64 {
        self.eval_bary((1.0 - s - t, s, t))
    }

    /// `d/ds` (along `p1 - p0`), degree `d - 1`; zero for `d = 0`.
    pub fn deriv_s(&self) -> Self {
        self.deriv(true)
    }

    /// `d/dt` (along `p2 - p0`), degree `d - 1`; zero for `d = 0`.
    pub fn deriv_t(&self) -> Self {
        self.deriv(false)
    }

    fn deriv(&self, along_s: bool) -> Self {
        let d = self.d;
        if d == 0 {
            return Self { d: 0, c: vec![0.0] };
        }
        let df = d as f64;
        Self::from_fn(d - 1, |_, j, k| {
            let hi = if along_s {
                self.c[idx(d, j + 1, k)]
            } else {
                self.c[idx(d, j, k + 1)]
            };
            df * (hi - self.c[idx(d, j, k)])
        })
    }

    /// The product, of degree `d + d'`.
    pub fn mul(&self, other: &Self) -> Self {
        let d = self.d + other.d;
        let mut c = vec![0.0; coefficient_count(d)];
        for (a, (i, j, k)) in self.c.iter().zip(multi_indices(self.d)) {
            let ma = multinomial(i, j, k);
            for (b, (p, q, r)) in other.c.iter().zip(multi_indices(other.d)) {
                let w = ma * multinomial(p, q, r) / multinomial(i + p, j + q, k + r);
                c[idx(d, j + q, k + r)] += w * a * b;
            }
        }
        Self { d, c }
    }

    /// Degree elevation by one (same polynomial).
    pub fn elevate(&self) -> Self {
        let d = self.d;
        let e = (d + 1) as f64;
        Self::from_fn(d + 1, |i, j, k| {
            let mut acc = 0.0;
            if i > 0 {
                acc += i as f64 * self.c[idx(d, j, k)];
            }
            if j > 0 {
                acc += j as f64 * self.c[idx(d, j - 1, k)];
            }
            if k > 0 {
                acc += k as f64 * self.c[idx(d, j, k - 1)];
            }
            acc / e
        })
    }

    /// Elevated to degree `d >= self.degree()` (a clone if equal).
    pub fn elevate_to(&self, d: usize) -> Self {
        let mut out = self.clone();
        while out.d < d {
            out = out.elevate();
        }
        out
    }

    /// The polynomial over the sub-triangle with barycentric corners
    /// `q = [q0, q1, q2]` (relative to this triangle), in that sub-triangle's
    /// own Bernstein basis: `b'_ijk = f[q0^i, q1^j, q2^k]`.
    pub fn subtriangle(&self, q: [(f64, f64, f64); 3]) -> Self {
        let d = self.d;
        Self::from_fn(d, |i, j, k| {
            let mut args = Vec::with_capacity(d);
            args.extend(std::iter::repeat_n(q[0], i));
            args.extend(std::iter::repeat_n(q[1], j));
            args.extend(std::iter::repeat_n(q[2], k));
            let mut c = self.c.clone();
            for (r, a) in args.iter().enumerate() {
                c = Self::step(d - r, &c, *a);
            }
            c[0]
        })
    }

    /// Midpoint subdivision into four: the corner triangles at `p0, p1, p2`
    /// and the middle one, as [`SPLIT4`] describes (each keeps the
    /// orientation of the parent). Every new coefficient is formed by `d`
    /// averaging levels with weights `0, 1/2, 1` (one rounding per level).
    pub fn split4(&self) -> [Self; 4] {
        SPLIT4.map(|tri| self.subtriangle(tri.map(bary)))
    }

    /// Bisection at the midpoint of the edge `p1 p2`: the halves
    /// `(p0, p1, m12)` and `(p0, m12, p2)` ([`BISECT`]).
    pub fn bisect(&self) -> [Self; 2] {
        BISECT.map(|tri| self.subtriangle(tri.map(bary)))
    }

    /// The coefficients along the edge from corner `a` to corner `b`
    /// (`a != b` in `0..3`): the univariate Bernstein coefficients of the
    /// restriction of `f` to that edge, `d + 1` of them.
    pub fn edge(&self, a: usize, b: usize) -> Result<Vec<f64>> {
        if a > 2 || b > 2 || a == b {
            return Err(Error::InvalidParameter {
                name: "edge",
                value: format!("({a}, {b})"),
                reason: "an edge joins two different corners 0, 1, 2",
            });
        }
        let d = self.d;
        Ok((0..=d)
            .map(|m| {
                let mut ijk = [0usize; 3];
                ijk[a] = d - m;
                ijk[b] = m;
                self.c[idx(d, ijk[1], ijk[2])]
            })
            .collect())
    }
}

/// `(s, t)` to barycentric `(1 - s - t, s, t)`.
pub fn bary((s, t): (f64, f64)) -> (f64, f64, f64) {
    (1.0 - s - t, s, t)
}

/// The four sub-triangles of [`TriBezier::split4`], corners in the parent's
/// `(s, t)`: at `p0`, at `p1`, at `p2`, middle.
pub const SPLIT4: [[(f64, f64); 3]; 4] = [
    [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5)],
    [(0.5, 0.0), (1.0, 0.0), (0.5, 0.5)],
    [(0.0, 0.5), (0.5, 0.5), (0.0, 1.0)],
    [(0.5, 0.5), (0.0, 0.5), (0.5, 0.0)],
];

/// The two halves of [`TriBezier::bisect`], corners in the parent's `(s, t)`.
pub const BISECT: [[(f64, f64); 3]; 2] = [
    [(0.0, 0.0), (1.0, 0.0), (0.5, 0.5)],
    [(0.0, 0.0), (0.5, 0.5), (0.0, 1.0)],
];

/// A planar triangular Bezier patch `(x(s, t), y(s, t))`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarTri {
    /// First coordinate.
    pub x: TriBezier,
    /// Second coordinate.
    pub y: TriBezier,
}

impl PlanarTri {
    /// A patch from control points in storage order ([`multi_indices`]).
    pub fn from_points(d: usize, pts: &[[f64; 2]]) -> Result<Self> {
        Ok(Self {
            x: TriBezier::new(d, pts.iter().map(|p| p[0]).collect())?,
            y: TriBezier::new(d, pts.iter().map(|p| p[1]).collect())?,
        })
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.x.degree()
    }

    /// The point at `(s, t)`.
    pub fn eval(&self, s: f64, t: f64) -> [f64; 2] {
        [self.x.eval(s, t), self.y.eval(s, t)]
    }

    /// The Jacobian determinant `x_s y_t - x_t y_s` (degree `2d - 2`).
    pub fn jacobian(&self) -> TriBezier {
        let (xs, xt) = (self.x.deriv_s(), self.x.deriv_t());
        let (ys, yt) = (self.y.deriv_s(), self.y.deriv_t());
        xs.mul(&yt).sub(&xt.mul(&ys))
    }

    /// The Jacobian evaluated directly from the derivative patches at `(s, t)`
    /// (independent of the Bernstein product).
    pub fn jacobian_at(&self, s: f64, t: f64) -> f64 {
        let (xs, xt) = (self.x.deriv_s(), self.x.deriv_t());
        let (ys, yt) = (self.y.deriv_s(), self.y.deriv_t());
        xs.eval(s, t) * yt.eval(s, t) - xt.eval(s, t) * ys.eval(s, t)
    }

    /// The patch with its second coordinate negated (reverses orientation).
    pub fn mirrored(&self) -> Self {
        Self {
            x: self.x.clone(),
            y: self.y.scale(-1.0),
        }
    }

    /// The patch with every control point mapped by the linear map `m` (row-major).
    pub fn transformed(&self, m: [[f64; 2]; 2]) -> Self {
        Self {
            x: self.x.scale(m[0][0]).add(&self.y.scale(m[0][1])),
            y: self.x.scale(m[1][0]).add(&self.y.scale(m[1][1])),
        }
    }

    /// The boundary curve from corner `a` to corner `b`.
    pub fn boundary(&self, a: usize, b: usize) -> Result<BezierCurve> {
        let (x, y) = (self.x.edge(a, b)?, self.y.edge(a, b)?);
        Ok(BezierCurve::new(
            x.into_iter().zip(y).map(|(p, q)| [p, q]).collect(),
        ))
    }
}

/// The 12-point control net of a regular Loop patch in lattice coordinates
/// `(a, b)` (point `a P + b Q` of the triangular lattice spanned by two unit
/// vectors 60 degrees apart, edges along `(1, 0)`, `(0, 1)`, `(-1, 1)`): the
/// triangle `(0,0), (1,0), (0,1)` first, then its nine neighbours
/// counter-clockwise from `(1, -1)`.
pub const REGULAR_NET: [(i32, i32); 12] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (1, -1),
    (2, -1),
    (2, 0),
    (1, 1),
    (0, 2),
    (-1, 2),
    (-1, 1),
    (-1, 0),
    (0, -1),
];

/// Denominator of [`BOX_SPLINE_TO_BEZIER`].
pub const BOX_SPLINE_DENOMINATOR: i64 = 24;

/// The quartic box spline patch (regular Loop patch) in triangular Bezier
/// form **\[derived\]**: row `r` gives the Bezier coefficient number `r`
/// (storage order, [`multi_indices`] of degree 4) as
/// `sum_m BOX_SPLINE_TO_BEZIER[r][m] P_m / 24` over the net
/// [`REGULAR_NET`]. Derived here (math doc section 11) by two exact Loop
/// steps on the lattice, the regular limit stencil `(1/2, 1/12 x 6)` at the
/// 15 level-2 vertices of the triangle (the domain points `(j/4, k/4)`), and
/// exact interpolation; the test `box_spline_table_is_rederived_exactly`
/// repeats that derivation. All entries are non-negative and every row sums
/// to 24.
pub const BOX_SPLINE_TO_BEZIER: [[i64; 12]; 15] = [
    [12, 2, 2, 2, 0, 0, 0, 0, 0, 2, 2, 2],
    [12, 4, 3, 3, 0, 0, 0, 0, 0, 1, 0, 1],
    [8, 8, 4, 4, 0, 0, 0, 0, 0, 0, 0, 0],
    [4, 12, 3, 3, 1, 0, 1, 0, 0, 0, 0, 0],
    [2, 12, 2, 2, 2, 2, 2, 0, 0, 0, 0, 0],
    [12, 3, 4, 1, 0, 0, 0, 0, 0, 3, 1, 0],
    [10, 6, 6, 1, 0, 0, 0, 0, 0, 1, 0, 0],
    [6, 10, 6, 1, 0, 0, 1, 0, 0, 0, 0, 0],
    [3, 12, 4, 1, 0, 1, 3, 0, 0, 0, 0, 0],
    [8, 4, 8, 0, 0, 0, 0, 0, 0, 4, 0, 0],
    [6, 6, 10, 0, 0, 0, 1, 0, 0, 1, 0, 0],
    [4, 8, 8, 0, 0, 0, 4, 0, 0, 0, 0, 0],
    [4, 3, 12, 0, 0, 0, 1, 0, 1, 3, 0, 0],
    [3, 4, 12, 0, 0, 0, 3, 1, 0, 1, 0, 0],
    [2, 2, 12, 0, 0, 0, 2, 2, 2, 2, 0, 0],
];

/// The regular Loop patch of a scalar net (ordered as [`REGULAR_NET`]) as a
/// quartic [`TriBezier`]. Each coefficient is `(sum_m k_m P_m) / 24` with
/// integer `k_m >= 0` summing to 24: at most 13 roundings, so the computed
/// coefficients are within `gamma_13 max|P|` of the exact ones.
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::tri_bezier::{regular_patch_scalar, REGULAR_NET};
/// // linear data is reproduced: the patch of a = (first lattice coordinate) is s
/// let net: Vec<f64> = REGULAR_NET.iter().map(|p| p.0 as f64).collect();
/// let f = regular_patch_scalar(net.as_slice().try_into().unwrap());
/// assert!((f.eval(0.3, 0.2) - 0.3).abs() < 1e-15);
/// ```
pub fn regular_patch_scalar(net: &[f64; 12]) -> TriBezier {
    TriBezier {
        d: 4,
        c: BOX_SPLINE_TO_BEZIER
            .iter()
            .map(|row| {
                let s: f64 = row.iter().zip(net).map(|(k, p)| *k as f64 * p).sum();
                s / BOX_SPLINE_DENOMINATOR as f64
            })
            .collect(),
    }
}

/// The regular Loop patch of a planar net (ordered as [`REGULAR_NET`]).
pub fn regular_patch(net: &[[f64; 2]; 12]) -> PlanarTri {
    PlanarTri {
        x: regular_patch_scalar(&net.map(|p| p[0])),
        y: regular_patch_scalar(&net.map(|p| p[1])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Rational, Scalar};
    use crate::schemes::catmull_clark::limit::solve_linear;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;
    use std::collections::HashMap;

    fn coeffs(d: usize) -> impl Strategy<Value = TriBezier> {
        prop::collection::vec(-2.0f64..2.0, coefficient_count(d))
            .prop_map(move |c| TriBezier::new(d, c).unwrap())
    }

    fn point() -> impl Strategy<Value = (f64, f64)> {
        (0.0f64..=1.0, 0.0f64..=1.0).prop_map(|(a, b)| {
            if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            }
        })
    }

    /// Evaluation by the explicit Bernstein sum (independent of de Casteljau).
    fn eval_sum(f: &TriBezier, s: f64, t: f64) -> f64 {
        let u = 1.0 - s - t;
        multi_indices(f.degree())
            .zip(f.coeffs())
            .map(|((i, j, k), c)| {
                c * multinomial(i, j, k) * u.powi(i as i32) * s.powi(j as i32) * t.powi(k as i32)
            })
            .sum()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn de_casteljau_equals_the_bernstein_sum(f in coeffs(5), (s, t) in point()) {
            prop_assert!((f.eval(s, t) - eval_sum(&f, s, t)).abs() < 1e-12);
        }

        #[test]
        fn product_is_the_pointwise_product(f in coeffs(3), g in coeffs(4), (s, t) in point()) {
            let h = f.mul(&g);
            prop_assert_eq!(h.degree(), 7);
            prop_assert!((h.eval(s, t) - f.eval(s, t) * g.eval(s, t)).abs() < 1e-12);
        }

        #[test]
        fn derivatives_obey_the_product_rule_and_differences(f in coeffs(3), g in coeffs(2), (s, t) in point()) {
            let h = f.mul(&g);
            for (dh, df, dg) in [
                (h.deriv_s(), f.deriv_s(), g.deriv_s()),
                (h.deriv_t(), f.deriv_t(), g.deriv_t()),
            ] {
                let want = df.eval(s, t) * g.eval(s, t) + f.eval(s, t) * dg.eval(s, t);
                prop_assert!((dh.eval(s, t) - want).abs() < 1e-11);
            }
            // central differences (polynomials extend beyond the triangle)
            let e = 1e-5;
            let fd = (f.eval(s + e, t) - f.eval(s - e, t)) / (2.0 * e);
            prop_assert!((f.deriv_s().eval(s, t) - fd).abs() < 1e-7);
            let fd = (f.eval(s, t + e) - f.eval(s, t - e)) / (2.0 * e);
            prop_assert!((f.deriv_t().eval(s, t) - fd).abs() < 1e-7);
        }

        #[test]
        fn elevation_keeps_the_polynomial(f in coeffs(4), (s, t) in point()) {
            let g = f.elevate_to(6);
            prop_assert_eq!(g.degree(), 6);
            prop_assert!((g.eval(s, t) - f.eval(s, t)).abs() < 1e-12);
        }

        #[test]
        fn split4_and_bisect_agree_with_evaluation(f in coeffs(6), (a, b) in point()) {
            // a point (a, b) of each piece maps to corner-weighted parent parameters
            for (piece, corners) in f.split4().iter().zip(SPLIT4) {
                let (s, t) = map_point(corners, a, b);
                prop_assert!((piece.eval(a, b) - f.eval(s, t)).abs() < 1e-12);
            }
            for (piece, corners) in f.bisect().iter().zip(BISECT) {
                let (s, t) = map_point(corners, a, b);
                prop_assert!((piece.eval(a, b) - f.eval(s, t)).abs() < 1e-12);
            }
        }

        #[test]
        fn blossom_is_symmetric_and_diagonal(f in coeffs(3), p in point(), q in point(), r in point()) {
            let (p, q, r) = (bary(p), bary(q), bary(r));
            let a = f.blossom(&[p, q, r]).unwrap();
            let b = f.blossom(&[r, p, q]).unwrap();
            prop_assert!((a - b).abs() < 1e-12);
            prop_assert!((f.blossom(&[p, p, p]).unwrap() - f.eval_bary(p)).abs() < 1e-12);
        }
    }

    fn map_point(c: [(f64, f64); 3], a: f64, b: f64) -> (f64, f64) {
        let u = 1.0 - a - b;
        (
            u * c[0].0 + a * c[1].0 + b * c[2].0,
            u * c[0].1 + a * c[1].1 + b * c[2].1,
        )
    }

    #[test]
    fn corners_edges_and_errors() {
        let f = TriBezier::from_fn(3, |i, j, k| (i * 100 + j * 10 + k) as f64);
        assert_eq!(f.eval(0.0, 0.0), 300.0);
        assert_eq!(f.eval(1.0, 0.0), 30.0);
        assert_eq!(f.eval(0.0, 1.0), 3.0);
        assert_eq!(f.edge(1, 2).unwrap(), vec![30.0, 21.0, 12.0, 3.0]);
        assert_eq!(f.edge(0, 1).unwrap(), vec![300.0, 210.0, 120.0, 30.0]);
        assert_eq!(f.edge(2, 0).unwrap(), vec![3.0, 102.0, 201.0, 300.0]);
        assert!(f.edge(1, 1).is_err() && f.edge(0, 3).is_err());
        assert!(TriBezier::new(2, vec![0.0; 5]).is_err());
        assert!(f.blossom(&[(1.0, 0.0, 0.0)]).is_err());
        assert_eq!(f.min_coeff(), (3.0, (0, 0, 3)));
        assert_eq!(coefficient_count(6), 28);
        // split pieces keep the orientation: the identity map has Jacobian 1 everywhere
        let id = PlanarTri::from_points(1, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).unwrap();
        assert_eq!(id.jacobian().coeffs(), &[1.0]);
        for piece in id.x.split4().iter().zip(id.y.split4()) {
            let p = PlanarTri {
                x: piece.0.clone(),
                y: piece.1,
            };
            assert!(p.jacobian().coeffs()[0] > 0.0);
        }
    }

    #[test]
    fn jacobian_of_a_quartic_has_28_coefficients_and_matches_direct_evaluation() {
        let x = TriBezier::from_fn(4, |i, j, k| {
            (i as f64).sin() + j as f64 + 0.1 * (k * k) as f64
        });
        let y = TriBezier::from_fn(4, |i, j, k| {
            (j as f64).cos() + k as f64 - 0.05 * (i * j) as f64
        });
        let p = PlanarTri { x, y };
        let j = p.jacobian();
        assert_eq!((j.degree(), j.coeffs().len()), (6, 28));
        for (s, t) in [
            (0.1, 0.2),
            (0.5, 0.5),
            (0.0, 0.0),
            (0.7, 0.1),
            (1.0 / 3.0, 1.0 / 3.0),
        ] {
            assert!((j.eval(s, t) - p.jacobian_at(s, t)).abs() < 1e-12);
        }
    }

    // ---- the regular patch ----

    type Lattice<T> = HashMap<(i32, i32), T>;

    const NB: [(i32, i32); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];

    /// One regular Loop step on lattice data (missing points are zero): vertex
    /// points `5/8 p + 1/16 sum`, edge points `3/8 (p + q) + 1/8 (far points)`
    /// for the three edge directions.
    fn lattice_step<T: Scalar>(vals: &Lattice<T>) -> Lattice<T> {
        let g = |p: (i32, i32)| vals.get(&p).cloned().unwrap_or_else(T::zero);
        let r = vals
            .keys()
            .map(|p| p.0.abs().max(p.1.abs()))
            .max()
            .unwrap_or(0)
            + 1;
        let mut out = Lattice::new();
        for a in -r..=r {
            for b in -r..=r {
                let p = (a, b);
                let mut v = T::frac(5, 8) * g(p);
                for d in NB {
                    v = v + T::frac(1, 16) * g((a + d.0, b + d.1));
                }
                out.insert((2 * a, 2 * b), v);
                for (d, o1, o2) in [
                    ((1, 0), (0, 1), (1, -1)),
                    ((0, 1), (1, 0), (-1, 1)),
                    ((-1, 1), (0, 1), (-1, 0)),
                ] {
                    let q = (a + d.0, b + d.1);
                    let e = T::frac(3, 8) * (g(p) + g(q))
                        + T::frac(1, 8) * (g((a + o1.0, b + o1.1)) + g((a + o2.0, b + o2.1)));
                    out.insert((2 * a + d.0, 2 * b + d.1), e);
                }
            }
        }
        out
    }

    /// The regular limit stencil `1/2 p + 1/12 sum(neighbours)`.
    fn lattice_limit<T: Scalar>(vals: &Lattice<T>, p: (i32, i32)) -> T {
        let g = |p: (i32, i32)| vals.get(&p).cloned().unwrap_or_else(T::zero);
        let mut v = T::frac(1, 2) * g(p);
        for d in NB {
            v = v + T::frac(1, 12) * g((p.0 + d.0, p.1 + d.1));
        }
        v
    }

    #[test]
    fn box_spline_table_is_rederived_exactly() {
        // exact limit values of each net point's basis function at the 15
        // level-2 vertices (j/4, k/4), then exact Bernstein interpolation
        let pts: Vec<(usize, usize)> = multi_indices(4).map(|(_, j, k)| (j, k)).collect();
        let q = |a: i64, b: i64| Rational::frac(a, b);
        let mut a = DMatrix::from_element(15, 15, q(0, 1));
        for (row, &(pj, pk)) in pts.iter().enumerate() {
            for (col, (i, j, k)) in multi_indices(4).enumerate() {
                // B^4_ijk at (s, t) = (pj/4, pk/4), times 4^4
                let (u, s, t) = (4 - pj - pk, pj, pk);
                let v = multinomial(i, j, k) as i64
                    * (u as i64).pow(i as u32)
                    * (s as i64).pow(j as u32)
                    * (t as i64).pow(k as u32);
                a[(row, col)] = q(v, 256);
            }
        }
        for (m, off) in REGULAR_NET.iter().enumerate() {
            let mut vals = Lattice::new();
            vals.insert(*off, q(1, 1));
            let l2 = lattice_step(&lattice_step(&vals));
            let rhs = DVector::from_iterator(
                15,
                pts.iter()
                    .map(|&(j, k)| lattice_limit(&l2, (j as i32, k as i32))),
            );
            let sol = solve_linear(a.clone(), rhs).unwrap();
            for (r, row) in BOX_SPLINE_TO_BEZIER.iter().enumerate() {
                assert_eq!(
                    sol[r],
                    q(row[m], BOX_SPLINE_DENOMINATOR),
                    "coefficient {r}, net point {m}"
                );
            }
        }
        for row in BOX_SPLINE_TO_BEZIER {
            assert_eq!(row.iter().sum::<i64>(), BOX_SPLINE_DENOMINATOR);
            assert!(row.iter().all(|k| *k >= 0));
        }
    }

    #[test]
    fn regular_patch_reproduces_linear_functions() {
        let net: [[f64; 2]; 12] = REGULAR_NET.map(|p| [p.0 as f64, p.1 as f64]);
        let p = regular_patch(&net);
        for ((_, j, k), (x, y)) in multi_indices(4).zip(p.x.coeffs().iter().zip(p.y.coeffs())) {
            assert_eq!((*x, *y), (j as f64 / 4.0, k as f64 / 4.0));
        }
        let c = regular_patch_scalar(&[2.5; 12]);
        assert!(c.coeffs().iter().all(|x| *x == 2.5));
        assert!(p
            .jacobian()
            .coeffs()
            .iter()
            .all(|x| (x - 1.0).abs() < 1e-14));
    }

    fn random_lattice(r: i32, seed: u64) -> Lattice<f64> {
        let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        let mut out = Lattice::new();
        for a in -r..=r {
            for b in -r..=r {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                out.insert((a, b), (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
            }
        }
        out
    }

    /// The patch over the up-triangle at `origin`, or over the down-triangle
    /// `centre - (up triangle)` (point reflection) when `reflect` is set.
    fn patch_at(vals: &Lattice<f64>, origin: (i32, i32), reflect: bool) -> TriBezier {
        let net = REGULAR_NET.map(|o| {
            let p = if reflect {
                (origin.0 - o.0, origin.1 - o.1)
            } else {
                (origin.0 + o.0, origin.1 + o.1)
            };
            vals[&p]
        });
        regular_patch_scalar(&net)
    }

    #[test]
    fn adjacent_regular_patches_join_with_c1() {
        for seed in 0..5 {
            let vals = random_lattice(4, seed);
            let up = patch_at(&vals, (0, 0), false);
            // down triangles across the edges (1,0)-(0,1) and (0,0)-(1,0):
            // lattice point x is (centre - x) in their parameters
            for centre in [(1, 1), (1, 0)] {
                let down = patch_at(&vals, centre, true);
                let cf = (centre.0 as f64, centre.1 as f64);
                for m in 0..=8 {
                    let h = m as f64 / 8.0;
                    let x = if centre == (1, 1) {
                        (h, 1.0 - h)
                    } else {
                        (h, 0.0)
                    };
                    let y = (cf.0 - x.0, cf.1 - x.1);
                    assert!((up.eval(x.0, x.1) - down.eval(y.0, y.1)).abs() < 1e-14);
                    // gradients with respect to the lattice coordinates
                    let gu = (up.deriv_s().eval(x.0, x.1), up.deriv_t().eval(x.0, x.1));
                    let gd = (
                        -down.deriv_s().eval(y.0, y.1),
                        -down.deriv_t().eval(y.0, y.1),
                    );
                    assert!(
                        (gu.0 - gd.0).abs() < 1e-13 && (gu.1 - gd.1).abs() < 1e-13,
                        "seed {seed}, centre {centre:?}, h {h}"
                    );
                }
            }
        }
    }

    #[test]
    fn regular_patch_is_the_limit_of_subdivision() {
        // limit values at the level-3 vertices (j/8, k/8) of the triangle, by three
        // lattice steps and the limit stencil, against the patch (a check beyond
        // the 15 level-2 points the table was derived from)
        for seed in 0..3 {
            let vals = random_lattice(3, 100 + seed);
            let p = patch_at(&vals, (0, 0), false);
            let l3 = lattice_step(&lattice_step(&lattice_step(&vals)));
            for k in 0..=8 {
                for j in 0..=8 - k {
                    let want = lattice_limit(&l3, (j, k));
                    let got = p.eval(j as f64 / 8.0, k as f64 / 8.0);
                    assert!(
                        (got - want).abs() < 1e-13,
                        "seed {seed} at ({j}, {k}): {got} vs {want}"
                    );
                }
            }
        }
    }
}
