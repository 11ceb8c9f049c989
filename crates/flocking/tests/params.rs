//! The library refuses each parameter outside its domain with a typed error naming the field,
//! as the scenario file does: the protocol crate's parameter types, the interactions and the
//! simulation.

use flocking::obstacles::ObstacleField;
use flocking::protocols::{
    AlphaConfig, AlphaInteraction, AlphaParams, AvoidanceGains, BetaConfig, BetaInteraction,
    BetaParams, GammaAgent, Integrator, ParamError, Simulation, Swarm,
};
use flocking::{DynSimulation, Scenario};
use glam::DVec2;

use crate::common::fixture;

/// The field of the error of `result`, which must fail.
fn field<T: std::fmt::Debug>(result: Result<T, ParamError>) -> String {
    let error = result.expect_err("a parameter outside its domain");
    assert!(!error.why.is_empty() && !error.fix.is_empty(), "{error}");
    assert!(
        error
            .to_string()
            .starts_with(&format!("`{}` = ", error.field)),
        "{error}"
    );
    error.field
}

#[test]
fn alpha_parameters_outside_their_domain_are_refused() {
    let papers = AlphaParams::default();
    for (params, expected) in [
        (AlphaParams { r: 7.0, ..papers }, "r"),
        (AlphaParams { r: 5.0, ..papers }, "r"),
        (AlphaParams { d: 0.0, ..papers }, "d"),
        (
            AlphaParams {
                d: f64::NAN,
                ..papers
            },
            "d",
        ),
        (
            AlphaParams {
                epsilon: 0.0,
                ..papers
            },
            "epsilon",
        ),
        (AlphaParams { h: 1.0, ..papers }, "h"),
        (AlphaParams { a: 6.0, ..papers }, "a"),
    ] {
        assert_eq!(field(params.validate()), expected, "{params:?}");
        assert_eq!(field(AlphaInteraction::new(params, 1.0, 1.0)), expected);
    }
    assert_eq!(field(AlphaInteraction::new(papers, 0.0, 1.0)), "c1");
    assert_eq!(field(AlphaInteraction::new(papers, 1.0, -1.0)), "c2");
    let config = AlphaConfig {
        r: Some(6.0),
        ..AlphaConfig::default()
    };
    assert_eq!(
        field(config.validate().map_err(|e| e.within("alpha"))),
        "alpha.r"
    );
}

#[test]
fn beta_and_gamma_parameters_outside_their_domain_are_refused() {
    let papers = BetaParams::papers(7.0);
    assert_eq!(
        field(
            BetaParams {
                r: papers.d,
                ..papers
            }
            .validate()
        ),
        "r"
    );
    assert_eq!(field(BetaParams { h: 0.0, ..papers }.validate()), "h");
    let obstacles = || ObstacleField::<DVec2>::from_specs(&[]).expect("no obstacle");
    assert_eq!(
        field(BetaInteraction::new(obstacles(), papers, 0.1, 0.0, 1.0)),
        "c1"
    );
    assert_eq!(
        field(BetaInteraction::new(obstacles(), papers, 0.1, 1.0, -1.0)),
        "c2"
    );
    let beta = BetaConfig {
        h: 1.5,
        ..BetaConfig::default()
    };
    assert_eq!(field(beta.validate(7.0)), "h");
    let gains = AvoidanceGains {
        lambda_d: 1.5,
        ..AvoidanceGains::default()
    };
    assert_eq!(field(gains.validate()), "lambda_d");
    let path = GammaAgent::<DVec2>::Path {
        waypoints: vec![DVec2::ZERO],
        speed: 0.0,
    };
    assert_eq!(field(path.validate()), "speed");
    let empty = GammaAgent::<DVec2>::Path {
        waypoints: Vec::new(),
        speed: 1.0,
    };
    assert_eq!(field(empty.validate()), "waypoints");
    let nowhere = GammaAgent::Static {
        position: DVec2::new(f64::INFINITY, 0.0),
    };
    assert_eq!(field(nowhere.validate()), "position");
}

#[test]
fn a_simulation_refuses_a_bad_step_or_state() {
    let alpha = AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).expect("valid");
    let protocol = flocking::protocols::Algorithm1 { alpha };
    let swarm = Swarm::new(vec![DVec2::ZERO, DVec2::X * 7.0], vec![DVec2::ZERO; 2]);
    for step in [0.0, -0.01, f64::NAN] {
        let result = Simulation::new(protocol.clone(), Integrator::Rk4, swarm.clone(), step);
        assert_eq!(field(result.map(|_| ())), "step");
    }
    let lost = Swarm::new(vec![DVec2::ZERO, DVec2::NAN], vec![DVec2::ZERO; 2]);
    let result = Simulation::new(protocol, Integrator::SymplecticEuler, lost, 0.01);
    assert_eq!(field(result.map(|_| ())), "positions[1]");
}

#[test]
fn a_dynamic_simulation_refuses_rows_of_the_wrong_size() {
    let scenario: Scenario = fixture("tac2006_fig11_alg2_n100");
    let error = DynSimulation::from_state(&scenario, &[0.0; 10], &[0.0; 200], 0).unwrap_err();
    assert_eq!(error.field().as_deref(), Some("agents"), "{error}");
}

/// A scenario's snapshot times are ≥ 0, increase and are at most `MAX_SNAPSHOTS`; each
/// refusal names the time at fault, and the times survive the written scenario.
#[test]
fn snapshot_times_are_checked_and_written() {
    let base = fixture("tac2006_fig11_alg2_n100");
    let with = |times: Vec<f64>| base.with_values([("snapshots", serde_json::json!(times))]);
    let ok = with(vec![0.0, 4.0, 100.0]).expect("valid times");
    assert_eq!(ok.snapshots.as_deref(), Some(&[0.0, 4.0, 100.0][..]));
    let written = ok.to_ron().expect("ron");
    assert!(written.contains("snapshots: ["), "{written}");
    assert_eq!(Scenario::parse(&written, "s.ron").expect("parses"), ok);
    assert!(!base.to_ron().expect("ron").contains("snapshots"));
    for (times, at) in [
        (vec![1.0, 1.0], "snapshots[1]"),
        (vec![5.0, 4.0], "snapshots[1]"),
        (vec![-1.0], "snapshots[0]"),
        (vec![], "snapshots"),
        ((0..13).map(f64::from).collect(), "snapshots"),
    ] {
        let error = with(times.clone()).expect_err("refused");
        assert_eq!(error.field().as_deref(), Some(at), "{times:?}: {error}");
    }
}

/// A misspelled field is reported as itself, in the struct it was written in, not "in the value
/// of" the last field read before it (`c_1` after `gamma: Static(position: …)` was reported "in
/// the value of `position`").
#[test]
fn a_misspelled_field_is_not_blamed_on_the_field_before_it() {
    let text = "Scenario(
    name: \"typo\",
    dim: 2,
    agents: 10,
    algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c_1: 0.05, c2: 0.4),
    initial: (positions: Gaussian(mean: [0.0, 0.0], std: 5.0)),
)";
    let error = Scenario::parse(text, "typo.ron").expect_err("c_1 is no field");
    let message = error.to_string();
    assert!(message.contains("c_1"), "{message}");
    assert!(!message.contains("position"), "{message}");
    assert!(message.starts_with("typo.ron:5:"), "{message}");
}

/// A path of `with_values` that names nothing says so without a value it never read.
#[test]
fn an_unknown_path_is_reported_without_a_value() {
    let scenario = fixture("tac2006_fig11_alg2_n100");
    let error = scenario
        .with_values([("agent", flocking::serde_json::json!(10))])
        .expect_err("no such parameter");
    let message = error.to_string();
    assert!(
        message.starts_with("`agent`: no such parameter"),
        "{message}"
    );
    assert!(!message.contains("no value read"), "{message}");
}

/// Rust's names stay out of the messages: a fractional agent count is "expected a whole number
/// ≥ 0", not "expected usize"; a position that is not finite is `(NaN, 0.0)`, not `DVec2(NaN, 0.0)`.
#[test]
fn messages_name_no_rust_types() {
    let scenario = fixture("tac2006_fig11_alg2_n100");
    let error = scenario
        .with_values([("agents", flocking::serde_json::json!(10.5))])
        .expect_err("not a whole number")
        .to_string();
    assert!(error.contains("expected a whole number ≥ 0"), "{error}");
    assert!(!error.contains("usize"), "{error}");
    let scenario = scenario
        .with_values([("agents", flocking::serde_json::json!(2))])
        .expect("valid");
    let error = DynSimulation::from_state(&scenario, &[f64::NAN, 0.0, 1.0, 0.0], &[0.0; 4], 0)
        .expect_err("not finite")
        .to_string();
    assert!(error.contains("(NaN, 0.0)"), "{error}");
    assert!(!error.contains("DVec"), "{error}");
}

/// Consensus's gain is refused once, by its constructor, named by its scenario path, on the
/// proximity net and on a fixed graph; a broken fixed graph is reported before the gain.
#[test]
fn the_consensus_gain_is_refused_by_its_constructor_named() {
    let base = fixture("consensus_cycle_n20");
    for gain in [0.0, -1.0, f64::INFINITY] {
        let error = base
            .with_values([("algorithm.gain", serde_json::json!(gain))])
            .expect_err("refused");
        assert_eq!(
            error.field().as_deref(),
            Some("algorithm.gain"),
            "{gain}: {error}"
        );
        let proximity = base
            .with_values([
                ("algorithm.graph", serde_json::Value::Null),
                ("algorithm.gain", serde_json::json!(gain)),
            ])
            .expect_err("refused");
        assert_eq!(
            proximity.field().as_deref(),
            Some("algorithm.gain"),
            "{proximity}"
        );
    }
    let ok = base.with_values([("algorithm.gain", serde_json::json!(0.5))]);
    assert!(ok.is_ok(), "{ok:?}");
    let broken = base
        .with_values([("algorithm.graph", serde_json::json!("Edges([(0, 99)])"))])
        .expect_err("an edge to an agent that does not exist");
    assert!(
        broken
            .field()
            .as_deref()
            .is_some_and(|f| f.starts_with("algorithm.graph")),
        "{broken}"
    );
}
