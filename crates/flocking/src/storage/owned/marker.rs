//! The marker every directory flocking writes carries, naming what wrote it ([`Kind`]).

use std::fs::{self, File};
use std::io::{self, Write as _};
use std::path::Path;

use super::kind::Kind;
use super::names::MARKER_FILE;
use crate::storage::fs::at;

/// Writes the marker of `kind` into `dir` (flushed to the disk); on error no marker is left. A
/// marker already there is left as it is: rewriting it would truncate it first, and a kill at that
/// instant would leave a resumable run without its marker.
///
/// # Errors
/// Any I/O error, with its path.
pub fn mark(dir: &Path, kind: Kind) -> io::Result<()> {
    if marked(dir, kind) {
        return Ok(());
    }
    let path = dir.join(MARKER_FILE);
    let write = || {
        let mut file = File::create(&path)?;
        file.write_all(kind.marker().as_bytes())?;
        file.sync_all()
    };
    write().map_err(|e| {
        // a marker cut short (a full disk) is removed: it would make the directory unremovable
        let _ = fs::remove_file(&path);
        at(format_args!("write {}", path.display()))(e)
    })
}

/// Whether `dir` carries the marker of `kind`.
#[must_use]
pub fn marked(dir: &Path, kind: Kind) -> bool {
    fs::read_to_string(dir.join(MARKER_FILE)).is_ok_and(|text| text == kind.marker())
}

/// Whether `dir` carries a marker of flocking, of any [`Kind`].
#[must_use]
pub fn marked_by_flocking(dir: &Path) -> bool {
    [Kind::Run, Kind::Sweep, Kind::Figures]
        .into_iter()
        .any(|kind| marked(dir, kind))
}

#[cfg(test)]
mod tests {
    /// A resume marks its run again; a marker already in place is not rewritten, since rewriting
    /// truncates it first and a SIGKILL at that instant left `DIR.partial` without its marker,
    /// which no resume then accepted (the SIGKILL test failed 1 time in about 10).
    #[test]
    fn a_marker_in_place_is_not_rewritten() {
        use crate::storage::owned::{Kind, MARKER_FILE, mark, marked};
        let dir = tempfile::tempdir().expect("a temporary directory");
        mark(dir.path(), Kind::Run).expect("marked");
        let path = dir.path().join(MARKER_FILE);
        let epoch = std::time::SystemTime::UNIX_EPOCH;
        std::fs::File::options()
            .write(true)
            .open(&path)
            .and_then(|f| f.set_modified(epoch))
            .expect("an old time");
        mark(dir.path(), Kind::Run).expect("marked again");
        let modified = std::fs::metadata(&path).and_then(|m| m.modified());
        assert_eq!(modified.expect("a time"), epoch, "the marker was rewritten");
        assert!(marked(dir.path(), Kind::Run));
        // another kind's marker is still replaced by the one asked for
        mark(dir.path(), Kind::Sweep).expect("marked as a sweep");
        assert!(marked(dir.path(), Kind::Sweep));
    }
}
