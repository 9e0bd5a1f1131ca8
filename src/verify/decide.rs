//! From enclosing discs to verdicts over a cell (math doc section 15).
//!
//! The discs enclose the non-unit eigenvalues of the face block; the rest of
//! the spectrum of `S_n` is `1` (simple when every disc lies inside the unit
//! circle) and the fixed `1/4, 1/8, 1/16` (`n` times each, math doc section 4).
//! Overlapping discs are merged into components; a component of `k` discs
//! contains exactly `k` eigenvalues.

use super::interval::Disc;
use crate::spectral::ClassName;

/// Modulus of the largest fixed eigenvalue of `S_n` (the `E` blocks' `1/4`,
/// `n >= 3` times).
pub const FIXED_MODULUS: f64 = 0.25;

/// What is proven about one property over a cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Holds for every parameter in the cell.
    Certified,
    /// Fails for every parameter in the cell.
    Refuted,
    /// Neither proven (or not attempted for this scheme).
    Undecided,
    /// Not evaluated: the cell does not meet the fundamental domain of the
    /// spec's symmetry group ([`super::symmetry`]); what holds on it follows
    /// from the cells that meet the domain, through the group.
    BySymmetry,
}

impl Status {
    /// The CSV/JSON word.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Certified => "certified",
            Status::Refuted => "refuted",
            Status::Undecided => "undecided",
            Status::BySymmetry => "by_symmetry",
        }
    }
}

/// The spectral verdicts of one set of discs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpectralVerdict {
    /// `|lambda_2| > |lambda_3|` (including the fixed `1/4`) and `lambda_0 = 1` simple.
    pub separation: Status,
    /// The subdominant class when proven constant on the cell.
    pub class: Option<ClassName>,
}

const UNDECIDED: SpectralVerdict = SpectralVerdict {
    separation: Status::Undecided,
    class: None,
};

fn components(discs: &[Disc]) -> Vec<Vec<usize>> {
    let m = discs.len();
    let mut parent: Vec<usize> = (0..m).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for i in 0..m {
        for j in i + 1..m {
            if !discs[i].disjoint(&discs[j]) {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut root_of: Vec<Option<usize>> = vec![None; m];
    for i in 0..m {
        let r = find(&mut parent, i);
        match root_of[r] {
            Some(g) => groups[g].push(i),
            None => {
                root_of[r] = Some(groups.len());
                groups.push(vec![i]);
            }
        }
    }
    groups
}

/// Decides separation and class from one set of enclosing discs.
///
/// ```
/// use subdiv_lab::verify::decide::{decide, Status};
/// use subdiv_lab::verify::interval::Disc;
/// use subdiv_lab::spectral::ClassName;
/// let d = |re, im| Disc { re, im, radius: 0.01 };
/// let v = decide(&[d(0.4, 0.1), d(0.4, -0.1)]);
/// assert_eq!((v.separation, v.class), (Status::Certified, Some(ClassName::ComplexPair)));
/// let v = decide(&[d(0.5, 0.0), d(0.3, 0.0), d(0.1, 0.0)]);
/// assert_eq!(v.class, Some(ClassName::RealDistinct));
/// let v = decide(&[d(0.5, 0.0), d(0.2, 0.0)]);
/// assert_eq!((v.separation, v.class), (Status::Refuted, Some(ClassName::NotSeparated)));
/// ```
pub fn decide(discs: &[Disc]) -> SpectralVerdict {
    if discs
        .iter()
        .any(|d| !(d.re.is_finite() && d.im.is_finite() && d.radius.is_finite()))
    {
        return UNDECIDED;
    }
    // lambda_0 = 1 simple: every non-unit eigenvalue inside the unit circle
    if !discs.iter().all(|d| d.max_modulus() < 1.0) {
        return UNDECIDED;
    }
    let comps = components(discs);
    let min_mod = |c: &[usize]| {
        c.iter()
            .map(|&i| discs[i].min_modulus())
            .fold(f64::INFINITY, f64::min)
    };
    let max_mod = |c: &[usize]| {
        c.iter()
            .map(|&i| discs[i].max_modulus())
            .fold(0.0, f64::max)
    };
    // every component strictly above or strictly below the fixed 1/4
    let mut above: Vec<&Vec<usize>> = Vec::new();
    for c in &comps {
        if min_mod(c) > FIXED_MODULUS {
            above.push(c);
        } else if !(max_mod(c) < FIXED_MODULUS) {
            return UNDECIDED;
        }
    }
    let count_above: usize = above.iter().map(|c| c.len()).sum();
    if count_above <= 1 {
        // |lambda_2| = |lambda_3| = 1/4 (the fixed eigenvalue, n >= 3 times)
        return SpectralVerdict {
            separation: Status::Refuted,
            class: Some(ClassName::NotSeparated),
        };
    }
    // the two largest: components by decreasing lower modulus until count 2
    let mut order: Vec<&Vec<usize>> = comps.iter().collect();
    order.sort_by(|a, b| min_mod(b).total_cmp(&min_mod(a)));
    let mut count = 0;
    let mut top = 0;
    while count < 2 {
        count += order[top].len();
        top += 1;
    }
    if count != 2 {
        return UNDECIDED;
    }
    let lower_top = order[..top]
        .iter()
        .map(|c| min_mod(c))
        .fold(f64::INFINITY, f64::min);
    let upper_rest = order[top..]
        .iter()
        .map(|c| max_mod(c))
        .fold(FIXED_MODULUS, f64::max);
    if !(lower_top > upper_rest) {
        return UNDECIDED;
    }
    let separation = Status::Certified;
    if top != 2 {
        // one component holding both: real or complex cannot be told apart
        return SpectralVerdict {
            separation,
            class: None,
        };
    }
    let (i, j) = (order[0][0], order[1][0]);
    let (a, b) = (discs[i], discs[j]);
    // a lone non-real eigenvalue: its conjugate has the same modulus, so it is the other one
    if a.off_real_axis() || b.off_real_axis() {
        return SpectralVerdict {
            separation,
            class: Some(ClassName::ComplexPair),
        };
    }
    // real: the mirror of the disc meets no other disc, so the conjugate of
    // its only eigenvalue lies in it, hence equals it
    let is_real = |k: usize| {
        let mirror = discs[k].conj();
        discs
            .iter()
            .enumerate()
            .all(|(l, d)| l == k || mirror.disjoint(d))
    };
    if is_real(i) && is_real(j) && a.right_half_plane() && b.right_half_plane() {
        return SpectralVerdict {
            separation,
            class: Some(ClassName::RealDistinct),
        };
    }
    SpectralVerdict {
        separation,
        class: None,
    }
}

/// The better of the row and column verdicts (each alone is sound; they
/// cannot contradict each other, since both enclose the same eigenvalues).
pub fn decide_either(rows: &[Disc], cols: &[Disc]) -> SpectralVerdict {
    let a = decide(rows);
    if a.class.is_some() && a.separation != Status::Undecided {
        return a;
    }
    let b = decide(cols);
    let score = |v: &SpectralVerdict| {
        usize::from(v.class.is_some()) + usize::from(v.separation != Status::Undecided)
    };
    if score(&b) > score(&a) {
        b
    } else {
        a
    }
}
