//! One validator for a scheme choice, shared by every front end: the
//! command line (`--scheme` with `--knots`/`--ratios`/`--uniform`/`--c`),
//! report specs (`configs[i]`, mesh figures) and sweep specs (`scheme` with
//! its `space`). It owns the rules (math doc section 12):
//!
//! * the name must be a known scheme ([`SchemeKind`]);
//! * knot intervals (ratios, corner intervals, random or sampled knots) only
//!   for schemes that take them ([`SchemeKind::takes_knots`]);
//! * the shape parameter `c` exactly for the schemes that take it
//!   ([`SchemeKind::takes_c`]): required there, refused elsewhere.
//!
//! The messages are front-end neutral; a front end prefixes its own key
//! (`--scheme`, `configs[2].scheme`, `space.kind`) and location. The
//! library's constructors of a configuration from a [`SchemeKind`]
//! ([`LocalScheme::from_kind_with_c`](super::LocalScheme::from_kind_with_c),
//! [`crate::mesh::builtin::mesh_rules`]) apply the same rules through
//! [`check`] and report them as [`Error::InvalidParameter`]
//! ([`ChoiceError::into_error`]).
//!
//! ```
//! use subdiv_lab::schemes::choice::{validate, Choice, ChoiceError};
//! use subdiv_lab::schemes::SchemeKind;
//! let ok = validate(&Choice { name: "nurds", knots: true, c: false }).unwrap();
//! assert_eq!(ok, SchemeKind::Nurds);
//! let e = validate(&Choice { name: "loop", knots: true, c: false }).unwrap_err();
//! assert_eq!(e, ChoiceError::TakesNoKnots(SchemeKind::Loop));
//! assert!(e.to_string().contains("takes no knot intervals"));
//! ```

use super::kind::{SchemeKind, UnknownScheme};
use crate::error::Error;

/// What a front end was given with a scheme name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Choice<'a> {
    /// The scheme's name as written.
    pub name: &'a str,
    /// Whether non-uniform knot data was given (ratios, intervals, random or
    /// sampled knots; an explicit "uniform" is not knot data).
    pub knots: bool,
    /// Whether a shape parameter `c` was given (or is sampled).
    pub c: bool,
}

/// Why a scheme choice is refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChoiceError {
    /// Not a known scheme name.
    #[error(transparent)]
    Unknown(#[from] UnknownScheme),
    /// Knot data for a scheme without knot intervals.
    #[error("scheme {0} takes no knot intervals (only nurds does; others are uniform)")]
    TakesNoKnots(SchemeKind),
    /// A shape parameter for a scheme without one.
    #[error("scheme {0} takes no shape parameter c (only adjustable-cc does)")]
    TakesNoC(SchemeKind),
    /// A scheme with a shape parameter, without it.
    #[error("scheme {0} needs the shape parameter c in [0, 1]")]
    NeedsC(SchemeKind),
}

impl ChoiceError {
    /// Which part of the choice is wrong: `"scheme"`, `"knots"` or `"c"` (front
    /// ends map it to their own key).
    pub fn part(&self) -> &'static str {
        match self {
            ChoiceError::Unknown(_) => "scheme",
            ChoiceError::TakesNoKnots(_) => "knots",
            ChoiceError::TakesNoC(_) | ChoiceError::NeedsC(_) => "c",
        }
    }

    /// The library's error for this refusal: [`Error::InvalidParameter`]
    /// naming [`part`](Self::part), with the scheme's name (knots, an unknown
    /// name), the value of `c` as given (`c`, `"(missing)"` when needed and
    /// absent) as its value.
    pub fn into_error(self, c: Option<String>) -> Error {
        let part = self.part();
        let (value, reason) = match self {
            ChoiceError::Unknown(UnknownScheme(name)) => (name, "not a known scheme"),
            ChoiceError::TakesNoKnots(kind) => (
                kind.name().to_owned(),
                "this scheme has no knot intervals; use --scheme nurds for non-uniform knots",
            ),
            ChoiceError::TakesNoC(_) => (
                c.unwrap_or_default(),
                "only adjustable-cc takes the shape parameter c",
            ),
            ChoiceError::NeedsC(_) => (
                "(missing)".to_owned(),
                "adjustable-cc needs the shape parameter c in [0, 1]",
            ),
        };
        Error::InvalidParameter {
            name: part,
            value,
            reason,
        }
    }
}

/// Validates a scheme choice (the rules of this module's documentation) and
/// returns the scheme.
pub fn validate(choice: &Choice<'_>) -> Result<SchemeKind, ChoiceError> {
    check(choice.name.parse()?, choice.knots, choice.c)
}

/// The rules of this module's documentation for a known scheme: `knots`
/// whether non-uniform knot data was given, `c` whether a shape parameter
/// was. Knot errors come before shape errors.
pub fn check(kind: SchemeKind, knots: bool, c: bool) -> Result<SchemeKind, ChoiceError> {
    if knots && !kind.takes_knots() {
        return Err(ChoiceError::TakesNoKnots(kind));
    }
    match (kind.takes_c(), c) {
        (false, true) => Err(ChoiceError::TakesNoC(kind)),
        (true, false) => Err(ChoiceError::NeedsC(kind)),
        _ => Ok(kind),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scheme_and_every_combination_follows_the_rules() {
        for &kind in SchemeKind::ALL {
            for knots in [false, true] {
                for c in [false, true] {
                    let r = validate(&Choice {
                        name: kind.name(),
                        knots,
                        c,
                    });
                    let expect_ok = (!knots || kind.takes_knots()) && c == kind.takes_c();
                    assert_eq!(r.is_ok(), expect_ok, "{kind} knots={knots} c={c}: {r:?}");
                    if let Ok(k) = r {
                        assert_eq!(k, kind);
                    }
                }
            }
        }
        let e = validate(&Choice {
            name: "midedge",
            knots: false,
            c: false,
        })
        .unwrap_err();
        assert_eq!(e.part(), "scheme");
        assert!(e.to_string().contains("midedge"));
    }

    #[test]
    fn knot_errors_come_before_shape_errors() {
        let e = validate(&Choice {
            name: "catmull-clark",
            knots: true,
            c: true,
        })
        .unwrap_err();
        assert_eq!(e, ChoiceError::TakesNoKnots(SchemeKind::CatmullClark));
        assert_eq!(e.part(), "knots");
    }
}
