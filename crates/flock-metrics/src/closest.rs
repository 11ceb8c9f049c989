//! The closest approach of a run's agents over a span of its records: the least distance between
//! two agents and the most pairs closer than the collision distance at any record from a time on.
//!
//! Over the whole run these measure the start as much as the flock: agents drawn at random start
//! arbitrarily close. After the run has settled (from a fraction of its duration on, by default
//! a quarter) they measure what the protocol keeps apart.

use crate::FlockMetrics;

/// The least distance between two agents and the most colliding pairs over some records.
///
/// # Example
/// ```
/// use flock_metrics::{Closest, FlockMetrics};
///
/// let at = |min_distance, collisions| FlockMetrics {
///     connectivity: 1.0,
///     giant_component: 1.0,
///     components: 1,
///     cohesion_radius: 10.0,
///     deviation_energy: 0.0,
///     velocity_mismatch: 0.0,
///     min_distance,
///     collisions,
///     polarisation: 1.0,
///     milling: 0.0,
///     nearest_neighbour_mean: min_distance,
///     nearest_neighbour_min: min_distance,
///     group_speed: 1.0,
/// };
/// // a random start with colliding pairs, spread out by t = 5
/// let records = [(0.0, at(0.1, 3)), (5.0, at(6.0, 0)), (10.0, at(6.5, 0))];
/// let whole = Closest::over(&records, f64::NEG_INFINITY).unwrap();
/// assert_eq!((whole.min_distance, whole.collisions), (0.1, 3));
/// let settled = Closest::over(&records, 2.5).unwrap();
/// assert_eq!((settled.min_distance, settled.collisions), (6.0, 0));
/// assert_eq!(Closest::over(&records, 11.0), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Closest {
    /// The least distance between two agents at any of the records.
    pub min_distance: f64,
    /// The most pairs closer than the collision distance at any of the records.
    pub collisions: usize,
}

impl Closest {
    /// The default settling fraction: a run has settled after the first quarter of its duration.
    pub const SETTLE: f64 = 0.25;

    /// The closest approach over the records at t ≥ `from` (`None` when there is none).
    #[must_use]
    pub fn over(records: &[(f64, FlockMetrics)], from: f64) -> Option<Self> {
        records
            .iter()
            .filter(|(t, _)| *t >= from)
            .map(|(_, m)| Self {
                min_distance: m.min_distance,
                collisions: m.collisions,
            })
            .reduce(|a, b| Self {
                min_distance: a.min_distance.min(b.min_distance),
                collisions: a.collisions.max(b.collisions),
            })
    }
}
