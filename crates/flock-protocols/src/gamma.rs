//! γ-agents: the group objective (q_r, p_r) of Algorithms 2 and 3 (TAC 2006 eq. 25–26).

use flock_math::Vector;

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

/// The navigational feedback f_i^γ = −c₁(q_i − q_r) − c₂(p_i − p_r) of Algorithm 2 (TAC 2006 eq. 25).
#[derive(Clone, Debug, PartialEq)]
pub struct NavigationalFeedback<V> {
    /// The γ-agent.
    pub gamma: GammaAgent<V>,
    /// Position gain c₁ > 0.
    pub c1: f64,
    /// Velocity gain c₂ > 0.
    pub c2: f64,
}

impl<V: Vector> NavigationalFeedback<V> {
    /// f_i^γ for an agent at (q, p) given the γ-agent state (q_r, p_r).
    #[inline]
    #[must_use]
    pub fn input(&self, q: V, p: V, (q_r, p_r): (V, V)) -> V {
        -((q - q_r) * self.c1) - (p - p_r) * self.c2
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
        let feedback = NavigationalFeedback {
            gamma,
            c1: 2.0,
            c2: 3.0,
        };
        let u = feedback.input(DVec2::new(4.0, 1.0), DVec2::ZERO, feedback.gamma.state(4.0));
        assert_relative_eq!(u, DVec2::new(-2.0 + 1.5, 0.0));
    }
}
