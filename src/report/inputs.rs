//! The input files of a report's figures, passed in by the caller.

/// Files that figures of a spec read (e.g. the CSV of a `sweep` figure), by
/// the path as written in the spec. The library never opens files: the
/// caller reads every path of [`ReportSpec::input_paths`](crate::report::ReportSpec::input_paths) and passes the
/// bytes here.
#[derive(Clone, Debug, Default)]
pub struct Inputs {
    files: std::collections::BTreeMap<String, Vec<u8>>,
}

impl Inputs {
    /// Adds the contents of `path`.
    pub fn insert(&mut self, path: impl Into<String>, bytes: Vec<u8>) {
        self.files.insert(path.into(), bytes);
    }

    /// The contents of `path`, if given.
    pub fn get(&self, path: &str) -> Option<&[u8]> {
        self.files.get(path).map(Vec::as_slice)
    }
}
