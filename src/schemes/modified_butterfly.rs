//! The modified butterfly scheme (Zorin, Schroder, Sweldens 1996): the
//! butterfly scheme ([`super::butterfly`]) on edges between two regular
//! vertices (valence 6), and at an edge `(p, q)` with `p` of valence `K != 6`
//! the stencil
//!
//! ```text
//! 3/4 p + sum_{j < K} s_j e_j,     e_0 = q, e_j the neighbours of p in order,
//! s_j = (1/4 + cos(2 pi j / K) + 1/2 cos(4 pi j / K)) / K     (K >= 5),
//! (5/12, -1/12, -1/12) (K = 3),   (3/8, 0, -1/8, 0) (K = 4);
//! ```
//!
//! an edge between two extraordinary vertices averages the two stencils
//! (math doc section 21). The old vertices are kept. The local matrix lives
//! on the three-ring (`6n + 1` points; for `n != 6` the one-ring is closed
//! too, but the regular butterfly part reaches the third ring).
//!
//! ```
//! use subdiv_lab::schemes::modified_butterfly::extraordinary_weights;
//! let s = extraordinary_weights::<f64>(5).unwrap();
//! assert!((s.iter().sum::<f64>() - 0.25).abs() < 1e-15);
//! ```

use super::assembly::LocalMatrix;
use super::loop_subdivision::check_size;
use super::tri_rings::TriNeighbourhood;
use super::tri_rings::{self, butterfly_edge, split4_parent, Lattice, Split4Point, Stencil};
use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// Scheme name used in the matrix labels.
pub const NAME: &str = "modified-butterfly";

/// The ring of the local matrix: the three-ring (math doc section 21).
pub const RING: usize = 3;

/// The valence of a regular vertex (the butterfly stencil applies between two).
pub const REGULAR_VALENCE: usize = 6;

/// The weights `s_0 .. s_{K-1}` of the stencil at a vertex of valence `K >= 3`
/// (module docs; they sum to 1/4). Over the rationals only where they are
/// rational, `K` in {3, 4, 6}; refused elsewhere.
pub fn extraordinary_weights<T: Scalar>(k: usize) -> Result<Vec<T>> {
    let q = |v: &[(i64, i64)]| v.iter().map(|&(a, b)| T::frac(a, b)).collect();
    match k {
        0..=2 => Err(Error::ValenceTooSmall { valence: k }),
        3 => Ok(q(&[(5, 12), (-1, 12), (-1, 12)])),
        4 => Ok(q(&[(3, 8), (0, 1), (-1, 8), (0, 1)])),
        6 => Ok(q(&[(7, 24), (1, 12), (-1, 12), (-1, 24), (-1, 12), (1, 12)])),
        _ if T::EXACT => Err(Error::InvalidParameter {
            name: "valence",
            value: k.to_string(),
            reason: "modified butterfly weights are irrational for this valence; exact arithmetic supports n = 3, 4, 6",
        }),
        _ => Ok((0..k)
            .map(|j| {
                // s_j = s_{K-j} bit for bit (the mirror symmetry)
                let x = 2.0 * std::f64::consts::PI * j.min(k - j) as f64 / k as f64;
                T::from_f64_lossless((0.25 + x.cos() + 0.5 * (2.0 * x).cos()) / k as f64)
            })
            .collect()),
    }
}

/// The stencil at the extraordinary end `p` of an edge whose other end is
/// the `t`-th neighbour of `p`: `3/4 p + sum_j s_j e_{t+j}`.
fn extraordinary_stencil<T: Scalar>(
    g: &impl TriNeighbourhood,
    p: usize,
    t: usize,
    s: &[T],
) -> Stencil<T> {
    let mut out = vec![(p, T::frac(3, 4))];
    out.extend(
        s.iter()
            .enumerate()
            .map(|(j, w)| (g.neighbour(p, t + j), w.clone())),
    );
    out
}

/// The new point of the edge `(p, q)` (`q` the `t`-th neighbour of `p`, `p`
/// the `tq`-th of `q`): the butterfly stencil between two regular vertices,
/// the extraordinary stencil of the irregular end, or the mean of both ends'
/// stencils. `weights(K)` gives [`extraordinary_weights`] (a mesh caches
/// them by valence).
pub fn edge<T: Scalar>(
    g: &impl TriNeighbourhood,
    (p, t): (usize, usize),
    (q, tq): (usize, usize),
    weights: &mut impl FnMut(usize) -> Result<Vec<T>>,
) -> Result<Stencil<T>> {
    let (kp, kq) = (g.valence(p), g.valence(q));
    Ok(match (kp != REGULAR_VALENCE, kq != REGULAR_VALENCE) {
        (false, false) => butterfly_edge(g, p, t, q, tq),
        (true, false) => extraordinary_stencil(g, p, t, &weights(kp)?),
        (false, true) => extraordinary_stencil(g, q, tq, &weights(kq)?),
        (true, true) => {
            let half = T::frac(1, 2);
            let mut st = extraordinary_stencil(g, p, t, &weights(kp)?);
            st.extend(extraordinary_stencil(g, q, tq, &weights(kq)?));
            st.into_iter().map(|(i, w)| (i, w * half.clone())).collect()
        }
    })
}

/// The local matrix of valence `n >= 3` on the `k`-ring over any scalar
/// (over the rationals at `n` in {3, 4, 6}); [`local_matrix`] is the
/// three-ring.
pub fn local_matrix_on<T: Scalar>(n: usize, k: usize) -> Result<LocalMatrix<T>> {
    let d = tri_rings::ring_len(n, k) as u128;
    check_size(n, d * d, "modified butterfly local matrix")?;
    extraordinary_weights::<T>(n)?;
    let lat = Lattice::new(n);
    tri_rings::assemble(NAME, n, k, |p| {
        Ok(match split4_parent(&lat, p) {
            Split4Point::Vertex(q) => vec![(q, T::one())],
            Split4Point::Edge(a, t, b, tb) => {
                edge(&lat, (a, t), (b, tb), &mut extraordinary_weights)?
            }
        })
    })
}

/// The `(6n + 1)`-square local matrix on the three-ring.
pub fn local_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    local_matrix_on(n, RING)
}

/// The regular part's rule as plain data: the butterfly edge mask
/// ([`super::butterfly::regular_edge_mask`]).
pub fn regular_edge_mask() -> tri_rings::Mask {
    super::butterfly::regular_edge_mask()
}
