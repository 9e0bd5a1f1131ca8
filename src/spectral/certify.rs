//! Fast exact root structure for the certificates of [`super::exact`]
//! (math doc sections 4 and 7).
//!
//! The reference algorithms of [`super::exact`] (Sturm sequences, the rational
//! Schur-Cohn recursion, rank over `Q[x]/(f)`) are exact but their rational
//! coefficients grow like the subresultants (`~2 k h` bits at step `k` for
//! height `h`), which made `--exact` unusable beyond n ~ 20. This module
//! decides the same questions from a *certified root structure*:
//!
//! 1. **square-free test mod p**: with `Q` the primitive integer multiple of
//!    `q` and a prime `p` not dividing its leading coefficient,
//!    `gcd(Q mod p, Q' mod p) = 1` proves `Q` square-free over `Q` (a square
//!    factor `F^2 | Q` survives reduction: `deg F mod p = deg F`);
//! 2. **Gerschgorin inclusion disks** (B. T. Smith, *Error bounds for zeros
//!    of a polynomial based upon Gerschgorin's theorems*, JACM 17, 1970): for
//!    distinct approximations `z_1..z_m` of the roots of a degree-`m`
//!    polynomial `P` with leading coefficient `a_m`, the roots of `P` are the
//!    eigenvalues of `diag(z) - w 1^T` with Weierstrass corrections
//!    `w_i = P(z_i) / (a_m prod_{j != i} (z_i - z_j))` (Lagrange interpolation
//!    at the `z_j` and the matrix determinant lemma), so by Gerschgorin every
//!    root lies in a disk `D(z_i - w_i, (m - 1)|w_i|)`, contained in
//!    `D(z_i, m |w_i|)`, and a connected union of `k` disks holds exactly `k`
//!    roots. The `w_i` are computed exactly (dyadic approximations, integer
//!    arithmetic) and the radii rounded up to powers of two; when all disks of
//!    all square-free factors are pairwise disjoint, each holds exactly one
//!    root of the square-free part, a disk centred on the real axis holds a
//!    real root (its conjugate is in the same disk) and a disk missing the real
//!    axis a non-real one. When the disks around the `f64` approximations
//!    overlap (close roots, whose `f64` values are only accurate to about
//!    `eps^(1/k)`), the points are first moved by exact Weierstrass
//!    (Durand-Kerner) steps `z_i <- z_i - w_i`, quadratically convergent near
//!    simple roots, on a grid of 60, 120, .., 960 bits ([`REFINE_ROUNDS`]);
//! 3. real roots are refined by exact sign evaluation of the square-free part
//!    (a simple root changes sign), which reproduces the reference bisection
//!    tree of [`super::poly::isolate_real_roots`] cell by cell;
//! 4. moduli: a disk strictly inside or outside `|z| = t` decides its root;
//!    the reference Schur-Cohn recursion would return its count unless it is
//!    singular, which is excluded by running the same recursion modulo a prime
//!    (a non-zero residue of `gamma_k` and of the leading coefficient at every
//!    step proves they are non-zero over `Q`, so the exact recursion is
//!    regular and its count is the true count);
//! 5. semisimplicity: all roots of a square-free `f` are semisimple iff
//!    `(f e)(A) = 0` with `e` the part of the characteristic polynomial
//!    coprime to `f` (the minimal polynomial divides `f e`); the integer
//!    matrix `D^k (f e)(A)` is zero iff it vanishes modulo primes whose
//!    product exceeds twice the bound `sum |c_k| |M|_inf^k D^(deg - k)`.
//!
//! Anything that cannot be certified this way (overlapping disks, a disk on a
//! circle `|z| = t`, a singular residue, a non-semisimple root) returns `None`
//! and the caller falls back to the reference algorithm, so the results are
//! those of the reference algorithms in every case.

use super::poly::Poly;
use crate::scalar::Rational;
use nalgebra::DMatrix;
use num_bigint::{BigInt, Sign};
use num_complex::Complex64;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Bits of the dyadic grid the floating-point root approximations are rounded
/// to (`|z| <= 1` for every root here, so `2^-60` keeps all 53 mantissa bits of
/// the approximations that matter and the integers small).
const GRID_BITS: u32 = 60;

/// Two approximations closer than this (relative to `max(1, |z|)`) are taken
/// as one multiple root (a defective double eigenvalue splits by
/// `~sqrt(eps) ~ 1e-8` in `f64`). Only a guess: a wrong grouping makes the
/// disk certificate fail and the reference algorithm runs.
const CLUSTER_TOL: f64 = 1e-6;

/// Weierstrass refinement steps tried when the disks around the
/// floating-point approximations overlap (close roots: the `f64` eigenvalues
/// of a cluster are only accurate to about `eps^(1/k)`). Each step doubles the
/// grid bits (60, 120, ..., 960 after 4 steps); a failure after the last one
/// falls back to the reference algorithms, so the rounds cost time, never
/// correctness.
const REFINE_ROUNDS: usize = 4;

/// A polynomial with integer coefficients (ascending), a positive rational
/// multiple of a [`Poly`].
#[derive(Clone, Debug)]
pub(crate) struct IntPoly(pub(crate) Vec<BigInt>);

impl IntPoly {
    /// The primitive integer polynomial with the same roots as `p` and a
    /// positive leading coefficient ratio (`p = c * self`, `c > 0`).
    pub(crate) fn from_poly(p: &Poly) -> Self {
        let mut l = BigInt::one();
        for c in p.coeffs() {
            l = l.lcm(c.denom());
        }
        let mut v: Vec<BigInt> = p
            .coeffs()
            .iter()
            .map(|c| c.numer() * (&l / c.denom()))
            .collect();
        let mut g = BigInt::zero();
        for c in &v {
            g = g.gcd(c);
        }
        if !g.is_zero() && !g.is_one() {
            for c in &mut v {
                *c /= &g;
            }
        }
        IntPoly(v)
    }

    fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    /// Sign of the value at the rational `x` (homogeneous Horner in integers:
    /// `sum c_k a^k b^(d-k)` with `x = a/b`, `b > 0`, no gcds).
    pub(crate) fn sign_at(&self, x: &Rational) -> i32 {
        let (a, b) = (x.numer(), x.denom());
        let mut acc = BigInt::zero();
        let mut bp = BigInt::one();
        for c in self.0.iter().rev() {
            acc = acc * a + c * &bp;
            bp *= b;
        }
        // acc = sum c_k a^k b^(d-k) ... with b^(d-k) built incrementally:
        // the loop above multiplies bp after use, so term k carries
        // b^(d-k) exactly when it is added (see `sign_at_matches_eval`).
        match acc.sign() {
            Sign::Plus => 1,
            Sign::Minus => -1,
            Sign::NoSign => 0,
        }
    }

    /// Residues modulo the prime `p`.
    fn residues(&self, p: u64) -> Vec<u64> {
        self.0.iter().map(|c| modp(c, p)).collect()
    }
}

fn modp(c: &BigInt, p: u64) -> u64 {
    let r = c.mod_floor(&BigInt::from(p));
    r.to_u64().unwrap_or(0)
}

fn mulmod(a: u64, b: u64, p: u64) -> u64 {
    ((a as u128 * b as u128) % p as u128) as u64
}

fn powmod(mut a: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1u64;
    while e > 0 {
        if e & 1 == 1 {
            r = mulmod(r, a, p);
        }
        a = mulmod(a, a, p);
        e >>= 1;
    }
    r
}

fn invmod(a: u64, p: u64) -> u64 {
    powmod(a, p - 2, p)
}

/// Deterministic Miller-Rabin for 64-bit integers.
fn is_prime(n: u64) -> bool {
    if n < 2 {
        return false;
    }
    for q in [2u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37] {
        if n % q == 0 {
            return n == q;
        }
    }
    let (mut d, mut s) = (n - 1, 0);
    while d % 2 == 0 {
        d /= 2;
        s += 1;
    }
    'w: for a in [2u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37] {
        let mut x = powmod(a, d, n);
        if x == 1 || x == n - 1 {
            continue;
        }
        for _ in 1..s {
            x = mulmod(x, x, n);
            if x == n - 1 {
                continue 'w;
            }
        }
        return false;
    }
    true
}

/// The primes below `2^62`, descending (as many as asked for).
pub(crate) fn primes(count: usize) -> Vec<u64> {
    let mut out = Vec::with_capacity(count);
    let mut n = (1u64 << 62) - 1;
    while out.len() < count {
        if is_prime(n) {
            out.push(n);
        }
        n -= 2;
    }
    out
}

/// Degree of `gcd(a, b)` over `F_p` (`a`, `b` ascending, possibly untrimmed).
fn gcd_degree_mod(a: &[u64], b: &[u64], p: u64) -> Option<usize> {
    let trim = |v: &mut Vec<u64>| {
        while v.last() == Some(&0) {
            v.pop();
        }
    };
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        // a <- a mod b
        let db = b.len() - 1;
        let inv = invmod(b[db], p);
        while a.len() > db {
            let da = a.len() - 1;
            let f = mulmod(a[da], inv, p);
            for j in 0..=db {
                let t = mulmod(f, b[j], p);
                a[da - db + j] = (a[da - db + j] + p - t) % p;
            }
            trim(&mut a);
            if a.len() > da {
                a.pop();
            }
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len().checked_sub(1)
}

/// `Some(true)` when `Q` is proven square-free by a residue (see the module
/// docs); `None` when the primes tried are inconclusive.
pub(crate) fn squarefree_mod_p(q: &IntPoly) -> Option<bool> {
    let d = q.degree();
    if d == 0 {
        return Some(true);
    }
    for p in primes(3) {
        let r = q.residues(p);
        if r[d] == 0 {
            continue;
        }
        let dr: Vec<u64> = (1..=d).map(|k| mulmod(r[k], k as u64 % p, p)).collect();
        if gcd_degree_mod(&r, &dr, p) == Some(0) {
            return Some(true);
        }
    }
    None
}

/// Whether the Schur-Cohn recursion of [`super::poly::roots_inside_unit_disc`]
/// on `Q(t z)` is regular (never singular), proven by running it modulo a
/// prime; `false` means "not proven".
pub(crate) fn schur_cohn_regular(q: &IntPoly, t: &Rational) -> bool {
    let d = q.degree();
    for p in primes(2) {
        let (a, b) = (modp(t.numer(), p), modp(t.denom(), p));
        let mut c: Vec<u64> = q
            .residues(p)
            .iter()
            .enumerate()
            .map(|(k, &ck)| {
                mulmod(
                    ck,
                    mulmod(powmod(a, k as u64, p), powmod(b, (d - k) as u64, p), p),
                    p,
                )
            })
            .collect();
        let mut ok = c.last().is_some_and(|&l| l != 0);
        while ok && c.len() > 1 {
            let dd = c.len() - 1;
            let (a0, ad) = (c[0], c[dd]);
            let gamma = (mulmod(a0, a0, p) + p - mulmod(ad, ad, p)) % p;
            if gamma == 0 {
                ok = false;
                break;
            }
            let t: Vec<u64> = (0..dd)
                .map(|k| (mulmod(a0, c[k], p) + p - mulmod(ad, c[dd - k], p)) % p)
                .collect();
            if t[dd - 1] == 0 {
                ok = false;
                break;
            }
            c = t;
        }
        if ok {
            return true;
        }
    }
    false
}

/// A certified root: the disk `|z - (x + i y)| <= r` holds exactly one root of
/// the square-free part, of multiplicity `mult` in `q`.
#[derive(Clone, Debug)]
struct Disk {
    x: Rational,
    y: Rational,
    r: Rational,
    mult: usize,
}

/// The state of a real root for refinement by sign changes of the square-free
/// part: exactly known, or the only root in the open interval `(l, h)` with
/// the sign `sl` of the square-free part at `l`.
#[derive(Clone, Debug)]
enum RealState {
    Exact(Rational),
    Open { l: Rational, h: Rational, sl: i32 },
}

/// The certified roots of `q` (every root, with multiplicity).
#[derive(Debug)]
pub(crate) struct RootStructure {
    disks: Vec<Disk>,
    /// Indices of the real roots in `disks`, and their refinement state.
    real: Vec<(usize, RealState)>,
    sf: IntPoly,
}

/// A Gaussian integer `(re, im)`.
type Gaussian = (BigInt, BigInt);

/// One square-free factor, its grid points (one per root) and its
/// multiplicity in `q`.
type FactorPoints = (IntPoly, Vec<Gaussian>, usize);

fn gauss_mul(a: &(BigInt, BigInt), b: &(BigInt, BigInt)) -> (BigInt, BigInt) {
    (&a.0 * &b.0 - &a.1 * &b.1, &a.0 * &b.1 + &a.1 * &b.0)
}

fn dyadic(m: &BigInt, bits: u32) -> Rational {
    Rational::new(m.clone(), BigInt::one() << bits)
}

fn grid(x: f64) -> Option<BigInt> {
    let v = (x * (1u64 << GRID_BITS) as f64).round();
    if !v.is_finite() || v.abs() > 1e30 {
        return None;
    }
    Some(BigInt::from(v as i128))
}

/// Pairs `(x, y)` of grid integers: conjugate-symmetric, real ones with
/// `y = 0` exactly. An approximation is taken as real when its imaginary part
/// is at most `real_tol` relative to `max(1, |z|)` (with `real_tol = 0`: only
/// an exactly real one, as a real eigen-solver returns its real eigenvalues).
fn symmetric(centres: &[Complex64], real_tol: f64) -> Option<Vec<(BigInt, BigInt)>> {
    let mut out = Vec::new();
    let mut lower = 0;
    for z in centres {
        let tol = real_tol * z.norm().max(1.0);
        if z.im.abs() <= tol {
            out.push((grid(z.re)?, BigInt::zero()));
        } else if z.im > 0.0 {
            let (x, y) = (grid(z.re)?, grid(z.im)?);
            out.push((x.clone(), -&y));
            out.push((x, y));
        } else {
            lower += 1;
        }
    }
    (2 * lower + out.iter().filter(|p| p.1.is_zero()).count() == out.len()).then_some(out)
}

/// For the grid points `z_i = (x_i + i y_i) / 2^bits` (`m = deg f` of them),
/// the Gaussian integers `V_i = f(z_i) 2^(bits m)` and
/// `Pi_i = prod_(j != i) (z_i - z_j) 2^(bits (m - 1))`, so that the
/// Weierstrass correction is `w_i = V_i / (lc(f) Pi_i 2^bits)`. `None` when
/// the counts disagree or two points coincide.
fn weierstrass(
    f: &IntPoly,
    z: &[(BigInt, BigInt)],
    bits: u32,
) -> Option<Vec<(Gaussian, Gaussian)>> {
    let m = f.degree();
    if z.len() != m || m == 0 {
        return None;
    }
    let s = BigInt::one() << bits;
    let mut out = Vec::with_capacity(m);
    for (i, zi) in z.iter().enumerate() {
        let mut v = (f.0[m].clone(), BigInt::zero());
        let mut sp = s.clone();
        for k in (0..m).rev() {
            v = gauss_mul(&v, zi);
            v.0 += &f.0[k] * &sp;
            sp *= &s;
        }
        let mut pi = (BigInt::one(), BigInt::zero());
        for (j, zj) in z.iter().enumerate() {
            if j != i {
                pi = gauss_mul(&pi, &(&zi.0 - &zj.0, &zi.1 - &zj.1));
            }
        }
        if pi.0.is_zero() && pi.1.is_zero() {
            return None;
        }
        out.push((v, pi));
    }
    Some(out)
}

/// Disks for the roots of the square-free `f` (degree `m`) around the grid
/// points `z` (`m` of them, `bits` fractional bits), or `None`.
fn disks(f: &IntPoly, z: &[(BigInt, BigInt)], bits: u32, mult: usize) -> Option<Vec<Disk>> {
    let m = f.degree();
    let s = BigInt::one() << bits;
    let lc = f.0.last()?.clone();
    let w = weierstrass(f, z, bits)?;
    let mut out = Vec::with_capacity(m);
    for (zi, (v, pi)) in z.iter().zip(&w) {
        let den = (&pi.0 * &pi.0 + &pi.1 * &pi.1) * &lc * &lc * &s * &s;
        let num = &v.0 * &v.0 + &v.1 * &v.1;
        // |w|^2 = num / den < 2^(bits(num) - bits(den) + 1); r = m 2^ceil((e+1)/2) >= m |w|.
        let r = if num.is_zero() {
            Rational::zero()
        } else {
            let e = num.bits() as i64 - den.bits() as i64 + 1;
            let h = e.div_euclid(2) + e.rem_euclid(2);
            let pow = if h >= 0 {
                Rational::from_integer(BigInt::one() << h as u32)
            } else {
                Rational::new(BigInt::one(), BigInt::one() << (-h) as u32)
            };
            pow * Rational::from_integer(BigInt::from(m))
        };
        out.push(Disk {
            x: dyadic(&zi.0, bits),
            y: dyadic(&zi.1, bits),
            r,
            mult,
        });
    }
    Some(out)
}

/// `a / b` rounded to the nearest integer, halves away from zero (`b > 0`);
/// odd in `a`, so conjugate points stay conjugate and real points real.
fn round_div(a: &BigInt, b: &BigInt) -> BigInt {
    let half = b >> 1u32;
    if a.is_negative() {
        -((-a + &half) / b)
    } else {
        (a + &half) / b
    }
}

/// One Weierstrass (Durand-Kerner) step `z_i <- z_i - w_i` on the grid points
/// `z` (`bits` fractional bits), rounded to `new_bits` fractional bits. The
/// step converges quadratically near simple roots, so doubling the bits per
/// step keeps the rounding below the correction. Exact arithmetic: a
/// conjugate-symmetric set stays conjugate-symmetric and real points real.
fn weierstrass_step(
    f: &IntPoly,
    z: &[(BigInt, BigInt)],
    bits: u32,
    new_bits: u32,
) -> Option<Vec<(BigInt, BigInt)>> {
    let lc = f.0.last()?.clone();
    let w = weierstrass(f, z, bits)?;
    let up = new_bits - bits;
    Some(
        z.iter()
            .zip(&w)
            .map(|(zi, (v, pi))| {
                // w 2^new_bits = V conj(Pi) 2^new_bits / (lc |Pi|^2 2^bits).
                let den = (&pi.0 * &pi.0 + &pi.1 * &pi.1) * &lc;
                let num = gauss_mul(v, &(pi.0.clone(), -&pi.1));
                let (wr, wi) = (
                    round_div(&(num.0 << up), &den),
                    round_div(&(num.1 << up), &den),
                );
                ((&zi.0 << up) - wr, (&zi.1 << up) - wi)
            })
            .collect(),
    )
}

impl RootStructure {
    /// Certifies the roots of `q = prod_k a_k^k` from the square-free factors
    /// `factors[k-1] = a_k` (monic or not), their product `sf` and
    /// floating-point approximations `approx` of the roots of `q` with
    /// multiplicity. `None` when the certificate fails.
    pub(crate) fn certify(factors: &[Poly], sf: &Poly, approx: &[Complex64]) -> Option<Self> {
        // Group the approximations into clusters (multiple roots). A proven
        // square-free `q` (one factor) has simple roots only, however close
        // their approximations: no grouping then.
        let mut left: Vec<Complex64> = approx.to_vec();
        let mut clusters: Vec<(Complex64, usize)> = Vec::new();
        if factors.len() == 1 {
            clusters = left.drain(..).map(|z| (z, 1)).collect();
        }
        while let Some(z) = left.pop() {
            let tol = CLUSTER_TOL * z.norm().max(1.0);
            let (close, far): (Vec<Complex64>, Vec<Complex64>) =
                left.iter().partition(|w| (*w - z).norm() <= tol);
            let k = close.len() + 1;
            let centre = (close.iter().sum::<Complex64>() + z) / k as f64;
            clusters.push((centre, k));
            left = far;
        }
        let sfi = IntPoly::from_poly(sf);
        // Real or a conjugate pair? The eigen-solver's exact zeros first (a
        // close pair of real roots and a complex pair with a tiny imaginary
        // part look alike), then the clustering tolerance. A wrong guess
        // cannot converge (the Weierstrass step keeps real points real and
        // pairs paired), so it only costs the rounds.
        let mut tried: Vec<Vec<FactorPoints>> = Vec::new();
        for real_tol in [0.0, CLUSTER_TOL] {
            // Every factor gets its points, or this guess is skipped.
            let starts: Option<Vec<FactorPoints>> = factors
                .iter()
                .enumerate()
                .filter(|(_, a)| a.degree().unwrap_or(0) > 0)
                .map(|(k, a)| {
                    let centres: Vec<Complex64> = clusters
                        .iter()
                        .filter(|c| c.1 == k + 1)
                        .map(|c| c.0)
                        .collect();
                    Some((IntPoly::from_poly(a), symmetric(&centres, real_tol)?, k + 1))
                })
                .collect();
            let Some(starts) = starts else {
                continue;
            };
            if tried
                .iter()
                .any(|t| t.len() == starts.len() && t.iter().zip(&starts).all(|(a, b)| a.1 == b.1))
            {
                continue;
            }
            if let Some(s) = Self::refine_and_certify(starts.clone(), &sfi) {
                return Some(s);
            }
            tried.push(starts);
        }
        None
    }

    /// Up to [`REFINE_ROUNDS`] Weierstrass steps on the grid points of each
    /// factor until [`Self::from_grid`] certifies them.
    fn refine_and_certify(mut starts: Vec<FactorPoints>, sfi: &IntPoly) -> Option<Self> {
        let mut bits = GRID_BITS;
        for round in 0..=REFINE_ROUNDS {
            if let Some(s) = Self::from_grid(&starts, bits, sfi) {
                return Some(s);
            }
            if round == REFINE_ROUNDS {
                break;
            }
            for (f, z, _) in &mut starts {
                *z = weierstrass_step(f, z, bits, 2 * bits)?;
            }
            bits *= 2;
        }
        None
    }

    /// The certificate from the grid points `starts` (per square-free factor:
    /// the factor, its points with `bits` fractional bits, its
    /// multiplicity), or `None` when the disks overlap or a real root cannot
    /// be told from a complex pair.
    fn from_grid(starts: &[FactorPoints], bits: u32, sfi: &IntPoly) -> Option<Self> {
        let mut all = Vec::new();
        for (f, z, mult) in starts {
            all.extend(disks(f, z, bits, *mult)?);
        }
        // Pairwise disjoint: |c_i - c_j|^2 > (r_i + r_j)^2.
        for i in 0..all.len() {
            for j in i + 1..all.len() {
                let (dx, dy) = (&all[i].x - &all[j].x, &all[i].y - &all[j].y);
                let rr = &all[i].r + &all[j].r;
                if &dx * &dx + &dy * &dy <= &rr * &rr {
                    return None;
                }
            }
        }
        let mut real = Vec::new();
        for (i, d) in all.iter().enumerate() {
            if d.y.is_zero() {
                let (l, h) = (&d.x - &d.r, &d.x + &d.r);
                let state = if d.r.is_zero() {
                    RealState::Exact(d.x.clone())
                } else {
                    let (sl, sh) = (sfi.sign_at(&l), sfi.sign_at(&h));
                    if sl == 0 {
                        RealState::Exact(l)
                    } else if sh == 0 {
                        RealState::Exact(h)
                    } else if sl != sh {
                        RealState::Open { l, h, sl }
                    } else {
                        return None;
                    }
                };
                real.push((i, state));
            } else if d.y.abs() <= d.r {
                return None;
            }
        }
        Some(RootStructure {
            disks: all,
            real,
            sf: sfi.clone(),
        })
    }

    /// Number of distinct real roots.
    pub(crate) fn real_count(&self) -> usize {
        self.real.len()
    }

    /// Multiplicity in `q` of the `k`-th real root.
    pub(crate) fn real_mult(&self, k: usize) -> usize {
        self.disks[self.real[k].0].mult
    }

    /// Whether the `k`-th real root is `<= m`.
    pub(crate) fn le(&mut self, k: usize, m: &Rational) -> bool {
        let sf = &self.sf;
        let st = &mut self.real[k].1;
        match st {
            RealState::Exact(x) => &*x <= m,
            RealState::Open { l, h, sl } => {
                if m >= h {
                    return true;
                }
                if m <= l {
                    return false;
                }
                let s = sf.sign_at(m);
                if s == 0 {
                    *st = RealState::Exact(m.clone());
                    true
                } else if s == *sl {
                    *l = m.clone();
                    false
                } else {
                    *h = m.clone();
                    true
                }
            }
        }
    }

    /// Number of distinct real roots in `(a, b]`.
    pub(crate) fn count(&mut self, a: &Rational, b: &Rational) -> usize {
        (0..self.real.len())
            .filter(|&k| !self.le(k, a) && self.le(k, b))
            .count()
    }

    /// Number of distinct real roots in `(a, +infinity)`.
    pub(crate) fn count_above(&mut self, a: &Rational) -> usize {
        (0..self.real.len()).filter(|&k| !self.le(k, a)).count()
    }

    /// Number of distinct real roots in `(-infinity, b]`.
    pub(crate) fn count_below(&mut self, b: &Rational) -> usize {
        (0..self.real.len()).filter(|&k| self.le(k, b)).count()
    }

    /// Number of roots of `q` (with multiplicity) of modulus `> t`, when every
    /// disk is strictly inside or outside the circle `|z| = t` (`t > 0`).
    pub(crate) fn count_outside(&self, t: &Rational) -> Option<usize> {
        let mut c = 0;
        for d in &self.disks {
            let m2 = &d.x * &d.x + &d.y * &d.y;
            let hi = t + &d.r;
            if m2 > &hi * &hi {
                c += d.mult;
            } else if t > &d.r {
                let lo = t - &d.r;
                if m2 >= &lo * &lo {
                    return None;
                }
            } else {
                return None;
            }
        }
        Some(c)
    }

    /// The reference bisection of [`super::poly::isolate_real_roots`] on the
    /// square-free part (root bound `b`, stopping width `width`): the same
    /// cells, with the index of the real root in each.
    pub(crate) fn isolate(
        &mut self,
        b: &Rational,
        width: &Rational,
    ) -> Vec<(Rational, Rational, usize)> {
        let two = Rational::from_integer(BigInt::from(2));
        let mut out = Vec::new();
        let mut stack = vec![(
            -b.clone(),
            b.clone(),
            (0..self.real.len()).collect::<Vec<_>>(),
        )];
        while let Some((lo, hi, idx)) = stack.pop() {
            if idx.is_empty() {
                continue;
            }
            if idx.len() == 1 && &hi - &lo <= *width {
                out.push((lo, hi, idx[0]));
                continue;
            }
            let mid = (&lo + &hi) / &two;
            let (left, right): (Vec<usize>, Vec<usize>) =
                idx.into_iter().partition(|&k| self.le(k, &mid));
            stack.push((mid.clone(), hi, right));
            stack.push((lo, mid, left));
        }
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }
}

/// Whether `(f e)(A) = 0` exactly (all roots of `f` semisimple; see the module
/// docs), with `fe` the polynomial. `false` means "not proven" (it may also be
/// a true non-zero).
pub(crate) fn annihilates(a: &DMatrix<Rational>, fe: &Poly) -> bool {
    let n = a.nrows();
    let mut den = BigInt::one();
    for x in a.iter() {
        den = den.lcm(x.denom());
    }
    let m: Vec<BigInt> = a.iter().map(|x| x.numer() * (&den / x.denom())).collect(); // column-major
    let c = IntPoly::from_poly(fe);
    let deg = c.degree();
    // Bound on the entries of Z = sum c_k M^k D^(deg - k).
    let mut norm = BigInt::zero();
    for i in 0..n {
        let mut s = BigInt::zero();
        for j in 0..n {
            s += m[i + j * n].abs();
        }
        if s > norm {
            norm = s;
        }
    }
    let norm = norm.max(BigInt::one());
    let mut bound = BigInt::zero();
    let mut np = BigInt::one();
    for (k, ck) in c.0.iter().enumerate() {
        bound += ck.abs() * &np * num_traits::pow(den.clone(), deg - k);
        np *= &norm;
    }
    let need: BigInt = bound * 2 + 1;
    let mut prod = BigInt::one();
    let mut k = 0;
    let ps = primes(1 + (need.bits() as usize) / 61);
    while prod < need {
        let p = ps[k];
        k += 1;
        prod *= BigInt::from(p);
        let mm: Vec<u64> = m.iter().map(|x| modp(x, p)).collect();
        let dm = modp(&den, p);
        let cr = c.residues(p);
        // Horner: Z = c_deg I; Z <- Z M + c_k D^(deg-k) I.
        let mut z = vec![0u64; n * n];
        for i in 0..n {
            z[i + i * n] = cr[deg];
        }
        let mut dp = 1u64;
        for kk in (0..deg).rev() {
            dp = mulmod(dp, dm, p);
            let mut nz = vec![0u64; n * n];
            for j in 0..n {
                for l in 0..n {
                    let b = mm[l + j * n];
                    if b == 0 {
                        continue;
                    }
                    for i in 0..n {
                        let a = z[i + l * n];
                        if a != 0 {
                            nz[i + j * n] = (nz[i + j * n] + mulmod(a, b, p)) % p;
                        }
                    }
                }
            }
            let add = mulmod(cr[kk], dp, p);
            for i in 0..n {
                nz[i + i * n] = (nz[i + i * n] + add) % p;
            }
            z = nz;
        }
        if z.iter().any(|&v| v != 0) {
            return false;
        }
    }
    true
}

/// Characteristic polynomial modulo `p` of the matrix with entries `a`
/// (row-major `m x m`): Hessenberg reduction by Gaussian similarity, then the
/// Hessenberg determinant recurrence (as `exact::charpoly` over the rationals).
fn charpoly_mod(mut h: Vec<u64>, m: usize, p: u64) -> Vec<u64> {
    let at = |i: usize, j: usize| i * m + j;
    for k in 0..m.saturating_sub(2) {
        let Some(piv_row) = (k + 1..m).find(|&i| h[at(i, k)] != 0) else {
            continue;
        };
        if piv_row != k + 1 {
            for j in 0..m {
                h.swap(at(piv_row, j), at(k + 1, j));
            }
            for i in 0..m {
                h.swap(at(i, piv_row), at(i, k + 1));
            }
        }
        let inv = invmod(h[at(k + 1, k)], p);
        for i in k + 2..m {
            let f = mulmod(h[at(i, k)], inv, p);
            if f == 0 {
                continue;
            }
            for j in 0..m {
                let t = mulmod(f, h[at(k + 1, j)], p);
                h[at(i, j)] = (h[at(i, j)] + p - t) % p;
            }
            for r in 0..m {
                let t = mulmod(f, h[at(r, i)], p);
                h[at(r, k + 1)] = (h[at(r, k + 1)] + t) % p;
            }
        }
    }
    // p_k = (x - h_kk) p_(k-1) - sum_(i<k) h_ik (prod_(j=i+1..k) h_(j,j-1)) p_(i-1).
    let mut ps: Vec<Vec<u64>> = vec![vec![1]];
    for k in 0..m {
        let prev = &ps[k];
        let mut pk = vec![0u64; k + 2];
        for (d, &c) in prev.iter().enumerate() {
            pk[d + 1] = (pk[d + 1] + c) % p;
            pk[d] = (pk[d] + p - mulmod(h[at(k, k)], c, p)) % p;
        }
        let mut prod = 1u64;
        for i in (0..k).rev() {
            prod = mulmod(prod, h[at(i + 1, i)], p);
            if prod == 0 {
                break;
            }
            let coef = mulmod(h[at(i, k)], prod, p);
            if coef != 0 {
                for (d, &c) in ps[i].iter().enumerate() {
                    pk[d] = (pk[d] + p - mulmod(coef, c, p)) % p;
                }
            }
        }
        ps.push(pk);
    }
    ps.pop().unwrap_or_else(|| vec![1])
}

/// `det(x I - A)` of a rational matrix by the Chinese remainder theorem: with
/// `d_i` the common denominator of row `i` and `N = diag(d) A` (integer),
/// `G(x) = det(x diag(d) - N) = (prod d_i) det(x I - A)` has integer
/// coefficients bounded by `H = prod_i (d_i + |N_i|_2)` (expand the rows and
/// apply Hadamard's inequality to each minor), so its residues modulo primes
/// (none dividing a `d_i`) whose product exceeds `2 H` determine it.
pub(crate) fn charpoly_multimodular(a: &DMatrix<Rational>) -> Poly {
    let m = a.nrows();
    let mut d = Vec::with_capacity(m);
    let mut bound = BigInt::one();
    for i in 0..m {
        let mut di = BigInt::one();
        for j in 0..m {
            di = di.lcm(a[(i, j)].denom());
        }
        let mut s2 = BigInt::zero();
        for j in 0..m {
            let v = a[(i, j)].numer() * (&di / a[(i, j)].denom());
            s2 += &v * &v;
        }
        bound *= &di + s2.sqrt() + 1u32;
        d.push(di);
    }
    let dprod: BigInt = d.iter().product();
    let need: BigInt = bound * 2u32 + 1u32;
    // Residue CRT: x = sum over primes, kept as (value, modulus).
    let mut value: Vec<BigInt> = vec![BigInt::zero(); m + 1];
    let mut modulus = BigInt::one();
    let mut n = (1u64 << 62) - 1;
    while modulus < need {
        while !is_prime(n) || d.iter().any(|di| modp(di, n) == 0) {
            n -= 2;
        }
        let p = n;
        n -= 2;
        let entries: Vec<u64> = (0..m * m)
            .map(|k| {
                let x = &a[(k / m, k % m)];
                mulmod(modp(x.numer(), p), invmod(modp(x.denom(), p), p), p)
            })
            .collect();
        let cp = charpoly_mod(entries, m, p);
        let dp = modp(&dprod, p);
        let mp = modp(&modulus, p);
        let minv = invmod(mp, p);
        for (k, v) in value.iter_mut().enumerate() {
            let r = mulmod(cp[k], dp, p);
            let cur = modp(v, p);
            let t = mulmod((r + p - cur) % p, minv, p);
            *v += &modulus * BigInt::from(t);
        }
        modulus *= BigInt::from(p);
    }
    let half = &modulus >> 1u32;
    Poly::new(
        value
            .into_iter()
            .map(|v| {
                let v = if v > half { v - &modulus } else { v };
                Rational::new(v, dprod.clone())
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Rational {
        Rational::from_integer(BigInt::from(n))
    }

    #[test]
    fn sign_at_matches_eval() {
        let p = Poly::new(vec![
            Rational::new(3.into(), 7.into()),
            q(-2),
            Rational::new(5.into(), 3.into()),
            q(1),
        ]);
        let ip = IntPoly::from_poly(&p);
        for x in [
            q(0),
            q(1),
            q(-3),
            Rational::new(2.into(), 9.into()),
            Rational::new((-7).into(), 4.into()),
        ] {
            let v = p.eval(&x);
            let s = if v.is_positive() {
                1
            } else if v.is_negative() {
                -1
            } else {
                0
            };
            assert_eq!(ip.sign_at(&x), s, "at {x}");
        }
    }

    /// `(x - a)(x - b)(x - 1/2)` with `b - a = 2^-45`: the `f64`
    /// approximations (each off by ~1e-14) give overlapping disks at 60 bits;
    /// the Weierstrass steps separate them. And `(x - 1/4)^2 + 2^-90`, a
    /// complex pair `1/4 +- 2^-45 i` that looks real to a tolerance: taken as
    /// a pair (the eigen-solver's non-zero imaginary part) and certified
    /// non-real. Both came out of `--exact` with `f64` knots, where they sent
    /// every n >= 40 to the slow reference algorithms.
    #[test]
    fn close_roots_are_certified_after_refinement() {
        let two = |e: u32| Rational::new(BigInt::one(), BigInt::one() << e);
        let lin = |r: Rational| Poly::new(vec![-r, q(1)]);
        let a = Rational::new(1.into(), 4.into());
        let b = &a + two(45);
        let half = Rational::new(1.into(), 2.into());
        let p = lin(a.clone()).mul(&lin(b.clone())).mul(&lin(half));
        let z = [
            Complex64::new(0.25 - 1e-14, 0.0),
            Complex64::new(0.25 + 2f64.powi(-45) + 1e-14, 0.0),
            Complex64::new(0.5, 0.0),
        ];
        let bits = GRID_BITS;
        let grid0 = symmetric(&z, 0.0).unwrap();
        assert!(
            RootStructure::from_grid(
                &[(IntPoly::from_poly(&p), grid0, 1)],
                bits,
                &IntPoly::from_poly(&p)
            )
            .is_none(),
            "the unrefined disks must overlap for this test to mean anything"
        );
        let mut s = RootStructure::certify(std::slice::from_ref(&p), &p, &z).expect("certified");
        assert_eq!(s.real_count(), 3);
        let mid = (&a + &b) / q(2);
        assert_eq!(s.count(&q(0), &mid), 1);
        assert_eq!(s.count(&mid, &q(1)), 2);

        let eps = two(90);
        let p = Poly::new(vec![&a * &a + eps, -(&a * q(2)), q(1)]);
        let im = 2f64.powi(-45);
        let z = [Complex64::new(0.25, im), Complex64::new(0.25, -im)];
        let s = RootStructure::certify(std::slice::from_ref(&p), &p, &z).expect("certified");
        assert_eq!(s.real_count(), 0);
        assert_eq!(s.count_outside(&Rational::new(1.into(), 8.into())), Some(2));
    }

    #[test]
    fn squarefree_residue() {
        let a = Poly::new(vec![q(-1), q(1)]);
        let b = Poly::new(vec![q(2), q(0), q(1)]);
        assert_eq!(
            squarefree_mod_p(&IntPoly::from_poly(&a.mul(&b))),
            Some(true)
        );
        assert_eq!(
            squarefree_mod_p(&IntPoly::from_poly(&a.mul(&a).mul(&b))),
            None
        );
    }

    #[test]
    fn schur_cohn_residue_detects_singular() {
        // (z - 2)(z + 1/2): gamma = a0^2 - a2^2 = 0 at t = 1 (singular, though
        // no root is on the circle), regular at t = 3.
        let p = IntPoly::from_poly(&Poly::new(vec![
            q(-1),
            Rational::new((-3).into(), 2.into()),
            q(1),
        ]));
        assert!(!schur_cohn_regular(&p, &q(1)));
        assert!(schur_cohn_regular(&p, &q(3)));
    }
}
