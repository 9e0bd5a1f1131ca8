//! Mesh refinement with a scheme file's vertex rule (math doc section 12.2):
//! the file's rule ([`SchemeFile`]) as a [`VertexRule`], on the refiners of
//! the built-in scheme whose edge and face rules the file's topology names
//! (Catmull-Clark's [`refine_quads`](super::catmull_clark::refine_quads),
//! Loop's [`refine_with`](super::loop_subdivision::refine_with)). Closed
//! meshes only: a scheme file states no boundary, crease or corner rules.
//!
//! **Quad files.** The file's rule `v' = s v + e sum e_i + f sum f_i` (`f_i`
//! the face-diagonal neighbours) is, on an all-quad neighbourhood, the rule
//!
//! ```text
//! v' = w_v v + w_R R + w_Q Q,   w_v = s - n e + n f,  w_R = 2 n (e - 2 f),  w_Q = 4 n f
//! ```
//!
//! in the mean `R` of the edge midpoints `(v + e_i)/2` and the mean `Q` of
//! the new face points, the form Catmull-Clark's refiner takes, which is also
//! defined next to faces that are not quads (Catmull-Clark's
//! `v' = (Q + 2R + (n - 3) v)/n` is the file `analysis/schemes/catmull-clark.toml`).
//! The limit stencil is the left eigenvector for 1 of the one-ring matrix:
//! `l_e = B l_v`, `l_f = C l_v`, `l_v = 1 / (1 + n B + n C)` with
//! `B = (12 e + 8 f)/5`, `C = 4 f/3 + B/6` (Catmull-Clark: `n^2 : 4 : 1`).
//!
//! **Triangle files.** `v' = s v + e sum e_i` is Loop's form with
//! `beta = e`; the limit stencil is Loop's closed form with that `beta`,
//! `chi = 1 / (3/(8 e) + n)`, `l_v = 1 - n chi`, `l_e = chi`.
//!
//! When every expression of the file is rational the weights are computed
//! exactly and rounded once, so a file that restates a built-in scheme
//! refines to the same bits.
//!
//! ```
//! use subdiv_lab::mesh::{generators, rules::MeshRules, user::file_rules};
//! use subdiv_lab::mesh::builtin::mesh_rules;
//! use subdiv_lab::schemes::{user::SchemeFile, SchemeKind};
//! let file = SchemeFile::parse_shared(r#"
//! name = "my-cc"
//! topology = "quad"
//! [vertex]
//! self = "1 - 7/(4*n)"
//! edge = "3/(2*n^2)"
//! face = "1/(4*n^2)"
//! "#).unwrap();
//! let cube = generators::cube();
//! let mine = file_rules(file).refine(&cube).unwrap();
//! let cc = mesh_rules(SchemeKind::CatmullClark, None).unwrap().refine(&cube).unwrap();
//! assert_eq!(mine.positions(), cc.positions());
//! ```

use super::catmull_clark::CatmullClarkRules;
use super::loop_subdivision::LoopRules;
use super::rules::{MeshRules, VertexRule};
use super::MeshError;
use crate::error::{Error, SchemeFileError};
use crate::scalar::{Rational, Scalar};
use crate::schemes::user::{SchemeFile, Topology};
use std::sync::Arc;

/// The mesh rules of a scheme file: the refiner of its topology's built-in
/// scheme with the file's vertex rule (module docs).
pub fn file_rules(file: Arc<SchemeFile>) -> Box<dyn MeshRules> {
    let name = file.name().to_owned();
    let rule: Arc<dyn VertexRule> = Arc::new(FileVertexRule(Arc::clone(&file)));
    match file.topology() {
        Topology::Quad => Box::new(CatmullClarkRules::with_vertex_rule(&name, rule)),
        Topology::Triangle => Box::new(LoopRules::with_vertex_rule(&name, rule)),
    }
}

/// A scheme file's vertex rule as a [`VertexRule`] (module docs).
#[derive(Clone, Debug)]
struct FileVertexRule(Arc<SchemeFile>);

fn weights(file: &SchemeFile, n: usize) -> Result<crate::schemes::user::Weights, MeshError> {
    file.weights(n)
        .map_err(|e| MeshError::Core(Error::SchemeFile(e)))
}

fn no_limit(n: usize) -> MeshError {
    MeshError::Core(Error::SchemeFile(SchemeFileError {
        key: "vertex".to_owned(),
        valence: Some(n),
        reason: "the rule has no limit stencil (1 + n B + n C = 0 in the left eigenvector of the one-ring matrix)".to_owned(),
    }))
}

/// The quad rule in the `(v, R, Q)` form, `[w_v, w_R, w_Q]` (module docs).
fn quad_refine<T: Scalar>(n: &T, s: &T, e: &T, f: &T) -> [T; 3] {
    let (two, four) = (T::frac(2, 1), T::frac(4, 1));
    [
        s.clone() - n.clone() * e.clone() + n.clone() * f.clone(),
        two.clone() * n.clone() * (e.clone() - two * f.clone()),
        four * n.clone() * f.clone(),
    ]
}

/// The quad limit stencil `[l_v, l_e, l_f]` (module docs); `None` when
/// `1 + n B + n C = 0`.
fn quad_limit<T: Scalar>(n: &T, e: &T, f: &T) -> Option<[T; 3]> {
    let b = (T::frac(12, 1) * e.clone() + T::frac(8, 1) * f.clone()) / T::frac(5, 1);
    let c = T::frac(4, 1) * f.clone() / T::frac(3, 1) + b.clone() / T::frac(6, 1);
    let den = T::frac(1, 1) + n.clone() * b.clone() + n.clone() * c.clone();
    if den == T::frac(0, 1) {
        return None;
    }
    let lv = T::frac(1, 1) / den;
    Some([lv.clone(), b * lv.clone(), c * lv])
}

impl VertexRule for FileVertexRule {
    fn refine_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let w = weights(&self.0, n)?;
        Ok(match self.0.topology() {
            Topology::Triangle => [w.float.own, w.float.edge, 0.0],
            Topology::Quad => match &w.exact {
                Some(q) => {
                    let nq = Rational::from_integer((n as u64).into());
                    quad_refine(&nq, &q.own, &q.edge, &q.face).map(|x| x.to_f64())
                }
                None => quad_refine(&(n as f64), &w.float.own, &w.float.edge, &w.float.face),
            },
        })
    }

    fn limit_weights(&self, n: usize) -> Result<[f64; 3], MeshError> {
        let w = weights(&self.0, n)?;
        match self.0.topology() {
            Topology::Triangle => {
                // Loop's closed form with beta = e, in Loop's own operation order.
                let chi = 1.0 / (3.0 / (8.0 * w.float.edge) + n as f64);
                Ok([1.0 - n as f64 * chi, chi, 0.0])
            }
            Topology::Quad => {
                let l = match &w.exact {
                    Some(q) => {
                        let nq = Rational::from_integer((n as u64).into());
                        quad_limit(&nq, &q.edge, &q.face).map(|l| l.map(|x| x.to_f64()))
                    }
                    None => quad_limit(&(n as f64), &w.float.edge, &w.float.face),
                };
                match l {
                    Some(l) if l.iter().all(|x| x.is_finite()) => Ok(l),
                    _ => Err(no_limit(n)),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::{One, Zero};

    #[test]
    fn quad_forms_restate_catmull_clark_exactly() {
        for n in 3..=12u64 {
            let nq = Rational::from_integer(n.into());
            let q = |a: i64, b: u64| Rational::new(a.into(), b.into());
            let s = Rational::one() - q(7, 4 * n);
            let e = q(3, 2 * n * n);
            let f = q(1, 4 * n * n);
            let [wv, wr, wq] = quad_refine(&nq, &s, &e, &f);
            assert_eq!(
                (wv, wr, wq),
                (q(n as i64 - 3, n), q(2, n), q(1, n)),
                "n = {n}"
            );
            let [lv, le, lf] = quad_limit(&nq, &e, &f).unwrap();
            let den = n * (n + 5);
            assert_eq!((lv, le, lf), (q((n * n) as i64, den), q(4, den), q(1, den)));
        }
        assert!(Rational::zero().is_zero());
    }
}
