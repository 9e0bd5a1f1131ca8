//! The result types of a characteristic-map check (math doc section 7): the
//! verdict, the report and the patch identifiers of every scheme's ring.
//!
//! A leaf module: the scheme abstraction ([`crate::schemes::Scheme`]) returns
//! these types, so they depend on nothing above the ring geometry.

use super::regularity::{Regularity, RegularityVerdict};
use crate::schemes::catmull_clark::SubPatch;
use crate::schemes::doo_sabin::ring::{PatchKind, RingPatchId};
use std::fmt;

/// The eigenstructures that have a characteristic map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Eigenstructure {
    /// `lambda_1 = lambda_2` real with a 2-D eigenspace.
    Standard,
    /// `lambda_1 > lambda_2`, both real.
    RealDistinct,
    /// `lambda_{1,2} = rho e^{+-i theta}`.
    ComplexPair,
}

impl Eigenstructure {
    /// `standard`, `real_distinct` or `complex_pair`.
    pub fn as_str(self) -> &'static str {
        match self {
            Eigenstructure::Standard => "standard",
            Eigenstructure::RealDistinct => "real_distinct",
            Eigenstructure::ComplexPair => "complex_pair",
        }
    }
}

/// A cell of the Catmull-Clark ring: sector `j` and regular sub-patch `Omega_m`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct CcPatchId {
    /// Sector (the quad `v, e_j, f_j, e_{j+1}`).
    pub sector: usize,
    /// Which of the three regular cells of the first ring in the sector.
    pub sub: SubPatch,
}

impl fmt::Display for CcPatchId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Omega{}_{}", self.sub.index(), self.sector)
    }
}

/// The overall verdict of the characteristic-map check.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Verdict {
    /// Standard eigenstructure, regular and injective: C1 (Reif's criterion).
    C1Standard,
    /// Non-standard eigenstructure, regular and injective: tangent-plane
    /// continuity (the generalised test; not "C1").
    TangentPlaneContinuous {
        /// `real_distinct` or `complex_pair`.
        structure: Eigenstructure,
    },
    /// The characteristic map is not regular (a point with the wrong Jacobian sign exists).
    NotRegular,
    /// Regular, but the boundary winds `winding` times around the origin.
    NotInjective {
        /// The certified winding number.
        winding: i64,
    },
    /// The floating-point evidence cannot decide.
    Indeterminate {
        /// Why.
        reason: String,
    },
    /// No characteristic map exists for this eigenstructure.
    NoCharacteristicMap {
        /// `defective`, `not_separated` or `indeterminate`.
        class: String,
        /// Why there is no planar map.
        reason: String,
    },
}

impl Verdict {
    /// A short machine-readable code (sweep columns).
    pub fn code(&self) -> &'static str {
        match self {
            Verdict::C1Standard => "c1",
            Verdict::TangentPlaneContinuous {
                structure: Eigenstructure::RealDistinct,
            } => "tpc_real_distinct",
            Verdict::TangentPlaneContinuous {
                structure: Eigenstructure::ComplexPair,
            } => "tpc_complex_pair",
            Verdict::TangentPlaneContinuous { .. } => "tpc",
            Verdict::NotRegular => "not_regular",
            Verdict::NotInjective { .. } => "not_injective",
            Verdict::Indeterminate { .. } => "indeterminate",
            Verdict::NoCharacteristicMap { .. } => "no_charmap",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Verdict::C1Standard => f.write_str("C1 (standard; Reif)"),
            Verdict::TangentPlaneContinuous { structure } => write!(
                f,
                "tangent-plane continuous (non-standard: {})",
                structure.as_str()
            ),
            Verdict::NotRegular => f.write_str("not regular (characteristic map folds)"),
            Verdict::NotInjective { winding } => {
                write!(f, "not injective (winding number {winding})")
            }
            Verdict::Indeterminate { reason } => write!(f, "indeterminate ({reason})"),
            Verdict::NoCharacteristicMap { class, reason } => {
                write!(f, "no characteristic map ({class}: {reason})")
            }
        }
    }
}

/// The full result of a characteristic-map check (`P` identifies ring patches:
/// [`RingPatchId`] for the Doo-Sabin family,
/// [`CcPatchId`] for the Catmull-Clark family).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CharmapReport<P = RingPatchId> {
    /// Eigenstructure of the planar basis (`None` when there is no map).
    pub structure: Option<Eigenstructure>,
    /// Regularity details (`None` when there is no map).
    pub regularity: Option<Regularity<P>>,
    /// Certified winding number of the outer boundary (ring on the left,
    /// basis oriented so that the Jacobian is positive); `None` if undecided.
    pub winding_number: Option<i64>,
    /// The same for the inner boundary (a cross-check: equal for an embedded ring).
    pub inner_winding_number: Option<i64>,
    /// Absolute error bound used for the ring's control points (planar basis of unit vectors).
    pub point_error: f64,
    /// The verdict.
    pub verdict: Verdict,
}

/// A ring patch of either scheme family (the patch type of [`check`](super::check) and
/// [`check_classified`](super::check_classified), which serve both families).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(untagged)]
pub enum AnyPatchId {
    /// A biquadratic patch of the Doo-Sabin family's ring.
    DooSabin(RingPatchId),
    /// A regular cell of the Catmull-Clark family's ring.
    CatmullClark(CcPatchId),
    /// A patch of another scheme's ring (Loop's triangles `T0..T2`, a user
    /// scheme's patches): displayed `<prefix><slot>_<sector>`.
    Other {
        /// The sector the patch belongs to.
        sector: usize,
        /// Position of the patch within its sector.
        slot: usize,
        /// Name prefix of the patch kind (`"T"` for Loop's triangles).
        prefix: &'static str,
    },
}

impl AnyPatchId {
    /// The sector (edge or corner index) the patch belongs to.
    pub fn sector(&self) -> usize {
        match self {
            AnyPatchId::DooSabin(p) => p.index,
            AnyPatchId::CatmullClark(p) => p.sector,
            AnyPatchId::Other { sector, .. } => *sector,
        }
    }

    /// Position `0..3` of the patch within its sector (`A, B, C` or
    /// `Omega_1, Omega_2, Omega_3`).
    pub fn slot(&self) -> usize {
        match self {
            AnyPatchId::DooSabin(p) => match p.kind {
                PatchKind::A => 0,
                PatchKind::B => 1,
                PatchKind::C => 2,
            },
            AnyPatchId::CatmullClark(p) => p.sub.index() - 1,
            AnyPatchId::Other { slot, .. } => *slot,
        }
    }

    /// The patch kind as text (`A`, `B`, `C`, `Omega1`, `Omega2`, `Omega3`).
    pub fn kind_name(&self) -> String {
        match self {
            AnyPatchId::DooSabin(_) => ["A", "B", "C"][self.slot()].to_owned(),
            AnyPatchId::CatmullClark(_) => format!("Omega{}", self.slot() + 1),
            AnyPatchId::Other { prefix, slot, .. } => format!("{prefix}{slot}"),
        }
    }
}

impl fmt::Display for AnyPatchId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnyPatchId::DooSabin(p) => p.fmt(f),
            AnyPatchId::CatmullClark(p) => p.fmt(f),
            AnyPatchId::Other {
                sector,
                slot,
                prefix,
            } => write!(f, "{prefix}{slot}_{sector}"),
        }
    }
}

impl<P> CharmapReport<P> {
    /// The same report with every patch identifier mapped by `f`.
    pub fn map_patches<Q>(self, f: impl Fn(P) -> Q) -> CharmapReport<Q> {
        CharmapReport {
            structure: self.structure,
            regularity: self.regularity.map(|r| r.map_patches(&f)),
            winding_number: self.winding_number,
            inner_winding_number: self.inner_winding_number,
            point_error: self.point_error,
            verdict: self.verdict,
        }
    }
}

impl<P> CharmapReport<P> {
    /// A report for an eigenstructure without characteristic map.
    pub fn no_map(class: &str, reason: &str) -> Self {
        Self {
            structure: None,
            regularity: None,
            winding_number: None,
            inner_winding_number: None,
            point_error: f64::NAN,
            verdict: Verdict::NoCharacteristicMap {
                class: class.to_owned(),
                reason: reason.to_owned(),
            },
        }
    }

    /// `Some(true)` regular, `Some(false)` not regular, `None` undecided or no map.
    pub fn regular(&self) -> Option<bool> {
        match self.regularity.as_ref()?.verdict {
            RegularityVerdict::Regular => Some(true),
            RegularityVerdict::NotRegular => Some(false),
            RegularityVerdict::Indeterminate => None,
        }
    }

    /// `min sigma c_ij / max |c_ij|` (see [`Regularity::min_coeff`]).
    pub fn min_jacobian_coeff(&self) -> Option<f64> {
        self.regularity.as_ref().map(|r| r.min_coeff)
    }
}

impl<P: fmt::Display> CharmapReport<P> {
    /// The `"charmap"` JSON object: `regular`, `min_jacobian_coeff`,
    /// `winding_number`, `verdict` (human text), plus `verdict_code`,
    /// `regularity`, `structure`, `inner_winding_number`, and the witness.
    pub fn to_json(&self) -> serde_json::Value {
        let reg = self.regularity.as_ref();
        serde_json::json!({
            "regular": self.regular(),
            "regularity": reg.map(|r| r.verdict.as_str()),
            "min_jacobian_coeff": self.min_jacobian_coeff(),
            "min_jacobian_location": reg.map(|r| serde_json::json!({
                "patch": r.min_location.patch.to_string(), "s": r.min_location.s, "t": r.min_location.t})),
            "relative_error_bound": reg.map(|r| r.relative_error_bound),
            "witness": reg.and_then(|r| r.witness.as_ref()).map(|(p, v)| serde_json::json!({
                "patch": p.patch.to_string(), "s": p.s, "t": p.t, "jacobian": v})),
            "winding_number": self.winding_number,
            "inner_winding_number": self.inner_winding_number,
            "structure": self.structure.map(Eigenstructure::as_str),
            "verdict": self.verdict.to_string(),
            "verdict_code": self.verdict.code(),
        })
    }
}

/// The `"charmap"` object: the report's own JSON, or on a numerical failure
/// an indeterminate verdict carrying the error (the analysis itself stands).
pub fn charmap_json(c: &crate::Result<CharmapReport<AnyPatchId>>) -> serde_json::Value {
    match c {
        Ok(r) => r.to_json(),
        Err(e) => serde_json::json!({
            "regular": null, "min_jacobian_coeff": null, "winding_number": null,
            "verdict": format!("indeterminate (characteristic map not computed: {e})"),
            "verdict_code": "indeterminate", "error": e.to_string(),
        }),
    }
}
