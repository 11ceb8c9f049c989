//! **Integrate**: the state after the step h, written once per kind of update
//! ([`Update`]):
//!
//! - an **acceleration**, through the run's [`Integrator`] ([`accelerated`]): symplectic Euler
//!   p ← p + h a, q ← q + h p; or RK4 — in the ideal run re-evaluating the input at its four
//!   stages ([`runge_kutta`](super::runge_kutta)), and under conditions, where the delivered
//!   acceleration a is held over the step (sampled, delayed or lagged, it is not a function of
//!   the stages' states), RK4 of that held input. RK4's four stages for ṗ = a constant give
//!   k₁ = k₄ − h a = (p, a), k₂ = k₃ = (p + ½ h a, a), hence q ← q + h p + ½ h² a and
//!   p ← p + h a: the closed form, which this stage computes (equal to the four stages in exact
//!   arithmetic, to round-off in floating point);
//! - a **next velocity**, a model's own update ([`advance`]);
//! - a **vehicle**, which follows its delivered acceleration through its own controller and
//!   dynamics at its inner step ([`Fleet::advance`]).
//!
//! Under conditions the disturbance ([`disturb`](super::disturb)) adds the wind to the
//! acceleration and the process noise's kick σ √h ξ to the velocity (Euler–Maruyama), ‖p‖ is
//! clipped to v_max, and agents that do not move keep their position with zero velocity.

use flock_graph::Numbering;
use flock_math::{Domain, Vector};
use flock_protocols::{Protocol, Swarm, Update};

use crate::agents::for_each_agent;
use crate::conditions::Stage;
use crate::conditions::actuation::clip;
use crate::vehicle::Fleet;
use crate::{Integrator, Simulation};

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// Integrate step `k` from the inputs of the control stage (delivered by the actuate
    /// stage). Returns whether the step was taken: not when an interrupt cut RK4's stages short,
    /// before the state changed.
    pub(crate) fn integrate(&mut self, k: u64) -> bool {
        let (h, integrator, update) = (self.step, self.integrator, self.protocol.update());
        let ideal = self.conditions.is_none() && self.fleet.is_none();
        if update == Update::Acceleration && integrator == Integrator::Rk4 && ideal {
            return self.runge_kutta();
        }
        let numbering = self.net.numbering();
        if let Some(stage) = self.conditions.as_deref_mut() {
            stage.advance_gusts(numbering, k);
        }
        let stage = self.conditions.as_deref();
        let (domain, swarm, inputs) = (&self.domain, &mut self.swarm, &self.inputs);
        match (update, self.fleet.as_deref_mut()) {
            (Update::Acceleration, Some(fleet)) => {
                drive(fleet, (h, k), domain, swarm, inputs, stage, numbering);
            }
            (Update::Acceleration, None) => {
                let clipped =
                    accelerate(integrator, (h, k), domain, swarm, inputs, stage, numbering);
                if let Some(stage) = self.conditions.as_deref_mut() {
                    stage.readings.at_speed_limit = clipped as f64;
                }
            }
            (update, _) => set_velocities(update, h, domain, swarm, inputs, stage),
        }
        true
    }
}

/// One agent's state (q, p) after the step h under the acceleration `a` held over it and the
/// velocity `kick` (the process noise), ‖p‖ clipped to `max_speed`: symplectic Euler
/// p ← p + h a (+ kick), q ← q + h p, or RK4 of the held `a`, q ← q + h p + ½ h² a (see the
/// [module](self)); q wrapped into the box of a periodic `domain`. Also whether p was clipped.
#[inline]
#[must_use]
pub fn accelerated<V: Vector>(
    integrator: Integrator,
    domain: &Domain<V>,
    h: f64,
    (q, p): (V, V),
    a: V,
    kick: Option<V>,
    max_speed: Option<f64>,
) -> (V, V, bool) {
    let next = match kick {
        Some(kick) => p + a * h + kick,
        None => p + a * h,
    };
    let (next_p, clipped) = clip(next, max_speed);
    let q = match integrator {
        Integrator::SymplecticEuler => domain.wrap(q + next_p * h),
        Integrator::Rk4 => domain.wrap(q + p * h + a * (0.5 * h * h)),
    };
    (q, next_p, clipped)
}

/// One agent's state after a step h from its input u: symplectic Euler for an acceleration
/// ([`accelerated`]), or the model's own update ([`Update`]); q wrapped into the box of a
/// periodic `domain`.
#[inline]
#[must_use]
pub fn advance<V: Vector>(update: Update, domain: &Domain<V>, h: f64, q: V, p: V, u: V) -> (V, V) {
    match update {
        Update::Acceleration => {
            let (q, p, _) = accelerated(
                Integrator::SymplecticEuler,
                domain,
                h,
                (q, p),
                u,
                None,
                None,
            );
            (q, p)
        }
        Update::TurnThenMove => (domain.wrap(q + u * h), u),
        Update::MoveThenTurn => (domain.wrap(q + p * h), u),
    }
}

/// Every agent's acceleration step ([`accelerated`]) at step h of step number k: the inputs as
/// commanded in the ideal run; under conditions, the delivered accelerations with the wind, the
/// process noise and the speed limit, agents that do not move held still. Returns the number of
/// agents whose speed was clipped.
fn accelerate<V: Vector>(
    integrator: Integrator,
    (h, k): (f64, u64),
    domain: &Domain<V>,
    swarm: &mut Swarm<V>,
    inputs: &[V],
    stage: Option<&Stage<V>>,
    numbering: &Numbering,
) -> usize {
    let Swarm {
        positions,
        velocities,
    } = swarm;
    let n = positions.len();
    let Some(stage) = stage else {
        // the ideal run: each agent's own slots, no index (the loop the compiler vectorises)
        let agent = |((q, p), &u): ((&mut V, &mut V), &V)| {
            (*q, *p, _) = accelerated(integrator, domain, h, (*q, *p), u, None, None);
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            positions
                .par_iter_mut()
                .zip(velocities.par_iter_mut())
                .zip(inputs.par_iter())
                .with_min_len(4096)
                .for_each(agent);
        }
        #[cfg(not(feature = "parallel"))]
        positions
            .iter_mut()
            .zip(velocities.iter_mut())
            .zip(inputs)
            .for_each(agent);
        return 0;
    };
    let max_speed = stage.conditions.actuation.and_then(|a| a.max_speed);
    let delivered = stage.delivered(inputs);
    for_each_agent(positions, velocities, &mut vec![(); n], |i, q, p, ()| {
        if !stage.moves(i) {
            *p = V::ZERO;
            return 0;
        }
        let (wind, noise) = stage.disturbance(i, numbering, k);
        let a = delivered[i] + wind;
        let clipped;
        (*q, *p, clipped) = accelerated(integrator, domain, h, (*q, *p), a, Some(noise), max_speed);
        usize::from(clipped)
    })
}

/// Every agent's vehicle follows its input (delivered under conditions) through its controller
/// and dynamics; under conditions with the external acceleration wind + σ ξ/√h (the process
/// noise's kick σ √h ξ spread over the step), agents that do not move keeping their place and
/// state.
fn drive<V: Vector>(
    fleet: &mut Fleet<V>,
    (h, k): (f64, u64),
    domain: &Domain<V>,
    swarm: &mut Swarm<V>,
    inputs: &[V],
    stage: Option<&Stage<V>>,
    numbering: &Numbering,
) {
    match stage {
        None => fleet.advance(h, domain, swarm, inputs, |_| V::ZERO, |_| true, numbering),
        Some(stage) => {
            let disturbance = |i: usize| {
                let (wind, noise) = stage.disturbance(i, numbering, k);
                wind + noise * (1.0 / h)
            };
            let moves = |i: usize| stage.moves(i);
            let delivered = stage.delivered(inputs);
            fleet.advance(h, domain, swarm, delivered, disturbance, moves, numbering);
        }
    }
}

/// Every agent's own update ([`advance`]) for a model that sets velocities, from its input
/// (delivered under conditions); agents that do not move keep their position with zero velocity.
fn set_velocities<V: Vector>(
    update: Update,
    h: f64,
    domain: &Domain<V>,
    swarm: &mut Swarm<V>,
    inputs: &[V],
    stage: Option<&Stage<V>>,
) {
    let delivered = stage.map_or(inputs, |s| s.delivered(inputs));
    let n = swarm.len();
    for_each_agent(
        &mut swarm.positions,
        &mut swarm.velocities,
        &mut vec![(); n],
        |i, q, p, ()| {
            (*q, *p) = if stage.is_none_or(|s| s.moves(i)) {
                advance(update, domain, h, *q, *p, delivered[i])
            } else {
                (*q, V::ZERO)
            };
            0
        },
    );
}
