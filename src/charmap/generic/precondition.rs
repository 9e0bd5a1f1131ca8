//! The spectral precondition of the generic certificate decided in exact
//! rational arithmetic (math doc section 20.8), for schemes whose local
//! matrix is rational where the floating-point classification is not
//! standard.
//!
//! With `p(x) = det(x I - S) = (x - 1) q(x) x^k` (`q(0) != 0`) and a rational
//! threshold `t` with `0 < t < 1`, the eigenstructure is standard when
//!
//! 1. `q(1) != 0` (the eigenvalue 1 is simple);
//! 2. `q` has exactly two roots, with multiplicity, of modulus `> t`
//!    (Schur-Cohn count): every other eigenvalue is at most `t` in modulus;
//! 3. the square-free part of `gcd(q, q')` (the multiple roots) has a real
//!    root `lambda` in `(t, 1)` (Sturm count): being at least double, it is
//!    both roots of step 2, of multiplicity exactly 2;
//! 4. `rank(S - lambda I) = dim - 2` (exact, in `Q(lambda)`): the eigenspace
//!    is 2-dimensional.
//!
//! Any `t` is valid: a poor choice makes the test fail, never pass wrongly.

use crate::scalar::{f64_to_rational, Rational};
use crate::spectral::exact::{charpoly, rank_at_root};
use crate::spectral::poly::{roots_outside, Poly, Sturm};
use nalgebra::DMatrix;
use num_traits::{One, Signed, Zero};

/// Width below which the isolating interval of `lambda` is refined before
/// the gap is read from it (`2^-40`: far below any gap the certificate can
/// use, cheap in bisection steps).
pub const ISOLATION_WIDTH: f64 = 9.094947017729282e-13;

/// The grid of the threshold `t` (`2^-6`): the midpoint of a pair and the
/// rest moves by at most `2^-7`, so gaps above `2^-6` keep `t` between
/// them (the butterfly schemes' are above 0.2); coarse enough that `p(t x)`
/// has short coefficients.
pub const THRESHOLD_GRID: f64 = 1.0 / 64.0;

/// A standard eigenstructure proven exactly.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ExactStandard {
    /// The threshold `t`: every eigenvalue other than 1 and `lambda` has
    /// modulus at most `t`.
    pub threshold: f64,
    /// An isolating interval `(lo, hi]` of `lambda` (rounded outwards).
    pub lambda: [f64; 2],
    /// A lower bound of `lambda - t` and of `1 - lambda` (rounded down).
    pub gap: f64,
}

/// Decides the precondition for the rational matrix `s` with the threshold
/// `t` (module docs; `t` is first rounded to a multiple of
/// [`THRESHOLD_GRID`], which keeps the Schur-Cohn recursion's rationals
/// short). `Err` carries the reason it is not proven.
pub fn exact_standard(s: &DMatrix<Rational>, t: f64) -> Result<ExactStandard, String> {
    let dim = s.nrows();
    let t = (t / THRESHOLD_GRID).round() * THRESHOLD_GRID;
    let t_q = f64_to_rational(t)
        .filter(|x| x.is_positive() && *x < Rational::one())
        .ok_or_else(|| format!("no threshold between the subdominant pair and the rest ({t})"))?;
    let p = charpoly(s);
    let one = Rational::one();
    let (q, r) = p.divrem(&Poly::new(vec![-one.clone(), one.clone()]));
    if !r.is_zero() {
        return Err("1 is not an eigenvalue of the local matrix".into());
    }
    if q.eval(&one).is_zero() {
        return Err("the eigenvalue 1 is not simple".into());
    }
    // the roots at 0 (modulus below t) are removed before the Schur-Cohn count
    let zeros = q.coeffs().iter().take_while(|c| c.is_zero()).count();
    let q = Poly::new(q.coeffs()[zeros..].to_vec());
    match count_outside(&q, &t_q)? {
        Some(2) => {}
        Some(k) => {
            return Err(format!(
                "{k} eigenvalues other than 1 have modulus above {t} (exact count; a standard pair needs 2)"
            ))
        }
        None => return Err(format!("an eigenvalue may have modulus exactly {t}")),
    }
    // a multiple root of q in (t, 1) accounts for both roots above t: it
    // is the real double lambda (its polynomial, the square-free part of
    // gcd(q, q'), has a low degree: isolation and rank work with it)
    let multiple = q.gcd(&q.derivative()).squarefree();
    let sturm = Sturm::new(&multiple);
    if sturm.count(&t_q, &one) != 1 {
        return Err(format!(
            "the two eigenvalues of modulus above {t} are not one real double eigenvalue in ({t}, 1)"
        ));
    }
    // isolate lambda in (lo, hi] by bisection
    let (mut lo, mut hi) = (t_q.clone(), one.clone());
    let width = f64_to_rational(ISOLATION_WIDTH).unwrap_or_else(Rational::zero);
    while &hi - &lo > width {
        let mid = (&lo + &hi) / Rational::from_integer(2.into());
        if sturm.count(&lo, &mid) == 1 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    // the rank is computed in Q(lambda): with lambda rational (a simple
    // fraction in the interval that is an exact root) over Q, otherwise
    // modulo the polynomial of the multiple roots if its degree is small
    let field = match simple_root(&multiple, &lo, &hi) {
        Some(r) => Poly::new(vec![-r, one.clone()]),
        None if multiple.degree().unwrap_or(0) <= MAX_FIELD_DEGREE => multiple.clone(),
        None => {
            return Err(format!(
                "the double eigenvalue is irrational and its polynomial has degree {} (the exact rank stops at {MAX_FIELD_DEGREE})",
                multiple.degree().unwrap_or(0)
            ))
        }
    };
    let rank = rank_at_root(s, &field, &lo, &hi);
    if rank + 2 != dim {
        return Err(format!(
            "the double eigenvalue in ({}, {}] has a {}-dimensional eigenspace (exact rank), not 2: defective",
            down(&lo),
            up(&hi),
            dim - rank
        ));
    }
    let gap = down(&(&lo - &t_q)).min(down(&(&one - &hi)));
    Ok(ExactStandard {
        threshold: t,
        lambda: [down(&lo), up(&hi)],
        gap,
    })
}

/// Largest degree of a square-free factor the Schur-Cohn count is run on
/// (its rationals grow quickly with the degree; a larger factor makes the
/// test give up, never pass).
pub const MAX_FACTOR_DEGREE: usize = 24;

/// The number of roots of `q` (with multiplicity) of modulus `> t`: `q` is
/// split into the square-free factors `f_i` of its roots of multiplicity
/// exactly `i` (from the chain of `gcd(g, g')`), and the Schur-Cohn counts of
/// the `f_i` are added with weight `i`. `Ok(None)` when a root may lie on
/// `|z| = t`; `Err` when a factor is too large.
fn count_outside(q: &Poly, t: &Rational) -> Result<Option<usize>, String> {
    let mut total = 0;
    let mut at_least = q.squarefree(); // roots of multiplicity >= i
    let mut g = q.gcd(&q.derivative());
    let mut i = 1;
    loop {
        let next = if g.degree().unwrap_or(0) == 0 {
            Poly::constant(Rational::one())
        } else {
            g.squarefree()
        };
        let exact = at_least.divrem(&next).0; // multiplicity exactly i
        if let Some(d) = exact.degree().filter(|d| *d > 0) {
            if d > MAX_FACTOR_DEGREE {
                return Err(format!(
                    "a square-free factor of the characteristic polynomial has degree {d} (the exact count stops at {MAX_FACTOR_DEGREE})"
                ));
            }
            match roots_outside(&exact, t) {
                Some(k) => total += i * k,
                None => return Ok(None),
            }
        }
        if next.degree().unwrap_or(0) == 0 {
            return Ok(Some(total));
        }
        at_least = next;
        g = g.gcd(&g.derivative());
        i += 1;
    }
}

/// Largest degree of the field polynomial of an irrational `lambda` for the
/// exact rank (the entries of the elimination are polynomials of that
/// degree; above it the test gives up, never passes).
pub const MAX_FIELD_DEGREE: usize = 6;

/// A root of `f` in `(lo, hi]` that is a fraction with denominator at most
/// 64, if there is one.
fn simple_root(f: &Poly, lo: &Rational, hi: &Rational) -> Option<Rational> {
    (1..=64i64).find_map(|d| {
        let d = Rational::from_integer(d.into());
        let r = (hi * &d).floor() / &d;
        (&r > lo && f.eval(&r).is_zero()).then_some(r)
    })
}

/// `x` rounded down to an `f64`.
fn down(x: &Rational) -> f64 {
    let y = crate::scalar::rational_to_f64(x);
    match f64_to_rational(y) {
        // the next f64 towards -inf
        Some(q) if &q > x => {
            let bits = y.to_bits();
            if y == 0.0 {
                -f64::from_bits(1)
            } else if y > 0.0 {
                f64::from_bits(bits - 1)
            } else {
                f64::from_bits(bits + 1)
            }
        }
        _ => y,
    }
}

/// `x` rounded up to an `f64`.
fn up(x: &Rational) -> f64 {
    -down(&-x.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(a: i64, b: i64) -> Rational {
        Rational::new(a.into(), b.into())
    }

    /// `diag(1, blocks)` from rational rows.
    fn matrix(rows: &[&[Rational]]) -> DMatrix<Rational> {
        let n = rows.len();
        DMatrix::from_fn(n, n, |i, j| rows[i][j].clone())
    }

    #[test]
    fn a_semisimple_double_pair_over_a_jordan_block_is_standard() {
        let z = Rational::zero;
        // 1, 1/2 (twice, diagonal), a Jordan block at 1/4
        let s = matrix(&[
            &[q(1, 1), z(), z(), z(), z()],
            &[z(), q(1, 2), z(), z(), z()],
            &[z(), z(), q(1, 2), z(), z()],
            &[z(), z(), z(), q(1, 4), q(1, 1)],
            &[z(), z(), z(), z(), q(1, 4)],
        ]);
        let e = exact_standard(&s, 0.375).unwrap();
        assert!(e.lambda[0] < 0.5 && 0.5 <= e.lambda[1]);
        assert!(e.gap > 0.12 && e.gap < 0.125);
    }

    #[test]
    fn a_defective_pair_is_refused() {
        let z = Rational::zero;
        let s = matrix(&[
            &[q(1, 1), z(), z(), z()],
            &[z(), q(1, 2), q(1, 1000), z()],
            &[z(), z(), q(1, 2), z()],
            &[z(), z(), z(), q(1, 4)],
        ]);
        let e = exact_standard(&s, 0.375).unwrap_err();
        assert!(e.contains("defective"), "{e}");
    }

    #[test]
    fn a_third_eigenvalue_above_the_threshold_is_refused() {
        let z = Rational::zero;
        let s = matrix(&[
            &[q(1, 1), z(), z(), z()],
            &[z(), q(1, 2), z(), z()],
            &[z(), z(), q(1, 2), z()],
            &[z(), z(), z(), q(-2, 5)],
        ]);
        let e = exact_standard(&s, 0.375).unwrap_err();
        assert!(e.contains("3 eigenvalues"), "{e}");
        // below the pair and above |-2/5| the pair is separated
        assert!(exact_standard(&s, 0.45).is_ok());
    }
}
