//! Certified verdicts over boxes of parameters (`verify`).
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;

mod verify;
mod verify_charmap;
mod verify_g1;
mod verify_symmetry;
