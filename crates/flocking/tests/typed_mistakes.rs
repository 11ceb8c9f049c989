//! The errors of values of the wrong type in a scenario file (issue 53): each names the field by
//! its dotted path, the value, the type expected and an example, at the value's line and column.

use flocking::{Scenario, ScenarioError};

/// A small valid scenario, every field the mistakes below change written once.
const BASE: &str = "Scenario(
    dim: 2,
    agents: 20,
    seed: 3,
    algorithm: Algorithm3(
        gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5]),
        c1: 0.02,
        c2: 0.4,
    ),
    integrator: Rk4,
    initial: (
        positions: Gaussian(mean: [0.0, 0.0], std: 10.0),
    ),
    step: 0.01,
    duration: 1.0,
    record_every: 10,
    conditions: (communication: (loss: Bernoulli(p: 0.1)), sensing: (noise: White(sigma_q: 0.1, sigma_p: 0.0))),
    obstacles: [Ball(centre: [50.0, 0.0], radius: 2.0)],
)";

/// The mistakes a user types: (what is replaced, by what).
const MISTAKES: &[(&str, &str)] = &[
    // an integer field given a real
    ("agents: 20", "agents: 200.0"),
    ("seed: 3", "seed: 1.5"),
    ("dim: 2", "dim: 2.0"),
    ("record_every: 10", "record_every: 1e1"),
    // an enum field given a number
    ("loss: Bernoulli(p: 0.1)", "loss: 0.1"),
    ("noise: White(sigma_q: 0.1, sigma_p: 0.0)", "noise: 0.1"),
    ("dim: 2,", "dim: 2, vehicle: 1.0,"),
    ("integrator: Rk4", "integrator: 4"),
    ("algorithm: Algorithm3(", "algorithm: 2, unused: ("),
    // a number given a string
    ("step: 0.01", "step: \"0.01\""),
    ("agents: 20", "agents: \"20\""),
    ("c1: 0.02", "c1: \"0.02\""),
    ("radius: 2.0", "radius: \"2\""),
    // a list given a scalar, and an item of the wrong type
    ("mean: [0.0, 0.0]", "mean: 0.0"),
    ("velocity: [1.0, 0.5]", "velocity: [1.0, \"fast\"]"),
    // an unknown variant
    ("loss: Bernoulli(", "loss: Bernouli("),
    ("integrator: Rk4", "integrator: RK4"),
    ("algorithm: Algorithm3(", "algorithm: Algorithm9("),
    ("dim: 2,", "dim: 2, vehicle: Unicycl(()),"),
    ("positions: Gaussian(", "positions: Gauss("),
    ("Ball(", "Bal("),
    // a missing comma between two fields is a syntax error, not a type: named, not explained
    ("agents: 20,", "agents: 20"),
];

/// The error of `BASE` with `from` replaced by `to`.
fn error_of(from: &str, to: &str) -> ScenarioError {
    assert!(BASE.contains(from), "{from}");
    Scenario::parse(&BASE.replacen(from, to, 1), "s.ron").expect_err(to)
}

#[test]
fn the_base_scenario_is_valid() {
    Scenario::parse(BASE, "s.ron").expect("valid");
}

#[test]
fn typed_mistakes_name_the_field_the_type_and_an_example() {
    let messages: Vec<String> = MISTAKES
        .iter()
        .map(|(from, to)| format!("{to}\n  {}", error_of(from, to)))
        .collect();
    insta::assert_snapshot!(messages.join("\n"));
}

#[test]
fn the_field_of_a_typed_mistake_is_its_dotted_path_at_the_value() {
    let error = error_of("loss: Bernoulli(p: 0.1)", "loss: 0.1");
    assert_eq!(
        error.field().as_deref(),
        Some("conditions.communication.loss")
    );
    let ScenarioError::Syntax { line, col, .. } = error else {
        panic!("{error:?}")
    };
    // the value `0.1`, not the parser's stop after the colon
    assert_eq!((line, col), (17, 40));
    let error = error_of("agents: 20", "agents: 200.0");
    assert!(
        matches!(
            error,
            ScenarioError::Syntax {
                line: 3,
                col: 13,
                ..
            }
        ),
        "{error:?}"
    );
    assert_eq!(
        error_of("radius: 2.0", "radius: \"2\"").field().as_deref(),
        Some("obstacles[0].radius")
    );
}
