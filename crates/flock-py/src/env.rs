//! `flocking._VecEnv`: the engine of `flocking.env` ([`flocking::env::VecEnv`]) — `num_envs`
//! flocks stepped in Rust by one call, the GIL released, their observations, rewards and flags
//! written into arrays allocated once and returned as views (each call overwrites them).

use std::sync::{Mutex, MutexGuard, PoisonError};

use flocking::env::{EnvOptions, Reward, VecEnv};
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray3, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::scenario_error;
use crate::scenario::PyScenario;

/// `num_envs` flocks of a scenario stepped together: the engine of `flocking.env`'s classes.
#[pyclass(name = "_VecEnv", module = "flocking")]
pub struct PyVecEnv {
    /// Locked by each call (Python objects are shared between threads).
    env: Mutex<VecEnv>,
    /// (num_envs, n, size) observations, (num_envs, n) rewards, written by `reset` and `step`.
    obs: Py<PyArray3<f64>>,
    rewards: Py<PyArray2<f64>>,
}

/// The shape (num_envs, n, dim) of a batch of actions.
fn action_shape(env: &VecEnv) -> [usize; 3] {
    [env.num_envs(), env.agents(), env.scenario().dim]
}

impl PyVecEnv {
    /// The environments, for this call alone.
    fn lock(&self) -> MutexGuard<'_, VecEnv> {
        self.env.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[pymethods]
impl PyVecEnv {
    #[new]
    #[pyo3(signature = (scenario, num_envs, seed, neighbours = 6, reward = None))]
    fn new(
        py: Python<'_>,
        scenario: &PyScenario,
        num_envs: usize,
        seed: u64,
        neighbours: usize,
        reward: Option<[f64; 4]>,
    ) -> PyResult<Self> {
        let defaults = Reward::default();
        let [deviation, mismatch, collision, gamma] = reward.unwrap_or([
            defaults.deviation,
            defaults.mismatch,
            defaults.collision,
            defaults.gamma,
        ]);
        let options = EnvOptions {
            neighbours,
            reward: Reward {
                deviation,
                mismatch,
                collision,
                gamma,
            },
        };
        let scenario = &scenario.inner;
        let env = py
            .detach(|| VecEnv::new(scenario, num_envs, seed, options))
            .map_err(|e| scenario_error(py, &e))?;
        let (n, size) = (env.agents(), env.layout().size());
        Ok(Self {
            obs: PyArray3::zeros(py, [num_envs, n, size], false).unbind(),
            rewards: PyArray2::zeros(py, [num_envs, n], false).unbind(),
            env: Mutex::new(env),
        })
    }

    /// The layout of an agent's observation: a dict of field → (start, length).
    fn layout<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let fields = PyDict::new(py);
        let mut start = 0;
        for (name, length) in self.lock().layout().fields() {
            fields.set_item(name, (start, length))?;
            start += length;
        }
        Ok(fields)
    }

    /// Restarts every environment (environment k seeded `seed + k`, or with its own seed) and
    /// returns the observations (a view, overwritten by the next call).
    #[pyo3(signature = (seed = None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seed: Option<u64>,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let obs = self.obs.bind(py).clone();
        {
            let mut view = obs.readwrite();
            let out = view.as_slice_mut()?;
            let mut env = self.lock();
            let env: &mut VecEnv = &mut env;
            py.detach(|| env.reset(seed, out))
                .map_err(|e| scenario_error(py, &e))?;
        }
        Ok(obs)
    }

    /// One step of every environment with `actions` (num_envs, n, dim) float64: the
    /// observations and rewards (views, overwritten by the next call) and, per environment,
    /// whether it terminated, was truncated, was reset by this step, and its fault.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: PyReadonlyArray3<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray3<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray1<bool>>,
        Bound<'py, PyArray1<bool>>,
        Bound<'py, PyArray1<bool>>,
        Vec<Option<String>>,
    )> {
        let mut env = self.lock();
        let expected = action_shape(&env);
        if actions.shape() != expected {
            return Err(PyValueError::new_err(format!(
                "actions of shape {:?}; expected {expected:?} (num_envs, agents, dim)",
                actions.shape()
            )));
        }
        let owned;
        let actions = match actions.as_slice() {
            Ok(slice) => slice,
            Err(_) => {
                owned = actions.as_array().iter().copied().collect::<Vec<f64>>();
                &owned
            }
        };
        let (obs, rewards) = (self.obs.bind(py).clone(), self.rewards.bind(py).clone());
        let outcomes = {
            let (mut o, mut r) = (obs.readwrite(), rewards.readwrite());
            let (o, r) = (o.as_slice_mut()?, r.as_slice_mut()?);
            let env: &mut VecEnv = &mut env;
            py.detach(|| env.step(actions, o, r))
                .map_err(|e| PyValueError::new_err(e.message))?
        };
        let flags = |f: fn(&flocking::env::Outcome) -> bool| {
            PyArray1::from_iter(py, outcomes.iter().map(f))
        };
        Ok((
            obs,
            rewards,
            flags(|o| o.terminated),
            flags(|o| o.truncated),
            flags(|o| o.reset),
            outcomes.iter().map(|o| o.fault.clone()).collect(),
        ))
    }

    /// What the scenario's protocol would command now (num_envs, n, dim): stepping with it gives
    /// `flocking run`'s bits.
    fn protocol_actions<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let mut env = self.lock();
        let out = PyArray3::zeros(py, action_shape(&env), false);
        {
            let mut view = out.readwrite();
            let slice = view.as_slice_mut()?;
            let env: &mut VecEnv = &mut env;
            py.detach(|| env.protocol_actions(slice));
        }
        Ok(out)
    }

    /// Every environment's state: times (num_envs,), positions and velocities
    /// (num_envs, n, dim), and which agents a fault removed (num_envs, n).
    #[allow(clippy::type_complexity)]
    fn states<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray3<f64>>,
        Bound<'py, PyArray3<f64>>,
        Bound<'py, PyArray2<bool>>,
    )> {
        let env = self.lock();
        let shape = action_shape(&env);
        let (mut t, mut q, mut p, mut failed) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for sim in env.simulations() {
            let state = sim.state();
            t.push(sim.time());
            q.extend_from_slice(&state.positions);
            p.extend_from_slice(&state.velocities);
            match &state.failed {
                Some(f) => failed.extend_from_slice(f),
                None => failed.extend(std::iter::repeat_n(false, shape[1])),
            }
        }
        Ok((
            PyArray1::from_vec(py, t),
            PyArray1::from_vec(py, q).reshape(shape)?,
            PyArray1::from_vec(py, p).reshape(shape)?,
            PyArray1::from_vec(py, failed).reshape([shape[0], shape[1]])?,
        ))
    }
}
