//! Python bindings of subdiv-lab (`subdiv_lab._native`): thin wrappers over the
//! library, one per CLI command. The Python package `subdiv_lab` adds the
//! keyword-argument API, numpy/pyarrow conversion and docstrings.
//!
//! The promises, kept at this boundary:
//!
//! * bad input raises `ValueError` with the library's (the CLI's) message,
//!   arguments spelled as Python keywords (`threads`, `force=True`); any other
//!   failure `RuntimeError`;
//! * integer arguments take any Python integer: a negative or huge value is a
//!   `ValueError` naming the argument ([`Int`]), never an `OverflowError`;
//! * heavy work is estimated first and refused above the CLI's limits
//!   ([`limit`], the library's [`subdiv_lab::budget::check`]) unless
//!   `force=True`; above the machine's physical memory it is refused even
//!   then (an allocation failure would abort the interpreter);
//! * no panic reaches Python: every function's body runs in [`guard`], which
//!   turns a panic (a bug) into a `RuntimeError` naming the function.
//!
//! Heavy work runs with the GIL released.

mod analysis;
mod batch;
mod commands;
mod sweeps;
mod user;

use pyo3::exceptions::{PyOverflowError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use subdiv_lab::budget::{Estimate, Spelling};

/// How this front end spells its arguments in the shared messages.
const PY: Spelling = Spelling::Python;

/// Runs the body of the Python function `name`. A panic (a bug: the library
/// and this binding never panic on input) becomes a `RuntimeError` naming the
/// function instead of a `PanicException`, which derives from
/// `BaseException` and so escapes `except Exception` (and ends a notebook
/// cell's error handling). The panic message is kept in the error; the
/// default hook has also printed it, with its location, to standard error.
fn guard<T>(name: &str, body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(body)) {
        Ok(result) => result,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".to_owned());
            Err(PyRuntimeError::new_err(format!(
                "{name}: internal error (a bug in subdiv-lab, please report it): {what}"
            )))
        }
    }
}

/// A library error as a Python exception: input errors are `ValueError`.
fn lib_err(e: impl Into<subdiv_lab::AnyError>) -> PyErr {
    let e = e.into();
    if e.is_input_error() {
        PyValueError::new_err(e.to_string())
    } else {
        PyRuntimeError::new_err(e.to_string())
    }
}

fn value_err(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

fn runtime_err(msg: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(msg.to_string())
}

/// Refuses `estimate` of `command` on `subject` above the CLI's limits
/// (`time_limit` seconds, [`subdiv_lab::budget::MEMORY_LIMIT_BYTES`]) unless
/// `force`, and above the physical memory always: a `ValueError` with the
/// CLI's message (`force=True` where it says `--force`).
fn limit(
    command: &str,
    subject: &str,
    estimate: &Estimate,
    time_limit: f64,
    force: bool,
) -> PyResult<()> {
    subdiv_lab::budget::check(command, subject, estimate, time_limit, force, PY).map_err(value_err)
}

/// An integer argument as Python gave it: any `int` (or an object with
/// `__index__`, such as a numpy integer), of any size. The binding checks its
/// range itself, so that `levels=-1` or `valence=10**30` is a `ValueError`
/// naming the argument rather than PyO3's `OverflowError`. Values beyond
/// `i128` are kept as its bounds (and shown as such).
#[derive(Clone, Copy, Debug)]
struct Int(i128);

impl<'a, 'py> FromPyObject<'a, 'py> for Int {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match obj.extract::<i128>() {
            Ok(v) => Ok(Int(v)),
            Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => {
                Ok(Int(if obj.lt(0)? { i128::MIN } else { i128::MAX }))
            }
            Err(e) => Err(e),
        }
    }
}

impl std::fmt::Display for Int {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            i128::MAX => write!(f, "a value >= 2^127"),
            i128::MIN => write!(f, "a value <= -2^127"),
            v => write!(f, "{v}"),
        }
    }
}

impl Int {
    /// The value as a `T`, or a `ValueError`: "`name` must be >= 0" for a
    /// negative value, "must be at most `T::MAX`" for a larger one.
    fn to<T: TryFrom<i128> + std::fmt::Display + Bounded>(self, name: &str) -> PyResult<T> {
        if self.0 < 0 {
            return Err(value_err(format!("{name} must be >= 0, got {self}")));
        }
        T::try_from(self.0)
            .map_err(|_| value_err(format!("{name} must be at most {}, got {self}", T::MAX)))
    }

    fn usize(self, name: &str) -> PyResult<usize> {
        self.to::<usize>(name)
    }

    fn u64(self, name: &str) -> PyResult<u64> {
        self.to::<u64>(name)
    }

    fn u32(self, name: &str) -> PyResult<u32> {
        self.to::<u32>(name)
    }
}

/// The largest value of an unsigned integer type (for [`Int::to`]'s message).
trait Bounded {
    const MAX: Self;
}

impl Bounded for usize {
    const MAX: usize = usize::MAX;
}

impl Bounded for u64 {
    const MAX: u64 = u64::MAX;
}

impl Bounded for u32 {
    const MAX: u32 = u32::MAX;
}

/// The thread count of a run: `None` is every core; otherwise checked as
/// the CLI's `--threads` ([`subdiv_lab::budget::check_threads`]).
fn threads(threads: Option<Int>) -> PyResult<usize> {
    match threads {
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
        Some(t) => {
            let t = t.usize("threads")?;
            subdiv_lab::budget::check_threads(t, PY).map_err(value_err)?;
            Ok(t)
        }
    }
}

/// The scheme called `name`, checked with the knot data and shape parameter
/// given with it by the library's one validator
/// ([`subdiv_lab::schemes::choice`]), the message prefixed with the argument
/// it is about (`scheme`, `knots/ratios`, `c`).
fn scheme_choice(name: &str, knots: bool, c: bool) -> PyResult<subdiv_lab::schemes::SchemeKind> {
    use subdiv_lab::schemes::choice::{validate, Choice, ChoiceError};
    validate(&Choice { name, knots, c }).map_err(|e| {
        let part = match e {
            ChoiceError::Unknown(_) => "scheme",
            ChoiceError::TakesNoKnots(_) => "knots/ratios",
            ChoiceError::TakesNoC(_) | ChoiceError::NeedsC(_) => "c",
        };
        value_err(format!("{part}: {e}"))
    })
}

/// A rayon pool of `threads` workers.
fn pool(threads: usize) -> PyResult<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| runtime_err(format!("cannot start the worker threads: {e}")))
}

/// Where a spec came from, for its error messages: a file (messages start
/// with its path, as the CLI's), a Python dict (messages name the dict key
/// instead of a line of the TOML text made from it), or TOML text.
enum SpecOrigin {
    Path(String),
    Dict,
    Text,
}

impl SpecOrigin {
    /// From the `spec_path` / `from_dict` arguments of the native functions.
    fn new(path: Option<String>, from_dict: bool) -> Self {
        match (path, from_dict) {
            (Some(p), _) => SpecOrigin::Path(p),
            (None, true) => SpecOrigin::Dict,
            (None, false) => SpecOrigin::Text,
        }
    }

    /// A spec error (`key`: the dotted TOML key path it is about, when known;
    /// `message`: the library's message; `full`: the message with its line) as
    /// a `ValueError`.
    fn error(&self, key: Option<&str>, message: &str, full: &str) -> PyErr {
        match self {
            SpecOrigin::Path(p) => value_err(format!("{p}: {full}")),
            SpecOrigin::Text => value_err(full.to_owned()),
            SpecOrigin::Dict => match key {
                Some(k) if k != "spec" => {
                    let subscript = dict_key(k);
                    let text = match message.strip_prefix(k) {
                        Some(rest) => format!("{subscript}{rest}"),
                        None => format!("{subscript}: {message}"),
                    };
                    value_err(text)
                }
                _ => value_err(message.to_owned()),
            },
        }
    }

    /// A sweep or verify spec error.
    fn sweep_error(&self, e: subdiv_lab::sweep::SweepError) -> PyErr {
        match &e {
            subdiv_lab::sweep::SweepError::Spec { key, message, .. } => {
                self.error(Some(key), message, &e.to_string())
            }
            _ => match self {
                SpecOrigin::Path(p) => value_err(format!("{p}: {e}")),
                _ => lib_err(e),
            },
        }
    }
}

/// The dotted TOML key path `sampler.count` / `valences[1]` as the Python
/// subscripts of the dict it came from: `spec['sampler']['count']`,
/// `spec['valences'][1]`.
fn dict_key(key: &str) -> String {
    let mut out = String::from("spec");
    for part in key.split('.') {
        let (name, rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !name.is_empty() {
            out.push_str(&format!("['{name}']"));
        }
        out.push_str(rest);
    }
    out
}

/// Exists for the test suite only: panics inside [`guard`], so that the tests
/// can check that a panic reaches Python as a `RuntimeError`.
#[pyfunction]
fn _guard_selftest(message: &str) -> PyResult<()> {
    guard("_guard_selftest", || -> PyResult<()> {
        // allowed panic: the deliberate one this function exists for
        std::panic::panic_any(message.to_owned())
    })
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", subdiv_lab::spectral::json::TOOL_VERSION)?;
    m.add_function(wrap_pyfunction!(analysis::matrix, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::analyze_json, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::analyze_file_json, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::analyze_matrix_json, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::analyze_object_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweeps::spec_json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(batch::classify_batch, m)?)?;
    m.add_function(wrap_pyfunction!(sweeps::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(sweeps::merge, m)?)?;
    m.add_function(wrap_pyfunction!(commands::subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(commands::report_files, m)?)?;
    m.add_function(wrap_pyfunction!(commands::verify, m)?)?;
    m.add_function(wrap_pyfunction!(commands::g2_cap, m)?)?;
    m.add_function(wrap_pyfunction!(commands::plot, m)?)?;
    m.add_function(wrap_pyfunction!(commands::cc_study, m)?)?;
    m.add_function(wrap_pyfunction!(commands::ccss_bound, m)?)?;
    m.add_function(wrap_pyfunction!(_guard_selftest, m)?)?;
    Ok(())
}
