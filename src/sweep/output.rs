//! CSV layout, row formatting and parsing, the streaming sweep driver and the
//! shard merge.
//!
//! The CSV has a header and one line per configuration:
//!
//! ```text
//! id,valence,<coordinates>,<results>,error
//! ```
//!
//! Coordinates are named for the largest valence of the sweep (`r0..r{N-1}`,
//! `p0..p{N-1},q0..q{N-1}`, ...); a row of a smaller valence leaves the extra
//! cells empty. Numbers are written in the shortest round-trip form, Ryu's format (reading a
//! cell back gives the same `f64` bit for bit), so a summary rebuilt from the CSV
//! equals the one accumulated while writing. Text cells never contain line
//! breaks, so every line is one row; a line without its final `\n` is a torn
//! write.

use super::eval::{result_columns, Cell, CellSink, Evaluate};
use super::plan::{Configuration, Plan, Shard};
use super::summary::{PartialSummary, Summary};
use super::SweepError;
use crate::spectral::kernel::BATCH;
use rayon::prelude::*;
use std::collections::BinaryHeap;
use std::io::Write;

mod verify;
pub use verify::{
    check_fingerprint, fingerprint_digest, fingerprint_line, fingerprint_shard, LineFault,
    Verifier, PIECE_BYTES, RECHECK_SAMPLE,
};

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

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Numeric,
    Text,
}

/// One CSV row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Configuration id.
    pub id: u64,
    /// Valence.
    pub valence: usize,
    /// Coordinate cells then result cells, in column order.
    pub cells: Vec<Cell>,
    /// The evaluation error, if the configuration failed.
    pub error: Option<String>,
}

/// The columns of a sweep's CSV.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    names: Vec<String>,
    kinds: Vec<Kind>,
    coordinates: usize,
    class: Option<usize>,
    numeric: Vec<(usize, String)>,
}

impl Layout {
    /// The layout of `plan`'s CSV.
    pub fn new(plan: &Plan) -> Layout {
        let mut names = Vec::new();
        let mut kinds = Vec::new();
        for c in plan.coordinate_columns() {
            names.push(c);
            kinds.push(Kind::Numeric);
        }
        let coordinates = names.len();
        for c in result_columns(&plan.spec().columns) {
            names.push(c.name.to_owned());
            kinds.push(if c.numeric { Kind::Numeric } else { Kind::Text });
        }
        let class = names.iter().position(|n| n == "class");
        let numeric = names
            .iter()
            .zip(&kinds)
            .enumerate()
            .filter(|(_, (_, k))| **k == Kind::Numeric)
            .map(|(i, (n, _))| (i, n.clone()))
            .collect();
        Layout {
            names,
            kinds,
            coordinates,
            class,
            numeric,
        }
    }

    /// Number of cells (coordinates + results) of a row.
    pub fn cells(&self) -> usize {
        self.names.len()
    }

    /// Number of coordinate cells.
    pub fn coordinate_cells(&self) -> usize {
        self.coordinates
    }

    /// The header line (with `\n`).
    pub fn header(&self) -> String {
        let mut s = String::from("id,valence");
        for n in &self.names {
            s.push(',');
            s.push_str(n);
        }
        s.push_str(",error\n");
        s
    }

    /// Writes the header.
    pub fn write_header<W: Write>(&self, out: &mut W) -> Result<(), SweepError> {
        out.write_all(self.header().as_bytes())?;
        Ok(())
    }

    /// Numeric cells: (cell index, column name).
    pub fn numeric_columns(&self) -> &[(usize, String)] {
        &self.numeric
    }

    /// The number in cell `pos` of `row`, if any.
    pub fn number_at(&self, row: &Row, pos: usize) -> Option<f64> {
        match row.cells.get(pos) {
            Some(Cell::Num(x)) => Some(*x),
            _ => None,
        }
    }

    /// The `class` cell of `row`, if the sweep computes it and the row has one.
    pub fn class_of<'a>(&self, row: &'a Row) -> Option<&'a str> {
        match row.cells.get(self.class?) {
            Some(Cell::Text(t)) => Some(t),
            _ => None,
        }
    }

    /// The CSV line of `row` (with `\n`).
    pub fn format(&self, row: &Row) -> String {
        let mut s = String::with_capacity(32 + 24 * row.cells.len());
        self.format_into(row, &mut s);
        s
    }

    /// Appends the CSV line of `row` (with `\n`) to `s`.
    pub fn format_into(&self, row: &Row, s: &mut String) {
        let mut digits = zmij::Buffer::new();
        let mut ibuf = itoa_buf();
        s.push_str(small_uint(row.id, &mut ibuf));
        s.push(',');
        s.push_str(small_uint(row.valence as u64, &mut ibuf));
        for c in &row.cells {
            s.push(',');
            match c {
                Cell::Empty => {}
                Cell::Num(x) => push_number(s, &mut digits, *x),
                Cell::Text(t) => push_text(s, t),
            }
        }
        s.push(',');
        if let Some(e) = &row.error {
            push_text(s, e);
        }
        s.push('\n');
    }

    /// Parses one line (without `\n`) back into a row.
    pub fn parse(&self, line: &str) -> Result<Row, String> {
        let fields = split_csv_line(line)?;
        if fields.len() != self.names.len() + 3 {
            return Err(format!(
                "expected {} fields, found {}",
                self.names.len() + 3,
                fields.len()
            ));
        }
        let id: u64 = fields[0]
            .parse()
            .map_err(|_| format!("id {:?} is not an integer", fields[0]))?;
        let valence: usize = fields[1]
            .parse()
            .map_err(|_| format!("valence {:?} is not an integer", fields[1]))?;
        let mut cells = Vec::with_capacity(self.names.len());
        for ((f, k), name) in fields[2..2 + self.names.len()]
            .iter()
            .zip(&self.kinds)
            .zip(&self.names)
        {
            cells.push(if f.is_empty() {
                Cell::Empty
            } else {
                match k {
                    Kind::Numeric => Cell::Num(
                        f.parse()
                            .map_err(|_| format!("{name} = {f:?} is not a number"))?,
                    ),
                    Kind::Text => Cell::Text(f.clone()),
                }
            });
        }
        let e = &fields[fields.len() - 1];
        Ok(Row {
            id,
            valence,
            cells,
            error: (!e.is_empty()).then(|| e.clone()),
        })
    }

    fn coordinate_row(&self, plan: &Plan, c: &super::Configuration) -> Vec<Cell> {
        let mut cells = vec![Cell::Empty; self.coordinates];
        for (k, x) in c.coordinates.iter().enumerate() {
            cells[plan.coordinate_column(c.valence, k)] = Cell::Num(*x);
        }
        cells
    }

    /// Evaluates configuration `id` into a row.
    pub fn row<E: Evaluate + ?Sized>(&self, plan: &Plan, eval: &E, id: u64) -> Row {
        let c = match plan.configuration(id) {
            Ok(c) => c,
            Err(e) => {
                return Row {
                    id,
                    valence: 0,
                    cells: vec![Cell::Empty; self.names.len()],
                    error: Some(e.to_string()),
                }
            }
        };
        let mut cells = self.coordinate_row(plan, &c);
        let n_results = self.names.len() - self.coordinates;
        let error = match plan.scheme(&c).and_then(|s| eval.evaluate(plan, &c, &s)) {
            Ok(r) if r.len() == n_results => {
                cells.extend(r);
                None
            }
            Ok(r) => {
                cells.resize(self.names.len(), Cell::Empty);
                Some(format!(
                    "internal: evaluator returned {} cells for {n_results} result columns",
                    r.len()
                ))
            }
            Err(e) => {
                cells.resize(self.names.len(), Cell::Empty);
                Some(e.to_string())
            }
        };
        Row {
            id: c.id,
            valence: c.valence,
            cells,
            error,
        }
    }
}

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
struct Staged {
    config: Configuration,
    sampler: Vec<f64>,
    stage: Stage,
    /// Coordinate cells of the current row (by column).
    coordinates: Vec<Option<f64>>,
    error: Option<String>,
    valence: usize,
}

impl Staged {
    fn new() -> Self {
        Staged {
            config: Configuration {
                id: 0,
                valence: 0,
                coordinates: Vec::new(),
            },
            sampler: Vec::new(),
            stage: Stage::default(),
            coordinates: Vec::new(),
            error: None,
            valence: 0,
        }
    }
}

/// Reusable per-task storage of the sweep driver: [`BATCH`] staged rows (the
/// driver evaluates configurations in batches, [`Evaluate::write_results_batch`]).
struct Scratch {
    rows: [Staged; BATCH],
    digits: zmij::Buffer,
}

impl Scratch {
    fn new() -> Self {
        Scratch {
            rows: std::array::from_fn(|_| Staged::new()),
            digits: zmij::Buffer::new(),
        }
    }
}

impl Layout {
    /// The sweep driver's path for one configuration: evaluates `id`, appends
    /// its CSV line to `text` and adds it to `part`. Equal, byte for byte and
    /// for the summary, to [`row`](Self::row) + [`format_into`](Self::format_into)
    /// + [`Summary::add`] (a test checks it), but allocation-free after warm-up.
    fn append_row<E: Evaluate + ?Sized>(
        &self,
        plan: &Plan,
        eval: &E,
        id: u64,
        sc: &mut Scratch,
        text: &mut String,
        part: &mut PartialSummary,
    ) {
        let row = &mut sc.rows[0];
        if let Some(scheme) = self.load(plan, id, row) {
            let r = eval.write_results(plan, &row.config, &scheme, &mut row.stage);
            self.check_results(row, r);
        }
        self.emit(id, row, &mut sc.digits, text, part);
    }

    /// [`append_row`](Self::append_row) for [`BATCH`] configurations, evaluated
    /// together by [`Evaluate::write_results_batch`]; the lines are those of
    /// `append_row` calls (evaluators must give equal cells either way).
    fn append_batch<E: Evaluate + ?Sized>(
        &self,
        plan: &Plan,
        eval: &E,
        ids: [u64; BATCH],
        sc: &mut Scratch,
        text: &mut String,
        part: &mut PartialSummary,
    ) {
        let rows = &mut sc.rows;
        let schemes: [Option<_>; BATCH] =
            std::array::from_fn(|l| self.load(plan, ids[l], &mut rows[l]));
        if schemes.iter().all(Option::is_some) {
            let schemes = schemes.map(|s| s.expect("all loaded"));
            let mut it = rows.iter_mut();
            let items = std::array::from_fn(|l| {
                let row = it.next().expect("one row per lane");
                (
                    &row.config,
                    &schemes[l],
                    &mut row.stage as &mut dyn CellSink,
                )
            });
            let res = eval.write_results_batch(plan, items);
            for (row, r) in rows.iter_mut().zip(res) {
                self.check_results(row, r);
            }
        } else {
            for (row, s) in rows.iter_mut().zip(schemes) {
                if let Some(s) = s {
                    let r = eval.write_results(plan, &row.config, &s, &mut row.stage);
                    self.check_results(row, r);
                }
            }
        }
        for (row, &id) in rows.iter_mut().zip(&ids) {
            self.emit(id, row, &mut sc.digits, text, part);
        }
    }

    /// Enumerates configuration `id` into `row` (coordinates by column) and
    /// builds its scheme; on an error, records it in `row` and returns `None`.
    fn load(
        &self,
        plan: &Plan,
        id: u64,
        row: &mut Staged,
    ) -> Option<crate::schemes::LocalScheme<f64>> {
        row.stage.clear();
        row.coordinates.clear();
        row.coordinates.resize(self.coordinates, None);
        row.error = None;
        match plan.configuration_into(id, &mut row.config, &mut row.sampler) {
            Ok(()) => {
                let c = &row.config;
                row.valence = c.valence;
                for (k, x) in c.coordinates.iter().enumerate() {
                    row.coordinates[plan.coordinate_column(c.valence, k)] = Some(*x);
                }
                match plan.scheme(c) {
                    Ok(s) => Some(s),
                    Err(e) => {
                        row.error = Some(e.to_string());
                        None
                    }
                }
            }
            Err(e) => {
                row.error = Some(e.to_string());
                row.coordinates.clear();
                row.coordinates.resize(self.coordinates, None);
                row.valence = 0;
                None
            }
        }
    }

    /// Records the outcome of an evaluation into `row`: a wrong cell count or
    /// an error empties the stage and becomes the row's error.
    fn check_results(&self, row: &mut Staged, result: crate::Result<()>) {
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

    /// Appends the CSV line of the staged `row` (configuration `id`) to `text`
    /// and adds it to `part`.
    fn emit(
        &self,
        id: u64,
        row: &Staged,
        digits: &mut zmij::Buffer,
        text: &mut String,
        part: &mut PartialSummary,
    ) {
        let n_results = self.names.len() - self.coordinates;
        let valence = row.valence;
        let error = &row.error;
        let mut ibuf = itoa_buf();
        text.push_str(small_uint(id, &mut ibuf));
        text.push(',');
        text.push_str(small_uint(valence as u64, &mut ibuf));
        let mut numeric = 0usize;
        for (pos, x) in row.coordinates.iter().enumerate() {
            text.push(',');
            let is_num = self.kinds[pos] == Kind::Numeric;
            if let Some(x) = x {
                push_number(text, digits, *x);
                if is_num {
                    part.push(numeric, *x, id);
                }
            }
            if is_num {
                numeric += 1;
            }
        }
        let mut class: Option<&str> = None;
        if row.stage.slots.is_empty() {
            for _ in 0..n_results {
                text.push(',');
            }
        } else {
            for (k, slot) in row.stage.slots.iter().enumerate() {
                let pos = self.coordinates + k;
                text.push(',');
                let is_num = self.kinds[pos] == Kind::Numeric;
                match *slot {
                    Slot::Empty => {}
                    Slot::Num(x) => {
                        push_number(text, digits, x);
                        if is_num {
                            part.push(numeric, x, id);
                        }
                    }
                    Slot::Text(a, b) => {
                        let t = &row.stage.text[a..b];
                        push_text(text, t);
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
        text.push(',');
        if let Some(e) = &error {
            push_text(text, e);
        }
        text.push('\n');
        let class = class.unwrap_or(if error.is_some() { "error" } else { "all" });
        part.count_row(valence, class, error.is_some());
    }
}

fn itoa_buf() -> [u8; 20] {
    [0; 20]
}

/// Decimal digits of `v` (no allocation).
fn small_uint(mut v: u64, buf: &mut [u8; 20]) -> &str {
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    std::str::from_utf8(&buf[i..]).unwrap_or("?")
}

/// Shortest round-trip text of an `f64` (`0.375`, `1e-20`, `1e16`, `1.0`, `NaN`,
/// `inf`, `-inf`): the shortest digits that read back to the same bits (Ryu's
/// output format: positive exponents without a sign); `str::parse::<f64>` reads
/// every form back to the same bits.
pub fn format_number(x: f64) -> String {
    let mut s = String::new();
    push_number(&mut s, &mut zmij::Buffer::new(), x);
    s
}

/// Appends [`format_number`]`(x)` to `s`. The digits come from the Żmij
/// algorithm (about 1.5x faster than Ryu here); its text differs from Ryu's
/// only by the `+` of a positive exponent (`1e+16`), dropped here, so the CSV
/// bytes are those Ryu wrote (a test compares the two on random doubles).
fn push_number(s: &mut String, buf: &mut zmij::Buffer, x: f64) {
    if x.is_finite() {
        let t = buf.format_finite(x);
        // A '+' can only be the sign of a positive exponent, so only |x| >= 1 has one.
        let plus = if x.abs() < 1.0 {
            None
        } else {
            t.bytes().position(|b| b == b'+')
        };
        match plus {
            Some(i) => {
                s.push_str(&t[..i]);
                s.push_str(&t[i + 1..]);
            }
            None => s.push_str(t),
        }
    } else if x.is_nan() {
        s.push_str("NaN");
    } else if x > 0.0 {
        s.push_str("inf");
    } else {
        s.push_str("-inf");
    }
}

/// The powers of ten that are exact in `f64`: `10^k = 5^k * 2^k` with
/// `5^k < 2^53` for `k <= 22`.
const EXACT_POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Most significant digits for which [`short_canonical`] decides alone: every
/// decimal of at most 15 significant digits in the normal range is the only
/// one of that length in its `f64` rounding interval (`DBL_DIG = 15`), so it is
/// the shortest round-trip text of the `f64` it reads as.
const SHORT_DIGITS: usize = 15;

/// A number text in the plain decimal layout of the CSV: `-m * 10^k` or
/// `m * 10^k`, `m` of `digits` significant digits (at most 17).
#[derive(Clone, Copy, Debug)]
struct Plain {
    neg: bool,
    m: u64,
    digits: usize,
    k: i32,
}

/// Reads `f` if it has the plain decimal forms of Ryu's layout (the CSV's
/// number format, see the module documentation): `-`? then `0.` followed by
/// at most four zeros and digits without a trailing zero, or an integer part
/// without a leading zero (at most 16 digits) followed by `.0` or by a
/// fraction without a trailing zero; at most 17 significant digits. `None`
/// for every other text (an exponent, another layout, not a number).
fn plain_decimal(f: &[u8]) -> Option<Plain> {
    // Texts of another form are rejected as early as their length allows.
    const MAX_DIGITS: usize = 17;
    let (neg, s) = match f {
        [b'-', rest @ ..] => (true, rest),
        _ => (false, f),
    };
    let int = s.iter().take(17).position(|&b| b == b'.')?;
    let frac = &s[int + 1..];
    let (&last, _) = frac.split_last()?;
    if int == 0 || int > 16 {
        return None;
    }
    let (m, digits, k) = if s[0] == b'0' {
        if int != 1 {
            return None;
        }
        // 0.000ddd: at most four zeros, then the digits (no trailing zero).
        let zeros = frac.iter().take(5).take_while(|&&b| b == b'0').count();
        let digits = frac.len() - zeros;
        if zeros > 4 || digits > MAX_DIGITS || last == b'0' {
            return None;
        }
        (
            digits_value(&frac[zeros..], 0)?,
            digits,
            -(frac.len() as i32),
        )
    } else if frac == b"0" {
        // An integer and `.0`: its digits without the trailing zeros.
        let zeros = s[..int].iter().rev().take_while(|&&b| b == b'0').count();
        let m = digits_value(&s[..int], 0)?;
        (m / EXACT_POW10[zeros] as u64, int - zeros, zeros as i32)
    } else {
        // Integer digits, the point, fraction digits (no trailing zero).
        let digits = int + frac.len();
        if digits > MAX_DIGITS || last == b'0' {
            return None;
        }
        let m = digits_value(&s[..int], 0)?;
        (digits_value(frac, m)?, digits, -(frac.len() as i32))
    };
    Some(Plain { neg, m, digits, k })
}

/// `m` followed by the decimal digits `t` (`10^len(t) m + t`), if `t` is all
/// digits; eight at a time (SWAR: the eight bytes as one `u64`, digits
/// checked with two masks, combined pairwise by three multiplications).
/// The caller keeps the result below `10^19`.
fn digits_value(t: &[u8], mut m: u64) -> Option<u64> {
    const ZEROS: u64 = 0x3030_3030_3030_3030;
    const HIGH: u64 = 0xF0F0_F0F0_F0F0_F0F0;
    let mut chunks = t.chunks_exact(8);
    for c in &mut chunks {
        let v = u64::from_le_bytes(c.try_into().ok()?);
        // Every byte 0x30..=0x39: high nibble 3, and still 3 after adding 6.
        if v & HIGH != ZEROS || v.wrapping_add(0x0606_0606_0606_0606) & HIGH != ZEROS {
            return None;
        }
        let d = v - ZEROS; // first digit in the lowest byte
        let d = ((d * 10) + (d >> 8)) & 0x00FF_00FF_00FF_00FF; // pairs
        let d = ((d * 100) + (d >> 16)) & 0x0000_FFFF_0000_FFFF; // quads
        let d = (d * 10_000 + (d >> 32)) & 0xFFFF_FFFF; // eight digits
        m = m * 100_000_000 + d;
    }
    for &b in chunks.remainder() {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        m = m * 10 + u64::from(d);
    }
    Some(m)
}

impl Plain {
    /// `m * 10^k` (or `m / 10^-k`) in `f64`, with the sign: one rounding of
    /// `m` (none when `m < 2^53`) and one of the product or quotient (`10^|k|`
    /// is exact, `|k| <= 21`). With at most 15 digits, `m < 2^53`, so this is
    /// the correctly rounded value of the text, `str::parse`'s (Clinger's fast
    /// path); otherwise it is within about one ulp of it.
    fn value(&self) -> f64 {
        let m = self.m as f64;
        let x = if self.k >= 0 {
            m * EXACT_POW10[self.k as usize]
        } else {
            m / EXACT_POW10[self.k.unsigned_abs() as usize]
        };
        if self.neg {
            -x
        } else {
            x
        }
    }
}

/// A cheap exact test of the number format, for the verifier: `Some(x)` when
/// `f` is certainly the text [`push_number`] writes for `x`; `None` when the
/// test does not decide (the caller then compares with [`push_number`]'s
/// text, the definitive test).
///
/// It decides the [`plain_decimal`] texts of at most [`SHORT_DIGITS`]
/// significant digits `m`, written `m * 10^k`: then `|k| <= 21` and
/// `m < 2^53`, so `x` = [`Plain::value`] equals `f.parse::<f64>()`; `x` is
/// normal, so by the `DBL_DIG` argument of [`SHORT_DIGITS`] the shortest round
/// trip of `x` has the digits `m` and the exponent `k`, and Ryu's layout of
/// `(m, k)` is the form [`plain_decimal`] checked (`0 <= k`, at most 16
/// integer digits: the integer and `.0`; `k < 0` with an integer part: the
/// digits with the point inserted; no integer part, at most four zeros after
/// the point: `0.` and the zeros). A test compares this with the definitive
/// test on random texts.
/// (The first stage of [`canonical_number`], kept apart for its test.)
#[cfg(test)]
fn short_canonical(f: &[u8]) -> Option<f64> {
    let p = plain_decimal(f)?;
    (p.digits <= SHORT_DIGITS).then(|| p.value())
}

/// The `x` whose text [`push_number`] writes is `f`, found without parsing
/// `f` in full: [`short_canonical`] first; for a [`plain_decimal`] of 16 or
/// 17 digits, the text written for [`Plain::value`] and for its two
/// neighbours (one ulp apart) is compared with `f` (`scratch` is refilled).
/// `Some(x)` is exact (`f` is the text of `x`, so `f.parse() == x`); `None`
/// decides nothing (the caller parses `f` and compares).
fn canonical_number(f: &str, scratch: &mut String, digits: &mut zmij::Buffer) -> Option<f64> {
    let p = plain_decimal(f.as_bytes())?;
    if p.digits <= SHORT_DIGITS {
        return Some(p.value());
    }
    let bits = p.value().abs().to_bits();
    for b in [bits, bits + 1, bits - 1] {
        let y = f64::from_bits(b);
        let y = if p.neg { -y } else { y };
        scratch.clear();
        push_number(scratch, digits, y);
        if f == scratch {
            return Some(y);
        }
    }
    None
}

fn push_text(s: &mut String, t: &str) {
    if !t.contains(['\n', '\r', ',', '"']) {
        s.push_str(t);
        return;
    }
    let t: String = t
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect();
    if t.contains(',') || t.contains('"') {
        s.push('"');
        s.push_str(&t.replace('"', "\"\""));
        s.push('"');
    } else {
        s.push_str(&t);
    }
}

/// Splits one CSV line (RFC 4180 quoting, no embedded line breaks).
pub fn split_csv_line(line: &str) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut chars = line.chars().peekable();
    let mut at_start = true;
    loop {
        if at_start && chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        cur.push('"');
                    }
                    Some('"') => break,
                    Some(c) => cur.push(c),
                    None => return Err("unterminated quoted field".into()),
                }
            }
            match chars.next() {
                None => {
                    out.push(std::mem::take(&mut cur));
                    return Ok(out);
                }
                Some(',') => {
                    out.push(std::mem::take(&mut cur));
                    at_start = true;
                    continue;
                }
                Some(c) => return Err(format!("unexpected {c:?} after a quoted field")),
            }
        }
        at_start = false;
        match chars.next() {
            None => {
                out.push(cur);
                return Ok(out);
            }
            Some(',') => {
                out.push(std::mem::take(&mut cur));
                at_start = true;
            }
            Some('"') => return Err("quote inside an unquoted field".into()),
            Some(c) => cur.push(c),
        }
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
    run_counting(
        plan,
        layout,
        eval,
        ids,
        out,
        summary,
        progress,
        &std::sync::atomic::AtomicU64::new(0),
    )
}

/// [`run`], also adding to `evaluated` the configurations evaluated so far (by
/// groups of at most [`SUB_CHUNK`], as the workers finish them, before they
/// are written): another thread can read it for a progress report that moves
/// even when a chunk takes minutes (slow columns such as `charmap`).
#[allow(clippy::too_many_arguments)]
pub fn run_counting<E, W, I>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: I,
    out: &mut W,
    summary: &mut Summary,
    progress: &mut dyn FnMut(u64),
    evaluated: &std::sync::atomic::AtomicU64,
) -> Result<u64, SweepError>
where
    E: Evaluate + ?Sized,
    W: Write,
    I: IntoIterator<Item = u64>,
{
    let mut ids = ids.into_iter();
    let threads = rayon::current_num_threads().max(1);
    let numeric = layout.numeric.len();
    let chunk_len = chunk_len(layout);
    let mut written = 0u64;
    // Rows evaluated but not yet written: (text, partial summary) per task.
    let mut pending: Vec<(String, PartialSummary)> = Vec::new();
    let mut next: Vec<u64> = Vec::with_capacity(chunk_len);
    loop {
        next.clear();
        next.extend(ids.by_ref().take(chunk_len));
        if next.is_empty() && pending.is_empty() {
            break;
        }
        let mut fresh: Vec<(String, PartialSummary)> = Vec::new();
        let mut wrote: Result<u64, SweepError> = Ok(0);
        rayon::in_place_scope(|scope| {
            if !next.is_empty() {
                let chunk = &next;
                let slot = &mut fresh;
                scope.spawn(move |_| {
                    *slot = evaluate_chunk(plan, layout, eval, chunk, threads, numeric, evaluated);
                });
            }
            // Meanwhile, on this thread: write the previous chunk in order.
            wrote = (|| {
                let mut rows = 0u64;
                for (text, part) in &pending {
                    out.write_all(text.as_bytes())?;
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
        pending = fresh;
    }
    Ok(written)
}

/// Configurations per chunk: [`CHUNK`], fewer for long rows (large valences)
/// so that a chunk's text stays within about 8 MB.
fn chunk_len(layout: &Layout) -> usize {
    let row_bytes = 32 + 24 * layout.cells();
    ((8 << 20) / row_bytes).clamp(SUB_CHUNK, CHUNK)
}

/// Evaluates one chunk on the current pool: tasks of consecutive
/// configurations, each formatting its rows into one buffer and keeping a
/// partial summary, returned in order.
fn evaluate_chunk<E: Evaluate + ?Sized>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    chunk: &[u64],
    threads: usize,
    numeric: usize,
    evaluated: &std::sync::atomic::AtomicU64,
) -> Vec<(String, PartialSummary)> {
    let sub = (chunk.len() / (8 * threads)).clamp(1, SUB_CHUNK);
    chunk
        .par_chunks(sub)
        .map(|ids| {
            let mut text = String::with_capacity(ids.len() * (32 + 24 * layout.cells()));
            let mut part = PartialSummary::new(numeric);
            let mut scratch = Scratch::new();
            let mut batches = ids.chunks_exact(BATCH);
            for b in &mut batches {
                let b: [u64; BATCH] = b.try_into().expect("chunks of BATCH");
                layout.append_batch(plan, eval, b, &mut scratch, &mut text, &mut part);
            }
            for &id in batches.remainder() {
                layout.append_row(plan, eval, id, &mut scratch, &mut text, &mut part);
            }
            evaluated.fetch_add(ids.len() as u64, std::sync::atomic::Ordering::Relaxed);
            (text, part)
        })
        .collect()
}

/// A source of CSV data lines for [`merge`] (fingerprint and header already
/// checked): a name (for messages), the shard its fingerprint names, and its
/// data lines without `\n`, in file order (the first is line 3 of the file).
pub struct MergeSource<I> {
    /// File name.
    pub name: String,
    /// The shard the file holds (from its fingerprint line).
    pub shard: Shard,
    /// Data lines.
    pub lines: I,
}

/// Merges shard CSVs (each in id order, as `sweep` writes them) into one CSV in
/// id order. Every line is verified in full against `plan` ([`Verifier`]: the
/// id is the shard's next one, parameters re-derived from it, results well
/// formed, a random sample re-evaluated with `eval`), and the ids must be
/// exactly `0..total`: an error names the first missing or duplicated id and
/// where it was found. Memory is one line per source. Returns, per source, the
/// summary of its rows (rebuilt from the verified lines, to compare with the
/// summary file written beside it).
pub fn merge<W, I, E>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    sources: Vec<MergeSource<I>>,
    out: &mut W,
    salt: u64,
) -> Result<Vec<Summary>, SweepError>
where
    W: Write,
    I: Iterator<Item = Result<String, SweepError>>,
    E: Evaluate + ?Sized,
{
    struct Head {
        line: String,
        lineno: u64,
    }
    let total = plan.total();
    let mut sources = sources;
    let mut verifiers: Vec<Verifier> = (0..sources.len())
        .map(|k| Verifier::new(plan, layout, salt ^ k as u64))
        .collect();
    let mut heads: Vec<Option<Head>> = Vec::with_capacity(sources.len());
    let mut heap = BinaryHeap::new();
    let advance = |src: &mut MergeSource<I>,
                   ver: &mut Verifier,
                   lineno: u64|
     -> Result<Option<(u64, Head)>, SweepError> {
        match src.lines.next() {
            None => Ok(None),
            Some(line) => {
                let line = line?;
                let expected = src.shard.id(ver.rows());
                let id =
                    ver.check(lineno, &line, expected)
                        .map_err(|message| SweepError::Mismatch {
                            source_name: src.name.clone(),
                            line: lineno,
                            message,
                        })?;
                Ok(Some((id, Head { line, lineno })))
            }
        }
    };
    for (k, (src, ver)) in sources.iter_mut().zip(&mut verifiers).enumerate() {
        match advance(src, ver, 3)? {
            Some((id, h)) => {
                heap.push(std::cmp::Reverse((id, k)));
                heads.push(Some(h));
            }
            None => heads.push(None),
        }
    }
    let mut expected = 0u64;
    let mut last: Option<(u64, usize, u64)> = None;
    let mut buf = String::new();
    while let Some(std::cmp::Reverse((id, k))) = heap.pop() {
        let head = heads[k]
            .take()
            .ok_or_else(|| SweepError::Merge("internal: empty head".into()))?;
        if id < expected {
            let (_, pk, pl) = last.unwrap_or((id, k, head.lineno));
            return Err(SweepError::Merge(format!(
                "configuration id {id} appears twice ({} line {}, {} line {})",
                sources[pk].name, pl, sources[k].name, head.lineno
            )));
        }
        if id > expected {
            return Err(SweepError::Merge(format!(
                "configuration id {expected} is missing (next id found: {id} in {} line {})",
                sources[k].name, head.lineno
            )));
        }
        if id >= total {
            return Err(SweepError::Merge(format!(
                "configuration id {id} ({} line {}) is beyond the sweep's {total} configurations",
                sources[k].name, head.lineno
            )));
        }
        buf.push_str(&head.line);
        buf.push('\n');
        if buf.len() > 1 << 16 {
            out.write_all(buf.as_bytes())?;
            buf.clear();
        }
        last = Some((id, k, head.lineno));
        expected += 1;
        if let Some((nid, h)) = advance(&mut sources[k], &mut verifiers[k], head.lineno + 1)? {
            heap.push(std::cmp::Reverse((nid, k)));
            heads[k] = Some(h);
        }
    }
    out.write_all(buf.as_bytes())?;
    out.flush()?;
    if expected < total {
        return Err(SweepError::Merge(format!(
            "configuration id {expected} is missing (the shards end there; the sweep has {total} configurations)"
        )));
    }
    let mut parts = Vec::with_capacity(sources.len());
    for (src, ver) in sources.iter().zip(&verifiers) {
        ver.recheck(eval)
            .map_err(|(line, message)| SweepError::Mismatch {
                source_name: src.name.clone(),
                line,
                message,
            })?;
        let mut s = Summary::new(plan, layout, src.shard, None);
        ver.add_to(&mut s);
        parts.push(s);
    }
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::super::eval::SpectralEvaluator;
    use super::super::plan::Shard;
    use super::*;

    #[test]
    fn csv_split_round_trips() {
        assert_eq!(split_csv_line("1,,a").unwrap(), vec!["1", "", "a"]);
        assert_eq!(
            split_csv_line("\"x, \"\"y\"\"\",2").unwrap(),
            vec!["x, \"y\"", "2"]
        );
        assert!(split_csv_line("\"abc").is_err());
        let mut s = String::new();
        push_text(&mut s, "a, \"b\"\nc");
        assert_eq!(split_csv_line(&s).unwrap(), vec!["a, \"b\" c"]);
        for x in [
            0.1,
            1.0 / 3.0,
            1e-300,
            5e300,
            -0.0,
            0.75,
            1.0,
            1e16,
            2.5e-8,
            f64::MIN_POSITIVE / 8.0,
        ] {
            assert_eq!(
                format_number(x).parse::<f64>().unwrap().to_bits(),
                x.to_bits()
            );
        }
    }

    #[test]
    fn numbers_are_written_as_ryu_writes_them() {
        // The CSV format is Ryu's shortest round trip; the digits now come from
        // Zmij, so compare the two on random bit patterns, random values of
        // every magnitude and short decimals.
        let mut ryu_buf = ryu::Buffer::new();
        let mut digits = zmij::Buffer::new();
        let mut s = String::new();
        let mut check = |x: f64| {
            s.clear();
            push_number(&mut s, &mut digits, x);
            let want = if x.is_finite() {
                ryu_buf.format_finite(x)
            } else {
                ""
            };
            if x.is_finite() {
                assert_eq!(s, want, "{x:e}");
            }
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
        };
        for i in 0..200_000u64 {
            let h = super::super::sampler::mix64(i);
            let bits = f64::from_bits(h);
            if !bits.is_nan() {
                check(bits);
            }
            let u = (h >> 11) as f64 / (1u64 << 53) as f64;
            let e = (super::super::sampler::mix64(h) % 90) as i32 - 45;
            check(u * 10f64.powi(e));
            check(-u);
            check((h % 100_000) as f64 / 10f64.powi((h % 23) as i32));
        }
        for x in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1e15,
            1e16,
            1e17,
            123_456_789_012_345_680.0,
            1e-5,
            1e-6,
            1e-7,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            check(x);
        }
        assert_eq!(format_number(f64::NAN), "NaN");
        assert_eq!(format_number(f64::INFINITY), "inf");
        assert_eq!(format_number(1e16), "1e16");
        assert_eq!(format_number(1.0), "1.0");
    }

    /// The verifier's cheap number tests never disagree with the definitive one
    /// (`f == format_number(f.parse())`), on written numbers of every magnitude
    /// and on near-miss texts (a digit more or less, leading or trailing zeros,
    /// a sign, an exponent form, a neighbour); and they decide often enough to
    /// matter (the candidate search finds every plain canonical text: the
    /// value of a plain decimal is within one ulp).
    #[test]
    fn short_canonical_agrees_with_the_definitive_test() {
        let (mut decided, mut found, mut canonical) = (0usize, 0usize, 0usize);
        let mut scratch = String::new();
        let mut digits = zmij::Buffer::new();
        let mut check = |t: &str| {
            let definitive = t
                .parse::<f64>()
                .ok()
                .filter(|x| format_number(*x) == t)
                .map(f64::to_bits);
            let fast = short_canonical(t.as_bytes());
            if let Some(y) = fast {
                assert_eq!(definitive, Some(y.to_bits()), "{t:?}");
                decided += 1;
            }
            match canonical_number(t, &mut scratch, &mut digits) {
                Some(y) => {
                    assert_eq!(definitive, Some(y.to_bits()), "{t:?}");
                    found += 1;
                }
                None => assert!(
                    definitive.is_none() || plain_decimal(t.as_bytes()).is_none(),
                    "{t:?}"
                ),
            }
            if definitive.is_some() {
                canonical += 1;
            }
        };
        let mutate = |t: &str| -> Vec<String> {
            let mut v = vec![
                format!("{t}0"),
                format!("0{t}"),
                format!("+{t}"),
                format!("-{t}"),
                t.replacen('.', "", 1),
                t.replacen(".0", ".", 1),
                t.replacen("0.", ".", 1),
                t.replacen('.', ".0", 1),
                format!("{t}e0"),
                t.to_uppercase(),
                t[..t.len() - 1].to_owned(),
                t[1..].to_owned(),
            ];
            let b = t.as_bytes();
            for d in [b'0', b'1', b'5', b'9'] {
                let mut c = b.to_vec();
                let last = c.len() - 1;
                if c[last].is_ascii_digit() {
                    c[last] = d;
                    v.push(String::from_utf8(c).unwrap());
                }
            }
            v
        };
        let mut texts: Vec<String> = Vec::new();
        for i in 0..40_000u64 {
            let h = super::super::sampler::mix64(i);
            let u = (h >> 11) as f64 / (1u64 << 53) as f64;
            let e = (super::super::sampler::mix64(h) % 50) as i32 - 25;
            for x in [
                f64::from_bits(h),
                u * 10f64.powi(e),
                -u,
                (h % 100_000) as f64 / 10f64.powi((h % 23) as i32),
                (h % 1_000_000_000_000_000) as f64,
                (h % 10_000_000_000_000_000) as f64 / 10f64.powi((h % 20) as i32),
                (h >> 40) as f64 * 10f64.powi((h % 7) as i32),
            ] {
                if !x.is_nan() {
                    texts.push(format_number(x));
                }
            }
        }
        for t in [
            "0.0",
            "-0.0",
            "1.0",
            "0.00001",
            "0.000001",
            "1e-5",
            "1e-6",
            "0.00012345",
            "123456789012345.0",
            "1234567890123456.0",
            "999999999999999.0",
            "9999999999999999.0",
            "1e16",
            "1e15",
            "100000000000000000.0",
            "0.30000000000000004",
            "0.3",
            "0.1",
            "5e-324",
            "inf",
            "NaN",
            "-inf",
            "",
            "-",
            ".",
            "0.",
            ".0",
            "00.5",
            "1..0",
            "1.-0",
            "1.5.",
        ] {
            texts.push(t.to_owned());
        }
        let base = texts.len();
        for k in 0..base {
            if !texts[k].is_empty() {
                let m = mutate(&texts[k]);
                texts.extend(m);
            }
        }
        for t in &texts {
            check(t);
        }
        assert!(
            canonical > texts.len() / 20,
            "{canonical} of {}",
            texts.len()
        );
        assert!(decided > canonical / 4, "{decided} of {canonical}");
        assert!(found > canonical * 9 / 10, "{found} of {canonical}");
    }

    /// The eight-at-a-time digit reader agrees with a digit-by-digit one and
    /// refuses every non-digit byte in every position.
    #[test]
    fn digits_value_reads_digits() {
        for i in 0..20_000u64 {
            let h = super::super::sampler::mix64(i);
            let len = (h % 18) as usize;
            let t: String = format!("{:019}", h % 10_000_000_000_000_000_000)[..len].to_owned();
            let want = t.bytes().fold(7u64, |m, b| m * 10 + u64::from(b - b'0'));
            if len <= 17 {
                assert_eq!(digits_value(t.as_bytes(), 7), Some(want), "{t}");
            }
            for pos in 0..len {
                for bad in [b'/', b':', b'.', b'e', b'-', 0x80, b' ', b'0' + 0x10] {
                    let mut b = t.clone().into_bytes();
                    b[pos] = bad;
                    assert_eq!(digits_value(&b, 7), None, "{b:?}");
                }
            }
        }
        assert_eq!(digits_value(b"", 3), Some(3));
        assert_eq!(digits_value(b"12345678", 0), Some(12_345_678));
        assert_eq!(
            digits_value(b"9876543210123456", 1),
            Some(19_876_543_210_123_456)
        );
    }

    /// An evaluator that returns the wrong number of cells for odd ids and fails
    /// for ids divisible by 5, to exercise the error rows of the fast path.
    struct Faulty(SpectralEvaluator);

    impl Evaluate for Faulty {
        fn evaluate(
            &self,
            plan: &Plan,
            c: &Configuration,
            scheme: &crate::schemes::LocalScheme<f64>,
        ) -> crate::Result<Vec<Cell>> {
            let mut v = self.0.evaluate(plan, c, scheme)?;
            if c.id % 5 == 0 {
                return Err(crate::Error::InvalidParameter {
                    name: "test",
                    value: format!("id {}", c.id),
                    reason: "a failure with a comma, and \"quotes\"",
                });
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
        let plan = Plan::new(super::super::SweepSpec::from_toml(spec).unwrap());
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
        let mut got = String::new();
        let mut part = PartialSummary::new(layout.numeric.len());
        let mut scratch = Scratch::new();
        for &id in &ids {
            layout.append_row(&plan, &eval, id, &mut scratch, &mut got, &mut part);
        }
        let mut got_summary = Summary::new(&plan, &layout, Shard::ALL, None);
        got_summary.absorb_partial(&part);
        assert_eq!(got, want);
        assert_eq!(got_summary, want_summary);
        // The batched path (the driver's) gives the same lines, whatever the
        // phase of the batches (lone first rows shift every batch).
        for skip in [0, 1, BATCH / 2 + 1, BATCH - 1] {
            let skip = skip.min(ids.len());
            let mut got = String::new();
            let mut part = PartialSummary::new(layout.numeric.len());
            for &id in &ids[..skip] {
                layout.append_row(&plan, &eval, id, &mut scratch, &mut got, &mut part);
            }
            let mut batches = ids[skip..].chunks_exact(BATCH);
            for b in &mut batches {
                let b: [u64; BATCH] = b.try_into().unwrap();
                layout.append_batch(&plan, &eval, b, &mut scratch, &mut got, &mut part);
            }
            for &id in batches.remainder() {
                layout.append_row(&plan, &eval, id, &mut scratch, &mut got, &mut part);
            }
            let mut got_summary = Summary::new(&plan, &layout, Shard::ALL, None);
            got_summary.absorb_partial(&part);
            assert_eq!(got, want, "batches from row {skip}");
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
    }

    const EIGHT: &str = "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n";

    type Lines = std::vec::IntoIter<Result<String, SweepError>>;

    fn src(name: &str, shard: Shard, lines: &[&str]) -> MergeSource<Lines> {
        MergeSource {
            name: name.into(),
            shard,
            lines: lines
                .iter()
                .map(|l| Ok(l.to_string()))
                .collect::<Vec<_>>()
                .into_iter(),
        }
    }

    #[test]
    fn merge_checks_ids_and_rows() {
        let plan = Plan::new(super::super::SweepSpec::from_toml(EIGHT).unwrap());
        let layout = Layout::new(&plan);
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let mut all = Vec::new();
        run(
            &plan,
            &layout,
            &eval,
            0..8,
            &mut all,
            &mut Summary::new(&plan, &layout, Shard::ALL, None),
            &mut |_| {},
        )
        .unwrap();
        let all = String::from_utf8(all).unwrap();
        let l: Vec<&str> = all.lines().collect();
        let s0: Shard = "0/2".parse().unwrap();
        let s1: Shard = "1/2".parse().unwrap();
        let evens = [l[0], l[2], l[4], l[6]];
        let odds = [l[1], l[3], l[5], l[7]];
        let mut out = Vec::new();
        let parts = merge(
            &plan,
            &layout,
            &eval,
            vec![src("a", s0, &evens), src("b", s1, &odds)],
            &mut out,
            1,
        )
        .unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), all);
        assert_eq!(parts.iter().map(|p| p.rows).collect::<Vec<_>>(), vec![4, 4]);
        let go = |srcs: Vec<MergeSource<Lines>>| {
            merge(&plan, &layout, &eval, srcs, &mut Vec::new(), 1)
                .unwrap_err()
                .to_string()
        };
        let e = go(vec![src("a", s0, &evens), src("b", s1, &odds[..3])]);
        assert!(e.contains("configuration id 7 is missing"), "{e}");
        let e = go(vec![
            src("a", s0, &evens),
            src("b", s1, &odds),
            src("c", s0, &evens[..1]),
        ]);
        assert!(e.contains("configuration id 0 appears twice"), "{e}");
        let e = go(vec![src("a", s0, &[l[0], l[1]])]);
        assert!(
            e.contains("a: line 4: configuration id 1 where 2 was expected"),
            "{e}"
        );
        // A bogus class, an edited number, an edited parameter.
        let bogus = l[2]
            .replacen(",standard,", ",bogus,", 1)
            .replacen(",real_distinct,", ",bogus,", 1)
            .replacen(",complex_pair,", ",bogus,", 1);
        assert_ne!(bogus, l[2]);
        let e = go(vec![
            src("a", s0, &[l[0], &bogus, l[4], l[6]]),
            src("b", s1, &odds),
        ]);
        assert!(e.contains("a: line 4: class = \"bogus\""), "{e}");
        let f: Vec<&str> = l[4].split(',').collect();
        let mut g = f.clone();
        let lam = format!("{}", f[6].parse::<f64>().unwrap() + 0.25);
        g[6] = &lam;
        let edited = g.join(",");
        let e = go(vec![
            src("a", s0, &[l[0], l[2], &edited, l[6]]),
            src("b", s1, &odds),
        ]);
        assert!(
            e.contains("a: line 5: configuration 4 differs from a fresh evaluation: lambda1_re"),
            "{e}"
        );
        let mut g = f.clone();
        g[2] = "0.5";
        let edited = g.join(",");
        let e = go(vec![
            src("a", s0, &[l[0], l[2], &edited, l[6]]),
            src("b", s1, &odds),
        ]);
        assert!(
            e.contains("configuration 4 has r0 = \"0.5\" where the spec gives"),
            "{e}"
        );
    }
}
