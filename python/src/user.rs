//! Schemes a Python user computed: a local matrix given as an array (one
//! validator, [`local_matrix`]), and a duck-typed object with
//! `matrix(valence) -> (S, labels)` and `name`, as a
//! [`SchemeFactory`] for the spec sweep ([`python_factory`]). Exceptions the
//! user's code raises are kept and re-raised as they are.

use crate::value_err;
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::sync::{Arc, Mutex};
use subdiv_lab::schemes::{Assembler, LocalMatrix, PointLabel, Role};
use subdiv_lab::sweep::SchemeFactory;

/// A scheme whose one configuration is a given local matrix, with the same
/// scheme's configuration at the regular valence when the user's object
/// gave one ([`with_regular`]: the generic certificate reads the regular
/// rules from it, math doc section 20).
#[derive(Clone, Debug)]
pub(crate) struct MatrixScheme {
    name: String,
    lm: LocalMatrix<f64>,
    regular: Option<Box<MatrixScheme>>,
}

impl subdiv_lab::Scheme for MatrixScheme {
    fn name(&self) -> &str {
        &self.name
    }

    fn valence(&self) -> usize {
        self.lm.valence()
    }

    fn local_matrix(&self) -> subdiv_lab::Result<LocalMatrix<f64>> {
        Ok(self.lm.clone())
    }

    fn regular_configuration(&self) -> Option<subdiv_lab::Result<Box<dyn subdiv_lab::Scheme>>> {
        self.regular
            .as_ref()
            .map(|r| Ok(r.clone() as Box<dyn subdiv_lab::Scheme>))
    }
}

/// The regular valence of the Python scheme object `obj` whose configuration
/// `s` was computed: its `regular_valence` attribute (4 or 6) when it has
/// one, else read from `s`'s labels: second-ring points (`g`) make it a
/// triangle scheme (6), face neighbours (`f`) without them a quad scheme (4);
/// `None` when the labels tell neither.
fn regular_valence(obj: &Bound<'_, PyAny>, s: &MatrixScheme) -> PyResult<Option<usize>> {
    if let Ok(v) = obj.getattr("regular_valence") {
        return match v.extract::<usize>() {
            Ok(n @ (4 | 6)) => Ok(Some(n)),
            _ => Err(value_err(format!(
                "scheme.regular_valence must be 4 (quad schemes) or 6 (triangle schemes), got {}",
                v.repr().map(|r| r.to_string()).unwrap_or_default()
            ))),
        };
    }
    let has = |role: Role| s.lm.rows().iter().any(|l| l.role == role);
    Ok(if has(Role::SecondRing) {
        Some(6)
    } else if has(Role::FaceNeighbour) {
        Some(4)
    } else {
        None
    })
}

/// `s`, a configuration of the Python scheme object `obj`, with the object's
/// configuration at its regular valence ([`regular_valence`]) attached, so
/// that the generic certificate can read the regular rules.
pub(crate) fn with_regular(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    mut s: MatrixScheme,
) -> PyResult<MatrixScheme> {
    if let Some(n) = regular_valence(obj, &s)? {
        let name = s.name.clone();
        s.regular = Some(Box::new(call_matrix(py, obj, &name, n)?));
    }
    Ok(s)
}

/// A row label as [`PointLabel`] prints it (`v`, `e3`, `f3`, `g3`, `P3`,
/// `E3,1`, `E3,2`, `C3`, `o3`, `X3`).
fn parse_label(text: &str) -> Option<PointLabel> {
    if text == "v" {
        return Some(PointLabel::new(Role::Vertex, 0));
    }
    if let Some(rest) = text.strip_prefix('E') {
        let (i, k) = rest.split_once(',')?;
        let role = match k {
            "1" => Role::EdgeFirst,
            "2" => Role::EdgeSecond,
            _ => return None,
        };
        return Some(PointLabel::new(role, index(i)?));
    }
    let mut chars = text.chars();
    let role = match chars.next()? {
        'e' => Role::EdgeNeighbour,
        'f' => Role::FaceNeighbour,
        'g' => Role::SecondRing,
        'P' => Role::FaceCorner,
        'C' => Role::Corner,
        'o' => Role::PatchOuter,
        'X' => Role::Extended,
        _ => return None,
    };
    Some(PointLabel::new(role, index(chars.as_str())?))
}

fn index(text: &str) -> Option<usize> {
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    text.parse().ok()
}

/// The one validator of a user's local matrix: `matrix` (any array-like,
/// converted with `numpy.asarray(..., dtype=float64)`) must be a non-empty
/// square 2-D array of finite numbers whose rows sum to 1 within
/// `ROW_SUM_TOL`; `labels` (optional) one label per row as the library
/// prints them, no label twice; the valence is `valence`, else the number
/// of `e` labels (vertex-centred) or `P` labels (face-centred), else the
/// number of rows. Errors are `ValueError`s naming the problem (`what`: the
/// argument, e.g. `matrix` or `scheme.matrix(5)`).
pub(crate) fn local_matrix(
    py: Python<'_>,
    what: &str,
    name: &str,
    matrix: &Bound<'_, PyAny>,
    labels: Option<Vec<String>>,
    valence: Option<usize>,
) -> PyResult<LocalMatrix<f64>> {
    let np = py.import("numpy")?;
    let kwargs = pyo3::types::PyDict::new(py);
    kwargs.set_item("dtype", "float64")?;
    let array = np
        .getattr("asarray")?
        .call((matrix,), Some(&kwargs))
        .map_err(|e| value_err(format!("{what}: not an array of numbers: {e}")))?;
    let array = array
        .cast::<PyArrayDyn<f64>>()
        .map_err(|_| value_err(format!("{what}: not an array of numbers")))?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 || shape[0] != shape[1] || shape[0] == 0 {
        return Err(value_err(format!(
            "{what}: must be a non-empty square 2-D array, got shape {shape:?}"
        )));
    }
    // The work is estimated (and refused above the limits) by the caller,
    // from this matrix's size; it holds no more memory than the array given.
    let d = shape[0];
    let ro = array.try_readonly()?;
    let a = ro.as_array();
    let labels: Vec<PointLabel> = match labels {
        None => (0..d).map(|i| PointLabel::new(Role::Extended, i)).collect(),
        Some(l) => {
            if l.len() != d {
                return Err(value_err(format!(
                    "labels: {} labels for {d} rows",
                    l.len()
                )));
            }
            let mut out = Vec::with_capacity(d);
            for (i, t) in l.iter().enumerate() {
                let p = parse_label(t).ok_or_else(|| {
                    value_err(format!(
                        "labels[{i}]: {t:?} is not a point label (v, e<i>, f<i>, g<i>, P<i>, E<i>,1, E<i>,2, C<i>, o<i>, X<i>)"
                    ))
                })?;
                if let Some(j) = out.iter().position(|q| *q == p) {
                    return Err(value_err(format!("labels[{i}]: {t:?} repeats labels[{j}]")));
                }
                out.push(p);
            }
            out
        }
    };
    let count = |role: Role| labels.iter().filter(|p| p.role == role).count();
    let n = match valence {
        Some(n) => n,
        None => match (count(Role::EdgeNeighbour), count(Role::FaceCorner)) {
            (e, _) if e > 0 => e,
            (_, p) if p > 0 => p,
            _ => d,
        },
    };
    if n == 0 {
        return Err(value_err("valence must be at least 1, got 0"));
    }
    let tol = subdiv_lab::schemes::ROW_SUM_TOL;
    let mut asm = Assembler::square(name, n, labels.clone());
    for i in 0..d {
        let mut sum = 0.0;
        for j in 0..d {
            let x = a[[i, j]];
            if !x.is_finite() {
                return Err(value_err(format!(
                    "{what}: entry [{i}, {j}] is {x}, not a finite number"
                )));
            }
            sum += x;
            if x != 0.0 {
                asm.add(i, j, x);
            }
        }
        if (sum - 1.0).abs() > tol {
            return Err(value_err(format!(
                "{what}: row {i} ({}) sums to {sum}, not 1 within ROW_SUM_TOL = {tol:e} (a subdivision rule is affine invariant)",
                labels[i]
            )));
        }
    }
    asm.finish().map_err(crate::lib_err)
}

/// `local_matrix` as a scheme named `name`.
pub(crate) fn matrix_scheme(name: &str, lm: LocalMatrix<f64>) -> MatrixScheme {
    MatrixScheme {
        name: name.to_owned(),
        lm,
        regular: None,
    }
}

/// The configuration of the Python object `obj` at valence `n`: its
/// `matrix(n)` must return `(S, labels)` (labels may be `None`); the
/// exception its code raises comes back as it is.
pub(crate) fn call_matrix(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    n: usize,
) -> PyResult<MatrixScheme> {
    let what = format!("scheme.matrix({n})");
    let out = obj.call_method1("matrix", (n,))?;
    let pair = out
        .cast::<pyo3::types::PyTuple>()
        .ok()
        .filter(|t| t.len() == 2)
        .ok_or_else(|| {
            value_err(format!(
                "{what} must return a pair (S, labels), got {}",
                out.get_type()
                    .name()
                    .map(|s| s.to_string())
                    .unwrap_or_default()
            ))
        })?;
    let labels_obj = pair.get_item(1)?;
    let labels: Option<Vec<String>> =
        if labels_obj.is_none() {
            None
        } else {
            Some(labels_obj.extract().map_err(|_| {
                value_err(format!("{what}: labels must be a list of strings or None"))
            })?)
        };
    let lm = local_matrix(py, &what, name, &pair.get_item(0)?, labels, Some(n))?;
    Ok(matrix_scheme(name, lm))
}

/// The `name` attribute of a duck-typed scheme (a non-empty string).
pub(crate) fn scheme_name(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let name = obj.getattr("name").map_err(|_| {
        value_err(
            "scheme: an object needs a name attribute (a string) and a matrix(valence) method",
        )
    })?;
    let name: String = name
        .extract()
        .map_err(|_| value_err("scheme.name must be a string"))?;
    if name.is_empty() {
        return Err(value_err("scheme.name must not be empty"));
    }
    Ok(name)
}

/// A sweep's factory over the Python object `obj`: each configuration calls
/// `obj.matrix(n)` with the GIL held. The first exception is kept in `raised`
/// (the row records a short error) for the caller to re-raise after the run.
/// The work model is that of a dense matrix whose size grows as between the
/// valences 3 and 4 (two calls made here, whose exceptions propagate).
pub(crate) fn python_factory(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    raised: Arc<Mutex<Option<PyErr>>>,
) -> PyResult<SchemeFactory> {
    let name = scheme_name(obj)?;
    let d3 = call_matrix(py, obj, &name, 3)?.lm.matrix().nrows() as f64;
    let d4 = call_matrix(py, obj, &name, 4)?.lm.matrix().nrows() as f64;
    let per = (d4 - d3).max(0.0);
    let model = subdiv_lab::budget::CostModel::dense(per, (d3 - 3.0 * per).max(1.0));
    let obj: Py<PyAny> = obj.clone().unbind();
    let label = name.clone();
    Ok(SchemeFactory::new(&name, model, move |n| {
        Python::attach(|py| match call_matrix(py, obj.bind(py), &label, n) {
            Ok(s) => Ok(Box::new(s) as Box<dyn subdiv_lab::Scheme>),
            Err(e) => {
                let reason = e.to_string();
                if let Ok(mut slot) = raised.lock() {
                    slot.get_or_insert(e);
                }
                Err(subdiv_lab::Error::InvalidParameter {
                    name: "scheme",
                    value: format!("{label}.matrix({n}): {reason}"),
                    reason: "the Python scheme raised (re-raised after the sweep)",
                })
            }
        })
    })
    .with_identity(format!("python object {name}")))
}
