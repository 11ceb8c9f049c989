//! The directories flocking writes, and the guards that keep it from touching anything else.
//!
//! - [`mark`]: every directory flocking writes (a run's, a sweep's, the figures') carries a
//!   marker file, [`MARKER_FILE`], naming what wrote it ([`Kind`]).
//! - [`check_owned`]: a directory may be written into only when it is missing, empty or marked
//!   by the same [`Kind`]; otherwise [`DirError::Foreign`] names a file in it that flocking did
//!   not write.
//! - [`remove`] ([`check_removable`]): the only way flocking removes a directory. It refuses the filesystem root, the
//!   working directory and its ancestors, mount points ([`DirError::Special`]), and any directory
//!   without the marker or holding, at any depth, an entry that its [`Kind`] does not write: a
//!   name it never writes, a link, a FIFO, a subdirectory of its `figures/` ([`DirError::Foreign`],
//!   naming it by its relative path, `figures/mine`).
//! - [`check_only_own`]: the same at every depth, for a writer that cuts back and appends to a
//!   directory (`flocking run --resume`).
//! - [`write_no_follow`]: a figure is never written through a link.
//! - [`DirLock`]: an exclusive advisory lock ([`File::try_lock`](std::fs::File::try_lock)) on [`LOCK_FILE`] held by the
//!   writer for as long as it writes; a second writer gets [`DirError::Busy`] with the holder's
//!   process id and start time. The operating system releases the lock when the process dies, so
//!   a stale lock file is simply taken over.
//! - [`write_file`]: a file written where a user names it (a figure, a table) never replaces a
//!   file that flocking did not write, nor one of the files a directory of flocking's is made of
//!   ([`DirError::Reserved`]: a sweep's `runs.csv`).
//! - [`manifest`]: the size and content hash of every file flocking wrote into a directory, at
//!   every depth, so that a file the user saved over one of flocking's names is told from
//!   flocking's ([`DirError::Changed`]) and never replaced or removed.
//! - [`at`]: every I/O error of these paths says what was being done to which path.

mod check;
mod error;
mod kind;
mod lock;
pub mod manifest;
mod marker;
mod names;
mod remove;
mod special;
mod tmp;
mod write;

pub use crate::storage::fs::{at, parent_of};
pub use check::{check_files, check_only_own, check_owned, check_removable};
pub use error::DirError;
pub use kind::{FIGURES_DIR, Kind, RUN_FIGURES};
pub use lock::DirLock;
pub use manifest::{drop_manifest, record_manifest, start_manifest};
pub use marker::{mark, marked, marked_by_flocking};
pub use names::{LOCK_FILE, MANIFEST_FILE, MANIFEST_TMP, MARKER_FILE};
pub use remove::{remove, remove_file, remove_own_files};
pub use write::{write_file, write_no_follow};
