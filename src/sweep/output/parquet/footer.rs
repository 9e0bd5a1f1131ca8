//! The footer of a file of many row groups, assembled from each group's
//! serialised metadata (math doc section 16.2, "Cost of a footer per
//! commit").
//!
//! A commit writes the footer of the whole file so far, and the footer lists
//! every row group: about 690 bytes per group of the default columns at
//! n = 3. Serialised afresh at every commit by the `parquet` crate, the
//! footer of `G` groups costs time in proportion to `G` (13 ms at `G` = 1,526,
//! that is 10^8 rows), so a run of `G` groups spends time in proportion to
//! `G^2` on footers: about 10 CPU-seconds for 10^8 rows at n = 3, a quarter
//! of the evaluation. [`Footers`] serialises each group's metadata once and
//! assembles a footer by copying bytes, so that a commit costs a copy of the
//! footer (0.027 ms for the 1 MB footer at `G` = 1,526; `cargo bench --bench
//! parquet_footer`) and no serialisation beyond the new group.
//!
//! # The frame
//!
//! The footer is the Thrift compact encoding of `FileMetaData` (fields 1
//! `version`, 2 `schema`, 3 `num_rows`, 4 `row_groups`, then the key-value
//! metadata, `created_by` and the column orders), its length in 4 bytes
//! little-endian, and `PAR1`. In the compact protocol each element of a list
//! of structs is encoded on its own (a struct starts its field ids afresh), so
//! the metadata of a file of groups `g_1 .. g_G` holding `R` rows is
//!
//! ```text
//! P | zigzag-varint(R) | 0x19 | list header(G, struct) | g_1 | ... | g_G | S
//! ```
//!
//! where `P` ends with the header of field 3 (`0x16`: delta 1, type i64),
//! `0x19` is the header of field 4 (delta 1, type list) and the list header
//! is `(G << 4) | 0x0C` for `G < 15`, else `0xFC` and the varint `G`. `P` and
//! `S` do not depend on the groups. They are found, not assumed: `P` is the
//! longest common prefix of the crate's footers of no group and of one probe
//! group of one row (their first difference is the row count, `0` against
//! `2`, its zigzag encoding) and `S` their longest common suffix (the footer
//! of no group has `0x0C` before `S`, a group's encoding ends with the stop
//! byte `0x00`). Both
//! footers are then checked to be exactly the frame above, and so is the
//! footer of one group from which each group's bytes are cut; a footer that is
//! not framed so is an error, never a wrong file. Tests compare the
//! assembled footers with the crate's, byte for byte, up to and past the
//! one-byte list header.

use std::sync::Arc;

use parquet::file::metadata::{
    ColumnChunkMetaData, FileMetaData, KeyValue, ParquetMetaData, ParquetMetaDataBuilder,
    ParquetMetaDataWriter, RowGroupMetaData,
};
use parquet::file::properties::WriterProperties;
use parquet::schema::types::{SchemaDescriptor, TypePtr};

use super::pq_err;
use crate::sweep::SweepError;

/// Thrift compact header of field 4 (`row_groups`) after field 3: delta 1,
/// type list.
const ROW_GROUPS_FIELD: u8 = 0x19;
/// Thrift compact element type of a list of structs.
const STRUCT: u8 = 0x0C;

/// The footers of a growing file: the groups so far, each serialised once.
#[derive(Debug)]
pub(super) struct Footers {
    schema: TypePtr,
    props: Arc<WriterProperties>,
    key_value: Vec<KeyValue>,
    /// The metadata (without length and `PAR1`) of the file of no group.
    empty: Vec<u8>,
    /// `P` of the frame.
    prefix: Vec<u8>,
    /// `S` of the frame.
    suffix: Vec<u8>,
    groups: Vec<RowGroupMetaData>,
    /// The groups' encodings, one after the other.
    bytes: Vec<u8>,
    rows: i64,
}

/// The crate's encoding of the metadata of a file of `groups` (without the
/// length and `PAR1` that end a footer).
pub(super) fn metadata_bytes(
    schema: &TypePtr,
    props: &Arc<WriterProperties>,
    key_value: &[KeyValue],
    groups: &[RowGroupMetaData],
) -> Result<Vec<u8>, SweepError> {
    let rows: i64 = groups.iter().map(RowGroupMetaData::num_rows).sum();
    let file = FileMetaData::new(
        props.writer_version().as_num(),
        rows,
        Some(props.created_by().to_owned()),
        Some(key_value.to_vec()),
        Arc::new(SchemaDescriptor::new(schema.clone())),
        None,
    );
    let md: ParquetMetaData = ParquetMetaDataBuilder::new(file)
        .set_row_groups(groups.to_vec())
        .build();
    let mut out = Vec::new();
    ParquetMetaDataWriter::new(&mut out, &md)
        .finish()
        .map_err(pq_err)?;
    // `finish` ends with the length and `PAR1`.
    let n = out.len().checked_sub(8).ok_or_else(unframed)?;
    out.truncate(n);
    Ok(out)
}

/// The footer of the metadata `md`: `md`, its length, `PAR1`.
pub(super) fn with_trailer(mut md: Vec<u8>) -> Result<Vec<u8>, SweepError> {
    let len = u32::try_from(md.len())
        .map_err(|_| SweepError::Io(format!("parquet: a footer of {} bytes", md.len())))?;
    md.extend_from_slice(&len.to_le_bytes());
    md.extend_from_slice(super::MAGIC);
    Ok(md)
}

fn unframed() -> SweepError {
    SweepError::Io("parquet: the footer is not framed as expected (math doc 16.2)".into())
}

/// Appends `v` zigzag-encoded as a varint (a Thrift compact `i64`).
fn zigzag_i64(out: &mut Vec<u8>, v: i64) {
    super::encode::varint(out, ((v << 1) ^ (v >> 63)) as u64);
}

/// Appends the compact header of a list of `n` structs.
fn list_header(out: &mut Vec<u8>, n: usize) {
    if n < 15 {
        out.push(((n as u8) << 4) | STRUCT);
    } else {
        out.push(0xF0 | STRUCT);
        super::encode::varint(out, n as u64);
    }
}

/// The head of a file's metadata before its groups' encodings: `P`, the
/// rows, field 4's header and the list header.
fn head(p: &[u8], rows: i64, groups: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(p.len() + 16);
    out.extend_from_slice(p);
    zigzag_i64(&mut out, rows);
    out.push(ROW_GROUPS_FIELD);
    list_header(&mut out, groups);
    out
}

impl Footers {
    /// The footers of a file with `schema` and `key_value`, holding
    /// `existing` groups so far.
    pub(super) fn new(
        schema: TypePtr,
        props: Arc<WriterProperties>,
        key_value: Vec<KeyValue>,
        existing: Vec<RowGroupMetaData>,
    ) -> Result<Self, SweepError> {
        let empty = metadata_bytes(&schema, &props, &key_value, &[])?;
        let probe = probe_group(&schema)?;
        let one = metadata_bytes(&schema, &props, &key_value, &[probe])?;
        let (prefix, suffix) = frame_of(&empty, &one)?;
        let mut f = Footers {
            schema,
            props,
            key_value,
            empty,
            prefix,
            suffix,
            groups: Vec::with_capacity(existing.len()),
            bytes: Vec::new(),
            rows: 0,
        };
        for g in existing {
            f.push(g)?;
        }
        Ok(f)
    }

    /// The groups so far.
    pub(super) fn groups(&self) -> &[RowGroupMetaData] {
        &self.groups
    }

    /// Rows of the groups so far.
    pub(super) fn rows(&self) -> u64 {
        self.rows as u64
    }

    /// Adds group `g`: serialises it (in the footer of a file of `g` alone)
    /// and keeps its bytes.
    pub(super) fn push(&mut self, g: RowGroupMetaData) -> Result<(), SweepError> {
        let one = metadata_bytes(
            &self.schema,
            &self.props,
            &self.key_value,
            std::slice::from_ref(&g),
        )?;
        let (p, s) = (&self.prefix, &self.suffix);
        let h = head(p, g.num_rows(), 1);
        // `one` is exactly `h`, the group's bytes (at least its stop byte),
        // then `S`.
        if one.len() <= h.len() + s.len() || !one.starts_with(&h) || !one.ends_with(s) {
            return Err(unframed());
        }
        self.bytes
            .extend_from_slice(&one[h.len()..one.len() - s.len()]);
        self.rows += g.num_rows();
        self.groups.push(g);
        Ok(())
    }

    /// The footer of the file of the groups so far (metadata, length,
    /// `PAR1`).
    pub(super) fn footer(&self) -> Result<Vec<u8>, SweepError> {
        if self.groups.is_empty() {
            return with_trailer(self.empty.clone());
        }
        let (p, s) = (&self.prefix, &self.suffix);
        let mut md = head(p, self.rows, self.groups.len());
        md.reserve(self.bytes.len() + s.len() + 8);
        md.extend_from_slice(&self.bytes);
        md.extend_from_slice(s);
        with_trailer(md)
    }

    /// The footer as the `parquet` crate serialises it whole (for tests).
    #[cfg(test)]
    pub(super) fn footer_whole(&self) -> Result<Vec<u8>, SweepError> {
        with_trailer(metadata_bytes(
            &self.schema,
            &self.props,
            &self.key_value,
            &self.groups,
        )?)
    }
}

/// A group of one row whose column chunks carry the builder's defaults: the
/// probe from which the frame is found (whatever the sweep's groups hold).
fn probe_group(schema: &TypePtr) -> Result<RowGroupMetaData, SweepError> {
    let descr = Arc::new(SchemaDescriptor::new(schema.clone()));
    let columns = descr
        .columns()
        .iter()
        .map(|c| ColumnChunkMetaData::builder(c.clone()).build())
        .collect::<Result<Vec<_>, _>>()
        .map_err(pq_err)?;
    RowGroupMetaData::builder(descr)
        .set_num_rows(1)
        .set_column_metadata(columns)
        .build()
        .map_err(pq_err)
}

/// `P` and `S` from the metadata of the file of no group (`empty`) and of
/// one group (`one`), checked: `empty` must be `P 0x00 0x19 0x0C S` and `P`
/// must end with field 3's header.
fn frame_of(empty: &[u8], one: &[u8]) -> Result<(Vec<u8>, Vec<u8>), SweepError> {
    let p = empty.iter().zip(one).take_while(|(a, b)| a == b).count();
    let s = empty
        .iter()
        .rev()
        .zip(one.iter().rev())
        .take_while(|(a, b)| a == b)
        .count();
    let (pre, suf) = (&empty[..p], &empty[empty.len().saturating_sub(s)..]);
    let framed = pre.last() == Some(&0x16)
        && p + 3 + s == empty.len()
        && empty[p..p + 3] == [0x00, ROW_GROUPS_FIELD, STRUCT];
    if !framed {
        return Err(unframed());
    }
    Ok((pre.to_vec(), suf.to_vec()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::output::layout::Layout;
    use crate::sweep::plan::Plan;

    /// A layout with every optional column (labels, booleans, floats).
    fn schema() -> TypePtr {
        let spec = "name = \"f\"\nscheme = \"nurds\"\nvalences = [4]\n[space]\nkind = \"ratios\"\nratio_range = [0.1, 0.9]\n[sampler]\nkind = \"random\"\ncount = 10\nseed = 1\n[columns]\nexact_certificate = true\n";
        let plan = Plan::new(crate::sweep::SweepSpec::from_toml(spec).unwrap());
        super::super::schema_of(&Layout::new(&plan)).unwrap()
    }

    fn key_value() -> Vec<KeyValue> {
        vec![
            KeyValue::new("subdiv-lab.fingerprint".to_owned(), "# spec abc".to_owned()),
            KeyValue::new(
                "subdiv-lab.schema".to_owned(),
                "[{\"name\":\"id\"}]".to_owned(),
            ),
        ]
    }

    /// Group `k` of a file: `rows` rows, its column chunks at distinct
    /// offsets with distinct sizes (so that no two groups encode alike, and
    /// the varints have one to several bytes).
    fn group(schema: &TypePtr, k: usize, rows: i64) -> RowGroupMetaData {
        let descr = Arc::new(SchemaDescriptor::new(schema.clone()));
        let columns = descr
            .columns()
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let at = 4 + (k as i64) * 9_000_000 + (j as i64) * 524_300;
                ColumnChunkMetaData::builder(c.clone())
                    .set_num_values(rows)
                    .set_data_page_offset(at)
                    .set_total_compressed_size(524_300 + j as i64)
                    .set_total_uncompressed_size(524_300 + j as i64)
                    .build()
                    .unwrap()
            })
            .collect();
        RowGroupMetaData::builder(descr)
            .set_num_rows(rows)
            .set_ordinal(k as i32)
            .set_column_metadata(columns)
            .build()
            .unwrap()
    }

    /// The assembled footer is the crate's, byte for byte, for 0 to 40
    /// groups (the list header is one byte below 15 groups, two from 15) and
    /// at 130 (its varint takes two bytes), with groups of 0, 1 and many
    /// rows; and a file that starts with groups already committed (a resumed
    /// run) has the footers of one that pushed them one by one.
    #[test]
    fn assembled_footers_are_the_crates() {
        let schema = schema();
        let props = super::super::properties();
        let mut f = Footers::new(schema.clone(), props.clone(), key_value(), Vec::new()).unwrap();
        assert_eq!(f.footer().unwrap(), f.footer_whole().unwrap());
        let rows = |k: usize| match k % 4 {
            0 => 65_536,
            1 => 1,
            2 => 0,
            _ => 300 + k as i64,
        };
        let mut all = Vec::new();
        for k in 0..130 {
            let g = group(&schema, k, rows(k));
            all.push(g.clone());
            f.push(g).unwrap();
            if k < 40 || k == 129 {
                assert_eq!(
                    f.footer().unwrap(),
                    f.footer_whole().unwrap(),
                    "{} groups",
                    k + 1
                );
            }
        }
        assert_eq!(f.groups().len(), 130);
        assert_eq!(f.rows(), (0..130).map(rows).sum::<i64>() as u64);
        let resumed = Footers::new(schema, props, key_value(), all).unwrap();
        assert_eq!(resumed.footer().unwrap(), f.footer().unwrap());
    }

    /// A frame is refused unless the footer of no group is exactly
    /// `P 0x00 0x19 0x0C S` with `P` ending in field 3's header.
    #[test]
    fn frames_that_are_not_the_expected_one_are_refused() {
        let p = [0x15, 0x02, 0x19, 0x1C, 0x16];
        let s = [0x15, 0x04, 0x00];
        let empty = [&p[..], &[0x00, 0x19, 0x0C], &s[..]].concat();
        let one = [&p[..], &[0x02, 0x19, 0x1C, 0x00], &s[..]].concat();
        let (pp, ss) = frame_of(&empty, &one).unwrap();
        assert_eq!((pp.as_slice(), ss.as_slice()), (&p[..], &s[..]));
        // Field 3 is not an i64 header; a byte too many; a byte too few.
        let bad_p = [&p[..4], &[0x17, 0x00, 0x19, 0x0C], &s[..]].concat();
        let bad_one = [&p[..4], &[0x17, 0x02, 0x19, 0x1C, 0x00], &s[..]].concat();
        assert!(frame_of(&bad_p, &bad_one).is_err());
        let long = [&p[..], &[0x00, 0x19, 0x0C, 0x07], &s[..]].concat();
        assert!(frame_of(&long, &one).is_err());
        let short = [&p[..], &[0x00, 0x19], &s[..]].concat();
        assert!(frame_of(&short, &one).is_err());
    }
}
