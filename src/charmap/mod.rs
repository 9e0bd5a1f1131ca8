//! Characteristic maps of the Doo-Sabin family: regularity and injectivity.
//!
//! Math doc section 7. The characteristic map of a configuration is the
//! planar map whose coordinates are the subdominant eigenfunctions; its ring
//! is built from `3n` biquadratic patches ([`ring`](crate::schemes::doo_sabin::ring)) whose control points are
//! the extended matrix ([`extended`](crate::schemes::doo_sabin::extended)) applied to a basis of the subdominant
//! real invariant subspace:
//!
//! * `standard` (`lambda_1 = lambda_2` real, 2-D eigenspace): any basis of the
//!   eigenspace (Reif's criterion: C1 for generic data iff the map is regular
//!   and injective);
//! * `real_distinct`: `(v_1, v_2)`;
//! * `complex_pair`: `(Re v, Im v)`;
//! * `defective`, `not_separated`: no characteristic map (a 1-D eigenspace, or
//!   no pair of subdominant eigenvalues to span a plane).
//!
//! Regularity and injectivity (regular, and the boundary winds exactly once
//! around the origin once the basis is oriented so that the Jacobian is
//! positive) do not change under a linear change of the planar basis, so the
//! checks run on an orthonormal basis of the invariant subspace
//! ([`PlanarBasis::new`]), which is also what makes the error analysis simple.
//! For non-standard eigenstructures the verdict is "tangent-plane continuous
//! (non-standard: ...)", never "C1": the literature settles only the standard case.
//!
//! The Doo-Sabin family's rules for the ring are the scheme's own:
//! [`extended`](crate::schemes::doo_sabin::extended) (the `9n x 4n` matrix)
//! and [`ring`](crate::schemes::doo_sabin::ring) (the `3n` patches and
//! boundary chains). Submodules: [`basis`] (the subdominant invariant
//! subspace from the face block), [`regularity`] (Jacobian sign with error
//! bound and subdivision), [`winding`] (certified winding numbers), `figure`
//! (plot data). Entry points: [`check`] (one configuration, classification
//! included; the sweep entry point), [`check_classified`] (when the
//! classification is already known), [`check_basis`] / [`check_ring`] (any
//! planar basis or ring, e.g. deliberately perturbed ones), [`plot_data`].
//!
//! **Error control.** Two error sources are bounded separately: (1) the error
//! of the computed invariant subspace, bounded by Stewart's perturbation
//! theorem ([`subspace_bound`]: `4 ||E_21||_F / sep` per entry, with the
//! separation `sep(M, L_22)` computed from the smallest singular value of its
//! Kronecker form, minus that computation's own error bound); (2) all rounding
//! from the basis onwards (extended matrix, Bezier conversion, derivatives,
//! products, subdivision, evaluation), bounded with Higham's `gamma_k`
//! ([`point_error`], [`regularity::ErrorModel`]). Verdicts within these bounds
//! are `indeterminate`, never guessed. Not covered: the floating-point error
//! of the SVD that yields `sep` is taken from LAPACK-style backward stability
//! (`|Δsigma| <= c m eps ||K||`, with `c` = [`SVD_ERROR_FACTOR`]), not proven
//! for faer's implementation.
//!
//! ```
//! use subdiv_lab::charmap::{check_basis, Eigenstructure, PlanarBasis};
//! use subdiv_lab::schemes::doo_sabin::extended::ExtendedMatrix;
//! use subdiv_lab::schemes::LocalScheme;
//! use num_complex::Complex64;
//! // n = 4, uniform: the subdominant eigenvectors are the linear functions of the grid.
//! let s = LocalScheme::<f64>::cc_variant(4).unwrap();
//! let ext = ExtendedMatrix::new(&s).unwrap();
//! let sn = s.matrix().unwrap();
//! // Greville coordinates of the 16 points (P, E, C) in the regular 4x4 grid
//! let xy: [(f64, f64); 16] = [
//!     (-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5),           // P_0..P_3
//!     (-0.5, -1.5), (0.5, -1.5), (1.5, -0.5), (1.5, 0.5),           // E_01 E_02 E_11 E_12
//!     (0.5, 1.5), (-0.5, 1.5), (-1.5, 0.5), (-1.5, -0.5),           // E_21 E_22 E_31 E_32
//!     (-1.5, -1.5), (1.5, -1.5), (1.5, 1.5), (-1.5, 1.5),           // C_0..C_3
//! ];
//! let w1: Vec<f64> = xy.iter().map(|p| p.0).collect();
//! let w2: Vec<f64> = xy.iter().map(|p| p.1).collect();
//! let lam = [Complex64::new(0.5, 0.0); 2];
//! let basis = PlanarBasis::new(sn.matrix(), Eigenstructure::Standard, lam, &w1, &w2, 0.25).unwrap();
//! let report = check_basis(&ext, &s.ratios(), &basis).unwrap();
//! assert_eq!(report.winding_number, Some(1));
//! assert_eq!(report.verdict.to_string(), "C1 (standard; Reif)");
//! ```

pub mod basis;
pub mod catmull_clark;
pub(crate) mod figure;
pub mod generic;
pub mod loop_subdivision;
mod planar;
pub mod regularity;
pub(crate) mod report;
mod verdict;
pub mod winding;

use crate::error::Result;
use crate::knots::EdgeRatios;
use crate::schemes::doo_sabin::extended::ExtendedMatrix;
use crate::schemes::doo_sabin::ring::Ring;
use crate::schemes::{LocalScheme, RingPatches, Scheme};
use crate::spectral::{Subdominant, SubdominantClass};
pub use planar::{
    subspace_bound, PlanarBasis, MIN_BASIS_SINE, SUBSPACE_ERROR_SAFETY, SVD_ERROR_FACTOR,
};
use regularity::{check_regularity, gamma};
pub use report::{charmap_json, AnyPatchId, CharmapReport, Eigenstructure, Verdict};
use verdict::{assemble_report, propagated_error, structure_of};

/// Error bound of the ring's Bezier control points for a basis with entry
/// error `vector_error` **\[derived\]**: `Ext` has absolute row sums `rho`, so the
/// `9n` points are off by at most `rho vector_error + gamma_K rho max|w|`
/// (`K` = nonzeros per row + 1); the B-spline-to-Bezier conversion forms convex
/// combinations of at most 4 points (`+ gamma_8 max|P|`).
pub fn point_error(ext: &ExtendedMatrix<f64>, basis: &PlanarBasis) -> f64 {
    let (e, pmax) = propagated_error(ext.matrix().matrix(), basis);
    e + gamma(8) * pmax
}

/// Runs the regularity and winding checks for a planar basis of `S_n`'s
/// subdominant subspace (the geometric part of [`check`]-style entry points).
pub fn check_basis(
    ext: &ExtendedMatrix<f64>,
    ratios: &EdgeRatios<f64>,
    basis: &PlanarBasis,
) -> Result<CharmapReport> {
    let ring = Ring::from_basis(ext, ratios, &basis.w1, &basis.w2)?;
    let delta = point_error(ext, basis);
    Ok(check_ring(&ring, delta, basis.structure))
}

/// Regularity, winding numbers and verdict of a ring whose control points are
/// accurate to `delta` (absolute).
pub fn check_ring(ring: &Ring, delta: f64, structure: Eigenstructure) -> CharmapReport {
    let reg = check_regularity(ring, delta);
    let oriented;
    let r = if reg.orientation < 0 {
        oriented = ring.mirrored();
        &oriented
    } else {
        ring
    };
    let winding = winding::winding_number(&r.outer_boundary(), delta);
    let inner = winding::winding_number(&r.inner_boundary(), delta);
    assemble_report(reg, winding, inner, delta, structure)
}

/// The characteristic-map check of one configuration of any [`Scheme`], given
/// its subdominant classification (from [`crate::spectral`]), by the ring of
/// patches the scheme provides ([`Scheme::ring_patches`]), or `no_charmap`
/// when it provides none:
///
/// * [`RingPatches::Biquadratic`]: the Doo-Sabin family's biquadratic ring
///   ([`check_classified_doo_sabin`]);
/// * [`RingPatches::Bicubic`]: the ring of [`catmull_clark`] (bicubic Bezier
///   certificate at `c = 1/2`, cone certificate otherwise);
/// * [`RingPatches::QuarticBoxSpline`]: Loop's ring
///   ([`loop_subdivision::check`]), built on the standard eigenstructure
///   (Loop's at every valence: the subdominant pair is the `k = +-1` Fourier
///   eigenvalue); another class has no map, with the class that prevents it.
pub fn check_classified<S: Scheme + ?Sized>(
    scheme: &S,
    sub: &Subdominant,
) -> Result<CharmapReport<AnyPatchId>> {
    match scheme.ring_patches() {
        Some(RingPatches::Biquadratic(s)) => check_classified_doo_sabin(s, sub),
        Some(RingPatches::Bicubic { valence, c }) => {
            let certificate = catmull_clark::Certificate::for_c(c);
            catmull_clark::check_classified(valence, c, sub, certificate)
                .map(|r| r.map_patches(AnyPatchId::CatmullClark))
        }
        Some(RingPatches::QuarticBoxSpline { valence }) => {
            if sub.class != SubdominantClass::Standard {
                return Ok(CharmapReport::no_map(
                    sub.class.name(),
                    "Loop's ring is built on the standard eigenstructure",
                ));
            }
            loop_subdivision::check(valence).map(|r| {
                r.map_patches(|p| AnyPatchId::Other {
                    sector: p.sector,
                    slot: p.kind.slot(),
                    prefix: "T",
                })
            })
        }
        _ => Ok(CharmapReport::no_map(
            sub.class.name(),
            &format!("scheme {} provides no characteristic ring", scheme.name()),
        )),
    }
}

/// Which characteristic-map certificate to run: the scheme's ring of
/// polynomial patches (math doc section 7) or the generic certificate from
/// the local matrix and the regular rules (math doc section 20).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// [`check_classified`]: the ring certificates.
    #[default]
    Ring,
    /// [`generic::check`]: any vertex-centred scheme.
    Generic,
}

impl Method {
    /// The names front ends accept, in order.
    pub const NAMES: [&'static str; 2] = ["ring", "generic"];

    /// The method called `name` (`ring` or `generic`), `None` otherwise.
    ///
    /// ```
    /// use subdiv_lab::charmap::Method;
    /// assert_eq!(Method::from_name("generic"), Some(Method::Generic));
    /// assert_eq!(Method::from_name("rings"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Method> {
        match name {
            "ring" => Some(Method::Ring),
            "generic" => Some(Method::Generic),
            _ => None,
        }
    }

    /// `ring` or `generic`.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Ring => "ring",
            Method::Generic => "generic",
        }
    }
}

/// The report of either certificate ([`certify`]).
#[derive(Debug)]
pub enum Certificate {
    /// The ring certificate's report.
    Ring(Result<CharmapReport<AnyPatchId>>),
    /// The generic certificate's report.
    Generic(Result<generic::GenericReport>),
}

impl Certificate {
    /// The JSON object of `analyze --json`'s `charmap` key.
    pub fn json(&self) -> serde_json::Value {
        match self {
            Certificate::Ring(r) => charmap_json(r),
            Certificate::Generic(r) => generic::report_json(r),
        }
    }

    /// The verdict code: the ring's ([`Verdict::code`]) or the generic one's
    /// (`c1`, `not_c1`, `indeterminate`); `error` when the certificate could
    /// not be computed.
    pub fn verdict_code(&self) -> &'static str {
        match self {
            Certificate::Ring(Ok(r)) => r.verdict.code(),
            Certificate::Generic(Ok(r)) => r.verdict.code(),
            Certificate::Ring(Err(_)) | Certificate::Generic(Err(_)) => "error",
        }
    }

    /// The verdict for humans (the error when the certificate could not be
    /// computed).
    pub fn verdict_text(&self) -> String {
        match self {
            Certificate::Ring(Ok(r)) => r.verdict.to_string(),
            Certificate::Generic(Ok(r)) => r.verdict.to_string(),
            Certificate::Ring(Err(e)) | Certificate::Generic(Err(e)) => {
                format!("not computed ({e})")
            }
        }
    }
}

/// The certificate `method` for `scheme`, given its subdominant
/// classification `sub` (use [`crate::spectral::LocalAnalysis::charmap_subdominant`]
/// after an analysis).
///
/// ```
/// use subdiv_lab::charmap::{certify, Method};
/// use subdiv_lab::schemes::LocalScheme;
/// let s = LocalScheme::<f64>::catmull_clark(5).unwrap();
/// let sub = subdiv_lab::spectral::classify_local(&s).unwrap();
/// assert_eq!(certify(Method::Ring, &s, &sub).verdict_code(), "c1");
/// assert_eq!(certify(Method::Generic, &s, &sub).verdict_code(), "c1");
/// ```
pub fn certify<S: Scheme + ?Sized>(method: Method, scheme: &S, sub: &Subdominant) -> Certificate {
    match method {
        Method::Ring => Certificate::Ring(check_classified(scheme, sub)),
        Method::Generic => Certificate::Generic(generic::check(scheme, sub)),
    }
}

/// The Doo-Sabin family's check (the `9n`-point extended configuration and
/// its `3n` biquadratic ring patches).
///
/// Cost: the `n x n` face block (a product and an SVD), `O(n)` small solves,
/// the `9n x 4n` extended matrix and `3n` Jacobian patches; no `4n x 4n`
/// eigen-decomposition.
pub fn check_classified_doo_sabin(
    scheme: &LocalScheme<f64>,
    sub: &Subdominant,
) -> Result<CharmapReport<AnyPatchId>> {
    let r = match prepare(scheme, sub)? {
        Prepared::NoMap(r) => r,
        Prepared::Basis(ext, basis) => check_basis(&ext, &scheme.ratios(), &basis)?,
    };
    Ok(r.map_patches(AnyPatchId::DooSabin))
}

enum Prepared {
    NoMap(CharmapReport),
    Basis(ExtendedMatrix<f64>, PlanarBasis),
}

fn prepare(scheme: &LocalScheme<f64>, sub: &Subdominant) -> Result<Prepared> {
    let structure = match structure_of(&sub.class) {
        Ok(s) => s,
        Err((class, reason)) => return Ok(Prepared::NoMap(CharmapReport::no_map(&class, &reason))),
    };
    let ext = ExtendedMatrix::new(scheme)?;
    let sn = scheme.matrix()?.into_matrix();
    let gap = sub.gap.min(1.0 - sub.lambda1.norm());
    let basis = basis::subdominant_basis(scheme, &sn, structure, [sub.lambda1, sub.lambda2], gap)?;
    Ok(Prepared::Basis(ext, basis))
}

/// The characteristic-map check of one configuration: classification by the
/// spectral engine's structured fast path ([`crate::spectral::classify_scheme`]),
/// then [`check_classified`]. This is the entry point for sweeps (one call per
/// configuration, no shared state, safe to run in parallel).
///
/// ```
/// use subdiv_lab::charmap::{check, Verdict};
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::LocalScheme;
/// let r = check(&LocalScheme::<f64>::doo_sabin(5).unwrap()).unwrap();
/// assert_eq!(r.verdict, Verdict::C1Standard);
/// let r = check(&LocalScheme::nurds(EdgeRatios::new(vec![0.1, 0.8, 0.3]).unwrap())).unwrap();
/// assert_ne!(r.verdict, Verdict::C1Standard); // non-standard: never "C1"
/// ```
pub fn check<S: Scheme + ?Sized>(scheme: &S) -> crate::spectral::Result<CharmapReport<AnyPatchId>> {
    let sub = crate::spectral::classify_local(scheme)?;
    Ok(check_classified(scheme, &sub)?)
}

/// The plot data of a configuration's ring and `levels - 1` further levels
/// (see `figure::ring_plot`), with the report of the check; `None` for the
/// plot when the scheme's ring has no plot (Loop's) or there is no
/// characteristic map.
pub fn plot_data<S: Scheme + ?Sized>(
    scheme: &S,
    levels: usize,
    per_side: usize,
) -> crate::spectral::Result<(CharmapReport<AnyPatchId>, Option<figure::RingPlot>)> {
    let sub = crate::spectral::classify_local(scheme)?;
    Ok(match scheme.ring_patches() {
        Some(RingPatches::Biquadratic(s)) => plot_data_doo_sabin(s, &sub, levels, per_side)?,
        Some(RingPatches::Bicubic { valence, c }) => {
            catmull_clark::plot_data(valence, c, &sub, levels, per_side)?
        }
        _ => (check_classified(scheme, &sub)?, None),
    })
}

/// [`plot_data`] of the Doo-Sabin family given its classification.
pub fn plot_data_doo_sabin(
    scheme: &LocalScheme<f64>,
    sub: &Subdominant,
    levels: usize,
    per_side: usize,
) -> Result<(CharmapReport<AnyPatchId>, Option<figure::RingPlot>)> {
    let (ext, basis) = match prepare(scheme, sub)? {
        Prepared::NoMap(r) => return Ok((r.map_patches(AnyPatchId::DooSabin), None)),
        Prepared::Basis(e, b) => (e, b),
    };
    let structure = basis.structure;
    let ring = Ring::from_basis(&ext, &scheme.ratios(), &basis.w1, &basis.w2)?;
    let report = check_ring(&ring, point_error(&ext, &basis), structure);
    let orientation = report.regularity.as_ref().map_or(1, |r| r.orientation);
    let plot = figure::ring_plot(&ring, basis.restriction, orientation, levels, per_side);
    Ok((report.map_patches(AnyPatchId::DooSabin), Some(plot)))
}
