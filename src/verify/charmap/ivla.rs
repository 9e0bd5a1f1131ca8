//! Interval helpers of the cell characteristic-map certificate (math doc
//! section 15, "The characteristic map over a cell"): planar boxes, boxes in
//! midpoint-radius form for convex refinement, division and square root,
//! and verified linear algebra (an enclosure of `Q^{-1}` and of the
//! solution set of an interval linear system).
//!
//! Rounding model as in [`super::super::interval`]: every operation rounds
//! to nearest and moves the result one float outward; a `NaN` makes every
//! certifying comparison false.

use super::super::interval::{down, up, Iv};
use nalgebra::DMatrix;

/// A planar box: one interval per coordinate.
pub type P2 = [Iv; 2];

/// `1/2`, exact.
pub const HALF: Iv = Iv::point(0.5);

/// The box of the float point `p` (exact).
pub fn p2(p: [f64; 2]) -> P2 {
    [Iv::point(p[0]), Iv::point(p[1])]
}

/// Componentwise sum.
pub fn p2_add(a: P2, b: P2) -> P2 {
    [a[0].add(b[0]), a[1].add(b[1])]
}

/// Componentwise difference.
pub fn p2_sub(a: P2, b: P2) -> P2 {
    [a[0].sub(b[0]), a[1].sub(b[1])]
}

/// Both coordinates times the interval `s`.
pub fn p2_scale(a: P2, s: Iv) -> P2 {
    [a[0].mul(s), a[1].mul(s)]
}

/// `a_x b_y - a_y b_x` over the boxes.
pub fn p2_det(a: P2, b: P2) -> Iv {
    a[0].mul(b[1]).sub(a[1].mul(b[0]))
}

/// The float midpoint of an interval.
pub fn mid(x: Iv) -> f64 {
    x.mid_rad().0
}

/// `a / b` for `b` not containing 0 (`None` otherwise).
pub fn div(a: Iv, b: Iv) -> Option<Iv> {
    if !(b.lo > 0.0 || b.hi < 0.0) {
        return None;
    }
    let q = [a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi];
    if q.iter().any(|x| x.is_nan()) {
        return None;
    }
    let lo = q.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = q.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some(Iv::new(down(lo), up(hi)))
}

/// `sqrt` of an interval with `lo >= 0` (`None` otherwise). IEEE `sqrt` is
/// correctly rounded, so one float outward covers it.
pub fn sqrt(a: Iv) -> Option<Iv> {
    if !(a.lo >= 0.0) || a.hi.is_nan() {
        return None;
    }
    Some(Iv::new(down(a.lo.sqrt()).max(0.0), up(a.hi.sqrt())))
}

/// `{x^2 : x in a}`, rounded outward (non-negative; `[0, max x^2]` when
/// `a` holds 0, unlike `a.mul(a)`).
///
/// ```
/// use subdiv_lab::verify::charmap::ivla::sqr;
/// use subdiv_lab::verify::interval::Iv;
/// let s = sqr(Iv::new(-0.1, 0.2));
/// assert!(s.lo == 0.0 && s.hi >= 0.04 && s.hi < 0.0401);
/// ```
pub fn sqr(a: Iv) -> Iv {
    if a.lo > 0.0 || a.hi < 0.0 {
        let (p, q) = (a.lo * a.lo, a.hi * a.hi);
        Iv::new(down(p.min(q)).max(0.0), up(p.max(q)))
    } else if a.lo <= 0.0 && a.hi >= 0.0 {
        Iv::new(0.0, up(a.mag() * a.mag()))
    } else {
        Iv::new(f64::NAN, f64::NAN)
    }
}

/// Upper bound of `sqrt(sum x_i^2)` (rounded up).
pub fn norm2_upper(xs: impl IntoIterator<Item = f64>) -> f64 {
    let mut s = 0.0f64;
    for x in xs {
        s = up(s + up(x * x));
    }
    up(s.sqrt())
}

/// Upper bound of the spectral norm `||E||_2` of every matrix `E` with
/// `|E| <= A` entrywise, for the non-negative `rows x cols` matrix `A`
/// (row-major): `||E||_2 <= || |E| ||_2 <= ||A||_2 <= min(||A||_F,
/// sqrt(||A||_1 ||A||_inf))` (math doc section 15, "G1 over a cell"),
/// rounded up. The second bound is the sharper one for a diagonally
/// dominant `A` (it is exact for a diagonal one, where the Frobenius norm
/// overestimates by up to `sqrt(rows)`).
///
/// ```
/// use subdiv_lab::verify::charmap::ivla::norm2_op_upper;
/// let a = [0.25, 0.0, 0.0, 0.25];
/// let b = norm2_op_upper(&a, 2, 2);
/// assert!(b >= 0.25 && b < 0.25 * (1.0 + 1e-15));
/// ```
pub fn norm2_op_upper(a: &[f64], rows: usize, cols: usize) -> f64 {
    if a.len() != rows * cols {
        return f64::INFINITY;
    }
    let mut row_max = 0.0f64;
    let mut col = vec![0.0f64; cols];
    for i in 0..rows {
        let mut r = 0.0f64;
        for (j, c) in col.iter_mut().enumerate() {
            let x = a[i * cols + j].abs();
            r = up(r + x);
            *c = up(*c + x);
        }
        row_max = row_max.max(r);
    }
    let col_max = col.iter().copied().fold(0.0f64, f64::max);
    let mixed = up(up(row_max * col_max).sqrt());
    norm2_upper(a.iter().copied()).min(mixed)
}

/// A planar point known to lie in the square `|p - m|_inf <= r`
/// (midpoint-radius form). Convex combinations (non-negative weights adding
/// up to 1) of such points have a radius at most the largest input radius,
/// so repeated refinement with a convex rule never inflates it; only the
/// midpoints are combined in interval arithmetic (with the interval weights)
/// and their rounding and weight uncertainty is added to the radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mr {
    /// Midpoint (floats).
    pub m: [f64; 2],
    /// Radius (max-norm), an upper bound.
    pub r: f64,
}

impl Mr {
    /// The smallest square around a box with a float centre.
    pub fn from_box(p: P2) -> Mr {
        let (m0, r0) = p[0].mid_rad();
        let (m1, r1) = p[1].mid_rad();
        Mr {
            m: [m0, m1],
            r: r0.max(r1),
        }
    }

    /// The box of the square.
    pub fn to_box(self) -> P2 {
        [
            Iv::point(self.m[0]).widen(self.r),
            Iv::point(self.m[1]).widen(self.r),
        ]
    }

    fn mid_box(self) -> P2 {
        p2(self.m)
    }

    /// `from_box(b)` with the extra radius `extra` (from the inputs' radii).
    fn with_extra(b: P2, extra: f64) -> Mr {
        let mut q = Mr::from_box(b);
        q.r = up(q.r + extra);
        q
    }

    /// `b + w (a - b)` for `w` in `[0, 1]` (the convex combination `(1 - w) b + w a`).
    pub fn lerp(b: Mr, a: Mr, w: Iv) -> Mr {
        let (bm, am) = (b.mid_box(), a.mid_box());
        let v = p2_add(bm, p2_scale(p2_sub(am, bm), w));
        Mr::with_extra(v, b.r.max(a.r))
    }

    /// `(a + b) / 2`.
    pub fn mid2(a: Mr, b: Mr) -> Mr {
        let v = p2_scale(p2_add(a.mid_box(), b.mid_box()), HALF);
        Mr::with_extra(v, a.r.max(b.r))
    }

    /// `w a + (1 - 2w) b + w d = b + w ((a - b) + (d - b))` for `w` in `[0, 1/2]`.
    pub fn stencil3(a: Mr, b: Mr, d: Mr, w: Iv) -> Mr {
        let bm = b.mid_box();
        let s = p2_add(p2_sub(a.mid_box(), bm), p2_sub(d.mid_box(), bm));
        let v = p2_add(bm, p2_scale(s, w));
        Mr::with_extra(v, a.r.max(b.r).max(d.r))
    }

    /// `a - b` (the radii add up).
    pub fn diff(a: Mr, b: Mr) -> Mr {
        let v = p2_sub(a.mid_box(), b.mid_box());
        Mr::with_extra(v, up(a.r + b.r))
    }

    /// The square rotated by the interval matrix `[[c, -s], [s, c]]`.
    pub fn rotate(self, c: Iv, s: Iv) -> Mr {
        let b = self.to_box();
        Mr::from_box([c.mul(b[0]).sub(s.mul(b[1])), s.mul(b[0]).add(c.mul(b[1]))])
    }
}

/// Largest accepted `||I - X A||_inf` in the verified inverse and solve:
/// below it the Neumann bound at most doubles the correction.
pub const MAX_RESIDUAL: f64 = 0.5;

/// An interval matrix (row-major, `k x k`) containing `A^{-1}` for the float
/// matrix `a` (`None` when `a` is numerically singular or the residual of the
/// numerical inverse is too large): with `X ~ A^{-1}` and `E = I - X A` in
/// interval arithmetic, `beta = ||E||_inf < 1/2` gives
/// `||A^{-1} - X||_inf <= beta ||X||_inf / (1 - beta)` (Neumann series).
pub fn verified_inverse(a: &DMatrix<f64>) -> Option<Vec<Iv>> {
    let k = a.nrows();
    let x = a.clone().try_inverse()?;
    let mut beta = 0.0f64;
    let mut xnorm = 0.0f64;
    for i in 0..k {
        let mut row = 0.0;
        let mut xrow = 0.0;
        for j in 0..k {
            let mut s = Iv::point(if i == j { 1.0 } else { 0.0 });
            for l in 0..k {
                s = s.sub(Iv::point(x[(i, l)]).mul(Iv::point(a[(l, j)])));
            }
            row = up(row + s.mag());
            xrow = up(xrow + x[(i, j)].abs());
        }
        beta = beta.max(row);
        xnorm = xnorm.max(xrow);
    }
    if !(beta < MAX_RESIDUAL) || !xnorm.is_finite() {
        return None;
    }
    let delta =
        up(Iv::point(beta).mul(Iv::point(xnorm)).hi / Iv::point(1.0).sub(Iv::point(beta)).lo);
    Some(
        (0..k * k)
            .map(|t| Iv::point(x[(t / k, t % k)]).widen(delta))
            .collect(),
    )
}

/// An enclosure of the solutions `x = A^{-1} b` for every `A` in the
/// interval matrix `a` (row-major `k x k`) and every `b` in the interval
/// vector(s) `bs` (each of length `k`), or `None` when the enclosure fails
/// (`A` possibly singular).
///
/// With `R ~ mid(A)^{-1}` and `x~ = R mid(b)` (floats), `C = I - R A` and
/// `z = R (b - A x~)` in interval arithmetic: if `beta = ||C||_inf < 1` then
/// every `A` is non-singular and `y = x - x~` satisfies `y = z + C y`, so
/// `||y||_inf <= ||z||_inf / (1 - beta)` and `|y_i| <= |z_i| + (sum_j |C_ij|) ||y||_inf`.
pub fn solve(a: &[Iv], bs: &[Vec<Iv>], k: usize) -> Option<Vec<Vec<Iv>>> {
    let am = DMatrix::from_fn(k, k, |i, j| mid(a[i * k + j]));
    let r = am.try_inverse()?;
    let ri = |i: usize, j: usize| Iv::point(r[(i, j)]);
    // C = I - R A
    let mut crow = vec![0.0f64; k];
    for (i, cr) in crow.iter_mut().enumerate() {
        for j in 0..k {
            let mut s = Iv::point(if i == j { 1.0 } else { 0.0 });
            for l in 0..k {
                s = s.sub(ri(i, l).mul(a[l * k + j]));
            }
            *cr = up(*cr + s.mag());
        }
    }
    let beta = crow.iter().copied().fold(0.0f64, f64::max);
    if !(beta < MAX_RESIDUAL) {
        return None;
    }
    let one_minus = Iv::point(1.0).sub(Iv::point(beta)).lo;
    let mut out = Vec::with_capacity(bs.len());
    for b in bs {
        let bm: Vec<f64> = b.iter().map(|x| mid(*x)).collect();
        let xt: Vec<f64> = (0..k)
            .map(|i| (0..k).map(|j| r[(i, j)] * bm[j]).sum())
            .collect();
        // residual b - A x~
        let res: Vec<Iv> = (0..k)
            .map(|i| {
                let mut s = b[i];
                for j in 0..k {
                    s = s.sub(a[i * k + j].mul(Iv::point(xt[j])));
                }
                s
            })
            .collect();
        let z: Vec<Iv> = (0..k)
            .map(|i| {
                let mut s = Iv::point(0.0);
                for j in 0..k {
                    s = s.add(ri(i, j).mul(res[j]));
                }
                s
            })
            .collect();
        let zn = z.iter().fold(0.0f64, |m, v| m.max(v.mag()));
        let e = up(zn / one_minus);
        if !e.is_finite() {
            return None;
        }
        out.push(
            (0..k)
                .map(|i| {
                    let rad = up(z[i].mag() + up(crow[i] * e));
                    Iv::point(xt[i]).widen(rad)
                })
                .collect(),
        );
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verified_inverse_and_solve_contain_the_exact_answers() {
        let a = DMatrix::from_row_slice(3, 3, &[4.0, 1.0, 0.5, 1.0, 3.0, -1.0, 0.25, 2.0, 5.0]);
        let y = verified_inverse(&a).unwrap();
        let x = a.clone().try_inverse().unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let v = y[i * 3 + j];
                assert!(v.lo <= x[(i, j)] && x[(i, j)] <= v.hi && v.hi - v.lo < 1e-12);
            }
        }
        // an interval system: every matrix of the family and every rhs
        let ai: Vec<Iv> = (0..9)
            .map(|t| Iv::point(a[(t / 3, t % 3)]).widen(1e-3))
            .collect();
        let b = vec![Iv::new(1.0, 1.01), Iv::point(-2.0), Iv::new(0.5, 0.6)];
        let sol = solve(&ai, &[b], 3).unwrap();
        for k in 0..50 {
            let t = k as f64 / 49.0;
            let am = DMatrix::from_fn(3, 3, |i, j| {
                a[(i, j)] + 1e-3 * (2.0 * t - 1.0) * ((i + 2 * j) % 3) as f64 / 2.0
            });
            let bv = nalgebra::DVector::from_vec(vec![1.0 + 0.01 * t, -2.0, 0.5 + 0.1 * (1.0 - t)]);
            let xv = am.try_inverse().unwrap() * bv;
            for i in 0..3 {
                assert!(sol[0][i].lo <= xv[i] && xv[i] <= sol[0][i].hi, "{k} {i}");
            }
        }
    }

    /// `norm2_op_upper` bounds the 2-norm (the largest singular value) of
    /// every matrix below the given magnitudes, and is exact for a diagonal
    /// one.
    #[test]
    fn the_spectral_norm_bound_holds_for_random_matrices() {
        let mut rng = crate::rng::SplitMix64::new(7);
        for t in 0..400 {
            let (rows, cols) = (1 + t % 5, 1 + (t / 5) % 5);
            let a: Vec<f64> = (0..rows * cols)
                .map(|_| {
                    let x = rng.uniform(0.0, 1.0);
                    // mostly small off the diagonal, some full rows
                    if t % 3 == 0 {
                        x
                    } else {
                        x * x * x * 0.1
                    }
                })
                .collect();
            let bound = norm2_op_upper(&a, rows, cols);
            // the signs do not matter: |E| <= A
            for sign_seed in 0..4u64 {
                let e = DMatrix::from_fn(rows, cols, |i, j| {
                    let flip = (sign_seed >> ((i + j) % 2)) & 1 == 1;
                    let v = a[i * cols + j];
                    if flip {
                        -v
                    } else {
                        v
                    }
                });
                let norm = e.svd(false, false).singular_values.max();
                assert!(norm <= bound * (1.0 + 1e-12), "{t}: {norm} > {bound}");
            }
        }
        let d = norm2_op_upper(&[0.25, 0.0, 0.0, 0.5], 2, 2);
        assert!((0.5..0.5 * (1.0 + 1e-15)).contains(&d), "{d}");
        assert!(norm2_op_upper(&[1.0; 3], 2, 2).is_infinite());
    }

    #[test]
    fn midpoint_radius_combinations_contain_the_exact_values() {
        let a = Mr {
            m: [1.0, 2.0],
            r: 0.01,
        };
        let b = Mr {
            m: [-0.5, 0.25],
            r: 0.02,
        };
        let d = Mr {
            m: [0.3, -1.0],
            r: 0.0,
        };
        let w = Iv::new(0.1, 0.2);
        let s = Mr::stencil3(a, b, d, w);
        let l = Mr::lerp(b, a, w);
        for (ea, eb, ed, ww) in [
            (0.01, -0.02, 0.0, 0.1),
            (-0.01, 0.02, 0.0, 0.2),
            (0.0, 0.0, 0.0, 0.15),
        ] {
            for k in 0..2 {
                let (pa, pb, pd) = (a.m[k] + ea, b.m[k] + eb, d.m[k] + ed);
                let v = ww * pa + (1.0 - 2.0 * ww) * pb + ww * pd;
                assert!((v - s.m[k]).abs() <= s.r);
                let v = (1.0 - ww) * pb + ww * pa;
                assert!((v - l.m[k]).abs() <= l.r);
            }
        }
        // with exact weights the radius is the largest input radius (plus rounding)
        let s = Mr::stencil3(a, b, d, Iv::point(0.125));
        let l = Mr::lerp(b, a, Iv::point(0.25));
        assert!(s.r < 0.0200001 && l.r < 0.0200001, "{} {}", s.r, l.r);
    }
}
