//! The shape-adjustable Catmull-Clark scheme tuned for bounded curvature:
//! `mu / lambda^2` against `c`, and the values of `c` where `mu = lambda^2`,
//! certified (math doc section 13.3).
//!
//! The second-order spectrum (the `2n + 8` patch matrix, math doc section
//! 13.5) is the union of the one-ring's Fourier blocks' spectra (math doc
//! sections 6 and 8; [`crate::schemes::catmull_clark::fourier`]) and the
//! regular part ([`fourier::patch_spectrum`]): block 0
//! contributes 1 and the roots of `x^2 - t_0 x + d_0` with
//! `t_0 = (3n - 16c + 4c^2)/(4n)`, `d_0 = (n(1 - c) - 8c + 12c^2 - 4c^3)/(8n)`;
//! block `l = 1..n-1` the roots of `x^2 - t_l x + (1 - c)/8` with
//! `t_l = 3/4 - c/4 + (c/4) cos(2 pi l / n)`; the regular part's largest is
//! `c/4` (the others, `c/8`, `c(1 - c)/8`, `c^2/16`, are below it). With the
//! `2n + 1` moduli (the `2n` non-unit Fourier ones and `c/4`) sorted,
//! `lambda` is the largest (the pair `l = 1, n - 1`; `lambda >= 3/8 > 1/4 >= c/4`)
//! and `mu` the third largest, and `F(c) = mu - lambda^2`. The regular part
//! decides `mu` at `n = 3` for `c > 0.557` and moves the second root there
//! to `c = 0.63120`.
//!
//! **Rigorous sign evaluation.** [`enclosure`] evaluates `F(c)` in interval
//! arithmetic with outward rounding: every `f64` operation (`+ - * /` and
//! `sqrt`, all correctly rounded in IEEE 754) is followed by one step
//! outward (to the neighbouring double), so each computed interval
//! contains the exact value. `cos(2 pi l / n)` enters as an enclosure proved
//! over the rationals: it is a root of `T_n(x) - 1` (Chebyshev); a Sturm
//! count (`Sturm`) proves that a small interval around the `f64` cosine
//! holds exactly one root, and the intervals' order identifies which. The moduli of a quadratic's
//! roots are enclosed for real, complex and undecided discriminants; the
//! `k`-th largest of interval values is enclosed by the `k`-th largest lower
//! and upper ends (the order statistic is monotone in each argument). A sign
//! is *certified* when the enclosure of `F` excludes 0.
//!
//! **Certified roots.** On a grid of `c` in `[0, 1]`, two neighbours with
//! certified opposite signs bracket a root of `F` (continuous in `c`: the
//! sorted moduli of the roots of a polynomial depend continuously on its
//! coefficients); the bracket is narrowed by bisection on certified signs to
//! [`ROOT_WIDTH`] or until the sign at the midpoint is undecided. Grid
//! points with an undecided sign (on the coarser grid [`EXACT_GRID`]) are
//! tried with the exact certificate of
//! [`crate::curvature`] (rational `c`: the patch matrix is rational); at
//! `n = 4` this certifies `mu = lambda^2` on the whole of `[1/2, 1]` sampled
//! (math doc section 13.3 derives it for every `c` there).
//!
//! ```
//! use subdiv_lab::curvature::tuning::{tune, Sign};
//! let t = tune(5, 40).unwrap();
//! assert_eq!(t.roots.len(), 1);
//! let r = &t.roots[0];
//! assert!(r.c_lo < 0.686 && 0.684 < r.c_hi && r.c_hi - r.c_lo <= 1e-12);
//! assert_eq!(t.curve[20].sign, Sign::Positive); // c = 1/2: Catmull-Clark, unbounded at n = 5
//! ```

use crate::error::Error;
use crate::scalar::{f64_to_rational, rational_to_f64, Rational};
use crate::schemes::catmull_clark::fourier;
use crate::schemes::LocalScheme;
use crate::spectral::poly::{Poly, Sturm};
use crate::spectral::Result;
use num_bigint::BigInt;
use num_traits::One;
use serde::Serialize;

/// Width to which certified root brackets are narrowed: `1e-12`, a thousand
/// times the spacing of doubles near `c = 1`, so the bisection stops on the
/// width rather than on rounding in the common case.
pub const ROOT_WIDTH: f64 = 1e-12;

/// Half-width of the rational intervals around the `f64` cosines that are
/// proved to isolate `cos(2 pi l / n)`: `2^-50`, a few hundred ulps (the
/// `f64` cosine is within a few ulps of the true value, so the proof
/// succeeds; if it did not, [`cos_enclosures`] would fail, never guess).
/// The width enters every sign decision, and is far below the margins
/// `|mu - lambda^2|` away from the roots.
pub const COS_ISOLATION_BITS: u32 = 50;

/// Grid points with an undecided sign get the exact certificate only where
/// `c` is a multiple of `1 / EXACT_GRID` (and on the sampling grid): each
/// certificate costs a rational characteristic polynomial (about 5 ms at
/// `n = 4`), and 33 points over `[0, 1]` show the bounded stretch of `n = 4`
/// at a fraction of the default report's time budget.
pub const EXACT_GRID: usize = 32;

/// Largest valence [`tune`] accepts (the Chebyshev polynomial has degree `n`).
pub const MAX_VALENCE: usize = 64;

/// Largest number of grid cells [`tune`] accepts.
pub const MAX_GRID: usize = 100_000;

/// A closed interval `[lo, hi]` of reals with `f64` ends.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Interval {
    /// The point interval `[x, x]`.
    pub fn point(x: f64) -> Self {
        Self { lo: x, hi: x }
    }
    fn out(lo: f64, hi: f64) -> Self {
        Self {
            lo: step_down(lo),
            hi: step_up(hi),
        }
    }
    fn add(self, o: Self) -> Self {
        Self::out(self.lo + o.lo, self.hi + o.hi)
    }
    fn sub(self, o: Self) -> Self {
        Self::out(self.lo - o.hi, self.hi - o.lo)
    }
    fn mul(self, o: Self) -> Self {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        Self::out(
            p.iter().copied().fold(f64::INFINITY, f64::min),
            p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }
    /// Division by a positive constant.
    fn div(self, k: f64) -> Self {
        Self::out(self.lo / k, self.hi / k)
    }
    /// `sqrt` of the non-negative part.
    fn sqrt(self) -> Self {
        Self::out(self.lo.max(0.0).sqrt(), self.hi.max(0.0).sqrt())
    }
    fn abs(self) -> Self {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            Self {
                lo: -self.hi,
                hi: -self.lo,
            }
        } else {
            Self {
                lo: 0.0,
                hi: self.hi.max(-self.lo),
            }
        }
    }
    fn hull(self, o: Self) -> Self {
        Self {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }
    /// Whether the interval lies strictly on one side of 0.
    pub fn sign(self) -> Sign {
        if self.lo > 0.0 {
            Sign::Positive
        } else if self.hi < 0.0 {
            Sign::Negative
        } else {
            Sign::Undecided
        }
    }
}

/// The next `f64` above `x` (`f64::next_up`, which needs Rust 1.86; the
/// crate's MSRV is 1.85): infinities and NaN are returned unchanged.
fn step_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// The next `f64` below `x`.
fn step_down(x: f64) -> f64 {
    -step_up(-x)
}

/// A certified sign of `mu - lambda^2`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sign {
    /// `mu < lambda^2` (curvature tends to zero).
    Negative,
    /// `mu > lambda^2` (unbounded curvature).
    Positive,
    /// The enclosure contains 0.
    Undecided,
}

impl Sign {
    /// `"negative"`, `"positive"` or `"undecided"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Sign::Negative => "negative",
            Sign::Positive => "positive",
            Sign::Undecided => "undecided",
        }
    }
}

/// Enclosures of `cos(2 pi l / n)` for `l = 0..=n/2`, proved over the
/// rationals (module docs).
pub fn cos_enclosures(n: usize) -> Result<Vec<Interval>> {
    if !(3..=MAX_VALENCE).contains(&n) {
        return Err(Error::InvalidParameter {
            name: "valence",
            value: n.to_string(),
            reason: "the curvature tuning takes valences 3..=64",
        }
        .into());
    }
    // Chebyshev T_0 = 1, T_1 = x, T_{k+1} = 2x T_k - T_{k-1}.
    let one = Rational::one();
    let x = Poly::new(vec![Rational::from_integer(BigInt::from(0)), one.clone()]);
    let two_x = x.scale(&Rational::from_integer(BigInt::from(2)));
    let (mut a, mut b) = (Poly::constant(one.clone()), x);
    for _ in 1..n {
        let c = two_x.mul(&b).sub(&a);
        a = b;
        b = c;
    }
    let g = b.sub(&Poly::constant(one)).squarefree();
    let sturm = Sturm::new(&g);
    let m = n / 2;
    if sturm.count_all() != m + 1 {
        return Err(Error::Numerical {
            routine: "cos enclosures",
            reason: format!(
                "T_{n}(x) - 1 has {} distinct real roots, expected {}",
                sturm.count_all(),
                m + 1
            ),
        }
        .into());
    }
    // Candidate intervals around the f64 cosines, proved to hold one root
    // each (Sturm counts over (lo, hi]); disjoint and decreasing in l, they
    // hold the m + 1 roots in order, i.e. cos(2 pi l / n) is in the l-th.
    let delta = Rational::new(BigInt::from(1), BigInt::from(1u64) << COS_ISOLATION_BITS);
    let mut out = Vec::with_capacity(m + 1);
    let mut prev_lo: Option<Rational> = None;
    for l in 0..=m {
        let x = (2.0 * std::f64::consts::PI * l as f64 / n as f64).cos();
        let xq = f64_to_rational(x).ok_or_else(|| Error::Numerical {
            routine: "cos enclosures",
            reason: format!("cos(2 pi {l} / {n}) is not finite"),
        })?;
        let (lo, hi) = (&xq - &delta, &xq + &delta);
        let disjoint = prev_lo.as_ref().is_none_or(|p| hi < *p);
        if !disjoint || sturm.count(&lo, &hi) != 1 {
            return Err(Error::Numerical {
                routine: "cos enclosures",
                reason: format!(
                    "could not isolate cos(2 pi {l} / {n}) within 2^-{COS_ISOLATION_BITS}"
                ),
            }
            .into());
        }
        out.push(Interval::out(rational_to_f64(&lo), rational_to_f64(&hi)));
        prev_lo = Some(lo);
    }
    Ok(out)
}

/// Enclosures of the moduli of the two roots of `x^2 - t x + d`.
fn quadratic_moduli(t: Interval, d: Interval) -> [Interval; 2] {
    let disc = t.mul(t).sub(d.mul(Interval::point(4.0)));
    let real = |disc: Interval| {
        let s = disc.sqrt();
        [t.add(s).div(2.0).abs(), t.sub(s).div(2.0).abs()]
    };
    if disc.lo >= 0.0 {
        real(disc)
    } else {
        let complex = d.sqrt();
        if disc.hi < 0.0 {
            [complex, complex]
        } else {
            let [p, q] = real(Interval {
                lo: 0.0,
                hi: disc.hi,
            });
            [p.hull(complex), q.hull(complex)]
        }
    }
}

/// The enclosures of `lambda`, `mu` and `F = mu - lambda^2` at `c` (module
/// docs), from the cosine enclosures `cos` of [`cos_enclosures`]`(n)`.
pub fn enclosure(n: usize, c: f64, cos: &[Interval]) -> [Interval; 3] {
    let ci = Interval::point(c);
    let nf = n as f64;
    let q = |x: f64| Interval::point(x);
    // Block 0.
    let c2 = ci.mul(ci);
    let c3 = c2.mul(ci);
    let t0 = q(3.0 * nf)
        .sub(ci.mul(q(16.0)))
        .add(c2.mul(q(4.0)))
        .div(4.0 * nf);
    let d0 = q(nf)
        .mul(q(1.0).sub(ci))
        .sub(ci.mul(q(8.0)))
        .add(c2.mul(q(12.0)))
        .sub(c3.mul(q(4.0)))
        .div(8.0 * nf);
    let mut moduli: Vec<Interval> = quadratic_moduli(t0, d0).to_vec();
    let d = q(1.0).sub(ci).div(8.0);
    let quarter_c = ci.div(4.0);
    // The regular part's largest eigenvalue, c/4 (module docs).
    moduli.push(quarter_c);
    for l in 1..n {
        let cl = cos[l.min(n - l)];
        let t = q(0.75).sub(quarter_c).add(quarter_c.mul(cl));
        moduli.extend(quadratic_moduli(t, d));
    }
    let kth = |k: usize| {
        let mut lo: Vec<f64> = moduli.iter().map(|i| i.lo).collect();
        let mut hi: Vec<f64> = moduli.iter().map(|i| i.hi).collect();
        lo.sort_by(|a, b| b.total_cmp(a));
        hi.sort_by(|a, b| b.total_cmp(a));
        Interval {
            lo: lo[k],
            hi: hi[k],
        }
    };
    let lambda = kth(0);
    let mu = kth(2);
    [lambda, mu, mu.sub(lambda.mul(lambda))]
}

/// One sample of the curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurvePoint {
    /// The shape parameter.
    pub c: f64,
    /// `lambda` (closed-form block eigenvalues in `f64`).
    pub lambda: f64,
    /// `mu`.
    pub mu: f64,
    /// `mu / lambda^2`.
    pub ratio: f64,
    /// The certified sign of `mu - lambda^2` (interval evaluation).
    pub sign: Sign,
    /// Whether `mu = lambda^2` was certified exactly at this `c` (only tried
    /// where the sign is undecided and `c` is a multiple of `1 / EXACT_GRID`).
    pub exact_bounded: bool,
}

/// A certified root of `mu = lambda^2`: `F` has opposite certified signs at
/// `c_lo` and `c_hi`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TunedRoot {
    /// Lower end (sign `below`).
    pub c_lo: f64,
    /// Upper end.
    pub c_hi: f64,
    /// The sign of `mu - lambda^2` at `c_lo`.
    pub below: Sign,
    /// The sign at `c_hi`.
    pub above: Sign,
}

/// The tuning result for one valence.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Tuning {
    /// The valence.
    pub n: usize,
    /// The grid samples, `c = j / grid`.
    pub curve: Vec<CurvePoint>,
    /// Certified roots, increasing.
    pub roots: Vec<TunedRoot>,
}

/// `mu / lambda^2` on `c = j / grid`, `j = 0..=grid`, with certified signs,
/// and the certified roots of `mu = lambda^2` (module docs).
pub fn tune(n: usize, grid: usize) -> Result<Tuning> {
    if !(1..=MAX_GRID).contains(&grid) {
        return Err(Error::InvalidParameter {
            name: "grid",
            value: grid.to_string(),
            reason: "the number of grid cells must be in 1..=100000",
        }
        .into());
    }
    let cos = cos_enclosures(n)?;
    let mut curve = Vec::with_capacity(grid + 1);
    for j in 0..=grid {
        let c = j as f64 / grid as f64;
        let spec = fourier::patch_spectrum(n, c)?;
        let (lambda, mu) = (spec[1].norm(), spec[3].norm());
        let sign = enclosure(n, c, &cos)[2].sign();
        let on_exact_grid = (j * EXACT_GRID) % grid == 0;
        let exact_bounded = sign == Sign::Undecided && on_exact_grid && exact_bounded_at(n, c)?;
        curve.push(CurvePoint {
            c,
            lambda,
            mu,
            ratio: mu / (lambda * lambda),
            sign,
            exact_bounded,
        });
    }
    let mut roots = Vec::new();
    for w in curve.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let opposite = matches!(
            (a.sign, b.sign),
            (Sign::Negative, Sign::Positive) | (Sign::Positive, Sign::Negative)
        );
        if !opposite {
            continue;
        }
        let (mut lo, mut hi) = (a.c, b.c);
        while hi - lo > ROOT_WIDTH {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            match enclosure(n, mid, &cos)[2].sign() {
                s if s == a.sign => lo = mid,
                s if s == b.sign => hi = mid,
                _ => break,
            }
        }
        roots.push(TunedRoot {
            c_lo: lo,
            c_hi: hi,
            below: a.sign,
            above: b.sign,
        });
    }
    Ok(Tuning { n, curve, roots })
}

/// Whether the exact certificate proves bounded curvature at `c`: `mu =
/// lambda^2` with `mu` non-defective (math doc section 13.1).
fn exact_bounded_at(n: usize, c: f64) -> Result<bool> {
    let s = LocalScheme::adjustable_cc(n, c)?;
    let r = crate::spectral::curvature::curvature(&s)?;
    Ok(
        r.verdict == crate::spectral::curvature::CurvatureVerdict::Bounded
            && r.evidence == crate::spectral::curvature::CurvatureEvidence::Exact,
    )
}
