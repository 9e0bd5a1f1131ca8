//! Corner knot intervals and edge ratios, validated (math doc section 3).

use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// Smallest valence of a face or vertex.
pub const MIN_VALENCE: usize = 3;

fn check_valence(n: usize) -> Result<()> {
    if n < MIN_VALENCE {
        Err(Error::ValenceTooSmall { valence: n })
    } else {
        Ok(())
    }
}

fn check_interval<T: Scalar>(name: &'static str, index: usize, v: &T) -> Result<()> {
    if v.is_finite_value() && *v > T::zero() {
        Ok(())
    } else {
        Err(Error::InvalidInterval {
            name,
            index,
            value: v.to_text(),
        })
    }
}

/// Checks two interval vectors of one face: `first` of length `n >= 3`,
/// `second` of the same length (`what` names it in the count error), every
/// value finite and `> 0` (named `first_name[i]`, `second_name[i]`).
fn check_interval_pair<T: Scalar>(
    (first_name, first): (&'static str, &[T]),
    (second_name, second): (&'static str, &[T]),
    what: &'static str,
) -> Result<()> {
    check_valence(first.len())?;
    if second.len() != first.len() {
        return Err(Error::CountMismatch {
            what,
            expected: first.len(),
            got: second.len(),
        });
    }
    for (i, v) in first.iter().enumerate() {
        check_interval(first_name, i, v)?;
    }
    for (i, v) in second.iter().enumerate() {
        check_interval(second_name, i, v)?;
    }
    Ok(())
}

/// The knot intervals `(p_i, q_i)` at the corners of one n-sided face.
///
/// ```
/// use subdiv_lab::knots::CornerIntervals;
/// let k = CornerIntervals::new(vec![1.0, 2.0, 1.0], vec![1.0, 1.0, 3.0]).unwrap();
/// let r = k.ratios().unwrap();
/// // r_0 = q_1 / (p_0 + q_1) = 1 / 2
/// assert_eq!(r.as_slice()[0], 0.5);
/// assert!(CornerIntervals::new(vec![1.0, -2.0, 1.0], vec![1.0; 3]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CornerIntervals<T = f64> {
    p: Vec<T>,
    q: Vec<T>,
}

impl<T: Scalar> CornerIntervals<T> {
    /// Validates `p` and `q`: equal length `n >= 3`, every value finite and `> 0`.
    pub fn new(p: Vec<T>, q: Vec<T>) -> Result<Self> {
        check_interval_pair(("p", &p), ("q", &q), "q intervals (one per corner)")?;
        Ok(Self { p, q })
    }

    /// All intervals equal to 1.
    pub fn uniform(n: usize) -> Result<Self> {
        check_valence(n)?;
        Ok(Self {
            p: vec![T::one(); n],
            q: vec![T::one(); n],
        })
    }

    /// The valence `n` of the face.
    pub fn valence(&self) -> usize {
        self.p.len()
    }

    /// `p_i = d(P_i -> P_{i+1})`.
    pub fn p(&self) -> &[T] {
        &self.p
    }

    /// `q_i = d(P_i -> P_{i-1})`.
    pub fn q(&self) -> &[T] {
        &self.q
    }

    /// Multiplies every interval by `s > 0` (ratios are invariant).
    pub fn scaled(&self, s: &T) -> Result<Self> {
        Self::new(
            self.p.iter().map(|x| x.clone() * s.clone()).collect(),
            self.q.iter().map(|x| x.clone() * s.clone()).collect(),
        )
    }

    /// Edge ratios `r_i = q_{i+1} / (p_i + q_{i+1})`.
    ///
    /// Any finite positive intervals are accepted (`a + b` may overflow `f64`:
    /// the ratios are computed with unbounded exponents). Fails only if a
    /// ratio itself lies beyond the `f64` range (an interval quotient beyond
    /// about `1e308`, e.g. `1e-300` against `1e300`):
    /// [`Error::RatioNotRepresentable`] names the edge.
    ///
    /// ```
    /// use subdiv_lab::knots::CornerIntervals;
    /// let k = CornerIntervals::new(vec![9e307; 3], vec![9e307; 3]).unwrap();
    /// assert_eq!(k.ratios().unwrap().as_slice(), &[0.5, 0.5, 0.5]);
    /// let k = CornerIntervals::new(vec![1e300; 3], vec![1.0, 1e-300, 1.0]).unwrap();
    /// let e = k.ratios().unwrap_err().to_string();
    /// assert!(e.contains("r_0") && e.contains("1e-300"), "{e}");
    /// ```
    pub fn ratios(&self) -> Result<EdgeRatios<T>> {
        let n = self.valence();
        let q_next: Vec<T> = (0..n).map(|i| self.q[(i + 1) % n].clone()).collect();
        EdgeRatios::from_edge_pairs(&self.p, &q_next)
    }

    /// Rotates the corner labels: corner `i` of the result is corner `i + k` of `self`.
    pub fn rotated(&self, k: usize) -> Self {
        let n = self.valence();
        let rot = |v: &[T]| (0..n).map(|i| v[(i + k) % n].clone()).collect();
        Self {
            p: rot(&self.p),
            q: rot(&self.q),
        }
    }
}

/// Edge ratios `r_i in (0, 1)` of an n-sided face (`n >= 3`).
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// let r = EdgeRatios::new(vec![0.5, 0.25, 0.75]).unwrap();
/// assert_eq!(r.valence(), 3);
/// assert!(EdgeRatios::new(vec![0.5, 1.0, 0.5]).is_err()); // r_1 = 1 is not inside (0, 1)
/// assert!(EdgeRatios::new(vec![0.5, 0.5]).is_err());      // valence 2
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeRatios<T = f64> {
    /// `r_i`.
    r: Vec<T>,
    /// `s_i = 1 - r_i`, kept separately so that a ratio computed from intervals
    /// (`s_i = p_i / (p_i + q_{i+1})`) keeps full relative accuracy near `r_i = 1`.
    s: Vec<T>,
}

impl<T: Scalar> EdgeRatios<T> {
    /// Validates `n >= 3` and `0 < r_i < 1` (finite).
    pub fn new(r: Vec<T>) -> Result<Self> {
        Self::check(&r)?;
        let s = r.iter().map(|x| T::one() - x.clone()).collect();
        Ok(Self { r, s })
    }

    /// [`new`](Self::new) from `values`, reusing this value's storage (a
    /// sweep builds one scheme per configuration; this saves the two
    /// allocations). The same validation and the same result as
    /// `EdgeRatios::new(values.to_vec())`; on an error the old ratios are
    /// dropped.
    pub fn refilled(mut self, values: &[T]) -> Result<Self> {
        Self::check(values)?;
        self.r.clear();
        self.r.extend_from_slice(values);
        self.s.clear();
        self.s.extend(values.iter().map(|x| T::one() - x.clone()));
        Ok(self)
    }

    /// The validation of [`new`](Self::new): `n >= 3` values, each finite and
    /// inside `(0, 1)`; the first bad value is named.
    fn check(values: &[T]) -> Result<()> {
        check_valence(values.len())?;
        for (i, v) in values.iter().enumerate() {
            if !(v.is_finite_value() && *v > T::zero() && *v < T::one()) {
                return Err(Error::InvalidRatio {
                    index: i,
                    value: v.to_text(),
                });
            }
        }
        Ok(())
    }

    /// Ratios from the two intervals of each edge: `r_i = b_i / (a_i + b_i)`,
    /// `s_i = a_i / (a_i + b_i)`; both computed directly ([`Scalar::edge_ratio`]:
    /// exact for rationals, with unbounded exponents for `f64`), so each keeps
    /// full relative accuracy even when `a_i / b_i` is extreme and `a_i + b_i`
    /// overflows. A ratio below the `f64` range is an error naming the edge.
    pub(crate) fn from_edge_pairs(a: &[T], b: &[T]) -> Result<Self> {
        let mut r = Vec::with_capacity(a.len());
        let mut s = Vec::with_capacity(a.len());
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            let (ri, si) = T::edge_ratio(x, y);
            if !(ri > T::zero() && si > T::zero()) {
                // Both intervals are finite and positive (validated by the
                // callers), so the ratio is inside (0, 1): it only rounded.
                return Err(Error::RatioNotRepresentable {
                    index: i,
                    value: format!("{} / ({} + {})", y.to_text(), x.to_text(), y.to_text()),
                    rounded: if ri > T::zero() { "1" } else { "0" },
                });
            }
            r.push(ri);
            s.push(si);
        }
        Ok(Self { r, s })
    }

    /// All ratios 1/2 (uniform knots).
    pub fn uniform(n: usize) -> Result<Self> {
        check_valence(n)?;
        Ok(Self {
            r: vec![T::frac(1, 2); n],
            s: vec![T::frac(1, 2); n],
        })
    }

    /// The valence `n`.
    pub fn valence(&self) -> usize {
        self.r.len()
    }

    /// The complements `s_i = 1 - r_i`.
    pub fn complement(&self) -> &[T] {
        &self.s
    }

    /// The ratios `r_0..r_{n-1}`.
    pub fn as_slice(&self) -> &[T] {
        &self.r
    }

    /// `r_i` with the index taken modulo `n`.
    pub fn get(&self, i: isize) -> &T {
        let n = self.r.len() as isize;
        &self.r[i.rem_euclid(n) as usize]
    }

    /// Whether every ratio equals 1/2.
    pub fn is_uniform(&self) -> bool {
        let half = T::frac(1, 2);
        self.r.iter().all(|x| *x == half)
    }

    /// Canonical corner intervals with these ratios: `p_i = 1 - r_i`, `q_i = r_{i-1}`
    /// (so `p_i + q_{i+1} = 1` on every edge).
    pub fn to_corner_intervals(&self) -> CornerIntervals<T> {
        let n = self.valence();
        CornerIntervals {
            p: self.s.clone(),
            q: (0..n).map(|i| self.r[(i + n - 1) % n].clone()).collect(),
        }
    }

    /// Face EP preset: an initial n-gon with directed-edge intervals
    /// `forward_i = d(P_i -> P_{i+1})`, `backward_i = d(P_{i+1} -> P_i)`:
    /// `r_i = backward_i / (forward_i + backward_i)` (math doc section 3).
    pub fn face_ep(forward: &[T], backward: &[T]) -> Result<Self> {
        check_interval_pair(
            ("forward", forward),
            ("backward", backward),
            "backward edge intervals",
        )?;
        Self::from_edge_pairs(forward, backward)
    }

    /// Vertex EP preset **\[derived\]** (math doc section 3): a valence-n vertex `v`
    /// with faces `f_0..f_{n-1}` numbered counter-clockwise, `w_k = next_{f_k}(v)`
    /// and `a_k = d(v -> w_k)`. Corner `k` of its V-face lies in `f_k` and
    /// `r_k = a_{k+2} / (a_k + a_{k+2})`.
    pub fn vertex_ep(a: &[T]) -> Result<Self> {
        let n = a.len();
        check_valence(n)?;
        for (i, v) in a.iter().enumerate() {
            check_interval("a", i, v)?;
        }
        let a2: Vec<T> = (0..n).map(|k| a[(k + 2) % n].clone()).collect();
        Self::from_edge_pairs(a, &a2)
    }

    /// Rotates the labels: ratio `i` of the result is ratio `i + k` of `self`.
    pub fn rotated(&self, k: usize) -> Self {
        let n = self.valence();
        let rot = |v: &[T]| (0..n).map(|i| v[(i + k) % n].clone()).collect();
        Self {
            r: rot(&self.r),
            s: rot(&self.s),
        }
    }

    /// The ratios converted to `f64`.
    pub fn to_f64(&self) -> EdgeRatios<f64> {
        EdgeRatios {
            r: self.r.iter().map(Scalar::to_f64).collect(),
            s: self.s.iter().map(Scalar::to_f64).collect(),
        }
    }
}

impl EdgeRatios<crate::scalar::Rational> {
    /// The nearest `f64` ratios (each `r_i` and `s_i` rounded once), or
    /// [`Error::RatioNotRepresentable`] naming the first edge whose `r_i` or
    /// `s_i` lies below the `f64` range (so that it would round to 0 or 1).
    ///
    /// ```
    /// use subdiv_lab::knots::CornerIntervals;
    /// use subdiv_lab::scalar::parse_exact;
    /// let big = parse_exact("1e400/3").unwrap();
    /// let one = parse_exact("1").unwrap();
    /// // equal huge intervals: ratios 1/2, computed exactly
    /// let k = CornerIntervals::new(vec![big.clone(); 3], vec![big.clone(); 3]).unwrap();
    /// assert_eq!(k.ratios().unwrap().to_f64_checked().unwrap().as_slice(), &[0.5; 3]);
    /// // r_0 = 1 / (1e400/3 + 1) is below the f64 range
    /// let k = CornerIntervals::new(vec![big, one.clone(), one.clone()], vec![one; 3]).unwrap();
    /// let e = k.ratios().unwrap().to_f64_checked().unwrap_err().to_string();
    /// assert!(e.contains("r_0") && e.contains("e-400"), "{e}");
    /// ```
    pub fn to_f64_checked(&self) -> Result<EdgeRatios<f64>> {
        let out = self.to_f64();
        for (i, (r, s)) in out.r.iter().zip(&out.s).enumerate() {
            if !(*r > 0.0 && *s > 0.0) {
                return Err(Error::RatioNotRepresentable {
                    index: i,
                    value: crate::scalar::short_text(&self.r[i]),
                    rounded: if *r > 0.0 { "1" } else { "0" },
                });
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;

    #[test]
    fn canonical_corner_form_round_trips() {
        let r = EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9]).unwrap();
        let back = r.to_corner_intervals().ratios().unwrap();
        for (a, b) in r.as_slice().iter().zip(back.as_slice()) {
            assert!((a - b).abs() < 1e-15);
        }
        let rq = EdgeRatios::<Rational>::new(vec![
            Rational::frac(1, 3),
            Rational::frac(2, 7),
            Rational::frac(5, 6),
        ])
        .unwrap();
        assert_eq!(rq.to_corner_intervals().ratios().unwrap(), rq);
    }

    #[test]
    fn errors_name_the_value() {
        let e = CornerIntervals::new(vec![1.0, 1.0, 1.0], vec![1.0, f64::NAN, 1.0]).unwrap_err();
        assert_eq!(
            e,
            Error::InvalidInterval {
                name: "q",
                index: 1,
                value: "NaN".into()
            }
        );
        let e = EdgeRatios::new(vec![0.5, 0.5, 0.0, 0.5]).unwrap_err();
        assert!(e.to_string().contains("r_2") && e.to_string().contains('0'));
        assert_eq!(
            EdgeRatios::<f64>::uniform(2).unwrap_err(),
            Error::ValenceTooSmall { valence: 2 }
        );
        let e = EdgeRatios::vertex_ep(&[1.0, 0.0, 2.0]).unwrap_err();
        assert!(e.to_string().contains("a_1"));
        let e = EdgeRatios::face_ep(&[1.0, 1.0, 1.0], &[1.0, 1.0]).unwrap_err();
        assert!(matches!(
            e,
            Error::CountMismatch {
                expected: 3,
                got: 2,
                ..
            }
        ));
    }

    #[test]
    fn presets() {
        let r = EdgeRatios::face_ep(&[1.0, 3.0, 1.0], &[1.0, 1.0, 4.0]).unwrap();
        assert_eq!(r.as_slice(), &[0.5, 0.25, 0.8]);
        let r = EdgeRatios::vertex_ep(&[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!(r.as_slice(), &[0.75, 4.0 / 6.0, 0.25, 2.0 / 6.0]);
        // valence 5 against the definition r_k = a_{k+2} / (a_k + a_{k+2}) (at
        // valence 4, corners k + 2 and k - 2 coincide)
        let a = [1.0, 2.0, 4.0, 8.0, 16.0];
        let r = EdgeRatios::vertex_ep(&a).unwrap();
        assert_eq!(r.valence(), 5);
        for (k, &rk) in r.as_slice().iter().enumerate() {
            let b = a[(k + 2) % 5];
            let want = b / (a[k] + b);
            assert!(
                (rk - want).abs() <= 1e-15 * want,
                "r_{k} = {rk}, want {want}"
            );
        }
    }

    /// A ratio that rounds to 1 in `f64` (its complement `s_0 = p_0 / (p_0 +
    /// q_1)` is about `1e-600`) is refused naming the edge and "rounds to 1";
    /// one that rounds to 0 names "rounds to 0" (the other side, also in
    /// tests/analysis/knots.rs). Both reach `from_edge_pairs` through `ratios` and
    /// through the face-EP preset.
    #[test]
    fn ratios_that_round_to_zero_or_one_name_the_edge() {
        let k = CornerIntervals::new(vec![1.0, 1e-300, 1.0], vec![1.0, 1.0, 1e300]).unwrap();
        let e = k.ratios().unwrap_err();
        assert!(
            matches!(&e, Error::RatioNotRepresentable { index: 1, rounded: "1", value } if value.contains("1e300")),
            "{e:?}"
        );
        let e = EdgeRatios::face_ep(&[1.0, 1.0, 1e-300], &[1.0, 1.0, 1e300]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::RatioNotRepresentable {
                    index: 2,
                    rounded: "1",
                    ..
                }
            ),
            "{e:?}"
        );
        let e = EdgeRatios::face_ep(&[1.0, 1e300, 1.0], &[1.0, 1e-300, 1.0]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::RatioNotRepresentable {
                    index: 1,
                    rounded: "0",
                    ..
                }
            ),
            "{e:?}"
        );
    }

    /// Exact ratios outside the `f64` range: `r_1 = 1 / (1e400/3 + 1)` rounds
    /// to 0 and `r_2 = (1e400/3) / (1 + 1e400/3)` rounds to 1 (its complement
    /// to 0); `to_f64_checked` names the first such edge and which way it
    /// rounds, and passes representable ratios through unchanged.
    #[test]
    fn exact_ratios_beyond_f64_are_refused_by_to_f64_checked() {
        let big = crate::scalar::parse_exact("1e400/3").unwrap();
        let one = Rational::frac(1, 1);
        // edge 1: p_1 = big, q_2 = 1 -> r_1 ~ 3e-400
        let k = CornerIntervals::new(
            vec![one.clone(), big.clone(), one.clone()],
            vec![one.clone(); 3],
        )
        .unwrap();
        let e = k.ratios().unwrap().to_f64_checked().unwrap_err();
        assert!(
            matches!(&e, Error::RatioNotRepresentable { index: 1, rounded: "0", value } if value.contains("e-400")),
            "{e:?}"
        );
        // edge 2: p_2 = 1, q_0 = big -> s_2 ~ 3e-400, r_2 rounds to 1
        let k = CornerIntervals::new(vec![one.clone(); 3], vec![big, one.clone(), one.clone()])
            .unwrap();
        let e = k.ratios().unwrap().to_f64_checked().unwrap_err();
        assert!(
            matches!(
                e,
                Error::RatioNotRepresentable {
                    index: 2,
                    rounded: "1",
                    ..
                }
            ),
            "{e:?}"
        );
        let rq = EdgeRatios::<Rational>::new(vec![
            Rational::frac(1, 3),
            Rational::frac(1, 4),
            Rational::frac(3, 4),
        ])
        .unwrap();
        let rf = rq.to_f64_checked().unwrap();
        assert_eq!(rf, rq.to_f64());
        assert_eq!(rf.as_slice(), &[1.0 / 3.0, 0.25, 0.75]);
        assert_eq!(rf.complement(), &[2.0 / 3.0, 0.75, 0.25]);
    }

    /// `rotated` and `get` against the definitions, and rotating the ratios
    /// equals taking the ratios of the rotated corner intervals.
    #[test]
    fn rotation_and_cyclic_indexing() {
        let r = EdgeRatios::new(vec![0.125, 0.25, 0.375, 0.5, 0.625]).unwrap();
        let rot = r.rotated(2);
        assert_eq!(rot.as_slice(), &[0.375, 0.5, 0.625, 0.125, 0.25]);
        assert_eq!(rot.complement(), &[0.625, 0.5, 0.375, 0.875, 0.75]);
        assert_eq!(r.rotated(0), r);
        assert_eq!(r.rotated(5), r);
        for (i, want) in [
            (-6, 0.625),
            (-1, 0.625),
            (0, 0.125),
            (2, 0.375),
            (4, 0.625),
            (7, 0.375),
        ] {
            assert_eq!(*r.get(i), want, "r.get({i})");
        }
        let k = CornerIntervals::new(vec![1.0, 2.0, 0.5, 3.0, 1.5], vec![0.7, 1.1, 2.0, 0.3, 1.0])
            .unwrap();
        for s in 0..5 {
            assert_eq!(
                k.rotated(s).ratios().unwrap(),
                k.ratios().unwrap().rotated(s)
            );
        }
    }

    #[test]
    fn only_all_halves_are_uniform() {
        assert!(EdgeRatios::<f64>::uniform(4).unwrap().is_uniform());
        assert!(EdgeRatios::new(vec![0.5; 3]).unwrap().is_uniform());
        assert!(!EdgeRatios::new(vec![0.5, 0.5, 0.25]).unwrap().is_uniform());
        let q = EdgeRatios::<Rational>::new(vec![
            Rational::frac(1, 2),
            Rational::frac(1, 3),
            Rational::frac(1, 2),
        ])
        .unwrap();
        assert!(!q.is_uniform());
        assert!(EdgeRatios::<Rational>::uniform(3).unwrap().is_uniform());
    }

    /// `scaled` multiplies every interval by `s` (checked on the intervals
    /// themselves, not only through the invariant ratios); `refilled` equals
    /// `new` on the same values, complements `1 - r_i` included, whatever the
    /// old valence, and refuses what `new` refuses (directly here; the sweep's
    /// reuse path checks it through `Plan::scheme_reusing`).
    #[test]
    fn scaling_multiplies_every_interval_and_refilling_equals_new() {
        let k = CornerIntervals::new(vec![1.0, 2.0, 0.5], vec![3.0, 0.25, 1.5]).unwrap();
        let s = k.scaled(&4.0).unwrap();
        assert_eq!(s.p(), &[4.0, 8.0, 2.0]);
        assert_eq!(s.q(), &[12.0, 1.0, 6.0]);
        assert_eq!(s.ratios().unwrap(), k.ratios().unwrap());
        let old = EdgeRatios::new(vec![0.5; 4]).unwrap();
        let values = [0.125, 0.75, 0.375];
        let r = old.clone().refilled(&values).unwrap();
        assert_eq!(r, EdgeRatios::new(values.to_vec()).unwrap());
        assert_eq!(r.complement(), &[0.875, 0.25, 0.625]);
        assert_eq!(
            old.refilled(&[0.5, 1.0, 0.5]).unwrap_err(),
            EdgeRatios::new(vec![0.5, 1.0, 0.5]).unwrap_err()
        );
    }
}
