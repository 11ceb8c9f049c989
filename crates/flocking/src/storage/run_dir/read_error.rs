//! Why a run directory could not be read ([`ReadError`]): the file, and for a malformed line
//! the line.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use crate::error::ScenarioError;

/// Why a run directory could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// A file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// The error of the operating system.
        source: io::Error,
    },
    /// A line of a file is malformed.
    Parse {
        /// The file.
        path: PathBuf,
        /// The line, 1-based (the header is line 1; line 1 for a `.npy` header).
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// The run's `scenario.ron` does not load.
    Scenario(ScenarioError),
}

impl ReadError {
    /// The file `path` could not be read.
    #[must_use]
    pub fn io(path: &Path, source: io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Parse {
                path,
                line,
                message,
            } => write!(f, "{}:{line}: {message}", path.display()),
            Self::Scenario(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            Self::Scenario(e) => Some(e),
            Self::Parse { .. } => None,
        }
    }
}
