//! The crate's non-cryptographic hash: 64-bit FNV-1a (Fowler, Noll and
//! Vo), for per-item seeds ([`crate::rng::derive_seed`]) and spec digests
//! ([`crate::sweep::spec`]). Their values are recorded (seeds in report
//! manifests, digests in sweep summaries), so they must never change.

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
}
