//! Reports: specs, figures, tables, HTML and the manifest.
//!
//! One test binary; each module is one topic.

mod figure_layout;
mod report_cli;
mod report_data;
mod report_mesh;
mod report_scheme_file;
mod report_sector;
