//! The regular part's rules: the subdivision mask read from the scheme's own
//! regular configuration, its difference schemes by exact division of the
//! symbol, and their contraction (math doc section 20.3).

use super::layout::{label_position, Lattice, LatticePoint};
use crate::charmap::regularity::gamma;
use crate::scalar::{f64_to_rational, Rational};
use crate::schemes::LocalMatrix;
use num_traits::{Signed, Zero};
use std::collections::BTreeMap;

/// Largest accepted disagreement between two rows of the regular
/// configuration that give the same mask entry, and largest accepted
/// distance of a coset sum from 1 (absolute; the weights are `O(1)`). The
/// `f64` rows of a translation-invariant rule agree to a few ulps; a rule
/// that is not translation invariant differs by `O(1)`.
pub const MASK_CONSISTENCY_TOL: f64 = 1e-12;

/// Largest power `L` of a difference scheme whose norm is tried for the
/// contraction `||S_d^L||_inf < 1` (the support grows like `2^L`; box
/// splines contract at `L = 1` or `2`).
pub const MAX_CONTRACTION_POWER: u32 = 5;

/// Margin of the contraction test: the computed norm (rounded products of
/// exact dyadic weights) must be below `1 - CONTRACTION_MARGIN`.
pub const CONTRACTION_MARGIN: f64 = 1e-9;

pub use super::layout::Symbol;

/// The regular rules as the certificate uses them.
#[derive(Clone, Debug)]
pub struct RegularRules {
    /// The lattice.
    pub lattice: Lattice,
    /// The dilation `d` of the rules: 2 (a halving), or 3 (a one-to-nine
    /// split: sqrt(3)'s two steps, math doc section 20.9).
    pub dilation: i64,
    /// The mask `a` (new point `beta` = `sum_alpha a_{beta - d alpha} p_alpha`), non-zero entries.
    pub mask: Vec<(LatticePoint, f64)>,
    /// The mask's entries by coset `(g_x mod d) + d (g_y mod d)` (`d^2` cosets).
    pub by_coset: Vec<Vec<(LatticePoint, f64)>>,
    /// Largest ring index of the mask's support.
    pub radius: i64,
    /// Bounding box `[xmin, xmax, ymin, ymax]` of the mask's support.
    pub mask_box: [i64; 4],
    /// Bounding boxes of the supports of the derivative schemes `2 a / (1 + z^{e_k})`, `k = 1, 2`.
    pub derivative_box: [[i64; 4]; 2],
    /// The contraction norms `||S_d^L||_inf` found (per derivative scheme
    /// and difference direction) and the power `L`.
    pub contraction: [[f64; 2]; 2],
    /// The power `L` at which every difference scheme contracted.
    pub contraction_power: u32,
    /// The norm-based enclosure constants, for a mask with negative weights
    /// (`None`: the mask and its derivative schemes are non-negative and the
    /// convex-hull enclosures apply).
    pub norm: Option<NormBounds>,
    /// The enclosure of the derivatives through the matrix difference
    /// schemes, for rules of dilation 3 (math doc section 20.9; `None` for
    /// dilation 2).
    pub matrix: Option<super::matrix_mask::MatrixBound>,
}

/// The constants of the norm-based enclosure **\[derived\]** (math doc
/// section 20.3) for one scheme `c` (rows `q'_beta = sum_gamma c_{beta - 2 gamma} q_gamma`
/// summing to 1 per parity class) whose differences `D_w q_y = q_y - q_{y - w}`
/// in two directions `u, v` (`det(u, v) = +-1`) evolve by difference
/// schemes of norms `N_t = max ||S_d^t||_inf`: for `x` in a level-`m` cell
/// with bounding box `C` and `alpha = floor(x)` (a corner of `C`), the limit
/// satisfies `|g(x) - q_alpha| <= K T M`, where `T >= sum_{t >= 0} N_t`, `M` is
/// the largest difference over the window `[C + lo, C + hi]`, and `K` is the
/// largest `l1` norm of the one-step jumps `q'_{2 alpha + delta} - q_alpha`
/// written exactly as a signed combination of the differences along the
/// paths from `alpha` to the stencil points (first along `u`, then `v`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormBound {
    /// `K T`, rounded up.
    pub factor: f64,
    /// The two difference directions.
    pub directions: [LatticePoint; 2],
    /// Per-axis offsets of the window: `[[lo_x, hi_x], [lo_y, hi_y]]`
    /// added to the cell's bounding box.
    pub window: [[i64; 2]; 2],
    /// The shift `sigma` of the scheme's linear reproduction ([`linear_shift`]):
    /// affine data `l` has the limit `x -> l(x - sigma)`; `None` when the
    /// scheme does not reproduce affine data (then only the zero-order
    /// enclosure applies).
    pub shift: Option<[f64; 2]>,
}

/// The shift of the linear reproduction of a scheme `c` whose parity
/// classes sum to 1 **\[derived\]** (math doc section 20.3): for
/// `l(alpha) = alpha`, the new point `beta` is
/// `sum_{g in class(beta)} c_g (beta - g) / 2 = (beta - sigma) / 2` with
/// `sigma = sum_{g in class(beta)} g c_g`; when `sigma` is the same for the
/// four classes, `t` steps give `beta / 2^t - sigma (1 - 2^-t)`, so affine
/// data `l` has the limit `x -> l(x - sigma)`. `None` when the classes' first
/// moments differ. `sigma` is exact (dyadic rationals, exact in `f64` for
/// the masks the certificate reads; `None` otherwise).
pub fn linear_shift(c: &Symbol) -> Option<[f64; 2]> {
    let mut moments: Vec<[Rational; 2]> = Vec::with_capacity(4);
    for class in 0..4 {
        let mut m = [Rational::zero(), Rational::zero()];
        for (g, q) in c.iter().filter(|(g, _)| coset(**g) == class) {
            m[0] += q * Rational::from_integer(g[0].into());
            m[1] += q * Rational::from_integer(g[1].into());
        }
        moments.push(m);
    }
    if moments.iter().any(|m| *m != moments[0]) {
        return None;
    }
    let exact = |q: &Rational| {
        let x = crate::scalar::rational_to_f64(q);
        (f64_to_rational(x).as_ref() == Some(q)).then_some(x)
    };
    Some([exact(&moments[0][0])?, exact(&moments[0][1])?])
}

/// The norm-based enclosures, for a mask with negative weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormBounds {
    /// For the derivative schemes `c_k` (values: the differences
    /// `p_alpha - p_{alpha - e_k}`).
    pub derivative: [NormBound; 2],
    /// For the mask itself (values: the control points).
    pub mask: NormBound,
}

/// `(a, b)` with `d = a u + b v` (`det(u, v) = +-1`).
fn coefficients(d: LatticePoint, dirs: [LatticePoint; 2]) -> [i64; 2] {
    let [u, v] = dirs;
    let det = u[0] * v[1] - u[1] * v[0];
    [
        (d[0] * v[1] - d[1] * v[0]) * det,
        (u[0] * d[1] - u[1] * d[0]) * det,
    ]
}

/// A signed difference `coef D_w q_y` as `((direction index, y), coef)`.
type PathTerm = ((usize, LatticePoint), i64);

/// The path from `0` to `d` (first along `u`, then `v`) as a signed sum of
/// differences: `q_d - q_0 = sum coef D_{w} q_{y}`; also returns the points
/// visited.
fn path(d: LatticePoint, dirs: [LatticePoint; 2]) -> (Vec<PathTerm>, Vec<LatticePoint>) {
    let ab = coefficients(d, dirs);
    let mut z = [0i64, 0i64];
    let mut terms = Vec::new();
    let mut points = vec![z];
    for (w, &n) in ab.iter().enumerate() {
        let step = dirs[w];
        for _ in 0..n.abs() {
            if n > 0 {
                z = [z[0] + step[0], z[1] + step[1]];
                terms.push(((w, z), 1));
            } else {
                terms.push(((w, z), -1));
                z = [z[0] - step[0], z[1] - step[1]];
            }
            points.push(z);
        }
    }
    (terms, points)
}

/// Depth `J` of the exact composite jump norms of [`NormBound`]: the jumps
/// of levels `0..J` are composed with the difference schemes exactly (cost
/// `4^J` digit patterns), the later ones bounded through the norm series.
pub const COMPOSITE_DEPTH: u32 = 3;

/// The symbol of `S_d^t` (`d(z) d(z^2) .. d(z^{2^{t-1}})`) in `f64`, with the
/// same product of the absolute weights (for the rounding bound).
fn power_symbol(d: &[(LatticePoint, f64)], t: u32) -> Vec<(LatticePoint, f64)> {
    let mut power: BTreeMap<LatticePoint, f64> = BTreeMap::new();
    power.insert([0, 0], 1.0);
    for l in 0..t {
        let step = 1i64 << l;
        let mut next: BTreeMap<LatticePoint, f64> = BTreeMap::new();
        for (p, x) in &power {
            for (g, y) in d {
                *next
                    .entry([p[0] + step * g[0], p[1] + step * g[1]])
                    .or_insert(0.0) += x * y;
            }
        }
        power = next;
    }
    power.into_iter().collect()
}

/// The constants of [`NormBound`] for the scheme `c`, the directions, their
/// difference schemes `diffs` and the norm bound `t` of the difference
/// series **\[derived\]**. Window: the paths from `alpha_s = floor(2^s x)`
/// (in `2^s C`) to the stencil points `gamma` of its child stay in
/// `alpha_s + E`, `E` the box of the path offsets; the differences there come
/// from level-`m` differences in `C + 2^-s E + (1 - 2^-s)(-B_e)`, inside
/// `C + hull(E, -B_e)` (`B_e` the box of the difference schemes). Factor: the
/// jump of level `s` is the functional `w_delta` on the level-`(m + s)`
/// differences around `alpha_s`; composed with `S_e^s` it is a functional on
/// the level-`m` differences whose `l1` norm `J_s` (the largest over the
/// digits of `alpha_s` and over `delta`) is computed for `s <= COMPOSITE_DEPTH`,
/// and `J_s <= J_{COMPOSITE_DEPTH} N_{s - COMPOSITE_DEPTH}` beyond, so
/// `K T = sum_{s < J} J_s + J_J T`.
fn norm_bound(c: &Symbol, dirs: [LatticePoint; 2], diffs: [&Symbol; 2], t: f64) -> NormBound {
    let e_box = bbox(diffs[0].keys().chain(diffs[1].keys()));
    let mut e = [0i64, 0, 0, 0];
    let mut jumps: Vec<[Vec<(LatticePoint, f64)>; 2]> = Vec::new();
    let mut jump_l1 = 0.0f64;
    for delta in [[0i64, 0i64], [1, 0], [0, 1], [1, 1]] {
        let mut jump: BTreeMap<(usize, LatticePoint), Rational> = BTreeMap::new();
        for (g, w) in c.iter().filter(|(g, _)| coset(**g) == coset(delta)) {
            let d = [(delta[0] - g[0]) / 2, (delta[1] - g[1]) / 2];
            let (terms, points) = path(d, dirs);
            for p in points {
                e = [
                    e[0].min(p[0]),
                    e[1].max(p[0]),
                    e[2].min(p[1]),
                    e[3].max(p[1]),
                ];
            }
            for (key, sign) in terms {
                *jump.entry(key).or_insert_with(Rational::zero) +=
                    w * Rational::from_integer(sign.into());
            }
        }
        let mut split: [Vec<(LatticePoint, f64)>; 2] = Default::default();
        for ((w, y), q) in jump {
            if !q.is_zero() {
                let x = crate::scalar::rational_to_f64(&q);
                jump_l1 = jump_l1.max(x.abs());
                split[w].push((y, x));
            }
        }
        jumps.push(split);
    }
    let base: [Vec<(LatticePoint, f64)>; 2] = [to_f64(diffs[0]), to_f64(diffs[1])];
    let abs_sum = base
        .iter()
        .map(|b| b.iter().map(|(_, x)| x.abs()).sum::<f64>())
        .fold(1.0f64, f64::max);
    let mut composite = Vec::new();
    for s in 0..=COMPOSITE_DEPTH {
        let powers = [power_symbol(&base[0], s), power_symbol(&base[1], s)];
        let scale = 1i64 << s;
        let mut worst = 0.0f64;
        let mut worst_w = 0.0f64;
        for rx in 0..scale {
            for ry in 0..scale {
                for split in &jumps {
                    let mut l1 = 0.0f64;
                    let mut w1 = 0.0f64;
                    for (w, terms) in split.iter().enumerate() {
                        let mut coef: BTreeMap<LatticePoint, f64> = BTreeMap::new();
                        for (z, x) in terms {
                            w1 += x.abs();
                            for (g, y) in &powers[w] {
                                let px = rx + z[0] - g[0];
                                let py = ry + z[1] - g[1];
                                if px.rem_euclid(scale) == 0 && py.rem_euclid(scale) == 0 {
                                    *coef
                                        .entry([px.div_euclid(scale), py.div_euclid(scale)])
                                        .or_insert(0.0) += x * y;
                                }
                            }
                        }
                        l1 += coef.values().map(|v| v.abs()).sum::<f64>();
                    }
                    worst = worst.max(l1);
                    worst_w = worst_w.max(w1);
                }
            }
        }
        // rounding of the f64 weights, products and sums: at most
        // gamma(2^20) of the absolute sums
        let err = gamma(1 << 20) * worst_w * abs_sum.powi(s as i32) * (1.0 + jump_l1);
        composite.push((worst + err) * (1.0 + gamma(4)));
    }
    let depth = COMPOSITE_DEPTH as usize;
    let head: f64 = composite[..depth].iter().sum();
    // both `sum_{s < J} J_s + J_J T` and `J_0 T` bound the series; the smaller is used
    let factor = (head + composite[depth] * t).min(composite[0] * t);
    NormBound {
        factor: factor * (1.0 + gamma(depth + 4)),
        directions: dirs,
        window: [
            [e[0].min(-e_box[1]), e[1].max(-e_box[0])],
            [e[2].min(-e_box[3]), e[3].max(-e_box[2])],
        ],
        shift: linear_shift(c),
    }
}

/// `||S_d^t||_inf` for `t = 0..=MAX_CONTRACTION_POWER` (`t = 0`: 1), each
/// rounded up as in [`contraction`].
pub fn power_norms(d: &Symbol) -> Vec<f64> {
    let base = to_f64(d);
    let mut power: BTreeMap<LatticePoint, f64> = base.iter().copied().collect();
    let mut terms = 1usize;
    let mut out = vec![1.0];
    for l in 1..=MAX_CONTRACTION_POWER {
        if l > 1 {
            let step = 1i64 << (l - 1);
            let mut next: BTreeMap<LatticePoint, f64> = BTreeMap::new();
            for (p, x) in &power {
                for (g, y) in &base {
                    *next
                        .entry([p[0] + step * g[0], p[1] + step * g[1]])
                        .or_insert(0.0) += x * y;
                }
            }
            terms *= base.len();
            power = next;
        }
        let modulus = 1i64 << l;
        let mut sums: BTreeMap<LatticePoint, f64> = BTreeMap::new();
        for (p, x) in &power {
            *sums
                .entry([p[0].rem_euclid(modulus), p[1].rem_euclid(modulus)])
                .or_insert(0.0) += x.abs();
        }
        out.push(
            sums.values().fold(0.0f64, |a, &b| a.max(b)) * (1.0 + gamma(terms + power.len() + 2)),
        );
    }
    out
}

/// `T >= sum_{t >= 0} N_t` from the norms `N_0 = 1, N_1, ..` of
/// [`power_norms`] (sub-multiplicativity: `N_{qL + i} <= N_L^q N_i`): the
/// smallest `sum_{i < L} N_i / (1 - N_L)` over the `L` with
/// `N_L < 1 - CONTRACTION_MARGIN`, rounded up; `None` if none contracts.
pub fn series_bound(norms: &[f64]) -> Option<f64> {
    (1..norms.len())
        .filter(|&l| norms[l] < 1.0 - CONTRACTION_MARGIN)
        .map(|l| {
            let head: f64 = norms[..l].iter().sum();
            head / (1.0 - norms[l]) * (1.0 + gamma(l + 4))
        })
        .min_by(f64::total_cmp)
}

fn coset(g: LatticePoint) -> usize {
    coset_mod(g, 2)
}

/// The coset of `g` modulo `d`: `(g_x mod d) + d (g_y mod d)`.
fn coset_mod(g: LatticePoint, d: i64) -> usize {
    (g[0].rem_euclid(d) + d * g[1].rem_euclid(d)) as usize
}

fn bbox<'a, I: Iterator<Item = &'a LatticePoint>>(it: I) -> [i64; 4] {
    let mut b = [i64::MAX, i64::MIN, i64::MAX, i64::MIN];
    for p in it {
        b = [
            b[0].min(p[0]),
            b[1].max(p[0]),
            b[2].min(p[1]),
            b[3].max(p[1]),
        ];
    }
    b
}

/// Reads the mask from the local matrix of the regular configuration
/// (valence 6 or 4): row `beta` (new point), column `alpha` (old point) give
/// `a_{beta - 2 alpha}`. Every coset needs a row; rows that see the same
/// entry must agree to [`MASK_CONSISTENCY_TOL`]; every row must see every
/// non-zero entry of its coset (the configuration is closed under one step);
/// every coset sums to 1. `exact`, when given, supplies the exact weights.
/// Rules that are not translation invariant as a halving are read as a
/// one-to-nine split (dilation 3, math doc section 20.9). Returns the
/// lattice, the mask and its dilation; `Err` carries the reason the rules
/// cannot be used.
pub fn read_mask(
    regular: &LocalMatrix<f64>,
    exact: Option<&LocalMatrix<Rational>>,
) -> Result<(Lattice, Symbol, i64), String> {
    let nn = regular.valence();
    let lattice = Lattice::of_regular_valence(nn).ok_or_else(|| {
        format!("the regular configuration has valence {nn}, not 4 (quads) or 6 (triangles)")
    })?;
    match read_with_dilation(regular, exact, lattice, 2) {
        Ok(symbol) => Ok((lattice, symbol, 2)),
        Err(why) => match read_with_dilation(regular, exact, lattice, 3) {
            Ok(symbol) => Ok((lattice, symbol, 3)),
            Err(_) => Err(why),
        },
    }
}

/// The rules of [`read_mask`]'s dilation: [`regular_rules`] for 2,
/// [`ternary_rules`] for 3.
pub fn rules_of(lattice: Lattice, symbol: &Symbol, dilation: i64) -> Result<RegularRules, String> {
    match dilation {
        2 => regular_rules(lattice, symbol),
        _ => ternary_rules(lattice, symbol),
    }
}

/// The mask of dilation `d` (`a_{beta - d alpha}`, `d = 2` or `3`) under the
/// checks of [`read_mask`], with cosets modulo `d`.
pub fn read_with_dilation(
    regular: &LocalMatrix<f64>,
    exact: Option<&LocalMatrix<Rational>>,
    lattice: Lattice,
    d: i64,
) -> Result<Symbol, String> {
    let nn = regular.valence();
    let pos = |labels: &[crate::schemes::PointLabel]| -> Result<Vec<LatticePoint>, String> {
        labels
            .iter()
            .map(|l| {
                label_position(*l, nn)
                    .map(|p| lattice.regular_position(p))
                    .ok_or_else(|| {
                        format!("the point {l} has no place in a vertex-centred neighbourhood")
                    })
            })
            .collect()
    };
    let rows = pos(regular.rows())?;
    let cols = pos(regular.cols())?;
    let m = regular.matrix();
    let classes = (d * d) as usize;
    // per row: the entries it sees
    let mut seen: BTreeMap<LatticePoint, (f64, usize)> = BTreeMap::new();
    let mut exact_of: BTreeMap<LatticePoint, Rational> = BTreeMap::new();
    let mut covered = vec![false; classes];
    for (r, beta) in rows.iter().enumerate() {
        covered[coset_mod(*beta, d)] = true;
        for (c, alpha) in cols.iter().enumerate() {
            let g = [beta[0] - d * alpha[0], beta[1] - d * alpha[1]];
            let w = m[(r, c)];
            match seen.get(&g) {
                Some(&(w0, r0)) if (w0 - w).abs() > MASK_CONSISTENCY_TOL => {
                    return Err(format!(
                        "the regular rules are not translation invariant (mask entry {g:?}: {w0} from row {} and {w} from row {})",
                        regular.rows()[r0],
                        regular.rows()[r]
                    ));
                }
                Some(_) => {}
                None => {
                    seen.insert(g, (w, r));
                    let q = match exact {
                        Some(e) => e.matrix()[(r, c)].clone(),
                        None => f64_to_rational(w).ok_or("a weight is not finite")?,
                    };
                    exact_of.insert(g, q);
                }
            }
        }
    }
    if let Some(k) = covered.iter().position(|c| !c) {
        return Err(format!(
            "the regular configuration has no new point of parity class {k}"
        ));
    }
    let symbol: Symbol = exact_of.into_iter().filter(|(_, q)| !q.is_zero()).collect();
    // closure: every row sees every non-zero entry of its coset
    for (r, beta) in rows.iter().enumerate() {
        for g in symbol
            .keys()
            .filter(|g| coset_mod(**g, d) == coset_mod(*beta, d))
        {
            let alpha = [(beta[0] - g[0]) / d, (beta[1] - g[1]) / d];
            if !cols.contains(&alpha) {
                return Err(format!(
                    "the regular configuration is not closed: new point {} needs a point outside it",
                    regular.rows()[r]
                ));
            }
        }
    }
    for k in 0..classes {
        let sum: f64 = symbol
            .iter()
            .filter(|(g, _)| coset_mod(**g, d) == k)
            .map(|(_, q)| crate::scalar::rational_to_f64(q))
            .sum();
        if (sum - 1.0).abs() > MASK_CONSISTENCY_TOL {
            return Err(format!("the mask's parity class {k} sums to {sum}, not 1"));
        }
    }
    Ok(symbol)
}

/// The reason a mask of dilation 3 (a one-to-nine split) is not usable
/// **\[derived\]** (math doc section 20.9): the
/// derivative scheme in direction `e` would be
/// `c = 3 a / (1 + z^e + z^{2e})`, which exists iff the exact symbol is
/// divisible by `1 + z^e + z^{2e}`; the reason says for which lattice
/// directions it is (sqrt(3): none, so its derivative schemes are matrix
/// schemes). The regular part's smoothness is then decided by the matrix
/// difference schemes ([`super::matrix_mask::matrix_differences`]): C1 when
/// `||(3 E)^L||_inf < 1` (exact); without it the certificate has no
/// enclosure of the derivatives, which the reason also says.
pub fn dilation_three_reason(lattice: Lattice, symbol: &Symbol) -> String {
    let divides: Vec<String> = difference_directions(lattice)
        .into_iter()
        .filter(|e| divide_by(symbol, *e, 3).is_some())
        .map(|e| format!("{e:?}"))
        .collect();
    let factors = if divides.is_empty() {
        "its symbol has no factor 1 + z^e + z^2e along any lattice direction, so its derivative schemes are matrix schemes".to_owned()
    } else {
        format!(
            "its symbol has the factor 1 + z^e + z^2e for e = {}",
            divides.join(", ")
        )
    };
    let regular = match super::matrix_mask::matrix_differences(symbol, 3) {
        Ok(md) => match (md.power, md.norms.last()) {
            (Some(l), Some(norm)) => format!(
                "the regular part is C1 by its matrix difference schemes (||(3 E)^{l}||_inf = {} < 1, exact)",
                ceil4(norm)
            ),
            (_, norm) => format!(
                "its second-difference scheme 3 E does not contract by power {} (norm {}): the regular part is not certified C1",
                super::matrix_mask::MAX_MATRIX_CONTRACTION_POWER,
                norm.map_or(f64::NAN, ceil4)
            ),
        },
        Err(why) => format!("it has no matrix difference schemes ({why})"),
    };
    format!(
        "the regular rules are a one-to-nine split (dilation 3, {} weights); {factors}; {regular}; the ternary certificate needs contracting matrix difference schemes (math doc 20.9)",
        symbol.len()
    )
}

/// `x` rounded up to four decimals (for a reason's text; every comparison
/// is exact).
fn ceil4(x: &Rational) -> f64 {
    (crate::scalar::rational_to_f64(x) * 1e4).ceil() / 1e4
}

/// Exact division of a symbol by `1 + z^e` (`e` a unit lattice vector):
/// along every line in direction `e`, `c_t = b_t + b_{t-1}`. `None` when the
/// remainder is not zero.
pub fn divide(sym: &Symbol, e: LatticePoint) -> Option<Symbol> {
    divide_by(sym, e, 2)
}

/// Exact division of a symbol by `1 + z^e + .. + z^{(d - 1) e}` (`e` a unit
/// lattice vector, `d >= 2`): along every line in direction `e`,
/// `c_t = b_t + b_{t-1} + .. + b_{t-d+1}`, solved for `b` from the lowest
/// `t`. `None` when the remainder is not zero.
pub fn divide_by(sym: &Symbol, e: LatticePoint, d: i64) -> Option<Symbol> {
    // group by line: key = coordinate across e, t = coordinate along e
    // (`e` is (1, 0), (0, 1) or (-1, 1); on the last, `x + y` is constant)
    let diagonal = e[0] != 0 && e[1] != 0;
    let across = |p: &LatticePoint| {
        if diagonal {
            p[0] + p[1]
        } else if e[0] != 0 {
            p[1]
        } else {
            p[0]
        }
    };
    let along = |p: &LatticePoint| if e[0] != 0 && !diagonal { p[0] } else { p[1] };
    let make = |line: i64, t: i64| {
        if diagonal {
            [line - t, t]
        } else if e[0] != 0 {
            [t, line]
        } else {
            [line, t]
        }
    };
    let mut lines: BTreeMap<i64, BTreeMap<i64, Rational>> = BTreeMap::new();
    for (p, q) in sym {
        lines
            .entry(across(p))
            .or_default()
            .insert(along(p), q.clone());
    }
    let mut out = Symbol::new();
    for (line, coeffs) in lines {
        let (lo, hi) = (*coeffs.keys().next()?, *coeffs.keys().next_back()?);
        // b_t for t in lo..=hi - d + 1; then the last d - 1 coefficients of
        // the product must match (zero remainder)
        let mut b: Vec<Rational> = Vec::new();
        let coef = |t: i64| coeffs.get(&t).cloned().unwrap_or_else(Rational::zero);
        // the sum b_{t-1} + .. + b_{t-d+1} of the quotient found so far
        let tail = |b: &[Rational], t: i64| -> Rational {
            (1..d)
                .filter_map(|k| usize::try_from(t - k - lo).ok().and_then(|i| b.get(i)))
                .sum()
        };
        for t in lo..=hi - d + 1 {
            let q = coef(t) - tail(&b, t);
            if !q.is_zero() {
                out.insert(make(line, t), q.clone());
            }
            b.push(q);
        }
        for t in (hi - d + 2).max(lo)..=hi {
            if coef(t) != tail(&b, t) {
                return None;
            }
        }
    }
    Some(out)
}

fn scale(sym: &Symbol, k: i64) -> Symbol {
    sym.iter()
        .map(|(p, q)| (*p, q * Rational::from_integer(k.into())))
        .collect()
}

fn to_f64(sym: &Symbol) -> Vec<(LatticePoint, f64)> {
    sym.iter()
        .map(|(p, q)| (*p, crate::scalar::rational_to_f64(q)))
        .collect()
}

/// `||S_d^L||_inf` for `L = 1..=MAX_CONTRACTION_POWER` until one is below
/// `1 - CONTRACTION_MARGIN`: the symbol of `S_d^L` is
/// `d(z) d(z^2) ... d(z^{2^{L-1}})`, the norm the largest coset sum of
/// absolute values modulo `2^L`. The products are rounded: the sums are
/// inflated by `gamma` of the number of terms. Returns `(norm, L)` of the
/// first contracting power, or the last norm with `None`.
pub fn contraction(d: &Symbol) -> (f64, Option<u32>) {
    let base = to_f64(d);
    let mut power: BTreeMap<LatticePoint, f64> = base.iter().copied().collect();
    let mut terms = 1usize;
    let mut last = f64::INFINITY;
    for l in 1..=MAX_CONTRACTION_POWER {
        if l > 1 {
            let step = 1i64 << (l - 1);
            let mut next: BTreeMap<LatticePoint, f64> = BTreeMap::new();
            for (p, x) in &power {
                for (g, y) in &base {
                    *next
                        .entry([p[0] + step * g[0], p[1] + step * g[1]])
                        .or_insert(0.0) += x * y;
                }
            }
            terms *= base.len();
            power = next;
        }
        let modulus = 1i64 << l;
        let mut sums: BTreeMap<LatticePoint, f64> = BTreeMap::new();
        for (p, x) in &power {
            *sums
                .entry([p[0].rem_euclid(modulus), p[1].rem_euclid(modulus)])
                .or_insert(0.0) += x.abs();
        }
        let norm =
            sums.values().fold(0.0f64, |a, &b| a.max(b)) * (1.0 + gamma(terms + power.len() + 2));
        last = norm;
        if norm < 1.0 - CONTRACTION_MARGIN {
            return (norm, Some(l));
        }
    }
    (last, None)
}

/// The difference directions tried for a derivative scheme with negative
/// weights: the axes, then the third edge direction of the triangle lattice.
fn difference_directions(lattice: Lattice) -> Vec<LatticePoint> {
    match lattice {
        Lattice::Quad => vec![[1, 0], [0, 1]],
        Lattice::Triangle => vec![[1, 0], [0, 1], [-1, 1]],
    }
}

/// For a derivative scheme `c` (direction `e`) of a mask with negative
/// weights: the first pair of independent lattice directions along which
/// `c` has difference schemes whose norm series converges, its
/// [`NormBound`], the two first contracting norms and the power.
fn signed_differences(
    lattice: Lattice,
    c: &Symbol,
    e: LatticePoint,
) -> Result<(NormBound, [f64; 2], u32), String> {
    let dirs = difference_directions(lattice);
    let quotients: Vec<Option<Symbol>> = dirs.iter().map(|f| divide(c, *f)).collect();
    for a in 0..dirs.len() {
        for b in a + 1..dirs.len() {
            let (Some(da), Some(db)) = (&quotients[a], &quotients[b]) else {
                continue;
            };
            let (na, nb) = (power_norms(da), power_norms(db));
            let joint: Vec<f64> = na.iter().zip(&nb).map(|(x, y)| x.max(*y)).collect();
            let Some(t) = series_bound(&joint) else {
                continue;
            };
            let (ca, pa) = contraction(da);
            let (cb, pb) = contraction(db);
            let at = pa
                .unwrap_or(MAX_CONTRACTION_POWER)
                .max(pb.unwrap_or(MAX_CONTRACTION_POWER));
            return Ok((norm_bound(c, [dirs[a], dirs[b]], [da, db], t), [ca, cb], at));
        }
    }
    Err(format!(
        "the derivative scheme in direction {e:?} has no pair of difference schemes whose norms contract by power {MAX_CONTRACTION_POWER}: the regular part is not certified C1"
    ))
}

/// The regular rules with their derivative schemes checked: the mask and
/// every derivative scheme `c_k = 2 a / (1 + z^{e_k})` non-negative (the
/// convex-hull enclosures need it), every `c_k`'s parity classes summing to
/// 1 (it reproduces constants), and every difference scheme
/// `c_k / (1 + z^{e_l})` contracting ([`contraction`]): then the regular
/// part is C1 and `d_k f = sum_alpha (p_alpha - p_{alpha - e_k}) psi_k(. - alpha)`
/// with the non-negative refinable function `psi_k` of `c_k`, supported in
/// the convex hull of `c_k`'s support (math doc section 20.3). `Err` carries
/// the reason the certificate cannot use the rules.
pub fn regular_rules(lattice: Lattice, symbol: &Symbol) -> Result<RegularRules, String> {
    let units = [[1i64, 0i64], [0, 1]];
    // the convex-hull enclosures need the mask and both derivative schemes
    // non-negative; otherwise the norm-based ones are used
    let derivatives: Vec<Option<Symbol>> = units
        .iter()
        .map(|e| divide(symbol, *e).map(|b| scale(&b, 2)))
        .collect();
    let signed = symbol.values().any(|q| q.is_negative())
        || derivatives
            .iter()
            .flatten()
            .any(|c| c.values().any(|q| q.is_negative()));
    let mut derivative_box = [[0i64; 4]; 2];
    let mut norms = [[0.0f64; 2]; 2];
    let mut power = 0u32;
    let mut derivative_bounds = Vec::new();
    let mut halves: Vec<Symbol> = Vec::new();
    let mut mask_norms = vec![0.0f64; MAX_CONTRACTION_POWER as usize + 1];
    for (k, e) in units.iter().enumerate() {
        let b = divide(symbol, *e).ok_or_else(|| {
            format!(
                "the regular mask's symbol is not divisible by 1 + z^{e:?} (no derivative scheme)"
            )
        })?;
        let c = scale(&b, 2);
        for class in 0..4 {
            let sum: Rational = c
                .iter()
                .filter(|(g, _)| coset(**g) == class)
                .map(|(_, q)| q.clone())
                .sum();
            if sum != Rational::from_integer(1.into()) {
                return Err(format!(
                    "the derivative scheme in direction {e:?} does not reproduce constants"
                ));
            }
        }
        derivative_box[k] = bbox(c.keys());
        if signed {
            halves.push(b.clone());
            // the differences of `p` in direction `e` evolve by `c / 2`
            for (t, x) in power_norms(&c).iter().enumerate() {
                mask_norms[t] = mask_norms[t].max(x / f64::from(1u32 << t));
            }
            let (bound, pair_norms, at) = signed_differences(lattice, &c, *e)?;
            norms[k] = pair_norms;
            power = power.max(at);
            derivative_bounds.push(bound);
            continue;
        }
        for (l, f) in units.iter().enumerate() {
            let d = divide(&c, *f).ok_or_else(|| {
                format!("the derivative scheme in direction {e:?} has no difference scheme in direction {f:?}")
            })?;
            let (norm, at) = contraction(&d);
            norms[k][l] = norm;
            match at {
                Some(p) => power = power.max(p),
                None => {
                    return Err(format!(
                        "the difference scheme of the derivative in direction {e:?} does not contract by power {MAX_CONTRACTION_POWER} (norm {norm:.4}): the regular part is not certified C1"
                    ))
                }
            }
        }
    }
    let norm = if signed {
        let t = series_bound(&mask_norms).ok_or_else(|| {
            format!(
                "the mask's difference schemes do not contract by power {MAX_CONTRACTION_POWER}"
            )
        })?;
        Some(NormBounds {
            derivative: [derivative_bounds[0], derivative_bounds[1]],
            mask: norm_bound(symbol, units, [&halves[0], &halves[1]], t),
        })
    } else {
        None
    };
    Ok(assemble_rules(
        lattice,
        symbol,
        2,
        derivative_box,
        norms,
        power,
        norm,
        None,
    ))
}

/// The rules with the mask's `f64` entries by coset modulo `d`, its radius
/// and bounding box.
#[allow(clippy::too_many_arguments)]
fn assemble_rules(
    lattice: Lattice,
    symbol: &Symbol,
    d: i64,
    derivative_box: [[i64; 4]; 2],
    contraction: [[f64; 2]; 2],
    contraction_power: u32,
    norm: Option<NormBounds>,
    matrix: Option<super::matrix_mask::MatrixBound>,
) -> RegularRules {
    let mask = to_f64(symbol);
    let mut by_coset: Vec<Vec<(LatticePoint, f64)>> = vec![Vec::new(); (d * d) as usize];
    for &(g, w) in &mask {
        by_coset[coset_mod(g, d)].push((g, w));
    }
    RegularRules {
        lattice,
        dilation: d,
        radius: mask
            .iter()
            .map(|(g, _)| lattice.ring(*g))
            .max()
            .unwrap_or(0),
        mask_box: bbox(mask.iter().map(|(g, _)| g)),
        mask,
        by_coset,
        derivative_box,
        contraction,
        contraction_power,
        norm,
        matrix,
    }
}

/// The regular rules of dilation 3 **\[derived\]** (math doc section
/// 20.9): the matrix difference schemes `M`, `E` of the mask
/// ([`super::matrix_mask::matrix_differences`]) with `||(3 E)^L||_inf < 1`
/// prove the regular part C1, and their enclosure of the derivatives
/// ([`super::matrix_mask::MatrixBound`]) replaces the scalar derivative
/// schemes. The winding test encloses the map over an edge by the convex
/// hull of control points, so the mask must be non-negative. `Err` carries
/// the reason the certificate cannot use the rules.
pub fn ternary_rules(lattice: Lattice, symbol: &Symbol) -> Result<RegularRules, String> {
    let d = 3;
    let md = super::matrix_mask::matrix_differences(symbol, d)
        .map_err(|_| dilation_three_reason(lattice, symbol))?;
    let Some(power) = md.power else {
        return Err(dilation_three_reason(lattice, symbol));
    };
    if symbol.values().any(|q| q.is_negative()) {
        return Err("the regular rules are a one-to-nine split (dilation 3) with negative weights: the winding test of dilation 3 encloses the map by convex hulls of control points and needs a non-negative mask (math doc 20.9)".into());
    }
    let bound = super::matrix_mask::MatrixBound::new(&md, symbol)?;
    let norm = md.norms.last().map_or(f64::NAN, |x| {
        crate::scalar::rational_to_f64(x) * (1.0 + gamma(4))
    });
    let b = bound.box_of_window();
    Ok(assemble_rules(
        lattice,
        symbol,
        d,
        [b, b],
        [[norm; 2]; 2],
        power,
        None,
        Some(bound),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sym(entries: &[([i64; 2], i64, i64)]) -> Symbol {
        entries
            .iter()
            .map(|(p, a, b)| (*p, Rational::new((*a).into(), (*b).into())))
            .collect()
    }

    #[test]
    fn division_is_exact_or_refused() {
        // (1 + x)^2 = 1 + 2x + x^2 divides by 1 + x into 1 + x
        let s = sym(&[([0, 0], 1, 1), ([1, 0], 2, 1), ([2, 0], 1, 1)]);
        assert_eq!(
            divide(&s, [1, 0]),
            Some(sym(&[([0, 0], 1, 1), ([1, 0], 1, 1)]))
        );
        // 1 + x^2 does not divide by 1 + x
        let t = sym(&[([0, 0], 1, 1), ([2, 0], 1, 1)]);
        assert_eq!(divide(&t, [1, 0]), None);
        // nor by 1 + y
        assert_eq!(divide(&s, [0, 1]), None);
    }

    use super::super::matrix_mask::product as times;

    #[test]
    fn division_by_the_triadic_factor_is_exact_or_refused() {
        // (1 + x + x^2)(1 + x) = 1 + 2x + 2x^2 + x^3 divides by 1 + x + x^2
        let s = sym(&[
            ([0, 0], 1, 1),
            ([1, 0], 2, 1),
            ([2, 0], 2, 1),
            ([3, 0], 1, 1),
        ]);
        assert_eq!(
            divide_by(&s, [1, 0], 3),
            Some(sym(&[([0, 0], 1, 1), ([1, 0], 1, 1)]))
        );
        // 1 + x^3 = (1 + x)(1 - x + x^2) does not; nor along y
        let t = sym(&[([0, 0], 1, 1), ([3, 0], 1, 1)]);
        assert_eq!(divide_by(&t, [1, 0], 3), None);
        assert_eq!(divide_by(&s, [0, 1], 3), None);
        // a line shorter than the factor
        assert_eq!(
            divide_by(&sym(&[([0, 0], 1, 1), ([1, 0], 1, 1)]), [1, 0], 3),
            None
        );
    }

    #[test]
    fn the_dilation_three_reason_names_the_dividing_directions() {
        // the ternary three-direction box symbol (up to a factor)
        let f = |e: [i64; 2]| sym(&[([0, 0], 1, 1), (e, 1, 1), ([2 * e[0], 2 * e[1]], 1, 1)]);
        let boxed = times(&times(&f([1, 0]), &f([0, 1])), &f([-1, 1]));
        let reason = dilation_three_reason(Lattice::Triangle, &boxed);
        assert!(
            reason.contains("factor 1 + z^e + z^2e for e = [1, 0], [0, 1], [-1, 1]"),
            "{reason}"
        );
        // one factor fewer: two directions
        let two = times(&f([1, 0]), &f([0, 1]));
        let reason = dilation_three_reason(Lattice::Triangle, &two);
        assert!(reason.contains("for e = [1, 0], [0, 1];"), "{reason}");
    }
}
