//! Bad scenarios get an error naming the field (from the library and from the `flocking` binary),
//! and `flocking run` writes its outputs whole or not at all.

use std::collections::BTreeMap;
use std::path::Path;

use flocking::run_dir::METRICS_HEADER;
use flocking::{Scenario, ScenarioError};

use crate::common::{TempDir, files, flocking, stderr, temp_dir, write};

/// A valid 2D scenario of 5 agents and 10 steps; each error test breaks one field of it.
pub const TINY_2D: &str = r#"Scenario(
    name: "tiny",
    dim: 2,
    agents: 5,
    seed: 1,
    algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.02, c2: 0.4),
    alpha: (d: 7.0, epsilon: 0.1, a: 5.0, b: 5.0, h: 0.2),
    initial: (
        positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0]),
        velocities: Box(min: [-1.0, -1.0], max: [1.0, 1.0]),
    ),
    step: 0.01,
    duration: 0.1,
)
"#;

/// [`TINY_2D`] in 3D.
fn tiny_3d() -> String {
    let text = edit(TINY_2D, "dim: 2", "dim: 3");
    let text = edit(&text, "position: [0.0, 0.0]", "position: [0.0, 0.0, 0.0]");
    let text = edit(
        &text,
        "min: [-10.0, -10.0], max: [10.0, 10.0]",
        "min: [-10.0, -10.0, -10.0], max: [10.0, 10.0, 10.0]",
    );
    edit(
        &text,
        "min: [-1.0, -1.0], max: [1.0, 1.0]",
        "min: [-1.0, -1.0, -1.0], max: [1.0, 1.0, 1.0]",
    )
}

/// `text` with its one occurrence of `from` replaced by `to`.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(
        text.matches(from).count(),
        1,
        "`{from}` must occur once in\n{text}"
    );
    text.replacen(from, to, 1)
}

/// Parses `text`, which must fail; returns the error and its message.
fn parse_error(text: &str) -> (ScenarioError, String) {
    match Scenario::parse(text, "test.ron") {
        Ok(s) => panic!("accepted an invalid scenario: {s:?}\n{text}"),
        Err(e) => {
            let message = e.to_string();
            (e, message)
        }
    }
}

/// Parses `text`, which must fail validation on `field`; returns the message, which names it.
fn invalid_field(text: &str, field: &str) -> String {
    let (error, message) = parse_error(text);
    let problems = error.problems();
    assert_eq!(problems.len(), 1, "one invalid value: {message}");
    match problems[0] {
        ScenarioError::Invalid {
            field: f, why, fix, ..
        } => {
            assert_eq!(f, field, "{message}");
            assert!(!why.is_empty() && !fix.is_empty(), "{message}");
        }
        other => panic!("expected an invalid `{field}`, got {other:?}"),
    }
    assert!(
        message.contains(&format!("`{field}`")),
        "the message must name `{field}`: {message}"
    );
    message
}

#[test]
fn the_base_scenarios_are_valid() {
    let two = Scenario::parse(TINY_2D, "test.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((two.dim, two.agents, two.steps()), (2, 5, 10));
    let three = Scenario::parse(&tiny_3d(), "test.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((three.dim, three.agents, three.steps()), (3, 5, 10));
}

/// Switching a scenario to `dim: 3` and nothing else: every 2D vector is named at once, each at
/// its line and column, in the order of the text — one edit-and-retry round, not four.
#[test]
fn every_invalid_value_is_reported_at_once_in_the_order_of_the_text() {
    let text = edit(TINY_2D, "dim: 2", "dim: 3");
    let (error, message) = parse_error(&text);
    let fields: Vec<String> = error.problems().iter().filter_map(|e| e.field()).collect();
    assert_eq!(
        fields,
        [
            "algorithm.gamma.position",
            "initial.positions.min",
            "initial.positions.max",
            "initial.velocities.min",
            "initial.velocities.max",
        ],
        "{message}"
    );
    assert!(message.starts_with("5 invalid values:"), "{message}");
    let lines: Vec<&str> = message.lines().skip(1).collect();
    // where each field's name stands in TINY_2D (line 6: `Static(position: …`, line 9: the
    // positions' box, line 10: the velocities' box)
    let places: Vec<String> = lines
        .iter()
        .map(|l| {
            l.trim()
                .splitn(4, ':')
                .take(3)
                .collect::<Vec<_>>()
                .join(":")
        })
        .collect();
    assert_eq!(
        places,
        [
            "test.ron:6:41",
            "test.ron:9:24",
            "test.ron:9:45",
            "test.ron:10:25",
            "test.ron:10:44"
        ],
        "{message}"
    );
    for line in &lines {
        assert!(
            line.contains("has 2 components but the scenario has dim = 3"),
            "{line}"
        );
        assert!(
            line.contains("give exactly 3 numbers, e.g. [0.0, 0.0, 0.0]"),
            "{line}"
        );
    }
    // a wrong dim hides nothing else: it is the one error when the vectors cannot be judged
    let (error, message) = parse_error(&edit(TINY_2D, "dim: 2", "dim: 4"));
    assert_eq!(error.field().as_deref(), Some("dim"), "{message}");
    assert!(message.starts_with("test.ron:3:5: `dim` = 4"), "{message}");
}

#[test]
fn unknown_field_is_named_with_its_line_and_column() {
    let text = edit(
        TINY_2D,
        "    agents: 5,\n",
        "    agents: 5,\n    speed: 3.0,\n",
    );
    let (error, message) = parse_error(&text);
    assert!(
        matches!(error, ScenarioError::Syntax { line: 5, .. }),
        "{error:?}"
    );
    assert!(message.contains("speed"), "{message}");
    assert!(message.starts_with("test.ron:5:"), "{message}");
}

#[test]
fn unknown_nested_field_is_named() {
    let text = edit(TINY_2D, "h: 0.2)", "h: 0.2, k: 1.0)");
    let (error, message) = parse_error(&text);
    assert!(
        matches!(error, ScenarioError::Syntax { line: 7, .. }),
        "{error:?}"
    );
    assert!(message.contains('k'), "{message}");
}

#[test]
fn missing_required_field_is_named() {
    let text = edit(TINY_2D, "    duration: 0.1,\n", "");
    let (error, message) = parse_error(&text);
    assert!(matches!(error, ScenarioError::Syntax { .. }), "{error:?}");
    assert!(message.contains("duration"), "{message}");
    assert!(message.to_lowercase().contains("missing"), "{message}");
    assert!(message.starts_with("test.ron:"), "{message}");
}

#[test]
fn range_not_above_lattice_distance_names_alpha_r() {
    let alpha = "alpha: (d: 7.0, epsilon: 0.1, a: 5.0, b: 5.0, h: 0.2)";
    let message = invalid_field(&edit(TINY_2D, alpha, "alpha: (d: 9.0, r: 8.4)"), "alpha.r");
    assert!(
        message.contains("8.4") && message.contains('9'),
        "{message}"
    );
    invalid_field(&edit(TINY_2D, alpha, "alpha: (d: 7.0, r: 7.0)"), "alpha.r");
}

#[test]
fn non_positive_epsilon_names_alpha_epsilon() {
    for bad in ["0.0", "-0.1"] {
        invalid_field(
            &edit(TINY_2D, "epsilon: 0.1", &format!("epsilon: {bad}")),
            "alpha.epsilon",
        );
    }
}

#[test]
fn bump_parameter_outside_the_unit_interval_names_alpha_h() {
    for bad in ["1.0", "0.0", "1.5", "-0.2"] {
        invalid_field(&edit(TINY_2D, "h: 0.2", &format!("h: {bad}")), "alpha.h");
    }
}

#[test]
fn attraction_above_repulsion_names_alpha_a() {
    let message = invalid_field(
        &edit(TINY_2D, "a: 5.0, b: 5.0", "a: 6.0, b: 5.0"),
        "alpha.a",
    );
    assert!(message.contains("exceeds b = 5"), "{message}");
}

#[test]
fn no_agents_names_agents() {
    invalid_field(&edit(TINY_2D, "agents: 5", "agents: 0"), "agents");
}

/// A box at a density holds no agent: `agents` is the one error, not also a box side of 0.
#[test]
fn no_agents_in_a_box_at_density_names_agents_alone() {
    let vicsek = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/vicsek1995_fig2a_n400.ron"
    ))
    .expect("the fixture");
    invalid_field(&edit(&vicsek, "agents: 400", "agents: 0"), "agents");
}

#[test]
fn non_positive_step_names_step() {
    for bad in ["-0.01", "0.0"] {
        invalid_field(
            &edit(TINY_2D, "step: 0.01", &format!("step: {bad}")),
            "step",
        );
    }
}

#[test]
fn negative_agent_count_names_agents_with_line_and_column() {
    let (error, message) = parse_error(&edit(TINY_2D, "agents: 5", "agents: -1"));
    assert_eq!(error.field().as_deref(), Some("agents"), "{message}");
    assert!(message.starts_with("test.ron:4:"), "{message}");
    assert!(
        message.contains("`agents` = -1: expected a whole number ≥ 1"),
        "{message}"
    );
}

#[test]
fn a_value_of_the_wrong_type_names_its_field() {
    let (error, message) = parse_error(&edit(TINY_2D, "epsilon: 0.1", "epsilon: \"small\""));
    assert!(
        matches!(error, ScenarioError::Syntax { line: 7, .. }),
        "{error:?}"
    );
    assert!(message.contains("`alpha.epsilon` = \"small\""), "{message}");
}

#[test]
fn non_positive_duration_names_duration() {
    for bad in ["-1.0", "0.0"] {
        let message = invalid_field(
            &edit(TINY_2D, "duration: 0.1", &format!("duration: {bad}")),
            "duration",
        );
        assert!(message.contains("must be > 0"), "{message}");
    }
}

#[test]
fn gains_the_theory_needs_positive_are_named() {
    let alpha = "h: 0.2)";
    for (text, field, why) in [
        (
            edit(TINY_2D, alpha, "h: 0.2, c1: 0.0)"),
            "alpha.c1",
            "` = 0.0: must be > 0",
        ),
        (
            edit(TINY_2D, alpha, "h: 0.2, c1: -1.0)"),
            "alpha.c1",
            "` = -1.0: must be > 0",
        ),
        (
            edit(TINY_2D, alpha, "h: 0.2, c2: -1.0)"),
            "alpha.c2",
            "negative consensus gain",
        ),
        (
            edit(TINY_2D, "c1: 0.02", "c1: 0.0"),
            "algorithm.c1",
            "` = 0.0: must be > 0",
        ),
        (
            edit(TINY_2D, "c2: 0.4", "c2: -0.4"),
            "algorithm.c2",
            "` = -0.4: must be > 0",
        ),
    ] {
        let message = invalid_field(&text, field);
        assert!(message.contains(why), "{message}");
    }
}

/// The warnings of a valid scenario, as text.
fn warnings(text: &str) -> Vec<String> {
    let scenario = Scenario::parse(text, "test.ron").unwrap_or_else(|e| panic!("{e}"));
    scenario
        .warnings()
        .iter()
        .map(ToString::to_string)
        .collect()
}

#[test]
fn the_fixtures_and_the_base_scenarios_give_no_warning() {
    assert_eq!(warnings(TINY_2D), Vec::<String>::new());
    assert_eq!(warnings(&tiny_3d()), Vec::<String>::new());
    for path in crate::common::fixture_paths() {
        let scenario = Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            scenario.warnings().is_empty(),
            "{}: {:?}",
            path.display(),
            scenario.warnings()
        );
    }
}

#[test]
fn a_step_the_stiffness_makes_unstable_is_warned_with_the_largest_stable_step() {
    let stiff = edit(TINY_2D, "h: 0.2)", "h: 0.2, c1: 500.0)");
    let stable =
        flocking::largest_stable_step(&Scenario::parse(&stiff, "test.ron").expect("valid"))
            .expect("an estimate for Algorithm 2");
    // The papers' gains leave a wide margin above h = 0.01; c₁^α = 500 takes it below.
    assert!(stable < 0.01, "{stable}");
    let found = warnings(&stiff);
    assert_eq!(found.len(), 1, "{found:?}");
    let expected = format!("{stable:.3e}");
    assert!(
        found[0].starts_with("warning: `step` = 0.01:"),
        "{}",
        found[0]
    );
    assert!(found[0].contains("largest stable step"), "{}", found[0]);
    assert!(
        found[0].contains(&format!("set `step` to at most {expected}")),
        "{}",
        found[0]
    );
    // The same scenario with a step below the estimate is not warned.
    let fine = edit(&stiff, "step: 0.01", &format!("step: {}", stable / 2.0));
    assert_eq!(warnings(&fine), Vec::<String>::new());
}

#[test]
fn the_stable_step_estimate_separates_stable_from_unstable_runs() {
    // 30 agents in a 20 × 20 box under Algorithm 1 with c₁^α = 200: half the estimated step
    // flocks, four times the estimate blows up (or is caught running away).
    let text = r#"Scenario(
        dim: 2, agents: 30, seed: 4, algorithm: Algorithm1, alpha: (c1: 200.0),
        initial: (positions: Box(min: [0.0, 0.0], max: [20.0, 20.0])),
        step: 0.01, duration: 6.0, record_every: 100,
    )"#;
    let base = Scenario::parse(text, "test.ron").expect("valid");
    let stable = flocking::largest_stable_step(&base).expect("an estimate");
    let with_step = |h: f64| Scenario {
        step: h,
        ..base.clone()
    };
    let summary = flocking::run(&with_step(0.5 * stable), &mut ())
        .unwrap_or_else(|e| panic!("half the estimate must run: {e}"));
    assert!(
        summary.metrics.min_distance > 0.8 * 7.0,
        "{:?}",
        summary.metrics
    );
    match flocking::run(&with_step(4.0 * stable), &mut ()) {
        Err(flocking::RunError::Numerical(e)) => {
            assert!(e.cause.contains("largest stable step"), "{e}");
        }
        Ok(summary) => assert!(
            summary.metrics.cohesion_radius > 100.0,
            "four times the estimate stayed stable: {:?}",
            summary.metrics
        ),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn coincident_agents_at_the_start_are_warned() {
    let rows = "Explicit([[0.0, 0.0], [5.0, 0.0], [9.0, 1.0], [5.0, 0.0], [2.0, 8.0]])";
    let text = edit(
        TINY_2D,
        "positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])",
        &format!("positions: {rows}"),
    );
    let found = warnings(&text);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0]
            .starts_with("warning: `initial.positions` = agents 1 and 3: start at the same point"),
        "{}",
        found[0]
    );
}

#[test]
fn values_beyond_what_doubles_resolve_are_named() {
    let message = invalid_field(&edit(TINY_2D, "d: 7.0", "d: 1e200"), "alpha.d");
    assert!(message.contains("outside [1e-9, 1e9]"), "{message}");
    let message = invalid_field(&edit(TINY_2D, "d: 7.0", "d: 5e-324"), "alpha.d");
    assert!(message.contains("outside [1e-9, 1e9]"), "{message}");
    // zero and below are not a matter of scale: a positive value, not a rescaling
    for bad in ["0.0", "-7.0"] {
        let message = invalid_field(&edit(TINY_2D, "d: 7.0", &format!("d: {bad}")), "alpha.d");
        assert!(
            message.contains("must be > 0; give a positive value") && !message.contains("rescale"),
            "{message}"
        );
    }
    let message = invalid_field(
        &edit(TINY_2D, "epsilon: 0.1", "epsilon: 1e300"),
        "alpha.epsilon",
    );
    assert!(message.contains("σ-norm"), "{message}");
    let message = invalid_field(
        &edit(TINY_2D, "a: 5.0, b: 5.0", "a: 1e-300, b: 5.0"),
        "alpha.a",
    );
    assert!(message.contains("uneven sigmoid"), "{message}");
    let message = invalid_field(
        &edit(TINY_2D, "max: [10.0, 10.0]", "max: [7e154, 10.0]"),
        "initial.positions.max",
    );
    assert!(message.contains("beyond ±1e9"), "{message}");
    let message = invalid_field(&edit(TINY_2D, "c1: 0.02", "c1: 1e308"), "algorithm.c1");
    assert!(message.contains("exceeds 1e9"), "{message}");
    let message = invalid_field(
        &edit(TINY_2D, "agents: 5", "agents: 100000000000"),
        "agents",
    );
    assert!(message.contains("25000 GB"), "{message}");
}

#[test]
fn tanner_agents_starting_at_the_same_point_are_rejected() {
    let text = edit(
        TINY_2D,
        "algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.02, c2: 0.4)",
        "algorithm: Tanner(graph: Edges([(0, 1), (1, 2), (2, 3), (3, 4)]))",
    );
    let text = edit(
        &text,
        "positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])",
        "positions: Explicit([[0.0, 0.0], [5.0, 0.0], [9.0, 1.0], [0.0, 0.0], [2.0, 8.0]])",
    );
    let message = invalid_field(&text, "initial.positions");
    assert!(message.contains("agents 0 and 3"), "{message}");
    assert!(message.contains("Tanner potential"), "{message}");
}

#[test]
fn step_longer_than_duration_names_step() {
    invalid_field(&edit(TINY_2D, "step: 0.01", "step: 0.5"), "step");
}

#[test]
fn nan_names_its_field() {
    let message = invalid_field(&edit(TINY_2D, "step: 0.01", "step: NaN"), "step");
    assert!(message.contains("finite"), "{message}");
    invalid_field(&edit(TINY_2D, "duration: 0.1", "duration: NaN"), "duration");
    invalid_field(&edit(TINY_2D, "d: 7.0", "d: NaN"), "alpha.d");
}

#[test]
fn unsupported_dimension_names_dim() {
    for bad in ["4", "1", "0"] {
        invalid_field(&edit(TINY_2D, "dim: 2", &format!("dim: {bad}")), "dim");
    }
}

#[test]
fn vectors_of_the_wrong_dimension_are_named() {
    let message = invalid_field(
        &edit(TINY_2D, "position: [0.0, 0.0]", "position: [0.0, 0.0, 0.0]"),
        "algorithm.gamma.position",
    );
    assert!(message.contains("dim = 2"), "{message}");
    invalid_field(
        &edit(TINY_2D, "max: [10.0, 10.0]", "max: [10.0]"),
        "initial.positions.max",
    );
}

#[test]
fn box_with_min_above_max_names_it() {
    invalid_field(
        &edit(TINY_2D, "max: [1.0, 1.0]", "max: [1.0, -2.0]"),
        "initial.velocities.max",
    );
}

#[test]
fn explicit_positions_of_the_wrong_count_name_initial_positions() {
    let cloud = "Box(min: [-10.0, -10.0], max: [10.0, 10.0])";
    let message = invalid_field(
        &edit(TINY_2D, cloud, "Explicit([[0.0, 0.0], [7.0, 0.0]])"),
        "initial.positions",
    );
    assert!(message.contains("agents = 5"), "{message}");
}

#[test]
fn explicit_position_of_the_wrong_dimension_is_named_with_its_index() {
    let cloud = "Box(min: [-10.0, -10.0], max: [10.0, 10.0])";
    let rows = "Explicit([[0.0, 0.0], [7.0, 0.0], [14.0, 0.0], [21.0, 0.0, 0.0], [28.0, 0.0]])";
    let message = invalid_field(&edit(TINY_2D, cloud, rows), "initial.positions[3]");
    assert!(message.contains("3 components"), "{message}");
    // The same rows with the right dimension are accepted.
    let good = edit(
        TINY_2D,
        cloud,
        &rows.replace("[21.0, 0.0, 0.0]", "[21.0, 0.0]"),
    );
    assert!(Scenario::parse(&good, "test.ron").is_ok());
}

// ---- The `flocking` binary ----------------------------------------------------------------------

/// The files of a directory by name, with their contents as text.
fn contents(dir: &Path) -> BTreeMap<String, String> {
    files(dir)
        .into_iter()
        .map(|(name, bytes)| (name, String::from_utf8(bytes).expect("a text file")))
        .collect()
}

fn partial(out: &Path) -> std::path::PathBuf {
    let mut name = out.as_os_str().to_owned();
    name.push(".partial");
    name.into()
}

#[test]
fn validate_accepts_a_valid_scenario_and_prints_it_resolved() {
    let tmp = temp_dir("validate_good");
    let file = write(tmp.path(), "tiny.ron", TINY_2D);
    let output = flocking(tmp.path(), &["validate", &file]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(stderr(&output).contains("tiny.ron: valid"), "{stdout}");
    assert!(
        stdout.contains("r: 8.4"),
        "the range is written out: {stdout}"
    );
}

#[test]
fn validate_rejects_a_bad_scenario_with_exit_code_2() {
    let tmp = temp_dir("validate_bad");
    let file = write(tmp.path(), "bad.ron", &edit(TINY_2D, "h: 0.2", "h: 1.0"));
    let output = flocking(tmp.path(), &["validate", &file]);
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(err.contains("alpha.h"), "{err}");
    assert!(
        output.stdout.is_empty(),
        "nothing on stdout for an invalid scenario"
    );
}

/// `flocking run` needs a scenario unless it resumes: its usage says so, and so does the error.
#[test]
fn run_help_shows_the_scenario_as_required_unless_resuming() {
    let tmp = temp_dir("run_help");
    let help = flocking(tmp.path(), &["run", "--help"]);
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(help.status.success(), "{text}");
    let usage: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("Usage:"))
        .take(2)
        .collect();
    assert_eq!(
        usage,
        [
            "Usage: flocking run [OPTIONS] <SCENARIO>",
            "       flocking run --resume <DIR> [OPTIONS]"
        ],
        "{text}"
    );
    assert!(text.contains("required unless --resume"), "{text}");
    let bare = flocking(tmp.path(), &["run"]);
    assert_eq!(bare.status.code(), Some(2));
    assert!(stderr(&bare).contains("<SCENARIO>"), "{}", stderr(&bare));
}

#[test]
fn validate_names_an_unreadable_file_with_exit_code_2() {
    let tmp = temp_dir("validate_missing");
    let missing = tmp.path().join("no-such-scenario.ron");
    let output = flocking(tmp.path(), &["validate", missing.to_str().expect("UTF-8")]);
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(err.contains("no-such-scenario.ron"), "{err}");
}

#[test]
fn run_of_a_bad_scenario_exits_2_and_writes_nothing() {
    let tmp = temp_dir("run_bad");
    let file = write(
        tmp.path(),
        "bad.ron",
        &edit(TINY_2D, "agents: 5", "agents: 0"),
    );
    let out = tmp.path().join("out");
    let output = flocking(
        tmp.path(),
        &["run", &file, "--out", out.to_str().expect("UTF-8")],
    );
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(err.contains("agents"), "{err}");
    assert!(!out.exists(), "no output directory for an invalid scenario");
    assert!(
        !partial(&out).exists(),
        "no partial output for an invalid scenario"
    );
    assert!(!tmp.path().join("out").join("bad").exists());
}

/// Runs `text` with `flocking run --out tmp/out` and checks the four outputs; returns them.
fn check_run(tmp: &TempDir, text: &str, dim: usize) -> BTreeMap<String, String> {
    let file = write(tmp.path(), "tiny.ron", text);
    let out = tmp.path().join("out");
    let output = flocking(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            out.to_str().expect("UTF-8"),
            "--threads",
            "2",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        !partial(&out).exists(),
        "the partial directory was moved into place"
    );
    let files = contents(&out);
    let names: Vec<&str> = files.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        [
            ".flocking",
            ".flocking.manifest",
            "final.csv",
            "flocking.txt",
            "metrics.csv",
            "scenario.ron",
            "trajectory.csv"
        ]
    );
    assert!(
        files["flocking.txt"].contains("TAC 2006 Definition 5"),
        "{}",
        files["flocking.txt"]
    );

    let state_header = if dim == 2 {
        "id,x,y,vx,vy"
    } else {
        "id,x,y,z,vx,vy,vz"
    };
    let columns = 1 + 2 * dim;

    // metrics.csv: t = 0 and the 10th (last) step.
    let metrics: Vec<&str> = files["metrics.csv"].lines().collect();
    // the common columns, then Algorithm 2's γ-tracking errors
    assert_eq!(
        metrics[0],
        format!("{METRICS_HEADER},gamma_position_error,gamma_velocity_error")
    );
    assert_eq!(
        metrics[0],
        "t,connectivity,giant_component,cohesion_radius,deviation_energy,velocity_mismatch,min_distance,collisions,energy,polarisation,milling,nearest_neighbour_mean,nearest_neighbour_min,group_speed,components,gamma_position_error,gamma_velocity_error"
    );
    assert_eq!(metrics.len(), 3, "{metrics:?}");
    for row in &metrics[1..] {
        let values: Vec<f64> = row
            .split(',')
            .map(|x| x.parse().expect("a number"))
            .collect();
        assert_eq!(values.len(), 17, "{row}");
        assert!(values.iter().all(|x| x.is_finite()), "{row}");
    }
    assert!(metrics[1].starts_with("0,"), "{}", metrics[1]);
    let t_end: f64 = metrics[2]
        .split(',')
        .next()
        .expect("t")
        .parse()
        .expect("a number");
    approx::assert_relative_eq!(t_end, 0.1, max_relative = 1e-12);

    // trajectory.csv: 5 agents at each of the 2 recorded instants.
    let trajectory: Vec<&str> = files["trajectory.csv"].lines().collect();
    assert_eq!(trajectory[0], format!("t,{state_header}"));
    assert_eq!(trajectory.len(), 1 + 2 * 5);
    assert!(
        trajectory[1..]
            .iter()
            .all(|row| row.split(',').count() == 1 + columns)
    );

    // final.csv: the last instant of the trajectory, without t.
    let last: Vec<&str> = files["final.csv"].lines().collect();
    assert_eq!(last[0], state_header);
    assert_eq!(last.len(), 1 + 5);
    for (i, (row, traj)) in last[1..].iter().zip(&trajectory[6..]).enumerate() {
        assert!(row.starts_with(&format!("{i},")), "{row}");
        assert_eq!(row.split(',').count(), columns, "{row}");
        assert_eq!(traj.split_once(',').expect("t,").1, *row);
    }

    // scenario.ron: loads, with the defaults written out.
    let written = Scenario::load(out.join("scenario.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(written.range(), 1.2 * written.alpha.d);
    assert!(
        files["scenario.ron"].contains("r: 8.4"),
        "{}",
        files["scenario.ron"]
    );
    assert_eq!(written, Scenario::parse(text, "tiny.ron").expect("valid"));
    files
}

#[test]
fn run_writes_the_four_outputs_in_2d() {
    let tmp = temp_dir("run_2d");
    check_run(&tmp, TINY_2D, 2);
}

#[test]
fn run_writes_the_four_outputs_in_3d() {
    let tmp = temp_dir("run_3d");
    check_run(&tmp, &tiny_3d(), 3);
}

#[test]
fn run_refuses_an_existing_output_without_force() {
    let tmp = temp_dir("run_force");
    let first = check_run(&tmp, TINY_2D, 2);
    let out = tmp.path().join("out");
    let out_arg = out.to_str().expect("UTF-8");
    // Another seed: a replaced output would differ from the first.
    let other = write(
        tmp.path(),
        "other.ron",
        &edit(TINY_2D, "seed: 1", "seed: 2"),
    );

    let refused = flocking(tmp.path(), &["run", &other, "--out", out_arg]);
    assert!(!refused.status.success());
    assert_eq!(refused.status.code(), Some(2));
    let err = stderr(&refused);
    assert!(err.contains("--force"), "{err}");
    assert_eq!(contents(&out), first, "the first output is left intact");
    assert!(!partial(&out).exists());

    let forced = flocking(tmp.path(), &["run", &other, "--out", out_arg, "--force"]);
    assert_eq!(forced.status.code(), Some(0), "{}", stderr(&forced));
    let second = contents(&out);
    assert_eq!(
        second.keys().collect::<Vec<_>>(),
        first.keys().collect::<Vec<_>>()
    );
    assert_ne!(
        second["final.csv"], first["final.csv"],
        "--force replaced the output"
    );
    assert!(
        second["scenario.ron"].contains("seed: 2"),
        "{}",
        second["scenario.ron"]
    );
    assert!(!partial(&out).exists());
}
