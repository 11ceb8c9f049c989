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
//! - [`DirLock`]: an exclusive advisory lock ([`File::try_lock`]) on [`LOCK_FILE`] held by the
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

pub mod manifest;

use std::fmt;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Read as _, Seek as _, Write as _};
use std::os::unix::fs::MetadataExt as _;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use manifest::{Digest, Listed, Manifest};
pub use manifest::{MANIFEST_FILE, MANIFEST_TMP};

/// The marker file of every directory flocking writes.
pub const MARKER_FILE: &str = ".flocking";

/// The lock file of a directory being written: it holds the writer's process id and start time
/// while it writes, and is removed when the writer is done.
pub const LOCK_FILE: &str = ".flocking.lock";

/// What wrote a directory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A run directory (`flocking run`, `DIR` and `DIR.partial`).
    Run,
    /// A sweep's output directory (`flocking sweep`, `sweep merge`, Python's `sweep`).
    Sweep,
    /// The gallery of `flocking figures`.
    Figures,
}

impl Kind {
    /// The marker's text.
    fn marker(self) -> String {
        format!("written by flocking {}\n", self.command())
    }

    /// What a directory of this kind is, for messages.
    const fn what(self) -> &'static str {
        match self {
            Self::Run => "a run directory",
            Self::Sweep => "a sweep's output directory",
            Self::Figures => "a gallery of flocking figures",
        }
    }

    fn command(self) -> &'static str {
        match self {
            Self::Run => "run",
            Self::Sweep => "sweep",
            Self::Figures => "figures",
        }
    }

    /// The files a directory of this kind may hold at its top level when [`remove`] removes it
    /// (each a regular file, never a link), besides the subdirectories of [`Kind::subdirectories`].
    fn entries(self) -> &'static [&'static str] {
        match self {
            Self::Run => RUN_FILES,
            // Sweeps and galleries are written into, never removed.
            Self::Sweep | Self::Figures => &[],
        }
    }

    /// Whether `name` is one of the names a directory of this kind is made of, which
    /// [`write_file`] never replaces: its files and subdirectories.
    fn is_reserved(self, name: &str) -> bool {
        let files: &[&str] = match self {
            Self::Run => RUN_FILES,
            Self::Sweep => &[
                MARKER_FILE,
                LOCK_FILE,
                "sweep.ron",
                "sweep.tmp",
                "runs.csv",
                "runs.tmp",
                "times.csv",
                "times.tmp",
                "rows",
                "runs",
                MANIFEST_FILE,
                MANIFEST_TMP,
            ],
            Self::Figures => &[
                MARKER_FILE,
                LOCK_FILE,
                MANIFEST_FILE,
                MANIFEST_TMP,
                "index.html",
                "functions",
            ],
        };
        files.contains(&name) || self.subdirectories().iter().any(|&(dir, _)| dir == name)
    }

    /// The subdirectories a directory of this kind may hold when [`remove`] removes it, each
    /// with the files it may hold (regular files, never links, no deeper directories).
    fn subdirectories(self) -> &'static [(&'static str, &'static [&'static str])] {
        match self {
            Self::Run => &[(FIGURES_DIR, RUN_FIGURES)],
            Self::Sweep | Self::Figures => &[],
        }
    }
}

/// Every file flocking writes at the top of a run directory.
const RUN_FILES: &[&str] = &[
    MARKER_FILE,
    LOCK_FILE,
    "metrics.csv",
    "trajectory.csv",
    "trajectory.npy",
    "final.csv",
    "scenario.ron",
    "flocking.txt",
    "checkpoint.bin",
    "checkpoint.tmp",
    "INCOMPLETE",
    "INCOMPLETE.tmp",
    "controls.txt",
    MANIFEST_FILE,
    MANIFEST_TMP,
];

/// The subdirectory of a run directory that `flocking plot` draws into.
pub const FIGURES_DIR: &str = "figures";

/// Every file `flocking plot` writes into a run's [`FIGURES_DIR`]: a run directory holding any
/// other is never removed (issue 27: ownership at every depth).
pub const RUN_FIGURES: &[&str] = &[
    "snapshots.svg",
    "snapshots.png",
    "snapshots_top.svg",
    "snapshots_top.png",
    "views.svg",
    "views.png",
    "metrics.svg",
    "metrics.png",
    "reynolds.svg",
    "reynolds.png",
    "animation.gif",
    "player.html",
];

/// Why flocking refuses a directory.
#[derive(Debug)]
pub enum DirError {
    /// The directory holds something flocking did not write.
    Foreign {
        /// The directory.
        dir: PathBuf,
        /// An entry of it that flocking did not write.
        entry: String,
    },
    /// The directory's manifest lists the entry, but its size or content is not what flocking
    /// wrote: the user saved over it ([`manifest`]).
    Changed {
        /// The directory.
        dir: PathBuf,
        /// The file, relative to `dir`.
        entry: String,
    },
    /// The directory is flocking's, but of another kind (a run directory given as a sweep's).
    OtherKind {
        /// The directory.
        dir: PathBuf,
        /// What it is.
        is: &'static str,
        /// What was asked for.
        wanted: &'static str,
    },
    /// The directory is one flocking never removes.
    Special {
        /// The directory.
        dir: PathBuf,
        /// What it is.
        what: &'static str,
    },
    /// The path names one of the files a directory of flocking's is made of (a sweep's
    /// `runs.csv`, a run's `metrics.csv`): a figure or table is never written over it.
    Reserved {
        /// The path.
        path: PathBuf,
        /// What the directory is.
        of: &'static str,
    },
    /// Another process is writing the directory.
    Busy {
        /// The directory.
        dir: PathBuf,
        /// The holder, as its lock file says (`process N, started …`).
        holder: String,
    },
    /// The directory's manifest is not one flocking wrote (a FIFO, a file too large, a header or
    /// line it never writes): flocking cannot tell its files from the user's there.
    Damaged {
        /// The manifest.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// An I/O error, naming the operation and the path ([`at`]).
    Io(io::Error),
}

impl fmt::Display for DirError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Foreign { dir, entry } => write!(
                f,
                "{} holds {entry}, which flocking did not write; choose another output directory or move it",
                dir.display()
            ),
            Self::Changed { dir, entry } => write!(
                f,
                "{} holds {entry}, which is not the file flocking wrote there (its size or content changed since): it is yours now, and flocking never replaces it; choose another output directory or move it",
                dir.display()
            ),
            Self::OtherKind { dir, is, wanted } => write!(
                f,
                "{} is {is} of flocking's, not {wanted}; choose another output directory",
                dir.display()
            ),
            Self::Special { dir, what } => write!(
                f,
                "{} is {what}: flocking never replaces it; choose another output directory",
                dir.display()
            ),
            Self::Reserved { path, of } => write!(
                f,
                "{} is one of the files of {of}: flocking never writes a figure or a table over it; choose another output file",
                path.display()
            ),
            Self::Busy { dir, holder } => {
                write!(f, "{} is being written by {holder}", dir.display())
            }
            Self::Damaged { path, why } => write!(
                f,
                "{} is not a manifest flocking wrote: {why}; flocking cannot tell its files from yours there, so it replaces nothing — choose another output directory, or move the directory away",
                path.display()
            ),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for DirError {}

impl From<io::Error> for DirError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

/// Wraps an I/O error with the operation and the path: `cannot {what}: {error}`, of the same
/// kind.
pub fn at(what: impl fmt::Display) -> impl FnOnce(io::Error) -> io::Error {
    move |e| io::Error::new(e.kind(), format!("cannot {what}: {e}"))
}

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

/// Writes `bytes` to the file `path`, never over a file that flocking did not write. In a
/// directory that carries flocking's marker, the names it is made of are refused, and an existing
/// `path` is replaced only when the directory's [`manifest`] lists it with its content (a file
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
/// When the directory of `path` or its parent keeps a [`manifest`] (a run's `figures/`, a
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

/// The error of a link that flocking would have written through.
/// Writes `bytes` into `tmp`, one of flocking's own `.tmp` names, flushed, never through a link
/// (`O_NOFOLLOW`) and never over a file it finds there (`O_EXCL`) unless `leftover_is_ours`: the
/// caller has checked flocking's marker and knows a `tmp` there can only be a write of
/// flocking's cut short (the manifest's own temporary file, or a `NAME.tmp` whose write the
/// manifest records), which is then removed first, and only a regular file that is no mount
/// point. When the write fails, the file this call created is removed, and only while `tmp`
/// still names it.
///
/// # Errors
/// A link or a file flocking did not leave in `tmp`'s place, or any I/O error, with its path.
pub(crate) fn write_tmp(tmp: &Path, bytes: &[u8], leftover_is_ours: bool) -> io::Result<()> {
    use std::os::unix::fs::{MetadataExt as _, OpenOptionsExt as _};
    let create = || {
        OpenOptions::new()
            .write(true)
            .create_new(true)
            .custom_flags(rustix::fs::OFlags::NOFOLLOW.bits().cast_signed())
            .open(tmp)
    };
    let found = || fs::symlink_metadata(tmp);
    let opened = match create() {
        Err(e)
            if e.kind() == io::ErrorKind::AlreadyExists
                && leftover_is_ours
                && found().is_ok_and(|m| m.is_file())
                && !is_mount_point(tmp) =>
        {
            fs::remove_file(tmp).map_err(at(format_args!("remove {}", tmp.display())))?;
            create()
        }
        opened => opened,
    };
    let mut file = opened.map_err(|e| {
        if e.kind() == io::ErrorKind::AlreadyExists {
            io::Error::new(
                e.kind(),
                format!(
                    "{} exists and flocking did not leave it there: flocking never writes over it; move it away",
                    tmp.display()
                ),
            )
        } else if e.raw_os_error() == Some(rustix::io::Errno::LOOP.raw_os_error()) {
            link_refused(tmp)
        } else {
            at(format_args!("write {}", tmp.display()))(e)
        }
    })?;
    file.write_all(bytes)
        .and_then(|()| file.sync_all())
        .map_err(|e| {
            // only the file created above, while `tmp` still names it
            let created = file.metadata().map(|m| (m.dev(), m.ino()));
            if found().is_ok_and(|m| created.is_ok_and(|c| c == (m.dev(), m.ino()))) {
                let _ = fs::remove_file(tmp);
            }
            at(format_args!("write {}", tmp.display()))(e)
        })
}

fn link_refused(path: &Path) -> io::Error {
    io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!(
            "{} is a link, which flocking did not create: flocking never writes through it; move it away",
            path.display()
        ),
    )
}

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

/// Checks that [`remove`] may remove `dir`: it carries the marker of `kind`, holds only entries
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

/// Records in the [`manifest`] of `dir` every file flocking wrote there, at every depth: a run's
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

/// Refuses the filesystem root, the working directory and its ancestors, and mount points.
fn check_special(dir: &Path) -> Result<(), DirError> {
    let special = |what| {
        Err(DirError::Special {
            dir: dir.to_owned(),
            what,
        })
    };
    let real = fs::canonicalize(dir).map_err(at(format_args!("resolve {}", dir.display())))?;
    let Some(parent) = real.parent() else {
        return special("the filesystem root");
    };
    let cwd = std::env::current_dir().map_err(at("read the working directory"))?;
    if fs::canonicalize(&cwd).is_ok_and(|cwd| cwd.starts_with(&real)) {
        return special("the working directory or one of its parents");
    }
    let device = |path: &Path| {
        fs::metadata(path)
            .map(|m| m.dev())
            .map_err(at(format_args!("read {}", path.display())))
    };
    if device(&real)? != device(parent)? || is_mount_point(&real) {
        return special("a mount point");
    }
    Ok(())
}

/// Whether `/proc/self/mountinfo` lists `dir` (a canonical path) as a mount point (a bind mount
/// shares its parent's device).
fn is_mount_point(dir: &Path) -> bool {
    let Ok(table) = fs::read_to_string("/proc/self/mountinfo") else {
        return false;
    };
    table
        .lines()
        .filter_map(|line| line.split(' ').nth(4))
        .any(|point| Path::new(&unescape_mount_point(point)) == dir)
}

/// A mount point as `/proc/self/mountinfo` writes it, with `\ooo` octal escapes undone.
fn unescape_mount_point(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let octal = bytes.get(i + 1..i + 4).and_then(|digits| {
            std::str::from_utf8(digits)
                .ok()
                .and_then(|d| u8::from_str_radix(d, 8).ok())
        });
        match (bytes[i], octal) {
            (b'\\', Some(byte)) => {
                out.push(byte);
                i += 4;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The parent directory of `path` (`.` for a bare name).
#[must_use]
pub fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// An exclusive lock on a directory being written, held until dropped (or until the process
/// dies: the operating system then releases it). Dropping it removes its [`LOCK_FILE`], if that
/// path still names the very file it locked.
#[derive(Debug)]
pub struct DirLock {
    file: File,
    path: PathBuf,
}

impl DirLock {
    /// Locks the existing directory `dir` and writes this process's id and start time into its
    /// [`LOCK_FILE`].
    ///
    /// # Errors
    /// [`DirError::Busy`] when another process holds the lock; any I/O error, with its path.
    pub fn acquire(dir: &Path) -> Result<Self, DirError> {
        let path = dir.join(LOCK_FILE);
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(at(format_args!("open {}", path.display())))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(fs::TryLockError::WouldBlock) => {
                    let mut holder = String::new();
                    let _ = file.read_to_string(&mut holder);
                    let holder = holder.trim();
                    return Err(DirError::Busy {
                        dir: dir.to_owned(),
                        holder: if holder.is_empty() {
                            "another process".into()
                        } else {
                            holder.to_owned()
                        },
                    });
                }
                Err(fs::TryLockError::Error(e)) => {
                    return Err(at(format_args!("lock {}", path.display()))(e).into());
                }
            }
            // The holder before us may have removed the file between our open and our lock: the
            // lock is ours only if the path still names the file we locked.
            let same = |m: fs::Metadata| {
                file.metadata()
                    .is_ok_and(|ours| ours.ino() == m.ino() && ours.dev() == m.dev())
            };
            if !fs::metadata(&path).is_ok_and(same) {
                continue;
            }
            let holder = format!("process {}, started {}\n", std::process::id(), utc_now());
            let write = |file: &mut File| {
                file.set_len(0)?;
                file.rewind()?;
                file.write_all(holder.as_bytes())
            };
            write(&mut file).map_err(at(format_args!("write {}", path.display())))?;
            return Ok(Self { file, path });
        }
    }

    /// Follows the directory after it was renamed to `dir`.
    pub fn moved_to(&mut self, dir: &Path) {
        self.path = dir.join(LOCK_FILE);
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        // Removed while still locked, so that no other writer can lock this file afterwards
        // believing it holds the directory; only if the path still names the file this lock
        // holds (same device and inode), so that nothing else put there is ever removed.
        let ours = |m: fs::Metadata| {
            self.file
                .metadata()
                .is_ok_and(|held| m.is_file() && (held.dev(), held.ino()) == (m.dev(), m.ino()))
        };
        if fs::symlink_metadata(&self.path).is_ok_and(ours) {
            let _ = fs::remove_file(&self.path);
        }
        let _ = self.file.unlock();
    }
}

/// The current time in UTC, `YYYY-MM-DD HH:MM:SS UTC`.
fn utc_now() -> String {
    let seconds = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, time) = (seconds / 86_400, seconds % 86_400);
    // Howard Hinnant's days-to-civil algorithm.
    let z = days.cast_signed() + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC",
        time / 3600,
        time / 60 % 60,
        time % 60
    )
}

#[cfg(test)]
mod tests {
    use super::{DirLock, LOCK_FILE, unescape_mount_point};

    /// A lock removes its own lock file when dropped, and leaves a file that has replaced it.
    #[test]
    fn a_dropped_lock_removes_only_its_own_file() {
        let dir = std::env::temp_dir().join(format!("flocking-dirlock-{}", std::process::id()));
        std::fs::create_dir(&dir).expect("a new directory");
        let lock_file = dir.join(LOCK_FILE);
        drop(DirLock::acquire(&dir).expect("locked"));
        assert!(!lock_file.exists(), "its own lock file removed");

        let lock = DirLock::acquire(&dir).expect("locked");
        let moved = dir.join("moved");
        std::fs::rename(&lock_file, &moved).expect("moved away");
        std::fs::write(&lock_file, "another's\n").expect("a file in its place");
        drop(lock);
        assert_eq!(std::fs::read(&lock_file).expect("kept"), b"another's\n");

        // only the two files this test made, each checked to hold what was written into it
        let holder = format!("process {}, started ", std::process::id());
        let moved_text = std::fs::read_to_string(&moved).expect("the moved lock file");
        assert!(moved_text.starts_with(&holder), "{moved_text}");
        for file in [&lock_file, &moved] {
            std::fs::remove_file(file).expect("clean");
        }
        std::fs::remove_dir(&dir).expect("clean");
    }

    /// Only regular files of a run's names go, and only from a marked directory: a link in a
    /// name's place is refused and kept, and so is the file it points to.
    #[test]
    fn own_files_are_removed_and_nothing_else() {
        use super::{DirError, Kind, mark, remove_own_files};
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

    /// A figure or table written into a marked directory never takes one of its own names: a
    /// run's files and its `figures` subdirectory, a sweep's `runs.csv`, a gallery's
    /// `index.html`; another name is written.
    #[test]
    fn a_directorys_own_names_are_never_written_over() {
        use super::{DirError, Kind, mark, write_file};
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

    #[test]
    fn mount_points_are_unescaped() {
        assert_eq!(unescape_mount_point(r"/mnt/a\040b"), "/mnt/a b");
        assert_eq!(unescape_mount_point("/plain"), "/plain");
    }

    /// A resume marks its run again; a marker already in place is not rewritten, since rewriting
    /// truncates it first and a SIGKILL at that instant left `DIR.partial` without its marker,
    /// which no resume then accepted (the SIGKILL test failed 1 time in about 10).
    #[test]
    fn a_marker_in_place_is_not_rewritten() {
        use super::{Kind, MARKER_FILE, mark, marked};
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

    /// A `NAME.tmp` that flocking did not leave is never written over: a user's file in its place
    /// is refused and kept, whether or not flocking wrote `NAME` before. Only in a marked
    /// directory whose manifest records the write of `NAME` under way (the new content accepted
    /// beside the old) is a `NAME.tmp` flocking's own replacement cut short, and replaced;
    /// elsewhere an existing `NAME.tmp` is always refused, even beside a copied manifest.
    #[test]
    fn a_temporary_name_flocking_did_not_leave_is_never_written_over() {
        use super::{Kind, mark, write_file, write_no_follow};
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
        super::start_manifest::<&str>(&sweep, &[]).expect("a manifest");
        std::fs::write(sweep.join("b.svg.tmp"), "mine\n").expect("a user's file");
        // a refusal (exit code 2 in the commands), not an I/O failure
        assert!(matches!(
            write_file(&sweep.join("b.svg"), b"1"),
            Err(super::DirError::Foreign { entry, .. }) if entry == "b.svg.tmp"
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
            Err(super::DirError::Foreign { .. })
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
            let mut manifest = super::Manifest::read(&sweep)
                .expect("read")
                .expect("a manifest");
            manifest.accept("c.svg", super::manifest::Digest::of(content));
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

    /// `remove_file` and `drop_manifest` remove nothing from a directory without flocking's
    /// marker, nor a name that leaves the directory.
    #[test]
    fn removals_need_the_marker_and_a_plain_name() {
        use super::{DirError, Kind, MANIFEST_FILE, drop_manifest, mark, remove_file};
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
