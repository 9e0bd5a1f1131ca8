//! Sweeps over any [`Scheme`], including schemes defined outside the crate
//! (math doc section 12).
//!
//! The spec-driven sweep (`subdiv-lab sweep`: samplers, shards, resumable
//! CSV) enumerates the built-in schemes' parameter spaces. A scheme of one's
//! own brings its own parameter space: [`sweep`] evaluates `make(p)` for every
//! parameter point `p` in parallel (rayon, one configuration per task, the
//! linear algebra single-threaded inside) and returns one [`OwnRow`] per point
//! in input order; [`to_csv`] writes them with the spec sweep's column names
//! and number format (shortest round-trip), so the same plotting scripts read
//! both.
//!
//! ```
//! use subdiv_lab::schemes::LocalScheme;
//! use subdiv_lab::sweep::own::{sweep, to_csv};
//! let cs = [0.3, 0.5, 0.7];
//! let rows = sweep(&cs, |&c| LocalScheme::<f64>::adjustable_cc(5, c), false);
//! assert_eq!(rows.len(), 3);
//! assert_eq!(rows[1].subdominant.as_ref().unwrap().class.name(), "standard");
//! let csv = to_csv(&rows);
//! assert!(csv.starts_with("index,label,class,"));
//! ```

use crate::charmap::report::{AnyPatchId, CharmapReport};
use crate::scheme::Scheme;
use crate::spectral::classify::Subdominant;
use rayon::prelude::*;
use std::fmt::Write;

/// The result of one parameter point.
#[derive(Clone, Debug)]
pub struct OwnRow {
    /// Position of the point in the input.
    pub index: usize,
    /// The scheme's [`Scheme::label`] (empty when `make` failed).
    pub label: String,
    /// The subdominant classification, or the error that stopped it.
    pub subdominant: Result<Subdominant, String>,
    /// The characteristic-map check (when asked for and classified).
    pub charmap: Option<Result<CharmapReport<AnyPatchId>, String>>,
}

/// Evaluates `make(p)` for every point of `params` in parallel: the
/// classification by the scheme's fast path or the dense classifier, and the
/// characteristic-map check when `charmap` is set. A failing point records its
/// error and the sweep goes on.
pub fn sweep<P, S, F>(params: &[P], make: F, charmap: bool) -> Vec<OwnRow>
where
    P: Sync,
    S: Scheme,
    F: Fn(&P) -> crate::Result<S> + Sync,
{
    params
        .par_iter()
        .enumerate()
        .map(|(index, p)| {
            let scheme = match make(p) {
                Ok(s) => s,
                Err(e) => {
                    return OwnRow {
                        index,
                        label: String::new(),
                        subdominant: Err(e.to_string()),
                        charmap: None,
                    }
                }
            };
            let sub = crate::spectral::classify_local(&scheme);
            let map = match (&sub, charmap) {
                (Ok(sub), true) => {
                    Some(crate::charmap::check_classified(&scheme, sub).map_err(|e| e.to_string()))
                }
                _ => None,
            };
            OwnRow {
                index,
                label: scheme.label(),
                subdominant: sub.map_err(|e| e.to_string()),
                charmap: map,
            }
        })
        .collect()
}

/// The rows as CSV: `index,label,class,lambda1_re,lambda1_im,lambda2_re,
/// lambda2_im,abs_lambda3,gap,charmap_verdict,charmap_min_jacobian,
/// charmap_winding,error` (empty cells where a value does not apply).
pub fn to_csv(rows: &[OwnRow]) -> String {
    let mut s = String::from(
        "index,label,class,lambda1_re,lambda1_im,lambda2_re,lambda2_im,abs_lambda3,gap,\
         charmap_verdict,charmap_min_jacobian,charmap_winding,error\n",
    );
    let num = |x: f64| crate::sweep::output::format_number(x);
    for r in rows {
        let _ = write!(s, "{},{},", r.index, quote(&r.label));
        match &r.subdominant {
            Ok(sub) => {
                let class = super::eval::class_text(&sub.class);
                let _ = write!(
                    s,
                    "{class},{},{},{},{},{},{},",
                    num(sub.lambda1.re),
                    num(sub.lambda1.im),
                    num(sub.lambda2.re),
                    num(sub.lambda2.im),
                    num(sub.abs_lambda3),
                    num(sub.gap)
                );
            }
            Err(_) => s.push_str(",,,,,,,"),
        }
        match &r.charmap {
            Some(Ok(m)) => {
                let _ = write!(
                    s,
                    "{},{},{},",
                    m.verdict.code(),
                    m.min_jacobian_coeff().map(num).unwrap_or_default(),
                    m.winding_number.map(|w| w.to_string()).unwrap_or_default()
                );
            }
            _ => s.push_str(",,,"),
        }
        let err = match (&r.subdominant, &r.charmap) {
            (Err(e), _) | (_, Some(Err(e))) => quote(e),
            _ => String::new(),
        };
        s.push_str(&err);
        s.push('\n');
    }
    s
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn quote(t: &str) -> String {
    if t.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", t.replace('"', "\"\""))
    } else {
        t.to_owned()
    }
}
