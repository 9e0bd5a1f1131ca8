//! Loop subdivision (Loop 1987) on triangle meshes: weights, the local
//! subdivision matrix on the two-ring of an extraordinary vertex, its Fourier
//! blocks, the certified characteristic map, and mesh refinement.
//!
//! Weights (math doc, Loop section):
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

pub mod charmap;
pub mod fourier;
pub mod matrix;
pub mod mesh;
pub mod tri_bezier;

/// Smallest valence of a Loop vertex.
pub const MIN_VALENCE: usize = 3;

/// Loop's vertex weight `beta_n = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`
/// (math doc, Loop section). `n >= 3` is the caller's business.
pub fn beta(n: usize) -> f64 {
    let t = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
    (0.625 - t * t) / n as f64
}

/// The subdominant eigenvalue `3/8 + cos(2 pi / n) / 4` of valence `n`.
pub fn subdominant_eigenvalue(n: usize) -> f64 {
    0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos()
}
