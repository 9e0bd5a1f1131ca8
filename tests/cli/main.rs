//! The command-line tool end to end: every command's output, exit codes and refusals (the hostile-input table), work limits, and the console sessions of the README and the guide.
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;

mod bounded_work;
mod charmap_cli;
mod cli_analyze;
mod cli_ccfamily;
mod cli_io;
mod cli_loop;
mod cli_matrix;
mod cli_outputs;
mod guide;
mod hostile_inputs;
mod mesh_cli;
