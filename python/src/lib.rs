//! Python bindings of subdiv-lab (`subdiv_lab._native`): thin wrappers over the
//! library, one per CLI command. The Python package `subdiv_lab` adds the
//! keyword-argument API, numpy/pyarrow conversion and docstrings.
//!
//! Bad input raises `ValueError` with the library's (the CLI's) message, any
//! other failure `RuntimeError`. Heavy work runs with the GIL released.

use std::cell::{Cell as StdCell, RefCell};

use numpy::{PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::scheme::registry::Builtin;
use subdiv_lab::schemes::SchemeKind;
use subdiv_lab::spectral::json::AnalysisInput;
use subdiv_lab::spectral::BATCH;
use subdiv_lab::sweep::eval::CellSink;
use subdiv_lab::sweep::{
    Cell, Configuration, Evaluate, Layout, Plan, Shard, SpectralEvaluator, SweepSpec,
};

/// A library error as a Python exception: input errors are `ValueError`.
fn lib_err(e: impl Into<subdiv_lab::Error>) -> PyErr {
    let e = e.into();
    if e.is_input_error() {
        PyValueError::new_err(e.to_string())
    } else {
        PyRuntimeError::new_err(e.to_string())
    }
}

fn value_err(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// A rayon pool of `threads` workers (`None` or 0: all cores).
fn pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the worker threads: {e}")))
}

/// The scheme flags of `matrix` / `analyze`, validated as the CLI does.
struct Resolved {
    scheme: Box<dyn subdiv_lab::Scheme>,
    input: AnalysisInput,
}

fn resolve(
    scheme: &str,
    valence: Option<usize>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
) -> PyResult<Resolved> {
    let kind: SchemeKind = scheme
        .parse()
        .map_err(|e: subdiv_lab::schemes::UnknownScheme| value_err(e.to_string()))?;
    let given = [knots.is_some(), ratios.is_some(), uniform]
        .iter()
        .filter(|b| **b)
        .count();
    if given > 1 {
        return Err(value_err(
            "knots, ratios and uniform are mutually exclusive; give one",
        ));
    }
    if !kind.takes_knots() && (knots.is_some() || ratios.is_some()) {
        return Err(value_err(format!(
            "scheme {kind} takes no knot intervals (only uniform); use scheme nurds for knots/ratios"
        )));
    }
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
    let s = subdiv_lab::scheme::registry::from_kind(kind, n, rf, c).map_err(lib_err)?;
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
#[pyo3(signature = (scheme, valence=None, knots=None, ratios=None, uniform=false, c=None, block="full"))]
#[allow(clippy::too_many_arguments)]
fn matrix<'py>(
    py: Python<'py>,
    scheme: &str,
    valence: Option<usize>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
    block: &str,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Vec<String>)> {
    let r = resolve(scheme, valence, knots, ratios, uniform, c)?;
    let lm = r.scheme.local_matrix().map_err(lib_err)?;
    let n = lm.valence();
    let (labels, m) = match block {
        "full" => (lm.rows().to_vec(), lm.matrix().clone()),
        "face" => {
            if r.scheme.spectral_structure() != subdiv_lab::scheme::SpectralStructure::FaceBlock {
                return Err(lib_err(subdiv_lab::Error::NotApplicable {
                    scheme: r.scheme.name().to_owned(),
                    operation: "the face block (a Doo-Sabin-family notion)",
                }));
            }
            (
                lm.rows()[..n].to_vec(),
                lm.matrix().view((0, 0), (n, n)).into_owned(),
            )
        }
        other => {
            return Err(value_err(format!(
                "block must be \"full\" or \"face\", got {other:?}"
            )))
        }
    };
    let rows: Vec<Vec<f64>> = m
        .row_iter()
        .map(|row| row.iter().copied().collect())
        .collect();
    let a = PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((a, labels.iter().map(ToString::to_string).collect()))
}

/// `analyze`: the JSON text of `subdiv-lab analyze --json`.
#[pyfunction]
#[pyo3(signature = (scheme, valence=None, knots=None, ratios=None, uniform=false, c=None, path="full", levels=60, seed=0x5EED))]
#[allow(clippy::too_many_arguments)]
fn analyze_json(
    py: Python<'_>,
    scheme: &str,
    valence: Option<usize>,
    knots: Option<Vec<(f64, f64)>>,
    ratios: Option<Vec<f64>>,
    uniform: bool,
    c: Option<f64>,
    path: &str,
    levels: usize,
    seed: u64,
) -> PyResult<String> {
    use subdiv_lab::spectral::{AnalyzeOptions, SpectrumPath};
    if levels == 0 || levels > 10_000 {
        return Err(value_err(format!(
            "levels must be between 1 and 10000, got {levels}"
        )));
    }
    let path = match path {
        "full" => SpectrumPath::Full,
        "structured" => SpectrumPath::Structured,
        other => {
            return Err(value_err(format!(
                "path must be \"full\" or \"structured\", got {other:?}"
            )))
        }
    };
    let r = resolve(scheme, valence, knots, ratios, uniform, c)?;
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
        let charmap = subdiv_lab::charmap::check_classified(&*scheme, &result.subdominant);
        Ok((result, charmap))
    })?;
    let v = subdiv_lab::spectral::json::analysis_json(&result, &charmap, &input);
    serde_json::to_string(&v).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// A TOML sweep spec from its JSON form (the Python dict).
#[pyfunction]
fn spec_json_to_toml(json: &str) -> PyResult<String> {
    let v: serde_json::Value =
        serde_json::from_str(json).map_err(|e| value_err(format!("spec: {e}")))?;
    toml::to_string(&v).map_err(|e| value_err(format!("spec: {e}")))
}

/// Columns of evaluated rows, filled in row order.
struct Columns {
    names: Vec<String>,
    numeric: Vec<bool>,
    nums: Vec<Vec<f64>>,
    valid: Vec<Vec<bool>>,
    texts: Vec<Vec<String>>,
}

impl Columns {
    fn new(names: Vec<String>, numeric: Vec<bool>, rows: usize) -> Self {
        let k = names.len();
        Columns {
            nums: numeric
                .iter()
                .map(|&n| {
                    if n {
                        Vec::with_capacity(rows)
                    } else {
                        Vec::new()
                    }
                })
                .collect(),
            valid: (0..k).map(|_| Vec::with_capacity(rows)).collect(),
            texts: numeric
                .iter()
                .map(|&n| {
                    if n {
                        Vec::new()
                    } else {
                        Vec::with_capacity(rows)
                    }
                })
                .collect(),
            names,
            numeric,
        }
    }

    fn push(&mut self, cells: &[Cell]) {
        for (j, numeric) in self.numeric.iter().enumerate() {
            let cell = cells.get(j).unwrap_or(&Cell::Empty);
            let ok = !matches!(cell, Cell::Empty);
            self.valid[j].push(ok);
            if *numeric {
                self.nums[j].push(match cell {
                    Cell::Num(x) => *x,
                    _ => f64::NAN,
                });
            } else {
                self.texts[j].push(match cell {
                    Cell::Text(t) => t.clone(),
                    Cell::Num(x) => x.to_string(),
                    Cell::Empty => String::new(),
                });
            }
        }
    }

    /// `{name: (values, valid)}`: numpy float64 arrays or lists of str, with a numpy bool mask.
    fn into_dict<'py>(self, py: Python<'py>, out: &Bound<'py, PyDict>) -> PyResult<()> {
        let Columns {
            names,
            numeric,
            nums,
            valid,
            texts,
        } = self;
        for ((((name, numeric), num), ok), text) in names
            .into_iter()
            .zip(numeric)
            .zip(nums)
            .zip(valid)
            .zip(texts)
        {
            let mask = PyArray1::from_vec(py, ok);
            if numeric {
                out.set_item(name, (PyArray1::from_vec(py, num), mask))?;
            } else {
                out.set_item(name, (text, mask))?;
            }
        }
        Ok(())
    }
}

/// A refined mesh: vertex positions `(m, 3)` and faces.
type MeshOut<'py> = (Bound<'py, PyArray2<f64>>, Vec<Vec<usize>>);

/// The distinct texts of one text column; a cell is stored as its index
/// (`u32` code). Sweep text columns take a handful of values (class names,
/// verdict codes, `true`/`false`), so a linear search is the fastest lookup.
/// The second field is the last code given: consecutive rows often share
/// their class, so it is tried first.
#[derive(Default)]
struct Levels(Vec<String>, usize);

impl Levels {
    fn code(&mut self, t: &str) -> u32 {
        if self.0.get(self.1).is_some_and(|l| l == t) {
            return self.1 as u32;
        }
        let i = match self.0.iter().position(|l| l == t) {
            Some(i) => i,
            None => {
                self.0.push(t.to_owned());
                self.0.len() - 1
            }
        };
        self.1 = i;
        i as u32
    }
}

/// Where a result column's cells are kept in a [`ResultColumns`].
#[derive(Clone, Copy)]
enum ColKind {
    /// The `k`-th numeric column.
    Num(usize),
    /// The `t`-th text column (codes into its levels).
    Text(usize),
}

/// The empty text's code: every [`Levels`] of `classify_batch` starts with it.
const EMPTY_CODE: u32 = 0;

/// Levels holding the empty text as [`EMPTY_CODE`].
fn empty_levels() -> Levels {
    let mut l = Levels::default();
    l.code("");
    l
}

/// The result columns of `classify_batch`, each one flat vector of all rows,
/// created empty (NaN, the empty text, not valid): the blocks of rows write
/// their cells in place ([`BlockCells`]), so nothing is staged or
/// concatenated.
struct ResultColumns {
    rows: usize,
    kind: Vec<ColKind>,
    /// Numeric column `k` at `nums[k * rows..(k + 1) * rows]`.
    nums: Vec<f64>,
    /// Text column `t`'s codes at `codes[t * rows..]`.
    codes: Vec<u32>,
    /// Column `j`'s validity at `valid[j * rows..]`.
    valid: Vec<bool>,
    errors: Vec<u32>,
}

/// One block's disjoint parts of the [`ResultColumns`] (sendable to a worker).
struct BlockParts<'a> {
    nums: Vec<&'a mut [f64]>,
    codes: Vec<&'a mut [u32]>,
    valid: Vec<&'a mut [bool]>,
    errors: &'a mut [u32],
}

impl ResultColumns {
    /// `rows` empty rows of the columns `numeric` describes.
    fn new(numeric: &[bool], rows: usize) -> Self {
        let (mut k, mut t) = (0, 0);
        let kind: Vec<ColKind> = numeric
            .iter()
            .map(|&n| {
                if n {
                    k += 1;
                    ColKind::Num(k - 1)
                } else {
                    t += 1;
                    ColKind::Text(t - 1)
                }
            })
            .collect();
        ResultColumns {
            rows,
            nums: vec![f64::NAN; k * rows],
            codes: vec![EMPTY_CODE; t * rows],
            valid: vec![false; kind.len() * rows],
            kind,
            errors: vec![EMPTY_CODE; rows],
        }
    }

    /// The storage of rows `[b * chunk, (b + 1) * chunk)` for every block `b`
    /// (`rows > 0`).
    fn blocks(&mut self, chunk: usize) -> Vec<BlockParts<'_>> {
        let rows = self.rows;
        let count = rows.div_ceil(chunk);
        let mut out: Vec<BlockParts<'_>> = Vec::with_capacity(count);
        for e in self.errors.chunks_mut(chunk) {
            out.push(BlockParts {
                nums: Vec::new(),
                codes: Vec::new(),
                valid: Vec::new(),
                errors: e,
            });
        }
        for col in self.nums.chunks_mut(rows) {
            for (b, part) in out.iter_mut().zip(col.chunks_mut(chunk)) {
                b.nums.push(part);
            }
        }
        for col in self.codes.chunks_mut(rows) {
            for (b, part) in out.iter_mut().zip(col.chunks_mut(chunk)) {
                b.codes.push(part);
            }
        }
        for col in self.valid.chunks_mut(rows) {
            for (b, part) in out.iter_mut().zip(col.chunks_mut(chunk)) {
                b.valid.push(part);
            }
        }
        out
    }

    /// Translates block `b`'s text codes (rows `[b * chunk, ..)`, codes into
    /// that block's `levels`) into codes of one set of levels per column, and
    /// returns them: `(column levels, error levels)`.
    fn merge_levels(
        &mut self,
        chunk: usize,
        levels: Vec<(Vec<Levels>, Levels)>,
    ) -> (Vec<Vec<String>>, Vec<String>) {
        let rows = self.rows;
        let texts = self.codes.len() / rows.max(1);
        let mut merged: Vec<Levels> = (0..texts).map(|_| empty_levels()).collect();
        let mut errors = empty_levels();
        let remap = |all: &mut Levels, mine: &Levels, codes: &mut [u32]| {
            let map: Vec<u32> = mine.0.iter().map(|t| all.code(t)).collect();
            for c in codes {
                *c = map[*c as usize];
            }
        };
        for (b, (cols, errs)) in levels.iter().enumerate() {
            let lo = b * chunk;
            let hi = (lo + chunk).min(rows);
            for (t, mine) in cols.iter().enumerate() {
                remap(
                    &mut merged[t],
                    mine,
                    &mut self.codes[t * rows + lo..t * rows + hi],
                );
            }
            remap(&mut errors, errs, &mut self.errors[lo..hi]);
        }
        (merged.into_iter().map(|l| l.0).collect(), errors.0)
    }

    /// `name -> (values, mask)` for numeric columns and `name -> (codes,
    /// levels, mask)` for text columns (the Python side expands the codes);
    /// `error -> (codes, levels)`.
    fn into_dict<'py>(
        self,
        levels: (Vec<Vec<String>>, Vec<String>),
        py: Python<'py>,
        names: &[String],
        out: &Bound<'py, PyDict>,
    ) -> PyResult<()> {
        let rows = self.rows;
        let (mut text_levels, error_levels) = levels;
        let part = |v: &[f64], k: usize| v[k * rows..(k + 1) * rows].to_vec();
        for (j, (name, kind)) in names.iter().zip(&self.kind).enumerate() {
            let mask = PyArray1::from_slice(py, &self.valid[j * rows..(j + 1) * rows]);
            match *kind {
                ColKind::Num(k) => {
                    out.set_item(name, (PyArray1::from_vec(py, part(&self.nums, k)), mask))?
                }
                ColKind::Text(t) => out.set_item(
                    name,
                    (
                        PyArray1::from_slice(py, &self.codes[t * rows..(t + 1) * rows]),
                        std::mem::take(&mut text_levels[t]),
                        mask,
                    ),
                )?,
            }
        }
        out.set_item("error", (PyArray1::from_vec(py, self.errors), error_levels))?;
        Ok(())
    }
}

/// One block's cells, written in place by the lanes' [`RowSink`]s (a cell
/// store each: `std::cell::Cell` views of the block's parts, so the sinks share the
/// block without a borrow flag; only texts take the levels' `RefCell`).
struct BlockCells<'a> {
    kind: &'a [ColKind],
    nums: Vec<&'a [StdCell<f64>]>,
    codes: Vec<&'a [StdCell<u32>]>,
    valid: Vec<&'a [StdCell<bool>]>,
    errors: &'a [StdCell<u32>],
    levels: Vec<RefCell<Levels>>,
    error_levels: RefCell<Levels>,
}

impl<'a> BlockCells<'a> {
    fn new(kind: &'a [ColKind], parts: BlockParts<'a>) -> Self {
        BlockCells {
            kind,
            levels: parts
                .codes
                .iter()
                .map(|_| RefCell::new(empty_levels()))
                .collect(),
            nums: parts
                .nums
                .into_iter()
                .map(|s| StdCell::from_mut(s).as_slice_of_cells())
                .collect(),
            codes: parts
                .codes
                .into_iter()
                .map(|s| StdCell::from_mut(s).as_slice_of_cells())
                .collect(),
            valid: parts
                .valid
                .into_iter()
                .map(|s| StdCell::from_mut(s).as_slice_of_cells())
                .collect(),
            errors: StdCell::from_mut(parts.errors).as_slice_of_cells(),
            error_levels: RefCell::new(empty_levels()),
        }
    }

    /// Writes the number `x` as cell `j` of row `row`. A cell beyond the
    /// columns is dropped; a number in a text column becomes Rust's shortest
    /// text for it (the built-in evaluator writes neither).
    #[inline]
    fn put_num(&self, row: usize, j: usize, x: f64) {
        match self.kind.get(j) {
            Some(&ColKind::Num(k)) => {
                self.nums[k][row].set(x);
                self.valid[j][row].set(true);
            }
            Some(&ColKind::Text(_)) => self.put_num_as_text(row, j, x),
            None => {}
        }
    }

    /// [`put_num`](Self::put_num) into a text column (rare: out of line, so
    /// that the common path saves no registers).
    #[cold]
    #[inline(never)]
    fn put_num_as_text(&self, row: usize, j: usize, x: f64) {
        self.put_text(row, j, &x.to_string());
    }

    /// Writes the text `t` as cell `j` of row `row`; a text in a numeric
    /// column leaves the cell empty (NaN, not valid).
    #[inline(never)]
    fn put_text(&self, row: usize, j: usize, t: &str) {
        match self.kind.get(j) {
            Some(&ColKind::Text(c)) => {
                self.codes[c][row].set(self.levels[c].borrow_mut().code(t));
                self.valid[j][row].set(true);
            }
            Some(&ColKind::Num(_)) => self.put_empty(row, j),
            None => {}
        }
    }

    /// Makes cell `j` of row `row` empty (NaN or the empty text, not valid).
    #[inline]
    fn put_empty(&self, row: usize, j: usize) {
        match self.kind.get(j) {
            Some(&ColKind::Num(k)) => self.nums[k][row].set(f64::NAN),
            Some(&ColKind::Text(c)) => self.codes[c][row].set(EMPTY_CODE),
            None => return,
        }
        self.valid[j][row].set(false);
    }

    /// Makes row `row` an error row: every cell empty, the error text `msg`.
    fn fail_row(&self, row: usize, msg: &str) {
        for j in 0..self.kind.len() {
            self.put_empty(row, j);
        }
        self.errors[row].set(self.error_levels.borrow_mut().code(msg));
    }

    /// The block's levels: `(one per text column, the errors')`.
    fn into_levels(self) -> (Vec<Levels>, Levels) {
        (
            self.levels.into_iter().map(RefCell::into_inner).collect(),
            self.error_levels.into_inner(),
        )
    }
}

/// One lane's writer into a block: cell after cell of row `row`, in place.
struct RowSink<'a> {
    block: &'a BlockCells<'a>,
    row: usize,
    j: usize,
}

impl CellSink for RowSink<'_> {
    fn empty(&mut self) {
        self.block.put_empty(self.row, self.j);
        self.j += 1;
    }
    fn num(&mut self, x: f64) {
        self.block.put_num(self.row, self.j, x);
        self.j += 1;
    }
    fn text(&mut self, t: &str) {
        self.block.put_text(self.row, self.j, t);
        self.j += 1;
    }
}

/// `classify_batch`: result columns of a ratios sweep, one row per row of `ratios`.
///
/// Rows are evaluated in blocks of whole batches on the pool; each block
/// writes typed columns directly (numbers as `f64`, texts as codes into a few
/// distinct values), so a row costs no allocation beyond its scheme.
#[pyfunction]
#[pyo3(signature = (ratios, scheme="nurds", columns_json=None, threads=None))]
fn classify_batch<'py>(
    py: Python<'py>,
    ratios: PyReadonlyArray2<'py, f64>,
    scheme: &str,
    columns_json: Option<&str>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = ratios.shape();
    let n = shape[1];
    if n < 3 {
        return Err(value_err(format!(
            "ratios must have one column per edge of a valence n >= 3 face, got {n} columns"
        )));
    }
    let columns: serde_json::Value = match columns_json {
        Some(t) => serde_json::from_str(t).map_err(|e| value_err(format!("columns: {e}")))?,
        None => serde_json::json!({}),
    };
    let spec = serde_json::json!({
        "name": "classify_batch",
        "scheme": scheme,
        "valences": [n],
        "space": {"kind": "ratios", "ratio_range": [0.01, 0.99]},
        "sampler": {"kind": "grid", "points_per_axis": 1},
        "columns": columns,
    });
    let toml_text = toml::to_string(&spec).map_err(|e| value_err(format!("columns: {e}")))?;
    let spec = SweepSpec::from_toml(&toml_text).map_err(lib_err)?;
    let plan = Plan::new(spec);
    let result_names: Vec<_> = subdiv_lab::sweep::eval::result_columns(&plan.spec().columns);
    let names: Vec<String> = result_names.iter().map(|c| c.name.clone()).collect();
    let numeric: Vec<bool> = result_names.iter().map(|c| c.numeric).collect();
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let data: Vec<f64> = match ratios.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => ratios.as_array().iter().copied().collect(),
    };
    let pool = pool(threads)?;
    // Row-major rows of n ratios; blocks of whole batches, evaluated in parallel.
    const CHUNK: usize = 64 * BATCH;
    let rows_total = shape[0];
    let mut result = ResultColumns::new(&numeric, rows_total);
    let kind = result.kind.clone();
    let levels: Vec<(Vec<Levels>, Levels)> = if rows_total == 0 {
        Vec::new()
    } else {
        let parts = result.blocks(CHUNK);
        py.detach(|| {
            pool.install(|| {
                parts
                    .into_par_iter()
                    .zip(data.par_chunks(CHUNK * n))
                    .enumerate()
                    .map(|(ci, (parts, chunk))| -> PyResult<(Vec<Levels>, Levels)> {
                        let block = BlockCells::new(&kind, parts);
                        let mut configs: [Configuration; BATCH] =
                            std::array::from_fn(|_| Configuration {
                                id: 0,
                                valence: n,
                                coordinates: Vec::with_capacity(n),
                            });
                        let mut kept: [Option<Builtin>; BATCH] = Default::default();
                        for (bi, group) in chunk.chunks(BATCH * n).enumerate() {
                            let width = group.len() / n;
                            let base = (ci * CHUNK + bi * BATCH) as u64;
                            for (l, r) in group.chunks(n).enumerate() {
                                configs[l].id = base + l as u64;
                                configs[l].coordinates.clear();
                                configs[l].coordinates.extend_from_slice(r);
                            }
                            // Each lane's scheme reuses the storage of its last one.
                            let mut schemes = Vec::with_capacity(width);
                            for (c, old) in configs[..width].iter().zip(&mut kept) {
                                schemes.push(
                                    plan.scheme_reusing(c, old.take()).map_err(|e| {
                                        value_err(format!("ratios row {}: {e}", c.id))
                                    })?,
                                );
                            }
                            let row0 = bi * BATCH;
                            let mut sinks: [RowSink; BATCH] = std::array::from_fn(|l| RowSink {
                                block: &block,
                                row: row0 + l,
                                j: 0,
                            });
                            if width == BATCH {
                                let mut it = sinks.iter_mut();
                                let items = std::array::from_fn(|l| {
                                    (
                                        &configs[l],
                                        &*schemes[l],
                                        it.next().expect("lane") as &mut dyn CellSink,
                                    )
                                });
                                let res = eval.write_results_batch(&plan, items);
                                for (l, r) in res.into_iter().enumerate() {
                                    if let Err(e) = r {
                                        block.fail_row(row0 + l, &e.to_string());
                                    }
                                }
                            } else {
                                for (l, sink) in sinks[..width].iter_mut().enumerate() {
                                    if let Err(e) =
                                        eval.write_results(&plan, &configs[l], &*schemes[l], sink)
                                    {
                                        block.fail_row(row0 + l, &e.to_string());
                                    }
                                }
                            }
                            for (k, s) in kept.iter_mut().zip(schemes) {
                                *k = Some(s);
                            }
                        }
                        Ok(block.into_levels())
                    })
                    .collect::<PyResult<Vec<_>>>()
            })
        })?
    };
    let levels = result.merge_levels(CHUNK, levels);
    let out = PyDict::new(py);
    result.into_dict(levels, py, &names, &out)?;
    Ok(out)
}

/// `sweep`: the rows of a sweep (all, one shard, or its first `limit` ids) as columns.
#[pyfunction]
#[pyo3(signature = (spec_toml, threads=None, shard=None, limit=None))]
fn sweep<'py>(
    py: Python<'py>,
    spec_toml: &str,
    threads: Option<usize>,
    shard: Option<(u64, u64)>,
    limit: Option<u64>,
) -> PyResult<(Vec<String>, Bound<'py, PyDict>)> {
    let spec = SweepSpec::from_toml(spec_toml).map_err(lib_err)?;
    let shard = match shard {
        Some((i, k)) => Shard::new(i, k).map_err(lib_err)?,
        None => Shard::ALL,
    };
    let plan = Plan::new(spec);
    let layout = Layout::new(&plan);
    let header = layout.header();
    let names: Vec<String> = header.trim_end().split(',').map(str::to_owned).collect();
    let inner: Vec<String> = names[2..names.len() - 1].to_vec();
    let mut numeric = vec![false; inner.len()];
    for (pos, _) in layout.numeric_columns() {
        if let Some(x) = numeric.get_mut(*pos) {
            *x = true;
        }
    }
    let count = shard.len(plan.total()).min(limit.unwrap_or(u64::MAX));
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let pool = pool(threads)?;
    let rows: Vec<subdiv_lab::sweep::output::Row> = py.detach(|| {
        pool.install(|| {
            (0..count)
                .into_par_iter()
                .map(|j| layout.row(&plan, &eval, shard.id(j)))
                .collect()
        })
    });
    let mut cols = Columns::new(inner, numeric, rows.len());
    let mut ids = Vec::with_capacity(rows.len());
    let mut valences = Vec::with_capacity(rows.len());
    let mut errors = Vec::with_capacity(rows.len());
    for r in rows {
        ids.push(r.id);
        valences.push(r.valence as u32);
        cols.push(&r.cells);
        errors.push(r.error.unwrap_or_default());
    }
    let out = PyDict::new(py);
    out.set_item("id", PyArray1::from_vec(py, ids))?;
    out.set_item("valence", PyArray1::from_vec(py, valences))?;
    cols.into_dict(py, &out)?;
    out.set_item("error", errors)?;
    Ok((names, out))
}

/// `subdivide`: `levels` refinement steps of a closed polygon mesh.
#[pyfunction]
#[pyo3(signature = (vertices, faces, scheme="nurds", knots=None, levels=1, c=None))]
fn subdivide<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: Vec<Vec<usize>>,
    scheme: &str,
    knots: Option<Vec<((usize, usize), f64)>>,
    levels: usize,
    c: Option<f64>,
) -> PyResult<MeshOut<'py>> {
    use subdiv_lab::mesh::Mesh;
    let kind: SchemeKind = scheme
        .parse()
        .map_err(|e: subdiv_lab::schemes::UnknownScheme| value_err(e.to_string()))?;
    let shape = vertices.shape();
    if shape[1] != 3 {
        return Err(value_err(format!(
            "vertices must have shape (m, 3), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    let v = vertices.as_array();
    let positions: Vec<[f64; 3]> = v.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect();
    let mut mesh = Mesh::from_polygons(positions, &faces).map_err(lib_err)?;
    if let Some(k) = &knots {
        if !kind.takes_knots() {
            return Err(value_err(format!(
                "scheme {kind} takes no knot intervals; use scheme nurds for knots"
            )));
        }
        for &((a, b), x) in k {
            let h = mesh.find_half_edge(a, b).ok_or_else(|| {
                value_err(format!("knots: ({a}, {b}) is not an edge of the mesh"))
            })?;
            mesh.set_knot(h, x).map_err(lib_err)?;
        }
    }
    let cc = match (kind, c) {
        (SchemeKind::CatmullClark, None) => Some(0.5),
        (SchemeKind::CatmullClark, Some(_)) => {
            return Err(value_err(
                "scheme catmull-clark has c = 1/2; use scheme adjustable-cc with c",
            ))
        }
        (SchemeKind::AdjustableCc, None) => {
            return Err(value_err("scheme adjustable-cc needs c in [0, 1]"))
        }
        (SchemeKind::AdjustableCc, Some(c)) => Some(c),
        (_, Some(_)) => {
            return Err(value_err(
                "c is the shape parameter of scheme adjustable-cc only",
            ))
        }
        (_, None) => None,
    };
    let mut est = mesh.half_edge_count() as u64;
    for _ in 0..levels {
        est = est.saturating_mul(4);
    }
    if est > subdiv_lab::mesh::MAX_HALF_EDGES {
        return Err(value_err(format!(
            "{levels} levels would make about {est} half-edges, more than {}",
            subdiv_lab::mesh::MAX_HALF_EDGES
        )));
    }
    let refined = py.detach(move || -> Result<Mesh, subdiv_lab::mesh::MeshError> {
        for _ in 0..levels {
            mesh = match (kind, cc) {
                (_, Some(c)) => subdiv_lab::mesh::catmull_clark::refine_cc(&mesh, c)?,
                (SchemeKind::Loop, _) => {
                    subdiv_lab::schemes::loop_subdivision::mesh::refine(&mesh)?
                }
                _ => subdiv_lab::mesh::refine::refine(&mesh, kind)?,
            };
        }
        Ok(mesh)
    });
    let mesh = refined.map_err(lib_err)?;
    let pos: Vec<Vec<f64>> = mesh.positions().iter().map(|p| p.to_vec()).collect();
    let faces: Vec<Vec<usize>> = (0..mesh.face_count())
        .map(|f| mesh.face_vertices(f).collect())
        .collect();
    let a = if pos.is_empty() {
        PyArray2::zeros(py, [0, 3], false)
    } else {
        PyArray2::from_vec2(py, &pos).map_err(|e| PyRuntimeError::new_err(e.to_string()))?
    };
    Ok((a, faces))
}

/// `report`: the files of a report (`(relative path, bytes)`), generated with
/// the GIL released; the Python side writes them.
#[pyfunction]
#[pyo3(signature = (spec_toml, spec_path=None))]
fn report_files(
    py: Python<'_>,
    spec_toml: &str,
    spec_path: Option<String>,
) -> PyResult<Vec<(String, pyo3::Py<pyo3::types::PyBytes>)>> {
    use subdiv_lab::report::{figures::NoProgress, generate, ReportError, ReportSpec, RunInfo};
    let report_err = |e: ReportError| {
        let input = match &e {
            ReportError::Spec { .. } => true,
            ReportError::Analysis { source, .. } => source.is_input_error(),
            _ => false,
        };
        if input {
            PyValueError::new_err(e.to_string())
        } else {
            PyRuntimeError::new_err(e.to_string())
        }
    };
    let spec = ReportSpec::parse(spec_toml).map_err(report_err)?;
    let run = RunInfo {
        version: Some(subdiv_lab::spectral::json::TOOL_VERSION.to_owned()),
        git_revision: None,
        spec_path,
        spec_builtin: false,
    };
    let report = py
        .detach(|| generate(&spec, &run, &NoProgress))
        .map_err(report_err)?;
    Ok(report
        .files
        .into_iter()
        .map(|f| (f.path, pyo3::types::PyBytes::new(py, &f.bytes).unbind()))
        .collect())
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", subdiv_lab::spectral::json::TOOL_VERSION)?;
    m.add_function(wrap_pyfunction!(matrix, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_json, m)?)?;
    m.add_function(wrap_pyfunction!(spec_json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(classify_batch, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(report_files, m)?)?;
    Ok(())
}
