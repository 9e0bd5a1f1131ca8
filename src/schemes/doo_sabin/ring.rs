//! The characteristic ring: `3n` biquadratic patches around the extraordinary face.
//!
//! Math doc section 7 **\[derived\]**. Among the `9n` points of one step (see
//! [`super::extended`]) the new vertices `(E_i, P_i)`, `(E_i, P_{i+1})` and
//! `(V_i, P_i)` have complete 3x3 regular neighbourhoods. In a chart around
//! the old vertex `P_i` with `x` along the old edge `P_i -> P_{i+1}` and `y`
//! outward (towards `E_i1`), the nets are (rows `y-`, `y0`, `y+`; columns
//! `x-`, `x0`, `x+`):
//!
//! ```text
//! A_i (centre (E_i,P_i)):   (E_{i-1},P_i)       (F,P_i)        (F,P_{i+1})
//!                           (V_i,P_i)           (E_i,P_i)      (E_i,P_{i+1})
//!                           (V_i,E_i1)          (E_i,E_i1)     (E_i,E_i2)
//! B_i (centre (E_i,P_{i+1})): (F,P_i)           (F,P_{i+1})    (E_{i+1},P_{i+1})
//!                           (E_i,P_i)           (E_i,P_{i+1})  (V_{i+1},P_{i+1})
//!                           (E_i,E_i1)          (E_i,E_i2)     (V_{i+1},E_i2)
//! C_i (centre (V_i,P_i)):   (E_{i-1},E_{i-1,2}) (E_{i-1},P_i)  (F,P_i)
//!                           (V_i,E_{i-1,2})     (V_i,P_i)      (E_i,P_i)
//!                           (V_i,C_i)           (V_i,E_i1)     (E_i,E_i1)
//! ```
//!
//! Knot intervals **\[derived\]** from the propagation rules of math doc section
//! 3 (canonical corner intervals `p_i = 1 - r_i`, `q_{i+1} = r_i`; the common
//! factor `2^-(k+1)` is irrelevant): across (`y`) every patch is uniform; along
//! (`x`) `A_i` has intervals `(p_i, p_i, q_{i+1})`, `B_i` has
//! `(p_i, q_{i+1}, q_{i+1})`, `C_i` is uniform. So `A_i` and `B_i` meet at the
//! edge point `r_i (E_i,P_i) + (1 - r_i) (E_i,P_{i+1})` of the old edge's
//! direction, every other junction is a midpoint, and all twelve grid edges of
//! each net are consistent with one tensor-product knot vector (checked in the
//! derivation for every row and column; the tests check that neighbouring
//! patches share their boundary curves).
//!
//! The parameter `s` of a patch runs along `x`, `t` along `y`; all `3n` charts
//! induce the same orientation (the chart of `C_i` maps to that of `B_{i-1}`
//! by a rotation by -90 degrees). That orientation is clockwise with respect
//! to the face's counter-clockwise corner order (for `n = 4` with the grid's
//! own coordinates the Jacobian is `-1/4`; tests); the checks orient the
//! planar basis by the sign of the Jacobian, so this is immaterial.
//!
//! Planar control points come from a 2-D real invariant subspace of `S_n`
//! (see [`crate::charmap::PlanarBasis`]): `x = Ext w1`, `y = Ext w2`.

use super::extended::{ExtLayout, ExtendedMatrix};
use crate::bezier::{BezierCurve, PlanarPatch};
use crate::bspline::{BiquadraticPatch, QuadraticSpan};
use crate::error::{Error, Result};
use crate::knots::EdgeRatios;
use std::fmt;

/// Which of the three patches of sector `i`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum PatchKind {
    /// Centred at `(E_i, P_i)`.
    A,
    /// Centred at `(E_i, P_{i+1})`.
    B,
    /// Centred at `(V_i, P_i)`.
    C,
}

/// A ring patch: kind and sector index `i`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct RingPatchId {
    /// Kind.
    pub kind: PatchKind,
    /// Sector (edge / corner) index.
    pub index: usize,
}

impl fmt::Display for RingPatchId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let k = match self.kind {
            PatchKind::A => "A",
            PatchKind::B => "B",
            PatchKind::C => "C",
        };
        write!(f, "{k}{}", self.index)
    }
}

/// One patch of the ring: B-spline form and Bezier form.
#[derive(Clone, Debug)]
pub struct RingPatch {
    /// Which patch.
    pub id: RingPatchId,
    /// The non-uniform biquadratic B-spline patch.
    pub spline: BiquadraticPatch<2>,
    /// Its Bezier form (bidegree (2, 2)).
    pub bezier: PlanarPatch,
}

/// The `3n` patches of a characteristic ring, ordered `A_0, B_0, C_0, A_1, ...`.
#[derive(Clone, Debug)]
pub struct Ring {
    n: usize,
    patches: Vec<RingPatch>,
}

/// Indices (into the `9n` points) of the net `net[a][b]` of a patch
/// (`a` along `x`/`s`, `b` along `y`/`t`).
pub fn patch_grid(n: usize, id: RingPatchId) -> [[usize; 3]; 3] {
    let x = ExtLayout::new(n);
    let i = id.index % n;
    let ip = i + n - 1; // i - 1 (mod n, via the layout)
                        // rows[b][a] as in the module docs, then transposed
    let rows: [[usize; 3]; 3] = match id.kind {
        PatchKind::A => [
            [x.e_pnext(ip), x.f_p(i), x.f_p(i + 1)],
            [x.v_p(i), x.e_p(i), x.e_pnext(i)],
            [x.v_e1(i), x.e_e1(i), x.e_e2(i)],
        ],
        PatchKind::B => [
            [x.f_p(i), x.f_p(i + 1), x.e_p(i + 1)],
            [x.e_p(i), x.e_pnext(i), x.v_p(i + 1)],
            [x.e_e1(i), x.e_e2(i), x.v_eprev2(i + 1)],
        ],
        PatchKind::C => [
            [x.e_e2(ip), x.e_pnext(ip), x.f_p(i)],
            [x.v_eprev2(i), x.v_p(i), x.e_p(i)],
            [x.v_c(i), x.v_e1(i), x.e_e1(i)],
        ],
    };
    let mut net = [[0; 3]; 3];
    for (a, col) in net.iter_mut().enumerate() {
        for (b, v) in col.iter_mut().enumerate() {
            *v = rows[b][a];
        }
    }
    net
}

/// Knot spans `(u, v)` of a patch (canonical intervals `p_i = s_i`, `q_{i+1} = r_i`).
pub fn patch_spans(
    ratios: &EdgeRatios<f64>,
    id: RingPatchId,
) -> Result<(QuadraticSpan, QuadraticSpan)> {
    let i = id.index % ratios.valence();
    let (r, s) = (ratios.as_slice()[i], ratios.complement()[i]);
    let u = match id.kind {
        PatchKind::A => QuadraticSpan::new(s, s, r)?,
        PatchKind::B => QuadraticSpan::new(s, r, r)?,
        PatchKind::C => QuadraticSpan::uniform(),
    };
    Ok((u, QuadraticSpan::uniform()))
}

impl Ring {
    /// The ring whose `9n` planar control points are `points` (in the order of
    /// [`ExtendedMatrix`]) for a configuration with edge ratios `ratios`.
    pub fn from_points(points: &[[f64; 2]], ratios: &EdgeRatios<f64>) -> Result<Self> {
        let n = ratios.valence();
        if points.len() != 9 * n {
            return Err(Error::CountMismatch {
                what: "ring control points (9n)",
                expected: 9 * n,
                got: points.len(),
            });
        }
        let mut patches = Vec::with_capacity(3 * n);
        for i in 0..n {
            for kind in [PatchKind::A, PatchKind::B, PatchKind::C] {
                let id = RingPatchId { kind, index: i };
                let g = patch_grid(n, id);
                let mut control = [[[0.0; 2]; 3]; 3];
                for a in 0..3 {
                    for b in 0..3 {
                        control[a][b] = points[g[a][b]];
                    }
                }
                let (u, v) = patch_spans(ratios, id)?;
                let spline = BiquadraticPatch::new(u, v, control);
                let bez = spline.to_bezier();
                let net: Vec<Vec<[f64; 2]>> = bez.iter().map(|c| c.to_vec()).collect();
                patches.push(RingPatch {
                    id,
                    spline,
                    bezier: PlanarPatch::from_net(&net)?,
                });
            }
        }
        Ok(Self { n, patches })
    }

    /// The ring of the planar basis `(w1, w2)` (two `4n`-vectors) under the extended matrix.
    pub fn from_basis(
        ext: &ExtendedMatrix<f64>,
        ratios: &EdgeRatios<f64>,
        w1: &[f64],
        w2: &[f64],
    ) -> Result<Self> {
        let points = ring_points(ext, w1, w2)?;
        Self::from_points(&points, ratios)
    }

    /// Valence `n`.
    pub fn valence(&self) -> usize {
        self.n
    }

    /// The patches, `A_0, B_0, C_0, A_1, ...`.
    pub fn patches(&self) -> &[RingPatch] {
        &self.patches
    }

    /// The patch `id`.
    pub fn patch(&self, id: RingPatchId) -> &RingPatch {
        let k = match id.kind {
            PatchKind::A => 0,
            PatchKind::B => 1,
            PatchKind::C => 2,
        };
        &self.patches[3 * (id.index % self.n) + k]
    }

    /// The ring with its second coordinate negated (reverses the orientation).
    pub fn mirrored(&self) -> Self {
        Self {
            n: self.n,
            patches: self
                .patches
                .iter()
                .map(|p| {
                    let mut spline = p.spline;
                    for col in spline.control.iter_mut() {
                        for pt in col.iter_mut() {
                            pt[1] = -pt[1];
                        }
                    }
                    RingPatch {
                        id: p.id,
                        spline,
                        bezier: p.bezier.mirrored(),
                    }
                })
                .collect(),
        }
    }

    /// The outer boundary as `4n` quadratic Bezier curves, traversed with the
    /// ring on the left in every chart (counter-clockwise around the origin
    /// when the Jacobian is positive and the ring is embedded).
    ///
    /// Forward order (ring on the right): `A_i` top, `B_i` top, `C_{i+1}` left
    /// side (`s = 0`, `t` up), `C_{i+1}` top; this returns it reversed.
    pub fn outer_boundary(&self) -> Vec<BezierCurve> {
        let n = self.n;
        let id = |kind, index| RingPatchId { kind, index };
        let mut fwd = Vec::with_capacity(4 * n);
        for i in 0..n {
            fwd.push(self.patch(id(PatchKind::A, i)).bezier.boundary_t(true));
            fwd.push(self.patch(id(PatchKind::B, i)).bezier.boundary_t(true));
            let c = &self.patch(id(PatchKind::C, i + 1)).bezier;
            fwd.push(c.boundary_s(false));
            fwd.push(c.boundary_t(true));
        }
        fwd.iter().rev().map(BezierCurve::reversed).collect()
    }

    /// The inner boundary as `2n` curves (`A_i` and `B_i` bottoms), traversed
    /// counter-clockwise around the origin when the Jacobian is positive and
    /// the ring is embedded (ring on the right).
    pub fn inner_boundary(&self) -> Vec<BezierCurve> {
        let n = self.n;
        let mut fwd = Vec::with_capacity(2 * n);
        for i in 0..n {
            for kind in [PatchKind::A, PatchKind::B] {
                fwd.push(
                    self.patch(RingPatchId { kind, index: i })
                        .bezier
                        .boundary_t(false),
                );
            }
        }
        fwd.iter().rev().map(BezierCurve::reversed).collect()
    }

    /// Largest coordinate magnitude of the Bezier control points.
    pub fn max_abs(&self) -> f64 {
        self.patches
            .iter()
            .map(|p| p.bezier.x.max_abs().max(p.bezier.y.max_abs()))
            .fold(0.0, f64::max)
    }
}

/// The `9n` planar points `(Ext w1, Ext w2)`.
pub fn ring_points(ext: &ExtendedMatrix<f64>, w1: &[f64], w2: &[f64]) -> Result<Vec<[f64; 2]>> {
    let m = ext.matrix().matrix();
    for w in [w1, w2] {
        if w.len() != m.ncols() {
            return Err(Error::CountMismatch {
                what: "planar basis vector (4n entries)",
                expected: m.ncols(),
                got: w.len(),
            });
        }
    }
    Ok((0..m.nrows())
        .map(|i| {
            let (mut x, mut y) = (0.0, 0.0);
            for j in 0..m.ncols() {
                let a = m[(i, j)];
                if a != 0.0 {
                    x += a * w1[j];
                    y += a * w2[j];
                }
            }
            [x, y]
        })
        .collect())
}
