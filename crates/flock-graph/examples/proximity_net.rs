//! Builds the proximity net of a random flock, in 2D and 3D, and prints its summary.
//!
//! `cargo run -p flock-graph --release --example proximity_net -- [agents]`

use std::time::Instant;

use flock_graph::{Components, NeighbourSearch, ProximityNet, nearest_pair_distance};
use flock_math::Vector;
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn run<V: Vector>(n: usize) {
    let mut rng = Pcg64::seed_from_u64(1);
    // Agents uniform in a box holding about one agent per unit volume; range 1.2.
    let side = (n as f64).powf(1.0 / V::DIM as f64);
    let q: Vec<V> = (0..n)
        .map(|_| V::from_fn(|_| side * rng.random::<f64>()))
        .collect();
    let (mut search, mut net) = (NeighbourSearch::new(), ProximityNet::new());
    search.build(&q, 1.2, &mut net); // warm-up: allocates the buffers
    let start = Instant::now();
    search.build(&q, 1.2, &mut net);
    let elapsed = start.elapsed();
    let components = Components::of(net.graph());
    println!(
        "{}D: {n} agents, {} edges in {elapsed:.2?}; {} components, density {:.3}; closest pair {:.4}",
        V::DIM,
        net.graph().undirected_edge_count(),
        components.count(),
        components.giant_share(),
        nearest_pair_distance(&q).unwrap_or(f64::NAN),
    );
}

fn main() {
    let n = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(10_000);
    run::<DVec2>(n);
    run::<DVec3>(n);
}
