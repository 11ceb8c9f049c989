//! The manifest of a directory flocking wrote: the size and content hash of every file it wrote
//! there, at every depth, so that a file the user saved over one of flocking's own names (an
//! annotated `figures/metrics.svg`, a `final.csv` edited by hand) is told from flocking's and
//! never replaced (issue 27: ownership by content, not only by name).
//!
//! [`MANIFEST_FILE`] holds one line per file, `SIZE HASH PATH`, after a header line: the size in
//! bytes, the file's XXH3-128 hash in hexadecimal, and its path relative to the directory (`/`
//! between components). A path may have several lines while flocking replaces it (the old and the
//! new content, [`Manifest::accept`]); any of them matches. It is always replaced whole (written
//! beside, flushed, renamed over), so a failure at any instant leaves the old one or the new one.
//!
//! A run records its manifest when it finishes, just before `DIR.partial` becomes `DIR`
//! ([`Manifest::of_dir`]): the records of an interrupted run are appended across a resume, so a
//! `DIR.partial` is judged by the names of its files, as before. Figures drawn later into a
//! directory that has a manifest are checked against it and added to it ([`super::write_no_follow`]).
//! A directory without a manifest (written by an older flocking) is judged by names alone.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Read as _};
use std::path::Path;

use super::error::{DirError, link_refused};
use super::kind::Kind;
use super::marker::{marked, marked_by_flocking};
use super::names::{LOCK_FILE, MARKER_FILE};
pub use super::names::{MANIFEST_FILE, MANIFEST_TMP};
use super::tmp::write_tmp;
use crate::storage::fs::at;

/// The first line of a manifest.
const HEADER: &str = "flocking manifest 1";

/// The size and XXH3-128 hash of a file's content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Digest {
    size: u64,
    hash: u128,
}

impl Digest {
    /// The digest of `bytes`.
    #[must_use]
    pub fn of(bytes: &[u8]) -> Self {
        Self {
            size: bytes.len() as u64,
            hash: xxhash_rust::xxh3::xxh3_128(bytes),
        }
    }

    /// The digest of the file `path`, read in blocks (never whole into memory: a trajectory may
    /// be gigabytes), never through a link.
    ///
    /// # Errors
    /// Any I/O error, naming the path.
    pub fn of_file(path: &Path) -> io::Result<Self> {
        use std::os::unix::fs::OpenOptionsExt as _;
        let read = || {
            let mut file = OpenOptions::new()
                .read(true)
                .custom_flags(rustix::fs::OFlags::NOFOLLOW.bits().cast_signed())
                .open(path)?;
            let mut hasher = xxhash_rust::xxh3::Xxh3Default::new();
            let mut buffer = vec![0; 1 << 20];
            let mut size = 0_u64;
            loop {
                match file.read(&mut buffer) {
                    Ok(0) => break,
                    Ok(n) => {
                        hasher.update(&buffer[..n]);
                        size += n as u64;
                    }
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            }
            Ok(Self {
                size,
                hash: hasher.digest128(),
            })
        };
        read().map_err(at(format_args!("read {}", path.display())))
    }
}

/// What a manifest says of a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Listed {
    /// The file is the one flocking wrote (or it is absent: nothing to keep).
    Matches,
    /// The manifest lists the path, but the file's size or content differs.
    Differs,
    /// The manifest does not list the path: flocking never wrote a file there.
    Unlisted,
}

/// The files flocking wrote into a directory, each with its accepted [`Digest`]s.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Manifest {
    files: BTreeMap<String, Vec<Digest>>,
}

impl Manifest {
    /// The manifest of `dir`, or `None` when it has none (a directory of an older flocking, or a
    /// run not finished yet).
    ///
    /// # Errors
    /// A manifest that is not one ([`DirError::Damaged`], a refusal: issue 49, a FIFO or a file of
    /// 100 MB was an I/O error), or any I/O error, naming the path.
    pub fn read(dir: &Path) -> Result<Option<Self>, DirError> {
        let path = dir.join(MANIFEST_FILE);
        let text = match fs::symlink_metadata(&path) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(at(format_args!("read {}", path.display()))(e).into()),
            Ok(m) if !m.is_file() => return Err(damaged(&path, "it is not a regular file")),
            Ok(m) if m.len() > 1 << 24 => {
                return Err(damaged(
                    &path,
                    &format!("it holds {} bytes, more than any manifest", m.len()),
                ));
            }
            Ok(_) => match fs::read_to_string(&path) {
                Ok(text) => text,
                Err(e) if e.kind() == io::ErrorKind::InvalidData => {
                    return Err(damaged(&path, "it is not text"));
                }
                Err(e) => return Err(at(format_args!("read {}", path.display()))(e).into()),
            },
        };
        let mut lines = text.lines();
        if lines.next() != Some(HEADER) {
            return Err(damaged(
                &path,
                "its first line is not the manifest's header",
            ));
        }
        let mut manifest = Self::default();
        for (number, line) in lines.enumerate() {
            let mut fields = line.splitn(3, ' ');
            let digest = (|| {
                let size = fields.next()?.parse().ok()?;
                let hash = u128::from_str_radix(fields.next()?, 16).ok()?;
                let file = fields.next().filter(|f| !f.is_empty())?;
                Some((file, Digest { size, hash }))
            })();
            let Some((file, digest)) = digest else {
                return Err(damaged(
                    &path,
                    &format!("line {} is not `SIZE HASH PATH`", number + 2),
                ));
            };
            manifest
                .files
                .entry(file.to_owned())
                .or_default()
                .push(digest);
        }
        Ok(Some(manifest))
    }

    /// The manifest of every regular file in `dir` at every depth, but flocking's own
    /// bookkeeping ([`is_transient`]).
    ///
    /// # Errors
    /// Any I/O error, naming the path.
    pub fn of_dir(dir: &Path) -> io::Result<Self> {
        let mut manifest = Self::default();
        manifest.add_dir(dir, "")?;
        Ok(manifest)
    }

    fn add_dir(&mut self, dir: &Path, prefix: &str) -> io::Result<()> {
        let listing = fs::read_dir(dir).map_err(at(format_args!("list {}", dir.display())))?;
        for entry in listing {
            let entry = entry.map_err(at(format_args!("list {}", dir.display())))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            let file_type = entry
                .file_type()
                .map_err(at(format_args!("read {}", entry.path().display())))?;
            let relative = format!("{prefix}{name}");
            if file_type.is_dir() {
                self.add_dir(&entry.path(), &format!("{relative}/"))?;
            } else if file_type.is_file() && !is_transient(&name) {
                let digest = Digest::of_file(&entry.path())?;
                self.files.insert(relative, vec![digest]);
            }
        }
        Ok(())
    }

    /// What the manifest says of the file `relative` in `dir`: an absent file [`Listed::Matches`]
    /// (there is nothing of the user's to keep).
    ///
    /// # Errors
    /// Any I/O error reading the file, naming it.
    pub fn check(&self, dir: &Path, relative: &str) -> io::Result<Listed> {
        let path = dir.join(relative);
        if fs::symlink_metadata(&path).is_err_and(|e| e.kind() == io::ErrorKind::NotFound) {
            return Ok(Listed::Matches);
        }
        let Some(accepted) = self.files.get(relative) else {
            return Ok(Listed::Unlisted);
        };
        let size = fs::symlink_metadata(&path)
            .map_err(at(format_args!("read {}", path.display())))?
            .len();
        // the size first: a file of another size is not read
        if !accepted.iter().any(|d| d.size == size) {
            return Ok(Listed::Differs);
        }
        let digest = Digest::of_file(&path)?;
        Ok(if accepted.contains(&digest) {
            Listed::Matches
        } else {
            Listed::Differs
        })
    }

    /// Whether it lists `relative`: flocking wrote a file there.
    #[must_use]
    pub fn lists(&self, relative: &str) -> bool {
        self.files.contains_key(relative)
    }

    /// Whether a replacement of `relative` is under way: more than one content accepted (between
    /// [`Manifest::accept`] and [`Manifest::settle`]).
    #[must_use]
    pub fn replacing(&self, relative: &str) -> bool {
        self.files
            .get(relative)
            .is_some_and(|accepted| accepted.len() > 1)
    }

    /// Accepts `digest` for `relative` besides what it accepted before: written before the file
    /// is replaced, so that either content matches whenever the replacement is cut short.
    pub fn accept(&mut self, relative: &str, digest: Digest) {
        let accepted = self.files.entry(relative.to_owned()).or_default();
        if !accepted.contains(&digest) {
            accepted.push(digest);
        }
    }

    /// Accepts only `digest` for `relative`: once the file holds it.
    pub fn settle(&mut self, relative: &str, digest: Digest) {
        self.files.insert(relative.to_owned(), vec![digest]);
    }

    /// Forgets `relative` (a file flocking removed).
    pub fn forget(&mut self, relative: &str) {
        self.files.remove(relative);
    }

    /// Writes the manifest into `dir`, replacing the old one whole: written to [`MANIFEST_TMP`],
    /// flushed, renamed over [`MANIFEST_FILE`], and `dir` flushed.
    ///
    /// # Errors
    /// Any I/O error, naming the path; the old manifest is then kept.
    pub fn write(&self, dir: &Path) -> io::Result<()> {
        let mut text = format!("{HEADER}\n");
        for (file, digests) in &self.files {
            for digest in digests {
                let _ = writeln!(text, "{} {:032x} {file}", digest.size, digest.hash);
            }
        }
        let tmp = dir.join(MANIFEST_TMP);
        let path = dir.join(MANIFEST_FILE);
        // the manifest is written only in directories of flocking's: its temporary file there
        // is flocking's own name
        write_tmp(&tmp, text.as_bytes(), marked_by_flocking(dir))?;
        fs::rename(&tmp, &path).map_err(at(format_args!(
            "rename {} to {}",
            tmp.display(),
            path.display()
        )))?;
        File::open(dir)
            .and_then(|d| d.sync_all())
            .map_err(at(format_args!("flush {}", dir.display())))
    }
}

/// Whether `name` is one of flocking's bookkeeping files, never listed in a manifest and
/// recognised by its name alone: the marker, the lock, the manifest, a run's checkpoint and
/// `INCOMPLETE` note (gone once it finishes), and the temporary `NAME.tmp` of a file being
/// replaced.
#[must_use]
pub fn is_transient(name: &str) -> bool {
    [
        MARKER_FILE,
        LOCK_FILE,
        MANIFEST_FILE,
        "checkpoint.bin",
        "INCOMPLETE",
    ]
    .contains(&name)
        || name.ends_with(".tmp")
}

/// The error of a manifest that cannot be read as one.
fn damaged(path: &Path, why: &str) -> DirError {
    DirError::Damaged {
        path: path.to_owned(),
        why: why.to_owned(),
    }
}

/// Records in the manifest of `dir` every file flocking wrote there, at every depth: a run's
/// files once it is finished, just before it is moved into place.
///
/// # Errors
/// Any I/O error, naming its path.
pub fn record_manifest(dir: &Path) -> io::Result<()> {
    Manifest::of_dir(dir)?.write(dir)
}

/// Removes the manifest of `dir`, if any: a run being resumed cuts back and appends to its
/// files, and records its manifest again when it finishes.
///
/// # Errors
/// The I/O error of the removal, naming the path.
pub fn drop_manifest(dir: &Path) -> io::Result<()> {
    let path = dir.join(MANIFEST_FILE);
    if !marked(dir, Kind::Run) {
        return Err(io::Error::new(
            io::ErrorKind::PermissionDenied,
            format!(
                "{} is not a run of flocking's: its manifest is kept",
                dir.display()
            ),
        ));
    }
    if fs::symlink_metadata(&path).is_ok_and(|m| !m.is_file()) {
        return Err(link_refused(&path));
    }
    match fs::remove_file(&path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => {
            Err(at(format_args!("remove {}", path.display()))(e))
        }
        _ => Ok(()),
    }
}

/// Starts the manifest of `dir` when it has none: records the files `relatives` that exist,
/// recognised by their names as flocking's (a gallery of an older flocking, or a new one).
///
/// # Errors
/// A manifest that is not flocking's ([`DirError::Damaged`]), or any I/O error, naming its path.
pub fn start_manifest<S: AsRef<str>>(dir: &Path, relatives: &[S]) -> Result<(), DirError> {
    if Manifest::read(dir)?.is_some() {
        return Ok(());
    }
    let mut manifest = Manifest::default();
    for relative in relatives {
        let path = dir.join(relative.as_ref());
        if fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
            manifest.settle(relative.as_ref(), Digest::of_file(&path)?);
        }
    }
    Ok(manifest.write(dir)?)
}

#[cfg(test)]
mod tests {
    use super::{Digest, Listed, Manifest};

    /// A file is flocking's only with the size and content it was recorded with; an absent one
    /// matches, one never recorded is unlisted, and a manifest reads back as it was written.
    #[test]
    fn a_file_matches_its_manifest_only_with_the_content_recorded() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        std::fs::create_dir(dir.path().join("figures")).expect("mkdir");
        std::fs::write(dir.path().join("final.csv"), "i,x\n0,1\n").expect("write");
        std::fs::write(dir.path().join("figures/metrics.svg"), "<svg/>").expect("write");
        let manifest = Manifest::of_dir(dir.path()).expect("recorded");
        manifest.write(dir.path()).expect("written");
        let read = Manifest::read(dir.path()).expect("read").expect("present");
        assert_eq!(read, manifest);
        let check = |file| read.check(dir.path(), file).expect("checked");
        assert_eq!(check("final.csv"), Listed::Matches);
        assert_eq!(check("figures/metrics.svg"), Listed::Matches);
        assert_eq!(check("trajectory.csv"), Listed::Matches, "absent");
        assert!(!read.files.contains_key(super::MANIFEST_FILE));

        // the same size, another content: only the hash tells
        std::fs::write(dir.path().join("final.csv"), "i,x\n0,2\n").expect("edited");
        assert_eq!(check("final.csv"), Listed::Differs);
        std::fs::write(dir.path().join("figures/metrics.svg"), "<svg>mine</svg>").expect("saved");
        assert_eq!(check("figures/metrics.svg"), Listed::Differs);
        std::fs::write(dir.path().join("figures/views.svg"), "<svg/>").expect("a user's file");
        assert_eq!(check("figures/views.svg"), Listed::Unlisted);

        // while a file is replaced, the old and the new content both match
        let mut manifest = read;
        let new = Digest::of(b"<svg>mine</svg>");
        manifest.accept("figures/metrics.svg", new);
        assert_eq!(
            manifest
                .check(dir.path(), "figures/metrics.svg")
                .expect("checked"),
            Listed::Matches
        );
        manifest.settle("figures/metrics.svg", Digest::of(b"<svg/>"));
        assert_eq!(
            manifest
                .check(dir.path(), "figures/metrics.svg")
                .expect("checked"),
            Listed::Differs
        );
    }

    /// A manifest that is not one is refused, naming it, never taken as empty.
    #[test]
    fn a_damaged_manifest_is_refused() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        for text in ["", "flocking manifest 1\n12 zz final.csv\n", "mine\n"] {
            std::fs::write(dir.path().join(super::MANIFEST_FILE), text).expect("write");
            let error = Manifest::read(dir.path()).expect_err("refused");
            assert!(
                error
                    .to_string()
                    .contains(".flocking.manifest is not a manifest"),
                "{error}"
            );
        }
    }
}
