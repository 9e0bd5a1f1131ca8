//! Seeds and random knot draws of the reports: the crate's generators
//! ([`crate::rng`]), re-exported under the reports' path.
//!
//! The generator is [`SplitMix64`]: its output for a given seed is fixed
//! forever, so the seeds recorded in a report's `manifest.json` reproduce its
//! figures exactly.

pub use crate::rng::{derive_seed, log_uniform, SplitMix64};
