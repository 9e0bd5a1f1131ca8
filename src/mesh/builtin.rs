//! The mesh refinement rules of the built-in schemes, chosen by name.

use super::catmull_clark::CatmullClarkRules;
use super::loop_subdivision::LoopRules;
use super::rules::{FaceSplit, MeshRules};
use super::MeshError;
use crate::error::Error;
use crate::schemes::SchemeKind;

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
    let rules: Box<dyn MeshRules> = match (kind, c) {
        (SchemeKind::AdjustableCc, Some(c)) => Box::new(CatmullClarkRules::new(kind.name(), c)?),
        (SchemeKind::AdjustableCc, None) => {
            return Err(Error::InvalidParameter {
                name: "c",
                value: "(missing)".to_owned(),
                reason: "adjustable-cc needs the shape parameter c in [0, 1]",
            }
            .into())
        }
        (_, Some(c)) => {
            return Err(Error::InvalidParameter {
                name: "c",
                value: c.to_string(),
                reason: "only adjustable-cc takes the shape parameter c",
            }
            .into())
        }
        (SchemeKind::CatmullClark, None) => Box::new(CatmullClarkRules::new(kind.name(), 0.5)?),
        (SchemeKind::Loop, None) => Box::new(LoopRules::default()),
        (_, None) => Box::new(FaceSplit::new(kind)?),
    };
    Ok(rules)
}
