//! The reusable storage of the kernel and its entry points: one matrix at a
//! time ([`KernelWorkspace::eigenvalues`]) or [`BATCH`] in lock step
//! ([`KernelWorkspace::eigenvalues_batch`]).

use super::condition::{self, LaneStorage};
use super::hessenberg::hessenberg;
use super::lockstep::{self, BATCH};
use super::qr::hqr;
use crate::spectral::SpectralError;
use num_complex::Complex64;

/// Reusable storage for the kernel (grows to the largest size seen).
#[derive(Debug, Default, Clone)]
pub struct KernelWorkspace {
    n: usize,
    /// Working copy (column major, `n x n`), destroyed by the QR iteration.
    h: Vec<f64>,
    /// Untouched copy of the input.
    a: Vec<f64>,
    /// The Hessenberg form of the input, for condition numbers.
    pub(super) hess: Vec<f64>,
    /// Householder vector and scratch.
    v: Vec<f64>,
    w: Vec<f64>,
    /// Inverse-iteration storage for real and for complex eigenvalues.
    real: LaneStorage<f64>,
    complex: LaneStorage<Complex64>,
    /// Frobenius norm of `hess`.
    pub(super) hess_norm: f64,
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
    /// use subdiv_lab::spectral::{KernelWorkspace, BATCH};
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
        // Interleave the inputs (one pass over the storage, which is written
        // once: no zeroing first).
        let zeros = if dims.iter().all(|&d| d == n) {
            Vec::new()
        } else {
            vec![0.0; n * n]
        };
        let src: [&[f64]; BATCH] = std::array::from_fn(|lane| match &ws[lane] {
            Some(x) if dims[lane] == n => &x.a[..n * n],
            _ => &zeros[..],
        });
        h.clear();
        h.extend((0..n * n).map(|e| -> lockstep::Lanes { std::array::from_fn(|l| src[l][e]) }));
        h.resize(lockstep::storage_len(n), [0.0; BATCH]);
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
        condition::condition_numbers(
            self.n,
            &self.hess,
            self.hess_norm,
            &mut self.real,
            &mut self.complex,
            lambdas,
            out,
        );
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
        // Each lane's Hessenberg form, tile by tile (one pass over the
        // storage).
        let mut hess = hess;
        for x in hess.iter_mut() {
            x.clear();
            x.reserve(n * n);
        }
        for tile in h[..n * n].chunks(64) {
            for (lane, x) in hess.iter_mut().enumerate() {
                x.extend(tile.iter().map(|e| e[lane]));
            }
        }
        lockstep::hqr(dims, n, h, v, wr, wi)
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
