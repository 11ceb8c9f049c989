//! One run of a sweep reduced to a row of `runs.csv`.

use std::path::Path;
use std::time::Instant;

use flock_metrics::{Closest, FlockMetrics};
use serde_json::Value;

use flock_protocols::{GAMMA_POSITION_ERROR, GAMMA_VELOCITY_ERROR};

use super::{RunSpec, Sweep};
use crate::RunDirectory;
use crate::run::{Record, Recorder, RunError, RunSummary, Start, resume_mapped};
use crate::simulation::{MapBoth, MapProtocol, ScenarioProtocol};
use crate::verdict::Verdict;

/// What a finished run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// C, C*, R, Ẽ and K̃ at the final time, but `min_distance` the least distance between two
    /// agents at any record and `collisions` the most pairs closer than the collision distance at
    /// any record.
    pub metrics: FlockMetrics,
    /// The least distance and the most colliding pairs after the run has settled: over the
    /// records at t ≥ the sweep's `settle` × the duration (`None` without such a record).
    pub settled: Option<Closest>,
    /// The time after which the net stays connected (C = 1 at that record and every later one);
    /// `None` when it is not connected at the end.
    pub connected_from: Option<f64>,
    /// TAC 2006 Definition 5 over the last quarter: an α-flock, and a strict one (`None` for a
    /// run without records in its window, or of a model judged otherwise).
    pub alpha_flock: Option<(bool, bool)>,
    /// The model's verdict in a few words ([`Verdict::state`]): `strict α-flock`, `torus`,
    /// `polarised (ordered)`, … (`None` for a run without records in its window).
    pub verdict: Option<&'static str>,
    /// The γ-tracking errors ‖q̄ − q_r‖ and ‖p̄ − p_r‖ at the final record, for a protocol with a
    /// γ-agent (`None` otherwise).
    pub gamma_tracking: Option<(f64, f64)>,
    /// With obstacles: the least clearance of an agent to an obstacle and the most agents inside
    /// one, at any record.
    pub obstacles: Option<(f64, f64)>,
    /// The mean polarisation and milling over the records after the run has settled (t ≥ the
    /// sweep's `settle` × the duration): the time averages of the collective-motion literature
    /// (Vicsek et al. 1995's v_a, Couzin et al. 2002's p_group and m_group). `None` without such
    /// a record.
    pub settled_order: Option<(f64, f64)>,
    /// The mean over the same records of the fraction of agents in the largest group, C* (the
    /// largest connected component of the proximity net: for the velocity models, the agents
    /// linked by chains of neighbours within the interaction range); below 1 where the group has
    /// split (Couzin et al. 2002 count the runs whose group fragments). `None` without such a
    /// record.
    pub settled_largest_group: Option<f64>,
}

/// The columns of `runs.csv` of an [`Outcome`] (after the seed, before `error`), each with what a
/// figure calls it ([`metric_label`]).
const OUTCOME_COLUMNS: [(&str, &str); 23] = {
    let [c, giant, radius, deviation, mismatch, distance] = FlockMetrics::REAL_COLUMNS;
    [
        (c, "connectivity C"),
        (giant, "giant component C*"),
        (radius, "cohesion radius R"),
        (deviation, "deviation energy Ẽ"),
        (mismatch, "velocity mismatch K̃"),
        (distance, "least distance over the run"),
        ("collisions", "most colliding pairs over the run"),
        ("connected_from", "connected from t"),
        ("alpha_flock", "fraction α-flocking"),
        ("strict_alpha_flock", "fraction strictly α-flocking"),
        ("obstacle_clearance", "least obstacle clearance"),
        ("inside_obstacles", "most agents inside obstacles"),
        ("settled_min_distance", "least distance after settling"),
        ("settled_collisions", "most colliding pairs after settling"),
        ("polarisation", "polarisation (final)"),
        ("milling", "milling (final)"),
        ("nearest_neighbour_mean", "mean nearest-neighbour distance"),
        ("settled_polarisation", "polarisation, mean after settling"),
        ("settled_milling", "milling, mean after settling"),
        (
            "settled_largest_group",
            "fraction in the largest group, mean after settling",
        ),
        (GAMMA_POSITION_ERROR, "‖q̄ − q_r‖ (final)"),
        (GAMMA_VELOCITY_ERROR, "‖p̄ − p_r‖ (final)"),
        ("verdict", "the model's verdict"),
    ]
};

/// What a figure calls the `runs.csv` column `column` (`cohesion_radius` is "cohesion radius R",
/// `alpha_flock`, averaged, "fraction α-flocking"); an unknown column by its name.
///
/// # Example
/// ```
/// use flocking::sweep::metric_label;
///
/// assert_eq!(metric_label("cohesion_radius"), "cohesion radius R");
/// assert_eq!(metric_label("seed"), "seed");
/// ```
#[must_use]
pub fn metric_label(column: &str) -> &str {
    OUTCOME_COLUMNS
        .iter()
        .find(|(name, _)| *name == column)
        .map_or(column, |(_, label)| label)
}

impl Outcome {
    /// The outcome of a run's summary and its obstacle columns, the model's verdict judged with
    /// the sweep's criteria, settled from the sweep's `settle` × `duration` on.
    #[must_use]
    pub fn of(
        summary: &RunSummary,
        obstacles: Option<(f64, f64)>,
        sweep: &Sweep,
        duration: f64,
    ) -> Self {
        let history = &summary.history;
        let whole = Closest::over(history, f64::NEG_INFINITY).unwrap_or(Closest {
            min_distance: f64::INFINITY,
            collisions: 0,
        });
        let connected_from = match history.iter().rposition(|(_, m)| m.connectivity < 1.0) {
            None => history.first().map(|(t, _)| *t),
            Some(k) => history.get(k + 1).map(|(t, _)| *t),
        };
        let verdict = summary.verdict(&sweep.criteria());
        let final_value = |name: &str| {
            summary
                .diagnostics
                .iter()
                .find(|(n, _)| *n == name)
                .map(|&(_, v)| v)
        };
        let settled: Vec<&FlockMetrics> = history
            .iter()
            .filter(|(t, _)| *t >= sweep.settle * duration)
            .map(|(_, m)| m)
            .collect();
        let count = settled.len() as f64;
        let settled_order = (!settled.is_empty()).then(|| {
            let mean =
                |f: fn(&FlockMetrics) -> f64| settled.iter().map(|m| f(m)).sum::<f64>() / count;
            (mean(|m| m.polarisation), mean(|m| m.milling))
        });
        let settled_largest_group = (!settled.is_empty())
            .then(|| settled.iter().map(|m| m.giant_component).sum::<f64>() / count);
        Self {
            metrics: FlockMetrics {
                min_distance: whole.min_distance,
                collisions: whole.collisions,
                ..summary.metrics
            },
            settled: Closest::over(history, sweep.settle * duration),
            connected_from,
            alpha_flock: verdict.as_ref().and_then(Verdict::alpha_flock),
            verdict: verdict.as_ref().map(Verdict::state),
            gamma_tracking: final_value(GAMMA_POSITION_ERROR)
                .zip(final_value(GAMMA_VELOCITY_ERROR)),
            obstacles,
            settled_order,
            settled_largest_group,
        }
    }

    /// The fields of [`OUTCOME_COLUMNS`]: numbers as Rust prints them (shortest round trip),
    /// empty where the run has no value.
    fn fields(&self) -> [String; OUTCOME_COLUMNS.len()] {
        let [c, giant, radius, deviation, mismatch, distance] =
            self.metrics.reals().map(|x| x.to_string());
        let or_empty = |x: Option<String>| x.unwrap_or_default();
        [
            c,
            giant,
            radius,
            deviation,
            mismatch,
            distance,
            self.metrics.collisions.to_string(),
            or_empty(self.connected_from.map(|t| t.to_string())),
            or_empty(self.alpha_flock.map(|(a, _)| a.to_string())),
            or_empty(self.alpha_flock.map(|(_, s)| s.to_string())),
            or_empty(self.obstacles.map(|(c, _)| c.to_string())),
            or_empty(self.obstacles.map(|(_, i)| i.to_string())),
            or_empty(self.settled.map(|s| s.min_distance.to_string())),
            or_empty(self.settled.map(|s| s.collisions.to_string())),
            self.metrics.polarisation.to_string(),
            self.metrics.milling.to_string(),
            self.metrics.nearest_neighbour_mean.to_string(),
            or_empty(self.settled_order.map(|(p, _)| p.to_string())),
            or_empty(self.settled_order.map(|(_, m)| m.to_string())),
            or_empty(self.settled_largest_group.map(|g| g.to_string())),
            or_empty(self.gamma_tracking.map(|(q, _)| q.to_string())),
            or_empty(self.gamma_tracking.map(|(_, p)| p.to_string())),
            or_empty(self.verdict.map(str::to_owned)),
        ]
    }
}

/// A recorder that keeps the least `obstacle_clearance` and the most `inside_obstacles` of the
/// records it hands on to `inner`.
struct Obstacles<R> {
    inner: R,
    extremes: Option<(f64, f64)>,
}

impl<R: Recorder> Recorder for Obstacles<R> {
    type Error = R::Error;

    fn record(&mut self, record: &Record<'_>) -> Result<(), R::Error> {
        let value = |name: &str| {
            record
                .diagnostics
                .iter()
                .find(|(n, _)| *n == name)
                .map(|&(_, v)| v)
        };
        if let (Some(clearance), Some(inside)) =
            (value("obstacle_clearance"), value("inside_obstacles"))
        {
            let (least, most) = self.extremes.unwrap_or((f64::INFINITY, 0.0));
            self.extremes = Some((least.min(clearance), most.max(inside)));
        }
        self.inner.record(record)
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.inner.wants_checkpoint(steps)
    }

    fn checkpoint(&mut self, start: &Start) -> Result<(), R::Error> {
        self.inner.checkpoint(start)
    }

    fn stop_requested(&self) -> bool {
        self.inner.stop_requested()
    }
}

/// One row of `runs.csv`, and the run's wall time (kept in `times.csv`: a wall time is never the
/// same twice, and `runs.csv` must be).
#[derive(Clone, Debug, PartialEq)]
pub struct RunRow {
    /// The run's index in run order.
    pub index: usize,
    /// The run's id ([`RunSpec::id`]).
    pub id: String,
    /// Its axis values.
    pub values: Vec<Value>,
    /// Its seed.
    pub seed: u64,
    /// What it measured, or why it has no measures (an invalid value, a numerical blow-up).
    pub outcome: Result<Outcome, String>,
    /// Seconds of wall-clock time, from building the scenario to the last record.
    pub wall_time: f64,
    /// Whether the failure is not the run's but the machine's: its kept directory could not be
    /// written (a full disk, a user's file in it), or an interrupt stopped it. Such a row is
    /// never stored: the run is made again by the next invocation (issue 27).
    pub retry: bool,
}

/// An axis value as `runs.csv` writes it: a string as itself, anything else as JSON (`0.2`, `50`,
/// `20.0`).
#[must_use]
pub fn value_field(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// The column of `runs.csv` that holds each run's seed, after the axes' columns.
pub const SEED_COLUMN: &str = "seed";

/// The header of `runs.csv` for the sweep's axes.
#[must_use]
pub fn header(sweep: &Sweep) -> Vec<String> {
    let mut header = vec!["run".to_owned(), "id".to_owned()];
    header.extend(sweep.axes.iter().map(|a| a.path.clone()));
    header.push(SEED_COLUMN.to_owned());
    header.extend(OUTCOME_COLUMNS.map(|(name, _)| name.to_owned()));
    header.push("error".to_owned());
    header
}

impl RunRow {
    /// The row's fields, aligned with [`header`]: numbers as Rust prints them (shortest round
    /// trip), axis values as JSON, empty where a run has no value.
    #[must_use]
    pub fn fields(&self) -> Vec<String> {
        let mut fields = vec![self.index.to_string(), self.id.clone()];
        fields.extend(self.values.iter().map(value_field));
        fields.push(self.seed.to_string());
        match &self.outcome {
            Ok(outcome) => {
                fields.extend(outcome.fields());
                fields.push(String::new());
            }
            Err(error) => {
                fields.extend(std::iter::repeat_n(String::new(), OUTCOME_COLUMNS.len()));
                fields.push(error.clone());
            }
        }
        fields
    }
}

/// Runs `spec` of `sweep` on the current thread's rayon pool (the sweep's workers give each run a
/// pool of one thread) and reduces it to its row. With `keep`, the run's directory is written to
/// `keep/<id>` as `flocking run` writes it. Never fails: an invalid value or a numerical blow-up is
/// the row's error.
#[must_use]
pub fn run_one(sweep: &Sweep, spec: &RunSpec, keep: Option<&Path>) -> RunRow {
    run_one_mapped(sweep, spec, keep, &ScenarioProtocol)
}

/// [`run_one`] simulating the protocol `map` makes of each run's scenario
/// ([`resume_with`](crate::resume_with)).
#[must_use]
pub fn run_one_with<M: MapProtocol>(
    sweep: &Sweep,
    spec: &RunSpec,
    keep: Option<&Path>,
    map: &M,
) -> RunRow {
    run_one_mapped(sweep, spec, keep, map)
}

/// [`run_one_with`] with the map as a trait object (compiled once for every map).
fn run_one_mapped(sweep: &Sweep, spec: &RunSpec, keep: Option<&Path>, map: &dyn MapBoth) -> RunRow {
    let start = Instant::now();
    let id = spec.id(&sweep.axes);
    let mut retry = false;
    let outcome = sweep
        .scenario(spec)
        .map_err(|e| e.to_string())
        .and_then(|scenario| {
            let ran = match keep {
                None => {
                    let mut recorder = Obstacles {
                        inner: (),
                        extremes: None,
                    };
                    resume_mapped(&scenario, None, &mut recorder, map)
                        .map(|summary| (summary, recorder.extremes))
                        .map_err(|e| {
                            // stopped by an interrupt: not a result, made again next time
                            retry = matches!(e, RunError::Interrupted { .. });
                            e.to_string()
                        })
                }
                Some(dir) => keep_run(&scenario, &dir.join(&id), map).map_err(|(e, io)| {
                    retry = io;
                    e
                }),
            };
            ran.map(|(summary, obstacles)| {
                Outcome::of(&summary, obstacles, sweep, scenario.duration)
            })
        });
    RunRow {
        index: spec.index,
        id,
        values: spec.values.clone(),
        seed: spec.seed,
        outcome,
        wall_time: start.elapsed().as_secs_f64(),
        retry,
    }
}

/// A kept run's summary and obstacle extremes, or why it failed and whether that is the
/// machine's failure (to be retried) rather than the run's.
type Kept = Result<(RunSummary, Option<(f64, f64)>), (String, bool)>;

/// The run written to `dir` (replaced if present) as `flocking run --out dir` writes it. An
/// error says why, and whether it is the machine's (the directory could not be made, written
/// or finished: the run is to be made again) rather than the run's.
fn keep_run(scenario: &crate::Scenario, dir: &Path, map: &dyn MapBoth) -> Kept {
    let mut recorder = Obstacles {
        inner: RunDirectory::create(dir, scenario, true).map_err(|e| (e.to_string(), true))?,
        extremes: None,
    };
    match resume_mapped(scenario, None, &mut recorder, map) {
        Ok(summary) => {
            recorder.inner.finish().map_err(|e| {
                // the run is made again from its start: its partial directory (flocking's)
                // would only hold the room a full disk lacks
                let _ = crate::owned::remove(
                    &crate::run_dir::partial_path(dir),
                    crate::owned::Kind::Run,
                );
                (e.to_string(), true)
            })?;
            Ok((summary, recorder.extremes))
        }
        Err(error) => {
            recorder.inner.abandon();
            Err(match error {
                RunError::Record(e) => (format!("writing {}: {e}", dir.display()), true),
                // stopped by an interrupt: not a result, made again next time
                e @ RunError::Interrupted { .. } => (e.to_string(), true),
                other => (other.to_string(), false),
            })
        }
    }
}
