//! Local subdivision matrices at boundary, crease and corner vertices of
//! Catmull-Clark and Loop, and their analysis (math doc section 18).
//!
//! A [`SectorConfig`] names one configuration: the scheme, the kind of
//! vertex ([`VertexKind`]: a boundary vertex with one sector of `K` faces, an
//! interior crease vertex whose two sharp edges split its faces into sectors
//! of `K1` and `K2` faces, a corner with one sector of `K` faces and the
//! angle `theta` the sector should fill), and the rule set ([`RuleSet`]):
//!
//! * `standard`: OpenSubdiv's crease and corner vertex masks (the crease
//!   vertex `3/4 v + 1/8 (e_a + e_b)`, the corner `v`, the sharp edge
//!   `(v + e)/2`) with the smooth edge and face rules everywhere else;
//! * `blz`: Biermann, Levin and Zorin (2000): the same, except that every
//!   smooth edge at the vertex gives its far end the weight `gamma` and the
//!   vertex `3/4 - gamma` (the other weights unchanged), with
//!   `gamma = 1/2 - cos(theta_K)/4` (Loop) or `3/8 - cos(theta_K)/4`
//!   (Catmull-Clark) and `theta_K = pi/K` on a boundary or crease sector,
//!   `theta/K` at a convex corner, `(2 pi - theta)/K` at a concave one
//!   ([`SectorConfig::theta_k`], [`SectorConfig::gamma`]).
//!
//! The neighbourhood ([`SectorConfig::local_matrix`]) is the vertex `v`,
//! its edge neighbours `e_i` (`K + 1` of them on a boundary or corner
//! sector, `e_0` and `e_K` on the sharp edges; `K1 + K2` around a crease,
//! sharp edges `e_0` and `e_K1`) and, for Catmull-Clark, the far corners
//! `f_j` of the quads (face `j` is `v, e_j, f_j, e_(j+1)`). It is closed
//! under one step, so its matrix carries the whole local spectrum.
//!
//! ```
//! use subdiv_lab::boundary::{RuleSet, SectorConfig, VertexKind};
//! use subdiv_lab::mesh::sharp::rules::SdcScheme;
//! let c = SectorConfig::new(SdcScheme::Loop, VertexKind::Boundary, &[4], None, RuleSet::Blz).unwrap();
//! let m = c.local_matrix().unwrap();
//! assert_eq!(m.matrix().shape(), (6, 6));
//! assert_eq!(m.rows()[1].to_string(), "e0");
//! ```

pub mod analysis;
pub mod charmap;
pub mod curvature;
pub mod normals;
#[cfg(test)]
mod tests;

use crate::error::{Error, Result};
use crate::mesh::sharp::rules::SdcScheme;
use crate::schemes::{Assembler, LocalMatrix, PointLabel, Role};
use std::f64::consts::PI;
use std::fmt;

/// The largest face count of one sector: `2^20`, far beyond any matrix the
/// work limits allow (a dense matrix of dimension `2^21` needs about
/// `10^15` bytes), and small enough that the index arithmetic
/// ([`SectorConfig::dimension`]) cannot overflow.
pub const MAX_SECTOR_FACES: usize = 1 << 20;

/// The kind of vertex at the centre of the configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum VertexKind {
    /// A boundary vertex: one sector of `K` faces between two boundary edges.
    Boundary,
    /// An interior vertex on a crease: two sharp edges split its faces into
    /// sectors of `K1` and `K2` faces.
    Crease,
    /// A corner: one sector of `K` faces that should fill the angle `theta`.
    Corner,
}

impl VertexKind {
    /// All kinds.
    pub const ALL: [VertexKind; 3] = [VertexKind::Boundary, VertexKind::Crease, VertexKind::Corner];

    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            VertexKind::Boundary => "boundary",
            VertexKind::Crease => "crease",
            VertexKind::Corner => "corner",
        }
    }

    /// The kind of a command-line or spec spelling ([`VertexKind::name`]).
    pub fn parse(s: &str) -> Option<Self> {
        VertexKind::ALL.into_iter().find(|k| k.name() == s)
    }
}

/// The rule set at the vertex (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RuleSet {
    /// OpenSubdiv's crease and corner masks with the smooth edge rules.
    Standard,
    /// Biermann-Levin-Zorin: the smooth edges at the vertex weighted by `gamma`.
    Blz,
}

impl RuleSet {
    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            RuleSet::Standard => "standard",
            RuleSet::Blz => "blz",
        }
    }

    /// The rule set of a command-line or spec spelling ([`RuleSet::name`]).
    pub fn parse(s: &str) -> Option<Self> {
        [RuleSet::Standard, RuleSet::Blz]
            .into_iter()
            .find(|r| r.name() == s)
    }
}

/// The work model of the sector configurations of `scheme` and `kind` by
/// face count `K` per sector (the sweep's valence; a crease has two sectors
/// of `K` faces): the analysis is dominated by the sector's second-order
/// matrix ([`charmap::refinement_matrix`] at radius [`charmap::EIGEN_RADIUS`],
/// math doc section 18.5), `1 + 3 E + 9 F` points for Catmull-Clark and
/// `1 + 3 E + 3 F` for Loop with `E` edges and `F` faces at the vertex
/// (`12 K + 4` and `6 K + 4` on a boundary sector), decomposed densely.
pub fn sector_cost_model(scheme: SdcScheme, kind: VertexKind) -> crate::budget::CostModel {
    let sectors = if kind == VertexKind::Crease { 2.0 } else { 1.0 };
    let per_face = match scheme {
        SdcScheme::CatmullClark => 12.0,
        SdcScheme::Loop => 6.0,
    };
    crate::budget::CostModel::dense(per_face * sectors, 4.0)
}

/// The command-line name of a scheme with sector rules.
pub fn scheme_name(scheme: SdcScheme) -> &'static str {
    match scheme {
        SdcScheme::CatmullClark => "catmull-clark",
        SdcScheme::Loop => "loop",
    }
}

/// One boundary, crease or corner configuration (module docs). Built only
/// by validation ([`SectorConfig::new`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SectorConfig {
    scheme: SdcScheme,
    kind: VertexKind,
    faces: Vec<usize>,
    /// The corner angle in radians (corners only).
    angle: Option<f64>,
    rules: RuleSet,
}

impl SectorConfig {
    /// Validates a configuration: `faces` is `[K]` (boundary, corner) or
    /// `[K1, K2]` (crease), every count `>= 1`; `angle_degrees` is given for
    /// a corner only, finite and strictly between 0 and 360.
    ///
    /// There is no upper bound on the counts here, as for interior valences:
    /// the front ends estimate the work ([`SectorConfig::dimension`]) and
    /// refuse it above their limits.
    pub fn new(
        scheme: SdcScheme,
        kind: VertexKind,
        faces: &[usize],
        angle_degrees: Option<f64>,
        rules: RuleSet,
    ) -> Result<Self> {
        let want = if kind == VertexKind::Crease { 2 } else { 1 };
        if faces.len() != want {
            return Err(Error::InvalidParameter {
                name: "faces",
                value: faces
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(","),
                reason: if want == 2 {
                    "a crease takes two face counts K1,K2 (one per sector)"
                } else {
                    "a boundary or corner vertex takes one face count K"
                },
            });
        }
        if let Some(&k) = faces.iter().find(|&&k| k == 0) {
            return Err(Error::InvalidParameter {
                name: "faces",
                value: k.to_string(),
                reason: "a sector has at least 1 face",
            });
        }
        if let Some(&k) = faces.iter().find(|&&k| k > MAX_SECTOR_FACES) {
            return Err(Error::InvalidParameter {
                name: "faces",
                value: k.to_string(),
                reason: "a sector has at most 2^20 faces",
            });
        }
        let angle = match (kind, angle_degrees) {
            (VertexKind::Corner, None) => {
                return Err(Error::InvalidParameter {
                    name: "angle",
                    value: "(missing)".to_owned(),
                    reason: "a corner needs its angle in degrees, in (0, 360)",
                })
            }
            (VertexKind::Corner, Some(a)) if !(a.is_finite() && a > 0.0 && a < 360.0) => {
                return Err(Error::InvalidParameter {
                    name: "angle",
                    value: a.to_string(),
                    reason:
                        "the corner angle must be finite and strictly between 0 and 360 degrees",
                })
            }
            (VertexKind::Corner, Some(a)) => Some(a.to_radians()),
            (_, Some(a)) => {
                return Err(Error::InvalidParameter {
                    name: "angle",
                    value: a.to_string(),
                    reason: "only a corner takes an angle (a boundary or crease sector fills pi)",
                })
            }
            (_, None) => None,
        };
        Ok(SectorConfig {
            scheme,
            kind,
            faces: faces.to_vec(),
            angle,
            rules,
        })
    }

    /// The scheme.
    pub fn scheme(&self) -> SdcScheme {
        self.scheme
    }
    /// The kind of vertex.
    pub fn kind(&self) -> VertexKind {
        self.kind
    }
    /// The face counts of the sectors (`[K]` or `[K1, K2]`).
    pub fn faces(&self) -> &[usize] {
        &self.faces
    }
    /// The corner angle in radians (corners only).
    pub fn angle(&self) -> Option<f64> {
        self.angle
    }
    /// The rule set.
    pub fn rules(&self) -> RuleSet {
        self.rules
    }

    /// Whether the sectors are open (boundary, corner: `K + 1` edges) rather
    /// than closed around the vertex (crease: `K1 + K2` edges).
    fn open(&self) -> bool {
        self.kind != VertexKind::Crease
    }

    /// The number of faces at the vertex (`K` or `K1 + K2`).
    pub fn face_count(&self) -> usize {
        self.faces.iter().sum()
    }

    /// The number of edges at the vertex: `K + 1` (boundary, corner) or
    /// `K1 + K2` (crease). This is the matrix's `valence`.
    pub fn edge_count(&self) -> usize {
        self.face_count() + usize::from(self.open())
    }

    /// The dimension of the local matrix: `1 + edges (+ faces for Catmull-Clark)`.
    pub fn dimension(&self) -> usize {
        let quads = if self.scheme == SdcScheme::CatmullClark {
            self.face_count()
        } else {
            0
        };
        1 + self.edge_count() + quads
    }

    /// The indices (into `e_i`) of the two sharp edges: `e_0, e_K` or `e_0, e_K1`.
    pub fn sharp_edges(&self) -> [usize; 2] {
        [0, self.faces[0]]
    }

    /// The sector (index into [`SectorConfig::faces`]) of the smooth edge
    /// `e_i`, `None` for a sharp edge.
    pub fn sector_of_edge(&self, i: usize) -> Option<usize> {
        let [a, b] = self.sharp_edges();
        if i == a || i == b {
            None
        } else if i < b {
            Some(0)
        } else {
            Some(1)
        }
    }

    /// `theta_K` of sector `s` (math doc section 18.2): `pi/K` on a boundary
    /// or crease sector, `theta/K` at a convex corner (`theta <= pi`),
    /// `(2 pi - theta)/K` at a concave one.
    pub fn theta_k(&self, s: usize) -> f64 {
        let k = self.faces[s] as f64;
        match self.angle {
            Some(t) if t > PI => (2.0 * PI - t) / k,
            Some(t) => t / k,
            None => PI / k,
        }
    }

    /// The weight of the far end of a smooth edge in sector `s`: `3/8` for
    /// both schemes under the standard rules; BLZ's `gamma = 1/2 -
    /// cos(theta_K)/4` (Loop) or `3/8 - cos(theta_K)/4` (Catmull-Clark).
    /// The vertex gets `3/4 - gamma` (math doc section 18.2).
    pub fn gamma(&self, s: usize) -> f64 {
        match self.rules {
            RuleSet::Standard => 0.375,
            RuleSet::Blz => {
                let c = self.theta_k(s).cos() / 4.0;
                match self.scheme {
                    SdcScheme::Loop => 0.5 - c,
                    SdcScheme::CatmullClark => 0.375 - c,
                }
            }
        }
    }

    /// A one-line description: `catmull-clark boundary K=3 (blz)`,
    /// `loop crease K1=2, K2=3 (standard)`, `loop corner K=2, theta=90 deg (blz)`.
    pub fn describe(&self) -> String {
        let faces = match self.kind {
            VertexKind::Crease => format!("K1={}, K2={}", self.faces[0], self.faces[1]),
            _ => format!("K={}", self.faces[0]),
        };
        let angle = self
            .angle
            .map(|a| format!(", theta={} deg", trim_float(a.to_degrees())))
            .unwrap_or_default();
        format!(
            "{} {} {faces}{angle} ({})",
            scheme_name(self.scheme),
            self.kind.name(),
            self.rules.name()
        )
    }

    /// The labels of the neighbourhood: `v`, `e_0..`, then (Catmull-Clark) `f_0..`.
    pub fn labels(&self) -> Vec<PointLabel> {
        let mut l = vec![PointLabel::new(Role::Vertex, 0)];
        l.extend((0..self.edge_count()).map(|i| PointLabel::new(Role::EdgeNeighbour, i)));
        if self.scheme == SdcScheme::CatmullClark {
            l.extend((0..self.face_count()).map(|j| PointLabel::new(Role::FaceNeighbour, j)));
        }
        l
    }

    /// The local subdivision matrix on the neighbourhood (module docs; math
    /// doc section 18.1), rows and columns labelled `v, e_i, f_j`:
    ///
    /// ```text
    /// v'   = 3/4 v + 1/8 (e_a + e_b)    boundary, crease (e_a, e_b sharp)
    /// v'   = v                           corner
    /// e'   = (v + e)/2                   sharp edge
    /// e_i' = (3/4 - g) v + g e_i + 1/16 (e_(i-1) + e_(i+1) + f_(i-1) + f_i)   Catmull-Clark
    /// e_i' = (3/4 - g) v + g e_i + 1/8 (e_(i-1) + e_(i+1))                    Loop
    /// f_j' = (v + e_j + f_j + e_(j+1))/4                                      Catmull-Clark
    /// ```
    ///
    /// with `g` = [`SectorConfig::gamma`] of the edge's sector (`3/8` for the
    /// standard rules) and indices modulo `K1 + K2` around a crease.
    pub fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        let ne = self.edge_count();
        let nf = self.face_count();
        let cc = self.scheme == SdcScheme::CatmullClark;
        let e = |i: usize| 1 + i % ne;
        let f = |j: usize| 1 + ne + j % nf;
        let mut a = Assembler::square(scheme_name(self.scheme), ne, self.labels());
        let [sa, sb] = self.sharp_edges();
        match self.kind {
            VertexKind::Corner => a.add(0, 0, 1.0),
            _ => a.stencil(0, [(0, 0.75), (e(sa), 0.125), (e(sb), 0.125)]),
        }
        for i in 0..ne {
            let row = e(i);
            let Some(s) = self.sector_of_edge(i) else {
                a.stencil(row, [(0, 0.5), (row, 0.5)]);
                continue;
            };
            let g = self.gamma(s);
            a.stencil(row, [(0, 0.75 - g), (row, g)]);
            // a smooth edge has faces on both sides: i - 1 and i (mod the ring)
            let prev = (i + ne - 1) % ne;
            if cc {
                a.stencil(
                    row,
                    [
                        (e(prev), 0.0625),
                        (e(i + 1), 0.0625),
                        (f(prev), 0.0625),
                        (f(i), 0.0625),
                    ],
                );
            } else {
                a.stencil(row, [(e(prev), 0.125), (e(i + 1), 0.125)]);
            }
        }
        if cc {
            for j in 0..nf {
                a.stencil(
                    f(j),
                    [(0, 0.25), (e(j), 0.25), (f(j), 0.25), (e(j + 1), 0.25)],
                );
            }
        }
        a.finish()
    }
}

/// A configuration is a scheme configuration of its own (name, the edge
/// count at the vertex as valence, the local matrix), so that the sweep
/// engine enumerates it like any other ([`crate::sweep`]); its analysis is
/// [`analysis::analyze_sector`], not the interior one.
impl crate::schemes::Scheme for SectorConfig {
    fn name(&self) -> &str {
        scheme_name(self.scheme)
    }
    fn valence(&self) -> usize {
        self.edge_count()
    }
    fn label(&self) -> String {
        self.describe()
    }
    fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        SectorConfig::local_matrix(self)
    }
}

impl fmt::Display for SectorConfig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe())
    }
}

/// `90`, `22.5`: a float without trailing zeros (up to 6 decimals).
fn trim_float(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_owned()
}
