//! `flocking.Simulation`: a scenario's [`DynSimulation`] driven step by step from Python — stepped
//! with the GIL released, its state as numpy arrays (agents in original order), its metrics and
//! energy, and its state replaced to perturb it; its inputs from a Python function when given
//! ([`PythonControls`]).

use std::sync::{Mutex, MutexGuard, PoisonError};

use flocking::metrics::FlockMetrics;
use flocking::{DynSimulation, Scenario, ScenarioError};
use numpy::{AllowTypeChange, PyArray1, PyArray2, PyArrayLike2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::controls::PythonControls;
use crate::errors::{exception, numerical_error, refuse_complex, scenario_error};
use crate::interrupt::watched;
use crate::scenario::PyScenario;

/// The simulation of a scenario, stepped from Python: `step(k)` advances it k steps of h (the GIL
/// released; Ctrl-C stops it between steps, or within a second inside a long one), `q` and `p`
/// are its positions and velocities as
/// n × dim arrays (copies, agents in original order), `t` its time; `metrics()` and `energy()`
/// measure it as a run records it. Stepping a fresh `Simulation(scenario)` `scenario.steps`
/// times gives the bits of `flocking.run(scenario).final`.
///
/// `positions` and `velocities` (n × dim arrays) start it from an explicit state instead of the
/// scenario's initial condition (velocities zero when omitted). `controls`, a function
/// `f(t, q, p, neighbours)` returning u as an n × dim array, replaces the inputs of the
/// scenario's protocol; when it raises, `step` stops before the step it was called for and raises
/// its exception.
#[pyclass(name = "Simulation", module = "flocking", frozen)]
pub struct PySimulation {
    /// Locked only with the GIL released, so that a thread stepping it (which takes the GIL back
    /// between steps to check for Ctrl-C, and to call `controls`) and one reading it cannot wait
    /// on each other.
    sim: Mutex<DynSimulation>,
    /// The inputs' function, if given.
    controls: Option<PythonControls>,
}

/// The simulation of `scenario` from the given state after `steps` steps, its inputs from
/// `controls` when given.
fn simulation(
    scenario: &Scenario,
    positions: &[f64],
    velocities: &[f64],
    steps: u64,
    controls: Option<&PythonControls>,
) -> Result<DynSimulation, ScenarioError> {
    match controls {
        Some(controls) => {
            DynSimulation::from_state_with(scenario, positions, velocities, steps, controls)
        }
        None => DynSimulation::from_state(scenario, positions, velocities, steps),
    }
}

impl PySimulation {
    /// The simulation, for the calling thread alone (call with the GIL released).
    fn lock(&self) -> MutexGuard<'_, DynSimulation> {
        self.sim.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// `flocking.SimulationError` when Ctrl-C cut a step short after it had changed the state: the
    /// state is then between two steps, and stepping or measuring it would continue a run that
    /// never was.
    fn check_whole(&self, py: Python<'_>) -> PyResult<()> {
        let torn = py.detach(|| {
            let sim = self.lock();
            sim.is_torn().then(|| sim.steps())
        });
        match torn {
            None => Ok(()),
            Some(steps) => Err(exception(
                py,
                "SimulationError",
                (format!(
                    "Ctrl-C cut step {} short mid-way, inside a vehicle's inner steps or the conditions' stage: the state is between two steps and cannot be continued; build a new Simulation (from the scenario, or from a state you kept)",
                    steps + 1
                ),),
            )),
        }
    }
}

/// Why `Simulation.step` stopped before its k steps, but for Ctrl-C.
enum Stopped {
    /// `controls` raised (or returned a bad value).
    Controls(PyErr),
    /// The state blew up.
    Numerical(flocking::NumericalError),
}

/// The rows of an n × dim array, row by row.
/// The `name` array (`positions` or `velocities`) in row order, checked to be exactly
/// (`agents`, `dim`): a (dim, agents) array is refused, not read scrambled.
pub(crate) fn rows(
    array: &PyArrayLike2<'_, f64, AllowTypeChange>,
    name: &str,
    (agents, dim): (usize, usize),
) -> Result<Vec<f64>, ScenarioError> {
    let array = array.as_array();
    let shape = array.shape();
    if shape != [agents, dim] {
        let fix = if shape == [dim, agents] {
            "the array is transposed: pass its transpose (`array.T`), one row per agent"
        } else {
            "give one row of dim coordinates per agent"
        };
        return Err(ScenarioError::invalid(
            name,
            Shape(shape[0], shape[1]),
            format!(
                "the scenario has {agents} agents in {dim}D, so the shape must be ({agents}, {dim})"
            ),
            fix,
        ));
    }
    Ok(array.iter().copied().collect())
}

/// An array's shape, shown as Python shows it: `(2, 100)`.
struct Shape(usize, usize);

impl std::fmt::Debug for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "an array of shape ({}, {})", self.0, self.1)
    }
}

#[pymethods]
impl PySimulation {
    #[new]
    #[pyo3(signature = (scenario, positions = None, velocities = None, *, controls = None))]
    fn new(
        py: Python<'_>,
        scenario: &PyScenario,
        positions: Option<&Bound<'_, PyAny>>,
        velocities: Option<&Bound<'_, PyAny>>,
        controls: Option<Py<PyAny>>,
    ) -> PyResult<Self> {
        let mut arrays = [None, None];
        for (slot, (array, name)) in arrays
            .iter_mut()
            .zip([(positions, "positions"), (velocities, "velocities")])
        {
            if let Some(array) = array {
                refuse_complex(py, array, name)?;
                *slot = Some(array.extract::<PyArrayLike2<'_, f64, AllowTypeChange>>()?);
            }
        }
        let [positions, velocities] = arrays;
        let scenario = &scenario.inner;
        crate::errors::check_resources(py, scenario, &flocking::estimate::Outputs::NONE, None)?;
        let controls = controls.map(|f| PythonControls::new(f, scenario));
        let sim = match (&positions, &velocities, &controls) {
            (None, None, None) => DynSimulation::new(scenario),
            (None, None, Some(controls)) => DynSimulation::new_with(scenario, controls),
            _ => {
                let start = DynSimulation::new(scenario).map_err(|e| scenario_error(py, &e))?;
                let state = start.state();
                let size = (scenario.agents, scenario.dim);
                let q = positions.as_ref().map_or_else(
                    || Ok(state.positions.to_vec()),
                    |a| rows(a, "positions", size),
                );
                let p = velocities.as_ref().map_or_else(
                    || Ok(state.velocities.to_vec()),
                    |a| rows(a, "velocities", size),
                );
                q.and_then(|q| p.map(|p| (q, p)))
                    .and_then(|(q, p)| simulation(scenario, &q, &p, 0, controls.as_ref()))
            }
        }
        .map_err(|e| scenario_error(py, &e))?;
        sim.check_health().map_err(|e| numerical_error(py, &e))?;
        Ok(Self {
            sim: Mutex::new(sim),
            controls,
        })
    }

    /// Advances the state by `k` steps of h, checking after each step that it is finite and that
    /// no agent outran the interaction range (as a run does).
    ///
    /// Raises `flocking.NumericalError` at a blow-up (the state is then the bad one),
    /// `KeyboardInterrupt` on Ctrl-C after the current step (the state is that of the steps done),
    /// and the exception of `controls` (or `flocking.ControlsError` for a result of the wrong shape
    /// or not finite) before the step it was called for (the state is that of the steps done).
    /// A step still running half a second after Ctrl-C is cut short ([`flocking::interrupt`]):
    /// before it changed the state, the state is that of the steps done; inside a vehicle's inner
    /// steps or the conditions' stage, the simulation is torn between two steps, and every later
    /// `step` raises `flocking.SimulationError`.
    #[pyo3(signature = (k = 1))]
    fn step(&self, py: Python<'_>, k: u64) -> PyResult<()> {
        self.check_whole(py)?;
        let (outcome, raised) = watched(py, || {
            let mut sim = self.lock();
            for _ in 0..k {
                let before = sim.steps();
                sim.step();
                if let Some(failure) = self
                    .controls
                    .as_ref()
                    .and_then(PythonControls::take_failure)
                {
                    if let Some((q, p)) = failure.start {
                        let steps = sim.steps() - 1;
                        let back =
                            simulation(sim.scenario(), &q, &p, steps, self.controls.as_ref());
                        // the state the step started from was a valid state of this scenario
                        if let Ok(back) = back {
                            *sim = back;
                        }
                    }
                    return Err(Stopped::Controls(failure.error));
                }
                if sim.is_torn() || sim.steps() == before {
                    // cut short by the interrupt: torn, or not taken
                    return Ok(());
                }
                sim.check_health().map_err(Stopped::Numerical)?;
                if flocking::interrupt::requested() {
                    break;
                }
            }
            Ok(())
        });
        match outcome {
            Err(Stopped::Controls(error)) => return Err(error),
            Err(Stopped::Numerical(e)) => return Err(numerical_error(py, &e)),
            Ok(()) => {}
        }
        raised.map_or(Ok(()), Err)
    }

    /// Replaces the positions and/or velocities (n × dim arrays) at the current time, e.g. to
    /// perturb the flock; stepping goes on from the new state.
    ///
    /// Raises `flocking.ScenarioError` for arrays of another shape or values that are not finite.
    #[pyo3(signature = (positions = None, velocities = None))]
    fn set_state(
        &self,
        py: Python<'_>,
        positions: Option<PyArrayLike2<'_, f64, AllowTypeChange>>,
        velocities: Option<PyArrayLike2<'_, f64, AllowTypeChange>>,
    ) -> PyResult<()> {
        let size = {
            let sim = self.lock();
            (sim.scenario().agents, sim.scenario().dim)
        };
        let checked = |array: Option<&PyArrayLike2<'_, f64, AllowTypeChange>>, name| {
            array
                .map(|a| rows(a, name, size))
                .transpose()
                .map_err(|e| scenario_error(py, &e))
        };
        let q = checked(positions.as_ref(), "positions")?;
        let p = checked(velocities.as_ref(), "velocities")?;
        py.detach(|| {
            let mut sim = self.lock();
            let state = sim.state();
            let q = q.unwrap_or_else(|| state.positions.to_vec());
            let p = p.unwrap_or_else(|| state.velocities.to_vec());
            let changed = simulation(sim.scenario(), &q, &p, sim.steps(), self.controls.as_ref())?;
            *sim = changed;
            Ok(sim.check_health())
        })
        .map_err(|e| scenario_error(py, &e))?
        .map_err(|e| numerical_error(py, &e))
    }

    /// The positions, an n × dim array (a copy), agent i on row i.
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (rows, agents, dim) = py.detach(|| {
            let state = self.lock().state().into_owned();
            (state.positions.to_vec(), state.agents(), state.dim)
        });
        PyArray1::from_vec(py, rows).reshape([agents, dim])
    }

    /// The velocities, an n × dim array (a copy), agent i on row i.
    #[getter]
    fn p<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (rows, agents, dim) = py.detach(|| {
            let state = self.lock().state().into_owned();
            (state.velocities.to_vec(), state.agents(), state.dim)
        });
        PyArray1::from_vec(py, rows).reshape([agents, dim])
    }

    /// The time t = steps · h.
    #[getter]
    fn t(&self, py: Python<'_>) -> f64 {
        py.detach(|| self.lock().time())
    }

    /// The number of steps taken.
    #[getter]
    fn steps(&self, py: Python<'_>) -> u64 {
        py.detach(|| self.lock().steps())
    }

    /// The dimension, 2 or 3.
    #[getter]
    fn dim(&self, py: Python<'_>) -> usize {
        py.detach(|| self.lock().dim())
    }

    /// The number of agents n.
    #[getter]
    fn agents(&self, py: Python<'_>) -> usize {
        py.detach(|| self.lock().agents())
    }

    /// The scenario simulated.
    #[getter]
    fn scenario(&self, py: Python<'_>) -> PyScenario {
        let inner = py.detach(|| self.lock().scenario().clone());
        PyScenario { inner }
    }

    /// The flocking metrics of the current state (TAC 2006 Section VIII), named and ordered as the
    /// columns of `metrics.csv`: connectivity, giant_component, cohesion_radius,
    /// deviation_energy, velocity_mismatch, min_distance (floats), collisions (an int),
    /// polarisation, milling, nearest_neighbour_mean, nearest_neighbour_min (floats) and
    /// components (an int).
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let metrics = py.detach(|| self.lock().metrics());
        let dict = PyDict::new(py);
        for (name, value) in FlockMetrics::REAL_COLUMNS.into_iter().zip(metrics.reals()) {
            dict.set_item(name, value)?;
        }
        dict.set_item("collisions", metrics.collisions)?;
        for (name, value) in FlockMetrics::EXTRA_COLUMNS
            .into_iter()
            .zip(metrics.extras())
        {
            dict.set_item(name, value)?;
        }
        dict.set_item("components", metrics.components)?;
        Ok(dict)
    }

    /// The energy H of the current state: the Hamiltonian the algorithm's theorem makes
    /// non-increasing (the `energy` column of `metrics.csv`).
    fn energy(&self, py: Python<'_>) -> f64 {
        py.detach(|| self.lock().energy())
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        py.detach(|| {
            let sim = self.lock();
            format!(
                "Simulation(scenario={:?}, dim={}, agents={}, steps={}, t={}{})",
                sim.scenario().name,
                sim.dim(),
                sim.agents(),
                sim.steps(),
                sim.time(),
                if self.controls.is_some() {
                    ", controls=python"
                } else {
                    ""
                }
            )
        })
    }
}
