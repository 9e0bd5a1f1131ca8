//! OpenSubdiv's tag lines (math doc section 17), read from OBJ text or from a
//! sidecar file of the same lines:
//!
//! ```text
//! t crease NI/NF/0 v0 v1 [v2 v3 ...] s [s ...]   # NI even: NI/2 edges (v0,v1), (v2,v3), ...
//! t corner NI/NF/0 v [v ...] s [s ...]           # NI vertices
//! ```
//!
//! Vertex indices are 0-based; `NF` is 1 (one sharpness for every edge or
//! vertex of the line) or one per edge (`NI/2`) or per vertex (`NI`).
//! Sharpness is a finite number `>= 0`; `>= 10` is infinitely sharp. Other
//! tag names, counts that disagree with the arguments, negative or NaN
//! sharpness are errors naming the line. In a sidecar file every line that
//! is not blank, a `#` comment or a `t` line is an error.

use crate::mesh::MeshError;

/// What a tag applies to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TagTarget {
    /// The edge between two vertices (0-based).
    Edge(usize, usize),
    /// A vertex (0-based).
    Vertex(usize),
}

/// One sharpness assignment from a tag line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tag {
    /// 1-based line number in its text.
    pub line: usize,
    /// The edge or vertex.
    pub target: TagTarget,
    /// The sharpness, single precision (OpenSubdiv's), finite and `>= 0`.
    pub sharpness: f32,
}

fn syntax(line: usize, message: String) -> MeshError {
    MeshError::TagSyntax { line, message }
}

/// Parses one `t` line's tokens after the `t` (line `line`, 1-based) into
/// `out`.
pub fn parse_tag_tokens<'a>(
    line: usize,
    mut tokens: impl Iterator<Item = &'a str>,
    out: &mut Vec<Tag>,
) -> Result<(), MeshError> {
    let name = tokens
        .next()
        .ok_or_else(|| syntax(line, "tag line without a name".into()))?;
    if name != "crease" && name != "corner" {
        return Err(syntax(
            line,
            format!("unsupported tag {name:?} (only crease and corner; boundary interpolation and creasing method are command-line options)"),
        ));
    }
    let counts = tokens
        .next()
        .ok_or_else(|| syntax(line, format!("tag {name} has no NI/NF/NS counts")))?;
    let parts: Vec<&str> = counts.split('/').collect();
    let parsed: Vec<Option<usize>> = parts.iter().map(|p| p.parse().ok()).collect();
    let (ni, nf) = match parsed.as_slice() {
        [Some(ni), Some(nf), Some(0)] => (*ni, *nf),
        _ => {
            return Err(syntax(
                line,
                format!("tag {name}: counts {counts:?} are not NI/NF/0"),
            ))
        }
    };
    let rest: Vec<&str> = tokens.collect();
    if rest.len() != ni + nf {
        return Err(syntax(
            line,
            format!(
                "tag {name} {counts}: expected {} arguments, got {}",
                ni + nf,
                rest.len()
            ),
        ));
    }
    let per = if name == "crease" { 2 } else { 1 };
    if ni == 0 || ni % per != 0 {
        return Err(syntax(
            line,
            format!("tag {name}: {ni} vertex indices (need a positive multiple of {per})"),
        ));
    }
    let items = ni / per;
    if nf != 1 && nf != items {
        return Err(syntax(
            line,
            format!("tag {name}: {nf} sharpness values for {items} items (need 1 or {items})"),
        ));
    }
    let mut idx = Vec::with_capacity(ni);
    for tok in &rest[..ni] {
        idx.push(tok.parse::<usize>().map_err(|_| {
            syntax(
                line,
                format!("tag {name}: vertex index {tok:?} is not a non-negative integer"),
            )
        })?);
    }
    let mut sharp = Vec::with_capacity(nf);
    for tok in &rest[ni..] {
        let s: f64 = tok.parse().map_err(|_| {
            syntax(
                line,
                format!("tag {name}: sharpness {tok:?} is not a number"),
            )
        })?;
        if !(s.is_finite() && s >= 0.0) {
            return Err(MeshError::TagSharpness {
                line,
                value: tok.to_string(),
            });
        }
        sharp.push(s as f32);
    }
    for k in 0..items {
        let sharpness = sharp[if nf == 1 { 0 } else { k }];
        let target = if per == 2 {
            TagTarget::Edge(idx[2 * k], idx[2 * k + 1])
        } else {
            TagTarget::Vertex(idx[k])
        };
        out.push(Tag {
            line,
            target,
            sharpness,
        });
    }
    Ok(())
}

/// Reads a tag sidecar file: `t` lines, blank lines and `#` comments only.
///
/// ```
/// use subdiv_lab::mesh::sharp::tags::{parse_tag_file, TagTarget};
/// let tags = parse_tag_file("# creases\nt crease 2/1/0 0 1 2.5\nt corner 1/1/0 3 10\n").unwrap();
/// assert_eq!(tags.len(), 2);
/// assert_eq!(tags[0].target, TagTarget::Edge(0, 1));
/// assert!(parse_tag_file("v 0 0 0\n").is_err());
/// ```
pub fn parse_tag_file(text: &str) -> Result<Vec<Tag>, MeshError> {
    let mut out = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        match tokens.next() {
            None => continue,
            Some("t") => parse_tag_tokens(line, tokens, &mut out)?,
            Some(other) => {
                return Err(syntax(
                    line,
                    format!("{other:?}: a tag file holds only t lines"),
                ))
            }
        }
    }
    Ok(out)
}
