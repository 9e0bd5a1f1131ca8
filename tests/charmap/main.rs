//! Characteristic maps: regularity and injectivity certificates for every family, against meshes and in reports.
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;

mod charmap;
mod charmap_cc;
mod charmap_generic;
mod charmap_generic_sqrt3;
mod charmap_mesh;
mod charmap_report;
