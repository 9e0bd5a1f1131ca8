//! Subdivision schemes and their local subdivision matrices.
//!
//! Every scheme builds its matrices through [`assembly::Assembler`], the one
//! assembly path; each family lives in its own module:
//!
//! * [`doo_sabin`]: NURDS `S_n` (4n x 4n) and its face block, original
//!   Doo-Sabin, and the Catmull-Clark variant (math doc sections 1-4).
//!
//! [`LocalScheme`] names one configuration (scheme + valence + parameters) and
//! is what the spectral analysis, sweeps and reports take.
//!
//! ```
//! use subdiv_lab::knots::EdgeRatios;
//! use subdiv_lab::schemes::LocalScheme;
//! let s = LocalScheme::nurds(EdgeRatios::new(vec![0.3, 0.6, 0.5, 0.2, 0.7]).unwrap());
//! let m = s.matrix().unwrap();
//! assert_eq!(m.matrix().shape(), (20, 20));
//! assert_eq!(m.rows()[5].to_string(), "E0,1");
//! ```

pub mod assembly;
pub mod doo_sabin;

pub use assembly::{Assembler, LocalMatrix, PointLabel, Role};

use crate::error::{Error, Result};
use crate::knots::{face_weights, EdgeRatios};
use crate::scalar::Scalar;
use nalgebra::DMatrix;
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
}

impl SchemeKind {
    /// All known schemes.
    pub const ALL: &'static [SchemeKind] = &[
        SchemeKind::Nurds,
        SchemeKind::DooSabin,
        SchemeKind::CcVariant,
    ];

    /// The scheme's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            SchemeKind::Nurds => "nurds",
            SchemeKind::DooSabin => "doo-sabin",
            SchemeKind::CcVariant => "cc-variant",
        }
    }

    /// Whether the scheme takes knot intervals.
    pub fn takes_knots(self) -> bool {
        matches!(self, SchemeKind::Nurds)
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
#[error("unknown scheme {0:?} (known: nurds, doo-sabin, cc-variant)")]
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

/// One local configuration: a scheme, a valence and the scheme's parameters.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LocalScheme<T = f64> {
    /// NURDS around an n-sided face with the given edge ratios.
    Nurds(EdgeRatios<T>),
    /// Original Doo-Sabin around an n-sided face.
    DooSabin {
        /// Valence.
        valence: usize,
    },
    /// The Catmull-Clark variant of Doo-Sabin around an n-sided face.
    CcVariant {
        /// Valence.
        valence: usize,
    },
}

impl<T: Scalar> LocalScheme<T> {
    /// NURDS with these ratios.
    pub fn nurds(ratios: EdgeRatios<T>) -> Self {
        LocalScheme::Nurds(ratios)
    }

    /// Original Doo-Sabin of valence `n >= 3`.
    pub fn doo_sabin(n: usize) -> Result<Self> {
        EdgeRatios::<T>::uniform(n)?;
        Ok(LocalScheme::DooSabin { valence: n })
    }

    /// Catmull-Clark variant of valence `n >= 3`.
    pub fn cc_variant(n: usize) -> Result<Self> {
        EdgeRatios::<T>::uniform(n)?;
        Ok(LocalScheme::CcVariant { valence: n })
    }

    /// A configuration of `kind` with optional ratios (required iff the scheme takes knots;
    /// `None` means uniform for NURDS).
    pub fn from_kind(
        kind: SchemeKind,
        valence: usize,
        ratios: Option<EdgeRatios<T>>,
    ) -> Result<Self> {
        if let Some(r) = &ratios {
            if r.valence() != valence {
                return Err(Error::CountMismatch {
                    what: "edge ratios (one per edge)",
                    expected: valence,
                    got: r.valence(),
                });
            }
        }
        match kind {
            SchemeKind::Nurds => Ok(LocalScheme::Nurds(match ratios {
                Some(r) => r,
                None => EdgeRatios::uniform(valence)?,
            })),
            SchemeKind::DooSabin | SchemeKind::CcVariant if ratios.as_ref().is_some_and(|r| !r.is_uniform()) => {
                Err(Error::InvalidParameter {
                    name: "knots",
                    value: kind.name().to_owned(),
                    reason: "this scheme has no knot intervals; use --scheme nurds for non-uniform knots",
                })
            }
            SchemeKind::DooSabin => Self::doo_sabin(valence),
            SchemeKind::CcVariant => Self::cc_variant(valence),
        }
    }

    /// The scheme kind.
    pub fn kind(&self) -> SchemeKind {
        match self {
            LocalScheme::Nurds(_) => SchemeKind::Nurds,
            LocalScheme::DooSabin { .. } => SchemeKind::DooSabin,
            LocalScheme::CcVariant { .. } => SchemeKind::CcVariant,
        }
    }

    /// Valence of the extraordinary face.
    pub fn valence(&self) -> usize {
        match self {
            LocalScheme::Nurds(r) => r.valence(),
            LocalScheme::DooSabin { valence } | LocalScheme::CcVariant { valence } => *valence,
        }
    }

    /// The edge ratios used by the E/C rows (1/2 for the uniform schemes).
    pub fn ratios(&self) -> EdgeRatios<T> {
        match self {
            LocalScheme::Nurds(r) => r.clone(),
            LocalScheme::DooSabin { valence } | LocalScheme::CcVariant { valence } => {
                EdgeRatios::uniform(*valence).expect("valence validated at construction")
            }
        }
    }

    /// Face weights `c` (the left eigenvector of the face block for 1; `1/n` for
    /// the uniform schemes).
    pub fn face_weights(&self) -> Vec<T> {
        match self {
            LocalScheme::Nurds(r) => face_weights(r),
            LocalScheme::DooSabin { valence } | LocalScheme::CcVariant { valence } => {
                vec![T::frac(1, *valence as i64); *valence]
            }
        }
    }

    /// The n x n face block (the `P` rows restricted to the `P` columns).
    pub fn face_block(&self) -> Result<DMatrix<T>> {
        match self {
            LocalScheme::Nurds(r) => Ok(doo_sabin::face_block_from(r, &face_weights(r))),
            LocalScheme::DooSabin { valence } => doo_sabin::doo_sabin_face_block(*valence),
            LocalScheme::CcVariant { .. } => Ok(doo_sabin::face_block_from(
                &self.ratios(),
                &self.face_weights(),
            )),
        }
    }

    /// The full local subdivision matrix (`S_n`, 4n x 4n, for the Doo-Sabin family).
    pub fn matrix(&self) -> Result<LocalMatrix<T>> {
        doo_sabin::assemble(self.kind().name(), &self.face_block()?, &self.ratios())
    }
}
