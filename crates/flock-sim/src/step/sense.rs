//! **Sense**: each agent measures its own state, the true state plus the sensor noise
//! ([`noise`](crate::conditions::noise)), refreshed at the sensor's rate; the measured states of
//! the last D + 1 steps are the delay line ([`history`](crate::conditions::history)) that
//! communication reads.

use flock_graph::Numbering;
use flock_math::Vector;
use flock_math::stream::Purpose;
use flock_protocols::Swarm;

use crate::agents::for_each_agent;
use crate::conditions::Stage;
use crate::conditions::history::Slot;

impl<V: Vector> Stage<V> {
    /// Sense: each agent's measured state is its true state plus the sensor noise, refreshed
    /// every sensor period and held between (the true state at every step without sensing),
    /// written into the delay line's slot of step `k`; at the first step, into every slot.
    /// Nothing when no condition changes what agents perceive (they perceive the true state).
    pub(crate) fn sense(&mut self, swarm: &Swarm<V>, numbering: &Numbering, k: u64) {
        if !self.perceives {
            return;
        }
        let started = self.started;
        self.measure(swarm, numbering, k);
        if !started {
            self.history.fill_from(k);
        }
    }

    /// The measured state of step `k`, into its slot of the delay line.
    fn measure(&mut self, swarm: &Swarm<V>, numbering: &Numbering, k: u64) {
        let (slot, before) = self.history.newest(k);
        let Some(sensor) = self.sensor else {
            copy_states(slot, &swarm.positions, &swarm.velocities);
            return;
        };
        if self.started && !k.is_multiple_of(self.sensor_period) {
            // held: the state of step k − 1 (already in place when D = 0)
            if let Some(before) = before {
                copy_states(slot, &before.0, &before.1);
            }
            return;
        }
        let (started, streams) = (self.started, &self.streams);
        let (positions, velocities) = (&mut slot.0, &mut slot.1);
        let measure = |i: usize, q: &mut V, p: &mut V, previous: Option<(V, V)>| {
            let agent = numbering.original(i) as u64;
            let mut draws = streams.draws(Purpose::Sensing, agent, k);
            let (xi_q, xi_p) = (draws.normal_vector(), draws.normal_vector());
            let offsets = sensor.update(previous, xi_q, xi_p);
            *q = swarm.positions[i] + offsets.0;
            *p = swarm.velocities[i] + offsets.1;
            offsets
        };
        if self.noise.is_empty() {
            let n = positions.len();
            for_each_agent(positions, velocities, &mut vec![(); n], |i, q, p, ()| {
                measure(i, q, p, None);
                0
            });
        } else {
            for_each_agent(positions, velocities, &mut self.noise, |i, q, p, noise| {
                *noise = measure(i, q, p, started.then_some(*noise));
                0
            });
        }
    }
}

/// The states `q` and `p` copied into `slot`, in parallel with the `parallel` feature (the
/// delay line's slots are cold: at 10⁶ agents and two threads, copied on one thread they cost
/// about 2 % of a step with a delay alone).
fn copy_states<V: Vector>(slot: &mut Slot<V>, q: &[V], p: &[V]) {
    let n = q.len();
    for_each_agent(
        &mut slot.0,
        &mut slot.1,
        &mut vec![(); n],
        |i, qi, pi, ()| {
            (*qi, *pi) = (q[i], p[i]);
            0
        },
    );
}
