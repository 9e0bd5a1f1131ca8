//! The subdominant classification of a scheme or a matrix (math doc
//! sections 5-6): the face-block kernel, the dense kernel with the structural
//! certificate of a double eigenvalue, and the general fallback; with the
//! per-eigenvalue error radii and the double-eigenvalue test `analyze` shares.

use super::classify::Subdominant;
use super::classify::{
    classify, classify_into, equality_limit, DoubleTest, Evidence, BACKWARD_ERROR_FACTOR,
};
use super::eigen::spectral_order;
use super::eigen::{Eigen, EigenOptions};
use super::{kernel, pairing, structured, svd, Result, SpectralError, StructuredWorkspace};
use crate::schemes::{Scheme, SpectralStructure};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::cell::RefCell;

/// Error radius of `|lambda_1|` for the spectral-bound check of a
/// Doo-Sabin-family scheme: the first-order radius `e` of the classification,
/// capped by the perturbation bound of a defective double eigenvalue (a
/// Jordan block of size 2, where first-order radii blow up: see
/// [`classify::equality_limit`]): a backward error `eta` moves its
/// eigenvalues by about `sqrt(||N|| eta)` with the nilpotent part
/// `||N|| <= ||A - lambda I|| <= ||A||_F + 1`, so the cap is
/// `sqrt((||A||_F + 1) eta)` with `eta = BACKWARD_ERROR_FACTOR n eps ||A||_F`
/// for the face block `A`. (The classification meets no larger Jordan
/// blocks; a block of size `k` would move by `eta^(1/k)`.)
pub(super) fn modulus_radius(a: &DMatrix<f64>, e: f64) -> f64 {
    let norm = a.norm();
    let eta = BACKWARD_ERROR_FACTOR * a.nrows() as f64 * f64::EPSILON * norm;
    let cap = ((norm + 1.0) * eta).sqrt();
    if e.is_nan() {
        cap
    } else {
        e.min(cap)
    }
}

/// Error radius `max(kappa, 1) * eta` (0 when `eta = 0`, i.e. the zero matrix,
/// even if `kappa` is infinite).
pub(super) fn radius(kappa: f64, eta: f64) -> f64 {
    if eta == 0.0 {
        0.0
    } else if kappa.is_nan() {
        f64::INFINITY
    } else {
        kappa.max(1.0) * eta
    }
}

pub(super) fn c64(z: Complex64) -> [f64; 2] {
    [z.re, z.im]
}

/// The double-eigenvalue evidence ([`DoubleTest`]): the rank test of
/// [`second_smallest_sigma`] and the structural certificate `semisimple`.
pub(super) fn double_test(
    x: &DMatrix<f64>,
    lambda: f64,
    semisimple: Option<&'static str>,
) -> Result<DoubleTest, SpectralError> {
    Ok(DoubleTest {
        sigma: second_smallest_sigma(x, lambda)?,
        semisimple,
    })
}

/// Second smallest singular value of `x - lambda I` ([`svd::singular_values`]:
/// faer's SVD, the one-sided Jacobi SVD when that does not converge).
pub(super) fn second_smallest_sigma(x: &DMatrix<f64>, lambda: f64) -> Result<f64, SpectralError> {
    let n = x.nrows();
    if n < 2 {
        return Ok(f64::INFINITY);
    }
    let m = DMatrix::from_fn(n, n, |i, j| x[(i, j)] - if i == j { lambda } else { 0.0 });
    // faer's SVD, with the one-sided Jacobi SVD as the fallback route
    let s = svd::singular_values(&m)?;
    // Sorted non-increasing.
    Ok(s[n - 2])
}

/// Condition numbers of the `wanted` entries of `values` (the others are
/// left 0) by one call of `compute` (the kernel's interleaved inverse
/// iterations). A wanted value that is the conjugate of the wanted value
/// before it shares that value's number: for a real matrix the computation
/// for `conj(z)` is the conjugate of the one for `z`, bit for bit.
fn condition_numbers_of(
    values: &[Complex64; 4],
    wanted: [bool; 4],
    compute: impl FnOnce(&[Complex64], &mut [f64]),
) -> [f64; 4] {
    let mut shifts = [Complex64::new(0.0, 0.0); 4];
    let mut slot = [usize::MAX; 4];
    let mut count = 0;
    let mut last: Option<usize> = None;
    for k in 0..4 {
        if !wanted[k] {
            continue;
        }
        match last {
            Some(p) if values[p] == values[k].conj() => slot[k] = slot[p],
            _ => {
                shifts[count] = values[k];
                slot[k] = count;
                count += 1;
            }
        }
        last = Some(k);
    }
    let mut kappa = [0.0f64; 4];
    compute(&shifts[..count], &mut kappa[..count]);
    std::array::from_fn(|k| if wanted[k] { kappa[slot[k]] } else { 0.0 })
}

/// The subdominant classification of any scheme: [`classify_scheme`] (the
/// face-block kernel for a scheme with a face block, else the local matrix
/// with the scheme's structural certificate,
/// [`pairing::scheme_pair_certificate`]).
pub fn classify_local<S: Scheme + ?Sized>(scheme: &S) -> Result<Subdominant> {
    classify_scheme(scheme)
}

thread_local! {
    static WORKSPACE: RefCell<StructuredWorkspace> = RefCell::new(StructuredWorkspace::new());
}

/// Classification only, by the structured path (the sweep fast path).
///
/// Doo-Sabin family only; uses a thread-local [`StructuredWorkspace`], so it
/// allocates nothing after the first call per thread and valence (except in
/// the rare near-double case, which runs a singular value decomposition).
/// Condition numbers of the face eigenvalues in positions 1-3 come from
/// inverse iteration on the Hessenberg form (`O(n^2)` each).
///
/// Schemes without a face block (the Catmull-Clark family, Loop): the local
/// matrix is classified by [`classify_matrix`] (the allocation-free kernel;
/// the matrix itself is assembled per call).
pub fn classify_scheme<S: Scheme + ?Sized>(scheme: &S) -> Result<Subdominant> {
    WORKSPACE.with(|ws| classify_scheme_with(&mut ws.borrow_mut(), scheme))
}

/// [`classify_scheme`] with an explicit workspace (unused for schemes
/// without a face block: those are classified by [`classify_matrix`] on
/// their local matrix).
pub fn classify_scheme_with<S: Scheme + ?Sized>(
    ws: &mut StructuredWorkspace,
    scheme: &S,
) -> Result<Subdominant> {
    if scheme.spectral_structure() != SpectralStructure::FaceBlock {
        return classify_matrix_with(scheme.local_matrix()?.matrix(), &mut |lam| {
            pairing::scheme_pair_certificate(scheme, lam)
        });
    }
    ws.face_nonunit(scheme)?;
    classify_face(ws, scheme.valence())
}

/// [`classify_scheme_with`] for [`BATCH`](super::BATCH) schemes in as many
/// workspaces at once: the face spectra come from
/// [`StructuredWorkspace::face_nonunit_batch`] (the QR iterations in lock
/// step, one per SIMD lane), so the results equal, bit for bit, those of
/// `classify_scheme_with` calls, at a higher throughput (the sweep driver and
/// `benches/throughput.rs` classify configurations in batches).
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::BATCH;
/// use subdiv_lab::spectral::{classify_scheme, classify_schemes_batch, StructuredWorkspace};
/// let schemes: Vec<LocalScheme<f64>> = (0..BATCH)
///     .map(|i| LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.5, 0.05 + 0.05 * i as f64]).unwrap()))
///     .collect();
/// let mut ws: [StructuredWorkspace; BATCH] = Default::default();
/// let res = classify_schemes_batch(ws.each_mut(), std::array::from_fn(|i| &schemes[i]));
/// for (r, s) in res.into_iter().zip(&schemes) {
///     assert_eq!(r.unwrap(), classify_scheme(s).unwrap());
/// }
/// ```
pub fn classify_schemes_batch<S: Scheme + ?Sized>(
    ws: [&mut StructuredWorkspace; kernel::BATCH],
    schemes: [&S; kernel::BATCH],
) -> [Result<Subdominant>; kernel::BATCH] {
    let mut subs: [Subdominant; kernel::BATCH] = std::array::from_fn(|_| Subdominant::unset());
    let res = classify_schemes_batch_into(ws, schemes, subs.each_mut());
    let mut subs = subs.into_iter();
    res.map(|r| {
        let s = subs.next().expect("one result per lane");
        r.map(|()| s)
    })
}

/// [`classify_schemes_batch`] into `out` (lane `l`'s classification into
/// `out[l]`, overwritten whole when its result is `Ok`).
pub(crate) fn classify_schemes_batch_into<S: Scheme + ?Sized>(
    ws: [&mut StructuredWorkspace; kernel::BATCH],
    schemes: [&S; kernel::BATCH],
    out: [&mut Subdominant; kernel::BATCH],
) -> [Result<()>; kernel::BATCH] {
    let mut ws = ws;
    let mut out = out;
    if !schemes
        .iter()
        .all(|s| s.spectral_structure() == SpectralStructure::FaceBlock)
    {
        return std::array::from_fn(|l| {
            classify_scheme_with(ws[l], schemes[l]).map(|s| *out[l] = s)
        });
    }
    let faces = StructuredWorkspace::face_nonunit_batch(ws.each_mut().map(|w| &mut **w), schemes);
    let mut faces = faces.into_iter();
    std::array::from_fn(|l| {
        let f = faces.next().expect("one result per lane");
        f.and_then(|()| classify_face_into(ws[l], schemes[l].valence(), out[l]))
    })
}

/// The classification of a valence-`n` Doo-Sabin-family scheme whose face
/// spectrum `ws` holds.
fn classify_face(ws: &mut StructuredWorkspace, n: usize) -> Result<Subdominant> {
    let mut out = Subdominant::unset();
    classify_face_into(ws, n, &mut out)?;
    Ok(out)
}

/// [`classify_face`] into `out` (overwritten whole when `Ok`).
fn classify_face_into(ws: &mut StructuredWorkspace, n: usize, out: &mut Subdominant) -> Result<()> {
    let face_len = ws.face_nonunit_cached().len();
    let m = ws.deflated_dim();
    let eta = BACKWARD_ERROR_FACTOR * m.max(1) as f64 * f64::EPSILON * ws.frobenius_norm();
    // Merge the top of the face spectrum with the known 1/4 (n copies).
    let mut top = [(Complex64::new(1.0, 0.0), 0.0f64, usize::MAX); 4];
    let mut face_top = [Complex64::new(0.0, 0.0); 3];
    let k = face_len.min(3);
    {
        let face = ws.face_nonunit_cached();
        face_top[..k].copy_from_slice(&face[..k]);
    }
    let quarter = Complex64::new(structured::KNOWN_EIGENVALUES[0], 0.0);
    let (mut fi, mut qi) = (0usize, 0usize);
    for slot in top.iter_mut().skip(1) {
        let take_face = fi < k && (qi >= n || spectral_order(&face_top[fi], &quarter).is_le());
        if take_face {
            *slot = (face_top[fi], 0.0, fi);
            fi += 1;
        } else {
            *slot = (quarter, 0.0, usize::MAX);
            qi += 1;
        }
    }
    // Condition numbers for face eigenvalues among lambda_1..lambda_3.
    let wanted = [
        false,
        top[1].2 != usize::MAX,
        top[2].2 != usize::MAX,
        top[3].2 != usize::MAX,
    ];
    let values4 = [top[0].0, top[1].0, top[2].0, top[3].0];
    let kappa = condition_numbers_of(&values4, wanted, |z, k| ws.condition_numbers(z, k));
    for (k, slot) in top.iter_mut().enumerate() {
        if wanted[k] {
            slot.1 = radius(kappa[k], eta);
        }
    }
    let values = [top[0].0, top[1].0, top[2].0, top[3].0];
    let radii = [top[0].1, top[1].1, top[2].1, top[3].1];
    let bm = ws.deflated_matrix();
    // A double made of two face eigenvalues (not the known 1/4) is certified
    // by a circulant, mirror-symmetric face block ([`pairing`]).
    let both_face = top[1].2 != usize::MAX && top[2].2 != usize::MAX;
    let face = ws.face_block();
    classify_into(
        &Evidence {
            values: &values,
            radii: &radii,
            eta,
        },
        &mut |lam| {
            let b = DMatrix::from_column_slice(m, m, bm);
            let cert = if both_face {
                pairing::circulant_pair(face, n, lam)
            } else {
                None
            };
            double_test(&b, lam, cert)
        },
        out,
    )?;
    Ok(())
}

thread_local! {
    static MATRIX_WORKSPACE: RefCell<(kernel::KernelWorkspace, Vec<Complex64>)> =
        RefCell::new((kernel::KernelWorkspace::new(), Vec::new()));
}

/// Classification only for any square matrix (e.g. schemes outside the
/// Doo-Sabin family), by the allocation-free eigenvalue kernel ([`KernelWorkspace`](super::KernelWorkspace)): all eigenvalues,
/// condition numbers of `lambda_1..lambda_3` by inverse iteration, and the
/// rank test (faer SVD) only for a double-eigenvalue candidate.
///
/// ```
/// use nalgebra::DMatrix;
/// use subdiv_lab::spectral::{classify_matrix, SubdominantClass};
/// // Eigenvalues 1, 1/2, 1/4, 1/4: |lambda_2| = |lambda_3|.
/// let s = DMatrix::from_row_slice(4, 4, &[
///     1.0, 0.0, 0.0, 0.0,
///     0.5, 0.5, 0.0, 0.0,
///     0.75, 0.0, 0.25, 0.0,
///     0.75, 0.0, 0.0, 0.25,
/// ]);
/// assert_eq!(classify_matrix(&s).unwrap().class, SubdominantClass::NotSeparated);
/// ```
pub fn classify_matrix(s: &DMatrix<f64>) -> Result<Subdominant> {
    classify_matrix_with(s, &mut |_| None)
}

/// [`classify_matrix`] with a structural certificate for a double candidate
/// `lambda` ([`DoubleTest::semisimple`], e.g.
/// [`pairing::scheme_pair_certificate`]); without one a double eigenvalue is
/// `indeterminate` ([`classify`](mod@super::classify) module docs).
///
/// The kernel's verdict stands when it is decided and every radius
/// `kappa_k eta` (`k <= 3`) is at most [`equality_limit`]`(eta) =
/// sqrt(eta)`; otherwise (a nearly defective eigenvalue, whose condition
/// number one step of inverse iteration does not estimate reliably) the
/// verdict is the general decomposition's, the one `analyze` reports (math
/// doc 10, "Two routes, one verdict").
pub fn classify_matrix_with(
    s: &DMatrix<f64>,
    certificate: &mut dyn FnMut(f64) -> Option<&'static str>,
) -> Result<Subdominant> {
    let (n, m) = s.shape();
    if n != m {
        return Err(SpectralError::NotSquare { rows: n, cols: m });
    }
    MATRIX_WORKSPACE.with(|cell| {
        let mut guard = cell.borrow_mut();
        let (ws, values) = &mut *guard;
        ws.input(n).copy_from_slice(s.as_slice());
        let (re, im) = match ws.eigenvalues() {
            Ok(v) => v,
            // fallback route: the general eigen-decomposition (faer), as on
            // the full path of `analyze`
            Err(SpectralError::NoConvergence { .. }) => return classify_general(s, certificate),
            Err(e) => return Err(e),
        };
        values.clear();
        values.extend(re.iter().zip(im).map(|(&a, &b)| Complex64::new(a, b)));
        values.sort_by(spectral_order);
        let eta = BACKWARD_ERROR_FACTOR * n.max(1) as f64 * f64::EPSILON * s.norm();
        let top: Vec<Complex64> = values.iter().take(4).copied().collect();
        let mut values4 = [Complex64::new(0.0, 0.0); 4];
        values4[..top.len()].copy_from_slice(&top);
        let wanted: [bool; 4] = std::array::from_fn(|k| k < top.len());
        let kappa = condition_numbers_of(&values4, wanted, |z, k| ws.condition_numbers(z, k));
        let mut radii = [0.0f64; 4];
        for k in 0..top.len() {
            radii[k] = radius(kappa[k], eta);
        }
        let sub = classify(
            &Evidence {
                values: &top,
                radii: &radii[..top.len()],
                eta,
            },
            &mut |lam| double_test(s, lam, certificate(lam)),
        )?;
        // Inverse iteration's condition numbers are estimates; where they
        // leave the verdict open or leave the linear regime (a nearly
        // defective eigenvalue among lambda_0..lambda_3), the verdict is the
        // general decomposition's, as in `analyze` (math doc 10, "Two routes,
        // one verdict").
        let limit = equality_limit(eta);
        if sub.class.is_indeterminate() || radii[..top.len()].iter().any(|&e| e > limit) {
            drop(guard);
            return classify_general(s, certificate);
        }
        Ok(sub)
    })
}

/// Classification of any square matrix from its general eigen-decomposition
/// with condition numbers ([`Eigen`], the full path of [`analyze`]): the
/// fallback of [`classify_matrix`] when the small-matrix kernel's QR
/// iteration does not converge within its bound.
fn classify_general(
    s: &DMatrix<f64>,
    certificate: &mut dyn FnMut(f64) -> Option<&'static str>,
) -> Result<Subdominant> {
    let e = Eigen::new(s, EigenOptions::BOTH)?;
    let eta = BACKWARD_ERROR_FACTOR * e.dim() as f64 * f64::EPSILON * e.frobenius_norm();
    let radii: Vec<f64> = e
        .condition_numbers()
        .unwrap_or(&[])
        .iter()
        .map(|&k| radius(k, eta))
        .collect();
    classify(
        &Evidence {
            values: e.values(),
            radii: &radii,
            eta,
        },
        &mut |lam| double_test(s, lam, certificate(lam)),
    )
}

#[cfg(test)]
mod tests {
    use crate::spectral::svd::{jacobi_svd, singular_values};
    use nalgebra::DMatrix;

    /// The 7 x 7 matrix on which faer's SVD reports no
    /// convergence: the second smallest singular value of `S - lambda I` for
    /// the adjustable scheme, n = 3, c = 0.22986, at the classifier's
    /// lambda_1. The fallback gives it; both eigenvalue copies (a standard
    /// double eigenvalue) make it tiny.
    #[test]
    fn fallback_where_faer_does_not_converge() {
        use crate::schemes::LocalScheme;
        let scheme = LocalScheme::<f64>::adjustable_cc(3, 0.22986).unwrap();
        let m = scheme.matrix().unwrap().into_matrix();
        let sub = super::classify_local(&scheme).unwrap();
        assert_eq!(sub.class, crate::spectral::SubdominantClass::Standard);
        let x = &m - DMatrix::identity(7, 7) * sub.lambda1.re;
        let s = singular_values(&x).unwrap();
        let (j, _) = jacobi_svd(&x, false).unwrap();
        assert!(s[5] < 1e-12 && j[5] < 1e-12, "{s:?} {j:?}");
    }
}
