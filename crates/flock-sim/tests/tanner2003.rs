//! The Tanner–Jadbabaie–Pappas law on a fixed graph (seed 001): Theorem IV.4 checked on the set-up
//! of its Fig. 3–8 (N = 10, start in a ball of radius 2.5 m, speeds in (0, 1) m/s, 100 s).

use approx::assert_abs_diff_eq;
use flock_graph::{Components, Graph, ProximityNet};
use flock_math::{Potential, TannerPotential, Vector};
use flock_protocols::{
    DisconnectedGraph, Protocol, Swarm, TannerJadbabaiePappas, random_connected_graph,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// ‖a − b‖ ≤ epsilon for vectors of either dimension.
#[track_caller]
fn assert_close<V: Vector>(a: V, b: V, epsilon: f64) {
    assert!(
        (a - b).length() <= epsilon,
        "{a:?} vs {b:?} (tolerance {epsilon})"
    );
}

/// A point uniform in the ball of radius `radius` (rejection from the cube).
fn in_ball<V: Vector>(rng: &mut Pcg64, radius: f64) -> V {
    loop {
        let x = V::from_fn(|_| radius * (2.0 * rng.random::<f64>() - 1.0));
        if x.length() <= radius {
            return x;
        }
    }
}

/// Seed 001 § V: N agents uniform in the ball of radius 2.5, velocities of random direction and
/// speed uniform in (0, 1). Positions closer than `spacing` to an earlier one are redrawn, so that
/// W(0) is finite and moderate (the paper's figures start well separated too).
fn papers_start<V: Vector>(n: usize, spacing: f64, seed: u64) -> Swarm<V> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut positions: Vec<V> = Vec::with_capacity(n);
    while positions.len() < n {
        let x: V = in_ball(&mut rng, 2.5);
        if positions.iter().all(|&y| (x - y).length() >= spacing) {
            positions.push(x);
        }
    }
    let velocities = (0..n)
        .map(|_| in_ball::<V>(&mut rng, 1.0).normalize_or_zero() * rng.random::<f64>())
        .collect();
    Swarm::new(positions, velocities)
}

#[test]
fn random_connected_graphs_are_connected_and_reproducible() {
    for seed in 0..50 {
        for (n, extra) in [(10, 0.0), (10, 0.2), (25, 0.05), (2, 0.5)] {
            let g = random_connected_graph(n, extra, seed);
            assert_eq!(g.len(), n);
            assert!(Components::of(&g).is_connected(), "n = {n}, seed {seed}");
            assert_eq!(g, random_connected_graph(n, extra, seed));
            if extra == 0.0 {
                assert_eq!(g.undirected_edge_count(), n - 1, "a spanning tree");
            }
        }
    }
    assert_eq!(
        random_connected_graph(8, 1.0, 3).undirected_edge_count(),
        28
    );
    assert_ne!(
        random_connected_graph(10, 0.2, 1),
        random_connected_graph(10, 0.2, 2)
    );
    // extra edges appear at about the requested rate: 36 non-tree pairs of 10 nodes, p = 0.25
    let extra: usize = (0..400)
        .map(|seed| random_connected_graph(10, 0.25, seed).undirected_edge_count() - 9)
        .sum();
    let rate = extra as f64 / (400.0 * 36.0);
    assert!((rate - 0.25).abs() < 0.02, "extra-edge rate {rate}");
}

#[test]
fn a_disconnected_graph_is_refused() {
    let g = Graph::from_edges(4, &[(0, 1), (2, 3)]).expect("a graph");
    assert_eq!(
        TannerJadbabaiePappas::new(g, TannerPotential::new(1.0), 2.0),
        Err(DisconnectedGraph { components: 2 })
    );
}

/// Eq. 5 by hand for a path 0 — 1 — 2 on a line, V(z) = 1/z² + ln z² − 1 (d = 1).
#[test]
fn law_by_hand_on_a_path() {
    let g = Graph::from_edges(3, &[(0, 1), (1, 2)]).expect("a graph");
    let law = TannerJadbabaiePappas::new(g, TannerPotential::new(1.0), 2.0).expect("connected");
    let r = [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(2.0, 0.5)];
    let v = [DVec2::new(1.0, 0.0), DVec2::ZERO, DVec2::new(0.0, 1.0)];
    // V′(z) = 2/z − 2/z³: V′(2) = 3/4, V′(1/2) = −12
    let u0 = -(v[0] - v[1]) + DVec2::new(0.75, 0.0);
    let u1 = -(v[1] - v[0]) - (v[1] - v[2]) + DVec2::new(-0.75, 0.0) + DVec2::new(0.0, -12.0);
    let u2 = -(v[2] - v[1]) + DVec2::new(0.0, 12.0);
    assert_abs_diff_eq!(law.input(0, &r, &v), u0, epsilon = 1e-14);
    assert_abs_diff_eq!(law.input(1, &r, &v), u1, epsilon = 1e-14);
    assert_abs_diff_eq!(law.input(2, &r, &v), u2, epsilon = 1e-14);
    // W = V(2) + V(1/2) + ½ Σ ‖v‖²
    let swarm = Swarm::new(r.to_vec(), v.to_vec());
    let w = 0.25 + 4f64.ln() - 1.0 + 4.0 + 0.25f64.ln() - 1.0 + 1.0;
    let net = ProximityNet::brute_force(&r, 2.0);
    assert_abs_diff_eq!(law.energy(0.0, &swarm, &net), w, epsilon = 1e-14);
    let bound = law.collision_bound(w);
    assert!(bound > 0.0 && bound < 1.0);
    assert_abs_diff_eq!(law.pair_potential().potential(bound), w, epsilon = 1e-9);
}

/// Theorem IV.4 on seed 001's set-up: W non-increasing, velocities aligned by orders of magnitude
/// in 100 s, linked agents kept apart by the bound V_ij ≤ W(0).
fn flocking_on_a_fixed_graph<V: Vector>(seed: u64) {
    let n = 10;
    let d = 1.0; // V = 1/‖r‖² + ln ‖r‖² (ours: seed 001 gives no formula), shifted by −1
    let graph = random_connected_graph(n, 0.2, seed);
    let law =
        TannerJadbabaiePappas::new(graph, TannerPotential::new(d), 2.0 * d).expect("connected");
    let swarm: Swarm<V> = papers_start(n, 0.3, seed);
    let disagreement = TannerJadbabaiePappas::velocity_disagreement(&swarm.velocities);
    let mismatch = TannerJadbabaiePappas::max_velocity_mismatch(&swarm.velocities);
    let w0 = law.lyapunov(&swarm);
    let mean_velocity = swarm.mean_velocity();
    let guaranteed = law.collision_bound(w0);
    assert!(guaranteed > 0.1 * d, "W(0) = {w0} allows {guaranteed}");
    assert!(law.min_linked_distance(&swarm.positions) >= guaranteed);
    let mut sim = Simulation::new(law, Integrator::Rk4, swarm, 0.01).expect("a valid simulation");
    let mut w = w0;
    let mut closest = f64::INFINITY;
    while sim.time() < 100.0 - 1e-9 {
        sim.step();
        let next = sim.energy();
        assert!(
            next <= w + 1e-10 * w,
            "W rose from {w} to {next} at t = {}",
            sim.time()
        );
        w = next;
        closest = closest.min(sim.protocol().min_linked_distance(&sim.swarm().positions));
    }
    let final_velocities = &sim.swarm().velocities;
    let end = TannerJadbabaiePappas::velocity_disagreement(final_velocities);
    let end_mismatch = TannerJadbabaiePappas::max_velocity_mismatch(final_velocities);
    assert!(
        end < 1e-3 * disagreement,
        "disagreement {disagreement} → {end}"
    );
    assert!(
        end_mismatch < 1e-2 * mismatch,
        "mismatch {mismatch} → {end_mismatch}"
    );
    assert!(
        closest >= guaranteed,
        "linked agents came {closest} apart (bound {guaranteed})"
    );
    assert!(w < 0.9 * w0);
    // the consensus preserves the mean velocity (Σ u_i = 0)
    assert_close(sim.swarm().mean_velocity(), mean_velocity, 1e-12);
}

#[test]
fn velocities_align_on_a_fixed_graph_2d() {
    flocking_on_a_fixed_graph::<DVec2>(4);
}

#[test]
fn velocities_align_on_a_fixed_graph_3d() {
    flocking_on_a_fixed_graph::<DVec3>(5);
}

/// Seed 001's agents interact on the fixed graph, whatever their distances: C, C* and the
/// components of the simulation's metrics are those of that graph (connected, Assumption IV.2),
/// not of the proximity net, and so is the per-component velocity mismatch.
#[test]
fn connectivity_is_measured_on_the_fixed_graph() {
    let g = Graph::from_edges(3, &[(0, 1), (1, 2)]).expect("a graph");
    let law = TannerJadbabaiePappas::new(g, TannerPotential::new(1.0), 2.0).expect("connected");
    // 1 and 2 are 50 apart: the proximity net (range 2) has two components
    let r = vec![DVec2::ZERO, DVec2::new(1.5, 0.0), DVec2::new(51.5, 0.0)];
    let v = vec![DVec2::X, DVec2::ZERO, DVec2::Y];
    let sim = Simulation::new(law, Integrator::SymplecticEuler, Swarm::new(r, v), 0.01)
        .expect("a valid simulation");
    assert_eq!(Components::of(&sim.graph()).count(), 2);
    let params = flock_metrics::MetricParams {
        d: 1.0,
        collision_distance: 0.25,
    };
    let metrics = sim.metrics(&params);
    assert_eq!(
        (
            metrics.connectivity,
            metrics.giant_component,
            metrics.components
        ),
        (1.0, 1.0, 1)
    );
    // K̃ over the one component: ½ Σ ‖p_i − p̄‖² / n with p̄ = (1, 1)/3
    let p_bar = DVec2::new(1.0, 1.0) / 3.0;
    let mismatch = 0.5
        * [DVec2::X, DVec2::ZERO, DVec2::Y]
            .iter()
            .map(|&p| (p - p_bar).length_squared())
            .sum::<f64>()
        / 3.0;
    assert_abs_diff_eq!(sim.component_velocity_mismatch(), mismatch, epsilon = 1e-15);
}
