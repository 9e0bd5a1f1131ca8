//! Sweep enumeration against its documented formulas (src/sweep/plan.rs
//! module docs, math doc section 9): grid digits and end points, the linear
//! and log-uniform maps of the random and Halton samplers, per-valence
//! offsets, coordinate columns, and shard membership. The plan's values are
//! recomputed here from the samplers' public functions and the formulas in
//! the docs (not from the plan's own code path).

use subdiv_lab::sweep::sampler::{hash_uniform, Halton};
use subdiv_lab::sweep::{Plan, Shard, SweepSpec};

fn plan(valences: &str, space: &str, sampler: &str) -> Plan {
    Plan::new(
        SweepSpec::from_toml(&format!(
            "scheme = \"nurds\"\nvalences = {valences}\n[space]\n{space}\n[sampler]\n{sampler}\n"
        ))
        .unwrap(),
    )
}

/// Relative agreement of a recomputed coordinate: the plan and the formula
/// below round differently (one `ln`/`exp` pair, a few products), a few ulps;
/// 1e-14 leaves a wide margin and is far below any mapping error.
const SAME_POINT: f64 = 1e-14;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_POINT * b.abs()
}

/// Linear grid: digit `j` of `k` maps to `lo + (hi - lo) j / (k - 1)`, the
/// last free coordinate fastest; the end points are `lo` and `hi` exactly
/// (here `0.7 * 3 / 3` would round to `0.6999999999999998`).
#[test]
fn linear_grid_points_are_the_documented_values_with_exact_end_points() {
    let (lo, hi, k) = (0.1, 0.7, 4u64);
    let p = plan(
        "[3]",
        "kind = \"ratios\"\nratio_range = [0.1, 0.7]",
        "kind = \"grid\"\npoints_per_axis = 4",
    );
    assert_eq!(p.total(), k.pow(3));
    for id in 0..p.total() {
        let c = p.configuration(id).unwrap();
        let digits = [id / (k * k), (id / k) % k, id % k];
        for (x, j) in c.coordinates.iter().zip(digits) {
            match j {
                0 => assert_eq!(*x, lo, "id {id}"),
                3 => assert_eq!(*x, hi, "id {id}"),
                _ => assert!(close(*x, lo + (hi - lo) * j as f64 / 3.0), "id {id}: {x}"),
            }
        }
    }
}

/// Log grid (interval spaces): digit `j` maps to `lo (hi / lo)^(j / (k - 1))`,
/// end points exact (`exp(ln 9)` is `8.999999999999998`).
#[test]
fn log_grid_points_are_geometric_with_exact_end_points() {
    let (lo, hi) = (0.01, 9.0);
    for k in [3u64, 5] {
        let p = plan(
            "[3]",
            "kind = \"corner-intervals\"\ninterval_range = [0.01, 9.0]\nfixed = { p0 = 1.0, p1 = 1.0, p2 = 1.0, q0 = 1.0 }",
            &format!("kind = \"grid\"\npoints_per_axis = {k}"),
        );
        assert_eq!(p.total(), k * k);
        for id in 0..p.total() {
            let c = p.configuration(id).unwrap();
            assert_eq!(&c.coordinates[..4], &[1.0; 4]);
            for (x, j) in c.coordinates[4..].iter().zip([id / k, id % k]) {
                if j == 0 {
                    assert_eq!(*x, lo);
                } else if j == k - 1 {
                    assert_eq!(*x, hi);
                } else {
                    let want = lo * (hi / lo).powf(j as f64 / (k - 1) as f64);
                    assert!(close(*x, want), "k = {k}, id {id}: {x} vs {want}");
                }
            }
        }
    }
}

/// Random sampler: coordinate `c` of sample `i` of valence `n` is
/// `hash_uniform(seed, n, i, c)` mapped linearly (ratios) or log-uniformly
/// (intervals); sample indices restart at 0 in every valence block.
#[test]
fn random_samples_are_the_documented_maps_of_hash_uniform() {
    let p = plan(
        "[3, 4]",
        "kind = \"ratios\"\nratio_range = [0.2, 0.8]",
        "kind = \"random\"\ncount = 6\nseed = 7",
    );
    assert_eq!(p.total(), 12);
    for id in 0..12 {
        let c = p.configuration(id).unwrap();
        let (n, i) = if id < 6 { (3, id) } else { (4, id - 6) };
        assert_eq!(c.valence, n);
        for (k, x) in c.coordinates.iter().enumerate() {
            let want = 0.2 + 0.6 * hash_uniform(7, n as u64, i, k as u64);
            assert!(close(*x, want), "id {id}, r{k}: {x} vs {want}");
        }
    }
    let (lo, hi) = (0.01f64, 100.0f64);
    let p = plan(
        "[3]",
        "kind = \"corner-intervals\"\ninterval_range = [0.01, 100.0]",
        "kind = \"random\"\ncount = 8\nseed = 3",
    );
    let mut seen = Vec::new();
    for id in 0..8 {
        let c = p.configuration(id).unwrap();
        for (k, x) in c.coordinates.iter().enumerate() {
            let u = hash_uniform(3, 3, id, k as u64);
            let want = lo * (hi / lo).powf(u);
            assert!(close(*x, want), "id {id}, coordinate {k}: {x} vs {want}");
            seen.push(*x);
        }
    }
    // the samples spread over the range (not collapsed onto an end point)
    assert!(seen.iter().any(|&x| x < 0.1) && seen.iter().any(|&x| x > 10.0));
}

/// Halton sampler: sample `i` is point `i + 1` of the sequence (the origin
/// is skipped), stream = valence, mapped as for random.
#[test]
fn halton_samples_skip_the_origin() {
    let p = plan(
        "[3]",
        "kind = \"ratios\"\nratio_range = [0.2, 0.8]",
        "kind = \"halton\"\ncount = 5",
    );
    let h = Halton::new(3, None, 3);
    let mut u = vec![0.0; 3];
    for id in 0..5 {
        h.point(id + 1, &mut u);
        let c = p.configuration(id).unwrap();
        for (k, (x, u)) in c.coordinates.iter().zip(&u).enumerate() {
            assert!(close(*x, 0.2 + 0.6 * u), "id {id}, r{k}: {x} vs {u}");
        }
    }
    // Point 1 of the unscrambled sequence is (1/2, 1/3, 1/5), not the origin.
    assert!(close(p.configuration(0).unwrap().coordinates[0], 0.5));
}

/// Coordinate `k` of a valence-`n` configuration goes to column
/// `(k / n) N + k % n` (`N` the largest valence): family by family, the
/// cells beyond `n` left empty.
#[test]
fn coordinate_columns_align_families_across_valences() {
    let p = plan(
        "[3, 5]",
        "kind = \"corner-intervals\"\ninterval_range = [0.5, 2.0]",
        "kind = \"random\"\ncount = 1\nseed = 1",
    );
    assert_eq!(p.max_valence(), 5);
    assert_eq!(
        p.coordinate_columns(),
        ["p0", "p1", "p2", "p3", "p4", "q0", "q1", "q2", "q3", "q4"]
    );
    let cols: Vec<usize> = (0..6).map(|k| p.coordinate_column(3, k)).collect();
    assert_eq!(cols, [0, 1, 2, 5, 6, 7]);
    let cols: Vec<usize> = (0..10).map(|k| p.coordinate_column(5, k)).collect();
    assert_eq!(cols, (0..10).collect::<Vec<_>>());
    let p = plan(
        "[4, 3]",
        "kind = \"ratios\"\nratio_range = [0.2, 0.8]",
        "kind = \"random\"\ncount = 1\nseed = 1",
    );
    assert_eq!(p.max_valence(), 4);
    assert_eq!(p.coordinate_columns(), ["r0", "r1", "r2", "r3"]);
    assert_eq!(p.coordinate_column(3, 2), 2);
    // valences in spec order: id 0 is valence 4, id 1 valence 3
    assert_eq!(p.configuration(0).unwrap().valence, 4);
    assert_eq!(p.configuration(1).unwrap().valence, 3);
}

/// Shard `I/N` holds the ids with `id % N == I`.
#[test]
fn shard_membership_length_and_text() {
    let s = Shard::new(2, 3).unwrap();
    let members: Vec<u64> = (0..12).filter(|&id| s.contains(id)).collect();
    assert_eq!(members, [2, 5, 8, 11]);
    assert_eq!((0..s.len(12)).map(|j| s.id(j)).collect::<Vec<_>>(), members);
    assert_eq!(s.len(11), 3);
    assert!(s.is_empty(2) && s.is_empty(0));
    assert!(!s.is_empty(3));
    assert!(Shard::ALL.contains(0) && Shard::ALL.contains(7));
    assert_eq!(s.to_string(), "2/3");
    assert_eq!("2/3".parse::<Shard>().unwrap(), s);
    assert_eq!(Shard::ALL.to_string(), "0/1");
    assert!(Shard::new(0, 0).is_err() && Shard::new(3, 3).is_err());
}

/// Derived columns of a corner-interval sweep: the names `r0..r{N-1}` (`N`
/// the largest valence), and per configuration the edge ratios
/// `r_i = q_{i+1} / (p_i + q_{i+1})` of its scheme, bit for bit, `None` beyond
/// the valence; every cell `None` for a space without derived columns, for a
/// configuration whose coordinate count is not `2 n`, and for intervals that
/// give no ratios (every earlier value of `out` is overwritten).
#[test]
fn derived_cells_are_the_edge_ratios_of_the_scheme() {
    use subdiv_lab::sweep::Configuration;
    let p = plan(
        "[3, 5]",
        "kind = \"corner-intervals\"\ninterval_range = [0.5, 2.0]",
        "kind = \"random\"\ncount = 2\nseed = 5",
    );
    assert_eq!(p.derived_columns(), ["r0", "r1", "r2", "r3", "r4"]);
    for id in 0..p.total() {
        let c = p.configuration(id).unwrap();
        let n = c.valence;
        let mut out = [Some(-1.0); 5];
        p.derived_into(&c, &mut out);
        let r = p.scheme(&c).unwrap().builtin().unwrap().ratios();
        for (i, cell) in out.iter().enumerate() {
            if i < n {
                let (pi, qn) = (c.coordinates[i], c.coordinates[n + (i + 1) % n]);
                let want = r.as_slice()[i];
                assert_eq!(*cell, Some(want), "id {id}, r{i}");
                assert!(close(want, qn / (pi + qn)), "id {id}, r{i}: {want}");
            } else {
                assert_eq!(*cell, None, "id {id}, r{i}");
            }
        }
    }
    // a coordinate count other than 2 n, and intervals whose ratio rounds to 0
    // (r_0 = q_1 / (p_0 + q_1) = 1e-300 / 1e300)
    let bad = [
        Configuration {
            id: 0,
            valence: 3,
            coordinates: vec![1.0; 5],
        },
        Configuration {
            id: 0,
            valence: 3,
            coordinates: vec![1e300, 1.0, 1.0, 1.0, 1e-300, 1.0],
        },
    ];
    for c in &bad {
        let mut out = [Some(-1.0); 5];
        p.derived_into(c, &mut out);
        assert_eq!(out, [None; 5], "{c:?}");
    }
    // a ratios space has no derived columns: every cell None
    let p = plan(
        "[3]",
        "kind = \"ratios\"\nratio_range = [0.2, 0.8]",
        "kind = \"random\"\ncount = 1\nseed = 5",
    );
    assert!(p.derived_columns().is_empty());
    let mut out = [Some(-1.0); 3];
    p.derived_into(&p.configuration(0).unwrap(), &mut out);
    assert_eq!(out, [None; 3]);
}

/// `scheme_reusing` gives `scheme`'s result whatever it is handed: it may
/// refill the ratios of a NURDS scheme only for a NURDS sweep over edge
/// ratios, and only when the configuration has one ratio per edge of that
/// valence (vertex-EP intervals are not ratios; a hand-made configuration with
/// a wrong coordinate count is an error; another scheme over ratios refuses
/// non-uniform knots).
#[test]
fn reusing_a_scheme_never_changes_the_result() {
    use subdiv_lab::schemes::SchemeKind;
    use subdiv_lab::sweep::{Configuration, Configured};
    let same = |p: &Plan, c: &Configuration, old| {
        let fresh = p.scheme(c).map_err(|e| e.to_string());
        let reused = p.scheme_reusing(c, old).map_err(|e| e.to_string());
        let builtin = |r: Result<Configured, String>| r.map(|s| s.builtin().cloned());
        assert_eq!(builtin(reused), builtin(fresh), "{c:?}");
    };
    // vertex-EP intervals (some above 1): the previous NURDS scheme of the same valence
    let p = plan(
        "[3, 4]",
        "kind = \"vertex-ep\"\ninterval_range = [0.2, 5.0]",
        "kind = \"random\"\ncount = 3\nseed = 2",
    );
    let mut old = None;
    for id in 0..p.total() {
        let c = p.configuration(id).unwrap();
        same(&p, &c, old.take());
        old = p.scheme(&c).ok();
        assert!(old.is_some());
    }
    // ratios, but four of them for a valence-3 configuration
    let p = plan(
        "[3]",
        "kind = \"ratios\"\nratio_range = [0.2, 0.8]",
        "kind = \"random\"\ncount = 1\nseed = 2",
    );
    let c = p.configuration(0).unwrap();
    let wrong = Configuration {
        id: 0,
        valence: 3,
        coordinates: vec![0.3, 0.4, 0.6, 0.7],
    };
    assert!(p.scheme(&wrong).is_err());
    same(&p, &wrong, p.scheme(&c).ok());
    // a hand-built spec pairing ratios with Catmull-Clark, handed a NURDS scheme
    let mut spec = p.spec().clone();
    spec.scheme = SchemeKind::CatmullClark;
    let cc = Plan::new(spec);
    let nurds = p.scheme(&c).ok();
    assert!(nurds.is_some());
    assert!(cc.scheme(&c).is_err());
    same(&cc, &c, nurds);
}
