//! Parameters by path ([`Scenario::value`], [`Scenario::with_values`]): what sweeps and the Python
//! package change, with the errors of a loaded scenario.

use flocking::Scenario;
use flocking::serde_json::{Value, json};

use crate::common::fixture;

fn invalid_field(result: Result<Scenario, flocking::ScenarioError>) -> (String, String) {
    let error = result.expect_err("refused");
    (error.field().expect("names its field"), error.to_string())
}

#[test]
fn no_change_gives_the_same_scenario_for_every_fixture() {
    for path in crate::common::fixture_paths() {
        let scenario = Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let same = scenario
            .with_values(std::iter::empty::<(&str, Value)>())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(same, scenario, "{}", path.display());
    }
}

#[test]
fn a_path_changes_that_value_only() {
    let scenario = fixture("tac2006_fig11_alg2_n100");
    let changed = scenario
        .with_values([
            ("algorithm.c1", json!(0.05)),
            ("agents", json!(400)),
            ("initial.positions.std", json!(20)),
        ])
        .expect("valid");
    assert_eq!(changed.value("algorithm.c1").expect("a path"), json!(0.05));
    assert_eq!(changed.agents, 400);
    let flocking::Algorithm::Algorithm2(flocking::scenario::Algorithm2Params { c1, c2, .. }) =
        &changed.algorithm
    else {
        panic!("the variant is kept: {:?}", changed.algorithm)
    };
    assert_eq!((*c1, *c2), (0.05, 0.4));
    let back = changed
        .with_values([
            ("algorithm.c1", json!(0.02)),
            ("agents", json!(100)),
            ("initial.positions.std", json!(50.0)),
        ])
        .expect("valid");
    assert_eq!(back, scenario);
}

#[test]
fn unset_defaults_follow_the_values_they_depend_on() {
    let scenario = fixture("tac2006_fig11_alg2_n100");
    assert_eq!(scenario.value("alpha.r").expect("a path"), Value::Null);
    let wider = scenario
        .with_values([("alpha.d", json!(10.0))])
        .expect("valid");
    assert_eq!(wider.range(), 12.0, "r = 1.2 d");
    assert_eq!(wider.collision_distance(), 2.5, "d/4");
}

#[test]
fn list_elements_are_numbered_and_integral_numbers_fill_integer_fields() {
    let scenario = fixture("tac2006_fig16_squeeze_n150");
    let changed = scenario
        .with_values([("obstacles.1.radius", json!(20.0)), ("seed", json!(7.0))])
        .expect("valid");
    assert_eq!(
        changed.value("obstacles.1.radius").expect("a path"),
        json!(20.0)
    );
    assert_eq!(changed.seed, 7);
    assert_eq!(
        changed.value("obstacles.0").expect("a path"),
        scenario.value("obstacles.0").expect("a path")
    );
}

#[test]
fn bad_paths_and_values_are_refused_naming_the_field() {
    let scenario = fixture("tac2006_fig11_alg2_n100");
    let (field, message) = invalid_field(scenario.with_values([("algorithm.c3", json!(1.0))]));
    assert_eq!(field, "algorithm.c3");
    assert!(
        message.contains("`c1`") && message.contains("`gamma`"),
        "{message}"
    );
    let (field, message) = invalid_field(scenario.with_values([("alpah.d", json!(1.0))]));
    assert_eq!(field, "alpah.d");
    assert!(message.contains("`alpha`"), "{message}");
    let (field, message) = invalid_field(scenario.with_values([("agents", json!("many"))]));
    assert_eq!(field, "agents");
    assert!(message.contains("\"many\""), "{message}");
    let (field, _) = invalid_field(scenario.with_values([("agents", json!(2.5))]));
    assert_eq!(field, "agents");
    let (field, _) = invalid_field(scenario.with_values([("obstacles.0", json!(1.0))]));
    assert_eq!(field, "obstacles.0");
    // the validation of a loaded scenario
    let (field, _) = invalid_field(scenario.with_values([("alpha.d", json!(-1.0))]));
    assert_eq!(field, "alpha.d");
    let (field, _) = invalid_field(scenario.with_values([("algorithm.c2", json!(0.0))]));
    assert_eq!(field, "algorithm.c2");
    assert!(scenario.value("algorithm.c1.x").is_err());
}

/// Issue 53: every enum of the scenario is given whole as RON text, as those of the conditions
/// are — the vehicle, the algorithm, the integrator, the domain, the initial clouds — and gives
/// the scenario the RON file would; text that is not one of its variants is refused by name.
#[test]
fn every_enum_is_given_as_ron_text() {
    let base = fixture("tac2006_fig11_alg2_n100");
    let written = base.to_ron().expect("written");
    let replaced = |text: &str, from: &str, to_end: &str, by: &str| {
        let start = text.find(from).expect("the field");
        let end = start + text[start..].find(to_end).expect("its end") + to_end.len();
        text.replace(&text[start..end], by)
    };
    // the vehicle and an initial cloud
    let robots = base
        .with_values([
            ("vehicle", json!("Unicycle(())")),
            (
                "initial.positions",
                json!("Box(min: [-20.0, -20.0], max: [20.0, 20.0])"),
            ),
        ])
        .expect("RON text of each enum");
    let edited = written.replace(
        "integrator: SymplecticEuler,",
        "integrator: SymplecticEuler, vehicle: Unicycle(()),",
    );
    let edited = replaced(
        &edited,
        "positions: Gaussian(",
        "),",
        "positions: Box(min: [-20.0, -20.0], max: [20.0, 20.0]),",
    );
    assert_eq!(
        robots,
        Scenario::parse(&edited, "edited").expect("the edited file")
    );
    // the algorithm, the domain and the integrator
    let vicsek = base
        .with_values([
            ("algorithm", json!("Vicsek(eta: 0.3)")),
            ("integrator", json!("Rk4")),
            ("domain", json!("Periodic(size: [60.0, 60.0])")),
        ])
        .expect("RON text of each enum");
    let edited = replaced(
        &written,
        "algorithm:",
        "alpha:",
        "algorithm: Vicsek(eta: 0.3),\n    alpha:",
    );
    let edited = edited.replace(
        "integrator: SymplecticEuler,",
        "integrator: Rk4, domain: Periodic(size: [60.0, 60.0]),",
    );
    assert_eq!(
        vicsek,
        Scenario::parse(&edited, "edited").expect("the edited file")
    );
    let (field, message) = invalid_field(base.with_values([("vehicle", json!("Bicycle(())"))]));
    assert_eq!(field, "vehicle", "{message}");
}
