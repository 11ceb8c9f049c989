//! A scenario's `vehicle`: what each agent is, `PointMass` (the double integrator of the papers,
//! the default, not written) or a vehicle of [`flock_sim::vehicle`] whose reference point
//! follows the protocol's commanded acceleration (docs/vehicles.md).

use flock_sim::DynVehicle;
use flock_sim::vehicle::{
    FixedWing, FixedWingParams, Quadrotor, QuadrotorParams, Unicycle, UnicycleParams,
};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::ScenarioError;

/// The vehicle of a scenario's agents. A vehicle holds its parameters as the scenario's other
/// optional sections do (`Some((…))`): `vehicle: Quadrotor(())` for the defaults,
/// `vehicle: Unicycle((handle: 0.1, max_speed: 0.3))` to change some.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum VehicleSpec {
    /// The double integrator q̇ = p, ṗ = u (TAC 2006 eq. 1): today's agents, bit for bit.
    #[default]
    PointMass,
    /// A ground robot in 2D: the kinematic unicycle (differential drive) whose handle, ℓ ahead
    /// of its axle, is the reference point; defaults of a TurtleBot3 Burger.
    Unicycle(UnicycleParams),
    /// A fixed-wing aircraft in 2D or 3D: Beard & McLain's guidance model (2012, ch. 9),
    /// airspeed in [V_min, V_max], coordinated turns with a bank limit, flight-path angle in 3D.
    FixedWing(FixedWingParams),
    /// A quadrotor in 3D: the rigid body on SE(3) with four rotors under the geometric tracking
    /// controller of Lee, Leok & McClamroch (CDC 2010), the command its feed-forward; the
    /// parameters default to a Crazyflie 2.x ([`QuadrotorParams::crazyflie`]).
    Quadrotor(QuadrotorParams),
}

impl VehicleSpec {
    /// Whether the agents are point masses (the default, not written in a resolved scenario).
    #[must_use]
    pub fn is_point_mass(&self) -> bool {
        *self == Self::PointMass
    }

    /// The vehicle's name as a scenario writes it.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::PointMass => "PointMass",
            Self::Unicycle(_) => "Unicycle",
            Self::FixedWing(_) => "FixedWing",
            Self::Quadrotor(_) => "Quadrotor",
        }
    }

    /// The fastest the vehicle's reference point can go on a straight line, with the field
    /// (relative to `vehicle`) that sets it: the unicycle's `max_speed`, or its
    /// `max_wheel_speed` when lower (driving straight, both wheels turn at v); the fixed wing's
    /// `max_airspeed`. `None` for point masses and the quadrotor, whose limits are its thrust
    /// and tilt, not a speed.
    #[must_use]
    pub fn top_speed(&self) -> Option<(&'static str, f64)> {
        match self {
            Self::Unicycle(p) => Some(match (p.track_width, p.max_wheel_speed) {
                (Some(_), Some(wheel)) if wheel < p.max_speed => ("max_wheel_speed", wheel),
                _ => ("max_speed", p.max_speed),
            }),
            Self::FixedWing(p) => Some(("max_airspeed", p.max_airspeed)),
            Self::PointMass | Self::Quadrotor(_) => None,
        }
    }

    /// The vehicle's inner step δ (s), `None` for point masses.
    #[must_use]
    pub const fn inner_step(&self) -> Option<f64> {
        match self {
            Self::PointMass => None,
            Self::Unicycle(params) => Some(params.inner_step),
            Self::FixedWing(params) => Some(params.inner_step),
            Self::Quadrotor(params) => Some(params.inner_step),
        }
    }

    /// The inner steps δ of the vehicle in a step `h` (each agent integrates every one: the work
    /// of one step is agents × inner steps); 0 for point masses.
    #[must_use]
    pub fn inner_steps(&self, h: f64) -> f64 {
        self.inner_step()
            .map_or(0.0, |delta| (h / delta).round().max(1.0))
    }

    /// The names of each agent's vehicle state in `dim` dimensions (columns of `final.csv`, the
    /// trajectory and the checkpoint after the reference point's), empty for point masses or a
    /// vehicle that does not exist in `dim` dimensions.
    #[must_use]
    pub fn state_columns(&self, dim: usize) -> &'static [&'static str] {
        match dim {
            2 => DVec2::vehicle(self)
                .ok()
                .flatten()
                .map_or(&[][..], |v| v.state_columns()),
            _ => DVec3::vehicle(self)
                .ok()
                .flatten()
                .map_or(&[][..], |v| v.state_columns()),
        }
    }
}

impl VehicleSpec {
    /// The direction each vehicle points ([`Vehicle::heading`](flock_sim::Vehicle::heading)),
    /// `dim` numbers per agent, from the reference points' `velocities` (`dim` per agent) and the
    /// vehicles' `states`; `None` for point masses (they point along their velocity).
    #[must_use]
    pub fn headings(&self, dim: usize, velocities: &[f64], states: &[f64]) -> Option<Vec<f64>> {
        match dim {
            2 => headings::<DVec2>(self, velocities, states),
            _ => headings::<DVec3>(self, velocities, states),
        }
    }
}

/// [`VehicleSpec::headings`] in the dimension of `V`.
fn headings<V: VehicleSpace>(
    spec: &VehicleSpec,
    velocities: &[f64],
    states: &[f64],
) -> Option<Vec<f64>> {
    let vehicle = V::vehicle(spec).ok().flatten()?;
    let width = vehicle.state_columns().len().max(1);
    let rows = velocities
        .chunks_exact(V::DIM)
        .zip(states.chunks_exact(width))
        .flat_map(|(p, state)| {
            let e = vehicle.heading(V::from_fn(|k| p[k]), state);
            (0..V::DIM).map(move |k| e.coord(k))
        });
    Some(rows.collect())
}

/// The vehicles of a dimension: [`VehicleSpace::vehicle`] builds a scenario's vehicle for
/// `Self`, or says that it does not exist in this dimension.
pub trait VehicleSpace: flock_math::Vector + Sized {
    /// The vehicle `spec` in this dimension; `None` for point masses.
    ///
    /// # Errors
    /// A vehicle that does not exist in this dimension (field `vehicle`).
    fn vehicle(spec: &VehicleSpec) -> Result<Option<DynVehicle<Self>>, ScenarioError>;
}

impl VehicleSpace for DVec2 {
    fn vehicle(spec: &VehicleSpec) -> Result<Option<DynVehicle<Self>>, ScenarioError> {
        match spec {
            VehicleSpec::PointMass => Ok(None),
            VehicleSpec::Unicycle(params) => boxed(Unicycle::new(*params)),
            VehicleSpec::FixedWing(params) => boxed(FixedWing::new(*params)),
            VehicleSpec::Quadrotor(_) => Err(not_in(spec, 2, "set dim: 3")),
        }
    }
}

impl VehicleSpace for DVec3 {
    fn vehicle(spec: &VehicleSpec) -> Result<Option<DynVehicle<Self>>, ScenarioError> {
        match spec {
            VehicleSpec::PointMass => Ok(None),
            VehicleSpec::Unicycle(_) => Err(not_in(spec, 3, "set dim: 2")),
            VehicleSpec::FixedWing(params) => boxed(FixedWing::new(*params)),
            VehicleSpec::Quadrotor(params) => boxed(Quadrotor::new(*params)),
        }
    }
}

/// A vehicle built from its parameters, boxed; their error inside `vehicle`.
fn boxed<V: flock_math::Vector, T: flock_sim::Vehicle<V> + 'static>(
    vehicle: Result<T, flock_protocols::ParamError>,
) -> Result<Option<DynVehicle<V>>, ScenarioError> {
    match vehicle {
        Ok(vehicle) => Ok(Some(Box::new(vehicle))),
        Err(e) => Err(e.within("vehicle").into()),
    }
}

/// The error of a vehicle that does not exist in `dim` dimensions.
fn not_in(spec: &VehicleSpec, dim: usize, fix: &str) -> ScenarioError {
    ScenarioError::invalid(
        "vehicle",
        spec.name(),
        format!("does not exist in {dim}D"),
        format!("{fix}, or choose another vehicle (docs/vehicles.md)"),
    )
}
