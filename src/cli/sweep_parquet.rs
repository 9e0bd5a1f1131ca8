//! The file side of `sweep --format parquet`: the commit protocol (row group,
//! footer, journal) and resume. The encoding, the verification and the journal
//! format live in `subdiv_lab::sweep::output::parquet` (math doc section 16.2).
//!
//! On disk: `NAME.parquet` is `PAR1`, the committed row groups and the footer
//! of the last commit (a valid Parquet file after every commit);
//! `.NAME.parquet.commit` (beside it, while the run is unfinished) is the
//! journal of the last commit, replaced atomically after each one. A commit
//! truncates the file at the end of the previous group (dropping its footer),
//! writes the group and the new footer, then replaces the journal. A run
//! killed anywhere leaves a file whose first `data_end` bytes (the journal's)
//! are the committed groups: `--resume` truncates there and appends the
//! journal's footer, which drops a torn trailing group.

use super::outfiles::parent_dir;
use super::{CliError, CliResult};
use anyhow::{anyhow, Context};
use std::fs::{self, File, OpenOptions};
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use subdiv_lab::sweep::output::parquet::{
    self as pq, footer_for_groups, journal_bytes, parse_journal, read_table, Commit, ParquetRows,
};
use subdiv_lab::sweep::output::{self, LineFault, Verifier};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepError};

/// The commit callback of a run.
pub(crate) type CommitFn = Box<dyn FnMut(Commit<'_>) -> std::io::Result<()> + Send>;

/// The rows sink of a Parquet run.
pub(crate) struct ParquetSink {
    rows: ParquetRows<CommitFn>,
    journal: PathBuf,
}

impl ParquetSink {
    /// The rows (for the sweep driver's typed path).
    pub(crate) fn rows_mut(&mut self) -> &mut ParquetRows<CommitFn> {
        &mut self.rows
    }

    /// Commits the last group and removes the journal (the file is complete).
    pub(crate) fn finish(self) -> anyhow::Result<()> {
        self.rows.finish().map_err(|e| anyhow!("{e}"))?;
        match fs::remove_file(&self.journal) {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
            Err(e) => Err(anyhow!("removing {}: {e}", self.journal.display())),
        }
    }
}

/// `.NAME.commit` beside `path`.
fn journal_path(path: &Path) -> PathBuf {
    path.with_file_name(format!(
        ".{}.commit",
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    ))
}

/// Truncates `file` at `at` and writes the pieces of `group`, then
/// `footer`, there.
fn write_at(file: &mut File, at: u64, group: &[&[u8]], footer: &[u8]) -> std::io::Result<()> {
    file.set_len(at)?;
    file.seek(SeekFrom::Start(at))?;
    for p in group.iter().chain([&footer]) {
        file.write_all(p)?;
    }
    file.flush()
}

fn commit_fn(mut file: File, journal: PathBuf) -> CommitFn {
    Box::new(move |c: Commit<'_>| {
        write_at(&mut file, c.offset, c.group, c.footer)?;
        let end = c.offset + c.group_len();
        super::outfiles::write_atomic(&journal, &journal_bytes(end, c.footer))
            .map_err(|e| std::io::Error::other(format!("{e:#}")))
    })
}

/// Opens `path` for a Parquet run of `shard`: a new file, or (when it exists)
/// the committed rows of an earlier run, recovered from the journal if the run
/// was killed, verified in full ([`Verifier`], as for a CSV) and added to
/// `summary`. Returns the sink, the rows already present and whether groups
/// after the last commit (or a last short group) were dropped.
pub(crate) fn open(
    path: &Path,
    plan: &Plan,
    layout: &Layout,
    eval: &SpectralEvaluator,
    shard: Shard,
    summary: &mut Summary,
    salt: u64,
) -> CliResult<(ParquetSink, u64, bool)> {
    let name = path.display().to_string();
    let journal = journal_path(path);
    let fingerprint = output::fingerprint_line(plan, shard);
    let io = |e: std::io::Error, what: &str| CliError::failure(anyhow!("{what} {name}: {e}"));
    let mut recovered = false;
    let mut existing = Vec::new();
    let mut data_end = pq::MAGIC.len() as u64;
    let mut done = 0u64;
    let exists = fs::symlink_metadata(path).is_ok();
    if exists {
        // A killed run: back to the journal's last commit.
        if journal.exists() {
            let j = fs::read(&journal).map_err(|e| io(e, "reading the journal of"))?;
            let (end, footer) = parse_journal(&j).map_err(|m| {
                CliError::usage(anyhow!("{}: {m}; cannot resume", journal.display()))
            })?;
            let len = fs::metadata(path).map_err(|e| io(e, "reading"))?.len();
            if len < end {
                return Err(CliError::usage(anyhow!(
                    "{name}: shorter ({len} bytes) than its last commit ({end} bytes); cannot resume"
                )));
            }
            let mut f = OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|e| io(e, "opening"))?;
            write_at(&mut f, end, &[], &footer).map_err(|e| io(e, "writing"))?;
            recovered = len != end + footer.len() as u64;
        }
        let bytes = fs::read(path).map_err(|e| io(e, "reading"))?;
        if bytes.is_empty() {
            // A file of this tool is created whole (PAR1 and a footer):
            // an empty one is someone else's.
            return Err(CliError::usage(anyhow!(
                "{name} exists but is empty: not a sweep file of this tool (one is created whole, with its fingerprint); remove it or choose another --out"
            )));
        }
        {
            let table = read_table(bytes).map_err(|e| {
                CliError::usage(anyhow!(
                    "{}; cannot resume (not a sweep Parquet file, or torn without its commit journal)",
                    read_error(&name, e)
                ))
            })?;
            let mismatch = |line: u64, message: String| {
                CliError::usage(SweepError::Mismatch {
                    source_name: name.clone(),
                    line,
                    message,
                })
            };
            let fp = table.fingerprint().unwrap_or_default().to_owned() + "\n";
            output::check_fingerprint(plan, shard, &fp)
                .map_err(|m| mismatch(1, format!("{m}; cannot resume")))?;
            if table.names != layout.column_names() {
                return Err(CliError::usage(anyhow!(
                    "{name}: the columns do not match this spec's; cannot resume (expected {})",
                    layout.column_names().join(",")
                )));
            }
            let rows = table.rows() as u64;
            let expected = summary.expected_rows;
            if rows > expected {
                return Err(CliError::usage(anyhow!(
                    "{name}: has more rows than this run expects ({expected}); was it written with another --limit?"
                )));
            }
            // Keep the leading full groups (all of them if the file is
            // complete): the groups are then those of an uninterrupted run.
            let sizes = table.group_rows();
            let keep = if rows == expected {
                sizes.len()
            } else {
                sizes
                    .iter()
                    .take_while(|&&r| r == pq::ROW_GROUP_ROWS as u64)
                    .count()
            };
            done = sizes[..keep].iter().sum();
            let lines = table.csv_lines(0, done as usize);
            let mut verifier = Verifier::new(plan, layout, salt);
            let expected_id = |j: u64| shard.id(j);
            verifier
                .check_block(1, lines.as_bytes(), &expected_id, expected)
                .map_err(|(l, fault)| match fault {
                    LineFault::Mismatch(m) => mismatch(l, format!("row {l}: {m}")),
                    LineFault::NotUtf8 => mismatch(l, "not UTF-8".into()),
                    LineFault::TooManyRows => mismatch(l, "more rows than expected".into()),
                })?;
            verifier.recheck(eval).map_err(|(l, m)| mismatch(l, m))?;
            verifier.add_to(summary);
            data_end = table.end_of_groups(keep);
            if keep < sizes.len() {
                let footer = footer_for_groups(layout, &table, keep).map_err(CliError::failure)?;
                let mut f = OpenOptions::new()
                    .write(true)
                    .open(path)
                    .map_err(|e| io(e, "opening"))?;
                write_at(&mut f, data_end, &[], &footer).map_err(|e| io(e, "writing"))?;
                recovered = true;
            }
            existing = table.row_groups()[..keep].to_vec();
        }
    }
    if exists {
        let file = OpenOptions::new()
            .write(true)
            .open(path)
            .with_context(|| format!("opening {name}"))
            .map_err(CliError::failure)?;
        let commit = commit_fn(
            file.try_clone().map_err(|e| io(e, "opening"))?,
            journal.clone(),
        );
        let rows = ParquetRows::new(layout, &fingerprint, existing, data_end, commit)
            .map_err(CliError::failure)?;
        return Ok((ParquetSink { rows, journal }, done, recovered));
    }
    // A new file: PAR1 and the footer of no group (valid Parquet), written to
    // a temporary file of this run and put in place whole, so that a file at
    // `path` without a fingerprint is never the tool's.
    let name_only = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let (mut file, tmp) = super::outfiles::create_temp_file(&parent_dir(path), &name_only)
        .with_context(|| format!("creating {name}"))
        .map_err(CliError::failure)?;
    let created = (|| -> CliResult<ParquetRows<CommitFn>> {
        let commit = commit_fn(
            file.try_clone().map_err(|e| io(e, "creating"))?,
            journal.clone(),
        );
        let rows = ParquetRows::new(layout, &fingerprint, existing, data_end, commit)
            .map_err(CliError::failure)?;
        let footer = rows.current_footer().map_err(CliError::failure)?;
        write_at(&mut file, 0, &[pq::MAGIC], &footer).map_err(|e| io(e, "writing"))?;
        Ok(rows)
    })();
    let rows = match created {
        Ok(rows) => rows,
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            return Err(e);
        }
    };
    super::outfiles::install_new(&tmp, path).map_err(|e| io(e, "creating"))?;
    let footer = rows.current_footer().map_err(CliError::failure)?;
    super::outfiles::write_atomic(&journal, &journal_bytes(data_end, &footer))
        .map_err(CliError::failure)?;
    Ok((ParquetSink { rows, journal }, done, recovered))
}

/// The message of a failure to read `name`: "cannot read NAME: ..." for a
/// file that is not (or no longer) a readable Parquet file.
fn read_error(name: &str, e: SweepError) -> String {
    match e {
        SweepError::Read(m) => format!("cannot read {name}: {m}"),
        other => format!("{name}: {other}"),
    }
}

/// The rows sink of a merged Parquet file (written to a temporary file that
/// the caller renames when every check passed: no journal).
pub(crate) fn merge_sink(
    mut file: File,
    plan: &Plan,
    layout: &Layout,
) -> CliResult<ParquetRows<CommitFn>> {
    file.write_all(pq::MAGIC).map_err(CliError::failure)?;
    let commit: CommitFn =
        Box::new(move |c: Commit<'_>| write_at(&mut file, c.offset, c.group, c.footer));
    let rows = ParquetRows::new(
        layout,
        &output::fingerprint_line(plan, Shard::ALL),
        Vec::new(),
        pq::MAGIC.len() as u64,
        commit,
    )
    .map_err(CliError::failure)?;
    Ok(rows)
}
