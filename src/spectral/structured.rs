//! Structured spectrum of the Doo-Sabin family (math doc section 4, **\[derived\]**).
//!
//! `S_n` is block lower-triangular (P block `n x n`; E block = `n` decoupled
//! 2x2 blocks `[[ (1+r)/8, (1-r)/8 ], [ r/8, (2-r)/8 ]]` with trace 3/8 and
//! determinant 1/32, hence eigenvalues 1/4 and 1/8; C block = `I/16`), so
//!
//! ```text
//! spec(S_n) = spec(A) U {1/4, 1/8} (each n times) U {1/16} (n times).
//! ```
//!
//! The face block `A` has row sums 1 (`A 1 = 1`), so the eigenvalue 1 is
//! deflated exactly with the Householder reflection `H` that maps `1` to a
//! multiple of `e_0`: the trailing `(n-1) x (n-1)` block `B` of `H A H` has
//! `spec(B) = spec(A) \ {1}`. For NURDS and the Catmull-Clark variant,
//! `A = M + 1 c^T / 4` with `M = (I + R)/4`, and `H 1 c^T H` only touches row 0,
//! so `B` is the trailing block of `H M H` **\[derived\]**: the face weights `c`
//! are not needed for the spectrum at all (no closed form, no linear solve).
//!
//! `B` goes to the allocation-free [`kernel`](super::kernel). This path is for
//! the Doo-Sabin family only ([`SchemeKind::is_doo_sabin_family`]); it is
//! tested against the full `4n x 4n` decomposition.
//!
//! [`SchemeKind::is_doo_sabin_family`]: crate::schemes::SchemeKind::is_doo_sabin_family

use super::eigen::spectral_order;
use super::kernel::KernelWorkspace;
use super::SpectralError;
use crate::schemes::LocalScheme;
use num_complex::Complex64;

/// The eigenvalues of the E and C blocks, each of multiplicity `n`:
/// `1/4`, `1/8` (E blocks) and `1/16` (C block).
pub const KNOWN_EIGENVALUES: [f64; 3] = [0.25, 0.125, 0.0625];

/// Reusable storage for the structured path (no allocation once warmed up).
#[derive(Debug, Default, Clone)]
pub struct StructuredWorkspace {
    kernel: KernelWorkspace,
    f: Vec<f64>,
    face: Vec<Complex64>,
    frobenius: f64,
}

impl StructuredWorkspace {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    /// The non-unit eigenvalues of the face block `A` (the `n - 1` eigenvalues
    /// of the deflated block `B`), sorted by non-increasing modulus.
    pub fn face_nonunit(
        &mut self,
        scheme: &LocalScheme<f64>,
    ) -> Result<&[Complex64], SpectralError> {
        let n = scheme.valence();
        if !scheme.kind().is_doo_sabin_family() {
            return Err(SpectralError::NotDooSabinFamily {
                scheme: scheme.kind().name(),
            });
        }
        self.f.clear();
        self.f.resize(n * n, 0.0);
        fill_face_like(scheme, n, &mut self.f)?;
        let m = n - 1;
        let b = self.kernel.input(m);
        deflate_ones(n, &self.f, b);
        self.frobenius = b.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (re, im) = self.kernel.eigenvalues()?;
        self.face.clear();
        self.face
            .extend(re.iter().zip(im).map(|(&r, &i)| Complex64::new(r, i)));
        self.face.sort_by(spectral_order);
        Ok(&self.face)
    }

    /// The result of the last [`face_nonunit`](Self::face_nonunit) call.
    pub fn face_nonunit_cached(&self) -> &[Complex64] {
        &self.face
    }

    /// Condition number of an eigenvalue of the deflated block `B` last
    /// computed by [`face_nonunit`](Self::face_nonunit) (`O(n^2)`).
    pub fn condition_number(&mut self, lambda: Complex64) -> f64 {
        self.kernel.condition_number(lambda)
    }

    /// QR sweeps of the last kernel call (diagnostics).
    pub fn last_sweeps(&self) -> usize {
        self.kernel.last_sweeps()
    }

    /// Frobenius norm of the deflated block `B` last computed.
    pub fn frobenius_norm(&self) -> f64 {
        self.frobenius
    }

    /// Dimension of the deflated block `B` (`n - 1`).
    pub fn deflated_dim(&self) -> usize {
        self.kernel.dim()
    }

    /// The deflated block `B` (column major), e.g. for a rank test.
    pub fn deflated_matrix(&self) -> &[f64] {
        self.kernel.matrix()
    }
}

/// Fills `f` (column major, `n x n`) with a matrix whose deflated block is `B`:
/// `M = (I + R)/4` for NURDS and the CC variant, the face block for original Doo-Sabin.
fn fill_face_like(scheme: &LocalScheme<f64>, n: usize, f: &mut [f64]) -> Result<(), SpectralError> {
    match scheme {
        LocalScheme::DooSabin { .. } => {
            let den = 4.0 * n as f64;
            for j in 0..n {
                for i in 0..n {
                    f[i + j * n] = if i == j {
                        (n as f64 + 5.0) / den
                    } else {
                        let k = (i + n - j) % n;
                        (3.0 + 2.0 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos()) / den
                    };
                }
            }
        }
        LocalScheme::Nurds(ratios) => fill_m(n, ratios.as_slice(), ratios.complement(), f),
        LocalScheme::CcVariant { .. } => {
            // Uniform ratios 1/2 (no allocation): diagonal 1/2, neighbours 1/8.
            for i in 0..n {
                let prev = (i + n - 1) % n;
                let next = (i + 1) % n;
                f[i + i * n] = 0.25 * 2.0;
                f[i + prev * n] += 0.125;
                f[i + next * n] += 0.125;
            }
        }
        #[allow(unreachable_patterns)]
        _ => {
            return Err(SpectralError::NotDooSabinFamily {
                scheme: scheme.kind().name(),
            })
        }
    }
    Ok(())
}

/// `M = (I + R)/4`: diagonal `(1 + s_{i-1} + r_i)/4`, sub `r_{i-1}/4`, super `s_i/4`.
fn fill_m(n: usize, r: &[f64], s: &[f64], f: &mut [f64]) {
    for i in 0..n {
        let prev = (i + n - 1) % n;
        let next = (i + 1) % n;
        f[i + i * n] = 0.25 * (1.0 + s[prev] + r[i]);
        f[i + prev * n] += 0.25 * r[prev];
        f[i + next * n] += 0.25 * s[i];
    }
}

/// Trailing `(n-1) x (n-1)` block of `H F H`, `H = I - beta v v^T`,
/// `v = 1 + sqrt(n) e_0` (so `H 1 = -sqrt(n) e_0`), for `F` with constant row
/// sums. With `w^T = v^T F` and `z = H F v`: `G_ij = F_ij - beta w_j - beta z_i`
/// for `i, j >= 1`.
fn deflate_ones(n: usize, f: &[f64], b: &mut [f64]) {
    let sq = (n as f64).sqrt();
    let beta = 1.0 / (n as f64 + sq);
    let m = n - 1;
    // w_j = sum_i v_i F_ij
    let mut wv = 0.0;
    let w = |j: usize| -> f64 {
        let mut s = sq * f[j * n];
        for i in 0..n {
            s += f[i + j * n];
        }
        s
    };
    // w_j is recomputed in the second loop (O(n^2) either way, no allocation).
    for j in 0..n {
        let v_j = if j == 0 { 1.0 + sq } else { 1.0 };
        wv += w(j) * v_j;
    }
    for j in 1..n {
        let wj = w(j);
        for i in 1..n {
            b[(i - 1) + (j - 1) * m] = f[i + j * n] - beta * wj;
        }
    }
    for i in 1..n {
        // z_i = rowsum_i + sqrt(n) F_i0 - beta (w . v)
        let mut rs = sq * f[i];
        for j in 0..n {
            rs += f[i + j * n];
        }
        let z = rs - beta * wv;
        for j in 1..n {
            b[(i - 1) + (j - 1) * m] -= beta * z;
        }
    }
}

/// The full `4n` spectrum of a Doo-Sabin-family scheme by the structured path,
/// sorted by non-increasing modulus (math doc section 4).
///
/// ```
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::LocalScheme;
/// use subdiv_lab::spectral::structured::structured_spectrum;
/// let s = LocalScheme::nurds(EdgeRatios::<f64>::uniform(4).unwrap());
/// let ev = structured_spectrum(&s).unwrap();
/// assert_eq!(ev.len(), 16);
/// assert!((ev[0].re - 1.0).abs() < 1e-15 && (ev[1].re - 0.5).abs() < 1e-15);
/// ```
pub fn structured_spectrum(scheme: &LocalScheme<f64>) -> Result<Vec<Complex64>, SpectralError> {
    let mut ws = StructuredWorkspace::new();
    let n = scheme.valence();
    let face = ws.face_nonunit(scheme)?;
    let mut all = Vec::with_capacity(4 * n);
    all.push(Complex64::new(1.0, 0.0));
    all.extend_from_slice(face);
    for v in KNOWN_EIGENVALUES {
        all.extend(std::iter::repeat_n(Complex64::new(v, 0.0), n));
    }
    all.sort_by(spectral_order);
    Ok(all)
}
