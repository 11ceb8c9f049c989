//! Bit-identical results whatever the number of threads.

use flock_protocols::{
    Algorithm2, GammaAgent, Integrator, NavigationalFeedback, Simulation, Swarm,
};
use glam::DVec2;

use crate::common::{papers_alpha, random_swarm};

fn run(threads: usize, integrator: Integrator) -> Swarm<DVec2> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        let navigation = NavigationalFeedback::linear(
            GammaAgent::ConstantVelocity {
                position: DVec2::ZERO,
                velocity: DVec2::new(1.0, 0.0),
            },
            0.05,
            0.4,
        );
        let protocol = Algorithm2 {
            alpha: papers_alpha(),
            navigation,
        };
        let mut sim = Simulation::new(
            protocol,
            integrator,
            random_swarm(2000, 100.0, 2.0, 8),
            0.01,
        );
        for _ in 0..60 {
            sim.step();
        }
        sim.swarm().clone()
    })
}

#[test]
fn one_and_four_threads_are_bit_identical() {
    for integrator in [Integrator::SymplecticEuler, Integrator::Rk4] {
        let (serial, parallel) = (run(1, integrator), run(4, integrator));
        let bits = |s: &Swarm<DVec2>| -> Vec<u64> {
            s.positions
                .iter()
                .chain(&s.velocities)
                .flat_map(|v| [v.x.to_bits(), v.y.to_bits()])
                .collect()
        };
        assert_eq!(bits(&serial), bits(&parallel), "{integrator:?}");
    }
}
