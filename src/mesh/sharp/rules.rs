//! The rules of sharp and semi-sharp features (math doc section 17): vertex
//! rules, sharpness decay and the refinement masks of Catmull-Clark and Loop
//! with OpenSubdiv's Sdc semantics. Pure functions of local data (the
//! sharpness of a vertex and of its incident edges); the refiner
//! ([`super::refine`]) applies them.
//!
//! Sharpness values are single precision, as in OpenSubdiv: every decay,
//! Chaikin average and fractional weight is computed in `f32` and only the
//! resulting blend weight is widened to `f64`, so the masks agree with
//! OpenSubdiv's to the last bit of the sharpness arithmetic.
//!
//! ```text
//! rule(s_v, k)   = corner               if s_v > 0 or k > 2
//!                  smooth / dart / crease for k = 0 / 1 / 2 sharp edges
//! decay_uniform(s) = s - 1 (0 below), infinite stays infinite
//! decay_chaikin(s_i) = 3/4 s_i + 1/4 mean_{j != i} s_j - 1 over the
//!                      semi-sharp edges j of the end vertex
//! ```

/// Sharpness at and above which a feature is infinitely sharp.
pub const SHARPNESS_INFINITE: f32 = 10.0;

/// The subdivision scheme whose masks are used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SdcScheme {
    /// Catmull-Clark (any polygons in, quads out).
    CatmullClark,
    /// Loop (triangles).
    Loop,
}

/// How boundary vertices are interpolated (OpenSubdiv's `VtxBoundaryInterpolation`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Boundary edges are sharp, and the faces at boundary vertices are
    /// holes: left out of the output.
    None,
    /// Boundary edges are infinitely sharp (crease rule at boundary vertices).
    EdgeOnly,
    /// As `EdgeOnly`, and a boundary vertex with a single face is an
    /// infinitely sharp corner.
    EdgeAndCorner,
}

impl Boundary {
    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::None => "none",
            Boundary::EdgeOnly => "edge-only",
            Boundary::EdgeAndCorner => "edge-and-corner",
        }
    }
}

/// How semi-sharp edge sharpness decays from level to level
/// (OpenSubdiv's `CreasingMethod`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Creasing {
    /// Every semi-sharp value decreases by 1.
    Uniform,
    /// Chaikin: a child edge mixes 3/4 of its parent's sharpness with 1/4
    /// of the mean of the other semi-sharp edges at its end vertex, then
    /// decreases by 1.
    Chaikin,
}

impl Creasing {
    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            Creasing::Uniform => "uniform",
            Creasing::Chaikin => "chaikin",
        }
    }
}

/// The rule of a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// No sharp edge, smooth vertex.
    Smooth,
    /// One sharp edge: the smooth mask.
    Dart,
    /// Two sharp edges: the crease mask `(1/8, 3/4, 1/8)` along them.
    Crease,
    /// A sharp vertex or more than two sharp edges: the vertex stays.
    Corner,
}

/// Whether `s` is sharp at all (`s > 0`).
#[inline]
pub fn is_sharp(s: f32) -> bool {
    s > 0.0
}

/// Whether `s` is infinitely sharp (`s >= 10`).
#[inline]
pub fn is_infinite(s: f32) -> bool {
    s >= SHARPNESS_INFINITE
}

/// Whether `s` is semi-sharp (`0 < s < 10`).
#[inline]
pub fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < SHARPNESS_INFINITE
}

/// Uniform decay: smooth stays smooth, infinite stays infinite, `s > 1`
/// becomes `s - 1`, anything else becomes smooth.
#[inline]
pub fn decrement(s: f32) -> f32 {
    if s <= 0.0 {
        0.0
    } else if is_infinite(s) {
        SHARPNESS_INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// The rule of a vertex of sharpness `vertex_sharpness` with `sharp_edges`
/// sharp incident edges (module docs).
#[inline]
pub fn vertex_rule(vertex_sharpness: f32, sharp_edges: usize) -> Rule {
    if is_sharp(vertex_sharpness) {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// The sharpness of the child of every edge around a vertex, at that
/// vertex's end (`parent[i]` -> `child[i]`; module docs): uniform decay, or
/// Chaikin's average with the other semi-sharp edges of the vertex.
pub fn child_edge_sharpness(creasing: Creasing, parent: &[f32], child: &mut [f32]) {
    if creasing == Creasing::Uniform || parent.len() < 2 {
        for (c, &p) in child.iter_mut().zip(parent) {
            *c = decrement(p);
        }
        return;
    }
    let (mut sum, mut count) = (0.0f32, 0usize);
    for &p in parent {
        if is_semi_sharp(p) {
            sum += p;
            count += 1;
        }
    }
    for (c, &p) in child.iter_mut().zip(parent) {
        *c = if !is_sharp(p) {
            0.0
        } else if is_infinite(p) {
            SHARPNESS_INFINITE
        } else if count == 1 {
            decrement(p)
        } else {
            let others = (sum - p) / (count - 1) as f32;
            let s = (0.75 * p + 0.25 * others) - 1.0;
            if is_sharp(s) {
                s
            } else {
                0.0
            }
        };
    }
}

/// The weight of the parent's rule when a vertex's rule changes between
/// levels: the mean of the sharpness values that decayed to zero (the
/// vertex's own, and each incident edge's), clamped to 1.
pub fn fractional_weight(
    creasing: Creasing,
    parent_vertex: f32,
    child_vertex: f32,
    parent_edges: &[f32],
    child_edges: &[f32],
) -> f32 {
    let (mut count, mut sum) = (0usize, 0.0f32);
    if is_sharp(parent_vertex) && !is_sharp(child_vertex) {
        count = 1;
        sum = parent_vertex;
    }
    for (&p, &c) in parent_edges.iter().zip(child_edges) {
        let decayed = match creasing {
            Creasing::Uniform => is_sharp(p) && p <= 1.0,
            Creasing::Chaikin => is_sharp(p) && !is_sharp(c),
        };
        if decayed {
            sum += p;
            count += 1;
        }
    }
    if count == 0 {
        return 0.0;
    }
    let w = sum / count as f32;
    if w > 1.0 {
        1.0
    } else {
        w
    }
}

/// The smooth vertex mask of an interior vertex with `valence` edges:
/// `(weight of the vertex, of each edge's far end, of each face point)`.
///
/// Catmull-Clark: `((n - 2)/n, 1/n^2, 1/n^2)`; Loop:
/// `(1 - n w, w, 0)`, `w = (5/8 - beta^2)/n`, `beta = 3/8 + cos(2 pi/n)/4`
/// (`w = 1/16` at `n = 6`).
pub fn smooth_vertex_weights(scheme: SdcScheme, valence: usize) -> (f64, f64, f64) {
    let n = valence as f64;
    match scheme {
        SdcScheme::CatmullClark => ((n - 2.0) / n, 1.0 / (n * n), 1.0 / (n * n)),
        SdcScheme::Loop => {
            if valence == 6 {
                (0.625, 0.0625, 0.0)
            } else {
                let beta = 0.25 * (2.0 * std::f64::consts::PI / n).cos() + 0.375;
                let w = (0.625 - beta * beta) / n;
                (1.0 - w * n, w, 0.0)
            }
        }
    }
}

/// A vertex-vertex mask: `v` on the vertex, `edges[i]` on the far end of
/// incident edge `i`, `faces[j]` on the face point of incident face `j`
/// (Catmull-Clark only).
#[derive(Clone, Debug, Default)]
pub struct VertexMask {
    /// Weight of the vertex itself.
    pub v: f64,
    /// Weights of the far ends of the incident edges.
    pub edges: Vec<f64>,
    /// Weights of the face points of the incident faces.
    pub faces: Vec<f64>,
    child_edges: Vec<f32>,
}

impl VertexMask {
    /// Fills the mask of `rule` (Crease: the sharp edges of `sharpness` are
    /// its ends) scaled by `scale`, added onto the current weights.
    fn add_rule(&mut self, scheme: SdcScheme, rule: Rule, sharpness: &[f32], scale: f64) {
        match rule {
            Rule::Smooth | Rule::Dart => {
                let (wv, we, wf) = smooth_vertex_weights(scheme, self.edges.len());
                self.v += scale * wv;
                for e in &mut self.edges {
                    *e += scale * we;
                }
                if scheme == SdcScheme::CatmullClark {
                    for f in &mut self.faces {
                        *f += scale * wf;
                    }
                }
            }
            Rule::Crease => {
                self.v += scale * 0.75;
                for (e, &s) in self.edges.iter_mut().zip(sharpness) {
                    if is_sharp(s) {
                        *e += scale * 0.125;
                    }
                }
            }
            Rule::Corner => self.v += scale,
        }
    }

    /// The vertex-vertex mask of a vertex of sharpness `vertex_sharpness`
    /// whose incident edges have `edge_sharpness` and which has `faces`
    /// incident faces: the parent's rule, blended with the child's rule by
    /// [`fractional_weight`] when the two differ:
    /// `m = w m_parent + (1 - w) m_child`.
    pub fn compute(
        &mut self,
        scheme: SdcScheme,
        creasing: Creasing,
        vertex_sharpness: f32,
        edge_sharpness: &[f32],
        faces: usize,
    ) {
        let n = edge_sharpness.len();
        self.v = 0.0;
        self.edges.clear();
        self.edges.resize(n, 0.0);
        self.faces.clear();
        self.faces.resize(faces, 0.0);
        let sharp = edge_sharpness.iter().filter(|&&s| is_sharp(s)).count();
        let parent = vertex_rule(vertex_sharpness, sharp);
        if matches!(parent, Rule::Smooth | Rule::Dart) {
            self.add_rule(scheme, parent, edge_sharpness, 1.0);
            return;
        }
        let child_vertex = decrement(vertex_sharpness);
        let mut child_edges = std::mem::take(&mut self.child_edges);
        child_edges.clear();
        child_edges.resize(n, 0.0);
        child_edge_sharpness(creasing, edge_sharpness, &mut child_edges);
        let child_sharp = child_edges.iter().filter(|&&s| is_sharp(s)).count();
        let child = vertex_rule(child_vertex, child_sharp);
        if child == parent {
            self.add_rule(scheme, parent, edge_sharpness, 1.0);
        } else {
            let w = fractional_weight(
                creasing,
                vertex_sharpness,
                child_vertex,
                edge_sharpness,
                &child_edges,
            ) as f64;
            self.add_rule(scheme, parent, edge_sharpness, w);
            self.add_rule(scheme, child, &child_edges, 1.0 - w);
        }
        self.child_edges = child_edges;
    }
}

/// The edge-vertex mask of an edge of sharpness `s` whose two child edges
/// have sharpness `children`: `(weight of each end, weight of each face
/// point (Catmull-Clark) or opposite vertex (Loop))`.
///
/// Smooth: Catmull-Clark `(1/4, 1/4)`, Loop `(3/8, 1/8)`. Crease (both
/// children sharp): `(1/2, 0)`. A sharp edge whose children are not both
/// sharp blends the two with the parent's sharpness `s` (unclamped, as
/// OpenSubdiv does): `(s/2 + (1 - s) a, (1 - s) b)`.
pub fn edge_weights(scheme: SdcScheme, s: f32, children: [f32; 2]) -> (f64, f64) {
    let (a, b) = match scheme {
        SdcScheme::CatmullClark => (0.25, 0.25),
        SdcScheme::Loop => (0.375, 0.125),
    };
    if !is_sharp(s) {
        return (a, b);
    }
    if is_sharp(children[0]) && is_sharp(children[1]) {
        return (0.5, 0.0);
    }
    let w = s as f64;
    (w * 0.5 + (1.0 - w) * a, (1.0 - w) * b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_by_sharp_edge_count() {
        assert_eq!(vertex_rule(0.0, 0), Rule::Smooth);
        assert_eq!(vertex_rule(0.0, 1), Rule::Dart);
        assert_eq!(vertex_rule(0.0, 2), Rule::Crease);
        assert_eq!(vertex_rule(0.0, 3), Rule::Corner);
        assert_eq!(vertex_rule(0.5, 0), Rule::Corner);
    }

    #[test]
    fn decay() {
        assert_eq!(decrement(2.5), 1.5);
        assert_eq!(decrement(1.0), 0.0);
        assert_eq!(decrement(10.0), 10.0);
        let mut c = [0.0f32; 3];
        child_edge_sharpness(Creasing::Chaikin, &[2.0, 3.0, 0.0], &mut c);
        // 3/4 * 2 + 1/4 * 3 - 1 = 1.25; 3/4 * 3 + 1/4 * 2 - 1 = 1.75
        assert_eq!(c, [1.25, 1.75, 0.0]);
        child_edge_sharpness(Creasing::Uniform, &[2.0, 3.0, 0.0], &mut c);
        assert_eq!(c, [1.0, 2.0, 0.0]);
    }

    #[test]
    fn semi_sharp_crease_vertex_blends_by_sharpness() {
        // a crease of sharpness 0.5 through a valence-4 vertex: half crease, half smooth
        let mut m = VertexMask::default();
        m.compute(
            SdcScheme::CatmullClark,
            Creasing::Uniform,
            0.0,
            &[0.5, 0.0, 0.5, 0.0],
            4,
        );
        assert!((m.v - (0.5 * 0.75 + 0.5 * 0.5)).abs() < 1e-15);
        assert!((m.edges[0] - (0.5 * 0.125 + 0.5 / 16.0)).abs() < 1e-15);
        assert!((m.edges[1] - 0.5 / 16.0).abs() < 1e-15);
        assert!((m.faces[0] - 0.5 / 16.0).abs() < 1e-15);
        let total = m.v + m.edges.iter().sum::<f64>() + m.faces.iter().sum::<f64>();
        assert!((total - 1.0).abs() < 1e-15);
    }

    #[test]
    fn edge_masks() {
        assert_eq!(
            edge_weights(SdcScheme::Loop, 0.0, [0.0, 0.0]),
            (0.375, 0.125)
        );
        assert_eq!(
            edge_weights(SdcScheme::CatmullClark, 2.0, [1.0, 1.0]),
            (0.5, 0.0)
        );
        assert_eq!(
            edge_weights(SdcScheme::CatmullClark, 0.5, [0.0, 0.0]),
            (0.375, 0.125)
        );
    }
}
