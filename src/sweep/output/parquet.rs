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
    let parts: Vec<&str> = rest.split('-').collect();
    let num = |t: &str| {
        t.parse::<u64>()
            .ok()
            .filter(|_| t.bytes().all(|b| b.is_ascii_digit()))
    };
    let (shard, k) = match parts.as_slice() {
        [k] => (Shard::ALL, *k),
        [i, "of", n, k] => (format!("{}/{}", num(i)?, num(n)?).parse().ok()?, *k),
        _ => return None,
    };
    (k.len() >= 6).then_some(())?;
    let k = num(k)?;
    (part_name(shard, k) == name).then_some((shard, k))
}

fn pq_err(e: parquet::errors::ParquetError) -> SweepError {
    SweepError::Io(format!("parquet: {e}"))
}

/// A reader error of the `parquet` crate (reading an existing file).
fn pq_read_err(e: parquet::errors::ParquetError) -> SweepError {
    SweepError::Read(format!("parquet: {e}"))
}

/// The column types of a layout, `id` to `error`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Col {
    Id,
    Valence,
    Float,
    Label,
    Bool,
    Error,
}

fn columns_of(layout: &Layout) -> Vec<Col> {
    let mut v = vec![Col::Id, Col::Valence];
    v.extend(layout.types.iter().map(|t| match t {
        ColumnType::Float => Col::Float,
        ColumnType::Label => Col::Label,
        ColumnType::Bool => Col::Bool,
    }));
    v.push(Col::Error);
    v
}

/// The Parquet schema of `layout`'s rows.
fn schema_of(layout: &Layout) -> Result<TypePtr, SweepError> {
    let names = layout.column_names();
    let mut fields = Vec::with_capacity(names.len());
    for (name, col) in names.iter().zip(columns_of(layout)) {
        let unsigned = |bit_width| {
            let t = IntType {
                bit_width,
                is_signed: false,
            };
            Some(LogicalType::Integer(t))
        };
        let (phys, logical) = match col {
            Col::Id => (PhysicalType::INT64, unsigned(64)),
            Col::Valence => (PhysicalType::INT32, unsigned(32)),
            Col::Float => (PhysicalType::DOUBLE, None),
            Col::Label | Col::Error => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String)),
            Col::Bool => (PhysicalType::BOOLEAN, None),
        };
        let required = matches!(col, Col::Id | Col::Valence);
        let t = Type::primitive_type_builder(name, phys)
            .with_repetition(if required {
                Repetition::REQUIRED
            } else {
                Repetition::OPTIONAL
            })
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
    for (name, col) in layout.column_names().into_iter().zip(columns_of(layout)) {
        if col == Col::Label {
            b = b.set_column_dictionary_enabled(ColumnPath::from(name), true);
        }
    }
    Ok(Arc::new(b.build()))
}

/// Labels interned in order of first appearance: a label column's
/// dictionary (math doc section 16.2). A short linear search while there are
/// few labels (class names, verdicts), a hash map beyond.
#[derive(Debug, Default)]
struct Dict {
    entries: Vec<Box<str>>,
    /// The entry of the last label looked up (most rows repeat it).
    last: u32,
    map: std::collections::HashMap<Box<str>, u32>,
}

/// The index of a null label (no dictionary has `u32::MAX` entries: a row
/// group has [`PART_ROWS`] rows).
const NULL_INDEX: u32 = u32::MAX;

/// The bits of a null in a float column: a NaN whose payload no value
/// stored there has (every NaN value is stored as the canonical `f64::NAN`,
/// as its CSV text `NaN` reads back), so nulls need no separate levels.
const NULL_F64: u64 = 0x7ff8_5d1b_0000_0001;

/// A null in a boolean column (`0` false, `1` true).
const NULL_BOOL: u8 = 2;

impl Dict {
    /// Entries searched linearly before the hash map takes over.
    const LINEAR: usize = 16;

    /// The index of label `t`, if it is an entry.
    fn find(&self, t: &str) -> Option<u32> {
        if self.entries.len() <= Self::LINEAR {
            self.entries
                .iter()
                .position(|e| **e == *t)
                .map(|i| i as u32)
        } else {
            self.map.get(t).copied()
        }
    }

    /// The index of label `t`, a new entry if it is new.
    fn intern(&mut self, t: &str) -> u32 {
        if let Some(i) = self.find(t) {
            return i;
        }
        let i = self.entries.len() as u32;
        self.entries.push(t.into());
        if self.entries.len() == Self::LINEAR + 1 {
            for (k, e) in self.entries.iter().enumerate() {
                self.map.insert(e.clone(), k as u32);
            }
        } else if self.entries.len() > Self::LINEAR + 1 {
            self.map.insert(t.into(), i);
        }
        i
    }

    /// The index of label `t` as the CSV holds it ([`csv_text`]), a new
    /// entry if it is new. The entries hold no line breaks, so a `t` found
    /// among them is its own CSV text: only a new label is scanned.
    #[inline(always)]
    fn label_index(&mut self, t: &str) -> u32 {
        if self
            .entries
            .get(self.last as usize)
            .is_some_and(|e| **e == *t)
        {
            return self.last;
        }
        let i = match self.find(t) {
            Some(i) => i,
            None => self.intern(&csv_text(t)),
        };
        self.last = i;
        i
    }

    fn clear(&mut self) {
        self.entries.clear();
        self.map.clear();
        self.last = 0;
    }
}

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

/// The rows of one task of the sweep driver as typed cells, row after row
/// (the typed path of `sweep --format parquet`, math doc section 16.2): the
/// evaluator's cells go straight into the block, with the values the CSV
/// of the same rows holds once read back. A number in a float column is the
/// `f64` itself (its CSV text is its shortest round trip, which reads back to
/// the same bits; a NaN is the canonical NaN, as the text `NaN` reads back);
/// a label is its text with line breaks as spaces (as the CSV writes it);
/// `true` / `false` in a boolean column are booleans. A cell of another kind
/// than its column's (not written by the built-in evaluator) goes through its
/// CSV text, as in [`ParquetRows`]' [`Write`](std::io::Write) path, and a cell
/// that text does not fit is reported by [`ParquetRows::push_block`].
pub struct TypedBlock {
    /// The column types, `id` to `error`.
    kinds: Vec<Col>,
    /// Cells per row: the columns between `valence` and `error`.
    stride: usize,
    /// Per row, `cap` of them (the rows so far are the first `rows`).
    ids: Vec<i64>,
    /// Per row, `cap` of them.
    valences: Vec<i32>,
    /// The cells, column after column, `cap` rows per column: a float's
    /// bits, a label's index into its column's block dictionary, a boolean as
    /// 0 / 1, or the column's null sentinel ([`null_bits`]). One store per
    /// cell, and a column of the block is one slice when it is appended to a
    /// row group.
    cells: Vec<u64>,
    /// Rows per column of `cells` (grown, doubling, when a row does not fit).
    cap: usize,
    /// Index in `cells` of the next cell of the current row.
    at: usize,
    /// Per column: the labels of this block (empty for other columns).
    dicts: Vec<Dict>,
    /// The rows with an error (row in the block, CSV text), in row order.
    errors: Vec<(usize, String)>,
    /// Per column: the nulls of a float column in the block (a block that
    /// joins a group whole adds them without a pass over its cells).
    float_nulls: Vec<usize>,
    /// Column of the next cell.
    col: usize,
    rows: usize,
    /// Id of the current row.
    id: u64,
    /// The first cell that does not fit its column: (id, column, CSV text).
    fault: Option<(u64, usize, String)>,
    number: String,
    digits: zmij::Buffer,
}

/// The null of a cell column of type `kind` in [`TypedBlock`]'s cells.
fn null_bits(kind: Col) -> u64 {
    match kind {
        Col::Float => NULL_F64,
        Col::Label => u64::from(NULL_INDEX),
        Col::Bool => u64::from(NULL_BOOL),
        // Not cell columns.
        Col::Id | Col::Valence | Col::Error => 0,
    }
}

impl std::fmt::Debug for TypedBlock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TypedBlock")
            .field("rows", &self.rows)
            .field("fault", &self.fault)
            .finish()
    }
}

impl TypedBlock {
    /// Appends the next cell from its CSV text `f`, read as the text path
    /// reads a CSV cell: empty is a null, a float column parses a
    /// number, a label column interns it, a boolean column takes `true` /
    /// `false`. Text that does not fit is a null and the block's fault.
    fn push_text_cell(&mut self, f: &str) {
        let k = self.col;
        let kind = self.kinds[k];
        if f.is_empty() {
            self.put_null(kind);
            return;
        }
        let cell = match kind {
            Col::Float => canonical_number(f, &mut self.number, &mut self.digits)
                .or_else(|| f.parse::<f64>().ok())
                .map(|x| stored(x).to_bits()),
            Col::Label => Some(u64::from(self.dicts[k].label_index(f))),
            Col::Bool => match f {
                "true" => Some(1),
                "false" => Some(0),
                _ => None,
            },
            Col::Id | Col::Valence | Col::Error => None,
        };
        match cell {
            Some(c) => self.put(c),
            None => {
                // Keep the rows aligned; the block is refused when written.
                self.put_null(kind);
                if self.fault.is_none() {
                    self.fault = Some((self.id, k, f.to_owned()));
                }
            }
        }
    }

    /// [`num`](super::run::RowBlock::num) for a NaN, or for a number in a
    /// column that is not a float column (through its CSV text).
    #[cold]
    #[inline(never)]
    fn num_cold(&mut self, x: f64) {
        if self.kinds[self.col] == Col::Float {
            self.put(stored(x).to_bits());
        } else {
            let mut t = String::new();
            push_number(&mut t, &mut self.digits, x);
            self.push_text_cell(&t);
        }
    }

    /// Stores a null in the next cell (of a `kind` column), counting the
    /// nulls of a float column.
    #[inline(always)]
    fn put_null(&mut self, kind: Col) {
        if kind == Col::Float {
            self.float_nulls[self.col] += 1;
        }
        self.put(null_bits(kind));
    }

    /// Stores the next cell of the current row.
    #[inline(always)]
    fn put(&mut self, cell: u64) {
        self.cells[self.at] = cell;
        self.at += self.cap;
        self.col += 1;
    }

    /// Room for one more row: doubles `cap`, moving each column to its new
    /// place.
    #[cold]
    fn grow(&mut self) {
        let cap = (2 * self.cap).max(16);
        let mut cells = vec![0u64; self.stride * cap];
        for (k, col) in self.cells.chunks_exact(self.cap.max(1)).enumerate() {
            cells[k * cap..k * cap + self.rows].copy_from_slice(&col[..self.rows]);
        }
        self.cells = cells;
        self.cap = cap;
        self.ids.resize(cap, 0);
        self.valences.resize(cap, 0);
    }

    /// The cells of column `j` (a cell column) in rows `rows`.
    fn column(&self, j: usize, rows: std::ops::Range<usize>) -> &[u64] {
        let base = (j - 2) * self.cap;
        &self.cells[base + rows.start..base + rows.end]
    }

    /// Appends rows `rows` of `src` (a block of the same layout; a row
    /// group collects the driver's blocks this way). Labels are re-interned
    /// in row order, so that the dictionary stays in order of first
    /// appearance whatever the blocks were.
    fn append(&mut self, src: &TypedBlock, rows: std::ops::Range<usize>) {
        let n = rows.len();
        while self.rows + n > self.cap {
            self.grow();
        }
        let (at, whole) = (self.rows, rows == (0..src.rows));
        self.ids[at..at + n].copy_from_slice(&src.ids[rows.clone()]);
        self.valences[at..at + n].copy_from_slice(&src.valences[rows.clone()]);
        // The block's errors are in row order.
        let first = src.errors.partition_point(|(r, _)| *r < rows.start);
        for (r, e) in src.errors[first..]
            .iter()
            .take_while(|(r, _)| *r < rows.end)
        {
            self.errors.push((at + r - rows.start, e.clone()));
        }
        for j in 2..self.kinds.len() - 1 {
            let cells = src.column(j, rows.clone());
            let base = (j - 2) * self.cap + at;
            let dst = &mut self.cells[base..base + n];
            match self.kinds[j] {
                Col::Label => {
                    // Block entry -> group entry, assigned at first use.
                    let mut map = vec![NULL_INDEX; src.dicts[j].entries.len()];
                    for (d, &b) in dst.iter_mut().zip(cells) {
                        let b = b as u32;
                        if b != NULL_INDEX && map[b as usize] == NULL_INDEX {
                            map[b as usize] =
                                self.dicts[j].intern(&src.dicts[j].entries[b as usize]);
                        }
                        *d = u64::from(if b == NULL_INDEX { b } else { map[b as usize] });
                    }
                }
                kind => {
                    dst.copy_from_slice(cells);
                    if kind == Col::Float {
                        self.float_nulls[j] += if whole {
                            src.float_nulls[j]
                        } else {
                            cells.iter().filter(|&&b| b == NULL_F64).count()
                        };
                    }
                }
            }
        }
        self.rows += n;
    }
}

impl RowBlock for TypedBlock {
    fn with_rows(layout: &Layout, rows: usize) -> Self {
        let kinds = columns_of(layout);
        let stride = kinds.len() - 3;
        TypedBlock {
            stride,
            ids: vec![0; rows],
            valences: vec![0; rows],
            cells: vec![0; rows * stride],
            cap: rows,
            at: 0,
            dicts: kinds.iter().map(|_| Dict::default()).collect(),
            errors: Vec::new(),
            float_nulls: vec![0; kinds.len()],
            kinds,
            col: 0,
            rows: 0,
            id: 0,
            fault: None,
            number: String::new(),
            digits: zmij::Buffer::new(),
        }
    }

    #[inline(always)]
    fn start(&mut self, id: u64, valence: usize) {
        if self.rows == self.cap {
            self.grow();
        }
        self.id = id;
        let r = self.rows;
        self.ids[r] = id as i64;
        self.valences[r] = match u32::try_from(valence) {
            Ok(n) => n as i32,
            Err(_) => {
                if self.fault.is_none() {
                    self.fault = Some((id, 1, valence.to_string()));
                }
                0
            }
        };
        self.col = 2;
        self.at = r;
    }

    #[inline(always)]
    fn empty(&mut self) {
        self.put_null(self.kinds[self.col]);
    }

    #[inline(always)]
    fn num(&mut self, x: f64) {
        // The common cell (a number, not NaN, in a float column) is one
        // branch; NaN and a number in another column take the cold path.
        if self.kinds[self.col] == Col::Float && !x.is_nan() {
            self.put(x.to_bits());
        } else {
            self.num_cold(x);
        }
    }

    #[inline(always)]
    fn float(&mut self, x: f64) {
        debug_assert_eq!(self.kinds[self.col], Col::Float);
        if x.is_nan() {
            self.num_cold(x);
        } else {
            self.put(x.to_bits());
        }
    }

    #[inline(always)]
    fn text(&mut self, t: &str) {
        let k = self.col;
        if self.kinds[k] == Col::Label && !t.is_empty() {
            let i = self.dicts[k].label_index(t);
            self.put(u64::from(i));
        } else {
            self.push_text_cell(&csv_text(t));
        }
    }

    fn clear(&mut self) {
        self.errors.clear();
        self.float_nulls.fill(0);
        self.at = 0;
        // Only label columns have entries.
        for (d, kind) in self.dicts.iter_mut().zip(&self.kinds) {
            if *kind == Col::Label {
                d.clear();
            }
        }
        self.col = 0;
        self.rows = 0;
        self.id = 0;
        self.fault = None;
    }

    #[inline(always)]
    fn end(&mut self, error: Option<&str>) {
        match error {
            Some(e) if !e.is_empty() => self.errors.push((self.rows, csv_text(e).into_owned())),
            _ => {}
        }
        self.col = 0;
        self.rows += 1;
    }
}

/// Writes the rows of `group` as one row group, column by column, with the
/// `parquet` crate's column writers: a null (the column's sentinel,
/// [`null_bits`]) becomes definition level 0, every other value level 1.
fn write_group<W: std::io::Write + Send>(
    w: &mut SerializedFileWriter<W>,
    group: &TypedBlock,
) -> Result<(), SweepError> {
    let rows = group.rows;
    let mut rg = w.next_row_group().map_err(pq_err)?;
    let mut def: Vec<i16> = Vec::with_capacity(rows);
    let mut j = 0;
    while let Some(mut col) = rg.next_column().map_err(pq_err)? {
        let kind = group.kinds.get(j).copied();
        let cells = match kind {
            Some(Col::Float | Col::Label | Col::Bool) => group.column(j, 0..rows),
            _ => &[],
        };
        let null = kind.map_or(0, null_bits);
        def.clear();
        def.extend(cells.iter().map(|&c| i16::from(c != null)));
        let present = cells.iter().copied().filter(|&c| c != null);
        let written = match (col.untyped(), kind) {
            (ColumnWriter::Int64ColumnWriter(c), Some(Col::Id)) => {
                c.write_batch(&group.ids[..rows], None, None)
            }
            (ColumnWriter::Int32ColumnWriter(c), Some(Col::Valence)) => {
                c.write_batch(&group.valences[..rows], None, None)
            }
            (ColumnWriter::DoubleColumnWriter(c), Some(Col::Float)) => {
                if group.float_nulls[j] == 0 {
                    c.write_batch(bytemuck::cast_slice(cells), Some(&def), None)
                } else {
                    let v: Vec<f64> = present.map(f64::from_bits).collect();
                    c.write_batch(&v, Some(&def), None)
                }
            }
            (ColumnWriter::ByteArrayColumnWriter(c), Some(Col::Label)) => {
                // One buffer per label, shared by its cells (no copy per cell).
                let entries: Vec<ByteArray> = group.dicts[j]
                    .entries
                    .iter()
                    .map(|e| ByteArray::from(Bytes::copy_from_slice(e.as_bytes())))
                    .collect();
                let v: Vec<ByteArray> = present.map(|i| entries[i as usize].clone()).collect();
                c.write_batch(&v, Some(&def), None)
            }
            (ColumnWriter::ByteArrayColumnWriter(c), Some(Col::Error)) => {
                def.resize(rows, 0);
                for (r, _) in &group.errors {
                    def[*r] = 1;
                }
                let v: Vec<ByteArray> = group
                    .errors
                    .iter()
                    .map(|(_, t)| ByteArray::from(t.as_str()))
                    .collect();
                c.write_batch(&v, Some(&def), None)
            }
            (ColumnWriter::BoolColumnWriter(c), Some(Col::Bool)) => {
                let v: Vec<bool> = present.map(|b| b == 1).collect();
                c.write_batch(&v, Some(&def), None)
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
    names: Vec<String>,
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
    fn new(layout: &Layout, fingerprint: &str, target: Target) -> Result<Self, SweepError> {
        Ok(ParquetRows {
            group: TypedBlock::with_rows(layout, PART_ROWS),
            names: layout.column_names(),
            schema: schema_of(layout)?,
            props: properties(layout, fingerprint)?,
            written: 0,
            next_part: 0,
            pending: Vec::new(),
            target: Some(target),
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
        let mut r = ParquetRows::new(layout, fingerprint, Target::Parts(commit))?;
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
        let schema = schema_of(layout)?;
        let props = properties(layout, fingerprint)?;
        let w = SerializedFileWriter::new(out, schema, props).map_err(pq_err)?;
        ParquetRows::new(layout, fingerprint, Target::File(w))
    }

    /// Appends the rows of `block` (built by the sweep driver for this
    /// layout), writing each group as it fills. A cell that does not fit
    /// its column is refused with a message naming the configuration, the
    /// column and the value.
    pub fn push_block(&mut self, block: &TypedBlock) -> Result<(), SweepError> {
        if let Some((id, k, f)) = &block.fault {
            let name = self.names.get(*k).map_or("?", String::as_str);
            let what = match block.kinds.get(*k) {
                Some(Col::Float) => "a number",
                Some(Col::Bool) => "true or false",
                _ => "an unsigned integer",
            };
            return Err(SweepError::Io(format!(
                "parquet: configuration {id}: {name} = {f:?} is not {what}"
            )));
        }
        if block.kinds != self.group.kinds {
            return Err(SweepError::Io(format!(
                "parquet: a block of {} columns for {} columns",
                block.kinds.len(),
                self.group.kinds.len()
            )));
        }
        let mut start = 0;
        while start < block.rows {
            let take = (block.rows - start).min(PART_ROWS - self.group.rows);
            self.group.append(block, start..start + take);
            start += take;
            if self.group.rows == PART_ROWS {
                self.commit_group()?;
            }
        }
        Ok(())
    }

    /// Writes the open group: a part file handed to the caller, or a row
    /// group of the one file.
    fn commit_group(&mut self) -> Result<(), SweepError> {
        let rows = self.group.rows;
        match self.target.as_mut() {
            Some(Target::Parts(commit)) => {
                let mut w = SerializedFileWriter::new(
                    Vec::with_capacity(rows * 8 * self.group.kinds.len()),
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
        if self.group.rows > 0 {
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
        self.push_block(&block)
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
            match (reader, col) {
                (ColumnReader::Int64ColumnReader(mut r), Column::U64(v)) => {
                    for x in required(read_column(&mut r, rows)?).ok_or_else(|| bad("a null"))? {
                        if !unsigned && x < 0 {
                            return Err(bad(&x.to_string()));
                        }
                        v.push(x as u64);
                    }
                }
                (ColumnReader::Int32ColumnReader(mut r), Column::U32(v)) => {
                    for x in required(read_column(&mut r, rows)?).ok_or_else(|| bad("a null"))? {
                        if !unsigned && x < 0 {
                            return Err(bad(&x.to_string()));
                        }
                        v.push(x as u32);
                    }
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

/// The values of a column that holds no null, else `None`.
fn required<T>(values: Vec<Option<T>>) -> Option<Vec<T>> {
    values.into_iter().collect()
}

impl super::run::BlockWriter<TypedBlock> for ParquetRows {
    fn write_block(&mut self, block: &TypedBlock) -> Result<(), SweepError> {
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
            for c in 2..block.kinds.len() - 1 {
                match (block.kinds[c], (r + c as u64) % 5) {
                    (_, 0) => block.empty(),
                    (Col::Float, _) => block.num(r as f64 * 100.0 + c as f64),
                    (Col::Label, k) => block.text(["a", "b", "c", "d", "e"][k as usize]),
                    (Col::Bool, k) => block.text(if k % 2 == 0 { "true" } else { "false" }),
                    _ => block.empty(),
                }
            }
            block.end(if r % 7 == 3 { Some("failed") } else { None });
        }
    }

    /// A block that starts with room for 2 rows and grows (doubling, the
    /// columns moved) holds exactly the rows of one that never grows, and
    /// so does a cleared, reused block.
    #[test]
    fn a_block_that_grows_keeps_its_rows() {
        let spec = "name = \"g\"\nscheme = \"nurds\"\nvalences = [4]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 10\nseed = 1\n[columns]\nexact_certificate = true\n";
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        let layout = Layout::new(&plan);
        let rows = 70u64;
        let mut roomy = TypedBlock::with_rows(&layout, rows as usize);
        fill(&mut roomy, rows);
        let mut small = TypedBlock::with_rows(&layout, 2);
        fill(&mut small, 5);
        small.clear();
        fill(&mut small, rows);
        assert!(small.cap >= rows as usize && small.cap < roomy.cap + 64);
        assert!(roomy.kinds.contains(&Col::Label) && roomy.kinds.contains(&Col::Bool));
        assert_eq!(small.rows, roomy.rows);
        assert_eq!(small.ids[..70], roomy.ids[..70]);
        assert_eq!(small.valences[..70], roomy.valences[..70]);
        assert_eq!(small.ids[..70], (0..70).collect::<Vec<i64>>());
        let valences: Vec<i32> = (0..70).map(|r| 3 + r % 4).collect();
        assert_eq!(small.valences[..70], valences);
        assert_eq!(small.errors, roomy.errors);
        for j in 2..roomy.kinds.len() - 1 {
            assert_eq!(small.column(j, 0..70), roomy.column(j, 0..70), "column {j}");
            assert_eq!(
                small.column(j, 20..33),
                roomy.column(j, 20..33),
                "column {j}"
            );
        }
        // The float cells hold what was written.
        let j = (2..roomy.kinds.len() - 1)
            .find(|&j| roomy.kinds[j] == Col::Float)
            .unwrap();
        for (r, &bits) in small.column(j, 0..70).iter().enumerate() {
            let want = if (r + j) % 5 == 0 {
                NULL_F64
            } else {
                (r as f64 * 100.0 + j as f64).to_bits()
            };
            assert_eq!(bits, want, "row {r}");
        }
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
        rows.push_block(&a).unwrap();
        rows.push_block(&b).unwrap();
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
        let j = (2..a.kinds.len() - 1)
            .find(|&j| a.kinds[j] == Col::Float)
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
