//! The ring of Loop's characteristic map as data (math doc section 11): in
//! sector `i` (the triangle `v, e_i, e_{i+1}`) the three level-1 triangles
//! at `e_i`, in the middle and at `e_{i+1}` have only valence-6 corners, so
//! each is a regular patch whose 12-point net ([`REGULAR_NET`]) lies among
//! the `6n + 1` level-1 points of the [`extended_matrix`]; [`LoopRing`]
//! converts the `3n` nets to quartic triangular Bezier form
//! ([`tri_bezier::BOX_SPLINE_TO_BEZIER`]). The certified checks on it are
//! [`crate::charmap::loop_subdivision`].

#[cfg(doc)]
use super::matrix::extended_matrix;
use super::matrix::extended_row_a;
use super::tri_bezier::{self, PlanarTri, REGULAR_NET};
use super::TwoRing;
use crate::bezier::BezierCurve;
use crate::error::{Error, Result};
use std::fmt;

/// Degree of the ring patches (quartic box splines).
pub const DEGREE: usize = 4;

/// Which of the three regular level-1 triangles of a sector.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum LoopPatchKind {
    /// The triangle `e_i, g_i, f_i` of level 1 (at the old `e_i`).
    Start,
    /// The triangle `f_i, e_{i+1}, e_i` of level 1 (the middle one).
    Middle,
    /// The triangle `e_{i+1}, f_i, g_{i+1}` of level 1 (at the old `e_{i+1}`).
    End,
}

impl LoopPatchKind {
    /// All three, in ring order.
    pub const ALL: [LoopPatchKind; 3] = [
        LoopPatchKind::Start,
        LoopPatchKind::Middle,
        LoopPatchKind::End,
    ];

    /// Position `0..3` within the sector.
    pub fn slot(self) -> usize {
        match self {
            LoopPatchKind::Start => 0,
            LoopPatchKind::Middle => 1,
            LoopPatchKind::End => 2,
        }
    }
}

/// A patch of the Loop ring: sector and kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct LoopPatchId {
    /// Sector `i` (the triangle `v, e_i, e_{i+1}`).
    pub sector: usize,
    /// Which regular triangle.
    pub kind: LoopPatchKind,
}

impl fmt::Display for LoopPatchId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "T{}_{}", self.kind.slot(), self.sector)
    }
}

/// Index of the level-1 point at lattice position `(a, b)` in sector `i`'s
/// frame (`v = (0, 0)`, `e_i = (1, 0)`, `e_{i+1} = (0, 1)`), over the rows of
/// the [`extended_matrix`]. Positions: `e_{i-1} = (1,-1)`, `e_{i+2} = (-1,1)`,
/// `g_i = (2,0)`, `g_{i+1} = (0,2)`, `f_{i-1} = (2,-1)`, `f_i = (1,1)`,
/// `f_{i+1} = (-1,2)`, `a_i = (3,0)`, `a_{i+1} = (0,3)`, `b_i = (2,1)`,
/// `b_{i+1} = (-1,3)`, `c_{i-1} = (3,-1)`, `c_i = (1,2)`.
fn sector_point(r: &TwoRing, i: usize, (a, b): (i32, i32)) -> Option<usize> {
    let n = r.valence();
    let (ip, i1, i2) = (r.prev(i), (i + 1) % n, (i + 2) % n);
    Some(match (a, b) {
        (0, 0) => r.v(),
        (1, 0) => r.e(i),
        (0, 1) => r.e(i1),
        (1, -1) => r.e(ip),
        (-1, 1) => r.e(i2),
        (2, 0) => r.g(i),
        (0, 2) => r.g(i1),
        (2, -1) => r.f(ip),
        (1, 1) => r.f(i),
        (-1, 2) => r.f(i1),
        (3, 0) => extended_row_a(n, i),
        (0, 3) => extended_row_a(n, i1),
        (2, 1) => extended_row_a(n, i) + 1,
        (-1, 3) => extended_row_a(n, i1) + 1,
        (3, -1) => extended_row_a(n, ip) + 2,
        (1, 2) => extended_row_a(n, i) + 2,
        _ => return None,
    })
}

/// The 12 level-1 indices of the net of patch `kind` in sector `i`, ordered
/// as [`REGULAR_NET`]: `Start` is the up-triangle at `(1, 0)`, `End` the one
/// at `(0, 1)` (translations), `Middle` the down-triangle
/// `(1, 1) - (up triangle at the origin)` (a rotation by `pi`); all three
/// parametrisations keep the orientation of the sector.
pub fn net_indices(n: usize, i: usize, kind: LoopPatchKind) -> Result<[usize; 12]> {
    let r = TwoRing::new(n)?;
    let place = |o: (i32, i32)| match kind {
        LoopPatchKind::Start => (1 + o.0, o.1),
        LoopPatchKind::Middle => (1 - o.0, 1 - o.1),
        LoopPatchKind::End => (o.0, 1 + o.1),
    };
    let mut out = [0; 12];
    for (x, o) in out.iter_mut().zip(REGULAR_NET) {
        *x = sector_point(&r, i % n, place(o)).ok_or_else(|| Error::Numerical {
            routine: "Loop ring nets",
            reason: format!("lattice position {:?} is not a level-1 point", place(o)),
        })?;
    }
    Ok(out)
}

/// The `3n` regular quartic patches of a Loop ring, ordered sector 0
/// (`Start, Middle, End`), sector 1, ...
#[derive(Clone, Debug, PartialEq)]
pub struct LoopRing {
    n: usize,
    patches: Vec<(LoopPatchId, PlanarTri)>,
}

impl LoopRing {
    /// The ring of the level-1 points `pts` (`6n + 1` planar points, the rows
    /// of the [`extended_matrix`] applied to two-ring data).
    ///
    /// ```
    /// use subdiv_lab::schemes::loop_subdivision::ring::LoopRing;
    /// let pts = vec![[1.0, 2.0]; 31];
    /// let ring = LoopRing::from_points(5, &pts).unwrap();
    /// assert_eq!(ring.patches().len(), 15);
    /// assert!(LoopRing::from_points(5, &pts[..30]).is_err());
    /// ```
    pub fn from_points(n: usize, pts: &[[f64; 2]]) -> Result<Self> {
        TwoRing::new(n)?;
        if pts.len() != 6 * n + 1 {
            return Err(Error::CountMismatch {
                what: "level-1 points of a Loop ring (6n + 1)",
                expected: 6 * n + 1,
                got: pts.len(),
            });
        }
        let mut patches = Vec::with_capacity(3 * n);
        for i in 0..n {
            for kind in LoopPatchKind::ALL {
                let idx = net_indices(n, i, kind)?;
                let net = idx.map(|k| pts[k]);
                patches.push((
                    LoopPatchId { sector: i, kind },
                    tri_bezier::regular_patch(&net),
                ));
            }
        }
        Ok(Self { n, patches })
    }

    /// A ring from explicit patches (e.g. a deliberately broken one): `3n`
    /// quartic patches, `n >= 3`, ordered and labelled as [`LoopRing::patches`].
    pub fn from_patches(patches: Vec<(LoopPatchId, PlanarTri)>) -> Result<Self> {
        let n = patches.len() / 3;
        if n < 3 || patches.len() != 3 * n {
            return Err(Error::CountMismatch {
                what: "ring patches (3 per sector, at least 3 sectors)",
                expected: 3 * n.max(3),
                got: patches.len(),
            });
        }
        for (k, (id, p)) in patches.iter().enumerate() {
            let want = LoopPatchId {
                sector: k / 3,
                kind: LoopPatchKind::ALL[k % 3],
            };
            if *id != want || p.degree() != DEGREE || p.y.degree() != DEGREE {
                return Err(Error::InvalidParameter {
                    name: "ring patch",
                    value: id.to_string(),
                    reason:
                        "patches must be quartic and ordered by sector, then Start, Middle, End",
                });
            }
        }
        Ok(Self { n, patches })
    }

    /// The valence.
    pub fn valence(&self) -> usize {
        self.n
    }

    /// The patches.
    pub fn patches(&self) -> &[(LoopPatchId, PlanarTri)] {
        &self.patches
    }

    /// The ring with the second coordinate negated (reverses orientation).
    pub fn mirrored(&self) -> Self {
        Self {
            n: self.n,
            patches: self
                .patches
                .iter()
                .map(|(id, p)| (*id, p.mirrored()))
                .collect(),
        }
    }

    /// The outer boundary, counter-clockwise in the sector frames: per sector
    /// the edge `g_i -> f_i` of `Start` and `f_i -> g_{i+1}` of `End` (their
    /// corners 1 -> 2).
    pub fn outer_boundary(&self) -> Vec<BezierCurve> {
        self.patches
            .iter()
            .filter(|(id, _)| id.kind != LoopPatchKind::Middle)
            .filter_map(|(_, p)| p.boundary(1, 2).ok())
            .collect()
    }

    /// The inner boundary, same direction: per sector the edge
    /// `e_i -> e_{i+1}` of `Middle` (its corners 2 -> 1).
    pub fn inner_boundary(&self) -> Vec<BezierCurve> {
        self.patches
            .iter()
            .filter(|(id, _)| id.kind == LoopPatchKind::Middle)
            .filter_map(|(_, p)| p.boundary(2, 1).ok())
            .collect()
    }
}
