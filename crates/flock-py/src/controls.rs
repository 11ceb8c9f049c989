//! `controls=`: the inputs u_i computed by a Python function `f(t, q, p, neighbours)` in place of
//! the scenario protocol's ([`flocking::protocols::Protocol::controls`]), everything else kept:
//! the proximity net built by Rust with the scenario protocol's interaction range, the obstacles
//! drawn, the metrics, the energy and the diagnostics of the scenario's algorithm, checkpoints,
//! run directories and sweeps.
//!
//! - [`PythonControls`]: the [`MapProtocol`] that wraps a scenario's protocol around `f`.
//! - [`PyNeighbours`]: the net handed to `f` — CSR arrays `indptr`, `indices`, `distances`.
//! - [`Failure`]: an exception raised by `f` (or a result of the wrong shape, or not finite), with
//!   the state the failed step started from, so that a run stops there as after Ctrl-C.
//! - [`bump`]: `flocking.bump`, the built-in ρ_h for an `f` written in numpy.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use flocking::graph::Graph;
use flocking::graph::ProximityNet;
use flocking::math::{Bump, Vector};
use flocking::obstacles::Space;
use flocking::protocols::{DynProtocol, Integrator, Protocol, Swarm};
use flocking::{MapProtocol, Scenario};
use numpy::{AllowTypeChange, PyArray1, PyArray2, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::inputs::{Failure, checked_inputs, lock};
use crate::local::{LocalPython, PyLocal};
use flocking::controller::WithController;

/// The inputs of a scenario's runs computed by the Python function `f(t, q, p, neighbours)`: the
/// [`MapProtocol`] whose protocols call `f` for u_i and take everything else from the scenario's
/// protocol.
///
/// When `f` fails, the protocol keeps the [`Failure`] ([`PythonControls::take_failure`]) and gives
/// every agent a NaN input, so that the step fails its health check: a run stops there as at a
/// blow-up, before recording that step, and `f` is not called again.
#[derive(Clone, Debug)]
pub struct PythonControls {
    f: Arc<Py<PyAny>>,
    /// Evaluations of u per step: 1 (symplectic Euler) or 4 (Runge–Kutta).
    evaluations: u64,
    failure: Arc<Mutex<Option<Failure>>>,
    /// The local controller, when `f` is a `flocking.Local`.
    local: Option<Arc<LocalPython>>,
}

impl PythonControls {
    /// The controls `f` for runs of `scenario` (its integrator tells which evaluations start a
    /// step): a function of the whole state, or a local controller `flocking.Local(g)`.
    #[must_use]
    pub fn new(f: Py<PyAny>, scenario: &Scenario) -> Self {
        let evaluations = match scenario.integrator {
            Integrator::SymplecticEuler => 1,
            Integrator::Rk4 => 4,
        };
        let failure = Arc::new(Mutex::new(None));
        let local = Python::attach(|py| {
            f.bind(py).cast::<PyLocal>().ok().map(|local| {
                Arc::new(LocalPython {
                    f: local.get().f.clone_ref(py),
                    failure: Arc::clone(&failure),
                })
            })
        });
        Self {
            f: Arc::new(f),
            evaluations,
            failure,
            local,
        }
    }

    /// The failure of `f` since the last call, if any (the protocols call `f` again afterwards).
    #[must_use]
    pub fn take_failure(&self) -> Option<Failure> {
        lock(&self.failure).take()
    }
}

impl MapProtocol for PythonControls {
    fn map<V: Space + bytemuck::Pod>(&self, protocol: DynProtocol<V>) -> DynProtocol<V> {
        if let Some(local) = &self.local {
            return WithController(Arc::clone(local)).map(protocol);
        }
        Box::new(Controlled {
            inner: protocol,
            f: Arc::clone(&self.f),
            evaluations: self.evaluations,
            calls: AtomicU64::new(0),
            step_start: Mutex::new(None),
            failure: Arc::clone(&self.failure),
        })
    }
}

/// A scenario's protocol whose inputs come from `f`.
struct Controlled<V> {
    inner: DynProtocol<V>,
    f: Arc<Py<PyAny>>,
    evaluations: u64,
    /// The evaluations of u so far: those at multiples of `evaluations` start a step.
    calls: AtomicU64,
    /// With Runge–Kutta, the state the current step started from (its later stages see others).
    step_start: Mutex<Option<(Vec<f64>, Vec<f64>)>>,
    failure: Arc<Mutex<Option<Failure>>>,
}

/// The coordinates of vectors, `V::DIM` per vector.
fn rows<V: bytemuck::Pod>(vectors: &[V]) -> Vec<f64> {
    bytemuck::cast_slice(vectors).to_vec()
}

impl<V: Space + bytemuck::Pod> Controlled<V> {
    /// Calls `f(t, q, p, neighbours)` and writes its result, validated, into `inputs`.
    fn call(
        &self,
        py: Python<'_>,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
        inputs: &mut [V],
    ) -> PyResult<()> {
        let (n, dim) = (swarm.len(), V::DIM);
        let q = PyArray1::from_vec(py, rows(&swarm.positions)).reshape([n, dim])?;
        let p = PyArray1::from_vec(py, rows(&swarm.velocities)).reshape([n, dim])?;
        let neighbours = PyNeighbours::of(py, net)?;
        let u = self.f.bind(py).call1((t, q, p, neighbours))?;
        checked_inputs(py, &u, (n, dim), t, bytemuck::cast_slice_mut(inputs))
    }
}

impl<V: Space + bytemuck::Pod> Protocol<V> for Controlled<V> {
    fn interaction_range(&self) -> f64 {
        self.inner.interaction_range()
    }

    /// u_i from `f`, agents in original order (the protocol does not follow the numbering, so the
    /// simulation keeps them so); NaN for every agent once `f` has failed.
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let call = self.calls.fetch_add(1, Ordering::Relaxed);
        let starts_step = call.is_multiple_of(self.evaluations);
        if lock(&self.failure).is_some() {
            inputs_nan(inputs);
            return;
        }
        let state = || (rows(&swarm.positions), rows(&swarm.velocities));
        if starts_step && self.evaluations > 1 {
            *lock(&self.step_start) = Some(state());
        }
        let called = Python::attach(|py| self.call(py, t, swarm, net, inputs));
        if let Err(error) = called {
            let start = if starts_step {
                Some(state())
            } else {
                lock(&self.step_start).take()
            };
            *lock(&self.failure) = Some(Failure { error, start });
            inputs_nan(inputs);
        }
    }

    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.inner.energy(t, swarm, net)
    }

    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        self.inner.diagnostics(t, swarm, net)
    }

    /// `f` is given the distances.
    fn uses_net_distances(&self) -> bool {
        true
    }

    /// `f` sees the agents in original order.
    fn follows_numbering(&self) -> bool {
        false
    }

    fn interaction_graph(&self) -> Option<&Graph> {
        self.inner.interaction_graph()
    }
}

/// NaN for every input.
fn inputs_nan<V: Vector>(inputs: &mut [V]) {
    inputs.fill(V::from_fn(|_| f64::NAN));
}

/// The proximity net N_i = { j ≠ i : ‖q_j − q_i‖ < r } handed to a `controls` function, in
/// compressed sparse rows: agent i's neighbours are `indices[indptr[i]:indptr[i + 1]]` (in
/// ascending order) at distances `distances[indptr[i]:indptr[i + 1]]`; every edge appears in
/// both directions. `scipy.sparse.csr_matrix((distances, indices, indptr))` is its matrix of
/// distances.
#[pyclass(name = "Neighbours", module = "flocking", frozen)]
pub struct PyNeighbours {
    indptr: Py<PyArray1<i64>>,
    indices: Py<PyArray1<i64>>,
    distances: Py<PyArray1<f64>>,
    /// The number of agents n.
    agents: usize,
}

/// An index as numpy's int64 (a net's sizes are far below 2⁶³).
fn int64(x: usize) -> i64 {
    i64::try_from(x).unwrap_or(i64::MAX)
}

impl PyNeighbours {
    fn of(py: Python<'_>, net: &ProximityNet) -> PyResult<Self> {
        let graph = net.graph();
        Ok(Self {
            indptr: PyArray1::from_iter(py, graph.offsets().iter().map(|&k| int64(k))).unbind(),
            indices: PyArray1::from_iter(
                py,
                graph.neighbour_indices().iter().map(|&j| i64::from(j)),
            )
            .unbind(),
            distances: PyArray1::from_slice(py, net.distances()).unbind(),
            agents: graph.len(),
        })
    }
}

#[pymethods]
impl PyNeighbours {
    /// Where each agent's neighbours start in `indices`: n + 1 int64, `indptr[0] == 0`.
    #[getter]
    fn indptr(&self, py: Python<'_>) -> Py<PyArray1<i64>> {
        self.indptr.clone_ref(py)
    }

    /// The neighbours j of every agent i in turn, ascending for each i (int64).
    #[getter]
    fn indices(&self, py: Python<'_>) -> Py<PyArray1<i64>> {
        self.indices.clone_ref(py)
    }

    /// ‖q_j − q_i‖ for each entry of `indices` (float64).
    #[getter]
    fn distances(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        self.distances.clone_ref(py)
    }

    /// The directed edges (i, j), one row each in the order of `indices`: an (m, 2) int64 array.
    fn pairs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let indptr = self.indptr.bind(py).readonly();
        let indices = self.indices.bind(py).readonly();
        let (indptr, indices) = (indptr.as_slice()?, indices.as_slice()?);
        let mut pairs = Vec::with_capacity(2 * indices.len());
        for (i, bounds) in indptr.windows(2).enumerate() {
            // `indptr` and `indices` are writable numpy arrays: bounds a caller changed are an
            // error, never a panic.
            let neighbours = usize::try_from(bounds[0])
                .ok()
                .zip(usize::try_from(bounds[1]).ok())
                .and_then(|(from, to)| indices.get(from..to))
                .ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "indptr[{i}:{}] = {bounds:?} is not a range of the {} indices; the net's \
                         arrays were changed",
                        i + 2,
                        indices.len()
                    ))
                })?;
            for &j in neighbours {
                pairs.extend([int64(i), j]);
            }
        }
        PyArray1::from_vec(py, pairs).reshape([indices.len(), 2])
    }

    /// The number of agents n.
    fn __len__(&self) -> usize {
        self.agents
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let edges = self.indices.bind(py).len()?;
        Ok(format!(
            "Neighbours(n={}, directed_edges={edges})",
            self.agents
        ))
    }
}

/// `flocking.bump(x, h)`: ρ_h(x) of TAC 2006 eq. 10 — 1 on [0, h), ½(1 + cos(π(x − h)/(1 − h)))
/// on [h, 1], 0 elsewhere — for every element of `x` (any shape, as float64), with the bits of
/// the built-in protocols ([`Bump::values`], four elements at a time: each lane is its element
/// alone), so that an `f` written in numpy can reproduce a built-in algorithm bit for bit.
///
/// # Errors
/// `ValueError` naming `h` when h is not in (0, 1), or `x` not an array of floats.
#[pyfunction]
pub fn bump<'py>(
    py: Python<'py>,
    x: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    h: f64,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if !(h > 0.0 && h < 1.0) {
        return Err(PyValueError::new_err(format!(
            "h = {h}: the flat part [0, h) of the bump must end inside (0, 1); use 0 < h < 1 \
             (TAC 2006 uses h = 0.2 for α-agents, 0.9 for β-agents)"
        )));
    }
    let rho = Bump::tac(h);
    let x = x.as_array();
    let elements: Vec<f64> = x.iter().copied().collect();
    let mut out = Vec::with_capacity(elements.len());
    for run in elements.chunks(4) {
        let mut lanes = [0.0; 4];
        lanes[..run.len()].copy_from_slice(run);
        out.extend_from_slice(&rho.values(lanes)[..run.len()]);
    }
    PyArray1::from_vec(py, out).reshape(x.shape())
}
