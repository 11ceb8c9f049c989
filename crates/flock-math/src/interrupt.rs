//! Ctrl-C inside one step: the one interrupt of the process, which the long loops of a step (a
//! protocol's inputs over every pair, a vehicle's inner steps, the conditions' stage) check per
//! block of work, so that a step of seconds or minutes stops within a fraction of a second.
//!
//! A command's Ctrl-C handler (or Python's, through the `flocking` package) calls [`request`];
//! a run checks [`requested`] between steps and stops there, keeping a checkpoint of the whole
//! state. A step still running [`GRACE`] after the request is *cut short*: its loops see
//! [`cuts_short`] and leave the rest of their work undone, so that the step stops within about
//! `GRACE` plus one block (each block is far shorter than 0.1 s of work). What such a step had
//! done is not kept (`Simulation::step` in `flock-protocols` says how). Short steps are never cut:
//! they end within the grace, and the run stops after them as before.
//!
//! The request stays until [`clear`]: a command quits after it, and a long-lived caller (the
//! Python package) clears it before each call.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// How long a step may still run after [`request`] before its loops cut it short: a step shorter
/// than this always ends whole, and the run keeps its state.
pub const GRACE: Duration = Duration::from_millis(500);

/// Items of a loop between two checks of [`cuts_short`] (a block of agents of a protocol's inputs,
/// of inner steps of a vehicle): a relaxed load per block, nothing per pair.
pub const BLOCK: usize = 16;

/// The interrupt of the process, which [`request`], [`requested`], [`clear`] and [`cuts_short`]
/// read and write.
static PROCESS: Interrupt = Interrupt::new();

/// Asks every run of the process to stop: between steps at once, inside a step once it has run
/// [`GRACE`] longer. Returns whether an interrupt was already requested (a second Ctrl-C).
pub fn request() -> bool {
    PROCESS.request()
}

/// Whether an interrupt is requested: a run stops after its current step.
#[must_use]
pub fn requested() -> bool {
    PROCESS.requested()
}

/// Forgets the request (a long-lived caller, before its next call).
pub fn clear() {
    PROCESS.clear();
}

/// Whether a long loop must leave the rest of its work undone: an interrupt was requested at
/// least [`GRACE`] ago. Once true, it stays true until [`clear`].
#[inline]
#[must_use]
pub fn cuts_short() -> bool {
    PROCESS.cuts_short()
}

/// An interrupt request and its time: [`PROCESS`]'s, or a test's own.
struct Interrupt {
    /// 0 when no interrupt is requested; otherwise 1 + the nanoseconds from [`epoch`] to the
    /// request.
    at: AtomicU64,
}

/// The instant the request times count from (the first use of this module).
fn epoch() -> Instant {
    static EPOCH: OnceLock<Instant> = OnceLock::new();
    *EPOCH.get_or_init(Instant::now)
}

impl Interrupt {
    const fn new() -> Self {
        Self {
            at: AtomicU64::new(0),
        }
    }

    fn request(&self) -> bool {
        let now = 1 + u64::try_from(epoch().elapsed().as_nanos()).unwrap_or(u64::MAX - 1);
        self.at
            .compare_exchange(0, now, Ordering::SeqCst, Ordering::SeqCst)
            .is_err()
    }

    fn requested(&self) -> bool {
        self.at.load(Ordering::Relaxed) != 0
    }

    fn clear(&self) {
        self.at.store(0, Ordering::SeqCst);
    }

    #[inline]
    fn cuts_short(&self) -> bool {
        match self.at.load(Ordering::Relaxed) {
            0 => false,
            at => epoch().elapsed().as_nanos() >= u128::from(at - 1) + GRACE.as_nanos(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On an interrupt of the test's own: the process's would stop the loops of the tests
    /// running beside it.
    #[test]
    fn a_request_cuts_loops_short_only_after_the_grace() {
        let interrupt = Interrupt::new();
        assert!(!interrupt.requested() && !interrupt.cuts_short());
        assert!(!interrupt.request(), "the first request");
        assert!(
            interrupt.requested() && !interrupt.cuts_short(),
            "within the grace"
        );
        assert!(interrupt.request(), "a second request is told so");
        std::thread::sleep(GRACE + Duration::from_millis(20));
        assert!(interrupt.cuts_short(), "after the grace");
        interrupt.clear();
        assert!(!interrupt.requested() && !interrupt.cuts_short());
    }
}
