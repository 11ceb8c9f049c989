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

/// Removes the file `relative` of `dir` that flocking wrote and forgets it in the manifest: only
/// from a directory carrying flocking's marker, only a plain relative name below it (not empty,
/// no `.`, `..` or root), only a regular file the manifest lists with the content flocking wrote
/// ([`check_files`]). Without a manifest nothing tells flocking's file from a user's, so nothing is
/// removed. An absent file is fine (a removal cut short before the manifest forgot it finishes
/// when called again).
///
/// # Errors
/// [`DirError::Foreign`] or [`DirError::Changed`] (nothing removed), or an I/O error naming its
/// path.
pub fn remove_file(dir: &Path, relative: &str) -> Result<(), DirError> {
    let foreign = || DirError::Foreign {
        dir: dir.to_owned(),
        entry: relative.to_owned(),
    };
    let plain = !relative.is_empty()
        && Path::new(relative)
            .components()
            .all(|c| matches!(c, std::path::Component::Normal(_)));
    if !plain || !marked_by_flocking(dir) {
        return Err(foreign());
    }
    let path = dir.join(relative);
    let present = fs::symlink_metadata(&path).is_ok();
    let manifest = Manifest::read(dir)?;
    if present && !manifest.as_ref().is_some_and(|m| m.lists(relative)) {
        return Err(foreign());
    }
    check_files(dir, &[relative])?;
    match fs::remove_file(&path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => {
            return Err(at(format_args!("remove {}", path.display()))(e).into());
        }
        _ => {}
    }
    // removed first, forgotten after: a file absent from the disk is never the user's
    if let Some(mut manifest) = manifest.filter(|m| m.lists(relative)) {
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

    /// In a marked directory, `remove_file` removes only a file its manifest lists with the
    /// content flocking wrote: not one without a manifest, not an unlisted or changed one, not
    /// an empty name or `.`; a removal repeated after it finished is fine, and the manifest forgets
    /// the file.
    #[test]
    fn removals_need_the_manifest_to_list_the_file() {
        use super::Manifest;
        use crate::storage::owned::{DirError, Kind, mark, record_manifest, remove_file};
        let dir = tempfile::tempdir().expect("a temporary directory");
        let run = dir.path().join("run");
        std::fs::create_dir(&run).expect("mkdir");
        mark(&run, Kind::Run).expect("marked");
        std::fs::write(run.join("final.csv"), "ours\n").expect("a file");
        // no manifest: flocking cannot tell its file from a user's
        assert!(matches!(
            remove_file(&run, "final.csv"),
            Err(DirError::Foreign { .. })
        ));
        assert!(run.join("final.csv").is_file());
        for name in ["", "."] {
            assert!(
                matches!(remove_file(&run, name), Err(DirError::Foreign { .. })),
                "{name:?}"
            );
        }
        record_manifest(&run).expect("the manifest of what is there");
        // a file the manifest does not list, and one changed since it was written, are kept
        std::fs::write(run.join("trajectory.csv"), "mine\n").expect("a user's file");
        assert!(matches!(
            remove_file(&run, "trajectory.csv"),
            Err(DirError::Foreign { .. })
        ));
        std::fs::write(run.join("final.csv"), "changed\n").expect("changed by the user");
        assert!(matches!(
            remove_file(&run, "final.csv"),
            Err(DirError::Changed { .. })
        ));
        assert_eq!(
            std::fs::read(run.join("final.csv")).expect("kept"),
            b"changed\n"
        );
        assert_eq!(
            std::fs::read(run.join("trajectory.csv")).expect("kept"),
            b"mine\n"
        );
        // the file flocking wrote goes, and is forgotten; asked again, nothing happens
        std::fs::write(run.join("final.csv"), "ours\n").expect("as written");
        remove_file(&run, "final.csv").expect("removed");
        assert!(!run.join("final.csv").exists());
        let manifest = Manifest::read(&run).expect("read").expect("a manifest");
        assert!(!manifest.lists("final.csv"));
        remove_file(&run, "final.csv").expect("absent: nothing to do");
    }
}
