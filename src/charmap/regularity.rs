//! Regularity of a ring: the sign of the Jacobian determinant on every patch.
//!
//! Math doc section 7. For a planar patch `(x, y)` of bidegree `(p, p)` the
//! Jacobian `J = x_s y_t - x_t y_s` is a Bernstein polynomial of bidegree
//! `(2p - 1, 2p - 1)` ([`crate::bezier::PlanarPatch::jacobian`]): (3, 3) for
//! the biquadratic rings of the Doo-Sabin family, (5, 5) for the bicubic rings
//! of Catmull-Clark ([`super::catmull_clark`]). By the convex-hull property, coefficients that
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

use crate::bezier::{PlanarPatch, TensorBezier};
use crate::error::{Error, Result};
use crate::schemes::doo_sabin::ring::{Ring, RingPatchId};

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
/// largest magnitude of a coefficient of `x_s, x_t, y_s, y_t`; `degree`, the
/// patch bidegree `p` (2 biquadratic, 3 bicubic).
///
/// A derivative coefficient `p (b_{i+1,j} - b_ij)` is off by at most
/// `2 p delta` (plus one rounding, counted below). Each Jacobian coefficient
/// is a difference of two convex combinations (non-negative weights summing
/// to 1) of products `f g` of derivative coefficients, and
/// `|Δ(fg)| <= |Δf| |g| + |f| |Δg| + |Δf| |Δg| <= 4 p delta md + 4 p^2 delta^2`,
/// so the propagated error is at most `8 p delta md + 8 p^2 delta^2`
/// (`16 delta md + 32 delta^2` for `p = 2`). Rounding: a product coefficient
/// sums at most `p^2` terms (`p` indices per direction), each formed with 7
/// roundings (a weight of 3 binomial ratios, two multiplications), then the
/// sum and the difference: at most `gamma_{8 + 2 p^2} * 2 md^2`
/// (`gamma_16` for `p = 2`, `gamma_26` for `p = 3`; generous for both).
///
/// Subdivision: a split at 1/2 of a Bernstein polynomial of degree `2p - 1`
/// forms each new coefficient by at most `2p - 1` averaging steps `(a + b)/2`
/// (halving is exact), so each level in `s` and in `t` adds at most
/// `gamma_{2p-1} * max|c|`; depth `d` adds `2 d gamma_{2p-1} max|c|`.
///
/// Direct evaluation of `J` at a point (witnesses) from the derivative patches:
/// de Casteljau on the derivative coefficients (convex, `gamma_{2p}` relative
/// to their magnitudes), two products and a difference: within the
/// coefficient bound as well.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ErrorModel {
    /// Error bound of the Bezier control points (absolute, per coordinate).
    pub delta: f64,
    /// Largest derivative coefficient magnitude.
    pub md: f64,
    /// Bidegree `p` of the patches (2 or 3).
    pub degree: usize,
}

impl ErrorModel {
    /// Bound on the error of a Jacobian coefficient before subdivision.
    pub fn coefficient_bound(&self) -> f64 {
        let p = self.degree as f64;
        8.0 * p * self.delta * self.md
            + 8.0 * p * p * self.delta * self.delta
            + gamma(8 + 2 * self.degree * self.degree) * 2.0 * self.md * self.md
    }

    /// Bound after `depth` levels of subdivision, for coefficients of magnitude at most `cmax`.
    pub fn subdivided_bound(&self, depth: u32, cmax: f64) -> f64 {
        self.coefficient_bound()
            + 2.0 * depth as f64 * gamma((2 * self.degree).saturating_sub(1)) * cmax
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

/// What the certificate coefficients of a [`Regularity`] are (how its
/// `min_coeff` reads).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Coefficients {
    /// Bezier coefficients of the Jacobian (polynomial patches).
    BezierJacobian,
    /// Pairwise determinants of the derivative cones of the cells (the cone
    /// test of [`super::catmull_clark`], non-polynomial cells).
    DerivativeCones,
}

impl Coefficients {
    /// `Bezier coefficient` or `derivative-cone determinant` (text output).
    pub fn describe(self) -> &'static str {
        match self {
            Coefficients::BezierJacobian => "Bezier coefficient",
            Coefficients::DerivativeCones => "derivative-cone determinant",
        }
    }
}

/// A point of the ring's domain: patch and local parameters. The patch
/// identifier is [`RingPatchId`] for the Doo-Sabin family and
/// [`super::catmull_clark::CcPatchId`] for the Catmull-Clark family.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct DomainPoint<P = RingPatchId> {
    /// The patch.
    pub patch: P,
    /// Local parameter along `x`.
    pub s: f64,
    /// Local parameter along `y`.
    pub t: f64,
}

/// Result of the regularity check.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Regularity<P = RingPatchId> {
    /// The verdict.
    pub verdict: RegularityVerdict,
    /// Orientation `sigma` (sign of the signed area).
    pub orientation: i8,
    /// `min sigma c_ij / max |c_ij|` over the unsubdivided certificate
    /// coefficients of all patches (Bezier coefficients of the Jacobian, or
    /// the pairwise determinants of the derivative cones of
    /// [`super::catmull_clark`]); invariant under linear changes of the
    /// planar basis.
    pub min_coeff: f64,
    /// Where the minimum is: patch, and the coefficient's Greville point
    /// (`(i/m, j/n)` for a Bezier coefficient).
    pub min_location: DomainPoint<P>,
    /// The coefficient error bound relative to `max |c_ij|`.
    pub relative_error_bound: f64,
    /// For `not_regular`: a point with `sigma J < 0` and the value of `sigma J`
    /// there (relative to `max |c_ij|`), evaluated directly from the derivatives.
    pub witness: Option<(DomainPoint<P>, f64)>,
    /// For `indeterminate`: a piece left undecided (its lower-left corner).
    pub undecided: Option<DomainPoint<P>>,
    /// Pieces examined (3n without subdivision).
    pub pieces: usize,
    /// Deepest subdivision level used.
    pub max_depth: u32,
    /// What the coefficients are (not part of the JSON output, whose
    /// `min_coeff` is described by the scheme).
    #[serde(skip)]
    pub coefficients: Coefficients,
}

impl<P: Copy> Regularity<P> {
    /// The state before the work loop of a certificate: `Regular` so far,
    /// or `Indeterminate` at once when the certificate's coefficients are all
    /// zero or not finite (`scale` = their largest magnitude).
    pub(crate) fn initial(
        orientation: f64,
        min_coeff: f64,
        min_location: DomainPoint<P>,
        error_bound: f64,
        scale: f64,
    ) -> Self {
        let degenerate = scale == 0.0 || !scale.is_finite();
        let s = if scale > 0.0 { scale } else { 1.0 };
        Self {
            verdict: if degenerate {
                RegularityVerdict::Indeterminate
            } else {
                RegularityVerdict::Regular
            },
            orientation: orientation as i8,
            min_coeff: min_coeff / s,
            min_location,
            relative_error_bound: error_bound / s,
            witness: None,
            undecided: degenerate.then_some(min_location),
            pieces: 0,
            max_depth: 0,
            coefficients: Coefficients::BezierJacobian,
        }
    }
}

impl<P> Regularity<P> {
    /// The same result with every patch identifier mapped by `f`.
    pub fn map_patches<Q>(self, f: impl Fn(P) -> Q) -> Regularity<Q> {
        let dp = |d: DomainPoint<P>| DomainPoint {
            patch: f(d.patch),
            s: d.s,
            t: d.t,
        };
        Regularity {
            verdict: self.verdict,
            orientation: self.orientation,
            min_coeff: self.min_coeff,
            min_location: dp(self.min_location),
            relative_error_bound: self.relative_error_bound,
            witness: self.witness.map(|(d, v)| (dp(d), v)),
            undecided: self.undecided.map(dp),
            pieces: self.pieces,
            max_depth: self.max_depth,
            coefficients: self.coefficients,
        }
    }
}

/// Checks the sign of the Jacobian on every patch of `ring`; `delta` bounds the
/// error of the ring's Bezier control points (see [`ErrorModel`]).
pub fn check_regularity(ring: &Ring, delta: f64) -> Regularity {
    let patches: Vec<(RingPatchId, &PlanarPatch)> =
        ring.patches().iter().map(|p| (p.id, &p.bezier)).collect();
    // a ring has 3n >= 9 patches
    check_bezier_patches(&patches, delta).unwrap_or_else(|_| unreachable!("ring without patches"))
}

/// Checks the sign of the Jacobian on a set of planar Bezier patches of one
/// bidegree `(p, p)`, `p >= 1` (a ring of any scheme whose ring patches are
/// polynomial); `delta` bounds the error of their control points (see
/// [`ErrorModel`]). An empty set is an error.
pub fn check_bezier_patches<P: Copy>(
    patches: &[(P, &PlanarPatch)],
    delta: f64,
) -> Result<Regularity<P>> {
    let Some(first) = patches.first() else {
        return Err(Error::CountMismatch {
            what: "patches for the regularity check",
            expected: 1,
            got: 0,
        });
    };
    let jac: Vec<(P, TensorBezier)> = patches.iter().map(|(id, p)| (*id, p.jacobian())).collect();
    let mut md = 0.0f64;
    let mut degree = 1;
    for (_, p) in patches {
        degree = degree.max(p.degree().0).max(p.degree().1);
        for d in [p.x.deriv_s(), p.x.deriv_t(), p.y.deriv_s(), p.y.deriv_t()] {
            md = md.max(d.max_abs());
        }
    }
    let model = ErrorModel { delta, md, degree };
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
        patch: first.0,
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
    let mut out = Regularity::initial(
        sigma,
        min_coeff,
        min_location,
        model.coefficient_bound(),
        cmax,
    );
    if out.verdict == RegularityVerdict::Indeterminate {
        return Ok(out);
    }
    // Work list: (patch index, piece coefficients, s0, t0, size, depth).
    let mut work: Vec<(usize, TensorBezier, f64, f64, f64, u32)> = jac
        .into_iter()
        .enumerate()
        .map(|(k, (_, j))| (k, j, 0.0, 0.0, 1.0, 0))
        .collect();
    while let Some((k, j, s0, t0, h, depth)) = work.pop() {
        let (id, patch) = patches[k];
        out.pieces += 1;
        out.max_depth = out.max_depth.max(depth);
        let bound = model.subdivided_bound(depth, cmax);
        let (lo, _, _) = min_signed(&j, sigma);
        if lo > bound {
            continue;
        }
        // subdivision never takes the coefficients below the rounding floor:
        // once the bound exceeds every coefficient of the piece, stop there
        let hopeless = bound.is_nan() || bound >= j.max_abs();
        // Witness search: corners (exact values) and centre, evaluated directly.
        let (m, n) = j.degree();
        for (a, b) in [(0, 0), (m, 0), (0, n), (m, n)] {
            if sigma * j.coeff(a, b) < -bound {
                let (s, t) = (s0 + h * (a / m) as f64, t0 + h * (b / n) as f64);
                let v = sigma * patch.jacobian_at(s, t);
                if v < -eval_bound {
                    out.verdict = RegularityVerdict::NotRegular;
                    out.witness = Some((DomainPoint { patch: id, s, t }, v / scale));
                    return Ok(out);
                }
            }
        }
        let (sc, tc) = (s0 + h / 2.0, t0 + h / 2.0);
        let vc = sigma * patch.jacobian_at(sc, tc);
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
            return Ok(out);
        }
        if hopeless || depth >= MAX_DEPTH || out.pieces + work.len() + 4 > MAX_PIECES {
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
            work.push((k, b0, s0 + ds, t0, h2, depth + 1));
            work.push((k, b1, s0 + ds, t0 + h2, h2, depth + 1));
        }
    }
    Ok(out)
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
