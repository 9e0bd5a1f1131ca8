//! Files the tool writes: new temporary files at free names beside their
//! target (never truncating an existing file), installing a new file only
//! where nothing is, and atomic replacement. Shared by the command-line
//! tool, the sweep outputs ([`crate::sweep::run`]) and the Python package;
//! the rule they implement is described in docs/guide/commands.md, "Files".

use std::fs::{self, File, OpenOptions};
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// How many temporary names are tried before giving up.
const TEMP_ATTEMPTS: u32 = 1000;

/// The directory part of `p` (`.` for a bare file name).
pub fn parent_dir(p: &Path) -> PathBuf {
    match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Creates something new at the first free name `dir/.{name}.tmp-{pid}[-k]`
/// with `create`, which must fail with `AlreadyExists` when the name is
/// taken (so nothing existing is ever truncated or reused).
fn create_at_free_temp_name<T>(
    dir: &Path,
    name: &str,
    create: impl Fn(&Path) -> std::io::Result<T>,
) -> std::io::Result<(T, PathBuf)> {
    let pid = std::process::id();
    let mut last = None;
    for k in 0..TEMP_ATTEMPTS {
        let tmp = if k == 0 {
            dir.join(format!(".{name}.tmp-{pid}"))
        } else {
            dir.join(format!(".{name}.tmp-{pid}-{k}"))
        };
        match create(&tmp) {
            Ok(t) => return Ok((t, tmp)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no free temporary name")))
}

/// Creates a new file `dir/.{name}.tmp-{pid}[-k]` that did not exist before
/// (so no existing file is ever truncated); returns it and its path.
pub fn create_temp_file(dir: &Path, name: &str) -> std::io::Result<(File, PathBuf)> {
    create_at_free_temp_name(dir, name, |p| {
        OpenOptions::new().write(true).create_new(true).open(p)
    })
}

/// [`create_temp_file`] beside `path`, named after its file name.
pub fn create_temp_beside(path: &Path) -> std::io::Result<(File, PathBuf)> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    create_temp_file(&parent_dir(path), &name)
}

/// Creates a new directory `dir/.{name}.tmp-{pid}[-k]` that did not exist before.
pub fn create_temp_dir(dir: &Path, name: &str) -> std::io::Result<PathBuf> {
    create_at_free_temp_name(dir, name, |p| fs::create_dir(p)).map(|((), p)| p)
}

/// Puts the complete temporary file `tmp` (of this run) at `target` only if
/// nothing is there: a hard link, which fails with `AlreadyExists` when the
/// name is taken (so a file that appeared meanwhile is never replaced), then
/// the temporary name is removed. On a file system without hard links, a
/// rename after checking that `target` is free.
pub fn install_new(tmp: &Path, target: &Path) -> std::io::Result<()> {
    match fs::hard_link(tmp, target) {
        Ok(()) => {
            let _ = fs::remove_file(tmp);
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            let _ = fs::remove_file(tmp);
            Err(e)
        }
        Err(_) if fs::symlink_metadata(target).is_err() => {
            fs::rename(tmp, target).inspect_err(|_| {
                let _ = fs::remove_file(tmp);
            })
        }
        Err(e) => {
            let _ = fs::remove_file(tmp);
            Err(e)
        }
    }
}

/// Whether `p` exists and is neither a regular file nor a directory (after
/// following symbolic links): a character or block device such as
/// `/dev/null`, a FIFO or a socket. Such a target is written in place, never
/// replaced by a rename (replacing `/dev/null` with a regular file would
/// destroy something the tool did not create).
pub fn is_special(p: &Path) -> bool {
    fs::metadata(p).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Writes `bytes` to `path` atomically: a new temporary file of this run
/// ([`create_temp_file`], so no existing file is truncated), then a rename.
/// The error names the file and the step (`writing P: ...`, `renaming T to
/// P: ...`).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let (mut f, tmp) = create_temp_file(&parent_dir(path), &name)
        .map_err(|e| format!("writing {}: {e}", path.display()))?;
    let result = f
        .write_all(bytes)
        .map_err(|e| format!("writing {}: {e}", tmp.display()))
        .and_then(|()| {
            fs::rename(&tmp, path)
                .map_err(|e| format!("renaming {} to {}: {e}", tmp.display(), path.display()))
        });
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}
