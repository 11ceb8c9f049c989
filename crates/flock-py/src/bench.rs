//! `flocking.bench`: the benchmark engine of `flocking bench` ([`flocking::bench`],
//! [`flocking::workload`]) with the same report, its figures as attributes.

use flocking::bench::{
    BenchAlgorithm, BenchConditions, BenchConfig, BenchError, BenchReport, parse_delayed,
};
use flocking::estimate::check_threads;
use flocking::workload::{Workload, WorkloadConfig, WorkloadReport, time_seeds};
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyValueError};
use pyo3::prelude::*;

use crate::interrupt::watched;

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

    /// Seconds of building each seed's model (its random start and its net), in the order of
    /// `times`: the frameworks' own benchmarks time it with the steps.
    #[getter]
    fn build_times(&self) -> Vec<f64> {
        self.0
            .built
            .iter()
            .map(std::time::Duration::as_secs_f64)
            .collect()
    }

    /// The median over the seeds of building the model and taking its steps (s), as the
    /// frameworks time them.
    #[getter]
    fn median_seconds_with_building(&self) -> f64 {
        self.0.median_with_building().as_secs_f64()
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

/// A benchmark's error as Python raises it: `ValueError` naming the keyword, `MemoryError`, or the
/// exception a signal handler raised (`KeyboardInterrupt`).
fn bench_error(error: BenchError, raised: Option<PyErr>) -> PyErr {
    let message = error.with_flag(|flag, value| format!("{flag}={value}"));
    match error {
        BenchError::Invalid { .. } => PyValueError::new_err(message),
        BenchError::Memory(_) => PyMemoryError::new_err(message),
        BenchError::Interrupted => {
            raised.unwrap_or_else(|| PyKeyboardInterrupt::new_err("the benchmark was interrupted"))
        }
    }
}

/// The defaults of the α-lattice's keywords, as `flocking bench`'s flags have them.
const DEFAULTS: BenchConfig = BenchConfig {
    n: 100_000,
    dim: 2,
    steps: 20,
    warmup: 3,
    algorithm: BenchAlgorithm::Algorithm2,
    shuffled: false,
    conditions: BenchConditions {
        delay: None,
        delayed: None,
        loss: None,
        sensing_noise: None,
        control_rate: None,
        max_acceleration: None,
    },
    vehicle: None,
};

/// Times the simulation loop as `flocking bench` does, with the same flags as keywords, and
/// returns its report (`BenchReport`, or `WorkloadReport` with `workload=`): its estimate first
/// checked against this machine's memory (`MemoryError` when it does not fit), the GIL released
/// while it runs and Ctrl-C raising `KeyboardInterrupt` within a second. The keywords of the
/// α-lattice are refused with `workload=`, and `seeds` and `scale_to` without it, naming them.
#[pyfunction]
#[pyo3(signature = (
    n = None, dim = None, steps = None, *, algorithm = None, threads = None, warmup = None,
    shuffled = None, delay = None, delayed = None, loss = None, sensing_noise = None,
    control_rate = None, max_acceleration = None, vehicle = None, workload = None, seeds = None,
    scale_to = None
))]
#[allow(clippy::too_many_arguments)]
pub fn bench(
    py: Python<'_>,
    n: Option<usize>,
    dim: Option<usize>,
    steps: Option<u64>,
    algorithm: Option<String>,
    threads: Option<usize>,
    warmup: Option<u64>,
    shuffled: Option<bool>,
    delay: Option<f64>,
    delayed: Option<String>,
    loss: Option<f64>,
    sensing_noise: Option<(f64, f64)>,
    control_rate: Option<f64>,
    max_acceleration: Option<f64>,
    vehicle: Option<String>,
    workload: Option<String>,
    seeds: Option<u64>,
    scale_to: Option<usize>,
) -> PyResult<Py<PyAny>> {
    let lattice = [
        ("n", n.is_some()),
        ("dim", dim.is_some()),
        ("steps", steps.is_some()),
        ("algorithm", algorithm.is_some()),
        ("warmup", warmup.is_some()),
        ("shuffled", shuffled.is_some()),
        ("delay", delay.is_some()),
        ("delayed", delayed.is_some()),
        ("loss", loss.is_some()),
        ("sensing_noise", sensing_noise.is_some()),
        ("control_rate", control_rate.is_some()),
        ("max_acceleration", max_acceleration.is_some()),
        ("vehicle", vehicle.is_some()),
    ];
    fn given(keywords: &[(&'static str, bool)]) -> Vec<&'static str> {
        keywords
            .iter()
            .filter(|(_, given)| *given)
            .map(|(name, _)| *name)
            .collect()
    }
    if let Some(name) = workload {
        let workload = keyword("workload", &name, str::parse::<Workload>)?;
        let refused = given(&lattice);
        if !refused.is_empty() {
            return Err(PyValueError::new_err(format!(
                "{} {} not apply to workload='{name}', which sets its own agents, steps and box: leave them out, or scale it with scale_to",
                refused.join(", "),
                if refused.len() == 1 { "does" } else { "do" }
            )));
        }
        let config = WorkloadConfig {
            workload,
            seeds: seeds.unwrap_or(10),
            scale_to,
        };
        let estimate = config.estimate().map_err(|e| bench_error(e, None))?;
        crate::errors::check_estimate(py, Some(estimate), None, None)?;
        let (report, raised) = watched(py, || {
            on_threads(threads, || {
                config.scenario().and_then(|s| time_seeds(&s, config.seeds))
            })
        });
        let report = report?.map_err(|e| bench_error(e, raised))?;
        return Ok(Py::new(py, PyWorkloadReport(report))?.into_any());
    }
    let refused = given(&[("seeds", seeds.is_some()), ("scale_to", scale_to.is_some())]);
    if !refused.is_empty() {
        return Err(PyValueError::new_err(format!(
            "{} {} only with workload=: give a workload, or leave {} out",
            refused.join(", "),
            if refused.len() == 1 {
                "applies"
            } else {
                "apply"
            },
            if refused.len() == 1 { "it" } else { "them" }
        )));
    }
    let config = BenchConfig {
        n: n.unwrap_or(DEFAULTS.n),
        dim: dim.unwrap_or(DEFAULTS.dim),
        steps: steps.unwrap_or(DEFAULTS.steps),
        warmup: warmup.unwrap_or(DEFAULTS.warmup),
        algorithm: algorithm
            .map(|a| keyword("algorithm", &a, str::parse::<BenchAlgorithm>))
            .transpose()?
            .unwrap_or(DEFAULTS.algorithm),
        shuffled: shuffled.unwrap_or(DEFAULTS.shuffled),
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
    config.check().map_err(|e| bench_error(e, None))?;
    crate::errors::check_estimate(py, Some(config.estimate()), None, None)?;
    let (report, raised) = watched(py, || {
        on_threads(threads, || flocking::bench::bench(&config))
    });
    let report = report?.map_err(|e| bench_error(e, raised))?;
    Ok(Py::new(py, PyBenchReport(report))?.into_any())
}
