//! Symmetries: translation, rotation and permutation of the agents; the plane inside space.

use approx::assert_abs_diff_eq;
use flock_graph::ProximityNet;
use flock_protocols::{Algorithm1, Algorithm2, GammaAgent, NavigationalFeedback, Protocol, Swarm};
use flock_sim::{Integrator, Simulation};
use glam::{DMat3, DVec2, DVec3};

use crate::common::{following, papers_alpha, planar, random_swarm};

fn controls<P: Protocol<DVec3>>(protocol: &P, swarm: &Swarm<DVec3>) -> Vec<DVec3> {
    let net = ProximityNet::brute_force(&swarm.positions, protocol.interaction_range());
    let mut u = vec![DVec3::ZERO; swarm.len()];
    protocol.controls(0.0, swarm, &net, &mut u);
    u
}

fn algorithm2(gamma_position: DVec3) -> Algorithm2<DVec3> {
    let gamma = GammaAgent::Static {
        position: gamma_position,
    };
    Algorithm2 {
        alpha: papers_alpha(),
        navigation: NavigationalFeedback::linear(gamma, 0.1, 0.5),
    }
}

#[test]
fn translation_invariance() {
    let swarm: Swarm<DVec3> = random_swarm(150, 20.0, 2.0, 1);
    let shift = DVec3::new(1.0e3, -250.0, 37.5);
    let moved = Swarm::new(
        swarm.positions.iter().map(|&q| q + shift).collect(),
        swarm.velocities.clone(),
    );
    let (u, u_moved) = (
        controls(&algorithm2(DVec3::ONE), &swarm),
        controls(&algorithm2(DVec3::ONE + shift), &moved),
    );
    for (a, b) in u.iter().zip(&u_moved) {
        assert_abs_diff_eq!(*a, *b, epsilon = 1e-10);
    }
}

#[test]
fn rotation_equivariance() {
    let swarm: Swarm<DVec3> = random_swarm(150, 20.0, 2.0, 2);
    let rotation = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.83);
    let turned = Swarm::new(
        swarm.positions.iter().map(|&q| rotation * q).collect(),
        swarm.velocities.iter().map(|&p| rotation * p).collect(),
    );
    let gamma = DVec3::new(2.0, -1.0, 4.0);
    let u = controls(&algorithm2(gamma), &swarm);
    let u_turned = controls(&algorithm2(rotation * gamma), &turned);
    for (a, b) in u.iter().zip(&u_turned) {
        assert_abs_diff_eq!(rotation * *a, *b, epsilon = 1e-11);
    }
}

#[test]
fn permutation_equivariance() {
    let swarm: Swarm<DVec3> = random_swarm(150, 20.0, 2.0, 3);
    // a fixed derangement: i ↦ (37 i + 11) mod n
    let n = swarm.len();
    let order: Vec<usize> = (0..n).map(|i| (37 * i + 11) % n).collect();
    let shuffled = Swarm::new(
        order.iter().map(|&i| swarm.positions[i]).collect(),
        order.iter().map(|&i| swarm.velocities[i]).collect(),
    );
    let protocol = Algorithm1 {
        alpha: papers_alpha(),
    };
    let (u, u_shuffled) = (controls(&protocol, &swarm), controls(&protocol, &shuffled));
    for (k, &i) in order.iter().enumerate() {
        assert_abs_diff_eq!(u[i], u_shuffled[k], epsilon = 1e-12);
    }
}

/// A planar initial condition run in 3D stays planar and matches the 2D run.
#[test]
fn planar_runs_agree_in_2d_and_3d() {
    let flat: Swarm<DVec2> = random_swarm(80, 25.0, 2.0, 4);
    let lifted = Swarm::new(
        flat.positions.iter().map(|q| planar(q.x, q.y)).collect(),
        flat.velocities.iter().map(|p| planar(p.x, p.y)).collect(),
    );
    let protocol2 = following(DVec2::new(1.0, 0.5));
    let protocol3 = following(DVec3::new(1.0, 0.5, 0.0));
    let mut sim2 = Simulation::new(protocol2, Integrator::SymplecticEuler, flat, 0.01)
        .expect("a valid simulation");
    let mut sim3 = Simulation::new(protocol3, Integrator::SymplecticEuler, lifted, 0.01)
        .expect("a valid simulation");
    for _ in 0..1000 {
        sim2.step();
        sim3.step();
    }
    assert_eq!(sim2.graph(), sim3.graph());
    for (q2, q3) in sim2.swarm().positions.iter().zip(&sim3.swarm().positions) {
        assert_abs_diff_eq!(*q2, q3.truncate(), epsilon = 1e-9);
        assert_eq!(q3.z, 0.0);
    }
    assert_abs_diff_eq!(
        sim2.energy(),
        sim3.energy(),
        epsilon = 1e-9 * sim2.energy().abs()
    );
}
