//! Mesh refinement: closed and open meshes, every scheme's rules, OBJ and knot files, limit positions, convergence.
//!
//! One test binary; each module is one topic.

#[path = "../common/mod.rs"]
mod common;

mod butterfly_mesh;
mod loop_mesh;
mod mesh_cc;
mod mesh_consistency;
mod mesh_io;
mod mesh_props;
mod mesh_shipped;
mod mesh_tensor_limit;
mod modified_butterfly_mesh;
mod open_doo_sabin;
mod sharp_mesh;
mod sharp_normals;
mod sqrt3_mesh;
