//! Long runs (ignored by default; run with `cargo test --release -p flock-protocols --test lib
//! long_run -- --ignored --nocapture`, about two minutes): over 10⁶ steps of Algorithm 1 the total
//! momentum Σ p_i is still its initial value up to round-off (TAC 2006 Lemma 2: Σ u_i = 0 since
//! φ_α is odd in q_j − q_i and a_ij is symmetric).

use flock_protocols::{Algorithm1, Swarm};
use flock_sim::{Integrator, Simulation};
use glam::DVec2;

use crate::common::{papers_alpha, random_swarm};

#[test]
#[ignore = "10⁶ steps: about two minutes in a release build"]
fn algorithm_1_preserves_momentum_over_a_million_steps() {
    const STEPS: u64 = 1_000_000;
    let start: Swarm<DVec2> = random_swarm(100, 30.0, 2.0, 21);
    // A common drift, so that the momentum compared against is far from zero.
    let drift = DVec2::new(1.0, 0.5);
    let start = Swarm::new(
        start.positions,
        start.velocities.iter().map(|&p| p + drift).collect(),
    );
    let momentum = |s: &Swarm<DVec2>| s.velocities.iter().copied().sum::<DVec2>();
    let initial = momentum(&start);
    let mut sim = Simulation::new(
        Algorithm1 {
            alpha: papers_alpha(),
        },
        Integrator::SymplecticEuler,
        start,
        0.01,
    )
    .expect("a valid simulation");
    let mut worst = 0.0_f64;
    for _ in 0..STEPS / 1000 {
        for _ in 0..1000 {
            sim.step();
        }
        let drift = (momentum(&sim.swarm()) - initial).length() / initial.length();
        worst = worst.max(drift);
    }
    println!(
        "Algorithm 1, n = 100, {STEPS} steps: largest relative momentum drift {worst:.3e}, final {:.3e}",
        (momentum(&sim.swarm()) - initial).length() / initial.length()
    );
    assert!(worst <= 1e-9, "momentum drifted by {worst:e} (relative)");
}
