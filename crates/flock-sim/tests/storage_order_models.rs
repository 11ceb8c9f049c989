//! The classic models of agents numbered at random are stored by cell, in open space and on a
//! torus, ideal and under conditions, with results bit-identical to the agents kept in their
//! original order.

use flock_math::{Domain, Vector};
use flock_metrics::MetricParams;
use flock_protocols::{
    Couzin, CouzinParams, CuckerSmale, CuckerSmaleParams, Protocol, Swarm, Vasarhelyi,
    VasarhelyiParams, Vicsek,
};
use flock_sim::conditions::{Communication, Conditions, Loss, Noise, Sensing};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{following, random_swarm, vicsek_on_a_torus};
use crate::storage_order::{InOriginalOrder, assert_same_metrics, assert_same_step};

/// 20 steps of `step` (a re-sort at step 16) of `protocol` in `domain` under `conditions`, from
/// `start` (agents numbered at random), stored by cell against the same protocol kept in
/// original order: the same state, energy, failures and diagnostics bits after every step, the
/// same graph and metrics at the end.
fn model_stored_by_cell<V: Vector, P: Protocol<V> + Clone>(
    protocol: &P,
    start: &Swarm<V>,
    domain: Domain<V>,
    conditions: &Conditions,
    step: f64,
) {
    fn build<V: Vector, Q: Protocol<V>>(
        protocol: Q,
        start: &Swarm<V>,
        domain: Domain<V>,
        conditions: &Conditions,
        step: f64,
    ) -> Simulation<V, Q> {
        Simulation::new(protocol, Integrator::SymplecticEuler, start.clone(), step)
            .expect("a valid simulation")
            .with_domain(domain)
            .expect("a valid domain")
            .with_conditions(conditions, 11)
            .expect("valid conditions")
    }
    assert!(protocol.follows_numbering());
    let mut sorted = build(protocol.clone(), start, domain, conditions, step);
    let mut original = build(
        InOriginalOrder(protocol.clone()),
        start,
        domain,
        conditions,
        step,
    );
    assert!(sorted.stored_by_cell() && !original.stored_by_cell());
    for k in 1..=20 {
        sorted.step();
        original.step();
        assert_same_step(&sorted, &original, &format!("step {k}"));
    }
    assert_eq!(sorted.graph(), original.graph());
    let n = start.len();
    assert!(
        sorted.graph().directed_edge_count() > 4 * n,
        "the test wants neighbours"
    );
    let params = MetricParams {
        d: 1.0,
        collision_distance: 0.25,
    };
    assert_same_metrics(&sorted.metrics(&params), &original.metrics(&params));
}

/// A delay of two steps of `step`, 10 % Bernoulli loss, a communication range of 1.5 `r` and
/// white sensing noise.
fn lossy(step: f64, r: f64) -> Conditions {
    Conditions {
        communication: Some(Communication {
            delay: 2.0 * step,
            range: Some(1.5 * r),
            loss: Loss::Bernoulli { p: 0.1 },
            ..Communication::default()
        }),
        sensing: Some(Sensing {
            noise: Noise::White {
                sigma_q: 0.01 * r,
                sigma_p: 0.01,
            },
            rate: None,
        }),
        ..Conditions::default()
    }
}

/// 20,000 particles at the density ρ = 4 of `fixtures/vicsek1995_fig2a_n400.ron` (the paper's
/// Fig. 2(a)) on a torus of side 70, η = 2.
fn vicsek() -> (Vicsek<DVec2>, Swarm<DVec2>, Domain<DVec2>) {
    let (model, torus) = vicsek_on_a_torus(70.0, 2.0, 3);
    (model, random_swarm(20_000, 35.0, 0.03, 41), torus)
}

#[test]
fn vicsek_on_a_torus_stored_by_cell_is_bit_identical() {
    let (model, start, domain) = vicsek();
    model_stored_by_cell(&model, &start, domain, &Conditions::default(), 1.0);
}

#[test]
fn vicsek_on_a_torus_under_conditions_stored_by_cell_is_bit_identical() {
    let (model, start, domain) = vicsek();
    model_stored_by_cell(&model, &start, domain, &lossy(1.0, 1.0), 1.0);
}

/// Couzin's zones (the defaults: r_r = 1, r_o = 3, r_a = 15, noise 0.05 rad) in 3D, 20,000
/// individuals on a torus of side 240 (about 20 within r_a of each).
#[test]
fn couzin_on_a_torus_stored_by_cell_is_bit_identical() {
    let domain = Domain::Periodic {
        size: DVec3::splat(240.0),
    };
    let model = Couzin::new(CouzinParams::default(), 0.1, 7, domain).expect("valid");
    let start = random_swarm(20_000, 120.0, 3.0, 43);
    model_stored_by_cell(&model, &start, domain, &Conditions::default(), 0.1);
    model_stored_by_cell(&model, &start, domain, &lossy(0.1, 15.0), 0.1);
}

/// Cucker–Smale with a cut-off of 8 (β = 0.3), 20,000 agents, open and on a torus of side 400.
#[test]
fn cucker_smale_with_a_cutoff_stored_by_cell_is_bit_identical() {
    let params = CuckerSmaleParams {
        cutoff: Some(8.0),
        ..CuckerSmaleParams::with_beta(0.3)
    };
    let start: Swarm<DVec2> = random_swarm(20_000, 200.0, 2.0, 47);
    let torus = Domain::Periodic {
        size: DVec2::splat(400.0),
    };
    for domain in [Domain::Open, torus] {
        let model = CuckerSmale::new(params, 8.0, 20_000, domain).expect("valid");
        model_stored_by_cell(&model, &start, domain, &Conditions::default(), 0.05);
    }
    let every_pair =
        CuckerSmale::<DVec2>::new(CuckerSmaleParams::with_beta(0.3), 8.0, 10, Domain::Open)
            .expect("valid");
    assert!(
        !every_pair.follows_numbering(),
        "the all-to-all sum runs in storage order"
    );
}

/// Vásárhelyi's drones (the paper's optimised parameters, r_c = 100 m) in 2D, 20,000 in a
/// square arena of side 6 km (about 20 within r_c of each), ideal and under conditions: the
/// order parameters among the diagnostics.
#[test]
fn vasarhelyi_stored_by_cell_is_bit_identical() {
    let params = VasarhelyiParams {
        arena_side: 6000.0,
        ..VasarhelyiParams::default()
    };
    let model = Vasarhelyi::<DVec2>::new(params).expect("valid");
    let start = random_swarm(20_000, 2800.0, 6.0, 53);
    model_stored_by_cell(&model, &start, Domain::Open, &Conditions::default(), 0.01);
    model_stored_by_cell(&model, &start, Domain::Open, &lossy(0.01, 100.0), 0.01);
}

/// Algorithm 2 on a torus of side 400 computes its inputs through its local form, each
/// neighbour at its nearest image.
#[test]
fn algorithm2_on_a_torus_stored_by_cell_is_bit_identical() {
    let torus = Domain::Periodic {
        size: DVec2::splat(400.0),
    };
    let start = random_swarm(20_000, 200.0, 2.0, 59);
    model_stored_by_cell(
        &following(DVec2::new(1.0, 0.5)),
        &start,
        torus,
        &Conditions::default(),
        0.01,
    );
}
