//! Local matrices and their analyses through the library: spectra and classes, Theorem 1, curvature, the built-in and users' schemes, knots, the G2 cap and the proptest kit.
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;
#[path = "../../examples/own_scheme.rs"]
#[allow(dead_code)]
mod example_scheme;

mod butterfly;
mod cc_analysis;
mod contraction;
mod curvature;
mod curvature_schemes;
mod g2cap;
mod knots;
mod modified_butterfly;
mod own_scheme;
mod scheme_files;
mod schemes;
mod second_order;
mod sector_curvature;
mod spectral;
mod sqrt3;
#[cfg(feature = "testing")]
mod testing_kit;
