//! The quantities by which Olfati-Saber (IEEE TAC 51(3) 2006, Section VIII "What constitutes
//! flocking?") judges a run: relative connectivity C, cohesion radius R, normalised deviation energy
//! Ẽ, normalised velocity mismatch K̃, the giant-component share C*, plus the minimum inter-agent
//! distance and the number of colliding pairs. Every metric costs O(n + |E|).
//!
//! - [`ObstacleMetrics`]: the smallest agent–obstacle clearance and the agents inside obstacles.
//! - [`FlockMetrics::measure`]: all of them at once from positions, velocities and the net.
//! - The functions [`relative_connectivity`], [`cohesion_radius`], [`deviation_energy`],
//!   [`velocity_mismatch`], [`component_velocity_mismatch`], [`min_distance`], [`collisions`].

pub mod flocking;
pub mod obstacles;

pub use flocking::{
    FlockMetrics, MetricParams, cohesion_radius, collisions, component_velocity_mismatch,
    deviation_energy, min_distance, relative_connectivity, velocity_mismatch,
};
pub use obstacles::ObstacleMetrics;
