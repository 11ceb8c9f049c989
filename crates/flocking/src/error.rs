//! Errors of scenario files and runs: each names the field, the bad value, why it is wrong and the fix.

use std::fmt;

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
    /// An error of a value written at `line`:`col` of a scenario's text.
    At {
        /// Where the text came from.
        origin: String,
        /// 1-based line of the field.
        line: usize,
        /// 1-based column of the field.
        col: usize,
        /// The error.
        error: Box<ScenarioError>,
    },
    /// Several values are invalid: every one found, in the order of the text.
    Several(Vec<ScenarioError>),
    /// A valid value that needs more memory than this machine gives (the delay line of a long
    /// delay, allocated with `try_reserve`: an error, not an abort), as the
    /// [`ScenarioError::Invalid`] that names the field, its value, what the memory is for and how
    /// to need less. Not bad input: `flocking` exits with code 1
    /// ([`ScenarioError::is_memory`]).
    Memory(Box<ScenarioError>),
}

impl ScenarioError {
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
            value: flock_protocols::plain_value(&value),
            why: why.into(),
            fix: fix.into(),
        }
    }
}

/// A parameter outside its domain, its field a path in the scenario (`alpha.r`); or one whose
/// memory could not be had ([`ScenarioError::Memory`]).
impl From<flock_protocols::ParamError> for ScenarioError {
    fn from(e: flock_protocols::ParamError) -> Self {
        let flock_protocols::ParamError {
            field,
            value,
            why,
            fix,
            memory,
        } = e;
        let invalid = Self::Invalid {
            field,
            value,
            why,
            fix,
        };
        if memory {
            Self::Memory(Box::new(invalid))
        } else {
            invalid
        }
    }
}

impl ScenarioError {
    /// The path of the field at fault, for the errors that name one (the first of several).
    #[must_use]
    pub fn field(&self) -> Option<String> {
        match self {
            Self::Invalid { field, .. } => Some(field.clone()),
            Self::Memory(error) => error.field(),
            Self::Obstacle(error) => Some(error.field()),
            Self::Syntax { field, .. } => field.clone(),
            Self::At { error, .. } => error.field(),
            Self::Several(errors) => errors.first().and_then(Self::field),
            Self::Io { .. } => None,
        }
    }

    /// Whether the error is memory that could not be had ([`ScenarioError::Memory`]), not a
    /// value out of its domain.
    #[must_use]
    pub fn is_memory(&self) -> bool {
        self.problems()
            .iter()
            .any(|e| matches!(e, Self::Memory { .. }))
    }

    /// Every error this one holds, without their places in the text: itself, or the errors of
    /// [`ScenarioError::Several`] and [`ScenarioError::At`].
    #[must_use]
    pub fn problems(&self) -> Vec<&Self> {
        match self {
            Self::At { error, .. } => error.problems(),
            Self::Several(errors) => errors.iter().flat_map(Self::problems).collect(),
            other => vec![other],
        }
    }

    /// The error placed in `text` (from `origin`): each invalid value at the line and column
    /// of its field, several sorted by line (those not written in the text, such as a default,
    /// last).
    #[must_use]
    pub fn placed(self, origin: &str, text: &str) -> Self {
        let place = |error: Self| match error.field().and_then(|f| locate(text, &f)) {
            Some((line, col)) if !matches!(error, Self::Syntax { .. } | Self::Io { .. }) => {
                Self::At {
                    origin: origin.to_owned(),
                    line,
                    col,
                    error: Box::new(error),
                }
            }
            _ => error,
        };
        match self {
            Self::Several(errors) => {
                let mut placed: Vec<Self> = errors.into_iter().map(place).collect();
                placed.sort_by_key(|e| match e {
                    Self::At { line, col, .. } => (*line, *col),
                    _ => (usize::MAX, 0),
                });
                Self::Several(placed)
            }
            error => place(error),
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
                    Some(field) if !message.contains(&format!("`{field}`")) => {
                        write!(f, " (in the value of `{field}`)")
                    }
                    _ => Ok(()),
                }
            }
            Self::Obstacle(error) => write!(f, "{error}"),
            Self::Invalid {
                field,
                value,
                why,
                fix,
            } if value.is_empty() => write!(f, "`{field}`: {why}; {fix}"),
            Self::Invalid {
                field,
                value,
                why,
                fix,
            } => write!(f, "`{field}` = {value}: {why}; {fix}"),
            Self::Memory(error) => write!(f, "{error}"),
            Self::At {
                origin,
                line,
                col,
                error,
            } => write!(f, "{origin}:{line}:{col}: {error}"),
            Self::Several(errors) => {
                write!(f, "{} invalid values:", errors.len())?;
                errors.iter().try_for_each(|e| write!(f, "\n  {e}"))
            }
        }
    }
}

impl std::error::Error for ScenarioError {}

/// The 1-based line and column where the field `path` (`algorithm.gamma.position`,
/// `obstacles[2].radius`) is written in RON `text`: each name looked up among the fields of the
/// value of the one before it (an index `[k]` takes the k-th item of a list); the deepest part
/// written, or `None` when not even the first is (a value left to its default).
#[must_use]
pub fn locate(text: &str, path: &str) -> Option<(usize, usize)> {
    let chars: Vec<char> = text.chars().collect();
    let tokens = ron_tokens(&chars);
    // (start, end) of the token range of the value being searched: the whole text first
    let (mut from, mut to) = (0, tokens.len());
    let mut found = None;
    for part in path.split('.') {
        let (name, indices) = match part.split_once('[') {
            Some((name, rest)) => (
                name,
                rest.split('[')
                    .filter_map(|k| k.trim_end_matches(']').parse::<usize>().ok())
                    .collect(),
            ),
            None => (part, Vec::new()),
        };
        let Some(k) = field_in(&tokens, from, to, name) else {
            break;
        };
        found = Some(tokens[k].at);
        (from, to) = value_after(&tokens, k + 2, to);
        for index in indices {
            let Some(item) = item_in(&tokens, from, to, index) else {
                return found;
            };
            found = Some(tokens[item.0].at);
            (from, to) = item;
        }
    }
    found
}

/// A token of RON text: an identifier or number, a string, or one punctuation character, with
/// its line and column and its place among the text's characters.
pub(crate) struct Token {
    /// The token as written (a string with its quotes).
    pub text: String,
    /// 1-based line and column of its first character.
    pub at: (usize, usize),
    /// The index of its first character.
    pub offset: usize,
    /// The index after its last character.
    pub end: usize,
}

/// The identifiers, numbers, strings and brackets of `chars`, without comments.
pub(crate) fn ron_tokens(chars: &[char]) -> Vec<Token> {
    let (mut tokens, mut k, mut line, mut col) = (Vec::new(), 0, 1, 1);
    let advance = |k: &mut usize, line: &mut usize, col: &mut usize| {
        if chars[*k] == '\n' {
            (*line, *col) = (*line + 1, 1);
        } else {
            *col += 1;
        }
        *k += 1;
    };
    while k < chars.len() {
        let (c, at, start) = (chars[k], (line, col), k);
        if c == '/' && chars.get(k + 1) == Some(&'/') {
            while k < chars.len() && chars[k] != '\n' {
                advance(&mut k, &mut line, &mut col);
            }
        } else if c == '/' && chars.get(k + 1) == Some(&'*') {
            while k < chars.len() && !(chars[k] == '*' && chars.get(k + 1) == Some(&'/')) {
                advance(&mut k, &mut line, &mut col);
            }
            for _ in 0..2.min(chars.len() - k) {
                advance(&mut k, &mut line, &mut col);
            }
        } else if c == '"' {
            advance(&mut k, &mut line, &mut col);
            while k < chars.len() && chars[k] != '"' {
                if chars[k] == '\\' {
                    advance(&mut k, &mut line, &mut col);
                }
                if k < chars.len() {
                    advance(&mut k, &mut line, &mut col);
                }
            }
            if k < chars.len() {
                advance(&mut k, &mut line, &mut col);
            }
            tokens.push(Token {
                text: chars[start..k].iter().collect(),
                at,
                offset: start,
                end: k,
            });
        } else if c.is_alphanumeric() || c == '_' || c == '.' || c == '-' || c == '+' {
            let mut word = String::new();
            while k < chars.len()
                && (chars[k].is_alphanumeric() || matches!(chars[k], '_' | '.' | '-' | '+'))
            {
                word.push(chars[k]);
                advance(&mut k, &mut line, &mut col);
            }
            tokens.push(Token {
                text: word,
                at,
                offset: start,
                end: k,
            });
        } else {
            if !c.is_whitespace() {
                tokens.push(Token {
                    text: c.to_string(),
                    at,
                    offset: start,
                    end: k + 1,
                });
            }
            advance(&mut k, &mut line, &mut col);
        }
    }
    tokens
}

/// The change of nesting depth a token makes.
fn depth_change(token: &Token) -> i32 {
    match token.text.as_str() {
        "(" | "[" | "{" => 1,
        ")" | "]" | "}" => -1,
        _ => 0,
    }
}

/// The token index of `name:` among the fields of the value `from..to` (at its first depth of
/// brackets, or one deeper in a newtype variant around a struct, `Quadrotor((mass: 1.0))`).
fn field_in(tokens: &[Token], from: usize, to: usize, name: &str) -> Option<usize> {
    let mut depth = 0;
    let found = (from..to).find(|&k| {
        let hit = depth == 1
            && tokens[k].text == name
            && tokens.get(k + 1).is_some_and(|t| t.text == ":");
        depth += depth_change(&tokens[k]);
        hit
    });
    found.or_else(|| {
        let open = (from..to).find(|&k| tokens[k].text == "(")?;
        let inner = open + 1;
        (inner < to && tokens[inner].text == "(").then(|| field_in(tokens, inner, to, name))?
    })
}

/// The token range of the value that starts at `from`: up to the comma or closing bracket that
/// ends it.
pub(crate) fn value_after(tokens: &[Token], from: usize, to: usize) -> (usize, usize) {
    let mut depth = 0;
    let end = (from..to).find(|&k| {
        depth += depth_change(&tokens[k]);
        depth < 0 || (depth == 0 && tokens[k].text == ",")
    });
    (from, end.unwrap_or(to))
}

/// The token range of item `index` of the list that is the value `from..to`.
fn item_in(tokens: &[Token], from: usize, to: usize, index: usize) -> Option<(usize, usize)> {
    let open = (from..to).find(|&k| tokens[k].text == "[")?;
    let mut start = open + 1;
    for _ in 0..index {
        let (_, end) = value_after(tokens, start, to);
        if end >= to || tokens[end].text != "," {
            return None;
        }
        start = end + 1;
    }
    (start < to && tokens[start].text != "]").then(|| value_after(tokens, start, to))
}

#[cfg(test)]
mod tests {
    use super::locate;

    const TEXT: &str = "Scenario(\n    name: \"c1: not a field\", // c1: nor this\n    algorithm: Algorithm3(\n        beta: (c1: 30.0),\n        c1: 1.0,\n    ),\n    obstacles: [\n        Ball(centre: [0.0, 0.0], radius: 1.0),\n        Ball(centre: [5.0, 0.0], radius: 2.0),\n    ],\n    initial: (positions: Explicit([[0.0, 0.0], [1.0, 2.0]])),\n)";

    #[test]
    fn a_field_is_found_among_the_fields_of_its_parent_only() {
        assert_eq!(locate(TEXT, "algorithm.c1"), Some((5, 9)));
        assert_eq!(locate(TEXT, "algorithm.beta.c1"), Some((4, 16)));
        assert_eq!(locate(TEXT, "name"), Some((2, 5)));
    }

    #[test]
    fn an_index_takes_the_item_of_a_list() {
        assert_eq!(locate(TEXT, "obstacles[1].radius"), Some((9, 34)));
        assert_eq!(locate(TEXT, "obstacles[0].centre"), Some((8, 14)));
        assert_eq!(locate(TEXT, "initial.positions[1]"), Some((11, 48)));
    }

    #[test]
    fn a_field_of_a_newtype_variant_around_a_struct_is_found() {
        let text = "Scenario(\n    vehicle: Quadrotor((\n        k_x: 16.0,\n        mass: -1.0,\n    )),\n    dim: 3,\n)";
        assert_eq!(locate(text, "vehicle.mass"), Some((4, 9)));
        assert_eq!(locate(text, "vehicle.k_x"), Some((3, 9)));
        assert_eq!(locate(text, "vehicle.k_v"), Some((2, 5)));
        assert_eq!(locate(text, "dim"), Some((6, 5)));
        // one bracket, not two: no deeper look
        assert_eq!(locate("S(v: A(b: (mass: 1.0)))", "v.mass"), Some((1, 3)));
    }

    #[test]
    fn an_unwritten_field_gives_its_deepest_written_parent() {
        assert_eq!(locate(TEXT, "algorithm.c2"), Some((3, 5)));
        assert_eq!(locate(TEXT, "obstacles[7].radius"), Some((7, 5)));
        assert_eq!(locate(TEXT, "alpha.r"), None);
    }
}
