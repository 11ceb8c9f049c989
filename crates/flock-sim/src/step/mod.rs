//! One step of a run, in the order a vehicle lives it: **fail → sense → communicate → control →
//! actuate → integrate** ([`Simulation::step`]), each stage a call in its own file.
//!
//! | stage | reads | writes |
//! | --- | --- | --- |
//! | [fail] | the faults, the step | the failed agents |
//! | [sense] | the true state, the sensor | the delay line's newest slot |
//! | [communicate] | the delay line, the nets, the links | what each agent perceives ([`communicate::Perception`]) |
//! | [control] | the perception, the protocol | the inputs u_i |
//! | [actuate] | the inputs | the delivered accelerations |
//! | [integrate] | the delivered inputs, the disturbance | the state (q, p), a vehicle's state |
//!
//! A run without conditions is this loop with nothing to do in its stages: no agent fails, each
//! perceives the true state and its net ([`Perception::Truth`](communicate::Perception::Truth)),
//! its input is delivered as commanded and no disturbance acts. The protocols take no part but to
//! compute u_i.

pub mod actuate;
pub mod communicate;
pub mod control;
pub mod disturb;
pub mod fail;
pub mod integrate;
pub mod runge_kutta;
pub mod sense;

use flock_math::Vector;
use flock_math::interrupt::cuts_short;
use flock_protocols::Protocol;

use crate::Simulation;
use communicate::communicate;
use control::control;

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// Advances the state by one step h: **fail → sense → communicate → control → actuate →
    /// integrate**. Without [conditions](Simulation::with_conditions) only control (of the true
    /// state) and integrate have work to do.
    ///
    /// An interrupt that [cuts the step short](flock_math::interrupt::cuts_short) (a Ctrl-C
    /// during a step of more than half a second) stops its long loops. Cut while the inputs are
    /// computed, before the state changes, the step is not taken: the state and the step count
    /// stay those of the steps taken. Cut inside a vehicle's inner steps or under conditions,
    /// whose stages change their state as they go, it leaves the state between two steps: the
    /// simulation is then [torn](Simulation::is_torn) and takes no more steps.
    pub fn step(&mut self) {
        if self.torn {
            return;
        }
        let (k, t) = (self.steps, self.time());
        // the stages take the protocol behind a reference to its trait: they are compiled once
        // per dimension, not once per protocol (its own loops stay its own, monomorphic)
        let protocol: &dyn Protocol<V> = &self.protocol;
        let numbering = self.net.numbering();
        let mut stage = self.conditions.as_deref_mut();
        if let Some(stage) = stage.as_deref_mut() {
            stage.fail(k, numbering);
            stage.sense(&self.swarm, numbering, k);
        }
        if stage.as_deref().is_none_or(|s| s.controls_at(k)) {
            let perception = communicate(
                stage.as_deref_mut(),
                protocol,
                &self.domain,
                &self.swarm,
                &self.net,
                k,
            );
            let received = control(protocol, t, perception, &mut self.inputs);
            if let Some(stage) = stage.as_deref_mut() {
                stage.controlled(received, &mut self.inputs);
            }
        }
        if cuts_short() {
            // the conditions' state has moved on; the ideal state is untouched
            self.torn = stage.is_some();
            return;
        }
        if let Some(stage) = stage {
            stage.actuate(&mut self.inputs);
        }
        let taken = self.integrate(k);
        if let Some(stage) = self.conditions.as_deref_mut() {
            // the noise, gusts and delay line carry on from here
            stage.started = true;
        }
        self.torn = taken && (self.conditions.is_some() || self.fleet.is_some()) && cuts_short();
        if taken && !self.torn {
            self.steps += 1;
            self.rebuild_net();
        }
    }

    /// Whether an interrupt cut a step short after it had changed the state
    /// ([`Simulation::step`]): the state is then between two steps, neither of which it is, and
    /// the simulation takes no more steps.
    #[must_use]
    pub const fn is_torn(&self) -> bool {
        self.torn
    }
}
