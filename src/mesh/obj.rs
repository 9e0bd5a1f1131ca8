//! Wavefront OBJ text: parsing into a validated [`Mesh`] and writing.
//!
//! Read: `v x y z [w]` (w ignored), `f` with any number of corners in the
//! forms `v`, `v/vt`, `v//vn`, `v/vt/vn`, positive (1-based) or negative
//! (relative to the vertices read so far) indices, and OpenSubdiv's `t crease`
//! / `t corner` tag lines ([`super::sharp::tags`]). Every other statement
//! (`vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, `p`, ...) is ignored and
//! counted. `#` starts a comment.
//!
//! ```
//! use subdiv_lab::mesh::obj::{parse_obj, write_obj_string};
//! let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n\
//!             f 1 3 2\nf 1//1 2//1 4//1\nf -3 -2 -1\nf 3/1 1/1 4/1\n";
//! let (mesh, info) = parse_obj(text).unwrap();
//! assert_eq!(mesh.face_count(), 4);
//! assert_eq!(info.ignored_statements, 1);
//! let again = parse_obj(&write_obj_string(&mesh)).unwrap().0;
//! assert_eq!(again.positions(), mesh.positions());
//! ```

use super::sharp::tags::{parse_tag_tokens, Tag};
use super::{Mesh, MeshError};
use std::io::{self, Write};

/// What the parser saw besides the mesh.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjInfo {
    /// Number of statements other than `v` and `f` that were ignored.
    pub ignored_statements: usize,
    /// The distinct ignored keywords, in order of first appearance.
    pub ignored_keywords: Vec<String>,
}

/// Positions and faces as read, before validation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjData {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Faces (0-based vertex indices).
    pub faces: Vec<Vec<usize>>,
    /// Crease and corner tags (`t` lines).
    pub tags: Vec<Tag>,
    /// Ignored statements.
    pub info: ObjInfo,
}

fn syntax(line: usize, message: String) -> MeshError {
    MeshError::ObjSyntax { line, message }
}

/// Reads the `v` and `f` statements of OBJ text without validating the mesh.
pub fn parse_obj_data(text: &str) -> Result<ObjData, MeshError> {
    let mut data = ObjData::default();
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let mut p = [0.0; 3];
                for (axis, slot) in p.iter_mut().enumerate() {
                    let tok = tokens.next().ok_or_else(|| {
                        syntax(line, format!("vertex has {axis} coordinates, 3 needed"))
                    })?;
                    *slot = tok.parse::<f64>().map_err(|_| {
                        syntax(line, format!("vertex coordinate {tok:?} is not a number"))
                    })?;
                }
                data.positions.push(p);
            }
            "f" => {
                let mut face = Vec::new();
                for tok in tokens {
                    let first = tok.split('/').next().unwrap_or("");
                    let idx: i64 = first.parse().map_err(|_| {
                        syntax(line, format!("face corner {tok:?} has no vertex index"))
                    })?;
                    let nv = data.positions.len() as i64;
                    let zero_based = if idx > 0 {
                        idx - 1
                    } else if idx < 0 {
                        nv + idx
                    } else {
                        return Err(syntax(line, "face index 0 is not valid in OBJ".into()));
                    };
                    if zero_based < 0 {
                        return Err(syntax(
                            line,
                            format!("relative index {idx} reaches before the first vertex ({nv} read so far)"),
                        ));
                    }
                    face.push(zero_based as usize);
                }
                data.faces.push(face);
            }
            "t" => parse_tag_tokens(line, tokens, &mut data.tags)?,
            other => {
                data.info.ignored_statements += 1;
                if !data.info.ignored_keywords.iter().any(|k| k == other) {
                    data.info.ignored_keywords.push(other.to_owned());
                }
            }
        }
    }
    Ok(data)
}

/// Parses OBJ text into a validated closed mesh (all knot intervals 1).
/// Crease and corner tags are refused ([`MeshError::TagsUnsupported`]): a
/// [`Mesh`] carries none ([`super::sharp::SharpMesh`] does).
pub fn parse_obj(text: &str) -> Result<(Mesh, ObjInfo), MeshError> {
    let data = parse_obj_data(text)?;
    if let Some(t) = data.tags.first() {
        return Err(MeshError::TagsUnsupported { line: t.line });
    }
    let mesh = Mesh::from_polygons(data.positions, &data.faces)?;
    Ok((mesh, data.info))
}

/// Writes `mesh` as OBJ (`v` lines with round-trip precision, then `f` lines, 1-based).
pub fn write_obj<W: Write>(mesh: &Mesh, out: &mut W) -> io::Result<()> {
    writeln!(
        out,
        "# subdiv-lab: {} vertices, {} faces",
        mesh.vertex_count(),
        mesh.face_count()
    )?;
    for p in &mesh.positions {
        writeln!(out, "v {:?} {:?} {:?}", p[0], p[1], p[2])?;
    }
    let mut line = String::new();
    for f in 0..mesh.face_count() {
        line.clear();
        line.push('f');
        for v in mesh.face_vertices(f) {
            use std::fmt::Write as _;
            let _ = write!(line, " {}", v + 1);
        }
        line.push('\n');
        out.write_all(line.as_bytes())?;
    }
    Ok(())
}

/// Writes an open mesh as OBJ, as [`write_obj`].
pub fn write_open_obj<W: Write>(mesh: &super::open::OpenMesh, out: &mut W) -> io::Result<()> {
    write_obj(mesh.faces(), out)
}

/// [`write_obj`] into a `String`.
pub fn write_obj_string(mesh: &Mesh) -> String {
    let mut buf = Vec::new();
    // Writing into a Vec cannot fail.
    let _ = write_obj(mesh, &mut buf);
    String::from_utf8(buf).unwrap_or_default()
}
