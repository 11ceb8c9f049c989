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
        /// The innermost field whose value holds the error, when the message does not name it.
        field: Option<String>,
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

    /// A RON error in `text` at its position.
    #[must_use]
    pub fn syntax(origin: &str, text: &str, error: &ron::error::SpannedError) -> Self {
        let (line, col) = (error.span.start.line, error.span.start.col);
        let message = error.code.to_string();
        let field = enclosing_field(text, line, col)
            .filter(|field| !message.contains(&format!("`{field}`")));
        Self::Syntax {
            origin: origin.to_owned(),
            line,
            col,
            message,
            field,
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

/// A parameter outside its domain, its field a path in the scenario (`alpha.r`).
impl From<flock_protocols::ParamError> for ScenarioError {
    fn from(e: flock_protocols::ParamError) -> Self {
        Self::Invalid {
            field: e.field,
            value: e.value,
            why: e.why,
            fix: e.fix,
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
            Self::Syntax { field, .. } => field.clone(),
            Self::Io { .. } => None,
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
                field,
            } => {
                write!(f, "{origin}:{line}:{col}: {message}")?;
                match field {
                    Some(field) => write!(f, " (in the value of `{field}`)"),
                    None => Ok(()),
                }
            }
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

/// The last `name:` (outside `//` comments) before 1-based `line`:`col` of `text`: the field whose
/// value is being read.
fn enclosing_field(text: &str, line: usize, col: usize) -> Option<String> {
    let code = |l: &str| l.split("//").next().unwrap_or_default().to_owned();
    let mut prefix: String = text
        .lines()
        .take(line.saturating_sub(1))
        .flat_map(|l| [code(l), "\n".to_owned()])
        .collect();
    let last: String = text
        .lines()
        .nth(line.saturating_sub(1))?
        .chars()
        .take(col.saturating_sub(1))
        .collect();
    prefix.push_str(&code(&last));
    let mut rest = prefix.as_str();
    while let Some(colon) = rest.rfind(':') {
        let before = rest[..colon].trim_end();
        let start = before
            .char_indices()
            .rfind(|&(_, c)| !(c.is_alphanumeric() || c == '_'))
            .map_or(0, |(k, c)| k + c.len_utf8());
        let name = &before[start..];
        if !name.is_empty() && !name.starts_with(|c: char| c.is_ascii_digit()) {
            return Some(name.to_owned());
        }
        rest = &rest[..colon];
    }
    None
}
