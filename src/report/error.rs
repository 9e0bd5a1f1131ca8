//! Errors of the report generator.

use thiserror::Error as ThisError;

/// Where in a spec file something is: 1-based line and column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
}

impl Location {
    /// The location of byte `offset` in `src`.
    pub fn of(src: &str, offset: usize) -> Self {
        let offset = offset.min(src.len());
        let before = &src[..floor_char_boundary(src, offset)];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        Location { line, column }
    }
}

/// The dotted key path (`sampler.count`, `space.fixed.r2`, `valences[1]`) of
/// the deepest key or value whose span contains `offset`, from the parsed
/// TOML tree (exact, where a text scan would guess); `None` if the text does not
/// parse or nothing contains the offset.
pub(crate) fn key_path_in_tree(text: &str, offset: usize) -> Option<String> {
    use toml::de::{DeTable, DeValue};
    fn find(v: &DeValue<'_>, offset: usize, path: &mut String) -> bool {
        match v {
            DeValue::Table(t) => {
                for (k, v) in t.iter() {
                    let mark = path.len();
                    if !path.is_empty() {
                        path.push('.');
                    }
                    path.push_str(k.get_ref());
                    let here = k.span().contains(&offset) || v.span().contains(&offset);
                    if find(v.get_ref(), offset, path) || here {
                        return true;
                    }
                    path.truncate(mark);
                }
                false
            }
            DeValue::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    let mark = path.len();
                    path.push_str(&format!("[{i}]"));
                    if find(v.get_ref(), offset, path) || v.span().contains(&offset) {
                        return true;
                    }
                    path.truncate(mark);
                }
                false
            }
            _ => false,
        }
    }
    let root = DeTable::parse(text).ok()?;
    let mut path = String::new();
    (find(&DeValue::Table(root.into_inner()), offset, &mut path) && !path.is_empty())
        .then_some(path)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

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
        source: crate::Error,
    },
    /// Drawing or encoding a figure failed.
    #[error("figure {figure:?}: rendering failed: {message}")]
    Render {
        /// Figure id (empty if unknown).
        figure: String,
        /// What went wrong.
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
            other => other,
        }
    }
}
