//! [`LocalScheme`]: one configuration of a built-in scheme, of the Doo-Sabin
//! family (NURDS, Doo-Sabin, the Catmull-Clark variant), of the Catmull-Clark
//! family (Catmull-Clark, the shape-adjustable scheme) or Loop: a scheme, a
//! valence and its parameters (math doc sections 1-4, 6, 8 and 11).
//!
//! A built-in scheme has two names: [`SchemeKind`] says which one it is (a
//! name, no parameters), and a [`LocalScheme`] is one configuration of it,
//! which implements the [`Scheme`](super::Scheme) trait like any scheme a user
//! writes. [`LocalScheme::from_kind_with_c`] is the one constructor from a
//! kind; it applies the rules of [`choice`](super::choice) once, and the named
//! constructors ([`LocalScheme::catmull_clark`], ...) go through it.
//!
//! ```
//! use subdiv_lab::knots::EdgeRatios;
//! use subdiv_lab::schemes::LocalScheme;
//! let s = LocalScheme::nurds(EdgeRatios::new(vec![0.3, 0.6, 0.5, 0.2, 0.7]).unwrap());
//! let m = s.matrix().unwrap();
//! assert_eq!(m.matrix().shape(), (20, 20));
//! assert_eq!(m.rows()[5].to_string(), "E0,1");
//! ```

use super::assembly::LocalMatrix;
use super::choice::{self, ChoiceError};
use super::kind::SchemeKind;
use super::{butterfly, catmull_clark, doo_sabin, loop_subdivision, modified_butterfly, sqrt3};
use crate::budget::CostModel;
use crate::error::{Error, Result};
use crate::knots::{face_weights, EdgeRatios};
use crate::scalar::{Rational, Scalar};
use nalgebra::DMatrix;

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
    /// Catmull-Clark around a vertex of valence n.
    CatmullClark {
        /// Valence.
        valence: usize,
    },
    /// The shape-adjustable Catmull-Clark scheme around a vertex of valence n.
    AdjustableCc {
        /// Valence.
        valence: usize,
        /// Shape parameter in [0, 1] (1/2 is Catmull-Clark).
        c: T,
    },
    /// Loop subdivision around a vertex of valence n whose neighbours are
    /// regular (the two-ring matrix, `3n + 1`).
    Loop {
        /// Valence.
        valence: usize,
    },
    /// Kobbelt's sqrt(3) scheme around a vertex of valence n (the two-step
    /// two-ring matrix, `3n + 1`; math doc section 21).
    Sqrt3 {
        /// Valence.
        valence: usize,
    },
    /// The butterfly scheme around a vertex of valence n (the three-ring
    /// matrix, `6n + 1`).
    Butterfly {
        /// Valence.
        valence: usize,
    },
    /// The modified butterfly scheme around a vertex of valence n (the
    /// three-ring matrix, `6n + 1`).
    ModifiedButterfly {
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
        Self::from_kind_with_c(SchemeKind::DooSabin, n, None, None)
    }

    /// Catmull-Clark variant of valence `n >= 3`.
    pub fn cc_variant(n: usize) -> Result<Self> {
        Self::from_kind_with_c(SchemeKind::CcVariant, n, None, None)
    }

    /// Catmull-Clark of valence `n >= 3`.
    pub fn catmull_clark(n: usize) -> Result<Self> {
        Self::from_kind_with_c(SchemeKind::CatmullClark, n, None, None)
    }

    /// The shape-adjustable Catmull-Clark scheme of valence `n >= 3`, `c` in `[0, 1]`.
    pub fn adjustable_cc(n: usize, c: T) -> Result<Self> {
        Self::from_kind_with_c(SchemeKind::AdjustableCc, n, None, Some(c))
    }

    /// Loop subdivision at a vertex of valence `n >= 3`.
    ///
    /// ```
    /// use subdiv_lab::schemes::{LocalScheme, Scheme};
    /// use subdiv_lab::spectral::{analyze, AnalyzeOptions};
    /// let s = LocalScheme::loop_subdivision(5).unwrap();
    /// let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
    /// let lambda = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / 5.0).cos();
    /// assert!((a.subdominant.lambda1.re - lambda).abs() < 1e-12);
    /// assert_eq!(a.eigenvalues.len(), 16);
    /// assert_eq!(s.label(), "Loop n=5");
    /// ```
    pub fn loop_subdivision(n: usize) -> Result<Self> {
        Self::from_kind_with_c(SchemeKind::Loop, n, None, None)
    }

    /// The configuration of `kind` at `valence` with optional edge ratios
    /// (`None`: uniform; non-uniform only for a scheme that takes knots) and
    /// the shape parameter `c` (required iff [`SchemeKind::takes_c`]): the
    /// rules of [`choice`](super::choice), then the family's own validation
    /// of the valence and `c`.
    ///
    /// ```
    /// use subdiv_lab::schemes::{LocalScheme, Scheme, SchemeKind};
    /// use subdiv_lab::spectral::classify_scheme;
    /// let s = LocalScheme::from_kind_with_c(SchemeKind::Loop, 5, None, None).unwrap();
    /// let sub = classify_scheme(&s).unwrap();
    /// let lambda = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / 5.0).cos();
    /// assert!((sub.lambda1.re - lambda).abs() < 1e-12);
    /// assert_eq!((s.kind(), s.name()), (SchemeKind::Loop, "loop"));
    /// assert!(LocalScheme::from_kind_with_c(SchemeKind::CatmullClark, 5, None, Some(0.3)).is_err());
    /// ```
    pub fn from_kind_with_c(
        kind: SchemeKind,
        valence: usize,
        ratios: Option<EdgeRatios<T>>,
        c: Option<T>,
    ) -> Result<Self> {
        let knots = ratios.as_ref().is_some_and(|r| !r.is_uniform());
        choice::check(kind, knots, c.is_some())
            .map_err(|e| e.into_error(c.as_ref().map(Scalar::to_text)))?;
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
            SchemeKind::DooSabin => {
                EdgeRatios::<T>::uniform(valence)?;
                Ok(LocalScheme::DooSabin { valence })
            }
            SchemeKind::CcVariant => {
                EdgeRatios::<T>::uniform(valence)?;
                Ok(LocalScheme::CcVariant { valence })
            }
            SchemeKind::CatmullClark => {
                catmull_clark::validate(valence, &T::frac(1, 2))?;
                Ok(LocalScheme::CatmullClark { valence })
            }
            SchemeKind::AdjustableCc => match c {
                Some(c) => {
                    catmull_clark::validate(valence, &c)?;
                    Ok(LocalScheme::AdjustableCc { valence, c })
                }
                None => Err(ChoiceError::NeedsC(kind).into_error(None)),
            },
            SchemeKind::Loop => {
                loop_subdivision::validate(valence)?;
                Ok(LocalScheme::Loop { valence })
            }
            SchemeKind::Sqrt3 => {
                loop_subdivision::validate(valence)?;
                Ok(LocalScheme::Sqrt3 { valence })
            }
            SchemeKind::Butterfly => {
                loop_subdivision::validate(valence)?;
                Ok(LocalScheme::Butterfly { valence })
            }
            SchemeKind::ModifiedButterfly => {
                loop_subdivision::validate(valence)?;
                Ok(LocalScheme::ModifiedButterfly { valence })
            }
        }
    }

    /// [`from_kind_with_c`](Self::from_kind_with_c) without a shape parameter.
    pub fn from_kind(
        kind: SchemeKind,
        valence: usize,
        ratios: Option<EdgeRatios<T>>,
    ) -> Result<Self> {
        Self::from_kind_with_c(kind, valence, ratios, None)
    }

    /// The scheme kind.
    pub fn kind(&self) -> SchemeKind {
        match self {
            LocalScheme::Nurds(_) => SchemeKind::Nurds,
            LocalScheme::DooSabin { .. } => SchemeKind::DooSabin,
            LocalScheme::CcVariant { .. } => SchemeKind::CcVariant,
            LocalScheme::CatmullClark { .. } => SchemeKind::CatmullClark,
            LocalScheme::AdjustableCc { .. } => SchemeKind::AdjustableCc,
            LocalScheme::Loop { .. } => SchemeKind::Loop,
            LocalScheme::Sqrt3 { .. } => SchemeKind::Sqrt3,
            LocalScheme::Butterfly { .. } => SchemeKind::Butterfly,
            LocalScheme::ModifiedButterfly { .. } => SchemeKind::ModifiedButterfly,
        }
    }

    /// The work model of a built-in scheme, by kind (that of its
    /// configurations, which does not depend on the parameters): for the
    /// estimates a front end makes before any configuration exists (a sweep's
    /// plan).
    ///
    /// ```
    /// use subdiv_lab::schemes::{LocalScheme, SchemeKind};
    /// assert_eq!(LocalScheme::<f64>::cost_model_of(SchemeKind::Nurds).dimension(5), 20.0);
    /// assert_eq!(LocalScheme::<f64>::cost_model_of(SchemeKind::Loop).dimension(5), 16.0);
    /// ```
    pub fn cost_model_of(kind: SchemeKind) -> CostModel {
        match kind {
            SchemeKind::Nurds | SchemeKind::DooSabin | SchemeKind::CcVariant => {
                doo_sabin::COST_MODEL
            }
            SchemeKind::CatmullClark | SchemeKind::AdjustableCc => catmull_clark::COST_MODEL,
            SchemeKind::Loop => loop_subdivision::COST_MODEL,
            // dense only: the two-ring (3n+1) and the three-ring (6n+1)
            SchemeKind::Sqrt3 => CostModel::dense(3.0, 1.0),
            SchemeKind::Butterfly | SchemeKind::ModifiedButterfly => CostModel::dense(6.0, 1.0),
        }
    }

    /// Valence of the extraordinary face.
    pub fn valence(&self) -> usize {
        match self {
            LocalScheme::Nurds(r) => r.valence(),
            LocalScheme::DooSabin { valence } | LocalScheme::CcVariant { valence } => *valence,
            LocalScheme::CatmullClark { valence }
            | LocalScheme::AdjustableCc { valence, .. }
            | LocalScheme::Loop { valence }
            | LocalScheme::Sqrt3 { valence }
            | LocalScheme::Butterfly { valence }
            | LocalScheme::ModifiedButterfly { valence } => *valence,
        }
    }

    /// The edge ratios used by the E/C rows (1/2 for the uniform schemes, and
    /// for the Catmull-Clark family and Loop, which have no knot intervals).
    pub fn ratios(&self) -> EdgeRatios<T> {
        match self {
            LocalScheme::Nurds(r) => r.clone(),
            LocalScheme::DooSabin { valence }
            | LocalScheme::CcVariant { valence }
            | LocalScheme::CatmullClark { valence }
            | LocalScheme::AdjustableCc { valence, .. }
            | LocalScheme::Loop { valence }
            | LocalScheme::Sqrt3 { valence }
            | LocalScheme::Butterfly { valence }
            | LocalScheme::ModifiedButterfly { valence } => {
                EdgeRatios::uniform(*valence).expect("valence validated at construction")
            }
        }
    }

    /// Face weights `c` (the left eigenvector of the face block for 1; `1/n` for
    /// the uniform schemes). Empty for the Catmull-Clark family and Loop
    /// (vertex-centred: there is no central face; see
    /// [`catmull_clark::limit::limit_stencil`]).
    pub fn face_weights(&self) -> Vec<T> {
        match self {
            LocalScheme::Nurds(r) => face_weights(r),
            LocalScheme::CatmullClark { .. }
            | LocalScheme::AdjustableCc { .. }
            | LocalScheme::Loop { .. }
            | LocalScheme::Sqrt3 { .. }
            | LocalScheme::Butterfly { .. }
            | LocalScheme::ModifiedButterfly { .. } => Vec::new(),
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
            LocalScheme::CatmullClark { .. }
            | LocalScheme::AdjustableCc { .. }
            | LocalScheme::Loop { .. }
            | LocalScheme::Sqrt3 { .. }
            | LocalScheme::Butterfly { .. }
            | LocalScheme::ModifiedButterfly { .. } => Err(Error::NotApplicable {
                scheme: self.kind().name().to_owned(),
                operation: "the face block (a Doo-Sabin-family notion)",
            }),
        }
    }

    /// The shape parameter `c` of the Catmull-Clark family (`1/2` for
    /// Catmull-Clark); `None` for the Doo-Sabin family.
    pub fn shape_parameter(&self) -> Option<T> {
        match self {
            LocalScheme::CatmullClark { .. } => Some(T::frac(1, 2)),
            LocalScheme::AdjustableCc { c, .. } => Some(c.clone()),
            _ => None,
        }
    }

    /// The full local subdivision matrix (`S_n`, 4n x 4n, for the Doo-Sabin
    /// family; the (2n+1) one-ring matrix for the Catmull-Clark family; the
    /// (3n+1) two-ring matrix for Loop, over the rationals only at the
    /// valences with rational weights, n = 3, 4, 6; the two-step (3n+1)
    /// two-ring matrix for sqrt3 (rational at n = 3, 4, 6); the (6n+1)
    /// three-ring matrix for the butterfly schemes (butterfly: rational at
    /// every n; modified butterfly at n = 3, 4, 6)).
    pub fn matrix(&self) -> Result<LocalMatrix<T>> {
        match self {
            LocalScheme::Loop { valence } => {
                loop_subdivision::matrix::two_ring_matrix_over(*valence)
            }
            LocalScheme::Sqrt3 { valence } => sqrt3::local_matrix_on(*valence, sqrt3::RING),
            LocalScheme::Butterfly { valence } => {
                butterfly::local_matrix_on(*valence, butterfly::RING)
            }
            LocalScheme::ModifiedButterfly { valence } => {
                modified_butterfly::local_matrix_on(*valence, modified_butterfly::RING)
            }
            LocalScheme::CatmullClark { valence } => {
                catmull_clark::one_ring_named(self.kind().name(), *valence, &T::frac(1, 2))
            }
            LocalScheme::AdjustableCc { valence, c } => {
                catmull_clark::one_ring_named(self.kind().name(), *valence, c)
            }
            _ => doo_sabin::assemble(self.kind().name(), &self.face_block()?, &self.ratios()),
        }
    }
}

impl LocalScheme<Rational> {
    /// The most bits a knot parameter needs: numerator plus denominator of
    /// the largest NURDS edge ratio (0 for the schemes without knot
    /// intervals), which sizes the exact path's work estimate
    /// ([`crate::budget::analyze_exact`]).
    pub fn parameter_bits(&self) -> u64 {
        match self {
            LocalScheme::Nurds(r) => r
                .as_slice()
                .iter()
                .map(|x| x.numer().bits() + x.denom().bits())
                .max()
                .unwrap_or(0),
            _ => 0,
        }
    }
}

impl LocalScheme<f64> {
    /// Fills `f` (column major, `n x n`) with a matrix whose deflated block is `B`:
    /// `M = (I + R)/4` for NURDS and the CC variant, the face block for original
    /// Doo-Sabin ([`Scheme::fill_face_block`](super::Scheme::fill_face_block)).
    pub(crate) fn fill_face_like(&self, f: &mut [f64]) -> Result<()> {
        let n = self.valence();
        match self {
            LocalScheme::DooSabin { .. } => {
                let den = 4.0 * n as f64;
                for j in 0..n {
                    for i in 0..n {
                        f[i + j * n] = if i == j {
                            (n as f64 + 5.0) / den
                        } else {
                            let k = doo_sabin::fold(i + n - j, n);
                            (3.0 + 2.0 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos())
                                / den
                        };
                    }
                }
            }
            LocalScheme::Nurds(ratios) => {
                doo_sabin::fill_m(n, ratios.as_slice(), ratios.complement(), f)
            }
            LocalScheme::CcVariant { .. } => {
                // Uniform ratios 1/2 (no allocation): diagonal 1/2, neighbours 1/8.
                for i in 0..n {
                    let (prev, next) = doo_sabin::neighbours(i, n);
                    f[i + i * n] = 0.25 * 2.0;
                    f[i + prev * n] += 0.125;
                    f[i + next * n] += 0.125;
                }
            }
            _ => {
                return Err(Error::NotApplicable {
                    scheme: self.kind().name().to_owned(),
                    operation: "the face block (a Doo-Sabin-family notion)",
                })
            }
        }
        Ok(())
    }

    /// The legend label reports generate for this configuration: NURDS with
    /// its knots (`NURDS n=3, r=(0.300, 0.600, 0.500)` up to `n = 6`,
    /// `NURDS n=8, non-uniform` beyond, `NURDS n=5, uniform`), the adjustable
    /// scheme with its `c`, the others by name and valence. A non-empty
    /// `suffix` (how random knots were drawn, `", random knots <= 4"`)
    /// replaces the description of non-uniform knots.
    ///
    /// ```
    /// use subdiv_lab::knots::EdgeRatios;
    /// use subdiv_lab::schemes::LocalScheme;
    /// let s = LocalScheme::nurds(EdgeRatios::new(vec![0.3, 0.6, 0.5]).unwrap());
    /// assert_eq!(s.legend_label(""), "NURDS n=3, r=(0.300, 0.600, 0.500)");
    /// assert_eq!(LocalScheme::<f64>::doo_sabin(5).unwrap().legend_label(""), "doo-sabin n=5");
    /// ```
    pub fn legend_label(&self, suffix: &str) -> String {
        let n = self.valence();
        match self {
            LocalScheme::Nurds(r) if r.is_uniform() => format!("NURDS n={n}, uniform"),
            LocalScheme::Nurds(r) if suffix.is_empty() && n <= 6 => {
                let parts: Vec<String> = r.as_slice().iter().map(|x| format!("{x:.3}")).collect();
                format!("NURDS n={n}, r=({})", parts.join(", "))
            }
            LocalScheme::Nurds(_) if suffix.is_empty() => format!("NURDS n={n}, non-uniform"),
            LocalScheme::Nurds(_) => format!("NURDS n={n}{suffix}"),
            LocalScheme::AdjustableCc { c, .. } => format!("adjustable-cc n={n}, c={c}"),
            LocalScheme::Loop { .. } => format!("Loop n={n}"),
            other => format!("{} n={n}", other.kind()),
        }
    }
}
