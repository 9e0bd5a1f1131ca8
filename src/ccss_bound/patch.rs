//! The extraordinary Catmull-Clark patch with its `2n + 8` control points as
//! symbols: sub-patch control nets, their Bezier forms and the limit face, all
//! as linear forms (coefficient vectors) over the original points.

use super::Result;
use crate::schemes::catmull_clark::{
    extended_matrix, limit::limit_stencil, patch_matrix, PatchLayout, SubPatch,
};
use nalgebra::DMatrix;

/// Uniform cubic B-spline to Bezier conversion (one direction):
/// `bezier_i = sum_a M[i][a] bspline_a`.
pub const BSPLINE_TO_BEZIER: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 4.0 / 6.0, 2.0 / 6.0, 0.0],
    [0.0, 2.0 / 6.0, 4.0 / 6.0, 0.0],
    [0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
];

/// Regular limit-point mask of a valence-4 vertex, one direction: `(1, 4, 1)/6`.
const REGULAR_LIMIT: [f64; 3] = [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0];

/// A sub-patch `Omega^k_m` (`k >= 1`): its domain in the patch's `[0, 1]^2` is
/// `2^{1-k} origin(m) + [0, 2^{-k}]^2`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct SubDomain {
    /// Level `k >= 1`.
    pub level: u32,
    /// Which of the three regular sub-patches.
    pub part: SubPatch,
}

impl SubDomain {
    /// `[u0, u1] x [v0, v1]` as `((u0, u1), (v0, v1))`.
    pub fn bounds(&self) -> ((f64, f64), (f64, f64)) {
        let h = 0.5f64.powi(self.level as i32);
        let (ou, ov) = self.part.origin();
        let (u0, v0) = (2.0 * h * ou, 2.0 * h * ov);
        ((u0, u0 + h), (v0, v0 + h))
    }
    /// The sub-domain containing `(u, v)` in `[0, 1]^2 \ {(0, 0)}`; `None` at
    /// the extraordinary corner and outside the patch.
    pub fn containing(u: f64, v: f64) -> Option<Self> {
        if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) || (u == 0.0 && v == 0.0) {
            return None;
        }
        let m = u.max(v);
        // Smallest k >= 1 with 2^{-k} <= m, i.e. m in [2^{-k}, 2^{1-k}].
        let mut k = 1u32;
        while 0.5f64.powi(k as i32) > m {
            k += 1;
        }
        let h = 0.5f64.powi(k as i32);
        let part = match (u >= h, v >= h) {
            (true, true) => SubPatch::Two,
            (true, false) => SubPatch::One,
            _ => SubPatch::Three,
        };
        Some(SubDomain { level: k, part })
    }
}

/// The extraordinary patch of valence `n` (Catmull-Clark, `c = 1/2`) with its
/// control points as symbols (math doc section 9; Stam 1998 for the
/// sub-patch structure). Numbering: [`PatchLayout`].
#[derive(Clone, Debug)]
pub struct ExtraordinaryPatch {
    layout: PatchLayout,
    /// `(2n+8) x (2n+8)` patch matrix `A`.
    a: DMatrix<f64>,
    /// `(2n+17) x (2n+8)` extended matrix `A-bar`.
    ext: DMatrix<f64>,
}

impl ExtraordinaryPatch {
    /// The patch for valence `n >= 3`.
    pub fn new(n: usize) -> Result<Self> {
        let layout = PatchLayout::new(n)?;
        Ok(Self {
            layout,
            a: patch_matrix::<f64>(n, &0.5)?.into_matrix(),
            ext: extended_matrix::<f64>(n, &0.5)?.into_matrix(),
        })
    }
    /// The valence.
    pub fn valence(&self) -> usize {
        self.layout.valence()
    }
    /// The point numbering.
    pub fn layout(&self) -> &PatchLayout {
        &self.layout
    }
    /// Number of symbols, `2n + 8`.
    pub fn len(&self) -> usize {
        self.layout.patch_len()
    }
    /// Always false (a patch has `2n + 8 >= 14` points).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// The patch matrix `A`.
    pub fn patch_matrix(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// `A^{k-1}`: the level-`(k-1)` patch points as forms over the original ones.
    fn level_forms(&self, k: u32) -> DMatrix<f64> {
        let mut p = DMatrix::identity(self.len(), self.len());
        for _ in 1..k {
            p = &self.a * p;
        }
        p
    }

    /// Bicubic B-spline control net of `Omega^k_m` as a `16 x (2n+8)` matrix
    /// (row `4i + j` is control point `(i, j)`, `i` along `u`).
    pub fn bspline_net(&self, d: SubDomain) -> DMatrix<f64> {
        let refined = &self.ext * self.level_forms(d.level.max(1));
        let pick = self.layout.sub_patch(d.part);
        DMatrix::from_fn(16, self.len(), |r, c| refined[(pick[r / 4][r % 4], c)])
    }

    /// Bicubic Bezier coefficients `b_ij` of `Omega^k_m` (`16 x (2n+8)`, row `4i + j`).
    pub fn bezier_net(&self, d: SubDomain) -> DMatrix<f64> {
        let p = self.bspline_net(d);
        let mut out = DMatrix::zeros(16, self.len());
        for i in 0..4 {
            for j in 0..4 {
                for a in 0..4 {
                    for b in 0..4 {
                        let w = BSPLINE_TO_BEZIER[i][a] * BSPLINE_TO_BEZIER[j][b];
                        if w != 0.0 {
                            for col in 0..self.len() {
                                out[(4 * i + j, col)] += w * p[(4 * a + b, col)];
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Limit points of the four patch corners as forms: `(0,0)` = `v`
    /// (extraordinary stencil), `(1,0)` = `e_0`, `(1,1)` = `f_0`, `(0,1)` = `e_1`
    /// (regular stencil `(1,4,1) x (1,4,1) / 36`). Returned in the order
    /// `[F00, F10, F01, F11]`.
    pub fn corner_limits(&self) -> Result<[Vec<f64>; 4]> {
        let n = self.valence();
        let mut f00 = limit_stencil::<f64>(n, &0.5)?;
        f00.resize(self.len(), 0.0);
        let regular = |ci: usize, cj: usize| {
            let mut f = vec![0.0; self.len()];
            for (a, wa) in REGULAR_LIMIT.iter().enumerate() {
                for (b, wb) in REGULAR_LIMIT.iter().enumerate() {
                    // Grid neighbours of (ci, cj) are never the missing corner (0, 0).
                    if let Some(col) = self.layout.grid(ci + a - 1, cj + b - 1) {
                        f[col] += wa * wb;
                    }
                }
            }
            f
        };
        Ok([f00, regular(2, 1), regular(1, 2), regular(2, 2)])
    }

    /// The limit face `F(u, v)` (bilinear in the four corner limits) at a point, as a form.
    pub fn limit_face_at(&self, corners: &[Vec<f64>; 4], u: f64, v: f64) -> Vec<f64> {
        let [f00, f10, f01, f11] = corners;
        (0..self.len())
            .map(|k| {
                (1.0 - v) * ((1.0 - u) * f00[k] + u * f10[k])
                    + v * ((1.0 - u) * f01[k] + u * f11[k])
            })
            .collect()
    }

    /// Bicubic Bezier coefficients `bbar_ij` of `F` restricted to `Omega^k_m`
    /// (a bilinear function's degree-elevated coefficients are its values at
    /// the points `(u0 + i h/3, v0 + j h/3)`), `16 x (2n+8)`, row `4i + j`.
    pub fn limit_face_bezier(&self, d: SubDomain) -> Result<DMatrix<f64>> {
        let corners = self.corner_limits()?;
        let ((u0, u1), (v0, v1)) = d.bounds();
        let mut out = DMatrix::zeros(16, self.len());
        for i in 0..4 {
            for j in 0..4 {
                let u = u0 + (u1 - u0) * i as f64 / 3.0;
                let v = v0 + (v1 - v0) * j as f64 / 3.0;
                let f = self.limit_face_at(&corners, u, v);
                for (k, x) in f.into_iter().enumerate() {
                    out[(4 * i + j, k)] = x;
                }
            }
        }
        Ok(out)
    }
}

/// Uniform cubic B-spline basis at `t` in `[0, 1]` (the tests' reference
/// evaluation of the patch).
#[cfg(test)]
pub fn bspline_basis(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

/// Cubic Bernstein basis at `t`.
pub fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}
