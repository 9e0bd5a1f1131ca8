//! The characteristic map on a Catmull-Clark boundary, corner or crease
//! neighbourhood, certified regular and injective (math doc section 18.4).
//!
//! **The grid.** Around the vertex every other vertex is regular, so the
//! neighbourhood of radius `r` is `v`, the points `L_i(d)` at distance
//! `d = 1..r` on every edge line `i` at the vertex, and per quad `j` the
//! points `(a, b)`, `a, b = 1..r`, of the quadrant between lines `j` (the
//! `a` axis) and `j + 1` (the `b` axis) ([`Grid`]). At radius 1 this is the
//! local matrix's neighbourhood in its order (`v, e_i, f_j`). The rules
//! ([`refinement_matrix`]): those of [`SectorConfig::local_matrix`] at the
//! vertex and its edges, the crease rule `(1/8, 3/4, 1/8)` and the midpoint
//! on the sharp lines, Catmull-Clark's regular rules everywhere else. A
//! level-1 point at distance `<= 2 r - 1` needs level-0 points at distance
//! `<= r` only, so radius `r >= 2` is closed under one step and radius 3
//! refines to radius 5.
//!
//! **The ring.** The level-1 cells `[a, a+1] x [b, b+1]` of a quad with
//! `a, b <= 3` and `max(a, b) >= 2` (12 per quad; the annulus between
//! level-0 distances 1 and 2) never need a rule at the vertex or on its
//! edges when refined, so each is the uniform bicubic B-spline patch of its
//! 4 x 4 window. Across a sharp line the window takes the linearly
//! extrapolated points `2 L - P` (the crease rules are the B-spline rules on
//! that extension). The windows are linear in the radius-3 eigenvectors
//! (the rows of [`window_matrix`]).
//!
//! **The certificate.** An orthonormal basis of the subdominant invariant
//! subspace of the radius-3 matrix with Stewart's error bound
//! ([`PlanarBasis`]); the Bezier Jacobian test of the interior rings
//! ([`check_bezier_patches`]) on the ring; then injectivity:
//!
//! * crease (a closed ring): the outer boundary winds once around the
//!   origin, as at interior points;
//! * boundary and corner (an open ring): each sharp line's eigenvector
//!   entries are linear (the eigenvalue `1/2` of the cubic B-spline curve) or
//!   zero, so the lines map onto two rays from the origin; the outer arc is
//!   **star-shaped** (`det(gamma, gamma') > 0`, certified on Bezier hulls)
//!   and sweeps a certified angle `Theta < 2 pi`. Then the image of the
//!   boundary of the neighbourhood is a Jordan curve and a regular map is
//!   one-to-one onto the sector it bounds (degree argument). A sweep
//!   `Theta > 2 pi` proves a double cover (not injective).

use super::{SectorConfig, VertexKind};
use crate::bezier::{BezierCurve, PlanarPatch, TensorBezier};
use crate::charmap::regularity::{check_bezier_patches, gamma, RegularityVerdict};
use crate::charmap::winding::{swept_angle, winding_number, HullCurve};
use crate::charmap::{Eigenstructure, PlanarBasis};
use crate::error::{Error, Result};
use crate::mesh::sharp::rules::SdcScheme;
use crate::schemes::catmull_clark::ring::{bicubic_bezier, Window};
use crate::schemes::loop_subdivision::tri_bezier::{regular_patch, PlanarTri, REGULAR_NET};
use crate::spectral::{Subdominant, SubdominantClass};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;
use std::fmt;

/// How far a classifier's double-eigenvalue candidate may lie from `1/2`
/// for the structural certificate of [`half_is_semisimple`](super::analysis::half_is_semisimple) to speak about
/// it: the candidate is the mean of two computed eigenvalues whose error
/// radii (`kappa * eta`, about `1e-14` for these well-conditioned matrices
/// of dimension below a few hundred) the classifier has already found
/// consistent with equality, so a candidate for the exact eigenvalue `1/2`
/// lies within `1e-12` of it, and a candidate farther than `1e-9` is some
/// other double eigenvalue (the closed-form spectrum has no other eigenvalue
/// within `1e-9` of `1/2` except at the configurations where one equals it
/// exactly: math doc section 18.3).
pub const HALF_MATCH_TOL: f64 = 1e-9;

/// What is certified about the characteristic map on the sector(s).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SectorCharmapVerdict {
    /// Not injective: neither subdominant eigenvalue is an eigenvalue of the
    /// sharp-edge block, so the invariant subspace vanishes on `v` and the
    /// sharp edges' neighbours, and the map sends the limit curves of the
    /// sharp edges (which depend on those points only) to the origin.
    BoundaryCollapses,
    /// No characteristic map: the class is not standard, real_distinct or
    /// complex_pair.
    NoCharacteristicMap,
    /// Neither certified nor refuted (the reason says why).
    Indeterminate,
    /// Standard eigenstructure, regular and one-to-one onto a sector (or
    /// around the vertex at a crease): C1 (math doc section 18.4).
    C1Standard,
    /// Real distinct subdominant eigenvalues, regular and one-to-one:
    /// tangent-plane continuous (never "C1" for a non-standard structure).
    TangentPlaneContinuous,
    /// The Jacobian changes sign on the ring (a witness point).
    NotRegular,
    /// Regular, but the neighbourhood is covered more than once.
    NotInjective,
}

impl SectorCharmapVerdict {
    /// The snake_case name.
    pub fn as_str(&self) -> &'static str {
        match self {
            SectorCharmapVerdict::BoundaryCollapses => "boundary_collapses",
            SectorCharmapVerdict::NoCharacteristicMap => "no_charmap",
            SectorCharmapVerdict::Indeterminate => "indeterminate",
            SectorCharmapVerdict::C1Standard => "c1",
            SectorCharmapVerdict::TangentPlaneContinuous => "tpc_real_distinct",
            SectorCharmapVerdict::NotRegular => "not_regular",
            SectorCharmapVerdict::NotInjective => "not_injective",
        }
    }
}

/// Radius of the neighbourhood whose eigenvectors are computed (the ring's
/// windows reach level-1 distance 5 = `2 * 3 - 1`).
pub const EIGEN_RADIUS: usize = 3;

/// Radius (in level-1 units) of the points the ring's windows use.
pub const RING_RADIUS: usize = 5;

/// Largest face count whose characteristic map is certified: the radius-3
/// matrix has `12 K + 4` rows and Stewart's bound takes the singular values
/// of a Kronecker matrix of twice that size (`K = 32`: 776 x 776, well under
/// a second); above it the verdict is `indeterminate` (not attempted).
pub const MAX_CHARMAP_FACES: usize = 32;

/// Maximum de Casteljau depth of the star-shape test per outer-arc curve.
pub const STAR_MAX_DEPTH: u32 = 24;

/// Margin (radians) between the certified sweep of the outer arc and
/// `2 pi` (one turn): within it the verdict is `indeterminate`. The
/// certified sweep is exact up to the winding module's per-piece angle
/// uncertainty (about `1e-9` rad per piece at the error bounds seen here);
/// `1e-6` leaves three orders of magnitude.
pub const SWEEP_MARGIN: f64 = 1e-6;

/// The points of a sector neighbourhood of radius `r` (module docs).
#[derive(Clone, Copy, Debug)]
pub struct Grid<'a> {
    c: &'a SectorConfig,
    r: usize,
}

impl<'a> Grid<'a> {
    /// The grid of radius `r >= 1`.
    pub fn new(c: &'a SectorConfig, r: usize) -> Self {
        Self { c, r: r.max(1) }
    }

    /// Number of points: `1 + lines r + faces w`, with `w = r^2` points
    /// `(a, b)`, `a, b = 1..r`, per quad (Catmull-Clark) and
    /// `w = r (r - 1)/2` points `a, b >= 1`, `a + b <= r`, per triangle (Loop).
    pub fn dim(&self) -> usize {
        1 + self.c.edge_count() * self.r + self.c.face_count() * self.wedge_points()
    }

    /// The points strictly inside one face's wedge.
    fn wedge_points(&self) -> usize {
        match self.c.scheme() {
            SdcScheme::CatmullClark => self.r * self.r,
            SdcScheme::Loop => self.r * (self.r - 1) / 2,
        }
    }

    /// The offset of the inner point `(a, b)` (`a, b >= 1`) within its wedge.
    fn wedge_offset(&self, a: usize, b: usize) -> usize {
        match self.c.scheme() {
            SdcScheme::CatmullClark => (a - 1) * self.r + b - 1,
            // rows a = 1, 2, .. hold r - a points each
            SdcScheme::Loop => (a - 1) * self.r - (a - 1) * a / 2 + b - 1,
        }
    }

    /// The index of point `(a, b)` of face `j` (`a, b <= r`, Loop also
    /// `a + b <= r`): `v` at `(0, 0)`, line `j` at `(a, 0)`, line `j + 1` at
    /// `(0, b)`. A Loop face's lattice has the edges `(1, 0)`, `(0, 1)` and
    /// `(-1, 1)`.
    pub fn pos(&self, j: usize, a: usize, b: usize) -> usize {
        let (nl, nf, r) = (self.c.edge_count(), self.c.face_count(), self.r);
        let j = j % nf;
        match (a, b) {
            (0, 0) => 0,
            (a, 0) => 1 + j * r + a - 1,
            (0, b) => 1 + ((j + 1) % nl) * r + b - 1,
            (a, b) => 1 + nl * r + j * self.wedge_points() + self.wedge_offset(a, b),
        }
    }

    /// A Loop lattice point of face `j` with one coordinate possibly `-1`:
    /// `(a, -1)` is point `(1, a - 1)` of face `j - 1` and `(-1, b)` point
    /// `(b - 1, 1)` of face `j + 1` (the lattice continues across a smooth
    /// edge line).
    fn loop_point(&self, j: usize, a: i64, b: i64) -> usize {
        let nf = self.c.face_count();
        match (a, b) {
            (a, -1) => self.pos(j + nf - 1, 1, (a - 1) as usize),
            (-1, b) => self.pos(j + 1, (b - 1) as usize, 1),
            (a, b) => self.pos(j, a as usize, b as usize),
        }
    }

    /// Point `d` of line `i` (`d = 0` is `v`).
    fn line(&self, i: usize, d: usize) -> usize {
        if d == 0 {
            0
        } else {
            1 + i * self.r + d - 1
        }
    }
}

/// The matrix taking the level-0 points of radius `r0` to the level-1
/// points of radius `r1` (module docs; `1 <= r1 <= 2 r0 - 1`; rows and
/// columns in [`Grid`] order). Catmull-Clark only. At `r0 = r1 = 1` it is
/// [`SectorConfig::local_matrix`].
pub fn refinement_matrix(c: &SectorConfig, r0: usize, r1: usize) -> Result<DMatrix<f64>> {
    if r0 == 0 || r1 == 0 || r1 + 1 > 2 * r0 {
        return Err(Error::InvalidParameter {
            name: "radius",
            value: format!("{r0} -> {r1}"),
            reason: "a level-1 radius r1 needs 1 <= r1 <= 2 r0 - 1",
        });
    }
    let g0 = Grid::new(c, r0);
    let g1 = Grid::new(c, r1);
    let (nl, nf) = (c.edge_count(), c.face_count());
    let mut m = DMatrix::<f64>::zeros(g1.dim(), g0.dim());
    let mut add = |row: usize, col: usize, w: f64| m[(row, col)] += w;
    let [sa, sb] = c.sharp_edges();
    match c.kind() {
        VertexKind::Corner => add(0, 0, 1.0),
        _ => {
            add(0, 0, 0.75);
            add(0, g0.line(sa, 1), 0.125);
            add(0, g0.line(sb, 1), 0.125);
        }
    }
    if c.scheme() == SdcScheme::Loop {
        loop_rows(c, &g0, &g1, &mut add);
        return Ok(m);
    }
    for i in 0..nl {
        let sector = c.sector_of_edge(i);
        // quad i has line i as its a axis, quad i - 1 as its b axis
        let qi = |x: usize, y: usize| g0.pos(i, x, y);
        let qp = |x: usize, y: usize| g0.pos(i + nf - 1, y, x);
        for big_d in 1..=r1 {
            let row = g1.line(i, big_d);
            let d = big_d / 2;
            match (sector, big_d % 2) {
                (None, 0) => {
                    add(row, g0.line(i, d - 1), 0.125);
                    add(row, g0.line(i, d), 0.75);
                    add(row, g0.line(i, d + 1), 0.125);
                }
                (None, _) => {
                    add(row, g0.line(i, d), 0.5);
                    add(row, g0.line(i, d + 1), 0.5);
                }
                (Some(_), 0) => {
                    add(row, g0.line(i, d), 9.0 / 16.0);
                    for p in [g0.line(i, d - 1), g0.line(i, d + 1), qi(d, 1), qp(d, 1)] {
                        add(row, p, 3.0 / 32.0);
                    }
                    for p in [qi(d - 1, 1), qi(d + 1, 1), qp(d - 1, 1), qp(d + 1, 1)] {
                        add(row, p, 1.0 / 64.0);
                    }
                }
                (Some(s), _) => {
                    let (w0, w1) = if d == 0 {
                        let g = c.gamma(s);
                        (0.75 - g, g)
                    } else {
                        (0.375, 0.375)
                    };
                    add(row, g0.line(i, d), w0);
                    add(row, g0.line(i, d + 1), w1);
                    for p in [qi(d, 1), qi(d + 1, 1), qp(d, 1), qp(d + 1, 1)] {
                        add(row, p, 0.0625);
                    }
                }
            }
        }
    }
    for j in 0..nf {
        let q = |x: usize, y: usize| g0.pos(j, x, y);
        for big_a in 1..=r1 {
            for big_b in 1..=r1 {
                let row = g1.pos(j, big_a, big_b);
                let (a, b) = (big_a / 2, big_b / 2);
                match (big_a % 2, big_b % 2) {
                    (0, 0) => {
                        add(row, q(a, b), 9.0 / 16.0);
                        for p in [q(a - 1, b), q(a + 1, b), q(a, b - 1), q(a, b + 1)] {
                            add(row, p, 3.0 / 32.0);
                        }
                        for p in [
                            q(a - 1, b - 1),
                            q(a + 1, b - 1),
                            q(a - 1, b + 1),
                            q(a + 1, b + 1),
                        ] {
                            add(row, p, 1.0 / 64.0);
                        }
                    }
                    (1, 0) => {
                        add(row, q(a, b), 0.375);
                        add(row, q(a + 1, b), 0.375);
                        for p in [q(a, b - 1), q(a, b + 1), q(a + 1, b - 1), q(a + 1, b + 1)] {
                            add(row, p, 0.0625);
                        }
                    }
                    (0, _) => {
                        add(row, q(a, b), 0.375);
                        add(row, q(a, b + 1), 0.375);
                        for p in [q(a - 1, b), q(a + 1, b), q(a - 1, b + 1), q(a + 1, b + 1)] {
                            add(row, p, 0.0625);
                        }
                    }
                    _ => {
                        for p in [q(a, b), q(a + 1, b), q(a, b + 1), q(a + 1, b + 1)] {
                            add(row, p, 0.25);
                        }
                    }
                }
            }
        }
    }
    Ok(m)
}

/// The Loop rows of [`refinement_matrix`] below the vertex's: on a sharp
/// line the crease rule and the midpoint; on a smooth line and inside a
/// face Loop's regular rules (vertex `5/8` and `1/16` per neighbour, edge
/// `3/8` per end and `1/8` per opposite vertex), except the edge at the
/// vertex, whose ends get `3/4 - g` and `g` ([`SectorConfig::gamma`]). In
/// face `j`'s lattice the edge `(a, b)-(a+1, b)` has the opposite vertices
/// `(a, b+1)` and `(a+1, b-1)`, the edge `(a, b)-(a, b+1)` the vertices
/// `(a+1, b)` and `(a-1, b+1)`, the edge `(a+1, b)-(a, b+1)` the vertices
/// `(a, b)` and `(a+1, b+1)`; a level-1 point at distance `D` needs level-0
/// points at distance `<= (D + 1)/2`, so `r1 <= 2 r0 - 1` suffices, as for
/// Catmull-Clark.
fn loop_rows(c: &SectorConfig, g0: &Grid, g1: &Grid, add: &mut impl FnMut(usize, usize, f64)) {
    let (nl, nf, r1) = (c.edge_count(), c.face_count(), g1.r);
    let p = |j: usize, a: i64, b: i64| g0.loop_point(j, a, b);
    for i in 0..nl {
        let sector = c.sector_of_edge(i);
        for big_d in 1..=r1 {
            let row = g1.line(i, big_d);
            let d = (big_d / 2) as i64;
            match (sector, big_d % 2) {
                (None, 0) => {
                    add(row, g0.line(i, d as usize - 1), 0.125);
                    add(row, g0.line(i, d as usize), 0.75);
                    add(row, g0.line(i, d as usize + 1), 0.125);
                }
                (None, _) => {
                    add(row, g0.line(i, d as usize), 0.5);
                    add(row, g0.line(i, d as usize + 1), 0.5);
                }
                // line i is the a axis of face i (a smooth line has face i - 1 too)
                (Some(_), 0) => {
                    add(row, p(i, d, 0), 0.625);
                    for q in [
                        p(i, d - 1, 0),
                        p(i, d + 1, 0),
                        p(i, d, 1),
                        p(i, d - 1, 1),
                        p(i, d + 1, -1),
                        p(i, d, -1),
                    ] {
                        add(row, q, 0.0625);
                    }
                }
                (Some(s), _) => {
                    let (w0, w1) = if d == 0 {
                        let g = c.gamma(s);
                        (0.75 - g, g)
                    } else {
                        (0.375, 0.375)
                    };
                    add(row, p(i, d, 0), w0);
                    add(row, p(i, d + 1, 0), w1);
                    add(row, p(i, d, 1), 0.125);
                    add(row, p(i, d + 1, -1), 0.125);
                }
            }
        }
    }
    for j in 0..nf {
        for big_a in 1..r1 {
            for big_b in 1..=r1 - big_a {
                let row = g1.pos(j, big_a, big_b);
                let (a, b) = ((big_a / 2) as i64, (big_b / 2) as i64);
                let mut put = |pts: &[(i64, i64)], w: f64| {
                    for &(x, y) in pts {
                        add(row, p(j, x, y), w);
                    }
                };
                match (big_a % 2, big_b % 2) {
                    (0, 0) => {
                        put(&[(a, b)], 0.625);
                        put(
                            &[
                                (a - 1, b),
                                (a + 1, b),
                                (a, b - 1),
                                (a, b + 1),
                                (a + 1, b - 1),
                                (a - 1, b + 1),
                            ],
                            0.0625,
                        );
                    }
                    (1, 0) => {
                        put(&[(a, b), (a + 1, b)], 0.375);
                        put(&[(a, b + 1), (a + 1, b - 1)], 0.125);
                    }
                    (0, _) => {
                        put(&[(a, b), (a, b + 1)], 0.375);
                        put(&[(a + 1, b), (a - 1, b + 1)], 0.125);
                    }
                    _ => {
                        put(&[(a + 1, b), (a, b + 1)], 0.375);
                        put(&[(a, b), (a + 1, b + 1)], 0.125);
                    }
                }
            }
        }
    }
}

/// The shape of a ring cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CellShape {
    /// A Catmull-Clark cell `[a, a+1] x [b, b+1]` (a bicubic patch).
    Square,
    /// A Loop triangle `(a, b), (a+1, b), (a, b+1)` (a quartic patch).
    Up,
    /// A Loop triangle `(a+1, b+1), (a, b+1), (a+1, b)` (a quartic patch).
    Down,
}

/// A cell of the sector's ring: face `face`, level-1 cell `[a, a+1] x [b,
/// b+1]` of a quad or the level-1 triangle at `(a, b)` of a Loop face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct SectorCell {
    /// The face (`v, e_j, f_j, e_(j+1)` or `v, e_j, e_(j+1)`).
    pub face: usize,
    /// Cell offset along the face's first edge line (level-1 units).
    pub a: usize,
    /// Cell offset along the face's second edge line.
    pub b: usize,
    /// Square, or which Loop triangle.
    pub shape: CellShape,
}

impl fmt::Display for SectorCell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.shape {
            CellShape::Square => write!(f, "cell ({}, {}) of quad {}", self.a, self.b, self.face),
            CellShape::Up => write!(
                f,
                "triangle (a, b) + (0,0), (1,0), (0,1) at (a, b) = ({}, {}) of face {}",
                self.a, self.b, self.face
            ),
            CellShape::Down => write!(
                f,
                "triangle (a, b) + (1,1), (0,1), (1,0) at (a, b) = ({}, {}) of face {}",
                self.a, self.b, self.face
            ),
        }
    }
}

/// The ring's cells in order, 12 per face. Catmull-Clark: quad by quad, `a`
/// then `b`, the cells with `a, b <= 3` and `max(a, b) >= 2`. Loop: face by
/// face, the level-1 triangles whose corners lie at level-1 distances 2 to 4
/// (`a + b` in the face's lattice): the up triangles with `a + b = 2, 3`
/// (in order of `a + b`, then decreasing `a`) and the down triangles with
/// `a + b = 1, 2`. Their corners are at distance `>= 2`, so no edge at a
/// corner ends at the vertex and refining them never uses a rule of the
/// vertex or of its edges (math doc 18.4).
pub fn ring_cells(c: &SectorConfig) -> Vec<SectorCell> {
    let mut out = Vec::new();
    for face in 0..c.face_count() {
        match c.scheme() {
            SdcScheme::CatmullClark => {
                for a in 0..4 {
                    for b in 0..4 {
                        if a.max(b) >= 2 {
                            out.push(SectorCell {
                                face,
                                a,
                                b,
                                shape: CellShape::Square,
                            });
                        }
                    }
                }
            }
            SdcScheme::Loop => {
                for (shape, sums) in [(CellShape::Up, [2, 3]), (CellShape::Down, [1, 2])] {
                    for sum in sums {
                        for a in (0..=sum).rev() {
                            out.push(SectorCell {
                                face,
                                a,
                                b: sum - a,
                                shape,
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// The 12-point net of a Loop ring triangle in its face's lattice, ordered
/// as [`REGULAR_NET`]: an up triangle at `(a, b)` is the translate, a down
/// triangle `(a+1, b+1) - o` (a rotation by `pi`, which keeps the
/// orientation, as the middle patch of the interior ring).
fn loop_net(cell: &SectorCell) -> [(i64, i64); 12] {
    let (a, b) = (cell.a as i64, cell.b as i64);
    REGULAR_NET.map(|(x, y)| {
        let (x, y) = (x as i64, y as i64);
        match cell.shape {
            CellShape::Down => (a + 1 - x, b + 1 - y),
            _ => (a + x, b + y),
        }
    })
}

/// The window rows of a Loop ring: row `12 k + m` is net point `m` of cell
/// `k` of [`ring_cells`] over the radius-3 points. Across a smooth line the
/// lattice continues into the next face; across a sharp line the net takes
/// the **point reflection in the edge's midpoint**: the point `(a, -1)`
/// beyond the edge `L(a-1) L(a)` of line `j` is `L(a-1) + L(a) - (a-1, 1)`
/// (and `(-1, b)` beyond line `j + 1` is `L(b-1) + L(b) - (1, b-1)`). With
/// these points Loop's regular rules reproduce the crease rules on the
/// line: the vertex rule gives `5/8 L + 1/16 (L_- + L_+ + P_1 + P_2 + G_1 +
/// G_2) = 3/4 L + 1/8 (L_- + L_+)`, the boundary edge's rule
/// `3/8 (L + L_+) + 1/8 (P + G) = (L + L_+)/2`, and the reflected points of the refined
/// lattice are the edge rule's values across the line (math doc 18.4).
fn loop_window_matrix(c: &SectorConfig) -> Result<DMatrix<f64>> {
    let ext = refinement_matrix(c, EIGEN_RADIUS, RING_RADIUS)?;
    let g1 = Grid::new(c, RING_RADIUS);
    let nl = c.edge_count();
    let cells = ring_cells(c);
    let row = |j: usize, a: i64, b: i64| -> Vec<f64> {
        ext.row(g1.loop_point(j, a, b)).iter().copied().collect()
    };
    let reflect = |x: Vec<f64>, y: Vec<f64>, z: Vec<f64>| -> Vec<f64> {
        x.iter()
            .zip(&y)
            .zip(&z)
            .map(|((p, q), r)| p + q - r)
            .collect()
    };
    let point = |j: usize, a: i64, b: i64| -> Vec<f64> {
        match (a, b) {
            (a, -1) if c.sector_of_edge(j).is_none() => {
                reflect(row(j, a - 1, 0), row(j, a, 0), row(j, a - 1, 1))
            }
            (-1, b) if c.sector_of_edge((j + 1) % nl).is_none() => {
                reflect(row(j, 0, b - 1), row(j, 0, b), row(j, 1, b - 1))
            }
            (a, b) => row(j, a, b),
        }
    };
    let mut w = DMatrix::<f64>::zeros(12 * cells.len(), ext.ncols());
    for (k, cell) in cells.iter().enumerate() {
        for (m, (a, b)) in loop_net(cell).into_iter().enumerate() {
            for (col, x) in point(cell.face, a, b).into_iter().enumerate() {
                w[(12 * k + m, col)] = x;
            }
        }
    }
    Ok(w)
}

/// The window rows: row `16 k + 4 p + q` gives point `(a - 1 + p, b - 1 + q)`
/// of cell `k` of [`ring_cells`] as a combination of the radius-3 points
/// (the radius-5 level-1 points of [`refinement_matrix`], extrapolated
/// across sharp lines; module docs).
pub fn window_matrix(c: &SectorConfig) -> Result<DMatrix<f64>> {
    if c.scheme() == SdcScheme::Loop {
        return loop_window_matrix(c);
    }
    let ext = refinement_matrix(c, EIGEN_RADIUS, RING_RADIUS)?;
    let g1 = Grid::new(c, RING_RADIUS);
    let nf = c.face_count();
    let cells = ring_cells(c);
    let cols = ext.ncols();
    let row_of = |j: usize, a: usize, b: usize| -> Vec<f64> {
        ext.row(g1.pos(j, a, b)).iter().copied().collect()
    };
    let combo = |x: Vec<f64>, y: Vec<f64>| -> Vec<f64> {
        x.iter().zip(&y).map(|(p, q)| 2.0 * p - q).collect()
    };
    // point (aa, bb) of quad j, aa or bb possibly -1
    let point = |j: usize, aa: i64, bb: i64| -> Vec<f64> {
        match (aa, bb) {
            (a, -1) => {
                let a = a as usize;
                if c.sector_of_edge(j).is_none() {
                    combo(row_of(j, a, 0), row_of(j, a, 1))
                } else {
                    row_of(j + nf - 1, 1, a)
                }
            }
            (-1, b) => {
                let b = b as usize;
                if c.sector_of_edge((j + 1) % c.edge_count()).is_none() {
                    combo(row_of(j, 0, b), row_of(j, 1, b))
                } else {
                    row_of(j + 1, b, 1)
                }
            }
            (a, b) => row_of(j, a as usize, b as usize),
        }
    };
    let mut w = DMatrix::<f64>::zeros(16 * cells.len(), cols);
    for (k, cell) in cells.iter().enumerate() {
        for p in 0..4 {
            for q in 0..4 {
                let v = point(
                    cell.face,
                    cell.a as i64 - 1 + p as i64,
                    cell.b as i64 - 1 + q as i64,
                );
                for (col, x) in v.into_iter().enumerate() {
                    w[(16 * k + 4 * p + q, col)] = x;
                }
            }
        }
    }
    Ok(w)
}

/// The right null vectors of `S - lambda I` (`count` of them, smallest
/// singular values first).
pub(super) fn null_vectors(s: &DMatrix<f64>, lambda: f64, count: usize) -> Vec<Vec<f64>> {
    let n = s.nrows();
    let m = s - DMatrix::<f64>::identity(n, n) * lambda;
    let svd = m.svd(false, true);
    let Some(vt) = svd.v_t else {
        return Vec::new();
    };
    let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
    order.sort_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]));
    order
        .into_iter()
        .take(count)
        .map(|k| vt.row(k).iter().copied().collect())
        .collect()
}

/// The certified result on the sector (math doc section 18.4).
#[derive(Clone, Debug, PartialEq)]
pub struct SectorMapCheck {
    /// The verdict.
    pub verdict: SectorCharmapVerdict,
    /// Why (one sentence).
    pub reason: String,
    /// The smallest Bezier coefficient of the oriented Jacobian relative to
    /// the largest (`None` before the regularity test).
    pub min_jacobian_coeff: Option<f64>,
    /// The error bound of the ring's control points (`None` before it is known).
    pub point_error: Option<f64>,
    /// The certified angle (degrees) swept by the outer arc of a boundary or
    /// corner ring, in the oriented orthonormal basis (a linear change of
    /// basis changes it, but not whether it is below, at or above 180).
    pub swept_degrees: Option<f64>,
}

impl SectorMapCheck {
    fn undecided(reason: String) -> Self {
        Self {
            verdict: SectorCharmapVerdict::Indeterminate,
            reason,
            min_jacobian_coeff: None,
            point_error: None,
            swept_degrees: None,
        }
    }
}

/// Is `det(gamma, gamma') > 0` on the cubic Bezier curve? The curve lies in
/// the hull of its points `b_i` and its derivative in the cone of the
/// differences `d_k = b_(k+1) - b_k`, so `det(b_i, d_k) > E` for all pairs
/// certifies it. `E` **\[derived\]**: points off by `e` (`eps` plus the
/// splits' rounding), differences by `2 e`, so a determinant of magnitudes
/// `pm`, `dm` is off by at most `2 (2 e pm + e dm + 2 e^2)` plus its own
/// rounding `2 gamma_3 pm dm`. A start or end value below `-E` is a
/// witness (the curve's end points and end tangents are `b_0`, `b_3` and
/// multiples of `d_0`, `d_2`).
fn star_shaped(c: &BezierCurve, eps: f64, split_err: f64, depth: u32) -> Option<bool> {
    let p = &c.points;
    let e = eps + split_err * depth as f64;
    let d: Vec<[f64; 2]> = p
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .collect();
    let mag = |v: &[[f64; 2]]| {
        v.iter()
            .fold(0.0f64, |m, x| m.max(x[0].abs()).max(x[1].abs()))
    };
    let (pm, dm) = (mag(p), mag(&d));
    let bound = 2.0 * (2.0 * e * pm + e * dm + 2.0 * e * e) + 2.0 * gamma(3) * pm * dm;
    let det = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let lo = p
        .iter()
        .flat_map(|a| d.iter().map(move |b| det(*a, *b)))
        .fold(f64::INFINITY, f64::min);
    if lo > bound {
        return Some(true);
    }
    let (first, last) = (p.len() - 1, d.len() - 1);
    if det(p[0], d[0]) < -bound || det(p[first], d[last]) < -bound {
        return Some(false);
    }
    if depth >= STAR_MAX_DEPTH || bound.is_nan() {
        return None;
    }
    let (l, r) = c.split(0.5);
    match star_shaped(&l, eps, split_err, depth + 1) {
        Some(false) => Some(false),
        left => match (left, star_shaped(&r, eps, split_err, depth + 1)) {
            (_, Some(false)) => Some(false),
            (Some(true), Some(true)) => Some(true),
            _ => None,
        },
    }
}

/// Certifies the characteristic map of a Catmull-Clark sector whose
/// subdominant pair `sub` (class standard or real_distinct) is not
/// collapsed on the sharp lines; `on_sharp` says which of `lambda_1,
/// lambda_2` are eigenvalues of the sharp-edge block (module docs).
pub fn certify(c: &SectorConfig, sub: &Subdominant, on_sharp: [Option<bool>; 2]) -> SectorMapCheck {
    if c.face_count() > MAX_CHARMAP_FACES {
        return SectorMapCheck::undecided(format!(
            "not attempted above {MAX_CHARMAP_FACES} faces (the certificate's cost grows as the cube of the neighbourhood)"
        ));
    }
    let structure = match sub.class {
        SubdominantClass::Standard => Eigenstructure::Standard,
        SubdominantClass::RealDistinct => Eigenstructure::RealDistinct,
        _ => {
            return SectorMapCheck::undecided(format!(
                "the sector certificate is built for real subdominant eigenvalues (class {})",
                sub.class.name()
            ))
        }
    };
    let open = c.kind() != VertexKind::Crease;
    if open {
        for (k, lam) in [sub.lambda1, sub.lambda2].iter().enumerate() {
            if on_sharp[k] == Some(true) && (lam.re - 0.5).abs() > HALF_MATCH_TOL {
                return SectorMapCheck::undecided(format!(
                    "lambda{} = {} belongs to the sharp-edge block but is not 1/2, so the sharp lines' images are not known to be rays",
                    k + 1,
                    lam.re
                ));
            }
        }
    }
    match certify_ring(c, sub, structure, open) {
        Ok(r) => r,
        Err(e) => SectorMapCheck::undecided(format!("the ring could not be built: {e}")),
    }
}

/// The Catmull-Clark ring (12 bicubic patches per quad, from the windows
/// `x`, `y` of [`window_matrix`]): its regularity and its outer arc (per
/// quad the cells' outer edges from line `j` to line `j + 1`, unoriented).
fn cc_ring(
    c: &SectorConfig,
    cells: &[SectorCell],
    x: &[f64],
    y: &[f64],
    delta: f64,
) -> Result<(
    crate::charmap::regularity::Regularity<SectorCell>,
    Vec<BezierCurve>,
)> {
    let patches: Vec<(SectorCell, PlanarPatch)> = cells
        .iter()
        .enumerate()
        .map(|(k, cell)| {
            let win: Window = std::array::from_fn(|p| {
                std::array::from_fn(|q| [x[16 * k + 4 * p + q], y[16 * k + 4 * p + q]])
            });
            let coord = |i: usize| {
                let b = bicubic_bezier(&win, i);
                TensorBezier::from_fn(3, 3, |a, bb| b[a][bb])
            };
            (
                *cell,
                PlanarPatch {
                    x: coord(0),
                    y: coord(1),
                },
            )
        })
        .collect();
    let refs: Vec<(SectorCell, &PlanarPatch)> = patches.iter().map(|(i, p)| (*i, p)).collect();
    let reg = check_bezier_patches(&refs, delta)?;
    let index = |cell: SectorCell| cells.iter().position(|x| *x == cell);
    let mut arc: Vec<BezierCurve> = Vec::new();
    for face in 0..c.face_count() {
        let pts = |a: usize, b: usize, ij: &dyn Fn(usize) -> (usize, usize)| {
            let shape = CellShape::Square;
            let k = index(SectorCell { face, a, b, shape }).unwrap_or(0);
            let p = &patches[k].1;
            BezierCurve::new(
                (0..4)
                    .map(|t| {
                        let (i, j) = ij(t);
                        [p.x.coeff(i, j), p.y.coeff(i, j)]
                    })
                    .collect(),
            )
        };
        for b in 0..4 {
            arc.push(pts(3, b, &|t| (3, t)));
        }
        for a in (0..4).rev() {
            arc.push(pts(a, 3, &|t| (3 - t, 3)));
        }
    }
    Ok((reg, arc))
}

/// The Loop ring (12 quartic triangular patches per face, the box splines
/// of the nets of [`window_matrix`]): its regularity (the triangular
/// Jacobian test of section 11) and its outer arc (per face the edges
/// `(a+1, b) -> (a, b+1)` of the up triangles with `a + b = 3`, from line
/// `j` to line `j + 1`, unoriented).
fn loop_ring(
    cells: &[SectorCell],
    x: &[f64],
    y: &[f64],
    delta: f64,
) -> Result<(
    crate::charmap::regularity::Regularity<SectorCell>,
    Vec<BezierCurve>,
)> {
    let patches: Vec<(SectorCell, PlanarTri)> = cells
        .iter()
        .enumerate()
        .map(|(k, cell)| {
            let net: [[f64; 2]; 12] = std::array::from_fn(|m| [x[12 * k + m], y[12 * k + m]]);
            (*cell, regular_patch(&net))
        })
        .collect();
    let refs: Vec<(SectorCell, &PlanarTri)> = patches.iter().map(|(i, p)| (*i, p)).collect();
    let reg = crate::charmap::loop_subdivision::check_tri_patches(&refs, delta)?;
    let mut arc = Vec::new();
    for (cell, p) in &patches {
        if cell.shape == CellShape::Up && cell.a + cell.b == 3 {
            arc.push(p.boundary(1, 2)?);
        }
    }
    Ok((reg, arc))
}

fn certify_ring(
    c: &SectorConfig,
    sub: &Subdominant,
    structure: Eigenstructure,
    open: bool,
) -> Result<SectorMapCheck> {
    let s = refinement_matrix(c, EIGEN_RADIUS, EIGEN_RADIUS)?;
    let (l1, l2) = (sub.lambda1.re, sub.lambda2.re);
    let vecs = match structure {
        Eigenstructure::Standard => null_vectors(&s, l1, 2),
        _ => {
            let mut v = null_vectors(&s, l1, 1);
            v.extend(null_vectors(&s, l2, 1));
            v
        }
    };
    if vecs.len() != 2 {
        return Ok(SectorMapCheck::undecided(
            "no pair of null vectors from the singular value decomposition".to_owned(),
        ));
    }
    let gap = sub.gap.min(1.0 - sub.lambda1.norm());
    let lam = [Complex64::new(l1, 0.0), Complex64::new(l2, 0.0)];
    let basis = PlanarBasis::new(&s, structure, lam, &vecs[0], &vecs[1], gap)?;
    let wm = window_matrix(c)?;
    let delta = match c.scheme() {
        SdcScheme::CatmullClark => crate::charmap::catmull_clark::point_error(&wm, &basis, &[]),
        SdcScheme::Loop => crate::charmap::loop_subdivision::point_error(&wm, &basis),
    };
    if !delta.is_finite() {
        return Ok(SectorMapCheck::undecided(
            "the subdominant invariant subspace of the radius-3 neighbourhood is not certified (Stewart's separation hypothesis fails)".to_owned(),
        ));
    }
    let apply = |w: &[f64]| -> Vec<f64> {
        (&wm * nalgebra::DVector::from_column_slice(w))
            .iter()
            .copied()
            .collect()
    };
    let (x, y) = (apply(&basis.w1), apply(&basis.w2));
    let cells = ring_cells(c);
    let (reg, mut arc) = match c.scheme() {
        SdcScheme::CatmullClark => cc_ring(c, &cells, &x, &y, delta)?,
        SdcScheme::Loop => loop_ring(&cells, &x, &y, delta)?,
    };
    let mut out = SectorMapCheck {
        verdict: SectorCharmapVerdict::Indeterminate,
        reason: String::new(),
        min_jacobian_coeff: Some(reg.min_coeff),
        point_error: Some(delta),
        swept_degrees: None,
    };
    match reg.verdict {
        RegularityVerdict::NotRegular => {
            out.verdict = SectorCharmapVerdict::NotRegular;
            out.reason = match reg.witness {
                Some((p, v)) => format!(
                    "the Jacobian changes sign: {} at (s, t) = ({:.4}, {:.4}) has relative value {v:.3e}",
                    p.patch, p.s, p.t
                ),
                None => "the Jacobian changes sign".to_owned(),
            };
            return Ok(out);
        }
        RegularityVerdict::Indeterminate => {
            out.reason = format!(
                "Jacobian sign not certified (min coefficient {:.3e}, error bound {:.3e}, relative)",
                reg.min_coeff, reg.relative_error_bound
            );
            return Ok(out);
        }
        RegularityVerdict::Regular => {}
    }
    // the outer arc, oriented so that the Jacobian is positive
    if reg.orientation < 0 {
        for cu in &mut arc {
            for p in &mut cu.points {
                p[1] = -p[1];
            }
        }
    }
    let tpc_or_c1 = || match structure {
        Eigenstructure::Standard => SectorCharmapVerdict::C1Standard,
        _ => SectorCharmapVerdict::TangentPlaneContinuous,
    };
    if !open {
        return Ok(match winding_number(&arc, delta) {
            Some(1) => SectorMapCheck {
                verdict: tpc_or_c1(),
                reason: "regular, and the ring's outer boundary winds once around the limit point (as at interior points)".to_owned(),
                ..out
            },
            Some(w) => SectorMapCheck {
                verdict: SectorCharmapVerdict::NotInjective,
                reason: format!("regular, but the ring's outer boundary winds {w} times around the limit point"),
                ..out
            },
            None => SectorMapCheck {
                reason: "regular; the winding number of the outer boundary is not certified".to_owned(),
                ..out
            },
        });
    }
    let mut scale = 0.0f64;
    for cu in &arc {
        for p in &cu.points {
            scale = scale.max(p[0].abs()).max(p[1].abs());
        }
    }
    let mut star = Some(true);
    for cu in &arc {
        let split_err = cu.split_error(scale);
        match star_shaped(cu, delta, split_err, 0) {
            Some(true) => {}
            Some(false) => {
                star = Some(false);
                break;
            }
            None => star = None,
        }
    }
    match star {
        Some(false) => {
            out.reason = "regular, but the outer arc is not star-shaped around the limit point, so the injectivity certificate (section 18.4) does not apply".to_owned();
            return Ok(out);
        }
        None => {
            out.reason = "regular; whether the outer arc is star-shaped around the limit point is not certified".to_owned();
            return Ok(out);
        }
        Some(true) => {}
    }
    let Some(theta) = swept_angle(&arc, delta) else {
        out.reason =
            "regular and star-shaped; the angle swept by the outer arc is not certified".to_owned();
        return Ok(out);
    };
    out.swept_degrees = Some(theta.to_degrees());
    if theta < 2.0 * PI - SWEEP_MARGIN {
        let shape = if theta < PI - SWEEP_MARGIN {
            "a convex sector"
        } else if theta > PI + SWEEP_MARGIN {
            "a reflex sector"
        } else {
            "a half-plane (up to the sweep margin)"
        };
        out.verdict = tpc_or_c1();
        // a linear change of basis keeps a sector convex or reflex: compare
        // with the corner's angle
        let mismatch = match c.angle() {
            Some(t) if t > PI && theta < PI - SWEEP_MARGIN => {
                "; the corner angle is reflex but the image is convex, so the limit surface has a convex corner there (section 18.2)"
            }
            Some(t) if t < PI && theta > PI + SWEEP_MARGIN => {
                "; the corner angle is convex but the image is reflex (section 18.2)"
            }
            _ => "",
        };
        out.reason = format!(
            "regular, and one-to-one onto {shape}: the sharp lines map onto two rays and the star-shaped outer arc between them sweeps {:.6} degrees{mismatch}",
            theta.to_degrees()
        );
    } else if theta > 2.0 * PI + SWEEP_MARGIN {
        out.verdict = SectorCharmapVerdict::NotInjective;
        out.reason = format!(
            "regular, but the star-shaped outer arc sweeps {:.6} degrees (more than one turn): the sector is covered twice near the limit point",
            theta.to_degrees()
        );
    } else {
        out.reason = "regular; the outer arc sweeps one turn within the margin".to_owned();
    }
    Ok(out)
}
