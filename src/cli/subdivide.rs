//! `subdiv-lab subdivide`: refine a closed OBJ mesh with NURDS, original
//! Doo-Sabin or the Catmull-Clark variant.
//!
//! Conflicting outputs (`-o X --knots-out X`, an output naming the input) are
//! refused before anything is written. All outputs are produced in memory
//! first, written to temporary files the tool creates in the target
//! directories, and renamed into place only once every output (and standard
//! output) is written, so a failed run leaves no new or partial file.

use super::outfiles::{check_distinct, Staged};
use super::{write_stderr, write_stdout, CliError, CliResult};
use anyhow::{anyhow, Context};
use clap::Args;
use std::io::Write;
use std::path::PathBuf;
use subdiv_lab::mesh::limit::{level_stats, limit_mesh, LevelStats};
use subdiv_lab::mesh::refine::{half_edges_after, refine};
use subdiv_lab::mesh::{knot_file, obj, Mesh, MeshError, MAX_HALF_EDGES};
use subdiv_lab::schemes::SchemeKind;

#[derive(Args, Debug)]
pub(crate) struct SubdivideArgs {
    /// Input mesh (closed, oriented OBJ).
    input: PathBuf,
    /// Scheme: nurds, doo-sabin, cc-variant, catmull-clark, adjustable-cc or loop.
    #[arg(long)]
    scheme: String,
    /// Shape parameter c in [0, 1] of --scheme adjustable-cc (0.3, 1/3, 25e-2).
    #[arg(long)]
    c: Option<String>,
    /// Knot-interval file, one directed edge per line: "u v d" (1-based OBJ indices). NURDS only.
    #[arg(long)]
    knots: Option<PathBuf>,
    /// Interval of every directed edge not listed in --knots.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    default_interval: f64,
    /// Number of refinement steps.
    #[arg(long, default_value_t = 1)]
    levels: usize,
    /// Output OBJ ("-" for standard output).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Write the refined knot intervals here (NURDS only).
    #[arg(long)]
    knots_out: Option<PathBuf>,
    /// Write the limit mesh instead of the refined control mesh: face limit
    /// points (the dual of the refined mesh), fanned around the limit point of
    /// every regular vertex. Catmull-Clark family: the refined mesh with every
    /// vertex moved to its limit position (needs --levels >= 1 for non-quads).
    #[arg(long)]
    limit: bool,
    /// Print per-level statistics (counts; every extraordinary face's max |P_i - F| and its ratio).
    #[arg(long)]
    stats: bool,
    /// Print the refinement wall time (excluding reading and writing) to standard error.
    #[arg(long)]
    timing: bool,
    /// Run even when the estimated memory or time exceeds the limits (see README).
    #[arg(long)]
    force: bool,
}

/// Refuses a refinement whose output (`half_edges` half-edges) exceeds the
/// memory or time limit (before any level is refined).
fn check_budget(args: &SubdivideArgs, half_edges: u64) -> CliResult {
    super::budget::check(
        "subdivide",
        &format!("--levels {}", args.levels),
        &subdiv_lab::budget::subdivide(half_edges),
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )
}

/// Refuses outputs that name each other, the input OBJ or the knot file.
fn check_outputs(args: &SubdivideArgs) -> CliResult {
    let mut outputs = Vec::new();
    if let Some(p) = &args.output {
        outputs.push(("-o", p.as_path()));
    }
    if let Some(p) = &args.knots_out {
        outputs.push(("--knots-out", p.as_path()));
    }
    let mut inputs = vec![("the input", args.input.as_path())];
    if let Some(p) = &args.knots {
        inputs.push(("--knots", p.as_path()));
    }
    check_distinct(&outputs, &inputs)
}

pub(crate) fn run(args: SubdivideArgs) -> CliResult {
    let scheme: SchemeKind = args.scheme.parse().map_err(CliError::usage)?;
    check_outputs(&args)?;
    if scheme.is_catmull_clark_family() {
        return run_cc(args, scheme);
    }
    if scheme == SchemeKind::Loop {
        return run_loop(args);
    }
    if args.c.is_some() {
        return Err(CliError::usage(anyhow!(
            "--c is the shape parameter of --scheme adjustable-cc only"
        )));
    }
    if args.output.is_none() && args.knots_out.is_none() && !args.stats && !args.timing {
        return Err(CliError::usage(anyhow!(
            "nothing to do: give -o OUT.obj, --knots-out OUT.knots, --stats or --timing"
        )));
    }
    if !scheme.takes_knots() && (args.knots.is_some() || args.knots_out.is_some()) {
        return Err(CliError::usage(anyhow!(
            "--scheme {scheme} takes no knot intervals; use --scheme nurds for --knots/--knots-out"
        )));
    }
    if !(args.default_interval.is_finite() && args.default_interval > 0.0) {
        return Err(CliError::usage(anyhow!(
            "--default-interval must be finite and > 0, got {}",
            args.default_interval
        )));
    }
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read {}", args.input.display()))
        .map_err(CliError::usage)?;
    let (mut mesh, info) = obj::parse_obj(&text)
        .with_context(|| format!("{}", args.input.display()))
        .map_err(CliError::usage)?;
    // Printed only when the run succeeds: an error stays a single stderr line.
    let note = (info.ignored_statements > 0).then(|| {
        format!(
            "note: ignored {} OBJ statements ({})",
            info.ignored_statements,
            info.ignored_keywords.join(", ")
        )
    });
    let knot_text = match &args.knots {
        Some(path) => Some(
            std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))
                .map_err(CliError::usage)?,
        ),
        None => None,
    };
    if let (Some(path), Some(t)) = (&args.knots, &knot_text) {
        knot_file::apply_knot_text(&mut mesh, t, args.default_interval)
            .with_context(|| format!("{}", path.display()))
            .map_err(CliError::usage)?;
    } else {
        knot_file::apply_knot_text(&mut mesh, "", args.default_interval)
            .map_err(CliError::usage)?;
    }
    let needed = half_edges_after(&mesh, args.levels);
    if needed > MAX_HALF_EDGES {
        return Err(CliError::usage(anyhow!(
            "--levels {}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})",
            args.levels
        )));
    }
    check_budget(&args, needed)?;

    let mut stats: Vec<LevelStats> = Vec::new();
    if args.stats {
        stats.push(level_stats(&mesh, scheme, 0, None));
    }
    let mut refine_secs = 0.0;
    for level in 1..=args.levels {
        let t = std::time::Instant::now();
        mesh = refine(&mesh, scheme).map_err(CliError::lib)?;
        refine_secs += t.elapsed().as_secs_f64();
        if args.stats {
            let s = level_stats(&mesh, scheme, level, stats.last());
            stats.push(s);
        }
    }
    if args.timing {
        write_stderr(&format!(
            "refinement: {} levels, {} faces, {} vertices, {:.6} s, {:.0} output faces/s",
            args.levels,
            mesh.face_count(),
            mesh.vertex_count(),
            refine_secs,
            mesh.face_count() as f64 / refine_secs.max(1e-9)
        ));
    }

    // Build every output in memory before touching the file system.
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut to_stdout: Option<Vec<u8>> = None;
    if let Some(path) = &args.output {
        let mut buf = Vec::new();
        if args.limit {
            let lm = limit_mesh(&mesh, scheme).map_err(CliError::lib)?;
            obj::write_obj(&lm, &mut buf).map_err(CliError::failure)?;
        } else {
            obj::write_obj(&mesh, &mut buf).map_err(CliError::failure)?;
        }
        if path.as_os_str() == "-" {
            to_stdout = Some(buf);
        } else {
            outputs.push((path.clone(), buf));
        }
    }
    if let Some(path) = &args.knots_out {
        let mut buf = Vec::new();
        knot_file::write_knots(&mesh, &mut buf).map_err(CliError::failure)?;
        outputs.push((path.clone(), buf));
    }
    // Files to temporaries, then standard output, then the renames: a
    // failure anywhere before the renames leaves no new file.
    let staged = Staged::write(&outputs)?;
    let mut text = Vec::new();
    if args.stats {
        print_stats(&mut text, scheme, &stats).map_err(CliError::failure)?;
    }
    if let Some(buf) = to_stdout {
        text.extend_from_slice(&buf);
    }
    if !text.is_empty() {
        write_stdout(&text)?;
    }
    staged.commit()?;
    if let Some(note) = note {
        write_stderr(&note);
    }
    Ok(())
}

/// A refinement error: an interval the refinement cannot halve comes from
/// the input (exit 2); anything else is a failure while running (exit 1).
fn print_stats(
    out: &mut impl Write,
    scheme: SchemeKind,
    stats: &[LevelStats],
) -> std::io::Result<()> {
    writeln!(out, "# subdivide --scheme {scheme}: per-level statistics")?;
    for s in stats {
        writeln!(
            out,
            "level {}: faces {}, vertices {}, extraordinary faces {}",
            s.level,
            s.faces,
            s.vertices,
            s.extraordinary.len()
        )?;
        for e in &s.extraordinary {
            match e.ratio {
                Some(r) => writeln!(
                    out,
                    "  face {} (n={}): max|P_i - F| = {:.6e}, ratio {:.6}",
                    e.face, e.valence, e.distance, r
                )?,
                None => writeln!(
                    out,
                    "  face {} (n={}): max|P_i - F| = {:.6e}, ratio -",
                    e.face, e.valence, e.distance
                )?,
            }
        }
    }
    Ok(())
}

/// `subdivide` for the Catmull-Clark family (`--scheme catmull-clark|adjustable-cc [--c C]`).
fn run_cc(args: SubdivideArgs, scheme: SchemeKind) -> CliResult {
    let c = match (scheme, &args.c) {
        (SchemeKind::CatmullClark, None) => 0.5,
        (SchemeKind::CatmullClark, Some(_)) => {
            return Err(CliError::usage(anyhow!(
                "--scheme catmull-clark has c = 1/2; use --scheme adjustable-cc --c C"
            )))
        }
        (_, None) => {
            return Err(CliError::usage(anyhow!(
                "--scheme adjustable-cc needs --c C in [0, 1]"
            )))
        }
        (_, Some(t)) => {
            let (_, x) = super::scheme_args::parse_c(t)?;
            if !(0.0..=1.0).contains(&x) {
                return Err(CliError::usage(anyhow!(
                    "--c: {t:?} is not a number in [0, 1]"
                )));
            }
            x
        }
    };
    use subdiv_lab::mesh::catmull_clark::{limit_mesh_cc, refine_cc};
    let rules = VertexRules {
        refine: &|m| refine_cc(m, c),
        limit: &|m| limit_mesh_cc(m, c),
    };
    vertex_centred(args, &rules)
}

/// `subdivide --scheme loop` (closed triangle meshes; math doc section 11).
fn run_loop(args: SubdivideArgs) -> CliResult {
    use subdiv_lab::schemes::loop_subdivision::mesh::{limit_mesh, refine};
    if args.c.is_some() {
        return Err(CliError::usage(anyhow!(
            "--c is the shape parameter of --scheme adjustable-cc only"
        )));
    }
    let rules = VertexRules {
        refine: &refine,
        limit: &limit_mesh,
    };
    vertex_centred(args, &rules)
}

/// One refinement step and the limit positions of a vertex-centred scheme
/// (no knot intervals, no per-level statistics).
struct VertexRules<'a> {
    refine: &'a dyn Fn(&Mesh) -> Result<Mesh, MeshError>,
    limit: &'a dyn Fn(&Mesh) -> Result<Mesh, MeshError>,
}

/// The `subdivide` flow of the vertex-centred schemes (Catmull-Clark family, Loop).
fn vertex_centred(args: SubdivideArgs, rules: &VertexRules<'_>) -> CliResult {
    if args.knots.is_some() || args.knots_out.is_some() || args.stats {
        return Err(CliError::usage(anyhow!(
            "--knots, --knots-out and --stats are Doo-Sabin-family options"
        )));
    }
    let Some(path) = args.output.clone() else {
        if args.timing {
            // Timing only: fall through with no output.
            return refine_and_write(&args, rules, None);
        }
        return Err(CliError::usage(anyhow!(
            "nothing to do: give -o OUT.obj or --timing"
        )));
    };
    refine_and_write(&args, rules, Some(path))
}

fn refine_and_write(
    args: &SubdivideArgs,
    rules: &VertexRules<'_>,
    path: Option<PathBuf>,
) -> CliResult {
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read {}", args.input.display()))
        .map_err(CliError::usage)?;
    let (mut mesh, _) = obj::parse_obj(&text)
        .with_context(|| format!("{}", args.input.display()))
        .map_err(CliError::usage)?;
    let needed = half_edges_after(&mesh, args.levels);
    if needed > MAX_HALF_EDGES {
        return Err(CliError::usage(anyhow!(
            "--levels {}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})",
            args.levels
        )));
    }
    check_budget(args, needed)?;
    let t = std::time::Instant::now();
    for _ in 0..args.levels {
        mesh = (rules.refine)(&mesh).map_err(CliError::lib)?;
    }
    let secs = t.elapsed().as_secs_f64();
    if args.timing {
        write_stderr(&format!(
            "refinement: {} levels, {} faces, {} vertices, {:.6} s",
            args.levels,
            mesh.face_count(),
            mesh.vertex_count(),
            secs
        ));
    }
    let Some(path) = path else { return Ok(()) };
    let out_mesh = if args.limit {
        (rules.limit)(&mesh).map_err(CliError::lib)?
    } else {
        mesh
    };
    let mut buf = Vec::new();
    obj::write_obj(&out_mesh, &mut buf).map_err(CliError::failure)?;
    if path.as_os_str() == "-" {
        write_stdout(&buf)
    } else {
        Staged::write(&[(path, buf)])?.commit()
    }
}
