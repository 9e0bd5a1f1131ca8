//! Loop subdivision of whole triangle meshes
//! (`mesh::loop_subdivision`): topology and counts per level, an
//! independent reference implementation of one step, linear reproduction on a
//! regular planar patch, the convex-hull property, convergence to the
//! closed-form limit stencil at the rates of the subdivision matrix, the
//! shipped triangle meshes (`analysis/meshes/triangles/`), refusals, and
//! invariance under affine maps (proptest).

use proptest::prelude::*;
use std::collections::HashMap;
use std::path::PathBuf;
use subdiv_lab::mesh::loop_subdivision::{
    counts_after, half_edges_after, limit_mesh, limit_positions, refine, refine_levels,
};
use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};
use subdiv_lab::mesh::{generators, Mesh, MeshError, MAX_HALF_EDGES};
use subdiv_lab::schemes::loop_subdivision::{beta, subdominant_eigenvalue};

// ---------------------------------------------------------------------------
// Tolerances (all relative to the size of the coordinates involved).

/// Two routes to the same refined point (the library and the reference step
/// below, or `refine(A x)` and `A refine(x)`): each coordinate is a convex
/// combination of at most 13 terms per step (valence <= 12 plus the vertex),
/// rounding at most about `14 eps` of the coordinate scale per step and side,
/// plus `4 eps` for applying an affine map; two levels on two sides give
/// about `72 eps = 1.6e-14`. `1e-13` leaves a factor 6 and is still nine
/// orders below any geometric error a wrong weight would cause.
const ROUTE_RTOL: f64 = 1e-13;

/// Per-level decay ratios measured on refined meshes are exact algebraic
/// facts; their measured value carries the rounding of the distances
/// (`~1e-16 * scale`) divided by the distances themselves, which stay above
/// `1e-6 * scale` in the tests below: at most `1e-10` relative. `1e-8` leaves
/// a margin of 100.
const RATE_RTOL: f64 = 1e-8;

// ---------------------------------------------------------------------------
// Triangle meshes shipped under analysis/meshes/triangles/ (the files are the
// output of these generators; see `shipped_triangle_meshes_are_the_generated_ones`).

fn build(p: Vec<[f64; 3]>, faces: &[Vec<usize>]) -> Mesh {
    Mesh::from_polygons(p, faces).expect("generated mesh is valid")
}

/// The regular octahedron: 8 triangles, 6 vertices of valence 4.
fn octahedron() -> Mesh {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = vec![
        vec![0, 2, 4],
        vec![2, 1, 4],
        vec![1, 3, 4],
        vec![3, 0, 4],
        vec![2, 0, 5],
        vec![1, 2, 5],
        vec![3, 1, 5],
        vec![0, 3, 5],
    ];
    build(p, &faces)
}

/// An 11-gon bipyramid with one top triangle split 1-to-3 at a point raised
/// above it: valences 3 (the new point), 12 (the top apex), 11 (the bottom
/// apex), 5 (two equator vertices) and 4 (the other nine). 14 vertices, 24
/// triangles.
fn bipyramid_3_12() -> Mesh {
    let n = 11;
    let mut p = Vec::new();
    for i in 0..n {
        let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        p.push([a.cos(), a.sin(), 0.0]);
    }
    let (top, bottom, mid) = (n, n + 1, n + 2);
    p.push([0.0, 0.0, 1.2]);
    p.push([0.0, 0.0, -1.2]);
    // above the centroid of the triangle (top, e0, e1), pushed outwards
    let c = [
        (p[0][0] + p[1][0] + p[top][0]) / 3.0,
        (p[0][1] + p[1][1] + p[top][1]) / 3.0,
        (p[0][2] + p[1][2] + p[top][2]) / 3.0,
    ];
    p.push([1.25 * c[0], 1.25 * c[1], 1.25 * c[2]]);
    let mut faces = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        if i == 0 {
            faces.push(vec![i, j, mid]);
            faces.push(vec![j, top, mid]);
            faces.push(vec![top, i, mid]);
        } else {
            faces.push(vec![i, j, top]);
        }
        faces.push(vec![j, i, bottom]);
    }
    build(p, &faces)
}

/// A torus of `10 x 8` quads, each cut into two triangles along the diagonal
/// `(i, j)-(i+1, j+1)` (all valence 6), then four diagonals flipped: the
/// flips of quads `(1, 2)` and `(2, 1)` give vertex `(2, 2)` valence 8, the
/// flips of quads `(6, 5)` and `(5, 4)` give vertex `(6, 5)` valence 4, with
/// valences 5 and 7 around them. 80 vertices, 160 triangles.
fn torus_irregular() -> Mesh {
    let (m, k) = (10usize, 8usize);
    let (big_r, r) = (2.0, 0.75);
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
    let flipped = [(1, 2), (2, 1), (6, 5), (5, 4)];
    let mut faces = Vec::new();
    for i in 0..m {
        for j in 0..k {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            if flipped.contains(&(i, j)) {
                faces.push(vec![a, b, d]);
                faces.push(vec![b, c, d]);
            } else {
                faces.push(vec![a, b, c]);
                faces.push(vec![a, c, d]);
            }
        }
    }
    build(p, &faces)
}

/// `(file stem, mesh, Euler characteristic)` of the shipped triangle meshes.
fn shipped_triangles() -> Vec<(&'static str, Mesh, i64)> {
    vec![
        ("octahedron", octahedron(), 2),
        ("bipyramid_3_12", bipyramid_3_12(), 2),
        ("torus_irregular", torus_irregular(), 0),
    ]
}

/// Every closed triangle mesh of the tests: the shipped ones and the
/// generators' tetrahedron and icosahedron.
fn all_triangle_meshes() -> Vec<(&'static str, Mesh, i64)> {
    let mut v = vec![
        ("tetrahedron", generators::tetrahedron(), 2),
        ("icosahedron", generators::icosahedron(), 2),
    ];
    v.extend(shipped_triangles());
    v
}

fn triangle_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("analysis/meshes/triangles")
}

fn chi(m: &Mesh) -> i64 {
    m.vertex_count() as i64 - m.edge_count() as i64 + m.face_count() as i64
}

fn valences(m: &Mesh) -> Vec<usize> {
    let mut v: Vec<usize> = (0..m.vertex_count()).map(|v| m.valence(v)).collect();
    v.sort_unstable();
    v.dedup();
    v
}

fn scale(points: &[[f64; 3]]) -> f64 {
    points
        .iter()
        .flat_map(|p| p.iter().map(|x| x.abs()))
        .fold(1e-300, f64::max)
}

fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, f64::max)
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The files are the generators' output. Set `SUBDIV_LAB_WRITE_MESHES=1` to
/// (re)write them; otherwise they are compared (topology exactly, positions
/// to 1e-14, the last-bit differences a platform's sin/cos may produce).
#[test]
fn shipped_triangle_meshes_are_the_generated_ones() {
    let write = std::env::var_os("SUBDIV_LAB_WRITE_MESHES").is_some();
    for (name, mesh, euler) in shipped_triangles() {
        let path = triangle_dir().join(format!("{name}.obj"));
        if write {
            std::fs::create_dir_all(triangle_dir()).unwrap();
            std::fs::write(&path, write_obj_string(&mesh)).unwrap();
        }
        let (parsed, _) = parse_obj(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(parsed.face_count(), mesh.face_count(), "{name}");
        for f in 0..mesh.face_count() {
            assert!(
                parsed.face_vertices(f).eq(mesh.face_vertices(f)),
                "{name} {f}"
            );
        }
        assert!(
            max_diff(parsed.positions(), mesh.positions()) < 1e-14,
            "{name}"
        );
        assert_eq!(chi(&mesh), euler, "{name}");
    }
    assert_eq!(valences(&octahedron()), vec![4]);
    assert_eq!(valences(&bipyramid_3_12()), vec![3, 4, 5, 11, 12]);
    assert_eq!(valences(&torus_irregular()), vec![4, 5, 6, 7, 8]);
}

// ---------------------------------------------------------------------------
// Topology.

#[test]
fn counts_and_euler_characteristic_per_level() {
    for (name, mesh, euler) in all_triangle_meshes() {
        let (v0, e0, f0) = (
            mesh.vertex_count() as u64,
            mesh.edge_count() as u64,
            mesh.face_count() as u64,
        );
        let mut m = mesh.clone();
        for level in 1..=3 {
            m = refine(&m).unwrap();
            m.check_invariants().unwrap();
            let counts = (
                m.vertex_count() as u64,
                m.edge_count() as u64,
                m.face_count() as u64,
            );
            assert_eq!(counts, counts_after(v0, e0, f0, level), "{name} {level}");
            assert_eq!(m.face_count() as u64, f0 * 4u64.pow(level as u32));
            assert_eq!(m.half_edge_count() as u64, half_edges_after(&mesh, level));
            assert_eq!(chi(&m), euler, "{name} level {level}");
            assert!((0..m.face_count()).all(|f| m.face_size(f) == 3));
            // new vertices are regular; old ones keep their valence
            for v in 0..m.vertex_count() {
                let expected = if v < mesh.vertex_count() {
                    mesh.valence(v)
                } else if level == 1 {
                    6
                } else {
                    continue;
                };
                assert_eq!(m.valence(v), expected, "{name} level {level} vertex {v}");
            }
        }
        assert_eq!(refine_levels(&mesh, 3).unwrap(), m, "{name}");
        assert_eq!(refine_levels(&mesh, 0).unwrap(), mesh, "{name}");
    }
}

/// The half-edge structure built directly by `refine` equals the one that
/// `Mesh::from_polygons` builds from the same face list (orientation checked
/// there by the pairing of directed edges).
#[test]
fn refined_topology_equals_the_validated_rebuild() {
    for (name, mesh, _) in all_triangle_meshes() {
        let r = refine_levels(&mesh, 2).unwrap();
        let faces: Vec<Vec<usize>> = (0..r.face_count())
            .map(|f| r.face_vertices(f).collect())
            .collect();
        let rebuilt = Mesh::from_polygons(r.positions().to_vec(), &faces).unwrap();
        for h in 0..r.half_edge_count() {
            assert_eq!(r.twin(h), rebuilt.twin(h), "{name} half-edge {h}");
        }
        for v in 0..r.vertex_count() {
            assert_eq!(r.valence(v), rebuilt.valence(v), "{name} vertex {v}");
        }
    }
}

// ---------------------------------------------------------------------------
// An independent reference step: edges found by their end points (hash map),
// neighbours by walking the vertex ring, the faces listed per old triangle.

fn reference_step(m: &Mesh) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let p = m.positions();
    let nv = m.vertex_count();
    let mut out: Vec<[f64; 3]> = Vec::new();
    for v in 0..nv {
        let ring = m.vertex_ring(v);
        let n = ring.len();
        let b = beta(n);
        let mut q = [0.0; 3];
        for k in 0..3 {
            let s: f64 = ring.iter().map(|&h| p[m.target(h)][k]).sum();
            q[k] = (1.0 - n as f64 * b) * p[v][k] + b * s;
        }
        out.push(q);
    }
    let mut edge_point: HashMap<(usize, usize), usize> = HashMap::new();
    let mut faces = Vec::new();
    for f in 0..m.face_count() {
        let c: Vec<usize> = m.face_vertices(f).collect();
        let mut mids = [0usize; 3];
        for i in 0..3 {
            let (a, b, o) = (c[i], c[(i + 1) % 3], c[(i + 2) % 3]);
            let key = (a.min(b), a.max(b));
            mids[i] = *edge_point.entry(key).or_insert_with(|| {
                // the other opposite vertex: third vertex of the face across
                let h = m.find_half_edge(b, a).unwrap();
                let d = m.target(m.next(h));
                out.push(std::array::from_fn(|k| {
                    0.375 * (p[a][k] + p[b][k]) + 0.125 * (p[o][k] + p[d][k])
                }));
                out.len() - 1
            });
        }
        faces.push(vec![c[0], mids[0], mids[2]]);
        faces.push(vec![c[1], mids[1], mids[0]]);
        faces.push(vec![c[2], mids[2], mids[1]]);
        faces.push(vec![mids[0], mids[1], mids[2]]);
    }
    (out, faces)
}

/// Maps every vertex of `a` to the vertex of `b` at the same place in the
/// same faces: the face lists agree up to the numbering of the edge points.
#[test]
fn one_step_agrees_with_the_reference_step() {
    for (name, mesh, _) in all_triangle_meshes() {
        // perturbed positions, so that no symmetry hides a wrong neighbour
        let mut m = mesh.clone();
        let q: Vec<[f64; 3]> = m
            .positions()
            .iter()
            .enumerate()
            .map(|(i, x)| {
                std::array::from_fn(|k| x[k] + 0.1 * (((i * 7 + k * 3) % 11) as f64 / 11.0 - 0.5))
            })
            .collect();
        m.set_positions(q).unwrap();
        let r = refine(&m).unwrap();
        let (pos, faces) = reference_step(&m);
        assert_eq!(r.face_count(), faces.len(), "{name}");
        let mut map = vec![usize::MAX; pos.len()];
        for (f, face) in faces.iter().enumerate() {
            let ours: Vec<usize> = r.face_vertices(f).collect();
            for (&a, &b) in face.iter().zip(&ours) {
                assert!(map[a] == usize::MAX || map[a] == b, "{name} face {f}");
                map[a] = b;
            }
        }
        // old vertices keep their index
        assert!((0..m.vertex_count()).all(|v| map[v] == v), "{name}");
        let s = scale(&pos);
        for (i, x) in pos.iter().enumerate() {
            let y = r.positions()[map[i]];
            assert!(
                (0..3).all(|k| (x[k] - y[k]).abs() <= ROUTE_RTOL * s),
                "{name} vertex {i}: {x:?} vs {y:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// Linear reproduction on a regular planar patch.

/// A torus grid `m x k` of the diagonal triangulation (all valence 6) whose
/// vertex `(i, j)` sits at the affine image `(i + 0.3 j, 0.9 j, 0.2 i - 0.7 j
/// + 3)` of the lattice: planar and regular everywhere except across the
/// seams `i = m - 1 -> 0` and `j = k - 1 -> 0`, where the geometry jumps.
fn planar_regular_torus(m: usize, k: usize) -> Mesh {
    let mut p = Vec::new();
    for i in 0..m {
        for j in 0..k {
            let (x, y) = (i as f64, j as f64);
            p.push([x + 0.3 * y, 0.9 * y, 0.2 * x - 0.7 * y + 3.0]);
        }
    }
    let idx = |i: usize, j: usize| (i % m) * k + (j % k);
    let mut faces = Vec::new();
    for i in 0..m {
        for j in 0..k {
            faces.push(vec![idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            faces.push(vec![idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    build(p, &faces)
}

/// Whether every point of `stencil` is still on the lattice (`good`) and lies
/// within `reach` of `centre` (the stencil does not cross a seam of the
/// planar torus).
fn local(m: &Mesh, good: &[bool], centre: usize, stencil: &[usize], reach: f64) -> bool {
    let p = m.positions();
    good[centre]
        && stencil
            .iter()
            .all(|&v| good[v] && dist(&p[v], &p[centre]) < reach)
}

/// On the regular planar patch, every vertex point whose one-ring is a
/// lattice hexagon equals the vertex (the data of a linear function are
/// reproduced), and every edge point whose four stencil points are on the
/// lattice is the midpoint of its edge; checked over three levels (a point
/// computed from a stencil across a seam is off the lattice and excluded,
/// together with every later stencil that uses it).
#[test]
fn regular_planar_patch_reproduces_linear_functions() {
    let mut m = planar_regular_torus(12, 10);
    let mut good = vec![true; m.vertex_count()];
    let mut reach = 2.5; // longer than every lattice edge, shorter than a seam jump
    for level in 0..3 {
        let r = refine(&m).unwrap();
        let (p, q) = (m.positions(), r.positions());
        let s = scale(p);
        let mut next_good = vec![false; r.vertex_count()];
        let mut checked_v = 0;
        for v in 0..m.vertex_count() {
            let ring: Vec<usize> = m.vertex_ring(v).iter().map(|&h| m.target(h)).collect();
            if ring.len() == 6 && local(&m, &good, v, &ring, reach) {
                assert!(
                    dist(&q[v], &p[v]) <= ROUTE_RTOL * s,
                    "level {level} vertex {v}"
                );
                next_good[v] = true;
                checked_v += 1;
            }
        }
        let mut checked_e = 0;
        for h in 0..m.half_edge_count() {
            let t = m.twin(h);
            if h > t {
                continue;
            }
            let (a, b) = (m.origin(h), m.target(h));
            let (c, d) = (m.origin(m.prev(h)), m.origin(m.prev(t)));
            if !local(&m, &good, a, &[b, c, d], reach) {
                continue;
            }
            // the new vertex on this edge: the common neighbour of a and b in r
            let e = r
                .vertex_ring(a)
                .iter()
                .map(|&g| r.target(g))
                .find(|&x| x >= m.vertex_count() && r.find_half_edge(x, b).is_some())
                .unwrap();
            let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (p[a][k] + p[b][k]));
            assert!(
                dist(&q[e], &mid) <= ROUTE_RTOL * s,
                "level {level} edge {a}-{b}"
            );
            next_good[e] = true;
            checked_e += 1;
        }
        // most of the patch is away from the seams
        assert!(
            checked_v > m.vertex_count() / 3,
            "level {level}: {checked_v}"
        );
        assert!(checked_e > m.edge_count() / 3, "level {level}: {checked_e}");
        m = r;
        good = next_good;
        reach /= 2.0;
    }
}

// ---------------------------------------------------------------------------
// Convex hull.

/// Every refined point and every limit point lies in the convex hull of the
/// control points: checked through the support function in 200 directions
/// spread over the sphere (a point outside the hull is separated in some
/// direction; the fixed directions catch any point outside by more than the
/// hull's curvature between them, and the maxima must not exceed the
/// control points' by more than rounding).
#[test]
fn refined_and_limit_points_lie_in_the_convex_hull() {
    let dirs: Vec<[f64; 3]> = (0..200)
        .map(|i| {
            // Fibonacci sphere
            let z = 1.0 - (2.0 * i as f64 + 1.0) / 200.0;
            let r = (1.0 - z * z).sqrt();
            let a = i as f64 * std::f64::consts::PI * (3.0 - 5f64.sqrt());
            [r * a.cos(), r * a.sin(), z]
        })
        .collect();
    let support = |pts: &[[f64; 3]], d: &[f64; 3]| {
        pts.iter()
            .map(|p| p[0] * d[0] + p[1] * d[1] + p[2] * d[2])
            .fold(f64::NEG_INFINITY, f64::max)
    };
    for (name, mesh, _) in all_triangle_meshes() {
        let control = mesh.positions();
        let s = scale(control);
        let r = refine_levels(&mesh, 2).unwrap();
        let lim = limit_positions(&r).unwrap();
        for d in &dirs {
            let h0 = support(control, d);
            assert!(support(r.positions(), d) <= h0 + ROUTE_RTOL * s, "{name}");
            assert!(support(&lim, d) <= h0 + ROUTE_RTOL * s, "{name}");
            // and strictly inside for the limit points of a sphere-like mesh
            if name != "torus_irregular" {
                assert!(support(&lim, d) < h0, "{name}");
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Limit positions and convergence.

/// The closed-form stencil is the limit: applying it to the refined mesh
/// gives the same point for every old vertex (which keeps its index), at
/// every level.
#[test]
fn limit_stencil_is_invariant_under_refinement() {
    for (name, mesh, _) in all_triangle_meshes() {
        let l0 = limit_positions(&mesh).unwrap();
        let s = scale(mesh.positions());
        let mut m = mesh.clone();
        for level in 1..=3 {
            m = refine(&m).unwrap();
            let l = limit_positions(&m).unwrap();
            let d = max_diff(&l0, &l[..mesh.vertex_count()]);
            assert!(d <= ROUTE_RTOL * s, "{name} level {level}: {d:e}");
        }
        let lm = limit_mesh(&mesh).unwrap();
        assert_eq!(lm.positions(), &l0[..]);
        assert_eq!(lm.face_count(), mesh.face_count());
    }
}

/// The vertex converges to its limit stencil position with the ratio
/// `5/8 - n beta_n = lambda_n^2` per level, exactly (the rotation-invariant
/// block of the one-ring matrix has eigenvalues 1 and `5/8 - n beta_n`); the
/// first Fourier coefficient of its one-ring, `sum_i e_i w^-i`
/// (`w = exp(2 pi i / n)`), shrinks by exactly the subdominant eigenvalue
/// `lambda_n = 3/8 + cos(2 pi / n) / 4` per level. Measured on the refined
/// meshes at every original vertex (valences 3, 4, 5, 7, 8, 11, 12) over 5
/// levels; and after 5 levels the vertex is within `(lambda_n^2)^5` of the
/// stencil's limit.
#[test]
fn vertices_converge_to_the_limit_at_the_subdominant_rates() {
    let mut seen = std::collections::BTreeSet::new();
    for (name, mesh, _) in all_triangle_meshes() {
        let limit = limit_positions(&mesh).unwrap();
        let nv = mesh.vertex_count();
        let s = scale(mesh.positions());
        let fourier = |m: &Mesh, v: usize| -> f64 {
            let ring = m.vertex_ring(v);
            let n = ring.len() as f64;
            let mut re = [0.0; 3];
            let mut im = [0.0; 3];
            for (i, &h) in ring.iter().enumerate() {
                let a = 2.0 * std::f64::consts::PI * i as f64 / n;
                let e = m.positions()[m.target(h)];
                for k in 0..3 {
                    re[k] += e[k] * a.cos();
                    im[k] -= e[k] * a.sin();
                }
            }
            (0..3)
                .map(|k| re[k] * re[k] + im[k] * im[k])
                .sum::<f64>()
                .sqrt()
        };
        let mut m = mesh.clone();
        let mut d_prev: Vec<f64> = (0..nv)
            .map(|v| dist(&m.positions()[v], &limit[v]))
            .collect();
        let d0 = d_prev.clone();
        let mut f_prev: Vec<f64> = (0..nv).map(|v| fourier(&m, v)).collect();
        for level in 1..=5 {
            m = refine(&m).unwrap();
            for v in 0..nv {
                let n = mesh.valence(v);
                seen.insert(n);
                let lambda = subdominant_eigenvalue(n);
                let rate_v = 0.625 - n as f64 * beta(n);
                assert!((rate_v - lambda * lambda).abs() < 1e-15);
                let d = dist(&m.positions()[v], &limit[v]);
                assert!(
                    d_prev[v] > 1e-6 * s,
                    "{name} {v}: distance too small to measure"
                );
                let ratio = d / d_prev[v];
                assert!(
                    (ratio - rate_v).abs() <= RATE_RTOL * rate_v,
                    "{name} level {level} vertex {v} (n = {n}): vertex ratio {ratio} vs {rate_v}"
                );
                let f = fourier(&m, v);
                assert!(f_prev[v] > 1e-6 * s, "{name} {v}: no subdominant component");
                let ratio = f / f_prev[v];
                assert!(
                    (ratio - lambda).abs() <= RATE_RTOL * lambda,
                    "{name} level {level} vertex {v} (n = {n}): ring ratio {ratio} vs {lambda}"
                );
                d_prev[v] = d;
                f_prev[v] = f;
                if level == 5 {
                    assert!(d <= d0[v] * rate_v.powi(5) * (1.0 + 1e-6));
                }
            }
        }
    }
    assert_eq!(
        seen.into_iter().collect::<Vec<_>>(),
        vec![3, 4, 5, 6, 7, 8, 11, 12]
    );
}

// ---------------------------------------------------------------------------
// Refusals and estimates.

/// The work estimate of `levels` Loop steps: the `subdivide` model of every scheme.
fn estimate(mesh: &subdiv_lab::mesh::Mesh, levels: usize) -> subdiv_lab::budget::Estimate {
    subdiv_lab::budget::subdivide(half_edges_after(mesh, levels))
}

#[test]
fn refuses_quads_and_mixed_meshes_naming_the_face() {
    let cube = generators::cube();
    let err = refine(&cube).unwrap_err();
    assert_eq!(
        err,
        MeshError::NotAllTriangles {
            face: 0,
            corners: 4,
            operation: "Loop refinement"
        }
    );
    assert!(err.to_string().contains("face 0 has 4 corners"));
    assert!(matches!(
        limit_positions(&cube),
        Err(MeshError::NotAllTriangles { face: 0, .. })
    ));
    assert!(matches!(
        refine_levels(&cube, 2),
        Err(MeshError::NotAllTriangles { .. })
    ));
    // a square pyramid: four triangles, then the quad base (face 4)
    let text = "v 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0 1\n\
                f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n";
    let (pyramid, _) = parse_obj(text).unwrap();
    let err = refine(&pyramid).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::NotAllTriangles {
                face: 4,
                corners: 4,
                ..
            }
        ),
        "{err}"
    );
    let err = limit_mesh(&pyramid).unwrap_err();
    assert!(err.to_string().contains("face 4"), "{err}");
}

#[test]
fn meshes_with_boundary_are_refused_naming_the_face() {
    // the octahedron without its last face: an open triangle mesh
    let text = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
                f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\n";
    let err = parse_obj(text).unwrap_err();
    // edge 4->1 (OBJ) of face 3 has no opposite face
    assert_eq!(
        err,
        MeshError::BoundaryEdge {
            u: 3,
            v: 0,
            face: 3
        }
    );
    assert!(
        err.to_string().contains("of face 3 has no opposite face"),
        "{err}"
    );
}

#[test]
fn oversized_requests_are_refused_before_any_work() {
    let ico = generators::icosahedron();
    // 60 * 4^15 > 2^32 - 1 half-edges
    let err = refine_levels(&ico, 15).unwrap_err();
    assert_eq!(
        err,
        MeshError::TooLarge {
            half_edges: 60 * 4u64.pow(15),
            max: MAX_HALF_EDGES
        }
    );
    assert_eq!(half_edges_after(&ico, 40), u64::MAX);
    // the estimate grows by 4 per level, like the other schemes'
    let (a, b) = (estimate(&ico, 3), estimate(&ico, 4));
    assert!((b.bytes / a.bytes - 4.0).abs() < 1e-12);
    assert!((b.seconds / a.seconds - 4.0).abs() < 1e-12);
    assert_eq!(
        estimate(&ico, 3),
        subdiv_lab::budget::subdivide(half_edges_after(&ico, 3))
    );
}

// ---------------------------------------------------------------------------
// Affine invariance (proptest).

fn base(i: usize) -> Mesh {
    all_triangle_meshes().swap_remove(i).1
}

fn apply(a: &[f64; 12], p: &[[f64; 3]]) -> Vec<[f64; 3]> {
    p.iter()
        .map(|x| {
            std::array::from_fn(|r| {
                a[3 * r] * x[0] + a[3 * r + 1] * x[1] + a[3 * r + 2] * x[2] + a[9 + r]
            })
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// `refine(A x) = A refine(x)` and the same for the limit positions, for
    /// random affine maps `A` (possibly singular or orientation reversing)
    /// and randomly perturbed meshes.
    #[test]
    fn refinement_commutes_with_affine_maps(
        i in 0usize..5,
        levels in 1usize..=2,
        a in proptest::array::uniform12(-2.0f64..2.0),
        noise in proptest::collection::vec(-0.3f64..0.3, 240),
    ) {
        let mut m = base(i);
        let q: Vec<[f64; 3]> = m.positions().iter().enumerate()
            .map(|(v, x)| std::array::from_fn(|k| x[k] + noise[(3 * v + k) % noise.len()]))
            .collect();
        m.set_positions(q).unwrap();
        let mut am = m.clone();
        am.set_positions(apply(&a, m.positions())).unwrap();
        let (r, ar) = (refine_levels(&m, levels).unwrap(), refine_levels(&am, levels).unwrap());
        let norm = a.iter().map(|x| x.abs()).sum::<f64>();
        let s = norm * scale(m.positions()) + 1.0;
        let d = max_diff(&apply(&a, r.positions()), ar.positions());
        prop_assert!(d <= ROUTE_RTOL * s, "refined: {d:e} (scale {s})");
        let d = max_diff(&apply(&a, &limit_positions(&r).unwrap()), &limit_positions(&ar).unwrap());
        prop_assert!(d <= ROUTE_RTOL * s, "limit: {d:e} (scale {s})");
    }
}
