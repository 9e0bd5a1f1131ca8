//! Butterfly refinement of closed triangle meshes (`mesh::tri_schemes`,
//! math doc section 21) against an independent step written here on the
//! triangle list (third vertices looked up by directed edge), on the shipped
//! triangle meshes: same new points, old vertices kept, limit = control
//! mesh, refusals. The helpers serve the modified butterfly's and sqrt3's
//! modules too.

use std::collections::HashMap;
use std::path::PathBuf;
use subdiv_lab::mesh::builtin::mesh_rules;
use subdiv_lab::mesh::obj::parse_obj;
use subdiv_lab::mesh::{generators, Mesh, MeshError};
use subdiv_lab::schemes::SchemeKind;

/// Two routes to the same new point: at most a dozen terms with weights of
/// modulus <= 1 (sums of moduli <= 2), rounding about `24 eps` of the
/// coordinate scale per side; `1e-13` relative leaves a wide margin and is
/// far below the effect of any wrong weight (`>= 1/48` of an edge).
pub(crate) const ROUTE_RTOL: f64 = 1e-13;

/// The closed triangle meshes shipped with the repository, and two
/// generated ones.
pub(crate) fn meshes() -> Vec<(String, Mesh)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("analysis/meshes/triangles");
    let mut out: Vec<(String, Mesh)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p.display().to_string(), parse_obj(&text).unwrap().0)
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out.push(("icosahedron".into(), generators::icosahedron()));
    out.push(("tetrahedron".into(), generators::tetrahedron()));
    out
}

/// A triangle list with its third vertices by directed edge.
pub(crate) struct Tris {
    pub tris: Vec<[usize; 3]>,
    /// `opp[(a, b)]`: the third vertex of the triangle with the directed edge `a -> b`.
    pub opp: HashMap<(usize, usize), usize>,
}

impl Tris {
    pub fn of(mesh: &Mesh) -> Tris {
        let tris: Vec<[usize; 3]> = (0..mesh.face_count())
            .map(|f| {
                let v: Vec<usize> = mesh.face_vertices(f).collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        let mut opp = HashMap::new();
        for t in &tris {
            for k in 0..3 {
                opp.insert((t[k], t[(k + 1) % 3]), t[(k + 2) % 3]);
            }
        }
        Tris { tris, opp }
    }

    /// The neighbours of `p` in turn, starting at `q`.
    pub fn ring(&self, p: usize, q: usize) -> Vec<usize> {
        let mut out = vec![q];
        let mut x = self.opp[&(p, q)];
        while x != q {
            out.push(x);
            x = self.opp[&(p, x)];
        }
        out
    }

    /// The undirected edges `(a, b)`, `a < b`.
    pub fn edges(&self) -> Vec<(usize, usize)> {
        let mut e: Vec<(usize, usize)> = self.opp.keys().filter(|(a, b)| a < b).copied().collect();
        e.sort();
        e
    }
}

/// `sum w p` of a stencil.
pub(crate) fn apply(p: &[[f64; 3]], st: &[(usize, f64)]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for &(q, w) in st {
        for k in 0..3 {
            out[k] += w * p[q][k];
        }
    }
    out
}

/// The reference butterfly stencil of the edge `(a, b)`: `1/2` on the ends,
/// `1/8` on the far corners `c, d`, `-1/16` on the four far corners of the
/// triangles across the other edges of the two triangles.
pub(crate) fn butterfly_stencil(t: &Tris, a: usize, b: usize) -> Vec<(usize, f64)> {
    let c = t.opp[&(a, b)];
    let d = t.opp[&(b, a)];
    let wings = [
        t.opp[&(c, b)],
        t.opp[&(a, c)],
        t.opp[&(d, a)],
        t.opp[&(b, d)],
    ];
    let mut st = vec![(a, 0.5), (b, 0.5), (c, 0.125), (d, 0.125)];
    st.extend(wings.iter().map(|&w| (w, -0.0625)));
    st
}

/// Checks one refinement step against `edge_point(a, b)`: old vertices kept
/// at their index, the new vertex adjacent to exactly the old `a`, `b` at
/// the reference point, four times the faces.
pub(crate) fn check_split4(
    name: &str,
    mesh: &Mesh,
    refined: &Mesh,
    edge_point: impl Fn(usize, usize) -> [f64; 3],
) {
    let nv = mesh.vertex_count();
    let scale = mesh
        .positions()
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    assert_eq!(refined.face_count(), 4 * mesh.face_count(), "{name}");
    assert_eq!(refined.vertex_count(), nv + mesh.edge_count(), "{name}");
    assert_eq!(&refined.positions()[..nv], mesh.positions(), "{name}");
    let rt = Tris::of(refined);
    for m in nv..refined.vertex_count() {
        let some_nb = rt.opp.keys().find(|(a, _)| *a == m).unwrap().1;
        let old: Vec<usize> = rt
            .ring(m, some_nb)
            .into_iter()
            .filter(|&x| x < nv)
            .collect();
        assert_eq!(old.len(), 2, "{name}: new vertex {m}");
        let want = edge_point(old[0], old[1]);
        let got = refined.positions()[m];
        for k in 0..3 {
            assert!(
                (want[k] - got[k]).abs() <= ROUTE_RTOL * scale,
                "{name}: edge ({}, {}): {got:?} vs {want:?}",
                old[0],
                old[1]
            );
        }
    }
}

/// Planted: reading the wings of `q` at `tq + 1`, `tq - 1` instead of
/// `tq + 2`, `tq - 2` (in `schemes::tri_rings::butterfly_edge`) fails here.
#[test]
fn one_step_matches_the_reference_on_every_shipped_triangle_mesh() {
    let rules = mesh_rules(SchemeKind::Butterfly, None).unwrap();
    for (name, mesh) in meshes() {
        let t = Tris::of(&mesh);
        let refined = rules.refine(&mesh).unwrap();
        check_split4(&name, &mesh, &refined, |a, b| {
            apply(mesh.positions(), &butterfly_stencil(&t, a, b))
        });
        assert!(t.edges().len() == mesh.edge_count());
    }
}

#[test]
fn the_limit_is_the_control_mesh_and_quads_are_refused() {
    let rules = mesh_rules(SchemeKind::Butterfly, None).unwrap();
    let ico = generators::icosahedron();
    let twice = rules.refine_levels(&ico, 2).unwrap();
    assert_eq!(rules.limit_mesh(&twice).unwrap(), twice);
    assert_eq!(&twice.positions()[..12], ico.positions());
    let err = rules.refine(&generators::cube()).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::NotAllTriangles {
                face: 0,
                corners: 4,
                ..
            }
        ),
        "{err}"
    );
    assert!(rules.limit_mesh(&generators::cube()).is_err());
}
