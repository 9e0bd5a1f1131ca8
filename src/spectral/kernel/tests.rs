//! Tests of the kernel: cross-checks against faer and of the lock-step and
//! interleaved paths against lone calls, bit for bit.

use super::condition::{inverse_iteration_kappa, kappa_2x2, LaneStorage};
use super::*;
use crate::spectral::SpectralError;
use num_complex::Complex64;

fn eig(n: usize, f: impl Fn(usize, usize) -> f64) -> Vec<Complex64> {
    let mut ws = KernelWorkspace::new();
    let a = ws.input(n);
    for j in 0..n {
        for i in 0..n {
            a[i + j * n] = f(i, j);
        }
    }
    let (re, im) = ws.eigenvalues().unwrap();
    let mut v: Vec<Complex64> = re
        .iter()
        .zip(im)
        .map(|(&r, &i)| Complex64::new(r, i))
        .collect();
    v.sort_by(|a, b| {
        (b.norm(), b.re, b.im)
            .partial_cmp(&(a.norm(), a.re, a.im))
            .unwrap()
    });
    v
}

#[test]
fn cyclic_permutations_converge() {
    for n in 1..=40 {
        let v = eig(n, |i, j| if (i + 1) % n == j { 1.0 } else { 0.0 });
        assert_eq!(v.len(), n);
        for z in &v {
            assert!((z.norm() - 1.0).abs() < 1e-12, "n={n} {z}");
            // z^n = 1
            assert!((z.powu(n as u32) - 1.0).norm() < 1e-10, "n={n} {z}");
        }
    }
}

#[test]
fn zero_and_tiny_matrices() {
    assert!(eig(0, |_, _| 0.0).is_empty());
    assert_eq!(eig(1, |_, _| 2.5), vec![Complex64::new(2.5, 0.0)]);
    for n in 1..8 {
        assert!(eig(n, |_, _| 0.0).iter().all(|z| z.norm() == 0.0));
    }
    let v = eig(2, |i, j| [[0.0, -1.0], [1.0, 0.0]][i][j]);
    assert!((v[0] - Complex64::new(0.0, 1.0)).norm() < 1e-15);
}

#[test]
fn non_finite_input_is_an_error() {
    let mut ws = KernelWorkspace::new();
    ws.input(3)[4] = f64::NAN;
    assert!(matches!(
        ws.eigenvalues(),
        Err(SpectralError::NonFinite { row: 1, col: 1 })
    ));
}

#[test]
fn condition_number_of_normal_and_jordan() {
    let mut ws = KernelWorkspace::new();
    // Symmetric: kappa = 1.
    let a = ws.input(3);
    a.copy_from_slice(&[2.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 4.0]);
    let (re, _) = ws.eigenvalues().unwrap();
    let l = re[0];
    let k = ws.condition_number(Complex64::new(l, 0.0));
    assert!((k - 1.0).abs() < 1e-8, "{k}");
    // Nearly defective: large kappa.
    let a = ws.input(2);
    a.copy_from_slice(&[1.0, 0.0, 1.0, 1.0 + 1e-10]);
    ws.eigenvalues().unwrap();
    let k = ws.condition_number(Complex64::new(1.0, 0.0));
    assert!(k > 1e8, "{k}");
}

fn random_matrix(rng: &mut crate::rng::SplitMix64, n: usize) -> Vec<f64> {
    (0..n * n).map(|_| rng.uniform(-1.0, 1.0)).collect()
}

fn eig_of(ws: &mut KernelWorkspace, a: &[f64], n: usize) -> Vec<Complex64> {
    ws.input(n).copy_from_slice(a);
    let (re, im) = ws.eigenvalues().unwrap();
    let mut v: Vec<Complex64> = re
        .iter()
        .zip(im)
        .map(|(&r, &i)| Complex64::new(r, i))
        .collect();
    v.sort_by(super::super::eigen::spectral_order);
    v
}

/// The closed-form condition number of a 2 x 2 block equals the
/// inverse-iteration estimate (two independent methods), for real and complex
/// eigenvalues, including nearly defective blocks (large kappa), and a
/// multiple of the identity is left to inverse iteration.
#[test]
fn closed_form_2x2_condition_numbers_equal_inverse_iteration() {
    let mut rng = crate::rng::SplitMix64::new(11);
    let mut ws = KernelWorkspace::new();
    let (mut real, mut complex, mut large) = (0, 0, 0);
    for trial in 0..400 {
        let mut a = random_matrix(&mut rng, 2);
        if trial % 4 == 3 {
            // Nearly a Jordan block: [[l, 1], [t, l]] with tiny t.
            let t = 10f64.powi(-(2 + trial % 9));
            a = vec![0.3, t * (a[1].signum()), 1.0, 0.3 + 1e-3 * a[3]];
        }
        let values = eig_of(&mut ws, &a, 2);
        let tiny = f64::EPSILON * ws.hess_norm.max(f64::MIN_POSITIVE);
        for z in &values {
            let closed = kappa_2x2(&ws.hess[..4], *z, tiny).expect("not a multiple of I");
            let iterated = inverse_iteration_kappa::<Complex64, 1>(
                2,
                &ws.hess[..4],
                [*z],
                tiny,
                &mut LaneStorage::default(),
            )[0];
            assert!(
                (closed - iterated).abs() <= 1e-8 * iterated,
                "a = {a:?}, lambda = {z}: {closed} vs {iterated}"
            );
            if z.im == 0.0 {
                real += 1;
            } else {
                complex += 1;
            }
            if closed > 1e3 {
                large += 1;
            }
        }
    }
    assert!(
        real > 100 && complex > 100 && large > 20,
        "{real} {complex} {large}"
    );
    // A multiple of the identity: no closed form.
    assert_eq!(
        kappa_2x2(&[0.5, 0.0, 0.0, 0.5], Complex64::new(0.5, 0.0), 1e-16),
        None
    );
}

#[test]
fn real_and_complex_inverse_iteration_agree_for_real_eigenvalues() {
    // The real-arithmetic path for real lambda must give the condition
    // number the complex path gives for the same lambda.
    let mut rng = crate::rng::SplitMix64::new(5);
    let mut ws = KernelWorkspace::new();
    let mut checked = 0;
    for trial in 0..60 {
        let n = 2 + trial % 12;
        let a = random_matrix(&mut rng, n);
        let values = eig_of(&mut ws, &a, n);
        for z in values.iter().filter(|z| z.im == 0.0) {
            let real = ws.condition_number(*z);
            let tiny = f64::EPSILON * ws.hess_norm.max(f64::MIN_POSITIVE);
            let complex = inverse_iteration_kappa::<Complex64, 1>(
                n,
                &ws.hess[..n * n],
                [*z],
                tiny,
                &mut LaneStorage::default(),
            )[0];
            assert!(
                (real - complex).abs() <= 1e-10 * complex,
                "n = {n}, lambda = {z}: {real} vs {complex}"
            );
            assert!(real >= 1.0 && real.is_finite());
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn interleaved_condition_numbers_equal_lone_ones_bit_for_bit() {
    // Lanes share loops but not arithmetic: any mix of real and complex
    // eigenvalues, in groups of up to LANES, gives exactly the numbers of
    // one call per eigenvalue.
    let mut rng = crate::rng::SplitMix64::new(11);
    let mut ws = KernelWorkspace::new();
    let mut mixed = 0;
    for trial in 0..40 {
        let n = 2 + trial % 14;
        let a = random_matrix(&mut rng, n);
        let values = eig_of(&mut ws, &a, n);
        let lone: Vec<f64> = values.iter().map(|&z| ws.condition_number(z)).collect();
        let mut together = vec![0.0; values.len()];
        ws.condition_numbers(&values, &mut together);
        assert_eq!(lone, together, "n = {n}");
        let reals = values.iter().filter(|z| z.im == 0.0).count();
        if reals > 0 && reals < values.len() {
            mixed += 1;
        }
    }
    assert!(mixed > 10, "{mixed}");
}

/// Bit patterns of a workspace's last results: eigenvalues, sweeps,
/// Hessenberg form and its norm.
fn result_bits(w: &KernelWorkspace) -> Vec<u64> {
    let (re, im) = w.last_eigenvalues();
    let mut bits: Vec<u64> = re.iter().chain(im).map(|x| x.to_bits()).collect();
    bits.push(w.last_sweeps() as u64);
    bits.extend(w.hessenberg_form().iter().map(|x| x.to_bits()));
    bits.push(w.hess_norm.to_bits());
    bits
}

/// [`result_bits`] of a lone call on `a`, or `None` if it fails.
fn lone_bits(lone: &mut KernelWorkspace, a: &[f64], n: usize) -> Option<Vec<u64>> {
    lone.input(n).copy_from_slice(a);
    lone.eigenvalues().ok()?;
    Some(result_bits(lone))
}

/// Matrices that exercise every branch of the lock-step kernel.
fn lockstep_cases(rng: &mut crate::rng::SplitMix64, n: usize, trial: usize) -> Vec<f64> {
    let mut a = random_matrix(rng, n);
    match trial % 8 {
        // sparse: exact zeros, whole zero columns (Hessenberg steps skipped
        // in some lanes only), signed zeros
        0 => a.iter_mut().enumerate().for_each(|(i, x)| {
            if (i * 7 + trial) % 3 != 0 {
                *x = if i % 2 == 0 { 0.0 } else { -0.0 };
            }
        }),
        // cyclic permutation (exceptional shifts)
        1 => {
            a.iter_mut().for_each(|x| *x = 0.0);
            for j in 0..n {
                a[(j + 1) % n + j * n] = 1.0;
            }
        }
        // scaled out of the no-rescaling range of the reflectors
        2 => a.iter_mut().for_each(|x| *x *= 2f64.powi(520)),
        3 => a.iter_mut().for_each(|x| *x *= 2f64.powi(-520)),
        // the zero matrix
        4 => a.iter_mut().for_each(|x| *x = 0.0),
        // symmetric (real spectrum, many real deflations)
        5 => {
            for j in 0..n {
                for i in 0..j {
                    a[i + j * n] = a[j + i * n];
                }
            }
        }
        _ => {}
    }
    a
}

/// Runs `trials` batches (trial number, dimension) through the lock-step
/// kernel and compares every lane with a lone call, bit for bit; returns
/// the numbers of lanes compared and of lanes that failed (alone and in the
/// batch alike).
fn lockstep_against_lone(trials: impl Iterator<Item = (usize, usize)>) -> (usize, usize) {
    let mut rng = crate::rng::SplitMix64::new(77);
    let mut ws: Vec<KernelWorkspace> = (0..BATCH).map(|_| KernelWorkspace::new()).collect();
    let mut lone = KernelWorkspace::new();
    let (mut compared, mut failed) = (0, 0);
    for (trial, n) in trials {
        let mut inputs = Vec::new();
        for (lane, w) in ws.iter_mut().enumerate() {
            // mostly equal dimensions (the lock-step path), some unequal
            // (the one-at-a-time fallback)
            let m = if trial % 10 == 9 && lane == 2 {
                n + 1
            } else {
                n
            };
            let mut a = lockstep_cases(&mut rng, m, trial + lane * (trial % 3));
            if trial % 13 == 5 && lane == 1 {
                a[m * m - 1] = f64::NAN;
            }
            w.input(m).copy_from_slice(&a);
            inputs.push((a, m));
        }
        let lanes: &mut [KernelWorkspace; BATCH] = (&mut ws[..]).try_into().unwrap();
        let res = KernelWorkspace::eigenvalues_batch(lanes.each_mut());
        for ((w, r), (a, m)) in ws.iter().zip(res).zip(&inputs) {
            let want = lone_bits(&mut lone, a, *m);
            match (r, want) {
                (Ok(()), Some(want)) => {
                    assert_eq!(result_bits(w), want, "trial {trial}, n = {m}");
                    compared += 1;
                }
                (Err(e), None) => {
                    lone.input(*m).copy_from_slice(a);
                    assert_eq!(Some(e), lone.eigenvalues().err(), "trial {trial}");
                    failed += 1;
                }
                (r, w) => panic!("trial {trial}: batch {r:?}, lone ok = {}", w.is_some()),
            }
        }
    }
    (compared, failed)
}

#[test]
fn lockstep_batches_equal_lone_calls_bit_for_bit() {
    let (compared, failed) = lockstep_against_lone((0..160).map(|trial| (trial, 1 + trial % 24)));
    // Both branches ran: most lanes compared bit for bit; the failures
    // (the 12 NaN lanes, and overflow of the 2^520-scaled inputs, which
    // fails alone in the same way) matched the lone errors.
    assert_eq!(compared + failed, 160 * BATCH);
    assert!(
        compared > 2000 && failed > 12,
        "{compared} compared, {failed} failed"
    );
}

/// The lock-step sweeps at the dimensions of large valences (up to
/// `LOCKSTEP_MAX_DIM`), where the lanes' active blocks drift apart: the
/// unmasked updates (which write outside a lane's block) and the masked
/// ones both stay bit for bit those of lone calls.
#[test]
fn large_lockstep_batches_equal_lone_calls_bit_for_bit() {
    let dims = |trial: usize| 25 + (trial * 7) % (LOCKSTEP_MAX_DIM - 24);
    let (compared, failed) = lockstep_against_lone((0..48).map(|trial| (trial, dims(trial))));
    assert!((0..48).any(|t| dims(t) == LOCKSTEP_MAX_DIM));
    assert_eq!(compared + failed, 48 * BATCH);
    assert!(
        compared > 600 && failed > 3,
        "{compared} compared, {failed} failed"
    );
}

#[test]
fn extreme_scales_take_the_rescaled_reflector_path() {
    // Entries of modulus ~2^+-505 are outside [SAFE_MIN, SAFE_MAX], so the
    // QR sweeps rescale (p, q, r); at ~2^+-400 they are inside and do not.
    // Either way the spectrum must scale along (squares of the entries,
    // formed by the shifts, stay normal numbers).
    let mut rng = crate::rng::SplitMix64::new(9);
    let mut ws = KernelWorkspace::new();
    for trial in 0..40 {
        let n = 3 + trial % 15;
        let a = random_matrix(&mut rng, n);
        let base = eig_of(&mut ws, &a, n);
        for scale in [505, -505, 400, -400].map(|e| 2f64.powi(e)) {
            let b: Vec<f64> = a.iter().map(|x| x * scale).collect();
            let ev = eig_of(&mut ws, &b, n);
            assert_eq!(ev.len(), n);
            for v in &ev {
                let d = base
                    .iter()
                    .map(|u| (u - v / scale).norm())
                    .fold(f64::INFINITY, f64::min);
                assert!(d <= 1e-9, "n = {n}, scale {scale:e}: {v} ({d:e})");
            }
        }
    }
}

/// Largest distance from a kernel eigenvalue to the nearest faer eigenvalue
/// of the same matrix, and the trace defect.
fn versus_faer(ws: &mut KernelWorkspace, a: &nalgebra::DMatrix<f64>) -> (f64, f64) {
    use crate::spectral::eigen::{Eigen, EigenOptions};
    let n = a.nrows();
    let ours = eig_of(ws, a.as_slice(), n);
    let theirs = Eigen::new(a, EigenOptions::VALUES).unwrap();
    let d = ours
        .iter()
        .map(|z| {
            theirs
                .values()
                .iter()
                .map(|w| (z - w).norm())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let tr: Complex64 = ours.iter().sum();
    (d, (tr.re - a.trace()).abs() + tr.im.abs())
}

#[test]
fn adversarial_inputs_agree_with_faer() {
    use crate::knots::EdgeRatios;
    use crate::schemes::LocalScheme;
    use nalgebra::DMatrix;
    let mut ws = KernelWorkspace::new();
    let mut rng = crate::rng::SplitMix64::new(2024);
    // NURDS face blocks with extreme ratios (1e-6 and 1 - 1e-6 mixed in).
    for trial in 0..60 {
        let n = 3 + trial % 20;
        let r: Vec<f64> = (0..n)
            .map(|i| match (i + trial) % 3 {
                0 => 1e-6,
                1 => 1.0 - 1e-6,
                _ => rng.uniform(0.01, 0.99),
            })
            .collect();
        let a = LocalScheme::nurds(EdgeRatios::new(r).unwrap())
            .face_block()
            .unwrap();
        let (d, t) = versus_faer(&mut ws, &a);
        // Well separated except near-double roots: compare loosely, the
        // trace tightly.
        assert!(d < 1e-6, "n = {n}: {d:e}");
        assert!(t < 1e-12 * n as f64, "n = {n}: trace defect {t:e}");
    }
    // Defective: Jordan blocks J_k(1/2), also hidden by a similarity.
    for k in 2..=5usize {
        let j = DMatrix::from_fn(k, k, |i, c| {
            if i == c {
                0.5
            } else if c == i + 1 {
                1.0
            } else {
                0.0
            }
        });
        let q =
            DMatrix::from_fn(k, k, |_, _| rng.uniform(-1.0, 1.0)) + DMatrix::identity(k, k) * 3.0;
        let a = &q * &j * q.try_inverse().unwrap();
        for m in [j, a] {
            let v = eig_of(&mut ws, m.as_slice(), k);
            // A k-fold defective eigenvalue moves by ~ eps^(1/k).
            let tol = 100.0 * f64::EPSILON.powf(1.0 / k as f64);
            assert!(v.iter().all(|z| (z - 0.5).norm() < tol), "k = {k}: {v:?}");
            let (_, t) = versus_faer(&mut ws, &m);
            assert!(t < 1e-12, "k = {k}: trace defect {t:e}");
        }
    }
    // Graded (badly scaled by a diagonal similarity) and companion matrices.
    for n in 3..=16usize {
        let b = DMatrix::from_fn(n, n, |_, _| rng.uniform(-1.0, 1.0));
        let g = DMatrix::from_fn(n, n, |i, j| b[(i, j)] * 10f64.powi(i as i32 - j as i32));
        let (d, _) = versus_faer(&mut ws, &g);
        let scale = g.norm();
        assert!(d < 1e-6 * scale, "graded n = {n}: {d:e}");
        // Companion matrix of prod_k (x - k / n): eigenvalues k / n, k = 1..n
        // (Wilkinson-like, unbalanced: ill-conditioned beyond n ~ 10 for
        // any unbalanced QR, faer's included).
        if n > 10 {
            continue;
        }
        let mut c = vec![1.0f64];
        for k in 1..=n {
            let root = k as f64 / n as f64;
            let mut next = vec![0.0; c.len() + 1];
            for (i, &ci) in c.iter().enumerate() {
                next[i + 1] += ci;
                next[i] -= root * ci;
            }
            c = next;
        }
        let comp = DMatrix::from_fn(n, n, |i, j| {
            if j == n - 1 {
                -c[i]
            } else if i == j + 1 {
                1.0
            } else {
                0.0
            }
        });
        let v = eig_of(&mut ws, comp.as_slice(), n);
        let (d, _) = versus_faer(&mut ws, &comp);
        assert!(d < 1e-6, "companion n = {n}: {d:e}");
        if n <= 8 {
            for z in &v {
                let k = (z.re * n as f64).round();
                assert!(
                    (1.0..=n as f64).contains(&k) && (z - k / n as f64).norm() < 1e-6,
                    "companion n = {n}: {z}"
                );
            }
        }
    }
}
