//! Writing a file where flocking may: never over a file it did not write, never through a link,
//! recorded in the directory's manifest.

use std::fs::{self, OpenOptions};
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use super::error::{DirError, link_refused};
use super::kind::Kind;
use super::manifest::{Digest, Listed, Manifest};
use super::marker::{marked, marked_by_flocking};
use super::tmp::write_tmp;
use crate::storage::fs::{at, parent_of};

/// Writes `bytes` to the file `path`, never over a file that flocking did not write. In a
/// directory that carries flocking's marker, the names it is made of are refused, and an existing
/// `path` is replaced only when the directory's [`manifest`](super::manifest) lists it with its content (a file
/// the user saved there, or over a figure flocking drew, is the user's); the new file is
/// recorded in the manifest, as [`write_no_follow`] does. A marked directory of an older flocking,
/// without a manifest (or a copy of one: the committed sweeps of `docs/figures/sweeps`), judges
/// an existing `path` by its name.
/// Anywhere else `path` is created new, and an existing one is refused (atomically: `O_EXCL`).
///
/// # Errors
/// [`DirError::Reserved`], [`DirError::Foreign`] (an existing file flocking did not write, or a
/// link), [`DirError::Changed`] (one whose content changed since flocking wrote it): nothing is
/// written; any I/O error, with its path.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), DirError> {
    let dir = parent_of(path);
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let marker = [Kind::Run, Kind::Sweep, Kind::Figures]
        .into_iter()
        .find(|&kind| marked(dir, kind));
    let foreign = || DirError::Foreign {
        dir: dir.to_owned(),
        entry: name.clone().unwrap_or_else(|| path.display().to_string()),
    };
    if let (Some(kind), Some(name)) = (marker, &name) {
        if kind.is_reserved(name) {
            return Err(DirError::Reserved {
                path: path.to_owned(),
                of: kind.what(),
            });
        }
        if fs::symlink_metadata(path).is_ok_and(|m| !m.is_file()) {
            // a link (to a user's file) or a directory: never written through or over
            return Err(foreign());
        }
        // without a manifest (a directory of an older flocking): by its name, as before
        return write_tracked(path, bytes, tracking_manifest(path)?);
    }
    let mut file = match OpenOptions::new().write(true).create_new(true).open(path) {
        Ok(file) => file,
        Err(e) if e.kind() == io::ErrorKind::AlreadyExists => return Err(foreign()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            // issue 27: "No such file or directory (os error 2)" named neither the cause nor
            // the fix
            return Err(io::Error::new(
                e.kind(),
                format!(
                    "cannot create {}: the directory {} does not exist; create it, or choose another output file",
                    path.display(),
                    dir.display()
                ),
            )
            .into());
        }
        Err(e) => return Err(at(format_args!("create {}", path.display()))(e).into()),
    };
    file.write_all(bytes)
        .map_err(|e| at(format_args!("write {}", path.display()))(e).into())
}

/// Writes `bytes` to the file `path` (created, or replaced whole), never through a link: a link
/// at `path` is refused and what it points to left untouched, as is a directory at `path` that
/// is a link (issue 27: `flocking plot r` with `r/figures` a link to a user's directory).
///
/// When the directory of `path` or its parent keeps a [`manifest`](super::manifest) (a run's `figures/`, a
/// gallery's `index.html` and `functions/`), an existing `path` is replaced only if the manifest
/// lists it with its size and content, and the new content is recorded: first beside the old
/// one, then alone once the file is in place, so that a failure at any instant leaves a file
/// the manifest accepts. The bytes go to `path.tmp` first and are renamed over `path`.
///
/// # Errors
/// A link, or a file the user saved over flocking's (naming it and what to do); any I/O error,
/// with its path.
pub fn write_no_follow(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let parent = parent_of(path);
    if fs::symlink_metadata(parent).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(link_refused(parent));
    }
    if fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(link_refused(path));
    }
    tracking_manifest(path)
        .and_then(|tracked| write_tracked(path, bytes, tracked))
        .map_err(|e| match e {
            DirError::Io(e) => e,
            refused => io::Error::new(io::ErrorKind::AlreadyExists, refused.to_string()),
        })
}

/// Writes `bytes` to `path` through `path.tmp` and a rename, `O_NOFOLLOW`; with the manifest
/// that `tracked` names (its directory, `path` relative to it), only over a file it lists with
/// its content, recording the new content beside the old before the rename and alone after it.
fn write_tracked(
    path: &Path,
    bytes: &[u8],
    tracked: Option<(PathBuf, String, Manifest)>,
) -> Result<(), DirError> {
    let digest = Digest::of(bytes);
    if let Some((root, relative, manifest)) = &tracked {
        match manifest.check(root, relative)? {
            Listed::Matches => {}
            Listed::Differs => {
                return Err(DirError::Changed {
                    dir: root.clone(),
                    entry: relative.clone(),
                });
            }
            Listed::Unlisted => {
                return Err(DirError::Foreign {
                    dir: root.clone(),
                    entry: relative.clone(),
                });
            }
        }
        let mut accepting = manifest.clone();
        accepting.accept(relative, digest);
        accepting.write(root)?;
    }
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    // a `tmp` is a write of flocking's cut short only while the manifest records one: the new
    // content accepted beside the old (a replacement), or a file it lists that is not there yet
    // (a first write); beside a file it settled, a `tmp` is the user's
    let leftover_is_ours = tracked.as_ref().is_some_and(|(root, relative, manifest)| {
        marked_by_flocking(root)
            && (manifest.replacing(relative) || (manifest.lists(relative) && !path.exists()))
    });
    write_tmp(&tmp, bytes, leftover_is_ours).map_err(|e| {
        // a `tmp` flocking did not leave (or a link there) is a refusal, not an I/O failure
        if e.kind() == io::ErrorKind::AlreadyExists {
            DirError::Foreign {
                dir: parent_of(&tmp).to_owned(),
                entry: tmp
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
            }
        } else {
            DirError::Io(e)
        }
    })?;
    fs::rename(&tmp, path).map_err(at(format_args!(
        "rename {} to {}",
        tmp.display(),
        path.display()
    )))?;
    if let Some((root, relative, mut manifest)) = tracked {
        manifest.settle(&relative, digest);
        manifest.write(&root)?;
    }
    Ok(())
}

/// The directory whose [`manifest`] tracks the file `path` (the directory of `path`, or its
/// parent: a run's `figures/metrics.svg`), with `path` relative to it and the manifest; `None`
/// when neither keeps one.
fn tracking_manifest(path: &Path) -> Result<Option<(PathBuf, String, Manifest)>, DirError> {
    let Some(name) = path.file_name() else {
        return Ok(None);
    };
    let parent = parent_of(path);
    let mut relative = name.to_string_lossy().into_owned();
    for root in [parent, parent_of(parent)] {
        if let Some(manifest) = Manifest::read(root)? {
            return Ok(Some((root.to_owned(), relative, manifest)));
        }
        let Some(dir) = root.file_name() else {
            return Ok(None);
        };
        relative = format!("{}/{relative}", dir.to_string_lossy());
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    /// A figure or table written into a marked directory never takes one of its own names: a
    /// run's files and its `figures` subdirectory, a sweep's `runs.csv`, a gallery's
    /// `index.html`; another name is written.
    #[test]
    fn a_directorys_own_names_are_never_written_over() {
        use crate::storage::owned::{DirError, Kind, mark, write_file};
        let dir = tempfile::tempdir().expect("a temporary directory");
        for (kind, own) in [
            (Kind::Run, ["metrics.csv", "figures", "INCOMPLETE"]),
            (Kind::Sweep, ["runs.csv", "rows", "sweep.ron"]),
            (Kind::Figures, ["index.html", "functions", ".flocking"]),
        ] {
            let marked = dir.path().join(kind.what().replace(' ', "_"));
            std::fs::create_dir(&marked).expect("mkdir");
            mark(&marked, kind).expect("marked");
            for name in own {
                assert!(
                    matches!(
                        write_file(&marked.join(name), b"plot\n"),
                        Err(DirError::Reserved { .. })
                    ),
                    "{name}"
                );
            }
            write_file(&marked.join("plot.svg"), b"plot\n").expect("another name is written");
        }
    }

    /// A `NAME.tmp` that flocking did not leave is never written over: a user's file in its place
    /// is refused and kept, whether or not flocking wrote `NAME` before. Only in a marked
    /// directory whose manifest records the write of `NAME` under way (the new content accepted
    /// beside the old) is a `NAME.tmp` flocking's own replacement cut short, and replaced;
    /// elsewhere an existing `NAME.tmp` is always refused, even beside a copied manifest.
    #[test]
    fn a_temporary_name_flocking_did_not_leave_is_never_written_over() {
        use crate::storage::owned::{Kind, mark, write_file, write_no_follow};
        let dir = tempfile::tempdir().expect("a temporary directory");
        let plain = dir.path().join("plain");
        std::fs::create_dir(&plain).expect("mkdir");
        std::fs::write(plain.join("a.svg.tmp"), "mine\n").expect("a user's file");
        let refused = write_no_follow(&plain.join("a.svg"), b"<svg/>").expect_err("refused");
        assert!(
            refused
                .to_string()
                .contains("holds a.svg.tmp, which flocking did not write"),
            "{refused}"
        );
        assert_eq!(
            std::fs::read(plain.join("a.svg.tmp")).expect("kept"),
            b"mine\n"
        );
        assert!(!plain.join("a.svg").exists());
        // a sweep's directory: a first plot beside a user's `.tmp` is refused
        let sweep = dir.path().join("sweep");
        std::fs::create_dir(&sweep).expect("mkdir");
        mark(&sweep, Kind::Sweep).expect("marked");
        crate::storage::owned::start_manifest::<&str>(&sweep, &[]).expect("a manifest");
        std::fs::write(sweep.join("b.svg.tmp"), "mine\n").expect("a user's file");
        // a refusal (exit code 2 in the commands), not an I/O failure
        assert!(matches!(
            write_file(&sweep.join("b.svg"), b"1"),
            Err(crate::storage::owned::DirError::Foreign { entry, .. }) if entry == "b.svg.tmp"
        ));
        assert_eq!(
            std::fs::read(sweep.join("b.svg.tmp")).expect("kept"),
            b"mine\n"
        );
        // beside a `c.svg` flocking wrote and settled, a `c.svg.tmp` is the user's: kept
        write_file(&sweep.join("c.svg"), b"1").expect("written");
        std::fs::write(sweep.join("c.svg.tmp"), "mine\n").expect("a user's file");
        assert!(matches!(
            write_file(&sweep.join("c.svg"), b"2"),
            Err(crate::storage::owned::DirError::Foreign { .. })
        ));
        assert_eq!(
            std::fs::read(sweep.join("c.svg.tmp")).expect("kept"),
            b"mine\n"
        );
        assert_eq!(std::fs::read(sweep.join("c.svg")).expect("kept"), b"1");
        // a replacement cut short (the manifest accepting the new content beside the old, and
        // the temporary file half written) is flocking's own: the next write replaces it
        let moved = dir.path().join("c.svg.tmp.mine");
        std::fs::rename(sweep.join("c.svg.tmp"), &moved).expect("the user moves it away");
        // the sweep's manifest accepting `content` for c.svg beside what it already holds
        let accepting = |content: &[u8]| {
            let mut manifest = crate::storage::owned::manifest::Manifest::read(&sweep)
                .expect("read")
                .expect("a manifest");
            manifest.accept(
                "c.svg",
                crate::storage::owned::manifest::Digest::of(content),
            );
            manifest
        };
        accepting(b"2").write(&sweep).expect("written");
        std::fs::write(sweep.join("c.svg.tmp"), "cut sh").expect("a write cut short");
        write_file(&sweep.join("c.svg"), b"2").expect("replaced");
        assert_eq!(std::fs::read(sweep.join("c.svg")).expect("written"), b"2");
        assert!(!sweep.join("c.svg.tmp").exists());
        assert_eq!(std::fs::read(&moved).expect("kept"), b"mine\n");
        // the same records copied into a directory without flocking's marker: the `.tmp` there
        // is kept and the write refused
        let copy = dir.path().join("copy");
        std::fs::create_dir(&copy).expect("mkdir");
        std::fs::write(copy.join("c.svg"), b"2").expect("a copy");
        accepting(b"3").write(&copy).expect("a copied manifest");
        std::fs::write(copy.join("c.svg.tmp"), "mine\n").expect("a user's file");
        assert!(write_no_follow(&copy.join("c.svg"), b"3").is_err());
        assert_eq!(
            std::fs::read(copy.join("c.svg.tmp")).expect("kept"),
            b"mine\n"
        );
    }
}
