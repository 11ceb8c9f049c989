//! Real conditions checked against the theory: delay and sampled-data bounds of consensus,
//! stationary noise, momentum under symmetric loss, Gilbert–Elliott loss, actuation limits and
//! lag, wind, faults, determinism over threads and checkpoints.

use std::f64::consts::PI;

use approx::assert_abs_diff_eq;

use flock_graph::{Graph, ProximityNet};
use flock_math::Domain;
use flock_metrics::MetricParams;
use flock_protocols::{
    Algorithm1, Algorithm2, Consensus, GammaAgent, NavigationalFeedback, Protocol, Swarm, Vicsek,
};
#[cfg(feature = "serde")]
use flock_sim::conditions::ConditionsState;
use flock_sim::conditions::{
    Actuation, Communication, Conditions, Delayed, Disturbance, Failure, FaultMode, Faults, Loss,
    Noise, SampledControl, Sensing, WhenLost, Wind, bytes_per_agent,
};
use flock_sim::{Integrator, Simulation};
use glam::DVec2;
use proptest::prelude::*;

use crate::common::{papers_alpha, random_swarm, vicsek_on_a_torus};

/// The cycle C_n: λ_k = 2 − 2 cos(2πk/n).
fn cycle(n: usize) -> Graph {
    let edges: Vec<_> = (0..n).map(|i| (i, (i + 1) % n)).collect();
    Graph::from_edges(n, &edges).expect("a cycle")
}

fn cycle_eigenvalues(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| 2.0 - 2.0 * (2.0 * PI * k as f64 / n as f64).cos())
        .collect()
}

/// Six agents at rest positions with distinct velocities.
fn six_velocities() -> Swarm<DVec2> {
    let p = (0..6)
        .map(|i| DVec2::new(f64::from(i).sin() * 2.0, f64::from(i) * 0.3 - 0.7))
        .collect();
    Swarm::new(vec![DVec2::ZERO; 6], p)
}

/// Σ_i ‖p_i − p̄‖².
fn disagreement(swarm: &Swarm<DVec2>) -> f64 {
    let mean = swarm.mean_velocity();
    swarm
        .velocities
        .iter()
        .map(|p| (*p - mean).length_squared())
        .sum()
}

fn consensus_run(
    gain: f64,
    graph: Graph,
    h: f64,
    conditions: &Conditions,
    steps: usize,
) -> Simulation<DVec2, Consensus> {
    let protocol = Consensus::fixed(gain, graph, 1.0).expect("valid");
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, six_velocities(), h)
        .expect("valid")
        .with_conditions(conditions, 1)
        .expect("valid conditions");
    for _ in 0..steps {
        sim.step();
    }
    sim
}

/// Conditions of communication alone.
fn communicating(communication: Communication) -> Conditions {
    Conditions {
        communication: Some(communication),
        ..Conditions::default()
    }
}

fn delayed(delay: f64, delayed: Delayed) -> Conditions {
    communicating(Communication {
        delay,
        delayed,
        ..Communication::default()
    })
}

/// The ratio of the final to the initial disagreement.
fn decay(sim: &Simulation<DVec2, Consensus>) -> f64 {
    disagreement(&sim.swarm()) / disagreement(&six_velocities())
}

/// Olfati-Saber & Murray 2004: ṗ = −c L p(t − τ) converges iff τ < π / (2 c λ_max). With c
/// chosen so that the bound is 1 s, delays of 0.9 s and 1.1 s (90 and 110 steps of 0.01 s).
#[test]
fn delay_all_converges_below_the_bound_and_diverges_above() {
    let lambda_max = 4.0; // C_6: 2 − 2 cos π
    let gain = PI / (2.0 * lambda_max); // τ* = 1 s
    let h = 0.01;
    let steps = 40_000; // 400 s
    let below = decay(&consensus_run(
        gain,
        cycle(6),
        h,
        &delayed(0.9, Delayed::All),
        steps,
    ));
    let above = decay(&consensus_run(
        gain,
        cycle(6),
        h,
        &delayed(1.1, Delayed::All),
        steps,
    ));
    println!(
        "delay all: τ* = 1 s, disagreement ratio after 400 s: 0.9τ* {below:.3e}, 1.1τ* {above:.3e}"
    );
    assert!(below < 1e-6, "{below}");
    assert!(above > 1e6, "{above}");
    // the neighbours-only semantics converges far beyond the bound
    let five = decay(&consensus_run(
        gain,
        cycle(6),
        h,
        &delayed(5.0, Delayed::Neighbours),
        steps,
    ));
    println!("delay neighbours at 5τ*: {five:.3e}");
    assert!(five < 1e-6, "{five}");
}

/// Sampled control: p ← (I − c T L) p per period, converging iff c T λ_max < 2: with c = 1 and
/// λ_max = 4 the bound is T = 0.5 s; periods 0.45 s and 0.55 s (9 and 11 steps of 0.05 s).
#[test]
fn sampled_control_converges_iff_c_t_lambda_max_below_two() {
    let sampled = |period: f64| Conditions {
        control: Some(SampledControl { rate: 1.0 / period }),
        ..Conditions::default()
    };
    let below = decay(&consensus_run(1.0, cycle(6), 0.05, &sampled(0.45), 4000));
    let above = decay(&consensus_run(1.0, cycle(6), 0.05, &sampled(0.55), 4000));
    println!(
        "sampled: T* = 0.5 s, disagreement ratio after 200 s: 0.9T* {below:.3e}, 1.1T* {above:.3e}"
    );
    assert!(below < 1e-12, "{below}");
    assert!(above > 1e12, "{above}");
}

/// The mean of `samples` and its standard error by batch means (`batches` consecutive batches,
/// each much longer than the correlation time, so their means are nearly independent).
fn batch_means(samples: &[f64], batches: usize) -> (f64, f64) {
    let len = samples.len() / batches;
    let means: Vec<f64> = samples
        .chunks_exact(len)
        .map(|b| b.iter().sum::<f64>() / len as f64)
        .collect();
    let m = means.iter().sum::<f64>() / means.len() as f64;
    let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (means.len() - 1) as f64;
    (m, (var / means.len() as f64).sqrt())
}

/// p ← (I − h c L) p + σ √h ξ: each mode k ≥ 2 has stationary variance σ²/(c λ_k (2 − h c λ_k))
/// per dimension, so E Σ ‖p_i − p̄‖² = dim Σ_{k≥2} σ²/(c λ_k (2 − h c λ_k)). The time average of
/// a long run (after a burn-in of 50 correlation times 1/(c λ₂)) agrees within 4 standard errors,
/// estimated by batch means over 40 batches of 250 correlation times each.
#[test]
fn process_noise_gives_the_stationary_disagreement() {
    let (gain, h, sigma) = (1.0, 0.05, 0.3);
    let predicted: f64 = 2.0
        * cycle_eigenvalues(6)[1..]
            .iter()
            .map(|&l| sigma * sigma / (gain * l * (2.0 - h * gain * l)))
            .sum::<f64>();
    let conditions = Conditions {
        disturbance: Some(Disturbance {
            wind: None,
            process_noise: sigma,
        }),
        ..Conditions::default()
    };
    let mut sim = consensus_run(gain, cycle(6), h, &conditions, 1000);
    let samples: Vec<f64> = (0..200_000)
        .map(|_| {
            sim.step();
            disagreement(&sim.swarm())
        })
        .collect();
    let (mean, error) = batch_means(&samples, 40);
    println!("noise: predicted {predicted:.5}, measured {mean:.5} ± {error:.5}");
    assert!(
        (mean - predicted).abs() < 4.0 * error,
        "{mean} ± {error} vs {predicted}"
    );
    assert!(error < 0.03 * predicted, "{error}");
}

fn algorithm1_momentum(symmetric: bool) -> f64 {
    let swarm = random_swarm::<DVec2>(30, 12.0, 1.0, 5);
    let conditions = communicating(Communication {
        loss: Loss::Bernoulli { p: 0.3 },
        symmetric,
        ..Communication::default()
    });
    let protocol = Algorithm1 {
        alpha: papers_alpha(),
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
        .expect("valid")
        .with_conditions(&conditions, 9)
        .expect("valid");
    let total = |s: &Simulation<DVec2, Algorithm1>| -> DVec2 { s.swarm().velocities.iter().sum() };
    let start = total(&sim);
    for _ in 0..500 {
        sim.step();
    }
    (total(&sim) - start).length()
}

/// Σ u_i = 0 needs each pair to hear each other or neither: symmetric loss keeps Σ p_i of
/// Algorithm 1 to round-off, independent loss does not.
#[test]
fn symmetric_loss_keeps_the_momentum_and_independent_loss_does_not() {
    let symmetric = algorithm1_momentum(true);
    let independent = algorithm1_momentum(false);
    println!("Σp drift over 5 s: symmetric {symmetric:.3e}, independent {independent:.3e}");
    assert!(symmetric < 1e-12, "{symmetric}");
    assert!(independent > 1e-3, "{independent}");
}

/// The Gilbert–Elliott channel (a = 0.5/s, b = 1.5/s) loses p = a/(a+b) = 0.25 of the packets
/// in the long run: the mean of `links_lost` over 12 directed links and 4000 s, within 4
/// standard errors (batch means over 40 batches of 100 s, 200 correlation times 1/(a+b)).
#[test]
fn gilbert_elliott_loses_its_stationary_fraction() {
    let conditions = communicating(Communication {
        loss: Loss::GilbertElliott {
            p_fail: 0.5,
            p_recover: 1.5,
        },
        ..Communication::default()
    });
    let mut sim = consensus_run(0.1, cycle(6), 0.1, &conditions, 0);
    let column = |sim: &Simulation<DVec2, Consensus>| {
        sim.diagnostics()
            .iter()
            .find(|(name, _)| *name == "links_lost")
            .expect("a links_lost column")
            .1
    };
    let samples: Vec<f64> = (0..40_000)
        .map(|_| {
            sim.step();
            column(&sim)
        })
        .collect();
    let (mean, error) = batch_means(&samples, 40);
    println!("Gilbert–Elliott: expected 0.25, measured {mean:.4} ± {error:.4}");
    assert!((mean - 0.25).abs() < 4.0 * error, "{mean} ± {error}");
    assert!(error < 0.01, "{error}");
}

/// The lag's step response: a constant command u (held by a 0.1 Hz controller), delivered
/// a = u (1 − e^(−t/τ_a)) at every step.
#[test]
fn the_lag_has_the_first_order_step_response() {
    let (h, tau) = (0.01, 0.5);
    let graph = Graph::from_edges(2, &[(0, 1)]).expect("an edge");
    let swarm = Swarm::new(
        vec![DVec2::ZERO; 2],
        vec![DVec2::new(1.0, 0.5), DVec2::ZERO],
    );
    let conditions = Conditions {
        control: Some(SampledControl { rate: 0.1 }),
        actuation: Some(Actuation {
            lag: Some(tau),
            ..Actuation::default()
        }),
        ..Conditions::default()
    };
    let protocol = Consensus::fixed(2.0, graph, 1.0).expect("valid");
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, h)
        .expect("valid")
        .with_conditions(&conditions, 0)
        .expect("valid");
    let u = DVec2::new(-2.0, -1.0);
    let mut worst = 0.0_f64;
    for k in 1..1000 {
        sim.step();
        let state = sim.conditions_state().expect("conditions");
        let a = DVec2::new(state.delivered[0], state.delivered[1]);
        let expected = u * (1.0 - (-(k as f64) * h / tau).exp());
        worst = worst.max((a - expected).length());
    }
    println!("lag: worst deviation from u (1 − e^(−t/τ)) {worst:.2e}");
    assert!(worst < 1e-12, "{worst}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// ‖a_i‖ ≤ a_max and ‖p_i‖ ≤ v_max at every step, whatever the swarm, gains, lag and wind.
    #[test]
    fn actuation_limits_hold_at_every_step(
        seed in 0u64..1000,
        max_acceleration in 0.05f64..3.0,
        max_speed in 0.2f64..4.0,
        lag in proptest::option::of(0.02f64..1.0),
        wind in -1.0f64..1.0,
        noise in 0.0f64..0.5,
    ) {
        let conditions = Conditions {
            actuation: Some(Actuation {
                max_acceleration: Some(max_acceleration),
                max_speed: Some(max_speed),
                lag,
            }),
            disturbance: Some(Disturbance {
                wind: Some(Wind { mean: vec![wind, -wind], gust: 0.0, correlation_time: 1.0, per_agent: false }),
                process_noise: noise,
            }),
            ..Conditions::default()
        };
        let protocol = Algorithm1 { alpha: papers_alpha() };
        let swarm = random_swarm::<DVec2>(12, 8.0, 6.0, seed);
        let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
            .expect("valid")
            .with_conditions(&conditions, seed)
            .expect("valid");
        for _ in 0..150 {
            sim.step();
            let state = sim.conditions_state().expect("conditions");
            for a in state.delivered.chunks_exact(2) {
                prop_assert!(a[0].hypot(a[1]) <= max_acceleration * (1.0 + 1e-12));
            }
            for p in &sim.swarm().velocities {
                prop_assert!(p.length() <= max_speed * (1.0 + 1e-12));
            }
        }
    }
}

/// Under a constant wind w the centre of mass of Algorithm 2 with linear navigational feedback
/// to a static γ-agent obeys q̈_c = −c₁ (q_c − q_γ) − c₂ p_c + w (the α-forces cancel), and
/// settles at q_γ + w/c₁.
#[test]
fn wind_offsets_the_centre_by_w_over_c1() {
    let (c1, c2) = (0.05, 0.4);
    let w = DVec2::new(0.01, -0.004);
    let gamma = DVec2::new(3.0, 1.0);
    let protocol = Algorithm2 {
        alpha: papers_alpha(),
        navigation: NavigationalFeedback::linear(GammaAgent::Static { position: gamma }, c1, c2),
    };
    let q = (0..5)
        .map(|i| DVec2::new(6.0 * f64::from(i), f64::from(i % 2)))
        .collect();
    let swarm = Swarm::new(q, vec![DVec2::ZERO; 5]);
    let conditions = Conditions {
        disturbance: Some(Disturbance {
            wind: Some(Wind {
                mean: vec![w.x, w.y],
                gust: 0.0,
                correlation_time: 1.0,
                per_agent: false,
            }),
            process_noise: 0.0,
        }),
        ..Conditions::default()
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
        .expect("valid")
        .with_conditions(&conditions, 0)
        .expect("valid");
    for _ in 0..20_000 {
        sim.step();
    }
    let offset = sim.swarm().centre() - gamma;
    let error = (offset - w / c1).length();
    println!(
        "wind: offset {offset:?}, w/c1 {:?}, error {error:.2e}",
        w / c1
    );
    assert!(error < 1e-6, "{error}");
}

/// Consensus (gain 1) on the path 0–1–2–3–4 from positions `q` and velocities `p`, its cut
/// vertex 2 failing at t = 0 in `mode`, after `steps` steps of 0.01 s.
fn path_with_failed_cut_vertex(
    q: Vec<DVec2>,
    p: Vec<DVec2>,
    mode: FaultMode,
    steps: usize,
) -> Simulation<DVec2, Consensus> {
    let graph = Graph::from_edges(5, &[(0, 1), (1, 2), (2, 3), (3, 4)]).expect("a path");
    let conditions = Conditions {
        faults: Some(Faults {
            at: vec![Failure {
                agent: 2,
                time: 0.0,
            }],
            rate: 0.0,
            mode,
        }),
        ..Conditions::default()
    };
    let protocol = Consensus::fixed(1.0, graph, 1.0).expect("valid");
    let mut sim = Simulation::new(
        protocol,
        Integrator::SymplecticEuler,
        Swarm::new(q, p),
        0.01,
    )
    .expect("valid")
    .with_conditions(&conditions, 0)
    .expect("valid");
    for _ in 0..steps {
        sim.step();
    }
    sim
}

/// Removing the cut vertex 2 of the path 0–1–2–3–4 at t = 0 leaves the components {0, 1} and
/// {3, 4}, each converging to the mean of its own initial velocities; the metrics count the
/// two components and leave the removed agent out.
#[test]
fn removing_a_cut_vertex_splits_the_consensus() {
    let p: Vec<DVec2> = [1.0, 3.0, 10.0, -2.0, 0.0]
        .into_iter()
        .map(|x| DVec2::new(x, 0.5 * x))
        .collect();
    let q = (0..5)
        .map(|i| DVec2::new(f64::from(i) * 0.5, 0.0))
        .collect();
    let sim = path_with_failed_cut_vertex(q, p.clone(), FaultMode::Removed, 3000);
    let v = sim.swarm().velocities.clone();
    let left = (p[0] + p[1]) / 2.0;
    let right = (p[3] + p[4]) / 2.0;
    for (i, target) in [(0, left), (1, left), (3, right), (4, right)] {
        assert!(
            (v[i] - target).length() < 1e-9,
            "agent {i}: {:?} vs {target:?}",
            v[i]
        );
    }
    assert_eq!(v[2], DVec2::ZERO);
    let metrics = sim.metrics(&MetricParams {
        d: 0.4,
        collision_distance: 0.1,
    });
    assert_eq!(metrics.components, 2);
    let failed = sim.diagnostics().into_iter().find(|(n, _)| *n == "failed");
    assert_eq!(failed, Some(("failed", 1.0)));
}

/// A frozen cut vertex (p = 0, still heard) pulls the whole path to rest; a silent one (flying
/// on, heard by nobody) splits it like a removed one, while it follows its neighbours.
#[test]
fn frozen_and_silent_faults() {
    let p: Vec<DVec2> = [1.0, 3.0, 10.0, -2.0, 0.0]
        .into_iter()
        .map(|x| DVec2::new(x, -x))
        .collect();
    let run = |mode| {
        path_with_failed_cut_vertex(vec![DVec2::ZERO; 5], p.clone(), mode, 10_000)
            .swarm()
            .into_owned()
    };
    let frozen = run(FaultMode::Frozen);
    assert_eq!(frozen.positions[2], DVec2::ZERO);
    assert!(frozen.velocities.iter().all(|v| v.length() < 1e-9));
    let silent = run(FaultMode::Silent);
    let (left, right) = ((p[0] + p[1]) / 2.0, (p[3] + p[4]) / 2.0);
    for (i, target) in [(0, left), (1, left), (3, right), (4, right)] {
        assert!((silent.velocities[i] - target).length() < 1e-9, "{i}");
    }
    // agent 2 still hears 1 and 3: it settles at their mean
    assert!((silent.velocities[2] - (left + right) / 2.0).length() < 1e-9);
}

/// Every condition on at once.
pub fn everything() -> Conditions {
    Conditions {
        communication: Some(Communication {
            delay: 0.05,
            jitter: 0.03,
            delayed: Delayed::Neighbours,
            range: Some(9.0),
            loss: Loss::GilbertElliott {
                p_fail: 0.3,
                p_recover: 2.0,
            },
            symmetric: false,
            when_lost: WhenLost::Hold { max_age: 0.2 },
        }),
        sensing: Some(Sensing {
            noise: Noise::OrnsteinUhlenbeck {
                sigma_q: 0.05,
                sigma_p: 0.02,
                correlation_time: 0.5,
            },
            rate: Some(50.0),
        }),
        control: Some(SampledControl { rate: 50.0 }),
        actuation: Some(Actuation {
            max_acceleration: Some(3.0),
            max_speed: Some(4.0),
            lag: Some(0.1),
        }),
        disturbance: Some(Disturbance {
            wind: Some(Wind {
                mean: vec![0.1, 0.0],
                gust: 0.2,
                correlation_time: 2.0,
                per_agent: true,
            }),
            process_noise: 0.05,
        }),
        faults: Some(Faults {
            at: vec![Failure {
                agent: 3,
                time: 0.1,
            }],
            rate: 0.2,
            mode: FaultMode::Silent,
        }),
    }
}

fn bits(swarm: &Swarm<DVec2>) -> Vec<u64> {
    swarm
        .positions
        .iter()
        .chain(&swarm.velocities)
        .flat_map(|v| [v.x.to_bits(), v.y.to_bits()])
        .collect()
}

fn everything_run(threads: usize) -> (Vec<u64>, Vec<(&'static str, f64)>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool");
    pool.install(|| {
        let protocol = Algorithm1 {
            alpha: papers_alpha(),
        };
        let mut sim = Simulation::new(
            protocol,
            Integrator::SymplecticEuler,
            random_swarm(1500, 60.0, 1.0, 4),
            0.01,
        )
        .expect("valid")
        .with_conditions(&everything(), 42)
        .expect("valid");
        for _ in 0..40 {
            sim.step();
        }
        (bits(&sim.swarm()), sim.diagnostics())
    })
}

#[test]
fn every_condition_gives_the_same_bits_on_one_and_two_threads() {
    let (one, d1) = everything_run(1);
    let (two, d2) = everything_run(2);
    assert_eq!(one, two);
    assert_eq!(d1, d2);
    println!("diagnostics: {d1:?}");
}

/// A model that sets velocities (Vicsek on a torus, 5,000 particles) under a delay, Bernoulli
/// loss and frozen faults, whose integrate step runs in parallel: the same bits and readings on
/// one and two threads; the failed particles stand still and the others move at v₀.
#[test]
fn a_velocity_setting_model_under_conditions_is_the_same_on_one_and_two_threads() {
    let (vicsek, torus) = vicsek_on_a_torus(35.0, 0.5, 9);
    let start = random_swarm::<DVec2>(5_000, 17.5, 0.03, 62);
    let conditions = Conditions {
        faults: Some(Faults {
            at: vec![],
            rate: 0.02,
            mode: FaultMode::Frozen,
        }),
        ..communicating(Communication {
            delay: 2.0,
            loss: Loss::Bernoulli { p: 0.2 },
            ..Communication::default()
        })
    };
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        pool.install(|| {
            let mut sim = vicsek_under(&vicsek, torus, &start, &conditions, 11);
            for _ in 0..20 {
                sim.step();
            }
            let failed = sim.failed().expect("faults").into_owned();
            (
                bits(&sim.swarm()),
                sim.diagnostics(),
                failed,
                sim.swarm().into_owned(),
            )
        })
    };
    let (one, r1, failed, swarm) = run(1);
    let (two, r2, ..) = run(2);
    assert_eq!(one, two);
    assert_eq!(r1, r2);
    // about 1 − e^(−0.4) = 33 % failed over 20 s at a rate of 0.02 /s
    let share = failed.iter().filter(|f| **f).count() as f64 / failed.len() as f64;
    assert!((0.28..0.38).contains(&share), "{share}");
    for (failed, v) in failed.iter().zip(&swarm.velocities) {
        let expected = if *failed { 0.0 } else { 0.03 };
        assert_abs_diff_eq!(v.length(), expected, epsilon = 1e-12);
    }
}

/// Interrupted after 37 steps, the state serialized (RON, with the serde feature) and a new simulation resumed from
/// it: the same bits as the uninterrupted run, for both integrators.
#[test]
fn a_resumed_run_with_every_condition_is_bit_identical() {
    let protocol = || Algorithm1 {
        alpha: papers_alpha(),
    };
    for integrator in [Integrator::SymplecticEuler, Integrator::Rk4] {
        let start = random_swarm::<DVec2>(200, 25.0, 1.0, 6);
        let new = |swarm| {
            Simulation::new(protocol(), integrator, swarm, 0.01)
                .expect("valid")
                .with_conditions(&everything(), 7)
                .expect("valid")
        };
        let mut whole = new(start.clone());
        let mut first = new(start);
        for _ in 0..37 {
            whole.step();
            first.step();
        }
        let state = first.conditions_state().expect("conditions");
        // through RON when the serde feature is on (as in the workspace's tests)
        #[cfg(feature = "serde")]
        let state: ConditionsState =
            ron::from_str(&ron::to_string(&state).expect("RON")).expect("RON");
        let mut resumed = Simulation::resume(
            protocol(),
            integrator,
            first.swarm().into_owned(),
            0.01,
            first.steps(),
        )
        .expect("valid")
        .with_conditions(&everything(), 7)
        .expect("valid");
        resumed.restore_conditions(state).expect("the same run");
        for _ in 0..63 {
            whole.step();
            resumed.step();
        }
        assert_eq!(
            bits(&whole.swarm()),
            bits(&resumed.swarm()),
            "{integrator:?}"
        );
        assert_eq!(whole.diagnostics(), resumed.diagnostics());
    }
}

/// Algorithm 1 from `n` random agents, run `steps` steps ideally and under `conditions`: the
/// two final states, and the conditioned simulation.
fn ideal_and_conditioned(
    n: usize,
    conditions: &Conditions,
    steps: usize,
) -> (Swarm<DVec2>, Simulation<DVec2, Algorithm1>) {
    let protocol = || Algorithm1 {
        alpha: papers_alpha(),
    };
    let start = random_swarm::<DVec2>(n, 20.0, 1.0, 2);
    let mut ideal = Simulation::new(protocol(), Integrator::SymplecticEuler, start.clone(), 0.01)
        .expect("valid");
    let mut conditioned = Simulation::new(protocol(), Integrator::SymplecticEuler, start, 0.01)
        .expect("valid")
        .with_conditions(conditions, 0)
        .expect("valid");
    for _ in 0..steps {
        ideal.step();
        conditioned.step();
    }
    (ideal.swarm().into_owned(), conditioned)
}

/// Perception made exact (a communication section with no delay and no loss) takes the local
/// path, and agrees with the ideal run to round-off.
#[test]
fn exact_perception_on_the_local_path_is_the_ideal_run() {
    let exact = Conditions {
        communication: Some(Communication::default()),
        ..Conditions::default()
    };
    let (a, local) = ideal_and_conditioned(80, &exact, 300);
    let b = local.swarm();
    let worst = a
        .positions
        .iter()
        .zip(&b.positions)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max);
    println!("exact perception: largest position difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst}");
}

/// On a torus, a communication range beyond r reaches across the wrap: with exact perception
/// (no delay, no loss, no noise) Vicsek's particles hear within the range and keep those within
/// r, so the run is the ideal one, bit for bit. (Its own net was once built in open space, and
/// particles near an edge missed their neighbours across it.)
#[test]
fn a_communication_range_on_a_torus_reaches_across_the_wrap() {
    let (model, torus) = vicsek_on_a_torus(20.0, 0.5, 9);
    let start = random_swarm::<DVec2>(2_000, 10.0, 0.03, 61);
    let run =
        |conditions: &Conditions| stepped(vicsek_under(&model, torus, &start, conditions, 0), 30).0;
    let ranged = Conditions {
        communication: Some(Communication {
            range: Some(1.5),
            ..Communication::default()
        }),
        ..Conditions::default()
    };
    assert!(run(&ranged) == run(&Conditions::default()));
}

/// The final state's bits and the last step's readings of `sim` after `steps` steps.
fn stepped<P: Protocol<DVec2>>(
    mut sim: Simulation<DVec2, P>,
    steps: usize,
) -> (Vec<u64>, Vec<(&'static str, f64)>) {
    for _ in 0..steps {
        sim.step();
    }
    (bits(&sim.swarm()), sim.diagnostics())
}

/// Vicsek's `model` on `torus` from `start` (a step of 1 s) under `conditions` drawn from `seed`.
fn vicsek_under(
    model: &Vicsek<DVec2>,
    torus: Domain<DVec2>,
    start: &Swarm<DVec2>,
    conditions: &Conditions,
    seed: u64,
) -> Simulation<DVec2, Vicsek<DVec2>> {
    Simulation::new(
        model.clone(),
        Integrator::SymplecticEuler,
        start.clone(),
        1.0,
    )
    .expect("valid")
    .with_domain(torus)
    .expect("a valid domain")
    .with_conditions(conditions, seed)
    .expect("valid")
}

/// Links that keep nothing and lose each packet by its own draw take a loop of their own; the
/// general loop decides the same link by link. `Hold` with a maximal age of 0 sends them through
/// the general loop (a held state is at least one step old, so it is never used: a lost packet
/// is dropped): the same bits and the same readings, for Bernoulli loss and none, in open space
/// (Algorithm 1, 1,500 agents) and on a torus (Vicsek, 2,000 particles, the images of the
/// senders across the wrap).
#[test]
fn memoryless_links_take_the_bits_of_the_general_loop() {
    let conditions = |loss, when_lost, delay| {
        communicating(Communication {
            delay,
            loss,
            when_lost,
            ..Communication::default()
        })
    };
    let (vicsek, torus) = vicsek_on_a_torus(20.0, 0.5, 9);
    let open = random_swarm::<DVec2>(1_500, 60.0, 1.0, 4);
    let on_torus = random_swarm::<DVec2>(2_000, 10.0, 0.03, 61);
    let hold_nothing = WhenLost::Hold { max_age: 0.0 };
    for loss in [Loss::None, Loss::Bernoulli { p: 0.3 }] {
        let alpha = |when_lost| {
            let protocol = Algorithm1 {
                alpha: papers_alpha(),
            };
            let sim = Simulation::new(protocol, Integrator::SymplecticEuler, open.clone(), 0.01)
                .expect("valid")
                .with_conditions(&conditions(loss, when_lost, 0.05), 3)
                .expect("valid");
            stepped(sim, 40)
        };
        let on_a_torus = |when_lost| {
            let conditions = conditions(loss, when_lost, 2.0);
            let sim = vicsek_under(&vicsek, torus, &on_torus, &conditions, 5);
            stepped(sim, 30)
        };
        let alpha_drop = alpha(WhenLost::Drop);
        assert_eq!(alpha_drop, alpha(hold_nothing), "Algorithm 1, {loss:?}");
        let vicsek_drop = on_a_torus(WhenLost::Drop);
        assert_eq!(vicsek_drop, on_a_torus(hold_nothing), "Vicsek, {loss:?}");
        // the readings are those of the loss drawn and of the delay
        let (lost, age) = (alpha_drop.1[0].1, alpha_drop.1[1].1);
        let p = if loss == Loss::None { 0.0 } else { 0.3 };
        assert!((lost - p).abs() < 0.02, "links lost {lost} against {p}");
        assert_abs_diff_eq!(age, 0.05, epsilon = 1e-12);
    }
}

/// `Conditions::default()` is the ideal run, bit for bit.
#[test]
fn default_conditions_are_the_ideal_run() {
    let (ideal, same) = ideal_and_conditioned(300, &Conditions::default(), 50);
    assert_eq!(bits(&ideal), bits(&same.swarm()));
    assert!(same.conditions_state().is_none());
}

/// Consensus without its local form.
#[derive(Debug)]
struct Global(Consensus);

impl Protocol<DVec2> for Global {
    fn interaction_range(&self) -> f64 {
        Protocol::<DVec2>::interaction_range(&self.0)
    }
    fn controls(&self, t: f64, swarm: &Swarm<DVec2>, net: &ProximityNet, inputs: &mut [DVec2]) {
        self.0.controls(t, swarm, net, inputs);
    }
    fn energy(&self, t: f64, swarm: &Swarm<DVec2>, net: &ProximityNet) -> f64 {
        self.0.energy(t, swarm, net)
    }
}

/// A condition that changes perception is refused for a protocol without a local form, named by
/// its field; one that does not (actuation) is accepted.
#[test]
fn perception_needs_a_local_form() {
    let sim = || {
        let protocol = Global(Consensus::proximity(1.0, 2.0).expect("valid"));
        Simulation::new(
            protocol,
            Integrator::SymplecticEuler,
            six_velocities(),
            0.01,
        )
        .expect("valid")
    };
    let error = sim()
        .with_conditions(&delayed(0.1, Delayed::All), 0)
        .expect_err("refused");
    assert_eq!(error.field, "conditions.communication");
    let actuation = Conditions {
        actuation: Some(Actuation {
            max_speed: Some(1.0),
            ..Actuation::default()
        }),
        ..Conditions::default()
    };
    assert!(sim().with_conditions(&actuation, 0).is_ok());
    let bad = delayed(0.105, Delayed::All);
    let error = Simulation::new(
        Consensus::proximity(1.0, 2.0).expect("valid"),
        Integrator::SymplecticEuler,
        six_velocities(),
        0.01,
    )
    .expect("valid")
    .with_conditions(&bad, 0)
    .expect_err("not whole steps");
    assert_eq!(error.field, "conditions.communication.delay");
}

/// The history's bytes per agent: (D + 1) states of 2·dim f64 plus the per-agent vectors.
#[test]
fn bytes_per_agent_counts_the_delay_line() {
    assert_eq!(bytes_per_agent(&Conditions::default(), 2, 0.01), 0);
    let ten = bytes_per_agent(&delayed(0.1, Delayed::All), 2, 0.01);
    let none = bytes_per_agent(&delayed(0.0, Delayed::All), 2, 0.01);
    assert_eq!(ten - none, 10 * 32);
}

/// Issue 31: what `flocking bench --delay 0.1 --loss 0.1 --sensing-noise 0.1` keeps in 2D at
/// h = 0.01 s: the delay line's 11 states, the newest the measured one (11 × 32 B), the input,
/// delivered in place (16 B), and the failure flag; white noise keeps no offsets and Bernoulli
/// loss with dropped packets no links. Ornstein–Uhlenbeck noise adds its offsets (32 B), holding
/// a lost packet a list of links per receiver (24 B), an actuator lag the delivered acceleration
/// apart from the input (16 B).
#[test]
fn bytes_per_agent_of_the_benchmarks_conditions() {
    let mut c = Conditions {
        communication: Some(Communication {
            delay: 0.1,
            loss: Loss::Bernoulli { p: 0.1 },
            ..Communication::default()
        }),
        sensing: Some(Sensing {
            noise: Noise::White {
                sigma_q: 0.1,
                sigma_p: 0.1,
            },
            rate: None,
        }),
        ..Conditions::default()
    };
    assert_eq!(bytes_per_agent(&c, 2, 0.01), 11 * 32 + 16 + 1);
    if let Some(s) = c.sensing.as_mut() {
        s.noise = Noise::OrnsteinUhlenbeck {
            sigma_q: 0.1,
            sigma_p: 0.1,
            correlation_time: 1.0,
        };
    }
    if let Some(m) = c.communication.as_mut() {
        m.when_lost = WhenLost::Hold { max_age: 0.5 };
    }
    assert_eq!(bytes_per_agent(&c, 2, 0.01), 12 * 32 + 16 + 1 + 24);
    c.actuation = Some(Actuation {
        lag: Some(0.5),
        ..Actuation::default()
    });
    assert_eq!(bytes_per_agent(&c, 2, 0.01), 12 * 32 + 2 * 16 + 1 + 24);
}

/// Every condition in 3D: the limits hold and a resumed run keeps the bits.
#[test]
fn every_condition_in_3d() {
    use glam::DVec3;
    let mut conditions = everything();
    if let Some(wind) = conditions
        .disturbance
        .as_mut()
        .and_then(|d| d.wind.as_mut())
    {
        wind.mean = vec![0.1, 0.0, -0.05];
    }
    let new = || {
        let protocol = Algorithm1 {
            alpha: papers_alpha(),
        };
        Simulation::new(
            protocol,
            Integrator::SymplecticEuler,
            random_swarm::<DVec3>(150, 15.0, 1.0, 11),
            0.01,
        )
        .expect("valid")
        .with_conditions(&conditions, 3)
        .expect("valid")
    };
    let (mut whole, mut first) = (new(), new());
    for _ in 0..20 {
        whole.step();
        first.step();
    }
    let mut resumed = Simulation::resume(
        Algorithm1 {
            alpha: papers_alpha(),
        },
        Integrator::SymplecticEuler,
        first.swarm().into_owned(),
        0.01,
        20,
    )
    .expect("valid")
    .with_conditions(&conditions, 3)
    .expect("valid");
    resumed
        .restore_conditions(first.conditions_state().expect("conditions"))
        .expect("same run");
    for _ in 0..30 {
        whole.step();
        resumed.step();
        assert!(
            whole
                .swarm()
                .velocities
                .iter()
                .all(|p| p.length() <= 4.0 * (1.0 + 1e-12))
        );
    }
    assert_eq!(whole.swarm().into_owned(), resumed.swarm().into_owned());
}

/// An explicit communication range cuts the links of a fixed graph longer than it: agents 1 m
/// apart with a 0.5 m range hear nobody and keep their velocities.
#[test]
fn a_communication_range_cuts_fixed_links() {
    let conditions = communicating(Communication {
        range: Some(0.5),
        ..Communication::default()
    });
    let start = six_velocities();
    let swarm = Swarm::new(
        (0..6).map(|i| DVec2::new(f64::from(i), 0.0)).collect(),
        start.velocities.clone(),
    );
    let protocol = Consensus::fixed(1.0, cycle(6), 1.0).expect("valid");
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
        .expect("valid")
        .with_conditions(&conditions, 0)
        .expect("valid");
    // moving apart, so no link ever comes within the range
    for _ in 0..10 {
        sim.step();
    }
    assert_eq!(sim.swarm().velocities, start.velocities);
}

/// With half the packets lost and `Hold`, agents use the last value received (information older
/// than one step on average); with `Drop` every state used is current.
#[test]
fn hold_uses_the_last_value_received() {
    let run = |when_lost| {
        let conditions = communicating(Communication {
            loss: Loss::Bernoulli { p: 0.5 },
            when_lost,
            ..Communication::default()
        });
        let mut sim = consensus_run(0.5, cycle(6), 0.01, &conditions, 0);
        let (mut lost, mut age) = (0.0, 0.0);
        for _ in 0..2000 {
            sim.step();
            let d = sim.diagnostics();
            lost += d[0].1 / 2000.0;
            age += d[1].1 / 2000.0;
        }
        (lost, age)
    };
    let (lost_drop, age_drop) = run(WhenLost::Drop);
    let (lost_hold, age_hold) = run(WhenLost::Hold { max_age: 1.0 });
    println!("hold: lost {lost_hold:.3}, mean information age {age_hold:.4} s; drop: {age_drop}");
    assert!((lost_drop - 0.5).abs() < 0.02 && (lost_hold - 0.5).abs() < 0.02);
    assert_eq!(age_drop, 0.0);
    // half the states used are fresh (age 0); a held one is k ≥ 1 steps old with probability
    // 2^-k, 2 steps on average: the mean age is ½ · 2 h = h = 0.01 s
    assert!((age_hold - 0.01).abs() < 0.0005, "{age_hold}");
}

/// Under conditions the delivered acceleration a is held over the step, and `Integrator::Rk4`
/// integrates that held input: RK4's four stages of ṗ = a give q + h p + ½ h² a and p + h a (to
/// round-off). Bracketed on both sides: not symplectic Euler's q + h (p + h a), ½ h² a away, nor
/// the ideal RK4, which re-evaluates the input at its stages.
#[test]
fn rk4_under_conditions_integrates_the_held_input() {
    let h = 0.1;
    let swarm = six_velocities();
    let protocol = || Consensus::fixed(1.0, cycle(6), 1.0).expect("valid");
    // an acceleration limit never reached: the input is delivered as commanded
    let conditions = Conditions {
        actuation: Some(Actuation {
            max_acceleration: Some(1e9),
            ..Actuation::default()
        }),
        ..Conditions::default()
    };
    let mut held = Simulation::new(protocol(), Integrator::Rk4, swarm.clone(), h)
        .expect("valid")
        .with_conditions(&conditions, 1)
        .expect("valid");
    held.step();
    let mut u = vec![DVec2::ZERO; 6];
    protocol().controls(0.0, &swarm, &ProximityNet::new(), &mut u);
    let (q, p) = (&swarm.positions, &swarm.velocities);
    let after = held.swarm();
    for i in 0..6 {
        // the four stages of RK4 for (q̇, ṗ) = (p, a), a held
        let k = [
            p[i],
            p[i] + u[i] * (h / 2.0),
            p[i] + u[i] * (h / 2.0),
            p[i] + u[i] * h,
        ];
        let q_rk4 = q[i] + (k[0] + k[1] * 2.0 + k[2] * 2.0 + k[3]) * (h / 6.0);
        let p_rk4 = p[i] + (u[i] + u[i] * 2.0 + u[i] * 2.0 + u[i]) * (h / 6.0);
        assert_abs_diff_eq!(after.positions[i], q_rk4, epsilon = 1e-14);
        assert_abs_diff_eq!(after.velocities[i], p_rk4, epsilon = 1e-14);
        let q_euler = q[i] + (p[i] + u[i] * h) * h;
        let gap = (after.positions[i] - q_euler).length();
        assert_abs_diff_eq!(gap, 0.5 * h * h * u[i].length(), epsilon = 1e-14);
    }
    assert!(u.iter().any(|u| u.length() > 0.1), "a test with inputs");
    let mut ideal = Simulation::new(protocol(), Integrator::Rk4, swarm, h).expect("valid");
    ideal.step();
    let gap = (0..6)
        .map(|i| (ideal.swarm().positions[i] - after.positions[i]).length())
        .fold(0.0, f64::max);
    assert!(gap > 1e-6, "the ideal RK4 re-evaluates the input: {gap}");
}
