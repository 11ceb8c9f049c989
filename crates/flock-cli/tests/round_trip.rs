//! Issue 53: `flocking validate s.ron > resolved.ron` gives a scenario that validates and runs to
//! the same bits; `--set PATH=VALUE` on `run` and `validate` equals editing the file; a typed
//! mistake in a file is refused (exit 2) naming the field, the type and an example.

use std::fs;
use std::path::Path;

use crate::common::{flocking, stderr, temp_dir, write};

/// A short scenario that leaves its defaults unset (r, the collision distance) and runs under
/// delay and loss, so that a round trip must keep the random draws of the conditions.
const SCENARIO: &str = "Scenario(
    dim: 2,
    agents: 12,
    seed: 5,
    algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.05, c2: 0.4),
    initial: (
        positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0]),
        velocities: Box(min: [-1.0, -1.0], max: [1.0, 1.0]),
    ),
    duration: 0.5,
    conditions: (communication: (delay: 0.02, loss: GilbertElliott(p_fail: 0.5, p_recover: 2.0))),
)";

/// The outputs of a run that its scenario determines.
const OUTPUTS: [&str; 3] = ["metrics.csv", "trajectory.csv", "final.csv"];

/// Runs `args` (a scenario and flags) into `dir/out`, and returns its outputs' bytes.
fn run(dir: &Path, out: &str, args: &[&str]) -> Vec<Vec<u8>> {
    let mut all = vec!["run", "--quiet", "--out", out];
    all.extend_from_slice(args);
    let output = flocking(dir, &all);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    OUTPUTS
        .iter()
        .map(|name| fs::read(dir.join(out).join(name)).expect(name))
        .collect()
}

#[test]
fn validate_prints_a_resolved_scenario_that_validates_and_runs_to_the_same_bits() {
    let tmp = temp_dir("round_trip");
    let file = write(tmp.path(), "s.ron", SCENARIO);
    let output = flocking(tmp.path(), &["validate", &file]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("s.ron: valid"),
        "{}",
        stderr(&output)
    );
    let resolved = String::from_utf8(output.stdout).expect("UTF-8");
    // the defaults written as their values (the message said 1.75 = d/4 and 8.4 = 1.2 d)
    assert!(resolved.contains("collision_distance: 1.75,"), "{resolved}");
    assert!(resolved.contains("r: 8.4,"), "{resolved}");
    let again = write(tmp.path(), "resolved.ron", &resolved);
    let output = flocking(tmp.path(), &["validate", &again]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    // validating the resolved file prints it unchanged
    assert_eq!(String::from_utf8_lossy(&output.stdout), resolved);
    assert_eq!(
        run(tmp.path(), "a", &[&file]),
        run(tmp.path(), "b", &[&again])
    );
}

#[test]
fn every_fixture_validates_after_a_round_trip() {
    let tmp = temp_dir("round_trip_fixtures");
    for path in crate::common::fixture_paths() {
        let path = path.to_str().expect("UTF-8").to_owned();
        let output = flocking(tmp.path(), &["validate", &path]);
        assert_eq!(output.status.code(), Some(0), "{path}: {}", stderr(&output));
        let file = write(
            tmp.path(),
            "resolved.ron",
            &String::from_utf8_lossy(&output.stdout),
        );
        let output = flocking(tmp.path(), &["validate", &file]);
        assert_eq!(output.status.code(), Some(0), "{path}: {}", stderr(&output));
    }
}

#[test]
fn set_on_run_equals_a_run_of_the_edited_file() {
    let tmp = temp_dir("set_run");
    let file = write(tmp.path(), "s.ron", SCENARIO);
    let edited = SCENARIO.replace("agents: 12", "agents: 20").replace(
        "GilbertElliott(p_fail: 0.5, p_recover: 2.0)",
        "Bernoulli(p: 0.1)",
    );
    let edited = write(tmp.path(), "edited.ron", &edited);
    let set = run(
        tmp.path(),
        "set",
        &[
            &file,
            "--set",
            "agents=20",
            "--set",
            "conditions.communication.loss=Bernoulli(p: 0.1)",
        ],
    );
    assert_eq!(set, run(tmp.path(), "edited", &[&edited]));
    // the run's scenario.ron is the changed scenario, so that it reruns and resumes as run
    assert_eq!(
        fs::read(tmp.path().join("set/scenario.ron")).expect("scenario.ron"),
        fs::read(tmp.path().join("edited/scenario.ron")).expect("scenario.ron")
    );
    // and it differs from the unchanged run: the change took effect
    assert_ne!(set, run(tmp.path(), "plain", &[&file]));
}

#[test]
fn set_on_validate_prints_the_changed_scenario() {
    let tmp = temp_dir("set_validate");
    let file = write(tmp.path(), "s.ron", SCENARIO);
    let output = flocking(
        tmp.path(),
        &[
            "validate",
            &file,
            "--set",
            "alpha.d=5",
            "--set",
            "conditions.communication.loss=None",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    // r follows the changed d (1.2 d = 6), the loss is gone
    assert!(
        text.contains("d: 5.0,") && text.contains("r: 6.0,"),
        "{text}"
    );
    assert!(!text.contains("GilbertElliott"), "{text}");
}

#[test]
fn set_with_a_bad_path_or_value_exits_2_naming_it_and_writes_nothing() {
    let tmp = temp_dir("set_bad");
    let file = write(tmp.path(), "s.ron", SCENARIO);
    for (set, words) in [
        (
            "agnts=20",
            &[
                "--set",
                "`agnts`: no such parameter",
                "`agents`",
                "`conditions`",
            ][..],
        ),
        (
            "algorithm.c3=1.0",
            &["`algorithm.c3`: no such parameter", "`c1`, `c2`"][..],
        ),
        ("agents=0", &["`agents` = 0", "at least one agent"][..]),
        ("agents", &["PATH=VALUE", "--set agents=20"][..]),
    ] {
        for command in ["run", "validate"] {
            let mut args = vec![command, file.as_str(), "--set", set];
            if command == "run" {
                args.extend(["--out", "o"]);
            }
            let output = flocking(tmp.path(), &args);
            let err = stderr(&output);
            assert_eq!(
                output.status.code(),
                Some(2),
                "{command} --set {set}: {err}"
            );
            for word in words {
                assert!(err.contains(word), "{command} --set {set}: {word} in {err}");
            }
            assert!(output.stdout.is_empty() || command == "run", "{command}");
            assert!(!tmp.path().join("o").exists(), "{command} --set {set}");
        }
    }
}

#[test]
fn a_typed_mistake_exits_2_naming_the_field_the_type_and_an_example() {
    let tmp = temp_dir("typed_mistake");
    for (from, to, message) in [
        (
            "agents: 12",
            "agents: 200.0",
            "s.ron:3:13: `agents` = 200.0: expected a whole number ≥ 1, e.g. `agents: 200`",
        ),
        (
            "GilbertElliott(p_fail: 0.5, p_recover: 2.0)",
            "0.1",
            "s.ron:11:53: `conditions.communication.loss` = 0.1: expected a loss model (`None`, \
             `Bernoulli`, `GilbertElliott` or `Distance`), e.g. `loss: Bernoulli(p: 0.1)` or \
             `loss: GilbertElliott(p_fail: 0.2, p_recover: 1.0)`",
        ),
    ] {
        let file = write(tmp.path(), "s.ron", &SCENARIO.replace(from, to));
        for command in ["run", "validate"] {
            let output = flocking(tmp.path(), &[command, &file]);
            assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
            let err = stderr(&output);
            assert!(err.contains(message), "{err}");
        }
    }
}
