//! Structural certificates of a semisimple real double eigenvalue (math doc
//! section 10, "A double eigenvalue").
//!
//! Floating point cannot tell a semisimple double eigenvalue (`standard`)
//! from a Jordan block with a tiny nilpotent part or from two eigenvalues
//! closer than their error radii ([`super::classify`](mod@super::classify) module docs). What can
//! is *structure* that holds exactly:
//!
//! * A matrix `X` that commutes with the rotation of its `n` sectors splits,
//!   by the discrete Fourier transform, into blocks `X_l`, `l = 0..n-1`
//!   (math doc sections 6 and 11). If `X` is also mirror symmetric, `X_l` and
//!   `X_{n-l}` have the same real spectrum. An eigenvalue `lambda` that is
//!   simple in `X_l` with `l != 0`, `2 l != n` therefore has one eigenvector in
//!   mode `l` and one in mode `n - l`: it is a real double eigenvalue with a
//!   two-dimensional eigenspace. The schemes' closed-form Fourier spectra
//!   ([`Scheme::fourier_spectrum`]) carry this structure.
//! * A face block that is, bit for bit, circulant
//!   (`A[i][j] = a_{(i - j) mod n}`) and mirror symmetric (`a_k = a_{n-k}`) is
//!   the special case of one-by-one blocks: `lambda_l = sum_k a_k cos(2 pi l k / n)`.
//!   Deflating the simple eigenvalue 1 and embedding the face block in the
//!   block-triangular local matrix keep the Jordan structure of every
//!   eigenvalue that is not one of the other diagonal blocks' (`1/4, 1/8,
//!   1/16`; math doc section 4).
//!
//! The certificate is given only when the top pair is identified beyond
//! doubt: the largest non-unit block eigenvalue is real (exactly, in the
//! closed form), lies in two conjugate modes, every other block eigenvalue is
//! smaller in modulus by more than [`PAIR_MATCH_TOLERANCE`], and the
//! candidate double eigenvalue of the dense evidence matches it.

use crate::schemes::assembly::{LocalMatrix, PointLabel, Role};
use crate::schemes::Scheme;
use crate::spectral::eigen::{Eigen, EigenOptions};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// How closely a closed-form block eigenvalue must match the dense candidate
/// (and how far every other block eigenvalue must stay below it) for the
/// pairing to be certain. The closed-form block eigenvalues agree with dense
/// spectra to `2e-15 n^2`
/// ([`BLOCK_MATCH_TOL_PER_N2`](crate::schemes::catmull_clark::fourier::BLOCK_MATCH_TOL_PER_N2)),
/// below `1e-9` for every valence up to 700; the gaps between distinct block
/// eigenvalues at the top of the built-in spectra are above `1e-3`.
pub const PAIR_MATCH_TOLERANCE: f64 = 1e-9;

/// `Some(reason)` when the Fourier block spectra `blocks` (`(l, eigenvalues
/// of block l)`, valence `n`) certify that the top non-unit eigenvalue is a
/// real double eigenvalue with a two-dimensional eigenspace, made of modes
/// `l` and `n - l`, and that it matches `lambda` (module docs).
///
/// ```
/// use num_complex::Complex64;
/// use subdiv_lab::spectral::pairing::conjugate_mode_pair;
/// let z = |x: f64| Complex64::new(x, 0.0);
/// let blocks = vec![(0, vec![z(1.0), z(0.25)]), (1, vec![z(0.5)]), (2, vec![z(0.5)])];
/// assert!(conjugate_mode_pair(&blocks, 3, 0.5).is_some());
/// // A double eigenvalue inside one block proves nothing.
/// let blocks = vec![(0, vec![z(1.0), z(0.5), z(0.5)]), (1, vec![z(0.2)]), (2, vec![z(0.2)])];
/// assert!(conjugate_mode_pair(&blocks, 3, 0.5).is_none());
/// ```
pub fn conjugate_mode_pair(
    blocks: &[(usize, Vec<Complex64>)],
    n: usize,
    lambda: f64,
) -> Option<&'static str> {
    let tol = PAIR_MATCH_TOLERANCE;
    let mut all: Vec<(usize, Complex64)> = blocks
        .iter()
        .flat_map(|(l, v)| v.iter().map(move |&z| (*l % n.max(1), z)))
        .collect();
    // The dominant eigenvalue 1 of mode 0.
    let unit = all
        .iter()
        .enumerate()
        .filter(|(_, (l, _))| *l == 0)
        .min_by(|a, b| (a.1 .1 - 1.0).norm().total_cmp(&(b.1 .1 - 1.0).norm()))
        .map(|(i, (_, z))| (i, *z))?;
    if (unit.1 - 1.0).norm() > tol {
        return None;
    }
    all.swap_remove(unit.0);
    all.sort_by(|a, b| b.1.norm().total_cmp(&a.1.norm()));
    let (&(l1, z1), &(l2, z2)) = (all.first()?, all.get(1)?);
    let third = all.get(2).map_or(0.0, |t| t.1.norm());
    let conjugate = l1 != l2 && (l1 + l2) % n == 0;
    (conjugate
        && z1.im == 0.0
        && z2.im == 0.0
        && (z1.re - z2.re).abs() <= tol
        && third < z1.norm() - tol
        && (lambda - z1.re).abs() <= tol)
        .then_some(
            "the pair lies in two conjugate Fourier modes l and n - l of a real block eigenvalue",
        )
}

/// `Some(reason)` when the column-major `n x n` face block `f` is, bit for
/// bit, circulant and mirror symmetric (a kernel face block: constant row
/// sums, the vector of ones standing for the dominant 1) and its closed-form
/// eigenvalues
/// `lambda_l = sum_k a_k cos(2 pi l k / n)` certify `lambda` as the top pair
/// by [`conjugate_mode_pair`] (module docs).
///
/// ```
/// use subdiv_lab::spectral::pairing::circulant_pair;
/// // A circulant face block at n = 4: 1/2 on the diagonal, 1/8 on the two
/// // neighbours; mode l has 1/2 + cos(2 pi l / 4)/4: 1/2 in modes 1 and 3.
/// let n = 4;
/// let f: Vec<f64> = (0..n * n)
///     .map(|k| match ((k % n) + n - k / n) % n { 0 => 0.5, 1 | 3 => 0.125, _ => 0.0 })
///     .collect();
/// assert!(circulant_pair(&f, n, 0.5).is_some());
/// let mut g = f.clone();
/// g[1] += 1e-16; // no longer circulant bit for bit
/// assert!(circulant_pair(&g, n, 0.5).is_none());
/// ```
pub fn circulant_pair(f: &[f64], n: usize, lambda: f64) -> Option<&'static str> {
    if n < 3 || f.len() != n * n {
        return None;
    }
    let at = |i: usize, j: usize| f[i + j * n];
    // a_k = A[k][0]; circulant: A[i][j] = a_{(i - j) mod n}.
    for j in 0..n {
        for i in 0..n {
            if at(i, j).to_bits() != at((i + n - j) % n, 0).to_bits() {
                return None;
            }
        }
    }
    for k in 1..n {
        if at(k, 0).to_bits() != at(n - k, 0).to_bits() {
            return None;
        }
    }
    // Mode 0 is the vector of ones: its eigenvalue (the constant row sum of
    // a kernel face block) becomes the dominant 1 of the local matrix, and
    // the deflation removes it (math doc section 6).
    let blocks: Vec<(usize, Vec<Complex64>)> = std::iter::once((0, vec![Complex64::new(1.0, 0.0)]))
        .chain((1..n).map(|l| {
            let v: f64 = (0..n)
                .map(|k| {
                    let t = 2.0 * std::f64::consts::PI * ((l * k) % n) as f64 / n as f64;
                    at(k, 0) * t.cos()
                })
                .sum();
            (l, vec![Complex64::new(v, 0.0)])
        }))
        .collect();
    conjugate_mode_pair(&blocks, n, lambda)
        .map(|_| "the face block is circulant and mirror symmetric bit for bit, and the pair lies in two conjugate Fourier modes")
}

/// The structural certificate of a scheme for a double candidate `lambda` of
/// its **local matrix** (module docs): the closed-form Fourier spectrum when
/// the scheme has one; for a scheme with a face block, the circulant face
/// block, provided `lambda` exceeds the largest eigenvalue `1/4` of the other
/// diagonal blocks by more than [`PAIR_MATCH_TOLERANCE`]; else the
/// rotation and mirror symmetry of the labelled local matrix
/// ([`symmetric_pair`], which serves users' schemes too). `None` when nothing
/// certifies the pair (or the structure cannot be built).
pub fn scheme_pair_certificate<S: Scheme + ?Sized>(
    scheme: &S,
    lambda: f64,
) -> Option<&'static str> {
    let n = scheme.valence();
    if let Some(Ok(blocks)) = scheme.fourier_spectrum() {
        if let Some(why) = conjugate_mode_pair(&blocks, n, lambda) {
            return Some(why);
        }
    }
    if lambda > super::structured::KNOWN_EIGENVALUES[0] + PAIR_MATCH_TOLERANCE {
        let mut f = vec![0.0; n * n];
        if let Some(Ok(())) = scheme.fill_face_block(&mut f) {
            if let Some(why) = circulant_pair(&f, n, lambda) {
                return Some(why);
            }
        }
    }
    scheme
        .local_matrix()
        .ok()
        .and_then(|lm| symmetric_pair(&lm, lambda))
}

/// Where the rotation of the `n` sectors takes a labelled point (`k` steps),
/// or where the mirror through sector 0 takes it; `None` for points whose
/// label carries no sector (extended and patch-outer points).
///
/// Sector conventions (math doc sections 4, 8 and 11): `e_i`, `g_i`, `P_i`
/// and `C_i` sit on ray `i`; `f_i` between rays `i` and `i + 1`; `E_{i,1}`
/// next to `P_i` and `E_{i,2}` next to `P_{i+1}` on the edge `(P_i, P_{i+1})`.
fn moved(label: PointLabel, n: usize, mirror: bool) -> Option<PointLabel> {
    let i = label.index % n;
    let neg = |j: usize| (n - j % n) % n;
    let (role, index) = match (label.role, mirror) {
        (Role::Vertex, _) => (Role::Vertex, label.index),
        (r @ (Role::EdgeNeighbour | Role::SecondRing | Role::FaceCorner | Role::Corner), false)
        | (r @ Role::FaceNeighbour, false)
        | (r @ (Role::EdgeFirst | Role::EdgeSecond), false) => (r, (i + 1) % n),
        (r @ (Role::EdgeNeighbour | Role::SecondRing | Role::FaceCorner | Role::Corner), true) => {
            (r, neg(i))
        }
        (Role::FaceNeighbour, true) => (Role::FaceNeighbour, neg(i + 1)),
        (Role::EdgeFirst, true) => (Role::EdgeSecond, neg(i + 1)),
        (Role::EdgeSecond, true) => (Role::EdgeFirst, neg(i + 1)),
        (Role::OuterRing, mirror) => (
            Role::OuterRing,
            crate::schemes::tri_rings::moved_outer(label.index, n, mirror),
        ),
        _ => return None,
    };
    Some(PointLabel::new(role, index))
}

/// The permutation `p` of the rows with `label(p[k]) = moved(label(k))`, if
/// every label moves to a label of the matrix.
fn permutation(labels: &[PointLabel], n: usize, mirror: bool) -> Option<Vec<usize>> {
    let at: std::collections::HashMap<PointLabel, usize> =
        labels.iter().enumerate().map(|(k, l)| (*l, k)).collect();
    if at.len() != labels.len() {
        return None;
    }
    labels
        .iter()
        .map(|l| moved(*l, n, mirror).and_then(|m| at.get(&m).copied()))
        .collect()
}

/// `Some(reason)` when the labelled local matrix `lm` is, bit for bit,
/// invariant under the rotation of its sectors and under the mirror through
/// sector 0, and some pair of conjugate modes `l, n - l` (`0 < l < n/2`)
/// holds `lambda` exactly twice (module docs): then `lambda` is a real
/// eigenvalue of a two-dimensional eigenspace with one eigenvector in each
/// mode.
///
/// The modes `l` and `n - l` together span a real invariant subspace with
/// the orthonormal basis `cos(2 pi l j / n) e_(o, j)`, `sin(2 pi l j / n)
/// e_(o, j)` (`sqrt(2/n)`-scaled, `o` over the rotation orbits of size `n`);
/// the restriction `R_l = Q^T X Q` has the spectrum of the Fourier block
/// `X_l` twice (the mirror makes `X_{n-l}` similar to `X_l`, and `X_{n-l}`
/// is the conjugate of `X_l`, so the spectrum of `X_l` is closed under
/// conjugation). Exactly two eigenvalues of `R_l` within
/// [`PAIR_MATCH_TOLERANCE`] of `lambda` make `lambda` a simple, hence real,
/// eigenvalue of `X_l`.
///
/// ```
/// use subdiv_lab::schemes::Scheme;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::pairing::symmetric_pair;
/// let s = LocalScheme::<f64>::catmull_clark(5).unwrap();
/// let lm = s.local_matrix().unwrap();
/// // 0.3 is no eigenvalue of the matrix: nothing is certified.
/// assert!(symmetric_pair(&lm, 0.3).is_none());
/// ```
pub fn symmetric_pair(lm: &LocalMatrix<f64>, lambda: f64) -> Option<&'static str> {
    let n = lm.valence();
    let x = lm.matrix();
    let labels = lm.rows();
    if n < 3 || labels != lm.cols() || x.nrows() != labels.len() {
        return None;
    }
    let rot = permutation(labels, n, false)?;
    let mir = permutation(labels, n, true)?;
    let d = labels.len();
    for p in [&rot, &mir] {
        for j in 0..d {
            for i in 0..d {
                if x[(p[i], p[j])].to_bits() != x[(i, j)].to_bits() {
                    return None;
                }
            }
        }
    }
    // Orbits of size n, by a representative.
    let mut seen = vec![false; d];
    let mut orbits: Vec<Vec<usize>> = Vec::new();
    for k in 0..d {
        if seen[k] {
            continue;
        }
        let mut orbit = vec![k];
        seen[k] = true;
        let mut j = rot[k];
        while j != k {
            seen[j] = true;
            orbit.push(j);
            j = rot[j];
        }
        match orbit.len() {
            1 => {}
            len if len == n => orbits.push(orbit),
            _ => return None,
        }
    }
    let m = orbits.len();
    let scale = (2.0 / n as f64).sqrt();
    for l in 1..n.div_ceil(2) {
        if 2 * l == n {
            continue;
        }
        let mut q = DMatrix::<f64>::zeros(d, 2 * m);
        for (o, orbit) in orbits.iter().enumerate() {
            for (j, &row) in orbit.iter().enumerate() {
                let t = 2.0 * std::f64::consts::PI * ((l * j) % n) as f64 / n as f64;
                q[(row, 2 * o)] = scale * t.cos();
                q[(row, 2 * o + 1)] = scale * t.sin();
            }
        }
        let r = q.transpose() * x * &q;
        let Ok(e) = Eigen::new(&r, EigenOptions::VALUES) else {
            continue;
        };
        let near = e
            .values()
            .iter()
            .filter(|z| (**z - lambda).norm() <= PAIR_MATCH_TOLERANCE)
            .count();
        if near == 2 {
            return Some("the labelled matrix is rotation and mirror invariant bit for bit, and the pair is one real eigenvalue of the conjugate Fourier modes l and n - l");
        }
    }
    None
}
