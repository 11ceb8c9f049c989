//! [`Perception`]: what every agent perceives at a control update, as plain rows of numbers in
//! either dimension, agents in original order — what a controller written outside the library
//! ([`Controller`](crate::controller::Controller), Python's `flocking.Local`) and an
//! environment's observations ([`env`](crate::env)) are made from.
//!
//! It is the communicate stage's output ([`flock_sim::step::perceive::Percepts`]): with the
//! scenario's delay, loss, range, faults and sensing noise applied, each agent's own state as it
//! measures it and each neighbour's as it received it; in the ideal run, the true state.

use flock_math::Vector;
use flock_protocols::{LocalForm, Perceptions};

/// What every agent perceives at time `t`, in compressed sparse rows, agents in original order.
/// Agent i measures its own position and velocity as `positions[i·dim..(i+1)·dim]` and
/// `velocities[…]`; it heard the agents `neighbours[indptr[i]..indptr[i+1]]` (ascending original
/// index), each at the relative position q_j − q_i and relative velocity p_j − p_i (rows of
/// `relative_positions`, `relative_velocities`; for a protocol of the proximity net they may lie
/// beyond the interaction range r when the communication range is larger, and on a torus each is
/// at its image nearest the agent). The γ-agent's state (q_r, p_r) when the scenario's protocol
/// tracks one (TAC 2006 Algorithms 2 and 3), and the β-agents each agent senses on the
/// obstacles within r′ (Algorithm 3), relative to the agent, in `beta_indptr`'s rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Perception {
    /// The dimension, 2 or 3.
    pub dim: usize,
    /// The time t of the control update.
    pub t: f64,
    /// Each agent's own position as it measures it (n × dim).
    pub positions: Vec<f64>,
    /// Each agent's own velocity as it measures it (n × dim).
    pub velocities: Vec<f64>,
    /// Where each agent's neighbours start in `neighbours` (n + 1 entries, from 0).
    pub indptr: Vec<usize>,
    /// The agents heard, agent by agent, by original index.
    pub neighbours: Vec<u32>,
    /// q_j − q_i of each agent heard (m × dim).
    pub relative_positions: Vec<f64>,
    /// p_j − p_i of each agent heard (m × dim).
    pub relative_velocities: Vec<f64>,
    /// The γ-agent's (q_r, p_r), each `dim` numbers; `None` without one.
    pub gamma: Option<(Vec<f64>, Vec<f64>)>,
    /// Where each agent's β-agents start in `beta_relative_positions` (n + 1 entries).
    pub beta_indptr: Vec<usize>,
    /// q̂_ik − q_i of each β-agent (rows of `dim`).
    pub beta_relative_positions: Vec<f64>,
    /// p̂_ik − p_i of each β-agent (rows of `dim`).
    pub beta_relative_velocities: Vec<f64>,
}

/// Appends the coordinates of `v`.
fn push<V: Vector>(rows: &mut Vec<f64>, v: V) {
    rows.extend((0..V::DIM).map(|k| v.coord(k)));
}

impl Perception {
    /// The number of agents.
    #[must_use]
    pub fn agents(&self) -> usize {
        self.indptr.len().saturating_sub(1)
    }

    /// The perceptions `all` at time `t` (agents as the simulation stores them, each named by
    /// its original index), with the γ-agent and β-agents of the protocol's `local` form.
    pub fn fill<V: Vector>(
        &mut self,
        t: f64,
        all: Perceptions<'_, V>,
        local: Option<&dyn LocalForm<V>>,
    ) {
        let n = all.owns.len();
        // the place in `all` of the agent of each original index
        let mut stored = vec![0; n];
        for (s, own) in all.owns.iter().enumerate() {
            stored[own.agent as usize] = s;
        }
        self.dim = V::DIM;
        self.t = t;
        for rows in [
            &mut self.positions,
            &mut self.velocities,
            &mut self.relative_positions,
            &mut self.relative_velocities,
            &mut self.beta_relative_positions,
            &mut self.beta_relative_velocities,
        ] {
            rows.clear();
        }
        self.indptr.clear();
        self.indptr.push(0);
        self.neighbours.clear();
        self.beta_indptr.clear();
        self.beta_indptr.push(0);
        let mut betas = Vec::new();
        for &s in &stored {
            let own = &all.owns[s];
            let heard = &all.heard[if s == 0 { 0 } else { all.ends[s - 1] }..all.ends[s]];
            push(&mut self.positions, own.position);
            push(&mut self.velocities, own.velocity);
            for j in heard {
                self.neighbours.push(j.agent);
                push(&mut self.relative_positions, j.position - own.position);
                push(&mut self.relative_velocities, j.velocity - own.velocity);
            }
            self.indptr.push(self.neighbours.len());
            if let Some(local) = local {
                betas.clear();
                local.beta_agents(own, &mut betas);
                for &(q, p) in &betas {
                    push(&mut self.beta_relative_positions, q - own.position);
                    push(&mut self.beta_relative_velocities, p - own.velocity);
                }
            }
            self.beta_indptr
                .push(self.beta_relative_positions.len() / V::DIM);
        }
        self.gamma = local.and_then(|l| l.reference(t)).map(|(q, p)| {
            let (mut qr, mut pr) = (Vec::new(), Vec::new());
            push(&mut qr, q);
            push(&mut pr, p);
            (qr, pr)
        });
    }
}
