//! Integration tests of `flock-cli`, one binary (see STYLE.md): scenario files, the papers' runs,
//! snapshots and determinism of short runs, and the errors of bad scenarios and of the `flock` binary.

mod bench;
mod browser;
mod common;
mod errors;
mod figures_cmd;
mod fixtures;
mod obstacle_errors;
mod papers;
mod plot;
mod snapshots;
mod storage_order;
mod trust;
