//! Tensor-product Bernstein (Bezier) polynomials and planar Bezier curves.
//!
//! Generic machinery, independent of any subdivision scheme: the
//! characteristic-map checks of the Doo-Sabin family use it for biquadratic
//! patches (Jacobian bidegree (3, 3)); the Catmull-Clark family can use it for
//! bicubic patches (Jacobian bidegree (5, 5)).
//!
//! A [`TensorBezier`] of bidegree `(m, n)` is
//!
//! ```text
//! f(s, t) = sum_{i=0..m} sum_{j=0..n} c_ij B^m_i(s) B^n_j(t),   (s, t) in [0, 1]^2,
//! B^m_i(s) = C(m, i) s^i (1 - s)^(m - i).
//! ```
//!
//! Facts used (standard; e.g. Farin, *Curves and Surfaces for CAGD*):
//!
//! * convex hull: `min c_ij <= f <= max c_ij` on `[0, 1]^2`, so coefficients of
//!   one strict sign certify the sign of `f`;
//! * derivative: `d/ds f` has bidegree `(m - 1, n)` and coefficients
//!   `m (c_{i+1,j} - c_ij)`;
//! * product: `(f g)_kl = sum_{i+i'=k, j+j'=l} w c_ij d_i'j'` with
//!   `w = C(m,i) C(m',i') / C(m+m',k) * C(n,j) C(n',j') / C(n+n',l)`; for fixed
//!   `(k, l)` the weights are non-negative and sum to 1;
//! * de Casteljau subdivision at `s = a` splits a patch into two patches of the
//!   same bidegree over `[0, a]` and `[a, 1]` (convex combinations only);
//! * degree elevation in `s`: `c'_i = i/(m+1) c_{i-1} + (1 - i/(m+1)) c_i`.
//!
//! ```
//! use subdiv_lab::bezier::TensorBezier;
//! // f(s, t) = s t as a bilinear patch
//! let f = TensorBezier::new(1, 1, vec![0.0, 0.0, 0.0, 1.0]).unwrap();
//! let g = f.mul(&f);                      // s^2 t^2, bidegree (2, 2)
//! assert!((g.eval(0.5, 0.5) - 0.0625).abs() < 1e-15);
//! let (lo, _) = g.split_s(0.5);
//! assert!((lo.eval(1.0, 1.0) - 0.25).abs() < 1e-15);
//! ```

use crate::error::{Error, Result};

/// Binomial coefficient `C(n, k)` as `f64` (exact for the degrees used here, `n <= 60`).
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut r = 1.0f64;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r.round()
}

/// A scalar tensor-product Bernstein polynomial of bidegree `(m, n)` on `[0, 1]^2`.
///
/// Coefficient `c_ij` (index `i` along `s`, `j` along `t`) is stored at
/// `i * (n + 1) + j`.
#[derive(Clone, Debug, PartialEq)]
pub struct TensorBezier {
    m: usize,
    n: usize,
    c: Vec<f64>,
}

impl TensorBezier {
    /// A patch from its `(m + 1)(n + 1)` coefficients (row-major in `i`).
    pub fn new(m: usize, n: usize, coeffs: Vec<f64>) -> Result<Self> {
        let want = (m + 1) * (n + 1);
        if coeffs.len() != want {
            return Err(Error::CountMismatch {
                what: "Bezier coefficients ((m + 1)(n + 1))",
                expected: want,
                got: coeffs.len(),
            });
        }
        Ok(Self { m, n, c: coeffs })
    }

    /// A patch with `c_ij = f(i, j)`.
    pub fn from_fn(m: usize, n: usize, mut f: impl FnMut(usize, usize) -> f64) -> Self {
        let mut c = Vec::with_capacity((m + 1) * (n + 1));
        for i in 0..=m {
            for j in 0..=n {
                c.push(f(i, j));
            }
        }
        Self { m, n, c }
    }

    /// Bidegree `(m, n)`.
    pub fn degree(&self) -> (usize, usize) {
        (self.m, self.n)
    }

    /// Coefficient `c_ij`.
    pub fn coeff(&self, i: usize, j: usize) -> f64 {
        self.c[i * (self.n + 1) + j]
    }

    /// All coefficients, row-major in `i`.
    pub fn coeffs(&self) -> &[f64] {
        &self.c
    }

    /// Largest coefficient magnitude.
    pub fn max_abs(&self) -> f64 {
        self.c.iter().fold(0.0f64, |a, x| a.max(x.abs()))
    }

    /// The smallest coefficient and its index `(value, i, j)`.
    pub fn min_coeff(&self) -> (f64, usize, usize) {
        let mut best = (f64::INFINITY, 0, 0);
        for i in 0..=self.m {
            for j in 0..=self.n {
                let v = self.coeff(i, j);
                if v < best.0 {
                    best = (v, i, j);
                }
            }
        }
        best
    }

    /// The largest coefficient and its index `(value, i, j)`.
    pub fn max_coeff(&self) -> (f64, usize, usize) {
        let mut best = (f64::NEG_INFINITY, 0, 0);
        for i in 0..=self.m {
            for j in 0..=self.n {
                let v = self.coeff(i, j);
                if v > best.0 {
                    best = (v, i, j);
                }
            }
        }
        best
    }

    /// Value at `(s, t)` by de Casteljau (rows in `t`, then the column in `s`).
    pub fn eval(&self, s: f64, t: f64) -> f64 {
        let mut col = Vec::with_capacity(self.m + 1);
        let mut row = vec![0.0; self.n + 1];
        for i in 0..=self.m {
            row.copy_from_slice(&self.c[i * (self.n + 1)..(i + 1) * (self.n + 1)]);
            col.push(de_casteljau(&mut row, t));
        }
        de_casteljau(&mut col, s)
    }

    /// `d f / d s` (bidegree `(m - 1, n)`; the zero polynomial of degree 0 if `m = 0`).
    pub fn deriv_s(&self) -> Self {
        if self.m == 0 {
            return Self::from_fn(0, self.n, |_, _| 0.0);
        }
        let m = self.m as f64;
        Self::from_fn(self.m - 1, self.n, |i, j| {
            m * (self.coeff(i + 1, j) - self.coeff(i, j))
        })
    }

    /// `d f / d t` (bidegree `(m, n - 1)`).
    pub fn deriv_t(&self) -> Self {
        if self.n == 0 {
            return Self::from_fn(self.m, 0, |_, _| 0.0);
        }
        let n = self.n as f64;
        Self::from_fn(self.m, self.n - 1, |i, j| {
            n * (self.coeff(i, j + 1) - self.coeff(i, j))
        })
    }

    /// The product `f g` (bidegree `(m + m', n + n')`).
    pub fn mul(&self, other: &Self) -> Self {
        let (m, n) = (self.m + other.m, self.n + other.n);
        let mut out = vec![0.0; (m + 1) * (n + 1)];
        for i in 0..=self.m {
            for i2 in 0..=other.m {
                let wu = binomial(self.m, i) * binomial(other.m, i2) / binomial(m, i + i2);
                for j in 0..=self.n {
                    let a = self.coeff(i, j) * wu;
                    for j2 in 0..=other.n {
                        let wv = binomial(self.n, j) * binomial(other.n, j2) / binomial(n, j + j2);
                        out[(i + i2) * (n + 1) + j + j2] += a * wv * other.coeff(i2, j2);
                    }
                }
            }
        }
        Self { m, n, c: out }
    }

    /// `f - g`; the lower-degree operand is degree-elevated first.
    pub fn sub(&self, other: &Self) -> Self {
        let (m, n) = (self.m.max(other.m), self.n.max(other.n));
        let a = self.elevate_to(m, n);
        let b = other.elevate_to(m, n);
        Self {
            m,
            n,
            c: a.c.iter().zip(&b.c).map(|(x, y)| x - y).collect(),
        }
    }

    /// `f + g`; the lower-degree operand is degree-elevated first.
    pub fn add(&self, other: &Self) -> Self {
        let (m, n) = (self.m.max(other.m), self.n.max(other.n));
        let a = self.elevate_to(m, n);
        let b = other.elevate_to(m, n);
        Self {
            m,
            n,
            c: a.c.iter().zip(&b.c).map(|(x, y)| x + y).collect(),
        }
    }

    /// Degree elevation by one in `s`.
    pub fn elevate_s(&self) -> Self {
        let m1 = (self.m + 1) as f64;
        Self::from_fn(self.m + 1, self.n, |i, j| {
            let a = i as f64 / m1;
            let lo = if i > 0 { self.coeff(i - 1, j) } else { 0.0 };
            let hi = if i <= self.m { self.coeff(i, j) } else { 0.0 };
            a * lo + (1.0 - a) * hi
        })
    }

    /// Degree elevation by one in `t`.
    pub fn elevate_t(&self) -> Self {
        let n1 = (self.n + 1) as f64;
        Self::from_fn(self.m, self.n + 1, |i, j| {
            let a = j as f64 / n1;
            let lo = if j > 0 { self.coeff(i, j - 1) } else { 0.0 };
            let hi = if j <= self.n { self.coeff(i, j) } else { 0.0 };
            a * lo + (1.0 - a) * hi
        })
    }

    /// Degree elevation to bidegree `(m, n)` (no-op in a direction already at that degree;
    /// degrees are never lowered).
    pub fn elevate_to(&self, m: usize, n: usize) -> Self {
        let mut f = self.clone();
        while f.m < m {
            f = f.elevate_s();
        }
        while f.n < n {
            f = f.elevate_t();
        }
        f
    }

    /// de Casteljau split at `s = a`: the patches over `[0, a]` and `[a, 1]` in `s`,
    /// each reparametrised to `[0, 1]`.
    pub fn split_s(&self, a: f64) -> (Self, Self) {
        let (m, n) = (self.m, self.n);
        let mut lo = self.clone();
        let mut hi = self.clone();
        let mut col = vec![0.0; m + 1];
        let mut l = vec![0.0; m + 1];
        let mut h = vec![0.0; m + 1];
        for j in 0..=n {
            for (i, c) in col.iter_mut().enumerate() {
                *c = self.coeff(i, j);
            }
            split_1d(&col, a, &mut l, &mut h);
            for i in 0..=m {
                lo.c[i * (n + 1) + j] = l[i];
                hi.c[i * (n + 1) + j] = h[i];
            }
        }
        (lo, hi)
    }

    /// de Casteljau split at `t = a`.
    pub fn split_t(&self, a: f64) -> (Self, Self) {
        let n = self.n;
        let mut lo = self.clone();
        let mut hi = self.clone();
        let mut l = vec![0.0; n + 1];
        let mut h = vec![0.0; n + 1];
        for i in 0..=self.m {
            let row = &self.c[i * (n + 1)..(i + 1) * (n + 1)];
            split_1d(row, a, &mut l, &mut h);
            lo.c[i * (n + 1)..(i + 1) * (n + 1)].copy_from_slice(&l);
            hi.c[i * (n + 1)..(i + 1) * (n + 1)].copy_from_slice(&h);
        }
        (lo, hi)
    }

    /// The restriction to `[s0, s1] x [t0, t1]`, reparametrised to `[0, 1]^2`.
    pub fn restrict(&self, s0: f64, s1: f64, t0: f64, t1: f64) -> Self {
        let mut f = self.clone();
        if s1 < 1.0 {
            f = f.split_s(s1).0;
        }
        if s0 > 0.0 {
            f = f.split_s(s0 / s1).1;
        }
        if t1 < 1.0 {
            f = f.split_t(t1).0;
        }
        if t0 > 0.0 {
            f = f.split_t(t0 / t1).1;
        }
        f
    }
}

/// In-place de Casteljau on a coefficient row; returns the value at `t`.
fn de_casteljau(b: &mut [f64], t: f64) -> f64 {
    let k = b.len();
    for r in 1..k {
        for i in 0..k - r {
            b[i] = (1.0 - t) * b[i] + t * b[i + 1];
        }
    }
    b[0]
}

/// Splits univariate coefficients `b` at `a` into `lo` (over `[0, a]`) and `hi` (over `[a, 1]`).
fn split_1d(b: &[f64], a: f64, lo: &mut [f64], hi: &mut [f64]) {
    let k = b.len();
    let mut buf = [0.0f64; 16];
    let mut heap;
    let tmp: &mut [f64] = if k <= 16 {
        &mut buf[..k]
    } else {
        heap = vec![0.0; k];
        &mut heap[..]
    };
    tmp.copy_from_slice(b);
    for r in 0..k {
        lo[r] = tmp[0];
        hi[k - 1 - r] = tmp[k - 1 - r];
        for i in 0..k - 1 - r {
            tmp[i] = (1.0 - a) * tmp[i] + a * tmp[i + 1];
        }
    }
}

/// A planar tensor-product Bezier patch `(x(s, t), y(s, t))`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarPatch {
    /// First coordinate.
    pub x: TensorBezier,
    /// Second coordinate.
    pub y: TensorBezier,
}

impl PlanarPatch {
    /// A patch from a control net `net[i][j] = [x, y]` (`i` along `s`).
    pub fn from_net(net: &[Vec<[f64; 2]>]) -> Result<Self> {
        let m = net.len().checked_sub(1).ok_or(Error::CountMismatch {
            what: "rows of a Bezier net",
            expected: 1,
            got: 0,
        })?;
        let n = net[0].len().checked_sub(1).ok_or(Error::CountMismatch {
            what: "columns of a Bezier net",
            expected: 1,
            got: 0,
        })?;
        if let Some(r) = net.iter().find(|r| r.len() != n + 1) {
            return Err(Error::CountMismatch {
                what: "columns of a Bezier net (rows must have equal length)",
                expected: n + 1,
                got: r.len(),
            });
        }
        Ok(Self {
            x: TensorBezier::from_fn(m, n, |i, j| net[i][j][0]),
            y: TensorBezier::from_fn(m, n, |i, j| net[i][j][1]),
        })
    }

    /// The point at `(s, t)`.
    pub fn eval(&self, s: f64, t: f64) -> [f64; 2] {
        [self.x.eval(s, t), self.y.eval(s, t)]
    }

    /// Control point `b_ij`.
    pub fn control(&self, i: usize, j: usize) -> [f64; 2] {
        [self.x.coeff(i, j), self.y.coeff(i, j)]
    }

    /// Bidegree.
    pub fn degree(&self) -> (usize, usize) {
        self.x.degree()
    }

    /// The Jacobian determinant `x_s y_t - x_t y_s` as a Bernstein polynomial
    /// (bidegree `(2m - 1, 2n - 1)`).
    pub fn jacobian(&self) -> TensorBezier {
        let (xs, xt) = (self.x.deriv_s(), self.x.deriv_t());
        let (ys, yt) = (self.y.deriv_s(), self.y.deriv_t());
        xs.mul(&yt).sub(&xt.mul(&ys))
    }

    /// The Jacobian determinant evaluated directly from the derivatives at `(s, t)`
    /// (an evaluation independent of the Bernstein product).
    pub fn jacobian_at(&self, s: f64, t: f64) -> f64 {
        let (xs, xt) = (self.x.deriv_s(), self.x.deriv_t());
        let (ys, yt) = (self.y.deriv_s(), self.y.deriv_t());
        xs.eval(s, t) * yt.eval(s, t) - xt.eval(s, t) * ys.eval(s, t)
    }

    /// The patch with its second coordinate negated (reverses orientation).
    pub fn mirrored(&self) -> Self {
        Self {
            x: self.x.clone(),
            y: TensorBezier {
                m: self.y.m,
                n: self.y.n,
                c: self.y.c.iter().map(|v| -v).collect(),
            },
        }
    }

    /// Boundary curve `t = t0` (`t0` in {0, 1}) as a Bezier curve in `s`.
    pub fn boundary_t(&self, at_one: bool) -> BezierCurve {
        let (m, n) = self.degree();
        let j = if at_one { n } else { 0 };
        BezierCurve::new((0..=m).map(|i| self.control(i, j)).collect())
    }

    /// Boundary curve `s = s0` (`s0` in {0, 1}) as a Bezier curve in `t`.
    pub fn boundary_s(&self, at_one: bool) -> BezierCurve {
        let (m, n) = self.degree();
        let i = if at_one { m } else { 0 };
        BezierCurve::new((0..=n).map(|j| self.control(i, j)).collect())
    }
}

/// A planar Bezier curve `sum_k b_k B^d_k(u)`, `u in [0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierCurve {
    /// Control points `b_0..b_d`.
    pub points: Vec<[f64; 2]>,
}

impl BezierCurve {
    /// A curve from its control points (at least one).
    pub fn new(points: Vec<[f64; 2]>) -> Self {
        Self { points }
    }

    /// Degree `d`.
    pub fn degree(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// The same curve traversed backwards.
    pub fn reversed(&self) -> Self {
        let mut p = self.points.clone();
        p.reverse();
        Self { points: p }
    }

    /// The point at `u` (de Casteljau).
    pub fn eval(&self, u: f64) -> [f64; 2] {
        let mut x: Vec<f64> = self.points.iter().map(|p| p[0]).collect();
        let mut y: Vec<f64> = self.points.iter().map(|p| p[1]).collect();
        [de_casteljau(&mut x, u), de_casteljau(&mut y, u)]
    }

    /// de Casteljau split at `u = a`.
    pub fn split(&self, a: f64) -> (Self, Self) {
        let k = self.points.len();
        let mut lo = vec![[0.0; 2]; k];
        let mut hi = vec![[0.0; 2]; k];
        for d in 0..2 {
            let b: Vec<f64> = self.points.iter().map(|p| p[d]).collect();
            let mut l = vec![0.0; k];
            let mut h = vec![0.0; k];
            split_1d(&b, a, &mut l, &mut h);
            for i in 0..k {
                lo[i][d] = l[i];
                hi[i][d] = h[i];
            }
        }
        (Self { points: lo }, Self { points: hi })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Power-form reference: f(s, t) = sum a_pq s^p t^q.
    fn poly(s: f64, t: f64) -> f64 {
        1.0 + 2.0 * s - 3.0 * t + s * t - 0.5 * s * s * t + 0.25 * t * t * s
    }

    /// Bernstein coefficients of `poly` at bidegree (2, 2) by interpolation-free
    /// blossoming: for monomials s^p, coefficient i is C(i, p)/C(m, p).
    fn poly_bezier() -> TensorBezier {
        let mono = |i: usize, p: usize, m: usize| binomial(i, p) / binomial(m, p);
        let terms: [(f64, usize, usize); 6] = [
            (1.0, 0, 0),
            (2.0, 1, 0),
            (-3.0, 0, 1),
            (1.0, 1, 1),
            (-0.5, 2, 1),
            (0.25, 1, 2),
        ];
        TensorBezier::from_fn(2, 2, |i, j| {
            terms
                .iter()
                .map(|&(a, p, q)| a * mono(i, p, 2) * mono(j, q, 2))
                .sum()
        })
    }

    #[test]
    fn eval_matches_power_form() {
        let f = poly_bezier();
        for (s, t) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.2), (0.5, 1.0)] {
            assert!((f.eval(s, t) - poly(s, t)).abs() < 1e-14);
        }
    }

    #[test]
    fn derivatives_products_and_elevation() {
        let f = poly_bezier();
        let h = 1e-6;
        for (s, t) in [(0.2, 0.4), (0.9, 0.1)] {
            let ds = (poly(s + h, t) - poly(s - h, t)) / (2.0 * h);
            let dt = (poly(s, t + h) - poly(s, t - h)) / (2.0 * h);
            assert!((f.deriv_s().eval(s, t) - ds).abs() < 1e-8);
            assert!((f.deriv_t().eval(s, t) - dt).abs() < 1e-8);
            let g = f.deriv_s().mul(&f);
            assert_eq!(g.degree(), (3, 4));
            assert!((g.eval(s, t) - f.deriv_s().eval(s, t) * poly(s, t)).abs() < 1e-13);
            let e = f.elevate_to(4, 3);
            assert!((e.eval(s, t) - poly(s, t)).abs() < 1e-14);
            let d = f.sub(&f.deriv_t());
            assert!((d.eval(s, t) - (poly(s, t) - dt)).abs() < 1e-8);
        }
    }

    #[test]
    fn splits_reparametrise() {
        let f = poly_bezier();
        let (lo, hi) = f.split_s(0.3);
        let (lt, ht) = f.split_t(0.6);
        for (s, t) in [(0.0, 0.0), (0.5, 0.5), (1.0, 0.25)] {
            assert!((lo.eval(s, t) - poly(0.3 * s, t)).abs() < 1e-14);
            assert!((hi.eval(s, t) - poly(0.3 + 0.7 * s, t)).abs() < 1e-14);
            assert!((lt.eval(s, t) - poly(s, 0.6 * t)).abs() < 1e-14);
            assert!((ht.eval(s, t) - poly(s, 0.6 + 0.4 * t)).abs() < 1e-14);
            let r = f.restrict(0.25, 0.5, 0.5, 0.75);
            assert!((r.eval(s, t) - poly(0.25 + 0.25 * s, 0.5 + 0.25 * t)).abs() < 1e-14);
        }
    }

    #[test]
    fn jacobian_of_a_planar_patch() {
        // x = s + s t, y = t^2 + s: J = (1 + t)(2t) - s * 1
        let net: Vec<Vec<[f64; 2]>> = (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| {
                        let (a, b) = (i as f64 / 2.0, j as f64 / 2.0);
                        // blossom of x = s + s t at (i/2, j/2) for bidegree (2, 2): s + s t exactly
                        // (bilinear terms have blossom = value at the averaged arguments)
                        let y_t2 = if j == 2 { 1.0 } else { 0.0 }; // blossom of t^2: b0=0,b1=0,b2=1
                        [a + a * b, y_t2 + a]
                    })
                    .collect()
            })
            .collect();
        let p = PlanarPatch::from_net(&net).unwrap();
        for (s, t) in [(0.1, 0.2), (0.7, 0.9)] {
            let want = (1.0 + t) * 2.0 * t - s;
            assert!((p.jacobian().eval(s, t) - want).abs() < 1e-13);
            assert!((p.jacobian_at(s, t) - want).abs() < 1e-13);
        }
        assert_eq!(p.jacobian().degree(), (3, 3));
        let c = p.boundary_t(true);
        assert_eq!(c.eval(0.5), p.eval(0.5, 1.0));
        let (a, b) = c.split(0.25);
        assert!((a.eval(1.0)[0] - c.eval(0.25)[0]).abs() < 1e-15);
        assert!((b.eval(0.5)[1] - c.eval(0.625)[1]).abs() < 1e-15);
    }
}
