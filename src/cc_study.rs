//! Parameter study of the shape-adjustable Catmull-Clark scheme (math doc
//! sections 6-8): for each valence `n`, as a function of
//! `c` in `[0, 1]`, the subdominant eigenvalues, `|lambda_3|`, the
//! subdominant class and the characteristic-map verdict, and the interval(s)
//! of `c` on which the scheme is certified C1 (class `standard`, map regular
//! and injective: Reif's criterion) or certified `standard`, located by
//! bisection.
//!
//! Classification is [`crate::spectral::classify_scheme`] (the common engine's
//! kernel on the `(2n+1)` one-ring matrix, condition-scaled tolerances; a
//! verdict inside a tolerance is `indeterminate` and is *not* counted as
//! standard). The eigenvalues are cross-checked against the closed-form
//! Fourier blocks ([`crate::schemes::catmull_clark::fourier`]).
//!
//! The characteristic-map verdict is [`crate::charmap::check_classified`]
//! (the cone certificate of [`crate::charmap::catmull_clark`]; the bicubic
//! Bezier certificate at `c = 1/2`). A point counts as C1 only when every
//! step is *certified*; `indeterminate` anywhere counts as "not certified",
//! so the intervals are inner bounds of the true C1 set, and the verdict just
//! outside each end says why the bisection stopped there.
//!
//! The regular part of the surface is C1 for every `c` in `(0, 1]` (the
//! univariate rule's second divided-difference rule `(c/2, 1 - c, c/2)` is
//! contractive, see [`crate::charmap::catmull_clark`]), so Reif's criterion at
//! the extraordinary point decides.
//!
//! ```
//! use subdiv_lab::cc_study::{c1_intervals, standard_intervals, study_point};
//! let p = study_point(5, 0.5).unwrap();
//! assert_eq!(p.class, "standard");
//! assert_eq!(p.charmap, "c1");
//! let iv = standard_intervals(5, 20, 1e-6).unwrap();
//! assert_eq!(iv.len(), 1);
//! assert!(iv[0].hi == 1.0 && iv[0].lo < 1e-3);
//! let c1 = c1_intervals(5, 20, 1e-6).unwrap();
//! // C1 needs a standard eigenstructure, so the C1 interval lies inside the standard one
//! assert!(c1[0].lo >= iv[0].lo && c1[0].hi == 1.0);
//! ```

use crate::charmap;
use crate::error::Error;
use crate::schemes::catmull_clark::fourier;
use crate::schemes::LocalScheme;
use crate::spectral::Result;
use crate::spectral::{classify_scheme, SubdominantClass};
use serde::Serialize;

/// Largest valence of a study.
pub const MAX_VALENCE: usize = 256;

/// Most grid cells in `c` of a study.
pub const MAX_SAMPLES: usize = 100_000;

/// Checks the arguments of a study: `3 <= n_min <= n_max <=`
/// [`MAX_VALENCE`], `1 <= samples <=` [`MAX_SAMPLES`], `0 < tol < 1` (the
/// message names the arguments as `spelling` spells them).
///
/// ```
/// use subdiv_lab::budget::Spelling;
/// use subdiv_lab::cc_study::check_study;
/// assert!(check_study(3, 32, 100, 1e-6, Spelling::Cli).is_ok());
/// assert_eq!(
///     check_study(5, 4, 100, 1e-6, Spelling::Python).unwrap_err(),
///     "need 3 <= n_min <= n_max <= 256, got 5..4"
/// );
/// ```
pub fn check_study(
    n_min: usize,
    n_max: usize,
    samples: usize,
    tol: f64,
    spelling: crate::budget::Spelling,
) -> std::result::Result<(), String> {
    let arg = |name| spelling.arg(name);
    if n_min < 3 || n_max < n_min || n_max > MAX_VALENCE {
        return Err(format!(
            "need 3 <= {} <= {} <= {MAX_VALENCE}, got {n_min}..{n_max}",
            arg("n_min"),
            arg("n_max")
        ));
    }
    if samples == 0 || samples > MAX_SAMPLES {
        return Err(format!(
            "{} must be in 1..={MAX_SAMPLES}, got {samples}",
            arg("samples")
        ));
    }
    check_tol(tol).map_err(|e| format!("{}: {e}", arg("tol")))
}

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
    /// Characteristic-map verdict code ([`charmap::Verdict::code`]: `c1`,
    /// `not_regular`, `not_injective`, `indeterminate`, `no_charmap`).
    pub charmap: &'static str,
}

/// Classifies the adjustable scheme at `(n, c)`.
pub fn study_point(n: usize, c: f64) -> Result<StudyPoint> {
    let s = LocalScheme::<f64>::adjustable_cc(n, c)?;
    let sub = classify_scheme(&s)?;
    let map = charmap::check_classified(&s, &sub)?;
    Ok(StudyPoint {
        valence: n,
        c,
        lambda1: [sub.lambda1.re, sub.lambda1.im],
        lambda2: [sub.lambda2.re, sub.lambda2.im],
        abs_lambda3: sub.abs_lambda3,
        class: sub.class.name(),
        fourier_subdominant: fourier::subdominant(n, c)?,
        charmap: map.verdict.code(),
    })
}

/// What a study point is tested for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Criterion {
    /// Subdominant class certified `standard`.
    Standard,
    /// Certified C1: `standard` and the characteristic map certified regular and injective.
    C1,
}

/// The verdict of `(n, c)` under `criterion`: `Ok("")` when it holds,
/// otherwise a short reason (the class, or `charmap:<verdict code>`).
///
/// A numerical failure at `(n, c)` counts as "not certified", with the
/// reason `error:<message>` (commas replaced so the reason stays one CSV
/// cell): the intervals stay inner bounds and the study goes on.
fn verdict(n: usize, c: f64, criterion: Criterion) -> Result<String> {
    let s = LocalScheme::<f64>::adjustable_cc(n, c)?;
    match certify(&s, criterion) {
        Ok(v) => Ok(v),
        Err(e) => Ok(format!("error:{}", csv_cell(&e.to_string()))),
    }
}

/// `text` with the CSV separators (`,`, line breaks) replaced by `;` and spaces.
pub fn csv_cell(text: &str) -> String {
    text.replace(',', ";").replace(['\n', '\r'], " ")
}

/// The verdict of a valid scheme (see [`verdict`]).
fn certify(s: &LocalScheme<f64>, criterion: Criterion) -> Result<String> {
    let sub = classify_scheme(s)?;
    if !matches!(sub.class, SubdominantClass::Standard) {
        return Ok(sub.class.name().to_owned());
    }
    if criterion == Criterion::Standard {
        return Ok(String::new());
    }
    let map = charmap::check_classified(s, &sub)?;
    Ok(match map.verdict {
        charmap::Verdict::C1Standard => String::new(),
        v => format!("charmap:{}", v.code()),
    })
}

/// `samples + 1` equally spaced values of `c` in `[0, 1]` for one valence.
pub fn study_curve(n: usize, samples: usize) -> Result<Vec<StudyPoint>> {
    let m = samples.max(1);
    (0..=m)
        .map(|k| study_point(n, k as f64 / m as f64))
        .collect()
}

/// `samples + 1` equally spaced values of `c` in `[0, 1]` for one valence,
/// each with its own result: a point whose computation fails keeps its
/// error and the others are still computed (the `cc-study --curves` rows).
pub fn study_curve_rows(n: usize, samples: usize) -> Vec<(f64, Result<StudyPoint>)> {
    let m = samples.max(1);
    (0..=m)
        .map(|k| {
            let c = k as f64 / m as f64;
            (c, study_point(n, c))
        })
        .collect()
}

/// A maximal interval of `c` on which the criterion is certified.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CInterval {
    /// Lower end (certified here).
    pub lo: f64,
    /// Upper end (certified here).
    pub hi: f64,
    /// `lo - step` of the bisection: not certified (or `lo` if `lo = 0`).
    pub lo_outside: f64,
    /// `hi + step`: not certified (or `hi` if `hi = 1`).
    pub hi_outside: f64,
    /// Why `lo_outside` is not certified (class name or `charmap:<code>`;
    /// empty if `lo = 0`).
    pub below: String,
    /// Why `hi_outside` is not certified (empty if `hi = 1`).
    pub above: String,
}

/// Smallest bisection width of [`intervals`]: `f64::EPSILON = 2^-52`
/// (about `2.2e-16`). Doubles in `[1/2, 1)` are `2^-53` apart, the widest
/// spacing in `[0, 1]`, so the midpoint of any bracket in `[0, 1]` wider than
/// `2^-52` lies strictly inside it and every step halves the bracket. Below
/// it a bracket can shrink to two adjacent doubles still wider than `tol`
/// (next to `c = 1/2` they are `1.1e-16` apart) and never narrow further.
pub const MIN_TOL: f64 = f64::EPSILON;

/// Most bisection steps per interval end: `64`. From a bracket of width at
/// most 1, [`MIN_TOL`] is reached in at most 52 halvings; a bracket still
/// wider than `tol` after 64 steps is a numerical failure, never an endless
/// loop.
pub const MAX_BISECTION_STEPS: u32 = 64;

/// Checks a bisection width for [`intervals`]: `MIN_TOL <= tol < 1`.
pub fn check_tol(tol: f64) -> Result<()> {
    if tol.is_finite() && (MIN_TOL..1.0).contains(&tol) {
        return Ok(());
    }
    Err(Error::InvalidParameter {
        name: "tol",
        value: format!("{tol:?}"),
        reason: "the bisection width must be at least 2^-52 (2.2e-16, the spacing f64 resolves in [0, 1]) and below 1",
    }.into())
}

/// Bisection between `inside` (certified) and `outside` (not) to width `tol`
/// (at least [`MIN_TOL`]), in at most [`MAX_BISECTION_STEPS`] steps; returns
/// `(inside, outside, reason at outside)`.
fn bisect(
    n: usize,
    mut inside: f64,
    mut outside: f64,
    mut reason: String,
    tol: f64,
    criterion: Criterion,
) -> Result<(f64, f64, String)> {
    let mut steps = 0;
    while (inside - outside).abs() > tol {
        let mid = 0.5 * (inside + outside);
        let strictly_inside = (inside.min(outside) < mid) && (mid < inside.max(outside));
        if steps == MAX_BISECTION_STEPS || !strictly_inside {
            return Err(Error::Numerical {
                routine: "cc-study bisection",
                reason: format!(
                    "the bracket [{:e}, {:e}] did not narrow to {tol:e} in {steps} steps",
                    inside.min(outside),
                    inside.max(outside)
                ),
            }
            .into());
        }
        steps += 1;
        let v = verdict(n, mid, criterion)?;
        if v.is_empty() {
            inside = mid;
        } else {
            outside = mid;
            reason = v;
        }
    }
    Ok((inside, outside, reason))
}

/// The intervals of `c` in `[0, 1]` on which valence `n` is certified
/// standard (see [`intervals`]).
pub fn standard_intervals(n: usize, samples: usize, tol: f64) -> Result<Vec<CInterval>> {
    intervals(n, samples, tol, Criterion::Standard)
}

/// The intervals of `c` in `[0, 1]` on which valence `n` is certified C1
/// (see [`intervals`]).
pub fn c1_intervals(n: usize, samples: usize, tol: f64) -> Result<Vec<CInterval>> {
    intervals(n, samples, tol, Criterion::C1)
}

/// The intervals of `c` in `[0, 1]` on which valence `n` satisfies
/// `criterion` with certainty: a grid of `samples + 1` values brackets every
/// change, and each end is located by bisection to `tol` (both ends of the
/// final bracket are reported, with the reason just outside). Changes between
/// two grid points that cancel out (two ends within one grid cell) are not
/// seen: choose `samples` accordingly. A `tol` outside `[MIN_TOL, 1)` is an
/// input error ([`check_tol`]).
pub fn intervals(
    n: usize,
    samples: usize,
    tol: f64,
    criterion: Criterion,
) -> Result<Vec<CInterval>> {
    check_tol(tol)?;
    let m = samples.max(1);
    let grid: Vec<f64> = (0..=m).map(|k| k as f64 / m as f64).collect();
    let reasons: Vec<String> = grid
        .iter()
        .map(|&c| verdict(n, c, criterion))
        .collect::<Result<_>>()?;
    let flags: Vec<bool> = reasons.iter().map(String::is_empty).collect();
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
        let (lo, lo_outside, below) = if start == 0 {
            (0.0, 0.0, String::new())
        } else {
            let r = reasons[start - 1].clone();
            bisect(n, grid[start], grid[start - 1], r, tol, criterion)?
        };
        let (hi, hi_outside, above) = if k == m {
            (1.0, 1.0, String::new())
        } else {
            let r = reasons[k + 1].clone();
            bisect(n, grid[k], grid[k + 1], r, tol, criterion)?
        };
        out.push(CInterval {
            lo,
            hi,
            lo_outside,
            hi_outside,
            below,
            above,
        });
        k += 1;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tolerance below what `f64` resolves in `[0, 1]` is an input error
    /// before any work; the smallest accepted one still terminates.
    #[test]
    fn tolerance_below_f64_resolution_is_refused() {
        for tol in [1e-21, 0.0, -1.0, 1.0, f64::NAN, MIN_TOL / 2.0] {
            let e = intervals(5, 4, tol, Criterion::Standard).unwrap_err();
            assert!(
                crate::AnyError::from(e.clone()).is_input_error(),
                "{tol}: {e}"
            );
        }
        let iv = intervals(5, 4, MIN_TOL, Criterion::Standard).unwrap();
        assert!(iv[0].lo > 0.0 && (iv[0].lo - iv[0].lo_outside).abs() <= MIN_TOL);
    }

    /// The bisection itself stops after `MAX_BISECTION_STEPS` (or when the
    /// midpoint no longer lies strictly inside) with a numerical error, even
    /// for a width `f64` cannot reach near the end point (the standard
    /// interval of `n = 5` starts at `c ~ 4.7e-10`, where doubles are
    /// `1.0e-25` apart; a width of `1e-26` is never reached).
    #[test]
    fn bisection_is_bounded_by_a_step_count() {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let r = bisect(5, 1.0 / 64.0, 0.0, "x".into(), 1e-26, Criterion::Standard);
            let _ = tx.send(r);
        });
        let r = rx
            .recv_timeout(std::time::Duration::from_secs(60))
            .expect("the bisection must stop");
        let e = r.unwrap_err();
        assert!(
            !crate::AnyError::from(e.clone()).is_input_error()
                && e.to_string().contains("did not narrow"),
            "{e}"
        );
    }
}
