//! The generic C1 certificate: regularity and injectivity of the
//! characteristic map of any vertex-centred scheme from its local matrix, the
//! labelled neighbourhood and the regular part's rules (math doc section 20;
//! the method is Zorin's, SIAM J. Numer. Anal. 37(5), 2000).
//!
//! What a scheme provides ([`crate::schemes::Scheme`]): its labelled local
//! matrix ([`Scheme::local_matrix`]) and its own configuration at the regular
//! valence ([`Scheme::regular_configuration`]), from whose local matrix the
//! regular mask is read. Nothing else: a scheme from a file or from Python
//! gets the certificate through the same two methods. Contract: every point
//! outside the local matrix's neighbourhood follows the regular rules.
//!
//! Stages (one file each):
//!
//! 1. [`layout`]: the labelled neighbourhood as a sector grid and the charts
//!    on which the regular lattice applies;
//! 2. [`mask`]: the regular mask, its derivative and difference schemes by
//!    exact division of the symbol, their contraction; for rules of
//!    dilation 3 (sqrt(3)'s two steps) [`matrix_mask`]: the matrix difference
//!    schemes that prove the regular part C1 and enclose the derivatives
//!    (math doc 20.9; the later stages take the dilation as a parameter:
//!    ternary nets and cells);
//! 3. [`net`]: the subdominant eigenbasis on the neighbourhood (with
//!    Stewart's bound, [`crate::charmap::subspace_bound`]), its extension by the
//!    eigen-relation, and refinement in midpoint-radius arithmetic;
//! 4. [`cells`]: the Jacobian's sign on the cells of the annulus (convex-hull
//!    cones of the derivative schemes, or the norm and matrix enclosures,
//!    adaptive down to [`MAX_LEVEL`], [`levels`] for dilation 3) and the
//!    winding number.
//!
//! Verdicts ([`GenericVerdict`]): `c1` (standard eigenstructure, the
//! Jacobian certified of one sign on the whole annulus, winding number equal
//! to that sign), `not_c1` with a witness (two cells certified of opposite
//! signs, or a certified winding number other than the orientation), and
//! `indeterminate` with the reason otherwise (a non-standard
//! eigenstructure, rules the certificate cannot use, or bounds that do not
//! close by [`MAX_LEVEL`]).

pub mod cells;
pub mod layout;
pub mod mask;
pub mod matrix_mask;
pub mod net;
pub mod precondition;

use crate::charmap::{Eigenstructure, PlanarBasis};
use crate::error::Result;
use crate::schemes::Scheme;
use crate::spectral::{Subdominant, SubdominantClass};
use cells::{annulus, cell_sign, cell_sign_of, children, winding, Cell, CellSign, Patch, Values};
use layout::Lattice;
use net::{initial_net, neighbourhood_matrix, refine, Eigenvalue, LocalRows};
use num_complex::Complex64;

/// The first level whose annulus cells are tested (ring index `2^3 / 2 = 4`
/// at the inner boundary, so that the derivative windows of box-spline-size
/// masks stay off the centre); cells whose window still reaches the centre
/// are passed to the next level.
pub const FIRST_LEVEL: u32 = 3;

/// The deepest level of the adaptive Jacobian test and of the winding test
/// (the work limit: the net of level `m` has about `n 4^m` points).
pub const MAX_LEVEL: u32 = 8;

/// The deepest level of the local refinement of the cells still undecided
/// at [`MAX_LEVEL`] (each refined on a patch of its own,
/// [`cells::Patch`], at a cost independent of the level).
pub const MAX_LOCAL_LEVEL: u32 = 12;

/// The levels of rules of dilation `d` with the resolution of the dyadic
/// ones, `[first, max, local]`: the first level is the smallest `m` whose
/// annulus starts at ring index `d^(m - 1) >= 2^(FIRST_LEVEL - 1)` (so the
/// windows keep the dyadic distance from the centre), the deepest and the
/// local ones the largest `m` with `d^m <= 2^M` for `M` = [`MAX_LEVEL`],
/// [`MAX_LOCAL_LEVEL`] (so the cells are no smaller, and the nets no larger,
/// than the dyadic ones). Dilation 2: 3, 8, 12; dilation 3: 3, 5, 7.
pub fn levels(dilation: i64) -> [u32; 3] {
    let inner = 1i64 << (FIRST_LEVEL - 1);
    let mut first = 1u32;
    while dilation.pow(first - 1) < inner {
        first += 1;
    }
    let [max, local] = [MAX_LEVEL, MAX_LOCAL_LEVEL].map(|m| {
        let cap = 1i64 << m;
        let mut k = 0u32;
        while dilation.pow(k + 1) <= cap {
            k += 1;
        }
        k
    });
    [first, max, local]
}

/// Largest number of cells tested over all levels (work limit; a Jacobian
/// with a zero on the annulus keeps cells undecided at every level).
pub const MAX_CELLS: usize = 400_000;

/// The witness of a `not_c1` verdict.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Witness {
    /// The Jacobian is certified positive on one cell and negative on another.
    JacobianSignChange {
        /// A cell with a certified positive Jacobian.
        positive: Cell,
        /// A cell with a certified negative Jacobian.
        negative: Cell,
    },
    /// The map is regular with orientation `orientation`, and the image of the
    /// ring path winds `winding` times around the origin.
    Winding {
        /// The certified winding number.
        winding: i64,
        /// The sign of the Jacobian.
        orientation: i8,
    },
}

/// The verdict of the generic certificate.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum GenericVerdict {
    /// Standard eigenstructure, regular and injective characteristic map.
    C1,
    /// Not C1 for generic control points, with the witness.
    NotC1 {
        /// What shows it.
        witness: Witness,
    },
    /// The evidence does not decide.
    Indeterminate {
        /// Why.
        reason: String,
    },
}

impl GenericVerdict {
    /// `c1`, `not_c1` or `indeterminate`.
    pub fn code(&self) -> &'static str {
        match self {
            GenericVerdict::C1 => "c1",
            GenericVerdict::NotC1 { .. } => "not_c1",
            GenericVerdict::Indeterminate { .. } => "indeterminate",
        }
    }
}

impl std::fmt::Display for GenericVerdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GenericVerdict::C1 => f.write_str("C1 (standard; regular and injective characteristic map)"),
            GenericVerdict::NotC1 {
                witness: Witness::JacobianSignChange { positive, negative },
            } => write!(
                f,
                "not C1 (the Jacobian changes sign: positive on {positive}, negative on {negative})"
            ),
            GenericVerdict::NotC1 {
                witness: Witness::Winding { winding, orientation },
            } => write!(
                f,
                "not C1 (regular with orientation {orientation:+}, but the ring winds {winding} times around the origin)"
            ),
            GenericVerdict::Indeterminate { reason } => write!(f, "indeterminate ({reason})"),
        }
    }
}

/// The report of the generic certificate.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct GenericReport {
    /// The verdict.
    pub verdict: GenericVerdict,
    /// The regular lattice (`None` when the rules were not read).
    pub lattice: Option<Lattice>,
    /// The deepest level refined.
    pub level: Option<u32>,
    /// Cells tested over all levels.
    pub cells: usize,
    /// The sign of the Jacobian when every cell is certified of one sign.
    pub orientation: Option<i8>,
    /// The certified winding number of the ring path.
    pub winding_number: Option<i64>,
    /// Smallest lower bound of the relative Jacobian over the certified cells
    /// (oriented; `None` before any cell is certified).
    pub min_relative_jacobian: Option<f64>,
    /// Bound on the subdominant basis' entries (Stewart).
    pub vector_error: Option<f64>,
    /// Largest error radius of the finest net.
    pub point_error: Option<f64>,
    /// Contraction norms of the difference schemes and the power they hold at.
    pub contraction: Option<([[f64; 2]; 2], u32)>,
    /// The exact proof of the standard eigenstructure, where the
    /// floating-point class was not standard.
    pub class_proof: Option<precondition::ExactStandard>,
    /// The subdivision steps of the local matrix the verdict refers to, for a
    /// scheme whose local matrix covers several steps because one step turns
    /// the ring ([`Scheme::one_step_matrix`]; sqrt(3): 2, math doc section
    /// 21); `None` for one step.
    pub matrix_steps: Option<usize>,
}

impl GenericReport {
    fn indeterminate(reason: impl Into<String>) -> Self {
        Self {
            verdict: GenericVerdict::Indeterminate {
                reason: reason.into(),
            },
            lattice: None,
            level: None,
            cells: 0,
            orientation: None,
            winding_number: None,
            min_relative_jacobian: None,
            vector_error: None,
            point_error: None,
            contraction: None,
            class_proof: None,
            matrix_steps: None,
        }
    }

    /// The `"charmap"` JSON object of `--charmap generic`.
    pub fn to_json(&self) -> serde_json::Value {
        let witness = match &self.verdict {
            GenericVerdict::NotC1 { witness } => serde_json::to_value(witness).ok(),
            _ => None,
        };
        let reason = match &self.verdict {
            GenericVerdict::Indeterminate { reason } => Some(reason.clone()),
            _ => None,
        };
        let mut json = serde_json::json!({
            "method": "generic",
            "verdict": self.verdict.to_string(),
            "verdict_code": self.verdict.code(),
            "witness": witness,
            "reason": reason,
            "lattice": self.lattice,
            "level": self.level,
            "cells": self.cells,
            "orientation": self.orientation,
            "winding_number": self.winding_number,
            "min_relative_jacobian": self.min_relative_jacobian,
            "vector_error": self.vector_error,
            "point_error": self.point_error,
            "contraction_norms": self.contraction.map(|c| c.0),
            "contraction_power": self.contraction.map(|c| c.1),
        });
        if let Some(k) = self.matrix_steps {
            json["matrix_steps"] = serde_json::json!(k);
        }
        if let Some(e) = &self.class_proof {
            json["class_proof"] = serde_json::json!({
                "method": "exact",
                "threshold": e.threshold,
                "lambda_interval": e.lambda,
                "gap": e.gap,
            });
        }
        json
    }
}

/// Seconds per `d^3` of the certificate, `d` the dimension of the
/// neighbourhood matrix `S_1` (the separation's SVD of the `2 (d - 2)`
/// Kronecker matrix dominates above `n = 20`; the refinement is bounded by
/// [`MAX_LEVEL`] and [`MAX_CELLS`]). Measured 2.1e-8 (Catmull-Clark,
/// `n = 100`, `d = 601`: 4.5 s) on the 2-core reference machine under load;
/// rounded up.
pub const SECONDS_PER_DIM3: f64 = 4e-8;

/// Seconds of the refinement and the cell tests per unit of valence (bounded
/// by [`MAX_LEVEL`] and [`MAX_CELLS`]); measured and rounded up.
pub const SECONDS_PER_VALENCE: f64 = 0.05;

/// The work estimate of [`check`] for a front end's budget check: the
/// dimension of `S_1` is at most `1 + n (R + 1)^2` with `R` the ring radius
/// of the neighbourhood (2 for the built-in vertex-centred schemes).
pub fn estimate<S: Scheme + ?Sized>(scheme: &S) -> crate::budget::Estimate {
    estimate_for_valence(scheme.valence())
}

/// [`estimate`] at valence `n` (sweeps estimate whole shards from the
/// valences of their spec).
pub fn estimate_for_valence(n: usize) -> crate::budget::Estimate {
    let n = n as f64;
    let d = 1.0 + 6.0 * n;
    let k = 2.0 * d;
    crate::budget::Estimate {
        // the Kronecker matrix of the separation and its SVD workspace (4 copies)
        bytes: 4.0 * 8.0 * k * k,
        seconds: SECONDS_PER_DIM3 * d.powi(3) + SECONDS_PER_VALENCE * n,
        what: format!(
            "the generic certificate (a {0} x {0} separation SVD and the refined nets)",
            k.round()
        ),
    }
}

/// The `"charmap"` object of `--charmap generic`, or an indeterminate
/// verdict carrying the error.
pub fn report_json(r: &Result<GenericReport>) -> serde_json::Value {
    match r {
        Ok(r) => r.to_json(),
        Err(e) => serde_json::json!({
            "method": "generic",
            "verdict": format!("indeterminate (characteristic map not computed: {e})"),
            "verdict_code": "indeterminate",
            "error": e.to_string(),
        }),
    }
}

/// The generic certificate of one configuration, given its subdominant
/// classification (of the local matrix, which for sqrt(3) covers two steps:
/// the report's `matrix_steps` says so). Failures to build a scheme's
/// matrices are errors; every reason the certificate cannot decide is an
/// `indeterminate` verdict.
pub fn check<S: Scheme + ?Sized>(scheme: &S, sub: &Subdominant) -> Result<GenericReport> {
    let mut out = check_local(scheme, sub)?;
    out.matrix_steps = scheme.one_step_matrix().map(|(steps, _)| steps);
    Ok(out)
}

/// [`check`] without the steps of the local matrix.
fn check_local<S: Scheme + ?Sized>(scheme: &S, sub: &Subdominant) -> Result<GenericReport> {
    let lm = scheme.local_matrix()?;
    if let Some(label) = layout::face_centred_label(lm.rows()) {
        return Ok(GenericReport::indeterminate(format!(
            "face-centred neighbourhood (point {label}): the certificate's sector grid is centred on a vertex (math doc 20.6); the ring certificate (--charmap ring) decides {}",
            scheme.name()
        )));
    }
    let lambda = sub.lambda1.re;
    let (gap, class_proof) = match &sub.class {
        SubdominantClass::Standard => (sub.gap.min(1.0 - sub.lambda1.norm()), None),
        other => match exact_class(scheme, sub)? {
            Ok(e) => (e.gap, Some(e)),
            Err(why) => {
                return Ok(GenericReport::indeterminate(format!(
                    "subdominant class {}: the certificate decides C1 for a double real subdominant eigenvalue with a 2-D eigenspace (for a complex pair, analyse a power of the step whose pair is real){why}",
                    other.name()
                )))
            }
        },
    };
    let Some(regular) = scheme.regular_configuration() else {
        return Ok(GenericReport::indeterminate(format!(
            "scheme {} provides no regular configuration to read its regular rules from",
            scheme.name()
        )));
    };
    let regular = regular?;
    let rm = regular.local_matrix()?;
    let exact = regular.exact_local_matrix().transpose()?;
    let (lattice, symbol, dilation) = match mask::read_mask(&rm, exact.as_ref()) {
        Ok(x) => x,
        Err(reason) => return Ok(GenericReport::indeterminate(reason)),
    };
    let rules = match mask::rules_of(lattice, &symbol, dilation) {
        Ok(r) => r,
        Err(reason) => {
            let mut r = GenericReport::indeterminate(reason);
            r.lattice = Some(lattice);
            return Ok(r);
        }
    };
    let local = match LocalRows::new(&lm) {
        Ok(l) => l,
        Err(reason) => return Ok(GenericReport::indeterminate(reason)),
    };
    let mut out = certify(&rules, &local, scheme.valence(), lambda, gap);
    out.class_proof = class_proof;
    Ok(out)
}

/// The exact precondition ([`precondition::exact_standard`]) for a
/// configuration whose floating-point class is not standard: `Ok(Err(why))`
/// (`why` a clause for the verdict's reason, empty when the scheme has no
/// rational matrix) when it is not proven. The threshold is the midpoint of
/// the estimates of `lambda` and `|lambda_3|`.
fn exact_class<S: Scheme + ?Sized>(
    scheme: &S,
    sub: &Subdominant,
) -> Result<std::result::Result<precondition::ExactStandard, String>> {
    let Some(exact) = scheme.exact_local_matrix() else {
        return Ok(Err(String::new()));
    };
    let exact = exact?;
    let t = 0.5 * (sub.lambda1.norm() + sub.abs_lambda3);
    let turn = precondition::rotation(exact.rows(), scheme.valence());
    Ok(
        precondition::exact_standard_turned(exact.matrix(), t, turn.as_deref())
            .map_err(|e| format!("; exact test of the local matrix: {e}")),
    )
}

/// The characteristic map's level-0 control net with what refines it
/// (stages 1 to 3 of the module docs).
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The regular rules.
    pub rules: RegularRules,
    /// The local matrix on the sector grid.
    pub local: LocalRows,
    /// The level-0 net (extent `1 + margin`).
    pub net: net::Net,
    /// Level `j` holds the points of ring index at most `d^j + margin`
    /// (`d` the rules' dilation).
    pub margin: usize,
    /// Stewart's bound on the basis.
    pub vector_error: f64,
}

impl Prepared {
    /// The net refined from level `from` (held in `net`) to level `from + 1`.
    pub fn refine(&self, net: &net::Net, from: u32) -> net::Net {
        refine(
            net,
            &self.rules,
            &self.local,
            cells::steps(self.rules.dilation, from + 1) as usize + self.margin,
        )
    }
}

/// Stages 1 to 3 for one configuration: `Err` carries the reason the
/// certificate cannot go on (an `indeterminate` verdict), `Ok` the prepared
/// net; `lambda` is the subdominant eigenvalue and `gap` a lower bound of its
/// distance from the rest of the spectrum.
pub fn prepare(
    rules: &RegularRules,
    local: &LocalRows,
    n: usize,
    lambda: f64,
    gap: f64,
) -> std::result::Result<Prepared, String> {
    let lattice = rules.lattice;
    let radius_local = local.radius(lattice);
    let r_a = rules.radius as usize;
    let r1 = radius_local.max(r_a);
    let (points, s1) = neighbourhood_matrix(local, rules, n, r1)?;
    // the eigenspace: the two smallest singular vectors of S_1 - lambda I
    let d = s1.nrows();
    let shifted = &s1 - nalgebra::DMatrix::<f64>::identity(d, d) * lambda;
    let svd = shifted.svd(false, true);
    let vt = svd.v_t.ok_or("no singular vectors")?;
    let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
    order.sort_by(|a, b| svd.singular_values[*a].total_cmp(&svd.singular_values[*b]));
    let v1: Vec<f64> = vt.row(order[0]).iter().copied().collect();
    let v2: Vec<f64> = vt.row(order[1]).iter().copied().collect();
    let lam = Complex64::new(lambda, 0.0);
    let basis = PlanarBasis::new(&s1, Eigenstructure::Standard, [lam, lam], &v1, &v2, gap)
        .map_err(|e| format!("subdominant basis: {e}"))?;
    if !basis.vector_error.is_finite() {
        return Err("the subdominant subspace of the neighbourhood matrix is not certified (Stewart's hypothesis fails)".into());
    }
    // lambda* = m_11 + w1^T S e1 with |e1| <= vector_error (e1 orthogonal to w1)
    let st_w1 = s1.transpose() * nalgebra::DVector::from_column_slice(&basis.w1);
    let frob = s1.iter().map(|x| x * x).sum::<f64>().sqrt();
    let eig = Eigenvalue {
        value: basis.restriction[0][0],
        err: (st_w1.norm() * basis.vector_error + crate::charmap::regularity::gamma(2 * d) * frob)
            * (1.0 + crate::charmap::regularity::gamma(4)),
    };
    // the reach of a cell's enclosure past the cell: the derivative schemes'
    // windows (dilation 2), or the matrix enclosure's box (dilation 3)
    let b = match &rules.matrix {
        Some(mb) => [mb.box_of_window(); 2],
        None => rules.derivative_box,
    };
    let window = b
        .iter()
        .flat_map(|x| x.iter())
        .chain(rules.mask_box.iter())
        .map(|v| v.unsigned_abs() as usize)
        .max()
        .unwrap_or(0);
    // a cell's window reaches `window + 1` past the cell along each axis
    // (twice that in the ring index of triangles), plus one for the difference
    let margin = (r_a + 1).max(2 * window + 3).max(r1);
    let net = initial_net(
        rules,
        n,
        &points,
        [&basis.w1, &basis.w2],
        basis.vector_error,
        eig,
        1 + margin,
    )?;
    Ok(Prepared {
        rules: rules.clone(),
        local: local.clone(),
        net,
        margin,
        vector_error: basis.vector_error,
    })
}

/// Stages 1 to 3 for a scheme with a standard classification (for tests
/// and plots of the net): `Ok(Err(reason))` when the certificate cannot go
/// on.
pub fn prepare_scheme<S: Scheme + ?Sized>(
    scheme: &S,
    sub: &Subdominant,
) -> Result<std::result::Result<Prepared, String>> {
    if sub.class != SubdominantClass::Standard {
        return Ok(Err(format!("subdominant class {}", sub.class.name())));
    }
    let Some(regular) = scheme.regular_configuration() else {
        return Ok(Err("no regular configuration".into()));
    };
    let regular = regular?;
    let rm = regular.local_matrix()?;
    let exact = regular.exact_local_matrix().transpose()?;
    let local = LocalRows::new(&scheme.local_matrix()?);
    let gap = sub.gap.min(1.0 - sub.lambda1.norm());
    Ok(mask::read_mask(&rm, exact.as_ref())
        .and_then(|(lattice, symbol, dilation)| mask::rules_of(lattice, &symbol, dilation))
        .and_then(|rules| prepare(&rules, &local?, scheme.valence(), sub.lambda1.re, gap)))
}

/// The cells certified so far.
struct Tally {
    /// The first cell certified positive, and negative.
    signs: [Option<Cell>; 2],
    /// The smallest relative Jacobian bound per sign.
    min_rel: [f64; 2],
    /// Cells tested.
    cells: usize,
    /// The deepest level of the local refinement.
    deepest: u32,
}

impl Default for Tally {
    fn default() -> Self {
        Self {
            signs: [None; 2],
            min_rel: [f64::INFINITY; 2],
            cells: 0,
            deepest: 0,
        }
    }
}

impl Tally {
    /// Counts the cell and records its sign; `false` when undecided.
    fn record(&mut self, cell: Cell, cs: CellSign) -> bool {
        self.cells += 1;
        match cs.sign {
            1 => {
                self.signs[0].get_or_insert(cell);
                self.min_rel[0] = self.min_rel[0].min(cs.bounds[0]);
            }
            -1 => {
                self.signs[1].get_or_insert(cell);
                self.min_rel[1] = self.min_rel[1].min(-cs.bounds[1]);
            }
            _ => return false,
        }
        true
    }

    /// Both signs certified (the `not_c1` witness).
    fn both(&self) -> bool {
        self.signs[0].is_some() && self.signs[1].is_some()
    }
}

/// The children of an undecided `cell` tested on a patch of the next level
/// refined from `values` (the cell's level, in its sector chart), and their
/// undecided children likewise, down to [`MAX_LOCAL_LEVEL`]; cells left
/// undecided go to `still`. The patch covers the children's bounding box
/// plus the net's margin (which holds every window of a cell).
fn refine_locally(
    values: &Values,
    cell: Cell,
    rules: &RegularRules,
    prep: &Prepared,
    min_ring: i64,
    tally: &mut Tally,
    still: &mut Vec<Cell>,
) {
    let d = rules.dilation;
    let children_count = (d * d) as usize;
    if cell.level >= levels(d)[2] || tally.both() || tally.cells + children_count > MAX_CELLS {
        still.push(cell);
        return;
    }
    let m = prep.margin as i64;
    let bx = [
        d * cell.i - m,
        d * cell.i + d + m,
        d * cell.j - m,
        d * cell.j + d + m,
    ];
    let patch = Patch::refine(values, rules, bx, min_ring);
    let next = |p| patch.at(p);
    tally.deepest = tally.deepest.max(cell.level + 1);
    for child in children(rules.lattice, d, &cell) {
        if !tally.record(child, cell_sign_of(&next, rules, &child)) {
            refine_locally(&next, child, rules, prep, min_ring, tally, still);
        }
    }
}

/// The stages after the rules are read (see the module docs).
pub fn certify(
    rules: &RegularRules,
    local: &LocalRows,
    n: usize,
    lambda: f64,
    gap: f64,
) -> GenericReport {
    let mut report = GenericReport::indeterminate("");
    report.lattice = Some(rules.lattice);
    report.contraction = Some((rules.contraction, rules.contraction_power));
    let fail = |mut r: GenericReport, reason: String| {
        r.verdict = GenericVerdict::Indeterminate { reason };
        r
    };
    let lattice = rules.lattice;
    let d = rules.dilation;
    let [first_level, max_level, max_local] = levels(d);
    let children_count = (d * d) as usize;
    let prep = match prepare(rules, local, n, lambda, gap) {
        Ok(p) => p,
        Err(reason) => return fail(report, reason),
    };
    report.vector_error = Some(prep.vector_error);
    let mut net = prep.net.clone();
    let mut level = 0u32;
    let mut pending: Vec<Cell> = Vec::new();
    let mut tally = Tally::default();
    let mut wind = None;
    while level < max_level {
        net = prep.refine(&net, level);
        level += 1;
        if level < first_level {
            continue;
        }
        let todo: Vec<Cell> = if level == first_level {
            (0..n).flat_map(|s| annulus(lattice, d, s, level)).collect()
        } else {
            pending
                .iter()
                .flat_map(|p| children(lattice, d, p))
                .collect()
        };
        pending.clear();
        for cell in todo {
            if !tally.record(cell, cell_sign(&net, rules, &cell)) {
                pending.push(cell);
            }
        }
        if wind.is_none() {
            wind = winding(&net, rules, level);
        }
        if tally.both() {
            break;
        }
        if pending.is_empty() && wind.is_some() {
            break;
        }
        if tally.cells + children_count * pending.len() > MAX_CELLS {
            break;
        }
    }
    // the cells still undecided at the deepest level: refined locally, depth first
    if level == max_level
        && !tally.both()
        && tally.cells + children_count * pending.len() <= MAX_CELLS
    {
        let min_ring = local.radius(lattice) as i64;
        let mut still = Vec::new();
        for cell in std::mem::take(&mut pending) {
            let values = |p| net.at(cell.sector, p);
            refine_locally(
                &values, cell, rules, &prep, min_ring, &mut tally, &mut still,
            );
        }
        pending = still;
    }
    let cells = tally.cells;
    let signs = tally.signs;
    let min_rel = tally.min_rel;
    let level = level.max(tally.deepest);
    report.level = Some(level);
    report.cells = cells;
    report.point_error = Some(net.max_rad());
    report.winding_number = wind;
    if let (Some(p), Some(q)) = (signs[0], signs[1]) {
        report.verdict = GenericVerdict::NotC1 {
            witness: Witness::JacobianSignChange {
                positive: p,
                negative: q,
            },
        };
        return report;
    }
    if !pending.is_empty() {
        let reason = format!(
            "the Jacobian's sign is undecided on {} cells at level {level} (work limit: level {max_level}, locally {max_local}, {MAX_CELLS} cells)",
            pending.len()
        );
        return fail(report, reason);
    }
    let orientation: i8 = if signs[0].is_some() { 1 } else { -1 };
    report.orientation = Some(orientation);
    report.min_relative_jacobian = Some(min_rel[if orientation > 0 { 0 } else { 1 }]);
    match wind {
        None => fail(
            report,
            format!("regular, but the winding number is undecided at level {level}"),
        ),
        Some(w) if w == i64::from(orientation) => {
            report.verdict = GenericVerdict::C1;
            report
        }
        Some(w) => {
            report.verdict = GenericVerdict::NotC1 {
                witness: Witness::Winding {
                    winding: w,
                    orientation,
                },
            };
            report
        }
    }
}

use mask::RegularRules;
