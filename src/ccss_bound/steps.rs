//! How many subdivision steps bring the limit mesh within `epsilon` of the surface.
//!
//! After `k` steps, the part of the patch near the extraordinary vertex is the
//! level-`k` extraordinary patch, and the rest is made of regular sub-patches
//! `Omega^j_m` (`j <= k`) refined `k - j` more times. On regular parts one step
//! divides every row/column second difference by at least 4 (cubic
//! B-spline refinement: refined second differences are averages of old ones
//! divided by 4), and the regular bound is `beta(4) = 1/4`.
//!
//! **At the extraordinary vertex \[derived\]:** the differences through `v`
//! (`e_{i-1} - 2v + e_{i+1}`) do not annihilate the subdominant eigenvectors
//! of the patch matrix for `n != 4`, so on such data `M` shrinks by exactly
//! `lambda_1(n)` per step (`lambda_1 > 1/4`, e.g. `0.41` for `n = 3`,
//! `0.55` for `n = 5`): the factor 4 does **not** hold there. We compute the
//! guaranteed per-step factor by LP: `r_ev(n) = max_l min ||y||_1` s.t.
//! `alpha_l^T A = sum_k y_k alpha_k^T` (each new difference of the level-`k+1`
//! patch as a combination of the level-`k` family), so `M_{k+1} <= r_ev M_k`,
//! and `r_ev(n) >= lambda_1(n)`; likewise `r_sub(n)` for the 16 row and column
//! differences of each new regular sub-patch net. With `rho = max(r_ev, 1/4)`:
//!
//! ```text
//! max |S - limit mesh| after k steps <= C rho^k M_0,   C = max(beta_full(n), r_sub / (4 rho))
//! ```
//!
//! (EV piece: `beta r_ev^k M_0`; a regular piece born at level `j`:
//! `1/4 (1/4)^{k-j} r_sub r_ev^{j-1} M_0 <= r_sub/(4 rho) rho^k M_0`).

use super::bound::bound;
use super::differences::{default_family, DifferenceFamily};
use super::lp::l1_representation;
use super::patch::ExtraordinaryPatch;
use super::CcssBoundError;
use super::Result;
use crate::schemes::catmull_clark::SubPatch;
use nalgebra::DMatrix;

/// The per-step contraction factors of the default family.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Contraction {
    /// Valence.
    pub valence: usize,
    /// `r_ev(n)`: factor for the extraordinary patch's family.
    pub r_ev: f64,
    /// `r_sub(n)`: factor from the level-`k` family to the 16 row/column
    /// differences of the new regular sub-patch nets.
    pub r_sub: f64,
    /// `rho = max(r_ev, 1/4)`.
    pub rho: f64,
    /// The constant `C` of the module docs.
    pub constant: f64,
    /// `beta_full(n)` used in `C`.
    pub beta: f64,
}

/// The 16 row and column second differences of a 4 x 4 net as index triples `(p, q, r)`
/// (difference `P_p - 2 P_q + P_r`).
#[allow(clippy::needless_range_loop)] // `a` indexes both net[s][a] and net[a][s]
fn net_triples(net: &[[usize; 4]; 4]) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::with_capacity(16);
    for a in 0..4 {
        for s in 0..2 {
            out.push((net[s][a], net[s + 1][a], net[s + 2][a]));
            out.push((net[a][s], net[a][s + 1], net[a][s + 2]));
        }
    }
    out
}

/// Row/column second differences of a 4 x 4 net given by point indices, as
/// forms over the rows of `forms`.
fn net_differences(forms: &DMatrix<f64>, net: &[[usize; 4]; 4]) -> Vec<Vec<f64>> {
    net_triples(net)
        .into_iter()
        .map(|(p, q, r)| {
            (0..forms.ncols())
                .map(|k| forms[(p, k)] - 2.0 * forms[(q, k)] + forms[(r, k)])
                .collect()
        })
        .collect()
}

/// Computes the contraction factors (LPs; `levels` as in [`bound`]).
pub fn contraction(n: usize, levels: u32) -> Result<Contraction> {
    let patch = ExtraordinaryPatch::new(n)?;
    let family = default_family(n)?;
    contraction_with(&patch, &family, bound(n, levels)?.full_max)
}

fn max_l1(alphas: &DMatrix<f64>, targets: &[Vec<f64>], what: &str) -> Result<f64> {
    let mut worst = 0.0f64;
    for (k, t) in targets.iter().enumerate() {
        let s = l1_representation(alphas, t, &format!("{what} #{k}"))?;
        worst = worst.max(s.objective);
    }
    Ok(worst)
}

/// Contraction factors for a given patch, family and `beta`.
pub fn contraction_with(
    patch: &ExtraordinaryPatch,
    family: &DifferenceFamily,
    beta: f64,
) -> Result<Contraction> {
    let alphas = family.matrix();
    let a = patch.patch_matrix();
    // New family differences as forms over the old points: alpha^T A.
    let new_ev: Vec<Vec<f64>> = family
        .differences()
        .iter()
        .map(|d| {
            let v = nalgebra::DVector::from_vec(d.to_vector(patch.len()));
            (a.transpose() * v).iter().copied().collect()
        })
        .collect();
    let r_ev = max_l1(&alphas, &new_ev, "next-level extraordinary difference")?;
    let ext =
        crate::schemes::catmull_clark::extended_matrix::<f64>(patch.valence(), &0.5)?.into_matrix();
    let mut subs = Vec::new();
    for m in SubPatch::ALL {
        subs.extend(net_differences(&ext, &patch.layout().sub_patch(m)));
    }
    let r_sub = max_l1(&alphas, &subs, "next-level regular difference")?;
    let rho = r_ev.max(0.25);
    Ok(Contraction {
        valence: patch.valence(),
        r_ev,
        r_sub,
        rho,
        constant: beta.max(r_sub / (4.0 * rho)),
        beta,
    })
}

/// Largest number of steps [`steps_needed`] examines before giving up.
pub const MAX_STEPS: u32 = 200;

/// The smallest `epsilon` [`steps_needed`] accepts, relative to the largest
/// coordinate magnitude `m` of the net: the refined points carry rounding
/// errors of order `1e-16 m`, so their second differences stop shrinking
/// near that level and a smaller `epsilon` is never reached (without this
/// floor a run would take [`MAX_STEPS`] steps and fail as if an LP had). `1e-12` leaves a margin of
/// ten thousand over the rounding floor; with `rho <= 0.66` for every valence
/// it is reached in well under [`MAX_STEPS`] steps.
pub const EPSILON_FLOOR_RELATIVE: f64 = 1e-12;

/// The net scaled by `2^-e` so that its largest coordinate magnitude lies in
/// `[1, 2)` (exact: binary scaling commutes with rounding), and `e`; the
/// distance bounds are homogeneous of degree 1 in the net, so they are
/// computed on the scaled net and scaled back (no overflow of the squared
/// differences for coordinates near `1e300`). A zero net is returned as is.
fn normalized(net: &[Vec<f64>]) -> (Vec<Vec<f64>>, i32) {
    let m = net
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |a, x| a.max(x.abs()));
    if m == 0.0 {
        return (net.to_vec(), 0);
    }
    let e = m.log2().floor() as i32;
    let scaled = net
        .iter()
        .map(|p| p.iter().map(|&x| scale_pow2(x, -e)).collect())
        .collect();
    (scaled, e)
}

/// `x 2^k` in two exact steps (each factor a normal power of two).
fn scale_pow2(x: f64, k: i32) -> f64 {
    let h = k / 2;
    x * 2f64.powi(h) * 2f64.powi(k - h)
}

/// Checks a control net's points: one dimension (at least 1) for all, every
/// coordinate finite.
fn check_net(net: &[Vec<f64>]) -> Result<()> {
    let expected = net.first().map_or(1, |p| p.len().max(1));
    if let Some((index, p)) = net.iter().enumerate().find(|(_, p)| p.len() != expected) {
        return Err(CcssBoundError::RaggedNet {
            index,
            got: p.len(),
            expected,
        });
    }
    if let Some(index) = net.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
        return Err(CcssBoundError::NonFinitePoint { index });
    }
    Ok(())
}

/// What [`steps_needed`] found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StepsReport {
    /// The number of steps `k`.
    pub steps: u32,
    /// The guaranteed distance bound after `k` steps (`<= epsilon`).
    pub bound: f64,
    /// `M^{ev}_j` of the level-`j` extraordinary patch, `j = 0..=k`.
    pub m_ev: Vec<f64>,
    /// Largest row/column second difference of the three new regular
    /// sub-patch nets born at level `j`, `j = 1..=k`.
    pub m_sub: Vec<f64>,
}

/// Data-driven step count for an actual control net (`2n + 8` points, any
/// dimension): subdivides the net and returns the least `k` with
///
/// ```text
/// max( beta M^{ev}_k ,  max_{j=1..k} 1/4 (1/4)^{k-j} M^{sub}_j )  <=  epsilon
/// ```
///
/// (the level-`k` extraordinary patch is within `beta M^{ev}_k` of its limit
/// face; a regular sub-patch born at level `j` has its second differences
/// divided by at least 4 per further step and the regular bound `1/4`).
/// `beta` is `beta_full(n)` of [`crate::ccss_bound::bound::bound`].
/// Near the extraordinary vertex `M^{ev}_k` shrinks like `lambda_1(n)^k`,
/// not `4^{-k}` (module docs), which is what makes `k` grow for `n != 4`.
pub fn steps_needed(
    patch: &ExtraordinaryPatch,
    family: &DifferenceFamily,
    beta: f64,
    net: &[Vec<f64>],
    epsilon: f64,
) -> Result<StepsReport> {
    if !(epsilon.is_finite() && epsilon > 0.0) {
        return Err(CcssBoundError::InvalidTolerance(epsilon));
    }
    check_net(net)?;
    let magnitude = net
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let floor = EPSILON_FLOOR_RELATIVE * magnitude;
    if epsilon < floor {
        return Err(CcssBoundError::ToleranceBelowResolution {
            epsilon,
            magnitude,
            floor,
        });
    }
    let (net, e) = normalized(net);
    let mut report = steps_needed_unit(patch, family, beta, &net, scale_pow2(epsilon, -e))?;
    report.bound = scale_pow2(report.bound, e);
    for m in report.m_ev.iter_mut().chain(report.m_sub.iter_mut()) {
        *m = scale_pow2(*m, e);
    }
    Ok(report)
}

/// [`steps_needed`] on a net of magnitude about 1.
fn steps_needed_unit(
    patch: &ExtraordinaryPatch,
    family: &DifferenceFamily,
    beta: f64,
    net: &[Vec<f64>],
    epsilon: f64,
) -> Result<StepsReport> {
    let len = patch.len();
    let mut cur: Vec<Vec<f64>> = net.to_vec();
    let mut m_ev = vec![family.max_norm(&cur)?];
    let mut m_sub = Vec::new();
    let ext =
        crate::schemes::catmull_clark::extended_matrix::<f64>(patch.valence(), &0.5)?.into_matrix();
    let apply = |m: &DMatrix<f64>, pts: &[Vec<f64>]| -> Vec<Vec<f64>> {
        let dim = pts.first().map_or(0, Vec::len);
        (0..m.nrows())
            .map(|i| {
                (0..dim)
                    .map(|d| (0..len).map(|j| m[(i, j)] * pts[j][d]).sum())
                    .collect()
            })
            .collect()
    };
    let mut k = 0u32;
    loop {
        let regular = m_sub
            .iter()
            .enumerate()
            .map(|(j, m)| 0.25 * 0.25f64.powi((k as usize - 1 - j) as i32) * m)
            .fold(0.0, f64::max);
        let bound = (beta * m_ev[k as usize]).max(regular);
        if bound <= epsilon {
            return Ok(StepsReport {
                steps: k,
                bound,
                m_ev,
                m_sub,
            });
        }
        if k == MAX_STEPS {
            return Err(CcssBoundError::Lp {
                what: "steps needed".to_owned(),
                status: format!("bound {bound:e} still above epsilon after {MAX_STEPS} steps"),
            });
        }
        // One step: the new regular sub-patch nets and the new extraordinary patch.
        let refined = apply(&ext, &cur);
        let mut worst = 0.0f64;
        for m in SubPatch::ALL {
            for (p, q, r) in net_triples(&patch.layout().sub_patch(m)) {
                let d2: f64 = (0..refined[p].len())
                    .map(|d| (refined[p][d] - 2.0 * refined[q][d] + refined[r][d]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                worst = worst.max(d2);
            }
        }
        m_sub.push(worst);
        cur = refined[..len].to_vec();
        m_ev.push(family.max_norm(&cur)?);
        k += 1;
    }
}

/// A-priori step count from the contraction factors alone: the least `k`
/// with `C rho^k M_0 <= epsilon` (an upper bound for [`steps_needed`]), and `M_0`.
pub fn steps_a_priori(c: &Contraction, net: &[Vec<f64>], epsilon: f64) -> Result<(u32, f64)> {
    if !(epsilon.is_finite() && epsilon > 0.0) {
        return Err(CcssBoundError::InvalidTolerance(epsilon));
    }
    check_net(net)?;
    let family = default_family(c.valence)?;
    // On the net scaled to magnitude about 1 (an unscaled M_0 can overflow to
    // infinity, and `inf * rho` never drops below epsilon).
    let (unit, e) = normalized(net);
    let m0_unit = family.max_norm(&unit)?;
    let epsilon = scale_pow2(epsilon, -e);
    let m0 = scale_pow2(m0_unit, e);
    if c.rho.is_nan() || c.rho >= 1.0 {
        return Err(CcssBoundError::Lp {
            what: "contraction factor".to_owned(),
            status: format!("rho = {} is not below 1", c.rho),
        });
    }
    let mut k = 0u32;
    let mut bound = c.constant * m0_unit;
    while bound > epsilon {
        bound *= c.rho;
        k += 1;
    }
    Ok((k, m0))
}
