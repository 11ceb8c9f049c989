//! The `flock` command line as a library: scenarios, their validation, runs and their outputs.
//!
//! - [`Scenario`]: a RON scenario file, [`Scenario::load`] parses and validates it.
//! - [`run_scenario`]: runs it in its dimension and hands records to a [`Recorder`].
//! - [`RunDirectory`]: the recorder behind `flock run --out DIR`.
//! - [`figures()`]: every fixture run and drawn into one directory with an `index.html`.
//! - [`Progress`]: the progress bar of `flock run`, a recorder wrapper.
//! - [`bench::bench()`]: the synthetic throughput benchmark behind `flock bench`.

pub mod bench;
pub mod checkpoint;
pub mod diagnostics;
pub mod error;
pub mod figures;
pub mod health;
pub mod initial;
pub mod npy;
pub mod output;
pub mod plot;
pub mod progress;
pub mod run;
pub mod scenario;
pub mod stability;
pub mod summary;
mod validate;

pub use error::ScenarioError;
pub use figures::{FigureEntry, FiguresError, figures};
pub use health::NumericalError;
pub use output::{
    INCOMPLETE_FILE, METRICS_HEADER, OutputOptions, ResumeError, RunDirectory, TrajectoryFormat,
};
pub use plot::{PlotError, plot_run};
pub use progress::Progress;
pub use run::{Record, Recorder, RunError, RunSummary, Start, resume_scenario, run, run_scenario};
pub use scenario::Scenario;
pub use stability::Warning;
pub use summary::Report;
