//! The output directory of `flocking run`: `metrics.csv`, the trajectory (`trajectory.csv`, or
//! `trajectory.npy` for large runs), `final.csv` and the resolved `scenario.ron`.
//!
//! Crash safety:
//! - Everything is written into a sibling `DIR.partial`, renamed to `DIR` only when the run
//!   completes: `DIR` exists only for complete runs.
//! - `DIR.partial/INCOMPLETE` says why the directory is incomplete (running or killed,
//!   interrupted, failed) and how to resume it.
//! - Each record goes to each file in one write of whole lines; a process killed inside that
//!   write can still leave the record cut (a `.npy` header counts only whole records).
//!   `checkpoint.bin` ([`Checkpoint`]) is replaced atomically every `checkpoint_every` steps and
//!   when the run is interrupted, and the note then says up to which byte the records are whole.
//!   [`RunDirectory::resume`] cuts the files back to the last checkpoint and continues them.
//! - Durability: before `checkpoint.bin` is replaced, the outputs it counts are flushed to the
//!   disk (fsync), and so is every file and directory before each rename (the checkpoint, the
//!   `INCOMPLETE` note, `DIR.partial` to `DIR`), so that a power cut cannot leave a checkpoint
//!   that counts bytes the disk does not hold.
//! - Ownership ([`crate::owned`]): the directory carries flocking's marker; `force` replaces only
//!   a `DIR` that flocking wrote; `DIR.partial` is locked for the whole run, so that a second
//!   writer is refused; finishing never removes `DIR.partial` (an error leaves it resumable) nor
//!   renames over a `DIR` that appeared during the run, even an empty one: the rename is atomic
//!   and refuses an existing `DIR` (`RENAME_NOREPLACE`), so nothing appearing between the last
//!   check and the rename is replaced either.
//! - Before the final rename, every file of the run is recorded by size and content in its
//!   manifest ([`owned::manifest`]): `force` replaces a `DIR` only while its files are those
//!   flocking wrote. A resume drops a manifest a cut-short finish left in `DIR.partial`, and
//!   records it again when it finishes.
//! - The checkpoint holds the resolved scenario: `--resume` refuses a `scenario.ron` edited
//!   since, naming the fields that changed.
//! - The header of `metrics.csv` is written with the first record: the columns of the protocol's
//!   diagnostics are named by the diagnostics themselves ([`Record::diagnostics`]), and every
//!   later record must carry the same names.

use std::fmt::Write as _;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::str::FromStr;

use super::checkpoint::{
    CHECKPOINT_FILE, CHECKPOINT_TMP, Checkpoint, Counts, DrawsOf, sync_dir, write_checkpoint,
};
use super::npy::{NpyFile, trajectory_dtype};
use super::read::{FAILED_COLUMN, trajectory_header_with};
use super::verdict::{VERDICT_FILE, judge_metrics_file, verdict_text};
use crate::error::ScenarioError;
use crate::owned::{self, DirError, DirLock, Kind, at, parent_of};
use crate::run::{Record, Recorder, Start};
use crate::scenario::Scenario;
use crate::simulation::State;
use crate::verdict::{Verdict, VerdictKind};
use flock_metrics::FlockingCriteria;

/// The header of `metrics.csv`: t, [`FlockMetrics::REAL_COLUMNS`](flock_metrics::FlockMetrics::REAL_COLUMNS),
/// the collisions, the energy, then (appended later, so that the former columns keep their
/// places) [`FlockMetrics::EXTRA_COLUMNS`](flock_metrics::FlockMetrics::EXTRA_COLUMNS) and the
/// number of components; the protocol's diagnostics follow.
pub const METRICS_HEADER: &str = "t,connectivity,giant_component,cohesion_radius,deviation_energy,velocity_mismatch,min_distance,collisions,energy,polarisation,milling,nearest_neighbour_mean,nearest_neighbour_min,group_speed,components";

/// The file that marks a directory as incomplete, and says why.
pub const INCOMPLETE_FILE: &str = "INCOMPLETE";

/// Renames `from` to `to` only if `to` does not exist, atomically (`renameat2` with
/// `RENAME_NOREPLACE`): an existing `to` is an [`io::ErrorKind::AlreadyExists`] error and is kept.
/// Where the filesystem cannot (`EINVAL`, `ENOSYS`), `to` is checked first and the rename is the
/// ordinary one.
///
/// # Errors
/// [`io::ErrorKind::AlreadyExists`] for an existing `to`; any other I/O error of the rename.
pub(crate) fn rename_no_replace(from: &Path, to: &Path) -> io::Result<()> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    use rustix::io::Errno;
    match renameat_with(CWD, from, CWD, to, RenameFlags::NOREPLACE) {
        Ok(()) => Ok(()),
        Err(Errno::INVAL | Errno::NOSYS) => {
            if fs::symlink_metadata(to).is_ok() {
                Err(io::Error::from(io::ErrorKind::AlreadyExists))
            } else {
                fs::rename(from, to)
            }
        }
        Err(e) => Err(e.into()),
    }
}

/// Whether `path` is a directory with no entries.
fn is_empty_dir(path: &Path) -> bool {
    fs::read_dir(path).is_ok_and(|mut entries| entries.next().is_none())
}

/// The temporary file [`INCOMPLETE_FILE`] is written to before its rename.
const INCOMPLETE_TMP: &str = "INCOMPLETE.tmp";

/// The first word of [`INCOMPLETE_FILE`] for a run that cannot be resumed.
const FAILED: &str = "failed";

/// How a run's trajectory is stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TrajectoryFormat {
    /// `trajectory.csv`: `t,id,x,y[,z],vx,vy[,vz]`, one line per agent and record.
    #[default]
    Csv,
    /// `trajectory.npy`: one structured record per instant, fields `t`, `q` (n × dim) and
    /// `p` (n × dim), read by `numpy.load` (see [`super::npy`]).
    Npy,
}

impl FromStr for TrajectoryFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "csv" => Ok(Self::Csv),
            "npy" => Ok(Self::Npy),
            other => Err(format!(
                "unknown trajectory format {other:?}: use csv or npy"
            )),
        }
    }
}

/// How a run directory is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputOptions {
    /// Replace an existing `DIR` that flocking wrote (never a directory holding anything else).
    pub force: bool,
    /// The trajectory's format.
    pub format: TrajectoryFormat,
    /// Keep a checkpoint every this many steps (0: only when interrupted).
    pub checkpoint_every: u64,
}

impl Default for OutputOptions {
    fn default() -> Self {
        Self {
            force: false,
            format: TrajectoryFormat::Csv,
            checkpoint_every: 1000,
        }
    }
}

/// The trajectory file being written.
#[derive(Debug)]
enum Trajectory {
    Csv { file: File, bytes: u64 },
    Npy(NpyFile),
}

/// An output directory being written.
#[derive(Debug)]
pub struct RunDirectory {
    target: PathBuf,
    partial: PathBuf,
    metrics: File,
    metrics_bytes: u64,
    trajectory: Trajectory,
    records: u64,
    dim: usize,
    checkpoint_every: u64,
    /// One trajectory record's bytes (CSV text or `.npy` row), reused.
    buffer: Vec<u8>,
    /// The last recorded state (dim coordinates of q, then of p, then the vehicle's state, then
    /// 0 or 1 for `failed` when it is marked, per agent) for `final.csv`.
    last_state: Vec<f64>,
    /// The names of each agent's vehicle state (empty for point masses).
    vehicle_columns: &'static [&'static str],
    /// Whether each agent's row ends with `failed` (0 or 1): the scenario has `faults`.
    marks_failed: bool,
    /// The diagnostic columns of the header of `metrics.csv`, once written.
    columns: Option<Vec<String>>,
    /// The number of agents.
    agents: usize,
    /// The criteria of the verdict of [`VERDICT_FILE`].
    criteria: FlockingCriteria,
    /// The verdict the scenario's model gets.
    verdict_kind: VerdictKind,
    /// The resolved scenario as RON, kept in every checkpoint.
    scenario: String,
    /// Whether `DIR` may be replaced at the end (it carried flocking's marker at the start).
    force: bool,
    /// Whether `DIR` was an empty directory when this writer started: it is then replaced at the
    /// end, while an empty `DIR` that appears during the run is kept.
    empty_target: bool,
    /// The lock on `DIR.partial`, held until the directory is dropped.
    lock: DirLock,
    /// Where the run's inputs come from when not from the scenario's protocol
    /// ([`CONTROLS_FILE`]).
    controls: Option<String>,
}

/// A complete run directory.
#[derive(Clone, Debug, PartialEq)]
pub struct Finished {
    /// `DIR`.
    pub path: PathBuf,
    /// The model's verdict judged on its whole `metrics.csv` (also in [`VERDICT_FILE`]).
    pub verdict: Option<Verdict>,
}

/// Why a run directory cannot be created.
#[derive(Debug)]
pub enum CreateError {
    /// The target directory already holds files (and `force` was not set).
    Occupied {
        /// The target directory.
        target: PathBuf,
    },
    /// `DIR.partial` holds an interrupted run (and `force` was not set).
    Interrupted {
        /// `DIR.partial`.
        partial: PathBuf,
        /// `DIR`.
        target: PathBuf,
    },
    /// The output path exists and is not a directory (a file, a FIFO, a device, a link).
    NotADirectory {
        /// The output path.
        target: PathBuf,
        /// What it is.
        what: &'static str,
    },
    /// The directory is not flocking's to replace, or another process is writing it.
    Dir(DirError),
    /// Writing failed.
    Io(io::Error),
}

impl std::fmt::Display for CreateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Occupied { target } => write!(
                f,
                "output directory {} already holds files (replace it with `force`)",
                target.display()
            ),
            Self::Interrupted { partial, .. } => write!(
                f,
                "{} holds an interrupted run (resume it, or start over with `force`)",
                partial.display()
            ),
            Self::NotADirectory { target, what } => write!(
                f,
                "output directory {} is {what}, not a directory: flocking never replaces it; choose another output directory",
                target.display()
            ),
            Self::Dir(e) => write!(f, "{e}"),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for CreateError {}

impl From<DirError> for CreateError {
    fn from(e: DirError) -> Self {
        match e {
            DirError::Io(e) => Self::Io(e),
            e => Self::Dir(e),
        }
    }
}

impl From<io::Error> for CreateError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

/// Why a run directory cannot be resumed.
#[derive(Debug)]
pub enum ResumeError {
    /// There is no interrupted run at `partial`.
    Nothing {
        /// `DIR.partial`, which does not exist.
        partial: PathBuf,
        /// `DIR`.
        target: PathBuf,
        /// Whether `DIR` holds a complete run.
        complete: bool,
    },
    /// `DIR` holds a complete run whose finishing was cut short after its rename (a second
    /// SIGTERM, a kill): its leftover checkpoint and note have now been removed.
    Tidied {
        /// `DIR`.
        target: PathBuf,
    },
    /// The run cannot be resumed; the message says why and what to do.
    Refused(String),
    /// The directory's `scenario.ron` no longer loads.
    Scenario(ScenarioError),
    /// Another process is writing the directory.
    Dir(DirError),
    /// Reading or cutting back the files failed.
    Io(io::Error),
}

impl std::fmt::Display for ResumeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Nothing {
                partial,
                target,
                complete,
            } => {
                if *complete {
                    write!(
                        f,
                        "{} holds a complete run: there is nothing to resume",
                        target.display()
                    )
                } else {
                    write!(f, "there is no interrupted run at {}", partial.display())
                }
            }
            Self::Tidied { target } => write!(
                f,
                "{} holds a complete run whose finishing was cut short: its leftover checkpoint and {INCOMPLETE_FILE} note are removed, there is nothing to resume",
                target.display()
            ),
            Self::Refused(why) => write!(f, "{why}"),
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Dir(e) => write!(f, "{e}"),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ResumeError {}

impl From<DirError> for ResumeError {
    fn from(e: DirError) -> Self {
        match e {
            DirError::Io(e) => Self::Io(e),
            e => Self::Dir(e),
        }
    }
}

impl From<io::Error> for ResumeError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

/// `DIR.partial`.
#[must_use]
pub fn partial_path(target: &Path) -> PathBuf {
    let mut partial = target.as_os_str().to_owned();
    partial.push(".partial");
    PathBuf::from(partial)
}

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
    /// Starts writing the run of `scenario` to `target` with default options but `force`: CSV,
    /// a checkpoint every 1,000 steps.
    ///
    /// # Errors
    /// When `target` holds files and `force` is false, or on any I/O error.
    pub fn create(target: &Path, scenario: &Scenario, force: bool) -> Result<Self, CreateError> {
        Self::create_with(
            target,
            scenario,
            &OutputOptions {
                force,
                ..OutputOptions::default()
            },
        )
    }

    /// Starts writing the run of `scenario` to `target`. An existing non-empty `target` is
    /// refused unless it carries flocking's marker and `options.force` is set (it is then
    /// replaced when the run finishes); `DIR.partial` is refused while another process writes
    /// it, and replaced only with `options.force` and only if flocking wrote it. Nothing is
    /// removed that flocking did not write ([`owned::remove`]).
    ///
    /// # Errors
    /// [`CreateError::Occupied`], [`CreateError::Interrupted`], [`CreateError::Dir`] (not
    /// flocking's, or being written), or an I/O error naming its path (the new directory is then
    /// removed, everything else left as it was).
    pub fn create_with(
        target: &Path,
        scenario: &Scenario,
        options: &OutputOptions,
    ) -> Result<Self, CreateError> {
        // `newdir/` is `newdir` (issue 27: else `DIR.partial` would be `newdir/.partial`)
        let target = &normalized(target);
        check_target(target)?;
        let non_empty = fs::read_dir(target).is_ok_and(|mut entries| entries.next().is_some());
        if non_empty {
            owned::check_owned(target, Kind::Run)?;
            if !options.force {
                return Err(CreateError::Occupied {
                    target: target.to_owned(),
                });
            }
            owned::check_removable(target, Kind::Run)?;
        }
        let partial = partial_path(target);
        if fs::symlink_metadata(&partial).is_ok() {
            check_target(&partial)?;
            owned::check_owned(&partial, Kind::Run)?;
            let lock = DirLock::acquire(&partial)?;
            if !options.force {
                return Err(CreateError::Interrupted {
                    partial,
                    target: target.to_owned(),
                });
            }
            owned::remove(&partial, Kind::Run)?;
            drop(lock);
        }
        let this = Self::create_in(target, partial, scenario, options)?;
        // Holding `DIR.partial`, no other run can finish into `DIR`; one that finished between
        // the check above and the rename into `DIR.partial` left `DIR` behind (issue 27: two
        // runs started together): this run is refused, its own new directory removed.
        let appeared = fs::read_dir(target).is_ok_and(|mut entries| entries.next().is_some());
        if appeared && !options.force {
            let partial = this.partial.clone();
            drop(this);
            owned::remove(&partial, Kind::Run)?;
            return Err(CreateError::Occupied {
                target: target.to_owned(),
            });
        }
        Ok(this)
    }

    /// [`RunDirectory::create_with`] once `target` may be written.
    fn create_in(
        target: &Path,
        partial: PathBuf,
        scenario: &Scenario,
        options: &OutputOptions,
    ) -> Result<Self, DirError> {
        // The directory is prepared under another name and appears as `DIR.partial` with its
        // marker, lock, `INCOMPLETE` note and scenario already inside.
        // One name per process: two runs started together into the same `DIR` each prepare
        // their own, and the rename to `DIR.partial` picks one (issue 27).
        let mut staging = partial.clone().into_os_string();
        staging.push(format!(".new-{}", std::process::id()));
        let staging = PathBuf::from(staging);
        remove_stale_staging(&partial);
        fs::create_dir_all(parent_of(&staging))
            .map_err(at(format_args!("create {}", parent_of(&staging).display())))?;
        fs::create_dir(&staging).map_err(at(format_args!("create {}", staging.display())))?;
        let prepared = Self::prepare(target, &staging, &partial, scenario, options);
        if prepared.is_err() {
            // only what this call created: the marker makes it removable
            let _ = owned::remove(&staging, Kind::Run);
        }
        prepared
    }

    /// Fills the new directory `staging` and renames it to `partial`.
    fn prepare(
        target: &Path,
        staging: &Path,
        partial: &Path,
        scenario: &Scenario,
        options: &OutputOptions,
    ) -> Result<Self, DirError> {
        owned::mark(staging, Kind::Run)?;
        let lock = DirLock::acquire(staging)?;
        write_incomplete(staging, &running_note(target, options.force))?;
        let text = scenario.to_ron().map_err(io::Error::other)? + "\n";
        write_durably(&staging.join("scenario.ron"), text.as_bytes())?;
        let mut this = Self::start_files(
            target,
            staging.to_owned(),
            scenario,
            options.format,
            options,
            lock,
        )?;
        this.force = options.force;
        sync_dir(staging).map_err(at(format_args!("flush {}", staging.display())))?;
        // The open files follow the directory's rename; a `DIR.partial` that another process
        // created meanwhile makes it fail.
        rename_no_replace(staging, partial).map_err(|e| {
            if e.kind() == io::ErrorKind::AlreadyExists {
                // another process started a run into the same `DIR` at the same time, and won
                DirError::Busy {
                    dir: partial.to_owned(),
                    holder: "another flocking process, started at the same time".into(),
                }
            } else {
                at(format_args!(
                    "rename {} to {}",
                    staging.display(),
                    partial.display()
                ))(e)
                .into()
            }
        })?;
        this.partial = partial.to_owned();
        this.lock.moved_to(partial);
        sync_dir(parent_of(partial))
            .map_err(at(format_args!("flush {}", parent_of(partial).display())))?;
        Ok(this)
    }

    /// Writes the headers of fresh output files into `partial`.
    fn start_files(
        target: &Path,
        partial: PathBuf,
        scenario: &Scenario,
        format: TrajectoryFormat,
        options: &OutputOptions,
        lock: DirLock,
    ) -> io::Result<Self> {
        let metrics_path = partial.join("metrics.csv");
        let metrics = File::create(&metrics_path)
            .map_err(at(format_args!("create {}", metrics_path.display())))?;
        let trajectory = match format {
            TrajectoryFormat::Csv => {
                let header = trajectory_csv_header(scenario);
                let path = partial.join("trajectory.csv");
                let file = File::create(&path)
                    .and_then(|mut file| file.write_all(header.as_bytes()).map(|()| file))
                    .map_err(at(format_args!("write {}", path.display())))?;
                Trajectory::Csv {
                    file,
                    bytes: header.len() as u64,
                }
            }
            TrajectoryFormat::Npy => {
                let (descr, row_bytes) = trajectory_dtype(
                    scenario.agents,
                    scenario.dim,
                    scenario.vehicle.state_columns(scenario.dim).len(),
                    marks_failed(scenario),
                );
                let path = partial.join("trajectory.npy");
                Trajectory::Npy(
                    NpyFile::create(&path, descr, row_bytes)
                        .map_err(at(format_args!("write {}", path.display())))?,
                )
            }
        };
        Ok(Self {
            target: target.to_owned(),
            partial,
            metrics,
            metrics_bytes: 0,
            trajectory,
            records: 0,
            dim: scenario.dim,
            checkpoint_every: options.checkpoint_every,
            buffer: Vec::new(),
            last_state: Vec::new(),
            vehicle_columns: scenario.vehicle.state_columns(scenario.dim),
            marks_failed: marks_failed(scenario),
            columns: None,
            agents: scenario.agents,
            criteria: FlockingCriteria::default(),
            verdict_kind: VerdictKind::of(&scenario.algorithm),
            scenario: scenario.to_ron().map_err(io::Error::other)?,
            force: false,
            empty_target: is_empty_dir(target),
            lock,
            controls: None,
        })
    }

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
    /// with controls from elsewhere records them in [`CONTROLS_FILE`]
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

    /// Records in [`CONTROLS_FILE`] that the run's inputs come from `source` (e.g. "Python
    /// controls `f`"), not from the scenario's protocol: a resume must supply them
    /// ([`RunDirectory::resume_with_controls`]). The file stays in the finished `DIR`.
    ///
    /// # Errors
    /// Any I/O error, with its path.
    pub fn record_controls(&mut self, source: &str) -> io::Result<()> {
        let line = source.replace('\n', " ");
        write_durably(
            &self.partial.join(CONTROLS_FILE),
            format!("{CONTROLS_PREFIX}{line}\n").as_bytes(),
        )?;
        sync_dir(&self.partial).map_err(at(format_args!("flush {}", self.partial.display())))?;
        self.controls = Some(line);
        Ok(())
    }

    /// Where the run's inputs come from, when not from the scenario's protocol
    /// ([`RunDirectory::record_controls`]).
    #[must_use]
    pub fn controls(&self) -> Option<&str> {
        self.controls.as_deref()
    }

    /// Judges the finished run by `criteria` in [`VERDICT_FILE`] (default: the last quarter,
    /// ε₁ = ε₂ = 0.01).
    #[must_use]
    pub const fn with_criteria(mut self, criteria: FlockingCriteria) -> Self {
        self.criteria = criteria;
        self
    }

    /// The directory being written, `DIR.partial`.
    #[must_use]
    pub fn partial(&self) -> &Path {
        &self.partial
    }

    /// Writes `final.csv` and [`VERDICT_FILE`] and moves the directory into place: renames
    /// `DIR.partial` to `DIR`, then removes its checkpoint and `INCOMPLETE` note. A `DIR` is
    /// replaced only if it was empty when the run started and still is, or if `force` was set
    /// and it is flocking's ([`owned::remove`]); a `DIR` that appeared during the run is never
    /// renamed over (the rename itself refuses an existing `DIR`: it is made with `RENAME_NOREPLACE`).
    ///
    /// # Errors
    /// Any I/O error, naming the operation and the path; `DIR.partial` is then kept with its
    /// records, its checkpoint and its note, resumable (the message says how).
    pub fn finish(mut self) -> io::Result<Finished> {
        let verdict = self.complete().map_err(|e| {
            io::Error::new(
                e.kind(),
                format!(
                    "{e}\nthe run is kept in {}; once that is fixed, finish it with `flocking run --resume {}`",
                    self.partial.display(),
                    self.target.display()
                ),
            )
        })?;
        Ok(Finished {
            path: self.target.clone(),
            verdict,
        })
    }

    fn complete(&mut self) -> io::Result<Option<Verdict>> {
        let header = agent_header(self.dim, self.vehicle_columns, self.marks_failed);
        let mut last = format!("{}\n", header[1..].join(",")).into_bytes();
        let coordinates = self.row_width();
        for (i, state) in self.last_state.chunks_exact(coordinates).enumerate() {
            write_state(&mut last, i, state);
        }
        write_durably(&self.partial.join("final.csv"), &last)?;
        self.sync_outputs()?;
        let verdict = judge_metrics_file(
            &self.partial.join("metrics.csv"),
            self.agents,
            self.verdict_kind,
            &self.criteria,
        )?;
        let text = verdict_text(verdict.as_ref(), self.verdict_kind, &self.criteria);
        write_durably(&self.partial.join(VERDICT_FILE), text.as_bytes())?;
        // every file of the run, by size and content, once none will change (issue 27)
        owned::record_manifest(&self.partial)?;
        self.clear_target()?;
        // a `DIR` that appears between the check and the rename is not renamed over
        rename_no_replace(&self.partial, &self.target).map_err(|e| {
            if e.kind() == io::ErrorKind::AlreadyExists {
                io::Error::new(
                    e.kind(),
                    format!(
                        "cannot rename {} to {}: {} appeared during the run; move it away",
                        self.partial.display(),
                        self.target.display(),
                        self.target.display()
                    ),
                )
            } else {
                at(format_args!(
                    "rename {} to {}",
                    self.partial.display(),
                    self.target.display()
                ))(e)
            }
        })?;
        self.lock.moved_to(&self.target);
        let parent = parent_of(&self.target);
        sync_dir(parent).map_err(at(format_args!("flush {}", parent.display())))?;
        // with the temporary files a failed write (a full disk) may have left
        owned::remove_own_files(&self.target, Kind::Run, &RUN_LEFTOVERS)
            .map_err(io::Error::other)?;
        Ok(verdict)
    }

    /// Makes way for the rename to `DIR`: removes a `DIR` that was empty when the run started
    /// and still is, or with `force` one that flocking wrote; refuses any other, even an empty
    /// one that appeared during the run.
    fn clear_target(&self) -> io::Result<()> {
        let target = &self.target;
        if fs::symlink_metadata(target).is_err() {
            return Ok(());
        }
        // `remove_dir` removes only an empty directory, atomically.
        if self.empty_target && fs::remove_dir(target).is_ok() {
            return Ok(());
        }
        let refused = |why: String| {
            io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!(
                    "cannot rename {} to {}: {why}",
                    self.partial.display(),
                    target.display()
                ),
            )
        };
        if !self.force {
            return Err(refused(format!(
                "{} appeared during the run; move it away",
                target.display()
            )));
        }
        owned::remove(target, Kind::Run).map_err(|e| match e {
            DirError::Io(e) => e,
            e => refused(e.to_string()),
        })
    }

    /// Flushes `metrics.csv` and the trajectory to the disk.
    fn sync_outputs(&self) -> io::Result<()> {
        self.metrics
            .sync_data()
            .and_then(|()| match &self.trajectory {
                Trajectory::Csv { file, .. } => file.sync_data(),
                Trajectory::Npy(file) => file.sync_data(),
            })
            .map_err(at(format_args!(
                "flush the records in {}",
                self.partial.display()
            )))
    }

    /// Abandons the run: removes the partial directory (flocking's, [`owned::remove`]).
    pub fn abandon(self) {
        let _ = owned::remove(&self.partial, Kind::Run);
    }

    /// Keeps the partial directory, its records and its last checkpoint, and says in its
    /// `INCOMPLETE` file why the run stopped; `resumable` tells whether `flocking run --resume` may
    /// continue it. Returns the partial directory.
    ///
    /// # Errors
    /// When the note cannot be written.
    pub fn keep_incomplete(self, why: &str, resumable: bool) -> io::Result<PathBuf> {
        let note = if resumable {
            format!(
                "incomplete: {why}\nEvery record in this directory is complete up to the last one written.\nResume: flocking run --resume {}\n{}",
                self.target.display(),
                force_line(self.force)
            )
        } else {
            format!(
                "{FAILED}: {why}\nEvery record in this directory is complete up to the last one written; the run cannot be resumed.\n"
            )
        };
        write_incomplete(&self.partial, &note)?;
        Ok(self.partial)
    }
}

/// Whether the trajectory and `final.csv` of `scenario` mark each agent `failed`: its conditions
/// have `faults` (issue 28; the column's sum at a record is `metrics.csv`'s `failed`).
fn marks_failed(scenario: &Scenario) -> bool {
    scenario.conditions.faults.is_some()
}

/// The columns of a trajectory row: [`trajectory_header_with`], then [`FAILED_COLUMN`] when
/// `failed`.
fn agent_header(dim: usize, vehicle: &[&str], failed: bool) -> Vec<String> {
    let mut header = trajectory_header_with(dim, vehicle);
    if failed {
        header.push(FAILED_COLUMN.to_owned());
    }
    header
}

/// The header line of the `trajectory.csv` of `scenario`.
fn trajectory_csv_header(scenario: &Scenario) -> String {
    let vehicle = scenario.vehicle.state_columns(scenario.dim);
    format!(
        "{}\n",
        agent_header(scenario.dim, vehicle, marks_failed(scenario)).join(",")
    )
}

/// The header line of `metrics.csv` with the diagnostic columns `columns`.
fn metrics_header(columns: &[String]) -> String {
    let mut header = String::from(METRICS_HEADER);
    for column in columns {
        header.push(',');
        header.push_str(column);
    }
    header.push('\n');
    header
}

/// The diagnostic columns of the header of the `metrics.csv` at `path`: the names after those of
/// [`METRICS_HEADER`].
fn diagnostic_columns(path: &Path) -> io::Result<Vec<String>> {
    let text = fs::read_to_string(path).map_err(at(format_args!("read {}", path.display())))?;
    let header = text.lines().next().unwrap_or_default();
    let Some(rest) = header.strip_prefix(METRICS_HEADER) else {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "{} does not start with the header {METRICS_HEADER}",
                path.display()
            ),
        ));
    };
    Ok(rest
        .split(',')
        .filter(|name| !name.is_empty())
        .map(str::to_owned)
        .collect())
}

/// Writes `bytes` to `path` and flushes them to the disk.
fn write_durably(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let write = || {
        let mut file = File::create(path)?;
        file.write_all(bytes)?;
        file.sync_all()
    };
    write().map_err(at(format_args!("write {}", path.display())))
}

/// The checkpoint must be of `scenario` (the run's `scenario.ron`): the same resolved scenario,
/// and a state of its agents in its dimension.
fn check_scenario(
    checkpoint: &Checkpoint,
    scenario: &Scenario,
    partial: &Path,
) -> Result<(), ResumeError> {
    let started: Scenario = checkpoint.scenario.parse().map_err(ResumeError::Scenario)?;
    if started != *scenario {
        return Err(ResumeError::Refused(format!(
            "{} was edited after the run started (changed: {}); resuming would continue one scenario with another. Undo the edit, or start a new run with --out elsewhere",
            partial.join("scenario.ron").display(),
            changed_fields(&started, scenario).join(", ")
        )));
    }
    // the draws of an older flocking cannot continue the run's: its random numbers came from
    // ChaCha8 (before issue 31's Philox4x32-10), its normal ones from Box–Muller (before the
    // ziggurat), or each link's from a block of its own (before a receiver's links shared them)
    let older_draws = if checkpoint.draws <= DrawsOf::ChaCha8 && scenario.draws_at_random() {
        Some(
            "drew its random numbers with ChaCha8; this one draws them with Philox4x32-10, so the run's random draws",
        )
    } else if checkpoint.draws <= DrawsOf::BoxMuller && scenario.draws_normals() {
        Some(
            "drew its normal random numbers by Box–Muller; this one draws them by the ziggurat, so the run's noise",
        )
    } else if checkpoint.draws <= DrawsOf::BlockPerLink && scenario.draws_per_link() {
        Some(
            "drew each link's packet loss and jitter from a block of its own; this one draws a receiver's links from its shared blocks, so the run's losses and jitter",
        )
    } else {
        None
    };
    if let Some(why) = older_draws {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} was written by a flocking that {why} cannot continue bit for bit. Resume it with the flocking that started it, or start the run again with --out elsewhere",
            partial.display()
        )));
    }
    // issue 27: a step count past the scenario's end would stop the output short and judge it
    if checkpoint.start.steps > scenario.steps() {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} is at step {}, past the scenario's last step {}: it is not a checkpoint of this run; start a new run with --out elsewhere",
            partial.display(),
            checkpoint.start.steps,
            scenario.steps()
        )));
    }
    // t = 0, every `record_every` steps, and the last step
    let records_bound = checkpoint.start.steps / scenario.record_every.max(1) + 2;
    if checkpoint.records > records_bound {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} counts {} records after step {}, more than the {records_bound} a run records by then: it is not a checkpoint of this run",
            partial.display(),
            checkpoint.records,
            checkpoint.start.steps
        )));
    }
    if checkpoint.dim == scenario.dim
        && checkpoint.start.positions.len() == scenario.agents * scenario.dim
        && checkpoint.start.velocities.len() == checkpoint.start.positions.len()
    {
        return Ok(());
    }
    Err(ResumeError::Refused(format!(
        "the checkpoint in {} is of {} coordinates in {}D, not of this scenario's {} agents in {}D",
        partial.display(),
        checkpoint.start.positions.len(),
        checkpoint.dim,
        scenario.agents,
        scenario.dim
    )))
}

/// The dotted paths of the fields whose values differ between `a` and `b`, as
/// [`Scenario::value`] names them (an enum's variant passed through; a changed variant is named
/// by the field that holds it).
fn changed_fields(a: &Scenario, b: &Scenario) -> Vec<String> {
    use serde_json::Value;
    /// The tag and content of an externally tagged enum value `{"Variant": content}`.
    fn variant(map: &serde_json::Map<String, Value>) -> Option<(&String, &Value)> {
        (map.len() == 1)
            .then(|| map.iter().next())
            .flatten()
            .filter(|(tag, _)| tag.starts_with(|c: char| c.is_ascii_uppercase()))
    }
    fn walk(path: &str, a: &Value, b: &Value, out: &mut Vec<String>) {
        let join = |key: &str| {
            if path.is_empty() {
                key.to_owned()
            } else {
                format!("{path}.{key}")
            }
        };
        match (a, b) {
            _ if a == b => {}
            (Value::Object(x), Value::Object(y)) => match (variant(x), variant(y)) {
                (Some((tx, vx)), Some((ty, vy))) if tx == ty => walk(path, vx, vy, out),
                (Some(_), _) | (_, Some(_)) => out.push(path.to_owned()),
                (None, None) => {
                    let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
                    keys.sort();
                    keys.dedup();
                    for key in keys {
                        let null = Value::Null;
                        let (u, v) = (x.get(key).unwrap_or(&null), y.get(key).unwrap_or(&null));
                        walk(&join(key), u, v, out);
                    }
                }
            },
            (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
                for (i, (u, v)) in x.iter().zip(y).enumerate() {
                    walk(&join(&i.to_string()), u, v, out);
                }
            }
            _ => out.push(path.to_owned()),
        }
    }
    let tree = |s: &Scenario| serde_json::to_value(s).expect("a scenario serializes");
    let mut out = Vec::new();
    walk("", &tree(a), &tree(b), &mut out);
    out
}

/// The note of a directory being written.
fn running_note(target: &Path, force: bool) -> String {
    format!(
        "incomplete: the run is in progress (flocking process {}), or was killed.\nA process killed while writing may leave its last record cut; `flocking run --resume` removes it.\nResume a killed run: flocking run --resume {}\n{}",
        std::process::id(),
        target.display(),
        force_line(force)
    )
}

/// The file of a run directory that records where the run's inputs came from when not from the
/// scenario's protocol (Python's `controls=f`).
pub const CONTROLS_FILE: &str = "controls.txt";

/// The start of [`CONTROLS_FILE`]'s line.
const CONTROLS_PREFIX: &str = "inputs from ";

/// The source of the controls recorded in `partial` ([`CONTROLS_FILE`]), if any.
fn read_controls(partial: &Path) -> Result<Option<String>, ResumeError> {
    use std::io::Read as _;
    let path = partial.join(CONTROLS_FILE);
    let file = match File::open(&path) {
        Ok(file) => file,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(at(format_args!("read {}", path.display()))(e).into()),
    };
    let mut text = String::new();
    file.take(4096)
        .read_to_string(&mut text)
        .map_err(at(format_args!("read {}", path.display())))?;
    let line = text.trim_end();
    Ok(Some(
        line.strip_prefix(CONTROLS_PREFIX)
            .unwrap_or(line)
            .to_owned(),
    ))
}

/// The line of the `INCOMPLETE` note of a run started with `force`: it replaces its `DIR`, if
/// flocking's, when it completes, also after a resume.
const FORCE_LINE: &str =
    "With --force: the run replaces the earlier run in its directory when it completes.";

/// [`FORCE_LINE`] with its line break, or nothing.
fn force_line(force: bool) -> String {
    if force {
        format!("{FORCE_LINE}\n")
    } else {
        String::new()
    }
}

/// Finishes what [`RunDirectory::finish`] left undone when killed right after renaming
/// The files of a running or interrupted run that a complete run does not keep, the note last:
/// removed by the final rename's tidy-up and by a resume that finds the rename done.
const RUN_LEFTOVERS: [&str; 5] = [
    CHECKPOINT_FILE,
    CHECKPOINT_TMP,
    INCOMPLETE_TMP,
    owned::MANIFEST_TMP,
    INCOMPLETE_FILE,
];

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

/// `path` without a trailing slash or `.` components (`newdir/` is `newdir`).
fn normalized(path: &Path) -> PathBuf {
    let path: PathBuf = path.components().collect();
    if path.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        path
    }
}

/// Refuses an output path that exists but is not a directory (a file, a FIFO, a device such as
/// `/dev/null`, a link, even one to a directory or a dangling one), before anything is written.
fn check_target(target: &Path) -> Result<(), CreateError> {
    let Ok(meta) = fs::symlink_metadata(target) else {
        return Ok(());
    };
    let file_type = meta.file_type();
    let what = {
        use std::os::unix::fs::FileTypeExt as _;
        if file_type.is_dir() {
            return Ok(());
        } else if file_type.is_symlink() {
            if fs::metadata(target).is_ok() {
                "a link"
            } else {
                "a dangling link"
            }
        } else if file_type.is_file() {
            "a file"
        } else if file_type.is_fifo() {
            "a FIFO"
        } else if file_type.is_char_device() || file_type.is_block_device() {
            "a device"
        } else {
            "a socket"
        }
    };
    Err(CreateError::NotADirectory {
        target: target.to_owned(),
        what,
    })
}

/// Removes the staging directories `DIR.partial.new-<pid>` of runs killed while preparing, each
/// only under flocking's marker, holding only files a run writes ([`owned::remove`]) and with
/// its lock free: one noted `INCOMPLETE` (its writer took its lock first), or one killed before
/// its note, when its process is gone (no `/proc/<pid>`, Linux).
///
/// A staging directory of a live process is locked, or not yet noted with its process alive,
/// and kept; so is anything without the marker, even empty (a process killed between creating
/// it and marking it leaves an empty directory, which is not known to be flocking's).
fn remove_stale_staging(partial: &Path) {
    let Some(name) = partial
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
    else {
        return;
    };
    let prefix = format!("{name}.new");
    let Ok(entries) = fs::read_dir(parent_of(partial)) else {
        return;
    };
    for entry in entries.flatten() {
        let entry_name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = entry_name.strip_prefix(&prefix) else {
            continue;
        };
        let staging = entry.path();
        let noted = fs::symlink_metadata(staging.join(INCOMPLETE_FILE)).is_ok_and(|m| m.is_file());
        if !noted && process_alive(pid.trim_start_matches('-')) {
            continue;
        }
        if !owned::marked(&staging, Kind::Run) {
            continue;
        }
        if let Ok(lock) = DirLock::acquire(&staging) {
            let _ = owned::remove(&staging, Kind::Run);
            drop(lock);
        }
    }
}

/// Whether the process `pid` (decimal) may still be running: false only when it is a number and
/// `/proc` shows no such process (Linux); an unreadable name or another platform counts as alive.
fn process_alive(pid: &str) -> bool {
    let proc = Path::new("/proc");
    match pid.parse::<u32>() {
        Ok(pid) if proc.join("self").exists() => proc.join(pid.to_string()).exists(),
        _ => true,
    }
}

/// Replaces the `INCOMPLETE` note atomically.
fn write_incomplete(partial: &Path, note: &str) -> io::Result<()> {
    let temporary = partial.join(INCOMPLETE_TMP);
    write_durably(&temporary, note.as_bytes())?;
    let note = partial.join(INCOMPLETE_FILE);
    fs::rename(&temporary, &note).map_err(at(format_args!(
        "rename {} to {}",
        temporary.display(),
        note.display()
    )))?;
    sync_dir(partial).map_err(at(format_args!("flush {}", partial.display())))
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

/// Whether agent `i` of `state` has failed (never, when its run marks no failures).
fn failed(state: &State<'_>, i: usize) -> bool {
    state.failed.as_ref().is_some_and(|failed| failed[i])
}

/// Appends `id,x,y[,z],vx,vy[,vz]` of agent `i` (shortest round-trip decimal forms).
fn write_state(out: &mut Vec<u8>, i: usize, state: &[f64]) {
    // Writing to a Vec cannot fail.
    let _ = write!(out, "{i}");
    for x in state {
        let _ = write!(out, ",{x}");
    }
    out.push(b'\n');
}

impl RunDirectory {
    /// The values of one agent's row after its id: q, p, the vehicle's state, `failed`.
    const fn row_width(&self) -> usize {
        2 * self.dim + self.vehicle_columns.len() + self.marks_failed as usize
    }

    /// Writes the header of `metrics.csv` with the first record's diagnostic columns, or checks
    /// that a later record names the same columns.
    fn check_columns(&mut self, record: &Record<'_>) -> io::Result<()> {
        let names = record.diagnostics.iter().map(|(name, _)| *name);
        match &self.columns {
            Some(columns) if names.clone().eq(columns.iter().map(String::as_str)) => Ok(()),
            Some(columns) => Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "the record at t = {} has the diagnostic columns {:?} where metrics.csv has {columns:?}",
                    record.t,
                    names.collect::<Vec<_>>()
                ),
            )),
            None => {
                let columns: Vec<String> = names.map(str::to_owned).collect();
                let header = metrics_header(&columns);
                self.metrics
                    .write_all(header.as_bytes())
                    .map_err(at(format_args!(
                        "write {}",
                        self.partial.join("metrics.csv").display()
                    )))?;
                self.metrics_bytes += header.len() as u64;
                self.columns = Some(columns);
                Ok(())
            }
        }
    }
}

impl Recorder for RunDirectory {
    type Error = io::Error;

    fn record(&mut self, record: &Record<'_>) -> io::Result<()> {
        self.check_columns(record)?;
        let m = &record.metrics;
        let mut line = record.t.to_string();
        for value in m.reals() {
            let _ = write!(line, ",{value}");
        }
        let _ = write!(line, ",{},{}", m.collisions, record.energy);
        for value in m.extras() {
            let _ = write!(line, ",{value}");
        }
        let _ = write!(line, ",{}", m.components);
        for (_, value) in record.diagnostics {
            let _ = write!(line, ",{value}");
        }
        line.push('\n');
        let state = &record.state;
        let dim = state.dim;
        let width = state.vehicle_columns.len();
        self.last_state.clear();
        for (i, (q, p)) in state
            .positions
            .chunks_exact(dim)
            .zip(state.velocities.chunks_exact(dim))
            .enumerate()
        {
            self.last_state.extend_from_slice(q);
            self.last_state.extend_from_slice(p);
            self.last_state
                .extend_from_slice(&state.vehicle[i * width..(i + 1) * width]);
            if self.marks_failed {
                self.last_state.push(f64::from(u8::from(failed(state, i))));
            }
        }
        let row = self.row_width();
        match &mut self.trajectory {
            Trajectory::Csv { file, bytes } => {
                self.buffer.clear();
                for (i, agent) in self.last_state.chunks_exact(row).enumerate() {
                    let _ = write!(self.buffer, "{},", record.t);
                    write_state(&mut self.buffer, i, agent);
                }
                file.write_all(&self.buffer).map_err(at(format_args!(
                    "write {}",
                    self.partial.join("trajectory.csv").display()
                )))?;
                *bytes += self.buffer.len() as u64;
            }
            Trajectory::Npy(file) => {
                self.buffer.clear();
                self.buffer.extend_from_slice(&record.t.to_le_bytes());
                for rows in [&state.positions, &state.velocities, &state.vehicle] {
                    for x in rows.iter() {
                        self.buffer.extend_from_slice(&x.to_le_bytes());
                    }
                }
                if self.marks_failed {
                    let agents = state.agents();
                    self.buffer
                        .extend((0..agents).map(|i| u8::from(failed(state, i))));
                }
                file.append(&self.buffer).map_err(at(format_args!(
                    "write {}",
                    self.partial.join("trajectory.npy").display()
                )))?;
            }
        }
        self.metrics
            .write_all(line.as_bytes())
            .map_err(at(format_args!(
                "write {}",
                self.partial.join("metrics.csv").display()
            )))?;
        self.metrics_bytes += line.len() as u64;
        self.records += 1;
        Ok(())
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.checkpoint_every > 0 && steps.is_multiple_of(self.checkpoint_every)
    }

    fn checkpoint(&mut self, start: &Start) -> io::Result<()> {
        // the records the checkpoint counts are on the disk before it is
        self.sync_outputs()?;
        let trajectory_bytes = match &self.trajectory {
            Trajectory::Csv { bytes, .. } => *bytes,
            Trajectory::Npy(file) => file.rows(),
        };
        let counts = Counts {
            dim: self.dim,
            records: self.records,
            metrics_bytes: self.metrics_bytes,
            trajectory_bytes,
        };
        write_checkpoint(&self.partial, &counts, start, &self.scenario)?;
        let whole = format!(
            "{}Whole records, checkpointed after step {}: {} (the first {} bytes of metrics.csv; of the trajectory, {} {}).\n",
            running_note(&self.target, self.force),
            start.steps,
            self.records,
            self.metrics_bytes,
            trajectory_bytes,
            match self.trajectory {
                Trajectory::Csv { .. } => "bytes",
                Trajectory::Npy(_) => "records",
            }
        );
        write_incomplete(&self.partial, &whole)
    }
}

#[cfg(test)]
mod tests {
    use flock_metrics::FlockMetrics;

    use super::METRICS_HEADER;
    use crate::run_dir::TIME;

    /// The header names what a record writes, in its order: t, [`FlockMetrics::reals`], the
    /// collisions, the energy, [`FlockMetrics::extras`] and the components.
    #[test]
    fn the_metrics_header_names_the_recorded_values() {
        let names: Vec<&str> = std::iter::once(TIME)
            .chain(FlockMetrics::REAL_COLUMNS)
            .chain(["collisions", "energy"])
            .chain(FlockMetrics::EXTRA_COLUMNS)
            .chain(["components"])
            .collect();
        assert_eq!(METRICS_HEADER, names.join(","));
    }

    /// Issue 20: a `DIR` that appears between the last check and the rename of `DIR.partial`
    /// to it, even an empty one, is kept, and so is `DIR.partial`.
    #[test]
    fn issue_20_the_finishing_rename_never_replaces_a_directory_that_appeared() {
        let tmp = std::env::temp_dir().join(format!("flocking-noreplace-{}", std::process::id()));
        let (partial, target) = (tmp.join("d.partial"), tmp.join("d"));
        // new directories only: nothing that was there before is touched, nor removed below
        std::fs::create_dir(&tmp).expect("a new directory");
        std::fs::create_dir(&partial).expect("mkdir");
        std::fs::write(partial.join("metrics.csv"), "t\n").expect("a record");
        std::fs::create_dir(&target).expect("an empty DIR appears");
        let error = super::rename_no_replace(&partial, &target).expect_err("refused");
        assert_eq!(error.kind(), std::io::ErrorKind::AlreadyExists, "{error}");
        assert!(target.is_dir() && std::fs::read_dir(&target).expect("ls").next().is_none());
        assert_eq!(
            std::fs::read(partial.join("metrics.csv")).expect("kept"),
            b"t\n"
        );
        std::fs::remove_dir(&target).expect("the user moves it away");
        super::rename_no_replace(&partial, &target).expect("renamed");
        assert!(target.join("metrics.csv").is_file() && !partial.exists());
        // what this test made, one by one (remove_dir refuses a directory that is not empty):
        // the record it wrote, checked first
        assert_eq!(
            std::fs::read(target.join("metrics.csv")).expect("the record"),
            b"t\n"
        );
        std::fs::remove_file(target.join("metrics.csv")).expect("clean");
        std::fs::remove_dir(&target).expect("clean");
        std::fs::remove_dir(&tmp).expect("clean");
    }
}
