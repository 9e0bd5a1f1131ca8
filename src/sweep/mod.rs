//! Parameter sweeps: millions of configurations, deterministic, shardable and
//! resumable.
//!
//! * `spec`: the TOML sweep specification and its validation ([`SweepSpec`]);
//! * [`sampler`]: counter-based random draws, Halton and Sobol sequences;
//! * `plan`: the enumeration `id -> configuration` ([`Plan`]) and [`Shard`]s;
//! * [`eval`]: the per-configuration evaluation ([`Evaluate`], one place that calls
//!   the spectral engine) and the result columns;
//! * [`output`]: the CSV layout, row formatting and parsing, the streaming
//!   [`run`](output::run()) driver and the shard [`merge`](output::merge());
//! * `summary`: the mergeable summary accumulator ([`Summary`]).
//!
//! Every scheme runs through the one engine: the spec's built-in scheme, or a
//! scheme of one's own (a Rust [`Scheme`](crate::Scheme), a scheme file, a
//! Python object) given as a [`SchemeFactory`] to [`Plan::with_scheme`]; the
//! columns, shards, resume and merge are the same. [`run_csv`] runs a whole
//! plan into memory.
//!
//! [`run`] runs a sweep into its files (a CSV or a Parquet dataset with the
//! summary beside it, or a stream): planning, shards, resume and the summary;
//! [`output::files::merge_files`] merges shard files. The `subdiv-lab sweep`
//! and `merge` commands and the Python `sweep(out=...)` and `merge` call them;
//! the driver below them writes to any `impl std::io::Write`.
//!
//! ```
//! use subdiv_lab::sweep::{output, Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};
//! let spec = SweepSpec::from_toml(r#"
//! scheme = "nurds"
//! valences = [3]
//! [space]
//! kind = "ratios"
//! ratio_range = [0.2, 0.8]
//! [sampler]
//! kind = "grid"
//! points_per_axis = 2
//! "#).unwrap();
//! let plan = Plan::new(spec);
//! let layout = Layout::new(&plan);
//! let eval = SpectralEvaluator::new(plan.spec().columns);
//! let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
//! let mut csv = Vec::new();
//! layout.write_header(&mut csv).unwrap();
//! output::run(&plan, &layout, &eval, 0..plan.total(), &mut csv, &mut summary, &mut |_| {}).unwrap();
//! let text = String::from_utf8(csv).unwrap();
//! assert_eq!(text.lines().count(), 1 + 8);
//! assert!(text.starts_with("id,valence,r0,r1,r2,class,"));
//! assert_eq!(summary.rows, 8);
//! ```

mod error;
pub(crate) mod estimate;
pub mod eval;
pub mod output;
pub(crate) mod plan;
pub mod sampler;
mod sobol_table;
pub(crate) mod spec;
pub(crate) mod summary;

pub use error::SweepError;
pub use estimate::{batch_rows, sweep_rows};
pub use eval::{Cell, Evaluate, SpectralEvaluator};
pub use output::files::{run, run_plan, Opened, Progress, RunOptions, RunReport, Sink};
pub use output::Layout;
pub use plan::{Configuration, Configured, Plan, SchemeFactory, Shard};
pub use spec::{Columns, Sampler, SectorSweep, Space, SpaceKind, SweepSpec, MAX_CONFIGURATIONS};
pub use summary::Summary;

/// Runs every configuration of `plan` and returns the CSV text (the header
/// and one line per configuration, in id order, as `subdiv-lab sweep` writes
/// them after its fingerprint line): the library entry for a sweep in
/// memory, e.g. of a scheme of one's own ([`Plan::with_scheme`]).
///
/// ```
/// use subdiv_lab::sweep::{run_csv, Plan, SweepSpec};
/// let spec = SweepSpec::from_toml("scheme = \"loop\"\nvalences = [3, 7]\n[space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n").unwrap();
/// let csv = run_csv(&Plan::new(spec)).unwrap();
/// assert_eq!(csv.lines().count(), 3);
/// assert!(csv.lines().nth(2).unwrap().starts_with("1,7,standard,"));
/// ```
pub fn run_csv(plan: &Plan) -> Result<String, SweepError> {
    let layout = Layout::new(plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(plan, &layout, Shard::ALL, None);
    let mut csv = Vec::new();
    layout.write_header(&mut csv)?;
    output::run(
        plan,
        &layout,
        &eval,
        0..plan.total(),
        &mut csv,
        &mut summary,
        &mut |_| {},
    )?;
    String::from_utf8(csv).map_err(|e| SweepError::Io(e.to_string()))
}
