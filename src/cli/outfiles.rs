//! Output files of the CLI: conflict checks and atomic writes.
//!
//! The rule, one for every command (docs/guide/commands.md, "Files"):
//!
//! * **A single-file output** (`-o FILE`, `merge --out FILE`) replaces a
//!   regular file atomically, as Unix tools do: it is written to a temporary
//!   file that the tool creates itself (`create_new`, so an existing file of
//!   the same name is never truncated) in the target's directory, and renamed
//!   into place only when every output and standard output are written. A
//!   device or FIFO (`-o /dev/null`) is written in place; a directory is
//!   refused.
//! * **Directories and resumable outputs** (`verify --out DIR`, `report
//!   --out DIR`, `sweep --out FILE` with its summary and journal) are never
//!   touched unless the tool wrote them: a directory must be new, empty, or
//!   an earlier output of the same command (recognised by the file it always
//!   writes there); a resumable file is created whole with its fingerprint
//!   ([`subdiv_lab::outfiles::install_new`], so a file at that path without one is not the
//!   tool's) and continued only by `--resume`.
//!
//! A failed run leaves no new file, and the tool never deletes or renames
//! anything it did not create.

use super::{CliError, CliResult};
use anyhow::{anyhow, Context as _};
use std::fs::{self, OpenOptions};
use std::io::Write as _;
use std::path::{Path, PathBuf};
pub(crate) use subdiv_lab::outfiles::{create_temp_dir, create_temp_file, is_special, parent_dir};

/// A comparable form of a path that may not exist yet: the canonical path if
/// it exists, else the canonical parent joined with the file name, else the
/// path made absolute lexically.
fn comparable(p: &Path) -> PathBuf {
    if let Ok(c) = fs::canonicalize(p) {
        return c;
    }
    if let (Some(name), Ok(dir)) = (p.file_name(), fs::canonicalize(parent_dir(p))) {
        return dir.join(name);
    }
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// Whether two paths name the same file (same canonical path, or, for two
/// existing files on Unix, the same device and inode: hard links).
fn same_target(a: &Path, b: &Path) -> bool {
    if comparable(a) == comparable(b) {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    false
}

/// Refuses (exit 2) before anything is written when two outputs name the same
/// file, an output names an input, or an output is an existing directory.
/// `outputs` and `inputs` are `(flag, path)` pairs; `-` (standard output) is
/// skipped.
pub(crate) fn check_distinct(outputs: &[(&str, &Path)], inputs: &[(&str, &Path)]) -> CliResult {
    let outputs: Vec<&(&str, &Path)> = outputs
        .iter()
        .filter(|(_, p)| p.as_os_str() != "-")
        .collect();
    for (i, (flag, p)) in outputs.iter().enumerate() {
        let dir = parent_dir(p);
        if !dir.is_dir() {
            return Err(CliError::usage(anyhow!(
                "{flag} {}: directory {} does not exist",
                p.display(),
                dir.display()
            )));
        }
        if p.is_dir() {
            return Err(CliError::usage(anyhow!(
                "{flag} {} is a directory; give a file path",
                p.display()
            )));
        }
        for (flag2, q) in &outputs[..i] {
            if same_target(p, q) {
                return Err(CliError::usage(anyhow!(
                    "{flag2} {} and {flag} {} name the same file; give two different paths",
                    q.display(),
                    p.display()
                )));
            }
        }
        for (flag2, q) in inputs {
            if same_target(p, q) {
                return Err(CliError::usage(anyhow!(
                    "{flag} {} is also {flag2} {}; write the output elsewhere",
                    p.display(),
                    q.display()
                )));
            }
        }
    }
    Ok(())
}

/// Output files written to temporaries, not yet in place. Dropping it without
/// [`Staged::commit`] removes the temporaries (which the tool created).
/// Outputs that are special files ([`is_special`], e.g. `-o /dev/null`) are
/// kept in memory and written in place by [`Staged::commit`], before any
/// rename.
pub(crate) struct Staged {
    /// (temporary, target, the target existed before).
    files: Vec<(PathBuf, PathBuf, bool)>,
    /// Special-file targets and their bytes.
    special: Vec<(PathBuf, Vec<u8>)>,
}

impl Staged {
    /// Writes every `(target, bytes)` to a temporary file next to its target.
    pub(crate) fn write(outputs: &[(PathBuf, Vec<u8>)]) -> CliResult<Staged> {
        let mut staged = Staged {
            files: Vec::new(),
            special: Vec::new(),
        };
        for (target, data) in outputs {
            if is_special(target) {
                staged.special.push((target.clone(), data.clone()));
                continue;
            }
            let name = target
                .file_name()
                .ok_or_else(|| CliError::usage(anyhow!("{} is not a file path", target.display())))?
                .to_string_lossy()
                .into_owned();
            let existed = fs::symlink_metadata(target).is_ok();
            let (mut f, tmp) = create_temp_file(&parent_dir(target), &name)
                .with_context(|| format!("cannot write {}", target.display()))
                .map_err(CliError::failure)?;
            staged.files.push((tmp, target.clone(), existed));
            f.write_all(data)
                .and_then(|()| f.sync_all())
                .with_context(|| format!("cannot write {}", target.display()))
                .map_err(CliError::failure)?;
        }
        Ok(staged)
    }

    /// Renames every temporary into place. If a rename fails, the targets
    /// already renamed that did not exist before are removed again (they are
    /// the tool's own); a target that existed before and was already replaced
    /// stays replaced (reported in the error).
    pub(crate) fn commit(mut self) -> CliResult {
        // Special files first: a failed write there (`/dev/full`) leaves
        // every temporary unrenamed (removed on drop), so no new file.
        for (target, data) in &self.special {
            OpenOptions::new()
                .write(true)
                .open(target)
                .and_then(|mut f| f.write_all(data))
                .with_context(|| format!("cannot write {}", target.display()))
                .map_err(CliError::failure)?;
        }
        let files = std::mem::take(&mut self.files);
        for (i, (tmp, target, _)) in files.iter().enumerate() {
            if let Err(e) = fs::rename(tmp, target) {
                let mut replaced = Vec::new();
                for (_, done, existed) in &files[..i] {
                    if *existed {
                        replaced.push(done.display().to_string());
                    } else {
                        let _ = fs::remove_file(done);
                    }
                }
                for (t, _, _) in &files[i..] {
                    let _ = fs::remove_file(t);
                }
                let also = if replaced.is_empty() {
                    String::new()
                } else {
                    format!(" (already replaced: {})", replaced.join(", "))
                };
                return Err(CliError::failure(
                    anyhow!(e).context(format!("cannot write {}{also}", target.display())),
                ));
            }
        }
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        for (tmp, _, _) in &self.files {
            let _ = fs::remove_file(tmp);
        }
    }
}
