//! Bit-identical results whatever the number of threads.

use flock_protocols::Swarm;
use flock_sim::{Integrator, Simulation};
use glam::DVec2;

use crate::common::{following, random_swarm};

fn run(threads: usize, integrator: Integrator) -> Swarm<DVec2> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        let protocol = following(DVec2::new(1.0, 0.0));
        let mut sim = Simulation::new(
            protocol,
            integrator,
            random_swarm(2000, 100.0, 2.0, 8),
            0.01,
        )
        .expect("a valid simulation");
        for _ in 0..60 {
            sim.step();
        }
        sim.swarm().into_owned()
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

/// A simulation resumed from the state and step count of an interrupted one (a checkpoint) goes
/// on bit-identically, the time-dependent γ-agent included.
#[test]
fn a_resumed_simulation_is_bit_identical_to_the_uninterrupted_one() {
    let protocol = || following(DVec2::new(1.0, 0.5));
    for integrator in [Integrator::SymplecticEuler, Integrator::Rk4] {
        let start = random_swarm(300, 40.0, 2.0, 3);
        let mut whole = Simulation::new(protocol(), integrator, start.clone(), 0.01)
            .expect("a valid simulation");
        let mut first =
            Simulation::new(protocol(), integrator, start, 0.01).expect("a valid simulation");
        for _ in 0..37 {
            whole.step();
            first.step();
        }
        let mut resumed = Simulation::resume(
            protocol(),
            integrator,
            first.swarm().into_owned(),
            0.01,
            first.steps(),
        )
        .expect("a valid simulation");
        assert_eq!(resumed.time().to_bits(), whole.time().to_bits());
        for _ in 0..41 {
            whole.step();
            resumed.step();
        }
        assert_eq!(resumed.steps(), 78);
        assert_eq!(resumed.swarm(), whole.swarm(), "{integrator:?}");
        assert_eq!(resumed.energy().to_bits(), whole.energy().to_bits());
    }
}
