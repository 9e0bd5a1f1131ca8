//! Open meshes under the Doo-Sabin family (math doc section 19): the
//! boundary polygon after `k` steps is `k` steps of the curve rule (math doc
//! section 2) applied to the input's boundary polygon, and it converges to
//! the quadratic B-spline of that polygon, evaluated independently with
//! `subdiv_lab::bspline`.

use subdiv_lab::bspline::QuadraticSpan;
use subdiv_lab::mesh::generators;
use subdiv_lab::mesh::open::OpenMesh;
use subdiv_lab::mesh::refine::refine;
use subdiv_lab::schemes::SchemeKind;

/// Largest distance between a refined boundary point and the curve rule's
/// point: both are the same few convex combinations of coordinates of size
/// about 1 (the edge ratio may be computed with scaled intervals, one
/// rounding apart), so they agree to a few units in the last place per
/// step; 1e-13 leaves room for 5 steps and fails on any wrong weight.
const CURVE_RULE_AGREEMENT: f64 = 1e-13;

/// The three members of the family.
const SCHEMES: [SchemeKind; 3] = [
    SchemeKind::Nurds,
    SchemeKind::DooSabin,
    SchemeKind::CcVariant,
];

/// A 4 x 4 grid of quads, non-planar, with the quad (1, 1) removed (a hole:
/// two boundary loops, hole corners with 3 faces), the quad (2, 0) split
/// into two triangles (a boundary vertex with 3 faces) and the grid's
/// corners with one face each.
fn grid_with_hole() -> OpenMesh {
    let w = 5;
    let mut p = Vec::new();
    for j in 0..w {
        for i in 0..w {
            let (x, y) = (i as f64, j as f64);
            let z = 0.3 * (0.9 * x).sin() * (0.7 * y).cos() + 0.01 * ((i * 7 + j * 3) % 5) as f64;
            p.push([x + 0.05 * (y * 1.3).sin(), y + 0.04 * (x * 0.8).cos(), z]);
        }
    }
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            let a = j * w + i;
            if (i, j) == (1, 1) {
                continue;
            }
            if (i, j) == (2, 0) {
                faces.push(vec![a, a + 1, a + w + 1]);
                faces.push(vec![a, a + w + 1, a + w]);
                continue;
            }
            faces.push(vec![a, a + 1, a + w + 1, a + w]);
        }
    }
    OpenMesh::from_polygons(p, &faces).unwrap()
}

/// Sets non-uniform intervals: `per_vertex` gives every boundary vertex one
/// interval along both its boundary edges (the curve of math doc section 2);
/// otherwise every directed edge gets its own.
fn nonuniform(m: &mut OpenMesh, per_vertex: bool) {
    let n = m.directed_edge_count();
    let mut k: Vec<f64> = (0..n)
        .map(|h| 0.4 + ((h * 7919) % 23) as f64 / 10.0)
        .collect();
    if per_vertex {
        for lp in m.boundary_corner_loops() {
            for (i, &h) in lp.iter().enumerate() {
                let (u, _) = m.directed_edge(h);
                let d = 0.5 + ((u * 31) % 7) as f64 / 4.0;
                // d(u -> next) on the corner, d(u -> prev) on the ghost of the previous corner
                let prev = lp[(i + lp.len() - 1) % lp.len()];
                k[h] = d;
                k[m.twin(prev)] = d;
            }
        }
    }
    m.set_knots(k).unwrap();
}

/// A closed polygon with directed intervals: `a[i] = d(P_i -> P_{i+1})`,
/// `b[i] = d(P_{i+1} -> P_i)`.
#[derive(Clone, Debug)]
struct Polygon {
    p: Vec<[f64; 3]>,
    a: Vec<f64>,
    b: Vec<f64>,
}

/// The boundary loops of `m` as polygons.
fn boundary_polygons(m: &OpenMesh) -> Vec<Polygon> {
    m.boundary_corner_loops()
        .into_iter()
        .map(|lp| Polygon {
            p: lp
                .iter()
                .map(|&h| m.positions()[m.directed_edge(h).0])
                .collect(),
            a: lp.iter().map(|&h| m.knots()[h]).collect(),
            b: lp.iter().map(|&h| m.knots()[m.twin(h)]).collect(),
        })
        .collect()
}

/// One step of the curve rule (math doc section 2) with directed intervals:
/// `E_i = r P_i + (1 - r) P_{i+1}`, `r = b_i / (a_i + b_i)`, the new points
/// `(P_i + E_i) / 2` and `(E_i + P_{i+1}) / 2`; the new edges carry half the
/// intervals of the ends' directions.
fn curve_step(c: &Polygon) -> Polygon {
    let n = c.p.len();
    let mut out = Polygon {
        p: Vec::new(),
        a: Vec::new(),
        b: Vec::new(),
    };
    for i in 0..n {
        let j = (i + 1) % n;
        let r = c.b[i] / (c.a[i] + c.b[i]);
        let e: Vec<f64> = (0..3)
            .map(|k| r * c.p[i][k] + (1.0 - r) * c.p[j][k])
            .collect();
        out.p.push([0, 1, 2].map(|k| 0.5 * (c.p[i][k] + e[k])));
        out.p.push([0, 1, 2].map(|k| 0.5 * (e[k] + c.p[j][k])));
        out.a.push(c.a[i] / 2.0);
        out.b.push(c.b[i] / 2.0);
        out.a.push(c.b[i] / 2.0);
        out.b.push(c.a[j] / 2.0);
    }
    out
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// Asserts that `got` is `want` up to a cyclic shift, point by point (within
/// [`CURVE_RULE_AGREEMENT`]) and interval by interval (exactly: halving is exact).
fn assert_same_loop(got: &Polygon, want: &Polygon, what: &str) {
    let n = want.p.len();
    assert_eq!(got.p.len(), n, "{what}: loop length");
    let shift = (0..n)
        .min_by(|&x, &y| dist(&got.p[0], &want.p[x]).total_cmp(&dist(&got.p[0], &want.p[y])))
        .unwrap();
    for i in 0..n {
        let w = (i + shift) % n;
        let d = dist(&got.p[i], &want.p[w]);
        assert!(d <= CURVE_RULE_AGREEMENT, "{what}: point {i} is {d:e} off");
        assert_eq!(
            (got.a[i], got.b[i]),
            (want.a[w], want.b[w]),
            "{what}: intervals of edge {i}"
        );
    }
}

/// The refined boundary is the curve rule applied to the input's boundary,
/// for every member, uniform intervals, one interval per boundary vertex and
/// independent directed intervals, levels 1-4, both loops.
#[test]
fn boundary_polygon_is_the_curve_rule() {
    for scheme in SCHEMES {
        for knots in ["uniform", "per-vertex", "directed"] {
            let mut m = grid_with_hole();
            match knots {
                "per-vertex" => nonuniform(&mut m, true),
                "directed" => nonuniform(&mut m, false),
                _ => {}
            }
            // The uniform members ignore the input's intervals (they only
            // propagate them): their curve is Chaikin's, ratio 1/2.
            let mut want: Vec<Polygon> = boundary_polygons(&m);
            if scheme != SchemeKind::Nurds {
                for c in &mut want {
                    c.a.fill(1.0);
                    c.b.fill(1.0);
                }
            }
            let mut r = m.clone();
            for level in 1..=4 {
                r = r.refine(scheme).unwrap();
                r.check_invariants().unwrap();
                want = want.iter().map(curve_step).collect();
                let got = boundary_polygons(&r);
                assert_eq!(got.len(), 2, "two boundary loops");
                for w in &want {
                    let g = got
                        .iter()
                        .find(|g| g.p.len() == w.p.len())
                        .expect("a loop of that length");
                    let what = format!("{scheme} {knots} level {level}");
                    if scheme == SchemeKind::Nurds {
                        assert_same_loop(g, w, &what);
                    } else {
                        // compare points only: the propagated intervals are the input's
                        let mut g = g.clone();
                        g.a.clone_from(&w.a);
                        g.b.clone_from(&w.b);
                        assert_same_loop(&g, w, &what);
                    }
                }
            }
        }
    }
}

/// Distance from `q` to the closed quadratic B-spline of polygon `c` whose
/// control point `P_i` carries the interval `c.a[i]` (`= d(P_i -> P_{i+1})
/// = d(P_i -> P_{i-1})`): minimum over the spans (`bspline::QuadraticSpan`
/// over `P_{i-1}, P_i, P_{i+1}`) of a sampled then golden-section-refined
/// distance.
fn distance_to_curve(c: &Polygon, q: &[f64; 3]) -> f64 {
    let n = c.p.len();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (h, j) = ((i + n - 1) % n, (i + 1) % n);
        let span = QuadraticSpan::new(c.a[h], c.a[i], c.a[j]).unwrap();
        let ctrl = [c.p[h], c.p[i], c.p[j]];
        let f = |t: f64| dist(&span.eval(&ctrl, t), q);
        let samples = 64;
        let t0 = (0..=samples)
            .map(|s| s as f64 / samples as f64)
            .min_by(|&x, &y| f(x).total_cmp(&f(y)))
            .unwrap();
        let (mut lo, mut hi) = (
            (t0 - 1.0 / samples as f64).max(0.0),
            (t0 + 1.0 / samples as f64).min(1.0),
        );
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..80 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if f(x1) < f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        best = best.min(f(0.5 * (lo + hi)));
    }
    best
}

/// The boundary polygon converges to the quadratic B-spline of the input's
/// boundary polygon (uniform, and non-uniform with one interval per
/// boundary vertex): the largest distance of a boundary point to the curve
/// shrinks by the quadratic B-spline's factor 4 per step (measured: 3.98,
/// 4.00, 4.00 from level 3 to 6; 4.5e-5 of a mesh of size 4 at level 6).
#[test]
fn boundary_converges_to_the_quadratic_bspline() {
    for (scheme, per_vertex) in [
        (SchemeKind::DooSabin, false),
        (SchemeKind::CcVariant, false),
        (SchemeKind::Nurds, true),
    ] {
        let mut m = grid_with_hole();
        if per_vertex {
            nonuniform(&mut m, true);
        }
        let curves = boundary_polygons(&m);
        let mut r = m.clone();
        let mut dists = Vec::new();
        for _level in 1..=6 {
            r = r.refine(scheme).unwrap();
            let mut worst = 0.0f64;
            for g in boundary_polygons(&r) {
                // the input loop this one refines: the one with the same share of points
                let c = curves
                    .iter()
                    .find(|c| g.p.len() % c.p.len() == 0 && g.p.len() / c.p.len() == 1 << _level)
                    .expect("loop");
                for q in &g.p {
                    worst = worst.max(distance_to_curve(c, q));
                }
            }
            dists.push(worst);
        }
        for k in 3..dists.len() {
            let ratio = dists[k - 1] / dists[k];
            assert!(
                (3.9..=4.1).contains(&ratio),
                "{scheme}: distance {:e} -> {:e}, ratio {ratio} (expected about 4); all {dists:?}",
                dists[k - 1],
                dists[k]
            );
        }
    }
}

/// On a closed mesh the open refiner is the closed one: same points (bit
/// for bit), faces and intervals.
#[test]
fn closed_meshes_refine_as_before() {
    for base in [generators::cube(), generators::truncated_icosahedron()] {
        let faces: Vec<Vec<usize>> = (0..base.face_count())
            .map(|f| base.face_vertices(f).collect())
            .collect();
        let mut closed = base.clone();
        let k: Vec<f64> = (0..closed.half_edge_count())
            .map(|h| 0.3 + ((h * 131) % 17) as f64 / 7.0)
            .collect();
        closed.set_knots(k).unwrap();
        let mut open = OpenMesh::from_polygons(base.positions().to_vec(), &faces).unwrap();
        assert_eq!(open.boundary_edge_count(), 0);
        // the same interval on the same directed edge
        let ko: Vec<f64> = (0..open.directed_edge_count())
            .map(|h| {
                let (u, v) = open.directed_edge(h);
                closed.knot(closed.find_half_edge(u, v).unwrap())
            })
            .collect();
        open.set_knots(ko).unwrap();
        for scheme in SCHEMES {
            let a = refine(&refine(&closed, scheme).unwrap(), scheme).unwrap();
            let b = open.refine(scheme).unwrap().refine(scheme).unwrap();
            assert_eq!(a.positions(), b.positions(), "{scheme}");
            assert_eq!(a.face_count(), b.face_count());
            for f in 0..a.face_count() {
                assert!(
                    a.face_vertices(f).eq(b.face_vertices(f)),
                    "{scheme} face {f}"
                );
            }
            assert_eq!(a.knots(), b.knots(), "{scheme}");
        }
    }
}

/// Counts: one new point per corner plus two per boundary edge; faces
/// `F + E + V`; a boundary vertex with `k` faces gives a `(k + 2)`-gon; after
/// one step every boundary vertex has two faces.
#[test]
fn open_topology_counts() {
    let m = grid_with_hole();
    let r = m.refine(SchemeKind::Nurds).unwrap();
    let (h, g) = (m.corner_count(), m.boundary_edge_count());
    let edges = (h + g) / 2;
    assert_eq!(r.vertex_count(), h + 2 * g);
    assert_eq!(r.face_count(), m.face_count() + edges + m.vertex_count());
    assert_eq!(r.boundary_edge_count(), 2 * g);
    // the grid's corner (vertex 0, one face) gets a triangle, the hole's
    // corners (three faces) pentagons
    let sizes: Vec<usize> = (0..r.face_count())
        .map(|f| r.face_vertices(f).count())
        .collect();
    let v_face = |v: usize| sizes[m.face_count() + edges + v];
    assert_eq!(v_face(0), 3);
    assert_eq!(v_face(6), 5);
    assert_eq!(v_face(1), 4);
    let r2 = r.refine(SchemeKind::Nurds).unwrap();
    let sizes2: Vec<usize> = (0..r2.face_count())
        .map(|f| r2.face_vertices(f).count())
        .collect();
    let e2 = (r.corner_count() + r.boundary_edge_count()) / 2;
    for v in 0..r.vertex_count() {
        if v >= r.corner_count() {
            assert_eq!(sizes2[r.face_count() + e2 + v], 4, "boundary vertex {v}");
        }
    }
}
