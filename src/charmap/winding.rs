//! Certified winding number of a closed chain of planar curves around the origin.
//!
//! Math doc section 7 (injectivity). A curve here is anything with the
//! convex-hull property and a subdivision rule ([`HullCurve`]): Bezier curves
//! (de Casteljau) and the limit curves of non-negative stationary subdivision
//! rules (e.g. [`super::catmull_clark::WindowCurve`]). Each curve is split at
//! its parametric midpoint until the hull points of every piece lie in an open
//! cone with apex at the origin and opening `< pi - `[`ANGLE_MARGIN`], *after*
//! widening every point's direction by its angular uncertainty
//! `asin(eps_k / |b_k|)` (`eps_k` = the control-point error bound plus the
//! rounding of the splits). The convex hull of the points, hence the piece,
//! then lies in the cone: it avoids the origin and its change of argument
//! equals the principal angle from its first to its last point (the piece's
//! end points are hull points). The gaps between the end of one curve and the
//! start of the next (identical in exact arithmetic, rounding apart in
//! floating point) are bridged by their principal angles as well. The total
//! is an exact multiple of `2 pi` in exact arithmetic; the computed sum must
//! be within [`INTEGRALITY_TOL`] (in turns) of an integer, otherwise the
//! result is undecided. A piece that still fails at [`MAX_SPLIT_DEPTH`] (the
//! curve passes through or within rounding of the origin) also leaves the
//! winding number undecided.

use crate::bezier::BezierCurve;
use std::f64::consts::PI;

/// Safety margin on the cone opening (radians).
pub const ANGLE_MARGIN: f64 = 1e-9;

/// Maximum split depth per curve.
pub const MAX_SPLIT_DEPTH: u32 = 40;

/// Largest accepted distance (in turns) of the accumulated angle from an integer.
pub const INTEGRALITY_TOL: f64 = 1e-6;

/// A planar curve piece with a convex-hull certificate and a midpoint split.
pub trait HullCurve: Sized {
    /// Points whose convex hull contains the curve; the first is the curve's
    /// start point and the last its end point.
    fn hull(&self) -> Vec<[f64; 2]>;
    /// The two halves (parametric midpoint split).
    fn halves(&self) -> (Self, Self);
    /// Bound on the rounding added to every hull point by one split, for
    /// points of magnitude at most `scale`.
    fn split_error(&self, scale: f64) -> f64;
    /// Bound on the rounding of the hull points themselves beyond the error
    /// of the data (e.g. end points computed by a stencil), magnitude `scale`.
    fn hull_error(&self, scale: f64) -> f64;
}

impl HullCurve for BezierCurve {
    fn hull(&self) -> Vec<[f64; 2]> {
        self.points.clone()
    }
    fn halves(&self) -> (Self, Self) {
        self.split(0.5)
    }
    /// de Casteljau at 1/2 of degree `d`: `d` averaging levels (halving exact).
    fn split_error(&self, scale: f64) -> f64 {
        2.0 * super::regularity::gamma(self.points.len().saturating_sub(1).max(1)) * scale
    }
    fn hull_error(&self, _scale: f64) -> f64 {
        0.0
    }
}

/// Winding number of the closed chain `curves` around the origin, or `None`
/// if it cannot be certified. `eps` bounds the absolute error of the control
/// points; consecutive curves must join (end of `k` = start of `k + 1`, and of
/// the last = start of the first) up to rounding.
pub fn winding_number<C: HullCurve>(curves: &[C], eps: f64) -> Option<i64> {
    let total = accumulated_angle(curves, eps, true)?;
    let turns = total / (2.0 * PI);
    let w = turns.round();
    if (turns - w).abs() <= INTEGRALITY_TOL {
        Some(w as i64)
    } else {
        None
    }
}

/// The certified change of argument (radians) along the open chain
/// `curves` (consecutive curves join up to rounding, the last is not joined
/// to the first), or `None` if it cannot be certified: the same pieces and
/// bridges as [`winding_number`] without the closing bridge. Used for the
/// outer boundary of a boundary or corner sector (math doc section 18.4).
pub fn swept_angle<C: HullCurve>(curves: &[C], eps: f64) -> Option<f64> {
    accumulated_angle(curves, eps, false)
}

fn accumulated_angle<C: HullCurve>(curves: &[C], eps: f64, closed: bool) -> Option<f64> {
    let mut total = 0.0;
    let mut scale = 0.0f64;
    let hulls: Vec<Vec<[f64; 2]>> = curves.iter().map(HullCurve::hull).collect();
    for h in &hulls {
        for p in h {
            scale = scale.max(p[0].abs()).max(p[1].abs());
        }
    }
    let mut worst_split = 0.0f64;
    for (k, c) in curves.iter().enumerate() {
        let split_err = c.split_error(scale);
        worst_split = worst_split.max(split_err);
        let e0 = eps + c.hull_error(scale);
        total += curve_angle(c, &hulls[k], e0, split_err, 0)?;
    }
    let bridges = if closed {
        curves.len()
    } else {
        curves.len().saturating_sub(1)
    };
    for k in 0..bridges {
        let (a, b) = (hulls[k].last()?, hulls[(k + 1) % curves.len()].first()?);
        if a != b {
            // bridge: both points must be clearly away from the origin
            let e = eps
                + curves[k]
                    .hull_error(scale)
                    .max(curves[(k + 1) % curves.len()].hull_error(scale))
                + worst_split * MAX_SPLIT_DEPTH as f64;
            total += certified_angle(&[*a, *b], e)?;
        }
    }
    Some(total)
}

fn curve_angle<C: HullCurve>(
    c: &C,
    hull: &[[f64; 2]],
    eps: f64,
    split_err: f64,
    depth: u32,
) -> Option<f64> {
    let e = eps + split_err * depth as f64;
    if let Some(a) = certified_angle(hull, e) {
        return Some(a);
    }
    if depth >= MAX_SPLIT_DEPTH {
        return None;
    }
    let (l, r) = c.halves();
    let (hl, hr) = (l.hull(), r.hull());
    Some(
        curve_angle(&l, &hl, eps, split_err, depth + 1)?
            + curve_angle(&r, &hr, eps, split_err, depth + 1)?,
    )
}

/// The principal angle from the first to the last point if all points (each
/// uncertain by `e`) lie in an open cone of opening `< pi - ANGLE_MARGIN`.
fn certified_angle(pts: &[[f64; 2]], e: f64) -> Option<f64> {
    let p0 = *pts.first()?;
    let th0 = p0[1].atan2(p0[0]);
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    for p in pts {
        let r = p[0].hypot(p[1]);
        if r.is_nan() || r <= e {
            return None;
        }
        let unc = (e / r).min(1.0).asin() + 4.0 * f64::EPSILON;
        let mut d = p[1].atan2(p[0]) - th0;
        if d > PI {
            d -= 2.0 * PI;
        } else if d <= -PI {
            d += 2.0 * PI;
        }
        lo = lo.min(d - unc);
        hi = hi.max(d + unc);
    }
    if hi - lo >= PI - ANGLE_MARGIN || lo <= -PI || hi >= PI {
        return None;
    }
    let pl = pts[pts.len() - 1];
    let cross = p0[0] * pl[1] - p0[1] * pl[0];
    let dot = p0[0] * pl[0] + p0[1] * pl[1];
    Some(cross.atan2(dot))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle_quads(k: usize, turns: usize, r: f64) -> Vec<BezierCurve> {
        // quadratic Bezier arcs approximating a circle traversed `turns` times
        let m = k * turns;
        (0..m)
            .map(|i| {
                let a0 = 2.0 * PI * i as f64 / k as f64;
                let a1 = 2.0 * PI * (i + 1) as f64 / k as f64;
                let am = 0.5 * (a0 + a1);
                let w = 1.0 / ((a1 - a0) / 2.0).cos();
                BezierCurve::new(vec![
                    [r * a0.cos(), r * a0.sin()],
                    [r * w * am.cos(), r * w * am.sin()],
                    [r * a1.cos(), r * a1.sin()],
                ])
            })
            .collect()
    }

    #[test]
    fn circles() {
        assert_eq!(winding_number(&circle_quads(8, 1, 1.0), 1e-15), Some(1));
        assert_eq!(winding_number(&circle_quads(3, 2, 2.0), 1e-15), Some(2));
        let rev: Vec<_> = circle_quads(5, 1, 1.0)
            .iter()
            .rev()
            .map(BezierCurve::reversed)
            .collect();
        assert_eq!(winding_number(&rev, 1e-15), Some(-1));
        // shifted away from the origin: winding 0
        let shifted: Vec<_> = circle_quads(6, 1, 1.0)
            .into_iter()
            .map(|c| BezierCurve::new(c.points.iter().map(|p| [p[0] + 3.0, p[1]]).collect()))
            .collect();
        assert_eq!(winding_number(&shifted, 1e-15), Some(0));
        // through the origin: undecided
        let through: Vec<_> = circle_quads(6, 1, 1.0)
            .into_iter()
            .map(|c| BezierCurve::new(c.points.iter().map(|p| [p[0] + 1.0, p[1]]).collect()))
            .collect();
        assert_eq!(winding_number(&through, 1e-15), None);
        // a huge error bound makes everything undecided
        assert_eq!(winding_number(&circle_quads(8, 1, 1.0), 2.0), None);
    }
}
