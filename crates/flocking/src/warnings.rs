//! The warnings of a valid scenario that is likely to go somewhere the user did not mean
//! ([`Scenario::warnings`], printed by `flocking validate` and `flocking run`, returned by
//! Python's `Scenario.warnings()`), each with its field, its value, why and the fix:
//! - the stability warnings ([`crate::stability`]): a step or a control period too long for the
//!   gains, a delay beyond the consensus bound, agents that start at the same point;
//! - a γ-agent faster than the vehicle can go ([`crate::vehicle::VehicleSpec::top_speed`]): the agents fall
//!   behind it, each at its limit, and the flock breaks into groups;
//! - initial velocities above the vehicle's top speed, which its start clips;
//! - a model of one step run at a step other than its paper's ([`Algorithm::paper_step`]);
//! - a start denser than the α-lattice ([`DenseStart`]), whose close pairs count as collisions
//!   and merges that are the start's, not the gains'.

use flock_protocols::GammaAgent;
use glam::{DVec2, DVec3};

use crate::merging::DenseStart;
use crate::scenario::{Algorithm, Scenario};
use crate::warning::Warning;

impl Scenario {
    /// Every warning of a valid scenario (module documentation), each once.
    #[must_use]
    pub fn warnings(&self) -> Vec<Warning> {
        let mut warnings = self.stability_warnings();
        warnings.extend(self.gamma_speed_warning());
        warnings.extend(self.initial_speed_warning());
        warnings.extend(self.paper_step_warning());
        warnings.extend(DenseStart::of(self).map(|dense| Warning {
            field: "initial.positions".to_owned(),
            value: format!("{} agents", self.agents),
            why: format!(
                "the start is {dense}: the agents start well under d apart, the first records count its close pairs as collisions (and those within 10⁻³ d as merged agents, whatever the gains), and the α-forces throw the crowd apart before it flocks"
            ),
            fix: dense.fix(),
        }));
        warnings
    }

    /// A γ-agent that moves faster than the vehicle's top speed.
    fn gamma_speed_warning(&self) -> Option<Warning> {
        let (limit_field, limit) = self.vehicle.top_speed()?;
        let gamma = self.algorithm.gamma()?;
        let prefix = match self.algorithm {
            Algorithm::Flocking2003(_) => "algorithm.translation.gamma",
            _ => "algorithm.gamma",
        };
        let (field, speed) = match gamma {
            GammaAgent::Static { .. } => return None,
            GammaAgent::ConstantVelocity { velocity, .. } => (
                "velocity",
                velocity.iter().map(|x| x * x).sum::<f64>().sqrt(),
            ),
            GammaAgent::Path { speed, .. } => ("speed", *speed),
        };
        faster(speed, limit).then(|| Warning {
            field: format!("{prefix}.{field}"),
            value: format!("speed {speed:.4}"),
            why: format!(
                "the γ-agent moves faster than the {} can go (vehicle.{limit_field} = {limit}): the agents fall behind it, each at its limit, and the flock breaks into groups",
                self.vehicle.name()
            ),
            fix: format!(
                "move the γ-agent slower than {limit} (fixtures/unicycle_alg2_n50.ron: at half the robots' top speed), or raise vehicle.{limit_field}"
            ),
        })
    }

    /// Initial velocities above the vehicle's top speed, which its start clips (docs/vehicles.md).
    fn initial_speed_warning(&self) -> Option<Warning> {
        let (limit_field, limit) = self.vehicle.top_speed()?;
        let (agent, speed) = match self.dim {
            2 => crate::validate::fastest_agent(crate::initial::initial_velocities::<DVec2>(self)),
            _ => crate::validate::fastest_agent(crate::initial::initial_velocities::<DVec3>(self)),
        }?;
        faster(speed, limit).then(|| Warning {
            field: "initial.velocities".to_owned(),
            value: format!("agent {agent} at speed {speed:.4}"),
            why: format!(
                "is above the {}'s top speed vehicle.{limit_field} = {limit}, to which the vehicle clips every initial speed: the run does not start from the velocities given",
                self.vehicle.name()
            ),
            fix: format!(
                "draw initial velocities of at most {limit} (e.g. `Headings(speed: {limit})`), or raise vehicle.{limit_field}"
            ),
        })
    }

    /// A model of one step run at another step than its paper's.
    fn paper_step_warning(&self) -> Option<Warning> {
        let (paper, source) = self.algorithm.paper_step()?;
        ((self.step - paper).abs() > 1e-9 * paper).then(|| Warning {
            field: "step".to_owned(),
            value: self.step.to_string(),
            why: format!(
                "differs from the step of the model's paper ({source}): the model's rules are per step (one turn, one move and one draw of noise where it has any), so at another step it is another model and the paper's results do not apply"
            ),
            fix: format!(
                "set `step: {paper:?}`, and `duration` to the number of steps wanted × {paper:?}"
            ),
        })
    }
}

/// Whether `speed` is above `limit` by more than round-off (`Headings(speed: 0.22)` draws
/// lengths of 0.22 to within 10⁻¹⁶, which the vehicle does not change).
fn faster(speed: f64, limit: f64) -> bool {
    speed > limit * (1.0 + 1e-9)
}
