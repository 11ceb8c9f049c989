//! Helpers shared by the test modules: the fixtures, self-removing temporary directories, rounding.

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

/// The fixture `fixtures/{name}.ron`, loaded and validated.
pub fn fixture(name: &str) -> Scenario {
    let path = fixtures_dir().join(format!("{name}.ron"));
    Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// A fresh directory for `test` under the system's temporary directory, with a name of its
/// own, removed when dropped.
pub fn temp_dir(test: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("flocking-{test}-"))
        .tempdir()
        .expect("create a temporary directory")
}

/// Runs the `flocking` binary in `dir` with `args` and waits for it.
pub fn flocking(dir: &Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the flocking binary runs")
}

/// `flocking args` run in `dir` under a 4 GiB address-space limit (`ulimit -v`), which the
/// resource check counts: what does not fit there is refused before anything is written.
pub fn flocking_under_4_gib(dir: &Path, args: &str) -> std::process::Output {
    std::process::Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg(format!(
            "ulimit -v 4194304 && exec {} {args}",
            env!("CARGO_BIN_EXE_flocking")
        ))
        .output()
        .expect("sh runs")
}

/// The standard error of a finished command, as text.
pub fn stderr(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Writes `text` to `dir/name` and returns the path as a string.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    fs::write(&path, text).expect("write a scenario file");
    path.to_str().expect("a UTF-8 temporary path").to_owned()
}

/// The files of a directory (not its subdirectories) by name, with their bytes.
pub fn files(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.is_file())
        .map(|path| {
            let name = path
                .file_name()
                .expect("a name")
                .to_string_lossy()
                .into_owned();
            (name, fs::read(&path).expect("a readable file"))
        })
        .collect()
}

/// The column `name` of CSV `text` (a header line, then rows), as text, row by row.
pub fn csv_column(text: &str, name: &str) -> Vec<String> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let k = reader
        .headers()
        .expect("a header")
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    reader
        .records()
        .map(|r| r.expect("a row")[k].to_owned())
        .collect()
}

/// Removes `path`, a file the test or flocking wrote under the test's own temporary directory
/// `tmp`, after checking both: it lies under `tmp` (no `..` or link leads out) and it begins with
/// `holds`, what the test knows it wrote there, and it is a regular file, not a link. A test
/// removes nothing it did not make.
pub fn remove_own_file(tmp: &Path, path: &Path, holds: &[u8]) {
    assert!(
        fs::symlink_metadata(path).is_ok_and(|m| m.is_file()),
        "{} is not a regular file",
        path.display()
    );
    let path = path
        .canonicalize()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let tmp = tmp.canonicalize().expect("the test's directory");
    assert!(
        path.starts_with(&tmp) && path != tmp,
        "{} is not under the test's directory {}",
        path.display(),
        tmp.display()
    );
    let bytes = fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.starts_with(holds),
        "{} does not hold what the test wrote there",
        path.display()
    );
    fs::remove_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

/// The canonical form of `path`'s parent, checked to lie under the test's directory `tmp` (so
/// that a removal there touches only what the test made).
fn under_test_dir(tmp: &Path, path: &Path) -> std::path::PathBuf {
    let parent = path
        .parent()
        .and_then(|p| p.canonicalize().ok())
        .unwrap_or_else(|| panic!("{} has no readable parent", path.display()));
    let tmp = tmp.canonicalize().expect("the test's directory");
    assert!(
        parent.starts_with(&tmp),
        "{} is not under the test's directory {}",
        path.display(),
        tmp.display()
    );
    parent
}

/// Removes the symbolic link `link` the test made under `tmp`, after checking that it is a link
/// and points where the test pointed it (`to`); never what it points to.
pub fn remove_own_link(tmp: &Path, link: &Path, to: &Path) {
    under_test_dir(tmp, link);
    assert!(
        fs::symlink_metadata(link).is_ok_and(|m| m.file_type().is_symlink()),
        "{} is not a link",
        link.display()
    );
    assert_eq!(
        fs::read_link(link).expect("the link's target"),
        to,
        "{} is not the test's link",
        link.display()
    );
    fs::remove_file(link).unwrap_or_else(|e| panic!("{}: {e}", link.display()));
}

/// Removes the empty directory `dir` the test made under `tmp`, never `tmp` itself, `.`, `..` or
/// a parent (`remove_dir` removes no content).
pub fn remove_own_empty_dir(tmp: &Path, dir: &Path) {
    under_test_dir(tmp, dir);
    let real = dir
        .canonicalize()
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let tmp = tmp.canonicalize().expect("the test's directory");
    assert!(
        real.starts_with(&tmp) && real != tmp,
        "{} is not a directory the test made under {}",
        dir.display(),
        tmp.display()
    );
    assert!(
        fs::symlink_metadata(&real).is_ok_and(|m| m.is_dir()),
        "{} is not a directory",
        dir.display()
    );
    fs::remove_dir(&real).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
}
