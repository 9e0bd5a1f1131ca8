//! `sweep` and `merge`: the rows of a sweep, computed or merged from shard
//! files, as typed columns (the `pyarrow.Table` of the Python side). The
//! command-line tool streams such rows to a file; here they are held in
//! memory, which the estimate counts.

use crate::{guard, lib_err, runtime_err, value_err, Int, SpecOrigin};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use subdiv_lab::budget::{
    held_in_memory, Estimate, SWEEP_TIME_LIMIT_SECONDS, TABLE_BYTES_PER_CELL,
};
use subdiv_lab::schemes::user::SchemeFile;
use subdiv_lab::sweep::output::{self, files, shards, Row};
use subdiv_lab::sweep::{Layout, Plan, SchemeFactory, Shard, SpectralEvaluator, SweepSpec};
use subdiv_lab::table::Column;

/// A TOML sweep spec from its JSON form (the Python dict).
#[pyfunction]
pub(crate) fn spec_json_to_toml(json: &str) -> PyResult<String> {
    guard("spec_json_to_toml", || {
        let v: serde_json::Value =
            serde_json::from_str(json).map_err(|e| value_err(format!("spec: {e}")))?;
        toml::to_string(&v).map_err(|e| value_err(format!("spec: {e}")))
    })
}

/// A spec's text parsed, its errors phrased for where it came from.
fn parse_spec(text: &str, origin: &SpecOrigin) -> PyResult<SweepSpec> {
    SweepSpec::from_toml(text).map_err(|e| origin.sweep_error(e))
}

/// `(column names, {name: column})` of `rows` (the layout's columns, as
/// [`Layout::table`] types them): `id` (uint64), `valence` (uint32), each
/// coordinate and result column as `(values, valid)` (numpy float64 with NaN
/// where not valid, or a list of str with `""`, and a numpy bool mask) and
/// `error` (list of str, empty when the row succeeded).
fn table<'py>(
    py: Python<'py>,
    layout: &Layout,
    rows: Vec<Row>,
) -> PyResult<(Vec<String>, Bound<'py, PyDict>)> {
    let table = layout.table(rows).map_err(runtime_err)?;
    let names = table.names().to_vec();
    let out = PyDict::new(py);
    for (name, column) in table.into_columns() {
        match column {
            Column::U64(v) => out.set_item(name, PyArray1::from_vec(py, v))?,
            Column::U32(v) => out.set_item(name, PyArray1::from_vec(py, v))?,
            Column::Str(v) if name == "error" => {
                let v: Vec<String> = v.into_iter().map(Option::unwrap_or_default).collect();
                out.set_item(name, v)?;
            }
            Column::Str(v) => {
                let mask: Vec<bool> = v.iter().map(Option::is_some).collect();
                let v: Vec<String> = v.into_iter().map(Option::unwrap_or_default).collect();
                out.set_item(name, (v, PyArray1::from_vec(py, mask)))?;
            }
            Column::F64(v) => {
                let mask: Vec<bool> = v.iter().map(Option::is_some).collect();
                let v: Vec<f64> = v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect();
                out.set_item(
                    name,
                    (PyArray1::from_vec(py, v), PyArray1::from_vec(py, mask)),
                )?;
            }
            Column::Bool(v) => {
                let mask: Vec<bool> = v.iter().map(Option::is_some).collect();
                let v: Vec<bool> = v.into_iter().map(Option::unwrap_or_default).collect();
                out.set_item(
                    name,
                    (PyArray1::from_vec(py, v), PyArray1::from_vec(py, mask)),
                )?;
            }
        }
    }
    Ok((names, out))
}

/// Where an exception raised by a Python scheme object is kept.
type Raised = std::sync::Arc<std::sync::Mutex<Option<PyErr>>>;

/// A shard `(I, N)` as Python gave it (default: all configurations).
fn shard_of(shard: Option<(Int, Int)>) -> PyResult<Shard> {
    let Some((i, k)) = shard else {
        return Ok(Shard::ALL);
    };
    let bad = || lib_err(subdiv_lab::sweep::SweepError::BadShard(format!("{i}/{k}")));
    let (i, k) = (
        i.u64("shard").map_err(|_| bad())?,
        k.u64("shard").map_err(|_| bad())?,
    );
    Shard::new(i, k).map_err(lib_err)
}

/// The plan of a spec, with `scheme_file` (a scheme file's text) or
/// `scheme` (a duck-typed Python object, [`crate::user::python_factory`],
/// whose exceptions go to `raised`) in place of the spec's scheme.
fn plan_of(
    py: Python<'_>,
    spec: SweepSpec,
    origin: &SpecOrigin,
    scheme_file: Option<String>,
    scheme: Option<&Bound<'_, PyAny>>,
    raised: &Raised,
) -> PyResult<Plan> {
    let factory = match (scheme_file, scheme) {
        (Some(_), Some(_)) => {
            return Err(value_err(
                "scheme_file and scheme are mutually exclusive; give one",
            ))
        }
        (Some(text), None) => Some(SchemeFactory::from_file(
            SchemeFile::parse_shared(&text).map_err(|e| value_err(format!("scheme_file: {e}")))?,
        )),
        (None, Some(obj)) => Some(crate::user::python_factory(py, obj, raised.clone())?),
        (None, None) => None,
    };
    match factory {
        Some(f) => Plan::with_scheme(spec, f).map_err(|e| origin.sweep_error(e)),
        None => Ok(Plan::new(spec)),
    }
}

/// `sweep`: the rows of a sweep (all, one shard, or its first `limit` ids)
/// as columns; with `out`, run into that file instead ([`files::run_plan`]:
/// a CSV, or a Parquet dataset directory NAME.parquet, resumable as the
/// command's) and return its summary (JSON text).
#[pyfunction]
/// With `scheme_file` (a scheme file's text) or `scheme` (a duck-typed
/// Python object, [`crate::user::python_factory`]) the spec's valences are
/// swept with that scheme through the same engine ([`Plan::with_scheme`]);
/// an exception raised by the object's code is re-raised as it is.
#[pyo3(signature = (spec_toml, spec_path=None, from_dict=false, threads=None, shard=None, limit=None, force=false, scheme_file=None, scheme=None, out=None, resume=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn sweep<'py>(
    py: Python<'py>,
    spec_toml: &str,
    spec_path: Option<String>,
    from_dict: bool,
    threads: Option<Int>,
    shard: Option<(Int, Int)>,
    limit: Option<Int>,
    force: bool,
    scheme_file: Option<String>,
    scheme: Option<Bound<'py, PyAny>>,
    out: Option<std::path::PathBuf>,
    resume: bool,
) -> PyResult<Bound<'py, PyAny>> {
    guard("sweep", || {
        let origin = SpecOrigin::new(spec_path, from_dict);
        let spec = parse_spec(spec_toml, &origin)?;
        let threads = crate::threads(threads)?;
        let shard = shard_of(shard)?;
        let limit_rows = limit.map(|l| l.u64("limit")).transpose()?;
        let raised = Raised::default();
        let plan = plan_of(py, spec, &origin, scheme_file, scheme.as_ref(), &raised)?;
        let layout = Layout::new(&plan);
        let count = shard.len(plan.total()).min(limit_rows.unwrap_or(u64::MAX));
        // The CLI's sweep estimate of these rows (and in memory, the rows held).
        let mut estimate = subdiv_lab::sweep::sweep_rows(&plan, count, shard.count, threads);
        if out.is_none() {
            estimate = held_in_memory(
                estimate,
                count,
                layout.column_names().len(),
                TABLE_BYTES_PER_CELL,
            );
        }
        let subject = match &origin {
            SpecOrigin::Path(p) => p.clone(),
            _ => format!("spec {:?}", plan.spec().name),
        };
        crate::limit(
            "sweep",
            &subject,
            &estimate,
            SWEEP_TIME_LIMIT_SECONDS,
            force,
        )?;
        let reraise = || raised.lock().ok().and_then(|mut slot| slot.take());
        if let Some(out) = out {
            let options = files::RunOptions {
                shard,
                limit: limit_rows,
                resume,
                threads,
                progress: None,
            };
            let report = py.detach(|| files::run_plan(&plan, files::Sink::for_path(&out), options));
            if let Some(e) = reraise() {
                return Err(e);
            }
            let report = report.map_err(|e| match e {
                subdiv_lab::sweep::SweepError::Exists(p) => value_err(format!(
                    "{} exists; pass resume=True to continue it, or remove it",
                    p.display()
                )),
                e => lib_err(e),
            })?;
            let json = serde_json::to_string(&report.summary).map_err(runtime_err)?;
            return Ok(pyo3::types::PyString::new(py, &json).into_any());
        }
        if resume {
            return Err(value_err(
                "resume=True needs out=FILE (a CSV or NAME.parquet)",
            ));
        }
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let pool = crate::pool(threads)?;
        let rows: Vec<Row> = py.detach(|| {
            pool.install(|| {
                (0..count)
                    .into_par_iter()
                    .map(|j| layout.row(&plan, &eval, shard.id(j)))
                    .collect()
            })
        });
        if let Some(e) = reraise() {
            return Err(e);
        }
        Ok(table(py, &layout, rows)?.into_pyobject(py)?.into_any())
    })
}

/// `merge`: the shards of one sweep (files written by `sweep --shard I/N`),
/// every row verified as `subdiv-lab merge` verifies it, as the columns of
/// [`sweep`]; with the merged summary (JSON text).
#[pyfunction]
#[pyo3(signature = (inputs, spec_toml, spec_path=None, from_dict=false, force=false))]
pub(crate) fn merge<'py>(
    py: Python<'py>,
    inputs: Vec<String>,
    spec_toml: &str,
    spec_path: Option<String>,
    from_dict: bool,
    force: bool,
) -> PyResult<(Vec<String>, Bound<'py, PyDict>, String)> {
    guard("merge", || {
        let origin = SpecOrigin::new(spec_path, from_dict);
        let spec = parse_spec(spec_toml, &origin)?;
        if inputs.is_empty() {
            return Err(value_err("inputs: give at least one shard file"));
        }
        let plan = Plan::new(spec);
        let layout = Layout::new(&plan);
        let total = plan.total();
        let estimate = held_in_memory(
            Estimate {
                bytes: 0.0,
                seconds: 0.0,
                what: format!("merging {total} configurations"),
            },
            total,
            layout.column_names().len(),
            TABLE_BYTES_PER_CELL,
        );
        crate::limit(
            "merge",
            &format!("{} shards", inputs.len()),
            &estimate,
            SWEEP_TIME_LIMIT_SECONDS,
            force,
        )?;
        let paths: Vec<std::path::PathBuf> = inputs.iter().map(Into::into).collect();
        let shards = files::merge_inputs(&paths).map_err(lib_err)?;
        let spec_name = match &origin {
            SpecOrigin::Path(p) => p.clone(),
            _ => "the spec".to_owned(),
        };
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let (text, summary) = py.detach(|| -> PyResult<(Vec<u8>, String)> {
            let prepared = shards::prepare(&plan, &layout, &spec_name, shards).map_err(lib_err)?;
            let mut text = Vec::new();
            let summary = prepared
                .run(&plan, &layout, &eval, &mut text, output::fresh_salt())
                .map_err(lib_err)?;
            let json = serde_json::to_string(&summary).map_err(runtime_err)?;
            Ok((text, json))
        })?;
        let text = String::from_utf8(text).map_err(runtime_err)?;
        let rows = text
            .lines()
            .map(|l| layout.parse(l))
            .collect::<Result<Vec<Row>, String>>()
            .map_err(runtime_err)?;
        let (names, cols) = table(py, &layout, rows)?;
        Ok((names, cols, summary))
    })
}
