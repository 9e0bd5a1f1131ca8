//! The [`Scheme`] trait: what one configuration of a subdivision scheme
//! provides (data only: matrices, blocks, stencils, spectra in closed form,
//! its ring of patches), so that every analysis runs on it (module docs of
//! [`crate::schemes`]; math doc section 12).

use super::assembly::LocalMatrix;
use super::local::LocalScheme;
use crate::budget::CostModel;
use crate::error::Result;
use crate::scalar::Rational;
use num_complex::Complex64;
use std::cmp::Ordering;
use std::fmt;

/// The spectrum by Fourier mode: `(l, eigenvalues of block l)` per frequency
/// ([`Scheme::fourier_spectrum`]).
pub type FourierSpectrum = Vec<(usize, Vec<Complex64>)>;

/// How a scheme's spectrum decomposes: which closed-form structure the
/// analysis may cross-check against (math doc sections 4, 6 and 11).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SpectralStructure {
    /// No known structure: the dense decomposition is the only path.
    Dense,
    /// Face-centred (Doo-Sabin type): the spectrum is that of the `n x n`
    /// central face block together with eigenvalues known in closed form
    /// (math doc section 4).
    FaceBlock,
    /// Rotationally symmetric (vertex-centred): the spectrum is the union of
    /// the Fourier blocks' spectra (math doc sections 6 and 11); the dense
    /// spectrum is compared with it (`fourier_deviation`).
    Fourier,
}

/// The crate's order of eigenvalues: non-increasing modulus, then
/// non-increasing real part, then non-increasing imaginary part (a total
/// order, so sorting is deterministic). [`Scheme::structured_spectrum`]
/// returns its eigenvalues in this order.
pub fn spectral_order(a: &Complex64, b: &Complex64) -> Ordering {
    b.norm_sqr()
        .total_cmp(&a.norm_sqr())
        .then(b.re.total_cmp(&a.re))
        .then(b.im.total_cmp(&a.im))
}

/// The ring of patches around the extraordinary point, by family: which
/// rules turn a vector over the local matrix's points (an eigenvector) into
/// the Bezier control nets of the ring (math doc sections 7, 8 and 11). The
/// analyses dispatch on it: the characteristic map ([`crate::charmap`]) and,
/// for the face-centred family, Theorem 1 ([`crate::contraction`]). A scheme
/// without a ring gets `no_charmap` and no Theorem 1 section.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RingPatches<'a> {
    /// The Doo-Sabin family (face-centred): one step makes the `9n` points
    /// of the extended configuration, which hold the `3n` biquadratic
    /// patches of the ring; the configuration's knot intervals give the
    /// B-spline-to-Bezier conversion (math doc section 7). Its central face
    /// contracts by `3/4` (Theorem 1, math doc section 5).
    Biquadratic(&'a LocalScheme<f64>),
    /// The Catmull-Clark family with shape parameter `c` (vertex-centred):
    /// the `n` bicubic-type patches over the `2n + 8` points of
    /// [`patch_matrix`](super::catmull_clark::patch_matrix) (math doc
    /// section 8).
    Bicubic {
        /// The valence `n`.
        valence: usize,
        /// The shape parameter (`1/2`: Catmull-Clark).
        c: f64,
    },
    /// Loop: the quartic box-spline triangles of the two-ring
    /// ([`tri_bezier`](super::loop_subdivision::tri_bezier); math doc
    /// section 11).
    QuarticBoxSpline {
        /// The valence `n`.
        valence: usize,
    },
}

/// One local configuration of a subdivision scheme (module docs: what is
/// required, what is optional, and who uses what).
///
/// Implementations must be deterministic: the same configuration gives the
/// same matrix bit for bit (sweeps re-evaluate rows on `--resume`).
pub trait Scheme: fmt::Debug + Send + Sync {
    /// The scheme's name in outputs (`scheme` field and column), e.g. `"loop"`.
    fn name(&self) -> &str;

    /// The valence `n`: the number of sides of the central face (face-centred
    /// schemes) or of edges at the central vertex (vertex-centred schemes).
    fn valence(&self) -> usize;

    /// A short human-readable label for figure legends (default `"<name> n=<n>"`).
    fn label(&self) -> String {
        format!("{} n={}", self.name(), self.valence())
    }

    /// The local subdivision matrix `S` with labelled rows and columns
    /// (`new = S old`), built through [`Assembler`](crate::schemes::Assembler). Square;
    /// its dominant eigenvalue is 1 for an affine-invariant scheme.
    fn local_matrix(&self) -> Result<LocalMatrix<f64>>;

    /// The same matrix in exact rational arithmetic, when the weights are
    /// rational (default: none).
    fn exact_local_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        None
    }

    /// The second-order neighbourhood matrix `S_2` (math doc section 13.5):
    /// square, closed under subdivision, and holding the support of the
    /// limit surface on the ring of patches around the extraordinary point
    /// (the control nets of the next level's ring are combinations of its
    /// points). Every verdict that depends on eigenvalues beyond the
    /// subdominant pair (`mu` of [`crate::curvature`]) is made on it; the
    /// classification and everything first-order stay on
    /// [`local_matrix`](Self::local_matrix).
    ///
    /// Contract: its points contain the local matrix's (the same subdominant
    /// pair), it is closed under one step (its new points are combinations
    /// of its old points) and it contains that support; a larger closed
    /// neighbourhood then adds only eigenvalues whose eigenvectors vanish on
    /// it. Default: the local matrix, which is right when the local
    /// matrix already holds that support (the Doo-Sabin family's `4n`
    /// points, Loop's two-ring). A scheme whose local matrix is smaller (the
    /// Catmull-Clark family's one-ring: the ring's bicubic-type patches
    /// reach the two-ring) must override it, and then
    /// [`exact_second_order_matrix`](Self::exact_second_order_matrix) and
    /// [`regular_part_spectrum`](Self::regular_part_spectrum) with it.
    fn second_order_matrix(&self) -> Result<LocalMatrix<f64>> {
        self.local_matrix()
    }

    /// [`second_order_matrix`](Self::second_order_matrix) in exact rational
    /// arithmetic (default: [`exact_local_matrix`](Self::exact_local_matrix)).
    fn exact_second_order_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        self.exact_local_matrix()
    }

    /// The eigenvalues [`second_order_matrix`](Self::second_order_matrix)
    /// has beyond those of the local matrix (the regular part of the ring of
    /// patches; math doc section 13.5), in closed form. Default none: the
    /// second-order matrix is the local matrix. Used to label `mu`
    /// (`mu_regular_part`) and, with
    /// [`structured_spectrum`](Self::structured_spectrum), for the structured
    /// path's second-order spectrum.
    fn regular_part_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        None
    }

    /// The closed-form limit stencil: the left eigenvector of `S` for 1 over
    /// the local matrix's columns, normalised to sum 1 (default: none; the
    /// analysis then reports the numerical one without a closed-form check).
    fn limit_stencil(&self) -> Option<Result<Vec<f64>>> {
        None
    }

    /// The weights `c` of the central face's limit point (face-centred
    /// schemes; default empty).
    fn face_weights(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Which closed-form spectral structure the scheme has (default
    /// [`SpectralStructure::Dense`]).
    fn spectral_structure(&self) -> SpectralStructure {
        SpectralStructure::Dense
    }

    /// Face-block schemes ([`SpectralStructure::FaceBlock`]): writes into
    /// `out` (column-major, `n x n`, zeroed by the caller) a matrix with
    /// constant row sums whose deflation by the constant vector has the
    /// spectrum of the central face block without its eigenvalue 1 (the face
    /// block itself, or for NURDS `M = (I + R)/4`, which differs from it by
    /// `1 c^T / 4`; math doc section 4). Default none.
    fn fill_face_block(&self, out: &mut [f64]) -> Option<Result<()>> {
        let _ = out;
        None
    }

    /// The whole spectrum of `S` by the scheme's structure (face block plus
    /// known eigenvalues, or Fourier blocks), sorted by
    /// [`spectral_order`]; default none.
    fn structured_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        None
    }

    /// The ring of patches the scheme's eigenvectors define ([`RingPatches`];
    /// default none: no characteristic map and no Theorem 1 section).
    fn ring_patches(&self) -> Option<RingPatches<'_>> {
        None
    }

    /// The same scheme at its regular valence (6 on triangle meshes, 4 on
    /// quad meshes), whose labelled local matrix holds the rules every point
    /// away from the extraordinary vertex follows: the generic
    /// characteristic-map certificate ([`crate::charmap::generic`]; math doc
    /// section 20) reads the regular mask from it. Default none (the
    /// certificate is then `indeterminate`).
    fn regular_configuration(&self) -> Option<Result<Box<dyn Scheme>>> {
        None
    }

    /// The spectrum by Fourier mode (rotationally symmetric schemes): one
    /// entry `(l, eigenvalues of block l)` per frequency `l = 0..n`, block 0
    /// first with its eigenvalue 1 first (default none: the dense spectrum
    /// carries no modes, and the curvature analysis reports `mu_mode: null`;
    /// math doc sections 6, 11 and 13).
    fn fourier_spectrum(&self) -> Option<Result<FourierSpectrum>> {
        None
    }

    /// For a scheme whose [`local_matrix`](Self::local_matrix) covers several
    /// subdivision steps because one step turns the ring (sqrt(3): two steps,
    /// math doc section 21): the number of steps and the one-step matrix,
    /// whose spectrum `analyze` reports beside the verdicts (which refer to
    /// the local matrix). Default none: the local matrix is one step.
    fn one_step_matrix(&self) -> Option<(usize, Result<LocalMatrix<f64>>)> {
        None
    }

    /// The work model of the heavy steps ([`crate::budget`]: the local
    /// matrix's dimension as a function of the valence and the constants of
    /// its analysis), so that a front end can estimate and refuse work before
    /// it starts. Default: [`CostModel::dense`] with the dimension of
    /// [`local_matrix`](Self::local_matrix) at this valence (which builds the
    /// matrix once: a scheme whose matrix is itself large at the valences
    /// users ask for should override it, as the built-in schemes do).
    fn cost_model(&self) -> CostModel {
        let n = self.valence().max(1);
        let d = self.local_matrix().map_or(0, |m| m.rows().len());
        CostModel::dense(d as f64 / n as f64, 0.0)
    }
}
