use subdiv_lab::curvature::tuning::tune;
use subdiv_lab::schemes::catmull_clark::fourier;
fn main() {
    for n in 3..=16 {
        let t = tune(n, 128).unwrap();
        for r in &t.roots { println!("n={n} root [{:.11}, {:.11}] {:?}->{:?}", r.c_lo, r.c_hi, r.below, r.above); }
        // where c/4 exceeds the one-ring mu
        let mut first = None;
        for j in 0..=1000 { let c = j as f64/1000.0; let s = fourier::spectrum(n, c).unwrap(); if c/4.0 > s[3].norm() + 1e-12 && first.is_none() { first = Some(c); } }
        println!("n={n} c/4 > one-ring mu from c = {:?}", first);
    }
}
