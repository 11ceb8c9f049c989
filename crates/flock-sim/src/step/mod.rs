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
//!
//! A controller outside the loop (a policy learning to flock, a user's function) takes the
//! control stage's place in the same step split in two: [`Simulation::perceive`] runs fail →
//! sense → communicate and gives every agent's perception ([`perceive::Percepts`]);
//! [`Simulation::act`] takes the inputs it computed and runs actuate → integrate.

pub mod actuate;
pub mod communicate;
pub mod control;
pub mod disturb;
pub mod fail;
pub mod integrate;
pub mod perceive;
pub mod runge_kutta;
pub mod sense;

use flock_math::Vector;
use flock_math::interrupt::cuts_short;
use flock_protocols::Protocol;

#[cfg(doc)]
use crate::Integrator;
use crate::Simulation;
use communicate::Received;
use communicate::communicate;
use control::{control, controls_in};
use perceive::{Percepts, Sensed};

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// Advances the state by one step h: **fail → sense → communicate → control → actuate →
    /// integrate**. Without [conditions](Simulation::with_conditions) only control (of the true
    /// state) and integrate have work to do. After [`Simulation::perceive`], the step's inputs
    /// are the protocol's of that perception ([`Simulation::protocol_inputs`]).
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
        let controlled = match self.pending.take() {
            None if !self.sense() => None,
            None => {
                let t = self.time();
                // the stages take the protocol behind a reference to its trait: they are
                // compiled once per dimension, not once per protocol (its own loops stay its
                // own, monomorphic)
                let protocol: &dyn Protocol<V> = &self.protocol;
                let perception = communicate(
                    self.conditions.as_deref_mut(),
                    protocol,
                    &self.domain,
                    &self.swarm,
                    &self.net,
                    self.steps,
                );
                let inputs = &mut self.inputs;
                Some(control(protocol, t, perception, inputs, &mut self.percepts))
            }
            Some(Sensed::Held) => None,
            Some(Sensed::Perceived { truth, received }) => {
                let mut inputs = core::mem::take(&mut self.inputs);
                self.inputs_of(truth, &mut inputs);
                self.inputs = inputs;
                Some(received)
            }
        };
        self.finish(controlled);
    }

    /// The first half of a step for a controller outside the loop: **fail → sense →
    /// communicate**, and what every agent perceives at this control update; `None` at a step
    /// without one (sampled control: [`Simulation::act`] then holds the inputs). Calling it
    /// again before [`Simulation::act`] gives the same perceptions; a [torn](Simulation::is_torn)
    /// simulation perceives nothing.
    pub fn perceive(&mut self) -> Option<&Percepts<V>> {
        if self.torn {
            return None;
        }
        if self.pending.is_none() {
            // the percepts are of the net
            self.refresh_net();
            let sensed = if self.sense() {
                let protocol: &dyn Protocol<V> = &self.protocol;
                let perception = communicate(
                    self.conditions.as_deref_mut(),
                    protocol,
                    &self.domain,
                    &self.swarm,
                    &self.net,
                    self.steps,
                );
                let truth = matches!(perception, communicate::Perception::Truth { .. });
                let received = match perception {
                    communicate::Perception::Truth { domain, swarm, net } => {
                        let graph = protocol.interaction_graph();
                        self.percepts.of_truth(domain, swarm, net, graph);
                        None
                    }
                    communicate::Perception::Heard(heard) => Some(self.percepts.of_heard(*heard)),
                };
                Sensed::Perceived { truth, received }
            } else {
                Sensed::Held
            };
            self.pending = Some(sensed);
        }
        self.perceived()
    }

    /// The perceptions of the step begun by [`Simulation::perceive`], if it has a control
    /// update.
    #[must_use]
    pub fn perceived(&self) -> Option<&Percepts<V>> {
        match self.pending {
            Some(Sensed::Perceived { .. }) => Some(&self.percepts),
            _ => None,
        }
    }

    /// The second half of a step begun by [`Simulation::perceive`] (begun here if it was not):
    /// every agent's input u_i from `inputs` (stored order, as the perceptions; ignored at a step
    /// without a control update, whose inputs are held), then **actuate → integrate**, exactly as
    /// [`Simulation::step`] applies the protocol's. (In the ideal loop with [`Integrator::Rk4`],
    /// RK4's three later stages evaluate the protocol: `inputs` are its first stage's.)
    ///
    /// # Panics
    /// When `inputs` does not hold one input per agent at a control update.
    pub fn act(&mut self, inputs: &[V]) {
        self.perceive();
        let controlled = match self.pending.take() {
            Some(Sensed::Perceived { received, .. }) => {
                self.inputs.copy_from_slice(inputs);
                Some(received)
            }
            Some(Sensed::Held) | None => None,
        };
        self.finish(controlled);
    }

    /// What the protocol would command for the perceptions of [`Simulation::perceive`], into
    /// `out` (stored order): its inputs of the true state when the agents perceive it, else its
    /// [`LocalForm`](flock_protocols::LocalForm) of what they heard — the bits a
    /// [`Simulation::step`] applies. Returns false, `out` untouched, when no perception is
    /// pending (before `perceive`, or at a step without a control update).
    pub fn protocol_inputs(&mut self, out: &mut [V]) -> bool {
        match self.pending {
            Some(Sensed::Perceived { truth, .. }) => {
                self.inputs_of(truth, out);
                true
            }
            _ => false,
        }
    }

    /// The protocol's inputs of the perceptions gathered: of the true state (`truth`), or of
    /// what the agents heard through its local form.
    fn inputs_of(&mut self, truth: bool, out: &mut [V]) {
        let (t, protocol) = (self.time(), &self.protocol as &dyn Protocol<V>);
        match protocol.local_form() {
            Some(local) if !truth => local.local_inputs(t, self.percepts.perceptions(), out),
            _ => {
                let state = (&self.swarm, &self.net);
                controls_in(protocol, &self.domain, t, state, out, &mut self.percepts);
            }
        }
    }

    /// **fail → sense** of the next step; whether it has a control update.
    fn sense(&mut self) -> bool {
        let k = self.steps;
        let numbering = self.net.numbering();
        match self.conditions.as_deref_mut() {
            Some(stage) => {
                stage.fail(k, numbering);
                stage.sense(&self.swarm, numbering, k);
                stage.controls_at(k)
            }
            None => true,
        }
    }

    /// **actuate → integrate**: the step finished from the inputs of its control update
    /// (`controlled`, with what the conditions get back; `None` when the inputs are held).
    fn finish(&mut self, controlled: Option<Option<Received<V>>>) {
        let k = self.steps;
        if let (Some(received), Some(stage)) = (controlled, self.conditions.as_deref_mut()) {
            stage.controlled(received, &mut self.inputs);
        }
        if cuts_short() {
            // the conditions' state has moved on; the ideal state is untouched
            self.torn = self.conditions.is_some();
            return;
        }
        if let Some(stage) = self.conditions.as_deref_mut() {
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
            if self.keeps_net() {
                self.rebuild_net();
            } else {
                // built when a measurement reads it (Simulation::current_net)
                self.net_stale = true;
            }
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
