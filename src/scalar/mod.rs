//! Scalars the local matrices are generic over: `f64` and exact rationals.
//!
//! Every matrix builder in [`crate::schemes`] is written once against the
//! [`Scalar`] trait, so the same code produces a floating-point matrix for
//! analysis and an exact [`BigRational`] matrix for certificates ("row sums are
//! exactly 1", "the Theorem 1 weights sum to exactly 3/4").
//!
//! Exact input comes from text: [`parse_exact`] reads decimals (`1.3`),
//! fractions (`13/10`) and scientific notation (`1e-6`) without rounding.

pub(crate) mod weight_kernels;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Num, One, Signed, ToPrimitive, Zero};
use std::fmt;

/// Exact rational numbers with arbitrary-precision numerator and denominator.
pub type Rational = BigRational;

/// A field element the local matrices can be assembled over.
///
/// Implemented for `f64` (fast, rounded) and [`Rational`] (exact).
pub trait Scalar:
    Clone + fmt::Debug + fmt::Display + PartialOrd + Num + Signed + Send + Sync + 'static
{
    /// `num / den` in this scalar type (`den != 0`).
    fn frac(num: i64, den: i64) -> Self;
    /// The nearest `f64` (exact for `f64`, rounded for rationals).
    fn to_f64(&self) -> f64;
    /// Whether arithmetic in this type is exact.
    const EXACT: bool;
    /// Whether the value is finite (always true for rationals).
    fn is_finite_value(&self) -> bool;
    /// `self` as text: shortest round-trip decimal for `f64`, `a/b` for rationals.
    fn to_text(&self) -> String;
    /// Converts an `f64` that is already a value of this type's field without
    /// rounding (every finite `f64` is a dyadic rational). NaN and infinities
    /// map to zero for rationals; callers validate finiteness first.
    fn from_f64_lossless(x: f64) -> Self;
    /// The edge ratio `r = b / (a + b)` and `s = a / (a + b)` of two positive
    /// intervals (math doc section 2). Exact for rationals; for `f64` computed
    /// with unbounded exponents, so `a + b` never overflows (each result is
    /// accurate to 2 ulps, or rounds to 0 when it lies below the `f64` range).
    fn edge_ratio(a: &Self, b: &Self) -> (Self, Self) {
        let sum = a.clone() + b.clone();
        (b.clone() / sum.clone(), a.clone() / sum)
    }
    /// Face-point weight kernel (see [`crate::knots::face_weights`]); `f64`
    /// overrides it with an overflow-free extended-exponent evaluation.
    #[doc(hidden)]
    fn face_weights_kernel(r: &[Self], s: &[Self]) -> Vec<Self> {
        weight_kernels::generic_kernel(r, s)
    }
}

impl Scalar for f64 {
    fn frac(num: i64, den: i64) -> Self {
        num as f64 / den as f64
    }
    fn to_f64(&self) -> f64 {
        *self
    }
    const EXACT: bool = false;
    fn is_finite_value(&self) -> bool {
        self.is_finite()
    }
    fn to_text(&self) -> String {
        format!("{self:?}")
    }
    fn face_weights_kernel(r: &[Self], s: &[Self]) -> Vec<Self> {
        weight_kernels::f64_kernel(r, s)
    }
    fn edge_ratio(a: &Self, b: &Self) -> (Self, Self) {
        if !(*a > 0.0 && *b > 0.0 && a.is_finite() && b.is_finite()) {
            // Not an interval pair; the plain formula (callers validate).
            let sum = a + b;
            return (b / sum, a / sum);
        }
        let (r, s) = weight_kernels::edge_ratio_ext(*a, *b);
        (r.to_f64(), s.to_f64())
    }
    fn from_f64_lossless(x: f64) -> Self {
        x
    }
}

impl Scalar for Rational {
    fn frac(num: i64, den: i64) -> Self {
        Rational::new(BigInt::from(num), BigInt::from(den))
    }
    fn to_f64(&self) -> f64 {
        rational_to_f64(self)
    }
    const EXACT: bool = true;
    fn is_finite_value(&self) -> bool {
        true
    }
    fn from_f64_lossless(x: f64) -> Self {
        Rational::from_float(x).unwrap_or_else(Rational::zero)
    }
    fn face_weights_kernel(r: &[Self], s: &[Self]) -> Vec<Self> {
        weight_kernels::rational_kernel(r, s)
    }
    fn to_text(&self) -> String {
        if self.denom().is_one() {
            self.numer().to_string()
        } else {
            format!("{}/{}", self.numer(), self.denom())
        }
    }
}

/// Nearest `f64` of a rational, robust to huge numerators and denominators.
///
/// `BigRational::to_f64` already handles large operands; this wrapper maps the
/// (impossible for finite rationals) `None` to NaN so callers never panic.
pub fn rational_to_f64(x: &Rational) -> f64 {
    ToPrimitive::to_f64(x).unwrap_or(f64::NAN)
}

/// Parses a number written in decimal, fraction or scientific notation exactly.
///
/// Accepted forms: `3`, `-2`, `1.25`, `.5`, `13/10`, `1e-6`, `2.5E+3`.
/// Returns `None` for anything else (including `inf`, `nan`, `1/0`).
///
/// ```
/// use subdiv_lab::scalar::{parse_exact, Rational};
/// use num_traits::FromPrimitive;
/// assert_eq!(parse_exact("1.3").unwrap(), Rational::new(13.into(), 10.into()));
/// assert_eq!(parse_exact("2/6").unwrap(), Rational::new(1.into(), 3.into()));
/// assert_eq!(parse_exact("1e-2").unwrap(), Rational::new(1.into(), 100.into()));
/// assert!(parse_exact("nan").is_none());
/// ```
pub fn parse_exact(text: &str) -> Option<Rational> {
    let s = text.trim();
    if s.is_empty() {
        return None;
    }
    if let Some((a, b)) = s.split_once('/') {
        let num = parse_exact(a)?;
        let den = parse_exact(b)?;
        if den.is_zero() {
            return None;
        }
        return Some(num / den);
    }
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(pos) => {
            let exp: i64 = s[pos + 1..].parse().ok()?;
            (&s[..pos], exp)
        }
        None => (s, 0),
    };
    let (negative, digits) = match mantissa.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (int_part, frac_part) = match digits.split_once('.') {
        Some((i, f)) => (i, f),
        None => (digits, ""),
    };
    if int_part.is_empty() && frac_part.is_empty() {
        return None;
    }
    if !int_part.bytes().all(|b| b.is_ascii_digit())
        || !frac_part.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    // Guard against absurd exponents that would allocate enormous integers.
    if exponent.unsigned_abs() > 10_000 {
        return None;
    }
    let all_digits = format!("{int_part}{frac_part}");
    let mut numer = BigInt::from_str_radix(
        if all_digits.is_empty() {
            "0"
        } else {
            &all_digits
        },
        10,
    )
    .ok()?;
    if negative {
        numer = -numer;
    }
    let scale = exponent - frac_part.len() as i64;
    let ten = BigInt::from(10);
    let value = if scale >= 0 {
        Rational::from_integer(numer * num_traits::pow(ten, scale as usize))
    } else {
        Rational::new(numer, num_traits::pow(ten, (-scale) as usize))
    };
    Some(value)
}

/// A rational as text for messages: `a/b` when that is at most 40
/// characters, otherwise a 7-digit scientific approximation `~d.dddddde[+-]x`
/// (exact values of `1e400/3`-like inputs are hundreds of digits long).
///
/// ```
/// use subdiv_lab::scalar::{parse_exact, short_text};
/// assert_eq!(short_text(&parse_exact("13/10").unwrap()), "13/10");
/// assert_eq!(short_text(&parse_exact("1e400/3").unwrap()), "~3.333333e399");
/// assert_eq!(short_text(&parse_exact("-3e-400").unwrap()), "~-3.000000e-400");
/// ```
pub fn short_text(q: &Rational) -> String {
    let t = q.to_text();
    if t.len() <= 40 {
        return t;
    }
    // log10 |q| from the leading digits of numerator and denominator.
    let log10 = |x: &BigInt| -> f64 {
        let d = x.abs().to_string();
        let head: f64 = d[..d.len().min(17)].parse().unwrap_or(1.0);
        head.log10() + (d.len() - d.len().min(17)) as f64
    };
    let l = log10(q.numer()) - log10(q.denom());
    let mut exp = l.floor();
    let mut mant = 10f64.powf(l - exp);
    if mant >= 9.9999995 {
        mant /= 10.0;
        exp += 1.0;
    }
    let sign = if q.is_negative() { "-" } else { "" };
    format!("~{sign}{mant:.6}e{exp}")
}

/// The exact rational value of a finite `f64` (every finite double is a dyadic rational).
pub fn f64_to_rational(x: f64) -> Option<Rational> {
    Rational::from_float(x)
}

/// Convert a slice of any scalar to `f64`.
pub fn to_f64_vec<T: Scalar>(v: &[T]) -> Vec<f64> {
    v.iter().map(Scalar::to_f64).collect()
}

/// Convert a matrix of any scalar to `f64`.
pub fn to_f64_matrix<T: Scalar>(m: &nalgebra::DMatrix<T>) -> nalgebra::DMatrix<f64> {
    m.map(|x| x.to_f64())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_forms() {
        let r = |a: i64, b: i64| Rational::new(a.into(), b.into());
        assert_eq!(parse_exact("3").unwrap(), r(3, 1));
        assert_eq!(parse_exact("-0.25").unwrap(), r(-1, 4));
        assert_eq!(parse_exact(".5").unwrap(), r(1, 2));
        assert_eq!(parse_exact("2.5E+3").unwrap(), r(2500, 1));
        assert_eq!(parse_exact("1/3").unwrap(), r(1, 3));
        for bad in [
            "", "abc", "1/0", "inf", "NaN", "1.2.3", "e5", "--1", "1e99999",
        ] {
            assert!(parse_exact(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn rational_text() {
        assert_eq!(Rational::frac(6, 4).to_text(), "3/2");
        assert_eq!(Rational::frac(4, 2).to_text(), "2");
        assert_eq!(0.1f64.to_text(), "0.1");
    }
}
