//! A local controller written outside the library ([`Controller`]): every agent's input u_i from
//! what that agent perceives ([`Perception`]), all agents in one call, run by the scenario's loop
//! in place of its protocol's inputs ([`WithController`]) — under every condition and vehicle,
//! in runs, sweeps, checkpoints and resumes, like a built-in protocol. Python's
//! `controls=flocking.Local(f)` is one.

use std::sync::{Arc, Mutex, PoisonError};

use flock_graph::{Graph, ProximityNet};
use flock_math::{Domain, Vector};
use flock_obstacles::Space;
use flock_protocols::{DynProtocol, LocalForm, Perceived, Perceptions, Protocol, Swarm, Update};
use flock_sim::step::perceive::Percepts;

use crate::initial::to_vector;
use crate::perception::Perception;
use crate::simulation::MapProtocol;

/// u_i of every agent from what each perceives: a distributed controller, each agent's input a
/// function of its own row of the [`Perception`] alone (its own measured state, the neighbours it
/// heard, the γ-agent, its β-agents).
pub trait Controller: Send + Sync {
    /// Writes u_i of every agent into `out` (n rows of `dim`, agents in original order): the
    /// commanded acceleration (or, for a model whose input is a velocity, the next velocity;
    /// for a vehicle, the acceleration its controller tracks).
    fn inputs(&self, perception: &Perception, out: &mut [f64]);
}

/// The [`MapProtocol`] that runs a [`Controller`] in place of the scenario protocol's inputs,
/// keeping its interaction range, energy, diagnostics and kind of update.
#[derive(Debug)]
pub struct WithController<C>(pub Arc<C>);

impl<C> Clone for WithController<C> {
    fn clone(&self) -> Self {
        Self(Arc::clone(&self.0))
    }
}

impl<C: Controller + 'static> MapProtocol for WithController<C> {
    fn map<V: Space + bytemuck::Pod>(&self, protocol: DynProtocol<V>) -> DynProtocol<V> {
        Box::new(Controlled {
            inner: protocol,
            controller: Arc::clone(&self.0),
            buffers: Mutex::new(Buffers::default()),
        })
    }
}

/// The rows handed to the controller and its result, reused from step to step.
#[derive(Default)]
struct Buffers {
    perception: Perception,
    out: Vec<f64>,
}

/// A scenario's protocol whose inputs come from a [`Controller`].
struct Controlled<V, C> {
    inner: DynProtocol<V>,
    controller: Arc<C>,
    buffers: Mutex<Buffers>,
}

impl<V: Vector, C: Controller> LocalForm<V> for Controlled<V, C> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let mut out = [V::ZERO];
        let ends = [heard.len()];
        let one = Perceptions {
            owns: core::slice::from_ref(own),
            heard,
            ends: &ends,
        };
        self.local_inputs(t, one, &mut out);
        out[0]
    }

    /// The controller's inputs, given in original order, put in the order of `all`.
    fn local_inputs(&self, t: f64, all: Perceptions<'_, V>, out: &mut [V]) {
        let mut buffers = self.buffers.lock().unwrap_or_else(PoisonError::into_inner);
        let Buffers {
            perception,
            out: rows,
        } = &mut *buffers;
        perception.fill(t, all, self.inner.local_form());
        rows.clear();
        rows.resize(all.owns.len() * V::DIM, 0.0);
        self.controller.inputs(perception, rows);
        for (u, own) in out.iter_mut().zip(all.owns) {
            let i = own.agent as usize;
            *u = to_vector(&rows[i * V::DIM..(i + 1) * V::DIM]);
        }
    }

    fn takes_all(&self) -> bool {
        true
    }

    fn reference(&self, t: f64) -> Option<(V, V)> {
        self.inner.local_form().and_then(|l| l.reference(t))
    }

    fn beta_agents(&self, own: &Perceived<V>, out: &mut Vec<(V, V)>) {
        if let Some(local) = self.inner.local_form() {
            local.beta_agents(own, out);
        }
    }
}

impl<V: Vector, C: Controller> Protocol<V> for Controlled<V, C> {
    fn interaction_range(&self) -> f64 {
        self.inner.interaction_range()
    }

    /// The controller's inputs of the true state in open space (a simulation gives it every
    /// perception itself, on a torus each neighbour at its nearest image).
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let mut all = Percepts::default();
        all.of_truth(&Domain::Open, swarm, net, self.interaction_graph());
        self.local_inputs(t, all.perceptions(), inputs);
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

    fn uses_net_distances(&self) -> bool {
        self.inner.uses_net_distances()
    }

    /// The controller sees every agent in original order whatever the storage: the bits do
    /// not depend on it.
    fn follows_numbering(&self) -> bool {
        self.inner.follows_numbering()
    }

    fn interaction_graph(&self) -> Option<&Graph> {
        self.inner.interaction_graph()
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    fn update(&self) -> Update {
        self.inner.update()
    }

    fn measures_in_domain(&self) -> bool {
        false
    }
}
