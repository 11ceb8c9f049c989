//! flocking's errors as Python exceptions (defined in `flocking/_errors.py`), each with the message the
//! CLI prints: `ScenarioError` (a `ValueError`, with the field), `NumericalError` (an
//! `ArithmeticError`, with the step, time and agent) and `RunDirectoryError` (an `OSError`).

use std::fmt::Display;
use std::path::Path;

use flocking::run_dir::{CreateError, ReadError, ResumeError};
use flocking::{NumericalError, ScenarioError};
use pyo3::call::PyCallArgs;
use pyo3::prelude::*;

/// An instance of the exception class `name` of `flocking._errors`, called with `args`.
pub(crate) fn exception<'py>(py: Python<'py>, name: &str, args: impl PyCallArgs<'py>) -> PyErr {
    let instance = py
        .import("flocking._errors")
        .and_then(|module| module.getattr(name))
        .and_then(|class| class.call1(args));
    match instance {
        Ok(instance) => PyErr::from_value(instance),
        Err(error) => error,
    }
}

/// `flocking.ScenarioError` (a `ValueError`): an invalid scenario, `.field` naming the parameter;
/// `MemoryError` for memory this machine could not give ([`ScenarioError::is_memory`]).
pub fn scenario_error(py: Python<'_>, error: &ScenarioError) -> PyErr {
    if error.is_memory() {
        return pyo3::exceptions::PyMemoryError::new_err(error.to_string());
    }
    exception(py, "ScenarioError", (error.to_string(), error.field()))
}

/// `flocking.NumericalError` (an `ArithmeticError`): a blow-up, with `.step`, `.t` and `.agent`.
pub fn numerical_error(py: Python<'_>, error: &NumericalError) -> PyErr {
    exception(
        py,
        "NumericalError",
        (error.to_string(), error.steps, error.t, error.fault.agent),
    )
}

/// `flocking.RunDirectoryError` (an `OSError`): a run directory that cannot be written or read,
/// `.path` naming it.
pub fn run_directory_error(py: Python<'_>, message: impl Display, path: &Path) -> PyErr {
    exception(
        py,
        "RunDirectoryError",
        (message.to_string(), path.display().to_string()),
    )
}

/// A run directory that cannot be created: the CLI's messages, with the keyword arguments of
/// `flocking.run` where the CLI names its flags.
pub fn create_error(py: Python<'_>, error: &CreateError, out: &Path) -> PyErr {
    let message = match error {
        CreateError::Occupied { target } => format!(
            "output directory {} already holds files; choose another `out` or pass force=True to replace it",
            target.display()
        ),
        CreateError::Interrupted { partial, target } => format!(
            "{} holds an interrupted run; continue it with `flocking.resume({:?})`, or pass force=True to start over",
            partial.display(),
            target.display().to_string()
        ),
        e @ CreateError::NotADirectory { .. } => e.to_string(),
        CreateError::Dir(e) => e.to_string(),
        CreateError::Io(e) => e.to_string(),
    };
    run_directory_error(py, message, out)
}

/// The error of a run directory's `scenario.ron`: an `OSError` when it cannot be read, a
/// `ScenarioError` when it does not load.
fn run_scenario_error(py: Python<'_>, error: &ScenarioError) -> PyErr {
    match error {
        ScenarioError::Io { path, .. } => run_directory_error(py, error, Path::new(path)),
        _ => scenario_error(py, error),
    }
}

/// A run directory that cannot be resumed.
pub fn resume_error(py: Python<'_>, error: &ResumeError, dir: &Path) -> PyErr {
    match error {
        ResumeError::Scenario(e) => run_scenario_error(py, e),
        ResumeError::Nothing {
            partial,
            target,
            complete: false,
        } => run_directory_error(
            py,
            format!(
                "there is no interrupted run at {}: start it with `flocking.run(scenario, out={:?})`",
                partial.display(),
                target.display().to_string()
            ),
            dir,
        ),
        _ => run_directory_error(py, error, dir),
    }
}

/// A run directory that cannot be read, `.path` naming the file at fault.
pub fn read_error(py: Python<'_>, error: &ReadError) -> PyErr {
    match error {
        ReadError::Scenario(e) => run_scenario_error(py, e),
        ReadError::Io { path, .. } | ReadError::Parse { path, .. } => {
            run_directory_error(py, error, path)
        }
    }
}

/// The CLI's resource check before a run or a simulation (issue 27: `Simulation` with a 10⁶ s
/// delay, `run` with 10⁸ agents aborted the interpreter): the scenario's estimate with `outputs`,
/// its start counted, must fit in this machine's memory and, with `out`, in the free space
/// there. Raises `MemoryError` (memory) or `RunDirectoryError` (disk) with the CLI's figures,
/// before anything is allocated or written.
pub fn check_resources(
    py: Python<'_>,
    scenario: &flocking::Scenario,
    outputs: &flocking::estimate::Outputs,
    out: Option<&Path>,
) -> PyResult<()> {
    check_estimate(py, Some(scenario.estimate_at_start(outputs)), out, None)
}

/// [`check_resources`] of `estimate` (`None`: nothing to run, nothing to check), with at most
/// `memory_cap` bytes of memory when the process has a limit of its own below the machine's (a
/// Dask worker's `memory_limit`).
pub fn check_estimate(
    py: Python<'_>,
    estimate: Option<flocking::estimate::Estimate>,
    out: Option<&Path>,
    memory_cap: Option<f64>,
) -> PyResult<()> {
    use flocking::estimate::Resources;
    let mut resources = match out {
        Some(out) => Resources::of_machine(out),
        None => Resources {
            disk_bytes: None,
            ..Resources::of_machine(Path::new("."))
        },
    };
    if let Some(cap) = memory_cap {
        resources.memory_bytes = Some(resources.memory_bytes.map_or(cap, |m| m.min(cap)));
    }
    let Some(Err(why)) = estimate.map(|e| e.check(&resources)) else {
        return Ok(());
    };
    let why = why.replace(", or --no-resource-check to try anyway", "");
    match out {
        Some(out) if why.starts_with("the outputs") => Err(run_directory_error(py, why, out)),
        _ => Err(pyo3::exceptions::PyMemoryError::new_err(why)),
    }
}

/// Whether `value` holds complex numbers (`numpy.iscomplexobj`: a complex dtype, or a sequence
/// of Python complex numbers). numpy would cast them to float with only a `ComplexWarning`,
/// dropping the imaginary parts; every array the package reads is refused instead (issue 27).
pub fn is_complex(value: &Bound<'_, PyAny>) -> PyResult<bool> {
    let numpy = value.py().import("numpy")?;
    numpy.getattr("iscomplexobj")?.call1((value,))?.extract()
}

/// Refuses the argument `field` when it holds complex numbers, as a `ScenarioError` naming it.
pub fn refuse_complex(py: Python<'_>, value: &Bound<'_, PyAny>, field: &str) -> PyResult<()> {
    if is_complex(value)? {
        return Err(scenario_error(
            py,
            &ScenarioError::invalid(
                field,
                ComplexArray,
                "holds complex numbers, whose imaginary parts a position or velocity cannot have",
                "pass real numbers (`array.real` when the imaginary parts are zero)",
            ),
        ));
    }
    Ok(())
}

/// A complex array, as an error shows the value refused.
struct ComplexArray;

impl std::fmt::Debug for ComplexArray {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a complex array")
    }
}
