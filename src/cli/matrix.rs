//! `subdiv-lab matrix`: print a local subdivision matrix.

use super::scheme_args::SchemeArgs;
use super::sector_args::{InteriorFlags, SectorArgs};
use super::{write_stdout, CliError, CliResult};
use clap::{Args, ValueEnum};
use nalgebra::DMatrix;
use subdiv_lab::scalar::Scalar;
use subdiv_lab::schemes::SpectralStructure;
use subdiv_lab::schemes::{LocalMatrix, PointLabel};

#[derive(Args, Debug)]
pub(crate) struct MatrixArgs {
    #[command(flatten)]
    scheme: SchemeArgs,
    #[command(flatten)]
    sector: SectorArgs,
    /// Which block: the full 4n x 4n matrix or the n x n face block.
    #[arg(long, value_enum, default_value_t = Block::Full)]
    block: Block,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Exact rational entries (a/b) computed from the exact value of the input.
    #[arg(long)]
    exact: bool,
    /// Run even when the estimated memory or time exceeds the limits (see docs/guide/commands.md, "Work limits").
    #[arg(long)]
    force: bool,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Block {
    Full,
    Face,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Format {
    Csv,
    Json,
    Text,
}

pub(crate) fn run(args: MatrixArgs) -> CliResult {
    let interior = [
        ("--valence", args.scheme.valence.is_some()),
        ("--knots", args.scheme.knots.is_some()),
        ("--ratios", args.scheme.ratios.is_some()),
        ("--uniform", args.scheme.uniform),
        ("--c", args.scheme.c.is_some()),
        ("--scheme-file", args.scheme.scheme_file.is_some()),
        ("--exact", args.exact),
        ("--block face", matches!(args.block, Block::Face)),
    ];
    if let Some(c) = args
        .sector
        .resolve(&args.scheme.scheme, InteriorFlags { given: &interior })?
    {
        super::budget::check(
            "matrix",
            &c.describe(),
            &super::sector::matrix_estimate(&c),
            subdiv_lab::budget::TIME_LIMIT_SECONDS,
            args.force,
        )?;
        let name = c.describe();
        let face = Err(subdiv_lab::Error::NotApplicable {
            scheme: name.clone(),
            operation: "the face block (a Doo-Sabin-family notion)",
        });
        let out = render(&name, c.local_matrix(), face, Vec::new(), &args)?;
        return write_stdout(out.as_bytes());
    }
    let resolved = args.scheme.resolve(args.exact)?;
    let n = resolved.scheme.valence();
    let estimate = subdiv_lab::budget::matrix(
        &resolved.scheme.cost_model(),
        n,
        matches!(args.block, Block::Face),
        args.exact,
    );
    super::budget::check(
        "matrix",
        &format!("valence {n}"),
        &estimate,
        subdiv_lab::budget::TIME_LIMIT_SECONDS,
        args.force,
    )?;
    let file_exact = match (&args.scheme.scheme_file, args.exact) {
        (Some(path), true) => Some(resolved.scheme.exact_local_matrix().ok_or_else(|| {
            CliError::usage(anyhow::anyhow!(
                "--exact: scheme file {} has no exact matrix (an expression uses pi, cos, sin, sqrt or a non-integer power, or the topology is triangle)",
                path.display()
            ))
        })?),
        _ => None,
    };
    let out = match (&resolved.exact, file_exact) {
        (_, Some(full)) => {
            let s = &*resolved.scheme;
            let face = Err(subdiv_lab::Error::NotApplicable {
                scheme: s.name().to_owned(),
                operation: "the face block (a Doo-Sabin-family notion)",
            });
            render(s.name(), full, face, Vec::new(), &args)?
        }
        (Some(exact), None) => render(
            exact.kind().name(),
            exact.matrix(),
            exact.face_block().map(drop),
            exact.face_weights(),
            &args,
        )?,
        (None, None) => {
            let s = &*resolved.scheme;
            // the face block exists for face-block schemes only (a typed error otherwise)
            let face = match s.spectral_structure() {
                SpectralStructure::FaceBlock => Ok(()),
                _ => Err(subdiv_lab::Error::NotApplicable {
                    scheme: s.name().to_owned(),
                    operation: "the face block (a Doo-Sabin-family notion)",
                }),
            };
            render(s.name(), s.local_matrix(), face, s.face_weights(), &args)?
        }
    };
    write_stdout(out.as_bytes())
}

/// Renders a scheme's local matrix (`full`) or its face block; `face` is the
/// error to report when the face block is asked for and there is none.
fn render<T: Scalar>(
    name: &str,
    full: subdiv_lab::Result<LocalMatrix<T>>,
    face: subdiv_lab::Result<()>,
    weights: Vec<T>,
    args: &MatrixArgs,
) -> CliResult<String> {
    let full: LocalMatrix<T> = full.map_err(CliError::lib)?;
    let n = full.valence();
    if matches!(args.block, Block::Face) {
        // Typed error for schemes without a face block (the Catmull-Clark family).
        face.map_err(CliError::lib)?;
    }
    let (labels, m): (Vec<PointLabel>, DMatrix<T>) = match args.block {
        Block::Full => (full.rows().to_vec(), full.matrix().clone()),
        Block::Face => (
            full.rows()[..n].to_vec(),
            full.matrix().view((0, 0), (n, n)).into_owned(),
        ),
    };
    Ok(match args.format {
        Format::Csv => m
            .row_iter()
            .map(|row| {
                row.iter()
                    .map(Scalar::to_text)
                    .collect::<Vec<_>>()
                    .join(",")
                    + "\n"
            })
            .collect(),
        Format::Json => {
            let value = |x: &T| {
                if T::EXACT {
                    serde_json::Value::String(x.to_text())
                } else {
                    serde_json::json!(x.to_f64())
                }
            };
            let doc = serde_json::json!({
                "scheme": name,
                "valence": n,
                "exact": T::EXACT,
                "rows": labels.iter().map(ToString::to_string).collect::<Vec<_>>(),
                "matrix": m.row_iter().map(|row| row.iter().map(value).collect::<Vec<_>>()).collect::<Vec<_>>(),
                "face_weights": weights.iter().map(value).collect::<Vec<_>>(),
            });
            serde_json::to_string_pretty(&doc).map_err(CliError::failure)? + "\n"
        }
        Format::Text => {
            let cells: Vec<Vec<String>> = m
                .row_iter()
                .map(|row| row.iter().map(Scalar::to_text).collect())
                .collect();
            let names: Vec<String> = labels.iter().map(ToString::to_string).collect();
            let width = cells
                .iter()
                .flatten()
                .chain(&names)
                .map(String::len)
                .max()
                .unwrap_or(1);
            let mut s = format!(
                "{} S_{} ({} block, {}x{}){}\n",
                name,
                n,
                match args.block {
                    Block::Full => "full",
                    Block::Face => "face",
                },
                m.nrows(),
                m.ncols(),
                if T::EXACT { ", exact" } else { "" }
            );
            s += &format!("{:>w$} ", "", w = width);
            for name in &names {
                s += &format!(" {name:>width$}");
            }
            s.push('\n');
            for (name, row) in names.iter().zip(&cells) {
                s += &format!("{name:>width$} ");
                for c in row {
                    s += &format!(" {c:>width$}");
                }
                s.push('\n');
            }
            if !weights.is_empty() {
                s += "face weights c:";
                for c in &weights {
                    s += &format!(" {}", c.to_text());
                }
                s.push('\n');
            }
            s
        }
    })
}
