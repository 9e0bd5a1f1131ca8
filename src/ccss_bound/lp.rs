//! The linear programs of the bound: `min sum_l |x_l|` subject to
//! `sum_l x_l alpha_l = target` (math doc section 9, the paper's eq. (11)),
//! and its dual `max target . y` subject to `|alpha_l . y| <= 1`, both solved
//! with good_lp + microlp.
//!
//! Every `alpha_l` and every target annihilates constants, so one equation
//! (the extraordinary vertex's, index 0) is redundant: the primal drops it and
//! the dual fixes `y_0 = 0` (the dual is invariant under `y -> y + t 1`). The
//! primal solution is then *polished*: the equations are re-solved by least
//! squares on the solver's support, which keeps the signs and brings the
//! equality residual from the simplex tolerance down to rounding level.

use super::CcssBoundError;
use super::Result;
use good_lp::{constraint, microlp, variable, Expression, ProblemVariables, Solution, SolverModel};
use nalgebra::{DMatrix, DVector};

/// Entries with `|x_l|` at or below this are outside the support when polishing
/// (microlp's feasibility tolerance is `1e-9`; true non-zeros of these
/// problems are `>= 1e-6`).
pub const SUPPORT_TOL: f64 = 1e-9;

/// Largest accepted equality residual after polishing (max norm over the
/// `2n+8` equations); the data are `O(1)` combinations of `2n+10` columns
/// with entries in `{-2, 1}`, so rounding is `~1e-15`.
pub const RESIDUAL_TOL: f64 = 1e-11;

/// A solved representation.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct L1Solution {
    /// The coefficients `x_l`.
    pub x: Vec<f64>,
    /// `sum_l |x_l|`.
    pub objective: f64,
    /// `max_p |(sum_l x_l alpha_l - target)_p|` over all equations.
    pub residual: f64,
}

fn lp_err(what: &str, e: impl std::fmt::Display) -> CcssBoundError {
    CcssBoundError::Lp {
        what: what.to_owned(),
        status: e.to_string(),
    }
}

/// `min ||x||_1` s.t. `alphas x = target` (`alphas` is `(2n+8) x L`, columns = differences).
pub fn l1_representation(alphas: &DMatrix<f64>, target: &[f64], what: &str) -> Result<L1Solution> {
    let (m, l) = alphas.shape();
    let mut vars = ProblemVariables::new();
    let x: Vec<_> = (0..l).map(|_| vars.add(variable())).collect();
    let t: Vec<_> = (0..l).map(|_| vars.add(variable().min(0.0))).collect();
    let objective: Expression = t.iter().copied().sum();
    let mut problem = vars.minimise(objective).using(microlp);
    for k in 0..l {
        problem = problem.with(constraint!(x[k] - t[k] <= 0.0));
        problem = problem.with(constraint!(x[k] + t[k] >= 0.0));
    }
    for p in 1..m {
        let lhs: Expression = (0..l)
            .filter(|&k| alphas[(p, k)] != 0.0)
            .map(|k| alphas[(p, k)] * x[k])
            .sum();
        problem = problem.with(constraint!(lhs == target[p]));
    }
    let sol = problem.solve().map_err(|e| lp_err(what, e))?;
    let raw: Vec<f64> = x.iter().map(|v| sol.value(*v)).collect();
    let polished = polish(alphas, target, &raw).unwrap_or(raw);
    let r = residual(alphas, target, &polished);
    if r > RESIDUAL_TOL {
        return Err(lp_err(
            what,
            format!("equality residual {r:e} after polishing"),
        ));
    }
    Ok(L1Solution {
        objective: polished.iter().map(|v| v.abs()).sum(),
        x: polished,
        residual: r,
    })
}

/// Max-norm residual of `alphas x - target`.
pub fn residual(alphas: &DMatrix<f64>, target: &[f64], x: &[f64]) -> f64 {
    let ax = alphas * DVector::from_column_slice(x);
    ax.iter()
        .zip(target)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// Least-squares re-solve on the support of `x` (normal equations via
/// Gaussian elimination on the small support); `None` if the support columns
/// are rank deficient or the signs change.
fn polish(alphas: &DMatrix<f64>, target: &[f64], x: &[f64]) -> Option<Vec<f64>> {
    let support: Vec<usize> = (0..x.len()).filter(|&k| x[k].abs() > SUPPORT_TOL).collect();
    if support.is_empty() {
        return Some(vec![0.0; x.len()]);
    }
    let a = DMatrix::from_fn(alphas.nrows(), support.len(), |i, j| {
        alphas[(i, support[j])]
    });
    let b = DVector::from_column_slice(target);
    let ata = a.transpose() * &a;
    let atb = a.transpose() * b;
    let xs = crate::schemes::catmull_clark::limit::solve_linear(ata, atb).ok()?;
    let mut out = vec![0.0; x.len()];
    for (j, &k) in support.iter().enumerate() {
        if xs[j].signum() != x[k].signum() {
            return None;
        }
        out[k] = xs[j];
    }
    (residual(alphas, target, &out) <= residual(alphas, target, x)).then_some(out)
}

/// Box `|y_p| <= DUAL_BOX` on the dual variables. For `n` divisible by 4 the
/// default family has a 3-dimensional left kernel besides the constants
/// (period-4 "fake linear" data around the extraordinary vertex), i.e. a
/// lineality space of the dual feasible set along which the objective is
/// constant (the targets are orthogonal to it, to `1e-16`); microlp can then
/// mistake rounding for an unbounded ray. The box removes the lineality; an
/// optimal `y` of moderate size exists (the family's non-zero singular values
/// are `>= 0.03` for `n <= 50`, so optimal `y` have norm `<~ 100`), so the
/// boxed optimum equals the dual optimum. (The dual is the tests' independent
/// optimality check.)
#[cfg(test)]
pub const DUAL_BOX: f64 = 1e4;

/// The dual optimum `max target . y` s.t. `-1 <= alpha_l . y <= 1`, `y_0 = 0`,
/// `|y_p| <= DUAL_BOX`. Equal to the primal optimum by LP duality: an
/// independent optimality check.
#[cfg(test)]
pub fn dual_objective(alphas: &DMatrix<f64>, target: &[f64], what: &str) -> Result<f64> {
    let (m, l) = alphas.shape();
    let mut vars = ProblemVariables::new();
    let y: Vec<_> = (0..m)
        .map(|_| vars.add(variable().min(-DUAL_BOX).max(DUAL_BOX)))
        .collect();
    let objective: Expression = (1..m).map(|p| target[p] * y[p]).sum();
    let mut problem = vars.maximise(objective.clone()).using(microlp);
    problem = problem.with(constraint!(y[0] == 0.0));
    for k in 0..l {
        let lhs: Expression = (0..m)
            .filter(|&p| alphas[(p, k)] != 0.0)
            .map(|p| alphas[(p, k)] * y[p])
            .sum();
        problem = problem.with(constraint!(lhs.clone() <= 1.0));
        problem = problem.with(constraint!(lhs >= -1.0));
    }
    let sol = problem.solve().map_err(|e| lp_err(what, e))?;
    Ok(sol.eval(&objective))
}
