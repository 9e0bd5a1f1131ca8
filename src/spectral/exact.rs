//! Exact certificates for rational input (math doc sections 4, 5, 7).
//!
//! For a Doo-Sabin-family configuration with rational parameters:
//!
//! 1. the characteristic polynomial `p` of the face block `A` over the
//!    rationals (exact Hessenberg reduction by Gaussian similarity, then the
//!    Hessenberg determinant recurrence); `q = p / (x - 1)` exactly (the
//!    remainder must vanish: rows sum to 1); `1` is simple iff `q(1) != 0`;
//! 2. the real roots of `q` by Sturm sequences: how many, isolating intervals,
//!    multiplicities (from the chain `gcd(q, q')`, `gcd(q'', ..)`);
//! 3. the subdominant structure of the full spectrum
//!    `spec(S_n) = {1} U roots(q) U {1/4, 1/8, 1/16} (n each)`, decided exactly:
//!    * **count by modulus**: the Schur-Cohn recursion (`roots_outside`)
//!      counts the roots with `|z| > t` for a rational `t`; a count of exactly 2
//!      at `t` proves `|lambda_2| > t > |lambda_3|` (separation);
//!    * **real or complex**: Sturm counts of the real roots in `|x| > t`: 0 means
//!      the two are a complex-conjugate pair, 2 distinct real roots means
//!      `real_distinct`, 1 real root means a real double root (a non-real root
//!      cannot be alone: conjugates come in pairs);
//!    * **eigenspace of a double root** `lambda`: `rank(A - lambda I)` computed
//!      exactly in the field `Q(lambda)` = `Q[x] / (f)`, starting from the
//!      square-free polynomial of the multiple roots of `q` and splitting `f`
//!      by gcds whenever a pivot is a zero divisor (dynamic evaluation), keeping
//!      the factor that vanishes at `lambda` (decided by a Sturm count on
//!      `lambda`'s isolating interval);
//!    * **not separated**: proven when `q` has at most one root of modulus
//!      `> 1/4` (then `lambda_2 = lambda_3 = 1/4` from the E blocks), or when
//!      the modulus count at every candidate threshold shows no gap and the
//!      equal moduli are certified by a multiple root.
//!
//!    The rational thresholds `t` come from the floating-point estimates (any
//!    `t` is valid: a wrong guess only makes the verdict undecided, never
//!    wrong).
//! 4. the spectral bound `|lambda| < 3/4` for every non-unit eigenvalue (the
//!    Schur-Cohn count at `t = 3/4` is zero);
//! 5. the Theorem 1 certificate in exact arithmetic ([`crate::contraction::certificate`]).
//!
//! Speed: the steps above are the *reference* algorithms. [`exact_verdict`]
//! answers the same questions first by the certified root structure of
//! `spectral::certify` (the characteristic polynomial of the deflated face
//! block [`deflate_unit_rows`] by CRT; Gerschgorin inclusion disks computed
//! exactly; residues proving square-freeness, a regular Schur-Cohn recursion
//! and semisimplicity) and falls back to the reference algorithm for any
//! question a fast certificate does not settle, so the verdict, the
//! polynomials, the isolating intervals and the reasons are the same; the
//! unit tests compare both paths field by field.

use super::certify::{self, IntPoly, RootStructure};
use super::classify::{ClassName, Subdominant};
use super::poly::{isolate_real_roots, roots_outside, Poly, Sturm};
use super::Result;
use super::SpectralError;
use crate::contraction;
use crate::scalar::{rational_to_f64, Rational, Scalar};
use crate::schemes::LocalScheme;
use nalgebra::DMatrix;
use num_bigint::BigInt;
use num_traits::{One, Zero};
use serde::Serialize;

/// Width of the reported isolating intervals of real roots.
pub const ISOLATION_WIDTH: f64 = 1e-12;

/// The exact structure of the two subdominant eigenvalues.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TopPair {
    /// A real double root; `semisimple` = 2-dimensional eigenspace.
    RealDouble {
        /// Whether the eigenspace is 2-dimensional.
        semisimple: bool,
    },
    /// Two distinct real roots.
    RealDistinct,
    /// A complex-conjugate pair.
    ComplexPair,
    /// Not decided (with the reason).
    Undecided {
        /// Why.
        reason: String,
    },
}

/// A real root of `q` with an isolating interval.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RealRoot {
    /// `[a, b]` (as `f64`, rounded outward is not guaranteed; the exact
    /// interval is `(a, b]` in rationals).
    pub interval: [f64; 2],
    /// Multiplicity.
    pub multiplicity: usize,
}

/// Exact verdicts for one rational configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExactVerdict {
    /// Characteristic polynomial of the face block, ascending coefficients.
    pub face_charpoly: Vec<String>,
    /// `q = p / (x - 1)`, ascending coefficients.
    pub reduced_charpoly: Vec<String>,
    /// `1` is a simple eigenvalue of the face block (`q(1) != 0`).
    pub one_is_simple: bool,
    /// Number of distinct real roots of `q`.
    pub real_root_count: usize,
    /// The real roots of `q`, increasing, with multiplicities.
    pub real_roots: Vec<RealRoot>,
    /// Every non-unit eigenvalue has modulus `< 3/4` (`None`: a root on the circle
    /// `|z| = 3/4` could not be excluded).
    pub spectral_bound_below_three_quarters: Option<bool>,
    /// Structure of `lambda_1, lambda_2`.
    pub top_pair: TopPair,
    /// `|lambda_2| > |lambda_3|` (`None`: undecided).
    pub separated: Option<bool>,
    /// The exact class (`None`: undecided).
    pub class: Option<ClassName>,
    /// Why the class is what it is (or undecided).
    pub reason: String,
    /// Theorem 1 certificate holds exactly (weights >= 0, row sums exactly 3/4, `F` invariant).
    pub theorem1_certificate: bool,
    /// Whether the exact class equals the floating-point one (`None` when either
    /// is undecided/indeterminate or no float verdict was given).
    pub agrees_with_float: Option<bool>,
}

/// Characteristic polynomial `det(x I - A)` of a rational square matrix.
pub fn charpoly(a: &DMatrix<Rational>) -> Poly {
    let n = a.nrows();
    let mut h = a.clone();
    // Hessenberg reduction by Gaussian similarity transforms.
    for k in 0..n.saturating_sub(2) {
        let Some(p) = (k + 1..n).find(|&i| !h[(i, k)].is_zero()) else {
            continue;
        };
        if p != k + 1 {
            h.swap_rows(p, k + 1);
            h.swap_columns(p, k + 1);
        }
        let piv = h[(k + 1, k)].clone();
        for i in k + 2..n {
            if h[(i, k)].is_zero() {
                continue;
            }
            let m = &h[(i, k)] / &piv;
            // row_i -= m row_{k+1}
            for j in 0..n {
                let t = &m * &h[(k + 1, j)];
                h[(i, j)] -= t;
            }
            // col_{k+1} += m col_i
            for r in 0..n {
                let t = &m * &h[(r, i)];
                h[(r, k + 1)] += t;
            }
        }
    }
    // p_k(x) = (x - h_kk) p_{k-1} - sum_{i<k} h_{ik} (prod_{j=i+1}^{k} h_{j,j-1}) p_{i-1}
    // (1-based); here p[k] is the charpoly of the leading k x k block.
    let mut ps: Vec<Poly> = vec![Poly::constant(Rational::one())];
    for k in 0..n {
        let mut pk = Poly::linear(h[(k, k)].clone()).mul(&ps[k]);
        let mut prod = Rational::one();
        for i in (0..k).rev() {
            prod *= &h[(i + 1, i)];
            if prod.is_zero() {
                break;
            }
            let coef = &h[(i, k)] * &prod;
            if !coef.is_zero() {
                pk = pk.sub(&ps[i].scale(&coef));
            }
        }
        ps.push(pk);
    }
    ps.pop().unwrap_or_else(|| Poly::constant(Rational::one()))
}

/// The deflation of a matrix whose rows all sum to 1 (`A 1 = 1`): with
/// `T = [1, e_2, .., e_n]`, `T^-1 A T = [[1, *], [0, A']]` and
/// `A'_(ij) = A_(ij) - A_(0j)` (`i, j >= 1`), so `det(x I - A) = (x - 1)
/// det(x I - A')`. For a face block `A = 1/4 (I + R + 1 c^T)` (math doc
/// section 4) the rank-one part cancels exactly in `A'`: the entries keep the
/// small denominators of the ratios instead of the face weights' large common
/// denominator. `None` when a row sum differs from 1.
pub fn deflate_unit_rows(a: &DMatrix<Rational>) -> Option<DMatrix<Rational>> {
    let n = a.nrows();
    if n == 0 || a.ncols() != n {
        return None;
    }
    let one = Rational::one();
    if (0..n).any(|i| a.row(i).iter().fold(Rational::zero(), |s, x| s + x) != one) {
        return None;
    }
    Some(DMatrix::from_fn(n - 1, n - 1, |i, j| {
        &a[(i + 1, j + 1)] - &a[(0, j + 1)]
    }))
}

/// Rank of `A - lambda I` where `lambda` is the unique root of the square-free
/// `f` in the isolating interval `(lo, hi]`, computed exactly in `Q[x]/(f)`
/// with dynamic splitting of `f` (see the module docs).
pub fn rank_at_root(a: &DMatrix<Rational>, f: &Poly, lo: &Rational, hi: &Rational) -> usize {
    let n = a.nrows();
    let mut f = f.clone();
    // Entries are polynomials in x (mod f): A - x I.
    let mut m: Vec<Vec<Poly>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let mut c = vec![a[(i, j)].clone()];
                    if i == j {
                        c.push(-Rational::one());
                    }
                    Poly::new(c)
                })
                .collect()
        })
        .collect();
    // Is g(lambda) == 0? Splits f when gcd(g, f) is a proper factor.
    let is_zero_at = |g: &Poly, f: &mut Poly| -> bool {
        let g = g.rem(f);
        if g.is_zero() {
            return true;
        }
        let d = g.gcd(f);
        if d.degree() == Some(0) {
            return false;
        }
        let root_in_d = Sturm::new(&d).count(lo, hi) > 0;
        if root_in_d {
            *f = d;
            true
        } else {
            *f = f.divrem(&d).0.monic();
            false
        }
    };
    let mut rank = 0;
    let mut row = 0;
    for col in 0..n {
        let mut piv = None;
        for (r, mrow) in m.iter().enumerate().skip(row) {
            if !is_zero_at(&mrow[col], &mut f) {
                piv = Some(r);
                break;
            }
        }
        let Some(p) = piv else { continue };
        m.swap(row, p);
        // Inverse of the pivot mod f (invertible: gcd with f is 1).
        let pv = m[row][col].rem(&f);
        let (g, s, _) = pv.xgcd(&f);
        if g.degree() != Some(0) {
            // Cannot happen after is_zero_at; treat as zero defensively.
            continue;
        }
        let inv = s.scale(&(Rational::one() / g.lead())).rem(&f);
        for r in row + 1..n {
            let factor = m[r][col].mul(&inv).rem(&f);
            if factor.is_zero() {
                continue;
            }
            let (top, bottom) = m.split_at_mut(r);
            for (dst, src) in bottom[0].iter_mut().zip(&top[row]).skip(col) {
                *dst = dst.sub(&factor.mul(src)).rem(&f);
            }
        }
        row += 1;
        rank += 1;
        if row == n {
            break;
        }
    }
    rank
}

/// The root questions of [`exact_verdict`] about `q = p / (x - 1)`, answered
/// by the certified root structure of [`super::certify`] when it applies and by
/// the reference algorithms (Sturm sequences, rational Schur-Cohn recursion,
/// rank over `Q[x]/(f)`) otherwise; both give the same answers (see the
/// module docs of [`super::certify`]).
struct Roots {
    q: Poly,
    /// The square-free part of `q` (monic).
    sf: Poly,
    /// `squarefree(gcd^k(q))` for `k = 1, 2, ..` (the roots of multiplicity `> k`).
    chain: Vec<Poly>,
    fast: Option<RootStructure>,
    q_int: IntPoly,
    sturm_sf: Option<Sturm>,
    sturm_chain: Option<Vec<Sturm>>,
}

impl Roots {
    /// `approx`: floating-point eigenvalues of the face block (`None`: the
    /// reference algorithms only).
    fn new(q: &Poly, approx: Option<Vec<num_complex::Complex64>>) -> Self {
        let q_int = IntPoly::from_poly(q);
        let proven_squarefree = approx.is_some() && certify::squarefree_mod_p(&q_int) == Some(true);
        let (sf, chain) = if q.degree().unwrap_or(0) == 0 {
            (q.squarefree(), Vec::new())
        } else if proven_squarefree {
            // gcd(q, q') = 1: the reference computes sf = q / 1 made monic and an empty chain.
            (q.monic(), Vec::new())
        } else {
            let mut chain = Vec::new();
            let mut g = q.clone();
            loop {
                let d = g.gcd(&g.derivative());
                if d.degree().unwrap_or(0) == 0 {
                    break;
                }
                chain.push(d.squarefree());
                g = d;
            }
            (q.squarefree(), chain)
        };
        let fast = match approx {
            Some(mut z) if q.degree().unwrap_or(0) > 0 => {
                // q = p / (x - 1): drop the approximation nearest to 1.
                let one = num_complex::Complex64::new(1.0, 0.0);
                if let Some(k) = (0..z.len())
                    .min_by(|&i, &j| (z[i] - one).norm().total_cmp(&(z[j] - one).norm()))
                {
                    z.remove(k);
                }
                // Square-free factors a_k = s_(k-1) / s_k (s_0 = sf, s_k = chain[k-1]).
                let mut factors = Vec::new();
                let mut prev = sf.clone();
                for s in chain
                    .iter()
                    .chain(std::iter::once(&Poly::constant(Rational::one())))
                {
                    factors.push(prev.divrem(s).0);
                    prev = s.clone();
                }
                RootStructure::certify(&factors, &sf, &z)
            }
            _ => None,
        };
        Roots {
            q: q.clone(),
            sf,
            chain,
            fast,
            q_int,
            sturm_sf: None,
            sturm_chain: None,
        }
    }

    fn sturm_sf(&mut self) -> &Sturm {
        self.sturm_sf.get_or_insert_with(|| Sturm::new(&self.sf))
    }

    /// Isolating intervals of the real roots of `q` with multiplicities.
    fn real_roots(&mut self, width: &Rational) -> Vec<(Rational, Rational, usize)> {
        if self.q.degree().unwrap_or(0) == 0 {
            return Vec::new();
        }
        if let Some(f) = &mut self.fast {
            let b = self.sf.root_bound();
            return f
                .isolate(&b, width)
                .into_iter()
                .map(|(lo, hi, k)| {
                    let m = f.real_mult(k);
                    (lo, hi, m)
                })
                .collect();
        }
        let intervals = isolate_real_roots(&self.sf, width);
        let chain: &Vec<Sturm> = self
            .sturm_chain
            .get_or_insert_with(|| self.chain.iter().map(Sturm::new).collect());
        intervals
            .into_iter()
            .map(|(lo, hi)| {
                let m = 1 + chain.iter().filter(|s| s.count(&lo, &hi) > 0).count();
                (lo, hi, m)
            })
            .collect()
    }

    /// Roots of `q` (with multiplicity) of modulus `> t` ([`roots_outside`]).
    fn outside(&self, t: &Rational) -> Option<usize> {
        if self.q.degree().unwrap_or(0) == 0 {
            return Some(0);
        }
        if let Some(c) = self.fast.as_ref().and_then(|f| f.count_outside(t)) {
            if certify::schur_cohn_regular(&self.q_int, t) {
                return Some(c);
            }
        }
        roots_outside(&self.q, t)
    }

    /// Distinct real roots in `(a, +infinity)`.
    fn count_above(&mut self, a: &Rational) -> usize {
        match &mut self.fast {
            Some(f) => f.count_above(a),
            None => self.sturm_sf().count_above(a),
        }
    }

    /// Distinct real roots in `(-infinity, b]`.
    fn count_below(&mut self, b: &Rational) -> usize {
        match &mut self.fast {
            Some(f) => f.count_below(b),
            None => self.sturm_sf().count_below(b),
        }
    }

    /// Distinct real roots in `(a, b]`.
    fn count(&mut self, a: &Rational, b: &Rational) -> usize {
        match &mut self.fast {
            Some(f) => f.count(a, b),
            None => self.sturm_sf().count(a, b),
        }
    }

    /// `rank(A - lambda I)` for the root `lambda` of the square-free
    /// polynomial of the multiple roots isolated in `(lo, hi]`
    /// ([`rank_at_root`]); `p` is the face block's characteristic polynomial.
    fn rank(&mut self, a: &DMatrix<Rational>, p: &Poly, lo: &Rational, hi: &Rational) -> usize {
        let multi = match self.chain.first() {
            Some(m) => m.clone(),
            None => self.q.gcd(&self.q.derivative()).squarefree(),
        };
        if let Some(f) = &mut self.fast {
            // All roots of `multi` semisimple => rank = n - (multiplicity of lambda in p).
            let mut e = p.clone();
            loop {
                let g = e.gcd(&multi);
                if g.degree().unwrap_or(0) == 0 {
                    break;
                }
                e = e.divrem(&g).0;
            }
            let k = (0..f.real_count()).find(|&k| !f.le(k, lo) && f.le(k, hi));
            if let Some(k) = k {
                if certify::annihilates(a, &multi.mul(&e)) {
                    // (lo, hi] holds one root of q: it is 1 iff q(1) = 0 and 1 is in it.
                    let one = Rational::one();
                    let at_one = lo < &one && &one <= hi && self.q.eval(&one).is_zero();
                    let m = f.real_mult(k) + usize::from(at_one);
                    return a.nrows().saturating_sub(m);
                }
            }
        }
        rank_at_root(a, &multi, lo, hi)
    }
}

/// Floating-point eigenvalues of the face block (root approximations for
/// [`super::certify`]; any values are safe: a bad guess only means the
/// reference algorithms run).
fn approx_eigenvalues(a: &DMatrix<Rational>) -> Option<Vec<num_complex::Complex64>> {
    let n = a.nrows();
    let mut ws = super::kernel::KernelWorkspace::new();
    let input = ws.input(n);
    for j in 0..n {
        for i in 0..n {
            input[i + j * n] = rational_to_f64(&a[(i, j)]);
        }
    }
    if input.iter().any(|x| !x.is_finite()) {
        return None;
    }
    // The project's bounded kernel (no unbounded eigen-solver).
    let (wr, wi) = ws.eigenvalues().ok()?;
    Some(
        wr.iter()
            .zip(wi)
            .map(|(&re, &im)| num_complex::Complex64::new(re, im))
            .collect(),
    )
}

/// The floating-point classification of the same configuration (for thresholds).
fn float_guide(scheme: &LocalScheme<Rational>) -> Option<Subdominant> {
    let f = match scheme {
        LocalScheme::Nurds(r) => LocalScheme::nurds(r.to_f64()),
        LocalScheme::DooSabin { valence } => LocalScheme::<f64>::doo_sabin(*valence).ok()?,
        LocalScheme::CcVariant { valence } => LocalScheme::<f64>::cc_variant(*valence).ok()?,
        #[allow(unreachable_patterns)]
        _ => return None,
    };
    super::classify_scheme(&f).ok()
}

/// A rational close to `x` (dyadic, 2^-40 resolution).
fn rat(x: f64) -> Rational {
    let scale = (1u64 << 40) as f64;
    Rational::new(
        BigInt::from((x * scale).round() as i64),
        BigInt::from(1u64 << 40),
    )
}

/// Exact verdicts for a Doo-Sabin-family configuration with rational
/// parameters; `float` (optional; computed internally when `None`) supplies
/// the thresholds, and a given `float` verdict is compared.
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::scalar::Rational;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::{exact::exact_verdict, ClassName};
/// let s = LocalScheme::nurds(EdgeRatios::<Rational>::uniform(5).unwrap());
/// let v = exact_verdict(&s, None).unwrap();
/// assert_eq!(v.class, Some(ClassName::Standard));
/// assert!(v.one_is_simple && v.theorem1_certificate);
/// ```
pub fn exact_verdict(
    scheme: &LocalScheme<Rational>,
    float: Option<&Subdominant>,
) -> Result<ExactVerdict> {
    verdict(scheme, float, true)
}

/// [`exact_verdict`] by the reference algorithms alone (Sturm sequences,
/// rational Schur-Cohn recursion, rank over `Q[x]/(f)`): the cross-check of the
/// certified fast path.
#[cfg(test)]
pub(crate) fn exact_verdict_reference(
    scheme: &LocalScheme<Rational>,
    float: Option<&Subdominant>,
) -> Result<ExactVerdict> {
    verdict(scheme, float, false)
}

fn verdict(
    scheme: &LocalScheme<Rational>,
    float: Option<&Subdominant>,
    fast: bool,
) -> Result<ExactVerdict> {
    let n = scheme.valence();
    let a = scheme.face_block()?;
    let deflated = if fast { deflate_unit_rows(&a) } else { None };
    let (p, (q, r)) = match deflated {
        // Rows sum to 1: p = (x - 1) charpoly(A'), remainder 0.
        Some(d) => {
            let q = certify::charpoly_multimodular(&d);
            (Poly::linear(Rational::one()).mul(&q), (q, Poly::zero()))
        }
        None => {
            let p = charpoly(&a);
            let qr = p.divrem(&Poly::linear(Rational::one()));
            (p, qr)
        }
    };
    if !r.is_zero() {
        return Err(SpectralError::Exact(format!(
            "1 is not an eigenvalue of the face block (p(1) = {})",
            r.coeffs()[0].to_text()
        )));
    }
    let one_is_simple = !q.eval(&Rational::one()).is_zero();
    let mut roots = Roots::new(&q, if fast { approx_eigenvalues(&a) } else { None });
    // Real roots with multiplicities.
    let width = rat(ISOLATION_WIDTH).max(Rational::new(1.into(), BigInt::from(1u64 << 40)));
    let isolated = roots.real_roots(&width);
    let intervals: Vec<(Rational, Rational)> = isolated
        .iter()
        .map(|(lo, hi, _)| (lo.clone(), hi.clone()))
        .collect();
    let real_roots: Vec<RealRoot> = isolated
        .iter()
        .map(|(lo, hi, m)| RealRoot {
            interval: [rational_to_f64(lo), rational_to_f64(hi)],
            multiplicity: *m,
        })
        .collect();
    // Spectral bound |z| < 3/4.
    let spectral_bound_below_three_quarters = if q.degree().unwrap_or(0) == 0 {
        Some(true)
    } else {
        // Zero roots outside and a non-singular count => none on the circle either.
        roots
            .outside(&Rational::new(3.into(), 4.into()))
            .map(|c| c == 0)
    };
    let cert = contraction::certificate(scheme)?;
    let quarter = Rational::new(1.into(), 4.into());
    // Count of all non-unit eigenvalues of S_n with modulus > t.
    let count_full = |roots: &Roots, t: &Rational| -> Option<usize> {
        let cq = roots.outside(t)?;
        let mut extra = 0;
        for (v, m) in [(1i64, 4i64), (1, 8), (1, 16)] {
            let e = Rational::new(v.into(), m.into());
            if &e == t {
                return None;
            }
            if &e > t {
                extra += n;
            }
        }
        Some(cq + extra)
    };
    let mut top_pair = TopPair::Undecided {
        reason: "no threshold separated |lambda_2| from |lambda_3|".into(),
    };
    let mut separated = None;
    let mut reason = String::new();
    // Candidate thresholds: between the float |lambda_2| and |lambda_3|.
    let mut candidates = Vec::new();
    // Without a float verdict, compute one (thresholds only; any t is valid).
    let own_guide = match float {
        Some(_) => None,
        None => float_guide(scheme),
    };
    if let Some(f) = float.or(own_guide.as_ref()) {
        let (m2, m3) = (f.lambda2.norm(), f.abs_lambda3);
        if m2 > m3 {
            for w in [0.5, 0.25, 0.75, 0.1, 0.9] {
                candidates.push(rat(m3 + w * (m2 - m3)));
            }
        }
    }
    let mut found = false;
    let mut double_positive = None;
    for t in &candidates {
        if t <= &Rational::zero() {
            continue;
        }
        if let Some(c) = count_full(&roots, t) {
            if c == 2 {
                found = true;
                separated = Some(true);
                // Real roots of q with |x| > t (extras are below t: c == 2 < n).
                let real = roots.count_above(t) + roots.count_below(&(-t.clone()));
                top_pair = match real {
                    0 => TopPair::ComplexPair,
                    2 => TopPair::RealDistinct,
                    1 => {
                        // The double real root: its isolating interval, cut at +-t.
                        let positive = roots.count_above(t) == 1;
                        double_positive = Some(positive);
                        let neg_t = -t.clone();
                        let iv = intervals.iter().find_map(|(lo, hi)| {
                            let (lo, hi) = if positive {
                                (if lo > t { lo.clone() } else { t.clone() }, hi.clone())
                            } else {
                                (
                                    lo.clone(),
                                    if hi < &neg_t {
                                        hi.clone()
                                    } else {
                                        neg_t.clone()
                                    },
                                )
                            };
                            (lo < hi && roots.count(&lo, &hi) == 1).then_some((lo, hi))
                        });
                        match iv {
                            Some((lo, hi)) => {
                                let rank = roots.rank(&a, &p, &lo, &hi);
                                TopPair::RealDouble {
                                    semisimple: rank + 2 == n,
                                }
                            }
                            None => TopPair::Undecided {
                                reason: "could not isolate the double real root".into(),
                            },
                        }
                    }
                    _ => TopPair::Undecided {
                        reason: format!("{real} real roots among the two largest"),
                    },
                };
                reason = format!(
                    "exactly 2 eigenvalues have modulus > {} (Schur-Cohn); {} of them real (Sturm)",
                    rational_to_f64(t),
                    real
                );
                break;
            }
        }
    }
    if !found {
        // Not separated when at most one root of q lies outside |z| = 1/4:
        // then lambda_2 = lambda_3 = 1/4 (n >= 3 copies from the E blocks).
        let cq = roots.outside(&quarter);
        if let Some(c) = cq {
            if c <= 1 {
                separated = Some(false);
                reason = format!(
                    "{c} root(s) of q have modulus > 1/4, so |lambda_2| = |lambda_3| = 1/4 (E blocks)"
                );
                top_pair = TopPair::Undecided {
                    reason: "lambda_2 is the multiple eigenvalue 1/4".into(),
                };
            }
        }
        if separated.is_none() {
            reason =
                "no rational threshold between |lambda_2| and |lambda_3| gave a count of 2".into();
        }
    }
    let class = if !one_is_simple || separated == Some(false) {
        Some(ClassName::NotSeparated)
    } else if separated == Some(true) {
        match &top_pair {
            // Standard needs a positive double eigenvalue (math doc section 7);
            // the float classifier reports a non-positive one as not separated.
            TopPair::RealDouble { semisimple: true } if double_positive == Some(true) => {
                Some(ClassName::Standard)
            }
            TopPair::RealDouble { semisimple: true } => Some(ClassName::NotSeparated),
            TopPair::RealDouble { semisimple: false } => Some(ClassName::Defective),
            TopPair::RealDistinct => Some(ClassName::RealDistinct),
            TopPair::ComplexPair => Some(ClassName::ComplexPair),
            TopPair::Undecided { .. } => None,
        }
    } else {
        None
    };
    if !one_is_simple {
        reason = "1 is a multiple root of the face block's characteristic polynomial".into();
    }
    let agrees_with_float = match (float.and_then(|f| f.class.class_name()), class) {
        (Some(f), Some(e)) => Some(f == e),
        _ => None,
    };
    Ok(ExactVerdict {
        face_charpoly: p.to_text(),
        reduced_charpoly: q.to_text(),
        one_is_simple,
        real_root_count: intervals.len(),
        real_roots,
        spectral_bound_below_three_quarters,
        top_pair,
        separated,
        class,
        reason,
        theorem1_certificate: cert.holds(),
        agrees_with_float,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::{CornerIntervals, EdgeRatios};
    use crate::rng::SplitMix64;

    fn q(a: i64, b: i64) -> Rational {
        Rational::new(a.into(), b.into())
    }

    /// The multimodular characteristic polynomial (certify.rs) against the
    /// rational Hessenberg one (this module): two independent methods.
    #[test]
    fn multimodular_charpoly_matches_rational_hessenberg() {
        let mut rng = crate::rng::SplitMix64::new(3);
        for m in [1usize, 2, 3, 6, 9] {
            let a = DMatrix::from_fn(m, m, |_, _| {
                let num = (rng.next_u64() % 41) as i64 - 20;
                let den = 1 + (rng.next_u64() % 97) as i64;
                Rational::new(num.into(), den.into())
            });
            assert_eq!(certify::charpoly_multimodular(&a), charpoly(&a), "m = {m}");
        }
        // A zero sub-diagonal (block triangular) and a zero matrix.
        let mut a = DMatrix::from_element(4, 4, Rational::zero());
        a[(0, 1)] = q(3, 1);
        a[(2, 3)] = Rational::new(1.into(), 7.into());
        assert_eq!(certify::charpoly_multimodular(&a), charpoly(&a));
    }

    /// Random rational knot intervals a/b, a and b in 1..12.
    fn random_knots(rng: &mut SplitMix64, n: usize) -> LocalScheme<Rational> {
        let mut draw = || {
            q(
                1 + (rng.next_u64() % 12) as i64,
                1 + (rng.next_u64() % 12) as i64,
            )
        };
        let p: Vec<Rational> = (0..n).map(|_| draw()).collect();
        let qq: Vec<Rational> = (0..n).map(|_| draw()).collect();
        LocalScheme::nurds(CornerIntervals::new(p, qq).unwrap().ratios().unwrap())
    }

    fn same(s: &LocalScheme<Rational>) -> ExactVerdict {
        let fast = exact_verdict(s, None).unwrap();
        let reference = exact_verdict_reference(s, None).unwrap();
        assert_eq!(fast, reference, "valence {}", s.valence());
        fast
    }

    #[test]
    fn fast_path_matches_reference_on_random_rationals() {
        let mut rng = SplitMix64::new(16);
        let mut classes = std::collections::HashSet::new();
        for trial in 0..36 {
            let n = 3 + trial % 6;
            classes.insert(same(&random_knots(&mut rng, n)).class);
        }
        // Both non-standard generic classes occur, so both branches ran.
        assert!(
            classes.contains(&Some(ClassName::RealDistinct))
                && classes.contains(&Some(ClassName::ComplexPair)),
            "{classes:?}"
        );
    }

    #[test]
    fn fast_path_matches_reference_on_multiple_roots() {
        // Uniform: double roots, the semisimple rank through (f e)(A) = 0.
        for n in 3..=10 {
            let v = same(&LocalScheme::nurds(
                EdgeRatios::<Rational>::uniform(n).unwrap(),
            ));
            assert_eq!(
                v.top_pair,
                TopPair::RealDouble { semisimple: true },
                "n = {n}"
            );
            assert!(v.real_roots.iter().any(|r| r.multiplicity == 2), "n = {n}");
        }
        // A defective double root (the fast rank test must decline).
        let d = EdgeRatios::new(vec![q(69, 250), q(529, 1000), q(181, 250), q(37, 50)]).unwrap();
        let v = same(&LocalScheme::nurds(d));
        assert_eq!(v.top_pair, TopPair::RealDouble { semisimple: false });
        // Tensor-product knots and the original Doo-Sabin weights.
        let t = EdgeRatios::new(vec![q(3, 10), q(1, 5), q(7, 10), q(4, 5)]).unwrap();
        assert_eq!(
            same(&LocalScheme::nurds(t)).class,
            Some(ClassName::Standard)
        );
        for n in [3, 4, 6] {
            same(&LocalScheme::<Rational>::doo_sabin(n).unwrap());
        }
    }

    #[test]
    fn deflation_keeps_the_characteristic_polynomial() {
        let mut rng = SplitMix64::new(5);
        for n in [3, 5, 8] {
            let a = random_knots(&mut rng, n).face_block().unwrap();
            let d = deflate_unit_rows(&a).unwrap();
            assert_eq!(
                Poly::linear(Rational::one()).mul(&charpoly(&d)),
                charpoly(&a),
                "n = {n}"
            );
        }
        // Rows not summing to 1: no deflation.
        let mut a = DMatrix::from_element(2, 2, q(1, 2));
        assert!(deflate_unit_rows(&a).is_some());
        a[(0, 0)] = q(1, 3);
        assert!(deflate_unit_rows(&a).is_none());
    }
}
