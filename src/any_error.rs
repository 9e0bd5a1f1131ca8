//! An error of any layer, as the front ends (the command-line tool, the
//! Python package, reports) see it, and the one place that decides whether
//! it is about the caller's input.
//!
//! Each module keeps its own error type: the core's [`Error`], the spectral
//! engine's [`SpectralError`], [`MeshError`], [`SweepError`],
//! [`G2CapError`] and [`CcssBoundError`]. The modules above the core wrap
//! [`Error`] where their work calls into it; the core wraps none of them.
//! [`AnyError`] sits above all of them, so that a front end can hold the
//! error of whichever analysis it ran and map it to its exit code or
//! exception with [`AnyError::is_input_error`].

#[cfg(feature = "lp")]
use crate::ccss_bound::CcssBoundError;
use crate::error::Error;
use crate::g2cap::G2CapError;
use crate::mesh::MeshError;
use crate::spectral::SpectralError;
use crate::sweep::SweepError;
use thiserror::Error as ThisError;

/// The error of an analysis of any layer; its message is the inner error's.
#[derive(Debug, Clone, PartialEq, ThisError)]
#[non_exhaustive]
pub enum AnyError {
    /// An error of the library core (schemes, knots, parameters).
    #[error(transparent)]
    Core(#[from] Error),
    /// Failures of the patch-to-limit-face distance bound (`ccss_bound`).
    #[cfg(feature = "lp")]
    #[error(transparent)]
    CcssBound(#[from] CcssBoundError),
    /// Mesh construction, I/O parsing or refinement.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// An error of the spectral engine.
    #[error(transparent)]
    Spectral(#[from] SpectralError),
    /// A sweep spec, resume or merge error.
    #[error(transparent)]
    Sweep(#[from] SweepError),
    /// The G2 cap construction refused its input or its result.
    #[error(transparent)]
    G2Cap(#[from] G2CapError),
}

impl AnyError {
    /// Whether the error is about the caller's input (a bad parameter, spec
    /// or mesh: the CLI's exit 2, Python's `ValueError`) rather than a failure
    /// while running (a numerical failure, an I/O error).
    ///
    /// Input: invalid values (valence, knots, ratios, parameters, counts), an
    /// operation the chosen scheme does not have (`NotApplicable`), every mesh
    /// error, spec errors of sweeps, the CCSS bound's tolerance and control
    /// net, a structured path asked of a scheme outside the Doo-Sabin family,
    /// the G2 cap's own input errors. Failure: numerical non-convergence,
    /// residual checks, LP failures, I/O.
    pub fn is_input_error(&self) -> bool {
        match self {
            AnyError::Core(e) => core_is_input(e),
            #[cfg(feature = "lp")]
            AnyError::CcssBound(e) => ccss_bound_is_input(e),
            AnyError::Mesh(e) => mesh_is_input(e),
            AnyError::Spectral(e) => spectral_is_input(e),
            AnyError::Sweep(e) => !matches!(e, SweepError::Io(_) | SweepError::File(_)),
            AnyError::G2Cap(e) => e.is_input_error(),
        }
    }
}

fn core_is_input(e: &Error) -> bool {
    !matches!(e, Error::Numerical { .. })
}

#[cfg(feature = "lp")]
fn ccss_bound_is_input(e: &CcssBoundError) -> bool {
    use CcssBoundError as C;
    match e {
        C::Core(e) => core_is_input(e),
        C::InvalidTolerance(_)
        | C::NonFinitePoint { .. }
        | C::RaggedNet { .. }
        | C::ToleranceBelowResolution { .. } => true,
        _ => false,
    }
}

fn mesh_is_input(e: &MeshError) -> bool {
    match e {
        MeshError::Core(e) => core_is_input(e),
        _ => true,
    }
}

fn spectral_is_input(e: &SpectralError) -> bool {
    match e {
        SpectralError::Core(e) => core_is_input(e),
        SpectralError::NotDooSabinFamily { .. } => true,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A G2 cap error keeps its own classification through [`AnyError`] (the
    /// Python binding maps library errors through it).
    #[test]
    fn g2_cap_errors_keep_their_kind() {
        assert!(AnyError::from(G2CapError::ShapeParameter { c: f64::NAN }).is_input_error());
        let residual = G2CapError::Residual {
            what: "g1",
            value: 1.0,
            tol: 1e-9,
        };
        assert!(!AnyError::from(residual).is_input_error());
    }

    /// The CCSS bound's tolerance below the net's resolution is input; a
    /// failed linear program is not.
    #[cfg(feature = "lp")]
    #[test]
    fn ccss_bound_errors_by_kind() {
        let below = CcssBoundError::ToleranceBelowResolution {
            epsilon: 1e-300,
            magnitude: 1.0,
            floor: 1e-15,
        };
        assert!(AnyError::from(below).is_input_error());
        let lp = CcssBoundError::Lp {
            what: "beta".to_owned(),
            status: "infeasible".to_owned(),
        };
        assert!(!AnyError::from(lp).is_input_error());
    }

    /// A core error wrapped by a module above the core is classified as the
    /// core error itself.
    #[test]
    fn wrapped_core_errors_keep_their_kind() {
        let input = Error::ValenceTooSmall { valence: 2 };
        let failure = Error::Numerical {
            routine: "r",
            reason: "x".to_owned(),
        };
        for (e, expected) in [(input, true), (failure, false)] {
            assert_eq!(AnyError::from(e.clone()).is_input_error(), expected);
            let spectral = SpectralError::from(e.clone());
            assert_eq!(AnyError::from(spectral).is_input_error(), expected);
            let mesh = MeshError::from(e.clone());
            assert_eq!(AnyError::from(mesh).is_input_error(), expected);
            #[cfg(feature = "lp")]
            {
                let bound = CcssBoundError::from(e);
                assert_eq!(AnyError::from(bound).is_input_error(), expected);
            }
        }
    }
}
