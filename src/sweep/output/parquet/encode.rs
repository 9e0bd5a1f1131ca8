//! The bytes of one row group: each column chunk encoded directly from the
//! typed column buffers (math doc section 16.2).
//!
//! A sweep's columns need only the simplest part of the Parquet format, so
//! the chunks are written here rather than through a general column writer
//! (which hashes every value for its dictionary, buffers pages and copies
//! each value several times: at n = 3 it cost more than a third of the
//! evaluation itself). Each column chunk is one uncompressed version-1 data
//! page, preceded for the label columns by one dictionary page:
//!
//! * page headers: the Thrift compact encoding of `PageHeader` with its
//!   required fields only (no statistics, no CRC);
//! * definition levels (optional columns, maximum level 1): the RLE /
//!   bit-packed hybrid of width 1, prefixed by its length in 4 bytes
//!   (little-endian); one RLE run when every row has a value (or none has),
//!   otherwise one bit-packed run;
//! * values: `PLAIN` (integers and doubles little-endian, booleans one bit
//!   each least significant first, byte arrays as a 4-byte length and the
//!   bytes), or for the labels `RLE_DICTIONARY` indices (a bit-width byte and
//!   one hybrid run) into a `PLAIN` dictionary of the group's distinct labels
//!   in order of first appearance.
//!
//! The group is handed over in pieces ([`GroupBytes`]): the headers, levels
//! and small bodies in one buffer, and the values of the integer and float
//! columns as the column buffers' own bytes (on a little-endian machine),
//! so that a group's values are not copied before they are written.
//!
//! The bytes depend only on the rows, so a group is the same for any thread
//! count or interruption point. Readers (arrow-rs, pyarrow, polars) decode
//! them as any Parquet file; the tests read every sweep file back.

use parquet::basic::{Compression, Encoding};
use parquet::file::metadata::{ColumnChunkMetaData, RowGroupMetaData};
use parquet::schema::types::SchemaDescPtr;

use super::{Values, NULL_BOOL, NULL_F64, NULL_INDEX};
use crate::sweep::SweepError;

/// Thrift `PageType` of a data page (version 1).
const DATA_PAGE: i32 = 0;
/// Thrift `PageType` of a dictionary page.
const DICTIONARY_PAGE: i32 = 2;
/// Thrift `Encoding` values used here.
const PLAIN: i32 = 0;
const PLAIN_DICTIONARY: i32 = 2;
const RLE: i32 = 3;
const RLE_DICTIONARY: i32 = 8;

/// A row group's bytes as a sequence of pieces: runs of an owned buffer
/// (page headers, definition levels, small bodies) and whole column buffers
/// whose bytes are the page's values as they are ([`Piece::Column`]).
#[derive(Debug, Default)]
pub(super) struct GroupBytes {
    own: Vec<u8>,
    pieces: Vec<Piece>,
    /// Start in `own` of the run not yet closed by a [`Piece::Column`].
    open: usize,
    /// Bytes of the column pieces so far.
    borrowed: usize,
}

/// A piece of [`GroupBytes`].
#[derive(Clone, Copy, Debug)]
enum Piece {
    /// Bytes `a..b` of the owned buffer.
    Own(usize, usize),
    /// All the bytes of column `k`'s values.
    Column(usize),
}

impl GroupBytes {
    fn clear(&mut self) {
        self.own.clear();
        self.pieces.clear();
        self.open = 0;
        self.borrowed = 0;
    }

    /// Bytes of the group so far.
    pub(super) fn len(&self) -> usize {
        self.own.len() + self.borrowed
    }

    /// Closes the owned run so far.
    fn close(&mut self) {
        if self.own.len() > self.open {
            self.pieces.push(Piece::Own(self.open, self.own.len()));
            self.open = self.own.len();
        }
    }

    /// Appends the `bytes` bytes of column `k`'s values, as they are.
    fn column(&mut self, k: usize, bytes: usize) {
        self.close();
        self.pieces.push(Piece::Column(k));
        self.borrowed += bytes;
    }

    /// The pieces, in order, the column pieces taken from `values` (those
    /// the group was encoded from).
    pub(super) fn pieces<'a>(&'a self, values: &'a [Values]) -> Vec<&'a [u8]> {
        self.pieces
            .iter()
            .map(|p| match *p {
                Piece::Own(a, b) => &self.own[a..b],
                Piece::Column(k) => match &values[k] {
                    Values::U64(x) => bytemuck::cast_slice(x),
                    Values::U32(x) => bytemuck::cast_slice(x),
                    Values::F64(x, _) => bytemuck::cast_slice(x),
                    // Never a column piece (see `encode_group`).
                    Values::Dict(_) | Values::Str(_) | Values::Bool(_) => &[],
                },
            })
            .collect()
    }
}

/// Appends `v` as an unsigned LEB128 varint.
pub(super) fn varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// Appends a Thrift compact `i32` field whose id is one more than the
/// previous field's (the field header `0x15`: delta 1, type i32).
fn i32_field(out: &mut Vec<u8>, v: i32) {
    out.push(0x15);
    varint(out, ((v << 1) ^ (v >> 31)) as u32 as u64);
}

/// The Thrift compact `PageHeader` of a page of `size` bytes holding
/// `values` values in `encoding`: a data page (`DataPageHeader`, field 5,
/// levels RLE) or a dictionary page (`DictionaryPageHeader`, field 7).
fn page_header(out: &mut Vec<u8>, dictionary: bool, size: i32, values: i32, encoding: i32) {
    i32_field(
        out,
        if dictionary {
            DICTIONARY_PAGE
        } else {
            DATA_PAGE
        },
    );
    i32_field(out, size); // uncompressed_page_size
    i32_field(out, size); // compressed_page_size
    if dictionary {
        out.push(0x4c); // field 7 (delta 4), struct
        i32_field(out, values);
        i32_field(out, encoding);
    } else {
        out.push(0x2c); // field 5 (delta 2), struct
        i32_field(out, values);
        i32_field(out, encoding);
        i32_field(out, RLE); // definition_level_encoding
        i32_field(out, RLE); // repetition_level_encoding
    }
    out.push(0); // end of the inner struct
    out.push(0); // end of PageHeader
}

/// Appends `values` (each below `2^width`, `width` <= 32) packed `width`
/// bits each, least significant bit first, padded with zero bits to a whole
/// number of groups of 8 values.
fn bit_pack(out: &mut Vec<u8>, values: impl Iterator<Item = u32>, width: u32) {
    let mut acc: u64 = 0;
    let mut bits = 0u32;
    let mut count = 0usize;
    for v in values {
        acc |= u64::from(v) << bits;
        bits += width;
        while bits >= 8 {
            out.push(acc as u8);
            acc >>= 8;
            bits -= 8;
        }
        count += 1;
    }
    // Pad to a multiple of 8 values (8 values of `width` bits fill `width` bytes).
    let padded_bits = (count.div_ceil(8) * 8 - count) as u32 * width + bits;
    let mut left = padded_bits;
    while left >= 8 {
        out.push(acc as u8);
        acc >>= 8;
        left -= 8;
    }
    debug_assert_eq!(left, 0);
}

/// [`bit_pack`] of width 1 for flags: a byte per 8 flags, least
/// significant bit first, the last byte padded with zeros (the same bytes,
/// without the general packer's shifts per value).
fn bit_pack_flags(out: &mut Vec<u8>, flags: impl Iterator<Item = bool>) {
    let (mut byte, mut k) = (0u8, 0u32);
    for f in flags {
        byte |= u8::from(f) << k;
        k += 1;
        if k == 8 {
            out.push(byte);
            (byte, k) = (0, 0);
        }
    }
    if k > 0 {
        out.push(byte);
    }
}

/// Appends the RLE / bit-packed hybrid encoding of `values` (`count` of
/// them, each below `2^width`): one RLE run if they are all equal, else one
/// bit-packed run.
fn hybrid(out: &mut Vec<u8>, values: &[u32], width: u32) {
    let Some(&first) = values.first() else {
        return;
    };
    if values.iter().all(|&v| v == first) {
        varint(out, (values.len() as u64) << 1);
        let bytes = width.div_ceil(8) as usize;
        out.extend_from_slice(&first.to_le_bytes()[..bytes]);
    } else {
        varint(out, ((values.len().div_ceil(8) as u64) << 1) | 1);
        bit_pack(out, values.iter().copied(), width);
    }
}

/// Appends the definition levels of `rows` rows, `values` of which hold a
/// value (`has` says which, row by row), in the hybrid encoding of width 1,
/// prefixed by their length (4 bytes, little-endian): one RLE run when all or
/// none hold a value, otherwise one bit-packed run.
fn def_levels(out: &mut Vec<u8>, rows: usize, values: usize, has: impl Iterator<Item = bool>) {
    let at = out.len();
    out.extend_from_slice(&[0; 4]);
    if values == rows || values == 0 {
        varint(out, (rows as u64) << 1);
        out.push(u8::from(values == rows));
    } else {
        varint(out, ((rows.div_ceil(8) as u64) << 1) | 1);
        bit_pack_flags(out, has);
    }
    let len = (out.len() - at - 4) as u32;
    out[at..at + 4].copy_from_slice(&len.to_le_bytes());
}

/// Appends the little-endian bytes of `x` (`N` bytes each), the values of
/// column `k`: on a little-endian machine the column's own bytes, not
/// copied; otherwise converted into the owned buffer.
fn plain<const N: usize, T: bytemuck::Pod>(
    out: &mut GroupBytes,
    k: usize,
    x: &[T],
    bytes: impl Fn(T) -> [u8; N],
) {
    if cfg!(target_endian = "little") {
        out.column(k, N * x.len());
    } else {
        out.own.reserve(N * x.len());
        for &v in x {
            out.own.extend_from_slice(&bytes(v));
        }
    }
}

/// Bits needed for indices below `entries` (at least 1).
fn index_width(entries: usize) -> u32 {
    (usize::BITS - entries.saturating_sub(1).leading_zeros()).max(1)
}

fn too_big(what: &str) -> SweepError {
    SweepError::Io(format!("parquet: a page of {what} over 2 GiB"))
}

/// Appends a page: its header, then `parts` (the body, in pieces).
fn page(
    out: &mut Vec<u8>,
    dictionary: bool,
    parts: &[&[u8]],
    values: usize,
    encoding: i32,
) -> Result<(), SweepError> {
    let len: usize = parts.iter().map(|p| p.len()).sum();
    let size = i32::try_from(len).map_err(|_| too_big("bytes"))?;
    let values = i32::try_from(values).map_err(|_| too_big("values"))?;
    page_header(out, dictionary, size, values, encoding);
    for p in parts {
        out.extend_from_slice(p);
    }
    Ok(())
}

/// The row group of `values` (`rows` rows each) into `group` (its pieces,
/// [`GroupBytes::pieces`] of the same `values`), whose first byte goes at
/// byte `offset` of the file; returns its metadata (row group `ordinal`).
pub(super) fn encode_group(
    schema: &SchemaDescPtr,
    values: &[Values],
    rows: usize,
    offset: u64,
    ordinal: usize,
    group: &mut GroupBytes,
) -> Result<RowGroupMetaData, SweepError> {
    group.clear();
    // Definition levels, and the values of the pages not written in place.
    let mut levels = Vec::new();
    let mut body = Vec::new();
    let mut indices = Vec::new();
    let mut columns = Vec::with_capacity(values.len());
    let at = |g: &GroupBytes| offset as i64 + g.len() as i64;
    for (k, v) in values.iter().enumerate() {
        let start = at(group);
        let mut dictionary_offset = None;
        levels.clear();
        body.clear();
        let encoding = match v {
            Values::U64(x) => {
                let size = bytes_i32(8 * x.len())?;
                page_header(&mut group.own, false, size, rows_i32(rows)?, PLAIN);
                plain(group, k, x, i64::to_le_bytes);
                None
            }
            Values::U32(x) => {
                let size = bytes_i32(4 * x.len())?;
                page_header(&mut group.own, false, size, rows_i32(rows)?, PLAIN);
                plain(group, k, x, i32::to_le_bytes);
                None
            }
            &Values::F64(ref x, nulls) => {
                let null = |v: &f64| v.to_bits() == NULL_F64;
                debug_assert_eq!(nulls, x.iter().filter(|v| null(v)).count());
                def_levels(&mut levels, rows, rows - nulls, x.iter().map(|v| !null(v)));
                let size = bytes_i32(levels.len() + 8 * (rows - nulls))?;
                page_header(&mut group.own, false, size, rows_i32(rows)?, PLAIN);
                group.own.extend_from_slice(&levels);
                if nulls == 0 {
                    plain(group, k, x, f64::to_le_bytes);
                } else {
                    // The non-null values, into room made once.
                    let out = &mut group.own;
                    let n0 = out.len();
                    out.resize(n0 + 8 * (rows - nulls), 0);
                    let mut dst = out[n0..].chunks_exact_mut(8);
                    for v in x.iter().filter(|v| !null(v)) {
                        if let Some(d) = dst.next() {
                            d.copy_from_slice(&v.to_le_bytes());
                        }
                    }
                }
                None
            }
            Values::Bool(x) => {
                let set = x.iter().filter(|&&b| b != NULL_BOOL);
                def_levels(
                    &mut levels,
                    rows,
                    set.clone().count(),
                    x.iter().map(|&b| b != NULL_BOOL),
                );
                // PLAIN booleans: one bit each, least significant first; the
                // padding of the last byte is ignored by readers.
                bit_pack_flags(&mut body, set.map(|&b| b == 1));
                Some(PLAIN)
            }
            Values::Str(x) => {
                let texts = &x.texts;
                debug_assert_eq!(x.rows, rows);
                let mut next = texts.iter().map(|(r, _)| *r).peekable();
                let has = (0..rows).map(|r| next.next_if_eq(&r).is_some());
                def_levels(&mut levels, rows, texts.len(), has);
                for (_, s) in texts {
                    let len = u32::try_from(s.len()).map_err(|_| too_big("text"))?;
                    body.extend_from_slice(&len.to_le_bytes());
                    body.extend_from_slice(s.as_bytes());
                }
                Some(PLAIN)
            }
            Values::Dict(dict) => {
                // The dictionary page: the distinct labels, PLAIN.
                for e in dict.entries() {
                    let len = u32::try_from(e.len()).map_err(|_| too_big("text"))?;
                    body.extend_from_slice(&len.to_le_bytes());
                    body.extend_from_slice(e.as_bytes());
                }
                dictionary_offset = Some(start);
                let n = dict.entries().len();
                page(&mut group.own, true, &[&body], n, PLAIN_DICTIONARY)?;
                body.clear();
                indices.clear();
                indices.extend(dict.indices().iter().copied().filter(|&i| i != NULL_INDEX));
                let has = dict.indices().iter().map(|&i| i != NULL_INDEX);
                def_levels(&mut levels, rows, indices.len(), has);
                let width = index_width(dict.entries().len());
                body.push(width as u8);
                hybrid(&mut body, &indices, width);
                Some(RLE_DICTIONARY)
            }
        };
        let data_offset = match encoding {
            // Written in place above (header first).
            None => start,
            Some(e) => {
                let d = at(group);
                page(&mut group.own, false, &[&levels, &body], rows, e)?;
                d
            }
        };
        let size = at(group) - start;
        let encodings = if dictionary_offset.is_some() {
            vec![
                Encoding::PLAIN_DICTIONARY,
                Encoding::RLE,
                Encoding::RLE_DICTIONARY,
            ]
        } else {
            vec![Encoding::PLAIN, Encoding::RLE]
        };
        let meta = ColumnChunkMetaData::builder(schema.column(k))
            .set_encodings(encodings)
            .set_compression(Compression::UNCOMPRESSED)
            .set_num_values(rows as i64)
            .set_total_compressed_size(size)
            .set_total_uncompressed_size(size)
            .set_data_page_offset(data_offset)
            .set_dictionary_page_offset(dictionary_offset)
            .build()
            .map_err(super::pq_err)?;
        columns.push(meta);
    }
    group.close();
    RowGroupMetaData::builder(schema.clone())
        .set_num_rows(rows as i64)
        .set_total_byte_size(group.len() as i64)
        .set_column_metadata(columns)
        .set_ordinal(i32::try_from(ordinal).unwrap_or(i32::MAX))
        .set_file_offset(offset as i64)
        .build()
        .map_err(super::pq_err)
}

/// A page size as the header's `i32`.
fn bytes_i32(n: usize) -> Result<i32, SweepError> {
    i32::try_from(n).map_err(|_| too_big("bytes"))
}

/// A value count as the header's `i32`.
fn rows_i32(n: usize) -> Result<i32, SweepError> {
    i32::try_from(n).map_err(|_| too_big("values"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varints_and_zigzag() {
        let mut v = Vec::new();
        varint(&mut v, 300);
        assert_eq!(v, [0xac, 0x02]);
        v.clear();
        i32_field(&mut v, -1);
        assert_eq!(v, [0x15, 0x01]);
        v.clear();
        i32_field(&mut v, 65_536);
        assert_eq!(v, [0x15, 0x80, 0x80, 0x08]);
    }

    #[test]
    fn flags_pack_as_width_one() {
        for n in [0usize, 1, 7, 8, 9, 16, 21, 64, 100] {
            let flags: Vec<bool> = (0..n).map(|i| (i * 7 + i / 3) % 5 < 2).collect();
            let (mut a, mut b) = (Vec::new(), Vec::new());
            bit_pack(&mut a, flags.iter().map(|&f| u32::from(f)), 1);
            bit_pack_flags(&mut b, flags.iter().copied());
            assert_eq!(a, b, "{n} flags");
        }
    }

    #[test]
    fn bit_packing_pads_to_groups_of_eight() {
        let mut v = Vec::new();
        // The example of the Parquet format's documentation: 0..=7, width 3.
        bit_pack(&mut v, 0..8, 3);
        assert_eq!(v, [0b1000_1000, 0b1100_0110, 0b1111_1010]);
        v.clear();
        bit_pack(&mut v, [1, 1, 1].into_iter(), 1);
        assert_eq!(v, [0b0000_0111]);
        v.clear();
        bit_pack(&mut v, (0..9).map(|i| i % 2), 2);
        assert_eq!(v.len(), 4, "9 values of 2 bits pad to 16 values, 4 bytes");
    }

    #[test]
    fn hybrid_runs() {
        let mut v = Vec::new();
        hybrid(&mut v, &[1; 100], 1);
        assert_eq!(v, [200, 1, 1], "one RLE run: header 100 << 1, value");
        v.clear();
        hybrid(&mut v, &[1, 0, 1], 1);
        assert_eq!(v, [0b11, 0b101], "one bit-packed group");
        assert_eq!(index_width(1), 1);
        assert_eq!(index_width(2), 1);
        assert_eq!(index_width(3), 2);
        assert_eq!(index_width(256), 8);
        assert_eq!(index_width(257), 9);
    }
}
