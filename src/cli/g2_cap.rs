//! `subdiv-lab g2-cap`: the G2 cap of bidegree (7, 7) around an extraordinary
//! vertex (math doc section 14). Parse, validate, call
//! [`subdiv_lab::g2cap::G2Cap`], format. A residual above the library's
//! tolerance is an error (exit 1); nothing is written then.

use super::outfiles::{check_distinct, Staged};
use super::scheme_args::parse_c;
use super::{write_stdout, CliError, CliResult};
use anyhow::{anyhow, Context};
use clap::Args;
use std::fmt::Write as _;
use std::path::PathBuf;
use subdiv_lab::budget::Spelling;
use subdiv_lab::g2cap::ring::TwoRing;
use subdiv_lab::g2cap::{check_samples, G2Cap, G2CapError, RESIDUAL_TOL};
use subdiv_lab::mesh::obj::parse_obj_data;

#[derive(Args, Debug)]
pub(crate) struct G2CapArgs {
    /// Input mesh (OBJ; may be open away from the 2-ring of --vertex).
    input: Option<PathBuf>,
    /// The extraordinary vertex (0-based index into the OBJ's vertices; its
    /// valence must be in 3..=16).
    #[arg(long)]
    vertex: Option<usize>,
    /// Valence of a generated test net (with --random-net), 3 to 16.
    #[arg(long)]
    valence: Option<usize>,
    /// Seed of a generated test net: a random perturbation of a regular-looking 2-ring.
    #[arg(long = "random-net")]
    random_net: Option<u64>,
    /// Shape parameter c in [0, 1] of the mixed subdivision (0.5 = Catmull-Clark).
    #[arg(long)]
    c: String,
    /// Write the cap, sampled on --samples x --samples quads per patch, as OBJ.
    /// An existing regular file is replaced atomically.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Quads per patch side in the OBJ output, 1 to 256.
    #[arg(long, default_value_t = 16)]
    samples: usize,
    /// Print the result as JSON (degree, patches, residuals, energy).
    #[arg(long)]
    json: bool,
}

fn lib(e: G2CapError) -> CliError {
    if e.is_input_error() {
        CliError::usage(e)
    } else {
        CliError::failure(e)
    }
}

/// The ring the arguments name.
fn ring(args: &G2CapArgs) -> CliResult<TwoRing> {
    match (&args.input, args.vertex, args.valence, args.random_net) {
        (Some(path), Some(v), None, None) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))
                .map_err(CliError::usage)?;
            let data = parse_obj_data(&text)
                .with_context(|| format!("{}", path.display()))
                .map_err(CliError::usage)?;
            TwoRing::from_polygons(&data.positions, &data.faces, v)
                .map(|(r, _)| r)
                .map_err(|e| lib(e).context(path.display().to_string()))
        }
        (None, None, Some(n), Some(seed)) => TwoRing::random(n, seed).map_err(lib),
        (Some(_), None, _, _) => Err(CliError::usage(anyhow!(
            "g2-cap MESH.obj needs --vertex I (the extraordinary vertex, 0-based)"
        ))),
        (Some(_), Some(_), _, _) | (None, Some(_), Some(_), _) | (None, Some(_), _, Some(_)) => {
            Err(CliError::usage(anyhow!(
                "give either MESH.obj --vertex I or --valence N --random-net SEED, not both"
            )))
        }
        (None, Some(_), None, None) => Err(CliError::usage(anyhow!(
            "--vertex needs an input mesh: g2-cap MESH.obj --vertex I"
        ))),
        (None, None, Some(_), None) => Err(CliError::usage(anyhow!(
            "--valence needs --random-net SEED"
        ))),
        (None, None, None, Some(_)) => {
            Err(CliError::usage(anyhow!("--random-net needs --valence N")))
        }
        (None, None, None, None) => Err(CliError::usage(anyhow!(
            "nothing to cap: give MESH.obj --vertex I or --valence N --random-net SEED"
        ))),
    }
}

fn obj_text(cap: &G2Cap, samples: usize) -> String {
    let (pts, quads) = cap.sample_mesh(samples);
    let mut s = format!(
        "# subdiv-lab g2-cap: {} patches of bidegree (7, 7), c = {}, {samples} x {samples} quads each\n",
        cap.valence(),
        cap.c()
    );
    for p in &pts {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    for q in &quads {
        let _ = writeln!(s, "f {} {} {} {}", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    s
}

fn json_text(cap: &G2Cap) -> String {
    let mut s = serde_json::to_string_pretty(&cap.to_json()).unwrap_or_default();
    s.push('\n');
    s
}

fn human_text(cap: &G2Cap) -> String {
    let outer = cap.outer_residual();
    format!(
        "G2 cap: valence {}, c = {}, {} patches of bidegree (7, 7)\n\
         g1_residual {:.3e}  g2_residual {:.3e}  (internal, tolerance {:.0e})\n\
         outer_residual g1 {:.3e}  g2 {:.3e}  (C2 join)\n\
         energy {:.6e}\n",
        cap.valence(),
        cap.c(),
        cap.valence(),
        cap.g1_residual(),
        cap.g2_residual(),
        RESIDUAL_TOL,
        outer.normal,
        outer.curvature,
        cap.energy()
    )
}

pub(crate) fn run(args: G2CapArgs) -> CliResult {
    let (_, c) = parse_c(&args.c)?;
    if !(0.0..=1.0).contains(&c) {
        return Err(CliError::usage(anyhow!(
            "--c: {:?} is not a number in [0, 1]",
            args.c
        )));
    }
    check_samples(args.samples, Spelling::Cli).map_err(super::budget::usage)?;
    if let Some(out) = &args.output {
        let inputs: Vec<(&str, &std::path::Path)> = args
            .input
            .as_deref()
            .map(|p| ("the input", p))
            .into_iter()
            .collect();
        check_distinct(&[("-o", out.as_path())], &inputs)?;
    }
    let ring = ring(&args)?;
    let cap = G2Cap::build(&ring, c).map_err(lib)?;
    cap.check().map_err(lib)?;
    let staged = match &args.output {
        Some(out) => Some(Staged::write(&[(
            out.clone(),
            obj_text(&cap, args.samples).into_bytes(),
        )])?),
        None => None,
    };
    let text = if args.json {
        json_text(&cap)
    } else {
        human_text(&cap)
    };
    write_stdout(text.as_bytes())?;
    if let Some(s) = staged {
        s.commit()?;
    }
    Ok(())
}
