//! Scheme names to implementations: the one place where the command-line
//! tool and the specs turn a [`SchemeKind`] and its parameters into a
//! [`Scheme`] (math doc section 12).
//!
//! A leaf of the module graph on purpose: every scheme module may depend on
//! [`crate::scheme`], and only this file depends on every scheme module.

use super::Scheme;
use crate::error::{Error, Result};
use crate::knots::EdgeRatios;
use crate::schemes::loop_subdivision::LoopScheme;
use crate::schemes::{LocalScheme, SchemeKind};

/// The configuration of a built-in scheme, by kind, as a [`Scheme`]: the one
/// place where a scheme name becomes an implementation (the CLI and the specs
/// dispatch here). `ratios` (NURDS; `None` = uniform) and `c` (the adjustable
/// scheme) are validated as in [`LocalScheme::from_kind_with_c`].
///
/// ```
/// use subdiv_lab::schemes::SchemeKind;
/// let s = subdiv_lab::scheme::registry::from_kind(SchemeKind::CatmullClark, 5, None, None).unwrap();
/// assert_eq!((s.name(), s.valence()), ("catmull-clark", 5));
/// ```
pub fn from_kind(
    kind: SchemeKind,
    valence: usize,
    ratios: Option<EdgeRatios<f64>>,
    c: Option<f64>,
) -> Result<Box<dyn Scheme>> {
    if kind != SchemeKind::Loop {
        return Ok(Box::new(LocalScheme::from_kind_with_c(
            kind, valence, ratios, c,
        )?));
    }
    if ratios.as_ref().is_some_and(|r| !r.is_uniform()) {
        return Err(Error::InvalidParameter {
            name: "knots",
            value: kind.name().to_owned(),
            reason: "this scheme has no knot intervals; use --scheme nurds for non-uniform knots",
        });
    }
    if let Some(c) = c {
        return Err(Error::InvalidParameter {
            name: "c",
            value: c.to_string(),
            reason: "only adjustable-cc takes the shape parameter c",
        });
    }
    Ok(Box::new(LoopScheme::new(valence)?))
}
