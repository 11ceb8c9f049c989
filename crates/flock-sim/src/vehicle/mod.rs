//! Vehicles: the **actuate and integrate** part of the loop (fail → sense → communicate →
//! control → actuate → integrate) for agents that are not point masses.
//!
//! A protocol's output u_i is the commanded acceleration of agent i's *reference point* (the
//! handle ahead of a ground robot's axle, an aircraft's or a quadrotor's centre of mass). A
//! [`Vehicle`] turns it into the vehicle's own inputs through its low-level controller, and
//! integrates the vehicle's dynamics over the flock's step h at its own inner step δ (h a whole
//! number of inner steps). The swarm's state (q_i, p_i) is the reference point's position and
//! velocity; everything else a vehicle carries (heading, attitude, rates, rotor speeds, bank…)
//! is its per-agent `state`, named by [`Vehicle::state_columns`].
//!
//! Without a vehicle an agent is today's point mass, the double integrator q̇ = p, ṗ = u
//! (TAC 2006 eq. 1).

use flock_math::Vector;
use flock_math::interrupt::{BLOCK, cuts_short};

use flock_protocols::ParamError;

pub mod fixed_wing;
pub mod fleet;
pub mod quadrotor;
pub mod unicycle;

pub use fixed_wing::{FixedWing, FixedWingParams};
pub use fleet::{Fleet, check_inner_step};
pub use quadrotor::{Quadrotor, QuadrotorParams};
pub use unicycle::{Unicycle, UnicycleParams};

/// The acceleration of gravity g (m/s²), along −e3 in the flock's z-up coordinates (the value
/// Beard & McLain's simulations and gym-pybullet-drones take).
pub const GRAVITY: f64 = 9.81;

/// A vehicle's dynamics and the controller that makes its reference point follow a commanded
/// acceleration. One value serves every agent; each agent's state is a slice of
/// [`Vehicle::state_columns`]`.len()` numbers.
///
/// A vehicle is implemented for the dimensions it exists in (a ground robot in the plane, a
/// quadrotor in space).
pub trait Vehicle<V: Vector>: VehicleKind {
    /// The names of an agent's state beyond its reference point's position and velocity, in the
    /// order of the `state` slices: columns of `final.csv`, of the trajectory and of the
    /// checkpoint (`heading`, `bank`, `attitude_w`, `rotor_speed_1`, …).
    fn state_columns(&self) -> &'static [&'static str];

    /// The names of the vehicle's limits (`at_speed_limit`, `at_thrust_limit`, `at_tilt_limit`,
    /// …): one `metrics.csv` column each, the number of agents that hit that limit during the
    /// last step.
    fn limit_columns(&self) -> &'static [&'static str];

    /// An agent at the start of a run: its state in equilibrium (at rest on the ground, in hover,
    /// in level flight) with its reference point at `q`, moving with `p`. Writes `state` and
    /// returns the reference point's position and velocity, changed where the vehicle cannot
    /// have them (a fixed wing flies at least at its stall speed).
    fn start(&self, q: V, p: V, state: &mut [f64]) -> (V, V);

    /// One agent over a step `h` (a whole number of inner steps) under the commanded acceleration
    /// `command` of its reference point, held over the step, and the external acceleration
    /// `disturbance` (zero unless [`VehicleKind::takes_disturbance`]): advances `q`, `p` and
    /// `state`, and sets `limits[k]` for every limit k of [`Vehicle::limit_columns`] the vehicle
    /// hit during the step (it never clears one).
    #[allow(clippy::too_many_arguments)]
    fn advance(
        &self,
        h: f64,
        command: V,
        disturbance: V,
        q: &mut V,
        p: &mut V,
        state: &mut [f64],
        limits: &mut [bool],
    );

    /// The unit vector along which the vehicle points (its body's forward axis), from its
    /// reference point's velocity `p` and its `state`: the figures' oriented marker.
    fn heading(&self, p: V, state: &[f64]) -> V;
}

/// What a vehicle is in every dimension it exists in: its name, its parameters, its inner step
/// and whether it takes an external acceleration.
pub trait VehicleKind: Sync + Send + core::fmt::Debug {
    /// The vehicle's name as a scenario writes it (`Unicycle`, `FixedWing`, `Quadrotor`).
    fn name(&self) -> &'static str;

    /// Checks every parameter, naming the field (relative to the vehicle: `max_speed`,
    /// `motor_time_constant`), the value and the fix.
    ///
    /// # Errors
    /// The first parameter outside its domain.
    fn validate(&self) -> Result<(), ParamError>;

    /// The inner step δ (s) at which the dynamics are integrated; the flock's step h must be a
    /// whole number of inner steps.
    fn inner_step(&self) -> f64;

    /// Whether the vehicle takes an external acceleration (wind, process noise) on its reference
    /// point ([`Vehicle::advance`]'s `disturbance`). A vehicle that cannot (a ground robot whose
    /// wheels do not slip) is refused the `disturbance` condition.
    fn takes_disturbance(&self) -> bool;
}

/// The number of inner steps δ in the flock's step h (at least one; none for an h that is not
/// positive and finite).
#[must_use]
pub(crate) fn inner_steps(h: f64, delta: f64) -> usize {
    if h > 0.0 && h.is_finite() {
        ((h / delta).round() as usize).max(1)
    } else {
        0
    }
}

/// The inner steps 0, 1, …, `n` − 1 of one step, ending early once an interrupt cuts the step
/// short ([`flock_math::interrupt`], checked every [`BLOCK`] inner steps): the one loop of every
/// vehicle's inner steps.
pub(crate) fn inner_loop(n: usize) -> impl Iterator<Item = usize> {
    (0..n).take_while(|k| k % BLOCK != 0 || !cuts_short())
}

/// A vehicle chosen at run time.
pub type DynVehicle<V> = Box<dyn Vehicle<V>>;
