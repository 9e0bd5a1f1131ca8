//! The scheme abstraction: what a subdivision scheme provides so that the
//! whole toolkit (analysis, classification, contraction, characteristic maps,
//! sweeps, reports, the testing kit) runs on it (math doc section 12).
//!
//! A [`Scheme`] is one *local configuration*: a scheme with its parameters at
//! one valence (a face of `n` sides for face-centred schemes, a vertex of
//! valence `n` for vertex-centred ones). It must provide one thing, the local
//! subdivision matrix with labelled points ([`Scheme::local_matrix`], built
//! through the one assembly path [`Assembler`](crate::schemes::Assembler)); everything
//! else is an optional capability with a documented default, and the analysis
//! engine uses a capability when it is there and the dense general method when
//! it is not:
//!
//! | capability | default | used by |
//! |---|---|---|
//! | [`exact_local_matrix`](Scheme::exact_local_matrix) | none: no exact verdicts | `--exact` |
//! | [`second_order_matrix`](Scheme::second_order_matrix) | the local matrix | every verdict on eigenvalues beyond the subdominant pair (`mu`: the curvature) |
//! | [`exact_second_order_matrix`](Scheme::exact_second_order_matrix) | the exact local matrix | the curvature's exact certificate |
//! | [`regular_part_spectrum`](Scheme::regular_part_spectrum) | none: the second-order matrix adds no eigenvalues | `mu_regular_part`, the structured path above [`STRUCTURED_DENSE_MAX_DIM`](crate::curvature::STRUCTURED_DENSE_MAX_DIM) |
//! | [`limit_stencil`](Scheme::limit_stencil) | none: the limit weights are reported without a closed-form check | `analyze` |
//! | [`structured_spectrum`](Scheme::structured_spectrum) | none: only the dense path | `--path structured`, sweeps' `eigenvalues` |
//! | [`spectral_structure`](Scheme::spectral_structure) | [`SpectralStructure::Dense`] | which closed-form cross-checks apply; `FaceBlock`: the subdominant classification by the face-block kernel |
//! | [`face_contraction`](Scheme::face_contraction) | none: no Theorem 1 section | `analyze`, sweeps' `contraction` |
//! | [`characteristic_map`](Scheme::characteristic_map) | none: `no_charmap` | sweeps' `charmap`, reports |
//! | [`fourier_spectrum`](Scheme::fourier_spectrum) | none: the curvature's `mu_mode` is `null` | `analyze`'s `curvature` |
//! | [`cost_model`](Scheme::cost_model) | [`CostModel::dense`] at the local matrix's size | the work estimates of [`crate::budget`] |
//!
//! The built-in families implement it: [`LocalScheme`](crate::schemes::LocalScheme)
//! (NURDS, Doo-Sabin, the Catmull-Clark variant, Catmull-Clark and the
//! shape-adjustable scheme) and [`LoopScheme`](crate::schemes::loop_subdivision::LoopScheme).
//! A scheme defined outside the crate implements it the same way; see the
//! tutorial in `examples/own_scheme.rs` and the doctest below.
//!
//! Names become implementations in one place, [`registry`] (configurations,
//! cost models; the mesh rules in [`crate::mesh::builtin`]); the validation of
//! a scheme choice is [`choice`].
//! The front ends (`analyze`, `matrix`, `sweep`, `report`, `subdivide`, the
//! testing kit) dispatch there once and then only ask for capabilities.
//! Code that *is* one family's implementation lives in that family's modules,
//! and is reached only through the trait or the registry:
//!
//! * the Doo-Sabin family: [`crate::schemes::doo_sabin`]; its mesh
//!   refinement and limit points [`crate::mesh::refine`] and
//!   [`crate::mesh::limit`] (behind [`crate::mesh::rules::FaceSplit`]; the
//!   [`SchemeKind`](crate::schemes::SchemeKind) they take selects the member
//!   of the family, other schemes are refused); Theorem 1,
//!   [`crate::contraction`] (behind [`Scheme::face_contraction`]); the
//!   `9n`-point ring of [`crate::charmap`] (behind
//!   [`Scheme::characteristic_map`]); the exact face-block verdicts of
//!   [`crate::spectral::exact`] (`analyze --exact`, the sweeps'
//!   `exact_certificate`);
//! * the Catmull-Clark family: [`crate::schemes::catmull_clark`],
//!   [`crate::mesh::catmull_clark`], [`crate::charmap::catmull_clark`];
//! * Loop: [`crate::schemes::loop_subdivision`], its mesh refinement
//!   [`crate::mesh::loop_subdivision`].
//!
//! Studies of one particular scheme build the configurations they study
//! directly: [`crate::cc_study`], `curvature::tuning` and the `c` intervals
//! of [`crate::verify`] (the adjustable Catmull-Clark scheme), the ratio
//! boxes of `verify` (NURDS), [`crate::ccss_bound`] (Catmull-Clark).
//!
//! ```
//! use subdiv_lab::schemes::{Assembler, LocalMatrix, PointLabel, Role};
//! use subdiv_lab::Scheme;
//! use subdiv_lab::spectral::{analyze, AnalyzeOptions};
//!
//! /// Catmull-Clark-type one-ring rules with a user-chosen vertex weight.
//! #[derive(Debug)]
//! struct MyScheme { n: usize, alpha: f64 }
//!
//! impl Scheme for MyScheme {
//!     fn name(&self) -> &str { "my-scheme" }
//!     fn valence(&self) -> usize { self.n }
//!     fn local_matrix(&self) -> subdiv_lab::Result<LocalMatrix<f64>> {
//!         let n = self.n;
//!         let labels: Vec<PointLabel> = std::iter::once(PointLabel::new(Role::Vertex, 0))
//!             .chain((0..n).map(|i| PointLabel::new(Role::EdgeNeighbour, i)))
//!             .collect();
//!         let mut a = Assembler::square("my-scheme", n, labels);
//!         // vertex: (1 - alpha) v + alpha * mean of the neighbours
//!         a.add(0, 0, 1.0 - self.alpha);
//!         a.stencil(0, (0..n).map(|i| (1 + i, self.alpha / n as f64)));
//!         // edge points: (v + e_i) / 2
//!         for i in 0..n {
//!             a.stencil(1 + i, [(0, 0.5), (1 + i, 0.5)]);
//!         }
//!         a.finish()
//!     }
//! }
//!
//! let s = MyScheme { n: 5, alpha: 0.5 };
//! let r = analyze(&s, &AnalyzeOptions::default()).unwrap();
//! assert_eq!(r.scheme, "my-scheme");
//! assert!((r.eigenvalues[0][0] - 1.0).abs() < 1e-12);
//! ```

use crate::budget::CostModel;
use crate::charmap::figure::RingPlot;
use crate::charmap::report::{AnyPatchId, CharmapReport};
use crate::contraction::{Certificate, MeasureOptions, Measured};
use crate::error::Result;
use crate::scalar::Rational;
use crate::schemes::assembly::LocalMatrix;
use crate::spectral::classify::Subdominant;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::fmt;

mod builtin;
pub mod choice;
pub mod registry;

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

/// Theorem 1 evidence of a face-centred scheme (math doc section 5): the
/// certificate, the measured contraction and the face block whose spectrum
/// bounds the rate.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceContraction {
    /// The certificate (weights from the scheme's parameters, checked against the assembly).
    pub certificate: Certificate<f64>,
    /// The measured contraction of random control points.
    pub measured: Measured,
    /// The `n x n` central face block `A`.
    pub face_block: DMatrix<f64>,
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
    /// [`spectral_order`](crate::spectral::eigen::spectral_order); default none.
    fn structured_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        None
    }

    /// Theorem 1 evidence (face-centred schemes whose face contracts by 3/4;
    /// default none).
    fn face_contraction(&self, options: &MeasureOptions) -> Option<Result<FaceContraction>> {
        let _ = options;
        None
    }

    /// The characteristic-map check given the subdominant classification
    /// (default none: reported as `no_charmap`).
    fn characteristic_map(
        &self,
        subdominant: &Subdominant,
    ) -> Option<Result<CharmapReport<AnyPatchId>>> {
        let _ = subdominant;
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

    /// The characteristic-map check with the plot data of the ring and
    /// `levels - 1` further levels (`crate::charmap::figure::ring_plot`;
    /// `per_side` samples per patch side) for report figures (default none:
    /// [`characteristic_map`](Self::characteristic_map) without a plot).
    fn characteristic_plot(
        &self,
        subdominant: &Subdominant,
        levels: usize,
        per_side: usize,
    ) -> Option<Result<(CharmapReport<AnyPatchId>, Option<RingPlot>)>> {
        let _ = (subdominant, levels, per_side);
        None
    }
}
