//! The progress line of `flocking.run` and `flocking.resume`: simulated time against the
//! duration, steps per second and the time left, redrawn on Python's `sys.stderr` at most five
//! times a second and cleared at the end. `flocking.run(progress=None)` shows it only when
//! `sys.stderr` is a terminal (never in a pipe, a file, a test or a notebook's captured stream);
//! `progress=False` never, `progress=True` always.

use std::time::{Duration, Instant};

use pyo3::prelude::*;

/// How often the line is redrawn at most.
const EVERY: Duration = Duration::from_millis(200);

/// The bar's width in characters.
const WIDTH: usize = 30;

/// A progress line of a run from `t0` to `duration`, drawn on `sys.stderr`.
#[derive(Debug)]
pub struct Progress {
    start: Instant,
    last: Option<Instant>,
    t0: f64,
    duration: f64,
    step: f64,
    drawn: bool,
}

impl Progress {
    /// The line of a run of `duration` s at step `step` resumed at `t0` (0 for a new run).
    #[must_use]
    pub fn new(t0: f64, duration: f64, step: f64) -> Self {
        Self {
            start: Instant::now(),
            last: None,
            t0,
            duration,
            step,
            drawn: false,
        }
    }

    /// The line at simulated time `t`.
    #[must_use]
    pub fn line(&self, t: f64, elapsed: f64) -> String {
        let fraction = if self.duration > 0.0 {
            (t / self.duration).clamp(0.0, 1.0)
        } else {
            1.0
        };
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
            "\r[{}{}] {:>3.0} %  t = {t:.2} of {} s  {rate:.0} steps/s  {eta}",
            "#".repeat(filled),
            "-".repeat(WIDTH - filled),
            100.0 * fraction,
            self.duration,
        )
    }

    /// Redraws the line at simulated time `t` when the last drawing is old enough.
    pub fn at(&mut self, t: f64) {
        let now = Instant::now();
        if self.last.is_some_and(|last| now - last < EVERY) {
            return;
        }
        self.last = Some(now);
        let line = self.line(t, (now - self.start).as_secs_f64());
        self.drawn = write(&line) || self.drawn;
    }

    /// Clears the line, if one was drawn.
    pub fn clear(&self) {
        if self.drawn {
            write(&format!("\r{}\r", " ".repeat(WIDTH + 70)));
        }
    }
}

/// Writes `text` to `sys.stderr` and flushes it (taking the GIL); whether that worked.
fn write(text: &str) -> bool {
    Python::attach(|py| {
        let stderr = py.import("sys")?.getattr("stderr")?;
        stderr.call_method1("write", (text,))?;
        stderr.call_method0("flush")?;
        Ok::<_, PyErr>(())
    })
    .is_ok()
}
