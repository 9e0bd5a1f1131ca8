//! The `[sector]` table of a sweep spec: a sweep of boundary, crease or
//! corner configurations (math doc section 18) over the face count `K` and,
//! for corners, the corner angle.
//!
//! ```toml
//! scheme = "loop"                  # catmull-clark | loop
//! [sector]
//! vertex = "corner"                # boundary | crease | corner
//! rules = "blz"                    # standard | blz
//! faces = { from = 1, to = 8 }     # K: a list or a range (a crease: two sectors of K faces)
//! [space]
//! kind = "corner-angle"            # corners; "uniform" for boundary and crease vertices
//! angle_range = [30.0, 330.0]      # degrees, in (0, 360)
//! ```
//!
//! The face counts take the place of `valences` (which the spec must not
//! give): they are the plan's valences, so the samplers, shards and the
//! `valence` column carry `K`.

use super::model::SectorSweep;
use super::raw::{forbid, Ctx, RawSector, RawSpec};
use super::scheme::{counts, space_kind, space_range, CountKey, SchemeConfig};
use super::SpaceKind;
use crate::boundary::{RuleSet, VertexKind};
use crate::schemes::SchemeKind;
use crate::sweep::SweepError;
use toml::Spanned;

const COUNTS_FACES: CountKey = CountKey {
    key: "sector.faces",
    min: 1,
    noun: "face count",
    list: "[1, 2, 5]",
    range: "{ from = 1, to = 8 }",
};

/// Parses and validates a `[sector]` spec's scheme configuration: `scheme`
/// (catmull-clark or loop), no `valences`, `sector.vertex`, `sector.rules`,
/// `sector.faces`, and the space kind the vertex takes (`corner-angle` with
/// `space.angle_range` for corners, `uniform` otherwise).
pub(super) fn sector_config(
    ctx: &Ctx,
    raw: &RawSpec,
    sector: &Spanned<RawSector>,
) -> Result<(SchemeConfig, SectorSweep), SweepError> {
    let scheme = match raw.scheme.get_ref().as_str() {
        "catmull-clark" => SchemeKind::CatmullClark,
        "loop" => SchemeKind::Loop,
        other => {
            return ctx.err(
                "scheme",
                Some(raw.scheme.span()),
                format!(
                    "scheme: a [sector] sweep takes scheme catmull-clark or loop, got {other:?}"
                ),
            )
        }
    };
    forbid(
        ctx,
        "valences",
        &raw.valences,
        "by a [sector] sweep (its face counts are sector.faces)",
    )?;
    let s = sector.get_ref();
    let Some(vertex) = VertexKind::parse(s.vertex.get_ref()) else {
        return ctx.err(
            "sector.vertex",
            Some(s.vertex.span()),
            format!(
                "sector.vertex: unknown vertex kind {:?} (known: boundary, crease, corner)",
                s.vertex.get_ref()
            ),
        );
    };
    let Some(rules) = RuleSet::parse(s.rules.get_ref()) else {
        return ctx.err(
            "sector.rules",
            Some(s.rules.span()),
            format!(
                "sector.rules: unknown rule set {:?} (known: standard, blz)",
                s.rules.get_ref()
            ),
        );
    };
    let valences = counts(ctx, &s.faces, &COUNTS_FACES)?;
    let kind = space_kind(ctx, raw)?;
    let want = if vertex == VertexKind::Corner {
        SpaceKind::CornerAngle
    } else {
        SpaceKind::Uniform
    };
    if kind != want {
        let hint = if vertex == VertexKind::Corner {
            "a corner sweep samples the corner angle: use kind = \"corner-angle\" with space.angle_range (degrees)"
        } else {
            "a boundary or crease sector has no parameter beyond K: use kind = \"uniform\""
        };
        return ctx.err(
            "space.kind",
            Some(raw.space.kind.span()),
            format!(
                "space.kind: kind {:?} with sector.vertex = {:?}: {hint}",
                kind.name(),
                vertex.name()
            ),
        );
    }
    let range = space_range(ctx, raw, kind)?;
    Ok((
        SchemeConfig {
            scheme,
            valences,
            kind,
            range,
        },
        SectorSweep { vertex, rules },
    ))
}
