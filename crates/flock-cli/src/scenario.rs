//! Scenario files: what a run simulates, read from RON, validated, and written back resolved.
//!
//! A scenario names the dimension, the algorithm and its parameters, the gains, the γ-agent, the
//! initial condition, the step, the duration and how often to record. Every parameter with a value in
//! the papers defaults to it (d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2; TAC 2006 Section VIII).

use std::path::Path;

use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};

use crate::error::ScenarioError;

/// A simulation scenario, as written in a `.ron` file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A short name, used in summaries.
    #[serde(default)]
    pub name: String,
    /// What the scenario reproduces and why its parameters are what they are.
    #[serde(default)]
    pub description: String,
    /// The dimension m of the space: 2 or 3.
    pub dim: usize,
    /// The number of α-agents n ≥ 1.
    pub agents: usize,
    /// Seed of the random initial condition (PCG64 stream).
    #[serde(default)]
    pub seed: u64,
    /// The protocol.
    pub algorithm: Algorithm,
    /// Parameters and gains of the α-interaction.
    #[serde(default)]
    pub alpha: Alpha,
    /// The initial positions and velocities.
    pub initial: Initial,
    /// The integration scheme.
    #[serde(default)]
    pub integrator: IntegratorKind,
    /// The fixed time step h > 0 (the papers use 0.01–0.03 s).
    #[serde(default = "default_step")]
    pub step: f64,
    /// The simulated time T > 0.
    pub duration: f64,
    /// Record metrics and trajectory every this many steps (≥ 1); the last step is always recorded.
    #[serde(default = "default_record_every")]
    pub record_every: u64,
    /// Two agents closer than this collide; default d/4, and at most r.
    #[serde(default)]
    pub collision_distance: Option<f64>,
}

/// The protocol of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Algorithm {
    /// Algorithm 1 of TAC 2006: α-interaction alone.
    Algorithm1,
    /// Algorithm 2 of TAC 2006: α-interaction plus navigational feedback −c₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm2 {
        /// The γ-agent.
        gamma: Gamma,
        /// Position gain c₁ > 0.
        c1: f64,
        /// Velocity gain c₂ > 0.
        c2: f64,
    },
}

/// The γ-agent's trajectory.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Gamma {
    /// A fixed rendezvous point.
    Static {
        /// q_r.
        position: Vec<f64>,
    },
    /// Uniform motion from `position` with `velocity`.
    ConstantVelocity {
        /// q_r(0).
        position: Vec<f64>,
        /// p_r.
        velocity: Vec<f64>,
    },
    /// A polyline travelled at constant speed, then holding at its last waypoint.
    Path {
        /// The waypoints, at least one.
        waypoints: Vec<Vec<f64>>,
        /// The speed > 0.
        speed: f64,
    },
}

/// Parameters of the α-interaction and its gains (Algorithm 3 notation c₁^α, c₂^α; 1 and 1 give
/// Algorithms 1 and 2 exactly).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Alpha {
    /// Lattice distance d > 0.
    pub d: f64,
    /// Interaction range r > d; default 1.2 d.
    pub r: Option<f64>,
    /// σ-norm parameter ε > 0.
    pub epsilon: f64,
    /// Attraction bound a, 0 < a ≤ b.
    pub a: f64,
    /// Repulsion bound b.
    pub b: f64,
    /// Bump parameter h ∈ (0, 1).
    pub h: f64,
    /// Gradient gain c₁^α > 0.
    pub c1: f64,
    /// Consensus gain c₂^α ≥ 0.
    pub c2: f64,
}

impl Default for Alpha {
    fn default() -> Self {
        Self {
            d: 7.0,
            r: None,
            epsilon: 0.1,
            a: 5.0,
            b: 5.0,
            h: 0.2,
            c1: 1.0,
            c2: 1.0,
        }
    }
}

/// The initial condition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    /// Where the agents start.
    pub positions: Cloud,
    /// How fast they start; default at rest.
    #[serde(default)]
    pub velocities: Cloud,
}

/// A set of n vectors: seeded random, or explicit.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Cloud {
    /// All zero.
    #[default]
    Zero,
    /// Uniform in the box [min, max].
    Box {
        /// Lower corner.
        min: Vec<f64>,
        /// Upper corner.
        max: Vec<f64>,
    },
    /// Uniform in the ball of `radius` around `centre`.
    Ball {
        /// Centre.
        centre: Vec<f64>,
        /// Radius > 0.
        radius: f64,
    },
    /// Independent normal components with mean `mean` and standard deviation `std`.
    Gaussian {
        /// Mean.
        mean: Vec<f64>,
        /// Standard deviation > 0.
        std: f64,
    },
    /// One vector per agent.
    Explicit(Vec<Vec<f64>>),
}

/// The integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum IntegratorKind {
    /// Semi-implicit (symplectic) Euler.
    #[default]
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta.
    Rk4,
}

fn default_step() -> f64 {
    0.01
}

fn default_record_every() -> u64 {
    10
}

impl Scenario {
    /// Reads and validates a scenario file.
    ///
    /// # Errors
    /// When the file cannot be read, is not valid RON for a scenario (the error gives the line and
    /// column), or fails [`Scenario::validate`].
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError::io(path, &e))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and validates scenario text; `origin` names it in errors.
    ///
    /// # Errors
    /// As [`Scenario::load`].
    pub fn parse(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        let options = ron::Options::default().with_default_extension(Extensions::IMPLICIT_SOME);
        let scenario: Self = options
            .from_str(text)
            .map_err(|e| ScenarioError::syntax(origin, &e))?;
        scenario.validate()?;
        Ok(scenario.resolved())
    }

    /// The scenario with every default written out (r = 1.2 d, the collision distance d/4).
    #[must_use]
    pub fn resolved(mut self) -> Self {
        let d = self.alpha.d;
        self.alpha.r.get_or_insert(1.2 * d);
        self.collision_distance.get_or_insert(0.25 * d);
        self
    }

    /// The interaction range r.
    #[must_use]
    pub fn range(&self) -> f64 {
        self.alpha.r.unwrap_or(1.2 * self.alpha.d)
    }

    /// The collision distance.
    #[must_use]
    pub fn collision_distance(&self) -> f64 {
        self.collision_distance.unwrap_or(0.25 * self.alpha.d)
    }

    /// The number of steps ⌈T / h⌉ (rounded to the nearest when T/h is within round-off of an integer).
    #[must_use]
    pub fn steps(&self) -> u64 {
        let ratio = self.duration / self.step;
        let nearest = ratio.round();
        if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
            nearest as u64
        } else {
            ratio.ceil() as u64
        }
    }

    /// The protocol-specific columns appended to `metrics.csv` for this scenario.
    #[must_use]
    pub fn extra_columns(&self) -> &'static [&'static str] {
        &[]
    }

    /// The scenario as RON text with every default filled in.
    ///
    /// # Errors
    /// Never for a validated scenario; the RON serializer's error otherwise.
    pub fn to_ron(&self) -> Result<String, ron::Error> {
        let config = ron::ser::PrettyConfig::new().extensions(Extensions::IMPLICIT_SOME);
        ron::ser::to_string_pretty(&self.clone().resolved(), config)
    }
}
