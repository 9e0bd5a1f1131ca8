//! General eigen-decomposition of a real square matrix (math doc sections 4, 7).
//!
//! [`Eigen::new`] computes all eigenvalues of any square `DMatrix<f64>` with
//! faer (Hessenberg reduction + multishift QR, LAPACK style, bounded
//! iterations), optionally right eigenvectors `S v = lambda v` and left
//! eigenvectors `u^H S = lambda u^H`, and from them
//!
//! * residuals `||S v - lambda v||_2` (and `||u^H S - lambda u^H||_2`) with
//!   `||v|| = ||u|| = 1`;
//! * eigenvalue condition numbers `kappa = ||u|| ||v|| / |u^H v|` (Wilkinson):
//!   a perturbation `E` moves a simple eigenvalue by at most
//!   `kappa ||E|| + O(||E||^2)`.
//!
//! Eigenvalues are sorted by non-increasing modulus; ties (equal moduli, e.g.
//! conjugate pairs) are broken by larger real part first, then larger imaginary
//! part first, which is deterministic (a total order on `f64` triples).
//!
//! faer reports non-convergence of its QR iteration only through non-finite
//! input; it does not surface the LAPACK `info` flag. This module therefore
//! checks the result independently: the eigenvalues must be finite and sum to
//! the trace to within [`TRACE_CHECK_FACTOR`] `* dim * eps * ||S||_F`, and
//! every residual (when vectors are computed, after refinement of poor ones
//! by inverse iteration) must be below [`RESIDUAL_FAIL_FACTOR`]
//! `* sqrt(dim * eps) * ||S||_F`; otherwise an error is returned instead of
//! wrong numbers.
//!
//! Residuals are small (`~ dim eps ||S||`) for simple and semisimple
//! eigenvalues, but only `O(sqrt(eps))` at defective ones. **\[derived\]** For
//! NURDS with even `n` the face block always has the eigenvalue 1/4 (the
//! alternating vector `(-1)^j` is a left null vector of `R`), which collides
//! with the 1/4 of the E blocks; `S_n` then generally has a Jordan block at 1/4.

use super::SpectralError;
use faer::diag::Diag;
use faer::linalg::evd::{evd_real, evd_scratch, ComputeEigenvectors};
use faer::{Mat, Par};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Bound on `|sum(lambda) - trace| / (dim eps ||S||_F)` for a converged decomposition.
///
/// The QR algorithm is backward stable with a backward error of a small
/// multiple of `dim eps ||S||_F`; the trace of the computed Schur form differs
/// from the trace of `S` by at most `dim` such errors. A factor 1e4 leaves
/// room for the constants while a non-converged (wrong) block, whose
/// eigenvalues are off by `O(||S||)`, is still caught.
pub const TRACE_CHECK_FACTOR: f64 = 1e4;

/// Residuals above `RESIDUAL_REFINE_FACTOR * dim * eps * ||S||_F` trigger two
/// steps of inverse iteration on `S - lambda I` for that eigenvector. faer's
/// back-substitution in the Schur form loses accuracy at (nearly) multiple
/// eigenvalues; inverse iteration restores residuals of the order of the
/// eigenvalue error (`eps` for semisimple, `sqrt(eps)` for defective ones).
pub const RESIDUAL_REFINE_FACTOR: f64 = 100.0;

/// Eigenvalues closer than `REFINE_CLUSTER * ||S||_F` share one LU
/// factorisation during refinement (inverse iteration converges to the
/// cluster's invariant subspace from each vector's own starting point).
pub const REFINE_CLUSTER: f64 = 1e-6;

/// A residual above `RESIDUAL_FAIL_FACTOR * sqrt(dim * eps) * ||S||_F` after
/// refinement means the decomposition is wrong, not merely inaccurate: even a
/// defective eigenvalue (error `O(sqrt(eps))`) stays far below it, while a
/// non-converged QR block leaves `O(||S||)` residuals.
pub const RESIDUAL_FAIL_FACTOR: f64 = 1e3;

/// Two computed eigenvalues closer than `PAIR_CLUSTER * max(1, ||S||_F)` are
/// treated as one double eigenvalue by the decomposition's pair check
/// (`pair_conditions`). A semisimple double eigenvalue is computed to
/// `O(kappa eps ||S||)`, far below this; a defective one splits by
/// `O(sqrt(eps ||S||))` (about 1e-8), also below it, and is then caught by
/// the ill-conditioning of `Y^H X` instead.
pub const PAIR_CLUSTER: f64 = 1e-6;

/// Condition numbers of double eigenvalues from the pair's spectral projector
/// **\[derived\]**. At a double eigenvalue the computed left and right vectors
/// of each copy are arbitrary members of the 2-D eigenspaces, so the
/// individual `1 / |u_k^H v_k|` can be huge (even infinite) although the
/// eigenvalue is perfectly conditioned. For a semisimple double eigenvalue
/// with right basis `X = [v_i v_j]` and left basis `Y = [u_i u_j]` (unit
/// columns), first-order perturbation theory (Stewart and Sun, *Matrix
/// Perturbation Theory*, IV.2) moves both copies by at most
/// `||P|| ||E||`, `P = X (Y^H X)^{-1} Y^H`, and
/// `||P||_2 <= ||X||_2 ||Y||_2 / sigma_min(Y^H X) <= 2 / sigma_min(Y^H X)`.
/// Each copy's condition number becomes the smaller of the two bounds (both
/// are valid); a defective pair has `sigma_min(Y^H X) ~ 0` and keeps a huge
/// value. Clusters of three or more are left alone.
fn pair_conditions(
    values: &[Complex64],
    v: &DMatrix<Complex64>,
    u: &DMatrix<Complex64>,
    frobenius: f64,
    kappa: &mut [f64],
) {
    let n = values.len();
    let tol = PAIR_CLUSTER * frobenius.max(1.0);
    for i in 0..n {
        let near: Vec<usize> = (0..n)
            .filter(|&j| j != i && (values[j] - values[i]).norm() <= tol)
            .collect();
        if near.len() != 1 {
            continue;
        }
        let j = near[0];
        // G = Y^H X (2 x 2), sigma_min from the eigenvalues of G^H G
        let g = [
            [
                u.column(i).dotc(&v.column(i)),
                u.column(i).dotc(&v.column(j)),
            ],
            [
                u.column(j).dotc(&v.column(i)),
                u.column(j).dotc(&v.column(j)),
            ],
        ];
        let fro2: f64 = g.iter().flatten().map(|z| z.norm_sqr()).sum();
        let det = (g[0][0] * g[1][1] - g[0][1] * g[1][0]).norm();
        // sigma_min^2 = (fro2 - sqrt(fro2^2 - 4 det^2)) / 2, computed stably
        let disc = (fro2 * fro2 - 4.0 * det * det).max(0.0).sqrt();
        let smax2 = 0.5 * (fro2 + disc);
        let smin = if smax2 > 0.0 { det / smax2.sqrt() } else { 0.0 };
        if smin > 0.0 {
            let cluster = (2.0 / smin).max(1.0);
            kappa[i] = kappa[i].min(cluster);
        }
    }
}

/// Which eigenvectors to compute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EigenOptions {
    /// Right eigenvectors `S v = lambda v`.
    pub right: bool,
    /// Left eigenvectors `u^H S = lambda u^H`.
    pub left: bool,
}

impl EigenOptions {
    /// Eigenvalues only.
    pub const VALUES: Self = Self {
        right: false,
        left: false,
    };
    /// Right and left vectors (needed for condition numbers).
    pub const BOTH: Self = Self {
        right: true,
        left: true,
    };
}

/// Eigenvalues (sorted by non-increasing modulus) and optional vectors of a
/// real square matrix.
///
/// ```
/// use nalgebra::DMatrix;
/// use subdiv_lab::spectral::eigen::{Eigen, EigenOptions};
/// let s = DMatrix::from_row_slice(2, 2, &[0.5, 0.5, 0.25, 0.75]);
/// let e = Eigen::new(&s, EigenOptions::BOTH).unwrap();
/// assert!((e.values()[0].re - 1.0).abs() < 1e-14);
/// assert!((e.values()[1].re - 0.25).abs() < 1e-14);
/// assert!(e.residuals().unwrap().iter().all(|&r| r < 1e-14));
/// assert!(e.condition_numbers().unwrap().iter().all(|&k| k >= 1.0));
/// ```
#[derive(Clone, Debug)]
pub struct Eigen {
    values: Vec<Complex64>,
    right: Option<DMatrix<Complex64>>,
    left: Option<DMatrix<Complex64>>,
    residuals: Option<Vec<f64>>,
    left_residuals: Option<Vec<f64>>,
    conditions: Option<Vec<f64>>,
    frobenius: f64,
}
pub use crate::schemes::spectral_order;

/// Two steps of inverse iteration for every column whose residual exceeds
/// `trigger` (columns are eigenvectors of `m` for `values`).
fn refine(
    m: &DMatrix<Complex64>,
    values: &[Complex64],
    vecs: &mut DMatrix<Complex64>,
    res: &mut [f64],
    trigger: f64,
) {
    let n = m.nrows();
    let norm = m.norm().max(f64::MIN_POSITIVE);
    // One factorisation per cluster: eigenvalues within REFINE_CLUSTER * ||S||
    // of the cached shift reuse its LU (a multiple eigenvalue such as the 1/4
    // of the Doo-Sabin family would otherwise cost one O(dim^3) LU per copy).
    let mut cache: Option<(
        Complex64,
        nalgebra::linalg::LU<Complex64, nalgebra::Dyn, nalgebra::Dyn>,
    )> = None;
    for k in 0..n {
        if res[k] <= trigger {
            continue;
        }
        let reuse =
            matches!(&cache, Some((c, _)) if (c - values[k]).norm() <= REFINE_CLUSTER * norm);
        if !reuse {
            // Shift slightly off the eigenvalue so the LU is not exactly singular.
            let lambda = values[k] + Complex64::new(norm * 1e-14, 0.0);
            let mut a = m.clone();
            for i in 0..n {
                a[(i, i)] -= lambda;
            }
            cache = Some((values[k], a.lu()));
        }
        let Some((_, lu)) = &cache else { continue };
        let mut x = vecs.column(k).into_owned();
        // faer can return non-finite vectors at exactly repeated eigenvalues
        // (e.g. the adjustable Catmull-Clark scheme at c = 0, where 1/2 and
        // 1/4 have multiplicity n): restart from a deterministic generic
        // vector, different for each k.
        if x.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) || x.norm() == 0.0 {
            x = nalgebra::DVector::from_fn(n, |i, _| {
                let t = ((i + 1) * (k + 2)) as f64 * 0.618_033_988_749_895;
                Complex64::new(0.5 + (t - t.floor()), 0.0)
            });
        }
        let mut ok = true;
        for _ in 0..2 {
            match lu.solve(&x) {
                Some(y) => {
                    let s = y.norm();
                    if !(s.is_finite() && s > 0.0) {
                        ok = false;
                        break;
                    }
                    x = y / Complex64::new(s, 0.0);
                }
                None => {
                    ok = false;
                    break;
                }
            }
        }
        if !ok {
            continue;
        }
        let r = (m * &x - &x * values[k]).norm();
        if r < res[k] || res[k].is_nan() {
            res[k] = r;
            vecs.set_column(k, &x);
        }
    }
}

impl Eigen {
    /// Decomposes `s` (square, finite entries).
    pub fn new(s: &DMatrix<f64>, options: EigenOptions) -> Result<Self, SpectralError> {
        let (n, m) = s.shape();
        if n != m {
            return Err(SpectralError::NotSquare { rows: n, cols: m });
        }
        for j in 0..n {
            for i in 0..n {
                if !s[(i, j)].is_finite() {
                    return Err(SpectralError::NonFinite { row: i, col: j });
                }
            }
        }
        let frobenius = s.norm();
        let a = Mat::<f64>::from_fn(n, n, |i, j| s[(i, j)]);
        let mut s_re = Diag::<f64>::zeros(n);
        let mut s_im = Diag::<f64>::zeros(n);
        let want = |b: bool| {
            if b {
                ComputeEigenvectors::Yes
            } else {
                ComputeEigenvectors::No
            }
        };
        let mut ul = if options.left {
            Some(Mat::<f64>::zeros(n, n))
        } else {
            None
        };
        let mut ur = if options.right {
            Some(Mat::<f64>::zeros(n, n))
        } else {
            None
        };
        let par = Par::Seq;
        let scratch = evd_scratch::<f64>(
            n,
            want(options.left),
            want(options.right),
            par,
            Default::default(),
        );
        let mut mem = faer::dyn_stack::MemBuffer::new(scratch);
        let stack = faer::dyn_stack::MemStack::new(&mut mem);
        evd_real(
            a.as_ref(),
            s_re.as_mut(),
            s_im.as_mut(),
            ul.as_mut().map(|m| m.as_mut()),
            ur.as_mut().map(|m| m.as_mut()),
            par,
            stack,
            Default::default(),
        )
        .map_err(|_| SpectralError::NoConvergence {
            routine: "faer eigendecomposition",
            size: n,
            sweeps: 0,
        })?;
        let re: Vec<f64> = (0..n).map(|i| s_re[i]).collect();
        let im: Vec<f64> = (0..n).map(|i| s_im[i]).collect();
        let raw: Vec<Complex64> = re
            .iter()
            .zip(&im)
            .map(|(&r, &i)| Complex64::new(r, i))
            .collect();
        // Independent convergence check: finite, and the trace is reproduced.
        let trace: f64 = (0..n).map(|i| s[(i, i)]).sum();
        let sum: Complex64 = raw.iter().sum();
        let scale = (n.max(1) as f64) * f64::EPSILON * frobenius.max(f64::MIN_POSITIVE);
        if raw.iter().any(|z| !z.re.is_finite() || !z.im.is_finite())
            || (sum - trace).norm() > TRACE_CHECK_FACTOR * scale
        {
            return Err(SpectralError::NoConvergence {
                routine: "faer eigendecomposition (trace check)",
                size: n,
                sweeps: 0,
            });
        }
        // Complex vectors from the real storage (pairs: columns j, j+1 hold
        // Re and Im of the vector of re + i im with im > 0).
        let to_complex = |u: &Mat<f64>| -> DMatrix<Complex64> {
            let mut out = DMatrix::<Complex64>::zeros(n, n);
            let mut j = 0;
            while j < n {
                if im[j] == 0.0 || j + 1 == n {
                    for i in 0..n {
                        out[(i, j)] = Complex64::new(u[(i, j)], 0.0);
                    }
                    j += 1;
                } else {
                    for i in 0..n {
                        out[(i, j)] = Complex64::new(u[(i, j)], u[(i, j + 1)]);
                        out[(i, j + 1)] = Complex64::new(u[(i, j)], -u[(i, j + 1)]);
                    }
                    j += 2;
                }
            }
            out
        };
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| spectral_order(&raw[a], &raw[b]).then(a.cmp(&b)));
        let values: Vec<Complex64> = order.iter().map(|&k| raw[k]).collect();
        let permute = |m: DMatrix<Complex64>| -> DMatrix<Complex64> {
            let mut out = DMatrix::<Complex64>::zeros(n, n);
            for (new, &old) in order.iter().enumerate() {
                let mut col = m.column(old).into_owned();
                let norm = col.norm();
                if norm > 0.0 {
                    col /= Complex64::new(norm, 0.0);
                }
                out.set_column(new, &col);
            }
            out
        };
        let right = ur.as_ref().map(|u| permute(to_complex(u)));
        let left = ul.as_ref().map(|u| permute(to_complex(u)));
        let sc = s.map(|x| Complex64::new(x, 0.0));
        // A residual only means something for a unit vector: faer can return
        // zero columns at exactly repeated eigenvalues (residual 0!), which
        // must go to refinement, not pass as eigenvectors.
        let unit = |norm: f64, r: f64| {
            if (norm - 1.0).abs() <= 1e-6 {
                r
            } else {
                f64::INFINITY
            }
        };
        let residuals = right.as_ref().map(|v| {
            (0..n)
                .map(|k| {
                    let col = v.column(k);
                    unit(col.norm(), (&sc * col - col * values[k]).norm())
                })
                .collect::<Vec<f64>>()
        });
        let left_residuals = left.as_ref().map(|u| {
            (0..n)
                .map(|k| {
                    let col = u.column(k);
                    // u^H S - lambda u^H  <=>  S^T conj(u) - lambda conj(u)
                    let cu = col.map(|z| z.conj());
                    unit(col.norm(), (sc.transpose() * &cu - cu * values[k]).norm())
                })
                .collect::<Vec<f64>>()
        });
        // Refine poor pairs (faer's back-substitution loses accuracy at
        // multiple / defective eigenvalues) by inverse iteration on S itself.
        let refine_at = RESIDUAL_REFINE_FACTOR * scale;
        let mut right = right;
        let mut left = left;
        let mut residuals = residuals;
        let mut left_residuals = left_residuals;
        if let (Some(v), Some(res)) = (right.as_mut(), residuals.as_mut()) {
            refine(&sc, &values, v, res, refine_at);
        }
        if let (Some(u), Some(res)) = (left.as_mut(), left_residuals.as_mut()) {
            let st = sc.transpose();
            let conj: Vec<Complex64> = values.iter().map(|z| z.conj()).collect();
            refine(&st, &conj, u, res, refine_at);
        }
        let fail_at = RESIDUAL_FAIL_FACTOR * (n.max(1) as f64 * f64::EPSILON).sqrt() * frobenius;
        for res in [&residuals, &left_residuals].into_iter().flatten() {
            if let Some((k, r)) = res
                .iter()
                .enumerate()
                .find(|&(_, &r)| r.is_nan() || r > fail_at)
            {
                return Err(SpectralError::ResidualTooLarge {
                    index: k,
                    residual: *r,
                    bound: fail_at,
                });
            }
        }
        let conditions = match (&right, &left) {
            (Some(v), Some(u)) => {
                let mut kappa: Vec<f64> = (0..n)
                    .map(|k| {
                        let d = u.column(k).dotc(&v.column(k)).norm();
                        if d > 0.0 {
                            (1.0 / d).max(1.0)
                        } else {
                            f64::INFINITY
                        }
                    })
                    .collect();
                pair_conditions(&values, v, u, frobenius, &mut kappa);
                Some(kappa)
            }
            _ => None,
        };
        Ok(Self {
            values,
            right,
            left,
            residuals,
            left_residuals,
            conditions,
            frobenius,
        })
    }

    /// Eigenvalues, sorted by non-increasing modulus (see [`spectral_order`]).
    pub fn values(&self) -> &[Complex64] {
        &self.values
    }
    /// Unit right eigenvectors (column `k` belongs to `values()[k]`), if computed.
    pub fn right(&self) -> Option<&DMatrix<Complex64>> {
        self.right.as_ref()
    }
    /// Unit left eigenvectors `u^H S = lambda u^H` (column `k`), if computed.
    pub fn left(&self) -> Option<&DMatrix<Complex64>> {
        self.left.as_ref()
    }
    /// `||S v_k - lambda_k v_k||_2` for unit `v_k`, if right vectors were computed.
    pub fn residuals(&self) -> Option<&[f64]> {
        self.residuals.as_deref()
    }
    /// `||u_k^H S - lambda_k u_k^H||_2` for unit `u_k`, if left vectors were computed.
    pub fn left_residuals(&self) -> Option<&[f64]> {
        self.left_residuals.as_deref()
    }
    /// Condition numbers `1 / |u_k^H v_k|` (unit vectors), if both sides were computed.
    pub fn condition_numbers(&self) -> Option<&[f64]> {
        self.conditions.as_deref()
    }
    /// Frobenius norm of the decomposed matrix.
    pub fn frobenius_norm(&self) -> f64 {
        self.frobenius
    }
    /// Dimension.
    pub fn dim(&self) -> usize {
        self.values.len()
    }
}
