//! `flocking.run`, `flocking.resume` and `flocking.read_run`: whole runs of the [`flocking`] crate
//! ([`flocking::resume`]) recorded in memory as numpy arrays and, when asked, into the run directory
//! `flocking run --out` writes ([`RunDirectory`]); and any run directory read back ([`read_run`])
//! into the same arrays.
//!
//! Each returns a dict that `flocking.Run` wraps: `scenario`, `metrics` (the columns of
//! `metrics.csv`), `times`, `positions` and `velocities` ((T, n, dim), `None` when the
//! trajectory is not kept), `final` (t, positions, velocities) and `path`.

use std::io;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use flocking::metrics::{FlockMetrics, FlockingCriteria};
use flocking::run_dir::{
    OutputOptions, RunDirectory, TIME, TrajectoryFormat, VERDICT_FILE, is_count_column,
};
use flocking::{DynSimulation, Record, Recorder, RunError, Scenario, ScenarioProtocol, Start};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::controls::PythonControls;
use crate::errors::{
    create_error, numerical_error, read_error, resume_error, run_directory_error, scenario_error,
};
use crate::interrupt::watched;
use crate::local::PyLocal;
use crate::progress::Progress;
use crate::scenario::PyScenario;

/// The recorded instants of a run, kept as the columns of `metrics.csv` and the trajectory.
#[derive(Debug, Default)]
struct Memory {
    /// Whether to keep every recorded state, or only the last.
    keep_trajectory: bool,
    /// The names of the protocol's diagnostic columns (after `energy`).
    diagnostics: Vec<&'static str>,
    /// The real-valued columns of `metrics.csv` but `collisions` and `components`: t, the six
    /// metrics, the energy, the four extra metrics, then the diagnostics.
    reals: Vec<Vec<f64>>,
    /// The `collisions` column.
    collisions: Vec<i64>,
    /// The `components` column.
    components: Vec<i64>,
    /// The recorded positions (frames of n rows of dim), when kept.
    positions: Vec<f64>,
    /// The recorded velocities, when kept.
    velocities: Vec<f64>,
    /// The last recorded time, positions and velocities (the positions and velocities only when
    /// the trajectory is not kept: its last frame holds them).
    last: (f64, Vec<f64>, Vec<f64>),
    /// The dimension and the number of agents.
    dim: usize,
    agents: usize,
    /// The names of each agent's vehicle state (none for point masses).
    vehicle_columns: &'static [&'static str],
    /// The recorded vehicle states (frames of n rows of k) when the trajectory is kept, else
    /// the last.
    vehicle: Vec<f64>,
    /// Which agents have failed (frames of n when the trajectory is kept, else the last), when
    /// the scenario has `faults`.
    failed: Option<Vec<bool>>,
}

/// The real columns before the diagnostics: t, the real metrics, the energy, the extra metrics.
const REAL_COLUMNS: usize =
    FlockMetrics::REAL_COLUMNS.len() + 2 + FlockMetrics::EXTRA_COLUMNS.len();

impl Memory {
    /// Nothing recorded yet; room for every record of a run of `scenario` from t = 0 (t = 0,
    /// every `record_every` steps and the last step), the trajectory's only when it is kept.
    fn new(scenario: &Scenario, keep_trajectory: bool) -> Self {
        let (steps, every) = (scenario.steps(), scenario.record_every.max(1));
        let records = 1 + steps / every + u64::from(!steps.is_multiple_of(every));
        let size = if keep_trajectory {
            // Room reserved up front only up to 2²⁴ values (128 MiB each): a larger trajectory
            // grows as it is recorded, and an overflowing size reserves nothing.
            usize::try_from(records)
                .ok()
                .and_then(|r| r.checked_mul(scenario.agents)?.checked_mul(scenario.dim))
                .map_or(0, |size| size.min(1 << 24))
        } else {
            0
        };
        Self {
            keep_trajectory,
            positions: Vec::with_capacity(size),
            velocities: Vec::with_capacity(size),
            ..Self::default()
        }
    }

    fn record(&mut self, record: &Record<'_>) {
        if self.reals.is_empty() {
            self.diagnostics = record.diagnostics.iter().map(|(name, _)| *name).collect();
            self.reals = vec![Vec::new(); REAL_COLUMNS + self.diagnostics.len()];
        }
        let m = &record.metrics;
        let values = std::iter::once(record.t)
            .chain(m.reals())
            .chain([record.energy])
            .chain(m.extras())
            .chain(record.diagnostics.iter().map(|(_, value)| *value));
        for (column, value) in self.reals.iter_mut().zip(values) {
            column.push(value);
        }
        self.collisions
            .push(i64::try_from(m.collisions).unwrap_or(i64::MAX));
        self.components
            .push(i64::try_from(m.components).unwrap_or(i64::MAX));
        let state = &record.state;
        (self.dim, self.agents) = (state.dim, state.agents());
        self.vehicle_columns = state.vehicle_columns;
        if !self.keep_trajectory {
            self.vehicle.clear();
        }
        self.vehicle.extend_from_slice(&state.vehicle);
        if let Some(flags) = &state.failed {
            let failed = self.failed.get_or_insert_with(Vec::new);
            if !self.keep_trajectory {
                failed.clear();
            }
            failed.extend_from_slice(flags);
        }
        self.last.0 = record.t;
        if self.keep_trajectory {
            self.positions.extend_from_slice(&state.positions);
            self.velocities.extend_from_slice(&state.velocities);
        } else {
            self.last.1.clear();
            self.last.1.extend_from_slice(&state.positions);
            self.last.2.clear();
            self.last.2.extend_from_slice(&state.velocities);
        }
    }

    /// The result dict of `flocking.Run`.
    fn into_result<'py>(
        mut self,
        py: Python<'py>,
        scenario: &Scenario,
        path: Option<&Path>,
        verdict: Option<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let names = std::iter::once(TIME)
            .chain(FlockMetrics::REAL_COLUMNS)
            .chain(["energy"])
            .chain(FlockMetrics::EXTRA_COLUMNS)
            .chain(self.diagnostics.iter().copied());
        let mut columns = Vec::with_capacity(self.reals.len() + 1);
        for (name, column) in names.zip(self.reals) {
            columns.push((name.to_owned(), Column::Real(column)));
        }
        // `collisions` stands before `energy`, and `components` after the extra metrics, as in
        // metrics.csv
        let (collisions, components) = if columns.is_empty() {
            (0, 1)
        } else {
            let collisions = 1 + FlockMetrics::REAL_COLUMNS.len();
            (
                collisions,
                collisions + 2 + FlockMetrics::EXTRA_COLUMNS.len(),
            )
        };
        columns.insert(
            collisions,
            ("collisions".to_owned(), Column::Integer(self.collisions)),
        );
        columns.insert(
            components,
            ("components".to_owned(), Column::Integer(self.components)),
        );
        if self.keep_trajectory {
            let size = self.agents * self.dim;
            let from = self.positions.len().saturating_sub(size);
            self.last.1 = self.positions[from..].to_vec();
            self.last.2 = self.velocities[from..].to_vec();
        }
        let trajectory = self.keep_trajectory.then(|| {
            let times = match columns.first() {
                Some((_, Column::Real(t))) => t.clone(),
                _ => Vec::new(),
            };
            (times, self.positions, self.velocities)
        });
        let dict = result(
            py,
            scenario,
            columns,
            trajectory,
            (self.last, self.agents, self.dim),
            path,
            verdict,
        )?;
        let columns: Vec<String> = self.vehicle_columns.iter().map(|&c| c.to_owned()).collect();
        let kept = self.keep_trajectory.then_some(self.vehicle.clone());
        set_vehicle(&dict, &columns, kept, &self.vehicle, self.agents)?;
        set_failed(&dict, self.failed, self.keep_trajectory, self.agents)?;
        Ok(dict)
    }
}

/// Which agents have failed, in the result dict, from `failed` (frames of n when `frames`, else
/// the last frame's n): `failed` ((T, n) booleans when the frames are kept, else `None`) and
/// `final["failed"]` ((n,)); both `None` for a scenario without `faults`.
fn set_failed(
    dict: &Bound<'_, PyDict>,
    failed: Option<Vec<bool>>,
    frames: bool,
    agents: usize,
) -> PyResult<()> {
    let py = dict.py();
    let last = failed
        .as_ref()
        .map(|f| f[f.len() - agents.min(f.len())..].to_vec());
    match failed.filter(|_| frames) {
        Some(failed) => {
            let count = failed.len() / agents.max(1);
            let array = PyArray1::from_vec(py, failed).reshape([count, agents])?;
            dict.set_item("failed", array)?;
        }
        None => dict.set_item("failed", py.None())?,
    }
    if let Some(last_frame) = dict.get_item("final")? {
        match last {
            Some(last) => last_frame.set_item("failed", PyArray1::from_vec(py, last))?,
            None => last_frame.set_item("failed", py.None())?,
        }
    }
    Ok(())
}

/// The vehicles' states in the result dict: `vehicle_columns` (their names, empty for point
/// masses), `vehicle` ((T, n, k) when the trajectory is kept and the agents have a vehicle,
/// else `None`) and `final["vehicle"]` ((n, k)), from the recorded `frames` and the states
/// whose last frame is the final one (`states`).
fn set_vehicle(
    dict: &Bound<'_, PyDict>,
    columns: &[String],
    frames: Option<Vec<f64>>,
    states: &[f64],
    agents: usize,
) -> PyResult<()> {
    let py = dict.py();
    let k = columns.len();
    dict.set_item("vehicle_columns", columns.to_vec())?;
    match frames.filter(|_| k > 0) {
        Some(frames) => {
            let count = frames.len() / (agents * k).max(1);
            let array = PyArray1::from_vec(py, frames).reshape([count, agents, k])?;
            dict.set_item("vehicle", array)?;
        }
        None => dict.set_item("vehicle", py.None())?,
    }
    let last = states[states.len() - (agents * k).min(states.len())..].to_vec();
    let array = PyArray1::from_vec(py, last).reshape([agents, k])?;
    match dict.get_item("final")? {
        Some(last) => last.set_item("vehicle", array),
        None => Ok(()),
    }
}

/// A column of `metrics.csv`: the counts ([`is_count_column`]: `collisions`, `components`, the
/// diagnostics' counts) are integers, the others reals.
enum Column {
    Real(Vec<f64>),
    Integer(Vec<i64>),
}

impl Column {
    /// The column `name` as Python gets it: a count column of whole numbers as integers (a real
    /// column otherwise, NaN and ∞ included, as it is).
    fn counted(self, name: &str) -> Self {
        match self {
            Self::Real(values)
                if is_count_column(name) && values.iter().all(|x| x.fract() == 0.0) =>
            {
                Self::Integer(values.iter().map(|&x| x as i64).collect())
            }
            column => column,
        }
    }
}

/// The dict that `flocking.Run` wraps; `verdict` is the first line of `flocking.txt`.
fn result<'py>(
    py: Python<'py>,
    scenario: &Scenario,
    columns: Vec<(String, Column)>,
    trajectory: Option<(Vec<f64>, Vec<f64>, Vec<f64>)>,
    ((t, positions, velocities), agents, dim): ((f64, Vec<f64>, Vec<f64>), usize, usize),
    path: Option<&Path>,
    verdict: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item(
        "scenario",
        PyScenario {
            inner: scenario.clone(),
        },
    )?;
    let metrics = PyDict::new(py);
    for (name, column) in columns {
        match column.counted(&name) {
            Column::Real(values) => metrics.set_item(name, PyArray1::from_vec(py, values))?,
            Column::Integer(values) => metrics.set_item(name, PyArray1::from_vec(py, values))?,
        }
    }
    dict.set_item("metrics", metrics)?;
    match trajectory {
        Some((times, positions, velocities)) => {
            let frames = times.len();
            dict.set_item("times", PyArray1::from_vec(py, times))?;
            for (key, rows) in [("positions", positions), ("velocities", velocities)] {
                let array = PyArray1::from_vec(py, rows).reshape([frames, agents, dim])?;
                dict.set_item(key, array)?;
            }
        }
        None => {
            for key in ["times", "positions", "velocities"] {
                dict.set_item(key, py.None())?;
            }
        }
    }
    let last = PyDict::new(py);
    last.set_item("t", t)?;
    for (key, rows) in [("positions", positions), ("velocities", velocities)] {
        let array = PyArray1::from_vec(py, rows).reshape([agents, dim])?;
        last.set_item(key, array)?;
    }
    dict.set_item("final", last)?;
    dict.set_item("path", path.map(|p| p.display().to_string()))?;
    dict.set_item("verdict", verdict)?;
    Ok(dict)
}

/// Records in memory and, when given, into a run directory (the run stops on Ctrl-C through the
/// library's interrupt, [`crate::interrupt::watched`]).
struct PyRecorder {
    memory: Memory,
    dir: Option<RunDirectory>,
    /// H(0), for a checkpoint after `controls` failed: that of the first record, or the start's.
    initial_energy: Option<f64>,
    /// The progress, told to a Python sink, when asked.
    progress: Option<Progress>,
}

impl Recorder for PyRecorder {
    type Error = io::Error;

    fn record(&mut self, record: &Record<'_>) -> io::Result<()> {
        if let Some(dir) = &mut self.dir {
            dir.record(record)?;
        }
        self.initial_energy.get_or_insert(record.energy);
        self.memory.record(record);
        if let Some(progress) = &mut self.progress {
            progress.at(record.t);
        }
        Ok(())
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.dir
            .as_ref()
            .is_some_and(|dir| dir.wants_checkpoint(steps))
    }

    fn checkpoint(&mut self, start: &Start) -> io::Result<()> {
        self.dir
            .as_mut()
            .map_or(Ok(()), |dir| dir.checkpoint(start))
    }
}

/// Runs `sim` (built from `start`, or at t = 0 when `None`) with the GIL released and Ctrl-C
/// watched ([`watched`]), into `dir` when given, its inputs from `controls` when given; on
/// failure keeps `dir` as `flocking run` does (resumable after Ctrl-C, a failed write or an
/// exception of `controls`, marked failed after a blow-up) and raises the error. Returns the
/// records, the finished directory and the model's verdict on the records of this
/// call (the line `flocking.txt` begins with).
fn execute<'py>(
    py: Python<'py>,
    sim: DynSimulation,
    start: Option<&Start>,
    dir: Option<RunDirectory>,
    keep_trajectory: bool,
    (controls, progress): (Option<&PythonControls>, Option<Py<PyAny>>),
) -> PyResult<(Memory, Option<PathBuf>, Option<String>)> {
    let scenario = &sim.scenario().clone();
    let t0 = start.map_or(0.0, |s| s.steps as f64 * scenario.step);
    let mut recorder = PyRecorder {
        memory: Memory::new(scenario, keep_trajectory),
        dir,
        initial_energy: start.map(|s| s.initial_energy),
        progress: progress.map(|sink| Progress::new(sink, t0, scenario.duration, scenario.step)),
    };
    let initial_energy = recorder.initial_energy;
    let ((outcome, recorder), raised) = watched(py, move || {
        let outcome = flocking::run_from(sim, initial_energy, &mut recorder);
        let verdict = outcome.map(|summary| {
            summary
                .verdict(&FlockingCriteria::default())
                .map(|v| v.to_string())
        });
        (verdict, recorder)
    });
    let PyRecorder {
        memory,
        mut dir,
        initial_energy,
        progress,
    } = recorder;
    if let Some(progress) = progress {
        progress.close();
    }
    let error = match outcome {
        Ok(verdict) => {
            let path = match dir {
                Some(dir) => {
                    let partial = dir.partial().to_owned();
                    let finished = dir
                        .finish()
                        .map_err(|e| run_directory_error(py, e, &partial))?;
                    Some(finished.path)
                }
                None => None,
            };
            return Ok((memory, path, verdict));
        }
        Err(error) => error,
    };
    let (why, resumable, raised) = match &error {
        // the simulation was built before the run began: its directory is kept as it is
        RunError::Scenario(e) => (error.to_string(), true, scenario_error(py, e)),
        RunError::Numerical(e) => match controls.and_then(PythonControls::take_failure) {
            // `controls` failed in step e.steps: the run stops before it, as after Ctrl-C
            Some(failure) => {
                let steps = e.steps.saturating_sub(1);
                // with conditions or vehicles, the state before the failed step is not all a
                // resume needs (their delay line, noise and vehicle states moved on): the last
                // regular checkpoint stays
                let ideal = scenario.conditions.is_ideal() && scenario.vehicle.is_point_mass();
                if let (true, Some(dir), Some((positions, velocities)), Some(initial_energy)) =
                    (ideal, dir.as_mut(), failure.start, initial_energy)
                {
                    let start = Start {
                        steps,
                        initial_energy,
                        positions,
                        velocities,
                        conditions: String::new(),
                        vehicle: Vec::new(),
                    };
                    dir.checkpoint(&start)
                        .map_err(|e| run_directory_error(py, e, dir.partial()))?;
                }
                let why = format!("controls raised an exception in step {}", steps + 1);
                (why, true, failure.error)
            }
            None => (error.to_string(), false, numerical_error(py, e)),
        },
        RunError::Record(e) => {
            let path = dir
                .as_ref()
                .map_or_else(PathBuf::new, |d| d.partial().to_owned());
            (
                format!("writing failed: {e}"),
                true,
                run_directory_error(py, &error, &path),
            )
        }
        RunError::Interrupted { .. } => {
            let raised = raised.unwrap_or_else(|| PyKeyboardInterrupt::new_err(error.to_string()));
            (format!("{error} by Ctrl-C"), true, raised)
        }
    };
    let Some(dir) = dir else {
        return Err(interrupted_message(py, raised, &error, None));
    };
    match dir.keep_incomplete(&why, resumable) {
        Ok(partial) => Err(interrupted_message(py, raised, &error, Some(&partial))),
        Err(e) => Err(run_directory_error(
            py,
            format!("{why}; cannot mark the run incomplete: {e}"),
            Path::new(""),
        )),
    }
}

/// A `KeyboardInterrupt` of a run carries the CLI's message: the step reached and, with a run
/// directory, where the records are kept and how to continue; other errors stay as they are.
fn interrupted_message(
    py: Python<'_>,
    raised: PyErr,
    error: &RunError<io::Error>,
    partial: Option<&Path>,
) -> PyErr {
    if !matches!(error, RunError::Interrupted { .. })
        || !raised.is_instance_of::<PyKeyboardInterrupt>(py)
    {
        return raised;
    }
    let message = match partial {
        Some(partial) => format!(
            "{error}; the records so far are kept in {}; continue with `flocking.resume({:?})`",
            partial.display(),
            partial.display().to_string()
        ),
        None => error.to_string(),
    };
    PyKeyboardInterrupt::new_err(message)
}

/// Warns of each of the scenario's warnings (a step above the largest stable step, agents
/// starting at one point), as `flocking run` prints them.
fn warn(py: Python<'_>, scenario: &Scenario) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for warning in scenario.warnings() {
        // Python prints the category, `UserWarning: `, before the message: not `warning: ` again
        let text = warning.to_string();
        let text = text.strip_prefix("warning: ").unwrap_or(&text);
        let message =
            std::ffi::CString::new(text).map_err(|e| PyValueError::new_err(e.to_string()))?;
        PyErr::warn(py, &category, &message, 2)?;
    }
    Ok(())
}

/// Runs `scenario` to its end and returns its records (wrapped by `flocking.run` as a `flocking.Run`).
///
/// With `out`, also writes the run directory of `flocking run --out` (byte for byte the same):
/// `trajectory_format` `"csv"` or `"npy"`, a checkpoint every `checkpoint_every` steps, an
/// existing directory replaced only with `force`. `trajectory=False` keeps only the final state in
/// memory. The GIL is released while the run steps; Ctrl-C raises `KeyboardInterrupt` after the
/// current step, leaving `out` resumable (`flocking.resume(out)`).
///
/// `controls` (a function `f(t, q, p, neighbours)` returning u as an n × dim array) replaces the
/// inputs of the scenario's protocol ([`PythonControls`]); an exception it raises stops the run
/// before the step it was called for, leaves `out` resumable with the same `controls`, and is
/// raised again.
#[pyfunction]
#[pyo3(signature = (scenario, out = None, *, trajectory = true, trajectory_format = "csv", checkpoint_every = 1000, force = false, controls = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    scenario: &PyScenario,
    out: Option<PathBuf>,
    trajectory: bool,
    trajectory_format: &str,
    checkpoint_every: u64,
    force: bool,
    controls: Option<Py<PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let format = TrajectoryFormat::from_str(trajectory_format).map_err(PyValueError::new_err)?;
    let scenario = &scenario.inner;
    let outputs = match &out {
        Some(_) => flocking::estimate::Outputs {
            trajectory_csv: Some(format == TrajectoryFormat::Csv),
            ..flocking::estimate::Outputs::RUN
        },
        None => flocking::estimate::Outputs::NONE,
    };
    // before the warnings, which build the initial net of every agent
    crate::errors::check_resources(py, scenario, &outputs, out.as_deref())?;
    warn(py, scenario)?;
    let controls = controls.map(|f| (PythonControls::new(f.clone_ref(py), scenario), f));
    // built before `out` is written, so that a refusal leaves nothing behind
    let sim = py
        .detach(|| match &controls {
            Some((controls, _)) => DynSimulation::new_with(scenario, controls),
            None => DynSimulation::new(scenario),
        })
        .map_err(|e| scenario_error(py, &e))?;
    let dir = match &out {
        Some(out) => {
            let options = OutputOptions {
                force,
                format,
                checkpoint_every,
            };
            Some(
                RunDirectory::create_with(out, scenario, &options)
                    .map_err(|e| create_error(py, &e, out))?,
            )
        }
        None => None,
    };
    // issue 27: the directory records that its inputs came from Python, so that a resume
    // without them is refused
    let mut dir = dir;
    if let (Some(directory), Some((_, f)), Some(out)) = (&mut dir, &controls, &out) {
        directory
            .record_controls(&controls_source(py, f))
            .map_err(|e| crate::errors::run_directory_error(py, e, out))?;
    }
    let controls = controls.map(|(controls, _)| controls);
    let (memory, path, verdict) = execute(
        py,
        sim,
        None,
        dir,
        trajectory,
        (controls.as_ref(), progress),
    )?;
    memory.into_result(py, scenario, path.as_deref(), verdict)
}

/// Continues the interrupted or killed run in `dir` (or `dir.partial`) from its last checkpoint,
/// as `flocking run --resume` does (the finished directory is byte-identical to an uninterrupted
/// run's), and returns the whole run read back from it. A run made with `controls` needs the same
/// `controls` to continue as it would have.
#[pyfunction]
#[pyo3(signature = (dir, *, checkpoint_every = 1000, controls = None, progress = None))]
pub fn resume<'py>(
    py: Python<'py>,
    dir: PathBuf,
    checkpoint_every: u64,
    controls: Option<Py<PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let source = controls.as_ref().map(|f| controls_source(py, f));
    let (interrupted, scenario, start) =
        RunDirectory::resume_with_controls(&dir, checkpoint_every, source.as_deref())
            .map_err(|e| resume_error(py, &e, &dir))?;
    let controls = controls.map(|f| PythonControls::new(f, &scenario));
    // what `flocking run --resume` checks: the run must fit this machine
    let outputs = flocking::estimate::Outputs {
        trajectory_csv: Some(!interrupted.partial().join("trajectory.npy").exists()),
        ..flocking::estimate::Outputs::RUN
    };
    crate::errors::check_resources(py, &scenario, &outputs, Some(interrupted.partial()))?;
    // the run's simulation rebuilt from its checkpoint before anything is written (issue 49: a
    // refused checkpoint deleted the run)
    let sim = py
        .detach(|| match &controls {
            Some(controls) => DynSimulation::build_with(&scenario, start.as_ref(), controls),
            None => DynSimulation::build_with(&scenario, start.as_ref(), &ScenarioProtocol),
        })
        .map_err(|e| {
            let kept = format!(
                "the checkpoint in {} cannot be continued ({} is kept as it was): {e}",
                interrupted.partial().display(),
                interrupted.partial().display()
            );
            crate::errors::exception(py, "ScenarioError", (kept, e.field()))
        })?;
    let directory = interrupted
        .reopen()
        .map_err(|e| run_directory_error(py, e, &dir))?;
    let (_, path, _) = execute(
        py,
        sim,
        start.as_ref(),
        Some(directory),
        false,
        (controls.as_ref(), progress),
    )?;
    let path = path.unwrap_or(dir);
    read_run(py, path)
}

/// What a run directory records of Python's `controls=f`: "Python controls=`module.qualname`".
///
/// A callable object without a name of its own (an instance of a class with `__call__`) is named
/// by its class, `module.Class`: the name a resume compares is the same in every process (its
/// `repr` holds an address).
fn controls_source(py: Python<'_>, f: &Py<PyAny>) -> String {
    let f = f.bind(py);
    let named = |object: &Bound<'_, PyAny>| {
        let attribute = |name: &str| {
            object
                .getattr(name)
                .ok()
                .and_then(|v| v.extract::<String>().ok())
        };
        let qualname = attribute("__qualname__")?;
        Some(match attribute("__module__") {
            Some(module) => format!("{module}.{qualname}"),
            None => qualname,
        })
    };
    let name_of = |f: &Bound<'_, PyAny>| {
        named(f)
            .or_else(|| named(f.get_type().as_any()))
            .unwrap_or_else(|| "a callable".to_owned())
    };
    let name = match f.cast::<PyLocal>() {
        Ok(local) => format!("Local({})", name_of(local.get().f.bind(py))),
        Err(_) => name_of(f),
    };
    format!("Python controls={name}")
}

/// Reads the run directory `dir` (complete, or an interrupted `DIR.partial`): its scenario, the
/// columns of `metrics.csv` and the trajectory (`trajectory.csv` or `trajectory.npy`); the final
/// state is the last recorded one.
#[pyfunction]
pub fn read_run(py: Python<'_>, dir: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let files = py
        .detach(|| flocking::read_run(&dir))
        .map_err(|e| read_error(py, &e))?;
    // an interrupted run has no verdict yet
    let verdict = std::fs::read_to_string(dir.join(VERDICT_FILE))
        .ok()
        .and_then(|text| text.lines().next().map(str::to_owned));
    let trajectory = files.trajectory;
    let (dim, agents, frames) = (trajectory.dim, trajectory.agents, trajectory.frames());
    let last = match frames.checked_sub(1) {
        Some(k) => (
            trajectory.times[k],
            trajectory.positions_at(k).to_vec(),
            trajectory.velocities_at(k).to_vec(),
        ),
        None => (f64::NAN, Vec::new(), Vec::new()),
    };
    let columns = files
        .metrics
        .into_iter()
        .map(|(name, values)| (name, Column::Real(values)))
        .collect();
    let vehicle_columns = trajectory.vehicle_columns.clone();
    let vehicle = trajectory.vehicle;
    let failed = (!trajectory.failed.is_empty()).then_some(trajectory.failed);
    let dict = result(
        py,
        &files.scenario,
        columns,
        Some((
            trajectory.times,
            trajectory.positions,
            trajectory.velocities,
        )),
        (last, agents, dim),
        Some(&dir),
        verdict,
    )?;
    set_vehicle(
        &dict,
        &vehicle_columns,
        Some(vehicle.clone()),
        &vehicle,
        agents,
    )?;
    set_failed(&dict, failed, true, agents)?;
    Ok(dict)
}
