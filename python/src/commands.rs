//! The other commands: `subdivide`, `report`, `verify`, `g2-cap`, `plot`,
//! `cc-study` and `ccss-bound`, each calling the library code its CLI command
//! calls, with the same checks and limits. The Python side reads and writes
//! the files.

use crate::{guard, lib_err, limit, runtime_err, scheme_choice, value_err, Int, SpecOrigin, PY};
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use subdiv_lab::budget::{SWEEP_TIME_LIMIT_SECONDS, TIME_LIMIT_SECONDS};

/// A refined mesh: vertex positions `(m, 3)` and faces.
type MeshOut<'py> = (Bound<'py, PyArray2<f64>>, Vec<Vec<usize>>);

/// The `(m, 3)` points of `vertices` (any other shape is a `ValueError`).
fn points(name: &str, vertices: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 3]>> {
    let shape = vertices.shape();
    if shape.get(1) != Some(&3) {
        return Err(value_err(format!(
            "{name} must have shape (m, 3), got {shape:?}"
        )));
    }
    Ok(vertices
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// Faces as lists of vertex indices (a negative or huge index is a
/// `ValueError` naming it; the mesh checks the range).
fn face_lists(faces: Vec<Vec<Int>>) -> PyResult<Vec<Vec<usize>>> {
    faces
        .into_iter()
        .enumerate()
        .map(|(i, f)| {
            f.into_iter()
                .enumerate()
                .map(|(j, v)| v.usize(&format!("faces[{i}][{j}]")))
                .collect()
        })
        .collect()
}

/// `(m, 3)` points as a numpy array (`(0, 3)` when empty).
fn points_array<'py>(py: Python<'py>, pos: &[[f64; 3]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if pos.is_empty() {
        return Ok(PyArray2::zeros(py, [0, 3], false));
    }
    let rows: Vec<Vec<f64>> = pos.iter().map(|p| p.to_vec()).collect();
    PyArray2::from_vec2(py, &rows).map_err(runtime_err)
}

/// `subdivide`: `levels` refinement steps of a closed polygon mesh, through
/// the scheme's mesh rules (as `subdiv-lab subdivide`).
#[pyfunction]
#[pyo3(signature = (vertices, faces, scheme="nurds", knots=None, levels=Int(1), c=None, force=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn subdivide<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: Vec<Vec<Int>>,
    scheme: &str,
    knots: Option<Vec<((Int, Int), f64)>>,
    levels: Int,
    c: Option<f64>,
    force: bool,
) -> PyResult<MeshOut<'py>> {
    use subdiv_lab::mesh::refine::half_edges_after;
    use subdiv_lab::mesh::rules::KnotUse;
    use subdiv_lab::mesh::{knot_file, Mesh, MAX_HALF_EDGES};
    guard("subdivide", || {
        let kind = scheme_choice(scheme, knots.is_some(), c.is_some())?;
        let levels = levels.usize("levels")?;
        let positions = points("vertices", &vertices)?;
        let faces = face_lists(faces)?;
        let mut mesh = Mesh::from_polygons(positions, &faces).map_err(lib_err)?;
        let rules = subdiv_lab::mesh::builtin::mesh_rules(kind, c).map_err(lib_err)?;
        if rules.knots() != KnotUse::None {
            // every directed edge 1, then the given ones (the CLI's default interval)
            knot_file::apply_knot_text(&mut mesh, "", 1.0).map_err(lib_err)?;
        }
        for ((a, b), x) in knots.unwrap_or_default() {
            let (a, b) = (a.usize("knots: a vertex")?, b.usize("knots: a vertex")?);
            let h = mesh.find_half_edge(a, b).ok_or_else(|| {
                value_err(format!("knots: ({a}, {b}) is not an edge of the mesh"))
            })?;
            mesh.set_knot(h, x).map_err(lib_err)?;
        }
        let needed = half_edges_after(&mesh, levels);
        if needed > MAX_HALF_EDGES {
            return Err(value_err(format!(
                "levels {levels}: the result would have {needed} half-edges (limit {MAX_HALF_EDGES})"
            )));
        }
        limit(
            "subdivide",
            &format!("levels {levels}"),
            &subdiv_lab::budget::subdivide(needed),
            TIME_LIMIT_SECONDS,
            force,
        )?;
        let mesh = py.detach(move || -> Result<Mesh, subdiv_lab::mesh::MeshError> {
            for _ in 0..levels {
                mesh = rules.refine(&mesh)?;
            }
            Ok(mesh)
        });
        let mesh = mesh.map_err(lib_err)?;
        let faces: Vec<Vec<usize>> = (0..mesh.face_count())
            .map(|f| mesh.face_vertices(f).collect())
            .collect();
        Ok((points_array(py, mesh.positions())?, faces))
    })
}

/// A report error as a Python exception: the spec and the inputs of the
/// figures are input (`ValueError`, phrased for where the spec came from),
/// as is an analysis that failed on its input; anything else `RuntimeError`.
fn report_err(e: subdiv_lab::report::ReportError, origin: &SpecOrigin) -> PyErr {
    use subdiv_lab::report::ReportError as R;
    match &e {
        R::Spec { key, message, .. } => origin.error(key.as_deref(), message, &e.to_string()),
        R::Input { .. } => value_err(e.to_string()),
        R::Analysis { source, .. } if source.is_input_error() => value_err(e.to_string()),
        _ => runtime_err(e),
    }
}

/// `report`: the files of a report (`(relative path, bytes)`), generated with
/// the GIL released; the Python side writes them.
#[pyfunction]
#[pyo3(signature = (spec_toml, spec_path=None, from_dict=false))]
pub(crate) fn report_files(
    py: Python<'_>,
    spec_toml: &str,
    spec_path: Option<String>,
    from_dict: bool,
) -> PyResult<Vec<(String, pyo3::Py<PyBytes>)>> {
    use subdiv_lab::report::{figures::NoProgress, generate, ReportSpec, RunInfo};
    guard("report", || {
        let origin = SpecOrigin::new(spec_path.clone(), from_dict);
        // Scheme files are read beside the spec file (the current directory
        // for a spec given as text or a dict).
        let base = spec_path
            .as_deref()
            .and_then(|p| std::path::Path::new(p).parent())
            .map(std::path::Path::to_path_buf)
            .unwrap_or_default();
        let read = |p: &str| std::fs::read_to_string(base.join(p)).map_err(|e| e.to_string());
        let spec = ReportSpec::parse_with(spec_toml, &read).map_err(|e| report_err(e, &origin))?;
        let run = RunInfo {
            version: Some(subdiv_lab::spectral::json::TOOL_VERSION.to_owned()),
            git_revision: None,
            spec_path,
            spec_builtin: false,
        };
        let report = py
            .detach(|| generate(&spec, &run, &NoProgress))
            .map_err(|e| report_err(e, &origin))?;
        Ok(report
            .files
            .into_iter()
            .map(|f| (f.path, PyBytes::new(py, &f.bytes).unbind()))
            .collect())
    })
}

/// `verify`: `(summary JSON, cells CSV)` of a verify spec, as
/// `subdiv-lab verify` writes them to `summary.json` and `cells.csv`.
#[pyfunction]
#[pyo3(signature = (spec_toml, spec_path=None, from_dict=false, threads=None, max_cells=None, force=false))]
pub(crate) fn verify(
    py: Python<'_>,
    spec_toml: &str,
    spec_path: Option<String>,
    from_dict: bool,
    threads: Option<Int>,
    max_cells: Option<Int>,
    force: bool,
) -> PyResult<(String, String)> {
    use subdiv_lab::verify::{self as v, spec::VerifySpec, Limits};
    guard("verify", || {
        let origin = SpecOrigin::new(spec_path, from_dict);
        let spec = VerifySpec::parse(spec_toml).map_err(|e| origin.sweep_error(e))?;
        let threads = crate::threads(threads)?;
        let max_cells = match max_cells {
            Some(m) => m.u64("max_cells")?,
            None => v::DEFAULT_MAX_CELLS,
        };
        v::check_max_cells(max_cells, PY).map_err(value_err)?;
        let subject = match &origin {
            SpecOrigin::Path(p) => format!("{p} (max_cells={max_cells})"),
            _ => format!("spec {:?} (max_cells={max_cells})", spec.name),
        };
        limit(
            "verify",
            &subject,
            &v::estimate(&spec, max_cells, threads),
            SWEEP_TIME_LIMIT_SECONDS,
            force,
        )?;
        let pool = crate::pool(threads)?;
        let limits = Limits {
            max_cells,
            ..Limits::default()
        };
        let (summary, cells) = py.detach(|| {
            let outcome = pool.install(|| v::run(&spec, &limits));
            (v::summary(&spec, &outcome), v::cells_csv(&spec, &outcome))
        });
        let json = serde_json::to_string(&summary).map_err(runtime_err)?;
        Ok((json, cells))
    })
}

/// `g2-cap`: the JSON of `subdiv-lab g2-cap --json` for the 2-ring around
/// `vertex` of a mesh, or for a generated test net; with `samples`, also the
/// cap sampled on `samples x samples` quads per patch (the OBJ of `-o`).
#[pyfunction]
#[pyo3(signature = (c, vertices=None, faces=None, vertex=None, valence=None, random_net=None, samples=None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn g2_cap<'py>(
    py: Python<'py>,
    c: f64,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    faces: Option<Vec<Vec<Int>>>,
    vertex: Option<Int>,
    valence: Option<Int>,
    random_net: Option<Int>,
    samples: Option<Int>,
) -> PyResult<(String, Option<(Bound<'py, PyArray2<f64>>, Vec<[usize; 4]>)>)> {
    use subdiv_lab::g2cap::ring::TwoRing;
    use subdiv_lab::g2cap::{check_samples, G2Cap};
    guard("g2_cap", || {
        let samples = match samples {
            Some(s) => {
                let s = s.usize("samples")?;
                check_samples(s, PY).map_err(value_err)?;
                Some(s)
            }
            None => None,
        };
        let mesh_given = vertices.is_some() || faces.is_some() || vertex.is_some();
        let net_given = valence.is_some() || random_net.is_some();
        let ring = match (mesh_given, net_given) {
            (true, true) => {
                return Err(value_err(
                    "give either vertices, faces and vertex or valence and random_net, not both",
                ))
            }
            (false, false) => {
                return Err(value_err(
                    "nothing to cap: give vertices, faces and vertex (the extraordinary vertex, 0-based) or valence and random_net",
                ))
            }
            (true, false) => {
                let (Some(vs), Some(fs), Some(v)) = (&vertices, faces, vertex) else {
                    return Err(value_err(
                        "a mesh needs vertices, faces and vertex (the extraordinary vertex, 0-based)",
                    ));
                };
                let positions = points("vertices", vs)?;
                let faces = face_lists(fs)?;
                let v = v.usize("vertex")?;
                TwoRing::from_polygons(&positions, &faces, v)
                    .map(|(r, _)| r)
                    .map_err(lib_err)?
            }
            (false, true) => {
                let (Some(n), Some(seed)) = (valence, random_net) else {
                    return Err(value_err("a generated net needs valence and random_net (its seed)"));
                };
                TwoRing::random(n.usize("valence")?, seed.u64("random_net")?).map_err(lib_err)?
            }
        };
        let (json, mesh) = py
            .detach(|| -> Result<_, subdiv_lab::g2cap::G2CapError> {
                let cap = G2Cap::build(&ring, c)?;
                cap.check()?;
                let json = cap.to_json().to_string();
                Ok((json, samples.map(|s| cap.sample_mesh(s))))
            })
            .map_err(lib_err)?;
        let mesh = match mesh {
            Some((pts, quads)) => Some((points_array(py, &pts)?, quads)),
            None => None,
        };
        Ok((json, mesh))
    })
}

/// `plot`: the figure (SVG text or PNG bytes) of a sweep's CSV or Parquet
/// file (`name` for messages and the format; `data` its bytes).
#[pyfunction]
#[pyo3(signature = (data, name, svg, kind=None, x=None, y=None, color=None, title=None, width=Int(1600), height=Int(1000), force=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn plot<'py>(
    py: Python<'py>,
    data: &[u8],
    name: &str,
    svg: bool,
    kind: Option<&str>,
    x: Option<String>,
    y: Option<String>,
    color: Option<String>,
    title: Option<String>,
    width: Int,
    height: Int,
    force: bool,
) -> PyResult<Bound<'py, PyBytes>> {
    use subdiv_lab::report::sweep_plot::{self, PlotRequest, SweepPlot};
    use subdiv_lab::report::{render_png, render_svg, Area};
    guard("plot", || {
        let (width, height) = (width.u32("width")?, height.u32("height")?);
        let kind = sweep_plot::check_options(kind, width, height, PY).map_err(value_err)?;
        let table = subdiv_lab::sweep::output::read_output(name, data)
            .map_err(|e| value_err(format!("{name}: {e}")))?;
        limit(
            "plot",
            name,
            &sweep_plot::estimate(table.len(), table.names().len(), data.len() as u64),
            TIME_LIMIT_SECONDS,
            force,
        )?;
        let request = PlotRequest { kind, x, y, color };
        let plot =
            SweepPlot::build(&table, &request).map_err(|e| value_err(format!("{name}: {e}")))?;
        let title = title.unwrap_or_else(|| plot.default_title());
        let size = (width, height);
        let bytes = py
            .detach(|| {
                let draw = |area: &Area<'_>| plot.draw(area, &title, size);
                if svg {
                    render_svg(size, &draw).map(String::into_bytes)
                } else {
                    render_png(size, &draw)
                }
            })
            .map_err(runtime_err)?;
        Ok(PyBytes::new(py, &bytes))
    })
}

/// `cc-study`: the rows of `subdiv-lab cc-study` (the curves, or the
/// certified intervals of `c`) as JSON text, one object per CSV row.
#[pyfunction]
#[pyo3(signature = (n_min=Int(3), n_max=Int(32), samples=Int(100), tol=1e-6, curves=false, criterion="c1", force=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn cc_study(
    py: Python<'_>,
    n_min: Int,
    n_max: Int,
    samples: Int,
    tol: f64,
    curves: bool,
    criterion: &str,
    force: bool,
) -> PyResult<String> {
    use subdiv_lab::cc_study::{check_study, intervals, study_curve_rows, Criterion};
    guard("cc_study", || {
        let (n_min, n_max) = (n_min.usize("n_min")?, n_max.usize("n_max")?);
        let samples = samples.usize("samples")?;
        check_study(n_min, n_max, samples, tol, PY).map_err(value_err)?;
        let criterion = match criterion {
            "c1" => Criterion::C1,
            "standard" => Criterion::Standard,
            other => {
                return Err(value_err(format!(
                    "criterion must be \"c1\" or \"standard\", got {other:?}"
                )))
            }
        };
        limit(
            "cc_study",
            &format!("valences {n_min}..{n_max}"),
            &subdiv_lab::budget::cc_study(n_min, n_max, samples, curves),
            TIME_LIMIT_SECONDS,
            force,
        )?;
        let rows = py.detach(|| -> subdiv_lab::spectral::Result<Vec<serde_json::Value>> {
            let mut rows = Vec::new();
            for n in n_min..=n_max {
                if curves {
                    for (c, row) in study_curve_rows(n, samples) {
                        rows.push(match row {
                            Ok(p) => serde_json::json!({
                                "n": n, "c": p.c,
                                "lambda1_re": p.lambda1[0], "lambda1_im": p.lambda1[1],
                                "lambda2_re": p.lambda2[0], "lambda2_im": p.lambda2[1],
                                "abs_lambda3": p.abs_lambda3, "class": p.class,
                                "fourier_subdominant": p.fourier_subdominant,
                                "charmap": p.charmap, "error": null,
                            }),
                            Err(e) => serde_json::json!({
                                "n": n, "c": c,
                                "lambda1_re": null, "lambda1_im": null,
                                "lambda2_re": null, "lambda2_im": null,
                                "abs_lambda3": null, "class": "error",
                                "fourier_subdominant": null,
                                "charmap": "error", "error": e.to_string(),
                            }),
                        });
                    }
                } else {
                    for (k, i) in intervals(n, samples, tol, criterion)?
                        .into_iter()
                        .enumerate()
                    {
                        rows.push(serde_json::json!({
                            "n": n, "interval": k, "c_lo": i.lo, "c_hi": i.hi,
                            "c_lo_outside": i.lo_outside, "c_hi_outside": i.hi_outside,
                            "below": i.below, "above": i.above,
                        }));
                    }
                }
            }
            Ok(rows)
        });
        let rows = rows.map_err(lib_err)?;
        serde_json::to_string(&rows).map_err(runtime_err)
    })
}

/// `ccss-bound`: the JSON of `subdiv-lab ccss-bound --json` for one valence
/// (with a control net and `epsilon`: the steps needed), or with `table_to`
/// the rows of the `beta(n)` table (JSON, one object per CSV row).
#[pyfunction]
#[pyo3(signature = (valence=None, levels=Int(4), table_to=None, net=None, epsilon=None, force=false))]
pub(crate) fn ccss_bound(
    py: Python<'_>,
    valence: Option<Int>,
    levels: Int,
    table_to: Option<Int>,
    net: Option<Vec<Vec<f64>>>,
    epsilon: Option<f64>,
    force: bool,
) -> PyResult<String> {
    use subdiv_lab::ccss_bound::bound::beta_table;
    use subdiv_lab::ccss_bound::summary::{check_levels, check_table_to, BoundSummary};
    guard("ccss_bound", || {
        let levels = levels.u32("levels")?;
        check_levels(levels, PY).map_err(value_err)?;
        if net.is_some() != epsilon.is_some() {
            return Err(value_err(
                "net and epsilon go together: give both or neither",
            ));
        }
        match (valence, table_to) {
            (Some(_), Some(_)) => Err(value_err("give valence or table_to, not both")),
            (None, None) => Err(value_err(
                "give valence (or table_to for the beta(n) table)",
            )),
            (None, Some(max)) => {
                if net.is_some() {
                    return Err(value_err("net and epsilon go with valence, not table_to"));
                }
                let max = max.usize("table_to")?;
                check_table_to(max, PY).map_err(value_err)?;
                limit(
                    "ccss_bound",
                    &format!("table_to={max}"),
                    &subdiv_lab::budget::ccss_table(max, levels),
                    TIME_LIMIT_SECONDS,
                    force,
                )?;
                let rows = py.detach(|| beta_table(3..=max, levels)).map_err(lib_err)?;
                serde_json::to_string(&rows).map_err(runtime_err)
            }
            (Some(n), None) => {
                let n = n.usize("valence")?;
                if n < 3 {
                    return Err(lib_err(subdiv_lab::Error::ValenceTooSmall { valence: n }));
                }
                limit(
                    "ccss_bound",
                    &format!("valence {n}"),
                    &subdiv_lab::budget::ccss_bound(n, levels),
                    TIME_LIMIT_SECONDS,
                    force,
                )?;
                let net = net.zip(epsilon);
                let summary = py
                    .detach(|| {
                        BoundSummary::compute(
                            n,
                            levels,
                            net.as_ref().map(|(p, e)| (p.as_slice(), *e)),
                        )
                    })
                    .map_err(lib_err)?;
                Ok(summary.to_json().to_string())
            }
        }
    })
}
