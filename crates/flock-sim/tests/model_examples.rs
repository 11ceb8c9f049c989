//! The models' documented behaviour run in time: the runs behind the examples of
//! flock-protocols' docs, which compute one input (the laws' crate does not depend on the loop).

use flock_graph::Graph;
use flock_math::Domain;
use flock_protocols::{
    ArenaShape, Consensus, CuckerSmale, CuckerSmaleParams, Swarm, Vasarhelyi, VasarhelyiParams,
};
use flock_sim::{Integrator, Simulation};
use glam::DVec2;

/// A path of three agents: their velocities meet at the mean, (1, 0).
#[test]
fn consensus_meets_at_the_mean() -> Result<(), Box<dyn std::error::Error>> {
    let graph = Graph::from_edges(3, &[(0, 1), (1, 2)])?;
    let p = vec![DVec2::new(3.0, 0.0), DVec2::ZERO, DVec2::ZERO];
    let swarm = Swarm::new(vec![DVec2::ZERO; 3], p);
    let mut sim = Simulation::new(
        Consensus::fixed(1.0, graph, 1.0)?,
        Integrator::Rk4,
        swarm,
        0.05,
    )?;
    for _ in 0..800 {
        sim.step();
    }
    assert!(
        sim.swarm()
            .velocities
            .iter()
            .all(|v| (*v - DVec2::X).length() < 1e-9)
    );
    Ok(())
}

/// Two drones 10 m apart are pushed apart towards r_0^rep = 25 m.
#[test]
fn vasarhelyi_pushes_a_close_pair_apart() -> Result<(), flock_protocols::ParamError> {
    let model = Vasarhelyi::new(VasarhelyiParams {
        arena_shape: ArenaShape::Square,
        arena_side: 250.0,
        arena_centre: None,
        ..VasarhelyiParams::default()
    })?;
    let q = vec![DVec2::ZERO, DVec2::new(10.0, 0.0)];
    let p = vec![DVec2::new(0.0, 6.0), DVec2::new(0.0, 6.0)];
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, Swarm::new(q, p), 0.01)?;
    for _ in 0..500 {
        sim.step();
    }
    let q = &sim.swarm().positions;
    assert!((q[1] - q[0]).length() > 15.0);
    Ok(())
}

/// Two agents 30 m apart align at their initial mean velocity (0, 1) (Cucker & Smale 2007,
/// β = 1/4 < 1/2: unconditional flocking).
#[test]
fn cucker_smale_aligns_at_the_mean() -> Result<(), flock_protocols::ParamError> {
    let q = vec![DVec2::ZERO, DVec2::new(30.0, 0.0)];
    let p = vec![DVec2::new(1.0, 0.0), DVec2::new(-1.0, 2.0)];
    let model = CuckerSmale::new(CuckerSmaleParams::with_beta(0.25), 8.4, 2, Domain::Open)?;
    let mut sim = Simulation::new(model, Integrator::Rk4, Swarm::new(q, p), 0.05)?;
    for _ in 0..4000 {
        sim.step();
    }
    let v = sim.swarm().velocities.clone();
    assert!((v[0] - v[1]).length() < 1e-6);
    assert!((v[0] - DVec2::new(0.0, 1.0)).length() < 1e-6);
    Ok(())
}
