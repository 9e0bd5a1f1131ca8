//! `classify_batch`: many ratios configurations at once, written straight
//! into typed result columns (the numpy arrays of the Python side).

use crate::{guard, lib_err, limit, value_err, Int};
use numpy::{PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use std::cell::{Cell as StdCell, RefCell};
use subdiv_lab::budget::{held_in_memory, BATCH_BYTES_PER_CELL, SWEEP_TIME_LIMIT_SECONDS};
use subdiv_lab::spectral::BATCH;
use subdiv_lab::sweep::eval::CellSink;
use subdiv_lab::sweep::{Configuration, Configured, Evaluate, Plan, SpectralEvaluator, SweepSpec};

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
        let texts = self
            .kind
            .iter()
            .filter(|k| matches!(k, ColKind::Text(_)))
            .count();
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
#[pyo3(signature = (ratios, scheme="nurds", columns_json=None, threads=None, force=false))]
pub(crate) fn classify_batch<'py>(
    py: Python<'py>,
    ratios: PyReadonlyArray2<'py, f64>,
    scheme: &str,
    columns_json: Option<&str>,
    threads: Option<Int>,
    force: bool,
) -> PyResult<Bound<'py, PyDict>> {
    guard("classify_batch", || {
        classify_batch_body(py, ratios, scheme, columns_json, threads, force)
    })
}

fn classify_batch_body<'py>(
    py: Python<'py>,
    ratios: PyReadonlyArray2<'py, f64>,
    scheme: &str,
    columns_json: Option<&str>,
    threads: Option<Int>,
    force: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = ratios.shape();
    let (rows_total, n) = (
        shape.first().copied().unwrap_or(0),
        shape.get(1).copied().unwrap_or(0),
    );
    if n < 3 {
        return Err(value_err(format!(
            "ratios must have one column per edge of a valence n >= 3 face, got {n} columns"
        )));
    }
    let threads = crate::threads(threads)?;
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
    // The rows' work as a sweep's (the CLI's sweep limit), with the result
    // columns and the copied input held in memory.
    let estimate = held_in_memory(
        subdiv_lab::sweep::batch_rows(&plan, n, rows_total as u64, threads),
        rows_total as u64,
        names.len() + n,
        BATCH_BYTES_PER_CELL,
    );
    limit(
        "classify_batch",
        &format!("{rows_total} rows of valence {n}"),
        &estimate,
        SWEEP_TIME_LIMIT_SECONDS,
        force,
    )?;
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let data: Vec<f64> = match ratios.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => ratios.as_array().iter().copied().collect(),
    };
    let pool = crate::pool(threads)?;
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
                        let mut kept: [Option<Configured>; BATCH] = Default::default();
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
                                let mut l = 0;
                                let items = sinks.each_mut().map(|sink| {
                                    let item =
                                        (&configs[l], &*schemes[l], sink as &mut dyn CellSink);
                                    l += 1;
                                    item
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
