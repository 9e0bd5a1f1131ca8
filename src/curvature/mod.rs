//! Second order at an extraordinary point (math doc section 13): the
//! curvature verdict of every scheme (computed by `analyze` in the spectral
//! module, whose items are re-exported here), the measured curvature of refined
//! nets ([`measured`] for the Catmull-Clark family, [`measured_scheme`] for
//! any scheme with a square local matrix) and the certified tuning of the
//! shape-adjustable scheme ([`tuning`]).

pub use crate::spectral::curvature::*;

pub mod measured;
pub mod measured_scheme;
pub mod tuning;
