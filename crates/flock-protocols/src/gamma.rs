//! γ-agents: the group objective (q_r, p_r) of Algorithms 2 and 3 (TAC 2006 eq. 25–26).

use flock_graph::Numbering;
use flock_math::{Vector, mean_of, sigma1_vec};

use crate::error::{ParamError, check};

/// The γ-agent's trajectory (q_r(t), p_r(t)), solution of q̇_r = p_r, ṗ_r = f_r(q_r, p_r).
///
/// `V` is the vector type of the simulation (`DVec2`, `DVec3`); a scenario file writes a
/// γ-agent with lists of numbers (`GammaAgent<Vec<f64>>`, feature `serde`), turned into vectors
/// by [`GammaAgent::map`].
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub enum GammaAgent<V> {
    /// A fixed rendezvous point: p_r = 0.
    Static {
        /// q_r.
        position: V,
    },
    /// Uniform motion: q_r(t) = q_r(0) + t p_r, f_r = 0.
    ConstantVelocity {
        /// q_r(0).
        position: V,
        /// p_r.
        velocity: V,
    },
    /// Motion along a polyline at constant `speed`, starting at its first waypoint at t = 0 and
    /// holding still at the last one.
    Path {
        /// The waypoints, at least one.
        waypoints: Vec<V>,
        /// The speed > 0.
        speed: f64,
    },
}

impl<V> GammaAgent<V> {
    /// The same trajectory with every vector mapped by `f` (e.g. lists of numbers to vectors).
    #[must_use]
    pub fn map<W>(&self, mut f: impl FnMut(&V) -> W) -> GammaAgent<W> {
        match self {
            Self::Static { position } => GammaAgent::Static {
                position: f(position),
            },
            Self::ConstantVelocity { position, velocity } => GammaAgent::ConstantVelocity {
                position: f(position),
                velocity: f(velocity),
            },
            Self::Path { waypoints, speed } => GammaAgent::Path {
                waypoints: waypoints.iter().map(f).collect(),
                speed: *speed,
            },
        }
    }

    /// Every vector of the trajectory with its field (`position`, `velocity`, `waypoints[k]`).
    #[must_use]
    pub fn vectors(&self) -> Vec<(String, &V)> {
        match self {
            Self::Static { position } => vec![("position".to_owned(), position)],
            Self::ConstantVelocity { position, velocity } => vec![
                ("position".to_owned(), position),
                ("velocity".to_owned(), velocity),
            ],
            Self::Path { waypoints, .. } => waypoints
                .iter()
                .enumerate()
                .map(|(k, w)| (format!("waypoints[{k}]"), w))
                .collect(),
        }
    }

    /// Checks what does not depend on the vectors: a path has a waypoint and a speed > 0.
    ///
    /// # Errors
    /// An empty path or a speed that is not positive, named by its field (`waypoints`, `speed`).
    pub fn validate_path(&self) -> Result<(), ParamError> {
        let Self::Path { waypoints, speed } = self else {
            return Ok(());
        };
        check::require(
            !waypoints.is_empty(),
            "waypoints",
            "[]",
            "a path needs a waypoint",
            "list at least one waypoint",
        )?;
        check::positive("speed", *speed)
    }
}

impl<V: Vector> GammaAgent<V> {
    /// (q_r(t), p_r(t)).
    #[must_use]
    pub fn state(&self, t: f64) -> (V, V) {
        match self {
            Self::Static { position } => (*position, V::ZERO),
            Self::ConstantVelocity { position, velocity } => (*position + *velocity * t, *velocity),
            Self::Path { waypoints, speed } => path_state(waypoints, *speed, t),
        }
    }

    /// True when p_r is constant in time, the case of the energy theorems.
    #[must_use]
    pub fn is_uniform(&self) -> bool {
        !matches!(self, Self::Path { .. })
    }

    /// Checks that every vector is finite and the path well formed ([`GammaAgent::validate_path`]).
    ///
    /// # Errors
    /// The first vector that is not finite, or a malformed path, named by its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        for (field, v) in self.vectors() {
            let coordinates: Vec<f64> = (0..V::DIM).map(|k| v.coord(k)).collect();
            check::coordinates(&field, &coordinates)?;
        }
        self.validate_path()
    }
}

/// The state on the polyline `waypoints` at arc length `speed · t`: the position, and the velocity
/// along the current segment; after the last waypoint, that waypoint with zero velocity
/// (the origin at rest for no waypoint). Zero-length segments are passed over.
fn path_state<V: Vector>(waypoints: &[V], speed: f64, t: f64) -> (V, V) {
    let s = speed * t.max(0.0);
    // `arc` is the arc length at waypoint k − 1; segment k − 1 → k is current when s < arc + ‖·‖
    let mut arc = 0.0;
    for k in 1..waypoints.len() {
        let (from, to) = (waypoints[k - 1], waypoints[k]);
        let next = arc + (to - from).length();
        if next > s {
            let direction = (to - from).normalize_or_zero();
            return (from + direction * (s - arc), direction * speed);
        }
        arc = next;
    }
    (waypoints.last().copied().unwrap_or(V::ZERO), V::ZERO)
}

/// c₂ = 2√c₁, the critically damped velocity gain of a position gain c₁ (TAC 2006 Section VIII),
/// the default c₂^γ of Algorithm 3 and c₂^β of its β-interaction.
#[must_use]
pub fn critical_damping(c1: f64) -> f64 {
    2.0 * c1.sqrt()
}

/// The form of the position feedback to the γ-agent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Feedback {
    /// −c₁(q_i − q_r): Algorithm 2 (TAC 2006 eq. 25), the sink of the 2003 papers.
    #[default]
    Linear,
    /// −c₁ σ₁(q_i − q_r), bounded by c₁: Algorithm 3 (TAC 2006 eq. 67).
    Bounded,
}

/// The navigational feedback f_i^γ = −c₁ g(q_i − q_r) − c₂(p_i − p_r), g the identity (Algorithm 2,
/// TAC 2006 eq. 25) or σ₁ (Algorithm 3, eq. 67).
#[derive(Clone, Debug, PartialEq)]
pub struct NavigationalFeedback<V> {
    /// The γ-agent.
    pub gamma: GammaAgent<V>,
    /// Position gain c₁ > 0.
    pub c1: f64,
    /// Velocity gain c₂ > 0.
    pub c2: f64,
    /// The form of the position term.
    pub form: Feedback,
}

impl<V: Vector> NavigationalFeedback<V> {
    /// f^γ = −c₁(q − q_r) − c₂(p − p_r) (Algorithm 2).
    #[must_use]
    pub const fn linear(gamma: GammaAgent<V>, c1: f64, c2: f64) -> Self {
        Self {
            gamma,
            c1,
            c2,
            form: Feedback::Linear,
        }
    }

    /// f^γ = −c₁ σ₁(q − q_r) − c₂(p − p_r) (Algorithm 3).
    #[must_use]
    pub const fn bounded(gamma: GammaAgent<V>, c1: f64, c2: f64) -> Self {
        Self {
            gamma,
            c1,
            c2,
            form: Feedback::Bounded,
        }
    }

    /// f_i^γ for an agent at (q, p) given the γ-agent state (q_r, p_r).
    #[inline]
    #[must_use]
    pub fn input(&self, q: V, p: V, (q_r, p_r): (V, V)) -> V {
        let offset = q - q_r;
        let pull = match self.form {
            Feedback::Linear => offset,
            Feedback::Bounded => sigma1_vec(offset),
        };
        -(pull * self.c1) - (p - p_r) * self.c2
    }

    /// The potential whose negative gradient is the position term, times c₁:
    /// (c₁/2)‖q − q_r‖² (linear) or c₁(√(1 + ‖q − q_r‖²) − 1) (bounded, V_γ of TAC 2006 eq. 70).
    #[inline]
    #[must_use]
    pub fn potential(&self, q: V, q_r: V) -> f64 {
        let d2 = (q - q_r).length_squared();
        self.c1
            * match self.form {
                Feedback::Linear => 0.5 * d2,
                Feedback::Bounded => d2 / ((1.0 + d2).sqrt() + 1.0),
            }
    }

    /// The γ-tracking errors at time `t`, as the `metrics.csv` columns
    /// [`GAMMA_POSITION_ERROR`] ‖q̄ − q_r‖ and [`GAMMA_VELOCITY_ERROR`] ‖p̄ − p_r‖, q̄ and p̄ the
    /// centre and mean velocity of the agents (summed in original order whatever `numbering`
    /// stores them in): how far the flock is from its group objective. The feedback steers each
    /// agent, and the α-terms cancel in the sum (Σ_i u_i^α = 0), so the centre obeys
    /// q̄̈ = −c₁(q̄ − q_r) − c₂(p̄ − p_r) + p_r' (linear form) and both vanish for a γ-agent of
    /// constant velocity; delays, losses, limits and vehicles leave a lag (docs/conditions.md).
    #[must_use]
    pub fn tracking_columns(
        &self,
        t: f64,
        positions: &[V],
        velocities: &[V],
        numbering: &Numbering,
    ) -> [(&'static str, f64); 2] {
        let (q_r, p_r) = self.gamma.state(t);
        let centre = mean_of(numbering.ordered(positions));
        let mean_velocity = mean_of(numbering.ordered(velocities));
        [
            (GAMMA_POSITION_ERROR, (centre - q_r).length()),
            (GAMMA_VELOCITY_ERROR, (mean_velocity - p_r).length()),
        ]
    }
}

/// The column of ‖q̄ − q_r‖, the distance from the flock's centre to its γ-agent
/// ([`NavigationalFeedback::tracking_columns`]).
pub const GAMMA_POSITION_ERROR: &str = "gamma_position_error";

/// The column of ‖p̄ − p_r‖, the difference between the flock's mean velocity and its
/// γ-agent's ([`NavigationalFeedback::tracking_columns`]).
pub const GAMMA_VELOCITY_ERROR: &str = "gamma_velocity_error";

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::DVec2;

    #[test]
    fn path_is_travelled_at_constant_speed() {
        let path = GammaAgent::Path {
            waypoints: vec![DVec2::ZERO, DVec2::new(3.0, 0.0), DVec2::new(3.0, 4.0)],
            speed: 2.0,
        };
        assert_eq!(path.state(0.0), (DVec2::ZERO, DVec2::new(2.0, 0.0)));
        let (q, p) = path.state(1.0);
        assert_relative_eq!(q, DVec2::new(2.0, 0.0));
        assert_relative_eq!(p, DVec2::new(2.0, 0.0));
        let (q, p) = path.state(2.5);
        assert_relative_eq!(q, DVec2::new(3.0, 2.0));
        assert_relative_eq!(p, DVec2::new(0.0, 2.0));
        assert_eq!(path.state(10.0), (DVec2::new(3.0, 4.0), DVec2::ZERO));
    }

    #[test]
    fn constant_velocity_gamma_agent_moves_uniformly() {
        let gamma = GammaAgent::ConstantVelocity {
            position: DVec2::new(1.0, 1.0),
            velocity: DVec2::new(0.5, 0.0),
        };
        assert_eq!(
            gamma.state(4.0),
            (DVec2::new(3.0, 1.0), DVec2::new(0.5, 0.0))
        );
        let feedback = NavigationalFeedback::linear(gamma, 2.0, 3.0);
        let u = feedback.input(DVec2::new(4.0, 1.0), DVec2::ZERO, feedback.gamma.state(4.0));
        assert_relative_eq!(u, DVec2::new(-2.0 + 1.5, 0.0));
        assert_relative_eq!(
            feedback.potential(DVec2::new(4.0, 1.0), DVec2::new(3.0, 1.0)),
            1.0
        );
    }

    #[test]
    fn bounded_feedback_is_the_gradient_of_its_potential() {
        let (q, q_r) = (DVec2::new(4.0, 2.0), DVec2::new(1.0, -2.0));
        let feedback =
            NavigationalFeedback::bounded(GammaAgent::Static { position: q_r }, 0.7, 0.0);
        let u = feedback.input(q, DVec2::ZERO, (q_r, DVec2::ZERO));
        assert_relative_eq!(u.length(), 0.7 * 5.0 / 26f64.sqrt(), epsilon = 1e-15);
        let step = 1e-6;
        for e in [DVec2::X, DVec2::Y] {
            let fd = (feedback.potential(q + e * step, q_r)
                - feedback.potential(q - e * step, q_r))
                / (2.0 * step);
            assert_relative_eq!(-u.dot(e), fd, epsilon = 1e-8);
        }
    }
}
