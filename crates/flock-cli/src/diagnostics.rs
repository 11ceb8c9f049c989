//! Protocol-specific columns of `metrics.csv`, appended after the common ones.

use flock_math::Vector;
use flock_protocols::{Algorithm1, Algorithm2, Swarm};

/// Diagnostics a protocol adds to the common flocking metrics.
pub trait Diagnostics<V: Vector> {
    /// The values at time `t` of the state `swarm`, in the order of
    /// [`Scenario::extra_columns`](crate::Scenario::extra_columns).
    #[must_use]
    fn values(&self, _t: f64, _swarm: &Swarm<V>) -> Vec<f64> {
        Vec::new()
    }
}

impl<V: Vector> Diagnostics<V> for Algorithm1 {}

impl<V: Vector> Diagnostics<V> for Algorithm2<V> {}
