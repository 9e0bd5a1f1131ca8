//! The parts of a characteristic-map verdict shared by the families' rings
//! (math doc section 7): the propagated error of the ring's control points,
//! the verdict from regularity and winding numbers, and the eigenstructure a
//! subdominant class gives.

use super::planar::PlanarBasis;
use super::regularity::{gamma, Regularity, RegularityVerdict};
use super::report::{CharmapReport, Eigenstructure, Verdict};
use crate::spectral::SubdominantClass;
use nalgebra::DMatrix;

/// The error of `m * [w1 w2]` for a basis with entry error `vector_error`,
/// and a bound on its entries: `m` has absolute row sums `rho` and at most
/// `K - 1` nonzeros per row, so each entry is off by at most
/// `rho vector_error + gamma_K rho max|w|`. Returns `(error, rho max|w|)`.
pub(crate) fn propagated_error(m: &DMatrix<f64>, basis: &PlanarBasis) -> (f64, f64) {
    let mut rho = 0.0f64;
    let mut nnz = 0usize;
    for i in 0..m.nrows() {
        let row = m.row(i);
        rho = rho.max(row.iter().map(|x| x.abs()).sum());
        nnz = nnz.max(row.iter().filter(|x| **x != 0.0).count());
    }
    let wmax = basis
        .w1
        .iter()
        .chain(&basis.w2)
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let pmax = rho * wmax;
    (rho * basis.vector_error + gamma(nnz + 1) * pmax, pmax)
}

/// The verdict from a regularity result and the certified winding numbers
/// (shared by both scheme families).
pub(crate) fn assemble_report<P>(
    reg: Regularity<P>,
    winding: Option<i64>,
    inner: Option<i64>,
    delta: f64,
    structure: Eigenstructure,
) -> CharmapReport<P> {
    let verdict = match (reg.verdict, winding) {
        _ if !delta.is_finite() => Verdict::Indeterminate {
            reason: "the subdominant invariant subspace is not certified (Stewart's \
                     separation hypothesis fails: eigenvalues too close for the residual)"
                .to_owned(),
        },
        (RegularityVerdict::NotRegular, _) => Verdict::NotRegular,
        (RegularityVerdict::Indeterminate, _) => Verdict::Indeterminate {
            reason: format!(
                "Jacobian sign not certified (min coefficient {:.3e}, error bound {:.3e}, relative)",
                reg.min_coeff, reg.relative_error_bound
            ),
        },
        (RegularityVerdict::Regular, None) => Verdict::Indeterminate {
            reason: "winding number not certified (boundary within rounding of the origin)"
                .to_owned(),
        },
        (RegularityVerdict::Regular, Some(1)) => match structure {
            Eigenstructure::Standard => Verdict::C1Standard,
            s => Verdict::TangentPlaneContinuous { structure: s },
        },
        (RegularityVerdict::Regular, Some(w)) => Verdict::NotInjective { winding: w },
    };
    CharmapReport {
        structure: Some(structure),
        regularity: Some(reg),
        winding_number: winding,
        inner_winding_number: inner,
        point_error: delta,
        verdict,
    }
}

/// Why a class has no characteristic map, or `None` if it has one.
pub(crate) fn structure_of(
    class: &SubdominantClass,
) -> std::result::Result<Eigenstructure, (String, String)> {
    match class {
        SubdominantClass::Standard => Ok(Eigenstructure::Standard),
        SubdominantClass::RealDistinct => Ok(Eigenstructure::RealDistinct),
        SubdominantClass::ComplexPair => Ok(Eigenstructure::ComplexPair),
        SubdominantClass::Defective => Err((
            "defective".to_owned(),
            "lambda_1 = lambda_2 has a 1-dimensional eigenspace, so the subdominant \
             eigenvectors span a line, not a plane; the generic limit surface has no \
             regular tangent plane parametrisation from them"
                .to_owned(),
        )),
        SubdominantClass::NotSeparated => Err((
            "not_separated".to_owned(),
            "|lambda_2| = |lambda_3| (or lambda_0 is not a simple 1): no 2-dimensional \
             dominant invariant subspace determines the local shape"
                .to_owned(),
        )),
        SubdominantClass::Indeterminate { between, reason } => Err((
            "indeterminate".to_owned(),
            format!(
                "the eigenstructure is undecided between {} and {} ({reason}), so the planar \
                 basis and the verdict's label are not determined",
                between.0.as_str(),
                between.1.as_str()
            ),
        )),
    }
}
