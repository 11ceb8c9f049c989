//! The only ways flocking removes anything: a directory it wrote ([`remove`]), or files of one.

use std::fs;
use std::io;
use std::path::Path;

use super::check::{check_files, check_removable};
use super::error::DirError;
use super::kind::Kind;
use super::manifest::Manifest;
use super::marker::{marked, marked_by_flocking};
use super::names::MARKER_FILE;
use super::special::check_special;
use crate::storage::fs::at;

/// Removes the directory `dir` that flocking wrote as `kind`, and nothing else
/// ([`check_removable`] first).
///
/// # Errors
/// [`DirError::Special`], [`DirError::Foreign`] (nothing is removed), or the I/O error of the
/// removal, with its path.
pub fn remove(dir: &Path, kind: Kind) -> Result<(), DirError> {
    check_removable(dir, kind)?;
    fs::remove_dir_all(dir).map_err(|e| at(format_args!("remove {}", dir.display()))(e).into())
}

/// Removes the files `names` of the directory `dir` that flocking wrote as `kind`, each only if
/// it is a regular file of one of the names `kind` writes: the marker is checked first, `dir` is
/// never the filesystem root, the working directory or an ancestor, or a mount point, and a link,
/// a directory or a FIFO in a name's place is refused and kept. A name that is absent is fine
/// (a run's temporaries after a clean finish). `dir` is flushed afterwards.
///
/// # Errors
/// [`DirError::Foreign`] for a `dir` without the marker or an entry that is not a regular file,
/// [`DirError::Special`], or the I/O error of a removal, with its path. Files removed before an
/// error stay removed; those after it are kept, so the directory is as resumable as before.
pub fn remove_own_files(dir: &Path, kind: Kind, names: &[&str]) -> Result<(), DirError> {
    let foreign = |entry: &str| DirError::Foreign {
        dir: dir.to_owned(),
        entry: entry.to_owned(),
    };
    if !marked(dir, kind) {
        return Err(foreign(MARKER_FILE));
    }
    check_special(dir)?;
    for &name in names {
        let path = dir.join(name);
        let file_type = match fs::symlink_metadata(&path) {
            Ok(metadata) => metadata.file_type(),
            Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
            Err(e) => return Err(at(format_args!("read {}", path.display()))(e).into()),
        };
        if !(kind.entries().contains(&name) && file_type.is_file()) {
            return Err(foreign(name));
        }
        match fs::remove_file(&path) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => {
                return Err(at(format_args!("remove {}", path.display()))(e).into());
            }
            _ => {}
        }
    }
    fs::File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(|e| at(format_args!("flush {}", dir.display()))(e).into())
}

/// Removes the file `relative` of `dir` that flocking wrote (checked as [`check_files`]) and
/// forgets it in the manifest; an absent file is fine.
///
/// # Errors
/// [`DirError::Changed`] (nothing removed), or an I/O error naming its path.
pub fn remove_file(dir: &Path, relative: &str) -> Result<(), DirError> {
    // only below a marked directory, and only a plain relative name (no `..`, no root)
    let plain = Path::new(relative)
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    if !plain || !marked_by_flocking(dir) {
        return Err(DirError::Foreign {
            dir: dir.to_owned(),
            entry: relative.to_owned(),
        });
    }
    check_files(dir, &[relative])?;
    let path = dir.join(relative);
    match fs::remove_file(&path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => {
            return Err(at(format_args!("remove {}", path.display()))(e).into());
        }
        _ => {}
    }
    // removed first, forgotten after: a file absent from the disk is never the user's
    if let Some(mut manifest) = Manifest::read(dir)? {
        manifest.forget(relative);
        manifest.write(dir)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    /// Only regular files of a run's names go, and only from a marked directory: a link in a
    /// name's place is refused and kept, and so is the file it points to.
    #[test]
    fn own_files_are_removed_and_nothing_else() {
        use crate::storage::owned::{DirError, Kind, mark, remove_own_files};
        let dir = tempfile::tempdir().expect("a temporary directory");
        let run = dir.path().join("run");
        std::fs::create_dir(&run).expect("mkdir");
        std::fs::write(run.join("checkpoint.bin"), "state\n").expect("a checkpoint");
        let names = ["checkpoint.bin", "checkpoint.tmp", "INCOMPLETE"];
        // no marker: nothing removed
        assert!(matches!(
            remove_own_files(&run, Kind::Run, &names),
            Err(DirError::Foreign { .. })
        ));
        assert!(run.join("checkpoint.bin").is_file());
        mark(&run, Kind::Run).expect("marked");
        // a link in place of the note: refused after the files before it, the user's file kept
        let users = dir.path().join("notes.txt");
        std::fs::write(&users, "mine\n").expect("a user's file");
        std::os::unix::fs::symlink(&users, run.join("INCOMPLETE")).expect("a link");
        assert!(matches!(
            remove_own_files(&run, Kind::Run, &names),
            Err(DirError::Foreign { entry, .. }) if entry == "INCOMPLETE"
        ));
        assert!(
            !run.join("checkpoint.bin").exists(),
            "absent checkpoint.tmp is fine"
        );
        assert!(std::fs::symlink_metadata(run.join("INCOMPLETE")).is_ok());
        assert_eq!(std::fs::read(&users).expect("kept"), b"mine\n");
        // a name a run never writes is refused even when it is a regular file
        std::fs::write(run.join("notes.txt"), "mine too\n").expect("a user's file in the run");
        assert!(matches!(
            remove_own_files(&run, Kind::Run, &["notes.txt"]),
            Err(DirError::Foreign { .. })
        ));
        assert_eq!(
            std::fs::read(run.join("notes.txt")).expect("kept"),
            b"mine too\n"
        );
    }

    /// `remove_file` and `drop_manifest` remove nothing from a directory without flocking's
    /// marker, nor a name that leaves the directory.
    #[test]
    fn removals_need_the_marker_and_a_plain_name() {
        use crate::storage::owned::{
            DirError, Kind, MANIFEST_FILE, drop_manifest, mark, remove_file,
        };
        let dir = tempfile::tempdir().expect("a temporary directory");
        let run = dir.path().join("run");
        std::fs::create_dir(&run).expect("mkdir");
        std::fs::write(run.join("final.csv"), "mine\n").expect("a user's file");
        std::fs::write(run.join(MANIFEST_FILE), "mine\n").expect("a user's file");
        std::fs::write(dir.path().join("notes.txt"), "mine\n").expect("a user's file");
        assert!(matches!(
            remove_file(&run, "final.csv"),
            Err(DirError::Foreign { .. })
        ));
        assert!(drop_manifest(&run).is_err());
        mark(&run, Kind::Run).expect("marked");
        for name in ["../notes.txt", "/etc/hostname", "figures/../../notes.txt"] {
            assert!(
                matches!(remove_file(&run, name), Err(DirError::Foreign { .. })),
                "{name}"
            );
        }
        assert!(run.join("final.csv").is_file() && run.join(MANIFEST_FILE).is_file());
        assert!(dir.path().join("notes.txt").is_file());
    }
}
