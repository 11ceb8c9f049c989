//! Integration tests of flock-viz: one binary, one module per figure.

mod animation;
mod determinism;
mod figures;
mod metrics_plot;
mod player;
mod run_data;
mod scene;
mod snapshot;
mod support;
mod views;
