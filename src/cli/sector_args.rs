//! The boundary, crease and corner flags of `analyze` and `matrix`
//! (`--vertex`, `--faces`, `--angle`, `--rules`) and their validation into a
//! [`SectorConfig`].

use super::{CliError, CliResult};
use anyhow::anyhow;
use clap::{Args, ValueEnum};
use subdiv_lab::boundary::{RuleSet, SectorConfig, VertexKind};
use subdiv_lab::mesh::sharp::rules::SdcScheme;

/// The sector flags.
#[derive(Args, Debug, Clone)]
pub(crate) struct SectorArgs {
    /// Analyse a boundary, crease or corner vertex of --scheme catmull-clark or loop instead of an interior configuration (see docs/guide/boundaries.md).
    #[arg(long, value_enum)]
    pub vertex: Option<VertexArg>,
    /// With --vertex: faces in the sector, "K" (boundary, corner) or "K1,K2" (the two sectors of a crease).
    #[arg(long, allow_hyphen_values = true)]
    pub faces: Option<String>,
    /// With --vertex corner: the angle the sector fills, in degrees, in (0, 360).
    #[arg(long, allow_hyphen_values = true)]
    pub angle: Option<String>,
    /// With --vertex: the rules at the vertex (standard: OpenSubdiv's; blz: Biermann-Levin-Zorin).
    #[arg(long, value_enum)]
    pub rules: Option<RulesArg>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum VertexArg {
    Boundary,
    Crease,
    Corner,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum RulesArg {
    Standard,
    Blz,
}

/// The interior-configuration flags a sector configuration does not take,
/// with whether each was given.
pub(crate) struct InteriorFlags<'a> {
    pub given: &'a [(&'static str, bool)],
}

impl SectorArgs {
    /// The validated configuration, or `None` without `--vertex` (then the
    /// sector flags must be absent). `scheme` is `--scheme`; `interior` the
    /// interior-only flags, refused with `--vertex`.
    pub fn resolve(
        &self,
        scheme: &str,
        interior: InteriorFlags<'_>,
    ) -> CliResult<Option<SectorConfig>> {
        let Some(vertex) = self.vertex else {
            for (flag, given) in [
                ("--faces", self.faces.is_some()),
                ("--angle", self.angle.is_some()),
                ("--rules", self.rules.is_some()),
            ] {
                if given {
                    return Err(CliError::usage(anyhow!(
                        "{flag} needs --vertex boundary, crease or corner"
                    )));
                }
            }
            return Ok(None);
        };
        if let Some((flag, _)) = interior.given.iter().find(|(_, g)| *g) {
            return Err(CliError::usage(anyhow!(
                "{flag} is not available with --vertex (a sector is given by --faces, --angle and --rules)"
            )));
        }
        let sdc = match scheme {
            "catmull-clark" => SdcScheme::CatmullClark,
            "loop" => SdcScheme::Loop,
            other => {
                return Err(CliError::usage(anyhow!(
                    "--vertex needs --scheme catmull-clark or loop, got {other:?}"
                )))
            }
        };
        let kind = match vertex {
            VertexArg::Boundary => VertexKind::Boundary,
            VertexArg::Crease => VertexKind::Crease,
            VertexArg::Corner => VertexKind::Corner,
        };
        let faces_text = self.faces.as_deref().ok_or_else(|| {
            CliError::usage(anyhow!(
                "--vertex {} needs --faces ({})",
                kind.name(),
                if kind == VertexKind::Crease {
                    "K1,K2"
                } else {
                    "K"
                }
            ))
        })?;
        let faces = faces_text
            .split(',')
            .map(|t| {
                let t = t.trim();
                t.parse::<usize>().map_err(|_| {
                    CliError::usage(anyhow!(
                        "--faces: {t:?} is not a face count (an integer >= 1)"
                    ))
                })
            })
            .collect::<CliResult<Vec<usize>>>()?;
        let angle = match &self.angle {
            None => None,
            Some(t) => Some(t.trim().parse::<f64>().map_err(|_| {
                CliError::usage(anyhow!(
                    "--angle: {:?} is not a number of degrees",
                    t.trim()
                ))
            })?),
        };
        let rules = match self.rules {
            Some(RulesArg::Standard) => RuleSet::Standard,
            Some(RulesArg::Blz) => RuleSet::Blz,
            None => {
                return Err(CliError::usage(anyhow!(
                    "--vertex needs --rules standard or blz"
                )))
            }
        };
        SectorConfig::new(sdc, kind, &faces, angle, rules)
            .map(Some)
            .map_err(CliError::usage)
    }
}
