//! Validation of a parsed scenario: every value inside the domain the theory needs.

use crate::error::ScenarioError;
use crate::scenario::{Algorithm, Cloud, Gamma, Scenario};

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
    )
}

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
        self.validate_cloud("initial.velocities", &self.initial.velocities)
    }

    fn validate_alpha(&self) -> Check {
        let a = &self.alpha;
        positive("alpha.d", a.d)?;
        if let Some(r) = a.r {
            finite("alpha.r", r)?;
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
        positive("alpha.epsilon", a.epsilon)?;
        finite("alpha.h", a.h)?;
        require(
            a.h > 0.0 && a.h < 1.0,
            "alpha.h",
            a.h,
            "the bump ρ_h needs h in (0, 1)",
            "use e.g. h: 0.2 (the papers' value)",
        )?;
        positive("alpha.a", a.a)?;
        positive("alpha.b", a.b)?;
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
                self.validate_gamma(gamma)
            }
        }
    }

    fn validate_gamma(&self, gamma: &Gamma) -> Check {
        match gamma {
            Gamma::Static { position } => vector("algorithm.gamma.position", position, self.dim),
            Gamma::ConstantVelocity { position, velocity } => {
                vector("algorithm.gamma.position", position, self.dim)?;
                vector("algorithm.gamma.velocity", velocity, self.dim)
            }
            Gamma::Path { waypoints, speed } => {
                require(
                    !waypoints.is_empty(),
                    "algorithm.gamma.waypoints",
                    waypoints,
                    "a path needs a waypoint",
                    "list at least one waypoint",
                )?;
                for (k, w) in waypoints.iter().enumerate() {
                    vector(&format!("algorithm.gamma.waypoints[{k}]"), w, self.dim)?;
                }
                positive("algorithm.gamma.speed", *speed)
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
                positive(&format!("{field}.radius"), *radius)
            }
            Cloud::Gaussian { mean, std } => {
                vector(&format!("{field}.mean"), mean, dim)?;
                positive(&format!("{field}.std"), *std)
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
