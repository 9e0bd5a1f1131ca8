//! The JSON document of one local analysis (`subdiv-lab analyze --json` and the
//! Python `analyze`): the [`LocalAnalysis`] fields, the characteristic-map
//! object (math doc section 7, built by the characteristic-map module), the
//! echoed input and the tool version.
//!
//! Built here, not in the CLI, so every front end prints the same keys.

use super::LocalAnalysis;
use serde::Serialize;

/// The tool version echoed in every analysis document (the crate version).
pub const TOOL_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The input of one analysis, echoed under `"input"` so a saved document
/// says what was analysed.
///
/// Exactly one of `knots`, `ratios` and `uniform = true` describes the knots of
/// a scheme that takes knots; schemes without knots have all three empty.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct AnalysisInput {
    /// The scheme's command-line name (`nurds`, `catmull-clark`, ...).
    pub scheme: String,
    /// Valence of the extraordinary face or vertex.
    pub valence: usize,
    /// Corner knot intervals `[p_i, q_i]` as given (nearest `f64`), if given.
    pub knots: Option<Vec<[f64; 2]>>,
    /// Edge ratios `r_i` as given (nearest `f64`), if given.
    pub ratios: Option<Vec<f64>>,
    /// Uniform knots (all ratios 1/2).
    pub uniform: bool,
    /// Shape parameter `c` of the adjustable Catmull-Clark scheme, if given.
    pub c: Option<f64>,
}

/// The analysis document: the fields of `result`, then `"charmap"` (the
/// characteristic-map object of the front end's check,
/// `charmap::charmap_json`), `"input"` ([`AnalysisInput`]) and
/// `"tool_version"`.
///
/// ```
/// use subdiv_lab::spectral::{analyze, AnalyzeOptions};
/// use subdiv_lab::spectral::json::{analysis_json, AnalysisInput, TOOL_VERSION};
/// use subdiv_lab::knots::EdgeRatios;
/// use subdiv_lab::schemes::{LocalScheme, SchemeKind};
/// let ratios = vec![0.3, 0.5, 0.7];
/// let s = LocalScheme::from_kind_with_c(
///     SchemeKind::Nurds, 3, Some(EdgeRatios::new(ratios.clone()).unwrap()), None).unwrap();
/// let a = analyze(&s, &AnalyzeOptions::default()).unwrap();
/// let input = AnalysisInput { scheme: "nurds".into(), valence: 3, ratios: Some(ratios), ..Default::default() };
/// let map = subdiv_lab::charmap::check_classified(&s, &a.subdominant);
/// let v = analysis_json(&a, subdiv_lab::charmap::charmap_json(&map), &input);
/// assert_eq!(v["input"]["ratios"][2], 0.7);
/// assert_eq!(v["tool_version"], TOOL_VERSION);
/// assert!(v["subdominant"]["class"].is_string() && v["charmap"]["verdict"].is_string());
/// ```
pub fn analysis_json(
    result: &LocalAnalysis,
    charmap: serde_json::Value,
    input: &AnalysisInput,
) -> serde_json::Value {
    // LocalAnalysis and AnalysisInput are plain data (numbers, strings,
    // options): serialising them cannot fail, but stay total anyway.
    let mut value = serde_json::to_value(result).unwrap_or(serde_json::Value::Null);
    if let serde_json::Value::Object(map) = &mut value {
        map.insert("charmap".to_owned(), charmap);
        map.insert(
            "input".to_owned(),
            serde_json::to_value(input).unwrap_or(serde_json::Value::Null),
        );
        map.insert("tool_version".to_owned(), TOOL_VERSION.into());
    }
    value
}
