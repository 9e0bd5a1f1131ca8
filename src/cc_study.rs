//! Parameter study of the shape-adjustable Catmull-Clark scheme (issue 8,
//! item 3; math doc sections 6-8): for each valence `n`, as a function of
//! `c` in `[0, 1]`, the subdominant eigenvalues, `|lambda_3|` and the
//! subdominant class, and the interval(s) of `c` on which the class is
//! certified `standard`, located by bisection.
//!
//! Classification is [`crate::spectral::classify_scheme`] (the common engine's
//! kernel on the `(2n+1)` one-ring matrix, condition-scaled tolerances; a
//! verdict inside a tolerance is `indeterminate` and is *not* counted as
//! standard). The eigenvalues are cross-checked against the closed-form
//! Fourier blocks ([`crate::schemes::catmull_clark::fourier`]).
//!
//! **Scope**: the C1 criterion also needs the characteristic map to be
//! regular and injective; that verdict is not part of this study (the
//! characteristic map of the Catmull-Clark family is not implemented yet), so
//! the intervals here are the *spectral* part of the C1 intervals only.
//!
//! ```
//! use subdiv_lab::cc_study::{standard_intervals, study_point};
//! let p = study_point(5, 0.5).unwrap();
//! assert_eq!(p.class, "standard");
//! let iv = standard_intervals(5, 20, 1e-6).unwrap();
//! assert_eq!(iv.len(), 1);
//! assert!(iv[0].hi == 1.0 && iv[0].lo < 1e-3);
//! ```

use crate::error::Result;
use crate::schemes::catmull_clark::fourier;
use crate::schemes::LocalScheme;
use crate::spectral::{classify_scheme, SubdominantClass};
use serde::Serialize;

/// One `(n, c)` sample.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StudyPoint {
    /// Valence.
    pub valence: usize,
    /// Shape parameter.
    pub c: f64,
    /// `lambda_1` as `[re, im]`.
    pub lambda1: [f64; 2],
    /// `lambda_2` as `[re, im]`.
    pub lambda2: [f64; 2],
    /// `|lambda_3|`.
    pub abs_lambda3: f64,
    /// Subdominant class name (`standard`, `not_separated`, `indeterminate`, ...).
    pub class: &'static str,
    /// `|lambda_1|` from the closed-form Fourier blocks (cross-check).
    pub fourier_subdominant: f64,
}

/// Classifies the adjustable scheme at `(n, c)`.
pub fn study_point(n: usize, c: f64) -> Result<StudyPoint> {
    let s = LocalScheme::<f64>::adjustable_cc(n, c)?;
    let sub = classify_scheme(&s)?;
    Ok(StudyPoint {
        valence: n,
        c,
        lambda1: [sub.lambda1.re, sub.lambda1.im],
        lambda2: [sub.lambda2.re, sub.lambda2.im],
        abs_lambda3: sub.abs_lambda3,
        class: sub.class.name(),
        fourier_subdominant: fourier::subdominant(n, c)?,
    })
}

fn is_standard(n: usize, c: f64) -> Result<bool> {
    let s = LocalScheme::<f64>::adjustable_cc(n, c)?;
    Ok(matches!(
        classify_scheme(&s)?.class,
        SubdominantClass::Standard
    ))
}

/// `samples + 1` equally spaced values of `c` in `[0, 1]` for one valence.
pub fn study_curve(n: usize, samples: usize) -> Result<Vec<StudyPoint>> {
    let m = samples.max(1);
    (0..=m)
        .map(|k| study_point(n, k as f64 / m as f64))
        .collect()
}

/// A maximal interval of `c` on which the class is certified standard.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CInterval {
    /// Lower end (certified standard here).
    pub lo: f64,
    /// Upper end (certified standard here).
    pub hi: f64,
    /// `lo - step` of the bisection: not certified standard (or `lo` if `lo = 0`).
    pub lo_outside: f64,
    /// `hi + step`: not certified standard (or `hi` if `hi = 1`).
    pub hi_outside: f64,
}

/// Bisection between `inside` (standard) and `outside` (not) to width `tol`;
/// returns `(inside, outside)`.
fn bisect(n: usize, mut inside: f64, mut outside: f64, tol: f64) -> Result<(f64, f64)> {
    while (inside - outside).abs() > tol {
        let mid = 0.5 * (inside + outside);
        if is_standard(n, mid)? {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    Ok((inside, outside))
}

/// The intervals of `c` in `[0, 1]` on which valence `n` is certified
/// standard: a grid of `samples + 1` values brackets every change, and each
/// end is located by bisection to `tol`. Changes between two grid points that
/// cancel out (two ends within one grid cell) are not seen: choose `samples`
/// accordingly.
pub fn standard_intervals(n: usize, samples: usize, tol: f64) -> Result<Vec<CInterval>> {
    let m = samples.max(1);
    let grid: Vec<f64> = (0..=m).map(|k| k as f64 / m as f64).collect();
    let flags: Vec<bool> = grid
        .iter()
        .map(|&c| is_standard(n, c))
        .collect::<Result<_>>()?;
    let mut out = Vec::new();
    let mut k = 0;
    while k <= m {
        if !flags[k] {
            k += 1;
            continue;
        }
        let start = k;
        while k < m && flags[k + 1] {
            k += 1;
        }
        let (lo, lo_outside) = if start == 0 {
            (0.0, 0.0)
        } else {
            bisect(n, grid[start], grid[start - 1], tol)?
        };
        let (hi, hi_outside) = if k == m {
            (1.0, 1.0)
        } else {
            bisect(n, grid[k], grid[k + 1], tol)?
        };
        out.push(CInterval {
            lo,
            hi,
            lo_outside,
            hi_outside,
        });
        k += 1;
    }
    Ok(out)
}
