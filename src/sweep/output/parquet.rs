//! The Parquet form of a sweep's rows (`sweep --out NAME.parquet`; math doc
//! section 16.2): a dataset directory of part files, each a complete Parquet
//! file written by the `parquet` crate's column writers.
//!
//! # Columns
//!
//! The columns of the CSV, in the same order, typed: `id` `INT64` (unsigned),
//! `valence` `INT32` (unsigned), coordinates and float results `DOUBLE`,
//! labels (`class`, verdicts) dictionary-encoded UTF-8 `BYTE_ARRAY`, booleans
//! `BOOLEAN`, `error` UTF-8 `BYTE_ARRAY`; every column but `id` and `valence`
//! is optional (an empty CSV cell is a null, [`NULL_RULES`]). The type of a
//! result column is declared once, in the column table ([`result_columns`]).
//! The values are those of the CSV bit for bit (a float is the `f64` its CSV
//! text reads back to). No compression and no statistics: the bytes depend
//! only on the rows, so every part is byte-identical for any thread count.
//!
//! # Parts
//!
//! Rows are cut into parts of [`PART_ROWS`] rows of the shard (the last one
//! shorter); [`ParquetRows`] hands each completed part, a whole Parquet file
//! of one row group, to its caller, which commits it by an atomic rename
//! ([`part_name`]). The key-value metadata of every part holds the
//! fingerprint ([`FINGERPRINT_KEY`]: spec digest, shard, configurations), the
//! format ([`FORMAT_KEY`]), the part's index ([`PART_KEY`]), the column
//! documentation ([`SCHEMA_KEY`]) and the null rules ([`NULLS_KEY`]).
//! [`ParquetRows::file`] writes the same row groups into one file instead
//! (a compacted dataset).
//!
//! [`result_columns`]: crate::sweep::eval::result_columns

use super::csv::{canonical_number, push_number, push_text};
use super::layout::Layout;
use super::run::RowBlock;
use crate::sweep::eval::{ColumnType, Evaluate};
use crate::sweep::plan::{Plan, Shard};
use crate::sweep::summary::Summary;
use crate::sweep::SweepError;
use crate::table::{Column, Table};
use bytes::Bytes;
use parquet::basic::{IntType, LogicalType, Repetition, Type as PhysicalType};
use parquet::column::reader::ColumnReader;
use parquet::column::writer::ColumnWriter;
use parquet::data_type::ByteArray;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::{EnabledStatistics, WriterProperties, WriterVersion};
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnPath, Type, TypePtr};
use std::sync::Arc;

/// Rows per part (per row group of a compacted file; the last part of a
/// shard is shorter). Fixed, so that the parts, and with them the bytes of
/// the files, do not depend on the thread count or on where a run was
/// interrupted; 65 536 rows of the default columns are about 8 MB, a common
/// row-group size for readers, and a few seconds of evaluation.
pub const PART_ROWS: usize = 65_536;

/// The key of the fingerprint line in the key-value metadata.
pub const FINGERPRINT_KEY: &str = "subdiv-lab.fingerprint";

/// The key of the column documentation (JSON) in the key-value metadata.
pub const SCHEMA_KEY: &str = "subdiv-lab.schema";

/// The key of the format in the key-value metadata ([`FORMAT`]).
pub const FORMAT_KEY: &str = "subdiv-lab.format";

/// The format of a part file: files without it (a single file of the older
/// format, with its commit journal) are refused, never misread.
pub const FORMAT: &str = "sweep dataset part 1";

/// The key of a part's index (within its shard) in the key-value metadata.
pub const PART_KEY: &str = "subdiv-lab.part";

/// The key of the null rules ([`NULL_RULES`]) in the key-value metadata.
pub const NULLS_KEY: &str = "subdiv-lab.nulls";

/// When a cell is null (the CSV's empty cell).
pub const NULL_RULES: &str = "id and valence are never null; a coordinate is null beyond the row's valence; a result column is null where the result is not defined for the row (see its meaning in subdiv-lab.schema) and in every result column of a failed row; error is null when the row succeeded";

pub use super::detect::MAGIC;

/// The file name of part `k` of `shard` in a dataset directory:
/// `part-000017.parquet` for an unsharded run, `part-2-of-8-000017.parquet`
/// for shard 2/8 (the shards of one run write into one directory).
///
/// ```
/// use subdiv_lab::sweep::output::parquet::{part_name, parse_part_name};
/// use subdiv_lab::sweep::Shard;
/// assert_eq!(part_name(Shard::ALL, 17), "part-000017.parquet");
/// let s: Shard = "2/8".parse().unwrap();
/// assert_eq!(part_name(s, 3), "part-2-of-8-000003.parquet");
/// assert_eq!(parse_part_name("part-2-of-8-000003.parquet"), Some((s, 3)));
/// assert_eq!(parse_part_name("notes.txt"), None);
/// ```
pub fn part_name(shard: Shard, k: u64) -> String {
    if shard == Shard::ALL {
        format!("part-{k:06}.parquet")
    } else {
        format!("part-{}-of-{}-{k:06}.parquet", shard.index, shard.count)
    }
}

/// The shard and index a [`part_name`] names, if `name` is one.
pub fn parse_part_name(name: &str) -> Option<(Shard, u64)> {
    let rest = name.strip_prefix("part-")?.strip_suffix(".parquet")?;
    let (shard, k) = match rest.split('-').collect::<Vec<_>>().as_slice() {
        [k] => (Shard::ALL, *k),
        [i, "of", n, k] => (format!("{i}/{n}").parse().ok()?, *k),
        _ => return None,
    };
    // Only the name `part_name` writes for what was read (no sign, no
    // padding or spaces other than its own).
    let k = k.parse().ok()?;
    (part_name(shard, k) == name).then_some((shard, k))
}

fn pq_err(e: parquet::errors::ParquetError) -> SweepError {
    SweepError::Io(format!("parquet: {e}"))
}

/// A reader error of the `parquet` crate (reading an existing file).
fn pq_read_err(e: parquet::errors::ParquetError) -> SweepError {
    SweepError::Read(format!("parquet: {e}"))
}

/// The Parquet schema of `layout`'s rows: `id` and `valence` required
/// unsigned integers, a column per cell by its [`ColumnType`], `error` text;
/// all but `id` and `valence` optional.
fn schema_of(layout: &Layout) -> Result<TypePtr, SweepError> {
    let unsigned = |bit_width| {
        let t = IntType {
            bit_width,
            is_signed: false,
        };
        Some(LogicalType::Integer(t))
    };
    let text = (PhysicalType::BYTE_ARRAY, Some(LogicalType::String));
    let mut types = vec![
        (PhysicalType::INT64, unsigned(64)),
        (PhysicalType::INT32, unsigned(32)),
    ];
    types.extend(layout.types.iter().map(|t| match t {
        ColumnType::Float => (PhysicalType::DOUBLE, None),
        ColumnType::Label => text.clone(),
        ColumnType::Bool => (PhysicalType::BOOLEAN, None),
    }));
    types.push(text);
    let mut fields = Vec::with_capacity(types.len());
    for (j, (name, (phys, logical))) in layout.column_names().iter().zip(types).enumerate() {
        let repetition = if j < 2 {
            Repetition::REQUIRED
        } else {
            Repetition::OPTIONAL
        };
        let t = Type::primitive_type_builder(name, phys)
            .with_repetition(repetition)
            .with_logical_type(logical)
            .build()
            .map_err(pq_err)?;
        fields.push(Arc::new(t));
    }
    Ok(Arc::new(
        Type::group_type_builder("sweep")
            .with_fields(fields)
            .build()
            .map_err(pq_err)?,
    ))
}

/// Writer properties: no compression or statistics (the bytes depend on the
/// rows only), a dictionary for the label columns only, and the key-value
/// metadata of every file of `layout` tied to `fingerprint`.
fn properties(layout: &Layout, fingerprint: &str) -> Result<Arc<WriterProperties>, SweepError> {
    let schema_json =
        serde_json::to_string(layout.column_docs()).map_err(|e| SweepError::Io(e.to_string()))?;
    let kv = |k: &str, v: &str| KeyValue::new(k.to_owned(), v.to_owned());
    let mut b = WriterProperties::builder()
        .set_writer_version(WriterVersion::PARQUET_1_0)
        .set_statistics_enabled(EnabledStatistics::None)
        .set_dictionary_enabled(false)
        .set_created_by(format!("subdiv-lab {}", env!("CARGO_PKG_VERSION")))
        .set_key_value_metadata(Some(vec![
            kv(FORMAT_KEY, FORMAT),
            kv(FINGERPRINT_KEY, fingerprint.trim_end_matches('\n')),
            kv(SCHEMA_KEY, &schema_json),
            kv(NULLS_KEY, NULL_RULES),
        ]));
    for (name, t) in layout.names.iter().zip(&layout.types) {
        if *t == ColumnType::Label {
            b = b.set_column_dictionary_enabled(ColumnPath::from(name.as_str()), true);
        }
    }
    Ok(Arc::new(b.build()))
}

/// Label buffers kept per block for reuse: a label cell shares its label's
/// buffer (no copy per cell). Labels are few (class names, verdicts); a
/// label beyond this many gets a buffer of its own.
const SHARED_LABELS: usize = 64;

/// `x` as a float column stores it: NaN as the canonical NaN.
#[inline(always)]
fn stored(x: f64) -> f64 {
    if x.is_nan() {
        f64::NAN
    } else {
        x
    }
}

/// `t` as the CSV holds it after unquoting: line breaks become spaces (a CSV
/// line is one row), everything else is kept.
fn csv_text(t: &str) -> std::borrow::Cow<'_, str> {
    // Labels are short: a plain scan beats a vectorised search's set-up.
    if t.bytes().any(|b| b == b'\n' || b == b'\r') {
        std::borrow::Cow::Owned(t.replace(['\n', '\r'], " "))
    } else {
        std::borrow::Cow::Borrowed(t)
    }
}

/// One optional column of a [`TypedBlock`], as the `parquet` crate's column
/// writer takes it: a definition level per row (0 a null, 1 a value) and the
/// values of the rows that have one, in the vector of the column's type.
#[derive(Debug, Default)]
struct Cells {
    def: Vec<i16>,
    floats: Vec<f64>,
    texts: Vec<ByteArray>,
    bools: Vec<bool>,
}

impl Cells {
    /// The values of rows `rows` of this column, appended to `dst` (text
    /// buffers are moved, not shared: no reference count is touched).
    fn append_to(&mut self, dst: &mut Cells, rows: std::ops::Range<usize>) {
        let whole = rows.start == 0 && rows.end == self.def.len();
        let values = |r: std::ops::Range<usize>| {
            if whole {
                return 0..self.floats.len() + self.texts.len() + self.bools.len();
            }
            let before = |k: usize| self.def[..k].iter().filter(|&&d| d > 0).count();
            before(r.start)..before(r.end)
        };
        let v = values(rows.clone());
        dst.def.extend_from_slice(&self.def[rows]);
        if !self.floats.is_empty() {
            dst.floats.extend_from_slice(&self.floats[v]);
        } else if !self.texts.is_empty() {
            dst.texts
                .extend(self.texts[v].iter_mut().map(std::mem::take));
        } else if !self.bools.is_empty() {
            dst.bools.extend_from_slice(&self.bools[v]);
        }
    }

    fn clear(&mut self) {
        self.def.clear();
        self.floats.clear();
        self.texts.clear();
        self.bools.clear();
    }
}

/// The rows of one task of the sweep driver as typed columns (the typed path
/// of `sweep --format parquet`, math doc section 16.2): the evaluator's cells
/// go straight into the column vectors the `parquet` crate's writers take,
/// with the values the CSV of the same rows holds once read back. A number
/// in a float column is the `f64` itself (its CSV text is its shortest round
/// trip, which reads back to the same bits; a NaN is the canonical NaN, as
/// the text `NaN` reads back); a label is its text with line breaks as
/// spaces (as the CSV writes it); `true` / `false` in a boolean column are
/// booleans. A cell of another kind than its column's (not written by the
/// built-in evaluator) goes through its CSV text, as in [`ParquetRows`]'
/// [`Write`](std::io::Write) path, and a cell that text does not fit is
/// reported by [`ParquetRows::push_block`].
pub struct TypedBlock {
    /// The column types of the cells (after `valence`, before `error`).
    kinds: Vec<ColumnType>,
    /// Per row.
    ids: Vec<i64>,
    /// Per row.
    valences: Vec<i32>,
    /// The columns after `valence`, `error` last.
    cells: Vec<Cells>,
    /// The buffers of the labels met, each with no line break (so a cell
    /// found among them is its own CSV text).
    labels: Vec<ByteArray>,
    /// Column of the next cell.
    col: usize,
    /// Id of the current row.
    id: u64,
    /// The first cell that does not fit its column: (id, column, CSV text).
    fault: Option<(u64, usize, String)>,
    number: String,
    digits: zmij::Buffer,
}

impl std::fmt::Debug for TypedBlock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TypedBlock")
            .field("rows", &self.ids.len())
            .field("fault", &self.fault)
            .finish()
    }
}

impl TypedBlock {
    /// Rows in the block.
    fn rows(&self) -> usize {
        self.ids.len()
    }

    /// The column of the next cell.
    #[inline(always)]
    fn next(&mut self) -> &mut Cells {
        let k = self.col;
        self.col += 1;
        &mut self.cells[k - 2]
    }

    #[inline(always)]
    fn put_float(&mut self, x: f64) {
        let c = self.next();
        c.def.push(1);
        c.floats.push(x);
    }

    #[inline(always)]
    fn put_null(&mut self) {
        self.next().def.push(0);
    }

    /// Stores label `t` (its CSV text) in the next cell, sharing the buffer
    /// of an equal label met before (a label column holds a few distinct
    /// values, so a scan of those met is short).
    #[inline(always)]
    fn put_label(&mut self, t: &str) {
        let b = match self.labels.iter().find(|b| b.data() == t.as_bytes()) {
            Some(b) => b.clone(),
            None => self.new_label(t),
        };
        let c = self.next();
        c.def.push(1);
        c.texts.push(b);
    }

    /// The buffer of label `t` (its CSV text), not met before: kept for the
    /// next cells unless its text has a line break or the block keeps
    /// [`SHARED_LABELS`] already.
    #[cold]
    fn new_label(&mut self, t: &str) -> ByteArray {
        let text = csv_text(t);
        let b = ByteArray::from(Bytes::copy_from_slice(text.as_bytes()));
        let own_text = matches!(text, std::borrow::Cow::Borrowed(_));
        if self.labels.len() < SHARED_LABELS && own_text {
            self.labels.push(b.clone());
        }
        b
    }

    /// Appends the next cell from its CSV text `f`, read as the text path
    /// reads a CSV cell: empty is a null, a float column parses a
    /// number, a label column takes the text, a boolean column takes `true`
    /// / `false`. Text that does not fit is a null and the block's fault.
    fn push_text_cell(&mut self, f: &str) {
        let k = self.col;
        if f.is_empty() {
            return self.put_null();
        }
        let fits = match self.kinds[k - 2] {
            ColumnType::Float => match canonical_number(f, &mut self.number, &mut self.digits)
                .or_else(|| f.parse::<f64>().ok())
            {
                Some(x) => {
                    self.put_float(stored(x));
                    true
                }
                None => false,
            },
            ColumnType::Label => {
                self.put_label(f);
                true
            }
            ColumnType::Bool if f == "true" || f == "false" => {
                let c = self.next();
                c.def.push(1);
                c.bools.push(f == "true");
                true
            }
            _ => false,
        };
        if !fits {
            // Keep the rows aligned; the block is refused when written.
            self.put_null();
            if self.fault.is_none() {
                self.fault = Some((self.id, k, f.to_owned()));
            }
        }
    }

    /// [`num`](super::run::RowBlock::num) for a NaN, or for a number in a
    /// column that is not a float column (through its CSV text).
    #[cold]
    #[inline(never)]
    fn num_cold(&mut self, x: f64) {
        if self.kinds[self.col - 2] == ColumnType::Float {
            self.put_float(stored(x));
        } else {
            let mut t = String::new();
            push_number(&mut t, &mut self.digits, x);
            self.push_text_cell(&t);
        }
    }

    /// Appends rows `rows` of `src` (a block of the same layout; a row
    /// group collects the driver's blocks this way).
    fn append(&mut self, src: &mut TypedBlock, rows: std::ops::Range<usize>) {
        self.ids.extend_from_slice(&src.ids[rows.clone()]);
        self.valences.extend_from_slice(&src.valences[rows.clone()]);
        for (dst, c) in self.cells.iter_mut().zip(&mut src.cells) {
            c.append_to(dst, rows.clone());
        }
    }
}

impl RowBlock for TypedBlock {
    fn with_rows(layout: &Layout, rows: usize) -> Self {
        let kinds = layout.types.clone();
        // Each column's values sized for `rows` rows up front (no growth
        // while the block fills); `error` (the last) is usually null.
        let cells = kinds.iter().map(Some).chain([None]).map(|t| {
            let rows_of = |want: ColumnType| if t == Some(&want) { rows } else { 0 };
            Cells {
                def: Vec::with_capacity(rows),
                floats: Vec::with_capacity(rows_of(ColumnType::Float)),
                texts: Vec::with_capacity(rows_of(ColumnType::Label)),
                bools: Vec::with_capacity(rows_of(ColumnType::Bool)),
            }
        });
        let cells = cells.collect();
        TypedBlock {
            ids: Vec::with_capacity(rows),
            valences: Vec::with_capacity(rows),
            cells,
            kinds,
            labels: Vec::new(),
            col: 0,
            id: 0,
            fault: None,
            number: String::new(),
            digits: zmij::Buffer::new(),
        }
    }

    #[inline(always)]
    fn start(&mut self, id: u64, valence: usize) {
        self.id = id;
        self.ids.push(id as i64);
        let v = u32::try_from(valence).unwrap_or_else(|_| {
            if self.fault.is_none() {
                self.fault = Some((id, 1, valence.to_string()));
            }
            0
        });
        self.valences.push(v as i32);
        self.col = 2;
    }

    #[inline(always)]
    fn empty(&mut self) {
        self.put_null();
    }

    #[inline(always)]
    fn num(&mut self, x: f64) {
        // The common cell (a number, not NaN, in a float column) is one
        // branch; NaN and a number in another column take the cold path.
        if self.kinds[self.col - 2] == ColumnType::Float && !x.is_nan() {
            self.put_float(x);
        } else {
            self.num_cold(x);
        }
    }

    #[inline(always)]
    fn float(&mut self, x: f64) {
        debug_assert_eq!(self.kinds[self.col - 2], ColumnType::Float);
        if x.is_nan() {
            self.num_cold(x);
        } else {
            self.put_float(x);
        }
    }

    #[inline(always)]
    fn text(&mut self, t: &str) {
        if self.kinds[self.col - 2] == ColumnType::Label && !t.is_empty() {
            self.put_label(t);
        } else {
            self.push_text_cell(&csv_text(t));
        }
    }

    fn clear(&mut self) {
        self.ids.clear();
        self.valences.clear();
        self.cells.iter_mut().for_each(Cells::clear);
        self.col = 0;
        self.id = 0;
        self.fault = None;
    }

    #[inline(always)]
    fn end(&mut self, error: Option<&str>) {
        let c = self.next();
        match error {
            Some(e) if !e.is_empty() => {
                c.def.push(1);
                c.texts.push(ByteArray::from(csv_text(e).as_ref()));
            }
            _ => c.def.push(0),
        }
        self.col = 0;
    }
}

/// Writes the rows of `group` as one row group, column by column, each
/// handed whole to the `parquet` crate's column writer (its values and
/// definition levels; `id` and `valence` are required and have none).
fn write_group<W: std::io::Write + Send>(
    w: &mut SerializedFileWriter<W>,
    group: &TypedBlock,
) -> Result<(), SweepError> {
    let mut rg = w.next_row_group().map_err(pq_err)?;
    let mut j = 0usize;
    while let Some(mut col) = rg.next_column().map_err(pq_err)? {
        let c = j.checked_sub(2).and_then(|k| group.cells.get(k));
        let written = match (col.untyped(), j, c) {
            (ColumnWriter::Int64ColumnWriter(w), 0, _) => w.write_batch(&group.ids, None, None),
            (ColumnWriter::Int32ColumnWriter(w), 1, _) => {
                w.write_batch(&group.valences, None, None)
            }
            (ColumnWriter::DoubleColumnWriter(w), _, Some(c)) => {
                w.write_batch(&c.floats, Some(&c.def), None)
            }
            (ColumnWriter::ByteArrayColumnWriter(w), _, Some(c)) => {
                w.write_batch(&c.texts, Some(&c.def), None)
            }
            (ColumnWriter::BoolColumnWriter(w), _, Some(c)) => {
                w.write_batch(&c.bools, Some(&c.def), None)
            }
            _ => {
                return Err(SweepError::Io(format!(
                    "parquet: column {j} does not match its values"
                )))
            }
        };
        written.map_err(pq_err)?;
        col.close().map_err(pq_err)?;
        j += 1;
    }
    rg.close().map_err(pq_err)?;
    Ok(())
}

/// The callback of a dataset: part index, rows in the part, the part file's bytes.
pub type PartFn = Box<dyn FnMut(u64, u64, Vec<u8>) -> std::io::Result<()> + Send>;

/// Where [`ParquetRows`] puts its row groups.
enum Target {
    /// A dataset: each group is a part file of its own.
    Parts(PartFn),
    /// One file of many groups.
    File(SerializedFileWriter<Box<dyn std::io::Write + Send>>),
}

/// Rows of a sweep in Parquet form: takes the sweep driver's typed blocks
/// ([`run_parquet`]) or CSV lines (as a [`std::io::Write`]; the merge's
/// path), builds row groups of [`PART_ROWS`] rows and writes each completed
/// one: as a part file handed to the caller ([`ParquetRows::parts`]), or
/// into one file ([`ParquetRows::file`]). [`finish`](Self::finish) writes
/// the last, shorter group.
pub struct ParquetRows {
    schema: TypePtr,
    props: Arc<WriterProperties>,
    /// The open row group.
    group: TypedBlock,
    /// Rows written (in completed groups).
    written: u64,
    /// Index of the next part.
    next_part: u64,
    /// The bytes after the last complete CSV line written.
    pending: Vec<u8>,
    target: Option<Target>,
    layout: Layout,
}

impl std::fmt::Debug for ParquetRows {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParquetRows")
            .field("written", &self.written)
            .field("next_part", &self.next_part)
            .finish()
    }
}

impl ParquetRows {
    fn new(layout: &Layout, fingerprint: &str, target: Option<Target>) -> Result<Self, SweepError> {
        Ok(ParquetRows {
            group: TypedBlock::with_rows(layout, PART_ROWS),
            schema: schema_of(layout)?,
            props: properties(layout, fingerprint)?,
            written: 0,
            next_part: 0,
            pending: Vec::new(),
            target,
            layout: layout.clone(),
        })
    }

    /// Rows for `layout` tied to `fingerprint` ([`super::fingerprint_line`]),
    /// as part files from part `first_part` on (the parts before it are
    /// already committed): `commit(k, rows, bytes)` gets each.
    pub fn parts(
        layout: &Layout,
        fingerprint: &str,
        first_part: u64,
        commit: PartFn,
    ) -> Result<Self, SweepError> {
        let mut r = ParquetRows::new(layout, fingerprint, Some(Target::Parts(commit)))?;
        r.next_part = first_part;
        Ok(r)
    }

    /// Rows for `layout` tied to `fingerprint`, as the row groups of one file
    /// written to `out`.
    pub fn file(
        layout: &Layout,
        fingerprint: &str,
        out: Box<dyn std::io::Write + Send>,
    ) -> Result<Self, SweepError> {
        let mut r = ParquetRows::new(layout, fingerprint, None)?;
        let w = SerializedFileWriter::new(out, r.schema.clone(), r.props.clone());
        r.target = Some(Target::File(w.map_err(pq_err)?));
        Ok(r)
    }

    /// Appends the rows of `block` (built by the sweep driver for this
    /// layout), writing each group as it fills. A cell that does not fit
    /// its column is refused with a message naming the configuration, the
    /// column and the value.
    pub fn push_block(&mut self, block: &mut TypedBlock) -> Result<(), SweepError> {
        if let Some((id, k, f)) = &block.fault {
            let names = self.layout.column_names();
            let name = names.get(*k).map_or("?", String::as_str);
            let what = match k.checked_sub(2).and_then(|c| block.kinds.get(c)) {
                Some(ColumnType::Float) => "a number",
                Some(ColumnType::Bool) => "true or false",
                _ => "an unsigned integer",
            };
            return Err(SweepError::Io(format!(
                "parquet: configuration {id}: {name} = {f:?} is not {what}"
            )));
        }
        if block.kinds != self.group.kinds {
            return Err(SweepError::Io(format!(
                "parquet: a block of {} columns for {} columns",
                block.kinds.len() + 3,
                self.group.kinds.len() + 3
            )));
        }
        let mut start = 0;
        while start < block.rows() {
            let take = (block.rows() - start).min(PART_ROWS - self.group.rows());
            self.group.append(block, start..start + take);
            start += take;
            if self.group.rows() == PART_ROWS {
                self.commit_group()?;
            }
        }
        Ok(())
    }

    /// Writes the open group: a part file handed to the caller, or a row
    /// group of the one file.
    fn commit_group(&mut self) -> Result<(), SweepError> {
        let rows = self.group.rows();
        match self.target.as_mut() {
            Some(Target::Parts(commit)) => {
                let mut w = SerializedFileWriter::new(
                    Vec::with_capacity(rows * 8 * (self.group.kinds.len() + 3)),
                    self.schema.clone(),
                    self.props.clone(),
                )
                .map_err(pq_err)?;
                w.append_key_value_metadata(KeyValue::new(
                    PART_KEY.to_owned(),
                    self.next_part.to_string(),
                ));
                write_group(&mut w, &self.group)?;
                let bytes = w.into_inner().map_err(pq_err)?;
                commit(self.next_part, rows as u64, bytes)
                    .map_err(|e| SweepError::Io(e.to_string()))?;
            }
            Some(Target::File(w)) => write_group(w, &self.group)?,
            None => return Err(SweepError::Io("parquet: rows after the end".into())),
        }
        self.next_part += 1;
        self.written += rows as u64;
        self.group.clear();
        Ok(())
    }

    /// Writes the last (shorter) group, if any rows are open, and closes the
    /// file; returns the rows written.
    pub fn finish(mut self) -> Result<u64, SweepError> {
        if !self.pending.is_empty() {
            return Err(SweepError::Io(
                "parquet: the rows ended inside a line".into(),
            ));
        }
        if self.group.rows() > 0 {
            self.commit_group()?;
        }
        if let Some(Target::File(w)) = self.target.take() {
            w.close().map_err(pq_err)?;
        }
        Ok(self.written)
    }
}

/// CSV lines of the rows' layout (the merge's path, and the reference of
/// the typed path): each complete line is read back ([`Layout::parse`]) and
/// its cells appended as the sweep driver appends them.
impl std::io::Write for ParquetRows {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.pending.extend_from_slice(buf);
        let Some(end) = memchr::memrchr(b'\n', &self.pending) else {
            return Ok(buf.len());
        };
        let lines = std::mem::take(&mut self.pending);
        self.pending.extend_from_slice(&lines[end + 1..]);
        let text = std::str::from_utf8(&lines[..end])
            .map_err(|_| std::io::Error::other("parquet: a row is not UTF-8"))?;
        let mut block = TypedBlock::with_rows(&self.layout, 256);
        for line in text.split('\n') {
            let row = self
                .layout
                .parse(line)
                .map_err(|m| std::io::Error::other(format!("parquet: row {line:?}: {m}")))?;
            block.push_row(&row);
        }
        self.push_block(&mut block)
            .map_err(|e| std::io::Error::other(e.to_string()))?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The CSV lines (each with `\n`) of rows `from..to` of a sweep's table,
/// byte for byte those the sweep writes for them (numbers in shortest
/// round-trip form).
pub fn csv_lines(table: &Table, from: usize, to: usize) -> String {
    let mut s = String::new();
    let mut digits = zmij::Buffer::new();
    for r in from..to {
        for (k, c) in table.columns().iter().enumerate() {
            if k > 0 {
                s.push(',');
            }
            match c {
                Column::U64(v) => s.push_str(&v[r].to_string()),
                Column::U32(v) => s.push_str(&v[r].to_string()),
                Column::F64(v) => {
                    if let Some(x) = v[r] {
                        push_number(&mut s, &mut digits, x);
                    }
                }
                Column::Str(v) => {
                    if let Some(t) = &v[r] {
                        push_text(&mut s, t);
                    }
                }
                Column::Bool(v) => {
                    if let Some(b) = v[r] {
                        s.push_str(if b { "true" } else { "false" });
                    }
                }
            }
        }
        s.push('\n');
    }
    s
}

/// The number of rows and of columns of a Parquet file, from its footer
/// alone (a work estimate before [`read_table`]). A file that is not Parquet
/// or is torn is refused as by [`read_table`].
pub fn shape(bytes: &[u8]) -> Result<(u64, usize), SweepError> {
    check_magic(bytes)?;
    let md = parquet::file::metadata::ParquetMetaDataReader::new()
        .parse_and_finish(&Bytes::copy_from_slice(bytes))
        .map_err(pq_read_err)?;
    let f = md.file_metadata();
    Ok((
        u64::try_from(f.num_rows()).unwrap_or(0),
        f.schema_descr().num_columns(),
    ))
}

/// Refuses bytes that do not begin and end with [`MAGIC`] (not Parquet, or
/// a file torn before its footer was written).
fn check_magic(bytes: &[u8]) -> Result<(), SweepError> {
    let n = bytes.len();
    if n < 12 || &bytes[..4] != MAGIC || &bytes[n - 4..] != MAGIC {
        return Err(SweepError::Read(
            "not a Parquet file, or torn (no PAR1 footer at its end)".into(),
        ));
    }
    Ok(())
}

/// Reads a sweep's Parquet file from its bytes (the library does no I/O: the
/// caller reads the file, e.g. `std::fs::read`), returning the columns by
/// name. Every column must be of a type a sweep writes (`u64`, `u32`, `f64`,
/// string, `bool`); a file that is not Parquet, or is torn (no valid footer),
/// is refused with a message naming the problem. Each column of each row
/// group is decoded whole by the crate's typed column reader (its values and
/// definition levels: level 0 is a null).
///
/// ```
/// use subdiv_lab::sweep::output::parquet::read_table;
/// assert!(read_table(b"not parquet".to_vec()).is_err());
/// ```
pub fn read_table(bytes: impl Into<Bytes>) -> Result<Table, SweepError> {
    let bytes: Bytes = bytes.into();
    check_magic(&bytes)?;
    let reader = SerializedFileReader::new(bytes).map_err(pq_read_err)?;
    let md = reader.metadata();
    let key_value = md
        .file_metadata()
        .key_value_metadata()
        .map(|kv| {
            kv.iter()
                .map(|k| (k.key.clone(), k.value.clone().unwrap_or_default()))
                .collect()
        })
        .unwrap_or_default();
    let schema = md.file_metadata().schema_descr();
    let names: Vec<String> = schema
        .columns()
        .iter()
        .map(|c| c.name().to_owned())
        .collect();
    let mut columns: Vec<Column> = schema
        .columns()
        .iter()
        .map(|c| match c.physical_type() {
            PhysicalType::INT64 => Ok(Column::U64(Vec::new())),
            PhysicalType::INT32 => Ok(Column::U32(Vec::new())),
            PhysicalType::DOUBLE => Ok(Column::F64(Vec::new())),
            PhysicalType::BYTE_ARRAY => Ok(Column::Str(Vec::new())),
            PhysicalType::BOOLEAN => Ok(Column::Bool(Vec::new())),
            t => Err(SweepError::Read(format!(
                "parquet: column {} has type {t}, which a sweep does not write",
                c.name()
            ))),
        })
        .collect::<Result<_, _>>()?;
    for g in 0..reader.num_row_groups() {
        let group = reader.get_row_group(g).map_err(pq_read_err)?;
        let rows = usize::try_from(group.metadata().num_rows()).unwrap_or(0);
        for (k, col) in columns.iter_mut().enumerate() {
            let c = schema.column(k);
            let unsigned = matches!(
                c.logical_type_ref(),
                Some(LogicalType::Integer(IntType {
                    is_signed: false,
                    ..
                }))
            );
            let bad = |what: &str| {
                SweepError::Read(format!(
                    "parquet: column {} holds {what}, not a value a sweep writes there",
                    names[k]
                ))
            };
            let reader = group.get_column_reader(k).map_err(pq_read_err)?;
            // The integers of a required column (signed ones non-negative).
            let ints = |values: Vec<Option<i64>>| {
                let v: Option<Vec<i64>> = values.into_iter().collect();
                let v = v.ok_or_else(|| bad("a null"))?;
                match v.iter().find(|&&x| !unsigned && x < 0) {
                    Some(x) => Err(bad(&x.to_string())),
                    None => Ok(v),
                }
            };
            match (reader, col) {
                (ColumnReader::Int64ColumnReader(mut r), Column::U64(v)) => {
                    v.extend(ints(read_column(&mut r, rows)?)?.iter().map(|&x| x as u64));
                }
                (ColumnReader::Int32ColumnReader(mut r), Column::U32(v)) => {
                    let values = read_column(&mut r, rows)?;
                    let wide = values.into_iter().map(|x| x.map(i64::from)).collect();
                    v.extend(ints(wide)?.iter().map(|&x| x as u32));
                }
                (ColumnReader::DoubleColumnReader(mut r), Column::F64(v)) => {
                    v.extend(read_column(&mut r, rows)?);
                }
                (ColumnReader::BoolColumnReader(mut r), Column::Bool(v)) => {
                    v.extend(read_column(&mut r, rows)?);
                }
                (ColumnReader::ByteArrayColumnReader(mut r), Column::Str(v)) => {
                    for x in read_column(&mut r, rows)? {
                        let text = x.map(|b| String::from_utf8(b.data().to_vec()));
                        v.push(
                            text.transpose()
                                .map_err(|_| bad("text that is not UTF-8"))?,
                        );
                    }
                }
                _ => return Err(bad("values of another type")),
            }
        }
    }
    Table::new(names, columns)
        .map(|t| t.with_metadata(key_value))
        .map_err(|e| SweepError::Read(format!("parquet: {e}")))
}

/// The values of one flat column chunk of `rows` rows, `None` where its
/// definition level is 0 (a null; a required column has no levels).
fn read_column<T: parquet::data_type::DataType>(
    r: &mut parquet::column::reader::ColumnReaderImpl<T>,
    rows: usize,
) -> Result<Vec<Option<T::T>>, SweepError> {
    let (mut def, mut values) = (Vec::with_capacity(rows), Vec::with_capacity(rows));
    let (records, _, _) = r
        .read_records(rows, Some(&mut def), None, &mut values)
        .map_err(pq_read_err)?;
    if records != rows {
        return Err(SweepError::Read(format!(
            "parquet: a column chunk holds {records} rows where its row group has {rows}"
        )));
    }
    if def.is_empty() {
        return Ok(values.into_iter().map(Some).collect());
    }
    let mut values = values.into_iter();
    Ok(def
        .iter()
        .map(|&d| if d > 0 { values.next() } else { None })
        .collect())
}

impl super::run::BlockWriter<TypedBlock> for ParquetRows {
    fn write_block(&mut self, block: &mut TypedBlock) -> Result<(), SweepError> {
        self.push_block(block)
    }
    fn flush(&mut self) -> Result<(), SweepError> {
        Ok(())
    }
}

/// [`run`](super::run()) for Parquet, counting the evaluated configurations
/// in `evaluated` as the workers finish them: the rows go straight
/// from the evaluator's cells into typed column buffers (no CSV text in
/// between; math doc section 16.2), which `rows` cuts into parts. The values
/// and the summary are those of the CSV path (a test compares them).
#[allow(clippy::too_many_arguments)]
pub fn run_parquet<E, I>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: I,
    rows: &mut ParquetRows,
    summary: &mut Summary,
    progress: &mut dyn FnMut(u64),
    evaluated: &std::sync::atomic::AtomicU64,
) -> Result<u64, SweepError>
where
    E: Evaluate + ?Sized,
    I: IntoIterator<Item = u64>,
{
    super::run::drive::<E, TypedBlock, _, I>(
        plan, layout, eval, ids, rows, summary, progress, evaluated,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of every cell kind into `block`: floats, labels, booleans and
    /// nulls, each cell a function of its row and column.
    fn fill(block: &mut TypedBlock, rows: u64) {
        for r in 0..rows {
            block.start(r, 3 + (r % 4) as usize);
            for c in 2..block.kinds.len() + 2 {
                match (block.kinds[c - 2], (r + c as u64) % 5) {
                    (_, 0) => block.empty(),
                    (ColumnType::Float, _) => block.num(r as f64 * 100.0 + c as f64),
                    (ColumnType::Label, k) => block.text(["a", "b", "c", "d", "e"][k as usize]),
                    (ColumnType::Bool, k) => block.text(if k % 2 == 0 { "true" } else { "false" }),
                }
            }
            block.end(if r % 7 == 3 { Some("failed") } else { None });
        }
    }

    /// A cleared, reused block holds exactly the rows of a fresh one, and
    /// pieces of a block appended in turn give the block again (the values
    /// of a piece found from its definition levels).
    #[test]
    fn pieces_of_a_block_and_a_reused_block_keep_their_rows() {
        let spec = "name = \"g\"\nscheme = \"nurds\"\nvalences = [4]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 10\nseed = 1\n[columns]\nexact_certificate = true\n";
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        let layout = Layout::new(&plan);
        let mut whole = TypedBlock::with_rows(&layout, 70);
        fill(&mut whole, 70);
        let mut reused = TypedBlock::with_rows(&layout, 2);
        fill(&mut reused, 5);
        reused.clear();
        fill(&mut reused, 70);
        let mut source = TypedBlock::with_rows(&layout, 70);
        fill(&mut source, 70);
        let mut pieces = TypedBlock::with_rows(&layout, 0);
        for r in [0..20, 20..33, 33..70] {
            pieces.append(&mut source, r);
        }
        assert!(
            whole.kinds.contains(&ColumnType::Label) && whole.kinds.contains(&ColumnType::Bool)
        );
        let valences: Vec<i32> = (0..70).map(|r| 3 + r % 4).collect();
        for b in [&reused, &pieces] {
            assert_eq!(b.ids, (0..70).collect::<Vec<i64>>());
            assert_eq!(b.valences, valences);
            for (j, (x, y)) in b.cells.iter().zip(&whole.cells).enumerate() {
                assert_eq!(x.def, y.def, "column {j}");
                assert_eq!(x.floats, y.floats, "column {j}");
                assert_eq!(x.texts, y.texts, "column {j}");
                assert_eq!(x.bools, y.bools, "column {j}");
            }
        }
        // The float cells hold what was written.
        let j = (2..whole.kinds.len() + 2)
            .find(|&j| whole.kinds[j - 2] == ColumnType::Float)
            .unwrap();
        let rows = (0..70u64).filter(|r| (r + j as u64) % 5 != 0);
        let want: Vec<f64> = rows.map(|r| r as f64 * 100.0 + j as f64).collect();
        assert_eq!(pieces.cells[j - 2].floats, want);
        let errors = &pieces.cells[pieces.cells.len() - 1];
        let failed = (0..70).filter(|r| r % 7 == 3).count();
        assert_eq!(errors.texts.len(), failed);
    }

    /// A block split between two parts (its first 36 rows close the first
    /// part) keeps every row's error text, floats and nulls, in both parts,
    /// and the parts are complete Parquet files carrying their index and the
    /// fingerprint.
    #[test]
    fn a_block_split_between_parts_keeps_its_rows() {
        let spec = "name = \"g\"\nscheme = \"nurds\"\nvalences = [4]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 10\nseed = 1\n";
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        let layout = Layout::new(&plan);
        let first = PART_ROWS as u64 - 36;
        let mut a = TypedBlock::with_rows(&layout, first as usize);
        fill(&mut a, first);
        let mut b = TypedBlock::with_rows(&layout, 100);
        fill(&mut b, 100);
        let parts = Arc::new(std::sync::Mutex::new(Vec::new()));
        let sink = parts.clone();
        let commit: PartFn = Box::new(move |k, rows, bytes| {
            sink.lock().unwrap().push((k, rows, bytes));
            Ok(())
        });
        let mut rows = ParquetRows::parts(&layout, "fp", 5, commit).unwrap();
        rows.push_block(&mut a).unwrap();
        rows.push_block(&mut b).unwrap();
        assert_eq!(rows.finish().unwrap(), first + 100);
        let parts = parts.lock().unwrap();
        assert_eq!(
            parts.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
            vec![(5, PART_ROWS as u64), (6, 64)]
        );
        let tables: Vec<Table> = parts
            .iter()
            .map(|p| read_table(p.2.clone()).unwrap())
            .collect();
        assert_eq!(tables[1].metadata(PART_KEY), Some("6"));
        assert_eq!(tables[0].metadata(FINGERPRINT_KEY), Some("fp"));
        assert_eq!(tables[0].metadata(FORMAT_KEY), Some(FORMAT));
        // Row i of the dataset is row r of block a or b.
        let r_of = |i: usize| (i as u64).checked_sub(first).unwrap_or(i as u64);
        let column = |name: &str| -> Vec<Column> {
            tables
                .iter()
                .map(|t| t.column(name).unwrap().clone())
                .collect()
        };
        let errors: Vec<Option<String>> = column("error")
            .into_iter()
            .flat_map(|c| match c {
                Column::Str(v) => v,
                _ => panic!("error is not text"),
            })
            .collect();
        for (i, e) in errors.iter().enumerate() {
            let want = (r_of(i) % 7 == 3).then(|| "failed".to_owned());
            assert_eq!(*e, want, "error of row {i}");
        }
        let j = (2..a.kinds.len() + 2)
            .find(|&j| a.kinds[j - 2] == ColumnType::Float)
            .unwrap();
        let x: Vec<Option<f64>> = column(&layout.column_names()[j])
            .into_iter()
            .flat_map(|c| match c {
                Column::F64(v) => v,
                _ => panic!("not a float column"),
            })
            .collect();
        for (i, x) in x.iter().enumerate() {
            let r = r_of(i);
            let want = ((r + j as u64) % 5 != 0).then_some(r as f64 * 100.0 + j as f64);
            assert_eq!(*x, want, "column {j}, row {i}");
        }
    }
}
