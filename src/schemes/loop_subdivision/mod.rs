//! Loop subdivision (Loop 1987) on triangle meshes: weights, the local
//! subdivision matrix on the two-ring of an extraordinary vertex, its Fourier
//! blocks and the Bezier ring of its characteristic map; its mesh refinement is
//! [`crate::mesh::loop_subdivision`].
//!
//! Weights (math doc section 11):
//!
//! * vertex point: `(1 - n beta_n) v + beta_n sum e_i` with
//!   `beta_n = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`;
//! * edge point of edge `(a, b)` with opposite vertices `c, d`:
//!   `3/8 (a + b) + 1/8 (c + d)`.
//!
//! The subdominant eigenvalue of valence `n` is `3/8 + cos(2 pi / n) / 4`.
//!
//! ## Two-ring layout (shared by every file of this module)
//!
//! Around a vertex `v` of valence `n` whose neighbours are all regular
//! (valence 6), the two-ring has `3n + 1` points, indexed:
//!
//! * `0`: `v`;
//! * `1 + i` (`i = 0..n`): `e_i`, the one-ring, counter-clockwise;
//! * `1 + n + 2i`: `g_i`, the two-ring vertex straight beyond `e_i`
//!   (adjacent to `e_i`, `f_{i-1}` and `f_i`);
//! * `2 + n + 2i`: `f_i`, the vertex across the edge `e_i e_{i+1}` from `v`.
//!
//! Indices of `e`, `g`, `f` are taken mod `n`. The triangles of the two-ring
//! are `(v, e_i, e_{i+1})`, `(e_i, f_i, e_{i+1})`, `(e_i, g_i, f_i)` and
//! `(e_i, f_{i-1}, g_i)`, all counter-clockwise.
//!
//! [`TwoRing`] computes these indices; [`matrix`] assembles the local
//! matrices on them, [`fourier`] block-diagonalises them, [`tri_bezier`]
//! holds the triangular Bezier machinery and the regular (box-spline) patch,
//! and [`ring`] converts the regular patches of the ring around the vertex to
//! Bezier form; the characteristic map is certified by
//! [`crate::charmap::loop_subdivision`].
//!
//! ```
//! use subdiv_lab::schemes::loop_subdivision::{beta, limit_weights, subdominant_eigenvalue};
//! // valence 6 is the regular case: beta = 1/16, eigenvalue 1/2, limit mask (1/2, 1/12 x 6)
//! assert!((beta(6) - 1.0 / 16.0).abs() < 1e-17);
//! assert!((subdominant_eigenvalue(6) - 0.5).abs() < 1e-15);
//! let l = limit_weights(6).unwrap();
//! assert!((l[0] - 0.5).abs() < 1e-15 && (l[1] - 1.0 / 12.0).abs() < 1e-15);
//! ```

pub mod fourier;
pub mod matrix;
pub mod ring;
mod rules;
pub mod tri_bezier;

pub(crate) use rules::check_size;
pub use rules::{
    beta, limit_weights, subdominant_eigenvalue, validate, TwoRing, ANALYZE_SECONDS_PER_N3,
    COST_MODEL, MIN_VALENCE, SWEEP_CHARMAP_SECONDS_PER_N3, SWEEP_CLASSIFY_SECONDS_PER_N3,
};
