//! Scenario errors of obstacles and of the issue-3 algorithms: each names its field.

use flocking::Scenario;

/// A valid 2D Algorithm 3 scenario with one ball, far from the agents.
const ALG3: &str = r#"Scenario(
    dim: 2,
    agents: 6,
    seed: 2,
    algorithm: Algorithm3(gamma: Static(position: [0.0, 0.0]), c1: 1.0),
    obstacles: [Ball(centre: [50.0, 0.0], radius: 5.0)],
    initial: (positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])),
    duration: 0.1,
)
"#;

fn invalid(text: &str) -> (String, String) {
    match Scenario::parse(text, "test.ron") {
        Ok(s) => panic!("accepted an invalid scenario: {s:?}"),
        Err(e) => {
            let field = e
                .field()
                .unwrap_or_else(|| panic!("expected a field error, got {e}"));
            assert!(e.to_string().contains(&format!("`{field}`")), "{e}");
            (field, e.to_string())
        }
    }
}

#[test]
fn the_base_scenario_is_valid_and_resolves_the_beta_defaults() {
    let s = Scenario::parse(ALG3, "test.ron").unwrap_or_else(|e| panic!("{e}"));
    let text = s.to_ron().expect("serialises");
    // d′ = 0.6 d, r′ = 1.2 d′, c₂ = 2√c₁ written out in comments, left unset in the value
    assert!(text.contains("// algorithm.beta.d: 4.2"), "{text}");
    assert!(text.contains("// algorithm.c2: 2.0"), "{text}");
    assert_eq!(
        Scenario::parse(&text, "written.ron").expect("written parses"),
        s
    );
}

#[test]
fn degenerate_ball_is_named_with_its_index() {
    let (field, message) = invalid(&ALG3.replace("radius: 5.0", "radius: 0.0"));
    assert_eq!(field, "obstacles[0].radius", "{message}");
    assert!(message.contains("radius"), "{message}");
}

#[test]
fn flat_hull_is_rejected() {
    let text = ALG3.replace(
        "Ball(centre: [50.0, 0.0], radius: 5.0)",
        "Ball(centre: [50.0, 0.0], radius: 5.0), ConvexHull(points: [[60.0, 0.0], [61.0, 1.0], [62.0, 2.0]])",
    );
    let (field, message) = invalid(&text);
    assert!(
        field.starts_with("obstacles[1].points"),
        "{field}: {message}"
    );
}

#[test]
fn non_convex_outline_is_rejected_with_the_inner_point() {
    // (61, 1) lies strictly inside the triangle of the other three points: not a convex outline.
    let text = ALG3.replace(
        "Ball(centre: [50.0, 0.0], radius: 5.0)",
        "Ball(centre: [50.0, 0.0], radius: 5.0), ConvexHull(points: [[60.0, 0.0], [64.0, 0.0], [61.0, 1.0], [62.0, 4.0]])",
    );
    let (field, message) = invalid(&text);
    assert!(
        field.starts_with("obstacles[1].points"),
        "{field}: {message}"
    );
    assert!(message.contains("not convex"), "{message}");
}

#[test]
fn agents_starting_inside_an_obstacle_are_rejected() {
    let (field, message) = invalid(&ALG3.replace("centre: [50.0, 0.0]", "centre: [0.0, 0.0]"));
    assert_eq!(field, "initial.positions", "{message}");
    assert!(message.contains("inside obstacles[0]"), "{message}");
}

#[test]
fn obstacles_need_an_algorithm_that_sees_them() {
    let text = ALG3.replace(
        "Algorithm3(gamma: Static(position: [0.0, 0.0]), c1: 1.0)",
        "Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 1.0, c2: 1.0)",
    );
    assert_eq!(invalid(&text).0, "obstacles");
}

#[test]
fn beta_range_must_exceed_beta_distance() {
    let text = ALG3.replace("c1: 1.0)", "c1: 1.0, beta: (d: 5.0, r: 4.0))");
    assert_eq!(invalid(&text).0, "algorithm.beta.r");
}

#[test]
fn obstacle_of_the_wrong_dimension_is_named() {
    let (field, message) =
        invalid(&ALG3.replace("centre: [50.0, 0.0]", "centre: [50.0, 0.0, 1.0]"));
    assert!(field.starts_with("obstacles[0]"), "{field}: {message}");
}

#[test]
fn the_2003_obstacle_protocol_takes_balls_only() {
    let text = ALG3
        .replace(
            "Algorithm3(gamma: Static(position: [0.0, 0.0]), c1: 1.0)",
            "Flocking2003(form: Smooth, c1: 1.0, avoidance: Some(()))",
        )
        .replace("    initial:", "    alpha: (a: 1.0, b: 5.0),\n    initial:")
        .replace(
            "Ball(centre: [50.0, 0.0], radius: 5.0)",
            "Cuboid(centre: [50.0, 0.0], half_extents: [2.0, 2.0])",
        );
    assert_eq!(invalid(&text).0, "obstacles[0]");
}

#[test]
fn the_2003_potential_needs_b_above_a() {
    let text = ALG3
        .replace(
            "Algorithm3(gamma: Static(position: [0.0, 0.0]), c1: 1.0)",
            "Flocking2003(form: Nonsmooth, c1: 1.0)",
        )
        .replace(
            "    obstacles: [Ball(centre: [50.0, 0.0], radius: 5.0)],\n",
            "",
        );
    assert_eq!(invalid(&text).0, "alpha.a");
}

#[test]
fn tanner_needs_a_connected_graph() {
    let text = ALG3
        .replace(
            "Algorithm3(gamma: Static(position: [0.0, 0.0]), c1: 1.0)",
            "Tanner(graph: Edges([(0, 1), (2, 3), (3, 4), (4, 5)]))",
        )
        .replace(
            "    obstacles: [Ball(centre: [50.0, 0.0], radius: 5.0)],\n",
            "",
        );
    let (field, message) = invalid(&text);
    assert_eq!(field, "algorithm.graph", "{message}");
    assert!(message.contains("2 components"), "{message}");
}
