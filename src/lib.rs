//! # subdiv-lab
//!
//! Numerical analysis and verification of subdivision surfaces: local
//! subdivision matrices of NURDS (Non-Uniform Recursive Doo-Sabin), Doo-Sabin
//! and its Catmull-Clark variant, Catmull-Clark and its shape-adjustable
//! variant, Loop, and of schemes users define themselves ([`schemes`]), their
//! spectra, and the convergence facts about them.
//!
//! The mathematics is restated in the project's math document
//! (`docs/math.md`, cited below as "math doc section N"); items it marks
//! **\[derived\]** or **\[reconstructed\]** are marked the same way here.
//!
//! # The public surface
//!
//! At the root: [`Scheme`] (the scheme abstraction), [`Error`] and
//! [`Result`] (the library's typed errors; the error module itself is
//! private). The public modules, one concept each:
//!
//! * schemes and their parameters:
//!   * [`schemes`]: the rules layer: the scheme abstraction ([`Scheme`]),
//!     what a scheme provides (data: matrices, blocks, stencils, its ring of
//!     patches) so that every analysis runs on it; the built-in schemes'
//!     local subdivision matrices through one assembly path (Doo-Sabin
//!     family, Catmull-Clark family, Loop), scheme files, and the one
//!     validator of a scheme choice;
//!   * [`knots`]: knot intervals, edge ratios, extraordinary-point presets,
//!     face weights;
//!   * [`scalar`]: `f64` and exact rationals behind one trait;
//! * analysis:
//!   * [`spectral`]: eigen-analysis and subdominant classification (math doc
//!     sections 4, 6, 7), the exact verdicts, the JSON of `analyze`;
//!   * [`contraction`]: Theorem 1, certified and measured (section 5);
//!   * [`charmap`]: characteristic maps (regularity, injectivity);
//!   * [`curvature`]: second order at an extraordinary point (section 13);
//!   * [`boundary`]: local matrices and analysis at boundary, crease and
//!     corner vertices of Catmull-Clark and Loop (section 18);
//!   * [`cc_study`]: parameter study of the shape-adjustable Catmull-Clark
//!     scheme (spectral part);
//!   * [`ccss_bound`]: distance bound between a Catmull-Clark patch and its
//!     limit face;
//!   * [`g2cap`]: the G2 cap of bidegree (7, 7) around an extraordinary
//!     vertex (seed 003);
//!   * [`verify`]: certified verdicts over boxes of ratios and intervals of
//!     `c` (branch and bound);
//! * meshes: [`mesh`]: closed polygon meshes with knot intervals, OBJ, and
//!   mesh-level subdivision through each scheme's mesh rules;
//! * many configurations and their pictures:
//!   * [`sweep`]: parameter sweeps (specs, samplers, sharded resumable CSV
//!     and Parquet output; sweeps of a user's own scheme);
//!   * [`report`]: plotted reports (spec in, figures/CSV/HTML out, in
//!     memory); the figure kinds' modules document the spec keys;
//!   * [`budget`]: memory and time estimates of the heavy steps (checked
//!     before they start), from each scheme's cost model;
//! * building blocks the public types are made of: [`bezier`] (tensor-product
//!   Bernstein patches, planar Bezier curves), [`bspline`] (non-uniform
//!   quadratic B-splines), [`rng`] (the deterministic generators behind every
//!   seeded result);
//! * `testing` (feature `testing`): proptest strategies and checks for users'
//!   own property tests.
//!
//! Everything else is private: the error module, FNV hashing, TOML
//! locations, and the implementation modules inside the ones above (the
//! eigenvalue kernel, SVD and polynomial helpers of `spectral`, the sweep's
//! plan, spec and summary, the report's backend, plotting and HTML, the G2
//! cap's solvers, ...); what their users need is re-exported by the public
//! module.
//!
//! # Cargo features
//!
//! * `cli` (default): the `subdiv-lab` command-line tool (clap, anyhow,
//!   indicatif, libc); turns on `report` and `lp`;
//! * `report`: the [`report`] module (plotters, png): figures and HTML;
//! * `lp`: the [`ccss_bound`] module (good_lp with the pure-Rust microlp
//!   solver);
//! * `testing`: the `testing` module (proptest).
//!
//! With `default-features = false` the library builds the local matrices,
//! the spectral analysis, characteristic maps, curvature, `verify`, meshes
//! and sweeps without any of them:
//!
//! ```toml
//! [dependencies]
//! subdiv-lab = { version = "0.1", default-features = false }
//! ```
//!
//! ```
//! use subdiv_lab::knots::CornerIntervals;
//! use subdiv_lab::schemes::LocalScheme;
//! let knots = CornerIntervals::new(vec![1.0, 2.0, 1.0, 0.5, 3.0], vec![2.0, 1.0, 1.0, 1.0, 0.25]).unwrap();
//! let s5 = LocalScheme::nurds(knots.ratios().unwrap()).matrix().unwrap();
//! assert_eq!(s5.matrix().nrows(), 20);
//! ```

#![warn(missing_docs)]

pub mod any_error;
pub mod bezier;
pub mod boundary;
pub mod bspline;
pub mod budget;
pub mod cc_study;
#[cfg(feature = "lp")]
pub mod ccss_bound;
pub mod charmap;
pub mod contraction;
pub mod curvature;
pub(crate) mod error;
pub mod g2cap;
pub(crate) mod hash;
pub mod knots;
pub mod mesh;
pub mod outfiles;
#[cfg(feature = "report")]
pub mod report;
pub mod rng;
pub mod scalar;
pub mod schemes;
pub mod spectral;
pub mod sweep;
pub mod table;
#[cfg(feature = "testing")]
pub mod testing;
pub(crate) mod toml_location;
pub mod verify;

pub use any_error::AnyError;
pub use error::{Error, Result};
pub use schemes::Scheme;
