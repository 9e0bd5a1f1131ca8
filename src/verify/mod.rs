//! Proofs over regions (math doc section 15): certified verdicts
//! for whole boxes of edge ratios (NURDS) and intervals of `c` (the
//! shape-adjustable Catmull-Clark scheme), by branch and bound.
//!
//! Each cell gets a rigorous enclosure of the eigenvalues that holds for
//! every parameter in it ([`enclose`] for NURDS: the closed 2 x 2 form for
//! `n = 3, 4`, Gershgorin discs in the eigenvector basis above; [`cc`] for the `c` path), in
//! interval arithmetic with outward rounding ([`interval`]); [`decide`] turns
//! the enclosure into verdicts; [`charmap`] proves the characteristic map
//! regular and injective over the cell. A cell whose requested properties are not all
//! decided is bisected across its widest side, down to `min_width`; what is
//! still open there is `undecided`, and so is a cell left unevaluated when
//! the spec's `time_budget` runs out (checked before every cell, so a run
//! stops within one cell's evaluation of its budget). Bisection points are floats strictly
//! inside their cells, so the cells tile the box exactly. With a spec
//! `symmetry` ([`symmetry`]), a cell whose interior does not meet the
//! group's fundamental domain is neither evaluated nor refined: it is a
//! final cell with the status `by_symmetry`; the others are evaluated with
//! the most volume in the domain first, and the summary's fractions are
//! bounds over the whole box through the group ([`summary`]).
//!
//! ```
//! use subdiv_lab::verify::{run, spec::VerifySpec, Limits};
//! let spec = VerifySpec::parse(
//!     "scheme = \"nurds\"\nvalence = 3\nbox = [[0.3, 0.4], [0.3, 0.4], [0.3, 0.4]]\nproperties = [\"class\", \"separation\"]\n",
//! ).unwrap();
//! let out = run(&spec, &Limits::default());
//! assert!(out.cells.iter().all(|c| c.verdict() == "complex_pair"));
//! ```

// Negated float comparisons (`!(x < bound)`) are deliberate throughout: a NaN
// makes them true, so a NaN never certifies anything.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod cc;
pub mod charmap;
pub mod decide;
pub mod enclose;
pub mod factor;
pub mod interval;
pub mod invariants;
pub mod spec;
pub mod symmetry;
pub mod taylor;
pub mod taylor2;
pub mod witness;

use crate::spectral::ClassName;
use decide::Status;
pub use enclose::Tamper;
use rayon::prelude::*;
use serde::Serialize;
use spec::{Property, Region, VerifySpec};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Default cap on the number of cells evaluated.
pub const DEFAULT_MAX_CELLS: u64 = 4_000_000;

/// A level's cells are evaluated in this many consecutive chunks (each in
/// parallel on the rayon pool), so that a time budget running out within a
/// level leaves the last cells of the level's order unevaluated rather than
/// the tail of every thread's share. A scheduling choice, never a verdict:
/// 64 chunks keep each chunk hundreds of cells wide (tens of milliseconds
/// and more) on the levels where a budget runs out.
const EVALUATION_CHUNKS: usize = 64;

/// The fewest cells in a chunk of [`EVALUATION_CHUNKS`], so that the small
/// levels still run in parallel.
const MIN_CHUNK: usize = 64;

/// Checks a cap on the evaluated cells: at least 1 (the message names the
/// argument as `spelling` spells it).
pub fn check_max_cells(max_cells: u64, spelling: crate::budget::Spelling) -> Result<(), String> {
    if max_cells == 0 {
        return Err(format!(
            "{} must be at least 1, got 0",
            spelling.arg("max_cells")
        ));
    }
    Ok(())
}

/// Limits of one run (besides the spec's `min_width` and `time_budget`).
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// At most this many cells are evaluated; refinement stops before a
    /// level that would exceed it (the open cells stay `undecided`).
    pub max_cells: u64,
    /// Test hook: deliberately weakens the enclosure (never set by the CLI).
    #[doc(hidden)]
    pub tamper: Tamper,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_cells: DEFAULT_MAX_CELLS,
            tamper: Tamper::None,
        }
    }
}

/// The work estimate of [`run`] of `spec` with at most `max_cells` evaluated
/// cells on `threads` threads: [`crate::budget::verify_charmap`] when the
/// spec asks for the `charmap` or the `g1` property, else [`crate::budget::verify`]
/// (the spec's `time_budget` caps the time).
pub fn estimate(spec: &VerifySpec, max_cells: u64, threads: usize) -> crate::budget::Estimate {
    let estimate_fn = if spec.properties.contains(&Property::Charmap)
        || spec.properties.contains(&Property::G1)
    {
        crate::budget::verify_charmap
    } else {
        crate::budget::verify
    };
    estimate_fn(
        spec.valence(),
        spec.scheme() == "nurds",
        max_cells,
        spec.time_budget,
        threads,
    )
}

/// The verdicts of one cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Lower corner.
    pub lo: Vec<f64>,
    /// Upper corner.
    pub hi: Vec<f64>,
    /// Bisection depth (0 = the whole box).
    pub level: u32,
    /// The class when the class property is requested and proven.
    pub class: Option<ClassName>,
    /// One status per requested property (spec order).
    pub status: Vec<(Property, Status)>,
}

impl Cell {
    /// The `verdict` column: `by_symmetry` for a cell outside the
    /// fundamental domain of the spec's symmetry (never evaluated); `g1`
    /// when the `g1` property is requested and certified (whatever class or classes the cell holds); else the class
    /// name when `class` is requested (or `undecided`); otherwise `certified`
    /// when every property holds, `refuted` when one fails and none is open,
    /// else `undecided`.
    pub fn verdict(&self) -> &'static str {
        if self.by_symmetry() {
            return "by_symmetry";
        }
        if self
            .status
            .iter()
            .any(|(p, s)| *p == Property::G1 && *s == Status::Certified)
        {
            return "g1";
        }
        if self.status.iter().any(|(p, _)| *p == Property::Class) {
            return self.class.map_or("undecided", ClassName::as_str);
        }
        if self.status.iter().all(|(_, s)| *s == Status::Certified) {
            "certified"
        } else if self.status.iter().any(|(_, s)| *s == Status::Undecided) {
            "undecided"
        } else {
            "refuted"
        }
    }

    /// Whether the cell was left to the symmetry (outside the fundamental
    /// domain, never evaluated).
    pub fn by_symmetry(&self) -> bool {
        self.status.iter().any(|(_, s)| *s == Status::BySymmetry)
    }

    /// The cell's volume (product of the side lengths, in `f64`).
    pub fn volume(&self) -> f64 {
        self.lo.iter().zip(&self.hi).map(|(a, b)| b - a).product()
    }
}

/// Why refinement stopped early (cells left open are `undecided`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// The spec's `time_budget` ran out (checked before every cell: the
    /// cells of the level not yet evaluated then stay whole and
    /// `undecided`).
    TimeBudget,
    /// The next level would exceed `max_cells`.
    MaxCells,
}

/// The result of a run.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The final cells (a tiling of the box).
    pub cells: Vec<Cell>,
    /// Cells evaluated (leaves and inner nodes).
    pub evaluated: u64,
    /// Final cells that were never evaluated: the time budget ran out
    /// within their level (they are `undecided`). Cells left to the
    /// symmetry are not counted here.
    pub unevaluated: u64,
    /// Final cells left to the symmetry (`by_symmetry`: outside the
    /// fundamental domain, never evaluated).
    pub by_symmetry: u64,
    /// Why refinement stopped early, if it did.
    pub stopped: Option<Stop>,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// Whether a property can be attempted for this region (the others stay
/// `undecided` without driving the refinement).
fn attempted(region: &Region, p: Property) -> bool {
    !matches!((region, p), (Region::Shape { .. }, Property::Theorem1))
}

/// A cell's class (when proven), the status of each requested property and,
/// when the enclosure knows it, each parameter's share of the uncertainty
/// (the split coordinate is chosen by it).
type Evaluation = (Option<ClassName>, Vec<(Property, Status)>, Option<Vec<f64>>);

/// A cell's lower and upper corners.
type Corners = (Vec<f64>, Vec<f64>);

/// Evaluates one cell.
fn evaluate(
    spec: &VerifySpec,
    family: Option<&enclose::AffineFamily>,
    charpoly: Option<&factor::CharPoly>,
    tree: Option<&invariants::Tree>,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Evaluation {
    // the spectral enclosure is needed by every property but g1 and theorem1
    let spectral = spec.properties.iter().any(|p| {
        matches!(
            p,
            Property::Class | Property::Separation | Property::Charmap
        )
    });
    let (separation, class, scores) = match (&spec.region, family) {
        _ if !spectral => (Status::Undecided, None, None),
        (Region::Ratios { .. } | Region::Corners { .. }, Some(f)) if f.dim() == 2 => {
            match enclose::decide_2x2(f, lo, hi, tamper) {
                Some((v, scores)) => (v.separation, v.class, scores),
                None => (Status::Undecided, None, None),
            }
        }
        (Region::Ratios { .. } | Region::Corners { .. }, Some(f)) => {
            // the invariant route, the factor route, the disc route: the
            // first that applies
            match tree
                .and_then(|t| t.decide(lo, hi, tamper))
                .or_else(|| charpoly.and_then(|p| factor::decide(p, f, lo, hi, tamper)))
            {
                Some((v, scores)) => (v.separation, v.class, scores),
                None => match enclose::enclose(f, lo, hi, tamper) {
                    Some(e) => {
                        let v = decide::decide_either(&e.rows, &e.cols);
                        (v.separation, v.class, Some(e.scores))
                    }
                    None => (Status::Undecided, None, None),
                },
            }
        }
        (Region::Shape { valence, .. }, _) => {
            let (s, c) = cc::verdict(*valence, lo[0], hi[0]);
            (s, c, None)
        }
        _ => (Status::Undecided, None, None),
    };
    // the characteristic map over the cell (math doc section 15), only when requested
    let (charmap, charmap_scores) = if spec.properties.contains(&Property::Charmap) {
        let ct = match tamper {
            Tamper::DropSubspaceVariation => charmap::CellTamper::DropSubspaceVariation,
            _ => charmap::CellTamper::None,
        };
        charmap::cell_status(&spec.region, class, lo, hi, ct)
    } else {
        (Status::Undecided, None)
    };
    // the class-free g1 certificate (math doc section 15, "G1 over a cell")
    let (g1, g1_scores) = if spec.properties.contains(&Property::G1) {
        let ct = match tamper {
            Tamper::ShrinkStewartRadius => charmap::CellTamper::ShrinkStewartRadius,
            _ => charmap::CellTamper::None,
        };
        charmap::g1_status(&spec.region, lo, hi, ct)
    } else {
        (Status::Undecided, None)
    };
    // once the spectral part is decided, the open charmap drives the split;
    // an open g1 drives it when no spectral property is open
    let scores = if charmap == Status::Undecided
        && class.is_some()
        && separation != Status::Undecided
        && charmap_scores.is_some()
    {
        charmap_scores
    } else if g1 == Status::Undecided
        && g1_scores.is_some()
        && (!spectral || (class.is_some() && separation != Status::Undecided))
    {
        g1_scores
    } else {
        scores
    };
    let status = spec
        .properties
        .iter()
        .map(|&p| {
            let s = match p {
                Property::Class => {
                    if class.is_some() {
                        Status::Certified
                    } else {
                        Status::Undecided
                    }
                }
                Property::Separation => separation,
                // Theorem 1 holds for every ratio vector in (0, 1)^n (math doc
                // section 5): the box lies in (0, 1)^n (checked by the spec).
                Property::Theorem1 => match spec.region {
                    Region::Ratios { .. } | Region::Corners { .. } => Status::Certified,
                    Region::Shape { .. } => Status::Undecided,
                },
                Property::Charmap => charmap,
                Property::G1 => g1,
            };
            (p, s)
        })
        .collect();
    (class, status, scores)
}

/// The evaluation of a cell that was never evaluated (the time budget ran
/// out): no class, every property `undecided` except Theorem 1, which holds
/// on every ratio box without any evaluation (as in [`evaluate`]).
fn not_evaluated(spec: &VerifySpec) -> Evaluation {
    let status = spec
        .properties
        .iter()
        .map(|&p| {
            let s = match (p, &spec.region) {
                (Property::Theorem1, Region::Ratios { .. } | Region::Corners { .. }) => {
                    Status::Certified
                }
                _ => Status::Undecided,
            };
            (p, s)
        })
        .collect();
    (None, status, None)
}

fn decided(spec: &VerifySpec, class: Option<ClassName>, status: &[(Property, Status)]) -> bool {
    status.iter().all(|&(p, s)| {
        !attempted(&spec.region, p)
            || match p {
                Property::Class => class.is_some(),
                _ => s != Status::Undecided,
            }
    })
}

/// The coordinate to bisect and the bisection point, or `None` when the
/// cell is not split: only sides wider than `min_width` whose float midpoint
/// lies strictly inside are candidates (so a cell whose widest side is at
/// most `min_width` is never split, and the halves tile the cell). Among the
/// candidates, the one with the largest uncertainty share `scores[k]` (from
/// the enclosure) is chosen, ties and missing scores going to the widest side
/// and then the lowest index. The choice affects only efficiency, never a
/// verdict. With `log_split` (corner-interval boxes) the bisection point is
/// the ratio at the midpoint of the log ratio `ln((1 - r) / r)` when that
/// float lies strictly inside, else the ordinary midpoint. With a
/// symmetry `group`, a candidate whose cut leaves one half with its interior
/// outside the fundamental domain (that half is `by_symmetry` at once,
/// never evaluated) goes before the others.
fn split_coordinate(
    a: &[f64],
    b: &[f64],
    scores: Option<&[f64]>,
    min_width: f64,
    log_split: bool,
    group: symmetry::Symmetry,
) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64, bool, f64, f64)> = None; // (k, mid, free, score, width)
    for k in 0..a.len() {
        let w = b[k] - a[k];
        let mut mid = 0.5 * a[k] + 0.5 * b[k];
        if log_split {
            // the midpoint of the log ratio t = ln((1 - r) / r): any float
            // strictly inside tiles the cell, so rounding is harmless
            let g = (((1.0 - a[k]) / a[k]) * ((1.0 - b[k]) / b[k])).sqrt();
            let m = 1.0 / (1.0 + g);
            if a[k] < m && m < b[k] {
                mid = m;
            }
        }
        if !(w > min_width && a[k] < mid && mid < b[k]) {
            continue;
        }
        let sc = scores
            .and_then(|s| s.get(k).copied())
            .filter(|x| x.is_finite())
            .unwrap_or(0.0);
        let free = group != symmetry::Symmetry::None && {
            let mut upper = b.to_vec();
            upper[k] = mid;
            let mut lower = a.to_vec();
            lower[k] = mid;
            !group.meets_domain(a, &upper) || !group.meets_domain(&lower, b)
        };
        let better = match best {
            None => true,
            Some((_, _, bf, bs, bw)) => {
                (free && !bf) || (free == bf && (sc > bs || (sc == bs && w > bw)))
            }
        };
        if better {
            best = Some((k, mid, free, sc, w));
        }
    }
    best.map(|(k, mid, _, _, _)| (k, mid))
}

/// Runs the branch and bound (parallel over the cells of a level on the
/// current rayon pool; the result does not depend on the thread count).
pub fn run(spec: &VerifySpec, limits: &Limits) -> Outcome {
    let start = Instant::now();
    let family = match spec.region {
        Region::Ratios { .. } | Region::Corners { .. } => {
            Some(enclose::AffineFamily::nurds(spec.valence()))
        }
        Region::Shape { .. } => None,
    };
    let (lo, hi) = spec.bounds();
    // the spectral routes' set-up only when a spectral property is asked for
    let spectral = spec.properties.iter().any(|p| {
        matches!(
            p,
            Property::Class | Property::Separation | Property::Charmap
        )
    });
    let charpoly = family
        .as_ref()
        .filter(|_| spectral)
        .and_then(factor::CharPoly::new);
    let invariants = charpoly.as_ref().and_then(invariants::Invariants::new);
    let tree = invariants
        .as_ref()
        .filter(|inv| inv.count() <= invariants::MAX_TREE_INVARIANTS)
        .and_then(|inv| invariants::Tree::new(inv, &lo, &hi));
    let log_split = matches!(spec.region, Region::Corners { .. });
    let mut frontier: Vec<(Vec<f64>, Vec<f64>)> = vec![(lo, hi)];
    let mut cells = Vec::new();
    let mut evaluated: u64 = 0;
    let mut stopped = None;
    let mut level: u32 = 0;
    let mut unevaluated: u64 = 0;
    let mut by_symmetry: u64 = 0;
    // the time budget, checked before every cell (one clock read, tens of
    // nanoseconds against microseconds to milliseconds per cell): once it
    // has run out, the remaining cells of the level are not evaluated
    let deadline = spec
        .time_budget
        .and_then(|t| start.checked_add(Duration::try_from_secs_f64(t).ok()?));
    let expired = AtomicBool::new(false);
    let out_of_time = || {
        if expired.load(Ordering::Relaxed) {
            return true;
        }
        let late = deadline.is_some_and(|d| Instant::now() >= d);
        if late {
            expired.store(true, Ordering::Relaxed);
        }
        late
    };
    while !frontier.is_empty() {
        // a cell whose interior misses the fundamental domain is final,
        // never evaluated
        if spec.symmetry != symmetry::Symmetry::None {
            let (keep, skip): (Vec<_>, Vec<_>) = frontier
                .into_iter()
                .partition(|(a, b)| spec.symmetry.meets_domain(a, b));
            by_symmetry += skip.len() as u64;
            cells.extend(skip.into_iter().map(|(a, b)| {
                Cell {
                    lo: a,
                    hi: b,
                    level,
                    class: None,
                    status: spec
                        .properties
                        .iter()
                        .map(|&p| (p, Status::BySymmetry))
                        .collect(),
                }
            }));
            frontier = keep;
            if frontier.is_empty() {
                break;
            }
        }
        // with a symmetry, the cells with the most volume in the fundamental
        // domain first (stable, so the order does not depend on the thread
        // count): when the time budget runs out within the level, the cells
        // left unevaluated are those that weigh least in the bound
        if spec.symmetry != symmetry::Symmetry::None {
            let mut keyed: Vec<(f64, Corners)> = frontier
                .into_iter()
                .map(|(a, b)| (spec.symmetry.domain_volume(&a, &b), (a, b)))
                .collect();
            keyed.sort_by(|x, y| y.0.total_cmp(&x.0));
            frontier = keyed.into_iter().map(|(_, c)| c).collect();
        }
        // evaluated in consecutive chunks (each in parallel), so that the
        // cells a budget leaves unevaluated are the last ones of the order
        let chunk = (frontier.len() / EVALUATION_CHUNKS).max(MIN_CHUNK);
        let mut results: Vec<Option<Evaluation>> = Vec::with_capacity(frontier.len());
        for part in frontier.chunks(chunk) {
            results.par_extend(part.par_iter().map(|(a, b)| {
                if out_of_time() {
                    return None;
                }
                Some(evaluate(
                    spec,
                    family.as_ref(),
                    charpoly.as_ref(),
                    tree.as_ref(),
                    a,
                    b,
                    limits.tamper,
                ))
            }));
        }
        let skipped = results.iter().filter(|r| r.is_none()).count();
        if skipped > 0 {
            stopped.get_or_insert(Stop::TimeBudget);
        }
        unevaluated += skipped as u64;
        evaluated += (frontier.len() - skipped) as u64;
        // a cell not evaluated is open on every property it attempts
        let results: Vec<Evaluation> = results
            .into_iter()
            .map(|r| r.unwrap_or_else(|| not_evaluated(spec)))
            .collect();
        let splittable = |a: &[f64], b: &[f64], scores: Option<&Vec<f64>>| {
            split_coordinate(
                a,
                b,
                scores.map(Vec::as_slice),
                spec.min_width,
                log_split,
                spec.symmetry,
            )
        };
        let open: usize = frontier
            .iter()
            .zip(&results)
            .filter(|((a, b), (c, s, sc))| {
                !decided(spec, *c, s) && splittable(a, b, sc.as_ref()).is_some()
            })
            .count();
        if open > 0 && stopped.is_none() {
            if evaluated + 2 * open as u64 > limits.max_cells {
                stopped = Some(Stop::MaxCells);
            } else if out_of_time() {
                stopped = Some(Stop::TimeBudget);
            }
        }
        let mut next = Vec::with_capacity(2 * open);
        for ((a, b), (class, status, scores)) in frontier.into_iter().zip(results) {
            let split = if stopped.is_none() && !decided(spec, class, &status) {
                splittable(&a, &b, scores.as_ref())
            } else {
                None
            };
            match split {
                Some((k, mid)) => {
                    let mut b1 = b.clone();
                    b1[k] = mid;
                    let mut a2 = a.clone();
                    a2[k] = mid;
                    next.push((a, b1));
                    next.push((a2, b));
                }
                None => cells.push(Cell {
                    lo: a,
                    hi: b,
                    level,
                    class,
                    status,
                }),
            }
        }
        frontier = next;
        level += 1;
    }
    Outcome {
        cells,
        evaluated,
        unevaluated,
        by_symmetry,
        stopped,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The CSV columns' names: `lo0..`, `hi0..` (or `c_lo, c_hi`), `verdict`,
/// one per property.
pub fn csv_header(spec: &VerifySpec) -> Vec<String> {
    let mut h = Vec::new();
    match spec.region {
        Region::Ratios { .. } | Region::Corners { .. } => {
            let n = spec.valence();
            h.extend((0..n).map(|i| format!("lo{i}")));
            h.extend((0..n).map(|i| format!("hi{i}")));
        }
        Region::Shape { .. } => {
            h.push("c_lo".to_owned());
            h.push("c_hi".to_owned());
        }
    }
    h.push("verdict".to_owned());
    h.extend(spec.properties.iter().map(|p| p.as_str().to_owned()));
    h
}

/// `cells.csv` as text (end points in shortest round-trip form, so they
/// parse back to the exact floats of the cells).
pub fn cells_csv(spec: &VerifySpec, outcome: &Outcome) -> String {
    let mut s = csv_header(spec).join(",");
    s.push('\n');
    for c in &outcome.cells {
        let mut row: Vec<String> = c.lo.iter().chain(&c.hi).map(|x| format!("{x:?}")).collect();
        row.push(c.verdict().to_owned());
        row.extend(c.status.iter().map(|(_, st)| st.as_str().to_owned()));
        s.push_str(&row.join(","));
        s.push('\n');
    }
    s
}

/// `summary.json`'s content.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// `"subdiv-lab"`.
    pub tool: &'static str,
    /// `"verify"`.
    pub command: &'static str,
    /// Spec name.
    pub name: String,
    /// Scheme.
    pub scheme: &'static str,
    /// Valence.
    pub valence: usize,
    /// The box, one `[lo, hi]` per coordinate (`c` for the shape path).
    pub r#box: Vec<[f64; 2]>,
    /// Properties.
    pub properties: Vec<Property>,
    /// `min_width` of the spec.
    pub min_width: f64,
    /// Final cells.
    pub cells: usize,
    /// Cells evaluated, including the ones that were split.
    pub evaluated: u64,
    /// Final cells never evaluated because the time budget ran out within
    /// their level (counted as `undecided`; cells left to the symmetry are
    /// not counted).
    pub unevaluated: u64,
    /// The symmetry group the fractions go through: `"none"`,
    /// `"rotations"` or `"dihedral"`.
    pub symmetry: symmetry::Symmetry,
    /// Its order `k`: `1`, `n` or `2n`.
    pub group_order: usize,
    /// Final cells per verdict (`by_symmetry`: left to the symmetry).
    pub counts: BTreeMap<String, usize>,
    /// Volume fraction of the box per verdict. Without symmetry: the share
    /// of the cells of that verdict. With symmetry (`k` the group order,
    /// `V` the box's volume, `D` the fundamental domain, sums over the
    /// evaluated cells `C`, which are the ones meeting `D`, of an upper bound
    /// of `vol(C cap D)` ([`symmetry::Symmetry::domain_volume`]); math doc
    /// section 15, "Symmetry of the ratio box"): for a proven verdict (a
    /// class, `certified`, `g1`) the lower bound `max(0, 1 - k sum
    /// vol(C cap D) / V)` over the evaluated cells of another verdict on the
    /// share of the box where it holds; for `undecided` and `refuted` the
    /// upper bound `min(1, k sum vol(C cap D) / V)` over its cells;
    /// `by_symmetry` cells have no entry.
    pub volume_fraction: BTreeMap<String, f64>,
    /// Volume fraction of `undecided` cells (with symmetry: the upper bound
    /// above).
    pub undecided_fraction: f64,
    /// Per property: volume fraction per status (with symmetry: a lower
    /// bound for `certified`, upper bounds for `refuted` and `undecided`, as
    /// in `volume_fraction`).
    pub property_volume_fraction: BTreeMap<String, BTreeMap<String, f64>>,
    /// Deepest bisection level among the final cells.
    pub deepest_level: u32,
    /// Why refinement stopped early (`null`: it did not): `"time_budget"`
    /// or `"max_cells"`.
    pub stopped: Option<Stop>,
    /// Wall time of the refinement, seconds.
    pub seconds: f64,
}

/// Whether a verdict or status word is an open one (the other words,
/// except `by_symmetry`, are proven statements about every point of a cell).
fn open_word(w: &str) -> bool {
    w == "undecided" || w == "refuted"
}

/// The fraction of the box for one verdict or status word with a symmetry
/// group of order `k` ([`Summary::volume_fraction`]): `own` the volume of
/// the evaluated cells with that word, `evaluated` the volume of all the
/// evaluated cells, both divided by the box's volume.
fn through_group(word: &str, own: f64, evaluated: f64, k: f64) -> f64 {
    if open_word(word) {
        (k * own).min(1.0)
    } else {
        (1.0 - k * (evaluated - own)).max(0.0)
    }
}

/// Builds the summary of a run.
pub fn summary(spec: &VerifySpec, outcome: &Outcome) -> Summary {
    let (lo, hi) = spec.bounds();
    let total: f64 = lo.iter().zip(&hi).map(|(a, b)| b - a).product();
    let mut counts = BTreeMap::new();
    let mut vol: BTreeMap<String, f64> = BTreeMap::new();
    let mut pvol: BTreeMap<String, BTreeMap<String, f64>> = BTreeMap::new();
    for p in &spec.properties {
        let e = pvol.entry(p.as_str().to_owned()).or_default();
        for s in ["certified", "refuted", "undecided"] {
            e.insert(s.to_owned(), 0.0);
        }
    }
    let mut deepest = 0;
    let mut evaluated_volume = 0.0;
    for c in &outcome.cells {
        *counts.entry(c.verdict().to_owned()).or_insert(0) += 1;
        deepest = deepest.max(c.level);
        if c.by_symmetry() {
            continue;
        }
        // with a symmetry, only the part in the fundamental domain counts
        // (an upper bound of it, "Symmetry of the ratio box", the clipped bound)
        let v = if spec.symmetry == symmetry::Symmetry::None {
            c.volume() / total
        } else {
            spec.symmetry.domain_volume(&c.lo, &c.hi) / total
        };
        evaluated_volume += v;
        *vol.entry(c.verdict().to_owned()).or_insert(0.0) += v;
        for (p, s) in &c.status {
            *pvol
                .entry(p.as_str().to_owned())
                .or_default()
                .entry(s.as_str().to_owned())
                .or_insert(0.0) += v;
        }
    }
    let group_order = spec.symmetry.order(spec.valence());
    if spec.symmetry != symmetry::Symmetry::None {
        let k = group_order as f64;
        for (w, f) in vol.iter_mut() {
            *f = through_group(w, *f, evaluated_volume, k);
        }
        for m in pvol.values_mut() {
            for (w, f) in m.iter_mut() {
                *f = through_group(w, *f, evaluated_volume, k);
            }
        }
    }
    Summary {
        tool: "subdiv-lab",
        command: "verify",
        name: spec.name.clone(),
        scheme: spec.scheme(),
        valence: spec.valence(),
        r#box: lo.iter().zip(&hi).map(|(a, b)| [*a, *b]).collect(),
        properties: spec.properties.clone(),
        min_width: spec.min_width,
        cells: outcome.cells.len(),
        evaluated: outcome.evaluated,
        unevaluated: outcome.unevaluated,
        symmetry: spec.symmetry,
        group_order,
        undecided_fraction: vol.get("undecided").copied().unwrap_or(0.0),
        counts,
        volume_fraction: vol,
        property_volume_fraction: pvol,
        deepest_level: deepest,
        stopped: outcome.stopped,
        seconds: outcome.seconds,
    }
}

#[cfg(test)]
mod tests;
