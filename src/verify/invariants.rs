//! The invariant route (math doc section 15): the characteristic polynomial
//! of the deflated face block depends on the ratios only through a few
//! polynomial invariants, so a cell is decided in the (low-dimensional)
//! space of those invariants.
//!
//! **Invariants \[derived\].** Write each coefficient `p_j(r)` of
//! `P(z; r) = det(z I - C(r))` as its constant term plus its non-constant
//! part `v_j(r)`. Exact linear algebra over the rationals (at set-up) picks
//! a basis `phi_1 .. phi_t` among the `v_j` such that every coefficient is
//! `p_j = a_j + sum_i b_ji phi_i` with rational `a_j`, `b_ji`. For NURDS,
//! `t = 2` for `n = 5, 6` (the pair `s = sum_i (r_i r_{i+1} - r_i)` up to a
//! factor, and the constant coefficient), against `n` ratios. The spectrum
//! of `C(r)` is the root set of `P~(z; phi(r))`, with `P~(z; phi) = z^m +
//! sum_j (a_j + sum_i b_ji phi_i) z^j` affine in `phi`: every verdict is a
//! function of `phi(r)` alone.
//!
//! **Over a cell.** The invariants' ranges over the cell (second-order
//! Taylor forms with remainder, [`super::factor::CharPoly`]'s monomial
//! bounds) give a box `B` in invariant space that contains `phi(cell)`. If
//! every polynomial `P~(.; phi)`, `phi in B`, has the same verdict, so has
//! every ratio vector of the cell. That is decided by the quadratic-factor
//! route ([`super::factor`]) applied to the affine family `P~` over `B`,
//! bisecting `B` (at most [`MAX_INVARIANT_DEPTH`] times) where a part is
//! too large for its Krawczyk test; the verdicts of the parts must agree. A
//! large cell far from a class boundary maps into a box that a few such
//! parts decide, whatever the number of ratios.

use super::decide::{SpectralVerdict, Status};
use super::enclose::{centre_and_half_widths, Tamper};
use super::factor::{combo, companion_roots, monomial_form, solve, verdict, CharPoly, Cell};
use super::interval::{down, up, Iv};
use super::taylor::{Taylor, STRADDLE_SLACK};
use crate::scalar::{f64_to_rational, rational_to_f64, Rational};
use num_traits::{One, Zero};
use std::collections::BTreeMap;

/// Most bisections of an invariant box within one cell's evaluation: deep
/// enough that the first levels of the branch and bound (cells of a sizable
/// part of the box) are decided where they lie inside one class, shallow
/// enough to bound the work per cell (`2^8` factorisations at most).
pub const MAX_INVARIANT_DEPTH: u32 = 8;

/// The coefficients of the characteristic polynomial as affine functions
/// of a few polynomial invariants (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Invariants {
    m: usize,
    k: usize,
    /// `phi_i` as monomial lists (each the non-constant part of some `p_j`).
    phi: Vec<Vec<super::factor::Monomial>>,
    /// `a_j`, enclosed.
    a: Vec<Iv>,
    /// `b_ji`, enclosed (row `j`).
    b: Vec<Vec<Iv>>,
    #[doc(hidden)]
    pub scale: Vec<f64>,
}

/// An interval containing a rational.
fn enclose_rational(x: &Rational) -> Iv {
    let f = rational_to_f64(x);
    if !f.is_finite() {
        return Iv::new(f64::NEG_INFINITY, f64::INFINITY);
    }
    match f64_to_rational(f) {
        Some(q) if &q == x => Iv::point(f),
        Some(q) if &q < x => Iv::new(f, up(f)),
        Some(_) => Iv::new(down(f), f),
        None => Iv::new(f64::NEG_INFINITY, f64::INFINITY),
    }
}

type Vector = BTreeMap<Vec<u8>, Rational>;

/// Solves `sum_i x_i basis_i = v` exactly; `None` when `v` is not in the span.
fn solve_in_span(basis: &[Vector], v: &Vector) -> Option<Vec<Rational>> {
    let t = basis.len();
    let mut keys: Vec<&Vec<u8>> = v.keys().collect();
    for b in basis {
        keys.extend(b.keys());
    }
    keys.sort();
    keys.dedup();
    // rows: one per monomial, columns: t unknowns + right-hand side
    let mut rows: Vec<Vec<Rational>> = keys
        .iter()
        .map(|key| {
            let mut r: Vec<Rational> = basis
                .iter()
                .map(|b| b.get(*key).cloned().unwrap_or_else(Rational::zero))
                .collect();
            r.push(v.get(*key).cloned().unwrap_or_else(Rational::zero));
            r
        })
        .collect();
    let mut pivot_row = 0;
    let mut pivots = Vec::new();
    for col in 0..t {
        let Some(p) = (pivot_row..rows.len()).find(|&r| !rows[r][col].is_zero()) else {
            continue;
        };
        rows.swap(pivot_row, p);
        let inv = Rational::one() / rows[pivot_row][col].clone();
        for c in col..=t {
            rows[pivot_row][c] = rows[pivot_row][c].clone() * inv.clone();
        }
        for r in 0..rows.len() {
            if r != pivot_row && !rows[r][col].is_zero() {
                let f = rows[r][col].clone();
                for c in col..=t {
                    let sub = f.clone() * rows[pivot_row][c].clone();
                    rows[r][c] = rows[r][c].clone() - sub;
                }
            }
        }
        pivots.push(col);
        pivot_row += 1;
    }
    // consistent: no row 0 = nonzero
    if rows[pivot_row..].iter().any(|r| !r[t].is_zero()) {
        return None;
    }
    let mut x = vec![Rational::zero(); t];
    for (r, &col) in pivots.iter().enumerate() {
        x[col] = rows[r][t].clone();
    }
    Some(x)
}

/// Scratch: (decided, undecided leaves) of a uniform refinement to `depth`.
#[doc(hidden)]
pub fn scratch_tree(inv: &Invariants, lo: &[f64], hi: &[f64], depth: u32) -> (usize, usize, usize) {
    let v = inv.decide_box(lo, hi, 0, false);
    if v.complete() { return (1, 0, 0); }
    if depth == 0 { return (0, 1, usize::from(v.normal.is_some())); }
    let i = if (hi[0] - lo[0]) / inv.scale[0] >= (hi[1] - lo[1]) / inv.scale[1] { 0 } else { 1 };
    let mid = 0.5 * lo[i] + 0.5 * hi[i];
    let mut h1 = hi.to_vec(); h1[i] = mid; let mut l2 = lo.to_vec(); l2[i] = mid;
    let a = scratch_tree(inv, lo, &h1, depth - 1);
    let b = scratch_tree(inv, &l2, hi, depth - 1);
    (a.0 + b.0, a.1 + b.1, a.2 + b.2)
}

/// What one invariant box proves: the verdicts that hold on all of it
/// (`Undecided` / `None` where not), and the gradient in invariant space of
/// a quantity that left them open.
struct BoxVerdict {
    verdict: SpectralVerdict,
    normal: Option<Vec<f64>>,
}

impl BoxVerdict {
    fn complete(&self) -> bool {
        self.verdict.separation != Status::Undecided && self.verdict.class.is_some()
    }
}

impl Invariants {
    /// The invariants of a characteristic polynomial; `None` when there
    /// are as many as parameters (no gain) or a coefficient is not exact.
    ///
    /// ```
    /// use subdiv_lab::verify::enclose::AffineFamily;
    /// use subdiv_lab::verify::invariants::Invariants;
    /// let f = AffineFamily::nurds(5);
    /// let inv = Invariants::new(f.charpoly().unwrap()).unwrap();
    /// assert_eq!(inv.count(), 2);
    /// ```
    pub fn new(poly: &CharPoly) -> Option<Self> {
        let (m, k) = (poly.m, poly.k);
        let mut basis: Vec<Vector> = Vec::new();
        let mut phi = Vec::new();
        let mut a = vec![Iv::point(0.0); m];
        let mut coef: Vec<Vec<Rational>> = vec![Vec::new(); m];
        for j in (0..m).rev() {
            let mut v = Vector::new();
            let mut mons = Vec::new();
            for mo in &poly.coeffs[j] {
                if mo.vars.is_empty() {
                    a[j] = a[j].add(Iv::point(mo.coef));
                    continue;
                }
                let mut key = vec![0u8; k];
                for &x in &mo.vars {
                    key[x as usize] += 1;
                }
                let q = f64_to_rational(mo.coef)?;
                let e = v.entry(key).or_insert_with(Rational::zero);
                *e = e.clone() + q;
                mons.push(mo.clone());
            }
            v.retain(|_, c| !c.is_zero());
            if v.is_empty() {
                continue;
            }
            match solve_in_span(&basis, &v) {
                Some(x) => coef[j] = x,
                None => {
                    basis.push(v);
                    phi.push(mons);
                    let mut x = vec![Rational::zero(); basis.len()];
                    x[basis.len() - 1] = Rational::one();
                    coef[j] = x;
                }
            }
        }
        let t = basis.len();
        if t == 0 || t >= k {
            return None;
        }
        let b = coef
            .iter()
            .map(|x| {
                (0..t)
                    .map(|i| x.get(i).map_or(Iv::point(0.0), enclose_rational))
                    .collect()
            })
            .collect();
        // a_j sums exact dyadic constants: exact unless the sum rounded
        debug_assert!(a.iter().all(|v| v.lo == v.hi));
        Some(Invariants { m, k, phi, a, b, scale: vec![1.0; t] })
    }

    /// The number `t` of invariants.
    pub fn count(&self) -> usize {
        self.phi.len()
    }

    /// The invariants over a cell of ratios, as second-order Taylor forms.
    pub fn forms(&self, x0: &[f64], h: &[f64]) -> Vec<Taylor> {
        let k = self.k;
        let nq = k * (k + 1) / 2;
        self.phi
            .iter()
            .map(|mons| {
                let mut c = Iv::point(0.0);
                let mut g = vec![Iv::point(0.0); k];
                let mut q = vec![Iv::point(0.0); nq];
                let mut rem = 0.0;
                for mo in mons {
                    monomial_form(mo, x0, h, &mut c, &mut g, &mut q, &mut rem);
                }
                Taylor::from_parts(c, g, q, rem)
            })
            .collect()
    }

    /// `p_j(phi0 + d) = a_j + sum_i b_ji (phi0_i + d_i)` as exact affine
    /// forms over the invariant box `[phi0 - h, phi0 + h]`.
    fn coefficient_forms(&self, phi0: &[f64]) -> Vec<Taylor> {
        let t = self.count();
        (0..self.m)
            .map(|j| {
                let mut c = self.a[j];
                for i in 0..t {
                    c = c.add(self.b[j][i].mul(Iv::point(phi0[i])));
                }
                Taylor::from_parts(
                    c,
                    self.b[j].clone(),
                    vec![Iv::point(0.0); t * (t + 1) / 2],
                    0.0,
                )
            })
            .collect()
    }

    /// The verdicts that hold for every `P~(.; phi)`, `phi` in the box.
    fn decide_box(&self, lo: &[f64], hi: &[f64], depth: u32, first_order: bool) -> BoxVerdict {
        let open = BoxVerdict {
            verdict: SpectralVerdict {
                separation: Status::Undecided,
                class: None,
            },
            normal: None,
        };
        if lo.iter().zip(hi).any(|(a, b)| !(a.is_finite() && b.is_finite() && a <= b)) {
            return open;
        }
        let (c, h) = centre_and_half_widths(lo, hi);
        let p = self.coefficient_forms(&c);
        let mids: Vec<f64> = p.iter().map(|t| 0.5 * t.c.lo + 0.5 * t.c.hi).collect();
        let mut why: Option<Taylor> = None;
        if let Some(f) = companion_roots(&mids).and_then(|v| solve(p, h.clone(), v)) {
            let cell = Cell {
                h: &h,
                first_order,
            };
            let (v, w) = verdict(&f.factors, &f.moduli, &cell);
            let out = BoxVerdict {
                verdict: v,
                normal: w
                    .as_ref()
                    .map(|t| t.g.iter().map(|g| 0.5 * g.lo + 0.5 * g.hi).collect()),
            };
            if out.complete() {
                return out;
            }
            // a quantity that changes sign in the box: its parts cannot agree
            if let Some(t) = &w {
                let centre = 0.5 * t.c.lo + 0.5 * t.c.hi;
                if centre.abs() + t.quadratic_bound(&h) + t.rem
                    <= STRADDLE_SLACK * t.linear_bound(&h)
                {
                    return out;
                }
            }
            why = w;
        }
        if depth == 0 {
            return BoxVerdict {
                normal: why
                    .as_ref()
                    .map(|t| t.g.iter().map(|g| 0.5 * g.lo + 0.5 * g.hi).collect()),
                ..open
            };
        }
        // bisect: the side with the largest share of the open quantity, else
        // the side that moves the coefficients most
        let scores: Vec<f64> = match &why {
            Some(t) => t.scores(&h),
            None => (0..h.len())
                .map(|i| self.b.iter().map(|row| row[i].mag()).sum::<f64>() * h[i])
                .collect(),
        };
        let Some((i, mid)) = (0..h.len())
            .filter_map(|i| {
                let mid = 0.5 * lo[i] + 0.5 * hi[i];
                (lo[i] < mid && mid < hi[i]).then_some((i, mid))
            })
            .max_by(|x, y| scores[x.0].total_cmp(&scores[y.0]))
        else {
            return open;
        };
        let mut hi1 = hi.to_vec();
        hi1[i] = mid;
        let mut lo2 = lo.to_vec();
        lo2[i] = mid;
        let first = self.decide_box(lo, &hi1, depth - 1, first_order);
        let sep_open = first.verdict.separation == Status::Undecided;
        if sep_open && first.verdict.class.is_none() {
            return first;
        }
        let second = self.decide_box(&lo2, hi, depth - 1, first_order);
        let separation = if first.verdict.separation == second.verdict.separation {
            first.verdict.separation
        } else {
            Status::Undecided
        };
        let class = if first.verdict.class == second.verdict.class {
            first.verdict.class
        } else {
            None
        };
        BoxVerdict {
            verdict: SpectralVerdict { separation, class },
            normal: first.normal.or(second.normal),
        }
    }
}

/// The verdicts of the invariant route over a cell of ratios, and the
/// split shares when they are open; `None` when the route gives nothing
/// (the caller then tries the routes in ratio space).
pub fn decide(
    inv: &Invariants,
    lo: &[f64],
    hi: &[f64],
    tamper: Tamper,
) -> Option<(SpectralVerdict, Option<Vec<f64>>)> {
    if lo.len() != inv.k || hi.len() != inv.k {
        return None;
    }
    let (x0, mut h) = centre_and_half_widths(lo, hi);
    if tamper == Tamper::DropVariation {
        h = vec![0.0; inv.k];
    }
    let first_order = tamper == Tamper::FirstOrder;
    let forms = inv.forms(&x0, &h);
    let (blo, bhi): (Vec<f64>, Vec<f64>) = forms
        .iter()
        .map(|t| {
            let r = if first_order {
                t.c.widen(t.linear_bound(&h))
            } else {
                t.range(&h)
            };
            (r.lo, r.hi)
        })
        .unzip();
    let v = inv.decide_box(&blo, &bhi, MAX_INVARIANT_DEPTH, first_order);
    if v.verdict.separation == Status::Undecided && v.verdict.class.is_none() && v.normal.is_none()
    {
        return None;
    }
    // split shares: the open quantity's gradient in invariant space, carried
    // to the ratios through the invariants' forms
    let scores = v.normal.as_ref().map(|nu| {
        let parts: Vec<(f64, &Taylor)> = nu.iter().copied().zip(forms.iter()).collect();
        combo(&parts, Iv::point(0.0)).scores(&h)
    });
    Some((v.verdict, scores))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::verify::enclose::AffineFamily;

    /// `p_j = a_j + sum_i b_ji phi_i` at random points, against the
    /// expanded coefficients.
    #[test]
    fn coefficients_are_affine_in_the_invariants() {
        let mut rng = SplitMix64::new(2);
        for n in 5..=8 {
            let f = AffineFamily::nurds(n);
            let p = f.charpoly().unwrap();
            let Some(inv) = Invariants::new(p) else {
                continue;
            };
            for _ in 0..5 {
                let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
                let phi: Vec<f64> = inv
                    .forms(&r, &vec![0.0; n])
                    .iter()
                    .map(|t| 0.5 * t.c.lo + 0.5 * t.c.hi)
                    .collect();
                for j in 0..p.degree() {
                    let want = p.eval(j, &r);
                    let got: f64 = inv.a[j].lo
                        + (0..inv.count())
                            .map(|i| inv.b[j][i].lo * phi[i])
                            .sum::<f64>();
                    assert!((want - got).abs() < 1e-12, "n = {n}, p_{j}: {want} vs {got}");
                }
            }
        }
    }
}
