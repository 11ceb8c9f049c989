//! Shared fixtures: seeded random swarms and exact α-lattices.

use flock_math::{Domain, Vector};
use flock_protocols::{
    Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, NavigationalFeedback, Protocol, Swarm,
    Vicsek, VicsekParams,
};
use flock_sim::Simulation;
use glam::DVec2;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// n agents uniform in [−half, half]^m with velocities uniform in [−speed, speed]^m.
pub fn random_swarm<V: Vector>(n: usize, half: f64, speed: f64, seed: u64) -> Swarm<V> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut draw = |scale: f64| V::from_fn(|_| scale * (2.0 * rng.random::<f64>() - 1.0));
    let positions = (0..n).map(|_| draw(half)).collect();
    let velocities = (0..n).map(|_| draw(speed)).collect();
    Swarm::new(positions, velocities)
}

/// The Vicsek model (v₀ = 0.03, r = 1, Δt = 1, noise η drawn from the streams of `seed`) on a
/// torus of side `side`, and the torus.
pub fn vicsek_on_a_torus(side: f64, eta: f64, seed: u64) -> (Vicsek<DVec2>, Domain<DVec2>) {
    let torus = Domain::Periodic {
        size: DVec2::splat(side),
    };
    let params = VicsekParams {
        v0: 0.03,
        r: 1.0,
        eta,
    };
    (Vicsek::new(params, 1.0, seed, torus).expect("valid"), torus)
}

/// The papers' α-interaction (d = 7, r = 8.4, ε = 0.1, a = b = 5, h = 0.2) with unit gains.
pub fn papers_alpha() -> AlphaInteraction {
    AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).expect("valid α-parameters")
}

/// Algorithm 2 with the papers' α-interaction following a γ-agent that starts at the origin
/// with `velocity` (c₁ = 0.05, c₂ = 0.4).
pub fn following<V: Vector>(velocity: V) -> Algorithm2<V> {
    Algorithm2 {
        alpha: papers_alpha(),
        navigation: NavigationalFeedback::linear(
            GammaAgent::ConstantVelocity {
                position: V::ZERO,
                velocity,
            },
            0.05,
            0.4,
        ),
    }
}

/// A planar point lifted to V (z = 0 in 3D).
pub fn planar<V: Vector>(x: f64, y: f64) -> V {
    V::from_fn(|k| [x, y, 0.0][k])
}

/// A patch of the triangular lattice of spacing d: an α-lattice in the plane for r < √3 d.
pub fn triangular_lattice<V: Vector>(rows: usize, cols: usize, d: f64) -> Vec<V> {
    let mut points = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let x = d * (c as f64 + 0.5 * (r % 2) as f64);
            points.push(planar(x, d * r as f64 * 3f64.sqrt() / 2.0));
        }
    }
    points
}

/// Runs `steps` steps asserting the energy does not rise; returns (first, last).
pub fn energy_along<V: Vector, P: Protocol<V>>(
    sim: &mut Simulation<V, P>,
    steps: usize,
    energy: impl Fn(&Simulation<V, P>) -> f64,
) -> (f64, f64) {
    let start = energy(sim);
    let mut previous = start;
    for _ in 0..steps {
        sim.step();
        let next = energy(sim);
        assert!(
            next <= previous + 1e-9 * previous.abs().max(1.0),
            "energy rose from {previous} to {next} at t = {}",
            sim.time()
        );
        previous = next;
    }
    (start, previous)
}
