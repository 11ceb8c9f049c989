//! Whether a checkpoint continues the run of a directory's `scenario.ron`: the same resolved
//! scenario, draws this flocking continues bit for bit, and a state of its agents.

use std::path::Path;

use super::errors::ResumeError;
use crate::scenario::Scenario;
use crate::storage::run_dir::checkpoint::{Checkpoint, DrawsOf};

/// The checkpoint must be of `scenario` (the run's `scenario.ron`): the same resolved scenario,
/// and a state of its agents in its dimension.
pub(super) fn check_scenario(
    checkpoint: &Checkpoint,
    scenario: &Scenario,
    partial: &Path,
) -> Result<(), ResumeError> {
    let started: Scenario = checkpoint.scenario.parse().map_err(ResumeError::Scenario)?;
    if started != *scenario {
        return Err(ResumeError::Refused(format!(
            "{} was edited after the run started (changed: {}); resuming would continue one scenario with another. Undo the edit, or start a new run with --out elsewhere",
            partial.join("scenario.ron").display(),
            changed_fields(&started, scenario).join(", ")
        )));
    }
    // the draws of an older flocking cannot continue the run's: its random numbers came from
    // ChaCha8 (before issue 31's Philox4x32-10), its normal ones from Box–Muller (before the
    // ziggurat), or each link's from a block of its own (before a receiver's links shared them)
    let older_draws = if checkpoint.draws <= DrawsOf::ChaCha8 && scenario.draws_at_random() {
        Some(
            "drew its random numbers with ChaCha8; this one draws them with Philox4x32-10, so the run's random draws",
        )
    } else if checkpoint.draws <= DrawsOf::BoxMuller && scenario.draws_normals() {
        Some(
            "drew its normal random numbers by Box–Muller; this one draws them by the ziggurat, so the run's noise",
        )
    } else if checkpoint.draws <= DrawsOf::BlockPerLink && scenario.draws_per_link() {
        Some(
            "drew each link's packet loss and jitter from a block of its own; this one draws a receiver's links from its shared blocks, so the run's losses and jitter",
        )
    } else {
        None
    };
    if let Some(why) = older_draws {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} was written by a flocking that {why} cannot continue bit for bit. Resume it with the flocking that started it, or start the run again with --out elsewhere",
            partial.display()
        )));
    }
    // issue 27: a step count past the scenario's end would stop the output short and judge it
    if checkpoint.start.steps > scenario.steps() {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} is at step {}, past the scenario's last step {}: it is not a checkpoint of this run; start a new run with --out elsewhere",
            partial.display(),
            checkpoint.start.steps,
            scenario.steps()
        )));
    }
    // t = 0, every `record_every` steps, and the last step
    let records_bound = checkpoint.start.steps / scenario.record_every.max(1) + 2;
    if checkpoint.records > records_bound {
        return Err(ResumeError::Refused(format!(
            "the checkpoint in {} counts {} records after step {}, more than the {records_bound} a run records by then: it is not a checkpoint of this run",
            partial.display(),
            checkpoint.records,
            checkpoint.start.steps
        )));
    }
    if checkpoint.dim == scenario.dim
        && checkpoint.start.positions.len() == scenario.agents * scenario.dim
        && checkpoint.start.velocities.len() == checkpoint.start.positions.len()
    {
        return Ok(());
    }
    Err(ResumeError::Refused(format!(
        "the checkpoint in {} is of {} coordinates in {}D, not of this scenario's {} agents in {}D",
        partial.display(),
        checkpoint.start.positions.len(),
        checkpoint.dim,
        scenario.agents,
        scenario.dim
    )))
}

/// The dotted paths of the fields whose values differ between `a` and `b`, as
/// [`Scenario::value`] names them (an enum's variant passed through; a changed variant is named
/// by the field that holds it).
fn changed_fields(a: &Scenario, b: &Scenario) -> Vec<String> {
    use serde_json::Value;
    /// The tag and content of an externally tagged enum value `{"Variant": content}`.
    fn variant(map: &serde_json::Map<String, Value>) -> Option<(&String, &Value)> {
        (map.len() == 1)
            .then(|| map.iter().next())
            .flatten()
            .filter(|(tag, _)| tag.starts_with(|c: char| c.is_ascii_uppercase()))
    }
    fn walk(path: &str, a: &Value, b: &Value, out: &mut Vec<String>) {
        let join = |key: &str| {
            if path.is_empty() {
                key.to_owned()
            } else {
                format!("{path}.{key}")
            }
        };
        match (a, b) {
            _ if a == b => {}
            (Value::Object(x), Value::Object(y)) => match (variant(x), variant(y)) {
                (Some((tx, vx)), Some((ty, vy))) if tx == ty => walk(path, vx, vy, out),
                (Some(_), _) | (_, Some(_)) => out.push(path.to_owned()),
                (None, None) => {
                    let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
                    keys.sort();
                    keys.dedup();
                    for key in keys {
                        let null = Value::Null;
                        let (u, v) = (x.get(key).unwrap_or(&null), y.get(key).unwrap_or(&null));
                        walk(&join(key), u, v, out);
                    }
                }
            },
            (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
                for (i, (u, v)) in x.iter().zip(y).enumerate() {
                    walk(&join(&i.to_string()), u, v, out);
                }
            }
            _ => out.push(path.to_owned()),
        }
    }
    let tree = |s: &Scenario| serde_json::to_value(s).expect("a scenario serializes");
    let mut out = Vec::new();
    walk("", &tree(a), &tree(b), &mut out);
    out
}
