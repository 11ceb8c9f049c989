//! `controls=flocking.Local(f)`: a *local* controller written in Python, `f(t, perception)`,
//! given what every agent perceives after the sense and communicate stages ([`PyPerception`]: the
//! delay, loss, range and noise of the scenario applied) and returning u_i of every agent. It
//! runs through the loop as a built-in protocol's local form does ([`flocking::controller`]):
//! under every condition and vehicle, in runs, sweeps, checkpoints and resumes.

use std::sync::{Arc, Mutex};

use flocking::controller::Controller;
use flocking::perception::Perception;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::inputs::{Failure, checked_inputs, lock};

/// `flocking.Local(f)`: marks `f(t, perception)` as a local controller for `controls=` — called
/// once per control update with every agent's [`PyPerception`], it returns the inputs u as an
/// n × dim array (accelerations; the next velocities for a model whose input is a velocity).
#[pyclass(name = "Local", module = "flocking", frozen)]
pub struct PyLocal {
    /// The function.
    pub(crate) f: Py<PyAny>,
}

#[pymethods]
impl PyLocal {
    #[new]
    fn new(f: Py<PyAny>) -> Self {
        Self { f }
    }

    /// The function `f(t, perception)`.
    #[getter]
    fn function(&self, py: Python<'_>) -> Py<PyAny> {
        self.f.clone_ref(py)
    }

    /// `f(t, perception)`.
    fn __call__(&self, py: Python<'_>, t: f64, perception: Py<PyAny>) -> PyResult<Py<PyAny>> {
        self.f.call1(py, (t, perception))
    }

    /// Pickled as `Local(f)` (sweeps send it to their workers).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let class = py.get_type::<Self>();
        PyTuple::new(
            py,
            [
                class.into_any(),
                PyTuple::new(py, [slf.get().f.clone_ref(py)])?.into_any(),
            ],
        )
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!("Local({})", self.f.bind(py).repr()?))
    }
}

/// The [`Controller`] that calls a Python `f(t, perception)`: when it fails, the failure is kept
/// and every input is NaN, so that the step fails its health check and the run stops before
/// recording it (resumable from its last checkpoint).
#[derive(Debug)]
pub struct LocalPython {
    pub(crate) f: Py<PyAny>,
    pub(crate) failure: Arc<Mutex<Option<Failure>>>,
}

impl Controller for LocalPython {
    fn inputs(&self, perception: &Perception, out: &mut [f64]) {
        if lock(&self.failure).is_some() {
            out.fill(f64::NAN);
            return;
        }
        let called = Python::attach(|py| {
            let arg = Py::new(py, PyPerception::of(py, perception)?)?;
            let u = self.f.bind(py).call1((perception.t, arg))?;
            let n = perception.agents();
            checked_inputs(py, &u, (n, perception.dim), perception.t, out)
        });
        if let Err(error) = called {
            *lock(&self.failure) = Some(Failure { error, start: None });
            out.fill(f64::NAN);
        }
    }
}

/// What every agent perceives at a control update, as numpy arrays (agents in original order):
/// agent i measures itself at `positions[i]`, `velocities[i]`; it heard the agents
/// `neighbours[indptr[i]:indptr[i + 1]]` at `relative_positions` q_j − q_i and
/// `relative_velocities` p_j − p_i of the same rows (`heard_by[k]` is the agent that heard
/// entry k); the γ-agent is at `gamma_position`, `gamma_velocity` (None without one); agent i's
/// β-agents are rows `beta_indptr[i]:beta_indptr[i + 1]` of `beta_relative_positions` and
/// `beta_relative_velocities`.
#[pyclass(name = "Perception", module = "flocking", frozen, get_all)]
pub struct PyPerception {
    /// The time t.
    t: f64,
    /// n × dim.
    positions: Py<PyAny>,
    /// n × dim.
    velocities: Py<PyAny>,
    /// n + 1 int64.
    indptr: Py<PyAny>,
    /// m int64, original indices.
    neighbours: Py<PyAny>,
    /// m int64: the agent that heard each entry.
    heard_by: Py<PyAny>,
    /// m × dim.
    relative_positions: Py<PyAny>,
    /// m × dim.
    relative_velocities: Py<PyAny>,
    /// dim, or None.
    gamma_position: Option<Py<PyAny>>,
    /// dim, or None.
    gamma_velocity: Option<Py<PyAny>>,
    /// n + 1 int64.
    beta_indptr: Py<PyAny>,
    /// rows of dim.
    beta_relative_positions: Py<PyAny>,
    /// rows of dim.
    beta_relative_velocities: Py<PyAny>,
}

/// `values` as an array of rows of `dim`.
fn rows_of(py: Python<'_>, values: &[f64], dim: usize) -> PyResult<Py<PyAny>> {
    Ok(PyArray1::from_slice(py, values)
        .reshape([values.len() / dim.max(1), dim])?
        .into_any()
        .unbind())
}

/// `values` as an int64 array.
fn int64s(py: Python<'_>, values: impl IntoIterator<Item = usize>) -> Py<PyAny> {
    PyArray1::from_iter(py, values.into_iter().map(|x| x as i64))
        .into_any()
        .unbind()
}

impl PyPerception {
    pub(crate) fn of(py: Python<'_>, p: &Perception) -> PyResult<Self> {
        let dim = p.dim;
        let heard_by = p
            .indptr
            .windows(2)
            .enumerate()
            .flat_map(|(i, w)| std::iter::repeat_n(i, w[1] - w[0]));
        let vector = |v: &[f64]| PyArray1::from_slice(py, v).into_any().unbind();
        Ok(Self {
            t: p.t,
            positions: rows_of(py, &p.positions, dim)?,
            velocities: rows_of(py, &p.velocities, dim)?,
            indptr: int64s(py, p.indptr.iter().copied()),
            neighbours: int64s(py, p.neighbours.iter().map(|&j| j as usize)),
            heard_by: int64s(py, heard_by),
            relative_positions: rows_of(py, &p.relative_positions, dim)?,
            relative_velocities: rows_of(py, &p.relative_velocities, dim)?,
            gamma_position: p.gamma.as_ref().map(|(q, _)| vector(q)),
            gamma_velocity: p.gamma.as_ref().map(|(_, v)| vector(v)),
            beta_indptr: int64s(py, p.beta_indptr.iter().copied()),
            beta_relative_positions: rows_of(py, &p.beta_relative_positions, dim)?,
            beta_relative_velocities: rows_of(py, &p.beta_relative_velocities, dim)?,
        })
    }
}

#[pymethods]
impl PyPerception {
    /// The number of agents n.
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.indptr.bind(py).len()?.saturating_sub(1))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "Perception(t={}, n={}, heard={})",
            self.t,
            self.__len__(py)?,
            self.neighbours.bind(py).len()?
        ))
    }
}
