//! `kind = "table"`: an HTML table per configuration (no picture): the
//! eigenvalues of S_n with multiplicities, the subdominant class, the spectral
//! gap, the Theorem 1 certificate sum (math doc section 5) and the measured
//! contraction rate.
//!
//! ```toml
//! [[figure]]
//! kind = "table"
//! configs = [ { scheme = "nurds", ratios = [0.3, 0.6, 0.5] }, ... ]
//! ```

use super::{eigenvalues, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::contraction::MeasureOptions;
use crate::report::backend::Area;
use crate::report::config::{check_analysis_budget, resolve_all, ConfigSpec, Configuration};
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::markup::escape;
use crate::rng::derive_seed;
use crate::spectral::{analyze, AnalyzeOptions, LocalAnalysis, SubdominantClass};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Deserialize;
use std::fmt::Write;
use toml::Spanned;

/// Eigenvalues closer than this (absolute, in the complex plane) are listed as
/// one value with a multiplicity in the HTML table. The repeated eigenvalues of
/// S_n (1/4, 1/8, 1/16, each n times; math doc section 4) come out of a dense
/// eigen-solver perturbed by up to ~sqrt(eps) ~ 1e-8 when they are defective,
/// so the tolerance sits above that; the CSV lists every eigenvalue unmerged.
pub const GROUP_TOL: f64 = 1e-6;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "table",
    default_title: "Configurations",
    summary:
        "HTML table per configuration: eigenvalues, class, gap, certificate sum, measured rate",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    configs: Spanned<Vec<ConfigSpec>>,
}

struct Table {
    configs: Vec<Configuration>,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let configs = resolve_all(fs, &p.configs, None)?;
    check_analysis_budget(fs, &p.configs, &configs)?;
    Ok(Box::new(Table { configs }))
}

impl Figure for Table {
    fn work(&self) -> u64 {
        self.configs.len() as u64
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let rows = self
            .configs
            .par_iter()
            .enumerate()
            .map(|(i, c)| {
                let options = AnalyzeOptions {
                    measure: MeasureOptions {
                        seed: derive_seed(ctx.common.seed, &i.to_string()),
                        ..MeasureOptions::default()
                    },
                    ..AnalyzeOptions::default()
                };
                let a = analyze(&*c.scheme, &options).map_err(|e| ctx.err(e));
                ctx.tick(1);
                a
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Box::new(Output {
            rows: self.configs.iter().cloned().zip(rows).collect(),
        }))
    }
}

struct Output {
    rows: Vec<(Configuration, LocalAnalysis)>,
}

/// Groups nearly equal eigenvalues: (value, multiplicity).
fn grouped(values: &[Complex64]) -> Vec<(Complex64, usize)> {
    let mut out: Vec<(Complex64, usize)> = Vec::new();
    for z in values {
        match out.iter_mut().find(|(w, _)| (w - z).norm() < GROUP_TOL) {
            Some(e) => e.1 += 1,
            None => out.push((*z, 1)),
        }
    }
    out
}

fn ctext(z: Complex64) -> String {
    if z.im.abs() < 1e-14 {
        format!("{:.6}", z.re)
    } else {
        format!(
            "{:.6} {} {:.6}i",
            z.re,
            if z.im < 0.0 { "−" } else { "+" },
            z.im.abs()
        )
    }
}

/// The class for humans; indeterminate verdicts name their two candidates and why.
fn class_text(c: &SubdominantClass) -> String {
    match c {
        SubdominantClass::Indeterminate { between, reason } => format!(
            "indeterminate between {} and {} ({reason})",
            between.0.as_str().replace('_', " "),
            between.1.as_str().replace('_', " ")
        ),
        other => other.name().replace('_', " "),
    }
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        let mut t = DataTable::new(
            None,
            &[
                "config",
                "label",
                "scheme",
                "valence",
                "ratios",
                "class",
                "lambda1_re",
                "lambda1_im",
                "lambda2_re",
                "lambda2_im",
                "abs_lambda3",
                "gap",
                "certificate_sum",
                "certificate_nonnegative",
                "measured_rate",
            ],
        );
        let mut e = DataTable::new(
            Some("eigenvalues"),
            &["config", "index", "re", "im", "modulus"],
        );
        for (i, (c, a)) in self.rows.iter().enumerate() {
            let r = &c.ratios;
            t.push(vec![
                i.to_string(),
                c.label.clone(),
                c.scheme.name().into(),
                c.scheme.valence().to_string(),
                r.iter().map(|x| num(*x)).collect::<Vec<_>>().join(";"),
                a.subdominant.class.name().to_owned(),
                num(a.subdominant.lambda1.re),
                num(a.subdominant.lambda1.im),
                num(a.subdominant.lambda2.re),
                num(a.subdominant.lambda2.im),
                num(a.subdominant.abs_lambda3),
                num(a.subdominant.gap),
                a.contraction
                    .as_ref()
                    .map_or_else(|| "NaN".into(), |c| num(c.certificate_sum)),
                a.contraction
                    .as_ref()
                    .map_or_else(String::new, |c| c.certificate_nonnegative.to_string()),
                a.contraction
                    .as_ref()
                    .map_or_else(|| "NaN".into(), |c| num(c.measured_rate)),
            ]);
            for (k, z) in eigenvalues(a).iter().enumerate() {
                e.push(vec![
                    i.to_string(),
                    k.to_string(),
                    num(z.re),
                    num(z.im),
                    num(z.norm()),
                ]);
            }
        }
        vec![t, e]
    }

    fn has_plot(&self) -> bool {
        false
    }

    fn draw(&self, _area: &Area<'_>, _common: &Common) -> Result<(), ReportError> {
        Ok(())
    }

    fn html(&self) -> Option<String> {
        let mut h = String::new();
        for (c, a) in &self.rows {
            let _ = writeln!(h, "<h3>{}</h3>", escape(&c.label));
            let r = &c.ratios;
            let _ = writeln!(
                h,
                "<table><tr><th class=\"l\">scheme</th><td class=\"l\">{} (n = {})</td></tr>\
                 <tr><th class=\"l\">edge ratios r<sub>i</sub></th><td class=\"l\">{}</td></tr>\
                 <tr><th class=\"l\">class</th><td class=\"l\">{}</td></tr>\
                 <tr><th class=\"l\">λ<sub>1</sub>, λ<sub>2</sub></th><td class=\"l\">{}, {}</td></tr>\
                 <tr><th class=\"l\">|λ<sub>1</sub>|, |λ<sub>2</sub>|, |λ<sub>3</sub>|</th><td class=\"l\">{:.6}, {:.6}, {:.6}</td></tr>\
                 <tr><th class=\"l\">gap |λ<sub>2</sub>| − |λ<sub>3</sub>|</th><td class=\"l\">{:.6}</td></tr>\
                 <tr><th class=\"l\">Theorem 1 certificate sum (weights ≥ 0: {})</th><td class=\"l\">{}</td></tr>\
                 <tr><th class=\"l\">measured contraction rate</th><td class=\"l\">{}</td></tr></table>",
                escape(c.scheme.name()),
                c.scheme.valence(),
                escape(
                    &r.iter()
                        .map(|x| format!("{x:.6}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                escape(&class_text(&a.subdominant.class)),
                ctext(a.subdominant.lambda1),
                ctext(a.subdominant.lambda2),
                a.subdominant.lambda1.norm(),
                a.subdominant.lambda2.norm(),
                a.subdominant.abs_lambda3,
                a.subdominant.gap,
                match &a.contraction {
                    Some(c) if c.certificate_nonnegative => "yes",
                    Some(_) => "no",
                    None => "n/a",
                },
                a.contraction
                    .as_ref()
                    .map_or_else(|| "n/a".into(), |c| num(c.certificate_sum)),
                a.contraction
                    .as_ref()
                    .map_or_else(|| "n/a".into(), |c| format!("{:.6}", c.measured_rate)),
            );
            h.push_str("<table><tr><th>#</th><th>eigenvalue of S<sub>n</sub></th><th>|λ|</th><th>multiplicity</th></tr>\n");
            for (k, (z, m)) in grouped(&eigenvalues(a)).iter().enumerate() {
                let _ = writeln!(
                    h,
                    "<tr><td>{k}</td><td>{}</td><td>{:.6}</td><td>{m}</td></tr>",
                    ctext(*z),
                    z.norm()
                );
            }
            h.push_str("</table>\n");
        }
        Some(h)
    }
}
