//! Vicsek et al. 1995 against a brute-force step, and its order at low and full noise.

use super::*;

/// One Vicsek step, brute force: move with v(t), then the mean heading within r (self
/// included) plus the same keyed noise.
fn vicsek_step(
    q: &[DVec2],
    p: &[DVec2],
    params: VicsekParams,
    streams: &Streams,
    k: u64,
    side: Option<f64>,
) -> (Vec<DVec2>, Vec<DVec2>) {
    let n = q.len();
    let moved: Vec<DVec2> = (0..n).map(|i| wrapped(q[i] + p[i], side)).collect();
    let turned = (0..n)
        .map(|i| {
            let sum: DVec2 = (0..n)
                .filter(|&j| j == i || offset(q[i], q[j], side).length() < params.r)
                .map(|j| p[j])
                .sum();
            let noise =
                params.eta * (streams.draws(Purpose::ModelNoise, i as u64, k).uniform() - 0.5);
            let theta = sum.y.atan2(sum.x) + noise;
            DVec2::new(theta.cos(), theta.sin()) * params.v0
        })
        .collect();
    (moved, turned)
}

fn vicsek_headings(n: usize, seed: u64, v0: f64) -> Vec<DVec2> {
    let streams = Streams::new(seed ^ 0x5eed);
    (0..n)
        .map(|i| {
            let a = core::f64::consts::TAU * streams.draws(Purpose::Failure, i as u64, 0).uniform();
            DVec2::new(a.cos(), a.sin()) * v0
        })
        .collect()
}

#[test]
fn vicsek_equals_brute_force_open_and_periodic() {
    let params = VicsekParams {
        v0: 0.3,
        r: 1.0,
        eta: 1.5,
    };
    for side in [None, Some(5.0)] {
        let n = 100;
        let mut swarm = near_the_wrap::<DVec2>(n, 5.0, 0.3, 3);
        swarm.velocities = vicsek_headings(n, 3, params.v0);
        let model = Vicsek::new(params, 1.0, 9, domain(side)).unwrap();
        let streams = Streams::new(9);
        let reference = |k, q: &[DVec2], p: &[DVec2]| vicsek_step(q, p, params, &streams, k, side);
        agrees_with_reference(model, swarm, (1.0, side, 30), reference, (1e-9, 1e-12));
    }
}

/// v_a of a Vicsek run at density ρ = N/L² = 4 (v₀ = 0.03, r = 1), averaged over the last
/// `average` of `steps` steps.
fn vicsek_order(n: usize, eta: f64, steps: u64, average: u64, seed: u64) -> f64 {
    let side = (n as f64 / 4.0).sqrt();
    let params = VicsekParams {
        v0: 0.03,
        r: 1.0,
        eta,
    };
    let mut swarm = random_swarm::<DVec2>(n, side / 2.0, 0.0, seed);
    for q in &mut swarm.positions {
        *q += DVec2::splat(side / 2.0);
    }
    swarm.velocities = vicsek_headings(n, seed, params.v0);
    let torus = Domain::Periodic {
        size: DVec2::splat(side),
    };
    let model = Vicsek::new(params, 1.0, seed, torus).unwrap();
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 1.0)
        .unwrap()
        .with_domain(torus)
        .unwrap();
    let mut total = 0.0;
    for k in 0..steps {
        sim.step();
        if k >= steps - average {
            let sum: DVec2 = sim.swarm().velocities.iter().copied().sum();
            total += sum.length() / (n as f64 * params.v0);
        }
    }
    total / average as f64
}

/// Vicsek et al. 1995 Fig. 2(a): at ρ = 4 the particles order (v_a near 1) at small noise, and at
/// η = 2π (headings uniform) v_a is of the size of a sum of N random unit vectors,
/// E v_a ≈ √(π/4) / √N.
#[test]
fn vicsek_orders_at_low_noise_and_not_at_full_noise() {
    let n = 400;
    let low = vicsek_order(n, 0.1, 1500, 200, 1);
    assert!(low > 0.95, "η = 0.1: v_a = {low}");
    let full = vicsek_order(n, core::f64::consts::TAU, 300, 200, 1);
    let random = (core::f64::consts::PI / 4.0).sqrt() / (n as f64).sqrt();
    assert!(
        full > 0.5 * random && full < 2.0 * random,
        "η = 2π: v_a = {full}, {random}"
    );
}
