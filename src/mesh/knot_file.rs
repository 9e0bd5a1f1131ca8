//! The knot-interval sidecar file: one directed edge per line, `u v d`
//! (1-based OBJ vertex indices, `d = d(u -> v) > 0`). `#` starts a comment;
//! blank lines are skipped. Every directed edge not listed takes the default
//! interval. An edge the mesh does not have, a repeated edge, or a value that
//! is not a finite positive number is an error naming the line.
//!
//! ```
//! use subdiv_lab::mesh::{generators, knot_file};
//! let mut cube = generators::cube();
//! knot_file::apply_knot_text(&mut cube, "# d(1->2) = 3\n1 2 3\n", 1.0).unwrap();
//! let h = cube.find_half_edge(0, 1).unwrap();
//! assert_eq!(cube.knot(h), 3.0);
//! let err = knot_file::apply_knot_text(&mut cube, "1 2 3\n1 2 4\n", 1.0).unwrap_err();
//! assert!(err.to_string().contains("line 2"));
//! ```

use super::open::OpenMesh;
use super::{Mesh, MeshError};
use std::io::{self, Write};

/// Sets every knot interval of `mesh` from the sidecar text; unlisted
/// directed edges get `default`. On error the mesh is unchanged.
pub fn apply_knot_text(mesh: &mut Mesh, text: &str, default: f64) -> Result<(), MeshError> {
    let (knots, _) = read_knot_text(text, default, mesh.half_edge_count(), |u, v| {
        mesh.find_half_edge(u, v)
    })?;
    mesh.set_knots(knots)
}

/// Sets every knot interval of an open mesh from the sidecar text, the
/// directions of boundary edges that lie in no face included; unlisted
/// directed edges get `default`. A boundary edge listed in one direction
/// only is refused ([`MeshError::BoundaryKnotMissing`]): its other direction
/// lies in no face, and the curve rule of the boundary (math doc section 19)
/// uses both. On error the mesh is unchanged.
pub fn apply_open_knot_text(
    mesh: &mut OpenMesh,
    text: &str,
    default: f64,
) -> Result<(), MeshError> {
    let (knots, set_on) = read_knot_text(text, default, mesh.directed_edge_count(), |u, v| {
        mesh.find_directed_edge(u, v)
    })?;
    for h in mesh.corner_count()..mesh.directed_edge_count() {
        let c = mesh.twin(h);
        let (lc, lh) = (set_on[c], set_on[h]);
        if (lc == 0) != (lh == 0) {
            let (given, line) = if lc != 0 { (c, lc) } else { (h, lh) };
            let (u, v) = mesh.directed_edge(given);
            return Err(MeshError::BoundaryKnotMissing {
                line,
                u: u + 1,
                v: v + 1,
            });
        }
    }
    mesh.set_knots(knots)
}

/// The one reader of knot-file text: the intervals of `count` directed
/// edges (`default` where not listed) and the line that set each (0 = none);
/// `find(u, v)` (0-based) names the directed edge `u -> v`.
fn read_knot_text(
    text: &str,
    default: f64,
    count: usize,
    find: impl Fn(usize, usize) -> Option<usize>,
) -> Result<(Vec<f64>, Vec<usize>), MeshError> {
    if !(default.is_finite() && default > 0.0) {
        return Err(MeshError::InvalidDefaultInterval {
            value: format!("{default:?}"),
        });
    }
    let mut knots = vec![default; count];
    // line on which each directed edge was set (0 = not yet)
    let mut set_on = vec![0usize; count];
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let content = raw.split('#').next().unwrap_or("");
        let tokens: Vec<&str> = content.split_whitespace().collect();
        if tokens.is_empty() {
            continue;
        }
        if tokens.len() != 3 {
            return Err(MeshError::KnotSyntax {
                line,
                message: format!("expected \"u v d\", got {} fields", tokens.len()),
            });
        }
        let index = |tok: &str| -> Result<usize, MeshError> {
            match tok.parse::<usize>() {
                Ok(i) if i >= 1 => Ok(i),
                _ => Err(MeshError::KnotSyntax {
                    line,
                    message: format!(
                        "vertex index {tok:?} is not a positive integer (OBJ indices are 1-based)"
                    ),
                }),
            }
        };
        let (u, v) = (index(tokens[0])?, index(tokens[1])?);
        let d: f64 = tokens[2].parse().map_err(|_| MeshError::KnotSyntax {
            line,
            message: format!("interval {:?} is not a number", tokens[2]),
        })?;
        let h = find(u - 1, v - 1).ok_or(MeshError::UnknownEdge { line, u, v })?;
        if set_on[h] != 0 {
            return Err(MeshError::DuplicateEdge {
                line,
                u,
                v,
                first_line: set_on[h],
            });
        }
        let exact_positive = crate::scalar::parse_exact(tokens[2])
            .is_some_and(|q| num_traits::Signed::is_positive(&q));
        if exact_positive && !(d.is_finite() && d > 0.0) {
            return Err(MeshError::KnotNotRepresentable {
                line,
                u,
                v,
                value: tokens[2].to_owned(),
                rounded: d,
            });
        }
        if !(d.is_finite() && d > 0.0) {
            return Err(MeshError::KnotValue {
                line,
                u,
                v,
                value: tokens[2].to_owned(),
            });
        }
        set_on[h] = line;
        knots[h] = d;
    }
    Ok((knots, set_on))
}

/// Writes every directed edge `u v d` (1-based, round-trip precision), in half-edge order.
pub fn write_knots<W: Write>(mesh: &Mesh, out: &mut W) -> io::Result<()> {
    writeln!(
        out,
        "# subdiv-lab knot intervals: u v d(u->v), {} directed edges",
        mesh.half_edge_count()
    )?;
    for h in 0..mesh.half_edge_count() {
        writeln!(
            out,
            "{} {} {:?}",
            mesh.origin(h) + 1,
            mesh.target(h) + 1,
            mesh.knot(h)
        )?;
    }
    Ok(())
}

/// Writes every directed edge of an open mesh `u v d` (1-based, round-trip
/// precision): corners in order, then the boundary directions that lie in no face.
pub fn write_open_knots<W: Write>(mesh: &OpenMesh, out: &mut W) -> io::Result<()> {
    writeln!(
        out,
        "# subdiv-lab knot intervals: u v d(u->v), {} directed edges ({} along boundary edges outside the faces)",
        mesh.directed_edge_count(),
        mesh.boundary_edge_count()
    )?;
    for (h, d) in mesh.knots().iter().enumerate() {
        let (u, v) = mesh.directed_edge(h);
        writeln!(out, "{} {} {:?}", u + 1, v + 1, d)?;
    }
    Ok(())
}

/// [`write_knots`] into a `String`.
pub fn write_knots_string(mesh: &Mesh) -> String {
    let mut buf = Vec::new();
    let _ = write_knots(mesh, &mut buf);
    String::from_utf8(buf).unwrap_or_default()
}
