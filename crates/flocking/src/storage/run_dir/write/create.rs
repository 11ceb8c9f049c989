//! Starting a run directory ([`RunDirectory::create_with`]): prepared under another name, it
//! appears as `DIR.partial` with its marker, lock, note and scenario inside.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use super::directory::{RunDirectory, partial_path};
use super::errors::CreateError;
use super::note::{INCOMPLETE_FILE, running_note, write_incomplete};
use super::options::OutputOptions;
use crate::scenario::Scenario;
use crate::storage::fs::{at, parent_of, rename_no_replace, sync_dir, write_durably};
use crate::storage::owned::{self, DirError, DirLock, Kind};

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
