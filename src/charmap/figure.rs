//! Plot data of a characteristic ring (no drawing here; the report module draws it).
//!
//! The ring and `levels - 1` further rings (the next levels: ring `k + 1` is
//! `M^T` applied to ring `k`, with `M` the restriction of `S_n` to the planar
//! subspace, [`super::PlanarBasis::restriction`]), each patch as a closed
//! outline polyline, plus a grid of sample points per patch with the sign of
//! the Jacobian (relative to the ring's orientation) for a sign overlay.

use super::AnyPatchId;
use crate::schemes::doo_sabin::ring::Ring;
use serde::Serialize;

/// One patch of one level, sampled.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchPlot {
    /// Level (0 = the ring itself).
    pub level: usize,
    /// The patch (a Doo-Sabin ring patch or a Catmull-Clark ring cell).
    pub patch: AnyPatchId,
    /// Closed outline (first point repeated at the end).
    pub outline: Vec<[f64; 2]>,
    /// Sample points `(x, y, sign of sigma J)` on a regular grid of the patch domain.
    pub samples: Vec<([f64; 2], i8)>,
}

/// Plot data of a ring and its next levels.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RingPlot {
    /// Patches of all levels.
    pub patches: Vec<PatchPlot>,
    /// Orientation `sigma` used for the signs.
    pub orientation: i8,
}

/// `p` mapped to the ring `k` levels further: `M^T` applied `k` times
/// (`restriction` = `M`, row-major).
pub fn advance(p: [f64; 2], restriction: [[f64; 2]; 2], k: usize) -> [f64; 2] {
    let m = restriction;
    let mut q = p;
    for _ in 0..k {
        q = [
            m[0][0] * q[0] + m[1][0] * q[1],
            m[0][1] * q[0] + m[1][1] * q[1],
        ];
    }
    q
}

/// The sign of `v` as `-1, 0, 1`.
pub(crate) fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// Samples `ring` (oriented by `orientation`) and `levels - 1` further rings
/// obtained with `restriction` (`M`, row-major); `per_side` points per patch side.
pub fn ring_plot(
    ring: &Ring,
    restriction: [[f64; 2]; 2],
    orientation: i8,
    levels: usize,
    per_side: usize,
) -> RingPlot {
    let per_side = per_side.max(2);
    let apply = |p: [f64; 2], k: usize| advance(p, restriction, k);
    let sigma = f64::from(orientation);
    let mut patches = Vec::new();
    for level in 0..levels.max(1) {
        for p in ring.patches() {
            let b = &p.bezier;
            let h = 1.0 / (per_side - 1) as f64;
            let mut outline = Vec::with_capacity(4 * per_side);
            for k in 0..per_side {
                outline.push(apply(b.eval(k as f64 * h, 0.0), level));
            }
            for k in 1..per_side {
                outline.push(apply(b.eval(1.0, k as f64 * h), level));
            }
            for k in 1..per_side {
                outline.push(apply(b.eval(1.0 - k as f64 * h, 1.0), level));
            }
            for k in 1..per_side {
                outline.push(apply(b.eval(0.0, 1.0 - k as f64 * h), level));
            }
            let mut samples = Vec::with_capacity(per_side * per_side);
            for i in 0..per_side {
                for j in 0..per_side {
                    let (s, t) = (
                        (i as f64 + 0.5) / per_side as f64,
                        (j as f64 + 0.5) / per_side as f64,
                    );
                    let v = sigma * b.jacobian_at(s, t);
                    samples.push((apply(b.eval(s, t), level), sign(v)));
                }
            }
            patches.push(PatchPlot {
                level,
                patch: AnyPatchId::DooSabin(p.id),
                outline,
                samples,
            });
        }
    }
    RingPlot {
        patches,
        orientation,
    }
}
