//! Local subdivision matrices of the Doo-Sabin family (math doc section 4).

use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use subdiv_lab::knots::{CornerIntervals, EdgeRatios};
use subdiv_lab::scalar::{Rational, Scalar};
use subdiv_lab::schemes::doo_sabin::Layout;
use subdiv_lab::schemes::{LocalScheme, SchemeKind};

fn rational_knots(
    n: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = CornerIntervals<Rational>> {
    n.prop_flat_map(|n| {
        (
            prop::collection::vec((1i64..40, 1i64..40), n),
            prop::collection::vec((1i64..40, 1i64..40), n),
        )
            .prop_map(|(p, q)| {
                CornerIntervals::new(
                    p.into_iter().map(|(a, b)| Rational::frac(a, b)).collect(),
                    q.into_iter().map(|(a, b)| Rational::frac(a, b)).collect(),
                )
                .unwrap()
            })
    })
}

fn f64_ratios(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = EdgeRatios> {
    n.prop_flat_map(|n| prop::collection::vec(0.01f64..0.99, n))
        .prop_map(|r| EdgeRatios::new(r).unwrap())
}

/// An independent implementation of math doc section 4, written entry by entry
/// from the printed P', E', C' rows, with the face weights from a dense LU solve
/// of the stationary equations (not the closed form, not GTH).
fn independent_s_n(r: &[f64]) -> DMatrix<f64> {
    let n = r.len();
    let idx = |i: isize| i.rem_euclid(n as isize) as usize;
    // c^T (R/2 - I) = 0 with sum c = 1, as a square system (last equation replaced).
    let mut m = DMatrix::zeros(n, n);
    for i in 0..n as isize {
        let (iu, prev, next) = (idx(i), idx(i - 1), idx(i + 1));
        // R[i, i-1] = r_{i-1}, R[i,i] = 1 - r_{i-1} + r_i, R[i,i+1] = 1 - r_i; transpose into m
        m[(prev, iu)] += r[prev] / 2.0;
        m[(iu, iu)] += (1.0 - r[prev] + r[iu]) / 2.0 - 1.0;
        m[(next, iu)] += (1.0 - r[iu]) / 2.0;
    }
    for j in 0..n {
        m[(n - 1, j)] = 1.0;
    }
    let mut rhs = DVector::zeros(n);
    rhs[n - 1] = 1.0;
    let c = m.lu().solve(&rhs).unwrap();
    let mut s = DMatrix::zeros(4 * n, 4 * n);
    let (e1, e2, cc) = (
        |i: usize| n + 2 * i,
        |i: usize| n + 2 * i + 1,
        |i: usize| 3 * n + i,
    );
    for i in 0..n as isize {
        let (iu, prev, next) = (idx(i), idx(i - 1), idx(i + 1));
        for j in 0..n {
            s[(iu, j)] = c[j] / 4.0;
        }
        s[(iu, iu)] = (2.0 + c[iu] + r[iu] - r[prev]) / 4.0;
        s[(iu, prev)] = (c[prev] + r[prev]) / 4.0;
        s[(iu, next)] = (1.0 + c[next] - r[iu]) / 4.0;
        let ri = r[iu];
        s[(e1(iu), iu)] = 3.0 / 8.0 * (1.0 + ri);
        s[(e1(iu), next)] = 3.0 / 8.0 * (1.0 - ri);
        s[(e1(iu), e1(iu))] = (1.0 + ri) / 8.0;
        s[(e1(iu), e2(iu))] = (1.0 - ri) / 8.0;
        s[(e2(iu), iu)] = 3.0 / 8.0 * ri;
        s[(e2(iu), next)] = 3.0 / 8.0 * (2.0 - ri);
        s[(e2(iu), e1(iu))] = ri / 8.0;
        s[(e2(iu), e2(iu))] = (2.0 - ri) / 8.0;
        s[(cc(iu), iu)] = 9.0 / 16.0;
        s[(cc(iu), e1(iu))] = 3.0 / 16.0;
        s[(cc(iu), e2(prev))] = 3.0 / 16.0;
        s[(cc(iu), cc(iu))] = 1.0 / 16.0;
    }
    s
}

/// Independent implementation agreement: entries in [0, 1], a handful of
/// roundings each, plus an LU solve of a well-conditioned stationary system.
const INDEPENDENT_AGREE: f64 = 1e-12;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn rows_sum_exactly_to_one(k in rational_knots(3..=16)) {
        let m = LocalScheme::nurds(k.ratios().unwrap()).matrix().unwrap();
        prop_assert!(m.row_sum_defects().iter().all(|d| *d == Rational::frac(0, 1)));
        // entries are non-negative (a convex-combination scheme)
        prop_assert!(m.matrix().iter().all(|x| *x >= Rational::frac(0, 1)));
    }

    #[test]
    fn matches_independent_implementation(r in f64_ratios(3..=24)) {
        let ours = LocalScheme::nurds(r.clone()).matrix().unwrap();
        let theirs = independent_s_n(r.as_slice());
        prop_assert!((ours.matrix() - theirs).amax() < INDEPENDENT_AGREE);
    }

    #[test]
    fn f64_matrix_is_rounded_exact_matrix(k in rational_knots(3..=8)) {
        let exact = LocalScheme::nurds(k.ratios().unwrap()).matrix().unwrap();
        let kf = CornerIntervals::new(k.p().iter().map(Scalar::to_f64).collect(), k.q().iter().map(Scalar::to_f64).collect()).unwrap();
        let float = LocalScheme::nurds(kf.ratios().unwrap()).matrix().unwrap();
        prop_assert!((exact.to_f64().matrix() - float.matrix()).amax() < 1e-14);
    }

    /// Block lower-triangular structure; each E block has trace 3/8 and determinant 1/32.
    #[test]
    fn block_structure_exact(k in rational_knots(3..=10)) {
        let n = k.valence();
        let m = LocalScheme::nurds(k.ratios().unwrap()).matrix().unwrap().into_matrix();
        let lay = Layout::new(n);
        let zero = Rational::frac(0, 1);
        for i in 0..n {
            // P rows touch only P columns.
            for j in n..4 * n { prop_assert_eq!(&m[(lay.p(i), j)], &zero); }
            // E rows touch P and their own E pair only.
            for j in n..4 * n {
                if j != lay.e1(i) && j != lay.e2(i) {
                    prop_assert_eq!(&m[(lay.e1(i), j)], &zero);
                    prop_assert_eq!(&m[(lay.e2(i), j)], &zero);
                }
            }
            let (a, b, c, d) = (&m[(lay.e1(i), lay.e1(i))], &m[(lay.e1(i), lay.e2(i))], &m[(lay.e2(i), lay.e1(i))], &m[(lay.e2(i), lay.e2(i))]);
            prop_assert_eq!(a.clone() + d.clone(), Rational::frac(3, 8));
            prop_assert_eq!(a.clone() * d.clone() - b.clone() * c.clone(), Rational::frac(1, 32));
            // C block is I/16.
            for j in 3 * n..4 * n {
                let expect = if j == lay.c(i) { Rational::frac(1, 16) } else { zero.clone() };
                prop_assert_eq!(&m[(lay.c(i), j)], &expect);
            }
        }
    }
}

#[test]
fn uniform_nurds_is_exactly_the_cc_variant() {
    for n in 3..=12 {
        let nurds = LocalScheme::<Rational>::nurds(EdgeRatios::uniform(n).unwrap())
            .matrix()
            .unwrap();
        let ccv = LocalScheme::<Rational>::cc_variant(n)
            .unwrap()
            .matrix()
            .unwrap();
        assert_eq!(nurds.matrix(), ccv.matrix(), "n = {n}");
        // P'_i = 1/2 P_i + 1/8 (P_{i-1} + P_{i+1}) + F/4 with F the centroid (seed 004).
        let a = ccv.matrix();
        for i in 0..n {
            for j in 0..n {
                let mut expect = Rational::frac(1, 4 * n as i64);
                if i == j {
                    expect += Rational::frac(1, 2);
                }
                if (i + 1) % n == j || (j + 1) % n == i {
                    expect += Rational::frac(1, 8);
                }
                assert_eq!(a[(i, j)], expect, "n = {n}, ({i}, {j})");
            }
        }
    }
}

#[test]
fn original_doo_sabin_weights() {
    for n in [3usize, 4, 6] {
        let exact = LocalScheme::<Rational>::doo_sabin(n)
            .unwrap()
            .matrix()
            .unwrap();
        assert!(exact
            .row_sum_defects()
            .iter()
            .all(|d| *d == Rational::frac(0, 1)));
        let a = exact.matrix();
        assert_eq!(a[(0, 0)], Rational::frac(n as i64 + 5, 4 * n as i64));
        let float = LocalScheme::<f64>::doo_sabin(n).unwrap().matrix().unwrap();
        assert!((exact.to_f64().matrix() - float.matrix()).amax() < 1e-15);
    }
    // n = 4: w_01 = (3 + 2 cos(pi/2))/16 = 3/16, w_02 = (3 - 2)/16 = 1/16.
    let a = LocalScheme::<Rational>::doo_sabin(4)
        .unwrap()
        .face_block()
        .unwrap();
    assert_eq!(a[(0, 1)], Rational::frac(3, 16));
    assert_eq!(a[(0, 2)], Rational::frac(1, 16));
    // Irrational weights are refused in exact arithmetic, with the valence named.
    let e = LocalScheme::<Rational>::doo_sabin(5)
        .unwrap()
        .matrix()
        .unwrap_err();
    assert!(e.to_string().contains("valence = 5"), "{e}");
    for n in 3..=20 {
        let m = LocalScheme::<f64>::doo_sabin(n)
            .unwrap()
            .face_block()
            .unwrap();
        for i in 0..n {
            let expect = (3.0 + 2.0 * (2.0 * std::f64::consts::PI * 1.0 / n as f64).cos())
                / (4.0 * n as f64);
            assert!((m[(i, (i + n - 1) % n)] - expect).abs() < 1e-15);
        }
    }
}

#[test]
fn labels_follow_documented_order() {
    let m = LocalScheme::<f64>::cc_variant(3).unwrap().matrix().unwrap();
    let names: Vec<String> = m.rows().iter().map(ToString::to_string).collect();
    assert_eq!(
        names,
        ["P0", "P1", "P2", "E0,1", "E0,2", "E1,1", "E1,2", "E2,1", "E2,2", "C0", "C1", "C2"]
    );
}

#[test]
fn scheme_kinds_parse_and_validate() {
    for k in SchemeKind::ALL {
        assert_eq!(k.name().parse::<SchemeKind>().unwrap(), *k);
    }
    assert!("midedge"
        .parse::<SchemeKind>()
        .unwrap_err()
        .to_string()
        .contains("\"midedge\""));
    let r = EdgeRatios::new(vec![0.3, 0.5, 0.5]).unwrap();
    assert!(LocalScheme::from_kind(SchemeKind::DooSabin, 3, Some(r.clone())).is_err());
    assert!(LocalScheme::from_kind(SchemeKind::Nurds, 4, Some(r)).is_err());
    assert!(LocalScheme::<f64>::from_kind(SchemeKind::CcVariant, 2, None).is_err());
}
