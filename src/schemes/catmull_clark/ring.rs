//! The regular cells of the Catmull-Clark family's ring as data (math doc
//! section 8): the family's univariate rule ([`UnivariateRule`]: vertex mask
//! `(c/4, 1 - c/2, c/4)`, edge midpoint; the tensor product is the scheme on
//! a regular grid), the 4 x 4 window of control points of one regular cell
//! ([`Window`]), its refinement into four sub-windows and, at `c = 1/2`, its
//! conversion to bicubic Bezier form. The certified checks on the ring are
//! [`crate::charmap::catmull_clark`].

use crate::error::{Error, Result};

/// The univariate rule of the Catmull-Clark family (math doc section 8
/// \[reconstructed\]): new vertex point `c/4 p_{i-1} + (1 - c/2) p_i + c/4 p_{i+1}`,
/// new edge point `(p_i + p_{i+1}) / 2`; cubic B-spline refinement at `c = 1/2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnivariateRule {
    c: f64,
    side: f64,
    centre: f64,
}

impl UnivariateRule {
    /// The rule for `c` in `(0, 1]` (where it and its derived rule converge
    /// with non-negative masks; see the module docs).
    ///
    /// ```
    /// use subdiv_lab::schemes::catmull_clark::ring::UnivariateRule;
    /// let r = UnivariateRule::new(0.5).unwrap();
    /// assert_eq!(r.limit_weights(), [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]);
    /// assert!(UnivariateRule::new(0.0).is_err());
    /// ```
    pub fn new(c: f64) -> Result<Self> {
        if !(c > 0.0 && c <= 1.0) {
            return Err(Error::InvalidParameter {
                name: "c",
                value: c.to_string(),
                reason: "the cone test needs 0 < c <= 1 (at c = 0 the derived rule \
                         is piecewise constant and does not converge uniformly)",
            });
        }
        Ok(Self {
            c,
            side: c / 4.0,
            centre: 1.0 - c / 2.0,
        })
    }

    /// The shape parameter.
    pub fn c(&self) -> f64 {
        self.c
    }

    /// Limit stencil at a vertex `(alpha, beta, alpha)`, `beta = 1/(1 + c)`,
    /// `alpha = c / (2 (1 + c))`: the left eigenvector for 1 of the local
    /// matrix `[[1/2, 1/2, 0], [c/4, 1 - c/2, c/4], [0, 1/2, 1/2]]` (whose other
    /// eigenvalues are `1/2` with left eigenvector `(-1, 0, 1)`, the derivative
    /// stencil, and `(1 - c)/2`).
    pub fn limit_weights(&self) -> [f64; 3] {
        let alpha = self.c / (2.0 * (1.0 + self.c));
        let beta = 1.0 / (1.0 + self.c);
        [alpha, beta, alpha]
    }

    /// One refinement of a 4-point window `p_{-1}, p_0, p_1, p_2` of the cell
    /// `[0, 1]`: the 5 points at `-1/2, 0, 1/2, 1, 3/2`.
    pub fn refine4(&self, q: &[[f64; 2]; 4]) -> [[f64; 2]; 5] {
        let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let vert = |a: [f64; 2], b: [f64; 2], d: [f64; 2]| {
            [
                self.side * a[0] + self.centre * b[0] + self.side * d[0],
                self.side * a[1] + self.centre * b[1] + self.side * d[1],
            ]
        };
        [
            mid(q[0], q[1]),
            vert(q[0], q[1], q[2]),
            mid(q[1], q[2]),
            vert(q[1], q[2], q[3]),
            mid(q[2], q[3]),
        ]
    }

    /// Limit point of the middle vertex of three points.
    pub fn limit3(&self, a: [f64; 2], b: [f64; 2], d: [f64; 2]) -> [f64; 2] {
        let [al, be, _] = self.limit_weights();
        [
            al * a[0] + be * b[0] + al * d[0],
            al * a[1] + be * b[1] + al * d[1],
        ]
    }
}

/// A 4 x 4 window of planar control points of one regular cell, `w[a][b]`
/// with `a` along the cell parameter `s` and `b` along `t`; the cell is the
/// grid square between indices 1 and 2 in both directions.
pub type Window = [[[f64; 2]; 4]; 4];

/// The four sub-windows `[(0,0), (1,0), (0,1), (1,1)]` (sub-cell offsets
/// along `s`, `t`) after one refinement.
pub fn refine_window(rule: &UnivariateRule, w: &Window) -> [Window; 4] {
    // refine along b for each a, then along a
    let mut half = [[[0.0; 2]; 5]; 4];
    for a in 0..4 {
        half[a] = rule.refine4(&w[a]);
    }
    let mut full = [[[0.0; 2]; 5]; 5];
    for b in 0..5 {
        let col = [half[0][b], half[1][b], half[2][b], half[3][b]];
        let r = rule.refine4(&col);
        for a in 0..5 {
            full[a][b] = r[a];
        }
    }
    let sub = |da: usize, db: usize| {
        let mut out = [[[0.0; 2]; 4]; 4];
        for a in 0..4 {
            for b in 0..4 {
                out[a][b] = full[a + da][b + db];
            }
        }
        out
    };
    [sub(0, 0), sub(1, 0), sub(0, 1), sub(1, 1)]
}

/// Coordinate `k` of a window's cell as the control points of a uniform
/// bicubic Bezier patch, `out[a][b]` (valid at `c = 1/2` only, where the rule
/// is cubic B-spline refinement): per direction
/// `b_0 = (d_0 + 4 d_1 + d_2)/6, b_1 = (2 d_1 + d_2)/3, b_2 = (d_1 + 2 d_2)/3,
/// b_3 = (d_1 + 4 d_2 + d_3)/6`.
pub fn bicubic_bezier(w: &Window, k: usize) -> [[f64; 4]; 4] {
    let conv = |d: [f64; 4]| {
        [
            (d[0] + 4.0 * d[1] + d[2]) / 6.0,
            (2.0 * d[1] + d[2]) / 3.0,
            (d[1] + 2.0 * d[2]) / 3.0,
            (d[1] + 4.0 * d[2] + d[3]) / 6.0,
        ]
    };
    let mut half = [[0.0; 4]; 4];
    for (a, h) in half.iter_mut().enumerate() {
        *h = conv([w[a][0][k], w[a][1][k], w[a][2][k], w[a][3][k]]);
    }
    let mut out = [[0.0; 4]; 4];
    for b in 0..4 {
        let r = conv([half[0][b], half[1][b], half[2][b], half[3][b]]);
        for a in 0..4 {
            out[a][b] = r[a];
        }
    }
    out
}

/// One refinement of a grid of `m x m` points (`g[a][b]`) with the rule in
/// both directions: `2m - 3` points per direction (every edge point, the
/// vertex points of interior vertices), covering the same cells.
pub fn refine_grid(rule: &UnivariateRule, g: &[Vec<[f64; 2]>]) -> Vec<Vec<[f64; 2]>> {
    let line = |pts: &[[f64; 2]]| -> Vec<[f64; 2]> {
        let m = pts.len();
        let mut out = Vec::with_capacity(2 * m - 3);
        for i in 0..m - 1 {
            out.push([
                0.5 * (pts[i][0] + pts[i + 1][0]),
                0.5 * (pts[i][1] + pts[i + 1][1]),
            ]);
            if i + 2 < m {
                let (a, b, d) = (pts[i], pts[i + 1], pts[i + 2]);
                out.push([
                    rule.side * a[0] + rule.centre * b[0] + rule.side * d[0],
                    rule.side * a[1] + rule.centre * b[1] + rule.side * d[1],
                ]);
            }
        }
        out
    };
    let rows: Vec<Vec<[f64; 2]>> = g.iter().map(|r| line(r)).collect();
    let cols = rows[0].len();
    let refined_cols: Vec<Vec<[f64; 2]>> = (0..cols)
        .map(|b| line(&rows.iter().map(|r| r[b]).collect::<Vec<_>>()))
        .collect();
    (0..refined_cols[0].len())
        .map(|a| refined_cols.iter().map(|c| c[a]).collect())
        .collect()
}
