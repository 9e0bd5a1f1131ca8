//! The work estimate of a sweep (heavy work is estimated before it starts):
//! the per-configuration cost model of [`crate::budget`] summed over a shard.

use super::Plan;
use crate::budget::*;

/// Seconds of one sweep configuration at valence `n` with the columns of
/// `plan` (structured classification `O(n^3)` with a small constant; the
/// characteristic map like `analyze --path structured`; the exact
/// certificate grows fastest, `n^3` with a larger constant for floating-point
/// knots).
fn sweep_seconds_per_configuration(plan: &Plan, model: &CostModel, n: usize) -> f64 {
    let c = plan.spec().columns;
    let nf = n as f64;
    let mut s = SWEEP_SECONDS_BASE + 4e-9 * nf * nf * nf;
    s += model.sweep_classify_seconds_per_n3 * nf * nf * nf;
    if c.charmap {
        s += 1e-3 + model.sweep_charmap_seconds_per_n3 * nf * nf * nf;
    }
    if c.generic_charmap {
        s += crate::charmap::generic::estimate_for_valence(n).seconds;
    }
    if c.exact_certificate {
        let per_n3 = if plan.spec().space.kind == super::SpaceKind::Uniform {
            SWEEP_EXACT_UNIFORM_SECONDS_PER_N3
        } else {
            SWEEP_EXACT_SECONDS_PER_N3
        };
        s += per_n3 * nf * nf * nf;
    }
    s
}

/// `subdiv-lab sweep`: the per-configuration cost summed over a shard's first
/// `rows` configurations, computed per valence block without visiting each id
/// (`count_for(n)` configurations of valence `n`, in the order of the spec,
/// a shard taking every `shard_count`-th).
///
/// The per-scheme constants are the scheme's [`CostModel`]
/// ([`Plan::cost_model`]: the spec's scheme's or the plan's own).
pub fn sweep_rows(plan: &Plan, rows: u64, shard_count: u64, threads: usize) -> Estimate {
    let model = plan.cost_model();
    let mut left = rows;
    let mut seconds = 0.0;
    let mut max_n = 3;
    for &n in &plan.spec().valences {
        if left == 0 {
            break;
        }
        let block = plan.spec().count_for(n).div_ceil(shard_count.max(1));
        let take = block.min(left);
        left -= take;
        max_n = max_n.max(n);
        seconds += take as f64 * sweep_seconds_per_configuration(plan, &model, n);
    }
    Estimate {
        bytes: threads as f64 * bytes_per_thread(plan, &model, max_n) + 64e6,
        seconds: seconds / threads.max(1) as f64,
        what: format!("{rows} configurations on {threads} threads"),
    }
}

/// `rows` configurations of valence `n` with the columns of `plan`, on
/// `threads` threads: the per-configuration cost of [`sweep_rows`] without
/// the spec's enumeration (the rows of a batch given by the caller, e.g.
/// Python's `classify_batch`).
pub fn batch_rows(plan: &Plan, n: usize, rows: u64, threads: usize) -> Estimate {
    let model = plan.cost_model();
    let seconds = rows as f64 * sweep_seconds_per_configuration(plan, &model, n);
    Estimate {
        bytes: threads as f64 * bytes_per_thread(plan, &model, n) + 64e6,
        seconds: seconds / threads.max(1) as f64,
        what: format!("{rows} configurations of valence {n} on {threads} threads"),
    }
}

/// Scratch bytes of one worker thread at valence `n`: the characteristic
/// map works on the local matrix (`d x d`), the classification alone on the
/// `n x n` face block (when the scheme classifies through it) or on the
/// local matrix.
fn bytes_per_thread(plan: &Plan, model: &CostModel, n: usize) -> f64 {
    let d = model.dimension(n);
    let nf = n as f64;
    let generic = if plan.spec().columns.generic_charmap {
        crate::charmap::generic::estimate_for_valence(n).bytes
    } else {
        0.0
    };
    generic
        + if plan.spec().columns.charmap {
            model.analyze_bytes_per_entry * d * d
        } else if model.sweep_classify_on_face_block {
            64.0 * nf * nf
        } else {
            64.0 * d * d
        }
}
