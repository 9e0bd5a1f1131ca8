//! Small closed meshes made by the project (shipped as OBJ under
//! `analysis/meshes/`, where a test checks that the files equal these).
//!
//! All faces are counter-clockwise seen from outside.

use super::Mesh;

fn build(positions: Vec<[f64; 3]>, faces: &[Vec<usize>]) -> Mesh {
    // The generators below are fixed, valid closed manifolds (checked by tests).
    match Mesh::from_polygons(positions, faces) {
        Ok(m) => m,
        Err(e) => unreachable!("built-in mesh is invalid: {e}"),
    }
}

/// The unit cube `[-1, 1]^3`: 6 quads, 8 vertices of valence 3.
pub fn cube() -> Mesh {
    let mut p = Vec::new();
    for i in 0..8 {
        p.push([
            if i & 1 == 0 { -1.0 } else { 1.0 },
            if i & 2 == 0 { -1.0 } else { 1.0 },
            if i & 4 == 0 { -1.0 } else { 1.0 },
        ]);
    }
    let faces = vec![
        vec![0, 2, 3, 1], // z = -1
        vec![4, 5, 7, 6], // z = +1
        vec![0, 1, 5, 4], // y = -1
        vec![2, 6, 7, 3], // y = +1
        vec![0, 4, 6, 2], // x = -1
        vec![1, 3, 7, 5], // x = +1
    ];
    build(p, &faces)
}

/// A regular tetrahedron: 4 triangles, 4 vertices of valence 3.
pub fn tetrahedron() -> Mesh {
    let p = vec![
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    let faces = vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]];
    build(p, &faces)
}

/// The regular icosahedron: 20 triangles, 12 vertices of valence 5.
pub fn icosahedron() -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let p = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let faces: Vec<Vec<usize>> = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ]
    .iter()
    .map(|f| f.to_vec())
    .collect();
    build(p, &faces)
}

/// The truncated icosahedron ("soccer ball"): 12 pentagons and 20 hexagons,
/// 60 vertices of valence 3. Made by cutting every vertex of the icosahedron
/// at a third of each edge.
pub fn truncated_icosahedron() -> Mesh {
    let ico = icosahedron();
    let h = ico.half_edge_count();
    // one new vertex per half-edge u->v, at u + (v - u)/3
    let p: Vec<[f64; 3]> = (0..h)
        .map(|e| {
            let a = ico.positions()[ico.origin(e)];
            let b = ico.positions()[ico.target(e)];
            [
                a[0] + (b[0] - a[0]) / 3.0,
                a[1] + (b[1] - a[1]) / 3.0,
                a[2] + (b[2] - a[2]) / 3.0,
            ]
        })
        .collect();
    let mut faces = Vec::new();
    // a hexagon per triangle: for each edge u->v, the points near u then near v
    for f in 0..ico.face_count() {
        let mut face = Vec::new();
        for e in ico.face_corners(f) {
            face.push(e);
            face.push(ico.twin(e));
        }
        faces.push(face);
    }
    // a pentagon per vertex: the points near it, in ring order
    for v in 0..ico.vertex_count() {
        faces.push(ico.vertex_ring(v));
    }
    build(p, &faces)
}

/// A torus with `m x k` quads (`m, k >= 3`), major radius `big_r`, minor radius `r`.
pub fn torus(m: usize, k: usize, big_r: f64, r: f64) -> Mesh {
    let mut p = Vec::with_capacity(m * k);
    for i in 0..m {
        let a = 2.0 * std::f64::consts::PI * i as f64 / m as f64;
        for j in 0..k {
            let b = 2.0 * std::f64::consts::PI * j as f64 / k as f64;
            let rad = big_r + r * b.cos();
            p.push([rad * a.cos(), rad * a.sin(), r * b.sin()]);
        }
    }
    let idx = |i: usize, j: usize| (i % m) * k + (j % k);
    let mut faces = Vec::with_capacity(m * k);
    for i in 0..m {
        for j in 0..k {
            faces.push(vec![
                idx(i, j),
                idx(i + 1, j),
                idx(i + 1, j + 1),
                idx(i, j + 1),
            ]);
        }
    }
    build(p, &faces)
}

/// The shipped meshes by file stem: `(name, mesh)`.
pub fn shipped() -> Vec<(&'static str, Mesh)> {
    vec![
        ("cube", cube()),
        ("tetrahedron", tetrahedron()),
        ("icosahedron", icosahedron()),
        ("truncated_icosahedron", truncated_icosahedron()),
        ("torus", torus(8, 6, 2.0, 0.75)),
    ]
}
