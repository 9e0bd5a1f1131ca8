//! Deterministic enumeration of a sweep's configurations, and sharding.
//!
//! Configurations are numbered `0..total` by a **configuration id**: valences in
//! spec order, and within a valence by sample index. The id alone determines the
//! parameters:
//!
//! * grid: the sample index is a mixed-radix number with one digit per free
//!   coordinate, the **last free coordinate varying fastest** (nested loops in
//!   coordinate order `r0, r1, ...` or `p0.., q0..`); digit `j` of `k` points maps
//!   to `(a (k - 1 - j) + b j) / (k - 1)` (ratios) or `a (b / a)^(j / (k - 1))` (intervals),
//!   end points exact; a single point is the (geometric) midpoint;
//! * random: coordinate `c` of sample `i` of valence `n` is
//!   `hash_uniform(seed, n, i, c)`, mapped linearly (ratios) or log-uniformly
//!   (intervals) onto `[a, b)`;
//! * Halton / Sobol: point `i + 1` (Halton, skipping the origin) or `i` (Sobol, Gray
//!   order, Joe-Kuo direction numbers, the origin included) of the `d`-dimensional
//!   sequence, `d` = free coordinates of valence `n`, scrambled per valence (stream
//!   `n`; Halton: random shift, Sobol: Owen's nested uniform scrambling) when asked,
//!   mapped as for random.
//!
//! So results never depend on thread count or sharding. A [`Shard`] `I/N` is the
//! set of ids with `id % N == I` (round-robin, so every shard gets the same mix of
//! cheap and expensive valences); shard `I/N` processes its ids in increasing order.

use super::sampler::{hash_uniform, Halton, Sobol};
use super::spec::{Sampler, SpaceKind, SweepSpec};
use super::SweepError;
use crate::budget::CostModel;
use crate::knots::{CornerIntervals, EdgeRatios};
use crate::scalar::{Rational, Scalar};
use crate::schemes::user::SchemeFile;
use crate::schemes::LocalScheme;
use crate::schemes::Scheme;
use crate::schemes::SchemeKind;
use std::fmt;
use std::ops::Deref;
use std::str::FromStr;
use std::sync::Arc;

/// A scheme of one's own for the sweep engine (a Rust [`Scheme`], a scheme
/// file, a Python object): its configuration at each valence, its name and
/// its work model. A [`Plan`] built with one ([`Plan::with_scheme`]) sweeps
/// the spec's valences with it instead of the spec's built-in scheme: same
/// columns, resume and shards.
///
/// ```
/// use subdiv_lab::schemes::user::SchemeFile;
/// use subdiv_lab::sweep::{output, Layout, Plan, SchemeFactory, Shard, SpectralEvaluator, Summary, SweepSpec};
/// let file = SchemeFile::parse_shared(include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/schemes/catmull-clark.toml"))).unwrap();
/// let factory = SchemeFactory::from_file(file);
/// let spec = SweepSpec::from_toml(r#"
/// scheme = "catmull-clark"
/// valences = [3, 5]
/// [space]
/// kind = "uniform"
/// [sampler]
/// kind = "grid"
/// points_per_axis = 1
/// "#).unwrap();
/// let plan = Plan::with_scheme(spec, factory).unwrap();
/// let layout = Layout::new(&plan);
/// let eval = SpectralEvaluator::new(plan.spec().columns);
/// let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
/// let mut csv = Vec::new();
/// layout.write_header(&mut csv).unwrap();
/// output::run(&plan, &layout, &eval, 0..plan.total(), &mut csv, &mut summary, &mut |_| {}).unwrap();
/// let text = String::from_utf8(csv).unwrap();
/// assert_eq!(text.lines().count(), 3);
/// assert!(text.lines().nth(1).unwrap().starts_with("0,3,standard,"));
/// ```
#[derive(Clone)]
pub struct SchemeFactory {
    name: String,
    identity: String,
    cost_model: CostModel,
    make: Arc<dyn Fn(usize) -> crate::Result<Box<dyn Scheme>> + Send + Sync>,
}

impl SchemeFactory {
    /// The factory `make` (valence -> configuration) of the scheme `name`
    /// with the work model `cost_model` (the sweep's estimate before it runs).
    pub fn new(
        name: &str,
        cost_model: CostModel,
        make: impl Fn(usize) -> crate::Result<Box<dyn Scheme>> + Send + Sync + 'static,
    ) -> Self {
        SchemeFactory {
            name: name.to_owned(),
            identity: name.to_owned(),
            cost_model,
            make: Arc::new(make),
        }
    }

    /// The configurations of a scheme file ([`SchemeFile::at`]); its parsed
    /// rule is the identity.
    pub fn from_file(file: Arc<SchemeFile>) -> Self {
        let identity = format!("{file:?}");
        let name = file.name().to_owned();
        let cost_model = file.cost_model();
        SchemeFactory::new(&name, cost_model, move |n| {
            Ok(Box::new(file.at(n)?) as Box<dyn Scheme>)
        })
        .with_identity(identity)
    }

    /// The scheme's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// What tells this scheme apart from others of the same name (default:
    /// the name), e.g. a scheme file's text: it enters [`Plan::digest`], so
    /// that `--resume` and `merge` refuse rows of another scheme.
    pub fn with_identity(mut self, identity: impl Into<String>) -> Self {
        self.identity = identity.into();
        self
    }
}

impl fmt::Debug for SchemeFactory {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SchemeFactory")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// The scheme of one configuration of a [`Plan`]: a built-in one (no
/// allocation) or one from a [`SchemeFactory`]; a `&dyn Scheme` through
/// `Deref`.
#[derive(Debug)]
pub enum Configured {
    /// A built-in scheme's configuration.
    Builtin(LocalScheme<f64>),
    /// A configuration of a scheme of one's own.
    Own(Box<dyn Scheme>),
}

impl Configured {
    /// The built-in configuration (`None` for a scheme of one's own).
    pub fn builtin(&self) -> Option<&LocalScheme<f64>> {
        match self {
            Configured::Builtin(b) => Some(b),
            Configured::Own(_) => None,
        }
    }
}

impl Deref for Configured {
    type Target = dyn Scheme;
    fn deref(&self) -> &(dyn Scheme + 'static) {
        match self {
            Configured::Builtin(b) => b,
            Configured::Own(s) => &**s,
        }
    }
}

/// One configuration of a sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Configuration {
    /// Stable configuration id.
    pub id: u64,
    /// Valence.
    pub valence: usize,
    /// All coordinates (sampled and fixed) in column order (see [`SpaceKind::families`]).
    pub coordinates: Vec<f64>,
}

#[derive(Clone, Debug)]
enum Generator {
    Grid {
        k: u64,
    },
    Random {
        seed: u64,
    },
    Halton(Halton),
    Sobol(Sobol),
    /// A Sobol block beyond the shipped direction numbers (refused by spec
    /// validation; reported by [`Plan::configuration`] for hand-built specs).
    SobolTooLarge(super::sampler::SobolDimensionError),
}

#[derive(Clone, Debug)]
struct Block {
    valence: usize,
    offset: u64,
    /// Positions of the free coordinates.
    free: Vec<usize>,
    /// Fixed coordinates (position, value).
    fixed: Vec<(usize, f64)>,
    generator: Generator,
}

/// The enumeration of a validated spec.
#[derive(Clone, Debug)]
pub struct Plan {
    spec: SweepSpec,
    blocks: Vec<Block>,
    total: u64,
    /// The scheme of one's own, replacing the spec's built-in scheme.
    own: Option<SchemeFactory>,
}

impl Plan {
    /// Builds the enumeration (cheap: per-valence sequence tables only).
    pub fn new(spec: SweepSpec) -> Plan {
        let mut blocks = Vec::with_capacity(spec.valences.len());
        let mut offset = 0u64;
        let kind = spec.space.kind;
        for &n in &spec.valences {
            let fixed: Vec<(usize, f64)> = spec
                .space
                .fixed
                .iter()
                .filter_map(|(name, v)| kind.coordinate_index(n, name).map(|k| (k, *v)))
                .collect();
            let free: Vec<usize> = (0..kind.dimension(n))
                .filter(|k| !fixed.iter().any(|(f, _)| f == k))
                .collect();
            let d = free.len();
            let generator = match spec.sampler {
                Sampler::Grid { points_per_axis } => Generator::Grid { k: points_per_axis },
                Sampler::Random { seed, .. } => Generator::Random { seed },
                Sampler::Halton { scramble_seed, .. } => {
                    Generator::Halton(Halton::new(d, scramble_seed, n as u64))
                }
                Sampler::Sobol { scramble_seed, .. } => {
                    match Sobol::new(d, scramble_seed, n as u64) {
                        Ok(s) => Generator::Sobol(s),
                        Err(e) => Generator::SobolTooLarge(e),
                    }
                }
            };
            let count = spec.count_for(n);
            blocks.push(Block {
                valence: n,
                offset,
                free,
                fixed,
                generator,
            });
            offset += count;
        }
        Plan {
            spec,
            blocks,
            total: offset,
            own: None,
        }
    }

    /// The spec.
    pub fn spec(&self) -> &SweepSpec {
        &self.spec
    }

    /// Number of configurations.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// Largest valence of the sweep.
    pub fn max_valence(&self) -> usize {
        self.spec.valences.iter().copied().max().unwrap_or(3)
    }

    /// Names of the coordinate columns (for the largest valence; rows of smaller
    /// valences leave the extra cells empty).
    pub fn coordinate_columns(&self) -> Vec<String> {
        let kind = self.spec.space.kind;
        let n = self.max_valence();
        (0..kind.dimension(n))
            .map(|k| kind.coordinate_name(n, k))
            .collect()
    }

    /// Names of the columns derived from the coordinates, written after them:
    /// for a corner-interval space the edge ratios `r0..r{N-1}` (`N` the
    /// largest valence) the scheme is built from, `r_i = q_{i+1} / (p_i +
    /// q_{i+1})` (math doc section 2); none for the other spaces (a `ratios`
    /// space samples the `r_i` themselves).
    pub fn derived_columns(&self) -> Vec<String> {
        match self.spec.space.kind {
            SpaceKind::CornerIntervals => {
                (0..self.max_valence()).map(|i| format!("r{i}")).collect()
            }
            _ => Vec::new(),
        }
    }

    /// The derived cells of configuration `c` ([`derived_columns`](Self::derived_columns))
    /// into `out` (one per derived column): the edge ratios of a corner-interval
    /// configuration, computed as [`scheme`](Self::scheme) computes them (so
    /// they are the `r_i` of its matrix bit for bit); `None` beyond the valence,
    /// and for every cell when the intervals give no ratios (the row then
    /// carries the error).
    pub fn derived_into(&self, c: &Configuration, out: &mut [Option<f64>]) {
        out.fill(None);
        if self.spec.space.kind != SpaceKind::CornerIntervals {
            return;
        }
        let n = c.valence;
        if c.coordinates.len() != 2 * n {
            return;
        }
        let (p, q) = c.coordinates.split_at(n);
        if let Ok(r) = CornerIntervals::new(p.to_vec(), q.to_vec()).and_then(|k| k.ratios()) {
            for (o, x) in out.iter_mut().zip(r.as_slice()) {
                *o = Some(*x);
            }
        }
    }

    /// Column position of coordinate `k` of a valence-`n` configuration.
    pub fn coordinate_column(&self, n: usize, k: usize) -> usize {
        let big = self.max_valence();
        (k / n) * big + k % n
    }

    /// The configuration with this id.
    ///
    /// ```
    /// use subdiv_lab::sweep::{Plan, SweepSpec};
    /// let spec = SweepSpec::from_toml(r#"
    /// scheme = "nurds"
    /// valences = [3]
    /// [space]
    /// kind = "ratios"
    /// ratio_range = [0.2, 0.8]
    /// fixed = { r2 = 0.5 }
    /// [sampler]
    /// kind = "grid"
    /// points_per_axis = 3
    /// "#).unwrap();
    /// let plan = Plan::new(spec);
    /// assert_eq!(plan.total(), 9);
    /// // Last free coordinate fastest: id 1 = (r0, r1) = (0.2, 0.5).
    /// assert_eq!(plan.configuration(1).unwrap().coordinates, vec![0.2, 0.5, 0.5]);
    /// assert!(plan.configuration(9).is_err());
    /// ```
    pub fn configuration(&self, id: u64) -> Result<Configuration, SweepError> {
        let mut c = Configuration {
            id,
            valence: 0,
            coordinates: Vec::new(),
        };
        self.configuration_into(id, &mut c, &mut Vec::new())?;
        Ok(c)
    }

    /// [`configuration`](Self::configuration) into `c`, reusing its coordinate
    /// storage and `scratch` (the sweep driver's allocation-free path). On an
    /// error `c` is unspecified.
    pub(crate) fn configuration_into(
        &self,
        id: u64,
        c: &mut Configuration,
        scratch: &mut Vec<f64>,
    ) -> Result<(), SweepError> {
        if id >= self.total {
            return Err(SweepError::IdOutOfRange {
                id,
                total: self.total,
            });
        }
        let b = match self.blocks.binary_search_by(|b| b.offset.cmp(&id)) {
            Ok(i) => {
                // Several blocks can share an offset only if some have count 0 (impossible:
                // counts are >= 1); take the block starting here.
                &self.blocks[i]
            }
            Err(i) => &self.blocks[i - 1],
        };
        let local = id - b.offset;
        let n = b.valence;
        let kind = self.spec.space.kind;
        c.id = id;
        c.valence = n;
        let coords = &mut c.coordinates;
        coords.clear();
        coords.resize(kind.dimension(n), 0.0);
        for &(k, v) in &b.fixed {
            coords[k] = v;
        }
        let (lo, hi) = self.spec.space.range.unwrap_or((0.5, 0.5));
        let log = kind.is_log();
        let map = |u: f64| -> f64 {
            if log {
                (lo.ln() + u * (hi.ln() - lo.ln())).exp().clamp(lo, hi)
            } else {
                (lo + u * (hi - lo)).clamp(lo, hi)
            }
        };
        match &b.generator {
            Generator::Grid { k } => {
                let mut rest = local;
                for &pos in b.free.iter().rev() {
                    let j = rest % k;
                    rest /= k;
                    coords[pos] = if *k == 1 {
                        map(0.5)
                    } else if j == 0 {
                        lo
                    } else if j == k - 1 {
                        hi
                    } else if log {
                        map(j as f64 / (k - 1) as f64)
                    } else {
                        // (a (k-1-j) + b j) / (k-1): decimal-looking values for decimal bounds.
                        ((lo * (k - 1 - j) as f64 + hi * j as f64) / (k - 1) as f64).clamp(lo, hi)
                    };
                }
            }
            Generator::Random { seed } => {
                for (c, &pos) in b.free.iter().enumerate() {
                    coords[pos] = map(hash_uniform(*seed, n as u64, local, c as u64));
                }
            }
            Generator::Halton(h) => {
                scratch.clear();
                scratch.resize(b.free.len(), 0.0);
                h.point(local + 1, scratch);
                for (&pos, &x) in b.free.iter().zip(scratch.iter()) {
                    coords[pos] = map(x);
                }
            }
            Generator::Sobol(s) => {
                scratch.clear();
                scratch.resize(b.free.len(), 0.0);
                s.point(local, scratch);
                for (&pos, &x) in b.free.iter().zip(scratch.iter()) {
                    coords[pos] = map(x);
                }
            }
            Generator::SobolTooLarge(e) => {
                return Err(SweepError::Spec {
                    key: "sampler.kind".into(),
                    line: None,
                    message: format!("sampler.kind: valence {n}: {e}"),
                })
            }
        }
        Ok(())
    }

    /// The plan of `spec` with a scheme of one's own in place of the spec's
    /// scheme. The spec's space must be `uniform` (the factory's parameter is
    /// the valence only) and its columns must not ask for the exact
    /// certificate (a built-in notion of the Doo-Sabin family).
    pub fn with_scheme(spec: SweepSpec, factory: SchemeFactory) -> Result<Plan, SweepError> {
        let refuse = |key: &str, message: String| SweepError::Spec {
            key: key.to_owned(),
            line: None,
            message,
        };
        if spec.sector.is_some() {
            return Err(refuse(
                "sector",
                format!(
                    "sector: a [sector] sweep runs the boundary rules of catmull-clark and loop; scheme {} sweeps valences only",
                    factory.name
                ),
            ));
        }
        if spec.space.kind != SpaceKind::Uniform {
            return Err(refuse(
                "space.kind",
                format!(
                    "space.kind: scheme {} sweeps valences only; use kind = \"uniform\"",
                    factory.name
                ),
            ));
        }
        if spec.columns.exact_certificate {
            return Err(refuse(
                "columns.exact_certificate",
                format!(
                    "columns.exact_certificate: scheme {} has no exact face-block certificate (the Doo-Sabin family's)",
                    factory.name
                ),
            ));
        }
        let mut plan = Plan::new(spec);
        plan.own = Some(factory);
        Ok(plan)
    }

    /// The digest that ties output files to this plan: the spec's
    /// ([`SweepSpec::digest`]), or with a scheme of one's own the digest of
    /// the spec's digest, the scheme's name and its identity
    /// ([`SchemeFactory::with_identity`]).
    pub fn digest(&self) -> String {
        let spec = self.spec.digest();
        match &self.own {
            None => spec,
            Some(f) => {
                let text = format!("{spec}\n{}\n{}", f.name, f.identity);
                format!("{:016x}", crate::hash::fnv1a64(text.as_bytes()))
            }
        }
    }

    /// The work model of the plan's scheme (the spec's built-in scheme or
    /// the [`SchemeFactory`]'s).
    pub fn cost_model(&self) -> CostModel {
        match (&self.own, &self.spec.sector) {
            (Some(f), _) => f.cost_model,
            (None, Some(s)) => {
                crate::boundary::sector_cost_model(sdc_scheme(self.spec.scheme), s.vertex)
            }
            (None, None) => LocalScheme::<f64>::cost_model_of(self.spec.scheme),
        }
    }

    /// The boundary, crease or corner configuration of `c` in a `[sector]`
    /// sweep (`None` otherwise): the spec's scheme, vertex kind and rules,
    /// `K = c.valence` faces per sector (a crease: `K, K`) and, for a
    /// corner, the angle coordinate in degrees.
    pub fn sector_config(
        &self,
        c: &Configuration,
    ) -> Option<crate::Result<crate::boundary::SectorConfig>> {
        let s = self.spec.sector?;
        let k = c.valence;
        let faces: &[usize] = if s.vertex == crate::boundary::VertexKind::Crease {
            &[k, k]
        } else {
            &[k]
        };
        let angle = (self.spec.space.kind == SpaceKind::CornerAngle)
            .then(|| c.coordinates.first().copied())
            .flatten();
        Some(crate::boundary::SectorConfig::new(
            sdc_scheme(self.spec.scheme),
            s.vertex,
            faces,
            angle,
            s.rules,
        ))
    }

    /// The scheme of a configuration, in `f64` (a built-in scheme through
    /// [`LocalScheme`], or the plan's [`SchemeFactory`]).
    pub fn scheme(&self, c: &Configuration) -> crate::Result<Configured> {
        if let Some(f) = &self.own {
            return (f.make)(c.valence).map(Configured::Own);
        }
        if let Some(sector) = self.sector_config(c) {
            return Ok(Configured::Own(Box::new(sector?)));
        }
        let (ratios, shape) = self.parameters_in(c)?;
        LocalScheme::from_kind_with_c(self.spec.scheme, c.valence, ratios, shape)
            .map(Configured::Builtin)
    }

    /// [`scheme`](Self::scheme), reusing the storage of `old` (the scheme of
    /// an earlier configuration) where it can: NURDS over edge ratios of the
    /// same valence refills `old`'s ratios
    /// ([`EdgeRatios::refilled`](crate::knots::EdgeRatios::refilled)), saving
    /// the allocations of a new scheme per configuration; anything else is
    /// built anew. The result equals `self.scheme(c)`.
    pub fn scheme_reusing(
        &self,
        c: &Configuration,
        old: Option<Configured>,
    ) -> crate::Result<Configured> {
        if self.spec.space.kind == SpaceKind::Ratios && self.spec.scheme == SchemeKind::Nurds {
            if let Some(Configured::Builtin(LocalScheme::Nurds(r))) = old {
                if r.valence() == c.valence && c.coordinates.len() == c.valence {
                    return Ok(Configured::Builtin(LocalScheme::Nurds(
                        r.refilled(&c.coordinates)?,
                    )));
                }
            }
        }
        self.scheme(c)
    }

    /// The scheme of a configuration in exact rational arithmetic (every `f64`
    /// coordinate is a dyadic rational; the ratios are derived exactly from it).
    pub fn exact_scheme(&self, c: &Configuration) -> crate::Result<LocalScheme<Rational>> {
        if let Some(f) = &self.own {
            return Err(crate::Error::NotApplicable {
                scheme: f.name.clone(),
                operation: "a built-in exact configuration",
            });
        }
        if self.spec.sector.is_some() {
            return Err(crate::Error::NotApplicable {
                scheme: self.spec.scheme.to_string(),
                operation: "an exact configuration of a [sector] sweep",
            });
        }
        let (ratios, shape) = self.parameters_in(c)?;
        LocalScheme::from_kind_with_c(self.spec.scheme, c.valence, ratios, shape)
    }

    /// The edge ratios (`None`: uniform) and the shape parameter of a
    /// configuration, in `T`.
    #[allow(clippy::type_complexity)]
    fn parameters_in<T: Scalar>(
        &self,
        c: &Configuration,
    ) -> crate::Result<(Option<EdgeRatios<T>>, Option<T>)> {
        let n = c.valence;
        let x: Vec<T> = c
            .coordinates
            .iter()
            .map(|v| T::from_f64_lossless(*v))
            .collect();
        Ok(match self.spec.space.kind {
            SpaceKind::Shape => (None, x.into_iter().next()),
            SpaceKind::Uniform => (None, None),
            SpaceKind::Ratios => (Some(EdgeRatios::new(x)?), None),
            SpaceKind::CornerIntervals => (
                Some(CornerIntervals::new(x[..n].to_vec(), x[n..].to_vec())?.ratios()?),
                None,
            ),
            SpaceKind::FaceEp => (Some(EdgeRatios::face_ep(&x[..n], &x[n..])?), None),
            SpaceKind::VertexEp => (Some(EdgeRatios::vertex_ep(&x)?), None),
            // the corner angle is a parameter of the sector configuration
            // (`sector_config`), not of a built-in interior scheme
            SpaceKind::CornerAngle => {
                return Err(crate::Error::NotApplicable {
                    scheme: self.spec.scheme.to_string(),
                    operation: "a corner angle outside a [sector] sweep",
                })
            }
        })
    }
}

/// The boundary rules' scheme of a `[sector]` sweep's scheme (validated to
/// be catmull-clark or loop; anything else is Loop's triangle topology).
fn sdc_scheme(kind: SchemeKind) -> crate::mesh::sharp::rules::SdcScheme {
    match kind {
        SchemeKind::CatmullClark => crate::mesh::sharp::rules::SdcScheme::CatmullClark,
        _ => crate::mesh::sharp::rules::SdcScheme::Loop,
    }
}

/// A shard `I/N`: the configurations with `id % N == I`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shard {
    /// Shard index `I` (0-based, `< count`).
    pub index: u64,
    /// Number of shards `N >= 1`.
    pub count: u64,
}

impl Shard {
    /// The whole sweep (`0/1`).
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Validated shard.
    pub fn new(index: u64, count: u64) -> Result<Shard, SweepError> {
        if count == 0 || index >= count {
            return Err(SweepError::BadShard(format!("{index}/{count}")));
        }
        Ok(Shard { index, count })
    }

    /// Number of configurations of this shard in a sweep of `total`.
    pub fn len(&self, total: u64) -> u64 {
        if self.index >= total {
            0
        } else {
            (total - self.index - 1) / self.count + 1
        }
    }

    /// Whether the shard is empty in a sweep of `total`.
    pub fn is_empty(&self, total: u64) -> bool {
        self.len(total) == 0
    }

    /// The `j`-th id of this shard.
    pub fn id(&self, j: u64) -> u64 {
        self.index + j * self.count
    }

    /// Whether `id` belongs to the shard.
    pub fn contains(&self, id: u64) -> bool {
        id % self.count == self.index
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = SweepError;
    /// `"I/N"`.
    ///
    /// ```
    /// use subdiv_lab::sweep::Shard;
    /// let s: Shard = "2/8".parse().unwrap();
    /// assert_eq!((s.index, s.count), (2, 8));
    /// assert!("8/8".parse::<Shard>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Shard, SweepError> {
        let bad = || SweepError::BadShard(s.to_owned());
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i: u64 = i.trim().parse().map_err(|_| bad())?;
        let n: u64 = n.trim().parse().map_err(|_| bad())?;
        Shard::new(i, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(space: &str, sampler: &str) -> SweepSpec {
        SweepSpec::from_toml(&format!(
            "scheme = \"nurds\"\nvalences = [3, 5]\n[space]\n{space}\n[sampler]\n{sampler}\n"
        ))
        .unwrap()
    }

    #[test]
    fn grid_enumerates_every_point_once() {
        let p = Plan::new(spec(
            "kind = \"ratios\"\nratio_range = [0.25, 0.75]",
            "kind = \"grid\"\npoints_per_axis = 3",
        ));
        assert_eq!(p.total(), 27 + 243);
        let mut seen = std::collections::HashSet::new();
        for id in 0..p.total() {
            let c = p.configuration(id).unwrap();
            assert_eq!(c.valence, if id < 27 { 3 } else { 5 });
            assert!(c.coordinates.iter().all(|x| [0.25, 0.5, 0.75].contains(x)));
            let key: Vec<u64> = c.coordinates.iter().map(|x| x.to_bits()).collect();
            assert!(seen.insert(key));
            assert!(p.scheme(&c).is_ok());
        }
        assert_eq!(p.configuration(26).unwrap().coordinates, vec![0.75; 3]);
        assert_eq!(p.configuration(27).unwrap().coordinates, vec![0.25; 5]);
    }

    #[test]
    fn samplers_stay_in_range_and_are_deterministic() {
        for sampler in [
            "kind = \"random\"\ncount = 200\nseed = 4",
            "kind = \"halton\"\ncount = 200",
            "kind = \"sobol\"\ncount = 200\nscramble = true\nseed = 2",
        ] {
            let p = Plan::new(spec(
                "kind = \"corner-intervals\"\ninterval_range = [0.01, 100.0]\nfixed = { q1 = 2.0 }",
                sampler,
            ));
            let q = Plan::new(p.spec().clone());
            for id in 0..p.total() {
                let c = p.configuration(id).unwrap();
                assert_eq!(c, q.configuration(id).unwrap());
                assert_eq!(c.coordinates.len(), 2 * c.valence);
                assert_eq!(c.coordinates[c.valence + 1], 2.0);
                assert!(c.coordinates.iter().all(|x| (0.01..=100.0).contains(x)));
                let s = p.scheme(&c).unwrap();
                let e = p.exact_scheme(&c).unwrap();
                for (a, b) in s
                    .builtin()
                    .unwrap()
                    .ratios()
                    .as_slice()
                    .iter()
                    .zip(e.ratios().as_slice())
                {
                    assert!((a - b.to_f64()).abs() < 1e-15);
                }
            }
        }
    }

    #[test]
    fn shards_partition() {
        for total in [0u64, 1, 7, 100] {
            for n in 1..6 {
                let mut all: Vec<u64> = (0..n)
                    .flat_map(|i| {
                        let s = Shard::new(i, n).unwrap();
                        (0..s.len(total)).map(move |j| s.id(j))
                    })
                    .collect();
                all.sort();
                assert_eq!(all, (0..total).collect::<Vec<_>>());
            }
        }
        assert!("1/0".parse::<Shard>().is_err());
        assert!("x/2".parse::<Shard>().is_err());
    }
}
