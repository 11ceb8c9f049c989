//! Algorithm 2 (TAC 2006): 60 agents meet at a static γ-agent; prints the energy H, which Theorem 3
//! makes non-increasing, and the mean speed.
//!
//! `cargo run --release -p flock-protocols --example rendezvous`

use flock_protocols::{
    Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, Integrator, NavigationalFeedback,
    Simulation, Swarm,
};
use glam::DVec2;

fn main() {
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
        alpha: AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0),
        navigation,
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01);
    println!("t,energy,mean_speed,edges");
    for _ in 0..=20 {
        let speed = sim
            .swarm()
            .velocities
            .iter()
            .map(|p| p.length())
            .sum::<f64>()
            / 60.0;
        println!(
            "{},{:.6},{speed:.6},{}",
            sim.time(),
            sim.energy(),
            sim.net().graph().undirected_edge_count()
        );
        for _ in 0..500 {
            sim.step();
        }
    }
}
