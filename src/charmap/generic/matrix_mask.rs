//! Matrix difference schemes of a mask of any dilation **\[derived\]**
//! (math doc section 20.9): the first differences of the data evolve by a
//! 2 x 2 matrix mask `M`, the second differences by a 3 x 3 matrix mask `E`,
//! both found exactly in rational arithmetic, and the contraction of
//! `d E` (dilation `d`) that proves the regular part C1.
//!
//! With dilation `d` (`p'_beta = sum_alpha a_{beta - d alpha} p_alpha`, symbol
//! form `p'(z) = a(z) p(z^d)`) and the difference operators `D_k` of order
//! `r` (`r = 1`: `1 - z_1`, `1 - z_2`; `r = 2`: `(1 - z_1)^2`,
//! `(1 - z_1)(1 - z_2)`, `(1 - z_2)^2`), the matrix mask `A` of order `r`
//! satisfies
//!
//! ```text
//! D_k(z) a(z) = sum_l A_kl(z) D_l(z^d),
//! ```
//!
//! so that `(D p')(z) = A(z) (D p)(z^d)`: the differences of the refined data
//! are the matrix scheme `A` applied to the differences of the data.

use super::layout::{LatticePoint, Symbol};
use crate::scalar::Rational;
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// Largest power `L` tried for the contraction `||(d E)^L||_inf < 1` of the
/// second-difference scheme (the support of the `L`-step symbol grows like
/// `d^L`, the exact products with it; sqrt(3)'s two-step rules contract at
/// `L = 2`).
pub const MAX_MATRIX_CONTRACTION_POWER: u32 = 3;

/// A matrix mask: entry `(k, l)` is a symbol, the scheme
/// `q'_{beta, k} = sum_l sum_alpha A_kl[beta - d alpha] q_{alpha, l}`.
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixMask {
    /// The dilation `d`.
    pub dilation: i64,
    /// The order `r` of the differences (1: `M`, 2 x 2; 2: `E`, 3 x 3).
    pub order: u32,
    /// `entries[k][l]`, the symbol `A_kl`.
    pub entries: Vec<Vec<Symbol>>,
}

/// The difference operators of order `r` (1 or 2) as symbols, in the order
/// the matrix masks use: `r = 1`: `1 - z_1`, `1 - z_2`; `r = 2`:
/// `(1 - z_1)^2`, `(1 - z_1)(1 - z_2)`, `(1 - z_2)^2` (the monomials
/// `X^i Y^j`, `i + j = r`, `i` decreasing, with `X = 1 - z_1`, `Y = 1 - z_2`).
pub fn difference_operators(order: u32) -> Vec<Symbol> {
    let one_minus = |e: LatticePoint| -> Symbol {
        [([0, 0], Rational::one()), (e, -Rational::one())]
            .into_iter()
            .collect()
    };
    let (x, y) = (one_minus([1, 0]), one_minus([0, 1]));
    (0..=order)
        .rev()
        .map(|i| {
            let mut p: Symbol = [([0, 0], Rational::one())].into_iter().collect();
            for _ in 0..i {
                p = product(&p, &x);
            }
            for _ in i..order {
                p = product(&p, &y);
            }
            p
        })
        .collect()
}

/// The product of two symbols (exact; zero coefficients dropped).
pub fn product(p: &Symbol, q: &Symbol) -> Symbol {
    let mut out = Symbol::new();
    for (a, x) in p {
        for (b, y) in q {
            *out.entry([a[0] + b[0], a[1] + b[1]])
                .or_insert_with(Rational::zero) += x * y;
        }
    }
    out.retain(|_, v| !v.is_zero());
    out
}

/// `p(z^d)`.
pub fn dilate(p: &Symbol, d: i64) -> Symbol {
    p.iter()
        .map(|(g, v)| ([d * g[0], d * g[1]], v.clone()))
        .collect()
}

fn binomial(n: i64, k: i64) -> BigInt {
    (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1))
}

/// Writes `t` as `sum_l Q_l(z) D_l(z^d)` with the operators `D_l` of order
/// `r` **\[derived\]** (math doc 20.9). The symbols are a free module over
/// the polynomials in `(u, v) = (z_1^d, z_2^d)` with basis `z^rho`,
/// `rho in {0..d-1}^2`: after a shift `z^s` to non-negative exponents,
/// `t = z^s sum_rho z^rho R_rho(u, v)`, and `t` lies in the ideal of the
/// `D_l(z^d)` iff every `R_rho` vanishes to order `r` at `(u, v) = (1, 1)`.
/// Each `R_rho` is expanded in `X = 1 - u`, `Y = 1 - v`; a monomial
/// `X^a Y^b` (`a + b >= r`) is shared equally among the generators
/// `X^i Y^j` (`i + j = r`) that divide it (the symmetric quotient).
/// `Err` names the first coefficient of order below `r`.
pub fn divide_into_differences(t: &Symbol, d: i64, order: u32) -> Result<Vec<Symbol>, String> {
    let r = i64::from(order);
    let gens: Vec<[i64; 2]> = (0..=r).rev().map(|i| [i, r - i]).collect();
    let mut quotients = vec![Symbol::new(); gens.len()];
    let Some(s) = t
        .keys()
        .copied()
        .reduce(|a, b| [a[0].min(b[0]), a[1].min(b[1])])
    else {
        return Ok(quotients);
    };
    // R_rho(u, v) by residue class
    let mut classes: BTreeMap<[i64; 2], BTreeMap<[i64; 2], Rational>> = BTreeMap::new();
    for (g, v) in t {
        let (i, j) = (g[0] - s[0], g[1] - s[1]);
        classes
            .entry([i % d, j % d])
            .or_default()
            .insert([i / d, j / d], v.clone());
    }
    for (rho, poly) in classes {
        // Taylor coefficients at (1, 1): u^i = sum_a C(i, a) (-X)^a
        let mut taylor: BTreeMap<[i64; 2], Rational> = BTreeMap::new();
        for (e, v) in &poly {
            for a in 0..=e[0] {
                for b in 0..=e[1] {
                    let sign = if (a + b) % 2 == 0 { 1 } else { -1 };
                    let c = binomial(e[0], a) * binomial(e[1], b) * sign;
                    *taylor.entry([a, b]).or_insert_with(Rational::zero) +=
                        v * Rational::from_integer(c);
                }
            }
        }
        for ([a, b], v) in taylor.into_iter().filter(|(_, v)| !v.is_zero()) {
            if a + b < r {
                return Err(format!(
                    "not in the ideal of the order-{order} differences: residue class {rho:?} has the coefficient {v} of X^{a} Y^{b} at (1, 1) (the sum rules of order {order} fail)"
                ));
            }
            let dividing: Vec<usize> = (0..gens.len())
                .filter(|&l| gens[l][0] <= a && gens[l][1] <= b)
                .collect();
            let share = &v / Rational::from_integer(BigInt::from(dividing.len()));
            for l in dividing {
                // X^(a - i) Y^(b - j) back in u, v, then z^(s + rho + d e)
                let (aa, bb) = (a - gens[l][0], b - gens[l][1]);
                for i in 0..=aa {
                    for j in 0..=bb {
                        let sign = if (i + j) % 2 == 0 { 1 } else { -1 };
                        let c = binomial(aa, i) * binomial(bb, j) * sign;
                        let key = [s[0] + rho[0] + d * i, s[1] + rho[1] + d * j];
                        *quotients[l].entry(key).or_insert_with(Rational::zero) +=
                            &share * Rational::from_integer(c);
                    }
                }
            }
        }
    }
    for q in &mut quotients {
        q.retain(|_, v| !v.is_zero());
    }
    Ok(quotients)
}

/// The matrix mask of order `r` (1: `M`, 2: `E`) of the mask `a` with
/// dilation `d` **\[derived\]** (math doc 20.9): row `k` is the quotient of
/// `D_k(z) a(z)` by [`divide_into_differences`]. It exists iff `a`
/// satisfies the sum rules of order `r` (for `r = 1`: every coset sums to
/// the same value; for `r = 2` also equal first moments). `Err` carries the
/// reason.
///
/// ```
/// use subdiv_lab::charmap::generic::matrix_mask::{difference_mask, difference_operators, dilate, product};
/// use subdiv_lab::charmap::generic::mask::Symbol;
/// use subdiv_lab::scalar::Rational;
/// // the ternary box spline mask (1 + z + z^2)^2 (1 + w + w^2)^2 / 9
/// let f = |e: [i64; 2]| -> Symbol {
///     (0..3).map(|t| ([t * e[0], t * e[1]], Rational::from_integer(1.into()))).collect()
/// };
/// let mut a = product(&product(&f([1, 0]), &f([1, 0])), &product(&f([0, 1]), &f([0, 1])));
/// a.values_mut().for_each(|v| *v /= Rational::from_integer(9.into()));
/// let m = difference_mask(&a, 3, 1).unwrap();
/// // (1 - z_1) a(z) = M_11(z) (1 - z_1^3) + M_12(z) (1 - z_2^3)
/// let ops = difference_operators(1);
/// let mut rhs = product(&m.entries[0][0], &dilate(&ops[0], 3));
/// for (g, v) in product(&m.entries[0][1], &dilate(&ops[1], 3)) {
///     *rhs.entry(g).or_insert_with(|| Rational::from_integer(0.into())) += v;
/// }
/// rhs.retain(|_, v| *v != Rational::from_integer(0.into()));
/// assert_eq!(rhs, product(&ops[0], &a));
/// ```
pub fn difference_mask(a: &Symbol, d: i64, order: u32) -> Result<MatrixMask, String> {
    let entries = difference_operators(order)
        .iter()
        .map(|op| divide_into_differences(&product(op, a), d, order))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(MatrixMask {
        dilation: d,
        order,
        entries,
    })
}

impl MatrixMask {
    /// The coset sums `sum_{g = c mod d} A_kl[g]` of every entry, per coset
    /// `c` (row-major `[k][l]`).
    pub fn coset_sums(&self) -> BTreeMap<[i64; 2], Vec<Vec<Rational>>> {
        let d = self.dilation;
        let size = self.entries.len();
        let mut out: BTreeMap<[i64; 2], Vec<Vec<Rational>>> = BTreeMap::new();
        for cx in 0..d {
            for cy in 0..d {
                out.insert([cx, cy], vec![vec![Rational::zero(); size]; size]);
            }
        }
        for (k, row) in self.entries.iter().enumerate() {
            for (l, sym) in row.iter().enumerate() {
                for (g, v) in sym {
                    if let Some(s) = out.get_mut(&[g[0].rem_euclid(d), g[1].rem_euclid(d)]) {
                        s[k][l] += v;
                    }
                }
            }
        }
        out
    }

    /// `||(c A)^L||_inf` exactly **\[derived\]** (math doc 20.9): the `L`-step
    /// scheme has the symbol `P(z) = A(z) A(z^d) .. A(z^{d^{L-1}})` (matrix
    /// products in that order) and dilation `d^L`; its norm is the largest,
    /// over the rows `k` and the cosets modulo `d^L`, of
    /// `sum_{g in coset} sum_l |P_kl[g]|`, times `|c|^L`.
    pub fn power_norm(&self, c: &Rational, power: u32) -> Rational {
        let norm = match power {
            // the identity
            0 => Rational::one(),
            _ => self
                .powers()
                .nth(power as usize - 1)
                .unwrap_or_else(Rational::zero),
        };
        norm * c.abs().pow(power as i32)
    }

    /// The norms `||(c A)^L||_inf`, `L = 1, 2, ..`, up to the first below 1
    /// or [`MAX_MATRIX_CONTRACTION_POWER`]; with the contracting `L`. Each
    /// power is one product more than the one before.
    pub fn contraction(&self, c: &Rational) -> (Vec<Rational>, Option<u32>) {
        let mut norms = Vec::new();
        for (l, norm) in (1..=MAX_MATRIX_CONTRACTION_POWER).zip(self.powers()) {
            let n = norm * c.abs().pow(l as i32);
            let done = n < Rational::one();
            norms.push(n);
            if done {
                return (norms, Some(l));
            }
        }
        (norms, None)
    }

    /// For `L = 1, 2, ..`: the norm (without the factor `c`) of the
    /// `L`-step symbol `P_L(z) = P_{L-1}(z) A(z^{d^{L-1}})` of dilation
    /// `d^L`, the largest, over the rows `k` and the cosets modulo `d^L`, of
    /// `sum_{g in coset} sum_l |P_kl[g]|`.
    fn powers(&self) -> impl Iterator<Item = Rational> + '_ {
        let size = self.entries.len();
        let mut cur: Vec<Vec<Symbol>> = (0..size)
            .map(|k| {
                (0..size)
                    .map(|l| {
                        if k == l {
                            [([0, 0], Rational::one())].into_iter().collect()
                        } else {
                            Symbol::new()
                        }
                    })
                    .collect()
            })
            .collect();
        let mut step = 1i64;
        std::iter::from_fn(move || {
            let factor: Vec<Vec<Symbol>> = self
                .entries
                .iter()
                .map(|row| row.iter().map(|s| dilate(s, step)).collect())
                .collect();
            cur = (0..size)
                .map(|k| {
                    (0..size)
                        .map(|l| {
                            let mut acc = Symbol::new();
                            for m in 0..size {
                                for (g, v) in product(&cur[k][m], &factor[m][l]) {
                                    *acc.entry(g).or_insert_with(Rational::zero) += v;
                                }
                            }
                            acc.retain(|_, v| !v.is_zero());
                            acc
                        })
                        .collect()
                })
                .collect();
            step *= self.dilation;
            let mut best = Rational::zero();
            for row in &cur {
                let mut sums: BTreeMap<[i64; 2], Rational> = BTreeMap::new();
                for sym in row {
                    for (g, v) in sym {
                        *sums
                            .entry([g[0].rem_euclid(step), g[1].rem_euclid(step)])
                            .or_insert_with(Rational::zero) += v.abs();
                    }
                }
                for s in sums.into_values() {
                    if s > best {
                        best = s;
                    }
                }
            }
            Some(best)
        })
    }
}

/// The regular part's smoothness by matrix difference schemes **\[derived\]**
/// (math doc 20.9): `M` and `E` of the mask `a` with dilation `d`.
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixDifferences {
    /// The first-difference mask `M` (2 x 2).
    pub first: MatrixMask,
    /// The second-difference mask `E` (3 x 3).
    pub second: MatrixMask,
    /// `||(d E)^L||_inf` for `L = 1, 2, ..` (exact).
    pub norms: Vec<Rational>,
    /// The first `L` with `||(d E)^L||_inf < 1`, if any: then the scaled
    /// differences `q^t = d^t D p^t`, refined by `d M`, converge, and the
    /// regular part is C1.
    pub power: Option<u32>,
}

/// `M`, `E` and the contraction of `d E` for the mask `a` of dilation `d`
/// **\[derived\]** (math doc 20.9). `Err` when a matrix mask does not exist
/// (sum rules of order 2 fail) or `d M` does not reproduce constant vectors
/// (its coset sums are not the identity).
pub fn matrix_differences(a: &Symbol, d: i64) -> Result<MatrixDifferences, String> {
    let first = difference_mask(a, d, 1)?;
    let second = difference_mask(a, d, 2)?;
    let dd = Rational::from_integer(d.into());
    for (c, sums) in first.coset_sums() {
        for (k, row) in sums.iter().enumerate() {
            for (l, s) in row.iter().enumerate() {
                let want = if k == l {
                    Rational::one()
                } else {
                    Rational::zero()
                };
                if s * &dd != want {
                    return Err(format!(
                        "the first-difference scheme {d} M does not reproduce constants (coset {c:?}, entry ({k}, {l}) sums to {})",
                        s * &dd
                    ));
                }
            }
        }
    }
    let (norms, power) = second.contraction(&dd);
    Ok(MatrixDifferences {
        first,
        second,
        norms,
        power,
    })
}

/// The enclosure of the derivatives through the matrix difference schemes
/// **\[derived\]** (math doc section 20.9), the analogue for dilation `d` of
/// the norm-based enclosure of section 20.3.
///
/// With `q^t = d^t D p^t` (the first differences in level-`m` units,
/// `q^{t+1} = (d M) q^t`) and `v^t = d^t D^2 p^t = (d E)^t v^0`, the limit of
/// `q^t` is the derivative `g = (d_{e_1} f, d_{e_2} f)`. For `x` in a
/// level-`m` cell with bounding box `C`, let `alpha_t = floor(d^t x)`, so
/// `alpha_{t+1} = d alpha_t + delta` with a digit `delta in {0..d-1}^2`, and,
/// because the coset sums of `d M` are the identity,
///
/// ```text
/// q^{t+1}_{alpha_{t+1}} - q^t_{alpha_t} = sum_gamma (d M)[delta + d (alpha_t - gamma)] (q^t_gamma - q^t_{alpha_t}),
/// ```
///
/// where `q^t_gamma - q^t_alpha` is the sum of the differences `D_w q^t_l`
/// along the lattice path from `alpha` to `gamma` (first along `e_1`, then
/// `e_2`), and `D_w q^t_l` is the component `w + l` of `v^t` (`D_1 q_1 = D_11 p`,
/// `D_2 q_1 = D_1 q_2 = D_12 p`, `D_2 q_2 = D_22 p`, scaled by `d^t`). The
/// jump of component `k` is a fixed functional of `v^t`; `K_k` is the
/// largest `l1` norm of its coefficients over the digits (exact). With
/// `N_t = ||(d E)^t||_inf` and `T = sum_{i < L} N_i / (1 - N_L) >= sum_t N_t`
/// (sub-multiplicativity, `N_L < 1`),
///
/// ```text
/// |g_k(x) - q^0_{floor(x), k}| <= K_k T max |v^0|,
/// ```
///
/// the maximum over the second differences `v^0_eta` of the window: the
/// jump of level `t` reads `v^t` on `alpha_t + Y` (`Y` the box of the path
/// terms), which draws on `v^0` at `eta` in `C + d^-t Y + (1 - d^-t)(-B / (d - 1))`
/// (`B` the box of `E`'s support, that of `(d E)^t` lying in
/// `B (d^t - 1) / (d - 1)`), inside `C + hull(Y, -B / (d - 1))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixBound {
    /// The dilation `d`.
    pub dilation: i64,
    /// `K_k T` for the derivative along `e_k` (`k = 1, 2`), rounded up.
    pub factor: [f64; 2],
    /// `K_k`, rounded up.
    pub jump: [f64; 2],
    /// `T`, rounded up.
    pub series: f64,
    /// Per-axis offsets `[[lo_x, hi_x], [lo_y, hi_y]]` of the window of the
    /// second differences `v^0_eta`, added to the cell's bounding box.
    pub window: [[i64; 2]; 2],
    /// The mask reproduces quadratics up to a constant ([`reproduces_quadratics`]):
    /// the second-order enclosure applies.
    pub quadratic: bool,
}

/// Whether the mask `a` of dilation `d` maps every quadratic `Q` to
/// `Q(. / d) + c` **\[derived\]** (math doc section 20.9): every coset's
/// first moments `sum a_g g` are zero and its second moments
/// `sum a_g g g^T` are the same (exact). Then, by Taylor's formula around
/// `beta / d`, `sum_g a_g Q((beta - g) / d) = Q(beta / d) + tr(H S) / (2 d^2)`
/// (`H` the Hessian, `S` the common second moment), the constants of the
/// levels sum to a constant, and the limit of the data `Q` is `Q + const`:
/// its derivatives are exactly `grad Q`.
pub fn reproduces_quadratics(a: &Symbol, d: i64) -> bool {
    let mut moments: BTreeMap<[i64; 2], [Rational; 5]> = BTreeMap::new();
    for (g, w) in a {
        let m = moments
            .entry([g[0].rem_euclid(d), g[1].rem_euclid(d)])
            .or_insert_with(|| std::array::from_fn(|_| Rational::zero()));
        let (x, y) = (
            Rational::from_integer(g[0].into()),
            Rational::from_integer(g[1].into()),
        );
        m[0] += w * &x;
        m[1] += w * &y;
        m[2] += w * &x * &x;
        m[3] += w * &x * &y;
        m[4] += w * &y * &y;
    }
    let Some(first) = moments.values().next() else {
        return false;
    };
    moments.len() == (d * d) as usize
        && first[0].is_zero()
        && first[1].is_zero()
        && moments.values().all(|m| m == first)
}

/// `x` as `f64`, rounded up (the conversion is within a few units of the
/// last place; `gamma(2)` covers it).
fn upper(x: &Rational) -> f64 {
    crate::scalar::rational_to_f64(x) * (1.0 + crate::charmap::regularity::gamma(2))
}

impl MatrixBound {
    /// The constants of the enclosure for the matrix differences `md` of
    /// the mask `a` (whose `d E` contracts). `Err` when it does not.
    pub fn new(md: &MatrixDifferences, a: &Symbol) -> Result<Self, String> {
        let d = md.first.dilation;
        let dd = Rational::from_integer(d.into());
        let l = md
            .power
            .ok_or("the second-difference scheme d E does not contract")? as usize;
        // T = sum_{i < L} N_i / (1 - N_L), N_0 = 1
        let mut head = Rational::one();
        for n in &md.norms[..l - 1] {
            head += n;
        }
        let series = head / (Rational::one() - &md.norms[l - 1]);
        // the jump functionals, per digit and component
        let mut jump = [Rational::zero(), Rational::zero()];
        let mut ybox = [0i64, 0, 0, 0];
        for dx in 0..d {
            for dy in 0..d {
                for (k, row) in md.first.entries.iter().enumerate() {
                    let mut coef: BTreeMap<(usize, [i64; 2]), Rational> = BTreeMap::new();
                    for (l, entry) in row.iter().enumerate() {
                        for (g, w) in entry {
                            let (ox, oy) = (dx - g[0], dy - g[1]);
                            if ox.rem_euclid(d) != 0 || oy.rem_euclid(d) != 0 {
                                continue;
                            }
                            let o = [ox / d, oy / d];
                            let w = w * &dd;
                            for (dir, y, sign) in axis_path(o) {
                                ybox = [
                                    ybox[0].min(y[0]),
                                    ybox[1].max(y[0]),
                                    ybox[2].min(y[1]),
                                    ybox[3].max(y[1]),
                                ];
                                *coef.entry((dir + l, y)).or_insert_with(Rational::zero) +=
                                    &w * Rational::from_integer(sign.into());
                            }
                        }
                    }
                    let l1: Rational = coef.values().map(|c| c.abs()).sum();
                    if l1 > jump[k] {
                        jump[k] = l1;
                    }
                }
            }
        }
        // the box B of E's support
        let mut b = [i64::MAX, i64::MIN, i64::MAX, i64::MIN];
        for g in md.second.entries.iter().flatten().flat_map(|e| e.keys()) {
            b = [
                b[0].min(g[0]),
                b[1].max(g[0]),
                b[2].min(g[1]),
                b[3].max(g[1]),
            ];
        }
        // C + hull(Y, -B / (d - 1)), rounded outwards to lattice points
        let lo = |y: i64, bhi: i64| {
            y.min(-(bhi.div_euclid(d - 1)) - i64::from(bhi.rem_euclid(d - 1) != 0))
        };
        let hi = |y: i64, blo: i64| {
            y.max((-blo).div_euclid(d - 1) + i64::from((-blo).rem_euclid(d - 1) != 0))
        };
        let window = [
            [lo(ybox[0], b[1]), hi(ybox[1], b[0])],
            [lo(ybox[2], b[3]), hi(ybox[3], b[2])],
        ];
        let t = upper(&series);
        let k = [upper(&jump[0]), upper(&jump[1])];
        let g4 = 1.0 + crate::charmap::regularity::gamma(4);
        Ok(Self {
            dilation: d,
            factor: [k[0] * t * g4, k[1] * t * g4],
            jump: k,
            series: t,
            window,
            quadratic: reproduces_quadratics(a, d),
        })
    }

    /// The bounding box `[lo_x, hi_x, lo_y, hi_y]` of the lattice offsets the
    /// enclosure of a cell reads, relative to its lower corner: the window
    /// of the second differences, each reaching two points back.
    pub fn box_of_window(&self) -> [i64; 4] {
        let w = self.window;
        [w[0][0] - 2, w[0][1] + 1, w[1][0] - 2, w[1][1] + 1]
    }
}

/// The lattice path from `0` to `o`, first along `e_1`, then along `e_2`,
/// as signed differences `(direction, y, sign)`: `q_o - q_0 = sum sign (q_y - q_{y - e_dir})`.
fn axis_path(o: [i64; 2]) -> Vec<(usize, [i64; 2], i64)> {
    let mut z = [0i64, 0i64];
    let mut out = Vec::new();
    for (dir, &n) in o.iter().enumerate() {
        for _ in 0..n.abs() {
            if n > 0 {
                z[dir] += 1;
                out.push((dir, z, 1));
            } else {
                out.push((dir, z, -1));
                z[dir] -= 1;
            }
        }
    }
    out
}
