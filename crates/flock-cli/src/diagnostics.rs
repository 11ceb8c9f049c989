//! Protocol-specific columns of `metrics.csv`, appended after the common ones.

use flock_math::Vector;
use flock_metrics::ObstacleMetrics;
use flock_obstacles::Space;
use flock_protocols::{
    Algorithm1, Algorithm2, Algorithm3, Flocking2003, ObstacleFlocking2003, Swarm,
    TannerJadbabaiePappas,
};

/// Diagnostics a protocol adds to the common flocking metrics.
pub trait Diagnostics<V: Vector> {
    /// The values at time `t` of the state `swarm`, in the order of
    /// [`Scenario::extra_columns`](crate::Scenario::extra_columns). The state is as the
    /// simulation stores it ([`Simulation::stored_swarm`](flock_protocols::Simulation::stored_swarm)):
    /// in original order unless the protocol [follows the numbering](flock_protocols::Protocol::follows_numbering),
    /// whose values must then not depend on the order of the agents (minima, counts).
    #[must_use]
    fn values(&self, _t: f64, _swarm: &Swarm<V>) -> Vec<f64> {
        Vec::new()
    }
}

impl<V: Vector> Diagnostics<V> for Algorithm1 {}

impl<V: Vector> Diagnostics<V> for Algorithm2<V> {}

impl<V: Vector> Diagnostics<V> for Flocking2003<V> {}

/// `obstacle_clearance`, `inside_obstacles` (none without obstacles, as the columns).
impl<V: Space> Diagnostics<V> for Algorithm3<V> {
    fn values(&self, _t: f64, swarm: &Swarm<V>) -> Vec<f64> {
        let field = self.beta.field();
        if field.is_empty() {
            return Vec::new();
        }
        ObstacleMetrics::measure(&swarm.positions, |q| field.clearance(q)).values()
    }
}

/// `obstacle_clearance`, `inside_obstacles` (none without obstacles, as the columns).
impl<V: Space> Diagnostics<V> for ObstacleFlocking2003<V> {
    fn values(&self, _t: f64, swarm: &Swarm<V>) -> Vec<f64> {
        if self.obstacles.is_empty() {
            return Vec::new();
        }
        let clearance = |q: V| {
            self.obstacles
                .iter()
                .map(|ball| (q - ball.centre()).length() - ball.radius())
                .fold(f64::INFINITY, f64::min)
        };
        ObstacleMetrics::measure(&swarm.positions, clearance).values()
    }
}

/// `velocity_disagreement`, `min_linked_distance`.
impl<V: Vector> Diagnostics<V> for TannerJadbabaiePappas {
    fn values(&self, _t: f64, swarm: &Swarm<V>) -> Vec<f64> {
        vec![
            Self::velocity_disagreement(&swarm.velocities),
            self.min_linked_distance(&swarm.positions),
        ]
    }
}
