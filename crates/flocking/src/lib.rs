//! flocking as a library: the flocking algorithms of Olfati-Saber (IEEE TAC 51(3) 2006, Caltech
//! CDS 03-006 2003, ACC 2004) and of Tanner, Jadbabaie & Pappas (2003), run from scenarios in 2D
//! and 3D, with the metrics the papers judge flocking by, checkpoints, and the run directories
//! `flocking run` writes — without the command line.
//!
//! - [`Scenario`]: a RON scenario ([`Scenario::load`], [`str::parse`], [`Scenario::validate`],
//!   [`Scenario::warnings`]); its protocol in either dimension ([`Scenario::protocol`]); any
//!   parameter read or changed by its path ([`Scenario::value`], [`Scenario::with_values`]).
//! - [`DynSimulation`]: the simulation of a scenario behind one type, its state as plain `f64`
//!   rows ([`State`]), agents in original order; metrics, energy, diagnostics, health.
//! - [`run()`], [`resume()`]: a whole run, every recorded step handed to a [`Recorder`];
//!   [`resume_with()`] with the protocol changed by a [`MapProtocol`]; [`run_from()`] of a
//!   simulation built first.
//! - [`interrupt`]: the process's Ctrl-C, which a run checks between steps and the long loops of
//!   a step check inside it.
//! - [`storage`]: everything kept on the disk, re-exported as [`run_dir`] and [`owned`].
//! - [`run_dir`]: the run directory — [`RunDirectory`] writes it (crash-safe, checkpointed,
//!   resumable), [`read_run`] reads it back.
//! - [`verdict`]: the verdict a run gets, success as its model's papers measure it ([`Verdict`]:
//!   TAC 2006 Definition 5, or the order states of the classic models).
//! - [`warnings`]: the warnings of a valid scenario ([`Warning`]); [`stability`]: the largest
//!   stable step;
//!   [`NumericalError`]: a blow-up with its step, agent and likely cause; [`merging`]: agents
//!   driven onto one point ([`Merge`], [`MergedAgents`]).
//! - [`sweep`]: parameter sweeps and ensembles — a grid of values × seeds, one row of
//!   `runs.csv` per run, resumable, in shards.
//! - [`owned`]: the marker, the checks and the lock that keep flocking from removing or
//!   overwriting anything it did not write.
//! - [`synthetic`]: lattices of any size for benchmarks.
//! - The member crates, re-exported: [`math`], [`graph`], [`protocols`], [`sim`], [`obstacles`],
//!   [`metrics`], and [`glam`]; [`prelude`] for a glob import.
//!
//! # Example
//! ```
//! use flocking::prelude::*;
//!
//! # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))?; // the workspace root
//! let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
//! let summary = flocking::run(&scenario, &mut ())?;
//! println!("final connectivity C = {}", summary.metrics.connectivity);
//! assert_eq!(summary.metrics.connectivity, 1.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod algorithm;
pub mod bench;
pub mod build;
pub mod controller;
pub mod env;
pub mod error;
pub mod estimate;
pub mod health;
pub mod initial;
pub mod input;
pub mod machine;
pub mod merging;
pub mod overrides;
pub mod perception;
pub mod run;
pub mod scenario;
pub mod simulation;
pub mod stability;
pub mod storage;
mod struct_variant;
pub mod sweep;
pub mod synthetic;
pub mod time;
mod typed_mistake;
mod validate;
pub mod vehicle;
pub mod verdict;
pub mod warning;
pub mod warnings;
pub mod workload;

pub use build::check_local_form;
pub use error::ScenarioError;
pub use health::NumericalError;
pub use merging::{DenseStart, Merge, MergeCause, MergedAgents};
pub use run::{Record, Recorder, RunError, RunSummary, Start, resume, resume_with, run, run_from};
pub use run_dir::{OutputOptions, RunDirectory, RunFiles, TrajectoryFormat, read_run};
pub use scenario::{
    Algorithm, Cloud, FixedGraph, Initial, Point, Scenario, TannerGraph, Translation,
};
pub use simulation::{DynSimulation, MapProtocol, ScenarioProtocol, State};
pub use stability::{consensus_laplacian_max, largest_stable_step, velocity_consensus_delay_bound};
pub use storage::{owned, run_dir};
pub use validate::{MAX_AGENTS, MAX_STEPS};
pub use verdict::{Verdict, VerdictKind};
pub use warning::Warning;

pub use flock_graph as graph;
pub use flock_math as math;
pub use flock_math::interrupt;
pub use flock_metrics as metrics;
pub use flock_obstacles as obstacles;
pub use flock_sim as sim;

/// The protocols' laws (crate flock-protocols) and, at the paths they had before the loop got a
/// crate of its own, the loop's types (crate flock-sim, also [`sim`]).
pub mod protocols {
    pub use flock_protocols::*;
    pub use flock_sim::{
        AgentFault, Conditions, ConditionsState, DynVehicle, Fault, Fleet, Integrator, Observation,
        Simulation, Vehicle, VehicleKind, advance, check_vehicle_loop, conditions, health,
        simulation as integrator, vehicle,
    };
}
pub use glam;
pub use serde_json;

/// The names most programs use: `use flocking::prelude::*;`.
pub mod prelude {
    pub use crate::metrics::{FlockMetrics, MetricParams};
    pub use crate::protocols::{GammaAgent, Integrator, Protocol, Simulation, Swarm};
    pub use crate::{
        DynSimulation, Record, Recorder, RunDirectory, RunError, RunSummary, Scenario,
        ScenarioError, State, read_run, resume, run,
    };
    pub use glam::{DVec2, DVec3};
}
