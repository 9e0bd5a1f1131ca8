//! Eigenvalue condition numbers of the kernel's last input by inverse
//! iteration on its saved Hessenberg form, several eigenvalues interleaved.

use num_complex::Complex64;

/// The body of [`KernelWorkspace::condition_numbers`](super::KernelWorkspace::condition_numbers)
/// on the workspace's parts: the dimension `n`, the saved Hessenberg form
/// `hess_form` and its Frobenius norm, and the inverse-iteration storage.
pub(super) fn condition_numbers(
    n: usize,
    hess_form: &[f64],
    hess_norm: f64,
    st_real: &mut LaneStorage<f64>,
    st_complex: &mut LaneStorage<Complex64>,
    lambdas: &[Complex64],
    out: &mut [f64],
) {
    let lambdas = &lambdas[..lambdas.len().min(out.len())];
    if n == 0 {
        out[..lambdas.len()].iter_mut().for_each(|k| *k = 1.0);
        return;
    }
    let tiny = f64::EPSILON * hess_norm.max(f64::MIN_POSITIVE);
    let hess = &hess_form[..n * n];
    if n == 2 {
        // Closed form (valence 3 and 4 face blocks): no inverse iteration.
        let mut all = true;
        for (i, &z) in lambdas.iter().enumerate() {
            match kappa_2x2(hess, z, tiny) {
                Some(k) => out[i] = k,
                None => all = false,
            }
        }
        if all {
            return;
        }
    }
    // Real eigenvalues of a real matrix: real arithmetic throughout (the
    // LU, pivots and vectors the complex path computes, up to rounding,
    // at about a quarter of the cost; tested below).
    let mut real = [(0usize, 0.0f64); LANES];
    let mut complex = [(0usize, Complex64::new(0.0, 0.0)); LANES];
    let (mut nr, mut nc) = (0, 0);
    for (i, &z) in lambdas.iter().enumerate() {
        if z.im == 0.0 {
            real[nr] = (i, z.re);
            nr += 1;
            if nr == LANES {
                lanes(n, hess, &real, tiny, st_real, out);
                nr = 0;
            }
        } else {
            complex[nc] = (i, z);
            nc += 1;
            if nc == LANES {
                lanes(n, hess, &complex, tiny, st_complex, out);
                nc = 0;
            }
        }
    }
    lanes(n, hess, &real[..nr], tiny, st_real, out);
    lanes(n, hess, &complex[..nc], tiny, st_complex, out);
}

/// The condition number `kappa = ||x|| ||u|| / |u^T x|` of the eigenvalue
/// `lam` of the 2 x 2 matrix `h` (column major) in closed form, or `None`
/// when `h - lam I` is negligible (`h` a multiple of the identity: every
/// vector is an eigenvector; the caller's inverse iteration decides).
///
/// With `h = [[a, b], [c, d]]` and `lam` an eigenvalue, `h - lam I` has rank
/// one, so a right eigenvector is orthogonal (in the bilinear sense) to
/// either row: `x = (b, lam - a)` or `(lam - d, c)`; a left eigenvector
/// (`u^T h = lam u^T`) to either column: `u = (c, lam - a)` or `(lam - d, b)`.
/// Of each pair the one of larger norm is taken (the other may vanish). For
/// a complex `lam` the left eigenvector of the Hermitian definition is
/// `conj(u)`, so `|y^H x| = |u^T x|`. This is the quantity the inverse
/// iteration estimates (math doc section 10), computed exactly up to
/// rounding; `tests.rs` compares the two.
pub(super) fn kappa_2x2(h: &[f64], lam: Complex64, tiny: f64) -> Option<f64> {
    let (a, c, b, d) = (h[0], h[1], h[2], h[3]);
    let la = lam - a;
    let ld = lam - d;
    let pick = |p: [Complex64; 2], q: [Complex64; 2]| {
        let np = p[0].norm_sqr() + p[1].norm_sqr();
        let nq = q[0].norm_sqr() + q[1].norm_sqr();
        if np >= nq {
            (p, np.sqrt())
        } else {
            (q, nq.sqrt())
        }
    };
    let re = |v: f64| Complex64::new(v, 0.0);
    let (x, nx) = pick([re(b), la], [ld, re(c)]);
    let (u, nu) = pick([re(c), la], [ld, re(b)]);
    if !(nx > tiny && nu > tiny && nx.is_finite() && nu.is_finite()) {
        return None;
    }
    let dot = u[0] * x[0] + u[1] * x[1];
    let s = crate::spectral::classify::modulus(dot) / nx / nu;
    Some(if s == 0.0 || !s.is_finite() {
        f64::INFINITY
    } else {
        (1.0 / s).max(1.0)
    })
}

/// Most inverse iterations [`condition_numbers`] interleaves.
const LANES: usize = 3;

/// Storage of the interleaved inverse iterations: entry `e` of lane `l` at
/// `e * k + l` for `k` lanes.
#[derive(Debug, Default, Clone)]
pub(super) struct LaneStorage<T> {
    lu: Vec<T>,
    dinv: Vec<T>,
    x: Vec<T>,
    y: Vec<T>,
    piv: Vec<bool>,
}

/// Dispatches `shifts` (eigenvalue, output index) to the `k`-lane inverse
/// iteration for `k = shifts.len()` (0 to [`LANES`]).
fn lanes<T: Field>(
    n: usize,
    hess: &[f64],
    shifts: &[(usize, T)],
    tiny: f64,
    st: &mut LaneStorage<T>,
    out: &mut [f64],
) {
    fn run<T: Field, const K: usize>(
        n: usize,
        hess: &[f64],
        shifts: &[(usize, T)],
        tiny: f64,
        st: &mut LaneStorage<T>,
        out: &mut [f64],
    ) {
        let lam: [T; K] = std::array::from_fn(|l| shifts[l].1);
        let kappa = inverse_iteration_kappa::<T, K>(n, hess, lam, tiny, st);
        for (l, &(i, _)) in shifts.iter().enumerate() {
            out[i] = kappa[l];
        }
    }
    match shifts.len() {
        0 => {}
        1 => run::<T, 1>(n, hess, shifts, tiny, st, out),
        2 => run::<T, 2>(n, hess, shifts, tiny, st, out),
        _ => run::<T, LANES>(n, hess, shifts, tiny, st, out),
    }
}

/// The scalar types of the inverse iteration ([`f64`] for real eigenvalues,
/// [`Complex64`] otherwise).
pub(super) trait Field:
    Copy
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::SubAssign
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::MulAssign<f64>
    + std::iter::Sum
{
    fn from_f64(x: f64) -> Self;
    fn conj(self) -> Self;
    /// `|re| + |im|`: a cheap norm with the same pivoting quality as the modulus.
    fn l1(self) -> f64;
    fn norm_sqr(self) -> f64;
}

impl Field for f64 {
    fn from_f64(x: f64) -> Self {
        x
    }
    fn conj(self) -> Self {
        self
    }
    fn l1(self) -> f64 {
        self.abs()
    }
    fn norm_sqr(self) -> f64 {
        self * self
    }
}

impl Field for Complex64 {
    fn from_f64(x: f64) -> Self {
        Complex64::new(x, 0.0)
    }
    fn conj(self) -> Self {
        Complex64::conj(&self)
    }
    fn l1(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
    fn norm_sqr(self) -> f64 {
        Complex64::norm_sqr(&self)
    }
}

/// `kappa = ||x|| ||y|| / |y^H x|` of the `K` eigenvalues `lam` of the
/// Hessenberg matrix `hess`, each from one step of inverse iteration with
/// `H - lambda I` (LU factors with adjacent-row pivoting in `st.lu`), from
/// fixed, deterministic, non-special start vectors. The `K` lanes share every
/// loop; each lane's arithmetic is that of `K = 1`.
pub(super) fn inverse_iteration_kappa<T: Field, const K: usize>(
    n: usize,
    hess: &[f64],
    lam: [T; K],
    tiny: f64,
    st: &mut LaneStorage<T>,
) -> [f64; K] {
    let zero = T::from_f64(0.0);
    // Every entry is overwritten below: the storage is not cleared first (at
    // n = 64 that zeroing, up to 190 KB per call, was 1.2% of a profile's
    // samples).
    debug_assert!(hess.len() >= n * n);
    st.lu.resize(n * n * K, zero);
    for (e, &h) in st.lu.chunks_exact_mut(K).zip(hess) {
        e.fill(T::from_f64(h));
    }
    for i in 0..n {
        let d = &mut st.lu[(i + i * n) * K..(i + i * n + 1) * K];
        for (x, &z) in d.iter_mut().zip(&lam) {
            *x -= z;
        }
    }
    st.dinv.clear();
    st.dinv.resize(n * K, zero);
    st.piv.clear();
    st.piv.resize(n * K, false);
    hessenberg_lu::<T, K>(n, &mut st.lu, &mut st.piv, &mut st.dinv, tiny);
    st.x.clear();
    // x_i = 1 + (i * 7 mod 11) / 22 in every lane, the residue kept incrementally.
    let mut res = 0usize;
    for _ in 0..n {
        let v = T::from_f64(1.0 + res as f64 / 22.0);
        st.x.extend(std::iter::repeat_n(v, K));
        res = if res + 7 >= 11 { res + 7 - 11 } else { res + 7 };
    }
    st.y.clear();
    st.y.extend_from_slice(&st.x);
    hessenberg_solve::<T, K>(n, &st.lu, &st.piv, &st.dinv, &mut st.x);
    hessenberg_solve_adjoint::<T, K>(n, &st.lu, &st.piv, &st.dinv, &mut st.y);
    let mut xx = [0.0f64; K];
    let mut yy = [0.0f64; K];
    let mut dot = [zero; K];
    for (xs, ys) in st.x.chunks_exact(K).zip(st.y.chunks_exact(K)) {
        for l in 0..K {
            xx[l] += xs[l].norm_sqr();
            yy[l] += ys[l].norm_sqr();
            dot[l] = dot[l] + ys[l].conj() * xs[l];
        }
    }
    std::array::from_fn(|l| {
        // |y^H x| / (||x|| ||y||), a norm that is zero or not finite left as 1.
        let unit = |s: f64| {
            let s = s.sqrt();
            if s > 0.0 && s.is_finite() {
                s
            } else {
                1.0
            }
        };
        let d = dot[l].norm_sqr().sqrt() / unit(xx[l]) / unit(yy[l]);
        if d == 0.0 || !d.is_finite() {
            f64::INFINITY
        } else {
            (1.0 / d).max(1.0)
        }
    })
}

/// LU factorisation of `K` upper Hessenberg matrices (column major, lanes
/// interleaved) in place: step `k` optionally swaps rows `k, k+1`
/// (`piv[k] = true`) and eliminates the subdiagonal entry with multiplier
/// `l_k`, stored at `(k+1, k)`. Pivots that are exactly or nearly zero are
/// replaced by `tiny` (standard for inverse iteration at an eigenvalue).
fn hessenberg_lu<T: Field, const K: usize>(
    n: usize,
    a: &mut [T],
    piv: &mut [bool],
    dinv: &mut [T],
    tiny: f64,
) {
    debug_assert!(a.len() >= n * n * K && piv.len() >= n * K && dinv.len() >= n * K);
    let at = |i: usize, j: usize| (i + j * n) * K;
    for k in 0..n {
        if k + 1 < n {
            // Adjacent-row pivoting, branch-free (the choice is data-dependent
            // and unpredictable; a select per entry costs less than a mispredict).
            let swap: [bool; K] =
                std::array::from_fn(|l| u!(a[at(k + 1, k) + l]).l1() > u!(a[at(k, k) + l]).l1());
            for (l, &s) in swap.iter().enumerate() {
                *um!(piv[k * K + l]) = s;
            }
            for j in k..n {
                let (p, q) = (at(k, j), at(k + 1, j));
                for (l, &s) in swap.iter().enumerate() {
                    let (u, v) = (u!(a[p + l]), u!(a[q + l]));
                    *um!(a[p + l]) = if s { v } else { u };
                    *um!(a[q + l]) = if s { u } else { v };
                }
            }
        }
        let mut mult = [T::from_f64(0.0); K];
        for (l, ml) in mult.iter_mut().enumerate() {
            let p = at(k, k) + l;
            if u!(a[p]).l1() <= tiny {
                *um!(a[p]) = T::from_f64(tiny);
            }
            let inv = T::from_f64(1.0) / u!(a[p]);
            *um!(dinv[k * K + l]) = inv;
            if k + 1 < n {
                *ml = u!(a[at(k + 1, k) + l]) * inv;
                *um!(a[at(k + 1, k) + l]) = *ml;
            }
        }
        if k + 1 < n {
            for j in k + 1..n {
                let (p, q) = (at(k, j), at(k + 1, j));
                for (l, &m) in mult.iter().enumerate() {
                    let u = u!(a[p + l]);
                    *um!(a[q + l]) -= m * u;
                }
            }
        }
    }
}

/// Solves `H x = b` in every lane from [`hessenberg_lu`].
fn hessenberg_solve<T: Field, const K: usize>(
    n: usize,
    lu: &[T],
    piv: &[bool],
    dinv: &[T],
    b: &mut [T],
) {
    debug_assert!(lu.len() >= n * n * K && piv.len() >= n * K && dinv.len() >= n * K);
    debug_assert!(b.len() >= n * K);
    for k in 0..n.saturating_sub(1) {
        for l in 0..K {
            let (u, v) = (u!(b[k * K + l]), u!(b[(k + 1) * K + l]));
            let (bk, bk1) = if u!(piv[k * K + l]) { (v, u) } else { (u, v) };
            *um!(b[k * K + l]) = bk;
            *um!(b[(k + 1) * K + l]) = bk1 - u!(lu[(k + 1 + k * n) * K + l]) * bk;
        }
    }
    for j in (0..n).rev() {
        let bj: [T; K] = std::array::from_fn(|l| u!(b[j * K + l]) * u!(dinv[j * K + l]));
        for (l, &x) in bj.iter().enumerate() {
            *um!(b[j * K + l]) = x;
        }
        for i in 0..j {
            for (l, &x) in bj.iter().enumerate() {
                let ls = u!(lu[(i + j * n) * K + l]);
                *um!(b[i * K + l]) -= ls * x;
            }
        }
    }
}

/// Solves `H^H y = b` in every lane from [`hessenberg_lu`]: `M H = U` with
/// `M = M_{n-2} .. M_0`, `M_k = E_k P_k`, so `y = M_0^H .. M_{n-2}^H U^{-H} b`.
fn hessenberg_solve_adjoint<T: Field, const K: usize>(
    n: usize,
    lu: &[T],
    piv: &[bool],
    dinv: &[T],
    b: &mut [T],
) {
    debug_assert!(lu.len() >= n * n * K && piv.len() >= n * K && dinv.len() >= n * K);
    debug_assert!(b.len() >= n * K);
    for j in 0..n {
        let mut s: [T; K] = std::array::from_fn(|l| u!(b[j * K + l]));
        for i in 0..j {
            for (l, sl) in s.iter_mut().enumerate() {
                *sl -= u!(lu[(i + j * n) * K + l]).conj() * u!(b[i * K + l]);
            }
        }
        for (l, &sl) in s.iter().enumerate() {
            *um!(b[j * K + l]) = sl * u!(dinv[j * K + l]).conj();
        }
    }
    for k in (0..n.saturating_sub(1)).rev() {
        for l in 0..K {
            let m = u!(lu[(k + 1 + k * n) * K + l]);
            let t = u!(b[(k + 1) * K + l]);
            let u = u!(b[k * K + l]) - m.conj() * t;
            let (bk, bk1) = if u!(piv[k * K + l]) { (t, u) } else { (u, t) };
            *um!(b[k * K + l]) = bk;
            *um!(b[(k + 1) * K + l]) = bk1;
        }
    }
}
