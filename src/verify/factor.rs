//! The quadratic-factor route (math doc section 15): verdicts over a cell
//! for face blocks whose deflated block `C(r)` has size `m >= 4`
//! (`n >= 5`).
//!
//! **Characteristic polynomial.** `P(z; r) = det(z I - C(r)) = z^m +
//! sum_{j < m} p_j(r) z^j`, with each `p_j` a polynomial in the ratios with
//! dyadic coefficients. It is expanded once per valence, exactly in
//! integers: `4 C(r)` has integer entries affine in `r`, and
//! `det(w I - 4 C(r)) = sum_j 4^(m-j) p_j(r) w^j` (cofactor expansion over
//! column subsets, checked `i128` arithmetic), so `p_j` is that integer
//! polynomial divided by a power of two (exact in `f64`, checked). Over a
//! cell each `p_j(x0 + d)` is a second-order [`Taylor`] form: value,
//! gradient and Hessian at the centre in interval arithmetic, and the terms
//! of order three and more of every monomial bounded by those of the
//! expansion of `prod_i (|x_i| + t h_i)` at `t = 1` (a dominating series).
//!
//! **Factorisation.** `m` is even (`m = n - 1` for odd `n`, `n - 2` after
//! the removal of `1/4` for even `n`), and `P = prod_{i < m/2} (z^2 +
//! alpha_i z + beta_i)` with real coefficients whenever the roots are
//! grouped into conjugate or real pairs. At the centre the numerical
//! eigenvalues, sorted by modulus, are grouped that way (pair 0 is the
//! subdominant pair), giving `x~ = (alpha_i, beta_i)`; one Newton step
//! refines it. `F(x, d) = coeffs(prod_i Q_i) - coeffs(P(.; x0 + d))`
//! (degrees `0 .. m-1`) vanishes at the factorisation. Its Jacobian in `x`
//! is the generalised Sylvester matrix of the factors (columns
//! `z prod_{l != i} Q_l` and `prod_{l != i} Q_l`), invertible exactly when
//! the factors are pairwise coprime.
//!
//! **Parametric Krawczyk test with a Taylor model.** With `Y ~ J(x~)^-1`,
//! `S = Y dP/dd` and `T = -Y (quadratic part of F(x~ + S d, d))`, the model
//! `x^(d) = x~ + S d + d^T T d` makes `F(x^(d), d)` of third order in `d`.
//! Let `E = [-eps, eps]` and `X` the interval hull of `x^(d) + E` over the
//! cell. If
//!
//! ```text
//! K = range(-Y F(x^(d), d)) + (I - Y J(X)) E   lies inside   (-eps, eps)
//! ```
//!
//! then for every `d` of the cell the Krawczyk operator of `F(., d)` on the
//! box `x^(d) + E` maps it into itself, so `F(., d)` has a zero there
//! (Krawczyk 1969; Moore, Kearfott, Cloud, *Introduction to Interval
//! Analysis*, 2009, section 8.2): `P(.; x0 + d)` is exactly the product of
//! quadratics with coefficients in `x^(d) + E`. Every factor coefficient is
//! then a second-order Taylor form with remainder `eps_i`.
//!
//! **Verdicts** (math doc section 15): the roots of `z^2 + alpha z + beta`
//! lie in the open disc `|z| < rho` iff `Q(rho) > 0`, `Q(-rho) > 0` and
//! `|beta| < rho^2` (Jury's test), both outside the closed disc iff
//! `Q(+-rho) > 0` and `beta > rho^2` (Jury's test on the reversed
//! polynomial), exactly one inside iff `Q(rho) Q(-rho) < 0`. Counting the
//! eigenvalues of `C` outside `rho = 1` (none: `lambda_0 = 1` is simple),
//! outside a threshold `rho >= 1/4` (exactly two: separation), and outside
//! `1/4` (at most one: not separated), and the sign of the discriminant
//! `alpha^2/4 - beta` of the factor that holds the two (`< 0`: complex pair;
//! `> 0` with `alpha < 0`: two positive reals) gives the verdicts.

use super::decide::{SpectralVerdict, Status, FIXED_MODULUS};
use super::enclose::{centre_and_half_widths, AffineFamily, Tamper};
use super::interval::{up, Iv};
use super::taylor2::Taylor;
use crate::spectral::eigen::{Eigen, EigenOptions};
use crate::spectral::ClassName;
use nalgebra::DMatrix;
use std::collections::BTreeMap;

/// Largest deflated block size `m` of the factor route: the cofactor
/// expansion visits `2^m` column subsets, and the coefficient polynomials
/// grow quickly with `m` (`n <= 10`). Above it the disc route is used.
pub const MAX_FACTOR_DIM: usize = 8;

/// Attempts of the epsilon inflation of the Krawczyk test.
const KRAWCZYK_ATTEMPTS: usize = 6;

/// Factor of the epsilon inflation: the next radius is this times the
/// bound `K` of the previous attempt (a heuristic: any radius the test
/// accepts is valid).
const KRAWCZYK_INFLATION: f64 = 1.25;

/// One monomial `coef * prod_i r_{vars[i]}` (variables repeated for powers).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Monomial {
    pub(super) coef: f64,
    pub(super) vars: Vec<u8>,
}

/// The characteristic polynomial of an affine family, coefficient by
/// coefficient as exact polynomials in the parameters (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct CharPoly {
    pub(super) m: usize,
    pub(super) k: usize,
    /// `p_j`, `j = 0 .. m-1` (the leading coefficient is 1).
    pub(super) coeffs: Vec<Vec<Monomial>>,
}

/// A sparse polynomial in `(w, r_0, .., r_{k-1})`: exponents -> coefficient.
type Poly = BTreeMap<Vec<u8>, i128>;

fn poly_mul(a: &Poly, b: &Poly) -> Option<Poly> {
    let mut out = Poly::new();
    for (ea, ca) in a {
        for (eb, cb) in b {
            let e: Vec<u8> = ea.iter().zip(eb).map(|(x, y)| x + y).collect();
            let v = ca.checked_mul(*cb)?;
            let slot = out.entry(e).or_insert(0);
            *slot = slot.checked_add(v)?;
        }
    }
    out.retain(|_, v| *v != 0);
    Some(out)
}

fn poly_add_scaled(acc: &mut Poly, p: &Poly, sign: i128) -> Option<()> {
    for (e, c) in p {
        let slot = acc.entry(e.clone()).or_insert(0);
        *slot = slot.checked_add(c.checked_mul(sign)?)?;
    }
    acc.retain(|_, v| *v != 0);
    Some(())
}

impl CharPoly {
    /// Expands `det(z I - C(x))` of the family; `None` when the size is
    /// odd, below 4 or above [`MAX_FACTOR_DIM`], or a coefficient is not
    /// exact (never for the NURDS families).
    ///
    /// ```
    /// use subdiv_lab::verify::enclose::AffineFamily;
    /// use subdiv_lab::verify::factor::CharPoly;
    /// let f = AffineFamily::nurds(5);
    /// let p = &CharPoly::new(&f).unwrap();
    /// // the trace of C is 7/4 for every ratio vector: p_3 = -7/4
    /// assert_eq!(p.eval(3, &[0.3, 0.6, 0.2, 0.9, 0.5]), -1.75);
    /// ```
    pub fn new(family: &AffineFamily) -> Option<Self> {
        let m = family.dim();
        let k = family.params();
        if m < 4 || m % 2 != 0 || m > MAX_FACTOR_DIM || k > 200 {
            return None;
        }
        let vars = k + 1;
        // entries of w I - 4 C(r) as polynomials
        let int = |v: f64| -> Option<i128> {
            let s = 4.0 * v;
            (s.fract() == 0.0 && s.abs() < 1e15).then_some(s as i128)
        };
        let mut entry: Vec<Poly> = vec![Poly::new(); m * m];
        for a in 0..m {
            for b in 0..m {
                let e = &mut entry[a * m + b];
                let c = int(family.constant(a, b))?;
                if c != 0 {
                    e.insert(vec![0; vars], -c);
                }
                if a == b {
                    let mut x = vec![0; vars];
                    x[0] = 1;
                    e.insert(x, 1);
                }
            }
        }
        for (p, t) in family.terms().iter().enumerate() {
            for &(a, b, v) in t {
                let c = int(v)?;
                let mut x = vec![0u8; vars];
                x[1 + p] = 1;
                let slot = entry[a * m + b].entry(x).or_insert(0);
                *slot = slot.checked_sub(c)?;
            }
        }
        for e in &mut entry {
            e.retain(|_, v| *v != 0);
        }
        // det by expansion along the last row of each leading block:
        // f(S) = det(rows 0..|S|, columns S)
        let mut f: Vec<Poly> = vec![Poly::new(); 1 << m];
        f[0].insert(vec![0; vars], 1);
        for s in 1usize..(1 << m) {
            let row = s.count_ones() as usize - 1;
            let mut acc = Poly::new();
            let mut pos = 0;
            for col in 0..m {
                if s & (1 << col) == 0 {
                    continue;
                }
                let sub = &f[s & !(1 << col)];
                if !sub.is_empty() && !entry[row * m + col].is_empty() {
                    let prod = poly_mul(&entry[row * m + col], sub)?;
                    let sign = if (row + pos) % 2 == 0 { 1 } else { -1 };
                    poly_add_scaled(&mut acc, &prod, sign)?;
                }
                pos += 1;
            }
            f[s] = acc;
        }
        let det = &f[(1 << m) - 1];
        let mut coeffs: Vec<Vec<Monomial>> = vec![Vec::new(); m];
        for (e, &c) in det {
            let j = e[0] as usize;
            if j == m {
                // the leading term w^m
                if c != 1 || e[1..].iter().any(|&x| x != 0) {
                    return None;
                }
                continue;
            }
            // p_j = c / 4^(m - j), exact when |c| < 2^53
            if c.unsigned_abs() >= 1u128 << 53 {
                return None;
            }
            let coef = c as f64 / 4f64.powi((m - j) as i32);
            let mut v = Vec::new();
            for (p, &x) in e[1..].iter().enumerate() {
                for _ in 0..x {
                    v.push(p as u8);
                }
            }
            coeffs[j].push(Monomial { coef, vars: v });
        }
        Some(CharPoly { m, k, coeffs })
    }

    /// Degree `m`.
    pub fn degree(&self) -> usize {
        self.m
    }

    /// `p_j(x)` in floating point (for tests and the centre guess).
    pub fn eval(&self, j: usize, x: &[f64]) -> f64 {
        self.coeffs[j]
            .iter()
            .map(|mo| mo.coef * mo.vars.iter().map(|&v| x[v as usize]).product::<f64>())
            .sum()
    }

    /// Second-order Taylor forms of `p_j(x0 + d)`, `|d_i| <= h_i`, for
    /// `j = 0 .. m-1` (module docs).
    pub fn forms(&self, x0: &[f64], h: &[f64]) -> Vec<Taylor> {
        polynomial_forms(&self.coeffs, self.k, x0, h)
    }
}

/// Second-order Taylor forms over the cell `|d_i| <= h_i` around `x0` (`k`
/// variables) of the polynomials `polys`, each a sum of monomials
/// ([`monomial_form`]): the characteristic polynomial's coefficients here,
/// the invariants in [`super::invariants`].
pub(super) fn polynomial_forms(
    polys: &[Vec<Monomial>],
    k: usize,
    x0: &[f64],
    h: &[f64],
) -> Vec<Taylor> {
    let nq = k * (k + 1) / 2;
    polys
        .iter()
        .map(|mons| {
            let mut c = Iv::point(0.0);
            let mut g = vec![Iv::point(0.0); k];
            let mut q = vec![Iv::point(0.0); nq];
            let mut rem = 0.0;
            for mo in mons {
                monomial_form(mo, x0, h, &mut c, &mut g, &mut q, &mut rem);
            }
            Taylor::from_parts(c, g, q, rem)
        })
        .collect()
}

/// Adds the second-order expansion of one monomial at `x0` to the parts
/// (`rem` gets the bound of its terms of order three and more).
pub(super) fn monomial_form(
    mo: &Monomial,
    x0: &[f64],
    h: &[f64],
    c: &mut Iv,
    g: &mut [Iv],
    q: &mut [Iv],
    rem: &mut f64,
) {
    // degrees are at most MAX_FACTOR_DIM (a coefficient of a polynomial of
    // degree m <= MAX_FACTOR_DIM in an affine family)
    const D: usize = MAX_FACTOR_DIM + 1;
    let len = mo.vars.len();
    debug_assert!(len < D);
    let var = |i: usize| mo.vars[i] as usize;
    let x = |i: usize| Iv::point(x0[var(i)]);
    // pre[i] = coef * x_0 .. x_{i-1}, suf[i] = x_i .. x_{len-1}
    let mut pre = [Iv::point(0.0); D];
    let mut suf = [Iv::point(1.0); D];
    pre[0] = Iv::point(mo.coef);
    for i in 0..len {
        pre[i + 1] = pre[i].mul(x(i));
    }
    for i in (0..len).rev() {
        suf[i] = suf[i + 1].mul(x(i));
    }
    *c = c.add(pre[len]);
    for i in 0..len {
        g[var(i)] = g[var(i)].add(pre[i].mul(suf[i + 1]));
        // between: x_{i+1} .. x_{l-1}
        let mut between = pre[i];
        for l in i + 1..len {
            let (a, b) = (var(i).min(var(l)), var(i).max(var(l)));
            let t = b * (b + 1) / 2 + a;
            q[t] = q[t].add(between.mul(suf[l + 1]));
            between = between.mul(x(l));
        }
    }
    if len >= 3 {
        // e_j: coefficient of t^j in prod_i (|x_i| + t h_i), rounded up
        let mut e = [0.0f64; D + 1];
        e[0] = 1.0;
        for i in 0..len {
            let (a, b) = (x0[var(i)].abs(), h[var(i)]);
            for j in (1..=i + 1).rev() {
                e[j] = up(up(e[j] * a) + up(e[j - 1] * b));
            }
            e[0] = up(e[0] * a);
        }
        let tail = e[3..=len].iter().fold(0.0, |s, &x| up(s + x));
        *rem = up(*rem + up(tail * mo.coef.abs()));
    }
}

/// Lower-degree coefficients of the product of two monic polynomials given
/// by their lower coefficients (`u` of degree `u.len()`, `v` likewise), in
/// any coefficient arithmetic: `zero`, `add` and `mul` (the same order of
/// operations for every type, so the `f64`, interval and Taylor products
/// bound one another term by term).
fn monic_product<T>(
    u: &[T],
    v: &[T],
    zero: impl Fn() -> T,
    add: impl Fn(&T, &T) -> T,
    mul: impl Fn(&T, &T) -> T,
) -> Vec<T> {
    let (a, b) = (u.len(), v.len());
    (0..a + b)
        .map(|t| {
            let mut s = zero();
            if t >= b {
                s = add(&s, &u[t - b]);
            }
            if t >= a {
                s = add(&s, &v[t - a]);
            }
            for i in 0..a.min(t + 1) {
                if t - i < b {
                    s = add(&s, &mul(&u[i], &v[t - i]));
                }
            }
            s
        })
        .collect()
}

/// [`monic_product`] in `f64`.
fn monic_mul_f(u: &[f64], v: &[f64]) -> Vec<f64> {
    monic_product(u, v, || 0.0, |x, y| x + y, |x, y| x * y)
}

/// [`monic_product`] in interval arithmetic.
fn monic_mul_iv(u: &[Iv], v: &[Iv]) -> Vec<Iv> {
    monic_product(u, v, || Iv::point(0.0), |x, y| x.add(*y), |x, y| x.mul(*y))
}

/// [`monic_product`] of second-order Taylor forms over the cell `h`.
fn monic_mul_t(u: &[Taylor], v: &[Taylor], h: &[f64]) -> Vec<Taylor> {
    monic_product(
        u,
        v,
        || Taylor::constant(0.0, h.len()),
        |x, y| x.add(y),
        |x, y| x.mul(y, h),
    )
}

/// The lower coefficients of `prod_{l != skip} Q_l` (of all factors when
/// `skip` is out of range), each factor `[alpha, beta]` standing for
/// `z^2 + alpha z + beta`; `mul` multiplies two monic polynomials given by
/// their lower coefficients.
fn product_except<T: Clone>(
    factors: &[[T; 2]],
    skip: usize,
    mul: impl Fn(&[T], &[T]) -> Vec<T>,
) -> Vec<T> {
    let mut acc: Option<Vec<T>> = None;
    for (l, f) in factors.iter().enumerate() {
        if l == skip {
            continue;
        }
        let low = vec![f[1].clone(), f[0].clone()];
        acc = Some(match acc {
            None => low,
            Some(a) => mul(&a, &low),
        });
    }
    acc.unwrap_or_default()
}

/// The lower coefficients of `z^2 + alpha z + beta`: `[beta, alpha]`.
#[cfg(test)]
fn quad_lower(alpha: f64, beta: f64) -> [f64; 2] {
    [beta, alpha]
}

/// Jacobian of `F` in the unknowns `(alpha_0, beta_0, alpha_1, ..)` from
/// the lower coefficients of `prod_{l != i} Q_l` (column of `beta_i`; the
/// `alpha_i` column is that polynomial times `z`); rows are degrees
/// `0 .. m-1`.
fn jacobian<T: Clone>(rest: &[Vec<T>], m: usize, zero: T, one: T) -> Vec<T> {
    let mut j = vec![zero.clone(); m * m];
    for (i, r) in rest.iter().enumerate() {
        // prod_{l != i} Q_l = z^(m-2) + sum_t r_t z^t
        for t in 0..m {
            let beta_col = if t < m - 2 {
                r[t].clone()
            } else if t == m - 2 {
                one.clone()
            } else {
                zero.clone()
            };
            let alpha_col = if t == 0 {
                zero.clone()
            } else if t - 1 < m - 2 {
                r[t - 1].clone()
            } else {
                one.clone()
            };
            j[t * m + 2 * i] = alpha_col;
            j[t * m + 2 * i + 1] = beta_col;
        }
    }
    j
}

/// A second-order form with float coefficients (no remainder): the guess
/// of the model, never a bound.
#[derive(Clone, Debug)]
struct Quad {
    c: f64,
    g: Vec<f64>,
    q: Vec<f64>,
}

impl Quad {
    fn zero(k: usize) -> Quad {
        Quad {
            c: 0.0,
            g: vec![0.0; k],
            q: vec![0.0; k * (k + 1) / 2],
        }
    }

    fn add(&self, o: &Quad) -> Quad {
        Quad {
            c: self.c + o.c,
            g: self.g.iter().zip(&o.g).map(|(a, b)| a + b).collect(),
            q: self.q.iter().zip(&o.q).map(|(a, b)| a + b).collect(),
        }
    }

    /// Product truncated after the second order.
    fn mul(&self, o: &Quad) -> Quad {
        let k = self.g.len();
        let mut q = Vec::with_capacity(self.q.len());
        for kk in 0..k {
            for j in 0..=kk {
                let t = kk * (kk + 1) / 2 + j;
                let mut v = self.c * o.q[t] + o.c * self.q[t] + self.g[j] * o.g[kk];
                if j != kk {
                    v += self.g[kk] * o.g[j];
                }
                q.push(v);
            }
        }
        Quad {
            c: self.c * o.c,
            g: (0..k).map(|i| self.c * o.g[i] + o.c * self.g[i]).collect(),
            q,
        }
    }

    fn monic_mul(u: &[Quad], v: &[Quad]) -> Vec<Quad> {
        let k = u.first().or(v.first()).map_or(0, |x| x.g.len());
        monic_product(u, v, || Quad::zero(k), |x, y| x.add(y), |x, y| x.mul(y))
    }
}

/// The verdicts of the factor route over a cell, or `None` when the route
/// does not apply (family not factorable, numerical failure, Krawczyk test
/// failed): the caller then uses the disc route. The second value gives
/// the per-parameter shares of an undecided quantity (split choice).
pub fn decide(
    poly: &CharPoly,
    family: &AffineFamily,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Option<(SpectralVerdict, Option<Vec<f64>>)> {
    let f = factor_forms(poly, family, lo, hi, tamper)?;
    let cell = Cell { h: &f.h };
    let (v, why) = verdict(&f.factors, &f.moduli, &cell);
    Some((v, why.map(|t| t.scores(&f.h))))
}

/// The proven factorisation over a cell (module docs).
#[derive(Clone, Debug)]
pub struct Factors {
    /// Per factor `z^2 + alpha z + beta`: `[alpha, beta]` as Taylor forms
    /// over the cell (the remainders include the Krawczyk radius); factor 0
    /// holds the two largest eigenvalues at the centre.
    pub factors: Vec<[Taylor; 2]>,
    /// The moduli of the numerical eigenvalues at the centre, decreasing.
    pub moduli: Vec<f64>,
    /// The half-widths of the cell the forms hold on.
    pub h: Vec<f64>,
}

/// Proves `P(.; r) = prod_i (z^2 + alpha_i(r) z + beta_i(r))` over the cell
/// with each coefficient in its Taylor form (module docs), or `None`.
pub fn factor_forms(
    poly: &CharPoly,
    family: &AffineFamily,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Option<Factors> {
    let m = poly.m;
    let k = poly.k;
    if lo.len() != k || hi.len() != k {
        return None;
    }
    let (x0, mut h) = centre_and_half_widths(lo, hi);
    if tamper == Tamper::DropVariation {
        h = vec![0.0; k];
    }
    let p = poly.forms(&x0, &h);
    // numerical eigenvalues at the centre
    let cm = DMatrix::from_row_slice(m, m, &family.at(&x0));
    let eig = Eigen::new(&cm, EigenOptions::VALUES).ok()?;
    solve(p, h, eig.values().to_vec())
}

/// The eigenvalues of the companion matrix of `z^m + sum_j c_j z^j`.
pub(super) fn companion_roots(c: &[f64]) -> Option<Vec<num_complex::Complex64>> {
    let m = c.len();
    let mut a = DMatrix::zeros(m, m);
    for i in 1..m {
        a[(i, i - 1)] = 1.0;
    }
    for (i, v) in c.iter().enumerate() {
        a[(i, m - 1)] = -v;
    }
    Some(Eigen::new(&a, EigenOptions::VALUES).ok()?.values().to_vec())
}

/// The factorisation of `z^m + sum_j p_j z^j`, `p_j` Taylor forms over the
/// cell of half-widths `h`, from the numerical roots at its centre
/// (module docs), or `None`.
pub(super) fn solve(
    p: Vec<Taylor>,
    h: Vec<f64>,
    mut vals: Vec<num_complex::Complex64>,
) -> Option<Factors> {
    let m = p.len();
    let k = h.len();
    let nf = m / 2;
    if m % 2 != 0 || vals.len() != m || vals.iter().any(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        return None;
    }
    vals.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
    let mods: Vec<f64> = vals.iter().map(|z| z.norm()).collect();
    let mut used = vec![false; m];
    let mut factors: Vec<[f64; 2]> = Vec::with_capacity(nf); // [alpha, beta]
    for i in 0..m {
        if used[i] {
            continue;
        }
        used[i] = true;
        let z = vals[i];
        let complex = z.im.abs() > 1e-12 * z.norm().max(1e-300);
        let partner = (i + 1..m).filter(|&l| !used[l]).find(|&l| {
            let w = vals[l];
            let w_complex = w.im.abs() > 1e-12 * w.norm().max(1e-300);
            if complex {
                w_complex && (w - z.conj()).norm() <= 1e-8 * z.norm().max(1.0)
            } else {
                !w_complex
            }
        })?;
        used[partner] = true;
        let w = vals[partner];
        if complex {
            factors.push([-2.0 * z.re, z.norm_sqr()]);
        } else {
            factors.push([-(z.re + w.re), z.re * w.re]);
        }
    }
    let mid = |v: Iv| 0.5 * v.lo + 0.5 * v.hi;
    let p_mid: Vec<f64> = p.iter().map(|t| mid(t.c)).collect();
    let residual = |fs: &[[f64; 2]]| -> Vec<f64> {
        let prod = product_except(fs, usize::MAX, monic_mul_f);
        prod.iter().zip(&p_mid).map(|(a, b)| a - b).collect()
    };
    let jac_f = |fs: &[[f64; 2]]| -> DMatrix<f64> {
        let rest: Vec<Vec<f64>> = (0..nf)
            .map(|i| product_except(fs, i, monic_mul_f))
            .collect();
        DMatrix::from_row_slice(m, m, &jacobian(&rest, m, 0.0, 1.0))
    };
    // one Newton step
    let y = jac_f(&factors).try_inverse()?;
    let r = residual(&factors);
    for (i, f) in factors.iter_mut().enumerate() {
        for (t, v) in f.iter_mut().enumerate() {
            let row = 2 * i + t;
            *v -= (0..m).map(|j| y[(row, j)] * r[j]).sum::<f64>();
        }
    }
    let y = jac_f(&factors).try_inverse()?;
    if y.iter().any(|v| !v.is_finite()) {
        return None;
    }
    // the model x^(d) = x~ + S d + d^T T d, in floating point (a guess)
    let nq = k * (k + 1) / 2;
    let mut s = vec![0.0; m * k];
    for a in 0..m {
        for kk in 0..k {
            s[a * k + kk] = (0..m).map(|j| y[(a, j)] * mid(p[j].g[kk])).sum();
        }
    }
    let first: Vec<[Quad; 2]> = (0..nf)
        .map(|i| {
            let mk = |row: usize, c: f64| Quad {
                c,
                g: s[row * k..(row + 1) * k].to_vec(),
                q: vec![0.0; nq],
            };
            [mk(2 * i, factors[i][0]), mk(2 * i + 1, factors[i][1])]
        })
        .collect();
    let prod = product_except(&first, usize::MAX, Quad::monic_mul);
    let mut t = vec![vec![0.0; nq]; m];
    for (a, ta) in t.iter_mut().enumerate() {
        for (j, pj) in prod.iter().enumerate() {
            let yaj = y[(a, j)];
            for (idx, tv) in ta.iter_mut().enumerate() {
                *tv -= yaj * (pj.q[idx] - mid(p[j].q[idx]));
            }
        }
    }
    let xm: Vec<[Taylor; 2]> = (0..nf)
        .map(|i| {
            let mk = |row: usize, c: f64| {
                Taylor::from_parts(
                    Iv::point(c),
                    s[row * k..(row + 1) * k]
                        .iter()
                        .map(|&v| Iv::point(v))
                        .collect(),
                    t[row].iter().map(|&v| Iv::point(v)).collect(),
                    0.0,
                )
            };
            [mk(2 * i, factors[i][0]), mk(2 * i + 1, factors[i][1])]
        })
        .collect();
    // rigorous: F(x^(d), d) over the cell, then -Y F by magnitudes (each
    // component of F is already of third order: the model cancels the
    // linear and quadratic parts)
    let prod = product_except(&xm, usize::MAX, |u, v| monic_mul_t(u, v, &h));
    let f_mag: Vec<f64> = prod
        .iter()
        .zip(&p)
        .map(|(a, b)| a.sub(b).range(&h).mag())
        .collect();
    let mut z_mag = vec![0.0f64; m];
    for (a, za) in z_mag.iter_mut().enumerate() {
        for (j, fj) in f_mag.iter().enumerate() {
            *za = up(*za + Iv::point(y[(a, j)].abs()).mul(Iv::point(*fj)).hi);
        }
    }
    if z_mag.iter().any(|v| !v.is_finite()) {
        return None;
    }
    // I - Y J(x^(d)) as Taylor forms over the cell: the coefficients of the
    // factors move together (their sum is the trace), which an interval
    // Jacobian over the hull of x^(d) would forget
    let zero_t = Taylor::constant(0.0, k);
    let one_t = Taylor::constant(1.0, k);
    let rest_t: Vec<Vec<Taylor>> = (0..nf)
        .map(|i| product_except(&xm, i, |u, v| monic_mul_t(u, v, &h)))
        .collect();
    let jac_t = jacobian(&rest_t, m, zero_t, one_t);
    let mut m_mag = vec![0.0f64; m * m];
    for a in 0..m {
        for b in 0..m {
            let parts: Vec<(f64, &Taylor)> =
                (0..m).map(|j| (-y[(a, j)], &jac_t[j * m + b])).collect();
            let delta = Iv::point(if a == b { 1.0 } else { 0.0 });
            m_mag[a * m + b] = combo(&parts, delta).range(&h).mag();
        }
    }
    if m_mag.iter().any(|v| !v.is_finite()) {
        return None;
    }
    // ranges of the model over the cell
    let x_range: Vec<Iv> = (0..m).map(|a| xm[a / 2][a % 2].range(&h)).collect();
    let mut eps: Vec<f64> = z_mag
        .iter()
        .map(|&v| up(up(2.0 * v) + f64::MIN_POSITIVE))
        .collect();
    let mut ok = false;
    for _ in 0..KRAWCZYK_ATTEMPTS {
        // J(x^ + e) - J(x^) = J'(xi)[e], xi in X = x_range + E: column b of
        // factor i gets, per other factor l, eps(alpha_l) |z R_il| +
        // eps(beta_l) |R_il| (shifted by one for alpha_i), with
        // R_il = prod_{l' != i, l} Q_l' over X
        let xs: Vec<[Iv; 2]> = (0..nf)
            .map(|i| {
                [
                    x_range[2 * i].widen(eps[2 * i]),
                    x_range[2 * i + 1].widen(eps[2 * i + 1]),
                ]
            })
            .collect();
        let mut dj = vec![0.0f64; m * m];
        for i in 0..nf {
            for l in (0..nf).filter(|&l| l != i) {
                let others: Vec<[Iv; 2]> = (0..nf)
                    .filter(|&q| q != i && q != l)
                    .map(|q| xs[q])
                    .collect();
                // R_il: monic of degree m - 4, lower coefficients
                let low = product_except(&others, usize::MAX, monic_mul_iv);
                let coef = |t: isize| -> f64 {
                    if t < 0 {
                        0.0
                    } else if (t as usize) < low.len() {
                        low[t as usize].mag()
                    } else if t as usize == low.len() {
                        1.0
                    } else {
                        0.0
                    }
                };
                for (col, shift) in [(2 * i, 1isize), (2 * i + 1, 0)] {
                    for row in 0..m {
                        let t = row as isize - shift;
                        let v = up(up(eps[2 * l] * coef(t - 1)) + up(eps[2 * l + 1] * coef(t)));
                        dj[row * m + col] = up(dj[row * m + col] + v);
                    }
                }
            }
        }
        let mut kv = vec![0.0f64; m];
        for a in 0..m {
            let mut acc = z_mag[a];
            for b in 0..m {
                let mut spread = 0.0f64;
                for j in 0..m {
                    spread = up(spread + up(y[(a, j)].abs() * dj[j * m + b]));
                }
                acc = up(acc + up(up(m_mag[a * m + b] * eps[b]) + spread * eps[b]));
            }
            kv[a] = acc;
        }
        if kv.iter().zip(&eps).all(|(kk, e)| kk < e) {
            ok = true;
            break;
        }
        if kv.iter().any(|v| !v.is_finite()) {
            return None;
        }
        // epsilon inflation towards the fixed point of eps -> K(eps)
        eps = kv
            .iter()
            .map(|kk| up(up(KRAWCZYK_INFLATION * kk) + f64::MIN_POSITIVE))
            .collect();
    }
    if !ok {
        return None;
    }
    let fac: Vec<[Taylor; 2]> = xm
        .into_iter()
        .enumerate()
        .map(|(i, [mut a, mut b])| {
            a.rem = up(a.rem + eps[2 * i]);
            b.rem = up(b.rem + eps[2 * i + 1]);
            [a, b]
        })
        .collect();
    Some(Factors {
        factors: fac,
        moduli: mods,
        h,
    })
}

/// The cell's half-widths, over which ranges are taken.
pub(super) struct Cell<'a> {
    pub(super) h: &'a [f64],
}

impl Cell<'_> {
    pub(super) fn range(&self, t: &Taylor) -> Iv {
        t.range(self.h)
    }
}

/// What a factor's quantities at a threshold prove: the number of its roots
/// outside the closed disc `|z| <= rho`, when known, and the undecided form.
fn count_outside(f: &[Taylor; 2], rho: f64, cell: &Cell) -> (Option<usize>, Option<Taylor>) {
    let rho2 = Iv::point(rho).mul(Iv::point(rho));
    let qp = combo(&[(rho, &f[0]), (1.0, &f[1])], rho2);
    let qm = combo(&[(-rho, &f[0]), (1.0, &f[1])], rho2);
    let (rp, rm) = (cell.range(&qp), cell.range(&qm));
    if rp.lo > 0.0 && rm.lo > 0.0 {
        let above = combo(&[(1.0, &f[1])], rho2.neg());
        let ra = cell.range(&above);
        if ra.lo > 0.0 {
            return (Some(2), None);
        }
        let below = combo(&[(1.0, &f[1])], rho2);
        if ra.hi < 0.0 && cell.range(&below).lo > 0.0 {
            return (Some(0), None);
        }
        return (None, Some(above));
    }
    if (rp.lo > 0.0 && rm.hi < 0.0) || (rp.hi < 0.0 && rm.lo > 0.0) {
        return (Some(1), None);
    }
    let why = if !(rp.lo > 0.0 || rp.hi < 0.0) {
        qp
    } else {
        qm
    };
    (None, Some(why))
}

/// `constant + sum_i s_i t_i` as one form (exact float multipliers).
pub(super) fn combo(parts: &[(f64, &Taylor)], constant: Iv) -> Taylor {
    let first = parts[0].1;
    let mut c = constant;
    let mut g = vec![Iv::point(0.0); first.g.len()];
    let mut q = vec![Iv::point(0.0); first.q.len()];
    let mut rem = 0.0;
    for &(sc, t) in parts {
        let s = Iv::point(sc);
        c = c.add(t.c.mul(s));
        for (a, b) in g.iter_mut().zip(&t.g) {
            *a = a.add(b.mul(s));
        }
        for (a, b) in q.iter_mut().zip(&t.q) {
            *a = a.add(b.mul(s));
        }
        rem = up(rem + Iv::point(t.rem).mul(Iv::point(sc.abs())).hi);
    }
    Taylor::from_parts(c, g, q, rem)
}

/// The verdicts from a proven factorisation (module docs), and the
/// quantity that left them open, if any.
pub(super) fn verdict(
    fac: &[[Taylor; 2]],
    mods: &[f64],
    cell: &Cell,
) -> (SpectralVerdict, Option<Taylor>) {
    let h = cell.h;
    let undecided = |why: Option<Taylor>| {
        (
            SpectralVerdict {
                separation: Status::Undecided,
                class: None,
            },
            why,
        )
    };
    let counts = |rho: f64| -> (Vec<Option<usize>>, Option<Taylor>) {
        let mut why = None;
        let c = fac
            .iter()
            .map(|f| {
                let (c, w) = count_outside(f, rho, cell);
                if why.is_none() {
                    why = w;
                }
                c
            })
            .collect();
        (c, why)
    };
    // lambda_0 = 1 simple: no root of C on or outside the unit circle
    let (at_one, why) = counts(1.0);
    if !at_one.iter().all(|c| *c == Some(0)) {
        return undecided(why);
    }
    let rho = if mods.len() >= 3 {
        (0.5 * mods[1] + 0.5 * mods[2]).max(FIXED_MODULUS)
    } else {
        FIXED_MODULUS
    };
    let (at_rho, why_rho) = counts(rho);
    let known: Option<Vec<usize>> = at_rho.iter().copied().collect();
    if let Some(c) = &known {
        if c.iter().sum::<usize>() == 2 {
            let separation = Status::Certified;
            let holders: Vec<usize> = (0..fac.len()).filter(|&i| c[i] > 0).collect();
            let class = if holders.len() == 1 {
                let f = &fac[holders[0]];
                let half = f[0].scale(0.5);
                let disc = half.mul(&half, h).sub(&f[1]);
                let d = cell.range(&disc);
                if d.hi < 0.0 {
                    Some(ClassName::ComplexPair)
                } else if d.lo > 0.0 && cell.range(&f[0]).hi < 0.0 {
                    Some(ClassName::RealDistinct)
                } else {
                    return (
                        SpectralVerdict {
                            separation,
                            class: None,
                        },
                        Some(disc),
                    );
                }
            } else {
                // one real root outside rho in each of two coprime factors:
                // positive iff Q(rho) < 0
                let rho2 = Iv::point(rho).mul(Iv::point(rho));
                let positive = holders.iter().all(|&i| {
                    let qp = combo(&[(rho, &fac[i][0]), (1.0, &fac[i][1])], rho2);
                    cell.range(&qp).hi < 0.0
                });
                positive.then_some(ClassName::RealDistinct)
            };
            return (SpectralVerdict { separation, class }, None);
        }
    }
    // not separated: at most one eigenvalue of C outside 1/4
    let (at_q, why_q) = counts(FIXED_MODULUS);
    if let Some(c) = at_q.iter().copied().collect::<Option<Vec<usize>>>() {
        if c.iter().sum::<usize>() <= 1 {
            return (
                SpectralVerdict {
                    separation: Status::Refuted,
                    class: Some(ClassName::NotSeparated),
                },
                None,
            );
        }
    }
    undecided(why_rho.or(why_q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn charpoly_matches_the_numerical_eigenvalues() {
        let mut rng = SplitMix64::new(3);
        for n in 5..=10 {
            let f = AffineFamily::nurds(n);
            let Some(p) = CharPoly::new(&f) else {
                assert!(f.dim() > MAX_FACTOR_DIM, "n = {n}");
                continue;
            };
            let m = p.degree();
            for _ in 0..5 {
                let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
                let c = DMatrix::from_row_slice(m, m, &f.at(&r));
                let vals = Eigen::new(&c, EigenOptions::VALUES).unwrap();
                for z in vals.values() {
                    // P(z) = z^m + sum p_j z^j vanishes at every eigenvalue
                    let mut s = num_complex::Complex64::new(1.0, 0.0);
                    for j in (0..m).rev() {
                        s = s * z + p.eval(j, &r);
                    }
                    assert!(s.norm() < 1e-10, "n = {n}: P({z}) = {s}");
                }
            }
        }
    }

    /// The expanded coefficients, evaluated in rationals, against the
    /// characteristic polynomial of the assembled face block (Hessenberg
    /// reduction in rationals): `(z - 1) (z - 1/4)^[n even] P(z)`.
    #[test]
    fn charpoly_is_exact_against_the_face_block() {
        use crate::knots::EdgeRatios;
        use crate::scalar::{f64_to_rational, Rational};
        use crate::schemes::LocalScheme;
        use crate::spectral::exact::charpoly;
        use crate::spectral::poly::Poly;
        use num_traits::One;
        let mut rng = SplitMix64::new(9);
        for n in 5..=8 {
            let f = AffineFamily::nurds(n);
            let p = &CharPoly::new(&f).unwrap();
            for _ in 0..2 {
                let r: Vec<Rational> = (0..n)
                    .map(|_| f64_to_rational(rng.uniform(0.05, 0.95)).unwrap())
                    .collect();
                let face = LocalScheme::nurds(EdgeRatios::new(r.clone()).unwrap())
                    .face_block()
                    .unwrap();
                let mut coeffs: Vec<Rational> = p
                    .coeffs
                    .iter()
                    .map(|mons| {
                        mons.iter()
                            .map(|mo| {
                                mo.vars
                                    .iter()
                                    .map(|&v| r[v as usize].clone())
                                    .fold(f64_to_rational(mo.coef).unwrap(), |a, b| a * b)
                            })
                            .fold(Rational::from_integer(0.into()), |a, b| a + b)
                    })
                    .collect();
                coeffs.push(Rational::one());
                let mut got = Poly::new(coeffs).mul(&Poly::linear(Rational::one()));
                if n % 2 == 0 {
                    got = got.mul(&Poly::linear(Rational::new(1.into(), 4.into())));
                }
                assert_eq!(got, charpoly(&face), "n = {n}");
            }
        }
    }

    /// At sampled points of a cell, the numerical quadratic factors (the
    /// eigenvalues grouped as at the centre) lie in the proven forms.
    #[test]
    fn factor_forms_contain_the_factors_at_sampled_points() {
        let mut rng = SplitMix64::new(4);
        let mut proven = 0;
        for n in 5..=8 {
            let f = AffineFamily::nurds(n);
            let p = &CharPoly::new(&f).unwrap();
            let m = f.dim();
            for _ in 0..20 {
                let lo: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.9)).collect();
                let hi: Vec<f64> = lo.iter().map(|x| x + 0.01).collect();
                let Some(fs) = factor_forms(p, &f, &lo, &hi, Tamper::None) else {
                    continue;
                };
                proven += 1;
                let (x0, _) = centre_and_half_widths(&lo, &hi);
                for _ in 0..4 {
                    let r: Vec<f64> = lo
                        .iter()
                        .zip(&hi)
                        .map(|(a, b)| rng.uniform(*a, *b))
                        .collect();
                    let d: Vec<f64> = r.iter().zip(&x0).map(|(a, b)| a - b).collect();
                    let c = DMatrix::from_row_slice(m, m, &f.at(&r));
                    let vals = Eigen::new(&c, EigenOptions::VALUES).unwrap();
                    // every eigenvalue is a root of one proven factor
                    for z in vals.values() {
                        let hit = fs.factors.iter().any(|[a, b]| {
                            let (a, b) = (a.eval_at(&d), b.eval_at(&d));
                            // |z^2 + a z + b| small for some a, b in the intervals
                            let zc = *z * *z
                                + *z * (0.5 * a.lo + 0.5 * a.hi)
                                + (0.5 * b.lo + 0.5 * b.hi);
                            let slack = z.norm() * (a.hi - a.lo) + (b.hi - b.lo);
                            zc.norm() <= slack + 1e-9
                        });
                        assert!(hit, "n = {n}: eigenvalue {z} at {r:?} in no factor");
                    }
                }
            }
        }
        assert!(proven >= 30, "{proven}");
    }

    /// Where the disc route (eigenvector basis, Gershgorin) and the factor
    /// route both decide a cell, they agree: two independent methods.
    #[test]
    fn factor_and_disc_routes_agree() {
        use super::super::decide::decide_either;
        use super::super::enclose::enclose;
        let mut rng = SplitMix64::new(8);
        let mut both = 0;
        for n in 5..=8 {
            let f = AffineFamily::nurds(n);
            let p = &CharPoly::new(&f).unwrap();
            for _ in 0..40 {
                let lo: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.9)).collect();
                let hi: Vec<f64> = lo.iter().map(|x| x + 0.01).collect();
                let (Some((a, _)), Some(e)) = (
                    decide(p, &f, &lo, &hi, Tamper::None),
                    enclose(&f, &lo, &hi, Tamper::None),
                ) else {
                    continue;
                };
                let b = decide_either(&e.rows, &e.cols);
                if a.separation != Status::Undecided && b.separation != Status::Undecided {
                    assert_eq!(a.separation, b.separation, "n = {n} at {lo:?}");
                }
                if let (Some(x), Some(y)) = (a.class, b.class) {
                    assert_eq!(x, y, "n = {n} at {lo:?}");
                    both += 1;
                }
            }
        }
        assert!(both >= 40, "{both}");
    }

    #[test]
    fn monic_products_and_jacobian_agree_with_finite_differences() {
        let fs = [
            quad_lower(-1.1, 0.3),
            quad_lower(0.2, 0.05),
            quad_lower(-0.4, 0.1),
        ];
        let as_factors: Vec<[f64; 2]> = fs.iter().map(|l| [l[1], l[0]]).collect();
        let prod = product_except(&as_factors, usize::MAX, monic_mul_f);
        // (z^2 - 1.1 z + 0.3)(z^2 + 0.2 z + 0.05)(z^2 - 0.4 z + 0.1) at z = 0.7
        let z: f64 = 0.7;
        let direct = (z * z - 1.1 * z + 0.3) * (z * z + 0.2 * z + 0.05) * (z * z - 0.4 * z + 0.1);
        let horner = prod.iter().rev().fold(1.0, |s, c| s * z + c);
        assert!((direct - horner).abs() < 1e-14);
        let m = 6;
        let rest: Vec<Vec<f64>> = (0..3)
            .map(|i| product_except(&as_factors, i, monic_mul_f))
            .collect();
        let j = jacobian(&rest, m, 0.0, 1.0);
        for col in 0..m {
            let mut pert = as_factors.clone();
            pert[col / 2][col % 2] += 1e-7;
            let p2 = product_except(&pert, usize::MAX, monic_mul_f);
            for row in 0..m {
                let fd = (p2[row] - prod[row]) / 1e-7;
                assert!((fd - j[row * m + col]).abs() < 1e-6, "({row}, {col})");
            }
        }
    }
}
