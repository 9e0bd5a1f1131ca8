//! The analysis of a boundary, crease or corner configuration (math doc
//! section 18.3-18.5): the spectrum with its closed-form cross-check, the
//! honest subdominant class (the classifier of [`crate::spectral`],
//! unchanged), what can be certified about the characteristic map on the
//! sector, the curvature verdict, and the limit position and tangent
//! stencils from the left eigenvectors.

use super::charmap::{null_vectors, SectorCharmapVerdict, HALF_MATCH_TOL};
use super::{RuleSet, SectorConfig, VertexKind};
use crate::mesh::sharp::rules::SdcScheme;
use crate::spectral::classify::{decide, Decision};
use crate::spectral::curvature::CurvatureSummary;
use crate::spectral::eigen::spectral_order;
use crate::spectral::{classify_matrix_with, Eigen, EigenOptions, Result, Subdominant};
use crate::spectral::{SpectralError, SubdominantClass};
use num_complex::Complex64;
use std::f64::consts::PI;

/// The eigenvalues of the sharp-edge block (the rows of `v` and the sharp
/// edges' neighbours, which involve only those points): `1, 1/2, 1/4`
/// (the cubic B-spline of the crease curve) at a boundary or crease vertex,
/// `1, 1/2, 1/2` (two straight edges of an interpolated vertex) at a corner.
pub fn sharp_block_spectrum(kind: VertexKind) -> [f64; 3] {
    match kind {
        VertexKind::Corner => [1.0, 0.5, 0.5],
        _ => [1.0, 0.5, 0.25],
    }
}

/// The eigenvalues of one sector's smooth block (the points strictly inside
/// a sector of `k` faces, with the vertex and the sharp edges' neighbours
/// set to zero), in closed form (math doc section 18.3): with
/// `w_j = j pi / k`, `j = 1..k-1`, the sine modes give
///
/// * Loop: `g + cos(w_j)/4`;
/// * Catmull-Clark: the two roots of
///   `[[g + cos(w_j)/8, cos(w_j/2)/8], [cos(w_j/2)/2, 1/4]]`, and `1/4`
///   (the alternating mode of the far corners);
///
/// where `g` is the sector's far-end weight ([`SectorConfig::gamma`]).
pub fn smooth_block_spectrum(scheme: SdcScheme, k: usize, g: f64) -> Vec<Complex64> {
    let mut out = Vec::new();
    for j in 1..k {
        let w = j as f64 * PI / k as f64;
        match scheme {
            SdcScheme::Loop => out.push(Complex64::new(g + w.cos() / 4.0, 0.0)),
            SdcScheme::CatmullClark => {
                let (a, b, c, d) = (
                    g + w.cos() / 8.0,
                    (w / 2.0).cos() / 8.0,
                    (w / 2.0).cos() / 2.0,
                    0.25,
                );
                let tr = a + d;
                let det = a * d - b * c;
                let disc = Complex64::new(tr * tr / 4.0 - det, 0.0).sqrt();
                out.push(Complex64::new(tr / 2.0, 0.0) + disc);
                out.push(Complex64::new(tr / 2.0, 0.0) - disc);
            }
        }
    }
    if scheme == SdcScheme::CatmullClark {
        out.push(Complex64::new(0.25, 0.0));
    }
    out
}

/// The whole spectrum in closed form: [`sharp_block_spectrum`] and every
/// sector's [`smooth_block_spectrum`] (the local matrix is block
/// lower-triangular with these diagonal blocks), sorted by
/// [`spectral_order`].
pub fn closed_form_spectrum(c: &SectorConfig) -> Vec<Complex64> {
    let mut out: Vec<Complex64> = sharp_block_spectrum(c.kind())
        .iter()
        .map(|&x| Complex64::new(x, 0.0))
        .collect();
    for (s, &k) in c.faces().iter().enumerate() {
        out.extend(smooth_block_spectrum(c.scheme(), k, c.gamma(s)));
    }
    out.sort_by(spectral_order);
    out
}

/// The structural certificate that the eigenvalue `1/2` has (at least) two
/// independent eigenvectors, for the classifier's double-eigenvalue test
/// (math doc section 18.3): returns the reason, or `None` when no argument
/// applies to the candidate `lambda`.
///
/// * BLZ rules (and the standard rules where they coincide with BLZ,
///   `gamma = 3/8`): on a boundary or crease sector the vectors
///   `e_i = cos(i pi/K)` (sharp-edge neighbours `+-1`) and `sin(i pi/K)` are
///   eigenvectors for `1/2`; at a corner whose angle is not `pi` the two
///   vectors `sin(i theta_K)`, `sin((K - i) theta_K)` are (with the far
///   corners `f_j` on the same sine at `j + 1/2`).
/// * Standard rules at a corner (and either rule set at a corner of one
///   face, where they coincide): `1/2` is a double eigenvalue of the
///   sharp-edge block with two eigenvectors (`e_0`, `e_K`), and each extends
///   to an eigenvector of the whole matrix when `1/2` is not an eigenvalue
///   of the smooth block (Catmull-Clark: `K` odd; Loop: `K` not a multiple
///   of 3).
pub fn half_is_semisimple(c: &SectorConfig, lambda: f64) -> Option<&'static str> {
    if (lambda - 0.5).abs() > HALF_MATCH_TOL {
        return None;
    }
    // the standard rules are BLZ's on a regular sector (gamma = 3/8 at
    // theta_K = pi/2 for Catmull-Clark, pi/3 for Loop)
    let regular = match c.scheme() {
        SdcScheme::CatmullClark => 2,
        SdcScheme::Loop => 3,
    };
    let blz_like = c.rules() == RuleSet::Blz || c.faces().iter().all(|&k| k == regular);
    match c.kind() {
        VertexKind::Boundary | VertexKind::Crease if blz_like && c.faces().iter().all(|&k| k >= 2) => {
            Some("closed-form eigenvectors cos(i pi/K), sin(i pi/K) of 1/2 (math doc 18.3)")
        }
        VertexKind::Corner
            if c.rules() == RuleSet::Blz
                && c.faces()[0] >= 2
                && c.angle().is_some_and(|t| t != PI) =>
        {
            Some("closed-form eigenvectors sin(i theta_K), sin((K-i) theta_K) of 1/2 (math doc 18.3)")
        }
        // one face: no smooth edge, the two rule sets coincide
        VertexKind::Corner if c.rules() == RuleSet::Standard || c.faces()[0] == 1 => {
            let k = c.faces()[0];
            let smooth_has_half = match c.scheme() {
                SdcScheme::CatmullClark => k % 2 == 0,
                SdcScheme::Loop => k % 3 == 0,
            };
            (!smooth_has_half)
                .then_some("1/2 is a double eigenvalue of the corner's sharp-edge block with two eigenvectors, not an eigenvalue of the smooth block (math doc 18.3)")
        }
        _ => None,
    }
}

/// The characteristic-map verdict on the sector with its reason.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SectorCharmap {
    /// The verdict.
    pub verdict: SectorCharmapVerdict,
    /// Why (one sentence).
    pub reason: String,
    /// For `lambda_1` and `lambda_2`: whether each is an eigenvalue of the
    /// sharp-edge block (`Some(true)`), certainly not (`Some(false)`), or
    /// undecided within its error radius (`None`).
    pub on_sharp_edges: [Option<bool>; 2],
    /// The smallest Bezier coefficient of the ring's oriented Jacobian
    /// relative to the largest, when the ring was built
    /// ([`super::charmap::certify`]).
    pub min_jacobian_coeff: Option<f64>,
    /// The error bound of the ring's control points, when the ring was built.
    pub point_error: Option<f64>,
    /// The certified angle (degrees) the outer arc of a boundary or corner
    /// ring sweeps in the oriented orthonormal basis (below 180: a convex
    /// sector, 180: a half-plane, above: a reflex sector; only this
    /// comparison is independent of the basis).
    pub swept_degrees: Option<f64>,
}

/// The analysis of one configuration.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SectorAnalysis {
    /// The configuration, described ([`SectorConfig::describe`]).
    pub configuration: String,
    /// The dimension of the local matrix.
    pub dimension: usize,
    /// All eigenvalues, `[re, im]`, sorted by [`spectral_order`].
    pub eigenvalues: Vec<[f64; 2]>,
    /// The largest distance between the computed spectrum and
    /// [`closed_form_spectrum`] (paired in order).
    pub closed_form_deviation: f64,
    /// The honest subdominant class.
    pub subdominant: Subdominant,
    /// The characteristic-map verdict.
    pub charmap: SectorCharmap,
    /// The limit stencil: the left eigenvector for 1 normalised to sum 1,
    /// over the local matrix's points.
    pub limit_stencil: Vec<f64>,
    /// Largest difference between [`Self::limit_stencil`] and the
    /// closed-form mask (`2/3 v + 1/6 (e_a + e_b)`, or `v` at a corner).
    pub limit_stencil_error: f64,
    /// Tangent stencils: the left eigenvectors of `lambda_1` and `lambda_2`
    /// (real parts; real and imaginary part of one vector for a complex
    /// pair), each scaled to largest entry 1; empty without a characteristic map.
    pub tangent_stencils: Vec<Vec<f64>>,
    /// The curvature verdict on the sector's second-order matrix (math doc
    /// section 18.5; [`super::curvature::sector_curvature`]).
    pub curvature: CurvatureSummary,
}

/// The closed-form limit mask over the neighbourhood (math doc section 17):
/// crease `2/3 v + 1/6 (e_a + e_b)`, corner `v`.
pub fn limit_mask(c: &SectorConfig) -> Vec<f64> {
    let mut w = vec![0.0; c.dimension()];
    match c.kind() {
        VertexKind::Corner => w[0] = 1.0,
        _ => {
            w[0] = 2.0 / 3.0;
            for i in c.sharp_edges() {
                w[1 + i] = 1.0 / 6.0;
            }
        }
    }
    w
}

/// Analyses one configuration (module docs).
///
/// ```
/// use subdiv_lab::boundary::analysis::analyze_sector;
/// use subdiv_lab::boundary::{RuleSet, SectorConfig, VertexKind};
/// use subdiv_lab::mesh::sharp::rules::SdcScheme;
/// let c = SectorConfig::new(SdcScheme::CatmullClark, VertexKind::Boundary, &[5], None, RuleSet::Blz).unwrap();
/// let a = analyze_sector(&c).unwrap();
/// assert_eq!(a.subdominant.class.name(), "standard");
/// assert!((a.subdominant.lambda1.re - 0.5).abs() < 1e-12);
/// ```
pub fn analyze_sector(c: &SectorConfig) -> Result<SectorAnalysis> {
    let lm = c.local_matrix()?;
    let s = lm.matrix();
    let e = Eigen::new(s, EigenOptions::BOTH)?;
    let subdominant = classify_matrix_with(s, &mut |lam| half_is_semisimple(c, lam))?;
    let expected = closed_form_spectrum(c);
    let closed_form_deviation = e
        .values()
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    let left = e.left().ok_or(SpectralError::NoConvergence {
        routine: "left eigenvectors",
        size: s.nrows(),
        sweeps: 0,
    })?;
    let col0 = left.column(0);
    let sum: Complex64 = col0.iter().sum();
    let limit_stencil: Vec<f64> = col0.iter().map(|z| (z / sum).re).collect();
    let mask = limit_mask(c);
    let limit_stencil_error = limit_stencil
        .iter()
        .zip(&mask)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let charmap = charmap_verdict(c, &subdominant);
    let curvature = super::curvature::sector_curvature(c, &subdominant, e.values())?;
    let has_map = matches!(
        subdominant.class,
        SubdominantClass::Standard | SubdominantClass::RealDistinct | SubdominantClass::ComplexPair
    );
    let tangent_stencils = if has_map && e.dim() >= 3 {
        let scale = |v: Vec<f64>| {
            let m = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if m > 0.0 {
                v.iter().map(|x| x / m).collect()
            } else {
                v
            }
        };
        if subdominant.class == SubdominantClass::ComplexPair {
            let u = left.column(1);
            vec![
                scale(u.iter().map(|z| z.re).collect()),
                scale(u.iter().map(|z| z.im).collect()),
            ]
        } else {
            // real eigenvalues: the left null space of S - lambda I (one
            // vector per eigenvalue, or the two-dimensional one of a
            // double), from the singular value decomposition, so that a
            // double eigenvalue's basis is independent
            if subdominant.class == SubdominantClass::Standard {
                left_null_space(s, subdominant.lambda1.re, 2)
                    .into_iter()
                    .map(scale)
                    .collect()
            } else {
                [subdominant.lambda1.re, subdominant.lambda2.re]
                    .iter()
                    .flat_map(|&l| left_null_space(s, l, 1))
                    .map(scale)
                    .collect()
            }
        }
    } else {
        Vec::new()
    };
    Ok(SectorAnalysis {
        configuration: c.describe(),
        dimension: c.dimension(),
        eigenvalues: e.values().iter().map(|z| [z.re, z.im]).collect(),
        closed_form_deviation,
        subdominant,
        charmap,
        limit_stencil,
        limit_stencil_error,
        tangent_stencils,
        curvature,
    })
}

/// The `count` right singular vectors of `(S - lambda I)^T` with the
/// smallest singular values: a basis of the left null space of
/// `S - lambda I` when `lambda` is an eigenvalue of that geometric
/// multiplicity.
fn left_null_space(s: &nalgebra::DMatrix<f64>, lambda: f64, count: usize) -> Vec<Vec<f64>> {
    null_vectors(&s.transpose(), lambda, count)
}

/// Whether `lambda` (error radius `radius`) is an eigenvalue of the
/// sharp-edge block: `Some(true)` consistent with one, `Some(false)`
/// certainly none, `None` in the grey zone ([`decide`]).
fn on_sharp_block(kind: VertexKind, lambda: Complex64, radius: f64) -> Option<bool> {
    let d = sharp_block_spectrum(kind)[1..]
        .iter()
        .map(|&b| (lambda - b).norm())
        .fold(f64::INFINITY, f64::min);
    match decide(d, radius) {
        Decision::Zero => Some(true),
        Decision::NonZero => Some(false),
        Decision::Grey => None,
    }
}

/// The characteristic-map verdict (math doc section 18.4).
fn charmap_verdict(c: &SectorConfig, sub: &Subdominant) -> SectorCharmap {
    let on = [
        on_sharp_block(c.kind(), sub.lambda1, sub.radii[1]),
        on_sharp_block(c.kind(), sub.lambda2, sub.radii[2]),
    ];
    let has_map = matches!(
        sub.class,
        SubdominantClass::Standard | SubdominantClass::RealDistinct | SubdominantClass::ComplexPair
    );
    if !has_map {
        return SectorCharmap {
            verdict: SectorCharmapVerdict::NoCharacteristicMap,
            reason: format!(
                "the subdominant class is {}: no pair of eigenvectors spans the tangent plane",
                sub.class.name()
            ),
            on_sharp_edges: on,
            min_jacobian_coeff: None,
            point_error: None,
            swept_degrees: None,
        };
    }
    let (verdict, reason) = match on {
        [Some(false), Some(false)] => (
            SectorCharmapVerdict::BoundaryCollapses,
            "neither lambda1 nor lambda2 is an eigenvalue of the sharp-edge block, so the map sends the sharp edges' limit curves to the origin: not injective".to_owned(),
        ),
        [None, _] | [_, None] => (
            SectorCharmapVerdict::Indeterminate,
            "whether a subdominant eigenvalue belongs to the sharp-edge block is within its error radius".to_owned(),
        ),
        _ => {
            let r = super::charmap::certify(c, sub, on);
            return SectorCharmap {
                verdict: r.verdict,
                reason: r.reason,
                on_sharp_edges: on,
                min_jacobian_coeff: r.min_jacobian_coeff,
                point_error: r.point_error,
                swept_degrees: r.swept_degrees,
            };
        }
    };
    SectorCharmap {
        verdict,
        reason,
        on_sharp_edges: on,
        min_jacobian_coeff: None,
        point_error: None,
        swept_degrees: None,
    }
}

/// The limit position and unit normal at the vertex of a neighbourhood
/// `points` (ordered like the local matrix's columns; math doc section
/// 18.6): the position is the limit stencil applied to the points, the
/// normal `t_1 x t_2 / |t_1 x t_2|` with the tangents `t_k` the tangent
/// stencils applied to them. `None` without tangent stencils (no
/// characteristic map), for a point count that does not match, or when the
/// tangents are parallel (`|t_1 x t_2|` zero relative to `|t_1| |t_2|`).
pub fn limit_frame(a: &SectorAnalysis, points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    if points.len() != a.limit_stencil.len() || a.tangent_stencils.len() != 2 {
        return None;
    }
    let apply = |w: &[f64]| {
        let mut q = [0.0; 3];
        for (x, p) in w.iter().zip(points) {
            for k in 0..3 {
                q[k] += x * p[k];
            }
        }
        q
    };
    let pos = apply(&a.limit_stencil);
    let t1 = apply(&a.tangent_stencils[0]);
    let t2 = apply(&a.tangent_stencils[1]);
    let n = cross(t1, t2);
    let len = norm(n);
    // (a NaN length fails the test too)
    if len.is_nan() || len <= PARALLEL_TANGENTS * norm(t1) * norm(t2) {
        return None;
    }
    Some((pos, n.map(|x| x / len)))
}

/// `|t_1 x t_2| <= PARALLEL_TANGENTS |t_1| |t_2|` counts as parallel
/// tangents (no normal): the sine of the angle between them at a few
/// hundred rounding errors of the stencils' sums.
pub const PARALLEL_TANGENTS: f64 = 1e-12;

/// The cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The JSON document of one sector analysis (`analyze --vertex ... --json`):
/// the fields of [`SectorAnalysis`] (with `subdominant.class`,
/// `subdominant.lambda1`, `lambda2`, ... as in the interior document), the
/// `charmap` object (`verdict`, `reason`, `on_sharp_edges`), the
/// `curvature` object of the interior document (`verdict`, `lambda`, `mu`,
/// `mu_over_lambda_squared`, ...: math doc section 18.5), the echoed
/// `input` and the tool version.
pub fn sector_json(a: &SectorAnalysis, c: &SectorConfig) -> serde_json::Value {
    let mut value = serde_json::to_value(a).unwrap_or(serde_json::Value::Null);
    if let serde_json::Value::Object(map) = &mut value {
        if let Some(serde_json::Value::Object(cm)) = map.get_mut("charmap") {
            cm.insert("verdict".to_owned(), a.charmap.verdict.as_str().into());
        }
        map.insert(
            "input".to_owned(),
            serde_json::json!({
                "scheme": super::scheme_name(c.scheme()),
                "vertex": c.kind().name(),
                "faces": c.faces(),
                "angle_degrees": c.angle().map(f64::to_degrees),
                "rules": c.rules().name(),
            }),
        );
        map.insert(
            "tool_version".to_owned(),
            crate::spectral::json::TOOL_VERSION.into(),
        );
    }
    value
}
