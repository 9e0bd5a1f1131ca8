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
//! | `generic_charmap` | `generic_charmap_verdict` (`c1`, `not_c1`, `indeterminate`; [`crate::charmap::generic`], math doc section 20), `generic_charmap_orientation` (the certified sign of the map's Jacobian, `1` or `-1`; the eigenvector basis fixes it), `generic_charmap_winding` (the certified winding number, equal to the orientation for `c1`; empty when undecided), `generic_charmap_level` (the deepest refinement level it tested, empty when it stopped before refining) |
//! | `curvature` | `curvature_mu` (`mu`, the largest modulus after the subdominant pair), `curvature_ratio` (`mu / lambda^2`), `curvature_verdict` (`zero`, `bounded`, `unbounded`, `indeterminate`, `not_applicable`; [`crate::curvature`], math doc section 13; from the dense decomposition of the second-order matrix, math doc section 13.5, with the exact certificate where the float comparison is undecided) |
//! | `exact_certificate` | `exact_class`: the classification decided exactly over the rationals from the exact value of the `f64` parameters (`undecided` when the exact method cannot decide); `exact_agrees` = `true` / `false` when both verdicts are decided and agree / disagree (empty otherwise) |
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
use crate::schemes::{Scheme, SpectralStructure};
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

/// The type of a column, declared once in the column table
/// ([`result_columns`]); the CSV text, the Parquet type and the schema
/// documentation follow from it (math doc section 16.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ColumnType {
    /// A 64-bit float: CSV shortest round-trip text, Parquet `DOUBLE`;
    /// enters the summary's extremes.
    Float,
    /// A label from a small set of values: CSV text, Parquet dictionary-encoded
    /// `BYTE_ARRAY` (UTF-8 string).
    Label,
    /// A boolean: CSV `true` / `false`, Parquet `BOOLEAN`.
    Bool,
}

impl ColumnType {
    /// The name used in the schema documentation (`f64`, `string`, `bool`).
    pub fn name(self) -> &'static str {
        match self {
            ColumnType::Float => "f64",
            ColumnType::Label => "string",
            ColumnType::Bool => "bool",
        }
    }
}

/// A result column: one row of the column table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ResultColumn {
    /// CSV header name (and Parquet column name).
    pub name: String,
    /// Numeric (enters the summary's extremes) or text.
    pub numeric: bool,
    /// The column's type.
    pub ty: ColumnType,
    /// What the value is (for the schema documentation).
    pub meaning: String,
    /// Its unit (`1` for a pure number, `rad`, or `-` for a label).
    pub unit: &'static str,
}

/// The result columns of `columns`, in CSV order: the column table. Each row
/// gives the name, the type (once: CSV and Parquet follow it), the meaning and
/// the unit; a new column is one more row here and its cells in
/// [`SpectralEvaluator`].
pub fn result_columns(columns: &Columns) -> Vec<ResultColumn> {
    let col = |name: &str, ty: ColumnType, meaning: &str, unit: &'static str| ResultColumn {
        name: name.to_owned(),
        numeric: ty == ColumnType::Float,
        ty,
        meaning: meaning.to_owned(),
        unit,
    };
    let num = |n: &str, meaning: &str, unit: &'static str| col(n, ColumnType::Float, meaning, unit);
    let mut v = Vec::new();
    if columns.classification {
        v.push(col(
            "class",
            ColumnType::Label,
            "class of the subdominant eigenvalues (math doc section 7): standard, real_distinct, complex_pair, defective, not_separated, or indeterminate:A/B",
            "-",
        ));
        v.push(num("lambda1_re", "real part of lambda1, the subdominant eigenvalue of largest modulus (lambda0 = 1 excluded)", "1"));
        v.push(num("lambda1_im", "imaginary part of lambda1", "1"));
        v.push(num(
            "lambda2_re",
            "real part of lambda2, the second subdominant eigenvalue",
            "1",
        ));
        v.push(num("lambda2_im", "imaginary part of lambda2", "1"));
        v.push(num(
            "abs_lambda3",
            "|lambda3|, the modulus of the next eigenvalue",
            "1",
        ));
    }
    if columns.gap {
        v.push(num("gap", "|lambda2| - |lambda3|", "1"));
        v.push(num(
            "ratio",
            "lambda2 / lambda1 when both are real (empty otherwise)",
            "1",
        ));
        v.push(num(
            "rho",
            "|lambda1| for a complex pair (empty otherwise)",
            "1",
        ));
        v.push(num(
            "theta",
            "|arg lambda1| for a complex pair, in (0, pi) (empty otherwise)",
            "rad",
        ));
    }
    if columns.contraction {
        v.push(num(
            "contraction_rate",
            "|lambda1|, the asymptotic per-step contraction factor of the spectrum (a spectral quantity, not a measured rate; math doc section 5)",
            "1",
        ));
    }
    for k in 0..columns.eigenvalues {
        v.push(num(&format!("ev{k}_re"), &format!("real part of the eigenvalue of rank {k} by non-increasing modulus (empty beyond the matrix size)"), "1"));
        v.push(num(
            &format!("ev{k}_im"),
            &format!("imaginary part of the eigenvalue of rank {k}"),
            "1",
        ));
    }
    if columns.charmap && columns.sector {
        v.push(col("charmap_verdict", ColumnType::Label, "sector characteristic-map verdict (math doc section 18.4): c1, tpc_real_distinct, tpc_complex_pair, boundary_collapses, not_regular, not_injective, wrong_sector, indeterminate, no_charmap", "-"));
        v.push(num("charmap_min_jacobian", "smallest Bezier coefficient of the sector ring's Jacobian relative to the largest (> 0 certifies regularity; empty when the ring was not built)", "1"));
        v.push(num(
            "charmap_swept_degrees",
            "angle the outer arc of a boundary or corner ring sweeps (180: a half-plane; empty when not certified)",
            "deg",
        ));
    } else if columns.charmap {
        v.push(col("charmap_verdict", ColumnType::Label, "characteristic-map verdict code (c1, tpc_real_distinct, tpc_complex_pair, not_regular, not_injective, indeterminate, no_charmap)", "-"));
        v.push(num("charmap_min_jacobian", "smallest Bezier coefficient of the ring's Jacobian relative to the largest (> 0 certifies regularity)", "1"));
        v.push(num(
            "charmap_winding",
            "winding number of the ring boundary around the origin (an integer)",
            "1",
        ));
    }
    if columns.generic_charmap {
        v.push(col(
            "generic_charmap_verdict",
            ColumnType::Label,
            "the generic C1 certificate's verdict (c1, not_c1, indeterminate; math doc section 20)",
            "-",
        ));
        v.push(num(
            "generic_charmap_orientation",
            "certified sign of the characteristic map's Jacobian in the generic certificate (1 or -1; empty when undecided)",
            "1",
        ));
        v.push(num(
            "generic_charmap_winding",
            "winding number certified by the generic certificate (an integer; empty when undecided)",
            "1",
        ));
        v.push(num(
            "generic_charmap_level",
            "deepest refinement level the generic certificate tested (empty when it stopped before refining)",
            "1",
        ));
    }
    if columns.curvature {
        v.push(num(
            "curvature_mu",
            "mu, the largest eigenvalue modulus after the subdominant pair (math doc section 13)",
            "1",
        ));
        v.push(num(
            "curvature_ratio",
            "mu / lambda1^2 (> 1: curvature unbounded)",
            "1",
        ));
        v.push(col(
            "curvature_verdict",
            ColumnType::Label,
            "curvature at the extraordinary point: zero, bounded, unbounded, indeterminate, not_applicable",
            "-",
        ));
    }
    if columns.exact_certificate {
        v.push(col(
            "exact_class",
            ColumnType::Label,
            "class decided exactly over the rationals from the exact f64 parameters, or undecided",
            "-",
        ));
        v.push(col(
            "exact_agrees",
            ColumnType::Bool,
            "whether the exact and the floating-point class agree (empty when either is undecided)",
            "-",
        ));
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
        scheme: &dyn Scheme,
    ) -> crate::spectral::Result<Vec<Cell>>;

    /// Writes the result cells of `c` to `out`, in order; the cells must equal
    /// those of [`evaluate`](Self::evaluate). On an error the cells already
    /// written are discarded by the caller. The default calls `evaluate`; an
    /// evaluator overrides it to avoid building a `Vec<Cell>` per configuration
    /// (the sweep driver calls this method).
    fn write_results(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &dyn Scheme,
        out: &mut dyn CellSink,
    ) -> crate::spectral::Result<()> {
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
        items: [(&Configuration, &dyn Scheme, &mut dyn CellSink); BATCH],
    ) -> [crate::spectral::Result<()>; BATCH] {
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
    /// One scratch per configuration of a batch, and one classification per
    /// configuration (written in place by the batch classifier).
    static SCRATCH: RefCell<([Scratch; BATCH], [Subdominant; BATCH])> = RefCell::new((
        Default::default(),
        std::array::from_fn(|_| Subdominant::unset()),
    ));
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
        scheme: &dyn Scheme,
    ) -> crate::spectral::Result<Vec<Cell>> {
        let mut out = Vec::with_capacity(16 + 2 * self.columns.eigenvalues);
        self.write_results(plan, c, scheme, &mut out)?;
        Ok(out)
    }

    fn write_results(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &dyn Scheme,
        out: &mut dyn CellSink,
    ) -> crate::spectral::Result<()> {
        if let Some(sector) = plan.sector_config(c) {
            let sector = sector.map_err(crate::spectral::SpectralError::from)?;
            return self.write_sector(&sector, out);
        }
        SCRATCH.with(|cell| {
            let mut guard = cell.borrow_mut();
            let scratch = &mut guard.0[0];
            let sub = self.subdominant(scratch, scheme)?;
            self.write_with(scratch, plan, c, scheme, sub.as_ref(), out)
        })
    }

    fn write_results_batch(
        &self,
        plan: &Plan,
        items: [(&Configuration, &dyn Scheme, &mut dyn CellSink); BATCH],
    ) -> [crate::spectral::Result<()>; BATCH] {
        if plan.spec().sector.is_some() {
            return items.map(|(c, s, out)| self.write_results(plan, c, s, out));
        }
        SCRATCH.with(|cell| {
            let mut guard = cell.borrow_mut();
            let (scratch, subs) = &mut *guard;
            let schemes = items.each_ref().map(|(_, s, _)| *s);
            let mut results: [crate::spectral::Result<()>; BATCH] = std::array::from_fn(|_| Ok(()));
            // Each lane's classification is written out where it lies: the
            // 192-byte results are not moved between arrays.
            if self.needs_subdominant() && schemes.iter().all(|s| face_block(*s)) {
                let classified = spectral::classify_schemes_batch_into(
                    scratch.each_mut().map(|w| &mut w.ws),
                    schemes,
                    subs.each_mut(),
                );
                for ((((r, (c, s, out)), w), sub), ok) in results
                    .iter_mut()
                    .zip(items)
                    .zip(scratch.iter_mut())
                    .zip(subs.iter())
                    .zip(classified)
                {
                    *r = ok.and_then(|()| self.write_with(w, plan, c, s, Some(sub), out));
                }
            } else {
                for ((r, (c, s, out)), w) in results.iter_mut().zip(items).zip(scratch.iter_mut()) {
                    *r = self
                        .subdominant(w, s)
                        .and_then(|sub| self.write_with(w, plan, c, s, sub.as_ref(), out));
                }
            }
            results
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
            || cols.generic_charmap
    }

    /// The classification of `scheme` if a column needs it. Face-block
    /// schemes ([`SpectralStructure::FaceBlock`]: the Doo-Sabin family) go
    /// through the structured path with the per-thread workspace; anything
    /// else through the scheme's fast path or the dense classifier.
    fn subdominant(
        &self,
        scratch: &mut Scratch,
        scheme: &dyn Scheme,
    ) -> crate::spectral::Result<Option<Subdominant>> {
        if !self.needs_subdominant() {
            Ok(None)
        } else if face_block(scheme) {
            Ok(Some(spectral::classify_scheme_with(
                &mut scratch.ws,
                scheme,
            )?))
        } else {
            Ok(Some(spectral::classify_local(scheme)?))
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
        scheme: &dyn Scheme,
        sub: Option<&Subdominant>,
        out: &mut dyn CellSink,
    ) -> crate::spectral::Result<()> {
        let cols = &self.columns;
        let structured = face_block(scheme);
        if let Some(sub) = sub {
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
                out.num(spectral::classify::modulus(sub.lambda1));
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
            if let Some(sub) = sub {
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
        if cols.generic_charmap {
            if let Some(sub) = sub {
                let report = charmap::generic::check(scheme, sub)?;
                out.text(report.verdict.code());
                match report.orientation {
                    Some(o) => out.num(f64::from(o)),
                    None => out.empty(),
                }
                match report.winding_number {
                    Some(w) => out.num(w as f64),
                    None => out.empty(),
                }
                match report.level {
                    Some(l) => out.num(f64::from(l)),
                    None => out.empty(),
                }
            }
        }
        if cols.curvature {
            // The classification of this row when the columns made one (the
            // same as `curvature`'s own: the fast path or the local matrix).
            let k = match sub {
                Some(sub) => spectral::curvature::with_classification(scheme, sub, None)?,
                None => crate::curvature::curvature(scheme)?,
            };
            out.num(k.mu);
            out.num(k.mu_over_lambda_squared);
            out.text(k.verdict.as_str());
        }
        if cols.exact_certificate {
            let exact = plan.exact_scheme(c)?;
            let v = spectral::exact::exact_verdict(&exact, sub)?;
            out.text(v.class.map_or("undecided", |k| k.as_str()));
            match v.agrees_with_float {
                Some(a) => out.text(if a { "true" } else { "false" }),
                None => out.empty(),
            }
        }
        Ok(())
    }
}

impl SpectralEvaluator {
    /// The cells of a boundary, crease or corner configuration from its
    /// sector analysis ([`crate::boundary::analysis::analyze_sector`], math
    /// doc section 18): the interior columns with the sector's class (its
    /// structural certificate of `1/2` included), its characteristic-map
    /// certificate and its curvature verdict.
    fn write_sector(
        &self,
        sector: &crate::boundary::SectorConfig,
        out: &mut dyn CellSink,
    ) -> crate::spectral::Result<()> {
        let cols = &self.columns;
        let a = crate::boundary::analysis::analyze_sector(sector)?;
        let sub = &a.subdominant;
        let opt = |out: &mut dyn CellSink, x: Option<f64>| match x {
            Some(x) => out.num(x),
            None => out.empty(),
        };
        if cols.classification {
            out.text(&class_text(&sub.class));
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
                opt(out, x);
            }
        }
        if cols.contraction {
            out.num(spectral::classify::modulus(sub.lambda1));
        }
        for k in 0..cols.eigenvalues {
            match a.eigenvalues.get(k) {
                Some([re, im]) => {
                    out.num(*re);
                    out.num(*im);
                }
                None => {
                    out.empty();
                    out.empty();
                }
            }
        }
        if cols.charmap {
            out.text(a.charmap.verdict.as_str());
            opt(out, a.charmap.min_jacobian_coeff);
            opt(out, a.charmap.swept_degrees);
        }
        if cols.curvature {
            out.num(a.curvature.mu);
            out.num(a.curvature.mu_over_lambda_squared);
            out.text(a.curvature.verdict.as_str());
        }
        Ok(())
    }
}

/// Whether `scheme` classifies through the face-block workspace.
fn face_block(scheme: &dyn Scheme) -> bool {
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
                let built = plan.scheme(&c).unwrap();
                let scheme = &*built;
                let cells = eval.evaluate(&plan, &c, scheme).unwrap();
                let all = spectral::structured::structured_spectrum(scheme).unwrap();
                let first = if classification { 6 } else { 0 };
                if classification {
                    let sub = spectral::classify_scheme(scheme).unwrap();
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
