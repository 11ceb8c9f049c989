//! Every `fixtures/*.ron` parses and validates, and survives a round trip through `to_ron`.

use flocking::Scenario;

use crate::common::{fixture_paths, stem};

/// The fixtures the paper tests rely on.
const PAPER_FIXTURES: [&str; 4] = [
    "tac2006_fig10_alg2_n150",
    "tac2006_fig11_alg2_n100",
    "tac2006_fig12_alg1_n40",
    "tac2006_fig13_alg2_3d_n50",
];

#[test]
fn every_fixture_parses_and_validates() {
    let paths = fixture_paths();
    let stems: Vec<String> = paths.iter().map(|p| stem(p)).collect();
    for name in PAPER_FIXTURES {
        assert!(
            stems.iter().any(|s| s == name),
            "fixtures/{name}.ron is missing (found {stems:?})"
        );
    }
    for path in &paths {
        let scenario = Scenario::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(scenario.validate(), Ok(()), "{}", path.display());
        // `resolved` writes the defaults out, and changes no value the run uses.
        let resolved = scenario.clone().resolved();
        assert_eq!(
            resolved.alpha.r,
            Some(scenario.alpha.range()),
            "{}",
            path.display()
        );
        assert_eq!(resolved.range(), scenario.range(), "{}", path.display());
        // and it validates (issue 53: Vicsek's and the boids' r was written as alpha.r < d)
        assert_eq!(resolved.validate(), Ok(()), "{}", path.display());
        assert_eq!(
            resolved.collision_distance,
            Some(scenario.collision_distance()),
            "{}",
            path.display()
        );
        assert!(scenario.steps() >= 1, "{}", path.display());
        assert_eq!(
            scenario.name,
            stem(path),
            "the scenario's name is its file's stem"
        );
    }
}

#[test]
fn resolved_fixtures_round_trip_through_ron() {
    for path in fixture_paths() {
        let scenario = Scenario::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let text = scenario.to_ron().expect("a validated scenario serializes");
        let back = Scenario::parse(&text, "round-trip.ron").unwrap_or_else(|e| {
            panic!(
                "{}: to_ron output does not parse: {e}\n{text}",
                path.display()
            )
        });
        assert_eq!(
            back,
            scenario,
            "{}: round trip changed the scenario\n{text}",
            path.display()
        );
        // The written text is a fixed point.
        assert_eq!(
            back.to_ron().expect("serializes"),
            text,
            "{}",
            path.display()
        );
    }
}

#[test]
fn to_ron_writes_the_defaults_in_comments_and_keeps_them_derived() {
    let text = "Scenario(dim: 2, agents: 3, algorithm: Algorithm1, \
                initial: (positions: Box(min: [0.0, 0.0], max: [10.0, 10.0])), duration: 1.0)";
    let scenario = Scenario::parse(text, "defaults.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scenario.alpha.r, None, "an unset default stays unset");
    let resolved = scenario.clone().resolved();
    assert_eq!(resolved.alpha.r, Some(1.2 * 7.0));
    assert_eq!(resolved.collision_distance, Some(0.25 * 7.0));
    let written = scenario.to_ron().expect("serializes");
    for field in [
        "r: 8.4",
        "collision_distance: 1.75",
        "step: 0.01",
        "record_every: 10",
        "epsilon: 0.1",
        "h: 0.2",
    ] {
        assert!(written.contains(field), "`{field}` missing from\n{written}");
    }
    assert!(
        written.contains("// alpha.r: 8.4 (default 1.2 d)"),
        "{written}"
    );
    // read back, the defaults still follow d (r = 1.2 d), as in the original
    let back = Scenario::parse(&written, "written.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, scenario);
    let moved = back
        .with_values([("alpha.d", flocking::serde_json::json!(5.0))])
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(moved.range(), 6.0);
}
