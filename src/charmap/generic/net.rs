//! The characteristic map's control net on the sector grid, in midpoint-radius
//! arithmetic (math doc section 20.4): the eigenvector basis on the
//! neighbourhood, its extension outwards by the eigen-relation and the
//! regular rules, and `m` steps of refinement (the local matrix near the
//! centre, the regular mask elsewhere).

use super::layout::{label_position, Lattice, LatticePoint, SectorPoint};
use super::mask::RegularRules;
use crate::charmap::regularity::gamma;
use nalgebra::DMatrix;

/// A value with an error radius: the true value of each coordinate is within
/// `rad` of `mid`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// The computed value.
    pub mid: [f64; 2],
    /// Bound on the error of each coordinate.
    pub rad: f64,
}

/// Rounded `sum w_k p_k` of balls **\[derived\]**: the exact sum of the
/// centres is within `gamma_K sum |w_k| |p_k|` of the computed one (Higham,
/// `K` terms), the balls add `sum |w_k| rad_k`; the radius sum is itself
/// rounded up by a factor `1 + gamma_{K+2}`.
pub fn combine(terms: &[(f64, Ball)]) -> Ball {
    let k = terms.len().max(1);
    let mut mid = [0.0f64; 2];
    let (mut spread, mut size) = (0.0f64, 0.0f64);
    for (w, b) in terms {
        mid[0] += w * b.mid[0];
        mid[1] += w * b.mid[1];
        spread += w.abs() * b.rad;
        size += w.abs() * b.mid[0].abs().max(b.mid[1].abs());
    }
    let rad = (spread + gamma(k) * size) * (1.0 + gamma(k + 2));
    Ball { mid, rad }
}

/// The control net of one level: the centre and, per sector, the points
/// `(i, j)` with `1 <= i <= extent`, `0 <= j <= extent` and ring index at
/// most `extent`; `None` where a point could not be computed.
#[derive(Clone, Debug)]
pub struct Net {
    /// The lattice.
    pub lattice: Lattice,
    /// The valence.
    pub n: usize,
    /// The largest ring index held.
    pub extent: usize,
    values: Vec<Option<Ball>>,
}

impl Net {
    fn empty(lattice: Lattice, n: usize, extent: usize) -> Self {
        Self {
            lattice,
            n,
            extent,
            values: vec![None; 1 + n * extent * (extent + 1)],
        }
    }

    fn index(&self, p: SectorPoint) -> Option<usize> {
        match p {
            SectorPoint::Centre => Some(0),
            SectorPoint::In { s, i, j } => {
                let r = self.extent;
                (i >= 1 && i <= r && j <= r && self.lattice.ring_ij(i, j) <= r)
                    .then(|| 1 + (s * r + (i - 1)) * (r + 1) + j)
            }
        }
    }

    /// The value at a sector point.
    pub fn get(&self, p: SectorPoint) -> Option<Ball> {
        self.index(p).and_then(|k| self.values[k])
    }

    /// The value at lattice point `p` of sector `s`'s chart.
    pub fn at(&self, s: usize, p: LatticePoint) -> Option<Ball> {
        self.get(self.lattice.chart(self.n, s, p)?)
    }

    fn set(&mut self, p: SectorPoint, b: Ball) {
        if let Some(k) = self.index(p) {
            self.values[k] = Some(b);
        }
    }

    /// Every sector point held, centre first.
    pub fn points(&self) -> Vec<SectorPoint> {
        let r = self.extent;
        let mut out = vec![SectorPoint::Centre];
        for s in 0..self.n {
            for i in 1..=r {
                for j in 0..=r {
                    if self.lattice.ring_ij(i, j) <= r {
                        out.push(SectorPoint::In { s, i, j });
                    }
                }
            }
        }
        out
    }

    /// The largest radius of the net's values.
    pub fn max_rad(&self) -> f64 {
        self.values
            .iter()
            .flatten()
            .fold(0.0f64, |a, b| a.max(b.rad))
    }

    /// The regular rule at new point `(i, j)` of sector `s` (lattice point
    /// `beta`): `sum_gamma a_gamma p_{(beta - gamma) / d}` over the old net,
    /// `None` when a stencil point is missing.
    fn regular_point(&self, rules: &RegularRules, s: usize, beta: LatticePoint) -> Option<Ball> {
        regular_value(rules, beta, |alpha| self.at(s, alpha))
    }
}

/// The regular rule at the new lattice point `beta`:
/// `sum_gamma a_gamma p_{(beta - gamma) / d}` over the old `values` (`d` the
/// rules' dilation), `None` when a stencil point is missing.
pub fn regular_value<F>(rules: &RegularRules, beta: LatticePoint, values: F) -> Option<Ball>
where
    F: Fn(LatticePoint) -> Option<Ball>,
{
    let mut terms = Vec::with_capacity(rules.by_coset[coset_of(rules, beta)].len());
    for (w, alpha) in stencil(rules, beta) {
        terms.push((w, values(alpha)?));
    }
    Some(combine(&terms))
}

/// The coset `(beta_x mod d) + d (beta_y mod d)` of a new point.
fn coset_of(rules: &RegularRules, beta: LatticePoint) -> usize {
    let d = rules.dilation;
    (beta[0].rem_euclid(d) + d * beta[1].rem_euclid(d)) as usize
}

/// The regular stencil of the new point `beta`: the weights `a_gamma` and
/// the old points `(beta - gamma) / d`.
fn stencil(
    rules: &RegularRules,
    beta: LatticePoint,
) -> impl Iterator<Item = (f64, LatticePoint)> + '_ {
    let d = rules.dilation;
    rules.by_coset[coset_of(rules, beta)]
        .iter()
        .map(move |&(g, w)| (w, [(beta[0] - g[0]) / d, (beta[1] - g[1]) / d]))
}

/// The local matrix with its points placed on the sector grid.
#[derive(Clone, Debug)]
pub struct LocalRows {
    /// Position of each row (= column) of the matrix.
    pub positions: Vec<SectorPoint>,
    /// The matrix.
    pub matrix: DMatrix<f64>,
}

impl LocalRows {
    /// Places a square local matrix whose row and column labels coincide;
    /// `Err` with the reason otherwise.
    pub fn new(lm: &crate::schemes::LocalMatrix<f64>) -> Result<Self, String> {
        if lm.rows() != lm.cols() {
            return Err("the local matrix's rows and columns are not the same points".into());
        }
        let n = lm.valence();
        let positions = lm
            .rows()
            .iter()
            .map(|l| {
                label_position(*l, n).ok_or_else(|| {
                    format!("the point {l} has no place in a vertex-centred neighbourhood (the generic certificate reads vertex-centred neighbourhoods)")
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            positions,
            matrix: lm.matrix().clone(),
        })
    }

    /// The largest ring index of the local matrix's points.
    pub fn radius(&self, lattice: Lattice) -> usize {
        self.positions
            .iter()
            .map(|p| match *p {
                SectorPoint::Centre => 0,
                SectorPoint::In { i, j, .. } => lattice.ring_ij(i, j),
            })
            .max()
            .unwrap_or(0)
    }
}

/// The neighbourhood matrix `S_1` on every point of ring index at most
/// `radius` (the local matrix's rows for its points, the regular rule for the
/// others), with the points in index order. `Err` when a regular stencil
/// leaves the neighbourhood.
pub fn neighbourhood_matrix(
    local: &LocalRows,
    rules: &RegularRules,
    n: usize,
    radius: usize,
) -> Result<(Vec<SectorPoint>, DMatrix<f64>), String> {
    let net = Net::empty(rules.lattice, n, radius);
    let points = net.points();
    let index = |p: SectorPoint| points.iter().position(|q| *q == p);
    let d = points.len();
    let mut m = DMatrix::<f64>::zeros(d, d);
    for (r, p) in points.iter().enumerate() {
        if let Some(lr) = local.positions.iter().position(|q| q == p) {
            for (lc, q) in local.positions.iter().enumerate() {
                let c = index(*q).ok_or("a local point lies outside the neighbourhood")?;
                m[(r, c)] = local.matrix[(lr, lc)];
            }
            continue;
        }
        let SectorPoint::In { s, i, j } = *p else {
            return Err("the centre is not a point of the local matrix".into());
        };
        let beta = [i as i64, j as i64];
        for (w, alpha) in stencil(rules, beta) {
            let q = rules
                .lattice
                .chart(n, s, alpha)
                .and_then(index)
                .ok_or("a regular stencil leaves the neighbourhood of the local matrix")?;
            m[(r, q)] += w;
        }
    }
    Ok((points, m))
}

/// An enclosure `[lambda - err, lambda + err]` of the exact subdominant
/// eigenvalue, with `lambda - err > 0`.
#[derive(Clone, Copy, Debug)]
pub struct Eigenvalue {
    /// The computed value.
    pub value: f64,
    /// The error bound.
    pub err: f64,
}

/// The level-0 net of extent `extent`: the basis vectors `w1`, `w2` (on the
/// points of `S_1`, radius `vector_error`) and, ring by ring outwards, the
/// eigen-relation `p^0_x = p^1_x / lambda` with `p^1_x` the regular rule over
/// level-0 points of smaller ring index (the level-1 net of the exact eigen-net
/// is `lambda` times the level-0 net, the basis being an eigenbasis of the
/// double eigenvalue `lambda`).
pub fn initial_net(
    rules: &RegularRules,
    n: usize,
    points: &[SectorPoint],
    w: [&[f64]; 2],
    vector_error: f64,
    lambda: Eigenvalue,
    extent: usize,
) -> Result<Net, String> {
    let mut net = Net::empty(rules.lattice, n, extent);
    let mut inner = 0;
    for (k, p) in points.iter().enumerate() {
        net.set(
            *p,
            Ball {
                mid: [w[0][k], w[1][k]],
                rad: vector_error,
            },
        );
        if let SectorPoint::In { i, j, .. } = *p {
            inner = inner.max(rules.lattice.ring_ij(i, j));
        }
    }
    let lo = lambda.value - lambda.err;
    if lo.is_nan() || lo <= 0.0 {
        return Err("the subdominant eigenvalue is not certified positive".into());
    }
    for ring in inner + 1..=extent {
        for s in 0..n {
            for i in 1..=ring {
                for j in 0..=ring {
                    if rules.lattice.ring_ij(i, j) != ring {
                        continue;
                    }
                    let m = net
                        .regular_point(rules, s, [i as i64, j as i64])
                        .ok_or("the eigen-relation's stencil leaves the known net")?;
                    let inv = 1.0 / lambda.value;
                    let mid = [m.mid[0] * inv, m.mid[1] * inv];
                    let size = m.mid[0].abs().max(m.mid[1].abs());
                    let rad = (m.rad / lo
                        + size * lambda.err / (lambda.value * lo)
                        + gamma(2) * size * inv)
                        * (1.0 + gamma(4));
                    net.set(SectorPoint::In { s, i, j }, Ball { mid, rad });
                }
            }
        }
    }
    Ok(net)
}

/// One subdivision step: the local matrix's rows for its points (applied to
/// the old values at the same positions), the regular rule for every other
/// point of ring index at most `extent` (left out where a stencil point is
/// missing).
pub fn refine(net: &Net, rules: &RegularRules, local: &LocalRows, extent: usize) -> Net {
    let mut out = Net::empty(net.lattice, net.n, extent);
    let old: Vec<Option<Ball>> = local.positions.iter().map(|p| net.get(*p)).collect();
    for (r, p) in local.positions.iter().enumerate() {
        let terms: Option<Vec<(f64, Ball)>> = old
            .iter()
            .enumerate()
            .filter(|(c, _)| local.matrix[(r, *c)] != 0.0)
            .map(|(c, b)| b.map(|b| (local.matrix[(r, c)], b)))
            .collect();
        if let Some(t) = terms {
            out.set(*p, combine(&t));
        }
    }
    let local_radius = local.radius(net.lattice);
    for s in 0..net.n {
        for i in 1..=extent {
            for j in 0..=extent {
                let ring = net.lattice.ring_ij(i, j);
                if ring > extent {
                    continue;
                }
                let p = SectorPoint::In { s, i, j };
                if ring <= local_radius && local.positions.contains(&p) {
                    continue;
                }
                if let Some(b) = net.regular_point(rules, s, [i as i64, j as i64]) {
                    out.set(p, b);
                }
            }
        }
    }
    out
}
