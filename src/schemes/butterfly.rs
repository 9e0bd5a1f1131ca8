//! The butterfly scheme (Dyn, Gregory, Levin 1990) with tension `w = 1/16`:
//! an interpolatory scheme on triangle meshes that keeps every old vertex and
//! puts the new point of an edge `(p, q)` at
//!
//! ```text
//! 1/2 (p + q) + 1/8 (c + d) - 1/16 (w1 + w2 + w3 + w4)
//! ```
//!
//! ([`tri_rings::butterfly_edge`]), the regular eight-point stencil at every
//! valence. Its local matrix lives on the three-ring of the extraordinary
//! vertex (`6n + 1` points, layout of [`tri_rings`]): the smallest ring that
//! is closed under one step *and* holds every control point whose basis
//! function reaches the one-ring (math doc section 21). Its mesh refinement
//! is [`crate::mesh::tri_schemes`].
//!
//! ```
//! use subdiv_lab::schemes::butterfly::local_matrix;
//! let s = local_matrix(5).unwrap();
//! assert_eq!(s.matrix().shape(), (31, 31));
//! assert_eq!(s.matrix()[(0, 0)], 1.0); // the old vertex is kept
//! ```

use super::assembly::LocalMatrix;
use super::loop_subdivision::check_size;
use super::tri_rings::{self, butterfly_edge, split4_parent, Lattice, Split4Point};
use crate::error::Result;
use crate::scalar::Scalar;

/// Scheme name used in the matrix labels.
pub const NAME: &str = "butterfly";

/// The ring of the local matrix: the three-ring, `6n + 1` points (math doc
/// section 21).
pub const RING: usize = 3;

/// The regular part's rule as plain data: the new point of the lattice edge
/// from `(0, 0)` to `(1, 0)`, as `(lattice offset (a, b) = a u + b w, weight)`
/// with `u`, `w` two lattice directions 60 degrees apart (the old vertices
/// keep their place: the vertex rule is the identity).
///
/// ```
/// let m = subdiv_lab::schemes::butterfly::regular_edge_mask();
/// assert_eq!(m.len(), 8);
/// assert!((m.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-15);
/// ```
pub fn regular_edge_mask() -> tri_rings::Mask {
    vec![
        ([0, 0], 0.5),
        ([1, 0], 0.5),
        ([0, 1], 0.125),
        ([1, -1], 0.125),
        ([-1, 1], -0.0625),
        ([0, -1], -0.0625),
        ([1, 1], -0.0625),
        ([2, -1], -0.0625),
    ]
}

/// The local matrix of valence `n >= 3` on the `k`-ring over any scalar
/// (exact over the rationals at every valence: the weights are rational).
/// [`local_matrix`] is the three-ring; other rings serve the closure tests
/// (`k = 1` is refused: the one-ring is not closed).
pub fn local_matrix_on<T: Scalar>(n: usize, k: usize) -> Result<LocalMatrix<T>> {
    let d = tri_rings::ring_len(n, k) as u128;
    check_size(n, d * d, "butterfly local matrix")?;
    let lat = Lattice::new(n);
    tri_rings::assemble(NAME, n, k, |p| {
        Ok(match split4_parent(&lat, p) {
            Split4Point::Vertex(q) => vec![(q, T::one())],
            Split4Point::Edge(a, t, b, tb) => butterfly_edge(&lat, a, t, b, tb),
        })
    })
}

/// The `(6n + 1)`-square local matrix on the three-ring.
pub fn local_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    local_matrix_on(n, RING)
}
