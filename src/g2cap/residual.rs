//! Geometric residuals of the cap: jumps of the unit normal and of the
//! Gaussian and mean curvature across the internal edges and across the
//! outer boundary, sampled densely (math doc section 14.6).

use super::bernstein::{eval_bspline, eval_net, Net};
use super::ring::{Point, RefinedRing};

/// Samples per edge (`SAMPLES + 1` parameter values `t = s / SAMPLES`).
pub const SAMPLES: usize = 64;

/// Unit normal, Gaussian and mean curvature from the first and second
/// derivatives `[P_u, P_v, P_uu, P_uv, P_vv]`:
///
/// ```text
/// N = P_u x P_v / |P_u x P_v|,  E, F, G = P_u.P_u, P_u.P_v, P_v.P_v,
/// L, M, N' = P_uu.N, P_uv.N, P_vv.N,
/// K = (L N' - M^2) / (E G - F^2),  H = (E N' - 2 F M + G L) / (2 (E G - F^2))
/// ```
///
/// `None` where the tangents are parallel (a singular parametrisation).
pub fn shape(d: &[Point; 5]) -> Option<(Point, f64, f64)> {
    let dot = |a: &Point, b: &Point| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (pu, pv) = (&d[0], &d[1]);
    let cr = [
        pu[1] * pv[2] - pu[2] * pv[1],
        pu[2] * pv[0] - pu[0] * pv[2],
        pu[0] * pv[1] - pu[1] * pv[0],
    ];
    let len = dot(&cr, &cr).sqrt();
    let (e, f, g) = (dot(pu, pu), dot(pu, pv), dot(pv, pv));
    let det = e * g - f * f;
    if !(len > 0.0 && det > 0.0) || len * len < 1e-24 * e * g {
        return None;
    }
    let nrm = [cr[0] / len, cr[1] / len, cr[2] / len];
    let (l, m, nn) = (dot(&d[2], &nrm), dot(&d[3], &nrm), dot(&d[4], &nrm));
    let k = (l * nn - m * m) / det;
    let h = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
    Some((nrm, k, h))
}

fn net_derivs(net: &Net, u: f64, v: f64) -> [Point; 5] {
    [
        eval_net(net, u, v, 1, 0),
        eval_net(net, u, v, 0, 1),
        eval_net(net, u, v, 2, 0),
        eval_net(net, u, v, 1, 1),
        eval_net(net, u, v, 0, 2),
    ]
}

fn grid_derivs(grid: &[[Point; 4]; 4], u: f64, v: f64) -> [Point; 5] {
    [
        eval_bspline(grid, u, v, 1, 0),
        eval_bspline(grid, u, v, 0, 1),
        eval_bspline(grid, u, v, 2, 0),
        eval_bspline(grid, u, v, 1, 1),
        eval_bspline(grid, u, v, 0, 2),
    ]
}

/// Largest jumps along a family of sample pairs: `(normal, curvature)`,
/// with the curvature jump `max(|K_1 - K_2| / k_s^2, |H_1 - H_2| / k_s)`
/// relative to the curvature scale `k_s` (`curvature_scale`). A singular
/// sample is an infinite jump.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jumps {
    /// Largest `|N_1 - N_2|` (unit normals).
    pub normal: f64,
    /// Largest relative jump of `K` and `H`.
    pub curvature: f64,
}

/// Normal, `K` and `H` on both sides of one sample point.
pub type Pair = (Option<(Point, f64, f64)>, Option<(Point, f64, f64)>);

/// The curvature scale `k_s = max(1 / L, max |kappa|)`: the largest principal
/// curvature magnitude `|H| + sqrt(max(H^2 - K, 0))` over all samples, at
/// least the reciprocal of the length scale `L` (so a flat cap is measured
/// against its size).
pub fn curvature_scale(pairs: &[Pair], length: f64) -> f64 {
    let mut ks = 1.0 / length;
    for (a, b) in pairs {
        for (_, k, h) in a.iter().chain(b.iter()) {
            let kappa = h.abs() + (h * h - k).max(0.0).sqrt();
            if kappa.is_finite() {
                ks = ks.max(kappa);
            }
        }
    }
    ks
}

/// The jumps of a family of sample pairs against the curvature scale `ks`.
pub fn jumps(pairs: &[Pair], ks: f64) -> Jumps {
    let mut j = Jumps::default();
    for (a, b) in pairs {
        match (a, b) {
            (Some((na, ka, ha)), Some((nb, kb, hb))) => {
                let dn =
                    ((na[0] - nb[0]).powi(2) + (na[1] - nb[1]).powi(2) + (na[2] - nb[2]).powi(2))
                        .sqrt();
                let dc = ((ka - kb).abs() / (ks * ks)).max((ha - hb).abs() / ks);
                j.normal = j.normal.max(dn);
                j.curvature = j.curvature.max(dc);
            }
            _ => {
                j.normal = f64::INFINITY;
                j.curvature = f64::INFINITY;
            }
        }
    }
    j
}

/// Samples across the internal edges: `P_i(0, t)` against `P_(i+1)(t, 0)`.
pub fn internal(nets: &[Net]) -> Vec<Pair> {
    let n = nets.len();
    let mut out = Vec::new();
    for i in 0..n {
        for s in 0..=SAMPLES {
            let t = s as f64 / SAMPLES as f64;
            out.push((
                shape(&net_derivs(&nets[i], 0.0, t)),
                shape(&net_derivs(&nets[(i + 1) % n], t, 0.0)),
            ));
        }
    }
    out
}

/// Samples across the outer boundary: `P_i(1, t)` against the bicubic
/// B-spline cell across `u = 1` at `(0, t)`, and `P_i(t, 1)` against the cell
/// across `v = 1` at `(t, 0)`.
pub fn outer(nets: &[Net], refined: &RefinedRing) -> Vec<Pair> {
    let mut out = Vec::new();
    for (i, net) in nets.iter().enumerate() {
        let (gu, gv) = (refined.grid_u(i), refined.grid_v(i));
        for s in 0..=SAMPLES {
            let t = s as f64 / SAMPLES as f64;
            out.push((
                shape(&net_derivs(net, 1.0, t)),
                shape(&grid_derivs(&gu, 0.0, t)),
            ));
            out.push((
                shape(&net_derivs(net, t, 1.0)),
                shape(&grid_derivs(&gv, t, 0.0)),
            ));
        }
    }
    out
}

/// The length scale `L`: the diagonal of the bounding box of all control
/// points of the cap.
pub fn length_scale(nets: &[Net]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for net in nets {
        for row in net {
            for p in row {
                for x in 0..3 {
                    lo[x] = lo[x].min(p[x]);
                    hi[x] = hi[x].max(p[x]);
                }
            }
        }
    }
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
}
