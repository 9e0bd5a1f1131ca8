//! Where in a TOML spec an error is, for the messages of the report and sweep
//! spec readers: the line and column of a byte offset ([`Location`]) and the
//! dotted key path at it (from the parsed tree, with a text-scan fallback for
//! text that does not parse). No I/O; the offsets are the spans of the `toml`
//! crate.

/// Where in a spec file something is: 1-based line and column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
}

impl Location {
    /// The location of byte `offset` in `src` (clamped to `src.len()`; an
    /// offset inside a multi-byte character counts as that character).
    ///
    /// ```
    /// use subdiv_lab::report::Location;
    /// let src = "a = 1\nb = \"é\"\n";
    /// assert_eq!(Location::of(src, 6), Location { line: 2, column: 1 });
    /// assert_eq!(Location::of(src, 11).to_string(), "line 2, column 6");
    /// ```
    pub fn of(src: &str, offset: usize) -> Self {
        let offset = offset.min(src.len());
        let before = &src[..floor_char_boundary(src, offset)];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        Location { line, column }
    }
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// The dotted key path (`sampler.count`, `space.fixed.r2`, `valences[1]`) of
/// the deepest key or value whose span contains `offset`, from the parsed
/// TOML tree (exact, where a text scan would guess); `None` if the text does not
/// parse or nothing contains the offset.
pub(crate) fn key_path_in_tree(text: &str, offset: usize) -> Option<String> {
    use toml::de::{DeTable, DeValue};
    fn find(v: &DeValue<'_>, offset: usize, path: &mut String) -> bool {
        match v {
            DeValue::Table(t) => {
                for (k, v) in t.iter() {
                    let mark = path.len();
                    if !path.is_empty() {
                        path.push('.');
                    }
                    path.push_str(k.get_ref());
                    let here = k.span().contains(&offset) || v.span().contains(&offset);
                    if find(v.get_ref(), offset, path) || here {
                        return true;
                    }
                    path.truncate(mark);
                }
                false
            }
            DeValue::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    let mark = path.len();
                    path.push_str(&format!("[{i}]"));
                    if find(v.get_ref(), offset, path) || v.span().contains(&offset) {
                        return true;
                    }
                    path.truncate(mark);
                }
                false
            }
            _ => false,
        }
    }
    let root = DeTable::parse(text).ok()?;
    let mut path = String::new();
    (find(&DeValue::Table(root.into_inner()), offset, &mut path) && !path.is_empty())
        .then_some(path)
}

/// The TOML key path at a byte offset: the last `[table]` header before it, and
/// the bare key that starts at the offset (best effort; the line is exact); the
/// fallback of [`key_path_in_tree`] for text that does not parse.
pub(crate) fn key_path_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let header = before.lines().rev().find_map(|l| {
        let t = l.trim();
        (t.starts_with('[') && t.ends_with(']'))
            .then(|| t.trim_matches(|c| c == '[' || c == ']').trim().to_owned())
    });
    let key: String = text[offset..]
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '-')
        .collect();
    if key.is_empty() {
        return header;
    }
    Some(match header {
        Some(h) => format!("{h}.{key}"),
        None => key,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line of an offset counted byte by byte (as the sweep spec reader
    /// did before it used [`Location`]): the same at every offset, including
    /// offsets inside multi-byte characters and past the end.
    #[test]
    fn line_equals_the_newline_count_at_every_offset() {
        let src = "# été\n[space]\nkind = \"râtios\"\n\n  x = 1\r\ny";
        for offset in 0..=src.len() + 3 {
            let newlines = src.as_bytes()[..offset.min(src.len())]
                .iter()
                .filter(|b| **b == b'\n')
                .count();
            assert_eq!(Location::of(src, offset).line, newlines + 1, "{offset}");
        }
    }

    #[test]
    fn key_paths_from_the_tree_and_from_the_text() {
        let src = "name = \"t\"\n[sampler]\ncount = 5\nv = [1, 2]\n";
        let at = |needle: &str| src.find(needle).unwrap();
        assert_eq!(
            key_path_in_tree(src, at("count")).as_deref(),
            Some("sampler.count")
        );
        assert_eq!(
            key_path_in_tree(src, at("2]")).as_deref(),
            Some("sampler.v[1]")
        );
        assert_eq!(
            key_path_at(src, at("count")).as_deref(),
            Some("sampler.count")
        );
        // Text that does not parse: only the scan answers.
        let bad = "[space]\nkind = = 1\n";
        assert_eq!(key_path_in_tree(bad, bad.find("kind").unwrap()), None);
        assert_eq!(
            key_path_at(bad, bad.find("kind").unwrap()).as_deref(),
            Some("space.kind")
        );
    }
}
