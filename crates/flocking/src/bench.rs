//! The benchmark engine of `flocking bench` and Python's `flocking.bench`: throughput of the
//! simulation loop on synthetic scenarios of any size.
//!
//! [`bench()`] builds n agents on a jittered α-lattice at spacing ≈ d (triangular in 2D,
//! face-centred cubic in 3D) with small random velocities, runs warm-up steps, then times
//! `steps` steps of the chosen algorithm with the flocking metrics and the energy recorded every
//! [`RECORD_EVERY`] steps, as `flocking run` records them. The [`BenchReport`] it returns prints
//! agent-steps per second, ns per agent-step, ms per step, peak memory per agent and the thread
//! count. [`BenchConditions`] put the run under real conditions (delay, loss, sensing noise,
//! sampled control, an acceleration limit); the report then also prints the bytes per agent the
//! conditions keep ([`conditions::bytes_per_agent`]).

use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

use crate::error::ScenarioError;
use crate::estimate::{Estimate, Outputs};
use crate::math::Vector;
use crate::metrics::{FlockMetrics, MetricParams};
use crate::obstacles::{ObstacleField, Space};
use crate::protocols::conditions::{
    self, Actuation, Communication, Conditions, Delayed, Loss, Noise, SampledControl, Sensing,
};
use crate::protocols::vehicle::{FixedWingParams, QuadrotorParams, UnicycleParams};
use crate::protocols::{
    Algorithm1, Algorithm2, Algorithm3, AlphaInteraction, AlphaParams, BetaInteraction, BetaParams,
    DynProtocol, GammaAgent, Integrator, NavigationalFeedback, Simulation, Swarm,
};
use crate::protocols::{AlphaConfig, BetaConfig};
use crate::scenario::{
    Algorithm, Algorithm2Params, Algorithm3Params, Cloud, DomainSpec, Initial, Scenario,
};
use crate::synthetic::{D, lattice_swarm, shuffled};
use crate::vehicle::{VehicleSpace, VehicleSpec};

/// Steps between two recorded steps (metrics and energy), as the targets count them.
pub const RECORD_EVERY: u64 = 10;

/// Obstacles of the Algorithm 3 benchmark.
pub const BENCH_OBSTACLES: usize = 1000;

/// The integration step h of the benchmark (s); delays and control periods are whole numbers
/// of it.
pub const STEP: f64 = 0.01;

/// The seed of the conditions' random draws (loss, sensing noise).
pub const CONDITIONS_SEED: u64 = 0;

/// Which algorithm `flocking bench` runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BenchAlgorithm {
    /// Algorithm 1: the α-interaction alone.
    Algorithm1,
    /// Algorithm 2: α-interaction plus linear navigational feedback to a moving γ-agent.
    #[default]
    Algorithm2,
    /// Algorithm 3: Algorithm 2 with bounded feedback plus β-agents on [`BENCH_OBSTACLES`]
    /// ball and box obstacles spread over the flock.
    Algorithm3,
}

impl FromStr for BenchAlgorithm {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "1" | "alg1" | "algorithm1" => Ok(Self::Algorithm1),
            "2" | "alg2" | "algorithm2" => Ok(Self::Algorithm2),
            "3" | "alg3" | "algorithm3" => Ok(Self::Algorithm3),
            _ => Err(format!(
                "unknown algorithm `{s}`: expected 1, 2 or 3 (or algorithm1, algorithm2, algorithm3)"
            )),
        }
    }
}

impl fmt::Display for BenchAlgorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Algorithm1 => "Algorithm 1",
            Self::Algorithm2 => "Algorithm 2",
            Self::Algorithm3 => "Algorithm 3",
        })
    }
}

/// The vehicle `flocking bench` flies the agents on (none: point masses), with its default
/// parameters (docs/vehicles.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BenchVehicle {
    /// The TurtleBot3 Burger unicycle, 2D only.
    Unicycle,
    /// Beard & McLain's fixed wing.
    FixedWing,
    /// The Crazyflie 2.x quadrotor, 3D only.
    Quadrotor,
}

impl BenchVehicle {
    /// Every vehicle, in the order of [`Self::NAMES`].
    pub const ALL: [Self; 3] = [Self::Unicycle, Self::FixedWing, Self::Quadrotor];

    /// The names `flocking bench --vehicle` and Python's `vehicle=` take.
    pub const NAMES: [&'static str; 3] = ["unicycle", "fixed-wing", "quadrotor"];

    /// The scenario's vehicle.
    #[must_use]
    pub fn spec(self) -> VehicleSpec {
        match self {
            Self::Unicycle => VehicleSpec::Unicycle(UnicycleParams::default()),
            Self::FixedWing => VehicleSpec::FixedWing(FixedWingParams::default()),
            Self::Quadrotor => VehicleSpec::Quadrotor(QuadrotorParams::default()),
        }
    }
}

impl FromStr for BenchVehicle {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        one_of(s, "vehicle", &Self::NAMES, &Self::ALL)
    }
}

/// The item of `all` whose name in `names` (same order) is `text`, in any case and with `_` for
/// `-`; otherwise an error naming the `what`, the text and the names.
pub(crate) fn one_of<T: Copy>(
    text: &str,
    what: &str,
    names: &[&str],
    all: &[T],
) -> Result<T, String> {
    let name = text.to_ascii_lowercase().replace('_', "-");
    names
        .iter()
        .position(|&n| n == name)
        .map(|k| all[k])
        .ok_or_else(|| {
            format!(
                "unknown {what} `{text}`: expected one of {}",
                names.join(", ")
            )
        })
}

/// The real conditions a benchmark may run under; none set (the default) is the ideal loop.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BenchConditions {
    /// Communication delay τ in seconds, a whole number of steps of [`STEP`].
    pub delay: Option<f64>,
    /// Whose states the delay applies to.
    pub delayed: Option<Delayed>,
    /// Bernoulli packet loss: each packet of each directed link lost with this probability.
    pub loss: Option<f64>,
    /// White sensing noise: standard deviations σ_q (m) on positions and σ_p (m/s) on
    /// velocities.
    pub sensing_noise: Option<(f64, f64)>,
    /// Sampled control: the controller runs at this rate (Hz) and holds its input between.
    pub control_rate: Option<f64>,
    /// The commanded acceleration is clipped to this norm (m/s²).
    pub max_acceleration: Option<f64>,
}

impl BenchConditions {
    /// The conditions the flags set (not validated: [`bench()`] validates them).
    #[must_use]
    pub fn conditions(&self) -> Conditions {
        let communication = (self.delay.is_some() || self.delayed.is_some() || self.loss.is_some())
            .then(|| Communication {
                delay: self.delay.unwrap_or(0.0),
                delayed: self.delayed.unwrap_or_default(),
                loss: self.loss.map_or(Loss::None, |p| Loss::Bernoulli { p }),
                ..Communication::default()
            });
        Conditions {
            communication,
            sensing: self.sensing_noise.map(|(sigma_q, sigma_p)| Sensing {
                noise: Noise::White { sigma_q, sigma_p },
                rate: None,
            }),
            control: self.control_rate.map(|rate| SampledControl { rate }),
            actuation: self.max_acceleration.map(|a| Actuation {
                max_acceleration: Some(a),
                ..Actuation::default()
            }),
            ..Conditions::default()
        }
    }
}

/// One line naming the conditions set, e.g. `delay 0.1 s (neighbours), loss 0.1`.
impl fmt::Display for BenchConditions {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if self.delay.is_some() || self.delayed.is_some() {
            let whose = match self.delayed.unwrap_or_default() {
                Delayed::Neighbours => "neighbours",
                Delayed::All => "all",
            };
            parts.push(format!("delay {} s ({whose})", self.delay.unwrap_or(0.0)));
        }
        if let Some(p) = self.loss {
            parts.push(format!("loss {p} (Bernoulli)"));
        }
        if let Some((q, p)) = self.sensing_noise {
            parts.push(format!("sensing noise {q} m, {p} m/s (white)"));
        }
        if let Some(rate) = self.control_rate {
            parts.push(format!("control at {rate} Hz"));
        }
        if let Some(a) = self.max_acceleration {
            parts.push(format!("acceleration ≤ {a} m/s²"));
        }
        if parts.is_empty() {
            f.write_str("none (ideal)")
        } else {
            f.write_str(&parts.join(", "))
        }
    }
}

/// `neighbours` or `all`, as [`Delayed`].
///
/// # Errors
/// Any other word, with the two accepted.
pub fn parse_delayed(s: &str) -> Result<Delayed, String> {
    match s.to_ascii_lowercase().as_str() {
        "neighbours" | "neighbors" => Ok(Delayed::Neighbours),
        "all" => Ok(Delayed::All),
        _ => Err(format!("expected `neighbours` or `all`, got `{s}`")),
    }
}

/// What `flocking bench` runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchConfig {
    /// The number of agents n ≥ 2.
    pub n: usize,
    /// The dimension, 2 or 3.
    pub dim: usize,
    /// Timed steps.
    pub steps: u64,
    /// Untimed steps before the timed ones (buffers reach their final size).
    pub warmup: u64,
    /// The algorithm.
    pub algorithm: BenchAlgorithm,
    /// Number the agents in a random order instead of along the lattice rows, as a scenario whose
    /// agents are drawn at random is numbered: neighbours are then far apart in memory.
    pub shuffled: bool,
    /// The real conditions (none: the ideal loop).
    pub conditions: BenchConditions,
    /// The vehicle (none: point masses).
    pub vehicle: Option<BenchVehicle>,
}

/// The measurements of one `flocking bench` run.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchReport {
    /// What was run.
    pub config: BenchConfig,
    /// Worker threads of the rayon pool.
    pub threads: usize,
    /// Obstacles of the scenario (Algorithm 3 only).
    pub obstacles: usize,
    /// Time to build the scenario and its first net.
    pub setup: Duration,
    /// Wall-clock time of the timed steps, metrics and energy included.
    pub elapsed: Duration,
    /// Time of the plain (unrecorded) timed steps.
    pub plain: Duration,
    /// Number of plain timed steps.
    pub plain_steps: u64,
    /// Time of the recorded timed steps (step, metrics and energy).
    pub recorded: Duration,
    /// Number of recorded timed steps.
    pub recorded_steps: u64,
    /// Peak resident memory of the process in bytes (`VmHWM`), when the platform reports it.
    pub peak_memory: Option<u64>,
    /// Mean number of neighbours per agent at the end.
    pub mean_neighbours: f64,
    /// Whether the simulation stored the agents by cell (they were numbered at random).
    pub stored_by_cell: bool,
    /// The metrics at the end.
    pub metrics: FlockMetrics,
    /// The bytes per agent of the conditions' state, [`conditions::bytes_per_agent`] (0 when
    /// ideal).
    pub conditions_bytes_per_agent: usize,
}

impl BenchReport {
    /// Agent-steps per second over the timed steps.
    #[must_use]
    pub fn agent_steps_per_second(&self) -> f64 {
        (self.config.n as f64 * self.config.steps as f64) / self.elapsed.as_secs_f64()
    }

    /// Nanoseconds per agent-step.
    #[must_use]
    pub fn ns_per_agent_step(&self) -> f64 {
        self.elapsed.as_secs_f64() * 1e9 / (self.config.n as f64 * self.config.steps as f64)
    }

    /// Peak memory per agent in bytes.
    #[must_use]
    pub fn bytes_per_agent(&self) -> Option<f64> {
        self.peak_memory.map(|b| b as f64 / self.config.n as f64)
    }

    /// Milliseconds per timed step, metrics and energy included.
    #[must_use]
    pub fn ms_per_step(&self) -> f64 {
        ms_per(self.elapsed, self.config.steps)
    }

    /// Milliseconds per plain (unrecorded) step.
    #[must_use]
    pub fn ms_per_plain_step(&self) -> f64 {
        ms_per(self.plain, self.plain_steps)
    }

    /// Milliseconds per recorded step (step, metrics and energy); `None` with fewer than
    /// [`RECORD_EVERY`] timed steps.
    #[must_use]
    pub fn ms_per_recorded_step(&self) -> Option<f64> {
        (self.recorded_steps > 0).then(|| ms_per(self.recorded, self.recorded_steps))
    }
}

/// Milliseconds of `total` spread over `count` steps.
fn ms_per(total: Duration, count: u64) -> f64 {
    total.as_secs_f64() * 1e3 / count.max(1) as f64
}

impl fmt::Display for BenchReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = &self.config;
        writeln!(
            f,
            "flocking bench: {}, {}D, n = {}, {} steps after {} warm-up, metrics every {} steps",
            c.algorithm, c.dim, c.n, c.steps, c.warmup, RECORD_EVERY
        )?;
        if self.obstacles > 0 {
            writeln!(f, "  obstacles             {}", self.obstacles)?;
        }
        if c.shuffled {
            writeln!(f, "  agents numbered       at random")?;
        }
        if let Some(vehicle) = c.vehicle {
            writeln!(f, "  vehicle               {}", vehicle.spec().name())?;
        }
        if c.conditions != BenchConditions::default() {
            writeln!(f, "  conditions            {}", c.conditions)?;
            writeln!(
                f,
                "  conditions' state     {} bytes/agent (conditions::bytes_per_agent)",
                self.conditions_bytes_per_agent
            )?;
        }
        if self.stored_by_cell {
            writeln!(
                f,
                "  agents stored         by cell (re-sorted every 16 steps)"
            )?;
        }
        writeln!(f, "  threads               {}", self.threads)?;
        writeln!(
            f,
            "  agent-steps/s         {:.4e}",
            self.agent_steps_per_second()
        )?;
        writeln!(f, "  ns per agent-step     {:.1}", self.ns_per_agent_step())?;
        writeln!(f, "  ms per step           {:.3}", self.ms_per_step())?;
        writeln!(
            f,
            "  ms per plain step     {:.3}   ({} steps)",
            self.ms_per_plain_step(),
            self.plain_steps
        )?;
        if let Some(ms) = self.ms_per_recorded_step() {
            writeln!(
                f,
                "  ms per recorded step  {ms:.3}   ({} steps, metrics and energy included)",
                self.recorded_steps
            )?;
        } else {
            writeln!(
                f,
                "  ms per recorded step  n/a     (fewer than {RECORD_EVERY} steps)"
            )?;
        }
        match (self.peak_memory, self.bytes_per_agent()) {
            (Some(peak), Some(per_agent)) => writeln!(
                f,
                "  peak memory           {per_agent:.1} bytes/agent   ({:.1} MiB VmHWM)",
                peak as f64 / (1024.0 * 1024.0)
            )?,
            _ => writeln!(f, "  peak memory           n/a")?,
        }
        writeln!(f, "  mean neighbours       {:.2}", self.mean_neighbours)?;
        writeln!(
            f,
            "  final C, min distance {:.4}, {:.4}",
            self.metrics.connectivity, self.metrics.min_distance
        )?;
        write!(
            f,
            "  setup                 {:.3} s",
            self.setup.as_secs_f64()
        )
    }
}

/// Why a benchmark did not run to its end.
#[derive(Clone, Debug, PartialEq)]
pub enum BenchError {
    /// A flag's value is refused: `flag` as Python's keyword writes it (`n`, `scale_to`, `delay`;
    /// the command's `--n`, `--scale-to`, `--delay`), its value, why and the fix.
    Invalid {
        /// The flag.
        flag: String,
        /// Its value.
        value: String,
        /// Why it is refused.
        why: String,
        /// What to give instead.
        fix: String,
    },
    /// Memory that this machine could not give ([`ScenarioError::is_memory`]).
    Memory(String),
    /// The process's interrupt stopped it ([`crate::interrupt`]).
    Interrupted,
}

impl BenchError {
    /// `flag = value` is refused because `why`; `fix` says what to give instead.
    fn invalid(flag: &str, value: impl fmt::Display, why: &str, fix: &str) -> Self {
        Self::Invalid {
            flag: flag.to_owned(),
            value: value.to_string(),
            why: why.to_owned(),
            fix: fix.to_owned(),
        }
    }

    /// The error of the scenario a benchmark runs, its fields named by the flags that set them
    /// (`flags`: each field's prefix with its flag), the first one of several.
    pub(crate) fn of_scenario(error: &ScenarioError, flags: &[(&str, &str)]) -> Self {
        if error.is_memory() {
            return Self::Memory(error.to_string());
        }
        let Some(ScenarioError::Invalid {
            field,
            value,
            why,
            fix,
        }) = error.problems().into_iter().next()
        else {
            return Self::invalid("scenario", error, "is refused", "give other values");
        };
        let flag = flags
            .iter()
            .find(|(prefix, _)| field.starts_with(prefix))
            .map_or(field.as_str(), |(_, flag)| flag);
        Self::invalid(flag, value, why, fix)
    }
}

impl BenchError {
    /// The message with a refused flag written by `flag(name, value)` (`--scale-to 0` for the
    /// command, `scale_to=0` for Python): `--scale-to 0: why; fix`.
    #[must_use]
    pub fn with_flag(&self, flag: impl Fn(&str, &str) -> String) -> String {
        match self {
            Self::Invalid {
                flag: name,
                value,
                why,
                fix,
            } => format!("{}: {why}; {fix}", flag(name, value)),
            other => other.to_string(),
        }
    }
}

/// `n = 1: …; …`, the flag as Python's keyword (the command prints it as `--n`).
impl fmt::Display for BenchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid {
                flag,
                value,
                why,
                fix,
            } => write!(f, "{flag} = {value}: {why}; {fix}"),
            Self::Memory(why) => write!(f, "{why}"),
            Self::Interrupted => write!(f, "interrupted"),
        }
    }
}

impl std::error::Error for BenchError {}

/// The scenario fields a benchmark's flags set: the field's prefix, the flag.
const FLAGS: [(&str, &str); 8] = [
    ("agents", "n"),
    ("dim", "dim"),
    ("conditions.communication.delayed", "delayed"),
    ("conditions.communication.delay", "delay"),
    ("conditions.communication.loss", "loss"),
    ("conditions.sensing", "sensing_noise"),
    ("conditions.control", "control_rate"),
    ("conditions.actuation", "max_acceleration"),
];

impl BenchConfig {
    /// The scenario the benchmark runs, as its checks and its estimate see it: n agents of the
    /// algorithm (Algorithm 3 without its obstacles, which hold little memory), warm-up and timed
    /// steps of [`STEP`] recorded every [`RECORD_EVERY`], the conditions and the vehicle; the
    /// α-lattice start has the lattice's degree, which the estimate assumes.
    #[must_use]
    pub fn scenario(&self) -> Scenario {
        let point = |x: [f64; 3]| x[..self.dim.clamp(2, 3)].to_vec();
        let gamma = GammaAgent::ConstantVelocity {
            position: point([0.0; 3]),
            velocity: point([1.0, 0.5, 0.0]),
        };
        let algorithm = match self.algorithm {
            BenchAlgorithm::Algorithm1 => Algorithm::Algorithm1,
            BenchAlgorithm::Algorithm2 => Algorithm::Algorithm2(Algorithm2Params {
                gamma,
                c1: 0.02,
                c2: 0.4,
            }),
            BenchAlgorithm::Algorithm3 => Algorithm::Algorithm3(Algorithm3Params {
                gamma,
                c1: 0.02,
                c2: None,
                beta: BetaConfig::default(),
            }),
        };
        let steps = self.warmup.saturating_add(self.steps);
        Scenario {
            name: "bench".to_owned(),
            description: String::new(),
            dim: self.dim,
            agents: self.n,
            seed: 0,
            algorithm,
            domain: DomainSpec::Open,
            vehicle: self
                .vehicle
                .map_or(VehicleSpec::PointMass, BenchVehicle::spec),
            alpha: AlphaConfig::default(),
            initial: Initial {
                positions: Cloud::Zero,
                velocities: Cloud::Zero,
            },
            integrator: Integrator::SymplecticEuler,
            step: STEP,
            duration: steps as f64 * STEP,
            record_every: RECORD_EVERY,
            collision_distance: None,
            obstacles: Vec::new(),
            conditions: self.conditions.conditions(),
            snapshots: None,
        }
    }

    /// Checks every flag as `flocking run` checks a scenario: n from 2 to [`crate::MAX_AGENTS`],
    /// the dimension, at least one timed step and at most [`crate::MAX_STEPS`] in all, the
    /// conditions and the vehicle.
    ///
    /// # Errors
    /// The first flag refused, named.
    pub fn check(&self) -> Result<(), BenchError> {
        if self.n < 2 {
            return Err(BenchError::invalid(
                "n",
                self.n,
                "a benchmark needs at least 2 agents",
                "give n ≥ 2",
            ));
        }
        if self.steps == 0 {
            return Err(BenchError::invalid(
                "steps",
                self.steps,
                "times no step",
                "give at least 1 timed step",
            ));
        }
        let total = self.warmup as f64 + self.steps as f64;
        if total > crate::MAX_STEPS {
            let flag = if self.warmup > self.steps {
                ("warmup", self.warmup)
            } else {
                ("steps", self.steps)
            };
            return Err(BenchError::invalid(
                flag.0,
                flag.1,
                &format!(
                    "makes {total:.3e} steps with the warm-up, more than the {:e} a run may take",
                    crate::MAX_STEPS
                ),
                "give fewer steps",
            ));
        }
        self.scenario()
            .validate()
            .map_err(|e| BenchError::of_scenario(&e, &FLAGS))
    }

    /// What the benchmark will cost (memory, time), as `flocking run` estimates a run: nothing
    /// is written.
    #[must_use]
    pub fn estimate(&self) -> Estimate {
        self.scenario().estimate(&Outputs::NONE)
    }
}

/// Runs the benchmark `config` describes on the current rayon pool, once its flags pass
/// [`BenchConfig::check`] (its estimate is the caller's to check, [`BenchConfig::estimate`]).
///
/// # Errors
/// A flag refused ([`BenchConfig::check`]), memory the machine could not give, or the process's
/// interrupt ([`crate::interrupt`]) between two steps.
pub fn bench(config: &BenchConfig) -> Result<BenchReport, BenchError> {
    config.check()?;
    if config.dim == 2 {
        bench_in::<crate::glam::DVec2>(config, &config.conditions.conditions())
    } else {
        bench_in::<crate::glam::DVec3>(config, &config.conditions.conditions())
    }
}

fn bench_in<V: Space + VehicleSpace>(
    config: &BenchConfig,
    conditions: &Conditions,
) -> Result<BenchReport, BenchError> {
    let start = Instant::now();
    let alpha = AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0)
        .unwrap_or_else(|e| unreachable!("the papers' α-parameters are valid: {e}"));
    let obstacles = match config.algorithm {
        BenchAlgorithm::Algorithm3 => BENCH_OBSTACLES,
        BenchAlgorithm::Algorithm1 | BenchAlgorithm::Algorithm2 => 0,
    };
    let (swarm, specs) = lattice_swarm::<V>(config.n, obstacles);
    let swarm = if config.shuffled {
        shuffled(swarm)
    } else {
        swarm
    };
    // the protocol behind the dynamic type `flocking run` uses
    let protocol: DynProtocol<V> = match config.algorithm {
        BenchAlgorithm::Algorithm1 => Box::new(Algorithm1 { alpha }),
        BenchAlgorithm::Algorithm2 => {
            let navigation = navigation(&swarm, NavigationalFeedback::linear);
            Box::new(Algorithm2 { alpha, navigation })
        }
        BenchAlgorithm::Algorithm3 => {
            let navigation = navigation(&swarm, NavigationalFeedback::bounded);
            let field = ObstacleField::<V>::from_specs(&specs)
                .unwrap_or_else(|e| unreachable!("the benchmark's obstacles are valid: {e}"));
            let beta = BetaInteraction::new(field, BetaParams::papers(D), 0.1, 30.0, 30f64.sqrt())
                .unwrap_or_else(|e| unreachable!("the benchmark's β-parameters are valid: {e}"));
            Box::new(Algorithm3 {
                flock: Algorithm2 { alpha, navigation },
                beta,
            })
        }
    };
    time(config, conditions, protocol, swarm, specs.len(), start)
}

/// The feedback to a γ-agent that starts at the centre of the flock and moves at (1, 0.5[, 0]).
///
/// The papers give no c₁, c₂; fixtures use c₁ = 0.02, c₂ = 0.4 for 100 agents. The linear pull
/// c₁‖q_i − q_r‖ grows with the size of the flock, so c₁ is lowered to 1/R for a flock of radius
/// R > 50 (a pull of at most 1 at the rim): the lattice keeps its density during the benchmark.
fn navigation<V: Vector>(
    swarm: &Swarm<V>,
    form: fn(GammaAgent<V>, f64, f64) -> NavigationalFeedback<V>,
) -> NavigationalFeedback<V> {
    let centre = swarm.centre();
    let radius = swarm
        .positions
        .iter()
        .map(|&q| (q - centre).length())
        .fold(0.0, f64::max);
    let gamma = GammaAgent::ConstantVelocity {
        position: centre,
        velocity: V::from_fn(|k| [1.0, 0.5, 0.0][k]),
    };
    form(gamma, 0.02_f64.min(1.0 / radius.max(1.0)), 0.4)
}

fn time<V: Vector + VehicleSpace>(
    config: &BenchConfig,
    conditions: &Conditions,
    protocol: DynProtocol<V>,
    swarm: Swarm<V>,
    obstacles: usize,
    start: Instant,
) -> Result<BenchReport, BenchError> {
    let metric_params = MetricParams {
        d: D,
        collision_distance: D / 4.0,
    };
    let refused =
        |e: crate::protocols::ParamError| BenchError::of_scenario(&ScenarioError::from(e), &FLAGS);
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, STEP)
        .unwrap_or_else(|e| unreachable!("the benchmark's state and step are valid: {e}"));
    if let Some(vehicle) = config.vehicle {
        let vehicle = V::vehicle(&vehicle.spec())
            .ok()
            .flatten()
            .unwrap_or_else(|| unreachable!("checked: {vehicle:?} exists in {}D", V::DIM));
        sim = sim
            .with_vehicle(vehicle, None)
            .unwrap_or_else(|e| unreachable!("checked: {e}"));
    }
    let mut sim = sim
        .with_conditions(conditions, CONDITIONS_SEED)
        .map_err(refused)?;
    let setup = start.elapsed();
    // one step at a time, each stopped by an interrupt (a step cut short is not timed)
    let step = |sim: &mut Simulation<V, DynProtocol<V>>| {
        let before = sim.steps();
        sim.step();
        if sim.steps() == before || crate::interrupt::requested() {
            Err(BenchError::Interrupted)
        } else {
            Ok(())
        }
    };
    for _ in 0..config.warmup {
        step(&mut sim)?;
    }
    let measure = |sim: &Simulation<V, DynProtocol<V>>| {
        let o = sim.observe(&metric_params);
        (o.metrics, o.energy)
    };
    let (mut plain, mut recorded) = (Duration::ZERO, Duration::ZERO);
    let (mut plain_steps, mut recorded_steps) = (0, 0);
    let mut metrics = None;
    let timed = Instant::now();
    for k in 1..=config.steps {
        let t0 = Instant::now();
        step(&mut sim)?;
        if k % RECORD_EVERY == 0 {
            metrics = Some(std::hint::black_box(measure(&sim)).0);
            recorded += t0.elapsed();
            recorded_steps += 1;
        } else {
            plain += t0.elapsed();
            plain_steps += 1;
        }
    }
    let elapsed = timed.elapsed();
    let metrics = metrics.unwrap_or_else(|| measure(&sim).0);
    // before the graph is copied into original order below
    let peak_memory = peak_memory();
    Ok(BenchReport {
        config: *config,
        threads: rayon::current_num_threads(),
        obstacles,
        setup,
        elapsed,
        plain,
        plain_steps,
        recorded,
        recorded_steps,
        peak_memory,
        mean_neighbours: sim.graph().directed_edge_count() as f64 / config.n as f64,
        stored_by_cell: sim.stored_by_cell(),
        metrics,
        conditions_bytes_per_agent: conditions::bytes_per_agent(conditions, V::DIM, STEP),
    })
}

/// The process's peak resident set (`VmHWM` of `/proc/self/status`) in bytes; `None` where the
/// platform does not report it.
#[must_use]
pub fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line
        .trim_start_matches("VmHWM:")
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn algorithm_names_parse() {
        assert_eq!("3".parse(), Ok(BenchAlgorithm::Algorithm3));
        assert_eq!("Algorithm1".parse(), Ok(BenchAlgorithm::Algorithm1));
        assert!("4".parse::<BenchAlgorithm>().is_err());
        assert_eq!("fixed_wing".parse(), Ok(BenchVehicle::FixedWing));
        assert_eq!("Quadrotor".parse(), Ok(BenchVehicle::Quadrotor));
        assert!("boat".parse::<BenchVehicle>().is_err());
    }

    #[test]
    fn condition_flags_build_the_conditions() {
        assert!(BenchConditions::default().conditions().is_ideal());
        let flags = BenchConditions {
            delay: Some(0.1),
            loss: Some(0.1),
            sensing_noise: Some((0.05, 0.02)),
            ..BenchConditions::default()
        };
        let c = flags.conditions();
        let comm = c.communication.unwrap();
        assert_eq!(
            (comm.delay, comm.delayed, comm.loss),
            (0.1, Delayed::Neighbours, Loss::Bernoulli { p: 0.1 })
        );
        assert_eq!(
            c.sensing.map(|s| s.noise),
            Some(Noise::White {
                sigma_q: 0.05,
                sigma_p: 0.02
            })
        );
        assert_eq!(parse_delayed("All"), Ok(Delayed::All));
        assert_eq!(
            flags.to_string(),
            "delay 0.1 s (neighbours), loss 0.1 (Bernoulli), sensing noise 0.05 m, 0.02 m/s (white)"
        );
    }
}
