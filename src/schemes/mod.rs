//! Subdivision schemes: the scheme abstraction ([`Scheme`]), the built-in
//! families' rules and local matrices, scheme files ([`user`]), the names of
//! the built-ins ([`SchemeKind`]) and the one validator of a scheme choice
//! ([`choice`]). This is the rules layer: it returns data (matrices, blocks,
//! stencils, spectra in closed form, rings of patches) and imports no
//! analysis; the analyses ([`crate::spectral`], [`crate::charmap`],
//! [`crate::contraction`], [`crate::curvature`]) take a `&dyn Scheme`
//! (math doc section 12).
//!
//! A [`Scheme`] is one *local configuration*: a scheme with its parameters at
//! one valence (a face of `n` sides for face-centred schemes, a vertex of
//! valence `n` for vertex-centred ones). It must provide one thing, the local
//! subdivision matrix with labelled points ([`Scheme::local_matrix`], built
//! through the one assembly path [`Assembler`]); everything
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
//! | [`ring_patches`](Scheme::ring_patches) | none: `no_charmap`, no Theorem 1 section | the characteristic map ([`crate::charmap::check_classified`]: sweeps' `charmap`, reports) and Theorem 1 ([`crate::contraction::face_contraction`]: `analyze`, sweeps' `contraction`) |
//! | [`fourier_spectrum`](Scheme::fourier_spectrum) | none: the curvature's `mu_mode` is `null` | `analyze`'s `curvature` |
//! | [`cost_model`](Scheme::cost_model) | [`CostModel::dense`](crate::budget::CostModel::dense) at the local matrix's size | the work estimates of [`crate::budget`] |
//!
//! A built-in scheme has two names: [`SchemeKind`] says which one (a name,
//! no parameters), and a [`LocalScheme`] is one configuration of it (NURDS,
//! Doo-Sabin, the Catmull-Clark variant, Catmull-Clark, the shape-adjustable
//! scheme, Loop), which implements the trait. A scheme defined outside the
//! crate implements it the same way; see the tutorial in
//! `examples/own_scheme.rs` and the doctest below.
//!
//! Names become implementations through one constructor each:
//! [`LocalScheme::from_kind_with_c`] (configurations;
//! [`LocalScheme::cost_model_of`] the work model by kind) and
//! [`crate::mesh::builtin::mesh_rules`] (mesh rules); both apply the rules of
//! a scheme choice, [`choice`], once.
//! The front ends (`analyze`, `matrix`, `sweep`, `report`, `subdivide`, the
//! testing kit) dispatch there once and then only ask for capabilities.
//! Code that *is* one family's implementation lives in that family's modules,
//! and is reached only through the trait or those constructors:
//!
//! * the Doo-Sabin family: [`crate::schemes::doo_sabin`]; its mesh
//!   refinement and limit points [`crate::mesh::refine`] and
//!   [`crate::mesh::limit`] (behind [`crate::mesh::rules::FaceSplit`]; the
//!   [`SchemeKind`] they take selects the member
//!   of the family, other schemes are refused); Theorem 1,
//!   [`crate::contraction`] and the `9n`-point ring of [`crate::charmap`]
//!   (both behind [`RingPatches::Biquadratic`]); the exact face-block verdicts of
//!   [`crate::spectral::exact`] (`analyze --exact`, the sweeps'
//!   `exact_certificate`);
//! * the Catmull-Clark family: [`crate::schemes::catmull_clark`], its mesh
//!   refinement [`crate::mesh::catmull_clark`], its characteristic map
//!   [`crate::charmap::catmull_clark`] (behind [`RingPatches::Bicubic`]);
//! * Loop: [`crate::schemes::loop_subdivision`], its mesh refinement
//!   [`crate::mesh::loop_subdivision`], its characteristic map
//!   [`crate::charmap::loop_subdivision`] (behind
//!   [`RingPatches::QuarticBoxSpline`]).
//! * sqrt(3), butterfly and modified butterfly: [`crate::schemes::sqrt3`],
//!   [`crate::schemes::butterfly`], [`crate::schemes::modified_butterfly`]
//!   on the lattice rings of [`crate::schemes::tri_rings`]; their mesh
//!   refinement [`crate::mesh::tri_schemes`]; no ring of patches (`no_charmap`).
//!
//! Studies of one particular scheme build the configurations they study
//! directly: [`crate::cc_study`], `curvature::tuning` and the `c` intervals
//! of [`crate::verify`] (the adjustable Catmull-Clark scheme), the ratio
//! boxes of `verify` (NURDS), [`crate::ccss_bound`] (Catmull-Clark).
//!
//! ```
//! use subdiv_lab::schemes::{Assembler, LocalMatrix, PointLabel, Role, Scheme};
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

pub(crate) mod assembly;
mod builtin;
pub mod butterfly;
pub mod catmull_clark;
pub mod choice;
pub mod doo_sabin;
mod kind;
mod local;
pub mod loop_subdivision;
pub mod modified_butterfly;
mod scheme;
pub mod sqrt3;
pub mod tri_rings;
pub mod user;

pub use assembly::{Assembler, LocalMatrix, PointLabel, Role, ROW_SUM_TOL};
pub use kind::{SchemeKind, UnknownScheme};
pub use local::LocalScheme;
pub use scheme::{spectral_order, FourierSpectrum, RingPatches, Scheme, SpectralStructure};
