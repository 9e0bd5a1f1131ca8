//! The report spec format (TOML) and its parser.
//!
//! ```toml
//! name = "default"                 # output directory: reports/<name>/
//! title = "NURDS spectral report"  # heading of index.html
//! description = "..."              # optional paragraph under the heading
//! seed = 20240601                  # base seed of every random draw
//!
//! [[figure]]
//! kind = "spectrum"                # a registered figure kind (see figures::REGISTRY)
//! id = "spectra"                   # file stem: spectra.svg, spectra.png, spectra.csv
//! title = "Spectra of S_n"         # optional; defaults to the kind's title
//! caption = "..."                  # optional text under the figure in index.html
//! width = 1600                     # optional pixel size of the PNG (and the SVG canvas)
//! height = 1000
//! seed = 7                         # optional; default derived from the base seed and the id
//! # ... keys of the figure kind
//! ```
//!
//! Every table rejects unknown keys. Errors carry the line and column of the
//! offending key or value and name it (see [`ReportError::Spec`]).

use super::error::ReportError;
use super::figure_spec::toml_error;
pub use super::figure_spec::{Common, FigureSpec, FileReader, COMMON_KEYS};
pub use super::figure_spec::{DEFAULT_SIZE, MAX_PIXELS, MIN_PIXELS};
use super::figures::{self, Figure};
use crate::rng::derive_seed;
use serde::Deserialize;
use toml::de::{DeTable, DeValue, ValueDeserializer};
use toml::Spanned;

/// A parsed, validated report spec.
pub struct ReportSpec {
    /// Report name (default output directory `reports/<name>/`).
    pub name: String,
    /// Report title.
    pub title: String,
    /// Optional description paragraph.
    pub description: Option<String>,
    /// Base seed.
    pub seed: u64,
    /// The figures, in spec order.
    pub figures: Vec<FigureEntry>,
    /// The spec text as given (recorded in the manifest).
    pub source: String,
}

impl ReportSpec {
    /// The input files the spec's figures read (as written in the spec, in
    /// figure order, without repeats): the caller reads them and passes them
    /// to [`super::generate_with`] in [`super::Inputs`].
    pub fn input_paths(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for f in &self.figures {
            for p in f.figure.inputs() {
                if !out.contains(&p) {
                    out.push(p);
                }
            }
        }
        out
    }
}

impl std::fmt::Debug for ReportSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ReportSpec")
            .field("name", &self.name)
            .field(
                "figures",
                &self
                    .figures
                    .iter()
                    .map(|e| &e.common.id)
                    .collect::<Vec<_>>(),
            )
            .finish()
    }
}

/// One figure of a spec: shared keys plus the kind's parsed parameters.
pub struct FigureEntry {
    /// Shared keys.
    pub common: Common,
    /// The figure.
    pub figure: Box<dyn Figure>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TopRaw {
    name: Spanned<String>,
    title: Option<String>,
    description: Option<String>,
    seed: Option<u64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CommonRaw {
    kind: Spanned<String>,
    id: Option<Spanned<String>>,
    title: Option<String>,
    caption: Option<String>,
    width: Option<Spanned<u32>>,
    height: Option<Spanned<u32>>,
    seed: Option<u64>,
}

fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= 64
        && id
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '_')
        && !id.starts_with(['-', '_'])
}

impl ReportSpec {
    /// Parses and validates a spec. Every figure kind validates its own keys here,
    /// so a spec that parses can only fail later on numerical or rendering errors.
    ///
    /// ```
    /// use subdiv_lab::report::ReportSpec;
    /// let spec = ReportSpec::parse("name = \"demo\"\n[[figure]]\nkind = \"nonsense\"\n");
    /// let err = spec.unwrap_err().to_string();
    /// assert!(err.contains("line 3") && err.contains("nonsense"), "{err}");
    /// ```
    pub fn parse(src: &str) -> Result<Self, ReportError> {
        Self::parse_reading(src, None)
    }

    /// [`parse`](Self::parse), reading the files the spec names
    /// (`scheme_file = "..."` in a configuration or a mesh figure) through
    /// `files`.
    ///
    /// ```
    /// use subdiv_lab::report::ReportSpec;
    /// let cc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/schemes/catmull-clark.toml")).to_owned();
    /// let files = move |path: &str| match path {
    ///     "cc.toml" => Ok(cc.clone()),
    ///     _ => Err("no such file".to_owned()),
    /// };
    /// let spec = "name = \"demo\"\n[[figure]]\nkind = \"spectrum\"\nconfigs = [{ scheme_file = \"cc.toml\", valence = 5 }]\n";
    /// let parsed = ReportSpec::parse_with(spec, &files).unwrap();
    /// assert_eq!(parsed.figures.len(), 1);
    /// let missing = spec.replace("cc.toml", "other.toml");
    /// let err = ReportSpec::parse_with(&missing, &files).unwrap_err().to_string();
    /// assert!(err.contains("scheme_file") && err.contains("no such file"), "{err}");
    /// assert!(ReportSpec::parse(spec).is_err());
    /// ```
    pub fn parse_with(src: &str, files: FileReader<'_>) -> Result<Self, ReportError> {
        Self::parse_reading(src, Some(files))
    }

    fn parse_reading(src: &str, files: Option<FileReader<'_>>) -> Result<Self, ReportError> {
        let root = DeTable::parse(src).map_err(|e| toml_error(src, e, None))?;
        let root_span = root.span();
        let mut rest = DeTable::new();
        let mut figure_value = None;
        for (k, v) in root.into_inner() {
            if k.get_ref().as_ref() == "figure" {
                figure_value = Some(v);
            } else {
                rest.insert(k, v);
            }
        }
        let top = TopRaw::deserialize(toml::de::Deserializer::from(Spanned::new(root_span, rest)))
            .map_err(|e| toml_error(src, e, None))?;
        if !valid_id(top.name.get_ref()) {
            return Err(ReportError::spec_at(
                src,
                top.name.span().start,
                "name",
                format!(
                    "{:?} is not a valid report name (lowercase letters, digits, '-' and '_')",
                    top.name.get_ref()
                ),
            ));
        }
        let base_seed = top.seed.unwrap_or(0);
        let items: Vec<Spanned<DeValue<'_>>> = match figure_value {
            None => Vec::new(),
            Some(v) => {
                let span = v.span();
                match v.into_inner() {
                    DeValue::Array(a) => a.into_iter().collect(),
                    _ => {
                        return Err(ReportError::spec_at(
                            src,
                            span.start,
                            "figure",
                            "expected an array of tables ([[figure]])",
                        ))
                    }
                }
            }
        };
        if items.is_empty() {
            return Err(ReportError::Spec {
                at: None,
                key: Some("figure".into()),
                message: "the spec has no [[figure]] tables".into(),
            });
        }
        let mut figures: Vec<FigureEntry> = Vec::with_capacity(items.len());
        for (index, item) in items.into_iter().enumerate() {
            let key = format!("figure[{index}]");
            let span = item.span();
            let DeValue::Table(table) = item.into_inner() else {
                return Err(ReportError::spec_at(
                    src,
                    span.start,
                    key,
                    "expected a table",
                ));
            };
            let mut common_t = DeTable::new();
            let mut body = DeTable::new();
            for (k, v) in table {
                if COMMON_KEYS.contains(&k.get_ref().as_ref()) {
                    common_t.insert(k, v);
                } else {
                    body.insert(k, v);
                }
            }
            let raw = CommonRaw::deserialize(ValueDeserializer::from(Spanned::new(
                span.clone(),
                DeValue::Table(common_t),
            )))
            .map_err(|e| toml_error(src, e, Some(key.clone())))?;
            let kind_name = raw.kind.get_ref().as_str();
            let Some(kind) = figures::find_kind(kind_name) else {
                return Err(ReportError::spec_at(
                    src,
                    raw.kind.span().start,
                    format!("{key}.kind"),
                    format!(
                        "unknown figure kind {kind_name:?} (known: {})",
                        figures::REGISTRY
                            .iter()
                            .map(|k| k.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            };
            let id = match &raw.id {
                Some(id) => {
                    if !valid_id(id.get_ref()) {
                        return Err(ReportError::spec_at(
                            src,
                            id.span().start,
                            format!("{key}.id"),
                            format!("{:?} is not a valid figure id (lowercase letters, digits, '-' and '_')", id.get_ref()),
                        ));
                    }
                    if figures.iter().any(|f| &f.common.id == id.get_ref()) {
                        return Err(ReportError::spec_at(
                            src,
                            id.span().start,
                            format!("{key}.id"),
                            format!("duplicate figure id {:?}", id.get_ref()),
                        ));
                    }
                    id.get_ref().clone()
                }
                None => format!("{}-{}", kind.name, index + 1),
            };
            let mut size = DEFAULT_SIZE;
            for (dim, v) in [("width", &raw.width), ("height", &raw.height)] {
                if let Some(v) = v {
                    let x = *v.get_ref();
                    if !(MIN_PIXELS..=MAX_PIXELS).contains(&x) {
                        return Err(ReportError::spec_at(
                            src,
                            v.span().start,
                            format!("{key}.{dim}"),
                            format!("{dim} must be between {MIN_PIXELS} and {MAX_PIXELS} pixels, got {x}"),
                        ));
                    }
                    if dim == "width" {
                        size.0 = x;
                    } else {
                        size.1 = x;
                    }
                }
            }
            let seed = raw.seed.unwrap_or_else(|| derive_seed(base_seed, &id));
            let fs = FigureSpec {
                src,
                key: key.clone(),
                value: Spanned::new(span, DeValue::Table(body)),
                seed,
                files,
            };
            let figure = (kind.parse)(&fs)?;
            let common = Common {
                kind: kind.name,
                id,
                title: raw
                    .title
                    .clone()
                    .unwrap_or_else(|| kind.default_title.to_owned()),
                caption: raw.caption.clone(),
                size,
                seed,
            };
            figures.push(FigureEntry { common, figure });
        }
        Ok(ReportSpec {
            name: top.name.into_inner(),
            title: top.title.unwrap_or_else(|| "subdiv-lab report".to_owned()),
            description: top.description,
            seed: base_seed,
            figures,
            source: src.to_owned(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toml_location::Location;

    const ONE: &str = "name = \"t\"\nseed = 5\n[[figure]]\nkind = \"table\"\nconfigs = [{ scheme = \"nurds\", valence = 3 }]\n";

    #[test]
    fn defaults_id_title_size_and_seed() {
        let s = ReportSpec::parse(ONE).unwrap();
        let c = &s.figures[0].common;
        assert_eq!(c.id, "table-1");
        assert_eq!(c.title, "Configurations");
        assert_eq!(c.size, DEFAULT_SIZE);
        assert_eq!(c.seed, derive_seed(5, "table-1"));
        assert_eq!(s.source, ONE);
    }

    #[test]
    fn explicit_seed_overrides_derived() {
        let s = ReportSpec::parse(&ONE.replace("kind =", "seed = 99\nkind =")).unwrap();
        assert_eq!(s.figures[0].common.seed, 99);
    }

    fn err(src: &str) -> String {
        ReportSpec::parse(src).unwrap_err().to_string()
    }

    #[test]
    fn rejects_bad_sizes_ids_and_duplicates() {
        let e = err(&ONE.replace("kind =", "width = 100\nkind ="));
        assert!(
            e.contains("line 4") && e.contains("figure[0].width") && e.contains("100"),
            "{e}"
        );
        let e = err(&ONE.replace("kind =", "id = \"A b\"\nkind ="));
        assert!(
            e.contains("figure[0].id") && e.contains("not a valid figure id"),
            "{e}"
        );
        let twice = format!("{ONE}[[figure]]\nkind = \"table\"\nid = \"table-1\"\nconfigs = [{{ scheme = \"nurds\", valence = 4 }}]\n");
        let e = err(&twice);
        assert!(
            e.contains("line 8") && e.contains("duplicate figure id"),
            "{e}"
        );
        let e = err("name = \"../x\"\n[[figure]]\nkind = \"table\"\n");
        assert!(e.contains("line 1") && e.contains("name"), "{e}");
    }

    #[test]
    fn rejects_missing_figures_and_missing_name() {
        assert!(err("name = \"t\"\n").contains("no [[figure]]"));
        let e = err("[[figure]]\nkind = \"table\"\nconfigs = []\n");
        assert!(e.contains("name"), "{e}");
    }

    #[test]
    fn unknown_figure_key_lists_shared_keys() {
        let e = err(&ONE.replace("configs", "confgs"));
        assert!(
            e.contains("line 5") && e.contains("confgs") && e.contains("shared key"),
            "{e}"
        );
    }

    #[test]
    fn location_counts_lines_and_characters() {
        let src = "ab\nλx\n\nz";
        assert_eq!(Location::of(src, 0), Location { line: 1, column: 1 });
        assert_eq!(Location::of(src, 3), Location { line: 2, column: 1 });
        // 'x' follows the two-byte 'λ': column 2.
        assert_eq!(Location::of(src, 5), Location { line: 2, column: 2 });
        assert_eq!(
            Location::of(src, src.len()),
            Location { line: 4, column: 2 }
        );
        // An offset inside a multi-byte character does not panic.
        assert_eq!(Location::of(src, 4).line, 2);
    }
}
