//! What flocking may write into, cut back or remove: a directory it marked, holding, at every
//! depth, only the files it wrote there.

use std::fs;
use std::io;
use std::path::Path;

use super::error::DirError;
use super::kind::Kind;
use super::manifest::{self, Listed, Manifest};
use super::marker::marked;
use super::names::{LOCK_FILE, MARKER_FILE};
use super::special::check_special;
use crate::storage::fs::{at, parent_of};

/// The names in `dir`, sorted (none when it does not exist).
fn entries(dir: &Path) -> io::Result<Vec<String>> {
    let mut names = match fs::read_dir(dir) {
        Ok(entries) => entries
            .map(|entry| entry.map(|e| e.file_name().to_string_lossy().into_owned()))
            .collect::<io::Result<Vec<_>>>()?,
        Err(e) if e.kind() == io::ErrorKind::NotFound => Vec::new(),
        Err(e) => return Err(e),
    };
    names.sort();
    Ok(names)
}

/// Checks that flocking may write into `dir` as `kind`: it is missing, empty, or carries the
/// marker of `kind`.
///
/// # Errors
/// [`DirError::OtherKind`] for a directory marked by another [`Kind`];
/// [`DirError::Foreign`] naming an entry of a directory without the marker; a path that is not a
/// directory; any I/O error.
pub fn check_owned(dir: &Path, kind: Kind) -> Result<(), DirError> {
    if dir.exists() && !dir.is_dir() {
        return Err(DirError::Foreign {
            dir: parent_of(dir).to_owned(),
            entry: dir.file_name().map_or_else(
                || dir.display().to_string(),
                |name| name.to_string_lossy().into_owned(),
            ),
        });
    }
    let names = entries(dir).map_err(at(format_args!("list {}", dir.display())))?;
    if names.is_empty() || marked(dir, kind) {
        return Ok(());
    }
    let other = [Kind::Run, Kind::Sweep, Kind::Figures]
        .into_iter()
        .find(|&other| marked(dir, other));
    if let Some(other) = other {
        return Err(DirError::OtherKind {
            dir: dir.to_owned(),
            is: other.what(),
            wanted: kind.what(),
        });
    }
    // a file of the user's rather than a stale marker or lock, when there is one
    let entry = names
        .iter()
        .find(|name| ![MARKER_FILE, LOCK_FILE].contains(&name.as_str()))
        .unwrap_or(&names[0]);
    Err(DirError::Foreign {
        dir: dir.to_owned(),
        entry: entry.clone(),
    })
}

/// Checks that [`remove`](super::remove) may remove `dir`: it carries the marker of `kind`, holds only entries
/// that `kind` writes, and is not the filesystem root, the working directory or one of its
/// ancestors, or a mount point.
///
/// # Errors
/// [`DirError::Special`], [`DirError::Foreign`], or an I/O error naming its path.
pub fn check_removable(dir: &Path, kind: Kind) -> Result<(), DirError> {
    check_special(dir)?;
    check_only_own(dir, kind)
}

/// The first entry of `dir`, at any depth, that a directory of `kind` does not hold: a name it
/// never writes, a link, a file where it writes a directory or the reverse, anything inside a
/// subdirectory but the files it writes there ([`DirError::Foreign`]); and, when `dir` has a
/// [`manifest`], a file of flocking's name that the manifest does not list or whose size or
/// content differs from it ([`DirError::Changed`]). Named by its path relative to `dir`; `None`
/// when every entry is one flocking writes.
fn foreign_entry(dir: &Path, kind: Kind) -> io::Result<Option<DirError>> {
    let kind_of = |path: &Path| fs::symlink_metadata(path).map(|m| m.file_type());
    let foreign = |entry: String| {
        Some(DirError::Foreign {
            dir: dir.to_owned(),
            entry,
        })
    };
    let manifest = match Manifest::read(dir) {
        Ok(manifest) => manifest,
        Err(DirError::Io(e)) => return Err(e),
        // a manifest that is not flocking's: nothing there can be told flocking's
        Err(refusal) => return Ok(Some(refusal)),
    };
    // a file of flocking's name: by its content when there is a manifest, by its name otherwise
    let changed = |relative: String, name: &str| -> io::Result<Option<DirError>> {
        let Some(manifest) = &manifest else {
            return Ok(None);
        };
        if manifest::is_transient(name) || manifest.check(dir, &relative)? == Listed::Matches {
            return Ok(None);
        }
        Ok(Some(DirError::Changed {
            dir: dir.to_owned(),
            entry: relative,
        }))
    };
    for name in entries(dir)? {
        let path = dir.join(&name);
        let file_type = kind_of(&path)?;
        if kind.entries().contains(&name.as_str()) && file_type.is_file() {
            if let Some(error) = changed(name.clone(), &name)? {
                return Ok(Some(error));
            }
            continue;
        }
        let Some((_, files)) = kind
            .subdirectories()
            .iter()
            .find(|(sub, _)| *sub == name)
            .filter(|_| file_type.is_dir())
        else {
            return Ok(foreign(name));
        };
        for inner in entries(&path)? {
            let inner_path = path.join(&inner);
            let own = |file: &str| files.contains(&file);
            // `NAME.tmp`: a figure being replaced when the writer was stopped
            let own_name = own(&inner) || inner.strip_suffix(".tmp").is_some_and(own);
            let relative = format!("{name}/{inner}");
            if !(own_name && kind_of(&inner_path)?.is_file()) {
                return Ok(foreign(relative));
            }
            if let Some(error) = changed(relative, &inner)? {
                return Ok(Some(error));
            }
        }
    }
    Ok(None)
}

/// Checks that `dir` carries the marker of `kind` and holds, at every depth, only what `kind`
/// writes (regular files of its names, never a link or a FIFO), each, when `dir` has a
/// [`manifest`], with the size and content flocking wrote: what a writer may cut back, rewrite or
/// remove (`flocking run --resume`, `--force`).
///
/// # Errors
/// [`DirError::Foreign`] naming the first entry flocking did not write, [`DirError::Changed`]
/// naming one the user saved over, [`DirError::OtherKind`], or an I/O error naming its path.
pub fn check_only_own(dir: &Path, kind: Kind) -> Result<(), DirError> {
    check_owned(dir, kind)?;
    match foreign_entry(dir, kind).map_err(at(format_args!("list {}", dir.display())))? {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// Checks that each file `relatives` of `dir` that exists may be replaced: when `dir` has a
/// [`manifest`], the manifest lists it with its size and content (a directory without one, of
/// an older flocking, is judged by names alone, as its writer checks them).
///
/// # Errors
/// [`DirError::Foreign`] naming the first that is not a regular file (a link),
/// [`DirError::Changed`] the first file that is not flocking's, or an I/O error naming its path.
pub fn check_files<S: AsRef<str>>(dir: &Path, relatives: &[S]) -> Result<(), DirError> {
    let Some(manifest) = Manifest::read(dir)? else {
        return Ok(());
    };
    for relative in relatives {
        let relative = relative.as_ref();
        if fs::symlink_metadata(dir.join(relative)).is_ok_and(|m| !m.is_file()) {
            // a link, a directory or a FIFO in place of one of flocking's files
            return Err(DirError::Foreign {
                dir: dir.to_owned(),
                entry: relative.to_owned(),
            });
        }
        if manifest.check(dir, relative)? != Listed::Matches {
            return Err(DirError::Changed {
                dir: dir.to_owned(),
                entry: relative.to_owned(),
            });
        }
    }
    Ok(())
}
