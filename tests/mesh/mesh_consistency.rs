//! Mesh-level refinement against the local matrices `S_n` (math doc sections 3-4).
//!
//! Random directed-edge intervals on closed meshes; refine twice; the `4n`
//! points around every face equal, after one more mesh step, `S_n M` with
//! `S_n` built from the ratios the extraordinary-point presets predict from
//! the *initial* intervals. This validates the knot propagation rules, the
//! face-EP and vertex-EP presets and `S_n` together.

use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::mesh::neighbourhood::face_neighbourhood_points;
use subdiv_lab::mesh::refine::refine;
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::rng::XorShift64;
use subdiv_lab::schemes::{LocalScheme, SchemeKind};

/// Agreement required between a mesh step and `S_n M` (coordinates are O(1)).
const TOL: f64 = 1e-12;

struct Rng(XorShift64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0.next_f64()
    }
    /// log-uniform in [1/spread, spread]
    fn interval(&mut self, spread: f64) -> f64 {
        spread.powf(2.0 * self.next() - 1.0)
    }
}

fn randomise(mesh: &mut Mesh, rng: &mut Rng, spread: f64) {
    let k: Vec<f64> = (0..mesh.half_edge_count())
        .map(|_| rng.interval(spread))
        .collect();
    mesh.set_knots(k).unwrap();
    // perturb positions too, so that no accidental symmetry hides an error
    let p: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .map(|x| {
            [
                x[0] + 0.2 * (rng.next() - 0.5),
                x[1] + 0.2 * (rng.next() - 0.5),
                x[2] + 0.2 * (rng.next() - 0.5),
            ]
        })
        .collect();
    mesh.set_positions(p).unwrap();
}

/// `max |M' - S M|` over all coordinates.
fn defect(s: &LocalScheme<f64>, m: &[[f64; 3]], m_next: &[[f64; 3]]) -> f64 {
    let mat = s.matrix().unwrap();
    let a = mat.matrix();
    let mut worst: f64 = 0.0;
    for i in 0..m.len() {
        for k in 0..3 {
            let pred: f64 = (0..m.len()).map(|j| a[(i, j)] * m[j][k]).sum();
            worst = worst.max((pred - m_next[i][k]).abs());
        }
    }
    worst
}

/// Ratios of face `f` computed directly from the mesh's intervals.
fn mesh_ratios(mesh: &Mesh, f: usize) -> EdgeRatios<f64> {
    let (p, q): (Vec<f64>, Vec<f64>) = mesh
        .face_corners(f)
        .map(|h| mesh.corner_intervals(h))
        .unzip();
    CornerIntervals::new(p, q).unwrap().ratios().unwrap()
}

fn close_ratios(a: &EdgeRatios<f64>, b: &EdgeRatios<f64>) -> bool {
    a.as_slice()
        .iter()
        .zip(b.as_slice())
        .all(|(x, y)| (x - y).abs() < 1e-14)
}

/// Returns (face EPs checked, vertex EPs checked, worst defect).
fn check_mesh(name: &str, base: &Mesh, seed: u64, spread: f64) -> (usize, usize, f64) {
    let mut m0 = base.clone();
    randomise(&mut m0, &mut Rng(XorShift64::new(seed)), spread);
    let m1 = refine(&m0, SchemeKind::Nurds).unwrap();
    let m2 = refine(&m1, SchemeKind::Nurds).unwrap();
    let m3 = refine(&m2, SchemeKind::Nurds).unwrap();
    let (f0, e0) = (m0.face_count(), m0.edge_count());
    let mut worst: f64 = 0.0;
    let (mut nf, mut nv) = (0, 0);
    // face EPs (and ordinary faces): presets from the initial directed edges
    for f in 0..f0 {
        let fwd: Vec<f64> = m0.face_corners(f).map(|h| m0.knot(h)).collect();
        let bwd: Vec<f64> = m0.face_corners(f).map(|h| m0.knot(m0.twin(h))).collect();
        let r = EdgeRatios::face_ep(&fwd, &bwd).unwrap();
        assert!(
            close_ratios(&r, &mesh_ratios(&m2, f)),
            "{name}: face {f} ratios"
        );
        let m = face_neighbourhood_points(&m2, f).expect("4n configuration at level 2");
        let mn = face_neighbourhood_points(&m3, f).expect("4n configuration at level 3");
        let d = defect(&LocalScheme::nurds(r), &m, &mn);
        assert!(
            d < TOL,
            "{name}: face EP {f} (n = {}): |M' - S M| = {d:e}",
            fwd.len()
        );
        worst = worst.max(d);
        if fwd.len() != 4 {
            nf += 1;
        }
    }
    // vertex EPs: the V-face of vertex v is face f0 + e0 + v at levels 1, 2, 3
    for v in 0..m0.vertex_count() {
        let a: Vec<f64> = m0.vertex_ring(v).iter().map(|&h| m0.knot(h)).collect();
        let r = EdgeRatios::vertex_ep(&a).unwrap();
        let f = f0 + e0 + v;
        assert!(
            close_ratios(&r, &mesh_ratios(&m2, f)),
            "{name}: vertex {v} ratios"
        );
        let m = face_neighbourhood_points(&m2, f).expect("4n configuration at level 2");
        let mn = face_neighbourhood_points(&m3, f).expect("4n configuration at level 3");
        let d = defect(&LocalScheme::nurds(r), &m, &mn);
        assert!(
            d < TOL,
            "{name}: vertex EP {v} (n = {}): |M' - S M| = {d:e}",
            a.len()
        );
        worst = worst.max(d);
        if a.len() != 4 {
            nv += 1;
        }
    }
    // every F-face of level 2 (a child of a level-1 face) against S_n from its own intervals
    for f in 0..m1.face_count() {
        let m = face_neighbourhood_points(&m2, f).expect("4n configuration at level 2");
        let mn = face_neighbourhood_points(&m3, f).expect("4n configuration at level 3");
        let d = defect(&LocalScheme::nurds(mesh_ratios(&m2, f)), &m, &mn);
        assert!(d < TOL, "{name}: level-2 face {f}: {d:e}");
    }
    (nf, nv, worst)
}

#[test]
fn nurds_mesh_step_equals_s_n_on_every_shipped_mesh() {
    let mut total = (0, 0);
    for (k, (name, mesh)) in generators::shipped().into_iter().enumerate() {
        for (j, spread) in [3.0, 30.0].into_iter().enumerate() {
            let (nf, nv, worst) =
                check_mesh(name, &mesh, 0x9e3779b97f4a7c15 ^ (k * 7 + j) as u64, spread);
            eprintln!(
                "{name} spread {spread}: {nf} face EPs, {nv} vertex EPs, worst defect {worst:e}"
            );
            total.0 += nf;
            total.1 += nv;
        }
    }
    // the shipped meshes have both kinds (tetrahedron, icosahedron, soccer ball: faces; cube, ...: vertices)
    assert!(total.0 > 50 && total.1 > 50, "{total:?}");
}

#[test]
fn uniform_schemes_equal_their_s_n() {
    for kind in [SchemeKind::DooSabin, SchemeKind::CcVariant] {
        for (name, mesh) in generators::shipped() {
            let mut m0 = mesh.clone();
            randomise(&mut m0, &mut Rng(XorShift64::new(77)), 1.0);
            let m1 = refine(&m0, kind).unwrap();
            let m2 = refine(&m1, kind).unwrap();
            let m3 = refine(&m2, kind).unwrap();
            // the F-faces of level 2 (children of level-1 faces)
            for f in 0..m1.face_count() {
                let n = m2.face_size(f);
                let s = LocalScheme::from_kind(kind, n, None).unwrap();
                let m = face_neighbourhood_points(&m2, f).unwrap();
                let mn = face_neighbourhood_points(&m3, f).unwrap();
                let d = defect(&s, &m, &mn);
                assert!(d < TOL, "{kind} {name} face {f}: {d:e}");
            }
        }
    }
}

/// A deliberately wrong propagation rule must be caught: swapping p and q in
/// the S_n prediction (reversed ratios) fails on a non-uniform mesh.
#[test]
fn consistency_check_detects_wrong_ratios() {
    let mut m0 = generators::truncated_icosahedron();
    randomise(&mut m0, &mut Rng(XorShift64::new(5)), 10.0);
    let m2 = refine(&refine(&m0, SchemeKind::Nurds).unwrap(), SchemeKind::Nurds).unwrap();
    let m3 = refine(&m2, SchemeKind::Nurds).unwrap();
    let f = 20; // a pentagon (faces 20.. are the pentagons)
    assert_eq!(m0.face_size(f), 5);
    let fwd: Vec<f64> = m0.face_corners(f).map(|h| m0.knot(h)).collect();
    let bwd: Vec<f64> = m0.face_corners(f).map(|h| m0.knot(m0.twin(h))).collect();
    let wrong = EdgeRatios::face_ep(&bwd, &fwd).unwrap();
    let m = face_neighbourhood_points(&m2, f).unwrap();
    let mn = face_neighbourhood_points(&m3, f).unwrap();
    assert!(defect(&LocalScheme::nurds(wrong), &m, &mn) > 1e-4);
}

/// `S_n` needs the face to have been an F-face for one step in a mesh refined
/// at least twice: faces *created* by the second step (E- and V-faces of level
/// 2) do not yet satisfy it (their neighbours' transverse intervals differ),
/// but their F-children at level 3 do.
#[test]
fn faces_created_at_step_two_satisfy_s_n_one_step_later() {
    let mut m0 = generators::cube();
    randomise(&mut m0, &mut Rng(XorShift64::new(11)), 10.0);
    let m1 = refine(&m0, SchemeKind::Nurds).unwrap();
    let m2 = refine(&m1, SchemeKind::Nurds).unwrap();
    let m3 = refine(&m2, SchemeKind::Nurds).unwrap();
    let m4 = refine(&m3, SchemeKind::Nurds).unwrap();
    let mut not_yet = 0;
    for f in m1.face_count()..m2.face_count() {
        let r = mesh_ratios(&m2, f);
        if let (Some(m), Some(mn)) = (
            face_neighbourhood_points(&m2, f),
            face_neighbourhood_points(&m3, f),
        ) {
            if defect(&LocalScheme::nurds(r.clone()), &m, &mn) > 1e-6 {
                not_yet += 1;
            }
        }
        let m = face_neighbourhood_points(&m3, f).unwrap();
        let mn = face_neighbourhood_points(&m4, f).unwrap();
        let d = defect(&LocalScheme::nurds(mesh_ratios(&m3, f)), &m, &mn);
        assert!(
            d < TOL,
            "face {f} created at level 2, checked at level 3: {d:e}"
        );
        assert!(close_ratios(&r, &mesh_ratios(&m3, f)));
    }
    assert!(not_yet > 0, "some level-2 faces should not satisfy S_n yet");
}
