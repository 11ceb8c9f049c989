//! Resuming an interrupted run directory ([`RunDirectory::resume`]): everything checked before
//! anything is written, then its outputs cut back to its checkpoint ([`InterruptedRun::reopen`]).

use std::fs::{self, File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};

use flock_metrics::FlockingCriteria;

use super::columns::{diagnostic_columns, marks_failed};
use super::controls::read_controls;
use super::directory::{RunDirectory, Trajectory, partial_path};
use super::errors::ResumeError;
use super::finish::RUN_LEFTOVERS;
use super::note::{FAILED, FORCE_LINE, INCOMPLETE_FILE, running_note, write_incomplete};
use super::options::{OutputOptions, TrajectoryFormat};
use super::same_run::check_scenario;
use crate::run::Start;
use crate::scenario::Scenario;
use crate::storage::fs::{at, is_empty_dir};
use crate::storage::owned::{self, DirLock, Kind};
use crate::storage::run_dir::checkpoint::Checkpoint;
use crate::storage::run_dir::npy::{NpyFile, trajectory_dtype};
use crate::storage::run_dir::verdict::VERDICT_FILE;
use crate::verdict::VerdictKind;

/// An interrupted run directory, opened and checked by [`RunDirectory::resume`] and locked for
/// this process, of which nothing is written yet: [`InterruptedRun::reopen`] cuts its outputs
/// back to its checkpoint once the caller has rebuilt the run's simulation from it, so that a
/// checkpoint refused at that point leaves `DIR.partial` as it was (issue 49: a refused resume
/// deleted it).
#[derive(Debug)]
pub struct InterruptedRun {
    target: PathBuf,
    partial: PathBuf,
    /// Whether the run was started with `force` (its note says so).
    force: bool,
    state: Reopen,
}

/// What [`InterruptedRun::reopen`] continues: fresh files, or the files the checkpoint counts.
#[derive(Debug)]
enum Reopen {
    /// No checkpoint yet: the run starts over.
    Fresh(Box<Fresh>),
    /// The directory, its files open and not yet cut back to its checkpoint.
    Checkpointed(Box<RunDirectory>),
}

/// A run to start over in its own `DIR.partial`.
#[derive(Debug)]
struct Fresh {
    scenario: Scenario,
    options: OutputOptions,
    lock: DirLock,
    controls: Option<String>,
}

impl InterruptedRun {
    /// `DIR.partial`.
    #[must_use]
    pub fn partial(&self) -> &Path {
        &self.partial
    }

    /// Writes the resumed run's start: drops a manifest that a cut-short finish left, marks the
    /// directory running, and cuts `metrics.csv` and the trajectory back to the checkpoint (or,
    /// without one, starts them afresh).
    ///
    /// # Errors
    /// Any I/O error, naming its path.
    pub fn reopen(self) -> io::Result<RunDirectory> {
        let Self {
            target,
            partial,
            force,
            state,
        } = self;
        // a manifest recorded just before a finishing rename that was cut short: the files are
        // cut back and appended to, and recorded again when the run finishes
        owned::drop_manifest(&partial).map_err(io::Error::other)?;
        owned::mark(&partial, Kind::Run).map_err(io::Error::other)?;
        write_incomplete(&partial, &running_note(&target, force))?;
        match state {
            Reopen::Fresh(fresh) => {
                let Fresh {
                    scenario,
                    options,
                    lock,
                    controls,
                } = *fresh;
                let mut this = RunDirectory::start_files(
                    &target,
                    partial,
                    &scenario,
                    options.format,
                    &options,
                    lock,
                )?;
                this.force = force;
                this.controls = controls;
                Ok(this)
            }
            Reopen::Checkpointed(mut this) => {
                let cut = |file: &File, bytes: u64, name: &str| {
                    file.set_len(bytes).map_err(at(format_args!(
                        "cut {} back",
                        partial.join(name).display()
                    )))
                };
                cut(&this.metrics, this.metrics_bytes, "metrics.csv")?;
                match &mut this.trajectory {
                    Trajectory::Csv { file, bytes } => cut(file, *bytes, "trajectory.csv")?,
                    Trajectory::Npy(file) => file.cut_back().map_err(at(format_args!(
                        "cut {} back",
                        partial.join("trajectory.npy").display()
                    )))?,
                }
                Ok(*this)
            }
        }
    }
}

impl RunDirectory {
    /// Opens the interrupted run `dir` (`DIR` or `DIR.partial`), locked for this process, and
    /// checks everything a resume needs before anything is written: loads its `scenario.ron`
    /// and its last checkpoint and checks that its files hold the records the checkpoint counts.
    /// Returns the run to [reopen](InterruptedRun::reopen) with the scenario and the state to
    /// continue from (`None`: no checkpoint yet, the run starts over with fresh files). A
    /// refusal, here or of the state the caller then builds its simulation from
    /// ([`DynSimulation::resume`](crate::DynSimulation::resume)), leaves `DIR.partial` byte for
    /// byte as it was.
    ///
    /// # Errors
    /// [`ResumeError::Refused`] when there is no interrupted run at `dir`, when the run failed
    /// numerically (resuming would fail again), when `scenario.ron` differs from the scenario
    /// of the checkpoint (naming the fields that changed) or when its files do not match its
    /// checkpoint; [`ResumeError::Dir`] while another process writes it; otherwise the
    /// scenario's or the I/O error, naming its path.
    pub fn resume(
        dir: &Path,
        checkpoint_every: u64,
    ) -> Result<(InterruptedRun, Scenario, Option<Start>), ResumeError> {
        Self::resume_with_controls(dir, checkpoint_every, None)
    }

    /// [`RunDirectory::resume`] of a run whose inputs come from `controls` (a description of
    /// them, e.g. Python's `controls=f`), or from the scenario's protocol (`None`). A run made
    /// with controls from elsewhere records them in [`CONTROLS_FILE`](super::CONTROLS_FILE)
    /// ([`RunDirectory::record_controls`]): resuming it without them, with others, or a run of
    /// the protocol with them, would finish it as neither run, and is refused before anything is
    /// written.
    ///
    /// # Errors
    /// As [`RunDirectory::resume`]; [`ResumeError::Refused`] when the controls do not match.
    pub fn resume_with_controls(
        dir: &Path,
        checkpoint_every: u64,
        controls: Option<&str>,
    ) -> Result<(InterruptedRun, Scenario, Option<Start>), ResumeError> {
        let dir: PathBuf = dir.components().collect();
        let (target, partial) = match dir.to_str().and_then(|s| s.strip_suffix(".partial")) {
            Some(stem) => (PathBuf::from(stem), dir.clone()),
            None => (dir.clone(), partial_path(&dir)),
        };
        if !partial.is_dir() {
            if tidy_completed(&target)? {
                return Err(ResumeError::Tidied { target });
            }
            return Err(ResumeError::Nothing {
                complete: owned::marked(&target, Kind::Run)
                    && target.join("metrics.csv").is_file()
                    && !target.join(INCOMPLETE_FILE).exists(),
                partial,
                target,
            });
        }
        // Issue 27: only a directory flocking wrote, holding only what a run writes (regular
        // files, no link, no FIFO), is cut back and written into.
        if !owned::marked(&partial, Kind::Run) {
            return Err(ResumeError::Refused(format!(
                "{} has no {} marker: it is not a run directory flocking wrote, and flocking never writes into it; start a new run with --out elsewhere",
                partial.display(),
                owned::MARKER_FILE
            )));
        }
        owned::check_only_own(&partial, Kind::Run)?;
        let note_path = partial.join(INCOMPLETE_FILE);
        let note = match fs::read_to_string(&note_path) {
            Ok(note) => note,
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return Err(ResumeError::Refused(format!(
                    "{} has no {INCOMPLETE_FILE} note: it is not an interrupted run of flocking",
                    partial.display()
                )));
            }
            Err(e) => return Err(at(format_args!("read {}", note_path.display()))(e).into()),
        };
        let lock = DirLock::acquire(&partial)?;
        let recorded = read_controls(&partial)?;
        match (&recorded, controls) {
            (Some(recorded), None) => {
                return Err(ResumeError::Refused(format!(
                    "the run in {} was made with {recorded}, which this resume cannot supply: continuing it with the scenario's protocol would finish it as neither run; resume it from Python with flocking.resume({:?}, controls=…) and the same function",
                    partial.display(),
                    target.display().to_string()
                )));
            }
            (None, Some(given)) => {
                return Err(ResumeError::Refused(format!(
                    "the run in {} was made with the scenario's protocol, not with {given}: resume it without controls",
                    partial.display()
                )));
            }
            // issue 49: another function would finish the run as neither
            (Some(recorded), Some(given)) if recorded != given => {
                return Err(ResumeError::Refused(format!(
                    "the run in {} was made with {recorded}, not with {given}: continuing it with another function would finish it as neither run; resume it with the function it was made with",
                    partial.display()
                )));
            }
            _ => {}
        }
        // a run started with `force` replaces its `DIR` (flocking's) when it completes, also
        // after a resume (issue 27)
        let force = note.lines().any(|line| line == FORCE_LINE);
        if note.starts_with(FAILED) {
            return Err(ResumeError::Refused(format!(
                "the run in {} cannot be resumed, it would fail again: {}",
                partial.display(),
                note.trim_end()
            )));
        }
        let scenario =
            Scenario::load(partial.join("scenario.ron")).map_err(ResumeError::Scenario)?;
        let format = if partial.join("trajectory.npy").exists() {
            TrajectoryFormat::Npy
        } else {
            TrajectoryFormat::Csv
        };
        let reopened = |state| InterruptedRun {
            target: target.clone(),
            partial: partial.clone(),
            force,
            state,
        };
        let Some(checkpoint) = Checkpoint::read(&partial)? else {
            // No checkpoint yet: the run starts over, in fresh files.
            let options = OutputOptions {
                force,
                format,
                checkpoint_every,
            };
            let fresh = Fresh {
                scenario: scenario.clone(),
                options,
                lock,
                controls: recorded,
            };
            return Ok((reopened(Reopen::Fresh(Box::new(fresh))), scenario, None));
        };
        check_scenario(&checkpoint, &scenario, &partial)?;
        // the records the checkpoint counts must all be there (issue 27: a missing `metrics.csv`
        // was "No such file or directory (os error 2)", naming no path)
        let trajectory_file = match format {
            TrajectoryFormat::Csv => "trajectory.csv",
            TrajectoryFormat::Npy => "trajectory.npy",
        };
        for name in ["metrics.csv", trajectory_file] {
            if fs::symlink_metadata(partial.join(name)).is_err() {
                return Err(ResumeError::Refused(format!(
                    "{} has no {name}: the records of the interrupted run are gone, so it cannot be resumed; start it over with `flocking run SCENARIO --out {} --force`",
                    partial.display(),
                    target.display()
                )));
            }
        }
        let metrics_path = partial.join("metrics.csv");
        let columns =
            if checkpoint.records > 0 {
                Some(diagnostic_columns(&metrics_path).map_err(|e| match e.kind() {
                io::ErrorKind::InvalidData => ResumeError::Refused(format!(
                    "{e}: it is not the metrics.csv of this run, so the run cannot be resumed"
                )),
                _ => e.into(),
            })?)
            } else {
                None
            };
        let metrics = open_holding(&metrics_path, checkpoint.metrics_bytes)?;
        let trajectory = match format {
            TrajectoryFormat::Csv => Trajectory::Csv {
                file: open_holding(&partial.join("trajectory.csv"), checkpoint.trajectory_bytes)?,
                bytes: checkpoint.trajectory_bytes,
            },
            TrajectoryFormat::Npy => {
                let (descr, row_bytes) = trajectory_dtype(
                    scenario.agents,
                    scenario.dim,
                    scenario.vehicle.state_columns(scenario.dim).len(),
                    marks_failed(&scenario),
                );
                let path = partial.join("trajectory.npy");
                Trajectory::Npy(
                    NpyFile::open_holding(&path, descr, row_bytes, checkpoint.records).map_err(
                        |e| match e.kind() {
                            io::ErrorKind::UnexpectedEof => ResumeError::Refused(format!(
                                "{e}: the records of the interrupted run are cut, so it cannot be resumed"
                            )),
                            _ => at(format_args!("open {}", path.display()))(e).into(),
                        },
                    )?,
                )
            }
        };
        let empty_target = is_empty_dir(&target);
        let this = Self {
            target: target.clone(),
            partial: partial.clone(),
            metrics,
            metrics_bytes: checkpoint.metrics_bytes,
            trajectory,
            records: checkpoint.records,
            dim: scenario.dim,
            checkpoint_every,
            buffer: Vec::new(),
            last_state: Vec::new(),
            vehicle_columns: scenario.vehicle.state_columns(scenario.dim),
            marks_failed: marks_failed(&scenario),
            columns,
            agents: scenario.agents,
            criteria: FlockingCriteria::default(),
            verdict_kind: VerdictKind::of(&scenario.algorithm),
            scenario: checkpoint.scenario,
            force,
            empty_target,
            lock,
            controls: recorded,
        };
        Ok((
            reopened(Reopen::Checkpointed(Box::new(this))),
            scenario,
            Some(checkpoint.start),
        ))
    }
}

/// Finishes what [`RunDirectory::finish`] left undone when killed right after renaming
/// `DIR.partial` to `DIR`: removes the checkpoint and the `INCOMPLETE` note of a `DIR` that is
/// flocking's, holds only a run's files and is complete (its `final.csv` and verdict written
/// before the rename). Returns whether it did.
fn tidy_completed(target: &Path) -> Result<bool, ResumeError> {
    let leftover = |name: &str| fs::symlink_metadata(target.join(name)).is_ok_and(|m| m.is_file());
    if !(owned::marked(target, Kind::Run)
        && leftover(INCOMPLETE_FILE)
        && leftover("final.csv")
        && leftover(VERDICT_FILE))
    {
        return Ok(false);
    }
    owned::check_only_own(target, Kind::Run)?;
    let _lock = DirLock::acquire(target)?;
    owned::remove_own_files(target, Kind::Run, &RUN_LEFTOVERS)?;
    Ok(true)
}

/// Opens `path` for appending, unchanged, when it holds at least the `bytes` bytes its checkpoint
/// counts ([`InterruptedRun::reopen`] cuts it back to them).
fn open_holding(path: &Path, bytes: u64) -> Result<File, ResumeError> {
    let file = OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(at(format_args!("open {}", path.display())))?;
    let len = file
        .metadata()
        .map_err(at(format_args!("read {}", path.display())))?
        .len();
    if len < bytes {
        return Err(ResumeError::Refused(format!(
            "{} is shorter than its checkpoint says ({len} bytes, not {bytes}): the records of the interrupted run are cut, so it cannot be resumed",
            path.display()
        )));
    }
    Ok(file)
}
