//! The lines of the human-readable `analyze` summaries that interior and
//! boundary, crease and corner vertices share: eigenvalues in the same
//! format, and the subdominant pair's line.

use subdiv_lab::spectral::Subdominant;

/// `re` with ten decimals, or `re +- im i` for a complex value.
fn cplx(z: [f64; 2]) -> String {
    if z[1] == 0.0 {
        format!("{:.10}", z[0])
    } else {
        format!(
            "{:.10} {} {:.10}i",
            z[0],
            if z[1] < 0.0 { "-" } else { "+" },
            z[1].abs()
        )
    }
}

/// `leading eigenvalues:` and the first six of `eigenvalues`, with its newline.
pub(crate) fn leading_eigenvalues(eigenvalues: &[[f64; 2]]) -> String {
    let mut out = "leading eigenvalues:".to_owned();
    for z in eigenvalues.iter().take(6) {
        out += &format!("  {}", cplx(*z));
    }
    out.push('\n');
    out
}

/// `  lambda1 = .., lambda2 = .., |lambda3| = .., gap = ..`, with its newline.
pub(crate) fn subdominant_pair(s: &Subdominant) -> String {
    format!(
        "  lambda1 = {}, lambda2 = {}, |lambda3| = {:.10}, gap = {:.3e}\n",
        cplx([s.lambda1.re, s.lambda1.im]),
        cplx([s.lambda2.re, s.lambda2.im]),
        s.abs_lambda3,
        s.gap
    )
}
