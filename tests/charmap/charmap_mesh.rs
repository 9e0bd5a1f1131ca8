//! The extended matrix against mesh-level refinement (an independent route).
//!
//! Random directed-edge knot intervals on closed meshes (triangles, quads,
//! pentagons, hexagons), refined twice with the mesh module; around every
//! face the 4n points are extracted, the mesh is refined once more, and the
//! new point of every (old face, old corner) among the 9n of
//! `schemes::doo_sabin::extended` is compared with `Ext M`. This validates the [derived]
//! E-face and V-face ratios (non-uniform along the edge, uniform across) and
//! the row layout, for NURDS, the CC variant and original Doo-Sabin.

use subdiv_lab::knots::CornerIntervals;
use subdiv_lab::mesh::neighbourhood::face_neighbourhood;
use subdiv_lab::mesh::refine::refine;
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::schemes::doo_sabin::extended::{ExtendedMatrix, OldFace};
use subdiv_lab::schemes::doo_sabin::Layout;
use subdiv_lab::schemes::{LocalScheme, Role, SchemeKind};

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn randomise(mesh: &mut Mesh, rng: &mut Rng) {
    let k: Vec<f64> = (0..mesh.half_edge_count())
        .map(|_| 8f64.powf(2.0 * rng.next() - 1.0))
        .collect();
    mesh.set_knots(k).unwrap();
    let p: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .map(|x| {
            [
                x[0] + 0.3 * (rng.next() - 0.5),
                x[1] + 0.3 * (rng.next() - 0.5),
                x[2] + 0.3 * (rng.next() - 0.5),
            ]
        })
        .collect();
    mesh.set_positions(p).unwrap();
}

/// Worst |mesh - Ext M| over all faces of the level-2 mesh that come from level-0 faces.
fn worst_defect(base: &Mesh, kind: SchemeKind, seed: u64) -> (f64, usize) {
    let mut m0 = base.clone();
    randomise(&mut m0, &mut Rng(seed));
    let m1 = refine(&m0, kind).unwrap();
    let m2 = refine(&m1, kind).unwrap();
    let m3 = refine(&m2, kind).unwrap();
    let mut worst = 0.0f64;
    let mut checked = 0;
    for f in 0..m0.face_count() {
        let idx = face_neighbourhood(&m2, f).expect("4n configuration at level 2");
        let corners: Vec<usize> = m2.face_corners(f).collect();
        let n = corners.len();
        let lay = Layout::new(n);
        let scheme = match kind {
            SchemeKind::Nurds => {
                let (p, q): (Vec<f64>, Vec<f64>) =
                    corners.iter().map(|&h| m2.corner_intervals(h)).unzip();
                LocalScheme::nurds(CornerIntervals::new(p, q).unwrap().ratios().unwrap())
            }
            SchemeKind::DooSabin => LocalScheme::doo_sabin(n).unwrap(),
            _ => LocalScheme::cc_variant(n).unwrap(),
        };
        let ext = ExtendedMatrix::new(&scheme).unwrap();
        let a = ext.matrix().matrix();
        let face_of = |g: OldFace| match g {
            OldFace::F => f,
            OldFace::E(i) => m2.face_of(m2.twin(corners[i])),
            OldFace::V(i) => m2.face_of(m2.twin(m2.next(m2.twin(corners[i])))),
        };
        for (row, label) in ext.labels().iter().enumerate() {
            let i = label.corner.index;
            let v = match label.corner.role {
                Role::FaceCorner => idx[lay.p(i)],
                Role::EdgeFirst => idx[lay.e1(i)],
                Role::EdgeSecond => idx[lay.e2(i)],
                Role::Corner => idx[lay.c(i)],
                r => panic!("unexpected role {r:?}"),
            };
            let g = face_of(label.face);
            let h = m2
                .face_corners(g)
                .find(|&h| m2.origin(h) == v)
                .unwrap_or_else(|| panic!("face {g} has no corner at vertex {v} ({label})"));
            let got = m3.positions()[h];
            for (k, got_k) in got.iter().enumerate() {
                let pred: f64 = (0..4 * n)
                    .map(|j| a[(row, j)] * m2.positions()[idx[j]][k])
                    .sum();
                worst = worst.max((pred - got_k).abs());
            }
        }
        checked += 1;
    }
    (worst, checked)
}

#[test]
fn extended_matrix_matches_mesh_refinement() {
    let meshes = [
        ("tetrahedron", generators::tetrahedron()),
        ("cube", generators::cube()),
        ("icosahedron", generators::icosahedron()),
        ("truncated icosahedron", generators::truncated_icosahedron()),
    ];
    for (name, mesh) in &meshes {
        for (k, kind) in [
            SchemeKind::Nurds,
            SchemeKind::CcVariant,
            SchemeKind::DooSabin,
        ]
        .into_iter()
        .enumerate()
        {
            let (d, checked) =
                worst_defect(mesh, kind, 0x51ED ^ (k as u64 * 977) ^ name.len() as u64);
            assert!(checked > 0);
            assert!(d < 1e-12, "{name} {kind}: |mesh - Ext M| = {d:e}");
        }
    }
}
