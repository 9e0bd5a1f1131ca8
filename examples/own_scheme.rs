//! Tutorial: add your own scheme (math doc section 12).
//!
//! A Catmull-Clark-type scheme with user-chosen vertex weights, defined here,
//! outside the crate, through the public API only, and then given the
//! toolkit's analysis, a parameter sweep and a report figure.
//!
//! The scheme keeps Catmull-Clark's edge and face points and replaces the
//! vertex rule by
//!
//! ```text
//! v' = (1 - beta - gamma) v + beta/n sum_i e_i + gamma/n sum_i f_i
//! ```
//!
//! (Catmull-Clark: `beta = 3/(2n)`, `gamma = 1/(4n)`; math doc section 8).
//! Run with `cargo run --release --example own_scheme [OUT.svg]`.
//!
//! Only [`Scheme::local_matrix`] is required. Everything else is an optional
//! capability with a documented default (the table in the docs of
//! `subdiv_lab::schemes`): a closed-form limit stencil, an exact matrix, a
//! structured or Fourier spectrum, a characteristic ring, and the cost model
//! the work estimates use ([`Scheme::cost_model`]; the default measures the
//! local matrix once, enough for this scheme).
//!
//! One capability is a duty here: the one-ring is too small for the
//! second-order (curvature) analysis, whose neighbourhood must hold the
//! support of the ring of patches around the vertex (math doc section 13.5).
//! [`Scheme::second_order_matrix`] therefore returns one patch's support,
//! the `2n + 8` points of Stam's patch: this scheme's one-ring rows, and
//! Catmull-Clark's regular (bicubic) rules for the 7 outer points.

use subdiv_lab::schemes::catmull_clark::patch_matrix;
use subdiv_lab::schemes::{Assembler, LocalMatrix, PointLabel, Role};
use subdiv_lab::spectral::{analyze, AnalyzeOptions};
use subdiv_lab::sweep::{run_csv, Plan, SchemeFactory, SweepSpec};
use subdiv_lab::Scheme;

/// Step 1: the configuration type. One valence, the scheme's parameters.
#[derive(Clone, Debug)]
pub struct VertexWeightCc {
    /// Valence of the extraordinary vertex (>= 3).
    pub n: usize,
    /// Total weight of the edge neighbours in the new vertex point.
    pub beta: f64,
    /// Total weight of the face neighbours in the new vertex point.
    pub gamma: f64,
}

impl VertexWeightCc {
    /// Catmull-Clark's own weights at valence `n`.
    pub fn catmull_clark(n: usize) -> Self {
        Self {
            n,
            beta: 1.5 / n as f64,
            gamma: 0.25 / n as f64,
        }
    }

    /// Step 2: validate the parameters (typed errors naming the value).
    pub fn new(n: usize, beta: f64, gamma: f64) -> subdiv_lab::Result<Self> {
        if n < 3 {
            return Err(subdiv_lab::Error::ValenceTooSmall { valence: n });
        }
        for (name, x) in [("beta", beta), ("gamma", gamma)] {
            if !(0.0..=1.0).contains(&x) {
                return Err(subdiv_lab::Error::InvalidParameter {
                    name,
                    value: x.to_string(),
                    reason: "vertex weights must lie in [0, 1]",
                });
            }
        }
        Ok(Self { n, beta, gamma })
    }
}

/// Step 3: the one required method, the local matrix on the one-ring
/// `v, e_0.., f_0..` (`f_i` is the far corner of the quad `v, e_i, f_i, e_{i+1}`).
impl Scheme for VertexWeightCc {
    fn name(&self) -> &str {
        "vertex-weight-cc"
    }

    fn valence(&self) -> usize {
        self.n
    }

    fn label(&self) -> String {
        format!(
            "n={}, beta={:.3}, gamma={:.3}",
            self.n, self.beta, self.gamma
        )
    }

    fn local_matrix(&self) -> subdiv_lab::Result<LocalMatrix<f64>> {
        let n = self.n;
        let (e, f) = (|i: usize| 1 + i % n, |i: usize| 1 + n + i % n);
        let labels: Vec<PointLabel> = std::iter::once(PointLabel::new(Role::Vertex, 0))
            .chain((0..n).map(|i| PointLabel::new(Role::EdgeNeighbour, i)))
            .chain((0..n).map(|i| PointLabel::new(Role::FaceNeighbour, i)))
            .collect();
        let mut a = Assembler::square(self.name(), n, labels);
        let nf = n as f64;
        a.add(0, 0, 1.0 - self.beta - self.gamma);
        for i in 0..n {
            a.add(0, e(i), self.beta / nf);
            a.add(0, f(i), self.gamma / nf);
            // edge point of v e_i: (6 v + 6 e_i + e_{i-1} + e_{i+1} + f_{i-1} + f_i) / 16
            let row = e(i);
            a.stencil(
                row,
                [
                    (0, 6.0 / 16.0),
                    (e(i), 6.0 / 16.0),
                    (e(i + n - 1), 1.0 / 16.0),
                    (e(i + 1), 1.0 / 16.0),
                    (f(i + n - 1), 1.0 / 16.0),
                    (f(i), 1.0 / 16.0),
                ],
            );
            // face point of v e_i f_i e_{i+1}
            a.stencil(
                f(i),
                [(0, 0.25), (e(i), 0.25), (f(i), 0.25), (e(i + 1), 0.25)],
            );
        }
        a.finish()
    }

    /// Step 4: the second-order neighbourhood (module docs): the patch
    /// matrix's labels and outer rows (regular rules, the same for this
    /// scheme as for Catmull-Clark), with this scheme's one-ring block.
    fn second_order_matrix(&self) -> subdiv_lab::Result<LocalMatrix<f64>> {
        let ring = self.local_matrix()?;
        let patch = patch_matrix::<f64>(self.n, &0.5)?;
        let m = ring.matrix().nrows();
        let mut a = Assembler::square(self.name(), self.n, patch.rows().to_vec());
        a.block(0, 0, ring.matrix());
        for i in m..patch.matrix().nrows() {
            a.stencil(i, (0..m + 7).map(|j| (j, patch.matrix()[(i, j)])));
        }
        a.finish()
    }
}

/// Step 4: a sweep plan over valences 3..=8 at the weights `beta`, `gamma`
/// (a configuration that fails validation records its error in its row).
pub fn valence_sweep(beta: f64, gamma: f64) -> Result<Plan, Box<dyn std::error::Error>> {
    let spec = SweepSpec::from_toml(
        "name = \"vertex-weight-cc\"\nscheme = \"catmull-clark\"\nvalences = [3, 4, 5, 6, 7, 8]\n\
         [space]\nkind = \"uniform\"\n[sampler]\nkind = \"grid\"\npoints_per_axis = 1\n\
         [columns]\ncharmap = true\n",
    )?;
    let cost = VertexWeightCc::catmull_clark(5).cost_model();
    let factory = SchemeFactory::new("vertex-weight-cc", cost, move |n| {
        Ok(Box::new(VertexWeightCc::new(n, beta, gamma)?) as Box<dyn Scheme>)
    });
    Ok(Plan::with_scheme(spec, factory)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Analysis: the same `analyze` as `subdiv-lab analyze`.
    let s = VertexWeightCc::catmull_clark(5);
    let a = analyze(&s, &AnalyzeOptions::default())?;
    println!(
        "{}: class {}, lambda1 = {:.6}",
        s.label(),
        a.subdominant.class.name(),
        a.subdominant.lambda1.re
    );

    // Heavy work is estimated first: the scheme's cost model at a valence
    // far beyond this machine is refused before anything is built.
    let too_big = subdiv_lab::budget::analyze(&s.cost_model(), 100_000, false);
    println!(
        "n = 100000 would need {} ({})",
        subdiv_lab::budget::format_bytes(too_big.bytes),
        too_big.what
    );

    // A sweep over valences through the engine of `subdiv-lab sweep` (the
    // same columns, shards and resume): a spec with a uniform space, and the
    // scheme as a factory valence -> configuration.
    print!("{}", run_csv(&valence_sweep(0.3, 0.05)?)?);

    // A report figure: the spectra of three members.
    let picks = [
        VertexWeightCc::new(5, 0.1, 0.05)?,
        VertexWeightCc::catmull_clark(5),
        VertexWeightCc::new(5, 0.45, 0.05)?,
    ];
    let refs: Vec<&dyn Scheme> = picks.iter().map(|s| s as &dyn Scheme).collect();
    let svg = subdiv_lab::report::figures::spectrum::spectrum_svg(
        &refs,
        (1200, 420),
        "vertex-weight Catmull-Clark, n = 5",
    )?;
    let out = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("own_scheme_spectra.svg"));
    std::fs::write(&out, svg)?;
    println!("figure: {}", out.display());
    Ok(())
}
