//! The names of the built-in schemes ([`SchemeKind`]) and the error for an
//! unknown one.

use std::fmt;
use std::str::FromStr;

/// The schemes the toolkit knows, by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum SchemeKind {
    /// Non-Uniform Recursive Doo-Sabin.
    Nurds,
    /// Original Doo-Sabin weights.
    DooSabin,
    /// The Catmull-Clark variant of Doo-Sabin (= uniform NURDS).
    CcVariant,
    /// Catmull-Clark (vertex-centred; one-ring matrix 2n+1).
    CatmullClark,
    /// The shape-adjustable Catmull-Clark scheme with parameter c in [0, 1] (**\[reconstructed\]**).
    AdjustableCc,
    /// Loop subdivision on triangle meshes (vertex-centred; two-ring matrix 3n+1).
    Loop,
    /// Kobbelt's sqrt(3) subdivision on triangle meshes (vertex-centred;
    /// two-step two-ring matrix 3n+1).
    Sqrt3,
    /// The butterfly scheme (w = 1/16, regular stencil at every valence;
    /// interpolatory; three-ring matrix 6n+1).
    Butterfly,
    /// The modified butterfly scheme of Zorin, Schroder and Sweldens
    /// (interpolatory; three-ring matrix 6n+1).
    ModifiedButterfly,
}

impl SchemeKind {
    /// All known schemes.
    pub const ALL: &'static [SchemeKind] = &[
        SchemeKind::Nurds,
        SchemeKind::DooSabin,
        SchemeKind::CcVariant,
        SchemeKind::CatmullClark,
        SchemeKind::AdjustableCc,
        SchemeKind::Loop,
        SchemeKind::Sqrt3,
        SchemeKind::Butterfly,
        SchemeKind::ModifiedButterfly,
    ];

    /// Every known scheme's name, in [`SchemeKind::ALL`] order, joined by
    /// `sep` except the last two, which are joined by `last` when given
    /// (`names_or` for help texts: `"nurds, ..., adjustable-cc or loop"`).
    ///
    /// ```
    /// use subdiv_lab::schemes::SchemeKind;
    /// assert!(SchemeKind::names(", ").starts_with("nurds, doo-sabin, "));
    /// assert!(SchemeKind::names_or().ends_with(" or modified-butterfly"));
    /// ```
    pub fn names(sep: &str) -> String {
        let names: Vec<&str> = SchemeKind::ALL.iter().map(|k| k.name()).collect();
        names.join(sep)
    }

    /// Every known scheme's name, `"a, b, ... or z"` (help texts).
    pub fn names_or() -> String {
        let names: Vec<&str> = SchemeKind::ALL.iter().map(|k| k.name()).collect();
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => names.join(", "),
        }
    }

    /// The scheme's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            SchemeKind::Nurds => "nurds",
            SchemeKind::DooSabin => "doo-sabin",
            SchemeKind::CcVariant => "cc-variant",
            SchemeKind::CatmullClark => "catmull-clark",
            SchemeKind::AdjustableCc => "adjustable-cc",
            SchemeKind::Loop => "loop",
            SchemeKind::Sqrt3 => "sqrt3",
            SchemeKind::Butterfly => "butterfly",
            SchemeKind::ModifiedButterfly => "modified-butterfly",
        }
    }

    /// Whether the scheme takes knot intervals.
    pub fn takes_knots(self) -> bool {
        matches!(self, SchemeKind::Nurds)
    }

    /// Whether the scheme takes the shape parameter `c` (`--c`).
    pub fn takes_c(self) -> bool {
        matches!(self, SchemeKind::AdjustableCc)
    }

    /// Whether the scheme has the exact (rational) face-block certificate of
    /// sweeps' `exact_certificate` column (the Doo-Sabin family: rational
    /// weights for rational knots; math doc section 10).
    pub fn has_exact_certificate(self) -> bool {
        self.is_doo_sabin_family()
    }

    /// Whether the scheme belongs to the Catmull-Clark family ((2n+1) one-ring matrix).
    pub fn is_catmull_clark_family(self) -> bool {
        matches!(self, SchemeKind::CatmullClark | SchemeKind::AdjustableCc)
    }

    /// Whether the scheme is one of the triangle schemes without a ring of
    /// polynomial patches (sqrt3, butterfly, modified butterfly; math doc
    /// section 21).
    pub fn is_triangle_lattice_scheme(self) -> bool {
        matches!(
            self,
            SchemeKind::Sqrt3 | SchemeKind::Butterfly | SchemeKind::ModifiedButterfly
        )
    }

    /// Whether the scheme belongs to the Doo-Sabin family (4n x 4n `S_n` with face block).
    pub fn is_doo_sabin_family(self) -> bool {
        matches!(
            self,
            SchemeKind::Nurds | SchemeKind::DooSabin | SchemeKind::CcVariant
        )
    }
}

impl fmt::Display for SchemeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Error for an unknown scheme name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("unknown scheme {name:?} (known: {known})", name = .0, known = SchemeKind::names(", "))]
pub struct UnknownScheme(pub String);

impl FromStr for SchemeKind {
    type Err = UnknownScheme;
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        SchemeKind::ALL
            .iter()
            .copied()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownScheme(s.to_owned()))
    }
}
