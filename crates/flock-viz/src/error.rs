//! [`VizError`]: why a run could not be read or a figure could not be drawn.

use std::fmt;
use std::io;
use std::path::PathBuf;

/// Why a run could not be read or a figure could not be drawn.
///
/// Errors about files name the file, and parse errors its line (1-based, the header is line 1),
/// e.g. `o/metrics.csv:12: field 3 ("cohesion_radius") is "abc", not a number`.
#[derive(Debug)]
pub enum VizError {
    /// A file could not be read or written.
    Io {
        /// The file.
        path: PathBuf,
        /// The error of the operating system.
        source: io::Error,
    },
    /// A line of a CSV file could not be read.
    Parse {
        /// The file.
        path: PathBuf,
        /// The line, 1-based (the header is line 1).
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// The input cannot be drawn (no frames, a frame index out of range, an image of size 0, …).
    Invalid(String),
    /// plotters failed to draw.
    Draw(String),
    /// The PNG or GIF encoder failed.
    Encode(String),
}

impl VizError {
    /// An [`VizError::Invalid`] with this message.
    pub(crate) fn invalid(message: impl Into<String>) -> Self {
        Self::Invalid(message.into())
    }

    /// A [`VizError::Draw`] from a plotters error.
    pub(crate) fn draw(error: impl fmt::Display) -> Self {
        Self::Draw(error.to_string())
    }

    /// A [`VizError::Encode`] from an encoder's error.
    pub(crate) fn encode(error: impl fmt::Display) -> Self {
        Self::Encode(error.to_string())
    }
}

impl fmt::Display for VizError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Parse {
                path,
                line,
                message,
            } => write!(f, "{}:{line}: {message}", path.display()),
            Self::Invalid(message) => write!(f, "cannot draw: {message}"),
            Self::Draw(message) => write!(f, "drawing failed: {message}"),
            Self::Encode(message) => write!(f, "encoding failed: {message}"),
        }
    }
}

impl std::error::Error for VizError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}
