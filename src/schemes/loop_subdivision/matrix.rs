//! Local subdivision matrices of Loop subdivision around a vertex of valence
//! `n` whose neighbours are all regular (math doc section 11).
//!
//! One Loop step maps the two-ring (`3n + 1` points, layout of [`TwoRing`])
//! to the two-ring of the new vertex point, because every new two-ring point
//! has its stencil inside the old two-ring:
//!
//! ```text
//! v'   = (1 - n beta_n) v + beta_n sum_j e_j                          (vertex point of v)
//! e'_i = 3/8 (v + e_i) + 1/8 (e_{i-1} + e_{i+1})                       (edge point of v e_i)
//! g'_i = 5/8 e_i + 1/16 (v + e_{i-1} + e_{i+1} + f_{i-1} + g_i + f_i)  (vertex point of e_i, valence 6)
//! f'_i = 3/8 (e_i + e_{i+1}) + 1/8 (v + f_i)                           (edge point of e_i e_{i+1})
//! ```
//!
//! (the new `g'_i` sits at the old `e_i`, the new `f'_i` halfway between
//! `e_i` and `e_{i+1}`). The rows are checked against a generic Loop step on
//! the triangle list of the two-ring in the tests. The top-left
//! `(n + 1)`-square block is the one-ring matrix; the `g, f` rows and columns
//! form a lower-right block, and the one-ring rows have no `g, f` columns,
//! so the matrix is block lower-triangular.
//!
//! The [`extended_matrix`] adds, for each `i`, the three new edge points
//! `a_i` (edge `e_i g_i`), `b_i` (edge `e_i f_i`) and `c_i` (edge
//! `e_{i+1} f_i`): with them the `6n + 1` new points contain the 12-point
//! control nets of the `3n` regular triangles of the first ring
//! ([`super::ring`]).
//!
//! ```
//! use subdiv_lab::schemes::loop_subdivision::matrix::{one_ring_matrix, two_ring_matrix};
//! let s = two_ring_matrix(5).unwrap();
//! assert_eq!(s.matrix().shape(), (16, 16));
//! assert_eq!(s.rows()[7].to_string(), "f0");
//! let s1 = one_ring_matrix(5).unwrap();
//! assert_eq!(s1.matrix(), &s.matrix().view((0, 0), (6, 6)).into_owned());
//! ```

use super::{beta, check_size, TwoRing};
use crate::error::{Error, Result};
use crate::scalar::Scalar;
use crate::schemes::assembly::{Assembler, LocalMatrix, PointLabel, Role};

/// Denominator of every entry of the two-ring matrix at the valences whose
/// `cos(2 pi / n)` is rational, `n` in {3, 4, 6} **\[derived\]**: the
/// vertex weights are `beta_3 = 3/16`, `beta_4 = 31/256`, `beta_6 = 1/16`
/// (so `1 - n beta_n` = 7/16, 132/256, 10/16) and the fixed weights are 3/8,
/// 1/8, 5/8 and 1/16: all multiples of 1/256.
pub const EXACT_DENOMINATOR: i64 = 256;

/// How far an `f64` entry of the two-ring matrix may lie from its multiple of
/// `1/EXACT_DENOMINATOR` at `n` in {3, 4, 6}. The `f64` rules differ from the
/// exact weights by a few rounding errors (`~1e-16`); `1e-12` is far above
/// that and far below half the grid step (`1/512`), so rounding every entry to
/// the grid recovers the exact matrix, and an entry outside it is an error,
/// never a silently wrong exact matrix.
pub const EXACT_ROUNDING_CHECK: f64 = 1e-12;

/// Scheme name used in the matrix labels.
pub const LOOP: &str = "loop";

/// A stencil: `(column, weight)` pairs.
type Stencil = Vec<(usize, f64)>;

/// Edge point of the edge `(a, b)` whose two triangles have the far
/// vertices `c` and `d`: `3/8 (a + b) + 1/8 (c + d)`.
fn edge_point(a: usize, b: usize, c: usize, d: usize) -> Stencil {
    vec![(a, 0.375), (b, 0.375), (c, 0.125), (d, 0.125)]
}

/// Vertex point of a vertex `p` with neighbours `nb`:
/// `(1 - k beta_k) p + beta_k sum nb` with `k = nb.len()`.
fn vertex_point(p: usize, nb: &[usize]) -> Stencil {
    let k = nb.len();
    let b = beta(k);
    let mut s = vec![(p, 1.0 - k as f64 * b)];
    s.extend(nb.iter().map(|&q| (q, b)));
    s
}

/// The rules on the two-ring layout.
struct Rules {
    r: TwoRing,
    /// The central vertex's rule `(own, edge)` instead of Loop's (a scheme file's).
    vertex_rule: Option<(f64, f64)>,
}

impl Rules {
    fn vertex(&self) -> Stencil {
        let r = &self.r;
        let nb: Vec<usize> = (0..r.valence()).map(|i| r.e(i)).collect();
        match self.vertex_rule {
            Some((own, edge)) => {
                let mut s = vec![(r.v(), own)];
                s.extend(nb.iter().map(|&q| (q, edge)));
                s
            }
            None => vertex_point(r.v(), &nb),
        }
    }
    fn edge_e(&self, i: usize) -> Stencil {
        let r = &self.r;
        edge_point(r.v(), r.e(i), r.e(r.prev(i)), r.e(i + 1))
    }
    fn vertex_e(&self, i: usize) -> Stencil {
        let r = &self.r;
        // the six neighbours of e_i, counter-clockwise
        let nb = [
            r.v(),
            r.e(r.prev(i)),
            r.f(r.prev(i)),
            r.g(i),
            r.f(i),
            r.e(i + 1),
        ];
        vertex_point(r.e(i), &nb)
    }
    fn edge_f(&self, i: usize) -> Stencil {
        let r = &self.r;
        edge_point(r.e(i), r.e(i + 1), r.v(), r.f(i))
    }
    /// `a_i`: edge `e_i g_i`, far vertices `f_{i-1}`, `f_i`.
    fn edge_a(&self, i: usize) -> Stencil {
        let r = &self.r;
        edge_point(r.e(i), r.g(i), r.f(r.prev(i)), r.f(i))
    }
    /// `b_i`: edge `e_i f_i`, far vertices `e_{i+1}`, `g_i`.
    fn edge_b(&self, i: usize) -> Stencil {
        let r = &self.r;
        edge_point(r.e(i), r.f(i), r.e(i + 1), r.g(i))
    }
    /// `c_i`: edge `e_{i+1} f_i`, far vertices `e_i`, `g_{i+1}`.
    fn edge_c(&self, i: usize) -> Stencil {
        let r = &self.r;
        edge_point(r.e(i + 1), r.f(i), r.e(i), r.g(i + 1))
    }
}

fn add_two_ring_rows(asm: &mut Assembler<f64>, rules: &Rules, one_ring_only: bool) {
    let r = rules.r;
    asm.stencil(r.v(), rules.vertex());
    for i in 0..r.valence() {
        asm.stencil(r.e(i), rules.edge_e(i));
        if !one_ring_only {
            asm.stencil(r.g(i), rules.vertex_e(i));
            asm.stencil(r.f(i), rules.edge_f(i));
        }
    }
}

/// The `(3n + 1)`-square two-ring matrix of valence `n >= 3` (rows: new
/// points, columns: old points, both in the layout of [`TwoRing`]).
/// Refuses valences whose dense matrix exceeds the memory budget.
pub fn two_ring_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    two_ring_with(LOOP, n, None)
}

/// The two-ring matrix over any [`Scalar`]: [`two_ring_matrix`] itself in
/// `f64`; over the rationals, the exact matrix at `n` in {3, 4, 6}, where
/// every weight is a multiple of `1/256` ([`EXACT_DENOMINATOR`]): the `f64`
/// matrix with every entry rounded to that grid (each checked within
/// [`EXACT_ROUNDING_CHECK`]; rows then sum to 1 exactly). Other valences have
/// irrational weights and are refused over the rationals. This lets the
/// curvature verdict certify `mu = lambda^2` exactly at `n` = 4 and 6 (math
/// doc section 13).
///
/// ```
/// use subdiv_lab::scalar::{Rational, Scalar};
/// use subdiv_lab::schemes::loop_subdivision::matrix::two_ring_matrix_over;
/// let q = two_ring_matrix_over::<Rational>(6).unwrap();
/// assert_eq!(q.matrix()[(0, 0)], Rational::frac(10, 16));
/// assert!(two_ring_matrix_over::<Rational>(5).is_err());
/// ```
pub fn two_ring_matrix_over<T: Scalar>(n: usize) -> Result<LocalMatrix<T>> {
    if T::EXACT && !matches!(n, 3 | 4 | 6) {
        return Err(Error::InvalidParameter {
            name: "valence",
            value: n.to_string(),
            reason: "Loop weights are irrational for this valence; exact arithmetic supports n = 3, 4, 6",
        });
    }
    let m = two_ring_matrix(n)?;
    // In f64 the matrix is already the answer (no copy on the sweeps' path).
    let m: LocalMatrix<f64> =
        match (Box::new(m) as Box<dyn std::any::Any>).downcast::<LocalMatrix<T>>() {
            Ok(same) => return Ok(*same),
            Err(other) => *other.downcast().map_err(|_| Error::Numerical {
                routine: "Loop two-ring matrix",
                reason: "the f64 matrix changed type".to_owned(),
            })?,
        };
    let mut a = Assembler::<T>::new(m.scheme(), n, m.rows().to_vec(), m.cols().to_vec());
    let s = m.matrix();
    for i in 0..s.nrows() {
        for j in 0..s.ncols() {
            let x = s[(i, j)];
            if x == 0.0 {
                continue;
            }
            if !T::EXACT {
                a.add(i, j, T::from_f64_lossless(x));
                continue;
            }
            let d = EXACT_DENOMINATOR as f64;
            let k = (x * d).round();
            if (x - k / d).abs() > EXACT_ROUNDING_CHECK {
                return Err(Error::Numerical {
                    routine: "exact Loop matrix",
                    reason: format!(
                        "entry ({i}, {j}) = {x} is not a multiple of 1/{EXACT_DENOMINATOR}"
                    ),
                });
            }
            a.add(i, j, T::frac(k as i64, EXACT_DENOMINATOR));
        }
    }
    a.finish()
}

/// The two-ring matrix of Loop's edge rule and regular vertex rule with the
/// vertex rule `v' = own v + edge sum_j e_j` at the central vertex (a scheme
/// file's; math doc section 12.1), named `name`.
pub fn two_ring_with_vertex(name: &str, n: usize, own: f64, edge: f64) -> Result<LocalMatrix<f64>> {
    two_ring_with(name, n, Some((own, edge)))
}

fn two_ring_with(
    name: &str,
    n: usize,
    vertex_rule: Option<(f64, f64)>,
) -> Result<LocalMatrix<f64>> {
    let d = 3 * n as u128 + 1;
    check_size(n, d * d, "two-ring matrix")?;
    let r = TwoRing::new(n)?;
    let mut asm = Assembler::square(name, n, r.labels());
    add_two_ring_rows(&mut asm, &Rules { r, vertex_rule }, false);
    asm.finish()
}

/// The `(n + 1)`-square one-ring matrix `[v, e_0..e_{n-1}]`: the top-left
/// block of [`two_ring_matrix`].
pub fn one_ring_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    let d = n as u128 + 1;
    check_size(n, d * d, "one-ring matrix")?;
    let r = TwoRing::new(n)?;
    let labels = r.labels()[..r.one_ring_len()].to_vec();
    let mut asm = Assembler::square(LOOP, n, labels);
    add_two_ring_rows(
        &mut asm,
        &Rules {
            r,
            vertex_rule: None,
        },
        true,
    );
    asm.finish()
}

/// Row of `a_i` in the [`extended_matrix`] (`3n + 1 + 3i`); `b_i` and `c_i`
/// follow it.
pub fn extended_row_a(n: usize, i: usize) -> usize {
    3 * n + 1 + 3 * (i % n)
}

/// The `(6n + 1) x (3n + 1)` extended matrix: rows are the new two-ring
/// (`3n + 1`, as in [`two_ring_matrix`]) followed by `a_i, b_i, c_i` for
/// `i = 0..n` (labels `X{3i}`, `X{3i+1}`, `X{3i+2}`; see the module docs).
pub fn extended_matrix(n: usize) -> Result<LocalMatrix<f64>> {
    let rows = 6 * n as u128 + 1;
    check_size(n, rows * (3 * n as u128 + 1), "extended matrix")?;
    let r = TwoRing::new(n)?;
    let cols = r.labels();
    let mut labels = cols.clone();
    labels.extend((0..3 * n).map(|k| PointLabel::new(Role::Extended, k)));
    let mut asm = Assembler::new(LOOP, n, labels, cols);
    let rules = Rules {
        r,
        vertex_rule: None,
    };
    add_two_ring_rows(&mut asm, &rules, false);
    for i in 0..n {
        let row = extended_row_a(n, i);
        asm.stencil(row, rules.edge_a(i));
        asm.stencil(row + 1, rules.edge_b(i));
        asm.stencil(row + 2, rules.edge_c(i));
    }
    asm.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use std::collections::HashMap;

    /// A generic Loop step on a triangle list (independent of the stencils
    /// above): the vertex point of every vertex whose star is closed, and the
    /// edge point of every edge with two triangles. Returns the new points
    /// keyed by `Vertex(p)` / `Edge(min, max)`.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    enum New {
        Vertex(usize),
        Edge(usize, usize),
    }

    fn generic_loop_step(tris: &[[usize; 3]], pts: &[f64]) -> HashMap<New, f64> {
        let mut far: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        let mut next: HashMap<(usize, usize), usize> = HashMap::new();
        for t in tris {
            for k in 0..3 {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                far.entry((a.min(b), a.max(b))).or_default().push(c);
                next.insert((a, b), c);
            }
        }
        let mut out = HashMap::new();
        for (&(a, b), cs) in &far {
            if cs.len() == 2 {
                let v = 0.375 * (pts[a] + pts[b]) + 0.125 * (pts[cs[0]] + pts[cs[1]]);
                out.insert(New::Edge(a, b), v);
            }
        }
        // closed stars: walk the neighbours around p
        let verts: Vec<usize> = (0..pts.len()).collect();
        for &p in &verts {
            let Some(&(_, start)) = next.keys().find(|(a, _)| *a == p) else {
                continue;
            };
            let mut nb = vec![start];
            let mut cur = start;
            let closed = loop {
                match next.get(&(p, cur)) {
                    Some(&c) if c == start => break true,
                    Some(&c) => {
                        nb.push(c);
                        cur = c;
                        if nb.len() > pts.len() {
                            break false;
                        }
                    }
                    None => break false,
                }
            };
            if closed {
                let k = nb.len();
                let b = beta(k);
                let s: f64 = nb.iter().map(|&q| pts[q]).sum();
                out.insert(New::Vertex(p), (1.0 - k as f64 * b) * pts[p] + b * s);
            }
        }
        out
    }

    /// Arbitrary data in [-1/2, 1/2) (the crate's one RNG, [`crate::rng`]).
    fn pseudo_random(len: usize, seed: u64) -> Vec<f64> {
        let mut rng = crate::rng::SplitMix64::new(seed);
        (0..len).map(|_| rng.uniform(-0.5, 0.5)).collect()
    }

    #[test]
    fn rows_match_a_generic_loop_step_on_the_triangle_list() {
        for n in 3..=12 {
            let r = TwoRing::new(n).unwrap();
            let ext = extended_matrix(n).unwrap();
            let tris = r.triangles();
            for seed in 0..3 {
                let p = pseudo_random(r.len(), 7 * n as u64 + seed);
                let new = generic_loop_step(&tris, &p);
                let m = ext.matrix() * nalgebra::DVector::from_vec(p.clone());
                let e = |a: usize, b: usize| new[&New::Edge(a.min(b), a.max(b))];
                let want = |row: usize| -> f64 {
                    if row == r.v() {
                        return new[&New::Vertex(r.v())];
                    }
                    if row < r.one_ring_len() {
                        return e(r.v(), r.e(row - 1));
                    }
                    if row < r.len() {
                        let i = (row - 1 - n) / 2;
                        return if (row - 1 - n) % 2 == 0 {
                            new[&New::Vertex(r.e(i))]
                        } else {
                            e(r.e(i), r.e(i + 1))
                        };
                    }
                    let k = row - r.len();
                    let i = k / 3;
                    match k % 3 {
                        0 => e(r.e(i), r.g(i)),
                        1 => e(r.e(i), r.f(i)),
                        _ => e(r.e(i + 1), r.f(i)),
                    }
                };
                for row in 0..ext.matrix().nrows() {
                    assert!(
                        (m[row] - want(row)).abs() < 1e-14,
                        "n = {n}, row {row} ({}): {} vs {}",
                        ext.rows()[row],
                        m[row],
                        want(row)
                    );
                }
                // exactly the vertices v, e_i have closed stars in the two-ring
                let closed = new.keys().filter(|k| matches!(k, New::Vertex(_))).count();
                assert_eq!(closed, n + 1);
            }
        }
    }

    #[test]
    fn two_ring_is_closed_under_one_step_and_block_triangular() {
        for n in 3..=10 {
            let s = two_ring_matrix(n).unwrap();
            let ext = extended_matrix(n).unwrap();
            let d = 3 * n + 1;
            assert_eq!(
                ext.matrix().view((0, 0), (d, d)),
                s.matrix().view((0, 0), (d, d))
            );
            let m = s.matrix();
            for i in 0..=n {
                for j in n + 1..d {
                    assert_eq!(m[(i, j)], 0.0, "one-ring row {i} uses column {j}");
                }
            }
            // g rows never use f-row-only points beyond the two-ring: all rows sum to 1
            for d in s.row_sum_defects() {
                assert!(d.abs() < 1e-15);
            }
            assert_eq!(s.rows(), s.cols());
            assert_eq!(s.scheme(), LOOP);
        }
    }

    #[test]
    fn closed_form_entries() {
        let n = 7;
        let s = two_ring_matrix(n).unwrap();
        let r = TwoRing::new(n).unwrap();
        let m = s.matrix();
        let b = beta(n);
        assert_eq!(m[(0, 0)], 1.0 - n as f64 * b);
        assert_eq!(m[(0, r.e(3))], b);
        assert_eq!(m[(r.g(2), r.e(2))], 0.625);
        assert_eq!(m[(r.g(2), r.g(2))], 0.0625);
        assert_eq!(m[(r.g(2), r.f(1))], 0.0625);
        assert_eq!(m[(r.f(6), r.e(0))], 0.375);
        assert_eq!(m[(r.f(6), r.f(6))], 0.125);
        assert_eq!(m[(r.e(0), r.e(6))], 0.125);
    }

    #[test]
    fn valence_is_validated() {
        for f in [two_ring_matrix, one_ring_matrix, extended_matrix] {
            assert_eq!(f(2).unwrap_err(), Error::ValenceTooSmall { valence: 2 });
            assert_eq!(f(0).unwrap_err(), Error::ValenceTooSmall { valence: 0 });
            // 100000: a (300001)^2 matrix of 720 GB is refused, not attempted
            let e = f(100_000).unwrap_err().to_string();
            assert!(
                e.contains("valence = 100000") && e.contains("memory"),
                "{e}"
            );
        }
        // the limit sits at 4 GB: the (8001)^2 one-ring would pass, the
        // (24001)^2 two-ring of the same valence is refused
        assert!(check_size(8000, 8001 * 8001, "one-ring matrix").is_ok());
        assert!(two_ring_matrix(8000).is_err());
    }
}
