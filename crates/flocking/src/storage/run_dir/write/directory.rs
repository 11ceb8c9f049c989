//! A run directory being written ([`RunDirectory`]): its files, what it has written, and the
//! fresh files a run starts with.

use std::fs::File;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use flock_metrics::FlockingCriteria;

use super::columns::{marks_failed, trajectory_csv_header};
use super::options::{OutputOptions, TrajectoryFormat};
use crate::scenario::Scenario;
use crate::storage::fs::{at, is_empty_dir};
use crate::storage::owned::DirLock;
use crate::storage::run_dir::npy::{NpyFile, trajectory_dtype};
use crate::verdict::{Verdict, VerdictKind};

/// The trajectory file being written.
#[derive(Debug)]
pub(super) enum Trajectory {
    Csv { file: File, bytes: u64 },
    Npy(NpyFile),
}

/// An output directory being written.
#[derive(Debug)]
pub struct RunDirectory {
    pub(super) target: PathBuf,
    pub(super) partial: PathBuf,
    pub(super) metrics: File,
    pub(super) metrics_bytes: u64,
    pub(super) trajectory: Trajectory,
    pub(super) records: u64,
    pub(super) dim: usize,
    pub(super) checkpoint_every: u64,
    /// One trajectory record's bytes (CSV text or `.npy` row), reused.
    pub(super) buffer: Vec<u8>,
    /// The last recorded state (dim coordinates of q, then of p, then the vehicle's state, then
    /// 0 or 1 for `failed` when it is marked, per agent) for `final.csv`.
    pub(super) last_state: Vec<f64>,
    /// The names of each agent's vehicle state (empty for point masses).
    pub(super) vehicle_columns: &'static [&'static str],
    /// Whether each agent's row ends with `failed` (0 or 1): the scenario has `faults`.
    pub(super) marks_failed: bool,
    /// The diagnostic columns of the header of `metrics.csv`, once written.
    pub(super) columns: Option<Vec<String>>,
    /// The number of agents.
    pub(super) agents: usize,
    /// The criteria of the verdict of [`VERDICT_FILE`](crate::run_dir::VERDICT_FILE).
    pub(super) criteria: FlockingCriteria,
    /// The verdict the scenario's model gets.
    pub(super) verdict_kind: VerdictKind,
    /// The resolved scenario as RON, kept in every checkpoint.
    pub(super) scenario: String,
    /// Whether `DIR` may be replaced at the end (it carried flocking's marker at the start).
    pub(super) force: bool,
    /// Whether `DIR` was an empty directory when this writer started: it is then replaced at the
    /// end, while an empty `DIR` that appears during the run is kept.
    pub(super) empty_target: bool,
    /// The lock on `DIR.partial`, held until the directory is dropped.
    pub(super) lock: DirLock,
    /// Where the run's inputs come from when not from the scenario's protocol
    /// ([`CONTROLS_FILE`]).
    pub(super) controls: Option<String>,
}

/// A complete run directory.
#[derive(Clone, Debug, PartialEq)]
pub struct Finished {
    /// `DIR`.
    pub path: PathBuf,
    /// The model's verdict judged on its whole `metrics.csv` (also in [`VERDICT_FILE`](crate::run_dir::VERDICT_FILE)).
    pub verdict: Option<Verdict>,
}

/// `DIR.partial`.
#[must_use]
pub fn partial_path(target: &Path) -> PathBuf {
    let mut partial = target.as_os_str().to_owned();
    partial.push(".partial");
    PathBuf::from(partial)
}

impl RunDirectory {
    /// Writes the headers of fresh output files into `partial`.
    pub(super) fn start_files(
        target: &Path,
        partial: PathBuf,
        scenario: &Scenario,
        format: TrajectoryFormat,
        options: &OutputOptions,
        lock: DirLock,
    ) -> io::Result<Self> {
        let metrics_path = partial.join("metrics.csv");
        let metrics = File::create(&metrics_path)
            .map_err(at(format_args!("create {}", metrics_path.display())))?;
        let trajectory = match format {
            TrajectoryFormat::Csv => {
                let header = trajectory_csv_header(scenario);
                let path = partial.join("trajectory.csv");
                let file = File::create(&path)
                    .and_then(|mut file| file.write_all(header.as_bytes()).map(|()| file))
                    .map_err(at(format_args!("write {}", path.display())))?;
                Trajectory::Csv {
                    file,
                    bytes: header.len() as u64,
                }
            }
            TrajectoryFormat::Npy => {
                let (descr, row_bytes) = trajectory_dtype(
                    scenario.agents,
                    scenario.dim,
                    scenario.vehicle.state_columns(scenario.dim).len(),
                    marks_failed(scenario),
                );
                let path = partial.join("trajectory.npy");
                Trajectory::Npy(
                    NpyFile::create(&path, descr, row_bytes)
                        .map_err(at(format_args!("write {}", path.display())))?,
                )
            }
        };
        Ok(Self {
            target: target.to_owned(),
            partial,
            metrics,
            metrics_bytes: 0,
            trajectory,
            records: 0,
            dim: scenario.dim,
            checkpoint_every: options.checkpoint_every,
            buffer: Vec::new(),
            last_state: Vec::new(),
            vehicle_columns: scenario.vehicle.state_columns(scenario.dim),
            marks_failed: marks_failed(scenario),
            columns: None,
            agents: scenario.agents,
            criteria: FlockingCriteria::default(),
            verdict_kind: VerdictKind::of(&scenario.algorithm),
            scenario: scenario.to_ron().map_err(io::Error::other)?,
            force: false,
            empty_target: is_empty_dir(target),
            lock,
            controls: None,
        })
    }

    /// Judges the finished run by `criteria` in [`VERDICT_FILE`](crate::run_dir::VERDICT_FILE) (default: the last quarter,
    /// ε₁ = ε₂ = 0.01).
    #[must_use]
    pub const fn with_criteria(mut self, criteria: FlockingCriteria) -> Self {
        self.criteria = criteria;
        self
    }

    /// The directory being written, `DIR.partial`.
    #[must_use]
    pub fn partial(&self) -> &Path {
        &self.partial
    }

    /// Flushes `metrics.csv` and the trajectory to the disk.
    pub(super) fn sync_outputs(&self) -> io::Result<()> {
        self.metrics
            .sync_data()
            .and_then(|()| match &self.trajectory {
                Trajectory::Csv { file, .. } => file.sync_data(),
                Trajectory::Npy(file) => file.sync_data(),
            })
            .map_err(at(format_args!(
                "flush the records in {}",
                self.partial.display()
            )))
    }

    /// The values of one agent's row after its id: q, p, the vehicle's state, `failed`.
    pub(super) const fn row_width(&self) -> usize {
        2 * self.dim + self.vehicle_columns.len() + self.marks_failed as usize
    }
}
