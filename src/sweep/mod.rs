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
//! The library does no file-system I/O: it writes to `impl std::io::Write` and
//! reads lines the caller hands it. The `subdiv-lab sweep` and `subdiv-lab merge`
//! commands do the files.
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
pub mod own;
pub(crate) mod plan;
pub mod sampler;
mod sobol_table;
pub(crate) mod spec;
pub(crate) mod summary;

pub use error::SweepError;
pub use estimate::{batch_rows, sweep_rows};
pub use eval::{Cell, Evaluate, SpectralEvaluator};
pub use output::Layout;
pub use plan::{Configuration, Plan, Shard};
pub use spec::{Columns, Sampler, Space, SpaceKind, SweepSpec, MAX_CONFIGURATIONS};
pub use summary::Summary;
