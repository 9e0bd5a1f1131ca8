//! The scheme configuration of a sweep spec: the scheme, the valences, the
//! space kind the scheme admits and its range (edge ratios, knot intervals or
//! the shape parameter c), in one function, [`scheme_config`]; the rules for
//! the scheme and its parameters are the shared ones of
//! [`crate::schemes::choice`].

use super::raw::{forbid, range, Ctx, Domain, RawSpec};
use super::{SpaceKind, MAX_VALENCE};
use crate::schemes::choice::{validate, Choice, ChoiceError};
use crate::schemes::SchemeKind;
use crate::sweep::SweepError;
use toml::Spanned;

/// The validated scheme configuration of a spec.
pub(super) struct SchemeConfig {
    /// The scheme.
    pub(super) scheme: SchemeKind,
    /// The valences, in spec order.
    pub(super) valences: Vec<usize>,
    /// The space kind.
    pub(super) kind: SpaceKind,
    /// The sampled range of the space (none for `uniform`).
    pub(super) range: Option<(f64, f64)>,
}

/// Parses and validates the scheme configuration: `scheme`, `valences`,
/// `space.kind` against the scheme, and the range key of that kind
/// (`space.ratio_range`, `space.interval_range` or `space.c_range`; the others
/// forbidden).
pub(super) fn scheme_config(ctx: &Ctx, raw: &RawSpec) -> Result<SchemeConfig, SweepError> {
    // The scheme name first (its error names `scheme`), then the space kind,
    // then the shared rules (crate::schemes::choice) for that pair.
    if let Err(e) = raw.scheme.get_ref().parse::<SchemeKind>() {
        return ctx.err("scheme", Some(raw.scheme.span()), format!("scheme: {e}"));
    }
    let Some(raw_valences) = &raw.valences else {
        return ctx.err("valences", None, "valences: missing (required key)".into());
    };
    let valences = valences(ctx, raw_valences)?;

    // Space.
    let rs = &raw.space;
    let kind = space_kind(ctx, raw)?;
    if kind == SpaceKind::CornerAngle {
        return ctx.err(
            "space.kind",
            Some(rs.kind.span()),
            "space.kind: kind \"corner-angle\" sweeps corners: it needs a [sector] table with vertex = \"corner\"".into(),
        );
    }
    let choice = Choice {
        name: raw.scheme.get_ref(),
        knots: !matches!(kind, SpaceKind::Uniform | SpaceKind::Shape),
        c: kind == SpaceKind::Shape,
    };
    let scheme = match validate(&choice) {
        Ok(k) => k,
        Err(e) => {
            let msg = match &e {
                ChoiceError::TakesNoKnots(_) => {
                    format!("space.kind: {e}; use kind = \"uniform\"")
                }
                ChoiceError::TakesNoC(_) => format!("space.kind: kind \"shape\": {e}"),
                ChoiceError::NeedsC(_) => {
                    format!("space.kind: {e}; use kind = \"shape\" with space.c_range")
                }
                ChoiceError::Unknown(_) => format!("scheme: {e}"),
            };
            return ctx.err("space.kind", Some(rs.kind.span()), msg);
        }
    };
    let range = space_range(ctx, raw, kind)?;
    Ok(SchemeConfig {
        scheme,
        valences,
        kind,
        range,
    })
}

/// The space kind (`space.kind`), by name.
pub(super) fn space_kind(ctx: &Ctx, raw: &RawSpec) -> Result<SpaceKind, SweepError> {
    let rs = &raw.space;
    match SpaceKind::parse(rs.kind.get_ref()) {
        Some(k) => Ok(k),
        None => ctx.err(
            "space.kind",
            Some(rs.kind.span()),
            format!(
                "space.kind: unknown space {:?} (known: ratios, corner-intervals, face-ep, vertex-ep, uniform, shape, corner-angle)",
                rs.kind.get_ref()
            ),
        ),
    }
}

/// The range key of space kind `kind` (`space.ratio_range`,
/// `space.interval_range`, `space.c_range`, `space.angle_range`; none for
/// `uniform`), the other range keys forbidden.
pub(super) fn space_range(
    ctx: &Ctx,
    raw: &RawSpec,
    kind: SpaceKind,
) -> Result<Option<(f64, f64)>, SweepError> {
    let rs = &raw.space;
    if kind != SpaceKind::CornerAngle {
        forbid(
            ctx,
            "space.angle_range",
            &rs.angle_range,
            "except by space kind \"corner-angle\" of a [sector] sweep",
        )?;
    }
    if kind != SpaceKind::Shape {
        forbid(
            ctx,
            "space.c_range",
            &rs.c_range,
            "except by space kind \"shape\"",
        )?;
    }
    let range = match kind {
        SpaceKind::Ratios => {
            forbid(
                ctx,
                "space.interval_range",
                &rs.interval_range,
                "by space kind \"ratios\" (use space.ratio_range)",
            )?;
            match &rs.ratio_range {
                Some(r) => Some(range(ctx, "space.ratio_range", r, Domain::Ratio)?),
                None => {
                    return ctx.err(
                        "space.ratio_range",
                        Some(rs.kind.span()),
                        "space.ratio_range is required by space kind \"ratios\"".into(),
                    )
                }
            }
        }
        SpaceKind::CornerAngle => {
            let why = "by space kind \"corner-angle\" (use space.angle_range)";
            forbid(ctx, "space.ratio_range", &rs.ratio_range, why)?;
            forbid(ctx, "space.interval_range", &rs.interval_range, why)?;
            match &rs.angle_range {
                Some(r) => Some(range(ctx, "space.angle_range", r, Domain::Angle)?),
                None => {
                    return ctx.err(
                        "space.angle_range",
                        Some(rs.kind.span()),
                        "space.angle_range is required by space kind \"corner-angle\"".into(),
                    )
                }
            }
        }
        SpaceKind::Shape => {
            let why = "by space kind \"shape\" (use space.c_range)";
            forbid(ctx, "space.ratio_range", &rs.ratio_range, why)?;
            forbid(ctx, "space.interval_range", &rs.interval_range, why)?;
            match &rs.c_range {
                Some(r) => Some(range(ctx, "space.c_range", r, Domain::Shape)?),
                None => {
                    return ctx.err(
                        "space.c_range",
                        Some(rs.kind.span()),
                        "space.c_range is required by space kind \"shape\"".into(),
                    )
                }
            }
        }
        SpaceKind::Uniform => {
            forbid(
                ctx,
                "space.ratio_range",
                &rs.ratio_range,
                "by space kind \"uniform\"",
            )?;
            forbid(
                ctx,
                "space.interval_range",
                &rs.interval_range,
                "by space kind \"uniform\"",
            )?;
            forbid(ctx, "space.fixed", &rs.fixed, "by space kind \"uniform\"")?;
            None
        }
        _ => {
            forbid(
                ctx,
                "space.ratio_range",
                &rs.ratio_range,
                "by interval spaces (use space.interval_range)",
            )?;
            match &rs.interval_range {
                Some(r) => Some(range(ctx, "space.interval_range", r, Domain::Interval)?),
                None => {
                    return ctx.err(
                        "space.interval_range",
                        Some(rs.kind.span()),
                        format!(
                            "space.interval_range is required by space kind {:?}",
                            kind.name()
                        ),
                    )
                }
            }
        }
    };
    Ok(range)
}

fn valences(ctx: &Ctx, v: &Spanned<toml::Value>) -> Result<Vec<usize>, SweepError> {
    counts(ctx, v, &COUNTS_VALENCES)
}

/// What a list of counts holds: its key, the smallest count, the noun of
/// one count and the examples of the two forms in messages.
pub(super) struct CountKey {
    pub(super) key: &'static str,
    pub(super) min: usize,
    pub(super) noun: &'static str,
    pub(super) list: &'static str,
    pub(super) range: &'static str,
}

const COUNTS_VALENCES: CountKey = CountKey {
    key: "valences",
    min: 3,
    noun: "valence",
    list: "[3, 5]",
    range: "{ from = 3, to = 8 }",
};

/// A list `[a, b, ..]` or an inclusive range `{ from = a, to = b }` of
/// distinct counts in `what.min..=MAX_VALENCE` (the valences of a spec, the
/// face counts of a `[sector]` sweep).
pub(super) fn counts(
    ctx: &Ctx,
    v: &Spanned<toml::Value>,
    what: &CountKey,
) -> Result<Vec<usize>, SweepError> {
    let CountKey {
        key: top,
        min,
        noun,
        list: list_form,
        range: range_form,
    } = *what;
    let span = Some(v.span());
    let check = |key: &str, x: &toml::Value| -> Result<usize, SweepError> {
        match x.as_integer() {
            Some(n) if (min as i64..=MAX_VALENCE as i64).contains(&n) => Ok(n as usize),
            Some(n) => ctx.err(
                key,
                span.clone(),
                format!("{key} must be a {noun} in {min}..={MAX_VALENCE}, got {n}"),
            ),
            None => ctx.err(
                key,
                span.clone(),
                format!("{key} must be an integer, got {x}"),
            ),
        }
    };
    let list = match v.get_ref() {
        toml::Value::Array(items) => {
            if items.is_empty() {
                return ctx.err(top, span, format!("{top}: empty list"));
            }
            items
                .iter()
                .enumerate()
                .map(|(i, x)| check(&format!("{top}[{i}]"), x))
                .collect::<Result<Vec<_>, _>>()?
        }
        toml::Value::Table(t) => {
            for k in t.keys() {
                if k != "from" && k != "to" {
                    return ctx.err(
                        &format!("{top}.{k}"),
                        span,
                        format!("{top}.{k}: unknown key (a {noun} range has `from` and `to`)"),
                    );
                }
            }
            let get = |k: &str| -> Result<usize, SweepError> {
                match t.get(k) {
                    Some(x) => check(&format!("{top}.{k}"), x),
                    None => ctx.err(
                        &format!("{top}.{k}"),
                        span.clone(),
                        format!("{top}.{k} is missing (a {noun} range has `from` and `to`)"),
                    ),
                }
            };
            let (from, to) = (get("from")?, get("to")?);
            if from > to {
                return ctx.err(
                    top,
                    span,
                    format!("{top}: empty range, from = {from} > to = {to}"),
                );
            }
            (from..=to).collect()
        }
        other => {
            return ctx.err(
                top,
                span,
                format!("{top} must be a list {list_form} or a range {range_form}, got {other}"),
            )
        }
    };
    let mut seen = std::collections::BTreeSet::new();
    for n in &list {
        if !seen.insert(*n) {
            return ctx.err(top, span, format!("{top}: {noun} {n} is listed twice"));
        }
    }
    Ok(list)
}
