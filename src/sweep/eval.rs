//! Per-configuration evaluation: the result columns and the one place where a
//! sweep calls the spectral engine.
//!
//! Result columns, by `[columns]` switch (math doc sections 5-7):
//!
//! | switch | columns |
//! |---|---|
//! | `classification` | `class`, `lambda1_re`, `lambda1_im`, `lambda2_re`, `lambda2_im`, `abs_lambda3` |
//! | `gap` | `gap` = `|lambda2| - |lambda3|`; `ratio` = `lambda2 / lambda1` when both are real; `rho` = `|lambda1|` and `theta` = `|arg lambda1|` (radians, in (0, pi)) for a complex pair (empty otherwise) |
//! | `contraction` | `contraction_rate` = `|lambda1|`, the asymptotic per-step contraction of the face towards its limit point (math doc section 5; <= 3/4) |
//! | `eigenvalues = K` | `ev0_re, ev0_im, .., ev{K-1}_re, ev{K-1}_im`: the K leading eigenvalues of `S_n` by non-increasing modulus (empty beyond `4n`; for the Catmull-Clark family those of the `(2n+1)` one-ring matrix from the Fourier blocks, empty beyond `2n + 1`) |
//! | `charmap` | `charmap_verdict` (`c1`, `tpc_real_distinct`, `tpc_complex_pair`, `not_regular`, `not_injective`, `indeterminate`, `no_charmap`; see [`crate::charmap::Verdict`]), `charmap_min_jacobian` (smallest Bezier coefficient of the ring's Jacobian relative to the largest; > 0 certifies regularity), `charmap_winding` (winding number of the ring boundary around the origin) |
//! | `curvature` | `curvature_mu` (`mu`, the largest modulus after the subdominant pair), `curvature_ratio` (`mu / lambda^2`), `curvature_verdict` (`zero`, `bounded`, `unbounded`, `indeterminate`, `not_applicable`; [`crate::curvature`], math doc section 13; from the dense decomposition of the local matrix, with the exact certificate where the float comparison is undecided) |
//! | `exact_certificate` | `exact_class`: the classification decided exactly over the rationals from the exact value of the `f64` parameters (`undecided` when the exact method cannot decide); `exact_agrees` = 1 / 0 when both verdicts are decided and agree / disagree (empty otherwise) |
//!
//! `lambda0 = 1` is the dominant eigenvalue; `lambda1, lambda2` the subdominant
//! pair, `lambda3` the next one. The class is one of `standard`, `real_distinct`,
//! `complex_pair`, `defective`, `not_separated` (math doc section 7), or
//! `indeterminate:A/B` naming the two classes the floating-point evidence could
//! not separate. Classification uses the spectral engine's structured fast path
//! ([`crate::spectral::classify_scheme`]: face block plus the known eigenvalues
//! 1/4, 1/8, 1/16), with its documented tolerances.

use super::plan::{Configuration, Plan};
use super::spec::Columns;
use crate::charmap;
use crate::scheme::{Scheme, SpectralStructure};
use crate::schemes::LocalScheme;
use crate::spectral::kernel::BATCH;
use crate::spectral::structured::StructuredWorkspace;
use crate::spectral::{self, Subdominant, SubdominantClass};
use num_complex::Complex64;
use std::cell::RefCell;

/// One CSV cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// No value.
    Empty,
    /// A number.
    Num(f64),
    /// Text.
    Text(String),
}

/// A result column.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ResultColumn {
    /// CSV header name.
    pub name: String,
    /// Numeric (enters the summary's extremes) or text.
    pub numeric: bool,
}

/// The result columns of `columns`, in CSV order.
pub fn result_columns(columns: &Columns) -> Vec<ResultColumn> {
    let num = |n: &str| ResultColumn {
        name: n.to_owned(),
        numeric: true,
    };
    let text = |n: &str| ResultColumn {
        name: n.to_owned(),
        numeric: false,
    };
    let mut v = Vec::new();
    if columns.classification {
        v.push(text("class"));
        for n in [
            "lambda1_re",
            "lambda1_im",
            "lambda2_re",
            "lambda2_im",
            "abs_lambda3",
        ] {
            v.push(num(n));
        }
    }
    if columns.gap {
        for n in ["gap", "ratio", "rho", "theta"] {
            v.push(num(n));
        }
    }
    if columns.contraction {
        v.push(num("contraction_rate"));
    }
    for k in 0..columns.eigenvalues {
        v.push(num(&format!("ev{k}_re")));
        v.push(num(&format!("ev{k}_im")));
    }
    if columns.charmap {
        v.push(text("charmap_verdict"));
        v.push(num("charmap_min_jacobian"));
        v.push(num("charmap_winding"));
    }
    if columns.curvature {
        v.push(num("curvature_mu"));
        v.push(num("curvature_ratio"));
        v.push(text("curvature_verdict"));
    }
    if columns.exact_certificate {
        v.push(text("exact_class"));
        v.push(num("exact_agrees"));
    }
    v
}

/// Receives the result cells of one configuration, in column order (see
/// [`Evaluate::write_results`]). The sweep driver implements it with a reusable
/// staging buffer, so a row costs no allocation; `Vec<Cell>` implements it too.
pub trait CellSink {
    /// An empty cell.
    fn empty(&mut self);
    /// A number.
    fn num(&mut self, x: f64);
    /// Text.
    fn text(&mut self, t: &str);
    /// The cell `c`.
    fn cell(&mut self, c: &Cell) {
        match c {
            Cell::Empty => self.empty(),
            Cell::Num(x) => self.num(*x),
            Cell::Text(t) => self.text(t),
        }
    }
}

impl CellSink for Vec<Cell> {
    fn empty(&mut self) {
        self.push(Cell::Empty);
    }
    fn num(&mut self, x: f64) {
        self.push(Cell::Num(x));
    }
    fn text(&mut self, t: &str) {
        self.push(Cell::Text(t.to_owned()));
    }
}

/// Evaluates one configuration into its result cells (one per
/// [`result_columns`] entry, in order). Implementations must be deterministic:
/// the same configuration gives the same cells on any thread.
pub trait Evaluate: Sync {
    /// The result cells of configuration `c` (whose scheme is `scheme`).
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
    ) -> crate::Result<Vec<Cell>>;

    /// Writes the result cells of `c` to `out`, in order; the cells must equal
    /// those of [`evaluate`](Self::evaluate). On an error the cells already
    /// written are discarded by the caller. The default calls `evaluate`; an
    /// evaluator overrides it to avoid building a `Vec<Cell>` per configuration
    /// (the sweep driver calls this method).
    fn write_results(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
        out: &mut dyn CellSink,
    ) -> crate::Result<()> {
        for cell in &self.evaluate(plan, c, scheme)? {
            out.cell(cell);
        }
        Ok(())
    }

    /// [`write_results`](Self::write_results) for [`BATCH`] configurations at
    /// once (the sweep driver evaluates consecutive configurations in
    /// batches); the cells must equal those of `write_results` calls. The
    /// default makes those calls; the spectral evaluator overrides it to run
    /// the QR iterations in lock step ([`spectral::classify_schemes_batch`]).
    fn write_results_batch(
        &self,
        plan: &Plan,
        items: [(&Configuration, &LocalScheme<f64>, &mut dyn CellSink); BATCH],
    ) -> [crate::Result<()>; BATCH] {
        items.map(|(c, s, out)| self.write_results(plan, c, s, out))
    }
}

/// The evaluator of the `sweep` command: the project's spectral engine.
#[derive(Clone, Debug)]
pub struct SpectralEvaluator {
    columns: Columns,
}

impl SpectralEvaluator {
    /// An evaluator computing `columns`.
    pub fn new(columns: Columns) -> Self {
        SpectralEvaluator { columns }
    }
}

/// Per-thread storage of the spectral evaluator: the structured workspace (so
/// the `eigenvalues` columns reuse the face spectrum the classification
/// computed) and the spectrum buffer.
#[derive(Default)]
struct Scratch {
    ws: StructuredWorkspace,
    spectrum: Vec<Complex64>,
}

thread_local! {
    /// One scratch per configuration of a batch.
    static SCRATCH: RefCell<[Scratch; BATCH]> = RefCell::new(Default::default());
}

/// The full spectrum of `S_n` from the face spectrum in `ws`, in the order of
/// [`structured_spectrum`](spectral::structured::structured_spectrum) (the same
/// construction: `1`, the non-unit face eigenvalues, then
/// [`KNOWN_EIGENVALUES`](spectral::structured::KNOWN_EIGENVALUES) `n` times
/// each, sorted by [`spectral_order`](spectral::eigen::spectral_order); a
/// test checks the two agree bit for bit).
fn full_spectrum(n: usize, face: &[Complex64], all: &mut Vec<Complex64>) {
    all.clear();
    all.push(Complex64::new(1.0, 0.0));
    all.extend_from_slice(face);
    for v in spectral::structured::KNOWN_EIGENVALUES {
        all.extend(std::iter::repeat_n(Complex64::new(v, 0.0), n));
    }
    all.sort_by(spectral::eigen::spectral_order);
}

impl Evaluate for SpectralEvaluator {
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
    ) -> crate::Result<Vec<Cell>> {
        let mut out = Vec::with_capacity(16 + 2 * self.columns.eigenvalues);
        self.write_results(plan, c, scheme, &mut out)?;
        Ok(out)
    }

    fn write_results(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
        out: &mut dyn CellSink,
    ) -> crate::Result<()> {
        SCRATCH.with(|cell| {
            let mut guard = cell.borrow_mut();
            let scratch = &mut guard[0];
            let sub = self.subdominant(scratch, scheme)?;
            self.write_with(scratch, plan, c, scheme, sub, out)
        })
    }

    fn write_results_batch(
        &self,
        plan: &Plan,
        items: [(&Configuration, &LocalScheme<f64>, &mut dyn CellSink); BATCH],
    ) -> [crate::Result<()>; BATCH] {
        SCRATCH.with(|cell| {
            let mut guard = cell.borrow_mut();
            let scratch = &mut *guard;
            let schemes = items.each_ref().map(|(_, s, _)| *s);
            let subs: [crate::Result<Option<Subdominant>>; BATCH] =
                if self.needs_subdominant() && schemes.iter().all(|s| face_block(s)) {
                    spectral::classify_schemes_batch(scratch.each_mut().map(|w| &mut w.ws), schemes)
                        .map(|r| r.map(Some))
                } else {
                    std::array::from_fn(|l| self.subdominant(&mut scratch[l], schemes[l]))
                };
            let mut lanes = scratch.iter_mut().zip(subs);
            items.map(|(c, s, out)| {
                let (w, sub) = lanes.next().expect("one scratch per lane");
                sub.and_then(|sub| self.write_with(w, plan, c, s, sub, out))
            })
        })
    }
}

impl SpectralEvaluator {
    /// Whether any requested column needs the subdominant classification.
    fn needs_subdominant(&self) -> bool {
        let cols = &self.columns;
        cols.classification
            || cols.gap
            || cols.contraction
            || cols.exact_certificate
            || cols.charmap
    }

    /// The classification of `scheme` if a column needs it. Face-block
    /// schemes ([`SpectralStructure::FaceBlock`]: the Doo-Sabin family) go
    /// through the structured path with the per-thread workspace; anything
    /// else through the scheme's fast path or the dense classifier.
    fn subdominant(
        &self,
        scratch: &mut Scratch,
        scheme: &LocalScheme<f64>,
    ) -> crate::Result<Option<Subdominant>> {
        if !self.needs_subdominant() {
            Ok(None)
        } else if face_block(scheme) {
            Ok(Some(spectral::classify_scheme_with(
                &mut scratch.ws,
                scheme,
            )?))
        } else {
            Ok(Some(match scheme.fast_classification() {
                Some(fast) => fast?,
                None => spectral::classify_matrix(scheme.local_matrix()?.matrix())?,
            }))
        }
    }

    /// Writes the cells of `c` given its classification `sub` (from
    /// [`subdominant`](Self::subdominant) or a paired classification; for the
    /// Doo-Sabin family `scratch.ws` holds the face spectrum it computed).
    fn write_with(
        &self,
        scratch: &mut Scratch,
        plan: &Plan,
        c: &Configuration,
        scheme: &LocalScheme<f64>,
        sub: Option<Subdominant>,
        out: &mut dyn CellSink,
    ) -> crate::Result<()> {
        let cols = &self.columns;
        let structured = face_block(scheme);
        if let Some(sub) = &sub {
            if cols.classification {
                match &sub.class {
                    SubdominantClass::Indeterminate { .. } => out.text(&class_text(&sub.class)),
                    other => out.text(other.name()),
                }
                for x in [
                    sub.lambda1.re,
                    sub.lambda1.im,
                    sub.lambda2.re,
                    sub.lambda2.im,
                    sub.abs_lambda3,
                ] {
                    out.num(x);
                }
            }
            if cols.gap {
                out.num(sub.gap);
                for x in [sub.ratio, sub.rho, sub.theta] {
                    match x {
                        Some(x) => out.num(x),
                        None => out.empty(),
                    }
                }
            }
            if cols.contraction {
                out.num(sub.lambda1.norm());
            }
        }
        if cols.eigenvalues > 0 {
            let all = if structured {
                // Reuse the face spectrum of the classification when there is one.
                let face = if sub.is_some() {
                    scratch.ws.face_nonunit_cached()
                } else {
                    scratch.ws.face_nonunit(scheme)?
                };
                full_spectrum(scheme.valence(), face, &mut scratch.spectrum);
                &scratch.spectrum[..]
            } else {
                // the scheme's structured path (the closed-form Fourier blocks
                // of the Catmull-Clark family's (2n+1) one-ring matrix), else
                // the dense spectrum
                scratch.spectrum = match scheme.structured_spectrum() {
                    Some(all) => all?,
                    None => spectral::eigen::Eigen::new(
                        scheme.local_matrix()?.matrix(),
                        spectral::EigenOptions::VALUES,
                    )?
                    .values()
                    .to_vec(),
                };
                &scratch.spectrum[..]
            };
            for k in 0..cols.eigenvalues {
                match all.get(k) {
                    Some(z) => {
                        out.num(z.re);
                        out.num(z.im);
                    }
                    None => {
                        out.empty();
                        out.empty();
                    }
                }
            }
        }
        if cols.charmap {
            if let Some(sub) = &sub {
                let report = charmap::check_classified(scheme, sub)?;
                out.text(report.verdict.code());
                match report.min_jacobian_coeff() {
                    Some(x) => out.num(x),
                    None => out.empty(),
                }
                match report.winding_number {
                    Some(w) => out.num(w as f64),
                    None => out.empty(),
                }
            }
        }
        if cols.curvature {
            let k = crate::curvature::curvature(scheme)?;
            out.num(k.mu);
            out.num(k.mu_over_lambda_squared);
            out.text(k.verdict.as_str());
        }
        if cols.exact_certificate {
            let exact = plan.exact_scheme(c)?;
            let v = spectral::exact::exact_verdict(&exact, sub.as_ref())?;
            out.text(v.class.map_or("undecided", |k| k.as_str()));
            match v.agrees_with_float {
                Some(a) => out.num(f64::from(u8::from(a))),
                None => out.empty(),
            }
        }
        Ok(())
    }
}

/// Whether `scheme` classifies through the face-block workspace.
fn face_block(scheme: &LocalScheme<f64>) -> bool {
    scheme.spectral_structure() == SpectralStructure::FaceBlock
}

/// `standard`, ..., or `indeterminate:A/B`.
pub(crate) fn class_text(c: &SubdominantClass) -> String {
    match c {
        SubdominantClass::Indeterminate { between, .. } => {
            format!(
                "indeterminate:{}/{}",
                between.0.as_str(),
                between.1.as_str()
            )
        }
        other => other.name().to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::SweepSpec;

    /// The `eigenvalues` columns come from the per-thread workspace (reusing the
    /// classification's face spectrum); they must equal `structured_spectrum`
    /// bit for bit, whatever was computed before on the thread.
    #[test]
    fn eigenvalue_columns_equal_structured_spectrum() {
        for classification in [true, false] {
            let spec = SweepSpec::from_toml(&format!(
                "scheme = \"nurds\"\nvalences = [3, 7, 4, 16, 5]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"random\"\ncount = 40\nseed = 3\n[columns]\nclassification = {classification}\ngap = false\ncontraction = false\neigenvalues = 70\n"
            ))
            .unwrap();
            let plan = Plan::new(spec);
            let eval = SpectralEvaluator::new(plan.spec().columns);
            // Interleave valences so the workspace is reused across sizes.
            let ids: Vec<u64> = (0..40)
                .flat_map(|i| (0..5).map(move |v| v * 40 + i))
                .collect();
            for id in ids {
                let c = plan.configuration(id).unwrap();
                let scheme = plan.scheme(&c).unwrap();
                let cells = eval.evaluate(&plan, &c, &scheme).unwrap();
                let all = spectral::structured::structured_spectrum(&scheme).unwrap();
                let first = if classification { 6 } else { 0 };
                if classification {
                    let sub = spectral::classify_scheme(&scheme).unwrap();
                    assert_eq!(cells[1], Cell::Num(sub.lambda1.re));
                    assert_eq!(cells[5], Cell::Num(sub.abs_lambda3));
                }
                for k in 0..70 {
                    let (re, im) = (&cells[first + 2 * k], &cells[first + 2 * k + 1]);
                    match all.get(k) {
                        Some(z) => {
                            assert_eq!(
                                (re, im),
                                (&Cell::Num(z.re), &Cell::Num(z.im)),
                                "id {id} k {k}"
                            );
                            if let (Cell::Num(a), Cell::Num(b)) = (re, im) {
                                assert_eq!(
                                    (a.to_bits(), b.to_bits()),
                                    (z.re.to_bits(), z.im.to_bits())
                                );
                            }
                        }
                        None => assert_eq!((re, im), (&Cell::Empty, &Cell::Empty)),
                    }
                }
            }
        }
    }
}
