//! Loop subdivision as a [`Scheme`]: the two-ring matrix, the Fourier-block
//! spectrum, the limit stencil and the certified characteristic map of this
//! module behind the scheme abstraction (math doc sections 11 and 12).

use super::{charmap, fourier, limit_weights, matrix, validate};
use crate::budget::CostModel;
use crate::charmap::report::{AnyPatchId, CharmapReport};
use crate::error::Result;
use crate::scheme::{Scheme, SpectralStructure};
use crate::schemes::assembly::LocalMatrix;
use crate::spectral::classify::{Subdominant, SubdominantClass};
use num_complex::Complex64;

/// One Loop configuration: a vertex of valence `n >= 3` whose neighbours are
/// regular.
///
/// ```
/// use subdiv_lab::schemes::loop_subdivision::LoopScheme;
/// use subdiv_lab::spectral::{analyze, AnalyzeOptions};
/// let a = analyze(&LoopScheme::new(5).unwrap(), &AnalyzeOptions::default()).unwrap();
/// let lambda = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / 5.0).cos();
/// assert!((a.subdominant.lambda1.re - lambda).abs() < 1e-12);
/// assert_eq!(a.eigenvalues.len(), 16);
/// assert!(a.fourier_deviation.unwrap() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoopScheme {
    n: usize,
}

impl LoopScheme {
    /// Loop at valence `n >= 3`.
    pub fn new(n: usize) -> Result<Self> {
        validate(n)?;
        Ok(Self { n })
    }
}

impl Scheme for LoopScheme {
    fn name(&self) -> &str {
        "loop"
    }

    fn valence(&self) -> usize {
        self.n
    }

    fn label(&self) -> String {
        format!("Loop n={}", self.n)
    }

    fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        matrix::two_ring_matrix(self.n)
    }

    /// Over the one-ring (the two-ring entries are zero; math doc section 11).
    fn limit_stencil(&self) -> Option<Result<Vec<f64>>> {
        Some(limit_weights(self.n))
    }

    fn spectral_structure(&self) -> SpectralStructure {
        SpectralStructure::Fourier
    }

    fn structured_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        Some(fourier::spectrum(self.n))
    }

    fn fourier_spectrum(&self) -> Option<Result<crate::scheme::FourierSpectrum>> {
        Some(
            (0..self.n)
                .map(|l| fourier::block_eigenvalues(self.n, l).map(|e| (l, e)))
                .collect(),
        )
    }

    /// [`super::COST_MODEL`].
    fn cost_model(&self) -> CostModel {
        super::COST_MODEL
    }

    /// The certified ring of [`charmap::check`] when the classification is
    /// standard (Loop's eigenstructure is standard at every valence: the
    /// subdominant pair is the `k = +-1` Fourier eigenvalue); otherwise no
    /// map, with the class that prevents it.
    fn characteristic_map(
        &self,
        subdominant: &Subdominant,
    ) -> Option<Result<CharmapReport<AnyPatchId>>> {
        if subdominant.class != SubdominantClass::Standard {
            return Some(Ok(CharmapReport::no_map(
                subdominant.class.name(),
                "Loop's ring is built on the standard eigenstructure",
            )));
        }
        Some(charmap::check(self.n).map(|r| {
            r.map_patches(|p| AnyPatchId::Other {
                sector: p.sector,
                slot: p.kind.slot(),
                prefix: "T",
            })
        }))
    }
}
