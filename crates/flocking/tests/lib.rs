//! Integration tests of the `flocking` library, one binary (see STYLE.md): scenario files, the
//! papers' runs, the figures that had no fixture, the obstacle passes of TAC 2006 Fig. 14–17,
//! snapshots and determinism of short runs, the columns of `docs/outputs.md`, agents stored by cell, the errors of bad obstacles, and the warnings before a run.

mod common;
mod conditions;
mod controller;
mod env;
mod fig7_squeeze;
mod fixtures;
mod models;
mod new_figures;
mod obstacle_errors;
mod obstacle_fixtures;
mod outputs;
mod overrides;
mod papers;
mod params;
mod readme;
mod run_dir;
mod sink_fixtures;
mod snapshots;
mod stability;
mod storage_order;
mod sweep;
mod topology;
mod typed_mistakes;
mod vehicles;
mod warnings;
