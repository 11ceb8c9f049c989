//! Helpers shared by the test modules: the fixtures and rounding.

use std::fs;
use std::path::{Path, PathBuf};
pub use tempfile::TempDir;

use flocking::{Record, Recorder, Scenario, Start};

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

/// Every record's bits (time, energy, metrics, diagnostics, state and vehicle states), and the
/// checkpoint taken at step `at`.
struct Bits {
    at: u64,
    records: Vec<Vec<u64>>,
    checkpoint: Option<Start>,
}

impl Recorder for Bits {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let state = &record.state;
        let numbers = [record.t, record.energy]
            .into_iter()
            .chain(record.metrics.reals())
            .chain(record.metrics.extras())
            .chain(record.diagnostics.iter().map(|(_, x)| *x))
            .chain(state.positions.iter().copied())
            .chain(state.velocities.iter().copied())
            .chain(state.vehicle.iter().copied())
            .chain(
                state
                    .failed
                    .iter()
                    .flat_map(|f| f.iter())
                    .map(|&f| f64::from(u8::from(f))),
            );
        self.records.push(numbers.map(f64::to_bits).collect());
        Ok(())
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        steps == self.at
    }

    fn checkpoint(&mut self, start: &Start) -> Result<(), Self::Error> {
        self.checkpoint = Some(start.clone());
        Ok(())
    }
}

/// Runs `scenario` whole with a checkpoint at step `at`, resumes it from that checkpoint, and
/// asserts that the resumed run records the bits of the whole run's tail; returns the checkpoint.
pub fn assert_resumes_bit_for_bit(scenario: &Scenario, at: u64) -> Start {
    let mut whole = Bits {
        at,
        records: Vec::new(),
        checkpoint: None,
    };
    flocking::run(scenario, &mut whole).expect("the run");
    let checkpoint = whole.checkpoint.take().expect("a checkpoint");
    let mut resumed = Bits {
        at: u64::MAX,
        records: Vec::new(),
        checkpoint: None,
    };
    flocking::resume(scenario, Some(&checkpoint), &mut resumed).expect("the resumed run");
    assert!(!resumed.records.is_empty());
    let tail = &whole.records[whole.records.len() - resumed.records.len()..];
    assert!(
        resumed.records[..] == *tail,
        "{}: the resumed records differ",
        scenario.name
    );
    checkpoint
}
