//! The generic certificate on sqrt(3)'s two-step matrix (math doc sections
//! 20.9 and 21): the regular rules read as a one-to-nine split, checked
//! against the one-step rules composed here, and the verdict at every
//! valence consistent with the eigen-analysis of the two-step matrix.

use num_traits::{One, Zero};
use std::collections::BTreeMap;
use subdiv_lab::charmap::generic::{self, layout::Lattice, mask, GenericVerdict};
use subdiv_lab::scalar::Rational;
use subdiv_lab::schemes::{LocalScheme, Scheme};
use subdiv_lab::spectral::{classify_scheme, SubdominantClass};

type Stencil = BTreeMap<[i64; 2], Rational>;

fn frac(a: i64, b: i64) -> Rational {
    Rational::new(a.into(), b.into())
}

fn add(out: &mut Stencil, st: &Stencil, w: &Rational) {
    for (k, v) in st {
        *out.entry(*k).or_insert_with(Rational::zero) += v * w;
    }
}

/// The six lattice directions (triangle lattice, basis `d_0, d_1`).
const DIRS: [[i64; 2]; 6] = [[1, 0], [0, 1], [-1, 1], [-1, 0], [0, -1], [1, -1]];

/// The level-1 point `y` (coordinates in thirds of a level-0 step: an old
/// vertex at `3 alpha`, face points at `3 alpha + (1, 1)` and
/// `3 alpha + (2, 2)`) over the level-0 points: Kobbelt's regular rules,
/// vertex `2/3 p + 1/18 sum p_k` (`alpha_6 = 1/3`), face point the centroid.
fn level1(y: [i64; 2]) -> Stencil {
    let r = [y[0].rem_euclid(3), y[1].rem_euclid(3)];
    let a = [y[0].div_euclid(3), y[1].div_euclid(3)];
    let mut st = Stencil::new();
    match r {
        [0, 0] => {
            st.insert(a, frac(2, 3));
            for d in DIRS {
                st.insert([a[0] + d[0], a[1] + d[1]], frac(1, 18));
            }
        }
        [1, 1] => {
            for c in [[0, 0], [1, 0], [0, 1]] {
                st.insert([a[0] + c[0], a[1] + c[1]], frac(1, 3));
            }
        }
        [2, 2] => {
            for c in [[1, 0], [0, 1], [1, 1]] {
                st.insert([a[0] + c[0], a[1] + c[1]], frac(1, 3));
            }
        }
        _ => panic!("{y:?} is no level-1 point"),
    }
    st
}

fn is_level1(y: [i64; 2]) -> bool {
    let r = [y[0].rem_euclid(3), y[1].rem_euclid(3)];
    r[0] == r[1]
}

/// The level-2 point `beta` (thirds: every lattice point) over the level-0
/// points: the level-1 vertex rule (the level-1 neighbours sit at the face
/// points `d_k + d_{k+1}`, in thirds) or the centroid of a level-1 triangle.
fn level2(beta: [i64; 2]) -> Stencil {
    let n1: Vec<[i64; 2]> = (0..6)
        .map(|k| {
            let (a, b) = (DIRS[k], DIRS[(k + 1) % 6]);
            [a[0] + b[0], a[1] + b[1]]
        })
        .collect();
    let mut out = Stencil::new();
    if is_level1(beta) {
        add(&mut out, &level1(beta), &frac(2, 3));
        for d in &n1 {
            add(
                &mut out,
                &level1([beta[0] + d[0], beta[1] + d[1]]),
                &frac(1, 18),
            );
        }
        return out;
    }
    // beta = y + (n1_k + n1_{k+1}) / 3 = y + DIRS[k + 1] for a level-1 y
    for k in 0..6 {
        let u = DIRS[(k + 1) % 6];
        let y = [beta[0] - u[0], beta[1] - u[1]];
        if is_level1(y) {
            for c in [[0, 0], n1[k], n1[(k + 1) % 6]] {
                add(&mut out, &level1([y[0] + c[0], y[1] + c[1]]), &frac(1, 3));
            }
            return out;
        }
    }
    panic!("{beta:?} is in no level-1 triangle");
}

/// The two-step mask `a_{beta - 3 alpha}` composed from the one-step rules.
fn composed_mask() -> Stencil {
    let mut mask = Stencil::new();
    for x in -4..=4 {
        for y in -4..=4 {
            for (alpha, w) in level2([x, y]) {
                let g = [x - 3 * alpha[0], y - 3 * alpha[1]];
                if let Some(old) = mask.insert(g, w.clone()) {
                    assert_eq!(old, w, "the two-step rules are not translation invariant");
                }
            }
        }
    }
    mask.retain(|_, w| !w.is_zero());
    mask
}

fn regular_rows() -> (
    subdiv_lab::schemes::LocalMatrix<f64>,
    subdiv_lab::schemes::LocalMatrix<Rational>,
) {
    let s = LocalScheme::Sqrt3 { valence: 5 };
    let regular = s.regular_configuration().unwrap().unwrap();
    (
        regular.local_matrix().unwrap(),
        regular.exact_local_matrix().unwrap().unwrap(),
    )
}

#[test]
fn two_step_rules_are_the_composed_one_to_nine_split() {
    let (rm, exact) = regular_rows();
    let symbol = mask::read_with_dilation(&rm, Some(&exact), Lattice::Triangle, 3).unwrap();
    let composed = composed_mask();
    assert_eq!(symbol, composed);
    assert_eq!(symbol.len(), 73);
    assert!(symbol.values().all(|w| *w >= frac(1, 324)));
    // nine cosets, each summing to 1, with equal moments of order 1 and 2
    // (sigma = 0; sum rules of order 3)
    let moments = |cx: i64, cy: i64| -> Vec<Rational> {
        [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)]
            .iter()
            .map(|&(a, b)| {
                symbol
                    .iter()
                    .filter(|(g, _)| g[0].rem_euclid(3) == cx && g[1].rem_euclid(3) == cy)
                    .map(|(g, w)| w * Rational::from_integer((g[0].pow(a) * g[1].pow(b)).into()))
                    .sum()
            })
            .collect()
    };
    let first = moments(0, 0);
    assert!(first[0].is_one() && first[1].is_zero() && first[2].is_zero());
    for cx in 0..3 {
        for cy in 0..3 {
            assert_eq!(moments(cx, cy), first, "coset ({cx}, {cy})");
        }
    }
    // read as a halving the rules are not translation invariant
    assert!(mask::read_with_dilation(&rm, Some(&exact), Lattice::Triangle, 2).is_err());
    // no scalar derivative scheme: the symbol has no factor 1 + z^e + z^2e
    for e in [[1, 0], [0, 1], [-1, 1]] {
        assert!(mask::divide_by(&symbol, e, 3).is_none(), "{e:?}");
    }
}

#[test]
fn sqrt3_verdict_refers_to_the_two_step_matrix_and_matches_its_eigen_analysis() {
    for n in 3..=16 {
        let s = LocalScheme::Sqrt3 { valence: n };
        let sub = classify_scheme(&s).unwrap();
        // the two-step matrix: a real double subdominant eigenvalue
        // (2 + 2 cos(2 pi / n)) / 9 with a 2-D eigenspace
        let lambda = (2.0 + 2.0 * (2.0 * std::f64::consts::PI / n as f64).cos()) / 9.0;
        assert_eq!(sub.class, SubdominantClass::Standard, "n = {n}");
        assert!((sub.lambda1.re - lambda).abs() < 1e-12, "n = {n}");
        assert!(sub.lambda1.im.abs() < 1e-12, "n = {n}");
        // the one-step matrix: the complex pair (1 + exp(+-2 pi i / n)) / 3
        let (steps, one) = s.one_step_matrix().unwrap();
        assert_eq!(steps, 2);
        let one = one.unwrap();
        let ev = one.matrix().complex_eigenvalues();
        let pair = num_complex::Complex64::from_polar(1.0, 2.0 * std::f64::consts::PI / n as f64);
        let pair = (pair + 1.0) / 3.0;
        assert!(
            ev.iter().any(|z| (z - pair).norm() < 1e-9)
                && ev.iter().any(|z| (z - pair.conj()).norm() < 1e-9),
            "n = {n}"
        );
        // the precondition holds, so the verdict is decided by the rules:
        // indeterminate (dilation 3, matrix derivative schemes), never c1 or
        // not_c1, and it names the two-step matrix
        let g = generic::check(&s, &sub).unwrap();
        assert_eq!(g.matrix_steps, Some(2), "n = {n}");
        assert_eq!(g.to_json()["matrix_steps"], 2, "n = {n}");
        let GenericVerdict::Indeterminate { reason } = &g.verdict else {
            panic!("n = {n}: {}", g.verdict)
        };
        assert!(
            reason.contains("one-to-nine split (dilation 3, 73 weights)")
                && reason.contains("no factor 1 + z^e + z^2e along any lattice direction"),
            "n = {n}: {reason}"
        );
    }
    // one-step schemes carry no steps
    let sub = classify_scheme(&LocalScheme::loop_subdivision(5).unwrap()).unwrap();
    let g = generic::check(&LocalScheme::loop_subdivision(5).unwrap(), &sub).unwrap();
    assert_eq!(g.matrix_steps, None);
    assert!(g.to_json().get("matrix_steps").is_none());
}
