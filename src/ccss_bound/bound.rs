//! The distance bound `B(u, v)`, its diagonal `D(t)` and `beta(n)` (math doc
//! section 9; the paper's eqs. (10)-(13)).

use super::differences::{default_family, DifferenceFamily};
use super::lp::{l1_representation, L1Solution};
use super::patch::{bernstein, ExtraordinaryPatch, SubDomain};
use super::Result;
use crate::schemes::catmull_clark::SubPatch;
use nalgebra::DMatrix;

/// Samples per unit parameter for maximising `D(t)` on one sub-patch before
/// the golden-section refinement (a degree-6 polynomial with coefficients
/// `<= 1` varies by less than `1e-6` between samples `1/2048` apart).
pub const DIAGONAL_SAMPLES: usize = 2048;
/// Samples per direction for the (sampled) maximum of `B` over a sub-patch.
pub const PATCH_SAMPLES: usize = 64;
/// Default number of levels `k = 1..K` of sub-patches examined.
pub const DEFAULT_LEVELS: u32 = 4;

/// The bound on one sub-patch `Omega^k_m`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SubPatchBound {
    /// The sub-patch.
    pub domain: SubDomain,
    /// `c_ij` (index `[i][j]`, `i` along `u`).
    pub c: [[f64; 4]; 4],
    /// The 16 LP solutions (row-major `4i + j`).
    #[serde(skip)]
    pub solutions: Vec<L1Solution>,
    /// Largest equality residual of the 16 LPs.
    pub max_residual: f64,
    /// `max |c_ij - c_ji|` (the diagonal symmetry, checked rather than assumed).
    pub asymmetry: f64,
}

impl SubPatchBound {
    /// `B^k_m` at local coordinates `(s, t)` in `[0, 1]^2`.
    pub fn eval(&self, s: f64, t: f64) -> f64 {
        let (bs, bt) = (bernstein(s), bernstein(t));
        self.c
            .iter()
            .zip(bs)
            .map(|(row, wi)| wi * row.iter().zip(bt).map(|(c, wj)| c * wj).sum::<f64>())
            .sum()
    }
    /// Sampled maximum of `B^k_m` over the sub-patch.
    pub fn sampled_max(&self) -> f64 {
        let m = PATCH_SAMPLES;
        let mut best = 0.0f64;
        for a in 0..=m {
            for b in 0..=m {
                best = best.max(self.eval(a as f64 / m as f64, b as f64 / m as f64));
            }
        }
        best
    }
    /// Maximum of `D(t) = B(t, t)` on the sub-patch (local `t`), and where.
    pub fn diagonal_max(&self) -> (f64, f64) {
        maximise(|t| self.eval(t, t))
    }
}

/// Dense sampling plus golden-section refinement of a smooth function on `[0, 1]`.
fn maximise(f: impl Fn(f64) -> f64) -> (f64, f64) {
    let m = DIAGONAL_SAMPLES;
    let (mut bt, mut bv) = (0.0, f(0.0));
    for k in 1..=m {
        let t = k as f64 / m as f64;
        let v = f(t);
        if v > bv {
            (bt, bv) = (t, v);
        }
    }
    let h = 1.0 / m as f64;
    let (mut lo, mut hi) = ((bt - h).max(0.0), (bt + h).min(1.0));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let a = hi - g * (hi - lo);
        let b = lo + g * (hi - lo);
        if f(a) >= f(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let t = 0.5 * (lo + hi);
    if f(t) > bv {
        (f(t), t)
    } else {
        (bv, bt)
    }
}

/// Solves the 16 LPs of one sub-patch.
pub fn sub_patch_bound(
    patch: &ExtraordinaryPatch,
    family: &DifferenceFamily,
    domain: SubDomain,
) -> Result<SubPatchBound> {
    let alphas = family.matrix();
    let b = patch.bezier_net(domain);
    let bbar = patch.limit_face_bezier(domain)?;
    sub_patch_bound_from(&alphas, &(b - bbar), domain)
}

fn sub_patch_bound_from(
    alphas: &DMatrix<f64>,
    diff: &DMatrix<f64>,
    domain: SubDomain,
) -> Result<SubPatchBound> {
    let mut c = [[0.0; 4]; 4];
    let mut solutions = Vec::with_capacity(16);
    let mut max_residual = 0.0f64;
    for (i, row) in c.iter_mut().enumerate() {
        for (j, cij) in row.iter_mut().enumerate() {
            let target: Vec<f64> = diff.row(4 * i + j).iter().copied().collect();
            let what = format!(
                "b_{i}{j} - bbar_{i}{j} on Omega^{}_{}",
                domain.level,
                domain.part.index()
            );
            let sol = l1_representation(alphas, &target, &what)?;
            *cij = sol.objective;
            max_residual = max_residual.max(sol.residual);
            solutions.push(sol);
        }
    }
    let mut asymmetry = 0.0f64;
    for (i, row) in c.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            asymmetry = asymmetry.max((x - c[j][i]).abs());
        }
    }
    Ok(SubPatchBound {
        domain,
        c,
        solutions,
        max_residual,
        asymmetry,
    })
}

/// Everything about the bound for one valence.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BoundReport {
    /// Valence `n`.
    pub valence: usize,
    /// Number of differences in the family (`2n + 10` for the default).
    pub family_size: usize,
    /// `beta(n) = max_t D(t)` over the diagonal sub-patches `Omega^k_2`, `k = 1..levels`.
    pub beta: f64,
    /// Global parameter `t` where `D` attains `beta`.
    pub t_max: f64,
    /// Level `k` of the sub-patch `Omega^k_2` where the maximum lies.
    pub level_of_max: u32,
    /// Sampled maximum of `B(u, v)` over all sub-patches examined (checks
    /// the paper's claim that the maximum lies on the diagonal).
    pub full_max: f64,
    /// The sub-patch where `full_max` lies.
    pub full_max_domain: SubDomain,
    /// Largest LP equality residual.
    pub max_residual: f64,
    /// Largest `|c_ij - c_ji|` on the diagonal sub-patches.
    pub max_asymmetry: f64,
    /// Largest `|c^k_1[i][j] - c^k_3[j][i]|` (the off-diagonal sub-patches mirror each other).
    pub mirror_defect: f64,
    /// Per-level diagonal maxima `max_t D^k_2`, `k = 1..levels`.
    pub level_maxima: Vec<f64>,
    /// All sub-patch bounds (`levels x 3`).
    pub sub_patches: Vec<SubPatchBound>,
}

impl BoundReport {
    /// The bound `B^1_2` on `Omega^1_2` (the paper's main sub-patch).
    pub fn omega_1_2(&self) -> Option<&SubPatchBound> {
        self.sub_patches
            .iter()
            .find(|s| s.domain.level == 1 && s.domain.part == SubPatch::Two)
    }
    /// `D(t) = B(t, t)` at a global `t` in `(0, 1]` (0 at `t = 0`).
    pub fn diagonal(&self, t: f64) -> f64 {
        match SubDomain::containing(t, t) {
            Some(d) => self
                .sub_patches
                .iter()
                .find(|s| s.domain == d)
                .map_or(f64::NAN, |s| {
                    let ((u0, u1), _) = d.bounds();
                    let l = (t - u0) / (u1 - u0);
                    s.eval(l, l)
                }),
            None => 0.0,
        }
    }
}

/// The bound for valence `n` with the default family over `levels` levels.
///
/// ```
/// use subdiv_lab::ccss_bound::bound::bound;
/// let r = bound(4, 1).unwrap();
/// assert!((r.beta - 0.25).abs() < 1e-9);
/// ```
pub fn bound(n: usize, levels: u32) -> Result<BoundReport> {
    let patch = ExtraordinaryPatch::new(n)?;
    let family = default_family(n)?;
    bound_with(&patch, &family, levels)
}

/// The bound for a given patch and family over `levels >= 1` levels.
pub fn bound_with(
    patch: &ExtraordinaryPatch,
    family: &DifferenceFamily,
    levels: u32,
) -> Result<BoundReport> {
    let levels = levels.max(1);
    let mut subs = Vec::new();
    for k in 1..=levels {
        for part in SubPatch::ALL {
            subs.push(sub_patch_bound(
                patch,
                family,
                SubDomain { level: k, part },
            )?);
        }
    }
    let mut beta = 0.0f64;
    let mut t_max = 0.0;
    let mut level_of_max = 1;
    let mut level_maxima = Vec::new();
    let mut full_max = 0.0f64;
    let mut full_max_domain = subs[0].domain;
    let mut max_asymmetry = 0.0f64;
    let mut mirror_defect = 0.0f64;
    for s in &subs {
        let m = s.sampled_max();
        if m > full_max {
            full_max = m;
            full_max_domain = s.domain;
        }
        if s.domain.part == SubPatch::Two {
            let (v, t) = s.diagonal_max();
            let ((u0, u1), _) = s.domain.bounds();
            level_maxima.push(v);
            max_asymmetry = max_asymmetry.max(s.asymmetry);
            if v > beta {
                beta = v;
                t_max = u0 + t * (u1 - u0);
                level_of_max = s.domain.level;
            }
        }
        if s.domain.part == SubPatch::One {
            if let Some(mirror) = subs
                .iter()
                .find(|o| o.domain.level == s.domain.level && o.domain.part == SubPatch::Three)
            {
                for i in 0..4 {
                    for j in 0..4 {
                        mirror_defect = mirror_defect.max((s.c[i][j] - mirror.c[j][i]).abs());
                    }
                }
            }
        }
    }
    Ok(BoundReport {
        valence: patch.valence(),
        family_size: family.len(),
        beta,
        t_max,
        level_of_max,
        full_max: full_max.max(beta),
        full_max_domain,
        max_residual: subs.iter().map(|s| s.max_residual).fold(0.0, f64::max),
        max_asymmetry,
        mirror_defect,
        level_maxima,
        sub_patches: subs,
    })
}

/// One row of the `beta(n)` table.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BetaRow {
    /// Valence.
    pub n: usize,
    /// `beta(n)` (diagonal maximum).
    pub beta: f64,
    /// Global `t` of the maximum.
    pub t_max: f64,
    /// Level `k` of the maximising sub-patch.
    pub level: u32,
    /// Sampled maximum of `B` over all examined sub-patches.
    pub full_max: f64,
}

/// `beta(n)` for every `n` in `valences` (default family, `levels` levels).
pub fn beta_table(valences: impl IntoIterator<Item = usize>, levels: u32) -> Result<Vec<BetaRow>> {
    valences
        .into_iter()
        .map(|n| {
            let r = bound(n, levels)?;
            Ok(BetaRow {
                n,
                beta: r.beta,
                t_max: r.t_max,
                level: r.level_of_max,
                full_max: r.full_max,
            })
        })
        .collect()
}

/// Writes the table as CSV (`n,beta,t_max,level,full_max`).
pub fn write_beta_csv(rows: &[BetaRow], w: impl std::io::Write) -> Result<()> {
    let mut wr = csv::Writer::from_writer(w);
    for r in rows {
        wr.serialize(r)
            .map_err(|e| super::CcssBoundError::Output(e.to_string()))?;
    }
    wr.flush()
        .map_err(|e| super::CcssBoundError::Output(e.to_string()))?;
    Ok(())
}

/// Writes `D(t)` of each report on the global grid `t = k / samples`,
/// `k = 0..=samples`, as CSV (`n,t,d`) for figures of the diagonal bound.
/// Points beyond the examined levels (`t < 2^{-levels}`) are omitted.
pub fn write_diagonal_csv(
    reports: &[BoundReport],
    samples: usize,
    w: impl std::io::Write,
) -> Result<()> {
    let mut wr = csv::Writer::from_writer(w);
    let err = |e: csv::Error| super::CcssBoundError::Output(e.to_string());
    wr.write_record(["n", "t", "d"]).map_err(err)?;
    for r in reports {
        let levels = r.level_maxima.len() as i32;
        for k in 0..=samples.max(1) {
            let t = k as f64 / samples.max(1) as f64;
            if t > 0.0 && t < 0.5f64.powi(levels) {
                continue;
            }
            wr.write_record([
                r.valence.to_string(),
                t.to_string(),
                r.diagonal(t).to_string(),
            ])
            .map_err(err)?;
        }
    }
    wr.flush()
        .map_err(|e| super::CcssBoundError::Output(e.to_string()))?;
    Ok(())
}
