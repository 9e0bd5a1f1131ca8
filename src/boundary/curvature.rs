//! The curvature verdict at a boundary, crease or corner vertex (math doc
//! section 18.5): the classification of math doc section 13 (`mu` against
//! `lambda^2`) on the sector's second-order matrix.
//!
//! **The second-order matrix.** The ring of the characteristic map
//! ([`super::charmap`]) is the limit surface on the level-1 annulus between
//! level-0 distances 1 and 2, and its patches are combinations of the
//! radius-3 grid points only ([`refinement_matrix`]`(c, 3, 3)`, `12 K + 4`
//! points for Catmull-Clark, `6 K + 4` for Loop, closed under one step). As
//! the two-ring of Loop and the `2n + 8` patch matrix of Catmull-Clark at
//! interior points (math doc section 13.5), this matrix holds the support
//! of the surface on the ring, so the heights of a generic surface over the
//! ring of level `k` are of order `mu^k` with `mu` the largest modulus of
//! its eigenvalues after the subdominant pair, and the curvature of order
//! `(mu / lambda^2)^k`. The local matrix alone would miss the eigenvalues
//! that only the outer points carry (reported as `mu_regular_part`: `mu`
//! is no eigenvalue of the local matrix).
//!
//! **The decision** is [`summarize_spectrum`]'s: the subdominant class of
//! the local matrix (only the standard class has a rate), the float test
//! with error radii, and for the standard rules (every weight a dyadic
//! rational, so the float matrix is the exact one) the exact certificate
//! up to [`EXACT_MAX_DIM`]; BLZ on regular sectors (Catmull-Clark `K = 2`,
//! Loop `K = 3`) is the standard rule set and takes its exact matrix. The
//! BLZ weights `gamma` are irrational in general, so their equalities stay
//! `indeterminate`.

use super::charmap::{refinement_matrix, EIGEN_RADIUS, MAX_CHARMAP_FACES};
use super::{RuleSet, SectorConfig, VertexKind};
use crate::mesh::sharp::rules::SdcScheme;
use crate::scalar::{Rational, Scalar};
use crate::spectral::classify::BACKWARD_ERROR_FACTOR;
use crate::spectral::curvature::{
    first_order_radius, summarize_spectrum, CurvatureEvidence, CurvatureSummary, CurvatureVerdict,
    EXACT_MAX_DIM, MODE_MATCH_TOLERANCE,
};
use crate::spectral::{Eigen, EigenOptions, Result, Subdominant};
use num_complex::Complex64;

/// The curvature verdict of the sector (module docs); `local` is the
/// spectrum of the local matrix (for `mu_regular_part`).
pub fn sector_curvature(
    c: &SectorConfig,
    sub: &Subdominant,
    local: &[Complex64],
) -> Result<CurvatureSummary> {
    if c.face_count() > MAX_CHARMAP_FACES {
        return Ok(CurvatureSummary {
            lambda: sub.lambda1.norm(),
            mu: f64::NAN,
            mu_over_lambda_squared: f64::NAN,
            mu_multiplicity: 0,
            mu_mode: None,
            mu_regular_part: false,
            verdict: CurvatureVerdict::Indeterminate,
            radius: f64::INFINITY,
            evidence: CurvatureEvidence::None,
            reason: format!(
                "not attempted above {MAX_CHARMAP_FACES} faces (the second-order matrix of the sector grows as 12 K)"
            ),
        });
    }
    let s = refinement_matrix(c, EIGEN_RADIUS, EIGEN_RADIUS)?;
    let e = Eigen::new(&s, EigenOptions::BOTH)?;
    let eta = BACKWARD_ERROR_FACTOR * e.dim() as f64 * f64::EPSILON * e.frobenius_norm();
    let radii: Vec<f64> = e
        .condition_numbers()
        .unwrap_or(&[])
        .iter()
        .map(|&k| first_order_radius(k, eta))
        .collect();
    // BLZ coincides with the standard rules where every sector is regular
    // (gamma = 3/8: Catmull-Clark K = 2, Loop K = 3; math doc 18.2)
    let regular = match c.scheme() {
        SdcScheme::CatmullClark => 2,
        SdcScheme::Loop => 3,
    };
    let dyadic = c.rules() == RuleSet::Standard
        || (c.kind() != VertexKind::Corner && c.faces().iter().all(|&k| k == regular));
    let exact = || {
        (dyadic && s.nrows() <= EXACT_MAX_DIM).then(|| {
            let standard = SectorConfig::new(
                c.scheme(),
                c.kind(),
                c.faces(),
                c.angle().map(f64::to_degrees),
                RuleSet::Standard,
            )?;
            let m = refinement_matrix(&standard, EIGEN_RADIUS, EIGEN_RADIUS)?;
            Ok(m.map(<Rational as Scalar>::from_f64_lossless))
        })
    };
    let (mut out, r_mu) = summarize_spectrum(e.values(), &radii, sub, exact)?;
    if !out.mu.is_nan() {
        let tol = r_mu + MODE_MATCH_TOLERANCE;
        out.mu_regular_part = !local.iter().any(|z| (z.norm() - out.mu).abs() <= tol);
    }
    Ok(out)
}
