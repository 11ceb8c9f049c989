//! A sweep's output directory:
//!
//! | file | contents |
//! | --- | --- |
//! | `sweep.ron` | the sweep, base inlined ([`super::Sweep::to_ron`]); a directory holds one sweep |
//! | `rows/<index>-<id>.csv` | one finished run: its `runs.csv` line, then its wall time |
//! | `runs.csv` | the header and every finished run's line, in run order |
//! | `times.csv` | `run,id,wall_time` of every finished run, in run order |
//! | `runs/<id>/` | with `--keep-runs`, each run's directory as `flocking run` writes it |
//! | `.flocking`, `.flocking.lock` | flocking's marker, and the lock of the process writing it ([`crate::owned`]) |
//!
//! A directory is written only when it is new, empty or marked as a sweep's: a user's `runs.csv`
//! is never replaced, not even in a copy of a sweep's directory that lacks the marker. The
//! writer holds the directory's lock from [`prepare`] to its end, so that a second sweep or merge
//! into it is refused while the first one writes.
//!
//! A row file is written to a temporary name, synced and renamed, so that a sweep killed at any
//! moment leaves whole rows only; the same command then skips the runs it finds and assembles
//! `runs.csv` from all of them. `runs.csv` is the same bytes whatever the number of workers, the
//! order in which runs finished, the interruptions and the shards: its lines are in run order, and
//! a line depends on its run alone.

use std::collections::BTreeMap;
use std::fs;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use super::row::{RunRow, header};
use super::{Sweep, SweepError};
use crate::owned::{self, DirError, DirLock, Kind};
use crate::storage::fs::sync_dir;

/// The sweep's file in an output directory.
pub const SWEEP_FILE: &str = "sweep.ron";
/// The table of runs.
pub const RUNS_FILE: &str = "runs.csv";
/// The wall times.
pub const TIMES_FILE: &str = "times.csv";
/// The directory of row files.
pub const ROWS_DIR: &str = "rows";
/// The directory of kept runs.
pub const RUNS_DIR: &str = "runs";

/// Why an output directory cannot be used or completed.
#[derive(Debug)]
pub enum StoreError {
    /// A file could not be read or written.
    Io {
        /// The path.
        path: PathBuf,
        /// The error.
        source: io::Error,
    },
    /// The directory holds files flocking did not write, is being written by another process,
    /// or is one flocking never writes.
    Dir(DirError),
    /// The directory holds another sweep.
    OtherSweep(PathBuf),
    /// The directory is not the output directory of a sweep (it has no `sweep.ron`).
    NotASweep(PathBuf),
    /// A shard's `sweep.ron` is not a sweep.
    Sweep(SweepError),
    /// Merging shards that do not hold every run.
    Missing {
        /// How many runs are missing.
        missing: usize,
        /// Of how many.
        total: usize,
        /// The first missing run's index.
        first: usize,
    },
}

impl std::fmt::Display for StoreError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Dir(e) => write!(f, "{e}"),
            Self::NotASweep(dir) => write!(
                f,
                "{} is not the output directory of a sweep (it has no {SWEEP_FILE}); give a directory that flocking sweep --out wrote",
                dir.display()
            ),
            Self::OtherSweep(dir) => write!(
                f,
                "{} holds the results of another sweep ({SWEEP_FILE} differs); choose another output directory",
                dir.display()
            ),
            Self::Sweep(e) => write!(f, "{e}"),
            Self::Missing {
                missing,
                total,
                first,
            } => write!(
                f,
                "{missing} of {total} runs are in no shard (the first is run {first}); merge every shard, or rerun the missing ones"
            ),
        }
    }
}

impl std::error::Error for StoreError {}

impl From<DirError> for StoreError {
    fn from(e: DirError) -> Self {
        Self::Dir(e)
    }
}

impl StoreError {
    /// Whether the command was refused as asked (a directory that is not flocking's or is being
    /// written, another sweep, shards that do not make a sweep: exit code 2), rather than failed
    /// while doing it (an I/O error: exit code 1).
    #[must_use]
    pub const fn is_refusal(&self) -> bool {
        !matches!(self, Self::Io { .. } | Self::Dir(DirError::Io(_)))
    }
}

fn io_error(path: &Path) -> impl FnOnce(io::Error) -> StoreError + '_ {
    move |source| StoreError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `bytes` to `path` through a synced temporary file and a rename.
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    let tmp = path.with_extension("tmp");
    let mut file = fs::File::create(&tmp).map_err(io_error(&tmp))?;
    file.write_all(bytes).map_err(io_error(&tmp))?;
    file.sync_all().map_err(io_error(&tmp))?;
    fs::rename(&tmp, path).map_err(io_error(path))
}

/// Creates `dir` for `sweep`, or opens it again when it holds the same sweep (to resume), and
/// locks it: the returned lock is to be held until the sweep is written.
///
/// `dir` must be new, empty, or marked as a sweep's ([`owned::check_owned`]): a copy without
/// the marker is refused, even one holding this very sweep.
///
/// # Errors
/// [`StoreError::Dir`] for a directory holding files flocking did not write or being written by
/// another process; a directory that holds another sweep; any I/O error.
pub fn prepare(dir: &Path, sweep: &Sweep) -> Result<DirLock, StoreError> {
    let text = sweep.to_ron().map_err(|e| {
        StoreError::Sweep(SweepError::Invalid {
            field: "sweep".into(),
            why: e.to_string(),
        })
    })?;
    let file = dir.join(SWEEP_FILE);
    // Issue 27: a user's copy of a sweep (its `sweep.ron`, an edited `runs.csv`, no marker) is
    // the user's, even when it holds this very sweep.
    owned::check_owned(dir, Kind::Sweep)?;
    fs::create_dir_all(dir).map_err(io_error(dir))?;
    // marked before it is locked, so that a second writer meets the lock, not a stranger's file
    if !owned::marked(dir, Kind::Sweep) {
        owned::mark(dir, Kind::Sweep).map_err(io_error(dir))?;
        // the plots `sweep plot --out` draws here are recorded in it (issue 27)
        owned::start_manifest::<&str>(dir, &[])?;
    }
    let lock = DirLock::acquire(dir)?;
    fs::create_dir_all(dir.join(ROWS_DIR)).map_err(io_error(dir))?;
    match fs::read_to_string(&file) {
        Ok(existing) if existing == text => Ok(lock),
        Ok(_) => Err(StoreError::OtherSweep(dir.to_path_buf())),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            write_atomic(&file, text.as_bytes())?;
            sync_dir(dir).map_err(io_error(dir))?;
            Ok(lock)
        }
        Err(e) => Err(io_error(&file)(e)),
    }
}

/// The sweep of an output directory (its `sweep.ron`).
///
/// # Errors
/// A missing or invalid `sweep.ron`.
pub fn read_sweep(dir: &Path) -> Result<Sweep, StoreError> {
    let file = dir.join(SWEEP_FILE);
    // issue 27: a file given as the directory said "D/sweep.ron: Not a directory (os error 20)"
    let text = fs::read_to_string(&file).map_err(|e| match e.kind() {
        io::ErrorKind::NotFound | io::ErrorKind::NotADirectory => {
            StoreError::NotASweep(dir.to_owned())
        }
        _ => io_error(&file)(e),
    })?;
    Sweep::parse(&text, &file.display().to_string(), dir).map_err(StoreError::Sweep)
}

/// One CSV line of `fields` (quoted where a field holds a comma, a quote or a line break).
fn csv_line(fields: &[String]) -> Vec<u8> {
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    writer
        .write_record(fields)
        .expect("writing to memory cannot fail");
    writer.into_inner().expect("writing to memory cannot fail")
}

fn row_file(dir: &Path, index: usize, id: &str) -> PathBuf {
    dir.join(ROWS_DIR).join(format!("{index:08}-{id}.csv"))
}

/// Records a finished run: its row file, written atomically.
///
/// # Errors
/// Any I/O error.
pub fn write_row(dir: &Path, row: &RunRow) -> Result<(), StoreError> {
    write_fields(dir, row.index, &row.id, &row.fields(), row.wall_time)
}

/// Records a finished run from its fields ([`RunRow::fields`], as a worker of another process
/// returns them): its row file, written atomically.
///
/// # Errors
/// Any I/O error.
pub fn write_fields(
    dir: &Path,
    index: usize,
    id: &str,
    fields: &[String],
    wall_time: f64,
) -> Result<(), StoreError> {
    let mut bytes = csv_line(fields);
    bytes.extend(format!("{wall_time}\n").as_bytes());
    write_atomic(&row_file(dir, index, id), &bytes)
}

/// The runs of `sweep` finished in `dir`: the ids of its row files by run index. Only the names
/// are read: a row file is written whole (under a temporary name, then renamed), so that it
/// exists says that its run is done. A row file whose index is not a run of `sweep`, or whose id
/// is not that run's, is not a row of this sweep and is ignored (issue 27: a stray
/// `rows/00000099-ffff.csv` added a row to `runs.csv`).
///
/// # Errors
/// An unreadable directory.
pub fn finished(dir: &Path, sweep: &Sweep) -> Result<BTreeMap<usize, String>, StoreError> {
    let runs = sweep.runs();
    Ok(row_files(dir)?
        .into_iter()
        .filter_map(|(index, ids)| {
            let id = runs.get(index)?.id(&sweep.axes);
            ids.contains(&id).then_some((index, id))
        })
        .collect())
}

/// The ids of the row files of `dir` by index.
fn row_files(dir: &Path) -> Result<BTreeMap<usize, Vec<String>>, StoreError> {
    let rows = dir.join(ROWS_DIR);
    let mut found = BTreeMap::new();
    let entries = match fs::read_dir(&rows) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(found),
        Err(e) => return Err(io_error(&rows)(e)),
    };
    for entry in entries {
        let name = entry.map_err(io_error(&rows))?.file_name();
        let name = name.to_string_lossy();
        // the temporary file of a killed write has another suffix
        let run = name
            .strip_suffix(".csv")
            .and_then(|stem| stem.split_once('-'))
            .and_then(|(index, id)| Some((index.parse::<usize>().ok()?, id.to_owned())));
        if let Some((index, id)) = run {
            found.entry(index).or_insert_with(Vec::new).push(id);
        }
    }
    Ok(found)
}

/// The `runs.csv` line (with its line break) and the wall time of a row file.
fn read_row(path: &Path) -> Result<(String, String), StoreError> {
    let text = fs::read_to_string(path).map_err(io_error(path))?;
    match text.trim_end_matches('\n').rsplit_once('\n') {
        Some((line, time)) => Ok((format!("{line}\n"), time.to_owned())),
        None => Err(io_error(path)(io::Error::new(
            io::ErrorKind::InvalidData,
            "not a row file (a runs.csv line, then a wall time)",
        ))),
    }
}

/// Writes `runs.csv` and `times.csv` of `dir` from its row files, in run order, and returns how
/// many runs they hold.
///
/// # Errors
/// Any I/O error.
pub fn assemble(dir: &Path, sweep: &Sweep) -> Result<usize, StoreError> {
    let rows = finished(dir, sweep)?;
    let mut runs = csv_line(&header(sweep));
    let mut times = b"run,id,wall_time\n".to_vec();
    for (&index, id) in &rows {
        let (line, wall_time) = read_row(&row_file(dir, index, id))?;
        runs.extend(line.as_bytes());
        times.extend(format!("{index},{id},{wall_time}\n").as_bytes());
    }
    write_atomic(&dir.join(RUNS_FILE), &runs)?;
    write_atomic(&dir.join(TIMES_FILE), &times)?;
    sync_dir(dir).map_err(io_error(dir))?;
    Ok(rows.len())
}

/// Joins the shards' output directories into `out`: their row files copied, `runs.csv` and
/// `times.csv` assembled. Every shard must hold the same sweep, and together every run. `out` is
/// prepared and locked as a sweep's ([`prepare`]).
///
/// # Errors
/// An `out` that is not flocking's or is being written, shards of different sweeps, runs in no
/// shard, any I/O error.
pub fn merge(out: &Path, shards: &[PathBuf]) -> Result<usize, StoreError> {
    let Some(first) = shards.first() else {
        return Err(StoreError::Missing {
            missing: 0,
            total: 0,
            first: 0,
        });
    };
    // a file given as a shard is a refusal, not an I/O error (issue 27)
    if let Some(file) = shards.iter().find(|shard| !shard.is_dir()) {
        return Err(StoreError::NotASweep(file.clone()));
    }
    let sweep = read_sweep(first)?;
    let _lock = prepare(out, &sweep)?;
    for shard in shards {
        if read_sweep(shard)? != sweep {
            return Err(StoreError::OtherSweep(shard.clone()));
        }
        for (index, id) in finished(shard, &sweep)? {
            let from = row_file(shard, index, &id);
            let bytes = fs::read(&from).map_err(io_error(&from))?;
            write_atomic(&row_file(out, index, &id), &bytes)?;
        }
    }
    let total = sweep.runs().len();
    let have = finished(out, &sweep)?;
    let missing: Vec<usize> = (0..total).filter(|k| !have.contains_key(k)).collect();
    if let Some(&first) = missing.first() {
        return Err(StoreError::Missing {
            missing: missing.len(),
            total,
            first,
        });
    }
    assemble(out, &sweep)
}
