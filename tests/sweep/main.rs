//! Sweeps: plans, samplers, the engine, CSV and Parquet output, resume, shards and merge.
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;

mod generic_charmap;
mod loop_specs;
mod sector_sweeps;
mod sweep_cli;
mod sweep_engine;
mod sweep_parquet;
mod sweep_paths;
mod sweep_plan;
mod sweep_props;
mod sweep_run;
mod sweep_verify;
