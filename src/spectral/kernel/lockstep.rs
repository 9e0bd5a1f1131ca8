//! Lock-step Hessenberg reduction and QR iteration of [`BATCH`] matrices at
//! once, one matrix per SIMD lane.
//!
//! The matrices are stored lane-interleaved (entry `(i, j)` of every matrix
//! side by side in one `[f64; BATCH]`), so that each arithmetic operation of
//! the scalar kernel becomes one vector operation on all lanes. Every lane
//! runs exactly the arithmetic of the scalar [`hessenberg`](super::hessenberg())
//! and [`hqr`](super::hqr), operation for operation and in the same order
//! (Rust never contracts `a * b + c` into a fused multiply-add), so the
//! results are bit for bit those of one-at-a-time calls; the tests of the
//! parent module check this.
//!
//! Where the lanes' control flow differs, a lane computes the common
//! operation and keeps its old value (a select, never a masked arithmetic
//! trick, so that signed zeros survive as well):
//!
//! * Hessenberg reduction: a lane whose column below the subdiagonal is zero
//!   (or whose reflector is degenerate) skips the step, as the scalar code does;
//! * QR iteration: each lane keeps its own deflation state ([`Hqr`], run per
//!   lane through [`Hqr::search`] on a [`Lane`] view); when every unfinished
//!   lane has set up a sweep, one lock-step sweep runs the reflectors at rows
//!   `k = min l .. max nu - 1`, each lane active only inside its own active
//!   block `l..=nu`, with its own last (two-row) reflector at `k = nu - 1`.
//!
//! Why: at the small dimensions of sweeps (the face block of valence `n <= 16`)
//! the QR iteration is latency-bound (square root, then reciprocal, then
//! dependent updates per reflector); the lanes run as many such chains in
//! the time of one. The price is the idle lanes of a sweep whose active
//! blocks differ and the lanes that finish early.
//!
//! [`BATCH`] = 16 is measured (kernel time per matrix, deflated NURDS face
//! blocks of random ratios, Hessenberg reduction included, best of 4 runs on
//! the project's 2-core AMD EPYC Zen 4, AVX2 build; the scalar kernel for
//! comparison):
//!
//! | valence | scalar | 4 lanes | 8 lanes | 16 lanes | 32 lanes |
//! |---|---|---|---|---|---|
//! | 5 | 650 ns | 407 ns | 340 ns | 308 ns | 914 ns |
//! | 8 | 2.24 us | 1.27 us | 1.02 us | 0.94 us | 3.46 us |
//! | 16 | 10.2 us | 5.83 us | 5.16 us | 4.39 us | 20.5 us |
//! | 32 | 50.0 us | | 29.4 us | 25.8 us | 126 us |
//! | 64 | 285 us | | 241 us | 184 us | |
//!
//! With 16 lanes each operation is four 256-bit instructions, which the
//! processor overlaps (more independent chains per reflector); at 32 lanes
//! the compiler no longer keeps the lanes in registers. An AVX-512 build of
//! 8 lanes runs no faster than AVX2 on Zen 4 (whose 512-bit units are
//! double-pumped 256-bit ones), so only AVX2 is dispatched.

use super::qr::{negligible, Hqr, HqrMatrix, SAFE_MAX, SAFE_MIN};
use crate::spectral::SpectralError;

/// Matrices per lock-step batch.
pub const BATCH: usize = 16;

/// One lane-interleaved entry.
pub(super) type Lanes = [f64; BATCH];

/// Entries beyond `n * n` that the sweeps may read (never use): rows `k + 2`
/// up to `n` and the column `k + 2` up to `n` of a lane whose own block ends
/// earlier.
pub(super) fn storage_len(n: usize) -> usize {
    n * (n + 1) + 3
}

/// One lane of the interleaved storage, as a column-major `n x n` matrix of
/// stride `stride` (for [`Hqr::search`]).
pub(super) struct Lane<'a> {
    pub(super) a: &'a mut [Lanes],
    pub(super) stride: usize,
    pub(super) lane: usize,
}

impl HqrMatrix for Lane<'_> {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        let k = i + j * self.stride;
        debug_assert!(k < self.a.len() && self.lane < BATCH);
        // SAFETY: i, j < n <= stride and a.len() >= stride^2 (checked in debug).
        unsafe { *self.a.get_unchecked(k).get_unchecked(self.lane) }
    }
    #[inline(always)]
    fn at_mut(&mut self, i: usize, j: usize) -> &mut f64 {
        let k = i + j * self.stride;
        debug_assert!(k < self.a.len() && self.lane < BATCH);
        // SAFETY: as in `at`.
        unsafe { self.a.get_unchecked_mut(k).get_unchecked_mut(self.lane) }
    }
    #[inline(always)]
    fn clear_bulge(&mut self, _m: usize, _nu: usize) {
        // Done for all lanes at once by `clear_bulges`.
    }
}

/// [`HqrMatrix::clear_bulge`] of every chasing lane (its sweep starts at
/// row `st[l].l` and ends at `st[l].nu`), one lane-interleaved entry at a
/// time.
#[inline(always)]
fn clear_bulges(a: &mut [Lanes], s: usize, st: &[Hqr; BATCH], chasing: [bool; BATCH]) {
    let lo: [i64; BATCH] =
        std::array::from_fn(|l| if chasing[l] { st[l].l as i64 } else { i64::MAX });
    let nu: [i64; BATCH] = std::array::from_fn(|l| if chasing[l] { st[l].nu as i64 } else { -1 });
    let first = lo.iter().copied().min().unwrap_or(i64::MAX);
    let last = nu.iter().copied().max().unwrap_or(-1);
    if first == i64::MAX || first + 2 > last {
        return;
    }
    for i in (first + 2) as usize..=last as usize {
        let ii = [i as i64; BATCH];
        // (i, i - 2) where m + 2 <= i <= nu, (i, i - 3) where m + 3 <= i <= nu.
        let two: Mask = std::array::from_fn(|l| -((lo[l] + 2 <= ii[l] && ii[l] <= nu[l]) as i64));
        let three: Mask = std::array::from_fn(|l| -((lo[l] + 3 <= ii[l] && ii[l] <= nu[l]) as i64));
        let e2 = i + (i - 2) * s;
        let x = u!(a[e2]);
        *um!(a[e2]) = pick(two, [0.0; BATCH], x);
        if i >= 3 {
            let e3 = i + (i - 3) * s;
            let x = u!(a[e3]);
            *um!(a[e3]) = pick(three, [0.0; BATCH], x);
        }
    }
}

/// Whether any lane of `m` is set.
#[inline(always)]
fn any(m: Mask) -> bool {
    m.iter().any(|&b| b != 0)
}

/// `m` as a [`Mask`].
#[inline(always)]
fn mask(m: [bool; BATCH]) -> Mask {
    m.map(|b| -(b as i64))
}

/// The scalar [`hessenberg`](super::hessenberg()) on all lanes of the
/// interleaved `n x n` matrices `h` (stride `n`); `v`, `w` hold `n` entries.
///
/// A step whose reflector is live in every lane (the usual case) stores its
/// results without lane selects ([`hessenberg_step`] with `ALL = true`): a
/// select in front of a store is compiled to a masked store, which is slow
/// on AMD processors. The dot products run two columns (left update) or two
/// rows (`w = H v`) at a time, each accumulated in the scalar kernel's order,
/// so that the processor overlaps two dependency chains.
#[inline(always)]
pub(super) fn hessenberg(n: usize, h: &mut [Lanes], v: &mut [Lanes], w: &mut [Lanes]) {
    if n < 3 {
        return;
    }
    debug_assert!(h.len() >= n * n && v.len() >= n && w.len() >= n);
    for k in 0..n - 2 {
        let mut scale = [0.0f64; BATCH];
        for i in k + 1..n {
            let x = u!(h[i + k * n]);
            scale = std::array::from_fn(|l| scale[l].max(x[l].abs()));
        }
        let mut live: Mask = std::array::from_fn(|l| -((scale[l] != 0.0) as i64));
        if !any(live) {
            continue;
        }
        let inv_scale: Lanes = std::array::from_fn(|l| 1.0 / scale[l]);
        let mut norm2 = [0.0f64; BATCH];
        for i in k + 1..n {
            let x = u!(h[i + k * n]);
            let t: Lanes = std::array::from_fn(|l| x[l] * inv_scale[l]);
            *um!(v[i]) = t;
            norm2 = std::array::from_fn(|l| norm2[l] + t[l] * t[l]);
        }
        let x0 = u!(v[k + 1]);
        let alpha: Lanes = std::array::from_fn(|l| -x0[l].signum() * norm2[l].sqrt());
        let v0: Lanes = std::array::from_fn(|l| x0[l] - alpha[l]);
        *um!(v[k + 1]) = v0;
        let vtv: Lanes = std::array::from_fn(|l| norm2[l] - x0[l] * x0[l] + v0[l] * v0[l]);
        live = std::array::from_fn(|l| live[l] & -((vtv[l] != 0.0) as i64));
        if !any(live) {
            continue;
        }
        let beta: Lanes = std::array::from_fn(|l| 2.0 / vtv[l]);
        let sub: Lanes = std::array::from_fn(|l| alpha[l] * scale[l]);
        let step = Step {
            n,
            k,
            live,
            beta,
            sub,
        };
        if live.iter().all(|&m| m != 0) {
            hessenberg_step::<true>(&step, h, v, w);
        } else {
            hessenberg_step::<false>(&step, h, v, w);
        }
    }
}

/// One reflector of [`hessenberg`]: step `k`, the lanes where it is `live`,
/// its `beta = 2 / v^T v` and the new subdiagonal entry `sub`.
struct Step {
    n: usize,
    k: usize,
    live: Mask,
    beta: Lanes,
    sub: Lanes,
}

/// `new` where `m` is set, else `old`; with `ALL` (every lane set) `new`.
#[inline(always)]
fn put<const ALL: bool>(m: Mask, new: Lanes, old: Lanes) -> Lanes {
    if ALL {
        new
    } else {
        pick(m, new, old)
    }
}

/// The updates of one [`hessenberg`] step (`ALL`: the step is live in every
/// lane), in the scalar kernel's arithmetic: left update `H -= beta v (v^T
/// H)` of rows and columns `k + 1..n`, the new column `k`, right update
/// `H -= beta (H v) v^T` of all rows, columns `k + 1..n`.
#[inline(always)]
fn hessenberg_step<const ALL: bool>(st: &Step, h: &mut [Lanes], v: &[Lanes], w: &mut [Lanes]) {
    let Step {
        n,
        k,
        live,
        beta,
        sub,
    } = *st;
    // Left: rows k+1..n, columns k+1..n, two columns at a time. Each column's
    // `s = (v^T h_j) beta` is summed in row order from -0.0 (`Sum for f64`).
    let mut j = k + 1;
    while j + 1 < n {
        let (c0, c1) = (j * n, (j + 1) * n);
        let mut s0 = [-0.0f64; BATCH];
        let mut s1 = [-0.0f64; BATCH];
        for i in k + 1..n {
            let (x0, x1, y) = (u!(h[i + c0]), u!(h[i + c1]), u!(v[i]));
            s0 = std::array::from_fn(|l| s0[l] + x0[l] * y[l]);
            s1 = std::array::from_fn(|l| s1[l] + x1[l] * y[l]);
        }
        let s0: Lanes = std::array::from_fn(|l| s0[l] * beta[l]);
        let s1: Lanes = std::array::from_fn(|l| s1[l] * beta[l]);
        for i in k + 1..n {
            let (x0, x1, y) = (u!(h[i + c0]), u!(h[i + c1]), u!(v[i]));
            *um!(h[i + c0]) = put::<ALL>(live, std::array::from_fn(|l| x0[l] - s0[l] * y[l]), x0);
            *um!(h[i + c1]) = put::<ALL>(live, std::array::from_fn(|l| x1[l] - s1[l] * y[l]), x1);
        }
        j += 2;
    }
    if j < n {
        let c = j * n;
        let mut s = [-0.0f64; BATCH];
        for i in k + 1..n {
            let (x, y) = (u!(h[i + c]), u!(v[i]));
            s = std::array::from_fn(|l| s[l] + x[l] * y[l]);
        }
        let s: Lanes = std::array::from_fn(|l| s[l] * beta[l]);
        for i in k + 1..n {
            let (x, y) = (u!(h[i + c]), u!(v[i]));
            *um!(h[i + c]) = put::<ALL>(live, std::array::from_fn(|l| x[l] - s[l] * y[l]), x);
        }
    }
    let old = u!(h[k + 1 + k * n]);
    *um!(h[k + 1 + k * n]) = put::<ALL>(live, sub, old);
    for i in k + 2..n {
        let x = u!(h[i + k * n]);
        *um!(h[i + k * n]) = put::<ALL>(live, [0.0; BATCH], x);
    }
    // Right: all rows, columns k+1..n: w = H v (each w_i summed in column
    // order from 0.0, two rows at a time), H -= beta w v^T.
    let mut i = 0;
    while i + 1 < n {
        let mut w0 = [0.0f64; BATCH];
        let mut w1 = [0.0f64; BATCH];
        for j in k + 1..n {
            let (x0, x1, vj) = (u!(h[i + j * n]), u!(h[i + 1 + j * n]), u!(v[j]));
            w0 = std::array::from_fn(|l| w0[l] + x0[l] * vj[l]);
            w1 = std::array::from_fn(|l| w1[l] + x1[l] * vj[l]);
        }
        *um!(w[i]) = w0;
        *um!(w[i + 1]) = w1;
        i += 2;
    }
    if i < n {
        let mut w0 = [0.0f64; BATCH];
        for j in k + 1..n {
            let (x0, vj) = (u!(h[i + j * n]), u!(v[j]));
            w0 = std::array::from_fn(|l| w0[l] + x0[l] * vj[l]);
        }
        *um!(w[i]) = w0;
    }
    for j in k + 1..n {
        let vj = u!(v[j]);
        let f: Lanes = std::array::from_fn(|l| beta[l] * vj[l]);
        for i in 0..n {
            let (wi, x) = (u!(w[i]), u!(h[i + j * n]));
            *um!(h[i + j * n]) = put::<ALL>(live, std::array::from_fn(|l| x[l] - wi[l] * f[l]), x);
        }
    }
}

/// The scalar [`hqr`](super::hqr) on every lane of the interleaved upper
/// Hessenberg matrices `a` (stride `stride`, [`storage_len`] entries): lane
/// `l` holds an `n[l] x n[l]` matrix (`n[l] = 0`: an unused lane) and
/// receives its eigenvalues in `wr[l]`, `wi[l]`. Returns each lane's sweep
/// count, or its error (exactly as [`hqr`](super::hqr) would).
#[inline(always)]
pub(super) fn hqr(
    n: [usize; BATCH],
    stride: usize,
    a: &mut [Lanes],
    scratch: &mut [Lanes],
    wr: [&mut [f64]; BATCH],
    wi: [&mut [f64]; BATCH],
) -> [Result<usize, SpectralError>; BATCH] {
    debug_assert!(a.len() >= storage_len(stride) && n.iter().all(|&m| m <= stride));
    let mut st: [Hqr; BATCH] = std::array::from_fn(|lane| {
        Hqr::new(
            n[lane],
            &Lane {
                a: &mut *a,
                stride,
                lane,
            },
        )
    });
    let mut out: [Option<Result<usize, SpectralError>>; BATCH] = Default::default();
    let anorm: Lanes = std::array::from_fn(|l| st[l].anorm);
    loop {
        // Negligible subdiagonal entries of every lane (bit i: entry
        // (i, i - 1)), once per round: the deflations between two sweeps
        // write no entry but the zero of the split found.
        let top = st.iter().map(|s| s.nn).max().unwrap_or(-1);
        let mut bits = [0u64; BATCH];
        for i in 1..=top.max(0) as usize {
            let sub = u!(a[i + (i - 1) * stride]);
            let d0 = u!(a[(i - 1) + (i - 1) * stride]);
            let d1 = u!(a[i + i * stride]);
            bits = std::array::from_fn(|l| {
                bits[l] | ((negligible(sub[l], d0[l], d1[l], anorm[l]) as u64) << i)
            });
        }
        let mut chasing = [false; BATCH];
        for lane in 0..BATCH {
            if out[lane].is_some() {
                continue;
            }
            let mut view = Lane {
                a: &mut *a,
                stride,
                lane,
            };
            loop {
                let step = if st[lane].nn < 0 {
                    Ok(true)
                } else {
                    // Hqr::search, its scan replaced by the bits: the last
                    // negligible entry at or above row nu.
                    let nu = st[lane].nn as u32;
                    let below = bits[lane] & (u64::MAX >> (63 - nu));
                    let l = if below == 0 {
                        0
                    } else {
                        let l = 63 - below.leading_zeros() as usize;
                        *view.at_mut(l, l - 1) = 0.0;
                        l
                    };
                    st[lane].split_at(l, &mut view, wr[lane], wi[lane])
                };
                match step {
                    Ok(true) => {
                        out[lane] = Some(Ok(st[lane].total));
                        break;
                    }
                    Err(e) => {
                        out[lane] = Some(Err(e));
                        break;
                    }
                    Ok(false) if st[lane].chasing => {
                        chasing[lane] = true;
                        break;
                    }
                    Ok(false) => {}
                }
            }
        }
        if !any(mask(chasing)) {
            break;
        }
        clear_bulges(a, stride, &st, chasing);
        sweep(a, stride, scratch, &st, chasing);
        for (s, &c) in st.iter_mut().zip(&chasing) {
            if c {
                s.chasing = false;
            }
        }
    }
    // The loop ends only when no lane is left chasing, i.e. every lane has
    // finished or failed.
    out.map(|r| r.expect("every lane has finished"))
}

/// A lane mask: all ones (true) or zero (false) per lane, as `i64` so that
/// comparisons and selects stay in vector registers.
type Mask = [i64; BATCH];

/// `if a[l] <= b[l]` as a [`Mask`].
#[inline(always)]
fn le(a: [i64; BATCH], b: [i64; BATCH]) -> Mask {
    std::array::from_fn(|l| -((a[l] <= b[l]) as i64))
}

#[inline(always)]
fn and(a: Mask, b: Mask) -> Mask {
    std::array::from_fn(|l| a[l] & b[l])
}

/// `if m { x } else { y }`, lane by lane, by bit operations.
#[inline(always)]
fn pick(m: Mask, x: Lanes, y: Lanes) -> Lanes {
    std::array::from_fn(|l| {
        let (x, y) = (x[l].to_bits(), y[l].to_bits());
        f64::from_bits(y ^ ((x ^ y) & m[l] as u64))
    })
}

/// One lock-step double-shift sweep of the lanes with `chasing[l]`: lane `l`
/// applies the reflectors of the scalar `reflector` at rows
/// `st[l].l..st[l].nu`, and keeps every entry outside them.
#[inline(always)]
fn sweep(
    a: &mut [Lanes],
    s: usize,
    scratch: &mut [Lanes],
    st: &[Hqr; BATCH],
    chasing: [bool; BATCH],
) {
    let chase: Mask = mask(chasing);
    // Lanes not chasing get an empty block (lo > hi), so every mask is false.
    let lo: [i64; BATCH] =
        std::array::from_fn(|l| if chasing[l] { st[l].l as i64 } else { i64::MAX });
    let nu: [i64; BATCH] = std::array::from_fn(|l| if chasing[l] { st[l].nu as i64 } else { -1 });
    let p0: Lanes = std::array::from_fn(|l| st[l].p);
    let q0: Lanes = std::array::from_fn(|l| st[l].q);
    let r0: Lanes = std::array::from_fn(|l| st[l].r);
    let mut kmin = usize::MAX;
    let mut kmax = 0;
    for l in 0..BATCH {
        if chasing[l] {
            kmin = kmin.min(st[l].l);
            kmax = kmax.max(st[l].nu - 1);
        }
    }
    let zero = [0.0; BATCH];
    for k in kmin..=kmax {
        let kk = [k as i64; BATCH];
        let k1 = [k as i64 + 1; BATCH];
        // Active: lo <= k < nu; three rows unless k = nu - 1; first: k = lo.
        let act: Mask = and(le(lo, kk), le(k1, nu));
        let two: Mask = std::array::from_fn(|l| -((k1[l] == nu[l]) as i64));
        let first: Mask = std::array::from_fn(|l| -((kk[l] == lo[l]) as i64));
        let (cp, cq, cr) = if k > 0 {
            (
                u!(a[k + (k - 1) * s]),
                u!(a[k + 1 + (k - 1) * s]),
                u!(a[k + 2 + (k - 1) * s]),
            )
        } else {
            (zero, zero, zero)
        };
        // The reflector's vector, as in the scalar `reflector`: from the
        // shift at the first row, else from column k - 1, rescaled outside
        // [SAFE_MIN, SAFE_MAX].
        let cr = pick(two, zero, cr);
        let xl: Lanes = std::array::from_fn(|l| cp[l].abs() + cq[l].abs() + cr[l].abs());
        let inside: Mask =
            std::array::from_fn(|l| -((SAFE_MIN <= xl[l] && xl[l] <= SAFE_MAX) as i64));
        let scaled: Mask = std::array::from_fn(|l| !inside[l] & -((xl[l] != 0.0) as i64));
        let ix: Lanes = std::array::from_fn(|l| 1.0 / xl[l]);
        let p = pick(
            first,
            p0,
            pick(scaled, std::array::from_fn(|l| cp[l] * ix[l]), cp),
        );
        let q = pick(
            first,
            q0,
            pick(scaled, std::array::from_fn(|l| cq[l] * ix[l]), cq),
        );
        let r = pick(
            first,
            r0,
            pick(scaled, std::array::from_fn(|l| cr[l] * ix[l]), cr),
        );
        let x = pick(first, zero, pick(inside, [1.0; BATCH], xl));
        let sg: Lanes = std::array::from_fn(|l| {
            (p[l] * p[l] + q[l] * q[l] + r[l] * r[l])
                .sqrt()
                .copysign(p[l])
        });
        let blk = act;
        let act: Mask = std::array::from_fn(|l| act[l] & -((sg[l] != 0.0) as i64));
        if !any(act) {
            continue;
        }
        if k > 0 {
            let old = u!(a[k + (k - 1) * s]);
            let m: Mask = std::array::from_fn(|l| act[l] & !first[l]);
            *um!(a[k + (k - 1) * s]) = pick(m, std::array::from_fn(|l| -sg[l] * x[l]), old);
        }
        let pp: Lanes = std::array::from_fn(|l| p[l] + sg[l]);
        let is: Lanes = std::array::from_fn(|l| 1.0 / sg[l]);
        let xx: Lanes = std::array::from_fn(|l| pp[l] * is[l]);
        let yy: Lanes = std::array::from_fn(|l| q[l] * is[l]);
        let zz: Lanes = std::array::from_fn(|l| r[l] * is[l]);
        let ip: Lanes = std::array::from_fn(|l| 1.0 / pp[l]);
        let qq: Lanes = std::array::from_fn(|l| q[l] * ip[l]);
        let rr: Lanes = std::array::from_fn(|l| r[l] * ip[l]);
        // Per-lane ranges of the updates; inactive lanes get empty ones.
        let nua: [i64; BATCH] = std::array::from_fn(|l| if act[l] != 0 { nu[l] } else { -1 });
        let loa: [i64; BATCH] = std::array::from_fn(|l| if act[l] != 0 { lo[l] } else { i64::MAX });
        let mma: [i64; BATCH] = std::array::from_fn(|l| nua[l].min(k as i64 + 3));
        let numax = nua.iter().copied().max().unwrap_or(-1) as usize;
        let lmin = loa.iter().copied().min().unwrap_or(0) as usize;
        let mmax = mma.iter().copied().max().unwrap_or(0) as usize;
        // The fast path (see `sweep_unmasked`) unless a chasing lane must keep
        // the entries this row's reflector would write: its block starts
        // below row k, or its reflector is degenerate (the scalar code skips
        // it).
        let keep: Mask =
            std::array::from_fn(|l| chase[l] & ((-((kk[l] < lo[l]) as i64)) | (blk[l] & !act[l])));
        if !any(keep) {
            let r = Reflector {
                k,
                numax,
                lmin,
                mmax,
                xx,
                yy,
                zz,
                qq,
                rr,
                two,
                last: std::array::from_fn(|l| chase[l] & -((kk[l] == nu[l]) as i64)),
            };
            if any(two) {
                sweep_unmasked::<true>(a, s, scratch, &r);
            } else {
                sweep_unmasked::<false>(a, s, scratch, &r);
            }
            continue;
        }
        // Row modification: rows k..k+2 (k..k+1 for the last reflector) of
        // columns k..=nu.
        for j in k..=numax {
            let c = j * s;
            let (c0, c1, c2) = (u!(a[k + c]), u!(a[k + 1 + c]), u!(a[k + 2 + c]));
            let m: Mask = le([j as i64; BATCH], nua);
            let m3: Mask = std::array::from_fn(|l| m[l] & !two[l]);
            let t: Lanes = std::array::from_fn(|l| c0[l] + qq[l] * c1[l]);
            let pr = pick(two, t, std::array::from_fn(|l| t[l] + rr[l] * c2[l]));
            *um!(a[k + 2 + c]) = pick(m3, std::array::from_fn(|l| c2[l] - pr[l] * zz[l]), c2);
            *um!(a[k + 1 + c]) = pick(m, std::array::from_fn(|l| c1[l] - pr[l] * yy[l]), c1);
            *um!(a[k + c]) = pick(m, std::array::from_fn(|l| c0[l] - pr[l] * xx[l]), c0);
        }
        // Column modification: rows l..=min(nu, k+3) of columns k..k+2
        // (k..k+1 for the last reflector).
        for i in lmin..=mmax {
            let (a0, a1, a2) = (
                u!(a[i + k * s]),
                u!(a[i + (k + 1) * s]),
                u!(a[i + (k + 2) * s]),
            );
            let ii = [i as i64; BATCH];
            let m: Mask = and(le(loa, ii), le(ii, mma));
            let m3: Mask = std::array::from_fn(|l| m[l] & !two[l]);
            let t: Lanes = std::array::from_fn(|l| xx[l] * a0[l] + yy[l] * a1[l]);
            let pr = pick(two, t, std::array::from_fn(|l| t[l] + zz[l] * a2[l]));
            *um!(a[i + (k + 2) * s]) = pick(m3, std::array::from_fn(|l| a2[l] - pr[l] * rr[l]), a2);
            *um!(a[i + (k + 1) * s]) = pick(m, std::array::from_fn(|l| a1[l] - pr[l] * qq[l]), a1);
            *um!(a[i + k * s]) = pick(m, std::array::from_fn(|l| a0[l] - pr[l]), a0);
        }
    }
}

/// One reflector of a lock-step [`sweep`] for [`sweep_unmasked`]: row `k`,
/// the update ranges (columns `k..=numax`, rows `lmin..=mmax`), the
/// reflector's coefficients as in the scalar `reflector` (`xx, yy, zz` the
/// vector over `p + s`, `qq, rr` over `p`), the lanes whose last (two-row)
/// reflector this is, and the chasing lanes whose block ends at row `k`.
struct Reflector {
    k: usize,
    numax: usize,
    lmin: usize,
    mmax: usize,
    xx: Lanes,
    yy: Lanes,
    zz: Lanes,
    qq: Lanes,
    rr: Lanes,
    two: Mask,
    last: Mask,
}

/// The row and column modifications of one reflector of [`sweep`] without
/// lane selects on the stores, when no chasing lane needs to keep an entry
/// of the update ranges outside its block (`TWO`: some lane applies its
/// last, two-row reflector).
///
/// Why this is exact: the QR iteration computes eigenvalues only, and once
/// a lane works on its block `l..=nu`, it never again reads an entry in a
/// row or a column beyond `nu` (deflated, or outside the active block), nor
/// an entry of rows `< l` in columns `>= l` (the block above is finished
/// alone and reads only its own rows and columns). Every entry this function
/// writes for a lane outside the lane's own update is of that kind, with one
/// exception: a chasing lane whose block ends at row `k` (`last`) would have
/// column `k` (its last column, rows up to `k`) overwritten, so those rows
/// are saved in `scratch` first and put back after. Lanes that finished are
/// never read again at all. A lane whose block starts below row `k` (`k <
/// l`), or whose reflector is degenerate, takes the masked path of
/// [`sweep`] instead. The arithmetic of each lane's own update is that of
/// the scalar `reflector`, operation for operation; the lane's garbage
/// elsewhere (possibly infinite or NaN) never enters it, because the
/// two-row reflector's third row and column are selected away in registers.
#[inline(always)]
fn sweep_unmasked<const TWO: bool>(
    a: &mut [Lanes],
    s: usize,
    scratch: &mut [Lanes],
    r: &Reflector,
) {
    let Reflector {
        k,
        numax,
        lmin,
        mmax,
        xx,
        yy,
        zz,
        qq,
        rr,
        two,
        last,
    } = *r;
    let keep_last = any(last);
    if keep_last {
        debug_assert!(scratch.len() > k);
        for i in lmin..=k {
            *um!(scratch[i]) = u!(a[i + k * s]);
        }
    }
    // Row modification: rows k..k+2 of columns k..=numax (rows k..k+1 for a
    // lane's last reflector: its third row is selected away).
    for j in k..=numax {
        let c = j * s;
        let (c0, c1, c2) = (u!(a[k + c]), u!(a[k + 1 + c]), u!(a[k + 2 + c]));
        let t: Lanes = std::array::from_fn(|l| c0[l] + qq[l] * c1[l]);
        let t3: Lanes = std::array::from_fn(|l| t[l] + rr[l] * c2[l]);
        let pr = if TWO { pick(two, t, t3) } else { t3 };
        *um!(a[k + 2 + c]) = std::array::from_fn(|l| c2[l] - pr[l] * zz[l]);
        *um!(a[k + 1 + c]) = std::array::from_fn(|l| c1[l] - pr[l] * yy[l]);
        *um!(a[k + c]) = std::array::from_fn(|l| c0[l] - pr[l] * xx[l]);
    }
    // Column modification: rows lmin..=mmax of columns k..k+2.
    for i in lmin..=mmax {
        let (a0, a1, a2) = (
            u!(a[i + k * s]),
            u!(a[i + (k + 1) * s]),
            u!(a[i + (k + 2) * s]),
        );
        let t: Lanes = std::array::from_fn(|l| xx[l] * a0[l] + yy[l] * a1[l]);
        let t3: Lanes = std::array::from_fn(|l| t[l] + zz[l] * a2[l]);
        let pr = if TWO { pick(two, t, t3) } else { t3 };
        *um!(a[i + (k + 2) * s]) = std::array::from_fn(|l| a2[l] - pr[l] * rr[l]);
        *um!(a[i + (k + 1) * s]) = std::array::from_fn(|l| a1[l] - pr[l] * qq[l]);
        *um!(a[i + k * s]) = std::array::from_fn(|l| a0[l] - pr[l]);
    }
    if keep_last {
        for i in lmin..=k {
            let (x, y) = (u!(scratch[i]), u!(a[i + k * s]));
            *um!(a[i + k * s]) = pick(last, x, y);
        }
    }
}
