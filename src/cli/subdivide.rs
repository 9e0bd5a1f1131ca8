//! `subdivide`: refine a closed OBJ mesh with any built-in scheme, through
//! its mesh rules ([`subdiv_lab::mesh::builtin::mesh_rules`]), or with a
//! scheme file's vertex rule (`--scheme-file`,
//! [`subdiv_lab::mesh::user::file_rules`]): one flow that asks the rules for
//! capabilities (knot intervals, per-level statistics, sharp features).
//! Rules with sharp-feature masks (Catmull-Clark, Loop) also refine open
//! meshes and meshes with crease and corner tags (from the OBJ's `t` lines
//! and `--tags FILE`) through [`subdiv_lab::mesh::sharp::SharpMesh`], with
//! `--boundary` and `--creasing`; closed meshes without tags take the closed
//! refiners. The Doo-Sabin family refines open meshes without tags through
//! [`subdiv_lab::mesh::open::OpenMesh`] (its boundary rule, math doc section 19).
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
use subdiv_lab::boundary::normals::limit_normals;
use subdiv_lab::mesh::builtin::mesh_rules;
use subdiv_lab::mesh::limit::LevelStats;
use subdiv_lab::mesh::open::OpenMesh;
use subdiv_lab::mesh::rules::{KnotUse, MeshRules};
use subdiv_lab::mesh::sharp::rules::{Boundary, Creasing, SdcScheme};
use subdiv_lab::mesh::sharp::{tags, SharpMesh};
use subdiv_lab::mesh::user::file_rules;
use subdiv_lab::mesh::{knot_file, obj, Mesh, MeshError, MAX_HALF_EDGES};
use subdiv_lab::schemes::choice::{validate, Choice, ChoiceError};

#[derive(Args, Debug)]
pub(crate) struct SubdivideArgs {
    /// Input mesh (oriented manifold OBJ; open meshes: Catmull-Clark, Loop and the Doo-Sabin family).
    input: PathBuf,
    #[arg(long, help = super::scheme_args::scheme_help(), required_unless_present = "scheme_file")]
    scheme: Option<String>,
    /// A scheme file (TOML: a vertex rule in n; docs/scheme-files.md) instead
    /// of --scheme: Catmull-Clark's (quad) or Loop's (triangle) refiner with
    /// the file's vertex rule. Closed meshes without tags only.
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["scheme", "c", "knots", "knots_out", "tags", "boundary", "creasing"])]
    scheme_file: Option<PathBuf>,
    /// Shape parameter c in [0, 1] of --scheme adjustable-cc (0.3, 1/3, 25e-2).
    #[arg(long)]
    c: Option<String>,
    /// Knot-interval file, one directed edge per line: "u v d" (1-based OBJ indices). NURDS only.
    #[arg(long)]
    knots: Option<PathBuf>,
    /// Interval of every directed edge not listed in --knots.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    default_interval: f64,
    /// Crease and corner tags, OpenSubdiv's OBJ tag lines ("t crease 2/1/0 V0
    /// V1 S", "t corner 1/1/0 V S"; 0-based vertices) and comments only;
    /// applied after the OBJ's own tags. Catmull-Clark and Loop.
    #[arg(long)]
    tags: Option<PathBuf>,
    /// Boundary interpolation of open meshes (Catmull-Clark, Loop):
    /// sharp boundary edges; edge-and-corner also keeps boundary vertices
    /// with one face; none leaves the faces at the boundary out.
    #[arg(long, value_enum)]
    boundary: Option<BoundaryArg>,
    /// Decay of semi-sharp creases (Catmull-Clark, Loop): sharpness - 1 per
    /// level, or Chaikin's average with the neighbouring creases.
    #[arg(long, value_enum)]
    creasing: Option<CreasingArg>,
    /// Number of refinement steps.
    #[arg(long, default_value_t = 1)]
    levels: usize,
    /// Output OBJ ("-" for standard output). An existing regular file is
    /// replaced atomically.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Write the refined knot intervals here (NURDS only). An existing regular
    /// file is replaced atomically.
    #[arg(long)]
    knots_out: Option<PathBuf>,
    /// Write the limit mesh instead of the refined control mesh: face limit
    /// points (the dual of the refined mesh), fanned around the limit point of
    /// every regular vertex. Catmull-Clark family: the refined mesh with every
    /// vertex moved to its limit position (needs --levels >= 1 for non-quads).
    #[arg(long)]
    limit: bool,
    /// With --limit, on Catmull-Clark and Loop meshes: also write the limit
    /// normal of every vertex (`vn` lines, faces `f v//n`; one normal per
    /// sector where sharp edges cut the surface, from the left eigenvectors
    /// of the sector's local matrix, docs/math.md section 18.6).
    #[arg(long)]
    normals: bool,
    /// Print per-level statistics (counts; every extraordinary face's max |P_i - F| and its ratio).
    #[arg(long)]
    stats: bool,
    /// Print the refinement wall time (excluding reading and writing) to standard error.
    #[arg(long)]
    timing: bool,
    /// Run even when the estimated memory or time exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
}

/// `--boundary` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum BoundaryArg {
    None,
    EdgeOnly,
    EdgeAndCorner,
}

/// `--creasing` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum CreasingArg {
    Uniform,
    Chaikin,
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
    if let Some(p) = &args.tags {
        inputs.push(("--tags", p.as_path()));
    }
    check_distinct(&outputs, &inputs)
}

/// The scheme's mesh rules: the one dispatch (`--scheme` through [`mesh_rules`], `--scheme-file` through
/// [`file_rules`]); the flow below asks the rules for capabilities.
fn resolve_rules(args: &SubdivideArgs) -> CliResult<Box<dyn MeshRules>> {
    if let Some(path) = &args.scheme_file {
        let file = super::scheme_args::read_scheme_file("--scheme-file", path)?;
        return Ok(file_rules(file));
    }
    let name = args.scheme.as_deref().unwrap_or_default();
    // The shared rules (subdiv_lab::schemes::choice), with the flags named.
    let choice = Choice {
        name,
        knots: args.knots.is_some() || args.knots_out.is_some(),
        c: args.c.is_some(),
    };
    let kind = validate(&choice).map_err(|e| {
        CliError::usage(match e {
            ChoiceError::Unknown(_) => anyhow!("--scheme: {e}"),
            ChoiceError::TakesNoKnots(_) => anyhow!("--knots/--knots-out: {e}"),
            ChoiceError::TakesNoC(_) | ChoiceError::NeedsC(_) => anyhow!("--c: {e}"),
        })
    })?;
    let c = match &args.c {
        Some(t) => {
            let (_, x) = super::scheme_args::parse_c(t)?;
            if !(0.0..=1.0).contains(&x) {
                return Err(CliError::usage(anyhow!(
                    "--c: {t:?} is not a number in [0, 1]"
                )));
            }
            Some(x)
        }
        None => None,
    };
    mesh_rules(kind, c).map_err(CliError::usage)
}

/// `--timing`: the refinement's line on stderr (levels, output size, seconds,
/// output faces per second), the same for closed, open and tagged meshes.
fn write_timing(levels: usize, faces: usize, vertices: usize, secs: f64) {
    write_stderr(&format!(
        "refinement: {levels} levels, {faces} faces, {vertices} vertices, {secs:.6} s, {:.0} output faces/s",
        faces as f64 / secs.max(1e-9)
    ));
}

pub(crate) fn run(args: SubdivideArgs) -> CliResult {
    let rules = resolve_rules(&args)?;
    check_outputs(&args)?;
    let name = rules.name().to_owned();
    if args.stats && !rules.has_level_stats() {
        return Err(CliError::usage(anyhow!(
            "--stats: scheme {name} has no per-level statistics of extraordinary faces (a face-centred notion)"
        )));
    }
    if args.normals && !args.limit {
        return Err(CliError::usage(anyhow!(
            "--normals needs --limit (the normals are the limit surface's)"
        )));
    }
    if args.normals && args.output.is_none() {
        return Err(CliError::usage(anyhow!(
            "--normals needs -o OUT.obj (the normals are written to the OBJ)"
        )));
    }
    if args.output.is_none() && args.knots_out.is_none() && !args.stats && !args.timing {
        return Err(CliError::usage(anyhow!(
            "nothing to do: give -o OUT.obj, --knots-out OUT.knots, --stats or --timing"
        )));
    }
    let knots = rules.knots();
    if knots != KnotUse::None && !(args.default_interval.is_finite() && args.default_interval > 0.0)
    {
        return Err(CliError::usage(anyhow!(
            "--default-interval must be finite and > 0, got {}",
            args.default_interval
        )));
    }
    let sharp = rules.sharp_scheme();
    if args.normals && sharp.is_none() {
        return Err(CliError::usage(anyhow!(
            "--normals: scheme {name}: limit normals are written under catmull-clark or loop only"
        )));
    }
    if sharp.is_none() {
        for (flag, given) in [
            ("--tags", args.tags.is_some()),
            ("--boundary", args.boundary.is_some()),
            ("--creasing", args.creasing.is_some()),
        ] {
            if given {
                let what = if rules.has_open_rule() {
                    "takes no crease or corner tags and has one boundary rule (math doc section 19)"
                } else {
                    "refines closed meshes without tags only"
                };
                return Err(CliError::usage(anyhow!(
                    "{flag}: scheme {name} {what} (use catmull-clark or loop)"
                )));
            }
        }
    }
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read {}", args.input.display()))
        .map_err(CliError::usage)?;
    let mut data = obj::parse_obj_data(&text)
        .with_context(|| format!("{}", args.input.display()))
        .map_err(CliError::usage)?;
    let sidecar = match &args.tags {
        Some(path) => {
            let t = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))
                .map_err(CliError::usage)?;
            tags::parse_tag_file(&t)
                .with_context(|| format!("{}", path.display()))
                .map_err(CliError::usage)?
        }
        None => Vec::new(),
    };
    let input = || format!("{}", args.input.display());
    let info = std::mem::take(&mut data.info);
    let mut mesh = match sharp {
        Some(scheme) => {
            // Tagged meshes, and limit normals (which are the sharp-feature
            // rules' on closed meshes too), take the sharp-feature refiner.
            if !data.tags.is_empty() || args.tags.is_some() || args.normals {
                data.info = info;
                return run_sharp(&args, &name, scheme, data, &sidecar);
            }
            // Closed meshes without tags take the closed refiners.
            match Mesh::from_polygons(data.positions.clone(), &data.faces) {
                Err(MeshError::BoundaryEdge { .. }) => {
                    data.info = info;
                    return run_sharp(&args, &name, scheme, data, &sidecar);
                }
                other => other,
            }
        }
        None => match (data.tags.first(), &args.scheme_file) {
            (Some(t), Some(path)) => {
                return Err(CliError::usage(anyhow!(
                    "{}: OBJ line {}: a crease or corner tag, but --scheme-file {} gives no crease or corner rules (scheme files refine closed meshes without tags)",
                    args.input.display(),
                    t.line,
                    path.display()
                )))
            }
            (Some(t), None) => Err(MeshError::TagsUnsupported { line: t.line }),
            (None, Some(path)) => match Mesh::from_polygons(data.positions, &data.faces) {
                Err(e @ MeshError::BoundaryEdge { .. }) => {
                    return Err(CliError::usage(anyhow!(
                        "{}: {e}; --scheme-file {} gives no boundary rules (scheme files refine closed meshes)",
                        args.input.display(),
                        path.display()
                    )))
                }
                other => other,
            },
            (None, None) if rules.has_open_rule() => {
                // Closed meshes take the closed refiners; open ones the boundary rule.
                match Mesh::from_polygons(data.positions.clone(), &data.faces) {
                    Err(MeshError::BoundaryEdge { .. }) => {
                        data.info = info;
                        return run_open(&args, &name, rules.as_ref(), data);
                    }
                    other => other,
                }
            }
            (None, None) => Mesh::from_polygons(data.positions, &data.faces),
        },
    }
    .with_context(input)
    .map_err(CliError::usage)?;
    // Printed only when the run succeeds: an error stays a single stderr line.
    let note = ignored_note(&info);
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
    } else if knots != KnotUse::None {
        knot_file::apply_knot_text(&mut mesh, "", args.default_interval)
            .map_err(CliError::usage)?;
    }
    let needed = rules.half_edges_after(&mesh, args.levels);
    if needed > MAX_HALF_EDGES {
        return Err(CliError::usage(anyhow!(
            "--levels {}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})",
            args.levels
        )));
    }
    check_budget(&args, needed)?;

    let mut stats: Vec<LevelStats> = Vec::new();
    if args.stats {
        stats.extend(rules.level_stats(&mesh, 0, None));
    }
    let mut refine_secs = 0.0;
    for level in 1..=args.levels {
        let t = std::time::Instant::now();
        mesh = rules.refine(&mesh).map_err(CliError::lib)?;
        refine_secs += t.elapsed().as_secs_f64();
        if args.stats {
            stats.extend(rules.level_stats(&mesh, level, stats.last()));
        }
    }
    if args.timing {
        write_timing(
            args.levels,
            mesh.face_count(),
            mesh.vertex_count(),
            refine_secs,
        );
    }

    // Build every output in memory before touching the file system.
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut to_stdout: Option<Vec<u8>> = None;
    if let Some(path) = &args.output {
        let mut buf = Vec::new();
        if args.limit {
            let lm = rules.limit_mesh(&mesh).map_err(CliError::lib)?;
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
        print_stats(&mut text, &name, &stats).map_err(CliError::failure)?;
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

/// The note on ignored OBJ statements, if any.
fn ignored_note(info: &obj::ObjInfo) -> Option<String> {
    (info.ignored_statements > 0).then(|| {
        format!(
            "note: ignored {} OBJ statements ({})",
            info.ignored_statements,
            info.ignored_keywords.join(", ")
        )
    })
}

/// `subdivide` of an open or tagged mesh with the sharp-feature rules of
/// `scheme`: validate, apply the OBJ's tags then the tag file's, refine,
/// write (the faces that are holes under `--boundary none` are left out).
fn run_sharp(
    args: &SubdivideArgs,
    kind: &str,
    scheme: SdcScheme,
    data: obj::ObjData,
    sidecar: &[tags::Tag],
) -> CliResult {
    let boundary = match args.boundary.unwrap_or(BoundaryArg::EdgeOnly) {
        BoundaryArg::None => Boundary::None,
        BoundaryArg::EdgeOnly => Boundary::EdgeOnly,
        BoundaryArg::EdgeAndCorner => Boundary::EdgeAndCorner,
    };
    let creasing = match args.creasing.unwrap_or(CreasingArg::Uniform) {
        CreasingArg::Uniform => Creasing::Uniform,
        CreasingArg::Chaikin => Creasing::Chaikin,
    };
    let input = || format!("{}", args.input.display());
    let mut builder = SharpMesh::builder(data.positions, &data.faces)
        .with_context(input)
        .map_err(CliError::usage)?;
    builder
        .tags(&data.tags)
        .with_context(input)
        .map_err(CliError::usage)?;
    if let Some(path) = &args.tags {
        builder
            .tags(sidecar)
            .with_context(|| format!("{}", path.display()))
            .map_err(CliError::usage)?;
    }
    let mesh = builder.build(boundary);
    if scheme == SdcScheme::Loop {
        if let Some(f) = (0..mesh.face_count()).find(|&f| mesh.face_vertices(f).len() != 3) {
            return Err(CliError::usage(anyhow!(
                "{}: face {f} has {} corners; --scheme {kind} needs an all-triangle mesh",
                args.input.display(),
                mesh.face_vertices(f).len()
            )));
        }
    }
    let needed = (mesh.corner_count() as u64)
        .saturating_mul(4u64.saturating_pow(args.levels.min(64) as u32));
    if needed > MAX_HALF_EDGES {
        return Err(CliError::usage(anyhow!(
            "--levels {}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})",
            args.levels
        )));
    }
    check_budget(args, needed)?;
    let mut mesh = mesh;
    let t = std::time::Instant::now();
    for _ in 0..args.levels {
        mesh = mesh.refine(scheme, creasing).map_err(CliError::lib)?;
    }
    let refine_secs = t.elapsed().as_secs_f64();
    if args.timing {
        write_timing(
            args.levels,
            mesh.face_count(),
            mesh.vertex_count(),
            refine_secs,
        );
    }
    // Limit normals from the control points of the last level (math doc
    // section 18.6), before they move to their limit positions.
    let normals = if args.normals {
        Some(limit_normals(&mesh, scheme).map_err(|e| CliError::usage(anyhow!("--normals: {e}")))?)
    } else {
        None
    };
    if args.limit {
        // OpenSubdiv's limit masks at the last level (math doc section 17).
        let limit = mesh
            .limit_positions(scheme)
            .map_err(|e| CliError::usage(anyhow!("--limit: {e}")))?;
        mesh.set_positions(limit).map_err(CliError::lib)?;
    }
    let mut buf = Vec::new();
    if let (Some(n), Some(_)) = (&normals, &args.output) {
        mesh.write_obj_with_normals(&mut buf, &n.normals, |f, v| n.corner(f, v))
            .map_err(CliError::failure)?;
    } else if args.output.is_some() {
        mesh.write_obj(&mut buf).map_err(CliError::failure)?;
    }
    match &args.output {
        Some(path) if path.as_os_str() != "-" => {
            let staged = Staged::write(&[(path.clone(), buf)])?;
            staged.commit()?;
        }
        Some(_) => write_stdout(&buf)?,
        None => {}
    }
    if let Some(note) = ignored_note(&data.info) {
        write_stderr(&note);
    }
    Ok(())
}

/// `subdivide` of an open mesh (no tags) with the boundary rule of a
/// Doo-Sabin-family scheme (math doc section 19): validate, apply the knot
/// file (boundary directions included), refine, write the OBJ and the
/// refined intervals.
fn run_open(
    args: &SubdivideArgs,
    kind: &str,
    rules: &dyn MeshRules,
    data: obj::ObjData,
) -> CliResult {
    for (flag, given) in [("--limit", args.limit), ("--stats", args.stats)] {
        if given {
            return Err(CliError::usage(anyhow!(
                "{flag}: {} has a boundary; --scheme {kind} gives {flag} for closed meshes only (open meshes: refined control meshes)",
                args.input.display()
            )));
        }
    }
    let mut mesh = OpenMesh::from_polygons(data.positions, &data.faces)
        .with_context(|| format!("{}", args.input.display()))
        .map_err(CliError::usage)?;
    let knot_text = match &args.knots {
        Some(path) => std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))
            .map_err(CliError::usage)?,
        None => String::new(),
    };
    knot_file::apply_open_knot_text(&mut mesh, &knot_text, args.default_interval)
        .with_context(|| match &args.knots {
            Some(path) => format!("{}", path.display()),
            None => "--default-interval".to_owned(),
        })
        .map_err(CliError::usage)?;
    let needed = mesh.directed_edges_after(args.levels);
    if needed > MAX_HALF_EDGES {
        return Err(CliError::usage(anyhow!(
            "--levels {}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})",
            args.levels
        )));
    }
    check_budget(args, needed)?;
    let t = std::time::Instant::now();
    for _ in 0..args.levels {
        mesh = match rules.refine_open(&mesh) {
            Some(r) => r.map_err(CliError::lib)?,
            None => {
                return Err(CliError::usage(anyhow!(
                    "--scheme {kind}: no boundary rule"
                )))
            }
        };
    }
    let refine_secs = t.elapsed().as_secs_f64();
    if args.timing {
        write_timing(
            args.levels,
            mesh.face_count(),
            mesh.vertex_count(),
            refine_secs,
        );
    }
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut to_stdout: Option<Vec<u8>> = None;
    if let Some(path) = &args.output {
        let mut buf = Vec::new();
        obj::write_open_obj(&mesh, &mut buf).map_err(CliError::failure)?;
        if path.as_os_str() == "-" {
            to_stdout = Some(buf);
        } else {
            outputs.push((path.clone(), buf));
        }
    }
    if let Some(path) = &args.knots_out {
        let mut buf = Vec::new();
        knot_file::write_open_knots(&mesh, &mut buf).map_err(CliError::failure)?;
        outputs.push((path.clone(), buf));
    }
    let staged = Staged::write(&outputs)?;
    if let Some(buf) = to_stdout {
        write_stdout(&buf)?;
    }
    staged.commit()?;
    if let Some(note) = ignored_note(&data.info) {
        write_stderr(&note);
    }
    Ok(())
}

/// A refinement error: an interval the refinement cannot halve comes from
/// the input (exit 2); anything else is a failure while running (exit 1).
fn print_stats(out: &mut impl Write, scheme: &str, stats: &[LevelStats]) -> std::io::Result<()> {
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
