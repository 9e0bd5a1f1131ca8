//! The Catmull-Clark family: Catmull-Clark and the shape-adjustable scheme with
//! parameter `c` in `[0, 1]` (math doc section 8, seed 003).
//!
//! # The rules
//!
//! On a quad mesh (every face is a quad after one step), with parameter `c`:
//!
//! ```text
//! f' = mean of the face's vertices
//! e' = (1 - c)(v + e)/2 + c (f'_1 + f'_2)/2            (edge v-e, adjacent new face points f'_1, f'_2)
//! v' = ( 4 c^2 Q + 8 c (1 - c) R + (n - 4 c (2 - c)) v ) / n
//! ```
//!
//! where `Q` is the mean of the `n` new face points around `v` and `R` the mean
//! of the `n` edge midpoints `(v + e_i)/2`. At `c = 1/2` these are exactly the
//! Catmull-Clark rules (`e' = (v + e + f'_1 + f'_2)/4`,
//! `v' = (Q + 2R + (n - 3) v)/n`).
//!
//! # The shape-adjustable scheme is **\[reconstructed\]**
//!
//! The OCR of seed 003 prints a vertex rule whose weights do not sum to 1 and
//! an edge rule with `c` and `1 - c` swapped. The reading above (math doc
//! section 8) is the unique one that
//!
//! 1. keeps the printed coefficients of `R` (`8c(1-c)/n`) and of `v`
//!    (`(n - 4c(2-c))/n`);
//! 2. sums to 1 (affine invariance; checked exactly by [`Assembler::finish`]
//!    for rational `c`);
//! 3. gives Catmull-Clark at `c = 1/2` (test `adjustable_half_is_catmull_clark`,
//!    exact rationals);
//! 4. is, on a regular grid, the tensor product of one univariate rule
//!    (vertex mask `c/4, 1 - c/2, c/4`; new edge point = midpoint)
//!    (test `regular_grid_is_tensor_product`, random `c`, exact rationals).
//!
//! The printed edge rule (with `c` and `1 - c` swapped) is not tensor
//! consistent for `c != 1/2`.
//!
//! For `c != 1/2` the regular part of the limit surface is the tensor product
//! of the univariate scheme with mask `(c/4, 1/2, 1 - c/2, 1/2, c/4)`, which is
//! the cubic B-spline scheme only at `c = 1/2`: the "ring patches" of the
//! extended matrix are then control nets of that tensor-product scheme, not
//! bicubic B-spline patches.
//!
//! # Numbering
//!
//! See [`PatchLayout`]: the one-ring is `[v, e_0..e_{n-1}, f_0..f_{n-1}]`
//! (`2n + 1` points, `e_i` counter-clockwise, `f_i` the far corner of the quad
//! `v, e_i, f_i, e_{i+1}`); the patch adds 7 outer points (`2n + 8`, Stam's
//! count and geometry) and the extended configuration 9 more (`2n + 17`).
//!
//! ```
//! use subdiv_lab::scalar::{Rational, Scalar};
//! use subdiv_lab::schemes::catmull_clark::one_ring_matrix;
//! let s = one_ring_matrix::<Rational>(5, &Rational::frac(1, 2)).unwrap();
//! assert_eq!(s.matrix().shape(), (11, 11));
//! // Catmull-Clark vertex rule: v weight 1 - 7/(4n), e_j 3/(2n^2), f_j 1/(4n^2).
//! assert_eq!(s.matrix()[(0, 0)], Rational::frac(13, 20));
//! assert_eq!(s.matrix()[(0, 1)], Rational::frac(3, 50));
//! assert_eq!(s.matrix()[(0, 6)], Rational::frac(1, 100));
//! ```

pub mod fourier;
mod layout;
pub mod limit;
pub(crate) mod linear;
pub mod ring;

pub use layout::{PatchLayout, SubPatch};

use super::assembly::{Assembler, LocalMatrix, PointLabel};
use crate::budget::{
    CostModel, ANALYZE_BYTES_PER_ENTRY_CC, ANALYZE_SECONDS_PER_N3_CC, SWEEP_SECONDS_PER_N3_CC,
};
use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// The work model of the family ([`crate::budget`]): the `(2n + 1)` one-ring
/// matrix, decomposed densely on every path; `analyze`'s constant covers the
/// curvature verdict's `(2n + 8)` patch matrix too.
pub const COST_MODEL: CostModel = CostModel {
    dimension_per_valence: 2.0,
    dimension_offset: 1.0,
    analyze_bytes_per_entry: ANALYZE_BYTES_PER_ENTRY_CC,
    analyze_seconds_per_n3_full: ANALYZE_SECONDS_PER_N3_CC,
    analyze_seconds_per_n3_structured: ANALYZE_SECONDS_PER_N3_CC,
    sweep_classify_seconds_per_n3: SWEEP_SECONDS_PER_N3_CC,
    sweep_classify_on_face_block: false,
    sweep_charmap_seconds_per_n3: SWEEP_SECONDS_PER_N3_CC,
};

/// Scheme name used in matrix labels for `c = 1/2`.
pub const CATMULL_CLARK: &str = "catmull-clark";
/// Scheme name used in matrix labels for `c != 1/2`.
pub const ADJUSTABLE_CC: &str = "adjustable-cc";

/// Checks `3 <= n` and `0 <= c <= 1` (finite).
pub fn validate<T: Scalar>(n: usize, c: &T) -> Result<()> {
    if n < 3 {
        return Err(Error::ValenceTooSmall { valence: n });
    }
    if !c.is_finite_value() || *c < T::zero() || *c > T::one() {
        return Err(Error::InvalidParameter {
            name: "c",
            value: c.to_text(),
            reason: "the shape parameter must lie in [0, 1]",
        });
    }
    Ok(())
}

fn scheme_name<T: Scalar>(c: &T) -> &'static str {
    if *c == T::frac(1, 2) {
        CATMULL_CLARK
    } else {
        ADJUSTABLE_CC
    }
}

/// A stencil: `(column, weight)` pairs.
type Stencil<T> = Vec<(usize, T)>;

fn scaled<T: Scalar>(s: &[(usize, T)], w: &T) -> Stencil<T> {
    s.iter().map(|(j, x)| (*j, x.clone() * w.clone())).collect()
}

/// The three rules of math doc section 8 as stencils over the one-ring
/// columns of `lay` (the rules are written once and reused by all matrices).
struct OneRingRules<'a, T> {
    lay: &'a PatchLayout,
    c: T,
    /// A vertex rule given by its weights instead of the family's (a scheme file).
    vertex_rule: Option<&'a VertexWeights<T>>,
}

/// The weights of a vertex rule of Catmull-Clark type at valence `n`:
/// `v' = own v + edge sum_j e_j + face sum_j f_j` over the one-ring
/// (math doc section 12.1). The family's own rule is
/// `own = 1 - 7/(4n)`, `edge = 3/(2n^2)`, `face = 1/(4n^2)` at `c = 1/2`.
#[derive(Clone, Debug, PartialEq)]
pub struct VertexWeights<T> {
    /// Weight of the vertex itself.
    pub own: T,
    /// Weight of each edge neighbour `e_j`.
    pub edge: T,
    /// Weight of each face-diagonal neighbour `f_j`.
    pub face: T,
}

impl<T: Scalar> OneRingRules<'_, T> {
    /// `f'_i = (v + e_i + f_i + e_{i+1}) / 4`.
    fn face(&self, i: usize) -> Stencil<T> {
        let l = self.lay;
        let q = T::frac(1, 4);
        vec![
            (l.v(), q.clone()),
            (l.e(i), q.clone()),
            (l.f(i), q.clone()),
            (l.e(i + 1), q),
        ]
    }
    /// `e'_i = (1 - c)(v + e_i)/2 + c (f'_{i-1} + f'_i)/2`.
    fn edge(&self, i: usize) -> Stencil<T> {
        let l = self.lay;
        let n = l.valence();
        let half = T::frac(1, 2);
        let a = (T::one() - self.c.clone()) * half.clone();
        let b = self.c.clone() * half;
        let mut s = vec![(l.v(), a.clone()), (l.e(i), a)];
        s.extend(scaled(&self.face(i + n - 1), &b));
        s.extend(scaled(&self.face(i), &b));
        s
    }
    /// `v' = (4 c^2 Q + 8 c (1 - c) R + (n - 4 c (2 - c)) v) / n`.
    fn vertex(&self) -> Stencil<T> {
        let l = self.lay;
        let n = l.valence();
        if let Some(w) = self.vertex_rule {
            let mut s = vec![(l.v(), w.own.clone())];
            for i in 0..n {
                s.push((l.e(i), w.edge.clone()));
                s.push((l.f(i), w.face.clone()));
            }
            return s;
        }
        let nn = T::frac(n as i64, 1);
        let c = self.c.clone();
        let one = T::one();
        let two = T::frac(2, 1);
        let wq = T::frac(4, 1) * c.clone() * c.clone() / nn.clone();
        let wr = T::frac(8, 1) * c.clone() * (one.clone() - c.clone()) / nn.clone();
        let wv = (nn.clone() - T::frac(4, 1) * c.clone() * (two - c)) / nn.clone();
        let mut s = vec![(l.v(), wv)];
        // Q = (1/n) sum_i f'_i;  R = (1/n) sum_i (v + e_i)/2.
        let q_w = wq / nn.clone();
        let r_w = wr / (nn * T::frac(2, 1));
        for i in 0..n {
            s.extend(scaled(&self.face(i), &q_w));
            s.push((l.v(), r_w.clone()));
            s.push((l.e(i), r_w.clone()));
        }
        s
    }
}

/// The `(2n+1) x (2n+1)` one-ring matrix (order `[v, e_0..e_{n-1}, f_0..f_{n-1}]`).
///
/// Exact for rational `c`. Scheme name `catmull-clark` at `c = 1/2`,
/// `adjustable-cc` otherwise.
pub fn one_ring_matrix<T: Scalar>(n: usize, c: &T) -> Result<LocalMatrix<T>> {
    one_ring_named(scheme_name(c), n, c)
}

pub(crate) fn one_ring_named<T: Scalar>(name: &str, n: usize, c: &T) -> Result<LocalMatrix<T>> {
    validate(n, c)?;
    let lay = PatchLayout::new(n)?;
    let labels: Vec<PointLabel> = lay.labels()[..lay.one_ring_len()].to_vec();
    let mut asm = Assembler::square(name, n, labels);
    add_one_ring_rows(&mut asm, &lay, c);
    asm.finish()
}

fn add_one_ring_rows<T: Scalar>(asm: &mut Assembler<T>, lay: &PatchLayout, c: &T) {
    add_rows_with_vertex(asm, lay, c, None);
}

fn add_rows_with_vertex<T: Scalar>(
    asm: &mut Assembler<T>,
    lay: &PatchLayout,
    c: &T,
    vertex_rule: Option<&VertexWeights<T>>,
) {
    let rules = OneRingRules {
        lay,
        c: c.clone(),
        vertex_rule,
    };
    asm.stencil(lay.v(), rules.vertex());
    for i in 0..lay.valence() {
        asm.stencil(lay.e(i), rules.edge(i));
        asm.stencil(lay.f(i), rules.face(i));
    }
}

/// Univariate rule at half-grid coordinate `h` (new point at old coordinate
/// `h/2`): vertex mask `c/4, 1 - c/2, c/4` for even `h`, midpoint for odd `h`.
/// Returns `(old grid coordinate, weight)`.
pub(crate) fn univariate_rule<T: Scalar>(h: usize, c: &T) -> Vec<(usize, T)> {
    if h % 2 == 0 {
        let k = h / 2;
        let q = c.clone() * T::frac(1, 4);
        vec![
            (k - 1, q.clone()),
            (k, T::one() - c.clone() * T::frac(1, 2)),
            (k + 1, q),
        ]
    } else {
        let k = (h - 1) / 2;
        vec![(k, T::frac(1, 2)), (k + 1, T::frac(1, 2))]
    }
}

/// Adds the tensor-product rule for the new point at new-grid position
/// `(a, b)` (old half-grid coordinates `(a + 1, b + 1)`) to `row`.
fn add_regular_row<T: Scalar>(
    asm: &mut Assembler<T>,
    row: usize,
    lay: &PatchLayout,
    (a, b): (usize, usize),
    c: &T,
) -> Result<()> {
    for (i, wi) in univariate_rule(a + 1, c) {
        for (j, wj) in univariate_rule(b + 1, c) {
            let col = lay.grid(i, j).ok_or_else(|| Error::Numerical {
                routine: "catmull-clark patch assembly",
                reason: format!("regular rule at ({a}, {b}) reaches the extraordinary corner"),
            })?;
            asm.add(row, col, wi.clone() * wj);
        }
    }
    Ok(())
}

/// The `(2n+8) x (2n+8)` patch matrix (Stam's `A`): the one-ring block and the
/// 7 outer points of the next level's patch at the extraordinary corner,
/// in the order of [`PatchLayout`]. Block lower-triangular: the one-ring rows
/// use only one-ring columns, so its spectrum is the one-ring's together with
/// [`regular_part_eigenvalues`] (the outer `7 x 7` block).
///
/// It is the family's second-order neighbourhood (math doc section 13.5): one
/// patch's support, which holds the control nets of the regular sub-patches
/// of the ring of the next level.
pub fn patch_matrix<T: Scalar>(n: usize, c: &T) -> Result<LocalMatrix<T>> {
    patch_named(scheme_name(c), n, c)
}

pub(crate) fn patch_named<T: Scalar>(name: &str, n: usize, c: &T) -> Result<LocalMatrix<T>> {
    patch_with(name, n, c, None)
}

/// The one-ring matrix of Catmull-Clark's edge and face rules (`c = 1/2`)
/// with the vertex rule `w` at the extraordinary vertex (a scheme file's).
pub fn one_ring_with_vertex<T: Scalar>(
    name: &str,
    n: usize,
    w: &VertexWeights<T>,
) -> Result<LocalMatrix<T>> {
    let c = T::frac(1, 2);
    validate(n, &c)?;
    let lay = PatchLayout::new(n)?;
    let labels: Vec<PointLabel> = lay.labels()[..lay.one_ring_len()].to_vec();
    let mut asm = Assembler::square(name, n, labels);
    add_rows_with_vertex(&mut asm, &lay, &c, Some(w));
    asm.finish()
}

/// The patch matrix of [`one_ring_with_vertex`]: its one-ring rows and the
/// regular Catmull-Clark rows of the 7 outer points (math doc section 13.5).
pub fn patch_with_vertex<T: Scalar>(
    name: &str,
    n: usize,
    w: &VertexWeights<T>,
) -> Result<LocalMatrix<T>> {
    patch_with(name, n, &T::frac(1, 2), Some(w))
}

fn patch_with<T: Scalar>(
    name: &str,
    n: usize,
    c: &T,
    vertex_rule: Option<&VertexWeights<T>>,
) -> Result<LocalMatrix<T>> {
    validate(n, c)?;
    let lay = PatchLayout::new(n)?;
    let labels = lay.labels()[..lay.patch_len()].to_vec();
    let mut asm = Assembler::square(name, n, labels);
    add_rows_with_vertex(&mut asm, &lay, c, vertex_rule);
    for k in 0..7 {
        add_regular_row(
            &mut asm,
            lay.outer(k),
            &lay,
            PatchLayout::outer_position(k),
            c,
        )?;
    }
    asm.finish()
}

/// The eigenvalues the [`patch_matrix`] adds to the one-ring's: those of its
/// outer `7 x 7` block, the regular part (math doc section 13.5
/// **\[derived\]**); for `c` in `[0, 1]` the first, `c/4`, is the largest:
///
/// ```text
/// c/4, c/4, c/8, c/8, c(1 - c)/8, c(1 - c)/8, c^2/16
/// ```
///
/// Derivation: on the grid positions `0..3` of one parameter direction the
/// univariate rule (vertex mask `c/4, 1 - c/2, c/4`, new edge points at the
/// midpoints; module docs) is the matrix `U` whose column 3 is `c/4` on the
/// diagonal and 0 elsewhere (no new point at positions `0..2` reaches
/// position 3), so `U` is block lower-triangular with eigenvalues
/// `1, 1/2, (1 - c)/2` (positions `0..2`: trace `2 - c/2`) and `c/4`. The
/// outer points are the grid points with a coordinate 3; the tensor rule
/// `U (x) U` is block lower-triangular with respect to them, so the outer
/// block's eigenvalues are the products `u v` of eigenvalues of `U` with at
/// least one factor `c/4`: `c/4 {1, 1/2, (1 - c)/2}` twice (either
/// direction) and `(c/4)^2`. At `c = 1/2`: Stam's `1/8, 1/16, 1/32, 1/64`.
///
/// ```
/// use subdiv_lab::schemes::catmull_clark::regular_part_eigenvalues;
/// assert_eq!(regular_part_eigenvalues(&0.5), vec![0.125, 0.125, 0.0625, 0.0625, 0.03125, 0.03125, 0.015625]);
/// ```
pub fn regular_part_eigenvalues<T: Scalar>(c: &T) -> Vec<T> {
    let quarter = c.clone() * T::frac(1, 4);
    let eighth = c.clone() * T::frac(1, 8);
    let mixed = eighth.clone() * (T::one() - c.clone());
    let square = quarter.clone() * quarter.clone();
    vec![
        quarter.clone(),
        quarter,
        eighth.clone(),
        eighth,
        mixed.clone(),
        mixed,
        square,
    ]
}

/// The `(2n+17) x (2n+8)` extended matrix (Stam's `A-bar`): rows are the
/// next level's `2n+8` patch points followed by the 9 extra points that
/// complete the control nets of the three regular sub-patches
/// ([`PatchLayout::sub_patch`]); columns are the current `2n+8` patch points.
pub fn extended_matrix<T: Scalar>(n: usize, c: &T) -> Result<LocalMatrix<T>> {
    validate(n, c)?;
    let lay = PatchLayout::new(n)?;
    let rows = lay.labels();
    let cols = rows[..lay.patch_len()].to_vec();
    let mut asm = Assembler::new(scheme_name(c), n, rows, cols);
    add_one_ring_rows(&mut asm, &lay, c);
    for k in 0..7 {
        add_regular_row(
            &mut asm,
            lay.outer(k),
            &lay,
            PatchLayout::outer_position(k),
            c,
        )?;
    }
    for k in 0..9 {
        add_regular_row(
            &mut asm,
            lay.extra(k),
            &lay,
            PatchLayout::extra_position(k),
            c,
        )?;
    }
    asm.finish()
}

#[cfg(test)]
mod tests;
