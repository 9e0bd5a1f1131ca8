//! First-order affine forms with a rigorous remainder (math doc section 15,
//! "The characteristic map over a cell" **\[derived\]**).
//!
//! A value is `x_0 + sum_i x_i eps_i + [-e, e]` with shared noise symbols
//! `eps_i` in `[-1, 1]` (the cell's parameters and the entries of the
//! subspace correction `P`). Differences of quantities that depend on the
//! same symbols cancel to first order (the ring's control-point differences
//! and the Jacobian coefficients), which naive interval arithmetic loses:
//! there a cell of width `h` gives a width proportional to the size of the
//! points, here to the size of their derivatives.
//!
//! Rounding: every float operation on a coefficient is followed by adding
//! a bound of its rounding error to `e`: `|fl(x) - x| <= 2^-53 |x| + 2^-1075`,
//! bounded by `2^-52 |fl(x)| + MIN_POSITIVE` (summed over a form's
//! coefficients in one step, `err_sum`). Products bound the second-order
//! part `(sum |x_i| + e_x)(sum |y_i| + e_y)` into `e`.

use super::super::interval::{down, up, Iv};
use smallvec::SmallVec;

/// The symbol coefficients of a form, stored inline up to 64 symbols: the
/// `n + 2 (n - 2) + 4 + 6n` symbols over which a ratio cell's ring is
/// computed up to valence 7, and a ring patch's own symbols (math doc
/// section 15, "Named remainders"); longer forms spill to the heap.
pub type Coeffs = SmallVec<[f64; 64]>;

/// `2^-52`: twice the unit roundoff, a bound on the relative rounding error.
const EPS: f64 = f64::EPSILON;

/// Lanes of the coefficient loops: partial sums kept per lane and added at
/// the end (a summation order like any other for the bounds of
/// [`sum_upper`] and [`err_sum`]).
const LANES: usize = 4;

// [`lane_totals`] adds exactly four lanes
const _: () = assert!(LANES == 4);

/// The `A` sums of the coefficient loops from their per-lane partial sums
/// (`lanes[lane][t]`), each added as `(l_0 + l_1) + (l_2 + l_3)`.
fn lane_totals<const A: usize>(lanes: &[[f64; A]; LANES]) -> [f64; A] {
    std::array::from_fn(|t| (lanes[0][t] + lanes[1][t]) + (lanes[2][t] + lanes[3][t]))
}

/// `out_i <- f(out_i, b_i, sums)` over the coefficients in [`LANES`] lanes,
/// each lane with its own `A` partial sums, added at the end: the sums of
/// the coefficient loops in an order that the vector units can follow
/// (every bound here holds for any summation order).
fn zip_lanes<const A: usize>(
    out: &mut [f64],
    b: &[f64],
    f: impl Fn(f64, f64, &mut [f64; A]) -> f64,
) -> [f64; A] {
    assert_eq!(out.len(), b.len(), "forms over different symbols");
    let mut lanes = [[0.0f64; A]; LANES];
    let mut os = out.chunks_exact_mut(LANES);
    let mut bs = b.chunks_exact(LANES);
    for (o, bv) in (&mut os).zip(&mut bs) {
        for (lane, acc) in lanes.iter_mut().enumerate() {
            o[lane] = f(o[lane], bv[lane], acc);
        }
    }
    for (o, bi) in os.into_remainder().iter_mut().zip(bs.remainder()) {
        *o = f(*o, *bi, &mut lanes[0]);
    }
    lane_totals(&lanes)
}

/// Bound of the rounding error of an operation whose float result is `x`.
fn err(x: f64) -> f64 {
    up(up(x.abs() * EPS) + f64::MIN_POSITIVE)
}

/// Slack factor of [`err_sum`] over `2^-52`: covers the relative error
/// `(1 + k 2^-53)` of a float sum of `k <= 2^30` non-negative terms.
const SUM_SLACK: f64 = 1.001;

/// Bound of the summed rounding errors of `k` operations whose float
/// results have magnitudes summing (in floating point) to `mag`:
/// `sum_i (2^-52 |x_i| + MIN_POSITIVE) <= 2^-52 SUM_SLACK mag + k MIN_POSITIVE`
/// (one bound per coefficient vector instead of one per coefficient).
fn err_sum(mag: f64, k: usize) -> f64 {
    up(up(mag * (EPS * SUM_SLACK)) + k as f64 * f64::MIN_POSITIVE)
}

/// An upper bound of the exact sum `S` of `k` non-negative numbers whose
/// float sum (round to nearest, any order) is `s`: `|s - S| <= gamma S` with
/// `gamma = (k - 1) u / (1 - (k - 1) u)`, `u = 2^-53`, so `S <= s / (1 -
/// gamma) <= s (1 + 2 k u) = s (1 + k 2^-52)` while `k u <= 1/4`; the factor
/// and the product are rounded up. (Sums of non-negative floats have no
/// underflow error: a subnormal sum is exact.)
pub fn sum_upper(s: f64, k: usize) -> f64 {
    up(s * up(1.0 + k as f64 * EPS))
}

/// `a_0 b_1 - a_1 b_0` for two points of forms: both products of
/// [`Af::mul`] and their difference in one pass, with both products'
/// second-order parts and remainders and the rounding of the `7 k + 3`
/// float operations (math doc section 15, "Affine forms").
///
/// ```
/// use subdiv_lab::verify::charmap::af::{det, Af};
/// let (x, y) = (Af::symbol(0.5, 0.1, 0, 2), Af::symbol(-0.2, 0.05, 1, 2));
/// let d = det(&[x.clone(), y.clone()], &[y.clone(), x.clone()]);
/// let slow = x.mul(&x).sub(&y.mul(&y));
/// assert!((d.c - slow.c).abs() < 1e-15 && (d.e - slow.e).abs() < 1e-12);
/// ```
pub fn det(a: &[Af; 2], b: &[Af; 2]) -> Af {
    let (x, y, z, w) = (&a[0], &b[1], &a[1], &b[0]);
    let k = x.l.len();
    assert!(
        y.l.len() == k && z.l.len() == k && w.l.len() == k,
        "forms over different symbols"
    );
    let p0 = x.c * y.c;
    let q0 = z.c * w.c;
    let c = p0 - q0;
    let mut l = Coeffs::from_elem(0.0, k);
    // per lane: the magnitude sums of x, y, z, w and of the 7 rounded
    // operations' results (any summation order is covered, [`sum_upper`],
    // [`err_sum`]); four lanes let the loop run in vector registers
    let (xc, yc, zc, wc) = (x.c, y.c, z.c, w.c);
    let step = |xi: f64, yi: f64, zi: f64, wi: f64, acc: &mut [f64; 5]| -> f64 {
        acc[0] += xi.abs();
        acc[1] += yi.abs();
        acc[2] += zi.abs();
        acc[3] += wi.abs();
        let (p1, p2) = (xc * yi, yc * xi);
        let p = p1 + p2;
        let (q1, q2) = (zc * wi, wc * zi);
        let q = q1 + q2;
        let v = p - q;
        acc[4] += ((p1.abs() + p2.abs()) + (p.abs() + q1.abs())) + ((q2.abs() + q.abs()) + v.abs());
        v
    };
    let mut lanes = [[0.0f64; 5]; LANES];
    let (mut xs, mut ys) = (x.l.chunks_exact(LANES), y.l.chunks_exact(LANES));
    let (mut zs, mut ws) = (z.l.chunks_exact(LANES), w.l.chunks_exact(LANES));
    let mut ls = l.chunks_exact_mut(LANES);
    for ((((o, xv), yv), zv), wv) in (&mut ls)
        .zip(&mut xs)
        .zip(&mut ys)
        .zip(&mut zs)
        .zip(&mut ws)
    {
        for (lane, acc) in lanes.iter_mut().enumerate() {
            o[lane] = step(xv[lane], yv[lane], zv[lane], wv[lane], acc);
        }
    }
    let tails = (
        xs.remainder(),
        ys.remainder(),
        zs.remainder(),
        ws.remainder(),
    );
    for (i, o) in ls.into_remainder().iter_mut().enumerate() {
        *o = step(
            tails.0[i],
            tails.1[i],
            tails.2[i],
            tails.3[i],
            &mut lanes[0],
        );
    }
    let [rx, ry, rz, rw, mag] = lane_totals(&lanes);
    let k = l.len();
    let rad = |s: f64, f: &Af| up(sum_upper(s, k) + f.e);
    let second = up(up(rad(rx, x) * rad(ry, y)) + up(rad(rz, z) * rad(rw, w)));
    let first = up(up(up(x.c.abs() * y.e) + up(y.c.abs() * x.e))
        + up(up(z.c.abs() * w.e) + up(w.c.abs() * z.e)));
    let rounding = up(up(up(err(p0) + err(q0)) + err(c)) + err_sum(mag, 7 * k));
    Af {
        c,
        l,
        e: up(up(first + second) + rounding),
    }
}

/// An affine form over `s` shared noise symbols.
#[derive(Debug, PartialEq)]
pub struct Af {
    /// Central value.
    pub c: f64,
    /// Coefficients of the noise symbols.
    pub l: Coeffs,
    /// Remainder radius (an upper bound).
    pub e: f64,
}

impl Clone for Af {
    /// A copy (the coefficients copied as one block, not one by one as
    /// `SmallVec`'s own `clone` does).
    fn clone(&self) -> Af {
        Af {
            c: self.c,
            l: Coeffs::from_slice(&self.l),
            e: self.e,
        }
    }
}

impl Af {
    /// The exact constant `x` over `s` symbols.
    pub fn constant(x: f64, s: usize) -> Af {
        Af {
            c: x,
            l: Coeffs::from_elem(0.0, s),
            e: 0.0,
        }
    }

    /// The interval `x` as a form without symbols (midpoint and radius).
    pub fn from_iv(x: Iv, s: usize) -> Af {
        let (m, r) = x.mid_rad();
        Af {
            c: m,
            l: Coeffs::from_elem(0.0, s),
            e: r,
        }
    }

    /// `x0 + h eps_k` (the parameter `k` of a cell with centre `x0` and
    /// half-width `h`).
    pub fn symbol(x0: f64, h: f64, k: usize, s: usize) -> Af {
        let mut l = Coeffs::from_elem(0.0, s);
        l[k] = h;
        Af { c: x0, l, e: 0.0 }
    }

    /// The same form over `s >= self.symbols()` symbols, the new ones with
    /// coefficient zero (exact).
    pub fn extended(mut self, s: usize) -> Af {
        if s > self.l.len() {
            self.l.resize(s, 0.0);
        }
        self
    }

    /// Number of symbols.
    pub fn symbols(&self) -> usize {
        self.l.len()
    }

    /// `sum |x_i| + e`, rounded up: the radius of the form around `c` (the
    /// float sum of the magnitudes bounded by [`sum_upper`]).
    pub fn radius(&self) -> f64 {
        let s: f64 = self.l.iter().map(|x| x.abs()).sum();
        up(sum_upper(s, self.l.len()) + self.e)
    }

    /// The range as an interval (rounded outward).
    pub fn range(&self) -> Iv {
        let r = self.radius();
        Iv::new(down(self.c - r), up(self.c + r))
    }

    /// Sum.
    pub fn add(&self, o: &Af) -> Af {
        assert_eq!(self.l.len(), o.l.len(), "forms over different symbols");
        let c = self.c + o.c;
        let mut l = Coeffs::from_slice(&self.l);
        let [mag] = zip_lanes(&mut l, &o.l, |x, y, acc: &mut [f64; 1]| {
            let v = x + y;
            acc[0] += v.abs();
            v
        });
        let e = up(up(up(self.e + o.e) + err(c)) + err_sum(mag, l.len()));
        Af { c, l, e }
    }

    /// Difference.
    pub fn sub(&self, o: &Af) -> Af {
        assert_eq!(self.l.len(), o.l.len(), "forms over different symbols");
        let c = self.c - o.c;
        let mut l = Coeffs::from_slice(&self.l);
        let [mag] = zip_lanes(&mut l, &o.l, |x, y, acc: &mut [f64; 1]| {
            let v = x - y;
            acc[0] += v.abs();
            v
        });
        let e = up(up(up(self.e + o.e) + err(c)) + err_sum(mag, l.len()));
        Af { c, l, e }
    }

    /// Negation (exact).
    pub fn neg(&self) -> Af {
        let mut l = Coeffs::from_slice(&self.l);
        for x in l.iter_mut() {
            *x = -*x;
        }
        Af {
            c: -self.c,
            l,
            e: self.e,
        }
    }

    /// Product with the float `s`.
    pub fn scale(&self, s: f64) -> Af {
        let c = self.c * s;
        let mut l = Coeffs::from_slice(&self.l);
        let mut mag = 0.0;
        for x in l.iter_mut() {
            *x *= s;
            mag += x.abs();
        }
        let e = up(up(up(self.e * s.abs()) + err(c)) + err_sum(mag, l.len()));
        Af { c, l, e }
    }

    /// Product: `x y = x_0 y_0 + sum_i (x_0 y_i + y_0 x_i) eps_i` plus
    /// `|x_0| e_y + |y_0| e_x + (sum |x_i| + e_x)(sum |y_i| + e_y)` (the
    /// second-order part) and the rounding of every float operation, in
    /// one pass over the coefficients (the radii summed on the way).
    pub fn mul(&self, o: &Af) -> Af {
        assert_eq!(self.l.len(), o.l.len(), "forms over different symbols");
        let c = self.c * o.c;
        let mut l = Coeffs::from_slice(&self.l);
        let (xc, yc) = (self.c, o.c);
        // the rounding of c_x y_i, c_y x_i and their sum, per coefficient
        let [rx, ry, mag] = zip_lanes(&mut l, &o.l, |x, y, acc: &mut [f64; 3]| {
            acc[0] += x.abs();
            acc[1] += y.abs();
            let p = xc * y;
            let q = yc * x;
            let v = p + q;
            acc[2] += (p.abs() + q.abs()) + v.abs();
            v
        });
        let k = l.len();
        let rx = up(sum_upper(rx, k) + self.e);
        let ry = up(sum_upper(ry, k) + o.e);
        let mut e = up(up(up(self.c.abs() * o.e) + up(o.c.abs() * self.e)) + err(c));
        e = up(e + up(rx * ry));
        let e = up(e + err_sum(mag, 3 * k));
        Af { c, l, e }
    }

    /// `self + w y` in place for a float `w`: the coefficients
    /// `x_i + w y_i`, the remainder `e_x + |w| e_y` and the rounding of the
    /// `2 (k + 1)` float operations (one pass, no new form).
    pub fn add_scaled(&mut self, w: f64, y: &Af) {
        assert_eq!(self.l.len(), y.l.len(), "forms over different symbols");
        let t0 = w * y.c;
        let c = self.c + t0;
        let [mag] = zip_lanes(&mut self.l, &y.l, |x, yi, acc: &mut [f64; 1]| {
            let t = w * yi;
            let v = x + t;
            acc[0] += t.abs() + v.abs();
            v
        });
        let e = up(up(self.e + up(w.abs() * y.e)) + up(err(t0) + err(c)));
        self.e = up(e + err_sum(mag, 2 * self.l.len()));
        self.c = c;
    }

    /// Product with an interval `x = m + r [-1, 1]`: `m self` plus
    /// `r (|c| + radius)`, the bound [`Af::mul`] gives for the form of `x`
    /// without symbols, without building that form.
    pub fn mul_iv(&self, x: Iv) -> Af {
        let (m, r) = x.mid_rad();
        let out = self.scale(m);
        let extra = up(r * up(self.c.abs() + self.radius()));
        out.widen(extra)
    }

    /// The form widened by `r >= 0`.
    pub fn widen(&self, r: f64) -> Af {
        let mut out = self.clone();
        out.e = up(out.e + r);
        out
    }

    /// The form with its remainder turned into the symbol `k`, which no
    /// form has used so far: `x = c + sum_i x_i eps_i + e eps_k` with
    /// `eps_k = (x - c - sum_i x_i eps_i) / e in [-1, 1]`, a function of the
    /// cell's parameters like every symbol after the ratios (math doc
    /// section 15, "Named remainders"). The range is unchanged (up to the
    /// last bits of the rounded-up radius, [`sum_upper`]); what changes
    /// is that every later form computed from `x` carries the same `eps_k`,
    /// so differences of such forms cancel it to first order instead of
    /// adding two remainders. Exact (no rounding): the float `e` moves.
    ///
    /// ```
    /// use subdiv_lab::verify::charmap::af::Af;
    /// let x = Af::symbol(0.5, 0.1, 0, 3).mul(&Af::symbol(0.2, 0.1, 1, 3));
    /// let named = x.name_remainder(2);
    /// let (a, b) = (named.range(), x.range());
    /// assert!((a.lo - b.lo).abs() < 1e-15 && (a.hi - b.hi).abs() < 1e-15);
    /// // a difference of two forms sharing the named remainder cancels it
    /// let d = named.scale(1.001).sub(&named);
    /// assert!(d.radius() < 1e-4 && x.scale(1.001).sub(&x).radius() > 1e-2);
    /// ```
    pub fn name_remainder(&self, k: usize) -> Af {
        let mut out = self.clone();
        assert!(out.l[k] == 0.0, "symbol {k} is taken");
        out.l[k] = self.e;
        out.e = 0.0;
        out
    }

    /// `f(x)` for a differentiable `f` by the mean-value form: `fx0`
    /// encloses `f(c)` and `dfx` encloses `f'` on the range of `x`, so
    /// `f(x) = f(c) + f'(xi) (x - c)` lies in
    /// `mid(fx0) + mid(dfx) (x - c) + [rad(fx0) + rad(dfx) |x - c|]`.
    pub fn mean_value(&self, fx0: Iv, dfx: Iv) -> Af {
        let (f0, fr) = fx0.mid_rad();
        let (d, dr) = dfx.mid_rad();
        let mut dev = self.clone();
        dev.c = 0.0;
        let mut out = dev.scale(d);
        out.c = f0;
        out.e = up(up(out.e + fr) + up(dr * self.radius()));
        out
    }
}

/// An enclosure of the solutions `x(eps) = M(eps)^{-1} b(eps)` of a linear
/// system whose matrix `m` (row-major `k x k`) and right-hand sides `bs`
/// are affine forms, for every value of the symbols; `None` when it fails.
///
/// A first-order guess `x~ = x_0 + sum_t x_t eps_t` (floats:
/// `x_0 = R b_0`, `x_t = R (b_t - M_t x_0)` with `R ~ M_0^{-1}`) is
/// corrected rigorously: the residual `rho = b - M x~` is evaluated as a
/// form, `z = R rho` and `C = I - R M` are enclosed, and if
/// `beta = ||C||_inf < 1/2` the error `y = x - x~` satisfies `y = z + C y`,
/// so `||y||_inf <= ||z||_inf / (1 - beta)` and
/// `|y_i| <= |z_i| + (sum_j |C_ij|) ||y||_inf`, which is added to the remainder.
pub fn solve(m: &[Af], bs: &[Vec<Af>], k: usize) -> Option<Vec<Vec<Af>>> {
    let s = m.first()?.symbols();
    let m0 = nalgebra::DMatrix::from_fn(k, k, |i, j| m[i * k + j].c);
    let r = m0.try_inverse()?;
    // C = I - R M, row sums of its magnitude
    let mut crow = vec![0.0f64; k];
    for (i, cr) in crow.iter_mut().enumerate() {
        for j in 0..k {
            let mut acc = Af::constant(if i == j { 1.0 } else { 0.0 }, s);
            for l in 0..k {
                acc.add_scaled(-r[(i, l)], &m[l * k + j]);
            }
            *cr = up(*cr + acc.range().mag());
        }
    }
    let beta = crow.iter().copied().fold(0.0f64, f64::max);
    if !(beta < 0.5) {
        return None;
    }
    let one_minus = Iv::point(1.0).sub(Iv::point(beta)).lo;
    let mut out = Vec::with_capacity(bs.len());
    for b in bs {
        if b.len() != k {
            return None;
        }
        let b0: Vec<f64> = b.iter().map(|x| x.c).collect();
        let x0: Vec<f64> = (0..k)
            .map(|i| (0..k).map(|j| r[(i, j)] * b0[j]).sum())
            .collect();
        let mut guess: Vec<Af> = x0.iter().map(|&v| Af::constant(v, s)).collect();
        for t in 0..s {
            let rhs: Vec<f64> = (0..k)
                .map(|i| b[i].l[t] - (0..k).map(|j| m[i * k + j].l[t] * x0[j]).sum::<f64>())
                .collect();
            for (i, g) in guess.iter_mut().enumerate() {
                g.l[t] = (0..k).map(|j| r[(i, j)] * rhs[j]).sum();
            }
        }
        let rho: Vec<Af> = (0..k)
            .map(|i| {
                let mut acc = b[i].clone();
                for j in 0..k {
                    acc.add_scaled(-1.0, &m[i * k + j].mul(&guess[j]));
                }
                acc
            })
            .collect();
        let z: Vec<Iv> = (0..k)
            .map(|i| {
                let mut acc = Af::constant(0.0, s);
                for j in 0..k {
                    acc.add_scaled(r[(i, j)], &rho[j]);
                }
                acc.range()
            })
            .collect();
        let zn = z.iter().fold(0.0f64, |a, v| a.max(v.mag()));
        let en = up(zn / one_minus);
        if !en.is_finite() {
            return None;
        }
        out.push(
            guess
                .into_iter()
                .zip(z.iter().zip(&crow))
                .map(|(g, (zi, ci))| g.widen(up(zi.mag() + up(ci * en))))
                .collect(),
        );
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(a: &Af, eps: &[f64]) -> f64 {
        a.c + a.l.iter().zip(eps).map(|(x, e)| x * e).sum::<f64>()
    }

    #[test]
    fn forms_contain_sampled_values() {
        let x = Af::symbol(0.3, 0.01, 0, 2);
        let y = Af::symbol(-1.2, 0.05, 1, 2);
        let f = x.mul(&y).sub(&x.scale(3.0)).add(&y.mul(&y));
        let g = x.mean_value(
            Iv::new(
                (0.3f64).sqrt() * (1.0 - 1e-15),
                (0.3f64).sqrt() * (1.0 + 1e-15),
            ),
            Iv::new(0.5 / (0.31f64).sqrt(), 0.5 / (0.29f64).sqrt()),
        );
        for k in 0..=20 {
            for j in 0..=20 {
                let (e0, e1) = (-1.0 + 0.1 * k as f64, -1.0 + 0.1 * j as f64);
                let (xv, yv) = (0.3 + 0.01 * e0, -1.2 + 0.05 * e1);
                let fv = xv * yv - 3.0 * xv + yv * yv;
                let r = f.range();
                assert!(r.lo <= fv && fv <= r.hi);
                assert!((fv - eval(&f, &[e0, e1])).abs() <= f.e);
                let gv = xv.sqrt();
                assert!((gv - eval(&g, &[e0, e1])).abs() <= g.e);
            }
        }
        // first-order cancellation: x - x is exactly zero up to rounding
        assert!(x.sub(&x).radius() < 1e-300);
    }

    /// The fused determinant and the in-place `x + w y` against sampled
    /// values of their operands (their remainders must cover the second
    /// order and the rounding).
    #[test]
    fn det_and_add_scaled_contain_sampled_values() {
        let s = 3;
        let a = [
            Af::symbol(0.3, 0.05, 0, s).add(&Af::symbol(0.0, 0.02, 2, s)),
            Af::symbol(-1.2, 0.04, 1, s),
        ];
        let b = [
            Af::symbol(0.7, -0.03, 1, s),
            Af::symbol(0.9, 0.06, 0, s).add(&Af::symbol(0.0, -0.01, 2, s)),
        ];
        let d = det(&a, &b);
        let mut acc = a[0].clone();
        acc.add_scaled(-2.5, &b[1]);
        // every value in rationals, so that the comparisons carry no rounding
        // of their own: the forms' remainders alone must cover the gap
        use num_rational::BigRational;
        use num_traits::Signed as _;
        let q = |x: f64| BigRational::from_float(x).expect("finite");
        for k in 0..=10 {
            for j in 0..=10 {
                for t in [-1.0, 1.0] {
                    let eps = [-1.0 + 0.2 * k as f64, -1.0 + 0.2 * j as f64, t];
                    let v = |f: &Af| {
                        f.l.iter()
                            .zip(&eps)
                            .fold(q(f.c), |acc, (x, e)| acc + q(*x) * q(*e))
                    };
                    let exact = v(&a[0]) * v(&b[1]) - v(&a[1]) * v(&b[0]);
                    assert!((exact - v(&d)).abs() <= q(d.e), "{eps:?}");
                    let lin = v(&a[0]) - q(2.5) * v(&b[1]);
                    assert!((lin - v(&acc)).abs() <= q(acc.e), "{eps:?}");
                }
            }
        }
        // the second-order part is in the remainder: without it the
        // corners of the box fall outside
        assert!(d.e > 0.05 * 0.06 && d.radius() < 0.5);
    }

    /// The coefficient loops run in [`LANES`] lanes with a scalar tail:
    /// for every length (below, at and above a lane multiple, and past the
    /// inline capacity) the coefficients are the scalar formulas', and the
    /// remainders of `mul` and `det` are attained at the corner
    /// `eps = (1, .., 1)` by forms whose coefficients share their signs, so a
    /// lane or tail left out of a magnitude sum is caught.
    #[test]
    fn lane_loops_match_the_scalar_formulas_and_attain_their_bounds() {
        use num_rational::BigRational;
        use num_traits::Signed as _;
        let q = |x: f64| BigRational::from_float(x).expect("finite");
        let mut rng = crate::rng::SplitMix64::new(11);
        for k in [1usize, 3, 4, 5, 8, 11, 64, 70] {
            let mut form = |c: f64, sign: f64| Af {
                c,
                l: (0..k).map(|_| sign * rng.uniform(0.01, 0.1)).collect(),
                e: 0.0,
            };
            let (x, y, z, w) = (
                form(0.7, 1.0),
                form(-0.4, 1.0),
                form(0.2, 1.0),
                form(0.5, -1.0),
            );
            let at_one = |f: &Af| f.l.iter().fold(q(f.c), |acc, v| acc + q(*v));
            let m = x.mul(&y);
            let d = det(&[x.clone(), z.clone()], &[w.clone(), y.clone()]);
            let (sum, diff) = (x.add(&y), x.sub(&y));
            let mut acc = x.clone();
            acc.add_scaled(-1.5, &z);
            for i in 0..k {
                assert_eq!(m.l[i], x.c * y.l[i] + y.c * x.l[i], "mul k={k} i={i}");
                let (p, r) = (x.c * y.l[i] + y.c * x.l[i], z.c * w.l[i] + w.c * z.l[i]);
                assert_eq!(d.l[i], p - r, "det k={k} i={i}");
                assert_eq!(sum.l[i], x.l[i] + y.l[i], "add k={k} i={i}");
                assert_eq!(diff.l[i], x.l[i] - y.l[i], "sub k={k} i={i}");
                assert_eq!(acc.l[i], x.l[i] + -1.5 * z.l[i], "add_scaled k={k} i={i}");
            }
            let exact_m = at_one(&x) * at_one(&y);
            let exact_d = at_one(&x) * at_one(&y) - at_one(&z) * at_one(&w);
            for (exact, f, what) in [(exact_m, &m, "mul"), (exact_d, &d, "det")] {
                let gap = (exact - at_one(f)).abs();
                assert!(gap <= q(f.e), "{what} k={k}: remainder too small");
                // the bound is attained up to the rounding terms
                assert!(q(f.e) - gap < q(1e-12), "{what} k={k}: not attained");
            }
        }
    }

    #[test]
    fn affine_solve_contains_the_solutions() {
        // M(eps) = [[2 + 0.1 e0, 0.3], [0.2 e1, 1 - 0.05 e0]], b = [1 + 0.2 e1, -0.5]
        let s = 2;
        let m = vec![
            Af::symbol(2.0, 0.1, 0, s),
            Af::constant(0.3, s),
            Af::symbol(0.0, 0.2, 1, s),
            Af::symbol(1.0, -0.05, 0, s),
        ];
        let b = vec![Af::symbol(1.0, 0.2, 1, s), Af::constant(-0.5, s)];
        let x = solve(&m, &[b], 2).unwrap().pop().unwrap();
        for k in 0..=10 {
            for j in 0..=10 {
                let (e0, e1) = (-1.0 + 0.2 * k as f64, -1.0 + 0.2 * j as f64);
                let mm = nalgebra::Matrix2::new(2.0 + 0.1 * e0, 0.3, 0.2 * e1, 1.0 - 0.05 * e0);
                let xv = mm.try_inverse().unwrap() * nalgebra::Vector2::new(1.0 + 0.2 * e1, -0.5);
                for i in 0..2 {
                    assert!(
                        (xv[i] - eval(&x[i], &[e0, e1])).abs() <= x[i].e,
                        "{k} {j} {i}"
                    );
                }
            }
        }
        // first order exact: the remainder is second order
        assert!(x[0].e < 0.1 && x[1].e < 0.1, "{:?}", x);
    }
}
