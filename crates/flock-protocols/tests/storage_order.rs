//! Agents numbered at random are stored by cell inside a simulation, with results bit-identical to
//! the agents kept in their original order.

use flock_graph::ProximityNet;
use flock_math::Vector;
use flock_obstacles::ObstacleSpec;
use flock_protocols::{GammaAgent, Integrator, Protocol, Simulation, Swarm};
use glam::{DVec2, DVec3};

use crate::algorithm3::algorithm3;
use crate::common::{following, random_swarm};

/// `P` kept in original order: its [`Protocol::follows_numbering`] is the default, false.
struct InOriginalOrder<P>(P);

impl<V: Vector, P: Protocol<V>> Protocol<V> for InOriginalOrder<P> {
    fn interaction_range(&self) -> f64 {
        self.0.interaction_range()
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        self.0.controls(t, swarm, net, inputs);
    }

    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.0.energy(t, swarm, net)
    }

    fn uses_net_distances(&self) -> bool {
        self.0.uses_net_distances()
    }
}

/// The state's bits in original order.
fn bits<V: Vector>(swarm: &Swarm<V>) -> Vec<u64> {
    swarm
        .positions
        .iter()
        .chain(&swarm.velocities)
        .flat_map(|v| (0..V::DIM).map(|k| v.coord(k).to_bits()))
        .collect()
}

/// 17 steps (a re-sort at step 16) of `protocol` stored by cell against the same protocol kept in
/// original order, from 20,000 agents numbered at random: the same state and energy bits after
/// every step, with both integrators.
fn stored_by_cell_is_bit_identical<V: Vector, P: Protocol<V> + Clone>(protocol: &P, half: f64) {
    assert!(protocol.follows_numbering());
    for integrator in [Integrator::SymplecticEuler, Integrator::Rk4] {
        let start: Swarm<V> = random_swarm(20_000, half, 2.0, 17);
        let mut sorted = Simulation::new(protocol.clone(), integrator, start.clone(), 0.01);
        let mut original =
            Simulation::new(InOriginalOrder(protocol.clone()), integrator, start, 0.01);
        assert!(original.net().is_scattered() && original.numbering().is_identity());
        assert!(!sorted.net().is_scattered() && !sorted.numbering().is_identity());
        for step in 0..=17 {
            if step > 0 {
                sorted.step();
                original.step();
            }
            let state = sorted.swarm();
            assert!(
                bits(&state) == bits(original.stored_swarm()),
                "{integrator:?}, step {step}"
            );
            assert_eq!(
                sorted.energy().to_bits(),
                original.energy().to_bits(),
                "{integrator:?}, step {step}"
            );
        }
        let degree = |net: &ProximityNet| net.graph().directed_edge_count();
        assert_eq!(degree(sorted.net()), degree(original.net()));
        assert!(
            degree(sorted.net()) > 4 * 20_000,
            "the test wants neighbours"
        );
        let (stored, in_order) = (sorted.stored_swarm(), sorted.swarm());
        let numbering = sorted.numbering();
        assert!(
            (0..stored.len())
                .all(|s| stored.positions[s] == in_order.positions[numbering.original(s)])
        );
    }
}

#[test]
fn algorithm2_stored_by_cell_is_bit_identical_2d() {
    stored_by_cell_is_bit_identical(&following(DVec2::new(1.0, 0.5)), 200.0);
}

/// Algorithm 3 in 3D among obstacles inside the swarm (V_β in the energy).
#[test]
fn algorithm3_stored_by_cell_is_bit_identical_3d() {
    let specs = [
        ObstacleSpec::Ball {
            centre: vec![10.0, 0.0, 0.0],
            radius: 20.0,
        },
        ObstacleSpec::Ball {
            centre: vec![-40.0, 30.0, 10.0],
            radius: 15.0,
        },
    ];
    let gamma = GammaAgent::Static {
        position: DVec3::ZERO,
    };
    let protocol = algorithm3::<DVec3>(&specs, gamma);
    stored_by_cell_is_bit_identical(&protocol, 80.0);
}
