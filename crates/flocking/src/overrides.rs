//! Parameters by path: read or change any value of a scenario by the dotted path of its field
//! (`algorithm.c1`, `alpha.d`, `initial.positions.std`, `obstacles.0.radius`), as sweeps and the
//! Python package do.
//!
//! A path names fields as the RON file writes them; an enum's variant is passed through (the `c1`
//! of `algorithm: Algorithm2(c1: …)` is `algorithm.c1`) and a list's elements are numbered from 0.
//! The changed scenario is validated as a loaded one is, so a bad value gets the same error.
//!
//! The `conditions` section is reachable whether the scenario writes it or not: its parts that
//! have defaults (`communication`, `actuation`, `disturbance`, `faults`) read as their defaults
//! (`conditions.communication.delay` is 0 on an ideal scenario), a field left unset in it (such as
//! `conditions.communication.range`, or `conditions.control.rate` with no `control`) can be set,
//! and a part that a change leaves at its default stays unwritten. An enum value is given whole:
//! as a string of RON (`"Bernoulli(p: 0.1)"`, `"None"`, `"Unicycle(())"`) at the enum paths of
//! the conditions (`communication.loss`, `communication.when_lost`, `communication.delayed`,
//! `sensing.noise`, `faults.mode`) and of the scenario (`vehicle`, `integrator`, `algorithm`,
//! `domain`, `initial.positions`, `initial.velocities`), or anywhere in JSON's externally tagged
//! form (`{"Bernoulli": {"p": 0.1}}`, the same map in a RON sweep file).

use serde_json::Value;

use flock_sim::conditions::{Delayed, FaultMode, Loss, Noise, WhenLost};
use flock_sim::{Conditions, Integrator};

use crate::Scenario;
use crate::error::ScenarioError;
use crate::input::MAX_NESTING;
use crate::scenario::{Algorithm, Cloud, DomainSpec};
use crate::vehicle::VehicleSpec;

impl Scenario {
    /// The value at `path`, as JSON (numbers, strings, lists, and an enum as `{"Variant": …}`).
    ///
    /// # Errors
    /// A path that names no field of this scenario; the error lists the fields there are.
    pub fn value(&self, path: &str) -> Result<Value, ScenarioError> {
        let tree = self.tree();
        let mut node = &tree;
        for (depth, segment) in path.split('.').enumerate() {
            node = child(node, segment)
                .ok_or_else(|| unknown(path, depth, node))?
                .0;
        }
        Ok(node.clone())
    }

    /// The scenario with the value at each path replaced, then validated.
    ///
    /// A number with no fractional part is accepted where the field takes an integer (`agents:
    /// 400.0` is 400). Unset defaults follow the values they depend on: changing `alpha.d` of a
    /// scenario that leaves `alpha.r` unset moves r to 1.2 d.
    ///
    /// # Example
    /// ```
    /// use flocking::Scenario;
    /// use serde_json::json;
    ///
    /// # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).unwrap(); // the workspace root
    /// let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
    /// let changed = scenario.with_values([("algorithm.c1", json!(0.05)), ("agents", json!(400))])?;
    /// assert_eq!(changed.agents, 400);
    /// assert_eq!(changed.value("algorithm.c1")?, json!(0.05));
    /// // the errors of a loaded scenario, naming the field
    /// let error = scenario.with_values([("alpha.d", json!(-1.0))]).unwrap_err();
    /// assert_eq!(error.field().as_deref(), Some("alpha.d"));
    /// # Ok::<(), flocking::ScenarioError>(())
    /// ```
    ///
    /// # Errors
    /// A path that names no field (the error lists those there are), a value of the wrong type
    /// for its field, or a changed scenario that fails [`Scenario::validate`].
    pub fn with_values<P: AsRef<str>>(
        &self,
        values: impl IntoIterator<Item = (P, Value)>,
    ) -> Result<Self, ScenarioError> {
        let mut tree = self.tree();
        let mut scenario = self.clone();
        for (path, value) in values {
            let path = path.as_ref();
            check_depth(path, &value)?;
            let value = tagged(path, value);
            set(&mut tree, path, value.clone())?;
            scenario = match serde_json::from_value(tree.clone()) {
                Ok(scenario) => scenario,
                Err(error) => {
                    let Some(read) = integral(&value).or_else(|| empty_struct(&value)) else {
                        return Err(wrong_type(path, &value, &error));
                    };
                    set(&mut tree, path, read)?;
                    serde_json::from_value(tree.clone())
                        .map_err(|_| wrong_type(path, &value, &error))?
                }
            };
        }
        scenario.conditions = self.unwritten_defaults(scenario.conditions);
        scenario.validate()?;
        Ok(scenario)
    }

    /// `changed` with each part of the conditions that this scenario leaves unset and that the
    /// expanded tree ([`Scenario::tree`]) gave its default unset again.
    fn unwritten_defaults(&self, mut changed: Conditions) -> Conditions {
        fn unset<T: Default + PartialEq>(was: &Option<T>, now: &mut Option<T>) {
            if was.is_none() && now.as_ref() == Some(&T::default()) {
                *now = None;
            }
        }
        let was = &self.conditions;
        unset(&was.communication, &mut changed.communication);
        unset(&was.actuation, &mut changed.actuation);
        unset(&was.disturbance, &mut changed.disturbance);
        unset(&was.faults, &mut changed.faults);
        changed
    }

    /// `path` with the enum variants it passes through named and list indices as `#`, the key
    /// under which [`crate::sweep::ParameterLabel`] looks a parameter up: `algorithm.c1` of
    /// Algorithm 2 is `algorithm.Algorithm2.c1`, `obstacles.0.radius` of a ball
    /// `obstacles.#.Ball.radius`. `None` for a path this scenario does not have.
    pub(crate) fn typed_path(&self, path: &str) -> Option<String> {
        let tree = self.tree();
        let mut node = &tree;
        let mut typed = Vec::new();
        for segment in path.split('.') {
            let (next, through_variant) = child(node, segment)?;
            if through_variant {
                typed.push(tag(node)?);
            }
            typed.push(if node.is_array() { "#" } else { segment });
            node = next;
        }
        Some(typed.join("."))
    }

    /// The scenario as JSON, its `conditions` expanded: present, with every part that has a
    /// default written (its default when unset); `snapshots` present (null when unset).
    fn tree(&self) -> Value {
        let mut tree = serde_json::to_value(self).expect("a scenario is plain data and serializes");
        let c = &self.conditions;
        let defaults = [
            (
                "communication",
                to_json(&c.communication.unwrap_or_default()),
            ),
            ("actuation", to_json(&c.actuation.unwrap_or_default())),
            (
                "disturbance",
                to_json(&c.disturbance.clone().unwrap_or_default()),
            ),
            ("faults", to_json(&c.faults.clone().unwrap_or_default())),
        ];
        if let Value::Object(map) = &mut tree {
            // unset, not written, and settable
            map.entry("snapshots").or_insert(Value::Null);
            map.entry("domain")
                .or_insert_with(|| to_json(&crate::scenario::DomainSpec::default()));
            map.entry("vehicle")
                .or_insert_with(|| to_json(&crate::vehicle::VehicleSpec::default()));
            let conditions = map
                .entry("conditions")
                .or_insert_with(|| Value::Object(serde_json::Map::new()));
            if let Value::Object(parts) = conditions {
                for (part, value) in defaults {
                    parts.entry(part).or_insert(value);
                }
            }
        }
        tree
    }
}

fn to_json<T: serde::Serialize>(value: &T) -> Value {
    serde_json::to_value(value).expect("conditions are plain data and serialize")
}

/// A string of RON text at a path whose type is an enum — of the conditions (`"Bernoulli(p: 0.1)"`
/// at `conditions.communication.loss`), the vehicle (`"Unicycle(())"`), the integrator, the
/// algorithm, the domain, the initial clouds — as JSON tags that enum
/// (`{"Bernoulli": {"p": 0.1}}`); any other value as it is.
fn tagged(path: &str, value: Value) -> Value {
    fn parse<T: serde::de::DeserializeOwned + serde::Serialize>(text: &str) -> Option<Value> {
        let parsed: T = crate::input::ron_options().from_str(text).ok()?;
        serde_json::to_value(parsed).ok()
    }
    let Value::String(text) = &value else {
        return value;
    };
    let parsed = match path {
        "conditions.communication.loss" => parse::<Loss>(text),
        "conditions.communication.when_lost" => parse::<WhenLost>(text),
        "conditions.communication.delayed" => parse::<Delayed>(text),
        "conditions.sensing.noise" => parse::<Noise>(text),
        "conditions.faults.mode" => parse::<FaultMode>(text),
        "vehicle" => parse::<VehicleSpec>(text),
        "integrator" => parse::<Integrator>(text),
        "algorithm" => parse::<Algorithm>(text),
        "domain" => parse::<DomainSpec>(text),
        "initial.positions" | "initial.velocities" => parse::<Cloud>(text),
        _ => None,
    };
    parsed.unwrap_or(value)
}

/// Whether `path` lies in the `conditions` section, where a field left unset may be set.
fn in_conditions(path: &str) -> bool {
    path == "conditions" || path.starts_with("conditions.")
}

/// The child `segment` of `node`, passing through an enum variant's tag; with whether it did.
fn child<'a>(node: &'a Value, segment: &str) -> Option<(&'a Value, bool)> {
    match node {
        Value::Object(map) => match map.get(segment) {
            Some(value) => Some((value, false)),
            None => variant(node).and_then(|inner| child(inner, segment).map(|(v, _)| (v, true))),
        },
        Value::Array(items) => items
            .get(segment.parse::<usize>().ok()?)
            .map(|v| (v, false)),
        _ => None,
    }
}

/// The content of an externally tagged enum value `{"Variant": content}`.
fn variant(node: &Value) -> Option<&Value> {
    match node {
        Value::Object(map) if map.len() == 1 => {
            let (tag, inner) = map.iter().next()?;
            tag.starts_with(|c: char| c.is_ascii_uppercase())
                .then_some(inner)
        }
        _ => None,
    }
}

/// The variant's name of an externally tagged enum value `{"Variant": content}`.
fn tag(node: &Value) -> Option<&str> {
    variant(node)?;
    node.as_object()?.keys().next().map(String::as_str)
}

fn variant_mut(node: &mut Value) -> Option<&mut Value> {
    variant(node)?;
    match node {
        Value::Object(map) => map.values_mut().next(),
        _ => None,
    }
}

fn set(tree: &mut Value, path: &str, value: Value) -> Result<(), ScenarioError> {
    let mut node = tree;
    for (depth, segment) in path.split('.').enumerate() {
        // a field of the conditions left unset (skipped when written): create it
        if in_conditions(path) && child(node, segment).is_none() && variant(node).is_none() {
            if node.is_null() {
                *node = Value::Object(serde_json::Map::new());
            }
            if let Value::Object(map) = node {
                node = map.entry(segment).or_insert(Value::Null);
                continue;
            }
        }
        let Some((_, through_variant)) = child(node, segment) else {
            return Err(unknown(path, depth, node));
        };
        if through_variant {
            node = variant_mut(node).expect("child() passed through a variant");
        }
        node = match node {
            Value::Object(map) => map.get_mut(segment),
            Value::Array(items) => segment.parse::<usize>().ok().and_then(|k| items.get_mut(k)),
            _ => None,
        }
        .expect("child() found it");
    }
    *node = value;
    Ok(())
}

/// `value` nested at most [`MAX_NESTING`] levels deep (a scenario's values need about 6), so
/// that nothing recursing over it can overflow the stack.
fn check_depth(path: &str, value: &Value) -> Result<(), ScenarioError> {
    let mut level = vec![value];
    for _ in 0..=MAX_NESTING {
        level = level
            .into_iter()
            .flat_map(|v| match v {
                Value::Array(items) => items.iter().collect(),
                Value::Object(map) => map.values().collect(),
                _ => Vec::new(),
            })
            .collect();
        if level.is_empty() {
            return Ok(());
        }
    }
    Err(ScenarioError::invalid(
        path,
        "(a value nested too deep to show)",
        format!("lists or dicts are nested more than {MAX_NESTING} levels deep"),
        "give the value as the scenario file writes it (a scenario nests about 6 levels)",
    ))
}

/// `value` as an integer, when it is a number with no fractional part.
/// A variant holding `()` as one holding the struct of its defaults: `Quadrotor(())` of a RON
/// sweep file reads as `{"Quadrotor": null}`, where the scenario file's `Quadrotor(())` is the
/// vehicle of default parameters (issue 49).
fn empty_struct(value: &Value) -> Option<Value> {
    let tag = tag(value)?;
    variant(value)?
        .is_null()
        .then(|| serde_json::json!({ tag: {} }))
}

fn integral(value: &Value) -> Option<Value> {
    let x = value.as_f64()?;
    (value.is_f64() && x.fract() == 0.0 && x.abs() < 2f64.powi(53)).then(|| {
        if x < 0.0 {
            Value::from(x as i64)
        } else {
            Value::from(x as u64)
        }
    })
}

fn unknown(path: &str, depth: usize, node: &Value) -> ScenarioError {
    let parent: Vec<&str> = path.split('.').take(depth).collect();
    let node = variant(node).unwrap_or(node);
    let (why, fix) = match node {
        Value::Object(map) => (
            "no such parameter".to_owned(),
            format!(
                "the fields {} are {}",
                if depth == 0 {
                    "of a scenario".to_owned()
                } else {
                    format!("under `{}`", parent.join("."))
                },
                map.keys()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ),
        Value::Array(items) => (
            "no such element".to_owned(),
            format!(
                "`{}` has {} elements, numbered from 0",
                parent.join("."),
                items.len()
            ),
        ),
        other => (
            format!(
                "`{}` is the value {other}, which has no fields",
                parent.join(".")
            ),
            format!("end the path at `{}`", parent.join(".")),
        ),
    };
    ScenarioError::Invalid {
        field: path.to_owned(),
        // nothing was read at a path that names nothing: the message is "`path`: why; fix"
        value: String::new(),
        why,
        fix,
    }
}

/// serde's message with Rust's type names in words: "expected usize" is "expected a whole number
/// ≥ 0".
fn plain_types(message: &str) -> String {
    let mut text = message.to_owned();
    for (rust, words) in [
        ("usize", "a whole number ≥ 0"),
        ("u64", "a whole number ≥ 0"),
        ("u32", "a whole number ≥ 0"),
        ("u16", "a whole number ≥ 0"),
        ("u8", "a whole number ≥ 0"),
        ("i64", "a whole number"),
        ("i32", "a whole number"),
        ("f64", "a number"),
        ("f32", "a number"),
    ] {
        text = text.replace(&format!("expected {rust}"), &format!("expected {words}"));
    }
    text.replace("expected a sequence", "expected a list")
}

fn wrong_type(path: &str, value: &Value, error: &serde_json::Error) -> ScenarioError {
    ScenarioError::Invalid {
        field: path.to_owned(),
        value: value.to_string(),
        why: plain_types(&error.to_string()),
        fix: "give a value of the type the field takes, as the scenario file writes it".to_owned(),
    }
}
