//! `subdiv-lab analyze`: spectrum, subdominant class, Theorem 1 and the
//! characteristic-map verdict for one configuration.

use super::scheme_args::SchemeArgs;
use super::sector_args::{InteriorFlags, SectorArgs};
use super::spectrum_text::{leading_eigenvalues, subdominant_pair};
use super::{write_stdout, CliError, CliResult};
use clap::{Args, ValueEnum};
use subdiv_lab::charmap;
use subdiv_lab::contraction::MeasureOptions;
use subdiv_lab::schemes::SpectralStructure;
use subdiv_lab::schemes::{PointLabel, Role};
use subdiv_lab::spectral::{
    analyze, AnalyzeOptions, BoundCheck, LocalAnalysis, SpectrumPath, SubdominantClass,
};

#[derive(Args, Debug)]
pub(crate) struct AnalyzeArgs {
    #[command(flatten)]
    scheme: SchemeArgs,
    #[command(flatten)]
    sector: SectorArgs,
    /// Print the full result as JSON.
    #[arg(long)]
    json: bool,
    /// Add exact verdicts (characteristic polynomial, Sturm and Schur-Cohn counts,
    /// exact Theorem 1 certificate) computed from the exact value of the input.
    #[arg(long)]
    exact: bool,
    /// Spectrum path: full 4n x 4n decomposition (with vectors) or structured.
    #[arg(long, value_enum, default_value_t = Path::Full)]
    path: Path,
    /// Subdivision levels of the measured contraction.
    #[arg(long, default_value_t = 60)]
    levels: usize,
    /// Seed of the random control points of the measured contraction.
    #[arg(long, default_value_t = 0x5EED)]
    seed: u64,
    /// Run even when the estimated memory or time exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
    /// Characteristic-map certificate: `ring` (the scheme's ring of patches)
    /// or `generic` (any vertex-centred scheme, from its local matrix and its
    /// regular rules; docs/guide/is-it-c1.md).
    #[arg(long, value_enum, default_value_t = CharmapMethod::Ring)]
    charmap: CharmapMethod,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CharmapMethod {
    Ring,
    Generic,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Path {
    Full,
    Structured,
}

pub(crate) fn run(args: AnalyzeArgs) -> CliResult {
    let interior = [
        ("--valence", args.scheme.valence.is_some()),
        ("--knots", args.scheme.knots.is_some()),
        ("--ratios", args.scheme.ratios.is_some()),
        ("--uniform", args.scheme.uniform),
        ("--c", args.scheme.c.is_some()),
        ("--scheme-file", args.scheme.scheme_file.is_some()),
        ("--exact", args.exact),
        ("--path structured", matches!(args.path, Path::Structured)),
        ("--charmap generic", args.charmap == CharmapMethod::Generic),
    ];
    if let Some(c) = args
        .sector
        .resolve(&args.scheme.scheme, InteriorFlags { given: &interior })?
    {
        return super::sector::analyze(&c, args.json, args.force);
    }
    subdiv_lab::contraction::check_levels(args.levels, subdiv_lab::budget::Spelling::Cli)
        .map_err(super::budget::usage)?;
    if args.exact && args.scheme.scheme_file.is_some() {
        return Err(CliError::usage(anyhow::anyhow!(
            "--exact is not available with --scheme-file (the exact verdicts take a built-in configuration; `matrix --exact` prints a rational file's exact matrix)"
        )));
    }
    let resolved = args.scheme.resolve(args.exact)?;
    let n = resolved.scheme.valence();
    let estimate = subdiv_lab::budget::analyze(
        &resolved.scheme.cost_model(),
        n,
        matches!(args.path, Path::Structured),
    );
    super::budget::check(
        "analyze",
        &format!("valence {n}"),
        &estimate,
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )?;
    if args.charmap == CharmapMethod::Generic {
        super::budget::check(
            "analyze --charmap generic",
            &format!("valence {n}"),
            &charmap::generic::estimate(&*resolved.scheme),
            subdiv_lab::budget::TIME_LIMIT_SECONDS,
            args.force,
        )?;
    }
    if let Some(exact) = &resolved.exact {
        super::budget::check(
            "analyze --exact",
            &format!("valence {n}"),
            &subdiv_lab::budget::analyze_exact(n, exact.parameter_bits()),
            subdiv_lab::budget::TIME_LIMIT_SECONDS,
            args.force,
        )?;
    }
    let options = AnalyzeOptions {
        path: match args.path {
            Path::Full => SpectrumPath::Full,
            Path::Structured => SpectrumPath::Structured,
        },
        measure: MeasureOptions {
            levels: args.levels,
            seed: args.seed,
            ..MeasureOptions::default()
        },
    };
    let mut result = analyze(&*resolved.scheme, &options).map_err(CliError::lib)?;
    if let Some(exact) = &resolved.exact {
        result
            .add_exact(exact)
            .map_err(|e| match CliError::lib(e) {
                usage @ CliError::Usage(_) => usage.context(format!(
                    "--exact is not available for --scheme {}",
                    args.scheme.scheme
                )),
                failure => failure,
            })?;
    }
    // Characteristic map (math doc sections 7 and 20); a numerical failure
    // there is reported inside the "charmap" object, not as a failure of the
    // analysis.
    let method = match args.charmap {
        CharmapMethod::Ring => charmap::Method::Ring,
        CharmapMethod::Generic => charmap::Method::Generic,
    };
    let certificate = charmap::certify(method, &*resolved.scheme, &result.charmap_subdominant());
    let charmap_value = certificate.json();
    let charmap_text = match &certificate {
        charmap::Certificate::Ring(c) => charmap_summary(c),
        charmap::Certificate::Generic(g) => generic_summary(g),
    };
    if args.json {
        let value =
            subdiv_lab::spectral::json::analysis_json(&result, charmap_value, &resolved.input);
        let text = serde_json::to_string_pretty(&value).map_err(CliError::failure)? + "\n";
        write_stdout(text.as_bytes())?;
    } else {
        let lm = resolved.scheme.local_matrix().map_err(CliError::lib)?;
        let m = MatrixText::of(lm.rows(), n, resolved.scheme.spectral_structure());
        let mut text = summary(&result, &m);
        text += &charmap_text;
        write_stdout(text.as_bytes())?;
    }
    Ok(())
}

/// Human-readable lines of the generic certificate.
fn generic_summary(g: &subdiv_lab::Result<charmap::generic::GenericReport>) -> String {
    let r = match g {
        Ok(r) => r,
        Err(e) => return format!("characteristic map (generic): not computed ({e})\n"),
    };
    let mut out = format!("characteristic map (generic): {}\n", r.verdict);
    if let Some(k) = r.matrix_steps {
        out += &format!("  of the {k}-step local matrix (one step turns the ring)\n");
    }
    if let Some(level) = r.level {
        let opt = |x: Option<i64>| x.map_or("undecided".to_owned(), |w| w.to_string());
        out += &format!(
            "  {} cells tested down to level {level}; orientation {}; winding number {}; point error {:.1e}\n",
            r.cells,
            opt(r.orientation.map(i64::from)),
            opt(r.winding_number),
            r.point_error.unwrap_or(f64::NAN)
        );
    }
    if let Some(e) = &r.class_proof {
        out += &format!(
            "  class proven exactly: lambda in [{:.10}, {:.10}], every other eigenvalue but 1 of modulus at most {}\n",
            e.lambda[0], e.lambda[1], e.threshold
        );
    }
    out
}

/// Human-readable characteristic-map lines.
fn charmap_summary(c: &subdiv_lab::Result<charmap::CharmapReport<charmap::AnyPatchId>>) -> String {
    let r = match c {
        Ok(r) => r,
        Err(e) => return format!("characteristic map: not computed ({e})\n"),
    };
    let mut out = format!("characteristic map: {}\n", r.verdict);
    if let Some(g) = &r.regularity {
        out += &format!(
            "  Jacobian: {} (min {} {:.6e} relative to the largest, at {} s={:.3} t={:.3}; error bound {:.1e}; {} pieces, depth {})\n",
            g.verdict.as_str(),
            g.coefficients.describe(),
            g.min_coeff,
            g.min_location.patch,
            g.min_location.s,
            g.min_location.t,
            g.relative_error_bound,
            g.pieces,
            g.max_depth
        );
        if let Some((p, v)) = g.witness {
            out += &format!(
                "  wrong-sign Jacobian {v:.6e} (relative) at {} s={:.6} t={:.6}\n",
                p.patch, p.s, p.t
            );
        }
        let w = |x: Option<i64>| x.map_or("undecided".to_owned(), |w| w.to_string());
        out += &format!(
            "  winding number of the boundary around the origin: outer {}, inner {}\n",
            w(r.winding_number),
            w(r.inner_winding_number)
        );
    }
    out
}

/// Human-readable summary.
/// How the local matrix is described in the summary: the centre (`face` or
/// `vertex`), the full path's matrix and the structured path's method, from
/// the matrix's labels and the scheme's spectral structure.
struct MatrixText {
    vertex: bool,
    full: String,
    structured: &'static str,
    stencil: String,
}

impl MatrixText {
    fn of(labels: &[PointLabel], n: usize, structure: SpectralStructure) -> Self {
        let vertex = labels.first().is_some_and(|l| l.role == Role::Vertex);
        let d = labels.len();
        // the size as `a n + b` (`b < n`): `4n x 4n` around a face, `(2n+1)
        // one-ring` / `(3n+1) two-ring` around a vertex (by the labels' roles)
        let (a, b) = (d / n.max(1), d % n.max(1));
        let two_ring = labels.iter().any(|l| l.role == Role::SecondRing);
        let three_ring = labels.iter().any(|l| l.role == Role::OuterRing);
        let full = if !vertex && b == 0 && a > 0 {
            format!("full {a}n x {a}n")
        } else if vertex && a > 0 && b > 0 {
            let ring = if three_ring {
                "three-ring"
            } else if two_ring {
                "two-ring"
            } else {
                "one-ring"
            };
            format!("full ({a}n+{b}) {ring}")
        } else {
            format!("full {d} x {d}")
        };
        let structured = match structure {
            SpectralStructure::Fourier => "Fourier blocks",
            _ => "structured",
        };
        // the points' roles in order of first appearance: "v, e_0.., f_0.."
        let mut roles: Vec<String> = Vec::new();
        let mut seen = Vec::new();
        for l in labels {
            if !seen.contains(&l.role) {
                seen.push(l.role);
                let text = l.to_string();
                let stem = text.trim_end_matches(|c: char| c.is_ascii_digit() || c == ',');
                roles.push(if l.role == Role::Vertex {
                    text
                } else {
                    format!("{stem}_0..")
                });
            }
        }
        Self {
            vertex,
            full,
            structured,
            stencil: roles.join(", "),
        }
    }
}

fn summary(a: &LocalAnalysis, m: &MatrixText) -> String {
    let s = &a.subdominant;
    let cc = a.face_weights.is_empty();
    let mut out = format!(
        "{} around an n = {} {} ({} path, {} eigenvalues)\n",
        a.scheme,
        a.valence,
        if m.vertex { "vertex" } else { "face" },
        match a.path {
            SpectrumPath::Full => &m.full,
            SpectrumPath::Structured => m.structured,
        },
        a.eigenvalues.len()
    );
    if let Some(st) = &a.steps {
        out += &format!(
            "local matrix: {} subdivision steps (one step turns the ring); every verdict below refers to the {}-step matrix\n",
            st.matrix_steps, st.matrix_steps
        );
        out += &format!(
            "one-step matrix, {}",
            leading_eigenvalues(&st.one_step_eigenvalues)
        );
    }
    out += &leading_eigenvalues(&a.eigenvalues);
    out += &format!("subdominant class: {}", s.class.name());
    match &s.class {
        SubdominantClass::Indeterminate { between, reason } => {
            out += &format!(
                " (between {} and {}: {reason})",
                between.0.as_str(),
                between.1.as_str()
            );
        }
        SubdominantClass::RealDistinct | SubdominantClass::ComplexPair => {
            out += " -> tangent-plane continuity test applies (non-standard eigenstructure)";
        }
        _ => {}
    }
    if let Some(note) = s.note {
        out += &format!(" ({note})");
    }
    out.push('\n');
    out += &subdominant_pair(s);
    if let Some(full) = &a.subdominant_full {
        if full.class != s.class {
            out += &format!(
                "  (full 4n x 4n matrix alone: {}; the structured verdict uses the exactly known E/C eigenvalues)\n",
                full.class.name()
            );
        }
    }
    if let Some(r) = s.ratio {
        out += &format!("  lambda2 / lambda1 = {r:.10}\n");
    }
    if let (Some(rho), Some(theta)) = (s.rho, s.theta) {
        out += &format!("  rho = {rho:.10}, theta = {theta:.10} rad\n");
    }
    if cc {
        if let Some(w) = &a.limit_weights {
            out += &format!("limit stencil ({}):", m.stencil);
            for x in w {
                out += &format!(" {x:.8}");
            }
            out.push('\n');
        }
        if let Some(e) = a.limit_weights_error {
            out += &format!(
                "  left eigenvector for 1 vs closed-form limit stencil: max difference {e:.2e}\n"
            );
        }
        if let Some(d) = a.fourier_deviation {
            out += &format!("  spectrum vs closed-form Fourier blocks: max difference {d:.2e}\n");
        }
    } else {
        out += "face weights c:";
        for w in &a.face_weights {
            out += &format!(" {w:.8}");
        }
        out.push('\n');
        if let Some(e) = a.limit_weights_error {
            out += &format!("  left eigenvector for 1 vs (c, 0): max difference {e:.2e}\n");
        }
    }
    if let Some(c) = &a.contraction {
        out += &format!(
        "Theorem 1: certificate {} (weights from the knots >= 0: {}, smallest positive {:.3e}; row sums 3/4 to {:.1e}); spectral bound |lambda1| = {} (error radius {:.1e}): {}\n",
        if c.certificate_holds { "holds" } else { "FAILS" },
        c.certificate_nonnegative,
        c.certificate_min_weight,
        c.certificate_sum_defect,
        c.spectral_bound,
        c.spectral_bound_radius,
        match c.spectral_bound_check {
            BoundCheck::Holds => "< 3/4",
            BoundCheck::Indeterminate => "indeterminate against 3/4 (within its error radius)",
            BoundCheck::Violated => "> 3/4 (violated)",
        }
    );
        out += &format!(
        "  measured over {} levels: max per-step ratio {:.6}, fitted rate {:.6} (|lambda1| = {:.6}, bound 0.75)\n",
        c.measured_distances.len().saturating_sub(1),
        c.measured_max_ratio,
        c.measured_rate,
        c.spectral_bound
    );
    }
    out += &a.curvature.human_line();
    if let Some(x) = &a.exact {
        out += &format!(
            "exact: class {} ({}); 1 simple: {}; {} distinct real roots of p(x)/(x-1); |lambda| < 3/4: {}; Theorem 1 certificate exact: {}",
            x.class.map(|c| c.as_str()).unwrap_or("undecided"),
            x.reason,
            x.one_is_simple,
            x.real_root_count,
            match x.spectral_bound_below_three_quarters {
                Some(true) => "yes",
                Some(false) => "no",
                None => "undecided",
            },
            x.theorem1_certificate
        );
        if let Some(agree) = x.agrees_with_float {
            out += &format!("; agrees with float: {agree}");
        } else if let (Some(e), SubdominantClass::Indeterminate { between, .. }) =
            (x.class, &a.subdominant.class)
        {
            // The float verdict was indeterminate: the exact class settles it
            // when it is one of the two candidates.
            if e == between.0 || e == between.1 {
                out += &format!(
                    "; float indeterminate between {} and {}: certified {} exactly",
                    between.0.as_str(),
                    between.1.as_str(),
                    e.as_str()
                );
            } else {
                out += &format!(
                    "; float indeterminate between {} and {}, exact {} is neither",
                    between.0.as_str(),
                    between.1.as_str(),
                    e.as_str()
                );
            }
        }
        out.push('\n');
    }
    out
}
