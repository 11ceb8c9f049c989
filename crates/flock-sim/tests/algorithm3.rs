//! Algorithm 3 of TAC 2006: obstacle avoidance with β-agents.

use std::cell::Cell;

use flock_graph::ProximityNet;
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::{
    Algorithm2, Algorithm3, BetaInteraction, BetaParams, GammaAgent, NavigationalFeedback,
    Protocol, Swarm,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{energy_along, papers_alpha, random_swarm};

pub(crate) fn lifted<V: Space>(v: &[f64]) -> Vec<f64> {
    (0..V::DIM)
        .map(|k| v.get(k).copied().unwrap_or(0.0))
        .collect()
}

pub(crate) fn algorithm3<V: Space>(specs: &[ObstacleSpec], gamma: GammaAgent<V>) -> Algorithm3<V> {
    let field = ObstacleField::from_specs(specs).expect("valid obstacles");
    Algorithm3 {
        flock: Algorithm2 {
            alpha: papers_alpha(),
            navigation: NavigationalFeedback::bounded(gamma, 2.0, 2.0 * 2f64.sqrt()),
        },
        beta: BetaInteraction::new(
            field,
            BetaParams::papers(7.0),
            0.1,
            10.0,
            2.0 * 10f64.sqrt(),
        )
        .expect("valid β-parameters"),
    }
}

fn controls<V: Space, P: Protocol<V>>(protocol: &P, swarm: &Swarm<V>) -> Vec<V> {
    let net = ProximityNet::brute_force(&swarm.positions, protocol.interaction_range());
    let mut u = vec![V::ZERO; swarm.len()];
    protocol.controls(0.0, swarm, &net, &mut u);
    u
}

/// With every obstacle farther than r′ from every agent, Algorithm 3 is its Algorithm 2, bit for bit.
fn reduces_to_algorithm2<V: Space>() {
    let swarm: Swarm<V> = random_swarm(100, 20.0, 2.0, 21);
    let far = [
        ObstacleSpec::Ball {
            centre: lifted::<V>(&[200.0, 0.0]),
            radius: 10.0,
        },
        ObstacleSpec::Wall {
            point: lifted::<V>(&[0.0, -100.0]),
            normal: lifted::<V>(&[0.0, 1.0]),
        },
    ];
    let gamma = GammaAgent::Static { position: V::ZERO };
    let with_obstacles = algorithm3::<V>(&far, gamma);
    assert_eq!(
        controls(&with_obstacles, &swarm),
        controls(&with_obstacles.flock, &swarm)
    );
    // and an obstacle in range does change the inputs
    let near = [ObstacleSpec::Ball {
        centre: lifted::<V>(&[0.0, 0.0]),
        radius: 3.0,
    }];
    let shifted = Swarm::new(
        swarm
            .positions
            .iter()
            .map(|&q| q + V::from_fn(|_| 30.0))
            .collect(),
        swarm.velocities.clone(),
    );
    let blocked = algorithm3::<V>(&near, GammaAgent::Static { position: V::ZERO });
    assert_ne!(controls(&blocked, &swarm), controls(&blocked.flock, &swarm));
    assert_eq!(
        controls(&blocked, &shifted),
        controls(&blocked.flock, &shifted)
    );
}

#[test]
fn reduces_to_algorithm2_without_obstacles_in_range_2d() {
    reduces_to_algorithm2::<DVec2>();
}

#[test]
fn reduces_to_algorithm2_without_obstacles_in_range_3d() {
    reduces_to_algorithm2::<DVec3>();
}

/// Theorem 6 with a static γ-agent (condition (76) holds for all t): H is non-increasing, and no agent
/// enters an obstacle.
fn theorem6<V: Space>() {
    let specs = [
        ObstacleSpec::Ball {
            centre: lifted::<V>(&[25.0, 2.0]),
            radius: 6.0,
        },
        ObstacleSpec::Wall {
            point: lifted::<V>(&[0.0, -14.0]),
            normal: lifted::<V>(&[0.0, 1.0]),
        },
    ];
    let protocol = algorithm3::<V>(
        &specs,
        GammaAgent::Static {
            position: V::from_fn(|k| if k == 0 { 45.0 } else { 0.0 }),
        },
    );
    let swarm: Swarm<V> = random_swarm(30, 9.0, 0.5, 6);
    let mut sim =
        Simulation::new(protocol, Integrator::Rk4, swarm, 0.002).expect("a valid simulation");
    let closest = Cell::new(f64::INFINITY);
    let energy_and_clearance = |sim: &Simulation<V, Algorithm3<V>>| {
        for &q in &sim.swarm().positions {
            closest.set(closest.get().min(sim.protocol().beta.field().clearance(q)));
        }
        sim.energy()
    };
    let (start, end) = energy_along(&mut sim, 4000, energy_and_clearance);
    let closest = closest.get();
    assert!(
        closest < BetaParams::papers(7.0).r,
        "the run must bring agents near the obstacles"
    );
    assert!(
        closest > 0.5,
        "an agent came within {closest} of an obstacle"
    );
    assert!(end < start, "H must dissipate: {start} → {end}");
}

#[test]
fn theorem6_energy_non_increasing_2d() {
    theorem6::<DVec2>();
}

#[test]
fn theorem6_energy_non_increasing_3d() {
    theorem6::<DVec3>();
}
