//! `matrix` and `analyze`: one configuration, validated as the CLI's scheme
//! flags are, estimated and refused above the limits as the CLI does.

use crate::{guard, lib_err, limit, runtime_err, scheme_choice, value_err, Int, PY};
use numpy::PyArray2;
use pyo3::prelude::*;
use subdiv_lab::budget::TIME_LIMIT_SECONDS;
use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::spectral::json::AnalysisInput;

/// The scheme arguments of `matrix` / `analyze`, validated as the CLI does.
struct Resolved {
    scheme: Box<dyn subdiv_lab::Scheme>,
    input: AnalysisInput,
}

fn resolve(
    scheme: &str,
    valence: Option<Int>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
) -> PyResult<Resolved> {
    let given = [knots.is_some(), ratios.is_some(), uniform]
        .iter()
        .filter(|b| **b)
        .count();
    if given > 1 {
        return Err(value_err(
            "knots, ratios and uniform are mutually exclusive; give one",
        ));
    }
    let kind = scheme_choice(scheme, knots.is_some() || ratios.is_some(), c.is_some())?;
    let valence = valence.map(|v| v.usize("valence")).transpose()?;
    let count = |what: &str, got: usize| match valence {
        Some(n) if n != got => Err(value_err(format!(
            "{what} has {got} entries but valence is {n}"
        ))),
        _ => Ok(()),
    };
    let rf = if let Some(k) = &knots {
        count("knots", k.len())?;
        let (p, q): (Vec<f64>, Vec<f64>) = k.iter().copied().unzip();
        Some(
            CornerIntervals::new(p, q)
                .map_err(lib_err)?
                .ratios()
                .map_err(lib_err)?,
        )
    } else if let Some(r) = &ratios {
        count("ratios", r.len())?;
        Some(EdgeRatios::new(r.clone()).map_err(lib_err)?)
    } else {
        if kind.takes_knots() && !uniform {
            return Err(value_err(format!(
                "scheme {kind} needs one of knots, ratios or uniform=True"
            )));
        }
        None
    };
    let n = match (&rf, valence) {
        (Some(r), _) => r.valence(),
        (None, Some(n)) => n,
        (None, None) => return Err(value_err(format!("valence is required with scheme {kind}"))),
    };
    let s: Box<dyn subdiv_lab::schemes::Scheme> = Box::new(
        subdiv_lab::schemes::LocalScheme::from_kind_with_c(kind, n, rf, c).map_err(lib_err)?,
    );
    Ok(Resolved {
        scheme: s,
        input: AnalysisInput {
            scheme: kind.to_string(),
            valence: n,
            knots: knots.map(|k| k.into_iter().map(|(p, q)| [p, q]).collect()),
            ratios,
            uniform,
            c,
        },
    })
}

/// `matrix`: (matrix, row labels) of the local subdivision matrix or its face block.
#[pyfunction]
#[pyo3(signature = (scheme, valence=None, knots=None, ratios=None, uniform=false, c=None, block="full", force=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn matrix<'py>(
    py: Python<'py>,
    scheme: &str,
    valence: Option<Int>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
    block: &str,
    force: bool,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Vec<String>)> {
    guard("matrix", || {
        let face = match block {
            "full" => false,
            "face" => true,
            other => {
                return Err(value_err(format!(
                    "block must be \"full\" or \"face\", got {other:?}"
                )))
            }
        };
        let r = resolve(scheme, valence, knots, ratios, uniform, c)?;
        let n = r.scheme.valence();
        let estimate = subdiv_lab::budget::matrix(&r.scheme.cost_model(), n, face, false);
        limit(
            "matrix",
            &format!("valence {n}"),
            &estimate,
            TIME_LIMIT_SECONDS,
            force,
        )?;
        if face
            && r.scheme.spectral_structure() != subdiv_lab::schemes::SpectralStructure::FaceBlock
        {
            return Err(lib_err(subdiv_lab::Error::NotApplicable {
                scheme: r.scheme.name().to_owned(),
                operation: "the face block (a Doo-Sabin-family notion)",
            }));
        }
        let scheme = r.scheme;
        let lm = py.detach(move || scheme.local_matrix()).map_err(lib_err)?;
        let m = lm.matrix();
        let k = if face {
            lm.valence().min(m.nrows())
        } else {
            m.nrows()
        };
        let labels: Vec<String> = lm.rows().iter().take(k).map(ToString::to_string).collect();
        let rows: Vec<Vec<f64>> = m
            .row_iter()
            .take(k)
            .map(|row| row.iter().take(k).copied().collect())
            .collect();
        let a = PyArray2::from_vec2(py, &rows).map_err(runtime_err)?;
        Ok((a, labels))
    })
}

/// `analyze`: the JSON text of `subdiv-lab analyze --json`.
#[pyfunction]
#[pyo3(signature = (scheme, valence=None, knots=None, ratios=None, uniform=false, c=None, path="full", levels=Int(60), seed=Int(0x5EED), force=false, charmap="ring"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_json(
    py: Python<'_>,
    scheme: &str,
    valence: Option<Int>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
    path: &str,
    levels: Int,
    seed: Int,
    force: bool,
    charmap: &str,
) -> PyResult<String> {
    guard("analyze", || {
        let (levels, seed, path) = analyze_options(levels, seed, path)?;
        let method = charmap_method(charmap)?;
        let r = resolve(scheme, valence, knots, ratios, uniform, c)?;
        analyze_resolved(py, r, path, levels, seed, force, method)
    })
}

/// `analyze` of a scheme file's configuration at `valence` (`text`: the
/// file's contents, read by the Python wrapper; errors name the key and the
/// valence, as the CLI's `--scheme-file`).
#[pyfunction]
#[pyo3(signature = (text, valence, path="full", levels=Int(60), seed=Int(0x5EED), force=false, charmap="ring"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_file_json(
    py: Python<'_>,
    text: &str,
    valence: Int,
    path: &str,
    levels: Int,
    seed: Int,
    force: bool,
    charmap: &str,
) -> PyResult<String> {
    guard("analyze", || {
        let (levels, seed, path) = analyze_options(levels, seed, path)?;
        let method = charmap_method(charmap)?;
        let n = valence.usize("valence")?;
        let file = subdiv_lab::schemes::user::SchemeFile::parse_shared(text)
            .map_err(|e| value_err(format!("scheme_file: {e}")))?;
        let scheme = file
            .at(n)
            .map_err(|e| value_err(format!("scheme_file: {e}")))?;
        let r = Resolved {
            input: AnalysisInput {
                scheme: file.name().to_owned(),
                valence: n,
                ..Default::default()
            },
            scheme: Box::new(scheme),
        };
        analyze_resolved(py, r, path, levels, seed, force, method)
    })
}

/// The characteristic-map certificate called `name` (`ring` or `generic`).
fn charmap_method(name: &str) -> PyResult<subdiv_lab::charmap::Method> {
    subdiv_lab::charmap::Method::from_name(name).ok_or_else(|| {
        value_err(format!(
            "charmap must be \"ring\" or \"generic\", got {name:?}"
        ))
    })
}

/// The validated `levels`, `seed` and spectrum path of `analyze`.
fn analyze_options(
    levels: Int,
    seed: Int,
    path: &str,
) -> PyResult<(usize, u64, subdiv_lab::spectral::SpectrumPath)> {
    use subdiv_lab::spectral::SpectrumPath;
    let levels = levels.usize("levels")?;
    subdiv_lab::contraction::check_levels(levels, PY).map_err(value_err)?;
    let seed = seed.u64("seed")?;
    let path = match path {
        "full" => SpectrumPath::Full,
        "structured" => SpectrumPath::Structured,
        other => {
            return Err(value_err(format!(
                "path must be \"full\" or \"structured\", got {other:?}"
            )))
        }
    };
    Ok((levels, seed, path))
}

/// The analysis of a resolved configuration, estimated and refused above the
/// limits first, as JSON text.
fn analyze_resolved(
    py: Python<'_>,
    r: Resolved,
    path: subdiv_lab::spectral::SpectrumPath,
    levels: usize,
    seed: u64,
    force: bool,
    method: subdiv_lab::charmap::Method,
) -> PyResult<String> {
    use subdiv_lab::spectral::{AnalyzeOptions, SpectrumPath};
    let n = r.scheme.valence();
    let estimate = subdiv_lab::budget::analyze(
        &r.scheme.cost_model(),
        n,
        matches!(path, SpectrumPath::Structured),
    );
    limit(
        "analyze",
        &format!("valence {n}"),
        &estimate,
        TIME_LIMIT_SECONDS,
        force,
    )?;
    if method == subdiv_lab::charmap::Method::Generic {
        limit(
            "analyze with charmap=\"generic\"",
            &format!("valence {n}"),
            &subdiv_lab::charmap::generic::estimate(&*r.scheme),
            TIME_LIMIT_SECONDS,
            force,
        )?;
    }
    let options = AnalyzeOptions {
        path,
        measure: subdiv_lab::contraction::MeasureOptions {
            levels,
            seed,
            ..Default::default()
        },
    };
    let Resolved { scheme, input } = r;
    let scheme = std::sync::Arc::<dyn subdiv_lab::Scheme>::from(scheme);
    let (result, charmap) = py.detach(move || -> PyResult<_> {
        let result = subdiv_lab::spectral::analyze(&*scheme, &options).map_err(lib_err)?;
        let charmap = subdiv_lab::charmap::certify(method, &*scheme, &result.charmap_subdominant());
        Ok((result, charmap))
    })?;
    let v = subdiv_lab::spectral::json::analysis_json(&result, charmap.json(), &input);
    serde_json::to_string(&v).map_err(runtime_err)
}

/// `analyze` of a local matrix the user computed (`matrix`: any array-like;
/// validated by [`crate::user::local_matrix`]), named `name`.
#[pyfunction]
#[pyo3(signature = (matrix, labels=None, valence=None, name="matrix", path="full", levels=Int(60), seed=Int(0x5EED), force=false, charmap="ring"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_matrix_json(
    py: Python<'_>,
    matrix: &Bound<'_, PyAny>,
    labels: Option<Vec<String>>,
    valence: Option<Int>,
    name: &str,
    path: &str,
    levels: Int,
    seed: Int,
    force: bool,
    charmap: &str,
) -> PyResult<String> {
    guard("analyze", || {
        let (levels, seed, path) = analyze_options(levels, seed, path)?;
        let method = charmap_method(charmap)?;
        let valence = valence.map(|v| v.usize("valence")).transpose()?;
        if name.is_empty() {
            return Err(value_err("name must not be empty"));
        }
        let lm = crate::user::local_matrix(py, "matrix", name, matrix, labels, valence)?;
        let n = lm.valence();
        let r = Resolved {
            input: AnalysisInput {
                scheme: name.to_owned(),
                valence: n,
                ..Default::default()
            },
            scheme: Box::new(crate::user::matrix_scheme(name, lm)),
        };
        analyze_resolved(py, r, path, levels, seed, force, method)
    })
}

/// `analyze` of a duck-typed Python scheme at `valence`: its
/// `matrix(valence) -> (S, labels)` ([`crate::user::call_matrix`]; an
/// exception its code raises propagates as it is).
#[pyfunction]
#[pyo3(signature = (scheme, valence, path="full", levels=Int(60), seed=Int(0x5EED), force=false, charmap="ring"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_object_json(
    py: Python<'_>,
    scheme: &Bound<'_, PyAny>,
    valence: Int,
    path: &str,
    levels: Int,
    seed: Int,
    force: bool,
    charmap: &str,
) -> PyResult<String> {
    guard("analyze", || {
        let (levels, seed, path) = analyze_options(levels, seed, path)?;
        let method = charmap_method(charmap)?;
        let n = valence.usize("valence")?;
        let name = crate::user::scheme_name(scheme)?;
        let mut s = crate::user::call_matrix(py, scheme, &name, n)?;
        if method == subdiv_lab::charmap::Method::Generic {
            s = crate::user::with_regular(py, scheme, s)?;
        }
        let r = Resolved {
            input: AnalysisInput {
                scheme: name,
                valence: n,
                ..Default::default()
            },
            scheme: Box::new(s),
        };
        analyze_resolved(py, r, path, levels, seed, force, method)
    })
}
