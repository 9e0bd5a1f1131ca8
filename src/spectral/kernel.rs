//! A small dense eigenvalue kernel: Householder reduction to Hessenberg form
//! followed by the Francis double-shift QR iteration, eigenvalues only.
//!
//! Written for the many tiny matrices of parameter sweeps (the `n x n` face
//! block of the Doo-Sabin family, `n <= 64` typically), where the set-up cost of
//! a general-purpose library dominates. Properties:
//!
//! * **no allocation per call**: all storage lives in a reusable
//!   [`KernelWorkspace`];
//! * **bounded iterations**: at most [`MAX_SWEEPS_PER_EIGENVALUE`] QR sweeps per
//!   deflation and [`MAX_SWEEPS_PER_DIMENSION`] `* n` sweeps in total, with
//!   exceptional shifts every [`EXCEPTIONAL_SHIFT_PERIOD`] sweeps (the shifts of
//!   LAPACK's `dlahqr`, which break the cycle of the cyclic permutation
//!   matrices); running out of sweeps is an error, never a hang;
//! * deflation when a subdiagonal entry is below `eps` times its neighbouring
//!   diagonal entries (the standard `dlahqr` criterion, backward stable);
//! * range: entries beyond about `2^510` in modulus overflow in the shift
//!   computation and end in [`SpectralError::NoConvergence`] (an error, never
//!   a wrong spectrum; measured on random matrices: `2^510` converges,
//!   `2^515` does not). Local subdivision matrices have entries in `[0, 1]`;
//!   for other inputs, scale by a power of two first (exact).
//!
//! The algorithm is the classical EISPACK `hqr` (Wilkinson and Reinsch,
//! Handbook for Automatic Computation II, 1971), which is backward stable: the
//! computed eigenvalues are exact for a matrix within `O(n eps ||A||)` of the
//! input. It is tested against faer's LAPACK-style implementation.
//!
//! The module also computes eigenvalue condition numbers of a few selected
//! eigenvalues by inverse iteration on the Hessenberg form
//! ([`KernelWorkspace::condition_number`]), `O(n^2)` each, without allocation
//! (in real arithmetic for a real eigenvalue).
//!
//! Speed notes (small `n` is latency-bound: the chain scale -> square root ->
//! divisions of each 3x3 reflector dominates): reflectors use one reciprocal
//! instead of several divisions, skip EISPACK's rescaling of `(p, q, r)` where
//! it cannot matter ([`SAFE_MIN`]..[`SAFE_MAX`]), and the last reflector of
//! a sweep has its own two-row loops. Many matrices of one dimension (a
//! sweep) go through [`KernelWorkspace::eigenvalues_batch`]: [`BATCH`] of
//! them in lock step, one per SIMD lane, with the same arithmetic bit for bit
//! (module `lockstep`; 2.1x to 2.4x the throughput of one at a time at
//! valences 5 to 16).

use super::SpectralError;
use num_complex::Complex64;

/// Unchecked read of `a[k]` in the kernel's inner loops, where every index
/// is bounded by the loop invariants (checked in debug builds).
macro_rules! u {
    ($a:ident[$k:expr]) => {{
        let k = $k;
        debug_assert!(k < $a.len());
        // SAFETY: k < a.len() by the caller's loop bounds (checked in debug).
        unsafe { *$a.get_unchecked(k) }
    }};
}

/// Unchecked mutable `a[k]`; see `u!`.
macro_rules! um {
    ($a:ident[$k:expr]) => {{
        let k = $k;
        debug_assert!(k < $a.len());
        // SAFETY: as in `u!`.
        unsafe { $a.get_unchecked_mut(k) }
    }};
}

mod lockstep;
pub use lockstep::BATCH;

/// QR sweeps allowed before one eigenvalue (or a 2x2 block) deflates.
///
/// LAPACK allows 30 per eigenvalue with exceptional shifts at 10 and 20; we
/// allow twice that with exceptional shifts every 10 sweeps: still a hard bound.
pub const MAX_SWEEPS_PER_EIGENVALUE: usize = 60;

/// Total QR sweeps allowed, per matrix dimension (LAPACK's `itmax = 30 n`).
pub const MAX_SWEEPS_PER_DIMENSION: usize = 30;

/// An exceptional (ad hoc) shift is used every this many sweeps without deflation.
pub const EXCEPTIONAL_SHIFT_PERIOD: usize = 10;

/// Upper end (`2^500`) of the range of `x = |p| + |q| + |r|` in which the QR
/// sweep (`hqr`) forms `p^2 + q^2 + r^2` without EISPACK's rescaling by `x`:
/// that sum lies in `[x^2 / 3, x^2]`, so for `2^-500 <= x <= 2^500` it is a
/// normal number (`>= 2^-1002`, `<= 2^1000`) and can neither overflow nor lose
/// precision to underflow; outside the range the sweep rescales as EISPACK does.
pub const SAFE_MAX: f64 = 3.273_390_607_896_142e150;
/// Lower end (`2^-500`) of the no-rescaling range; see [`SAFE_MAX`].
pub const SAFE_MIN: f64 = 3.054_936_363_499_605e-151;

/// Reusable storage for the kernel (grows to the largest size seen).
#[derive(Debug, Default, Clone)]
pub struct KernelWorkspace {
    n: usize,
    /// Working copy (column major, `n x n`), destroyed by the QR iteration.
    h: Vec<f64>,
    /// Untouched copy of the input.
    a: Vec<f64>,
    /// The Hessenberg form of the input, for condition numbers.
    hess: Vec<f64>,
    /// Householder vector and scratch.
    v: Vec<f64>,
    w: Vec<f64>,
    /// Inverse-iteration storage for real and for complex eigenvalues.
    real: LaneStorage<f64>,
    complex: LaneStorage<Complex64>,
    /// Frobenius norm of `hess`.
    hess_norm: f64,
    /// Eigenvalues (real and imaginary parts).
    wr: Vec<f64>,
    wi: Vec<f64>,
    sweeps: usize,
    /// Lane-interleaved storage of [`eigenvalues_batch`](Self::eigenvalues_batch)
    /// (used in the first workspace of a batch): matrices, Householder vector,
    /// scratch.
    batch: [Vec<lockstep::Lanes>; 3],
}

impl KernelWorkspace {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    /// Prepares an `n x n` input and returns it for filling (column major,
    /// entry `(i, j)` at `i + j n`). All entries are zeroed first.
    pub fn input(&mut self, n: usize) -> &mut [f64] {
        self.n = n;
        let nn = n * n;
        self.a.clear();
        self.a.resize(nn, 0.0);
        &mut self.a
    }

    /// The current input matrix (column major).
    pub fn matrix(&self) -> &[f64] {
        &self.a[..self.n * self.n]
    }

    /// The Hessenberg form computed by the last
    /// [`eigenvalues`](Self::eigenvalues) call (column major).
    pub fn hessenberg_form(&self) -> &[f64] {
        &self.hess[..self.n * self.n]
    }

    /// QR sweeps used by the last [`eigenvalues`](Self::eigenvalues) call.
    pub fn last_sweeps(&self) -> usize {
        self.sweeps
    }

    /// Dimension of the current input.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Computes all eigenvalues of the current input; returns `(re, im)`
    /// slices in no particular order (complex pairs are adjacent, positive
    /// imaginary part first).
    pub fn eigenvalues(&mut self) -> Result<(&[f64], &[f64]), SpectralError> {
        self.reduce()?;
        self.iterate()?;
        Ok((&self.wr, &self.wi))
    }

    /// [`eigenvalues`](Self::eigenvalues) of the inputs of [`BATCH`]
    /// workspaces at once: the same arithmetic, bit for bit, but when all
    /// inputs have the same dimension, at most [`LOCKSTEP_MAX_DIM`], the
    /// Hessenberg reductions and the QR iterations run in lock step, one
    /// matrix per lane of a SIMD vector (256-bit AVX2 where the processor
    /// has it). Read the results with
    /// [`last_eigenvalues`](Self::last_eigenvalues).
    ///
    /// ```
    /// use subdiv_lab::spectral::kernel::{KernelWorkspace, BATCH};
    /// let mut ws: Vec<KernelWorkspace> = (0..BATCH).map(|_| KernelWorkspace::new()).collect();
    /// for (i, w) in ws.iter_mut().enumerate() {
    ///     // diag(1, 2, 3) + i times the cyclic shift
    ///     let a = w.input(3);
    ///     a.copy_from_slice(&[1.0, i as f64, 0.0, 0.0, 2.0, i as f64, i as f64, 0.0, 3.0]);
    /// }
    /// let mut lone = ws.clone();
    /// let lanes: &mut [KernelWorkspace; BATCH] = (&mut ws[..]).try_into().unwrap();
    /// let res = KernelWorkspace::eigenvalues_batch(lanes.each_mut());
    /// for (w, (l, r)) in ws.iter().zip(lone.iter_mut().zip(res)) {
    ///     r.unwrap();
    ///     let (re, im) = l.eigenvalues().unwrap();
    ///     assert_eq!(w.last_eigenvalues(), (re, im)); // bit for bit
    /// }
    /// ```
    pub fn eigenvalues_batch(ws: [&mut Self; BATCH]) -> [Result<(), SpectralError>; BATCH] {
        Self::eigenvalues_lanes(ws.map(Some)).map(|r| r.unwrap_or(Ok(())))
    }

    /// [`eigenvalues_batch`](Self::eigenvalues_batch) with unused lanes
    /// (`None`, whose result is `None`).
    pub(crate) fn eigenvalues_lanes(
        ws: [Option<&mut Self>; BATCH],
    ) -> [Option<Result<(), SpectralError>>; BATCH] {
        let mut dims = ws.iter().flatten().map(|w| w.n);
        let n = dims.next().unwrap_or(0);
        if !(LOCKSTEP_MIN_DIM..=LOCKSTEP_MAX_DIM).contains(&n) || dims.any(|m| m != n) {
            return ws.map(|w| w.map(|w| w.eigenvalues().map(|_| ())));
        }
        let mut ws = ws;
        let mut out: [Option<Result<(), SpectralError>>; BATCH] =
            std::array::from_fn(|l| ws[l].as_ref().map(|w| w.check()));
        // The interleaved storage lives in the first workspace of the batch.
        let Some(home) = ws.iter().position(Option::is_some) else {
            return out;
        };
        let [mut h, mut v, mut w] = std::mem::take(&mut ws[home].as_mut().expect("some").batch);
        h.clear();
        h.resize(lockstep::storage_len(n), [0.0; BATCH]);
        v.clear();
        v.resize(n, [0.0; BATCH]);
        w.clear();
        w.resize(n, [0.0; BATCH]);
        let mut dims = [0; BATCH];
        // Unused and failed lanes keep dimension 0 (finished at once) and a
        // zero matrix.
        let mut hess: [Vec<f64>; BATCH] = Default::default();
        let mut wr: [Vec<f64>; BATCH] = Default::default();
        let mut wi: [Vec<f64>; BATCH] = Default::default();
        for (lane, x) in ws.iter_mut().enumerate() {
            if let (Some(x), Some(Ok(()))) = (x, &out[lane]) {
                dims[lane] = n;
                for (e, &y) in h.iter_mut().zip(&x.a[..n * n]) {
                    e[lane] = y;
                }
                // Borrow the lane's output buffers for the run.
                hess[lane] = std::mem::take(&mut x.hess);
                wr[lane] = std::mem::take(&mut x.wr);
                wr[lane].clear();
                wr[lane].resize(n, 0.0);
                wi[lane] = std::mem::take(&mut x.wi);
                wi[lane].clear();
                wi[lane].resize(n, 0.0);
            }
        }
        let sweeps = lockstep_run(LockstepRun {
            dims,
            h: &mut h,
            v: &mut v,
            w: &mut w,
            hess: hess.each_mut(),
            wr: wr.each_mut().map(Vec::as_mut_slice),
            wi: wi.each_mut().map(Vec::as_mut_slice),
        });
        ws[home].as_mut().expect("some").batch = [h, v, w];
        for (lane, (x, s)) in ws.into_iter().zip(sweeps).enumerate() {
            if let (Some(x), Some(Ok(()))) = (x, &out[lane]) {
                x.hess = std::mem::take(&mut hess[lane]);
                x.wr = std::mem::take(&mut wr[lane]);
                x.wi = std::mem::take(&mut wi[lane]);
                x.hess_norm = x.hess[..n * n].iter().map(|x| x * x).sum::<f64>().sqrt();
                out[lane] = Some(s.map(|s| x.sweeps = s));
            }
        }
        out
    }

    /// The QR iteration on the reduced input (after [`reduce`](Self::reduce)).
    fn iterate(&mut self) -> Result<(), SpectralError> {
        self.sweeps = hqr(self.n, &mut self.h, &mut self.wr, &mut self.wi)?;
        Ok(())
    }

    /// The eigenvalues `(re, im)` computed by the last successful
    /// [`eigenvalues`](Self::eigenvalues) or
    /// [`eigenvalues_batch`](Self::eigenvalues_batch) call.
    pub fn last_eigenvalues(&self) -> (&[f64], &[f64]) {
        (&self.wr[..self.n], &self.wi[..self.n])
    }

    /// Checks the input, reduces a copy to Hessenberg form (kept for the
    /// condition numbers) and prepares the QR iteration's storage.
    fn reduce(&mut self) -> Result<(), SpectralError> {
        self.check()?;
        let n = self.n;
        self.h.clear();
        self.h.extend_from_slice(&self.a[..n * n]);
        self.v.clear();
        self.v.resize(n, 0.0);
        self.wr.clear();
        self.wr.resize(n, 0.0);
        self.wi.clear();
        self.wi.resize(n, 0.0);
        self.w.clear();
        self.w.resize(n, 0.0);
        hessenberg(n, &mut self.h, &mut self.v, &mut self.w);
        self.hess.clear();
        self.hess.extend_from_slice(&self.h);
        self.hess_norm = self.hess.iter().map(|x| x * x).sum::<f64>().sqrt();
        Ok(())
    }

    /// Checks that every input entry is finite.
    fn check(&self) -> Result<(), SpectralError> {
        let n = self.n;
        match self.a[..n * n].iter().position(|x| !x.is_finite()) {
            Some(k) => Err(SpectralError::NonFinite {
                row: k % n,
                col: k / n,
            }),
            None => Ok(()),
        }
    }

    /// The eigenvalue condition number `kappa = ||x|| ||y|| / |y^H x|` of the
    /// (computed) eigenvalue `lambda` of the input last passed to
    /// [`KernelWorkspace::eigenvalues`], with right and left eigenvectors `x`,
    /// `y` from one step of inverse iteration (from a fixed non-special start
    /// vector; one step suffices because `lambda` is accurate to rounding, so
    /// the amplification of the eigenvector component is `~ gap / eps`).
    ///
    /// Works on the saved Hessenberg form `H = Q^T A Q` (`kappa` is invariant
    /// under orthogonal similarity), so one call costs `O(n^2)`: an LU
    /// factorisation of the Hessenberg matrix `H - lambda I` with adjacent-row
    /// pivoting and four triangular solves.
    ///
    /// `kappa >= 1`; a value near `1 / eps` means `lambda` is (numerically) a
    /// multiple eigenvalue with a non-trivial Jordan block, or an ill-matched
    /// pair of vectors in a multi-dimensional eigenspace.
    pub fn condition_number(&mut self, lambda: Complex64) -> f64 {
        let mut out = [0.0];
        self.condition_numbers(&[lambda], &mut out);
        out[0]
    }

    /// [`condition_number`](Self::condition_number) of several eigenvalues at
    /// once: `out[i]` for `lambdas[i]`, for `i < min(lambdas.len(), out.len())`.
    ///
    /// The inverse iterations of up to three eigenvalues run interleaved, as
    /// lanes of one loop (real eigenvalues in real arithmetic, complex ones in
    /// complex arithmetic): each lane's arithmetic is exactly that of a lone
    /// call, but the processor overlaps their dependency chains (the pivot
    /// divisions of the LU factorisation, the substitutions), so three
    /// condition numbers cost little more than one.
    pub fn condition_numbers(&mut self, lambdas: &[Complex64], out: &mut [f64]) {
        let n = self.n;
        let lambdas = &lambdas[..lambdas.len().min(out.len())];
        if n == 0 {
            out[..lambdas.len()].iter_mut().for_each(|k| *k = 1.0);
            return;
        }
        let tiny = f64::EPSILON * self.hess_norm.max(f64::MIN_POSITIVE);
        let hess = &self.hess[..n * n];
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
                    lanes(n, hess, &real, tiny, &mut self.real, out);
                    nr = 0;
                }
            } else {
                complex[nc] = (i, z);
                nc += 1;
                if nc == LANES {
                    lanes(n, hess, &complex, tiny, &mut self.complex, out);
                    nc = 0;
                }
            }
        }
        lanes(n, hess, &real[..nr], tiny, &mut self.real, out);
        lanes(n, hess, &complex[..nc], tiny, &mut self.complex, out);
    }
}

/// Smallest dimension at which [`KernelWorkspace::eigenvalues_batch`] runs
/// the lock-step kernel: below it there is nothing to reduce and at most one
/// 2x2 block to deflate, and the batch's gathering and scattering cost more
/// than they save (valence 3, dimension 2: 0.87x the throughput of one at a
/// time).
pub const LOCKSTEP_MIN_DIM: usize = 3;

/// Largest dimension at which [`KernelWorkspace::eigenvalues_batch`] runs
/// the lock-step kernel (larger batches run one matrix at a time): the
/// negligible subdiagonal entries of a lane are kept as the bits of a `u64`.
/// At 64 the lock-step kernel still runs 1.4x faster than one matrix at a
/// time (about 200 us against 285 us per matrix; see the `lockstep` module).
pub const LOCKSTEP_MAX_DIM: usize = 64;

/// The storage of one [`lockstep_run`]: the interleaved matrices `h` (lane
/// `l` of dimension `dims[l]`, all equal or 0 for an unused lane), the
/// Householder vector and scratch `v`, `w`, and each lane's outputs (its
/// Hessenberg form and eigenvalues).
struct LockstepRun<'a> {
    dims: [usize; BATCH],
    h: &'a mut [lockstep::Lanes],
    v: &'a mut [lockstep::Lanes],
    w: &'a mut [lockstep::Lanes],
    hess: [&'a mut Vec<f64>; BATCH],
    wr: [&'a mut [f64]; BATCH],
    wi: [&'a mut [f64]; BATCH],
}

/// Each lane's sweep count or error.
type LaneResults = [Result<usize, SpectralError>; BATCH];

/// Lock-step Hessenberg reduction and QR iteration of the interleaved
/// matrices, the Hessenberg forms copied out; on x86-64 processors with
/// AVX2, compiled for AVX2 (a runtime check; the portable build runs the same
/// code with SSE2).
fn lockstep_run(run: LockstepRun<'_>) -> LaneResults {
    #[inline(always)]
    fn body(run: LockstepRun<'_>) -> LaneResults {
        let LockstepRun {
            dims,
            h,
            v,
            w,
            hess,
            wr,
            wi,
        } = run;
        let n = dims.iter().copied().max().unwrap_or(0);
        lockstep::hessenberg(n, h, v, w);
        for (lane, x) in hess.into_iter().enumerate() {
            x.clear();
            x.extend(h[..n * n].iter().map(|e| e[lane]));
        }
        lockstep::hqr(dims, n, h, wr, wi)
    }
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        unsafe fn avx2(run: LockstepRun<'_>) -> LaneResults {
            body(run)
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2 (checked just above).
            return unsafe { avx2(run) };
        }
    }
    body(run)
}

/// Most inverse iterations [`KernelWorkspace::condition_numbers`] interleaves.
const LANES: usize = 3;

/// Storage of the interleaved inverse iterations: entry `e` of lane `l` at
/// `e * k + l` for `k` lanes.
#[derive(Debug, Default, Clone)]
struct LaneStorage<T> {
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
trait Field:
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
fn inverse_iteration_kappa<T: Field, const K: usize>(
    n: usize,
    hess: &[f64],
    lam: [T; K],
    tiny: f64,
    st: &mut LaneStorage<T>,
) -> [f64; K] {
    let zero = T::from_f64(0.0);
    st.lu.clear();
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

/// Householder reduction of the column-major `n x n` matrix `h` to upper
/// Hessenberg form, in place (entries below the subdiagonal are zeroed).
/// `v` and `w` are scratch vectors of length `n`. All inner loops run over
/// contiguous column slices.
pub(crate) fn hessenberg(n: usize, h: &mut [f64], v: &mut [f64], w: &mut [f64]) {
    if n < 3 {
        return;
    }
    for k in 0..n - 2 {
        let col = &h[k * n + k + 1..(k + 1) * n];
        let scale = col.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if scale == 0.0 {
            continue;
        }
        let vk = &mut v[k + 1..n];
        let mut norm2 = 0.0;
        // Scaling by a power of two would be exact; by 1/scale it rounds once
        // more than x / scale, which is immaterial for a reflector.
        let inv_scale = 1.0 / scale;
        for (vi, x) in vk.iter_mut().zip(col) {
            let t = x * inv_scale;
            *vi = t;
            norm2 += t * t;
        }
        let x0 = vk[0];
        let alpha = -x0.signum() * norm2.sqrt();
        vk[0] = x0 - alpha;
        let vtv = norm2 - x0 * x0 + vk[0] * vk[0];
        if vtv == 0.0 {
            continue;
        }
        let beta = 2.0 / vtv;
        // Left: rows k+1..n, columns k+1..n (column k is set explicitly).
        for j in k + 1..n {
            let cj = &mut h[j * n + k + 1..(j + 1) * n];
            let s: f64 = cj.iter().zip(vk.iter()).map(|(x, y)| x * y).sum::<f64>() * beta;
            for (x, y) in cj.iter_mut().zip(vk.iter()) {
                *x -= s * y;
            }
        }
        h[k + 1 + k * n] = alpha * scale;
        for x in &mut h[k * n + k + 2..(k + 1) * n] {
            *x = 0.0;
        }
        // Right: all rows, columns k+1..n: w = H v, H -= beta w v^T.
        let w = &mut w[..n];
        w.iter_mut().for_each(|x| *x = 0.0);
        for (j, &vj) in (k + 1..n).zip(vk.iter()) {
            let cj = &h[j * n..(j + 1) * n];
            for (wi, x) in w.iter_mut().zip(cj) {
                *wi += x * vj;
            }
        }
        for (j, &vj) in (k + 1..n).zip(vk.iter()) {
            let f = beta * vj;
            let cj = &mut h[j * n..(j + 1) * n];
            for (x, wi) in cj.iter_mut().zip(w.iter()) {
                *x -= wi * f;
            }
        }
    }
}

/// Applies the 3-row reflector of [`hqr`] to one column segment `c = (c_k, c_k+1, c_k+2)`.
#[inline(always)]
fn row3(c: &mut [f64], q: f64, r: f64, x: f64, y: f64, z: f64) {
    let pp = c[0] + q * c[1] + r * c[2];
    c[2] -= pp * z;
    c[1] -= pp * y;
    c[0] -= pp * x;
}

/// The 2-row reflector of the last step of a [`hqr`] sweep.
#[inline(always)]
fn row2(c: &mut [f64], q: f64, x: f64, y: f64) {
    let pp = c[0] + q * c[1];
    c[1] -= pp * y;
    c[0] -= pp * x;
}

/// Unchecked read of entry `(i, j)` of the column-major `n x n` matrix `a`
/// in the QR iteration: every index there is `< n` by the loop invariants
/// (`l <= k <= nu < n`, and the guards on `k + 2` / `m - 1`), checked in
/// debug builds.
macro_rules! g {
    ($a:ident, $n:ident, $i:expr, $j:expr) => {{
        let (i, j) = ($i, $j);
        debug_assert!(i < $n && j < $n && $a.len() >= $n * $n);
        // SAFETY: i, j < n and a.len() >= n * n.
        unsafe { *$a.get_unchecked(i + j * $n) }
    }};
}

/// Unchecked mutable access to entry `(i, j)`; see `g!`.
macro_rules! m {
    ($a:ident, $n:ident, $i:expr, $j:expr) => {{
        let (i, j) = ($i, $j);
        debug_assert!(i < $n && j < $n && $a.len() >= $n * $n);
        // SAFETY: i, j < n and a.len() >= n * n.
        unsafe { $a.get_unchecked_mut(i + j * $n) }
    }};
}

/// Entry access of the QR iteration's bookkeeping ([`Hqr::search`]): the
/// same code runs on a column-major matrix ([`ColMajor`]) and on one lane of
/// the lane-interleaved storage of [`lockstep`].
trait HqrMatrix {
    /// Entry `(i, j)`.
    fn at(&self, i: usize, j: usize) -> f64;
    /// Mutable entry `(i, j)`.
    fn at_mut(&mut self, i: usize, j: usize) -> &mut f64;
}

/// A column-major `n x n` matrix (entry `(i, j)` at `i + j n`).
struct ColMajor<'a> {
    a: &'a mut [f64],
    n: usize,
}

impl HqrMatrix for ColMajor<'_> {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        let (a, n) = (&self.a, self.n);
        g!(a, n, i, j)
    }
    #[inline(always)]
    fn at_mut(&mut self, i: usize, j: usize) -> &mut f64 {
        let (a, n) = (&mut self.a, self.n);
        m!(a, n, i, j)
    }
}

/// Francis double-shift QR on an upper Hessenberg matrix (EISPACK `hqr`,
/// eigenvalues only), with bounded iterations: [`Hqr::step`] until done.
pub(crate) fn hqr(
    n: usize,
    a: &mut [f64],
    wr: &mut [f64],
    wi: &mut [f64],
) -> Result<usize, SpectralError> {
    let mut s = Hqr::new(n, &ColMajor { a, n });
    while !s.step(a, wr, wi)? {}
    Ok(s.total)
}

/// The state of one [`hqr`] run between two [`Hqr::step`]s: either between
/// sweeps (`chasing == false`: the next step looks for a negligible
/// subdiagonal entry, deflates or starts a sweep) or inside a sweep (the next
/// step applies the reflector at row `k`).
struct Hqr {
    n: usize,
    anorm: f64,
    budget: usize,
    total: usize,
    /// Accumulated exceptional shift.
    t: f64,
    /// Index of the last row of the active block (inclusive); `< 0`: done.
    nn: isize,
    /// Sweeps since the last deflation.
    its: usize,
    chasing: bool,
    /// Active block `l..=nu`; the sweep's next reflector is at row `k`.
    l: usize,
    nu: usize,
    k: usize,
    /// First reflector's vector (set up by the shift).
    p: f64,
    q: f64,
    r: f64,
}

impl Hqr {
    #[inline(always)]
    fn new<A: HqrMatrix>(n: usize, a: &A) -> Self {
        let mut anorm = 0.0;
        for j in 0..n {
            for i in 0..n.min(j + 2) {
                anorm += a.at(i, j).abs();
            }
        }
        Hqr {
            n,
            anorm,
            budget: MAX_SWEEPS_PER_DIMENSION * n.max(10),
            total: 0,
            t: 0.0,
            nn: n as isize - 1,
            its: 0,
            chasing: false,
            l: 0,
            nu: 0,
            k: 0,
            p: 0.0,
            q: 0.0,
            r: 0.0,
        }
    }

    /// One unit of work: a deflation search (deflating one or two
    /// eigenvalues into `wr`, `wi`, or setting up the next sweep's shift), or
    /// one reflector of the current sweep. `Ok(true)` once every eigenvalue is
    /// found.
    #[inline(always)]
    fn step(
        &mut self,
        a: &mut [f64],
        wr: &mut [f64],
        wi: &mut [f64],
    ) -> Result<bool, SpectralError> {
        let n = self.n;
        debug_assert!(a.len() >= n * n && wr.len() >= n && wi.len() >= n);
        if self.chasing {
            let (l, m, k, nu) = (self.l, self.l, self.k, self.nu);
            reflector(a, n, l, m, k, nu, self.p, self.q, self.r);
            self.k += 1;
            if self.k >= nu {
                self.chasing = false;
            }
            return Ok(false);
        }
        self.search(&mut ColMajor { a, n }, wr, wi)
    }

    /// The step between sweeps: looks for a negligible subdiagonal entry,
    /// deflates one or two eigenvalues into `wr`, `wi`, or sets up the next
    /// sweep's shift (then `chasing` is set). `Ok(true)` once every eigenvalue
    /// is found. Generic over the storage so that the lock-step iteration of
    /// several matrices ([`lockstep`]) runs exactly this code on each lane.
    #[inline(always)]
    fn search<A: HqrMatrix>(
        &mut self,
        a: &mut A,
        wr: &mut [f64],
        wi: &mut [f64],
    ) -> Result<bool, SpectralError> {
        if self.nn < 0 {
            return Ok(true);
        }
        let nu = self.nn as usize;
        // Look for a small subdiagonal element.
        let mut l = nu;
        while l >= 1 {
            if negligible(a.at(l, l - 1), a.at(l - 1, l - 1), a.at(l, l), self.anorm) {
                *a.at_mut(l, l - 1) = 0.0;
                break;
            }
            l -= 1;
        }
        self.split_at(l, a, wr, wi)
    }

    /// The rest of [`search`](Self::search) once the active block `l..=nu`
    /// is known (entry `(l, l - 1)` negligible and zeroed, or `l = 0`).
    #[inline(always)]
    fn split_at<A: HqrMatrix>(
        &mut self,
        l: usize,
        a: &mut A,
        wr: &mut [f64],
        wi: &mut [f64],
    ) -> Result<bool, SpectralError> {
        let n = self.n;
        let nu = self.nn as usize;
        let t = self.t;
        let mut x = a.at(nu, nu);
        if l == nu {
            // One root found.
            wr[nu] = x + t;
            wi[nu] = 0.0;
            self.nn -= 1;
            self.its = 0;
            return Ok(self.nn < 0);
        }
        let mut y = a.at(nu - 1, nu - 1);
        let mut w = a.at(nu, nu - 1) * a.at(nu - 1, nu);
        if l + 1 == nu {
            // Two roots found.
            let p = 0.5 * (y - x);
            let q = p * p + w;
            let z = q.abs().sqrt();
            x += t;
            if q >= 0.0 {
                let z = p + z.copysign(p);
                wr[nu - 1] = x + z;
                wr[nu] = if z != 0.0 { x - w / z } else { x + z };
                wi[nu - 1] = 0.0;
                wi[nu] = 0.0;
            } else {
                wr[nu - 1] = x + p;
                wr[nu] = x + p;
                wi[nu - 1] = z;
                wi[nu] = -z;
            }
            self.nn -= 2;
            self.its = 0;
            return Ok(self.nn < 0);
        }
        // No roots found yet: one more sweep.
        if self.its >= MAX_SWEEPS_PER_EIGENVALUE || self.total >= self.budget {
            return Err(SpectralError::NoConvergence {
                routine: "small-matrix QR kernel",
                size: n,
                sweeps: self.total,
            });
        }
        if self.its > 0 && self.its % EXCEPTIONAL_SHIFT_PERIOD == 0 {
            // Exceptional shift (EISPACK hqr; dlahqr's constants 0.75 and -0.4375).
            self.t += x;
            for i in 0..=nu {
                *a.at_mut(i, i) -= x;
            }
            let s = a.at(nu, nu - 1).abs() + a.at(nu - 1, nu - 2).abs();
            x = 0.75 * s;
            y = x;
            w = -0.4375 * s * s;
        } else {
            // LAPACK 3.10 dlahqr: when both Francis shifts are real, use the
            // one closer to a[nu][nu] twice. Two distinct real shifts placed
            // symmetrically in a spectrum that is itself symmetric (NURDS
            // with even n) stall the iteration.
            let p = 0.5 * (y - x);
            let disc = p * p + w;
            if disc >= 0.0 {
                let sq = disc.sqrt();
                let mid = 0.5 * (x + y);
                let (s1, s2) = (mid + sq, mid - sq);
                let sigma = if (s1 - x).abs() <= (s2 - x).abs() {
                    s1
                } else {
                    s2
                };
                x = sigma;
                y = sigma;
                w = 0.0;
            }
        }
        self.its += 1;
        self.total += 1;
        // Form the shift's first column. The bulge starts at l (EISPACK's
        // search for two consecutive small subdiagonal entries, to start
        // lower, rarely pays at small n).
        let m = l;
        let z = a.at(m, m);
        let rr = x - z;
        let ss = y - z;
        let p = (rr * ss - w) / a.at(m + 1, m) + a.at(m, m + 1);
        let q = a.at(m + 1, m + 1) - z - rr - ss;
        let r = a.at(m + 2, m + 1);
        let s = p.abs() + q.abs() + r.abs();
        self.p = p / s;
        self.q = q / s;
        self.r = r / s;
        for i in m + 2..=nu {
            *a.at_mut(i, i - 2) = 0.0;
            if i != m + 2 {
                *a.at_mut(i, i - 3) = 0.0;
            }
        }
        self.l = l;
        self.nu = nu;
        self.k = m;
        self.chasing = true;
        Ok(false)
    }
}

/// The deflation criterion of [`Hqr::search`]: the subdiagonal entry `sub`
/// between the diagonal entries `d0`, `d1` is negligible when
/// `|sub| <= eps (|d0| + |d1|)` (`eps ||A||_1` when both are zero).
#[inline(always)]
fn negligible(sub: f64, d0: f64, d1: f64, anorm: f64) -> bool {
    let mut s = d0.abs() + d1.abs();
    if s == 0.0 {
        s = anorm;
    }
    sub.abs() <= f64::EPSILON * s
}

/// One reflector of a double-shift QR sweep on the active block `l..=nu`
/// (bulge start `m`, current row `k`): for `k == m` its vector is the shift's
/// first column `(p, q, r)`, otherwise it is read from column `k - 1`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn reflector(
    a: &mut [f64],
    n: usize,
    l: usize,
    m: usize,
    k: usize,
    nu: usize,
    mut p: f64,
    mut q: f64,
    mut r: f64,
) {
    // The last reflector of a sweep acts on two rows/columns only.
    let three = k != nu - 1;
    let mut x = 0.0;
    if k != m {
        p = g!(a, n, k, k - 1);
        q = g!(a, n, k + 1, k - 1);
        r = if three { g!(a, n, k + 2, k - 1) } else { 0.0 };
        // EISPACK scales (p, q, r) by x = |p| + |q| + |r| against
        // over/underflow in p^2 + q^2 + r^2; inside the safe range
        // the scaling changes nothing but rounding, so it is skipped
        // there (a division less on the critical path of a sweep).
        x = p.abs() + q.abs() + r.abs();
        if (SAFE_MIN..=SAFE_MAX).contains(&x) {
            x = 1.0;
        } else if x != 0.0 {
            let ix = 1.0 / x;
            p *= ix;
            q *= ix;
            r *= ix;
        }
    }
    let s = (p * p + q * q + r * r).sqrt().copysign(p);
    if s == 0.0 {
        return;
    }
    if k == m {
        if l != m {
            *m!(a, n, k, k - 1) = -g!(a, n, k, k - 1);
        }
    } else {
        *m!(a, n, k, k - 1) = -s * x;
    }
    p += s;
    let is = 1.0 / s;
    let x = p * is;
    let y = q * is;
    let z = r * is;
    let ip = 1.0 / p;
    q *= ip;
    r *= ip;
    let mmin = if nu < k + 3 { nu } else { k + 3 };
    // Columns k.. of the block (column major, contiguous).
    let (ck, rest) = a[k * n..(nu + 1) * n].split_at_mut(n);
    let (ck1, rest) = rest.split_at_mut(n);
    if three {
        // Row modification: rows k..k+2 of columns k..nu.
        row3(&mut ck[k..k + 3], q, r, x, y, z);
        row3(&mut ck1[k..k + 3], q, r, x, y, z);
        for cj in rest.chunks_exact_mut(n) {
            row3(&mut cj[k..k + 3], q, r, x, y, z);
        }
        // Column modification: rows l..=mmin of columns k..k+2.
        let ck2 = &mut rest[..n];
        for ((a0, a1), a2) in ck[l..=mmin]
            .iter_mut()
            .zip(&mut ck1[l..=mmin])
            .zip(&mut ck2[l..=mmin])
        {
            let pp = x * *a0 + y * *a1 + z * *a2;
            *a2 -= pp * r;
            *a1 -= pp * q;
            *a0 -= pp;
        }
    } else {
        row2(&mut ck[k..k + 2], q, x, y);
        row2(&mut ck1[k..k + 2], q, x, y);
        for (a0, a1) in ck[l..=mmin].iter_mut().zip(&mut ck1[l..=mmin]) {
            let pp = x * *a0 + y * *a1;
            *a1 -= pp * q;
            *a0 -= pp;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eig(n: usize, f: impl Fn(usize, usize) -> f64) -> Vec<Complex64> {
        let mut ws = KernelWorkspace::new();
        let a = ws.input(n);
        for j in 0..n {
            for i in 0..n {
                a[i + j * n] = f(i, j);
            }
        }
        let (re, im) = ws.eigenvalues().unwrap();
        let mut v: Vec<Complex64> = re
            .iter()
            .zip(im)
            .map(|(&r, &i)| Complex64::new(r, i))
            .collect();
        v.sort_by(|a, b| {
            (b.norm(), b.re, b.im)
                .partial_cmp(&(a.norm(), a.re, a.im))
                .unwrap()
        });
        v
    }

    #[test]
    fn cyclic_permutations_converge() {
        for n in 1..=40 {
            let v = eig(n, |i, j| if (i + 1) % n == j { 1.0 } else { 0.0 });
            assert_eq!(v.len(), n);
            for z in &v {
                assert!((z.norm() - 1.0).abs() < 1e-12, "n={n} {z}");
                // z^n = 1
                assert!((z.powu(n as u32) - 1.0).norm() < 1e-10, "n={n} {z}");
            }
        }
    }

    #[test]
    fn zero_and_tiny_matrices() {
        assert!(eig(0, |_, _| 0.0).is_empty());
        assert_eq!(eig(1, |_, _| 2.5), vec![Complex64::new(2.5, 0.0)]);
        for n in 1..8 {
            assert!(eig(n, |_, _| 0.0).iter().all(|z| z.norm() == 0.0));
        }
        let v = eig(2, |i, j| [[0.0, -1.0], [1.0, 0.0]][i][j]);
        assert!((v[0] - Complex64::new(0.0, 1.0)).norm() < 1e-15);
    }

    #[test]
    fn non_finite_input_is_an_error() {
        let mut ws = KernelWorkspace::new();
        ws.input(3)[4] = f64::NAN;
        assert!(matches!(
            ws.eigenvalues(),
            Err(SpectralError::NonFinite { row: 1, col: 1 })
        ));
    }

    #[test]
    fn condition_number_of_normal_and_jordan() {
        let mut ws = KernelWorkspace::new();
        // Symmetric: kappa = 1.
        let a = ws.input(3);
        a.copy_from_slice(&[2.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 4.0]);
        let (re, _) = ws.eigenvalues().unwrap();
        let l = re[0];
        let k = ws.condition_number(Complex64::new(l, 0.0));
        assert!((k - 1.0).abs() < 1e-8, "{k}");
        // Nearly defective: large kappa.
        let a = ws.input(2);
        a.copy_from_slice(&[1.0, 0.0, 1.0, 1.0 + 1e-10]);
        ws.eigenvalues().unwrap();
        let k = ws.condition_number(Complex64::new(1.0, 0.0));
        assert!(k > 1e8, "{k}");
    }

    fn random_matrix(rng: &mut crate::contraction::SplitMix64, n: usize) -> Vec<f64> {
        (0..n * n).map(|_| rng.uniform(-1.0, 1.0)).collect()
    }

    fn eig_of(ws: &mut KernelWorkspace, a: &[f64], n: usize) -> Vec<Complex64> {
        ws.input(n).copy_from_slice(a);
        let (re, im) = ws.eigenvalues().unwrap();
        let mut v: Vec<Complex64> = re
            .iter()
            .zip(im)
            .map(|(&r, &i)| Complex64::new(r, i))
            .collect();
        v.sort_by(super::super::eigen::spectral_order);
        v
    }

    #[test]
    fn real_and_complex_inverse_iteration_agree_for_real_eigenvalues() {
        // The real-arithmetic path for real lambda must give the condition
        // number the complex path gives for the same lambda.
        let mut rng = crate::contraction::SplitMix64::new(5);
        let mut ws = KernelWorkspace::new();
        let mut checked = 0;
        for trial in 0..60 {
            let n = 2 + trial % 12;
            let a = random_matrix(&mut rng, n);
            let values = eig_of(&mut ws, &a, n);
            for z in values.iter().filter(|z| z.im == 0.0) {
                let real = ws.condition_number(*z);
                let tiny = f64::EPSILON * ws.hess_norm.max(f64::MIN_POSITIVE);
                let complex = inverse_iteration_kappa::<Complex64, 1>(
                    n,
                    &ws.hess[..n * n],
                    [*z],
                    tiny,
                    &mut LaneStorage::default(),
                )[0];
                assert!(
                    (real - complex).abs() <= 1e-10 * complex,
                    "n = {n}, lambda = {z}: {real} vs {complex}"
                );
                assert!(real >= 1.0 && real.is_finite());
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }

    #[test]
    fn interleaved_condition_numbers_equal_lone_ones_bit_for_bit() {
        // Lanes share loops but not arithmetic: any mix of real and complex
        // eigenvalues, in groups of up to LANES, gives exactly the numbers of
        // one call per eigenvalue.
        let mut rng = crate::contraction::SplitMix64::new(11);
        let mut ws = KernelWorkspace::new();
        let mut mixed = 0;
        for trial in 0..40 {
            let n = 2 + trial % 14;
            let a = random_matrix(&mut rng, n);
            let values = eig_of(&mut ws, &a, n);
            let lone: Vec<f64> = values.iter().map(|&z| ws.condition_number(z)).collect();
            let mut together = vec![0.0; values.len()];
            ws.condition_numbers(&values, &mut together);
            assert_eq!(lone, together, "n = {n}");
            let reals = values.iter().filter(|z| z.im == 0.0).count();
            if reals > 0 && reals < values.len() {
                mixed += 1;
            }
        }
        assert!(mixed > 10, "{mixed}");
    }

    /// Bit patterns of a workspace's last results: eigenvalues, sweeps,
    /// Hessenberg form and its norm.
    fn result_bits(w: &KernelWorkspace) -> Vec<u64> {
        let (re, im) = w.last_eigenvalues();
        let mut bits: Vec<u64> = re.iter().chain(im).map(|x| x.to_bits()).collect();
        bits.push(w.last_sweeps() as u64);
        bits.extend(w.hessenberg_form().iter().map(|x| x.to_bits()));
        bits.push(w.hess_norm.to_bits());
        bits
    }

    /// [`result_bits`] of a lone call on `a`, or `None` if it fails.
    fn lone_bits(lone: &mut KernelWorkspace, a: &[f64], n: usize) -> Option<Vec<u64>> {
        lone.input(n).copy_from_slice(a);
        lone.eigenvalues().ok()?;
        Some(result_bits(lone))
    }

    /// Matrices that exercise every branch of the lock-step kernel.
    fn lockstep_cases(
        rng: &mut crate::contraction::SplitMix64,
        n: usize,
        trial: usize,
    ) -> Vec<f64> {
        let mut a = random_matrix(rng, n);
        match trial % 8 {
            // sparse: exact zeros, whole zero columns (Hessenberg steps skipped
            // in some lanes only), signed zeros
            0 => a.iter_mut().enumerate().for_each(|(i, x)| {
                if (i * 7 + trial) % 3 != 0 {
                    *x = if i % 2 == 0 { 0.0 } else { -0.0 };
                }
            }),
            // cyclic permutation (exceptional shifts)
            1 => {
                a.iter_mut().for_each(|x| *x = 0.0);
                for j in 0..n {
                    a[(j + 1) % n + j * n] = 1.0;
                }
            }
            // scaled out of the no-rescaling range of the reflectors
            2 => a.iter_mut().for_each(|x| *x *= 2f64.powi(520)),
            3 => a.iter_mut().for_each(|x| *x *= 2f64.powi(-520)),
            // the zero matrix
            4 => a.iter_mut().for_each(|x| *x = 0.0),
            // symmetric (real spectrum, many real deflations)
            5 => {
                for j in 0..n {
                    for i in 0..j {
                        a[i + j * n] = a[j + i * n];
                    }
                }
            }
            _ => {}
        }
        a
    }

    #[test]
    fn lockstep_batches_equal_lone_calls_bit_for_bit() {
        let mut rng = crate::contraction::SplitMix64::new(77);
        let mut ws: Vec<KernelWorkspace> = (0..BATCH).map(|_| KernelWorkspace::new()).collect();
        let mut lone = KernelWorkspace::new();
        let (mut compared, mut failed) = (0, 0);
        for trial in 0..160 {
            let n = 1 + trial % 24;
            let mut inputs = Vec::new();
            for (lane, w) in ws.iter_mut().enumerate() {
                // mostly equal dimensions (the lock-step path), some unequal
                // (the one-at-a-time fallback)
                let m = if trial % 10 == 9 && lane == 2 {
                    n + 1
                } else {
                    n
                };
                let mut a = lockstep_cases(&mut rng, m, trial + lane * (trial % 3));
                if trial % 13 == 5 && lane == 1 {
                    a[m * m - 1] = f64::NAN;
                }
                w.input(m).copy_from_slice(&a);
                inputs.push((a, m));
            }
            let lanes: &mut [KernelWorkspace; BATCH] = (&mut ws[..]).try_into().unwrap();
            let res = KernelWorkspace::eigenvalues_batch(lanes.each_mut());
            for ((w, r), (a, m)) in ws.iter().zip(res).zip(&inputs) {
                let want = lone_bits(&mut lone, a, *m);
                match (r, want) {
                    (Ok(()), Some(want)) => {
                        assert_eq!(result_bits(w), want, "trial {trial}, n = {m}");
                        compared += 1;
                    }
                    (Err(e), None) => {
                        lone.input(*m).copy_from_slice(a);
                        assert_eq!(Some(e), lone.eigenvalues().err(), "trial {trial}");
                        failed += 1;
                    }
                    (r, w) => panic!("trial {trial}: batch {r:?}, lone ok = {}", w.is_some()),
                }
            }
        }
        // Both branches ran: most lanes compared bit for bit; the failures
        // (the 12 NaN lanes, and overflow of the 2^520-scaled inputs, which
        // fails alone in the same way) matched the lone errors.
        assert_eq!(compared + failed, 160 * BATCH);
        assert!(
            compared > 2000 && failed > 12,
            "{compared} compared, {failed} failed"
        );
    }

    #[test]
    fn extreme_scales_take_the_rescaled_reflector_path() {
        // Entries of modulus ~2^+-505 are outside [SAFE_MIN, SAFE_MAX], so the
        // QR sweeps rescale (p, q, r); at ~2^+-400 they are inside and do not.
        // Either way the spectrum must scale along (squares of the entries,
        // formed by the shifts, stay normal numbers).
        let mut rng = crate::contraction::SplitMix64::new(9);
        let mut ws = KernelWorkspace::new();
        for trial in 0..40 {
            let n = 3 + trial % 15;
            let a = random_matrix(&mut rng, n);
            let base = eig_of(&mut ws, &a, n);
            for scale in [505, -505, 400, -400].map(|e| 2f64.powi(e)) {
                let b: Vec<f64> = a.iter().map(|x| x * scale).collect();
                let ev = eig_of(&mut ws, &b, n);
                assert_eq!(ev.len(), n);
                for v in &ev {
                    let d = base
                        .iter()
                        .map(|u| (u - v / scale).norm())
                        .fold(f64::INFINITY, f64::min);
                    assert!(d <= 1e-9, "n = {n}, scale {scale:e}: {v} ({d:e})");
                }
            }
        }
    }

    /// Largest distance from a kernel eigenvalue to the nearest faer eigenvalue
    /// of the same matrix, and the trace defect.
    fn versus_faer(ws: &mut KernelWorkspace, a: &nalgebra::DMatrix<f64>) -> (f64, f64) {
        use crate::spectral::eigen::{Eigen, EigenOptions};
        let n = a.nrows();
        let ours = eig_of(ws, a.as_slice(), n);
        let theirs = Eigen::new(a, EigenOptions::VALUES).unwrap();
        let d = ours
            .iter()
            .map(|z| {
                theirs
                    .values()
                    .iter()
                    .map(|w| (z - w).norm())
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        let tr: Complex64 = ours.iter().sum();
        (d, (tr.re - a.trace()).abs() + tr.im.abs())
    }

    #[test]
    fn adversarial_inputs_agree_with_faer() {
        use crate::knots::EdgeRatios;
        use crate::schemes::LocalScheme;
        use nalgebra::DMatrix;
        let mut ws = KernelWorkspace::new();
        let mut rng = crate::contraction::SplitMix64::new(2024);
        // NURDS face blocks with extreme ratios (1e-6 and 1 - 1e-6 mixed in).
        for trial in 0..60 {
            let n = 3 + trial % 20;
            let r: Vec<f64> = (0..n)
                .map(|i| match (i + trial) % 3 {
                    0 => 1e-6,
                    1 => 1.0 - 1e-6,
                    _ => rng.uniform(0.01, 0.99),
                })
                .collect();
            let a = LocalScheme::nurds(EdgeRatios::new(r).unwrap())
                .face_block()
                .unwrap();
            let (d, t) = versus_faer(&mut ws, &a);
            // Well separated except near-double roots: compare loosely, the
            // trace tightly.
            assert!(d < 1e-6, "n = {n}: {d:e}");
            assert!(t < 1e-12 * n as f64, "n = {n}: trace defect {t:e}");
        }
        // Defective: Jordan blocks J_k(1/2), also hidden by a similarity.
        for k in 2..=5usize {
            let j = DMatrix::from_fn(k, k, |i, c| {
                if i == c {
                    0.5
                } else if c == i + 1 {
                    1.0
                } else {
                    0.0
                }
            });
            let q = DMatrix::from_fn(k, k, |_, _| rng.uniform(-1.0, 1.0))
                + DMatrix::identity(k, k) * 3.0;
            let a = &q * &j * q.try_inverse().unwrap();
            for m in [j, a] {
                let v = eig_of(&mut ws, m.as_slice(), k);
                // A k-fold defective eigenvalue moves by ~ eps^(1/k).
                let tol = 100.0 * f64::EPSILON.powf(1.0 / k as f64);
                assert!(v.iter().all(|z| (z - 0.5).norm() < tol), "k = {k}: {v:?}");
                let (_, t) = versus_faer(&mut ws, &m);
                assert!(t < 1e-12, "k = {k}: trace defect {t:e}");
            }
        }
        // Graded (badly scaled by a diagonal similarity) and companion matrices.
        for n in 3..=16usize {
            let b = DMatrix::from_fn(n, n, |_, _| rng.uniform(-1.0, 1.0));
            let g = DMatrix::from_fn(n, n, |i, j| b[(i, j)] * 10f64.powi(i as i32 - j as i32));
            let (d, _) = versus_faer(&mut ws, &g);
            let scale = g.norm();
            assert!(d < 1e-6 * scale, "graded n = {n}: {d:e}");
            // Companion matrix of prod_k (x - k / n): eigenvalues k / n, k = 1..n
            // (Wilkinson-like, unbalanced: ill-conditioned beyond n ~ 10 for
            // any unbalanced QR, faer's and the old kernel's alike).
            if n > 10 {
                continue;
            }
            let mut c = vec![1.0f64];
            for k in 1..=n {
                let root = k as f64 / n as f64;
                let mut next = vec![0.0; c.len() + 1];
                for (i, &ci) in c.iter().enumerate() {
                    next[i + 1] += ci;
                    next[i] -= root * ci;
                }
                c = next;
            }
            let comp = DMatrix::from_fn(n, n, |i, j| {
                if j == n - 1 {
                    -c[i]
                } else if i == j + 1 {
                    1.0
                } else {
                    0.0
                }
            });
            let v = eig_of(&mut ws, comp.as_slice(), n);
            let (d, _) = versus_faer(&mut ws, &comp);
            assert!(d < 1e-6, "companion n = {n}: {d:e}");
            if n <= 8 {
                for z in &v {
                    let k = (z.re * n as f64).round();
                    assert!(
                        (1.0..=n as f64).contains(&k) && (z - k / n as f64).norm() < 1e-6,
                        "companion n = {n}: {z}"
                    );
                }
            }
        }
    }
}
