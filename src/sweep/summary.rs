//! The sweep summary: counts per class per valence, the extremes of every
//! numeric column with the configuration that attains them, throughput.
//!
//! A [`Summary`] is an accumulator: [`Summary::add`] takes rows in any order,
//! [`Summary::merge`] combines the summaries of shards, and the result does not
//! depend on the order (ties in an extreme go to the smaller configuration id).
//! It serialises to the JSON written beside the CSV.

use super::output::layout::{Layout, Row};
use super::plan::{Plan, Shard};
use super::SweepError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Extremes of one numeric column.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ColumnStats {
    /// Column name.
    pub name: String,
    /// Number of finite values seen.
    pub count: u64,
    /// Number of non-finite values (NaN, infinities) seen; they do not enter min/max.
    pub non_finite: u64,
    /// Smallest value (`None` if no finite value).
    pub min: Option<f64>,
    /// Configuration id of the smallest value (smallest id on ties).
    pub min_id: Option<u64>,
    /// Largest value.
    pub max: Option<f64>,
    /// Configuration id of the largest value (smallest id on ties).
    pub max_id: Option<u64>,
}

impl ColumnStats {
    fn new(name: String) -> Self {
        ColumnStats {
            name,
            count: 0,
            non_finite: 0,
            min: None,
            min_id: None,
            max: None,
            max_id: None,
        }
    }

    fn push(&mut self, x: f64, id: u64) {
        if !x.is_finite() {
            self.non_finite += 1;
            return;
        }
        self.count += 1;
        self.fold(Some(x), Some(id), Some(x), Some(id));
    }

    fn fold(
        &mut self,
        min: Option<f64>,
        min_id: Option<u64>,
        max: Option<f64>,
        max_id: Option<u64>,
    ) {
        if let (Some(x), Some(id)) = (min, min_id) {
            let better = match (self.min, self.min_id) {
                (Some(m), Some(mid)) => x < m || (x == m && id < mid),
                _ => true,
            };
            if better {
                self.min = Some(x);
                self.min_id = Some(id);
            }
        }
        if let (Some(x), Some(id)) = (max, max_id) {
            let better = match (self.max, self.max_id) {
                (Some(m), Some(mid)) => x > m || (x == m && id < mid),
                _ => true,
            };
            if better {
                self.max = Some(x);
                self.max_id = Some(id);
            }
        }
    }
}

/// Extremes of one numeric column in a [`PartialSummary`] (plain numbers, no
/// allocation per update; same tie rule as [`ColumnStats`]).
#[derive(Clone, Copy, Debug, Default)]
struct Extremes {
    count: u64,
    non_finite: u64,
    min: Option<(f64, u64)>,
    max: Option<(f64, u64)>,
}

impl Extremes {
    #[inline]
    fn push(&mut self, x: f64, id: u64) {
        if !x.is_finite() {
            self.non_finite += 1;
            return;
        }
        self.count += 1;
        match self.min {
            Some((m, mid)) if !(x < m || (x == m && id < mid)) => {}
            _ => self.min = Some((x, id)),
        }
        match self.max {
            Some((m, mid)) if !(x > m || (x == m && id < mid)) => {}
            _ => self.max = Some((x, id)),
        }
    }
}

/// The summary of a run of rows, kept by one worker of the sweep driver and
/// folded into a [`Summary`] with [`Summary::absorb_partial`]: equivalent to
/// [`Summary::add`] on each row, without the per-row map look-ups by string.
#[derive(Clone, Debug, Default)]
pub(crate) struct PartialSummary {
    rows: u64,
    errors: u64,
    /// (valence, class, count); few distinct pairs, so a linear scan.
    classes: Vec<(usize, String, u64)>,
    columns: Vec<Extremes>,
}

impl PartialSummary {
    /// An empty partial summary for `numeric_columns` numeric columns.
    pub(crate) fn new(numeric_columns: usize) -> Self {
        PartialSummary {
            columns: vec![Extremes::default(); numeric_columns],
            ..Default::default()
        }
    }

    /// Adds the rows of `other` (same columns); the order does not matter
    /// (counts add up, extremes fold with the smaller-id tie rule).
    pub(crate) fn absorb(&mut self, other: &PartialSummary) {
        self.rows += other.rows;
        self.errors += other.errors;
        for (v, c, k) in &other.classes {
            match self
                .classes
                .iter_mut()
                .find(|(v2, c2, _)| v2 == v && c2 == c)
            {
                Some((_, _, x)) => *x += k,
                None => self.classes.push((*v, c.clone(), *k)),
            }
        }
        for (a, b) in self.columns.iter_mut().zip(&other.columns) {
            a.count += b.count;
            a.non_finite += b.non_finite;
            if let Some((x, id)) = b.min {
                if !matches!(a.min, Some((m, mid)) if !(x < m || (x == m && id < mid))) {
                    a.min = Some((x, id));
                }
            }
            if let Some((x, id)) = b.max {
                if !matches!(a.max, Some((m, mid)) if !(x > m || (x == m && id < mid))) {
                    a.max = Some((x, id));
                }
            }
        }
    }

    /// Rows counted.
    pub(crate) fn rows(&self) -> u64 {
        self.rows
    }

    /// Counts one row of `valence` in `class` (`errored`: its error cell is set).
    #[inline]
    pub(crate) fn count_row(&mut self, valence: usize, class: &str, errored: bool) {
        self.rows += 1;
        if errored {
            self.errors += 1;
        }
        match self
            .classes
            .iter_mut()
            .find(|(v, c, _)| *v == valence && c == class)
        {
            Some((_, _, k)) => *k += 1,
            None => self.classes.push((valence, class.to_owned(), 1)),
        }
    }

    /// The value `x` of numeric column `k` (its ordinal among the numeric
    /// columns) in configuration `id`.
    #[inline]
    pub(crate) fn push(&mut self, k: usize, x: f64, id: u64) {
        self.columns[k].push(x, id);
    }
}

/// Throughput of the run(s) behind a summary.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Throughput {
    /// Configurations evaluated in this run (not those read back on resume).
    pub evaluated: u64,
    /// Wall-clock seconds of the evaluation (summed over shards after a merge).
    pub seconds: f64,
    /// `evaluated / seconds`.
    pub configurations_per_second: f64,
    /// Worker threads (the largest over merged shards).
    pub threads: usize,
}

/// The summary of a sweep (or of one shard of it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Spec name.
    pub spec_name: String,
    /// Spec digest ([`SweepSpec::digest`](super::SweepSpec::digest)).
    pub spec_digest: String,
    /// Configurations of the full sweep.
    pub total_configurations: u64,
    /// The shard these rows belong to (`0/1` after a merge).
    pub shard: Shard,
    /// `--limit` of the run (configurations of the shard), if any.
    pub limit: Option<u64>,
    /// Configurations the shard has when complete (respecting the limit).
    pub expected_rows: u64,
    /// Rows accumulated.
    pub rows: u64,
    /// Whether every expected row is present.
    pub complete: bool,
    /// Rows whose evaluation failed (`error` column non-empty).
    pub errors: u64,
    /// Counts per valence (key) per class (key).
    pub classes: BTreeMap<String, BTreeMap<String, u64>>,
    /// Extremes of every numeric column, in CSV column order.
    pub columns: Vec<ColumnStats>,
    /// Throughput.
    pub throughput: Throughput,
    /// The data schema: every column of the rows file (CSV or Parquet), with
    /// its type, meaning and unit (math doc section 16.2).
    #[serde(default)]
    pub schema: Vec<crate::sweep::output::ColumnDoc>,
}

impl Summary {
    /// An empty summary for `shard` of `plan` (optionally limited to `limit` rows).
    pub fn new(plan: &Plan, layout: &Layout, shard: Shard, limit: Option<u64>) -> Self {
        let full = shard.len(plan.total());
        Summary {
            spec_name: plan.spec().name.clone(),
            spec_digest: plan.digest(),
            total_configurations: plan.total(),
            shard,
            limit,
            expected_rows: limit.map_or(full, |l| l.min(full)),
            rows: 0,
            complete: full == 0,
            errors: 0,
            classes: BTreeMap::new(),
            columns: layout
                .numeric_columns()
                .iter()
                .map(|(_, name)| ColumnStats::new(name.clone()))
                .collect(),
            throughput: Throughput::default(),
            schema: layout.column_docs().to_vec(),
        }
    }

    /// Adds one row.
    pub fn add(&mut self, layout: &Layout, row: &Row) {
        self.rows += 1;
        self.complete = self.rows == self.expected_rows;
        if row.error.is_some() {
            self.errors += 1;
        }
        let class =
            layout
                .class_of(row)
                .unwrap_or(if row.error.is_some() { "error" } else { "all" });
        // Look up before inserting: no allocation once a (valence, class) pair is known.
        let mut vbuf = itoa::Buffer::new();
        let vkey = vbuf.format(row.valence);
        if !self.classes.contains_key(vkey) {
            self.classes.insert(vkey.to_owned(), BTreeMap::new());
        }
        if let Some(per) = self.classes.get_mut(vkey) {
            match per.get_mut(class) {
                Some(k) => *k += 1,
                None => {
                    per.insert(class.to_owned(), 1);
                }
            }
        }
        for (stats, (pos, _)) in self.columns.iter_mut().zip(layout.numeric_columns()) {
            if let Some(x) = layout.number_at(row, *pos) {
                stats.push(x, row.id);
            }
        }
    }

    /// An empty accumulator for the same sweep, shard and columns (for partial
    /// summaries that [`Summary::absorb`] folds back).
    pub fn empty_like(&self) -> Summary {
        Summary {
            rows: 0,
            errors: 0,
            classes: BTreeMap::new(),
            columns: self
                .columns
                .iter()
                .map(|c| ColumnStats::new(c.name.clone()))
                .collect(),
            throughput: Throughput::default(),
            ..self.clone_header()
        }
    }

    fn clone_header(&self) -> Summary {
        Summary {
            spec_name: self.spec_name.clone(),
            spec_digest: self.spec_digest.clone(),
            total_configurations: self.total_configurations,
            shard: self.shard,
            limit: self.limit,
            expected_rows: self.expected_rows,
            rows: 0,
            complete: false,
            errors: 0,
            classes: BTreeMap::new(),
            columns: Vec::new(),
            throughput: Throughput::default(),
            schema: self.schema.clone(),
        }
    }

    /// Adds the rows of a partial summary of the same shard (from
    /// [`Summary::empty_like`]); equivalent to adding its rows one by one.
    pub fn absorb(&mut self, part: &Summary) {
        self.rows += part.rows;
        self.errors += part.errors;
        self.complete = self.rows == self.expected_rows;
        for (v, classes) in &part.classes {
            if !self.classes.contains_key(v) {
                self.classes.insert(v.clone(), BTreeMap::new());
            }
            if let Some(mine) = self.classes.get_mut(v) {
                for (c, k) in classes {
                    match mine.get_mut(c) {
                        Some(x) => *x += k,
                        None => {
                            mine.insert(c.clone(), *k);
                        }
                    }
                }
            }
        }
        for (a, b) in self.columns.iter_mut().zip(&part.columns) {
            a.count += b.count;
            a.non_finite += b.non_finite;
            a.fold(b.min, b.min_id, b.max, b.max_id);
        }
    }

    /// Adds the rows of a [`PartialSummary`] of the same layout; equivalent to
    /// adding its rows one by one (counts add up, extremes fold with the same
    /// smaller-id tie rule, so the order of partials does not matter).
    pub(crate) fn absorb_partial(&mut self, part: &PartialSummary) {
        self.rows += part.rows;
        self.errors += part.errors;
        self.complete = self.rows == self.expected_rows;
        let mut vbuf = itoa::Buffer::new();
        for (valence, class, k) in &part.classes {
            let vkey = vbuf.format(*valence);
            if !self.classes.contains_key(vkey) {
                self.classes.insert(vkey.to_owned(), BTreeMap::new());
            }
            if let Some(per) = self.classes.get_mut(vkey) {
                match per.get_mut(class.as_str()) {
                    Some(x) => *x += k,
                    None => {
                        per.insert(class.clone(), *k);
                    }
                }
            }
        }
        for (a, b) in self.columns.iter_mut().zip(&part.columns) {
            a.count += b.count;
            a.non_finite += b.non_finite;
            a.fold(
                b.min.map(|m| m.0),
                b.min.map(|m| m.1),
                b.max.map(|m| m.0),
                b.max.map(|m| m.1),
            );
        }
    }

    /// Records the throughput of this run.
    pub fn set_throughput(&mut self, evaluated: u64, seconds: f64, threads: usize) {
        self.throughput = Throughput {
            evaluated,
            seconds,
            configurations_per_second: if seconds > 0.0 {
                evaluated as f64 / seconds
            } else {
                0.0
            },
            threads,
        };
    }

    /// Combines the summary of another shard of the same sweep into this one. The
    /// result describes the union of the rows, as shard `0/1`.
    pub fn merge(&mut self, other: &Summary) -> Result<(), SweepError> {
        if other.spec_digest != self.spec_digest
            || other.total_configurations != self.total_configurations
        {
            return Err(SweepError::Merge(format!(
                "summaries come from different specs ({} with digest {}, {} with digest {})",
                self.spec_name, self.spec_digest, other.spec_name, other.spec_digest
            )));
        }
        if other.columns.len() != self.columns.len()
            || other
                .columns
                .iter()
                .zip(&self.columns)
                .any(|(a, b)| a.name != b.name)
        {
            return Err(SweepError::Merge("summaries have different columns".into()));
        }
        self.absorb(other);
        let t = &mut self.throughput;
        t.evaluated += other.throughput.evaluated;
        t.seconds += other.throughput.seconds;
        t.threads = t.threads.max(other.throughput.threads);
        t.configurations_per_second = if t.seconds > 0.0 {
            t.evaluated as f64 / t.seconds
        } else {
            0.0
        };
        self.shard = Shard::ALL;
        self.limit = None;
        self.expected_rows = self.total_configurations;
        self.complete = self.rows == self.total_configurations;
        Ok(())
    }

    /// The summary without throughput (the deterministic part: equal for any thread
    /// count, sharding or resume history).
    pub fn without_throughput(&self) -> Summary {
        Summary {
            throughput: Throughput::default(),
            ..self.clone()
        }
    }
}
