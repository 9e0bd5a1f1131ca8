//! Measured curvature around the extraordinary point of **any** scheme with
//! a square local subdivision matrix (the Doo-Sabin family, Loop, a user's
//! own [`Scheme`]): refine a lifted, perturbed net `k` levels with the
//! second-order matrix `S` ([`Scheme::second_order_matrix`]: the local
//! matrix for the Doo-Sabin family and Loop, the patch matrix for the
//! Catmull-Clark family; math doc section 13.5) and estimate the curvature
//! from the level-`k` control points (math doc section 13.4 **\[derived\]**).
//!
//! **Method: fitted quadrics to control points** (no limit evaluation, which
//! a general scheme need not provide).
//!
//! 1. The spectral data come from `S` alone (the classification from the
//!    local matrix): the classification must be
//!    standard (a double real subdominant eigenvalue `lambda` with a
//!    2-dimensional eigenspace, math doc section 7); the right eigenspace of
//!    `lambda`, the left eigenspace of `lambda` and the left eigenvector
//!    `l_0` of 1 (normalised to sum 1) are the null spaces of `S - lambda I`,
//!    `(S - lambda I)^T` and `(S - I)^T`, from the Jacobi SVD
//!    (`spectral::svd::jacobi_svd`, math doc section 10).
//! 2. The initial net: point `i` sits in the plane at `(x_i, y_i)`, the two
//!    right subdominant eigenvectors whitened (their `2 x 2` second-moment
//!    matrix over the points made the identity, so a rotationally symmetric
//!    scheme gets a rotationally symmetric layout) and scaled to radius 1; it
//!    is lifted by a smooth height `h(x, y)` plus a seeded random perturbation
//!    of amplitude [`PERTURBATION`] that excites every eigen-direction.
//! 3. Level `k`: `P_k = S P_{k-1}`. The centre's limit point `p_0 = l_0 P_k`
//!    is subtracted from every point (affine invariance: the net stays
//!    centred and shrinks instead of cancelling against a constant; this also
//!    removes the drift that rounding feeds into the eigenvalue 1).
//! 4. The tangent plane is spanned by `u_1 P_k`, `u_2 P_k` (`u_1, u_2` the
//!    left subdominant eigenvectors); in an orthonormal frame `(T_1, T_2, N)`
//!    of it the quadric **with a constant term**
//!    `z = a x^2 + b xy + c y^2 + d` is fitted to *all* level-`k` control
//!    points by least squares. The constant term is what makes control points
//!    (rather than limit points) usable: in the regular case the control
//!    points of a quadratic surface lie on the same quadric shifted along the
//!    normal (math doc section 13.4). Curvatures: `K = 4ac - b^2`,
//!    `H = a + c`, `twist = sqrt(H^2 - K)`, largest principal
//!    `|H| + twist`, as in [`super::measured`].
//!
//! The heights of the level-`k` net are of order `mu^k`, its extent of order
//! `lambda^k`, so the fitted curvatures change per level by `mu / lambda^2`
//! (with relative corrections of order `(nu / mu)^k`, `nu` the next modulus
//! whose eigenvectors reach the fit, and `(mu / lambda)^k` from the
//! tangential parametrisation). For schemes with the Fourier capability
//! ([`Scheme::fourier_spectrum`]) the mean curvature follows block 0
//! (`mean_rate`) and the twist block 2 (`twist_rate`, valences `n >= 4`;
//! at `n = 3` block 2 is the conjugate of the tangent plane's block 1).
//!
//! The Catmull-Clark family keeps its own measurement
//! ([`super::measured::measure`], limit points of the patch nets), which is
//! the better method there; this one works for it too (its local matrix is
//! square).

use super::measured::{apply, height, level_from_fit, tangent_frame, MeasuredLevel, PERTURBATION};
use crate::error::Error;
use crate::rng::SplitMix64;
use crate::schemes::Scheme;
use crate::spectral::classify::SubdominantClass;
use crate::spectral::svd::jacobi_svd;
use crate::spectral::Result;
use nalgebra::{DMatrix, Matrix4, Vector3, Vector4};
use serde::Serialize;

/// Largest number of levels [`measure_scheme`] accepts (as
/// [`super::measured::MAX_LEVELS`]: beyond it the rounding of the tangential
/// part, `eps (lambda / mu)^k` relative to the heights, swamps them).
pub const MAX_LEVELS: usize = super::measured::MAX_LEVELS;

/// Largest local-matrix dimension [`measure_scheme`] accepts: the Jacobi
/// SVDs cost `O(d^3)` per sweep; 400 (a Loop vertex of valence 133, a
/// Doo-Sabin-family face of 100 sides) keeps a measurement under a second.
pub const MAX_DIM: usize = 400;

/// The measured curvature of one configuration of a scheme.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SchemeCurvature {
    /// The scheme's name.
    pub scheme: String,
    /// The scheme's legend label ([`Scheme::label`]).
    pub label: String,
    /// The valence.
    pub n: usize,
    /// The subdominant class ([`SubdominantClass::name`]): `standard` or
    /// `real_distinct`.
    pub class: &'static str,
    /// `lambda = |lambda_1|`, the modulus of the subdominant eigenvalue.
    pub lambda: f64,
    /// `|lambda_2|`: equal to `lambda` in the standard class, the smaller
    /// of the two in the class `real_distinct`.
    pub lambda2: f64,
    /// `mu` (the largest modulus after the subdominant pair; math doc 13.1).
    pub mu: f64,
    /// The predicted per-level rate `mu / lambda_2^2` (`mu / lambda^2` in
    /// the standard class).
    pub predicted_rate: f64,
    /// The predicted rate of the mean curvature, `mu_0 / lambda^2` (`mu_0`:
    /// the largest non-unit modulus of Fourier block 0); `None` without the
    /// Fourier capability.
    pub mean_rate: Option<f64>,
    /// The predicted rate of the twist, `mu_2 / lambda^2` (block 2; `n >= 4`
    /// and the Fourier capability, else `None`).
    pub twist_rate: Option<f64>,
    /// Levels `0..=levels`.
    pub levels: Vec<MeasuredLevel>,
    /// The measured per-level ratio of `max_principal` at the last level.
    pub measured_rate: f64,
}

/// Refines the seeded test net of `scheme`'s local matrix `levels` times
/// and measures the curvature on every level (module docs).
///
/// Errors: a non-square local matrix or one larger than [`MAX_DIM`], a
/// subdominant structure that is not standard (`not_applicable` in the
/// curvature verdict), `levels` outside `1..=MAX_LEVELS`.
///
/// ```
/// use subdiv_lab::curvature::measured_scheme::measure_scheme;
/// use subdiv_lab::schemes::LocalScheme;
/// // Loop at n = 8: mu = 3/8 + cos(4 pi/8)/4 = 3/8 (Fourier block 2) exceeds
/// // lambda^2, so the twist grows by mu/lambda^2 per level.
/// let m = measure_scheme(&LocalScheme::loop_subdivision(8).unwrap(), 24, 3).unwrap();
/// let rate = m.twist_rate.unwrap();
/// assert!((rate - m.predicted_rate).abs() < 1e-12);
/// let t = m.levels[24].twist / m.levels[23].twist;
/// assert!((t - rate).abs() < 1e-3 * rate && rate > 1.0);
/// ```
pub fn measure_scheme<S: Scheme + ?Sized>(
    scheme: &S,
    levels: usize,
    seed: u64,
) -> Result<SchemeCurvature> {
    measure_with(scheme, levels, seed, PERTURBATION, height)
}

/// [`measure_scheme`] with the perturbation amplitude and the smooth height
/// as parameters (the unit tests lift nets by a pure quadratic).
fn measure_with<S: Scheme + ?Sized>(
    scheme: &S,
    levels: usize,
    seed: u64,
    perturbation: f64,
    height: fn(f64, f64) -> f64,
) -> Result<SchemeCurvature> {
    if !(1..=MAX_LEVELS).contains(&levels) {
        return Err(Error::InvalidParameter {
            name: "levels",
            value: levels.to_string(),
            reason: "the measured curvature takes 1..=40 levels",
        }
        .into());
    }
    // The second-order matrix: it holds the support of the ring of patches
    // (math doc section 13.5), so its nets carry every eigenvalue that
    // reaches the surface near the point; the classification is the local
    // matrix's.
    let lm = scheme.second_order_matrix()?;
    let s = lm.matrix();
    let d = s.nrows();
    if s.ncols() != d {
        return Err(crate::spectral::SpectralError::NotSquare {
            rows: d,
            cols: s.ncols(),
        });
    }
    if d > MAX_DIM {
        return Err(Error::InvalidParameter {
            name: "valence",
            value: scheme.valence().to_string(),
            reason: "the measured curvature takes local matrices of dimension up to 400",
        }
        .into());
    }
    let sub = crate::spectral::classify_local(scheme)?;
    let summary = crate::spectral::curvature::with_classification(scheme, &sub, None)?;
    // The subdominant pair: one 2-dimensional eigenspace (standard) or two
    // real eigenvalues with one vector each (real_distinct; module docs).
    let ident = DMatrix::<f64>::identity(d, d);
    let (lambda, lambda2, right, left) = match sub.class {
        SubdominantClass::Standard => {
            let lambda = 0.5 * (sub.lambda1.re + sub.lambda2.re);
            let shifted = s - &ident * lambda;
            let right = null_space(&shifted, 2, "right subdominant eigenvectors")?;
            let left = null_space(&shifted.transpose(), 2, "left subdominant eigenvectors")?;
            (lambda.abs(), lambda.abs(), right, left)
        }
        SubdominantClass::RealDistinct => {
            let (l1, l2) = (sub.lambda1.re, sub.lambda2.re);
            let (s1, s2) = (s - &ident * l1, s - &ident * l2);
            let mut right = null_space(&s1, 1, "right eigenvector of lambda_1")?;
            right.extend(null_space(&s2, 1, "right eigenvector of lambda_2")?);
            let mut left = null_space(&s1.transpose(), 1, "left eigenvector of lambda_1")?;
            left.extend(null_space(&s2.transpose(), 1, "left eigenvector of lambda_2")?);
            (l1.abs(), l2.abs(), right, left)
        }
        _ => {
            return Err(Error::NotApplicable {
                scheme: format!(
                    "{} (subdominant class {})",
                    scheme.label(),
                    sub.class.name()
                ),
                operation: "the measured curvature (it needs a real subdominant pair: class standard or real_distinct)",
            }.into())
        }
    };
    let mu = summary.mu;
    let l0 = null_space(&(s - &ident).transpose(), 1, "left eigenvector of 1")?;
    let l0 = normalise_sum(&l0[0])?;
    let layout = planar_layout(&right[0], &right[1])?;
    let mut net = initial_net(&layout, seed, perturbation, height);
    centre(&mut net, &l0);
    let mut out = Vec::with_capacity(levels + 1);
    for level in 0..=levels {
        if level > 0 {
            net = s * &net;
            centre(&mut net, &l0);
        }
        out.push(measure_level(level, &net, &left[0], &left[1])?);
    }
    let last = out.len() - 1;
    let measured_rate = out[last].max_principal / out[last - 1].max_principal;
    let l2 = lambda2 * lambda2;
    let n = scheme.valence();
    // The regular part's eigenvalues occur in every Fourier mode of the ring
    // (math doc section 13.5).
    let regular = match scheme.regular_part_spectrum() {
        Some(extra) => extra?.iter().map(|z| z.norm()).fold(0.0, f64::max),
        None => 0.0,
    };
    let (mean_rate, twist_rate) = match scheme.fourier_spectrum() {
        None => (None, None),
        Some(blocks) => {
            let blocks = blocks?;
            let block_max = |l: usize| {
                blocks.iter().find(|(b, _)| *b == l).map(|(_, ev)| {
                    let skip = usize::from(l == 0);
                    ev.iter()
                        .skip(skip)
                        .map(|z| z.norm())
                        .fold(regular, f64::max)
                        / l2
                })
            };
            (block_max(0), if n >= 4 { block_max(2) } else { None })
        }
    };
    Ok(SchemeCurvature {
        scheme: scheme.name().to_owned(),
        label: scheme.label(),
        n,
        lambda,
        lambda2,
        mu,
        class: sub.class.name(),
        predicted_rate: mu / l2,
        mean_rate,
        twist_rate,
        levels: out,
        measured_rate,
    })
}

/// The right singular vectors of the `dim` smallest singular values of `a`
/// (square): a basis of its numerical null space. The next singular value
/// must stand clear of them (else the eigenspace is not `dim`-dimensional).
fn null_space(a: &DMatrix<f64>, dim: usize, what: &str) -> Result<Vec<Vec<f64>>> {
    let (sv, v) = jacobi_svd(a, true)?;
    let v = v.ok_or_else(|| Error::Numerical {
        routine: "measured curvature",
        reason: format!("no singular vectors for the {what}"),
    })?;
    let d = sv.len();
    // Columns are ordered by non-increasing singular value.
    let scale = sv.first().copied().unwrap_or(0.0).max(1.0);
    let small = sv[d - dim..].iter().fold(0.0f64, |m, &x| m.max(x));
    let next = if d > dim { sv[d - dim - 1] } else { scale };
    if small.is_nan() || small > NULL_SPACE_RATIO * next {
        return Err(Error::Numerical {
            routine: "measured curvature",
            reason: format!(
                "the {what} do not span a {dim}-dimensional eigenspace (singular values {small:.3e} against {next:.3e})"
            ),
        }.into());
    }
    Ok((d - dim..d)
        .map(|j| v.column(j).iter().copied().collect())
        .collect())
}

/// How far the `dim` smallest singular values of `S - lambda I` must lie below
/// the next one for the null-space step to accept them as an eigenspace: the
/// standard class already certified the eigenspace's dimension; this guards
/// only against an eigenvalue so ill-conditioned that its vectors are
/// meaningless (the null singular values are at the rounding level, `1e-16`
/// relative; the next one is of order the spectral gap, `>= 1e-3` for every
/// configuration the figures take).
pub const NULL_SPACE_RATIO: f64 = 1e-6;

/// Smallest `|sum|` relative to the Euclidean norm that the left eigenvector
/// of 1 may have: for an affine-invariant scheme it is normalisable to sum 1
/// (the limit weights, mostly non-negative, sum to a sizeable fraction of
/// their norm); a sum at `1e-8` of the norm is rounding noise (`d eps` with
/// `d <= MAX_DIM`, times a margin) of a vector whose true sum is 0.
pub const AFFINE_SUM_FLOOR: f64 = 1e-8;

/// Smallest ratio of the two eigenvalues of the subdominant vectors'
/// second-moment matrix for the layout (step 2): below it the two vectors are
/// parallel to rounding accuracy (for a 2-dimensional eigenspace the SVD
/// returns orthonormal vectors, ratio near 1; split pairs have two
/// independent eigenvectors, ratio far above `1e-12`).
pub const PARALLEL_FLOOR: f64 = 1e-12;

fn normalise_sum(v: &[f64]) -> Result<Vec<f64>> {
    let s: f64 = v.iter().sum();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if s.is_nan() || s.abs() <= AFFINE_SUM_FLOOR * norm {
        return Err(Error::Numerical {
            routine: "measured curvature",
            reason: "the left eigenvector of 1 sums to zero: the scheme is not affine invariant"
                .to_owned(),
        }
        .into());
    }
    Ok(v.iter().map(|x| x / s).collect())
}

/// Whitened, unit-radius planar positions from the two subdominant vectors
/// (module docs, step 2).
fn planar_layout(x: &[f64], y: &[f64]) -> Result<Vec<[f64; 2]>> {
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxx += a * a;
        sxy += a * b;
        syy += b * b;
    }
    // Inverse square root of [[sxx, sxy], [sxy, syy]] by its eigen-decomposition.
    let tr = 0.5 * (sxx + syy);
    let disc = (0.25 * (sxx - syy).powi(2) + sxy * sxy).sqrt();
    let (e1, e2) = (tr + disc, tr - disc);
    if e2.is_nan() || e2 <= PARALLEL_FLOOR * e1 {
        return Err(Error::Numerical {
            routine: "measured curvature",
            reason: "the subdominant eigenvectors are (nearly) parallel".to_owned(),
        }
        .into());
    }
    // eigenvector of e1
    let (vx, vy) = if sxy.abs() > 0.0 {
        let (a, b) = (e1 - syy, sxy);
        let r = a.hypot(b);
        (a / r, b / r)
    } else if sxx >= syy {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    let (s1, s2) = (1.0 / e1.sqrt(), 1.0 / e2.sqrt());
    let pts: Vec<[f64; 2]> = x
        .iter()
        .zip(y)
        .map(|(&a, &b)| {
            let p = a * vx + b * vy;
            let q = -a * vy + b * vx;
            [p * s1, q * s2]
        })
        .collect();
    let r = pts.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
    Ok(pts.iter().map(|p| [p[0] / r, p[1] / r]).collect())
}

fn initial_net(
    layout: &[[f64; 2]],
    seed: u64,
    perturbation: f64,
    height: fn(f64, f64) -> f64,
) -> DMatrix<f64> {
    let mut rng = SplitMix64::new(seed);
    let mut m = DMatrix::zeros(layout.len(), 3);
    for (i, p) in layout.iter().enumerate() {
        m[(i, 0)] = p[0];
        m[(i, 1)] = p[1];
        m[(i, 2)] = height(p[0], p[1]) + perturbation * rng.uniform(-1.0, 1.0);
    }
    m
}

fn centre(net: &mut DMatrix<f64>, l0: &[f64]) {
    let p0 = apply(l0, net);
    for mut row in net.row_iter_mut() {
        for k in 0..3 {
            row[k] -= p0[k];
        }
    }
}

fn measure_level(
    level: usize,
    net: &DMatrix<f64>,
    u1: &[f64],
    u2: &[f64],
) -> Result<MeasuredLevel> {
    let degenerate = |what: &str| Error::Numerical {
        routine: "measured curvature",
        reason: format!("{what} at level {level}"),
    };
    let a1 = apply(u1, net);
    let a2 = apply(u2, net);
    let (e1, e2, nrm) =
        tangent_frame(&a1, &a2).ok_or_else(|| degenerate("degenerate tangent plane"))?;
    let pts: Vec<Vector3<f64>> = (0..net.nrows())
        .map(|i| Vector3::new(net[(i, 0)], net[(i, 1)], net[(i, 2)]))
        .collect();
    let radius = pts.iter().map(|p| p.norm()).fold(0.0, f64::max);
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(degenerate("degenerate net").into());
    }
    // Least squares z = a x^2 + b xy + c y^2 + d in coordinates scaled by the
    // net's radius (well-conditioned normal equations).
    let mut ata = Matrix4::zeros();
    let mut atb = Vector4::zeros();
    let mut zmax = 0.0f64;
    let rows: Vec<(Vector4<f64>, f64)> = pts
        .iter()
        .map(|p| {
            let (x, y, z) = (
                p.dot(&e1) / radius,
                p.dot(&e2) / radius,
                p.dot(&nrm) / radius,
            );
            zmax = zmax.max(z.abs());
            (Vector4::new(x * x, x * y, y * y, 1.0), z)
        })
        .collect();
    for (r, z) in &rows {
        ata += r * r.transpose();
        atb += r * *z;
    }
    let coef = ata
        .lu()
        .solve(&atb)
        .ok_or_else(|| degenerate("singular quadric fit"))?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::LocalScheme;

    fn quadratic(x: f64, y: f64) -> f64 {
        0.3 * x * x - 0.2 * x * y + 0.1 * y * y
    }

    /// The claim of math doc section 13.4: in the regular configurations
    /// the level-`k` control points of a quadratic graph lie on the same
    /// quadric shifted along the normal, so the fit with a constant term is
    /// exact and returns the graph's curvatures `H = 0.3 + 0.1`,
    /// `K = 4 (0.3)(0.1) - 0.2^2` at every level. (Planted: without the
    /// constant term the relative residual is `0.038` for Loop at `n = 6` and
    /// the test fails.)
    #[test]
    fn a_quadratic_is_recovered_exactly_in_the_regular_case() {
        let regular: Vec<Box<dyn Scheme>> = vec![
            Box::new(LocalScheme::loop_subdivision(6).unwrap()),
            Box::new(LocalScheme::<f64>::doo_sabin(4).unwrap()),
            Box::new(LocalScheme::<f64>::cc_variant(4).unwrap()),
            Box::new(LocalScheme::<f64>::catmull_clark(4).unwrap()),
        ];
        for s in regular {
            let m = measure_with(&*s, 12, 1, 0.0, quadratic).unwrap();
            for l in &m.levels {
                let what = format!("{} level {}", s.label(), l.level);
                assert!(l.fit_residual < 1e-9, "{what}: {}", l.fit_residual);
                // (the sign of H follows the orientation of the eigenvector basis)
                assert!((l.mean.abs() - 0.4).abs() < 1e-8, "{what}: H = {}", l.mean);
                assert!(
                    (l.gaussian - 0.08).abs() < 1e-8,
                    "{what}: K = {}",
                    l.gaussian
                );
            }
        }
    }
}
