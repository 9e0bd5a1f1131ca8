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
//! it cannot matter ([`SAFE_MIN`](qr::SAFE_MIN)..[`SAFE_MAX`](qr::SAFE_MAX)), and the last reflector of
//! a sweep has its own two-row loops. Many matrices of one dimension (a
//! sweep) go through [`KernelWorkspace::eigenvalues_batch`]: [`BATCH`] of
//! them in lock step, one per SIMD lane, with the same arithmetic bit for bit
//! (module `lockstep`; 2.1x to 2.4x the throughput of one at a time at
//! valences 5 to 16).
//!
//! Files, by concern: `workspace` (the reusable [`KernelWorkspace`] and the
//! dispatch of batches to the lock-step kernel), `hessenberg` (Householder
//! reduction), `qr` (the Francis double-shift QR iteration and its bounds),
//! `condition` (eigenvalue condition numbers by inverse iteration) and
//! `lockstep` (the SIMD-lane versions of the reduction and the iteration).

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

mod condition;
mod hessenberg;
mod lockstep;
mod qr;
mod workspace;

pub use lockstep::BATCH;
pub use qr::{EXCEPTIONAL_SHIFT_PERIOD, MAX_SWEEPS_PER_DIMENSION, MAX_SWEEPS_PER_EIGENVALUE};
pub use workspace::{KernelWorkspace, LOCKSTEP_MAX_DIM, LOCKSTEP_MIN_DIM};

#[cfg(test)]
mod tests;
