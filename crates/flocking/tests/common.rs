//! Helpers shared by the test modules: the fixtures and rounding.

use std::fs;
use std::path::{Path, PathBuf};
pub use tempfile::TempDir;

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

/// A fresh directory for `test` under the system's temporary directory, with a name of its
/// own, removed when dropped.
pub fn temp_dir(test: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("flocking-{test}-"))
        .tempdir()
        .expect("create a temporary directory")
}
