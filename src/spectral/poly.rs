//! Dense univariate polynomials over the rationals, with the exact root
//! counting tools the certificates need: Sturm sequences (real roots in an
//! interval) and the Schur-Cohn recursion (roots inside a disc).
//!
//! Coefficients are stored in ascending order (`c[k]` multiplies `x^k`) and the
//! representation is kept trimmed (no zero leading coefficient; the zero
//! polynomial is the empty vector).

use crate::scalar::Rational;
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// A polynomial with rational coefficients, ascending powers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Poly(Vec<Rational>);

fn q(n: i64) -> Rational {
    Rational::from_integer(BigInt::from(n))
}

impl Poly {
    /// From ascending coefficients (trimmed).
    pub fn new(mut c: Vec<Rational>) -> Self {
        while c.last().is_some_and(Zero::is_zero) {
            c.pop();
        }
        Poly(c)
    }
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly(Vec::new())
    }
    /// The constant `a`.
    pub fn constant(a: Rational) -> Self {
        Poly::new(vec![a])
    }
    /// `x - a`.
    pub fn linear(a: Rational) -> Self {
        Poly::new(vec![-a, Rational::one()])
    }
    /// Ascending coefficients.
    pub fn coeffs(&self) -> &[Rational] {
        &self.0
    }
    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }
    /// Degree (`None` for the zero polynomial).
    pub fn degree(&self) -> Option<usize> {
        self.0.len().checked_sub(1)
    }
    /// Leading coefficient (0 for the zero polynomial).
    pub fn lead(&self) -> Rational {
        self.0.last().cloned().unwrap_or_else(Rational::zero)
    }
    /// Value at `x` (Horner).
    pub fn eval(&self, x: &Rational) -> Rational {
        self.0
            .iter()
            .rev()
            .fold(Rational::zero(), |acc, c| acc * x + c)
    }
    /// Derivative.
    pub fn derivative(&self) -> Self {
        Poly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * q(k as i64))
                .collect(),
        )
    }
    /// Sum.
    pub fn add(&self, o: &Poly) -> Poly {
        let n = self.0.len().max(o.0.len());
        Poly::new(
            (0..n)
                .map(|k| {
                    let a = self.0.get(k).cloned().unwrap_or_else(Rational::zero);
                    let b = o.0.get(k).cloned().unwrap_or_else(Rational::zero);
                    a + b
                })
                .collect(),
        )
    }
    /// Difference.
    pub fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.scale(&-Rational::one()))
    }
    /// Product.
    pub fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::zero();
        }
        let mut c = vec![Rational::zero(); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            if a.is_zero() {
                continue;
            }
            for (j, b) in o.0.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::new(c)
    }
    /// `a * self`.
    pub fn scale(&self, a: &Rational) -> Poly {
        Poly::new(self.0.iter().map(|c| c * a).collect())
    }
    /// Monic multiple (zero stays zero).
    pub fn monic(&self) -> Poly {
        if self.is_zero() {
            return Poly::zero();
        }
        let l = self.lead();
        self.scale(&(Rational::one() / l))
    }
    /// Quotient and remainder (`d` non-zero).
    pub fn divrem(&self, d: &Poly) -> (Poly, Poly) {
        let dd = d.degree().expect("division by the zero polynomial");
        let mut r = self.0.clone();
        let ld = d.lead();
        if r.len() <= dd {
            return (Poly::zero(), Poly::new(r));
        }
        let mut quo = vec![Rational::zero(); r.len() - dd];
        for k in (0..quo.len()).rev() {
            let coef = &r[k + dd] / &ld;
            if !coef.is_zero() {
                for (j, dc) in d.0.iter().enumerate() {
                    r[k + j] -= &coef * dc;
                }
            }
            quo[k] = coef;
        }
        r.truncate(dd);
        (Poly::new(quo), Poly::new(r))
    }
    /// Remainder.
    pub fn rem(&self, d: &Poly) -> Poly {
        self.divrem(d).1
    }
    /// Monic greatest common divisor (zero if both are zero).
    pub fn gcd(&self, o: &Poly) -> Poly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let r = a.rem(&b).monic();
            a = b;
            b = r;
        }
        a.monic()
    }
    /// Extended gcd: `(g, s, t)` with `s a + t b = g` monic.
    pub fn xgcd(&self, o: &Poly) -> (Poly, Poly, Poly) {
        let (mut r0, mut r1) = (self.clone(), o.clone());
        let (mut s0, mut s1) = (Poly::constant(Rational::one()), Poly::zero());
        let (mut t0, mut t1) = (Poly::zero(), Poly::constant(Rational::one()));
        while !r1.is_zero() {
            let (qq, r) = r0.divrem(&r1);
            let s = s0.sub(&qq.mul(&s1));
            let t = t0.sub(&qq.mul(&t1));
            r0 = r1;
            r1 = r;
            s0 = s1;
            s1 = s;
            t0 = t1;
            t1 = t;
        }
        if r0.is_zero() {
            return (r0, s0, t0);
        }
        let inv = Rational::one() / r0.lead();
        (r0.scale(&inv), s0.scale(&inv), t0.scale(&inv))
    }
    /// Square-free part `p / gcd(p, p')` (monic).
    pub fn squarefree(&self) -> Poly {
        if self.degree().unwrap_or(0) == 0 {
            return self.monic();
        }
        let g = self.gcd(&self.derivative());
        self.divrem(&g).0.monic()
    }
    /// `p(t x)`.
    pub fn scale_var(&self, t: &Rational) -> Poly {
        let mut pw = Rational::one();
        let mut c = Vec::with_capacity(self.0.len());
        for a in &self.0 {
            c.push(a * &pw);
            pw *= t;
        }
        Poly::new(c)
    }
    /// `p(-x)`.
    pub fn reflect(&self) -> Poly {
        self.scale_var(&-Rational::one())
    }
    /// `x^deg p(1/x)` (coefficients reversed).
    pub fn reciprocal(&self) -> Poly {
        let mut c = self.0.clone();
        c.reverse();
        Poly::new(c)
    }
    /// Floating-point approximation of the coefficients.
    pub fn to_f64(&self) -> Vec<f64> {
        self.0.iter().map(crate::scalar::rational_to_f64).collect()
    }
    /// Coefficients as `a/b` text, ascending.
    pub fn to_text(&self) -> Vec<String> {
        use crate::scalar::Scalar;
        self.0.iter().map(Scalar::to_text).collect()
    }
    /// Cauchy bound: every root has modulus `< 1 + max |a_k / a_d|`.
    pub fn root_bound(&self) -> Rational {
        let l = self.lead().abs();
        let m = self
            .0
            .iter()
            .take(self.0.len().saturating_sub(1))
            .map(|c| c.abs() / &l)
            .fold(Rational::zero(), |a, b| if b > a { b } else { a });
        m + Rational::one()
    }
}

fn sign(x: &Rational) -> i32 {
    if x.is_positive() {
        1
    } else if x.is_negative() {
        -1
    } else {
        0
    }
}

/// A Sturm sequence `s_0 = p, s_1 = p', s_{k+1} = -rem(s_{k-1}, s_k)`.
#[derive(Clone, Debug)]
pub struct Sturm(Vec<Poly>);

impl Sturm {
    /// The Sturm sequence of `p` (use a square-free `p` for root counts without
    /// multiplicity; Sturm's theorem counts distinct roots either way).
    pub fn new(p: &Poly) -> Self {
        let mut seq = vec![p.clone()];
        if p.degree().unwrap_or(0) == 0 {
            return Sturm(seq);
        }
        seq.push(p.derivative());
        loop {
            let k = seq.len();
            let r = seq[k - 2].rem(&seq[k - 1]);
            if r.is_zero() {
                break;
            }
            // Positive rescaling keeps the signs and the sizes small.
            let l = r.lead().abs();
            seq.push(r.scale(&(-Rational::one() / l)));
        }
        Sturm(seq)
    }
    fn variations(signs: impl Iterator<Item = i32>) -> usize {
        let mut last = 0;
        let mut v = 0;
        for s in signs {
            if s != 0 {
                if last != 0 && s != last {
                    v += 1;
                }
                last = s;
            }
        }
        v
    }
    /// Sign variations at `x`.
    pub fn at(&self, x: &Rational) -> usize {
        Self::variations(self.0.iter().map(|p| sign(&p.eval(x))))
    }
    /// Sign variations at `+infinity` (`positive`) or `-infinity`.
    pub fn at_infinity(&self, positive: bool) -> usize {
        Self::variations(self.0.iter().map(|p| {
            let s = sign(&p.lead());
            let d = p.degree().unwrap_or(0);
            if positive || d % 2 == 0 {
                s
            } else {
                -s
            }
        }))
    }
    /// Number of distinct real roots in `(a, b]` (`a < b`).
    pub fn count(&self, a: &Rational, b: &Rational) -> usize {
        self.at(a).saturating_sub(self.at(b))
    }
    /// Number of distinct real roots in `(a, +infinity)`.
    pub fn count_above(&self, a: &Rational) -> usize {
        self.at(a).saturating_sub(self.at_infinity(true))
    }
    /// Number of distinct real roots in `(-infinity, b]`.
    pub fn count_below(&self, b: &Rational) -> usize {
        self.at_infinity(false).saturating_sub(self.at(b))
    }
    /// Number of distinct real roots.
    pub fn count_all(&self) -> usize {
        self.at_infinity(false)
            .saturating_sub(self.at_infinity(true))
    }
}

/// Isolating intervals `(a, b]` of the distinct real roots of the square-free
/// polynomial `p`, each of width `<= width`, in increasing order.
pub fn isolate_real_roots(p: &Poly, width: &Rational) -> Vec<(Rational, Rational)> {
    let sturm = Sturm::new(p);
    let b = p.root_bound();
    let mut out = Vec::new();
    let mut stack = vec![(-b.clone(), b)];
    while let Some((lo, hi)) = stack.pop() {
        let c = sturm.count(&lo, &hi);
        if c == 0 {
            continue;
        }
        if c == 1 && &hi - &lo <= *width {
            out.push((lo, hi));
            continue;
        }
        let mid = (&lo + &hi) / q(2);
        stack.push((mid.clone(), hi));
        stack.push((lo, mid));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Number of roots (with multiplicity) of `p` strictly inside the unit disc,
/// by the Schur-Cohn recursion; `None` when the recursion is singular (which
/// happens iff `p` has a root on the unit circle or a pair of roots symmetric
/// with respect to it).
///
/// With `p* (z) = z^d p(1/z)` and `T p = a_0 p - a_d p*` (degree `< d`), Rouché's
/// theorem on `|z| = 1` (where `|p*| = |p|`) gives `N(p) = N(Tp)` if
/// `a_0^2 > a_d^2` and `N(p) = d - N(Tp)` if `a_0^2 < a_d^2`.
pub fn roots_inside_unit_disc(p: &Poly) -> Option<usize> {
    let d = p.degree()?;
    if d == 0 {
        return Some(0);
    }
    let a0 = p.coeffs()[0].clone();
    let ad = p.lead();
    let gamma = &a0 * &a0 - &ad * &ad;
    if gamma.is_zero() {
        return None;
    }
    let t = p.scale(&a0).sub(&p.reciprocal().scale(&ad));
    // Re-normalise the size of the coefficients (positive factor, same roots).
    let t = if t.is_zero() {
        return None;
    } else {
        let l = t.lead().abs();
        t.scale(&(Rational::one() / l))
    };
    let n = roots_inside_unit_disc(&t)?;
    if gamma.is_positive() {
        Some(n)
    } else {
        Some(d - n)
    }
}

/// Number of roots (with multiplicity) of `p` with modulus strictly greater
/// than `t > 0`; `None` if some root may have modulus exactly `t` (singular
/// Schur-Cohn recursion).
pub fn roots_outside(p: &Poly, t: &Rational) -> Option<usize> {
    let d = p.degree()?;
    // Roots of p(t z) inside |z| < 1 are the roots of p inside |x| < t.
    let inside = roots_inside_unit_disc(&p.scale_var(t))?;
    // No root on |x| = t (non-singular), so the rest are outside.
    Some(d - inside)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[i64]) -> Poly {
        Poly::new(c.iter().map(|&x| q(x)).collect())
    }

    #[test]
    fn arithmetic() {
        let a = p(&[-1, 0, 1]); // x^2 - 1
        let b = p(&[-1, 1]); // x - 1
        let (qq, r) = a.divrem(&b);
        assert_eq!(qq, p(&[1, 1]));
        assert!(r.is_zero());
        assert_eq!(a.gcd(&p(&[1, 1])), p(&[1, 1]));
        let (g, s, t) = a.xgcd(&p(&[2, 1]));
        assert_eq!(g, p(&[1]));
        assert_eq!(s.mul(&a).add(&t.mul(&p(&[2, 1]))), p(&[1]));
        // (x-1)^2 (x+2) -> squarefree (x-1)(x+2)
        let c = p(&[-1, 1]).mul(&p(&[-1, 1])).mul(&p(&[2, 1]));
        assert_eq!(c.squarefree(), p(&[-1, 1]).mul(&p(&[2, 1])));
    }

    #[test]
    fn sturm_counts() {
        // (x-1)(x-2)(x+3)(x^2+1)
        let f = p(&[-1, 1])
            .mul(&p(&[-2, 1]))
            .mul(&p(&[3, 1]))
            .mul(&p(&[1, 0, 1]));
        let s = Sturm::new(&f);
        assert_eq!(s.count_all(), 3);
        assert_eq!(s.count(&q(0), &q(5)), 2);
        assert_eq!(s.count_above(&q(1)), 1);
        assert_eq!(s.count_below(&q(0)), 1);
        let iv = isolate_real_roots(&f.squarefree(), &Rational::new(1.into(), 1000.into()));
        assert_eq!(iv.len(), 3);
        assert!(iv[0].0 < q(-3) && iv[0].1 >= q(-3));
    }

    #[test]
    fn schur_cohn_counts() {
        // roots 1/2, 3, -4, 1/3 +- i/3 (|.| = 0.471)
        let f = p(&[-1, 2])
            .mul(&p(&[-3, 1]))
            .mul(&p(&[4, 1]))
            .mul(&p(&[2, -6, 9])); // 9x^2 - 6x + 2: roots (1 +- i)/3
        assert_eq!(roots_inside_unit_disc(&f), Some(3));
        assert_eq!(roots_outside(&f, &q(1)), Some(2));
        assert_eq!(
            roots_outside(&f, &Rational::new(1.into(), 4.into())),
            Some(5)
        );
        assert_eq!(
            roots_outside(&f, &Rational::new(48.into(), 100.into())),
            Some(3)
        );
        assert_eq!(
            roots_outside(&f, &Rational::new(47.into(), 100.into())),
            Some(5)
        );
        assert_eq!(
            roots_outside(&f, &Rational::new(5.into(), 2.into())),
            Some(2)
        );
        assert_eq!(
            roots_outside(&f, &Rational::new(7.into(), 2.into())),
            Some(1)
        );
        assert_eq!(roots_outside(&f, &q(5)), Some(0));
        // A root on the circle is singular, and so is a pair symmetric to it (1/2, 2).
        assert_eq!(roots_outside(&f, &q(3)), None);
        assert_eq!(roots_inside_unit_disc(&p(&[-1, 2]).mul(&p(&[-2, 1]))), None);
        assert_eq!(roots_inside_unit_disc(&p(&[1, 0, 1])), None);
    }
}
