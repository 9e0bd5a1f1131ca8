//! `kind = "table"`: an HTML table per configuration (no picture): the
//! eigenvalues of S_n with multiplicities, the subdominant class, the spectral
//! gap, the Theorem 1 certificate sum (math doc section 5) and the measured
//! contraction rate; with `charmap`, the verdict of that characteristic-map
//! certificate (`ring`: math doc section 7; `generic`: section 20).
//!
//! ```toml
//! [[figure]]
//! kind = "table"
//! configs = [ { scheme = "nurds", ratios = [0.3, 0.6, 0.5] }, ... ]
//! charmap = "generic"          # optional: "ring" or "generic"
//! ```

use super::{eigenvalues, num, Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::charmap::{certify, generic, Method};
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
    charmap: Option<Spanned<String>>,
}

struct Table {
    configs: Vec<Configuration>,
    charmap: Option<Method>,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    let charmap = match &p.charmap {
        None => None,
        Some(m) => Some(Method::from_name(m.get_ref()).ok_or_else(|| {
            fs.error_at(
                m,
                "charmap",
                format!(
                    "charmap must be one of {}, got {:?}",
                    Method::NAMES.join(", "),
                    m.get_ref()
                ),
            )
        })?),
    };
    let configs = resolve_all(fs, &p.configs, None)?;
    check_analysis_budget(fs, &p.configs, &configs)?;
    if charmap == Some(Method::Generic) {
        let seconds: f64 = configs
            .iter()
            .map(|c| generic::estimate(&*c.scheme).seconds)
            .sum();
        if seconds > crate::budget::TIME_LIMIT_SECONDS {
            return Err(fs.error_at(
                &p.configs,
                "configs",
                format!(
                    "the generic certificate of {} configuration{} takes ~{} (limit {} s); use fewer or smaller configurations",
                    configs.len(),
                    if configs.len() == 1 { "" } else { "s" },
                    crate::budget::format_seconds(seconds),
                    crate::budget::TIME_LIMIT_SECONDS
                ),
            ));
        }
    }
    Ok(Box::new(Table { configs, charmap }))
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
                let a = analyze(&*c.scheme, &options).map_err(|e| ctx.err(e))?;
                let cert = self.charmap.map(|m| {
                    let cert = certify(m, &*c.scheme, &a.charmap_subdominant());
                    (cert.verdict_code(), cert.verdict_text())
                });
                ctx.tick(1);
                Ok((a, cert))
            })
            .collect::<Result<Vec<_>, ReportError>>()?;
        Ok(Box::new(Output {
            charmap: self.charmap,
            rows: self
                .configs
                .iter()
                .cloned()
                .zip(rows)
                .map(|(c, (a, cert))| (c, a, cert))
                .collect(),
        }))
    }
}

/// A certificate's verdict code and its text for humans.
type CertificateVerdict = (&'static str, String);

struct Output {
    charmap: Option<Method>,
    rows: Vec<(Configuration, LocalAnalysis, Option<CertificateVerdict>)>,
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
        let mut header = vec![
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
        ];
        if self.charmap.is_some() {
            header.extend(["charmap_method", "charmap_verdict"]);
        }
        let mut t = DataTable::new(None, &header);
        let mut e = DataTable::new(
            Some("eigenvalues"),
            &["config", "index", "re", "im", "modulus"],
        );
        for (i, (c, a, cert)) in self.rows.iter().enumerate() {
            let r = &c.ratios;
            let mut row = vec![
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
            ];
            if let (Some(m), Some((code, _))) = (self.charmap, cert) {
                row.extend([m.as_str().to_owned(), (*code).to_owned()]);
            }
            t.push(row);
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
        for (c, a, cert) in &self.rows {
            let _ = writeln!(h, "<h3>{}</h3>", escape(&c.label));
            let cert_row = match (self.charmap, cert) {
                (Some(m), Some((_, text))) => format!(
                    "<tr><th class=\"l\">characteristic map ({} certificate)</th><td class=\"l\">{}</td></tr>",
                    m.as_str(),
                    escape(text)
                ),
                _ => String::new(),
            };
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
                 <tr><th class=\"l\">measured contraction rate</th><td class=\"l\">{}</td></tr>{}</table>",
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
                cert_row,
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
