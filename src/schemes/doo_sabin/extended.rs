//! The extended matrix of the Doo-Sabin family: all `9n` new points of one step.
//!
//! Math doc section 7 **\[derived\]**. At level `k` the configuration around an
//! n-sided face is the `4n` points of math doc section 4: the face
//! `F = (P_0..P_{n-1})`, an E-face `E_i = (P_i, P_{i+1}, E_i2, E_i1)` on every
//! edge and a V-face `V_i = (P_i, E_i1, C_i, E_{i-1,2})` at every corner. One
//! refinement step makes one new point per face corner (math doc section 3):
//! `n` in `F`, 4 in each `E_i`, 4 in each `V_i`, `9n` in all. The new point at
//! corner `j` of a face with corners `Q_0..Q_{m-1}` and edge ratios `rho` is
//!
//! ```text
//! (f, Q_j) = 1/4 (Q_j + E_{j-1} + E_j + F_f),   E_j = rho_j Q_j + (1 - rho_j) Q_{j+1},
//! ```
//!
//! i.e. row `j` of that face's own face block `1/4 (I + R + 1 c^T)` (for the
//! original Doo-Sabin scheme, the n-gon uses its own weights; on quads they
//! coincide with the uniform rule 9/16, 3/16, 3/16, 1/16).
//!
//! **Knot ratios of the faces \[derived\]** (from the knot propagation rules of
//! math doc section 3, valid from level 2 on): `F` has the ratios `r_i`; `E_i`
//! is a tensor-product quad, non-uniform along the old edge and uniform across:
//! in the corner order `(P_i, P_{i+1}, E_i2, E_i1)` its ratios are
//! `(r_i, 1/2, 1 - r_i, 1/2)`; `V_i` is uniform (all 1/2). Derivation: at a
//! level-k vertex opposite edges carry equal intervals, and both ends of a
//! spoke carry the same interval, so the transverse edges `P_i E_i1`,
//! `P_{i+1} E_i2` and all edges of `V_i` have equal intervals at both ends,
//! while `E_i1 -> E_i2` carries `p_i` and `E_i2 -> E_i1` carries `q_{i+1}` (the
//! same ratio as `P_i P_{i+1}`). The check: the first `4n` rows (the new
//! configuration points `P'_i = (F, P_i)`, `E'_i1 = (E_i, P_i)`,
//! `E'_i2 = (E_i, P_{i+1})`, `C'_i = (V_i, P_i)`) equal `S_n` exactly (tests).
//!
//! Row order: the `4n` configuration points in the order of `S_n`, then
//! `(E_i, E_i1), (E_i, E_i2)` for `i = 0..n`, then
//! `(V_i, E_i1), (V_i, C_i), (V_i, E_{i-1,2})` for `i = 0..n`.
//!
//! ```
//! use subdiv_lab::schemes::doo_sabin::extended::ExtendedMatrix;
//! use subdiv_lab::schemes::LocalScheme;
//! let s = LocalScheme::<f64>::cc_variant(5).unwrap();
//! let x = ExtendedMatrix::new(&s).unwrap();
//! assert_eq!(x.matrix().matrix().shape(), (45, 20));
//! assert_eq!(x.labels()[20].to_string(), "(E0,E0,1)");
//! ```

use crate::error::Result;
use crate::knots::CornerIntervals;
use crate::scalar::Scalar;
use crate::schemes::doo_sabin::{labels, Layout};
use crate::schemes::{Assembler, LocalMatrix, LocalScheme, PointLabel, Role};
use std::fmt;

/// A face of the level-k configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum OldFace {
    /// The extraordinary n-gon `F`.
    F,
    /// The E-face on edge `i`.
    E(usize),
    /// The V-face at corner `i`.
    V(usize),
}

/// A new point: the corner `corner` (a level-k point) of the level-k face `face`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct ExtendedLabel {
    /// The old face.
    pub face: OldFace,
    /// The old point at the corner.
    pub corner: PointLabel,
}

impl fmt::Display for ExtendedLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.face {
            OldFace::F => write!(f, "(F,{})", self.corner),
            OldFace::E(i) => write!(f, "(E{i},{})", self.corner),
            OldFace::V(i) => write!(f, "(V{i},{})", self.corner),
        }
    }
}

/// Row index of each new point in the `9n` order (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct ExtLayout {
    n: usize,
}

impl ExtLayout {
    /// Layout for valence `n`.
    pub fn new(n: usize) -> Self {
        Self { n }
    }
    fn m(&self, i: usize) -> usize {
        i % self.n
    }
    /// `(F, P_i)` = `P'_i`.
    pub fn f_p(&self, i: usize) -> usize {
        self.m(i)
    }
    /// `(E_i, P_i)` = `E'_i1`.
    pub fn e_p(&self, i: usize) -> usize {
        self.n + 2 * self.m(i)
    }
    /// `(E_i, P_{i+1})` = `E'_i2`.
    pub fn e_pnext(&self, i: usize) -> usize {
        self.n + 2 * self.m(i) + 1
    }
    /// `(V_i, P_i)` = `C'_i`.
    pub fn v_p(&self, i: usize) -> usize {
        3 * self.n + self.m(i)
    }
    /// `(E_i, E_i1)`.
    pub fn e_e1(&self, i: usize) -> usize {
        4 * self.n + 2 * self.m(i)
    }
    /// `(E_i, E_i2)`.
    pub fn e_e2(&self, i: usize) -> usize {
        4 * self.n + 2 * self.m(i) + 1
    }
    /// `(V_i, E_i1)`.
    pub fn v_e1(&self, i: usize) -> usize {
        6 * self.n + 3 * self.m(i)
    }
    /// `(V_i, C_i)`.
    pub fn v_c(&self, i: usize) -> usize {
        6 * self.n + 3 * self.m(i) + 1
    }
    /// `(V_i, E_{i-1,2})`.
    pub fn v_eprev2(&self, i: usize) -> usize {
        6 * self.n + 3 * self.m(i) + 2
    }
}

/// The `9n x 4n` extended matrix with its labels.
#[derive(Clone, Debug)]
pub struct ExtendedMatrix<T = f64> {
    matrix: LocalMatrix<T>,
    labels: Vec<ExtendedLabel>,
}

/// Corner intervals of the E-face quad `(P_i, P_{i+1}, E_i2, E_i1)` with ratios
/// `(r, 1/2, s, 1/2)`: `p = (s, 1, r, 1)`, `q = (1, r, 1, s)` (each ratio is
/// computed as a quotient of two given numbers, so it keeps full relative accuracy).
fn e_face_intervals<T: Scalar>(r: &T, s: &T) -> Result<CornerIntervals<T>> {
    let one = T::one();
    CornerIntervals::new(
        vec![s.clone(), one.clone(), r.clone(), one.clone()],
        vec![one.clone(), r.clone(), one, s.clone()],
    )
}

impl<T: Scalar> ExtendedMatrix<T> {
    /// Builds the extended matrix of a Doo-Sabin-family configuration.
    pub fn new(scheme: &LocalScheme<T>) -> Result<Self> {
        let n = scheme.valence();
        let lay = Layout::new(n);
        let xl = ExtLayout::new(n);
        let ratios = scheme.ratios();
        let (r, s) = (ratios.as_slice(), ratios.complement());
        let mut row_labels = labels(n);
        row_labels.extend((4 * n..9 * n).map(|k| PointLabel::new(Role::Extended, k)));
        let mut asm = Assembler::new(scheme.kind().name(), n, row_labels, labels(n));
        let mut ext_labels = vec![
            ExtendedLabel {
                face: OldFace::F,
                corner: PointLabel::new(Role::FaceCorner, 0)
            };
            9 * n
        ];
        let mut face = |asm: &mut Assembler<T>,
                        block: &nalgebra::DMatrix<T>,
                        f: OldFace,
                        corners: &[(usize, usize, PointLabel)]| {
            // corners[j] = (column of Q_j, row of (f, Q_j), label of Q_j)
            for (j, &(_, row, lab)) in corners.iter().enumerate() {
                for (k, &(col, _, _)) in corners.iter().enumerate() {
                    asm.add(row, col, block[(j, k)].clone());
                }
                ext_labels[row] = ExtendedLabel {
                    face: f,
                    corner: lab,
                };
            }
        };
        let pl = |i: usize| PointLabel::new(Role::FaceCorner, i % n);
        let e1l = |i: usize| PointLabel::new(Role::EdgeFirst, i % n);
        let e2l = |i: usize| PointLabel::new(Role::EdgeSecond, i % n);
        let cl = |i: usize| PointLabel::new(Role::Corner, i % n);
        let f_corners: Vec<_> = (0..n).map(|i| (lay.p(i), xl.f_p(i), pl(i))).collect();
        face(&mut asm, &scheme.face_block()?, OldFace::F, &f_corners);
        let uniform_quad = LocalScheme::<T>::cc_variant(4)?.face_block()?;
        for i in 0..n {
            let e_ratios = e_face_intervals(&r[i], &s[i])?.ratios()?;
            let e_block = LocalScheme::nurds(e_ratios).face_block()?;
            face(
                &mut asm,
                &e_block,
                OldFace::E(i),
                &[
                    (lay.p(i), xl.e_p(i), pl(i)),
                    (lay.p(i + 1), xl.e_pnext(i), pl(i + 1)),
                    (lay.e2(i), xl.e_e2(i), e2l(i)),
                    (lay.e1(i), xl.e_e1(i), e1l(i)),
                ],
            );
            face(
                &mut asm,
                &uniform_quad,
                OldFace::V(i),
                &[
                    (lay.p(i), xl.v_p(i), pl(i)),
                    (lay.e1(i), xl.v_e1(i), e1l(i)),
                    (lay.c(i), xl.v_c(i), cl(i)),
                    (lay.e2(i + n - 1), xl.v_eprev2(i), e2l(i + n - 1)),
                ],
            );
        }
        Ok(Self {
            matrix: asm.finish()?,
            labels: ext_labels,
        })
    }

    /// The labelled `9n x 4n` matrix.
    pub fn matrix(&self) -> &LocalMatrix<T> {
        &self.matrix
    }

    /// What each row is: `(old face, old corner)`.
    pub fn labels(&self) -> &[ExtendedLabel] {
        &self.labels
    }

    /// Valence `n`.
    pub fn valence(&self) -> usize {
        self.matrix.valence()
    }

    /// The matrix with `f(row, col, value)` applied to every entry (deliberate
    /// perturbations for testing the checks); rows must still sum to 1.
    pub fn map_entries(&self, mut f: impl FnMut(usize, usize, &T) -> T) -> Result<Self> {
        let m = self.matrix.matrix();
        let mapped = nalgebra::DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| f(i, j, &m[(i, j)]));
        let mut asm = Assembler::new(
            self.matrix.scheme(),
            self.valence(),
            self.matrix.rows().to_vec(),
            self.matrix.cols().to_vec(),
        );
        asm.block(0, 0, &mapped);
        Ok(Self {
            matrix: asm.finish()?,
            labels: self.labels.clone(),
        })
    }
}
