//! First-order Taylor forms with a rigorous second-order remainder, over a
//! cell (math doc section 15, "closed 2 x 2 route").
//!
//! A quantity `q(x)` for `x` in a cell `[x0 - h, x0 + h]` is enclosed as
//!
//! ```text
//! q(x0 + d)  in  c + sum_k g_k d_k + [-rem, rem],      |d_k| <= h_k,
//! ```
//!
//! with `c` and `g_k` intervals and `rem >= 0`. The range of the linear part
//! is exactly `[-sum |g_k| h_k, sum |g_k| h_k]` (up to the widths of the
//! `g_k`), so cancellation between the parameters is kept to first order;
//! the natural interval extension of a product of two affine entries loses
//! it. Products follow
//!
//! ```text
//! (c1 + l1 + e1)(c2 + l2 + e2) = c1 c2 + (c1 l2 + c2 l1)
//!                              + [c1 e2 + c2 e1 + (l1 + e1)(l2 + e2)],
//! rem = |c1| rem2 + |c2| rem1 + (L1 + rem1)(L2 + rem2),   L = sum |g_k| h_k.
//! ```
//!
//! Every bound is rounded outward ([`super::interval`]).

use super::interval::{up, Iv};

/// A Taylor form over a cell with half-widths `h` (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Taylor {
    /// The value at the centre (an interval: rounding).
    pub c: Iv,
    /// The gradient, one interval per parameter.
    pub g: Vec<Iv>,
    /// The remainder bound (`>= 0`).
    pub rem: f64,
}

impl Taylor {
    /// The affine form `c + sum_k g_k d_k` with exact float coefficients.
    pub fn affine(c: Iv, g: &[f64]) -> Self {
        Taylor {
            c,
            g: g.iter().map(|&v| Iv::point(v)).collect(),
            rem: 0.0,
        }
    }

    /// A constant (exact float).
    pub fn constant(v: f64, k: usize) -> Self {
        Taylor {
            c: Iv::point(v),
            g: vec![Iv::point(0.0); k],
            rem: 0.0,
        }
    }

    /// `sum_k |g_k| h_k`, rounded up.
    pub fn linear_bound(&self, h: &[f64]) -> f64 {
        self.g.iter().zip(h).fold(0.0, |s, (g, &hk)| {
            up(s + Iv::point(g.mag()).mul(Iv::point(hk)).hi)
        })
    }

    /// An interval containing `q(x)` for every `x` of the cell.
    ///
    /// ```
    /// use subdiv_lab::verify::taylor::Taylor;
    /// use subdiv_lab::verify::interval::Iv;
    /// // q(x) = (x0 + x1)(x0 - x1) around (0.5, 0.25) with h = (0.1, 0.1)
    /// let h = [0.1, 0.1];
    /// let a = Taylor::affine(Iv::point(0.75), &[1.0, 1.0]);
    /// let b = Taylor::affine(Iv::point(0.25), &[1.0, -1.0]);
    /// let q = a.mul(&b, &h);
    /// let r = q.range(&h);
    /// // the exact range of x0^2 - x1^2 over the cell is [0.16 - 0.1225, 0.36 - 0.0225]
    /// assert!(r.lo <= 0.0375 && r.hi >= 0.3375);
    /// assert!(r.lo > -0.05 && r.hi < 0.45);
    /// ```
    pub fn range(&self, h: &[f64]) -> Iv {
        let r = up(self.linear_bound(h) + self.rem);
        self.c.widen(r)
    }

    /// Sum.
    #[allow(clippy::should_implement_trait)]
    pub fn add(&self, o: &Taylor) -> Taylor {
        Taylor {
            c: self.c.add(o.c),
            g: self.g.iter().zip(&o.g).map(|(a, b)| a.add(*b)).collect(),
            rem: up(self.rem + o.rem),
        }
    }

    /// Difference.
    #[allow(clippy::should_implement_trait)]
    pub fn sub(&self, o: &Taylor) -> Taylor {
        Taylor {
            c: self.c.sub(o.c),
            g: self.g.iter().zip(&o.g).map(|(a, b)| a.sub(*b)).collect(),
            rem: up(self.rem + o.rem),
        }
    }

    /// Product with an exact float.
    pub fn scale(&self, s: f64) -> Taylor {
        let s_iv = Iv::point(s);
        Taylor {
            c: self.c.mul(s_iv),
            g: self.g.iter().map(|a| a.mul(s_iv)).collect(),
            rem: Iv::point(self.rem).mul(Iv::point(s.abs())).hi,
        }
    }

    /// Product over the cell of half-widths `h` (module docs).
    pub fn mul(&self, o: &Taylor, h: &[f64]) -> Taylor {
        let l1 = up(self.linear_bound(h) + self.rem);
        let l2 = up(o.linear_bound(h) + o.rem);
        let mag = |x: f64, y: f64| Iv::point(x).mul(Iv::point(y)).hi;
        let rem = up(up(mag(self.c.mag(), o.rem) + mag(o.c.mag(), self.rem)) + mag(l1, l2));
        Taylor {
            c: self.c.mul(o.c),
            g: self
                .g
                .iter()
                .zip(&o.g)
                .map(|(a, b)| self.c.mul(*b).add(o.c.mul(*a)))
                .collect(),
            rem,
        }
    }

    /// Per-parameter share of the uncertainty, used to choose the split
    /// coordinate: `|g_k| h_k` plus the remainder spread in proportion to
    /// `h_k` (a heuristic; it never affects soundness).
    pub fn scores(&self, h: &[f64]) -> Vec<f64> {
        let total: f64 = h.iter().sum();
        self.g
            .iter()
            .zip(h)
            .map(|(g, &hk)| {
                let share = if total > 0.0 { hk / total } else { 0.0 };
                g.mag() * hk + self.rem * share
            })
            .collect()
    }
}
