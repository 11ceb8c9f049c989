//! Environments for controllers that learn ([`VecEnv`]): `num_envs` flocks of a scenario, each
//! with its own seed and start, stepped together in parallel by one call — every agent observes
//! what it perceives through the scenario's conditions ([`Layout`]), acts with its commanded
//! input, and is rewarded by the measures of TAC 2006 ([`Reward`]). The Python package's
//! `flocking.env` (PettingZoo, Gymnasium) is made of it.
//!
//! One environment step is one control period: the actions are the inputs of the control update
//! the agents perceived ([`DynSimulation::perceive`]); the simulation then steps
//! ([`DynSimulation::act`]) until its next control update (one step of h, or more under sampled
//! control, the inputs held). An episode ends when the run's duration is reached (truncation),
//! or its state blows up (termination, the fault kept); an agent removed by a fault no longer
//! acts (its reward is 0, its input ignored). After an episode ends, the next `step` of that
//! environment resets it, ignoring its actions (Gymnasium 1.x's next-step autoreset), its
//! next episode seeded from its seed and the episode's number.

mod observation;
mod reward;

pub use observation::Layout;
pub use reward::{Reward, Scales};

use flock_sim::Integrator;

use crate::error::ScenarioError;
use crate::perception::Perception;
use crate::scenario::Scenario;
use crate::simulation::DynSimulation;

/// The options of an environment: the neighbours each agent observes and the reward's weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvOptions {
    /// The number k of nearest neighbours in an observation.
    pub neighbours: usize,
    /// The default reward's weights.
    pub reward: Reward,
}

impl Default for EnvOptions {
    /// k = 6 (the hexagonal lattice's neighbours in the plane), the default reward.
    fn default() -> Self {
        Self {
            neighbours: 6,
            reward: Reward::default(),
        }
    }
}

/// One flock of the batch.
struct Env {
    sim: DynSimulation,
    perception: Perception,
    /// The seed of the first episode, and the number of the current one.
    seed: u64,
    episode: u64,
    /// Whether the episode ended at the last step: the next step resets.
    ended: bool,
    /// Why the episode ended by termination (a blow-up).
    fault: Option<String>,
    /// Scratch of the observation's sort.
    order: Vec<(f64, usize)>,
}

/// What the `step` of one environment gives back, beside its observation and rewards.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outcome {
    /// The episode ended by termination (a blow-up: `fault`).
    pub terminated: bool,
    /// The episode ended by truncation (the scenario's duration reached).
    pub truncated: bool,
    /// This step reset the environment (it ended at the previous step): actions ignored.
    pub reset: bool,
    /// Why the episode was terminated.
    pub fault: Option<String>,
}

/// The seed of episode `episode` of an environment seeded `seed`: the seed itself for the first,
/// then SplitMix64 of the pair (a different start and different draws for every episode).
#[must_use]
pub const fn episode_seed(seed: u64, episode: u64) -> u64 {
    if episode == 0 {
        return seed;
    }
    let mut z = seed ^ episode.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Env {
    fn new(scenario: &Scenario, seed: u64) -> Result<Self, ScenarioError> {
        let mut env = Self {
            sim: DynSimulation::new(&Scenario {
                seed,
                ..scenario.clone()
            })?,
            perception: Perception::default(),
            seed,
            episode: 0,
            ended: false,
            fault: None,
            order: Vec::new(),
        };
        env.advance_to_control();
        Ok(env)
    }

    /// Starts episode `episode` of seed `seed`.
    fn start(&mut self, scenario: &Scenario, seed: u64, episode: u64) -> Result<(), ScenarioError> {
        *self = Self::new(scenario, episode_seed(seed, episode))?;
        self.seed = seed;
        self.episode = episode;
        Ok(())
    }

    /// Steps with held inputs until a control update (perceived into `perception`), or the end.
    fn advance_to_control(&mut self) {
        while !self.sim.perceive(&mut self.perception) {
            if self.finished() {
                return;
            }
            self.sim.act(&[]);
        }
    }

    /// Whether the run's duration is reached, or the simulation is torn.
    fn finished(&self) -> bool {
        self.sim.steps() >= self.sim.scenario().steps() || self.sim.is_torn()
    }
}

/// `num_envs` flocks of one scenario stepped together ([module](self)).
pub struct VecEnv {
    scenario: Scenario,
    options: EnvOptions,
    layout: Layout,
    scales: Scales,
    envs: Vec<Env>,
}

impl std::fmt::Debug for VecEnv {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VecEnv")
            .field("scenario", &self.scenario.name)
            .field("num_envs", &self.envs.len())
            .field("layout", &self.layout)
            .finish_non_exhaustive()
    }
}

/// An action, observation or state that cannot be used, naming the environment, the agent and
/// the field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnvError {
    /// The message.
    pub message: String,
}

impl std::fmt::Display for EnvError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for EnvError {}

impl VecEnv {
    /// `num_envs` ≥ 1 flocks of `scenario`, environment k seeded `seed + k`, each at the first
    /// control update of its first episode.
    ///
    /// # Errors
    /// An invalid scenario, `num_envs` of 0 (field `num_envs`), or k of 0 (`neighbours`).
    pub fn new(
        scenario: &Scenario,
        num_envs: usize,
        seed: u64,
        options: EnvOptions,
    ) -> Result<Self, ScenarioError> {
        if num_envs == 0 {
            return Err(ScenarioError::invalid(
                "num_envs",
                num_envs,
                "an environment batch holds at least one flock",
                "use num_envs ≥ 1",
            ));
        }
        if options.neighbours == 0 {
            return Err(ScenarioError::invalid(
                "neighbours",
                options.neighbours,
                "an observation holds at least one neighbour",
                "use neighbours ≥ 1 (6 by default)",
            ));
        }
        scenario.validate()?;
        if scenario.integrator == Integrator::Rk4
            && scenario.conditions.is_ideal()
            && scenario.vehicle.is_point_mass()
        {
            return Err(ScenarioError::invalid(
                "integrator",
                "Rk4",
                "the ideal loop's RK4 evaluates the protocol again at its three later stages, \
                 where a policy acts once per step",
                "use integrator: SymplecticEuler (the papers' figures do), or a condition (the \
                 input is then held over the step and RK4 integrates it)",
            ));
        }
        let envs = seeds(seed, num_envs)
            .map(|s| Env::new(scenario, s))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            layout: Layout {
                dim: scenario.dim,
                k: options.neighbours,
            },
            scales: Scales {
                d: scenario.alpha.d,
                r: scenario.range(),
                collision_distance: scenario.collision_distance(),
                box_size: scenario.box_size(),
            },
            scenario: scenario.clone(),
            options,
            envs,
        })
    }

    /// The number of environments.
    #[must_use]
    pub fn num_envs(&self) -> usize {
        self.envs.len()
    }

    /// The number of agents of each.
    #[must_use]
    pub fn agents(&self) -> usize {
        self.scenario.agents
    }

    /// The layout of an agent's observation.
    #[must_use]
    pub const fn layout(&self) -> Layout {
        self.layout
    }

    /// The scenario.
    #[must_use]
    pub const fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Restarts every environment and writes their observations into `obs`
    /// (num_envs × n × [`Layout::size`]): with a `seed`, environment k's first episode of seed
    /// `seed + k` (the same bits at every reset with that seed); without, each environment's next
    /// episode.
    ///
    /// # Errors
    /// A scenario that cannot be built with a seed (none that validated).
    pub fn reset(&mut self, seed: Option<u64>, obs: &mut [f64]) -> Result<(), ScenarioError> {
        let scenario = &self.scenario;
        let starts: Vec<(u64, u64)> = match seed {
            Some(seed) => seeds(seed, self.envs.len()).map(|s| (s, 0)).collect(),
            None => self.envs.iter().map(|e| (e.seed, e.episode + 1)).collect(),
        };
        let started: Vec<Result<(), ScenarioError>> = map_envs(&mut self.envs, |k, env| {
            env.start(scenario, starts[k].0, starts[k].1)
        });
        started.into_iter().collect::<Result<(), _>>()?;
        self.observe(obs);
        Ok(())
    }

    /// Every environment's observations into `obs` (num_envs × n × size).
    fn observe(&mut self, obs: &mut [f64]) {
        let (layout, size) = (self.layout, self.layout.size() * self.scenario.agents);
        let mut chunks: Vec<&mut [f64]> = obs.chunks_exact_mut(size).collect();
        map_envs_with(&mut self.envs, &mut chunks, |_, env, obs| {
            layout.observe(&env.perception, obs, &mut env.order);
        });
    }

    /// One step of every environment ([module](self)): `actions` (num_envs × n × dim, original
    /// order) in; observations (num_envs × n × size), rewards (num_envs × n) and the outcome of
    /// each environment out.
    ///
    /// # Errors
    /// `actions` of the wrong length, or an action that is not finite (naming the environment,
    /// the agent and the coordinate); nothing is stepped then.
    pub fn step(
        &mut self,
        actions: &[f64],
        obs: &mut [f64],
        rewards: &mut [f64],
    ) -> Result<Vec<Outcome>, EnvError> {
        let (n, dim) = (self.scenario.agents, self.scenario.dim);
        let per_env = n * dim;
        if actions.len() != per_env * self.envs.len() {
            return Err(EnvError {
                message: format!(
                    "actions hold {} numbers where {} environments of {n} agents in {dim}D need {}: give an array of shape ({}, {n}, {dim})",
                    actions.len(),
                    self.envs.len(),
                    per_env * self.envs.len(),
                    self.envs.len()
                ),
            });
        }
        if let Some(at) = actions.iter().position(|x| !x.is_finite()) {
            let (e, i, c) = (at / per_env, (at % per_env) / dim, at % dim);
            return Err(EnvError {
                message: format!(
                    "actions[{e}, {i}, {c}] = {} is not finite: environment {e}, agent {i} must be given a finite input",
                    actions[at]
                ),
            });
        }
        let (scenario, layout, scales) = (&self.scenario, self.layout, &self.scales);
        let weights = self.options.reward;
        let size = layout.size() * n;
        let mut slots: Vec<(&[f64], &mut [f64], &mut [f64])> = actions
            .chunks_exact(per_env)
            .zip(obs.chunks_exact_mut(size))
            .zip(rewards.chunks_exact_mut(n))
            .map(|((a, o), r)| (a, o, r))
            .collect();
        let outcomes = map_envs_with(&mut self.envs, &mut slots, |_, env, (a, o, r)| {
            let outcome = env.step(scenario, a, r, (&weights, scales));
            layout.observe(&env.perception, o, &mut env.order);
            outcome
        });
        Ok(outcomes)
    }

    /// What the scenario's protocol would command every agent of every environment for what it
    /// perceives now, into `out` (num_envs × n × dim): a step with these actions gives
    /// `flocking run`'s bits. An environment whose episode has ended gets zeros.
    pub fn protocol_actions(&mut self, out: &mut [f64]) {
        let per_env = self.scenario.agents * self.scenario.dim;
        let mut chunks: Vec<&mut [f64]> = out.chunks_exact_mut(per_env).collect();
        map_envs_with(&mut self.envs, &mut chunks, |_, env, out| {
            if env.ended || !env.sim.protocol_inputs(out) {
                out.fill(0.0);
            }
        });
    }

    /// The simulations, for their states and measures.
    pub fn simulations(&self) -> impl Iterator<Item = &DynSimulation> {
        self.envs.iter().map(|e| &e.sim)
    }
}

impl Env {
    /// One step: reset if the episode ended, else act with `actions` until the next control
    /// update, and the rewards of the state reached.
    fn step(
        &mut self,
        scenario: &Scenario,
        actions: &[f64],
        rewards: &mut [f64],
        (weights, scales): (&Reward, &Scales),
    ) -> Outcome {
        if self.ended {
            let (seed, episode) = (self.seed, self.episode + 1);
            rewards.fill(0.0);
            return match self.start(scenario, seed, episode) {
                Ok(()) => Outcome {
                    reset: true,
                    ..Outcome::default()
                },
                Err(e) => self.terminate(e.to_string()),
            };
        }
        self.sim.act(actions);
        if let Err(e) = self.sim.check_health() {
            rewards.fill(0.0);
            return self.terminate(e.to_string());
        }
        self.advance_to_control();
        let state = self.sim.state();
        let graph = self.sim.graph();
        let failed = state.failed.as_deref();
        let gamma = self.perception.gamma.as_ref().map(|(q, _)| q.as_slice());
        weights.of(
            scales,
            state.dim,
            (&state.positions, &state.velocities, &graph),
            gamma,
            |i| failed.is_none_or(|f| !f[i]),
            rewards,
        );
        let truncated = self.finished();
        self.ended = truncated;
        Outcome {
            truncated,
            ..Outcome::default()
        }
    }

    /// The episode terminated by `fault`.
    fn terminate(&mut self, fault: String) -> Outcome {
        self.ended = true;
        self.fault = Some(fault.clone());
        Outcome {
            terminated: true,
            fault: Some(fault),
            ..Outcome::default()
        }
    }
}

/// The seeds `seed`, `seed + 1`, … of `count` environments.
fn seeds(seed: u64, count: usize) -> impl Iterator<Item = u64> {
    (0..count as u64).map(move |k| seed.wrapping_add(k))
}

/// `f(k, env k)` for every environment, in parallel.
fn map_envs<T: Send>(envs: &mut [Env], f: impl Fn(usize, &mut Env) -> T + Sync) -> Vec<T> {
    let mut unit = vec![(); envs.len()];
    let mut units: Vec<&mut ()> = unit.iter_mut().collect();
    map_envs_with(envs, &mut units, |k, env, _| f(k, env))
}

/// `f(k, env k, slot k)` for every environment, in parallel (each environment's bits are its
/// own: the same for any thread count).
fn map_envs_with<S: Send, T: Send>(
    envs: &mut [Env],
    slots: &mut [S],
    f: impl Fn(usize, &mut Env, &mut S) -> T + Sync,
) -> Vec<T> {
    use rayon::prelude::*;
    envs.par_iter_mut()
        .zip(slots.par_iter_mut())
        .enumerate()
        .map(|(k, (env, slot))| f(k, env, slot))
        .collect()
}

/// Row `m` of rows of `dim` numbers.
fn row_of(dim: usize, rows: &[f64], m: usize) -> &[f64] {
    &rows[m * dim..(m + 1) * dim]
}
