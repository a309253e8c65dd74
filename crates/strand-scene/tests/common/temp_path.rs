//! A test's output in the system temp directory, removed when the test is done with it.
//! The test files of strand-scene, strand-cli, strand-plot and xtask include this one file
//! (`#[path]`).

use std::path::{Path, PathBuf};

/// `<temp dir>/<name>-<process id>` (a directory or a file), or a path below it: whatever is
/// left there from an earlier run is removed when it is made, and what the test wrote there
/// is removed when it is dropped, at the end of the test or while a failing test unwinds.
pub struct TempPath {
    /// What is removed on drop.
    root: PathBuf,
    /// What the guard stands for: `root` or a path below it.
    path: PathBuf,
}

impl TempPath {
    /// The path for `name` in this process, emptied.
    pub fn new(name: &str) -> Self {
        let root = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
        remove(&root);
        Self {
            path: root.clone(),
            root,
        }
    }

    /// The same guard standing for `sub` below its path (a model's folder of a run).
    #[allow(dead_code)]
    pub fn into_sub(mut self, sub: impl AsRef<Path>) -> Self {
        let path = self.path.join(sub);
        Self {
            root: std::mem::take(&mut self.root),
            path,
        }
    }
}

impl std::ops::Deref for TempPath {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for TempPath {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl Drop for TempPath {
    fn drop(&mut self) {
        if !self.root.as_os_str().is_empty() {
            remove(&self.root);
        }
    }
}

/// Removes the directory or file at `path`, if there is one.
fn remove(path: &Path) {
    if path.is_dir() {
        let _ = std::fs::remove_dir_all(path);
    } else {
        let _ = std::fs::remove_file(path);
    }
}
