//! [`RunData`]: what `flocking run --out DIR` wrote, read back: `metrics.csv` as [`Metrics`] and
//! `trajectory.csv` as [`Frame`]s (formats in docs/outputs.md).

use std::path::Path;

use flocking::Scenario;
use flocking::run_dir::{self, ReadError, Trajectory};
use flocking::vehicle::VehicleSpec;
use glam::DVec3;

use crate::data::metric_series::Metrics;
use crate::error::VizError;
use crate::scene::frames::{Frame, Scene};

/// A run's outputs: its dimension, metric time series and recorded frames.
#[derive(Clone, Debug, PartialEq)]
pub struct RunData {
    /// The dimension, 2 or 3 (from the columns of `trajectory.csv`).
    pub dim: usize,
    /// The rows of `metrics.csv`.
    pub metrics: Metrics,
    /// The frames of `trajectory.csv`, in time order, agents in id order.
    pub frames: Vec<Frame>,
}

impl RunData {
    /// Reads `dir/metrics.csv` and `dir/trajectory.csv` (or `dir/trajectory.npy` when the run
    /// wrote that instead) with the readers of [`flocking::run_dir`].
    ///
    /// # Errors
    /// [`VizError::Io`] naming a file that cannot be read, [`VizError::Parse`] naming the file
    /// and line of a malformed row (wrong field count, a field that is not a number, an id out of
    /// range or repeated, an agent missing from a frame, time going backwards).
    pub fn load(dir: &Path) -> Result<Self, VizError> {
        let metrics = load_metrics(&dir.join("metrics.csv"))?;
        let npy = dir.join("trajectory.npy");
        let csv = dir.join("trajectory.csv");
        let trajectory = if !csv.exists() && npy.exists() {
            run_dir::read_trajectory_npy(&npy)?
        } else {
            run_dir::read_trajectory_csv(&csv)?
        };
        // vehicles point along their heading, which their scenario's vehicle computes
        let vehicle = if trajectory.vehicle_columns.is_empty() {
            None
        } else {
            let scenario = Scenario::load(dir.join("scenario.ron"));
            Some(
                scenario
                    .map_err(|e| VizError::Invalid(e.to_string()))?
                    .vehicle,
            )
        };
        let (dim, frames) = frames_of(&trajectory, vehicle.as_ref());
        Ok(Self {
            dim,
            metrics,
            frames,
        })
    }

    /// The scene of this run with interaction range `range` (for the net's edges), no obstacles
    /// and no γ-agent: add them with [`Scene::with_obstacle`] and [`Scene::with_gamma`].
    #[must_use]
    pub fn scene(&self, range: f64) -> Scene {
        let mut scene = Scene::new(self.dim, range);
        scene.frames.clone_from(&self.frames);
        scene
    }
}

/// Reads a `metrics.csv` ([`run_dir::read_metrics`]).
///
/// # Errors
/// As [`RunData::load`].
pub fn load_metrics(path: &Path) -> Result<Metrics, VizError> {
    let columns = run_dir::read_metrics(path)?;
    Metrics::from_columns(columns).map_err(|e| VizError::Parse {
        path: path.to_owned(),
        line: 1,
        message: e.to_string(),
    })
}

/// Reads a `trajectory.csv` ([`run_dir::read_trajectory_csv`]): the dimension and the frames.
///
/// # Errors
/// As [`RunData::load`].
pub fn load_trajectory(path: &Path) -> Result<(usize, Vec<Frame>), VizError> {
    Ok(frames_of(&run_dir::read_trajectory_csv(path)?, None))
}

/// Reads a `trajectory.npy` ([`run_dir::read_trajectory_npy`]): the dimension and the frames.
///
/// # Errors
/// As [`RunData::load`].
pub fn load_trajectory_npy(path: &Path) -> Result<(usize, Vec<Frame>), VizError> {
    Ok(frames_of(&run_dir::read_trajectory_npy(path)?, None))
}

/// The frames of a trajectory, vectors lifted to 3D, with each `vehicle`'s heading.
fn frames_of(trajectory: &Trajectory, vehicle: Option<&VehicleSpec>) -> (usize, Vec<Frame>) {
    let dim = trajectory.dim;
    let vector = |v: &[f64]| DVec3::new(v[0], v[1], if dim == 3 { v[2] } else { 0.0 });
    let frames = (0..trajectory.frames())
        .map(|k| {
            let headings = vehicle.and_then(|v| {
                v.headings(dim, trajectory.velocities_at(k), trajectory.vehicle_at(k))
            });
            let frame = Frame::new(
                trajectory.times[k],
                trajectory
                    .positions_at(k)
                    .chunks_exact(dim)
                    .map(vector)
                    .collect(),
                trajectory
                    .velocities_at(k)
                    .chunks_exact(dim)
                    .map(vector)
                    .collect(),
            );
            let frame = frame.with_failed(
                trajectory
                    .failed_at(k)
                    .map_or_else(Vec::new, <[bool]>::to_vec),
            );
            match headings {
                Some(rows) => frame.with_headings(rows.chunks_exact(dim).map(vector).collect()),
                None => frame,
            }
        })
        .collect();
    (dim, frames)
}

/// A read error as the figures report it.
impl From<ReadError> for VizError {
    fn from(e: ReadError) -> Self {
        match e {
            ReadError::Io { path, source } => Self::Io { path, source },
            ReadError::Parse {
                path,
                line,
                message,
            } => Self::Parse {
                path,
                line,
                message,
            },
            ReadError::Scenario(e) => Self::Invalid(e.to_string()),
        }
    }
}
