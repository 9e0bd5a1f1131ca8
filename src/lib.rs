//! # subdiv-lab
//!
//! Numerical analysis and verification of subdivision surfaces: local
//! subdivision matrices of NURDS (Non-Uniform Recursive Doo-Sabin), Doo-Sabin
//! and its Catmull-Clark variant, their spectra, and the convergence facts
//! about them.
//!
//! The mathematics is restated in the project's math document
//! (`docs/math.md`, cited below as "math doc section N"); items it marks
//! **\[derived\]** or **\[reconstructed\]** are marked the same way here.
//!
//! Modules, one concept each:
//!
//! * [`budget`]: memory and time estimates of the heavy steps (checked before they start);
//! * [`scalar`]: `f64` and exact rationals behind one trait;
//! * [`knots`]: knot intervals, edge ratios, extraordinary-point presets, face weights;
//! * [`scheme`]: the scheme abstraction ([`Scheme`]): what a scheme provides so that the whole toolkit runs on it;
//! * [`schemes`]: the built-in schemes' local subdivision matrices, through one assembly path;
//! * [`spectral`]: eigen-analysis and subdominant classification (sections 4, 6, 7);
//! * [`contraction`]: Theorem 1, certified and measured (section 5);
//! * [`bspline`]: non-uniform quadratic B-splines and biquadratic patches;
//! * [`bezier`]: tensor-product Bernstein patches and planar Bezier curves;
//! * [`charmap`]: characteristic maps (regularity, injectivity) of the Doo-Sabin family;
//! * [`mesh`]: closed polygon meshes with knot intervals and mesh-level subdivision;
//! * [`cc_study`]: parameter study of the shape-adjustable Catmull-Clark scheme (spectral part);
//! * [`ccss_bound`]: distance bound between a Catmull-Clark patch and its limit face;
//! * [`g2cap`]: the G2 cap of bidegree (7, 7) around an extraordinary vertex (seed 003);
//! * [`report`]: plotted reports (spec in, figures/CSV/HTML out, in memory);
//! * [`sweep`]: parameter sweeps (specs, samplers, sharded resumable CSV output);
//! * [`verify`]: certified verdicts over boxes of ratios and intervals of `c` (branch and bound);
//! * `testing` (feature `testing`): proptest strategies and checks for users' own property tests.
//!
//! ```
//! use subdiv_lab::knots::CornerIntervals;
//! use subdiv_lab::schemes::LocalScheme;
//! let knots = CornerIntervals::new(vec![1.0, 2.0, 1.0, 0.5, 3.0], vec![2.0, 1.0, 1.0, 1.0, 0.25]).unwrap();
//! let s5 = LocalScheme::nurds(knots.ratios().unwrap()).matrix().unwrap();
//! assert_eq!(s5.matrix().nrows(), 20);
//! ```

#![warn(missing_docs)]

pub mod bezier;
pub mod bspline;
pub mod budget;
pub mod cc_study;
pub mod ccss_bound;
pub mod charmap;
pub mod contraction;
pub mod curvature;
pub(crate) mod error;
pub mod g2cap;
pub(crate) mod hash;
pub mod knots;
pub mod mesh;
pub mod report;
pub mod rng;
pub mod scalar;
pub mod scheme;
pub mod schemes;
pub mod spectral;
pub mod sweep;
#[cfg(feature = "testing")]
pub mod testing;
pub(crate) mod toml_location;
pub mod verify;

pub use error::{Error, Result};
pub use scheme::Scheme;
