//! A RON error of a scenario in the scenario's terms: the dotted path of the field being read
//! (`conditions.communication.loss`), the value written there, and — when that value is of the
//! wrong type (`agents: 200.0`, `loss: 0.1`, `mean: 0.0`, an unknown variant) — the type the field
//! takes, with an example, in place of the parser's "Expected comma".
//!
//! The path is found by walking the text up to the error's position, field name by field name
//! (an enum's variant is passed through, `algorithm: Algorithm2(c1: …)` is `algorithm.c1`, and a
//! list's item is numbered, `obstacles[2].radius`), as validation names fields. The type a field
//! takes is looked up in [`FIELDS`], the scenario's common fields; any other field gets the type
//! the parser expected (a number, a whole number, a list, …).

use ron::error::SpannedError;
use serde::de::DeserializeOwned;

use flock_obstacles::ObstacleSpec;
use flock_protocols::GammaAgent;
use flock_sim::Integrator;
use flock_sim::conditions::{Delayed, FaultMode, Loss, Noise, WhenLost};

use crate::error::{ScenarioError, Token, ron_tokens};
use crate::scenario::{Algorithm, Cloud, DomainSpec, Point};
use crate::vehicle::VehicleSpec;

/// What a RON error means in a scenario.
#[derive(Debug, PartialEq)]
pub(crate) struct Reading {
    /// 1-based line and column: of the value at fault, else of the parser's error.
    pub at: (usize, usize),
    /// The sentence: the type expected with an example, or the parser's message.
    pub message: String,
    /// The dotted path of the field being read, when the error lies in the value of one.
    pub field: Option<String>,
}

/// The type a field of a scenario takes: in words, examples of its value, and for an enum the
/// names of its variants (read from the type itself, so that the list cannot go stale).
struct Expected {
    /// The path (`*` for any one field, `[]` for any item of a list).
    path: &'static str,
    what: &'static str,
    examples: &'static [&'static str],
    variants: Option<fn() -> &'static [&'static str]>,
}

const fn plain(
    path: &'static str,
    what: &'static str,
    examples: &'static [&'static str],
) -> Expected {
    Expected {
        path,
        what,
        examples,
        variants: None,
    }
}

const fn variant_of(
    path: &'static str,
    what: &'static str,
    examples: &'static [&'static str],
    variants: fn() -> &'static [&'static str],
) -> Expected {
    Expected {
        path,
        what,
        examples,
        variants: Some(variants),
    }
}

/// The types of a scenario's common fields.
const FIELDS: &[Expected] = &[
    plain("agents", "a whole number ≥ 1", &["200"]),
    plain("dim", "2 or 3", &["2"]),
    plain("seed", "a whole number ≥ 0", &["7"]),
    plain("record_every", "a whole number ≥ 1", &["10"]),
    plain("step", "a time step in seconds > 0", &["0.01"]),
    plain("duration", "a duration in seconds > 0", &["100.0"]),
    plain("collision_distance", "a distance > 0", &["1.75"]),
    plain("name", "text in double quotes", &["\"my flock\""]),
    plain(
        "description",
        "text in double quotes",
        &["\"what it shows\""],
    ),
    plain(
        "alpha",
        "the α-interaction's parameters in round brackets",
        &["(d: 7.0, r: 8.4)"],
    ),
    plain(
        "initial",
        "the initial positions and velocities in round brackets",
        &["(positions: Gaussian(mean: [0.0, 0.0], std: 50.0))"],
    ),
    plain(
        "conditions",
        "the conditions in round brackets",
        &["(communication: (delay: 0.05, loss: Bernoulli(p: 0.1)))"],
    ),
    plain(
        "snapshots",
        "a list of times in seconds",
        &["[0.0, 10.0, 50.0]"],
    ),
    variant_of(
        "algorithm",
        "an algorithm",
        &[
            "Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.05, c2: 0.4)",
            "Vicsek(eta: 2.0)",
        ],
        variants::<Algorithm>,
    ),
    variant_of(
        "algorithm.gamma",
        "a γ-agent",
        &[
            "Static(position: [0.0, 0.0])",
            "ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5])",
        ],
        variants::<GammaAgent<Point>>,
    ),
    plain(
        "algorithm.gamma.position",
        "a list of `dim` numbers",
        &["[0.0, 0.0]"],
    ),
    plain(
        "algorithm.gamma.velocity",
        "a list of `dim` numbers",
        &["[1.0, 0.5]"],
    ),
    variant_of(
        "vehicle",
        "a vehicle",
        &["Unicycle(())", "Quadrotor((mass: 0.03))"],
        variants::<VehicleSpec>,
    ),
    variant_of(
        "integrator",
        "an integration scheme",
        &["Rk4"],
        variants::<Integrator>,
    ),
    variant_of(
        "domain",
        "a domain",
        &["Periodic(size: [100.0, 100.0])"],
        variants::<DomainSpec>,
    ),
    variant_of(
        "initial.*",
        "a cloud of vectors",
        &[
            "Gaussian(mean: [0.0, 0.0], std: 50.0)",
            "Box(min: [-2.0, -2.0], max: [2.0, 2.0])",
        ],
        variants::<Cloud>,
    ),
    plain("initial.*.mean", "a list of `dim` numbers", &["[0.0, 0.0]"]),
    plain(
        "initial.*.min",
        "a list of `dim` numbers",
        &["[-10.0, -10.0]"],
    ),
    plain(
        "initial.*.max",
        "a list of `dim` numbers",
        &["[10.0, 10.0]"],
    ),
    plain(
        "initial.*.centre",
        "a list of `dim` numbers",
        &["[0.0, 0.0]"],
    ),
    variant_of(
        "obstacles[]",
        "an obstacle",
        &["Ball(centre: [0.0, 0.0], radius: 1.0)"],
        variants::<ObstacleSpec>,
    ),
    variant_of(
        "conditions.communication.loss",
        "a loss model",
        &[
            "Bernoulli(p: 0.1)",
            "GilbertElliott(p_fail: 0.2, p_recover: 1.0)",
        ],
        variants::<Loss>,
    ),
    variant_of(
        "conditions.communication.when_lost",
        "what a receiver does with a lost packet",
        &["Hold(max_age: 0.5)"],
        variants::<WhenLost>,
    ),
    variant_of(
        "conditions.communication.delayed",
        "whose states are delayed",
        &["All"],
        variants::<Delayed>,
    ),
    plain(
        "conditions.communication.delay",
        "a time in seconds ≥ 0",
        &["0.05"],
    ),
    plain(
        "conditions.communication.symmetric",
        "true or false",
        &["true"],
    ),
    variant_of(
        "conditions.sensing.noise",
        "a noise model",
        &["White(sigma_q: 0.1, sigma_p: 0.05)"],
        variants::<Noise>,
    ),
    variant_of(
        "conditions.faults.mode",
        "how a failed agent behaves",
        &["Frozen"],
        variants::<FaultMode>,
    ),
];

/// The names of the variants of the enum `T`, as the parser lists them for an unknown one.
fn variants<T: DeserializeOwned>() -> &'static [&'static str] {
    match crate::input::ron_options().from_str::<T>("NoSuchVariant") {
        Err(SpannedError {
            code: ron::Error::NoSuchEnumVariant { expected, .. },
            ..
        }) => expected,
        _ => &[],
    }
}

/// `names` as "`A`, `B` or `C`".
fn listed(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.concat(),
    }
}

/// One level of brackets open at the error: the field being read in it (or the item of a
/// list) and the token where that value starts.
struct Frame {
    list: bool,
    field: Option<String>,
    index: usize,
    value_start: Option<usize>,
}

/// The frames of brackets open before `at` in `tokens`.
fn open_frames(tokens: &[Token], at: (usize, usize)) -> Vec<Frame> {
    let mut frames: Vec<Frame> = Vec::new();
    for (k, token) in tokens.iter().enumerate().take_while(|(_, t)| t.at < at) {
        match token.text.as_str() {
            "(" | "[" | "{" => frames.push(Frame {
                list: token.text == "[",
                field: None,
                index: 0,
                value_start: (token.text == "[").then_some(k + 1),
            }),
            ")" | "]" | "}" => {
                frames.pop();
            }
            "," => {
                if let Some(top) = frames.last_mut() {
                    top.index += 1;
                    top.field = None;
                    top.value_start = top.list.then_some(k + 1);
                }
            }
            name if tokens.get(k + 1).is_some_and(|t| t.text == ":") => {
                if let Some(top) = frames.last_mut().filter(|f| !f.list) {
                    top.field = Some(name.to_owned());
                    top.value_start = Some(k + 2);
                }
            }
            _ => {}
        }
    }
    frames
}

/// The dotted path of `frames` (`obstacles[1].radius`); `None` outside every field.
fn path_of(frames: &[Frame]) -> Option<String> {
    let mut path = String::new();
    for frame in frames {
        if frame.list {
            path.push_str(&format!("[{}]", frame.index));
        } else if let Some(field) = &frame.field {
            if !path.is_empty() {
                path.push('.');
            }
            path.push_str(field);
        }
    }
    (!path.is_empty() && !path.starts_with('[')).then_some(path)
}

/// Whether `pattern` (`initial.*.mean`, `obstacles[]`) names `path` (`initial.positions.mean`,
/// `obstacles[2]`).
fn matches(pattern: &str, path: &str) -> bool {
    let mut unindexed = String::new();
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => {
                unindexed.push_str("[]");
                in_index = true;
            }
            ']' => in_index = false,
            c if !in_index => unindexed.push(c),
            _ => {}
        }
    }
    let (p, q): (Vec<&str>, Vec<&str>) =
        (pattern.split('.').collect(), unindexed.split('.').collect());
    p.len() == q.len() && p.iter().zip(&q).all(|(a, b)| a == b || *a == "*")
}

/// The type the parser expected, in words with an example value, for the errors of a value of
/// the wrong type; `None` for the others (a missing comma between fields, an unclosed bracket).
fn expected_by_parser(code: &ron::Error) -> Option<(&'static str, &'static str)> {
    use ron::Error as E;
    Some(match code {
        E::ExpectedInteger
        | E::IntegerOutOfBounds
        | E::InvalidIntegerDigit { .. }
        | E::ExpectedComma => ("a whole number", "10"),
        E::ExpectedFloat => ("a number", "1.0"),
        E::ExpectedString | E::ExpectedStringEnd => ("text in double quotes", "\"text\""),
        E::ExpectedArray => ("a list in square brackets", "[0.0, 0.0]"),
        E::ExpectedBoolean => ("true or false", "true"),
        E::ExpectedStructLike | E::ExpectedNamedStructLike(_) | E::ExpectedUnit => {
            ("its fields in round brackets", "(…)")
        }
        E::ExpectedIdentifier | E::SuggestRawIdentifier(_) | E::InvalidIdentifier(_) => {
            ("the name of a variant", "")
        }
        _ => return None,
    })
}

/// The value written from token `start` to the end of its field or item, shortened to 60
/// characters.
fn value_text(text: &[char], tokens: &[Token], start: usize) -> String {
    if matches!(tokens[start].text.as_str(), "," | ")" | "]" | "}") {
        return "(nothing)".to_owned();
    }
    let (from, to) = crate::error::value_after(tokens, start, tokens.len());
    let end = tokens[from..to].last().map_or(tokens[start].end, |t| t.end);
    let value: String = text[tokens[start].offset..end].iter().collect();
    let value = value.split_whitespace().collect::<Vec<_>>().join(" ");
    if value.chars().count() > 60 {
        format!("{}…", value.chars().take(59).collect::<String>())
    } else {
        value
    }
}

/// What the RON `error` in `text` means.
pub(crate) fn read(text: &str, error: &SpannedError) -> Reading {
    let at = (error.span.start.line, error.span.start.col);
    let message = crate::input::ron_message(&error.code);
    let chars: Vec<char> = text.chars().collect();
    let tokens = ron_tokens(&chars);
    let frames = open_frames(&tokens, at);
    // a missing field is found at the closing bracket, after the last field given; an unknown
    // field at its own name: their messages name them
    let field = (!matches!(
        error.code,
        ron::Error::MissingStructField { .. } | ron::Error::NoSuchStructField { .. }
    ))
    .then(|| path_of(&frames))
    .flatten();
    let unchanged = Reading {
        at,
        message: message.clone(),
        field: field.clone(),
    };
    let Some(path) = field else {
        return unchanged;
    };
    // the error lies before the value of the field (the parser stops after the colon) or inside
    // its first word (`200.0` read as 200)
    let Some(start) = frames.last().and_then(|f| f.value_start) else {
        return unchanged;
    };
    let Some(token) = tokens.get(start) else {
        return unchanged;
    };
    let read_before = tokens.iter().take_while(|t| t.at < at).count();
    let inside_first_word = read_before == start + 1
        && token.at.0 == at.0
        && at.1 < token.at.1 + (token.end - token.offset);
    if read_before != start && !inside_first_word {
        return unchanged;
    }
    let value = value_text(&chars, &tokens, start);
    let known = FIELDS.iter().find(|e| matches(e.path, &path));
    let name = path.rsplit('.').next().unwrap_or(&path);
    let example = |v: &str| {
        if name.ends_with(']') {
            format!("`{v}`")
        } else {
            format!("`{name}: {v}`")
        }
    };
    let sentence = if let ron::Error::NoSuchEnumVariant {
        expected, found, ..
    } = &error.code
    {
        let what = known.map_or("a variant", |e| e.what);
        let examples = known.map_or(String::new(), |e| {
            format!(
                ", e.g. {}",
                e.examples
                    .iter()
                    .map(|v| example(v))
                    .collect::<Vec<_>>()
                    .join(" or ")
            )
        });
        return Reading {
            at: token.at,
            message: format!(
                "`{path}`: `{found}` is not {what}; write one of {}{examples}",
                listed(expected)
            ),
            field: Some(path),
        };
    } else if let Some(e) = known {
        let variants = e
            .variants
            .map_or(String::new(), |names| format!(" ({})", listed(names())));
        let examples: Vec<String> = e.examples.iter().map(|v| example(v)).collect();
        format!(
            "expected {}{variants}, e.g. {}",
            e.what,
            examples.join(" or ")
        )
    } else if let Some((what, v)) = expected_by_parser(&error.code) {
        if v.is_empty() {
            format!("expected {what}")
        } else {
            format!("expected {what}, e.g. {}", example(v))
        }
    } else {
        return unchanged;
    };
    Reading {
        at: token.at,
        message: format!("`{path}` = {value}: {sentence}"),
        field: Some(path),
    }
}

impl ScenarioError {
    /// A RON error in `text` at its position, in the scenario's terms: the dotted path of the
    /// field being read and, for a value of the wrong type, the type it takes with an example
    /// (found in the text by the module `typed_mistake`).
    #[must_use]
    pub fn syntax(origin: &str, text: &str, error: &ron::error::SpannedError) -> Self {
        let reading = read(text, error);
        Self::Syntax {
            origin: origin.to_owned(),
            line: reading.at.0,
            col: reading.at.1,
            message: reading.message,
            field: reading.field,
        }
    }
}
