//! Certified class over intervals of `c` for the shape-adjustable
//! Catmull-Clark scheme (math doc sections 6, 8 and 15).
//!
//! The one-ring matrix is block diagonal in the Fourier basis (math doc
//! section 6, [`crate::schemes::catmull_clark::fourier`]): for `l >= 1` a
//! 2 x 2 block with trace `t_l = 3/4 - (c/4)(1 - cos(2 pi l / n))` and
//! determinant `d = (1 - c)/8`; for `l = 0` the eigenvalue `1` and the roots
//! of `x^2 - T x + D`, `T = (3n - 16c + 4c^2)/(4n)`,
//! `D = (n(1 - c) - 8c + 12c^2 - 4c^3)/(8n)`. All of them are evaluated in
//! interval arithmetic over the cell.
//!
//! **standard** is certified when the larger root `lambda_+` of block `l = 1`
//! (equal to that of block `n - 1`, whose `cos` is the same) is real and
//! simple in its block (discriminant `> 0`), and exceeds the modulus bound
//! `|t|/2 + sqrt(|t^2/4 - d|)` of every other root, and the `l = 0` roots lie
//! inside the unit circle. The double eigenvalue then has two independent
//! eigenvectors (from two different Fourier blocks), so it is semisimple.

use super::decide::Status;
use super::interval::{down, up, Iv};
use crate::spectral::ClassName;

/// Slack added on both sides of `cos(2 pi l / n)` as computed by the
/// platform's `cos`: the argument carries at most a few ulps of error
/// (`< 1e-15` for arguments up to `2 pi`), and `cos` is accurate to 1-2 ulps
/// on the supported platforms (glibc documents at most 1 ulp for `cos` on
/// x86-64); `1e-14` covers both with a factor of five. This is the one
/// assumption of the c-path not reduced to IEEE round-to-nearest.
pub const COS_SLACK: f64 = 1e-14;

/// Upper bound of `|x|` over the roots of `x^2 - t x + d` for `t, d` in the intervals.
fn root_modulus_upper(t: Iv, d: Iv) -> f64 {
    let half = t.mul(Iv::point(0.5));
    let disc = half.mul(half).sub(d);
    up(half.mag() + up(disc.mag().sqrt()))
}

/// Verdicts `(separation, class)` of the adjustable scheme of valence `n`
/// over `c` in `[lo, hi]`.
///
/// ```
/// use subdiv_lab::verify::cc::verdict;
/// use subdiv_lab::verify::decide::Status;
/// use subdiv_lab::spectral::ClassName;
/// let (s, c) = verdict(5, 0.49, 0.51);
/// assert_eq!((s, c), (Status::Certified, Some(ClassName::Standard)));
/// ```
pub fn verdict(n: usize, lo: f64, hi: f64) -> (Status, Option<ClassName>) {
    let undecided = (Status::Undecided, None);
    if n < 3 || !(lo <= hi) {
        return undecided;
    }
    let c = Iv::new(lo, hi);
    let nf = Iv::point(n as f64);
    let eighth = Iv::point(0.125);
    let quarter = Iv::point(0.25);
    let d = Iv::point(1.0).sub(c).mul(eighth);
    let block = |l: usize| -> (Iv, Iv) {
        let theta = 2.0 * std::f64::consts::PI * l as f64 / n as f64;
        let cs = theta.cos();
        let cos = Iv::new(down(cs - COS_SLACK), up(cs + COS_SLACK));
        let t = Iv::point(0.75).sub(c.mul(quarter).mul(Iv::point(1.0).sub(cos)));
        (t, d)
    };
    // lambda_+ of l = 1, lower bound
    let (t1, d1) = block(1);
    let h1 = t1.mul(Iv::point(0.5));
    let disc1 = h1.mul(h1).sub(d1);
    if !(disc1.lo > 0.0) {
        return undecided;
    }
    let lam_lower = down(h1.lo + down(disc1.lo.sqrt()));
    // every other root
    let mut upper = 0.0f64;
    // the smaller root of l = 1 (and l = n - 1): t/2 - sqrt(disc)
    let small = Iv::new(
        down(h1.lo - up(disc1.hi.sqrt())),
        up(h1.hi - down(disc1.lo.sqrt())),
    );
    upper = upper.max(small.mag());
    for l in 2..=n / 2 {
        let (t, d) = block(l);
        upper = upper.max(root_modulus_upper(t, d));
    }
    // l = 0
    let cc = c.mul(c);
    let big_t = Iv::point(3.0)
        .mul(nf)
        .sub(Iv::point(16.0).mul(c))
        .add(Iv::point(4.0).mul(cc))
        .mul(Iv::point(0.25));
    let big_t = Iv::new(down(big_t.lo / n as f64), up(big_t.hi / n as f64));
    let big_d = nf
        .mul(Iv::point(1.0).sub(c))
        .sub(Iv::point(8.0).mul(c))
        .add(Iv::point(12.0).mul(cc))
        .sub(Iv::point(4.0).mul(cc.mul(c)))
        .mul(eighth);
    let big_d = Iv::new(down(big_d.lo / n as f64), up(big_d.hi / n as f64));
    let zero_upper = root_modulus_upper(big_t, big_d);
    if !(zero_upper < 1.0) || upper.is_nan() || zero_upper.is_nan() {
        return undecided;
    }
    upper = upper.max(zero_upper);
    if lam_lower > upper && lam_lower > 0.0 {
        (Status::Certified, Some(ClassName::Standard))
    } else {
        undecided
    }
}
