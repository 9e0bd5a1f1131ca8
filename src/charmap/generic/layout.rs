//! The labelled neighbourhood as a sector grid (math doc section 20.2).
//!
//! Around an extraordinary vertex of valence `n`, the points of every level
//! are indexed by a sector `s` (between the edges `s` and `s + 1`) and
//! coordinates `(i, j)` along those two edges: the point `i d_s + j d_{s+1}`.
//! A point on edge `s` is stored once, as `(s, i, 0)` (`i >= 1`); the centre
//! is separate. The regular lattice ([`Lattice`]) has the same description
//! with `N = 6` (triangles) or `N = 4` (quads) sectors and the directions
//! `d_k` of [`Lattice::direction`]; near sector `s` (three consecutive
//! sectors `s - 1, s, s + 1`, away from the centre) the neighbourhood *is* a
//! piece of that lattice ([`Lattice::chart`]), which is where the regular
//! rules apply.

use crate::schemes::{PointLabel, Role};

/// The regular lattice of a vertex-centred scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Lattice {
    /// Triangles, regular valence 6 (Loop type); edge directions
    /// `(1, 0), (0, 1), (-1, 1)` and their negatives.
    Triangle,
    /// Quads, regular valence 4 (Catmull-Clark type).
    Quad,
}

/// A lattice point (integer coordinates in the basis `d_0, d_1`).
pub type LatticePoint = [i64; 2];

/// A Laurent polynomial in two variables (a mask) with exact coefficients:
/// the weight of `z^alpha` for each lattice point `alpha`.
pub type Symbol = std::collections::BTreeMap<LatticePoint, crate::scalar::Rational>;

/// A point of the sector grid: the centre, or `(s, i, j)` with `i >= 1`,
/// `j >= 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SectorPoint {
    /// The extraordinary vertex.
    Centre,
    /// `i d_s + j d_{s+1}` in sector `s`.
    In {
        /// The sector.
        s: usize,
        /// Coordinate along edge `s` (at least 1).
        i: usize,
        /// Coordinate along edge `s + 1`.
        j: usize,
    },
}

impl Lattice {
    /// The lattice of a regular valence (6: triangles, 4: quads).
    pub fn of_regular_valence(n: usize) -> Option<Lattice> {
        match n {
            6 => Some(Lattice::Triangle),
            4 => Some(Lattice::Quad),
            _ => None,
        }
    }

    /// The regular valence `N`.
    pub fn valence(self) -> usize {
        match self {
            Lattice::Triangle => 6,
            Lattice::Quad => 4,
        }
    }

    /// The edge direction `d_k` (`k` mod `N`): quads `(1,0), (0,1), (-1,0),
    /// (0,-1)`; triangles `(1,0), (0,1), (-1,1), (-1,0), (0,-1), (1,-1)`.
    /// Consecutive directions have determinant 1.
    pub fn direction(self, k: usize) -> LatticePoint {
        match self {
            Lattice::Quad => [[1, 0], [0, 1], [-1, 0], [0, -1]][k % 4],
            Lattice::Triangle => [[1, 0], [0, 1], [-1, 1], [-1, 0], [0, -1], [1, -1]][k % 6],
        }
    }

    /// The ring index of a lattice point (its combinatorial distance from the
    /// origin): `max(|x|, |y|)` for quads; for triangles `|x + y|` when `x`
    /// and `y` have the same sign, else `max(|x|, |y|)`.
    pub fn ring(self, p: LatticePoint) -> i64 {
        let [x, y] = p;
        match self {
            Lattice::Quad => x.abs().max(y.abs()),
            Lattice::Triangle => {
                if (x >= 0) == (y >= 0) {
                    (x + y).abs()
                } else {
                    x.abs().max(y.abs())
                }
            }
        }
    }

    /// The ring index of sector coordinates `(i, j)` (`i, j >= 0`).
    pub fn ring_ij(self, i: usize, j: usize) -> usize {
        match self {
            Lattice::Quad => i.max(j),
            Lattice::Triangle => i + j,
        }
    }

    /// `(k, i, j)` with `p = i d_k + j d_{k+1}`, `i >= 1`, `j >= 0`
    /// (`None` for the origin).
    fn lattice_sector(self, p: LatticePoint) -> Option<(usize, i64, i64)> {
        if p == [0, 0] {
            return None;
        }
        let nn = self.valence();
        (0..nn).find_map(|k| {
            let a = self.direction(k);
            let b = self.direction(k + 1);
            // solve i a + j b = p (det [a b] = 1)
            let i = p[0] * b[1] - p[1] * b[0];
            let j = a[0] * p[1] - a[1] * p[0];
            (i >= 1 && j >= 0).then_some((k, i, j))
        })
    }

    /// The chart of sector `s` of a valence-`n` neighbourhood: the lattice
    /// point `p` as a point of the neighbourhood, with lattice sector 0 on
    /// sector `s`, lattice sector 1 on `s + 1`, lattice sector `N - 1` on
    /// `s - 1`, and the ray `d_2` on edge `s + 2`. `None` outside these
    /// (the chart covers three sectors).
    pub fn chart(self, n: usize, s: usize, p: LatticePoint) -> Option<SectorPoint> {
        let Some((k, i, j)) = self.lattice_sector(p) else {
            return Some(SectorPoint::Centre);
        };
        let (i, j) = (i as usize, j as usize);
        let nn = self.valence();
        let sector = if k == 0 {
            s
        } else if k == 1 {
            s + 1
        } else if k == nn - 1 {
            s + n - 1
        } else if k == 2 && j == 0 {
            s + 2
        } else {
            return None;
        };
        Some(SectorPoint::In {
            s: sector % n,
            i,
            j,
        })
    }

    /// The position of a sector point in the regular lattice (valence `N`,
    /// sector `s` at `d_s`): used to read a regular configuration's rules.
    pub fn regular_position(self, p: SectorPoint) -> LatticePoint {
        match p {
            SectorPoint::Centre => [0, 0],
            SectorPoint::In { s, i, j } => {
                let a = self.direction(s);
                let b = self.direction(s + 1);
                let (i, j) = (i as i64, j as i64);
                [i * a[0] + j * b[0], i * a[1] + j * b[1]]
            }
        }
    }
}

/// The sector-grid position of a vertex-centred label: `v` the centre,
/// `e_k = (k, 1, 0)`, `f_k = (k, 1, 1)` (the point across the edge
/// `e_k e_{k+1}` from `v`, triangles; the far corner of the quad
/// `v e_k f_k e_{k+1}`, quads), `g_k = (k, 2, 0)`, and the outer rings'
/// `h_k` of a triangle lattice (ring `r >= 3`, `(s, r - b, b)`). Other roles (face-centred
/// configurations, patch points) have no position: `None`.
pub fn label_position(label: PointLabel, n: usize) -> Option<SectorPoint> {
    let k = label.index;
    if label.role == Role::OuterRing {
        return outer_ring_position(k, n);
    }
    if label.role != Role::Vertex && k >= n {
        return None;
    }
    match label.role {
        Role::Vertex => Some(SectorPoint::Centre),
        Role::EdgeNeighbour => Some(SectorPoint::In { s: k, i: 1, j: 0 }),
        Role::FaceNeighbour => Some(SectorPoint::In { s: k, i: 1, j: 1 }),
        Role::SecondRing => Some(SectorPoint::In { s: k, i: 2, j: 0 }),
        _ => None,
    }
}

/// The first label of a face-centred configuration (the Doo-Sabin family:
/// corners `P_i` of the extraordinary face and the points around it), or
/// `None` when every label is vertex-centred. The sector grid is centred on
/// a lattice point, the extraordinary vertex; a face-centred neighbourhood
/// is centred on the middle of an `n`-sided face, which is no point of the
/// net (math doc section 20.6).
pub fn face_centred_label(labels: &[PointLabel]) -> Option<PointLabel> {
    labels.iter().copied().find(|l| {
        matches!(
            l.role,
            Role::FaceCorner | Role::EdgeFirst | Role::EdgeSecond | Role::Corner
        )
    })
}

/// The sector-grid position of `h_k`, the `k`-th point counted from the
/// first point of the third ring in the ring order of the triangle lattice
/// ([`crate::schemes::tri_rings`]: ring `r` holds `r` points per sector,
/// `(s, r - b, b)` for `b = 0..r`).
fn outer_ring_position(k: usize, n: usize) -> Option<SectorPoint> {
    let (mut r, mut off) = (3usize, k);
    while off >= r * n {
        off -= r * n;
        r += 1;
        if r > 1 << 20 {
            return None;
        }
    }
    let (s, b) = (off / r, off % r);
    Some(SectorPoint::In { s, i: r - b, j: b })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outer_ring_points_follow_the_ring_order() {
        let h = |k| label_position(PointLabel::new(Role::OuterRing, k), 5);
        assert_eq!(h(0), Some(SectorPoint::In { s: 0, i: 3, j: 0 }));
        assert_eq!(h(2), Some(SectorPoint::In { s: 0, i: 1, j: 2 }));
        assert_eq!(h(3), Some(SectorPoint::In { s: 1, i: 3, j: 0 }));
        assert_eq!(h(14), Some(SectorPoint::In { s: 4, i: 1, j: 2 }));
        // ring 4 starts after the 15 points of ring 3
        assert_eq!(h(15), Some(SectorPoint::In { s: 0, i: 4, j: 0 }));
    }

    #[test]
    fn chart_inverts_sector_coordinates() {
        for lat in [Lattice::Triangle, Lattice::Quad] {
            for n in 3..8 {
                for s in 0..n {
                    for i in 1..5usize {
                        for j in 0..5usize {
                            let p = [i as i64, j as i64];
                            assert_eq!(lat.chart(n, s, p), Some(SectorPoint::In { s, i, j }));
                            // sector s + 1 sits at lattice sector 1
                            let d1 = lat.direction(1);
                            let d2 = lat.direction(2);
                            let q = [
                                i as i64 * d1[0] + j as i64 * d2[0],
                                i as i64 * d1[1] + j as i64 * d2[1],
                            ];
                            assert_eq!(
                                lat.chart(n, s, q),
                                Some(SectorPoint::In {
                                    s: (s + 1) % n,
                                    i,
                                    j
                                })
                            );
                        }
                    }
                }
            }
        }
    }
}
