//! Open meshes with crease and corner tags (math doc section 17): agreement
//! with OpenSubdiv 3.5's reference meshes (shipped under
//! `tests/data/opensubdiv/`, written by `benches/opensubdiv/osd_sharp.cpp`),
//! the `subdivide` flags end to end, and closed untagged meshes unchanged.

use crate::common;
use common::run;
use std::path::PathBuf;
use subdiv_lab::mesh::obj::parse_obj_data;
use subdiv_lab::mesh::sharp::rules::{Boundary, Creasing, SdcScheme};
use subdiv_lab::mesh::sharp::SharpMesh;

/// The agreement required with OpenSubdiv's positions: the references are
/// printed with 17 significant digits and both sides evaluate the same masks
/// in `f64` (differences are rounding, about 1e-15 on these unit-size meshes).
const OSD_AGREEMENT: f64 = 1e-12;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn sharp_mesh(name: &str, boundary: Boundary) -> SharpMesh {
    let text = std::fs::read_to_string(root().join("analysis/meshes/sharp").join(name)).unwrap();
    let data = parse_obj_data(&text).unwrap();
    SharpMesh::new(data.positions, &data.faces, &data.tags, boundary).unwrap()
}

/// Largest distance between our vertices and OpenSubdiv's, matched by
/// nearest position (the numberings differ); panics unless the matching is
/// one-to-one and the faces agree as oriented cycles.
fn distance_to_reference(ours: &SharpMesh, reference: &str) -> f64 {
    let text =
        std::fs::read_to_string(root().join("tests/data/opensubdiv").join(reference)).unwrap();
    let data = parse_obj_data(&text).unwrap();
    let theirs = &data.positions;
    assert_eq!(
        ours.vertex_count(),
        theirs.len(),
        "{reference}: vertex count"
    );
    let mut worst = 0.0f64;
    let mut map = vec![usize::MAX; theirs.len()];
    let mut used = vec![false; theirs.len()];
    for (i, p) in ours.positions().iter().enumerate() {
        let (j, d) = theirs
            .iter()
            .enumerate()
            .map(|(j, q)| {
                let d =
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                (j, d)
            })
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        assert!(
            !used[j],
            "{reference}: two vertices match reference vertex {j}"
        );
        used[j] = true;
        map[i] = j;
        worst = worst.max(d);
    }
    let canonical = |f: Vec<usize>| {
        let k = (0..f.len()).min_by_key(|&k| f[k]).unwrap();
        [&f[k..], &f[..k]].concat()
    };
    let mut ref_faces: Vec<Vec<usize>> = data.faces.into_iter().map(canonical).collect();
    let mut our_faces: Vec<Vec<usize>> = (0..ours.face_count())
        .filter(|&f| !ours.is_hole(f))
        .map(|f| {
            canonical(
                ours.face_vertices(f)
                    .iter()
                    .map(|&v| map[v as usize])
                    .collect(),
            )
        })
        .collect();
    ref_faces.sort();
    our_faces.sort();
    assert_eq!(our_faces, ref_faces, "{reference}: faces");
    worst
}

#[test]
fn agrees_with_opensubdiv_on_open_creased_meshes() {
    let cases = [
        (
            "grid_quads.obj",
            SdcScheme::CatmullClark,
            Boundary::None,
            Creasing::Uniform,
            2,
            "grid_quads_none_uniform_2.obj",
        ),
        (
            "grid_quads.obj",
            SdcScheme::CatmullClark,
            Boundary::EdgeAndCorner,
            Creasing::Chaikin,
            2,
            "grid_quads_edge-and-corner_chaikin_2.obj",
        ),
        (
            "grid_tris.obj",
            SdcScheme::Loop,
            Boundary::EdgeOnly,
            Creasing::Chaikin,
            2,
            "grid_tris_edge-only_chaikin_2.obj",
        ),
        (
            "grid_tris.obj",
            SdcScheme::Loop,
            Boundary::EdgeAndCorner,
            Creasing::Uniform,
            2,
            "grid_tris_edge-and-corner_uniform_2.obj",
        ),
    ];
    let mut failures = Vec::new();
    for (mesh, scheme, boundary, creasing, levels, reference) in cases {
        let refined = sharp_mesh(mesh, boundary)
            .refine_levels(scheme, creasing, levels)
            .unwrap();
        let outcome = std::panic::catch_unwind(|| distance_to_reference(&refined, reference));
        match outcome {
            Ok(d) if d <= OSD_AGREEMENT => {}
            Ok(d) => failures.push(format!("{reference}: distance {d:e}")),
            Err(_) => failures.push(format!("{reference}: topology differs")),
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

#[test]
fn creasing_and_boundary_modes_change_what_they_should() {
    let q = |b, c| {
        sharp_mesh("grid_quads.obj", b)
            .refine_levels(SdcScheme::CatmullClark, c, 2)
            .unwrap()
    };
    let uniform = q(Boundary::EdgeOnly, Creasing::Uniform);
    let chaikin = q(Boundary::EdgeOnly, Creasing::Chaikin);
    assert_ne!(uniform.positions(), chaikin.positions());
    let corner = q(Boundary::EdgeAndCorner, Creasing::Uniform);
    // vertex 0 is a boundary vertex with one face: kept by edge-and-corner only
    assert_eq!(corner.positions()[0], [0.0, 0.0, -0.5]);
    assert_ne!(uniform.positions()[0], [0.0, 0.0, -0.5]);
    // none: same points as edge-only, the faces at the open boundary left out
    let none = q(Boundary::None, Creasing::Uniform);
    assert_eq!(none.positions(), uniform.positions());
    let holes = (0..none.face_count()).filter(|&f| none.is_hole(f)).count();
    assert!(holes > 0 && holes < none.face_count());
}

fn mesh_path(rel: &str) -> String {
    root().join(rel).to_str().unwrap().to_owned()
}

#[test]
fn tag_file_gives_the_same_mesh_as_tag_lines() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.obj");
    let b = dir.path().join("b.obj");
    let common = [
        "--scheme",
        "catmull-clark",
        "--creasing",
        "chaikin",
        "--levels",
        "2",
        "-o",
    ];
    let (code, _, err) = run(&[
        &[
            "subdivide",
            &mesh_path("analysis/meshes/sharp/grid_quads.obj"),
        ][..],
        &common[..],
        &[a.to_str().unwrap()][..],
    ]
    .concat());
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&[
        &[
            "subdivide",
            &mesh_path("analysis/meshes/sharp/grid_quads_untagged.obj"),
            "--tags",
            &mesh_path("analysis/meshes/sharp/grid_quads.tags"),
        ][..],
        &common[..],
        &[b.to_str().unwrap()][..],
    ]
    .concat());
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

#[test]
fn closed_untagged_meshes_ignore_the_sharp_flags() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.obj");
    let b = dir.path().join("b.obj");
    let cube = mesh_path("analysis/meshes/cube.obj");
    let base = [
        "subdivide",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "-o",
    ];
    let (code, _, err) = run(&[&base[..], &[a.to_str().unwrap()][..]].concat());
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&[
        &base[..],
        &[
            b.to_str().unwrap(),
            "--boundary",
            "none",
            "--creasing",
            "chaikin",
        ][..],
    ]
    .concat());
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}
