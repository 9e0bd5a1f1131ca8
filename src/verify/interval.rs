//! Real and complex intervals with outward rounding (math doc section 15).
//!
//! The rounding model: every `f64` operation of the hardware is
//! round-to-nearest, so its result is within half a unit in the last place
//! of the exact value (IEEE 754; also for subnormal results, where the
//! spacing is `2^-1074`). An interval operation computes each end point with
//! the ordinary operation and then moves it one representable number
//! outward ([`down`], [`up`]), which covers that half ulp. Round-to-nearest
//! is therefore never assumed to be exact. `NaN` end points make every
//! comparison false, so a certificate that meets one is simply not given.

/// The next representable `f64` above `x` (`+inf` stays; `NaN` stays).
///
/// Written out (rather than `f64::next_up`) for the crate's minimum Rust
/// version.
///
/// ```
/// use subdiv_lab::verify::interval::{down, up};
/// assert!(up(1.0) > 1.0 && down(1.0) < 1.0);
/// assert_eq!(up(0.0), f64::from_bits(1));
/// assert_eq!(down(up(0.25)), 0.25);
/// ```
pub fn up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    if x > 0.0 {
        f64::from_bits(b + 1)
    } else {
        f64::from_bits(b - 1)
    }
}

/// The next representable `f64` below `x` (`-inf` stays; `NaN` stays).
pub fn down(x: f64) -> f64 {
    -up(-x)
}

/// A closed real interval `[lo, hi]` whose end points were rounded outward.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iv {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Iv {
    /// The point interval `[x, x]` (exact: `x` is a float).
    pub const fn point(x: f64) -> Self {
        Iv { lo: x, hi: x }
    }

    /// `[lo, hi]` as given (the caller guarantees `lo <= hi`).
    pub const fn new(lo: f64, hi: f64) -> Self {
        Iv { lo, hi }
    }

    /// `[-r, r]`.
    pub fn symmetric(r: f64) -> Self {
        Iv { lo: -r, hi: r }
    }

    /// Sum, rounded outward.
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: Iv) -> Iv {
        Iv {
            lo: down(self.lo + o.lo),
            hi: up(self.hi + o.hi),
        }
    }

    /// Difference, rounded outward.
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, o: Iv) -> Iv {
        Iv {
            lo: down(self.lo - o.hi),
            hi: up(self.hi - o.lo),
        }
    }

    /// Product, rounded outward (the four end-point products).
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, o: Iv) -> Iv {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        let (mut lo, mut hi) = (p[0], p[0]);
        for &x in &p[1..] {
            // a NaN product poisons the result (min/max would drop it)
            if x.is_nan() {
                return Iv::new(f64::NAN, f64::NAN);
            }
            lo = lo.min(x);
            hi = hi.max(x);
        }
        if lo.is_nan() {
            return Iv::new(f64::NAN, f64::NAN);
        }
        Iv {
            lo: down(lo),
            hi: up(hi),
        }
    }

    /// Negation (exact).
    #[allow(clippy::should_implement_trait)]
    pub fn neg(self) -> Iv {
        Iv {
            lo: -self.hi,
            hi: -self.lo,
        }
    }

    /// `max |x|` over the interval (exact).
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// `min |x|` over the interval (exact; `0` when it holds `0`).
    ///
    /// ```
    /// use subdiv_lab::verify::interval::Iv;
    /// assert_eq!(Iv::new(-3.0, -2.0).mig(), 2.0);
    /// assert_eq!(Iv::new(-1.0, 2.0).mig(), 0.0);
    /// ```
    pub fn mig(self) -> f64 {
        if self.lo > 0.0 {
            self.lo
        } else if self.hi < 0.0 {
            -self.hi
        } else {
            0.0
        }
    }

    /// The interval widened by `r >= 0` on both sides (rounded outward).
    pub fn widen(self, r: f64) -> Iv {
        Iv {
            lo: down(self.lo - r),
            hi: up(self.hi + r),
        }
    }

    /// The float midpoint `m` and a radius `rad` with `[lo, hi] ⊂ [m - rad, m + rad]`.
    pub fn mid_rad(self) -> (f64, f64) {
        let m = 0.5 * self.lo + 0.5 * self.hi;
        let rad = up((self.hi - m).max(m - self.lo));
        (m, up(rad))
    }
}

/// A complex rectangle `re + i im` (both parts intervals).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ci {
    /// Real part.
    pub re: Iv,
    /// Imaginary part.
    pub im: Iv,
}

impl Ci {
    /// Zero.
    pub const ZERO: Ci = Ci {
        re: Iv::point(0.0),
        im: Iv::point(0.0),
    };

    /// The point `re + i im`.
    pub const fn point(re: f64, im: f64) -> Self {
        Ci {
            re: Iv::point(re),
            im: Iv::point(im),
        }
    }

    /// A real interval.
    pub const fn real(x: Iv) -> Self {
        Ci {
            re: x,
            im: Iv::point(0.0),
        }
    }

    /// Sum.
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: Ci) -> Ci {
        Ci {
            re: self.re.add(o.re),
            im: self.im.add(o.im),
        }
    }

    /// Difference.
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, o: Ci) -> Ci {
        Ci {
            re: self.re.sub(o.re),
            im: self.im.sub(o.im),
        }
    }

    /// Product `(a + ib)(c + id) = (ac - bd) + i(ad + bc)`.
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, o: Ci) -> Ci {
        Ci {
            re: self.re.mul(o.re).sub(self.im.mul(o.im)),
            im: self.re.mul(o.im).add(self.im.mul(o.re)),
        }
    }

    /// Product with a real interval.
    pub fn scale(self, s: Iv) -> Ci {
        Ci {
            re: self.re.mul(s),
            im: self.im.mul(s),
        }
    }

    /// An upper bound of `|z|` over the rectangle.
    pub fn mag(self) -> f64 {
        let (a, b) = (self.re.mag(), self.im.mag());
        up(up(up(a * a) + up(b * b)).sqrt())
    }

    /// Both parts widened by `r >= 0` (covers the disc of radius `r`).
    pub fn widen(self, r: f64) -> Ci {
        Ci {
            re: self.re.widen(r),
            im: self.im.widen(r),
        }
    }
}

/// A closed disc `|z - centre| <= radius` in the complex plane; the centre
/// is a float pair (exact), the radius an upper bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disc {
    /// Centre, real part.
    pub re: f64,
    /// Centre, imaginary part.
    pub im: f64,
    /// Radius.
    pub radius: f64,
}

impl Disc {
    /// The smallest float-centred disc around a rectangle: centre at the
    /// midpoints, radius the rounded-up distance to a corner.
    pub fn around(z: Ci) -> Disc {
        let (re, rr) = z.re.mid_rad();
        let (im, ri) = z.im.mid_rad();
        Disc {
            re,
            im,
            radius: up(up(up(rr * rr) + up(ri * ri)).sqrt()),
        }
    }

    /// A lower bound of `|centre|`.
    fn centre_abs_lower(&self) -> f64 {
        let s = down(down(self.re * self.re) + down(self.im * self.im));
        down(s.max(0.0).sqrt()).max(0.0)
    }

    /// An upper bound of `|centre|`.
    fn centre_abs_upper(&self) -> f64 {
        up(up(up(self.re * self.re) + up(self.im * self.im)).sqrt())
    }

    /// A lower bound of `|z|` over the disc (0 if it contains the origin).
    pub fn min_modulus(&self) -> f64 {
        down(self.centre_abs_lower() - self.radius).max(0.0)
    }

    /// An upper bound of `|z|` over the disc.
    pub fn max_modulus(&self) -> f64 {
        up(self.centre_abs_upper() + self.radius)
    }

    /// Whether the two discs are proven disjoint (distance of the centres
    /// above the sum of the radii, both bounds rounded against the claim).
    pub fn disjoint(&self, o: &Disc) -> bool {
        let dx = Iv::point(self.re).sub(Iv::point(o.re));
        let dy = Iv::point(self.im).sub(Iv::point(o.im));
        let dx_lo = dx.mig();
        let dy_lo = dy.mig();
        let d2 = down(down(dx_lo * dx_lo) + down(dy_lo * dy_lo));
        let dist = down(d2.max(0.0).sqrt());
        dist > up(self.radius + o.radius)
    }

    /// The mirror image in the real axis.
    pub fn conj(&self) -> Disc {
        Disc {
            re: self.re,
            im: -self.im,
            radius: self.radius,
        }
    }

    /// Whether the disc provably misses the real axis.
    pub fn off_real_axis(&self) -> bool {
        self.im.abs() > self.radius
    }

    /// Whether the disc lies in the open right half-plane `Re z > 0`.
    pub fn right_half_plane(&self) -> bool {
        self.re > self.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_moves_outward() {
        let a = Iv::point(0.1);
        let b = Iv::point(0.2);
        let s = a.add(b);
        assert!(s.lo < 0.1 + 0.2 && s.hi > 0.1 + 0.2);
        let p = Iv::new(-1.0, 2.0).mul(Iv::new(-3.0, 0.5));
        assert!(p.lo < -6.0 && p.hi > 3.0 && p.lo > -6.0000001 && p.hi < 3.0000001);
        assert_eq!(up(-f64::from_bits(1)), -0.0);
        assert!(down(0.0) < 0.0);
        assert!(up(f64::MAX).is_infinite());
    }

    #[test]
    fn nan_never_certifies() {
        let n = Iv::new(f64::NAN, f64::NAN);
        let p = n.mul(Iv::point(1.0));
        assert!(p.lo.is_nan());
        let d = Disc {
            re: f64::NAN,
            im: 0.0,
            radius: 0.0,
        };
        let e = Disc {
            re: 1.0,
            im: 0.0,
            radius: 0.1,
        };
        assert!(!d.disjoint(&e) && !e.disjoint(&d));
        assert!(!d.off_real_axis() || d.im.is_nan());
        assert!(d.min_modulus().is_nan() || d.min_modulus() == 0.0);
        assert!(!(d.min_modulus() > 0.25));
        assert!(!d.right_half_plane());
    }

    #[test]
    fn disc_bounds() {
        let d = Disc {
            re: 3.0,
            im: 4.0,
            radius: 1.0,
        };
        assert!(d.min_modulus() <= 4.0 && d.min_modulus() > 3.999999);
        assert!(d.max_modulus() >= 6.0 && d.max_modulus() < 6.000001);
        let e = Disc {
            re: 3.0,
            im: -4.0,
            radius: 1.0,
        };
        assert!(d.disjoint(&e) && d.off_real_axis());
        assert!(!d.disjoint(&Disc {
            re: 3.0,
            im: 2.0,
            radius: 1.0
        }));
    }
}
