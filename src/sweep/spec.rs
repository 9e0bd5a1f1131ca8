//! Sweep specifications: the TOML format, its validation, and the validated
//! [`SweepSpec`].
//!
//! A spec names a scheme, the valences, a parameter space, a sampler and the
//! columns to compute:
//!
//! ```toml
//! name = "n3-grid"                 # optional; default "sweep"
//! scheme = "nurds"                 # nurds | doo-sabin | cc-variant | catmull-clark | adjustable-cc
//! valences = [3]                   # a list, or a range: { from = 3, to = 16 } (inclusive)
//!
//! [space]
//! kind = "ratios"                  # ratios | corner-intervals | face-ep | vertex-ep | uniform | shape
//! ratio_range = [0.05, 0.95]       # kind = "ratios": every r_i in [a, b], 0 < a < b < 1
//! # interval_range = [0.1, 10.0]   # interval kinds: log-uniform in [a, b], 0 < a < b
//! # c_range = [0.0, 1.0]           # kind = "shape": the shape parameter c in [a, b], 0 <= a < b <= 1
//! fixed = { r2 = 0.5 }             # optional: fixed coordinates (slices)
//!
//! [sampler]
//! kind = "grid"                    # grid | random | halton | sobol
//! points_per_axis = 21             # grid
//! # count = 100000                 # random / halton / sobol: configurations per valence
//! # seed = 1                       # random (required); halton / sobol with scramble = true
//! # scramble = true                # halton (random shift) / sobol (digital shift)
//!
//! [columns]                        # optional; defaults shown
//! eigenvalues = 0                  # leading eigenvalues of S_n kept (by modulus)
//! classification = true            # class, lambda1, lambda2, |lambda3|
//! gap = true                       # gap |lambda2| - |lambda3|, modulus ratio, angle
//! contraction = true               # asymptotic contraction rate |lambda1|
//! exact_certificate = false        # exact classification over the rationals (slow)
//! charmap = false                  # characteristic-map verdict (regular, injective)
//! ```
//!
//! Coordinates of a valence-n configuration, by space kind:
//!
//! * `ratios`: `r0..r{n-1}` (edge ratios, math doc section 2), uniform in `ratio_range`;
//! * `corner-intervals`: `p0..p{n-1}, q0..q{n-1}` (corner knot intervals), log-uniform
//!   in `interval_range`; ratios `r_i = q_{i+1} / (p_i + q_{i+1})`;
//! * `face-ep`: `forward0.., backward0..` (directed edge intervals of an initial n-gon,
//!   math doc section 3), log-uniform;
//! * `vertex-ep`: `a0..a{n-1}` (intervals around an initial valence-n vertex, math doc
//!   section 3 **\[derived\]**), log-uniform;
//! * `uniform`: no coordinates (one configuration per valence; the only space of the
//!   knot-free schemes `doo-sabin`, `cc-variant` and `catmull-clark`);
//! * `shape`: `c`, the shape parameter of `adjustable-cc` (math doc section 8
//!   **\[reconstructed\]**), uniform in `c_range` (the only space of that scheme).
//!
//! For the Catmull-Clark family the classification is the common engine's on
//! the `(2n + 1)` one-ring matrix, `eigenvalues` come from the closed-form
//! Fourier blocks ([`crate::schemes::catmull_clark::fourier::spectrum`]), the
//! `charmap` column is [`crate::charmap::catmull_clark`]'s certificate, and
//! `exact_certificate` is not available (it is a face-block method).
//!
//! Every validation error names the key (`sampler.points_per_axis must be >= 1, got 0`)
//! and, where the TOML parser knows it, the line.

use super::SweepError;
use crate::schemes::SchemeKind;
use crate::toml_location::{key_path_at, key_path_in_tree, Location};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use toml::Spanned;

/// Largest number of configurations a sweep may have (over all valences).
///
/// Configuration ids are written to CSV and JSON; keeping them below `2^53`
/// keeps them exact in every JSON reader (IEEE doubles). `2^48` (2.8e14) is far
/// beyond any run that finishes, and catches grids such as 21^64 early.
pub const MAX_CONFIGURATIONS: u64 = 1 << 48;

/// Largest number of points of one Sobol sequence (32-bit direction numbers).
pub const MAX_SOBOL_POINTS: u64 = 1 << 32;

/// Largest leading-eigenvalue count that can be requested (`columns.eigenvalues`).
pub const MAX_KEPT_EIGENVALUES: usize = 1024;

/// Largest valence accepted in a sweep spec.
pub const MAX_VALENCE: usize = 4096;

/// The parameter space a sweep samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpaceKind {
    /// Edge ratios `r_i`, uniform in a sub-interval of (0, 1).
    Ratios,
    /// Corner intervals `p_i, q_i`, log-uniform.
    CornerIntervals,
    /// Face extraordinary point: directed edge intervals, log-uniform.
    FaceEp,
    /// Vertex extraordinary point: intervals `a_k`, log-uniform.
    VertexEp,
    /// Uniform knots: no coordinates.
    Uniform,
    /// The shape parameter `c` of the adjustable Catmull-Clark scheme.
    Shape,
}

impl SpaceKind {
    /// The spec name.
    pub fn name(self) -> &'static str {
        match self {
            SpaceKind::Ratios => "ratios",
            SpaceKind::CornerIntervals => "corner-intervals",
            SpaceKind::FaceEp => "face-ep",
            SpaceKind::VertexEp => "vertex-ep",
            SpaceKind::Uniform => "uniform",
            SpaceKind::Shape => "shape",
        }
    }

    fn parse(s: &str) -> Option<Self> {
        [
            SpaceKind::Ratios,
            SpaceKind::CornerIntervals,
            SpaceKind::FaceEp,
            SpaceKind::VertexEp,
            SpaceKind::Uniform,
            SpaceKind::Shape,
        ]
        .into_iter()
        .find(|k| k.name() == s)
    }

    /// The coordinate families, in column order (`["r"]`, `["p", "q"]`, ...).
    pub fn families(self) -> &'static [&'static str] {
        match self {
            SpaceKind::Ratios => &["r"],
            SpaceKind::CornerIntervals => &["p", "q"],
            SpaceKind::FaceEp => &["forward", "backward"],
            SpaceKind::VertexEp => &["a"],
            SpaceKind::Uniform => &[],
            SpaceKind::Shape => &["c"],
        }
    }

    /// Number of coordinates of a valence-`n` configuration.
    pub fn dimension(self, n: usize) -> usize {
        match self {
            SpaceKind::Shape => 1,
            _ => self.families().len() * n,
        }
    }

    /// Whether coordinates are sampled log-uniformly (knot intervals) rather than
    /// uniformly (ratios).
    pub fn is_log(self) -> bool {
        matches!(
            self,
            SpaceKind::CornerIntervals | SpaceKind::FaceEp | SpaceKind::VertexEp
        )
    }

    /// The name of coordinate `k` of a valence-`n` configuration (`r2`, `q0`, ...).
    pub fn coordinate_name(self, n: usize, k: usize) -> String {
        if self == SpaceKind::Shape {
            return "c".to_owned();
        }
        let fam = self.families()[k / n];
        format!("{fam}{}", k % n)
    }

    /// Position of a named coordinate in a valence-`n` configuration, if it exists.
    pub fn coordinate_index(self, n: usize, name: &str) -> Option<usize> {
        if self == SpaceKind::Shape {
            return (name == "c").then_some(0);
        }
        // Longest family prefix first ("backward" before "b..." would not clash, but be safe).
        self.families().iter().enumerate().find_map(|(f, fam)| {
            let rest = name.strip_prefix(fam)?;
            if rest.is_empty() || !rest.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            if rest.len() > 1 && rest.starts_with('0') {
                return None;
            }
            let i: usize = rest.parse().ok()?;
            (i < n).then_some(f * n + i)
        })
    }
}

/// The validated parameter space.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Space {
    /// What is sampled.
    pub kind: SpaceKind,
    /// Sampling range `[a, b]` of every free coordinate (`None` for `uniform`).
    pub range: Option<(f64, f64)>,
    /// Fixed coordinates by name (slices), e.g. `r2 = 0.5`.
    pub fixed: BTreeMap<String, f64>,
}

/// The validated sampler.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Sampler {
    /// Full tensor grid with `points_per_axis` points on every free coordinate
    /// (end points included; one point = the midpoint).
    Grid {
        /// Points per free coordinate (>= 1).
        points_per_axis: u64,
    },
    /// Independent uniform draws derived from `(seed, valence, index, coordinate)`.
    Random {
        /// Configurations per valence.
        count: u64,
        /// Seed.
        seed: u64,
    },
    /// Halton sequence (prime bases), optionally with a random shift modulo 1.
    Halton {
        /// Configurations per valence.
        count: u64,
        /// Seed of the random shift (`None`: unscrambled).
        scramble_seed: Option<u64>,
    },
    /// Sobol sequence (base 2), optionally with a random digital shift.
    Sobol {
        /// Configurations per valence.
        count: u64,
        /// Seed of the digital shift (`None`: unscrambled).
        scramble_seed: Option<u64>,
    },
}

/// Which result columns a sweep computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Columns {
    /// Number of leading eigenvalues of `S_n` (by non-increasing modulus) kept.
    pub eigenvalues: usize,
    /// Subdominant class, `lambda1`, `lambda2`, `|lambda3|`.
    pub classification: bool,
    /// Gap `|lambda2| - |lambda3|`, ratio `|lambda2| / |lambda1|`, angle of `lambda1`.
    pub gap: bool,
    /// Asymptotic contraction rate of the face (`|lambda1|`).
    pub contraction: bool,
    /// Exact classification over the rationals.
    pub exact_certificate: bool,
    /// Characteristic-map verdict (regularity, injectivity; math doc section 7).
    pub charmap: bool,
}

impl Default for Columns {
    fn default() -> Self {
        Columns {
            eigenvalues: 0,
            classification: true,
            gap: true,
            contraction: true,
            exact_certificate: false,
            charmap: false,
        }
    }
}

/// A validated sweep specification.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepSpec {
    /// Name (for reports and summaries).
    pub name: String,
    /// The scheme.
    pub scheme: SchemeKind,
    /// The valences, in enumeration order (distinct).
    pub valences: Vec<usize>,
    /// The parameter space.
    pub space: Space,
    /// The sampler.
    pub sampler: Sampler,
    /// The result columns.
    pub columns: Columns,
}

// ---------------------------------------------------------------------------
// Raw (serde) form.

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpec {
    name: Option<String>,
    scheme: Spanned<String>,
    valences: Spanned<toml::Value>,
    space: RawSpace,
    sampler: RawSampler,
    #[serde(default)]
    columns: RawColumns,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpace {
    kind: Spanned<String>,
    ratio_range: Option<Spanned<Vec<f64>>>,
    interval_range: Option<Spanned<Vec<f64>>>,
    c_range: Option<Spanned<Vec<f64>>>,
    fixed: Option<Spanned<BTreeMap<String, Spanned<f64>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSampler {
    kind: Spanned<String>,
    points_per_axis: Option<Spanned<i64>>,
    count: Option<Spanned<i64>>,
    seed: Option<Spanned<i64>>,
    scramble: Option<Spanned<bool>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawColumns {
    eigenvalues: Option<Spanned<i64>>,
    classification: Option<bool>,
    gap: Option<bool>,
    contraction: Option<bool>,
    exact_certificate: Option<bool>,
    charmap: Option<bool>,
}

/// A spec error from the TOML deserializer, naming the key path and line: the
/// key at the error's span; for a missing key, the table it is missing from
/// (the span is that table's header, or the empty span of the document)
/// joined with the missing key's name.
fn deserialize_error(text: &str, e: &toml::de::Error) -> SweepError {
    let span = e.span().filter(|s| s.end > 0);
    let message = e.message().trim().to_owned();
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|m| m.strip_suffix('`'));
    let at = span
        .as_ref()
        .and_then(|s| key_path_in_tree(text, s.start).or_else(|| key_path_at(text, s.start)));
    let (key, message) = match missing {
        Some(field) => {
            let key = match &at {
                Some(table) => format!("{table}.{field}"),
                None => field.to_owned(),
            };
            let what = if key == "space" || key == "sampler" {
                format!("missing [{key}] table")
            } else {
                "missing (required key)".to_owned()
            };
            (key.clone(), format!("{key}: {what}"))
        }
        None => {
            let key = at.unwrap_or_else(|| "spec".to_owned());
            (key.clone(), format!("{key}: {message}"))
        }
    };
    SweepError::Spec {
        line: span.map(|s| Location::of(text, s.start).line),
        message,
        key,
    }
}

struct Ctx<'a> {
    text: &'a str,
}

impl Ctx<'_> {
    fn err<T>(
        &self,
        key: &str,
        span: Option<std::ops::Range<usize>>,
        message: String,
    ) -> Result<T, SweepError> {
        Err(SweepError::Spec {
            key: key.to_owned(),
            line: span.map(|s| Location::of(self.text, s.start).line),
            message,
        })
    }
}

/// Integer from a spanned TOML integer, at least `min`.
fn at_least(ctx: &Ctx, key: &str, v: &Spanned<i64>, min: i64) -> Result<u64, SweepError> {
    let x = *v.get_ref();
    if x < min {
        return ctx.err(
            key,
            Some(v.span()),
            format!("{key} must be >= {min}, got {x}"),
        );
    }
    Ok(x as u64)
}

/// The domain a range key lives in.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Domain {
    /// Edge ratios: the open interval (0, 1).
    Ratio,
    /// Knot intervals: positive.
    Interval,
    /// The shape parameter: the closed interval [0, 1].
    Shape,
}

fn range(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<Vec<f64>>,
    domain: Domain,
) -> Result<(f64, f64), SweepError> {
    let span = Some(v.span());
    let r = v.get_ref();
    if r.len() != 2 {
        return ctx.err(
            key,
            span,
            format!("{key} must be [lower, upper], got {} values", r.len()),
        );
    }
    let (a, b) = (r[0], r[1]);
    if !(a.is_finite() && b.is_finite()) {
        return ctx.err(
            key,
            span,
            format!("{key}: bounds must be finite, got [{a}, {b}]"),
        );
    }
    if domain == Domain::Shape {
        for x in [a, b] {
            if !(0.0..=1.0).contains(&x) {
                return ctx.err(
                    key,
                    span,
                    format!(
                        "{key}: bound {x} is outside [0, 1], the range of the shape parameter c"
                    ),
                );
            }
        }
    } else if domain == Domain::Ratio {
        for x in [a, b] {
            if !(x > 0.0 && x < 1.0) {
                return ctx.err(
                    key,
                    span,
                    format!("{key}: bound {x} is outside the open interval (0, 1) of edge ratios"),
                );
            }
        }
    } else {
        for x in [a, b] {
            if x <= 0.0 {
                return ctx.err(
                    key,
                    span,
                    format!("{key}: bound {x} must be > 0 (knot intervals are positive)"),
                );
            }
        }
    }
    if a > b {
        return ctx.err(
            key,
            span,
            format!("{key}: lower bound {a} > upper bound {b}"),
        );
    }
    if a == b {
        return ctx.err(
            key,
            span,
            format!("{key}: empty range [{a}, {b}] (lower bound = upper bound); fix a coordinate with space.fixed instead"),
        );
    }
    Ok((a, b))
}

fn valences(ctx: &Ctx, v: &Spanned<toml::Value>) -> Result<Vec<usize>, SweepError> {
    let span = Some(v.span());
    let check = |key: &str, x: &toml::Value| -> Result<usize, SweepError> {
        match x.as_integer() {
            Some(n) if (3..=MAX_VALENCE as i64).contains(&n) => Ok(n as usize),
            Some(n) => ctx.err(
                key,
                span.clone(),
                format!("{key} must be a valence in 3..={MAX_VALENCE}, got {n}"),
            ),
            None => ctx.err(
                key,
                span.clone(),
                format!("{key} must be an integer, got {x}"),
            ),
        }
    };
    let list = match v.get_ref() {
        toml::Value::Array(items) => {
            if items.is_empty() {
                return ctx.err("valences", span, "valences: empty list".into());
            }
            items
                .iter()
                .enumerate()
                .map(|(i, x)| check(&format!("valences[{i}]"), x))
                .collect::<Result<Vec<_>, _>>()?
        }
        toml::Value::Table(t) => {
            for k in t.keys() {
                if k != "from" && k != "to" {
                    return ctx.err(
                        &format!("valences.{k}"),
                        span,
                        format!("valences.{k}: unknown key (a valence range has `from` and `to`)"),
                    );
                }
            }
            let get = |k: &str| -> Result<usize, SweepError> {
                match t.get(k) {
                    Some(x) => check(&format!("valences.{k}"), x),
                    None => ctx.err(
                        &format!("valences.{k}"),
                        span.clone(),
                        format!("valences.{k} is missing (a valence range has `from` and `to`)"),
                    ),
                }
            };
            let (from, to) = (get("from")?, get("to")?);
            if from > to {
                return ctx.err(
                    "valences",
                    span,
                    format!("valences: empty range, from = {from} > to = {to}"),
                );
            }
            (from..=to).collect()
        }
        other => {
            return ctx.err(
                "valences",
                span,
                format!(
                    "valences must be a list [3, 5] or a range {{ from = 3, to = 8 }}, got {other}"
                ),
            )
        }
    };
    let mut seen = std::collections::BTreeSet::new();
    for n in &list {
        if !seen.insert(*n) {
            return ctx.err(
                "valences",
                span,
                format!("valences: valence {n} is listed twice"),
            );
        }
    }
    Ok(list)
}

fn forbid<T>(ctx: &Ctx, key: &str, v: &Option<Spanned<T>>, why: &str) -> Result<(), SweepError> {
    match v {
        Some(s) => ctx.err(key, Some(s.span()), format!("{key} is not used {why}")),
        None => Ok(()),
    }
}

impl SweepSpec {
    /// Parses and validates a TOML spec.
    ///
    /// ```
    /// use subdiv_lab::sweep::SweepSpec;
    /// let spec = SweepSpec::from_toml(r#"
    /// scheme = "nurds"
    /// valences = [3]
    /// [space]
    /// kind = "ratios"
    /// ratio_range = [0.1, 0.9]
    /// [sampler]
    /// kind = "grid"
    /// points_per_axis = 0
    /// "#).unwrap_err();
    /// assert!(spec.to_string().starts_with("sampler.points_per_axis must be >= 1, got 0"));
    /// ```
    pub fn from_toml(text: &str) -> Result<SweepSpec, SweepError> {
        let raw: RawSpec = toml::from_str(text).map_err(|e| deserialize_error(text, &e))?;
        let ctx = Ctx { text };
        let scheme: SchemeKind = match raw.scheme.get_ref().parse() {
            Ok(k) => k,
            Err(e) => return ctx.err("scheme", Some(raw.scheme.span()), format!("scheme: {e}")),
        };
        let valences = valences(&ctx, &raw.valences)?;
        let min_valence = *valences.iter().min().unwrap_or(&3);

        // Space.
        let rs = &raw.space;
        let kind = match SpaceKind::parse(rs.kind.get_ref()) {
            Some(k) => k,
            None => {
                return ctx.err(
                    "space.kind",
                    Some(rs.kind.span()),
                    format!(
                        "space.kind: unknown space {:?} (known: ratios, corner-intervals, face-ep, vertex-ep, uniform, shape)",
                        rs.kind.get_ref()
                    ),
                )
            }
        };
        if scheme.takes_c() != (kind == SpaceKind::Shape) {
            let msg = if scheme.takes_c() {
                format!("space.kind: scheme {scheme} is sampled over its shape parameter; use kind = \"shape\" with space.c_range")
            } else {
                format!("space.kind: kind \"shape\" samples the shape parameter c of scheme \"adjustable-cc\", not of {scheme}")
            };
            return ctx.err("space.kind", Some(rs.kind.span()), msg);
        }
        if kind != SpaceKind::Shape {
            forbid(
                &ctx,
                "space.c_range",
                &rs.c_range,
                "except by space kind \"shape\"",
            )?;
        }
        if !scheme.takes_knots() && !matches!(kind, SpaceKind::Uniform | SpaceKind::Shape) {
            return ctx.err(
                "space.kind",
                Some(rs.kind.span()),
                format!(
                    "space.kind: scheme {scheme} takes no knot intervals; use kind = \"uniform\" (or scheme = \"nurds\")"
                ),
            );
        }
        let range = match kind {
            SpaceKind::Ratios => {
                forbid(
                    &ctx,
                    "space.interval_range",
                    &rs.interval_range,
                    "by space kind \"ratios\" (use space.ratio_range)",
                )?;
                match &rs.ratio_range {
                    Some(r) => Some(range(&ctx, "space.ratio_range", r, Domain::Ratio)?),
                    None => {
                        return ctx.err(
                            "space.ratio_range",
                            Some(rs.kind.span()),
                            "space.ratio_range is required by space kind \"ratios\"".into(),
                        )
                    }
                }
            }
            SpaceKind::Shape => {
                let why = "by space kind \"shape\" (use space.c_range)";
                forbid(&ctx, "space.ratio_range", &rs.ratio_range, why)?;
                forbid(&ctx, "space.interval_range", &rs.interval_range, why)?;
                match &rs.c_range {
                    Some(r) => Some(range(&ctx, "space.c_range", r, Domain::Shape)?),
                    None => {
                        return ctx.err(
                            "space.c_range",
                            Some(rs.kind.span()),
                            "space.c_range is required by space kind \"shape\"".into(),
                        )
                    }
                }
            }
            SpaceKind::Uniform => {
                forbid(
                    &ctx,
                    "space.ratio_range",
                    &rs.ratio_range,
                    "by space kind \"uniform\"",
                )?;
                forbid(
                    &ctx,
                    "space.interval_range",
                    &rs.interval_range,
                    "by space kind \"uniform\"",
                )?;
                forbid(&ctx, "space.fixed", &rs.fixed, "by space kind \"uniform\"")?;
                None
            }
            _ => {
                forbid(
                    &ctx,
                    "space.ratio_range",
                    &rs.ratio_range,
                    "by interval spaces (use space.interval_range)",
                )?;
                match &rs.interval_range {
                    Some(r) => Some(range(&ctx, "space.interval_range", r, Domain::Interval)?),
                    None => {
                        return ctx.err(
                            "space.interval_range",
                            Some(rs.kind.span()),
                            format!(
                                "space.interval_range is required by space kind {:?}",
                                kind.name()
                            ),
                        )
                    }
                }
            }
        };
        let mut fixed = BTreeMap::new();
        if let Some(f) = &rs.fixed {
            for (name, value) in f.get_ref() {
                let key = format!("space.fixed.{name}");
                let span = Some(value.span());
                if kind.coordinate_index(min_valence, name).is_none() {
                    let fams = kind
                        .families()
                        .iter()
                        .map(|f| format!("{f}0..{f}{}", min_valence - 1))
                        .collect::<Vec<_>>()
                        .join(", ");
                    return ctx.err(
                        &key,
                        span,
                        format!("{key}: unknown coordinate {name:?} (coordinates of valence {min_valence}: {fams})"),
                    );
                }
                let x = *value.get_ref();
                let ok = match kind {
                    SpaceKind::Ratios => x > 0.0 && x < 1.0,
                    SpaceKind::Shape => (0.0..=1.0).contains(&x),
                    _ => x.is_finite() && x > 0.0,
                };
                if !ok {
                    let domain = match kind {
                        SpaceKind::Ratios => "an edge ratio strictly between 0 and 1",
                        SpaceKind::Shape => "a shape parameter c in [0, 1]",
                        _ => "a finite knot interval > 0",
                    };
                    return ctx.err(&key, span, format!("{key} must be {domain}, got {x}"));
                }
                fixed.insert(name.clone(), x);
            }
        }
        let space = Space { kind, range, fixed };

        // Sampler.
        let s = &raw.sampler;
        let skind = s.kind.get_ref().as_str();
        let count = |what: &str| -> Result<u64, SweepError> {
            match &s.count {
                Some(c) => at_least(&ctx, "sampler.count", c, 1),
                None => ctx.err(
                    "sampler.count",
                    Some(s.kind.span()),
                    format!("sampler.count is required by sampler kind {what:?}"),
                ),
            }
        };
        let seed =
            |v: &Spanned<i64>| -> Result<u64, SweepError> { at_least(&ctx, "sampler.seed", v, 0) };
        let sampler = match skind {
            "grid" => {
                let why = "by sampler kind \"grid\"";
                forbid(&ctx, "sampler.count", &s.count, why)?;
                forbid(&ctx, "sampler.seed", &s.seed, why)?;
                forbid(&ctx, "sampler.scramble", &s.scramble, why)?;
                let k = match &s.points_per_axis {
                    Some(k) => at_least(&ctx, "sampler.points_per_axis", k, 1)?,
                    None => {
                        return ctx.err(
                            "sampler.points_per_axis",
                            Some(s.kind.span()),
                            "sampler.points_per_axis is required by sampler kind \"grid\"".into(),
                        )
                    }
                };
                Sampler::Grid { points_per_axis: k }
            }
            "random" => {
                let why = "by sampler kind \"random\"";
                forbid(&ctx, "sampler.points_per_axis", &s.points_per_axis, why)?;
                forbid(&ctx, "sampler.scramble", &s.scramble, why)?;
                let count = count("random")?;
                let seed = match &s.seed {
                    Some(v) => seed(v)?,
                    None => {
                        return ctx.err(
                            "sampler.seed",
                            Some(s.kind.span()),
                            "sampler.seed is required by sampler kind \"random\"".into(),
                        )
                    }
                };
                Sampler::Random { count, seed }
            }
            "halton" | "sobol" => {
                let why = format!("by sampler kind {skind:?}");
                forbid(&ctx, "sampler.points_per_axis", &s.points_per_axis, &why)?;
                let count = count(skind)?;
                let scramble = s.scramble.as_ref().is_some_and(|b| *b.get_ref());
                let scramble_seed = match (&s.seed, scramble) {
                    (Some(v), true) => Some(seed(v)?),
                    (None, true) => {
                        return ctx.err(
                            "sampler.seed",
                            s.scramble.as_ref().map(|b| b.span()),
                            "sampler.seed is required with sampler.scramble = true".into(),
                        )
                    }
                    (Some(v), false) => {
                        return ctx.err(
                            "sampler.seed",
                            Some(v.span()),
                            "sampler.seed has no effect without sampler.scramble = true".into(),
                        )
                    }
                    (None, false) => None,
                };
                if skind == "sobol" {
                    if count > MAX_SOBOL_POINTS {
                        return ctx.err(
                            "sampler.count",
                            s.count.as_ref().map(|c| c.span()),
                            format!("sampler.count must be <= {MAX_SOBOL_POINTS} for the Sobol sampler, got {count}"),
                        );
                    }
                    Sampler::Sobol {
                        count,
                        scramble_seed,
                    }
                } else {
                    Sampler::Halton {
                        count,
                        scramble_seed,
                    }
                }
            }
            other => {
                return ctx.err(
                    "sampler.kind",
                    Some(s.kind.span()),
                    format!(
                    "sampler.kind: unknown sampler {other:?} (known: grid, random, halton, sobol)"
                ),
                )
            }
        };

        // Columns.
        let c = &raw.columns;
        let mut columns = Columns::default();
        if let Some(k) = &c.eigenvalues {
            let k2 = at_least(&ctx, "columns.eigenvalues", k, 0)?;
            if k2 > MAX_KEPT_EIGENVALUES as u64 {
                return ctx.err(
                    "columns.eigenvalues",
                    Some(k.span()),
                    format!("columns.eigenvalues must be <= {MAX_KEPT_EIGENVALUES}, got {k2}"),
                );
            }
            columns.eigenvalues = k2 as usize;
        }
        columns.classification = c.classification.unwrap_or(columns.classification);
        columns.gap = c.gap.unwrap_or(columns.gap);
        columns.contraction = c.contraction.unwrap_or(columns.contraction);
        columns.exact_certificate = c.exact_certificate.unwrap_or(columns.exact_certificate);
        columns.charmap = c.charmap.unwrap_or(columns.charmap);
        if columns.exact_certificate && scheme.is_catmull_clark_family() {
            return ctx.err(
                "columns.exact_certificate",
                None,
                format!("columns.exact_certificate: the exact certificate is a face-block method of the Doo-Sabin family; scheme {scheme} has none"),
            );
        }

        let spec = SweepSpec {
            name: raw.name.unwrap_or_else(|| "sweep".to_owned()),
            scheme,
            valences,
            space,
            sampler,
            columns,
        };
        // Size check (grid overflow etc.).
        if spec.try_total().is_none() {
            let (key, span) = match (&spec.sampler, &s.points_per_axis, &s.count) {
                (Sampler::Grid { .. }, Some(k), _) => ("sampler.points_per_axis", Some(k.span())),
                (_, _, Some(c)) => ("sampler.count", Some(c.span())),
                _ => ("sampler", None),
            };
            return ctx.err(
                key,
                span,
                format!(
                    "{key}: the sweep would have more than {MAX_CONFIGURATIONS} configurations; use fewer points, fewer valences or a random / low-discrepancy sampler"
                ),
            );
        }
        Ok(spec)
    }

    /// Free (sampled) coordinates of a valence-`n` configuration.
    pub fn free_dimension(&self, n: usize) -> usize {
        self.space.kind.dimension(n) - self.space.fixed.len()
    }

    /// Configurations of valence `n`.
    fn try_count(&self, n: usize) -> Option<u64> {
        match self.sampler {
            Sampler::Grid { points_per_axis } => {
                let d = u32::try_from(self.free_dimension(n)).ok()?;
                points_per_axis.checked_pow(d)
            }
            Sampler::Random { count, .. }
            | Sampler::Halton { count, .. }
            | Sampler::Sobol { count, .. } => Some(count),
        }
    }

    fn try_total(&self) -> Option<u64> {
        let mut t: u64 = 0;
        for &n in &self.valences {
            t = t.checked_add(self.try_count(n)?)?;
        }
        (t <= MAX_CONFIGURATIONS).then_some(t)
    }

    /// Number of configurations of valence `n` (validated: no overflow).
    pub fn count_for(&self, n: usize) -> u64 {
        self.try_count(n).unwrap_or(0)
    }

    /// Total number of configurations (validated to be <= [`MAX_CONFIGURATIONS`]).
    pub fn total(&self) -> u64 {
        self.try_total().unwrap_or(0)
    }

    /// A stable 64-bit digest (FNV-1a) of the validated spec, written to the summary
    /// so that resume and merge can tell whether files come from the same spec.
    pub fn digest(&self) -> String {
        let json = serde_json::to_string(self).unwrap_or_default();
        let h = crate::hash::fnv1a64(json.as_bytes());
        format!("{h:016x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
name = "t"
scheme = "nurds"
valences = { from = 3, to = 5 }

[space]
kind = "ratios"
ratio_range = [0.1, 0.9]
fixed = { r2 = 0.5 }

[sampler]
kind = "grid"
points_per_axis = 4
"#;

    fn err(text: &str) -> SweepError {
        SweepSpec::from_toml(text).unwrap_err()
    }

    #[test]
    fn good_spec_counts() {
        let s = SweepSpec::from_toml(GOOD).unwrap();
        assert_eq!(s.valences, vec![3, 4, 5]);
        assert_eq!(s.count_for(3), 16);
        assert_eq!(s.count_for(4), 64);
        assert_eq!(s.total(), 16 + 64 + 256);
        assert_eq!(s.columns, Columns::default());
        assert_eq!(s.digest(), SweepSpec::from_toml(GOOD).unwrap().digest());
        let other = SweepSpec::from_toml(&GOOD.replace("0.9", "0.8")).unwrap();
        assert_ne!(s.digest(), other.digest());
    }

    #[test]
    fn errors_name_key_and_line() {
        let e = err(&GOOD.replace("points_per_axis = 4", "points_per_axis = 0"));
        assert_eq!(
            e.to_string(),
            "sampler.points_per_axis must be >= 1, got 0 (line 13)"
        );
        let e = err(&GOOD.replace("[0.1, 0.9]", "[0.7, 0.2]"));
        assert_eq!(
            e.to_string(),
            "space.ratio_range: lower bound 0.7 > upper bound 0.2 (line 8)"
        );
        let e = err(&GOOD.replace("[0.1, 0.9]", "[0.0, 0.9]"));
        assert!(
            e.to_string()
                .starts_with("space.ratio_range: bound 0 is outside"),
            "{e}"
        );
        let e = err(&GOOD.replace("[0.1, 0.9]", "[0.5, 0.5]"));
        assert!(
            e.to_string().contains("space.ratio_range: empty range"),
            "{e}"
        );
        let e = err(&GOOD.replace("kind = \"grid\"", "kind = \"grid\"\nbogus = 3"));
        assert!(
            e.to_string().starts_with("sampler.bogus: unknown field"),
            "{e}"
        );
        assert!(e.to_string().contains("line 13"), "{e}");
        let e = err(&GOOD.replace("from = 3", "from = 7"));
        assert!(e.to_string().starts_with("valences: empty range"), "{e}");
        let e = err(&GOOD.replace("r2 = 0.5", "r3 = 0.5"));
        assert!(
            e.to_string()
                .starts_with("space.fixed.r3: unknown coordinate"),
            "{e}"
        );
        let e = err(&GOOD.replace("r2 = 0.5", "r2 = 1.5"));
        assert!(e.to_string().starts_with("space.fixed.r2 must be"), "{e}");
        let e = err(&GOOD.replace("valences = { from = 3, to = 5 }", "valences = []"));
        assert!(e.to_string().starts_with("valences: empty list"), "{e}");
        let e = err(&GOOD.replace("points_per_axis = 4", "points_per_axis = 4\nseed = 1"));
        assert!(e.to_string().starts_with("sampler.seed is not used"), "{e}");
        let e = err(&GOOD.replace("\"nurds\"", "\"loop\""));
        assert!(e.to_string().starts_with("scheme: unknown scheme"), "{e}");
        let e = err(&GOOD.replace("to = 5", "to = 64"));
        assert!(
            e.to_string()
                .starts_with("sampler.points_per_axis: the sweep would have more"),
            "{e}"
        );
        match e {
            SweepError::Spec { key, line, .. } => {
                assert_eq!(key, "sampler.points_per_axis");
                assert_eq!(line, Some(13));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn coordinate_names_round_trip() {
        for kind in [
            SpaceKind::Ratios,
            SpaceKind::CornerIntervals,
            SpaceKind::FaceEp,
            SpaceKind::VertexEp,
        ] {
            for n in [3, 7, 12] {
                for k in 0..kind.dimension(n) {
                    let name = kind.coordinate_name(n, k);
                    assert_eq!(kind.coordinate_index(n, &name), Some(k), "{name}");
                }
                assert_eq!(kind.coordinate_index(n, "x0"), None);
                assert_eq!(
                    kind.coordinate_index(n, &format!("{}{n}", kind.families()[0])),
                    None
                );
            }
        }
        assert_eq!(SpaceKind::Ratios.coordinate_index(5, "r01"), None);
    }
}
