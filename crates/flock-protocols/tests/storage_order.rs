//! Agents numbered at random are stored by cell inside a simulation, with results bit-identical to
//! the agents kept in their original order.

use flock_graph::ProximityNet;
use flock_math::Vector;
use flock_metrics::{FlockMetrics, MetricParams};
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

    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        self.0.diagnostics(t, swarm, net)
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
/// original order, from 20,000 agents numbered at random: the same state, graph, energy, metrics
/// and diagnostics bits after every step, with both integrators.
fn stored_by_cell_is_bit_identical<V: Vector, P: Protocol<V> + Clone>(protocol: &P, half: f64) {
    assert!(protocol.follows_numbering());
    let params = MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    for integrator in [Integrator::SymplecticEuler, Integrator::Rk4] {
        let start: Swarm<V> = random_swarm(20_000, half, 2.0, 17);
        let mut sorted = Simulation::new(protocol.clone(), integrator, start.clone(), 0.01)
            .expect("a valid simulation");
        let mut original =
            Simulation::new(InOriginalOrder(protocol.clone()), integrator, start, 0.01)
                .expect("a valid simulation");
        assert!(!original.stored_by_cell() && sorted.stored_by_cell());
        for step in 0..=17 {
            if step > 0 {
                sorted.step();
                original.step();
            }
            let context = format!("{integrator:?}, step {step}");
            assert!(
                bits(&sorted.swarm()) == bits(&original.swarm()),
                "{context}"
            );
            assert_eq!(
                sorted.energy().to_bits(),
                original.energy().to_bits(),
                "{context}"
            );
        }
        assert_eq!(sorted.graph(), original.graph());
        assert!(
            sorted.graph().directed_edge_count() > 4 * 20_000,
            "the test wants neighbours"
        );
        let (a, b) = (sorted.observe(&params), original.observe(&params));
        assert!(
            a.metrics.reals().map(f64::to_bits) == b.metrics.reals().map(f64::to_bits)
                && a.metrics.collisions == b.metrics.collisions
                && a.metrics.components == b.metrics.components,
            "{a:?} {b:?}"
        );
        assert_eq!(a.diagnostics, b.diagnostics);
        assert_eq!(
            sorted.component_velocity_mismatch().to_bits(),
            original.component_velocity_mismatch().to_bits()
        );
    }
}

/// Issue 12: measuring the state of 20,000 agents numbered at random (stored by cell) through
/// the simulation gives the metrics of the state in original order with its brute-force net —
/// not those of the original-order state read against the storage-order net (Ẽ = 4238 and 1
/// collision where the truth was Ẽ = 0.119 and 2909 collisions).
#[test]
fn issue_12_metrics_of_agents_stored_by_cell_are_those_of_the_original_order_state() {
    let start: Swarm<DVec2> = random_swarm(20_000, 200.0, 2.0, 12);
    let mut sim = Simulation::new(
        following(DVec2::new(1.0, 0.5)),
        Integrator::SymplecticEuler,
        start,
        0.01,
    )
    .expect("a valid simulation");
    for _ in 0..5 {
        sim.step();
    }
    assert!(sim.stored_by_cell(), "the test wants agents stored by cell");
    let params = MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    let measured = sim.metrics(&params);
    let state = sim.swarm();
    let brute = ProximityNet::brute_force(&state.positions, 8.4);
    let truth = FlockMetrics::measure(&state.positions, &state.velocities, &brute, &params);
    assert!(truth.collisions > 1000, "{truth:?}");
    assert_eq!(measured.collisions, truth.collisions);
    assert_eq!(measured.components, truth.components);
    for (got, want) in measured.reals().iter().zip(truth.reals()) {
        approx::assert_relative_eq!(*got, want, max_relative = 1e-12);
    }
    assert_eq!(*sim.graph(), *brute.graph());
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
