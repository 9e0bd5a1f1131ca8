//! The `g1` targets of `verify` (math doc section 15, "G1 over a cell"):
//! runs the branch and bound for the property `g1` over a NURDS box and
//! looks for witnesses (a ratio vector where the pair is not separated or
//! the characteristic map folds) in the largest cells left undecided.
//!
//! ```text
//! cargo run --release --example verify_g1 -- N LO HI MIN_WIDTH TIME_BUDGET [WITNESS_CELLS] [corners] [rotations|dihedral] [levels]
//! ```
//!
//! `N` the valence; the box is `[LO, HI]^N` of edge ratios, or with
//! `corners` the corner-interval box `p_i, q_i in [LO, HI]` (log-scaled
//! bisection); `MIN_WIDTH` and `TIME_BUDGET` (seconds) as in a verify spec;
//! `WITNESS_CELLS` (default 200) undecided cells, largest first, are
//! searched for witnesses (centre and 16 random points each). With
//! `rotations` or `dihedral` the run uses that symmetry of the ratio box
//! (math doc section 15, "Symmetry of the ratio box"): `dihedral` verifies
//! the smallest box `[1 - h, h]^N` of floats containing `[LO, HI]^N`
//! (`lo + hi = 1` exactly; printed), and the share is the lower bound over
//! the whole box through the group. Prints one
//! line: the certified `g1` volume share, cells, wall time, why refinement
//! stopped, and the witnesses found by kind (`benches/verify_g1_targets.sh`
//! runs the targets). With `levels`, a table follows: per bisection level
//! the cells evaluated, the final cells certified, open and left to the
//! symmetry, and the open cells' share of the box (with a symmetry, `|G|`
//! times their volume in the fundamental domain over the box's, the terms
//! of the bound).

use std::collections::BTreeMap;
use subdiv_lab::verify::spec::{Property, Region, Symmetry, VerifySpec};
use subdiv_lab::verify::symmetry::symmetric_enclosure;
use subdiv_lab::verify::witness::g1_witness;
use subdiv_lab::verify::{run, summary, Limits};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: verify_g1 N LO HI MIN_WIDTH TIME_BUDGET [WITNESS_CELLS] [corners] [rotations|dihedral] [levels]";
    let num = |k: usize| -> f64 {
        args.get(k)
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("{usage}"))
    };
    let n = num(0) as usize;
    let (lo, hi, min_width, budget) = (num(1), num(2), num(3), num(4));
    let witness_cells = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(200usize);
    let corners = args.iter().any(|a| a == "corners");
    let symmetry = if args.iter().any(|a| a == "dihedral") {
        Symmetry::Dihedral
    } else if args.iter().any(|a| a == "rotations") {
        Symmetry::Rotations
    } else {
        Symmetry::None
    };
    // the reflection r -> 1 - r needs lo + hi = 1 exactly
    let (lo, hi) = if symmetry == Symmetry::Dihedral {
        symmetric_enclosure(lo, hi)
    } else {
        (lo, hi)
    };
    let text = if corners {
        let side = vec![format!("[{lo:?}, {hi:?}]"); n].join(", ");
        format!("p_box = [{side}]\nq_box = [{side}]\n")
    } else {
        format!(
            "box = [{}]\n",
            vec![format!("[{lo:?}, {hi:?}]"); n].join(", ")
        )
    };
    let spec = VerifySpec::parse(&format!(
        "name = \"g1-n{n}\"\nscheme = \"nurds\"\nvalence = {n}\n{text}properties = [\"g1\"]\nmin_width = {min_width:?}\ntime_budget = {budget:?}\nsymmetry = \"{}\"\n",
        symmetry.as_str()
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let out = run(&spec, &Limits::default());
    let s = summary(&spec, &out);
    let g1 = s.volume_fraction.get("g1").copied().unwrap_or(0.0);
    let mut open: Vec<_> = out
        .cells
        .iter()
        .filter(|c| {
            c.status
                .iter()
                .any(|(p, st)| *p == Property::G1 && matches!(st.as_str(), "undecided" | "refuted"))
        })
        .collect();
    open.sort_by(|a, b| b.volume().total_cmp(&a.volume()));
    let mut found: BTreeMap<&str, (usize, f64)> = BTreeMap::new();
    let mut first = Vec::new();
    let total: f64 = match &spec.region {
        Region::Ratios { lo, hi } | Region::Corners { lo, hi, .. } => {
            lo.iter().zip(hi).map(|(a, b)| b - a).product()
        }
        Region::Shape { .. } => 1.0,
    };
    for (k, c) in open.iter().take(witness_cells).enumerate() {
        if let Some(w) = g1_witness(&c.lo, &c.hi, 16, k as u64) {
            let e = found.entry(w.failure.as_str()).or_insert((0, 0.0));
            e.0 += 1;
            e.1 += c.volume() / total;
            if first.len() < 3 {
                first.push(w);
            }
        }
    }
    println!(
        "n={n} {} [{lo:?}, {hi:?}] min_width={min_width} symmetry={}: g1 {}{:.4}% of the volume, {} cells ({} evaluated, {} by symmetry), {:.1} s wall, stopped {:?}; witnesses in {} of the {} largest open cells: {:?}",
        if corners { "corners" } else { "ratios" },
        symmetry.as_str(),
        if symmetry == Symmetry::None { "" } else { "at least " },
        100.0 * g1,
        s.cells,
        s.evaluated,
        out.by_symmetry,
        s.seconds,
        s.stopped,
        found.values().map(|v| v.0).sum::<usize>(),
        witness_cells.min(open.len()),
        found
    );
    for w in first {
        println!("  witness {:?}: {}", w.ratios, w.failure.as_str());
    }
    if args.iter().any(|a| a == "levels") {
        print_levels(&out, &spec, total);
    }
}

/// The per-level table of `levels`: a level's nodes are its final cells and
/// the cells split there (half the nodes of the next level); the evaluated
/// ones are the nodes less the cells left to the symmetry and, on the last
/// level, the ones the time budget left unevaluated.
fn print_levels(out: &subdiv_lab::verify::Outcome, spec: &VerifySpec, total: f64) {
    let deepest = out.cells.iter().map(|c| c.level).max().unwrap_or(0) as usize;
    let k = spec.symmetry.order(spec.valence()) as f64;
    let mut finals = vec![[0u64; 3]; deepest + 2]; // g1, open, by_symmetry
    let mut open_share = vec![0.0; deepest + 2];
    for c in &out.cells {
        let l = c.level as usize;
        let slot = match c.verdict() {
            "g1" => 0,
            "by_symmetry" => 2,
            _ => 1,
        };
        finals[l][slot] += 1;
        if slot == 1 {
            open_share[l] += k * spec.symmetry.domain_volume(&c.lo, &c.hi) / total;
        }
    }
    let mut nodes = vec![0u64; deepest + 2];
    for l in (0..=deepest).rev() {
        nodes[l] = finals[l].iter().sum::<u64>() + nodes[l + 1] / 2;
    }
    println!("level evaluated g1 open by_symmetry open_share");
    for l in 0..=deepest {
        let mut evaluated = nodes[l] - finals[l][2];
        if l == deepest {
            evaluated -= out.unevaluated;
        }
        println!(
            "{l} {evaluated} {} {} {} {:.5}",
            finals[l][0], finals[l][1], finals[l][2], open_share[l]
        );
    }
}
