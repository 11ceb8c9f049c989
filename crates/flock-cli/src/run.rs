//! Running a scenario: build the protocol for the scenario's dimension, integrate, and hand every
//! recorded step to a recorder.

use std::time::{Duration, Instant};

use flock_graph::Components;
use flock_math::Vector;
use flock_metrics::{FlockMetrics, MetricParams, component_velocity_mismatch};
use flock_protocols::{
    Algorithm1, Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, Integrator,
    NavigationalFeedback, Path, Protocol, Simulation, Swarm,
};

use crate::diagnostics::Diagnostics;
use crate::initial::{initial_swarm, to_vector};
use crate::scenario::{Algorithm, Gamma, IntegratorKind, Scenario};

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

/// Runs a validated scenario in its dimension (the one dispatch from `dim` to a vector type),
/// recording t = 0, every `record_every` steps and the final step.
///
/// # Errors
/// The recorder's first error.
pub fn run_scenario<R: Recorder>(
    scenario: &Scenario,
    recorder: &mut R,
) -> Result<RunSummary, R::Error> {
    match scenario.dim {
        2 => run::<glam::DVec2, R>(scenario, recorder),
        _ => run::<glam::DVec3, R>(scenario, recorder),
    }
}

/// Runs a validated scenario with vectors `V` (of the scenario's dimension).
///
/// # Errors
/// The recorder's first error.
pub fn run<V: Vector, R: Recorder>(
    scenario: &Scenario,
    recorder: &mut R,
) -> Result<RunSummary, R::Error> {
    let a = &scenario.alpha;
    let params = AlphaParams {
        d: a.d,
        r: scenario.range(),
        epsilon: a.epsilon,
        a: a.a,
        b: a.b,
        h: a.h,
    };
    let alpha = AlphaInteraction::new(params, a.c1, a.c2);
    match &scenario.algorithm {
        Algorithm::Algorithm1 => drive::<V, _, _>(scenario, Algorithm1 { alpha }, recorder),
        Algorithm::Algorithm2 { gamma, c1, c2 } => {
            let navigation = NavigationalFeedback::linear(gamma_agent::<V>(gamma), *c1, *c2);
            drive(scenario, Algorithm2 { alpha, navigation }, recorder)
        }
    }
}

fn gamma_agent<V: Vector>(gamma: &Gamma) -> GammaAgent<V> {
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
) -> Result<RunSummary, R::Error> {
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
        let swarm = sim.swarm();
        let metrics = FlockMetrics::measure(
            &swarm.positions,
            &swarm.velocities,
            sim.net(),
            &metric_params,
        );
        let extra = sim.protocol().values(sim.time(), swarm);
        (metrics, sim.energy(), extra)
    };
    let (metrics, initial_energy, extra) = measure(&sim);
    recorder.record(&Record {
        t: 0.0,
        metrics,
        energy: initial_energy,
        swarm: sim.swarm(),
        extra: &extra,
    })?;
    let total = scenario.steps();
    let start = Instant::now();
    while sim.steps() < total {
        sim.step();
        if sim.steps() % scenario.record_every == 0 || sim.steps() == total {
            let (metrics, energy, extra) = measure(&sim);
            recorder.record(&Record {
                t: sim.time(),
                metrics,
                energy,
                swarm: sim.swarm(),
                extra: &extra,
            })?;
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
