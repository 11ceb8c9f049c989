//! Classical fourth-order Runge–Kutta of the ideal loop: the input u(t, q, p) re-evaluated at
//! each of its four stages, on the net of each stage's positions. (Under conditions the input is
//! held over the step, and the integrate stage takes RK4's closed form: see
//! [`integrate`](super::integrate).)

use flock_math::Vector;
use flock_math::interrupt::cuts_short;
use flock_protocols::Protocol;

use crate::Simulation;
use crate::step::control::controls_in;

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// y ← y + (h/6)(k₁ + 2k₂ + 2k₃ + k₄) with y = (q, p) and k = (p, u(t, q, p)), k₁'s input
    /// the control stage's (in `inputs`). Returns whether the step was taken (not when an
    /// interrupt cut an evaluation of the inputs short: y is then unchanged).
    pub(crate) fn runge_kutta(&mut self) -> bool {
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
        // stage 1 is y itself: its input u(t, y) is the control stage's, on the net of y
        rk.stage.velocities.copy_from_slice(&y.velocities);
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
            self.search
                .build_in(&self.domain, &rk.stage.positions, range, &mut rk.net);
            controls_in(
                &self.protocol,
                &self.domain,
                t + offset * h,
                (&rk.stage, &rk.net),
                &mut self.inputs,
                &mut self.percepts,
            );
        }
        if cuts_short() {
            return false;
        }
        for i in 0..y.len() {
            y.positions[i] = self.domain.wrap(y.positions[i] + rk.sum_q[i] * (h / 6.0));
            y.velocities[i] += rk.sum_p[i] * (h / 6.0);
        }
        true
    }
}
