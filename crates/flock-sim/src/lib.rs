//! The loop of a flocking run: a [`Simulation`] advances the agents of a swarm by one step at a
//! time, **fail → sense → communicate → control → actuate → integrate** ([`Simulation::step`]),
//! the laws u_i coming from `flock-protocols` (a [`Protocol`](flock_protocols::Protocol), from
//! what each agent perceives).
//!
//! - [`Simulation`]: the step, fixed-step [`Integrator`]s (symplectic Euler by default, RK4) that
//!   rebuild the proximity net at every evaluation, with the metrics, energy, diagnostics and
//!   health ([`health`]) of the state in the agents' original order; agents numbered at random
//!   stored by cell.
//! - [`Conditions`]: delay, loss, noise, sampled control, actuator limits, wind and faults, run by
//!   the same step ([`Simulation::with_conditions`], [`conditions`]).
//! - [`vehicle`]: agents that are vehicles (unicycle, fixed wing, quadrotor), which follow the
//!   commanded acceleration through their own controller and dynamics.
//!
//! Features: `parallel` (default; rayon, bit-identical results for any thread count),
//! `obstacles` (default; the obstacle protocols of flock-protocols), `serde` (the integrator, the
//! conditions and their checkpointed state read and written as the `flocking` crate's scenarios).

mod agents;
pub mod checks;
pub mod conditions;
pub mod health;
pub mod integrator;
mod permutation;
pub mod simulation;
pub mod step;
mod storage;
pub mod vehicle;

pub use checks::check_vehicle_loop;
pub use conditions::{Conditions, ConditionsState};
pub use health::{AgentFault, Fault};
pub use integrator::Integrator;
pub use simulation::{Observation, Simulation};
pub use step::integrate::advance;
pub use vehicle::{DynVehicle, Fleet, Vehicle, VehicleKind};
