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
//! `B` goes to the allocation-free eigenvalue kernel ([`KernelWorkspace`]). This path is for
//! face-block schemes ([`SpectralStructure::FaceBlock`]: the Doo-Sabin family),
//! which write their face block, or a matrix with the same deflated block, by
//! [`Scheme::fill_face_block`]; it is tested against the full `4n x 4n`
//! decomposition.
//!
//! [`SpectralStructure::FaceBlock`]: crate::schemes::SpectralStructure::FaceBlock

use super::eigen::spectral_order;
use super::kernel::{KernelWorkspace, BATCH};
use super::SpectralError;
use crate::schemes::{Scheme, SpectralStructure};
use num_complex::Complex64;

/// The eigenvalues of the E and C blocks, each of multiplicity `n`:
/// `1/4`, `1/8` (E blocks) and `1/16` (C block).
pub const KNOWN_EIGENVALUES: [f64; 3] = [0.25, 0.125, 0.0625];

/// Reusable storage for the structured path (no allocation once warmed up).
#[derive(Debug, Default, Clone)]
pub struct StructuredWorkspace {
    kernel: KernelWorkspace,
    f: Vec<f64>,
    /// Scratch of the deflation.
    wz: Vec<f64>,
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
    pub fn face_nonunit<S: Scheme + ?Sized>(
        &mut self,
        scheme: &S,
    ) -> Result<&[Complex64], SpectralError> {
        self.load(scheme)?;
        self.kernel.eigenvalues()?;
        self.collect();
        Ok(&self.face)
    }

    /// [`face_nonunit`](Self::face_nonunit) for [`BATCH`] schemes in as many
    /// workspaces at once, through [`KernelWorkspace::eigenvalues_batch`]
    /// (the QR iterations in lock step, one per SIMD lane): the results are
    /// bit for bit those of `face_nonunit` calls, at a higher throughput.
    /// Read them with [`face_nonunit_cached`](Self::face_nonunit_cached).
    ///
    /// ```
    /// use subdiv_lab::knots::EdgeRatios;
    /// use subdiv_lab::schemes::LocalScheme;
    /// use subdiv_lab::spectral::BATCH;
    /// use subdiv_lab::spectral::StructuredWorkspace;
    /// let schemes: Vec<LocalScheme<f64>> = (0..BATCH)
    ///     .map(|i| LocalScheme::nurds(EdgeRatios::new(vec![0.2, 0.7, 0.4, 0.9, 0.05 + 0.05 * i as f64]).unwrap()))
    ///     .collect();
    /// let mut ws: [StructuredWorkspace; BATCH] = Default::default();
    /// let res = StructuredWorkspace::face_nonunit_batch(ws.each_mut(), std::array::from_fn(|i| &schemes[i]));
    /// let mut single = StructuredWorkspace::new();
    /// for ((w, r), s) in ws.iter().zip(res).zip(&schemes) {
    ///     r.unwrap();
    ///     assert_eq!(w.face_nonunit_cached(), single.face_nonunit(s).unwrap());
    /// }
    /// ```
    pub fn face_nonunit_batch<S: Scheme + ?Sized>(
        ws: [&mut Self; BATCH],
        schemes: [&S; BATCH],
    ) -> [Result<(), SpectralError>; BATCH] {
        let mut ws = ws;
        let loaded: [Result<(), SpectralError>; BATCH] =
            std::array::from_fn(|l| ws[l].load(schemes[l]));
        let lanes: [Option<&mut KernelWorkspace>; BATCH] = {
            let mut i = 0;
            ws.each_mut().map(|w| {
                let ok = loaded[i].is_ok();
                i += 1;
                ok.then_some(&mut w.kernel)
            })
        };
        let run = KernelWorkspace::eigenvalues_lanes(lanes);
        let mut out = loaded;
        for ((o, r), w) in out.iter_mut().zip(run).zip(ws) {
            if let Some(r) = r {
                *o = r.map(|()| w.collect());
            }
        }
        out
    }

    /// Builds the deflated block `B` of `scheme` as the kernel's input.
    fn load<S: Scheme + ?Sized>(&mut self, scheme: &S) -> Result<(), SpectralError> {
        let n = scheme.valence();
        self.f.clear();
        self.f.resize(n * n, 0.0);
        match scheme.fill_face_block(&mut self.f) {
            Some(Ok(())) => {}
            Some(Err(e)) => {
                return Err(SpectralError::FaceBlock {
                    scheme: scheme.name().to_owned(),
                    reason: e.to_string(),
                })
            }
            None => {
                return Err(SpectralError::NotDooSabinFamily {
                    scheme: scheme.name().to_owned(),
                })
            }
        }
        let m = n - 1;
        let b = self.kernel.input(m);
        deflate_ones(n, &self.f, b, &mut self.wz);
        self.frobenius = b.iter().map(|x| x * x).sum::<f64>().sqrt();
        Ok(())
    }

    /// Sorts the kernel's eigenvalues into `face`.
    fn collect(&mut self) {
        let (re, im) = self.kernel.last_eigenvalues();
        self.face.clear();
        self.face
            .extend(re.iter().zip(im).map(|(&r, &i)| Complex64::new(r, i)));
        self.face.sort_by(spectral_order);
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

    /// [`condition_number`](Self::condition_number) of several eigenvalues at
    /// once ([`KernelWorkspace::condition_numbers`]: the inverse iterations
    /// run interleaved).
    pub fn condition_numbers(&mut self, lambdas: &[Complex64], out: &mut [f64]) {
        self.kernel.condition_numbers(lambdas, out)
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

    /// The face block the last load built (column major, `n x n`; see
    /// [`Scheme::fill_face_block`]), e.g. for a structural certificate.
    pub fn face_block(&self) -> &[f64] {
        &self.f
    }

    /// The deflated block `B` (column major), e.g. for a rank test.
    pub fn deflated_matrix(&self) -> &[f64] {
        self.kernel.matrix()
    }
}

/// Trailing `(n-1) x (n-1)` block of `H F H`, `H = I - beta v v^T`,
/// `v = 1 + sqrt(n) e_0` (so `H 1 = -sqrt(n) e_0`), for `F` with constant row
/// sums. With `w^T = v^T F` and `z = H F v`: `G_ij = F_ij - beta w_j - beta z_i`
/// for `i, j >= 1`. `wz` is scratch storage (resized to `2n`).
fn deflate_ones(n: usize, f: &[f64], b: &mut [f64], wz: &mut Vec<f64>) {
    let sq = (n as f64).sqrt();
    let beta = 1.0 / (n as f64 + sq);
    let m = n - 1;
    wz.clear();
    wz.resize(2 * n, 0.0);
    let (w, z) = wz.split_at_mut(n);
    // w_j = sum_i v_i F_ij
    let mut wv = 0.0;
    for (j, wj) in w.iter_mut().enumerate() {
        let col = &f[j * n..(j + 1) * n];
        let mut s = sq * col[0];
        for x in col {
            s += x;
        }
        *wj = s;
        let v_j = if j == 0 { 1.0 + sq } else { 1.0 };
        wv += s * v_j;
    }
    // z_i = rowsum_i + sqrt(n) F_i0 - beta (w . v)
    for (i, zi) in z.iter_mut().enumerate().skip(1) {
        let mut rs = sq * f[i];
        for j in 0..n {
            rs += f[i + j * n];
        }
        *zi = rs - beta * wv;
    }
    for j in 1..n {
        let bw = beta * w[j];
        let col = &f[j * n + 1..(j + 1) * n];
        let out = &mut b[(j - 1) * m..j * m];
        for ((o, x), zi) in out.iter_mut().zip(col).zip(&z[1..]) {
            *o = (x - bw) - beta * zi;
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
pub fn structured_spectrum<S: Scheme + ?Sized>(
    scheme: &S,
) -> Result<Vec<Complex64>, SpectralError> {
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

/// The whole spectrum of `S` by the scheme's structure: [`structured_spectrum`]
/// for a scheme with a face block ([`SpectralStructure::FaceBlock`]), else the
/// scheme's own [`Scheme::structured_spectrum`]; `None` when it has neither.
pub fn spectrum_of<S: Scheme + ?Sized>(
    scheme: &S,
) -> Option<Result<Vec<Complex64>, SpectralError>> {
    if scheme.spectral_structure() == SpectralStructure::FaceBlock {
        Some(structured_spectrum(scheme))
    } else {
        scheme
            .structured_spectrum()
            .map(|r| r.map_err(SpectralError::from))
    }
}
