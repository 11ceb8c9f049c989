//! `flock bench`: throughput of the simulation loop on synthetic scenarios of any size.
//!
//! [`bench()`] builds n agents on a jittered α-lattice at spacing ≈ d (triangular in 2D,
//! face-centred cubic in 3D) with small random velocities, runs warm-up steps, then times
//! `steps` steps of the chosen algorithm with the flocking metrics and the energy recorded every
//! [`RECORD_EVERY`] steps, as `flock run` records them. The [`BenchReport`] it returns prints
//! agent-steps per second, ns per agent-step, ms per step, peak memory per agent and the thread
//! count.

use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

use flock_math::Vector;
use flock_metrics::{FlockMetrics, MetricParams};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::{
    Algorithm1, Algorithm2, Algorithm3, AlphaInteraction, AlphaParams, BetaInteraction, BetaParams,
    GammaAgent, Integrator, NavigationalFeedback, Protocol, Simulation, Swarm,
};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

use crate::run::measure;

/// Steps between two recorded steps (metrics and energy), as the targets count them.
pub const RECORD_EVERY: u64 = 10;

/// Obstacles of the Algorithm 3 benchmark.
pub const BENCH_OBSTACLES: usize = 1000;

/// The lattice distance d of the synthetic scenarios (the papers' value).
const D: f64 = 7.0;

/// Seed of the jitter and of the initial velocities.
const SEED: u64 = 2006;

/// Which algorithm `flock bench` runs.
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

/// What `flock bench` runs.
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

/// The measurements of one `flock bench` run.
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
            "flock bench: {}, {}D, n = {}, {} steps after {} warm-up, metrics every {} steps",
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
/// When `n < 2`, the dimension is not 2 or 3, or `steps` is 0.
pub fn bench(config: &BenchConfig) -> Result<BenchReport, String> {
    if config.n < 2 {
        return Err(format!("--n must be at least 2, got {}", config.n));
    }
    if config.steps == 0 {
        return Err("--steps must be at least 1".to_owned());
    }
    match config.dim {
        2 => Ok(bench_in::<glam::DVec2>(config)),
        3 => Ok(bench_in::<glam::DVec3>(config)),
        dim => Err(format!("--dim must be 2 or 3, got {dim}")),
    }
}

fn bench_in<V: Space>(config: &BenchConfig) -> BenchReport {
    let start = Instant::now();
    let alpha = AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0);
    let scenario = |obstacles: usize| {
        let (swarm, specs) = scenario::<V>(config.n, obstacles);
        let swarm = if config.shuffled {
            shuffled(swarm)
        } else {
            swarm
        };
        (swarm, specs)
    };
    match config.algorithm {
        BenchAlgorithm::Algorithm1 => {
            let (swarm, _) = scenario(0);
            time(config, Algorithm1 { alpha }, swarm, 0, start)
        }
        BenchAlgorithm::Algorithm2 => {
            let (swarm, _) = scenario(0);
            let navigation = navigation(&swarm, NavigationalFeedback::linear);
            time(config, Algorithm2 { alpha, navigation }, swarm, 0, start)
        }
        BenchAlgorithm::Algorithm3 => {
            let (swarm, specs) = scenario(BENCH_OBSTACLES);
            let navigation = navigation(&swarm, NavigationalFeedback::bounded);
            let field = ObstacleField::<V>::from_specs(&specs)
                .unwrap_or_else(|e| unreachable!("the benchmark's obstacles are valid: {e}"));
            let beta = BetaInteraction::new(field, BetaParams::papers(D), 0.1, 30.0, 30f64.sqrt());
            let protocol = Algorithm3 {
                flock: Algorithm2 { alpha, navigation },
                beta,
            };
            time(config, protocol, swarm, specs.len(), start)
        }
    }
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

fn time<V: Vector, P: Protocol<V>>(
    config: &BenchConfig,
    protocol: P,
    swarm: Swarm<V>,
    obstacles: usize,
    start: Instant,
) -> BenchReport {
    let metric_params = MetricParams {
        d: D,
        collision_distance: D / 4.0,
    };
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01);
    let setup = start.elapsed();
    for _ in 0..config.warmup {
        sim.step();
    }
    let measure = |sim: &Simulation<V, P>| measure(sim, &metric_params);
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
        peak_memory: peak_memory(),
        mean_neighbours: sim.net().graph().directed_edge_count() as f64 / config.n as f64,
        stored_by_cell: !sim.numbering().is_identity(),
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

/// The sites of an α-lattice of spacing `spacing` (triangular in 2D, face-centred cubic in 3D),
/// at least `count` of them, in a square (cubic) patch with its lower corner at the origin.
fn lattice<V: Vector>(count: usize, spacing: f64) -> Vec<V> {
    let mut sites = Vec::with_capacity(count + 64);
    if V::DIM == 2 {
        let row = spacing * 3f64.sqrt() / 2.0;
        let cols = ((count as f64 * 2.0 / 3f64.sqrt()).sqrt().ceil() as usize).max(1);
        'rows: for r in 0.. {
            for c in 0..cols {
                if sites.len() >= count {
                    break 'rows;
                }
                let x = spacing * (c as f64 + 0.5 * (r % 2) as f64);
                sites.push(V::from_fn(|k| [x, row * r as f64][k]));
            }
        }
    } else {
        // conventional cubic cell of side √2 d with 4 sites: nearest neighbours at d
        let a = spacing * 2f64.sqrt();
        let cells = ((count as f64 / 4.0).cbrt().ceil() as usize).max(1);
        const BASIS: [[f64; 3]; 4] = [
            [0.0, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 0.0, 0.5],
            [0.0, 0.5, 0.5],
        ];
        'cells: for z in 0.. {
            for y in 0..cells {
                for x in 0..cells {
                    for b in BASIS {
                        if sites.len() >= count {
                            break 'cells;
                        }
                        let cell = [x as f64, y as f64, z as f64];
                        sites.push(V::from_fn(|k| a * (cell[k] + b[k])));
                    }
                }
            }
        }
    }
    sites
}

/// The initial swarm of n agents, and `obstacles` obstacle descriptions (alternately balls and
/// boxes, on a regular grid over the flock, none containing or touching an agent).
///
/// Agents sit on a lattice of spacing d, jittered by up to ±0.05 d per coordinate, with
/// velocities uniform in [−0.5, 0.5]^m. Lattice sites within an obstacle's reach are left empty and
/// the lattice is grown until n sites remain.
#[must_use]
pub fn scenario<V: Vector>(n: usize, obstacles: usize) -> (Swarm<V>, Vec<ObstacleSpec>) {
    let mut rng = Pcg64::seed_from_u64(SEED);
    let mut growth = 1.0;
    let (sites, specs) = loop {
        let mut sites: Vec<V> = lattice((n as f64 * growth).ceil() as usize, D);
        let specs = obstacle_grid(&sites, obstacles);
        if specs.is_empty() {
            break (sites, specs);
        }
        let reach: Vec<(V, f64)> = specs.iter().map(|s| obstacle_reach(s)).collect();
        let per_axis = obstacles_per_axis(obstacles, V::DIM);
        let (lo, step) = grid_of(&sites, per_axis);
        sites.retain(|&q| {
            // an obstacle reaches at most into the grid cells next to its own
            let cell: [isize; 3] = core::array::from_fn(|k| {
                if k < V::DIM {
                    ((q.coord(k) - lo[k]) / step[k]).floor() as isize
                } else {
                    0
                }
            });
            let span = |k: usize| if k < V::DIM { -1..=1 } else { 0..=0 };
            let axis = per_axis as isize;
            for dz in span(2) {
                for dy in span(1) {
                    for dx in span(0) {
                        let [x, y, z] = [cell[0] + dx, cell[1] + dy, cell[2] + dz];
                        if [x, y, z].iter().any(|&c| c < 0 || c >= axis) {
                            continue;
                        }
                        let index = (x + axis * (y + axis * z)) as usize;
                        if let Some(&(centre, radius)) = reach.get(index)
                            && (q - centre).length() <= radius
                        {
                            return false;
                        }
                    }
                }
            }
            true
        });
        if sites.len() >= n {
            break (sites, specs);
        }
        growth *= 1.05;
    };
    let jitter = 0.05 * D;
    let positions: Vec<V> = sites[..n]
        .iter()
        .map(|&q| q + V::from_fn(|_| jitter * (2.0 * rng.random::<f64>() - 1.0)))
        .collect();
    let velocities: Vec<V> = (0..n)
        .map(|_| V::from_fn(|_| rng.random::<f64>() - 0.5))
        .collect();
    (Swarm::new(positions, velocities), specs)
}

/// The swarm with its agents renumbered by a seeded random permutation (Fisher–Yates).
fn shuffled<V: Vector>(swarm: Swarm<V>) -> Swarm<V> {
    let mut rng = Pcg64::seed_from_u64(SEED + 1);
    let mut order: Vec<usize> = (0..swarm.len()).collect();
    for k in (1..order.len()).rev() {
        order.swap(k, rng.random_range(0..=k));
    }
    Swarm::new(
        order.iter().map(|&i| swarm.positions[i]).collect(),
        order.iter().map(|&i| swarm.velocities[i]).collect(),
    )
}

/// The number of obstacles per axis of the grid holding `count` obstacles.
fn obstacles_per_axis(count: usize, dim: usize) -> usize {
    let mut k = (count as f64).powf(1.0 / dim as f64).round() as usize;
    while k.pow(dim as u32) < count {
        k += 1;
    }
    k.max(1)
}

/// The lower corner and cell sizes of a grid of `per_axis`^m cells over the bounding box of
/// `sites`.
fn grid_of<V: Vector>(sites: &[V], per_axis: usize) -> ([f64; 3], [f64; 3]) {
    let (lo, hi) = sites
        .iter()
        .fold((sites[0], sites[0]), |(lo, hi), &q| (lo.min(q), hi.max(q)));
    let lo = core::array::from_fn(|k| if k < V::DIM { lo.coord(k) } else { 0.0 });
    let step = core::array::from_fn(|k| {
        if k < V::DIM {
            ((hi.coord(k) - lo[k]) / per_axis as f64).max(f64::MIN_POSITIVE)
        } else {
            1.0
        }
    });
    (lo, step)
}

/// `count` obstacles at the centres of a grid over the bounding box of `sites`: balls of radius
/// min(d, spacing/5) and boxes of the same half-width, alternately.
fn obstacle_grid<V: Vector>(sites: &[V], count: usize) -> Vec<ObstacleSpec> {
    if count == 0 {
        return Vec::new();
    }
    let per_axis = obstacles_per_axis(count, V::DIM);
    let (lo, step) = grid_of(sites, per_axis);
    let size = step[..V::DIM].iter().fold(D, |s, &st| s.min(st / 5.0));
    (0..count)
        .map(|index| {
            let cell = [
                index % per_axis,
                (index / per_axis) % per_axis,
                index / (per_axis * per_axis),
            ];
            let centre: Vec<f64> = (0..V::DIM)
                .map(|k| lo[k] + (cell[k] as f64 + 0.5) * step[k])
                .collect();
            if index % 2 == 0 {
                ObstacleSpec::Ball {
                    centre,
                    radius: size,
                }
            } else {
                ObstacleSpec::Cuboid {
                    centre,
                    half_extents: vec![size; V::DIM],
                    rotation: Vec::new(),
                }
            }
        })
        .collect()
}

/// The centre of an obstacle of [`obstacle_grid`] and the radius of the ball around it that agents
/// must stay out of: its circumradius plus a margin of 0.3 d (beyond the jitter).
fn obstacle_reach<V: Vector>(spec: &ObstacleSpec) -> (V, f64) {
    match spec {
        ObstacleSpec::Ball { centre, radius } => (V::from_fn(|k| centre[k]), radius + 0.3 * D),
        ObstacleSpec::Cuboid {
            centre,
            half_extents,
            ..
        } => (
            V::from_fn(|k| centre[k]),
            half_extents[0] * (V::DIM as f64).sqrt() + 0.3 * D,
        ),
        _ => unreachable!("the benchmark only places balls and boxes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn check_lattice<V: Space>() {
        let (swarm, specs) = scenario::<V>(2000, 0);
        assert_eq!(swarm.len(), 2000);
        assert!(specs.is_empty());
        let net = flock_graph::ProximityNet::brute_force(&swarm.positions, 1.2 * D);
        let mean = net.graph().directed_edge_count() as f64 / 2000.0;
        let full = if V::DIM == 2 { 6.0 } else { 12.0 };
        assert!(mean > 0.6 * full && mean <= full, "{mean} neighbours");
        let min = flock_graph::nearest_pair_distance(&swarm.positions).unwrap();
        assert!(min > 0.8 * D, "{min}");
    }

    #[test]
    fn lattice_has_the_papers_spacing_2d() {
        check_lattice::<DVec2>();
    }

    #[test]
    fn lattice_has_the_papers_spacing_3d() {
        check_lattice::<DVec3>();
    }

    #[test]
    fn shuffling_renumbers_the_same_agents() {
        let (swarm, _) = scenario::<DVec2>(3000, 0);
        let renumbered = shuffled(swarm.clone());
        // each agent's state as bits, in index order
        let states = |s: &Swarm<DVec2>| -> Vec<[u64; 4]> {
            let agents = s.positions.iter().zip(&s.velocities);
            agents
                .map(|(q, p)| [q.x, q.y, p.x, p.y].map(f64::to_bits))
                .collect()
        };
        let (mut before, mut after) = (states(&swarm), states(&renumbered));
        let moved = before.iter().zip(&after).filter(|(a, b)| a != b).count();
        assert!(moved > 2900, "only {moved} of 3000 agents renumbered");
        before.sort_unstable();
        after.sort_unstable();
        assert_eq!(before, after);
    }

    fn check_obstacles<V: Space>(n: usize) {
        let (swarm, specs) = scenario::<V>(n, BENCH_OBSTACLES);
        assert_eq!(swarm.len(), n);
        assert_eq!(specs.len(), BENCH_OBSTACLES);
        let field = ObstacleField::<V>::from_specs(&specs).unwrap();
        for &q in &swarm.positions {
            assert!(field.clearance(q) > 0.0, "an agent inside an obstacle");
        }
    }

    #[test]
    fn obstacles_avoid_the_agents() {
        check_obstacles::<DVec2>(500);
        check_obstacles::<DVec2>(20_000);
        check_obstacles::<DVec3>(500);
        check_obstacles::<DVec3>(20_000);
    }

    #[test]
    fn algorithm_names_parse() {
        assert_eq!("3".parse(), Ok(BenchAlgorithm::Algorithm3));
        assert_eq!("Algorithm1".parse(), Ok(BenchAlgorithm::Algorithm1));
        assert!("4".parse::<BenchAlgorithm>().is_err());
    }
}
