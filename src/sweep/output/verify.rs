//! Verification of existing sweep CSVs (resume and merge): the fingerprint
//! line, and every data line in full.
//!
//! A [`Verifier`] trusts nothing in a line:
//!
//! * the field count is the layout's;
//! * the id is the one expected at that position (resume: `shard.id(row)`;
//!   merge: the shard's next id);
//! * the valence and every coordinate are re-derived from the id
//!   ([`Plan::configuration`]) and must be written exactly as the sweep writes
//!   them (the same bytes), the coordinate cells beyond the valence empty;
//! * a row with an error has every result cell empty;
//! * a text result is one of the values the sweep writes (`class`: the five
//!   class names or `indeterminate:A/B`; `charmap_verdict`: the verdict codes;
//!   `exact_class`: the class names or `undecided`), and is present;
//! * a number parses as an `f64`, is written in the sweep's shortest round-trip
//!   form (so that a summary rebuilt from the file equals the one accumulated
//!   while writing), and lies in its column's range where the column has one
//!   (`abs_lambda3`, `contraction_rate` >= 0, `charmap_winding` an integer; `exact_agrees` `true` or
//!   `false`).
//!
//! Edited *results* that stay plausible (a `lambda1_re` changed to another
//! number, another valid class, an error text edited) cannot be told apart by
//! their form; the verifier therefore also keeps a uniform random sample of
//! [`RECHECK_SAMPLE`] lines (the smallest hashes of the ids, salted by the
//! caller so that which lines are re-evaluated cannot be predicted) and
//! [`recheck`](Verifier::recheck) re-evaluates them, requiring the same bytes.
//! A file of at most [`RECHECK_SAMPLE`] rows is thus re-evaluated in full; in a
//! larger file, `e` edited rows out of `r` escape detection with probability
//! about `(1 - e/r)^RECHECK_SAMPLE`.
//!
//! # Speed
//!
//! [`Verifier::check_block`] takes the file's bytes as read (no per-line
//! copies), cuts them into pieces at line ends and verifies the pieces in
//! parallel (UTF-8, line and field splitting included); the caller reads the
//! next block meanwhile. A number cell is checked without a full parse where
//! that is exact: a plain decimal of at most 15 significant digits is the
//! shortest round trip of its value by construction; one of 16 or 17 digits
//! is decided by exact integer arithmetic without formatting
//! (`shortest_by_integers` in `csv.rs`, math doc section 16.2) or, where that
//! leaves it undecided, compared with the text written for its approximate
//! value and that value's neighbours (`canonical_number`); other texts take
//! the definitive path (parse, format, compare). A coordinate cell is checked
//! the same way, its value compared bit for bit with the one re-derived from
//! the id, instead of formatting the expected value. Halton points use
//! constant-base digit arithmetic. None of these shortcuts drops or weakens a
//! check. The re-check time of a 1M-row file is in `BENCHMARKS.md`
//! (`benches/resume_check.sh`).

use super::csv::{canonical_number, push_number, split_csv_line};
use super::layout::Layout;
use crate::sweep::eval::ColumnType;
use crate::sweep::eval::Evaluate;
use crate::sweep::plan::{Configuration, Plan, Shard};
use crate::sweep::sampler::mix64;
use crate::sweep::summary::{PartialSummary, Summary};

/// Lines re-evaluated by [`Verifier::recheck`] (every line of a file this
/// short or shorter). 32 re-evaluations cost well under a second even with the
/// slowest columns (the characteristic map and the exact certificate), and
/// catch a corruption of 10% of the rows with probability `1 - 0.9^32 > 0.96`.
pub const RECHECK_SAMPLE: usize = 32;

/// The fingerprint of a Parquet part file (key-value metadata
/// [`parquet::FINGERPRINT_KEY`](super::parquet::FINGERPRINT_KEY)): ties the
/// file to its spec (by [`SweepSpec::digest`](crate::sweep::SweepSpec::digest))
/// and its shard. A sweep CSV has none: its first line is the header, and the
/// summary JSON beside it carries the same facts ([`check_summary`]).
///
/// ```
/// use subdiv_lab::sweep::{output, Plan, Shard, SweepSpec};
/// let spec = SweepSpec::from_toml("name = \"s\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n").unwrap();
/// let plan = Plan::new(spec);
/// let line = output::fingerprint_line(&plan, Shard::ALL);
/// assert!(line.starts_with("# subdiv-lab sweep: digest "));
/// assert_eq!(output::fingerprint_shard(&line), Some(Shard::ALL));
/// ```
pub fn fingerprint_line(plan: &Plan, shard: Shard) -> String {
    format!(
        "{FINGERPRINT_PREFIX}{}, shard {shard}, {} configurations, spec {:?}\n",
        plan.digest(),
        plan.total(),
        plan.spec().name
    )
}

const FINGERPRINT_PREFIX: &str = "# subdiv-lab sweep: digest ";

/// Whether `first_line` is the `#` fingerprint line that older versions wrote
/// above a sweep CSV's header: such a file is refused, never misread.
pub fn is_old_csv_fingerprint(first_line: &[u8]) -> bool {
    first_line.starts_with(b"# subdiv-lab sweep")
}

/// The refusal of a CSV written by an older version (see
/// [`is_old_csv_fingerprint`]).
pub const OLD_CSV: &str = "written by an older subdiv-lab (a `# subdiv-lab sweep` line above the header; sweep CSVs now start with their header and the summary JSON ties them to the spec): run the sweep into a new file";

/// The shard named by a fingerprint line, if `line` is one.
pub fn fingerprint_shard(line: &str) -> Option<Shard> {
    let rest = line.strip_prefix(FINGERPRINT_PREFIX)?;
    let after = rest.split_once(", shard ")?.1;
    after.split(',').next()?.parse().ok()
}

/// The message naming how `found` (a file's shard) differs from `shard` (this
/// run's), if it does.
fn shard_differs(found: Shard, shard: Shard) -> Option<String> {
    if found == shard {
        None
    } else if found.count != shard.count {
        Some(format!(
            "written as shard {found} of {} shards, but this run is shard {shard} of {}: the shard count must be the same",
            found.count, shard.count
        ))
    } else {
        Some(format!(
            "written as shard {found}, but this run is shard {shard}"
        ))
    }
}

/// Checks the fingerprint of a Parquet part file against `plan` and `shard`
/// (the file's own shard for merge, the run's for resume). The message names
/// what differs: no fingerprint, another spec, or another shard (count).
pub fn check_fingerprint(plan: &Plan, shard: Shard, line: &str) -> Result<(), String> {
    let digest = line.strip_prefix(FINGERPRINT_PREFIX);
    let Some(digest) = digest.and_then(|rest| rest.split(',').next()) else {
        return Err(
            "no sweep fingerprint: not a sweep file of this tool, or written by an older subdiv-lab"
                .into(),
        );
    };
    let want = plan.digest();
    if digest != want {
        return Err(format!(
            "written by another spec (digest {digest}; this spec's is {want})"
        ));
    }
    let found = fingerprint_shard(line).ok_or("the fingerprint names no shard")?;
    if let Some(m) = shard_differs(found, shard) {
        return Err(m);
    }
    if line.trim_end_matches('\n') != fingerprint_line(plan, shard).trim_end_matches('\n') {
        return Err("the fingerprint is not the one this spec writes".into());
    }
    Ok(())
}

/// Checks the fingerprint of a sweep CSV, which its summary JSON carries
/// (`spec_digest`, `total_configurations`, `shard`), against `plan` and this
/// run's `shard` (math doc section 16.2; a `--limit` may differ: a prefix run
/// can be continued further). The message names what differs.
pub fn check_summary(plan: &Plan, shard: Shard, summary: &Summary) -> Result<(), String> {
    let want = plan.digest();
    if summary.spec_digest != want || summary.total_configurations != plan.total() {
        return Err(format!(
            "written by another spec (digest {}; this spec's is {want})",
            summary.spec_digest
        ));
    }
    if let Some(m) = shard_differs(summary.shard, shard) {
        return Err(m);
    }
    Ok(())
}

/// What a result column may hold, beyond its type: the text rules
/// ([`text_ok`]) of the text columns, the number rules ([`num_ok`]) of the
/// numeric ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rule {
    Class,
    Verdict,
    ExactClass,
    Bool,
    NonNegative,
    Integer,
    Any,
}

/// The names [`ClassName::as_str`](crate::spectral::ClassName) writes.
const CLASSES: [&str; 5] = [
    "standard",
    "real_distinct",
    "complex_pair",
    "defective",
    "not_separated",
];

/// The codes [`Verdict::code`](crate::charmap::Verdict::code) writes.
const VERDICTS: [&str; 8] = [
    "c1",
    "tpc_real_distinct",
    "tpc_complex_pair",
    "tpc",
    "not_regular",
    "not_injective",
    "indeterminate",
    "no_charmap",
];

fn text_ok(rule: Rule, t: &str) -> bool {
    match rule {
        Rule::Class => {
            CLASSES.contains(&t)
                || t.strip_prefix("indeterminate:")
                    .and_then(|p| p.split_once('/'))
                    .is_some_and(|(a, b)| CLASSES.contains(&a) && CLASSES.contains(&b))
        }
        Rule::Verdict => VERDICTS.contains(&t),
        Rule::ExactClass => t == "undecided" || CLASSES.contains(&t),
        Rule::Bool => t == "true" || t == "false",
        _ => true,
    }
}

fn num_ok(rule: Rule, x: f64) -> bool {
    match rule {
        Rule::NonNegative => x >= 0.0,
        Rule::Integer => x.is_finite() && x.fract() == 0.0,
        _ => true,
    }
}

fn rule(name: &str) -> Rule {
    match name {
        "class" => Rule::Class,
        "charmap_verdict" => Rule::Verdict,
        "exact_class" => Rule::ExactClass,
        "exact_agrees" => Rule::Bool,
        "abs_lambda3" | "contraction_rate" => Rule::NonNegative,
        "charmap_winding" => Rule::Integer,
        _ => Rule::Any,
    }
}

/// The value whose text this sweep writes ([`push_number`]) is `f`:
/// `Err(None)` when `f` is not a number, `Err(Some(text))` when it is
/// another text of a number (`text` the one written for it). Without a
/// parse where [`canonical_number`] decides.
fn read_number(
    f: &str,
    number: &mut String,
    digits: &mut zmij::Buffer,
) -> Result<f64, Option<String>> {
    if let Some(x) = canonical_number(f, number, digits) {
        return Ok(x);
    }
    let x: f64 = f.parse().map_err(|_| None)?;
    number.clear();
    push_number(number, digits, x);
    if f != number {
        return Err(Some(number.clone()));
    }
    Ok(x)
}

/// Bytes per piece of [`Verifier::check_block`] (cut at the next line end):
/// about a thousand lines of a typical sweep, small enough that a block of a
/// few megabytes gives every thread many pieces, large enough that a piece's
/// verifier (and its recheck sample) costs little next to its lines.
pub const PIECE_BYTES: usize = 1 << 18;

/// Why [`Verifier::check_block`] refused a line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LineFault {
    /// The line is not UTF-8.
    NotUtf8,
    /// The line is a row beyond the limit the caller gave.
    TooManyRows,
    /// The line fails verification: the message of [`Verifier::check`].
    Mismatch(String),
}

/// A line kept for [`Verifier::recheck`].
#[derive(Clone, Debug)]
struct Kept {
    hash: u64,
    id: u64,
    lineno: u64,
    line: String,
}

/// Verifies the data lines of one existing sweep CSV, in file order, and
/// accumulates their summary (see the module documentation for the checks).
pub struct Verifier<'a> {
    plan: &'a Plan,
    layout: &'a Layout,
    /// Per cell.
    rules: Vec<Rule>,
    /// Field ranges of the current line (in `line` or in `unquoted`).
    fields: Vec<(usize, usize)>,
    unquoted: String,
    number: String,
    digits: zmij::Buffer,
    config: Configuration,
    sampler: Vec<f64>,
    /// Expected coordinate per coordinate cell.
    coordinates: Vec<Option<f64>>,
    part: PartialSummary,
    kept: Vec<Kept>,
    /// The largest hash in `kept` (`u64::MAX` while none is kept; checked
    /// for every line).
    kept_max: u64,
    salt: u64,
    rows: u64,
}

impl<'a> Verifier<'a> {
    /// A verifier for lines of `plan`'s CSV. `salt` chooses the lines kept for
    /// [`recheck`](Self::recheck) (pass something unpredictable, e.g. the time).
    pub fn new(plan: &'a Plan, layout: &'a Layout, salt: u64) -> Self {
        let rules = layout.names.iter().map(|n| rule(n)).collect();
        Verifier {
            plan,
            layout,
            rules,
            fields: Vec::with_capacity(layout.names.len() + 3),
            unquoted: String::new(),
            number: String::new(),
            digits: zmij::Buffer::new(),
            config: Configuration::default(),
            sampler: Vec::new(),
            coordinates: Vec::new(),
            part: PartialSummary::new(layout.numeric.len()),
            kept: Vec::new(),
            kept_max: u64::MAX,
            salt: mix64(salt ^ 0x005e_ed0f_5ee9),
            rows: 0,
        }
    }

    /// Keeps `k` if its hash is among the [`RECHECK_SAMPLE`] smallest met
    /// (bottom-k), dropping the largest kept.
    fn keep(&mut self, k: Kept) {
        if self.kept.len() < RECHECK_SAMPLE {
            self.kept.push(k);
        } else if let Some(worst) = self
            .kept
            .iter_mut()
            .max_by_key(|k| k.hash)
            .filter(|w| w.hash > k.hash)
        {
            *worst = k;
        }
        self.kept_max = self.kept.iter().map(|k| k.hash).max().unwrap_or(u64::MAX);
    }

    /// Verifies a block of complete lines (each ending in `\n`; the first is
    /// line `first_lineno` of the file) in parallel on the current rayon pool,
    /// and returns the number of lines. Row `j` of the file (counting from 0
    /// over all calls) must carry id `shard.id(j)`, and only rows `j <
    /// max_rows` may exist. The error is that of the first faulty line in file
    /// order: `(line number, fault)`. Same result as [`check`](Self::check) on
    /// each line in turn (after a UTF-8 check and the row limit).
    ///
    /// The block is cut at line ends into pieces of about [`PIECE_BYTES`]; the
    /// lines of each piece are counted as it is cut (so that every piece knows
    /// its first row index), then the pieces are verified in parallel, each by its own
    /// verifier, and the verifiers are combined in file order (rows, summary,
    /// the bottom-k recheck sample: the result does not depend on the cuts).
    pub fn check_block(
        &mut self,
        first_lineno: u64,
        block: &[u8],
        shard: Shard,
        max_rows: u64,
    ) -> Result<u64, (u64, LineFault)> {
        use rayon::prelude::*;
        // Pieces cut after a line end, each with the index of its first line.
        let (mut pieces, mut at, mut lines) = (Vec::new(), 0usize, 0u64);
        while at < block.len() {
            let target = at + PIECE_BYTES;
            let end = if target >= block.len() {
                block.len()
            } else {
                memchr::memchr(b'\n', &block[target - 1..]).map_or(block.len(), |p| target + p)
            };
            let piece = &block[at..end];
            pieces.push((lines, piece));
            lines += memchr::memchr_iter(b'\n', piece).count() as u64;
            lines += u64::from(piece.last().is_some_and(|&b| b != b'\n'));
            at = end;
        }
        let base = self.rows;
        let (plan, layout, salt) = (self.plan, self.layout, self.salt);
        let verified: Vec<Result<Verifier, (u64, LineFault)>> = pieces
            .par_iter()
            .map(|&(start, piece)| {
                let mut v = Verifier::new(plan, layout, 0);
                v.salt = salt;
                // Line ends: every '\n', and the end of a last line without one.
                let tail = piece
                    .last()
                    .is_some_and(|&b| b != b'\n')
                    .then_some(piece.len());
                let mut a = 0;
                for (i, end) in memchr::memchr_iter(b'\n', piece).chain(tail).enumerate() {
                    let k = start + i as u64;
                    let lineno = first_lineno + k;
                    let line = std::str::from_utf8(&piece[a..end])
                        .map_err(|_| (lineno, LineFault::NotUtf8))?;
                    a = end + 1;
                    if base + k >= max_rows {
                        return Err((lineno, LineFault::TooManyRows));
                    }
                    v.check(lineno, line, shard.id(base + k))
                        .map_err(|m| (lineno, LineFault::Mismatch(m)))?;
                }
                Ok(v)
            })
            .collect();
        for piece in verified {
            let v = piece?;
            self.rows += v.rows;
            self.part.absorb(&v.part);
            for k in v.kept {
                self.keep(k);
            }
        }
        Ok(lines)
    }

    /// Rows verified so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Verifies one data line (`lineno` 1-based in the file, for [`recheck`]'s
    /// messages; `line` without `\n`). `expected_id`: the id this position must
    /// carry. Returns the line's id; the message of an error names the problem
    /// (the caller adds the file and line).
    ///
    /// [`recheck`]: Self::recheck
    pub fn check(&mut self, lineno: u64, line: &str, expected_id: u64) -> Result<u64, String> {
        self.fields.clear();
        let mut quoted = false;
        let mut a = 0;
        for i in memchr::memchr2_iter(b',', b'"', line.as_bytes()) {
            if line.as_bytes()[i] == b'"' {
                quoted = true;
                break;
            }
            self.fields.push((a, i));
            a = i + 1;
        }
        if quoted {
            // Only error texts are ever quoted: the slow path is rare.
            self.fields.clear();
            self.unquoted.clear();
            for f in split_csv_line(line)? {
                let a = self.unquoted.len();
                self.unquoted.push_str(&f);
                self.fields.push((a, self.unquoted.len()));
            }
        } else {
            self.fields.push((a, line.len()));
        }
        let unquoted = std::mem::take(&mut self.unquoted);
        let src: &str = if quoted { &unquoted } else { line };
        let r = self.check_fields(src, expected_id);
        self.unquoted = unquoted;
        let id = r?;
        self.rows += 1;
        // Bottom-k sampling: keep the RECHECK_SAMPLE lines of smallest salted
        // hash of their id (a uniform sample, independent of the order and of
        // how the lines were split between verifiers).
        let h = mix64(self.salt ^ id);
        if self.kept.len() < RECHECK_SAMPLE || h < self.kept_max {
            let kept = Kept {
                hash: h,
                id,
                lineno,
                line: line.to_owned(),
            };
            self.keep(kept);
        }
        Ok(id)
    }

    fn check_fields(&mut self, src: &str, expected_id: u64) -> Result<u64, String> {
        let layout = self.layout;
        let plan = self.plan;
        let cells = layout.names.len();
        if self.fields.len() != cells + 3 {
            return Err(format!(
                "expected {} fields, found {}",
                cells + 3,
                self.fields.len()
            ));
        }
        let field = |k: usize| -> &str {
            let (a, b) = self.fields[k];
            &src[a..b]
        };
        let id_text = field(0);
        let id: u64 = id_text
            .parse()
            .map_err(|_| format!("id {id_text:?} is not an integer"))?;
        if id != expected_id {
            return Err(format!(
                "configuration id {id} where {expected_id} was expected"
            ));
        }
        plan.configuration_into(id, &mut self.config, &mut self.sampler)
            .map_err(|e| e.to_string())?;
        let valence = self.config.valence;
        if field(1) != itoa::Buffer::new().format(valence) {
            return Err(format!(
                "configuration {id} has valence {:?} where the spec gives {valence} (was the spec changed?)",
                field(1)
            ));
        }
        layout.coordinates_into(plan, &self.config, &mut self.coordinates);
        let mut numeric = 0usize;
        for pos in 0..layout.coordinates {
            let f = field(2 + pos);
            let ok = match self.coordinates[pos] {
                None => f.is_empty(),
                // `f` is the text written for `y` (without formatting `x`:
                // see `read_number`) and `y` is `x`.
                Some(x) => read_number(f, &mut self.number, &mut self.digits)
                    .is_ok_and(|y| y.to_bits() == x.to_bits()),
            };
            if !ok {
                self.number.clear();
                if let Some(x) = self.coordinates[pos] {
                    push_number(&mut self.number, &mut self.digits, x);
                }
                return Err(format!(
                    "configuration {id} has {} = {f:?} where the spec gives {:?} (was the spec changed?)",
                    layout.names[pos], self.number
                ));
            }
            if let Some(x) = self.coordinates[pos] {
                self.part.push(numeric, x, id);
            }
            numeric += 1;
        }
        let errored = !field(cells + 2).is_empty();
        let mut class: Option<(usize, usize)> = None;
        for pos in layout.coordinates..cells {
            let f = field(2 + pos);
            let name = &layout.names[pos];
            let is_num = layout.types[pos] == ColumnType::Float;
            if errored {
                if !f.is_empty() {
                    return Err(format!(
                        "configuration {id} has an error and a result ({name} = {f:?}); a failed row has no results"
                    ));
                }
            } else if is_num {
                if !f.is_empty() {
                    let x = read_number(f, &mut self.number, &mut self.digits).map_err(
                        |t| match t {
                            None => format!("{name} = {f:?} is not a number"),
                            Some(t) => format!(
                                "{name} = {f:?} is not written as this sweep writes numbers ({t:?})"
                            ),
                        },
                    )?;
                    if !num_ok(self.rules[pos], x) {
                        return Err(format!("{name} = {f} is out of range for that column"));
                    }
                    self.part.push(numeric, x, id);
                }
            } else {
                let rule = self.rules[pos];
                // `exact_agrees` is empty when either class is undecided.
                let empty_ok = rule == Rule::Bool;
                if (f.is_empty() && !empty_ok) || (!f.is_empty() && !text_ok(rule, f)) {
                    return Err(format!(
                        "{name} = {f:?} is not a value this sweep writes{}",
                        match rule {
                            Rule::Class => " (a class name: standard, real_distinct, complex_pair, defective, not_separated or indeterminate:A/B)",
                            Rule::Verdict => " (a characteristic-map verdict code)",
                            Rule::ExactClass => " (a class name or undecided)",
                            Rule::Bool => " (true or false)",
                            _ => "",
                        }
                    ));
                }
                if layout.class == Some(pos) {
                    class = Some(self.fields[2 + pos]);
                }
            }
            if is_num {
                numeric += 1;
            }
        }
        let class = match class {
            Some((a, b)) => &src[a..b],
            None if errored => "error",
            None => "all",
        };
        self.part.count_row(valence, class, errored);
        Ok(id)
    }

    /// Re-evaluates the kept lines (every line of a short file, a random sample
    /// of [`RECHECK_SAMPLE`] otherwise) and requires the same bytes. The error
    /// is `(line number, message)`.
    pub fn recheck<E: Evaluate + ?Sized>(&self, eval: &E) -> Result<(), (u64, String)> {
        let mut kept: Vec<&Kept> = self.kept.iter().collect();
        kept.sort_by_key(|k| k.lineno);
        for k in kept {
            // The line the sweep writes for this configuration.
            let fresh = self.layout.format(&self.layout.row(self.plan, eval, k.id));
            let fresh = fresh.trim_end_matches('\n');
            if fresh != k.line {
                let what = match (split_csv_line(fresh), split_csv_line(&k.line)) {
                    (Ok(a), Ok(b)) => {
                        let names = self.layout.column_names();
                        a.iter()
                            .zip(&b)
                            .zip(&names)
                            .find(|((x, y), _)| x != y)
                            .map(|((x, y), n)| {
                                format!(": {n} is {y:?} in the file, {x:?} when evaluated")
                            })
                            .unwrap_or_default()
                    }
                    _ => String::new(),
                };
                return Err((
                    k.lineno,
                    format!(
                        "configuration {} differs from a fresh evaluation{what}; the file was edited or written by another build",
                        k.id
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Adds the verified rows to `summary` (same result as adding each row with
    /// [`Summary::add`]).
    pub fn add_to(&self, summary: &mut Summary) {
        summary.absorb_partial(&self.part);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::eval::SpectralEvaluator;

    /// Each text and number rule accepts exactly what its columns may hold
    /// (the CLI tests edit only `class` and `abs_lambda3`).
    #[test]
    fn column_rules_accept_exactly_their_values() {
        for c in CLASSES {
            assert!(text_ok(Rule::Class, c), "{c}");
            assert!(text_ok(Rule::ExactClass, c), "{c}");
        }
        assert!(text_ok(
            Rule::Class,
            "indeterminate:real_distinct/complex_pair"
        ));
        for bad in [
            "",
            "Standard",
            "undecided",
            "indeterminate",
            "indeterminate:standard",
            "indeterminate:standard/",
            "indeterminate:/standard",
            "indeterminate:standard/bogus",
            "indeterminate:bogus/standard",
            "undetermined:standard/defective",
        ] {
            assert!(!text_ok(Rule::Class, bad), "class {bad:?}");
        }
        assert!(text_ok(Rule::ExactClass, "undecided"));
        for bad in ["", "undecided ", "indeterminate:standard/defective", "c1"] {
            assert!(!text_ok(Rule::ExactClass, bad), "exact class {bad:?}");
        }
        for v in VERDICTS {
            assert!(text_ok(Rule::Verdict, v), "{v}");
        }
        for bad in ["", "C1", "c2", "standard", "true", "undecided"] {
            assert!(!text_ok(Rule::Verdict, bad), "verdict {bad:?}");
        }
        assert!(text_ok(Rule::Bool, "true") && text_ok(Rule::Bool, "false"));
        for bad in ["", "1", "0", "1.0", "True", "yes"] {
            assert!(!text_ok(Rule::Bool, bad), "bool {bad:?}");
        }
        assert!(text_ok(Rule::Any, "") && text_ok(Rule::Any, "x,y"));

        assert_eq!(rule("class"), Rule::Class);
        assert_eq!(rule("charmap_verdict"), Rule::Verdict);
        assert_eq!(rule("exact_class"), Rule::ExactClass);
        assert_eq!(rule("exact_agrees"), Rule::Bool);
        assert_eq!(rule("error"), Rule::Any);
        assert_eq!(rule("abs_lambda3"), Rule::NonNegative);
        assert_eq!(rule("contraction_rate"), Rule::NonNegative);
        assert_eq!(rule("charmap_winding"), Rule::Integer);
        assert_eq!(rule("lambda1_re"), Rule::Any);

        for x in [0.0, -0.0, 1e-300, 2.5, f64::INFINITY] {
            assert!(num_ok(Rule::NonNegative, x), "{x}");
        }
        for x in [-1e-300, -1.0, f64::NEG_INFINITY] {
            assert!(!num_ok(Rule::NonNegative, x), "{x}");
        }
        for x in [0.0, -3.0, 1.0, 1e15] {
            assert!(num_ok(Rule::Integer, x), "{x}");
        }
        for x in [0.5, -2.5, 1e-9, f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            assert!(!num_ok(Rule::Integer, x), "{x}");
        }
        for x in [-1.0, f64::NAN, f64::NEG_INFINITY] {
            assert!(num_ok(Rule::Any, x), "{x}");
        }
    }

    /// The lines kept for `recheck` are the `RECHECK_SAMPLE` of smallest
    /// salted hash of their id (bottom-k), whatever the order they come in,
    /// and `kept_max` is the largest of their hashes.
    #[test]
    fn the_recheck_sample_is_the_bottom_k_of_the_salted_hashes() {
        let spec = "name = \"k\"\nscheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"halton\"\ncount = 150\n";
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        let layout = Layout::new(&plan);
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let lines: Vec<String> = (0..plan.total())
            .map(|id| {
                let mut s = String::new();
                layout.format_into(&layout.row(&plan, &eval, id), &mut s);
                s.trim_end_matches('\n').to_owned()
            })
            .collect();
        for (salt, reversed) in [(7, false), (12_345, false), (7, true)] {
            let mut v = Verifier::new(&plan, &layout, salt);
            let mut order: Vec<usize> = (0..lines.len()).collect();
            if reversed {
                order.reverse();
            }
            for id in order {
                v.check(id as u64 + 2, &lines[id], id as u64).unwrap();
            }
            assert_eq!(v.rows(), plan.total());
            let mut want: Vec<(u64, u64)> = (0..plan.total())
                .map(|id| (mix64(v.salt ^ id), id))
                .collect();
            want.sort_unstable();
            want.truncate(RECHECK_SAMPLE);
            let mut got: Vec<(u64, u64)> = v.kept.iter().map(|k| (k.hash, k.id)).collect();
            got.sort_unstable();
            assert_eq!(got, want, "salt {salt}, reversed {reversed}");
            assert_eq!(v.kept_max, want[RECHECK_SAMPLE - 1].0);
            for k in &v.kept {
                assert_eq!(k.line, lines[k.id as usize]);
                assert_eq!(k.lineno, k.id + 2);
            }
        }
    }
}
