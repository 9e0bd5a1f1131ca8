//! Work estimates: memory and time of the heavy steps, computed from the
//! sizes alone before any of the work (or its allocations) starts.
//!
//! Each function returns an [`Estimate`] (peak bytes, seconds on the
//! reference machine, and what the memory is for). The command-line tool
//! compares it with [`MEMORY_LIMIT_BYTES`] and [`TIME_LIMIT_SECONDS`]
//! ([`SWEEP_TIME_LIMIT_SECONDS`] for sweeps) and refuses above them unless
//! `--force` is given; above the machine's physical memory it refuses even
//! with `--force` (an allocation failure would abort the process).
//!
//! The models are dense-linear-algebra counts (`d^2` storage, `d^3` work for
//! a `d x d` decomposition) with constants **measured** on the reference
//! machine: 2 cores (shared), 24 GB of memory, release build, peak resident
//! set from `/usr/bin/time -f %M`. They are rounded *up* (the estimates
//! are meant to be conservative by up to a factor of about 2) and are only
//! used to refuse work, never to decide a verdict.
//!
//! The per-scheme part of the models (the local matrix's dimension and the
//! constants of its analysis) is a [`CostModel`] that each scheme provides
//! ([`Scheme::cost_model`](crate::Scheme::cost_model); by name before any
//! configuration exists, [`LocalScheme::cost_model_of`](crate::schemes::LocalScheme::cost_model_of)): this
//! module never asks which scheme it is estimating.
//!
//! ```
//! use subdiv_lab::budget::{self, MEMORY_LIMIT_BYTES, TIME_LIMIT_SECONDS};
//! use subdiv_lab::schemes::LocalScheme;
//! use subdiv_lab::Scheme;
//! let cc = LocalScheme::<f64>::catmull_clark(100_000).unwrap();
//! let e = budget::analyze(&cc.cost_model(), 100_000, false);
//! assert!(e.bytes > 300e9 && e.bytes > MEMORY_LIMIT_BYTES);
//! let ds = LocalScheme::<f64>::doo_sabin(5).unwrap();
//! let small = budget::analyze(&ds.cost_model(), 5, false);
//! assert!(small.within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
//! ```

/// Memory a single command may use without `--force`: 4 GB (a sixth of the
/// 24 GB reference machine, so that several runs fit side by side).
pub const MEMORY_LIMIT_BYTES: f64 = 4e9;

/// Time a single `analyze`, `matrix`, `ccss-bound`, `cc-study` or
/// `subdivide` may take without `--force`: one minute on the reference
/// machine. Interactive commands that take longer are almost always a typo
/// in a size (`--valence 100000`).
pub const TIME_LIMIT_SECONDS: f64 = 60.0;

/// Time a `sweep` (one shard, after `--limit`, spread over its threads) may
/// take without `--force`: one hour. Sweeps stream their rows and resume
/// after an interruption, so long runs are legitimate, but a spec of `10^12`
/// configurations is a mistake; shard it (`--shard I/N`) or pass `--force`.
pub const SWEEP_TIME_LIMIT_SECONDS: f64 = 3600.0;

/// Peak bytes per entry `d^2` of the `d x d` matrix of `analyze`, Doo-Sabin
/// family (`d = 4n`): the eigenvectors (complex, both sides) and the
/// `2(d-2)`-square Kronecker matrix of the characteristic map's subspace
/// bound dominate. Measured 162-173 bytes at `n = 200..400`.
pub const ANALYZE_BYTES_PER_ENTRY_DS: f64 = 200.0;

/// The same for the Catmull-Clark family (`d = 2n + 1`). Measured 128-190
/// bytes at `n = 200..400`; with the curvature verdict's `(2n + 8)` patch
/// matrix decomposed as well (math doc section 13.5), 169-175 bytes above a
/// 9.5 MB base at `n = 200..400`.
pub const ANALYZE_BYTES_PER_ENTRY_CC: f64 = 200.0;

/// Seconds per `n^3` of `analyze`, Doo-Sabin family, full path (the
/// `4n x 4n` eigen-decomposition with vectors, the rank tests, the
/// characteristic map's `(8n)`-square separation SVD). Measured
/// 1.6e-6 at `n = 200, 300`.
pub const ANALYZE_SECONDS_PER_N3_DS_FULL: f64 = 2.0e-6;

/// Seconds per `n^3` of `analyze`, Doo-Sabin family, structured path (the
/// characteristic map's subspace bound on `S_n` remains). Measured 2.9e-7 to
/// 3.8e-7 at `n = 200, 400`.
pub const ANALYZE_SECONDS_PER_N3_DS_STRUCTURED: f64 = 5.0e-7;

/// Seconds per `n^3` of `analyze`, Catmull-Clark family (either path): the
/// one-ring's decomposition and the curvature verdict's `(2n + 8)` patch
/// matrix (math doc section 13.5). The one-ring alone measured 1.9e-7 to
/// 2.1e-7 at `n = 200, 400`; the patch matrix multiplies the CPU time by 1.6
/// to 1.85 (`n = 200..400`: 0.91 s to 1.68 s, 4.00 s to 6.51 s, 8.52 s to
/// 15.45 s), so `2.1e-7 * 1.85`, rounded up.
pub const ANALYZE_SECONDS_PER_N3_CC: f64 = 4.0e-7;

/// Seconds per `n^3` of one sweep configuration's classification or
/// characteristic map, Catmull-Clark family: the one-ring alone, measured
/// as `analyze` without the patch matrix (1.9e-7 to 2.1e-7 at
/// `n = 200, 400`).
pub const SWEEP_SECONDS_PER_N3_CC: f64 = 2.5e-7;

/// Bytes per printed matrix entry of `matrix` (the entry, its text and the
/// per-cell `String` of the text/JSON renderers); exact rationals need about
/// twice as much.
pub const MATRIX_BYTES_PER_ENTRY: f64 = 96.0;

/// Seconds per printed matrix entry of `matrix` (formatting; exact
/// rationals: reduced fractions). About 5e-8 measured in f64.
pub const MATRIX_SECONDS_PER_ENTRY: f64 = 2.0e-7;

/// Seconds per `n^(5/2)` of `ccss-bound` at the default 4 levels (the family
/// of `2n + 10` second differences times `O(n)` control points per linear
/// program). Measured 4.4e-5 to 6.9e-5 at `n = 50..200`.
pub const CCSS_SECONDS_PER_N_2_5: f64 = 8.0e-5;

/// Peak bytes per half-edge of the refined mesh of `subdivide`: the mesh
/// (about 28 bytes: three `u32` and one `f64` per half-edge, positions per
/// vertex), the previous level (a quarter of that), the OBJ text built in
/// memory (about 25 bytes) and the limit mesh. Measured 54 (NURDS) and 98
/// (Catmull-Clark with `--limit`) at 1.6 million half-edges.
pub const SUBDIVIDE_BYTES_PER_HALF_EDGE: f64 = 128.0;

/// Seconds per half-edge of the refined mesh of `subdivide` (refinement,
/// OBJ formatting and writing). Measured 0.9e-6 (NURDS) and 1.5e-6
/// (Catmull-Clark with `--limit`) at 1.6 million half-edges.
pub const SUBDIVIDE_SECONDS_PER_HALF_EDGE: f64 = 2.0e-6;

/// Seconds of the cheapest sweep configuration (structured classification
/// of a small valence; the kernel adds about `4e-9 n^3`). Measured 2.6e-6 to
/// 5e-6 per configuration and thread.
pub const SWEEP_SECONDS_BASE: f64 = 5e-6;

/// Seconds per `n^3` of the exact certificate of one sweep configuration
/// whose knots are sampled floating-point numbers (53-bit mantissas: the
/// characteristic polynomial has coefficients of thousands of bits). Measured
/// on an idle reference machine, one thread, random corner intervals in
/// `[0.01, 100]`: 0.18 s at `n = 16`, 1.4 s at `n = 32`, 4.9 s at `n = 48`,
/// 12.2 s at `n = 64` (4.4e-5 to 4.7e-5 per `n^3`); rounded up for a loaded
/// machine. To be re-measured whenever the exact path changes.
pub const SWEEP_EXACT_SECONDS_PER_N3: f64 = 6e-5;

/// The same for uniform knots (all ratios 1/2, small rationals): 0.63 s at
/// `n = 64`, 0.19 s at `n = 48` (2.4e-6 per `n^3`), rounded up.
pub const SWEEP_EXACT_UNIFORM_SECONDS_PER_N3: f64 = 4e-6;

/// Peak bytes per cell of a result table held in memory by the Python
/// binding (`sweep` and `merge` return a `pyarrow.Table`: the rows, their
/// columns, the arrays and the Python strings of the text columns). Measured
/// 36 to 49 bytes per cell (peak resident set above the one before the call,
/// 100 000 to 400 000 rows, 17 and 33 columns); rounded up.
pub const TABLE_BYTES_PER_CELL: f64 = 64.0;

/// Peak bytes per cell of the result columns of Python's `classify_batch`
/// (typed columns, their numpy arrays and the expanded text columns), and per
/// cell of its input (copied once). Measured 16 to 20 bytes per result cell
/// (1 000 000 rows at `n = 3`, 300 000 at `n = 8`); rounded up.
pub const BATCH_BYTES_PER_CELL: f64 = 32.0;

/// `estimate` with its `rows` result rows of `columns` cells each held in
/// memory at `bytes_per_cell` ([`TABLE_BYTES_PER_CELL`],
/// [`BATCH_BYTES_PER_CELL`]): the command-line tool streams its rows to a
/// file, a Python call returns them.
///
/// ```
/// use subdiv_lab::budget::{held_in_memory, Estimate, TABLE_BYTES_PER_CELL};
/// let e = Estimate { bytes: 1e6, seconds: 1.0, what: "10 configurations".into() };
/// let held = held_in_memory(e, 10, 5, TABLE_BYTES_PER_CELL);
/// assert_eq!(held.bytes, 1e6 + 10.0 * 5.0 * 64.0);
/// assert_eq!(held.what, "10 configurations, 10 rows of 5 columns in memory");
/// ```
pub fn held_in_memory(
    estimate: Estimate,
    rows: u64,
    columns: usize,
    bytes_per_cell: f64,
) -> Estimate {
    Estimate {
        bytes: estimate.bytes + rows as f64 * columns as f64 * bytes_per_cell,
        seconds: estimate.seconds,
        what: format!(
            "{}, {rows} rows of {columns} columns in memory",
            estimate.what
        ),
    }
}

/// An estimate of one heavy step.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Peak memory, bytes.
    pub bytes: f64,
    /// Wall time on the reference machine, seconds.
    pub seconds: f64,
    /// What the memory and time are for (e.g. "the 400 x 400 matrix and its decompositions").
    pub what: String,
}

impl Estimate {
    /// Whether both the time and the memory are within the given limits.
    pub fn within_limits(&self, seconds: f64, bytes: f64) -> bool {
        self.seconds <= seconds && self.bytes <= bytes
    }
}

/// `12.3 GB`, `850 MB`, `3 kB` (decimal units).
pub fn format_bytes(b: f64) -> String {
    let units = [("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    for (name, size) in units {
        if b >= size {
            return format!("{} {name}", round_2(b / size));
        }
    }
    format!("{} bytes", b.round())
}

/// `45 s`, `12 min`, `3.5 h`, `40 d`.
pub fn format_seconds(s: f64) -> String {
    if s < 120.0 {
        format!("{} s", round_2(s.max(0.0)))
    } else if s < 3600.0 {
        format!("{} min", round_2(s / 60.0))
    } else if s < 86400.0 {
        format!("{} h", round_2(s / 3600.0))
    } else if s < 86400.0 * 365.0 * 100.0 {
        format!("{} d", round_2(s / 86400.0))
    } else {
        format!("{:.1e} years", s / (86400.0 * 365.0))
    }
}

/// Two significant digits (no exponent below 10^15).
fn round_2(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x >= 10.0 {
        format!("{:.0}", x)
    } else {
        format!("{:.1}", x)
    }
}

/// How a scheme's heavy steps scale: the dimension of its local matrix and
/// the measured constants of its analysis, from which the estimates of
/// [`analyze`], [`matrix`] and the sweep estimate are computed. A scheme
/// provides it ([`Scheme::cost_model`](crate::Scheme::cost_model)); the
/// constants of the built-in families are this module's `ANALYZE_*` and
/// `SWEEP_*` constants.
///
/// ```
/// use subdiv_lab::budget::CostModel;
/// // a vertex-centred one-ring scheme: (2n + 1) x (2n + 1)
/// let m = CostModel::dense(2.0, 1.0);
/// assert_eq!(m.dimension(5), 11.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostModel {
    /// The local matrix of valence `n` is `d x d` with
    /// `d = dimension_per_valence * n + dimension_offset`.
    pub dimension_per_valence: f64,
    /// See [`dimension_per_valence`](Self::dimension_per_valence).
    pub dimension_offset: f64,
    /// Peak bytes per entry `d^2` of `analyze`.
    pub analyze_bytes_per_entry: f64,
    /// Seconds per `n^3` of `analyze`, full path.
    pub analyze_seconds_per_n3_full: f64,
    /// Seconds per `n^3` of `analyze`, structured path.
    pub analyze_seconds_per_n3_structured: f64,
    /// Seconds per `n^3` of one sweep configuration's classification on top
    /// of [`SWEEP_SECONDS_BASE`] and the `4e-9 n^3` of the face-block kernel
    /// (zero when the scheme classifies through that kernel).
    pub sweep_classify_seconds_per_n3: f64,
    /// Whether a sweep's classification (without the characteristic map)
    /// works on the `n x n` face block (64 bytes per entry `n^2`) rather than
    /// the `d x d` local matrix (64 bytes per entry `d^2`).
    pub sweep_classify_on_face_block: bool,
    /// Seconds per `n^3` of a sweep's characteristic-map check (plus 1 ms).
    pub sweep_charmap_seconds_per_n3: f64,
}

impl CostModel {
    /// The model of a scheme analysed by the dense general method only: the
    /// local matrix has `per_valence * n + offset` rows, and every step costs
    /// what the largest measured built-in constant per `d^3` gives
    /// ([`DENSE_SECONDS_PER_D3`]), the analysis and a sweep's classification
    /// alike (the default of
    /// [`Scheme::cost_model`](crate::Scheme::cost_model)).
    pub fn dense(per_valence: f64, offset: f64) -> CostModel {
        // seconds per n^3 = DENSE_SECONDS_PER_D3 * (d / n)^3, d / n taken at n = 3 (its largest)
        let ratio = per_valence + offset.max(0.0) / 3.0;
        let per_n3 = DENSE_SECONDS_PER_D3 * ratio * ratio * ratio;
        CostModel {
            dimension_per_valence: per_valence,
            dimension_offset: offset,
            analyze_bytes_per_entry: ANALYZE_BYTES_PER_ENTRY_DS.max(ANALYZE_BYTES_PER_ENTRY_CC),
            analyze_seconds_per_n3_full: per_n3,
            analyze_seconds_per_n3_structured: per_n3,
            sweep_classify_seconds_per_n3: per_n3,
            sweep_classify_on_face_block: false,
            sweep_charmap_seconds_per_n3: per_n3,
        }
    }

    /// The dimension `d` of the local matrix at valence `n`.
    pub fn dimension(&self, n: usize) -> f64 {
        self.dimension_per_valence * n as f64 + self.dimension_offset
    }
}

/// Seconds per `d^3` of a `d x d` local matrix for [`CostModel::dense`]: the
/// largest of the built-in families' measured constants converted to `d^3`
/// (Loop's analysis, `2e-6 / 27`), rounded up.
pub const DENSE_SECONDS_PER_D3: f64 = 1e-7;

/// `subdiv-lab analyze` of a scheme with the cost model `model` at valence
/// `n` (`structured`: the structured path). Without `--exact`; the exact
/// verdicts have their own bounds.
pub fn analyze(model: &CostModel, n: usize, structured: bool) -> Estimate {
    let d = model.dimension(n);
    let nf = n as f64;
    let per_n3 = if structured {
        model.analyze_seconds_per_n3_structured
    } else {
        model.analyze_seconds_per_n3_full
    };
    Estimate {
        bytes: model.analyze_bytes_per_entry * d * d,
        seconds: per_n3 * nf * nf * nf,
        what: format!("the {d} x {d} matrix and its decompositions"),
    }
}

/// `subdiv-lab analyze --exact` at valence `n` (the exact verdict only; the
/// floating-point analysis is [`analyze`]), for edge ratios whose numerator
/// and denominator need at most `ratio_bits` bits together.
///
/// Small rationals (`ratio_bits <= 64`: uniform knots, `1/3`, `77/100`) cost
/// [`SWEEP_EXACT_UNIFORM_SECONDS_PER_N3`]; ratios of sampled `f64` knots
/// (about 106 bits) [`SWEEP_EXACT_SECONDS_PER_N3`]. Beyond that the constant
/// is scaled by `(ratio_bits / 106)^2` (the cost of multiplying the longer
/// coefficients): an extrapolation, not a measurement, and meant to be
/// pessimistic.
pub fn analyze_exact(n: usize, ratio_bits: u64) -> Estimate {
    let nf = n as f64;
    let per_n3 = if ratio_bits <= 64 {
        SWEEP_EXACT_UNIFORM_SECONDS_PER_N3
    } else {
        SWEEP_EXACT_SECONDS_PER_N3 * (ratio_bits as f64 / 106.0).max(1.0).powi(2)
    };
    Estimate {
        // Not measured (the exact path stays far below the memory limit in
        // every run so far): n^2 rationals of up to ~n * ratio_bits bits (the
        // face block and its reductions), plus 64 bytes of overhead each.
        bytes: nf * nf * (ratio_bits as f64 * nf / 8.0 + 64.0),
        seconds: per_n3 * nf * nf * nf,
        what: format!("the exact verdict of the {n} x {n} face block"),
    }
}

/// `subdiv-lab matrix` of a scheme with the cost model `model` at valence
/// `n` (`face`: the `n x n` face block only; the full matrix is still
/// assembled).
pub fn matrix(model: &CostModel, n: usize, face: bool, exact: bool) -> Estimate {
    let d = model.dimension(n);
    let printed = if face { (n as f64).powi(2) } else { d * d };
    let factor = if exact { 2.0 } else { 1.0 };
    Estimate {
        bytes: 8.0 * factor * d * d + MATRIX_BYTES_PER_ENTRY * factor * printed,
        seconds: MATRIX_SECONDS_PER_ENTRY * factor * printed,
        what: format!("the {d} x {d} matrix and its text"),
    }
}

/// `subdiv-lab ccss-bound --valence n --levels levels` (a `--table-to N` is
/// the sum over `n = 3..N`).
pub fn ccss_bound(n: usize, levels: u32) -> Estimate {
    let nf = n as f64;
    let seconds = CCSS_SECONDS_PER_N_2_5 * nf.powf(2.5) * f64::from(levels.max(1)) / 4.0;
    Estimate {
        // dense tables of the 2n + 10 differences over the 2n + 8 control
        // points; measured 17 MB at n = 200
        bytes: 512.0 * nf * nf + 8e6,
        seconds,
        what: format!("{} linear programs of {} unknowns", 16 * levels, 2 * n + 10),
    }
}

/// `subdiv-lab ccss-bound --table-to max --levels levels`.
pub fn ccss_table(max: usize, levels: u32) -> Estimate {
    let mut e = ccss_bound(max, levels);
    e.seconds = (3..=max.max(3))
        .map(|n| ccss_bound(n, levels).seconds)
        .sum();
    e.what = format!("{} valences", max.saturating_sub(2));
    e
}

/// `subdiv-lab cc-study` (one classification and characteristic-map check of
/// the `(2n+1)` one-ring per sample; the intervals add about 25 bisection
/// steps per interval end).
pub fn cc_study(n_min: usize, n_max: usize, samples: usize, curves: bool) -> Estimate {
    let per_valence = |n: usize| {
        let d = 2.0 * n as f64 + 1.0;
        // Measured per point on an idle reference machine (`--curves
        // --samples 100 --n-min n --n-max n`): 0.3 ms at n = 3, 8.9 ms at
        // n = 40, 29 ms at n = 64, i.e. 1.4e-8 to 1.7e-8 s per d^3;
        // rounded up to 3e-8 for a loaded machine.
        4e-4 + 3e-8 * d * d * d
    };
    let points = samples as f64 + 1.0 + if curves { 0.0 } else { 100.0 };
    let seconds = (n_min..=n_max).map(|n| points * per_valence(n)).sum();
    let d = 2.0 * n_max as f64 + 1.0;
    Estimate {
        bytes: ANALYZE_BYTES_PER_ENTRY_CC * d * d + 1e6,
        seconds,
        what: format!(
            "{} x {points} study points",
            n_max + 1 - n_min.min(n_max + 1)
        ),
    }
}

/// `subdiv-lab subdivide` producing a mesh of `half_edges` half-edges.
pub fn subdivide(half_edges: u64) -> Estimate {
    let h = half_edges as f64;
    Estimate {
        bytes: SUBDIVIDE_BYTES_PER_HALF_EDGE * h,
        seconds: SUBDIVIDE_SECONDS_PER_HALF_EDGE * h,
        what: format!("a refined mesh of {} faces", (h / 4.0).round()),
    }
}

/// Seconds per evaluated cell of `verify` on a NURDS box, per `n^4` (the
/// centre eigen-decomposition of the `(n-1)`-square deflated block and the
/// `n` interval products `Y C_k V`). Measured 6.3e-7 at `n = 3` (582 000
/// cells in 14.8 s on 2 threads of the loaded reference machine); rounded up.
pub const VERIFY_SECONDS_PER_CELL_N4: f64 = 1.0e-6;

/// Seconds per evaluated cell of `verify` on an interval of `c` (closed-form
/// Fourier blocks, `n/2` quadratics in interval arithmetic), per `n`.
pub const VERIFY_SECONDS_PER_CELL_N_CC: f64 = 2.0e-7;

/// Peak bytes per evaluated cell of `verify`, plus [`VERIFY_BYTES_PER_CELL_DIM`]
/// per box dimension: the cell's two corner vectors and verdicts, held in the
/// frontier and in the final list, and its CSV row.
pub const VERIFY_BYTES_PER_CELL: f64 = 400.0;

/// Additional peak bytes per evaluated cell and box dimension (see
/// [`VERIFY_BYTES_PER_CELL`]).
pub const VERIFY_BYTES_PER_CELL_DIM: f64 = 64.0;

/// Set-up seconds of `verify` on a NURDS box of valence 5: the proof of the
/// invariant grid (`2^20` cells over two invariants, math doc section 15,
/// "the invariant raster"). Measured with `verify --max-cells 1` (set-up
/// plus one cell) on `[0.05, 0.95]^5`, 2 threads, loaded machine: 4.99 s CPU
/// (user + sys), 7.6 s wall; a smaller box costs less (`[0.4, 0.6]^5`:
/// 0.16 s CPU). The full-box wall time, rounded up.
pub const VERIFY_SETUP_SECONDS_N5: f64 = 8.0;

/// The same for valence 6: 7.97 s CPU, 12.0 s wall on `[0.05, 0.95]^6`
/// (7.96 s CPU on `[0.01, 0.99]^6`), loaded machine; rounded up.
pub const VERIFY_SETUP_SECONDS_N6: f64 = 13.0;

/// The same for valences 7 to 9 (the characteristic polynomial and its
/// invariants in exact rationals, no grid: three or more invariants):
/// measured at most 0.02 s; rounded up.
pub const VERIFY_SETUP_SECONDS_N7_TO_9: f64 = 0.1;

/// Seconds of the set-up of `verify` before its first cell, NURDS of valence
/// `n` when `nurds` (else the `c` path, which has none): the characteristic
/// polynomial's monomial expansion and its invariants in exact rationals
/// (`n = 5..9`), and for `n = 5, 6` the proof of the invariant grid
/// ([`VERIFY_SETUP_SECONDS_N5`], [`VERIFY_SETUP_SECONDS_N6`],
/// [`VERIFY_SETUP_SECONDS_N7_TO_9`]; `n = 3, 4` and `n >= 10` use routes
/// without set-up). The set-up cannot be interrupted by the time budget.
pub fn verify_setup_seconds(n: usize, nurds: bool) -> f64 {
    match (nurds, n) {
        (true, 5) => VERIFY_SETUP_SECONDS_N5,
        (true, 6) => VERIFY_SETUP_SECONDS_N6,
        (true, 7..=9) => VERIFY_SETUP_SECONDS_N7_TO_9,
        _ => 0.0,
    }
}

/// Seconds of `max_cells` cell evaluations of `verify` (without `charmap`)
/// on `threads` threads.
fn verify_cells_seconds(n: usize, nurds: bool, max_cells: u64, threads: usize) -> f64 {
    let nf = n as f64;
    let per_cell = if nurds {
        VERIFY_SECONDS_PER_CELL_N4 * nf.powi(4)
    } else {
        VERIFY_SECONDS_PER_CELL_N_CC * nf
    };
    max_cells as f64 * per_cell / threads.max(1) as f64
}

/// `verify` with at most `max_cells` evaluated cells on `threads` threads
/// (NURDS of valence `n` when `nurds`, else the adjustable Catmull-Clark
/// scheme over `c`), plus the set-up ([`verify_setup_seconds`]). A
/// `time_budget` caps the refinement: it is checked before every cell, so a
/// run ends within one cell of it, or after the set-up when that alone
/// takes longer; the estimate is the set-up plus the smaller of the budget
/// and the cells' time.
///
/// ```
/// let e = subdiv_lab::budget::verify(3, true, 4_000_000, None, 2);
/// assert!(e.bytes < 4e9);
/// let t = subdiv_lab::budget::verify(8, true, 4_000_000, Some(60.0), 2);
/// assert!(t.seconds <= 60.0 + subdiv_lab::budget::verify_setup_seconds(8, true));
/// ```
pub fn verify(
    n: usize,
    nurds: bool,
    max_cells: u64,
    time_budget: Option<f64>,
    threads: usize,
) -> Estimate {
    let cells = max_cells as f64;
    let nf = n as f64;
    let mut seconds = verify_cells_seconds(n, nurds, max_cells, threads);
    if let Some(t) = time_budget {
        seconds = seconds.min(t);
    }
    let setup = verify_setup_seconds(n, nurds);
    seconds += setup;
    let dim = if nurds { nf } else { 1.0 };
    Estimate {
        bytes: cells * (VERIFY_BYTES_PER_CELL + VERIFY_BYTES_PER_CELL_DIM * dim),
        seconds,
        what: if setup > 0.0 {
            format!(
                "up to {max_cells} cells of the branch and bound after {} of set-up",
                format_seconds(setup)
            )
        } else {
            format!("up to {max_cells} cells of the branch and bound")
        },
    }
}

/// Additional seconds per evaluated cell of `verify` on a NURDS box when the
/// `charmap` property is requested, per `n^3` (the centre eigen-decomposition
/// of `W`, the verified inverse and Stewart's bound, `n` interval Sylvester
/// solves and `3n` Jacobian nets in affine forms with `3n - 4` symbols).
/// Measured: the `n = 3` target (`benches/specs/verify-charmap-n3.toml`)
/// takes 198 s of CPU for 1 178 991 evaluated cells on the loaded reference
/// machine, about 170 microseconds per cell, most of them with a charmap
/// evaluation; single cells take 0.5 ms (`n = 3`), 0.9 ms (`n = 4`), 1.4 ms
/// (`n = 5`) of wall time under the same load. `1.2e-5 n^3` (0.32 ms at `n = 3`, 1.5 ms at `n = 5`) is an
/// upper estimate for a run in which every cell gets a charmap evaluation.
pub const VERIFY_CHARMAP_SECONDS_PER_CELL_N3: f64 = 1.2e-5;

/// Additional seconds per evaluated cell of `verify` on an interval of `c`
/// when `charmap` is requested, per `n` (one 7 x 7 interval solve, the cone
/// test on three cells, `4n` boundary curves). Measured: 0.01-0.02 s of CPU
/// for 100-300 evaluated cells at `n = 3..16`.
pub const VERIFY_CHARMAP_SECONDS_PER_CELL_N_CC: f64 = 1.0e-5;

/// [`verify`] with the `charmap` property requested: the same bound on the
/// memory, the time per cell raised by [`VERIFY_CHARMAP_SECONDS_PER_CELL_N3`]
/// `n^3` (NURDS) or [`VERIFY_CHARMAP_SECONDS_PER_CELL_N_CC`] `n` (the `c`
/// path).
///
/// ```
/// let plain = subdiv_lab::budget::verify(3, true, 1_000_000, None, 2);
/// let cm = subdiv_lab::budget::verify_charmap(3, true, 1_000_000, None, 2);
/// assert!(cm.seconds > plain.seconds && cm.bytes == plain.bytes);
/// ```
pub fn verify_charmap(
    n: usize,
    nurds: bool,
    max_cells: u64,
    time_budget: Option<f64>,
    threads: usize,
) -> Estimate {
    let mut e = verify(n, nurds, max_cells, None, threads);
    let nf = n as f64;
    let extra = if nurds {
        VERIFY_CHARMAP_SECONDS_PER_CELL_N3 * nf.powi(3)
    } else {
        VERIFY_CHARMAP_SECONDS_PER_CELL_N_CC * nf
    };
    let mut seconds = verify_cells_seconds(n, nurds, max_cells, threads)
        + max_cells as f64 * extra / threads.max(1) as f64;
    if let Some(t) = time_budget {
        seconds = seconds.min(t);
    }
    e.seconds = seconds + verify_setup_seconds(n, nurds);
    e.what = format!("{} (with the charmap property)", e.what);
    e
}

/// Most worker threads per available core accepted for a run's thread count
/// (more only add scheduling and per-thread scratch memory).
pub const MAX_THREADS_PER_CORE: usize = 4;

/// Absolute cap on a run's thread count, whatever the core count.
pub const MAX_THREADS: usize = 1024;

/// The largest thread count accepted on this machine:
/// `min(MAX_THREADS, MAX_THREADS_PER_CORE x available cores)`.
pub fn max_threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (MAX_THREADS_PER_CORE * cores).min(MAX_THREADS)
}

/// How a front end spells its arguments in messages: `--n-min` and
/// `--force` on the command line, `n_min` and `force=True` in Python. The
/// validators shared by the front ends take it, so that one check gives each
/// front end its own one-line message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spelling {
    /// Command-line flags: `--` and the name with `_` as `-`.
    Cli,
    /// Python keyword arguments: the name itself.
    Python,
}

impl Spelling {
    /// The argument `name` (snake case) as the front end spells it.
    ///
    /// ```
    /// use subdiv_lab::budget::Spelling;
    /// assert_eq!(Spelling::Cli.arg("max_cells"), "--max-cells");
    /// assert_eq!(Spelling::Python.arg("max_cells"), "max_cells");
    /// ```
    pub fn arg(self, name: &str) -> String {
        match self {
            Spelling::Cli => format!("--{}", name.replace('_', "-")),
            Spelling::Python => name.to_owned(),
        }
    }

    /// The override of the limits: `--force` or `force=True`.
    pub fn force(self) -> &'static str {
        match self {
            Spelling::Cli => "--force",
            Spelling::Python => "force=True",
        }
    }
}

/// Checks a thread count: between 1 and [`max_threads`]; the error is the
/// one-line message naming the argument as `spelling` spells it.
///
/// ```
/// use subdiv_lab::budget::{check_threads, Spelling};
/// assert!(check_threads(1, Spelling::Cli).is_ok());
/// let e = check_threads(0, Spelling::Python).unwrap_err();
/// assert!(e.starts_with("threads must be between 1 and "), "{e}");
/// ```
pub fn check_threads(threads: usize, spelling: Spelling) -> Result<(), String> {
    let max = max_threads();
    if threads == 0 || threads > max {
        return Err(format!(
            "{} must be between 1 and {max} ({MAX_THREADS_PER_CORE} per available core, at most {MAX_THREADS}), got {threads}",
            spelling.arg("threads")
        ));
    }
    Ok(())
}

/// Total physical memory (`MemTotal` of `/proc/meminfo`), if known. The one
/// place the library reads the machine's state (like
/// [`std::thread::available_parallelism`]): the refusal above it holds even
/// when the limits are overridden.
pub fn physical_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses `estimate` of `command` on `subject` (e.g. "valence 100000") when
/// it exceeds [`MEMORY_LIMIT_BYTES`] or `time_limit` seconds, unless
/// `force`; refuses it always when it exceeds `physical` bytes (the
/// machine's memory, [`physical_memory`]; `None`: unknown, not checked),
/// since the allocation would abort the process. The error is the one-line
/// message stating the estimate and the limit, naming the override as
/// `spelling` spells it.
///
/// ```
/// use subdiv_lab::budget::{check_against, Estimate, Spelling};
/// let e = Estimate { bytes: 1e9, seconds: 432.0, what: "the work".into() };
/// assert_eq!(
///     check_against("analyze", "valence 600", &e, 60.0, false, Spelling::Python, None).unwrap_err(),
///     "analyze: valence 600 takes ~7.2 min for the work (limit 60 s); use force=True to run anyway"
/// );
/// assert!(check_against("analyze", "valence 600", &e, 60.0, true, Spelling::Python, None).is_ok());
/// let small = Some(5e8);
/// assert!(check_against("analyze", "valence 600", &e, 60.0, true, Spelling::Cli, small)
///     .unwrap_err()
///     .ends_with("(refused even with --force)"));
/// ```
pub fn check_against(
    command: &str,
    subject: &str,
    estimate: &Estimate,
    time_limit: f64,
    force: bool,
    spelling: Spelling,
    physical: Option<f64>,
) -> Result<(), String> {
    let bytes = format_bytes(estimate.bytes);
    let what = &estimate.what;
    let flag = spelling.force();
    if let Some(total) = physical {
        if estimate.bytes > total {
            return Err(format!(
                "{command}: {subject} needs ~{bytes} for {what}, more than this machine's {} of memory (refused even with {flag})",
                format_bytes(total)
            ));
        }
    }
    if force {
        return Ok(());
    }
    let over_memory = estimate.bytes > MEMORY_LIMIT_BYTES;
    let over_time = estimate.seconds > time_limit;
    let time = format_seconds(estimate.seconds);
    let (mem_limit, time_limit) = (format_bytes(MEMORY_LIMIT_BYTES), format_seconds(time_limit));
    let text = match (over_memory, over_time) {
        (false, false) => return Ok(()),
        (true, false) => format!("needs ~{bytes} for {what} (limit {mem_limit})"),
        (false, true) => format!("takes ~{time} for {what} (limit {time_limit})"),
        (true, true) => {
            format!("needs ~{bytes} and ~{time} for {what} (limits {mem_limit}, {time_limit})")
        }
    };
    Err(format!(
        "{command}: {subject} {text}; use {flag} to run anyway"
    ))
}

/// [`check_against`] this machine's [`physical_memory`]: the check every
/// front end applies before a heavy step.
pub fn check(
    command: &str,
    subject: &str,
    estimate: &Estimate,
    time_limit: f64,
    force: bool,
    spelling: Spelling,
) -> Result<(), String> {
    check_against(
        command,
        subject,
        estimate,
        time_limit,
        force,
        spelling,
        physical_memory(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_sizes_exceed_the_limits_and_small_ones_do_not() {
        // (the per-scheme sizes: the tests of `schemes::builtin`, over every built-in cost model)
        assert!(ccss_bound(1000, 4).seconds > TIME_LIMIT_SECONDS);
        assert!(ccss_bound(50, 4).seconds < 10.0);
        assert!(ccss_bound(100_000, 4).bytes > MEMORY_LIMIT_BYTES);
        // 720k quads, 5 levels
        assert!(subdivide(4 * 720_000 * 1024).bytes > MEMORY_LIMIT_BYTES);
        assert!(subdivide(4 * 720_000).within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES));
    }

    #[test]
    fn the_dense_default_model_is_at_least_as_costly_per_entry_as_the_built_in_ones() {
        // a (3n + 1)-dimensional scheme: d / n is largest at n = 3
        let m = CostModel::dense(3.0, 1.0);
        assert_eq!(m.dimension(4), 13.0);
        let ratio = 3.0 + 1.0 / 3.0;
        let per_n3 = DENSE_SECONDS_PER_D3 * ratio * ratio * ratio;
        assert_eq!(m.analyze_seconds_per_n3_full, per_n3);
        assert!(m.analyze_bytes_per_entry >= ANALYZE_BYTES_PER_ENTRY_DS);
        assert!(!m.sweep_classify_on_face_block);
        let e = analyze(&m, 10, true);
        assert_eq!(e.bytes, m.analyze_bytes_per_entry * 31.0 * 31.0);
        assert!((e.seconds - per_n3 * 1000.0).abs() <= 1e-15 * e.seconds);
        assert!(e.what.contains("31 x 31"));
    }

    /// The set-up of the invariant grid (`n = 5, 6`) is counted on top of
    /// the cells, also when a time budget caps them.
    #[test]
    fn verify_estimates_count_the_set_up() {
        for (n, setup) in [(5, VERIFY_SETUP_SECONDS_N5), (6, VERIFY_SETUP_SECONDS_N6)] {
            let cells = verify(n, true, 1000, None, 2).seconds;
            let budgeted = verify(n, true, 4_000_000, Some(1.0), 2);
            assert_eq!(budgeted.seconds, 1.0 + setup);
            assert!(cells >= setup && budgeted.what.contains("set-up"));
            let cm = verify_charmap(n, true, 4_000_000, Some(1.0), 2);
            assert_eq!(cm.seconds, 1.0 + setup);
        }
        // no set-up on the 2 x 2 route and on the c path
        assert_eq!(verify(3, true, 4_000_000, Some(1.0), 2).seconds, 1.0);
        assert_eq!(verify(5, false, 4_000_000, Some(1.0), 2).seconds, 1.0);
    }

    #[test]
    fn formatting() {
        assert_eq!(format_bytes(320e9), "320 GB");
        assert_eq!(format_bytes(MEMORY_LIMIT_BYTES), "4.0 GB");
        assert_eq!(format_bytes(12.0), "12 bytes");
        assert_eq!(format_seconds(30.0), "30 s");
        assert_eq!(format_seconds(200.0), "3.3 min");
        assert_eq!(format_seconds(60.0), "60 s");
        assert_eq!(format_seconds(7200.0), "2.0 h");
        assert!(format_seconds(1e12).contains("years"));
    }
}
