//! A scheme from a file: a vertex rule written as formulas in the valence
//! `n`, on the edge and face rules of Catmull-Clark or Loop (math doc
//! section 12.1; the format's reference is `docs/scheme-files.md`).
//!
//! # The format (TOML)
//!
//! | key | type | required | meaning |
//! |---|---|---|---|
//! | `name` | string | yes | the scheme's name in outputs: 1-64 characters `A-Z a-z 0-9 - _ .`, not a built-in scheme's name |
//! | `topology` | `"quad"` or `"triangle"` | yes | `quad`: Catmull-Clark type (one-ring `2n + 1`); `triangle`: Loop type (two-ring `3n + 1`) |
//! | `vertex.self` | expression | yes | weight of the extraordinary vertex itself |
//! | `vertex.edge` | expression | yes | weight of each of its `n` edge neighbours |
//! | `vertex.face` | expression | quad: yes; triangle: refused | weight of each of its `n` face-diagonal neighbours |
//!
//! The new vertex point is `v' = self v + edge sum_j e_j (+ face sum_j f_j)`.
//! Edge and face points follow the standard rules of the topology
//! (Catmull-Clark's, math doc section 8 at `c = 1/2`; Loop's, section 11),
//! and so do the regular vertices around the extraordinary one. No other key
//! is accepted. An expression ([`Expr`]) has numbers, `+ - * / ^`,
//! parentheses, `n`, `pi`, `cos`, `sin` and `sqrt`.
//!
//! # Validation
//!
//! [`SchemeFile::weights`] is the one validator of a rule at a valence: every
//! weight is defined (no division by zero, finite), and the weights sum to 1
//! (affine invariance): exactly when every expression is rational
//! ([`Expr::is_rational`]), else in `f64` to [`ROW_SUM_TOL`], the tolerance
//! of the matrix assembly, which checks the same rows again. [`SchemeFile::parse`]
//! runs it at every valence `3..=`[`LOAD_CHECK_MAX_VALENCE`], so a broken
//! file is refused when it is read; [`SchemeFile::at`] runs it at the
//! configuration's valence. Every error ([`SchemeFileError`]) names the key
//! and, where it depends on one, the valence.
//!
//! ```
//! use subdiv_lab::schemes::user::SchemeFile;
//! use subdiv_lab::Scheme;
//! let file = SchemeFile::parse_shared(r#"
//! name = "my-cc"
//! topology = "quad"
//! [vertex]
//! self = "1 - 7/(4*n)"
//! edge = "3/(2*n^2)"
//! face = "1/(4*n^2)"
//! "#).unwrap();
//! let s = file.at(5).unwrap();
//! assert_eq!((s.name(), s.valence()), ("my-cc", 5));
//! assert_eq!(s.local_matrix().unwrap().matrix().shape(), (11, 11));
//! assert!(s.exact_local_matrix().is_some());
//!
//! let bad = SchemeFile::parse("name = \"x\"\ntopology = \"quad\"\n[vertex]\nself = \"1\"\nedge = \"1/n\"\nface = \"0\"\n");
//! assert_eq!(bad.unwrap_err().to_string(), "vertex at valence 3: the weights self + n*edge + n*face sum to 2, not 1");
//! ```

mod expr;

pub use expr::{ExactError, Expr, Function, MAX_EXACT_EXPONENT, MAX_EXPRESSION_CHARS};

use super::assembly::{LocalMatrix, ROW_SUM_TOL};
use super::catmull_clark::{self, VertexWeights};
use super::loop_subdivision;
use super::SchemeKind;
use crate::budget::CostModel;
use crate::error::Result;
use crate::scalar::{Rational, Scalar};
use crate::schemes::Scheme;
use num_complex::Complex64;
use num_traits::{One, Zero};
use std::sync::Arc;

/// The largest valence [`SchemeFile::parse`] checks the rule at (every
/// valence from 3 on): the valences of real meshes, where a formula that
/// divides by zero or does not sum to 1 is refused before any work. A
/// configuration at a larger valence is checked when it is made.
pub const LOAD_CHECK_MAX_VALENCE: usize = 32;

/// The longest scheme name (characters).
pub const MAX_NAME_CHARS: usize = 64;

/// Which standard rules the file's vertex rule completes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topology {
    /// Quad meshes: Catmull-Clark's edge and face rules.
    Quad,
    /// Triangle meshes: Loop's edge rule.
    Triangle,
}

impl Topology {
    /// The name in the file.
    pub fn name(self) -> &'static str {
        match self {
            Topology::Quad => "quad",
            Topology::Triangle => "triangle",
        }
    }

    /// The built-in scheme whose edge and face rules (and mesh refiner) it uses.
    pub fn base(self) -> SchemeKind {
        match self {
            Topology::Quad => SchemeKind::CatmullClark,
            Topology::Triangle => SchemeKind::Loop,
        }
    }
}

pub use crate::error::SchemeFileError;

fn err(key: &str, valence: Option<usize>, reason: impl Into<String>) -> SchemeFileError {
    SchemeFileError {
        key: key.to_owned(),
        valence,
        reason: reason.into(),
    }
}

/// A parsed and validated scheme file (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SchemeFile {
    name: String,
    topology: Topology,
    own: Expr,
    edge: Expr,
    face: Option<Expr>,
}

/// The vertex weights at one valence, in `f64` and (when every expression is
/// rational) exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Weights {
    /// The `f64` weights (`face` 0 for a triangle scheme).
    pub float: VertexWeights<f64>,
    /// The exact weights, when every expression is rational.
    pub exact: Option<VertexWeights<Rational>>,
}

impl SchemeFile {
    /// Parses and validates the text of a scheme file (module docs); the
    /// rule is checked at every valence `3..=`[`LOAD_CHECK_MAX_VALENCE`].
    pub fn parse(text: &str) -> Result<SchemeFile, SchemeFileError> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let at = e
                .span()
                .map(|s| format!(" ({})", crate::toml_location::Location::of(text, s.start)))
                .unwrap_or_default();
            err(
                "scheme file",
                None,
                format!("not valid TOML{at}: {}", e.message().trim()),
            )
        })?;
        for key in table.keys() {
            if !matches!(key.as_str(), "name" | "topology" | "vertex") {
                return Err(err(
                    key,
                    None,
                    "unknown key (known: name, topology, vertex)",
                ));
            }
        }
        let name = string(&table, "name", "name")?;
        check_name(&name)?;
        let topology = match string(&table, "topology", "topology")?.as_str() {
            "quad" => Topology::Quad,
            "triangle" => Topology::Triangle,
            other => {
                return Err(err(
                    "topology",
                    None,
                    format!("{other:?} is not a topology (known: \"quad\", \"triangle\")"),
                ))
            }
        };
        let vertex = match table.get("vertex") {
            Some(toml::Value::Table(t)) => t,
            Some(_) => return Err(err("vertex", None, "must be a table ([vertex])")),
            None => return Err(err("vertex", None, "missing key")),
        };
        let known = match topology {
            Topology::Quad => "self, edge, face",
            Topology::Triangle => "self, edge",
        };
        for key in vertex.keys() {
            let ok = match topology {
                Topology::Quad => matches!(key.as_str(), "self" | "edge" | "face"),
                Topology::Triangle => matches!(key.as_str(), "self" | "edge"),
            };
            if !ok {
                let why = if key == "face" {
                    "a triangle scheme has no face-diagonal neighbours".to_owned()
                } else {
                    format!("unknown key (known: {known})")
                };
                return Err(err(&format!("vertex.{key}"), None, why));
            }
        }
        let expr = |key: &str| -> Result<Expr, SchemeFileError> {
            let full = format!("vertex.{key}");
            Expr::parse(&string(vertex, key, &full)?).map_err(|e| err(&full, None, e))
        };
        let file = SchemeFile {
            name,
            topology,
            own: expr("self")?,
            edge: expr("edge")?,
            face: match topology {
                Topology::Quad => Some(expr("face")?),
                Topology::Triangle => None,
            },
        };
        for n in 3..=LOAD_CHECK_MAX_VALENCE {
            file.weights(n)?;
        }
        Ok(file)
    }

    /// The scheme's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The topology.
    pub fn topology(&self) -> Topology {
        self.topology
    }

    /// The work model: that of the built-in scheme whose matrices it shares
    /// ([`Topology::base`]).
    pub fn cost_model(&self) -> CostModel {
        crate::schemes::LocalScheme::<f64>::cost_model_of(self.topology.base())
    }

    /// The validated vertex weights at valence `n` (module docs: the one
    /// validator).
    pub fn weights(&self, n: usize) -> Result<Weights, SchemeFileError> {
        if n < 3 {
            return Err(err("valence", None, format!("must be at least 3, got {n}")));
        }
        let zero = Expr::Num(Rational::zero(), 0.0);
        let face = self.face.as_ref().unwrap_or(&zero);
        let terms = [
            ("vertex.self", &self.own),
            ("vertex.edge", &self.edge),
            ("vertex.face", face),
        ];
        let mut float = [0.0; 3];
        let mut exact: Vec<Rational> = Vec::new();
        for (k, (key, e)) in terms.iter().enumerate() {
            match e.eval_exact(n) {
                Some(Ok(q)) => exact.push(q),
                Some(Err(ExactError::DivisionByZero)) => {
                    return Err(err(key, Some(n), "division by zero"))
                }
                None => {}
            }
            let x = e.eval_f64(n);
            if !x.is_finite() {
                return Err(err(
                    key,
                    Some(n),
                    format!(
                        "the weight is {x} (a division by zero or a root of a negative number)"
                    ),
                ));
            }
            float[k] = x;
        }
        let sum_text = match self.topology {
            Topology::Quad => "self + n*edge + n*face",
            Topology::Triangle => "self + n*edge",
        };
        let nq = Rational::from_integer((n as u64).into());
        if let [own, edge, face] = exact.as_slice() {
            let sum = own.clone() + nq * (edge.clone() + face.clone());
            if !sum.is_one() {
                return Err(err(
                    "vertex",
                    Some(n),
                    format!("the weights {sum_text} sum to {sum}, not 1"),
                ));
            }
        } else {
            let sum = float[0] + n as f64 * (float[1] + float[2]);
            if (sum - 1.0).abs() > ROW_SUM_TOL {
                return Err(err(
                    "vertex",
                    Some(n),
                    format!(
                        "the weights {sum_text} sum to {sum} in f64, not 1 within {ROW_SUM_TOL:e} (ROW_SUM_TOL; no exact check: an expression is not rational)"
                    ),
                ));
            }
        }
        let [own, edge, face] = float;
        Ok(Weights {
            float: VertexWeights { own, edge, face },
            exact: match <[Rational; 3]>::try_from(exact) {
                Ok([own, edge, face]) => Some(VertexWeights { own, edge, face }),
                Err(_) => None,
            },
        })
    }

    /// The configuration at valence `n` (validated there).
    pub fn at(self: &Arc<Self>, n: usize) -> Result<UserScheme, SchemeFileError> {
        let weights = self.weights(n)?;
        Ok(UserScheme {
            file: Arc::clone(self),
            n,
            weights,
        })
    }
}

impl SchemeFile {
    /// [`SchemeFile::parse`] into an [`Arc`] (what [`SchemeFile::at`] takes).
    pub fn parse_shared(text: &str) -> Result<Arc<SchemeFile>, SchemeFileError> {
        SchemeFile::parse(text).map(Arc::new)
    }
}

/// A string value of `table[key]`, named `full` in errors.
fn string(table: &toml::Table, key: &str, full: &str) -> Result<String, SchemeFileError> {
    match table.get(key) {
        Some(toml::Value::String(s)) => Ok(s.clone()),
        Some(v) => Err(err(
            full,
            None,
            format!("must be a string, got a {}", v.type_str()),
        )),
        None => Err(err(full, None, "missing key")),
    }
}

fn check_name(name: &str) -> Result<(), SchemeFileError> {
    let ok_chars = name
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if name.is_empty() || name.chars().count() > MAX_NAME_CHARS || !ok_chars {
        return Err(err(
            "name",
            None,
            format!("{name:?} must be 1-{MAX_NAME_CHARS} characters A-Z a-z 0-9 - _ ."),
        ));
    }
    if name.parse::<SchemeKind>().is_ok() {
        return Err(err(
            "name",
            None,
            format!("{name:?} is a built-in scheme's name; choose another"),
        ));
    }
    Ok(())
}

/// One configuration of a [`SchemeFile`]: its rule at valence `n`.
#[derive(Clone, Debug, PartialEq)]
pub struct UserScheme {
    file: Arc<SchemeFile>,
    n: usize,
    weights: Weights,
}

impl UserScheme {
    /// The file this configuration comes from.
    pub fn file(&self) -> &SchemeFile {
        &self.file
    }

    /// The validated vertex weights.
    pub fn weights(&self) -> &Weights {
        &self.weights
    }
}

impl Scheme for UserScheme {
    fn name(&self) -> &str {
        &self.file.name
    }

    fn valence(&self) -> usize {
        self.n
    }

    /// Quad: the `(2n + 1)` one-ring matrix
    /// ([`catmull_clark::one_ring_with_vertex`]); triangle: the `(3n + 1)`
    /// two-ring matrix ([`loop_subdivision::matrix::two_ring_with_vertex`]).
    fn local_matrix(&self) -> Result<LocalMatrix<f64>> {
        let w = &self.weights.float;
        match self.file.topology {
            Topology::Quad => catmull_clark::one_ring_with_vertex(&self.file.name, self.n, w),
            Topology::Triangle => loop_subdivision::matrix::two_ring_with_vertex(
                &self.file.name,
                self.n,
                w.own,
                w.edge,
            ),
        }
    }

    /// Quad with rational expressions only (Loop's matrices are `f64`).
    fn exact_local_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        match (self.file.topology, &self.weights.exact) {
            (Topology::Quad, Some(w)) => Some(catmull_clark::one_ring_with_vertex(
                &self.file.name,
                self.n,
                w,
            )),
            _ => None,
        }
    }

    /// Quad: the `(2n + 8)` patch matrix ([`catmull_clark::patch_with_vertex`]),
    /// as for Catmull-Clark; triangle: the two-ring, as for Loop.
    fn second_order_matrix(&self) -> Result<LocalMatrix<f64>> {
        match self.file.topology {
            Topology::Quad => {
                catmull_clark::patch_with_vertex(&self.file.name, self.n, &self.weights.float)
            }
            Topology::Triangle => self.local_matrix(),
        }
    }

    fn exact_second_order_matrix(&self) -> Option<Result<LocalMatrix<Rational>>> {
        match (self.file.topology, &self.weights.exact) {
            (Topology::Quad, Some(w)) => {
                Some(catmull_clark::patch_with_vertex(&self.file.name, self.n, w))
            }
            _ => None,
        }
    }

    /// Quad: Catmull-Clark's regular part (the outer rows are its regular
    /// rules; [`catmull_clark::regular_part_eigenvalues`] at `c = 1/2`).
    fn regular_part_spectrum(&self) -> Option<Result<Vec<Complex64>>> {
        match self.file.topology {
            Topology::Quad => Some(Ok(catmull_clark::regular_part_eigenvalues(&f64::frac(
                1, 2,
            ))
            .into_iter()
            .map(|x| Complex64::new(x, 0.0))
            .collect())),
            Topology::Triangle => None,
        }
    }

    /// The file's rule is the extraordinary vertex's only: the regular part
    /// is Catmull-Clark's (quad) or Loop's (triangle).
    fn regular_configuration(&self) -> Option<Result<Box<dyn Scheme>>> {
        let s = match self.file.topology {
            Topology::Quad => super::LocalScheme::catmull_clark(4),
            Topology::Triangle => super::LocalScheme::loop_subdivision(6),
        };
        Some(s.map(|s| Box::new(s) as Box<dyn Scheme>))
    }

    fn cost_model(&self) -> CostModel {
        self.file.cost_model()
    }
}

#[cfg(test)]
mod tests;
