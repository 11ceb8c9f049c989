//! Validation of a parsed scenario: every value inside the domain the theory needs. The domain of
//! each parameter type is checked by the type itself (`flock-protocols`: [`AlphaConfig`],
//! [`BetaConfig`], [`AvoidanceGains`], [`GammaAgent`]); this module adds what only the whole
//! scenario knows (the dimension of its vectors, its agents, obstacles and graph).
//!
//! [`AlphaConfig`]: flock_protocols::AlphaConfig
//! [`BetaConfig`]: flock_protocols::BetaConfig
//! [`AvoidanceGains`]: flock_protocols::AvoidanceGains

use flock_graph::{Components, Graph};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::check::{self, Check, length, non_negative, positive, require};
use flock_protocols::{GammaAgent, ParamError};
use glam::{DVec2, DVec3};

use crate::error::ScenarioError;
use crate::initial::initial_swarm;
use crate::scenario::{Algorithm, Cloud, Point, Scenario, TannerGraph};
use crate::stability::coincident_start;

/// The most agents accepted: flocking keeps about 250 bytes per agent (docs/performance.md).
pub const MAX_AGENTS: usize = 100_000_000;

/// `v` has `dim` finite coordinates within ±10⁹.
fn vector(field: &str, v: &[f64], dim: usize) -> Check {
    require(
        v.len() == dim,
        field,
        v,
        &format!(
            "has {} components but the scenario has dim = {dim}",
            v.len()
        ),
        &format!(
            "give exactly {dim} numbers, e.g. [{}]",
            vec!["0.0"; dim].join(", ")
        ),
    )?;
    check::coordinates(field, v)
}

impl Scenario {
    /// Checks every value against its domain.
    ///
    /// # Errors
    /// The first invalid value, with its field, why and the fix.
    pub fn validate(&self) -> Result<(), ScenarioError> {
        self.validate_values().map_err(ScenarioError::from)?;
        if matches!(self.algorithm, Algorithm::Tanner { .. }) {
            self.validate_distinct_start()?;
        }
        self.validate_obstacles()
    }

    /// Everything but what needs the initial state or the obstacles built.
    fn validate_values(&self) -> Check {
        let dim = self.dim;
        require(
            dim == 2 || dim == 3,
            "dim",
            dim,
            "flocking simulates the plane or space",
            "set dim: 2 or dim: 3",
        )?;
        require(
            self.agents >= 1,
            "agents",
            self.agents,
            "a flock needs at least one agent",
            "set agents to n ≥ 1",
        )?;
        require(
            self.agents <= MAX_AGENTS,
            "agents",
            self.agents,
            &format!(
                "exceeds {MAX_AGENTS}: at about 250 bytes per agent the state alone needs {:.0} GB",
                self.agents as f64 * 250e-9
            ),
            "split the swarm into runs of at most 10^8 agents",
        )?;
        self.alpha.validate().map_err(|e| e.within("alpha"))?;
        positive("step", self.step)?;
        positive("duration", self.duration)?;
        require(
            self.step <= self.duration,
            "step",
            self.step,
            &format!("is longer than the duration {}", self.duration),
            "choose a step smaller than the duration (the papers use 0.01–0.03 s)",
        )?;
        require(
            self.record_every >= 1,
            "record_every",
            self.record_every,
            "must be ≥ 1",
            "record every 1 or more steps",
        )?;
        if let Some(c) = self.collision_distance {
            positive("collision_distance", c)?;
            require(
                c <= self.range(),
                "collision_distance",
                c,
                &format!("exceeds the interaction range r = {}", self.range()),
                "choose a collision distance at most r (default d/4)",
            )?;
        }
        self.validate_algorithm()?;
        self.validate_cloud("initial.positions", &self.initial.positions)?;
        self.validate_cloud("initial.velocities", &self.initial.velocities)
    }

    fn validate_algorithm(&self) -> Check {
        let within = |prefix: &'static str| move |e: ParamError| e.within(prefix);
        match &self.algorithm {
            Algorithm::Algorithm1 => Ok(()),
            Algorithm::Algorithm2 { gamma, c1, c2 } => {
                positive("algorithm.c1", *c1)?;
                positive("algorithm.c2", *c2)?;
                self.validate_gamma("algorithm.gamma", gamma)
            }
            Algorithm::Algorithm3 {
                gamma,
                c1,
                c2,
                beta,
            } => {
                positive("algorithm.c1", *c1)?;
                if let Some(c2) = c2 {
                    positive("algorithm.c2", *c2)?;
                }
                self.validate_gamma("algorithm.gamma", gamma)?;
                beta.validate(self.alpha.d)
                    .map_err(within("algorithm.beta"))
            }
            Algorithm::Flocking2003 {
                c1,
                delta,
                power,
                translation,
                avoidance,
                ..
            } => {
                non_negative("algorithm.c1", *c1)?;
                require(
                    self.alpha.a < self.alpha.b,
                    "alpha.a",
                    self.alpha.a,
                    &format!(
                        "must be below alpha.b = {}: the 2003 potential (eq. 29) needs b > a > 0",
                        self.alpha.b
                    ),
                    "use e.g. a: 1.0, b: 5.0",
                )?;
                if let Some(delta) = delta {
                    check::unit_interval("algorithm.delta", *delta)?;
                }
                require(
                    *power >= 1,
                    "algorithm.power",
                    power,
                    "the influence map needs k ≥ 1",
                    "use power: 1 (C¹) or more",
                )?;
                if let Some(t) = translation {
                    non_negative("algorithm.translation.c1", t.c1)?;
                    positive("algorithm.translation.c2", t.c2)?;
                    self.validate_gamma("algorithm.translation.gamma", &t.gamma)?;
                }
                if let Some(a) = avoidance {
                    a.validate().map_err(within("algorithm.avoidance"))?;
                    for (k, spec) in self.obstacles.iter().enumerate() {
                        require(
                            matches!(spec, ObstacleSpec::Ball { .. }),
                            &format!("obstacles[{k}]"),
                            spec.kind(),
                            "the 2003 obstacle protocol handles balls only (seed 004 § 11)",
                            "use Ball obstacles, or Algorithm3 for other convex shapes",
                        )?;
                    }
                }
                Ok(())
            }
            Algorithm::Tanner { graph } => match graph {
                TannerGraph::Random { extra } => {
                    check::finite("algorithm.graph.extra", *extra)?;
                    require(
                        (0.0..=1.0).contains(extra),
                        "algorithm.graph.extra",
                        extra,
                        "is a probability",
                        "use a value in [0, 1]",
                    )
                }
                TannerGraph::Edges(edges) => {
                    let graph = Graph::from_edges(self.agents, edges).map_err(|e| {
                        ParamError::new(
                            "algorithm.graph",
                            edges.len(),
                            e.to_string(),
                            "list edges (i, j) with i ≠ j < agents",
                        )
                    })?;
                    let components = Components::of(&graph).count();
                    require(
                        components == 1,
                        "algorithm.graph",
                        format!("{components} components"),
                        "the Tanner law needs a connected graph",
                        "add edges joining the components",
                    )
                }
            },
        }
    }

    /// No two agents of a Tanner scenario start at the same point, where the potential
    /// d²/z² + ln(z²/d²) − 1 of a linked pair is infinite.
    fn validate_distinct_start(&self) -> Result<(), ScenarioError> {
        match coincident_start(self) {
            None => Ok(()),
            Some((i, j)) => Err(ScenarioError::invalid(
                "initial.positions",
                format!("agents {i} and {j}"),
                "start at the same point, where the Tanner potential d²/z² + ln(z²/d²) − 1 of a linked pair is infinite",
                "give every agent its own position",
            )),
        }
    }

    /// Obstacles are well formed in the scenario's dimension, seen by the algorithm, and no agent
    /// starts inside one.
    fn validate_obstacles(&self) -> Result<(), ScenarioError> {
        if self.obstacles.is_empty() {
            return Ok(());
        }
        require(
            self.algorithm.uses_obstacles(),
            "obstacles",
            format!("{} obstacle(s)", self.obstacles.len()),
            "this algorithm does not see obstacles",
            "use Algorithm3 (or Flocking2003 with avoidance), or remove the obstacles",
        )?;
        match self.dim {
            2 => self.validate_start_outside::<DVec2>(),
            _ => self.validate_start_outside::<DVec3>(),
        }
    }

    fn validate_start_outside<V: Space>(&self) -> Result<(), ScenarioError> {
        let field =
            ObstacleField::<V>::from_specs(&self.obstacles).map_err(ScenarioError::Obstacle)?;
        let swarm = initial_swarm::<V>(self);
        for (i, &q) in swarm.positions.iter().enumerate() {
            if let Some(k) = field.containing(q) {
                return Err(ScenarioError::invalid(
                    "initial.positions",
                    format!("agent {i} at {q:?}"),
                    format!(
                        "starts inside obstacles[{k}] ({})",
                        self.obstacles[k].kind()
                    ),
                    "move the initial cloud or the obstacle so that every agent starts outside",
                ));
            }
        }
        Ok(())
    }

    /// The γ-agent's vectors have the scenario's dimension and are finite; a path is well formed.
    fn validate_gamma(&self, field: &str, gamma: &GammaAgent<Point>) -> Check {
        for (name, v) in gamma.vectors() {
            vector(&format!("{field}.{name}"), v, self.dim)?;
        }
        gamma.validate_path().map_err(|e| e.within(field))
    }

    fn validate_cloud(&self, field: &str, cloud: &Cloud) -> Check {
        let dim = self.dim;
        match cloud {
            Cloud::Zero => Ok(()),
            Cloud::Box { min, max } => {
                vector(&format!("{field}.min"), min, dim)?;
                vector(&format!("{field}.max"), max, dim)?;
                require(
                    min.iter().zip(max).all(|(lo, hi)| lo <= hi),
                    &format!("{field}.max"),
                    max,
                    &format!("is below min = {min:?} in some component"),
                    "make every component of max ≥ the same component of min",
                )
            }
            Cloud::Ball { centre, radius } => {
                vector(&format!("{field}.centre"), centre, dim)?;
                length(&format!("{field}.radius"), *radius)
            }
            Cloud::Gaussian { mean, std } => {
                vector(&format!("{field}.mean"), mean, dim)?;
                length(&format!("{field}.std"), *std)
            }
            Cloud::Explicit(rows) => {
                require(
                    rows.len() == self.agents,
                    field,
                    format!("{} vectors", rows.len()),
                    &format!("the scenario has agents = {}", self.agents),
                    "give one vector per agent, or change agents",
                )?;
                for (i, row) in rows.iter().enumerate() {
                    vector(&format!("{field}[{i}]"), row, dim)?;
                }
                Ok(())
            }
        }
    }
}
