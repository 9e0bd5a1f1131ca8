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
use super::factor::{combo, companion_roots, solve, verdict, Cell, CharPoly};
use super::interval::{down, up, Iv};
use super::taylor2::Taylor;
use crate::scalar::{f64_to_rational, rational_to_f64, Rational};
use num_traits::{One, Zero};
use rayon::prelude::*;
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
#[allow(clippy::needless_range_loop)] // index-heavy linear algebra
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

impl Invariants {
    /// The invariants of a characteristic polynomial; `None` when there
    /// are as many as parameters (no gain) or a coefficient is not exact.
    ///
    /// ```
    /// use subdiv_lab::verify::enclose::AffineFamily;
    /// use subdiv_lab::verify::invariants::Invariants;
    /// use subdiv_lab::verify::factor::CharPoly;
    /// let f = AffineFamily::nurds(5);
    /// let inv = Invariants::new(&CharPoly::new(&f).unwrap()).unwrap();
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
        Some(Invariants { m, k, phi, a, b })
    }

    /// The number `t` of invariants.
    pub fn count(&self) -> usize {
        self.phi.len()
    }

    /// The invariants over a cell of ratios, as second-order Taylor forms.
    pub fn forms(&self, x0: &[f64], h: &[f64]) -> Vec<Taylor> {
        super::factor::polynomial_forms(&self.phi, self.k, x0, h)
    }

    /// `p_j(psi0 + d) = a_j + sum_i b_ji (psi0_i + d_i)` as affine forms
    /// over the box `[psi0 - h, psi0 + h]` of coordinates `psi` in which
    /// the coefficients have the slopes `b` (`self.b` for the invariants
    /// themselves).
    fn coefficient_forms(&self, b: &[Vec<Iv>], psi0: &[f64]) -> Vec<Taylor> {
        let t = self.count();
        (0..self.m)
            .map(|j| {
                let mut c = self.a[j];
                for i in 0..t {
                    c = c.add(b[j][i].mul(Iv::point(psi0[i])));
                }
                Taylor::from_parts(c, b[j].clone(), vec![Iv::point(0.0); t * (t + 1) / 2], 0.0)
            })
            .collect()
    }

    /// The factor route's verdicts for every `P~`, over the box of
    /// coordinates with slopes `b` (a node of the [`Tree`]).
    fn node_verdict(&self, b: &[Vec<Iv>], lo: &[f64], hi: &[f64]) -> SpectralVerdict {
        if lo
            .iter()
            .zip(hi)
            .any(|(a, b)| !(a.is_finite() && b.is_finite() && a <= b))
        {
            return OPEN;
        }
        let (c, h) = centre_and_half_widths(lo, hi);
        let p = self.coefficient_forms(b, &c);
        let mids: Vec<f64> = p.iter().map(|t| 0.5 * t.c.lo + 0.5 * t.c.hi).collect();
        match companion_roots(&mids).and_then(|v| solve(p, h.clone(), v)) {
            Some(f) => {
                let cell = Cell { h: &h };
                verdict(&f.factors, &f.moduli, &cell).0
            }
            None => OPEN,
        }
    }
}

/// Most invariants for which [`super::run`] uses the [`Tree`]: with three
/// (`n = 7, 8`) the grid at [`tree_level`] decided no cell of
/// `[0.05, 0.95]^7` in 90 s of CPU (measured), and the ratio-space routes
/// are used instead.
pub const MAX_TREE_INVARIANTS: usize = 2;

/// Levels of the [`Tree`]'s finest grid per number of invariants `t`: the
/// grid has `2^level` cells along every invariant (`2^(t level)` in all,
/// at most 2^21), fine enough that the factor route proves cells of the
/// grid away from the class boundaries (the quadratic factors are
/// ill-conditioned over larger boxes of invariants at `n = 5`).
pub fn tree_level(t: usize) -> u32 {
    match t {
        0 | 1 => 16,
        2 => 10,
        3 => 6,
        4 => 5,
        _ => 4,
    }
}

/// Subdivisions per side of the ratio box when its invariants are
/// enclosed for the root of the [`Tree`]: the union of the enclosures of
/// the parts is much tighter than the enclosure of the whole box.
fn root_splits(k: usize) -> usize {
    match k {
        0..=6 => 4,
        7..=8 => 3,
        _ => 2,
    }
}

/// Relative margin of the [`Tree`]'s root around the enclosure of the
/// invariants over the ratio box: a cell's own enclosure, which is not
/// always inside the box's, leaves the root less often (a cell whose
/// enclosure leaves it is not decided by the tree, never misjudged).
const ROOT_MARGIN: f64 = 0.25;

/// Verdicts in invariant space, proven once per run over a dyadic grid and
/// queried in constant time by every cell (math doc section 15, "the
/// invariant raster").
///
/// The root is a box `R` that contains the invariants of every ratio
/// vector of the region. The node of level `l` and index `a` is
/// `[e(l, a_i), e(l, a_i + 1)]` along invariant `i`, with
/// `e(l, a) = lo_i + w_i * (a / 2^l)` in floating point. As `a / 2^l` is
/// an exact dyadic, a child's end points are its parent's and the midpoint
/// bit for bit, and `e` is non-decreasing in `a / 2^l` (both rounded
/// operations are monotone), so the nodes of one level cover `R` with no
/// gap. Starting from `R`, a node the factor route decides (the affine
/// family `P~` in the invariants over the node) gives its verdict to all
/// grid cells (nodes of level [`tree_level`]) inside it; an open node is
/// split into its `2^t` children down to the grid. Per verdict the grid
/// carries a table of prefix sums (summed-area table).
///
/// A cell of ratios encloses its invariants in a box `B`; the grid cells
/// that meet `B` (closed boxes) form an index range, and the prefix sums
/// tell which verdicts occur in it: the cell gets the verdicts that all of
/// them prove alike.
#[derive(Debug)]
pub struct Tree<'a> {
    inv: &'a Invariants,
    /// `G`: unit lower triangular, exact floats; the tree's coordinates
    /// are `psi = G phi`.
    g: Vec<Vec<f64>>,
    /// The slopes of the coefficients in `psi`: `b G^-1`, enclosed.
    b: Vec<Vec<Iv>>,
    lo: Vec<f64>,
    w: Vec<f64>,
    level: u32,
    /// The distinct verdicts of the grid; index 0 is the open verdict.
    verdicts: Vec<SpectralVerdict>,
    /// Per verdict, the prefix sums over the grid: `(N + 1)^t` entries,
    /// `N = 2^level`, entry `s` = number of grid cells with index `< s`
    /// (componentwise) that carry the verdict.
    sums: Vec<Vec<u32>>,
}

const OPEN: SpectralVerdict = SpectralVerdict {
    separation: Status::Undecided,
    class: None,
};

impl<'a> Tree<'a> {
    /// Proves the grid for the cells of the box `[lo, hi]` of ratios (type
    /// docs); `None` when the root cannot be formed.
    pub fn new(inv: &'a Invariants, lo: &[f64], hi: &[f64]) -> Option<Self> {
        let k = inv.k;
        if lo.len() != k || hi.len() != k {
            return None;
        }
        let t = inv.count();
        let g = decorrelation(inv, lo, hi);
        let b = slopes_in(inv, &g);
        // the root: the union of the enclosures over the parts of the box
        let s = root_splits(k);
        let mut rlo = vec![f64::INFINITY; t];
        let mut rhi = vec![f64::NEG_INFINITY; t];
        let mut idx = vec![0usize; k];
        loop {
            let plo: Vec<f64> = (0..k)
                .map(|i| lo[i] + (hi[i] - lo[i]) * (idx[i] as f64 / s as f64))
                .collect();
            let phi: Vec<f64> = (0..k)
                .map(|i| lo[i] + (hi[i] - lo[i]) * ((idx[i] + 1) as f64 / s as f64))
                .collect();
            // the parts overlap a little where the rounded end points differ:
            // widen by one unit in the last place to keep the box covered
            let plo: Vec<f64> = plo.iter().zip(lo).map(|(a, b)| down(*a).max(*b)).collect();
            let phi: Vec<f64> = phi.iter().zip(hi).map(|(a, b)| up(*a).min(*b)).collect();
            let (x0, h) = centre_and_half_widths(&plo, &phi);
            for (i, f) in psi_forms(&g, &inv.forms(&x0, &h)).iter().enumerate() {
                let r = f.range(&h);
                rlo[i] = rlo[i].min(r.lo);
                rhi[i] = rhi[i].max(r.hi);
            }
            let mut d = 0;
            while d < k {
                idx[d] += 1;
                if idx[d] < s {
                    break;
                }
                idx[d] = 0;
                d += 1;
            }
            if d == k {
                break;
            }
        }
        let mut root_lo = Vec::with_capacity(t);
        let mut w = Vec::with_capacity(t);
        for i in 0..t {
            let width = up(rhi[i] - rlo[i]);
            if !(width.is_finite() && width > 0.0) {
                return None;
            }
            let l = down(rlo[i] - ROOT_MARGIN * width);
            // the root's upper end e(0, 1) = l + w_i must reach rhi + margin
            let span = up(up(rhi[i] - l) + ROOT_MARGIN * width);
            if !(l + span >= rhi[i]) {
                return None;
            }
            root_lo.push(l);
            w.push(span);
        }
        let level = tree_level(t);
        let mut tree = Tree {
            inv,
            g,
            b,
            lo: root_lo,
            w,
            level,
            verdicts: vec![OPEN],
            sums: Vec::new(),
        };
        // prove the nodes, then fill the grid
        let leaves = tree.prove(0, vec![0; t]);
        let n = 1usize << level;
        let mut grid = vec![0u8; n.pow(t as u32)];
        for (lv, ix, v) in leaves {
            let code = match tree.verdicts.iter().position(|x| *x == v) {
                Some(c) => c,
                None => {
                    tree.verdicts.push(v);
                    tree.verdicts.len() - 1
                }
            };
            let span = 1usize << (level - lv);
            // fill the block of grid cells of the node
            let mut off = vec![0usize; t];
            loop {
                let mut flat = 0;
                for i in (0..t).rev() {
                    flat = flat * n + (ix[i] as usize * span + off[i]);
                }
                grid[flat] = code as u8;
                let mut d = 0;
                while d < t {
                    off[d] += 1;
                    if off[d] < span {
                        break;
                    }
                    off[d] = 0;
                    d += 1;
                }
                if d == t {
                    break;
                }
            }
        }
        tree.sums = (0..tree.verdicts.len())
            .map(|c| prefix_sums(&grid, n, t, c as u8))
            .collect();
        Some(tree)
    }

    /// `e(level, a)` along invariant `i` (type docs).
    fn end(&self, i: usize, level: u32, a: u64) -> f64 {
        self.lo[i] + self.w[i] * (a as f64 / 2f64.powi(level as i32))
    }

    /// The decided nodes below `(level, ix)` and the open grid cells, each
    /// with its verdict (children in parallel near the root).
    fn prove(&self, level: u32, ix: Vec<u64>) -> Vec<(u32, Vec<u64>, SpectralVerdict)> {
        let t = ix.len();
        let lo: Vec<f64> = ix
            .iter()
            .enumerate()
            .map(|(i, &a)| self.end(i, level, a))
            .collect();
        let hi: Vec<f64> = ix
            .iter()
            .enumerate()
            .map(|(i, &a)| self.end(i, level, a + 1))
            .collect();
        let v = self.inv.node_verdict(&self.b, &lo, &hi);
        let complete = v.separation != Status::Undecided && v.class.is_some();
        if complete || level >= self.level {
            return vec![(level, ix, v)];
        }
        let children: Vec<Vec<u64>> = (0..(1u64 << t))
            .map(|c| {
                ix.iter()
                    .enumerate()
                    .map(|(i, &a)| 2 * a + ((c >> i) & 1))
                    .collect()
            })
            .collect();
        if level < 4 {
            children
                .into_par_iter()
                .flat_map_iter(|c| self.prove(level + 1, c))
                .collect()
        } else {
            children
                .into_iter()
                .flat_map(|c| self.prove(level + 1, c))
                .collect()
        }
    }

    /// The index range `[a0, a1]` of grid cells along invariant `i` that
    /// meet `[b0, b1]`, or `None` when `[b0, b1]` is not inside the root.
    fn index_range(&self, i: usize, b0: f64, b1: f64) -> Option<(u64, u64)> {
        let n = 1u64 << self.level;
        if !(self.lo[i] <= b0 && b0 <= b1 && b1 <= self.end(i, 0, 1)) {
            return None;
        }
        let guess = |x: f64| -> u64 {
            let g = ((x - self.lo[i]) / self.w[i] * n as f64).floor();
            (g.max(0.0) as u64).min(n - 1)
        };
        // a0: the first cell with e(a0 + 1) >= b0
        let mut a0 = guess(b0);
        while a0 > 0 && self.end(i, self.level, a0) >= b0 {
            a0 -= 1;
        }
        while a0 + 1 < n && self.end(i, self.level, a0 + 1) < b0 {
            a0 += 1;
        }
        // a1: the last cell with e(a1) <= b1
        let mut a1 = guess(b1).max(a0);
        while a1 + 1 < n && self.end(i, self.level, a1 + 1) <= b1 {
            a1 += 1;
        }
        while a1 > a0 && self.end(i, self.level, a1) > b1 {
            a1 -= 1;
        }
        Some((a0, a1))
    }

    /// The verdicts that hold for every invariant vector in the box
    /// `[blo, bhi]` (open when it leaves the root).
    fn query(&self, blo: &[f64], bhi: &[f64]) -> SpectralVerdict {
        let t = self.lo.len();
        let mut ranges = Vec::with_capacity(t);
        for i in 0..t {
            match self.index_range(i, blo[i], bhi[i]) {
                Some(r) => ranges.push(r),
                None => return OPEN,
            }
        }
        let total: u64 = ranges.iter().map(|(a, b)| b - a + 1).product();
        let n = (1usize << self.level) + 1;
        let mut agreed: Option<SpectralVerdict> = None;
        let mut separation = None;
        let mut class = None;
        for (c, sums) in self.sums.iter().enumerate() {
            // inclusion-exclusion over the 2^t corners
            let mut count: i64 = 0;
            for corner in 0..(1usize << t) {
                let mut flat = 0usize;
                let mut sign = 1i64;
                for i in (0..t).rev() {
                    let (a0, a1) = ranges[i];
                    let x = if corner >> i & 1 == 1 {
                        a1 as usize + 1
                    } else {
                        sign = -sign;
                        a0 as usize
                    };
                    flat = flat * n + x;
                }
                count += sign * i64::from(sums[flat]);
            }
            if count == 0 {
                continue;
            }
            let v = self.verdicts[c];
            if count as u64 == total {
                agreed = Some(v);
            }
            separation = Some(match separation {
                None => v.separation,
                Some(s) if s == v.separation => s,
                Some(_) => Status::Undecided,
            });
            class = Some(match class {
                None => v.class,
                Some(k) if k == v.class => k,
                Some(_) => None,
            });
        }
        agreed.unwrap_or(SpectralVerdict {
            separation: separation.unwrap_or(Status::Undecided),
            class: class.flatten(),
        })
    }

    /// The verdicts of the invariant route over a cell of ratios (type
    /// docs), and the split shares: each ratio's contribution to the
    /// invariants' enclosure, relative to the root.
    pub fn decide(
        &self,
        lo: &[f64],
        hi: &[f64],
        tamper: Tamper,
    ) -> Option<(SpectralVerdict, Option<Vec<f64>>)> {
        let inv = self.inv;
        if lo.len() != inv.k || hi.len() != inv.k {
            return None;
        }
        let (x0, mut h) = centre_and_half_widths(lo, hi);
        if tamper == Tamper::DropVariation {
            h = vec![0.0; inv.k];
        }
        let forms = psi_forms(&self.g, &inv.forms(&x0, &h));
        let (blo, bhi): (Vec<f64>, Vec<f64>) = forms
            .iter()
            .map(|t| {
                let r = t.range(&h);
                (r.lo, r.hi)
            })
            .unzip();
        let v = self.query(&blo, &bhi);
        let scores = (0..inv.k)
            .map(|k| {
                forms
                    .iter()
                    .zip(&self.w)
                    .map(|(f, w)| f.g[k].mag() * h[k] / w)
                    .sum()
            })
            .collect();
        Some((v, Some(scores)))
    }
}

/// The coordinates `psi = G phi` of the [`Tree`] as Taylor forms, from the
/// invariants' forms (exact float multipliers, outward rounding).
fn psi_forms(g: &[Vec<f64>], phi: &[Taylor]) -> Vec<Taylor> {
    g.iter()
        .map(|row| {
            let parts: Vec<(f64, &Taylor)> = row
                .iter()
                .zip(phi)
                .filter(|(c, _)| **c != 0.0)
                .map(|(c, f)| (*c, f))
                .collect();
            combo(&parts, Iv::point(0.0))
        })
        .collect()
}

/// Sample points per ratio for [`decorrelation`].
const DECORRELATION_SAMPLES: usize = 512;

/// A unit lower triangular `G` (exact floats) that decorrelates the
/// invariants over the box: `L` of `Sigma = L D L^T`, `Sigma` the
/// covariance of the invariants at quasi-random points of the box, and
/// `G = L^-1` rounded to floats. Any `G` of this shape is sound (the tree
/// encloses `G^-1` exactly); a good one makes the box hulls of the cells'
/// images, which are thin slanted strips in `phi`, small in `psi`.
#[allow(clippy::needless_range_loop)] // index-heavy linear algebra
fn decorrelation(inv: &Invariants, lo: &[f64], hi: &[f64]) -> Vec<Vec<f64>> {
    let t = inv.count();
    let k = inv.k;
    let mut rng = crate::rng::SplitMix64::new(0x5eed);
    let zero = vec![0.0; k];
    let pts: Vec<Vec<f64>> = (0..DECORRELATION_SAMPLES)
        .map(|_| {
            let r: Vec<f64> = lo
                .iter()
                .zip(hi)
                .map(|(a, b)| rng.uniform(*a, *b))
                .collect();
            inv.forms(&r, &zero)
                .iter()
                .map(|f| 0.5 * f.c.lo + 0.5 * f.c.hi)
                .collect()
        })
        .collect();
    let mean: Vec<f64> = (0..t)
        .map(|i| pts.iter().map(|p| p[i]).sum::<f64>() / pts.len() as f64)
        .collect();
    let mut cov = vec![vec![0.0; t]; t];
    for p in &pts {
        for i in 0..t {
            for j in 0..t {
                cov[i][j] += (p[i] - mean[i]) * (p[j] - mean[j]);
            }
        }
    }
    // L D L^T
    let mut l = vec![vec![0.0; t]; t];
    let mut d = vec![0.0; t];
    for j in 0..t {
        l[j][j] = 1.0;
        d[j] = cov[j][j] - (0..j).map(|s| l[j][s] * l[j][s] * d[s]).sum::<f64>();
        for i in j + 1..t {
            let v = cov[i][j] - (0..j).map(|s| l[i][s] * l[j][s] * d[s]).sum::<f64>();
            l[i][j] = if d[j] > 0.0 { v / d[j] } else { 0.0 };
        }
    }
    // G = L^-1 by forward substitution (floats: G is then exact by definition)
    let mut g = vec![vec![0.0; t]; t];
    for j in 0..t {
        g[j][j] = 1.0;
        for i in j + 1..t {
            g[i][j] = -(j..i).map(|s| l[i][s] * g[s][j]).sum::<f64>();
        }
    }
    if g.iter().flatten().any(|v| !v.is_finite()) {
        return (0..t)
            .map(|i| (0..t).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
            .collect();
    }
    g
}

/// The slopes `b G^-1` of the coefficients in `psi = G phi`: `G^-1` of the
/// unit lower triangular `G` by forward substitution in interval
/// arithmetic (`X_ii = 1`, `X_ij = -sum_{j <= s < i} G_is X_sj`).
#[allow(clippy::needless_range_loop)] // index-heavy linear algebra
fn slopes_in(inv: &Invariants, g: &[Vec<f64>]) -> Vec<Vec<Iv>> {
    let t = g.len();
    let mut x = vec![vec![Iv::point(0.0); t]; t];
    for j in 0..t {
        x[j][j] = Iv::point(1.0);
        for i in j + 1..t {
            let mut acc = Iv::point(0.0);
            for s in j..i {
                acc = acc.add(Iv::point(g[i][s]).mul(x[s][j]));
            }
            x[i][j] = acc.neg();
        }
    }
    inv.b
        .iter()
        .map(|row| {
            (0..t)
                .map(|l| (0..t).fold(Iv::point(0.0), |acc, i| acc.add(row[i].mul(x[i][l]))))
                .collect()
        })
        .collect()
}

/// The summed-area table of the grid cells carrying `code` (`n` cells
/// along each of `t` axes, first axis fastest): `(n + 1)^t` entries.
fn prefix_sums(grid: &[u8], n: usize, t: usize, code: u8) -> Vec<u32> {
    let m = n + 1;
    let mut s = vec![0u32; m.pow(t as u32)];
    // place the indicator at index + 1 along every axis
    let mut idx = vec![0usize; t];
    for &g in grid {
        if g == code {
            let mut flat = 0;
            for i in (0..t).rev() {
                flat = flat * m + idx[i] + 1;
            }
            s[flat] = 1;
        }
        let mut d = 0;
        while d < t {
            idx[d] += 1;
            if idx[d] < n {
                break;
            }
            idx[d] = 0;
            d += 1;
        }
    }
    // cumulative sums along each axis
    let mut stride = 1;
    for _ in 0..t {
        for flat in 0..s.len() {
            if (flat / stride) % m != 0 {
                s[flat] += s[flat - stride];
            }
        }
        stride *= m;
    }
    s
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
            let p = &CharPoly::new(&f).unwrap();
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
                    assert!(
                        (want - got).abs() < 1e-12,
                        "n = {n}, p_{j}: {want} vs {got}"
                    );
                }
            }
        }
    }

    /// The index range of a query holds exactly the grid cells whose
    /// closed boxes meet the query interval (brute force at a small level),
    /// and the prefix sums count the cells of a code in a block.
    #[test]
    fn index_ranges_and_prefix_sums_are_exact() {
        let f = AffineFamily::nurds(5);
        let p = &CharPoly::new(&f).unwrap();
        let inv = &Invariants::new(p).unwrap();
        let mut tree = Tree::new(inv, &[0.3; 5], &[0.32; 5]).unwrap();
        tree.level = 5;
        let n = 1u64 << tree.level;
        let mut rng = SplitMix64::new(12);
        for i in 0..2 {
            let (r0, r1) = (tree.end(i, 0, 0), tree.end(i, 0, 1));
            for _ in 0..300 {
                let mut b0 = rng.uniform(r0, r1);
                let mut b1 = rng.uniform(r0, r1);
                if b1 < b0 {
                    std::mem::swap(&mut b0, &mut b1);
                }
                // end points exactly on grid lines too
                if rng.uniform(0.0, 1.0) < 0.3 {
                    b0 = tree.end(i, tree.level, (b0 - r0) as u64 % n);
                }
                let (a0, a1) = tree.index_range(i, b0, b1).unwrap();
                for a in 0..n {
                    let meets =
                        tree.end(i, tree.level, a) <= b1 && b0 <= tree.end(i, tree.level, a + 1);
                    assert_eq!(
                        meets,
                        a0 <= a && a <= a1,
                        "cell {a} of [{b0}, {b1}]: {a0}..{a1}"
                    );
                }
            }
            assert!(tree.index_range(i, r0 - 1.0, r1).is_none());
        }
        // prefix sums of a 2-d grid against direct counts
        let m = 6;
        let grid: Vec<u8> = (0..m * m)
            .map(|_| (rng.uniform(0.0, 3.0) as u8).min(2))
            .collect();
        let sums = prefix_sums(&grid, m, 2, 1);
        for y0 in 0..m {
            for y1 in y0..m {
                for x0 in 0..m {
                    for x1 in x0..m {
                        let direct = (y0..=y1)
                            .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
                            .filter(|&(x, y)| grid[y * m + x] == 1)
                            .count() as i64;
                        let at = |x: usize, y: usize| i64::from(sums[y * (m + 1) + x]);
                        let got = at(x1 + 1, y1 + 1) - at(x0, y1 + 1) - at(x1 + 1, y0) + at(x0, y0);
                        assert_eq!(got, direct);
                    }
                }
            }
        }
    }

    /// [`Tree::query`] against brute force on a random grid of verdicts:
    /// the verdicts of the grid cells whose closed boxes meet the query box
    /// (found cell by cell from `e(level, a)`, not through the index
    /// ranges or the prefix sums), one verdict when they all agree, else
    /// the properties they agree on. Query end points lie on grid lines
    /// often (where an off-by-one in the index ranges or the table lookup
    /// shows), and outside the root.
    #[test]
    fn grid_queries_match_brute_force() {
        use crate::spectral::ClassName;
        let f = AffineFamily::nurds(5);
        let p = &CharPoly::new(&f).unwrap();
        let inv = &Invariants::new(p).unwrap();
        let mut tree = Tree::new(inv, &[0.3; 5], &[0.32; 5]).unwrap();
        tree.level = 4;
        let n = 1usize << tree.level;
        let t = tree.lo.len();
        assert_eq!(t, 2);
        let verdict = |separation, class| SpectralVerdict { separation, class };
        tree.verdicts = vec![
            OPEN,
            verdict(Status::Certified, Some(ClassName::ComplexPair)),
            verdict(Status::Certified, Some(ClassName::RealDistinct)),
            verdict(Status::Undecided, Some(ClassName::ComplexPair)),
            verdict(Status::Refuted, None),
        ];
        let mut rng = SplitMix64::new(40);
        // a grid of blocks (so that agreeing queries occur) with random cells
        let block: Vec<u8> = (0..16).map(|_| rng.uniform(0.0, 5.0) as u8 % 5).collect();
        let grid: Vec<u8> = (0..n * n)
            .map(|flat| {
                let (x, y) = (flat % n, flat / n);
                if rng.uniform(0.0, 1.0) < 0.1 {
                    rng.uniform(0.0, 5.0) as u8 % 5
                } else {
                    block[(y / 4) * 4 + x / 4]
                }
            })
            .collect();
        tree.sums = (0..tree.verdicts.len())
            .map(|c| prefix_sums(&grid, n, t, c as u8))
            .collect();
        let level = tree.level;
        let point = |rng: &mut SplitMix64, i: usize| -> f64 {
            let (r0, r1) = (tree.end(i, 0, 0), tree.end(i, 0, 1));
            let u = rng.uniform(0.0, 1.0);
            if u < 0.4 {
                // a grid line, the root's ends included
                tree.end(
                    i,
                    level,
                    (rng.uniform(0.0, n as f64 + 1.0) as u64).min(n as u64),
                )
            } else if u < 0.45 {
                // just outside the root
                if u < 0.425 {
                    down(r0)
                } else {
                    up(r1)
                }
            } else {
                rng.uniform(r0, r1)
            }
        };
        let (mut agreeing, mut mixed, mut outside) = (0, 0, 0);
        for _ in 0..4000 {
            let mut blo = vec![0.0; t];
            let mut bhi = vec![0.0; t];
            for i in 0..t {
                let (mut b0, mut b1) = (point(&mut rng, i), point(&mut rng, i));
                if b1 < b0 {
                    std::mem::swap(&mut b0, &mut b1);
                }
                blo[i] = b0;
                bhi[i] = b1;
            }
            let got = tree.query(&blo, &bhi);
            let inside = (0..t).all(|i| tree.end(i, 0, 0) <= blo[i] && bhi[i] <= tree.end(i, 0, 1));
            if !inside {
                outside += 1;
                assert_eq!(got, OPEN, "{blo:?} {bhi:?}");
                continue;
            }
            let meets = |i: usize, a: usize| {
                tree.end(i, level, a as u64) <= bhi[i] && blo[i] <= tree.end(i, level, a as u64 + 1)
            };
            let mut want: Option<SpectralVerdict> = None;
            let mut codes = std::collections::BTreeSet::new();
            for y in (0..n).filter(|&y| meets(1, y)) {
                for x in (0..n).filter(|&x| meets(0, x)) {
                    let v = tree.verdicts[grid[y * n + x] as usize];
                    codes.insert(grid[y * n + x]);
                    want = Some(match want {
                        None => v,
                        Some(w) => SpectralVerdict {
                            separation: if w.separation == v.separation {
                                w.separation
                            } else {
                                Status::Undecided
                            },
                            class: if w.class == v.class { w.class } else { None },
                        },
                    });
                }
            }
            if codes.len() == 1 {
                agreeing += 1;
            } else {
                mixed += 1;
            }
            assert_eq!(Some(got), want, "{blo:?} {bhi:?}");
        }
        // every kind of query occurred
        assert!(
            agreeing > 100 && mixed > 100 && outside > 100,
            "{agreeing} {mixed} {outside}"
        );
    }

    /// The coordinates of the tree: `G^-1` enclosed against `G`, and the
    /// coefficients through `psi = G phi` equal to those through `phi`.
    #[test]
    fn tree_coordinates_reproduce_the_coefficients() {
        let mut rng = SplitMix64::new(6);
        for n in [5, 7] {
            let f = AffineFamily::nurds(n);
            let p = &CharPoly::new(&f).unwrap();
            let inv = &Invariants::new(p).unwrap();
            let (lo, hi) = (vec![0.05; n], vec![0.95; n]);
            let g = decorrelation(inv, &lo, &hi);
            let b = slopes_in(inv, &g);
            for _ in 0..5 {
                let r: Vec<f64> = (0..n).map(|_| rng.uniform(0.05, 0.95)).collect();
                let zero = vec![0.0; n];
                let phi = inv.forms(&r, &zero);
                let psi: Vec<f64> = psi_forms(&g, &phi)
                    .iter()
                    .map(|t| 0.5 * t.c.lo + 0.5 * t.c.hi)
                    .collect();
                let direct =
                    inv.coefficient_forms(&inv.b, &phi.iter().map(|t| t.c.lo).collect::<Vec<_>>());
                let through = inv.coefficient_forms(&b, &psi);
                for j in 0..inv.m {
                    assert!(
                        (direct[j].c.lo - through[j].c.lo).abs() < 1e-12,
                        "n = {n}, p_{j}: {:?} vs {:?}",
                        direct[j].c,
                        through[j].c
                    );
                }
            }
        }
    }
}
