//! A sweep on this machine: its pending runs on N workers, one single-threaded run per worker.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::row::{RunRow, run_one};
use super::store::{self, RUNS_DIR, StoreError};
use super::{RunSpec, Sweep};
use crate::estimate::{Estimate, Outputs};

/// A slice of a sweep: run k belongs to shard k mod `count` (for Slurm job arrays).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0 ≤ `index` < `count`.
    pub index: usize,
    /// The number of shards ≥ 1.
    pub count: usize,
}

impl Shard {
    /// Whether run `k` is this shard's.
    #[must_use]
    pub const fn owns(&self, k: usize) -> bool {
        k % self.count == self.index
    }
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `i/N`, 0 ≤ i < N.
    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || format!("{text:?} is not a shard: write i/N with 0 ≤ i < N (e.g. 0/4)");
        let (index, count) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            index.trim().parse().map_err(|_| bad())?,
            count.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

/// How [`execute`] runs a sweep.
#[derive(Clone, Debug)]
pub struct ExecuteOptions {
    /// Workers, each running one run at a time on one thread (≥ 1).
    pub jobs: usize,
    /// Only this slice of the runs.
    pub shard: Option<Shard>,
    /// Keep each run's directory in `DIR/runs/<id>`.
    pub keep_runs: bool,
}

impl Default for ExecuteOptions {
    fn default() -> Self {
        Self {
            jobs: 1,
            shard: None,
            keep_runs: false,
        }
    }
}

/// What [`execute`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Executed {
    /// Runs of this shard found finished in the directory and skipped.
    pub skipped: usize,
    /// Runs made now.
    pub ran: usize,
    /// Runs whose directory could not be written (a full disk): no row is stored for them, and
    /// the same call makes them again.
    pub unwritten: usize,
    /// Rows in `runs.csv`.
    pub rows: usize,
    /// Whether `stop` ended it early (`runs.csv` then holds the finished runs; the same call
    /// resumes).
    pub stopped: bool,
}

/// Runs every pending run of the sweep (of its shard) into `dir` on `options.jobs` workers, each
/// with a rayon pool of one thread; `done` is called after each run (from the worker that made
/// it); `stop` ends it between runs, and so does the process's interrupt ([`crate::interrupt`]),
/// which also stops the runs under way at their next step (they get no row). Finished runs found
/// in `dir` are skipped; `runs.csv` is written at the end ([`store`]).
///
/// # Errors
/// A directory that is not flocking's or is being written ([`store::prepare`]), a directory
/// that holds another sweep, a worker pool that cannot be built, any I/O error. A run
/// that fails is not an error: its row says why; a run whose directory cannot be written has
/// no row ([`Executed::unwritten`]).
pub fn execute(
    sweep: &Sweep,
    dir: &Path,
    options: &ExecuteOptions,
    stop: &(dyn Fn() -> bool + Sync),
    done: &(dyn Fn(&RunRow) + Sync),
) -> Result<Executed, StoreError> {
    // held until the sweep returns: a second writer of `dir` is refused meanwhile
    let _lock = store::prepare(dir, sweep)?;
    let (skipped, pending) = share(sweep, dir, options.shard)?;
    let keep = options.keep_runs.then(|| dir.join(RUNS_DIR));
    let next = AtomicUsize::new(0);
    let ran = AtomicUsize::new(0);
    let unwritten = AtomicUsize::new(0);
    let failure: Mutex<Option<StoreError>> = Mutex::new(None);
    let worker = || {
        let pool = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
            Ok(pool) => pool,
            Err(e) => {
                let source = std::io::Error::other(e.to_string());
                *failure.lock().expect("no worker panics") = Some(StoreError::Io {
                    path: dir.to_path_buf(),
                    source,
                });
                return;
            }
        };
        loop {
            if stop()
                || crate::interrupt::requested()
                || failure.lock().expect("no worker panics").is_some()
            {
                return;
            }
            let Some(run) = pending.get(next.fetch_add(1, Ordering::Relaxed)) else {
                return;
            };
            let row = pool.install(|| run_one(sweep, run, keep.as_deref()));
            if row.retry && crate::interrupt::requested() {
                // stopped by the interrupt: no row, made again next time
                return;
            }
            if row.retry {
                // an I/O failure is not a result of the run: no row, made again next time
                unwritten.fetch_add(1, Ordering::Relaxed);
                done(&row);
                continue;
            }
            if let Err(e) = store::write_row(dir, &row) {
                *failure.lock().expect("no worker panics") = Some(e);
                return;
            }
            ran.fetch_add(1, Ordering::Relaxed);
            done(&row);
        }
    };
    std::thread::scope(|scope| {
        for _ in 0..options.jobs.max(1) {
            scope.spawn(worker);
        }
    });
    if let Some(e) = failure.into_inner().expect("no worker panics") {
        return Err(e);
    }
    let rows = store::assemble(dir, sweep)?;
    let ran = ran.into_inner();
    let unwritten = unwritten.into_inner();
    Ok(Executed {
        skipped,
        ran,
        unwritten,
        rows,
        stopped: ran + unwritten < pending.len(),
    })
}

/// The cost of running `runs` of `sweep` on `workers` at once, each writing `outputs`: the runs'
/// estimates with their starts counted ([`Scenario::estimate_at_start`](crate::Scenario), one
/// crowded run needs a crowd's memory in its worker), their memory that of `workers` such runs.
/// `None` when no run is left.
#[must_use]
pub fn estimate(
    sweep: &Sweep,
    runs: &[RunSpec],
    outputs: &Outputs,
    workers: usize,
) -> Option<Estimate> {
    let estimate = runs
        .iter()
        .filter_map(|run| sweep.scenario(run).ok())
        .map(|scenario| scenario.estimate_at_start(outputs))
        .reduce(Estimate::and)?;
    let workers = workers.min(runs.len()).max(1) as f64;
    Some(Estimate {
        memory_bytes: estimate.memory_bytes * workers,
        delay_line_bytes: estimate.delay_line_bytes * workers,
        ..estimate
    })
}

/// This machine's share of the sweep's runs (every run without a shard): how many of them `dir`
/// holds finished, and the others, in run order.
///
/// # Errors
/// An unreadable directory.
pub fn share(
    sweep: &Sweep,
    dir: &Path,
    shard: Option<Shard>,
) -> Result<(usize, Vec<RunSpec>), StoreError> {
    let finished = store::finished(dir, sweep)?;
    let mine = sweep
        .runs()
        .into_iter()
        .filter(|run| shard.is_none_or(|shard| shard.owns(run.index)));
    let (done, pending): (Vec<RunSpec>, Vec<RunSpec>) =
        mine.partition(|run| finished.contains_key(&run.index));
    Ok((done.len(), pending))
}
