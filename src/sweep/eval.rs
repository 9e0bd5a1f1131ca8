//! Per-configuration evaluation: the result columns and the one place where a
//! sweep calls the spectral engine.
//!
//! Result columns, by `[columns]` switch (math doc sections 5-7):
//!
//! | switch | columns |
//! |---|---|
//! | `classification` | `class`, `lambda1_re`, `lambda1_im`, `lambda2_re`, `lambda2_im`, `abs_lambda3` |
//! | `gap` | `gap` = `|lambda2| - |lambda3|`, `modulus_ratio` = `|lambda2| / |lambda1|`, `theta` = `arg lambda1` (radians; the rotation angle of a complex pair, 0 for real) |
//! | `contraction` | `contraction_rate` = `|lambda1|`, the asymptotic per-step contraction of the face towards its limit point (math doc section 5; <= 3/4) |
//! | `eigenvalues = K` | `ev0_re, ev0_im, .., ev{K-1}_re, ev{K-1}_im`: the K leading eigenvalues of `S_n` by non-increasing modulus (empty beyond `4n`) |
//! | `exact_certificate` | `exact_class`: the classification decided exactly over the rationals |
//!
//! `lambda0 = 1` is the dominant eigenvalue; `lambda1, lambda2` the subdominant
//! pair, `lambda3` the next one.

use super::plan::{Configuration, Plan};
use super::spec::Columns;
use crate::schemes::LocalScheme;

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
        for n in ["gap", "modulus_ratio", "theta"] {
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
    if columns.exact_certificate {
        v.push(text("exact_class"));
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
        let _ = (plan, c, scheme, &self.columns);
        Err(crate::Error::Numerical {
            routine: "sweep",
            reason: "spectral engine not merged yet".into(),
        })
    }
}
