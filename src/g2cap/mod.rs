//! The G2 cap of seed 003: `n` Bezier patches of bidegree (7, 7) filling the
//! `n`-sided hole around an extraordinary vertex after the mixed subdivision
//! of its 2-ring (math doc section 14; what the OCR of the paper leaves open
//! is designed there and marked **\[reconstructed\]** / **\[derived\]**).
//!
//! Steps:
//!
//! 1. [`ring`]: the 2-ring of the vertex (`6n + 1` points, from a polygon
//!    list or a random test net) and the **mixed subdivision**: one step of
//!    the shape-adjustable Catmull-Clark rules with parameter `c`, after
//!    which the hole is the `n` refined quads at the vertex and the cells
//!    around it are bicubic B-spline patches (math doc section 14.2).
//! 2. `solve`: patch `i` lies between spokes `i` and `i + 1`, `P_i(0,0)` is
//!    the centre and `P_i(0, t) = P_(i+1)(t, 0)`. Across each internal edge
//!    the patches meet G2 under the transition map
//!
//!    ```text
//!    (u, v) -> (-v, u + b(u) v),  b(t) = 2 c_n (1 - t)^3 [(1 + 3t) if n = 3],  c_n = cos(2 pi / n)
//!    ```
//!
//!    (G1: `P_(i+1)^v + P_i^u = b P_i^v`; G2: `P_(i+1)^vv = P_i^uu - 2 b
//!    P_i^uv + b^2 P_i^vv` on the edge). On the outer boundary the control
//!    rows `j >= 5` and columns `k >= 5` are those of the neighbouring
//!    B-spline cells continued into the cap: a C2 join in the natural
//!    parametrisation. The remaining `25 n` points minimise a discrete
//!    thin-plate energy subject to the conditions (math doc sections
//!    14.3-14.5), solved by `dft` (the paper's discrete Fourier transform
//!    over the patch index) and checked against the dense `solve`.
//! 3. `residual`: jumps of the normal and of `K` and `H` across the
//!    internal edges and the outer boundary, sampled densely; above
//!    [`RESIDUAL_TOL`] the cap is refused ([`G2Cap::check`]).
//!
//! ```
//! use subdiv_lab::g2cap::{ring::TwoRing, G2Cap};
//! let ring = TwoRing::random(5, 7).unwrap();
//! let cap = G2Cap::build(&ring, 0.5).unwrap();
//! cap.check().unwrap();
//! assert_eq!(cap.patches().len(), 5);
//! assert!(cap.g2_residual() < 1e-9);
//! ```

// Index loops mirror the subscripts of the formulas in the math doc.
#![allow(clippy::needless_range_loop)]

pub(crate) mod bernstein;
pub(crate) mod dft;
mod error;
pub mod plain;
pub(crate) mod residual;
pub mod ring;
pub(crate) mod solve;

pub use bernstein::{Net, DEGREE};
pub use error::{G2CapError, CONSTRAINT_RTOL, RESIDUAL_TOL};
pub use residual::Jumps;

use bernstein::eval_net;
use ring::{Point, RefinedRing, TwoRing};

/// Rings whose largest coordinate magnitude `m` has `|log2 m|` above this are
/// built on a copy scaled by a power of two (exact: every step of the
/// construction is homogeneous in the points, and binary scaling commutes
/// with rounding) and scaled back: the curvature evaluation squares lengths
/// twice (`|N|^2 ~ L^4`), which overflows near `L = 1e77` and underflows near
/// `L = 1e-77`. Within `2^-64 ..= 2^64` nothing is scaled, so ordinary inputs
/// take the unscaled path bit for bit.
pub const NORMALIZE_EXPONENT: i32 = 64;

/// `x 2^k` for `|k|` up to about 2000, in two exact steps (each factor is a
/// normal power of two).
fn scale_pow2(x: f64, k: i32) -> f64 {
    let h = k / 2;
    x * 2f64.powi(h) * 2f64.powi(k - h)
}

/// How the constrained least squares of the free points is solved (math
/// doc section 14.5). Both give the same control points up to rounding
/// (`tests/analysis/g2cap.rs` cross-checks them); the DFT path is the more accurate
/// (it keeps the rotational symmetry of the problem to `~1e-14 L`, the
/// dense path to `~1e-9 L` at `n = 6`) and the faster one, so it is the
/// default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Solver {
    /// The paper's route: a discrete Fourier transform over the patch index
    /// makes the block-circulant system block diagonal, `n` small complex
    /// solves (`dft::solve_dft`).
    #[default]
    Dft,
    /// One SVD of the whole constraint matrix (`solve::solve`), kept as
    /// the independent check.
    Dense,
}

/// Most quads per patch side of [`G2Cap::sample_mesh`] as the front ends
/// offer it (`g2-cap --samples`): 256 x 256 quads per patch, about 66 000
/// points per patch.
pub const MAX_SAMPLES: usize = 256;

/// Checks the quads per patch side of a sampled cap: 1 to [`MAX_SAMPLES`]
/// (the message names the argument as `spelling` spells it).
pub fn check_samples(samples: usize, spelling: crate::budget::Spelling) -> Result<(), String> {
    if samples == 0 || samples > MAX_SAMPLES {
        return Err(format!(
            "{} must be in 1..={MAX_SAMPLES}, got {samples}",
            spelling.arg("samples")
        ));
    }
    Ok(())
}

/// The cap and its measurements.
#[derive(Clone, Debug)]
pub struct G2Cap {
    c: f64,
    nets: Vec<Net>,
    energy: f64,
    constraint_residual: f64,
    corner_mismatch: f64,
    internal: Jumps,
    outer: Jumps,
    scale: f64,
    curvature_scale: f64,
    rank: usize,
    freedom: usize,
    condition: f64,
    energy_condition: f64,
    refined: RefinedRing,
}

impl G2Cap {
    /// Builds the cap of `ring` with shape parameter `c` in `[0, 1]` (the
    /// default [`Solver`], the DFT path). Residuals are measured, not
    /// checked: call [`G2Cap::check`].
    pub fn build(ring: &TwoRing, c: f64) -> Result<G2Cap, G2CapError> {
        G2Cap::build_with(ring, c, Solver::Dft)
    }

    /// [`G2Cap::build`] with a choice of solver.
    ///
    /// ```
    /// use subdiv_lab::g2cap::{ring::TwoRing, G2Cap, Solver};
    /// let ring = TwoRing::random(5, 3).unwrap();
    /// let dense = G2Cap::build_with(&ring, 0.8, Solver::Dense).unwrap();
    /// let dft = G2Cap::build(&ring, 0.8).unwrap();
    /// dft.check().unwrap();
    /// let d = (dense.patches()[2][1][3][0] - dft.patches()[2][1][3][0]).abs();
    /// assert!(d < 1e-9 * dense.length_scale());
    /// ```
    pub fn build_with(ring: &TwoRing, c: f64, solver: Solver) -> Result<G2Cap, G2CapError> {
        if !(0.0..=1.0).contains(&c) {
            return Err(G2CapError::ShapeParameter { c });
        }
        let m = ring
            .points()
            .iter()
            .flat_map(|p| p.iter())
            .fold(0.0f64, |a, x| a.max(x.abs()));
        let e = if m > 0.0 { m.log2().floor() as i32 } else { 0 };
        if e.abs() > NORMALIZE_EXPONENT {
            let unit = ring.map(|p| p.map(|x| scale_pow2(x, -e)));
            return Ok(G2Cap::build_unscaled(&unit, c, solver)?.rescaled(ring, e));
        }
        G2Cap::build_unscaled(ring, c, solver)
    }

    /// The cap of a ring scaled by `2^-k`, scaled back by `2^k` to be the cap
    /// of `ring` (the residuals are relative, so unchanged).
    fn rescaled(mut self, ring: &TwoRing, k: i32) -> G2Cap {
        for net in &mut self.nets {
            for row in net.iter_mut() {
                for p in row.iter_mut() {
                    *p = p.map(|x| scale_pow2(x, k));
                }
            }
        }
        self.energy = scale_pow2(self.energy, 2 * k);
        self.scale = scale_pow2(self.scale, k);
        self.curvature_scale = scale_pow2(self.curvature_scale, -k);
        self.refined = RefinedRing::new(ring, self.c);
        self
    }

    /// [`G2Cap::build_with`] without the scaling of extreme coordinates.
    fn build_unscaled(ring: &TwoRing, c: f64, solver: Solver) -> Result<G2Cap, G2CapError> {
        let n = ring.valence();
        let refined = RefinedRing::new(ring, c);
        let (fixed, corner_mismatch) = solve::fixed_nets(&refined, n);
        let solved = match solver {
            Solver::Dense => solve::solve(&fixed)?,
            Solver::Dft => dft::solve_dft(&fixed)?,
        };
        let scale = residual::length_scale(&solved.nets);
        let inner_pairs = residual::internal(&solved.nets);
        let outer_pairs = residual::outer(&solved.nets, &refined);
        let all: Vec<residual::Pair> = inner_pairs.iter().chain(&outer_pairs).cloned().collect();
        let curvature_scale = residual::curvature_scale(&all, scale);
        let internal = residual::jumps(&inner_pairs, curvature_scale);
        let outer = residual::jumps(&outer_pairs, curvature_scale);
        Ok(G2Cap {
            c,
            energy: solved.energy,
            constraint_residual: solved.constraint_residual / scale,
            corner_mismatch: corner_mismatch / scale,
            nets: solved.nets,
            internal,
            outer,
            scale,
            curvature_scale,
            rank: solved.rank,
            freedom: solved.freedom,
            condition: solved.condition,
            energy_condition: solved.energy_condition,
            refined,
        })
    }

    /// Refuses the cap if a residual exceeds its tolerance
    /// ([`RESIDUAL_TOL`], [`CONSTRAINT_RTOL`]); a NaN residual is refused too.
    pub fn check(&self) -> Result<(), G2CapError> {
        let items = [
            (
                "constraint_residual",
                self.constraint_residual,
                CONSTRAINT_RTOL,
            ),
            ("g1_residual", self.internal.normal, RESIDUAL_TOL),
            ("g2_residual", self.internal.curvature, RESIDUAL_TOL),
            ("outer_residual.g1", self.outer.normal, RESIDUAL_TOL),
            ("outer_residual.g2", self.outer.curvature, RESIDUAL_TOL),
        ];
        for (what, value, tol) in items {
            if value.is_nan() || value > tol {
                return Err(G2CapError::Residual { what, value, tol });
            }
        }
        Ok(())
    }

    /// The shape parameter.
    pub fn c(&self) -> f64 {
        self.c
    }
    /// The valence.
    pub fn valence(&self) -> usize {
        self.nets.len()
    }
    /// The degree in each variable (7).
    pub fn degree(&self) -> usize {
        DEGREE
    }
    /// The patches: `patches()[i][j][k] = p^i_jk`, `j` along `u` (spoke `i`),
    /// `k` along `v` (spoke `i + 1`), `p^i_00` the centre.
    pub fn patches(&self) -> &[Net] {
        &self.nets
    }
    /// The minimised energy (sum over the three coordinates).
    pub fn energy(&self) -> f64 {
        self.energy
    }
    /// Largest internal jump of the unit normal.
    pub fn g1_residual(&self) -> f64 {
        self.internal.normal
    }
    /// Largest internal jump of `K / k_s^2` and `H / k_s`.
    pub fn g2_residual(&self) -> f64 {
        self.internal.curvature
    }
    /// Jumps across the outer boundary.
    pub fn outer_residual(&self) -> Jumps {
        self.outer
    }
    /// `max |A x - r| / L` of the linear conditions.
    pub fn constraint_residual(&self) -> f64 {
        self.constraint_residual
    }
    /// Disagreement `/ L` of the two continued neighbours on the fixed corner
    /// blocks (rounding only: the bicubic spline is C2).
    pub fn corner_mismatch(&self) -> f64 {
        self.corner_mismatch
    }
    /// The length scale `L` (diameter of the control points).
    pub fn length_scale(&self) -> f64 {
        self.scale
    }
    /// The curvature scale `k_s` the curvature jumps are relative to: the
    /// largest principal curvature magnitude over all samples, at least
    /// `1 / L`.
    pub fn curvature_scale(&self) -> f64 {
        self.curvature_scale
    }
    /// Rank of the constraint matrix and dimension of its solution space.
    pub fn rank_and_freedom(&self) -> (usize, usize) {
        (self.rank, self.freedom)
    }
    /// `sigma_max / sigma_min` of the singular values of the constraint
    /// matrix kept by the rank decision (both solvers see the same values).
    pub fn constraint_condition(&self) -> f64 {
        self.condition
    }
    /// `sigma_max / sigma_min` of the energy restricted to the solution
    /// space of the constraints: the control points are determined to
    /// rounding times this number (math doc section 14.5).
    pub fn energy_condition(&self) -> f64 {
        self.energy_condition
    }
    /// The refined ring (the mixed subdivision) the cap joins.
    pub fn refined(&self) -> &RefinedRing {
        &self.refined
    }

    /// A point or derivative of patch `i`.
    pub fn eval(&self, i: usize, u: f64, v: f64, du: usize, dv: usize) -> Point {
        eval_net(&self.nets[i % self.nets.len()], u, v, du, dv)
    }

    /// Gaussian and mean curvature `(K, H)` of patch `i` at `(u, v)`, the
    /// normal `P_u x P_v / |P_u x P_v|` (`residual::shape`); `None` where
    /// the tangents are parallel.
    pub fn curvature_at(&self, i: usize, u: f64, v: f64) -> Option<(f64, f64)> {
        let d = [
            self.eval(i, u, v, 1, 0),
            self.eval(i, u, v, 0, 1),
            self.eval(i, u, v, 2, 0),
            self.eval(i, u, v, 1, 1),
            self.eval(i, u, v, 0, 2),
        ];
        residual::shape(&d).map(|(_, k, h)| (k, h))
    }

    /// The cap as JSON (`g2-cap --json`, the Python dict): degree, valence,
    /// `c`, the control points of the patches (with their orientation), the
    /// internal and outer residuals with their definitions and tolerances,
    /// and the energy.
    pub fn to_json(&self) -> serde_json::Value {
        let outer = self.outer_residual();
        serde_json::json!({
            "degree": self.degree(),
            "valence": self.valence(),
            "c": self.c(),
            "orientation": "patches[i][j][k] = p^i_jk: patch i lies between spokes i and i+1 (the faces around the vertex in the mesh's order), j along u (spoke i), k along v (spoke i+1), p^i_00 the vertex; P_i(0,t) = P_{i+1}(t,0)",
            "patches": self.patches(),
            "g1_residual": self.g1_residual(),
            "g2_residual": self.g2_residual(),
            "outer_residual": { "g1": outer.normal, "g2": outer.curvature },
            "outer_join": "C2 (rows and columns 5..7 from the neighbouring bicubic B-spline cells)",
            "residual_definition": "g1: max |N_1 - N_2| (unit normals); g2: max(|K_1 - K_2| / k_s^2, |H_1 - H_2| / k_s), k_s = curvature_scale = max(1/L, largest principal curvature magnitude over the samples), L = length_scale = diameter of the control points; 65 samples per edge",
            "curvature_scale": self.curvature_scale(),
            "length_scale": self.length_scale(),
            "constraint_residual": self.constraint_residual(),
            "tolerance": RESIDUAL_TOL,
            "constraint_tolerance": CONSTRAINT_RTOL,
            "energy": self.energy(),
            "energy_definition": "discrete thin-plate energy of the control nets (sum of squared second differences, mixed ones weighted 2)",
        })
    }

    /// The cap sampled on an `m x m` grid of quads per patch: points and
    /// quads (0-based, counter-clockwise as the patches), patch after patch
    /// (points on shared edges repeated).
    pub fn sample_mesh(&self, m: usize) -> (Vec<Point>, Vec<[usize; 4]>) {
        let m = m.max(1);
        let mut pts = Vec::new();
        let mut quads = Vec::new();
        for net in &self.nets {
            let base = pts.len();
            for a in 0..=m {
                for b in 0..=m {
                    pts.push(eval_net(
                        net,
                        a as f64 / m as f64,
                        b as f64 / m as f64,
                        0,
                        0,
                    ));
                }
            }
            let id = |a: usize, b: usize| base + a * (m + 1) + b;
            for a in 0..m {
                for b in 0..m {
                    quads.push([id(a, b), id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)]);
                }
            }
        }
        (pts, quads)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_residual_above_the_tolerance_or_nan_is_refused_by_name() {
        let ring = TwoRing::random(5, 1).unwrap();
        let good = G2Cap::build(&ring, 0.5).unwrap();
        good.check().unwrap();
        let mut bad = good.clone();
        bad.internal.curvature = 2.0 * RESIDUAL_TOL;
        let e = bad.check().unwrap_err();
        assert!(e.to_string().contains("g2_residual"), "{e}");
        assert!(!e.is_input_error());
        let mut nan = good.clone();
        nan.outer.normal = f64::NAN;
        let e = nan.check().unwrap_err();
        assert!(e.to_string().contains("outer_residual.g1"), "{e}");
    }

    #[test]
    fn the_fixed_corner_blocks_agree_and_the_system_is_consistent() {
        for n in [3, 5, 8] {
            let cap = G2Cap::build(&TwoRing::random(n, 9).unwrap(), 0.25).unwrap();
            assert!(cap.corner_mismatch() < 1e-14, "{}", cap.corner_mismatch());
            assert!(cap.constraint_residual() < CONSTRAINT_RTOL);
            let (rank, freedom) = cap.rank_and_freedom();
            assert_eq!(rank + freedom, 25 * n);
            assert!(freedom > 0);
        }
    }

    #[test]
    fn shape_parameter_outside_the_unit_interval_is_refused() {
        let ring = TwoRing::random(5, 1).unwrap();
        for c in [-0.1, 1.1, f64::NAN] {
            let e = G2Cap::build(&ring, c).unwrap_err();
            assert!(e.is_input_error(), "{e}");
        }
    }
}
