//! The `[sampler]` table of a sweep spec.

use super::raw::{at_least, forbid, Ctx, RawSampler};
use super::{Sampler, MAX_SOBOL_POINTS};
use crate::sweep::SweepError;
use toml::Spanned;

/// Parses and validates `[sampler]`.
pub(super) fn sampler(ctx: &Ctx, s: &RawSampler) -> Result<Sampler, SweepError> {
    let skind = s.kind.get_ref().as_str();
    let count = |what: &str| -> Result<u64, SweepError> {
        match &s.count {
            Some(c) => at_least(ctx, "sampler.count", c, 1),
            None => ctx.err(
                "sampler.count",
                Some(s.kind.span()),
                format!("sampler.count is required by sampler kind {what:?}"),
            ),
        }
    };
    let seed =
        |v: &Spanned<i64>| -> Result<u64, SweepError> { at_least(ctx, "sampler.seed", v, 0) };
    let sampler = match skind {
        "grid" => {
            let why = "by sampler kind \"grid\"";
            forbid(ctx, "sampler.count", &s.count, why)?;
            forbid(ctx, "sampler.seed", &s.seed, why)?;
            forbid(ctx, "sampler.scramble", &s.scramble, why)?;
            let k = match &s.points_per_axis {
                Some(k) => at_least(ctx, "sampler.points_per_axis", k, 1)?,
                None => {
                    return ctx.err(
                        "sampler.points_per_axis",
                        Some(s.kind.span()),
                        "sampler.points_per_axis is required by sampler kind \"grid\"".into(),
                    )
                }
            };
            Sampler::Grid { points_per_axis: k }
        }
        "random" => {
            let why = "by sampler kind \"random\"";
            forbid(ctx, "sampler.points_per_axis", &s.points_per_axis, why)?;
            forbid(ctx, "sampler.scramble", &s.scramble, why)?;
            let count = count("random")?;
            let seed = match &s.seed {
                Some(v) => seed(v)?,
                None => {
                    return ctx.err(
                        "sampler.seed",
                        Some(s.kind.span()),
                        "sampler.seed is required by sampler kind \"random\"".into(),
                    )
                }
            };
            Sampler::Random { count, seed }
        }
        "halton" | "sobol" => {
            let why = format!("by sampler kind {skind:?}");
            forbid(ctx, "sampler.points_per_axis", &s.points_per_axis, &why)?;
            let count = count(skind)?;
            let scramble = s.scramble.as_ref().is_some_and(|b| *b.get_ref());
            let scramble_seed = match (&s.seed, scramble) {
                (Some(v), true) => Some(seed(v)?),
                (None, true) => {
                    return ctx.err(
                        "sampler.seed",
                        s.scramble.as_ref().map(|b| b.span()),
                        "sampler.seed is required with sampler.scramble = true".into(),
                    )
                }
                (Some(v), false) => {
                    return ctx.err(
                        "sampler.seed",
                        Some(v.span()),
                        "sampler.seed has no effect without sampler.scramble = true".into(),
                    )
                }
                (None, false) => None,
            };
            if skind == "sobol" {
                if count > MAX_SOBOL_POINTS {
                    return ctx.err(
                        "sampler.count",
                        s.count.as_ref().map(|c| c.span()),
                        format!("sampler.count must be <= {MAX_SOBOL_POINTS} for the Sobol sampler, got {count}"),
                    );
                }
                Sampler::Sobol {
                    count,
                    scramble_seed,
                }
            } else {
                Sampler::Halton {
                    count,
                    scramble_seed,
                }
            }
        }
        other => {
            return ctx.err(
                "sampler.kind",
                Some(s.kind.span()),
                format!(
                    "sampler.kind: unknown sampler {other:?} (known: grid, random, halton, sobol)"
                ),
            )
        }
    };

    Ok(sampler)
}
