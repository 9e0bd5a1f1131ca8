//! The errors of the cap construction and the tolerances of its residual checks.

/// Largest accepted residual (internal G1 and G2, outer boundary): the jump
/// of the unit normal, and of `K / k_s^2` and `H / k_s` (`k_s` the curvature
/// scale: the largest principal curvature magnitude over the samples, at
/// least `1 / L`, `L` the diameter of the cap's control points). The construction satisfies its conditions
/// exactly; what remains is rounding in the SVD and in the evaluation,
/// measured between `1e-15` and `3e-11` for `n = 3..=8` (math doc section
/// 14.6), so `1e-9` leaves a margin of thirty and still refuses any real
/// defect (a missing condition gives jumps of order `1e-3` and above).
pub const RESIDUAL_TOL: f64 = 1e-9;

/// Largest accepted `max |A x - r| / L` of the linear conditions after the
/// solve (an inconsistent system shows here first).
pub const CONSTRAINT_RTOL: f64 = 1e-10;

/// Errors of the cap construction. Vertex indices are 0-based; messages also
/// print the 1-based OBJ index.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum G2CapError {
    /// A valence outside `3..=16`.
    #[error("valence {valence} is outside the supported range 3..=16")]
    Valence {
        /// The valence.
        valence: usize,
    },
    /// The vertex's valence is outside `3..=16`.
    #[error("vertex {vertex} (OBJ {}) has valence {valence}, outside the supported range 3..=16", vertex + 1)]
    VertexValence {
        /// The vertex.
        vertex: usize,
        /// Its valence.
        valence: usize,
    },
    /// Spokes and sectors of different counts.
    #[error("a 2-ring needs as many sectors as spokes: {spokes} spokes, {sectors} sectors")]
    RingShape {
        /// Spokes.
        spokes: usize,
        /// Sectors.
        sectors: usize,
    },
    /// A ring point that is NaN or infinite.
    #[error("2-ring point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// Its index in [`TwoRing::points`](super::ring::TwoRing::points).
        index: usize,
    },
    /// The 2-ring's points lie on one point or one line (no tangent plane).
    #[error("the 2-ring{} is degenerate: its points lie on one point or one line", degenerate_at(.vertex))]
    Degenerate {
        /// The centre vertex, when the ring comes from a mesh.
        vertex: Option<usize>,
    },
    /// The shape parameter outside `[0, 1]`.
    #[error("shape parameter c = {c} is outside [0, 1]")]
    ShapeParameter {
        /// The value.
        c: f64,
    },
    /// A vertex index out of range.
    #[error("vertex {vertex} (OBJ {}) does not exist: the mesh has {count} vertices", vertex + 1)]
    NoSuchVertex {
        /// The index.
        vertex: usize,
        /// Number of vertices.
        count: usize,
    },
    /// The vertex has valence 4.
    #[error("vertex {vertex} (OBJ {}) is not extraordinary: it has valence 4", vertex + 1)]
    NotExtraordinary {
        /// The vertex.
        vertex: usize,
    },
    /// The vertex (or a vertex of its 1-ring) lies on the boundary.
    #[error("vertex {vertex} (OBJ {}) is a boundary vertex or its 2-ring is incomplete (an edge with one face)", vertex + 1)]
    Boundary {
        /// The vertex.
        vertex: usize,
    },
    /// The faces at the vertex do not form one closed fan.
    #[error("the faces at vertex {vertex} (OBJ {}) do not form one closed fan", vertex + 1)]
    NotOneFan {
        /// The vertex.
        vertex: usize,
    },
    /// A face of the 2-ring that is not a quad.
    #[error("the 2-ring of vertex {vertex} (OBJ {}) is not all quads: face {face} has {corners} corners", vertex + 1)]
    NotQuad {
        /// The vertex whose ring was being read.
        vertex: usize,
        /// The face.
        face: usize,
        /// Its corner count.
        corners: usize,
    },
    /// A 1-ring vertex that is not a regular interior vertex.
    #[error("the 1-ring of vertex {vertex} (OBJ {}) is not regular: {what} vertex {neighbour} (OBJ {}) has {valence} faces (4 needed)", vertex + 1, neighbour + 1)]
    IrregularOneRing {
        /// The centre vertex.
        vertex: usize,
        /// The offending neighbour.
        neighbour: usize,
        /// `spoke` or `face`.
        what: &'static str,
        /// Its number of faces.
        valence: usize,
    },
    /// The 2-ring visits a vertex twice.
    #[error("the 2-ring of vertex {vertex} (OBJ {}) visits a vertex twice", vertex + 1)]
    RingNotDistinct {
        /// The vertex.
        vertex: usize,
    },
    /// A number of refinement levels outside `1..=max`.
    #[error("levels = {levels} is outside the supported range 1..={max}")]
    Levels {
        /// The value.
        levels: usize,
        /// The largest accepted.
        max: usize,
    },
    /// A linear-algebra step failed.
    #[error("numerical failure in the G2 cap: {0}")]
    Numerical(&'static str),
    /// A residual above its tolerance.
    #[error("G2 cap residual {what} = {value:e} exceeds the tolerance {tol:e}")]
    Residual {
        /// Which residual.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The tolerance.
        tol: f64,
    },
}

fn degenerate_at(vertex: &Option<usize>) -> String {
    vertex.map_or_else(String::new, |v| format!(" of vertex {v} (OBJ {})", v + 1))
}

impl G2CapError {
    /// Whether the error is about the input (the CLI's exit 2) rather than a
    /// failure of the construction (exit 1).
    pub fn is_input_error(&self) -> bool {
        !matches!(self, G2CapError::Numerical(_) | G2CapError::Residual { .. })
    }
}
