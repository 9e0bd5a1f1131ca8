//! The Francis double-shift QR iteration (EISPACK `hqr`, eigenvalues only) on
//! an upper Hessenberg matrix, with its iteration bounds and the range of the
//! reflectors' rescaling.

use crate::spectral::SpectralError;

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
/// the lane-interleaved storage of [`lockstep`](super::lockstep).
pub(super) trait HqrMatrix {
    /// Entry `(i, j)`.
    fn at(&self, i: usize, j: usize) -> f64;
    /// Mutable entry `(i, j)`.
    fn at_mut(&mut self, i: usize, j: usize) -> &mut f64;
    /// Zeroes the entries `(i, i - 2)` for `m + 2 <= i <= nu` and `(i, i -
    /// 3)` for `m + 3 <= i <= nu` (left from the previous sweep's bulge) as a
    /// sweep starting at row `m` is set up. The lanes of the lock-step
    /// iteration do nothing here: it zeroes them for all lanes at once
    /// before the sweep (nothing reads them in between).
    #[inline(always)]
    fn clear_bulge(&mut self, m: usize, nu: usize) {
        for i in m + 2..=nu {
            *self.at_mut(i, i - 2) = 0.0;
            if i != m + 2 {
                *self.at_mut(i, i - 3) = 0.0;
            }
        }
    }
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
pub(super) struct Hqr {
    n: usize,
    pub(super) anorm: f64,
    budget: usize,
    pub(super) total: usize,
    /// Accumulated exceptional shift.
    t: f64,
    /// Index of the last row of the active block (inclusive); `< 0`: done.
    pub(super) nn: isize,
    /// Sweeps since the last deflation.
    its: usize,
    pub(super) chasing: bool,
    /// Active block `l..=nu`; the sweep's next reflector is at row `k`.
    pub(super) l: usize,
    pub(super) nu: usize,
    k: usize,
    /// First reflector's vector (set up by the shift).
    pub(super) p: f64,
    pub(super) q: f64,
    pub(super) r: f64,
}

impl Hqr {
    #[inline(always)]
    pub(super) fn new<A: HqrMatrix>(n: usize, a: &A) -> Self {
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
    /// several matrices ([`lockstep`](super::lockstep)) runs exactly this code
    /// on each lane.
    #[inline(always)]
    pub(super) fn search<A: HqrMatrix>(
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
    pub(super) fn split_at<A: HqrMatrix>(
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
        a.clear_bulge(m, nu);
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
pub(super) fn negligible(sub: f64, d0: f64, d1: f64, anorm: f64) -> bool {
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
