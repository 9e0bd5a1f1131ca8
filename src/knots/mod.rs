//! Knot intervals on a face and the edge ratios derived from them.
//!
//! Math doc (`docs/math.md`) sections 2 and 3. On a counter-clockwise
//! face `P_0..P_{n-1}` the corner `P_i` carries two knot intervals
//!
//! ```text
//! p_i = d(P_i -> P_{i+1})      q_i = d(P_i -> P_{i-1})
//! ```
//!
//! and the edge `P_i P_{i+1}` has the ratio
//!
//! ```text
//! r_i = q_{i+1} / (p_i + q_{i+1})  in (0, 1),   E_i = r_i P_i + (1 - r_i) P_{i+1}.
//! ```
//!
//! Only ratios matter: scaling every interval of a face leaves every weight
//! unchanged, so the local matrices are functions of [`EdgeRatios`] alone.
//! [`CornerIntervals`] is the user-facing form; [`EdgeRatios::to_corner_intervals`]
//! gives a canonical corner form back (`p_i = 1 - r_i`, `q_i = r_{i-1}`).
//!
//! The two extraordinary-point presets of math doc section 3 **\[derived\]** are
//! [`EdgeRatios::face_ep`] (an initial n-gon) and [`EdgeRatios::vertex_ep`] (the
//! V-face of an initial valence-n vertex).

pub(crate) mod face_weights;
mod intervals;

pub use face_weights::{face_weights, stationary_distribution};
pub use intervals::{CornerIntervals, EdgeRatios, MIN_VALENCE};
