//! What a run's loop refuses, each refusal written once: the scenario's validation, the builder of
//! a simulation and the simulation itself call these and no other text.
//!
//! - [`check_acceleration_conditions`]: a condition that acts on an acceleration, for a model
//!   that sets velocities.
//! - [`check_local_form`]: a condition that changes what agents perceive, for a protocol with no
//!   local form.
//! - [`check_vehicle_loop`], [`check_vehicle`]: a vehicle in a loop that cannot drive it, and the
//!   conditions a vehicle cannot take.

use flock_protocols::ParamError;

use crate::conditions::{Conditions, FaultMode};
use crate::integrator::Integrator;
use crate::vehicle::VehicleKind;

/// The field of a condition that acts on an acceleration (actuation limits and lag, wind,
/// process noise), which a model that sets velocities cannot take.
#[must_use]
pub fn acceleration_field(conditions: &Conditions) -> Option<&'static str> {
    if conditions.actuation.is_some() {
        Some("conditions.actuation")
    } else if conditions.disturbance.is_some() {
        Some("conditions.disturbance")
    } else {
        None
    }
}

/// Whether `conditions` change what agents perceive (their own or others' states), and the
/// field that does.
#[must_use]
pub fn perception_field(conditions: &Conditions) -> Option<&'static str> {
    if conditions.communication.is_some() {
        Some("conditions.communication")
    } else if conditions.sensing.is_some() {
        Some("conditions.sensing")
    } else {
        match &conditions.faults {
            Some(f) if f.mode != FaultMode::Frozen => Some("conditions.faults.mode"),
            _ => None,
        }
    }
}

/// Refuses a condition that acts on an acceleration ([`acceleration_field`]) for a model that
/// sets its agents' velocities (`sets_velocity`, [`Update::sets_velocity`](flock_protocols::Update::sets_velocity)).
///
/// # Errors
/// The condition's field, why and the conditions that do apply.
pub fn check_acceleration_conditions(
    sets_velocity: bool,
    conditions: &Conditions,
) -> Result<(), ParamError> {
    match acceleration_field(conditions) {
        Some(field) if sets_velocity => Err(ParamError::new(
            field,
            "set",
            "acts on an acceleration, and this model sets its agents' velocities directly",
            "remove this condition for this model (delay, loss, range, sensing noise, sampled control and faults apply)",
        )),
        _ => Ok(()),
    }
}

/// Refuses a condition that changes what agents perceive ([`perception_field`]) for a protocol
/// with no local form (`has_local_form`: u_i from what agent i perceives,
/// [`LocalForm`](flock_protocols::LocalForm)).
///
/// # Errors
/// The condition's field, why (the protocol needs the whole flock's state) and the fix.
pub fn check_local_form(conditions: &Conditions, has_local_form: bool) -> Result<(), ParamError> {
    match perception_field(conditions) {
        Some(field) if !has_local_form => Err(ParamError::new(
            field,
            "set",
            "makes each agent perceive its own world (delayed, lost, noisy or missing neighbours), \
             but this algorithm has no local form: it needs the whole flock's state (a centralised \
             controller), which no agent perceives",
            "remove this condition, or choose a distributed algorithm (Algorithm1-3, Flocking2003, \
             Tanner, Consensus)",
        )),
        _ => Ok(()),
    }
}

/// Refuses a `vehicle` in a loop that cannot drive it: a protocol that sets velocities
/// ([`Update::sets_velocity`](flock_protocols::Update::sets_velocity): it has no acceleration to
/// command), or the `integrator` RK4 (a vehicle integrates its own dynamics at its inner step).
///
/// # Errors
/// The field refused: `vehicle` or `integrator`.
pub fn check_vehicle_loop(
    sets_velocity: bool,
    integrator: Integrator,
    vehicle: &dyn VehicleKind,
) -> Result<(), ParamError> {
    if sets_velocity {
        return Err(ParamError::new(
            "vehicle",
            vehicle.name(),
            "needs a commanded acceleration, and this model sets its agents' velocities directly",
            "use vehicle: PointMass for this model, or an acceleration protocol",
        ));
    }
    if integrator == Integrator::Rk4 {
        return Err(ParamError::new(
            "integrator",
            "Rk4",
            "is not used with a vehicle, which integrates its own dynamics at its inner step",
            "remove integrator (or write SymplecticEuler) with this vehicle",
        ));
    }
    Ok(())
}

/// Refuses the conditions a `vehicle` cannot take: a disturbance for a vehicle that takes no
/// external acceleration, and a speed limit, which the vehicle's own limits replace.
///
/// # Errors
/// The field of the condition refused.
pub fn check_vehicle(conditions: &Conditions, vehicle: &dyn VehicleKind) -> Result<(), ParamError> {
    if conditions.disturbance.is_some() && !vehicle.takes_disturbance() {
        return Err(ParamError::new(
            "conditions.disturbance",
            "set",
            format!(
                "is an external acceleration, and a {} takes none on its reference point",
                vehicle.name()
            ),
            "remove the disturbance for this vehicle, or use one that takes it (PointMass, Quadrotor)",
        ));
    }
    if conditions.actuation.and_then(|a| a.max_speed).is_some() {
        return Err(ParamError::new(
            "conditions.actuation.max_speed",
            "set",
            format!(
                "clips a point mass's speed; a {}'s own limits bound its speed",
                vehicle.name()
            ),
            "remove max_speed and set the vehicle's speed limits",
        ));
    }
    Ok(())
}
