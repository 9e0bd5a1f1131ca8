//! `analyze` and `matrix` at a boundary, crease or corner vertex
//! (`--vertex`): work estimate, analysis, text and JSON output.

use super::spectrum_text::{leading_eigenvalues, subdominant_pair};
use super::{write_stdout, CliError, CliResult};
use subdiv_lab::boundary::analysis::sector_json;
use subdiv_lab::boundary::analysis::{analyze_sector, SectorAnalysis};
use subdiv_lab::boundary::SectorConfig;
use subdiv_lab::budget::{CostModel, Estimate};

/// The sector's cost model: a dense matrix of [`SectorConfig::dimension`]
/// rows, written per edge at the vertex.
fn cost_model(c: &SectorConfig) -> CostModel {
    let n = c.edge_count().max(1) as f64;
    CostModel::dense(c.dimension() as f64 / n, 0.0)
}

/// The work estimate of `analyze --vertex`.
fn analyze_estimate(c: &SectorConfig) -> Estimate {
    subdiv_lab::budget::analyze(&cost_model(c), c.edge_count(), false)
}

/// The work estimate of `matrix --vertex`.
pub(crate) fn matrix_estimate(c: &SectorConfig) -> Estimate {
    subdiv_lab::budget::matrix(&cost_model(c), c.edge_count(), false, false)
}

/// `analyze --vertex ...`.
pub(crate) fn analyze(c: &SectorConfig, json: bool, force: bool) -> CliResult {
    super::budget::check(
        "analyze",
        &c.describe(),
        &analyze_estimate(c),
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        force,
    )?;
    let a = analyze_sector(c).map_err(CliError::lib)?;
    let text = if json {
        serde_json::to_string_pretty(&sector_json(&a, c)).map_err(CliError::failure)? + "\n"
    } else {
        summary(c, &a)
    };
    write_stdout(text.as_bytes())
}

/// `x` with eight decimals, a value that rounds to zero printed as `0`
/// (no `-0.00000000` for rounding noise of either sign).
fn fixed8(x: f64) -> String {
    let s = format!("{x:.8}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0.00000000".to_owned()
    } else {
        s
    }
}

fn yes_no(x: Option<bool>) -> &'static str {
    match x {
        Some(true) => "yes",
        Some(false) => "no",
        None => "undecided",
    }
}

/// Human-readable summary.
fn summary(c: &SectorConfig, a: &SectorAnalysis) -> String {
    let cc = c.dimension() > 1 + c.edge_count();
    let points = format!(
        "v, e_0..e_{}{}",
        c.edge_count() - 1,
        if cc {
            format!(", f_0..f_{}", c.face_count() - 1)
        } else {
            String::new()
        }
    );
    let [sa, sb] = c.sharp_edges();
    let mut out = format!(
        "{} ({} x {} matrix on {points}; sharp edges e_{sa}, e_{sb})\n",
        a.configuration, a.dimension, a.dimension
    );
    out += &leading_eigenvalues(&a.eigenvalues);
    out += &format!(
        "  spectrum vs closed form (sharp-edge block and sine modes): max difference {:.1e}\n",
        a.closed_form_deviation
    );
    let s = &a.subdominant;
    out += &format!("subdominant class: {}", s.class.name());
    if let subdiv_lab::spectral::SubdominantClass::Indeterminate { between, reason } = &s.class {
        out += &format!(
            " (between {} and {}: {reason})",
            between.0.as_str(),
            between.1.as_str()
        );
    }
    if let Some(note) = s.note {
        out += &format!(" ({note})");
    }
    out.push('\n');
    out += &subdominant_pair(s);
    out += &format!(
        "  eigenvalue of the sharp-edge block (1/2, 1/4 or the corner's 1/2): lambda1 {}, lambda2 {}\n",
        yes_no(a.charmap.on_sharp_edges[0]),
        yes_no(a.charmap.on_sharp_edges[1])
    );
    out += &format!(
        "characteristic map: {} ({})\n",
        a.charmap.verdict.as_str(),
        a.charmap.reason
    );
    if let (Some(m), Some(e)) = (a.charmap.min_jacobian_coeff, a.charmap.point_error) {
        out += &format!(
            "  ring of {} {} patches: min Jacobian coefficient {m:.3e} (relative), control-point error bound {e:.1e}\n",
            12 * c.face_count(),
            if cc { "bicubic" } else { "quartic triangular" }
        );
    }
    out += &format!("limit stencil ({points}):");
    for &x in &a.limit_stencil {
        out += &format!(" {}", fixed8(x));
    }
    out.push('\n');
    out += &format!(
        "  left eigenvector for 1 vs closed-form mask: max difference {:.2e}\n",
        a.limit_stencil_error
    );
    for (k, t) in a.tangent_stencils.iter().enumerate() {
        out += &format!("tangent stencil {}:", k + 1);
        for &x in t {
            out += &format!(" {}", fixed8(x));
        }
        out.push('\n');
    }
    out += &a.curvature.human_line();
    out
}
