//! What `ccss-bound` reports for one valence: the bound, the contraction of
//! the patch-to-face distance and (for a control net) the steps needed, and
//! its JSON form (the CLI's `--json`, the Python dict). The front ends
//! validate their arguments here ([`check_levels`], [`check_table_to`]).

use super::bound::{bound, BoundReport};
use super::Result;
use super::StepsReport;
use super::{contraction_with, default_family, steps_needed, Contraction, ExtraordinaryPatch};
use crate::budget::Spelling;
use crate::error::Error;

/// Most levels `k = 1..K` of sub-patches `Omega^k_m` (each level doubles the
/// resolution near the vertex; 12 is far below `f64` resolution of `t`).
pub const MAX_LEVELS: u32 = 12;

/// Checks the level count: 1 to [`MAX_LEVELS`] (the message names the
/// argument as `spelling` spells it).
///
/// ```
/// use subdiv_lab::budget::Spelling;
/// use subdiv_lab::ccss_bound::summary::check_levels;
/// assert_eq!(check_levels(0, Spelling::Cli).unwrap_err(), "--levels must be in 1..=12, got 0");
/// ```
pub fn check_levels(levels: u32, spelling: Spelling) -> Result<(), String> {
    if levels == 0 || levels > MAX_LEVELS {
        return Err(format!(
            "{} must be in 1..={MAX_LEVELS}, got {levels}",
            spelling.arg("levels")
        ));
    }
    Ok(())
}

/// Checks the last valence of a `beta(n)` table: at least 3.
pub fn check_table_to(max: usize, spelling: Spelling) -> Result<(), String> {
    if max < 3 {
        return Err(format!(
            "{} must be >= 3, got {max}",
            spelling.arg("table_to")
        ));
    }
    Ok(())
}

/// The bound for one valence with what derives from it.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundSummary {
    /// The bound `beta(n)` and its sub-patch bounds.
    pub report: BoundReport,
    /// The coefficients `c_ij` on `Omega^1_2` (`i` along `u`).
    pub c_omega_1_2: [[f64; 4]; 4],
    /// The per-step contraction of the distance.
    pub contraction: Contraction,
    /// The steps needed for a control net and tolerance, when given.
    pub steps: Option<StepsReport>,
}

impl BoundSummary {
    /// The bound for valence `n` over `levels` levels (default family),
    /// with the contraction and, for `net = Some((points, epsilon))`, the
    /// subdivision steps that bring that net's limit mesh within `epsilon`.
    pub fn compute(n: usize, levels: u32, net: Option<(&[Vec<f64>], f64)>) -> Result<Self> {
        let report = bound(n, levels)?;
        let c_omega_1_2 = report
            .omega_1_2()
            .map(|s| s.c)
            .ok_or_else(|| Error::Numerical {
                routine: "ccss_bound",
                reason: "no Omega^1_2 bound computed".into(),
            })?;
        let patch = ExtraordinaryPatch::new(n)?;
        let family = default_family(n)?;
        let contraction = contraction_with(&patch, &family, report.full_max)?;
        let steps = match net {
            Some((points, eps)) => {
                Some(steps_needed(&patch, &family, report.full_max, points, eps)?)
            }
            None => None,
        };
        Ok(BoundSummary {
            report,
            c_omega_1_2,
            contraction,
            steps,
        })
    }

    /// The JSON form (`ccss-bound --json`).
    pub fn to_json(&self) -> serde_json::Value {
        let r = &self.report;
        serde_json::json!({
            "valence": r.valence,
            "beta": r.beta,
            "t_max": r.t_max,
            "level_of_max": r.level_of_max,
            "full_max": r.full_max,
            "full_max_domain": r.full_max_domain,
            "family_size": r.family_size,
            "c_omega_1_2": self.c_omega_1_2,
            "level_maxima": r.level_maxima,
            "lp_status": "optimal",
            "max_lp_residual": r.max_residual,
            "max_asymmetry": r.max_asymmetry,
            "mirror_defect": r.mirror_defect,
            "contraction": self.contraction,
            "steps": self.steps,
        })
    }
}
