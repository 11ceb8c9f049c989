//! Fixed-step time integration of the closed loop q̇ = p, ṗ = u(t, q, p), with the net rebuilt at
//! every evaluation of u.

use flock_graph::{NeighbourSearch, ProximityNet};
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

/// A protocol integrated in time from an initial swarm with a fixed step.
///
/// The proximity net of the current state is kept up to date, so metrics and energies can be read
/// between steps without another neighbour search.
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
        let mut search = NeighbourSearch::new();
        let mut net = empty_net(&protocol);
        search.build(&swarm.positions, protocol.interaction_range(), &mut net);
        let rk = (integrator == Integrator::Rk4).then(|| RungeKuttaScratch {
            stage: swarm.clone(),
            net: empty_net(&protocol),
            sum_q: vec![V::ZERO; n],
            sum_p: vec![V::ZERO; n],
        });
        Self {
            protocol,
            integrator,
            step,
            steps: 0,
            swarm,
            search,
            net,
            inputs: vec![V::ZERO; n],
            rk,
        }
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

    /// The current state.
    #[must_use]
    pub const fn swarm(&self) -> &Swarm<V> {
        &self.swarm
    }

    /// The proximity net of the current state; it keeps no distances when the protocol does not
    /// use them ([`Protocol::uses_net_distances`]), see [`ProximityNet::edge_lengths`].
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
        self.search.build(
            &self.swarm.positions,
            self.protocol.interaction_range(),
            &mut self.net,
        );
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
