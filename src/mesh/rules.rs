//! A scheme's mesh refinement rules behind one trait, [`MeshRules`] (math doc
//! section 12): one refinement step, the limit mesh, and the optional
//! capabilities the `subdivide` command and the mesh figures use (half-edge
//! knot intervals, per-level statistics of extraordinary faces). The built-in
//! rules are chosen by name in one place,
//! [`mesh_rules`](crate::mesh::builtin::mesh_rules); this file holds the trait
//! and the Doo-Sabin family's implementation ([`FaceSplit`]); the
//! Catmull-Clark family's and Loop's sit with their refinement code.
//!
//! ```
//! use subdiv_lab::mesh::{generators, rules::MeshRules};
//! use subdiv_lab::mesh::builtin::mesh_rules;
//! use subdiv_lab::schemes::SchemeKind;
//! let rules = mesh_rules(SchemeKind::Loop, None).unwrap();
//! let ico = generators::icosahedron();
//! let once = rules.refine(&ico).unwrap();
//! assert_eq!(once.face_count(), 4 * ico.face_count());
//! assert!(rules.level_stats(&once, 1, None).is_none());
//! ```

use super::limit::{face_local_scheme, level_stats, limit_mesh, LevelStats};
use super::refine::refine;
use super::{Mesh, MeshError};
use crate::schemes::Scheme;
use crate::schemes::SchemeKind;
use std::fmt;

/// How a scheme's refinement treats the mesh's half-edge knot intervals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KnotUse {
    /// The scheme ignores them and the result carries none of interest.
    None,
    /// The scheme ignores them but propagates (halves) them, so they must be
    /// valid (original Doo-Sabin, the Catmull-Clark variant).
    Propagated,
    /// The scheme's weights depend on them and it propagates them (NURDS):
    /// `--knots` and `--knots-out` apply.
    Used,
}

/// The mesh refinement rules of one scheme (with its parameters).
pub trait MeshRules: fmt::Debug + Send + Sync {
    /// The scheme's name.
    fn name(&self) -> &str;

    /// How the rules treat half-edge knot intervals (default [`KnotUse::None`]).
    fn knots(&self) -> KnotUse {
        KnotUse::None
    }

    /// One refinement step of a closed mesh.
    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError>;

    /// The limit mesh of a (refined) control mesh.
    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError>;

    /// Per-level statistics of the extraordinary faces of `mesh` at `level`
    /// (`previous`: the parent level's, for the ratios); `None` (the
    /// default) when the scheme has no such notion (vertex-centred schemes).
    fn level_stats(
        &self,
        mesh: &Mesh,
        level: usize,
        previous: Option<&LevelStats>,
    ) -> Option<LevelStats> {
        let _ = (mesh, level, previous);
        None
    }

    /// Whether [`level_stats`](Self::level_stats) gives statistics (default
    /// `false`; must agree with it).
    fn has_level_stats(&self) -> bool {
        false
    }

    /// Number of half-edges after `levels` steps of a closed mesh,
    /// saturating (default: four times as many per step,
    /// [`super::refine::half_edges_after`]); lets callers refuse a request
    /// before allocating.
    fn half_edges_after(&self, mesh: &Mesh, levels: usize) -> u64 {
        super::refine::half_edges_after(mesh, levels)
    }

    /// `levels` steps of [`refine`](Self::refine).
    fn refine_levels(&self, mesh: &Mesh, levels: usize) -> Result<Mesh, MeshError> {
        let mut m = mesh.clone();
        for _ in 0..levels {
            m = self.refine(&m)?;
        }
        Ok(m)
    }

    /// `levels` steps of [`refine`](Self::refine) with the
    /// [`level_stats`](Self::level_stats) of every level `0..=levels`; `None`
    /// when the scheme has no per-level statistics.
    fn refine_with_stats(
        &self,
        mesh: &Mesh,
        levels: usize,
    ) -> Option<Result<(Mesh, Vec<LevelStats>), MeshError>> {
        let mut stats = vec![self.level_stats(mesh, 0, None)?];
        let mut m = mesh.clone();
        for level in 1..=levels {
            m = match self.refine(&m) {
                Ok(m) => m,
                Err(e) => return Some(Err(e)),
            };
            let s = self.level_stats(&m, level, stats.last())?;
            stats.push(s);
        }
        Some(Ok((m, stats)))
    }

    /// The scheme whose masks refine meshes with boundaries and crease or
    /// corner tags ([`super::sharp::SharpMesh`], math doc section 17);
    /// `None` (the default) when these rules refine closed meshes only.
    fn sharp_scheme(&self) -> Option<super::sharp::rules::SdcScheme> {
        None
    }

    /// One step of an open mesh without tags ([`super::open::OpenMesh`],
    /// the boundary rule of math doc section 19); `None` (the default) when
    /// these rules have no boundary rule of that kind.
    fn refine_open(
        &self,
        mesh: &super::open::OpenMesh,
    ) -> Option<Result<super::open::OpenMesh, MeshError>> {
        let _ = mesh;
        None
    }

    /// Whether [`refine_open`](Self::refine_open) refines (default `false`;
    /// must agree with it).
    fn has_open_rule(&self) -> bool {
        false
    }

    /// The local configuration that governs face `f` of `mesh` under these
    /// rules, for face-centred schemes whose extraordinary faces persist
    /// under refinement (the Doo-Sabin family: the face's own edge ratios
    /// for NURDS, its valence for the uniform schemes); default none.
    fn face_scheme(&self, mesh: &Mesh, f: usize) -> Option<crate::Result<Box<dyn Scheme>>> {
        let _ = (mesh, f);
        None
    }
}

/// A vertex rule by valence: the part of a one-ring scheme's mesh rules
/// that a scheme file states (math doc section 12.1). The Catmull-Clark
/// family's refiner ([`super::catmull_clark::refine_quads`]) and Loop's
/// ([`super::loop_subdivision::refine_with`]) take one; the built-in rules
/// and a scheme file's ([`super::user`]) implement it.
pub trait VertexRule: fmt::Debug + Send + Sync {
    /// The weights of one refinement step at valence `n`: quad meshes
    /// `[w_v, w_R, w_Q]` in `v' = w_v v + w_R R + w_Q Q` (`R` the mean of
    /// the edge midpoints, `Q` of the new face points around `v`); triangle
    /// meshes `[w_v, w_e, 0]` in `v' = w_v v + w_e sum e_i`.
    fn refine_weights(&self, n: usize) -> Result<[f64; 3], MeshError>;

    /// The limit stencil at valence `n`, `[l_v, l_e, l_f]` in
    /// `v_inf = l_v v + l_e sum e_i + l_f sum f_i` (`f_i` the face-diagonal
    /// neighbours of a quad mesh; `l_f = 0` on triangle meshes).
    fn limit_weights(&self, n: usize) -> Result<[f64; 3], MeshError>;
}

/// The weights of a [`VertexRule`] by valence, each valence asked once per
/// refinement step.
pub(crate) struct ValenceCache<'a> {
    rule: &'a dyn VertexRule,
    limit: bool,
    by_n: Vec<Option<[f64; 3]>>,
}

impl<'a> ValenceCache<'a> {
    /// The cache of `rule`'s refinement weights (`limit`: its limit stencil).
    pub(crate) fn new(rule: &'a dyn VertexRule, limit: bool) -> Self {
        ValenceCache {
            rule,
            limit,
            by_n: Vec::new(),
        }
    }

    /// The weights at valence `n`.
    pub(crate) fn get(&mut self, n: usize) -> Result<[f64; 3], MeshError> {
        if self.by_n.len() <= n {
            self.by_n.resize(n + 1, None);
        }
        if let Some(w) = self.by_n[n] {
            return Ok(w);
        }
        let w = if self.limit {
            self.rule.limit_weights(n)?
        } else {
            self.rule.refine_weights(n)?
        };
        self.by_n[n] = Some(w);
        Ok(w)
    }
}

/// The Doo-Sabin family's rules (NURDS, original Doo-Sabin, the
/// Catmull-Clark variant): [`refine`], [`limit_mesh`] and [`level_stats`] of
/// this crate's `mesh` module (math doc sections 1-3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceSplit(SchemeKind);

impl FaceSplit {
    /// The rules of `kind`, a scheme of the Doo-Sabin family
    /// ([`MeshError::UnsupportedScheme`] otherwise).
    pub fn new(kind: SchemeKind) -> Result<FaceSplit, MeshError> {
        if kind.is_doo_sabin_family() {
            Ok(FaceSplit(kind))
        } else {
            Err(MeshError::UnsupportedScheme(kind.name().to_owned()))
        }
    }
}

impl MeshRules for FaceSplit {
    fn name(&self) -> &str {
        self.0.name()
    }

    fn knots(&self) -> KnotUse {
        if self.0.takes_knots() {
            KnotUse::Used
        } else {
            KnotUse::Propagated
        }
    }

    fn refine(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        refine(mesh, self.0)
    }

    fn limit_mesh(&self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        limit_mesh(mesh, self.0)
    }

    fn level_stats(
        &self,
        mesh: &Mesh,
        level: usize,
        previous: Option<&LevelStats>,
    ) -> Option<LevelStats> {
        Some(level_stats(mesh, self.0, level, previous))
    }

    fn has_level_stats(&self) -> bool {
        true
    }

    fn refine_open(
        &self,
        mesh: &super::open::OpenMesh,
    ) -> Option<Result<super::open::OpenMesh, MeshError>> {
        Some(mesh.refine(self.0))
    }

    fn has_open_rule(&self) -> bool {
        true
    }

    fn face_scheme(&self, mesh: &Mesh, f: usize) -> Option<crate::Result<Box<dyn Scheme>>> {
        Some(face_local_scheme(mesh, f, self.0).map(|s| Box::new(s) as Box<dyn Scheme>))
    }
}
