//! The progress of `flocking.run` and `flocking.resume`: simulated time against the duration,
//! steps per second and the time left, handed at most five times a second to a Python sink
//! (`flocking._run`'s: a line redrawn on a terminal's `sys.stderr` and cleared at the end, or in
//! Jupyter a bar updated in place and kept, with the run's last line, when done). Which sink, if
//! any, `flocking.run(progress=…)` chooses in Python.

use std::time::{Duration, Instant};

use pyo3::prelude::*;

/// How often the sink is updated at most.
const EVERY: Duration = Duration::from_millis(200);

/// The bar's width in characters.
const WIDTH: usize = 30;

/// The progress of a run from `t0` to `duration`, told to a Python sink with `update(line,
/// fraction)` and `close(line)`.
#[derive(Debug)]
pub struct Progress {
    sink: Py<PyAny>,
    start: Instant,
    last: Option<Instant>,
    t0: f64,
    t: f64,
    duration: f64,
    step: f64,
}

impl Progress {
    /// The progress of a run of `duration` s at step `step` resumed at `t0` (0 for a new run),
    /// told to `sink`.
    #[must_use]
    pub fn new(sink: Py<PyAny>, t0: f64, duration: f64, step: f64) -> Self {
        Self {
            sink,
            start: Instant::now(),
            last: None,
            t0,
            t: t0,
            duration,
            step,
        }
    }

    /// The fraction of the run done at simulated time `t`, in [0, 1].
    fn fraction(&self, t: f64) -> f64 {
        if self.duration > 0.0 {
            (t / self.duration).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// The line at simulated time `t`, `elapsed` seconds after the start.
    #[must_use]
    pub fn line(&self, t: f64, elapsed: f64) -> String {
        let fraction = self.fraction(t);
        let filled = (fraction * WIDTH as f64).round() as usize;
        let done = (t - self.t0).max(0.0);
        let rate = if elapsed > 0.0 {
            done / self.step / elapsed
        } else {
            0.0
        };
        let left = if done > 0.0 {
            elapsed * (self.duration - t).max(0.0) / done
        } else {
            f64::NAN
        };
        let eta = if left.is_finite() {
            format!("{left:.0} s left")
        } else {
            "…".to_owned()
        };
        format!(
            "[{}{}] {:>3.0} %  t = {t:.2} of {} s  {rate:.0} steps/s  {eta}",
            "#".repeat(filled),
            "-".repeat(WIDTH - filled),
            100.0 * fraction,
            self.duration,
        )
    }

    /// The last line: how far the run went, in how long.
    fn last_line(&self, elapsed: f64) -> String {
        let steps = ((self.t - self.t0).max(0.0) / self.step).round();
        let rate = if elapsed > 0.0 { steps / elapsed } else { 0.0 };
        format!(
            "t = {:.2} of {} s ({:.0} %): {steps:.0} steps in {elapsed:.1} s, {rate:.0} steps/s",
            self.t,
            self.duration,
            100.0 * self.fraction(self.t),
        )
    }

    /// Tells the sink the run is at simulated time `t`, when its last update is old enough.
    pub fn at(&mut self, t: f64) {
        self.t = t;
        let now = Instant::now();
        if self.last.is_some_and(|last| now - last < EVERY) {
            return;
        }
        self.last = Some(now);
        let line = self.line(t, (now - self.start).as_secs_f64());
        let fraction = self.fraction(t);
        // a sink that fails is ignored: a progress display must not stop a run
        Python::attach(|py| {
            let _ = self.sink.bind(py).call_method1("update", (line, fraction));
        });
    }

    /// Tells the sink the run has ended (finished, failed or interrupted) with its last line.
    pub fn close(&self) {
        let line = self.last_line(self.start.elapsed().as_secs_f64());
        Python::attach(|py| {
            let _ = self.sink.bind(py).call_method1("close", (line,));
        });
    }
}
