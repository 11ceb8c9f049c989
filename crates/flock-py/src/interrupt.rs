//! Ctrl-C while Rust runs with the GIL released: [`watched`] runs the work on a thread of its
//! own while the calling thread (Python's main thread, where the signal handlers run) runs them
//! every [`CHECK_EVERY`] through [`Python::check_signals`]. A handler that raises
//! (`KeyboardInterrupt`, or any exception of a handler of the user's) requests the library's
//! interrupt ([`flocking::interrupt`]): a run stops after its current step, and a step still
//! running half a second later is cut short, so that Ctrl-C stops a run, a `Simulation.step` or
//! a benchmark within a second, even inside one long step (issue 49: a step of an all-pairs model
//! of 30,000 agents took 13 s and ignored Ctrl-C).

use std::time::Duration;

use pyo3::prelude::*;

/// How often the signal handlers run during a long call: often enough for Ctrl-C to feel
/// immediate, rarely enough to cost nothing against the steps.
pub const CHECK_EVERY: Duration = Duration::from_millis(50);

/// `work()`, run with the GIL released on a thread of its own, and the exception a signal handler
/// raised meanwhile, if one did (the library's interrupt was then requested, and `work` should
/// stop at its next check of [`flocking::interrupt::requested`]). The interrupt is cleared before
/// and after.
pub fn watched<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> (T, Option<PyErr>) {
    flocking::interrupt::clear();
    let outcome = py.detach(|| {
        std::thread::scope(|scope| {
            let caller = std::thread::current();
            let worker = scope.spawn(move || {
                let result = work();
                caller.unpark();
                result
            });
            let mut raised = None;
            while !worker.is_finished() {
                std::thread::park_timeout(CHECK_EVERY);
                if raised.is_none()
                    && let Err(error) = Python::attach(|py| py.check_signals())
                {
                    flocking::interrupt::request();
                    raised = Some(error);
                }
            }
            let result = worker
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (result, raised)
        })
    });
    flocking::interrupt::clear();
    outcome
}
