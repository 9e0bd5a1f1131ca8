//! `kind = "sweep"`: a plot of a sweep CSV or Parquet file (written by `subdiv-lab sweep`),
//! the same figure as `subdiv-lab plot` draws (see
//! [`crate::report::sweep_plot`] for the plot kinds and the defaults).
//!
//! ```toml
//! [[figure]]
//! kind = "sweep"
//! path = "n3-slice.csv"   # relative paths are read from the spec's directory
//! plot = "map"            # fractions | histogram | scatter | map (default: from the data)
//! x = "r0"                # columns (defaults: from the data)
//! y = "r1"
//! color = "class"
//! ```
//!
//! The library never reads the file: the caller reads every path of
//! [`crate::report::ReportSpec::input_paths`] and passes the bytes in
//! [`crate::report::Inputs`]; a missing or unusable file (a missing column,
//! a non-numeric axis column, no rows) fails before any figure is computed.
//! The CSV written with the figure is the data plotted (fractions, bin
//! counts, or the plotted points).

use super::{Context, DataTable, Figure, FigureKind, FigureOutput};
use crate::report::backend::Area;
use crate::report::error::ReportError;
use crate::report::figure_spec::{Common, FigureSpec};
use crate::report::sweep_plot::{PlotKind, PlotRequest, SweepPlot};
use crate::report::Inputs;
use crate::sweep::output::read_output;
use crate::table::TableError;
use serde::Deserialize;
use toml::Spanned;

/// The kind.
pub(crate) const KIND: FigureKind = FigureKind {
    name: "sweep",
    default_title: "Sweep results",
    summary: "a plot of a sweep CSV (class fractions, histogram, scatter or 2-D class map)",
    parse,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    path: Spanned<String>,
    plot: Option<Spanned<String>>,
    x: Option<String>,
    y: Option<String>,
    color: Option<String>,
}

struct Sweep {
    path: String,
    request: PlotRequest,
}

fn parse(fs: &FigureSpec<'_>) -> Result<Box<dyn Figure>, ReportError> {
    let p: Params = fs.parse()?;
    if p.path.get_ref().trim().is_empty() {
        return Err(fs.error_at(&p.path, "path", "path is empty"));
    }
    let kind = match &p.plot {
        None => None,
        Some(k) => Some(PlotKind::from_name(k.get_ref()).ok_or_else(|| {
            fs.error_at(
                k,
                "plot",
                format!(
                    "unknown plot {:?} (known: fractions, histogram, scatter, map)",
                    k.get_ref()
                ),
            )
        })?),
    };
    Ok(Box::new(Sweep {
        path: p.path.into_inner(),
        request: PlotRequest {
            kind,
            x: p.x,
            y: p.y,
            color: p.color,
        },
    }))
}

impl Sweep {
    fn build(&self, inputs: &Inputs) -> Result<SweepPlot, ReportError> {
        let err = |message: String| ReportError::Input {
            figure: String::new(),
            path: self.path.clone(),
            message,
        };
        let bytes = inputs
            .get(&self.path)
            .ok_or_else(|| err("not read (the caller passed no such input)".to_owned()))?;
        let table = read_output(&self.path, bytes).map_err(|e: TableError| err(e.to_string()))?;
        SweepPlot::build(&table, &self.request).map_err(|e| err(e.to_string()))
    }
}

impl Figure for Sweep {
    fn work(&self) -> u64 {
        1
    }

    fn inputs(&self) -> Vec<String> {
        vec![self.path.clone()]
    }

    fn check_inputs(&self, inputs: &Inputs) -> Result<(), ReportError> {
        self.build(inputs).map(|_| ())
    }

    fn compute(&self, ctx: &Context<'_>) -> Result<Box<dyn FigureOutput>, ReportError> {
        let plot = self
            .build(ctx.inputs)
            .map_err(|e| e.in_figure(&ctx.common.id))?;
        ctx.tick(1);
        Ok(Box::new(Output { plot }))
    }
}

struct Output {
    plot: SweepPlot,
}

impl FigureOutput for Output {
    fn tables(&self) -> Vec<DataTable> {
        vec![self.plot.data()]
    }

    fn draw(&self, area: &Area<'_>, common: &Common) -> Result<(), ReportError> {
        let title = if common.title == KIND.default_title {
            self.plot.default_title()
        } else {
            common.title.clone()
        };
        self.plot.draw(area, &title, common.size)
    }
}
