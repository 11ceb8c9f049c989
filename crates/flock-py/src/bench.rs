//! `flocking.bench`: the benchmark engine of `flocking bench` ([`flocking::bench`],
//! [`flocking::workload`]) with the same report, its figures as attributes.

use flocking::bench::{BenchAlgorithm, BenchConditions, BenchConfig, BenchReport, parse_delayed};
use flocking::estimate::check_threads;
use flocking::workload::{Workload, WorkloadReport, time_seeds};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::scenario_error;

/// The report of `flocking.bench` on the α-lattice: `str()` prints what `flocking bench` prints.
#[pyclass(name = "BenchReport", module = "flocking", frozen)]
pub struct PyBenchReport(BenchReport);

#[pymethods]
impl PyBenchReport {
    /// The number of agents.
    #[getter]
    fn n(&self) -> usize {
        self.0.config.n
    }

    /// The dimension, 2 or 3.
    #[getter]
    fn dim(&self) -> usize {
        self.0.config.dim
    }

    /// Timed steps.
    #[getter]
    fn steps(&self) -> u64 {
        self.0.config.steps
    }

    /// Worker threads that ran the steps.
    #[getter]
    fn threads(&self) -> usize {
        self.0.threads
    }

    /// Agent-steps per second over the timed steps (metrics every 10 steps included).
    #[getter]
    fn agent_steps_per_second(&self) -> f64 {
        self.0.agent_steps_per_second()
    }

    /// Nanoseconds per agent-step.
    #[getter]
    fn ns_per_agent_step(&self) -> f64 {
        self.0.ns_per_agent_step()
    }

    /// Milliseconds per timed step.
    #[getter]
    fn ms_per_step(&self) -> f64 {
        self.0.ms_per_step()
    }

    /// Milliseconds per plain (unrecorded) step.
    #[getter]
    fn ms_per_plain_step(&self) -> f64 {
        self.0.ms_per_plain_step()
    }

    /// Milliseconds per recorded step (metrics and energy included); None with fewer than 10
    /// timed steps.
    #[getter]
    fn ms_per_recorded_step(&self) -> Option<f64> {
        self.0.ms_per_recorded_step()
    }

    /// Peak resident memory of the process in bytes (`VmHWM`, Linux only; the interpreter's own
    /// memory included); None where the platform does not report it.
    #[getter]
    fn peak_memory(&self) -> Option<u64> {
        self.0.peak_memory
    }

    /// Peak memory per agent in bytes.
    #[getter]
    fn bytes_per_agent(&self) -> Option<f64> {
        self.0.bytes_per_agent()
    }

    /// The bytes per agent of the conditions' state (0 when ideal).
    #[getter]
    fn conditions_bytes_per_agent(&self) -> usize {
        self.0.conditions_bytes_per_agent
    }

    /// Mean number of neighbours per agent at the end.
    #[getter]
    fn mean_neighbours(&self) -> f64 {
        self.0.mean_neighbours
    }

    /// Seconds to build the scenario and its first net.
    #[getter]
    fn setup_seconds(&self) -> f64 {
        self.0.setup.as_secs_f64()
    }

    /// Seconds of the timed steps.
    #[getter]
    fn elapsed_seconds(&self) -> f64 {
        self.0.elapsed.as_secs_f64()
    }

    /// The connectivity C at the end.
    #[getter]
    fn connectivity(&self) -> f64 {
        self.0.metrics.connectivity
    }

    /// The least distance between two agents at the end.
    #[getter]
    fn min_distance(&self) -> f64 {
        self.0.metrics.min_distance
    }

    fn __str__(&self) -> String {
        self.0.to_string()
    }

    fn __repr__(&self) -> String {
        let c = &self.0.config;
        format!(
            "<BenchReport {}, {}D, n = {}, {:.4e} agent-steps/s on {} thread(s)>",
            c.algorithm,
            c.dim,
            c.n,
            self.0.agent_steps_per_second(),
            self.0.threads
        )
    }
}

/// The report of `flocking.bench(workload=…)`: `str()` prints what `flocking bench --workload`
/// prints.
#[pyclass(name = "WorkloadReport", module = "flocking", frozen)]
pub struct PyWorkloadReport(WorkloadReport);

#[pymethods]
impl PyWorkloadReport {
    /// The number of birds.
    #[getter]
    fn n(&self) -> usize {
        self.0.scenario.agents
    }

    /// Seconds of the scenario's steps for each seed 0, 1, …
    #[getter]
    fn times(&self) -> Vec<f64> {
        self.0
            .times
            .iter()
            .map(std::time::Duration::as_secs_f64)
            .collect()
    }

    /// The median of `times` (s).
    #[getter]
    fn median_seconds(&self) -> f64 {
        self.0.median().as_secs_f64()
    }

    /// Agent-steps per second at the median.
    #[getter]
    fn agent_steps_per_second(&self) -> f64 {
        self.0.agent_steps_per_second()
    }

    /// Worker threads.
    #[getter]
    fn threads(&self) -> usize {
        self.0.threads
    }

    fn __str__(&self) -> String {
        self.0.to_string()
    }

    fn __repr__(&self) -> String {
        format!("<WorkloadReport {}>", self.0)
    }
}

/// Whatever `f` returns, run on a pool of `threads` workers (None: the global pool, all cores).
fn on_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    let Some(threads) = threads else {
        return Ok(f());
    };
    let threads = check_threads(threads)
        .map_err(|e| PyValueError::new_err(format!("threads={threads}: {e}")))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyValueError::new_err(format!("cannot start {threads} threads: {e}")))?;
    Ok(pool.install(f))
}

/// A keyword's text parsed by `parse`, or a `ValueError` naming the keyword as Python writes it
/// (`vehicle='boat'`).
fn keyword<T>(name: &str, text: &str, parse: impl Fn(&str) -> Result<T, String>) -> PyResult<T> {
    parse(text).map_err(|e| PyValueError::new_err(format!("{name}='{text}': {e}")))
}

/// Times the simulation loop as `flocking bench` does, with the same flags as keywords, and
/// returns its report (`BenchReport`, or `WorkloadReport` with `workload=`). The GIL is released
/// while it runs.
#[pyfunction]
#[pyo3(signature = (
    n = 100_000, dim = 2, steps = 20, *, algorithm = "2".to_owned(), threads = None, warmup = 3,
    shuffled = false, delay = None, delayed = None, loss = None, sensing_noise = None,
    control_rate = None, max_acceleration = None, vehicle = None, workload = None, seeds = 10,
    scale_to = None
))]
#[allow(clippy::too_many_arguments)]
pub fn bench(
    py: Python<'_>,
    n: usize,
    dim: usize,
    steps: u64,
    algorithm: String,
    threads: Option<usize>,
    warmup: u64,
    shuffled: bool,
    delay: Option<f64>,
    delayed: Option<String>,
    loss: Option<f64>,
    sensing_noise: Option<(f64, f64)>,
    control_rate: Option<f64>,
    max_acceleration: Option<f64>,
    vehicle: Option<String>,
    workload: Option<String>,
    seeds: u64,
    scale_to: Option<usize>,
) -> PyResult<Py<PyAny>> {
    if let Some(name) = workload {
        let workload = keyword("workload", &name, str::parse::<Workload>)?;
        let report = py.detach(|| {
            on_threads(threads, || {
                let scenario = match scale_to {
                    None => Ok(workload.scenario()),
                    Some(n) => workload.scaled(n),
                };
                scenario.and_then(|s| time_seeds(&s, seeds.max(1)))
            })
        })?;
        let report = report.map_err(|e| scenario_error(py, &e))?;
        return Ok(Py::new(py, PyWorkloadReport(report))?.into_any());
    }
    let config = BenchConfig {
        n,
        dim,
        steps,
        warmup,
        algorithm: keyword("algorithm", &algorithm, str::parse::<BenchAlgorithm>)?,
        shuffled,
        conditions: BenchConditions {
            delay,
            delayed: delayed
                .map(|d| keyword("delayed", &d, parse_delayed))
                .transpose()?,
            loss,
            sensing_noise,
            control_rate,
            max_acceleration,
        },
        vehicle: vehicle
            .map(|v| keyword("vehicle", &v, str::parse))
            .transpose()?,
    };
    let report = py.detach(|| on_threads(threads, || flocking::bench::bench(&config)))?;
    let report = report.map_err(PyValueError::new_err)?;
    Ok(Py::new(py, PyBenchReport(report))?.into_any())
}
