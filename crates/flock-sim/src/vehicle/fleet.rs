//! [`Fleet`]: every agent's vehicle in a run, the one [`Vehicle`] and each agent's state, and
//! what the vehicles measured over the last step.

use flock_graph::Numbering;
use flock_math::{Domain, Vector};

use super::{DynVehicle, Vehicle, VehicleKind};
use crate::permutation::permute_rows_in_place;
use flock_protocols::Swarm;
use flock_protocols::error::{ParamError, check};

/// The vehicles of a run: one [`Vehicle`], the agents' states (agents in the simulation's
/// storage order, each [`Vehicle::state_columns`]`.len()` numbers) and the readings of the last
/// step.
#[derive(Debug)]
pub struct Fleet<V> {
    vehicle: DynVehicle<V>,
    width: usize,
    states: Vec<f64>,
    /// Agents that hit each limit during the last step.
    at_limit: Vec<usize>,
    /// The mean over moving agents of ‖(p⁺ − p)/h − u‖ at the last step.
    tracking_error: f64,
    /// Each agent's limits hit and tracking error (`None`: it did not move) at the last step.
    outcomes: Vec<Outcome>,
}

/// One agent's limits hit during a step and its tracking error (`None` when it did not move).
type Outcome = ([bool; MAX_LIMITS], Option<f64>);

/// One agent's place in [`Fleet::advance`]: position, velocity, state and outcome.
type Slot<'a, V> = (((&'a mut V, &'a mut V), &'a mut [f64]), &'a mut Outcome);

/// The most inner steps in one step h (2³²): each agent integrates every one of them, so that more
/// would make a single step of one agent last minutes (issue 49: an inner step of 10⁻³⁰⁰ s never
/// ended).
pub const MAX_INNER_STEPS: f64 = 4_294_967_296.0;

/// Checks that the flock's step `h` is a whole number of `vehicle`'s inner steps, and at most
/// [`MAX_INNER_STEPS`] of them.
///
/// # Errors
/// An inner step that is not positive, that does not divide h, or that divides it into more than
/// [`MAX_INNER_STEPS`] (`vehicle.inner_step`).
pub fn check_inner_step(vehicle: &dyn VehicleKind, h: f64) -> Result<(), ParamError> {
    let inner = vehicle.inner_step();
    check::positive("vehicle.inner_step", inner)?;
    let ratio = h / inner;
    check::require(
        ratio <= MAX_INNER_STEPS,
        "vehicle.inner_step",
        inner,
        &format!(
            "divides the step h = {h} into {ratio:.3e} inner steps, more than the {MAX_INNER_STEPS:.3e} one step may take"
        ),
        &format!(
            "choose an inner step of at least h / {MAX_INNER_STEPS:.0} = {:e} s (the defaults take 1 to 10 per step)",
            h / MAX_INNER_STEPS
        ),
    )?;
    check::require(
        ratio >= 1.0 - WHOLE && (ratio - ratio.round()).abs() <= WHOLE * ratio,
        "vehicle.inner_step",
        inner,
        &format!("does not divide the step h = {h} into whole inner steps"),
        &format!(
            "choose an inner step h / k for a whole k (h / {} = {})",
            ratio.ceil().max(1.0),
            h / ratio.ceil().max(1.0)
        ),
    )
}

/// The most limits a vehicle counts ([`Vehicle::limit_columns`]).
pub const MAX_LIMITS: usize = 8;

/// The relative slack allowed when a step is checked to be a whole number of inner steps.
const WHOLE: f64 = 1e-9;

impl<V: Vector> Fleet<V> {
    /// The fleet of `vehicle` for the agents of `swarm` at step `h`: every agent started in its
    /// vehicle's equilibrium ([`Vehicle::start`], which may change its velocity), or, resuming,
    /// in the `states` given (then `swarm` is already the vehicles' and is kept).
    ///
    /// # Errors
    /// A parameter of the vehicle outside its domain (field `vehicle.…`), a step that is not a
    /// whole number of inner steps (`vehicle.inner_step`), or states of another length or not
    /// finite (`vehicle`).
    pub fn new(
        vehicle: DynVehicle<V>,
        swarm: &mut Swarm<V>,
        h: f64,
        states: Option<Vec<f64>>,
    ) -> Result<Self, ParamError> {
        vehicle.validate().map_err(|e| e.within("vehicle"))?;
        check_inner_step(&*vehicle, h)?;
        let limits = vehicle.limit_columns().len();
        check::require(
            limits <= MAX_LIMITS,
            "vehicle",
            vehicle.name(),
            &format!("counts {limits} limits, more than the {MAX_LIMITS} a fleet records"),
            "count at most 8 limits in the vehicle's limit_columns",
        )?;
        let width = vehicle.state_columns().len();
        let n = swarm.len();
        let states = match states {
            Some(states) => {
                check::require(
                    states.len() == n * width && states.iter().all(|x| x.is_finite()),
                    "vehicle",
                    vehicle.name(),
                    &format!(
                        "was given {} finite state values where {n} agents need {}",
                        states.len(),
                        n * width
                    ),
                    "resume from a checkpoint of the same scenario",
                )?;
                states
            }
            None => {
                let mut states = vec![0.0; n * width];
                let Swarm {
                    positions,
                    velocities,
                } = swarm;
                for ((q, p), state) in positions
                    .iter_mut()
                    .zip(velocities.iter_mut())
                    .zip(states.chunks_exact_mut(width.max(1)))
                {
                    (*q, *p) = vehicle.start(*q, *p, state);
                }
                states
            }
        };
        Ok(Self {
            at_limit: vec![0; vehicle.limit_columns().len()],
            vehicle,
            width,
            states,
            tracking_error: 0.0,
            outcomes: Vec::new(),
        })
    }

    /// The vehicle.
    #[must_use]
    pub fn vehicle(&self) -> &dyn Vehicle<V> {
        &*self.vehicle
    }

    /// Every agent's state, agent i at `states()[i * k..(i + 1) * k]` with k the number of
    /// [`Vehicle::state_columns`] (agents as the simulation stores them:
    /// [`Simulation::vehicle_states`](crate::Simulation::vehicle_states) gives original order).
    #[must_use]
    pub fn states(&self) -> &[f64] {
        &self.states
    }

    /// Moves each agent's vehicle state with the agents: what agent `from(s)` carried goes to
    /// index s, for every s, in place. (The outcomes are rewritten at every step before they
    /// are read, and the readings are sums over all agents.)
    pub(crate) fn permute(&mut self, from: impl Fn(usize) -> usize) {
        permute_rows_in_place(&mut self.states, self.width, from);
    }

    /// One step h of every agent: agent i, if it `moves(i)`, follows the command `commands[i]`
    /// under the external acceleration `disturbance(i)` ([`Vehicle::advance`]); one that does
    /// not keeps its position and state, with zero velocity. Positions are wrapped into a
    /// periodic `domain`. The agents are stored as `numbering` says; the tracking error is their
    /// mean in original order.
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &mut self,
        h: f64,
        domain: &Domain<V>,
        swarm: &mut Swarm<V>,
        commands: &[V],
        disturbance: impl Fn(usize) -> V + Sync,
        moves: impl Fn(usize) -> bool + Sync,
        numbering: &Numbering,
    ) {
        let vehicle = &*self.vehicle;
        let limits = self.at_limit.len();
        let Swarm {
            positions,
            velocities,
        } = swarm;
        let agent = |(i, (((q, p), state), outcome)): (usize, Slot<'_, V>)| {
            *outcome = ([false; MAX_LIMITS], None);
            if !moves(i) {
                *p = V::ZERO;
                return;
            }
            let before = *p;
            let flags = &mut outcome.0[..limits];
            vehicle.advance(h, commands[i], disturbance(i), q, p, state, flags);
            *q = domain.wrap(*q);
            outcome.1 = Some(((*p - before) * (1.0 / h) - commands[i]).length());
        };
        let width = self.width.max(1);
        // one outcome per agent, in a buffer kept from step to step
        self.outcomes
            .resize(positions.len(), ([false; MAX_LIMITS], None));
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            positions
                .par_iter_mut()
                .zip(velocities.par_iter_mut())
                .zip(self.states.par_chunks_mut(width))
                .zip(self.outcomes.par_iter_mut())
                .enumerate()
                .with_min_len(256)
                .for_each(agent);
        }
        #[cfg(not(feature = "parallel"))]
        positions
            .iter_mut()
            .zip(velocities.iter_mut())
            .zip(self.states.chunks_mut(width))
            .zip(self.outcomes.iter_mut())
            .enumerate()
            .for_each(agent);
        self.at_limit.fill(0);
        let (mut sum, mut moving) = (0.0, 0usize);
        for (hit, error) in numbering.ordered(&self.outcomes) {
            for (count, hit) in self.at_limit.iter_mut().zip(hit) {
                *count += usize::from(hit);
            }
            if let Some(error) = error {
                sum += error;
                moving += 1;
            }
        }
        self.tracking_error = if moving == 0 {
            0.0
        } else {
            sum / moving as f64
        };
    }

    /// The vehicles' columns of `metrics.csv`: the agents at each limit during the last step
    /// ([`Vehicle::limit_columns`]), then `acceleration_tracking_error`, the mean over moving
    /// agents of ‖(p⁺ − p)/h − u_i‖, how far the reference point's mean acceleration over the
    /// step was from the command u_i (0 for a point mass; the disturbance counts in it).
    #[must_use]
    pub fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        let mut columns: Vec<(&'static str, f64)> = self
            .vehicle
            .limit_columns()
            .iter()
            .zip(&self.at_limit)
            .map(|(&name, &count)| (name, count as f64))
            .collect();
        columns.push(("acceleration_tracking_error", self.tracking_error));
        columns
    }
}
