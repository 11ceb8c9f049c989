//! Ctrl-C while Rust runs with the GIL released: Python's SIGINT handler only sets a flag, which
//! [`Interrupt::requested`] reads between steps by taking the GIL back for
//! [`Python::check_signals`] (at most every [`CHECK_EVERY`]), so `KeyboardInterrupt` stops a run
//! or a `Simulation.step` after the current step, as Ctrl-C stops `flocking run`.

use std::cell::{Cell, RefCell};
use std::time::{Duration, Instant};

use pyo3::prelude::*;

/// How often the signal handlers run during a long call: often enough for Ctrl-C to feel
/// immediate, rarely enough to cost nothing against the steps.
pub const CHECK_EVERY: Duration = Duration::from_millis(50);

/// Whether a signal handler raised (`KeyboardInterrupt`, or any exception of a handler of the
/// user's) since the call began, checked between steps.
#[derive(Debug)]
pub struct Interrupt {
    last: Cell<Instant>,
    raised: RefCell<Option<PyErr>>,
}

impl Interrupt {
    /// No signal yet; the first check comes [`CHECK_EVERY`] from now.
    #[must_use]
    pub fn new() -> Self {
        Self {
            last: Cell::new(Instant::now()),
            raised: RefCell::new(None),
        }
    }

    /// Whether to stop after the current step: runs Python's signal handlers (with the GIL) when
    /// [`CHECK_EVERY`] has passed since they last ran, and keeps the exception one raised.
    pub fn requested(&self) -> bool {
        if self.raised.borrow().is_some() {
            return true;
        }
        let now = Instant::now();
        if now.duration_since(self.last.get()) < CHECK_EVERY {
            return false;
        }
        self.last.set(now);
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => false,
            Err(error) => {
                *self.raised.borrow_mut() = Some(error);
                true
            }
        }
    }

    /// The exception a signal handler raised, if one did.
    #[must_use]
    pub fn into_raised(self) -> Option<PyErr> {
        self.raised.into_inner()
    }
}

impl Default for Interrupt {
    fn default() -> Self {
        Self::new()
    }
}
