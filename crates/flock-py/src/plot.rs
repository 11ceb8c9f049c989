//! `flocking.plot` and `Run.plot`: the figures of a run directory drawn by the renderer of
//! `flocking plot` ([`flock_viz::plot_run_with`]), with its checks and options, without the CLI.

use std::path::PathBuf;

use flock_viz::plot::check_plot_dir;
use flock_viz::{FigureOptions, Output, PlotError, plot_run_with};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::{run_directory_error, scenario_error};

/// Draws the figures of the run directory `dir` into `dir/figures` as `flocking plot dir` does:
/// `outputs` some of `"snapshots"`, `"metrics"`, `"gif"`, `"player"` (default all), `times`
/// the snapshot times in seconds (default the scenario's `snapshots`, else six even times),
/// `stress_edges` colouring each edge by the sign of its stress weight. Returns the files written.
///
/// Raises `ValueError` for an unknown output or a time outside the run (naming it and the run's
/// span), `RunDirectoryError` for a directory that is not a complete run of flocking's or is being
/// written, `ScenarioError` for an invalid `scenario.ron`.
#[pyfunction]
#[pyo3(signature = (dir, *, outputs = None, times = None, stress_edges = false))]
pub fn plot_run(
    py: Python<'_>,
    dir: PathBuf,
    outputs: Option<Vec<String>>,
    times: Option<Vec<f64>>,
    stress_edges: bool,
) -> PyResult<Vec<PathBuf>> {
    let outputs = outputs
        .map(|names| Output::parse_list(&names.join(",")))
        .transpose()
        .map_err(PyValueError::new_err)?;
    check_plot_dir(&dir).map_err(|e| run_directory_error(py, e, &dir))?;
    let options = FigureOptions::plot(outputs, times, stress_edges);
    py.detach(|| plot_run_with(&dir, &options))
        .map_err(|e| match &e {
            PlotError::Scenario(error) => scenario_error(py, error),
            PlotError::Time { .. } => PyValueError::new_err(e.to_string()),
            PlotError::Dir(_) | PlotError::Viz(_) => run_directory_error(py, &e, &dir),
        })
}
