//! The streaming sweep driver: evaluation in parallel chunks, rows formatted
//! without allocation, written in id order while the next chunk is evaluated.

use super::csv::{push_number, push_text};
use super::layout::Layout;
use crate::spectral::kernel::BATCH;
use crate::sweep::eval::{Cell, CellSink, ColumnType, Evaluate};
use crate::sweep::plan::{Configuration, Plan};
use crate::sweep::summary::{PartialSummary, Summary};
use crate::sweep::SweepError;
use rayon::prelude::*;
use std::io::Write;

/// Largest number of configurations evaluated in parallel as one chunk (fewer
/// when rows are long, so that a chunk's text stays within about 8 MB). At most
/// two chunks are in memory (one being evaluated, the previous one being
/// written), which bounds the memory of a run independently of the sweep size;
/// the chunk is large enough that the rayon split overhead is negligible.
pub const CHUNK: usize = 4096;

/// Largest number of consecutive configurations one rayon task evaluates (fewer
/// when a chunk is small, so that every thread gets several tasks). A task
/// formats its rows into one buffer and keeps one partial summary, reusing its
/// per-row storage, so a row costs no allocation.
pub const SUB_CHUNK: usize = 64;

/// A staged result cell (text as a range of [`Stage::text`]).
#[derive(Clone, Copy, Debug)]
enum Slot {
    Empty,
    Num(f64),
    Text(usize, usize),
}

/// The result cells of one configuration, staged without allocation (the
/// buffers are reused row after row).
#[derive(Debug, Default)]
struct Stage {
    slots: Vec<Slot>,
    text: String,
}

impl Stage {
    fn clear(&mut self) {
        self.slots.clear();
        self.text.clear();
    }
}

impl CellSink for Stage {
    fn empty(&mut self) {
        self.slots.push(Slot::Empty);
    }
    fn num(&mut self, x: f64) {
        self.slots.push(Slot::Num(x));
    }
    fn text(&mut self, t: &str) {
        let start = self.text.len();
        self.text.push_str(t);
        self.slots.push(Slot::Text(start, self.text.len()));
    }
}

/// One configuration of the sweep driver between evaluation and formatting.
#[derive(Default)]
struct Staged {
    config: Configuration,
    sampler: Vec<f64>,
    stage: Stage,
    /// Coordinate cells of the current row (by column).
    coordinates: Vec<Option<f64>>,
    error: Option<String>,
    valence: usize,
    /// The scheme of the last row, whose storage the next row's reuses
    /// ([`Plan::scheme_reusing`]).
    scheme: Option<crate::sweep::plan::Configured>,
}

/// Reusable per-task storage of the sweep driver: [`BATCH`] staged rows (the
/// driver evaluates configurations in batches, [`Evaluate::write_results_batch`]).
pub(super) struct Scratch {
    rows: [Staged; BATCH],
}

thread_local! {
    /// The [`Scratch`] of the thread's last driver task, for its next one.
    static SCRATCH: std::cell::RefCell<Option<Scratch>> = const { std::cell::RefCell::new(None) };
}

impl Scratch {
    pub(super) fn new() -> Self {
        Scratch {
            rows: std::array::from_fn(|_| Staged::default()),
        }
    }
}

/// The rows of one driver task in the output's form, built cell by cell: for
/// each row [`start`](Self::start), one call per cell (coordinates then
/// results, in column order), then [`end`](Self::end). [`CsvBlock`] makes the
/// CSV lines; the Parquet form appends to typed column buffers
/// ([`super::parquet::TypedBlock`]), so that no number goes through text.
pub(crate) trait RowBlock: Send {
    /// An empty block for about `rows` rows of `layout`.
    fn with_rows(layout: &Layout, rows: usize) -> Self;
    /// Starts the row of configuration `id` (valence `valence`; 0 when the
    /// configuration could not be enumerated).
    fn start(&mut self, id: u64, valence: usize);
    /// The next cell is empty.
    fn empty(&mut self);
    /// The next cell is the number `x`.
    fn num(&mut self, x: f64);
    /// The next cell is the number `x`, in a float column (a column of type
    /// [`ColumnType::Float`]): a block may skip the check of the column's
    /// type.
    #[inline(always)]
    fn float(&mut self, x: f64) {
        self.num(x);
    }
    /// The next cell is the text `t`.
    fn text(&mut self, t: &str);
    /// Ends the row with its `error` cell.
    fn end(&mut self, error: Option<&str>);
    /// Empties the block for reuse (its storage is kept): the driver recycles
    /// the blocks of written chunks, so that a task does not allocate.
    fn clear(&mut self);
    /// Appends a whole row, cell by cell.
    fn push_row(&mut self, row: &super::Row) {
        self.start(row.id, row.valence);
        for c in &row.cells {
            match c {
                Cell::Empty => self.empty(),
                Cell::Num(x) => self.num(*x),
                Cell::Text(t) => self.text(t),
            }
        }
        self.end(row.error.as_deref());
    }
}

/// The CSV lines of a task (the sweep's CSV text, byte for byte that of
/// [`Layout::format_into`]).
pub(crate) struct CsvBlock {
    /// The lines, each ending in `\n`.
    pub(crate) text: String,
    digits: zmij::Buffer,
}

impl CsvBlock {
    /// An empty block.
    pub(crate) fn new() -> Self {
        CsvBlock {
            text: String::new(),
            digits: zmij::Buffer::new(),
        }
    }
}

/// A row's CSV line is the sweep driver's CSV block given the row's cells,
/// so the line a resume check compares and the line a sweep writes come
/// from one formatter.
impl Layout {
    /// The CSV line of `row` (with `\n`).
    pub fn format(&self, row: &super::Row) -> String {
        let mut s = String::with_capacity(32 + 24 * row.cells.len());
        self.format_into(row, &mut s);
        s
    }

    /// Appends the CSV line of `row` (with `\n`) to `s`.
    pub fn format_into(&self, row: &super::Row, s: &mut String) {
        let mut block = CsvBlock::new();
        block.text = std::mem::take(s);
        block.push_row(row);
        *s = block.text;
    }
}

/// Whole rows: each row of the driver as a [`Row`](super::Row) of its cells.
impl RowBlock for Vec<super::Row> {
    fn with_rows(_: &Layout, rows: usize) -> Self {
        Vec::with_capacity(rows)
    }
    fn start(&mut self, id: u64, valence: usize) {
        let cells = Vec::new();
        self.push(super::Row {
            id,
            valence,
            cells,
            error: None,
        });
    }
    fn empty(&mut self) {
        push_cell(self, Cell::Empty);
    }
    fn num(&mut self, x: f64) {
        push_cell(self, Cell::Num(x));
    }
    fn text(&mut self, t: &str) {
        push_cell(self, Cell::Text(t.to_owned()));
    }
    fn end(&mut self, error: Option<&str>) {
        if let Some(r) = self.last_mut() {
            r.error = error.map(str::to_owned);
        }
    }
    fn clear(&mut self) {
        Vec::clear(self);
    }
}

/// Appends `cell` to the last of `rows`.
fn push_cell(rows: &mut [super::Row], cell: Cell) {
    if let Some(r) = rows.last_mut() {
        r.cells.push(cell);
    }
}

impl RowBlock for CsvBlock {
    fn with_rows(layout: &Layout, rows: usize) -> Self {
        CsvBlock {
            text: String::with_capacity(rows * (32 + 24 * layout.cells())),
            digits: zmij::Buffer::new(),
        }
    }
    fn start(&mut self, id: u64, valence: usize) {
        let mut ibuf = itoa::Buffer::new();
        self.text.push_str(ibuf.format(id));
        self.text.push(',');
        self.text.push_str(ibuf.format(valence));
    }
    fn empty(&mut self) {
        self.text.push(',');
    }
    fn num(&mut self, x: f64) {
        self.text.push(',');
        push_number(&mut self.text, &mut self.digits, x);
    }
    fn text(&mut self, t: &str) {
        self.text.push(',');
        push_text(&mut self.text, t);
    }
    fn end(&mut self, error: Option<&str>) {
        self.text.push(',');
        if let Some(e) = error {
            push_text(&mut self.text, e);
        }
        self.text.push('\n');
    }
    fn clear(&mut self) {
        self.text.clear();
    }
}

impl Layout {
    /// Evaluates configuration `id` into a row: the cells the sweep driver
    /// writes for it.
    pub fn row<E: Evaluate + ?Sized>(&self, plan: &Plan, eval: &E, id: u64) -> super::Row {
        let mut rows = Vec::with_capacity(1);
        let mut part = PartialSummary::new(self.numeric.len());
        self.append_rows(plan, eval, &[id], &mut Scratch::new(), &mut rows, &mut part);
        rows.pop().expect("append_rows emits one row per id")
    }

    /// The sweep driver's path for at most [`BATCH`] configurations `ids`:
    /// evaluates them (a full batch together, by
    /// [`Evaluate::write_results_batch`]; fewer, or a batch with a
    /// configuration that fails to load, one by one: evaluators must give
    /// equal cells either way), appends their rows to `out` and adds them to
    /// `part`. Equal, byte for byte and for the summary, to
    /// [`row`](Self::row) + [`format_into`](Self::format_into) +
    /// [`Summary::add`] per configuration (a test checks it), but
    /// allocation-free after warm-up.
    pub(super) fn append_rows<E: Evaluate + ?Sized, B: RowBlock>(
        &self,
        plan: &Plan,
        eval: &E,
        ids: &[u64],
        sc: &mut Scratch,
        out: &mut B,
        part: &mut PartialSummary,
    ) {
        let rows = &mut sc.rows;
        let schemes: [Option<_>; BATCH] =
            std::array::from_fn(|l| self.load(plan, *ids.get(l)?, &mut rows[l]));
        if ids.len() == BATCH && schemes.iter().all(Option::is_some) {
            let schemes = schemes.map(|s| s.expect("all loaded"));
            let mut it = rows.iter_mut();
            let items = std::array::from_fn(|l| {
                let row = it.next().expect("one row per lane");
                (
                    &row.config,
                    &*schemes[l],
                    &mut row.stage as &mut dyn CellSink,
                )
            });
            let res = eval.write_results_batch(plan, items);
            for ((row, r), s) in rows.iter_mut().zip(res).zip(schemes) {
                self.check_results(row, r);
                row.scheme = Some(s);
            }
        } else {
            for (row, s) in rows.iter_mut().zip(schemes) {
                if let Some(s) = s {
                    let r = eval.write_results(plan, &row.config, &*s, &mut row.stage);
                    self.check_results(row, r);
                    row.scheme = Some(s);
                }
            }
        }
        for (row, &id) in rows.iter_mut().zip(ids) {
            self.emit(id, row, out, part);
        }
    }

    /// Enumerates configuration `id` into `row` (coordinates by column) and
    /// builds its scheme; on an error, records it in `row` and returns `None`.
    fn load(
        &self,
        plan: &Plan,
        id: u64,
        row: &mut Staged,
    ) -> Option<crate::sweep::plan::Configured> {
        row.stage.clear();
        row.coordinates.clear();
        row.coordinates.resize(self.coordinates, None);
        row.error = None;
        match plan.configuration_into(id, &mut row.config, &mut row.sampler) {
            Ok(()) => {
                let c = &row.config;
                row.valence = c.valence;
                self.coordinates_into(plan, c, &mut row.coordinates);
                match plan.scheme_reusing(c, row.scheme.take()) {
                    Ok(s) => Some(s),
                    Err(e) => {
                        row.error = Some(e.to_string());
                        None
                    }
                }
            }
            Err(e) => {
                // The coordinates stay empty.
                row.error = Some(e.to_string());
                row.valence = 0;
                None
            }
        }
    }

    /// Records the outcome of an evaluation into `row`: a wrong cell count or
    /// an error empties the stage and becomes the row's error.
    fn check_results(&self, row: &mut Staged, result: crate::spectral::Result<()>) {
        let n_results = self.names.len() - self.coordinates;
        match result {
            Ok(()) if row.stage.slots.len() == n_results => {}
            Ok(()) => {
                row.error = Some(format!(
                    "internal: evaluator returned {} cells for {n_results} result columns",
                    row.stage.slots.len()
                ));
                row.stage.clear();
            }
            Err(e) => {
                row.error = Some(e.to_string());
                row.stage.clear();
            }
        }
    }

    /// Appends the row of the staged `row` (configuration `id`) to `out` and
    /// adds it to `part`.
    fn emit<B: RowBlock>(&self, id: u64, row: &Staged, out: &mut B, part: &mut PartialSummary) {
        let n_results = self.names.len() - self.coordinates;
        let valence = row.valence;
        let error = &row.error;
        out.start(id, valence);
        let mut numeric = 0usize;
        for (pos, x) in row.coordinates.iter().enumerate() {
            let is_num = self.types[pos] == ColumnType::Float;
            match x {
                Some(x) if is_num => {
                    out.float(*x);
                    part.push(numeric, *x, id);
                }
                Some(x) => out.num(*x),
                None => out.empty(),
            }
            if is_num {
                numeric += 1;
            }
        }
        let mut class: Option<&str> = None;
        if row.stage.slots.is_empty() {
            for _ in 0..n_results {
                out.empty();
            }
        } else {
            for (k, slot) in row.stage.slots.iter().enumerate() {
                let pos = self.coordinates + k;
                let is_num = self.types[pos] == ColumnType::Float;
                match *slot {
                    Slot::Empty => out.empty(),
                    Slot::Num(x) if is_num => {
                        out.float(x);
                        part.push(numeric, x, id);
                    }
                    Slot::Num(x) => out.num(x),
                    Slot::Text(a, b) => {
                        let t = &row.stage.text[a..b];
                        out.text(t);
                        if self.class == Some(pos) {
                            class = Some(t);
                        }
                    }
                }
                if is_num {
                    numeric += 1;
                }
            }
        }
        out.end(error.as_deref());
        let class = class.unwrap_or(if error.is_some() { "error" } else { "all" });
        part.count_row(valence, class, error.is_some());
    }
}

/// Where the driver writes the blocks of rows, in id order.
pub(super) trait BlockWriter<B> {
    /// Writes one block (which may take its buffers: the driver clears it
    /// before reusing it).
    fn write_block(&mut self, block: &mut B) -> Result<(), SweepError>;
    /// Called after the blocks of a chunk are written.
    fn flush(&mut self) -> Result<(), SweepError>;
}

/// CSV text to a [`Write`].
impl<W: Write + ?Sized> BlockWriter<CsvBlock> for W {
    fn write_block(&mut self, block: &mut CsvBlock) -> Result<(), SweepError> {
        self.write_all(block.text.as_bytes())?;
        Ok(())
    }
    fn flush(&mut self) -> Result<(), SweepError> {
        Write::flush(self)?;
        Ok(())
    }
}

/// Evaluates the configurations `ids` (in order) and writes their rows to `out`,
/// adding each to `summary`. Evaluation runs on the current rayon pool in chunks
/// of at most [`CHUNK`] configurations; while one chunk is evaluated, the
/// previous one is written (so the workers do not wait for the output). Rows are
/// written in `ids` order whatever the thread count. `progress` is called with
/// the number of rows written after each chunk.
pub fn run<E, W, I>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: I,
    out: &mut W,
    summary: &mut Summary,
    progress: &mut dyn FnMut(u64),
) -> Result<u64, SweepError>
where
    E: Evaluate + ?Sized,
    W: Write,
    I: IntoIterator<Item = u64>,
{
    let evaluated = std::sync::atomic::AtomicU64::new(0);
    drive::<E, CsvBlock, _, I>(plan, layout, eval, ids, out, summary, progress, &evaluated)
}

/// No rows: the cells are dropped as they come (the driver of
/// [`run_discard`]).
struct NullBlock;

impl RowBlock for NullBlock {
    fn with_rows(_: &Layout, _: usize) -> Self {
        NullBlock
    }
    fn start(&mut self, _: u64, _: usize) {}
    fn empty(&mut self) {}
    fn num(&mut self, _: f64) {}
    fn text(&mut self, _: &str) {}
    fn end(&mut self, _: Option<&str>) {}
    fn clear(&mut self) {}
}

impl BlockWriter<NullBlock> for () {
    fn write_block(&mut self, _: &mut NullBlock) -> Result<(), SweepError> {
        Ok(())
    }
    fn flush(&mut self) -> Result<(), SweepError> {
        Ok(())
    }
}

/// [`run`] without output: the configurations `ids` are enumerated, evaluated
/// and added to `summary` exactly as by [`run`], but no row is formed (no CSV
/// text, no Parquet buffers). It is the "evaluation alone" against which the
/// cost of the output formats is measured (`benches/sweep_formats.rs`);
/// returns the number of configurations.
///
/// ```
/// use subdiv_lab::sweep::{output, Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};
/// let spec = SweepSpec::from_toml(
///     "name = \"d\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\n\
///      ratio_range = [0.1, 0.9]\n[sampler]\nkind = \"halton\"\ncount = 10\n",
/// )
/// .unwrap();
/// let plan = Plan::new(spec);
/// let layout = Layout::new(&plan);
/// let eval = SpectralEvaluator::new(plan.spec().columns);
/// let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
/// let rows = output::run_discard(&plan, &layout, &eval, 0..plan.total(), &mut summary).unwrap();
/// assert_eq!(rows, 10);
/// ```
pub fn run_discard<E, I>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: I,
    summary: &mut Summary,
) -> Result<u64, SweepError>
where
    E: Evaluate + ?Sized,
    I: IntoIterator<Item = u64>,
{
    drive::<E, NullBlock, _, I>(
        plan,
        layout,
        eval,
        ids,
        &mut (),
        summary,
        &mut |_| {},
        &std::sync::atomic::AtomicU64::new(0),
    )
}

/// The driver behind [`run`] and [`run_parquet`](super::parquet::run_parquet): chunks evaluated
/// on the pool into blocks `B`, written in order by `out` while the next
/// chunk is evaluated. `evaluated` counts the configurations evaluated so
/// far (by groups of at most [`SUB_CHUNK`], as the workers finish them,
/// before they are written): another thread can read it for a progress
/// report that moves even when a chunk takes minutes.
#[allow(clippy::too_many_arguments)]
pub(super) fn drive<E, B, O, I>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: I,
    out: &mut O,
    summary: &mut Summary,
    progress: &mut dyn FnMut(u64),
    evaluated: &std::sync::atomic::AtomicU64,
) -> Result<u64, SweepError>
where
    E: Evaluate + ?Sized,
    B: RowBlock,
    O: BlockWriter<B>,
    I: IntoIterator<Item = u64>,
{
    let mut ids = ids.into_iter();
    let threads = rayon::current_num_threads().max(1);
    let numeric = layout.numeric.len();
    let chunk_len = chunk_len(layout);
    let mut written = 0u64;
    // Rows evaluated but not yet written: (block, partial summary) per task.
    let mut pending: Vec<(B, PartialSummary)> = Vec::new();
    // Blocks written, for reuse by the next tasks.
    let spare: std::sync::Mutex<Vec<B>> = std::sync::Mutex::new(Vec::new());
    let mut next: Vec<u64> = Vec::with_capacity(chunk_len);
    loop {
        next.clear();
        next.extend(ids.by_ref().take(chunk_len));
        if next.is_empty() && pending.is_empty() {
            break;
        }
        let mut fresh: Vec<(B, PartialSummary)> = Vec::new();
        let mut wrote: Result<u64, SweepError> = Ok(0);
        rayon::in_place_scope(|scope| {
            if !next.is_empty() {
                let chunk = &next;
                let slot = &mut fresh;
                let spare = &spare;
                scope.spawn(move |_| {
                    let work = Work {
                        plan,
                        layout,
                        eval,
                        threads,
                        numeric,
                        evaluated,
                        spare,
                    };
                    *slot = evaluate_chunk(&work, chunk);
                });
            }
            // Meanwhile, on this thread: write the previous chunk in order.
            wrote = (|| {
                let mut rows = 0u64;
                for (block, part) in &mut pending {
                    out.write_block(block)?;
                    summary.absorb_partial(part);
                    rows += part.rows();
                }
                if rows > 0 {
                    out.flush()?;
                }
                Ok(rows)
            })();
        });
        let rows = wrote?;
        if rows > 0 {
            written += rows;
            progress(written);
        }
        let done = std::mem::replace(&mut pending, fresh);
        if let Ok(mut s) = spare.lock() {
            s.extend(done.into_iter().map(|(mut b, _)| {
                b.clear();
                b
            }));
        }
    }
    Ok(written)
}

/// Configurations per chunk: [`CHUNK`], fewer for long rows (large valences)
/// so that a chunk's text stays within about 8 MB.
fn chunk_len(layout: &Layout) -> usize {
    let row_bytes = 32 + 24 * layout.cells();
    ((8 << 20) / row_bytes).clamp(SUB_CHUNK, CHUNK)
}

/// What the tasks of [`evaluate_chunk`] share: the sweep, the pool's thread
/// count, the number of numeric columns, the count of evaluated
/// configurations and the written blocks for reuse.
struct Work<'a, E: ?Sized, B> {
    plan: &'a Plan,
    layout: &'a Layout,
    eval: &'a E,
    threads: usize,
    numeric: usize,
    evaluated: &'a std::sync::atomic::AtomicU64,
    spare: &'a std::sync::Mutex<Vec<B>>,
}

/// Evaluates one chunk on the current pool: tasks of consecutive
/// configurations, each appending its rows to one block (a spare one when
/// there is one) and keeping a partial summary, returned in order.
fn evaluate_chunk<E: Evaluate + ?Sized, B: RowBlock>(
    work: &Work<'_, E, B>,
    chunk: &[u64],
) -> Vec<(B, PartialSummary)> {
    let Work {
        plan,
        layout,
        eval,
        threads,
        numeric,
        evaluated,
        spare,
    } = *work;
    let sub = (chunk.len() / (8 * threads)).clamp(1, SUB_CHUNK);
    chunk
        .par_chunks(sub)
        .map(|ids| {
            let reused = spare.lock().ok().and_then(|mut s| s.pop());
            let mut block = reused.unwrap_or_else(|| B::with_rows(layout, ids.len()));
            let mut part = PartialSummary::new(numeric);
            // The thread's scratch of its last task: its rows' buffers and
            // schemes are reused, not allocated per task (every row is
            // cleared when it is loaded, and `Plan::scheme_reusing` reuses a
            // scheme only of the same kind and valence).
            let mut scratch = SCRATCH
                .with(|s| s.borrow_mut().take())
                .unwrap_or_else(Scratch::new);
            for b in ids.chunks(BATCH) {
                layout.append_rows(plan, eval, b, &mut scratch, &mut block, &mut part);
            }
            evaluated.fetch_add(ids.len() as u64, std::sync::atomic::Ordering::Relaxed);
            SCRATCH.with(|s| *s.borrow_mut() = Some(scratch));
            (block, part)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::eval::{Cell, SpectralEvaluator};
    use crate::sweep::plan::Shard;

    /// An evaluator that returns the wrong number of cells for odd ids and fails
    /// for ids divisible by 5, to exercise the error rows of the fast path.
    struct Faulty(SpectralEvaluator);

    impl Evaluate for Faulty {
        fn evaluate(
            &self,
            plan: &Plan,
            c: &Configuration,
            scheme: &dyn crate::schemes::Scheme,
        ) -> crate::spectral::Result<Vec<Cell>> {
            let mut v = self.0.evaluate(plan, c, scheme)?;
            if c.id % 5 == 0 {
                return Err(crate::Error::InvalidParameter {
                    name: "test",
                    value: format!("id {}", c.id),
                    reason: "a failure with a comma, and \"quotes\"",
                }
                .into());
            }
            if c.id % 2 == 1 {
                v.push(Cell::Text("extra".into()));
            }
            Ok(v)
        }
    }

    /// The driver's allocation-free path equals `row` + `format` + `Summary::add`
    /// (and `run` writes exactly that, for any thread count).
    fn assert_fast_path_matches<E: Evaluate>(spec: &str, eval_of: impl Fn(&Plan) -> E) {
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        let layout = Layout::new(&plan);
        let eval = eval_of(&plan);
        let ids: Vec<u64> = (0..plan.total())
            .chain([plan.total(), plan.total() + 7])
            .collect();
        let mut want = String::new();
        let mut want_summary = Summary::new(&plan, &layout, Shard::ALL, None);
        for &id in &ids {
            let r = layout.row(&plan, &eval, id);
            layout.format_into(&r, &mut want);
            want_summary.add(&layout, &r);
        }
        let mut got = CsvBlock::new();
        let mut part = PartialSummary::new(layout.numeric.len());
        let mut scratch = Scratch::new();
        for &id in &ids {
            layout.append_rows(&plan, &eval, &[id], &mut scratch, &mut got, &mut part);
        }
        let got = got.text;
        let mut got_summary = Summary::new(&plan, &layout, Shard::ALL, None);
        got_summary.absorb_partial(&part);
        assert_eq!(got, want);
        assert_eq!(got_summary, want_summary);
        // The batched path (the driver's) gives the same lines, whatever the
        // phase of the batches (lone first rows shift every batch).
        for skip in [0, 1, BATCH / 2 + 1, BATCH - 1] {
            let skip = skip.min(ids.len());
            let mut got = CsvBlock::new();
            let mut part = PartialSummary::new(layout.numeric.len());
            for &id in &ids[..skip] {
                layout.append_rows(&plan, &eval, &[id], &mut scratch, &mut got, &mut part);
            }
            for b in ids[skip..].chunks(BATCH) {
                layout.append_rows(&plan, &eval, b, &mut scratch, &mut got, &mut part);
            }
            let mut got_summary = Summary::new(&plan, &layout, Shard::ALL, None);
            got_summary.absorb_partial(&part);
            assert_eq!(got.text, want, "batches from row {skip}");
            assert_eq!(got_summary, want_summary);
        }
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = Vec::new();
            let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
            let mut calls = Vec::new();
            let n = pool
                .install(|| {
                    run(
                        &plan,
                        &layout,
                        &eval,
                        ids.iter().copied(),
                        &mut out,
                        &mut summary,
                        &mut |k| calls.push(k),
                    )
                })
                .unwrap();
            assert_eq!(n, ids.len() as u64);
            assert_eq!(calls.last(), Some(&n));
            assert!(calls.windows(2).all(|w| w[0] < w[1]));
            assert_eq!(String::from_utf8(out).unwrap(), want);
            assert_eq!(summary, want_summary);
            // Evaluation alone: the same summary, no rows.
            let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
            let n = pool
                .install(|| run_discard(&plan, &layout, &eval, ids.iter().copied(), &mut summary))
                .unwrap();
            assert_eq!(n, ids.len() as u64);
            assert_eq!(summary, want_summary);
        }
    }

    /// `emit` hands every numeric cell to [`RowBlock::float`], which may skip
    /// the type check: so a numeric cell must be exactly a float column, in
    /// every column set (all optional columns on, and the curvature columns).
    #[test]
    fn numeric_cells_are_exactly_the_float_columns() {
        for spec in [
            "scheme = \"nurds\"\nvalences = [5]\n[space]\nkind = \"corner-intervals\"\ninterval_range = [0.1, 10.0]\n[sampler]\nkind = \"random\"\ncount = 2\nseed = 1\n[columns]\neigenvalues = 4\nexact_certificate = true\ncharmap = true\n",
            "scheme = \"cc-variant\"\nvalences = [3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\ncurvature = true\n",
        ] {
            let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
            let layout = Layout::new(&plan);
            assert!(layout.types.contains(&crate::sweep::eval::ColumnType::Label));
            let floats: Vec<usize> = (0..layout.types.len())
                .filter(|&k| layout.types[k] == crate::sweep::eval::ColumnType::Float)
                .collect();
            let numeric: Vec<usize> = layout.numeric.iter().map(|(k, _)| *k).collect();
            assert_eq!(numeric, floats, "{spec}");
        }
    }

    #[test]
    fn fast_path_matches_row_format_and_summary() {
        let spectral = |p: &Plan| SpectralEvaluator::new(p.spec().columns);
        assert_fast_path_matches(
            "scheme = \"nurds\"\nvalences = [4, 3]\n[space]\nkind = \"ratios\"\nratio_range = [0.001, 0.999]\nfixed = { r1 = 0.5 }\n[sampler]\nkind = \"grid\"\npoints_per_axis = 5\n[columns]\neigenvalues = 13\n",
            spectral,
        );
        assert_fast_path_matches(
            "scheme = \"nurds\"\nvalences = [3, 6]\n[space]\nkind = \"corner-intervals\"\ninterval_range = [0.001, 1000.0]\n[sampler]\nkind = \"random\"\ncount = 300\nseed = 5\n[columns]\ngap = false\ncharmap = true\n",
            spectral,
        );
        assert_fast_path_matches(
            "scheme = \"nurds\"\nvalences = [5]\n[space]\nkind = \"vertex-ep\"\ninterval_range = [0.1, 10.0]\n[sampler]\nkind = \"sobol\"\ncount = 200\nscramble = true\nseed = 2\n[columns]\nclassification = false\ngap = false\ncontraction = false\neigenvalues = 3\n",
            spectral,
        );
        assert_fast_path_matches(
            "scheme = \"cc-variant\"\nvalences = { from = 3, to = 40 }\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n[columns]\neigenvalues = 2\n",
            spectral,
        );
        assert_fast_path_matches(
            "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"face-ep\"\ninterval_range = [0.01, 100.0]\n[sampler]\nkind = \"halton\"\ncount = 120\n",
            |p: &Plan| Faulty(SpectralEvaluator::new(p.spec().columns)),
        );
        // Five chunks: from the third on, the driver writes into recycled
        // row blocks.
        const { assert!(5 * CHUNK > 18_000 && 4 * CHUNK < 18_000) };
        assert_fast_path_matches(
            "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = 18000\n",
            spectral,
        );
    }
}
