//! The plain subdivision surface over the cap's domain: what the cap
//! replaces, for the side-by-side curvature figures (math doc section 14.7).
//!
//! The refined ring `R_0` of the cap ([`RefinedRing`]) is refined again and
//! again with the same shape-adjustable rules: `R_m` is the refinement of the
//! 2-ring of `R_(m-1)`. The cap's cell of sector `i`, `[0,1]^2` in `R_0`'s
//! grid units, is covered by the L-shaped rings
//!
//! ```text
//! ring m:  2^-m <= max(u, v) <= 2^-(m-1),   m = 1..=M
//! ```
//!
//! and ring `m` consists of the three regular cells `[1,2] x [0,1]`,
//! `[0,1] x [1,2]`, `[1,2] x [1,2]` of `R_m` (at `(U, V) = 2^m (u, v)`), each
//! evaluated as a **uniform bicubic B-spline** cell like the surrounding
//! surface of the cap (math doc section 14.2). Derivatives are returned with
//! respect to the cap's `(u, v)` (the chain rule's `2^(m (du + dv))`).
//! The square `max(u, v) < 2^-M` around the vertex is not covered.
//!
//! At `c = 1/2` this is the Catmull-Clark limit surface exactly (the
//! B-spline cells of consecutive levels are pieces of one C2 spline). For
//! `c != 1/2` it is the B-spline reading of every level's net: the
//! adjustable scheme's own regular limit is only C1 (its symbol has the
//! factor `(1 + z)^2` but not `(1 + z)^3`), so it has no curvature to show,
//! and the rings of this reading do not join (measured in the tests).
//!
//! ```
//! use subdiv_lab::g2cap::{plain::PlainSurface, ring::TwoRing};
//! let ring = TwoRing::random(5, 2).unwrap();
//! let s = PlainSurface::new(&ring, 0.5, 6).unwrap();
//! assert!(s.curvature_at(1, 0.3, 0.6).is_some());
//! assert!(s.eval(1, 0.001, 0.001, 0, 0).is_none()); // inside 2^-6
//! ```

use super::bernstein::eval_bspline;
use super::residual::shape;
use super::ring::{Point, RefinedRing, TwoRing};
use super::G2CapError;

/// Largest number of levels: at `2^-30` the cells are below `1e-9` of the
/// cap and the B-spline coordinates lose their digits to rounding.
pub const MAX_LEVELS: usize = 30;

/// The plain subdivision surface around the vertex, `M` levels deep.
#[derive(Clone, Debug)]
pub struct PlainSurface {
    /// `R_0, .., R_M`.
    nets: Vec<RefinedRing>,
}

impl PlainSurface {
    /// `levels` (`M`, `1..=MAX_LEVELS`) refinements of the cap's refined
    /// ring of `ring` with shape parameter `c` in `[0, 1]`.
    pub fn new(ring: &TwoRing, c: f64, levels: usize) -> Result<PlainSurface, G2CapError> {
        if !(0.0..=1.0).contains(&c) {
            return Err(G2CapError::ShapeParameter { c });
        }
        if !(1..=MAX_LEVELS).contains(&levels) {
            return Err(G2CapError::Levels {
                levels,
                max: MAX_LEVELS,
            });
        }
        let mut nets = vec![RefinedRing::new(ring, c)];
        for _ in 0..levels {
            let next = RefinedRing::new(&nets[nets.len() - 1].two_ring()?, c);
            nets.push(next);
        }
        Ok(PlainSurface { nets })
    }

    /// `M`.
    pub fn levels(&self) -> usize {
        self.nets.len() - 1
    }

    /// The refined net `R_m`, `m = 0..=M` (`R_0` is the cap's
    /// [`super::G2Cap::refined`]).
    pub fn net(&self, m: usize) -> &RefinedRing {
        &self.nets[m.min(self.nets.len() - 1)]
    }

    /// The ring `m` containing `(u, v)` in `[0, 1]^2`, `None` inside
    /// `max(u, v) < 2^-M` (or outside the unit square).
    pub fn level_of(&self, u: f64, v: f64) -> Option<usize> {
        let s = u.max(v);
        if !(u >= 0.0 && v >= 0.0 && s <= 1.0) {
            return None;
        }
        let mut m = 1;
        let mut lo = 0.5;
        while s < lo {
            m += 1;
            if m > self.levels() {
                return None;
            }
            lo *= 0.5;
        }
        Some(m)
    }

    /// `d^(du + dv) P / du^du dv^dv` at `(u, v)` of sector `i`'s cell, in
    /// the cap's parameters; `None` where not covered.
    pub fn eval(&self, i: usize, u: f64, v: f64, du: usize, dv: usize) -> Option<Point> {
        let m = self.level_of(u, v)?;
        let f = (1u64 << m) as f64;
        let (uu, vv) = (u * f, v * f);
        let net = &self.nets[m];
        let p = if vv < 1.0 {
            eval_bspline(&net.grid_u(i), uu - 1.0, vv, du, dv)
        } else if uu < 1.0 {
            eval_bspline(&net.grid_v(i), uu, vv - 1.0, du, dv)
        } else {
            eval_bspline(&net.grid_corner(i), uu - 1.0, vv - 1.0, du, dv)
        };
        let g = f.powi((du + dv) as i32);
        Some([p[0] * g, p[1] * g, p[2] * g])
    }

    /// Gaussian and mean curvature `(K, H)` at `(u, v)` of sector `i` (the
    /// normal `P_u x P_v / |P_u x P_v|`, as the cap's).
    pub fn curvature_at(&self, i: usize, u: f64, v: f64) -> Option<(f64, f64)> {
        let d = [
            self.eval(i, u, v, 1, 0)?,
            self.eval(i, u, v, 0, 1)?,
            self.eval(i, u, v, 2, 0)?,
            self.eval(i, u, v, 1, 1)?,
            self.eval(i, u, v, 0, 2)?,
        ];
        shape(&d).map(|(_, k, h)| (k, h))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_cover_the_rings_and_refuse_bad_arguments() {
        let ring = TwoRing::random(4 + 1, 3).unwrap();
        let s = PlainSurface::new(&ring, 0.5, 4).unwrap();
        assert_eq!(s.level_of(1.0, 0.0), Some(1));
        assert_eq!(s.level_of(0.5, 0.2), Some(1));
        assert_eq!(s.level_of(0.49, 0.2), Some(2));
        assert_eq!(s.level_of(0.0625, 0.0), Some(4));
        assert_eq!(s.level_of(0.06, 0.0), None);
        assert_eq!(s.level_of(1.1, 0.0), None);
        assert!(PlainSurface::new(&ring, 0.5, 0).is_err());
        assert!(PlainSurface::new(&ring, 0.5, MAX_LEVELS + 1).is_err());
        assert!(PlainSurface::new(&ring, 1.5, 3).is_err());
    }
}
