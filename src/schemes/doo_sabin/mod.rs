//! The Doo-Sabin family: NURDS, original Doo-Sabin, and the Catmull-Clark variant.
//!
//! Math doc section 4 (seed 000). After at most two steps the neighbourhood of
//! an n-sided face is `4n` points, ordered
//!
//! ```text
//! M = [P_0..P_{n-1}, E_01, E_02, E_11, E_12, .., E_{n-1,1}, E_{n-1,2}, C_0..C_{n-1}]
//! ```
//!
//! and `M' = S_n M` with (indices mod n, `s_i = 1 - r_i`)
//!
//! ```text
//! P'_i  = 1/4 (I + R + 1 c^T) P                              (the face block A)
//! E'_i1 = 3/8 (1 + r_i) P_i + 3/8 s_i P_{i+1} + 1/8 (1 + r_i) E_i1 + 1/8 s_i E_i2
//! E'_i2 = 3/8 r_i P_i + 3/8 (1 + s_i) P_{i+1} + 1/8 r_i E_i1 + 1/8 (1 + s_i) E_i2
//! C'_i  = 1/16 (9 P_i + 3 E_i1 + 3 E_{i-1,2} + C_i)
//! ```
//!
//! where `R[i,i-1] = r_{i-1}`, `R[i,i] = 1 - r_{i-1} + r_i`, `R[i,i+1] = 1 - r_i`
//! and `c` are the face weights. Written out, row `i` of `A` is
//! `1/4 (2 + c_i + r_i - r_{i-1})` on `P_i`, `1/4 (c_{i-1} + r_{i-1})` on `P_{i-1}`,
//! `1/4 (1 + c_{i+1} - r_i)` on `P_{i+1}` and `c_j / 4` elsewhere (for `n = 3`
//! there is no "elsewhere").
//!
//! * **Original Doo-Sabin** (seed 004): the face block is
//!   `w_ii = (n+5)/(4n)`, `w_ij = (3 + 2 cos(2 pi (i-j)/n)) / (4n)`; E/C rows at `r = 1/2`.
//! * **Catmull-Clark variant**: uniform NURDS (`r_i = 1/2`, `c_j = 1/n`), i.e.
//!   `P'_i = 1/2 P_i + 1/8 (P_{i-1} + P_{i+1}) + F/4`.

pub mod extended;
pub mod ring;

use super::assembly::{Assembler, LocalMatrix, PointLabel, Role};
use crate::budget::{
    CostModel, ANALYZE_BYTES_PER_ENTRY_DS, ANALYZE_SECONDS_PER_N3_DS_FULL,
    ANALYZE_SECONDS_PER_N3_DS_STRUCTURED,
};
use crate::error::{Error, Result};
use crate::knots::{face_weights, EdgeRatios};
use crate::scalar::Scalar;
use nalgebra::DMatrix;

/// The work model of the family ([`crate::budget`]): the `4n x 4n` matrix
/// `S_n`; the classification works on the `n x n` face block (its `O(n^3)`
/// kernel is part of the sweep's base cost), the characteristic map like
/// `analyze --path structured`.
pub const COST_MODEL: CostModel = CostModel {
    dimension_per_valence: 4.0,
    dimension_offset: 0.0,
    analyze_bytes_per_entry: ANALYZE_BYTES_PER_ENTRY_DS,
    analyze_seconds_per_n3_full: ANALYZE_SECONDS_PER_N3_DS_FULL,
    analyze_seconds_per_n3_structured: ANALYZE_SECONDS_PER_N3_DS_STRUCTURED,
    sweep_classify_seconds_per_n3: 0.0,
    sweep_classify_on_face_block: true,
    sweep_charmap_seconds_per_n3: ANALYZE_SECONDS_PER_N3_DS_STRUCTURED,
};

/// Point labels of the `4n` configuration, in the order of math doc section 4.
pub fn labels(n: usize) -> Vec<PointLabel> {
    let mut v = Vec::with_capacity(4 * n);
    v.extend((0..n).map(|i| PointLabel::new(Role::FaceCorner, i)));
    for i in 0..n {
        v.push(PointLabel::new(Role::EdgeFirst, i));
        v.push(PointLabel::new(Role::EdgeSecond, i));
    }
    v.extend((0..n).map(|i| PointLabel::new(Role::Corner, i)));
    v
}

/// Column index of `P_i`, `E_i1`, `E_i2`, `C_i` in the `4n` ordering.
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    n: usize,
}

impl Layout {
    /// Layout for valence `n`.
    pub fn new(n: usize) -> Self {
        Self { n }
    }
    /// `P_i`.
    pub fn p(&self, i: usize) -> usize {
        i % self.n
    }
    /// `E_{i1}`.
    pub fn e1(&self, i: usize) -> usize {
        self.n + 2 * (i % self.n)
    }
    /// `E_{i2}`.
    pub fn e2(&self, i: usize) -> usize {
        self.n + 2 * (i % self.n) + 1
    }
    /// `C_i`.
    pub fn c(&self, i: usize) -> usize {
        3 * self.n + i % self.n
    }
}

/// The NURDS face block `A = 1/4 (I + R + 1 c^T)` (n x n) and the face weights `c`.
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::doo_sabin::nurds_face_block;
/// let (a, c) = nurds_face_block(&EdgeRatios::<f64>::uniform(4).unwrap());
/// assert_eq!(a[(0, 0)], 0.5 + 0.25 * 0.25);   // 1/2 + c_0/4
/// assert_eq!(c, vec![0.25; 4]);
/// ```
pub fn nurds_face_block<T: Scalar>(ratios: &EdgeRatios<T>) -> (DMatrix<T>, Vec<T>) {
    let c = face_weights(ratios);
    (face_block_from(ratios, &c), c)
}

/// `1/4 (I + R + 1 c^T)` for given ratios and face weights.
pub(crate) fn face_block_from<T: Scalar>(ratios: &EdgeRatios<T>, c: &[T]) -> DMatrix<T> {
    let n = ratios.valence();
    let r = ratios.as_slice();
    let s = ratios.complement();
    let quarter = T::frac(1, 4);
    // c_j / 4 once per column (exact c_j can have thousands of bits; scaling
    // each of the n^2 entries would be the bulk of an exact assembly).
    let c4: Vec<T> = c.iter().map(|x| x.clone() * quarter.clone()).collect();
    let mut a = DMatrix::from_fn(n, n, |_, j| c4[j].clone());
    for i in 0..n {
        let prev = (i + n - 1) % n;
        let next = (i + 1) % n;
        // (I + R) / 4: diagonal 1 + (1 - r_{i-1}) + r_i, sub r_{i-1}, super 1 - r_i.
        a[(i, i)] =
            a[(i, i)].clone() + (T::one() + s[prev].clone() + r[i].clone()) * quarter.clone();
        a[(i, prev)] = a[(i, prev)].clone() + r[prev].clone() * quarter.clone();
        a[(i, next)] = a[(i, next)].clone() + s[i].clone() * quarter.clone();
    }
    a
}

/// `cos(2 pi k / n)` exactly when it is rational (denominator of `k/n` in
/// {1, 2, 3, 4, 6}), in `f64` otherwise; `None` for an irrational value in an exact type.
///
/// The `f64` value is computed at the folded index `min(k, n - k)`, so that
/// `cos_2pi(k, n) == cos_2pi(n - k, n)` bit for bit: the rotationally
/// symmetric matrices built from it are exactly mirror symmetric too, which
/// the structural certificate of a double eigenvalue checks
/// ([`crate::spectral::pairing`]).
pub fn cos_2pi<T: Scalar>(k: usize, n: usize) -> Option<T> {
    let k = fold(k, n);
    let g = gcd(k % n, n);
    let (a, b) = ((k % n) / g, n / g);
    let exact = match (a, b) {
        (0, 1) => Some(T::one()),
        (_, 2) => Some(-T::one()),
        (_, 3) => Some(T::frac(-1, 2)),
        (_, 4) => Some(T::zero()),
        (_, 6) => Some(T::frac(1, 2)),
        _ => None,
    };
    match exact {
        Some(v) => Some(v),
        None if T::EXACT => None,
        None => {
            let v = (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos();
            Some(T::from_f64_lossless(v))
        }
    }
}

/// `min(k mod n, n - k mod n)`: the index of `cos(2 pi k / n)` that makes it
/// even in `k` bit for bit.
pub(crate) fn fold(k: usize, n: usize) -> usize {
    let k = k % n;
    k.min(n - k)
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a.max(1)
    } else {
        gcd(b, a % b)
    }
}

/// Original Doo-Sabin face block: `w_ii = (n+5)/(4n)`, `w_ij = (3 + 2 cos(2 pi (i-j)/n)) / (4n)`.
///
/// In exact arithmetic only `n` in {3, 4, 6} have rational weights; other
/// valences return [`Error::InvalidParameter`].
pub fn doo_sabin_face_block<T: Scalar>(n: usize) -> Result<DMatrix<T>> {
    if n < 3 {
        return Err(Error::ValenceTooSmall { valence: n });
    }
    let den = 4 * n as i64;
    let mut cosines = Vec::with_capacity(n);
    for k in 0..n {
        cosines.push(cos_2pi::<T>(k, n).ok_or(Error::InvalidParameter {
            name: "valence",
            value: n.to_string(),
            reason: "original Doo-Sabin weights are irrational for this valence; exact arithmetic supports n = 3, 4, 6",
        })?);
    }
    Ok(DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            T::frac(n as i64 + 5, den)
        } else {
            let k = (i + n - j) % n;
            (T::frac(3, 1) + T::frac(2, 1) * cosines[k].clone()) / T::frac(den, 1)
        }
    }))
}

/// Assembles the `4n x 4n` matrix `S_n` from a face block and the edge ratios.
pub(crate) fn assemble<T: Scalar>(
    scheme: &str,
    face_block: &DMatrix<T>,
    ratios: &EdgeRatios<T>,
) -> Result<LocalMatrix<T>> {
    let n = ratios.valence();
    let lay = Layout::new(n);
    let mut asm = Assembler::square(scheme, n, labels(n));
    asm.block(0, 0, face_block);
    let (r, s) = (ratios.as_slice(), ratios.complement());
    let f = |a: i64, b: i64| T::frac(a, b);
    for i in 0..n {
        let (ri, si) = (r[i].clone(), s[i].clone());
        let one_r = T::one() + ri.clone();
        let one_s = T::one() + si.clone();
        asm.stencil(
            lay.e1(i),
            [
                (lay.p(i), f(3, 8) * one_r.clone()),
                (lay.p(i + 1), f(3, 8) * si.clone()),
                (lay.e1(i), f(1, 8) * one_r),
                (lay.e2(i), f(1, 8) * si),
            ],
        );
        asm.stencil(
            lay.e2(i),
            [
                (lay.p(i), f(3, 8) * ri.clone()),
                (lay.p(i + 1), f(3, 8) * one_s.clone()),
                (lay.e1(i), f(1, 8) * ri),
                (lay.e2(i), f(1, 8) * one_s),
            ],
        );
        asm.stencil(
            lay.c(i),
            [
                (lay.p(i), f(9, 16)),
                (lay.e1(i), f(3, 16)),
                (lay.e2(i + n - 1), f(3, 16)),
                (lay.c(i), f(1, 16)),
            ],
        );
    }
    asm.finish()
}

/// The cyclic neighbours `(i - 1, i + 1) mod n` of `i < n` (no integer division).
#[inline(always)]
pub(crate) fn neighbours(i: usize, n: usize) -> (usize, usize) {
    let prev = if i == 0 { n - 1 } else { i - 1 };
    let next = if i + 1 == n { 0 } else { i + 1 };
    (prev, next)
}

/// `M = (I + R)/4`: diagonal `(1 + s_{i-1} + r_i)/4`, sub `r_{i-1}/4`, super `s_i/4`.
pub(crate) fn fill_m(n: usize, r: &[f64], s: &[f64], f: &mut [f64]) {
    for i in 0..n {
        let (prev, next) = neighbours(i, n);
        f[i + i * n] = 0.25 * (1.0 + s[prev] + r[i]);
        f[i + prev * n] += 0.25 * r[prev];
        f[i + next * n] += 0.25 * s[i];
    }
}
