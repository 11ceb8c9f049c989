//! Running a scenario: build the protocol for the scenario's dimension, integrate, and hand every
//! recorded step to a recorder.

use std::time::{Duration, Instant};

use flock_graph::Graph;
use flock_graph::{Components, Numbering};
use flock_math::Vector;
use flock_math::{Bump, TannerPotential};
use flock_metrics::{FlockMetrics, MetricParams, component_velocity_mismatch};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::{
    Algorithm1, Algorithm2, Algorithm3, AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams,
    AlphaInteraction, AlphaParams, BallObstacle, BetaInteraction, BetaParams, Flocking2003,
    GammaAgent, Integrator, NavigationalFeedback, ObstacleFlocking2003, ObstacleParams, Path,
    Protocol, Simulation, Swarm, TannerJadbabaiePappas, random_connected_graph,
};

use crate::diagnostics::Diagnostics;
use crate::error::ScenarioError;
use crate::health::{Health, NumericalError};
use crate::initial::{initial_swarm, to_vector};
use crate::scenario::{
    Algorithm, Form2003, Gamma, IntegratorKind, Scenario, TannerGraph, critical_damping,
};

/// One recorded instant.
#[derive(Debug)]
pub struct Record<'a, V> {
    /// The time t.
    pub t: f64,
    /// The flocking metrics at t.
    pub metrics: FlockMetrics,
    /// The protocol's energy H at t.
    pub energy: f64,
    /// The state at t.
    pub swarm: &'a Swarm<V>,
    /// The protocol's own diagnostics at t, in the order of [`Scenario::extra_columns`].
    pub extra: &'a [f64],
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
    /// The protocol's own diagnostics at the final time, named as in [`Scenario::extra_columns`].
    pub extra: Vec<(&'static str, f64)>,
    /// Wall-clock time of the integration.
    pub elapsed: Duration,
}

/// The whole state of a run after some steps: what a checkpoint keeps so that the run can be
/// resumed bit-identically (a [`Simulation`] carries nothing else between steps).
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    /// The number of steps taken.
    pub steps: u64,
    /// H at t = 0 (for the run's summary).
    pub initial_energy: f64,
    /// The positions, `dim` coordinates per agent.
    pub positions: Vec<f64>,
    /// The velocities, `dim` coordinates per agent.
    pub velocities: Vec<f64>,
}

impl Start {
    /// The state of `swarm` after `steps` steps.
    #[must_use]
    pub fn of<V: Vector>(steps: u64, initial_energy: f64, swarm: &Swarm<V>) -> Self {
        let flat = |vs: &[V]| -> Vec<f64> {
            vs.iter()
                .flat_map(|v| (0..V::DIM).map(move |k| v.coord(k)))
                .collect()
        };
        Self {
            steps,
            initial_energy,
            positions: flat(&swarm.positions),
            velocities: flat(&swarm.velocities),
        }
    }

    /// The swarm of this state in vectors `V`.
    #[must_use]
    pub fn swarm<V: Vector>(&self) -> Swarm<V> {
        let vectors =
            |flat: &[f64]| -> Vec<V> { flat.chunks_exact(V::DIM).map(to_vector::<V>).collect() };
        Swarm::new(vectors(&self.positions), vectors(&self.velocities))
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
    fn record<V: Vector>(&mut self, record: &Record<'_, V>) -> Result<(), Self::Error>;

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

    /// Whether the run should stop (after keeping a checkpoint); asked after every step.
    fn stop_requested(&self) -> bool {
        false
    }
}

/// Keeps nothing: for runs whose summary is all that matters.
impl Recorder for () {
    type Error = std::convert::Infallible;
    fn record<V: Vector>(&mut self, _record: &Record<'_, V>) -> Result<(), Self::Error> {
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
    /// The recorder asked the run to stop (Ctrl-C); a checkpoint of the state was kept.
    Interrupted {
        /// The steps taken.
        steps: u64,
        /// The time reached.
        t: f64,
    },
}

impl<E: std::fmt::Display> std::fmt::Display for RunError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Record(e) => write!(f, "{e}"),
            Self::Numerical(e) => write!(f, "{e}"),
            Self::Interrupted { steps, t } => {
                write!(f, "interrupted after step {steps} (t = {t})")
            }
        }
    }
}

impl<E: std::error::Error> std::error::Error for RunError<E> {}

/// Validates a scenario and runs it in its dimension (the one dispatch from `dim` to a vector
/// type), recording t = 0, every `record_every` steps and the final step.
///
/// # Errors
/// An invalid scenario, or the recorder's first error.
pub fn run_scenario<R: Recorder>(
    scenario: &Scenario,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    resume_scenario(scenario, None, recorder)
}

/// Runs a scenario as [`run_scenario`] does, or continues it from `start` (a checkpoint of the
/// same scenario): the records after `start` are then bit-identical to those of the
/// uninterrupted run, and t = 0 is not recorded again.
///
/// # Errors
/// An invalid scenario, a `start` of another size, a numerical blow-up, an interruption, or the
/// recorder's first error.
pub fn resume_scenario<R: Recorder>(
    scenario: &Scenario,
    start: Option<&Start>,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    scenario.validate().map_err(RunError::Scenario)?;
    if let Some(start) = start {
        let size = scenario.agents * scenario.dim;
        if start.positions.len() != size || start.velocities.len() != size {
            return Err(RunError::Scenario(ScenarioError::invalid(
                "agents",
                scenario.agents,
                format!(
                    "the checkpoint holds {} coordinates where {} agents in {}D need {size}",
                    start.positions.len(),
                    scenario.agents,
                    scenario.dim
                ),
                "resume a checkpoint with the scenario.ron of its own run",
            )));
        }
    }
    match scenario.dim {
        2 => run::<glam::DVec2, R>(scenario, start, recorder),
        _ => run::<glam::DVec3, R>(scenario, start, recorder),
    }
}

/// Runs a scenario with vectors `V` (of the scenario's dimension), from t = 0 or from `start`.
///
/// # Errors
/// An obstacle or graph the scenario describes cannot be built (it is invalid), a numerical
/// blow-up, an interruption, or the recorder's first error.
pub fn run<V: Space, R: Recorder>(
    scenario: &Scenario,
    start: Option<&Start>,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    let a = &scenario.alpha;
    let (d, r) = (a.d, scenario.range());
    let params = AlphaParams {
        d,
        r,
        epsilon: a.epsilon,
        a: a.a,
        b: a.b,
        h: a.h,
    };
    let alpha = AlphaInteraction::new(params, a.c1, a.c2);
    let invalid = |field: &str, why: String| {
        RunError::Scenario(ScenarioError::invalid(
            field,
            "",
            why,
            "run `flock validate` on the scenario",
        ))
    };
    match &scenario.algorithm {
        Algorithm::Algorithm1 => drive::<V, _, _>(scenario, start, Algorithm1 { alpha }, recorder),
        Algorithm::Algorithm2 { gamma, c1, c2 } => {
            let navigation = NavigationalFeedback::linear(gamma_agent::<V>(gamma), *c1, *c2);
            drive(scenario, start, Algorithm2 { alpha, navigation }, recorder)
        }
        Algorithm::Algorithm3 {
            gamma,
            c1,
            c2,
            beta,
        } => {
            let c2 = c2.unwrap_or(critical_damping(*c1));
            let navigation = NavigationalFeedback::bounded(gamma_agent::<V>(gamma), *c1, c2);
            let field = ObstacleField::<V>::from_specs(&scenario.obstacles)
                .map_err(|e| invalid(&e.field(), e.to_string()))?;
            let beta_params = BetaParams {
                d: beta.distance(d),
                r: beta.range(d),
                h: beta.h,
            };
            let beta = BetaInteraction::new(field, beta_params, a.epsilon, beta.c1, beta.damping());
            drive(
                scenario,
                start,
                Algorithm3 {
                    flock: Algorithm2 { alpha, navigation },
                    beta,
                },
                recorder,
            )
        }
        Algorithm::Flocking2003 {
            form,
            c1,
            delta,
            power,
            translation,
            avoidance,
        } => {
            let params = AlphaAlphaParams {
                bump: Bump::influence_map(delta.unwrap_or(d / r), *power),
                ..AlphaAlphaParams::new(d, r, a.a, a.b)
            };
            let form = match form {
                Form2003::Nonsmooth => AlphaAlphaForm::Nonsmooth,
                Form2003::Smooth => AlphaAlphaForm::Smooth,
                Form2003::Approximate => AlphaAlphaForm::Approximate,
            };
            let translation = translation
                .as_ref()
                .map(|t| NavigationalFeedback::linear(gamma_agent::<V>(&t.gamma), t.c1, t.c2));
            let flocking = Flocking2003 {
                alpha: AlphaAlpha::new(params, form, *c1),
                translation,
            };
            match avoidance {
                None => drive(scenario, start, flocking, recorder),
                Some(avoid) => {
                    let obstacles = scenario
                        .obstacles
                        .iter()
                        .enumerate()
                        .map(|(k, spec)| match spec {
                            ObstacleSpec::Ball { centre, radius } => {
                                BallObstacle::new(to_vector(centre), *radius).map_err(|e| {
                                    invalid(&e.clone().at(k).field(), e.at(k).to_string())
                                })
                            }
                            other => Err(invalid(
                                &format!("obstacles[{k}]"),
                                format!("{} is not a ball", other.kind()),
                            )),
                        })
                        .collect::<Result<Vec<_>, _>>()?;
                    let params = ObstacleParams {
                        c3: avoid.c3,
                        c4: avoid.c4,
                        lambda_d: avoid.lambda_d,
                        ..ObstacleParams::for_alpha(&params)
                    };
                    drive(
                        scenario,
                        start,
                        ObstacleFlocking2003 {
                            flocking,
                            obstacles,
                            params,
                        },
                        recorder,
                    )
                }
            }
        }
        Algorithm::Tanner { graph } => {
            let graph = match graph {
                TannerGraph::Random { extra } => {
                    random_connected_graph(scenario.agents, *extra, scenario.seed)
                }
                TannerGraph::Edges(edges) => Graph::from_edges(scenario.agents, edges)
                    .map_err(|e| invalid("algorithm.graph", e.to_string()))?,
            };
            let law = TannerJadbabaiePappas::new(graph, TannerPotential::new(d), r)
                .map_err(|e| invalid("algorithm.graph", e.to_string()))?;
            drive::<V, _, _>(scenario, start, law, recorder)
        }
    }
}

/// The γ-agent of a validated scenario.
pub(crate) fn gamma_agent<V: Vector>(gamma: &Gamma) -> GammaAgent<V> {
    match gamma {
        Gamma::Static { position } => GammaAgent::Static {
            position: to_vector(position),
        },
        Gamma::ConstantVelocity { position, velocity } => GammaAgent::ConstantVelocity {
            position: to_vector(position),
            velocity: to_vector(velocity),
        },
        Gamma::Path { waypoints, speed } => GammaAgent::Path(Path::new(
            waypoints.iter().map(|w| to_vector(w)).collect(),
            *speed,
        )),
    }
}

fn drive<V: Vector, P: Protocol<V> + Diagnostics<V>, R: Recorder>(
    scenario: &Scenario,
    start: Option<&Start>,
    protocol: P,
    recorder: &mut R,
) -> Result<RunSummary, RunError<R::Error>> {
    let integrator = match scenario.integrator {
        IntegratorKind::SymplecticEuler => Integrator::SymplecticEuler,
        IntegratorKind::Rk4 => Integrator::Rk4,
    };
    let metric_params = MetricParams {
        d: scenario.alpha.d,
        collision_distance: scenario.collision_distance(),
    };
    let measure = |sim: &Simulation<V, P>| {
        let (metrics, energy) = measure(sim, &metric_params);
        (
            metrics,
            energy,
            sim.protocol().values(sim.time(), sim.stored_swarm()),
        )
    };
    // Records the state and returns what it measured.
    let record = |recorder: &mut R, sim: &Simulation<V, P>| {
        let (metrics, energy, extra) = measure(sim);
        recorder
            .record(&Record {
                t: sim.time(),
                metrics,
                energy,
                swarm: &sim.swarm(),
                extra: &extra,
            })
            .map_err(RunError::Record)
            .map(|()| (metrics, energy, extra))
    };
    let (mut sim, initial_energy) = match start {
        None => {
            let swarm = initial_swarm::<V>(scenario);
            Health::check(scenario, 0, &swarm, &Numbering::identity())
                .map_err(RunError::Numerical)?;
            let sim = Simulation::new(protocol, integrator, swarm, scenario.step);
            let (_, energy, _) = record(recorder, &sim)?;
            (sim, energy)
        }
        Some(start) => (
            Simulation::resume(
                protocol,
                integrator,
                start.swarm(),
                scenario.step,
                start.steps,
            ),
            start.initial_energy,
        ),
    };
    let total = scenario.steps();
    let clock = Instant::now();
    // The final step is always recorded: its measurements are the summary's.
    let mut last = None;
    while sim.steps() < total {
        sim.step();
        Health::check(scenario, sim.steps(), sim.stored_swarm(), sim.numbering())
            .map_err(RunError::Numerical)?;
        let steps = sim.steps();
        if steps % scenario.record_every == 0 || steps == total {
            last = Some(record(recorder, &sim)?);
        }
        let stop = steps < total && recorder.stop_requested();
        if stop || (steps < total && recorder.wants_checkpoint(steps)) {
            let state = Start::of(steps, initial_energy, &sim.swarm());
            recorder.checkpoint(&state).map_err(RunError::Record)?;
        }
        if stop {
            return Err(RunError::Interrupted {
                steps,
                t: sim.time(),
            });
        }
    }
    let elapsed = clock.elapsed();
    let (metrics, final_energy, extra) = last.unwrap_or_else(|| measure(&sim));
    let components = Components::of(sim.net().graph());
    Ok(RunSummary {
        agents: scenario.agents,
        dim: scenario.dim,
        steps: sim.steps(),
        t: sim.time(),
        metrics,
        component_velocity_mismatch: component_velocity_mismatch(
            &sim.stored_swarm().velocities,
            &components,
            sim.numbering(),
        ),
        initial_energy,
        final_energy,
        extra: scenario
            .extra_columns()
            .iter()
            .copied()
            .zip(extra)
            .collect(),
        elapsed,
    })
}

/// The flocking metrics and the energy H of a simulation's current state: what every recorded
/// step costs on top of a plain step.
pub(crate) fn measure<V: Vector, P: Protocol<V>>(
    sim: &Simulation<V, P>,
    params: &MetricParams,
) -> (FlockMetrics, f64) {
    let swarm = sim.stored_swarm();
    // the energy's chunks fill the threads the metrics leave idle; each value as computed alone
    rayon::join(
        || FlockMetrics::measure(&swarm.positions, &swarm.velocities, sim.net(), params),
        || sim.energy(),
    )
}
