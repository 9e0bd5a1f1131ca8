//! The `[columns]` table of a sweep spec.

use super::raw::{at_least, Ctx, RawColumns};
use super::{Columns, MAX_KEPT_EIGENVALUES};
use crate::schemes::SchemeKind;
use crate::sweep::SweepError;

/// Parses and validates `[columns]` (the exact certificate needs a scheme of
/// the Doo-Sabin family, and for original Doo-Sabin a valence whose weights
/// are rational: `cos(2 pi / n)` rational, `n` in {3, 4, 6}; other valences
/// are refused here, since they would turn every row into an error row and
/// lose its float columns).
pub(super) fn columns(
    ctx: &Ctx,
    c: &RawColumns,
    scheme: SchemeKind,
    valences: &[usize],
) -> Result<Columns, SweepError> {
    let mut columns = Columns::default();
    if let Some(k) = &c.eigenvalues {
        let k2 = at_least(ctx, "columns.eigenvalues", k, 0)?;
        if k2 > MAX_KEPT_EIGENVALUES as u64 {
            return ctx.err(
                "columns.eigenvalues",
                Some(k.span()),
                format!("columns.eigenvalues must be <= {MAX_KEPT_EIGENVALUES}, got {k2}"),
            );
        }
        columns.eigenvalues = k2 as usize;
    }
    columns.classification = c.classification.unwrap_or(columns.classification);
    columns.gap = c.gap.unwrap_or(columns.gap);
    columns.contraction = c.contraction.unwrap_or(columns.contraction);
    columns.exact_certificate = c.exact_certificate.unwrap_or(columns.exact_certificate);
    columns.charmap = c.charmap.unwrap_or(columns.charmap);
    columns.generic_charmap = c.generic_charmap.unwrap_or(columns.generic_charmap);
    columns.curvature = c.curvature.unwrap_or(columns.curvature);
    if columns.exact_certificate && !scheme.has_exact_certificate() {
        return ctx.err(
            "columns.exact_certificate",
            None,
            format!("columns.exact_certificate: the exact certificate is a face-block method of the Doo-Sabin family; scheme {scheme} has none"),
        );
    }
    if columns.exact_certificate && scheme == SchemeKind::DooSabin {
        if let Some(n) = valences.iter().find(|n| !matches!(n, 3 | 4 | 6)) {
            return ctx.err(
                "columns.exact_certificate",
                None,
                format!("columns.exact_certificate: original Doo-Sabin weights are irrational at valence {n} (exact arithmetic supports n = 3, 4, 6); sweep those valences without the exact certificate"),
            );
        }
    }

    Ok(columns)
}
