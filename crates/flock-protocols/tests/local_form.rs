//! The local form of each distributed protocol against its whole-swarm form: given the exact
//! state, u_i from agent i's perception is the u_i of `Protocol::controls`, bit for bit, in 2D
//! and 3D; and agents heard beyond the interaction range change nothing.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::Vector;
use flock_obstacles::{ObstacleSpec, Space};
use flock_protocols::{
    Algorithm1, Consensus, GammaAgent, Perceived, Protocol, Swarm, random_connected_graph,
};
use glam::{DVec2, DVec3};

use crate::algorithm3::{algorithm3, lifted};
use crate::common::{following, papers_alpha, random_swarm};

/// The state of agent `j` as it is.
fn exact<V: Vector>(swarm: &Swarm<V>, j: usize) -> Perceived<V> {
    Perceived {
        agent: j as u32,
        position: swarm.positions[j],
        velocity: swarm.velocities[j],
    }
}

/// Asserts that every agent's local input from its exact neighbours (and, with `extra`, every
/// agent within `extra` as well) has the bits of `controls`.
fn local_is_controls<V: Vector, P: Protocol<V>>(protocol: &P, swarm: &Swarm<V>, extra: f64) {
    let local = protocol.local_form().expect("a distributed protocol");
    let r = protocol.interaction_range();
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build(&swarm.positions, r, &mut net);
    let mut inputs = vec![V::ZERO; swarm.len()];
    let t = 1.5;
    protocol.controls(t, swarm, &net, &mut inputs);
    let mut wide = ProximityNet::new();
    NeighbourSearch::new().build(&swarm.positions, r.max(extra), &mut wide);
    for (i, &u) in inputs.iter().enumerate() {
        let graph = protocol.interaction_graph().unwrap_or(net.graph());
        let heard: Vec<_> = graph
            .neighbours(i)
            .iter()
            .map(|&j| exact(swarm, j as usize))
            .collect();
        let own = exact(swarm, i);
        let bits = |v: V| {
            (0..V::DIM)
                .map(|k| v.coord(k).to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(
            bits(local.local_input(t, &own, &heard)),
            bits(u),
            "agent {i}"
        );
        if protocol.interaction_graph().is_none() {
            let more: Vec<_> = wide
                .graph()
                .neighbours(i)
                .iter()
                .map(|&j| exact(swarm, j as usize))
                .collect();
            approx::assert_relative_eq!(
                local.local_input(t, &own, &more).length(),
                u.length(),
                max_relative = 1e-12,
                epsilon = 1e-12
            );
        }
    }
}

fn every_protocol<V: Space>() {
    let swarm = random_swarm::<V>(120, 25.0, 2.0, 7);
    local_is_controls(
        &Algorithm1 {
            alpha: papers_alpha(),
        },
        &swarm,
        20.0,
    );
    local_is_controls(&following(V::from_fn(|k| [1.0, 0.5, 0.0][k])), &swarm, 20.0);
    let ball = [ObstacleSpec::Ball {
        centre: lifted::<V>(&[5.0, -3.0]),
        radius: 4.0,
    }];
    let gamma = GammaAgent::Static { position: V::ZERO };
    local_is_controls(&algorithm3::<V>(&ball, gamma), &swarm, 20.0);
    local_is_controls(
        &Consensus::proximity(0.7, 8.4).expect("valid"),
        &swarm,
        20.0,
    );
    let graph = random_connected_graph(120, 0.02, 3);
    local_is_controls(
        &Consensus::fixed(0.7, graph, 8.4).expect("valid"),
        &swarm,
        0.0,
    );
}

#[test]
fn local_forms_give_the_bits_of_controls_2d() {
    every_protocol::<DVec2>();
}

#[test]
fn local_forms_give_the_bits_of_controls_3d() {
    every_protocol::<DVec3>();
}
