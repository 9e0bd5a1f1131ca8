//! The certified characteristic map of Loop subdivision at valence `n`
//! (math doc section 11; the method of math doc section 7).
//!
//! **Eigenstructure.** By the Fourier blocks ([`fourier`](crate::schemes::loop_subdivision::fourier)) the
//! two-ring matrix has the simple eigenvalue 1, the double subdominant
//! eigenvalue `lambda = 3/8 + cos(2 pi/n)/4` (frequencies 1 and `n - 1`, two
//! independent eigenvectors) and every other eigenvalue strictly smaller in
//! modulus: the standard case of Reif's criterion, for every `n >= 3`.
//!
//! **The ring.** The eigenvector pair `(x_cos, x_sin)` on the two-ring
//! ([`subdominant_eigenvectors`]) is orthonormalised into a
//! [`PlanarBasis`] (whose Stewart bound gives the entry-wise error of the
//! basis), and one Loop step ([`extended_matrix`]) maps it to
//! the `6n + 1` level-1 points. In sector `i` (the triangle `v, e_i, e_{i+1}`)
//! the level-1 triangles at `e_i`, in the middle and at `e_{i+1}` have only
//! valence-6 corners, so each is a regular patch whose 12-point net
//! ([`REGULAR_NET`](crate::schemes::loop_subdivision::tri_bezier::REGULAR_NET)) lies among those points; the fourth
//! sub-triangle (at `v`) is the next level's irregular patch and not part of
//! the ring. [`LoopRing`] converts the `3n` nets to quartic triangular Bezier
//! form ([`BOX_SPLINE_TO_BEZIER`](crate::schemes::loop_subdivision::tri_bezier::BOX_SPLINE_TO_BEZIER)). The next ring is `lambda`
//! times this one, so the ring decides the whole map.
//!
//! **Regularity.** The Jacobian of each patch is a degree-6 triangular
//! Bernstein polynomial ([`PlanarTri::jacobian`](crate::schemes::loop_subdivision::tri_bezier::PlanarTri::jacobian), 28 coefficients). If
//! `sigma c > E` for all its coefficients (`sigma` the orientation, the sign
//! of the total signed area; `E` the error bound of [`TriErrorModel`]) the
//! patch is certified; otherwise it is split into four ([`TriBezier::split4`])
//! and the pieces are tested, up to [`MAX_DEPTH`] levels and [`MAX_PIECES`]
//! pieces. A corner coefficient (an exact value) or a centroid value,
//! evaluated directly from the derivatives, below `-E_eval` is a witness of
//! non-regularity; pieces left undecided make the verdict indeterminate.
//!
//! **Injectivity.** The outer boundary of the ring (per sector the edges
//! `g_i -> f_i -> g_{i+1}` of the level-1 net, two quartic curves) must have
//! the certified winding number 1 around the origin
//! ([`winding_number`]) once the plane is oriented
//! so that the Jacobian is positive; regular plus winding 1 gives an
//! injective map (math doc section 7). The inner boundary (the edges
//! `e_i -> e_{i+1}`) is checked as well.
//!
//! ```
//! use subdiv_lab::charmap::Verdict;
//! use subdiv_lab::charmap::loop_subdivision::check;
//! let r = check(5).unwrap();
//! assert_eq!(r.verdict, Verdict::C1Standard);
//! assert_eq!(r.winding_number, Some(1));
//! ```

use super::regularity::{gamma, DomainPoint, Regularity, RegularityVerdict};
use super::verdict::{assemble_report, propagated_error};
use super::winding::winding_number;
use super::{CharmapReport, Eigenstructure, PlanarBasis};
use crate::error::Result;
use crate::schemes::loop_subdivision::check_size;
use crate::schemes::loop_subdivision::fourier::{spectrum, subdominant_eigenvectors};
use crate::schemes::loop_subdivision::matrix::{extended_matrix, two_ring_matrix};
use crate::schemes::loop_subdivision::ring::{LoopPatchId, LoopRing, DEGREE};
use crate::schemes::loop_subdivision::tri_bezier::{self, PlanarTri, TriBezier, SPLIT4};
use num_complex::Complex64;

/// Maximum split depth of the regularity test per patch (pieces with sides
/// `2^-8` of the patch's).
pub const MAX_DEPTH: u32 = 8;

/// Maximum number of pieces examined per ring.
pub const MAX_PIECES: usize = 50_000;

/// The floating-point error model of the Jacobian coefficients of quartic
/// triangular patches **\[derived\]**.
///
/// Inputs: `delta` bounds the error of every coordinate of every Bezier
/// control point; `md` is the largest magnitude of a coefficient of
/// `x_s, x_t, y_s, y_t`.
///
/// * A derivative coefficient `4 (b' - b)` is off by at most
///   `eps_d = 8 delta + 2 u md` (the data, one subtraction, one product).
/// * A Jacobian coefficient is a difference of two convex combinations
///   (product weights `M(alpha) M(beta) / M(gamma)`, non-negative, sum 1) of
///   products `f g` of derivative coefficients, and
///   `|f^ g^ - f g| <= 2 eps_d md + eps_d^2`: propagated error
///   `4 eps_d md + 2 eps_d^2`. Rounding: each product coefficient sums at
///   most 10 terms, each formed with 3 roundings (the weight, two products):
///   `gamma_13 md^2`; with the final subtraction at most `2 gamma_14 md^2`.
/// * Splitting into four ([`TriBezier::split4`]) forms each coefficient of
///   the degree-6 piece by 6 de Casteljau levels with weights `0, 1/2, 1`
///   (exact products, one rounded addition per level): each split level adds
///   at most `gamma_6 cmax`; we charge `2 gamma_6 cmax` per level.
/// * A direct evaluation at a point (witnesses): each derivative value is a
///   de Casteljau evaluation of degree 3 (three levels of three products and
///   two additions with non-negative weights): off by at most
///   `e = eps_d + gamma_18 (md + eps_d)`; the determinant then by
///   `4 e md + 2 e^2 + 2 gamma_3 (md + e)^2`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TriErrorModel {
    /// Error bound of the Bezier control points (absolute, per coordinate).
    pub delta: f64,
    /// Largest derivative coefficient magnitude.
    pub md: f64,
}

impl TriErrorModel {
    fn eps_d(&self) -> f64 {
        2.0 * DEGREE as f64 * self.delta + 2.0 * gamma(1) * self.md
    }

    /// Bound on the error of a Jacobian coefficient before splitting.
    pub fn coefficient_bound(&self) -> f64 {
        let e = self.eps_d();
        4.0 * e * self.md + 2.0 * e * e + 2.0 * gamma(14) * self.md * self.md
    }

    /// Bound after `depth` split levels, for coefficients of magnitude at most `cmax`.
    pub fn subdivided_bound(&self, depth: u32, cmax: f64) -> f64 {
        self.coefficient_bound() + 2.0 * depth as f64 * gamma(2 * DEGREE - 2) * cmax
    }

    /// Bound on a directly evaluated Jacobian value.
    pub fn evaluation_bound(&self) -> f64 {
        let e = self.eps_d() + gamma(18) * (self.md + self.eps_d());
        4.0 * e * self.md + 2.0 * e * e + 2.0 * gamma(3) * (self.md + e) * (self.md + e)
    }
}

/// A piece of a patch under test: patch index, Jacobian over the piece, its
/// corners in the patch's `(s, t)`, depth.
struct Piece {
    patch: usize,
    jac: TriBezier,
    corners: [(f64, f64); 3],
    depth: u32,
}

fn map_corners(c: [(f64, f64); 3], sub: [(f64, f64); 3]) -> [(f64, f64); 3] {
    sub.map(|(a, b)| {
        let u = 1.0 - a - b;
        (
            u * c[0].0 + a * c[1].0 + b * c[2].0,
            u * c[0].1 + a * c[1].1 + b * c[2].1,
        )
    })
}

/// Checks the sign of the Jacobian on every patch of `ring`; `delta` bounds
/// the error of the patches' Bezier control points (see [`TriErrorModel`]).
pub fn check_regularity(ring: &LoopRing, delta: f64) -> Regularity<LoopPatchId> {
    let patches: Vec<(LoopPatchId, &PlanarTri)> =
        ring.patches().iter().map(|(id, p)| (*id, p)).collect();
    // a ring has 3n >= 9 patches
    check_tri_patches(&patches, delta).unwrap_or_else(|_| unreachable!("ring without patches"))
}

/// Checks the sign of the Jacobian on a set of quartic triangular patches
/// (a Loop ring, or the ring of a boundary sector: math doc 18.4); `delta`
/// bounds the error of their Bezier control points (see
/// [`TriErrorModel`]). An empty set is an error.
pub fn check_tri_patches<P: Copy>(
    patches: &[(P, &PlanarTri)],
    delta: f64,
) -> Result<Regularity<P>> {
    if patches.is_empty() {
        return Err(crate::error::Error::CountMismatch {
            what: "patches for the regularity check",
            expected: 1,
            got: 0,
        });
    }
    let jac: Vec<TriBezier> = patches.iter().map(|(_, p)| p.jacobian()).collect();
    let mut md = 0.0f64;
    for (_, p) in patches {
        for d in [p.x.deriv_s(), p.x.deriv_t(), p.y.deriv_s(), p.y.deriv_t()] {
            md = md.max(d.max_abs());
        }
    }
    let model = TriErrorModel { delta, md };
    let cmax = jac.iter().map(TriBezier::max_abs).fold(0.0, f64::max);
    let area: f64 = jac
        .iter()
        .map(|j| j.coeffs().iter().sum::<f64>() / j.coeffs().len() as f64)
        .sum();
    let sigma: f64 = if area < 0.0 { -1.0 } else { 1.0 };
    let scale = if cmax > 0.0 { cmax } else { 1.0 };
    let mut min_coeff = f64::INFINITY;
    let mut min_location = DomainPoint {
        patch: patches[0].0,
        s: 0.0,
        t: 0.0,
    };
    for ((id, _), j) in patches.iter().zip(&jac) {
        let d = j.degree() as f64;
        for (c, (_, a, b)) in j.coeffs().iter().zip(tri_bezier::multi_indices(j.degree())) {
            if sigma * c < min_coeff {
                min_coeff = sigma * c;
                min_location = DomainPoint {
                    patch: *id,
                    s: a as f64 / d,
                    t: b as f64 / d,
                };
            }
        }
    }
    let eval_bound = model.evaluation_bound();
    let mut out = Regularity::initial(
        sigma,
        min_coeff,
        min_location,
        model.coefficient_bound(),
        cmax,
    );
    if out.verdict == RegularityVerdict::Indeterminate {
        return Ok(out);
    }
    let unit = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    let mut work: Vec<Piece> = jac
        .into_iter()
        .enumerate()
        .map(|(k, j)| Piece {
            patch: k,
            jac: j,
            corners: unit,
            depth: 0,
        })
        .collect();
    while let Some(piece) = work.pop() {
        let (id, patch) = (&patches[piece.patch].0, &patches[piece.patch].1);
        out.pieces += 1;
        out.max_depth = out.max_depth.max(piece.depth);
        let bound = model.subdivided_bound(piece.depth, cmax);
        let lo = piece
            .jac
            .coeffs()
            .iter()
            .map(|c| sigma * c)
            .fold(f64::INFINITY, f64::min);
        if lo > bound {
            continue;
        }
        let hopeless = bound.is_nan() || bound >= piece.jac.max_abs();
        // witnesses: the corners (exact values) and the centroid, evaluated directly
        let d = piece.jac.degree();
        let corner_coeffs = [
            piece.jac.coeff(d, 0, 0),
            piece.jac.coeff(0, d, 0),
            piece.jac.coeff(0, 0, d),
        ];
        let c = piece.corners;
        let centroid = (
            (c[0].0 + c[1].0 + c[2].0) / 3.0,
            (c[0].1 + c[1].1 + c[2].1) / 3.0,
        );
        let mut candidates: Vec<(f64, f64)> = corner_coeffs
            .iter()
            .zip(c)
            .filter(|(v, _)| sigma * **v < -bound)
            .map(|(_, p)| p)
            .collect();
        candidates.push(centroid);
        for (s, t) in candidates {
            let v = sigma * patch.jacobian_at(s, t);
            if v < -eval_bound {
                out.verdict = RegularityVerdict::NotRegular;
                out.witness = Some((DomainPoint { patch: *id, s, t }, v / scale));
                return Ok(out);
            }
        }
        if hopeless || piece.depth >= MAX_DEPTH || out.pieces + work.len() + 4 > MAX_PIECES {
            out.verdict = RegularityVerdict::Indeterminate;
            out.undecided.get_or_insert(DomainPoint {
                patch: *id,
                s: c[0].0,
                t: c[0].1,
            });
            continue;
        }
        for (sub, q) in piece.jac.split4().into_iter().zip(SPLIT4) {
            work.push(Piece {
                patch: piece.patch,
                jac: sub,
                corners: map_corners(c, q),
                depth: piece.depth + 1,
            });
        }
    }
    Ok(out)
}

/// Regularity, winding numbers and verdict of a ring whose Bezier control
/// points are accurate to `delta` (absolute). The verdict follows the rules
/// of [`crate::charmap`] for the standard eigenstructure: `C1 (standard;
/// Reif)` iff regular and the outer boundary winds once.
pub fn check_ring(ring: &LoopRing, delta: f64) -> CharmapReport<LoopPatchId> {
    let reg = check_regularity(ring, delta);
    let oriented;
    let r = if reg.orientation < 0 {
        oriented = ring.mirrored();
        &oriented
    } else {
        ring
    };
    let winding = winding_number(&r.outer_boundary(), delta);
    let inner = winding_number(&r.inner_boundary(), delta);
    assemble_report(reg, winding, inner, delta, Eigenstructure::Standard)
}

/// The characteristic ring of valence `n` with its planar basis and the
/// error bound of its Bezier control points.
#[derive(Clone, Debug)]
pub struct PreparedLoopRing {
    /// The ring (in the orthonormal coordinates of [`PreparedLoopRing::basis`]).
    pub ring: LoopRing,
    /// The planar basis on the `3n + 1` two-ring points.
    pub basis: PlanarBasis,
    /// Absolute error bound of the Bezier control points ([`point_error`]).
    pub point_error: f64,
}

/// Error bound of the ring's Bezier control points **\[derived\]**: the
/// extended matrix has absolute row sums `rho` and at most 6 nonzeros per
/// row, so the `6n + 1` level-1 points are off by at most
/// `rho vector_error + gamma_7 rho max|w|` ([`crate::charmap`]'s propagated
/// error); the box-spline conversion (weights `k/24 >= 0` summing to 1)
/// keeps that and adds `gamma_13 rho max|w|`.
pub fn point_error(ext: &nalgebra::DMatrix<f64>, basis: &PlanarBasis) -> f64 {
    let (e, pmax) = propagated_error(ext, basis);
    e + gamma(13) * pmax
}

/// The dense working set of [`prepare_ring`] in `f64` entries: the two-ring
/// and extended matrices and the `2 (3n - 1)`-square Kronecker matrix of the
/// subspace bound (twice, with its SVD).
fn working_set(n: usize) -> u128 {
    let d = 3 * n as u128 + 1;
    let k = 2 * (d - 2);
    d * d + (2 * d - 1) * d + 2 * k * k
}

/// Builds the characteristic ring of valence `n >= 3` (see the module docs).
pub fn prepare_ring(n: usize) -> Result<PreparedLoopRing> {
    check_size(n, working_set(n), "characteristic map")?;
    let s = two_ring_matrix(n)?.into_matrix();
    let ext = extended_matrix(n)?.into_matrix();
    let (lambda, [xc, xs]) = subdominant_eigenvectors(n)?;
    // distance of the pair from the rest of the spectrum (closed form; the
    // pair sits at positions 1 and 2 of the ordered spectrum)
    let spec = spectrum(n)?;
    let gap = (1.0 - lambda).min(lambda - spec[3].norm());
    let basis = PlanarBasis::new(
        &s,
        Eigenstructure::Standard,
        [Complex64::new(lambda, 0.0); 2],
        &xc,
        &xs,
        gap,
    )?;
    let pts: Vec<[f64; 2]> = (0..ext.nrows())
        .map(|i| {
            let row = ext.row(i);
            [
                row.iter().zip(&basis.w1).map(|(a, b)| a * b).sum(),
                row.iter().zip(&basis.w2).map(|(a, b)| a * b).sum(),
            ]
        })
        .collect();
    let ring = LoopRing::from_points(n, &pts)?;
    let delta = point_error(&ext, &basis);
    Ok(PreparedLoopRing {
        ring,
        basis,
        point_error: delta,
    })
}

/// The certified characteristic-map check of Loop subdivision at valence
/// `n >= 3`: [`prepare_ring`], then [`check_ring`].
pub fn check(n: usize) -> Result<CharmapReport<LoopPatchId>> {
    let p = prepare_ring(n)?;
    Ok(check_ring(&p.ring, p.point_error))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::charmap::Verdict;
    use crate::schemes::loop_subdivision::matrix::extended_row_a;
    use crate::schemes::loop_subdivision::ring::{net_indices, LoopPatchKind};
    use crate::schemes::loop_subdivision::tri_bezier::PlanarTri;
    use crate::schemes::loop_subdivision::TwoRing;

    #[test]
    fn valences_3_to_12_are_certified_c1() {
        for n in 3..=12 {
            let r = check(n).unwrap();
            assert_eq!(r.verdict, Verdict::C1Standard, "n = {n}: {r:?}");
            assert_eq!(r.winding_number, Some(1));
            assert_eq!(r.inner_winding_number, Some(1));
            let reg = r.regularity.as_ref().unwrap();
            assert_eq!(reg.verdict, RegularityVerdict::Regular);
            assert!(reg.min_coeff > reg.relative_error_bound, "n = {n}");
            // the unsplit coefficients already certify every patch
            assert_eq!((reg.pieces, reg.max_depth), (3 * n, 0), "n = {n}");
            assert!(
                r.point_error > 0.0 && r.point_error < 1e-10,
                "n = {n}: {}",
                r.point_error
            );
        }
    }

    #[test]
    fn large_valences_are_certified_too() {
        for n in [16, 24, 32] {
            let r = check(n).unwrap();
            assert_eq!(r.verdict, Verdict::C1Standard, "n = {n}");
            let reg = r.regularity.as_ref().unwrap();
            assert_eq!(reg.max_depth, 0, "n = {n}");
        }
    }

    #[test]
    fn valence_six_ring_is_an_affine_image_of_the_lattice() {
        // the subdominant eigenvectors at n = 6 are linear functions: every
        // Jacobian coefficient of every patch is the same constant
        let p = prepare_ring(6).unwrap();
        let jac: Vec<f64> = p
            .ring
            .patches()
            .iter()
            .flat_map(|(_, q)| q.jacobian().coeffs().to_vec())
            .collect();
        let c0 = jac[0];
        assert!(c0.abs() > 1e-3);
        for c in &jac {
            assert!((c - c0).abs() < 1e-12 * c0.abs(), "{c} vs {c0}");
        }
        let reg = check_regularity(&p.ring, p.point_error);
        assert_eq!(reg.pieces, 18);
        assert!((reg.min_coeff - 1.0).abs() < 1e-12);
    }

    #[test]
    fn an_error_bound_above_the_data_is_indeterminate() {
        let p = prepare_ring(5).unwrap();
        let r = check_ring(&p.ring, 10.0);
        assert!(
            matches!(r.verdict, Verdict::Indeterminate { .. }),
            "{:?}",
            r.verdict
        );
        assert_eq!(r.regular(), None);
        let r = check_ring(&p.ring, f64::INFINITY);
        assert!(matches!(r.verdict, Verdict::Indeterminate { .. }));
    }

    #[test]
    fn a_mirrored_ring_winds_minus_once() {
        let p = prepare_ring(7).unwrap();
        let sigma = check_regularity(&p.ring, p.point_error).orientation;
        let positive = if sigma < 0 {
            p.ring.mirrored()
        } else {
            p.ring.clone()
        };
        let m = positive.mirrored();
        assert_eq!(
            winding_number(&positive.outer_boundary(), p.point_error),
            Some(1)
        );
        assert_eq!(winding_number(&m.outer_boundary(), p.point_error), Some(-1));
        assert_eq!(winding_number(&m.inner_boundary(), p.point_error), Some(-1));
        // the check orients the plane first: still C1
        assert_eq!(check_ring(&m, p.point_error).verdict, Verdict::C1Standard);
        assert_eq!(check_regularity(&positive, p.point_error).orientation, 1);
        assert_eq!(check_regularity(&m, p.point_error).orientation, -1);
    }

    #[test]
    fn a_broken_map_is_not_certified() {
        let p = prepare_ring(6).unwrap();
        // flip sector 0: its three patches mirrored
        let flipped: Vec<(LoopPatchId, PlanarTri)> = p
            .ring
            .patches()
            .iter()
            .map(|(id, q)| {
                (
                    *id,
                    if id.sector == 0 {
                        q.mirrored()
                    } else {
                        q.clone()
                    },
                )
            })
            .collect();
        let r = check_ring(&LoopRing::from_patches(flipped).unwrap(), p.point_error);
        assert_eq!(r.verdict, Verdict::NotRegular);
        let (w, v) = r.regularity.unwrap().witness.unwrap();
        assert_eq!(w.patch.sector, 0);
        assert!(v < 0.0);
        // the frequency-2 eigenvector pair at n = 8 gives a ring that is
        // regular but winds twice (the map of a non-subdominant mode)
        let n = 8;
        let r2 = TwoRing::new(n).unwrap();
        let ext = extended_matrix(n).unwrap();
        let theta = 2.0 * std::f64::consts::PI / n as f64;
        // the frequency-2 analogue of the subdominant eigenvectors
        let lam2 = 0.375 + 0.25 * (2.0 * theta).cos();
        let c2 = (2.0 * theta).cos();
        let gw =
            (0.625 + 0.125 * c2 + 3.0 * (1.0 + c2) / (8.0 * (8.0 * lam2 - 1.0))) / (lam2 - 0.0625);
        let fw = 3.0 / (8.0 * lam2 - 1.0);
        let mk = |f: fn(f64) -> f64| {
            let mut x = vec![0.0; r2.len()];
            for i in 0..n {
                let (a, b) = (f(2.0 * theta * i as f64), f(2.0 * theta * (i + 1) as f64));
                x[r2.e(i)] = a;
                x[r2.g(i)] = gw * a;
                x[r2.f(i)] = fw * (a + b);
            }
            x
        };
        let (xc, xs) = (mk(f64::cos), mk(f64::sin));
        let s = two_ring_matrix(n).unwrap();
        for x in [&xc, &xs] {
            let xv = nalgebra::DVector::from_vec(x.clone());
            assert!((s.matrix() * &xv - &xv * lam2).norm() < 1e-13);
        }
        let m = ext.matrix();
        let pts: Vec<[f64; 2]> = (0..m.nrows())
            .map(|i| {
                let row = m.row(i);
                [
                    row.iter().zip(&xc).map(|(a, b)| a * b).sum(),
                    row.iter().zip(&xs).map(|(a, b)| a * b).sum(),
                ]
            })
            .collect();
        let r = check_ring(&LoopRing::from_points(n, &pts).unwrap(), 1e-13);
        assert_eq!(r.verdict, Verdict::NotInjective { winding: 2 });
        assert_eq!(r.inner_winding_number, Some(2));
    }

    /// Arbitrary data in [-1/2, 1/2) (the crate's one RNG, [`crate::rng`]).
    fn random(len: usize, seed: u64) -> Vec<f64> {
        let mut rng = crate::rng::SplitMix64::new(seed);
        (0..len).map(|_| rng.uniform(-0.5, 0.5)).collect()
    }

    /// A ring of arbitrary two-ring data (first coordinate random, second zero).
    fn data_ring(n: usize, seed: u64) -> (LoopRing, Vec<f64>) {
        let ext = extended_matrix(n).unwrap();
        let x = nalgebra::DVector::from_vec(random(3 * n + 1, seed));
        let lvl1 = ext.matrix() * x;
        let pts: Vec<[f64; 2]> = lvl1.iter().map(|v| [*v, 0.0]).collect();
        (
            LoopRing::from_points(n, &pts).unwrap(),
            lvl1.iter().copied().collect(),
        )
    }

    #[test]
    fn ring_patches_join_with_c1_within_and_across_sectors() {
        for n in [3, 4, 5, 6, 9] {
            for seed in 0..3 {
                let (ring, _) = data_ring(n, 31 * seed + n as u64);
                let p = |i: usize, k: usize| &ring.patches()[3 * (i % n) + k].1.x;
                // value and lattice gradient of patch k of sector i at lattice point x (sector frame)
                let at = |i: usize, k: usize, x: (f64, f64)| {
                    let f = p(i, k);
                    let (st, sign) = match k {
                        0 => ((x.0 - 1.0, x.1), 1.0),
                        1 => ((1.0 - x.0, 1.0 - x.1), -1.0),
                        _ => ((x.0, x.1 - 1.0), 1.0),
                    };
                    (
                        f.eval(st.0, st.1),
                        sign * f.deriv_s().eval(st.0, st.1),
                        sign * f.deriv_t().eval(st.0, st.1),
                    )
                };
                for i in 0..n {
                    for m in 0..=6 {
                        let h = m as f64 / 6.0;
                        // Start | Middle along e_i f_i, Middle | End along f_i e_{i+1}
                        for (a, b, x) in [(0, 1, (1.0, h)), (1, 2, (h, 1.0))] {
                            let (u, v) = (at(i, a, x), at(i, b, x));
                            assert!(
                                (u.0 - v.0).abs() < 1e-14
                                    && (u.1 - v.1).abs() < 1e-13
                                    && (u.2 - v.2).abs() < 1e-13,
                                "n = {n}, sector {i}, patches {a}|{b} at {x:?}: {u:?} vs {v:?}"
                            );
                        }
                        // End of sector i | Start of sector i + 1 along e_{i+1} g_{i+1}:
                        // frame i point (0, 1 + h) is (1 + h, 0) in frame i + 1, and
                        // gradients map by M^T = [[0, 1], [-1, 1]]
                        let u = at(i, 2, (0.0, 1.0 + h));
                        let v = at(i + 1, 0, (1.0 + h, 0.0));
                        let mu = (u.2, -u.1 + u.2);
                        assert!(
                            (u.0 - v.0).abs() < 1e-14
                                && (mu.0 - v.1).abs() < 1e-13
                                && (mu.1 - v.2).abs() < 1e-13,
                            "n = {n}, sectors {i}|{}: {u:?} vs {v:?}",
                            i + 1
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn patch_corners_are_limit_points_of_level_one() {
        // corners of Start: e_i (level 1), g_i, f_i; the regular limit stencil
        // 1/2 p + 1/12 (six neighbours) with the neighbours read off the
        // level-1 triangles by hand
        for n in [3, 5, 8] {
            let (ring, l1) = data_ring(n, 7 + n as u64);
            let r = TwoRing::new(n).unwrap();
            let a = |i: usize| extended_row_a(n, i);
            let lim = |p: usize, nb: [usize; 6]| {
                0.5 * l1[p] + nb.iter().map(|&q| l1[q]).sum::<f64>() / 12.0
            };
            for i in 0..n {
                let ip = r.prev(i);
                let p = &ring.patches()[3 * i].1.x;
                let e = lim(
                    r.e(i),
                    [r.v(), r.e(ip), r.f(ip), r.g(i), r.f(i), r.e(i + 1)],
                );
                let g = lim(r.g(i), [r.e(i), r.f(ip), a(ip) + 2, a(i), a(i) + 1, r.f(i)]);
                let f = lim(
                    r.f(i),
                    [r.e(i), r.g(i), a(i) + 1, a(i) + 2, r.g(i + 1), r.e(i + 1)],
                );
                assert!((p.eval(0.0, 0.0) - e).abs() < 1e-14, "n = {n}");
                assert!((p.eval(1.0, 0.0) - g).abs() < 1e-14, "n = {n}");
                assert!((p.eval(0.0, 1.0) - f).abs() < 1e-14, "n = {n}");
            }
        }
    }

    #[test]
    fn net_positions_are_all_level_one_points() {
        for n in 3..=7 {
            for i in 0..n {
                for kind in LoopPatchKind::ALL {
                    let idx = net_indices(n, i, kind).unwrap();
                    let mut sorted = idx.to_vec();
                    sorted.sort_unstable();
                    sorted.dedup();
                    // n = 3: e_{i-1} = e_{i+2} appears twice in the middle net
                    let want = if n == 3 && kind == LoopPatchKind::Middle {
                        11
                    } else {
                        12
                    };
                    assert_eq!(sorted.len(), want, "n = {n}, {kind:?}");
                    assert!(idx.iter().all(|&k| k < 6 * n + 1));
                }
            }
        }
        assert!(check(2).is_err());
        assert!(check(100_000).is_err());
        assert!(LoopRing::from_patches(Vec::new()).is_err());
    }
}
