//! The 2-ring of an extraordinary vertex in sector-grid form, its extraction
//! from a polygon list, random test nets, and the mixed subdivision (math doc
//! section 14.2).
//!
//! Sector `i` (`0 <= i < n`) is the quad `(v, e_i, f_i, e_{i+1})` of the mesh
//! around `v` and the three quads beyond it, written as a 3 x 3 grid of points
//! `S(i, a, b)`, `a, b = 0..=2`, with `a` along spoke `i` and `b` along spoke
//! `i + 1`:
//!
//! ```text
//! S(i, 0, 0) = v,  S(i, a, 0) = spoke i at distance a,  S(i, 0, b) = spoke i+1 at distance b
//! S(i, a, -1) = S(i - 1, 1, a),  S(i, -1, b) = S(i + 1, b, 1)   (the neighbouring sectors)
//! ```
//!
//! The ring has `6n + 1` points: `v`, two per spoke and four per sector.

use super::G2CapError;
use crate::rng::SplitMix64;
use std::collections::HashMap;

/// A point in space.
pub type Point = [f64; 3];

/// The `6n + 1` points of the 2-ring of a vertex of valence `n` (all quads,
/// every vertex of the 1-ring regular).
#[derive(Clone, Debug, PartialEq)]
pub struct TwoRing {
    center: Point,
    /// `spokes[k] = [spoke k at distance 1, at distance 2]`.
    spokes: Vec<[Point; 2]>,
    /// `inner[i][a - 1][b - 1] = S(i, a, b)` for `a, b` in `{1, 2}`.
    inner: Vec<[[Point; 2]; 2]>,
}

/// A 2-ring whose points satisfy `max |(p - c) x (q - c)| <= DEGENERATE_RTOL
/// max |p - c|^2` lies on one line through its centre `c` (or on one point):
/// it has no tangent plane and is refused as bad input. `1e-12` is far
/// above the rounding of the cross products (`~1e-16` relative) and far
/// below the spread of any net a mesh would give (a sector of opening angle
/// `2 pi / 16` has a relative cross product of about 0.4).
pub const DEGENERATE_RTOL: f64 = 1e-12;

/// Smallest valence the construction accepts.
pub const MIN_VALENCE: usize = 3;
/// Largest valence the construction accepts (the residual targets are
/// checked for `n = 3..=8`; up to this valence the dense solve stays below a
/// few milliseconds).
pub const MAX_VALENCE: usize = 16;

fn check_valence(n: usize) -> Result<(), G2CapError> {
    if (MIN_VALENCE..=MAX_VALENCE).contains(&n) {
        Ok(())
    } else {
        Err(G2CapError::Valence { valence: n })
    }
}

fn finite(p: &Point) -> bool {
    p.iter().all(|x| x.is_finite())
}

impl TwoRing {
    /// A ring from its points: the centre, `n` spokes (`[distance 1,
    /// distance 2]`) and `n` sectors (`inner[i][a - 1][b - 1] = S(i, a, b)`).
    pub fn new(
        center: Point,
        spokes: Vec<[Point; 2]>,
        inner: Vec<[[Point; 2]; 2]>,
    ) -> Result<Self, G2CapError> {
        let n = spokes.len();
        check_valence(n)?;
        if inner.len() != n {
            return Err(G2CapError::RingShape {
                spokes: n,
                sectors: inner.len(),
            });
        }
        let ring = TwoRing {
            center,
            spokes,
            inner,
        };
        if let Some(k) = ring.points().iter().position(|p| !finite(p)) {
            return Err(G2CapError::NonFinitePoint { index: k });
        }
        if !ring.spans_a_plane() {
            return Err(G2CapError::Degenerate { vertex: None });
        }
        Ok(ring)
    }

    /// Whether the points span a plane: some `|(p - c) x (q - c)|` exceeds
    /// [`DEGENERATE_RTOL`] times `max |p - c|^2` (`c` the centre), computed
    /// on the points scaled by a power of two so that nothing overflows.
    fn spans_a_plane(&self) -> bool {
        let pts = self.points();
        let m = pts
            .iter()
            .flat_map(|p| p.iter())
            .fold(0.0f64, |a, x| a.max(x.abs()));
        if m == 0.0 {
            return false;
        }
        let k = -(m.log2().floor() as i32);
        let f = |x: f64| x * 2f64.powi(k / 2) * 2f64.powi(k - k / 2);
        let c = self.center.map(f);
        let d: Vec<Point> = pts
            .iter()
            .map(|p| {
                let q = p.map(f);
                [q[0] - c[0], q[1] - c[1], q[2] - c[2]]
            })
            .collect();
        let r2 = d
            .iter()
            .map(|v| v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            .fold(0.0f64, f64::max);
        if r2 == 0.0 {
            return false;
        }
        let mut best = 0.0f64;
        for (i, a) in d.iter().enumerate() {
            for b in &d[..i] {
                let x = [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ];
                best = best.max((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt());
            }
        }
        best > DEGENERATE_RTOL * r2
    }

    /// The valence `n`.
    pub fn valence(&self) -> usize {
        self.spokes.len()
    }

    /// All `6n + 1` points: the centre, then spoke `k` at distances 1 and 2
    /// for `k = 0..n`, then sector `i`'s `S(i,1,1), S(i,1,2), S(i,2,1),
    /// S(i,2,2)` for `i = 0..n`.
    pub fn points(&self) -> Vec<Point> {
        let mut out = vec![self.center];
        for s in &self.spokes {
            out.extend_from_slice(s);
        }
        for q in &self.inner {
            out.extend([q[0][0], q[0][1], q[1][0], q[1][1]]);
        }
        out
    }

    /// The ring with every point mapped by `f` (for invariance checks).
    pub fn map(&self, f: impl Fn(&Point) -> Point) -> TwoRing {
        TwoRing {
            center: f(&self.center),
            spokes: self.spokes.iter().map(|s| [f(&s[0]), f(&s[1])]).collect(),
            inner: self
                .inner
                .iter()
                .map(|q| [[f(&q[0][0]), f(&q[0][1])], [f(&q[1][0]), f(&q[1][1])]])
                .collect(),
        }
    }

    /// `S(i, a, b)` for `a, b` in `-1..=2` (not both negative; see the module
    /// documentation for the neighbouring sectors).
    pub fn point(&self, i: usize, a: i32, b: i32) -> Point {
        let n = self.valence();
        let i = i % n;
        if b < 0 {
            return self.point(i + n - 1, 1, a);
        }
        if a < 0 {
            return self.point(i + 1, b, 1);
        }
        match (a, b) {
            (0, 0) => self.center,
            (a, 0) => self.spokes[i][a as usize - 1],
            (0, b) => self.spokes[(i + 1) % n][b as usize - 1],
            (a, b) => self.inner[i][a as usize - 1][b as usize - 1],
        }
    }

    /// The ring as a polygon list: the points of [`TwoRing::points`] and
    /// `4n` counter-clockwise quads (sector after sector: the cell at the
    /// vertex, then the cells `[1,2] x [0,1]`, `[0,1] x [1,2]`, `[1,2]^2`).
    /// An open mesh whose vertex 0 is the centre.
    pub fn to_polygons(&self) -> (Vec<Point>, Vec<Vec<usize>>) {
        let n = self.valence();
        let id = |i: usize, a: usize, b: usize| -> usize {
            match (a, b) {
                (0, 0) => 0,
                (a, 0) => 1 + 2 * (i % n) + a - 1,
                (0, b) => 1 + 2 * ((i + 1) % n) + b - 1,
                (a, b) => 1 + 2 * n + 4 * (i % n) + 2 * (a - 1) + b - 1,
            }
        };
        let mut faces = Vec::with_capacity(4 * n);
        for i in 0..n {
            for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                faces.push(vec![
                    id(i, a, b),
                    id(i, a + 1, b),
                    id(i, a + 1, b + 1),
                    id(i, a, b + 1),
                ]);
            }
        }
        (self.points(), faces)
    }

    /// A random perturbation of a regular-looking 2-ring of valence `n`:
    /// `S(i, a, b) = a e_i + b e_{i+1}` in the plane (`e_k` the unit vector
    /// at angle `2 pi k / n`), lifted onto `z = 0.2 (x^2 - y^2 / 2)`, every
    /// coordinate of every point moved by a uniform amount in `[-0.1, 0.1]`.
    pub fn random(n: usize, seed: u64) -> Result<TwoRing, G2CapError> {
        check_valence(n)?;
        let mut rng = SplitMix64::new(seed);
        let mut jitter = |p: [f64; 2]| -> Point {
            let z = 0.2 * (p[0] * p[0] - 0.5 * p[1] * p[1]);
            [
                p[0] + rng.uniform(-0.1, 0.1),
                p[1] + rng.uniform(-0.1, 0.1),
                z + rng.uniform(-0.1, 0.1),
            ]
        };
        let e = |k: usize| {
            let t = 2.0 * std::f64::consts::PI * (k % n) as f64 / n as f64;
            [t.cos(), t.sin()]
        };
        let at = |k: usize, a: f64, b: f64| {
            let (u, w) = (e(k), e(k + 1));
            [a * u[0] + b * w[0], a * u[1] + b * w[1]]
        };
        let center = jitter([0.0, 0.0]);
        let spokes = (0..n)
            .map(|k| [jitter(at(k, 1.0, 0.0)), jitter(at(k, 2.0, 0.0))])
            .collect();
        let inner = (0..n)
            .map(|i| {
                [
                    [jitter(at(i, 1.0, 1.0)), jitter(at(i, 1.0, 2.0))],
                    [jitter(at(i, 2.0, 1.0)), jitter(at(i, 2.0, 2.0))],
                ]
            })
            .collect();
        TwoRing::new(center, spokes, inner)
    }

    /// The 2-ring of `vertex` in a polygon list (0-based indices; the mesh
    /// may be open away from the 2-ring). Returns the ring and the mesh
    /// indices of its points in the order of [`TwoRing::points`].
    ///
    /// Refused, naming the vertex: an index out of range; a vertex on the
    /// boundary (an edge at it with one face) or whose faces do not close
    /// into one fan; a face around it, or in its 2-ring, that is not a quad;
    /// valence 4 (not extraordinary); a 1-ring vertex that is not regular
    /// (valence 4, interior).
    pub fn from_polygons(
        positions: &[Point],
        faces: &[Vec<usize>],
        vertex: usize,
    ) -> Result<(TwoRing, Vec<usize>), G2CapError> {
        if vertex >= positions.len() {
            return Err(G2CapError::NoSuchVertex {
                vertex,
                count: positions.len(),
            });
        }
        // Directed edge -> (face, corner of its origin).
        let mut half: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
        let mut faces_at: Vec<usize> = vec![0; positions.len()];
        for (f, face) in faces.iter().enumerate() {
            for (k, &u) in face.iter().enumerate() {
                if u >= positions.len() {
                    return Err(G2CapError::NoSuchVertex {
                        vertex: u,
                        count: positions.len(),
                    });
                }
                let w = face[(k + 1) % face.len()];
                half.insert((u, w), (f, k));
                faces_at[u] += 1;
            }
        }
        let quad = |f: usize, at: usize| -> Result<&Vec<usize>, G2CapError> {
            if faces[f].len() == 4 {
                Ok(&faces[f])
            } else {
                Err(G2CapError::NotQuad {
                    vertex: at,
                    face: f,
                    corners: faces[f].len(),
                })
            }
        };
        // The quad containing directed edge (p -> q), rotated to start at p.
        let quad_from = |p: usize, q: usize, at: usize| -> Result<[usize; 4], G2CapError> {
            let &(f, k) = half
                .get(&(p, q))
                .ok_or(G2CapError::Boundary { vertex: at })?;
            let face = quad(f, at)?;
            Ok([
                face[k],
                face[(k + 1) % 4],
                face[(k + 2) % 4],
                face[(k + 3) % 4],
            ])
        };
        // The fan around the vertex, counter-clockwise.
        let first = faces
            .iter()
            .enumerate()
            .find_map(|(f, face)| face.iter().position(|&u| u == vertex).map(|k| (f, k)))
            .ok_or(G2CapError::Boundary { vertex })?;
        let face0 = quad(first.0, vertex)?;
        let mut fan: Vec<[usize; 4]> = Vec::new();
        let mut q = quad_from(vertex, face0[(first.1 + 1) % 4], vertex)?;
        loop {
            fan.push(q);
            if fan.len() > faces_at[vertex] {
                return Err(G2CapError::NotOneFan { vertex });
            }
            // Next sector: the quad with directed edge v -> e_{i+1} = q[3].
            q = quad_from(vertex, q[3], vertex)?;
            if q == fan[0] {
                break;
            }
        }
        let n = fan.len();
        if n != faces_at[vertex] {
            return Err(G2CapError::NotOneFan { vertex });
        }
        if n == 4 {
            return Err(G2CapError::NotExtraordinary { vertex });
        }
        if !(MIN_VALENCE..=MAX_VALENCE).contains(&n) {
            return Err(G2CapError::VertexValence { vertex, valence: n });
        }
        // Sector grids of mesh indices. Errors on the outer faces name the
        // centre vertex, whose 2-ring is refused.
        let mut grid = vec![[[usize::MAX; 3]; 3]; n];
        for (i, f) in fan.iter().enumerate() {
            let (e0, fi, e1) = (f[1], f[2], f[3]);
            for (w, what) in [(e0, "spoke"), (fi, "face")] {
                if faces_at[w] != 4 {
                    return Err(G2CapError::IrregularOneRing {
                        vertex,
                        neighbour: w,
                        what,
                        valence: faces_at[w],
                    });
                }
            }
            let a = quad_from(fi, e0, vertex)?; // [f_i, e_i, S(2,0), S(2,1)]
            let b = quad_from(e1, fi, vertex)?; // [e_{i+1}, f_i, S(1,2), S(0,2)]
            let d = quad_from(fi, a[3], vertex)?; // [f_i, S(2,1), S(2,2), S(1,2)]
            if d[3] != b[2] {
                return Err(G2CapError::IrregularOneRing {
                    vertex,
                    neighbour: fi,
                    what: "face",
                    valence: faces_at[fi],
                });
            }
            let g = &mut grid[i];
            g[0][0] = vertex;
            g[1][0] = e0;
            g[0][1] = e1;
            g[1][1] = fi;
            g[2][0] = a[2];
            g[2][1] = a[3];
            g[2][2] = d[2];
            g[1][2] = b[2];
            g[0][2] = b[3];
        }
        // Spoke points seen from both sectors must agree.
        for i in 0..n {
            let j = (i + 1) % n;
            if grid[i][0][2] != grid[j][2][0] || grid[i][0][1] != grid[j][1][0] {
                return Err(G2CapError::IrregularOneRing {
                    vertex,
                    neighbour: grid[j][1][0],
                    what: "spoke",
                    valence: faces_at[grid[j][1][0]],
                });
            }
        }
        let mut idx = vec![vertex];
        for g in &grid {
            idx.extend([g[1][0], g[2][0]]);
        }
        for g in &grid {
            idx.extend([g[1][1], g[1][2], g[2][1], g[2][2]]);
        }
        let mut sorted = idx.clone();
        sorted.sort_unstable();
        sorted.dedup();
        if sorted.len() != idx.len() {
            return Err(G2CapError::RingNotDistinct { vertex });
        }
        let p = |k: usize| positions[k];
        let spokes = grid.iter().map(|g| [p(g[1][0]), p(g[2][0])]).collect();
        let inner = grid
            .iter()
            .map(|g| [[p(g[1][1]), p(g[1][2])], [p(g[2][1]), p(g[2][2])]])
            .collect();
        let ring = TwoRing::new(p(vertex), spokes, inner).map_err(|e| match e {
            G2CapError::Degenerate { vertex: None } => G2CapError::Degenerate {
                vertex: Some(vertex),
            },
            other => other,
        })?;
        Ok((ring, idx))
    }
}

/// The ring after one step of the shape-adjustable scheme: the points
/// `T(i, A, B)`, `A, B = 0..=3`, of the refined sector grids (same index
/// conventions as [`TwoRing::point`], on the refined grid).
#[derive(Clone, Debug)]
pub struct RefinedRing {
    n: usize,
    /// `grid[i][A][B]`; the entries with `A = 0` are not used (they are
    /// those of the next sector with `A` and `B` swapped).
    grid: Vec<[[Point; 4]; 4]>,
}

fn lin(terms: &[(f64, Point)]) -> Point {
    let mut out = [0.0; 3];
    for (w, p) in terms {
        for k in 0..3 {
            out[k] += w * p[k];
        }
    }
    out
}

impl RefinedRing {
    /// One step of the shape-adjustable Catmull-Clark rules (math doc
    /// section 8) on the part of the ring where the stencils are complete:
    ///
    /// ```text
    /// f' = centroid,  e' = (1 - c)(v + e)/2 + c (f'_1 + f'_2)/2,
    /// v' = (4 c^2 Q + 8 c (1 - c) R + (m - 4 c (2 - c)) v) / m
    /// ```
    ///
    /// (`m` the valence of the old vertex).
    pub fn new(ring: &TwoRing, c: f64) -> RefinedRing {
        let n = ring.valence();
        let s = |i: usize, a: i32, b: i32| ring.point(i, a, b);
        // Face point of the old cell [a, a+1] x [b, b+1] of sector i.
        let fp = |i: usize, a: i32, b: i32| {
            lin(&[
                (0.25, s(i, a, b)),
                (0.25, s(i, a + 1, b)),
                (0.25, s(i, a + 1, b + 1)),
                (0.25, s(i, a, b + 1)),
            ])
        };
        let vrule = |q: Point, r: Point, v: Point, m: f64| {
            lin(&[
                (4.0 * c * c / m, q),
                (8.0 * c * (1.0 - c) / m, r),
                ((m - 4.0 * c * (2.0 - c)) / m, v),
            ])
        };
        let vp = |i: usize, a: i32, b: i32| -> Point {
            if a == 0 && b == 0 {
                let w = 1.0 / n as f64;
                let q: Vec<(f64, Point)> = (0..n).map(|k| (w, fp(k, 0, 0))).collect();
                let mut r: Vec<(f64, Point)> = (0..n).map(|k| (0.5 * w, s(k, 1, 0))).collect();
                r.push((0.5, ring.center));
                vrule(lin(&q), lin(&r), ring.center, n as f64)
            } else {
                let v = s(i, a, b);
                let q = lin(&[
                    (0.25, fp(i, a, b)),
                    (0.25, fp(i, a - 1, b)),
                    (0.25, fp(i, a, b - 1)),
                    (0.25, fp(i, a - 1, b - 1)),
                ]);
                let r = lin(&[
                    (0.5, v),
                    (0.125, s(i, a + 1, b)),
                    (0.125, s(i, a - 1, b)),
                    (0.125, s(i, a, b + 1)),
                    (0.125, s(i, a, b - 1)),
                ]);
                vrule(q, r, v, 4.0)
            }
        };
        let edge = |p: Point, q: Point, f1: Point, f2: Point| {
            lin(&[
                ((1.0 - c) / 2.0, p),
                ((1.0 - c) / 2.0, q),
                (c / 2.0, f1),
                (c / 2.0, f2),
            ])
        };
        let mut grid = vec![[[[0.0; 3]; 4]; 4]; n];
        for (i, g) in grid.iter_mut().enumerate() {
            for aa in 0..4i32 {
                for bb in 0..4i32 {
                    let (a, b) = (aa / 2, bb / 2);
                    g[aa as usize][bb as usize] = match (aa % 2, bb % 2) {
                        (0, 0) => vp(i, a, b),
                        (1, 0) => edge(s(i, a, b), s(i, a + 1, b), fp(i, a, b), fp(i, a, b - 1)),
                        (0, 1) => edge(s(i, a, b), s(i, a, b + 1), fp(i, a, b), fp(i, a - 1, b)),
                        _ => fp(i, a, b),
                    };
                }
            }
        }
        RefinedRing { n, grid }
    }

    /// `T(i, A, B)` for `A, B` in `-1..=3` (not both negative).
    pub fn point(&self, i: usize, a: i32, b: i32) -> Point {
        let n = self.n;
        let i = i % n;
        if b < 0 {
            return self.point(i + n - 1, 1, a);
        }
        if a < 0 {
            return self.point(i + 1, b, 1);
        }
        if a == 0 && b > 0 {
            return self.grid[(i + 1) % n][b as usize][0];
        }
        self.grid[i][a as usize][b as usize]
    }

    /// The 4 x 4 B-spline control grid of the regular cell across the cap's
    /// `u = 1` edge in sector `i` (cell `[1,2] x [0,1]`): `G[al][be] = T(i,
    /// al, be - 1)`.
    pub fn grid_u(&self, i: usize) -> [[Point; 4]; 4] {
        std::array::from_fn(|al| std::array::from_fn(|be| self.point(i, al as i32, be as i32 - 1)))
    }

    /// The grid of the diagonal cell `[1,2] x [1,2]` of sector `i`:
    /// `G[al][be] = T(i, al, be)`.
    pub fn grid_corner(&self, i: usize) -> [[Point; 4]; 4] {
        std::array::from_fn(|al| std::array::from_fn(|be| self.point(i, al as i32, be as i32)))
    }

    /// The 2-ring of the refined vertex (the points `T(i, A, B)`, `A, B <=
    /// 2`): refining it again gives the next level of the subdivision
    /// surface ([`super::plain`]). Refused only if a point overflowed.
    pub fn two_ring(&self) -> Result<TwoRing, G2CapError> {
        let n = self.n;
        let spokes = (0..n)
            .map(|k| [self.point(k, 1, 0), self.point(k, 2, 0)])
            .collect();
        let inner = (0..n)
            .map(|i| {
                [
                    [self.point(i, 1, 1), self.point(i, 1, 2)],
                    [self.point(i, 2, 1), self.point(i, 2, 2)],
                ]
            })
            .collect();
        TwoRing::new(self.point(0, 0, 0), spokes, inner)
    }

    /// The valence.
    pub fn valence(&self) -> usize {
        self.n
    }

    /// The grid of the cell across the cap's `v = 1` edge (cell `[0,1] x
    /// [1,2]`): `G[al][be] = T(i, al - 1, be)`.
    pub fn grid_v(&self, i: usize) -> [[Point; 4]; 4] {
        std::array::from_fn(|al| std::array::from_fn(|be| self.point(i, al as i32 - 1, be as i32)))
    }
}
