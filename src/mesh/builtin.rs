//! The mesh refinement rules of the built-in schemes, chosen by name.

use super::catmull_clark::CatmullClarkRules;
use super::loop_subdivision::LoopRules;
use super::rules::{FaceSplit, MeshRules};
use super::tri_schemes::TriRules;
use super::MeshError;
use crate::schemes::{choice, SchemeKind};

/// The mesh refinement rules of a built-in scheme, by kind: the one place
/// where a scheme name becomes [`MeshRules`] (`subdivide` and the mesh
/// figures dispatch here). `c` is the shape parameter of the adjustable
/// scheme (Catmull-Clark proper has `c = 1/2`); other schemes refuse it.
///
/// ```
/// use subdiv_lab::mesh::rules::KnotUse;
/// use subdiv_lab::mesh::builtin::mesh_rules;
/// use subdiv_lab::schemes::SchemeKind;
/// assert_eq!(mesh_rules(SchemeKind::Nurds, None).unwrap().knots(), KnotUse::Used);
/// assert!(mesh_rules(SchemeKind::AdjustableCc, None).is_err());
/// ```
pub fn mesh_rules(kind: SchemeKind, c: Option<f64>) -> Result<Box<dyn MeshRules>, MeshError> {
    choice::check(kind, false, c.is_some())
        .map_err(|e| MeshError::from(e.into_error(c.map(|c| c.to_string()))))?;
    let rules: Box<dyn MeshRules> = match (kind, c) {
        (SchemeKind::AdjustableCc, Some(c)) => Box::new(CatmullClarkRules::new(kind.name(), c)?),
        (SchemeKind::CatmullClark, _) => Box::new(CatmullClarkRules::new(kind.name(), 0.5)?),
        (SchemeKind::Loop, _) => Box::new(LoopRules::default()),
        (k, _) if k.is_triangle_lattice_scheme() => Box::new(TriRules::new(k)?),
        _ => Box::new(FaceSplit::new(kind)?),
    };
    Ok(rules)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mesh rules follow the rules of `schemes::choice` for `c` for every
    /// scheme. (Planted: letting `choice::check` accept `c` for
    /// catmull-clark fails here.)
    #[test]
    fn the_shape_parameter_follows_the_choice_rules() {
        for &kind in SchemeKind::ALL {
            for c in [None, Some(0.3)] {
                let expect_ok = c.is_some() == kind.takes_c();
                assert_eq!(mesh_rules(kind, c).is_ok(), expect_ok, "{kind} c={c:?}");
            }
        }
    }
}
