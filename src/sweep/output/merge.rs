//! The shard merge: shard CSVs, each verified in full, into one CSV in id
//! order.

use super::layout::Layout;
use super::verify::Verifier;
use crate::sweep::eval::Evaluate;
use crate::sweep::plan::{Plan, Shard};
use crate::sweep::summary::Summary;
use crate::sweep::SweepError;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::io::Write;

/// Line number of a sweep CSV's first data line (the header is line 1).
pub const FIRST_DATA_LINE: u64 = 2;

/// A source of CSV data lines for [`merge`] (its header already checked): a
/// name (for messages), the shard it holds (its summary's), and its data
/// lines without `\n`, in file order (the first is line 2 of the file, after the header).
pub struct MergeSource<I> {
    /// File name.
    pub name: String,
    /// The shard the file holds.
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
    let total = plan.total();
    let mut sources = sources;
    let mut verifiers: Vec<Verifier> = (0..sources.len())
        .map(|k| Verifier::new(plan, layout, salt ^ k as u64))
        .collect();
    // The next line of each source, verified: (id, line number, line).
    let advance = |src: &mut MergeSource<I>,
                   ver: &mut Verifier,
                   lineno: u64|
     -> Result<Option<(u64, u64, String)>, SweepError> {
        let Some(line) = src.lines.next() else {
            return Ok(None);
        };
        let line = line?;
        let expected = src.shard.id(ver.rows());
        let id = ver
            .check(lineno, &line, expected)
            .map_err(|m| SweepError::mismatch(&src.name, lineno, m))?;
        Ok(Some((id, lineno, line)))
    };
    // The heads of the sources, smallest id first: (id, source, line
    // number, line); a source has one head at a time. Every id is below the
    // sweep's total (the verifier derives its configuration from it).
    let mut heap = BinaryHeap::new();
    for (k, (src, ver)) in sources.iter_mut().zip(&mut verifiers).enumerate() {
        if let Some((id, lineno, line)) = advance(src, ver, FIRST_DATA_LINE)? {
            heap.push(Reverse((id, k, lineno, line)));
        }
    }
    let mut expected = 0u64;
    let mut last: Option<(u64, usize, u64)> = None;
    let mut buf = String::new();
    while let Some(Reverse((id, k, lineno, line))) = heap.pop() {
        if id < expected {
            let (_, pk, pl) = last.unwrap_or((id, k, lineno));
            return Err(SweepError::Merge(format!(
                "configuration id {id} appears twice ({} line {}, {} line {})",
                sources[pk].name, pl, sources[k].name, lineno
            )));
        }
        if id > expected {
            return Err(SweepError::Merge(format!(
                "configuration id {expected} is missing (next id found: {id} in {} line {})",
                sources[k].name, lineno
            )));
        }
        buf.push_str(&line);
        buf.push('\n');
        if buf.len() > 1 << 16 {
            out.write_all(buf.as_bytes())?;
            buf.clear();
        }
        last = Some((id, k, lineno));
        expected += 1;
        if let Some((nid, nl, next)) = advance(&mut sources[k], &mut verifiers[k], lineno + 1)? {
            heap.push(Reverse((nid, k, nl, next)));
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
            .map_err(|(line, m)| SweepError::mismatch(&src.name, line, m))?;
        let mut s = Summary::new(plan, layout, src.shard, None);
        ver.add_to(&mut s);
        parts.push(s);
    }
    Ok(parts)
}
