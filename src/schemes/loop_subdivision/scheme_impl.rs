//! Loop subdivision as a [`Scheme`]: the two-ring matrix, the Fourier-block
//! spectrum, the limit stencil and the ring of quartic box-spline patches of
//! this module behind the scheme abstraction (math doc sections 11 and 12).

use super::{fourier, limit_weights, matrix, validate};
use crate::budget::CostModel;
use crate::error::Result;
use crate::scalar::Rational;
use crate::schemes::assembly::{Assembler, LocalMatrix};
use crate::schemes::scheme::{FourierSpectrum, RingPatches, Scheme, SpectralStructure};
use num_complex::Complex64;

/// Denominator of every entry of the two-ring matrix at the valences whose
/// `cos(2 pi / n)` is rational, `n` in {3, 4, 6} **\[derived\]**: the
/// vertex weights are `beta_3 = 3/16`, `beta_4 = 31/256`, `beta_6 = 1/16`
/// (so `1 - n beta_n` = 7/16, 132/256, 10/16) and the fixed weights are 3/8,
/// 1/8, 5/8 and 1/16: all multiples of 1/256.
pub const EXACT_DENOMINATOR: i64 = 256;

/// How far an `f64` entry of the two-ring matrix may lie from its multiple of
/// `1/EXACT_DENOMINATOR` at `n` in {3, 4, 6}. The `f64` rules differ from the
/// exact weights by a few rounding errors (`~1e-16`); `1e-12` is far above
/// that and far below half the grid step (`1/512`), so rounding every entry to
/// the grid recovers the exact matrix, and an entry outside it is an error,
/// never a silently wrong exact matrix.
pub const EXACT_ROUNDING_CHECK: f64 = 1e-12;

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

    /// The exact two-ring matrix at `n` in {3, 4, 6}, where every weight is
    /// a multiple of `1/256` (`EXACT_DENOMINATOR` of this module): the `f64`
    /// matrix with every entry rounded to that grid (each checked within
    /// `EXACT_ROUNDING_CHECK`; rows then sum to 1 exactly). `None` at other
    /// valences (irrational weights). This lets the curvature verdict certify
    /// `mu = lambda^2` exactly at `n` = 4 and 6 (math doc section 13).
    fn exact_local_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        if !matches!(self.n, 3 | 4 | 6) {
            return None;
        }
        Some(self.local_matrix().and_then(|m| {
            let d = EXACT_DENOMINATOR as f64;
            let mut a = Assembler::<Rational>::new(
                m.scheme(),
                self.n,
                m.rows().to_vec(),
                m.cols().to_vec(),
            );
            let s = m.matrix();
            for i in 0..s.nrows() {
                for j in 0..s.ncols() {
                    let k = (s[(i, j)] * d).round();
                    if (s[(i, j)] - k / d).abs() > EXACT_ROUNDING_CHECK {
                        return Err(crate::Error::Numerical {
                            routine: "exact Loop matrix",
                            reason: format!(
                                "entry ({i}, {j}) = {} is not a multiple of 1/{EXACT_DENOMINATOR}",
                                s[(i, j)]
                            ),
                        });
                    }
                    if k != 0.0 {
                        a.add(
                            i,
                            j,
                            Rational::new((k as i64).into(), EXACT_DENOMINATOR.into()),
                        );
                    }
                }
            }
            a.finish()
        }))
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

    fn fourier_spectrum(&self) -> Option<Result<FourierSpectrum>> {
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

    /// The quartic box-spline triangles of the two-ring (math doc section 11).
    fn ring_patches(&self) -> Option<RingPatches<'_>> {
        Some(RingPatches::QuarticBoxSpline { valence: self.n })
    }
}
