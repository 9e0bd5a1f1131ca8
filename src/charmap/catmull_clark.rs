//! Characteristic maps of the Catmull-Clark family: Catmull-Clark (`c = 1/2`)
//! and the shape-adjustable scheme with parameter `c` in `(0, 1]`.
//!
//! Math doc sections 7 and 8. The scheme is rotationally
//! symmetric, so its subdominant eigenvalue comes from a Fourier mode
//! `l` with a double real eigenvalue (modes `l` and `n - l`), and the
//! characteristic map's control net is the real pair
//! `(x_cos, x_sin)` of [`fourier::mode_patch_eigenvectors`] on the `2n + 8`
//! patch points (Stam's layout, [`PatchLayout`]), orthonormalised into a
//! [`PlanarBasis`] (which also estimates its error). The extended matrix
//! ([`catmull_clark::extended_matrix`]) maps it to the 4 x 4 control windows of
//! the three regular cells `Omega_1, Omega_2, Omega_3` ([`SubPatch`]) of the
//! first ring in sector 0; sector `j` is sector 0 rotated by `j * 2 pi l / n`
//! in the `(x_cos, x_sin)` plane (exact by symmetry; applied here as the
//! corresponding 2 x 2 map in the orthonormal coordinates). So the ring has
//! `3n` cells ([`CcRing`]).
//!
//! **The ring cells are not polynomial for `c != 1/2`.** On a regular grid
//! the scheme is the tensor product of the univariate rule
//! ([`UnivariateRule`]: vertex mask `(c/4, 1 - c/2, c/4)`, edge midpoint;
//! math doc section 8 \[reconstructed\]), whose limit functions are cubic
//! B-splines only at `c = 1/2`. The regularity test is therefore built on the
//! rule itself **\[derived\]**:
//!
//! * symbol `a(z) = (1 + z)^2 (c/4 + (1 - c)/2 z + c/4 z^2) z^-2`, so the
//!   derived (first divided difference) rule has the non-negative mask
//!   `(c/2, 1 - c/2, 1 - c/2, c/2)` and the second one `(c/2, 1 - c, c/2)`
//!   (norm `max(c, 1 - c) < 1` for `0 < c < 1`; at `c = 1` its two-step
//!   norm is `1/2`). Both the rule and the derived rule are therefore
//!   convergent with non-negative masks, so their limit functions are
//!   non-negative partitions of unity (support width 4 and 3 cells), and a
//!   cell's limit values lie in the convex hull of its 4 x 4 window, and its
//!   `u`-derivatives (in grid units) in the convex hull of the 3 x 4 window of
//!   `u`-differences `a_ij = W[i+1][j] - W[i][j]` (likewise `v`: `b_ij`, 4 x 3);
//! * the Jacobian `det(d_u chi, d_v chi)` is bilinear, so `det(a_ij, b_kl) > 0`
//!   for all 144 pairs certifies `J > 0` on the cell (**cone test**);
//!   otherwise the window is refined with the rule (a 4 x 4 window determines
//!   the 4 x 4 windows of its four sub-cells) and the sub-cells are tested,
//!   up to [`CONE_MAX_DEPTH`]; this converges wherever `J != 0`;
//! * a witness of non-regularity: at a grid vertex the limit derivative is a
//!   positive multiple of the central difference
//!   `sum_b w_b (W[a+1][b] - W[a-1][b])`, `w = (alpha, beta, alpha)` the limit
//!   stencil ([`UnivariateRule::limit_weights`], `beta = 1/(1 + c)`); a cell
//!   corner with `sigma J < 0` beyond its error bound proves the map folds.
//!
//! At `c = 1/2` the cells are uniform bicubic B-spline patches and
//! [`check_bicubic`] runs the Bezier test of the Doo-Sabin family instead
//! (Jacobian of bidegree (5, 5), [`super::regularity::check_bezier_patches`]):
//! two independent certificates for Catmull-Clark.
//!
//! **Injectivity**: the ring's outer boundary (per sector the `s = 1` edges of
//! `Omega_1, Omega_2` and the `t = 1` edges of `Omega_2, Omega_3`, reversed) is
//! a chain of limit curves of the univariate rule applied to the limit-stencil
//! combination of three window rows ([`WindowCurve`], convex-hull property as
//! above), and its certified winding number about the origin
//! ([`super::winding::winding_number`]) must be 1 once the plane is oriented
//! so that the Jacobian is positive. The inner boundary is checked as well
//! (cross-check). A subdominant pair from mode `l > 1` gives winding `l`
//! (not injective).
//!
//! Error control as in the parent module: the subspace error is estimated
//! ([`PlanarBasis::vector_error`]); all rounding after it is bounded with
//! `gamma_k` ([`ConeErrorModel`]).
//!
//! ```
//! use subdiv_lab::charmap::catmull_clark::check;
//! use subdiv_lab::charmap::Verdict;
//! // Catmull-Clark at valence 5, and the shape-adjustable scheme at c = 0.3
//! assert_eq!(check(5, 0.5).unwrap().verdict, Verdict::C1Standard);
//! assert_eq!(check(7, 0.3).unwrap().verdict, Verdict::C1Standard);
//! ```

use super::regularity::{
    check_bezier_patches, gamma, Coefficients, DomainPoint, Regularity, RegularityVerdict,
};
pub use super::report::CcPatchId;
use super::verdict::{assemble_report, propagated_error, structure_of};
use super::winding::{winding_number, HullCurve};
use super::{CharmapReport, Eigenstructure, PlanarBasis};
use crate::bezier::{PlanarPatch, TensorBezier};
use crate::error::{Error, Result};
use crate::schemes::catmull_clark::ring::{
    bicubic_bezier, refine_grid, refine_window, UnivariateRule, Window,
};
use crate::schemes::catmull_clark::{self, fourier, PatchLayout, SubPatch};
use crate::schemes::LocalScheme;
use crate::spectral::{classify_scheme, Subdominant, SubdominantClass};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Maximum refinement depth of the cone test per cell (sub-cells of side `2^-12`).
pub const CONE_MAX_DEPTH: u32 = 12;

/// Maximum number of cells examined by the cone test per ring.
pub const CONE_MAX_PIECES: usize = 50_000;

/// Largest accepted relative distance between the classified subdominant
/// eigenvalue and the closed-form Fourier eigenvalue of the selected mode:
/// both are computed to a few ulps of `O(1)` quantities (the classification's
/// error radii are far below this), so a larger distance means no Fourier
/// mode carries the subdominant pair and the verdict is indeterminate.
pub const MODE_MATCH_TOL: f64 = 1e-9;

fn diff(p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    [p[0] - q[0], p[1] - q[1]]
}

fn det(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The `u`-differences (3 x 4) and `v`-differences (4 x 3) of a window, scaled by `2^depth`.
fn differences(w: &Window, scale: f64) -> ([[f64; 2]; 12], [[f64; 2]; 12]) {
    let mut du = [[0.0; 2]; 12];
    let mut dv = [[0.0; 2]; 12];
    for i in 0..3 {
        for j in 0..4 {
            let d = diff(w[i + 1][j], w[i][j]);
            du[i * 4 + j] = [d[0] * scale, d[1] * scale];
            let e = diff(w[j][i + 1], w[j][i]);
            dv[j * 3 + i] = [e[0] * scale, e[1] * scale];
        }
    }
    (du, dv)
}

/// `(min, max)` of `det(a, b)` over all pairs, with the pair attaining the minimum.
fn cone_range(du: &[[f64; 2]; 12], dv: &[[f64; 2]; 12], sigma: f64) -> (f64, f64, usize, usize) {
    let (mut lo, mut hi, mut at) = (f64::INFINITY, 0.0f64, (0, 0));
    for (i, a) in du.iter().enumerate() {
        for (k, b) in dv.iter().enumerate() {
            let d = sigma * det(*a, *b);
            hi = hi.max(d.abs());
            if d < lo {
                lo = d;
                at = (i, k);
            }
        }
    }
    (lo, hi, at.0, at.1)
}

/// Jacobian (up to a positive factor, grid units scaled by `2^depth`) at the
/// window vertex `(a, b)`, `a, b` in `{1, 2}` (the cell corners).
fn vertex_jacobian(rule: &UnivariateRule, w: &Window, a: usize, b: usize, scale: f64) -> f64 {
    let wt = rule.limit_weights();
    let mut du = [0.0; 2];
    let mut dv = [0.0; 2];
    for k in 0..3 {
        let d = diff(w[a + 1][b + k - 1], w[a - 1][b + k - 1]);
        let e = diff(w[a + k - 1][b + 1], w[a + k - 1][b - 1]);
        for c in 0..2 {
            du[c] += wt[k] * d[c] * scale;
            dv[c] += wt[k] * e[c] * scale;
        }
    }
    det(du, dv)
}

/// The floating-point error model of the cone test **\[derived\]**.
///
/// `delta` bounds the error of every window coordinate, `pmax` their
/// magnitude, `md` the magnitude of the differences (in grid units; the
/// differences of refined windows scaled by `2^depth` are convex combinations
/// of the parent's, so `md` bounds them at every depth up to rounding).
///
/// * Refinement forms each point from at most 3 points per direction with
///   weights summing to `1 + O(u)`: each level adds `gamma_8 pmax` (both
///   directions) and scales the inherited error by at most `1 + gamma_2`, so at
///   depth `d` the points are off by `delta_d = delta (1 + gamma_{2d}) + d gamma_8 pmax`.
/// * A scaled difference `2^d (p - q)` is off by `e_d = 2^{d+1} delta_d + gamma_2 md`
///   (the scaling by a power of two is exact).
/// * `det(a, b) = a_x b_y - a_y b_x` is off by at most
///   `2 (2 e_d md + e_d^2) + 2 gamma_3 md^2`.
/// * A vertex Jacobian uses central differences (magnitude `<= 2 md`)
///   combined with the limit stencil (weights summing to `1 + O(u)`): the
///   same bound with `e_d` replaced by `2 e_d + gamma_8 2 md` and `md` by `2 md`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ConeErrorModel {
    /// Error bound of the window points (absolute, per coordinate).
    pub delta: f64,
    /// Largest coordinate magnitude of a window point.
    pub pmax: f64,
    /// Largest coordinate magnitude of a difference.
    pub md: f64,
}

impl ConeErrorModel {
    fn point_error(&self, depth: u32) -> f64 {
        self.delta * (1.0 + gamma(2 * depth as usize)) + depth as f64 * gamma(8) * self.pmax
    }

    /// Bound on the error of a pairwise determinant at `depth`.
    pub fn det_bound(&self, depth: u32) -> f64 {
        let e = 2f64.powi(depth as i32 + 1) * self.point_error(depth) + gamma(2) * self.md;
        2.0 * (2.0 * e * self.md + e * e) + 2.0 * gamma(3) * self.md * self.md
    }

    /// Bound on the error of a vertex Jacobian at `depth`.
    pub fn vertex_bound(&self, depth: u32) -> f64 {
        let e = 2f64.powi(depth as i32 + 1) * self.point_error(depth) + gamma(2) * self.md;
        let e2 = 2.0 * e + gamma(8) * 2.0 * self.md;
        let m2 = 2.0 * self.md;
        2.0 * (2.0 * e2 * m2 + e2 * e2) + 2.0 * gamma(3) * m2 * m2
    }
}

/// Cone-test regularity of a set of cells (see the module docs); `delta`
/// bounds the error of the window points. An empty set is an error.
pub fn check_cone_regularity(
    rule: &UnivariateRule,
    cells: &[(CcPatchId, Window)],
    delta: f64,
) -> Result<Regularity<CcPatchId>> {
    let Some(first) = cells.first() else {
        return Err(Error::CountMismatch {
            what: "cells for the regularity check",
            expected: 1,
            got: 0,
        });
    };
    let mut pmax = 0.0f64;
    let mut md = 0.0f64;
    let mut area = 0.0;
    let mut cmax = 0.0f64;
    for (_, w) in cells {
        for row in w {
            for p in row {
                pmax = pmax.max(p[0].abs()).max(p[1].abs());
            }
        }
        let (du, dv) = differences(w, 1.0);
        for d in du.iter().chain(&dv) {
            md = md.max(d[0].abs()).max(d[1].abs());
        }
        for a in &du {
            for b in &dv {
                let d = det(*a, *b);
                area += d;
                cmax = cmax.max(d.abs());
            }
        }
    }
    let model = ConeErrorModel { delta, pmax, md };
    let sigma = if area < 0.0 { -1.0 } else { 1.0 };
    let scale = if cmax > 0.0 { cmax } else { 1.0 };
    // location of a difference pair: midpoint of the two differences' centres
    // in cell coordinates (window index k sits at k - 1), clamped to the cell.
    let locate = |i: usize, k: usize| {
        let (ia, ja) = (i / 4, i % 4);
        let (ib, jb) = (k / 3, k % 3);
        let s = 0.5 * ((ia as f64 - 0.5) + (ib as f64 - 1.0));
        let t = 0.5 * ((ja as f64 - 1.0) + (jb as f64 - 0.5));
        (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0))
    };
    let mut min_coeff = f64::INFINITY;
    let mut min_location = DomainPoint {
        patch: first.0,
        s: 0.5,
        t: 0.5,
    };
    for (id, w) in cells {
        let (du, dv) = differences(w, 1.0);
        let (lo, _, i, k) = cone_range(&du, &dv, sigma);
        if lo < min_coeff {
            min_coeff = lo;
            let (s, t) = locate(i, k);
            min_location = DomainPoint { patch: *id, s, t };
        }
    }
    let mut out = Regularity::initial(sigma, min_coeff, min_location, model.det_bound(0), cmax);
    out.coefficients = Coefficients::DerivativeCones;
    if out.verdict == RegularityVerdict::Indeterminate {
        return Ok(out);
    }
    let mut work: Vec<(usize, Window, f64, f64, f64, u32)> = cells
        .iter()
        .enumerate()
        .map(|(k, (_, w))| (k, *w, 0.0, 0.0, 1.0, 0))
        .collect();
    while let Some((k, w, s0, t0, h, depth)) = work.pop() {
        let id = cells[k].0;
        out.pieces += 1;
        out.max_depth = out.max_depth.max(depth);
        let sc = 2f64.powi(depth as i32);
        let (du, dv) = differences(&w, sc);
        let (lo, hi, _, _) = cone_range(&du, &dv, sigma);
        let bound = model.det_bound(depth);
        if lo > bound {
            continue;
        }
        // refinement shrinks the spread of the determinants, never below the
        // rounding floor: once the floor exceeds every determinant of the
        // piece, no depth can certify it
        let hopeless = bound >= hi;
        let vb = model.vertex_bound(depth);
        for (a, b) in [(1, 1), (2, 1), (1, 2), (2, 2)] {
            let v = sigma * vertex_jacobian(rule, &w, a, b, sc);
            if v < -vb {
                let (s, t) = (s0 + h * (a - 1) as f64, t0 + h * (b - 1) as f64);
                out.verdict = RegularityVerdict::NotRegular;
                out.witness = Some((DomainPoint { patch: id, s, t }, v / scale));
                return Ok(out);
            }
        }
        if hopeless || depth >= CONE_MAX_DEPTH || out.pieces + work.len() + 4 > CONE_MAX_PIECES {
            out.verdict = RegularityVerdict::Indeterminate;
            out.undecided.get_or_insert(DomainPoint {
                patch: id,
                s: s0,
                t: t0,
            });
            continue;
        }
        let h2 = h / 2.0;
        for (q, sub) in refine_window(rule, &w).into_iter().enumerate() {
            let (ds, dt) = ((q % 2) as f64 * h2, (q / 2) as f64 * h2);
            work.push((k, sub, s0 + ds, t0 + dt, h2, depth + 1));
        }
    }
    Ok(out)
}

/// A boundary curve of a ring cell: the limit curve of the univariate rule
/// on the 4-point polygon `q` (restricted to the middle span), where `q` is
/// the limit-stencil combination of three window rows (the curve along a grid
/// line of the tensor-product limit). Convex hull: `q` (non-negative basis);
/// end points by the limit stencil.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindowCurve {
    rule: UnivariateRule,
    q: [[f64; 2]; 4],
}

impl WindowCurve {
    /// The curve of polygon `q` under `rule`.
    pub fn new(rule: UnivariateRule, q: [[f64; 2]; 4]) -> Self {
        Self { rule, q }
    }

    /// The same curve traversed backwards.
    pub fn reversed(&self) -> Self {
        Self {
            rule: self.rule,
            q: [self.q[3], self.q[2], self.q[1], self.q[0]],
        }
    }

    /// Start point (limit at `q_1`).
    pub fn start(&self) -> [f64; 2] {
        self.rule.limit3(self.q[0], self.q[1], self.q[2])
    }

    /// End point (limit at `q_2`).
    pub fn end(&self) -> [f64; 2] {
        self.rule.limit3(self.q[1], self.q[2], self.q[3])
    }
}

impl HullCurve for WindowCurve {
    fn hull(&self) -> Vec<[f64; 2]> {
        vec![
            self.start(),
            self.q[0],
            self.q[1],
            self.q[2],
            self.q[3],
            self.end(),
        ]
    }
    fn halves(&self) -> (Self, Self) {
        let r = self.rule.refine4(&self.q);
        (
            Self::new(self.rule, [r[0], r[1], r[2], r[3]]),
            Self::new(self.rule, [r[1], r[2], r[3], r[4]]),
        )
    }
    /// Three-term combinations with weights summing to `1 + O(u)`.
    fn split_error(&self, scale: f64) -> f64 {
        2.0 * gamma(4) * scale
    }
    /// End points: a three-term stencil whose computed weights are off by a few ulps.
    fn hull_error(&self, scale: f64) -> f64 {
        gamma(8) * scale
    }
}

/// The `3n` cells of a Catmull-Clark-family characteristic ring with their
/// 4 x 4 windows, in the order sector 0 (`Omega_1, Omega_2, Omega_3`), sector 1, ...
#[derive(Clone, Debug, PartialEq)]
pub struct CcRing {
    rule: UnivariateRule,
    n: usize,
    cells: Vec<(CcPatchId, Window)>,
}

impl CcRing {
    /// The ring from the sector-0 windows (`[Omega_1, Omega_2, Omega_3]`) and
    /// the 2 x 2 maps taking sector 0 to sector `j` (`maps[j]`, row-major;
    /// `maps[0]` the identity).
    pub fn from_sector(rule: UnivariateRule, sector0: [Window; 3], maps: &[[[f64; 2]; 2]]) -> Self {
        let n = maps.len();
        let mut cells = Vec::with_capacity(3 * n);
        for (j, g) in maps.iter().enumerate() {
            for (m, w) in SubPatch::ALL.iter().zip(&sector0) {
                let mut out = *w;
                for row in out.iter_mut() {
                    for p in row.iter_mut() {
                        *p = [
                            g[0][0] * p[0] + g[0][1] * p[1],
                            g[1][0] * p[0] + g[1][1] * p[1],
                        ];
                    }
                }
                cells.push((CcPatchId { sector: j, sub: *m }, out));
            }
        }
        Self { rule, n, cells }
    }

    /// A ring from explicit cells (e.g. a deliberately perturbed ring): `3n`
    /// cells, `n >= 3`, ordered sector 0 (`Omega_1, Omega_2, Omega_3`), sector
    /// 1, ..., each labelled accordingly.
    pub fn from_cells(rule: UnivariateRule, cells: Vec<(CcPatchId, Window)>) -> Result<Self> {
        let n = cells.len() / 3;
        if n < 3 || cells.len() != 3 * n {
            return Err(Error::CountMismatch {
                what: "ring cells (3 per sector, at least 3 sectors)",
                expected: 3 * n.max(3),
                got: cells.len(),
            });
        }
        for (k, (id, _)) in cells.iter().enumerate() {
            let want = CcPatchId {
                sector: k / 3,
                sub: SubPatch::ALL[k % 3],
            };
            if *id != want {
                return Err(Error::InvalidParameter {
                    name: "ring cell order",
                    value: id.to_string(),
                    reason: "cells must be ordered by sector, then Omega_1, Omega_2, Omega_3",
                });
            }
        }
        Ok(Self { rule, n, cells })
    }

    /// The valence.
    pub fn valence(&self) -> usize {
        self.n
    }

    /// The cells.
    pub fn cells(&self) -> &[(CcPatchId, Window)] {
        &self.cells
    }

    /// The univariate rule.
    pub fn rule(&self) -> &UnivariateRule {
        &self.rule
    }

    /// The ring with the second coordinate negated (reverses orientation).
    pub fn mirrored(&self) -> Self {
        let mut out = self.clone();
        for (_, w) in out.cells.iter_mut() {
            for row in w.iter_mut() {
                for p in row.iter_mut() {
                    p[1] = -p[1];
                }
            }
        }
        out
    }

    fn cell(&self, sector: usize, m: usize) -> &Window {
        &self.cells[3 * sector + m].1
    }

    /// Curve along the grid column `a` (in `t`) of a window.
    fn column(&self, w: &Window, a: usize) -> WindowCurve {
        let q = std::array::from_fn(|b| self.rule.limit3(w[a - 1][b], w[a][b], w[a + 1][b]));
        WindowCurve::new(self.rule, q)
    }

    /// Curve along the grid row `b` (in `s`) of a window.
    fn row(&self, w: &Window, b: usize) -> WindowCurve {
        let q = std::array::from_fn(|a| self.rule.limit3(w[a][b - 1], w[a][b], w[a][b + 1]));
        WindowCurve::new(self.rule, q)
    }

    /// The outer boundary, counter-clockwise in the charts (per sector: the
    /// `s = 1` edges of `Omega_1` and `Omega_2`, then the `t = 1` edges of
    /// `Omega_2` and `Omega_3` backwards).
    pub fn outer_boundary(&self) -> Vec<WindowCurve> {
        let mut out = Vec::with_capacity(4 * self.n);
        for j in 0..self.n {
            out.push(self.column(self.cell(j, 0), 2));
            out.push(self.column(self.cell(j, 1), 2));
            out.push(self.row(self.cell(j, 1), 2).reversed());
            out.push(self.row(self.cell(j, 2), 2).reversed());
        }
        out
    }

    /// The inner boundary, same direction (per sector: the `s = 0` edge of
    /// `Omega_1`, then the `t = 0` edge of `Omega_3` backwards).
    pub fn inner_boundary(&self) -> Vec<WindowCurve> {
        let mut out = Vec::with_capacity(2 * self.n);
        for j in 0..self.n {
            out.push(self.column(self.cell(j, 0), 1));
            out.push(self.row(self.cell(j, 2), 1).reversed());
        }
        out
    }

    /// The cells as uniform bicubic Bezier patches (valid at `c = 1/2` only,
    /// where the rule is cubic B-spline refinement): per direction
    /// `b_0 = (d_0 + 4 d_1 + d_2)/6, b_1 = (2 d_1 + d_2)/3, b_2 = (d_1 + 2 d_2)/3,
    /// b_3 = (d_1 + 4 d_2 + d_3)/6`. `None` for `c != 1/2`.
    pub fn bicubic_patches(&self) -> Option<Vec<(CcPatchId, PlanarPatch)>> {
        if self.rule.c() != 0.5 {
            return None;
        }
        let coord = |w: &Window, k: usize| {
            let mut out = [[0.0; 4]; 4];
            for (a, row) in bicubic_bezier(w, k).into_iter().enumerate() {
                out[a] = row;
            }
            TensorBezier::from_fn(3, 3, |a, b| out[a][b])
        };
        Some(
            self.cells
                .iter()
                .map(|(id, w)| {
                    (
                        *id,
                        PlanarPatch {
                            x: coord(w, 0),
                            y: coord(w, 1),
                        },
                    )
                })
                .collect(),
        )
    }
}

/// The characteristic ring of the adjustable scheme at `(n, c)` with its
/// planar basis, from Fourier mode `l`, and the error bound of its window
/// points (see [`point_error`]).
#[derive(Clone, Debug)]
pub struct PreparedRing {
    /// The ring (orthonormal coordinates of [`PreparedRing::basis`]).
    pub ring: CcRing,
    /// The planar basis on the `2n + 8` patch points.
    pub basis: PlanarBasis,
    /// The Fourier mode of the subdominant pair.
    pub mode: usize,
    /// Absolute error bound of the window points.
    pub point_error: f64,
}

/// Builds the ring of mode `l` at `(n, c)`; `gap` is a lower bound on the
/// distance of the subdominant eigenvalue from the rest of the spectrum.
pub fn prepare_ring(n: usize, c: f64, l: usize, gap: f64) -> Result<PreparedRing> {
    let rule = UnivariateRule::new(c)?;
    let (lambda, [xc, xs]) = fourier::mode_patch_eigenvectors(n, c, l)?;
    let a = catmull_clark::patch_matrix::<f64>(n, &c)?.into_matrix();
    let lam = [Complex64::new(lambda, 0.0); 2];
    let basis = PlanarBasis::new(
        &a,
        Eigenstructure::Standard,
        lam,
        xc.as_slice(),
        xs.as_slice(),
        gap,
    )?;
    // (x_cos, x_sin) = (w1, w2) U^T with U = [[u11, 0], [u21, u22]] (Gram-Schmidt)
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let u11 = dot(xc.as_slice(), &basis.w1);
    let u21 = dot(xs.as_slice(), &basis.w1);
    let u22 = dot(xs.as_slice(), &basis.w2);
    if !(u11.abs() > 0.0 && u22.abs() > 0.0) {
        return Err(Error::Numerical {
            routine: "Catmull-Clark characteristic map",
            reason: format!("degenerate mode-{l} eigenvector pair at n = {n}, c = {c}"),
        });
    }
    // sector j in orthonormal coordinates: G_j = U^{-1} R(j theta) U, with
    // p_X = U p_W, U = [[u11, 0], [u21, u22]].
    let theta = 2.0 * PI * l as f64 / n as f64;
    let maps: Vec<[[f64; 2]; 2]> = (0..n)
        .map(|j| {
            if j == 0 {
                return [[1.0, 0.0], [0.0, 1.0]];
            }
            let (sn, cs) = (j as f64 * theta).sin_cos();
            // R U
            let ru = [
                [cs * u11 - sn * u21, -sn * u22],
                [sn * u11 + cs * u21, cs * u22],
            ];
            // U^{-1} = [[1/u11, 0], [-u21/(u11 u22), 1/u22]]
            [
                [ru[0][0] / u11, ru[0][1] / u11],
                [
                    (ru[1][0] - u21 / u11 * ru[0][0]) / u22,
                    (ru[1][1] - u21 / u11 * ru[0][1]) / u22,
                ],
            ]
        })
        .collect();
    let ext = catmull_clark::extended_matrix::<f64>(n, &c)?.into_matrix();
    let lay = PatchLayout::new(n)?;
    let pts: Vec<[f64; 2]> = (0..ext.nrows())
        .map(|i| {
            let row = ext.row(i);
            [
                row.iter().zip(&basis.w1).map(|(a, b)| a * b).sum(),
                row.iter().zip(&basis.w2).map(|(a, b)| a * b).sum(),
            ]
        })
        .collect();
    let sector0: [Window; 3] = std::array::from_fn(|m| {
        let idx = lay.sub_patch(SubPatch::ALL[m]);
        std::array::from_fn(|a| std::array::from_fn(|b| pts[idx[a][b]]))
    });
    let ring = CcRing::from_sector(rule, sector0, &maps);
    let delta = point_error(&ext, &basis, &maps);
    Ok(PreparedRing {
        ring,
        basis,
        mode: l,
        point_error: delta,
    })
}

/// Error bound of the window points **\[derived\]**: the extended matrix has
/// absolute row sums `rho`, so sector 0's points are off by at most
/// `rho vector_error + gamma_{K} rho max|w|` (`K` = nonzeros per row + 1);
/// the sector maps `G_j` (infinity norm `g`, entries computed with a few
/// roundings) multiply that by `g` and add `gamma_8 g pmax`; the
/// bicubic-to-Bezier conversion of [`check_bicubic`] adds `gamma_10 pmax`
/// (two passes of 3-term convex combinations), included here so one bound
/// serves both tests.
pub fn point_error(
    ext: &nalgebra::DMatrix<f64>,
    basis: &PlanarBasis,
    maps: &[[[f64; 2]; 2]],
) -> f64 {
    let (e0, p0) = propagated_error(ext, basis);
    let g = maps
        .iter()
        .map(|m| (m[0][0].abs() + m[0][1].abs()).max(m[1][0].abs() + m[1][1].abs()))
        .fold(1.0f64, f64::max);
    let pmax = g * p0;
    g * e0 + gamma(8) * pmax + gamma(10) * pmax
}

/// The subdominant Fourier mode: the `l` in `1..=(n-1)/2` (the modes with a
/// rotating pair) whose larger block
/// eigenvalue is closest to `lambda`, with its relative distance.
fn subdominant_mode(n: usize, c: f64, lambda: f64) -> Result<(usize, f64)> {
    let mut best = (1, f64::INFINITY);
    for l in 1..=(n - 1) / 2 {
        let ev = fourier::block_eigenvalues(n, l, c)?;
        let mu = ev[0].re.max(ev[1].re);
        let d = (mu - lambda).abs() / lambda.abs().max(f64::MIN_POSITIVE);
        if d < best.1 {
            best = (l, d);
        }
    }
    Ok(best)
}

/// Which regularity certificate to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Certificate {
    /// The cone test on the rule's derived windows (any `c` in `(0, 1]`).
    Cone,
    /// The Bezier Jacobian of bidegree (5, 5) (Catmull-Clark, `c = 1/2`, only).
    Bicubic,
}

impl Certificate {
    /// The default for `c`: the bicubic Bezier certificate the literature
    /// uses for Catmull-Clark proper (`c = 1/2`), the cone certificate for
    /// every other `c` (non-polynomial cells).
    pub fn for_c(c: f64) -> Self {
        if c == 0.5 {
            Certificate::Bicubic
        } else {
            Certificate::Cone
        }
    }
}

/// The characteristic-map check of the adjustable scheme at `(n, c)`,
/// classification included (common engine on the one-ring matrix), with the
/// cone test. Eigenstructures other than `standard` have no map here (for
/// these symmetric schemes they only arise as `not_separated` or
/// `indeterminate`, e.g. at `c = 0`).
pub fn check(n: usize, c: f64) -> crate::spectral::Result<CharmapReport<CcPatchId>> {
    check_with(n, c, Certificate::Cone)
}

/// Catmull-Clark (`c = 1/2`) with the bicubic Bezier certificate.
pub fn check_bicubic(n: usize) -> crate::spectral::Result<CharmapReport<CcPatchId>> {
    check_with(n, 0.5, Certificate::Bicubic)
}

/// [`check`] with a choice of certificate (`Bicubic` requires `c = 1/2`).
pub fn check_with(
    n: usize,
    c: f64,
    cert: Certificate,
) -> crate::spectral::Result<CharmapReport<CcPatchId>> {
    if cert == Certificate::Bicubic && c != 0.5 {
        return Err(Error::InvalidParameter {
            name: "c",
            value: c.to_string(),
            reason: "the bicubic Bezier certificate exists only for c = 1/2 (Catmull-Clark)",
        }
        .into());
    }
    let scheme = LocalScheme::<f64>::adjustable_cc(n, c)?;
    let sub = classify_scheme(&scheme)?;
    Ok(check_classified(n, c, &sub, cert)?)
}

/// The check when the classification `sub` of `(n, c)` is already known.
pub fn check_classified(
    n: usize,
    c: f64,
    sub: &Subdominant,
    cert: Certificate,
) -> Result<CharmapReport<CcPatchId>> {
    match &sub.class {
        SubdominantClass::Standard => {}
        other => {
            let (class, reason) = match structure_of(other) {
                Err(cr) => cr,
                Ok(s) => (
                    s.as_str().to_owned(),
                    "a rotationally symmetric scheme with a simple subdominant eigenvalue \
                     (Fourier mode 0 or n/2) has no planar subdominant pair"
                        .to_owned(),
                ),
            };
            return Ok(CharmapReport::no_map(&class, &reason));
        }
    }
    if c <= 0.0 {
        return Ok(CharmapReport::no_map(
            "standard",
            "c = 0: the regular rule is linear interpolation and its derived rule does not \
             converge, so the cone certificate does not apply",
        ));
    }
    let lambda = sub.lambda1.re;
    let (l, dist) = subdominant_mode(n, c, lambda)?;
    if dist > MODE_MATCH_TOL {
        return Ok(CharmapReport {
            structure: Some(Eigenstructure::Standard),
            regularity: None,
            winding_number: None,
            inner_winding_number: None,
            point_error: f64::NAN,
            verdict: super::Verdict::Indeterminate {
                reason: format!(
                    "no Fourier mode matches the subdominant eigenvalue {lambda} \
                     (closest: mode {l}, relative distance {dist:.1e})"
                ),
            },
        });
    }
    let gap = sub.gap.min(1.0 - sub.lambda1.norm());
    let prep = prepare_ring(n, c, l, gap)?;
    Ok(check_ring(&prep.ring, prep.point_error, cert))
}

/// Regularity, winding numbers and verdict of a ring whose window points are
/// accurate to `delta`.
pub fn check_ring(ring: &CcRing, delta: f64, cert: Certificate) -> CharmapReport<CcPatchId> {
    let reg = match cert {
        Certificate::Cone => check_cone_regularity(ring.rule(), ring.cells(), delta),
        Certificate::Bicubic => match ring.bicubic_patches() {
            Some(p) => {
                let refs: Vec<(CcPatchId, &PlanarPatch)> = p.iter().map(|(i, q)| (*i, q)).collect();
                check_bezier_patches(&refs, delta)
            }
            None => check_cone_regularity(ring.rule(), ring.cells(), delta),
        },
    };
    // a ring has 3n >= 9 cells
    let reg = match reg {
        Ok(r) => r,
        Err(e) => {
            return CharmapReport {
                structure: Some(Eigenstructure::Standard),
                regularity: None,
                winding_number: None,
                inner_winding_number: None,
                point_error: delta,
                verdict: super::Verdict::Indeterminate {
                    reason: e.to_string(),
                },
            }
        }
    };
    let oriented;
    let r = if reg.orientation < 0 {
        oriented = ring.mirrored();
        &oriented
    } else {
        ring
    };
    let winding = winding_number(&r.outer_boundary(), delta);
    let inner = winding_number(&r.inner_boundary(), delta);
    assemble_report(reg, winding, inner, delta, Eigenstructure::Standard)
}

/// Plot data of the ring of the adjustable scheme at `(n, c)` (classified as
/// `sub`) and `levels - 1` further rings, in the format of the Doo-Sabin
/// family (`super::figure::RingPlot`): each cell's window is refined with
/// the rule until its side has at least `per_side - 1` spans (at most 6
/// levels), the limit points of the grid vertices (limit stencil) give the
/// outline, and the vertex Jacobians (central differences with the limit
/// stencil) the sign samples. `None` for the plot when there is no map.
pub fn plot_data(
    n: usize,
    c: f64,
    sub: &Subdominant,
    levels: usize,
    per_side: usize,
) -> Result<(
    CharmapReport<super::AnyPatchId>,
    Option<super::figure::RingPlot>,
)> {
    use super::figure::{advance, sign, PatchPlot, RingPlot};
    use super::AnyPatchId;
    let report = check_classified(n, c, sub, Certificate::for_c(c))?;
    let prep = match (&report.regularity, c > 0.0) {
        (Some(_), true) => {
            let lambda = sub.lambda1.re;
            let (l, _) = subdominant_mode(n, c, lambda)?;
            prepare_ring(n, c, l, sub.gap.min(1.0 - sub.lambda1.norm()))?
        }
        _ => return Ok((report.map_patches(AnyPatchId::CatmullClark), None)),
    };
    let orientation = report.regularity.as_ref().map_or(1, |r| r.orientation);
    let sigma = f64::from(orientation);
    let rule = *prep.ring.rule();
    let [al, be, _] = rule.limit_weights();
    let mut depth = 0;
    while (1usize << depth) + 1 < per_side.max(2) && depth < 6 {
        depth += 1;
    }
    let mut patches = Vec::new();
    for (id, w) in prep.ring.cells() {
        let mut g: Vec<Vec<[f64; 2]>> = w.iter().map(|r| r.to_vec()).collect();
        for _ in 0..depth {
            g = refine_grid(&rule, &g);
        }
        let m = g.len(); // 2^depth + 3; the cell spans indices 1..=m-2
        let lim = |a: usize, b: usize| {
            let mut p = [0.0; 2];
            for (da, wa) in [(0, al), (1, be), (2, al)] {
                for (db, wb) in [(0, al), (1, be), (2, al)] {
                    for k in 0..2 {
                        p[k] += wa * wb * g[a + da - 1][b + db - 1][k];
                    }
                }
            }
            p
        };
        let jac = |a: usize, b: usize| {
            let (e, wv, no, so) = (lim(a + 1, b), lim(a - 1, b), lim(a, b + 1), lim(a, b - 1));
            sigma * det([e[0] - wv[0], e[1] - wv[1]], [no[0] - so[0], no[1] - so[1]])
        };
        let (lo, hi) = (1, m - 2);
        let mut ring_outline = Vec::with_capacity(4 * (hi - lo) + 1);
        for a in lo..=hi {
            ring_outline.push(lim(a, lo));
        }
        for b in lo + 1..=hi {
            ring_outline.push(lim(hi, b));
        }
        for a in (lo..hi).rev() {
            ring_outline.push(lim(a, hi));
        }
        for b in (lo..hi).rev() {
            ring_outline.push(lim(lo, b));
        }
        // sign samples on the interior vertices whose 3x3 neighbours exist
        let mut ring_samples = Vec::new();
        let step = ((hi - lo) / per_side.max(2)).max(1);
        for a in (lo..=hi).step_by(step) {
            for b in (lo..=hi).step_by(step) {
                if a >= 2 && b >= 2 && a + 2 < m && b + 2 < m {
                    ring_samples.push((lim(a, b), sign(jac(a, b))));
                }
            }
        }
        for level in 0..levels.max(1) {
            let map = |p: [f64; 2]| advance(p, prep.basis.restriction, level);
            patches.push(PatchPlot {
                level,
                patch: AnyPatchId::CatmullClark(*id),
                outline: ring_outline.iter().map(|p| map(*p)).collect(),
                samples: ring_samples.iter().map(|(p, s)| (map(*p), *s)).collect(),
            });
        }
    }
    Ok((
        report.map_patches(AnyPatchId::CatmullClark),
        Some(RingPlot {
            patches,
            orientation,
        }),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::charmap::Verdict;

    #[test]
    fn rule_refinement_is_cubic_bspline_at_half() {
        let r = UnivariateRule::new(0.5).unwrap();
        let q = [[0.0, 0.0], [1.0, 0.0], [3.0, 0.0], [7.0, 0.0]];
        let out = r.refine4(&q);
        let expect = [
            0.5,
            (0.0 + 6.0 + 3.0) / 8.0,
            2.0,
            (1.0 + 18.0 + 7.0) / 8.0,
            5.0,
        ];
        for (o, e) in out.iter().zip(expect) {
            assert!((o[0] - e).abs() < 1e-15);
        }
    }

    /// `||S_d^k||_inf` for the difference rule `d(z)` of the derived rule
    /// (`d = c/2 + (1 - c) z + c/2 z^2`): max over residues mod `2^k` of the
    /// absolute coefficient sums of `d(z) d(z^2) ... d(z^(2^(k-1)))`.
    fn difference_rule_norm(c: f64, k: u32) -> f64 {
        let mut poly = vec![1.0];
        for j in 0..k {
            let step = 1usize << j;
            let d = [c / 2.0, 1.0 - c, c / 2.0];
            let mut out = vec![0.0; poly.len() + 2 * step];
            for (i, p) in poly.iter().enumerate() {
                for (e, q) in d.iter().enumerate() {
                    out[i + e * step] += p * q;
                }
            }
            poly = out;
        }
        let m = 1usize << k;
        (0..m)
            .map(|r| poly.iter().skip(r).step_by(m).map(|x| x.abs()).sum::<f64>())
            .fold(0.0, f64::max)
    }

    #[test]
    fn derived_rule_converges_for_c_in_0_1() {
        // the claim in the module docs: one-step norm max(c, 1 - c), two-step 1/2 at c = 1
        for c in [0.01, 0.3, 0.5, 0.8, 0.99] {
            let one = difference_rule_norm(c, 1);
            assert!((one - c.max(1.0 - c)).abs() < 1e-15 && one < 1.0, "c = {c}");
        }
        assert_eq!(difference_rule_norm(1.0, 1), 1.0);
        assert_eq!(difference_rule_norm(1.0, 2), 0.5);
        // c = 0: never contractive (the derived rule is piecewise constant)
        assert_eq!(difference_rule_norm(0.0, 6), 1.0);
    }

    #[test]
    fn limit_stencil_is_a_fixed_point_of_the_local_matrix() {
        for c in [0.1, 0.5, 0.9, 1.0] {
            let r = UnivariateRule::new(c).unwrap();
            let [a, b, _] = r.limit_weights();
            // l M = l for M = [[1/2,1/2,0],[c/4,1-c/2,c/4],[0,1/2,1/2]]
            let col0 = a * 0.5 + b * c / 4.0;
            let col1 = a * 0.5 + b * (1.0 - c / 2.0) + a * 0.5;
            assert!((col0 - a).abs() < 1e-15 && (col1 - b).abs() < 1e-15);
            assert!((2.0 * a + b - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn affine_window_is_certified_with_constant_jacobian() {
        // the identity map on the grid: every pair determinant is 1
        let w: Window = std::array::from_fn(|a| std::array::from_fn(|b| [a as f64, b as f64]));
        let id = CcPatchId {
            sector: 0,
            sub: SubPatch::Two,
        };
        let rule = UnivariateRule::new(0.3).unwrap();
        let reg = check_cone_regularity(&rule, &[(id, w)], 1e-15).unwrap();
        assert_eq!(reg.verdict, RegularityVerdict::Regular);
        assert_eq!(reg.min_coeff, 1.0);
        assert_eq!(reg.pieces, 1);
    }

    #[test]
    fn folded_window_has_a_witness() {
        // (x, y) -> (x, y^2 - 1/4 style fold): y-coordinates (b - 1.5)^2 fold at the middle
        let w: Window = std::array::from_fn(|a| {
            std::array::from_fn(|b| [a as f64, (b as f64 - 1.5) * (b as f64 - 1.5)])
        });
        let id = CcPatchId {
            sector: 0,
            sub: SubPatch::One,
        };
        let rule = UnivariateRule::new(0.5).unwrap();
        let reg = check_cone_regularity(&rule, &[(id, w)], 1e-15).unwrap();
        assert_eq!(reg.verdict, RegularityVerdict::NotRegular);
        assert!(reg.witness.is_some());
    }

    #[test]
    fn catmull_clark_small_valences_are_c1_both_ways() {
        for n in [3, 4, 5, 6, 8] {
            let cone = check(n, 0.5).unwrap();
            assert_eq!(cone.verdict, Verdict::C1Standard, "n = {n}: {:?}", cone);
            let bez = check_bicubic(n).unwrap();
            assert_eq!(bez.verdict, Verdict::C1Standard, "n = {n}: {:?}", bez);
            assert_eq!(cone.inner_winding_number, Some(1));
        }
    }
}
