//! The one matrix-assembly path shared by every scheme.
//!
//! A scheme describes each new point as a *stencil*: a short list of
//! `(old point, weight)` pairs. [`Assembler`] collects stencils row by row into a
//! dense [`DMatrix`] and returns a [`LocalMatrix`]: the matrix together with a
//! [`PointLabel`] for every row and column, so that reports can name points
//! ("E3,1") instead of indices. Row `k` of the matrix is the stencil of new
//! point `k`: `new = S * old` (math doc conventions).

use crate::error::{Error, Result};
use crate::scalar::Scalar;
use nalgebra::DMatrix;
use serde::Serialize;
use std::fmt;

/// What kind of point a row or column of a local matrix stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[non_exhaustive]
pub enum Role {
    /// `P_i`: a corner of the central (extraordinary) face (Doo-Sabin family).
    FaceCorner,
    /// `E_{i1}`: the E-face vertex next to `P_i` (Doo-Sabin family).
    EdgeFirst,
    /// `E_{i2}`: the E-face vertex next to `P_{i+1}` (Doo-Sabin family).
    EdgeSecond,
    /// `C_i`: the outer corner of the V-face at `P_i` (Doo-Sabin family).
    Corner,
    /// A point of an extended (next-level) configuration, indexed by position.
    Extended,
    /// `v`: the extraordinary vertex (Catmull-Clark family).
    Vertex,
    /// `e_i`: an edge neighbour of the extraordinary vertex (Catmull-Clark family).
    EdgeNeighbour,
    /// `f_i`: a face neighbour (far quad corner) of the extraordinary vertex (Catmull-Clark family).
    FaceNeighbour,
    /// `o_k`: one of the 7 outer control points of a Catmull-Clark patch.
    PatchOuter,
    /// `g_i`: the Loop two-ring vertex straight beyond the edge neighbour `e_i`.
    SecondRing,
    /// `h_i`: a point of the third or a further ring around a vertex of a
    /// triangle mesh (the butterfly schemes' three-ring), counted from the
    /// first point of the third ring.
    OuterRing,
}

/// Role and index of one point of a local configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct PointLabel {
    /// The point's role.
    pub role: Role,
    /// Its index within the role (corner or edge index `i`).
    pub index: usize,
}

impl PointLabel {
    /// A label.
    pub const fn new(role: Role, index: usize) -> Self {
        Self { role, index }
    }
}

impl fmt::Display for PointLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = self.index;
        match self.role {
            Role::FaceCorner => write!(f, "P{i}"),
            Role::EdgeFirst => write!(f, "E{i},1"),
            Role::EdgeSecond => write!(f, "E{i},2"),
            Role::Corner => write!(f, "C{i}"),
            Role::Extended => write!(f, "X{i}"),
            Role::Vertex => write!(f, "v"),
            Role::EdgeNeighbour => write!(f, "e{i}"),
            Role::FaceNeighbour => write!(f, "f{i}"),
            Role::PatchOuter => write!(f, "o{i}"),
            Role::SecondRing => write!(f, "g{i}"),
            Role::OuterRing => write!(f, "h{i}"),
        }
    }
}

/// A local subdivision matrix with labelled rows and columns.
///
/// `rows()[k]` names new point `k`, `cols()[k]` names old point `k`; for the
/// square matrices `S_n` they coincide.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalMatrix<T = f64> {
    scheme: String,
    valence: usize,
    rows: Vec<PointLabel>,
    cols: Vec<PointLabel>,
    matrix: DMatrix<T>,
}

impl<T: Scalar> LocalMatrix<T> {
    /// Scheme name (`nurds`, `doo-sabin`, ...).
    pub fn scheme(&self) -> &str {
        &self.scheme
    }
    /// Valence of the extraordinary element.
    pub fn valence(&self) -> usize {
        self.valence
    }
    /// Labels of the rows (new points).
    pub fn rows(&self) -> &[PointLabel] {
        &self.rows
    }
    /// Labels of the columns (old points).
    pub fn cols(&self) -> &[PointLabel] {
        &self.cols
    }
    /// The matrix.
    pub fn matrix(&self) -> &DMatrix<T> {
        &self.matrix
    }
    /// Consumes `self`, returning the matrix.
    pub fn into_matrix(self) -> DMatrix<T> {
        self.matrix
    }
    /// Row sums minus one; all zero (exactly, for rationals) for an affine-invariant scheme.
    pub fn row_sum_defects(&self) -> Vec<T> {
        self.matrix
            .row_iter()
            .map(|row| row.iter().cloned().fold(T::zero(), |a, b| a + b) - T::one())
            .collect()
    }
    /// The matrix converted to `f64`.
    pub fn to_f64(&self) -> LocalMatrix<f64> {
        LocalMatrix {
            scheme: self.scheme.clone(),
            valence: self.valence,
            rows: self.rows.clone(),
            cols: self.cols.clone(),
            matrix: self.matrix.map(|x| x.to_f64()),
        }
    }
}

/// Collects stencils into a [`LocalMatrix`]; the only way schemes build matrices.
#[derive(Debug)]
pub struct Assembler<T> {
    scheme: String,
    valence: usize,
    rows: Vec<PointLabel>,
    cols: Vec<PointLabel>,
    matrix: DMatrix<T>,
}

impl<T: Scalar> Assembler<T> {
    /// An all-zero matrix with the given row and column labels.
    pub fn new(scheme: &str, valence: usize, rows: Vec<PointLabel>, cols: Vec<PointLabel>) -> Self {
        let matrix = DMatrix::from_element(rows.len(), cols.len(), T::zero());
        Self {
            scheme: scheme.to_owned(),
            valence,
            rows,
            cols,
            matrix,
        }
    }

    /// A square matrix whose rows and columns carry the same labels.
    pub fn square(scheme: &str, valence: usize, labels: Vec<PointLabel>) -> Self {
        Self::new(scheme, valence, labels.clone(), labels)
    }

    /// Adds `weight` to entry `(row, col)` (stencils may touch a column twice).
    pub fn add(&mut self, row: usize, col: usize, weight: T) {
        let e = &mut self.matrix[(row, col)];
        *e = e.clone() + weight;
    }

    /// Adds a whole stencil to `row`.
    pub fn stencil(&mut self, row: usize, stencil: impl IntoIterator<Item = (usize, T)>) {
        for (col, w) in stencil {
            self.add(row, col, w);
        }
    }

    /// Copies `block` into the matrix with its top-left corner at `(row, col)`.
    pub fn block(&mut self, row: usize, col: usize, block: &DMatrix<T>) {
        for i in 0..block.nrows() {
            for j in 0..block.ncols() {
                self.add(row + i, col + j, block[(i, j)].clone());
            }
        }
    }

    /// Finishes the matrix, checking that every row sums to 1 (affine
    /// invariance): exactly for rationals, to [`ROW_SUM_TOL`] for `f64`.
    pub fn finish(self) -> Result<LocalMatrix<T>> {
        let m = LocalMatrix {
            scheme: self.scheme,
            valence: self.valence,
            rows: self.rows,
            cols: self.cols,
            matrix: self.matrix,
        };
        let tol = if T::EXACT { 0.0 } else { ROW_SUM_TOL };
        for (k, d) in m.row_sum_defects().iter().enumerate() {
            if d.to_f64().abs() > tol || !d.to_f64().is_finite() {
                return Err(Error::Numerical {
                    routine: "matrix assembly",
                    reason: format!(
                        "row {} ({}) sums to 1 + {} instead of 1",
                        k,
                        m.rows[k],
                        d.to_text()
                    ),
                });
            }
        }
        Ok(m)
    }
}

/// Tolerance on `|row sum - 1|` for `f64` assembly: each row has at most a few
/// dozen weights in `[0, 1]` summing to 1, so rounding is below `64 eps ~ 1.4e-14`;
/// `1e-12` leaves margin for the face-weight column (`n <= 256` terms) and still
/// catches any wrong stencil (whose defects are `O(1/16)` or larger).
pub const ROW_SUM_TOL: f64 = 1e-12;
