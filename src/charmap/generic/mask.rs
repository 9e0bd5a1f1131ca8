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

/// A Laurent polynomial in two variables (a mask) with exact coefficients.
pub type Symbol = BTreeMap<LatticePoint, Rational>;

/// The regular rules as the certificate uses them.
#[derive(Clone, Debug)]
pub struct RegularRules {
    /// The lattice.
    pub lattice: Lattice,
    /// The mask `a` (new point `beta` = `sum_alpha a_{beta - 2 alpha} p_alpha`), non-zero entries.
    pub mask: Vec<(LatticePoint, f64)>,
    /// The mask's entries by coset `(g_x mod 2) + 2 (g_y mod 2)`.
    pub by_coset: [Vec<(LatticePoint, f64)>; 4],
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
}

fn coset(g: LatticePoint) -> usize {
    (g[0].rem_euclid(2) + 2 * g[1].rem_euclid(2)) as usize
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
/// `Err` carries the reason the rules cannot be used.
pub fn read_mask(
    regular: &LocalMatrix<f64>,
    exact: Option<&LocalMatrix<Rational>>,
) -> Result<(Lattice, Symbol), String> {
    let nn = regular.valence();
    let lattice = Lattice::of_regular_valence(nn).ok_or_else(|| {
        format!("the regular configuration has valence {nn}, not 4 (quads) or 6 (triangles)")
    })?;
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
    // per row: the entries it sees
    let mut seen: BTreeMap<LatticePoint, (f64, usize)> = BTreeMap::new();
    let mut exact_of: BTreeMap<LatticePoint, Rational> = BTreeMap::new();
    let mut covered = [false; 4];
    for (r, beta) in rows.iter().enumerate() {
        covered[coset(*beta)] = true;
        for (c, alpha) in cols.iter().enumerate() {
            let g = [beta[0] - 2 * alpha[0], beta[1] - 2 * alpha[1]];
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
        for g in symbol.keys().filter(|g| coset(**g) == coset(*beta)) {
            let alpha = [(beta[0] - g[0]) / 2, (beta[1] - g[1]) / 2];
            if !cols.contains(&alpha) {
                return Err(format!(
                    "the regular configuration is not closed: new point {} needs a point outside it",
                    regular.rows()[r]
                ));
            }
        }
    }
    for k in 0..4 {
        let sum: f64 = symbol
            .iter()
            .filter(|(g, _)| coset(**g) == k)
            .map(|(_, q)| crate::scalar::rational_to_f64(q))
            .sum();
        if (sum - 1.0).abs() > MASK_CONSISTENCY_TOL {
            return Err(format!("the mask's parity class {k} sums to {sum}, not 1"));
        }
    }
    Ok((lattice, symbol))
}

/// Exact division of a symbol by `1 + z^e` (`e` a unit lattice vector):
/// along every line in direction `e`, `c_t = b_t + b_{t-1}`. `None` when the
/// remainder is not zero.
pub fn divide(sym: &Symbol, e: LatticePoint) -> Option<Symbol> {
    // group by line: key = coordinate across e, t = coordinate along e
    let across = |p: &LatticePoint| if e[0] != 0 { p[1] } else { p[0] };
    let along = |p: &LatticePoint| if e[0] != 0 { p[0] } else { p[1] };
    let make = |line: i64, t: i64| if e[0] != 0 { [t, line] } else { [line, t] };
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
        let mut prev = Rational::zero();
        for t in lo..hi {
            let c = coeffs.get(&t).cloned().unwrap_or_else(Rational::zero);
            let b = c - &prev;
            if !b.is_zero() {
                out.insert(make(line, t), b.clone());
            }
            prev = b;
        }
        let last = coeffs.get(&hi).cloned().unwrap_or_else(Rational::zero);
        if last != prev {
            return None;
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
    if symbol.values().any(|q| q.is_negative()) {
        return Err("the regular mask has negative weights (the convex-hull enclosures of the certificate need non-negative ones; a norm-based enclosure is not implemented)".into());
    }
    let units = [[1i64, 0i64], [0, 1]];
    let mut derivative_box = [[0i64; 4]; 2];
    let mut norms = [[0.0f64; 2]; 2];
    let mut power = 0u32;
    for (k, e) in units.iter().enumerate() {
        let b = divide(symbol, *e).ok_or_else(|| {
            format!(
                "the regular mask's symbol is not divisible by 1 + z^{e:?} (no derivative scheme)"
            )
        })?;
        let c = scale(&b, 2);
        if c.values().any(|q| q.is_negative()) {
            return Err(format!("the derivative scheme in direction {e:?} has negative weights (the convex-hull enclosure needs non-negative ones)"));
        }
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
    let mask = to_f64(symbol);
    let mut by_coset: [Vec<(LatticePoint, f64)>; 4] = Default::default();
    for &(g, w) in &mask {
        by_coset[coset(g)].push((g, w));
    }
    Ok(RegularRules {
        lattice,
        radius: mask
            .iter()
            .map(|(g, _)| lattice.ring(*g))
            .max()
            .unwrap_or(0),
        mask_box: bbox(mask.iter().map(|(g, _)| g)),
        mask,
        by_coset,
        derivative_box,
        contraction: norms,
        contraction_power: power,
    })
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
}
