//! Face-point weights `c_j`: the face point is `F = sum_j c_j P_j`.
//!
//! Math doc section 3 (seed 000). The paper's closed form is
//!
//! ```text
//! alpha_j = 1/2 ( prod_{k=0}^{n-1} p_{j+k} + prod_{k=0}^{n-1} q_{j-k} )
//!         + sum_{m=1}^{n-1} ( prod_{k=1}^{m} q_{j+k} ) ( prod_{k=m}^{n-1} p_{j+k} ),
//! c_j = alpha_j / sum_k alpha_k.
//! ```
//!
//! Writing `p_i = s_i (p_i + q_{i+1})`, `q_{i+1} = r_i (p_i + q_{i+1})` with
//! `s_i = 1 - r_i`, every product above contains each edge sum `p_i + q_{i+1}`
//! exactly once, so that common factor cancels and **\[derived\]**
//!
//! ```text
//! alpha_j  ∝  sum_{m=0}^{n} w_m T_m(j),   w_0 = w_n = 1/2, w_m = 1 otherwise,
//! T_m(j)   =  prod_{i=j}^{j+m-1} r_i  *  prod_{i=j+m}^{j+n-1} s_i .
//! ```
//!
//! These products over- and underflow `f64` for large `n` or extreme ratios
//! (`(1e-6)^256`), so the `f64` kernel keeps every product as a mantissa and a
//! separate `i64` binary exponent (`ExtFloat`): all terms are positive, so
//! no cancellation occurs and the relative error is `O(n eps)` for any `n` and
//! any ratios. The rational kernel evaluates the same formula exactly.
//!
//! Independent check (math doc fact 3, **\[derived\]**): `c` is the stationary
//! distribution of the cyclic Markov chain `P = R/2`, computed here by the
//! subtraction-free GTH elimination ([`stationary_distribution`]).

use super::EdgeRatios;
use crate::scalar::Scalar;

pub(crate) use crate::scalar::weight_kernels::interval_kernel;

/// Face-point weights `c_0..c_{n-1}` (they sum to 1) by the closed form.
///
/// Exact for rationals; for `f64` accurate to a few ulps times `n` for any
/// valence and any ratios (no overflow or underflow).
///
/// ```
/// use subdiv_lab::knots::{face_weights, EdgeRatios};
/// let c = face_weights(&EdgeRatios::<f64>::uniform(5).unwrap());
/// assert!(c.iter().all(|&x| (x - 0.2).abs() < 1e-15));
/// ```
pub fn face_weights<T: Scalar>(ratios: &EdgeRatios<T>) -> Vec<T> {
    T::face_weights_kernel(ratios.as_slice(), ratios.complement())
}

/// Stationary distribution of the cyclic chain `P = R/2` (math doc fact 3),
/// with `R[i,i-1] = r_{i-1}`, `R[i,i] = 1 - r_{i-1} + r_i`, `R[i,i+1] = 1 - r_i`.
///
/// Computed by Grassmann-Taksar-Heyman elimination, which uses no subtraction
/// and is accurate to a small multiple of `n eps` componentwise; `O(n^3)`.
/// Exact for rationals. It is an independent route to [`face_weights`].
///
/// ```
/// use subdiv_lab::knots::{face_weights, stationary_distribution, EdgeRatios};
/// let r = EdgeRatios::new(vec![0.1, 0.8, 0.3, 0.6, 0.45]).unwrap();
/// let (a, b) = (face_weights(&r), stationary_distribution(&r));
/// assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-14));
/// ```
pub fn stationary_distribution<T: Scalar>(ratios: &EdgeRatios<T>) -> Vec<T> {
    let n = ratios.valence();
    let r = ratios.as_slice();
    let s = ratios.complement();
    let half = T::frac(1, 2);
    // Dense transition matrix (diagonal never used by GTH).
    let mut p = vec![vec![T::zero(); n]; n];
    for i in 0..n {
        let prev = (i + n - 1) % n;
        let next = (i + 1) % n;
        p[i][prev] = p[i][prev].clone() + half.clone() * r[prev].clone();
        p[i][next] = p[i][next].clone() + half.clone() * s[i].clone();
    }
    for k in (1..n).rev() {
        let total = (0..k).fold(T::zero(), |a, j| a + p[k][j].clone());
        for row in p.iter_mut().take(k) {
            row[k] = row[k].clone() / total.clone();
        }
        let (head, tail) = p.split_at_mut(k);
        let row_k = &tail[0][..k];
        for row in head.iter_mut() {
            let pik = row[k].clone();
            if pik.is_zero() {
                continue;
            }
            for (x, y) in row[..k].iter_mut().zip(row_k) {
                *x = x.clone() + pik.clone() * y.clone();
            }
        }
    }
    let mut x = vec![T::zero(); n];
    x[0] = T::one();
    for k in 1..n {
        x[k] = (0..k).fold(T::zero(), |a, i| a + x[i].clone() * p[i][k].clone());
    }
    let sum = x.iter().cloned().fold(T::zero(), |a, b| a + b);
    x.into_iter().map(|v| v / sum.clone()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::CornerIntervals;
    use crate::scalar::weight_kernels::*;
    use crate::scalar::{f64_to_rational, Rational};
    use num_bigint::BigInt;

    /// Intervals whose sums overflow or whose ratios underflow
    /// `f64` (`1e-300` against `1e300`, `9e307 + 9e307`). The weights come from
    /// the extended-exponent ratios and match the exact closed form.
    #[test]
    fn interval_kernel_takes_any_finite_positive_intervals() {
        let cases: [(&[f64], &[f64]); 4] = [
            (&[9e307, 9e307, 9e307, 9e307], &[9e307, 9e307, 9e307, 9e307]),
            (&[1e300, 1e300, 1e300], &[1e-300, 1e300, 1e300]),
            (
                &[f64::MAX, 5e-324, 1.0, 2.0],
                &[5e-324, f64::MAX, 3.0, 1e-310],
            ),
            (&[1e-320, 3e-321, 1e-300], &[7e-322, 1e-320, 2e-310]),
        ];
        for (a, b) in cases {
            let (c, rs) = interval_kernel(a, b);
            let aq: Vec<Rational> = a.iter().map(|&x| f64_to_rational(x).unwrap()).collect();
            let bq: Vec<Rational> = b.iter().map(|&x| f64_to_rational(x).unwrap()).collect();
            let exact = EdgeRatios::<Rational>::from_edge_pairs(&aq, &bq).unwrap();
            let cq = face_weights(&exact);
            // one weight per corner on both sides (a comparison by `zip`
            // alone passes on an empty result)
            assert_eq!((c.len(), cq.len()), (a.len(), a.len()), "{a:?} {b:?}");
            for (j, (x, y)) in c.iter().zip(&cq).enumerate() {
                let y = y.to_f64();
                // a weight below the f64 range rounds to 0 (absolute error < 1e-300)
                assert!(
                    (x - y).abs() <= 1e-14 * y.abs() || (x - y).abs() < 1e-300,
                    "{a:?} {b:?}: c_{j} = {x} vs {y}"
                );
            }
            for (i, (r, s)) in rs.iter().enumerate() {
                let (rq, sq) = (exact.as_slice()[i].to_f64(), exact.complement()[i].to_f64());
                // 2 ulps relative, or 2 subnormal steps where the ratio is subnormal
                let tol = |x: f64| 4.0 * f64::EPSILON * x + 2.0 * f64::from_bits(1);
                assert!((r - rq).abs() <= tol(rq), "r_{i}: {r:e} vs {rq:e}");
                assert!((s - sq).abs() <= tol(sq), "s_{i}: {s:e} vs {sq:e}");
            }
        }
    }

    /// The fraction-free rational kernel equals the reducing one exactly,
    /// for ratios with unrelated denominators and for `f64`-valued ratios
    /// (53-bit mantissas, the case it exists for), at several valences.
    #[test]
    fn fraction_free_kernel_matches_reducing_kernel() {
        let q = |a: i64, b: i64| Rational::new(BigInt::from(a), BigInt::from(b));
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for n in [3, 4, 7, 16] {
            for float in [false, true] {
                let r: Vec<Rational> = (0..n)
                    .map(|_| {
                        if float {
                            let x = (next() % 1_000_000 + 1) as f64 / 1_000_001.0;
                            f64_to_rational(x).unwrap()
                        } else {
                            let den = (next() % 97 + 2) as i64;
                            q((next() % (den as u64 - 1) + 1) as i64, den)
                        }
                    })
                    .collect();
                let s: Vec<Rational> = r
                    .iter()
                    .map(|x| Rational::from_integer(1.into()) - x)
                    .collect();
                let fast = rational_kernel(&r, &s);
                let slow = generic_kernel(&r, &s);
                assert_eq!(fast, slow, "n = {n}, float = {float}");
                let total = fast.iter().fold(q(0, 1), |a, b| a + b);
                assert_eq!(total, q(1, 1));
            }
        }
        // r_i and s_i with different denominators (not complements).
        let r = vec![q(1, 3), q(2, 5), q(3, 7)];
        let s = vec![q(1, 2), q(4, 9), q(1, 11)];
        assert_eq!(rational_kernel(&r, &s), generic_kernel(&r, &s));
    }

    /// Math doc fact 2: tensor-product quad knots.
    #[test]
    fn tensor_quad_fact_2() {
        let (d0, d1, e0, e1) = (1.3, 0.4, 2.2, 0.7);
        let k = CornerIntervals::new(vec![d0, e0, d1, e1], vec![e0, d1, e1, d0]).unwrap();
        let c = face_weights(&k.ratios().unwrap());
        assert_eq!(c.len(), 4, "{c:?}");
        let expected = [0.056795, 0.184584, 0.580122, 0.178499];
        for (a, b) in c.iter().zip(expected) {
            assert!((a - b).abs() < 5e-7, "{c:?}");
        }
        // and exactly the tensor face point weights of math doc section 2
        let den = (d0 + d1) * (e0 + e1);
        let tensor = [e1 * d1 / den, e1 * d0 / den, e0 * d0 / den, e0 * d1 / den];
        for (a, b) in c.iter().zip(tensor) {
            assert!((a - b).abs() < 1e-15, "{c:?} vs {tensor:?}");
        }
    }

    /// Extreme ratios and large n: compare with the exact rational closed form
    /// evaluated on the same (exactly representable) f64 inputs.
    #[test]
    fn extreme_ratios_match_exact() {
        let n = 256;
        let mut p = Vec::new();
        let mut q = Vec::new();
        for i in 0..n {
            // interval ratios up to 1e6, alternating and drifting
            p.push(if i % 2 == 0 {
                1e6
            } else {
                1.0 + (i as f64) / 7.0
            });
            q.push(if i % 3 == 0 { 1.0 } else { 1e3 });
        }
        let k = CornerIntervals::new(p.clone(), q.clone()).unwrap();
        let c = face_weights(&k.ratios().unwrap());
        assert_eq!(c.len(), n);
        assert!(c.iter().all(|x| x.is_finite() && *x > 0.0));
        // Exact reference on all 256 corners, from the exact knots. The
        // rational closed form over ratios takes minutes at n = 256 (every
        // step reduces huge fractions), so the paper's form over intervals is
        // used: T_m(j) times the common factor prod_i (p_i + q_{i+1}) is
        // prod_{i=j}^{j+m-1} q_{i+1} * prod_{i=j+m}^{j+n-1} p_i, and with
        // every (dyadic) interval scaled by 2^60 to an integer this is exact
        // integer arithmetic.
        let kq = CornerIntervals::<Rational>::new(
            p.iter().map(|&x| f64_to_rational(x).unwrap()).collect(),
            q.iter().map(|&x| f64_to_rational(x).unwrap()).collect(),
        )
        .unwrap();
        let two60 = Rational::from_integer(BigInt::from(1u64 << 60));
        let int = |x: &Rational| {
            let y = x * &two60;
            assert!(y.is_integer(), "{x} is not a multiple of 2^-60");
            y.to_integer()
        };
        let a: Vec<BigInt> = kq.p().iter().map(int).collect();
        let b: Vec<BigInt> = (0..n).map(|i| int(&kq.q()[(i + 1) % n])).collect();
        // 2 alpha_j (up to the common factor): w_0 = w_n = 1/2 become 1, the rest 2
        let mut alpha2 = Vec::with_capacity(n);
        let mut suffix = vec![BigInt::from(1); n + 1];
        for j in 0..n {
            for m in (0..n).rev() {
                suffix[m] = &suffix[m + 1] * &a[(j + m) % n];
            }
            let mut prefix = BigInt::from(1);
            let mut total = suffix[0].clone();
            for m in 1..=n {
                prefix *= &b[(j + m - 1) % n];
                let term = &prefix * &suffix[m];
                total += if m == n { term } else { term * 2 };
            }
            alpha2.push(total);
        }
        let sum: BigInt = alpha2.iter().sum();
        for (j, (x, al)) in c.iter().zip(alpha2).enumerate() {
            let y = Rational::new(al, sum.clone()).to_f64();
            assert!(
                y > 0.0 && ((x - y) / y).abs() < 1e-12,
                "c_{j}: {x} vs exact {y}"
            );
        }
        // and the exact rational closed form on a 24-corner face of the same knots
        let m = 24;
        let k_small = CornerIntervals::new(p[..m].to_vec(), q[..m].to_vec()).unwrap();
        let kq_small =
            CornerIntervals::<Rational>::new(kq.p()[..m].to_vec(), kq.q()[..m].to_vec()).unwrap();
        let c64 = face_weights(&k_small.ratios().unwrap());
        let cq = face_weights(&kq_small.ratios().unwrap());
        assert_eq!((c64.len(), cq.len()), (m, m));
        for (x, y) in c64.iter().zip(&cq) {
            let y = y.to_f64();
            assert!(((x - y) / y).abs() < 1e-13, "{x} vs {y}");
        }
        // GTH on the 24-corner face against the exact weights (a valence that
        // is not a power of two: cyclic indices modulo 256 could hide a
        // wrapped subtraction that modulo 24 cannot)
        let g_small = stationary_distribution(&k_small.ratios().unwrap());
        assert_eq!(g_small.len(), m);
        for (x, y) in g_small.iter().zip(&cq) {
            let y = y.to_f64();
            assert!(((x - y) / y).abs() < 1e-12, "GTH {x} vs {y}");
        }
        // the large case against GTH
        let g = stationary_distribution(&k.ratios().unwrap());
        assert_eq!(g.len(), n);
        for (a, b) in c.iter().zip(&g) {
            assert!(((a - b) / b).abs() < 1e-11, "{a} vs {b}");
        }
    }
}
