//! Scenario files: what a run simulates, read from RON, validated, and written back resolved.
//!
//! A scenario names the dimension, the algorithm and its parameters, the gains, the γ-agent, the
//! initial condition, the step, the duration and how often to record. Every parameter with a value in
//! the papers defaults to it (d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2; TAC 2006 Section VIII):
//! the defaults are those of the parameter types of `flock-protocols` ([`AlphaConfig`],
//! [`BetaConfig`](flock_protocols::BetaConfig), [`AvoidanceGains`](flock_protocols::AvoidanceGains)), which the scenario composes.

use std::path::Path;
use std::str::FromStr;

use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};

use flock_obstacles::ObstacleSpec;
use flock_protocols::{AlphaConfig, critical_damping};
use flock_sim::{Conditions, Integrator};

pub use crate::algorithm::{
    Algorithm, Algorithm2Params, Algorithm3Params, ConsensusParams, FixedGraph, Flocking2003Params,
    Point, TannerGraph, TannerParams, Translation,
};
use crate::error::ScenarioError;
use crate::vehicle::VehicleSpec;

/// The collision distance as a fraction of d, by default (TAC 2006 counts pairs closer than d/4).
pub const COLLISION_FRACTION: f64 = 0.25;

/// A simulation scenario, as written in a `.ron` file.
///
/// # Example
/// ```
/// use flocking::Scenario;
///
/// let scenario: Scenario = r#"Scenario(
///     dim: 2,
///     agents: 20,
///     algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.05, c2: 0.4),
///     initial: (positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])),
///     duration: 1.0,
/// )"#.parse()?;
/// assert_eq!(scenario.range(), 8.4); // r = 1.2 d, d = 7 by default
/// assert_eq!(scenario.steps(), 100);
/// assert!(scenario.warnings().is_empty());
/// // a bad value is refused with its field, its value, why and the fix
/// let error = "Scenario(dim: 4, agents: 1, algorithm: Algorithm1, initial: (positions: Zero), duration: 1.0)"
///     .parse::<Scenario>()
///     .unwrap_err();
/// assert_eq!(error.field().as_deref(), Some("dim"));
/// # Ok::<(), flocking::ScenarioError>(())
/// ```
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
    /// The space the agents live in: `Open` (the default, not written) or a periodic box.
    #[serde(default, skip_serializing_if = "DomainSpec::is_open")]
    pub domain: DomainSpec,
    /// What each agent is: `PointMass` (the default, not written) or a vehicle whose reference
    /// point follows the protocol's commanded acceleration (docs/vehicles.md).
    #[serde(default, skip_serializing_if = "VehicleSpec::is_point_mass")]
    pub vehicle: VehicleSpec,
    /// Parameters and gains of the α-interaction.
    #[serde(default)]
    pub alpha: AlphaConfig,
    /// The initial positions and velocities.
    pub initial: Initial,
    /// The integration scheme.
    #[serde(default)]
    pub integrator: Integrator,
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
    /// Convex obstacles, seen through β-agents by the algorithms that avoid obstacles.
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
    /// The real conditions of the run (delay, loss, noise, sampled control, actuation limits,
    /// wind, faults; docs/conditions.md), every part optional; absent (and not written) for the
    /// ideal run.
    #[serde(default, skip_serializing_if = "Conditions::is_ideal")]
    pub conditions: Conditions,
    /// The times (s) at which `flocking plot` draws the snapshots: where things happen (a net
    /// becoming a flock, a split, a rejoin), each drawn at the record nearest it (one beyond the
    /// end at the last record); ≥ 0, increasing, at most [`MAX_SNAPSHOTS`]. `None` (not
    /// written): six times spread evenly over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<Vec<f64>>,
}

/// The most snapshot times a scenario may ask for (a figure of three rows of four panels).
pub const MAX_SNAPSHOTS: usize = 12;

/// The arena side of the Vásárhelyi fixture and the default (250 m; see docs/models.md for its
/// source).
pub const VASARHELYI_ARENA_SIDE: f64 = flock_protocols::vasarhelyi2018::ARENA_SIDE;

/// The space of a scenario.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum DomainSpec {
    /// ℝ^m.
    #[default]
    Open,
    /// The torus [0, L₁) × … × [0, L_m): positions wrapped after each step, every distance the
    /// minimum image, the centre of mass the circular mean per axis.
    Periodic {
        /// The sides (L₁, …, L_m), each at least twice the interaction range.
        size: Vec<f64>,
    },
    /// The square or cube periodic box that holds the agents at number `density` ρ: side
    /// L = (n/ρ)^(1/m), so that a sweep over `agents` keeps the density fixed (Vicsek et al. 1995
    /// Fig. 2(a)).
    PeriodicAtDensity {
        /// Agents per unit area (2D) or volume (3D), > 0.
        density: f64,
    },
}

impl DomainSpec {
    /// Whether the domain is open space.
    #[must_use]
    pub fn is_open(&self) -> bool {
        matches!(self, Self::Open)
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
    /// Uniform in the scenario's periodic box (a periodic domain only).
    Domain,
    /// Vectors of one length `speed` in directions uniform on the circle or sphere: the random
    /// headings the constant-speed models start from (Vicsek et al. 1995, Couzin et al. 2002).
    Headings {
        /// The length ≥ 0 of every vector.
        speed: f64,
    },
}

fn default_step() -> f64 {
    0.01
}

fn default_record_every() -> u64 {
    10
}

impl Scenario {
    /// Reads and validates a scenario file. Defaults left unset stay unset (`alpha.r` is `None`
    /// and follows `alpha.d`); [`Scenario::resolved`] fills them in, [`Scenario::to_ron`] keeps them
    /// unset and writes their values in comments.
    ///
    /// # Errors
    /// When the file cannot be read, is not valid RON for a scenario (the error gives the line and
    /// column), or fails [`Scenario::validate`].
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ScenarioError> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|message| ScenarioError::Io {
            path: path.display().to_string(),
            message,
        })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and validates scenario text; `origin` names it in errors.
    ///
    /// # Errors
    /// As [`Scenario::load`].
    pub fn parse(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        let text = crate::input::without_bom(text);
        let scenario: Self = crate::input::ron_options()
            .from_str(text)
            .map_err(|e| ScenarioError::syntax(origin, text, &e))?;
        scenario.validate().map_err(|e| e.placed(origin, text))?;
        Ok(scenario)
    }

    /// The scenario with every default written out (r = 1.2 d, the collision distance d/4, the
    /// gains and distances of Algorithm 3, the flat part of the 2003 influence map).
    #[must_use]
    pub fn resolved(mut self) -> Self {
        let d = self.alpha.d;
        // the α-interaction's r, not the model's own range (Vicsek's r = 1 < d would not validate)
        let r = self.alpha.range();
        self.alpha.r = Some(r);
        self.collision_distance = Some(self.collision_distance());
        match &mut self.algorithm {
            Algorithm::Algorithm3(p) => {
                p.c2.get_or_insert(critical_damping(p.c1));
                p.beta = p.beta.resolved(d);
            }
            Algorithm::Flocking2003(p) => {
                p.delta.get_or_insert(d / r);
            }
            _ => {}
        }
        self
    }

    /// The interaction range r: `alpha.r` (default 1.2 d), or the model's own (Vicsek's r, the
    /// boids' visual distance plus 2 s h, Couzin's r_a, Cucker–Smale's cut-off when it has one,
    /// Vásárhelyi's communication range r_c).
    #[must_use]
    pub fn range(&self) -> f64 {
        match &self.algorithm {
            Algorithm::CuckerSmale(p) => p.cutoff.unwrap_or_else(|| self.alpha.range()),
            Algorithm::Vicsek(p) => p.r,
            Algorithm::Boids(p) => p.visual_distance + 2.0 * p.speed * self.step,
            Algorithm::Couzin(p) => p.r_r + p.delta_r_o + p.delta_r_a,
            Algorithm::Vasarhelyi(p) => p.r_c,
            _ => self.alpha.range(),
        }
    }

    /// The collision distance: as given, or by default d/4 (TAC 2006), and for the models of
    /// their own spacing the boids' `separation`, Couzin's zone of repulsion r_r, Vásárhelyi's
    /// r^coll, and r/4 for Vicsek's point particles.
    #[must_use]
    pub fn collision_distance(&self) -> f64 {
        self.collision_distance
            .unwrap_or_else(|| match &self.algorithm {
                Algorithm::Boids(p) => p.separation.min(self.range()),
                Algorithm::Couzin(p) => p.r_r,
                Algorithm::Vasarhelyi(p) => p.r_coll,
                Algorithm::Vicsek(p) => COLLISION_FRACTION * p.r,
                _ => COLLISION_FRACTION * self.alpha.d,
            })
    }

    /// Whether a run of the scenario draws random numbers as it steps (its algorithm's or its
    /// conditions'; a random initial state is drawn before the first step).
    #[must_use]
    pub fn draws_at_random(&self) -> bool {
        self.algorithm.draws_at_random() || self.conditions.draws_at_random()
    }

    /// Whether a run of the scenario draws random numbers per link (jitter, packet loss that is
    /// not symmetric).
    #[must_use]
    pub fn draws_per_link(&self) -> bool {
        self.conditions.draws_per_link()
    }

    /// Whether a run of the scenario draws normal random numbers as it steps (Couzin's angular
    /// noise, sensing noise, wind gusts, process noise).
    #[must_use]
    pub fn draws_normals(&self) -> bool {
        self.algorithm.draws_normals() || self.conditions.draws_normals()
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

    /// The scenario as RON text. Defaults left unset stay unset, so that a scenario read back
    /// from it still moves them with the values they follow (r with d); each is written resolved in
    /// a comment at the top (`// alpha.r: 8.4 (default 1.2 d)`). Reading the text back gives this
    /// scenario, and writing that gives the same text.
    ///
    /// # Errors
    /// Never for a validated scenario; the RON serializer's error otherwise.
    pub fn to_ron(&self) -> Result<String, ron::Error> {
        let config = ron::ser::PrettyConfig::new().extensions(Extensions::IMPLICIT_SOME);
        let text = ron::ser::to_string_pretty(self, config)?;
        let defaults = self.unset_defaults();
        if defaults.is_empty() {
            return Ok(text);
        }
        let (first, rest) = text.split_once('\n').unwrap_or((&text, ""));
        let mut out = format!(
            "{first}\n// Defaults left unset, which follow the values they depend on; resolved:\n"
        );
        for (path, value) in defaults {
            let rule = match path.as_str() {
                "alpha.r" => "default 1.2 d",
                "collision_distance" => "default d/4",
                "algorithm.c2" => "default 2 √c1, critically damped",
                "algorithm.delta" => "default d/r",
                _ => "default from alpha.d",
            };
            out.push_str(&format!("// {path}: {value} ({rule})\n"));
        }
        out.push_str(rest);
        Ok(out)
    }

    /// The defaults this scenario leaves unset, by path, with the values [`Scenario::resolved`]
    /// gives them.
    #[must_use]
    pub fn unset_defaults(&self) -> Vec<(String, serde_json::Value)> {
        fn walk(
            path: &str,
            unset: &serde_json::Value,
            resolved: &serde_json::Value,
            out: &mut Vec<(String, serde_json::Value)>,
        ) {
            use serde_json::Value;
            match (unset, resolved) {
                (Value::Null, value) if !value.is_null() => {
                    out.push((path.to_owned(), value.clone()));
                }
                (Value::Object(a), Value::Object(b)) => {
                    for (key, value) in a {
                        let inner =
                            if key.starts_with(|c: char| c.is_ascii_uppercase()) && a.len() == 1 {
                                path.to_owned()
                            } else if path.is_empty() {
                                key.clone()
                            } else {
                                format!("{path}.{key}")
                            };
                        if let Some(other) = b.get(key) {
                            walk(&inner, value, other, out);
                        }
                    }
                }
                _ => {}
            }
        }
        let tree = |s: &Self| serde_json::to_value(s).unwrap_or_default();
        let mut out = Vec::new();
        walk("", &tree(self), &tree(&self.clone().resolved()), &mut out);
        out
    }
}

/// Parses and validates scenario text ([`Scenario::parse`] with the origin `<string>`).
impl FromStr for Scenario {
    type Err = ScenarioError;

    fn from_str(text: &str) -> Result<Self, ScenarioError> {
        Self::parse(text, "<string>")
    }
}
