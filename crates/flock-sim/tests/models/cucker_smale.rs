//! Cucker–Smale 2007 against a brute-force step, its alignment theorem bracketed from both sides.

use super::*;

/// One symplectic Euler step of Cucker–Smale, brute force.
fn cucker_smale_step<V: Vector>(
    q: &[V],
    p: &[V],
    beta: f64,
    h: f64,
    side: Option<f64>,
) -> (Vec<V>, Vec<V>) {
    let n = q.len();
    let mut q2 = q.to_vec();
    let mut p2 = p.to_vec();
    for i in 0..n {
        let mut u = V::ZERO;
        for j in 0..n {
            if j != i {
                let r2 = offset(q[i], q[j], side).length_squared();
                u += (p[j] - p[i]) * (1.0 / (1.0 + r2).powf(beta));
            }
        }
        p2[i] = p[i] + u * (1.0 / n as f64) * h;
        q2[i] = wrapped(q[i] + p2[i] * h, side);
    }
    (q2, p2)
}

fn cucker_smale_agrees<V: Vector>(side: Option<f64>) {
    let swarm = match side {
        Some(l) => near_the_wrap::<V>(40, l, 2.0, 11),
        None => random_swarm::<V>(40, 20.0, 2.0, 11),
    };
    let model = CuckerSmale::new(CuckerSmaleParams::with_beta(0.3), 5.0, 40, domain(side)).unwrap();
    let h = 0.05;
    let reference = |_, q: &[V], p: &[V]| cucker_smale_step(q, p, 0.3, h, side);
    agrees_with_reference(model, swarm, (h, side, 20), reference, (1e-10, 1e-12));
}

#[test]
fn cucker_smale_equals_brute_force_open_and_periodic_2d_3d() {
    cucker_smale_agrees::<DVec2>(None);
    cucker_smale_agrees::<DVec3>(None);
    cucker_smale_agrees::<DVec2>(Some(30.0));
    cucker_smale_agrees::<DVec3>(Some(30.0));
}

fn mismatch<V: Vector>(p: &[V]) -> f64 {
    let mean = p.iter().fold(V::ZERO, |a, &v| a + v) / p.len() as f64;
    p.iter().map(|&v| (v - mean).length()).fold(0.0, f64::max)
}

/// Cucker & Smale 2007 Theorem 1 (β < 1/2): velocities align from any start, here 10 random
/// wide ones (positions over 200 units, speeds up to 5), and the mean velocity is conserved.
#[test]
fn cucker_smale_aligns_unconditionally_below_one_half() {
    for beta in [0.25, 0.45] {
        for seed in 0..10 {
            let swarm = random_swarm::<DVec2>(12, 100.0, 5.0, 100 + seed);
            let mean0 = swarm.mean_velocity();
            let model = CuckerSmale::new(CuckerSmaleParams::with_beta(beta), 8.4, 12, Domain::Open)
                .unwrap();
            // RK4 with h = 0.5: the rates λ ψ ≤ 1 keep it stable and accurate
            let mut sim = Simulation::new(model, Integrator::Rk4, swarm, 0.5).unwrap();
            let mut steps = 0;
            while mismatch(&sim.swarm().velocities) >= 1e-6 && steps < 2_000_000 {
                sim.step();
                steps += 1;
            }
            let p = sim.swarm().velocities.clone();
            assert!(
                mismatch(&p) < 1e-6,
                "β = {beta}, seed {seed}: {} after {steps} steps",
                mismatch(&p)
            );
            let mean = p.iter().copied().sum::<DVec2>() / 12.0;
            assert_abs_diff_eq!(mean, mean0, epsilon = 1e-12);
        }
    }
}

/// For two agents ẍ = −λ ψ(x) ẋ on their separation x, so ẋ(t) − ẋ(0) = −λ ∫_{x(0)}^{x(t)} ψ:
/// with β = 1 (ψ = 1/(1 + s²), ∫_{x₀}^∞ ψ = π/2 − atan x₀) and ẋ(0) above λ(π/2 − atan x₀),
/// the pair never aligns: its relative speed stays above ẋ(0) − λ(π/2 − atan x₀) > 0, and the
/// first integral holds along the run. The same start with β = 0.25 aligns.
#[test]
fn cucker_smale_beyond_one_half_keeps_a_fast_pair_apart() {
    let (x0, v0) = (1.0, 2.0);
    let start = Swarm::new(
        vec![DVec2::ZERO, DVec2::new(x0, 0.0)],
        vec![DVec2::new(-v0 / 2.0, 0.0), DVec2::new(v0 / 2.0, 0.0)],
    );
    // λ/N with N = 2 on each agent: the separation feels 2 λ/N = λ
    let params = CuckerSmaleParams {
        lambda: 1.0,
        ..CuckerSmaleParams::with_beta(1.0)
    };
    let model = CuckerSmale::new(params, 8.4, 2, Domain::Open).unwrap();
    let mut sim = Simulation::new(model, Integrator::Rk4, start.clone(), 0.01).unwrap();
    for _ in 0..100_000 {
        sim.step();
    }
    let s = sim.swarm();
    let x = (s.positions[1] - s.positions[0]).x;
    let v = (s.velocities[1] - s.velocities[0]).x;
    let bound = v0 - (core::f64::consts::FRAC_PI_2 - x0.atan());
    assert!(
        v > bound && bound > 1.2,
        "relative speed {v}, bound {bound}"
    );
    assert_abs_diff_eq!(v, v0 - (x.atan() - x0.atan()), epsilon = 1e-9);
    // the complement: β = 0.25 aligns the same pair
    let model = CuckerSmale::new(CuckerSmaleParams::with_beta(0.25), 8.4, 2, Domain::Open).unwrap();
    let mut sim = Simulation::new(model, Integrator::Rk4, start, 0.01).unwrap();
    for _ in 0..100_000 {
        sim.step();
    }
    let s = sim.swarm();
    assert!((s.velocities[1] - s.velocities[0]).length() < 1e-6);
}
