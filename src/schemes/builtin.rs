//! The built-in families as [`Scheme`]s: the Doo-Sabin family (NURDS,
//! Doo-Sabin, the Catmull-Clark variant; face-centred, math doc sections 1-5)
//! and the Catmull-Clark family (Catmull-Clark and the shape-adjustable
//! scheme; vertex-centred, math doc sections 6 and 8).
//!
//! This impl is the one place where a [`LocalScheme`] is told apart by
//! family: the analysis engine only sees the capabilities.

use super::assembly::LocalMatrix;
use super::local::LocalScheme;
use super::scheme::{FourierSpectrum, RingPatches, Scheme, SpectralStructure};
use super::{catmull_clark, doo_sabin};
use crate::budget::CostModel;
use crate::error::Result;
use crate::scalar::{f64_to_rational, Rational};
use num_complex::Complex64;

impl Scheme for LocalScheme<f64> {
    fn name(&self) -> &str {
        self.kind().name()
    }

    fn valence(&self) -> usize {
        LocalScheme::valence(self)
    }

    fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        self.matrix()
    }

    /// The same configuration over the rationals, from the exact values of
    /// its `f64` parameters (every finite `f64` is a dyadic rational): NURDS
    /// and the Catmull-Clark variant (rational knot weights), Catmull-Clark
    /// and the adjustable scheme (rational in `c` and `1/n`). Doo-Sabin's
    /// weights contain `cos(2 pi j / n)`: none.
    fn exact_local_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        let exact: Result<LocalScheme<Rational>> = match self {
            LocalScheme::Nurds(r) => r
                .as_slice()
                .iter()
                .map(|&x| {
                    f64_to_rational(x).ok_or_else(|| crate::Error::InvalidParameter {
                        name: "knots",
                        value: x.to_string(),
                        reason: "not a finite number",
                    })
                })
                .collect::<Result<Vec<_>>>()
                .and_then(|v| Ok(LocalScheme::nurds(crate::knots::EdgeRatios::new(v)?))),
            // Original Doo-Sabin is rational where cos(2 pi / n) is (n = 3, 4, 6).
            LocalScheme::DooSabin { valence } if matches!(valence, 3 | 4 | 6) => {
                LocalScheme::doo_sabin(*valence)
            }
            LocalScheme::CcVariant { valence } => LocalScheme::cc_variant(*valence),
            LocalScheme::CatmullClark { valence } => LocalScheme::catmull_clark(*valence),
            LocalScheme::AdjustableCc { valence, c } => match f64_to_rational(*c) {
                Some(q) => LocalScheme::adjustable_cc(*valence, q),
                None => return None,
            },
            _ => return None,
        };
        Some(exact.and_then(|s| s.matrix()))
    }

    /// Catmull-Clark family: the `(2n + 8)` patch matrix
    /// ([`catmull_clark::patch_matrix`]: one patch's support, which holds the
    /// control nets of the next level's regular sub-patches; the `n` patches
    /// around the vertex are rotations of it). The Doo-Sabin family: the
    /// local `4n` matrix, whose one step makes the `9n` points that hold the
    /// `3n` patches of the ring (math doc section 13.5).
    fn second_order_matrix(&self) -> Result<LocalMatrix<f64>> {
        match self.shape_parameter() {
            Some(c) => catmull_clark::patch_named(self.kind().name(), self.valence(), &c),
            None => self.matrix(),
        }
    }

    /// The patch matrix over the rationals where
    /// [`exact_local_matrix`](Scheme::exact_local_matrix) has the one-ring
    /// (the exact value of `c`), else as that.
    fn exact_second_order_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        match self {
            LocalScheme::CatmullClark { valence } => Some(catmull_clark::patch_named(
                self.kind().name(),
                *valence,
                &Rational::new(1.into(), 2.into()),
            )),
            LocalScheme::AdjustableCc { valence, c } => f64_to_rational(*c)
                .map(|q| catmull_clark::patch_named(self.kind().name(), *valence, &q)),
            _ => self.exact_local_matrix(),
        }
    }

    /// Catmull-Clark family: [`catmull_clark::regular_part_eigenvalues`].
    fn regular_part_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        let c = self.shape_parameter()?;
        Some(Ok(catmull_clark::regular_part_eigenvalues(&c)
            .into_iter()
            .map(|x| Complex64::new(x, 0.0))
            .collect()))
    }

    /// Doo-Sabin family: the face weights `c` over the `P` columns (the other
    /// entries are zero; math doc section 4). Catmull-Clark family: the limit
    /// stencil over the one-ring (math doc section 6).
    fn limit_stencil(&self) -> Option<Result<Vec<f64>>> {
        Some(match self.shape_parameter() {
            Some(c) => catmull_clark::limit::limit_stencil(self.valence(), &c),
            None => Ok(LocalScheme::face_weights(self)),
        })
    }

    fn face_weights(&self) -> Vec<f64> {
        LocalScheme::face_weights(self)
    }

    fn spectral_structure(&self) -> SpectralStructure {
        if self.kind().is_doo_sabin_family() {
            SpectralStructure::FaceBlock
        } else {
            SpectralStructure::Fourier
        }
    }

    fn fill_face_block(&self, out: &mut [f64]) -> Option<Result<()>> {
        self.kind()
            .is_doo_sabin_family()
            .then(|| self.fill_face_like(out))
    }

    /// The Catmull-Clark family: the closed-form Fourier blocks. The
    /// Doo-Sabin family has a face block: the spectral engine computes its
    /// structured spectrum ([`crate::spectral::structured::spectrum_of`]).
    fn structured_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        let c = self.shape_parameter()?;
        Some(catmull_clark::fourier::spectrum(self.valence(), c))
    }

    /// Doo-Sabin family: the face-block kernel
    /// ([`classify_scheme`](crate::spectral::classify_scheme)). The
    /// Catmull-Clark family has no faster path than the dense one.
    /// Catmull-Clark family: the closed-form block eigenvalues
    /// ([`catmull_clark::fourier::block_eigenvalues`]).
    fn fourier_spectrum(&self) -> Option<Result<FourierSpectrum>> {
        let c = self.shape_parameter()?;
        let n = self.valence();
        Some(
            (0..n)
                .map(|l| catmull_clark::fourier::block_eigenvalues(n, l, c).map(|e| (l, e)))
                .collect(),
        )
    }

    /// The Doo-Sabin family's biquadratic ring, the Catmull-Clark family's
    /// bicubic one with its shape parameter.
    fn ring_patches(&self) -> Option<RingPatches<'_>> {
        Some(match self.shape_parameter() {
            Some(c) => RingPatches::Bicubic {
                valence: self.valence(),
                c,
            },
            None => RingPatches::Biquadratic(self),
        })
    }

    /// [`doo_sabin::COST_MODEL`] or [`catmull_clark::COST_MODEL`].
    fn cost_model(&self) -> CostModel {
        match self {
            LocalScheme::Nurds(_)
            | LocalScheme::DooSabin { .. }
            | LocalScheme::CcVariant { .. } => doo_sabin::COST_MODEL,
            LocalScheme::CatmullClark { .. } | LocalScheme::AdjustableCc { .. } => {
                catmull_clark::COST_MODEL
            }
        }
    }
}
