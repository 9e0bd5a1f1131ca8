//! Second-order Taylor forms with a rigorous remainder, over a cell (math
//! doc section 15, "Taylor forms").
//!
//! A quantity `q(x)` for `x` in a cell `[x0 - h, x0 + h]` is enclosed as
//!
//! ```text
//! q(x0 + d)  in  c + sum_k g_k d_k + sum_{j <= k} q_jk d_j d_k + [-rem, rem],   |d_k| <= h_k,
//! ```
//!
//! with `c`, `g_k`, `q_jk` intervals and `rem >= 0`: for every `d` there are
//! reals in those intervals that make the statement exact up to `rem`. A
//! polynomial of degree two in the parameters (the 2 x 2 route's
//! discriminant, determinant and `p(z)`) is represented with `rem = 0`, so
//! the cancellation between the parameters is kept to second order; the
//! natural interval extension of a product loses it at first order, a
//! first-order form at second order. Products follow
//!
//! ```text
//! (c1 + l1 + s1 + e1)(c2 + l2 + s2 + e2) = c1 c2 + (c1 l2 + c2 l1) + (c1 s2 + c2 s1 + l1 l2) + [rest],
//! rest <= L1 B2 + L2 B1 + B1 B2 + e1 (|c2| + L2 + B2) + e2 (|c1| + L1 + B1) + e1 e2,
//! ```
//!
//! with `l`, `s` the linear and quadratic parts, `L = sum |g_k| h_k` and
//! `B = sum_{j <= k} |q_jk| h_j h_k` their bounds. Every bound is rounded
//! outward ([`super::interval`]).

use super::interval::{down, up, Iv};

/// Slack of the straddle test of [`Taylor::scores`]: a cell whose linear
/// part reaches the zero set up to this relative margin is treated as
/// straddling it (cells that touch it at a face or corner, where the ranges
/// are tight, cannot be decided either). A heuristic constant: it only
/// steers the split choice.
pub const STRADDLE_SLACK: f64 = 1.0 + 1.0 / 1024.0;

/// Index of `q_jk`, `j <= k`, in the packed upper triangle.
#[inline]
fn tri(j: usize, k: usize) -> usize {
    k * (k + 1) / 2 + j
}

/// A Taylor form over a cell with half-widths `h` (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Taylor {
    /// The value at the centre (an interval: rounding).
    pub c: Iv,
    /// The gradient, one interval per parameter.
    pub g: Vec<Iv>,
    /// The quadratic part, `q_jk` (`j <= k`) at `k (k + 1) / 2 + j`.
    pub q: Vec<Iv>,
    /// The remainder bound (`>= 0`).
    pub rem: f64,
}

/// Lower bound of `a d + b d^2` over `|d| <= h`, every `a` in `a`, `b` in `b`.
fn lower_1d(a: Iv, b: Iv, h: f64) -> f64 {
    let am = a.mag();
    if b.lo > 0.0 {
        // the minimum of a d + b d^2 is -a^2 / (4 b) at d = -a / (2 b) when that
        // lies in the cell, else -|a| h + b h^2; both decrease with |a|
        let two_bh = down(down(2.0 * b.lo) * h);
        if am <= two_bh {
            -up(up(am * am) / down(4.0 * b.lo))
        } else {
            down(-up(am * h) + down(down(b.lo * h) * h))
        }
    } else {
        down(-up(am * h) - up(up(-b.lo * h) * h))
    }
}

impl Taylor {
    /// The affine form `c + sum_k g_k d_k` with exact float coefficients.
    pub fn affine(c: Iv, g: &[f64]) -> Self {
        let k = g.len();
        Taylor {
            c,
            g: g.iter().map(|&v| Iv::point(v)).collect(),
            q: vec![Iv::point(0.0); k * (k + 1) / 2],
            rem: 0.0,
        }
    }

    /// A constant (exact float).
    pub fn constant(v: f64, k: usize) -> Self {
        Taylor {
            c: Iv::point(v),
            g: vec![Iv::point(0.0); k],
            q: vec![Iv::point(0.0); k * (k + 1) / 2],
            rem: 0.0,
        }
    }

    /// A form from its parts (`q` packed as in [`Taylor::q`]); `rem >= 0`.
    pub fn from_parts(c: Iv, g: Vec<Iv>, q: Vec<Iv>, rem: f64) -> Self {
        debug_assert_eq!(q.len(), g.len() * (g.len() + 1) / 2);
        Taylor { c, g, q, rem }
    }

    /// Number of parameters.
    pub fn params(&self) -> usize {
        self.g.len()
    }

    /// The coefficient interval of `d_j d_k` (`j <= k`).
    pub fn quad(&self, j: usize, k: usize) -> Iv {
        self.q[tri(j.min(k), j.max(k))]
    }

    /// `sum_k |g_k| h_k`, rounded up.
    pub fn linear_bound(&self, h: &[f64]) -> f64 {
        self.g.iter().zip(h).fold(0.0, |s, (g, &hk)| {
            up(s + Iv::point(g.mag()).mul(Iv::point(hk)).hi)
        })
    }

    /// `sum_{j <= k} |q_jk| h_j h_k`, rounded up.
    pub fn quadratic_bound(&self, h: &[f64]) -> f64 {
        let mut s = 0.0;
        for k in 0..h.len() {
            for j in 0..=k {
                let v = self.q[tri(j, k)].mag();
                if v != 0.0 {
                    s = up(s + up(up(v * h[j]) * h[k]));
                }
            }
        }
        s
    }

    /// An interval containing `q(x)` for every `x` of the cell: the centre
    /// value, each parameter's `g_k d_k + q_kk d_k^2` bounded on its own
    /// (a square is never negative), the cross terms and the remainder by
    /// their magnitudes.
    ///
    /// ```
    /// use subdiv_lab::verify::taylor2::Taylor;
    /// use subdiv_lab::verify::interval::Iv;
    /// // q(x) = (x0 + x1)(x0 - x1) around (0.5, 0.25) with h = (0.1, 0.1)
    /// let h = [0.1, 0.1];
    /// let a = Taylor::affine(Iv::point(0.75), &[1.0, 1.0]);
    /// let b = Taylor::affine(Iv::point(0.25), &[1.0, -1.0]);
    /// let q = a.mul(&b, &h);
    /// let r = q.range(&h);
    /// // the exact range of x0^2 - x1^2 over the cell is [0.16 - 0.1225, 0.36 - 0.0225]
    /// assert!(r.lo <= 0.0375 && r.hi >= 0.3375);
    /// assert!(r.lo > 0.0 && r.hi < 0.36);
    /// ```
    pub fn range(&self, h: &[f64]) -> Iv {
        let mut lo = self.c.lo;
        let mut hi = self.c.hi;
        let mut cross = self.rem;
        for k in 0..h.len() {
            let a = self.g[k];
            let b = self.q[tri(k, k)];
            lo = down(lo + lower_1d(a, b, h[k]));
            hi = up(hi - lower_1d(a.neg(), b.neg(), h[k]));
            for j in 0..k {
                let v = self.q[tri(j, k)].mag();
                if v != 0.0 {
                    cross = up(cross + up(up(v * h[j]) * h[k]));
                }
            }
        }
        Iv::new(down(lo - cross), up(hi + cross))
    }

    /// An interval containing `q(x0 + d)` at one offset `d` with
    /// `|d_k| <= h_k` (the form evaluated there, plus the remainder).
    #[allow(clippy::needless_range_loop)] // packed triangle indices
    pub fn eval_at(&self, d: &[f64]) -> Iv {
        let mut v = self.c;
        for (k, dk) in d.iter().enumerate() {
            let dk = Iv::point(*dk);
            v = v.add(self.g[k].mul(dk));
            for j in 0..=k {
                v = v.add(self.q[tri(j, k)].mul(Iv::point(d[j])).mul(dk));
            }
        }
        v.widen(self.rem)
    }

    /// Sum.
    #[allow(clippy::should_implement_trait)]
    pub fn add(&self, o: &Taylor) -> Taylor {
        Taylor {
            c: self.c.add(o.c),
            g: self.g.iter().zip(&o.g).map(|(a, b)| a.add(*b)).collect(),
            q: self.q.iter().zip(&o.q).map(|(a, b)| a.add(*b)).collect(),
            rem: up(self.rem + o.rem),
        }
    }

    /// Difference.
    #[allow(clippy::should_implement_trait)]
    pub fn sub(&self, o: &Taylor) -> Taylor {
        Taylor {
            c: self.c.sub(o.c),
            g: self.g.iter().zip(&o.g).map(|(a, b)| a.sub(*b)).collect(),
            q: self.q.iter().zip(&o.q).map(|(a, b)| a.sub(*b)).collect(),
            rem: up(self.rem + o.rem),
        }
    }

    /// Product with an exact float.
    pub fn scale(&self, s: f64) -> Taylor {
        let s_iv = Iv::point(s);
        Taylor {
            c: self.c.mul(s_iv),
            g: self.g.iter().map(|a| a.mul(s_iv)).collect(),
            q: self.q.iter().map(|a| a.mul(s_iv)).collect(),
            rem: Iv::point(self.rem).mul(Iv::point(s.abs())).hi,
        }
    }

    /// The form plus an interval constant.
    pub fn add_interval(&self, v: Iv) -> Taylor {
        Taylor {
            c: self.c.add(v),
            ..self.clone()
        }
    }

    /// Product over the cell of half-widths `h` (module docs).
    pub fn mul(&self, o: &Taylor, h: &[f64]) -> Taylor {
        let k = self.g.len();
        let (l1, l2) = (self.linear_bound(h), o.linear_bound(h));
        let (b1, b2) = (self.quadratic_bound(h), o.quadratic_bound(h));
        let (e1, e2) = (self.rem, o.rem);
        let mag = |x: f64, y: f64| Iv::point(x).mul(Iv::point(y)).hi;
        let t1 = up(up(mag(l1, b2) + mag(l2, b1)) + mag(b1, b2));
        let t2 = mag(e1, up(up(o.c.mag() + l2) + b2));
        let t3 = mag(e2, up(up(self.c.mag() + l1) + b1));
        let rem = up(up(up(t1 + t2) + t3) + mag(e1, e2));
        let g: Vec<Iv> = (0..k)
            .map(|i| self.c.mul(o.g[i]).add(o.c.mul(self.g[i])))
            .collect();
        let mut q = Vec::with_capacity(self.q.len());
        for kk in 0..k {
            for j in 0..=kk {
                let t = tri(j, kk);
                let mut v = self.c.mul(o.q[t]).add(o.c.mul(self.q[t]));
                v = v.add(self.g[j].mul(o.g[kk]));
                if j != kk {
                    v = v.add(self.g[kk].mul(o.g[j]));
                }
                q.push(v);
            }
        }
        Taylor {
            c: self.c.mul(o.c),
            g,
            q,
            rem,
        }
    }

    /// Per-parameter share of the uncertainty, used to choose the split
    /// coordinate (a heuristic; it never affects soundness).
    ///
    /// When the linear part outweighs the centre value and the higher
    /// terms, `|c| + B + rem <= sum |g_k| h_k` (in floating point, with
    /// [`STRADDLE_SLACK`]), the quantity very likely changes sign inside the
    /// cell or on its boundary: the cell straddles its zero set and no
    /// subdivision decides it as a whole. Then the shares are the gradient
    /// terms `|g_k| h_k` alone, so only the sides across the zero set are cut
    /// (math doc section 15, "split and stop rule"). Otherwise each side gets
    /// `|g_k| h_k`, the quadratic terms it takes part in,
    /// `sum_j |q_jk| h_j h_k`, and the remainder spread in proportion to `h_k`.
    pub fn scores(&self, h: &[f64]) -> Vec<f64> {
        let lin: Vec<f64> = self.g.iter().zip(h).map(|(g, &hk)| g.mag() * hk).collect();
        let centre = 0.5 * self.c.lo + 0.5 * self.c.hi;
        let b = self.quadratic_bound(h);
        if centre.abs() + b + self.rem <= STRADDLE_SLACK * lin.iter().sum::<f64>() {
            return lin;
        }
        let total: f64 = h.iter().sum();
        (0..h.len())
            .map(|k| {
                let quad: f64 = (0..h.len())
                    .map(|j| self.quad(j, k).mag() * h[j] * h[k])
                    .sum();
                let share = if total > 0.0 { h[k] / total } else { 0.0 };
                lin[k] + quad + self.rem * share
            })
            .collect()
    }
}
