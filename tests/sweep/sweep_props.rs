//! Property tests of the sweep machinery: summaries and CSV merges do not depend
//! on how the sweep is sharded or in which order shards are combined; grid
//! enumerations are bijective; samplers stay in range.

use proptest::prelude::*;
use subdiv_lab::sweep::output::{self, MergeSource, Row};
use subdiv_lab::sweep::sampler::{Halton, Sobol};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

fn plan() -> Plan {
    Plan::new(
        SweepSpec::from_toml(
            r#"
scheme = "nurds"
valences = [3, 4]
[space]
kind = "corner-intervals"
interval_range = [0.2, 5.0]
fixed = { p0 = 1.0, q0 = 1.0, q1 = 1.0 }
[sampler]
kind = "grid"
points_per_axis = 3
"#,
        )
        .unwrap(),
    )
}

fn rows(plan: &Plan, layout: &Layout) -> Vec<Row> {
    let eval = SpectralEvaluator::new(plan.spec().columns);
    (0..plan.total())
        .map(|id| layout.row(plan, &eval, id))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn sharded_summaries_and_csv_merge_equal_the_full_run(shards in 1u64..8, order_seed in any::<u64>()) {
        let plan = plan();
        let layout = Layout::new(&plan);
        let all = rows(&plan, &layout);
        prop_assert_eq!(all.len() as u64, 27 + 243);
        let mut full = Summary::new(&plan, &layout, Shard::ALL, None);
        for r in &all {
            full.add(&layout, r);
        }
        // One summary and one CSV body per shard.
        let mut parts: Vec<(Summary, Vec<String>)> = (0..shards)
            .map(|i| {
                let shard = Shard::new(i, shards).unwrap();
                let mut s = Summary::new(&plan, &layout, shard, None);
                let mut lines = Vec::new();
                for r in all.iter().filter(|r| shard.contains(r.id)) {
                    s.add(&layout, r);
                    let mut l = layout.format(r);
                    l.pop();
                    lines.push(l);
                }
                prop_assert!(s.complete);
                Ok((s, lines))
            })
            .collect::<Result<_, TestCaseError>>()?;
        // Combine in a pseudo-random order.
        let mut k = order_seed;
        for i in (1..parts.len()).rev() {
            k = k.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            parts.swap(i, (k >> 33) as usize % (i + 1));
        }
        let mut merged = parts[0].0.clone();
        for (s, _) in &parts[1..] {
            merged.merge(s).unwrap();
        }
        prop_assert_eq!(merged.without_throughput(), full.without_throughput());
        let sources = parts
            .iter()
            .enumerate()
            .map(|(i, (s, lines))| MergeSource {
                name: format!("part{i}"),
                shard: s.shard,
                lines: lines.clone().into_iter().map(Ok),
            })
            .collect();
        let mut out = Vec::new();
        let eval = subdiv_lab::sweep::SpectralEvaluator::new(plan.spec().columns);
        let rebuilt = output::merge(&plan, &layout, &eval, sources, &mut out, order_seed).unwrap();
        for ((s, _), r) in parts.iter().zip(&rebuilt) {
            prop_assert_eq!(r.without_throughput(), s.without_throughput());
        }
        let want: String = all.iter().map(|r| layout.format(r)).collect();
        prop_assert_eq!(String::from_utf8(out).unwrap(), want);
    }

    #[test]
    fn grid_enumeration_is_a_bijection(k in 1u64..6, lo in 0.01f64..0.4, width in 0.1f64..0.5, fix in any::<bool>()) {
        let hi = lo + width;
        let fixed = if fix { "fixed = { r1 = 0.5 }" } else { "" };
        let spec = SweepSpec::from_toml(&format!(
            "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [{lo}, {hi}]\n{fixed}\n[sampler]\nkind = \"grid\"\npoints_per_axis = {k}\n"
        )).unwrap();
        let plan = Plan::new(spec);
        let d = if fix { 2 } else { 3 };
        prop_assert_eq!(plan.total(), k.pow(d));
        let mut seen = std::collections::HashSet::new();
        for id in 0..plan.total() {
            let c = plan.configuration(id).unwrap();
            prop_assert!(c.coordinates.iter().enumerate().all(|(i, x)| (fix && i == 1 && *x == 0.5) || (lo..=hi).contains(x)));
            prop_assert!(seen.insert(c.coordinates.iter().map(|x| x.to_bits()).collect::<Vec<_>>()));
        }
        // Shards of any count partition the ids.
        for n in 1..5u64 {
            let total: u64 = (0..n).map(|i| Shard::new(i, n).unwrap().len(plan.total())).sum();
            prop_assert_eq!(total, plan.total());
        }
    }

    #[test]
    fn low_discrepancy_points_are_in_the_unit_cube(d in 1usize..40, i in 0u64..(1 << 32), seed in proptest::option::of(any::<u64>())) {
        let mut x = vec![0.0; d];
        Sobol::new(d, seed, 3).unwrap().point(i, &mut x);
        prop_assert!(x.iter().all(|v| (0.0..1.0).contains(v)));
        Halton::new(d, seed, 3).point(i, &mut x);
        prop_assert!(x.iter().all(|v| (0.0..1.0).contains(v)));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `Plan::scheme_reusing` (a sweep's per-lane scheme reuse) gives the scheme
    /// `Plan::scheme` builds, or the same error, whatever scheme it is handed:
    /// another valence, another ratio vector, or nothing; ratios outside
    /// (0, 1) included (errors of `EdgeRatios::refilled` and `new` agree).
    #[test]
    fn reused_schemes_equal_fresh_ones(
        steps in proptest::collection::vec(
            (3usize..7, proptest::collection::vec(-0.2f64..1.2, 7), any::<bool>()),
            1..12,
        )
    ) {
        use subdiv_lab::sweep::Configuration;
        let plan = Plan::new(SweepSpec::from_toml(
            "scheme = \"nurds\"\nvalences = [3, 4, 5, 6]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"random\"\ncount = 4\nseed = 1\n",
        ).unwrap());
        let mut kept = None;
        for (k, (n, r, drop)) in steps.into_iter().enumerate() {
            let c = Configuration { id: k as u64, valence: n, coordinates: r[..n].to_vec() };
            let fresh = plan.scheme(&c).map_err(|e| e.to_string());
            let reused = plan
                .scheme_reusing(&c, if drop { None } else { kept.take() })
                .map_err(|e| e.to_string());
            let builtin = |r: &Result<subdiv_lab::sweep::Configured, String>| {
                r.as_ref().map(|s| s.builtin().cloned()).map_err(Clone::clone)
            };
            prop_assert_eq!(builtin(&reused), builtin(&fresh));
            kept = reused.ok();
        }
    }
}
