//! The raw (serde) form of a sweep spec and the helpers of its validation:
//! error positions (key path and line), integer and range checks.

use crate::sweep::SweepError;
use crate::toml_location::{key_path_at, key_path_in_tree, Location};
use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSpec {
    pub(super) name: Option<String>,
    pub(super) scheme: Spanned<String>,
    /// Required unless the spec has a `[sector]` table (whose `faces` replace it).
    pub(super) valences: Option<Spanned<toml::Value>>,
    pub(super) sector: Option<Spanned<RawSector>>,
    pub(super) space: RawSpace,
    pub(super) sampler: RawSampler,
    #[serde(default)]
    pub(super) columns: RawColumns,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSpace {
    pub(super) kind: Spanned<String>,
    pub(super) ratio_range: Option<Spanned<Vec<f64>>>,
    pub(super) interval_range: Option<Spanned<Vec<f64>>>,
    pub(super) c_range: Option<Spanned<Vec<f64>>>,
    pub(super) angle_range: Option<Spanned<Vec<f64>>>,
    pub(super) fixed: Option<Spanned<BTreeMap<String, Spanned<f64>>>>,
}

/// The `[sector]` table: a boundary, crease or corner sweep.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSector {
    pub(super) vertex: Spanned<String>,
    pub(super) rules: Spanned<String>,
    pub(super) faces: Spanned<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSampler {
    pub(super) kind: Spanned<String>,
    pub(super) points_per_axis: Option<Spanned<i64>>,
    pub(super) count: Option<Spanned<i64>>,
    pub(super) seed: Option<Spanned<i64>>,
    pub(super) scramble: Option<Spanned<bool>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawColumns {
    pub(super) eigenvalues: Option<Spanned<i64>>,
    pub(super) classification: Option<bool>,
    pub(super) gap: Option<bool>,
    pub(super) contraction: Option<bool>,
    pub(super) exact_certificate: Option<bool>,
    pub(super) charmap: Option<bool>,
    pub(super) generic_charmap: Option<bool>,
    pub(super) curvature: Option<bool>,
}

/// A spec error from the TOML deserializer, naming the key path and line: the
/// key at the error's span; for a missing key, the table it is missing from
/// (the span is that table's header, or the empty span of the document)
/// joined with the missing key's name.
pub(super) fn deserialize_error(text: &str, e: &toml::de::Error) -> SweepError {
    let span = e.span().filter(|s| s.end > 0);
    let message = e.message().trim().to_owned();
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|m| m.strip_suffix('`'));
    let at = span
        .as_ref()
        .and_then(|s| key_path_in_tree(text, s.start).or_else(|| key_path_at(text, s.start)));
    let (key, message) = match missing {
        Some(field) => {
            let key = match &at {
                Some(table) => format!("{table}.{field}"),
                None => field.to_owned(),
            };
            let what = if key == "space" || key == "sampler" {
                format!("missing [{key}] table")
            } else {
                "missing (required key)".to_owned()
            };
            (key.clone(), format!("{key}: {what}"))
        }
        None => {
            let key = at.unwrap_or_else(|| "spec".to_owned());
            (key.clone(), format!("{key}: {message}"))
        }
    };
    SweepError::Spec {
        line: span.map(|s| Location::of(text, s.start).line),
        message,
        key,
    }
}

pub(crate) struct Ctx<'a> {
    pub(crate) text: &'a str,
}

impl Ctx<'_> {
    pub(crate) fn err<T>(
        &self,
        key: &str,
        span: Option<std::ops::Range<usize>>,
        message: String,
    ) -> Result<T, SweepError> {
        Err(SweepError::Spec {
            key: key.to_owned(),
            line: span.map(|s| Location::of(self.text, s.start).line),
            message,
        })
    }
}

/// Integer from a spanned TOML integer, at least `min`.
pub(super) fn at_least(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<i64>,
    min: i64,
) -> Result<u64, SweepError> {
    let x = *v.get_ref();
    if x < min {
        return ctx.err(
            key,
            Some(v.span()),
            format!("{key} must be >= {min}, got {x}"),
        );
    }
    Ok(x as u64)
}

/// The domain a range key lives in.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Domain {
    /// Edge ratios: the open interval (0, 1).
    Ratio,
    /// Knot intervals: positive.
    Interval,
    /// The shape parameter: the closed interval [0, 1].
    Shape,
    /// A corner angle in degrees: the open interval (0, 360).
    Angle,
}

/// A sweep's `[lower, upper]` range of `domain` (an empty range names
/// `space.fixed`, which fixes a coordinate).
pub(super) fn range(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<Vec<f64>>,
    domain: Domain,
) -> Result<(f64, f64), SweepError> {
    bounds(
        ctx,
        key,
        v,
        domain,
        "; fix a coordinate with space.fixed instead",
    )
}

/// A `[lower, upper]` range of `domain` from spec key `key`: two finite
/// bounds inside the domain, lower below upper (the sweep's and the
/// verifier's ranges); `empty_hint` ends the message of an empty range.
pub(crate) fn bounds(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<Vec<f64>>,
    domain: Domain,
    empty_hint: &str,
) -> Result<(f64, f64), SweepError> {
    let span = Some(v.span());
    let r = v.get_ref();
    if r.len() != 2 {
        return ctx.err(
            key,
            span,
            format!("{key} must be [lower, upper], got {} values", r.len()),
        );
    }
    let (a, b) = (r[0], r[1]);
    if !(a.is_finite() && b.is_finite()) {
        return ctx.err(
            key,
            span,
            format!("{key}: bounds must be finite, got [{a:?}, {b:?}]"),
        );
    }
    if domain == Domain::Shape {
        for x in [a, b] {
            if !(0.0..=1.0).contains(&x) {
                return ctx.err(
                    key,
                    span,
                    format!(
                        "{key}: bound {x:?} is outside [0, 1], the range of the shape parameter c"
                    ),
                );
            }
        }
    } else if domain == Domain::Angle {
        for x in [a, b] {
            if !(x > 0.0 && x < 360.0) {
                return ctx.err(
                    key,
                    span,
                    format!(
                        "{key}: bound {x:?} is outside the open interval (0, 360) of corner angles in degrees"
                    ),
                );
            }
        }
    } else if domain == Domain::Ratio {
        for x in [a, b] {
            if !(x > 0.0 && x < 1.0) {
                return ctx.err(
                    key,
                    span,
                    format!(
                        "{key}: bound {x:?} is outside the open interval (0, 1) of edge ratios"
                    ),
                );
            }
        }
    } else {
        for x in [a, b] {
            if x <= 0.0 {
                return ctx.err(
                    key,
                    span,
                    format!("{key}: bound {x:?} must be > 0 (knot intervals are positive)"),
                );
            }
        }
    }
    if a > b {
        return ctx.err(
            key,
            span,
            format!("{key}: lower bound {a:?} > upper bound {b:?}"),
        );
    }
    if a == b {
        return ctx.err(
            key,
            span,
            format!("{key}: empty range [{a:?}, {b:?}] (lower bound = upper bound){empty_hint}"),
        );
    }
    Ok((a, b))
}

pub(super) fn forbid<T>(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<T>>,
    why: &str,
) -> Result<(), SweepError> {
    match v {
        Some(s) => ctx.err(key, Some(s.span()), format!("{key} is not used {why}")),
        None => Ok(()),
    }
}
