//! Validation of a parsed scenario: every value inside the domain the theory needs.

use flock_graph::{Components, Graph};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::error::ScenarioError;
use crate::initial::initial_swarm;
use crate::scenario::{Algorithm, Cloud, Gamma, Scenario, TannerGraph};
use crate::stability::coincident_start;

type Check = Result<(), ScenarioError>;

/// Fails with an [`ScenarioError::Invalid`] unless `ok`.
fn require(ok: bool, field: &str, value: impl std::fmt::Debug, why: &str, fix: &str) -> Check {
    if ok {
        Ok(())
    } else {
        Err(ScenarioError::invalid(field, value, why, fix))
    }
}

fn finite(field: &str, value: f64) -> Check {
    require(
        value.is_finite(),
        field,
        value,
        "must be a finite number",
        "write a finite decimal value",
    )
}

fn positive(field: &str, value: f64) -> Check {
    finite(field, value)?;
    require(
        value > 0.0,
        field,
        value,
        "must be > 0",
        "give a positive value",
    )?;
    not_huge(field, value)
}

fn non_negative(field: &str, value: f64) -> Check {
    finite(field, value)?;
    require(
        value >= 0.0,
        field,
        value,
        "must be ≥ 0",
        "give a non-negative value",
    )?;
    not_huge(field, value)
}

/// Gains, times and lengths up to [`MAX_COORDINATE`]: beyond, the energies (quadratic in lengths
/// and linear in gains, summed over pairs) overflow.
fn not_huge(field: &str, value: f64) -> Check {
    require(
        value <= MAX_COORDINATE,
        field,
        value,
        &format!("exceeds {MAX_COORDINATE:e}, where the energies and forces overflow"),
        "use a value of at most 1e9 (rescale time or length if needed)",
    )
}

fn unit_interval(field: &str, value: f64) -> Check {
    finite(field, value)?;
    require(
        value > 0.0 && value < 1.0,
        field,
        value,
        "must lie in (0, 1)",
        "choose a value strictly between 0 and 1",
    )
}

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
    require(
        v.iter().all(|x| x.is_finite()),
        field,
        v,
        "has a non-finite component",
        "use finite numbers",
    )?;
    require(
        v.iter().all(|x| x.abs() <= MAX_COORDINATE),
        field,
        v,
        &format!("has a component beyond ±{MAX_COORDINATE:e}, {WHY_BOUNDED}"),
        "rescale the scenario (or move its origin) so that every coordinate stays within ±1e9",
    )
}

/// The largest coordinate, length or speed accepted.
const MAX_COORDINATE: f64 = 1e9;

/// The smallest length (and potential bound a, b) accepted.
const MIN_LENGTH: f64 = 1e-9;

/// Why lengths are bounded.
const WHY_BOUNDED: &str = "where 64-bit floats keep too few digits to resolve the lattice distance (and squares of distances overflow)";

/// A length in [[`MIN_LENGTH`], [`MAX_COORDINATE`]].
fn length(field: &str, value: f64) -> Check {
    within_scale(field, value, WHY_BOUNDED)
}

/// A positive value in [[`MIN_LENGTH`], [`MAX_COORDINATE`]], where `why` says what breaks outside.
fn within_scale(field: &str, value: f64, why: &str) -> Check {
    finite(field, value)?;
    require(
        (MIN_LENGTH..=MAX_COORDINATE).contains(&value),
        field,
        value,
        &format!("lies outside [{MIN_LENGTH:e}, {MAX_COORDINATE:e}], {why}"),
        "rescale the scenario so that it stays within [1e-9, 1e9]",
    )
}

/// The most agents accepted: flock keeps about 250 bytes per agent (docs/performance.md).
const MAX_AGENTS: usize = 100_000_000;

impl Scenario {
    /// Checks every value against its domain.
    ///
    /// # Errors
    /// The first invalid value, with its field, why and the fix.
    pub fn validate(&self) -> Check {
        let dim = self.dim;
        require(
            dim == 2 || dim == 3,
            "dim",
            dim,
            "flock simulates the plane or space",
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
        self.validate_alpha()?;
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
        self.validate_cloud("initial.velocities", &self.initial.velocities)?;
        if matches!(self.algorithm, Algorithm::Tanner { .. }) {
            self.validate_distinct_start()?;
        }
        self.validate_obstacles()
    }

    fn validate_alpha(&self) -> Check {
        let a = &self.alpha;
        length("alpha.d", a.d)?;
        if let Some(r) = a.r {
            length("alpha.r", r)?;
            require(
                r > a.d,
                "alpha.r",
                r,
                &format!(
                    "must exceed the lattice distance alpha.d = {} (0 < d < r)",
                    a.d
                ),
                "raise alpha.r (the papers use r = 1.2 d) or lower alpha.d",
            )?;
        }
        within_scale(
            "alpha.epsilon",
            a.epsilon,
            "where the σ-norm (√(1 + ε‖z‖²) − 1)/ε loses precision or overflows",
        )?;
        finite("alpha.h", a.h)?;
        require(
            a.h > 0.0 && a.h < 1.0,
            "alpha.h",
            a.h,
            "the bump ρ_h needs h in (0, 1)",
            "use e.g. h: 0.2 (the papers' value)",
        )?;
        let why =
            "where the uneven sigmoid's shift c = |a − b|/√(4ab) loses precision or overflows";
        within_scale("alpha.a", a.a, why)?;
        within_scale("alpha.b", a.b, why)?;
        require(
            a.a <= a.b,
            "alpha.a",
            a.a,
            &format!(
                "exceeds alpha.b = {}: the uneven sigmoid φ needs 0 < a ≤ b",
                a.b
            ),
            "swap a and b or lower a",
        )?;
        positive("alpha.c1", a.c1)?;
        finite("alpha.c2", a.c2)?;
        not_huge("alpha.c2", a.c2)?;
        require(
            a.c2 >= 0.0,
            "alpha.c2",
            a.c2,
            "a negative consensus gain amplifies velocity mismatch",
            "use c2 ≥ 0",
        )
    }

    fn validate_algorithm(&self) -> Check {
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
                let d = self.alpha.d;
                if let Some(d_beta) = beta.d {
                    positive("algorithm.beta.d", d_beta)?;
                }
                finite("algorithm.beta.r", beta.range(d))?;
                require(
                    beta.range(d) > beta.distance(d),
                    "algorithm.beta.r",
                    beta.range(d),
                    &format!(
                        "must exceed the obstacle distance d′ = {} (0 < d′ < r′)",
                        beta.distance(d)
                    ),
                    "raise algorithm.beta.r (the papers use r′ = 1.2 d′) or lower algorithm.beta.d",
                )?;
                unit_interval("algorithm.beta.h", beta.h)?;
                positive("algorithm.beta.c1", beta.c1)?;
                non_negative("algorithm.beta.c2", beta.damping())
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
                    unit_interval("algorithm.delta", *delta)?;
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
                    positive("algorithm.avoidance.c3", a.c3)?;
                    non_negative("algorithm.avoidance.c4", a.c4)?;
                    require(
                        a.lambda_d > 0.0 && a.lambda_d <= 1.0,
                        "algorithm.avoidance.lambda_d",
                        a.lambda_d,
                        "the γ-agent x_k = b_k + λ_d n_d needs λ_d in (0, 1]",
                        "use lambda_d: 1.0",
                    )?;
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
                    finite("algorithm.graph.extra", *extra)?;
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
                        ScenarioError::invalid(
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
    fn validate_distinct_start(&self) -> Check {
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

    fn uses_obstacles(&self) -> bool {
        matches!(
            self.algorithm,
            Algorithm::Algorithm3 { .. }
                | Algorithm::Flocking2003 {
                    avoidance: Some(_),
                    ..
                }
        )
    }

    /// Obstacles are well formed in the scenario's dimension, seen by the algorithm, and no agent
    /// starts inside one.
    fn validate_obstacles(&self) -> Check {
        if self.obstacles.is_empty() {
            return Ok(());
        }
        require(
            self.uses_obstacles(),
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

    fn validate_start_outside<V: Space>(&self) -> Check {
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

    fn validate_gamma(&self, field: &str, gamma: &Gamma) -> Check {
        match gamma {
            Gamma::Static { position } => vector(&format!("{field}.position"), position, self.dim),
            Gamma::ConstantVelocity { position, velocity } => {
                vector(&format!("{field}.position"), position, self.dim)?;
                vector(&format!("{field}.velocity"), velocity, self.dim)
            }
            Gamma::Path { waypoints, speed } => {
                require(
                    !waypoints.is_empty(),
                    &format!("{field}.waypoints"),
                    waypoints,
                    "a path needs a waypoint",
                    "list at least one waypoint",
                )?;
                for (k, w) in waypoints.iter().enumerate() {
                    vector(&format!("{field}.waypoints[{k}]"), w, self.dim)?;
                }
                positive(&format!("{field}.speed"), *speed)
            }
        }
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
