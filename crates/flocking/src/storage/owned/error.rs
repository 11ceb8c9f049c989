//! Why flocking refuses a directory ([`DirError`]).

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

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
    /// wrote: the user saved over it ([`manifest`](super::manifest)).
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
    /// An I/O error, naming the operation and the path ([`at`](super::at)).
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

/// The error of a link that flocking would have written through.
pub(super) fn link_refused(path: &Path) -> io::Error {
    io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!(
            "{} is a link, which flocking did not create: flocking never writes through it; move it away",
            path.display()
        ),
    )
}
