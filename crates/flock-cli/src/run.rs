//! Running a scenario: build the protocol for the scenario's dimension, integrate, and hand every
//! recorded step to a recorder.

use std::time::{Duration, Instant};

use flock_graph::Components;
use flock_graph::Graph;
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

/// Receives the recorded instants of a run.
pub trait Recorder {
    /// Why recording failed.
    type Error;
    /// Records one instant.
    ///
    /// # Errors
    /// When the record cannot be kept; the run stops with this error.
    fn record<V: Vector>(&mut self, record: &Record<'_, V>) -> Result<(), Self::Error>;
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
}

impl<E: std::fmt::Display> std::fmt::Display for RunError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Record(e) => write!(f, "{e}"),
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
    scenario.validate().map_err(RunError::Scenario)?;
    match scenario.dim {
        2 => run::<glam::DVec2, R>(scenario, recorder),
        _ => run::<glam::DVec3, R>(scenario, recorder),
    }
}

/// Runs a scenario with vectors `V` (of the scenario's dimension).
///
/// # Errors
/// An obstacle or graph the scenario describes cannot be built (it is invalid), or the recorder's
/// first error.
pub fn run<V: Space, R: Recorder>(
    scenario: &Scenario,
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
        Algorithm::Algorithm1 => drive::<V, _, _>(scenario, Algorithm1 { alpha }, recorder),
        Algorithm::Algorithm2 { gamma, c1, c2 } => {
            let navigation = NavigationalFeedback::linear(gamma_agent::<V>(gamma), *c1, *c2);
            drive(scenario, Algorithm2 { alpha, navigation }, recorder)
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
                None => drive(scenario, flocking, recorder),
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
            drive::<V, _, _>(scenario, law, recorder)
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
    let mut sim = Simulation::new(
        protocol,
        integrator,
        initial_swarm::<V>(scenario),
        scenario.step,
    );
    let measure = |sim: &Simulation<V, P>| {
        let (metrics, energy) = measure(sim, &metric_params);
        (
            metrics,
            energy,
            sim.protocol().values(sim.time(), sim.swarm()),
        )
    };
    let (metrics, initial_energy, extra) = measure(&sim);
    recorder
        .record(&Record {
            t: 0.0,
            metrics,
            energy: initial_energy,
            swarm: sim.swarm(),
            extra: &extra,
        })
        .map_err(RunError::Record)?;
    let total = scenario.steps();
    let start = Instant::now();
    while sim.steps() < total {
        sim.step();
        if sim.steps() % scenario.record_every == 0 || sim.steps() == total {
            let (metrics, energy, extra) = measure(&sim);
            recorder
                .record(&Record {
                    t: sim.time(),
                    metrics,
                    energy,
                    swarm: sim.swarm(),
                    extra: &extra,
                })
                .map_err(RunError::Record)?;
        }
    }
    let elapsed = start.elapsed();
    let (metrics, final_energy, extra) = measure(&sim);
    let components = Components::of(sim.net().graph());
    Ok(RunSummary {
        agents: scenario.agents,
        dim: scenario.dim,
        steps: sim.steps(),
        t: sim.time(),
        metrics,
        component_velocity_mismatch: component_velocity_mismatch(
            &sim.swarm().velocities,
            &components,
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
    let swarm = sim.swarm();
    let metrics = FlockMetrics::measure(&swarm.positions, &swarm.velocities, sim.net(), params);
    (metrics, sim.energy())
}
