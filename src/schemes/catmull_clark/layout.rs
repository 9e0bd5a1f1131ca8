//! Point numbering of the Catmull-Clark one-ring, patch and extended configurations.

use crate::error::{Error, Result};
use crate::schemes::assembly::{PointLabel, Role};

/// Numbering of the points around an extraordinary vertex of valence `n`.
///
/// Picture the patch as the cell `[1, 2] x [1, 2]` of a 4 x 4 grid of control
/// points `P(i, j)`, `i, j = 0..3` (`i` along the patch parameter `u`, `j`
/// along `v`), with the extraordinary vertex `v = P(1, 1)` at `(u, v) = (0, 0)`.
/// For `n != 4` the grid point `P(0, 0)` does not exist: it is replaced by the
/// remaining one-ring points. Indices (0-based):
///
/// | index | point | grid position |
/// | --- | --- | --- |
/// | `0` | `v`, the extraordinary vertex | `P(1,1)` |
/// | `1 + i` | `e_i`, edge neighbours, counter-clockwise, `i = 0..n-1` | `e_0 = P(2,1)`, `e_1 = P(1,2)`, `e_2 = P(0,1)`, `e_{n-1} = P(1,0)` |
/// | `1 + n + i` | `f_i`, the far corner of quad `v, e_i, f_i, e_{i+1}` | `f_0 = P(2,2)`, `f_1 = P(0,2)`, `f_{n-1} = P(2,0)` |
/// | `2n + 1 + k` | outer `o_k`, `k = 0..6` | `P(3,0), P(3,1), P(3,2), P(3,3), P(2,3), P(1,3), P(0,3)` |
/// | `2n + 8 + k` | extra `X_k`, `k = 0..8` (extended matrix rows only) | next-level `P(4,0..4)`, then `P(3,4), P(2,4), P(1,4), P(0,4)` |
///
/// The first `2n + 1` indices are the one-ring, the first `2n + 8` the patch
/// (Stam 1998, "Exact evaluation of Catmull-Clark subdivision surfaces at
/// arbitrary parameter values": same point set and geometry; Stam numbers the
/// one-ring interleaved, `c_1 = v, c_{2i+2} = e_i, c_{2i+3} = f_i`, 1-based,
/// we keep edge and face neighbours in two blocks). For `n = 3`, `P(0,1)` and
/// `P(1,0)` are the same point `e_2`.
///
/// The next level's patch (at the extraordinary corner, `[0, 1/2]^2`) uses the
/// same numbering on the refined grid, whose position `(a, b)` lies at old
/// grid coordinates `(1 + (a-1)/2, 1 + (b-1)/2)`. The extended configuration
/// (`2n + 17` points) covers the refined grid `(a, b)`, `a, b = 0..4`, minus
/// `(0, 0)`: exactly the control nets of the three regular sub-patches
/// ([`SubPatch`]).
///
/// ```
/// use subdiv_lab::schemes::catmull_clark::PatchLayout;
/// let lay = PatchLayout::new(5).unwrap();
/// assert_eq!(lay.grid(1, 1), Some(0));
/// assert_eq!(lay.grid(2, 1), Some(lay.e(0)));
/// assert_eq!(lay.grid(3, 3), Some(lay.outer(3)));
/// assert_eq!(lay.grid(0, 0), None);
/// assert_eq!(lay.labels()[lay.f(4)].to_string(), "f4");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatchLayout {
    n: usize,
}

/// The three regular sub-patches of one subdivision level (Stam's `Omega_m`):
/// parameters in the patch's `[0, 1]^2` are `[1/2, 1] x [0, 1/2]` (`m = 1`),
/// `[1/2, 1]^2` (`m = 2`), `[0, 1/2] x [1/2, 1]` (`m = 3`); at level `k` scale
/// by `2^{1-k}` (`Omega^k_m`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum SubPatch {
    /// `[1/2, 1] x [0, 1/2]`.
    One,
    /// `[1/2, 1] x [1/2, 1]` (on the diagonal).
    Two,
    /// `[0, 1/2] x [1/2, 1]`.
    Three,
}

impl SubPatch {
    /// All three, in order.
    pub const ALL: [SubPatch; 3] = [SubPatch::One, SubPatch::Two, SubPatch::Three];

    /// Stam's index `m`.
    pub fn index(self) -> usize {
        match self {
            SubPatch::One => 1,
            SubPatch::Two => 2,
            SubPatch::Three => 3,
        }
    }

    /// Lower-left corner of the sub-patch's domain in `[0, 1]^2` at level 1
    /// (the domain is this corner plus `[0, 1/2]^2`).
    pub fn origin(self) -> (f64, f64) {
        match self {
            SubPatch::One => (0.5, 0.0),
            SubPatch::Two => (0.5, 0.5),
            SubPatch::Three => (0.0, 0.5),
        }
    }

    /// Refined-grid position of the control point `(0, 0)` of this sub-patch.
    fn grid_origin(self) -> (usize, usize) {
        match self {
            SubPatch::One => (1, 0),
            SubPatch::Two => (1, 1),
            SubPatch::Three => (0, 1),
        }
    }
}

impl PatchLayout {
    /// The layout for valence `n >= 3`.
    pub fn new(n: usize) -> Result<Self> {
        if n < 3 {
            return Err(Error::ValenceTooSmall { valence: n });
        }
        Ok(Self { n })
    }
    /// The valence.
    pub fn valence(&self) -> usize {
        self.n
    }
    /// `2n + 1`.
    pub fn one_ring_len(&self) -> usize {
        2 * self.n + 1
    }
    /// `2n + 8`.
    pub fn patch_len(&self) -> usize {
        2 * self.n + 8
    }
    /// `2n + 17`.
    pub fn extended_len(&self) -> usize {
        2 * self.n + 17
    }
    /// Index of `v`.
    pub fn v(&self) -> usize {
        0
    }
    /// Index of `e_i` (`i` taken mod n).
    pub fn e(&self, i: usize) -> usize {
        1 + i % self.n
    }
    /// Index of `f_i` (`i` taken mod n).
    pub fn f(&self, i: usize) -> usize {
        1 + self.n + i % self.n
    }
    /// Index of the outer point `o_k`, `k = 0..6`.
    pub fn outer(&self, k: usize) -> usize {
        2 * self.n + 1 + k
    }
    /// Index of the extra point `X_k`, `k = 0..8`.
    pub fn extra(&self, k: usize) -> usize {
        2 * self.n + 8 + k
    }
    /// Grid position `(i, j)` of the outer point `o_k`.
    pub fn outer_position(k: usize) -> (usize, usize) {
        [(3, 0), (3, 1), (3, 2), (3, 3), (2, 3), (1, 3), (0, 3)][k]
    }
    /// Refined-grid position `(a, b)` of the extra point `X_k`.
    pub fn extra_position(k: usize) -> (usize, usize) {
        [
            (4, 0),
            (4, 1),
            (4, 2),
            (4, 3),
            (4, 4),
            (3, 4),
            (2, 4),
            (1, 4),
            (0, 4),
        ][k]
    }
    /// Index of grid point `P(i, j)`, `i, j = 0..3`; `None` for `(0, 0)` and
    /// positions off the grid.
    pub fn grid(&self, i: usize, j: usize) -> Option<usize> {
        let n = self.n;
        Some(match (i, j) {
            (1, 1) => self.v(),
            (2, 1) => self.e(0),
            (2, 2) => self.f(0),
            (1, 2) => self.e(1),
            (0, 2) => self.f(1),
            (0, 1) => self.e(2),
            (1, 0) => self.e(n - 1),
            (2, 0) => self.f(n - 1),
            (3, j) if j <= 3 => self.outer(j),
            (i, 3) if i <= 2 => self.outer(6 - i),
            _ => return None,
        })
    }
    /// Index in the extended configuration of refined-grid point `(a, b)`,
    /// `a, b = 0..4`; `None` for `(0, 0)` and off-grid positions.
    pub fn extended_grid(&self, a: usize, b: usize) -> Option<usize> {
        match (a, b) {
            (4, b) if b <= 4 => Some(self.extra(b)),
            (a, 4) if a <= 3 => Some(self.extra(8 - a)),
            _ => self.grid(a, b),
        }
    }
    /// The 16 indices (into the extended configuration) of the bicubic
    /// control net of regular sub-patch `m`: `[i][j]` is the control point
    /// with index `i` along `u` and `j` along `v`.
    pub fn sub_patch(&self, m: SubPatch) -> [[usize; 4]; 4] {
        let (a0, b0) = m.grid_origin();
        let mut out = [[0; 4]; 4];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                // Every position of a regular sub-patch is on the extended grid.
                *x = self.extended_grid(a0 + i, b0 + j).unwrap_or(usize::MAX);
            }
        }
        out
    }
    /// Labels of all `2n + 17` points (prefixes give the one-ring and the patch).
    pub fn labels(&self) -> Vec<PointLabel> {
        let n = self.n;
        let mut v = Vec::with_capacity(self.extended_len());
        v.push(PointLabel::new(Role::Vertex, 0));
        v.extend((0..n).map(|i| PointLabel::new(Role::EdgeNeighbour, i)));
        v.extend((0..n).map(|i| PointLabel::new(Role::FaceNeighbour, i)));
        v.extend((0..7).map(|k| PointLabel::new(Role::PatchOuter, k)));
        v.extend((0..9).map(|k| PointLabel::new(Role::Extended, k)));
        v
    }
}
