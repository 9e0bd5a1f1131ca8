//! Measured curvature around an extraordinary vertex of the Catmull-Clark
//! family: refine a control net `k` levels and estimate the Gaussian and
//! mean curvature of the limit surface on the ring of level `k` (math doc
//! section 13.2).
//!
//! **Method: limit evaluation, then a fitted quadric.**
//!
//! 1. The control net is the patch configuration of every sector `j`
//!    (the one-ring rotated by `j`, plus that sector's 7 outer points; the
//!    `(2n+8)` numbering of [`PatchLayout`]), laid out in the plane
//!    (`e_i = u_i`, `f_i = u_i + u_{i+1}`, `u_i` the unit vector at angle
//!    `2 pi i / n`, outer points continuing the sector's grid), lifted by a
//!    smooth height `h(x, y)` plus a seeded random perturbation that excites
//!    every eigen-direction. The limit point `p_0` of the centre is subtracted
//!    from every point first (subdivision is affine invariant), so that the
//!    coordinates shrink with the level instead of cancelling against a
//!    constant.
//! 2. Level `k`: each sector's net is multiplied by the patch matrix `A`
//!    ([`patch_matrix`]) `k` times (exact: `A`'s one-ring rows use only the
//!    one-ring, its outer rows only the sector's net).
//! 3. Limit evaluation: the centre by the limit stencil
//!    ([`limit_stencil`]), the points `e_j` and `f_j` of sector `j` (regular,
//!    valence 4) by the valence-4 limit stencil
//!    `(16 p + 8c sum edges + 4c^2 sum diagonals) / (16 (1 + c)^2)` over their
//!    3 x 3 grid neighbourhood. These `2n + 1` points lie on the limit surface
//!    on a ring of radius of order `lambda^k`.
//! 4. The tangent plane at the centre is spanned by the subdominant
//!    components `t_1 . P`, `t_2 . P` (the tangent stencils,
//!    [`tangent_stencils`]); in the orthonormal frame `(T_1, T_2, N)` the
//!    height quadric `z = a x^2 + b xy + c y^2` is fitted to the `2n` ring
//!    points by least squares. Its curvatures at the centre are
//!    `K = 4ac - b^2`, `H = a + c` and the largest principal curvature in
//!    modulus `|H| + sqrt(H^2 - K)`.
//!
//! The heights are of order `mu^k` and the ring's radius of order `lambda^k`,
//! so the fitted curvatures scale like `(mu / lambda^2)^k` (and `K` like
//! `(mu / lambda^2)^{2k}`); the per-level ratio of the largest principal
//! curvature converges to `mu / lambda^2` with a relative error of order
//! `rho^k`, `rho = max(nu / mu, mu / lambda)`, `nu` the largest modulus below
//! `mu` (math doc section 13.2 **\[derived\]**; tested in `tests/analysis/curvature.rs`).
//! `mu`, `lambda` and `nu` are those of the patch matrix
//! ([`fourier::patch_spectrum`]), the family's second-order matrix (math
//! doc section 13.5).
//!
//! The nets are recentred on the limit point at every level (rounding
//! would otherwise feed a constant drift into the eigenvalue 1, which the
//! quadric reads as curvature growing like `lambda^-2k`).
//!
//! **The dominant part and its stated error.** The largest principal
//! curvature mixes the two Fourier parts, so its ratio converges only as fast
//! as the slower part dies out (`(0.948)^k` at `n = 5`, `c = 1/2`). The part
//! that carries `mu` (the larger of the ratios of `|H|` and of the half
//! difference at the last level) converges with its own corrections:
//! [`MeasuredCurvature::dominant_rate`]. Its stated error
//! ([`MeasuredCurvature::rate_error`], an a-posteriori estimate, not a
//! bound): with the differences `d_k = |r_k - r_{k-1}|` of its ratios, a
//! correction `C rho^k` leaves `|r_K - lim r| = d_K rho / (1 - rho)`; `rho`
//! is read off the last differences, and the error is
//! [`RATE_ERROR_SAFETY`] times `max(d_K, rho d_{K-1}) rho / (1 - rho)` plus
//! the rounding [`RATE_ROUNDING_FACTOR`]` eps (lambda / mu)^K` (infinite
//! when `rho` reaches [`MAX_CONVERGENCE_FACTOR`]).

use crate::error::{Error, Result};
use crate::rng::SplitMix64;
use crate::schemes::catmull_clark::limit::{limit_stencil, tangent_stencils};
use crate::schemes::catmull_clark::{fourier, patch_matrix, regular_part_eigenvalues, PatchLayout};
use nalgebra::{DMatrix, Matrix3, Vector3};
use serde::Serialize;

/// Largest number of levels [`measure`] accepts: at level `k` the heights
/// are of order `mu^k` against coordinates of order `lambda^k`; beyond about
/// 40 levels the rounding of the tangential part (`eps (lambda / mu)^k`)
/// swamps the heights for the valences of interest.
pub const MAX_LEVELS: usize = 40;

/// Largest valence [`measure`] accepts.
pub const MAX_VALENCE: usize = 64;

/// Amplitude of the random height perturbation of the initial net (the
/// smooth part has amplitude of order 1): large enough to excite every
/// eigen-direction by a visible amount, small enough to keep the net a graph
/// over the plane.
pub const PERTURBATION: f64 = 0.05;

/// Safety factor of the stated error over the geometric-tail estimate
/// (module docs): the corrections are sums of several geometric terms, and
/// 4 covers a second term of up to three times the first's size at a
/// convergence factor like the first's.
pub const RATE_ERROR_SAFETY: f64 = 4.0;

/// Largest convergence factor `rho` (read off the last differences of the
/// ratios) for which the stated error is given; closer to 1 the tail
/// estimate `rho / (1 - rho)` is itself unreliable and the error is infinite.
pub const MAX_CONVERGENCE_FACTOR: f64 = 0.95;

/// Rounding term of the stated error, times `eps (lambda / mu)^k`: the nets
/// are recentred at every level, so the heights (of order `mu^k`) carry the
/// rounding of coordinates of order `lambda^k`. Observed at most `0.2 eps
/// (lambda / mu)^k` on the dominant part (`n = 3`, `c = 1/2`, levels 24 to
/// 32); 4 is twenty times that.
pub const RATE_ROUNDING_FACTOR: f64 = 4.0;

/// The stated error of the last of the per-level ratios `r` (module docs):
/// `rho` is the larger of `|d_K / d_(K-1)|` and `|d_K / d_(K-2)|^(1/2)`
/// (the latter for alternating corrections), the error
/// `RATE_ERROR_SAFETY max(d_K, rho d_(K-1)) rho / (1 - rho)` plus
/// `RATE_ROUNDING_FACTOR eps growth`. Infinite with fewer than four ratios or
/// `rho >= MAX_CONVERGENCE_FACTOR`.
fn rate_error(r: &[f64], growth: f64) -> f64 {
    let k = r.len();
    if k < 4 {
        return f64::INFINITY;
    }
    let d = |j: usize| (r[j] - r[j - 1]).abs();
    let (d0, d1, d2) = (d(k - 1), d(k - 2), d(k - 3));
    let rho = (d0 / d1).max((d0 / d2).sqrt());
    if rho.is_nan() || rho >= MAX_CONVERGENCE_FACTOR {
        return f64::INFINITY;
    }
    let tail = RATE_ERROR_SAFETY * d0.max(rho * d1) * rho / (1.0 - rho);
    let e = tail + RATE_ROUNDING_FACTOR * f64::EPSILON * growth;
    if e.is_nan() {
        f64::INFINITY
    } else {
        e
    }
}

/// The per-level ratios `|x_k / x_(k-1)|`, `k = 1..`.
fn ratios(levels: &[MeasuredLevel], x: impl Fn(&MeasuredLevel) -> f64) -> Vec<f64> {
    levels
        .windows(2)
        .map(|w| (x(&w[1]) / x(&w[0])).abs())
        .collect()
}

/// One level of the measurement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeasuredLevel {
    /// The level `k`.
    pub level: usize,
    /// The largest distance of a ring point from the centre (of order `lambda^k`).
    pub ring_radius: f64,
    /// The fitted quadric's Gaussian curvature `K` at the centre.
    pub gaussian: f64,
    /// The fitted quadric's mean curvature `H`.
    pub mean: f64,
    /// Half the difference of the principal curvatures, `sqrt(H^2 - K)`
    /// (the rotation-variant, Fourier mode 2 part of the quadric; `H` is the
    /// mode 0 part).
    pub twist: f64,
    /// The largest principal curvature in modulus, `|H| + twist`.
    pub max_principal: f64,
    /// Root-mean-square residual of the quadric fit relative to the largest height.
    pub fit_residual: f64,
}

/// The measured curvature of one configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeasuredCurvature {
    /// The valence.
    pub n: usize,
    /// The shape parameter (`1/2`: Catmull-Clark).
    pub c: f64,
    /// `lambda` (closed-form Fourier blocks).
    pub lambda: f64,
    /// `mu` of the patch matrix ([`fourier::patch_spectrum`]: the Fourier
    /// blocks and the regular part).
    pub mu: f64,
    /// The predicted per-level rate `mu / lambda^2`.
    pub predicted_rate: f64,
    /// The predicted rate of the mean curvature `H`: `mu_0 / lambda^2`, with
    /// `mu_0` the largest non-unit modulus of Fourier block 0 and of the
    /// regular part (whose eigenvalues occur in every mode of the ring).
    pub mean_rate: f64,
    /// The predicted rate of `twist`: `mu_2 / lambda^2`, with `mu_2` the
    /// largest modulus of Fourier block 2 and of the regular part (`n >= 5`;
    /// for `n = 3, 4` block 2 aliases the tangent plane's block or is the
    /// regular case: `None`).
    pub twist_rate: Option<f64>,
    /// Levels `0..=levels`.
    pub levels: Vec<MeasuredLevel>,
    /// The measured per-level ratio of `max_principal` at the last level.
    pub measured_rate: f64,
    /// The per-level ratio at the last level of the faster-growing Fourier
    /// part, `|H|` (mode 0) or the half difference (mode 2): the part that
    /// carries `mu`, whose ratio converges to `mu / lambda^2` without the
    /// other part's leakage (math doc section 13.2).
    pub dominant_rate: f64,
    /// The stated error of `dominant_rate` (absolute; module docs).
    pub rate_error: f64,
}

/// Refines the seeded test net of valence `n` and shape parameter `c`
/// `levels` times and measures the curvature on every level (module docs).
///
/// ```
/// use subdiv_lab::curvature::measured::measure;
/// let m = measure(5, 0.5, 16, 11).unwrap();
/// // Catmull-Clark at n = 5: mu / lambda^2 = 1.124..., carried by the twist
/// // (the half difference of the principal curvatures), which grows.
/// let twist = m.levels[16].twist / m.levels[15].twist;
/// assert!((twist - m.predicted_rate).abs() < 2e-3 * m.predicted_rate);
/// assert!(m.predicted_rate > 1.0);
/// ```
pub fn measure(n: usize, c: f64, levels: usize, seed: u64) -> Result<MeasuredCurvature> {
    if !(3..=MAX_VALENCE).contains(&n) {
        return Err(Error::InvalidParameter {
            name: "valence",
            value: n.to_string(),
            reason: "the measured curvature takes valences 3..=64",
        });
    }
    if !(1..=MAX_LEVELS).contains(&levels) {
        return Err(Error::InvalidParameter {
            name: "levels",
            value: levels.to_string(),
            reason: "the measured curvature takes 1..=40 levels",
        });
    }
    let lay = PatchLayout::new(n)?;
    let a = patch_matrix::<f64>(n, &c)?;
    let a = a.matrix();
    let spec = fourier::patch_spectrum(n, c)?;
    let (lambda, mu) = (spec[1].norm(), spec[3].norm());
    // The regular part's largest eigenvalue (c/4) lies in every Fourier mode
    // of the ring (math doc section 13.5).
    let regular = regular_part_eigenvalues(&c)
        .into_iter()
        .map(f64::abs)
        .fold(0.0, f64::max);
    let nets = initial_nets(n, &lay, seed);
    let stencil = limit_stencil::<f64>(n, &c)?;
    let (_, [t1, t2]) = tangent_stencils(n, c)?;
    // Limit point of the centre (the same for every sector and level).
    let p0 = apply(&stencil, &nets[0]);
    let mut nets: Vec<DMatrix<f64>> = nets
        .into_iter()
        .map(|m| {
            let mut m = m;
            for mut row in m.row_iter_mut() {
                for k in 0..3 {
                    row[k] -= p0[k];
                }
            }
            m
        })
        .collect();
    let mut out = Vec::with_capacity(levels + 1);
    for level in 0..=levels {
        if level > 0 {
            for net in nets.iter_mut() {
                *net = a * &*net;
                // Recentre: rounding feeds a constant drift into the
                // eigenvalue 1, which the quadric (no constant term) would
                // read as curvature growing like lambda^-2k.
                let p = apply(&stencil, net);
                for mut row in net.row_iter_mut() {
                    for k in 0..3 {
                        row[k] -= p[k];
                    }
                }
            }
        }
        out.push(measure_level(level, &nets, &lay, c, &stencil, &t1, &t2)?);
    }
    let last = out.len() - 1;
    let measured_rate = out[last].max_principal / out[last - 1].max_principal;
    let block_max = |l: usize| -> Result<f64> {
        let ev = fourier::block_eigenvalues(n, l, c)?;
        let skip = usize::from(l == 0);
        Ok(ev
            .iter()
            .skip(skip)
            .map(|z| z.norm())
            .fold(regular, f64::max))
    };
    let l2 = lambda * lambda;
    let growth = (lambda / mu).powi(levels as i32);
    let mean = ratios(&out, |l| l.mean);
    let twist = ratios(&out, |l| l.twist);
    let dominant = match (mean.last(), twist.last()) {
        (Some(a), Some(b)) if b > a => twist,
        _ => mean,
    };
    let dominant_rate = dominant.last().copied().unwrap_or(f64::NAN);
    let rate_error = rate_error(&dominant, growth);
    Ok(MeasuredCurvature {
        n,
        c,
        lambda,
        mu,
        dominant_rate,
        rate_error,
        predicted_rate: mu / l2,
        mean_rate: block_max(0)? / l2,
        twist_rate: if n >= 5 {
            Some(block_max(2)? / l2)
        } else {
            None
        },
        levels: out,
        measured_rate,
    })
}

/// `sum_i w_i P_i` over the first `w.len()` rows of `net` (`n x 3`).
/// `sum_i w_i P_i` (also used by `measured_scheme`).
pub(super) fn apply(w: &[f64], net: &DMatrix<f64>) -> Vector3<f64> {
    let mut s = Vector3::zeros();
    for (i, &wi) in w.iter().enumerate() {
        for k in 0..3 {
            s[k] += wi * net[(i, k)];
        }
    }
    s
}

fn row(net: &DMatrix<f64>, i: usize) -> Vector3<f64> {
    Vector3::new(net[(i, 0)], net[(i, 1)], net[(i, 2)])
}

/// The smooth height of the initial net (also used by
/// `measured_scheme`).
pub(super) fn height(x: f64, y: f64) -> f64 {
    0.3 * x * x - 0.2 * x * y + 0.1 * y * y + 0.05 * x * x * x - 0.03 * y * y * y
}

/// The `(2n + 8) x 3` patch nets of the `n` sectors (module docs, step 1).
fn initial_nets(n: usize, lay: &PatchLayout, seed: u64) -> Vec<DMatrix<f64>> {
    let mut rng = SplitMix64::new(seed);
    let u = |i: isize| {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        [t.cos(), t.sin()]
    };
    let lift = |p: [f64; 2], rng: &mut SplitMix64| {
        [
            p[0],
            p[1],
            height(p[0], p[1]) + rng.uniform(-PERTURBATION, PERTURBATION),
        ]
    };
    // The shared one-ring.
    let mut ring = vec![lift([0.0, 0.0], &mut rng)];
    for i in 0..n as isize {
        ring.push(lift(u(i), &mut rng));
    }
    for i in 0..n as isize {
        let (a, b) = (u(i), u(i + 1));
        ring.push(lift([a[0] + b[0], a[1] + b[1]], &mut rng));
    }
    (0..n)
        .map(|j| {
            let mut m = DMatrix::zeros(lay.patch_len(), 3);
            let set = |m: &mut DMatrix<f64>, r: usize, p: [f64; 3]| {
                for k in 0..3 {
                    m[(r, k)] = p[k];
                }
            };
            set(&mut m, lay.v(), ring[0]);
            for i in 0..n {
                set(&mut m, lay.e(i), ring[1 + (i + j) % n]);
                set(&mut m, lay.f(i), ring[1 + n + (i + j) % n]);
            }
            let ji = j as isize;
            let (u0, u1, um, u2) = (u(ji), u(ji + 1), u(ji - 1), u(ji + 2));
            for k in 0..7 {
                let (ga, gb) = PatchLayout::outer_position(k);
                let (ga, gb) = (ga as f64, gb as f64);
                let p = if gb == 0.0 {
                    [(ga - 1.0) * u0[0] + um[0], (ga - 1.0) * u0[1] + um[1]]
                } else if ga == 0.0 {
                    [u2[0] + (gb - 1.0) * u1[0], u2[1] + (gb - 1.0) * u1[1]]
                } else {
                    [
                        (ga - 1.0) * u0[0] + (gb - 1.0) * u1[0],
                        (ga - 1.0) * u0[1] + (gb - 1.0) * u1[1],
                    ]
                };
                set(&mut m, lay.outer(k), lift(p, &mut rng));
            }
            m
        })
        .collect()
}

/// The valence-4 limit point of grid point `(i, j)` of a sector net.
fn regular_limit(
    net: &DMatrix<f64>,
    lay: &PatchLayout,
    c: f64,
    (i, j): (usize, usize),
) -> Result<Vector3<f64>> {
    let at = |a: usize, b: usize| -> Result<Vector3<f64>> {
        lay.grid(a, b)
            .map(|r| row(net, r))
            .ok_or_else(|| Error::Numerical {
                routine: "measured curvature",
                reason: format!("grid point ({a}, {b}) is not in the patch net"),
            })
    };
    let den = 16.0 * (1.0 + c) * (1.0 + c);
    let mut s = at(i, j)? * (16.0 / den);
    for (a, b) in [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)] {
        s += at(a, b)? * (8.0 * c / den);
    }
    for (a, b) in [
        (i - 1, j - 1),
        (i + 1, j - 1),
        (i - 1, j + 1),
        (i + 1, j + 1),
    ] {
        s += at(a, b)? * (4.0 * c * c / den);
    }
    Ok(s)
}

fn measure_level(
    level: usize,
    nets: &[DMatrix<f64>],
    lay: &PatchLayout,
    c: f64,
    stencil: &[f64],
    t1: &[f64],
    t2: &[f64],
) -> Result<MeasuredLevel> {
    let p0 = apply(stencil, &nets[0]);
    let a1 = apply(t1, &nets[0]);
    let a2 = apply(t2, &nets[0]);
    let degenerate = || Error::Numerical {
        routine: "measured curvature",
        reason: format!("degenerate tangent plane at level {level}"),
    };
    let (e1, e2, nrm) = tangent_frame(&a1, &a2).ok_or_else(degenerate)?;
    let mut pts = Vec::with_capacity(2 * nets.len());
    for net in nets {
        pts.push(regular_limit(net, lay, c, (2, 1))? - p0);
        pts.push(regular_limit(net, lay, c, (2, 2))? - p0);
    }
    // Least squares z = a x^2 + b xy + c y^2, scaled by the ring radius so
    // the normal equations are well conditioned.
    let radius = pts.iter().map(|p| p.norm()).fold(0.0, f64::max);
    if radius.is_nan() || radius <= 0.0 {
        return Err(degenerate());
    }
    let mut ata = Matrix3::zeros();
    let mut atb = Vector3::zeros();
    let mut zmax = 0.0f64;
    let rows: Vec<(Vector3<f64>, f64)> = pts
        .iter()
        .map(|p| {
            let (x, y, z) = (
                p.dot(&e1) / radius,
                p.dot(&e2) / radius,
                p.dot(&nrm) / radius,
            );
            zmax = zmax.max(z.abs());
            (Vector3::new(x * x, x * y, y * y), z)
        })
        .collect();
    for (r, z) in &rows {
        ata += r * r.transpose();
        atb += r * *z;
    }
    let coef = ata.lu().solve(&atb).ok_or_else(degenerate)?;
    let rms = (rows
        .iter()
        .map(|(r, z)| (r.dot(&coef) - z).powi(2))
        .sum::<f64>()
        / rows.len() as f64)
        .sqrt();
    Ok(level_from_fit(
        level,
        radius,
        [coef[0], coef[1], coef[2]],
        rms,
        zmax,
    ))
}

/// The orthonormal frame `(e1, e2, n)` of the tangent plane spanned by `a1`,
/// `a2` (`e1` along `a1`, `n = a1 x a2 / |a1 x a2|`); `None` when the plane
/// is degenerate. Shared with `measured_scheme`.
pub(super) fn tangent_frame(
    a1: &Vector3<f64>,
    a2: &Vector3<f64>,
) -> Option<(Vector3<f64>, Vector3<f64>, Vector3<f64>)> {
    let normal = a1.cross(a2);
    let nn = normal.norm();
    if nn.is_nan() || nn <= 0.0 || nn.is_infinite() {
        return None;
    }
    let nrm = normal / nn;
    let e1 = a1.normalize();
    let e2 = nrm.cross(&e1);
    Some((e1, e2, nrm))
}

/// The level's curvatures from the quadric `z = a x^2 + b xy + c y^2 (+ d)`
/// fitted in coordinates scaled by the ring radius `radius` (`abc` are the
/// scaled coefficients; `z/R = a (x/R)^2 + ..` gives curvatures `/ R`):
/// `K = 4ac - b^2`, `H = a + c`, twist `sqrt(H^2 - K)`; `rms / zmax` is the
/// relative fit residual. Shared with `measured_scheme`.
pub(super) fn level_from_fit(
    level: usize,
    radius: f64,
    abc: [f64; 3],
    rms: f64,
    zmax: f64,
) -> MeasuredLevel {
    let (qa, qb, qc) = (abc[0] / radius, abc[1] / radius, abc[2] / radius);
    let gaussian = 4.0 * qa * qc - qb * qb;
    let mean = qa + qc;
    let twist = (mean * mean - gaussian).max(0.0).sqrt();
    MeasuredLevel {
        level,
        ring_radius: radius,
        gaussian,
        mean,
        twist,
        max_principal: mean.abs() + twist,
        fit_residual: if zmax > 0.0 { rms / zmax } else { 0.0 },
    }
}
