//! A testing kit for users' own property tests (feature `testing`).
//!
//! Researchers write properties such as "my scheme converges for all knots in
//! this box" or "this modified rule keeps the 3/4 bound". This module gives
//! them the generators ([`strategies`]) and the checks ([`assertions`]) that
//! subdiv-lab's own tests use, so they need not rebuild them.
//!
//! * Strategies shrink towards the simplest configuration: smallest valence,
//!   uniform knots (to within [`strategies::GRID_RESOLUTION`]), points at the
//!   origin, so failures are readable.
//! * Checks return `Result<_, Violation>` with the configuration and the
//!   offending row, eigenvalue or level; `Violation` is a `std::error::Error`,
//!   so `?` works inside `proptest!`.
//!
//! proptest stops shrinking after 128 steps by default (proptest 1.12); a
//! fully shrunk counterexample (smallest valence, uniform knots) needs
//! a few dozen steps per coordinate, so raise `max_shrink_iters` (the kit's
//! own tests use `1_000_000`; shrinking stops much earlier in practice).
//!
//! Enable it as a dev-dependency:
//!
//! ```toml
//! [dev-dependencies]
//! subdiv-lab = { version = "0.1", features = ["testing"] }
//! proptest = "1"
//! ```
//!
//! A complete property test of Theorem 1 (math doc section 5) for a knot box:
//!
//! ```
//! use proptest::prelude::*;
//! use subdiv_lab::testing::assertions::check_face_contraction;
//! use subdiv_lab::testing::strategies::{nurds_with_points, IntervalBox};
//!
//! proptest! {
//!     #![proptest_config(ProptestConfig::with_cases(32))]
//!     // in tests/my_scheme.rs, put #[test] here
//!     fn theorem_1_holds_in_my_box(
//!         (scheme, points) in nurds_with_points(3..=8, IntervalBox::new(0.25, 4.0).unwrap())
//!     ) {
//!         let s = scheme.matrix()?;
//!         check_face_contraction(s.matrix(), scheme.valence(), &points, 0.75, 40, &scheme)?;
//!     }
//! }
//! # theorem_1_holds_in_my_box();
//! ```

pub mod assertions;
pub mod strategies;
