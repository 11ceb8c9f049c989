//! Fixed-step time integration of the closed loop q̇ = p, ṗ = u(t, q, p), with the net rebuilt at
//! every evaluation of u.

use std::borrow::Cow;

use flock_graph::parallel::fill_indexed;
use flock_graph::{NeighbourSearch, Numbering, ProximityNet};
use flock_math::Vector;

use crate::{Protocol, Swarm};

/// The integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integrator {
    /// Semi-implicit (symplectic) Euler: p ← p + h u(t, q, p), then q ← q + h p. First order,
    /// one net per step, and free of the energy drift of explicit Euler.
    #[default]
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta: four evaluations of u (four nets) per step.
    Rk4,
}

/// Steps between two re-sorts of agents stored in space order.
const RESORT_EVERY: u64 = 16;

/// A protocol integrated in time from an initial swarm with a fixed step.
///
/// The proximity net of the current state is kept up to date, so metrics and energies can be read
/// between steps without another neighbour search.
///
/// When the agents are numbered at random (their net [`ProximityNet::is_scattered`]) and the
/// protocol [`Protocol::follows_numbering`], the simulation stores them in the order of the
/// search's cells, so that neighbours are near in memory, and re-sorts them every 16 steps; the
/// net carries the [`Numbering`]. Every state, energy and metric keeps the bits of the agents in
/// original order: [`Simulation::swarm`] gives the state in original order, while
/// [`Simulation::stored_swarm`] and [`Simulation::net`] are in storage order.
#[derive(Debug)]
pub struct Simulation<V, P> {
    protocol: P,
    integrator: Integrator,
    step: f64,
    steps: u64,
    swarm: Swarm<V>,
    search: NeighbourSearch,
    net: ProximityNet,
    inputs: Vec<V>,
    rk: Option<RungeKuttaScratch<V>>,
}

/// An empty net for `protocol`: without distances when it does not read them.
fn empty_net<V: Vector, P: Protocol<V>>(protocol: &P) -> ProximityNet {
    if protocol.uses_net_distances() {
        ProximityNet::new()
    } else {
        ProximityNet::without_distances()
    }
}

/// Buffers of the Runge–Kutta stages, allocated once.
#[derive(Debug)]
struct RungeKuttaScratch<V> {
    stage: Swarm<V>,
    net: ProximityNet,
    sum_q: Vec<V>,
    sum_p: Vec<V>,
}

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// A simulation at t = 0 from `swarm`, advancing by `step > 0`.
    #[must_use]
    pub fn new(protocol: P, integrator: Integrator, swarm: Swarm<V>, step: f64) -> Self {
        let n = swarm.len();
        let rk = (integrator == Integrator::Rk4).then(|| RungeKuttaScratch {
            stage: swarm.clone(),
            net: empty_net(&protocol),
            sum_q: vec![V::ZERO; n],
            sum_p: vec![V::ZERO; n],
        });
        let mut simulation = Self {
            net: empty_net(&protocol),
            protocol,
            integrator,
            step,
            steps: 0,
            swarm,
            search: NeighbourSearch::new(),
            inputs: vec![V::ZERO; n],
            rk,
        };
        simulation.rebuild_net();
        simulation
    }

    /// A simulation resumed after `steps` steps, at t = steps · h, from the state `swarm` those
    /// steps reached: stepping it gives bit-identical states to the uninterrupted simulation, since
    /// the state (q, p) and the step count are all a simulation carries between steps.
    #[must_use]
    pub fn resume(
        protocol: P,
        integrator: Integrator,
        swarm: Swarm<V>,
        step: f64,
        steps: u64,
    ) -> Self {
        Self {
            steps,
            ..Self::new(protocol, integrator, swarm, step)
        }
    }

    /// The protocol.
    #[must_use]
    pub const fn protocol(&self) -> &P {
        &self.protocol
    }

    /// The current state, agents in original order: borrowed when they are stored so, otherwise
    /// a copy in that order (see [`Simulation::stored_swarm`]).
    #[must_use]
    pub fn swarm(&self) -> Cow<'_, Swarm<V>> {
        let numbering = self.net.numbering();
        if numbering.is_identity() {
            return Cow::Borrowed(&self.swarm);
        }
        let ordered = |x: &[V]| numbering.ordered(x).collect();
        Cow::Owned(Swarm {
            positions: ordered(&self.swarm.positions),
            velocities: ordered(&self.swarm.velocities),
        })
    }

    /// The current state as stored: agent [`Numbering::original`]`(s)` at index s.
    #[must_use]
    pub const fn stored_swarm(&self) -> &Swarm<V> {
        &self.swarm
    }

    /// How the agents are stored (the identity unless they were numbered at random; see
    /// [`Simulation`]).
    #[must_use]
    pub fn numbering(&self) -> &Numbering {
        self.net.numbering()
    }

    /// The proximity net of the current state, in storage order with the [`Numbering`]; it keeps
    /// no distances when the protocol does not use them ([`Protocol::uses_net_distances`]), see
    /// [`ProximityNet::edge_lengths`].
    #[must_use]
    pub const fn net(&self) -> &ProximityNet {
        &self.net
    }

    /// The number of steps taken.
    #[must_use]
    pub const fn steps(&self) -> u64 {
        self.steps
    }

    /// The current time t = steps · h (not accumulated, so it carries no round-off).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.steps as f64 * self.step
    }

    /// The protocol's energy at the current state.
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.protocol.energy(self.time(), &self.swarm, &self.net)
    }

    /// Advances the state by one step h.
    pub fn step(&mut self) {
        match self.integrator {
            Integrator::SymplecticEuler => self.symplectic_euler(),
            Integrator::Rk4 => self.runge_kutta(),
        }
        self.steps += 1;
        self.rebuild_net();
    }

    /// Builds the net of the current state; agents stored in space order are re-sorted every
    /// [`RESORT_EVERY`] steps first, and agents in original order found scattered in memory are
    /// sorted, when the protocol follows the numbering. (Agents once sorted wait for the next
    /// re-sort even if still scattered, e.g. thousands in one cell: no sort at every step.)
    fn rebuild_net(&mut self) {
        let r = self.protocol.interaction_range();
        let sorts = self.protocol.follows_numbering();
        let sorted = !self.net.numbering().is_identity();
        if sorts && sorted && self.steps % RESORT_EVERY == 0 {
            self.sort_by_cell();
        }
        self.search.build(&self.swarm.positions, r, &mut self.net);
        if sorts && !sorted && self.net.is_scattered() {
            self.sort_by_cell();
            self.search.build(&self.swarm.positions, r, &mut self.net);
        }
    }

    /// Stores the agents in the order of the search's cells (agents with a non-finite position
    /// last, in their storage order) and renumbers the nets, which must then be rebuilt.
    fn sort_by_cell(&mut self) {
        let q = &self.swarm.positions;
        let cells = self.search.cell_order(q, self.protocol.interaction_range());
        let completed: Vec<u32>;
        let order = if cells.len() == q.len() {
            cells
        } else {
            let lost = (0..q.len()).filter(|&i| !q[i].is_finite());
            completed = cells
                .iter()
                .copied()
                .chain(lost.map(|i| i as u32))
                .collect();
            &completed
        };
        // the inputs are free between steps: each array is gathered there and swapped in
        for x in [&mut self.swarm.positions, &mut self.swarm.velocities] {
            fill_indexed(&mut self.inputs, |s| x[order[s] as usize]);
            core::mem::swap(x, &mut self.inputs);
        }
        self.net.permute(order);
        if let Some(rk) = self.rk.as_mut() {
            rk.net.share_numbering(&self.net);
        }
    }

    fn symplectic_euler(&mut self) {
        let (t, h) = (self.time(), self.step);
        self.protocol
            .controls(t, &self.swarm, &self.net, &mut self.inputs);
        let Swarm {
            positions,
            velocities,
        } = &mut self.swarm;
        let update = |((q, p), &u): ((&mut V, &mut V), &V)| {
            *p += u * h;
            *q += *p * h;
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            positions
                .par_iter_mut()
                .zip(velocities.par_iter_mut())
                .zip(self.inputs.par_iter())
                .with_min_len(4096)
                .for_each(update);
        }
        #[cfg(not(feature = "parallel"))]
        positions
            .iter_mut()
            .zip(velocities.iter_mut())
            .zip(&self.inputs)
            .for_each(update);
    }

    /// y ← y + (h/6)(k₁ + 2k₂ + 2k₃ + k₄) with y = (q, p) and k = (p, u(t, q, p)).
    fn runge_kutta(&mut self) {
        const WEIGHTS: [f64; 4] = [1.0, 2.0, 2.0, 1.0];
        const NEXT_OFFSETS: [f64; 3] = [0.5, 0.5, 1.0];
        let (t, h) = (self.time(), self.step);
        let range = self.protocol.interaction_range();
        let Some(rk) = self.rk.as_mut() else {
            unreachable!("Runge–Kutta buffers exist for Integrator::Rk4");
        };
        let y = &mut self.swarm;
        rk.sum_q.fill(V::ZERO);
        rk.sum_p.fill(V::ZERO);
        // stage 1 evaluates at y itself, whose net is already built
        rk.stage.velocities.copy_from_slice(&y.velocities);
        self.protocol.controls(t, y, &self.net, &mut self.inputs);
        for (stage, weight) in WEIGHTS.into_iter().enumerate() {
            // here rk.stage.velocities holds p_s and self.inputs holds u_s
            for i in 0..y.len() {
                rk.sum_q[i] += rk.stage.velocities[i] * weight;
                rk.sum_p[i] += self.inputs[i] * weight;
            }
            let Some(&offset) = NEXT_OFFSETS.get(stage) else {
                break;
            };
            for i in 0..y.len() {
                let (p_s, u_s) = (rk.stage.velocities[i], self.inputs[i]);
                rk.stage.positions[i] = y.positions[i] + p_s * (offset * h);
                rk.stage.velocities[i] = y.velocities[i] + u_s * (offset * h);
            }
            self.search.build(&rk.stage.positions, range, &mut rk.net);
            self.protocol
                .controls(t + offset * h, &rk.stage, &rk.net, &mut self.inputs);
        }
        for i in 0..y.len() {
            y.positions[i] += rk.sum_q[i] * (h / 6.0);
            y.velocities[i] += rk.sum_p[i] * (h / 6.0);
        }
    }
}
