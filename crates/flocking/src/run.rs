//! Running a scenario: integrate its [`DynSimulation`] and hand every recorded step to a
//! [`Recorder`] ([`run`], [`resume`]).

use std::time::{Duration, Instant};

use flock_graph::Graph;
use flock_metrics::{FlockMetrics, FlockingCriteria, LatticeSummary};
use flock_sim::Observation;

use crate::error::ScenarioError;
use crate::health::NumericalError;
use crate::merging::{
    DenseStart, MERGE_FRACTION, Merge, MergeCause, MergedAgents, closest_pair, merged_agents,
};
use crate::scenario::Scenario;
use crate::simulation::{DynSimulation, MapBoth, MapProtocol, ScenarioProtocol, State};
use crate::verdict::{Verdict, VerdictKind};
// where they lived before: `flocking::run::Start`, `flocking::run::time_text`
pub use crate::simulation::Start;
pub use crate::time::time_text;

/// One recorded instant.
#[derive(Debug)]
pub struct Record<'a> {
    /// The time t.
    pub t: f64,
    /// The steps taken.
    pub steps: u64,
    /// The flocking metrics at t.
    pub metrics: FlockMetrics,
    /// The protocol's energy H at t.
    pub energy: f64,
    /// The state at t, agents in original order.
    pub state: State<'a>,
    /// The protocol's own diagnostics at t, each with its column name (the same names at every
    /// record of a run).
    pub diagnostics: &'a [(&'static str, f64)],
}

/// What a finished run reports.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSummary {
    /// The number of agents.
    pub agents: usize,
    /// The dimension.
    pub dim: usize,
    /// The number of steps taken.
    pub steps: u64,
    /// The final time.
    pub t: f64,
    /// The metrics at the final time.
    pub metrics: FlockMetrics,
    /// The velocity mismatch of each agent against its own component's mean velocity, per agent
    /// (0 when every component moves rigidly).
    pub component_velocity_mismatch: f64,
    /// H at t = 0.
    pub initial_energy: f64,
    /// H at the final time.
    pub final_energy: f64,
    /// The protocol's own diagnostics at the final time, named.
    pub diagnostics: Vec<(&'static str, f64)>,
    /// The lattice of the final state (edges near d, triangles, TAC 2006 Theorem 5's bound).
    pub lattice: LatticeSummary,
    /// (t, metrics) of every record this run made (after its start, when resumed).
    pub history: Vec<(f64, FlockMetrics)>,
    /// The first pair of agents found merged at a record of this run (after its start, when
    /// resumed), if any.
    pub first_merge: Option<Merge>,
    /// The merged agents of the final state.
    pub merged: MergedAgents,
    /// The time of the first record of this run (after its start, when resumed) from which the
    /// edge set of the proximity net ([`DynSimulation::graph`], agents in original order) stays
    /// the same at every later record through the end; the final time when the last record's
    /// edge set differs from the one before (the topology is still changing). ACC 2004 § 5: "The
    /// topology of the flock is asymptotically invariant."
    pub topology_invariant_from: f64,
    /// Wall-clock time of the integration.
    pub elapsed: Duration,
    /// The verdict the scenario's model gets ([`VerdictKind::of`]).
    pub verdict_kind: VerdictKind,
}

impl RunSummary {
    /// The model's verdict judged on [`RunSummary::history`] (`None` when its window holds no
    /// record): TAC 2006 Definition 5 (an α-flock, a strict one) for Olfati-Saber's and Tanner's
    /// protocols, the order states of the classic models ([`Verdict`]).
    #[must_use]
    pub fn verdict(&self, criteria: &FlockingCriteria) -> Option<Verdict> {
        Verdict::judge(self.verdict_kind, &self.history, criteria)
    }
}

/// Receives the recorded instants of a run, and may keep checkpoints of it or stop it.
pub trait Recorder {
    /// Why recording failed.
    type Error;
    /// Records one instant.
    ///
    /// # Errors
    /// When the record cannot be kept; the run stops with this error.
    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error>;

    /// Whether the run should keep a checkpoint after `steps` steps (never, by default).
    fn wants_checkpoint(&self, _steps: u64) -> bool {
        false
    }

    /// Keeps `start`, the state after its steps, so that the run can be resumed from it.
    ///
    /// # Errors
    /// When the checkpoint cannot be kept; the run stops with this error.
    fn checkpoint(&mut self, _start: &Start) -> Result<(), Self::Error> {
        Ok(())
    }

    /// Whether the run should stop (after keeping a checkpoint); asked after every step. A run
    /// also stops when the process's interrupt is requested ([`crate::interrupt`]).
    fn stop_requested(&self) -> bool {
        false
    }

    /// Told at the record where two agents are first found merged (ignored by default).
    fn merged(&mut self, _merge: &Merge) {}
}

/// Keeps nothing: for runs whose summary is all that matters.
impl Recorder for () {
    type Error = std::convert::Infallible;

    fn record(&mut self, _record: &Record<'_>) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// Why a run stopped.
#[derive(Debug)]
pub enum RunError<E> {
    /// The scenario is invalid.
    Scenario(ScenarioError),
    /// The recorder failed.
    Record(E),
    /// The state blew up (NaN, ∞ or a runaway speed); nothing from that step was recorded.
    Numerical(NumericalError),
    /// An interrupt ([`crate::interrupt`], Ctrl-C) or the recorder stopped the run: after the
    /// steps taken, whose state was checkpointed; or, `torn`, inside a step that had changed the
    /// state ([`DynSimulation::is_torn`]), of which nothing was recorded nor checkpointed (a
    /// resume continues from the last checkpoint kept before).
    Interrupted {
        /// The steps taken (the last whole state).
        steps: u64,
        /// The time reached.
        t: f64,
        /// The step h, which fixes how many decimals of t are printed.
        step: f64,
        /// Whether the interrupt cut the next step mid-way, after it had changed the state.
        torn: bool,
    },
}

impl<E: std::fmt::Display> std::fmt::Display for RunError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Record(e) => write!(f, "{e}"),
            Self::Numerical(e) => write!(f, "{e}"),
            Self::Interrupted {
                steps,
                t,
                step,
                torn: false,
            } => write!(
                f,
                "interrupted after step {steps} (t = {})",
                time_text(*t, *step)
            ),
            Self::Interrupted { steps, .. } => write!(
                f,
                "interrupted during step {}, cut short mid-way (nothing of that step is kept; a resume continues from the last checkpoint)",
                steps + 1
            ),
        }
    }
}

impl<E: std::error::Error> std::error::Error for RunError<E> {}

impl<E> From<ScenarioError> for RunError<E> {
    fn from(e: ScenarioError) -> Self {
        Self::Scenario(e)
    }
}

/// Validates a scenario and runs it, recording t = 0, every `record_every` steps and the final
/// step.
///
/// # Example
/// ```
/// # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))?; // the workspace root
/// let mut scenario = flocking::Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
/// scenario.duration = 5.0;
/// let summary = flocking::run(&scenario, &mut ())?;
/// assert_eq!(summary.steps, 500);
/// assert!(summary.final_energy < summary.initial_energy); // TAC 2006 Theorem 3
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// An invalid scenario, a numerical blow-up, an interruption, or the recorder's first error.
pub fn run<R: Recorder + ?Sized>(
    scenario: &Scenario,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    resume(scenario, None, recorder)
}

/// Runs a scenario as [`run`] does, or continues it from `start` (a checkpoint of the same
/// scenario): the records after `start` are then bit-identical to those of the uninterrupted
/// run, and t = 0 is not recorded again.
///
/// # Errors
/// An invalid scenario, a `start` of another size, a numerical blow-up, an interruption, or the
/// recorder's first error.
pub fn resume<R: Recorder + ?Sized>(
    scenario: &Scenario,
    start: Option<&Start>,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    resume_with(scenario, start, recorder, &ScenarioProtocol)
}

/// [`resume`] simulating the protocol `map` makes of the scenario's
/// ([`DynSimulation::new_with`]); a run continued from `start` needs the same `map` for its
/// records to be those of the uninterrupted run.
///
/// # Errors
/// As [`resume`].
pub fn resume_with<R: Recorder + ?Sized, M: MapProtocol>(
    scenario: &Scenario,
    start: Option<&Start>,
    recorder: &mut R,
    map: &M,
) -> Result<RunSummary, RunError<R::Error>> {
    resume_mapped(scenario, start, recorder, map)
}

/// [`resume_with`] with the map as a trait object (the simulation built once for every map).
pub(crate) fn resume_mapped<R: Recorder + ?Sized>(
    scenario: &Scenario,
    start: Option<&Start>,
    recorder: &mut R,
    map: &dyn MapBoth,
) -> Result<RunSummary, RunError<R::Error>> {
    let sim = DynSimulation::build_mapped(scenario, start, map)?;
    run_from(sim, start.map(|start| start.initial_energy), recorder)
}

/// Runs `sim` to the end of its scenario as [`resume_with`] does, the simulation built first
/// ([`DynSimulation::build_with`]) so that a state it refuses is refused before the recorder is
/// told anything (a resumed run directory is reopened only then,
/// [`InterruptedRun::reopen`](crate::run_dir::InterruptedRun::reopen)). `initial_energy` is
/// H(0) of a run continued from a checkpoint; `None` for a simulation at its start, which is
/// checked and recorded at t = 0 first.
///
/// # Errors
/// As [`resume`], but for an invalid scenario.
pub fn run_from<R: Recorder + ?Sized>(
    mut sim: DynSimulation,
    initial_energy: Option<f64>,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    let mut history = Vec::new();
    let mut first_merge = None;
    let mut topology = EdgeSetWatch::default();
    let initial_energy = match initial_energy {
        Some(energy) => energy,
        None => {
            sim.check_health().map_err(RunError::Numerical)?;
            let observation = record(recorder, &sim, &mut first_merge)?;
            history.push((sim.time(), observation.metrics));
            topology.see(&sim);
            observation.energy
        }
    };
    let (total, record_every, h) = {
        let scenario = sim.scenario();
        (scenario.steps(), scenario.record_every, scenario.step)
    };
    let clock = Instant::now();
    // The final step is always recorded: its measurements are the summary's.
    let mut last = None;
    while sim.steps() < total {
        let before = sim.steps();
        sim.step();
        let steps = sim.steps();
        let interrupted = |torn| RunError::Interrupted {
            steps: before,
            t: before as f64 * h,
            step: h,
            torn,
        };
        if sim.is_torn() {
            // the state is between two steps: neither recorded nor checkpointed
            return Err(interrupted(true));
        }
        // an interrupt that cut the step short before it changed the state: not taken
        let taken = steps > before;
        if taken {
            sim.check_health().map_err(RunError::Numerical)?;
            if steps.is_multiple_of(record_every) || steps == total {
                let observation = record(recorder, &sim, &mut first_merge)?;
                history.push((sim.time(), observation.metrics));
                topology.see(&sim);
                last = Some(observation);
            }
        }
        let stop = !taken
            || (steps < total && (crate::interrupt::requested() || recorder.stop_requested()));
        if stop || (steps < total && recorder.wants_checkpoint(steps)) {
            recorder
                .checkpoint(&sim.start(initial_energy))
                .map_err(RunError::Record)?;
        }
        if stop {
            return Err(RunError::Interrupted {
                steps,
                t: sim.time(),
                step: h,
                torn: false,
            });
        }
    }
    let elapsed = clock.elapsed();
    let last = last.unwrap_or_else(|| sim.observe());
    Ok(RunSummary {
        agents: sim.agents(),
        dim: sim.dim(),
        steps: sim.steps(),
        t: sim.time(),
        metrics: last.metrics,
        component_velocity_mismatch: sim.component_velocity_mismatch(),
        initial_energy,
        final_energy: last.energy,
        diagnostics: last.diagnostics,
        lattice: sim.lattice(),
        history,
        first_merge,
        merged: merged_agents(&sim.state(), merge_tolerance(sim.scenario())),
        topology_invariant_from: topology.since.unwrap_or_else(|| sim.time()),
        elapsed,
        verdict_kind: VerdictKind::of(&sim.scenario().algorithm),
    })
}

/// The edge set of the proximity net at the last record seen, and the time of the record that
/// set it (when it last changed): O(edges) memory, whatever the number of records.
#[derive(Default)]
struct EdgeSetWatch {
    /// The net of the last record, agents in original order.
    previous: Option<Graph>,
    /// The time of the first record with the edge set of `previous`.
    since: Option<f64>,
}

impl EdgeSetWatch {
    /// Compares the net of `sim`'s current state with that of the last record seen.
    fn see(&mut self, sim: &DynSimulation) {
        let graph = sim.graph();
        // a graph's neighbour lists are sorted, so equal edge sets are equal graphs
        if self.previous.as_ref() != Some(&*graph) {
            self.previous = Some(graph.into_owned());
            self.since = Some(sim.time());
        }
    }
}

/// The distance below which two agents of `scenario` count as merged: 10⁻³ d, where the α-force
/// can no longer separate them; 0 (never) for the classic models, whose particles may overlap
/// (Vicsek's, Cucker–Smale's) or have no α-force (boids, Couzin).
fn merge_tolerance(scenario: &Scenario) -> f64 {
    if scenario.algorithm.is_classic_model() {
        0.0
    } else {
        MERGE_FRACTION * scenario.alpha.d
    }
}

/// Records the state of `sim` and returns what it measured; tells the recorder of the first
/// merged pair (kept in `first_merge`).
fn record<R: Recorder + ?Sized>(
    recorder: &mut R,
    sim: &DynSimulation,
    first_merge: &mut Option<Merge>,
) -> Result<Observation, RunError<R::Error>> {
    let observation = sim.observe();
    recorder
        .record(&Record {
            t: sim.time(),
            steps: sim.steps(),
            metrics: observation.metrics,
            energy: observation.energy,
            state: sim.state(),
            diagnostics: &observation.diagnostics,
        })
        .map_err(RunError::Record)?;
    let tolerance = merge_tolerance(sim.scenario());
    if first_merge.is_none()
        && observation.metrics.min_distance < tolerance
        && let Some((pair, distance)) = closest_pair(&sim.state(), tolerance)
    {
        let merge = Merge {
            t: sim.time(),
            step: sim.scenario().step,
            pair,
            distance,
            tolerance,
            cause: if sim.steps() == 0 {
                MergeCause::Start(DenseStart::of(sim.scenario()))
            } else {
                MergeCause::Driven
            },
        };
        recorder.merged(&merge);
        *first_merge = Some(merge);
    }
    Ok(observation)
}

#[cfg(test)]
mod tests {
    use super::time_text;

    #[test]
    fn times_are_printed_to_the_decimals_of_the_step() {
        // 6 steps of 0.1 make 0.6000000000000001 in f64
        let t = 6.0 * 0.1;
        assert_eq!(t.to_string(), "0.6000000000000001");
        assert_eq!(time_text(t, 0.1), "0.6");
        assert_eq!(time_text(60.0 * 0.01, 0.01), "0.6");
        assert_eq!(time_text(25.0 * 0.025, 0.025), "0.625");
        assert_eq!(time_text(3.0, 0.5), "3");
        assert_eq!(time_text(123.0 * 1e-4, 1e-4), "0.0123");
        // a step with no short decimal form keeps 12 decimals
        assert_eq!(time_text(1.0 / 3.0, 1.0 / 3.0), "0.333333333333");
    }
}
