//! The environments of `flocking::env`: the scenario's protocol acting through an environment
//! gives the run's bits (ideal and under delay + loss + noise); environment k of a batch is the
//! environment seeded alone; one and two threads agree; the reward's deviation terms sum to the
//! paper's Ẽ; the observation is the perception, nearest first; bad actions are refused by name;
//! an ended episode resets at the next step.

use flocking::env::{EnvOptions, Reward, VecEnv};
use flocking::{DynSimulation, Scenario};
use serde_json::json;

use crate::common::fixture;

/// Fig. 11 shortened to `seconds`, with `conditions` (RON) when given.
fn fig11(seconds: f64, conditions: Option<&str>) -> Scenario {
    let scenario = fixture("tac2006_fig11_alg2_n100")
        .with_values([("duration", json!(seconds))])
        .expect("a shorter run");
    match conditions {
        None => scenario,
        Some(text) => Scenario {
            conditions: ron::from_str(text).expect("valid conditions"),
            ..scenario
        },
    }
}

const DELAY_LOSS_NOISE: &str = "#![enable(implicit_some)] (communication: (delay: 0.03, loss: GilbertElliott(p_fail: 0.2, p_recover: 1.0), when_lost: Hold(max_age: 0.1)), sensing: (noise: White(sigma_q: 0.02, sigma_p: 0.01)), control: (rate: 50.0))";

/// The final state of `scenario` run alone, and through a one-flock environment acted on by the
/// scenario's protocol.
fn run_and_rollout(scenario: &Scenario) -> (Vec<f64>, Vec<f64>) {
    let mut sim = DynSimulation::new(scenario).expect("a valid scenario");
    for _ in 0..scenario.steps() {
        sim.step();
    }
    let mut env = VecEnv::new(scenario, 1, scenario.seed, EnvOptions::default()).expect("an env");
    let (n, dim, size) = (scenario.agents, scenario.dim, env.layout().size());
    let (mut obs, mut rewards, mut actions) =
        (vec![0.0; n * size], vec![0.0; n], vec![0.0; n * dim]);
    env.reset(Some(scenario.seed), &mut obs).expect("reset");
    loop {
        env.protocol_actions(&mut actions);
        let outcome = env.step(&actions, &mut obs, &mut rewards).expect("a step")[0].clone();
        assert!(!outcome.terminated, "{outcome:?}");
        if outcome.truncated {
            break;
        }
    }
    let rolled = env.simulations().next().expect("one env");
    assert_eq!(rolled.steps(), scenario.steps());
    let bits = |s: &DynSimulation| {
        let state = s.state();
        state
            .positions
            .iter()
            .chain(state.velocities.iter())
            .map(|x| x.to_bits() as f64)
            .collect()
    };
    (bits(&sim), bits(rolled))
}

#[test]
fn the_protocol_through_the_environment_is_the_run_bit_for_bit() {
    let (run, rollout) = run_and_rollout(&fig11(2.0, None));
    assert!(run == rollout, "ideal Fig. 11");
    let (run, rollout) = run_and_rollout(&fig11(2.0, Some(DELAY_LOSS_NOISE)));
    assert!(
        run == rollout,
        "Fig. 11 with delay, loss, noise and sampled control"
    );
}

/// Observations and rewards of 12 steps of `num_envs` environments from `seed`, each agent
/// pushed by a fixed input.
fn rollout(scenario: &Scenario, num_envs: usize, seed: u64) -> Vec<u64> {
    let mut env = VecEnv::new(scenario, num_envs, seed, EnvOptions::default()).expect("an env");
    let (n, dim, size) = (scenario.agents, scenario.dim, env.layout().size());
    let mut obs = vec![0.0; num_envs * n * size];
    let mut rewards = vec![0.0; num_envs * n];
    let actions: Vec<f64> = (0..num_envs * n * dim)
        .map(|k| ((k % (n * dim) % 7) as f64 - 3.0) * 0.1)
        .collect();
    let mut out: Vec<u64> = Vec::new();
    for _ in 0..12 {
        env.step(&actions, &mut obs, &mut rewards).expect("a step");
        out.extend(obs.iter().chain(&rewards).map(|x| x.to_bits()));
    }
    out
}

#[test]
fn environment_k_of_a_batch_is_the_environment_alone_with_one_or_two_threads() {
    let scenario = fig11(1.0, Some(DELAY_LOSS_NOISE));
    let (n, size) = (scenario.agents, EnvOptions::default().neighbours * 5 + 12);
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
    };
    let batch = pool(2).install(|| rollout(&scenario, 8, 40));
    assert_eq!(batch, pool(1).install(|| rollout(&scenario, 8, 40)));
    let alone = rollout(&scenario, 1, 43);
    // step s of the batch: 8 environments' observations, then their rewards
    let per_step = 8 * n * (size + 1);
    for step in 0..12 {
        let at = step * per_step;
        let obs = &batch[at + 3 * n * size..at + 4 * n * size];
        let rewards = &batch[at + 8 * n * size + 3 * n..at + 8 * n * size + 4 * n];
        let own = &alone[step * n * (size + 1)..];
        assert!(obs == &own[..n * size], "observations of step {step}");
        assert!(
            rewards == &own[n * size..n * (size + 1)],
            "rewards of step {step}"
        );
    }
    assert_ne!(
        &batch[..n * size],
        &batch[n * size..2 * n * size],
        "two seeds, two starts"
    );
}

#[test]
fn the_deviation_terms_of_the_reward_sum_to_the_papers_normalised_deviation_energy() {
    let scenario = fig11(0.5, None);
    let options = EnvOptions {
        reward: Reward {
            deviation: 1.0,
            mismatch: 0.0,
            collision: 0.0,
            gamma: 0.0,
        },
        ..EnvOptions::default()
    };
    let mut env = VecEnv::new(&scenario, 1, 7, options).expect("an env");
    let n = scenario.agents;
    let (mut obs, mut rewards, mut actions) = (
        vec![0.0; n * env.layout().size()],
        vec![0.0; n],
        vec![0.0; n * 2],
    );
    for _ in 0..20 {
        env.protocol_actions(&mut actions);
        env.step(&actions, &mut obs, &mut rewards).expect("a step");
    }
    let total: f64 = -rewards.iter().sum::<f64>();
    let metric = env
        .simulations()
        .next()
        .expect("one")
        .metrics()
        .deviation_energy;
    assert!(metric > 1e-3, "the start is not a lattice: {metric}");
    approx::assert_relative_eq!(total, metric, max_relative = 1e-12);
    // and the other terms count: collisions and γ make the reward lower
    let mut all = VecEnv::new(&scenario, 1, 7, EnvOptions::default()).expect("an env");
    for _ in 0..20 {
        all.protocol_actions(&mut actions);
        all.step(&actions, &mut obs, &mut rewards).expect("a step");
    }
    assert!(-rewards.iter().sum::<f64>() > total);
}

#[test]
fn an_observation_is_the_perception_nearest_first_with_its_masks() {
    let scenario = fig11(5.0, None);
    let options = EnvOptions {
        neighbours: 3,
        ..EnvOptions::default()
    };
    let mut env = VecEnv::new(&scenario, 1, scenario.seed, options).expect("an env");
    let layout = env.layout();
    assert_eq!(layout.size(), 5 * 2 + 2 + 3 * 5);
    let size = layout.size();
    let (n, mut actions) = (scenario.agents, vec![0.0; scenario.agents * 2]);
    let (mut obs, mut rewards) = (vec![0.0; n * size], vec![0.0; n]);
    // 3 s of Algorithm 2: neighbours gathered
    for _ in 0..300 {
        env.protocol_actions(&mut actions);
        env.step(&actions, &mut obs, &mut rewards).expect("a step");
    }
    let sim = env.simulations().next().expect("one");
    let (state, graph) = (sim.state(), sim.graph());
    let q = |i: usize| [state.positions[2 * i], state.positions[2 * i + 1]];
    let p = |i: usize| [state.velocities[2 * i], state.velocities[2 * i + 1]];
    let mut seen_full = false;
    for i in 0..scenario.agents {
        let o = &obs[i * size..(i + 1) * size];
        assert_eq!(&o[..2], &p(i));
        let mut near: Vec<(f64, u32)> = graph
            .neighbours(i)
            .iter()
            .map(|&j| {
                let (a, b) = (q(j as usize), q(i));
                (((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)), j)
            })
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mask = &o[2 + 3 * 4..2 + 3 * 4 + 3];
        let heard = near.len().min(3);
        seen_full |= heard == 3;
        assert_eq!(
            mask.iter().filter(|&&m| m == 1.0).count(),
            heard,
            "agent {i}"
        );
        for (slot, &(_, j)) in near.iter().take(3).enumerate() {
            let s = &o[2 + 4 * slot..2 + 4 * slot + 4];
            let j = j as usize;
            assert_eq!(
                s,
                &[
                    q(j)[0] - q(i)[0],
                    q(j)[1] - q(i)[1],
                    p(j)[0] - p(i)[0],
                    p(j)[1] - p(i)[1]
                ]
            );
        }
        // the γ-agent of Fig. 11, tracked: mask 1
        assert_eq!(o[2 + 15 + 4], 1.0);
        assert_eq!(o[size - 1], 0.0, "no obstacle, no β-agent");
    }
    assert!(seen_full, "the test wants an agent with three neighbours");
}

#[test]
fn bad_actions_are_refused_naming_the_environment_the_agent_and_the_coordinate() {
    let scenario = fig11(1.0, None);
    let mut env = VecEnv::new(&scenario, 2, 0, EnvOptions::default()).expect("an env");
    let n = scenario.agents;
    let (mut obs, mut rewards) = (vec![0.0; 2 * n * env.layout().size()], vec![0.0; 2 * n]);
    let short = env.step(&[0.0; 10], &mut obs, &mut rewards).unwrap_err();
    assert!(short.message.contains("shape (2, 100, 2)"), "{short}");
    let mut actions = vec![0.0; 2 * n * 2];
    actions[n * 2 + 2 * 17 + 1] = f64::NAN;
    let nan = env.step(&actions, &mut obs, &mut rewards).unwrap_err();
    assert!(nan.message.contains("actions[1, 17, 1] = NaN"), "{nan}");
    assert!(VecEnv::new(&scenario, 0, 0, EnvOptions::default()).is_err());
    // the ideal loop's RK4 would evaluate the protocol, not the policy, at its later stages
    let rk4 = scenario
        .with_values([("integrator", json!("Rk4"))])
        .expect("RK4");
    let refused = VecEnv::new(&rk4, 1, 0, EnvOptions::default()).unwrap_err();
    assert_eq!(refused.field().as_deref(), Some("integrator"));
    let held = Scenario {
        conditions: ron::from_str(DELAY_LOSS_NOISE).expect("valid conditions"),
        ..rk4
    };
    assert!(VecEnv::new(&held, 1, 0, EnvOptions::default()).is_ok());
}

#[test]
fn an_ended_episode_resets_at_the_next_step_with_a_new_start() {
    let scenario = fig11(0.03, None);
    let mut env = VecEnv::new(&scenario, 1, 5, EnvOptions::default()).expect("an env");
    let n = scenario.agents;
    let (mut obs, mut rewards) = (vec![0.0; n * env.layout().size()], vec![0.0; n]);
    let mut first = vec![0.0; obs.len()];
    env.reset(Some(5), &mut first).expect("reset");
    let actions = vec![0.0; n * 2];
    let ends: Vec<_> = (0..4)
        .map(|_| env.step(&actions, &mut obs, &mut rewards).expect("a step")[0].clone())
        .collect();
    assert_eq!(
        ends.iter()
            .map(|o| (o.truncated, o.reset))
            .collect::<Vec<_>>(),
        [(false, false), (false, false), (true, false), (false, true)]
    );
    assert_ne!(obs, first, "episode 1 starts elsewhere than episode 0");
    let sim = env.simulations().next().expect("one");
    assert_eq!(sim.steps(), 0);
    env.reset(Some(5), &mut obs).expect("reset");
    assert_eq!(obs, first, "reset(seed) reproduces the first episode");
    env.reset(None, &mut obs).expect("reset");
    assert_ne!(obs, first, "reset() starts the next episode");
}
