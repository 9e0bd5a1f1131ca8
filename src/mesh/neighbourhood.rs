//! The `4n` points around an n-sided face in the order of `S_n` (math doc section 4):
//!
//! ```text
//! M = [P_0..P_{n-1}, E_01, E_02, E_11, E_12, .., E_{n-1,1}, E_{n-1,2}, C_0..C_{n-1}]
//! ```
//!
//! `P_i` are the face's corners (from its first corner on), the E-face across
//! edge `P_i P_{i+1}` is `(P_i, P_{i+1}, E_i2, E_i1)` and the V-face at `P_i`
//! is `(P_i, E_i1, C_i, E_{i-1,2})`. The configuration exists after at most
//! two refinement steps (every corner valence 4, every neighbour a quad).
//!
//! `M' = S_n M` holds for a face that already existed one level earlier in a
//! mesh refined at least twice (the F-faces of level 2, i.e. children of
//! level-1 faces, which include every extraordinary face). A face *created* by
//! the second step (an E- or V-face of level 2) has the `4n` configuration but
//! not yet equal transverse intervals around it, so `S_n` applies to it one
//! level later (`tests/mesh/mesh_consistency.rs`).
//!
//! ```
//! use subdiv_lab::mesh::{generators, neighbourhood::face_neighbourhood, refine::refine_levels};
//! use subdiv_lab::schemes::SchemeKind;
//! let m = refine_levels(&generators::tetrahedron(), SchemeKind::Nurds, 2).unwrap();
//! let idx = face_neighbourhood(&m, 0).unwrap();
//! assert_eq!(idx.len(), 12);
//! ```

use super::Mesh;
use crate::schemes::doo_sabin::Layout;

/// Vertex indices of the `4n` configuration around face `f`, or `None` if the
/// neighbourhood does not have that shape (a corner of valence other than 4,
/// a neighbouring face that is not a quad, or points that are not distinct).
pub fn face_neighbourhood(mesh: &Mesh, f: usize) -> Option<Vec<usize>> {
    let corners: Vec<usize> = mesh.face_corners(f).collect();
    let n = corners.len();
    let lay = Layout::new(n);
    let mut idx = vec![usize::MAX; 4 * n];
    for (i, &h) in corners.iter().enumerate() {
        let v = mesh.origin(h);
        if mesh.valence(v) != 4 {
            return None;
        }
        idx[lay.p(i)] = v;
        // E-face across P_i -> P_{i+1}: P_{i+1} -> P_i -> E_i1 -> E_i2.
        let t = mesh.twin(h);
        if mesh.face_size(mesh.face_of(t)) != 4 {
            return None;
        }
        let a = mesh.next(t); // P_i -> E_i1
        idx[lay.e1(i)] = mesh.target(a);
        idx[lay.e2(i)] = mesh.target(mesh.next(a));
        // V-face at P_i: E_i1 -> P_i -> E_{i-1,2} -> C_i
        let u = mesh.twin(a);
        if mesh.face_size(mesh.face_of(u)) != 4 {
            return None;
        }
        let b = mesh.next(u); // P_i -> E_{i-1,2}
        idx[lay.c(i)] = mesh.target(mesh.next(b));
    }
    // E_{i-1,2} reached through the V-face must be the one of the E-face.
    for (i, &h) in corners.iter().enumerate() {
        let u = mesh.twin(mesh.next(mesh.twin(h)));
        if mesh.target(mesh.next(u)) != idx[lay.e2(i + n - 1)] {
            return None;
        }
    }
    let mut sorted = idx.clone();
    sorted.sort_unstable();
    sorted.dedup();
    (sorted.len() == 4 * n).then_some(idx)
}

/// The positions of [`face_neighbourhood`].
pub fn face_neighbourhood_points(mesh: &Mesh, f: usize) -> Option<Vec<[f64; 3]>> {
    face_neighbourhood(mesh, f).map(|idx| idx.iter().map(|&v| mesh.positions()[v]).collect())
}
