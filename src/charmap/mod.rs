//! Characteristic maps of the Doo-Sabin family: regularity and injectivity.
//!
//! Math doc section 7. The characteristic map of a configuration is the
//! planar map whose coordinates are the subdominant eigenfunctions; its ring
//! is built from `3n` biquadratic patches ([`ring`]) whose control points are
//! the extended matrix ([`extended`]) applied to a basis of the subdominant
//! real invariant subspace:
//!
//! * `standard` (`lambda_1 = lambda_2` real, 2-D eigenspace): any basis of the
//!   eigenspace (Reif's criterion: C1 for generic data iff the map is regular
//!   and injective);
//! * `real_distinct`: `(v_1, v_2)`;
//! * `complex_pair`: `(Re v, Im v)`;
//! * `defective`, `not_separated`: no characteristic map (a 1-D eigenspace, or
//!   no pair of subdominant eigenvalues to span a plane).
//!
//! Regularity and injectivity (regular, and the boundary winds exactly once
//! around the origin once the basis is oriented so that the Jacobian is
//! positive) do not change under a linear change of the planar basis, so the
//! checks run on an orthonormal basis of the invariant subspace
//! ([`PlanarBasis::new`]), which is also what makes the error analysis simple.
//! For non-standard eigenstructures the verdict is "tangent-plane continuous
//! (non-standard: ...)", never "C1": the literature settles only the standard case.
//!
//! Submodules: [`extended`] (the `9n x 4n` matrix), [`ring`] (the `3n`
//! patches and boundary chains), [`basis`] (the subdominant invariant
//! subspace from the face block), [`regularity`] (Jacobian sign with error
//! bound and subdivision), [`winding`] (certified winding numbers), `figure`
//! (plot data). Entry points: [`check`] (one configuration, classification
//! included; the sweep entry point), [`check_classified`] (when the
//! classification is already known), [`check_basis`] / [`check_ring`] (any
//! planar basis or ring, e.g. deliberately perturbed ones), [`plot_data`].
//!
//! **Error control.** Two error sources are bounded separately: (1) the error
//! of the computed invariant subspace, bounded by Stewart's perturbation
//! theorem ([`subspace_bound`]: `4 ||E_21||_F / sep` per entry, with the
//! separation `sep(M, L_22)` computed from the smallest singular value of its
//! Kronecker form, minus that computation's own error bound); (2) all rounding
//! from the basis onwards (extended matrix, Bezier conversion, derivatives,
//! products, subdivision, evaluation), bounded with Higham's `gamma_k`
//! ([`point_error`], [`regularity::ErrorModel`]). Verdicts within these bounds
//! are `indeterminate`, never guessed. Not covered: the floating-point error
//! of the SVD that yields `sep` is taken from LAPACK-style backward stability
//! (`|Δsigma| <= c m eps ||K||`, with `c` = [`SVD_ERROR_FACTOR`]), not proven
//! for faer's implementation.
//!
//! ```
//! use subdiv_lab::charmap::{check_basis, Eigenstructure, PlanarBasis};
//! use subdiv_lab::charmap::extended::ExtendedMatrix;
//! use subdiv_lab::schemes::LocalScheme;
//! use num_complex::Complex64;
//! // n = 4, uniform: the subdominant eigenvectors are the linear functions of the grid.
//! let s = LocalScheme::<f64>::cc_variant(4).unwrap();
//! let ext = ExtendedMatrix::new(&s).unwrap();
//! let sn = s.matrix().unwrap();
//! // Greville coordinates of the 16 points (P, E, C) in the regular 4x4 grid
//! let xy: [(f64, f64); 16] = [
//!     (-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5),           // P_0..P_3
//!     (-0.5, -1.5), (0.5, -1.5), (1.5, -0.5), (1.5, 0.5),           // E_01 E_02 E_11 E_12
//!     (0.5, 1.5), (-0.5, 1.5), (-1.5, 0.5), (-1.5, -0.5),           // E_21 E_22 E_31 E_32
//!     (-1.5, -1.5), (1.5, -1.5), (1.5, 1.5), (-1.5, 1.5),           // C_0..C_3
//! ];
//! let w1: Vec<f64> = xy.iter().map(|p| p.0).collect();
//! let w2: Vec<f64> = xy.iter().map(|p| p.1).collect();
//! let lam = [Complex64::new(0.5, 0.0); 2];
//! let basis = PlanarBasis::new(sn.matrix(), Eigenstructure::Standard, lam, &w1, &w2, 0.25).unwrap();
//! let report = check_basis(&ext, &s.ratios(), &basis).unwrap();
//! assert_eq!(report.winding_number, Some(1));
//! assert_eq!(report.verdict.to_string(), "C1 (standard; Reif)");
//! ```

pub mod basis;
pub mod catmull_clark;
pub mod extended;
pub(crate) mod figure;
pub mod regularity;
pub(crate) mod report;
pub mod ring;
pub mod winding;

use crate::error::{Error, Result};
use crate::knots::EdgeRatios;
use crate::scheme::Scheme;
use crate::schemes::LocalScheme;
use crate::spectral::{Subdominant, SubdominantClass};
use extended::ExtendedMatrix;
use nalgebra::DMatrix;
use num_complex::Complex64;
use regularity::{check_regularity, gamma, Regularity, RegularityVerdict};
pub use report::{AnyPatchId, CharmapReport, Eigenstructure, Verdict};
use ring::Ring;

/// Safety factor on the first-order estimate `||S W - W M||_F / gap` of the
/// error of the computed invariant subspace, reported as
/// [`PlanarBasis::estimated_error`] next to the rigorous bound (for
/// comparison: exact for normal matrices; for non-normal ones the true
/// separation can be smaller than the eigenvalue gap, hence the factor).
pub const SUBSPACE_ERROR_SAFETY: f64 = 100.0;

/// Backward-error factor `c` of the SVD that computes the separation: the
/// computed smallest singular value of the `2m x 2m` Kronecker matrix `K` is
/// taken to be within `c (2m) eps ||K||_F` of the exact one (LAPACK's bound
/// has `c` of order 1; we allow 8).
pub const SVD_ERROR_FACTOR: f64 = 8.0;

/// Smallest accepted `sin` of the angle between the two computed basis vectors;
/// below it the vectors do not determine a plane (numerically parallel).
pub const MIN_BASIS_SINE: f64 = 1e-8;

/// An orthonormal basis `W = [w1 w2]` of the subdominant real invariant subspace
/// of `S_n`, with `M = W^T S W` (so that `S W ~ W M`) and an error estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarBasis {
    /// The eigenstructure the subspace belongs to.
    pub structure: Eigenstructure,
    /// The subdominant eigenvalues `lambda_1, lambda_2`.
    pub lambda: [Complex64; 2],
    /// First basis vector (`4n` entries, unit 2-norm).
    pub w1: Vec<f64>,
    /// Second basis vector (orthogonal to `w1`, unit 2-norm).
    pub w2: Vec<f64>,
    /// The restriction `M` (row-major 2x2): next ring = `M` applied to this ring.
    pub restriction: [[f64; 2]; 2],
    /// `||S W - W M||_F`.
    pub residual: f64,
    /// Bound on the error of every entry of `w1`, `w2` (there is an exact
    /// invariant subspace with a basis within this distance, entry-wise):
    /// Stewart's bound ([`subspace_bound`]), `+inf` when its hypothesis
    /// fails (the subspace is then not certified and every verdict built on
    /// it is `indeterminate`).
    pub vector_error: f64,
    /// The first-order estimate [`SUBSPACE_ERROR_SAFETY`] `* residual / gap`
    /// (for comparison with the bound; not used by the checks).
    pub estimated_error: f64,
    /// Lower bound on `sep(M, L_22)` (0 if none could be certified).
    pub separation: f64,
}

impl PlanarBasis {
    /// Orthonormalises two real vectors spanning the subspace (`(v1, v2)` or
    /// `(Re v, Im v)`), computes `M = W^T S W`, the residual and the error
    /// estimate. `gap` is a lower bound on the distance of `lambda_{1,2}` from
    /// the rest of the spectrum (e.g. `min(|lambda_2| - |lambda_3|, 1 - |lambda_1|)`).
    pub fn new(
        s: &DMatrix<f64>,
        structure: Eigenstructure,
        lambda: [Complex64; 2],
        a: &[f64],
        b: &[f64],
        gap: f64,
    ) -> Result<Self> {
        let dim = s.nrows();
        for v in [a, b] {
            if v.len() != dim {
                return Err(Error::CountMismatch {
                    what: "planar basis vector (4n entries)",
                    expected: dim,
                    got: v.len(),
                });
            }
        }
        let bad = |reason: String| Error::Numerical {
            routine: "characteristic map basis",
            reason,
        };
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let na = norm(a);
        if !(na > 0.0 && na.is_finite()) {
            return Err(bad(format!("first basis vector has norm {na}")));
        }
        let w1: Vec<f64> = a.iter().map(|x| x / na).collect();
        let nb = norm(b);
        if !(nb > 0.0 && nb.is_finite()) {
            return Err(bad(format!("second basis vector has norm {nb}")));
        }
        let proj: f64 = w1.iter().zip(b).map(|(x, y)| x * y).sum();
        let mut w2: Vec<f64> = b.iter().zip(&w1).map(|(y, x)| y - proj * x).collect();
        // re-orthogonalise once (classical Gram-Schmidt twice is enough)
        let proj2: f64 = w1.iter().zip(&w2).map(|(x, y)| x * y).sum();
        for (y, x) in w2.iter_mut().zip(&w1) {
            *y -= proj2 * x;
        }
        let n2 = norm(&w2);
        if n2.is_nan() || n2 <= MIN_BASIS_SINE * nb {
            return Err(bad(format!(
                "the two subdominant vectors are numerically parallel (sin angle = {:e})",
                n2 / nb
            )));
        }
        for y in w2.iter_mut() {
            *y /= n2;
        }
        let sw1: Vec<f64> = (0..dim)
            .map(|i| (0..dim).map(|j| s[(i, j)] * w1[j]).sum())
            .collect();
        let sw2: Vec<f64> = (0..dim)
            .map(|i| (0..dim).map(|j| s[(i, j)] * w2[j]).sum())
            .collect();
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
        let m = [
            [dot(&w1, &sw1), dot(&w1, &sw2)],
            [dot(&w2, &sw1), dot(&w2, &sw2)],
        ];
        let mut res2 = 0.0;
        for i in 0..dim {
            let r1 = sw1[i] - (w1[i] * m[0][0] + w2[i] * m[1][0]);
            let r2 = sw2[i] - (w1[i] * m[0][1] + w2[i] * m[1][1]);
            res2 += r1 * r1 + r2 * r2;
        }
        let residual = res2.sqrt();
        if gap.is_nan() || gap <= 0.0 {
            return Err(bad(format!(
                "no spectral gap around the subdominant pair (gap = {gap})"
            )));
        }
        // the residual is itself computed in floating point: add its rounding floor
        let floor = gamma(2 * dim) * frob(s);
        let estimated_error = SUBSPACE_ERROR_SAFETY * (residual + floor) / gap;
        let (vector_error, separation) = subspace_bound(s, &w1, &w2)?;
        Ok(Self {
            structure,
            lambda,
            w1,
            w2,
            restriction: m,
            residual,
            vector_error,
            estimated_error,
            separation,
        })
    }
}

/// Rigorous (up to [`SVD_ERROR_FACTOR`]) entry-wise error bound of an
/// orthonormal basis `W = [w1 w2]` of an approximate invariant subspace of
/// `S`, and the certified separation **\[derived\]** from Stewart's theorem
/// (G. W. Stewart, SIAM Review 15, 1973; Golub and Van Loan, *Matrix
/// Computations*, 3rd ed., Theorem 7.2.4):
///
/// With `Q = [W W_perp]` orthogonal (QR of `W`), `Q^T S Q = T + E` where
/// `T = [[M, T_12], [0, L_22]]` has the exactly invariant subspace
/// `span(e_1, e_2)` and `E = [[0, 0], [E_21, 0]]`. If
/// `sep = sep(M, L_22) = sigma_min(I ⊗ M - L_22^T ⊗ I) > 0` and
/// `||E||_2 (1 + 5 ||T_12||_2 / sep) <= sep / 5`, then `S` has an invariant
/// subspace spanned by `W + W_perp P` with `||P||_2 <= 4 ||E_21||_2 / sep`;
/// every entry of `W_perp P e_j` is at most `||P||_2`. We use Frobenius norms
/// (upper bounds of the 2-norms), add the rounding of `Q^T S Q`
/// (`gamma_{4 dim} ||S||_F`) to `||E_21||` and `||T_12||`, and subtract the
/// SVD's error from `sigma_min`. Returns `(bound, sep_lower)`; the bound is
/// `+inf` when the hypothesis fails.
///
/// Cost: one `dim x dim` QR and product, and the singular values of a
/// `2 (dim - 2)` square matrix.
pub fn subspace_bound(s: &DMatrix<f64>, w1: &[f64], w2: &[f64]) -> Result<(f64, f64)> {
    let dim = s.nrows();
    if dim < 3 {
        return Ok((0.0, f64::INFINITY));
    }
    let wmat = faer::Mat::<f64>::from_fn(dim, 2, |i, j| if j == 0 { w1[i] } else { w2[i] });
    let q = wmat.qr().compute_Q();
    let sm = faer::Mat::<f64>::from_fn(dim, dim, |i, j| s[(i, j)]);
    let t = q.transpose() * &sm * &q;
    let m = dim - 2;
    let fro = |rows: std::ops::Range<usize>, cols: std::ops::Range<usize>| {
        let mut acc = 0.0;
        for i in rows {
            for j in cols.clone() {
                acc += t[(i, j)] * t[(i, j)];
            }
        }
        acc.sqrt()
    };
    let round = gamma(4 * dim) * frob(s);
    let e21 = fro(2..dim, 0..2) + round;
    let t12 = fro(0..2, 2..dim) + round;
    // K = I_m ⊗ M - L22^T ⊗ I_2 on vec(X), X 2 x m (column-major: X[a][i] at a + 2 i)
    let k = faer::Mat::<f64>::from_fn(2 * m, 2 * m, |r, c| {
        let (a, i) = (r % 2, r / 2);
        let (b, j) = (c % 2, c / 2);
        let mut v = 0.0;
        if i == j {
            v += t[(a, b)];
        }
        if a == b {
            v -= t[(2 + j, 2 + i)];
        }
        v
    });
    let mut kf = 0.0;
    for c in 0..2 * m {
        for r in 0..2 * m {
            kf += k[(r, c)] * k[(r, c)];
        }
    }
    let kf = kf.sqrt();
    let sv = match k.singular_values() {
        Ok(sv) => sv,
        // fallback route: the one-sided Jacobi SVD (same error model)
        Err(_) => {
            let kd = DMatrix::from_fn(2 * m, 2 * m, |r, c| k[(r, c)]);
            crate::spectral::svd::jacobi_svd(&kd, false)
                .map_err(|_| Error::Numerical {
                    routine: "subspace separation (SVD)",
                    reason: format!("no convergence for a {0} x {0} Kronecker matrix", 2 * m),
                })?
                .0
        }
    };
    let smin = sv.last().copied().unwrap_or(0.0);
    // sep of the exact T: the computed K is off by the rounding of Q^T S Q too
    let sep = smin - SVD_ERROR_FACTOR * (2 * m) as f64 * f64::EPSILON * kf - 2.0 * round;
    if sep.is_nan() || sep <= 0.0 || !sep.is_finite() {
        return Ok((f64::INFINITY, 0.0));
    }
    if e21 * (1.0 + 5.0 * t12 / sep) > sep / 5.0 {
        return Ok((f64::INFINITY, sep));
    }
    Ok((4.0 * e21 / sep, sep))
}

fn frob(s: &DMatrix<f64>) -> f64 {
    s.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Error bound of the ring's Bezier control points for a basis with entry
/// error `vector_error` **\[derived\]**: `Ext` has absolute row sums `rho`, so the
/// `9n` points are off by at most `rho vector_error + gamma_K rho max|w|`
/// (`K` = nonzeros per row + 1); the B-spline-to-Bezier conversion forms convex
/// combinations of at most 4 points (`+ gamma_8 max|P|`).
pub fn point_error(ext: &ExtendedMatrix<f64>, basis: &PlanarBasis) -> f64 {
    let (e, pmax) = propagated_error(ext.matrix().matrix(), basis);
    e + gamma(8) * pmax
}

/// The error of `m * [w1 w2]` for a basis with entry error `vector_error`,
/// and a bound on its entries: `m` has absolute row sums `rho` and at most
/// `K - 1` nonzeros per row, so each entry is off by at most
/// `rho vector_error + gamma_K rho max|w|`. Returns `(error, rho max|w|)`.
pub(crate) fn propagated_error(m: &DMatrix<f64>, basis: &PlanarBasis) -> (f64, f64) {
    let mut rho = 0.0f64;
    let mut nnz = 0usize;
    for i in 0..m.nrows() {
        let row = m.row(i);
        rho = rho.max(row.iter().map(|x| x.abs()).sum());
        nnz = nnz.max(row.iter().filter(|x| **x != 0.0).count());
    }
    let wmax = basis
        .w1
        .iter()
        .chain(&basis.w2)
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let pmax = rho * wmax;
    (rho * basis.vector_error + gamma(nnz + 1) * pmax, pmax)
}

/// Runs the regularity and winding checks for a planar basis of `S_n`'s
/// subdominant subspace (the geometric part of [`check`]-style entry points).
pub fn check_basis(
    ext: &ExtendedMatrix<f64>,
    ratios: &EdgeRatios<f64>,
    basis: &PlanarBasis,
) -> Result<CharmapReport> {
    let ring = Ring::from_basis(ext, ratios, &basis.w1, &basis.w2)?;
    let delta = point_error(ext, basis);
    Ok(check_ring(&ring, delta, basis.structure))
}

/// Regularity, winding numbers and verdict of a ring whose control points are
/// accurate to `delta` (absolute).
pub fn check_ring(ring: &Ring, delta: f64, structure: Eigenstructure) -> CharmapReport {
    let reg = check_regularity(ring, delta);
    let oriented;
    let r = if reg.orientation < 0 {
        oriented = ring.mirrored();
        &oriented
    } else {
        ring
    };
    let winding = winding::winding_number(&r.outer_boundary(), delta);
    let inner = winding::winding_number(&r.inner_boundary(), delta);
    assemble_report(reg, winding, inner, delta, structure)
}

/// The verdict from a regularity result and the certified winding numbers
/// (shared by both scheme families).
pub(crate) fn assemble_report<P>(
    reg: Regularity<P>,
    winding: Option<i64>,
    inner: Option<i64>,
    delta: f64,
    structure: Eigenstructure,
) -> CharmapReport<P> {
    let verdict = match (reg.verdict, winding) {
        _ if !delta.is_finite() => Verdict::Indeterminate {
            reason: "the subdominant invariant subspace is not certified (Stewart's \
                     separation hypothesis fails: eigenvalues too close for the residual)"
                .to_owned(),
        },
        (RegularityVerdict::NotRegular, _) => Verdict::NotRegular,
        (RegularityVerdict::Indeterminate, _) => Verdict::Indeterminate {
            reason: format!(
                "Jacobian sign not certified (min coefficient {:.3e}, error bound {:.3e}, relative)",
                reg.min_coeff, reg.relative_error_bound
            ),
        },
        (RegularityVerdict::Regular, None) => Verdict::Indeterminate {
            reason: "winding number not certified (boundary within rounding of the origin)"
                .to_owned(),
        },
        (RegularityVerdict::Regular, Some(1)) => match structure {
            Eigenstructure::Standard => Verdict::C1Standard,
            s => Verdict::TangentPlaneContinuous { structure: s },
        },
        (RegularityVerdict::Regular, Some(w)) => Verdict::NotInjective { winding: w },
    };
    CharmapReport {
        structure: Some(structure),
        regularity: Some(reg),
        winding_number: winding,
        inner_winding_number: inner,
        point_error: delta,
        verdict,
    }
}

/// Why a class has no characteristic map, or `None` if it has one.
fn structure_of(class: &SubdominantClass) -> std::result::Result<Eigenstructure, (String, String)> {
    match class {
        SubdominantClass::Standard => Ok(Eigenstructure::Standard),
        SubdominantClass::RealDistinct => Ok(Eigenstructure::RealDistinct),
        SubdominantClass::ComplexPair => Ok(Eigenstructure::ComplexPair),
        SubdominantClass::Defective => Err((
            "defective".to_owned(),
            "lambda_1 = lambda_2 has a 1-dimensional eigenspace, so the subdominant \
             eigenvectors span a line, not a plane; the generic limit surface has no \
             regular tangent plane parametrisation from them"
                .to_owned(),
        )),
        SubdominantClass::NotSeparated => Err((
            "not_separated".to_owned(),
            "|lambda_2| = |lambda_3| (or lambda_0 is not a simple 1): no 2-dimensional \
             dominant invariant subspace determines the local shape"
                .to_owned(),
        )),
        SubdominantClass::Indeterminate { between, reason } => Err((
            "indeterminate".to_owned(),
            format!(
                "the eigenstructure is undecided between {} and {} ({reason}), so the planar \
                 basis and the verdict's label are not determined",
                between.0.as_str(),
                between.1.as_str()
            ),
        )),
    }
}

/// The characteristic-map check of one configuration of any [`Scheme`], given
/// its subdominant classification (from [`crate::spectral`]): the scheme's
/// own ring ([`Scheme::characteristic_map`]), or `no_charmap` when the scheme
/// provides none.
///
/// Built-in schemes: the Doo-Sabin family's biquadratic ring
/// ([`check_classified_doo_sabin`]), or for Catmull-Clark and the adjustable
/// scheme the ring of [`catmull_clark`] (bicubic Bezier certificate at
/// `c = 1/2`, cone certificate otherwise).
pub fn check_classified<S: Scheme + ?Sized>(
    scheme: &S,
    sub: &Subdominant,
) -> Result<CharmapReport<AnyPatchId>> {
    match scheme.characteristic_map(sub) {
        Some(r) => r,
        None => Ok(CharmapReport::no_map(
            sub.class.name(),
            &format!("scheme {} provides no characteristic ring", scheme.name()),
        )),
    }
}

/// The Doo-Sabin family's check (the `9n`-point extended configuration and
/// its `3n` biquadratic ring patches).
///
/// Cost: the `n x n` face block (a product and an SVD), `O(n)` small solves,
/// the `9n x 4n` extended matrix and `3n` Jacobian patches; no `4n x 4n`
/// eigen-decomposition.
pub fn check_classified_doo_sabin(
    scheme: &LocalScheme<f64>,
    sub: &Subdominant,
) -> Result<CharmapReport<AnyPatchId>> {
    let r = match prepare(scheme, sub)? {
        Prepared::NoMap(r) => r,
        Prepared::Basis(ext, basis) => check_basis(&ext, &scheme.ratios(), &basis)?,
    };
    Ok(r.map_patches(AnyPatchId::DooSabin))
}

enum Prepared {
    NoMap(CharmapReport),
    Basis(ExtendedMatrix<f64>, PlanarBasis),
}

fn prepare(scheme: &LocalScheme<f64>, sub: &Subdominant) -> Result<Prepared> {
    let structure = match structure_of(&sub.class) {
        Ok(s) => s,
        Err((class, reason)) => return Ok(Prepared::NoMap(CharmapReport::no_map(&class, &reason))),
    };
    let ext = ExtendedMatrix::new(scheme)?;
    let sn = scheme.matrix()?.into_matrix();
    let gap = sub.gap.min(1.0 - sub.lambda1.norm());
    let basis = basis::subdominant_basis(scheme, &sn, structure, [sub.lambda1, sub.lambda2], gap)?;
    Ok(Prepared::Basis(ext, basis))
}

/// The characteristic-map check of one configuration: classification by the
/// spectral engine's structured fast path ([`crate::spectral::classify_scheme`]),
/// then [`check_classified`]. This is the entry point for sweeps (one call per
/// configuration, no shared state, safe to run in parallel).
///
/// ```
/// use subdiv_lab::charmap::{check, Verdict};
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::LocalScheme;
/// let r = check(&LocalScheme::<f64>::doo_sabin(5).unwrap()).unwrap();
/// assert_eq!(r.verdict, Verdict::C1Standard);
/// let r = check(&LocalScheme::nurds(EdgeRatios::new(vec![0.1, 0.8, 0.3]).unwrap())).unwrap();
/// assert_ne!(r.verdict, Verdict::C1Standard); // non-standard: never "C1"
/// ```
pub fn check<S: Scheme + ?Sized>(scheme: &S) -> Result<CharmapReport<AnyPatchId>> {
    let sub = crate::spectral::classify_local(scheme)?;
    check_classified(scheme, &sub)
}

/// The plot data of a configuration's ring and `levels - 1` further levels
/// (see `figure::ring_plot`), with the report of the check; `None` for the
/// plot when there is no characteristic map ([`Scheme::characteristic_plot`]).
pub fn plot_data<S: Scheme + ?Sized>(
    scheme: &S,
    levels: usize,
    per_side: usize,
) -> Result<(CharmapReport<AnyPatchId>, Option<figure::RingPlot>)> {
    let sub = crate::spectral::classify_local(scheme)?;
    match scheme.characteristic_plot(&sub, levels, per_side) {
        Some(r) => r,
        None => Ok((check_classified(scheme, &sub)?, None)),
    }
}

/// [`plot_data`] of the Doo-Sabin family given its classification.
pub fn plot_data_doo_sabin(
    scheme: &LocalScheme<f64>,
    sub: &Subdominant,
    levels: usize,
    per_side: usize,
) -> Result<(CharmapReport<AnyPatchId>, Option<figure::RingPlot>)> {
    let (ext, basis) = match prepare(scheme, sub)? {
        Prepared::NoMap(r) => return Ok((r.map_patches(AnyPatchId::DooSabin), None)),
        Prepared::Basis(e, b) => (e, b),
    };
    let structure = basis.structure;
    let ring = Ring::from_basis(&ext, &scheme.ratios(), &basis.w1, &basis.w2)?;
    let report = check_ring(&ring, point_error(&ext, &basis), structure);
    let orientation = report.regularity.as_ref().map_or(1, |r| r.orientation);
    let plot = figure::ring_plot(&ring, basis.restriction, orientation, levels, per_side);
    Ok((report.map_patches(AnyPatchId::DooSabin), Some(plot)))
}
