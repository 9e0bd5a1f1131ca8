//! The linear constraints of the cap (G0, G1, G2 across the internal edges;
//! the outer control points fixed by the C2 join) and the constrained least
//! squares that fixes the free control points (math doc sections 14.3-14.5).

use super::bernstein::{deriv_weights, extended_net, Net, DEGREE};
use super::ring::RefinedRing;
use super::G2CapError;
use nalgebra::DMatrix;

/// Free control points per patch: `p_jk` with `j, k < FREE`.
pub const FREE: usize = 5;

/// Relative rank threshold of the constraint matrix (rows scaled to unit
/// absolute sum): singular values below `RANK_RTOL * sigma_max` count as
/// zero. The matrix is rank-deficient by design (the conditions near the
/// outer corners hold automatically, and several vertex conditions repeat),
/// so a threshold is needed; the spurious singular values are rounding
/// (`~1e-15 sigma_max`), the genuine ones measure above `1e-4 sigma_max`.
/// A wrong rank decision would show as a constraint residual
/// above [`super::CONSTRAINT_RTOL`] or a geometric residual above
/// [`super::RESIDUAL_TOL`], both checked after the solve.
pub const RANK_RTOL: f64 = 1e-10;

/// Steps of iterative refinement of the constraints after the solve (two
/// bring the constraint residual to rounding level in every case measured).
pub const REFINEMENT_STEPS: usize = 2;

/// The coefficient `b(t)` of the transition map along an internal edge
/// **\[derived\]**:
///
/// ```text
/// b(t) = 2 c_n (1 - t)^3            (n != 3)
/// b(t) = 2 c_n (1 - t)^3 (1 + 3 t)  (n = 3),   c_n = cos(2 pi / n)
/// ```
///
/// `b(0) = 2 c_n` (the paper's value at the vertex), `b` vanishes to third
/// order at `t = 1` (the C2 join at the outer end); at `n = 3` also
/// `b'(0) = 0` (math doc section 14.3).
pub fn transition_b(n: usize, t: f64) -> f64 {
    let cn = (2.0 * std::f64::consts::PI / n as f64).cos();
    let base = 2.0 * cn * (1.0 - t).powi(3);
    if n == 3 {
        base * (1.0 + 3.0 * t)
    } else {
        base
    }
}

/// Degree of `b`.
fn degree_b(n: usize) -> usize {
    if n == 3 {
        4
    } else {
        3
    }
}

/// `m` Chebyshev nodes in `[0, 1]`.
fn chebyshev(m: usize) -> Vec<f64> {
    (0..m)
        .map(|q| 0.5 - 0.5 * (std::f64::consts::PI * (2 * q + 1) as f64 / (2 * m) as f64).cos())
        .collect()
}

/// The fixed part of every patch: rows `j >= 5` from the cell across `u = 1`
/// continued into the cap, columns `k >= 5` from the cell across `v = 1`.
/// Entries with `j, k < 5` are zero (free). Also returns the largest
/// disagreement of the two continuations on the shared `3 x 3` corner block
/// (zero up to rounding: the bicubic spline is C2).
pub fn fixed_nets(refined: &RefinedRing, n: usize) -> (Vec<Net>, f64) {
    let mut nets = Vec::with_capacity(n);
    let mut corner: f64 = 0.0;
    for i in 0..n {
        let from_u = extended_net(&refined.grid_u(i), -1.0, 0.0);
        let from_v = extended_net(&refined.grid_v(i), 0.0, -1.0);
        let mut net = [[[0.0; 3]; DEGREE + 1]; DEGREE + 1];
        for j in 0..=DEGREE {
            for k in 0..=DEGREE {
                if j >= FREE {
                    net[j][k] = from_u[j][k];
                    if k >= FREE {
                        for x in 0..3 {
                            corner = corner.max((from_u[j][k][x] - from_v[j][k][x]).abs());
                        }
                    }
                } else if k >= FREE {
                    net[j][k] = from_v[j][k];
                }
            }
        }
        nets.push(net);
    }
    (nets, corner)
}

/// A linear system in the free points: `rows x (25 n)` matrix and
/// `rows x 3` right-hand side.
pub(super) struct System<'a> {
    fixed: &'a [Net],
    n: usize,
    /// Sparse rows: (column, weight).
    pub(super) coef: Vec<Vec<(usize, f64)>>,
    /// Right-hand sides.
    pub(super) rhs: Vec<[f64; 3]>,
}

impl<'a> System<'a> {
    pub(super) fn new(fixed: &'a [Net]) -> Self {
        System {
            fixed,
            n: fixed.len(),
            coef: Vec::new(),
            rhs: Vec::new(),
        }
    }
    /// Appends the row `sum w p^patch_jk = 0`, scaled so that `sum |w| = 1`
    /// when `normalise` (the constraint rows: then `|A x - r|` is relative to
    /// the size of the points).
    fn row_scaled(&mut self, terms: &[(usize, usize, usize, f64)], normalise: bool) {
        let total: f64 = terms.iter().map(|t| t.3.abs()).sum();
        let scale = if normalise && total > 0.0 {
            1.0 / total
        } else {
            1.0
        };
        let mut c = Vec::new();
        let mut r = [0.0; 3];
        for &(patch, j, k, w) in terms {
            if w == 0.0 {
                continue;
            }
            let w = w * scale;
            let patch = patch % self.n;
            if j < FREE && k < FREE {
                c.push((index(patch, j, k), w));
            } else {
                for x in 0..3 {
                    r[x] -= w * self.fixed[patch][j][k][x];
                }
            }
        }
        self.coef.push(c);
        self.rhs.push(r);
    }
    fn row(&mut self, terms: &[(usize, usize, usize, f64)]) {
        self.row_scaled(terms, false);
    }
    pub(super) fn matrices(&self) -> (DMatrix<f64>, DMatrix<f64>) {
        let cols = self.n * FREE * FREE;
        let mut a = DMatrix::zeros(self.coef.len(), cols);
        let mut r = DMatrix::zeros(self.coef.len(), 3);
        for (q, (c, rh)) in self.coef.iter().zip(&self.rhs).enumerate() {
            for &(col, w) in c {
                a[(q, col)] += w;
            }
            for x in 0..3 {
                r[(q, x)] = rh[x];
            }
        }
        (a, r)
    }
}

/// Column of the free point `p^patch_jk`.
pub fn index(patch: usize, j: usize, k: usize) -> usize {
    patch * FREE * FREE + j * FREE + k
}

/// The G0, G1 and G2 conditions across edge `i` (between patches `i` and
/// `i + 1`, `P_i(0, t) = P_(i+1)(t, 0)`), as polynomial identities sampled at
/// `degree + 1` Chebyshev nodes (so they hold identically):
///
/// ```text
/// G0: p^i_0k = p^(i+1)_k0
/// G1: P_(i+1)^v(t,0) + P_i^u(0,t) - b(t) P_i^v(0,t) = 0
/// G2: P_(i+1)^vv(t,0) - P_i^uu(0,t) + 2 b(t) P_i^uv(0,t) - b(t)^2 P_i^vv(0,t) = 0
/// ```
pub(super) fn add_edge_conditions(sys: &mut System, i: usize) {
    let n = sys.n;
    let ip = i + 1;
    for k in 0..=DEGREE {
        sys.row_scaled(&[(i, 0, k, 1.0), (ip, k, 0, -1.0)], true);
    }
    let z0 = deriv_weights(0, 0.0);
    let z1 = deriv_weights(1, 0.0);
    let z2 = deriv_weights(2, 0.0);
    let db = degree_b(n);
    let mut terms = Vec::with_capacity(2 * (DEGREE + 1) * (DEGREE + 1));
    for t in chebyshev(DEGREE - 1 + db + 1) {
        let b = transition_b(n, t);
        let (t0, t1) = (deriv_weights(0, t), deriv_weights(1, t));
        terms.clear();
        for j in 0..=DEGREE {
            for k in 0..=DEGREE {
                terms.push((ip, j, k, t0[j] * z1[k]));
                terms.push((i, j, k, z1[j] * t0[k] - b * z0[j] * t1[k]));
            }
        }
        sys.row_scaled(&terms, true);
    }
    for t in chebyshev(DEGREE - 2 + 2 * db + 1) {
        let b = transition_b(n, t);
        let (t0, t1, t2) = (
            deriv_weights(0, t),
            deriv_weights(1, t),
            deriv_weights(2, t),
        );
        terms.clear();
        for j in 0..=DEGREE {
            for k in 0..=DEGREE {
                terms.push((ip, j, k, t0[j] * z2[k]));
                terms.push((
                    i,
                    j,
                    k,
                    -z2[j] * t0[k] + 2.0 * b * z1[j] * t1[k] - b * b * z0[j] * t2[k],
                ));
            }
        }
        sys.row_scaled(&terms, true);
    }
}

/// The energy: the discrete thin-plate energy of the control nets,
/// `sum |p_(j+1,k) - 2 p_jk + p_(j-1,k)|^2 + 2 |p_(j+1,k+1) - p_(j+1,k) -
/// p_(j,k+1) + p_jk|^2 + |p_(j,k+1) - 2 p_jk + p_(j,k-1)|^2` over all patches,
/// as rows of a least-squares system.
fn add_energy_rows(sys: &mut System) {
    for p in 0..sys.n {
        add_patch_energy_rows(sys, p);
    }
}

/// The energy rows of patch `p` alone (the same coefficients for every
/// patch: the energy is block diagonal in the patch index).
pub(super) fn add_patch_energy_rows(sys: &mut System, p: usize) {
    let s2 = std::f64::consts::SQRT_2;
    for j in 0..=DEGREE {
        for k in 0..=DEGREE {
            if j + 2 <= DEGREE {
                sys.row(&[(p, j, k, 1.0), (p, j + 1, k, -2.0), (p, j + 2, k, 1.0)]);
            }
            if k + 2 <= DEGREE {
                sys.row(&[(p, j, k, 1.0), (p, j, k + 1, -2.0), (p, j, k + 2, 1.0)]);
            }
            if j < DEGREE && k < DEGREE {
                sys.row(&[
                    (p, j, k, s2),
                    (p, j + 1, k, -s2),
                    (p, j, k + 1, -s2),
                    (p, j + 1, k + 1, s2),
                ]);
            }
        }
    }
}

/// The solved cap before the residual checks.
pub struct Solved {
    /// The patches.
    pub nets: Vec<Net>,
    /// The minimised energy.
    pub energy: f64,
    /// `max |A x - r|` of the constraint rows (absolute).
    pub constraint_residual: f64,
    /// Rank of the constraint matrix and number of free unknowns.
    pub rank: usize,
    /// Dimension of the solution space before the energy picks one.
    pub freedom: usize,
    /// `sigma_max / sigma_min` over the singular values of the constraint
    /// matrix kept by the rank decision: how much rounding in the data can
    /// be amplified in the particular solution.
    pub condition: f64,
    /// `sigma_max / sigma_min` of the energy rows restricted to the solution
    /// space of the constraints: how flat the energy is along its flattest
    /// feasible direction (the minimiser is determined to rounding times
    /// this number).
    pub energy_condition: f64,
}

/// Constrained least squares: minimise the energy subject to the edge
/// conditions. `x = x_p + N y`: `x_p` the least-norm solution of the
/// constraints, `N` a basis of their null space (both from one SVD, rank by
/// [`RANK_RTOL`]); `y` from the least-squares problem of the energy rows
/// restricted to `x_p + N y`.
pub fn solve(fixed: &[Net]) -> Result<Solved, G2CapError> {
    let n = fixed.len();
    let mut cons = System::new(fixed);
    for i in 0..n {
        add_edge_conditions(&mut cons, i);
    }
    let (a, r) = cons.matrices();
    let cols = a.ncols();
    // Thin SVD of A^T A would square the condition; take the SVD of A itself
    // (rows >= cols for every n here, so V is square).
    let svd = a.clone().svd(true, true);
    let (Some(u), Some(vt)) = (&svd.u, &svd.v_t) else {
        return Err(G2CapError::Numerical("SVD of the constraint matrix"));
    };
    let smax = svd.singular_values.max();
    let tol = RANK_RTOL * smax;
    let mut xp = DMatrix::<f64>::zeros(cols, 3);
    let mut null_rows = Vec::new();
    let mut rank = 0;
    let mut smin = f64::INFINITY;
    for (q, &s) in svd.singular_values.iter().enumerate() {
        if s > tol {
            rank += 1;
            smin = smin.min(s);
            let coeff = u.column(q).transpose() * &r / s; // 1 x 3
            xp += vt.row(q).transpose() * coeff;
        } else {
            null_rows.push(q);
        }
    }
    // Rows of V^T beyond the thin SVD's singular values also span the null space.
    for q in svd.singular_values.len()..vt.nrows() {
        null_rows.push(q);
    }
    let d = null_rows.len();
    let mut basis = DMatrix::<f64>::zeros(cols, d);
    for (c, &q) in null_rows.iter().enumerate() {
        basis.set_column(c, &vt.row(q).transpose());
    }
    let mut en = System::new(fixed);
    add_energy_rows(&mut en);
    let (l, lr) = en.matrices();
    let m = &l * &basis;
    let target = &lr - &l * &xp;
    let esvd = m.clone().svd(true, true);
    let energy_condition = esvd.singular_values.max() / esvd.singular_values.min();
    let y = esvd
        .solve(&target, 1e-14)
        .map_err(|_| G2CapError::Numerical("least squares of the energy"))?;
    let mut x = &xp + &basis * y;
    // Iterative refinement of the constraints: the SVD's null-space basis is
    // accurate to rounding times the conditioning, so `x_p + N y` can violate
    // the conditions by more than rounding; each step `x += A^+ (r - A x)`
    // (the same pseudo-inverse) projects back onto them.
    for _ in 0..REFINEMENT_STEPS {
        let res = &r - &a * &x;
        let mut dx = DMatrix::<f64>::zeros(cols, 3);
        for (q, &s) in svd.singular_values.iter().enumerate() {
            if s > tol {
                let coeff = u.column(q).transpose() * &res / s;
                dx += vt.row(q).transpose() * coeff;
            }
        }
        x += dx;
    }
    let res = &a * &x - &r;
    let constraint_residual = res.amax();
    let er = &l * &x - &lr;
    let energy = er.iter().map(|e| e * e).sum();
    let mut nets: Vec<Net> = fixed.to_vec();
    for (p, net) in nets.iter_mut().enumerate() {
        for j in 0..FREE {
            for k in 0..FREE {
                for c in 0..3 {
                    net[j][k][c] = x[(index(p, j, k), c)];
                }
            }
        }
    }
    Ok(Solved {
        nets,
        energy,
        constraint_residual,
        rank,
        freedom: d,
        condition: smax / smin,
        energy_condition,
    })
}
