//! `Scenario::with_values` on arbitrary value trees: the Rust side of Python's
//! `Scenario.with_values` (which converts a dict of Python values to the same `serde_json` trees)
//! and of a sweep's `set` and axes.
//!
//! The oracle (docs/fuzzing.md): nothing panics, aborts or overflows the stack — lists nested
//! 10,000 deep included — and a changed scenario that is accepted is valid and round-trips
//! through RON (`parse(to_ron(s)) == s`).
#![no_main]

use std::sync::OnceLock;

use flocking::Scenario;
use flocking::serde_json::{Map, Number, Value};
use libfuzzer_sys::arbitrary::{Result, Unstructured};
use libfuzzer_sys::fuzz_target;

/// The base scenarios: one of each kind of algorithm, obstacles and initial cloud.
const BASES: [&str; 4] = [
    include_str!("../../fixtures/tac2006_fig11_alg2_n100.ron"),
    include_str!("../../fixtures/tac2006_fig14_split_rejoin_n150.ron"),
    include_str!("../../fixtures/alg3_3d_mixed_obstacles_n100.ron"),
    include_str!("../../fixtures/tr2003_fig9_sink_n100.ron"),
];

/// The generated structure's depth; deeper values come from `Nest`, built without recursion.
const MAX_DEPTH: usize = 8;
/// The most agents a change may ask for (see `check_input`).
const MAX_FUZZ_AGENTS: f64 = 1e5;
/// The deepest `Nest`: as deep as the list that crashed Python (issue 20).
const MAX_NEST: usize = 10_000;

/// Each base scenario and every path of its value tree, as `with_values` names them.
fn bases() -> &'static [(Scenario, Vec<String>)] {
    static BASES_AND_PATHS: OnceLock<Vec<(Scenario, Vec<String>)>> = OnceLock::new();
    BASES_AND_PATHS.get_or_init(|| {
        BASES
            .iter()
            .map(|text| {
                let scenario = Scenario::parse(text, "fixture").expect("a fixture parses");
                let tree = flocking::serde_json::to_value(&scenario).expect("serializes");
                let mut paths = Vec::new();
                collect_paths(&tree, String::new(), &mut paths);
                (scenario, paths)
            })
            .collect()
    })
}

/// Every path below `node` (enum variants passed through, list elements numbered).
fn collect_paths(node: &Value, prefix: String, paths: &mut Vec<String>) {
    let join = |key: &str| {
        if prefix.is_empty() {
            key.to_owned()
        } else {
            format!("{prefix}.{key}")
        }
    };
    match node {
        Value::Object(map) if map.len() == 1 && map.keys().all(|k| k.starts_with(char::is_uppercase)) => {
            // `{"Variant": content}`: the path passes through the variant.
            if let Some(inner) = map.values().next() {
                collect_paths(inner, prefix.clone(), paths);
            }
        }
        Value::Object(map) => {
            for (key, child) in map {
                let path = join(key);
                paths.push(path.clone());
                collect_paths(child, path, paths);
            }
        }
        Value::Array(items) => {
            for (k, child) in items.iter().enumerate().take(4) {
                let path = join(&k.to_string());
                paths.push(path.clone());
                collect_paths(child, path, paths);
            }
        }
        _ => {}
    }
}

/// A value tree: scalars with their edge cases, lists, dicts (keys often a field's or a
/// variant's name), and deep nesting.
fn value(u: &mut Unstructured<'_>, depth: usize) -> Result<Value> {
    const KEYS: [&str; 12] = [
        "Ball", "Wall", "Cuboid", "centre", "radius", "point", "normal", "Gaussian", "Explicit",
        "c1", "d", "Algorithm2",
    ];
    let leaf = depth >= MAX_DEPTH;
    Ok(match u.int_in_range(0..=if leaf { 6 } else { 9 })? {
        0 => Value::Null,
        1 => Value::Bool(u.arbitrary()?),
        2 => Value::from(u.arbitrary::<i64>()?),
        3 => Value::from(u.arbitrary::<u64>()?),
        4 => Number::from_f64(u.arbitrary()?).map_or(Value::Null, Value::Number),
        5 => Value::from(*u.choose(&[0.0, -0.0, 1.0, -1.0, 0.5, 1e-300, 1e300, 1e9, 1e12, 3.0])?),
        6 => Value::String(u.arbitrary()?),
        7 => {
            let len = u.int_in_range(0..=4)?;
            Value::Array((0..len).map(|_| value(u, depth + 1)).collect::<Result<_>>()?)
        }
        8 => {
            let len = u.int_in_range(0..=3)?;
            let mut map = Map::new();
            for _ in 0..len {
                let key = if u.arbitrary()? {
                    (*u.choose(&KEYS)?).to_owned()
                } else {
                    u.arbitrary()?
                };
                map.insert(key, value(u, depth + 1)?);
            }
            Value::Object(map)
        }
        _ => {
            // Lists (or dicts) nested up to 10,000 deep around a value.
            let levels = u.int_in_range(1..=MAX_NEST)?;
            let dicts: bool = u.arbitrary()?;
            let mut nested = value(u, MAX_DEPTH)?;
            for _ in 0..levels {
                nested = if dicts {
                    Value::Object(Map::from_iter([("d".to_owned(), nested)]))
                } else {
                    Value::Array(vec![nested])
                };
            }
            nested
        }
    })
}

/// Drops a value without recursing (a 10,000-deep tree would otherwise be dropped recursively,
/// which is the harness's stack, not the code under test).
fn drop_flat(value: Value) {
    let mut stack = vec![value];
    while let Some(value) = stack.pop() {
        match value {
            Value::Array(items) => stack.extend(items),
            Value::Object(map) => stack.extend(map.into_iter().map(|(_, v)| v)),
            _ => {}
        }
    }
}

fn check_input(data: &[u8]) -> Result<()> {
    let mut u = Unstructured::new(data);
    let (base, paths) = u.choose(bases())?;
    let count = u.int_in_range(1..=3)?;
    let mut changes = Vec::with_capacity(count);
    for _ in 0..count {
        let path = if u.ratio(7, 8)? {
            u.choose(paths)?.clone()
        } else {
            u.arbitrary::<String>()?
        };
        changes.push((path, value(&mut u, 0)?));
    }
    // Validation is linear in the number of agents (each is drawn and checked against the
    // obstacles; 10⁸, the most allowed, take tens of seconds by design): larger flocks are
    // left to the unit tests of `MAX_AGENTS`, so that a timeout here means a real hang.
    let huge = |(path, value): &(String, Value)| {
        path == "agents" && value.as_f64().is_some_and(|n| n > MAX_FUZZ_AGENTS)
    };
    if changes.iter().any(huge) {
        for (_, value) in changes {
            drop_flat(value);
        }
        return Ok(());
    }
    if std::env::var_os("FLOCK_FUZZ_SHOW").is_some() {
        // What a reproducer asks, shown shallowly (`FLOCK_FUZZ_SHOW=1 cargo fuzz run … FILE`).
        for (path, value) in &changes {
            let text = value.to_string();
            eprintln!("{}: {path} = {}", base.name, &text[..text.len().min(300)]);
        }
    }
    let result = base.with_values(changes.iter().map(|(p, v)| (p.as_str(), v.clone())));
    for (_, value) in changes {
        drop_flat(value);
    }
    if let Ok(changed) = result {
        if let Err(e) = changed.validate() {
            panic!("with_values accepted an invalid scenario: {e}");
        }
        let ron = changed.to_ron().expect("a valid scenario serializes");
        match Scenario::parse(&ron, "round-trip") {
            Ok(back) => assert_eq!(back, changed, "to_ron changed the scenario\n{ron}"),
            Err(e) => panic!("to_ron output does not parse back: {e}\n{ron}"),
        }
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let _ = check_input(data);
});
