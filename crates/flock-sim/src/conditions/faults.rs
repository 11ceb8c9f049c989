//! Agents that fail: at given times, or at random at a rate per agent per second.

use flock_graph::Numbering;

use super::config::{FaultMode, Faults};
use flock_math::stream::{Purpose, Streams};

/// Marks the agents failing at step `k` (time k h) in `failed` (agents stored as `numbering`
/// says): those of `faults.at` whose time is reached, and each working agent with probability
/// 1 − e^(−rate h) (a draw keyed by its original index and the step; a Poisson failure process
/// of that rate, sampled at the steps).
pub fn update(
    faults: &Faults,
    streams: &Streams,
    k: u64,
    h: f64,
    numbering: &Numbering,
    failed: &mut [bool],
) {
    let t = k as f64 * h;
    for failure in &faults.at {
        if failure.time <= t + 1e-9 * h {
            failed[numbering.stored(failure.agent)] = true;
        }
    }
    if faults.rate > 0.0 {
        let p = -(-faults.rate * h).exp_m1();
        for (i, f) in failed.iter_mut().enumerate() {
            let agent = numbering.original(i) as u64;
            if !*f && streams.uniform(Purpose::Failure, agent, k) < p {
                *f = true;
            }
        }
    }
}

/// Whether a failed agent in `mode` is still heard by the others.
#[must_use]
pub const fn heard(mode: FaultMode) -> bool {
    matches!(mode, FaultMode::Frozen)
}

/// Whether a failed agent in `mode` still moves under its own control.
#[must_use]
pub const fn moves(mode: FaultMode) -> bool {
    matches!(mode, FaultMode::Silent)
}
