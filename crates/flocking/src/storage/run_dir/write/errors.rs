//! Why a run directory cannot be created ([`CreateError`]) or resumed ([`ResumeError`]).

use std::io;
use std::path::PathBuf;

use super::note::INCOMPLETE_FILE;
use crate::error::ScenarioError;
use crate::storage::owned::DirError;

/// Why a run directory cannot be created.
#[derive(Debug)]
pub enum CreateError {
    /// The target directory already holds files (and `force` was not set).
    Occupied {
        /// The target directory.
        target: PathBuf,
    },
    /// `DIR.partial` holds an interrupted run (and `force` was not set).
    Interrupted {
        /// `DIR.partial`.
        partial: PathBuf,
        /// `DIR`.
        target: PathBuf,
    },
    /// The output path exists and is not a directory (a file, a FIFO, a device, a link).
    NotADirectory {
        /// The output path.
        target: PathBuf,
        /// What it is.
        what: &'static str,
    },
    /// The directory is not flocking's to replace, or another process is writing it.
    Dir(DirError),
    /// Writing failed.
    Io(io::Error),
}

impl std::fmt::Display for CreateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Occupied { target } => write!(
                f,
                "output directory {} already holds files (replace it with `force`)",
                target.display()
            ),
            Self::Interrupted { partial, .. } => write!(
                f,
                "{} holds an interrupted run (resume it, or start over with `force`)",
                partial.display()
            ),
            Self::NotADirectory { target, what } => write!(
                f,
                "output directory {} is {what}, not a directory: flocking never replaces it; choose another output directory",
                target.display()
            ),
            Self::Dir(e) => write!(f, "{e}"),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for CreateError {}

impl From<DirError> for CreateError {
    fn from(e: DirError) -> Self {
        match e {
            DirError::Io(e) => Self::Io(e),
            e => Self::Dir(e),
        }
    }
}

impl From<io::Error> for CreateError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

/// Why a run directory cannot be resumed.
#[derive(Debug)]
pub enum ResumeError {
    /// There is no interrupted run at `partial`.
    Nothing {
        /// `DIR.partial`, which does not exist.
        partial: PathBuf,
        /// `DIR`.
        target: PathBuf,
        /// Whether `DIR` holds a complete run.
        complete: bool,
    },
    /// `DIR` holds a complete run whose finishing was cut short after its rename (a second
    /// SIGTERM, a kill): its leftover checkpoint and note have now been removed.
    Tidied {
        /// `DIR`.
        target: PathBuf,
    },
    /// The run cannot be resumed; the message says why and what to do.
    Refused(String),
    /// The directory's `scenario.ron` no longer loads.
    Scenario(ScenarioError),
    /// Another process is writing the directory.
    Dir(DirError),
    /// Reading or cutting back the files failed.
    Io(io::Error),
}

impl std::fmt::Display for ResumeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Nothing {
                partial,
                target,
                complete,
            } => {
                if *complete {
                    write!(
                        f,
                        "{} holds a complete run: there is nothing to resume",
                        target.display()
                    )
                } else {
                    write!(f, "there is no interrupted run at {}", partial.display())
                }
            }
            Self::Tidied { target } => write!(
                f,
                "{} holds a complete run whose finishing was cut short: its leftover checkpoint and {INCOMPLETE_FILE} note are removed, there is nothing to resume",
                target.display()
            ),
            Self::Refused(why) => write!(f, "{why}"),
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Dir(e) => write!(f, "{e}"),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ResumeError {}

impl From<DirError> for ResumeError {
    fn from(e: DirError) -> Self {
        match e {
            DirError::Io(e) => Self::Io(e),
            e => Self::Dir(e),
        }
    }
}

impl From<io::Error> for ResumeError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}
