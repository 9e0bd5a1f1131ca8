//! Build script: records the git revision of the source tree at build time as
//! `SUBDIV_LAB_GIT_REVISION` (12-digit short hash, `-dirty` with uncommitted
//! changes to tracked files), so `subdiv-lab report` writes the revision of the
//! binary into its manifest wherever it runs. Without git, or outside a git
//! checkout (a crates.io tarball), the value is `unknown`; the build never
//! fails because of it.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    Some(String::from_utf8(out.stdout).ok()?.trim().to_owned())
}

/// Asks cargo to rerun the script when `p` changes (only for existing paths:
/// a missing path would make cargo rerun the script on every build).
fn watch(p: &Path) {
    if p.exists() {
        println!("cargo:rerun-if-changed={}", p.display());
    }
}

fn main() {
    let dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_else(|| ".".into()));
    // Recompute when the checked-out commit or the sources change (a source
    // edit rebuilds the crate anyway; `-dirty` follows it).
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src");
    println!("cargo:rerun-if-changed=Cargo.toml");
    println!("cargo:rerun-if-changed=analysis/default.toml");
    if let Some(git_dir) = git(&dir, &["rev-parse", "--absolute-git-dir"]) {
        let git_dir = PathBuf::from(git_dir);
        // HEAD and the branch ref (a commit or checkout); not the index, so a
        // mere `git add` does not rebuild the crate.
        watch(&git_dir.join("HEAD"));
        if let Some(common) = git(&dir, &["rev-parse", "--git-common-dir"]) {
            let common = dir.join(common);
            watch(&common.join("packed-refs"));
            if let Some(head_ref) = git(&dir, &["symbolic-ref", "-q", "HEAD"]) {
                watch(&common.join(head_ref));
            }
        }
    }
    let revision = git(&dir, &["rev-parse", "--short=12", "HEAD"])
        .filter(|r| !r.is_empty())
        .map(|mut rev| {
            let dirty = git(
                &dir,
                &[
                    "--no-optional-locks",
                    "status",
                    "--porcelain",
                    "--untracked-files=no",
                ],
            )
            .is_some_and(|s| !s.is_empty());
            if dirty {
                rev.push_str("-dirty");
            }
            rev
        })
        .unwrap_or_else(|| "unknown".to_owned());
    println!("cargo:rustc-env=SUBDIV_LAB_GIT_REVISION={revision}");
}
