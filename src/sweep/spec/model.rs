//! The validated parts of a sweep spec (parameter space, sampler, result
//! columns) and the limits they are checked against.

use serde::Serialize;
use std::collections::BTreeMap;

/// Largest number of configurations a sweep may have (over all valences).
///
/// Configuration ids are written to CSV and JSON; keeping them below `2^53`
/// keeps them exact in every JSON reader (IEEE doubles). `2^48` (2.8e14) is far
/// beyond any run that finishes, and catches grids such as 21^64 early.
pub const MAX_CONFIGURATIONS: u64 = 1 << 48;

/// Largest number of points of one Sobol sequence (32-bit direction numbers).
pub const MAX_SOBOL_POINTS: u64 = 1 << 32;

/// Largest leading-eigenvalue count that can be requested (`columns.eigenvalues`).
pub const MAX_KEPT_EIGENVALUES: usize = 1024;

/// Largest valence accepted in a sweep spec.
pub const MAX_VALENCE: usize = 4096;

/// The parameter space a sweep samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpaceKind {
    /// Edge ratios `r_i`, uniform in a sub-interval of (0, 1).
    Ratios,
    /// Corner intervals `p_i, q_i`, log-uniform.
    CornerIntervals,
    /// Face extraordinary point: directed edge intervals, log-uniform.
    FaceEp,
    /// Vertex extraordinary point: intervals `a_k`, log-uniform.
    VertexEp,
    /// Uniform knots: no coordinates.
    Uniform,
    /// The shape parameter `c` of the adjustable Catmull-Clark scheme.
    Shape,
    /// The angle of a corner sector in degrees (a `[sector]` sweep of
    /// corners; math doc section 18.2), uniform in a sub-interval of (0, 360).
    CornerAngle,
}

impl SpaceKind {
    /// The spec name.
    pub fn name(self) -> &'static str {
        match self {
            SpaceKind::Ratios => "ratios",
            SpaceKind::CornerIntervals => "corner-intervals",
            SpaceKind::FaceEp => "face-ep",
            SpaceKind::VertexEp => "vertex-ep",
            SpaceKind::Uniform => "uniform",
            SpaceKind::Shape => "shape",
            SpaceKind::CornerAngle => "corner-angle",
        }
    }

    pub(super) fn parse(s: &str) -> Option<Self> {
        [
            SpaceKind::Ratios,
            SpaceKind::CornerIntervals,
            SpaceKind::FaceEp,
            SpaceKind::VertexEp,
            SpaceKind::Uniform,
            SpaceKind::Shape,
            SpaceKind::CornerAngle,
        ]
        .into_iter()
        .find(|k| k.name() == s)
    }

    /// The coordinate families, in column order (`["r"]`, `["p", "q"]`, ...).
    pub fn families(self) -> &'static [&'static str] {
        match self {
            SpaceKind::Ratios => &["r"],
            SpaceKind::CornerIntervals => &["p", "q"],
            SpaceKind::FaceEp => &["forward", "backward"],
            SpaceKind::VertexEp => &["a"],
            SpaceKind::Uniform => &[],
            SpaceKind::Shape => &["c"],
            SpaceKind::CornerAngle => &["angle"],
        }
    }

    /// Number of coordinates of a valence-`n` configuration.
    pub fn dimension(self, n: usize) -> usize {
        match self {
            SpaceKind::Shape | SpaceKind::CornerAngle => 1,
            _ => self.families().len() * n,
        }
    }

    /// Whether coordinates are sampled log-uniformly (knot intervals) rather than
    /// uniformly (ratios).
    pub fn is_log(self) -> bool {
        matches!(
            self,
            SpaceKind::CornerIntervals | SpaceKind::FaceEp | SpaceKind::VertexEp
        )
    }

    /// The name of coordinate `k` of a valence-`n` configuration (`r2`, `q0`, ...).
    pub fn coordinate_name(self, n: usize, k: usize) -> String {
        if matches!(self, SpaceKind::Shape | SpaceKind::CornerAngle) {
            return self.families()[0].to_owned();
        }
        let fam = self.families()[k / n];
        format!("{fam}{}", k % n)
    }

    /// Position of a named coordinate in a valence-`n` configuration, if it exists.
    pub fn coordinate_index(self, n: usize, name: &str) -> Option<usize> {
        if matches!(self, SpaceKind::Shape | SpaceKind::CornerAngle) {
            return (name == self.families()[0]).then_some(0);
        }
        // Longest family prefix first ("backward" before "b..." would not clash, but be safe).
        self.families().iter().enumerate().find_map(|(f, fam)| {
            let rest = name.strip_prefix(fam)?;
            if rest.is_empty() || !rest.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            if rest.len() > 1 && rest.starts_with('0') {
                return None;
            }
            let i: usize = rest.parse().ok()?;
            (i < n).then_some(f * n + i)
        })
    }
}

/// The validated parameter space.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Space {
    /// What is sampled.
    pub kind: SpaceKind,
    /// Sampling range `[a, b]` of every free coordinate (`None` for `uniform`).
    pub range: Option<(f64, f64)>,
    /// Fixed coordinates by name (slices), e.g. `r2 = 0.5`.
    pub fixed: BTreeMap<String, f64>,
}

/// The validated sampler.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Sampler {
    /// Full tensor grid with `points_per_axis` points on every free coordinate
    /// (end points included; one point = the midpoint).
    Grid {
        /// Points per free coordinate (>= 1).
        points_per_axis: u64,
    },
    /// Independent uniform draws derived from `(seed, valence, index, coordinate)`.
    Random {
        /// Configurations per valence.
        count: u64,
        /// Seed.
        seed: u64,
    },
    /// Halton sequence (prime bases), optionally with a random shift modulo 1.
    Halton {
        /// Configurations per valence.
        count: u64,
        /// Seed of the random shift (`None`: unscrambled).
        scramble_seed: Option<u64>,
    },
    /// Sobol sequence (base 2, Joe-Kuo direction numbers), optionally with
    /// Owen's nested uniform scrambling (math doc section 16.1).
    Sobol {
        /// Configurations per valence.
        count: u64,
        /// Seed of the scrambling (`None`: unscrambled, SciPy's points).
        scramble_seed: Option<u64>,
    },
}

/// Which result columns a sweep computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Columns {
    /// Number of leading eigenvalues of `S_n` (by non-increasing modulus) kept.
    pub eigenvalues: usize,
    /// Subdominant class, `lambda1`, `lambda2`, `|lambda3|`.
    pub classification: bool,
    /// Gap `|lambda2| - |lambda3|`, ratio `|lambda2| / |lambda1|`, angle of `lambda1`.
    pub gap: bool,
    /// Asymptotic contraction rate of the face (`|lambda1|`).
    pub contraction: bool,
    /// Exact classification over the rationals.
    pub exact_certificate: bool,
    /// Characteristic-map verdict (regularity, injectivity; math doc section 7).
    pub charmap: bool,
    /// The generic characteristic-map certificate ([`crate::charmap::generic`],
    /// math doc section 20). Left out of the serialised spec when false, so
    /// that existing summaries and fingerprints are unchanged.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub generic_charmap: bool,
    /// Curvature at the extraordinary point: `mu`, `mu / lambda^2` and the
    /// verdict ([`crate::curvature`], math doc section 13). Left out of the
    /// serialised spec when false, so that existing summaries are unchanged.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub curvature: bool,
    /// The columns are those of a `[sector]` sweep ([`SectorSweep`]): the
    /// characteristic-map columns are the sector certificate's (math doc
    /// section 18.4). Set by the spec's `[sector]` table, not a key of
    /// `[columns]`; left out of the serialised spec when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub sector: bool,
}

/// The `[sector]` table of a spec: a sweep of boundary, crease or corner
/// configurations ([`crate::boundary::SectorConfig`], math doc section 18)
/// over the face count `K` (the spec's valences) and, for corners, the angle
/// (space kind `corner-angle`). A crease sweep has two sectors of `K` faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct SectorSweep {
    /// The kind of vertex.
    pub vertex: crate::boundary::VertexKind,
    /// The rule set.
    pub rules: crate::boundary::RuleSet,
}

impl Default for Columns {
    fn default() -> Self {
        Columns {
            eigenvalues: 0,
            classification: true,
            gap: true,
            contraction: true,
            exact_certificate: false,
            charmap: false,
            generic_charmap: false,
            curvature: false,
            sector: false,
        }
    }
}
