//! The hot kernels of a simulation step on α-lattices of 10⁴ agents, in 2D and 3D.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use flock_graph::{NeighbourSearch, ProximityNet};
use flock_metrics::{FlockMetrics, MetricParams};
use flock_protocols::{
    Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, NavigationalFeedback, Protocol, Swarm,
};
use flock_sim::{Integrator, Simulation};
use flocking::synthetic::lattice_swarm;
use glam::{DVec2, DVec3};
use std::hint::black_box;

/// Agents per benchmark: large enough to leave the caches, small enough for `cargo test --benches`.
const N: usize = 10_000;
/// The papers' interaction range r = 1.2 d, d = 7.
const R: f64 = 8.4;

fn protocol<V: flock_math::Vector>(swarm: &Swarm<V>) -> Algorithm2<V> {
    Algorithm2 {
        alpha: AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).expect("valid α-parameters"),
        navigation: NavigationalFeedback::linear(
            GammaAgent::Static {
                position: swarm.centre(),
            },
            0.001,
            0.4,
        ),
    }
}

fn kernels<V: flock_obstacles::Space>(c: &mut Criterion, dim: &str) {
    let (swarm, _) = lattice_swarm::<V>(N, 0);
    let protocol = protocol(&swarm);
    let mut search = NeighbourSearch::new();
    // the kind of net a Simulation keeps for this protocol
    let mut net = if Protocol::<V>::uses_net_distances(&protocol) {
        ProximityNet::new()
    } else {
        ProximityNet::without_distances()
    };
    search.build(&swarm.positions, R, &mut net);
    let mut inputs = vec![V::ZERO; N];

    let mut group = c.benchmark_group(format!("kernels_{dim}"));
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(BenchmarkId::new("neighbour_search", N), |b| {
        b.iter(|| search.build(black_box(&swarm.positions), R, &mut net));
    });
    group.bench_function(BenchmarkId::new("forces_algorithm2", N), |b| {
        b.iter(|| protocol.controls(0.0, black_box(&swarm), &net, &mut inputs));
    });
    let mut sim = Simulation::new(
        protocol.clone(),
        Integrator::SymplecticEuler,
        swarm.clone(),
        0.01,
    )
    .expect("a valid simulation");
    group.bench_function(BenchmarkId::new("step_symplectic_euler", N), |b| {
        b.iter(|| sim.step());
    });
    let params = MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    group.bench_function(BenchmarkId::new("metrics", N), |b| {
        b.iter(|| {
            FlockMetrics::measure(
                black_box(&swarm.positions),
                &swarm.velocities,
                &net,
                &params,
            )
        });
    });
    group.bench_function(BenchmarkId::new("energy", N), |b| {
        b.iter(|| protocol.energy(0.0, black_box(&swarm), &net));
    });
    group.finish();
}

fn kernels_2d(c: &mut Criterion) {
    kernels::<DVec2>(c, "2d");
}

fn kernels_3d(c: &mut Criterion) {
    kernels::<DVec3>(c, "3d");
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(std::time::Duration::from_millis(300))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = kernels_2d, kernels_3d
}
criterion_main!(benches);
