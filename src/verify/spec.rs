//! The `verify` spec (TOML): what to prove over which region.
//!
//! ```toml
//! name = "v3"
//! scheme = "nurds"            # or "adjustable-cc" (then c_range instead of box)
//! valence = 3
//! box = [[0.01, 0.99], [0.01, 0.99], [0.01, 0.99]]   # one [lo, hi] per edge ratio r_i
//! properties = ["class", "separation"]                # also "theorem1", "charmap", "g1"
//! min_width = 0.002          # optional: cells this narrow are not split further
//! time_budget = 60           # optional, seconds: refinement stops after this (cells left open are undecided)
//! symmetry = "dihedral"      # optional: "none" (default), "rotations", "dihedral" (a nurds box only)
//! ```
//!
//! `symmetry` proves the properties over the fundamental domain of the
//! group and carries them to the whole box through it
//! ([`super::symmetry`]; math doc section 15, "Symmetry of the ratio
//! box"): `"rotations"` needs a box with equal sides `[lo, hi]^n`,
//! `"dihedral"` also `lo + hi = 1` exactly in binary (for example
//! `[0.04999999999999993, 0.9500000000000001]`, the smallest such box
//! containing the floats `0.05` and `0.95`).
//!
//! Errors name the key and the line (the rules of the sweep specs).

pub use super::symmetry::Symmetry;
use crate::sweep::spec::raw::{bounds, Ctx, Domain};
use crate::sweep::SweepError;
use crate::toml_location::{key_path_at, key_path_in_tree, Location};
use serde::Deserialize;
use toml::Spanned;

/// Default `min_width`: `2^-9` (cells of width about 0.002 in ratio space).
pub const DEFAULT_MIN_WIDTH: f64 = 1.0 / 512.0;

/// Smallest accepted `min_width`: `2^-40`; below it the cell count is
/// unbounded in practice and the end points approach the `f64` spacing.
pub const MIN_MIN_WIDTH: f64 = 1.0 / 1_099_511_627_776.0;

/// Largest valence of a NURDS box (the box has one dimension per edge; above
/// 16 dimensions bisection cannot reach a useful width).
pub const MAX_NURDS_VALENCE: usize = 16;

/// Largest valence of the adjustable Catmull-Clark scheme over `c`.
pub const MAX_CC_VALENCE: usize = 1024;

/// A property to prove on every cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Property {
    /// The subdominant class is constant on the cell.
    Class,
    /// `|lambda_2| > |lambda_3|` and `> 1/4`, `lambda_0 = 1` simple.
    Separation,
    /// Theorem 1 (the 3/4 contraction of the central face).
    Theorem1,
    /// The characteristic map is regular and injective on the whole cell.
    Charmap,
    /// For every parameter of the cell the pair of largest eigenvalues after
    /// `1` is separated from the rest of the spectrum and the
    /// characteristic map of its real invariant subspace is regular and
    /// injective, whatever the class (NURDS only; math doc section 15,
    /// "G1 over a cell").
    G1,
}

impl Property {
    /// The spec and CSV name.
    pub fn as_str(self) -> &'static str {
        match self {
            Property::Class => "class",
            Property::Separation => "separation",
            Property::Theorem1 => "theorem1",
            Property::Charmap => "charmap",
            Property::G1 => "g1",
        }
    }

    fn parse(s: &str) -> Option<Self> {
        [
            Property::Class,
            Property::Separation,
            Property::Theorem1,
            Property::Charmap,
            Property::G1,
        ]
        .into_iter()
        .find(|p| p.as_str() == s)
    }
}

/// The scheme and its parameter region.
#[derive(Clone, Debug, PartialEq)]
pub enum Region {
    /// NURDS of valence `lo.len()`, edge ratios `r_i` in `[lo_i, hi_i]`.
    Ratios {
        /// Lower ends.
        lo: Vec<f64>,
        /// Upper ends.
        hi: Vec<f64>,
    },
    /// NURDS of valence `p.len()` over a box of corner knot intervals
    /// `p_i in p[i]`, `q_i in q[i]` (math doc section 15): each ratio
    /// `r_i = q_{i+1} / (p_i + q_{i+1})` depends on its own pair, increasing
    /// in `q_{i+1}` and decreasing in `p_i`, so the box maps onto the ratio
    /// box `[q_lo / (p_hi + q_lo), q_hi / (p_lo + q_hi)]` per edge; `lo`,
    /// `hi` enclose it (rounded outward). Cells are bisected at the midpoint
    /// of the log ratio `ln(p_i / q_{i+1})` (log-scaled).
    Corners {
        /// `[lo, hi]` of each `p_i`.
        p: Vec<[f64; 2]>,
        /// `[lo, hi]` of each `q_i`.
        q: Vec<[f64; 2]>,
        /// Lower ends of the enclosing ratio box.
        lo: Vec<f64>,
        /// Upper ends of the enclosing ratio box.
        hi: Vec<f64>,
    },
    /// The adjustable Catmull-Clark scheme of valence `valence`, `c` in `[lo, hi]`.
    Shape {
        /// Valence.
        valence: usize,
        /// Lower end of `c`.
        lo: f64,
        /// Upper end of `c`.
        hi: f64,
    },
}

/// A validated `verify` spec.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifySpec {
    /// Name (default `verify`).
    pub name: String,
    /// Scheme and region.
    pub region: Region,
    /// Properties, sorted, without repetitions.
    pub properties: Vec<Property>,
    /// Cells whose widest side is at most this are not split.
    pub min_width: f64,
    /// Wall-time budget of the run, seconds (from its start, set-up
    /// included; checked before every cell, see [`super::Stop::TimeBudget`]).
    pub time_budget: Option<f64>,
    /// The symmetry group the run uses ([`Symmetry::None`]: none).
    pub symmetry: Symmetry,
}

impl VerifySpec {
    /// Valence of the configuration.
    pub fn valence(&self) -> usize {
        match &self.region {
            Region::Ratios { lo, .. } | Region::Corners { lo, .. } => lo.len(),
            Region::Shape { valence, .. } => *valence,
        }
    }

    /// The scheme's spec name.
    pub fn scheme(&self) -> &'static str {
        match &self.region {
            Region::Ratios { .. } | Region::Corners { .. } => "nurds",
            Region::Shape { .. } => "adjustable-cc",
        }
    }

    /// The box as `(lo, hi)` vectors (one entry for the `c` path).
    pub fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        match &self.region {
            Region::Ratios { lo, hi } | Region::Corners { lo, hi, .. } => (lo.clone(), hi.clone()),
            Region::Shape { lo, hi, .. } => (vec![*lo], vec![*hi]),
        }
    }

    /// Parses and validates a spec; errors name the key and the line.
    ///
    /// ```
    /// use subdiv_lab::verify::spec::{Property, VerifySpec};
    /// let s = VerifySpec::parse("scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]]\nproperties = [\"separation\", \"class\"]\n").unwrap();
    /// assert_eq!(s.properties, vec![Property::Class, Property::Separation]);
    /// let e = VerifySpec::parse("scheme = \"nurds\"\nvalence = 3\nbox = [[0.1, 0.9], [0.1, 0.9], [0.1, 1.5]]\nproperties = [\"class\"]\n").unwrap_err();
    /// assert!(e.to_string().contains("box[2]") && e.to_string().contains("line 3"));
    /// ```
    pub fn parse(text: &str) -> Result<Self, SweepError> {
        let raw: RawSpec = toml::from_str(text).map_err(|e| deserialize_error(text, &e))?;
        let ctx = Ctx { text };
        let scheme = raw.scheme.get_ref().as_str();
        let v = *raw.valence.get_ref();
        let vspan = Some(raw.valence.span());
        let region = match scheme {
            "nurds" => {
                if !(3..=MAX_NURDS_VALENCE as i64).contains(&v) {
                    return ctx.err(
                        "valence",
                        vspan,
                        format!("valence must be between 3 and {MAX_NURDS_VALENCE} for a nurds box, got {v}"),
                    );
                }
                if let Some(c) = &raw.c_range {
                    return ctx.err("c_range", Some(c.span()), "c_range is for scheme \"adjustable-cc\"; a nurds spec gives box".into());
                }
                let n = v as usize;
                match (&raw.r#box, &raw.p_box, &raw.q_box) {
                    (Some(b), None, None) => {
                        if b.get_ref().len() != n {
                            return ctx.err(
                                "box",
                                Some(b.span()),
                                format!("box must have one [lo, hi] per edge ratio ({n} for valence {n}), got {}", b.get_ref().len()),
                            );
                        }
                        let mut lo = Vec::with_capacity(n);
                        let mut hi = Vec::with_capacity(n);
                        for (i, r) in b.get_ref().iter().enumerate() {
                            let key = format!("box[{i}]");
                            let (a, z) = bounds(&ctx, &key, r, Domain::Ratio, "")?;
                            lo.push(a);
                            hi.push(z);
                        }
                        Region::Ratios { lo, hi }
                    }
                    (Some(b), _, _) => {
                        return ctx.err("box", Some(b.span()), "box: give either box (edge ratios) or p_box and q_box (corner intervals), not both".into());
                    }
                    (None, Some(pb), Some(qb)) => corners(&ctx, n, pb, qb)?,
                    (None, Some(pb), None) => {
                        return ctx.err("q_box", Some(pb.span()), "q_box: missing (p_box and q_box give a corner-interval box together)".into());
                    }
                    (None, None, Some(qb)) => {
                        return ctx.err("p_box", Some(qb.span()), "p_box: missing (p_box and q_box give a corner-interval box together)".into());
                    }
                    (None, None, None) => {
                        return ctx.err("box", None, "box: missing (required key for scheme \"nurds\", or p_box and q_box)".into());
                    }
                }
            }
            "adjustable-cc" => {
                if !(3..=MAX_CC_VALENCE as i64).contains(&v) {
                    return ctx.err(
                        "valence",
                        vspan,
                        format!("valence must be between 3 and {MAX_CC_VALENCE}, got {v}"),
                    );
                }
                if let Some(b) = &raw.r#box {
                    return ctx.err("box", Some(b.span()), "box is for scheme \"nurds\"; an adjustable-cc spec gives c_range".into());
                }
                for (key, b) in [("p_box", &raw.p_box), ("q_box", &raw.q_box)] {
                    if let Some(b) = b {
                        return ctx.err(key, Some(b.span()), format!("{key} is for scheme \"nurds\"; an adjustable-cc spec gives c_range"));
                    }
                }
                let Some(c) = &raw.c_range else {
                    return ctx.err("c_range", None, "c_range: missing (required key for scheme \"adjustable-cc\")".into());
                };
                let (lo, hi) = bounds(&ctx, "c_range", c, Domain::Shape, "")?;
                Region::Shape {
                    valence: v as usize,
                    lo,
                    hi,
                }
            }
            other => {
                return ctx.err(
                    "scheme",
                    Some(raw.scheme.span()),
                    format!("scheme: unknown scheme {other:?}; verify supports \"nurds\" (box) and \"adjustable-cc\" (c_range)"),
                )
            }
        };
        let mut properties = Vec::new();
        let plist = raw.properties.get_ref();
        if plist.is_empty() {
            return ctx.err(
                "properties",
                Some(raw.properties.span()),
                "properties: empty list; give at least one of class, separation, theorem1, charmap, g1"
                    .into(),
            );
        }
        for (i, p) in plist.iter().enumerate() {
            let key = format!("properties[{i}]");
            let Some(prop) = Property::parse(p.get_ref()) else {
                return ctx.err(
                    &key,
                    Some(p.span()),
                    format!(
                        "{key}: unknown property {:?}; one of class, separation, theorem1, charmap, g1",
                        p.get_ref()
                    ),
                );
            };
            if properties.contains(&prop) {
                return ctx.err(
                    &key,
                    Some(p.span()),
                    format!("{key}: property {:?} is listed twice", p.get_ref()),
                );
            }
            if prop == Property::Theorem1 && scheme != "nurds" {
                return ctx.err(
                    &key,
                    Some(p.span()),
                    format!("{key}: theorem1 (the 3/4 contraction of the central face) applies to scheme \"nurds\" only"),
                );
            }
            if prop == Property::G1 && scheme != "nurds" {
                return ctx.err(
                    &key,
                    Some(p.span()),
                    format!("{key}: g1 (the class-free certificate over a ratio box) applies to scheme \"nurds\" only; adjustable-cc gives charmap"),
                );
            }
            properties.push(prop);
        }
        properties.sort();
        let min_width = match &raw.min_width {
            None => DEFAULT_MIN_WIDTH,
            Some(w) => {
                let x = *w.get_ref();
                if !(x.is_finite() && x >= MIN_MIN_WIDTH) {
                    return ctx.err(
                        "min_width",
                        Some(w.span()),
                        format!("min_width must be finite and at least 2^-40 ({MIN_MIN_WIDTH:e}), got {x:?}"),
                    );
                }
                x
            }
        };
        let time_budget = match &raw.time_budget {
            None => None,
            Some(t) => {
                let x = *t.get_ref();
                if !(x.is_finite() && x > 0.0) {
                    return ctx.err(
                        "time_budget",
                        Some(t.span()),
                        format!("time_budget must be a positive number of seconds, got {x:?}"),
                    );
                }
                Some(x)
            }
        };
        let symmetry = match &raw.symmetry {
            None => Symmetry::None,
            Some(sy) => {
                let span = Some(sy.span());
                let Some(g) = Symmetry::parse(sy.get_ref()) else {
                    return ctx.err(
                        "symmetry",
                        span,
                        format!(
                            "symmetry: unknown symmetry {:?}; one of \"none\", \"rotations\", \"dihedral\"",
                            sy.get_ref()
                        ),
                    );
                };
                match &region {
                    _ if g == Symmetry::None => {}
                    Region::Ratios { lo, hi } => {
                        if let Some(problem) = g.box_problem(lo, hi) {
                            return ctx.err("symmetry", span, format!("symmetry: {problem}"));
                        }
                    }
                    Region::Corners { .. } => {
                        return ctx.err("symmetry", span, format!("symmetry: {:?} applies to a box of edge ratios (box); a corner-interval box (p_box, q_box) is bisected in log scale, which the group does not preserve; give symmetry = \"none\"", g.as_str()));
                    }
                    Region::Shape { .. } => {
                        return ctx.err("symmetry", span, format!("symmetry: {:?} applies to scheme \"nurds\" over a box of edge ratios; the c interval of adjustable-cc has no such symmetry", g.as_str()));
                    }
                }
                g
            }
        };
        let name = raw.name.unwrap_or_else(|| "verify".to_owned());
        Ok(VerifySpec {
            name,
            region,
            properties,
            min_width,
            time_budget,
            symmetry,
        })
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpec {
    name: Option<String>,
    scheme: Spanned<String>,
    valence: Spanned<i64>,
    r#box: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
    p_box: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
    q_box: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
    c_range: Option<Spanned<Vec<f64>>>,
    properties: Spanned<Vec<Spanned<String>>>,
    min_width: Option<Spanned<f64>>,
    time_budget: Option<Spanned<f64>>,
    symmetry: Option<Spanned<String>>,
}

type Boxes = Spanned<Vec<Spanned<Vec<f64>>>>;

/// The corner-interval box `p_box`, `q_box` and its enclosing ratio box
/// (see [`Region::Corners`]).
fn corners(ctx: &Ctx, n: usize, pb: &Boxes, qb: &Boxes) -> Result<Region, SweepError> {
    use super::interval::{down, up};
    let mut sides = Vec::with_capacity(2);
    for (name, b) in [("p_box", pb), ("q_box", qb)] {
        if b.get_ref().len() != n {
            return ctx.err(
                name,
                Some(b.span()),
                format!(
                    "{name} must have one [lo, hi] per corner ({n} for valence {n}), got {}",
                    b.get_ref().len()
                ),
            );
        }
        let mut v = Vec::with_capacity(n);
        for (i, r) in b.get_ref().iter().enumerate() {
            let key = format!("{name}[{i}]");
            let span = Some(r.span());
            let x = r.get_ref();
            if x.len() != 2 {
                return ctx.err(
                    &key,
                    span,
                    format!("{key} must be [lower, upper], got {} values", x.len()),
                );
            }
            let (a, z) = (x[0], x[1]);
            if !(a.is_finite() && z.is_finite() && a > 0.0) {
                return ctx.err(
                    &key,
                    span,
                    format!("{key}: knot intervals must be positive and finite, got [{a}, {z}]"),
                );
            }
            if a >= z {
                return ctx.err(
                    &key,
                    span,
                    format!("{key}: lower bound {a} must be below upper bound {z}"),
                );
            }
            v.push([a, z]);
        }
        sides.push(v);
    }
    let q = sides.pop().unwrap_or_default();
    let p = sides.pop().unwrap_or_default();
    let mut lo = Vec::with_capacity(n);
    let mut hi = Vec::with_capacity(n);
    for i in 0..n {
        let (pi, qn) = (p[i], q[(i + 1) % n]);
        // r_i = q / (p + q): smallest at (p_hi, q_lo), largest at (p_lo, q_hi)
        let a = down(qn[0] / up(pi[1] + qn[0]));
        let z = up(qn[1] / down(pi[0] + qn[1]));
        if !(a > 0.0 && a < z && z < 1.0) {
            return ctx.err(
                "p_box",
                Some(pb.span()),
                format!("p_box, q_box: the ratio r_{i} = q_{} / (p_{i} + q_{}) spans [{a}, {z}], which must lie strictly inside (0, 1)", (i + 1) % n, (i + 1) % n),
            );
        }
        lo.push(a);
        hi.push(z);
    }
    Ok(Region::Corners { p, q, lo, hi })
}

/// A deserializer error naming the key path and the line.
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
        Some(field) => (field.to_owned(), format!("{field}: missing (required key)")),
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
