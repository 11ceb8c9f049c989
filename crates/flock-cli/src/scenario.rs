//! Scenario files: what a run simulates, read from RON, validated, and written back resolved.
//!
//! A scenario names the dimension, the algorithm and its parameters, the gains, the γ-agent, the
//! initial condition, the step, the duration and how often to record. Every parameter with a value in
//! the papers defaults to it (d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2; TAC 2006 Section VIII).

use std::path::Path;

use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};

use flock_obstacles::ObstacleSpec;

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
    /// Convex obstacles, seen through β-agents by the algorithms that avoid obstacles.
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
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
    /// Algorithm 3 of TAC 2006: α-interaction, β-agents on the scenario's obstacles, and the bounded
    /// navigational feedback −c₁ σ₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm3 {
        /// The γ-agent.
        gamma: Gamma,
        /// Position gain c₁^γ > 0.
        c1: f64,
        /// Velocity gain c₂^γ > 0; default 2√c₁^γ (critically damped).
        #[serde(default)]
        c2: Option<f64>,
        /// The β-interaction.
        #[serde(default)]
        beta: Beta,
    },
    /// The 2003 (α, α) protocols (Caltech CDS 03-006, eq. 34–36) with the potential of eq. 29
    /// (`alpha.a < alpha.b`), an optional translational controller (sink, eq. 50, or velocity
    /// tracking) and optional avoidance of the scenario's ball obstacles (eq. 54–58).
    Flocking2003 {
        /// Which of the three protocols.
        form: Form2003,
        /// The consensus gain c₁ ≥ 0 of Σ_j (p_j − p_i).
        c1: f64,
        /// The flat part δ ∈ (0, 1) of the influence map ρ; default d/r.
        #[serde(default)]
        delta: Option<f64>,
        /// The power k ≥ 1 of the influence map (C^k smooth).
        #[serde(default = "default_power")]
        power: i32,
        /// The translational controller −c₁(q_i − q_r) − c₂(p_i − p_r) to a γ-agent.
        #[serde(default)]
        translation: Option<Translation>,
        /// β- and γ-agents on the scenario's obstacles (balls only).
        #[serde(default)]
        avoidance: Option<Avoidance2003>,
    },
    /// The Tanner–Jadbabaie–Pappas law on a fixed connected graph (seed 001 eq. 5), with the pair
    /// potential d²/z² + ln(z²/d²) − 1 of desired distance `alpha.d`.
    Tanner {
        /// The neighbouring graph.
        #[serde(default)]
        graph: TannerGraph,
    },
}

/// Which 2003 (α, α) protocol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Form2003 {
    /// (α, α, 1), eq. 34: 0/1 adjacency.
    Nonsmooth,
    /// (α, α, 2), eq. 35: smooth adjacency with its ρ′ term.
    Smooth,
    /// eq. 36: (α, α, 2) without the ρ′ term.
    Approximate,
}

/// A translational controller of the 2003 protocols: a sink (static γ-agent, eq. 50) or velocity
/// tracking (a γ-agent in uniform motion with c₁ = 0, eq. 65–66).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Translation {
    /// The γ-agent (q_d, p_d).
    pub gamma: Gamma,
    /// Position gain c₁ ≥ 0.
    pub c1: f64,
    /// Velocity gain c₂ > 0.
    pub c2: f64,
}

/// The β/γ construction of the 2003 obstacle protocol (seed 004 eq. 54).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Avoidance2003 {
    /// Gain c₃ > 0 of the β/γ position terms (the seed asks c₃ ≫ 1).
    pub c3: f64,
    /// Gain c₄ ≥ 0 of the velocity term c₄(p̂ − p_i).
    pub c4: f64,
    /// λ_d ∈ (0, 1]: the γ-agent of obstacle k sits at b_k + λ_d n_d.
    pub lambda_d: f64,
}

impl Default for Avoidance2003 {
    fn default() -> Self {
        Self {
            c3: 10.0,
            c4: 1.0,
            lambda_d: 1.0,
        }
    }
}

/// The fixed graph of the Tanner law.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum TannerGraph {
    /// A random spanning tree plus every other pair with probability `extra`, from the scenario's seed.
    Random {
        /// Probability of each extra edge, in [0, 1].
        extra: f64,
    },
    /// The given undirected edges (i, j); the graph must be connected.
    Edges(Vec<(usize, usize)>),
}

impl Default for TannerGraph {
    fn default() -> Self {
        Self::Random { extra: 0.2 }
    }
}

fn default_power() -> i32 {
    1
}

/// Parameters and gains of Algorithm 3's β-interaction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Beta {
    /// Desired distance d′ to obstacles; default 0.6 d.
    pub d: Option<f64>,
    /// β-neighbour range r′ > d′; default 1.2 d′.
    pub r: Option<f64>,
    /// Bump parameter h ∈ (0, 1) of φ_β and b_ik.
    pub h: f64,
    /// Repulsion gain c₁^β > 0.
    pub c1: f64,
    /// Damping gain c₂^β ≥ 0; default 2√c₁^β.
    pub c2: Option<f64>,
}

impl Default for Beta {
    fn default() -> Self {
        Self {
            d: None,
            r: None,
            h: 0.9,
            c1: 10.0,
            c2: None,
        }
    }
}

impl Beta {
    /// d′ for lattice distance `d` (default 0.6 d).
    #[must_use]
    pub fn distance(&self, d: f64) -> f64 {
        self.d.unwrap_or(0.6 * d)
    }

    /// r′ for lattice distance `d` (default 1.2 d′).
    #[must_use]
    pub fn range(&self, d: f64) -> f64 {
        self.r.unwrap_or(1.2 * self.distance(d))
    }

    /// c₂^β (default 2√c₁^β).
    #[must_use]
    pub fn damping(&self) -> f64 {
        self.c2.unwrap_or(critical_damping(self.c1))
    }
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

/// The columns of obstacle runs: the smallest agent–obstacle clearance and the agents inside.
pub const OBSTACLE_COLUMNS: [&str; 2] = ["obstacle_clearance", "inside_obstacles"];

/// The columns of Tanner runs: ½ Σ ‖v_i − v̄‖² and the smallest distance between linked agents.
pub const TANNER_COLUMNS: [&str; 2] = ["velocity_disagreement", "min_linked_distance"];

/// c₂ = 2√c₁, the critically damped gain of TAC 2006 Section VIII.
#[must_use]
pub fn critical_damping(c1: f64) -> f64 {
    2.0 * c1.sqrt()
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
            .map_err(|e| ScenarioError::syntax(origin, text, &e))?;
        scenario.validate()?;
        Ok(scenario.resolved())
    }

    /// The scenario with every default written out (r = 1.2 d, the collision distance d/4).
    #[must_use]
    pub fn resolved(mut self) -> Self {
        let d = self.alpha.d;
        self.alpha.r.get_or_insert(1.2 * d);
        self.collision_distance.get_or_insert(0.25 * d);
        if let Algorithm::Algorithm3 { c1, c2, beta, .. } = &mut self.algorithm {
            c2.get_or_insert(critical_damping(*c1));
            *beta = Beta {
                d: Some(beta.distance(d)),
                r: Some(beta.range(d)),
                c2: Some(beta.damping()),
                ..*beta
            };
        }
        let r = self.range();
        if let Algorithm::Flocking2003 { delta, .. } = &mut self.algorithm {
            delta.get_or_insert(d / r);
        }
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
    pub fn extra_columns(&self) -> Vec<&'static str> {
        let mut columns = Vec::new();
        if !self.obstacles.is_empty() {
            columns.extend(OBSTACLE_COLUMNS);
        }
        if matches!(self.algorithm, Algorithm::Tanner { .. }) {
            columns.extend(TANNER_COLUMNS);
        }
        columns
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
