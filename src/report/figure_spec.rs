//! The part of a report spec one figure sees: its shared keys ([`Common`])
//! and its own table ([`FigureSpec`]), with the errors that name a key and
//! its line. A leaf module: the figure kinds depend on it, and the spec
//! parser ([`super::spec`]) depends on the figure registry.

use super::error::ReportError;
use crate::schemes::user::SchemeFile;
use crate::toml_location::Location;
use serde::de::DeserializeOwned;
use std::sync::Arc;
use toml::de::{DeValue, ValueDeserializer};
use toml::Spanned;

/// Default figure size in pixels (width, height).
pub const DEFAULT_SIZE: (u32, u32) = (1600, 1000);
/// Smallest accepted figure width or height in pixels: below this, text no longer fits.
pub const MIN_PIXELS: u32 = 400;
/// Largest accepted figure width or height in pixels (keeps the RGB buffer below ~200 MB).
pub const MAX_PIXELS: u32 = 8000;

/// Keys every figure table may carry, handled here rather than by the kind.
pub const COMMON_KEYS: &[&str] = &["kind", "id", "title", "caption", "width", "height", "seed"];

/// The keys every figure shares.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Common {
    /// Figure kind name.
    pub kind: &'static str,
    /// Figure id (file stem).
    pub id: String,
    /// Title drawn on the figure and shown in index.html.
    pub title: String,
    /// Caption for index.html.
    pub caption: Option<String>,
    /// Pixel size (width, height).
    pub size: (u32, u32),
    /// Seed of the figure's random draws.
    pub seed: u64,
}

/// Reads the text of a file a spec names (`scheme_file = "..."`), given the
/// path as written; `Err` carries the reason (not found, not UTF-8, ...). The
/// front end decides what a relative path is relative to: the command-line
/// tool reads it beside the spec file. The library's `ReportSpec::parse`
/// reads no files.
pub type FileReader<'a> = &'a dyn Fn(&str) -> Result<String, String>;

/// The kind-specific part of one `[[figure]]` table, with its position in the
/// spec text so that errors can name the line.
pub struct FigureSpec<'a> {
    pub(super) src: &'a str,
    pub(super) key: String,
    pub(super) value: Spanned<DeValue<'a>>,
    pub(super) seed: u64,
    pub(super) files: Option<FileReader<'a>>,
}

impl<'a> FigureSpec<'a> {
    /// Deserializes the kind's keys into `T` (which should use
    /// `#[serde(deny_unknown_fields)]`); errors carry line, column and key.
    pub fn parse<T: DeserializeOwned>(&self) -> Result<T, ReportError> {
        T::deserialize(ValueDeserializer::from(self.value.clone())).map_err(|e| {
            let mut err = toml_error(self.src, e, Some(self.key.clone()));
            if let ReportError::Spec { message, .. } = &mut err {
                if message.starts_with("unknown field") && !message.contains("`id`") {
                    message.push_str(&format!(", or a shared key ({})", COMMON_KEYS.join(", ")));
                }
            }
            err
        })
    }

    /// An error about a value that deserialized but is invalid, located by its span.
    pub fn error_at<T>(
        &self,
        value: &Spanned<T>,
        key: &str,
        message: impl Into<String>,
    ) -> ReportError {
        ReportError::spec_at(
            self.src,
            value.span().start,
            format!("{}.{key}", self.key),
            message,
        )
    }

    /// The scheme file a `scheme_file` key names (`key`: its dotted key
    /// inside the figure), read through the spec's [`FileReader`] and
    /// parsed ([`SchemeFile::parse`]); every failure names the key and its
    /// line.
    pub fn scheme_file(
        &self,
        path: &Spanned<String>,
        key: &str,
    ) -> Result<Arc<SchemeFile>, ReportError> {
        let read = self.files.ok_or_else(|| {
            self.error_at(
                path,
                key,
                "scheme files are read only when the spec is parsed with a file reader (ReportSpec::parse_with; the command-line tool reads them beside the spec)",
            )
        })?;
        let text = read(path.get_ref())
            .map_err(|e| self.error_at(path, key, format!("{}: {e}", path.get_ref())))?;
        SchemeFile::parse_shared(&text)
            .map_err(|e| self.error_at(path, key, format!("{}: {e}", path.get_ref())))
    }

    /// An error about the figure table as a whole (e.g. a missing combination of keys).
    pub fn error(&self, message: impl Into<String>) -> ReportError {
        ReportError::spec_at(self.src, self.value.span().start, self.key.clone(), message)
    }

    /// The figure's seed (for random draws made while parsing).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The dotted key of this figure, e.g. `figure[2]`.
    pub fn key(&self) -> &str {
        &self.key
    }
}

/// A spec error from the TOML deserializer. The key is the exact dotted path
/// at the error's span (e.g. `figure[0].configs[0].valence`) when the text
/// parses, else `key`; a missing key is named by its table's path and name.
pub(super) fn toml_error(src: &str, e: toml::de::Error, key: Option<String>) -> ReportError {
    let span = e.span().filter(|s| s.end > 0);
    let message = e.message().trim().to_owned();
    let found = span
        .as_ref()
        .and_then(|s| crate::toml_location::key_path_in_tree(src, s.start));
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|m| m.strip_suffix('`'));
    let (key, message) = match (missing, found.or(key)) {
        (Some(field), Some(table)) => (Some(format!("{table}.{field}")), "missing".to_owned()),
        (Some(field), None) => (Some(field.to_owned()), "missing".to_owned()),
        (None, k) => (k, message),
    };
    ReportError::Spec {
        at: span.map(|s| Location::of(src, s.start)),
        key,
        message,
    }
}
