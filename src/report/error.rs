//! Errors of the report generator.

use thiserror::Error as ThisError;

pub use crate::toml_location::Location;

/// Errors while reading a report spec or producing a report.
#[derive(Debug, Clone, PartialEq, ThisError)]
#[non_exhaustive]
pub enum ReportError {
    /// The spec is invalid; `key` names the offending key (dotted path) when known.
    #[error("{}{}{message}", .at.map(|l| format!("{l}: ")).unwrap_or_default(), .key.as_ref().map(|k| format!("{k}: ")).unwrap_or_default())]
    Spec {
        /// Where in the spec text.
        at: Option<Location>,
        /// The offending key, e.g. `figure[2].configs[0].ratios`.
        key: Option<String>,
        /// What is wrong.
        message: String,
    },
    /// An analysis behind a figure failed.
    #[error("figure {figure:?}: {source}")]
    Analysis {
        /// Figure id.
        figure: String,
        /// The library error.
        source: crate::any_error::AnyError,
    },
    /// Drawing or encoding a figure failed.
    #[error("figure {figure:?}: rendering failed: {message}")]
    Render {
        /// Figure id (empty if unknown).
        figure: String,
        /// What went wrong.
        message: String,
    },
    /// An input file of a figure (e.g. the CSV of a `sweep` figure) is missing
    /// or unusable; `message` names the offending column or value.
    #[error("figure {figure:?}: {path}: {message}")]
    Input {
        /// Figure id (empty if unknown).
        figure: String,
        /// The path as written in the spec.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The bundled font could not be loaded.
    #[error("the bundled font could not be registered")]
    Font,
}

impl ReportError {
    /// A spec error at byte `offset` of `src` for `key`.
    pub fn spec_at(
        src: &str,
        offset: usize,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        ReportError::Spec {
            at: Some(Location::of(src, offset)),
            key: Some(key.into()),
            message: message.into(),
        }
    }

    /// Attaches a figure id to an error that has none.
    pub fn in_figure(self, id: &str) -> Self {
        match self {
            ReportError::Render { figure, message } if figure.is_empty() => ReportError::Render {
                figure: id.to_owned(),
                message,
            },
            ReportError::Input {
                figure,
                path,
                message,
            } if figure.is_empty() => ReportError::Input {
                figure: id.to_owned(),
                path,
                message,
            },
            other => other,
        }
    }
}
