//! The built-in families as [`Scheme`]s: the Doo-Sabin family (NURDS,
//! Doo-Sabin, the Catmull-Clark variant; face-centred, math doc sections 1-5),
//! the Catmull-Clark family (Catmull-Clark and the shape-adjustable scheme;
//! vertex-centred, math doc sections 6 and 8) and Loop (vertex-centred on
//! triangle meshes, math doc section 11).
//!
//! This impl is the one place where a [`LocalScheme`] is told apart by
//! family: the analysis engine only sees the capabilities, and each family's
//! rules stay in its module ([`doo_sabin`], [`catmull_clark`],
//! [`loop_subdivision`]).

use super::assembly::LocalMatrix;
use super::local::LocalScheme;
use super::scheme::{FourierSpectrum, RingPatches, Scheme, SpectralStructure};
use super::{catmull_clark, loop_subdivision, sqrt3};
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

    /// `"<name> n=<n>"`, and `"Loop n=<n>"` for Loop.
    fn label(&self) -> String {
        match self {
            LocalScheme::Loop { valence } => format!("Loop n={valence}"),
            _ => format!("{} n={}", self.name(), self.valence()),
        }
    }

    fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        self.matrix()
    }

    /// Loop, sqrt(3), butterfly and modified butterfly at valence 6, the
    /// Catmull-Clark family at valence 4 with the same `c` (its regular part
    /// is the tensor product of the `c` rule); none for the face-centred
    /// Doo-Sabin family.
    fn regular_configuration(&self) -> Option<Result<Box<dyn Scheme>>> {
        let boxed = |s: Result<LocalScheme<f64>>| s.map(|s| Box::new(s) as Box<dyn Scheme>);
        match self {
            LocalScheme::Loop { .. } => Some(boxed(LocalScheme::loop_subdivision(6))),
            LocalScheme::CatmullClark { .. } => Some(boxed(LocalScheme::catmull_clark(4))),
            LocalScheme::AdjustableCc { c, .. } => Some(boxed(LocalScheme::adjustable_cc(4, *c))),
            LocalScheme::Sqrt3 { .. }
            | LocalScheme::Butterfly { .. }
            | LocalScheme::ModifiedButterfly { .. } => Some(boxed(LocalScheme::from_kind_with_c(
                self.kind(),
                6,
                None,
                None,
            ))),
            _ => None,
        }
    }

    /// The same configuration over the rationals, from the exact values of
    /// its `f64` parameters (every finite `f64` is a dyadic rational): NURDS
    /// and the Catmull-Clark variant (rational knot weights), Catmull-Clark
    /// and the adjustable scheme (rational in `c` and `1/n`). Doo-Sabin's and
    /// Loop's weights contain `cos(2 pi j / n)`: only at n = 3, 4, 6 (Loop:
    /// [`loop_subdivision::matrix::two_ring_matrix_over`]).
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
            LocalScheme::Loop { valence } if matches!(valence, 3 | 4 | 6) => {
                LocalScheme::loop_subdivision(*valence)
            }
            // butterfly: rational weights at every valence; sqrt3 and the
            // modified butterfly where cos(2 pi / n) is rational
            LocalScheme::Butterfly { valence } => {
                LocalScheme::from_kind(crate::schemes::SchemeKind::Butterfly, *valence, None)
            }
            LocalScheme::Sqrt3 { valence } if matches!(valence, 3 | 4 | 6) => {
                LocalScheme::from_kind(crate::schemes::SchemeKind::Sqrt3, *valence, None)
            }
            LocalScheme::ModifiedButterfly { valence } if matches!(valence, 3 | 4 | 6) => {
                LocalScheme::from_kind(
                    crate::schemes::SchemeKind::ModifiedButterfly,
                    *valence,
                    None,
                )
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
    /// `3n` patches of the ring (math doc section 13.5). Loop: the two-ring
    /// matrix, which holds the ring's box-spline patches.
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

    /// Catmull-Clark family: [`catmull_clark::regular_part_eigenvalues`]
    /// (none for Loop, whose two-ring matrix holds its second-order part).
    fn regular_part_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        let c = self.shape_parameter()?;
        Some(Ok(catmull_clark::regular_part_eigenvalues(&c)
            .into_iter()
            .map(|x| Complex64::new(x, 0.0))
            .collect()))
    }

    /// Doo-Sabin family: the face weights `c` over the `P` columns (the other
    /// entries are zero; math doc section 4). Catmull-Clark family: the limit
    /// stencil over the one-ring (math doc section 6). Loop: over the one-ring
    /// (the two-ring entries are zero; math doc section 11).
    fn limit_stencil(&self) -> Option<Result<Vec<f64>>> {
        match self {
            LocalScheme::Loop { valence } => {
                return Some(loop_subdivision::limit_weights(*valence))
            }
            LocalScheme::Sqrt3 { valence } => return Some(sqrt3::limit_weights(*valence)),
            // interpolatory: the limit point is the vertex itself
            LocalScheme::Butterfly { valence } | LocalScheme::ModifiedButterfly { valence } => {
                let d = crate::schemes::tri_rings::ring_len(*valence, 3);
                let mut w = vec![0.0; d];
                w[0] = 1.0;
                return Some(Ok(w));
            }
            _ => {}
        }
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
        } else if self.kind().is_triangle_lattice_scheme() {
            SpectralStructure::Dense
        } else {
            SpectralStructure::Fourier
        }
    }

    fn fill_face_block(&self, out: &mut [f64]) -> Option<Result<()>> {
        self.kind()
            .is_doo_sabin_family()
            .then(|| self.fill_face_like(out))
    }

    /// The Catmull-Clark family and Loop: the closed-form Fourier blocks.
    /// The Doo-Sabin family has a face block: the spectral engine computes its
    /// structured spectrum ([`crate::spectral::structured::spectrum_of`]).
    fn structured_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        if let LocalScheme::Loop { valence } = self {
            return Some(loop_subdivision::fourier::spectrum(*valence));
        }
        let c = self.shape_parameter()?;
        Some(catmull_clark::fourier::spectrum(self.valence(), c))
    }

    /// Doo-Sabin family: the face-block kernel
    /// ([`classify_scheme`](crate::spectral::classify_scheme)). The
    /// Catmull-Clark family has no faster path than the dense one.
    /// Catmull-Clark family and Loop: the closed-form block eigenvalues
    /// ([`catmull_clark::fourier::block_eigenvalues`],
    /// [`loop_subdivision::fourier::block_eigenvalues`]).
    fn fourier_spectrum(&self) -> Option<Result<FourierSpectrum>> {
        let n = self.valence();
        if let LocalScheme::Loop { .. } = self {
            return Some(
                (0..n)
                    .map(|l| loop_subdivision::fourier::block_eigenvalues(n, l).map(|e| (l, e)))
                    .collect(),
            );
        }
        let c = self.shape_parameter()?;
        Some(
            (0..n)
                .map(|l| catmull_clark::fourier::block_eigenvalues(n, l, c).map(|e| (l, e)))
                .collect(),
        )
    }

    /// The Doo-Sabin family's biquadratic ring, the Catmull-Clark family's
    /// bicubic one with its shape parameter, Loop's quartic box-spline
    /// triangles of the two-ring.
    fn ring_patches(&self) -> Option<RingPatches<'_>> {
        if let LocalScheme::Loop { valence } = self {
            return Some(RingPatches::QuarticBoxSpline { valence: *valence });
        }
        if self.kind().is_triangle_lattice_scheme() {
            return None;
        }
        Some(match self.shape_parameter() {
            Some(c) => RingPatches::Bicubic {
                valence: self.valence(),
                c,
            },
            None => RingPatches::Biquadratic(self),
        })
    }

    /// sqrt3: its local matrix is two steps; the one-step matrix turns the
    /// ring by half a sector ([`sqrt3::one_step_matrix`]).
    fn one_step_matrix(&self) -> Option<(usize, Result<LocalMatrix<f64>>)> {
        match self {
            LocalScheme::Sqrt3 { valence } => {
                Some((sqrt3::STEPS, sqrt3::one_step_matrix(*valence)))
            }
            _ => None,
        }
    }

    /// [`LocalScheme::cost_model_of`] its kind.
    fn cost_model(&self) -> CostModel {
        LocalScheme::<f64>::cost_model_of(self.kind())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::{self, MEMORY_LIMIT_BYTES, TIME_LIMIT_SECONDS};
    use crate::knots::EdgeRatios;
    use crate::schemes::SchemeKind;

    /// A configuration of every built-in scheme (`c = 0.3` where it is needed).
    fn every_builtin(n: usize) -> Vec<LocalScheme<f64>> {
        SchemeKind::ALL
            .iter()
            .map(|&k| {
                LocalScheme::from_kind_with_c(k, n, None, k.takes_c().then_some(0.3)).unwrap()
            })
            .collect()
    }

    #[test]
    fn the_cost_model_by_kind_is_the_configurations_and_fits_its_matrix() {
        for s in every_builtin(5) {
            let m = LocalScheme::<f64>::cost_model_of(s.kind());
            assert_eq!(m, s.cost_model(), "{}", s.name());
            let d = s.local_matrix().unwrap().rows().len();
            assert_eq!(m.dimension(5), d as f64, "{}", s.name());
        }
    }

    /// Every constructor from a kind follows the rules of `choice` for every
    /// scheme and every combination of knots and `c`, and refuses with the
    /// part that is wrong (the mesh rules: `mesh::builtin`'s tests).
    /// (Planted: letting `check` accept `c` for catmull-clark fails here.)
    #[test]
    fn every_constructor_follows_the_choice_rules() {
        let skew = EdgeRatios::new(vec![0.3, 0.6, 0.5, 0.2, 0.7]).unwrap();
        for &kind in SchemeKind::ALL {
            for knots in [false, true] {
                for c in [false, true] {
                    let expect_ok = (!knots || kind.takes_knots()) && c == kind.takes_c();
                    let ratios = knots.then(|| skew.clone());
                    let c = c.then_some(0.3);
                    let b = LocalScheme::from_kind_with_c(kind, 5, ratios, c);
                    assert_eq!(b.is_ok(), expect_ok, "{kind} knots={knots} c={c:?}: {b:?}");
                    if let Err(crate::Error::InvalidParameter { name, .. }) = b {
                        assert_eq!(
                            name,
                            if knots && !kind.takes_knots() {
                                "knots"
                            } else {
                                "c"
                            }
                        );
                    }
                }
            }
        }
    }

    // The size limits over every built-in cost model.
    #[test]
    fn large_sizes_exceed_the_limits_and_small_ones_do_not() {
        for s in every_builtin(3) {
            let kind = s.kind();
            let model = s.cost_model();
            for structured in [false, true] {
                let big = budget::analyze(&model, 100_000, structured);
                assert!(big.bytes > MEMORY_LIMIT_BYTES, "{kind}");
                assert!(budget::analyze(&model, 20_000, structured).bytes > MEMORY_LIMIT_BYTES);
                assert!(budget::analyze(&model, 1000, structured).seconds > TIME_LIMIT_SECONDS);
                let small = budget::analyze(&model, 64, structured);
                assert!(small.within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
            }
            assert!(budget::matrix(&model, 100_000, false, false).bytes > MEMORY_LIMIT_BYTES);
            assert!(budget::matrix(&model, 64, false, true)
                .within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
        }
        // the CC one-ring at n = 100000 is a 320 GB matrix
        let cc = budget::analyze(
            &LocalScheme::<f64>::cost_model_of(SchemeKind::CatmullClark),
            100_000,
            false,
        );
        assert!(cc.bytes >= 8.0 * 200_001f64.powi(2));
        assert!(cc.what.contains("200001 x 200001"));
        let lp = budget::analyze(
            &LocalScheme::<f64>::cost_model_of(SchemeKind::Loop),
            100_000,
            false,
        );
        assert!(lp.what.contains("300001 x 300001"));
    }
}
