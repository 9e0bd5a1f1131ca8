//! Scheme configurations as written in report specs.
//!
//! ```toml
//! configs = [
//!   { scheme = "cc-variant", valence = 5 },
//!   { scheme = "nurds", ratios = [0.3, 0.6, 0.5] },            # r_i per edge
//!   { scheme = "nurds", knots = [[1, 2], [2, 1], [1, 1]] },    # [p_i, q_i] per corner
//!   { scheme = "nurds", valence = 6, random_knots = 4.0 },     # p_i, q_i log-uniform in [1, 4]
//!   { scheme = "doo-sabin", valence = 3, label = "Doo-Sabin, triangle" },
//!   { scheme_file = "my-cc.toml", valence = 5 },              # a scheme file (math doc section 12.1)
//! ]
//! ```
//!
//! A configuration names a built-in `scheme` or a `scheme_file` (read by the
//! front end, [`ReportSpec::parse_with`](super::ReportSpec::parse_with); the
//! command-line tool reads it beside the spec), never both; a scheme file's
//! configuration takes a `valence` and no knots or `c`.
//!
//! `scheme = "nurds"` without `ratios`, `knots` or `random_knots` is uniform
//! NURDS of the given valence. Random knots are drawn while the spec is parsed,
//! from the figure's seed, so the configuration is fixed by the spec and seed.

use super::error::ReportError;
use super::figure_spec::FigureSpec;
use crate::knots::{CornerIntervals, EdgeRatios};
use crate::rng::{log_uniform, SplitMix64};
use crate::schemes::choice::{validate, Choice, ChoiceError};
use crate::schemes::LocalScheme;
use crate::schemes::SchemeKind;
use crate::schemes::{Scheme, SpectralStructure};
use serde::Deserialize;
use std::sync::Arc;
use toml::Spanned;

/// Largest accepted valence in a report configuration (the figures' cost grows like n^3).
pub const MAX_VALENCE: usize = 256;

/// One configuration as written in a spec.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConfigSpec {
    /// Scheme name (`nurds`, `doo-sabin`, `cc-variant`, `catmull-clark`,
    /// `adjustable-cc`, `loop`); exactly one of `scheme` and `scheme_file`.
    pub scheme: Option<Spanned<String>>,
    /// A scheme file (math doc section 12.1), read through the spec's file
    /// reader.
    pub scheme_file: Option<Spanned<String>>,
    /// Valence (inferred from `ratios`/`knots` when omitted).
    pub valence: Option<Spanned<usize>>,
    /// Edge ratios r_i in (0, 1).
    pub ratios: Option<Spanned<Vec<f64>>>,
    /// Corner knot intervals `[p_i, q_i]`.
    pub knots: Option<Spanned<Vec<[f64; 2]>>>,
    /// Random knot intervals, log-uniform in [1, value].
    pub random_knots: Option<Spanned<f64>>,
    /// Shape parameter `c` in [0, 1] (`adjustable-cc` only).
    pub c: Option<Spanned<f64>>,
    /// Legend label (default: generated from the parameters).
    pub label: Option<String>,
}

/// A validated configuration.
#[derive(Clone, Debug)]
pub struct Configuration {
    /// Label used in legends and tables.
    pub label: String,
    /// The configuration: a built-in [`LocalScheme`] or a scheme file's.
    pub scheme: Arc<dyn Scheme>,
    /// The edge ratios of the E/C rows that tables show (uniform for the
    /// built-in schemes without knot intervals; empty for Loop and scheme
    /// files, whose local matrices have no such rows).
    pub ratios: Vec<f64>,
}

impl ConfigSpec {
    /// Validates the configuration; `key` is its dotted key (for messages),
    /// `rng` supplies random knots.
    pub fn resolve(
        &self,
        fs: &FigureSpec<'_>,
        key: &str,
        rng: &mut SplitMix64,
    ) -> Result<Configuration, ReportError> {
        let scheme = match (&self.scheme, &self.scheme_file) {
            (Some(s), None) => s,
            (None, Some(f)) => return self.resolve_file(fs, key, f),
            (Some(_), Some(f)) => {
                return Err(fs.error_at(
                    f,
                    &format!("{key}.scheme_file"),
                    "give either scheme or scheme_file, not both",
                ))
            }
            (None, None) => {
                return Err(fs.error(format!(
                    "{key}: give scheme (a built-in name) or scheme_file"
                )))
            }
        };
        let given = [
            self.ratios.is_some(),
            self.knots.is_some(),
            self.random_knots.is_some(),
        ]
        .iter()
        .filter(|b| **b)
        .count();
        if scheme.get_ref().parse::<SchemeKind>().is_ok() && given > 1 {
            return Err(fs.error_at(
                scheme,
                key,
                "give at most one of ratios, knots and random_knots",
            ));
        }
        // The shared rules (crate::schemes::choice); the error names the key of
        // the wrong part.
        let choice = Choice {
            name: scheme.get_ref(),
            knots: given > 0,
            c: self.c.is_some(),
        };
        let kind = validate(&choice).map_err(|e| match (&e, &self.c) {
            (ChoiceError::TakesNoC(_), Some(c)) => {
                fs.error_at(c, &format!("{key}.c"), e.to_string())
            }
            (ChoiceError::NeedsC(_), _) => fs.error_at(scheme, &format!("{key}.c"), e.to_string()),
            _ => fs.error_at(scheme, &format!("{key}.scheme"), e.to_string()),
        })?;
        if let Some(v) = &self.valence {
            let n = *v.get_ref();
            if !(3..=MAX_VALENCE).contains(&n) {
                return Err(fs.error_at(
                    v,
                    &format!("{key}.valence"),
                    format!("valence must be between 3 and {MAX_VALENCE}, got {n}"),
                ));
            }
        }
        let mut suffix = String::new();
        let ratios: Option<EdgeRatios<f64>> = if let Some(r) = &self.ratios {
            let er = EdgeRatios::new(r.get_ref().clone())
                .map_err(|e| fs.error_at(r, &format!("{key}.ratios"), e.to_string()))?;
            Some(er)
        } else if let Some(k) = &self.knots {
            let p: Vec<f64> = k.get_ref().iter().map(|x| x[0]).collect();
            let q: Vec<f64> = k.get_ref().iter().map(|x| x[1]).collect();
            let ci = CornerIntervals::new(p, q)
                .map_err(|e| fs.error_at(k, &format!("{key}.knots"), e.to_string()))?;
            Some(
                ci.ratios()
                    .map_err(|e| fs.error_at(k, &format!("{key}.knots"), e.to_string()))?,
            )
        } else if let Some(m) = &self.random_knots {
            let max = *m.get_ref();
            if !(max.is_finite() && max > 1.0 && max <= 1e6) {
                return Err(fs.error_at(
                    m,
                    &format!("{key}.random_knots"),
                    format!("random_knots is the largest interval ratio, in (1, 1e6]; got {max}"),
                ));
            }
            let Some(v) = &self.valence else {
                return Err(fs.error_at(m, key, "random_knots needs a valence"));
            };
            let n = *v.get_ref();
            let p: Vec<f64> = (0..n).map(|_| log_uniform(rng, max)).collect();
            let q: Vec<f64> = (0..n).map(|_| log_uniform(rng, max)).collect();
            let rk = format!("{key}.random_knots");
            let ci = CornerIntervals::new(p, q).map_err(|e| fs.error_at(m, &rk, e.to_string()))?;
            suffix = format!(", random knots <= {max}");
            Some(
                ci.ratios()
                    .map_err(|e| fs.error_at(m, &rk, e.to_string()))?,
            )
        } else {
            None
        };
        let valence = match (&ratios, &self.valence) {
            (Some(r), Some(v)) if r.valence() != *v.get_ref() => {
                return Err(fs.error_at(
                    v,
                    &format!("{key}.valence"),
                    format!(
                        "valence {} does not match the {} knot values given",
                        v.get_ref(),
                        r.valence()
                    ),
                ))
            }
            (Some(r), _) => r.valence(),
            (None, Some(v)) => *v.get_ref(),
            (None, None) => {
                return Err(fs.error_at(
                    scheme,
                    key,
                    "valence is required unless ratios or knots are given",
                ))
            }
        };
        let c = self.c.as_ref().map(|c| *c.get_ref());
        let local = LocalScheme::from_kind_with_c(kind, valence, ratios.clone(), c).map_err(
            |e| match &self.c {
                Some(cv) => fs.error_at(cv, &format!("{key}.c"), e.to_string()),
                None => fs.error_at(scheme, key, e.to_string()),
            },
        )?;
        let label = match &self.label {
            Some(l) => l.clone(),
            None => default_label(&local, &suffix),
        };
        let ratios = match kind {
            SchemeKind::Loop => Vec::new(),
            k if k.is_triangle_lattice_scheme() => Vec::new(),
            _ => local.ratios().as_slice().to_vec(),
        };
        Ok(Configuration {
            label,
            scheme: Arc::new(local),
            ratios,
        })
    }

    /// A configuration from a scheme file: a `valence` and no knot data or
    /// `c` (a scheme file's weights are functions of the valence only).
    fn resolve_file(
        &self,
        fs: &FigureSpec<'_>,
        key: &str,
        path: &Spanned<String>,
    ) -> Result<Configuration, ReportError> {
        let refused = [
            ("ratios", self.ratios.as_ref().map(|s| s.span())),
            ("knots", self.knots.as_ref().map(|s| s.span())),
            ("random_knots", self.random_knots.as_ref().map(|s| s.span())),
            ("c", self.c.as_ref().map(|s| s.span())),
        ];
        if let Some((name, Some(span))) = refused.iter().find(|(_, s)| s.is_some()) {
            return Err(fs.error_at(
                &Spanned::new(span.clone(), ()),
                &format!("{key}.{name}"),
                format!("{name} is not taken with scheme_file (a scheme file's weights depend on the valence only)"),
            ));
        }
        let Some(v) = &self.valence else {
            return Err(fs.error_at(path, key, "scheme_file needs a valence"));
        };
        if !(3..=MAX_VALENCE).contains(v.get_ref()) {
            return Err(fs.error_at(
                v,
                &format!("{key}.valence"),
                format!(
                    "valence must be between 3 and {MAX_VALENCE}, got {}",
                    v.get_ref()
                ),
            ));
        }
        let file = fs.scheme_file(path, &format!("{key}.scheme_file"))?;
        let scheme = file
            .at(*v.get_ref())
            .map_err(|e| fs.error_at(v, &format!("{key}.valence"), e.to_string()))?;
        let label = self.label.clone().unwrap_or_else(|| scheme.label());
        Ok(Configuration {
            label,
            scheme: Arc::new(scheme),
            ratios: Vec::new(),
        })
    }
}

/// The generated legend label of a configuration
/// ([`LocalScheme::legend_label`]).
pub fn default_label(scheme: &LocalScheme<f64>, suffix: &str) -> String {
    scheme.legend_label(suffix)
}

/// Validates the `configs` list of a figure: between 1 and `max` entries (a
/// `max` of `None` means no upper limit), each resolved with keys
/// `configs[i]` and random knots drawn from the figure's seed in list order.
pub fn resolve_all(
    fs: &FigureSpec<'_>,
    configs: &Spanned<Vec<ConfigSpec>>,
    max: Option<usize>,
) -> Result<Vec<Configuration>, ReportError> {
    let count = configs.get_ref().len();
    let upper = max.unwrap_or(usize::MAX);
    if count == 0 || count > upper {
        let message = match max {
            Some(m) => format!("give 1 to {m} configurations, got {count}"),
            None => "configs must list at least one configuration".to_owned(),
        };
        return Err(fs.error_at(configs, "configs", message));
    }
    let mut rng = SplitMix64::new(fs.seed());
    configs
        .get_ref()
        .iter()
        .enumerate()
        .map(|(i, c)| c.resolve(fs, &format!("configs[{i}]"), &mut rng))
        .collect()
}

/// Refuses (naming `configs`) a figure whose configurations together would
/// take longer than [`crate::budget::TIME_LIMIT_SECONDS`] to analyse: the
/// sum of the `analyze` estimates ([`crate::budget::analyze`], full path) of
/// every configuration. A table of a few NURDS faces of valence 256 (about
/// 30 s each) would otherwise run for minutes without a word.
pub fn check_analysis_budget(
    fs: &FigureSpec<'_>,
    specs: &Spanned<Vec<ConfigSpec>>,
    configs: &[Configuration],
) -> Result<(), ReportError> {
    let seconds: f64 = configs
        .iter()
        .map(|c| crate::budget::analyze(&c.scheme.cost_model(), c.scheme.valence(), false).seconds)
        .sum();
    if seconds > crate::budget::TIME_LIMIT_SECONDS {
        let largest = configs
            .iter()
            .map(|c| c.scheme.valence())
            .max()
            .unwrap_or(0);
        return Err(fs.error_at(
            specs,
            "configs",
            format!(
                "analysing these {} configurations (valences up to {largest}) takes ~{} (limit {} s); use fewer or smaller configurations",
                configs.len(),
                crate::budget::format_seconds(seconds),
                crate::budget::TIME_LIMIT_SECONDS
            ),
        ));
    }
    Ok(())
}

/// Rejects configurations outside the Doo-Sabin family for figures built on
/// its notions (face contraction, the 9n-point characteristic ring); the
/// error names `configs[i].scheme` and its line.
pub fn require_doo_sabin_family(
    fs: &FigureSpec<'_>,
    specs: &Spanned<Vec<ConfigSpec>>,
    configs: &[Configuration],
    what: &str,
) -> Result<(), ReportError> {
    for (i, (spec, c)) in specs.get_ref().iter().zip(configs).enumerate() {
        if c.scheme.spectral_structure() != SpectralStructure::FaceBlock {
            let (at, key) = match (&spec.scheme, &spec.scheme_file) {
                (Some(s), _) => (s, "scheme"),
                (None, Some(f)) => (f, "scheme_file"),
                (None, None) => return Err(fs.error(format!("configs[{i}]: no scheme"))),
            };
            return Err(fs.error_at(
                at,
                &format!("configs[{i}].{key}"),
                format!(
                    "scheme {} is not in the Doo-Sabin family (nurds, doo-sabin, cc-variant), which {what} needs",
                    c.scheme.name()
                ),
            ));
        }
    }
    Ok(())
}
