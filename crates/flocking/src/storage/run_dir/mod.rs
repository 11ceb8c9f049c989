//! Run directories: what `flocking run --out DIR` writes ([`RunDirectory`], crash-safe, with
//! checkpoints to resume from) and how to read it back ([`read_run`]).
//!
//! | file | contents |
//! | --- | --- |
//! | `metrics.csv` | `t`, the metrics of [`METRICS_HEADER`], then the protocol's diagnostics |
//! | `trajectory.csv` | `t,id,x,y[,z],vx,vy[,vz]`, the vehicle's state, `failed` (with faults), every agent at every recorded step |
//! | `trajectory.npy` | instead of `trajectory.csv`: records `t`, `q` (n × dim), `p` (n × dim), `s` (n × k), `failed` (n bytes) |
//! | `final.csv` | the columns of `trajectory.csv` without `t`, the final state |
//! | `scenario.ron` | the scenario with every default filled in |
//! | `flocking.txt` | the model's verdict judged on `metrics.csv` ([`verdict`]): TAC 2006 Definition 5, or a classic model's states |

pub mod checkpoint;
pub mod npy;
pub mod read;
mod read_error;
mod table;
pub mod verdict;
pub mod write;

pub use checkpoint::{CHECKPOINT_FILE, Checkpoint, DrawsOf};
pub use read::{
    Columns, FAILED_COLUMN, ReadError, RunFiles, TIME, Trajectory, read_metrics, read_run,
    read_trajectory_csv, read_trajectory_npy, trajectory_header, trajectory_header_with,
};
pub use verdict::{VERDICT_FILE, judge_metrics_file, read_records, verdict_text};
pub use write::{
    CONTROLS_FILE, COUNT_COLUMNS, CreateError, Finished, INCOMPLETE_FILE, InterruptedRun,
    METRICS_HEADER, OutputOptions, ResumeError, RunDirectory, TrajectoryFormat, is_count_column,
    partial_path,
};
