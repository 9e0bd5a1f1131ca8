//! Modified butterfly refinement of closed triangle meshes
//! (`mesh::tri_schemes`, math doc section 21) against a reference step on
//! the triangle list: the butterfly stencil between two valence-6 vertices,
//! `3/4 p + sum s_j e_j` at an irregular end, the mean at two irregular
//! ends, with the weights of Zorin, Schroder and Sweldens computed here from
//! their formula.

use super::butterfly_mesh::{apply, butterfly_stencil, check_split4, meshes, Tris};
use std::f64::consts::PI;
use subdiv_lab::mesh::builtin::mesh_rules;
use subdiv_lab::mesh::generators;
use subdiv_lab::schemes::SchemeKind;

/// The weights `s_j` at valence `k`, written from the paper.
fn weights(k: usize) -> Vec<f64> {
    match k {
        3 => vec![5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0],
        4 => vec![3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0],
        _ => (0..k)
            .map(|j| {
                let x = 2.0 * PI * j as f64 / k as f64;
                (0.25 + x.cos() + 0.5 * (2.0 * x).cos()) / k as f64
            })
            .collect(),
    }
}

fn irregular(t: &Tris, p: usize, q: usize) -> Vec<(usize, f64)> {
    let ring = t.ring(p, q);
    let mut st = vec![(p, 0.75)];
    st.extend(ring.iter().zip(weights(ring.len())).map(|(&e, w)| (e, w)));
    st
}

/// Planted: averaging two irregular ends with weights 1 and 0 (taking only
/// `p`'s stencil) fails here (the bipyramid has edges between its apexes'
/// neighbours of valence 4 and the apexes of valence 12).
#[test]
fn one_step_matches_the_reference_on_every_shipped_triangle_mesh() {
    let rules = mesh_rules(SchemeKind::ModifiedButterfly, None).unwrap();
    for (name, mesh) in meshes() {
        let t = Tris::of(&mesh);
        let refined = rules.refine(&mesh).unwrap();
        let val = |p: usize| mesh.valence(p);
        check_split4(&name, &mesh, &refined, |a, b| {
            let st = match (val(a) != 6, val(b) != 6) {
                (false, false) => butterfly_stencil(&t, a, b),
                (true, false) => irregular(&t, a, b),
                (false, true) => irregular(&t, b, a),
                (true, true) => {
                    let mut s = irregular(&t, a, b);
                    s.extend(irregular(&t, b, a));
                    s.into_iter().map(|(i, w)| (i, 0.5 * w)).collect()
                }
            };
            apply(mesh.positions(), &st)
        });
    }
}

#[test]
fn old_vertices_stay_and_the_limit_is_the_control_mesh() {
    let rules = mesh_rules(SchemeKind::ModifiedButterfly, None).unwrap();
    let ico = generators::icosahedron();
    let thrice = rules.refine_levels(&ico, 3).unwrap();
    assert_eq!(&thrice.positions()[..12], ico.positions());
    assert_eq!(rules.limit_mesh(&thrice).unwrap(), thrice);
}
