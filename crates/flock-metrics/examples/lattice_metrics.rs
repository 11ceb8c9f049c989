//! The flocking metrics (TAC 2006, Section VIII) of a perturbed triangular α-lattice.
//!
//! `cargo run -p flock-metrics --example lattice_metrics`

use flock_graph::ProximityNet;
use flock_metrics::{FlockMetrics, MetricParams};
use glam::DVec2;

fn main() {
    let d = 7.0;
    for jitter in [0.0, 0.2, 0.5, 1.0] {
        let q: Vec<DVec2> = (0..100)
            .map(|k| {
                let (row, col) = (f64::from(k / 10), f64::from(k % 10));
                let wobble =
                    DVec2::new((1.3 * f64::from(k)).sin(), (0.7 * f64::from(k)).cos()) * jitter;
                DVec2::new(d * (col + 0.5 * (row % 2.0)), d * row * 3f64.sqrt() / 2.0) + wobble
            })
            .collect();
        let p = vec![DVec2::new(1.0, 0.0); q.len()];
        let net = ProximityNet::brute_force(&q, 1.2 * d);
        let m = FlockMetrics::measure(
            &q,
            &p,
            &net,
            &MetricParams {
                d,
                collision_distance: 0.25 * d,
            },
        );
        println!(
            "jitter {jitter:.1}: C = {:.3}, C* = {:.3}, R = {:.2}, Ẽ = {:.2e}, K̃ = {:.1e}, min distance = {:.3}",
            m.connectivity,
            m.giant_component,
            m.cohesion_radius,
            m.deviation_energy,
            m.velocity_mismatch,
            m.min_distance
        );
    }
}
