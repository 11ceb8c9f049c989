//! `flocking bench`: throughput of the simulation loop on synthetic scenarios of any size.
//!
//! [`bench()`] builds n agents on a jittered α-lattice at spacing ≈ d (triangular in 2D,
//! face-centred cubic in 3D) with small random velocities, runs warm-up steps, then times
//! `steps` steps of the chosen algorithm with the flocking metrics and the energy recorded every
//! [`RECORD_EVERY`] steps, as `flocking run` records them. The [`BenchReport`] it returns prints
//! agent-steps per second, ns per agent-step, ms per step, peak memory per agent and the thread
//! count.

use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

use flocking::math::Vector;
use flocking::metrics::{FlockMetrics, MetricParams};
use flocking::obstacles::{ObstacleField, Space};
use flocking::protocols::{
    Algorithm1, Algorithm2, Algorithm3, AlphaInteraction, AlphaParams, BetaInteraction, BetaParams,
    DynProtocol, GammaAgent, Integrator, NavigationalFeedback, Simulation, Swarm,
};
use flocking::synthetic::{D, lattice_swarm, shuffled};

/// Steps between two recorded steps (metrics and energy), as the targets count them.
pub const RECORD_EVERY: u64 = 10;

/// Obstacles of the Algorithm 3 benchmark.
pub const BENCH_OBSTACLES: usize = 1000;

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

/// What `flocking bench` runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
        writeln!(
            f,
            "  ms per step           {:.3}",
            ms_per(self.elapsed, c.steps)
        )?;
        writeln!(
            f,
            "  ms per plain step     {:.3}   ({} steps)",
            ms_per(self.plain, self.plain_steps),
            self.plain_steps
        )?;
        if self.recorded_steps > 0 {
            writeln!(
                f,
                "  ms per recorded step  {:.3}   ({} steps, metrics and energy included)",
                ms_per(self.recorded, self.recorded_steps),
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

/// Runs the benchmark `config` describes on the current rayon pool.
///
/// # Errors
/// When `n < 2` or above [`flocking::MAX_AGENTS`], the dimension is not 2 or 3, or `steps` is 0.
pub fn bench(config: &BenchConfig) -> Result<BenchReport, String> {
    if config.n < 2 {
        return Err(format!("--n must be at least 2, got {}", config.n));
    }
    if config.n > flocking::MAX_AGENTS {
        return Err(format!(
            "--n {} exceeds the {} agents a scenario may have (about 250 bytes each); give a smaller --n",
            config.n,
            flocking::MAX_AGENTS
        ));
    }
    if config.steps == 0 {
        return Err("--steps must be at least 1".to_owned());
    }
    match config.dim {
        2 => Ok(bench_in::<flocking::glam::DVec2>(config)),
        3 => Ok(bench_in::<flocking::glam::DVec3>(config)),
        dim => Err(format!("--dim must be 2 or 3, got {dim}")),
    }
}

fn bench_in<V: Space>(config: &BenchConfig) -> BenchReport {
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
    time(config, protocol, swarm, specs.len(), start)
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

fn time<V: Vector>(
    config: &BenchConfig,
    protocol: DynProtocol<V>,
    swarm: Swarm<V>,
    obstacles: usize,
    start: Instant,
) -> BenchReport {
    let metric_params = MetricParams {
        d: D,
        collision_distance: D / 4.0,
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)
        .unwrap_or_else(|e| unreachable!("the benchmark's state and step are valid: {e}"));
    let setup = start.elapsed();
    for _ in 0..config.warmup {
        sim.step();
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
        sim.step();
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
    BenchReport {
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
    }
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
    }
}
