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
//!   `checkpoint.bin` ([`Checkpoint`](crate::run_dir::Checkpoint)) is replaced atomically every `checkpoint_every` steps and
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
//!   manifest ([`crate::owned::manifest`]): `force` replaces a `DIR` only while its files are those
//!   flocking wrote. A resume drops a manifest a cut-short finish left in `DIR.partial`, and
//!   records it again when it finishes.
//! - The checkpoint holds the resolved scenario: `--resume` refuses a `scenario.ron` edited
//!   since, naming the fields that changed.
//! - The header of `metrics.csv` is written with the first record: the columns of the protocol's
//!   diagnostics are named by the diagnostics themselves ([`Record::diagnostics`](crate::Record::diagnostics)), and every
//!   later record must carry the same names.

mod columns;
mod controls;
mod create;
mod directory;
mod errors;
mod finish;
mod note;
mod options;
mod record;
mod resume;
mod same_run;

pub use columns::{COUNT_COLUMNS, METRICS_HEADER, is_count_column};
pub use controls::CONTROLS_FILE;
pub use directory::{Finished, RunDirectory, partial_path};
pub use errors::{CreateError, ResumeError};
pub use note::INCOMPLETE_FILE;
pub use options::{OutputOptions, TrajectoryFormat};
pub use resume::InterruptedRun;
