//! The classic models against independent implementations written here (brute force, O(n²), no
//! code of the models shared: only the keyed random streams, so that both draw the same noise),
//! and their theorems or the papers' numbers bracketed from both sides.

use approx::assert_abs_diff_eq;
use flock_math::stream::{Purpose, Streams};
use flock_math::{Domain, Vector};
use flock_protocols::{
    Arena, ArenaShape, Boids, BoidsParams, Couzin, CouzinParams, CuckerSmale, CuckerSmaleParams,
    Protocol, Swarm, Vasarhelyi, VasarhelyiParams, Vicsek, VicsekParams,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::random_swarm;

/// The minimum image of b − a in a box of side `side` per axis (`None`: open space).
fn offset<V: Vector>(a: V, b: V, side: Option<f64>) -> V {
    let d = b - a;
    match side {
        None => d,
        Some(l) => V::from_fn(|k| {
            let x = d.coord(k);
            x - l * (x / l).round()
        }),
    }
}

/// `q` brought into [0, L) per axis.
fn wrapped<V: Vector>(q: V, side: Option<f64>) -> V {
    match side {
        None => q,
        Some(l) => V::from_fn(|k| {
            let y = q.coord(k) - l * (q.coord(k) / l).floor();
            if y >= l { y - l } else { y }
        }),
    }
}

fn domain<V: Vector>(side: Option<f64>) -> Domain<V> {
    side.map_or(Domain::Open, |l| Domain::Periodic {
        size: V::from_fn(|_| l),
    })
}

/// A swarm with a third of the agents within 1 of a face or corner of the box [0, side)^m.
fn near_the_wrap<V: Vector>(n: usize, side: f64, speed: f64, seed: u64) -> Swarm<V> {
    let mut swarm = random_swarm::<V>(n, side / 2.0, speed, seed);
    for (i, q) in swarm.positions.iter_mut().enumerate() {
        let centred = *q + V::from_fn(|_| side / 2.0);
        *q = if i % 3 == 0 {
            // hug the faces: each coordinate within 1 of 0 or of the side
            V::from_fn(|k| {
                let x = centred.coord(k) / side; // in [0, 1)
                if x < 0.5 { x } else { side - 1.0 + x }
            })
        } else {
            centred
        };
    }
    swarm
}

fn max_gap<V: Vector>(a: &[V], b: &[V]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max)
}

/// Runs `model` from `swarm` in the domain of `side` for `steps` steps of `h` beside the
/// brute-force `reference` (step k and state to the next state), then checks that the states
/// agree: positions within `tolerance.0`, velocities within `tolerance.1`.
fn agrees_with_reference<V: Vector, P: Protocol<V>>(
    model: P,
    swarm: Swarm<V>,
    (h, side, steps): (f64, Option<f64>, u64),
    mut reference: impl FnMut(u64, &[V], &[V]) -> (Vec<V>, Vec<V>),
    tolerance: (f64, f64),
) {
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm.clone(), h)
        .unwrap()
        .with_domain(domain(side))
        .unwrap();
    let (mut q, mut p) = (swarm.positions, swarm.velocities);
    for k in 0..steps {
        sim.step();
        (q, p) = reference(k, &q, &p);
    }
    let state = sim.swarm();
    let (gap_q, gap_p) = (
        max_gap(&state.positions, &q),
        max_gap(&state.velocities, &p),
    );
    assert!(gap_q < tolerance.0, "{side:?}: positions {gap_q}");
    assert!(gap_p < tolerance.1, "{side:?}: velocities {gap_p}");
}

// ---------------------------------------------------------------- Cucker–Smale

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

// ---------------------------------------------------------------- Vicsek

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

// ---------------------------------------------------------------- boids

/// One boids step as the ABM frameworks' declaration writes it, in the activation order given.
fn boids_step<V: Vector>(
    q: &mut [V],
    heading: &mut [V],
    order: &[u32],
    b: BoidsParams,
    h: f64,
    side: Option<f64>,
) {
    for &i in order {
        let i = i as usize;
        let (mut n, mut cohere, mut separate, mut matching) = (0, V::ZERO, V::ZERO, V::ZERO);
        for j in 0..q.len() {
            if j == i {
                continue;
            }
            let d = offset(q[i], q[j], side);
            if d.length() <= b.visual_distance {
                n += 1;
                cohere += d;
                if d.length() < b.separation {
                    separate -= d;
                }
                matching += heading[j];
            }
        }
        let n = f64::from(n.max(1));
        let v = (heading[i]
            + cohere * (b.cohere_factor / n)
            + separate * (b.separate_factor / n)
            + matching * (b.match_factor / n))
            * 0.5;
        heading[i] = v / v.length();
        q[i] = wrapped(q[i] + heading[i] * (b.speed * h), side);
    }
}

fn boids_agree<V: Vector>(side: Option<f64>) {
    let b = BoidsParams {
        visual_distance: 3.0,
        separation: 1.5,
        ..BoidsParams::default()
    };
    let n = 150;
    let mut swarm = near_the_wrap::<V>(n, 20.0, 1.0, 5);
    for p in &mut swarm.velocities {
        *p = p.normalize_or_zero() * b.speed;
    }
    let h = 0.5;
    let model = Boids::new(b, h, 4, domain(side)).unwrap();
    let orders: Vec<Vec<u32>> = (0..10)
        .map(|k| model.activation_order(f64::from(k) * h, n))
        .collect();
    // the declared rule keeps unit headings: the reference steps them and moves at the speed
    let reference = |k: u64, q: &[V], p: &[V]| {
        let (mut q, mut heading) = (
            q.to_vec(),
            p.iter().map(|&p| p / b.speed).collect::<Vec<V>>(),
        );
        boids_step(&mut q, &mut heading, &orders[k as usize], b, h, side);
        (q, heading.into_iter().map(|v| v * b.speed).collect())
    };
    agrees_with_reference(model, swarm, (h, side, 10), reference, (1e-9, 1e-12));
}

#[test]
fn boids_equal_the_declared_sequential_rule_2d_3d_open_and_periodic() {
    boids_agree::<DVec2>(Some(20.0));
    boids_agree::<DVec3>(Some(20.0));
    boids_agree::<DVec2>(None);
    boids_agree::<DVec3>(None);
}

/// On a torus the boids step without the net (their sweep searches its own cells): what the
/// simulation measures between steps is still of the net of the current state, and a step
/// after a measurement has the bits of one without.
#[test]
fn boids_measure_the_net_of_the_current_state() {
    let b = BoidsParams::default();
    let (n, side, h) = (200, 60.0, 1.0);
    let swarm = near_the_wrap::<DVec2>(n, side, b.speed, 3);
    let model = Boids::new(b, h, 2, domain(Some(side))).unwrap();
    let range = model.interaction_range();
    let new = |model| {
        Simulation::new(model, Integrator::SymplecticEuler, swarm.clone(), h)
            .unwrap()
            .with_domain(domain(Some(side)))
            .unwrap()
    };
    let (mut measured, mut unmeasured) = (new(model.clone()), new(model));
    let params = flock_metrics::MetricParams {
        d: 5.0,
        collision_distance: 1.0,
    };
    for _ in 0..5 {
        measured.step();
        unmeasured.step();
        let mut net = flock_graph::ProximityNet::without_distances();
        let now = measured.swarm();
        let torus = domain(Some(side));
        flock_graph::NeighbourSearch::new().build_in(&torus, &now.positions, range, &mut net);
        assert!(net.graph().directed_edge_count() > 0);
        assert_eq!(*measured.graph(), *net.graph());
        let (q, p) = (&now.positions, &now.velocities);
        let metrics = flock_metrics::FlockMetrics::measure_in(&torus, q, p, &net, &params);
        assert_eq!(measured.observe(&params).metrics, metrics);
        assert_eq!(measured.metrics(&params), metrics);
    }
    assert_eq!(measured.swarm(), unmeasured.swarm());
}

#[test]
fn boids_order_is_a_permutation_drawn_anew_each_step() {
    let model = Boids::<DVec2>::new(BoidsParams::default(), 1.0, 1, Domain::Open).unwrap();
    let a = model.activation_order(0.0, 1000);
    let b = model.activation_order(1.0, 1000);
    let mut sorted = a.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..1000).collect::<Vec<u32>>());
    assert_ne!(a, b);
    assert_eq!(a, model.activation_order(0.0, 1000));
}

// ---------------------------------------------------------------- Couzin

/// The desired direction of Couzin et al. 2002 without noise, then the bounded turn, brute force.
fn couzin_step<V: Vector>(
    q: &[V],
    p: &[V],
    c: CouzinParams,
    tau: f64,
    side: Option<f64>,
) -> (Vec<V>, Vec<V>) {
    let n = q.len();
    let r_o = c.r_r + c.delta_r_o;
    let r_a = r_o + c.delta_r_a;
    let half = c.field_of_perception.to_radians() / 2.0;
    let mut p2 = p.to_vec();
    for i in 0..n {
        let v = p[i] / p[i].length();
        let (mut dr, mut dorient, mut da) = (V::ZERO, V::ZERO, V::ZERO);
        let (mut nr, mut no, mut na) = (0, 0, 0);
        for j in 0..n {
            if j == i {
                continue;
            }
            let r = offset(q[i], q[j], side);
            let d = r.length();
            if d >= r_a || v.dot(r / d).clamp(-1.0, 1.0).acos() > half + 1e-12 {
                continue;
            }
            if d < c.r_r {
                dr -= r / d;
                nr += 1;
            } else if d < r_o {
                dorient += p[j] / p[j].length();
                no += 1;
            } else {
                da += r / d;
                na += 1;
            }
        }
        let desired = if nr > 0 {
            dr
        } else if no > 0 && na > 0 {
            (dorient / dorient.length() + da / da.length()) * 0.5
        } else if no > 0 {
            dorient
        } else if na > 0 {
            da
        } else {
            v
        };
        let desired = desired / desired.length();
        let angle = v.dot(desired).clamp(-1.0, 1.0).acos();
        let max = c.turning_rate.to_radians() * tau;
        let heading = if angle <= max {
            desired
        } else {
            // rotate v towards desired by max in their plane
            let w = desired - v * v.dot(desired);
            let w = w / w.length();
            v * max.cos() + w * max.sin()
        };
        p2[i] = heading * c.speed;
    }
    let q2 = (0..n).map(|i| wrapped(q[i] + p2[i] * tau, side)).collect();
    (q2, p2)
}

fn couzin_agrees<V: Vector>(side: Option<f64>) {
    let c = CouzinParams {
        noise: 0.0,
        delta_r_o: 1.5,
        delta_r_a: 3.0,
        ..CouzinParams::default()
    };
    let n = 120;
    let swarm = near_the_wrap::<V>(n, 14.0, 3.0, 8);
    let tau = 0.1;
    let model = Couzin::new(c, tau, 2, domain(side)).unwrap();
    let reference = |_, q: &[V], p: &[V]| couzin_step(q, p, c, tau, side);
    agrees_with_reference(model, swarm, (tau, side, 20), reference, (1e-9, 1e-9));
}

#[test]
fn couzin_equals_brute_force_2d_3d_open_and_periodic() {
    couzin_agrees::<DVec2>(None);
    couzin_agrees::<DVec3>(None);
    couzin_agrees::<DVec2>(Some(14.0));
    couzin_agrees::<DVec3>(Some(14.0));
}

/// The angular noise turns the desired direction by N(0, σ²): over many agents and steps of a
/// lone individual (no neighbours, desired = its heading), the turn's standard deviation is σ
/// (when the turning bound θ τ lets the turns through, as here).
#[test]
fn couzin_noise_has_the_papers_spread() {
    let c = CouzinParams {
        noise: 0.05,
        ..CouzinParams::default()
    };
    // τ = 1 s: the turning bound θ τ = 40° lets every drawn turn through
    let tau = 1.0;
    let n = 2000;
    let q: Vec<DVec2> = (0..n)
        .map(|i| DVec2::new(100.0 * f64::from(i), 0.0))
        .collect();
    let p = vec![DVec2::new(c.speed, 0.0); n as usize];
    let model = Couzin::new(c, tau, 7, Domain::Open).unwrap();
    let mut inputs = vec![DVec2::ZERO; n as usize];
    let swarm = Swarm::new(q, p);
    let net = flock_graph::ProximityNet::brute_force(&swarm.positions, model.interaction_range());
    model.controls(0.0, &swarm, &net, &mut inputs);
    let angles: Vec<f64> = inputs.iter().map(|u| u.y.atan2(u.x)).collect();
    let var = angles.iter().map(|a| a * a).sum::<f64>() / f64::from(n);
    assert!((var.sqrt() - 0.05).abs() < 0.005, "{}", var.sqrt());
}

// ---------------------------------------------------------------- periodic domain

/// A run of Algorithm 1 (the γ-agent-free α-interaction, TAC 2006 eq. 23 with c₁ = c₂ = 1) from
/// a perturbed triangular lattice drifting at `drift`, in `domain`.
fn drifting_lattice(
    domain: Domain<DVec2>,
    drift: DVec2,
    offset: DVec2,
) -> Simulation<DVec2, flock_protocols::Algorithm1> {
    let mut q = crate::common::triangular_lattice::<DVec2>(5, 6, 7.0);
    for (k, x) in q.iter_mut().enumerate() {
        *x += offset
            + DVec2::new(
                0.3 * ((k * 7) % 5) as f64 / 5.0,
                0.2 * ((k * 3) % 4) as f64 / 4.0,
            );
    }
    let p = vec![drift; q.len()];
    let protocol = flock_protocols::Algorithm1 {
        alpha: crate::common::papers_alpha(),
    };
    Simulation::new(
        protocol,
        Integrator::SymplecticEuler,
        Swarm::new(q, p),
        0.01,
    )
    .unwrap()
    .with_domain(domain)
    .unwrap()
}

/// Away from the wrap the torus changes nothing: the run of Algorithm 1 in a box of side 400
/// whose flock stays near its centre has the bits of the run in open space.
#[test]
fn periodic_run_equals_open_space_away_from_the_wrap() {
    let torus = Domain::Periodic {
        size: DVec2::splat(400.0),
    };
    let centre = DVec2::splat(180.0);
    let mut open = drifting_lattice(Domain::Open, DVec2::new(0.5, 0.2), centre);
    let mut periodic = drifting_lattice(torus, DVec2::new(0.5, 0.2), centre);
    for _ in 0..2000 {
        open.step();
        periodic.step();
    }
    let (a, b) = (open.swarm(), periodic.swarm());
    for (x, y) in a
        .positions
        .iter()
        .zip(&b.positions)
        .chain(a.velocities.iter().zip(&b.velocities))
    {
        assert_eq!(
            (x.x.to_bits(), x.y.to_bits()),
            (y.x.to_bits(), y.y.to_bits())
        );
    }
}

/// A lattice drifting across the wrap keeps its shape: its state is the open-space run's,
/// wrapped into the box (to round-off), and its metrics on the torus stay those of open space
/// at every step (connectivity 1, the same deviation energy, cohesion radius and least
/// distance), before, while and after it straddles the faces.
#[test]
fn a_lattice_crossing_the_wrap_keeps_its_metrics() {
    let side = 120.0;
    let torus = Domain::Periodic {
        size: DVec2::splat(side),
    };
    let start = DVec2::new(5.0, 20.0);
    let drift = DVec2::new(4.0, 1.5);
    let mut open = drifting_lattice(Domain::Open, drift, start);
    let mut periodic = drifting_lattice(torus, drift, start);
    let params = flock_metrics::MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    let mut straddled = 0;
    let mut worst_radius = 0.0_f64;
    for step in 0..3000 {
        open.step();
        periodic.step();
        if step % 50 != 0 {
            continue;
        }
        let (a, b) = (open.swarm(), periodic.swarm());
        for (x, y) in a.positions.iter().zip(&b.positions) {
            assert!(torus.displacement(*x, *y).length() < 1e-9);
        }
        let xs: Vec<f64> = b.positions.iter().map(|q| q.x).collect();
        if xs.iter().any(|&x| x < 7.0) && xs.iter().any(|&x| x > side - 7.0) {
            straddled += 1;
        }
        let (m_open, m_torus) = (open.metrics(&params), periodic.metrics(&params));
        assert_eq!(m_torus.connectivity, 1.0);
        assert_abs_diff_eq!(
            m_torus.deviation_energy,
            m_open.deviation_energy,
            epsilon = 1e-9
        );
        // R about the circular mean, not the arithmetic one: equal only for a flock small
        // against the box
        let gap = (m_torus.cohesion_radius - m_open.cohesion_radius).abs();
        worst_radius = worst_radius.max(gap / m_open.cohesion_radius);
        assert_abs_diff_eq!(m_torus.min_distance, m_open.min_distance, epsilon = 1e-9);
        assert_abs_diff_eq!(m_torus.polarisation, m_open.polarisation, epsilon = 1e-12);
    }
    assert!(
        straddled >= 5,
        "the flock straddled the faces at only {straddled} checks"
    );
    assert!(
        worst_radius < 0.01,
        "R on the torus {worst_radius} from R in open space"
    );
}

// ---------------------------------------------------------------- Vásárhelyi et al. 2018

/// D(r, a, p) written out again: 0, r p below a/p, √(2 a r − a²/p²) beyond.
fn vas_braking(r: f64, a: f64, p: f64) -> f64 {
    if r <= 0.0 {
        0.0
    } else if r * p < a / p {
        r * p
    } else {
        (2.0 * a * r - (a / p) * (a / p)).sqrt()
    }
}

/// The model's acceleration of every agent, brute force over all pairs: robotsim's terms
/// summed, cut at v^max, relaxed over τ and cut at a^max; the arena a square (cube) about `centre`.
fn vasarhelyi_inputs<V: Vector>(
    q: &[V],
    p: &[V],
    c: &VasarhelyiParams,
    centre: V,
    side: f64,
) -> Vec<V> {
    let n = q.len();
    let shorten = |x: V, limit: f64| {
        if x.length() > limit {
            x * (limit / x.length())
        } else {
            x
        }
    };
    (0..n)
        .map(|i| {
            let mut desired = p[i].normalize_or_zero() * c.v_flock;
            for j in 0..n {
                let r = (q[i] - q[j]).length();
                if j == i || r >= c.r_c {
                    continue;
                }
                if r < c.r0_rep {
                    desired += (q[i] - q[j]) * (1.0 / r) * (c.p_rep * (c.r0_rep - r));
                }
                let v_ij = (p[i] - p[j]).length();
                // the stopping point of robotsim's FrictionLinSqrt: R_0 + R_0_Offset_Frict
                let stop = c.r0_rep + c.r0_frict;
                let allowed = vas_braking(r - stop, c.a_frict, c.p_frict).max(c.v_frict);
                if v_ij > allowed {
                    desired += (p[j] - p[i]) * (1.0 / v_ij) * (c.c_frict * (v_ij - allowed));
                }
            }
            for k in 0..V::DIM {
                let x = q[i].coord(k) - centre.coord(k);
                let inwards = V::from_fn(|m| if m == k { -x.signum() } else { 0.0 });
                let to_wall = side / 2.0 - x.abs();
                let dv = inwards * c.v_shill - p[i];
                let allowed = vas_braking(to_wall - c.r0_shill, c.a_shill, c.p_shill);
                if dv.length() > allowed {
                    desired += dv * ((dv.length() - allowed) / dv.length());
                }
            }
            shorten((shorten(desired, c.v_max) - p[i]) * (1.0 / c.tau), c.a_max)
        })
        .collect()
}

/// A swarm of 40 at up to 8 m/s spread over 260 m about `centre`, in an arena of side 200: pairs
/// within r_0^rep, within and beyond r_c, agents outside the arena on every side.
fn vasarhelyi_agrees<V: Vector>() {
    let centre = V::from_fn(|k| 10.0 * (k as f64 + 1.0));
    let mut swarm = random_swarm::<V>(40, 130.0, 8.0, 23);
    for q in &mut swarm.positions {
        *q += centre;
    }
    let params = VasarhelyiParams::default();
    let arena = Arena {
        shape: ArenaShape::Square,
        centre,
        side: 200.0,
    };
    let model = vasarhelyi_in(params.clone(), arena);
    let h = 0.01;
    let reference = |_, q: &[V], p: &[V]| {
        let u = vasarhelyi_inputs(q, p, &params, centre, 200.0);
        let p2: Vec<V> = p.iter().zip(&u).map(|(&v, &a)| v + a * h).collect();
        let q2 = q.iter().zip(&p2).map(|(&x, &v)| x + v * h).collect();
        (q2, p2)
    };
    agrees_with_reference(model, swarm, (h, None, 50), reference, (1e-9, 1e-10));
}

#[test]
fn vasarhelyi_equals_brute_force_2d_3d() {
    vasarhelyi_agrees::<DVec2>();
    vasarhelyi_agrees::<DVec3>();
}

/// The braking curve at three points by hand (a = 4.16 m s⁻², p = 3.2 s⁻¹, the alignment's):
/// 0 before the stopping point, the linear branch r p = 0.8 at r = 0.25 (below a/p = 1.3) and
/// the square-root branch √(2 · 4.16 · 10 − 1.3²) = √81.51 at r = 10.
#[test]
fn vasarhelyi_braking_curve_at_hand_values() {
    use flock_protocols::vasarhelyi2018::braking_curve;
    assert_eq!(braking_curve(-1.0, 4.16, 3.2), 0.0);
    assert_abs_diff_eq!(braking_curve(0.25, 4.16, 3.2), 0.8, epsilon = 1e-15);
    assert_abs_diff_eq!(
        braking_curve(10.0, 4.16, 3.2),
        9.028_288_874_421_332,
        epsilon = 1e-12
    );
}

/// The model with `params` in `arena`.
fn vasarhelyi_in<V: Vector>(params: VasarhelyiParams, arena: Arena<V>) -> Vasarhelyi<V> {
    Vasarhelyi::new(VasarhelyiParams {
        arena_shape: arena.shape,
        arena_side: arena.side,
        arena_centre: Some((0..V::DIM).map(|k| arena.centre.coord(k)).collect()),
        ..params
    })
    .unwrap()
}

/// The default model in a 10 km arena (walls out of reach).
fn far_walls<V: Vector>() -> Vasarhelyi<V> {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: V::ZERO,
        side: 10_000.0,
    };
    vasarhelyi_in(VasarhelyiParams::default(), arena)
}

/// Two drones 10 m apart flying side by side at v^flock (no velocity difference, so no
/// alignment): each is pushed straight away from the other at p^rep (r_0^rep − r) =
/// 0.13 · 15 = 1.95 m/s, desired (∓1.95, 6) below v^max, so u = ∓(1.95, 0)/τ.
#[test]
fn vasarhelyi_repulsion_pushes_a_close_pair_apart() {
    let model = far_walls::<DVec2>();
    let v = DVec2::new(0.0, 6.0);
    let (a, b) = (DVec2::ZERO, DVec2::new(10.0, 0.0));
    let desired = model.desired_velocity(a, v, [(b, v)].into_iter());
    assert_abs_diff_eq!(desired, DVec2::new(-1.95, 6.0), epsilon = 1e-12);
    let swarm = Swarm::new(vec![a, b], vec![v, v]);
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    sim.step();
    let p = &sim.swarm().velocities;
    assert_abs_diff_eq!(p[0], v + DVec2::new(-1.95, 0.0) * 0.01, epsilon = 1e-12);
    assert_abs_diff_eq!(p[1], v + DVec2::new(1.95, 0.0) * 0.01, epsilon = 1e-12);
    // beyond r_0^rep and with equal velocities: self-propulsion alone
    let alone = model_far_desired(DVec2::new(30.0, 0.0), v);
    assert_abs_diff_eq!(alone, v, epsilon = 1e-12);
}

fn model_far_desired(b: DVec2, v: DVec2) -> DVec2 {
    far_walls::<DVec2>().desired_velocity(DVec2::ZERO, v, [(b, v)].into_iter())
}

/// The shill agents of a 250 m square: a drone at rest 5 m outside the right wall gets the
/// whole shill velocity (−13.6, 0) (D = 0 outside); one 5 m inside flying at the wall at 6 m/s
/// gets (19.6 − D(4.7, a^shill, p^shill)) along −x, D = √(2 · 3.02 · 4.7 − (3.02/3.55)²); one
/// at the centre gets nothing. A circle pushes back along the radius.
#[test]
fn vasarhelyi_walls_push_back_outside_and_brake_inside() {
    let square = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 250.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), square);
    let outside = model.wall_term(DVec2::new(130.0, 0.0), DVec2::ZERO);
    assert_abs_diff_eq!(outside, DVec2::new(-13.6, 0.0), epsilon = 1e-12);
    assert_eq!(square.outside(DVec2::new(130.0, 0.0)), 5.0);
    let inside = model.wall_term(DVec2::new(120.0, 0.0), DVec2::new(6.0, 0.0));
    let braking = 5.259_686_523_070_369;
    assert_abs_diff_eq!(inside, DVec2::new(-(19.6 - braking), 0.0), epsilon = 1e-9);
    assert_eq!(square.outside(DVec2::new(120.0, 0.0)), 0.0);
    assert_eq!(
        model.wall_term(DVec2::ZERO, DVec2::new(6.0, 0.0)),
        DVec2::ZERO
    );
    let circle = Arena {
        shape: ArenaShape::Circle,
        ..square
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), circle);
    let q = DVec2::new(100.0, 100.0); // 141.4 m out, 16.4 m beyond the wall
    let w = model.wall_term(q, DVec2::ZERO);
    assert_abs_diff_eq!(w, -q.normalize() * 13.6, epsilon = 1e-12);
    assert_abs_diff_eq!(circle.outside(q), q.length() - 125.0, epsilon = 1e-12);
}

/// The cut: a desired velocity beyond v^max keeps its direction at length v^max, and the
/// acceleration is cut at a^max. A drone at rest 5 m outside the left wall with two others 1 m
/// further out (repulsion 2 · 0.13 · 24 = 6.24 m/s inwards) plus the wall (13.6 m/s inwards):
/// ‖ṽ‖ = 19.84 > 8.
#[test]
fn vasarhelyi_cuts_the_desired_velocity_and_the_acceleration() {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 100.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let q = DVec2::new(-55.0, 0.0);
    let others = [
        (DVec2::new(-56.0, 0.0), DVec2::ZERO),
        (DVec2::new(-56.0, 0.0), DVec2::ZERO),
    ];
    let desired = model.desired_velocity(q, DVec2::ZERO, others.into_iter());
    assert_abs_diff_eq!(desired.length(), 8.0, epsilon = 1e-12);
    assert_abs_diff_eq!(desired.normalize(), DVec2::new(1.0, 0.0), epsilon = 1e-12);
    let swarm = Swarm::new(vec![q], vec![DVec2::ZERO]);
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    sim.step();
    // alone: u = (v_d − 0)/τ = 8 m s⁻² (13.6 cut at v^max), cut at a^max = 6
    assert_abs_diff_eq!(
        sim.swarm().velocities[0],
        DVec2::new(0.06, 0.0),
        epsilon = 1e-12
    );
}

/// The order parameters of a constructed state: φ^corr over all pairs (two heading +x, one +y:
/// (1 + 0 + 0) · 2 / 6 = 1/3), φ^vel / v^flock, φ^coll (one pair within r^coll of three: 2/6)
/// and φ^wall (one drone 10 m out of three: 10/3).
#[test]
fn vasarhelyi_order_parameters_of_a_constructed_state() {
    use flock_graph::{NeighbourSearch, ProximityNet};
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 100.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let q = vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(60.0, 0.0)];
    let p = vec![
        DVec2::new(6.0, 0.0),
        DVec2::new(3.0, 0.0),
        DVec2::new(0.0, 3.0),
    ];
    let swarm = Swarm::new(q.clone(), p);
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build(&q, model.interaction_range(), &mut net);
    let [corr, speed, coll, wall] = model.order_parameters(&swarm, &net);
    assert_abs_diff_eq!(corr, 1.0 / 3.0, epsilon = 1e-15);
    assert_abs_diff_eq!(speed, 12.0 / 3.0 / 6.0, epsilon = 1e-15);
    assert_abs_diff_eq!(coll, 1.0 / 3.0, epsilon = 1e-15);
    assert_abs_diff_eq!(wall, 10.0 / 3.0, epsilon = 1e-12);
}

/// The paper's flock in the small (the reproduction at full length runs the fixture in the
/// `flocking` crate's tests): 30 drones from random headings in a 250 m square align within a
/// minute of simulated time: φ^corr > 0.9, speed within 20 % of v^flock, none outside.
#[test]
fn vasarhelyi_thirty_drones_align_within_a_minute() {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 250.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let mut swarm = random_swarm::<DVec2>(30, 50.0, 6.0, 5);
    for v in &mut swarm.velocities {
        *v = v.normalize() * 6.0;
    }
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    for _ in 0..6000 {
        sim.step();
    }
    let diagnostics: std::collections::BTreeMap<_, _> = sim.diagnostics().into_iter().collect();
    assert!(diagnostics["velocity_correlation"] > 0.9, "{diagnostics:?}");
    assert!(
        (diagnostics["speed_ratio"] - 1.0).abs() < 0.2,
        "{diagnostics:?}"
    );
    assert_eq!(diagnostics["wall_violation"], 0.0, "{diagnostics:?}");
    assert_eq!(diagnostics["collision_ratio"], 0.0, "{diagnostics:?}");
}
