//! The 2003 protocols (seed 004; seed 003; seed 000): momentum, α-lattice equilibria, the gradient
//! structure of (α, α, 2), the PD (stress) form, the error bound of eq. 37, dissipation of the
//! structural energy, the sink and the separation principle, β-agents on balls and obstacle
//! avoidance.

use approx::assert_abs_diff_eq;
use flock_graph::ProximityNet;
use flock_math::{Bump, Potential, UnevenSigmoid, Vector};
use flock_obstacles::Space;
use flock_protocols::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, BallObstacle, Flocking2003, GammaAgent,
    NavigationalFeedback, ObstacleFlocking2003, ObstacleParams, Protocol, StressForm, Swarm,
    influence_map_lipschitz,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{energy_along, planar, random_swarm, triangular_lattice};

/// ‖a − b‖ ≤ epsilon for vectors of either dimension.
#[track_caller]
fn assert_close<V: Vector>(a: V, b: V, epsilon: f64) {
    assert!(
        (a - b).length() <= epsilon,
        "{a:?} vs {b:?} (tolerance {epsilon})"
    );
}

const FORMS: [AlphaAlphaForm; 3] = [
    AlphaAlphaForm::Nonsmooth,
    AlphaAlphaForm::Smooth,
    AlphaAlphaForm::Approximate,
];

fn protocol(form: AlphaAlphaForm) -> AlphaAlpha {
    AlphaAlpha::new(AlphaAlphaParams::default(), form, 1.0)
}

fn net<V: Vector>(q: &[V]) -> ProximityNet {
    ProximityNet::brute_force(q, AlphaAlphaParams::default().r)
}

fn controls<V: Vector, P: Protocol<V>>(protocol: &P, t: f64, swarm: &Swarm<V>) -> Vec<V> {
    let net = ProximityNet::brute_force(&swarm.positions, protocol.interaction_range());
    let mut u = vec![V::ZERO; swarm.len()];
    protocol.controls(t, swarm, &net, &mut u);
    u
}

/// Σ_i u_i = 0 for every (α, α) form and the stress form (seed 004 § 10).
fn momentum_preserved<V: Vector>() {
    for seed in 0..4 {
        let swarm: Swarm<V> = random_swarm(80, 18.0, 2.0, seed);
        for form in FORMS {
            let direct = controls(&protocol(form), 0.0, &swarm);
            let stress = controls(&StressForm(protocol(form)), 0.0, &swarm);
            for u in [direct, stress] {
                let total = u.iter().fold(V::ZERO, |acc, &ui| acc + ui);
                let scale: f64 = u.iter().map(|ui| ui.length()).sum();
                assert!(scale > 10.0, "the test swarm must interact ({form:?})");
                assert!(
                    total.length() <= 1e-13 * scale,
                    "{form:?}: Σu = {total:?} against Σ‖u‖ = {scale}"
                );
            }
        }
    }
}

#[test]
fn every_form_preserves_momentum_2d() {
    momentum_preserved::<DVec2>();
}

#[test]
fn every_form_preserves_momentum_3d() {
    momentum_preserved::<DVec3>();
}

/// A triangular α-lattice of spacing d_α = 7 with r = 1.2 d_α moving rigidly: every neighbour is at
/// d_α (next ones at √3 d_α > r), where φ_α(0) = ψ_α(0) = 0 — so the gradient coefficient of all
/// three forms vanishes whatever ρ — and the velocities agree: u = 0 and V = 0 (Proposition 2 i).
fn lattice_is_an_equilibrium<V: Vector>() {
    let q: Vec<V> = triangular_lattice(5, 6, 7.0);
    let velocity = V::from_fn(|k| 1.5 - k as f64);
    let swarm = Swarm::new(q.clone(), vec![velocity; q.len()]);
    let lattice_net = net(&q);
    assert_eq!(
        lattice_net.graph().undirected_edge_count(),
        5 * 5 + 4 * 11,
        "5 edges in each row, 11 between consecutive rows"
    );
    for form in FORMS {
        for u in [
            controls(&protocol(form), 0.0, &swarm),
            controls(&StressForm(protocol(form)), 0.0, &swarm),
        ] {
            for ui in u {
                assert!(ui.length() <= 1e-13, "{form:?}: u = {ui:?} on an α-lattice");
            }
        }
        assert!(protocol(form).potential(&lattice_net).abs() <= 1e-13);
        assert!(protocol(form).structural_energy(&swarm, &lattice_net) <= 1e-13);
    }
    // and a perturbed lattice is not an equilibrium and has V > 0
    let mut bent = q;
    bent[7] += V::from_fn(|k| 0.4 * (k as f64 + 1.0));
    let u = controls(
        &protocol(AlphaAlphaForm::Smooth),
        0.0,
        &Swarm::new(bent.clone(), vec![V::ZERO; 30]),
    );
    assert!(u[7].length() > 0.1);
    assert!(protocol(AlphaAlphaForm::Smooth).potential(&net(&bent)) > 0.01);
}

#[test]
fn triangular_lattice_is_an_equilibrium_2d() {
    lattice_is_an_equilibrium::<DVec2>();
}

#[test]
fn triangular_lattice_is_an_equilibrium_in_the_plane_of_3d() {
    lattice_is_an_equilibrium::<DVec3>();
}

/// (α, α, 2) is a gradient protocol: at rest (p = 0) its input is −∇V with V = ½ ΣΣ a_ij ψ_α
/// (eq. 30), checked against central differences of V on random configurations whose pairs spread
/// over the whole range, the cosine part of ρ included.
fn smooth_force_is_the_gradient<V: Vector>() {
    let alpha = protocol(AlphaAlphaForm::Smooth);
    let step = 1e-6;
    let mut in_cosine_part = 0;
    for seed in 0..3 {
        let q = random_swarm::<V>(30, 9.0, 0.0, 100 + seed).positions;
        let swarm = Swarm::new(q.clone(), vec![V::ZERO; q.len()]);
        let u = controls(&alpha, 0.0, &swarm);
        let here = net(&q);
        in_cosine_part += here
            .distances()
            .iter()
            .filter(|&&d| d > 7.0 && d < 8.4)
            .count();
        for i in 0..q.len() {
            for axis in 0..V::DIM {
                let e = V::from_fn(|k| if k == axis { step } else { 0.0 });
                let mut plus = q.clone();
                plus[i] += e;
                let mut minus = q.clone();
                minus[i] -= e;
                let fd =
                    (alpha.potential(&net(&plus)) - alpha.potential(&net(&minus))) / (2.0 * step);
                assert_abs_diff_eq!(
                    -fd,
                    u[i].coord(axis),
                    epsilon = 1e-7 * (1.0 + u[i].length())
                );
            }
        }
    }
    assert!(
        in_cosine_part >= 20,
        "only {in_cosine_part} directed edges test the ρ′ term"
    );
}

#[test]
fn smooth_force_is_minus_the_gradient_of_v_2d() {
    smooth_force_is_the_gradient::<DVec2>();
}

#[test]
fn smooth_force_is_minus_the_gradient_of_v_3d() {
    smooth_force_is_the_gradient::<DVec3>();
}

/// u = −L_s(q) q − c_d L(q) p (seed 000 eq. 39) is the direct form it rewrites, for every form and
/// a non-unit damping gain.
fn stress_form_equals_direct_form<V: Vector>() {
    for seed in 0..3 {
        let swarm: Swarm<V> = random_swarm(70, 15.0, 3.0, 40 + seed);
        for form in FORMS {
            let direct = AlphaAlpha::new(AlphaAlphaParams::default(), form, 0.7);
            let u = controls(&direct, 0.0, &swarm);
            let u_pd = controls(&StressForm(direct.clone()), 0.0, &swarm);
            let scale = u.iter().map(|ui| ui.length()).fold(0.0, f64::max);
            assert!(scale > 1.0);
            for (a, b) in u.iter().zip(&u_pd) {
                assert_close(*a, *b, 1e-13 * scale);
            }
        }
    }
}

#[test]
fn stress_form_equals_direct_form_2d() {
    stress_form_equals_direct_form::<DVec2>();
}

#[test]
fn stress_form_equals_direct_form_3d() {
    stress_form_equals_direct_form::<DVec3>();
}

/// The stress weights are φ/‖q_j − q_i‖ of the ACC-2004 action function (seed 000 eq. 26): one
/// hand-computed pair, at 8 (in the cosine part of ρ, flat part d_α/r = 5/6, k = 1).
#[test]
fn stress_weight_of_a_pair_by_hand() {
    let alpha = protocol(AlphaAlphaForm::Smooth);
    let q = [DVec2::ZERO, DVec2::new(8.0, 0.0)];
    let net = net(&q);
    let weights = StressForm(alpha).stress_weights(&net);
    // z = 1, a = 1, b = 5, c = 4/√20: φ_α(1) = 3 (1 + c)/√(1 + (1 + c)²) − 2,
    // ψ_α(1) = 3 (√(1 + (1 + c)²) − √(1 + c²)) − 2
    let c = 4.0 / 20f64.sqrt();
    let phi = 3.0 * (1.0 + c) / (1.0 + (1.0 + c) * (1.0 + c)).sqrt() - 2.0;
    let psi = 3.0 * ((1.0 + (1.0 + c) * (1.0 + c)).sqrt() - (1.0 + c * c).sqrt()) - 2.0;
    // ρ(8/8.4) with θ = π (8/8.4 − 5/6)/(1/6)
    let theta = std::f64::consts::PI * (8.0 / 8.4 - 5.0 / 6.0) * 6.0;
    let rho = 0.5 * (1.0 + theta.cos());
    let rho_prime = -std::f64::consts::PI * 3.0 * theta.sin();
    let expected = (rho * phi + rho_prime * psi / 8.4) / 8.0;
    assert_abs_diff_eq!(weights.weights()[0], expected, epsilon = 1e-14);
    assert_abs_diff_eq!(weights.weights()[1], expected, epsilon = 1e-14);
}

/// L_ρ = max |ρ′| in closed form, against a fine sampling of ρ′ for several powers k.
#[test]
fn influence_map_lipschitz_constant_is_the_max_slope() {
    for (delta, k) in [(5.0 / 6.0, 1), (0.2, 1), (0.5, 2), (0.3, 3), (0.1, 6)] {
        let bump = Bump::influence_map(delta, k);
        let sampled = (0..=200_000)
            .map(|i| bump.derivative(f64::from(i) / 200_000.0).abs())
            .fold(0.0, f64::max);
        let lipschitz = influence_map_lipschitz(bump);
        assert!(lipschitz >= sampled, "δ = {delta}, k = {k}");
        assert!(lipschitz <= sampled * (1.0 + 1e-8), "δ = {delta}, k = {k}");
    }
    assert_abs_diff_eq!(
        influence_map_lipschitz(Bump::influence_map(0.5, 1)),
        std::f64::consts::PI,
        epsilon = 1e-15
    );
    // seed 003 after eq. 5: −π/(2(1 − δ)) ≤ ρ′_δ ≤ 0, e.g. |ρ′_δ| < 5.25 for δ = 0.7
    for delta in [0.1, 0.7, 0.95] {
        let bump = Bump::influence_map(delta, 1);
        let bound = std::f64::consts::PI / (2.0 * (1.0 - delta));
        for i in 0..=20_000 {
            let slope = bump.derivative(1.2 * f64::from(i) / 20_000.0);
            assert!((-bound..=0.0).contains(&slope), "δ = {delta}: ρ′ = {slope}");
        }
        // attained at the middle of the transition, so the bound is sharp
        assert_abs_diff_eq!(
            bump.derivative(0.5 * (1.0 + delta)),
            -bound,
            epsilon = 1e-12
        );
    }
    assert!(influence_map_lipschitz(Bump::influence_map(0.7, 1)) < 5.25);
}

/// Seed 004 eq. 37: Σ_i ‖u_i^(α,α,2) − û_i^(α,α,2)‖ ≤ (2 L_ρ / r) V(q), V of eq. 28.
fn approximation_within_bound<V: Vector>() {
    let smooth = protocol(AlphaAlphaForm::Smooth);
    let approximate = protocol(AlphaAlphaForm::Approximate);
    for seed in 0..8 {
        let swarm: Swarm<V> = random_swarm(60, 14.0, 2.0, 200 + seed);
        let here = net(&swarm.positions);
        let (u, u_hat) = (
            controls(&smooth, 0.0, &swarm),
            controls(&approximate, 0.0, &swarm),
        );
        let error: f64 = u.iter().zip(&u_hat).map(|(a, b)| (*a - *b).length()).sum();
        let bound = smooth.approximation_error_bound(&here);
        assert!(
            error > 1e-3,
            "the configuration must use ρ′ (error {error})"
        );
        assert!(error <= bound, "error {error} above the bound {bound}");
    }
}

#[test]
fn approximation_is_within_the_bound_of_eq_37_2d() {
    approximation_within_bound::<DVec2>();
}

#[test]
fn approximation_is_within_the_bound_of_eq_37_3d() {
    approximation_within_bound::<DVec3>();
}

/// Why eq. 37's V must be eq. 28's (0/1 adjacency): for a pair near the edge of the range, a_ij
/// vanishes faster than ρ′, and the bound with the smooth V of eq. 30 fails.
#[test]
fn eq_37_needs_the_binary_potential() {
    let smooth = protocol(AlphaAlphaForm::Smooth);
    let approximate = protocol(AlphaAlphaForm::Approximate);
    let swarm = Swarm::new(
        vec![DVec2::ZERO, DVec2::new(0.97 * 8.4, 0.0)],
        vec![DVec2::ZERO; 2],
    );
    let here = net(&swarm.positions);
    let (u, u_hat) = (
        controls(&smooth, 0.0, &swarm),
        controls(&approximate, 0.0, &swarm),
    );
    let error: f64 = u.iter().zip(&u_hat).map(|(a, b)| (*a - *b).length()).sum();
    let lipschitz = influence_map_lipschitz(AlphaAlphaParams::default().bump);
    let with_smooth_v = 2.0 * lipschitz / 8.4 * smooth.potential(&here);
    assert!(error <= smooth.approximation_error_bound(&here));
    assert!(
        error > 5.0 * with_smooth_v,
        "error {error} vs smooth-V bound {with_smooth_v}"
    );
}

/// Proposition 5: H_s = V + K_r does not rise along (α, α, 2), links made and lost included
/// (RK4 with a small step, so the integration error is far below the dissipation).
fn structural_energy_non_increasing<V: Vector>() {
    let swarm: Swarm<V> = random_swarm(30, 11.0, 1.5, 7);
    let mut sim = Simulation::new(
        protocol(AlphaAlphaForm::Smooth),
        Integrator::Rk4,
        swarm,
        0.005,
    )
    .expect("a valid simulation");
    let links = sim.graph().undirected_edge_count();
    let (start, end) = energy_along(&mut sim, 800, Simulation::energy);
    assert!(end < 0.5 * start, "H_s must dissipate: {start} → {end}");
    assert_ne!(sim.graph().undirected_edge_count(), links);
}

#[test]
fn structural_energy_non_increasing_2d() {
    structural_energy_non_increasing::<DVec2>();
}

#[test]
fn structural_energy_non_increasing_3d() {
    structural_energy_non_increasing::<DVec3>();
}

/// Seed 004 eq. 31: the structural energy of (α, α, 1) (0/1 adjacency, eq. 28) jumps by
/// h₀ = ψ_α(r − d_α) > 0 at the step where a link is made, and by −h₀ where one is lost; between
/// the switches it does not rise (Proposition 4). A pair closing from r + 0.3 at 1 m/s, and one
/// leaving from r − 0.3 at 8 m/s, RK4 at h = 10⁻⁴ for 0.5 s: the jump is h₀ to within the
/// step's own change, and every other step changes H_s by less than 1 % of h₀.
#[test]
fn the_nonsmooth_energy_jumps_by_h0_when_a_link_is_made_or_lost() {
    let params = AlphaAlphaParams::default();
    let h0 = UnevenSigmoid::new(params.a, params.b).potential(params.r - params.d_alpha);
    assert!(h0 > 0.0);
    for (gap, speed, sign) in [(0.3, 0.5, 1.0), (-0.3, -4.0, -1.0)] {
        let half = 0.5 * (params.r + gap);
        let swarm = Swarm::new(
            vec![DVec2::new(-half, 0.0), DVec2::new(half, 0.0)],
            vec![DVec2::new(speed, 0.0), DVec2::new(-speed, 0.0)],
        );
        let mut sim = Simulation::new(
            protocol(AlphaAlphaForm::Nonsmooth),
            Integrator::Rk4,
            swarm,
            1e-4,
        )
        .expect("a valid simulation");
        let linked = |sim: &Simulation<DVec2, AlphaAlpha>| sim.graph().undirected_edge_count();
        let (mut energy, mut links) = (sim.energy(), linked(&sim));
        let (mut jump, mut largest_other) = (None, 0.0_f64);
        for _ in 0..5000 {
            sim.step();
            let (now, now_links) = (sim.energy(), linked(&sim));
            if now_links == links {
                assert!(now <= energy + 1e-12, "H_s rose between switches");
                largest_other = largest_other.max((now - energy).abs());
            } else {
                assert!(jump.is_none(), "one switch only");
                jump = Some(now - energy);
            }
            (energy, links) = (now, now_links);
        }
        let jump = jump.expect("the link switched");
        eprintln!("ΔH_s = {jump:.6} against ±h₀ = {h0:.6}; other steps ≤ {largest_other:.2e}");
        assert!(
            (jump - sign * h0).abs() <= 10.0 * largest_other,
            "ΔH_s = {jump} against ±h₀ = {h0} (other steps ≤ {largest_other})"
        );
        assert!(largest_other < 1e-2 * h0, "{largest_other} vs h₀ = {h0}");
    }
}

/// Seed 004 eq. 48–52, seed 000 eq. 40: (α, α, 2) plus the PD sink f_i = −c₁(q_i − q_d) − c₂ p_i.
/// Separation principle: the centre of mass follows ¨q̄ = −c₁(q̄ − q_d) − c₂ ˙q̄ exactly, whatever
/// the (α, α) forces — with c₁ = 1, c₂ = 2 (critical), q̄ − q_d = (e₀ + (ė₀ + e₀) t) e^{−t} — its
/// translational energy decreases, and so does the total H.
fn sink<V: Vector>() {
    let q_d = planar::<V>(6.0, -4.0) + V::from_fn(|k| if k == 2 { 3.0 } else { 0.0 });
    let sink = NavigationalFeedback::linear(GammaAgent::Static { position: q_d }, 1.0, 2.0);
    let flocking = Flocking2003 {
        alpha: protocol(AlphaAlphaForm::Smooth),
        translation: Some(sink),
    };
    // random start at rest (seed 004 Fig. 9)
    let swarm: Swarm<V> = random_swarm(30, 25.0, 0.0, 11);
    let e0 = swarm.centre() - q_d;
    let mut sim =
        Simulation::new(flocking, Integrator::Rk4, swarm, 0.01).expect("a valid simulation");
    let translational = |sim: &Simulation<V, Flocking2003<V>>| {
        sim.protocol()
            .translational_energy(sim.time(), &sim.swarm())
            .expect("a sink")
    };
    let (start, end) = energy_along(&mut sim, 1000, translational);
    assert!(end < 1e-6 * start, "H_tr: {start} → {end}");
    let t = sim.time();
    let exact = q_d + e0 * ((1.0 + t) * (-t).exp());
    assert_close(sim.swarm().centre(), exact, 1e-8);
    assert!((sim.swarm().centre() - q_d).length() < 1e-3 * e0.length());
    // the total energy of the closed loop is non-increasing too
    let mut sim = Simulation::new(
        sim.protocol().clone(),
        Integrator::Rk4,
        random_swarm(30, 25.0, 0.0, 12),
        0.01,
    )
    .expect("a valid simulation");
    let (start, end) = energy_along(&mut sim, 500, Simulation::energy);
    assert!(end < 0.2 * start, "H: {start} → {end}");
}

#[test]
fn sink_attracts_the_centre_of_mass_2d() {
    sink::<DVec2>();
}

#[test]
fn sink_attracts_the_centre_of_mass_3d() {
    sink::<DVec3>();
}

/// Seed 004 eq. 55–57 for a ball B(b, l): q̂ = s q + (1 − s) b, s = l/(l + ‖q̂ − q‖),
/// p̂ = s p − l (ṡ/s) n(q̂ − q), ṡ = l pᵀn(q̂ − q)/(l + ‖q̂ − q‖)² — the β-agent of flock-obstacles
/// (μ P p), and the time derivative of q̂ along q̇ = p.
fn beta_agent_is_eq_55_57<V: Space>() {
    let (b, l) = (V::from_fn(|k| [3.0, -2.0, 1.0][k]), 4.0);
    let ball = BallObstacle::<V>::new(b, l).expect("a ball");
    let swarm: Swarm<V> = random_swarm(50, 20.0, 3.0, 5);
    let mut checked = 0;
    for (&q, &p) in swarm.positions.iter().zip(&swarm.velocities) {
        if (q - b).length() <= l + 0.1 {
            continue;
        }
        checked += 1;
        let beta = ball.beta_agent(q, p);
        let distance = (beta.position - q).length();
        let s = l / (l + distance);
        assert_close(beta.position, q * s + b * (1.0 - s), 1e-12);
        let n = (beta.position - q) / distance;
        let s_dot = l * p.dot(n) / ((l + distance) * (l + distance));
        let p_hat = p * s - n * (l * s_dot / s);
        assert_close(beta.velocity, p_hat, 1e-12);
        let h = 1e-6;
        let fd = (ball.beta_agent(q + p * h, p).position - ball.beta_agent(q - p * h, p).position)
            / (2.0 * h);
        assert_close(fd, p_hat, 1e-7);
    }
    assert!(checked > 40);
}

#[test]
fn beta_agent_on_a_ball_is_eq_55_57_2d() {
    beta_agent_is_eq_55_57::<DVec2>();
}

#[test]
fn beta_agent_on_a_ball_is_eq_55_57_3d() {
    beta_agent_is_eq_55_57::<DVec3>();
}

/// Seed 004 eq. 58 with one ball B(centre, radius) and velocity tracking towards p_d only
/// (V_tr ≡ 0, the distributed form of eq. 65–66: c₁ = 0, c₂ = 1), our [`ObstacleParams`].
fn obstacle_protocol<V: Space>(centre: V, radius: f64, p_d: V) -> ObstacleFlocking2003<V> {
    let params = AlphaAlphaParams::default();
    let tracking = NavigationalFeedback::linear(
        GammaAgent::ConstantVelocity {
            position: V::ZERO,
            velocity: p_d,
        },
        0.0,
        1.0,
    );
    ObstacleFlocking2003 {
        flocking: Flocking2003 {
            alpha: AlphaAlpha::new(params, AlphaAlphaForm::Smooth, 1.0),
            translation: Some(tracking),
        },
        obstacles: vec![BallObstacle::<V>::new(centre, radius).expect("a ball")],
        params: ObstacleParams::for_alpha(&params),
    }
}

/// A lone agent heading straight at the centre of a ball at speed 5 is stopped and pushed back
/// before it reaches the ball (the symmetric head-on case has no tangential force to go around).
fn agent_is_repelled<V: Space>() {
    let (centre, radius) = (planar::<V>(40.0, 2.0), 6.0);
    let p_d = planar::<V>(5.0, 0.0);
    let protocol = obstacle_protocol::<V>(centre, radius, p_d);
    let swarm = Swarm::new(vec![planar(10.0, 2.0)], vec![p_d]);
    let mut sim =
        Simulation::new(protocol, Integrator::Rk4, swarm, 0.01).expect("a valid simulation");
    let mut closest = f64::INFINITY;
    let mut slowest = f64::INFINITY;
    for _ in 0..1000 {
        sim.step();
        let (q, p) = (sim.swarm().positions[0], sim.swarm().velocities[0]);
        closest = closest.min((q - centre).length() - radius);
        slowest = slowest.min(p.coord(0));
    }
    assert!(closest > 0.5, "the agent came within {closest} of the ball");
    assert!(slowest < 0.0, "the agent was never pushed back");
    let q = sim.swarm().positions[0];
    assert!(q.coord(0) < centre.coord(0) - radius, "{q:?}");
}

#[test]
fn agent_heading_into_a_ball_is_repelled_2d() {
    agent_is_repelled::<DVec2>();
}

#[test]
fn agent_heading_into_a_ball_is_repelled_3d() {
    agent_is_repelled::<DVec3>();
}

/// Seed 004 eq. 58: a small flock tracking p_d = (5, 0) at a ball splits around it without any
/// agent entering it, and gets past.
fn flock_avoids_a_ball<V: Space>() {
    let (centre, radius) = (planar::<V>(40.0, 2.0), 6.0);
    let p_d = planar::<V>(5.0, 0.0);
    let protocol = obstacle_protocol::<V>(centre, radius, p_d);
    // a 3 × 3 triangular patch around the x-axis, moving at p_d
    let patch: Vec<V> = triangular_lattice(3, 3, 7.0);
    let shift = planar::<V>(-7.0, -6.0);
    let q: Vec<V> = patch.iter().map(|&x| x + shift).collect();
    let swarm = Swarm::new(q.clone(), vec![p_d; q.len()]);
    let mut sim =
        Simulation::new(protocol, Integrator::Rk4, swarm, 0.01).expect("a valid simulation");
    let mut closest = f64::INFINITY;
    let mut active = 0;
    for _ in 0..2000 {
        sim.step();
        for &q in &sim.swarm().positions {
            let clearance = (q - centre).length() - radius;
            closest = closest.min(clearance);
            if clearance <= 4.2 {
                active += 1;
            }
        }
    }
    assert!(active > 100, "the obstacle must have been met");
    assert!(closest > 1.0, "an agent came within {closest} of the ball");
    for &q in &sim.swarm().positions {
        assert!(
            q.coord(0) > centre.coord(0) + radius,
            "an agent is stuck at {q:?}"
        );
    }
}

#[test]
fn flock_avoids_a_ball_2d() {
    flock_avoids_a_ball::<DVec2>();
}

#[test]
fn flock_avoids_a_ball_3d() {
    flock_avoids_a_ball::<DVec3>();
}
