//! What a run will cost before it starts: steps, memory, disk and time, from the figures measured
//! in `docs/performance.md`, and whether this machine can afford it.
//!
//! - [`Scenario::estimate`]: the [`Estimate`] of one run with the chosen outputs ([`Outputs`]);
//!   its memory counts the state of the scenario's conditions (mostly the delay line,
//!   [`conditions::bytes_per_agent`]).
//! - [`Estimate::times`]: a sweep's runs together (disk and time add up; memory is per worker).
//! - [`Resources::of_machine`]: the memory available (`MemAvailable` of `/proc/meminfo`, or a
//!   cgroup's `memory.max` if lower) and the free space of an output directory's disk;
//!   [`Estimate::check`] refuses what does not fit.
//! - [`check_threads`]: a thread (or sweep worker) count within reason for this machine.
//!
//! # Example
//! ```
//! use flocking::estimate::Outputs;
//! use flocking::Scenario;
//!
//! # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).unwrap(); // the workspace root
//! let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
//! let estimate = scenario.estimate(&Outputs::RUN);
//! assert_eq!(estimate.steps, 10_000);
//! assert_eq!(estimate.records, 501);
//! assert!(estimate.seconds < 10.0 && estimate.memory_bytes < 100e6);
//! # Ok::<(), flocking::ScenarioError>(())
//! ```

use std::fmt;

use flock_graph::NeighbourSearch;
use flock_obstacles::Space;
use glam::{DVec2, DVec3};

use crate::initial::initial_positions;
use crate::machine::available_memory;
pub use crate::machine::{Resources, THREADS_PER_CORE, check_threads, cores};
use crate::scenario::Scenario;
use crate::vehicle::VehicleSpec;
use flock_sim::{Integrator, conditions};

/// Memory of the process without agents: its code and the output buffers (peak RSS of `flocking
/// run` of 10 agents: 11.5 MB; docs/performance.md, "Crowds in the estimate").
pub const FIXED_BYTES: f64 = 20e6;

/// Memory per agent in 2D and 3D besides the net: state, inputs, cells, metrics and the summary
/// (peak RSS of `flocking run` less its edges' [`BYTES_PER_EDGE`], fitted in docs/performance.md:
/// 156 B in 2D at n = 10⁶, 357 B in 3D at 2·10⁵, both from sparse starts), with a margin.
pub const BYTES_PER_AGENT: [f64; 2] = [180.0, 380.0];

/// Memory per undirected edge of the net within the sensing range r, in 2D and 3D: the neighbour
/// lists of the step and of its search, the net of each record and of the summary, and in 2D the
/// edges' midpoints for their crossings (peak RSS of crowds of Algorithm 2, boids, Vicsek, Couzin
/// and Vásárhelyi's drones in docs/performance.md: 79–122 B in 2D, 25–38 B in 3D), with a margin.
pub const BYTES_PER_EDGE: [f64; 2] = [110.0, 45.0];

/// The mean degree every estimate assumes at least: the α-lattice's (6 neighbours in the plane,
/// 12 in space), which a flock reaches wherever it starts.
pub const LATTICE_DEGREE: [f64; 2] = [6.0, 12.0];

/// Agent-steps per second of one thread in 2D and 3D (docs/performance.md, `flocking bench`,
/// n = 10⁶, Algorithm 2, the slower of the measured rates) at [`LATTICE_DEGREE`]; a denser start
/// takes longer in proportion to its mean degree.
pub const AGENT_STEPS_PER_SECOND: [f64; 2] = [3.4e6, 1.13e6];

/// The most pair tests [`Scenario::estimate_at_start`] spends counting the start's net (2³²):
/// each step of the run tests as many, so a start past it is too dense to run in reasonable time.
/// It bounds the work of one step that validation lets through too (pairs of an all-pairs model,
/// agents × inner steps of a vehicle), so that every step the estimate states is one it can
/// count.
pub const START_COUNT_BUDGET: usize = 1 << 32;

/// Bytes of each slot of the delay line besides the agents' states: its two vectors' headers
/// (24 B each) and their heap blocks' (16 B each) — most of a slot for a few agents.
pub const SLOT_BYTES: f64 = 80.0;

/// What a checkpoint of a run with a delay line holds of it besides the line, in lines: a copy of
/// the conditions' state (1) and its RON text (up to 2.5: 20 characters for a number of 8
/// bytes), made while the checkpoint is written (docs/performance.md, "The delay line in the
/// estimate").
pub const CHECKPOINT_COPIES: f64 = 3.5;

/// Seconds of one inner step of one vehicle on one thread: the unicycle, the fixed wing, the
/// quadrotor (`flocking run` of 30–50 vehicles at 1,000 to 10,000 inner steps a step, one
/// thread; docs/performance.md, "Vehicles and all pairs in the estimate").
pub const INNER_STEP_SECONDS: [f64; 3] = [
    UNICYCLE_INNER_STEP,
    FIXED_WING_INNER_STEP,
    QUADROTOR_INNER_STEP,
];

/// [`INNER_STEP_SECONDS`] of the unicycle.
const UNICYCLE_INNER_STEP: f64 = 65e-9;
/// [`INNER_STEP_SECONDS`] of the fixed wing.
const FIXED_WING_INNER_STEP: f64 = 150e-9;
/// [`INNER_STEP_SECONDS`] of the quadrotor.
const QUADROTOR_INNER_STEP: f64 = 330e-9;

/// Seconds of one pair of an all-pairs sum (Cucker–Smale without a cutoff, ψ's power for each
/// of the n − 1 others of every agent) on one thread (docs/performance.md, "Vehicles and all
/// pairs in the estimate").
pub const ALL_PAIRS_SECONDS: f64 = 14e-9;

/// Bytes of a `metrics.csv` row (nine columns, shortest round-trip f64: ≈ 115 B in the gallery)
/// with room for a protocol's diagnostics.
pub const METRICS_ROW_BYTES: f64 = 200.0;

/// Bytes of one f64 written as CSV text (shortest round trip, sign, separator).
pub const CSV_NUMBER_BYTES: f64 = 21.0;

/// A warning is printed above this much time, in seconds (one hour).
pub const LONG_SECONDS: f64 = 3600.0;

/// A warning is printed above this much disk, in bytes (one gigabyte).
pub const LARGE_BYTES: f64 = 1e9;

/// What a run writes, which sizes its disk use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    /// `metrics.csv`: one row per record.
    pub metrics: bool,
    /// The trajectory: `Some(true)` for CSV text, `Some(false)` for binary `.npy`, `None` for none.
    pub trajectory_csv: Option<bool>,
    /// `checkpoint.bin` (the state, twice while it is replaced) and `final.csv`.
    pub checkpoint: bool,
}

impl Outputs {
    /// What `flocking run` writes by default: metrics, the CSV trajectory, checkpoint and final state.
    pub const RUN: Self = Self {
        metrics: true,
        trajectory_csv: Some(true),
        checkpoint: true,
    };
    /// What a sweep run keeps: nothing but its row (the run is in memory).
    pub const NONE: Self = Self {
        metrics: false,
        trajectory_csv: None,
        checkpoint: false,
    };
}

/// The estimated cost of a run (or of several, [`Estimate::times`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// How many runs it covers.
    pub runs: u64,
    /// Steps of one run, ⌈T / h⌉.
    pub steps: u64,
    /// Records of one run (every `record_every` steps, t = 0 and the last step).
    pub records: u64,
    /// Agent-steps in all, n × steps × runs.
    pub agent_steps: f64,
    /// Peak memory of one run, in bytes.
    pub memory_bytes: f64,
    /// Of `memory_bytes`, what the delay line holds: every agent's states over the delay and
    /// jitter ([`conditions::delay_line_bytes_per_agent`]; 0 when no condition changes
    /// perception).
    pub delay_line_bytes: f64,
    /// Disk written by all the runs, in bytes.
    pub disk_bytes: f64,
    /// Time on one thread, in seconds.
    pub seconds: f64,
    /// The density of the net the memory and time assume.
    pub density: Density,
}

/// The mean degree of the net within the sensing range r that an [`Estimate`] assumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Density {
    /// [`LATTICE_DEGREE`]: the start was not counted.
    Lattice,
    /// The start's net was counted: its mean degree (the estimate takes at least the lattice's).
    Start(f64),
    /// The start's net has more candidate pairs than [`START_COUNT_BUDGET`]: too dense to count
    /// (or to run), so the estimate does not fit any machine.
    TooDense,
}

impl Scenario {
    /// The cost of running this scenario with `outputs`.
    #[must_use]
    pub fn estimate(&self, outputs: &Outputs) -> Estimate {
        let n = self.agents as f64;
        let dim = self.dim.clamp(2, 3);
        let steps = self.steps();
        let every = self.record_every.max(1);
        // t = 0, every `record_every` steps, and the last step
        let records = steps / every + 1 + u64::from(!steps.is_multiple_of(every));
        let state_values = n * 2.0 * dim as f64;
        let trajectory = match outputs.trajectory_csv {
            // t, agent, position, velocity per row
            Some(true) => records as f64 * n * (2.0 + 2.0 * dim as f64) * CSV_NUMBER_BYTES,
            Some(false) => records as f64 * state_values * 8.0,
            None => 0.0,
        };
        let metrics = if outputs.metrics {
            records as f64 * METRICS_ROW_BYTES
        } else {
            0.0
        };
        let checkpoint = if outputs.checkpoint {
            2.0 * state_values * 8.0 + state_values * CSV_NUMBER_BYTES
        } else {
            0.0
        };
        let agent_steps = n * steps as f64;
        // the conditions' state besides the delay line, none for an ideal run
        let per_agent = conditions::bytes_per_agent(&self.conditions, dim, self.step)
            - conditions::delay_line_bytes_per_agent(&self.conditions, dim, self.step);
        let delay_line_bytes = self.delay_line_bytes(outputs);
        let degree = LATTICE_DEGREE[dim - 2];
        Estimate {
            runs: 1,
            steps,
            records,
            agent_steps,
            memory_bytes: FIXED_BYTES
                + n * (BYTES_PER_AGENT[dim - 2]
                    + per_agent as f64
                    + degree / 2.0 * BYTES_PER_EDGE[dim - 2])
                + delay_line_bytes,
            delay_line_bytes,
            disk_bytes: trajectory + metrics + checkpoint,
            seconds: agent_steps * self.seconds_per_agent_step(degree),
            density: Density::Lattice,
        }
    }

    /// The bytes of the delay line (every agent's states over the delay and jitter,
    /// [`conditions::delay_line_bytes_per_agent`]) with its slots' own [`SLOT_BYTES`], and when a
    /// run keeps checkpoints, what a checkpoint makes of it: a copy and its text
    /// ([`CHECKPOINT_COPIES`] times it in all; issue 49: a delay line of 10⁴ s was estimated at a
    /// third of its peak).
    fn delay_line_bytes(&self, outputs: &Outputs) -> f64 {
        let dim = self.dim.clamp(2, 3);
        let per_agent = conditions::delay_line_bytes_per_agent(&self.conditions, dim, self.step);
        let slots = per_agent as f64 / (2.0 * dim as f64 * 8.0);
        let line = self.agents as f64 * per_agent as f64 + slots * SLOT_BYTES;
        if outputs.checkpoint {
            line * (1.0 + CHECKPOINT_COPIES)
        } else {
            line
        }
    }

    /// The seconds of one agent-step on one thread with `degree` neighbours within the sensing
    /// range: the point masses' step at that degree ([`AGENT_STEPS_PER_SECOND`], in proportion
    /// to the degree above the lattice's), every evaluation of the inputs (four for RK4), the
    /// other agents of an all-pairs model ([`ALL_PAIRS_SECONDS`] each) and the vehicle's inner
    /// steps ([`INNER_STEP_SECONDS`] each).
    fn seconds_per_agent_step(&self, degree: f64) -> f64 {
        let dim = self.dim.clamp(2, 3);
        let lattice = LATTICE_DEGREE[dim - 2];
        let evaluations = match self.integrator {
            Integrator::Rk4 if !self.algorithm.sets_velocity() => 4.0,
            _ => 1.0,
        };
        let others = if self.algorithm.couples_every_pair() {
            self.agents.saturating_sub(1) as f64 * ALL_PAIRS_SECONDS
        } else {
            0.0
        };
        let inner = match self.vehicle {
            VehicleSpec::PointMass => 0.0,
            VehicleSpec::Unicycle(_) => INNER_STEP_SECONDS[0],
            VehicleSpec::FixedWing(_) => INNER_STEP_SECONDS[1],
            VehicleSpec::Quadrotor(_) => INNER_STEP_SECONDS[2],
        };
        evaluations * (degree.max(lattice) / lattice / AGENT_STEPS_PER_SECOND[dim - 2] + others)
            + self.vehicle.inner_steps(self.step) * inner
    }

    /// [`Scenario::estimate`] with the net of the start counted (within the sensing range r,
    /// [`Scenario::range`], in the scenario's domain) when it is denser than the lattice: memory
    /// grows by [`BYTES_PER_EDGE`] and time in proportion to the mean degree. A start of thousands
    /// of neighbours per agent needs hundreds of times the memory of a lattice, which
    /// [`Estimate::check`] must know before the run allocates it.
    ///
    /// The count holds the start's positions and a cell grid (≈ 40 bytes per agent, far below
    /// the estimate without it), and is made only when that estimate fits in the memory available
    /// ([`Resources::of_machine`]), so that it cannot exhaust memory itself.
    #[must_use]
    pub fn estimate_at_start(&self, outputs: &Outputs) -> Estimate {
        self.estimate_counted_within(outputs, available_memory())
    }

    /// [`Scenario::estimate_at_start`] with `memory` bytes available (`None`: unknown).
    fn estimate_counted_within(&self, outputs: &Outputs, memory: Option<f64>) -> Estimate {
        let estimate = self.estimate(outputs);
        if memory.is_some_and(|memory| estimate.memory_bytes > memory) {
            return estimate;
        }
        let edges = match self.dim {
            2 => start_edges::<DVec2>(self),
            _ => start_edges::<DVec3>(self),
        };
        let Some(edges) = edges else {
            return Estimate {
                density: Density::TooDense,
                ..estimate
            };
        };
        let dim = self.dim.clamp(2, 3);
        let n = self.agents.max(1) as f64;
        let degree = 2.0 * edges as f64 / n;
        let lattice = LATTICE_DEGREE[dim - 2];
        let extra = (degree - lattice).max(0.0);
        Estimate {
            memory_bytes: estimate.memory_bytes + n * extra / 2.0 * BYTES_PER_EDGE[dim - 2],
            seconds: estimate.agent_steps * self.seconds_per_agent_step(degree),
            density: Density::Start(degree),
            ..estimate
        }
    }
}

/// The undirected edges of the start's net within r, `None` past [`START_COUNT_BUDGET`] tests.
pub(crate) fn start_edges<V: Space>(scenario: &Scenario) -> Option<usize> {
    let q: Vec<V> = initial_positions(scenario).collect();
    NeighbourSearch::new().count_pairs_in(
        &scenario.domain(),
        &q,
        scenario.range(),
        START_COUNT_BUDGET,
        |_, _| true,
    )
}

impl Estimate {
    /// `runs` runs of this cost one after the other: disk and time add up, memory is that of one.
    #[must_use]
    pub fn times(self, runs: u64) -> Self {
        let k = runs as f64;
        Self {
            runs: self.runs.saturating_mul(runs),
            agent_steps: self.agent_steps * k,
            disk_bytes: self.disk_bytes * k,
            seconds: self.seconds * k,
            ..self
        }
    }

    /// The two runs together: the larger memory and its density (too dense if either is), the
    /// sums of the rest.
    #[must_use]
    pub fn and(self, other: Self) -> Self {
        Self {
            runs: self.runs.saturating_add(other.runs),
            steps: self.steps.max(other.steps),
            records: self.records.max(other.records),
            agent_steps: self.agent_steps + other.agent_steps,
            memory_bytes: self.memory_bytes.max(other.memory_bytes),
            delay_line_bytes: if self.memory_bytes >= other.memory_bytes {
                self.delay_line_bytes
            } else {
                other.delay_line_bytes
            },
            disk_bytes: self.disk_bytes + other.disk_bytes,
            seconds: self.seconds + other.seconds,
            density: match (self.density, other.density) {
                (Density::TooDense, _) | (_, Density::TooDense) => Density::TooDense,
                _ if self.memory_bytes >= other.memory_bytes => self.density,
                _ => other.density,
            },
        }
    }

    /// Warnings for a run longer than an hour or writing more than a gigabyte (the fixes those of
    /// `flocking run`).
    #[must_use]
    pub fn warnings(&self) -> Vec<String> {
        self.warnings_fixed_by(&Fixes::RUN)
    }

    /// [`Estimate::warnings`] of a sweep: the fixes those of `flocking sweep`, which writes run
    /// directories only with `--keep-runs` (and has no `--trajectory-format`).
    #[must_use]
    pub fn sweep_warnings(&self) -> Vec<String> {
        self.warnings_fixed_by(&Fixes::SWEEP)
    }

    fn warnings_fixed_by(&self, fixes: &Fixes) -> Vec<String> {
        let mut warnings = Vec::new();
        if self.seconds > LONG_SECONDS {
            warnings.push(format!(
                "warning: this will take about {} on one thread (more than an hour); \
                 a larger step, a shorter duration or fewer agents shorten it",
                duration(self.seconds)
            ));
        }
        if self.disk_bytes > LARGE_BYTES {
            warnings.push(format!(
                "warning: this will write about {} (more than a gigabyte); {} write less",
                bytes(self.disk_bytes),
                fixes.less_disk
            ));
        }
        warnings
    }

    /// Whether the estimate fits in `resources`.
    ///
    /// # Errors
    /// What does not fit, with the figures and the fix.
    pub fn check(&self, resources: &Resources) -> Result<(), String> {
        self.check_fixed_by(resources, &Fixes::RUN)
    }

    /// [`Estimate::check`] of a sweep: the fixes named are those of `flocking sweep`.
    ///
    /// # Errors
    /// What does not fit, with the figures and the fix.
    pub fn check_sweep(&self, resources: &Resources) -> Result<(), String> {
        self.check_fixed_by(resources, &Fixes::SWEEP)
    }

    fn check_fixed_by(&self, resources: &Resources, fixes: &Fixes) -> Result<(), String> {
        if self.density == Density::TooDense {
            return Err(format!(
                "the start is too dense to estimate: its net within the sensing range has more \
                 than 2^32 ({START_COUNT_BUDGET}) candidate pairs to test, and every step tests \
                 them all; use fewer agents or a larger start region, or --no-resource-check to \
                 try anyway"
            ));
        }
        if let Some(memory) = resources.memory_bytes
            && self.memory_bytes > memory
        {
            let needs = format!(
                "a run needs about {} of memory but {} is available",
                bytes(self.memory_bytes),
                bytes(memory)
            );
            // the delay line most of it: fewer agents is not the fix a user looks for
            if self.delay_line_bytes > 0.5 * self.memory_bytes {
                return Err(format!(
                    "{needs}, {} of it the delay line of conditions.communication.delay \
                     (every agent's states over the delay and jitter); a shorter delay or \
                     fewer agents, or --no-resource-check to try anyway",
                    bytes(self.delay_line_bytes)
                ));
            }
            return Err(format!(
                "{needs}; use fewer agents (about {:.0} bytes per agent), or \
                 --no-resource-check to try anyway",
                (self.memory_bytes - FIXED_BYTES) / self.agent_steps.max(1.0)
                    * self.steps.max(1) as f64
                    * self.runs.max(1) as f64
            ));
        }
        if let Some(disk) = resources.disk_bytes
            && self.disk_bytes > disk
        {
            let place = resources.disk_path.as_ref().map_or_else(
                || "there".to_owned(),
                |path| format!("for {}", path.display()),
            );
            return Err(format!(
                "the outputs need about {} of disk but {} is free {place}; {}, or \
                 --no-resource-check to try anyway",
                bytes(self.disk_bytes),
                bytes(disk),
                fixes.no_space
            ));
        }
        Ok(())
    }
}

/// What a command offers to write less: `flocking run`'s flags or `flocking sweep`'s.
struct Fixes {
    less_disk: &'static str,
    no_space: &'static str,
}

impl Fixes {
    const RUN: Self = Self {
        less_disk: "a larger record_every or --trajectory-format npy",
        no_space: "record less often (record_every), choose --trajectory-format npy or another --out",
    };
    const SWEEP: Self = Self {
        less_disk: "leaving out --keep-runs (a row of runs.csv is a few hundred bytes) or a larger \
                    record_every in the base scenario",
        no_space: "leave out --keep-runs, record less often (record_every in the base scenario) \
                   or choose another --out",
    };
}

/// One line: `estimate: 10000 steps, 501 records; memory 5.0 MB, disk 4.3 MB, about 0.3 s on one
/// thread (1.00e6 agent-steps)`, and the density of the start's net when it was counted.
impl fmt::Display for Estimate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "estimate: ")?;
        if self.runs > 1 {
            write!(f, "{} runs of ", self.runs)?;
        }
        write!(f, "{} steps, {} records; ", self.steps, self.records)?;
        if self.density == Density::TooDense {
            // the lattice's figures would understate both by orders of magnitude
            return write!(
                f,
                "disk {}, {:.2e} agent-steps; memory and time not estimated: the start's net is \
                 too dense to count",
                bytes(self.disk_bytes),
                self.agent_steps
            );
        }
        write!(
            f,
            "memory {}{}, disk {}, about {} on one thread ({:.2e} agent-steps)",
            bytes(self.memory_bytes),
            if self.runs > 1 { " per worker" } else { "" },
            bytes(self.disk_bytes),
            duration(self.seconds),
            self.agent_steps
        )?;
        match self.density {
            Density::Start(degree) => write!(f, "; start's net of mean degree {degree:.1}"),
            Density::Lattice | Density::TooDense => Ok(()),
        }
    }
}

/// `bytes` in B, kB, MB, GB or TB (powers of 10).
fn bytes(bytes: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB"];
    let mut value = bytes;
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < units.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{value:.0} B")
    } else {
        format!("{value:.1} {}", units[unit])
    }
}

/// `seconds` in s, min, h, days or years.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 60.0 => format!("{s:.1} s"),
        s if s < 3600.0 => format!("{:.1} min", s / 60.0),
        s if s < 86400.0 => format!("{:.1} h", s / 3600.0),
        s if s < 3.156e7 => format!("{:.1} days", s / 86400.0),
        s => format!("{:.1e} years", s / 3.156e7),
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn scenario(agents: usize, duration: f64) -> Scenario {
        let mut s: Scenario = "Scenario(dim: 2, agents: 10, algorithm: Algorithm1, \
             initial: (positions: Box(min: [0.0, 0.0], max: [100.0, 100.0])), duration: 1.0)"
            .parse()
            .unwrap();
        s.agents = agents;
        s.duration = duration;
        s
    }

    #[test]
    fn a_sweep_is_told_the_fixes_of_the_sweep_command() {
        // `flocking sweep --keep-runs` has no --trajectory-format: its warning must not name it
        let estimate = scenario(10_000_000, 1.0).estimate(&Outputs::RUN).times(3);
        let tight = Resources {
            memory_bytes: None,
            disk_bytes: Some(1e6),
            disk_path: Some("out/d".into()),
        };
        let run = [
            estimate.warnings().join("\n"),
            estimate.check(&tight).unwrap_err(),
        ];
        let sweep = [
            estimate.sweep_warnings().join("\n"),
            estimate.check_sweep(&tight).unwrap_err(),
        ];
        for text in run {
            assert!(text.contains("--trajectory-format npy"), "{text}");
        }
        for text in sweep {
            assert!(
                text.contains("gigabyte") || text.contains("of disk"),
                "{text}"
            );
            assert!(!text.contains("--trajectory-format"), "{text}");
            assert!(text.contains("--keep-runs"), "{text}");
        }
        // the place is named (issue 27)
        for text in [
            estimate.check(&tight).unwrap_err(),
            estimate.check_sweep(&tight).unwrap_err(),
        ] {
            assert!(text.contains("1.0 MB is free for out/d"), "{text}");
        }
    }

    #[test]
    fn ten_million_agents_need_gigabytes_and_are_refused_under_five() {
        let estimate = scenario(10_000_000, 1.0).estimate(&Outputs::RUN);
        assert_eq!(estimate.steps, 100);
        assert!(
            (5.1e9..5.2e9).contains(&estimate.memory_bytes),
            "{estimate}"
        );
        let small = Resources {
            memory_bytes: Some(5e9),
            disk_bytes: None,
            disk_path: None,
        };
        let error = estimate.check(&small).unwrap_err();
        assert!(
            error.contains("5.1 GB") && error.contains("5.0 GB"),
            "{error}"
        );
        assert!(estimate.check(&Resources::default()).is_ok());
        assert!(
            estimate.warnings().iter().any(|w| w.contains("gigabyte")),
            "{estimate}"
        );
    }

    #[test]
    fn a_long_run_is_warned_and_a_sweep_adds_up() {
        let estimate = scenario(1000, 1e6).estimate(&Outputs::NONE);
        assert_eq!(estimate.disk_bytes, 0.0);
        assert!(
            estimate.warnings()[0].contains("more than an hour"),
            "{estimate}"
        );
        let one = scenario(10, 1.0).estimate(&Outputs::RUN);
        let sweep = one.times(4);
        assert_eq!((sweep.runs, sweep.memory_bytes), (4, one.memory_bytes));
        assert_eq!(sweep.disk_bytes, 4.0 * one.disk_bytes);
        assert!(sweep.to_string().contains("4 runs of 100 steps"), "{sweep}");
    }

    #[test]
    fn conditions_add_their_bytes_per_agent() {
        let ideal = scenario(1_000_000, 1.0);
        let mut delayed = ideal.clone();
        delayed.conditions.communication = Some(conditions::Communication {
            delay: 0.1,
            ..conditions::Communication::default()
        });
        let extra = delayed.estimate(&Outputs::NONE).memory_bytes
            - ideal.estimate(&Outputs::NONE).memory_bytes;
        // 11 states of the delay line, the newest the measured state, 32 B each in 2D, the input
        // (delivered in place), 16 B, and a flag
        assert_eq!(
            conditions::bytes_per_agent(&delayed.conditions, 2, delayed.step),
            369
        );
        // and the 11 slots' own bytes
        assert!((extra - 369e6 - 11.0 * SLOT_BYTES).abs() < 1.0, "{extra}");
    }

    #[test]
    fn a_delay_line_too_large_is_named_as_the_fix() {
        // 100 agents with a delay of 10⁶ s at h = 0.01: 10⁸ + 1 states of 32 B each, 320 GB
        let mut delayed = scenario(100, 1.0);
        delayed.conditions.communication = Some(conditions::Communication {
            delay: 1e6,
            ..conditions::Communication::default()
        });
        let estimate = delayed.estimate(&Outputs::NONE);
        // 10⁸ + 1 slots of 100 agents' states, 32 B each, and of their own 80 B
        let line = (100.0 * 32.0 + SLOT_BYTES) * (1e8 + 1.0);
        assert!(
            (estimate.delay_line_bytes - line).abs() < 1.0,
            "{}",
            estimate.delay_line_bytes
        );
        // a run that keeps checkpoints copies it and writes it as text
        let checkpointed = delayed.estimate(&Outputs::RUN).delay_line_bytes;
        assert!((checkpointed - 4.5 * line).abs() < 1.0, "{checkpointed}");
        let room = |memory_bytes| Resources {
            memory_bytes: Some(memory_bytes),
            ..Resources::default()
        };
        let error = estimate.check(&room(1e9)).unwrap_err();
        assert!(
            error.contains("328.0 GB of it the delay line of conditions.communication.delay")
                && error.contains("a shorter delay")
                && !error.contains("bytes per agent"),
            "{error}"
        );
        // agents, not the delay line, are the fix of a large run with a short delay
        let mut many = scenario(10_000_000, 1.0);
        many.conditions = delayed.conditions.clone();
        many.conditions.communication.as_mut().unwrap().delay = 0.1;
        let many = many.estimate(&Outputs::NONE);
        assert!(many.delay_line_bytes > 0.0 && many.delay_line_bytes < 0.5 * many.memory_bytes);
        let error = many.check(&room(1e9)).unwrap_err();
        assert!(
            error.contains("use fewer agents") && !error.contains("delay line"),
            "{error}"
        );
    }

    /// `agents` of Algorithm 1 (r = 8.4) drawn uniformly in a square of side `side`.
    fn crowd(agents: usize, side: f64) -> Scenario {
        let mut s = scenario(agents, 1.0);
        s.initial.positions = crate::scenario::Cloud::Box {
            min: vec![0.0, 0.0],
            max: vec![side, side],
        };
        s
    }

    #[test]
    fn a_dense_start_scales_memory_and_time_by_its_mean_degree() {
        // 10⁴ agents in 100 × 100: π r² ρ = 221.7 neighbours inside, fewer near the sides
        let dense = crowd(10_000, 100.0);
        let lattice = dense.estimate(&Outputs::NONE);
        let start = dense.estimate_counted_within(&Outputs::NONE, None);
        let Density::Start(degree) = start.density else {
            panic!("{start}");
        };
        let inside = std::f64::consts::PI * 8.4 * 8.4;
        assert!((0.85 * inside..inside).contains(&degree), "{degree}");
        // the edges above the lattice's 3 per agent, at BYTES_PER_EDGE each
        let extra = 10_000.0 * (degree - 6.0) / 2.0 * BYTES_PER_EDGE[0];
        assert_relative_eq!(
            start.memory_bytes - lattice.memory_bytes,
            extra,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            start.seconds / lattice.seconds,
            degree / 6.0,
            max_relative = 1e-12
        );
        assert!(
            start.to_string().contains("start's net of mean degree"),
            "{start}"
        );
        // a machine with room for the lattice estimate and not for the crowd refuses it
        let room = Resources {
            memory_bytes: Some(lattice.memory_bytes * 2.0),
            disk_bytes: None,
            disk_path: None,
        };
        assert!(lattice.check(&room).is_ok());
        assert!(start.memory_bytes > lattice.memory_bytes * 2.0, "{start}");
        assert!(start.check(&room).unwrap_err().contains("of memory but"));
    }

    #[test]
    fn a_sparse_start_keeps_the_lattice_estimate() {
        // 10⁴ agents in 10⁴ × 10⁴: 0.022 neighbours each, the lattice's 6 assumed
        let sparse = crowd(10_000, 10_000.0);
        let start = sparse.estimate_counted_within(&Outputs::NONE, None);
        assert!(
            matches!(start.density, Density::Start(k) if (0.01..0.03).contains(&k)),
            "{start}"
        );
        let lattice = sparse.estimate(&Outputs::NONE);
        assert_eq!(
            (start.memory_bytes, start.seconds),
            (lattice.memory_bytes, lattice.seconds)
        );
        // not counted when the estimate without the count does not fit
        let unaffordable = sparse.estimate_counted_within(&Outputs::NONE, Some(1e6));
        assert_eq!(unaffordable, lattice);
    }

    #[test]
    fn a_start_too_dense_to_count_is_refused_before_testing() {
        // 70,000 agents in one cell of the grid: 70,000² = 4.9·10⁹ candidate pairs > 2³²
        let estimate = crowd(70_000, 1.0).estimate_counted_within(&Outputs::NONE, None);
        assert_eq!(estimate.density, Density::TooDense);
        let error = estimate.check(&Resources::default()).unwrap_err();
        assert!(
            error.contains("too dense to estimate") && error.contains("fewer agents"),
            "{error}"
        );
        assert!(
            estimate
                .to_string()
                .ends_with("memory and time not estimated: the start's net is too dense to count"),
            "{estimate}"
        );
    }
}
