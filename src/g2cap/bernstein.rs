//! Bernstein and uniform cubic B-spline helpers for the cap (math doc
//! section 14).

use super::ring::Point;

/// The degree of the cap patches in each variable.
pub const DEGREE: usize = 7;

/// A bidegree-(7, 7) control net: `net[j][k]`, `j` the index along `u`.
pub type Net = [[Point; DEGREE + 1]; DEGREE + 1];

fn binom(n: usize, k: usize) -> f64 {
    crate::bezier::binomial(n, k)
}

/// The weights `w_j` with `d^k/dt^k sum_j p_j B^7_j(t) = sum_j w_j p_j`:
///
/// ```text
/// w_j = 7!/(7-k)! sum_m (-1)^(k - j + m) C(k, j - m) B^(7-k)_m(t)
/// ```
pub fn deriv_weights(k: usize, t: f64) -> [f64; DEGREE + 1] {
    let mut w = [0.0; DEGREE + 1];
    if k > DEGREE {
        return w;
    }
    let d = DEGREE - k;
    let mut fall = 1.0;
    for r in 0..k {
        fall *= (DEGREE - r) as f64;
    }
    for m in 0..=d {
        let b = binom(d, m) * t.powi(m as i32) * (1.0 - t).powi((d - m) as i32);
        for q in 0..=k {
            let sign = if (k - q) % 2 == 0 { 1.0 } else { -1.0 };
            w[m + q] += fall * sign * binom(k, q) * b;
        }
    }
    w
}

/// Uniform cubic B-spline basis in monomial form: `N_l(u) = sum_r
/// BSPLINE[r][l] u^r` on one knot interval.
pub const BSPLINE: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [-3.0 / 6.0, 0.0, 3.0 / 6.0, 0.0],
    [3.0 / 6.0, -6.0 / 6.0, 3.0 / 6.0, 0.0],
    [-1.0 / 6.0, 3.0 / 6.0, -3.0 / 6.0, 1.0 / 6.0],
];

/// `E[l][j]`: the degree-7 Bernstein coefficients on `u` in `[0, 1]` of
/// `N_l(u + s)` (the basis polynomial of a cell continued by `s` cells).
/// Monomial to Bernstein: `b_j = sum_(r <= j) C(j, r) / C(7, r) m_r`.
pub fn bspline_in_bernstein(s: f64) -> [[f64; DEGREE + 1]; 4] {
    let mut out = [[0.0; DEGREE + 1]; 4];
    for (l, row) in out.iter_mut().enumerate() {
        // Monomial coefficients of N_l(u + s).
        let mut m = [0.0; 4];
        for r in 0..4 {
            for q in 0..=r {
                m[q] += BSPLINE[r][l] * binom(r, q) * s.powi((r - q) as i32);
            }
        }
        for (j, b) in row.iter_mut().enumerate() {
            for r in 0..=j.min(3) {
                *b += binom(j, r) / binom(DEGREE, r) * m[r];
            }
        }
    }
    out
}

/// The k-th derivative of the B-spline basis at `u`: `[N_0^(k), .., N_3^(k)]`.
pub fn bspline_deriv(k: usize, u: f64) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (l, o) in out.iter_mut().enumerate() {
        for r in k..4 {
            let mut f = 1.0;
            for q in 0..k {
                f *= (r - q) as f64;
            }
            *o += BSPLINE[r][l] * f * u.powi((r - k) as i32);
        }
    }
    out
}

/// The bicubic B-spline patch of a 4 x 4 grid, written on `[0,1]^2` shifted
/// by `(su, sv)` cells (`su = -1`: the cell to the left continued into
/// `[0,1]`) as a bidegree-(7, 7) net.
pub fn extended_net(grid: &[[Point; 4]; 4], su: f64, sv: f64) -> Net {
    let bu = bspline_in_bernstein(su);
    let bv = bspline_in_bernstein(sv);
    let mut net = [[[0.0; 3]; DEGREE + 1]; DEGREE + 1];
    for j in 0..=DEGREE {
        for k in 0..=DEGREE {
            for l in 0..4 {
                for m in 0..4 {
                    let w = bu[l][j] * bv[m][k];
                    for x in 0..3 {
                        net[j][k][x] += w * grid[l][m][x];
                    }
                }
            }
        }
    }
    net
}

/// `d^(du + dv) P / du^du dv^dv` of a net at `(u, v)`.
pub fn eval_net(net: &Net, u: f64, v: f64, du: usize, dv: usize) -> Point {
    let wu = deriv_weights(du, u);
    let wv = deriv_weights(dv, v);
    let mut out = [0.0; 3];
    for j in 0..=DEGREE {
        if wu[j] == 0.0 {
            continue;
        }
        for k in 0..=DEGREE {
            let w = wu[j] * wv[k];
            for x in 0..3 {
                out[x] += w * net[j][k][x];
            }
        }
    }
    out
}

/// A derivative of the bicubic B-spline patch of a 4 x 4 grid at `(u, v)`.
pub fn eval_bspline(grid: &[[Point; 4]; 4], u: f64, v: f64, du: usize, dv: usize) -> Point {
    let nu = bspline_deriv(du, u);
    let nv = bspline_deriv(dv, v);
    let mut out = [0.0; 3];
    for l in 0..4 {
        for m in 0..4 {
            let w = nu[l] * nv[m];
            for x in 0..3 {
                out[x] += w * grid[l][m][x];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_weights_match_differences_of_a_polynomial() {
        // p_j = j^2 as Bernstein coefficients; compare with a central difference.
        let t = 0.37;
        let val = |t: f64| {
            let w = deriv_weights(0, t);
            (0..8).map(|j| w[j] * (j * j) as f64).sum::<f64>()
        };
        let w1 = deriv_weights(1, t);
        let d1: f64 = (0..8).map(|j| w1[j] * (j * j) as f64).sum();
        let h = 1e-5;
        assert!((d1 - (val(t + h) - val(t - h)) / (2.0 * h)).abs() < 1e-7);
        let w2 = deriv_weights(2, t);
        let d2: f64 = (0..8).map(|j| w2[j] * (j * j) as f64).sum();
        assert!((d2 - (val(t + h) - 2.0 * val(t) + val(t - h)) / (h * h)).abs() < 1e-3);
    }

    #[test]
    fn continued_bspline_basis_agrees_with_the_monomial_form() {
        let e = bspline_in_bernstein(-1.0);
        for l in 0..4 {
            for &u in &[0.0, 0.3, 1.0] {
                let w = deriv_weights(0, u);
                let bern: f64 = (0..8).map(|j| w[j] * e[l][j]).sum();
                let mono = bspline_deriv(0, u - 1.0)[l];
                assert!((bern - mono).abs() < 1e-14, "{l} {u}");
            }
        }
    }
}
