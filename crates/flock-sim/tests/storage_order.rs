//! Agents numbered at random are stored by cell inside a simulation, with results bit-identical to
//! the agents kept in their original order.

use flock_graph::ProximityNet;
use flock_math::{Domain, Vector};
use flock_metrics::{FlockMetrics, MetricParams};
use flock_obstacles::ObstacleSpec;
use flock_protocols::{Algorithm2, GammaAgent, LocalForm, Protocol, Swarm, Update};
use flock_sim::conditions::{
    Communication, Conditions, Delayed, FaultMode, Faults, Loss, Noise, Sensing, WhenLost,
};
use flock_sim::vehicle::{Unicycle, UnicycleParams};
use flock_sim::{DynVehicle, Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::algorithm3::algorithm3;
use crate::common::{following, random_swarm};
use crate::conditions::everything;

/// `P` kept in original order: its [`Protocol::follows_numbering`] is the default, false.
pub struct InOriginalOrder<P>(pub P);

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

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        self.0.local_form()
    }

    fn update(&self) -> Update {
        self.0.update()
    }

    fn measures_in_domain(&self) -> bool {
        self.0.measures_in_domain()
    }
}

/// The state's bits in original order.
pub fn bits<V: Vector>(swarm: &Swarm<V>) -> Vec<u64> {
    swarm
        .positions
        .iter()
        .chain(&swarm.velocities)
        .flat_map(|v| (0..V::DIM).map(|k| v.coord(k).to_bits()))
        .collect()
}

/// The state, energy, failures and diagnostics of `sorted` and `original` have the same bits.
pub fn assert_same_step<V: Vector, P: Protocol<V>, Q: Protocol<V>>(
    sorted: &Simulation<V, P>,
    original: &Simulation<V, Q>,
    context: &str,
) {
    assert!(
        bits(&sorted.swarm()) == bits(&original.swarm()),
        "{context}"
    );
    assert_eq!(
        sorted.energy().to_bits(),
        original.energy().to_bits(),
        "{context}"
    );
    assert_eq!(sorted.failed(), original.failed(), "{context}");
    assert_eq!(sorted.diagnostics(), original.diagnostics(), "{context}");
}

/// The metrics have the same bits.
pub fn assert_same_metrics(a: &FlockMetrics, b: &FlockMetrics) {
    assert!(
        a.reals().map(f64::to_bits) == b.reals().map(f64::to_bits)
            && a.collisions == b.collisions
            && a.components == b.components,
        "{a:?} {b:?}"
    );
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
            assert_same_step(&sorted, &original, &format!("{integrator:?}, step {step}"));
        }
        assert_eq!(sorted.graph(), original.graph());
        assert!(
            sorted.graph().directed_edge_count() > 4 * 20_000,
            "the test wants neighbours"
        );
        let (a, b) = (sorted.observe(&params), original.observe(&params));
        assert_same_metrics(&a.metrics, &b.metrics);
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

/// The γ-agent's velocity of the conditioned runs below.
const VELOCITY: DVec2 = DVec2::new(1.0, 0.5);

/// Algorithm 2 following the γ-agent (`following(VELOCITY)`) from `swarm` after `steps` steps
/// of 0.01 s, with the symplectic Euler step.
fn resume(swarm: Swarm<DVec2>, steps: u64) -> Simulation<DVec2, Algorithm2<DVec2>> {
    Simulation::resume(
        following(VELOCITY),
        Integrator::SymplecticEuler,
        swarm,
        0.01,
        steps,
    )
    .expect("a valid simulation")
}

/// Symmetric Bernoulli loss, white sensing noise, the delay applied to the own state too, and
/// agents removed at a rate: the conditions `everything` leaves out.
fn removing() -> Conditions {
    Conditions {
        communication: Some(Communication {
            delay: 0.02,
            delayed: Delayed::All,
            loss: Loss::Bernoulli { p: 0.1 },
            symmetric: true,
            ..Communication::default()
        }),
        sensing: Some(Sensing {
            noise: Noise::White {
                sigma_q: 0.05,
                sigma_p: 0.02,
            },
            rate: None,
        }),
        faults: Some(Faults {
            at: Vec::new(),
            rate: 2.0,
            mode: FaultMode::Removed,
        }),
        ..Conditions::default()
    }
}

/// Point masses or unicycles (`unicycles`, TurtleBot3 defaults) of 20,000 agents numbered at
/// random under `conditions`, 20 steps (a re-sort at step 16) stored by cell against the same
/// protocol kept in original order: the same state, vehicle states, failures, diagnostics (the
/// vehicles' limits hit and tracking error among them) and checkpointed state of the conditions
/// after every step, the same metrics at the end; and a run resumed after step 17 from the
/// state, the vehicle states and the conditions' state (sorted afresh from the original order)
/// continues with the same bits.
fn stored_by_cell_under(conditions: &Conditions, unicycles: bool) {
    fn build<P: Protocol<DVec2>>(
        sim: Simulation<DVec2, P>,
        unicycles: bool,
        states: Option<Vec<f64>>,
        conditions: &Conditions,
    ) -> Simulation<DVec2, P> {
        let sim = if unicycles {
            let unicycle: DynVehicle<DVec2> =
                Box::new(Unicycle::new(UnicycleParams::default()).expect("valid"));
            sim.with_vehicle(unicycle, states).expect("a valid vehicle")
        } else {
            sim
        };
        sim.with_conditions(conditions, 5)
            .expect("valid conditions")
    }
    let params = MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    let start: Swarm<DVec2> = random_swarm(20_000, 200.0, 2.0, 23);
    let mut sorted = build(resume(start.clone(), 0), unicycles, None, conditions);
    let original = Simulation::new(
        InOriginalOrder(following(VELOCITY)),
        Integrator::SymplecticEuler,
        start,
        0.01,
    )
    .expect("a valid simulation");
    let mut original = build(original, unicycles, None, conditions);
    assert!(!original.stored_by_cell() && sorted.stored_by_cell());
    let vehicle_bits = |states: Option<std::borrow::Cow<'_, [f64]>>| -> Option<Vec<u64>> {
        states.map(|s| s.iter().map(|x| x.to_bits()).collect())
    };
    let mut resumed = None;
    for step in 1..=20 {
        sorted.step();
        original.step();
        if let Some(resumed) = resumed.as_mut() {
            Simulation::step(resumed);
        }
        let context = format!("step {step}");
        assert!(
            bits(&sorted.swarm()) == bits(&original.swarm()),
            "{context}"
        );
        assert!(
            vehicle_bits(sorted.vehicle_states()) == vehicle_bits(original.vehicle_states()),
            "{context}"
        );
        assert_eq!(sorted.failed(), original.failed(), "{context}");
        assert_eq!(sorted.diagnostics(), original.diagnostics(), "{context}");
        let state = sorted.conditions_state();
        assert!(state == original.conditions_state(), "{context}");
        if step == 17 {
            let states = sorted.vehicle_states().map(std::borrow::Cow::into_owned);
            let swarm = sorted.swarm().into_owned();
            let mut from = build(resume(swarm, sorted.steps()), unicycles, states, conditions);
            assert!(from.stored_by_cell(), "sorted again");
            if let Some(state) = state {
                from.restore_conditions(state).expect("the same run");
            }
            resumed = Some(from);
        }
    }
    let resumed = resumed.expect("resumed after step 17");
    assert!(bits(&resumed.swarm()) == bits(&sorted.swarm()), "resumed");
    assert!(
        vehicle_bits(resumed.vehicle_states()) == vehicle_bits(sorted.vehicle_states()),
        "resumed"
    );
    assert_eq!(resumed.diagnostics(), sorted.diagnostics(), "resumed");
    if let Some(failed) = sorted.failed() {
        assert!(failed.contains(&true), "the test wants failed agents");
    }
    assert_same_metrics(&sorted.metrics(&params), &original.metrics(&params));
}

#[test]
fn every_condition_stored_by_cell_is_bit_identical() {
    stored_by_cell_under(&everything(), false);
}

#[test]
fn removed_agents_and_symmetric_loss_stored_by_cell_are_bit_identical() {
    stored_by_cell_under(&removing(), false);
}

#[test]
fn unicycles_stored_by_cell_are_bit_identical() {
    stored_by_cell_under(&Conditions::default(), true);
}

#[test]
fn unicycles_under_conditions_stored_by_cell_are_bit_identical() {
    stored_by_cell_under(&for_unicycles(), true);
}

/// A run resumed with its conditions' state restored (agents stored by cell, the state moved
/// with them) and then put in a periodic domain, which puts the agents back in original order
/// before wrapping them (and sorts them again): the state goes back with the agents, and the run
/// continues as the uninterrupted one and as the one resumed with the domain set first.
#[test]
fn a_domain_set_after_restored_conditions_moves_their_state_back() {
    let domain = Domain::Periodic {
        size: DVec2::splat(400.0),
    };
    let conditions = everything();
    let mut whole = resume(random_swarm(20_000, 200.0, 2.0, 29), 0)
        .with_domain(domain)
        .expect("a valid domain")
        .with_conditions(&conditions, 5)
        .expect("valid conditions");
    for _ in 0..10 {
        whole.step();
    }
    let state = whole.conditions_state().expect("conditions");
    let swarm = whole.swarm().into_owned();
    let mut first = resume(swarm.clone(), 10)
        .with_conditions(&conditions, 5)
        .expect("valid conditions");
    assert!(
        first.stored_by_cell(),
        "the test wants agents stored by cell"
    );
    first
        .restore_conditions(state.clone())
        .expect("the same run");
    let mut first = first.with_domain(domain).expect("a valid domain");
    let mut last = resume(swarm, 10)
        .with_domain(domain)
        .expect("a valid domain")
        .with_conditions(&conditions, 5)
        .expect("valid conditions");
    last.restore_conditions(state).expect("the same run");
    for _ in 0..10 {
        whole.step();
        first.step();
        last.step();
    }
    assert!(
        bits(&first.swarm()) == bits(&whole.swarm()),
        "domain set last"
    );
    assert!(
        bits(&last.swarm()) == bits(&whole.swarm()),
        "domain set first"
    );
}

/// The conditions a unicycle takes that keep a state: a delay line with jitter, Gilbert–Elliott
/// loss holding the last value, Ornstein–Uhlenbeck sensing, agents failing silent at a rate.
fn for_unicycles() -> Conditions {
    Conditions {
        communication: Some(Communication {
            delay: 0.03,
            jitter: 0.02,
            loss: Loss::GilbertElliott {
                p_fail: 0.3,
                p_recover: 2.0,
            },
            when_lost: WhenLost::Hold { max_age: 0.1 },
            ..Communication::default()
        }),
        sensing: Some(Sensing {
            noise: Noise::OrnsteinUhlenbeck {
                sigma_q: 0.05,
                sigma_p: 0.02,
                correlation_time: 0.5,
            },
            rate: None,
        }),
        faults: Some(Faults {
            at: Vec::new(),
            rate: 2.0,
            mode: FaultMode::Silent,
        }),
        ..Conditions::default()
    }
}
