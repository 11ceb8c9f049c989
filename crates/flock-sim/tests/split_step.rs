//! A step split around a controller outside the loop ([`Simulation::perceive`], then
//! [`Simulation::act`]) is the step: given the protocol's own inputs of what the agents perceive
//! ([`Simulation::protocol_inputs`]) it gives [`Simulation::step`]'s bits, ideal and under every
//! condition, in 2D and 3D, agents stored by cell or not; and a local form that takes every
//! perception at once ([`LocalForm::takes_all`]) gives the bits of the same form block by block.

use flock_graph::ProximityNet;
use flock_math::{Domain, Vector};
use flock_protocols::{LocalForm, Perceived, Perceptions, Protocol, Swarm, Update};
use flock_sim::conditions::Conditions;
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{following, random_swarm};
use crate::conditions::everything;
use crate::storage_order::{assert_same_step, bits};

/// `P` with its local form taking every perception in one call.
struct AllAtOnce<P>(P);

impl<V: Vector, P: Protocol<V>> Protocol<V> for AllAtOnce<P> {
    fn interaction_range(&self) -> f64 {
        self.0.interaction_range()
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        self.0.controls(t, swarm, net, inputs);
    }

    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.0.energy(t, swarm, net)
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    fn update(&self) -> Update {
        self.0.update()
    }
}

impl<V: Vector, P: Protocol<V>> LocalForm<V> for AllAtOnce<P> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        self.0
            .local_form()
            .expect("a local form")
            .local_input(t, own, heard)
    }

    fn local_inputs(&self, t: f64, all: Perceptions<'_, V>, out: &mut [V]) {
        assert!(out.len() > 64, "every agent at once, not a block");
        self.0
            .local_form()
            .expect("a local form")
            .local_inputs(t, all, out);
    }

    fn takes_all(&self) -> bool {
        true
    }
}

fn simulation<V: Vector, P: Protocol<V>>(
    protocol: P,
    conditions: &Conditions,
    domain: Domain<V>,
) -> Simulation<V, P> {
    let start: Swarm<V> = random_swarm(300, 25.0, 2.0, 5);
    Simulation::new(protocol, Integrator::SymplecticEuler, start, 0.01)
        .and_then(|s| s.with_domain(domain))
        .and_then(|s| s.with_conditions(conditions, 3))
        .expect("a valid simulation")
}

/// 120 steps: `step` against perceive → the protocol's inputs → act, and against the protocol
/// taking every perception at once, compared after every step.
fn split_step_is_the_step<V: Vector>(conditions: &Conditions, domain: Domain<V>) {
    let protocol = following(V::from_fn(|k| if k == 0 { 1.0 } else { 0.0 }));
    let mut whole = simulation(protocol.clone(), conditions, domain);
    let mut split = simulation(protocol.clone(), conditions, domain);
    let mut at_once = simulation(AllAtOnce(protocol), conditions, domain);
    let mut inputs = vec![V::ZERO; 300];
    let (mut perceived, mut held) = (0, 0);
    for k in 1..=120 {
        whole.step();
        at_once.step();
        match split.perceive() {
            Some(percepts) => {
                assert_eq!(percepts.len(), 300);
                perceived += 1;
                assert!(split.protocol_inputs(&mut inputs));
            }
            None => {
                held += 1;
                assert!(!split.protocol_inputs(&mut inputs), "nothing perceived");
            }
        }
        split.act(&inputs);
        assert_same_step(&split, &whole, &format!("split, step {k}"));
        assert!(
            bits(&at_once.swarm()) == bits(&whole.swarm()),
            "at once, step {k}"
        );
    }
    let sampled = conditions.control.is_some();
    assert_eq!((perceived, held), if sampled { (60, 60) } else { (120, 0) });
}

#[test]
fn the_split_step_is_the_step_ideal_2d_and_3d() {
    split_step_is_the_step::<DVec2>(&Conditions::default(), Domain::Open);
    split_step_is_the_step::<DVec3>(&Conditions::default(), Domain::Open);
}

#[test]
fn the_split_step_is_the_step_under_every_condition() {
    split_step_is_the_step::<DVec2>(&everything(), Domain::Open);
    let mut three = everything();
    if let Some(wind) = three.disturbance.as_mut().and_then(|d| d.wind.as_mut()) {
        wind.mean = vec![0.1, 0.0, 0.0];
    }
    split_step_is_the_step::<DVec3>(&three, Domain::Open);
}

#[test]
fn the_split_step_is_the_step_on_a_torus() {
    let torus = Domain::Periodic {
        size: DVec2::splat(60.0),
    };
    split_step_is_the_step::<DVec2>(&Conditions::default(), torus);
    split_step_is_the_step::<DVec2>(&everything(), torus);
}

/// Perceiving twice before acting gives the same perceptions; in the ideal run they are the true
/// state, each neighbour within the interaction range once, in ascending index.
#[test]
fn perceptions_are_the_true_state_in_the_ideal_run() {
    let mut sim = simulation(following(DVec2::X), &Conditions::default(), Domain::Open);
    let first: Vec<_> = {
        let p = sim.perceive().expect("every step is a control update");
        let all = p.perceptions();
        all.receivers().map(|(o, h)| (*o, h.to_vec())).collect()
    };
    let swarm = sim.swarm().into_owned();
    let graph = sim.graph().into_owned();
    let again = sim.perceive().expect("the same update");
    for (i, ((own, heard), (own2, heard2))) in first
        .iter()
        .zip(again.perceptions().receivers())
        .enumerate()
    {
        assert_eq!((own, heard.as_slice()), (own2, heard2));
        assert_eq!(
            (own.agent as usize, own.position, own.velocity),
            (i, swarm.positions[i], swarm.velocities[i])
        );
        let ids: Vec<u32> = heard.iter().map(|h| h.agent).collect();
        assert_eq!(ids, graph.neighbours(i), "agent {i}");
        for h in heard {
            let j = h.agent as usize;
            assert_eq!(
                (h.position, h.velocity),
                (swarm.positions[j], swarm.velocities[j])
            );
        }
    }
    assert!(
        graph.directed_edge_count() > 300,
        "the test wants neighbours"
    );
}
