//! Regularity of a ring: the sign of the Jacobian determinant on every patch.
//!
//! Math doc section 7. For a biquadratic patch `(x, y)` the Jacobian
//! `J = x_s y_t - x_t y_s` is a Bernstein polynomial of bidegree (3, 3)
//! ([`crate::bezier::PlanarPatch::jacobian`]). By the convex-hull property, coefficients that
//! are all `> E` (after multiplying by the orientation `sigma = +-1`) certify
//! `sigma J > 0` on the patch, where `E` bounds the floating-point error of the
//! coefficients ([`ErrorModel`]). Otherwise the patch is split (de Casteljau,
//! in both directions at 1/2) and the pieces are checked, up to
//! [`MAX_DEPTH`] levels and [`MAX_PIECES`] pieces per ring. A piece whose
//! corner value (a corner coefficient is the exact value there) or centre value,
//! evaluated directly from the patch derivatives, has `sigma J < -E_eval` is a
//! witness that the ring is **not regular**; pieces left undecided make the
//! verdict **indeterminate**.
//!
//! The orientation `sigma` is the sign of the ring's signed area
//! `sum_patches mean(coefficients of J)` (the mean of the Bernstein
//! coefficients is the integral over the patch).

use super::ring::{Ring, RingPatchId};
use crate::bezier::TensorBezier;

/// Maximum de Casteljau subdivision depth per patch (pieces of side `2^-10`).
pub const MAX_DEPTH: u32 = 10;

/// Maximum number of pieces examined per ring (keeps degenerate cases bounded:
/// a Jacobian with an isolated zero needs ~4 pieces per level).
pub const MAX_PIECES: usize = 20_000;

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// `gamma_k = k u / (1 - k u)` (Higham's bound for `k` rounded operations).
pub fn gamma(k: usize) -> f64 {
    let ku = k as f64 * U;
    ku / (1.0 - ku)
}

/// The floating-point error model of the Jacobian coefficients **\[derived\]**.
///
/// Inputs: `delta`, an absolute bound on the error of every coordinate of every
/// Bezier control point of the ring (the eigenvector error propagated through
/// the extended matrix and the B-spline-to-Bezier conversion, plus the
/// rounding of both; see [`super::point_error`]); `md`, the
/// largest magnitude of a coefficient of `x_s, x_t, y_s, y_t`.
///
/// A derivative coefficient `2 (b_{i+1,j} - b_ij)` is off by at most `4 delta`
/// (plus one rounding, counted below). Each Jacobian coefficient is a
/// difference of two convex combinations (non-negative weights summing to 1)
/// of products `f g` of derivative coefficients, and
/// `|Δ(fg)| <= |Δf| |g| + |f| |Δg| + |Δf| |Δg| <= 8 delta md + 16 delta^2`,
/// so the propagated error is at most `16 delta md + 32 delta^2`. The rounding
/// of the product (at most 6 terms of 4 factors each, two such sums and a
/// difference) is at most `gamma_16 * 2 md^2`.
///
/// Subdivision: a split at 1/2 forms each new coefficient by at most three
/// averaging steps `(a + b)/2` (halving is exact), so each level in `s` and in
/// `t` adds at most `gamma_3 * max|c|`; depth `d` adds `2 d gamma_3 max|c|`.
///
/// Direct evaluation of `J` at a point (witnesses) from the derivative patches:
/// de Casteljau on 6 coefficients per derivative (convex, `gamma_6` relative
/// to their magnitudes), two products and a difference: at most
/// `16 delta md + 32 delta^2 + gamma_16 * 2 md^2` as well.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ErrorModel {
    /// Error bound of the Bezier control points (absolute, per coordinate).
    pub delta: f64,
    /// Largest derivative coefficient magnitude.
    pub md: f64,
}

impl ErrorModel {
    /// Bound on the error of a Jacobian coefficient before subdivision.
    pub fn coefficient_bound(&self) -> f64 {
        16.0 * self.delta * self.md
            + 32.0 * self.delta * self.delta
            + gamma(16) * 2.0 * self.md * self.md
    }

    /// Bound after `depth` levels of subdivision, for coefficients of magnitude at most `cmax`.
    pub fn subdivided_bound(&self, depth: u32, cmax: f64) -> f64 {
        self.coefficient_bound() + 2.0 * depth as f64 * gamma(3) * cmax
    }

    /// Bound on a directly evaluated Jacobian value.
    pub fn evaluation_bound(&self) -> f64 {
        self.coefficient_bound()
    }
}

/// The regularity verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RegularityVerdict {
    /// `sigma J > 0` certified on every patch.
    Regular,
    /// A point with `sigma J < 0` beyond the error bound was found.
    NotRegular,
    /// Some piece could not be decided within the depth / piece limits.
    Indeterminate,
}

impl RegularityVerdict {
    /// `regular`, `not_regular` or `indeterminate`.
    pub fn as_str(self) -> &'static str {
        match self {
            RegularityVerdict::Regular => "regular",
            RegularityVerdict::NotRegular => "not_regular",
            RegularityVerdict::Indeterminate => "indeterminate",
        }
    }
}

/// A point of the ring's domain: patch and local parameters.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct DomainPoint {
    /// The patch.
    pub patch: RingPatchId,
    /// Local parameter along `x`.
    pub s: f64,
    /// Local parameter along `y`.
    pub t: f64,
}

/// Result of the regularity check.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Regularity {
    /// The verdict.
    pub verdict: RegularityVerdict,
    /// Orientation `sigma` (sign of the signed area).
    pub orientation: i8,
    /// `min sigma c_ij / max |c_ij|` over the unsubdivided coefficients of all
    /// patches (invariant under linear changes of the planar basis).
    pub min_coeff: f64,
    /// Where the minimum is: patch, and the coefficient's Greville point `(i/3, j/3)`.
    pub min_location: DomainPoint,
    /// The coefficient error bound relative to `max |c_ij|`.
    pub relative_error_bound: f64,
    /// For `not_regular`: a point with `sigma J < 0` and the value of `sigma J`
    /// there (relative to `max |c_ij|`), evaluated directly from the derivatives.
    pub witness: Option<(DomainPoint, f64)>,
    /// For `indeterminate`: a piece left undecided (its lower-left corner).
    pub undecided: Option<DomainPoint>,
    /// Pieces examined (3n without subdivision).
    pub pieces: usize,
    /// Deepest subdivision level used.
    pub max_depth: u32,
}

/// Checks the sign of the Jacobian on every patch of `ring`; `delta` bounds the
/// error of the ring's Bezier control points (see [`ErrorModel`]).
pub fn check_regularity(ring: &Ring, delta: f64) -> Regularity {
    let jac: Vec<(RingPatchId, TensorBezier)> = ring
        .patches()
        .iter()
        .map(|p| (p.id, p.bezier.jacobian()))
        .collect();
    let mut md = 0.0f64;
    for p in ring.patches() {
        for d in [
            p.bezier.x.deriv_s(),
            p.bezier.x.deriv_t(),
            p.bezier.y.deriv_s(),
            p.bezier.y.deriv_t(),
        ] {
            md = md.max(d.max_abs());
        }
    }
    let model = ErrorModel { delta, md };
    let cmax = jac.iter().map(|(_, j)| j.max_abs()).fold(0.0, f64::max);
    let area: f64 = jac
        .iter()
        .map(|(_, j)| j.coeffs().iter().sum::<f64>() / j.coeffs().len() as f64)
        .sum();
    let sigma: f64 = if area < 0.0 { -1.0 } else { 1.0 };
    let scale = if cmax > 0.0 { cmax } else { 1.0 };
    // Minimum over the unsubdivided coefficients.
    let mut min_coeff = f64::INFINITY;
    let mut min_location = DomainPoint {
        patch: jac[0].0,
        s: 0.0,
        t: 0.0,
    };
    for (id, j) in &jac {
        let (m, n) = j.degree();
        for a in 0..=m {
            for b in 0..=n {
                let v = sigma * j.coeff(a, b);
                if v < min_coeff {
                    min_coeff = v;
                    min_location = DomainPoint {
                        patch: *id,
                        s: a as f64 / m as f64,
                        t: b as f64 / n as f64,
                    };
                }
            }
        }
    }
    let eval_bound = model.evaluation_bound();
    let mut out = Regularity {
        verdict: RegularityVerdict::Regular,
        orientation: sigma as i8,
        min_coeff: min_coeff / scale,
        min_location,
        relative_error_bound: model.coefficient_bound() / scale,
        witness: None,
        undecided: None,
        pieces: 0,
        max_depth: 0,
    };
    if cmax == 0.0 || !cmax.is_finite() {
        out.verdict = RegularityVerdict::Indeterminate;
        out.undecided = Some(min_location);
        return out;
    }
    let patch_of = |id: RingPatchId| &ring.patch(id).bezier;
    // Work list: (patch, piece coefficients, s0, t0, size, depth).
    let mut work: Vec<(RingPatchId, TensorBezier, f64, f64, f64, u32)> = jac
        .into_iter()
        .map(|(id, j)| (id, j, 0.0, 0.0, 1.0, 0))
        .collect();
    while let Some((id, j, s0, t0, h, depth)) = work.pop() {
        out.pieces += 1;
        out.max_depth = out.max_depth.max(depth);
        let bound = model.subdivided_bound(depth, cmax);
        let (lo, _, _) = min_signed(&j, sigma);
        if lo > bound {
            continue;
        }
        // Witness search: corners (exact values) and centre, evaluated directly.
        let (m, n) = j.degree();
        for (a, b) in [(0, 0), (m, 0), (0, n), (m, n)] {
            if sigma * j.coeff(a, b) < -bound {
                let (s, t) = (s0 + h * (a / m) as f64, t0 + h * (b / n) as f64);
                let v = sigma * patch_of(id).jacobian_at(s, t);
                if v < -eval_bound {
                    out.verdict = RegularityVerdict::NotRegular;
                    out.witness = Some((DomainPoint { patch: id, s, t }, v / scale));
                    return out;
                }
            }
        }
        let (sc, tc) = (s0 + h / 2.0, t0 + h / 2.0);
        let vc = sigma * patch_of(id).jacobian_at(sc, tc);
        if vc < -eval_bound {
            out.verdict = RegularityVerdict::NotRegular;
            out.witness = Some((
                DomainPoint {
                    patch: id,
                    s: sc,
                    t: tc,
                },
                vc / scale,
            ));
            return out;
        }
        if depth >= MAX_DEPTH || out.pieces + work.len() + 4 > MAX_PIECES {
            out.verdict = RegularityVerdict::Indeterminate;
            out.undecided.get_or_insert(DomainPoint {
                patch: id,
                s: s0,
                t: t0,
            });
            continue;
        }
        let (l, r) = j.split_s(0.5);
        let h2 = h / 2.0;
        for (piece, ds) in [(l, 0.0), (r, h2)] {
            let (b0, b1) = piece.split_t(0.5);
            work.push((id, b0, s0 + ds, t0, h2, depth + 1));
            work.push((id, b1, s0 + ds, t0 + h2, h2, depth + 1));
        }
    }
    out
}

/// `min sigma c_ij` with its index.
fn min_signed(j: &TensorBezier, sigma: f64) -> (f64, usize, usize) {
    if sigma > 0.0 {
        j.min_coeff()
    } else {
        let (v, a, b) = j.max_coeff();
        (-v, a, b)
    }
}
