//! The pieces of `flocking.sweep` (`python/flocking/__init__.py`): a sweep file loaded and made
//! self-contained, one run of it made in a worker (any process of any machine), and the output
//! directory of [`flocking::sweep::store`] — the same row files and `runs.csv` as `flocking sweep`.

use std::path::{Path, PathBuf};

use flocking::owned::DirLock;
use flocking::sweep::store::{self, StoreError};
use flocking::sweep::{Sweep, SweepError, run_one, run_one_with};
use pyo3::prelude::*;

use crate::controls::PythonControls;
use crate::errors::{exception, run_directory_error};

/// A sweep error as `flocking.ScenarioError` (a `ValueError`) with the message of `flocking sweep`.
fn sweep_error(py: Python<'_>, error: &SweepError) -> PyErr {
    exception(py, "ScenarioError", (error.to_string(), error.field()))
}

fn store_error(py: Python<'_>, error: &StoreError, dir: &Path) -> PyErr {
    match error {
        StoreError::Sweep(e) => sweep_error(py, e),
        other => run_directory_error(py, other, dir),
    }
}

/// The text of the sweep file at `path`, read as the CLI reads it (issue 27): a file that is not
/// regular (a FIFO, `/dev/zero`) or larger than the input limit is refused before reading,
/// naming the path, as a `ScenarioError`.
#[pyfunction]
pub fn sweep_read(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    py.detach(|| flocking::input::read_text(&path))
        .map_err(|message| {
            sweep_error(
                py,
                &SweepError::Io {
                    path: path.display().to_string(),
                    message,
                },
            )
        })
}

/// `(text, runs)`: the sweep in `text` (`Path` bases relative to `base_dir`) as self-contained RON,
/// and its number of runs.
#[pyfunction]
pub fn sweep_load(
    py: Python<'_>,
    text: &str,
    origin: &str,
    base_dir: PathBuf,
) -> PyResult<(String, usize)> {
    let sweep = Sweep::parse(text, origin, &base_dir).map_err(|e| sweep_error(py, &e))?;
    let resolved = sweep.to_ron().map_err(|e| {
        sweep_error(
            py,
            &SweepError::Invalid {
                field: "sweep".into(),
                why: e.to_string(),
            },
        )
    })?;
    Ok((resolved, sweep.runs().len()))
}

/// `(index, id, fields, wall_time)` of run `index` of the self-contained sweep `text`, run on one
/// thread with the GIL released: the row `flocking sweep` writes for it — its inputs from
/// `controls` when given ([`PythonControls`]; an exception it raises is raised again, no row).
///
/// With `check` (a worker of an executor the caller chose, whose machine the sweep's own check
/// did not see), the run's estimate, its start counted, must first fit in the memory of the
/// machine it landed on, and within `memory_limit` bytes when the worker has a limit of its own
/// (a Dask worker's): `MemoryError` naming the run and the figures otherwise, before anything
/// is allocated, instead of a worker killed for its memory.
#[pyfunction]
#[pyo3(signature = (text, index, controls = None, check = false, memory_limit = None))]
pub fn sweep_run(
    py: Python<'_>,
    text: &str,
    index: usize,
    controls: Option<Py<PyAny>>,
    check: bool,
    memory_limit: Option<f64>,
) -> PyResult<(usize, String, Vec<String>, f64)> {
    let sweep = Sweep::parse_checked(text, "<sweep>").map_err(|e| sweep_error(py, &e))?;
    let runs = sweep.runs();
    let Some(spec) = runs.get(index) else {
        return Err(pyo3::exceptions::PyIndexError::new_err(format!(
            "the sweep has {} runs, numbered from 0; there is no run {index}",
            runs.len()
        )));
    };
    // a run whose scenario is invalid is a row with its error: nothing to check or control
    let scenario = sweep.scenario(spec).ok();
    if check && let Some(scenario) = &scenario {
        let estimate = scenario.estimate_at_start(&flocking::estimate::Outputs::NONE);
        crate::errors::check_estimate(py, Some(estimate), None, memory_limit).map_err(|e| {
            let limit = memory_limit.map_or("", |_| " (its memory limit counted)");
            pyo3::exceptions::PyMemoryError::new_err(format!(
                "run {index} ({}) on the worker that took it{limit}: {}",
                spec.id(&sweep.axes),
                e.value(py)
            ))
        })?;
    }
    let controls = match (controls, &scenario) {
        (Some(f), Some(scenario)) => Some(PythonControls::new(f, scenario)),
        _ => None,
    };
    let one = || match &controls {
        Some(controls) => run_one_with(&sweep, spec, None, controls),
        None => run_one(&sweep, spec, None),
    };
    let row = py.detach(|| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build();
        match pool {
            Ok(pool) => pool.install(one),
            Err(_) => one(),
        }
    });
    if let Some(failure) = controls.as_ref().and_then(PythonControls::take_failure) {
        return Err(failure.error);
    }
    if row.retry {
        // stopped by the process's interrupt (another call's Ctrl-C): no row, made again
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(format!(
            "run {index} ({}) was interrupted",
            row.id
        )));
    }
    Ok((row.index, row.id.clone(), row.fields(), row.wall_time))
}

/// The resource check of `flocking sweep` before the self-contained sweep `text` runs its runs
/// not found finished in `dir` on `workers` processes of this machine: each worker needs the
/// memory of its run, the start of every run counted. Raises `MemoryError` with the figures.
#[pyfunction]
pub fn sweep_check(py: Python<'_>, text: &str, dir: PathBuf, workers: usize) -> PyResult<()> {
    let sweep = Sweep::parse_checked(text, "<sweep>").map_err(|e| sweep_error(py, &e))?;
    let pending = flocking::sweep::share(&sweep, &dir, None)
        .map_or_else(|_| sweep.runs(), |(_, pending)| pending);
    let outputs = flocking::estimate::Outputs::NONE;
    let estimate = py.detach(|| flocking::sweep::estimate(&sweep, &pending, &outputs, workers));
    crate::errors::check_estimate(py, estimate, None, None)
}

/// The lock of a sweep's output directory ([`store::prepare`]), held until
/// its `release` method is called (or until the process ends): another writer of the directory is
/// refused meanwhile.
#[pyclass(module = "flocking._flocking")]
pub struct SweepLock(Option<DirLock>);

#[pymethods]
impl SweepLock {
    /// Releases the lock (again: nothing).
    fn release(&mut self) {
        self.0 = None;
    }
}

/// Opens (or creates) the output directory `dir` of the self-contained sweep `text`, locked for
/// this process, and returns the indices of the runs already finished in it, with the lock
/// (to be released once the sweep is assembled). A directory holding files flocking did not
/// write, or being written by another process, raises `RunDirectoryError`.
#[pyfunction]
pub fn sweep_prepare(
    py: Python<'_>,
    dir: PathBuf,
    text: &str,
) -> PyResult<(Vec<usize>, SweepLock)> {
    let sweep = Sweep::parse_checked(text, "<sweep>").map_err(|e| sweep_error(py, &e))?;
    let lock = store::prepare(&dir, &sweep).map_err(|e| store_error(py, &e, &dir))?;
    let finished = store::finished(&dir, &sweep).map_err(|e| store_error(py, &e, &dir))?;
    Ok((finished.into_keys().collect(), SweepLock(Some(lock))))
}

/// Records a finished run (as [`sweep_run`] returned it) in `dir`.
#[pyfunction]
pub fn sweep_write_row(
    py: Python<'_>,
    dir: PathBuf,
    index: usize,
    id: &str,
    fields: Vec<String>,
    wall_time: f64,
) -> PyResult<()> {
    store::write_fields(&dir, index, id, &fields, wall_time).map_err(|e| store_error(py, &e, &dir))
}

/// Writes `runs.csv` and `times.csv` of `dir` from its rows; returns how many rows they hold.
#[pyfunction]
pub fn sweep_assemble(py: Python<'_>, dir: PathBuf, text: &str) -> PyResult<usize> {
    let sweep = Sweep::parse_checked(text, "<sweep>").map_err(|e| sweep_error(py, &e))?;
    store::assemble(&dir, &sweep).map_err(|e| store_error(py, &e, &dir))
}

/// The error of [`flock_viz::plot_sweep`] as Python's: a request the sweep cannot answer a
/// `ValueError`, a failure to read or write an `OSError`, with the CLI's message.
fn plot_error(error: flock_viz::SweepPlotError) -> PyErr {
    match error {
        flock_viz::SweepPlotError::Refused(message) => {
            pyo3::exceptions::PyValueError::new_err(message)
        }
        flock_viz::SweepPlotError::Failed(message) => pyo3::exceptions::PyOSError::new_err(message),
    }
}

/// `SweepResult.plot`: the diagram of `flocking sweep plot` drawn by the same code
/// ([`flock_viz::plot_sweep`]) into `out`; `(path written, warnings)`.
#[pyfunction]
#[pyo3(signature = (dir, metric, x, y, fixed, facet, series, reference, band, log_x, log_y, log_colour, even_cells, bound, bound_label, out))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_plot(
    py: Python<'_>,
    dir: PathBuf,
    metric: String,
    x: String,
    y: Option<String>,
    fixed: Vec<(String, String)>,
    facet: Option<String>,
    series: Option<String>,
    reference: Option<PathBuf>,
    band: &str,
    log_x: bool,
    log_y: bool,
    log_colour: bool,
    even_cells: bool,
    bound: Option<f64>,
    bound_label: String,
    out: Option<PathBuf>,
) -> PyResult<(PathBuf, Vec<String>)> {
    let band = match band {
        "minmax" => flock_viz::Band::MinMax,
        "quantiles" => flock_viz::Band::Quantiles,
        other => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "band={other:?}: give \"minmax\" or \"quantiles\""
            )));
        }
    };
    let request = flock_viz::SweepPlot {
        x,
        y,
        fixed,
        facet,
        series,
        reference,
        metric,
        band,
        log_x,
        log_y,
        log_colour,
        even_cells,
        bound: bound.map(|x| flock_viz::phase::Bound {
            x,
            label: bound_label,
        }),
    };
    let plotted = py
        .detach(|| flock_viz::plot_sweep(&dir, &request, out.as_deref()))
        .map_err(plot_error)?;
    Ok((plotted.path, plotted.warnings))
}

/// One axis of a sweep as `SweepResult.to_xarray` names it: (path, long name, unit).
type AxisName = (String, String, &'static str);

/// What `SweepResult.to_xarray` names: the sweep's name, description and seeds, its axes, and
/// the figure names of the columns asked for.
type SweepNames = (String, String, u64, Vec<AxisName>, Vec<String>);

/// `SweepResult.to_xarray`'s names: the sweep's name, description and seeds, its axes (path,
/// name and symbol, unit) and the figure names of `columns` ([`flocking::sweep::metric_label`]).
#[pyfunction]
pub fn sweep_names(py: Python<'_>, dir: PathBuf, columns: Vec<String>) -> PyResult<SweepNames> {
    let sweep = store::read_sweep(&dir).map_err(|e| store_error(py, &e, &dir))?;
    let base = sweep.base_scenario().map_err(|e| sweep_error(py, &e))?;
    let axes = sweep
        .axes
        .iter()
        .map(|axis| {
            let label = flocking::sweep::ParameterLabel::of(&base, &axis.path);
            (axis.path.clone(), label.name(), label.unit())
        })
        .collect();
    let labels = columns
        .iter()
        .map(|c| flocking::sweep::metric_label(c).to_owned())
        .collect();
    Ok((sweep.name, sweep.description, sweep.seeds, axes, labels))
}
