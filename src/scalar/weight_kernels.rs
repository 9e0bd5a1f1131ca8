//! The kernels of the face-point weights (math doc section 3): the closed
//! form in generic exact or plain arithmetic, fraction-free for rationals, and
//! with extended exponents for `f64` (formulas and error bounds in
//! [`crate::knots::face_weights`](mod@crate::knots::face_weights)).
//!
//! A leaf: it uses no other module of the crate, so that [`crate::scalar`]
//! can dispatch to these kernels while
//! [`crate::knots::face_weights`](mod@crate::knots::face_weights) is generic
//! over [`crate::scalar::Scalar`].

use num_rational::BigRational as Rational;
use num_traits::Num;

/// Closed form in exact (or plain floating) arithmetic; used for rationals.
pub(crate) fn generic_kernel<T: Clone + Num>(r: &[T], s: &[T]) -> Vec<T> {
    let n = r.len();
    // 1/2, exactly (in f64 and in the rationals alike).
    let half = T::one() / (T::one() + T::one());
    let mut alpha = Vec::with_capacity(n);
    for j in 0..n {
        // suffix[m] = prod_{i=j+m}^{j+n-1} s_i
        let mut suffix = vec![T::one(); n + 1];
        for m in (0..n).rev() {
            suffix[m] = suffix[m + 1].clone() * s[(j + m) % n].clone();
        }
        let mut prefix = T::one();
        let mut total = half.clone() * suffix[0].clone();
        for m in 1..=n {
            prefix = prefix * r[(j + m - 1) % n].clone();
            let term = prefix.clone() * suffix[m].clone();
            total = total + if m == n { half.clone() * term } else { term };
        }
        alpha.push(total);
    }
    let sum = alpha.iter().cloned().fold(T::zero(), |a, b| a + b);
    alpha.into_iter().map(|a| a / sum.clone()).collect()
}

/// The same closed form for rationals, fraction-free (the kernel of
/// [`face_weights`](crate::knots::face_weights()) for `Rational`).
///
/// With `D_i` the common denominator of `r_i` and `s_i` and the integers
/// `a_i = r_i D_i`, `b_i = s_i D_i`, every term `T_m(j)` is a product over
/// each index `i` of exactly one of `r_i, s_i`, so
/// `T_m(j) = (prod_{i=j}^{j+m-1} a_i)(prod_{i=j+m}^{j+n-1} b_i) / prod_i D_i`:
/// the denominator is the same for all `j` and `m` and cancels in
/// `c_j = alpha_j / sum_k alpha_k`. Doubling the weights (`1, 2, .., 2, 1`)
/// keeps everything in integers, so the products need no gcd; only the `n`
/// final quotients are reduced. Identical values to [`generic_kernel`], which
/// reduces after every operation (too slow for `--exact` with `f64` knots,
/// whose 53-bit mantissas give products of thousands of bits).
pub(crate) fn rational_kernel(r: &[Rational], s: &[Rational]) -> Vec<Rational> {
    use num_bigint::BigInt;
    use num_integer::Integer as _;
    use num_traits::{One as _, Zero as _};
    let n = r.len();
    let (a, b): (Vec<BigInt>, Vec<BigInt>) = r
        .iter()
        .zip(s)
        .map(|(ri, si)| {
            let d = ri.denom().lcm(si.denom());
            (
                ri.numer() * (&d / ri.denom()),
                si.numer() * (&d / si.denom()),
            )
        })
        .unzip();
    let mut alpha = Vec::with_capacity(n);
    for j in 0..n {
        // suffix[m] = prod_{i=j+m}^{j+n-1} b_i
        let mut suffix = vec![BigInt::one(); n + 1];
        for m in (0..n).rev() {
            suffix[m] = &suffix[m + 1] * &b[(j + m) % n];
        }
        let mut prefix = BigInt::one();
        let mut total = suffix[0].clone();
        for m in 1..=n {
            prefix *= &a[(j + m - 1) % n];
            let term = &prefix * &suffix[m];
            if m == n {
                total += term;
            } else {
                total += term << 1u32;
            }
        }
        alpha.push(total);
    }
    let sum = alpha.iter().fold(BigInt::zero(), |acc, x| acc + x);
    alpha
        .into_iter()
        .map(|x| Rational::new(x, sum.clone()))
        .collect()
}

/// A positive number `m * 2^e` with `m in [0.5, 1)` and an unbounded exponent.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ExtFloat {
    m: f64,
    e: i64,
}

impl ExtFloat {
    const ONE: ExtFloat = ExtFloat { m: 0.5, e: 1 };

    /// `x > 0`, finite (subnormals are handled). Callers validate `x`; a zero
    /// or non-finite `x` gives a value whose mantissa is not in `[0.5, 1)`
    /// (never a hang or a panic).
    pub(crate) fn new(x: f64) -> Self {
        debug_assert!(x > 0.0 && x.is_finite());
        let (m, e) = frexp(x);
        ExtFloat { m, e }
    }

    pub(crate) fn mul(self, o: ExtFloat) -> Self {
        let (m, e) = frexp(self.m * o.m);
        ExtFloat {
            m,
            e: e + self.e + o.e,
        }
    }

    /// `self / o` (both positive): `m_1 / m_2 in (0.5, 2)`, renormalised.
    pub(crate) fn div(self, o: ExtFloat) -> Self {
        let (m, e) = frexp(self.m / o.m);
        ExtFloat {
            m,
            e: e + self.e - o.e,
        }
    }

    pub(crate) fn add(self, o: ExtFloat) -> Self {
        let (big, small) = if self.e >= o.e { (self, o) } else { (o, self) };
        let shift = big.e - small.e;
        if shift > 1100 {
            return big;
        }
        let (m, e) = frexp(big.m + small.m * exp2i(-shift));
        ExtFloat { m, e: e + big.e }
    }

    fn half(self) -> Self {
        ExtFloat {
            m: self.m,
            e: self.e - 1,
        }
    }

    /// `self / o` as an ordinary f64 (finite when the quotient is representable).
    fn ratio(self, o: ExtFloat) -> f64 {
        (self.m / o.m) * exp2i(self.e - o.e)
    }

    /// The nearest `f64` (0 below the subnormal range, infinity above `f64::MAX`).
    ///
    /// Scales in two steps so that a subnormal result is rounded once.
    pub(crate) fn to_f64(self) -> f64 {
        if self.e > 1024 {
            f64::INFINITY
        } else if self.e < -1100 {
            0.0
        } else if self.e > 1000 {
            // m 2^(e - 1000) is exact; the product overflows only if the value does.
            (self.m * exp2i(self.e - 1000)) * exp2i(1000)
        } else if self.e >= -1021 {
            self.m * exp2i(self.e)
        } else {
            // 2^e = 2^-1000 * 2^(e + 1000), both factors normal; the product
            // is the only rounding step.
            (self.m * exp2i(self.e + 1000)) * exp2i(-1000)
        }
    }
}

/// The edge ratio `r = b / (a + b)` and its complement `s = a / (a + b)` of two
/// finite positive knot intervals, with unbounded exponents: `a + b` never
/// overflows and `r`, `s` never underflow, whatever `a / b` is (math doc
/// section 2). Each has a relative error of at most 2 ulps.
pub(crate) fn edge_ratio_ext(a: f64, b: f64) -> (ExtFloat, ExtFloat) {
    let (xa, xb) = (ExtFloat::new(a), ExtFloat::new(b));
    let sum = xa.add(xb);
    (xb.div(sum), xa.div(sum))
}

/// `2^k` for any integer `k`, saturating to 0 or infinity.
fn exp2i(k: i64) -> f64 {
    if k < -1074 {
        0.0
    } else if k > 1023 {
        f64::INFINITY
    } else if k < -1022 {
        f64::from_bits(1u64 << (k + 1074))
    } else {
        f64::from_bits(((k + 1023) as u64) << 52)
    }
}

/// `x = m * 2^e` with `m in [0.5, 1)` for finite `x > 0`.
///
/// Like C's `frexp`, zero, infinities and NaN come back unchanged with `e = 0`
/// (callers validate positivity first; this never recurses or loops).
fn frexp(x: f64) -> (f64, i64) {
    if x == 0.0 || !x.is_finite() {
        return (x, 0);
    }
    let (x, bias_shift) = if x.abs() < f64::MIN_POSITIVE {
        // Subnormal: 2^64 times it is normal (x >= 2^-1074), exactly.
        (x * exp2i(64), 64)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let m = f64::from_bits((bits & !(0x7ffu64 << 52)) | (1022u64 << 52));
    (m, biased - 1022 - bias_shift)
}

/// Closed form with extended exponents; `O(n^2)` operations.
pub(crate) fn f64_kernel(r: &[f64], s: &[f64]) -> Vec<f64> {
    let re: Vec<ExtFloat> = r.iter().map(|&x| ExtFloat::new(x)).collect();
    let se: Vec<ExtFloat> = s.iter().map(|&x| ExtFloat::new(x)).collect();
    ext_kernel(&re, &se)
}

/// Face weights straight from the knot intervals of each edge, `a_i = p_i`
/// and `b_i = q_{i+1}` (finite, positive): the ratios are kept with unbounded
/// exponents ([`edge_ratio_ext`]), so no interval quotient is too extreme.
/// Also returns the ratios `(r_i, s_i)` rounded to `f64` (a ratio below the
/// `f64` range rounds to 0; the weights are unaffected).
pub(crate) fn interval_kernel(a: &[f64], b: &[f64]) -> (Vec<f64>, Vec<(f64, f64)>) {
    let (re, se): (Vec<ExtFloat>, Vec<ExtFloat>) =
        a.iter().zip(b).map(|(&x, &y)| edge_ratio_ext(x, y)).unzip();
    let rs = re
        .iter()
        .zip(&se)
        .map(|(r, s)| (r.to_f64(), s.to_f64()))
        .collect();
    (ext_kernel(&re, &se), rs)
}

/// The closed form over extended-exponent ratios.
fn ext_kernel(re: &[ExtFloat], se: &[ExtFloat]) -> Vec<f64> {
    let n = re.len();
    let mut suffix = vec![ExtFloat::ONE; n + 1];
    let mut alpha = Vec::with_capacity(n);
    for j in 0..n {
        suffix[n] = ExtFloat::ONE;
        for m in (0..n).rev() {
            suffix[m] = suffix[m + 1].mul(se[(j + m) % n]);
        }
        let mut prefix = ExtFloat::ONE;
        let mut total = suffix[0].half();
        for m in 1..=n {
            prefix = prefix.mul(re[(j + m - 1) % n]);
            let term = prefix.mul(suffix[m]);
            total = total.add(if m == n { term.half() } else { term });
        }
        alpha.push(total);
    }
    let sum = alpha.iter().skip(1).fold(alpha[0], |a, &b| a.add(b));
    alpha.into_iter().map(|a| a.ratio(sum)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ext_float_basics() {
        for x in [1.0, 0.75, 3.0e-300, 5e-320, 1.7e308] {
            let (m, e) = frexp(x);
            assert!((0.5..1.0).contains(&m));
            assert_eq!(m * exp2i(e.min(1023)) * exp2i((e - 1023).max(0)), x);
        }
        // zero and non-finite values come back unchanged, without recursion
        assert_eq!(frexp(0.0), (0.0, 0));
        assert!(frexp(f64::NAN).0.is_nan());
        assert_eq!(frexp(f64::INFINITY), (f64::INFINITY, 0));
        assert_eq!(frexp(f64::from_bits(1)), (0.5, -1073));
        for x in [1.0, 3.0e-300, 5e-324, 2.5e-320, 1.7e308, f64::MAX] {
            let e = ExtFloat::new(x);
            assert_eq!(e.to_f64(), x);
            assert_eq!(
                e.mul(ExtFloat::new(0.5)).mul(ExtFloat::new(2.0)).to_f64(),
                x
            );
        }
        let a = ExtFloat::new(3.0).mul(ExtFloat::new(0.25));
        assert_eq!(a.ratio(ExtFloat::ONE), 0.75);
        assert_eq!(
            ExtFloat::new(1.5)
                .add(ExtFloat::new(0.25))
                .ratio(ExtFloat::ONE),
            1.75
        );
    }

    /// `exp2i` against repeated exact halving and doubling (every power of two
    /// from `2^-1074` to `2^1023` is an `f64`), at every `k`, and its
    /// saturation just outside that range.
    #[test]
    fn exp2i_is_every_power_of_two_and_saturates() {
        let mut x = 1.0f64;
        for k in 0..=1023 {
            assert_eq!(exp2i(k), x, "2^{k}");
            x *= 2.0;
        }
        assert_eq!(exp2i(1024), f64::INFINITY);
        assert_eq!(exp2i(5000), f64::INFINITY);
        let mut x = 1.0f64;
        for k in 0..=1074 {
            assert_eq!(exp2i(-k), x, "2^-{k}");
            x /= 2.0;
        }
        assert_eq!(exp2i(-1074), f64::from_bits(1));
        assert_eq!(exp2i(-1075), 0.0);
        assert_eq!(exp2i(-5000), 0.0);
    }

    /// `to_f64` on both sides of each of its branch boundaries (exponents
    /// 1024, 1000, -1021, -1100) and inside each branch, against the value
    /// computed independently: `0.5 * 2^e = 2^(e - 1)`, exact wherever it is
    /// an `f64` (0 below `2^-1074`, where `2^-1075` is a tie that rounds to
    /// even, and infinity from `2^1024` on), and `0.75 * 2^e = 1.5 *
    /// 2^(e - 1)` in the normal range.
    #[test]
    fn to_f64_on_both_sides_of_every_branch() {
        let es = [
            5000, 1026, 1025, 1024, 1023, 1010, 1001, 1000, 999, 100, 0, -100, -1020, -1021, -1022,
            -1023, -1050, -1073, -1074, -1075, -1076, -1099, -1100, -1101, -1200, -5000,
        ];
        for e in es {
            let half = ExtFloat { m: 0.5, e }.to_f64();
            let want = match e - 1 {
                k if k >= 1024 => f64::INFINITY,
                k if k < -1074 => 0.0,
                k => exp2i(k),
            };
            assert_eq!(half, want, "0.5 * 2^{e}");
            if (-1021..=1024).contains(&e) {
                let x = ExtFloat { m: 0.75, e }.to_f64();
                assert_eq!(x, 1.5 * exp2i(e - 1), "0.75 * 2^{e}");
            }
        }
    }

    /// Extended-exponent sums whose terms are more than `2^1024` apart, in
    /// both orders: the small term vanishes and the big one comes back
    /// exactly (no overflow in aligning the mantissas); `mul` and `div` keep
    /// exponents beyond the `f64` range.
    #[test]
    fn ext_float_sums_of_far_apart_terms() {
        let (big, small) = (ExtFloat::new(1e300), ExtFloat::new(1e-300));
        for sum in [big.add(small), small.add(big)] {
            assert_eq!(sum.to_f64(), 1e300);
            assert_eq!(sum.ratio(big), 1.0);
        }
        let (a, b) = (ExtFloat::new(3.0), ExtFloat::new(0.75));
        assert_eq!(a.add(b).to_f64(), 3.75);
        assert_eq!(b.add(a).to_f64(), 3.75);
        // x^2 / x = x for x = 1.5 * 2^(+-900) (mantissa products exact;
        // the squares are beyond the f64 range)
        for x in [1.5 * exp2i(900), 1.5 * exp2i(-900)] {
            let e = ExtFloat::new(x);
            let sq = e.mul(e);
            assert_eq!(sq.to_f64(), if x > 1.0 { f64::INFINITY } else { 0.0 });
            assert_eq!(sq.div(e).to_f64(), x);
        }
    }
}
