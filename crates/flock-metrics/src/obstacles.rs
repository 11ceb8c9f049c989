//! Clearance between the agents and the obstacles.

use flock_math::Vector;

/// The smallest agent–obstacle clearance and the number of agents inside obstacles, from a signed
/// clearance function (distance to the nearest obstacle, ≤ 0 inside or on the boundary).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObstacleMetrics {
    /// min_i clearance(q_i) (+∞ with no agent or no obstacle).
    pub clearance: f64,
    /// The number of agents with clearance ≤ 0.
    pub inside: usize,
}

impl ObstacleMetrics {
    /// Measures every agent with `clearance`.
    #[must_use]
    pub fn measure<V: Vector>(q: &[V], clearance: impl Fn(V) -> f64) -> Self {
        let mut metrics = Self {
            clearance: f64::INFINITY,
            inside: 0,
        };
        for &qi in q {
            let c = clearance(qi);
            metrics.clearance = metrics.clearance.min(c);
            metrics.inside += usize::from(c <= 0.0);
        }
        metrics
    }

    /// The columns of `metrics.csv` with their values: `obstacle_clearance`, `inside_obstacles`.
    #[must_use]
    pub fn columns(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("obstacle_clearance", self.clearance),
            ("inside_obstacles", self.inside as f64),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn clearance_to_a_disc() {
        let q = [
            DVec2::new(5.0, 0.0),
            DVec2::new(0.5, 0.0),
            DVec2::new(-3.0, 0.0),
        ];
        let m = ObstacleMetrics::measure(&q, |q| q.length() - 1.0);
        assert_eq!(m.clearance, -0.5);
        assert_eq!(m.inside, 1);
        assert_eq!(
            m.columns(),
            vec![("obstacle_clearance", -0.5), ("inside_obstacles", 1.0)]
        );
    }
}
