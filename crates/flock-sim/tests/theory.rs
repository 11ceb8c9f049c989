//! TAC 2006 theorems: momentum, energy dissipation, lattice equilibria.

use approx::assert_relative_eq;
use flock_graph::ProximityNet;
use flock_math::Vector;
use flock_protocols::{Algorithm1, Algorithm2, GammaAgent, NavigationalFeedback, Protocol, Swarm};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{energy_along, papers_alpha, random_swarm, triangular_lattice};

fn controls<V: Vector, P: Protocol<V>>(protocol: &P, t: f64, swarm: &Swarm<V>) -> Vec<V> {
    let net = ProximityNet::brute_force(&swarm.positions, protocol.interaction_range());
    let mut u = vec![V::ZERO; swarm.len()];
    protocol.controls(t, swarm, &net, &mut u);
    u
}

/// Algorithm 1's pair forces are antisymmetric, so Σ_i u_i = 0 and momentum is preserved.
fn momentum_preserved<V: Vector>() {
    let protocol = Algorithm1 {
        alpha: papers_alpha(),
    };
    for seed in 0..5 {
        let swarm: Swarm<V> = random_swarm(120, 25.0, 2.0, seed);
        let u = controls(&protocol, 0.0, &swarm);
        let total = u.iter().fold(V::ZERO, |acc, &ui| acc + ui);
        let scale: f64 = u.iter().map(|ui| ui.length()).sum();
        assert!(scale > 1.0, "the test swarm must interact");
        assert!(
            total.length() <= 1e-13 * scale,
            "Σu = {total:?} against Σ‖u‖ = {scale}"
        );
    }
    // and along a run: p_c is constant to round-off
    let swarm: Swarm<V> = random_swarm(60, 20.0, 2.0, 9);
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
        .expect("a valid simulation");
    let p_c = sim.swarm().mean_velocity();
    for _ in 0..500 {
        sim.step();
    }
    let drift = (sim.swarm().mean_velocity() - p_c).length();
    assert!(drift <= 1e-13, "mean velocity drifted by {drift}");
}

#[test]
fn algorithm1_preserves_momentum_2d() {
    momentum_preserved::<DVec2>();
}

#[test]
fn algorithm1_preserves_momentum_3d() {
    momentum_preserved::<DVec3>();
}

/// Theorem 1: H = V + ½Σ‖p_i − p_c‖² is non-increasing along Algorithm 1 (checked with RK4 and a
/// small step, so the integration error per step is far below the dissipation).
fn energy_non_increasing<V: Vector>() {
    let swarm: Swarm<V> = random_swarm(40, 12.0, 1.5, 3);
    let mut sim = Simulation::new(
        Algorithm1 {
            alpha: papers_alpha(),
        },
        Integrator::Rk4,
        swarm,
        0.002,
    )
    .expect("a valid simulation");
    let (start, end) = energy_along(&mut sim, 2500, Simulation::energy);
    assert!(end < start - 1.0, "H must dissipate: {start} → {end}");
}

#[test]
fn algorithm1_energy_non_increasing_2d() {
    energy_non_increasing::<DVec2>();
}

#[test]
fn algorithm1_energy_non_increasing_3d() {
    energy_non_increasing::<DVec3>();
}

/// Theorem 3 (uniform γ-agent): H = V + (c₁/2)Σ‖q_i − q_r‖² + ½Σ‖p_i − p_r‖² is non-increasing.
#[test]
fn algorithm2_energy_non_increasing_with_a_moving_gamma_agent() {
    let swarm: Swarm<DVec2> = random_swarm(40, 15.0, 1.5, 5);
    let navigation = NavigationalFeedback::linear(
        GammaAgent::ConstantVelocity {
            position: DVec2::new(3.0, -2.0),
            velocity: DVec2::new(1.0, 0.5),
        },
        0.05,
        0.4,
    );
    let protocol = Algorithm2 {
        alpha: papers_alpha(),
        navigation,
    };
    let mut sim =
        Simulation::new(protocol, Integrator::Rk4, swarm, 0.002).expect("a valid simulation");
    let (start, end) = energy_along(&mut sim, 2500, Simulation::energy);
    assert!(end < 0.5 * start, "H must dissipate: {start} → {end}");
}

/// On an exact α-lattice moving rigidly every α-input vanishes (φ_α(d_α) = 0, equal velocities).
fn lattice_is_an_equilibrium<V: Vector>(q: Vec<V>) {
    let velocity = V::from_fn(|k| 0.3 + k as f64);
    let swarm = Swarm::new(q.clone(), vec![velocity; q.len()]);
    let protocol = Algorithm1 {
        alpha: papers_alpha(),
    };
    let net = ProximityNet::brute_force(&q, 8.4);
    assert!(
        net.graph().directed_edge_count() >= 2 * q.len(),
        "the lattice must be connected densely"
    );
    for u in controls(&protocol, 0.0, &swarm) {
        assert!(u.length() <= 1e-12, "u = {u:?} on an α-lattice");
    }
    // and V is at its minimum: every edge contributes ψ_α(d_α) − ψ_α(r_α) = −ψ_α(r_α)
    let psi_far = {
        use flock_math::Potential;
        let action = papers_alpha().action().clone();
        action.potential(action.range())
    };
    let edges = net.graph().undirected_edge_count() as f64;
    assert_relative_eq!(
        papers_alpha().potential(&q, &net),
        -edges * psi_far,
        max_relative = 1e-12
    );
}

#[test]
fn triangular_lattice_is_an_equilibrium_2d() {
    lattice_is_an_equilibrium::<DVec2>(triangular_lattice(6, 7, 7.0));
}

#[test]
fn fcc_lattice_is_an_equilibrium_3d() {
    // face-centred cubic with nearest-neighbour distance d: cube side d√2; next neighbours at d√2 > r
    let side = 7.0 * 2f64.sqrt();
    let mut q = Vec::new();
    for (i, j, k) in (0..3).flat_map(|i| (0..3).flat_map(move |j| (0..3).map(move |k| (i, j, k)))) {
        let corner = DVec3::new(f64::from(i), f64::from(j), f64::from(k)) * side;
        for offset in [
            DVec3::ZERO,
            DVec3::new(0.5, 0.5, 0.0),
            DVec3::new(0.5, 0.0, 0.5),
            DVec3::new(0.0, 0.5, 0.5),
        ] {
            q.push(corner + offset * side);
        }
    }
    lattice_is_an_equilibrium(q);
}

#[test]
fn lattice_equilibrium_holds_in_the_plane_of_3d() {
    lattice_is_an_equilibrium::<DVec3>(triangular_lattice(4, 5, 7.0));
}
