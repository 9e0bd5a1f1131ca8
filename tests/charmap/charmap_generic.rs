//! The generic C1 certificate (`charmap::generic`): agreement with the ring
//! certificates, planted folds, and soundness of its enclosures.

use num_traits::Signed;
use proptest::prelude::*;
use subdiv_lab::charmap::generic::net::{combine, Ball, Net};
use subdiv_lab::charmap::generic::{self, cells, GenericVerdict, Witness};
use subdiv_lab::charmap::{self as cm};
use subdiv_lab::schemes::{LocalMatrix, LocalScheme, Scheme};
use subdiv_lab::spectral::classify_scheme;

pub(crate) fn generic_of<S: Scheme + ?Sized>(s: &S) -> generic::GenericReport {
    let sub = classify_scheme(s).unwrap();
    generic::check(s, &sub).unwrap()
}

fn ring_code<S: Scheme + ?Sized>(s: &S) -> &'static str {
    let sub = classify_scheme(s).unwrap();
    cm::check_classified(s, &sub).unwrap().verdict.code()
}

/// `c1` from one certificate is `c1` from the other; a negative verdict
/// of one is never `c1` of the other.
fn assert_agree<S: Scheme + ?Sized>(s: &S) {
    let g = generic_of(s);
    let ring = ring_code(s);
    let label = s.label();
    match g.verdict.code() {
        "c1" => assert_eq!(ring, "c1", "{label}: generic c1, ring {ring}"),
        "not_c1" => assert!(
            ring == "not_regular" || ring == "not_injective" || ring == "indeterminate",
            "{label}: generic {}, ring {ring}",
            g.verdict
        ),
        _ => panic!("{label}: generic {}, ring {ring}", g.verdict),
    }
    if ring == "c1" {
        assert_eq!(g.verdict, GenericVerdict::C1, "{label}");
    }
}

#[test]
fn loop_agrees_with_the_ring_certificate_n3_to_16() {
    for n in 3..=16 {
        assert_agree(&LocalScheme::loop_subdivision(n).unwrap());
    }
}

#[test]
fn catmull_clark_agrees_with_the_ring_certificate_n3_to_16() {
    for n in 3..=16 {
        assert_agree(&LocalScheme::catmull_clark(n).unwrap());
    }
}

#[test]
fn adjustable_scheme_agrees_with_the_cone_certificate() {
    for c in [0.2, 0.35, 0.5, 0.65, 0.8] {
        for n in [3, 5, 8] {
            assert_agree(&LocalScheme::adjustable_cc(n, c).unwrap());
        }
    }
}

#[test]
fn scheme_files_get_the_certificate_with_no_extra_code() {
    // Catmull-Clark's and Loop's vertex rules, written as files: the files
    // have no ring of patches (the ring certificate says no_charmap), the
    // generic certificate gives the built-in schemes' ring verdicts
    let quad = subdiv_lab::schemes::user::SchemeFile::parse_shared(
        "name = \"my-cc\"\ntopology = \"quad\"\n[vertex]\nself = \"1 - 7/(4*n)\"\nedge = \"3/(2*n^2)\"\nface = \"1/(4*n^2)\"\n",
    )
    .unwrap();
    let tri = subdiv_lab::schemes::user::SchemeFile::parse_shared(
        "name = \"my-loop\"\ntopology = \"triangle\"\n[vertex]\nself = \"1 - (5/8 - (3/8 + cos(2*pi/n)/4)^2)\"\nedge = \"(5/8 - (3/8 + cos(2*pi/n)/4)^2)/n\"\n",
    )
    .unwrap();
    for n in [3, 5, 9] {
        let q = quad.at(n).unwrap();
        assert_eq!(ring_code(&q), "no_charmap");
        assert_eq!(
            generic_of(&q).verdict.code(),
            ring_code(&LocalScheme::catmull_clark(n).unwrap())
        );
        let t = tri.at(n).unwrap();
        assert_eq!(
            generic_of(&t).verdict.code(),
            ring_code(&LocalScheme::loop_subdivision(n).unwrap())
        );
    }
}

#[test]
fn face_centred_schemes_are_indeterminate_with_the_reason() {
    // Doo-Sabin, its Catmull-Clark variant and NURDS (uniform and
    // non-uniform knots, as the ring tests use them): the ring certificate
    // decides, the generic one says why it does not apply, never a verdict
    let ratios =
        |r: &[f64]| LocalScheme::nurds(subdiv_lab::knots::EdgeRatios::new(r.to_vec()).unwrap());
    let mut schemes = Vec::new();
    for n in 3..=8 {
        schemes.push(LocalScheme::doo_sabin(n).unwrap());
        schemes.push(LocalScheme::cc_variant(n).unwrap());
        schemes.push(ratios(&vec![0.5; n]));
    }
    schemes.push(ratios(&[0.2, 0.85, 0.4, 0.6, 0.1, 0.7]));
    schemes.push(ratios(&[0.05, 0.3, 0.95]));
    for s in &schemes {
        let g = generic_of(s);
        let GenericVerdict::Indeterminate { reason } = &g.verdict else {
            panic!("{}: {}", s.label(), g.verdict)
        };
        assert!(
            reason.starts_with("face-centred neighbourhood (point P0)")
                && reason.contains("--charmap ring"),
            "{}: {reason}",
            s.label()
        );
        assert_ne!(ring_code(s), "no_charmap", "{}", s.label());
    }
}

/// A scheme given by a modified local matrix on an unchanged regular part.
#[derive(Debug)]
pub(crate) struct Planted {
    pub(crate) base: LocalScheme,
    /// `(row, column, delta)`: `delta` added at `(row, column)` and taken
    /// from `(row, 0)` (the centre), so rows still sum to 1.
    pub(crate) changes: Vec<(usize, usize, f64)>,
}

impl Scheme for Planted {
    fn name(&self) -> &str {
        "planted"
    }
    fn valence(&self) -> usize {
        self.base.valence()
    }
    fn local_matrix(&self) -> subdiv_lab::Result<LocalMatrix<f64>> {
        let m = self.base.local_matrix()?;
        let mut a = m.matrix().clone();
        for &(r, c, d) in &self.changes {
            a[(r, c)] += d;
            a[(r, 0)] -= d;
        }
        let mut asm = subdiv_lab::schemes::Assembler::<f64>::new(
            "planted",
            m.valence(),
            m.rows().to_vec(),
            m.cols().to_vec(),
        );
        for r in 0..a.nrows() {
            for c in 0..a.ncols() {
                if a[(r, c)] != 0.0 {
                    asm.add(r, c, a[(r, c)]);
                }
            }
        }
        asm.finish()
    }
    fn regular_configuration(&self) -> Option<subdiv_lab::Result<Box<dyn Scheme>>> {
        self.base.regular_configuration()
    }
}

/// Dense sampling of the discrete Jacobian of the net at `level`: the
/// signs of `det(p_{x+e1} - p_x, p_{x+e2} - p_x)` over the annulus, counted
/// where they are clearly away from zero (relative `1e-6`).
pub(crate) fn sampled_signs(prep: &generic::Prepared, level: u32) -> (usize, usize) {
    let mut net: Net = prep.net.clone();
    for k in 0..level {
        net = prep.refine(&net, k);
    }
    let d = prep.rules.dilation;
    let l = cells::steps(d, level);
    let (mut pos, mut neg) = (0, 0);
    for s in 0..net.n {
        for i in 0..l {
            for j in 0..l {
                let outside = match prep.rules.lattice {
                    generic::layout::Lattice::Triangle => i + j < l / d || i + j >= l,
                    _ => i.max(j) < l / d,
                };
                if outside {
                    continue;
                }
                let (Some(p), Some(a), Some(b)) = (
                    net.at(s, [i, j]),
                    net.at(s, [i + 1, j]),
                    net.at(s, [i, j + 1]),
                ) else {
                    continue;
                };
                let u = [a.mid[0] - p.mid[0], a.mid[1] - p.mid[1]];
                let v = [b.mid[0] - p.mid[0], b.mid[1] - p.mid[1]];
                let det = u[0] * v[1] - u[1] * v[0];
                let scale = (u[0].hypot(u[1])) * (v[0].hypot(v[1]));
                if det > 1e-6 * scale {
                    pos += 1;
                } else if det < -1e-6 * scale {
                    neg += 1;
                }
            }
        }
    }
    (pos, neg)
}

pub(crate) fn prepared<S: Scheme + ?Sized>(s: &S) -> Option<generic::Prepared> {
    let sub = classify_scheme(s).ok()?;
    generic::prepare_scheme(s, &sub).ok()?.ok()
}

/// Loop at valence `n` with the regular vertex rule of every `e_i`
/// (the row of `g_i`) given `delta` more weight on `e_i` (taken from `v`),
/// and the edge rule of `e_i e_{i+1}` (the row of `f_i`) `eps` more on both
/// ends: the spectrum is Loop's (the one-ring block is untouched), the
/// characteristic map moves its outer points.
fn planted_loop(n: usize, delta: f64, eps: f64) -> Planted {
    let mut changes = Vec::new();
    for i in 0..n {
        changes.push((1 + n + 2 * i, 1 + i, delta));
        changes.push((2 + n + 2 * i, 1 + i, eps));
        changes.push((2 + n + 2 * i, 1 + (i + 1) % n, eps));
    }
    Planted {
        base: LocalScheme::loop_subdivision(n).unwrap(),
        changes,
    }
}

/// The first `(delta, eps)` of a grid at which dense sampling of the
/// planted Loop net at valence `n` finds both Jacobian signs.
fn find_fold(n: usize) -> (f64, f64) {
    for delta in [-0.8, -1.0, -1.3, -1.6, -2.0, -2.5, 0.8, 1.5, 2.5] {
        for eps in [0.0, -0.3, 0.3] {
            let p = planted_loop(n, delta, eps);
            if let Some(prep) = prepared(&p) {
                let (pos, neg) = sampled_signs(&prep, 6);
                if pos > 0 && neg > 0 {
                    return (delta, eps);
                }
            }
        }
    }
    panic!("no fold found at valence {n}");
}

#[test]
fn planted_fold_is_not_c1_with_a_sign_change() {
    for n in [4, 5, 7] {
        let (delta, eps) = find_fold(n);
        let g = generic_of(&planted_loop(n, delta, eps));
        assert!(
            matches!(
                g.verdict,
                GenericVerdict::NotC1 {
                    witness: Witness::JacobianSignChange { .. }
                }
            ),
            "n = {n}, delta = {delta}, eps = {eps}: {}",
            g.verdict
        );
    }
    // the unperturbed scheme samples one sign and is c1
    let q = planted_loop(5, 0.0, 0.0);
    let (pos, neg) = sampled_signs(&prepared(&q).unwrap(), 6);
    assert!(pos == 0 || neg == 0);
    assert_eq!(generic_of(&q).verdict, GenericVerdict::C1);
}

/// Every cell the certificate signs at level 4 has no clearly wrong-signed
/// discrete Jacobian among the level-8 samples inside it (a folded net, so
/// that cells near the fold are tested).
#[test]
fn certified_cells_hold_their_sign_under_dense_sampling() {
    let (delta, eps) = find_fold(5);
    let prep = prepared(&planted_loop(5, delta, eps)).unwrap();
    let seen = assert_certified_cells_hold(&prep, 5, 4..=6, 3);
    // both signs were certified: the fold runs through the annulus
    assert!(seen[0] && seen[1], "{seen:?}");
}

/// The modified butterfly at valence `n` with the rows of the new `g_i`
/// (the old `e_i`, interpolated) given `delta` more weight on `e_i`, taken
/// from `v`: the matrix stays block lower triangular with the same
/// diagonal blocks (same spectrum), the characteristic map's outer points
/// move.
fn planted_butterfly(n: usize, delta: f64) -> Planted {
    Planted {
        base: LocalScheme::ModifiedButterfly { valence: n },
        changes: (0..n).map(|i| (1 + n + 2 * i, 1 + i, delta)).collect(),
    }
}

#[test]
fn modified_butterfly_is_c1_through_the_norm_enclosure() {
    for n in [5, 7] {
        let s = LocalScheme::ModifiedButterfly { valence: n };
        let g = generic_of(&s);
        assert_eq!(g.verdict, GenericVerdict::C1, "n = {n}");
    }
    let prep = prepared(&LocalScheme::ModifiedButterfly { valence: 5 }).unwrap();
    assert!(prep.rules.norm.is_some());
}

#[test]
fn planted_butterfly_fold_is_never_c1() {
    let n = 5;
    let mut found = false;
    for delta in [-0.5, -0.8, -1.2, -2.0, 0.8, 1.5, 3.0] {
        let p = planted_butterfly(n, delta);
        let Some(prep) = prepared(&p) else { continue };
        let (pos, neg) = sampled_signs(&prep, 6);
        if pos > 0 && neg > 0 {
            found = true;
            let g = generic_of(&p);
            assert!(
                matches!(
                    g.verdict,
                    GenericVerdict::NotC1 {
                        witness: Witness::JacobianSignChange { .. }
                    }
                ),
                "delta = {delta}: {}",
                g.verdict
            );
            // the norm-based enclosure signs cells only at fine levels here
            let seen = assert_certified_cells_hold(&prep, n, 8..=8, 2);
            assert!(seen[0] && seen[1], "{seen:?}");
            break;
        }
    }
    assert!(found, "no fold found");
}

/// Every cell signed at `levels` keeps its sign at the samples of the
/// net `finer` levels finer inside it; returns which signs were certified.
pub(crate) fn assert_certified_cells_hold(
    prep: &generic::Prepared,
    n: usize,
    levels: std::ops::RangeInclusive<u32>,
    finer: u32,
) -> [bool; 2] {
    let mut nets = vec![prep.net.clone()];
    for k in 0..levels.end() + finer {
        let next = prep.refine(&nets[k as usize], k);
        nets.push(next);
    }
    let (mut signed, mut checked) = (0, 0);
    let mut seen = [false; 2];
    let d = prep.rules.dilation;
    for coarse in levels {
        let fine = coarse + finer;
        let scale = cells::steps(d, fine - coarse);
        for s in 0..n {
            for cell in cells::annulus(prep.rules.lattice, d, s, coarse) {
                let cs = cells::cell_sign(&nets[coarse as usize], &prep.rules, &cell);
                if cs.sign == 0 {
                    continue;
                }
                signed += 1;
                seen[usize::from(cs.sign < 0)] = true;
                let net = &nets[fine as usize];
                for a in 0..scale {
                    for b in 0..scale {
                        // sample points inside the cell (triangles: the right half of the square)
                        let inside = match cell.kind {
                            0 => a + b < scale - 1,
                            _ => a + b > scale,
                        };
                        if !inside {
                            continue;
                        }
                        let x = [cell.i * scale + a, cell.j * scale + b];
                        let (Some(o), Some(u), Some(v)) = (
                            net.at(s, x),
                            net.at(s, [x[0] + 1, x[1]]),
                            net.at(s, [x[0], x[1] + 1]),
                        ) else {
                            continue;
                        };
                        let du = [u.mid[0] - o.mid[0], u.mid[1] - o.mid[1]];
                        let dv = [v.mid[0] - o.mid[0], v.mid[1] - o.mid[1]];
                        let det = du[0] * dv[1] - du[1] * dv[0];
                        let size = du[0].hypot(du[1]) * dv[0].hypot(dv[1]);
                        checked += 1;
                        assert!(
                            det * f64::from(cs.sign) > -1e-3 * size,
                            "{cell} certified {} but samples {det:e} (relative {:e})",
                            cs.sign,
                            det / size
                        );
                    }
                }
            }
        }
    }
    assert!(
        signed > 0 && checked > 0,
        "{signed} cells signed, {checked} samples"
    );
    seen
}

#[test]
fn rounding_terms_of_a_combination_cover_the_exact_sum() {
    use num_rational::BigRational;
    let mut rng = 0x2545F4914F6CDD1Du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut inexact = 0;
    for _ in 0..200 {
        let terms: Vec<(f64, Ball)> = (0..9)
            .map(|_| {
                (
                    next() / 3.0,
                    Ball {
                        mid: [next() * 7.0, next()],
                        rad: 0.0,
                    },
                )
            })
            .collect();
        let b = combine(&terms);
        for k in 0..2 {
            let exact: BigRational = terms
                .iter()
                .map(|(w, p)| {
                    BigRational::from_float(*w).unwrap()
                        * BigRational::from_float(p.mid[k]).unwrap()
                })
                .sum();
            let err = (exact - BigRational::from_float(b.mid[k]).unwrap()).abs();
            assert!(err <= BigRational::from_float(b.rad).unwrap());
            if err > BigRational::from_float(0.0).unwrap() {
                inexact += 1;
            }
        }
    }
    assert!(inexact > 0, "the test needs inexact sums to mean anything");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    /// Random perturbations of Loop's outer rows (Loop's spectrum kept) are
    /// never certified C1 where dense sampling of the net finds a fold.
    #[test]
    fn perturbations_that_fold_are_never_certified(
        n in 3usize..9,
        delta in -2.5f64..2.5,
        eps in -0.4f64..0.4,
    ) {
        let p = planted_loop(n, delta, eps);
        if let Some(prep) = prepared(&p) {
            let (pos, neg) = sampled_signs(&prep, 6);
            let g = generic_of(&p);
            if pos > 0 && neg > 0 {
                prop_assert_ne!(g.verdict, GenericVerdict::C1);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]
    /// Random perturbations of the modified butterfly's rows of `g_i` (its
    /// spectrum kept; the norm-based enclosure of a mask with negative
    /// weights) are never certified C1 where dense sampling of the net
    /// finds a fold. Each folded case runs the certificate to its work
    /// limit (4 to 11 s), so the default suite keeps the deterministic
    /// `planted_butterfly_fold_is_never_c1` and this draw runs in CI.
    #[test]
    #[ignore = "heavy randomised run (about 30 s); .ci/run runs it with --ignored"]
    fn butterfly_perturbations_that_fold_are_never_certified(
        n in prop::sample::select(vec![4usize, 5, 7]),
        delta in -3.0f64..3.0,
    ) {
        let p = planted_butterfly(n, delta);
        if let Some(prep) = prepared(&p) {
            let (pos, neg) = sampled_signs(&prep, 6);
            if pos > 0 && neg > 0 {
                prop_assert_ne!(generic_of(&p).verdict, GenericVerdict::C1);
            }
        }
    }
}

/// The modified butterfly's generic verdict is `c1` at every valence of
/// `valences`, n = 6 (the regular butterfly) with its class proven exactly.
/// At n = 10 (spectrum 1, 1/2 twice, 1/4 three times) the class comes from
/// the general eigen-decomposition, as in `analyze`: the sweep kernel's
/// radii leave the linear regime there (math doc 10, "Two routes, one
/// verdict").
fn assert_modified_butterfly_c1(valences: std::ops::RangeInclusive<usize>) {
    for n in valences {
        let g = generic_of(&LocalScheme::ModifiedButterfly { valence: n });
        eprintln!("modified butterfly n = {n}: {}", g.verdict);
        assert_eq!(g.verdict, GenericVerdict::C1, "n = {n}");
        assert_eq!(g.class_proof.is_some(), n == 6, "n = {n}");
    }
}

#[test]
fn modified_butterfly_is_c1_at_valences_3_to_11() {
    assert_modified_butterfly_c1(3..=11);
}

/// Valences 12 to 16 need a level of local refinement (3.5 to 7.8 s each).
#[test]
#[ignore = "heavy full-size run (about 20 s); .ci/run runs it with --ignored"]
fn modified_butterfly_is_c1_at_valences_12_to_16() {
    assert_modified_butterfly_c1(12..=16);
}

#[test]
fn butterfly_verdicts_3_to_16() {
    // n >= 8: where the library's floating-point class is standard (or
    // proven), regular with a ring winding 2 or 3 times; never c1
    let mut winds = 0;
    for n in 3..=16 {
        let g = generic_of(&LocalScheme::Butterfly { valence: n });
        eprintln!("butterfly n = {n}: {}", g.verdict);
        match n {
            // n = 3: an eigenvalue of modulus 1/4 at the exact test's threshold
            3 => assert_eq!(g.verdict.code(), "indeterminate", "n = {n}"),
            4 | 6 | 7 => assert_eq!(g.verdict, GenericVerdict::C1, "n = {n}"),
            // n = 5: lambda has degree 8; its eigenspace is proven by the
            // rotation of the sectors (math doc 20.8)
            5 => {
                assert_eq!(g.verdict, GenericVerdict::C1, "n = {n}");
                assert!(g.class_proof.is_some(), "n = {n}");
            }
            _ if g.level.is_none() => {}
            _ => {
                assert!(
                    matches!(g.verdict, GenericVerdict::NotC1 { witness: Witness::Winding { winding, .. } } if winding.abs() >= 2),
                    "n = {n}: {}",
                    g.verdict
                );
                winds += 1;
            }
        }
    }
    assert!(winds >= 5, "{winds} valences certified not C1");
}

/// The net refined `levels` times from level 0.
fn net_at(prep: &generic::Prepared, levels: u32) -> Net {
    let mut net = prep.net.clone();
    for k in 0..levels {
        net = prep.refine(&net, k);
    }
    net
}

#[test]
fn local_patches_hold_the_nets_values() {
    let prep = prepared(&LocalScheme::ModifiedButterfly { valence: 5 }).unwrap();
    let coarse = net_at(&prep, 6);
    let fine = prep.refine(&coarse, 6);
    let (mut compared, mut far) = (0, 0);
    for s in [0, 3] {
        let values = |p| coarse.at(s, p);
        let patch = cells::Patch::refine(&values, &prep.rules, [40, 80, -10, 30], 2);
        for x in 40..=80 {
            for y in -10..=30 {
                let (Some(a), Some(b)) = (patch.at([x, y]), fine.at(s, [x, y])) else {
                    continue;
                };
                compared += 1;
                for k in 0..2 {
                    let d = (a.mid[k] - b.mid[k]).abs();
                    assert!(d <= a.rad + b.rad, "sector {s} ({x}, {y}): {d:e}");
                    if d > 0.0 {
                        far += 1;
                    }
                }
            }
        }
    }
    assert!(compared > 1000, "{compared} values compared");
    // the points are the same combinations: equal to the last bit or nearly
    assert!(far < compared, "{far} of {compared} differ");
}

/// The box `[xmin, xmax, ymin, ymax]` of a set of balls.
pub(crate) fn ball_box(balls: &[Ball]) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for x in balls {
        b[0] = b[0].min(x.mid[0] - x.rad);
        b[1] = b[1].max(x.mid[0] + x.rad);
        b[2] = b[2].min(x.mid[1] - x.rad);
        b[3] = b[3].max(x.mid[1] + x.rad);
    }
    b
}

#[test]
fn derivative_enclosures_contain_the_enclosures_of_their_subcells() {
    // cells of level 9 (patches from the net of level 8) against their
    // descendants three levels finer: the derivative over a subcell
    // (enclosed tightly, in its level's units: 1/8 of the coarse ones)
    // lies in the cell's enclosure, so the boxes must meet
    let n = 7;
    let prep = prepared(&LocalScheme::ModifiedButterfly { valence: n }).unwrap();
    let net = net_at(&prep, 8);
    let lattice = prep.rules.lattice;
    let m = prep.margin as i64;
    let patch_of = |values: &cells::Values, c: &cells::Cell| {
        let bx = [2 * c.i - m, 2 * c.i + 2 + m, 2 * c.j - m, 2 * c.j + 2 + m];
        cells::Patch::refine(values, &prep.rules, bx, 2)
    };
    let (mut checked, mut first_order) = (0, 0);
    for (idx, coarse) in cells::annulus(lattice, 2, 2, 8).into_iter().enumerate() {
        if idx % 1999 != 0 {
            continue;
        }
        let p9 = patch_of(&|p| net.at(2, p), &coarse);
        for cell in cells::children(lattice, 2, &coarse) {
            let v9 = |p| p9.at(p);
            let p10 = patch_of(&v9, &cell);
            let outer: Vec<_> = (0..2)
                .map(|k| cells::derivative_enclosure(&v9, &prep.rules, &cell, k).unwrap())
                .collect();
            // the first-order enclosure is centred off the lattice values
            let (a, b) = (
                p9.at([cell.i, cell.j]).unwrap(),
                p9.at([cell.i - 1, cell.j]).unwrap(),
            );
            if outer[0][0].mid != [a.mid[0] - b.mid[0], a.mid[1] - b.mid[1]] {
                first_order += 1;
            }
            for c10 in cells::children(lattice, 2, &cell) {
                let v10 = |p| p10.at(p);
                let p11 = patch_of(&v10, &c10);
                for c11 in cells::children(lattice, 2, &c10) {
                    let v11 = |p| p11.at(p);
                    let p12 = patch_of(&v11, &c11);
                    for c12 in cells::children(lattice, 2, &c11) {
                        for (k, o) in outer.iter().enumerate() {
                            let inner =
                                cells::derivative_enclosure(&|p| p12.at(p), &prep.rules, &c12, k)
                                    .unwrap();
                            let scaled: Vec<Ball> = inner
                                .iter()
                                .map(|b| Ball {
                                    mid: [8.0 * b.mid[0], 8.0 * b.mid[1]],
                                    rad: 8.0 * b.rad,
                                })
                                .collect();
                            // the subcell's balls are tight: their centres
                            // lie in the cell's enclosure box
                            let a = ball_box(o);
                            for b in &scaled {
                                assert!(
                                    a[0] <= b.mid[0]
                                        && b.mid[0] <= a[1]
                                        && a[2] <= b.mid[1]
                                        && b.mid[1] <= a[3],
                                    "{cell} d{k}: enclosure {a:?}, subcell {c12} {b:?}"
                                );
                            }
                            checked += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(
        checked > 500 && first_order > 0,
        "{checked} checks, {first_order} first-order"
    );
}
