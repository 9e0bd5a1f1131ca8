//! The scheme and knot flags shared by `matrix`, `analyze` and friends, and
//! their validation into library types.

use super::{CliError, CliResult};
use anyhow::anyhow;
use clap::Args;
use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::scalar::{parse_exact, Rational, Scalar};
use subdiv_lab::schemes::choice::{validate, Choice, ChoiceError};
use subdiv_lab::schemes::user::SchemeFile;
use subdiv_lab::schemes::{LocalScheme, SchemeKind};
use subdiv_lab::Scheme;

/// Scheme selection flags.
#[derive(Args, Debug, Clone)]
pub(crate) struct SchemeArgs {
    #[arg(long, default_value = "nurds", help = scheme_help())]
    pub scheme: String,
    /// Valence n >= 3 of the extraordinary face (inferred from --knots/--ratios if omitted).
    #[arg(long)]
    pub valence: Option<usize>,
    /// Corner knot intervals "p0:q0,p1:q1,..." (n pairs; p_i = d(P_i->P_i+1), q_i = d(P_i->P_i-1)).
    #[arg(long, allow_hyphen_values = true)]
    pub knots: Option<String>,
    /// Edge ratios "r0,r1,..." (n values in (0,1)).
    #[arg(long, allow_hyphen_values = true)]
    pub ratios: Option<String>,
    /// Uniform knot intervals (all ratios 1/2).
    #[arg(long)]
    pub uniform: bool,
    /// Shape parameter c in [0, 1] of --scheme adjustable-cc (read exactly: 0.3, 1/3, 25e-2).
    #[arg(long, allow_hyphen_values = true)]
    pub c: Option<String>,
    /// A scheme file (TOML: a vertex rule in n; docs/scheme-files.md) instead of --scheme.
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["scheme", "knots", "ratios", "uniform", "c"])]
    pub scheme_file: Option<std::path::PathBuf>,
}

/// Reads and validates a scheme file; errors name the flag (or spec key)
/// `what` and the file, on one line.
pub(crate) fn read_scheme_file(
    what: &str,
    path: &std::path::Path,
) -> CliResult<std::sync::Arc<SchemeFile>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::usage(anyhow!("{what} {}: cannot read: {e}", path.display())))?;
    SchemeFile::parse_shared(&text)
        .map_err(|e| CliError::usage(anyhow!("{what} {}: {e}", path.display())))
}

/// The help text of `--scheme`: every known scheme (from
/// [`SchemeKind::ALL`], so that a new scheme needs no edit here).
pub(crate) fn scheme_help() -> String {
    format!("Scheme: {}", SchemeKind::names_or())
}

/// The validated configuration, in f64 and (when requested and possible) exactly.
pub(crate) struct Resolved {
    /// The configuration, through the scheme abstraction.
    pub scheme: Box<dyn Scheme>,
    /// The exact configuration (`--exact`).
    pub exact: Option<LocalScheme<Rational>>,
    /// The input as given, echoed by `analyze --json`.
    pub input: subdiv_lab::spectral::json::AnalysisInput,
}

/// One number from the command line, exactly and as the nearest f64.
///
/// The nearest f64 may be infinite or 0 for a finite non-zero number
/// (`1e400/3`, `1e-400`): see [`float_problem`].
fn parse_number(what: &str, text: &str) -> CliResult<(Rational, f64)> {
    let t = text.trim();
    match parse_exact(t) {
        Some(q) => {
            let x = t.parse::<f64>().unwrap_or_else(|_| q.to_f64());
            Ok((q, x))
        }
        None => match t.parse::<f64>() {
            Ok(x) => Err(CliError::usage(anyhow!(
                "{what} must be finite and > 0, got {x}"
            ))),
            Err(_) => Err(CliError::usage(anyhow!("{what}: {t:?} is not a number"))),
        },
    }
}

/// Why the nearest f64 `x` of the exact value `q` does not stand for it on
/// the float path: it overflows, or it rounds to 0 where `q` is not, or (for
/// a value in the unit range, `unit_range`) to 1 where `q` is not: 0 and 1
/// are the ends of the ratio and shape-parameter ranges, where a rounded
/// value changes the configuration. `None` when `x` is usable.
fn float_problem(q: &Rational, x: f64, unit_range: bool) -> Option<&'static str> {
    let zero = Rational::from_integer(0.into());
    let one = Rational::from_integer(1.into());
    if !x.is_finite() {
        Some("overflows to infinity")
    } else if x == 0.0 && *q != zero {
        Some("rounds to 0")
    } else if unit_range && x == 1.0 && *q != one {
        Some("rounds to 1")
    } else {
        None
    }
}

/// [`float_problem`] as a usage error naming the value.
fn check_float(
    what: &str,
    text: &str,
    (q, x): (&Rational, f64),
    unit_range: bool,
    hint: &str,
) -> CliResult {
    match float_problem(q, x, unit_range) {
        Some(why) => Err(CliError::usage(anyhow!(
            "{what} = {} is not representable in f64: it {why}{hint}",
            text.trim()
        ))),
        None => Ok(()),
    }
}

/// The shape parameter `c`, exactly and as the nearest f64 (range checked by
/// the library; a value the f64 cannot represent is an error naming it).
pub(crate) fn parse_c(text: &str) -> CliResult<(Rational, f64)> {
    let t = text.trim();
    let q = parse_exact(t)
        .ok_or_else(|| CliError::usage(anyhow!("--c: {t:?} is not a finite number in [0, 1]")))?;
    let x = t.parse::<f64>().unwrap_or_else(|_| q.to_f64());
    check_float("--c", t, (&q, x), true, "")?;
    Ok((q, x))
}

fn split_list(flag: &str, text: &str) -> CliResult<Vec<String>> {
    let items: Vec<String> = text.split(',').map(|s| s.trim().to_owned()).collect();
    if items.iter().any(|s| s.is_empty()) {
        return Err(CliError::usage(anyhow!("{flag}: empty entry in {text:?}")));
    }
    Ok(items)
}

fn lib_err(e: subdiv_lab::Error) -> CliError {
    CliError::usage(e)
}

impl SchemeArgs {
    /// Validates the flags; `exact` also builds the exact-rational configuration.
    pub fn resolve(&self, exact: bool) -> CliResult<Resolved> {
        if let Some(path) = &self.scheme_file {
            return self.resolve_file(path);
        }
        let given = [self.knots.is_some(), self.ratios.is_some(), self.uniform]
            .iter()
            .filter(|b| **b)
            .count();
        if given > 1 {
            return Err(CliError::usage(anyhow!(
                "--knots, --ratios and --uniform are mutually exclusive; give one"
            )));
        }
        // The shared rules (subdiv_lab::schemes::choice), with the flag named.
        let choice = Choice {
            name: &self.scheme,
            knots: self.knots.is_some() || self.ratios.is_some(),
            c: self.c.is_some(),
        };
        let kind = validate(&choice).map_err(|e| {
            CliError::usage(match e {
                ChoiceError::Unknown(_) => anyhow!("--scheme: {e}"),
                ChoiceError::TakesNoKnots(_) => anyhow!("--knots/--ratios: {e}"),
                ChoiceError::TakesNoC(_) | ChoiceError::NeedsC(_) => anyhow!("--c: {e}"),
            })
        })?;
        let mut knots_given: Option<Vec<[f64; 2]>> = None;
        let mut ratios_given: Option<Vec<f64>> = None;
        // Parse ratios in both arithmetics.
        let (rq, rf): (Option<EdgeRatios<Rational>>, Option<EdgeRatios<f64>>) = if let Some(text) =
            &self.knots
        {
            let mut pq = Vec::new();
            let mut pf = Vec::new();
            let mut qq = Vec::new();
            let mut qf = Vec::new();
            for (i, item) in split_list("--knots", text)?.iter().enumerate() {
                let (p, q) = item.split_once(':').ok_or_else(|| {
                    CliError::usage(anyhow!("--knots entry {i} is {item:?}; expected p{i}:q{i}"))
                })?;
                let (a, b) = parse_number(&format!("knot interval p_{i}"), p)?;
                let (c, d) = parse_number(&format!("knot interval q_{i}"), q)?;
                pq.push(a);
                pf.push(b);
                qq.push(c);
                qf.push(d);
            }
            self.check_count("--knots", pf.len())?;
            knots_given = Some(pf.iter().zip(&qf).map(|(p, q)| [*p, *q]).collect());
            let kq = CornerIntervals::new(pq.clone(), qq.clone()).map_err(lib_err)?;
            if exact {
                // The exact path: ratios computed exactly from the exact
                // intervals (any size), the float analysis uses their nearest
                // f64 values (an error names a ratio below the f64 range).
                let rq = kq.ratios().map_err(lib_err)?;
                let rf = rq.to_f64_checked().map_err(lib_err)?;
                (Some(rq), Some(rf))
            } else {
                let texts = split_list("--knots", text)?;
                for (i, item) in texts.iter().enumerate() {
                    let (p, q) = item.split_once(':').unwrap_or((item, item));
                    let hint = "; --exact computes the ratios from the exact intervals";
                    check_float(
                        &format!("knot interval p_{i}"),
                        p,
                        (&pq[i], pf[i]),
                        false,
                        hint,
                    )?;
                    check_float(
                        &format!("knot interval q_{i}"),
                        q,
                        (&qq[i], qf[i]),
                        false,
                        hint,
                    )?;
                }
                let kf = CornerIntervals::new(pf, qf).map_err(lib_err)?;
                (
                    Some(kq.ratios().map_err(lib_err)?),
                    Some(kf.ratios().map_err(lib_err)?),
                )
            }
        } else if let Some(text) = &self.ratios {
            let mut vq = Vec::new();
            let mut vf = Vec::new();
            for (i, item) in split_list("--ratios", text)?.iter().enumerate() {
                let (a, b) = match parse_number(&format!("edge ratio r_{i}"), item) {
                    Ok(v) => v,
                    Err(_) => {
                        return Err(CliError::usage(anyhow!(
                            "edge ratio r_{i}: {item:?} is not a number in (0, 1)"
                        )))
                    }
                };
                check_float(&format!("edge ratio r_{i}"), item, (&a, b), true, "")?;
                vq.push(a);
                vf.push(b);
            }
            self.check_count("--ratios", vf.len())?;
            ratios_given = Some(vf.clone());
            let rf = EdgeRatios::new(vf).map_err(lib_err)?;
            let rq = EdgeRatios::new(vq).map_err(lib_err)?;
            (Some(rq), Some(rf))
        } else {
            if kind.takes_knots() && !self.uniform {
                return Err(CliError::usage(anyhow!(
                    "--scheme {kind} needs one of --knots, --ratios or --uniform"
                )));
            }
            (None, None)
        };
        let valence = match (&rf, self.valence) {
            (Some(r), _) => r.valence(),
            (None, Some(n)) => n,
            (None, None) => {
                return Err(CliError::usage(anyhow!(
                    "--valence is required with --scheme {kind}"
                )))
            }
        };
        let (cq, cf) = match &self.c {
            Some(text) => {
                let (q, x) = parse_c(text)?;
                (Some(q), Some(x))
            }
            None => (None, None),
        };
        let scheme: Box<dyn Scheme> =
            Box::new(LocalScheme::from_kind_with_c(kind, valence, rf, cf).map_err(lib_err)?);
        let exact = if exact {
            // The f64 configuration was accepted, so a failure here means the
            // scheme has no exact (rational) configuration.
            Some(
                LocalScheme::from_kind_with_c(kind, valence, rq, cq).map_err(|e| {
                    CliError::usage(anyhow!("--exact is not available for --scheme {kind}: {e}"))
                })?,
            )
        } else {
            None
        };
        Ok(Resolved {
            scheme,
            exact,
            input: subdiv_lab::spectral::json::AnalysisInput {
                scheme: kind.to_string(),
                valence,
                knots: knots_given,
                ratios: ratios_given,
                uniform: self.uniform,
                c: cf,
            },
        })
    }

    /// `--scheme-file`: the file's configuration at `--valence` (no exact
    /// built-in configuration: the exact matrix is the scheme's own).
    fn resolve_file(&self, path: &std::path::Path) -> CliResult<Resolved> {
        let file = read_scheme_file("--scheme-file", path)?;
        let valence = self
            .valence
            .ok_or_else(|| CliError::usage(anyhow!("--valence is required with --scheme-file")))?;
        let scheme = file
            .at(valence)
            .map_err(|e| CliError::usage(anyhow!("--scheme-file {}: {e}", path.display())))?;
        Ok(Resolved {
            input: subdiv_lab::spectral::json::AnalysisInput {
                scheme: file.name().to_owned(),
                valence,
                ..Default::default()
            },
            scheme: Box::new(scheme),
            exact: None,
        })
    }

    fn check_count(&self, flag: &str, got: usize) -> CliResult {
        match self.valence {
            Some(n) if n != got => Err(CliError::usage(anyhow!(
                "{flag} has {got} entries but --valence is {n}"
            ))),
            _ => Ok(()),
        }
    }
}
