//! The fixed coordinates of a sweep spec's space (`space.fixed`).

use super::raw::{Ctx, RawSpace};
use super::SpaceKind;
use crate::sweep::SweepError;
use std::collections::BTreeMap;

/// Parses `space.fixed`: coordinate names of valence `min_valence` of `kind`,
/// values in the domain of the kind.
pub(super) fn fixed(
    ctx: &Ctx,
    rs: &RawSpace,
    kind: SpaceKind,
    min_valence: usize,
) -> Result<BTreeMap<String, f64>, SweepError> {
    let mut fixed = BTreeMap::new();
    if let Some(f) = &rs.fixed {
        for (name, value) in f.get_ref() {
            let key = format!("space.fixed.{name}");
            let span = Some(value.span());
            if kind.coordinate_index(min_valence, name).is_none() {
                let fams = if kind.dimension(min_valence) == 1 {
                    kind.families().join(", ")
                } else {
                    kind.families()
                        .iter()
                        .map(|f| format!("{f}0..{f}{}", min_valence - 1))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                return ctx.err(
                    &key,
                    span,
                    format!("{key}: unknown coordinate {name:?} (coordinates of valence {min_valence}: {fams})"),
                );
            }
            let x = *value.get_ref();
            let ok = match kind {
                SpaceKind::Ratios => x > 0.0 && x < 1.0,
                SpaceKind::Shape => (0.0..=1.0).contains(&x),
                SpaceKind::CornerAngle => x > 0.0 && x < 360.0,
                _ => x.is_finite() && x > 0.0,
            };
            if !ok {
                let domain = match kind {
                    SpaceKind::Ratios => "an edge ratio strictly between 0 and 1",
                    SpaceKind::Shape => "a shape parameter c in [0, 1]",
                    SpaceKind::CornerAngle => {
                        "a corner angle in degrees strictly between 0 and 360"
                    }
                    _ => "a finite knot interval > 0",
                };
                return ctx.err(&key, span, format!("{key} must be {domain}, got {x:?}"));
            }
            fixed.insert(name.clone(), x);
        }
    }
    Ok(fixed)
}
