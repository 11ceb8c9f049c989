//! Helpers shared by the test modules: the fixtures and rounding.

use std::fs;
use std::path::{Path, PathBuf};

use flocking::Scenario;

/// The workspace's `fixtures/` directory.
pub fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

/// Every `fixtures/*.ron`, sorted by name.
pub fn fixture_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = fs::read_dir(fixtures_dir())
        .expect("the fixtures directory exists")
        .map(|entry| entry.expect("readable directory entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "ron"))
        .collect();
    paths.sort();
    assert!(
        !paths.is_empty(),
        "no fixtures/*.ron found in {}",
        fixtures_dir().display()
    );
    paths
}

/// The file stem of a fixture path.
pub fn stem(path: &Path) -> String {
    path.file_stem()
        .expect("a file name")
        .to_string_lossy()
        .into_owned()
}

/// The fixture `fixtures/{name}.ron`, loaded and validated.
pub fn fixture(name: &str) -> Scenario {
    let path = fixtures_dir().join(format!("{name}.ron"));
    Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// `x` rounded to 6 significant digits, in scientific notation (`0` for ±0, so the sign of a zero
/// never changes a snapshot).
pub fn sig6(x: f64) -> String {
    if x == 0.0 {
        "0".to_owned()
    } else {
        format!("{x:.5e}")
    }
}

/// A fresh directory under the system's temporary directory, named after the process and the
/// test, removed (with its `.partial` sibling) when dropped.
pub struct TempDir(PathBuf);

impl TempDir {
    /// Creates `flock-cli-{pid}-{test}` (emptied first if a previous run left it).
    pub fn new(test: &str) -> Self {
        let path = std::env::temp_dir().join(format!("flock-cli-{}-{test}", std::process::id()));
        if path.exists() {
            fs::remove_dir_all(&path).expect("remove a stale temporary directory");
        }
        fs::create_dir_all(&path).expect("create the temporary directory");
        Self(path)
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}
