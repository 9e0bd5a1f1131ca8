//! Loop's rules at an extraordinary vertex: the weights, the two-ring, the
//! limit weights, the valence checks and the cost model (math doc section 11).

use crate::budget::{CostModel, ANALYZE_BYTES_PER_ENTRY_CC, MEMORY_LIMIT_BYTES};
use crate::error::{Error, Result};
use crate::schemes::assembly::{PointLabel, Role};

/// Smallest valence of a Loop vertex.
pub const MIN_VALENCE: usize = 3;

/// Seconds per `n^3` of `analyze` (the dense `(3n+1)` decomposition with
/// vectors and the characteristic-map certificate, either path). Measured
/// 1.4e-6 at `n = 100` and `n = 200` (1.40 s, 11.1 s) on the 2-core
/// reference machine under load; rounded up.
pub const ANALYZE_SECONDS_PER_N3: f64 = 2.0e-6;

/// Seconds per `n^3` of one sweep configuration's classification (the dense
/// `(3n+1)` decomposition). Measured 3.9e-7 CPU seconds (one thread; 159 s
/// for `n = 40..200`, one configuration each) under load; rounded up.
pub const SWEEP_CLASSIFY_SECONDS_PER_N3: f64 = 8e-7;

/// Seconds per `n^3` of one sweep configuration's characteristic-map
/// certificate on top of the classification: measured about 5e-8 (CPU,
/// `n = 40..120`, under load); rounded up.
pub const SWEEP_CHARMAP_SECONDS_PER_N3: f64 = 1e-7;

/// Loop's work model ([`crate::budget`]): the `(3n + 1)` two-ring matrix,
/// decomposed densely.
pub const COST_MODEL: CostModel = CostModel {
    dimension_per_valence: 3.0,
    dimension_offset: 1.0,
    analyze_bytes_per_entry: ANALYZE_BYTES_PER_ENTRY_CC,
    analyze_seconds_per_n3_full: ANALYZE_SECONDS_PER_N3,
    analyze_seconds_per_n3_structured: ANALYZE_SECONDS_PER_N3,
    sweep_classify_seconds_per_n3: SWEEP_CLASSIFY_SECONDS_PER_N3,
    sweep_classify_on_face_block: false,
    sweep_charmap_seconds_per_n3: SWEEP_CHARMAP_SECONDS_PER_N3,
};

/// Loop's vertex weight `beta_n = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`
/// (math doc section 11). `n >= 3` is the caller's business.
pub fn beta(n: usize) -> f64 {
    let t = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
    (0.625 - t * t) / n as f64
}

/// The subdominant eigenvalue `3/8 + cos(2 pi / n) / 4` of valence `n`.
pub fn subdominant_eigenvalue(n: usize) -> f64 {
    0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos()
}

/// Checks `n >= 3` ([`Error::ValenceTooSmall`] otherwise).
pub fn validate(n: usize) -> Result<()> {
    if n < MIN_VALENCE {
        return Err(Error::ValenceTooSmall { valence: n });
    }
    Ok(())
}

/// Refuses a valence whose dense working set (`entries` `f64` values) would
/// exceed [`MEMORY_LIMIT_BYTES`], the memory a single command may use in the
/// toolkit's budget (`crate::budget`): the library core would otherwise abort
/// on the allocation (absurd valences such as `100000` are typos; the
/// Catmull-Clark family is refused by the same limit, through the budget
/// estimates of the command-line tool). Checks `n >= 3` first.
pub(crate) fn check_size(n: usize, entries: u128, what: &'static str) -> Result<()> {
    validate(n)?;
    let bytes = entries.saturating_mul(8);
    if bytes as f64 > MEMORY_LIMIT_BYTES {
        return Err(Error::InvalidParameter {
            name: "valence",
            value: format!("{n} ({what}: {bytes} bytes)"),
            reason: "the working set exceeds the 4 GB memory limit of a single command (budget::MEMORY_LIMIT_BYTES)",
        });
    }
    Ok(())
}

/// Index arithmetic of the two-ring layout (see the module docs): `3n + 1`
/// points `v, e_i, g_i, f_i`; indices of `e`, `g`, `f` are taken mod `n`.
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::TwoRing;
/// let r = TwoRing::new(5).unwrap();
/// assert_eq!((r.v(), r.e(0), r.g(0), r.f(0)), (0, 1, 6, 7));
/// assert_eq!(r.f(5), r.f(0));
/// assert_eq!(r.labels()[r.g(2)].to_string(), "g2");
/// assert_eq!(r.len(), 16);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TwoRing {
    n: usize,
}

impl TwoRing {
    /// The layout of valence `n >= 3`.
    pub fn new(n: usize) -> Result<Self> {
        validate(n)?;
        Ok(Self { n })
    }
    /// The valence `n`.
    pub fn valence(&self) -> usize {
        self.n
    }
    /// `3n + 1`, the number of two-ring points.
    pub fn len(&self) -> usize {
        3 * self.n + 1
    }
    /// Always `false` (a two-ring has at least 10 points).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// `n + 1`, the number of one-ring points (the first indices).
    pub fn one_ring_len(&self) -> usize {
        self.n + 1
    }
    /// Index of `v`.
    pub fn v(&self) -> usize {
        0
    }
    /// Index of `e_i` (`i` mod `n`).
    pub fn e(&self, i: usize) -> usize {
        1 + i % self.n
    }
    /// Index of `g_i` (`i` mod `n`).
    pub fn g(&self, i: usize) -> usize {
        1 + self.n + 2 * (i % self.n)
    }
    /// Index of `f_i` (`i` mod `n`).
    pub fn f(&self, i: usize) -> usize {
        2 + self.n + 2 * (i % self.n)
    }
    /// `i - 1` mod `n`, for neighbours "before" `i`.
    pub fn prev(&self, i: usize) -> usize {
        (i % self.n + self.n - 1) % self.n
    }
    /// Labels `v, e0.., g0, f0, g1, f1, ..` in index order.
    pub fn labels(&self) -> Vec<PointLabel> {
        let mut out = Vec::with_capacity(self.len());
        out.push(PointLabel::new(Role::Vertex, 0));
        out.extend((0..self.n).map(|i| PointLabel::new(Role::EdgeNeighbour, i)));
        for i in 0..self.n {
            out.push(PointLabel::new(Role::SecondRing, i));
            out.push(PointLabel::new(Role::FaceNeighbour, i));
        }
        out
    }
    /// The `4n` triangles of the two-ring, counter-clockwise:
    /// `(v, e_i, e_{i+1})`, `(e_i, f_i, e_{i+1})`, `(e_i, g_i, f_i)`,
    /// `(e_i, f_{i-1}, g_i)` for `i = 0..n`.
    pub fn triangles(&self) -> Vec<[usize; 3]> {
        let mut out = Vec::with_capacity(4 * self.n);
        for i in 0..self.n {
            out.push([self.v(), self.e(i), self.e(i + 1)]);
            out.push([self.e(i), self.f(i), self.e(i + 1)]);
            out.push([self.e(i), self.g(i), self.f(i)]);
            out.push([self.e(i), self.f(self.prev(i)), self.g(i)]);
        }
        out
    }
}

/// The limit-point stencil over the one-ring `[v, e_0..e_{n-1}]` (math doc
/// section 11): the left eigenvector of the one-ring matrix for the
/// eigenvalue 1, normalised to sum 1,
///
/// ```text
/// chi_n = 1 / (3 / (8 beta_n) + n)   on every e_i,      1 - n chi_n   on v.
/// ```
///
/// On the two-ring the stencil is zero on every `g_i` and `f_i` (the matrix
/// is block lower-triangular). Checked against a dense left eigenvector in
/// the tests of [`fourier`](super::fourier).
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::limit_weights;
/// let l = limit_weights(3).unwrap(); // beta_3 = 3/16: chi = 1/5
/// assert!((l[0] - 0.4).abs() < 1e-15 && (l[3] - 0.2).abs() < 1e-15);
/// assert!(limit_weights(2).is_err());
/// ```
pub fn limit_weights(n: usize) -> Result<Vec<f64>> {
    check_size(n, n as u128 + 1, "limit stencil")?;
    let chi = 1.0 / (3.0 / (8.0 * beta(n)) + n as f64);
    let mut out = Vec::with_capacity(n + 1);
    out.push(1.0 - n as f64 * chi);
    out.extend(std::iter::repeat_n(chi, n));
    Ok(out)
}
