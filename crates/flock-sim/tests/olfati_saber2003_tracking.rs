//! The centralised translational controllers of seed 004 (eq. 64, 66) and the flocking separation
//! principle (Proposition 6, eq. 62–63, 65): H_s does not depend on ū and does not rise, while the
//! centre of mass follows its own bounded closed loop and H_tr converges.

use flock_math::{Vector, sigma1_vec};
use flock_obstacles::Space;
use flock_protocols::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, BallObstacle, CentralisedTracking2003,
    ObstacleParams, Swarm, TranslationalController,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::{energy_along, planar, random_swarm, triangular_lattice};

fn alpha() -> AlphaAlpha {
    AlphaAlpha::new(AlphaAlphaParams::default(), AlphaAlphaForm::Smooth, 1.0)
}

/// One RK4 step of the centre-of-mass loop ˙q̄ = p̄, ˙p̄ = ū(q̄, p̄) on its own.
fn rk4_centre<V: Vector>(
    controller: &TranslationalController<V>,
    (q, p): (V, V),
    h: f64,
) -> (V, V) {
    let f = |q: V, p: V| (p, controller.input(q, p));
    let (k1q, k1p) = f(q, p);
    let (k2q, k2p) = f(q + k1q * (0.5 * h), p + k1p * (0.5 * h));
    let (k3q, k3p) = f(q + k2q * (0.5 * h), p + k2p * (0.5 * h));
    let (k4q, k4p) = f(q + k3q * h, p + k3p * h);
    (
        q + (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (h / 6.0),
        p + (k1p + k2p * 2.0 + k3p * 2.0 + k4p) * (h / 6.0),
    )
}

/// Proposition 6 with the sink of eq. 64 (c₂ = 2) on a random swarm in motion:
/// i) H_s(t) is the same as without any translational controller (eq. 62: Ḣ_s does not depend on
///    ū) and does not rise (Proposition 5);
/// ii) q̄, p̄ follow the two-body loop ¨q̄ = −φ(q̄ − q_d) − c₂ φ(˙q̄) integrated on its own (Ḣ_tr does
///    not depend on u^α), and H_tr does not rise (eq. 63) and converges.
fn separation_principle<V: Space>() {
    let swarm: Swarm<V> = random_swarm(30, 12.0, 1.0, 21);
    let q_d = swarm.centre() + planar::<V>(6.0, -4.0);
    let sink = TranslationalController::sink(q_d, 2.0);
    let (h, steps) = (0.005, 5000);
    let mut tracked = Simulation::new(
        CentralisedTracking2003::new(alpha(), sink),
        Integrator::Rk4,
        swarm.clone(),
        h,
    )
    .expect("a valid simulation");
    let mut free =
        Simulation::new(alpha(), Integrator::Rk4, swarm.clone(), h).expect("a valid simulation");
    let mut centre = (swarm.centre(), swarm.mean_velocity());
    // H_s and H_tr as the protocol's diagnostics name them
    let diagnostic = |sim: &Simulation<V, CentralisedTracking2003<V>>, name: &str| {
        let columns = sim.diagnostics();
        columns
            .iter()
            .find(|(n, _)| *n == name)
            .expect("the column")
            .1
    };
    let structural =
        |sim: &Simulation<V, CentralisedTracking2003<V>>| diagnostic(sim, "structural_energy");
    let translational =
        |sim: &Simulation<V, CentralisedTracking2003<V>>| diagnostic(sim, "translational_energy");
    let (h_s0, h_tr0) = (structural(&tracked), translational(&tracked));
    let (mut h_s, mut h_tr) = (h_s0, h_tr0);
    let links = tracked.graph().undirected_edge_count();
    for _ in 0..steps {
        tracked.step();
        free.step();
        centre = rk4_centre(&sink, centre, h);
        let (next_s, next_tr) = (structural(&tracked), translational(&tracked));
        assert!(
            next_s <= h_s * (1.0 + 1e-9),
            "H_s rose from {h_s} to {next_s} at t = {}",
            tracked.time()
        );
        assert!(
            next_tr <= h_tr * (1.0 + 1e-9) + 1e-15,
            "H_tr rose from {h_tr} to {next_tr} at t = {}",
            tracked.time()
        );
        let free_s = free.energy();
        assert!(
            (next_s - free_s).abs() <= 1e-9 * free_s,
            "H_s depends on ū: {next_s} vs {free_s} at t = {}",
            tracked.time()
        );
        (h_s, h_tr) = (next_s, next_tr);
    }
    let state = tracked.swarm();
    assert!((state.centre() - centre.0).length() < 1e-9, "{centre:?}");
    assert!((state.mean_velocity() - centre.1).length() < 1e-9);
    assert!(h_s < 0.5 * h_s0, "H_s must dissipate: {h_s0} → {h_s}");
    assert!(h_tr < 1e-4 * h_tr0, "H_tr must converge: {h_tr0} → {h_tr}");
    assert_ne!(tracked.graph().undirected_edge_count(), links);
}

#[test]
fn separation_principle_with_the_bounded_sink_2d() {
    separation_principle::<DVec2>();
}

#[test]
fn separation_principle_with_the_bounded_sink_3d() {
    separation_principle::<DVec3>();
}

/// Eq. 65–66: p̄ − p_d keeps its direction and its norm e solves ė = −c₂ e/√(1 + e²), so
/// √(1 + e²) + ln(e/(1 + √(1 + e²))) = const − c₂ t; the total H = H_s + H_tr does not rise.
fn group_velocity<V: Space>() {
    let swarm: Swarm<V> = random_swarm(25, 10.0, 2.0, 5);
    let p_d = planar::<V>(3.0, -1.0);
    let c2 = 1.5;
    let tracking = TranslationalController::group_velocity(p_d, c2);
    let mut sim = Simulation::new(
        CentralisedTracking2003::new(alpha(), tracking),
        Integrator::Rk4,
        swarm.clone(),
        0.005,
    )
    .expect("a valid simulation");
    let e0 = swarm.mean_velocity() - p_d;
    let invariant = |e: f64| (1.0 + e * e).sqrt() + (e / (1.0 + (1.0 + e * e).sqrt())).ln();
    let (start, end) = energy_along(&mut sim, 1000, Simulation::energy);
    assert!(end < 0.5 * start, "H: {start} → {end}");
    let e = sim.swarm().mean_velocity() - p_d;
    assert!(
        (e.normalize_or_zero() - e0.normalize_or_zero()).length() < 1e-9,
        "{e:?} vs {e0:?}"
    );
    let drop = invariant(e0.length()) - invariant(e.length());
    assert!((drop - c2 * sim.time()).abs() < 1e-8, "{drop}");
    assert!(e.length() < 1e-2 * e0.length());
}

#[test]
fn group_velocity_tracking_converges_2d() {
    group_velocity::<DVec2>();
}

#[test]
fn group_velocity_tracking_converges_3d() {
    group_velocity::<DVec3>();
}

/// The inputs are the distributed (α, α) inputs plus one common ū = −c₂ φ(p̄ − p_d): with obstacles
/// far away, every agent's input differs from the (α, α) one by the same vector.
#[test]
fn the_common_input_is_added_to_every_agent() {
    let swarm: Swarm<DVec2> = random_swarm(20, 9.0, 1.0, 3);
    let p_d = DVec2::new(10.0, 0.0);
    let ball = BallObstacle::new(DVec2::new(500.0, 0.0), 10.0).expect("a ball");
    let params = ObstacleParams::for_alpha(&AlphaAlphaParams::default());
    let protocol = CentralisedTracking2003::with_obstacles(
        alpha(),
        vec![ball],
        params,
        TranslationalController::group_velocity(p_d, 2.0),
    );
    let net = flock_graph::ProximityNet::brute_force(&swarm.positions, 8.4);
    let mut u = vec![DVec2::ZERO; 20];
    flock_protocols::Protocol::controls(&protocol, 0.0, &swarm, &net, &mut u);
    let common = -sigma1_vec(swarm.mean_velocity() - p_d) * 2.0;
    assert_eq!(protocol.common_input(&swarm), common);
    assert_eq!(protocol.direction(0.0), DVec2::X);
    for (i, &ui) in u.iter().enumerate() {
        let alpha_input = alpha().input(i, &swarm.positions, &swarm.velocities, &net);
        assert!((ui - alpha_input - common).length() < 1e-12);
    }
}

/// Eq. 58 with the report's u^tr = k_tr^(2): a small lattice tracking p_d = (5, 0) flows around a
/// ball without entering it and gets past.
#[test]
fn centralised_tracking_gets_past_a_ball() {
    let (centre, radius) = (DVec2::new(40.0, 2.0), 6.0);
    let p_d = DVec2::new(5.0, 0.0);
    let params = ObstacleParams::for_alpha(&AlphaAlphaParams::default());
    let protocol = CentralisedTracking2003::with_obstacles(
        alpha(),
        vec![BallObstacle::new(centre, radius).expect("a ball")],
        params,
        TranslationalController::group_velocity(p_d, 2.0),
    );
    let q: Vec<DVec2> = triangular_lattice::<DVec2>(3, 3, 7.0)
        .into_iter()
        .map(|x| x + DVec2::new(-7.0, -6.0))
        .collect();
    let swarm = Swarm::new(q.clone(), vec![p_d; q.len()]);
    let mut sim =
        Simulation::new(protocol, Integrator::Rk4, swarm, 0.01).expect("a valid simulation");
    let mut closest = f64::INFINITY;
    for _ in 0..2000 {
        sim.step();
        for &q in &sim.swarm().positions {
            closest = closest.min((q - centre).length() - radius);
        }
    }
    assert!(closest > 1.0, "an agent came within {closest} of the ball");
    assert!(closest < params.r0, "the obstacle must have been met");
    for &q in &sim.swarm().positions {
        assert!(q.x > centre.x + radius, "an agent is stuck at {q:?}");
    }
}
