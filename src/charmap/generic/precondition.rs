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
//!    is 2-dimensional; where `lambda`'s polynomial is beyond
//!    [`MAX_FIELD_DEGREE`], by the rotation of the sectors instead
//!    ([`eigenspace_by_symmetry`]).
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
    exact_standard_turned(s, t, None)
}

/// [`exact_standard`] with the rotation of the configuration by one sector
/// (`turn[k]`: the index point `k` moves to, [`rotation`]), which decides
/// step 4 by symmetry ([`eigenspace_by_symmetry`]) where `lambda`'s
/// polynomial is beyond [`MAX_FIELD_DEGREE`].
pub fn exact_standard_turned(
    s: &DMatrix<Rational>,
    t: f64,
    turn: Option<&[usize]>,
) -> Result<ExactStandard, String> {
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
        Some(r) => Some(Poly::new(vec![-r, one.clone()])),
        None if multiple.degree().unwrap_or(0) <= MAX_FIELD_DEGREE => Some(multiple.clone()),
        None => None,
    };
    let rank = match (field, turn) {
        (Some(field), _) => rank_at_root(s, &field, &lo, &hi),
        (None, Some(turn)) => {
            eigenspace_by_symmetry(s, turn, &multiple, &lo, &hi)?;
            dim - 2
        }
        (None, None) => {
            return Err(format!(
                "the double eigenvalue is irrational and its polynomial has degree {} (the exact rank stops at {MAX_FIELD_DEGREE})",
                multiple.degree().unwrap_or(0)
            ))
        }
    };
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

/// The rotation of a vertex-centred configuration of valence `n` by one
/// sector: `turn[k]` is the index of the point that point `k` moves to
/// (`(s, i, j)` to `(s + 1, i, j)`, the centre fixed); `None` when a label
/// has no place on the sector grid or its image is not a point of the
/// configuration.
pub fn rotation(labels: &[crate::schemes::PointLabel], n: usize) -> Option<Vec<usize>> {
    use super::layout::{label_position, SectorPoint};
    let pos: Vec<SectorPoint> = labels
        .iter()
        .map(|l| label_position(*l, n))
        .collect::<Option<_>>()?;
    pos.iter()
        .map(|p| {
            let image = match *p {
                SectorPoint::Centre => SectorPoint::Centre,
                SectorPoint::In { s, i, j } => SectorPoint::In {
                    s: (s + 1) % n,
                    i,
                    j,
                },
            };
            pos.iter().position(|q| *q == image)
        })
        .collect()
}

/// Step 4 by symmetry **\[derived\]** (math doc section 20.8): `S`
/// commutes with the permutation `P` of `turn` (checked exactly), so the
/// 2-dimensional generalised eigenspace `G` of `lambda` (steps 2 and 3)
/// splits into the modes `G_k = G ∩ ker(P - omega^k)`. The blocks of the
/// rational modes, `k = 0` and (for an even order) `k = n/2`, are rational
/// matrices on the orbits (`B_ab = sum_m c^m S[r_a, P^m r_b]`, `c = 1` or
/// `-1`); when `lambda` is a root of neither block's characteristic
/// polynomial (no root of `gcd(multiple, det(x I - B))` in `lambda`'s
/// interval `(lo, hi]`), `G` lies in the other modes. `S` and `P` are real,
/// so `G_k` and `G_{n-k}` are conjugate, of equal dimension: `G` is one pair
/// `G_k + G_{n-k}` of dimension 1 each, each an invariant line, i.e. an
/// eigenvector, and the two are independent (`omega^k != omega^-k`). So the
/// eigenspace has dimension 2. `Err` carries the reason it is not proven.
pub fn eigenspace_by_symmetry(
    s: &DMatrix<Rational>,
    turn: &[usize],
    multiple: &Poly,
    lo: &Rational,
    hi: &Rational,
) -> Result<(), String> {
    let d = s.nrows();
    if turn.len() != d || (0..d).any(|i| (0..d).any(|j| s[(turn[i], turn[j])] != s[(i, j)])) {
        return Err("the local matrix does not commute with the rotation of its sectors".into());
    }
    // the orbits of the rotation: a representative and the length
    let mut seen = vec![false; d];
    let mut orbits: Vec<(usize, usize)> = Vec::new();
    for k in 0..d {
        if seen[k] {
            continue;
        }
        let (mut x, mut len) = (k, 0);
        while !seen[x] {
            seen[x] = true;
            x = turn[x];
            len += 1;
        }
        if x != k {
            return Err("the rotation of the sectors is not a permutation".into());
        }
        orbits.push((k, len));
    }
    let order = orbits.iter().map(|o| o.1).max().unwrap_or(1);
    let characters: &[i64] = if order % 2 == 0 { &[1, -1] } else { &[1] };
    for &c in characters {
        // the orbits that carry a vector of the mode (c^len = 1)
        let valid: Vec<(usize, usize)> = orbits
            .iter()
            .copied()
            .filter(|o| c == 1 || o.1 % 2 == 0)
            .collect();
        let m = valid.len();
        let mut b = DMatrix::<Rational>::from_element(m, m, Rational::zero());
        for (a, &(ra, _)) in valid.iter().enumerate() {
            for (bb, &(rb, len)) in valid.iter().enumerate() {
                let (mut x, mut sign) = (rb, Rational::one());
                for _ in 0..len {
                    b[(a, bb)] += &sign * &s[(ra, x)];
                    x = turn[x];
                    sign *= Rational::from_integer(c.into());
                }
            }
        }
        let g = multiple.gcd(&charpoly(&b));
        if g.degree().unwrap_or(0) > 0 && Sturm::new(&g).count(lo, hi) > 0 {
            return Err(format!(
                "the double eigenvalue is an eigenvalue of the rotation's mode {} (its eigenspace is not proven 2-dimensional)",
                if c == 1 { "0".to_owned() } else { format!("{}", order / 2) }
            ));
        }
    }
    Ok(())
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

    /// Valence 3: the centre (eigenvalue 1) and two orbits `e_k`, `g_k`
    /// (indices `1 + k`, `4 + k`), each row of an orbit the circulant
    /// `a p_k + b (p_{k-1} + p_{k+1})` (mode 0: `a + 2b`, modes 1 and 2:
    /// `a - b`), the `e` rows also `w` on every `g`. Returns the matrix and
    /// the rotation.
    fn circulant(e: (i64, i64), g: (i64, i64), w: Rational) -> (DMatrix<Rational>, Vec<usize>) {
        let q = |a: i64| Rational::new(a.into(), 8.into());
        let mut s = DMatrix::from_element(7, 7, Rational::zero());
        s[(0, 0)] = Rational::one();
        for k in 0..3 {
            for (base, (a, b)) in [(1, e), (4, g)] {
                s[(base + k, base + k)] = q(a);
                s[(base + k, base + (k + 1) % 3)] = q(b);
                s[(base + k, base + (k + 2) % 3)] = q(b);
            }
            for m in 0..3 {
                s[(1 + k, 4 + m)] = w.clone();
            }
        }
        let turn = vec![0, 2, 3, 1, 5, 6, 4];
        (s, turn)
    }

    #[test]
    fn symmetry_proves_the_eigenspace_of_a_pair_of_modes() {
        // e: a = 1/2, b = 1/8: modes 1, 2 at 3/8 (one eigenvector each)
        let (s, turn) = circulant((4, 1), (0, 0), Rational::zero());
        let lambda = Rational::new(3.into(), 8.into());
        let multiple = Poly::new(vec![-lambda.clone(), Rational::one()]);
        let lo = &lambda - Rational::new(1.into(), 64.into());
        assert!(eigenspace_by_symmetry(&s, &turn, &multiple, &lo, &lambda).is_ok());
        // a matrix that does not commute with the rotation is refused
        let mut t = s.clone();
        t[(1, 2)] += Rational::one();
        assert!(eigenspace_by_symmetry(&t, &turn, &multiple, &lo, &lambda).is_err());
    }

    #[test]
    fn symmetry_refuses_a_double_eigenvalue_of_mode_zero() {
        // e and g: a = 1/4, b = 1/8: mode 0 at 1/2 on both orbits, coupled
        // by 1/3 on every g: the mode-0 block [[1/2, 1], [0, 1/2]] is a
        // Jordan block (modes 1, 2: 1/8, uncoupled)
        let (s, turn) = circulant((2, 1), (2, 1), Rational::new(1.into(), 3.into()));
        let lambda = Rational::new(1.into(), 2.into());
        let multiple = Poly::new(vec![-lambda.clone(), Rational::one()]);
        let lo = &lambda - Rational::new(1.into(), 64.into());
        let e = eigenspace_by_symmetry(&s, &turn, &multiple, &lo, &lambda).unwrap_err();
        assert!(e.contains("mode 0"), "{e}");
        // and the rank agrees: a 1-dimensional eigenspace
        assert_eq!(rank_at_root(&s, &multiple, &lo, &lambda), 6);
    }
}
