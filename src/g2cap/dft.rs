//! The constrained least squares of the cap solved block by block after a
//! discrete Fourier transform over the patch index (math doc section 14.5):
//! the paper's method, here an independent second path next to the dense
//! solve of [`super::solve::solve`].
//!
//! The conditions across edge `i` involve patches `i` and `i + 1` only, with
//! the same coefficients for every `i`; the energy is the same quadratic form
//! on every patch. Writing `x_i` for the `25` free points of patch `i`
//! (one column per coordinate):
//!
//! ```text
//! minimise  sum_i |L x_i - l_i|^2   subject to   A x_i + B x_(i+1) = r_i  (i mod n)
//! ```
//!
//! With `X_w = sum_i x_i z^(-w i)`, `z = exp(2 pi sqrt(-1) / n)`, and the
//! same transform of `r_i` and `l_i`, the constraints become `(A + z^w B)
//! X_w = R_w` and the energy `(1 / n) sum_w |L X_w - L_w|^2` (Parseval), so
//! the problem splits into `n` independent complex problems with `25`
//! unknowns each: the block-circulant system made block diagonal. Each is
//! solved like the dense one (SVD of `A + z^w B`, particular solution plus
//! null space, energy least squares, refinement); then `x_i = (1 / n) sum_w
//! X_w z^(w i)`. The singular values of the dense constraint matrix are those
//! of the `n` blocks together (the transform is unitary up to the factor
//! `sqrt(n)`), so the rank threshold, relative to the largest over all
//! blocks, takes the same decisions as the dense path.

use super::bernstein::Net;
use super::solve::{
    add_edge_conditions, add_patch_energy_rows, Solved, System, FREE, RANK_RTOL, REFINEMENT_STEPS,
};
use super::G2CapError;
use nalgebra::DMatrix;
use num_complex::Complex64;

type CMat = DMatrix<Complex64>;

/// Free points per patch.
const PER: usize = FREE * FREE;

/// The per-patch blocks: the coefficients on patch `i` (`a`) and on patch
/// `i + 1` (`b`) of the rows of edge `i`, and the right-hand side of every
/// edge (`rhs[i]`, rows x 3).
struct EdgeBlocks {
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    rhs: Vec<DMatrix<f64>>,
}

/// Splits a system whose rows touch the patches `first` and `second` into
/// the two blocks and the right-hand side.
fn blocks_of(sys: &System, first: usize, second: Option<usize>) -> EdgeBlocks {
    let rows = sys.coef.len();
    let mut a = DMatrix::zeros(rows, PER);
    let mut b = DMatrix::zeros(rows, PER);
    let mut r = DMatrix::zeros(rows, 3);
    for (q, (c, rh)) in sys.coef.iter().zip(&sys.rhs).enumerate() {
        for &(col, w) in c {
            let (patch, local) = (col / PER, col % PER);
            if patch == first {
                a[(q, local)] += w;
            } else if Some(patch) == second {
                b[(q, local)] += w;
            }
        }
        for x in 0..3 {
            r[(q, x)] = rh[x];
        }
    }
    EdgeBlocks { a, b, rhs: vec![r] }
}

fn edge_blocks(fixed: &[Net]) -> EdgeBlocks {
    let n = fixed.len();
    let mut out: Option<EdgeBlocks> = None;
    for i in 0..n {
        let mut sys = System::new(fixed);
        add_edge_conditions(&mut sys, i);
        let bl = blocks_of(&sys, i, Some((i + 1) % n));
        match &mut out {
            None => out = Some(bl),
            Some(o) => o.rhs.extend(bl.rhs),
        }
    }
    out.expect("n >= 3 edges")
}

fn energy_blocks(fixed: &[Net]) -> EdgeBlocks {
    let mut out: Option<EdgeBlocks> = None;
    for p in 0..fixed.len() {
        let mut sys = System::new(fixed);
        add_patch_energy_rows(&mut sys, p);
        let bl = blocks_of(&sys, p, None);
        match &mut out {
            None => out = Some(bl),
            Some(o) => o.rhs.extend(bl.rhs),
        }
    }
    out.expect("n >= 3 patches")
}

fn complex(m: &DMatrix<f64>) -> CMat {
    m.map(|x| Complex64::new(x, 0.0))
}

/// `sum_i m_i exp(sign 2 pi sqrt(-1) w i / n)`.
fn transform(ms: &[DMatrix<f64>], w: usize, sign: f64) -> CMat {
    let n = ms.len();
    let mut out = CMat::zeros(ms[0].nrows(), ms[0].ncols());
    for (i, m) in ms.iter().enumerate() {
        let t = sign * 2.0 * std::f64::consts::PI * ((w * i) % n) as f64 / n as f64;
        let z = Complex64::new(t.cos(), t.sin());
        out += complex(m) * z;
    }
    out
}

/// The pseudo-inverse of a block applied to `rhs`, over the singular values
/// above `tol`.
fn pinv_apply(
    svd: &nalgebra::SVD<Complex64, nalgebra::Dyn, nalgebra::Dyn>,
    rhs: &CMat,
    tol: f64,
) -> CMat {
    let (u, vt) = (svd.u.as_ref(), svd.v_t.as_ref());
    let (Some(u), Some(vt)) = (u, vt) else {
        return CMat::zeros(PER, rhs.ncols());
    };
    let mut x = CMat::zeros(vt.ncols(), rhs.ncols());
    for (q, &s) in svd.singular_values.iter().enumerate() {
        if s > tol {
            let coeff = u.column(q).adjoint() * rhs / Complex64::new(s, 0.0);
            x += vt.row(q).adjoint() * coeff;
        }
    }
    x
}

/// The DFT solve: the same problem as [`super::solve::solve`], the same
/// result up to rounding (cross-checked in the tests), `n` SVDs of
/// `rows x 25` complex blocks instead of one of `n rows x 25 n`.
/// `Solved::constraint_residual` and `energy` are measured on the real
/// control points after the inverse transform.
pub fn solve_dft(fixed: &[Net]) -> Result<Solved, G2CapError> {
    let n = fixed.len();
    let cons = edge_blocks(fixed);
    let en = energy_blocks(fixed);
    let lc = complex(&en.a);
    let mut svds = Vec::with_capacity(n);
    let mut smax: f64 = 0.0;
    for w in 0..n {
        let t = 2.0 * std::f64::consts::PI * w as f64 / n as f64;
        let m = complex(&cons.a) + complex(&cons.b) * Complex64::new(t.cos(), t.sin());
        let svd = m.clone().svd(true, true);
        if svd.u.is_none() || svd.v_t.is_none() {
            return Err(G2CapError::Numerical("SVD of a Fourier block"));
        }
        smax = smax.max(svd.singular_values.max());
        svds.push((m, svd));
    }
    let tol = RANK_RTOL * smax;
    let (mut rank, mut freedom) = (0, 0);
    let mut smin = f64::INFINITY;
    let (mut emax, mut emin) = (0.0f64, f64::INFINITY);
    let mut modes = Vec::with_capacity(n);
    for (w, (m, svd)) in svds.iter().enumerate() {
        let r = transform(&cons.rhs, w, -1.0);
        let l = transform(&en.rhs, w, -1.0);
        let xp = pinv_apply(svd, &r, tol);
        let vt = svd.v_t.as_ref().expect("checked above");
        let mut null = Vec::new();
        for q in 0..vt.nrows() {
            let s = svd.singular_values.get(q).copied().unwrap_or(0.0);
            if s > tol {
                rank += 1;
                smin = smin.min(s);
            } else {
                null.push(q);
            }
        }
        freedom += null.len();
        let mut basis = CMat::zeros(PER, null.len());
        for (c, &q) in null.iter().enumerate() {
            basis.set_column(c, &vt.row(q).adjoint());
        }
        let mut x = if null.is_empty() {
            xp
        } else {
            let target = &l - &lc * &xp;
            let esvd = (&lc * &basis).svd(true, true);
            emax = emax.max(esvd.singular_values.max());
            emin = emin.min(esvd.singular_values.min());
            let y = esvd
                .solve(&target, 1e-14)
                .map_err(|_| G2CapError::Numerical("least squares of a Fourier block"))?;
            xp + basis * y
        };
        for _ in 0..REFINEMENT_STEPS {
            let res = &r - m * &x;
            x += pinv_apply(svd, &res, tol);
        }
        modes.push(x);
    }
    // Inverse transform, real part (the imaginary part is rounding: the
    // data are real, so X_(n - w) = conj(X_w)).
    let mut xs = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = CMat::zeros(PER, 3);
        for (w, m) in modes.iter().enumerate() {
            let t = 2.0 * std::f64::consts::PI * ((w * i) % n) as f64 / n as f64;
            x += m * Complex64::new(t.cos(), t.sin());
        }
        xs.push(x.map(|z| z.re / n as f64));
    }
    let mut constraint_residual: f64 = 0.0;
    for i in 0..n {
        let res = &cons.a * &xs[i] + &cons.b * &xs[(i + 1) % n] - &cons.rhs[i];
        constraint_residual = constraint_residual.max(res.amax());
    }
    let mut energy = 0.0;
    for (x, l) in xs.iter().zip(&en.rhs) {
        energy += (&en.a * x - l).iter().map(|e| e * e).sum::<f64>();
    }
    let mut nets: Vec<Net> = fixed.to_vec();
    for (net, x) in nets.iter_mut().zip(&xs) {
        for j in 0..FREE {
            for k in 0..FREE {
                for c in 0..3 {
                    net[j][k][c] = x[(j * FREE + k, c)];
                }
            }
        }
    }
    Ok(Solved {
        nets,
        energy,
        constraint_residual,
        rank,
        freedom,
        condition: smax / smin,
        energy_condition: emax / emin,
    })
}
