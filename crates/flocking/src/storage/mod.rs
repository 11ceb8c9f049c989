//! Storage: everything flocking keeps on the disk, apart from the scenario language, the runner,
//! the sweeps and the bench, which stand on it (never the reverse).
//!
//! - [`run_dir`]: the run directory — written crash-safe and resumable
//!   ([`RunDirectory`](run_dir::RunDirectory)), its checkpoints
//!   ([`Checkpoint`](run_dir::Checkpoint)), its `.npy` trajectory, and read back
//!   ([`read_run`](run_dir::read_run)).
//! - [`owned`]: the marker, the manifest, the checks and the lock that keep flocking from
//!   removing or overwriting anything it did not write, in every directory it writes (a run's, a
//!   sweep's, the gallery's).
//! - [`fs`]: the file operations both stand on (errors that name their path, writes flushed to
//!   the disk, a rename that never replaces).
//!
//! A module tree of `flocking`, not a crate of its own: a run directory holds the run's resolved
//! [`Scenario`](crate::Scenario), its records ([`Record`](crate::Record), [`State`](crate::State))
//! and its model's [`Verdict`](crate::Verdict), which `flocking` defines, while `flocking` writes
//! its runs through this tree; a crate would need those types moved out with it, or would import
//! the crate that imports it. Within the tree, `owned` and `fs` know nothing of runs.

pub mod fs;
pub mod owned;
pub mod run_dir;
