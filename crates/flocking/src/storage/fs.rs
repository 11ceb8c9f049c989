//! The file operations every writer of flocking's directories stands on: each I/O error names
//! what was done to which path ([`at`]), and what must survive a power cut is flushed to the disk.

use std::fmt;
use std::fs::{self, File};
use std::io::{self, Write as _};
use std::path::Path;

/// Wraps an I/O error with the operation and the path: `cannot {what}: {error}`, of the same
/// kind.
pub fn at(what: impl fmt::Display) -> impl FnOnce(io::Error) -> io::Error {
    move |e| io::Error::new(e.kind(), format!("cannot {what}: {e}"))
}

/// The parent directory of `path` (`.` for a bare name).
#[must_use]
pub fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// Flushes the entries of directory `dir` (a rename or a new file in it) to the disk.
///
/// # Errors
/// When the directory cannot be opened or flushed.
pub fn sync_dir(dir: &Path) -> io::Result<()> {
    fs::File::open(dir)?.sync_all()
}

/// Renames `from` to `to` only if `to` does not exist, atomically (`renameat2` with
/// `RENAME_NOREPLACE`): an existing `to` is an [`io::ErrorKind::AlreadyExists`] error and is kept.
/// Where the filesystem cannot (`EINVAL`, `ENOSYS`), `to` is checked first and the rename is the
/// ordinary one.
///
/// # Errors
/// [`io::ErrorKind::AlreadyExists`] for an existing `to`; any other I/O error of the rename.
pub fn rename_no_replace(from: &Path, to: &Path) -> io::Result<()> {
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
#[must_use]
pub fn is_empty_dir(path: &Path) -> bool {
    fs::read_dir(path).is_ok_and(|mut entries| entries.next().is_none())
}

/// Writes `bytes` to `path` and flushes them to the disk.
/// # Errors
/// Any I/O error, naming the path.
pub fn write_durably(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let write = || {
        let mut file = File::create(path)?;
        file.write_all(bytes)?;
        file.sync_all()
    };
    write().map_err(at(format_args!("write {}", path.display())))
}

#[cfg(test)]
mod tests {
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
