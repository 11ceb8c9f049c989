//! The `INCOMPLETE` note of a run directory being written: why it is incomplete (running or
//! killed, interrupted, failed) and how to resume it.

use std::fs;
use std::io;
use std::path::Path;

use crate::storage::fs::{at, sync_dir, write_durably};

/// The file that marks a directory as incomplete, and says why.
pub const INCOMPLETE_FILE: &str = "INCOMPLETE";

/// The temporary file [`INCOMPLETE_FILE`] is written to before its rename.
pub(super) const INCOMPLETE_TMP: &str = "INCOMPLETE.tmp";

/// The first word of [`INCOMPLETE_FILE`] for a run that cannot be resumed.
pub(super) const FAILED: &str = "failed";

/// The note of a directory being written.
pub(super) fn running_note(target: &Path, force: bool) -> String {
    format!(
        "incomplete: the run is in progress (flocking process {}), or was killed.\nA process killed while writing may leave its last record cut; `flocking run --resume` removes it.\nResume a killed run: flocking run --resume {}\n{}",
        std::process::id(),
        target.display(),
        force_line(force)
    )
}

/// The line of the `INCOMPLETE` note of a run started with `force`: it replaces its `DIR`, if
/// flocking's, when it completes, also after a resume.
pub(super) const FORCE_LINE: &str =
    "With --force: the run replaces the earlier run in its directory when it completes.";

/// [`FORCE_LINE`] with its line break, or nothing.
pub(super) fn force_line(force: bool) -> String {
    if force {
        format!("{FORCE_LINE}\n")
    } else {
        String::new()
    }
}

/// Replaces the `INCOMPLETE` note atomically.
pub(super) fn write_incomplete(partial: &Path, note: &str) -> io::Result<()> {
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
