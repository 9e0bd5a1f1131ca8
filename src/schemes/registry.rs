//! Scheme names to implementations: the one place where the command-line
//! tool and the specs turn a [`SchemeKind`] and its parameters into a
//! [`Scheme`] (math doc section 12).
//!
//! A leaf of the module graph on purpose: every scheme module may depend on
//! [`crate::schemes`], and only this file depends on every scheme module.
//! [`Builtin`] is the closed set of built-in implementations (no allocation,
//! so the sweep engine can build one per configuration); everything else
//! sees it as `&dyn Scheme` through `Deref`, so the trait's capabilities
//! never need to be repeated here.

use super::choice::check;
use super::Scheme;
use crate::budget::CostModel;
use crate::error::Result;
use crate::knots::EdgeRatios;
use crate::schemes::loop_subdivision::{self, LoopScheme};
use crate::schemes::{catmull_clark, doo_sabin, LocalScheme, SchemeKind};
use std::ops::Deref;

/// One configuration of a built-in scheme: the face- and one-ring families
/// ([`LocalScheme`]) or Loop ([`LoopScheme`]). Use it as a [`Scheme`] through
/// `Deref` (`&*builtin` is a `&dyn Scheme`).
///
/// ```
/// use subdiv_lab::schemes::registry::Builtin;
/// use subdiv_lab::schemes::SchemeKind;
/// use subdiv_lab::spectral::classify_scheme;
/// let s = Builtin::from_kind(SchemeKind::Loop, 5, None, None).unwrap();
/// let sub = classify_scheme(&*s).unwrap();
/// let lambda = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / 5.0).cos();
/// assert!((sub.lambda1.re - lambda).abs() < 1e-12);
/// assert_eq!(s.kind(), SchemeKind::Loop);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Builtin {
    /// NURDS, Doo-Sabin, the CC variant, Catmull-Clark, adjustable CC.
    Local(LocalScheme<f64>),
    /// Loop subdivision.
    Loop(LoopScheme),
}

impl Builtin {
    /// The configuration of `kind` at `valence`; `ratios` (NURDS; `None` =
    /// uniform) and `c` (the adjustable scheme) are validated as in
    /// [`LocalScheme::from_kind_with_c`] (the rules of [`super::choice`]).
    pub fn from_kind(
        kind: SchemeKind,
        valence: usize,
        ratios: Option<EdgeRatios<f64>>,
        c: Option<f64>,
    ) -> Result<Builtin> {
        if kind != SchemeKind::Loop {
            return Ok(Builtin::Local(LocalScheme::from_kind_with_c(
                kind, valence, ratios, c,
            )?));
        }
        let knots = ratios.as_ref().is_some_and(|r| !r.is_uniform());
        check(kind, knots, c.is_some()).map_err(|e| e.into_error(c.map(|c| c.to_string())))?;
        Ok(Builtin::Loop(LoopScheme::new(valence)?))
    }

    /// The scheme's kind.
    pub fn kind(&self) -> SchemeKind {
        match self {
            Builtin::Local(s) => s.kind(),
            Builtin::Loop(_) => SchemeKind::Loop,
        }
    }

    /// The edge ratios of a knot-interval scheme (uniform for the others;
    /// `None` for schemes without edge ratios around a face, Loop).
    pub fn ratios(&self) -> Option<EdgeRatios<f64>> {
        match self {
            Builtin::Local(s) => Some(s.ratios()),
            Builtin::Loop(_) => None,
        }
    }

    /// The legend label reports generate ([`LocalScheme::legend_label`]; a
    /// scheme without knots or parameters: [`Scheme::label`]); `suffix`
    /// describes how random knots were drawn.
    pub fn legend_label(&self, suffix: &str) -> String {
        match self {
            Builtin::Local(s) => s.legend_label(suffix),
            Builtin::Loop(s) => s.label(),
        }
    }

    /// The [`LocalScheme`] of the face- and one-ring families (`None` for Loop).
    pub fn as_local(&self) -> Option<&LocalScheme<f64>> {
        match self {
            Builtin::Local(s) => Some(s),
            Builtin::Loop(_) => None,
        }
    }
}

impl Deref for Builtin {
    type Target = dyn Scheme;
    fn deref(&self) -> &(dyn Scheme + 'static) {
        match self {
            Builtin::Local(s) => s,
            Builtin::Loop(s) => s,
        }
    }
}

impl From<LocalScheme<f64>> for Builtin {
    fn from(s: LocalScheme<f64>) -> Builtin {
        Builtin::Local(s)
    }
}

/// The configuration of a built-in scheme, by kind, as a boxed [`Scheme`]
/// ([`Builtin::from_kind`] boxed; the CLI dispatches here).
///
/// ```
/// use subdiv_lab::schemes::SchemeKind;
/// let s = subdiv_lab::schemes::registry::from_kind(SchemeKind::CatmullClark, 5, None, None).unwrap();
/// assert_eq!((s.name(), s.valence()), ("catmull-clark", 5));
/// ```
pub fn from_kind(
    kind: SchemeKind,
    valence: usize,
    ratios: Option<EdgeRatios<f64>>,
    c: Option<f64>,
) -> Result<Box<dyn Scheme>> {
    Ok(match Builtin::from_kind(kind, valence, ratios, c)? {
        Builtin::Local(s) => Box::new(s),
        Builtin::Loop(s) => Box::new(s),
    })
}

/// The work model of a built-in scheme, by kind ([`Scheme::cost_model`] of
/// its configurations, which does not depend on the parameters): for the
/// estimates a front end makes before any configuration exists (a sweep's
/// plan).
///
/// ```
/// use subdiv_lab::schemes::registry::cost_model;
/// use subdiv_lab::schemes::SchemeKind;
/// assert_eq!(cost_model(SchemeKind::Nurds).dimension(5), 20.0);
/// assert_eq!(cost_model(SchemeKind::Loop).dimension(5), 16.0);
/// ```
pub fn cost_model(kind: SchemeKind) -> CostModel {
    match kind {
        SchemeKind::Nurds | SchemeKind::DooSabin | SchemeKind::CcVariant => doo_sabin::COST_MODEL,
        SchemeKind::CatmullClark | SchemeKind::AdjustableCc => catmull_clark::COST_MODEL,
        SchemeKind::Loop => loop_subdivision::COST_MODEL,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::{self, MEMORY_LIMIT_BYTES, TIME_LIMIT_SECONDS};

    /// A configuration of every built-in scheme (`c = 0.3` where it is needed).
    fn every_builtin(n: usize) -> Vec<Builtin> {
        SchemeKind::ALL
            .iter()
            .map(|&k| Builtin::from_kind(k, n, None, k.takes_c().then_some(0.3)).unwrap())
            .collect()
    }

    #[test]
    fn the_cost_model_by_kind_is_the_configurations_and_fits_its_matrix() {
        for s in every_builtin(5) {
            let m = cost_model(s.kind());
            assert_eq!(m, s.cost_model(), "{}", s.name());
            let d = s.local_matrix().unwrap().rows().len();
            assert_eq!(m.dimension(5), d as f64, "{}", s.name());
        }
    }

    /// Every constructor from a kind follows the rules of `choice` for every
    /// scheme and every combination of knots and `c`, and refuses with the
    /// part that is wrong (the mesh rules: `mesh::builtin`'s tests).
    /// (Planted: letting `check` accept `c` for catmull-clark fails here.)
    #[test]
    fn every_constructor_follows_the_choice_rules() {
        let skew = EdgeRatios::new(vec![0.3, 0.6, 0.5, 0.2, 0.7]).unwrap();
        for &kind in SchemeKind::ALL {
            for knots in [false, true] {
                for c in [false, true] {
                    let expect_ok = (!knots || kind.takes_knots()) && c == kind.takes_c();
                    let ratios = knots.then(|| skew.clone());
                    let c = c.then_some(0.3);
                    let b = Builtin::from_kind(kind, 5, ratios.clone(), c);
                    assert_eq!(b.is_ok(), expect_ok, "{kind} knots={knots} c={c:?}: {b:?}");
                    if kind != SchemeKind::Loop {
                        let l = LocalScheme::from_kind_with_c(kind, 5, ratios, c);
                        assert_eq!(l.is_ok(), expect_ok, "{kind} knots={knots} c={c:?}: {l:?}");
                    }
                    if let Err(crate::Error::InvalidParameter { name, .. }) = b {
                        assert_eq!(
                            name,
                            if knots && !kind.takes_knots() {
                                "knots"
                            } else {
                                "c"
                            }
                        );
                    }
                }
            }
        }
    }

    // The size limits over every built-in cost model.
    #[test]
    fn large_sizes_exceed_the_limits_and_small_ones_do_not() {
        for s in every_builtin(3) {
            let kind = s.kind();
            let model = s.cost_model();
            for structured in [false, true] {
                let big = budget::analyze(&model, 100_000, structured);
                assert!(big.bytes > MEMORY_LIMIT_BYTES, "{kind}");
                assert!(budget::analyze(&model, 20_000, structured).bytes > MEMORY_LIMIT_BYTES);
                assert!(budget::analyze(&model, 1000, structured).seconds > TIME_LIMIT_SECONDS);
                let small = budget::analyze(&model, 64, structured);
                assert!(small.within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
            }
            assert!(budget::matrix(&model, 100_000, false, false).bytes > MEMORY_LIMIT_BYTES);
            assert!(budget::matrix(&model, 64, false, true)
                .within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
        }
        // the CC one-ring at n = 100000 is a 320 GB matrix
        let cc = budget::analyze(&cost_model(SchemeKind::CatmullClark), 100_000, false);
        assert!(cc.bytes >= 8.0 * 200_001f64.powi(2));
        assert!(cc.what.contains("200001 x 200001"));
        let lp = budget::analyze(&cost_model(SchemeKind::Loop), 100_000, false);
        assert!(lp.what.contains("300001 x 300001"));
    }
}
