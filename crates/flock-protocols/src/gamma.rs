//! γ-agents: the group objective (q_r, p_r) of Algorithms 2 and 3 (TAC 2006 eq. 25–26).

use flock_math::{Vector, sigma1_vec};

/// The γ-agent's trajectory (q_r(t), p_r(t)), solution of q̇_r = p_r, ṗ_r = f_r(q_r, p_r).
#[derive(Clone, Debug, PartialEq)]
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
    /// Motion along a polyline at constant speed, holding still at the last waypoint.
    Path(Path<V>),
}

impl<V: Vector> GammaAgent<V> {
    /// (q_r(t), p_r(t)).
    #[must_use]
    pub fn state(&self, t: f64) -> (V, V) {
        match self {
            Self::Static { position } => (*position, V::ZERO),
            Self::ConstantVelocity { position, velocity } => (*position + *velocity * t, *velocity),
            Self::Path(path) => path.state(t),
        }
    }

    /// True when p_r is constant in time, the case of the energy theorems.
    #[must_use]
    pub fn is_uniform(&self) -> bool {
        !matches!(self, Self::Path(_))
    }
}

/// A polyline q_r travels at constant `speed`, starting at its first waypoint at t = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Path<V> {
    waypoints: Vec<V>,
    /// Arc length at each waypoint.
    arc: Vec<f64>,
    speed: f64,
}

impl<V: Vector> Path<V> {
    /// A path through at least one waypoint, travelled at `speed > 0`.
    ///
    /// # Panics
    /// With no waypoint.
    #[must_use]
    pub fn new(waypoints: Vec<V>, speed: f64) -> Self {
        assert!(!waypoints.is_empty(), "a path needs a waypoint");
        let mut arc = Vec::with_capacity(waypoints.len());
        let mut length = 0.0;
        arc.push(length);
        for pair in waypoints.windows(2) {
            length += (pair[1] - pair[0]).length();
            arc.push(length);
        }
        Self {
            waypoints,
            arc,
            speed,
        }
    }

    /// (q_r(t), p_r(t)): position on the polyline at arc length `speed · t`, velocity along the
    /// current segment; after the last waypoint, that waypoint with zero velocity.
    #[must_use]
    pub fn state(&self, t: f64) -> (V, V) {
        let s = self.speed * t.max(0.0);
        // arc[0] = 0 ≤ s, so k ≥ 1: the current segment joins waypoints k − 1 and k (zero-length
        // segments are skipped, their two arc lengths being equal)
        let k = self.arc.partition_point(|&a| a <= s);
        if k == self.waypoints.len() {
            return (self.waypoints[k - 1], V::ZERO);
        }
        let (from, to) = (self.waypoints[k - 1], self.waypoints[k]);
        let direction = (to - from).normalize_or_zero();
        (
            from + direction * (s - self.arc[k - 1]),
            direction * self.speed,
        )
    }
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::DVec2;

    #[test]
    fn path_is_travelled_at_constant_speed() {
        let path = Path::new(
            vec![DVec2::ZERO, DVec2::new(3.0, 0.0), DVec2::new(3.0, 4.0)],
            2.0,
        );
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
