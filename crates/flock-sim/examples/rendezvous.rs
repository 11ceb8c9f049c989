//! Algorithm 2 (TAC 2006): 60 agents meet at a static γ-agent; prints the energy H, which Theorem 3
//! makes non-increasing, the mean speed and the flocking metrics, all measured through the
//! simulation (the state, net and numbering it keeps internally stay consistent).
//!
//! `cargo run --release -p flock-sim --example rendezvous`

use flock_metrics::MetricParams;
use flock_protocols::{
    Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, NavigationalFeedback, ParamError, Swarm,
};
use flock_sim::{Integrator, Simulation};
use glam::DVec2;

fn main() -> Result<(), ParamError> {
    // a deterministic spiral of agents at rest
    let positions = (0..60).map(|i| {
        let angle = 0.7 * f64::from(i);
        DVec2::new(angle.cos(), angle.sin()) * (4.0 + 1.5 * f64::from(i))
    });
    let swarm = Swarm::new(positions.collect(), vec![DVec2::ZERO; 60]);
    let navigation = NavigationalFeedback::linear(
        GammaAgent::Static {
            position: DVec2::ZERO,
        },
        0.02,
        0.4,
    );
    let protocol = Algorithm2 {
        alpha: AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0)?,
        navigation,
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)?;
    let params = MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    println!("t,energy,mean_speed,edges,connectivity,deviation_energy,collisions");
    for _ in 0..=20 {
        let speed = sim
            .swarm()
            .velocities
            .iter()
            .map(|p| p.length())
            .sum::<f64>()
            / 60.0;
        let m = sim.metrics(&params);
        println!(
            "{},{:.6},{speed:.6},{},{},{:.3e},{}",
            sim.time(),
            sim.energy(),
            sim.graph().undirected_edge_count(),
            m.connectivity,
            m.deviation_energy,
            m.collisions
        );
        for _ in 0..500 {
            sim.step();
        }
    }
    Ok(())
}
