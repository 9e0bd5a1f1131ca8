//! Limit normals of open and creased meshes (math doc section 18.6): the
//! normals `boundary::normals::limit_normals` computes at level 1 are the
//! limit of the normals of the refined control fans, and `subdivide --limit
//! --normals` writes them.

use crate::common;
use common::run;
use subdiv_lab::boundary::normals::limit_normals;
use subdiv_lab::mesh::obj::parse_obj_data;
use subdiv_lab::mesh::sharp::rules::{is_sharp, Boundary, Creasing, SdcScheme};
use subdiv_lab::mesh::sharp::SharpMesh;

/// A curved open grid of `n x n` vertices under `--boundary
/// edge-and-corner`: boundary vertices, corners and smooth vertices. Quads,
/// or each quad split into two triangles.
fn grid(n: usize, triangles: bool) -> SharpMesh {
    let p: Vec<[f64; 3]> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            [x, y, 0.4 * (0.9 * x + 0.5 * y * y / n as f64).sin()]
        })
        .collect();
    let id = |x: usize, y: usize| y * n + x;
    let mut faces = Vec::new();
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let q = [id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)];
            if triangles {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    SharpMesh::new(p, &faces, &[], Boundary::EdgeAndCorner).unwrap()
}

/// The unit normal of the control fan at `v`: `sum (next - v) x (prev - v)`
/// over the faces at `v`.
fn fan_normal(m: &SharpMesh, v: usize) -> [f64; 3] {
    let p = m.positions();
    let mut s = [0.0; 3];
    for &f in m.vertex_faces(v) {
        let verts = m.face_vertices(f as usize);
        let k = verts.len();
        let i = verts.iter().position(|&x| x as usize == v).unwrap();
        let a = p[verts[(i + 1) % k] as usize];
        let b = p[verts[(i + k - 1) % k] as usize];
        let d = |q: [f64; 3]| [q[0] - p[v][0], q[1] - p[v][1], q[2] - p[v][2]];
        let (a, b) = (d(a), d(b));
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    let l = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    s.map(|x| x / l)
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    s.atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// Largest angle (radians) between the level-1 limit normals and the fan
/// normals after `1 + extra` levels, separately for smooth vertices and for
/// boundary and corner vertices (the left-eigenvector normals).
fn angles(scheme: SdcScheme, extra: &[usize]) -> Vec<(f64, f64)> {
    let m = grid(6, scheme == SdcScheme::Loop)
        .refine(scheme, Creasing::Uniform)
        .unwrap();
    let normals = limit_normals(&m, scheme).unwrap();
    let sector: Vec<bool> = (0..m.vertex_count())
        .map(|v| {
            m.vertex_edges(v)
                .iter()
                .any(|&e| is_sharp(m.edge_sharpness()[e as usize]))
        })
        .collect();
    assert!(sector.iter().any(|&s| s) && sector.iter().any(|&s| !s));
    let mut fine = m.clone();
    let mut level = 0;
    let mut out = Vec::new();
    for &k in extra {
        while level < k {
            fine = fine.refine(scheme, Creasing::Uniform).unwrap();
            level += 1;
        }
        let mut worst = (0.0f64, 0.0f64);
        for (v, n) in normals.iter().enumerate() {
            let a = angle(*n, fan_normal(&fine, v));
            if sector[v] {
                worst.1 = worst.1.max(a);
            } else {
                worst.0 = worst.0.max(a);
            }
        }
        out.push(worst);
    }
    out
}

/// The fan normals converge to the limit normals: the largest angle, for
/// smooth and for boundary and corner vertices alike, shrinks
/// level by level and is below [`FINEST_ANGLE`] after 7 more levels.
fn check(scheme: SdcScheme) {
    let a = angles(scheme, &[3, 5, 7]);
    println!(
        "{scheme:?}: largest angles (smooth, boundary/corner) after 3, 5, 7 more levels: {a:?}"
    );
    for w in a.windows(2) {
        assert!(
            w[1].0 < 0.5 * w[0].0 && w[1].1 < 0.5 * w[0].1,
            "{scheme:?}: {a:?}"
        );
    }
    let last = a[a.len() - 1];
    assert!(
        last.0 < FINEST_ANGLE && last.1 < FINEST_ANGLE,
        "{scheme:?}: {a:?}"
    );
}

/// The largest angle (radians) allowed after 7 more levels: the fan's
/// faces are about `2^-8` of the grid spacing, and the fan normal differs
/// from the limit normal by a multiple of that size.
const FINEST_ANGLE: f64 = 1e-3;

#[test]
fn catmull_clark_limit_normals_are_the_limit_of_the_fan_normals() {
    check(SdcScheme::CatmullClark);
}

#[test]
fn loop_limit_normals_are_the_limit_of_the_fan_normals() {
    check(SdcScheme::Loop);
}

/// `subdivide --limit --normals` writes one `vn` line per vertex and faces
/// `f v//v`; without `--normals` the output has neither.
#[test]
fn subdivide_writes_limit_normals() {
    let dir = tempfile::tempdir().unwrap();
    let input = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/analysis/meshes/sharp/grid_quads_untagged.obj"
    );
    let out = dir.path().join("n.obj");
    let plain = dir.path().join("p.obj");
    let o = out.to_str().unwrap();
    let (code, _, err) = run(&[
        "subdivide",
        input,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--boundary",
        "edge-and-corner",
        "--limit",
        "--normals",
        "-o",
        o,
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&[
        "subdivide",
        input,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--boundary",
        "edge-and-corner",
        "--limit",
        "-o",
        plain.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    let plain = std::fs::read_to_string(&plain).unwrap();
    let count = |t: &str, p: &str| t.lines().filter(|l| l.starts_with(p)).count();
    assert_eq!(count(&text, "vn "), count(&text, "v "));
    assert!(count(&text, "v ") > 0);
    assert!(text
        .lines()
        .filter(|l| l.starts_with("f "))
        .all(|l| l.contains("//")));
    assert_eq!(count(&plain, "vn "), 0);
    let data = parse_obj_data(&text).unwrap();
    let same = parse_obj_data(&plain).unwrap();
    assert_eq!(data.positions, same.positions);
    assert_eq!(data.faces, same.faces);
}
