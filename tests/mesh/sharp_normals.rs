//! Limit normals of open and creased meshes (math doc section 18.6): the
//! normals `boundary::normals::limit_normals` computes at level 1 are the
//! limit of the normals of the refined control fans, and `subdivide --limit
//! --normals` writes them.

use crate::common;
use common::run;
use subdiv_lab::boundary::normals::limit_normals;
use subdiv_lab::mesh::obj::parse_obj_data;
use subdiv_lab::mesh::sharp::rules::{is_sharp, Boundary, Creasing, SdcScheme};
use subdiv_lab::mesh::sharp::tags::Tag;
use subdiv_lab::mesh::sharp::SharpMesh;

/// A curved open grid of `n x n` vertices under `--boundary
/// edge-and-corner`: boundary vertices, corners and smooth vertices. Quads,
/// or each quad split into two triangles. With `crease`, the grid is folded
/// along its middle column, whose edges are tagged infinitely sharp: interior
/// crease vertices, and boundary vertices where the crease meets the
/// boundary (three sharp edges: the corner rule).
fn grid(n: usize, triangles: bool, crease: bool) -> SharpMesh {
    let mid = (n / 2) as f64;
    let p: Vec<[f64; 3]> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            let fold = if crease { 0.8 * (x - mid).abs() } else { 0.0 };
            [x, y, fold + 0.4 * (0.9 * x + 0.5 * y * y / n as f64).sin()]
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
    let tags: Vec<Tag> = if crease {
        let mut text = String::new();
        for y in 0..n - 1 {
            let a = id(n / 2, y);
            text.push_str(&format!("t crease 2/1/0 {a} {} 10\n", a + n));
        }
        parse_obj_data(&text).unwrap().tags
    } else {
        Vec::new()
    };
    SharpMesh::new(p, &faces, &tags, Boundary::EdgeAndCorner).unwrap()
}

/// The unit normals of the control fan's sectors at `v`: the faces at `v`
/// grouped across the edges at `v` that are not sharp, each group's
/// `sum (next - v) x (prev - v)`.
fn sector_fan_normals(m: &SharpMesh, v: usize) -> Vec<[f64; 3]> {
    let p = m.positions();
    let faces: Vec<usize> = m.vertex_faces(v).iter().map(|&f| f as usize).collect();
    let around = |f: usize| {
        let verts = m.face_vertices(f);
        let k = verts.len();
        let i = verts.iter().position(|&x| x as usize == v).unwrap();
        (verts[(i + 1) % k] as usize, verts[(i + k - 1) % k] as usize)
    };
    // union-find over the faces at v, joined across edges that are not sharp
    let mut group: Vec<usize> = (0..faces.len()).collect();
    fn root(g: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while g[r] != r {
            r = g[r];
        }
        g[i] = r;
        r
    }
    for a in 0..faces.len() {
        for b in 0..faces.len() {
            let (next, _) = around(faces[a]);
            let (_, prev) = around(faces[b]);
            let e = m.find_edge(v, next).unwrap();
            if a != b && next == prev && !is_sharp(m.edge_sharpness()[e]) {
                let (ra, rb) = (root(&mut group, a), root(&mut group, b));
                group[ra] = rb;
            }
        }
    }
    let mut sums: Vec<(usize, [f64; 3])> = Vec::new();
    for (i, &f) in faces.iter().enumerate() {
        let r = root(&mut group, i);
        let (a, b) = around(f);
        let d = |q: [f64; 3]| [q[0] - p[v][0], q[1] - p[v][1], q[2] - p[v][2]];
        let (a, b) = (d(p[a]), d(p[b]));
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        match sums.iter_mut().find(|(g, _)| *g == r) {
            Some((_, s)) => (0..3).for_each(|k| s[k] += c[k]),
            None => sums.push((r, c)),
        }
    }
    sums.into_iter()
        .map(|(_, s)| {
            let l = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            s.map(|x| x / l)
        })
        .collect()
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

/// Largest angle (radians) between the level-1 limit normals and the
/// control fan's sector normals after `1 + extra` levels (each limit normal
/// against the nearest sector normal of its vertex), separately for smooth
/// vertices and for vertices with sharp edges (the left-eigenvector normals,
/// one per sector). With `crease`, also checks that the crease vertices
/// have two normals, and returns how many vertices do.
fn angles(scheme: SdcScheme, crease: bool, extra: &[usize]) -> (Vec<(f64, f64)>, usize) {
    let m = grid(7, scheme == SdcScheme::Loop, crease)
        .refine(scheme, Creasing::Uniform)
        .unwrap();
    let normals = limit_normals(&m, scheme).unwrap();
    let per_vertex: Vec<Vec<[f64; 3]>> = (0..m.vertex_count())
        .map(|v| {
            let mut idx: Vec<usize> = m
                .vertex_faces(v)
                .iter()
                .map(|&f| normals.corner(f as usize, v))
                .collect();
            idx.sort_unstable();
            idx.dedup();
            idx.iter().map(|&i| normals.normals[i]).collect()
        })
        .collect();
    let two_sided = per_vertex.iter().filter(|n| n.len() == 2).count();
    assert!(per_vertex.iter().all(|n| n.len() <= 2));
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
        for (v, ns) in per_vertex.iter().enumerate() {
            let fan = sector_fan_normals(&fine, v);
            assert_eq!(fan.len(), ns.len(), "vertex {v}");
            for n in ns {
                let a = fan
                    .iter()
                    .map(|f| angle(*n, *f))
                    .fold(f64::INFINITY, f64::min);
                if sector[v] {
                    worst.1 = worst.1.max(a);
                } else {
                    worst.0 = worst.0.max(a);
                }
            }
        }
        out.push(worst);
    }
    (out, two_sided)
}

/// The fan normals converge to the limit normals: the largest angle, for
/// smooth vertices and for vertices with sharp edges alike, shrinks by at
/// least `ratio` every two levels and is below `finest` after 7 more levels.
/// A normal that missed the limit would show as a plateau: the ratio would
/// tend to 1.
fn check(scheme: SdcScheme, crease: bool, ratio: f64, finest: f64) {
    let (a, two_sided) = angles(scheme, crease, &[3, 5, 7]);
    println!(
        "{scheme:?} (crease {crease}): largest angles (smooth, sharp) after 3, 5, 7 more levels: {a:?}; {two_sided} vertices with two sectors"
    );
    // the folded grid's crease after one level: 13 vertices (11 interior
    // crease vertices and 2 ends on the boundary, each with two sectors)
    assert_eq!(two_sided, if crease { 13 } else { 0 }, "{scheme:?}");
    for w in a.windows(2) {
        assert!(
            w[1].0 < ratio * w[0].0 && w[1].1 < ratio * w[0].1,
            "{scheme:?}: {a:?}"
        );
    }
    let last = a[a.len() - 1];
    assert!(last.0 < finest && last.1 < finest, "{scheme:?}: {a:?}");
}

/// The largest angle (radians) allowed after 7 more levels: the fan's
/// faces are about `2^-8` of the grid spacing, and the fan normal differs
/// from the limit normal by a multiple of that size.
const FINEST_ANGLE: f64 = 1e-3;

/// The factor by which the largest angle must shrink every two levels where
/// the subdominant eigenvalues are `1/2, 1/2` (or `1/2, 1/4`) and the next
/// one `1/4` or less: `(1/2)^2 = 1/4` for the error terms, with room for
/// the constants of the first levels.
const RATIO: f64 = 0.5;

/// The same factor at the Loop crease: where the crease meets the boundary
/// (corner rule, a sector of two triangles) the eigenvalues are `1/2, 1/2`
/// then `3/8` (`analyze --scheme loop --vertex corner --faces 2`), so the
/// fan normal approaches the limit normal by `(3/8) / (1/2) = 3/4` a
/// level, `9/16 = 0.5625` every two; measured 0.566 and 0.565.
const LOOP_CREASE_RATIO: f64 = 0.6;

/// After 7 more levels at that rate the angle is about `(3/4)^8` of the
/// coarse fan's: measured 0.013 rad.
const LOOP_CREASE_FINEST_ANGLE: f64 = 0.02;

#[test]
fn catmull_clark_limit_normals_are_the_limit_of_the_fan_normals() {
    check(SdcScheme::CatmullClark, false, RATIO, FINEST_ANGLE);
}

/// At an interior crease and where the crease meets the boundary, each
/// sector's normal is the limit of that sector's fan normals.
#[test]
fn catmull_clark_sector_normals_at_a_crease_are_the_limit_of_the_sector_fans() {
    check(SdcScheme::CatmullClark, true, RATIO, FINEST_ANGLE);
}

#[test]
fn loop_sector_normals_at_a_crease_are_the_limit_of_the_sector_fans() {
    check(
        SdcScheme::Loop,
        true,
        LOOP_CREASE_RATIO,
        LOOP_CREASE_FINEST_ANGLE,
    );
}

#[test]
fn loop_limit_normals_are_the_limit_of_the_fan_normals() {
    check(SdcScheme::Loop, false, RATIO, FINEST_ANGLE);
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

/// On a closed mesh every face corner takes its vertex's normal (`f v//v`),
/// and the normals point out of the cube; on a creased mesh the corners at
/// the crease take the normal of their own side (`f v//n` with `n` beyond
/// the vertices for one of the two sides).
#[test]
fn subdivide_writes_sector_normals_and_closed_mesh_normals() {
    let dir = tempfile::tempdir().unwrap();
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/meshes/cube.obj");
    let out = dir.path().join("c.obj");
    let o = out.to_str().unwrap();
    let args = ["--levels", "2", "--limit", "--normals", "-o", o];
    let (code, _, err) =
        run(&[&["subdivide", cube, "--scheme", "catmull-clark"][..], &args].concat());
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    let data = parse_obj_data(&text).unwrap();
    let normals: Vec<[f64; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(normals.len(), data.positions.len());
    let centre = data
        .positions
        .iter()
        .fold([0.0; 3], |c, p| [c[0] + p[0], c[1] + p[1], c[2] + p[2]]);
    let centre = centre.map(|x| x / data.positions.len() as f64);
    for (p, n) in data.positions.iter().zip(&normals) {
        let out = (0..3).map(|k| (p[k] - centre[k]) * n[k]).sum::<f64>();
        assert!(out > 0.0, "normal {n:?} at {p:?} points inwards");
    }
    // a quad strip folded along its middle edges, tagged sharp
    let folded = dir.path().join("f.obj");
    std::fs::write(
        &folded,
        "v 0 0 0\nv 1 0 1\nv 2 0 0\nv 0 1 0\nv 1 1 1\nv 2 1 0\nv 0 2 0\nv 1 2 1\nv 2 2 0\n\
         f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\nt crease 2/1/0 1 4 10\nt crease 2/1/0 4 7 10\n",
    )
    .unwrap();
    let (code, _, err) = run(&[
        &[
            "subdivide",
            folded.to_str().unwrap(),
            "--scheme",
            "catmull-clark",
        ][..],
        &["--boundary", "edge-and-corner"],
        &args,
    ]
    .concat());
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
    let vns = text.lines().filter(|l| l.starts_with("vn ")).count();
    // the crease has 9 vertices after two levels, each with a second normal
    assert_eq!(vns, vertices + 9, "{text}");
    let beyond = text
        .lines()
        .filter(|l| l.starts_with("f "))
        .flat_map(|l| l.split(' ').skip(1))
        .filter(|c| {
            let (v, n) = c.split_once("//").unwrap();
            v != n && n.parse::<usize>().unwrap() > vertices
        })
        .count();
    // each second normal is used by the corners of its side's faces at it
    assert!(beyond >= 9, "{beyond}");
}
