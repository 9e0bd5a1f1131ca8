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
//! # scramble = true                # halton (random shift) / sobol (Owen nested uniform); default false
//!
//! [columns]                        # optional; defaults shown
//! eigenvalues = 0                  # leading eigenvalues of S_n kept (by modulus)
//! classification = true            # class, lambda1, lambda2, |lambda3|
//! gap = true                       # gap |lambda2| - |lambda3|, modulus ratio, angle
//! contraction = true               # asymptotic contraction rate |lambda1|
//! exact_certificate = false        # exact classification over the rationals (slow)
//! charmap = false                  # characteristic-map verdict (regular, injective)
//! generic_charmap = false          # the generic C1 certificate's verdict (math doc section 20)
//! curvature = false                # mu, mu / lambda^2 and the curvature verdict (math doc section 13)
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
//!
//! [`SweepSpec::from_toml`] calls one parser per concern (files of this
//! directory): `raw.rs` (the serde form, error positions, integer and range
//! checks), `scheme.rs` (the scheme configuration: scheme, valences, space kind
//! and its ratio / interval / c range, in one function), `space.rs` (fixed
//! coordinates), `sampler.rs`, `columns.rs`; the size check is
//! [`SweepSpec`]'s own.

mod columns;
mod model;
pub(crate) mod raw;
mod sampler;
mod scheme;
mod sector;
mod space;

use super::SweepError;
use crate::schemes::SchemeKind;
pub use model::{
    Columns, Sampler, SectorSweep, Space, SpaceKind, MAX_CONFIGURATIONS, MAX_KEPT_EIGENVALUES,
    MAX_SOBOL_POINTS, MAX_VALENCE,
};
use raw::{deserialize_error, Ctx, RawSampler, RawSpec};
use scheme::SchemeConfig;
use serde::Serialize;

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
    /// A boundary, crease or corner sweep (the `[sector]` table): then
    /// `valences` are the face counts `K`. Left out of the serialised spec
    /// when absent, so that the digests of other specs are unchanged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sector: Option<SectorSweep>,
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
        let (
            SchemeConfig {
                scheme,
                valences,
                kind,
                range,
            },
            sector,
        ) = match &raw.sector {
            Some(s) => {
                let (config, sector) = sector::sector_config(&ctx, &raw, s)?;
                (config, Some(sector))
            }
            None => (scheme::scheme_config(&ctx, &raw)?, None),
        };
        let min_valence = *valences.iter().min().unwrap_or(&3);
        let fixed = space::fixed(&ctx, &raw.space, kind, min_valence)?;
        let space = Space { kind, range, fixed };
        let sampler = sampler::sampler(&ctx, &raw.sampler)?;
        let mut columns = columns::columns(&ctx, &raw.columns, scheme, &valences)?;
        columns.sector = sector.is_some();
        if columns.sector && columns.generic_charmap {
            return ctx.err(
                "columns.generic_charmap",
                None,
                "columns.generic_charmap: the generic certificate analyses interior configurations; a [sector] sweep's `charmap = true` gives the sector certificate (math doc section 18.4)".to_owned(),
            );
        }
        let spec = SweepSpec {
            name: raw.name.unwrap_or_else(|| "sweep".to_owned()),
            scheme,
            valences,
            space,
            sampler,
            columns,
            sector,
        };
        spec.check_size(&ctx, &raw.sampler)?;
        Ok(spec)
    }

    /// The size check (grid overflow etc.): at most [`MAX_CONFIGURATIONS`].
    fn check_size(&self, ctx: &Ctx, s: &RawSampler) -> Result<(), SweepError> {
        if let Sampler::Sobol { .. } = self.sampler {
            let max = crate::sweep::sampler::SOBOL_MAX_DIMENSION;
            if let Some(&n) = self
                .valences
                .iter()
                .find(|&&n| self.free_dimension(n) > max)
            {
                return ctx.err(
                    "sampler.kind",
                    Some(s.kind.span()),
                    format!(
                        "sampler.kind: the Sobol sampler supports at most {max} free coordinates (Joe-Kuo direction numbers shipped), valence {n} has {}; use sampler kind \"halton\" or \"random\", or fix coordinates",
                        self.free_dimension(n)
                    ),
                );
            }
        }
        if self.try_total().is_none() {
            let (key, span) = match (&self.sampler, &s.points_per_axis, &s.count) {
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
        Ok(())
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
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in json.bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
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
                .starts_with("space.ratio_range: bound 0.0 is outside"),
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
        let e = err(&GOOD.replace("\"nurds\"", "\"midedge\""));
        assert!(e.to_string().starts_with("scheme: unknown scheme"), "{e}");
        let e = err(&GOOD.replace("\"nurds\"", "\"loop\""));
        assert!(
            e.to_string()
                .starts_with("space.kind: scheme loop takes no knot intervals"),
            "{e}"
        );
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
