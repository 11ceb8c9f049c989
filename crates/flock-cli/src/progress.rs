//! The progress bar of `flocking run`: a [`Recorder`] wrapper that ticks an [`indicatif`] bar on every
//! record and hands the record on unchanged, so the simulation core and the run's outputs are the
//! same with or without it.
//!
//! The bar is drawn on stderr only when it is enabled (stderr is a terminal and `--quiet` was not
//! given, see [`Progress::for_terminal`]) and the run is expected to last more than about a second:
//! it stays hidden until [`SHOW_AFTER`] has passed and the projected total exceeds [`MIN_RUN`].

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use flocking::{Merge, Record, Recorder, Scenario, Start};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressFinish, ProgressState, ProgressStyle};

/// How long a run goes before its bar may appear.
pub const SHOW_AFTER: Duration = Duration::from_millis(300);

/// The projected length of a run below which no bar is drawn.
pub const MIN_RUN: Duration = Duration::from_secs(1);

/// A recorder that reports progress on stderr and delegates every record to `inner`.
#[derive(Debug)]
pub struct Progress<R> {
    inner: R,
    bar: Option<ProgressBar>,
    shown: bool,
    start: Instant,
    step: f64,
    total: u64,
    /// The step the run starts from (a resumed run's checkpoint).
    first: u64,
}

impl<R> Progress<R> {
    /// Wraps `inner` for a run of `scenario`; the bar is only ever drawn when `enabled`.
    pub fn new(inner: R, scenario: &Scenario, enabled: bool) -> Self {
        let total = scenario.steps();
        let bar = enabled.then(|| {
            let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} steps  {rate}  ETA {eta}",
                )
                .map(|style| {
                    style.with_key("rate", |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                        let _ = write!(w, "{:.0} steps/s", s.per_sec());
                    })
                })
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            // A bar dropped on an error path clears itself too.
            bar.with_finish(ProgressFinish::AndClear)
        });
        Self {
            inner,
            bar,
            shown: false,
            start: Instant::now(),
            step: scenario.step,
            total,
            first: 0,
        }
    }

    /// The bar of a run resumed after `steps` steps: its rate and ETA count the steps from there.
    #[must_use]
    pub fn starting_at(mut self, steps: u64) -> Self {
        self.first = steps.min(self.total);
        if let Some(bar) = &self.bar {
            bar.set_position(self.first);
            bar.reset_eta();
        }
        self
    }

    /// Wraps `inner`, enabling the bar when stderr is a terminal and not `quiet`.
    pub fn for_terminal(inner: R, scenario: &Scenario, quiet: bool) -> Self {
        Self::new(inner, scenario, !quiet && std::io::stderr().is_terminal())
    }

    /// Whether the bar has been drawn.
    #[must_use]
    pub fn shown(&self) -> bool {
        self.shown
    }

    /// Clears the bar and returns the inner recorder.
    pub fn into_inner(self) -> R {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
        self.inner
    }

    /// Moves the bar to the step of time `t`, drawing it once the run looks long enough.
    fn tick(&mut self, t: f64) {
        let Some(bar) = &self.bar else {
            return;
        };
        // Records carry t = steps · step up to rounding.
        let done = ((t / self.step).round().max(0.0) as u64).min(self.total);
        bar.set_position(done);
        if !self.shown && done > self.first && done < self.total {
            let elapsed = self.start.elapsed();
            let projected =
                elapsed.mul_f64((self.total - self.first) as f64 / (done - self.first) as f64);
            if elapsed >= SHOW_AFTER && projected >= MIN_RUN {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar.enable_steady_tick(Duration::from_millis(200));
                self.shown = true;
            }
        }
    }
}

impl<R: Recorder> Recorder for Progress<R> {
    type Error = R::Error;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let result = self.inner.record(record);
        self.tick(record.t);
        result
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.inner.wants_checkpoint(steps)
    }

    fn checkpoint(&mut self, start: &Start) -> Result<(), Self::Error> {
        self.inner.checkpoint(start)
    }

    fn stop_requested(&self) -> bool {
        self.inner.stop_requested()
    }

    /// Prints the warning at once, above the bar, and tells `inner`.
    fn merged(&mut self, merge: &Merge) {
        match &self.bar {
            Some(bar) if self.shown => bar.suspend(|| errln!("{merge}")),
            _ => errln!("{merge}"),
        }
        self.inner.merged(merge);
    }
}

/// A spinner on stderr while figures are drawn (`flocking plot`, `run --plot`): its message and
/// the time elapsed, cleared when dropped; drawn only on a terminal and not `quiet`, and only
/// after [`SHOW_AFTER`], so that quick plots print nothing.
#[derive(Debug)]
pub struct Spinner(Option<ProgressBar>);

impl Spinner {
    /// A spinner saying `message`, enabled when stderr is a terminal and not `quiet`.
    #[must_use]
    pub fn for_terminal(message: &str, quiet: bool) -> Self {
        let enabled = !quiet && std::io::stderr().is_terminal();
        Self(enabled.then(|| {
            let bar = ProgressBar::new_spinner().with_message(message.to_owned());
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar.enable_steady_tick(SHOW_AFTER);
            bar
        }))
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
