//! Per-configuration evaluation: the result columns and the one place where a
//! sweep calls the spectral engine.
//!
//! Result columns, by `[columns]` switch (math doc sections 5-7):
//!
//! | switch | columns |
//! |---|---|
//! | `classification` | `class`, `lambda1_re`, `lambda1_im`, `lambda2_re`, `lambda2_im`, `abs_lambda3` |
//! | `gap` | `gap` = `|lambda2| - |lambda3|`; `ratio` = `lambda2 / lambda1` when both are real; `rho` = `|lambda1|` and `theta` = `|arg lambda1|` (radians, in (0, pi)) for a complex pair (empty otherwise) |
//! | `contraction` | `contraction_rate` = `|lambda1|`, the asymptotic per-step contraction of the face towards its limit point (math doc section 5; <= 3/4) |
//! | `eigenvalues = K` | `ev0_re, ev0_im, .., ev{K-1}_re, ev{K-1}_im`: the K leading eigenvalues of `S_n` by non-increasing modulus (empty beyond `4n`) |
//! | `charmap` | `charmap_verdict` (`c1`, `tpc_real_distinct`, `tpc_complex_pair`, `not_regular`, `not_injective`, `indeterminate`, `no_charmap`; see [`crate::charmap::Verdict`]), `charmap_min_jacobian` (smallest Bezier coefficient of the ring's Jacobian relative to the largest; > 0 certifies regularity), `charmap_winding` (winding number of the ring boundary around the origin) |
//! | `exact_certificate` | `exact_class`: the classification decided exactly over the rationals from the exact value of the `f64` parameters (`undecided` when the exact method cannot decide); `exact_agrees` = 1 / 0 when both verdicts are decided and agree / disagree (empty otherwise) |
//!
//! `lambda0 = 1` is the dominant eigenvalue; `lambda1, lambda2` the subdominant
//! pair, `lambda3` the next one. The class is one of `standard`, `real_distinct`,
//! `complex_pair`, `defective`, `not_separated` (math doc section 7), or
//! `indeterminate:A/B` naming the two classes the floating-point evidence could
//! not separate. Classification uses the spectral engine's structured fast path
//! ([`crate::spectral::classify_scheme`]: face block plus the known eigenvalues
//! 1/4, 1/8, 1/16), with its documented tolerances.

use super::plan::{Configuration, Plan};
use super::spec::Columns;
use crate::charmap;
use crate::schemes::LocalScheme;
use crate::spectral::{self, SubdominantClass};

/// One CSV cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// No value.
    Empty,
    /// A number.
    Num(f64),
    /// Text.
    Text(String),
}

/// A result column.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ResultColumn {
    /// CSV header name.
    pub name: String,
    /// Numeric (enters the summary's extremes) or text.
    pub numeric: bool,
}

/// The result columns of `columns`, in CSV order.
pub fn result_columns(columns: &Columns) -> Vec<ResultColumn> {
    let num = |n: &str| ResultColumn {
        name: n.to_owned(),
        numeric: true,
    };
    let text = |n: &str| ResultColumn {
        name: n.to_owned(),
        numeric: false,
    };
    let mut v = Vec::new();
    if columns.classification {
        v.push(text("class"));
        for n in [
            "lambda1_re",
            "lambda1_im",
            "lambda2_re",
            "lambda2_im",
            "abs_lambda3",
        ] {
            v.push(num(n));
        }
    }
    if columns.gap {
        for n in ["gap", "ratio", "rho", "theta"] {
            v.push(num(n));
        }
    }
    if columns.contraction {
        v.push(num("contraction_rate"));
    }
    for k in 0..columns.eigenvalues {
        v.push(num(&format!("ev{k}_re")));
        v.push(num(&format!("ev{k}_im")));
    }
    if columns.charmap {
        v.push(text("charmap_verdict"));
        v.push(num("charmap_min_jacobian"));
        v.push(num("charmap_winding"));
    }
    if columns.exact_certificate {
        v.push(text("exact_class"));
        v.push(num("exact_agrees"));
    }
    v
}

/// Evaluates one configuration into its result cells (one per
/// [`result_columns`] entry, in order). Implementations must be deterministic:
/// the same configuration gives the same cells on any thread.
pub trait Evaluate: Sync {
    /// The result cells of configuration `c` (whose scheme is `scheme`).
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
    ) -> crate::Result<Vec<Cell>>;
}

/// The evaluator of the `sweep` command: the project's spectral engine.
#[derive(Clone, Debug)]
pub struct SpectralEvaluator {
    columns: Columns,
}

impl SpectralEvaluator {
    /// An evaluator computing `columns`.
    pub fn new(columns: Columns) -> Self {
        SpectralEvaluator { columns }
    }
}

impl Evaluate for SpectralEvaluator {
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
    ) -> crate::Result<Vec<Cell>> {
        let cols = &self.columns;
        let mut out = Vec::with_capacity(16 + 2 * cols.eigenvalues);
        let needs_sub = cols.classification
            || cols.gap
            || cols.contraction
            || cols.exact_certificate
            || cols.charmap;
        let sub = if needs_sub {
            Some(spectral::classify_scheme(scheme)?)
        } else {
            None
        };
        if let Some(sub) = &sub {
            if cols.classification {
                out.push(Cell::Text(class_text(&sub.class)));
                out.extend(
                    [
                        sub.lambda1.re,
                        sub.lambda1.im,
                        sub.lambda2.re,
                        sub.lambda2.im,
                        sub.abs_lambda3,
                    ]
                    .map(Cell::Num),
                );
            }
            if cols.gap {
                let opt = |x: Option<f64>| x.map_or(Cell::Empty, Cell::Num);
                out.push(Cell::Num(sub.gap));
                out.push(opt(sub.ratio));
                out.push(opt(sub.rho));
                out.push(opt(sub.theta));
            }
            if cols.contraction {
                out.push(Cell::Num(sub.lambda1.norm()));
            }
        }
        if cols.eigenvalues > 0 {
            let all = spectral::structured::structured_spectrum(scheme)?;
            for k in 0..cols.eigenvalues {
                match all.get(k) {
                    Some(z) => {
                        out.push(Cell::Num(z.re));
                        out.push(Cell::Num(z.im));
                    }
                    None => {
                        out.push(Cell::Empty);
                        out.push(Cell::Empty);
                    }
                }
            }
        }
        if cols.charmap {
            if let Some(sub) = &sub {
                let report = charmap::check_classified(scheme, sub)?;
                out.push(Cell::Text(report.verdict.code().to_owned()));
                out.push(report.min_jacobian_coeff().map_or(Cell::Empty, Cell::Num));
                out.push(
                    report
                        .winding_number
                        .map_or(Cell::Empty, |w| Cell::Num(w as f64)),
                );
            }
        }
        if cols.exact_certificate {
            let exact = plan.exact_scheme(c)?;
            let v = spectral::exact::exact_verdict(&exact, sub.as_ref())?;
            out.push(Cell::Text(
                v.class.map_or("undecided", |k| k.as_str()).to_owned(),
            ));
            out.push(
                v.agrees_with_float
                    .map_or(Cell::Empty, |a| Cell::Num(f64::from(u8::from(a)))),
            );
        }
        Ok(out)
    }
}

/// `standard`, ..., or `indeterminate:A/B`.
fn class_text(c: &SubdominantClass) -> String {
    match c {
        SubdominantClass::Indeterminate { between, .. } => {
            format!(
                "indeterminate:{}/{}",
                between.0.as_str(),
                between.1.as_str()
            )
        }
        other => other.name().to_owned(),
    }
}
