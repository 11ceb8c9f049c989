//! How a run directory is written: [`OutputOptions`], the trajectory's [`TrajectoryFormat`].

use std::str::FromStr;

/// How a run's trajectory is stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TrajectoryFormat {
    /// `trajectory.csv`: `t,id,x,y[,z],vx,vy[,vz]`, one line per agent and record.
    #[default]
    Csv,
    /// `trajectory.npy`: one structured record per instant, fields `t`, `q` (n × dim) and
    /// `p` (n × dim), read by `numpy.load` (see [`crate::run_dir::npy`]).
    Npy,
}

impl FromStr for TrajectoryFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "csv" => Ok(Self::Csv),
            "npy" => Ok(Self::Npy),
            other => Err(format!(
                "unknown trajectory format {other:?}: use csv or npy"
            )),
        }
    }
}

/// How a run directory is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputOptions {
    /// Replace an existing `DIR` that flocking wrote (never a directory holding anything else).
    pub force: bool,
    /// The trajectory's format.
    pub format: TrajectoryFormat,
    /// Keep a checkpoint every this many steps (0: only when interrupted).
    pub checkpoint_every: u64,
}

impl Default for OutputOptions {
    fn default() -> Self {
        Self {
            force: false,
            format: TrajectoryFormat::Csv,
            checkpoint_every: 1000,
        }
    }
}
