//! The local form of each distributed protocol against its whole-swarm form: given the exact
//! state, u_i from agent i's perception is the u_i of `Protocol::controls`, bit for bit, in 2D
//! and 3D; and agents heard beyond the interaction range change nothing.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{TannerPotential, Vector};
use flock_obstacles::{ObstacleSpec, Space};
use flock_protocols::{
    Algorithm1, AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, BallObstacle,
    CentralisedTracking2003, Consensus, Flocking2003, GammaAgent, NavigationalFeedback,
    ObstacleFlocking2003, ObstacleParams, Perceived, Perceptions, Protocol, StressForm, Swarm,
    TannerJadbabaiePappas, TranslationalController, random_connected_graph,
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
    let bits = |v: V| {
        (0..V::DIM)
            .map(|k| v.coord(k).to_bits())
            .collect::<Vec<_>>()
    };
    for (i, &u) in inputs.iter().enumerate() {
        let graph = protocol.interaction_graph().unwrap_or(net.graph());
        let heard: Vec<_> = graph
            .neighbours(i)
            .iter()
            .map(|&j| exact(swarm, j as usize))
            .collect();
        let own = exact(swarm, i);
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
    // every receiver at once through `local_inputs`, the odd ones having heard nothing: the
    // bits of `local_input` of each (the pair terms of one receiver run on into the next one's)
    let graph = protocol.interaction_graph().unwrap_or(net.graph());
    let owns: Vec<_> = (0..swarm.len()).map(|i| exact(swarm, i)).collect();
    let (mut heard, mut ends) = (Vec::new(), Vec::new());
    for i in 0..swarm.len() {
        if i % 2 == 0 {
            heard.extend(
                graph
                    .neighbours(i)
                    .iter()
                    .map(|&j| exact(swarm, j as usize)),
            );
        }
        ends.push(heard.len());
    }
    let mut out = vec![V::ZERO; swarm.len()];
    let block = Perceptions {
        owns: &owns,
        heard: &heard,
        ends: &ends,
    };
    local.local_inputs(t, block, &mut out);
    for (i, (&u, (own, heard))) in out.iter().zip(block.receivers()).enumerate() {
        assert!(i % 2 == 0 || heard.is_empty());
        assert_eq!(
            bits(u),
            bits(local.local_input(t, own, heard)),
            "agent {i} in a batch"
        );
        if i % 2 == 0 {
            assert_eq!(bits(u), bits(inputs[i]), "agent {i} in a batch");
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
        &Consensus::fixed(0.7, graph.clone(), 8.4).expect("valid"),
        &swarm,
        0.0,
    );
    let tanner = TannerJadbabaiePappas::new(graph, TannerPotential::new(3.0), 8.4);
    local_is_controls(&tanner.expect("connected"), &swarm, 0.0);
    for form in [
        AlphaAlphaForm::Nonsmooth,
        AlphaAlphaForm::Smooth,
        AlphaAlphaForm::Approximate,
    ] {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), form, 0.8);
        local_is_controls(&alpha, &swarm, 20.0);
        local_is_controls(&StressForm(alpha.clone()), &swarm, 20.0);
        let sink = NavigationalFeedback::linear(
            GammaAgent::ConstantVelocity {
                position: V::ZERO,
                velocity: V::from_fn(|k| [0.5, -1.0, 0.25][k]),
            },
            0.1,
            0.5,
        );
        for translation in [None, Some(sink)] {
            let flocking = Flocking2003 {
                alpha: alpha.clone(),
                translation,
            };
            local_is_controls(&flocking, &swarm, 20.0);
            let ball = BallObstacle::new(V::from_fn(|k| [5.0, -3.0, 0.0][k]), 4.0).expect("a ball");
            let obstacles = ObstacleFlocking2003 {
                params: ObstacleParams::for_alpha(alpha.params()),
                flocking,
                obstacles: vec![ball],
            };
            local_is_controls(&obstacles, &swarm, 20.0);
        }
    }
}

/// The 2003 centralised tracking needs the flock's centre of mass: it has no local form.
#[test]
fn centralised_tracking_has_no_local_form() {
    let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), AlphaAlphaForm::Smooth, 1.0);
    let tracking = CentralisedTracking2003::<DVec2>::new(
        alpha,
        TranslationalController::sink(DVec2::ZERO, 1.0),
    );
    assert!(Protocol::<DVec2>::local_form(&tracking).is_none());
}

#[test]
fn local_forms_give_the_bits_of_controls_2d() {
    every_protocol::<DVec2>();
}

#[test]
fn local_forms_give_the_bits_of_controls_3d() {
    every_protocol::<DVec3>();
}

/// Vásárhelyi et al. 2018 in an arena smaller than the swarm and a communication range shorter
/// than it (r_c = 20 m, r_0^rep = 8 m, r_0^frict = 5 m): every term and the cuts in play.
fn vasarhelyi_local_is_controls<V: Space>() {
    use flock_protocols::{ArenaShape, Vasarhelyi, VasarhelyiParams};
    let swarm = random_swarm::<V>(120, 25.0, 9.0, 7);
    for arena_shape in [ArenaShape::Square, ArenaShape::Circle] {
        let params = VasarhelyiParams {
            r_c: 20.0,
            r0_rep: 8.0,
            r0_frict: 5.0,
            arena_shape,
            arena_centre: Some([3.0, -2.0, 1.0][..V::DIM].to_vec()),
            arena_side: 40.0,
            ..VasarhelyiParams::default()
        };
        let model = Vasarhelyi::<V>::new(params).expect("valid");
        local_is_controls(&model, &swarm, 40.0);
    }
}

#[test]
fn vasarhelyi_local_form_gives_the_bits_of_controls_2d_3d() {
    vasarhelyi_local_is_controls::<DVec2>();
    vasarhelyi_local_is_controls::<DVec3>();
}
