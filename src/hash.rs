//! The crate's non-cryptographic hashes: 64-bit FNV-1a (Fowler, Noll and
//! Vo), for per-item seeds ([`crate::rng::derive_seed`]) and spec digests
//! ([`crate::sweep::spec`]), and its step over 64-bit words, for checksums
//! of long byte strings (the Parquet commit journal). Their values are
//! recorded (seeds in report manifests, digests in sweep summaries,
//! checksums in journals), so they must never change.

/// The FNV-1a offset basis of 64-bit hashes.
const FNV_OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
/// The 64-bit FNV prime, `2^40 + 2^8 + 0xb3`.
const FNV_PRIME: u64 = 0x0000_0100_0000_01B3;

/// 64-bit FNV-1a of `bytes`: from the offset basis, for each byte `b`,
/// `h = (h ^ b) * prime (mod 2^64)`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h = FNV_OFFSET_BASIS;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(FNV_PRIME);
    }
    h
}

/// FNV-1a's step over the 64-bit little-endian words of `bytes` (the last
/// one padded with zero bytes), then over the length: from the offset basis,
/// `h = (h ^ w) * prime (mod 2^64)` for each word `w`, then once more with
/// `w = bytes.len()`. A checksum of long strings, eight times fewer steps than
/// [`fnv1a64`]. Each step is a bijection of `h` for a given word, so two
/// strings of one length that differ in a single word always differ in it.
pub fn fnv1a64_words(bytes: &[u8]) -> u64 {
    let step = |h: u64, w: u64| (h ^ w).wrapping_mul(FNV_PRIME);
    let mut words = bytes.chunks_exact(8);
    let mut h = FNV_OFFSET_BASIS;
    for w in &mut words {
        h = step(h, u64::from_le_bytes(w.try_into().unwrap_or([0; 8])));
    }
    let tail = words.remainder();
    if !tail.is_empty() {
        let mut last = [0u8; 8];
        last[..tail.len()].copy_from_slice(tail);
        h = step(h, u64::from_le_bytes(last));
    }
    step(h, bytes.len() as u64)
}

#[cfg(test)]
mod doc_examples {
    //! The examples of this private module's items (not doctests: the module is
    //! not public).
    use super::*;

    #[test]
    fn fnv1a64_published_vectors() {
        // Published test vectors.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    /// The word step by hand for short strings: the empty string is one step
    /// with its length 0; a string of up to 8 bytes is its zero-padded word,
    /// then its length; zero padding is not confused with a zero byte.
    #[test]
    fn fnv1a64_words_by_hand() {
        let step = |h: u64, w: u64| (h ^ w).wrapping_mul(FNV_PRIME);
        assert_eq!(fnv1a64_words(b""), step(FNV_OFFSET_BASIS, 0));
        let ab = u64::from(b'a') | u64::from(b'b') << 8;
        assert_eq!(fnv1a64_words(b"ab"), step(step(FNV_OFFSET_BASIS, ab), 2));
        let nine = *b"abcdefghi";
        let w0 = u64::from_le_bytes(nine[..8].try_into().unwrap());
        let want = step(step(step(FNV_OFFSET_BASIS, w0), u64::from(b'i')), 9);
        assert_eq!(fnv1a64_words(&nine), want);
        assert_ne!(fnv1a64_words(b"ab"), fnv1a64_words(b"ab\0"));
        // One changed byte anywhere changes the checksum.
        let base: Vec<u8> = (0..100u8).collect();
        for k in 0..base.len() {
            let mut v = base.clone();
            v[k] ^= 0x40;
            assert_ne!(fnv1a64_words(&v), fnv1a64_words(&base), "byte {k}");
        }
    }
}
