//! Householder reduction to upper Hessenberg form (the scalar kernel; the
//! lock-step version is in `lockstep`).

/// Householder reduction of the column-major `n x n` matrix `h` to upper
/// Hessenberg form, in place (entries below the subdiagonal are zeroed).
/// `v` and `w` are scratch vectors of length `n`. All inner loops run over
/// contiguous column slices.
pub(crate) fn hessenberg(n: usize, h: &mut [f64], v: &mut [f64], w: &mut [f64]) {
    if n < 3 {
        return;
    }
    for k in 0..n - 2 {
        let col = &h[k * n + k + 1..(k + 1) * n];
        let scale = col.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if scale == 0.0 {
            continue;
        }
        let vk = &mut v[k + 1..n];
        let mut norm2 = 0.0;
        // Scaling by a power of two would be exact; by 1/scale it rounds once
        // more than x / scale, which is immaterial for a reflector.
        let inv_scale = 1.0 / scale;
        for (vi, x) in vk.iter_mut().zip(col) {
            let t = x * inv_scale;
            *vi = t;
            norm2 += t * t;
        }
        let x0 = vk[0];
        let alpha = -x0.signum() * norm2.sqrt();
        vk[0] = x0 - alpha;
        let vtv = norm2 - x0 * x0 + vk[0] * vk[0];
        if vtv == 0.0 {
            continue;
        }
        let beta = 2.0 / vtv;
        // Left: rows k+1..n, columns k+1..n (column k is set explicitly).
        for j in k + 1..n {
            let cj = &mut h[j * n + k + 1..(j + 1) * n];
            let s: f64 = cj.iter().zip(vk.iter()).map(|(x, y)| x * y).sum::<f64>() * beta;
            for (x, y) in cj.iter_mut().zip(vk.iter()) {
                *x -= s * y;
            }
        }
        h[k + 1 + k * n] = alpha * scale;
        for x in &mut h[k * n + k + 2..(k + 1) * n] {
            *x = 0.0;
        }
        // Right: all rows, columns k+1..n: w = H v, H -= beta w v^T.
        let w = &mut w[..n];
        w.iter_mut().for_each(|x| *x = 0.0);
        for (j, &vj) in (k + 1..n).zip(vk.iter()) {
            let cj = &h[j * n..(j + 1) * n];
            for (wi, x) in w.iter_mut().zip(cj) {
                *wi += x * vj;
            }
        }
        for (j, &vj) in (k + 1..n).zip(vk.iter()) {
            let f = beta * vj;
            let cj = &mut h[j * n..(j + 1) * n];
            for (x, wi) in cj.iter_mut().zip(w.iter()) {
                *x -= wi * f;
            }
        }
    }
}
