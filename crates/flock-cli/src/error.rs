//! Errors of scenario files and runs: each names the field, the bad value, why it is wrong and the fix.

use std::fmt;
use std::path::Path;

/// Why a scenario cannot be run.
#[derive(Clone, Debug, PartialEq)]
pub enum ScenarioError {
    /// The file could not be read.
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is not a scenario in RON (bad syntax, unknown or missing field, wrong type).
    Syntax {
        /// Where the text came from.
        origin: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// The parser's message.
        message: String,
    },
    /// An obstacle is malformed (its error names `obstacles[k].field`, the value, why and the fix).
    Obstacle(flock_obstacles::ObstacleError),
    /// A value is out of its domain.
    Invalid {
        /// The field, as a path (`alpha.h`, `initial.positions`).
        field: String,
        /// The value given.
        value: String,
        /// Why it cannot be used.
        why: String,
        /// How to fix it.
        fix: String,
    },
}

impl ScenarioError {
    /// The file at `path` could not be read.
    #[must_use]
    pub fn io(path: &Path, error: &std::io::Error) -> Self {
        Self::Io {
            path: path.display().to_string(),
            message: error.to_string(),
        }
    }

    /// A RON error at its position.
    #[must_use]
    pub fn syntax(origin: &str, error: &ron::error::SpannedError) -> Self {
        Self::Syntax {
            origin: origin.to_owned(),
            line: error.span.start.line,
            col: error.span.start.col,
            message: error.code.to_string(),
        }
    }

    /// `field = value` is invalid because `why`; `fix` says what to write instead.
    #[must_use]
    pub fn invalid(
        field: impl Into<String>,
        value: impl fmt::Debug,
        why: impl Into<String>,
        fix: impl Into<String>,
    ) -> Self {
        Self::Invalid {
            field: field.into(),
            value: format!("{value:?}"),
            why: why.into(),
            fix: fix.into(),
        }
    }
}

impl ScenarioError {
    /// The path of the field at fault, for the errors that name one.
    #[must_use]
    pub fn field(&self) -> Option<String> {
        match self {
            Self::Invalid { field, .. } => Some(field.clone()),
            Self::Obstacle(error) => Some(error.field()),
            Self::Io { .. } | Self::Syntax { .. } => None,
        }
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, message } => write!(f, "cannot read scenario {path}: {message}"),
            Self::Syntax {
                origin,
                line,
                col,
                message,
            } => write!(f, "{origin}:{line}:{col}: {message}"),
            Self::Obstacle(error) => write!(f, "{error}"),
            Self::Invalid {
                field,
                value,
                why,
                fix,
            } => write!(f, "`{field}` = {value}: {why}; {fix}"),
        }
    }
}

impl std::error::Error for ScenarioError {}
