//! Point generators of the sweep samplers, all random-access (the point with
//! index `i` is computed from `i` alone, so shards and threads need no shared
//! state):
//!
//! * [`hash_uniform`]: counter-based uniform draws, a SplitMix64 finaliser over
//!   `(seed, stream, index, coordinate)`;
//! * [`radical_inverse`] / [`Halton`]: the Halton sequence in the first `d`
//!   prime bases, optionally with a random shift modulo 1 (Cranley-Patterson);
//! * [`Sobol`]: the Sobol sequence in base 2 (Gray-code order) with the Joe-Kuo
//!   direction numbers `new-joe-kuo-6.21201` (first [`SOBOL_MAX_DIMENSION`]
//!   dimensions), optionally with Owen's nested uniform scrambling (math doc
//!   section 16.1).
//!
//! Unscrambled Sobol points are exactly those of
//! `scipy.stats.qmc.Sobol(d, scramble=False)`, the first point (the origin)
//! included (tests against SciPy's points in `tests/data/sobol_scipy.txt`).

use super::sobol_table::JOE_KUO;
pub use super::sobol_table::SOBOL_MAX_DIMENSION;
pub use crate::rng::mix64;

/// 64 well-mixed bits determined by `(seed, stream, index, coordinate)`.
#[inline]
pub fn hash4(seed: u64, stream: u64, index: u64, coordinate: u64) -> u64 {
    const G: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut h = mix64(seed.wrapping_add(G));
    h = mix64(h ^ stream.wrapping_mul(G).wrapping_add(1));
    h = mix64(h ^ index.wrapping_mul(G).wrapping_add(2));
    mix64(h ^ coordinate.wrapping_mul(G).wrapping_add(3))
}

/// A uniform draw in `[0, 1)` (53 random bits) determined by `(seed, stream, index, coordinate)`.
///
/// ```
/// use subdiv_lab::sweep::sampler::hash_uniform;
/// let u = hash_uniform(1, 3, 42, 0);
/// assert!((0.0..1.0).contains(&u));
/// assert_eq!(u, hash_uniform(1, 3, 42, 0));
/// assert_ne!(u, hash_uniform(1, 3, 42, 1));
/// ```
#[inline]
pub fn hash_uniform(seed: u64, stream: u64, index: u64, coordinate: u64) -> f64 {
    (hash4(seed, stream, index, coordinate) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The first `d` primes.
pub fn first_primes(d: usize) -> Vec<u64> {
    let mut p = Vec::with_capacity(d);
    let mut k = 2u64;
    while p.len() < d {
        if p.iter().take_while(|&&q| q * q <= k).all(|&q| k % q != 0) {
            p.push(k);
        }
        k += 1;
    }
    p
}

/// Radical inverse of `i` in base `b >= 2`: the base-`b` digits of `i` mirrored
/// about the radix point (`phi_2(6) = 0.011_2 = 3/8`).
///
/// ```
/// use subdiv_lab::sweep::sampler::radical_inverse;
/// assert_eq!(radical_inverse(6, 2), 0.375);
/// assert!((radical_inverse(5, 3) - 7.0 / 9.0).abs() < 1e-15);
/// ```
///
/// The bases of the first 16 dimensions (2 to 53) are compile-time constants
/// (their digit division is a multiplication, several times faster than a
/// division by a run-time base); the arithmetic, and so every bit of the
/// result, is the same for all bases.
pub fn radical_inverse(i: u64, b: u64) -> f64 {
    match b {
        2 => radical_inverse_in::<2>(i),
        3 => radical_inverse_in::<3>(i),
        5 => radical_inverse_in::<5>(i),
        7 => radical_inverse_in::<7>(i),
        11 => radical_inverse_in::<11>(i),
        13 => radical_inverse_in::<13>(i),
        17 => radical_inverse_in::<17>(i),
        19 => radical_inverse_in::<19>(i),
        23 => radical_inverse_in::<23>(i),
        29 => radical_inverse_in::<29>(i),
        31 => radical_inverse_in::<31>(i),
        37 => radical_inverse_in::<37>(i),
        41 => radical_inverse_in::<41>(i),
        43 => radical_inverse_in::<43>(i),
        47 => radical_inverse_in::<47>(i),
        53 => radical_inverse_in::<53>(i),
        _ => radical_inverse_by(i, b),
    }
}

/// [`radical_inverse`] in a constant base `B`.
#[inline(always)]
fn radical_inverse_in<const B: u64>(i: u64) -> f64 {
    radical_inverse_by(i, B)
}

/// [`radical_inverse`] (the one definition of its arithmetic).
#[inline(always)]
fn radical_inverse_by(mut i: u64, b: u64) -> f64 {
    let inv = 1.0 / b as f64;
    let mut f = inv;
    let mut x = 0.0;
    while i > 0 {
        x += (i % b) as f64 * f;
        i /= b;
        f *= inv;
    }
    x
}

/// The Halton sequence in `d` dimensions (bases = the first `d` primes).
#[derive(Clone, Debug)]
pub struct Halton {
    bases: Vec<u64>,
    shift: Option<Vec<f64>>,
}

impl Halton {
    /// `d` dimensions; `scramble_seed` adds a random shift modulo 1 per
    /// dimension (Cranley-Patterson rotation) derived from the seed and `stream`.
    pub fn new(d: usize, scramble_seed: Option<u64>, stream: u64) -> Self {
        Halton {
            bases: first_primes(d),
            shift: scramble_seed.map(|s| {
                (0..d as u64)
                    .map(|k| hash_uniform(s, stream, u64::MAX, k))
                    .collect()
            }),
        }
    }

    /// Writes point `i` (a coordinate in `[0, 1)` per dimension) into `out`.
    pub fn point(&self, i: u64, out: &mut [f64]) {
        for (k, (o, &b)) in out.iter_mut().zip(&self.bases).enumerate() {
            let x = radical_inverse(i, b);
            *o = match &self.shift {
                Some(s) => {
                    let y = x + s[k];
                    if y >= 1.0 {
                        y - 1.0
                    } else {
                        y
                    }
                }
                None => x,
            };
        }
    }
}

/// Bits of the Sobol direction numbers (points are multiples of `2^-32`).
pub const SOBOL_BITS: usize = 32;

/// Multiplies polynomials over GF(2) modulo `m` (degree `deg`); bit `k` = coefficient of x^k.
fn gf2_mulmod(a: u64, b: u64, m: u64, deg: u32) -> u64 {
    let mut r = 0u64;
    let mut a = a;
    let mut b = b;
    let top = 1u64 << deg;
    while b != 0 {
        if b & 1 == 1 {
            r ^= a;
        }
        b >>= 1;
        a <<= 1;
        if a & top != 0 {
            a ^= m;
        }
    }
    r
}

fn gf2_powmod_x(e: u64, m: u64, deg: u32) -> u64 {
    let mut result = 1u64;
    // x reduced modulo m (modulo x + 1, x = 1).
    let mut base = if deg == 1 { 1 } else { 0b10 };
    let mut e = e;
    while e > 0 {
        if e & 1 == 1 {
            result = gf2_mulmod(result, base, m, deg);
        }
        base = gf2_mulmod(base, base, m, deg);
        e >>= 1;
    }
    result
}

fn prime_factors(mut n: u64) -> Vec<u64> {
    let mut f = Vec::new();
    let mut p = 2;
    while p * p <= n {
        if n % p == 0 {
            f.push(p);
            while n % p == 0 {
                n /= p;
            }
        }
        p += 1;
    }
    if n > 1 {
        f.push(n);
    }
    f
}

/// Whether the GF(2) polynomial `m` (bit k = coefficient of x^k) of degree
/// `deg <= 31` is primitive: `x` has multiplicative order exactly `2^deg - 1`.
pub fn is_primitive(m: u64, deg: u32) -> bool {
    if deg == 0 || m >> deg != 1 || m & 1 == 0 {
        return false;
    }
    let order = (1u64 << deg) - 1;
    if gf2_powmod_x(order, m, deg) != 1 {
        return false;
    }
    prime_factors(order)
        .into_iter()
        .all(|q| q == order || gf2_powmod_x(order / q, m, deg) != 1)
}

/// The first `count` primitive polynomials over GF(2), by degree then value
/// (`x + 1`, `x^2 + x + 1`, `x^3 + x + 1`, `x^3 + x^2 + 1`, ...), as bit masks.
pub fn primitive_polynomials(count: usize) -> Vec<(u32, u64)> {
    let mut out = Vec::with_capacity(count);
    let mut deg = 1u32;
    while out.len() < count && deg < 32 {
        for m in (1u64 << deg)..(1u64 << (deg + 1)) {
            if out.len() == count {
                break;
            }
            if is_primitive(m, deg) {
                out.push((deg, m));
            }
        }
        deg += 1;
    }
    out
}

/// A Sobol dimension beyond the shipped Joe-Kuo table.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the Sobol sampler supports at most {SOBOL_MAX_DIMENSION} dimensions (Joe-Kuo direction numbers shipped), got {dimension}")]
pub struct SobolDimensionError {
    /// The requested dimension.
    pub dimension: usize,
}

/// The Sobol sequence in `d <= SOBOL_MAX_DIMENSION` dimensions, 32-bit
/// (math doc section 16.1).
///
/// Dimension `j` (0-based) uses row `j + 1` of Joe and Kuo's
/// `new-joe-kuo-6.21201` (dimension 0: `m_k = 1`), the recurrence
/// `m_k = 2 a_1 m_(k-1) ^ 4 a_2 m_(k-2) ^ ... ^ 2^s m_(k-s) ^ m_(k-s)` and
/// `v_k = m_k 2^(32 - k)`; point `i` is the XOR of the `v_k` of the set bits of
/// the Gray code `i ^ (i >> 1)`, divided by `2^32`.
///
/// ```
/// use subdiv_lab::sweep::sampler::Sobol;
/// // scipy.stats.qmc.Sobol(3, scramble=False).random(4)
/// let s = Sobol::new(3, None, 0).unwrap();
/// let mut x = [0.0; 3];
/// let pts: Vec<[f64; 3]> = (0..4).map(|i| { s.point(i, &mut x); x }).collect();
/// assert_eq!(pts, [[0.0, 0.0, 0.0], [0.5, 0.5, 0.5], [0.75, 0.25, 0.25], [0.25, 0.75, 0.75]]);
/// assert!(Sobol::new(5000, None, 0).is_err());
/// ```
#[derive(Clone, Debug)]
pub struct Sobol {
    /// `v[dim][k]`: direction number of bit `k` (already shifted to 32 bits).
    v: Vec<[u32; SOBOL_BITS]>,
    /// Per-dimension keys of the nested uniform scrambling (`None`: unscrambled).
    scramble: Option<Vec<u64>>,
}

/// Direction numbers `v_1..v_32` of 0-based Sobol dimension `dim <= SOBOL_MAX_DIMENSION - 1`.
fn direction_numbers(dim: usize) -> [u32; SOBOL_BITS] {
    let mut dir = [0u32; SOBOL_BITS];
    if dim == 0 {
        for (k, x) in dir.iter_mut().enumerate() {
            *x = 1u32 << (SOBOL_BITS - 1 - k);
        }
        return dir;
    }
    let (s, a, init) = JOE_KUO[dim - 1];
    let s = usize::from(s);
    let a = u64::from(a);
    // m[k], k = 1..=32 (index 0 unused).
    let mut m = [0u64; SOBOL_BITS + 1];
    for k in 1..=s.min(SOBOL_BITS) {
        m[k] = u64::from(init[k - 1]);
    }
    for k in (s + 1)..=SOBOL_BITS {
        let mut x = m[k - s] ^ (m[k - s] << s);
        for j in 1..s {
            // a_j: bit (s - 1 - j) of `a` (a_1 is the most significant of the s - 1 bits).
            if (a >> (s - 1 - j)) & 1 == 1 {
                x ^= m[k - j] << j;
            }
        }
        m[k] = x;
    }
    for k in 1..=SOBOL_BITS {
        dir[k - 1] = (m[k] << (SOBOL_BITS - k)) as u32;
    }
    dir
}

impl Sobol {
    /// `d` dimensions; `scramble_seed` applies Owen's nested uniform scrambling
    /// with per-dimension keys derived from the seed and `stream` (math doc
    /// section 16.1). Errors when `d > SOBOL_MAX_DIMENSION`.
    pub fn new(
        d: usize,
        scramble_seed: Option<u64>,
        stream: u64,
    ) -> Result<Self, SobolDimensionError> {
        if d > SOBOL_MAX_DIMENSION {
            return Err(SobolDimensionError { dimension: d });
        }
        Ok(Sobol {
            v: (0..d).map(direction_numbers).collect(),
            scramble: scramble_seed.map(|seed| {
                (0..d as u64)
                    .map(|k| hash4(seed, stream, u64::MAX - 2, k))
                    .collect()
            }),
        })
    }

    /// The unscrambled 32-bit integer `2^32 x` of coordinate `dim` of point `i`.
    #[inline]
    fn integer(&self, i: u64, dim: usize) -> u32 {
        let g = i ^ (i >> 1);
        let mut x = 0u32;
        let mut bits = g;
        let mut k = 0;
        while bits != 0 && k < SOBOL_BITS {
            if bits & 1 == 1 {
                x ^= self.v[dim][k];
            }
            bits >>= 1;
            k += 1;
        }
        x
    }

    /// Writes point `i < 2^32` (Gray-code order) into `out` (one coordinate in
    /// `[0, 1)` per dimension; extra entries of `out` are left alone).
    pub fn point(&self, i: u64, out: &mut [f64]) {
        for (dim, o) in out.iter_mut().enumerate().take(self.v.len()) {
            let x = self.integer(i, dim);
            *o = match &self.scramble {
                None => f64::from(x) * (1.0 / 4_294_967_296.0),
                Some(keys) => {
                    let (y, tail) = owen_scramble(x, keys[dim]);
                    ((u64::from(y) << 21) | tail) as f64 * (1.0 / (1u64 << 53) as f64)
                }
            };
        }
    }
}

/// Nested uniform (Owen) scrambling of the 32 leading binary digits of `x`
/// under `key`, and 21 further random digits (math doc section 16.1).
///
/// Digit `j` (from the top, `j = 0..32`) is flipped by a coin that depends on
/// the key and on the `j` digits above it (the node `2^j + prefix` of the
/// binary tree), so points that share a prefix share its flips: every
/// elementary interval is permuted as a whole, which keeps the net property.
/// The digits below the 32nd are zero in the unscrambled point, so their
/// scrambled values are fair coins determined by the full 32-digit prefix.
#[inline]
fn owen_scramble(x: u32, key: u64) -> (u32, u64) {
    const G: u64 = 0x9e37_79b9_7f4a_7c15;
    let xx = u64::from(x);
    let mut flips = 0u32;
    for j in 0..SOBOL_BITS as u32 {
        let node = (1u64 << j) | (xx >> (SOBOL_BITS as u32 - j));
        let coin = (mix64(key ^ node.wrapping_mul(G)) >> 63) as u32;
        flips |= coin << (SOBOL_BITS as u32 - 1 - j);
    }
    let tail = mix64(key ^ ((1u64 << SOBOL_BITS) | xx).wrapping_mul(G)) >> 43;
    (x ^ flips, tail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primes_and_radical_inverse() {
        assert_eq!(first_primes(8), vec![2, 3, 5, 7, 11, 13, 17, 19]);
        let b2: Vec<f64> = (1..8).map(|i| radical_inverse(i, 2)).collect();
        assert_eq!(b2, vec![0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875]);
        // First b^m points (from 0) of a 1-D van der Corput sequence are {j / b^m}.
        for b in [2u64, 3, 5, 7] {
            let m = b * b * b;
            let mut v: Vec<u64> = (0..m)
                .map(|i| (radical_inverse(i, b) * m as f64).round() as u64)
                .collect();
            v.sort();
            assert_eq!(v, (0..m).collect::<Vec<_>>());
        }
    }

    #[test]
    fn primitive_polynomial_counts() {
        // phi(2^s - 1) / s primitive polynomials of degree s.
        let polys = primitive_polynomials(1 + 1 + 2 + 2 + 6 + 6 + 18 + 16 + 48 + 60);
        let mut count = [0usize; 11];
        for (d, _) in &polys {
            count[*d as usize] += 1;
        }
        assert_eq!(&count[1..], &[1, 1, 2, 2, 6, 6, 18, 16, 48, 60]);
        assert_eq!(polys[0], (1, 0b11));
        assert_eq!(polys[1], (2, 0b111));
        assert_eq!(polys[2], (3, 0b1011));
        assert_eq!(polys[3], (3, 0b1101));
        // x^4 + x^3 + x^2 + x + 1 is irreducible but not primitive (order 5).
        assert!(!is_primitive(0b11111, 4));
        assert!(is_primitive(0b10011, 4));
    }

    /// Whether `pts` (first 2^m points, coordinates `a`, `b`) put exactly one point in
    /// every elementary box of area 2^-m (all shapes 2^-j x 2^-(m-j)).
    fn is_02_net(pts: &[[f64; 2]], m: u32) -> bool {
        (0..=m).all(|j| {
            let (nx, ny) = (1u64 << j, 1u64 << (m - j));
            let mut seen = vec![false; 1 << m];
            pts.iter().all(|p| {
                let cell = (p[0] * nx as f64) as u64 * ny + (p[1] * ny as f64) as u64;
                !std::mem::replace(&mut seen[cell as usize], true)
            })
        })
    }

    #[test]
    fn sobol_nets() {
        let d = 40;
        for seed in [None, Some(7)] {
            let s = Sobol::new(d, seed, 3).unwrap();
            let m = 10u32;
            let pts: Vec<Vec<f64>> = (0..1u64 << m)
                .map(|i| {
                    let mut x = vec![0.0; d];
                    s.point(i, &mut x);
                    x
                })
                .collect();
            // Every 1-D projection: one point per interval of length 2^-m.
            for k in 0..d {
                let mut cells: Vec<u64> = pts
                    .iter()
                    .map(|p| (p[k] * (1u64 << m) as f64) as u64)
                    .collect();
                cells.sort();
                assert_eq!(cells, (0..1u64 << m).collect::<Vec<_>>(), "dim {k}");
            }
            // Dimensions 0 and 1: a (0, m, 2)-net.
            let two: Vec<[f64; 2]> = pts.iter().map(|p| [p[0], p[1]]).collect();
            assert!(is_02_net(&two, m));
            // Shifts of a non-net would fail: check the checker on a bad set.
            let bad: Vec<[f64; 2]> = pts.iter().map(|p| [p[0], p[0]]).collect();
            assert!(!is_02_net(&bad, m));
        }
        // Unscrambled dimension 0 in Gray order: 0, 1/2, 3/4, 1/4, ...
        let s = Sobol::new(1, None, 0).unwrap();
        let xs: Vec<f64> = (0..4)
            .map(|i| {
                let mut x = [0.0];
                s.point(i, &mut x);
                x[0]
            })
            .collect();
        assert_eq!(xs, vec![0.0, 0.5, 0.75, 0.25]);
    }

    /// The shipped table is Joe-Kuo's: its first published lines
    /// (`d s a m_i`: `2 1 0 1`, `3 2 1 1 3`, `4 3 1 1 3 1`, `5 3 2 1 1 1`,
    /// `6 4 1 1 1 3 3`, `7 4 4 1 3 5 13`, `8 5 2 1 1 5 5 17`), every polynomial
    /// primitive, distinct, and by non-decreasing degree, every `m_k` odd and `< 2^k`.
    #[test]
    fn joe_kuo_table() {
        let first: [(u8, u16, &[u16]); 7] = [
            (1, 0, &[1]),
            (2, 1, &[1, 3]),
            (3, 1, &[1, 3, 1]),
            (3, 2, &[1, 1, 1]),
            (4, 1, &[1, 1, 3, 3]),
            (4, 4, &[1, 3, 5, 13]),
            (5, 2, &[1, 1, 5, 5, 17]),
        ];
        for (row, (s, a, m)) in JOE_KUO.iter().zip(first) {
            assert_eq!((row.0, row.1, &row.2[..m.len()]), (s, a, m));
        }
        let mut seen = std::collections::HashSet::new();
        let mut last_degree = 0;
        for (d, &(s, a, m)) in JOE_KUO.iter().enumerate() {
            let s32 = u32::from(s);
            let poly = (1u64 << s32) | (u64::from(a) << 1) | 1;
            assert!(is_primitive(poly, s32), "dimension {}", d + 2);
            assert!(seen.insert(poly));
            assert!(s >= last_degree);
            last_degree = s;
            for (k, &mk) in m.iter().enumerate() {
                if k < usize::from(s) {
                    assert!(
                        mk % 2 == 1 && u32::from(mk) < 1 << (k + 1),
                        "dimension {}",
                        d + 2
                    );
                } else {
                    assert_eq!(mk, 0);
                }
            }
        }
        assert_eq!(JOE_KUO.len() + 1, SOBOL_MAX_DIMENSION);
    }

    /// Unscrambled points equal SciPy's `qmc.Sobol(d, scramble=False)` exactly
    /// (fixture generated by `python/scripts/gen_sobol_fixture.py`).
    #[test]
    fn unscrambled_points_equal_scipy() {
        let text = include_str!("../../tests/data/sobol_scipy.txt");
        let mut lines = 0;
        let mut dims = std::collections::BTreeSet::new();
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let f: Vec<&str> = line.split(' ').collect();
            let d: usize = f[0].parse().unwrap();
            let i: u64 = f[1].parse().unwrap();
            let cols: Vec<usize> = f[2].split(',').map(|c| c.parse().unwrap()).collect();
            let s = Sobol::new(d, None, 0).unwrap();
            let mut x = vec![0.0; d];
            s.point(i, &mut x);
            for (c, k) in cols.iter().zip(&f[3..]) {
                let k: u64 = k.parse().unwrap();
                assert_eq!(
                    x[*c],
                    k as f64 / (1u64 << 30) as f64,
                    "d {d} point {i} coordinate {c}"
                );
            }
            lines += 1;
            dims.insert(d);
        }
        assert!(lines >= 100 && dims.len() >= 8, "{lines} {dims:?}");
    }

    /// Owen scrambling: a bijection of each elementary interval (points with a
    /// common `j`-digit prefix keep a common scrambled prefix, distinct
    /// prefixes stay distinct), not a digital shift (the flip of a digit
    /// depends on the digits above it), seeded, and uniform on average.
    #[test]
    fn owen_scrambling_is_nested_not_a_shift() {
        let key = hash4(11, 5, 0, 0);
        let xs: Vec<u32> = (0..4096u32).map(|i| i.wrapping_mul(0x9e37_79b9)).collect();
        let ys: Vec<u32> = xs.iter().map(|&x| owen_scramble(x, key).0).collect();
        for j in 1..=12u32 {
            let mut map = std::collections::HashMap::new();
            let mut back = std::collections::HashMap::new();
            for (&x, &y) in xs.iter().zip(&ys) {
                assert_eq!(
                    *map.entry(x >> (32 - j)).or_insert(y >> (32 - j)),
                    y >> (32 - j)
                );
                assert_eq!(
                    *back.entry(y >> (32 - j)).or_insert(x >> (32 - j)),
                    x >> (32 - j)
                );
            }
        }
        // A digital shift flips digit 11 the same way for every point; Owen's
        // flip depends on the 10 digits above it (1024 independent coins).
        let flip11: std::collections::HashSet<u32> = xs
            .iter()
            .zip(&ys)
            .map(|(x, y)| ((x ^ y) >> 21) & 1)
            .collect();
        assert_eq!(flip11.len(), 2);
        assert_ne!(owen_scramble(12345, key), owen_scramble(12345, key ^ 1));
        let s = Sobol::new(4, Some(3), 7).unwrap();
        let n = 1u64 << 14;
        let mut mean = [0.0; 4];
        let mut x = [0.0; 4];
        for i in 0..n {
            s.point(i, &mut x);
            for (m, v) in mean.iter_mut().zip(x) {
                assert!((0.0..1.0).contains(&v));
                *m += v / n as f64;
            }
        }
        // A scrambled (0, m, 1)-net of 2^14 points: every mean within 2^-14 of 1/2.
        assert!(
            mean.iter().all(|m| (m - 0.5).abs() < 1.0 / n as f64),
            "{mean:?}"
        );
        assert_eq!(
            Sobol::new(SOBOL_MAX_DIMENSION + 1, None, 0).unwrap_err(),
            SobolDimensionError {
                dimension: SOBOL_MAX_DIMENSION + 1
            }
        );
    }

    #[test]
    fn halton_stratifies_and_shift_is_seeded() {
        let h = Halton::new(3, None, 0);
        let mut x = [0.0; 3];
        h.point(1, &mut x);
        assert_eq!(x, [0.5, 1.0 / 3.0, 0.2]);
        let a = Halton::new(3, Some(1), 5);
        let b = Halton::new(3, Some(1), 5);
        let c = Halton::new(3, Some(2), 5);
        let (mut xa, mut xb, mut xc) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        a.point(17, &mut xa);
        b.point(17, &mut xb);
        c.point(17, &mut xc);
        assert_eq!(xa, xb);
        assert_ne!(xa, xc);
        assert!(xa.iter().all(|v| (0.0..1.0).contains(v)));
    }

    /// The constant-base paths give the bits of the run-time-base one (and
    /// that one the exact digit mirror where it is exact).
    #[test]
    fn radical_inverse_constant_bases_match() {
        for &b in &first_primes(20) {
            for i in (0..5000u64).chain((0..2000).map(|k| mix64(k) >> (k % 64))) {
                assert_eq!(
                    radical_inverse(i, b).to_bits(),
                    radical_inverse_by(std::hint::black_box(i), std::hint::black_box(b)).to_bits(),
                    "i {i} base {b}"
                );
            }
        }
        assert_eq!(radical_inverse(6, 2), 0.375);
        assert_eq!(radical_inverse(1 << 40, 2), 2f64.powi(-41));
    }

    #[test]
    fn hash_uniform_moments() {
        let n = 200_000u64;
        let (mut s1, mut s2) = (0.0, 0.0);
        for i in 0..n {
            let u = hash_uniform(9, 4, i, 2);
            assert!((0.0..1.0).contains(&u));
            s1 += u;
            s2 += u * u;
        }
        let mean = s1 / n as f64;
        let var = s2 / n as f64 - mean * mean;
        // Standard errors: 0.29/sqrt(n) = 6.5e-4 for the mean; 5 sigma bounds.
        assert!((mean - 0.5).abs() < 3.3e-3, "{mean}");
        assert!((var - 1.0 / 12.0).abs() < 2e-3, "{var}");
    }
}
