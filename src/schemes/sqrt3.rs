//! Kobbelt's sqrt(3) subdivision (Kobbelt 2000) on triangle meshes. One step
//! puts a new point at the centroid of every triangle, moves every old
//! vertex to
//!
//! ```text
//! p' = (1 - alpha_n) p + alpha_n / n sum_i p_i,     alpha_n = (4 - 2 cos(2 pi / n)) / 9,
//! ```
//!
//! and flips every old edge, so each new triangle has one old vertex and two
//! face points (math doc section 21).
//!
//! **One step rotates the ring.** Around a vertex of valence `n` the new
//! neighbours (face points) sit half-way between the old ones: the one-step
//! matrix ([`one_step_matrix`]) maps the two-ring onto a two-ring turned by
//! `pi / n`, and its subdominant eigenvalues are the complex pair
//! `(1 + exp(+-2 pi i / n)) / 3`. Two steps are a one-to-nine split turned by
//! a whole sector; [`local_matrix`] is that two-step matrix read in the old
//! layout (the sector shift undone), whose subdominant eigenvalue is the real
//! double `(2 + 2 cos(2 pi / n)) / 9` (1/3 at `n = 6`). The smoothness
//! analysis uses the two-step matrix; both are square on the two-ring
//! (`3n + 1` points, layout of [`super::tri_rings`]).
//!
//! ```
//! use subdiv_lab::schemes::sqrt3::{local_matrix, one_step_matrix};
//! let s1 = one_step_matrix(5).unwrap();
//! let s2 = local_matrix(5).unwrap();
//! assert_eq!((s1.matrix().shape(), s2.matrix().shape()), ((16, 16), (16, 16)));
//! ```

use super::assembly::LocalMatrix;
use super::loop_subdivision::check_size;
use super::tri_rings::{self, Lattice, Mask, Stencil, TriNeighbourhood};
use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// Scheme name used in the matrix labels.
pub const NAME: &str = "sqrt3";

/// The ring of the local matrices: the two-ring (math doc section 21).
pub const RING: usize = 2;

/// Steps of subdivision in [`local_matrix`] (the one the analysis uses).
pub const STEPS: usize = 2;

/// Kobbelt's `alpha_n = (4 - 2 cos(2 pi / n)) / 9`; over the rationals only
/// at `n` in {3, 4, 6} (5/9, 4/9, 1/3), refused elsewhere.
pub fn alpha<T: Scalar>(n: usize) -> Result<T> {
    match n {
        0..=2 => Err(Error::ValenceTooSmall { valence: n }),
        3 => Ok(T::frac(5, 9)),
        4 => Ok(T::frac(4, 9)),
        6 => Ok(T::frac(1, 3)),
        _ if T::EXACT => Err(Error::InvalidParameter {
            name: "valence",
            value: n.to_string(),
            reason: "sqrt3 weights are irrational for this valence; exact arithmetic supports n = 3, 4, 6",
        }),
        _ => Ok(T::from_f64_lossless(
            (4.0 - 2.0 * (2.0 * std::f64::consts::PI / n as f64).cos()) / 9.0,
        )),
    }
}

/// The vertex rule at `p` with `alpha = alpha_n` for its valence `n`.
pub fn vertex_stencil<T: Scalar>(g: &impl TriNeighbourhood, p: usize, alpha: T) -> Stencil<T> {
    let n = g.valence(p);
    let each = alpha.clone() / T::frac(n as i64, 1);
    let mut out = vec![(p, T::one() - alpha)];
    out.extend((0..n).map(|k| (g.neighbour(p, k), each.clone())));
    out
}

/// The regular part's rules as plain data, in lattice offsets `(a, b) = a u +
/// b w` (`u`, `w` two lattice directions 60 degrees apart): the vertex rule
/// at `(0, 0)` (`alpha_6 = 1/3`) and the face point of the triangle
/// `(0, 0), (1, 0), (0, 1)`. The new lattice is spanned by the face points
/// `(u + w) / 3` and `(2 w - u) / 3`.
pub fn regular_masks() -> (Mask, Mask) {
    let third = 1.0 / 3.0;
    let vertex = std::iter::once(([0, 0], 2.0 / 3.0))
        .chain(
            [[1, 0], [0, 1], [-1, 1], [-1, 0], [0, -1], [1, -1]]
                .into_iter()
                .map(|o| (o, 1.0 / 18.0)),
        )
        .collect();
    let face = vec![([0, 0], third), ([1, 0], third), ([0, 1], third)];
    (vertex, face)
}

/// What the new point `p` (new lattice, turned by half a sector) is: the old
/// vertex, or the centroid of an old triangle. New `(A, B)` of sector `s`
/// sits at `A (u_s + u_{s+1}) / 3 + B (u_{s+1} + u_{s+2}) / 3`, which is
/// `((A - B) / 3, (A + 2B) / 3)` of old sector `s` when `A >= B`, else
/// `((2A + B) / 3, (B - A) / 3)` of sector `s + 1`; integral coordinates are
/// an old vertex, thirds the centroid of the triangle around them.
fn parent(lat: &Lattice, p: usize) -> Result<Stencil<()>> {
    let (_, s, a, b) = lat.coords(p);
    let (s, x3, y3) = if a >= b {
        (s as i64, a - b, a + 2 * b)
    } else {
        (s as i64 + 1, 2 * a + b, b - a)
    };
    let (fx, fy) = (x3.div_euclid(3), y3.div_euclid(3));
    let pts: Vec<(i64, i64)> = match (x3.rem_euclid(3), y3.rem_euclid(3)) {
        (0, 0) => vec![(fx, fy)],
        (1, 1) => vec![(fx, fy), (fx + 1, fy), (fx, fy + 1)],
        (2, 2) => vec![(fx + 1, fy), (fx + 1, fy + 1), (fx, fy + 1)],
        r => {
            return Err(Error::Numerical {
                routine: "sqrt3 layout",
                reason: format!("point {p} has remainders {r:?}"),
            })
        }
    };
    Ok(pts
        .into_iter()
        .map(|(x, y)| (lat.index(s, x, y), ()))
        .collect())
}

/// The one-step matrix of valence `n >= 3` on the `k`-ring over any scalar
/// (rationals at `n` in {3, 4, 6}): row `p` is the new point `p` in the
/// turned layout (module docs).
pub fn one_step_matrix_on<T: Scalar>(n: usize, k: usize) -> Result<LocalMatrix<T>> {
    let d = tri_rings::ring_len(n, k) as u128;
    check_size(n, d * d, "sqrt3 local matrix")?;
    let lat = Lattice::new(n);
    let (a_n, a_6) = (alpha::<T>(n)?, alpha::<T>(6)?);
    tri_rings::assemble(NAME, n, k, |p| {
        let par = parent(&lat, p)?;
        Ok(if let [(q, ())] = par[..] {
            let a = if q == 0 { a_n.clone() } else { a_6.clone() };
            vertex_stencil(&lat, q, a)
        } else {
            par.into_iter().map(|(q, ())| (q, T::frac(1, 3))).collect()
        })
    })
}

/// The `(3n + 1)`-square one-step matrix on the two-ring.
pub fn one_step_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    one_step_matrix_on(n, RING)
}

/// The two-step matrix on the `k`-ring over any scalar: the one-step matrix
/// squared, with the new point of label `(s, a, b)` taken from the two-step
/// point `(s - 1, a, b)` (two steps turn the lattice by one sector), so rows
/// and columns share the layout and the rotation is gone.
pub fn local_matrix_on<T: Scalar>(n: usize, k: usize) -> Result<LocalMatrix<T>> {
    let s1 = one_step_matrix_on::<T>(n, k)?;
    let m = s1.matrix();
    let lat = Lattice::new(n);
    let nz = |i: usize| -> Vec<(usize, T)> {
        (0..m.ncols())
            .filter(|&j| !m[(i, j)].is_zero())
            .map(|j| (j, m[(i, j)].clone()))
            .collect()
    };
    tri_rings::assemble(NAME, n, k, |p| {
        let (_, s, a, b) = lat.coords(p);
        let from = if p == 0 {
            0
        } else {
            lat.index(s as i64 - 1, a, b)
        };
        let mut st = Vec::new();
        for (mid, w1) in nz(from) {
            st.extend(nz(mid).into_iter().map(|(j, w2)| (j, w1.clone() * w2)));
        }
        Ok(st)
    })
}

/// The `(3n + 1)`-square two-step matrix on the two-ring (the analysis's).
pub fn local_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    local_matrix_on(n, RING)
}

/// The limit stencil over the two-ring: `(1 - beta) v + beta / n sum e_i`,
/// `beta = 3 alpha_n / (1 + 3 alpha_n)`, zero on the second ring: the left
/// eigenvector for 1 of the one-step (and two-step) matrix (math doc section
/// 20; `beta_6 = 1/2`).
pub fn limit_weights(n: usize) -> Result<Vec<f64>> {
    check_size(n, 3 * n as u128 + 1, "limit stencil")?;
    let a: f64 = alpha(n)?;
    let beta = 3.0 * a / (1.0 + 3.0 * a);
    let mut out = vec![1.0 - beta];
    out.extend(std::iter::repeat_n(beta / n as f64, n));
    out.extend(std::iter::repeat_n(0.0, 2 * n));
    Ok(out)
}

/// The limit weights `(1 - beta, beta / n)` on a vertex and each of its `n`
/// neighbours ([`limit_weights`]).
pub fn limit_vertex_weights(n: usize) -> Result<(f64, f64)> {
    let a: f64 = alpha(n)?;
    let beta = 3.0 * a / (1.0 + 3.0 * a);
    Ok((1.0 - beta, beta / n as f64))
}
